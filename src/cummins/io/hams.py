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
  :func:`cummins.frequency_domain.motion_rao` to 3e-5 in modulus and 0.03° in phase on
  HAMS/Cylinder and DeepCwind, see ``tests/test_io_hams.py``); it is converted here;
* the mass matrix, external linear damping and external restoring matrices are
  inputs in ``Input/Hydrostatic.in`` (about the reference body centre): they become
  ``inertia_matrix``, ``additional_damping`` and ``additional_stiffness``. The
  external quadratic damping is not linear and is not used (history says so).
  Matrices of zeros (a run without mass properties) are not data.

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
from cummins.io._text import parse_numbers
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
        key = keys[tokens[0].lower()]
        out[key] = values if key == "center" else values[0]
        out[key + "_line"] = i
    for needed in ("depth", "output_type"):
        if needed not in out:
            raise text.error(f"no {needed.replace('_', ' ')} line in ControlFile.in")
    if int(out["output_type"]) not in FREQUENCY_TYPES:
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


def _hydrostatic_in(path: Path) -> dict[str, np.ndarray]:
    """The 6×6 matrices and the centre of gravity of ``Input/Hydrostatic.in``."""
    text = _read_text(path)
    out: dict[str, np.ndarray] = {}
    i = 0
    while i < len(text):
        title = text.lines[i].strip().rstrip(":").lower()
        if title == "center of gravity":
            out["cog"] = text.numbers(i + 1, 3)
            i += 2
            continue
        if title in _MATRIX_TITLES:
            rows = [text.numbers(i + 1 + k, 6) for k in range(6)]
            m = np.vstack(rows)
            if not np.all(np.isfinite(m)) or np.any(np.abs(m) >= 1e30):
                raise text.error("non-finite or implausible value in this matrix", i + 1)
            out[_MATRIX_TITLES[title]] = m
            i += 7
            continue
        if text.lines[i].strip() and parse_numbers(text.lines[i]) is not None:
            raise text.error("a row of numbers outside any matrix (a line added or lost?)", i)
        i += 1
    if "mass" not in out:
        raise text.error("no 'Body Mass Matrix:' in Hydrostatic.in")
    return out


def _constants(output: Path) -> tuple[float | None, float | None, str | None]:
    """ρ, g and the depth line printed in the Hydrostar_format headers of an output."""
    for f in sorted((output / "Hydrostar_format").glob("*.rao"))[:1]:
        head = f.read_text(errors="replace").splitlines()[:12]
        rho = g = None
        for line in head:
            if m := re.search(r"Water density \(rho\)\s*:\s*([-+0-9.Ee]+)", line):
                rho = float(m.group(1))
            if m := re.search(r"Gravity acceleration\s*:\s*([-+0-9.Ee]+)", line):
                g = float(m.group(1))
        return rho, g, f.name
    return None, None, None


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

    rho_file, g_file, where = _constants(chosen)
    if g_file is not None and abs(g_file - HAMS_G) < 5e-5:
        history.append(f"g printed as {g_file:g} in {where}: the standard 9.80665 m/s^2")
        g_file = HAMS_G
    if rho_file is None:
        rho_file, g_file = HAMS_RHO, HAMS_G
        history.append(
            "rho = 1025 kg/m^3, g = 9.80665 m/s^2: HAMS's constants (not written in the "
            "Wamit_format files; pass rho=, g= if the run used others)"
        )

    settings = RunSettings(
        source_format="hams",
        first_column=column,
        rho=rho_file,
        g=g_file,
        ulen=float(control.get("ulen", 1.0)),
        water_depth=depth,
        history=history,
        reference_point=np.asarray(control.get("center", [0.0, 0.0, 0.0]), dtype=float),
        rao_times_rho_g=True,
    )
    hydrostatic = project / "Input" / "Hydrostatic.in"
    if hydrostatic.is_file() and hydrostatic.stat().st_size:
        matrices = _hydrostatic_in(hydrostatic)
        if np.any(matrices["mass"]):
            settings.inertia_matrix = matrices["mass"]
            history.append("inertia matrix from Input/Hydrostatic.in (Body Mass Matrix)")
        else:
            history.append("no inertia matrix: Input/Hydrostatic.in gives a mass matrix of zeros")
        if "damping" in matrices and np.any(matrices["damping"]):
            settings.additional_damping = matrices["damping"]
            history.append("external linear damping from Input/Hydrostatic.in")
        if "external_restoring" in matrices and np.any(matrices["external_restoring"]):
            settings.additional_stiffness = matrices["external_restoring"]
            history.append("external restoring from Input/Hydrostatic.in as additional_stiffness")
        if "quadratic_damping" in matrices and np.any(matrices["quadratic_damping"]):
            history.append(
                "the external quadratic damping of Input/Hydrostatic.in is not linear: not used"
            )
    return read_wamit_run(_dot1(chosen), rho=rho, g=g, settings=settings, siblings=siblings)
