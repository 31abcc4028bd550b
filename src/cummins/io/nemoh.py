"""NEMOH v2 / v3 results: ``RadiationCoefficients.tec`` and its companion files.

A NEMOH run folder holds ``Nemoh.cal`` (the input), a ``mesh/`` (or ``Mesh/``) folder
with ``KH.dat`` and ``Hydrostatics.dat`` (``KH_0.dat``, ``Hydrostatics_0.dat`` … for
several bodies) and a ``results/`` (or ``Results/``) folder with the Tecplot files.
Some projects keep everything in one folder; both layouts are read.

Files and what cummins takes from them (all dimensional, SI):

* ``Nemoh.cal``: ρ, g, water depth (``0`` means deep water), the bodies (named after
  their mesh files), the degrees of freedom and generalised forces (type 1 = translation
  along a direction, type 2 = rotation about an axis through a point), the wave
  directions and, in v3, the unit of the frequency column of the output files.
  v2 writes the frequency line as ``N wmin wmax`` (rad/s); v3 as ``type N min max``
  and adds the RAO / output-frequency-unit lines and a QTF section.
* ``RadiationCoefficients.tec``: one zone per radiating DOF ("Motion of body b in DoF
  j"); each row is ω followed by (A, B) for every generalised force: zone j, pair k is
  ``added_mass[influenced=k, radiating=j]`` (kg, kg·m, kg·m²) and the damping.
* ``ExcitationForce.tec``, ``DiffractionForce.tec``, ``FKForce.tec``: one zone per wave
  direction ("… - beta = β deg"), rows ω, then (|F|, phase) per force, N/m or N·m/m per
  metre of wave amplitude. v2 titles the zones of ``ExcitationForce.tec`` "Diffraction
  force" although they hold the total excitation. Phases are in radians (v2, v3.0);
  a file whose phases exceed π in magnitude is read as degrees (documented for later
  v3 releases), and the dataset's ``history`` says which.
* ``KH.dat``: the 6×6 hydrostatic stiffness per body (N/m, N, N·m/rad), as NEMOH wrote
  it; ``Hydrostatics.dat``: centre of buoyancy ``XF YF ZF``, centre of gravity
  ``XG YG ZG``, displaced volume (m³) and, in v3, the mass.
* ``Mechanics/Inertia.dat`` (v3) → ``inertia_matrix`` about the rotation point (NEMOH
  requires the matrices there; when the user gives none NEMOH writes its own estimate,
  ρ∇ and a uniform hull shell, which ``history`` then says), ``Km.dat`` →
  ``additional_stiffness``, ``Badd.dat`` → ``additional_damping`` (when not zero),
  ``Kh.dat`` checked against the mesh folder's ``KH.dat``. Without ``Inertia.dat`` there
  is no ``inertia_matrix``: ρ∇ is the mass only of a freely floating body, and the
  inertia tensor cannot come from the volume (``history`` says so).
* Several bodies: ``KH_0.dat`` … per body in the order of ``Nemoh.cal`` (a ``KH.dat``
  beside them is the mesher's file of the last mesh it processed), labels
  ``body1__Surge`` …, the mesh names in ``body_names``. C33 of each body is checked
  against ρ g A_wp, the ω → 0 limit of the run's own Froude-Krylov heave force: files
  of another mesh (the corpus Cubes and bemio two-body runs) are not read, with a
  warning.
* ``Nemoh.cal`` edited after the run (other frequency or direction counts than the
  results): the results are read, ``history`` says so. QTF output is not read.
* ``IRF.tec`` (if the post-processor was run with IRF on): NEMOH's own A(∞), column
  "AddedMass k" of zone "DoF j" being ``added_mass_inf[influenced=k, radiating=j]``.
  It is only used after checking that the file belongs to the run: its K(t) must be the
  cosine transform (2/π)∫B(ω)cos(ωt)dω of the run's damping, computed as NEMOH does
  (trapezoidal rule on the run's grid). Otherwise it is ignored, with a warning and a
  ``history`` line. NEMOH's K(t) itself is never put in the dataset.
* The frequency column is ω in rad/s unless the ``VARIABLES`` header says ``f (Hz)`` or
  ``T (s)`` (v3 "output freq type" 2 or 3), or ``Nemoh.cal`` asks for it.

Conventions. NEMOH's complex amplitudes follow exp(−iωt) (its RAO equation is
−(M+A)ω² − iωB + K, and WEC-Sim's reader negates the phases): cummins conjugates them
to its exp(+iωt) convention, i.e. F = |F|·exp(−i·phase). The cross-code test of the
WEC-Sim cylinder confirms it (NEMOH's surge phase −90° becomes WAMIT's +90°). Axes are
z up, x and y in the mean free surface (as cummins); wave direction β is the direction
of propagation from +x towards +y (as cummins). Moments and rotations are about the
point given on the rotation lines of ``Nemoh.cal``, recorded as ``reference_point``.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES, dof_labels, make_hydrodb
from cummins.io._common import resolve_rho_g, warn_damage
from cummins.io._text import TextFile, check_cut_numbers, parse_numbers

__all__ = ["read_nemoh", "sniff", "sniff_dir"]

RADIATION_FILE = "RadiationCoefficients.tec"
_FORCE_FILES = {
    "excitation": "ExcitationForce.tec",
    "diffraction": "DiffractionForce.tec",
    "froude_krylov": "FKForce.tec",
}
_IRF_FILE = "IRF.tec"
_TEC_FILES = (RADIATION_FILE, *_FORCE_FILES.values(), _IRF_FILE)

#: Largest relative mismatch between IRF.tec's K(t) and the one computed from the
#: run's damping for the IRF file to be accepted (same formula, same data: ~1e-6).
IRF_TOLERANCE = 0.05

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"


# --------------------------------------------------------------------------- detection


def _head(path: Path, size: int = 4096) -> str:
    with open(path, "rb") as f:
        return f.read(size).decode("utf-8-sig", errors="replace")


def _is_tecplot(head: str) -> bool:
    lines = [line.strip() for line in head.splitlines() if line.strip()]
    if not lines or not lines[0].upper().startswith("VARIABLES"):
        return False
    zone = next((line for line in lines if line.lower().startswith("zone")), None)
    if zone is None:
        return False
    zone = zone.lower()
    return any(key in zone for key in ("motion of body", "beta", "fkforce", "dof"))


def _is_nemoh_cal(head: str) -> bool:
    low = head.lower()
    return "--- environment" in low and "number of bodies" in low


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` a NEMOH ``.tec`` result file or a ``Nemoh.cal``?"""
    path = Path(path)
    if not path.is_file():
        return False
    head = _head(path)
    return _is_tecplot(head) or _is_nemoh_cal(head)


