"""Compute a ``HydroDB`` with the open-source BEM solver Capytaine (optional extra ``[bem]``).

``pip install cummins[bem]`` installs Capytaine. Then

>>> import numpy as np
>>> from cummins import bem
>>> mesh = bem.box_barge_mesh(20.0, 8.0, 2.0, resolution=10)      # doctest: +SKIP
>>> ds = bem.compute_hydrodb(mesh, np.linspace(0.3, 2.0, 8))      # doctest: +SKIP

solves the radiation problems (six rigid-body DOFs) at each frequency ω (rad/s) and at
ω = 0 and ω = ∞ (``added_mass_zero`` / ``added_mass_inf``), the diffraction problems
for each wave direction, and computes the hydrostatic stiffness and the rigid-body
inertia of the freely floating body (mass = displaced mass). The result is a canonical
``HydroDB`` (e^{+iωt}, z-up axes, SI), converted with
:func:`cummins.io.netcdf.from_capytaine_dataset` like a Capytaine NetCDF file.

Geometry: a mesh file in any format Capytaine reads (WAMIT ``.gdf``, NEMOH ``.dat``,
``.stl``, ``.msh`` …; only its part below the free surface z = 0 is used), or a
parametric hull: :func:`box_barge_mesh` and :func:`wigley_mesh` (length L, beam B,
draft T, the midship section at x = 0, the waterline at z = 0). Axes are Capytaine's:
x forward, y to port, z up.

Assumptions (recorded in the dataset's ``history``):

* centre of mass: by default on the free surface above the centre of buoyancy; the
  mass is the displaced mass (the body floats freely);
* rotations are about the reference point, by default the centre of mass;
* rotational inertia: that of a solid of uniform density filling the displaced volume
  (Capytaine's model), evaluated about the reference point's projection on the free
  surface (where Capytaine's integral over an open hull is exact) and moved to the
  reference point with the screw transform — replace it with the real mass
  distribution for a ship;
* ω = 0 is not available in finite depth (Capytaine's finite-depth Green function
  needs kh ≥ 0.1): ``added_mass_zero`` is then omitted, and frequencies whose problems
  fail are dropped, both with a note in ``history``.
"""

from __future__ import annotations

import logging
import math
import os
import time
import warnings
from collections.abc import Callable, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from cummins.errors import ArgumentError, CumminsError, HydroDataError
from cummins.io._common import DEFAULT_G, DEFAULT_RHO
from cummins.kinematics import screw_transform
from cummins.restoring import weight_record

__all__ = [
    "HULLS",
    "box_barge_mesh",
    "compute_hydrodb",
    "default_omegas",
    "describe",
    "hull_mesh",
    "import_capytaine",
    "load_mesh",
    "wigley_mesh",
]

#: Progress callback: called with (problems solved, total problems).
ProgressCallback = Callable[[int, int], None]

INSTALL_HINT = "pip install cummins[bem]"


def import_capytaine():
    """Import Capytaine, or raise :class:`CumminsError` saying how to install it."""
    try:
        import capytaine
    except ImportError as exc:
        raise CumminsError(
            f"the BEM solver Capytaine is not installed ({exc}); install it with: {INSTALL_HINT}"
        ) from None
    return capytaine


# --------------------------------------------------------------------------- meshes


def _panels(length: float, extent: float, resolution: int) -> int:
    """Number of panels across ``extent`` for panels about ``length / resolution`` wide."""
    return max(2, math.ceil(round(extent * resolution / length, 9)))


def _check_dimensions(length: float, beam: float, draft: float, resolution: int) -> None:
    for name, value in (("length", length), ("beam", beam), ("draft", draft)):
        if not (np.isfinite(value) and value > 0):
            raise CumminsError(f"hull {name} must be a positive number of metres, got {value!r}")
    if int(resolution) != resolution or resolution < 2:
        raise CumminsError(
            f"resolution must be an integer >= 2 (panels along the length), got {resolution!r}"
        )


