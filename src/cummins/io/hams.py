"""HAMS projects: ``Input/ControlFile.in``, ``Input/Hydrostatic.in`` and the
"Wamit_format" output (``Output*/Wamit_format/Buoy.1 .3 .4 .hst``).

HAMS (Liu 2019, the open BEM solver of the HAMS repository) writes WAMIT-format numeric
files, read here with :func:`cummins.io.wamit.read_wamit_run`, with three differences:

* the first column follows ``Output_frequency_type`` of ``ControlFile.in``:
  1 deep-water wavenumber (ω² = g k), 2 finite-depth wavenumber (ω² = g k tanh kh at
  the run's depth), 3 ω (rad/s), 4 period (s), 5 wavelength (m); with a frequency or
  wavenumber column the limit rows are 0 (ω = 0) and −1 (ω = ∞);
* ρ and g are not in those files: HAMS prints them in its ``Hydrostar_format``
  headers (ρ = 1025 kg/m³, g printed 9.8066, the standard 9.80665 rounded); without
  them they are taken as those values, and ``history`` says so;
* the ``.4`` holds i·ξ/(ρg), not the motion RAO ξ (found by solving the equation of
  motion with the run's own matrices: −iρg × ``.4`` agrees with
  :func:`cummins.seakeeping.frequency_domain.motion_rao` to 3e-5 in modulus and 0.03° in phase on
  HAMS/Cylinder and DeepCwind, see ``tests/test_io_hams.py``); it is converted here;
* the mass matrix, external linear damping and external restoring matrices are
  inputs in ``Input/Hydrostatic.in`` (about the reference body centre): they become
  ``inertia_matrix``, ``additional_damping`` and ``additional_stiffness``. The
  external quadratic damping is not linear and is not used (history says so).
  Matrices of zeros (a run without mass properties) are not data.

The inputs are checked against the run: the water depth, reference length and centre
of ``ControlFile.in`` against those the run's Hydrostar_format headers print (an error
when they differ), the Hydrostatic Restoring Matrix of ``Hydrostatic.in`` against the
run's ``.hst`` (HAMS writes it from that matrix). ``Hydrostatic.in`` is read as HAMS
reads it (blocks in a fixed order, numbers in ``E12.5``): a block missing, a row outside
a block or a cut number is an error naming the line; matrices no user could have given
(a mass matrix that is not a rigid body's, damping that adds energy, restoring far from
symmetric: rows moved) are a warning, and none of the file's matrices is then used.

A project may hold the run's ``Output/`` and a reference ``Output_Benchmark/``. The
run's own output is read; when it holds no finite frequency (HAMS/DeepCwind's
``Output/Buoy.1`` has only the ω = 0 and ω = ∞ blocks), the benchmark set is read
instead and ``history`` says so. Empty (0-byte) sibling files are skipped with a
history note.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.files import note_read
from cummins.io._common import warn_damage
from cummins.io._text import check_cut_numbers, parse_numbers
from cummins.io.wamit import RunSettings, _parse_dot1, _read_text, numeric_kind, read_wamit_run

__all__ = ["read_hams", "sniff", "sniff_dir"]

#: Output_frequency_type of ControlFile.in → first column of the Wamit_format files.
FREQUENCY_TYPES = {
    1: "wavenumber_deep",
    2: "wavenumber",
    3: "omega",
    4: "period",
    5: "wavelength",
}
#: HAMS's constants, as its Hydrostar_format headers print them.
HAMS_RHO = 1025.0
HAMS_G = 9.80665


def _project_of(path: Path) -> Path | None:
    path = Path(path)
    if path.is_file() and path.name.lower() == "controlfile.in":
        return path.parent.parent
    if path.is_dir() and (path / "Input" / "ControlFile.in").is_file():
        return path
    return None


def _outputs(project: Path) -> list[Path]:
    """``Output*`` folders with a Wamit_format ``.1`` file, the run's own first."""
    found = [p for p in sorted(project.glob("Output*")) if p.is_dir() and _dot1(p) is not None]
    return sorted(found, key=lambda p: (p.name != "Output", p.name))