def _find(folder: Path, name: str) -> Path | None:
    """The file ``name`` in ``folder``, whatever the case of its letters."""
    exact = folder / name
    if exact.is_file():
        return exact
    if not folder.is_dir():
        return None
    lower = name.lower()
    for candidate in sorted(folder.iterdir()):
        if candidate.name.lower() == lower and candidate.is_file():
            return candidate
    return None


def _subfolder(folder: Path, name: str) -> Path | None:
    for candidate in (folder / name, folder / name.capitalize()):
        if candidate.is_dir():
            return candidate
    if folder.is_dir():
        for candidate in sorted(folder.iterdir()):
            if candidate.is_dir() and candidate.name.lower() == name:
                return candidate
    return None


def sniff_dir(path: Path) -> list[Path]:
    """The NEMOH run in a folder: ``[RadiationCoefficients.tec]`` or ``[]``.

    The folder may be the results folder itself or the run folder holding
    ``Nemoh.cal`` and a ``results/`` subfolder.
    """
    path = Path(path)
    for folder in (path, _subfolder(path, "results")):
        if folder is None:
            continue
        found = _find(folder, RADIATION_FILE)
        if found is not None and sniff(found):
            return [found]
    return []


# --------------------------------------------------------------------------- Tecplot files


@dataclass
class _Zone:
    title: str
    table: np.ndarray  # (rows, width)
    line: int  # 0-based index of the zone header line


@dataclass
class _Tecplot:
    text: TextFile
    variables: str
    zones: list[_Zone]

    @property
    def path(self) -> Path:
        return self.text.path


_ZONE_COUNT = re.compile(r"\bI\s*=\s*(\d+)", re.IGNORECASE)
_ZONE_TITLE = re.compile(r'T\s*=\s*"([^"]*)"', re.IGNORECASE)


def _read_tecplot(path: Path) -> _Tecplot:
    """Parse a NEMOH Tecplot file: header, then zones of ``I`` rows of numbers.

    Rows that Fortran wrapped over several lines (more than 80 values) are joined.
    """
    text = TextFile.read(path)
    lines = text.lines
    first = next((i for i, line in enumerate(lines) if line.strip()), None)
    if first is None or not lines[first].strip().upper().startswith("VARIABLES"):
        raise text.error(
            "not a NEMOH Tecplot file (no VARIABLES header)",
            first or 0,
            hint='NEMOH result files start with VARIABLES="w (rad/s)"',
        )
    zone_lines = [
        i for i in range(first, len(lines)) if lines[i].lstrip().lower().startswith("zone")
    ]
    if not zone_lines:
        raise text.error("no Zone in the file (truncated?)", len(lines) - 1)
    header = " ".join(lines[first : zone_lines[0]])
    names = re.findall(r'"([^"]*)"', header)
    width = len(names) if names and header.strip().upper().startswith('VARIABLES="') else 0
    zones: list[_Zone] = []
    for z, start in enumerate(zone_lines):
        stop = zone_lines[z + 1] if z + 1 < len(zone_lines) else len(lines)
        zone_line = lines[start]
        count_match = _ZONE_COUNT.search(zone_line)
        if count_match is None:
            raise text.error("zone header without its row count (I=…)", start)
        title_match = _ZONE_TITLE.search(zone_line)
        title = title_match.group(1) if title_match else zone_line.strip()
        table = _zone_rows(text, start + 1, stop, int(count_match.group(1)), width)
        if width == 0:
            width = table.shape[1]
        zones.append(_Zone(title.strip(), table, start))
    return _Tecplot(text, lines[first].strip(), zones)


def _zone_rows(text: TextFile, start: int, stop: int, count: int, width: int) -> np.ndarray:
    """``count`` rows of ``width`` numbers between lines ``start`` and ``stop``."""
    rows: list[np.ndarray] = []
    pending: list[np.ndarray] = []
    pending_size = 0
    for i in range(start, stop):
        line = text.lines[i]
        if not line.strip():
            continue
        values = parse_numbers(line)
        if values is None:
            raise text.error(f"expected a row of numbers, found {line.strip()[:60]!r}", i)
        if not np.all(np.isfinite(values)):
            raise text.error(
                "non-finite value (NaN or Inf) in the data",
                i,
                hint="the solver failed at this point; rerun it or remove the frequency",
            )
        if len(rows) == count:
            raise text.error(
                f"more rows than the {count} the zone header announces",
                i,
                hint="the file is damaged or was edited",
            )
        if width == 0:
            width = values.size
        pending.append(values)
        pending_size += values.size
        if pending_size == width:
            rows.append(np.concatenate(pending))
            pending, pending_size = [], 0
        elif pending_size > width:
            raise text.error(f"expected {width} numbers on the row, found {pending_size}", i)
    if pending or len(rows) != count:
        raise text.error(
            f"the zone announces {count} rows but has {len(rows)} complete ones (truncated?)",
            stop - 1,
        )
    numbered = [i for i in range(start, stop) if text.lines[i].strip()]
    check_cut_numbers(text, numbered, range(max(len(text.lines[i].split()) for i in numbered)))
    if width < 3 or width % 2 == 0:
        raise text.error(
            f"rows of {width} numbers: expected the frequency and pairs of values", start
        )
    return np.vstack(rows)