def box_barge_mesh(length: float, beam: float, draft: float, *, resolution: int = 20):
    """Mesh of the wetted surface of a box barge (no lid at the waterline).

    Parameters
    ----------
    length, beam, draft
        L, B, T in metres; the box spans x ∈ [−L/2, L/2], y ∈ [−B/2, B/2], z ∈ [−T, 0].
    resolution
        Panels along the length; across the beam and the draft the panels are about
        as wide (at least 2).

    Returns
    -------
    capytaine.Mesh
    """
    _check_dimensions(length, beam, draft, resolution)
    cpt = import_capytaine()
    n_x = int(resolution)
    n_y = _panels(length, beam, n_x)
    n_z = _panels(length, draft, n_x)
    return cpt.mesh_parallelepiped(
        size=(length, beam, draft),
        center=(0.0, 0.0, -draft / 2),
        resolution=(n_x, n_y, n_z),
        missing_sides={"top"},
        name="box_barge",
    )


def wigley_mesh(length: float, beam: float, draft: float, *, resolution: int = 20):
    """Mesh of the wetted surface of a Wigley hull.

    The hull surface is y = ±(B/2)(1 − (2x/L)²)(1 − (z/T)²) for |x| ≤ L/2, −T ≤ z ≤ 0
    (displacement 4/9 L B T, waterplane area 2/3 L B, centre of buoyancy at −3T/8).

    Parameters
    ----------
    length, beam, draft
        L, B, T in metres.
    resolution
        Panels along the length (per side); over the draft about as many per metre
        (at least 4).

    Returns
    -------
    capytaine.Mesh
    """
    _check_dimensions(length, beam, draft, resolution)
    cpt = import_capytaine()
    n_x = int(resolution)
    n_z = max(4, _panels(length, draft, n_x))
    x = np.linspace(-length / 2, length / 2, n_x + 1)
    z = np.linspace(-draft, 0.0, n_z + 1)
    xx, zz = np.meshgrid(x, z, indexing="ij")
    yy = beam / 2 * (1 - (2 * xx / length) ** 2) * (1 - (zz / draft) ** 2)
    port = np.stack([xx, yy, zz], axis=-1).reshape(-1, 3)
    starboard = port * np.array([1.0, -1.0, 1.0])
    vertices = np.vstack([port, starboard])
    offset = port.shape[0]

    def vid(i: int, k: int) -> int:
        return i * (n_z + 1) + k

    # A curved hull's quads are slightly non-planar, and the centre and normal Capytaine
    # computes for such a quad depend on which vertex comes first: the first vertex is
    # chosen so that the four quarters of the hull are exact mirror images (checked by the
    # zero roll-yaw product of inertia in the tests).
    faces = []
    for i in range(n_x):
        for k in range(n_z):
            quad = [vid(i, k), vid(i, k + 1), vid(i + 1, k + 1), vid(i + 1, k)]
            if x[i] + x[i + 1] > 0:  # fore body: mirror of the aft body's split
                quad = quad[3:] + quad[:3]
            faces.append(quad)  # port side: normal towards +y
            faces.append([offset + quad[0], offset + quad[3], offset + quad[2], offset + quad[1]])
    with _quiet_capytaine():  # the quads of a curved hull are (slightly) non-planar
        return cpt.Mesh(vertices=vertices, faces=np.asarray(faces), name="wigley")


HULLS: dict[str, Callable[..., Any]] = {"box": box_barge_mesh, "wigley": wigley_mesh}


def hull_mesh(kind: str, length: float, beam: float, draft: float, *, resolution: int = 20):
    """Mesh of a parametric hull: ``kind`` is ``"box"`` or ``"wigley"``."""
    if kind not in HULLS:
        raise CumminsError(f"unknown hull {kind!r}; choose one of {', '.join(HULLS)}")
    return HULLS[kind](length, beam, draft, resolution=resolution)


def load_mesh(path: str | os.PathLike[str]):
    """Load a mesh file with Capytaine (format from the extension: .gdf, .dat, .stl …)."""
    cpt = import_capytaine()
    p = Path(path)
    if not p.is_file():
        raise HydroDataError("mesh file not found", path=p)
    try:
        with _quiet_capytaine():
            return cpt.load_mesh(str(p))
    except Exception as exc:
        raise HydroDataError(
            f"Capytaine cannot read this mesh ({type(exc).__name__}: {exc})",
            path=p,
            hint="use a format Capytaine reads (WAMIT .gdf, NEMOH .dat, .stl, .msh, .pnl …)",
        ) from None


@contextmanager
def _quiet_capytaine(level: int = logging.ERROR):
    """Silence Capytaine's per-problem log warnings (cummins reports them once)."""
    logger = logging.getLogger("capytaine")
    old = logger.level
    logger.setLevel(level)
    try:
        yield
    finally:
        logger.setLevel(old)


# --------------------------------------------------------------------------- solving