def _dot1(output: Path) -> Path | None:
    folder = output / "Wamit_format"
    if not folder.is_dir():
        return None
    ones = [p for p in sorted(folder.glob("*.1")) if p.stat().st_size and numeric_kind(p) == ".1"]
    return ones[0] if ones else None


def sniff(path: Path) -> bool:
    """A HAMS ``ControlFile.in`` (by name and content)."""
    if Path(path).name.lower() != "controlfile.in":
        return False
    try:
        return "HAMS Control file" in Path(path).read_text(errors="replace")[:2000]
    except OSError:
        return False


def sniff_dir(path: Path) -> list[Path]:
    """A HAMS project folder: ``Input/ControlFile.in`` and an ``Output*/Wamit_format`` run."""
    control = Path(path) / "Input" / "ControlFile.in"
    if control.is_file() and _outputs(Path(path)):
        return [control]
    return []


def _control(path: Path) -> dict:
    """Water depth, frequency types, reference length and centre from ControlFile.in."""
    text = _read_text(path)
    out: dict = {}
    keys = {
        "waterdepth": "depth",
        "output_frequency_type": "output_type",
        "input_frequency_type": "input_type",
        "reference_body_length": "ulen",
        "reference_body_center": "center",
        "0_inf_frequency_limits": "limits",
    }
    for i, line in enumerate(text.lines):
        if "End HAMS Control file" in line:
            break
        tokens = line.split()
        if len(tokens) < 2 or tokens[0].lower() not in keys:
            continue
        values = []
        for t in tokens[1:]:
            v = parse_numbers(t)
            if v is None or v.size != 1:
                break
            values.append(float(v[0]))
        if not values:
            raise text.error(f"expected a number after {tokens[0]}", i)
        if not np.all(np.isfinite(values)):
            raise text.error(f"expected a finite number after {tokens[0]}", i)
        key = keys[tokens[0].lower()]
        if key == "center" and len(values) != 3:
            raise text.error(
                f"expected the 3 coordinates x y z after {tokens[0]}, found {len(values)}", i
            )
        out[key] = values if key == "center" else values[0]
        out[key + "_line"] = i
    for needed in ("depth", "output_type"):
        if needed not in out:
            raise text.error(f"no {needed.replace('_', ' ')} line in ControlFile.in")
    if (
        out["output_type"] != int(out["output_type"])
        or int(out["output_type"]) not in FREQUENCY_TYPES
    ):
        raise text.error(
            f"Output_frequency_type {out['output_type']:g} is not one of 1–5",
            out["output_type_line"],
        )
    return out


_MATRIX_TITLES = {
    "body mass matrix": "mass",
    "external linear damping matrix": "damping",
    "external damping matrix": "damping",
    "external quadratic damping matrix": "quadratic_damping",
    "hydrostatic restoring matrix": "restoring",
    "external restoring matrix": "external_restoring",
}


#: The blocks of ``Hydrostatic.in`` in the order HAMS reads them (``ReadHydroStatic``:
#: a title line, then the values); the quadratic damping is absent from older files.
_SECTION_ORDER = ("cog", "mass", "damping", "quadratic_damping", "restoring", "external_restoring")
_REQUIRED = {
    "cog": "Center of Gravity:",
    "mass": "Body Mass Matrix:",
    "damping": "External Linear Damping Matrix:",
    "restoring": "Hydrostatic Restoring Matrix:",
    "external_restoring": "External Restoring Matrix:",
}