def _frequency_unit(tec: _Tecplot, cal_unit: int | None) -> str:
    """``"rad/s"``, ``"Hz"`` or ``"s"`` for the first column of a Tecplot file."""
    head = tec.variables.lower().replace(" ", "")
    if "rad/s" in head:
        return "rad/s"
    if "(hz)" in head:
        return "Hz"
    if "(s)" in head:
        return "s"
    return {2: "Hz", 3: "s"}.get(cal_unit or 1, "rad/s")


def _to_omega(values: np.ndarray, unit: str) -> np.ndarray:
    if unit == "Hz":
        return 2 * np.pi * values
    if unit == "s":
        with np.errstate(divide="ignore"):
            return 2 * np.pi / values
    return values


def _frequencies(tec: _Tecplot, cal_unit: int | None) -> tuple[np.ndarray, str]:
    """The common frequency column of all zones, as ω (rad/s), checked."""
    unit = _frequency_unit(tec, cal_unit)
    reference = tec.zones[0].table[:, 0]
    for zone in tec.zones[1:]:
        column = zone.table[:, 0]
        if column.shape != reference.shape or not np.allclose(column, reference, rtol=1e-6, atol=0):
            k = int(np.argmax(~np.isclose(column, reference, rtol=1e-6, atol=0)))
            raise tec.text.error(
                f"zone {zone.title!r} has other frequencies than the first zone "
                f"({column[k]:g} instead of {reference[k]:g})",
                zone.line + 1 + k,
                hint="the file is damaged or edited: each zone repeats the same frequencies",
            )
    step = np.diff(reference)
    if reference.size > 1 and not (np.all(step > 0) or np.all(step < 0)):
        k = int(np.argmax(step <= 0) if step[0] > 0 else np.argmax(step >= 0))
        raise tec.text.error(
            f"the frequency column is not monotonic ({reference[k]:g} then {reference[k + 1]:g})",
            tec.zones[0].line + 2 + k,
            hint="NEMOH writes the frequencies in order; the file seems edited or damaged",
        )
    if np.any(reference <= 0):
        k = int(np.argmax(reference <= 0))
        raise tec.text.error(
            f"frequency {reference[k]:g} {unit} is not positive", tec.zones[0].line + 1 + k
        )
    return _to_omega(reference, unit), unit


# --------------------------------------------------------------------------- Nemoh.cal


@dataclass
class _Mode:
    """A degree of freedom or generalised force line of ``Nemoh.cal``."""

    kind: int  # 1 translation, 2 rotation
    direction: np.ndarray
    point: np.ndarray
    line: int


@dataclass
class _Body:
    name: str
    dofs: list[_Mode]
    forces: list[_Mode]


@dataclass
class _NemohCal:
    path: Path
    rho: float
    g: float
    depth: float
    bodies: list[_Body]
    version: str
    n_frequencies: int
    n_directions: int
    output_unit: int | None = None
    frequency_range: tuple[float, float, int] = (0.0, 0.0, 1)  # min, max, unit (1 rad/s …)
    qtf: bool = False


class _Cursor:
    """Walks the value lines of ``Nemoh.cal`` (the part before ``!`` of each line)."""

    def __init__(self, text: TextFile, start: int) -> None:
        self.text = text
        self.i = start

    def line(self) -> tuple[str, int]:
        while self.i < len(self.text.lines) and not self.text.lines[self.i].strip():
            self.i += 1
        if self.i >= len(self.text.lines):
            raise self.text.error("Nemoh.cal ends too early (truncated?)", len(self.text.lines) - 1)
        i = self.i
        self.i += 1
        return self.text.lines[i].split("!", 1)[0].strip(), i

    def numbers(self, what: str, at_least: int = 1) -> tuple[np.ndarray, int]:
        content, i = self.line()
        values = [
            float(v.replace("D", "E").replace("d", "e")) for v in re.findall(_NUMBER, content)
        ]
        leftover = re.sub(_NUMBER, "", content).strip()
        if len(values) < at_least or leftover:
            raise self.text.error(
                f"expected {what} ({at_least} number{'s' if at_least > 1 else ''}), "
                f"found {content[:60]!r}",
                i,
            )
        array = np.asarray(values)
        if not np.all(np.isfinite(array)):
            raise self.text.error(f"non-finite value in {what}", i)
        return array, i

    def count(self, what: str, maximum: int = 10000) -> int:
        values, i = self.numbers(what)
        n = values[0]
        if n != round(n) or n < 0 or n > maximum:
            raise self.text.error(f"{what} must be a whole number, found {n:g}", i)
        return int(n)

    def header(self, keyword: str) -> None:
        content, i = self.line()
        if not content.startswith("---") or keyword not in content.lower():
            raise self.text.error(f"expected the '--- {keyword}' section header", i)


