"""Mass and restoring of a NEMOH run, from its companion files, checked against the run.

* ``hydrostatic_stiffness`` from ``KH.dat`` / ``KH_<k>.dat`` (or ``Mechanics/Kh.dat``,
  which NEMOH's post-processor used, when they differ). C33 of each body is checked
  against ρ g A_wp, the ω → 0 limit of the run's own Froude-Krylov heave force
  (Newman (1977) §6.17): files of another mesh are not read, with a warning.
* ``inertia_matrix`` from ``Mechanics/Inertia.dat`` about the rotation point (NEMOH's
  own estimate, ρ∇ and a uniform hull shell, is recognised and ``history`` says so);
  without it there is none: ρ∇ is the mass only of a freely floating body, and the
  inertia tensor cannot come from the volume.
* ``additional_stiffness`` from ``Km.dat``, ``additional_damping`` from ``Badd.dat``
  (when not zero); centres of buoyancy and gravity, volumes from ``Hydrostatics.dat``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError
from cummins.io._common import warn_damage
from cummins.io._text import TextFile, parse_numbers
from cummins.io.nemoh.companions import (
    _body_files,
    _companion,
    _read_hydrostatics,
    _read_matrix,
)
from cummins.io.nemoh.files import _find, _Run, _subfolder
from cummins.restoring import SOURCE, weight_record

#: Largest relative difference between C33 of KH.dat and the run's own ρ g A_wp, the
#: ω → 0 limit of its Froude-Krylov heave force (≤ 0.2 % measured on the cylinder, the
#: COER float and the OSWEC flap; a factor 2 or 0.8 where the mesh files belong to
#: another mesh).
HYDROSTATIC_TOLERANCE = 0.05

# --------------------------------------------------------------------------- mass, restoring


@dataclass(frozen=True)
class _BodyInfo:
    dofs: list[str]
    points: np.ndarray  # (bodies, 3) reference points
    names: list[str]

    @property
    def count(self) -> int:
        return self.points.shape[0]

    def name(self, k: int) -> str:
        label = f"body{k + 1}" if self.count > 1 else "the body"
        return f"{label} ({self.names[k]})" if k < len(self.names) else label

    def heave(self, k: int) -> int | None:
        label = f"body{k + 1}__Heave" if self.count > 1 else "Heave"
        return self.dofs.index(label) if label in self.dofs else None


_MECHANICS = {
    "inertia": ("Inertia.dat", "inertia_matrix"),
    "kh": ("Kh.dat", "hydrostatic_stiffness"),
    "km": ("Km.dat", "additional_stiffness"),
    "badd": ("Badd.dat", "additional_damping"),
}


def _sibling_matrix(path: Path, n: int, variable: str, notes: list[str]) -> np.ndarray | None:
    """An n×n matrix file, or None with a warning saying which variable is lost."""
    try:
        matrix = _read_matrix(path)
    except HydroDataError as exc:
        warn_damage(
            f"{exc.message}: {variable} not read from it",
            path=exc.path or path,
            line=exc.line,
            notes=notes,
            hint=exc.hint,
        )
        return None
    if matrix.shape[0] != n:
        warn_damage(
            f"a {matrix.shape[0]}×{matrix.shape[0]} matrix for the run's {n} DOFs: "
            f"{variable} not read from it",
            path=path,
            notes=notes,
        )
        return None
    return matrix


def _stiffness(run: _Run, bodies: _BodyInfo, history, notes) -> tuple[np.ndarray, list] | None:
    """The hydrostatic stiffness of the mesh files (``KH.dat`` / ``KH_<k>.dat``)."""
    nb, n = bodies.count, len(bodies.dofs)
    files = _body_files(run, "KH", nb, history)
    if files is None:
        return None
    if len(files) == 1:
        if nb > 1:
            try:
                size = _read_matrix(files[0]).shape[0]
            except HydroDataError:
                size = None  # _sibling_matrix warns below
            if size == 6:
                history.append(
                    f"{files[0].name} not used: it holds one body's matrix (the NEMOH mesher "
                    f"writes it for the last mesh it processed) and the run has {nb} bodies; "
                    "give KH_0.dat … per body"
                )
                return None
            block = _sibling_matrix(files[0], 6 * nb, "hydrostatic_stiffness", notes)
            if block is None:
                return None
        else:
            block = _sibling_matrix(files[0], 6, "hydrostatic_stiffness", notes)
            if block is None:
                return None
        c = block
    else:
        c = np.zeros((6 * nb, 6 * nb))
        for k, path in enumerate(files):
            block = _sibling_matrix(path, 6, "hydrostatic_stiffness", notes)
            if block is None:
                return None
            c[6 * k : 6 * k + 6, 6 * k : 6 * k + 6] = block
    if c.shape[0] != n:
        history.append(f"{files[0].name} not used: the run has {n} DOFs, not all six per body")
        return None
    return c, files


def _hydrostatics(run: _Run, bodies: _BodyInfo, omega, forces: dict, constants, history, notes):
    """Restoring, mass properties, centres and external terms from the companion files."""
    rho, g, depth = constants
    nb, n = bodies.count, len(bodies.dofs)
    out: dict = {}
    found = _stiffness(run, bodies, history, notes)
    c, kh_files = found if found is not None else (None, [])
    hydro_files = _body_files(run, "Hydrostatics", nb, history) or []
    values: list[dict] = []
    for path in hydro_files:
        try:
            values.append(_read_hydrostatics(path))
        except HydroDataError as exc:
            warn_damage(
                f"{exc.message}: centre of buoyancy, centre of gravity and volume not read",
                path=exc.path or path,
                line=exc.line,
                notes=notes,
                hint=exc.hint,
            )
            values = []
            break
    mass_lines = [p.name for p, v in zip(hydro_files, values, strict=False) if "mass" in v]
    if len(values) != nb:
        values = []
    if nb > 1:
        _single_mesh_files(run, bodies, mass_lines, history)
    mechanics = _mechanics(run, n, omega.size, history, notes)
    _warn_missing(run, nb, "KH", "hydrostatic_stiffness" in mechanics or "kh" in mechanics, notes)
    _warn_missing(run, nb, "Hydrostatics", False, notes)
    if "kh" in mechanics:
        if c is None:
            c = mechanics["kh"]
            kh_files = [mechanics["kh_path"]]
        elif not np.allclose(mechanics["kh"], c, rtol=1e-5, atol=1e-9 * np.abs(c).max()):
            warn_damage(
                f"differs from the mesh folder's {', '.join(p.name for p in kh_files)}: "
                "hydrostatic stiffness taken from it (NEMOH's postprocessor used it)",
                path=mechanics["kh_path"],
                notes=notes,
            )
            c = mechanics["kh"]
            kh_files = [mechanics["kh_path"]]
    if c is not None:
        problem = _waterplane_mismatch(c, bodies, omega, forces, (rho, g, depth), values)
        if problem is not None:
            warn_damage(
                problem + ": the hydrostatics files do not describe the meshes of this run "
                "(they seem to come from another mesh); hydrostatic_stiffness, centres of "
                "buoyancy and gravity and volumes from them not read",
                path=kh_files[0],
                notes=notes,
                hint="give the hydrostatic stiffness yourself (--external-stiffness, "
                "cummins.with_external_terms or ds['hydrostatic_stiffness'] = ...)",
            )
            c, values = None, []
        else:
            out["hydrostatic_stiffness"] = c
            history.append(
                f"hydrostatic stiffness from {', '.join(p.name for p in kh_files)} (as NEMOH "
                "wrote it; its C33 agrees with the run's own Froude-Krylov heave force as "
                "w -> 0)"
                if _heave_checked(bodies)
                else f"hydrostatic stiffness from {', '.join(p.name for p in kh_files)} "
                "(as NEMOH wrote it)"
            )
    if values:
        cb = np.array([[v["xb"], v["yb"], v["zb"]] for v in values])
        out["center_of_buoyancy"] = cb.reshape(-1) if nb > 1 else cb[0]
        if all({"xg", "yg", "zg"} <= v.keys() for v in values):
            cg = np.array([[v["xg"], v["yg"], v["zg"]] for v in values])
            out["center_of_gravity"] = cg.reshape(-1) if nb > 1 else cg[0]
            if c is not None and not np.allclose(cg, bodies.points, atol=1e-6):
                history.append(
                    "NEMOH does not state the point of KH.dat: here the centre of "
                    "gravity differs from the reference point, check it"
                )
        volumes = np.array([v["volume"] for v in values])
        out["displaced_volume"] = float(volumes[0]) if nb == 1 else volumes
        if nb == 1:
            for key in ("mass", "waterplane_area"):
                if key in values[0]:
                    out[key] = values[0][key]
        history.append(
            f"centre of buoyancy/gravity, volume from {', '.join(p.name for p in hydro_files)}"
        )
    if "hydrostatic_stiffness" in out:
        out.update(_restoring_weight(kh_files, hydro_files, values, rho))
    _inertia(out, mechanics, values, run, bodies, rho, history, notes)
    for key in ("km", "badd"):
        if key not in mechanics:
            continue
        name, variable = _MECHANICS[key]
        matrix = mechanics[key]
        if not np.any(matrix):
            history.append(f"Mechanics/{name} holds zeros: no {variable.replace('_', ' ')}")
            continue
        out[variable] = matrix if key == "km" else np.tile(matrix, (omega.size, 1, 1))
        history.append(
            f"{variable} from Mechanics/{name} (about the reference point, as NEMOH requires)"
        )
    return out


#: What each file of NEMOH's mesher gives (it writes both for every mesh).
_MESHER_FILES = {
    "KH": "no hydrostatic restoring (hydrostatic_stiffness)",
    "Hydrostatics": "no centre of buoyancy, centre of gravity or displaced volume",
}


def _warn_missing(run: _Run, nb: int, stem: str, replaced: bool, notes: list[str]) -> None:
    """A warning when the mesher's ``<stem>.dat`` (``<stem>_<k>.dat`` per body) is absent:
    a quantity the run had is lost, as when the file is damaged (an empty or damaged one
    is warned about where it is read); ``replaced`` when another file gives it
    (``Mechanics/Kh.dat``)."""
    if replaced or _body_files(run, stem, nb, []) is not None:
        return
    names = f"{stem}.dat" if nb == 1 else f"{stem}_0.dat … {stem}_{nb - 1}.dat (or {stem}.dat)"
    warn_damage(
        f"the run has no {names}: {_MESHER_FILES[stem]} (NEMOH's mesher writes "
        "Hydrostatics.dat and KH.dat for every mesh; removed or not copied?)",
        path=run.folder,
        notes=notes,
        hint="copy the mesher's files back, or give the values yourself",
    )


def _single_mesh_files(run: _Run, bodies: _BodyInfo, mass_lines: list[str], history) -> None:
    """Say that a multi-body run's ``Mesh/Inertia_hull.dat`` and the ``Mass`` lines of its
    hydrostatics files are not used (one history line).

    NEMOH's mesher writes them for the one mesh it processed, so they describe no single
    body of the run; when ``GC_hull.dat`` puts that mesh's centre between the bodies'
    reference points (the WEC-Sim Cubes: x = 50 m, bodies at 0 and 100 m), it was the
    bodies meshed together, and the line says so.
    """
    hull = _companion(run, ["Inertia_hull.dat"])
    if hull is None and not mass_lines:
        return

    def shown(path: Path) -> str:
        try:
            return path.relative_to(run.folder).as_posix()
        except ValueError:
            return path.name

    unused = [shown(hull)] if hull is not None else []
    if mass_lines:
        unused.append(f"the Mass line of {', '.join(mass_lines)}")
    where = ""
    centre_file = _companion(run, ["GC_hull.dat"])
    if centre_file is not None:
        try:
            centre = TextFile.read(centre_file).numbers(0, 3)
        except HydroDataError:
            centre = None
        points = bodies.points
        if centre is not None and bodies.count > 1:
            low, high = points.min(axis=0), points.max(axis=0)
            span = float(np.linalg.norm(high - low))
            inside = np.all((centre[:2] >= low[:2] - 1e-6) & (centre[:2] <= high[:2] + 1e-6))
            apart = np.linalg.norm(points[:, :2] - centre[:2], axis=1).min() > 0.05 * span
            if span > 0 and inside and apart:
                where = (
                    f" (here the {bodies.count} bodies meshed together: {shown(centre_file)} "
                    f"puts its centre at x = {centre[0]:.2f} m, y = {centre[1]:.2f} m, between "
                    "the bodies' reference points)"
                )
    history.append(
        f"{' and '.join(unused)} not used: NEMOH's mesher writes them for one mesh, not per "
        + (f"body{where}" if where else f"body of this {bodies.count}-body run")
    )


def _mechanics(run: _Run, n: int, n_omega: int, history, notes) -> dict:
    """The matrices of ``Mechanics/`` (NEMOH v3): Inertia, Kh, Km, Badd (n×n each)."""
    folder = _subfolder(run.folder, "mechanics")
    if folder is None:
        return {}
    out: dict = {}
    for key, (name, variable) in _MECHANICS.items():
        path = _find(folder, name)
        if path is None:
            continue
        matrix = _sibling_matrix(path, n, variable, notes)
        if matrix is not None:
            out[key] = matrix
            out[f"{key}_path"] = path
    return out


def _inertia(
    out: dict, mechanics: dict, values: list[dict], run, bodies, rho, history, notes
) -> None:
    """``inertia_matrix`` from ``Mechanics/Inertia.dat``, or the reason there is none (a
    negative mass or inertia is damage: warned)."""
    if "inertia" in mechanics:
        m = mechanics["inertia"]
        if np.any(np.diag(m) < 0):
            warn_damage(
                "a mass or moment of inertia on its diagonal is negative: no inertia_matrix "
                "read from it (a sign lost?)",
                path=run.folder / "Mechanics" / "Inertia.dat",
                notes=notes,
            )
            return
        if not np.all(np.diag(m)[[0, 1, 2]] > 0):
            history.append("Mechanics/Inertia.dat not used: a mass or inertia is not positive")
            return
        out["inertia_matrix"] = m
        line = (
            "inertia matrix from Mechanics/Inertia.dat (about the reference point of "
            "Nemoh.cal, as NEMOH requires)"
        )
        if _is_nemoh_estimate(m, values, run, bodies):
            line += (
                "; it is NEMOH's own estimate (mass = rho * volume of Hydrostatics.dat, "
                "inertia of a hull shell of uniform density, Mesh/Inertia_hull.dat), written "
                "when the user gives none: check it against the real mass properties"
            )
        history.append(line)
        return
    volumes = [v["volume"] for v in values]
    text = (
        "no inertia_matrix: the run has no Mechanics/Inertia.dat"
        if not volumes
        else "no inertia_matrix: the run has no Mechanics/Inertia.dat, and Hydrostatics.dat "
        "gives only the displaced volume ("
        + ", ".join(f"{v:.6g} m^3, rho*V = {rho * v:.6g} kg" for v in volumes)
        + "); rho*V is the mass only of a freely floating body (not of a moored, hinged or "
        "fixed one) and the inertia tensor cannot come from the volume"
    )
    history.append(
        text + "; give the mass properties (cummins.with_inertia: mass, centre of gravity, "
        "radii of gyration; --mass/--radii-of-gyration/--inertia-matrix)"
    )


def _is_nemoh_estimate(m: np.ndarray, values: list[dict], run: _Run, bodies: _BodyInfo) -> bool:
    """True when Inertia.dat is what NEMOH writes without user input (one body)."""
    if bodies.count != 1 or m.shape != (6, 6) or not values or "mass" not in values[0]:
        return False
    hull = _companion(run, ["Inertia_hull.dat"])
    if hull is None:
        return False
    try:
        rows = [parse_numbers(line) for line in TextFile.read(hull).lines if line.strip()]
        shell = np.vstack(rows) if all(r is not None and r.size == 3 for r in rows) else None
    except (HydroDataError, ValueError):
        return False
    if shell is None or shell.shape != (3, 3):
        return False
    return bool(
        np.allclose(np.diag(m)[:3], values[0]["mass"], rtol=1e-5)
        and np.allclose(m[3:, 3:], shell, rtol=1e-5, atol=1e-6 * np.abs(shell).max())
    )


def _heave_checked(bodies: _BodyInfo) -> bool:
    return all(bodies.heave(k) is not None for k in range(bodies.count))


def _waterplane_mismatch(c, bodies: _BodyInfo, omega, forces: dict, constants, values):
    """Why C33 of the stiffness contradicts the run's Froude-Krylov heave force, or None.

    As ω → 0 the incident-wave pressure becomes hydrostatic, ρ g η at every depth, so the
    Froude-Krylov heave force per metre of wave amplitude tends to ρ g A_wp = C33 of the
    same mesh (Newman (1977) §6.17). The test is made only where the lowest frequency is
    a long wave for the body (k √A_wp ≤ 0.3).
    """
    from cummins.io.aqwa import wavenumber

    rho, g, depth = constants
    force = forces.get("froude_krylov_force", forces.get("excitation_force"))
    if force is None or not _heave_checked(bodies):
        return None
    lowest = int(np.argmin(omega))
    k = float(wavenumber(np.array([omega[lowest]]), depth, g)[0])
    for b in range(bodies.count):
        i = bodies.heave(b)
        c33, f3 = float(c[i, i]), float(np.abs(force[lowest, 0, i]))
        size = np.sqrt(max(abs(c33), f3) / (rho * g))
        if k * size > 0.3:
            continue
        volume = values[b]["volume"] if values else size**3
        floor = 0.01 * rho * g * abs(volume) ** (2 / 3)
        if abs(c33 - f3) > HYDROSTATIC_TOLERANCE * max(abs(c33), f3) + floor:
            return (
                f"C33 of {bodies.name(b)} is {c33:.4g} N/m, but the run's Froude-Krylov heave "
                f"force at {omega[lowest]:.3g} rad/s gives rho g A_wp = {f3:.4g} N/m "
                f"(ratio {c33 / f3 if f3 else np.inf:.3g})"
            )
    return None


def _restoring_weight(kh_files, hydro_files, values, rho) -> dict:
    """What NEMOH's ``KH`` holds (:mod:`cummins.restoring`): its mesher adds the weight of
    m = ρ∇ at the centre of gravity of its input to the hydrostatics (C₄₄ = ρg(∫y²dS +
    ∇z_B) − m g z_G, about that centre), the one its ``Hydrostatics.dat`` prints; without
    those files nothing is recorded."""
    names = ", ".join(p.name for p in kh_files)
    if values and all({"xg", "yg", "zg"} <= v.keys() for v in values):
        centers = np.array([[v["xg"], v["yg"], v["zg"]] for v in values])
        return weight_record(
            [rho * v["volume"] for v in values],
            centers,
            f"{names} (NEMOH's hydrostatics and weight: m = rho V at the centre of gravity "
            f"{', '.join(p.name for p in hydro_files)} prints)",
        )
    return {SOURCE: f"{names} (as NEMOH wrote it; no Hydrostatics.dat gives its centre of gravity)"}