def _hydrostatic_in(path: Path) -> tuple[dict[str, np.ndarray], dict[str, int]]:
    """The 6×6 matrices and the centre of gravity of ``Input/Hydrostatic.in``, and the
    line of each block's title.

    HAMS reads the blocks in a fixed order, the matrix rows in a fixed format
    (``6(2x,E12.5)``): a block missing, out of order or twice, a row outside a block and
    a number shorter than the others (a cut line) are errors naming the line.
    """
    text = _read_text(path)
    out: dict[str, np.ndarray] = {}
    titles: dict[str, int] = {}
    matrix_rows: list[int] = []
    i = 0
    while i < len(text):
        title = text.lines[i].strip().rstrip(":").lower()
        key = "cog" if title == "center of gravity" else _MATRIX_TITLES.get(title)
        if key is not None:
            if key in titles:
                raise text.error(f"a second '{text.lines[i].strip()}' block", i)
            later = [k for k in titles if _SECTION_ORDER.index(k) > _SECTION_ORDER.index(key)]
            if later:
                raise text.error(
                    f"'{text.lines[i].strip()}' after the block of line {titles[later[0]] + 1}: "
                    "HAMS reads the blocks in the order centre of gravity, mass, damping, "
                    "restoring (a line moved?)",
                    i,
                )
            titles[key] = i
        if key == "cog":
            out["cog"] = text.numbers(i + 1, 3)
            if not np.all(np.isfinite(out["cog"])):
                raise text.error("non-finite centre of gravity", i + 1)
            i += 2
            continue
        if key is not None:
            rows = [text.numbers(i + 1 + k, 6) for k in range(6)]
            m = np.vstack(rows)
            if not np.all(np.isfinite(m)) or np.any(np.abs(m) >= 1e30):
                raise text.error("non-finite or implausible value in this matrix", i + 1)
            out[key] = m
            matrix_rows.extend(range(i + 1, i + 7))
            i += 7
            continue
        if text.lines[i].strip() and parse_numbers(text.lines[i]) is not None:
            raise text.error("a row of numbers outside any matrix (a line added or lost?)", i)
        i += 1
    missing = [k for k in _REQUIRED if k not in titles]
    if missing:
        raise text.error(
            f"no '{_REQUIRED[missing[0]]}' block: HAMS reads "
            f"{', '.join(_REQUIRED.values())} in this order (the file is truncated or edited?)",
            len(text) - 1,
        )
    check_cut_numbers(text, matrix_rows, range(6))
    return out, titles