def _read_cal(path: Path) -> _NemohCal:
    """Parse ``Nemoh.cal`` (v2 or v3 layout)."""
    text = TextFile.read(path)
    start = next(
        (
            i
            for i, line in enumerate(text.lines)
            if "environment" in line.lower() and line.strip().startswith("---")
        ),
        None,
    )
    if start is None:
        raise text.error("no '--- Environment' section: not a Nemoh.cal file", 0)
    cur = _Cursor(text, start + 1)
    rho = cur.numbers("the water density RHO")[0][0]
    g = cur.numbers("gravity G")[0][0]
    depth = cur.numbers("the water depth")[0][0]
    cur.numbers("the wave measurement point", 2)
    if rho <= 0 or g <= 0 or depth < 0:
        raise text.error("RHO and G must be positive and the depth not negative", start + 1)
    cur.header("floating bodies")
    n_bodies = cur.count("the number of bodies", 1000)
    if n_bodies == 0:
        raise text.error("Nemoh.cal describes no body", cur.i - 1)
    bodies = [_read_body(cur) for _ in range(n_bodies)]
    cur.header("load cases")
    freq, freq_line = cur.numbers("the frequency range", 3)
    if freq.size >= 4:
        version, n_freq = "v3", freq[1]
        f_range = (float(freq[2]), float(freq[3]), int(freq[0]) if freq[0] in (1, 2, 3) else 1)
    else:
        version, n_freq = "v2", freq[0]
        f_range = (float(freq[1]), float(freq[2]), 1)
    if n_freq != round(n_freq) or n_freq < 1:
        raise text.error(
            f"number of frequencies must be a positive whole number, found {n_freq:g}", freq_line
        )
    n_dir = cur.count("the number of wave directions")
    output_unit = None
    qtf = False
    if version == "v3":
        output_unit = _output_unit(cur)
        qtf = _qtf_flag(cur)
    return _NemohCal(
        path,
        float(rho),
        float(g),
        np.inf if depth == 0 else float(depth),
        bodies,
        version,
        int(n_freq),
        n_dir,
        output_unit,
        f_range,
        qtf,
    )


def _qtf_flag(cur: _Cursor) -> bool:
    """v3 QTF flag (first value line of the ``--- QTF`` section), False if absent."""
    for i in range(cur.i, len(cur.text.lines)):
        line = cur.text.lines[i].strip()
        if line.startswith("--") and "qtf" in line.lower():
            for j in range(i + 1, len(cur.text.lines)):
                content = cur.text.lines[j].split("!", 1)[0].strip()
                if content:
                    return content.split()[0] == "1"
            return False
    return False


def _output_unit(cur: _Cursor) -> int | None:
    """v3 "output freq type" (6th value line of the post-processing section)."""
    try:
        cur.header("post processing")
        for _ in range(5):
            cur.line()
        values, _ = cur.numbers("the output frequency type")
    except HydroDataError:
        return None
    unit = values[0]
    return int(unit) if unit in (1.0, 2.0, 3.0) else None


def _read_body(cur: _Cursor) -> _Body:
    cur.header("body")
    content, i = cur.line()
    tokens = content.split()
    if not tokens:
        raise cur.text.error("expected the name of the mesh file", i)
    name = re.split(r"[\\/]", tokens[0])[-1].rsplit(".", 1)[0] or "body"
    cur.numbers("the number of points and panels", 2)
    dofs = [_read_mode(cur) for _ in range(cur.count("the number of degrees of freedom", 1000))]
    forces = [_read_mode(cur) for _ in range(cur.count("the number of generalised forces", 1000))]
    n_extra = cur.count("the number of lines of additional information", 1000)
    if n_extra:
        raise cur.text.error(
            f"{n_extra} line(s) of additional information (generalised modes) are not supported",
            cur.i - 1,
            hint="cummins reads rigid-body DOFs only",
        )
    return _Body(name, dofs, forces)


def _read_mode(cur: _Cursor) -> _Mode:
    values, i = cur.numbers("a DOF line: type, direction (3), point (3)", 7)
    kind = values[0]
    if kind not in (0.0, 1.0, 2.0):
        raise cur.text.error(f"unknown DOF type {kind:g} (1 translation, 2 rotation)", i)
    return _Mode(int(kind), values[1:4], values[4:7], i)


def _mode_name(text: TextFile, mode: _Mode, position: int, count: int) -> str:
    """Surge … Yaw for a rigid-body DOF line of ``Nemoh.cal``."""
    d = mode.direction
    axis = int(np.argmax(np.abs(d)))
    unit = np.zeros(3)
    unit[axis] = 1.0
    if not np.allclose(d, unit, atol=1e-6):
        raise text.error(
            f"DOF direction {d.tolist()} is not along x, y or z",
            mode.line,
            hint="cummins reads rigid-body DOFs along the body axes only",
        )
    if mode.kind == 1:
        return DOF_NAMES[axis]
    if mode.kind == 2:
        return DOF_NAMES[3 + axis]
    if count == 6 and axis == position % 3:  # type 0 (inactive) in a full 6-DOF list
        return DOF_NAMES[position]
    raise text.error("cannot tell translation from rotation for a DOF of type 0", mode.line)


def _body_point(text: TextFile, body: _Body) -> np.ndarray:
    """The point about which the rotations and moments of a body are defined."""
    modes = [m for m in (*body.dofs, *body.forces) if m.kind == 2]
    if not modes:
        return np.zeros(3)
    point = modes[0].point
    for mode in modes[1:]:
        if not np.allclose(mode.point, point, atol=1e-9):
            raise text.error(
                f"rotations/moments about different points ({point.tolist()} and "
                f"{mode.point.tolist()})",
                mode.line,
                hint="cummins needs one reference point per body; rerun NEMOH with one point",
            )
    return point


# --------------------------------------------------------------------------- run layout


@dataclass
class _Run:
    folder: Path  # the run folder (where Nemoh.cal is), else the results folder
    results: Path
    radiation: Path
    cal: Path | None
    mesh_dirs: list[Path] = field(default_factory=list)