def _solve(solver, problems: list, progress: bool | ProgressCallback) -> tuple[list, list]:
    """Solve ``problems`` one by one; return (results, [(problem, error), ...])."""
    results, failures = [], []
    total = len(problems)
    bar = None
    if progress is True:
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        bar = Progress(
            TextColumn("[bold]Capytaine[/bold] {task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            TimeRemainingColumn(),
            console=Console(stderr=True),
        )
    callback = progress if callable(progress) else None
    with _quiet_capytaine(), bar if bar is not None else _null():
        task = bar.add_task("BEM problems", total=total) if bar is not None else None
        for k, problem in enumerate(problems, start=1):
            try:
                results.append(solver.solve(problem, keep_details=False))
            except Exception as exc:  # Capytaine raises various errors for unsolvable cases
                failures.append((problem, exc))
            if bar is not None:
                bar.advance(task)
            if callback is not None:
                callback(k, total)
    return results, failures


@contextmanager
def _null():
    yield


def _problem_label(problem) -> str:
    kind = "radiation" if hasattr(problem, "radiating_dof") else "diffraction"
    detail = getattr(problem, "radiating_dof", None)
    if detail is None:
        detail = f"{math.degrees(float(problem.wave_direction)):g} deg"
    return f"{kind} ({detail}) at omega = {float(problem.omega):g} rad/s"


def _inertia_about(body_factory, mesh, cog, point, rho: float) -> np.ndarray:
    """Rigid-body inertia about ``point`` (see the module docstring for the model)."""
    cpt = import_capytaine()
    surface_point = np.array([point[0], point[1], 0.0])
    body = body_factory(mesh, cpt.rigid_body_dofs(rotation_center=surface_point), cog)
    m0 = np.asarray(body.compute_rigid_body_inertia(rho=rho).values, dtype=float)
    h = screw_transform(surface_point - np.asarray(point, dtype=float))
    return h.T @ m0 @ h


def compute_hydrodb(
    mesh: Any,
    omega: ArrayLike,
    *,
    wave_direction: ArrayLike = (math.pi,),
    water_depth: float = math.inf,
    rho: float = DEFAULT_RHO,
    g: float = DEFAULT_G,
    center_of_mass: ArrayLike | None = None,
    reference_point: ArrayLike | None = None,
    limits: bool = True,
    progress: bool | ProgressCallback = False,
    name: str | None = None,
) -> xr.Dataset:
    """Solve the radiation and diffraction problems of a floating body with Capytaine.

    Parameters
    ----------
    mesh
        A mesh file (str or Path, any format Capytaine reads) or a Capytaine mesh (e.g.
        from :func:`box_barge_mesh`). Only the part below z = 0 is used.
    omega
        Wave frequencies, rad/s, finite and > 0.
    wave_direction
        Directions of wave propagation, rad (0 = along +x, π = head seas).
    water_depth
        m; ``inf`` for deep water.
    rho, g
        Water density (kg/m³) and gravity (m/s²).
    center_of_mass
        m; default: on the free surface above the centre of buoyancy.
    reference_point
        Rotation centre of the DOFs, m; default: the centre of mass.
    limits
        Also solve ω = 0 and ω = ∞ (→ ``added_mass_zero``, ``added_mass_inf``).
    progress
        ``True`` for a rich progress bar, or a callback ``f(solved, total)``.
    name
        Body name (default: the mesh's name or the file stem).

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB`` with added mass, damping, excitation (Froude–Krylov and
        diffraction parts too), hydrostatic stiffness and inertia matrix.

    Raises
    ------
    CumminsError
        Capytaine not installed, bad parameters, or no problem could be solved.
    HydroDataError
        Unreadable mesh file.
    """
    cpt = import_capytaine()
    from cummins.io.netcdf import from_capytaine_dataset

    started = time.perf_counter()
    omega = np.unique(np.asarray(omega, dtype=float).reshape(-1))
    if omega.size == 0 or not np.all(np.isfinite(omega)) or np.any(omega <= 0):
        raise CumminsError(
            "omega must hold finite frequencies > 0 rad/s (ω = 0 and ∞ come with limits=True)"
        )
    beta = np.asarray(wave_direction, dtype=float).reshape(-1)
    if not np.all(np.isfinite(beta)):
        raise CumminsError("wave directions must be finite (radians)")
    for label, value in (("rho", rho), ("g", g)):
        if not (np.isfinite(value) and value > 0):
            raise CumminsError(f"{label} must be a positive number, got {value!r}")
    if not water_depth > 0:
        raise CumminsError(f"water_depth must be positive or inf, got {water_depth!r}")

    source = ""
    history: list[str] = []
    if isinstance(mesh, str | os.PathLike):
        source = str(mesh)
        name = name or Path(mesh).stem
        mesh = load_mesh(mesh)
        history.append(f"mesh read from {Path(source).name}")
    name = name or getattr(mesh, "name", None) or "body"

    def make_body(m, dofs, cog):
        return cpt.FloatingBody(mesh=m, dofs=dofs, center_of_mass=cog, name=name)

    with _quiet_capytaine():
        probe = make_body(mesh, cpt.rigid_body_dofs(), np.zeros(3)).immersed_part()
    wet = probe.mesh
    if wet.nb_faces == 0:
        raise CumminsError("the mesh has no panel below the free surface z = 0")
    volume = float(probe.volume)
    if not volume > 0:
        raise CumminsError(
            f"the immersed volume is {volume:g} m^3: the mesh normals point inwards or the hull "
            "is not closed below the waterline"
        )
    buoyancy = np.asarray(probe.center_of_buoyancy, dtype=float)
    if center_of_mass is None:
        cog = np.array([buoyancy[0], buoyancy[1], 0.0])
        history.append(
            f"centre of mass assumed on the free surface above the centre of buoyancy: "
            f"{np.round(cog, 6).tolist()} m"
        )
    else:
        cog = np.asarray(center_of_mass, dtype=float).reshape(3)
    point = (
        cog.copy()
        if reference_point is None
        else np.asarray(reference_point, dtype=float).reshape(3)
    )
    body = make_body(wet, cpt.rigid_body_dofs(rotation_center=point), cog)

    # deep-water wavelength, m (waves are longer in shallow water)
    shortest = 2 * math.pi * g / omega.max() ** 2
    if shortest < body.minimal_computable_wavelength:
        message = (
            f"the mesh is too coarse for omega = {omega.max():g} rad/s: wavelength "
            f"{shortest:.3g} m < {body.minimal_computable_wavelength:.3g} m (8 panels per "
            "wavelength); refine the mesh or lower the highest frequency"
        )
        warnings.warn(message, stacklevel=2)
        history.append("warning: " + message)

    common = {"body": body, "water_depth": water_depth, "rho": rho, "g": g}
    radiation_omegas = ([0.0] if limits else []) + omega.tolist() + ([math.inf] if limits else [])
    problems = [
        cpt.RadiationProblem(omega=w, radiating_dof=dof, **common)
        for w in radiation_omegas
        for dof in body.dofs
    ]
    problems += [
        cpt.DiffractionProblem(omega=w, wave_direction=float(b), **common)
        for w in omega
        for b in beta
    ]
    problems.sort(key=lambda p: float(p.omega))
    results, failures = _solve(cpt.BEMSolver(), problems, progress)
    if not results:
        problem, exc = failures[0]
        raise CumminsError(
            f"Capytaine solved none of the {len(problems)} problems; first error: "
            f"{_problem_label(problem)}: {exc}"
        )
    for problem, exc in failures:
        if float(problem.omega) == 0.0 and math.isfinite(water_depth):
            continue
        history.append(f"Capytaine failed: {_problem_label(problem)}: {exc}")
    if limits and any(float(p.omega) == 0.0 for p, _ in failures):
        history.append(
            "added_mass_zero not computed: Capytaine cannot solve omega = 0 "
            + ("in finite depth" if math.isfinite(water_depth) else "for this body")
        )
    real_failures = [p for p, _ in failures if float(p.omega) != 0.0]
    if real_failures:
        warnings.warn(
            f"Capytaine could not solve {len(real_failures)} of {len(problems)} problems "
            f"(e.g. {_problem_label(real_failures[0])}); their frequencies are dropped, see "
            "the dataset's history",
            stacklevel=2,
        )

    with _quiet_capytaine():
        raw = cpt.assemble_dataset(results, hydrostatics=False)
        stiffness = body.compute_hydrostatic_stiffness(rho=rho, g=g)
    labels = [str(d) for d in body.dofs]
    raw["hydrostatic_stiffness"] = (
        ("influenced_dof", "radiating_dof"),
        np.asarray(stiffness.sel(influenced_dof=labels, radiating_dof=labels).values, dtype=float),
    )
    raw["inertia_matrix"] = (
        ("influenced_dof", "radiating_dof"),
        _inertia_about(make_body, wet, cog, point, rho),
    )
    history.append(
        "inertia: displaced mass, rotational inertia of a uniform solid filling the displaced "
        "volume (Capytaine's model)"
    )
    history.append(
        f"Capytaine {cpt.__version__}: {wet.nb_faces} panels, {len(results)} of "
        f"{len(problems)} problems solved in {time.perf_counter() - started:.1f} s"
    )
    ds = from_capytaine_dataset(
        raw,
        reference_point=point,
        source_file=source,
        source_format="capytaine",
        history=history,
    )
    ds.attrs.update(
        body_name=str(name),
        center_of_gravity=cog,
        center_of_buoyancy=buoyancy,
        displaced_volume=volume,
        n_panels=int(wet.nb_faces),
        capytaine_version=str(cpt.__version__),
    )
    ds.attrs.update(
        weight_record(  # compute_hydrostatic_stiffness adds the weight (mass rho V) at cog
            [rho * volume],
            cog,
            "Capytaine's compute_hydrostatic_stiffness (the displaced mass at the centre of mass)",
        )
    )
    return ds


def default_omegas(omega_min: float, omega_max: float, n_omega: int) -> np.ndarray:
    """``n_omega`` frequencies evenly spaced from ``omega_min`` to ``omega_max`` (rad/s);
    one frequency (``n_omega`` 1) is ``omega_min`` = ``omega_max``."""
    if n_omega < 1:
        raise ArgumentError(f"n_omega must be >= 1, got {n_omega!r}")
    if n_omega == 1:
        if not (0 < omega_min == omega_max < math.inf):
            raise ArgumentError(
                f"one frequency (n_omega 1) is omega_min = omega_max, got {omega_min!r} and "
                f"{omega_max!r}"
            )
        return np.array([float(omega_min)])
    if not (0 < omega_min < omega_max) or not math.isfinite(omega_max):
        raise ArgumentError(
            f"need 0 < omega_min < omega_max (rad/s), got {omega_min!r} and {omega_max!r}"
        )
    return np.linspace(omega_min, omega_max, int(n_omega))


def data_warnings(ds: xr.Dataset, resolution: int | None = None) -> list[str]:
    """What ``cummins check`` warns of in a computed ``HydroDB`` that the run's own
    settings can mend: A or B not symmetric (the ``symmetry`` check; at zero speed they
    are, and a panel method misses it by its discretisation error: the box barge's
    B[Sway, Roll] 17 %, 9 %, 6 % of √(B_22 B_44) at 2 rad/s with 20, 30, 40 panels along
    its length), and too few frequencies for
    retardation functions and fits (the ``frequency_grid`` check). ``resolution``: the
    panels along the length of a parametric hull (advice to raise it)."""
    from cummins.check.coefficients import _check_grid, _check_symmetry

    finer = (
        f"raise --resolution (now {resolution} panels along the length)"
        if resolution
        else "a finer mesh"
    )
    out = []
    for finding in (*_check_symmetry(ds), *_check_grid(ds)):
        if finding.severity != "warning":
            continue
        if finding.check == "symmetry":
            out.append(
                f"{finding.where}: {finding.message}: the panels' discretisation error, "
                f"which shrinks as they are refined ({finer}); `cummins check` says what it "
                "costs the motions (reciprocity)"
            )
        else:
            out.append(f"{finding.message}: {finding.advice} (--n-omega)")
    return out


def describe(ds: xr.Dataset) -> Sequence[str]:
    """A few lines summarising a computed ``HydroDB`` (for the command line)."""
    omega = ds.omega.values
    lines = [
        f"{omega.size} frequencies {omega.min():.4g} to {omega.max():.4g} rad/s, "
        f"{ds.sizes.get('wave_direction', 0)} wave direction(s), {ds.sizes['influenced_dof']} DOFs",
    ]
    if "added_mass_inf" in ds:
        lines.append("limits: A(inf)" + (" and A(0)" if "added_mass_zero" in ds else " (no A(0))"))
    c33 = float(ds.hydrostatic_stiffness.sel(influenced_dof="Heave", radiating_dof="Heave"))
    mass = float(ds.inertia_matrix.sel(influenced_dof="Surge", radiating_dof="Surge"))
    lines.append(f"mass {mass:.6g} kg, heave stiffness {c33:.6g} N/m")
    return lines