def _implausible(matrices: dict[str, np.ndarray], titles: dict[str, int]) -> tuple[str, int] | None:
    """Why the matrices of ``Hydrostatic.in`` cannot be as HAMS's user gave them, with the
    line of the block at fault, or None.

    The rows carry no label (HAMS reads them in order), so a row moved or swapped shows
    only in what the matrices must be: a rigid body's mass matrix is symmetric, m·I in
    translation, with positive moments of inertia and positive semi-definite; linear and
    quadratic damping dissipate energy (symmetric part positive semi-definite); the
    external restoring is nearly symmetric (DeepCwind's: 0.9 % apart, HywindSpar's
    0.18 %; a swap makes an entry face a zero or a much different value).
    Matrices of zeros (a run without them) pass.
    """
    m = matrices["mass"]
    if np.any(m):
        scale = np.abs(m).max()
        bad = np.abs(m - m.T) > 1e-3 * np.maximum(np.abs(m), np.abs(m.T)) + 1e-9 * scale
        if bad.any():
            i, j = np.argwhere(bad)[0]
            return (
                f"the body mass matrix is not symmetric: M({i + 1},{j + 1}) = {m[i, j]:g}, "
                f"M({j + 1},{i + 1}) = {m[j, i]:g}",
                titles["mass"],
            )
        mass = float(m[0, 0])
        if mass <= 0 or np.abs(m[:3, :3] - mass * np.eye(3)).max() > 1e-6 * scale:
            return (
                "the body mass matrix of a rigid body has the mass on its first three diagonal "
                f"entries and zeros beside them; here {np.diag(m)[:3].tolist()}",
                titles["mass"],
            )
        if np.any(np.diag(m)[3:] <= 0):
            k = 3 + int(np.argmax(np.diag(m)[3:] <= 0))
            return (
                f"the body mass matrix has the mass {mass:g} kg but the moment of inertia "
                f"M({k + 1},{k + 1}) = {m[k, k]:g}, not positive",
                titles["mass"],
            )
    for key, what in (
        ("mass", "body mass"),
        ("damping", "external linear damping"),
        ("quadratic_damping", "external quadratic damping"),
    ):
        if key not in matrices or not np.any(matrices[key]):
            continue
        x = matrices[key]
        lowest = float(np.linalg.eigvalsh(0.5 * (x + x.T)).min())
        if lowest < -1e-9 * np.abs(x).max():
            return (
                f"the {what} matrix is not positive semi-definite (eigenvalue {lowest:.4g})",
                titles[key],
            )
    x = matrices["external_restoring"]
    larger = np.maximum(np.abs(x), np.abs(x.T))
    bad = (np.abs(x - x.T) > 0.5 * larger) & (larger > 1e-6 * np.abs(x).max())
    if bad.any():
        i, j = np.argwhere(bad)[0]
        return (
            f"the external restoring matrix is far from symmetric: K({i + 1},{j + 1}) = "
            f"{x[i, j]:g}, K({j + 1},{i + 1}) = {x[j, i]:g}",
            titles["external_restoring"],
        )
    return None  # the hydrostatic restoring (WAMIT's C46, C56 have no C64, C65) is
    # checked against the run's .hst instead: _restoring_against_hst


def _restoring_against_hst(
    restoring: np.ndarray, hst: Path | None, rho: float, g: float
) -> str | None:
    """How the Hydrostatic Restoring Matrix of ``Hydrostatic.in`` differs from the run's
    ``.hst``, or None.

    HAMS writes the ``.hst`` from that very matrix (``ReadHydroStatic``: C/(ρg)), so the
    two agree to the five digits of ``Hydrostatic.in`` (HAMS/Cylinder, DeepCwind,
    HywindSpar: within 3e-5 relative). An unreadable ``.hst`` is left to the WAMIT-format
    reader, which says so.
    """
    from cummins.io.wamit import _read_hst

    if hst is None or not hst.is_file() or not hst.stat().st_size:
        return None
    try:
        c = _read_hst(hst, 6)
    except HydroDataError:
        return None
    written = c * rho * g
    scale = max(np.abs(restoring).max(), np.abs(written).max())
    gap = np.abs(restoring - written)
    bad = gap > 2e-4 * np.abs(written) + 1e-6 * scale
    if bad.any():
        i, j = np.argwhere(bad)[0]
        return (
            f"its Hydrostatic Restoring Matrix gives C({i + 1},{j + 1}) = {restoring[i, j]:g}, "
            f"the run's {hst.name} {written[i, j]:g} (HAMS writes the .hst from that matrix)"
        )
    return None


_HEADER_VALUES = {
    "rho": re.compile(r"Water density \(rho\)\s*:\s*([-+0-9.Ee]+)"),
    "g": re.compile(r"Gravity acceleration\s*:\s*([-+0-9.Ee]+)"),
    "depth": re.compile(r"Waterdepth\s*:\s*(Inf\.?|[-+0-9.Ee]+)"),
    "ulen": re.compile(r"Reference length\s*:\s*([-+0-9.Ee]+)"),
    "center": re.compile(
        r"Reference point of body 1\s*:\s*\(\s*([-+0-9.Ee]+)\s+([-+0-9.Ee]+)\s+([-+0-9.Ee]+)\s*\)"
    ),
}