def _locate(path: Path) -> _Run:
    if not path.exists():
        raise HydroDataError("no such file or folder", path=path)
    if path.is_dir():
        found = sniff_dir(path)
        if not found:
            raise HydroDataError(
                f"no NEMOH results ({RADIATION_FILE}) in this folder or its results/ subfolder",
                path=path,
            )
        radiation = found[0]
    elif _is_nemoh_cal(_head(path)):
        found = sniff_dir(path.parent)
        if not found:
            raise HydroDataError(
                f"no {RADIATION_FILE} next to this Nemoh.cal or in results/", path=path
            )
        radiation = found[0]
    else:
        radiation = _find(path.parent, RADIATION_FILE)
        if radiation is None:
            raise HydroDataError(
                f"{RADIATION_FILE} not found next to this file",
                path=path,
                hint="cummins needs the added mass and damping of the run; keep the results "
                "folder together",
            )
    results = radiation.parent
    cal = _find(results, "Nemoh.cal") or _find(results.parent, "Nemoh.cal")
    run = cal.parent if cal is not None else results
    mesh_dirs = [d for d in (_subfolder(run, "mesh"), run, results) if d is not None]
    return _Run(run, results, radiation, cal, list(dict.fromkeys(mesh_dirs)))


# --------------------------------------------------------------------------- companion files

#: Magnitude beyond any floating body's coefficient (kg·m² of a 10⁹ kg hull 10³ m from
#: its reference point is 10¹⁵): larger numbers are sentinels (-9.99e99) or damage.
IMPLAUSIBLE = 1e20

#: Largest relative asymmetry |M - Mᵀ| / max|M| of the matrices NEMOH writes
#: (KH.dat, Inertia.dat: symmetric to the printed digits, 1e-7 in the corpus).
SYMMETRY_TOLERANCE = 1e-4

#: Largest relative difference between C33 of KH.dat and the run's own ρ g A_wp, the
#: ω → 0 limit of its Froude-Krylov heave force (≤ 0.2 % measured on the cylinder, the
#: COER float and the OSWEC flap; a factor 2 or 0.8 where the mesh files belong to
#: another mesh).
HYDROSTATIC_TOLERANCE = 0.05


def _read_matrix(path: Path) -> np.ndarray:
    """A square matrix written one row per line (``KH.dat``, ``Inertia.dat``, ``Km.dat``)."""
    text = TextFile.read(path)
    rows = []
    for i, line in enumerate(text.lines):
        if not line.strip():
            continue
        values = parse_numbers(line)
        if values is None or not np.all(np.isfinite(values)):
            raise text.error(f"expected a row of numbers, found {line.strip()[:60]!r}", i)
        if np.any(np.abs(values) > IMPLAUSIBLE):
            raise text.error(f"implausible value {values[np.abs(values) > IMPLAUSIBLE][0]:g}", i)
        if rows and values.size != rows[0].size:
            raise text.error(f"expected {rows[0].size} numbers on the row, found {values.size}", i)
        rows.append(values)
    matrix = np.vstack(rows)
    if matrix.shape[0] != matrix.shape[1] or matrix.shape[0] % 6:
        raise text.error(
            f"expected a 6N×6N matrix, found {matrix.shape[0]}×{matrix.shape[1]} (rows missing?)",
            len(text.lines) - 1,
        )
    scale = np.abs(matrix).max()
    asymmetry = np.abs(matrix - matrix.T).max()
    if asymmetry > SYMMETRY_TOLERANCE * scale:
        i, j = np.unravel_index(np.argmax(np.abs(matrix - matrix.T)), matrix.shape)
        raise text.error(
            f"the matrix is not symmetric: [{i + 1},{j + 1}] = {matrix[i, j]:g} but "
            f"[{j + 1},{i + 1}] = {matrix[j, i]:g} (rows swapped or edited?)",
            hint="NEMOH writes these matrices symmetric",
        )
    return matrix


_HYDROSTATICS_KEYS = {
    "XF": "xb",
    "YF": "yb",
    "ZF": "zb",
    "XG": "xg",
    "YG": "yg",
    "ZG": "zg",
    "DISPLACEMENT": "volume",
    "WATERPLANE AREA": "waterplane_area",
    "MASS": "mass",
}


def _read_hydrostatics(path: Path) -> dict[str, float]:
    """``Hydrostatics.dat``: ``XF = … - XG = …`` lines, displacement, (v3) mass."""
    text = TextFile.read(path)
    found: dict[str, float] = {}
    for i, line in enumerate(text.lines):
        pairs = re.findall(r"([A-Za-z][A-Za-z ]*?)\s*=\s*(\S*)", line)
        if not pairs and line.strip():
            raise text.error(f"expected 'NAME = value', found {line.strip()[:60]!r}", i)
        for name, value in pairs:
            key = _HYDROSTATICS_KEYS.get(name.strip().upper())
            if key is None:  # a quantity cummins does not use
                continue
            if key in found:
                raise text.error(f"{name.strip()} given twice", i)
            match = re.fullmatch(_NUMBER, value)
            number = float(value.replace("D", "E").replace("d", "e")) if match else np.nan
            if not np.isfinite(number) or abs(number) > IMPLAUSIBLE:
                raise text.error(f"{name.strip()} is not a number ({value[:20]!r})", i)
            found[key] = number
    missing = [k for k in ("XF", "YF", "ZF", "DISPLACEMENT") if _HYDROSTATICS_KEYS[k] not in found]
    if missing:
        raise text.error(
            f"no {', '.join(missing)} in the file (truncated, or not a Hydrostatics.dat)",
            len(text.lines) - 1,
        )
    return found


def _companion(run: _Run, names: list[str]) -> Path | None:
    for folder in run.mesh_dirs:
        for name in names:
            found = _find(folder, name)
            if found is not None:
                return found
    return None


def _body_files(run: _Run, stem: str, n_bodies: int, history: list[str]) -> list[Path] | None:
    """The files of ``stem`` per body, in body order, or None if absent.

    One body: ``KH.dat`` (or ``KH_0.dat``). Several: ``KH_0.dat`` … ``KH_<n-1>.dat``
    (WEC-Sim's convention, body k in the order of ``Nemoh.cal``), else one ``KH.dat``
    (NEMOH v3 writes one matrix of all bodies, or the mesher's file of the last mesh it
    processed; which one it is, its size tells, see :func:`_stiffness`).
    """
    single = _companion(run, [f"{stem}.dat"])
    if n_bodies == 1:
        found = single or _companion(run, [f"{stem}_0.dat"])
        return [found] if found is not None else None
    files = [_companion(run, [f"{stem}_{k}.dat"]) for k in range(n_bodies)]
    if all(f is not None for f in files):
        if single is not None:
            history.append(
                f"{', '.join(f.name for f in files)} used for bodies 1…{n_bodies} (in the "
                f"order of Nemoh.cal); {single.name} beside them (the NEMOH mesher's output "
                "for the last mesh it processed) not used"
            )
        return files  # type: ignore[return-value]
    return [single] if single is not None else None


# --------------------------------------------------------------------------- forces


@dataclass
class _Forces:
    path: Path
    omega: np.ndarray
    beta_deg: np.ndarray
    values: np.ndarray  # complex, (n_omega, n_beta, n_forces), exp(+iωt)
    degrees: bool


_BETA = re.compile(r"beta\s*=\s*(" + _NUMBER + ")", re.IGNORECASE)


def _read_forces(path: Path, cal_unit: int | None) -> _Forces:
    tec = _read_tecplot(path)
    omega, _ = _frequencies(tec, cal_unit)
    betas = []
    for zone in tec.zones:
        match = _BETA.search(zone.title)
        if match is None:
            raise tec.text.error(
                f"zone title {zone.title!r} does not give the wave direction (beta = …)", zone.line
            )
        betas.append(float(match.group(1)))
    beta = np.asarray(betas)
    if np.unique(beta).size != beta.size:
        raise tec.text.error("the same wave direction appears in two zones", tec.zones[-1].line)
    table = np.stack([zone.table[:, 1:] for zone in tec.zones], axis=1)  # (nω, nβ, 2nf)
    magnitude, phase = table[..., 0::2], table[..., 1::2]
    degrees = bool(np.abs(phase).max() > np.pi + 1e-3) if phase.size else False
    if degrees:
        phase = np.radians(phase)
    return _Forces(tec.path, omega, beta, magnitude * np.exp(-1j * phase), degrees)


# --------------------------------------------------------------------------- IRF.tec


def _irf_added_mass(
    path: Path, omega: np.ndarray, damping: np.ndarray, n_dofs: int, n_forces: int
) -> tuple[np.ndarray | None, str]:
    """NEMOH's A(∞) from ``IRF.tec`` (forces × DOFs), or None with the reason.

    The file is accepted only if its K(t) on the diagonal matches the cosine transform
    of ``damping`` (nω, forces, DOFs) computed with NEMOH's trapezoidal rule.
    """
    tec = _read_tecplot(path)
    if len(tec.zones) != n_dofs or tec.zones[0].table.shape[1] != 1 + 2 * n_forces:
        return None, (
            f"{path.name} has {len(tec.zones)} zones of "
            f"{(tec.zones[0].table.shape[1] - 1) // 2} forces, the run "
            f"{n_dofs} DOFs and {n_forces} forces: not from this run"
        )
    time = tec.zones[0].table[:, 0]
    order = np.argsort(omega)
    w, b = omega[order], damping[order]
    worst = 0.0
    diagonal = [np.abs(b[:, j, j]).max() for j in range(min(n_dofs, n_forces))]
    for j, size in enumerate(diagonal):
        if size <= 1e-6 * max(diagonal):  # no damping in this DOF (e.g. yaw of a cylinder)
            continue
        k_file = tec.zones[j].table[:, 2 + 2 * j]
        k_run = 2 / np.pi * np.trapezoid(b[:, j, j][:, None] * np.cos(np.outer(w, time)), w, axis=0)
        scale = np.abs(k_run).max()
        mismatch = min(np.abs(k_file - k_run).max(), np.abs(k_file + k_run).max()) / scale
        worst = max(worst, mismatch)
    if worst > IRF_TOLERANCE:
        return None, (
            f"{path.name} not used, so no added_mass_inf: its K(t) differs from "
            "(2/pi)∫B cos(wt)dw of "
            f"{RADIATION_FILE} by {worst:.3g} (relative; {IRF_TOLERANCE:g} allowed), "
            "so it belongs to another run"
        )
    a_inf = np.stack([zone.table[0, 1::2] for zone in tec.zones], axis=1)  # (forces, DOFs)
    return a_inf, (
        f"added_mass_inf from NEMOH's IRF.tec ('AddedMass' columns; its K(t) "
        f"matches the run's damping to {worst:.2g})"
    )


# --------------------------------------------------------------------------- reader