def _constants(output: Path) -> tuple[float | None, float | None, str | None, dict]:
    """ρ, g, the file they come from, and the depth, reference length and centre the run
    used, as printed in the Hydrostar_format headers of an output."""
    for f in sorted((output / "Hydrostar_format").glob("*.rao"))[:1]:
        note_read(f)
        head = f.read_text(errors="replace").splitlines()[:16]
        found: dict = {}
        for line in head:
            for key, rx in _HEADER_VALUES.items():
                if key not in found and (m := rx.search(line)):
                    try:
                        values = [
                            np.inf if v.lower().startswith("inf") else float(v) for v in m.groups()
                        ]
                    except ValueError:
                        continue
                    found[key] = values if key == "center" else values[0]
        return found.get("rho"), found.get("g"), f"{output.name}/Hydrostar_format/{f.name}", found
    return None, None, None, {}


def _check_control_against_run(control: dict, printed: dict, where: str, path: Path) -> None:
    """The ControlFile.in settings the run's own output headers print must agree."""
    text = _read_text(path)
    depth = float(control["depth"])
    checks = [
        ("depth", np.inf if depth <= 0 else depth, "Waterdepth", "m"),
        ("ulen", float(control.get("ulen", 1.0)), "Reference_body_length", "m"),
    ]
    for key, value, name, unit in checks:
        if key not in printed or (key == "ulen" and "ulen" not in control):
            continue
        run = float(printed[key])
        same = (np.isinf(run) and np.isinf(value)) or (
            np.isfinite(run) and np.isfinite(value) and abs(run - value) <= 1e-3 + 1e-4 * abs(run)
        )
        if not same:
            raise text.error(
                f"{name} is {value:g} {unit} here, but the run's output was computed with "
                f"{run:g} {unit} ({where})",
                control.get(f"{key}_line"),
                hint="this ControlFile.in is not the run's, or was edited since",
            )
    if "center" in printed and "center" in control:
        run = np.asarray(printed["center"], dtype=float)
        here = np.asarray(control["center"], dtype=float)
        if np.abs(run - here).max() > 1e-3 + 1e-4 * np.abs(run).max():
            raise text.error(
                f"Reference_body_center is {here.tolist()} m here, but the run's output was "
                f"computed about {run.tolist()} m ({where})",
                control.get("center_line"),
                hint="this ControlFile.in is not the run's, or was edited since",
            )


def read_hams(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    output: str | os.PathLike[str] | None = None,
    siblings: bool = True,
) -> xr.Dataset:
    """Read a HAMS project into a canonical ``HydroDB``.

    Parameters
    ----------
    path
        The project folder (holding ``Input/`` and ``Output*/``) or its
        ``Input/ControlFile.in``.
    rho, g
        Water density (kg/m³) and gravity (m/s²), if not HAMS's (module docstring).
    output
        The output folder to read (``Output``, ``Output_Benchmark`` …); by default the
        run's own ``Output/``, else the benchmark set (module docstring).
    siblings
        Read the ``.3``, ``.4`` and ``.hst`` beside the ``.1``.
    """
    project = _project_of(Path(path))
    if project is None:
        raise HydroDataError(
            "not a HAMS project (no Input/ControlFile.in)",
            path=path,
            hint="pass the folder that holds Input/ and Output/",
        )
    control_path = project / "Input" / "ControlFile.in"
    control = _control(control_path)
    history = [f"HAMS project {project.name}: settings from Input/ControlFile.in"]
    column = FREQUENCY_TYPES[int(control["output_type"])]
    depth = float(control["depth"])
    depth = np.inf if depth <= 0 else depth
    g_run = g if g is not None else HAMS_G

    outputs = _outputs(project) if output is None else [Path(output)]
    if not outputs or _dot1(outputs[0]) is None:
        raise HydroDataError(
            "no Wamit_format .1 file in the project's output folders",
            path=project if output is None else output,
            hint="run HAMS first, or pass the folder holding Wamit_format/",
        )
    chosen = outputs[0]
    if output is None and len(outputs) > 1:
        try:
            _parse_dot1(_dot1(chosen), column, depth=depth, g=g_run)
        except HydroDataError as exc:
            if "no finite frequency" not in str(exc):
                raise
            history.append(
                f"{chosen.name}/Wamit_format/{_dot1(chosen).name} holds no finite frequency "
                f"(only the ω = 0 and ω = ∞ blocks): read {outputs[1].name}/ instead, the "
                "project's benchmark output of the same run"
            )
            chosen = outputs[1]
    history.append(f"output read from {chosen.name}/Wamit_format")

    rho_file, g_file, where, printed = _constants(chosen)
    _check_control_against_run(control, printed, where, control_path)
    if g_file is not None and abs(g_file - HAMS_G) < 5e-5:
        history.append(f"g printed as {g_file:g} in {where}: the standard 9.80665 m/s^2")
        g_file = HAMS_G
    constants_source = None
    if rho_file is None:
        rho_file, g_file = HAMS_RHO, HAMS_G
        constants_source = "HAMS's constant, not written in its Wamit_format files"
        history.append(
            "rho = 1025 kg/m^3, g = 9.80665 m/s^2: HAMS's constants (not written in the "
            "Wamit_format files; pass rho=, g= if the run used others)"
        )

    settings = RunSettings(
        source_format="hams",
        first_column=column,
        rho=rho_file,
        g=g_file,
        constants_source=constants_source,
        ulen=float(control.get("ulen", 1.0)),
        water_depth=depth,
        history=history,
        reference_point=np.asarray(control.get("center", [0.0, 0.0, 0.0]), dtype=float),
        rao_times_rho_g=True,
    )
    hydrostatic = project / "Input" / "Hydrostatic.in"
    if hydrostatic.is_file() and hydrostatic.stat().st_size:
        matrices, titles = _hydrostatic_in(hydrostatic)
        problem = _implausible(matrices, titles)
        if problem is None:
            mismatch = _restoring_against_hst(
                matrices["restoring"],
                _dot1(chosen).with_suffix(".hst"),
                rho_file,  # HAMS divided by its own constants
                g_file,
            )
            problem = None if mismatch is None else (mismatch, titles["restoring"])
        if problem is not None:
            warn_damage(
                f"{problem[0]}: a row moved or edited? The matrices of Input/Hydrostatic.in "
                "are not read (no inertia_matrix, additional_damping, additional_stiffness "
                "from it)",
                path=hydrostatic,
                line=problem[1] + 1,
                notes=settings.notes,
            )
            matrices = {}
    else:
        # HAMS reads it for every run: without it the run's mass and external matrices
        # are lost, as when it is damaged
        warn_damage(
            f"{'empty' if hydrostatic.is_file() else 'missing'}: HAMS reads it for every "
            "run, so the run's mass, external damping and external restoring are unknown "
            "(no inertia_matrix, additional_damping, additional_stiffness)",
            path=hydrostatic,
            notes=settings.notes,
        )
        matrices = {}
    if matrices:
        if np.any(matrices["mass"]):
            settings.inertia_matrix = matrices["mass"]
            history.append("inertia matrix from Input/Hydrostatic.in (Body Mass Matrix)")
        else:
            history.append("no inertia matrix: Input/Hydrostatic.in gives a mass matrix of zeros")
        if np.any(matrices["damping"]):
            settings.additional_damping = matrices["damping"]
            history.append("external linear damping from Input/Hydrostatic.in")
        if np.any(matrices["external_restoring"]):
            settings.additional_stiffness = matrices["external_restoring"]
            history.append("external restoring from Input/Hydrostatic.in as additional_stiffness")
        if "quadratic_damping" in matrices and np.any(matrices["quadratic_damping"]):
            history.append(
                "the external quadratic damping of Input/Hydrostatic.in is not linear: not used"
            )
    return read_wamit_run(_dot1(chosen), rho=rho, g=g, settings=settings, siblings=siblings)