def _labels(
    text: TextFile | None, cal: _NemohCal | None, n_dofs: int, n_forces: int, notes: list[str]
):
    """Radiating and influenced DOF labels, the reference point(s) and the mesh names.

    Labels are positional (``body1__Surge`` … for several bodies, as every reader of
    cummins writes them); the mesh names go to the ``body_names`` attribute.
    """
    if cal is None or text is None:
        if n_dofs % 6 or n_forces != n_dofs:
            raise HydroDataError(
                f"{n_dofs} DOFs and {n_forces} forces without Nemoh.cal",
                hint="put the run's Nemoh.cal next to the results folder",
            )
        nb = n_dofs // 6
        labels = dof_labels(nb if nb > 1 else None)
        return labels, labels, np.zeros((nb, 3)), []
    nb = len(cal.bodies)
    radiating: list[str] = []
    influenced: list[str] = []
    points = []
    for k, body in enumerate(cal.bodies):
        prefix = f"body{k + 1}__" if nb > 1 else ""
        for modes, out, what in (
            (body.dofs, radiating, "degrees of freedom"),
            (body.forces, influenced, "generalised forces"),
        ):
            local = [_mode_name(text, m, p, len(modes)) for p, m in enumerate(modes)]
            if len(set(local)) != len(local):
                raise text.error(f"body {k + 1} ({body.name}) lists a DOF twice", modes[0].line)
            order = [DOF_NAMES.index(d) for d in local]
            if order != sorted(order):
                warn_damage(
                    f"the {what} of body {k + 1} ({body.name}) are listed as "
                    f"{', '.join(local)}, not in the order Surge…Yaw: read in the order given",
                    path=text.path,
                    line=modes[0].line + 1,
                    notes=notes,
                    hint="NEMOH's own files list them in order; check that Nemoh.cal was "
                    "not edited after the run",
                )
            out.extend(prefix + d for d in local)
        points.append(_body_point(text, body))
    return radiating, influenced, np.vstack(points), [b.name for b in cal.bodies]


def _frequency_note(run: _Run, cal: _NemohCal, omega: np.ndarray, unit: str) -> str:
    """History line when ``Nemoh.cal`` and the results disagree on the frequencies."""
    lo, hi, kind = cal.frequency_range
    cal_unit = {1: "rad/s", 2: "Hz", 3: "s"}.get(kind, "rad/s")
    note = (
        f"Nemoh.cal asks for {cal.n_frequencies} frequencies ({lo:g}-{hi:g} {cal_unit}) but "
        f"{RADIATION_FILE} holds {omega.size} ({omega.min():.4g}-{omega.max():.4g} rad/s): the "
        "results' frequencies are used (they are what the solver computed; Nemoh.cal was "
        "changed after the run"
    )
    index = _find(run.results, "index.dat")
    if index is not None:
        try:
            first = TextFile.read(index).numbers(0)
        except HydroDataError:
            first = None
        if first is not None and first.size and first[0] == omega.size:
            note += f"; {index.name}, which NEMOH's preprocessor wrote for the run, also lists "
            note += f"{omega.size}"
    return note + ")"


def read_nemoh(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
) -> xr.Dataset:
    """Read a NEMOH v2 or v3 run into a canonical ``HydroDB``.

    Parameters
    ----------
    path
        The results folder, the run folder (holding ``Nemoh.cal`` and ``results/``),
        ``Nemoh.cal``, or any of the result files (``RadiationCoefficients.tec``,
        ``ExcitationForce.tec``, ``DiffractionForce.tec``, ``FKForce.tec``, ``IRF.tec``).
    rho, g
        Water density (kg/m³) and gravity (m/s²). NEMOH's output is dimensional: they
        may only confirm the values of ``Nemoh.cal`` (a different value is an error).
        Without ``Nemoh.cal`` they are recorded as given (default 1025 kg/m³, 9.81 m/s²).

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB`` (SI units, exp(+iωt), z-up axes) about the rotation point
        of ``Nemoh.cal``: ``added_mass``, ``radiation_damping``, and when present
        ``excitation_force``, ``diffraction_force``, ``Froude_Krylov_force``,
        ``hydrostatic_stiffness``, ``inertia_matrix`` (``Mechanics/Inertia.dat``),
        ``additional_stiffness`` / ``additional_damping`` (``Mechanics/Km.dat``,
        ``Badd.dat``, when not zero), ``added_mass_inf`` (from a matching ``IRF.tec``).
        Several bodies are labelled ``body1__Surge`` …, the mesh names in the attribute
        ``body_names``.

    Raises
    ------
    HydroDataError
        Missing, damaged or mutually inconsistent files, naming the file and line.
    """
    run = _locate(Path(path))
    history = [f"read NEMOH results from {run.results}"]
    notes: list[str] = []
    cal = _read_cal(run.cal) if run.cal is not None else None
    cal_unit = cal.output_unit if cal is not None else None

    tec = _read_tecplot(run.radiation)
    omega, unit = _frequencies(tec, cal_unit)
    width = tec.zones[0].table.shape[1]
    if any(zone.table.shape[1] != width for zone in tec.zones):
        raise tec.text.error("zones have different numbers of columns")
    n_dofs, n_forces = len(tec.zones), (width - 1) // 2
    if cal is not None:
        history.append(
            f"constants, bodies and DOFs from {run.cal.name} (NEMOH {cal.version} layout)"
        )
        expected = (sum(len(b.dofs) for b in cal.bodies), sum(len(b.forces) for b in cal.bodies))
        if (n_dofs, n_forces) != expected:
            raise tec.text.error(
                f"{n_dofs} radiation zones of {n_forces} forces, but Nemoh.cal defines "
                f"{expected[0]} DOFs and {expected[1]} forces",
                hint="the results and Nemoh.cal come from different runs",
            )
        if omega.size != cal.n_frequencies:
            history.append(_frequency_note(run, cal, omega, unit))
    else:
        history.append(
            "no Nemoh.cal found: DOFs taken as Surge…Yaw about (0, 0, 0), "
            "water depth unknown (recorded as inf)"
        )
    if unit != "rad/s":
        history.append(f"frequency column of {run.radiation.name} in {unit}, converted to rad/s")
    qtf = _subfolder(run.results, "qtf")
    if qtf is not None or (cal is not None and cal.qtf):
        history.append(
            "second-order QTFs of the run (results/QTF) not read: cummins reads the "
            "first-order coefficients"
        )
    cal_text = TextFile.read(run.cal) if cal is not None else None
    dofs, force_labels, points, body_names = _labels(cal_text, cal, n_dofs, n_forces, notes)
    missing = [d for d in dofs if d not in force_labels]
    if missing:
        raise HydroDataError(
            f"DOF {missing[0]} has no matching generalised force in Nemoh.cal",
            path=run.cal,
            hint="cummins needs square added-mass matrices",
        )
    pick = np.array([force_labels.index(d) for d in dofs])
    if len(pick) < len(force_labels):
        history.append(
            "forces without a matching DOF dropped: "
            + ", ".join(f for f in force_labels if f not in dofs)
        )

    table = np.stack([zone.table for zone in tec.zones], axis=2)  # (nω, width, DOFs)
    added_mass = table[:, 1::2, :][:, pick, :]
    damping = table[:, 2::2, :][:, pick, :]

    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        cal.rho if cal else None,
        cal.g if cal else None,
        path=run.cal or run.radiation,
        history=history,
        dimensional=True,
    )
    depth = cal.depth if cal is not None else np.inf

    extra: dict = {}
    forces = {kind: _find(run.results, name) for kind, name in _FORCE_FILES.items()}
    read = {kind: _read_forces(p, cal_unit) for kind, p in forces.items() if p is not None}
    if read:
        extra.update(_force_arrays(read, omega, pick, n_forces, cal, history))
        history.append(
            "NEMOH's exp(-iwt) complex amplitudes conjugated to exp(+iwt) (F = |F| exp(-i phase))"
        )

    irf = _find(run.results, _IRF_FILE)
    if irf is not None:
        try:
            a_inf, note = _irf_added_mass(irf, omega, table[:, 2::2, :], n_dofs, n_forces)
        except HydroDataError as exc:  # optional file: the rest of the run is still good
            a_inf, note = None, f"{irf.name} not used, so no added_mass_inf: unreadable ({exc})"
        history.append(note)
        if a_inf is None:
            warn_damage(note, path=irf, notes=notes)
        else:
            extra["added_mass_inf"] = a_inf[pick, :]

    bodies = _BodyInfo(dofs, points, body_names)
    extra.update(_hydrostatics(run, bodies, omega, extra, (rho_v, g_v, depth), history, notes))
    n_bodies = points.shape[0]
    reference = points.reshape(-1) if n_bodies > 1 else points[0]
    return make_hydrodb(
        omega,
        added_mass,
        damping,
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format="nemoh",
        source_file=str(run.radiation),
        dofs=dofs,
        reference_point=reference,
        history=history,
        read_warnings=notes,
        nemoh_version=cal.version if cal is not None else None,
        body_name=body_names[0] if len(body_names) == 1 else None,
        body_names="\n".join(body_names) if n_bodies > 1 and body_names else None,
        **extra,
    )


def _force_arrays(read: dict[str, _Forces], omega, pick, n_forces, cal, history) -> dict:
    """Excitation, diffraction and Froude-Krylov arrays, checked against each other."""
    out: dict = {}
    reference = next(iter(read.values()))
    for kind, forces in read.items():
        name = forces.path.name
        if forces.values.shape[2] != n_forces:
            raise HydroDataError(
                f"{forces.values.shape[2]} forces per row, {RADIATION_FILE} has {n_forces}",
                path=forces.path,
            )
        if forces.omega.shape != omega.shape or not np.allclose(forces.omega, omega, rtol=1e-5):
            raise HydroDataError(
                f"other frequencies than {RADIATION_FILE}",
                path=forces.path,
                hint="the files come from different runs",
            )
        if forces.beta_deg.shape != reference.beta_deg.shape or not np.allclose(
            forces.beta_deg, reference.beta_deg, atol=1e-6
        ):
            raise HydroDataError(
                f"other wave directions than {reference.path.name}", path=forces.path
            )
        history.append(
            f"{kind.replace('_', '-')} force from {name} (phases in "
            f"{'degrees' if forces.degrees else 'radians'})"
        )
        out[kind] = forces.values[:, :, pick]
    if cal is not None and reference.beta_deg.size != cal.n_directions:
        history.append(
            f"Nemoh.cal asks for {cal.n_directions} wave directions, {reference.path.name} "
            f"holds {reference.beta_deg.size}: the results' directions are used"
        )
    result = {"wave_direction": np.radians(reference.beta_deg)}
    if "excitation" in out:
        result["excitation_force"] = out["excitation"]
    elif "diffraction" in out and "froude_krylov" in out:
        result["excitation_force"] = out["diffraction"] + out["froude_krylov"]
        history.append("excitation force = diffraction + Froude-Krylov")
    if "diffraction" in out:
        result["diffraction_force"] = out["diffraction"]
    if "froude_krylov" in out:
        result["froude_krylov_force"] = out["froude_krylov"]
    return result


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
    _inertia(out, mechanics, values, run, bodies, rho, history)
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


def _inertia(out: dict, mechanics: dict, values: list[dict], run, bodies, rho, history) -> None:
    """``inertia_matrix`` from ``Mechanics/Inertia.dat``, or the reason there is none."""
    if "inertia" in mechanics:
        m = mechanics["inertia"]
        if np.any(np.diag(m) < 0) or not np.all(np.diag(m)[[0, 1, 2]] > 0):
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
