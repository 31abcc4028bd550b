"""WAMIT output: numeric files ``.1`` ``.3`` ``.4`` ``.hst`` (with ``.frc``, ``.mmx``,
``.cfg``, ``.pot``) and the ``.out`` log; also the "Wamit_format" files HAMS writes
(read through :mod:`cummins.io.hams`).

WAMIT writes nondimensional numbers (WAMIT User Manual v7, §4.1). With L the length
scale ULEN, ρ the density and g gravity, and k = 0 for translations and generalized
modes, 1 for rotations:

* added mass       A = Ā ρ L^(3+k_i+k_j)          (``.1``)
* damping          B = B̄ ρ ω L^(3+k_i+k_j)        (``.1``)
* excitation       X = X̄ ρ g L^(2+k_i)            (``.3``, per metre of wave amplitude)
* hydrostatics     C = C̄ ρ g L^(2+k_i+k_j)        (``.hst``)
* motion RAO       ξ = ξ̄ / L^k_i                  (``.4`` and ``.out``)
* mean drift       F = F̄ ρ g L^(1+k_i)            (``.out``, per squared amplitude)

Generalized modes (mode 7, 8 … of a body, WAMIT User Manual v7 ch. 8) are normalized
like the translational modes (k = 0): their amplitude is a length. The corpus holds no
generalized-mode run with ULEN ≠ 1, so that exponent could not be checked on data.

The limit rows of the numeric files: in a period column, −1 is T = ∞ (ω = 0) and 0 is
T = 0 (ω = ∞); in a frequency or wavenumber column (HAMS), 0 is ω = 0 and −1 is ω = ∞.

Time dependence is Re{X e^{iωt}}, as in cummins. Wave heading β is the direction of
propagation from +x (0 = following seas), as in cummins. Axes are x forward, y to port,
z up; moments are about the body origin (XBODY, YBODY, ZBODY), which cummins records
as the ``reference_point`` in global coordinates (origin on the mean free surface).

Mass properties (→ ``inertia_matrix``, about the body origin, body axes):

* ``.frc`` alternative form 2: the IMASS matrix as given (n×n, dimensional);
* ``.frc`` alternative form 1, or the ``.out`` header, which prints what WAMIT used:
  mass m = ρ∇ (a freely floating body; ∇ the mean of VOLX, VOLY, VOLZ, as WAMIT's
  ``.mmx`` shows), centre of gravity (x_g, y_g from the centre of buoyancy, z_g = VCG),
  and the radii of gyration r_ij about the body-origin axes: I_ij = m r_ij |r_ij|
  (WAMIT User Manual v7, §4.3 and §3.4). Radii of gyration all zero are WAMIT's
  placeholder (no rotational inertia given): no inertia matrix is built from them.

WAMIT does not write the water density in its numeric files (version 7 not even in
the ``.out``): ρ comes from the ``.out`` (version 6), else from the ``.frc``, else
from ``rho=``, else 1025 kg/m³, and the dataset's ``history`` says which.
"""

from __future__ import annotations

import os
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import dof_labels, make_hydrodb
from cummins.io._common import (
    force_exponents,
    length_exponents,
    resolve_constant,
    resolve_rho_g,
    rotation_flags,
    warn_damage,
)
from cummins.io._text import (
    TextFile,
    check_cut_numbers,
    check_line_ends,
    numeric_table,
    parse_numbers,
)
from cummins.kinematics import skew

__all__ = ["read_wamit", "read_wamit_out", "sniff", "sniff_dir"]

#: Largest magnitude a WAMIT number can plausibly have; beyond it a value is a
#: missing-value marker (−9.99E99) or damage.
MAX_ABS_VALUE = 1e30
#: Memory the arrays of one run may take before the reader refuses (bytes).
MEMORY_LIMIT = 4 * 2**30
#: First-column kinds of the numeric files.
FIRST_COLUMNS = ("period", "omega", "wavenumber", "wavenumber_deep", "wavelength")


# --------------------------------------------------------------------------- text


def _read_text(path: Path) -> TextFile:
    """:meth:`TextFile.read` without a UTF-8 byte-order mark (not damage)."""
    text = TextFile.read(path)
    if text.lines and text.lines[0].startswith("\ufeff"):
        return TextFile(text.path, (text.lines[0][1:], *text.lines[1:]))
    return text


def _head_lines(path: Path, nbytes: int = 65536) -> list[str]:
    with open(path, "rb") as f:
        raw = f.read(nbytes)
    text = raw.decode("utf-8", errors="replace").lstrip("\ufeff")
    return text.splitlines()


def _title_lines(text: TextFile) -> int:
    """1 when the first line is a title (text, not a row of numbers), else 0.

    A row whose numbers were damaged still has most of its numbers: it is data, and
    the table parser then names its line.
    """
    if not text.lines:
        return 0
    first = text.lines[0]
    if parse_numbers(first) is not None:
        return 0
    tokens = first.split()
    numeric = sum(parse_numbers(t) is not None for t in tokens)
    return 1 if numeric < 3 or "WAMIT" in first else 0


def _numeric_rows(text: TextFile, start: int, columns, value_columns: Sequence[int]):
    """:func:`numeric_table` plus the damage checks of fixed-format Fortran output.

    Rows whose number in a value column is shorter than the others of that column
    (a cut line), and magnitudes beyond :data:`MAX_ABS_VALUE`, are errors naming the
    line.
    """
    table, where = numeric_table(text, start, columns=columns)
    check_cut_numbers(text, where, value_columns)
    values = table[:, list(value_columns)]
    big = np.abs(np.nan_to_num(values, nan=0.0)) >= MAX_ABS_VALUE
    if big.any():
        r = int(np.argmax(big.any(axis=1)))
        raise text.error(
            f"implausible value {values[r][big[r]][0]:g} (a missing-value marker?)",
            where[r],
            hint="the solver did not compute this entry, or the file is damaged",
        )
    return table, where


# --------------------------------------------------------------------------- detection


def numeric_kind(path: str | os.PathLike[str]) -> str | None:
    """Which WAMIT numeric file ``path`` is by its content: ``".1"``, ``".3"``, ``".hst"``.

    ``.1`` rows are ``PER I J A [B]``, ``.3`` (and ``.4``) rows ``PER BETA I Mod Pha Re
    Im`` and ``.hst`` rows ``I J C``; the integer columns must hold DOF indices. A first
    line of text (a title) is allowed.
    """
    try:
        head = _head_lines(Path(path))[:6]
    except OSError:
        return None
    if not head:
        return None
    first = head[0]
    lines = head[1:] if parse_numbers(first) is None else head
    lines = lines[:4]
    rows = [parse_numbers(line) for line in lines if line.strip()]
    if not rows or any(r is None for r in rows):
        return None

    def is_dof(x: float) -> bool:
        return float(x).is_integer() and 1 <= x <= 600

    widths = {r.size for r in rows}
    if widths <= {4, 5} and all(is_dof(r[1]) and is_dof(r[2]) for r in rows):
        return ".1"
    if widths == {7} and all(is_dof(r[2]) for r in rows):
        return ".3"
    if widths == {3} and all(is_dof(r[0]) and is_dof(r[1]) for r in rows):
        return ".hst"
    return None


def is_out_file(path: str | os.PathLike[str]) -> bool:
    """True if ``path`` is a WAMIT ``.out`` log (by its banner)."""
    try:
        with open(path, "rb") as f:
            head = f.read(4096).decode("utf-8", errors="replace")
    except OSError:
        return False
    return "WAMIT" in head and ("Version" in head or "POTEN" in head or "Output from" in head)


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` a WAMIT numeric file (``.1``, ``.3``, ``.hst``)?"""
    return numeric_kind(path) is not None


def _runs_in(folder: Path) -> list[Path]:
    ones = sorted(p for p in folder.glob("*.1") if numeric_kind(p) == ".1")
    if ones:
        return ones
    return sorted(p for p in folder.glob("*.out") if is_out_file(p))


def sniff_dir(path: Path) -> list[Path]:
    """The WAMIT runs in a directory: one ``.1`` file per run (else ``.out`` files).

    A folder without a run of its own is searched one level down (a run kept in
    ``outputFiles/`` beside ``inputFiles/``). HAMS project folders are left to
    :mod:`cummins.io.hams`.
    """
    found = _runs_in(path)
    if found or (path / "Input" / "ControlFile.in").is_file():
        return found
    return [run for sub in sorted(p for p in path.iterdir() if p.is_dir()) for run in _runs_in(sub)]


# --------------------------------------------------------------------------- .out header

_FLOAT = r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?)"
_GEOMETRY_FILE = re.compile(r"(?:Input from Geometric Data File:|N=\s*\d+)\s+(\S+\.(?:gdf|GDF))")
_LISTING_ROW = re.compile(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?\s+\d\d?:\d\d:\d\d")
_NUMBER_TOKEN = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?")


@dataclass
class _OutBody:
    """Parameters of one body printed in a ``.out`` header (body coordinates)."""

    origin: np.ndarray
    line: int
    volumes: np.ndarray | None = None
    center_of_buoyancy: np.ndarray | None = None
    center_of_gravity: np.ndarray | None = None
    radii_of_gyration: np.ndarray | None = None
    hydrostatics: dict[tuple[int, int], float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)


@dataclass
class _OutHeader:
    """Constants and body parameters printed in a ``.out`` header."""

    g: float | None = None
    ulen: float | None = None
    rho: float | None = None
    water_depth: float | None = None
    bodies: list[_OutBody] = field(default_factory=list)
    body_names: list[str] = field(default_factory=list)
    extra_modes: bool = False
    announced_blocks: int | None = None
    irregular_frequency_removal: bool | None = None
    has_gravity_line: bool = False


def _out_header(text: TextFile, notes: list[str] | None = None) -> _OutHeader:
    h = _OutHeader()
    stop = text.find(r"Output from\s+WAMIT")
    stop = len(text) if stop < 0 else stop
    listing = -1
    for i in range(stop):
        line = text.lines[i]
        if m := re.search(r"Gravity:\s*" + _FLOAT, line):
            h.g = float(m.group(1))
            h.has_gravity_line = True
        if m := re.search(r"Length scale:\s*" + _FLOAT, line):
            h.ulen = float(m.group(1))
        if m := re.search(r"Water depth:\s*(infinite|" + _FLOAT[1:-1] + ")", line):
            h.water_depth = np.inf if m.group(1) == "infinite" else float(m.group(1))
        if m := re.search(r"Water density:\s*" + _FLOAT, line):
            h.rho = float(m.group(1))
        if m := re.search(r"IRR\s*=\s*(\d+)", line):
            h.irregular_frequency_removal = int(m.group(1)) > 0
        if "Extra Mode" in line or "NEWMDS" in line or "generalized mode" in line.lower():
            h.extra_modes = True
        if m := _GEOMETRY_FILE.search(line):
            h.body_names.append(Path(m.group(1)).stem)
        if re.match(r"\s*(Period|Wavenum\w*|Frequency|Freq\w*)\b.*\bTime\b.*\bRAD\b", line):
            listing = i
        if "XBODY" in line:
            vals = re.findall(r"[XYZ]BODY\s*=\s*" + _FLOAT, line)
            if len(vals) != 3:
                raise text.error("expected XBODY, YBODY and ZBODY on this line", i)
            h.bodies.append(_OutBody(np.array([float(v) for v in vals]), i))
            continue
        body = h.bodies[-1] if h.bodies else None
        if body is None:
            continue
        if line.strip().startswith("Volumes"):
            body.volumes = _numbers_after_colon(text, i, 3)
        elif "Center of Buoyancy" in line:
            body.center_of_buoyancy = _numbers_after_colon(text, i, 3)
        elif "Center of Gravity" in line:
            body.center_of_gravity = _center_of_gravity(text, i, body)
        elif "Radii of gyration" in line:
            rows = [_numbers_after_colon(text, i, 3)]
            for k in (1, 2):
                row = parse_numbers(text.lines[i + k]) if i + k < stop else None
                if row is None or row.size != 3:
                    raise text.error("expected three radii of gyration on this line", i + k)
                rows.append(row)
            body.radii_of_gyration = np.vstack(rows)
        elif "Hydrostatic and gravitational restoring" in line:
            body.hydrostatics = _out_hydrostatics(text, i + 1)
    if listing >= 0:
        count = 0
        for k in range(listing + 1, stop):
            if not _LISTING_ROW.match(text.lines[k]):
                break
            count += 1
        h.announced_blocks = count
    return h


def _numbers_after_colon(text: TextFile, i: int, count: int) -> np.ndarray:
    line = text.lines[i]
    nums = parse_numbers(line.split(":", 1)[1]) if ":" in line else None
    if nums is None or nums.size != count:
        raise text.error(f"expected {count} numbers after the colon", i)
    if not np.all(np.isfinite(nums)) or np.any(np.abs(nums) >= MAX_ABS_VALUE):
        raise text.error("non-finite or implausible value", i)
    return nums


def _center_of_gravity(text: TextFile, i: int, body: _OutBody) -> np.ndarray | None:
    """Xg, Yg, Zg; blank fixed-width fields are placed by the columns of the CB line.

    WAMIT prints the three in fixed-width fields; a run seen in the wild printed only
    Zg (Xg, Yg blank). A blank Xg or Yg is taken from the centre of buoyancy above it
    (a freely floating body's CG is on the vertical through its CB); a blank Zg leaves
    the CG unknown.
    """
    line = text.lines[i]
    colon = line.find(":")
    found = [
        (m.end(), float(m.group().replace("D", "E").replace("d", "e")))
        for m in _NUMBER_TOKEN.finditer(line, colon + 1)
    ]
    rest = re.sub(_NUMBER_TOKEN, "", line[colon + 1 :])
    if colon < 0 or rest.strip():
        raise text.error("expected the coordinates of the centre of gravity after the colon", i)
    if len(found) == 3:
        return np.array([v for _, v in found])
    ends = _field_ends(text, i)
    if ends is None or not found:
        raise text.error("expected three coordinates (Xg, Yg, Zg) after the colon", i)
    values: list[float | None] = [None, None, None]
    for end, value in found:
        k = int(np.argmin([abs(end - e) for e in ends]))
        if abs(end - ends[k]) > 2 or values[k] is not None:
            raise text.error("cannot tell which of Xg, Yg, Zg this number is", i)
        values[k] = value
    if values[2] is None:
        raise text.error("the line ends before Zg (a cut line?)", i, hint="the .out is damaged")
    cb = body.center_of_buoyancy
    for k, name in ((0, "Xg"), (1, "Yg")):
        if values[k] is None:
            if cb is None:
                body.notes.append(f"the .out leaves {name} blank and prints no CB: {name} = 0")
                values[k] = 0.0
            else:
                values[k] = float(cb[k])
                body.notes.append(
                    f"the .out leaves {name} blank: {name} = {cb[k]:g} m from the centre of "
                    "buoyancy (a floating body's CG is on the vertical through its CB)"
                )
    return np.array(values, dtype=float)


def _field_ends(text: TextFile, i: int) -> list[int] | None:
    """Column ends of the three fixed-width numbers on the CB line above line ``i``."""
    for k in range(i - 1, max(i - 8, -1), -1):
        line = text.lines[k]
        if "Center of Buoyancy" in line:
            colon = line.find(":")
            ends = [m.end() for m in _NUMBER_TOKEN.finditer(line, colon + 1)]
            return ends if len(ends) == 3 else None
    return None


def _out_hydrostatics(text: TextFile, i: int) -> dict[tuple[int, int], float]:
    """The three ``C(3,3),C(3,4),C(3,5): …`` lines of a ``.out`` header."""
    entries: dict[tuple[int, int], float] = {}
    for k in range(i, min(i + 3, len(text))):
        line = text.lines[k]
        if ":" not in line:
            raise text.error("expected the hydrostatic coefficients C(i,j): …", k)
        names, values = line.split(":", 1)
        pairs = re.findall(r"C\((\d),(\d)\)", names)
        nums = parse_numbers(values)
        if nums is None or not pairs or len(pairs) != nums.size:
            raise text.error("unreadable hydrostatic coefficients", k)
        if not np.all(np.isfinite(nums)) or np.any(np.abs(nums) >= MAX_ABS_VALUE):
            raise text.error("non-finite or implausible hydrostatic coefficient", k)
        for (a, b), v in zip(pairs, nums, strict=True):
            entries[(int(a), int(b))] = float(v)
    if len(entries) != 8:
        raise text.error("expected the 8 hydrostatic coefficients C(3,3) … C(5,6)", i)
    return entries


def _hydrostatics_from_out(entries: dict[tuple[int, int], float], n: int = 6) -> np.ndarray:
    """n×n nondimensional C from the upper-triangle entries printed in the ``.out``.

    C34, C35 and C45 are symmetric (pure hydrostatics); C46 and C56 are the
    gravitational moments WAMIT adds, which have no symmetric counterpart (as in the
    ``.hst`` file).
    """
    c = np.zeros((n, n))
    for (i, j), v in entries.items():
        c[i - 1, j - 1] = v
        if (i, j) in {(3, 4), (3, 5), (4, 5)}:
            c[j - 1, i - 1] = v
    return c


# --------------------------------------------------------------------------- input files


def _leading_numbers(line: str) -> list[float]:
    """The numbers at the start of a line of an input file (comments may follow)."""
    out: list[float] = []
    for token in line.split():
        value = parse_numbers(token)
        if value is None or value.size != 1:
            break
        out.append(float(value[0]))
    return out


@dataclass
class _Config:
    """What cummins uses from a ``.cfg`` file."""

    new_modes: dict[int, int] = field(default_factory=dict)  # body number → NEWMDS
    ialtfrc: int | None = None
    first_column: str | None = None


_IPEROUT = {1: "period", 2: "omega", 3: "wavenumber_deep", 4: "wavenumber"}


def _read_cfg(path: Path) -> _Config:
    text = _read_text(path)
    cfg = _Config()
    for i, raw in enumerate(text.lines):
        line = raw.split("!", 1)[0].strip()
        if "=" not in line:
            continue
        key, _, value = line.partition("=")
        key = key.strip().upper()
        numbers = _leading_numbers(value)
        if not numbers:
            continue
        if m := re.fullmatch(r"NEWMDS(?:\((\d+)\))?", key):
            count = numbers[0]
            if count != int(count) or not 0 <= count <= 500:
                raise text.error(f"NEWMDS = {count:g} is not a mode count", i)
            cfg.new_modes[int(m.group(1) or 1)] = int(count)
        elif key == "IALTFRC":
            cfg.ialtfrc = int(numbers[0])
        elif key in ("IPEROUT", "IPERIO") and int(numbers[0]) in _IPEROUT:
            cfg.first_column = _IPEROUT[int(numbers[0])]
    return cfg


def _read_pot_bodies(path: Path) -> list[str] | None:
    """Body (geometry file) names listed in a ``.pot`` file, or ``None``."""
    text = _read_text(path)
    for i, line in enumerate(text.lines):
        numbers = _leading_numbers(line)
        if "NBODY" in line.upper() and len(numbers) == 1:
            count = int(numbers[0])
            names = []
            k = i + 1
            while len(names) < count and k < len(text):
                token = text.lines[k].split()
                if token and re.search(r"\.(gdf|GDF)$", token[0]):
                    names.append(Path(token[0]).stem)
                k += 1
            return names if len(names) == count else None
    return None


@dataclass
class _Mmx:
    """What cummins uses from a ``.mmx`` file (WAMIT's echo of the mass matrices)."""

    n_bodies: int | None = None
    normalized_mass: np.ndarray | None = None  # MASS/RHO, form 1
    external: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None  # MASS, DAMP, STIF


def _read_mmx(path: Path) -> _Mmx:
    text = _read_text(path)
    out = _Mmx()
    k = text.find(r"NBODY\s*=")
    if k >= 0:
        m = re.search(r"NBODY\s*=\s*(\d+)", text.lines[k])
        out.n_bodies = int(m.group(1)) if m else None
    for title, width in (("Normalized mass matrix", 3), ("External force matrices", 5)):
        i = text.find(re.escape(title))
        if i < 0:
            continue
        start = i + 1
        while start < len(text) and parse_numbers(text.lines[start]) is None:
            start += 1
        stop = start
        while stop < len(text):
            row = parse_numbers(text.lines[stop])
            if row is None or row.size != width:
                break
            stop += 1
        table, where = _numeric_rows(text, start, columns=width, value_columns=range(2, width))
        ij = table[:, :2]
        n = int(ij.max())
        if n > 600 or np.any(ij < 1) or np.any(ij != np.round(ij)):
            raise text.error("DOF index out of range", int(where[0]))
        if table.shape[0] != n * n:
            raise text.error(f"{table.shape[0]} entries, not {n}×{n} (truncated?)", stop - 1)
        mats = [np.zeros((n, n)) for _ in range(width - 2)]
        for c, mat in enumerate(mats):
            mat[ij[:, 0].astype(int) - 1, ij[:, 1].astype(int) - 1] = table[:, 2 + c]
        if width == 3:
            out.normalized_mass = mats[0]
        else:
            out.external = (mats[0], mats[1], mats[2])
    return out


@dataclass
class _ForceControl:
    """What cummins uses from a ``.frc`` file (alternative form 1 or 2)."""

    form: int | None = None
    rho: float | None = None
    vcg: list[float] = field(default_factory=list)  # form 1, per body
    radii_of_gyration: list[np.ndarray] = field(default_factory=list)  # form 1, per body
    center_of_gravity: np.ndarray | None = None  # form 2
    mass: np.ndarray | None = None
    damping: np.ndarray | None = None
    stiffness: np.ndarray | None = None


def _read_frc(path: Path, n: int, n_bodies: int, ialtfrc: int | None) -> _ForceControl:
    """Read a ``.frc`` file: alternative form 1 (VCG, radii of gyration XPRDCT per body)
    or form 2 (RHO, XCG, then the IMASS, IDAMP, ISTIF flags each followed by an n×n
    matrix when 1), WAMIT User Manual v7 §4.3–4.4. Damage raises HydroDataError.
    """
    text = _read_text(path)
    rows = [(i, _leading_numbers(line)) for i, line in enumerate(text.lines) if line.strip()]
    rows = rows[1:]  # the title
    if len(rows) < 5:
        raise text.error("too few lines for a .frc file (truncated?)", len(text) - 1)
    (i_opt, ioptn), body = rows[0], rows[1:]
    if len(ioptn) < 1:
        raise text.error("expected the IOPTN option flags", i_opt)
    form = ialtfrc
    if form is None:
        sizes = [len(v) for _, v in body[:3]]
        if sizes[:2] == [1, 3] and sizes[2] == 3:
            form = 1
        elif sizes[:3] == [1, 3, 1]:
            form = 2
        else:
            raise text.error(
                "neither alternative form 1 (VCG, XPRDCT) nor form 2 (RHO, XCG, IMASS …)",
                body[0][0],
            )
    out = _ForceControl(form=form)

    def need(k: int, count: int) -> list[float]:
        if k >= len(body):
            raise text.error("the file ends too early (truncated?)", len(text) - 1)
        i, values = body[k]
        if len(values) != count:
            raise text.error(f"expected {count} numbers, found {len(values)}", i)
        if not np.all(np.isfinite(values)) or np.any(np.abs(values) >= MAX_ABS_VALUE):
            raise text.error("non-finite or implausible value", i)
        return values

    if form == 1:
        k = 0
        for _ in range(n_bodies):
            out.vcg.append(need(k, 1)[0])
            out.radii_of_gyration.append(np.array([need(k + r, 3) for r in (1, 2, 3)]))
            k += 4
        return out
    if form != 2:
        raise text.error(f"alternative form {form} of the .frc is not read", i_opt)
    out.rho = need(0, 1)[0]
    if not out.rho > 0:
        raise text.error(f"RHO = {out.rho:g} is not a density", body[0][0])
    out.center_of_gravity = np.array(need(1, 3))
    k = 2
    matrices = []
    for name in ("IMASS", "IDAMP", "ISTIF"):
        flag = need(k, 1)[0]
        k += 1
        if flag == 1:
            matrices.append(np.array([need(k + r, n) for r in range(n)]))
            k += n
        elif flag == 0:
            matrices.append(None)
        else:
            raise text.error(f"{name} = {flag:g}: only 0 and 1 are read", body[k - 1][0])
    out.mass, out.damping, out.stiffness = matrices
    return out


def _sibling(path: Path, suffix: str) -> Path | None:
    for candidate in (path.with_suffix(suffix), path.with_suffix(suffix.upper())):
        if candidate.is_file():
            return candidate
    return None


# --------------------------------------------------------------------------- modes, inertia


def _mode_layout(
    n_seen: int,
    *,
    n_bodies: int | None,
    new_modes: dict[int, int],
    extra_modes: bool | None,
    modes: int | Sequence[int] | None,
    path: Path,
    history: list[str],
) -> list[int]:
    """Modes per body, from the files (never from n % 6).

    ``n_seen`` is the largest DOF index in the data; ``n_bodies`` the body count the
    ``.out``/``.pot``/``.mmx`` give; ``new_modes`` the ``.cfg`` NEWMDS per body;
    ``extra_modes`` whether the ``.out`` announces generalized modes (``None``: no
    ``.out``).
    """
    if modes is not None:
        layout = [int(modes)] if isinstance(modes, int | np.integer) else [int(m) for m in modes]
        if any(m < 1 for m in layout) or sum(layout) < n_seen:
            raise HydroDataError(
                f"modes={layout} does not hold the DOF indices 1…{n_seen} of the file",
                path=path,
            )
        history.append(f"modes per body: {layout} (given)")
        return layout
    if n_bodies is not None and n_bodies < 1:
        raise HydroDataError("the files announce no body", path=path)
    if new_modes and n_bodies is not None:
        layout = [6 + new_modes.get(k + 1, 0) for k in range(n_bodies)]
        if sum(layout) < n_seen:
            raise HydroDataError(
                f"DOF index {n_seen} in the data, but the .cfg announces {sum(layout)} modes "
                f"({layout} per body)",
                path=path,
                hint="the files come from different runs, or one is damaged",
            )
        history.append(f"modes per body: {layout} (bodies from the files, NEWMDS from the .cfg)")
        return layout
    if n_bodies == 1:
        if n_seen > 6 and extra_modes is False:
            raise HydroDataError(
                f"DOF index {n_seen} in the data, but the .out announces one body and no "
                "generalized modes",
                path=path,
                hint="the file is damaged, or pass modes= to say how many modes the body has",
            )
        layout = [max(n_seen, 6)]
        if n_seen > 6:
            history.append(f"one body with {n_seen - 6} generalized modes (Mode7 …)")
        return layout
    if n_bodies is not None:
        if n_seen > 6 * n_bodies:
            raise HydroDataError(
                f"DOF index {n_seen} in the data, more than the 6 modes of each of the "
                f"{n_bodies} bodies the files announce",
                path=path,
                hint="keep the run's .cfg (NEWMDS) beside it, or pass modes=[…] per body",
            )
        return [6] * n_bodies
    if n_seen <= 6:
        return [6]
    raise HydroDataError(
        f"DOF indices go up to {n_seen}, and no file of the run says how many bodies there are",
        path=path,
        hint=f"keep the run's .out (or .pot, .mmx, .cfg) beside it, or pass modes=: e.g. "
        f"modes=[6, 6] for two bodies, modes={n_seen} for one body with generalized modes",
    )


def _check_memory(n: int, n_omega: int, n_beta: int, path: Path) -> None:
    need = 8 * n * n * n_omega * 4 + 16 * n * n_beta * n_omega * 4
    if need > MEMORY_LIMIT:
        raise HydroDataError(
            f"{n} DOFs × {n_omega} frequencies would need {need / 2**30:.1f} GiB",
            path=path,
            hint="the DOF count comes from the file's indices: is the file damaged?",
        )


def _rigid_inertia(mass: float, cg: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """6×6 inertia about the body origin: I_ij = m r_ij |r_ij| (WAMIT v7 §4.3)."""
    s = skew(np.asarray(cg, dtype=float))
    out = np.zeros((6, 6))
    out[:3, :3] = mass * np.eye(3)
    out[:3, 3:] = -mass * s
    out[3:, :3] = mass * s
    out[3:, 3:] = mass * radii * np.abs(radii)
    return out


def _inertia_from_mass_properties(
    modes: list[int],
    rho: float,
    bodies: list[_OutBody],
    frc: _ForceControl | None,
    frc_name: str,
    out_name: str,
    history: list[str],
) -> np.ndarray | None:
    """Block-diagonal inertia from m = ρ∇, CG and radii of gyration of each body."""
    blocks = []
    for k, m_k in enumerate(modes):
        label = f"body {k + 1}: " if len(modes) > 1 else ""
        body = bodies[k] if k < len(bodies) else None
        volume = None if body is None or body.volumes is None else float(np.mean(body.volumes))
        radii, cg, source = None, None, None
        if body is not None and body.radii_of_gyration is not None:
            radii, cg, source = body.radii_of_gyration, body.center_of_gravity, out_name
        elif frc is not None and frc.form == 1 and k < len(frc.radii_of_gyration):
            radii, source = frc.radii_of_gyration[k], frc_name
            cb = body.center_of_buoyancy if body is not None else None
            cg = None if cb is None else np.array([cb[0], cb[1], frc.vcg[k]])
        if radii is None:
            return None
        if not np.any(radii):
            history.append(
                f"no inertia matrix: {label}{source} gives radii of gyration all zero "
                "(WAMIT's placeholder when the rotational inertia is not given); give the "
                "radii (cummins.with_inertia(ds, radii_of_gyration=...), or "
                "--radii-of-gyration RXX RYY RZZ; the mass defaults to rho*volume) or the "
                "whole matrix (--inertia-matrix FILE)"
            )
            return None
        if volume is None or cg is None:
            history.append(
                f"no inertia matrix: {label}radii of gyration in {source}, but the .out gives "
                "no volume or centre of gravity"
            )
            return None
        if m_k > 6:
            history.append(
                f"no inertia matrix: {label}radii of gyration give the rigid-body inertia, but "
                f"not the mass of its {m_k - 6} generalized modes (.frc form 2 needed)"
            )
            return None
        mass = rho * volume
        blocks.append(_rigid_inertia(mass, cg, radii))
        history.append(
            f"inertia matrix {label}from {source}: m = rho * V = {mass:.6g} kg (freely floating; "
            f"V = {volume:.6g} m^3, the mean of VOLX, VOLY, VOLZ in {out_name}), CG "
            f"{np.round(cg, 6).tolist()} m, radii of gyration about the body-origin axes"
        )
    n = sum(modes)
    out = np.zeros((n, n))
    offset = 0
    for block in blocks:
        out[offset : offset + 6, offset : offset + 6] = block
        offset += 6
    return out


# --------------------------------------------------------------------------- numeric files


def _limit_markers(first_column: str) -> tuple[float, float]:
    """(value marking ω = 0, value marking ω = ∞) in the first column."""
    return (-1.0, 0.0) if first_column == "period" else (0.0, -1.0)


def _omega_from_first_column(
    values: np.ndarray, first_column: str, *, depth: float, g: float
) -> np.ndarray:
    """ω (rad/s) from the first column: a period (s), ω, a wavenumber (1/m; finite-depth
    dispersion ω² = g k tanh(k h), or deep water ω² = g k) or a wavelength (m)."""
    values = np.asarray(values, dtype=float)
    if first_column == "period":
        return 2 * np.pi / values
    if first_column == "omega":
        return values
    if first_column == "wavenumber_deep":
        return np.sqrt(g * values)
    if first_column in ("wavenumber", "wavelength"):
        k = values if first_column == "wavenumber" else 2 * np.pi / values
        return np.sqrt(g * k * (np.tanh(k * depth) if np.isfinite(depth) else 1.0))
    raise HydroDataError(
        f"first_column must be one of {', '.join(FIRST_COLUMNS)}, got {first_column!r}"
    )


def _period_blocks(
    text: TextFile, periods: np.ndarray, where: np.ndarray, key_columns: np.ndarray
) -> list[tuple[float, np.ndarray]]:
    """Group row indices by period; reject duplicate keys and interleaved blocks."""
    blocks: list[tuple[float, list[int]]] = []
    seen_at: dict[float, int] = {}
    keys_seen: dict[tuple, int] = {}
    for r, per in enumerate(periods):
        key = (per, *key_columns[r])
        if key in keys_seen:
            raise text.error(
                f"entry {tuple(float(k) for k in key)} appears twice (first on line "
                f"{where[keys_seen[key]] + 1})",
                where[r],
                hint="the file is damaged or two runs were joined",
            )
        keys_seen[key] = r
        if not blocks or blocks[-1][0] != per:
            if per in seen_at:
                raise text.error(
                    f"rows of period {per:g} are not contiguous (also on line "
                    f"{where[seen_at[per]] + 1}): the first column is out of order",
                    where[r],
                    hint="WAMIT writes one block per period; the file seems edited or damaged",
                )
            seen_at[per] = r
            blocks.append((per, []))
        blocks[-1][1].append(r)
    return [(p, np.asarray(rows)) for p, rows in blocks]


def _dof_indices(text: TextFile, indices: np.ndarray, where: np.ndarray) -> int:
    """Largest DOF index; every index must be a positive integer."""
    if indices.size == 0:
        raise text.error("no data rows")
    bad = (indices < 1) | (indices != np.round(indices)) | (indices > 10000)
    if bad.any():
        r = int(np.argmax(bad.any(axis=1) if bad.ndim > 1 else bad))
        raise text.error("DOF index must be a positive integer", where[r])
    return int(indices.max())


@dataclass
class _Dot1:
    text: TextFile
    first: np.ndarray  # finite first-column values, in the order of increasing ω
    omega: np.ndarray
    finite: list[np.ndarray]  # row indices of each finite block, same order
    zero: np.ndarray | None  # rows of the ω = 0 block
    infinite: np.ndarray | None
    table: np.ndarray
    n_seen: int
    notes: list[str]


def _parse_dot1(path: Path, first_column: str, *, depth: float, g: float) -> _Dot1:
    """Parse a ``.1`` file: per-frequency nondimensional A (and B) rows."""
    text = _read_text(path)
    table, where = _numeric_rows(text, _title_lines(text), (4, 5), value_columns=(0, 3, 4))
    notes: list[str] = []
    per = table[:, 0]
    zero_mark, inf_mark = _limit_markers(first_column)
    limit = (per == zero_mark) | (per == inf_mark)
    if (per < 0).any() and not np.all(per[per < 0] == -1):
        raise text.error(
            "negative value other than -1 (a limit marker) in the first column",
            where[np.argmax((per < 0) & (per != -1))],
        )
    # the ω = 0 block written twice (identical rows): read once
    if limit.any():
        keep = np.ones(len(per), dtype=bool)
        seen: dict[tuple, int] = {}
        for r in np.flatnonzero(limit):
            key = tuple(table[r, :4])
            if key in seen:
                keep[r] = False
            else:
                seen[key] = r
        if not keep.all():
            notes.append(f"{path.name}: a limit block is written twice (identical): read once")
            table, where, per = table[keep], where[keep], per[keep]
            limit = limit[keep]
    missing_b = ~limit & np.isnan(table[:, 4])
    if missing_b.any():
        raise text.error(
            "a row at a finite frequency needs both added mass and damping (5 numbers)",
            where[np.argmax(missing_b)],
        )
    ij = table[:, 1:3]
    n_seen = _dof_indices(text, ij, where)
    blocks = _period_blocks(text, per, where, ij)
    pairs_of = {p: {tuple(ij[r]) for r in rows} for p, rows in blocks}
    finite = [(p, rows) for p, rows in blocks if p not in (zero_mark, inf_mark)]
    if not finite:
        raise text.error("no finite frequency in the file: nothing to build A(ω), B(ω) from")
    reference = pairs_of[finite[0][0]]
    for p, rows in finite[1:]:
        if pairs_of[p] != reference:
            missing = sorted(reference - pairs_of[p])
            detail = (
                f"entry (i, j) = {tuple(int(x) for x in missing[0])} missing"
                if missing
                else "entries differ from the first block"
            )
            raise text.error(
                f"the block at {p:g} does not have the same entries as the block at "
                f"{finite[0][0]:g}: {detail} (truncated or edited file?)",
                where[rows[-1]],
            )
    limits: dict[float, np.ndarray] = {}
    for p, rows in blocks:
        if p in (zero_mark, inf_mark):
            if not reference <= pairs_of[p]:
                missing = sorted(reference - pairs_of[p])
                raise text.error(
                    f"the limit block {p:g} lacks entry (i, j) = "
                    f"{tuple(int(x) for x in missing[0])} that every finite frequency has "
                    "(truncated or edited file?)",
                    where[rows[-1]],
                )
            limits[p] = rows
    first = np.array([p for p, _ in finite])
    with np.errstate(divide="ignore", invalid="ignore"):
        omega = _omega_from_first_column(first, first_column, depth=depth, g=g)
    if not np.all(np.isfinite(omega)) or np.any(omega <= 0):
        k = int(np.argmax(~np.isfinite(omega) | (omega <= 0)))
        raise text.error(
            f"first-column value {first[k]:g} is not a {first_column}", where[finite[k][1][0]]
        )
    order = np.argsort(omega)
    return _Dot1(
        text,
        first[order],
        omega[order],
        [finite[k][1] for k in order],
        limits.get(zero_mark),
        limits.get(inf_mark),
        table,
        n_seen,
        notes,
    )


def _dot1_arrays(d: _Dot1, n: int):
    """Nondimensional A(ω), B(ω) (nω, n, n) and the limits A(0), A(∞) (or None)."""
    ij = d.table[:, 1:3].astype(int) - 1
    a = np.zeros((d.omega.size, n, n))
    b = np.zeros((d.omega.size, n, n))
    for k, rows in enumerate(d.finite):
        a[k, ij[rows, 0], ij[rows, 1]] = d.table[rows, 3]
        b[k, ij[rows, 0], ij[rows, 1]] = d.table[rows, 4]

    def limit(rows):
        if rows is None:
            return None
        m = np.zeros((n, n))
        m[ij[rows, 0], ij[rows, 1]] = d.table[rows, 3]
        return m

    return a, b, limit(d.zero), limit(d.infinite)


def _read_wave_file(path: Path, first_values: np.ndarray, n: int, *, what: str):
    """Parse a ``.3`` (excitation) or ``.4`` (RAO) file: complex values per frequency,
    heading and DOF, nondimensional. Every (frequency, heading) block must hold the
    same DOFs; a missing row is an error, not a zero."""
    text = _read_text(path)
    table, where = _numeric_rows(text, _title_lines(text), 7, value_columns=(0, 1, 3, 5, 6))
    per, beta, dof = table[:, 0], table[:, 1], table[:, 2]
    _period_blocks(text, per, where, table[:, 1:3])
    bad = (dof > n) | (dof < 1) | (dof != np.round(dof))
    if bad.any():
        r = int(np.argmax(bad))
        raise text.error(f"DOF index {dof[r]:g} does not exist in the .1 file ({n} DOFs)", where[r])
    headings = np.unique(beta)
    if np.any(np.abs(headings) > 720):
        raise text.error(
            f"wave heading {headings[np.argmax(np.abs(headings) > 720)]:g} deg is not an angle",
            where[0],
        )
    by_value = np.argsort(first_values)
    sorted_values = first_values[by_value]
    pos = np.clip(np.searchsorted(sorted_values, per), 1, max(sorted_values.size - 1, 1))
    pos = np.where(sorted_values.size == 1, 0, pos)
    left = np.clip(pos - 1, 0, None)
    nearer = np.abs(sorted_values[left] - per) <= np.abs(sorted_values[pos] - per)
    pos = np.where(nearer, left, pos)
    matched = np.abs(sorted_values[pos] - per) <= 1e-5 * np.maximum(np.abs(per), 1e-12)
    if not matched.all():
        r = int(np.argmax(~matched))
        raise text.error(
            f"frequency {per[r]:g} is not in the .1 file",
            where[r],
            hint="the .1 and the " + path.suffix + " files must come from the same run",
        )
    k = by_value[pos]
    missing = np.setdiff1d(np.arange(first_values.size), k)
    if missing.size:
        raise text.error(
            f"no {what} at {first_values[missing[0]]:g} of the .1 file (truncated file?)",
            len(text) - 1,
        )
    h = np.searchsorted(headings, beta)
    d = dof.astype(int) - 1
    count = np.zeros((first_values.size, headings.size), dtype=int)
    np.add.at(count, (k, h), 1)
    present = np.zeros((first_values.size, headings.size, n), dtype=bool)
    present[k, h, d] = True
    reference = present[k[0], h[0]]
    mismatch = np.any(present != reference, axis=2)
    if mismatch.any():
        kk, hh = np.argwhere(mismatch)[0]
        gone = np.flatnonzero(reference & ~present[kk, hh])
        other = np.flatnonzero(present[kk, hh] & ~reference)
        which = f"DOF {gone[0] + 1} missing" if gone.size else f"DOF {other[0] + 1} extra"
        rows_here = np.flatnonzero((k == kk) & (h == hh))
        line = where[rows_here[-1]] if rows_here.size else len(text) - 1
        raise text.error(
            f"{what} at {first_values[kk]:g}, heading {headings[hh]:g} deg: {which} "
            "(a line deleted or damaged?)",
            line,
        )
    x = np.zeros((first_values.size, headings.size, n), dtype=complex)
    x[k, h, d] = table[:, 5] + 1j * table[:, 6]
    # modulus and phase columns must agree with the real and imaginary parts
    modulus = np.abs(table[:, 5] + 1j * table[:, 6])
    off = np.abs(modulus - table[:, 3]) > 1e-3 * np.maximum(np.abs(table[:, 3]), 1e-30) + 1e-6 * (
        np.abs(table[:, 3]).max() + 1e-300
    )
    if off.any():
        r = int(np.argmax(off))
        raise text.error(
            f"the modulus {table[r, 3]:g} does not match the real and imaginary parts "
            f"({modulus[r]:g}): an edited number?",
            where[r],
        )
    return x, np.radians(headings)


def _read_hst(path: Path, n: int) -> np.ndarray:
    """Parse a ``.hst`` file. WAMIT writes every entry of the n×n matrix; a missing one
    is damage (HydroDataError), never a zero."""
    text = _read_text(path)
    table, where = _numeric_rows(text, _title_lines(text), 3, value_columns=(2,))
    ij = table[:, :2]
    bad = (ij < 1) | (ij > n) | (ij != np.round(ij))
    if bad.any():
        r = int(np.argmax(bad.any(axis=1)))
        raise text.error(f"DOF index out of range 1…{n}", where[r])
    c = np.zeros((n, n))
    seen = np.zeros((n, n), dtype=bool)
    i, j = ij[:, 0].astype(int) - 1, ij[:, 1].astype(int) - 1
    if np.any(seen[i, j]) or len(set(zip(i.tolist(), j.tolist(), strict=True))) != len(i):
        r = len(i) - 1
        raise text.error("an entry appears twice", where[r])
    seen[i, j] = True
    c[i, j] = table[:, 2]
    n_file = int(ij.max())
    if not seen[:n_file, :n_file].all():
        a, b = np.argwhere(~seen[:n_file, :n_file])[0]
        raise text.error(
            f"entry C({a + 1},{b + 1}) missing: the file lists every entry of the "
            f"{n_file}×{n_file} matrix (truncated or edited?)",
            len(text) - 1,
        )
    return c


# --------------------------------------------------------------------------- a run


@dataclass
class RunSettings:
    """What another program's run fixes for the WAMIT-format reader (used for HAMS).

    Attributes
    ----------
    source_format
        Recorded as the dataset's ``source_format``.
    first_column
        Kind of the first column (see :data:`FIRST_COLUMNS`).
    rho, g, ulen, water_depth
        Constants of the run, as recorded in its files (``None``: unknown).
    history
        Lines to add to the dataset's history.
    inertia_matrix, additional_damping, additional_stiffness
        Matrices the run's input holds (n×n, dimensional).
    reference_point
        Point about which the run's moments are taken, m.
    rao_times_rho_g
        The ``.4`` holds i·ξ/(ρg) instead of the RAO ξ (HAMS does so).
    notes
        Damage the project's own files showed (warned about already), for the
        dataset's ``read_warnings``.
    """

    source_format: str = "wamit"
    first_column: str | None = None
    rho: float | None = None
    g: float | None = None
    ulen: float | None = None
    water_depth: float | None = None
    history: list[str] = field(default_factory=list)
    inertia_matrix: np.ndarray | None = None
    additional_damping: np.ndarray | None = None
    additional_stiffness: np.ndarray | None = None
    reference_point: np.ndarray | None = None
    rao_times_rho_g: bool = False
    notes: list[str] = field(default_factory=list)


def _hams_project(dot1: Path) -> Path | None:
    """The HAMS project folder of a file in ``<project>/Output*/Wamit_format/``."""
    folder = dot1.resolve().parent
    if folder.name == "Wamit_format":
        project = folder.parent.parent
        if (project / "Input" / "ControlFile.in").is_file():
            return project
    return None


def read_wamit(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    first_column: str | None = None,
    siblings: bool = True,
    modes: int | Sequence[int] | None = None,
) -> xr.Dataset:
    """Read a WAMIT run into a canonical ``HydroDB``.

    Parameters
    ----------
    path
        A ``.1`` file (its ``.3``, ``.4``, ``.hst``, ``.frc``, ``.mmx``, ``.cfg``,
        ``.pot`` and ``.out`` siblings with the same stem are read too, unless
        ``siblings=False``), a ``.3`` or ``.hst`` file (then the ``.1`` sibling is
        required), or a ``.out`` file (read on its own, see :func:`read_wamit_out`). A
        ``.1`` in a HAMS project's ``Output/Wamit_format/`` is read with the HAMS
        project's settings (:func:`cummins.io.hams.read_hams`).
    rho, g, ulen
        Water density (kg/m³), gravity (m/s²) and WAMIT length scale ULEN (m) used to
        make the numbers dimensional. By default they come from the ``.out`` header
        (ρ also from the ``.frc``), else ρ = 1025, g = 9.81, ULEN = 1.
    first_column
        What the first column of the numeric files holds: ``"period"`` (s, WAMIT's
        default), ``"omega"`` (rad/s), ``"wavenumber"`` (finite depth),
        ``"wavenumber_deep"`` or ``"wavelength"``; by default from the ``.cfg``
        (IPEROUT/IPERIO), else period.
    siblings
        Read the sibling files of a ``.1`` file.
    modes
        Modes per body (an int for one body, or one per body), when the files do not
        say (a ``.1`` without its ``.out``/``.pot``/``.cfg`` and DOF indices beyond 6).

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB``, z-up axes, about the body origin.

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.read(cummins.demo_files() / "tanker.1")
    >>> float(ds.attrs["rho"])
    1025.0
    """
    path = Path(path)
    if not path.exists():
        raise HydroDataError("file not found", path=path)
    if is_out_file(path):
        return read_wamit_out(path, rho=rho, g=g, ulen=ulen, modes=modes)
    kind = numeric_kind(path)
    if kind is None:
        raise HydroDataError(
            "not a WAMIT .1, .3, .hst or .out file (unrecognised content)", path=path
        )
    dot1 = path if kind == ".1" else _sibling(path, ".1")
    if dot1 is None:
        raise HydroDataError(
            f"a WAMIT {kind} file alone has no added mass and damping",
            path=path,
            hint=f"put the .1 file of the same run next to it ({path.with_suffix('.1').name})",
        )
    project = _hams_project(dot1)
    if project is not None and first_column is None:
        from cummins.io.hams import read_hams

        return read_hams(project, rho=rho, g=g, output=dot1.parent.parent, siblings=siblings)
    return read_wamit_run(
        dot1,
        rho=rho,
        g=g,
        ulen=ulen,
        first_column=first_column,
        siblings=siblings or kind != ".1",
        modes=modes,
        entry=path,
    )


def _nonempty_sibling(dot1: Path, suffix: str, history: list[str]) -> Path | None:
    p = _sibling(dot1, suffix)
    if p is not None and p.stat().st_size == 0:
        history.append(f"{p.name} is empty (0 bytes): skipped")
        return None
    return p


def read_wamit_run(
    dot1: Path,
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    first_column: str | None = None,
    siblings: bool = True,
    modes: int | Sequence[int] | None = None,
    settings: RunSettings | None = None,
    entry: Path | None = None,
) -> xr.Dataset:
    """Read the WAMIT-format run of the ``.1`` file ``dot1`` (see :func:`read_wamit`);
    ``settings`` carry what another program's project fixes (HAMS)."""
    settings = settings or RunSettings()
    history: list[str] = [f"read {dot1.name}", *settings.history]
    notes: list[str] = list(settings.notes)

    def sibling(suffix: str) -> Path | None:
        if not siblings and not (entry is not None and entry.suffix.lower() == suffix):
            return None
        return _nonempty_sibling(dot1, suffix, history)

    dot3, dot4, hst = sibling(".3"), sibling(".4"), sibling(".hst")
    out_path, frc_path = sibling(".out"), sibling(".frc")
    mmx_path, cfg_path, pot_path = sibling(".mmx"), sibling(".cfg"), sibling(".pot")

    header = _OutHeader()
    have_out = out_path is not None and is_out_file(out_path)
    if have_out:
        header = _out_header(_read_text(out_path))
        history.append(f"constants and body parameters from {out_path.name}")
        if not header.has_gravity_line or header.ulen is None:
            warn_damage(
                "the .out header has no 'Gravity: … Length scale: …' line (damaged?): "
                "g and ULEN not taken from it",
                path=out_path,
                notes=notes,
            )
        for body in header.bodies:
            history.extend(body.notes)
    cfg = _Config()
    if cfg_path is not None:
        try:
            cfg = _read_cfg(cfg_path)
        except HydroDataError as exc:
            warn_damage(f"not read: {exc}", path=cfg_path, notes=notes)
    column = first_column or settings.first_column or cfg.first_column or "period"
    if column not in FIRST_COLUMNS:
        raise HydroDataError(
            f"first_column must be one of {', '.join(FIRST_COLUMNS)}, got {column!r}"
        )
    if column != "period":
        history.append(f"first column of the numeric files: {column}")
    depth = settings.water_depth if settings.water_depth is not None else header.water_depth
    depth = np.inf if depth is None else depth
    g_guess = g or settings.g or header.g or 9.81
    d = _parse_dot1(dot1, column, depth=depth, g=g_guess)
    history.extend(d.notes)

    pot_names = None
    if pot_path is not None and not header.bodies:
        try:
            pot_names = _read_pot_bodies(pot_path)
        except HydroDataError as exc:
            warn_damage(f"not read: {exc}", path=pot_path, notes=notes)
    mmx = _Mmx()
    if mmx_path is not None:
        try:
            mmx = _read_mmx(mmx_path)
        except HydroDataError as exc:
            warn_damage(f"not read: {exc}", path=mmx_path, notes=notes)
    n_bodies = (
        len(header.bodies) if header.bodies else (len(pot_names) if pot_names else mmx.n_bodies)
    )
    layout = _mode_layout(
        d.n_seen,
        n_bodies=n_bodies,
        new_modes=cfg.new_modes,
        extra_modes=header.extra_modes if have_out and header.bodies else None,
        modes=modes,
        path=dot1,
        history=history,
    )
    n = sum(layout)
    _check_memory(n, d.omega.size, 1, dot1)

    frc = None
    if frc_path is not None:
        try:
            frc = _read_frc(frc_path, n, len(layout), cfg.ialtfrc)
            history.append(f"{frc_path.name}: alternative form {frc.form}")
        except HydroDataError as exc:
            warn_damage(
                f"not read, so no inertia or external matrices from it: {exc}",
                path=frc_path,
                notes=notes,
            )
    rho_in_file = header.rho if header.rho is not None else (frc.rho if frc else None)
    if rho_in_file is None:
        rho_in_file = settings.rho
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        rho_in_file,
        header.g if header.g is not None else settings.g,
        path=dot1,
        history=history,
        dimensional=False,
    )
    L = resolve_constant(
        "ulen",
        ulen,
        header.ulen if header.ulen is not None else settings.ulen,
        1.0,
        unit="m",
        path=dot1,
        history=history,
        dimensional=False,
    )
    if column != "period" and column != "omega" and not np.isclose(g_v, g_guess):
        d = _parse_dot1(dot1, column, depth=depth, g=g_v)

    a_bar, b_bar, a_zero, a_inf = _dot1_arrays(d, n)
    omega = d.omega
    scale_a = rho_v * L ** length_exponents(n, 3, layout)
    extra: dict = {
        "added_mass": a_bar * scale_a,
        "radiation_damping": b_bar * scale_a * omega[:, None, None],
    }
    if a_inf is not None:
        extra["added_mass_inf"] = a_inf * scale_a
    if a_zero is not None:
        extra["added_mass_zero"] = a_zero * scale_a
    force_scale = rho_v * g_v * L ** force_exponents(n, 2, layout)
    if dot3 is not None:
        x_bar, beta = _read_wave_file(dot3, d.first, n, what="excitation")
        extra["excitation_force"] = x_bar * force_scale
        extra["wave_direction"] = beta
        history.append(f"excitation from {dot3.name}")
    elif have_out:
        _excitation_from_out(out_path, omega, layout, rho_v, g_v, L, extra, history)
    if dot4 is not None:
        try:
            rao_bar, beta4 = _read_wave_file(dot4, d.first, n, what="RAO")
            if "wave_direction" in extra and not (
                beta4.shape == extra["wave_direction"].shape
                and np.allclose(beta4, extra["wave_direction"])
            ):
                raise HydroDataError("its headings differ from the excitation headings", path=dot4)
            extra["rao"] = rao_bar / L ** rotation_flags(n, layout)
            if settings.rao_times_rho_g:
                extra["rao"] = extra["rao"] * (-1j * rho_v * g_v)
                history.append(f"{dot4.name}: RAOs written as i·ξ/(rho g) by HAMS, multiplied back")
            extra.setdefault("wave_direction", beta4)
            history.append(f"motion RAOs from {dot4.name} (the solver's own)")
        except HydroDataError as exc:
            warn_damage(f"RAOs not read: {exc}", path=dot4, notes=notes)
    if hst is not None:
        try:
            extra["hydrostatic_stiffness"] = _read_hst(hst, n) * (
                rho_v * g_v * L ** length_exponents(n, 2, layout)
            )
            history.append(f"hydrostatics from {hst.name}")
        except HydroDataError as exc:
            warn_damage(f"hydrostatics not read: {exc}", path=hst, notes=notes)
    elif header.bodies and all(b.hydrostatics for b in header.bodies) and n == 6 * len(layout):
        extra["hydrostatic_stiffness"] = _hydrostatics_matrix(header, layout) * (
            rho_v * g_v * L ** length_exponents(n, 2, layout)
        )
        history.append(f"hydrostatics from {out_path.name} (no .hst file)")

    _mass_matrices(
        extra,
        layout,
        rho_v,
        header,
        frc,
        frc_path,
        mmx,
        mmx_path,
        out_path,
        settings,
        history,
        notes,
        omega.size,
    )
    names = header.body_names if len(header.body_names) == len(layout) else (pot_names or [])
    return make_hydrodb(
        omega,
        extra.pop("added_mass"),
        extra.pop("radiation_damping"),
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format=settings.source_format,
        source_file=str(dot1),
        dofs=dof_labels(len(layout) if len(layout) > 1 else None, layout),
        history=history,
        read_warnings=notes,
        ulen=L,
        body_names="\n".join(names) if len(names) == len(layout) else None,
        **extra,
        **_body_attrs(header, layout, settings),
    )


def _hydrostatics_matrix(header: _OutHeader, layout: list[int]) -> np.ndarray:
    n = sum(layout)
    c = np.zeros((n, n))
    offset = 0
    for body, m in zip(header.bodies, layout, strict=False):
        c[offset : offset + 6, offset : offset + 6] = _hydrostatics_from_out(body.hydrostatics)
        offset += m
    return c


def _mass_matrices(
    extra,
    layout,
    rho_v,
    header,
    frc,
    frc_path,
    mmx,
    mmx_path,
    out_path,
    settings,
    history,
    notes,
    n_omega,
) -> None:
    """Inertia and external matrices into ``extra``, from the best source the run has."""
    n = sum(layout)
    frc_name = frc_path.name if frc_path is not None else ".frc"
    out_name = out_path.name if out_path is not None else ".out"
    inertia = None
    if frc is not None and frc.form == 2:
        if mmx.external is not None and mmx.external[0].shape == (n, n):
            for name, a, b in zip(
                ("IMASS", "IDAMP", "ISTIF"),
                (frc.mass, frc.damping, frc.stiffness),
                mmx.external,
                strict=True,
            ):
                a = np.zeros((n, n)) if a is None else a
                if not np.allclose(a, b, rtol=1e-5, atol=1e-6 * (np.abs(b).max() + 1e-30)):
                    k = np.unravel_index(np.argmax(np.abs(a - b)), a.shape)
                    warn_damage(
                        f"{name}({k[0] + 1},{k[1] + 1}) = {a[k]:g} but {mmx_path.name}, WAMIT's "
                        f"echo of it, says {b[k]:g}: the .frc is not the run's (or damaged); "
                        "its matrices are not used",
                        path=frc_path,
                        notes=notes,
                    )
                    frc = None
                    break
        if frc is not None and frc.mass is not None:
            inertia = frc.mass
            history.append(f"inertia matrix from {frc_name} (IMASS, alternative form 2, as given)")
        if frc is not None and frc.damping is not None and np.any(frc.damping):
            extra["additional_damping"] = np.broadcast_to(frc.damping, (n_omega, n, n))
            history.append(f"external damping from {frc_name} (IDAMP) as additional_damping")
        if frc is not None and frc.stiffness is not None and np.any(frc.stiffness):
            extra["additional_stiffness"] = frc.stiffness
            history.append(f"external stiffness from {frc_name} (ISTIF) as additional_stiffness")
    elif settings.inertia_matrix is not None:
        inertia = settings.inertia_matrix
    else:
        inertia = _inertia_from_mass_properties(
            layout, rho_v, header.bodies, frc, frc_name, out_name, history
        )
        if (
            inertia is None
            and not header.bodies
            and mmx.normalized_mass is not None
            and mmx.normalized_mass.shape == (n, n)
        ):
            inertia = rho_v * mmx.normalized_mass
            history.append(
                f"inertia matrix from {mmx_path.name} (WAMIT's normalized mass matrix × rho)"
            )
    if inertia is not None:
        if inertia.shape != (n, n):
            warn_damage(
                f"the mass matrix is {inertia.shape[0]}×{inertia.shape[1]}, the data {n}×{n}: "
                "not used",
                path=frc_path,
                notes=notes,
            )
        elif np.any(inertia):
            extra["inertia_matrix"] = inertia
    for name in ("additional_damping", "additional_stiffness"):
        value = getattr(settings, name)
        if value is not None and np.any(value) and name not in extra:
            extra[name] = (
                np.broadcast_to(value, (n_omega, n, n)) if name == "additional_damping" else value
            )


def _excitation_from_out(out_path, omega, layout, rho_v, g_v, L, extra, history) -> None:
    """Excitation printed in the ``.out`` when the run has no ``.3`` file."""
    out = read_wamit_out(out_path, rho=rho_v, g=g_v, ulen=L, modes=layout)
    if "excitation_force" not in out:
        history.append(f"no excitation: no .3 file, and {out_path.name} prints none")
        return
    if out.sizes["omega"] != omega.size or not np.allclose(out.omega.values, omega, rtol=1e-5):
        history.append(f"no excitation: no .3 file, and {out_path.name} has other frequencies")
        return
    extra["excitation_force"] = out.excitation_force.values
    extra["wave_direction"] = out.wave_direction.values
    history.append(
        f"excitation from {out_path.name} (no .3 file; the log prints 7 digits and phases "
        "in whole degrees)"
    )


def _body_attrs(header: _OutHeader, layout: list[int], settings: RunSettings) -> dict:
    """Reference point, CG, CB in global coordinates (origin on the free surface)."""
    nb = len(layout)
    origin = np.zeros((nb, 3))
    if settings.reference_point is not None:
        origin[:] = np.asarray(settings.reference_point, dtype=float).reshape(-1, 3)[:nb]
    for k, body in enumerate(header.bodies[:nb]):
        origin[k] = body.origin
    attrs: dict = {"reference_point": origin.reshape(-1) if nb > 1 else origin[0]}
    bodies = header.bodies[:nb]
    if len(bodies) == nb:
        cg = [b.center_of_gravity for b in bodies]
        if all(c is not None for c in cg):
            attrs["center_of_gravity"] = (np.vstack(cg) + origin).reshape(-1)
        cb = [b.center_of_buoyancy for b in bodies]
        if all(c is not None for c in cb):
            attrs["center_of_buoyancy"] = (np.vstack(cb) + origin).reshape(-1)
        if nb == 1 and bodies[0].volumes is not None:
            attrs["displaced_volume"] = float(np.mean(bodies[0].volumes))
    return attrs


# --------------------------------------------------------------------------- .out file

_PERIOD_LINE = re.compile(r"Wave period\s*(?:\(sec\))?\s*=\s*(infinite|zero|" + _FLOAT[1:-1] + ")")
_HEADING_LINE = re.compile(r"Wave Heading \(deg\)\s*:\s*" + _FLOAT)
_SECTION_TITLES = {
    "ADDED-MASS AND DAMPING COEFFICIENTS": "radiation",
    "ADDED-MASS COEFFICIENTS": "radiation",
    "DIFFRACTION EXCITING FORCES AND MOMENTS": "diffraction",
    "HASKIND EXCITING FORCES AND MOMENTS": "haskind",
    "RESPONSE AMPLITUDE OPERATORS": "rao",
    "DRIFT FORCES (Pressure Integration)": "drift_pressure",
    "DRIFT FORCES (Momentum Conservation)": "drift_momentum",
    "DRIFT FORCES (Control Surface)": "drift_control_surface",
}


def _section_kind(line: str) -> str | None:
    stripped = line.strip()
    for title, kind in _SECTION_TITLES.items():
        if stripped.endswith(title):
            return kind
    return None


def _rows_after(text: TextFile, i: int, stop: int) -> tuple[list[np.ndarray], list[int], int]:
    """Numeric rows after line ``i`` up to the first non-numeric non-blank line."""
    rows, where = [], []
    k = i
    while k < stop:
        line = text.lines[k]
        if line.strip():
            values = parse_numbers(line)
            if values is None:
                break
            if not np.all(np.isfinite(values)):
                raise text.error("non-finite value (NaN or Inf) in the data", k)
            if np.any(np.abs(values) >= MAX_ABS_VALUE):
                raise text.error("implausible value (a missing-value marker?)", k)
            rows.append(values)
            where.append(k)
        k += 1
    return rows, where, k


def _skip_column_titles(text: TextFile, i: int, stop: int) -> int:
    """Number of lines from ``i`` up to and including the column-title line (I J …)."""
    for k in range(i, min(i + 6, stop)):
        fields = text.lines[k].split()  # "I  J …", with blanks or tabs between
        if fields and fields[0] == "I":
            return k - i + 1
    return 0


def _out_blocks(text: TextFile, starts: list[int]) -> list[tuple[str, dict, int]]:
    """Per 'Wave period' block: its label, {section: rows} and its first line."""
    blocks = []
    bounds = [*starts, len(text)]
    for b in range(len(starts)):
        i0, i1 = bounds[b], bounds[b + 1]
        label = _PERIOD_LINE.search(text.lines[i0]).group(1)
        content: dict = {}
        k = i0 + 1
        while k < i1:
            kind = _section_kind(text.lines[k])
            if kind is None:
                k += 1
                continue
            if kind in content:
                raise text.error(
                    f"a second {kind} table in the block of period {label} (a 'Wave period' "
                    "line deleted?)",
                    k,
                )
            if kind == "radiation":
                rows, where, k = _rows_after(text, k + 1 + _skip_column_titles(text, k + 1, i1), i1)
                content["radiation"] = (rows, where)
                continue
            per_heading: dict[float, tuple[list[np.ndarray], list[int]]] = {}
            k += 1
            while k < i1:
                if _section_kind(text.lines[k]) is not None:
                    break
                m = _HEADING_LINE.search(text.lines[k])
                if m:
                    beta = float(m.group(1))
                    if beta in per_heading:
                        raise text.error(f"heading {beta:g} deg appears twice in this block", k)
                    rows, where, k = _rows_after(
                        text, k + 1 + _skip_column_titles(text, k + 1, i1), i1
                    )
                    per_heading[beta] = (rows, where)
                    continue
                k += 1
            content[kind] = per_heading
        blocks.append((label, content, i0))
    return blocks


def _check_out_tables(text: TextFile, blocks) -> None:
    """Every row of the log's tables as WAMIT writes it: as many numbers as the other
    rows of its kind of table (limit blocks print A alone; the drift tables mix 3- and
    5-number rows), in WAMIT's fixed columns (:func:`check_line_ends`, per kind and
    number of fields). A garbled number that splits in two ("1.2.3" reads as 1.2 and
    0.3) or a cut row would otherwise pass."""
    groups: dict[tuple[str, int], list[int]] = {}
    sizes: dict[tuple[str, bool], dict[int, list[int]]] = {}
    for label, content, _ in blocks:
        limit = label in ("infinite", "zero")
        for kind, value in content.items():
            tables = [value] if kind == "radiation" else list(value.values())
            for rows, where in tables:
                for r, w in zip(rows, where, strict=True):
                    groups.setdefault((kind, r.size), []).append(w)
                    if not kind.startswith("drift"):
                        sizes.setdefault((kind, limit), {}).setdefault(r.size, []).append(w)
    for (kind, limit), by_size in sizes.items():
        usual = max(by_size, key=lambda size: len(by_size[size]))
        odd = [size for size in by_size if size != usual]
        if odd:
            line = min(by_size[odd[0]])
            raise text.error(
                f"expected {usual} numbers, as on the other rows of the {kind} tables"
                f"{' of the limit blocks' if limit else ''}, found {odd[0]}",
                line,
                hint="the file is damaged; take it again from the WAMIT run",
            )
    for lines in groups.values():
        check_line_ends(text, lines)


def read_wamit_out(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    modes: int | Sequence[int] | None = None,
) -> xr.Dataset:
    """Read a WAMIT ``.out`` log on its own.

    The log prints the same nondimensional quantities as the numeric files, to
    fewer digits (phases in whole degrees), plus motion RAOs and mean drift forces:
    added mass and damping, A(0) and A(∞), diffraction (else Haskind) excitation,
    hydrostatics and mass properties (header), RAOs and mean drift forces (pressure
    integration, else momentum conservation), about the body origin. A ``.cfg``
    (NEWMDS) and ``.frc`` with the same stem are read too.

    Parameters
    ----------
    path
        The ``.out`` file.
    rho, g, ulen
        As in :func:`read_wamit`; from the header when printed there.
    modes
        Modes per body, when the files do not say (see :func:`read_wamit`).
    """
    path = Path(path)
    text = _read_text(path)
    if not is_out_file(path):
        raise text.error("not a WAMIT .out file (no WAMIT banner)")
    notes: list[str] = []
    header = _out_header(text)
    history = [f"read {path.name}"]
    for body in header.bodies:
        history.extend(body.notes)
    if not header.has_gravity_line or header.ulen is None:
        warn_damage(
            "no 'Gravity: … Length scale: …' line in the header (damaged?)",
            path=path,
            notes=notes,
        )
    rho_v, g_v = resolve_rho_g(
        rho, g, header.rho, header.g, path=path, history=history, dimensional=False
    )
    L = resolve_constant(
        "ulen", ulen, header.ulen, 1.0, unit="m", path=path, history=history, dimensional=False
    )

    starts = [i for i, line in enumerate(text.lines) if _PERIOD_LINE.search(line)]
    if not starts:
        raise text.error(
            "no 'Wave period' blocks: the run did not reach the FORCE output (truncated log?)"
        )
    blocks = _out_blocks(text, starts)
    _check_out_tables(text, blocks)
    if header.announced_blocks is not None and header.announced_blocks != len(blocks):
        warn_damage(
            f"the header lists {header.announced_blocks} periods, the log holds "
            f"{len(blocks)} 'Wave period' blocks (truncated or edited?): read the "
            f"{len(blocks)}",
            path=path,
            notes=notes,
        )

    n_seen = 0
    for _, content, _ in blocks:
        for r, w in zip(*content.get("radiation", ([], [])), strict=True):
            if r.size < 3 or r[0] != int(r[0]) or r[1] != int(r[1]) or min(r[0], r[1]) < 1:
                raise text.error("expected DOF indices I J at the start of the row", w)
            if max(r[0], r[1]) > 10000:
                raise text.error(f"DOF index {max(r[0], r[1]):g} is not plausible", w)
            n_seen = max(n_seen, int(r[0]), int(r[1]))
    if n_seen == 0:
        raise text.error("no added-mass coefficients found")
    cfg = _Config()
    cfg_path = _sibling(path, ".cfg")
    if cfg_path is not None and cfg_path.stat().st_size:
        try:
            cfg = _read_cfg(cfg_path)
        except HydroDataError as exc:
            warn_damage(f"not read: {exc}", path=cfg_path, notes=notes)
    layout = _mode_layout(
        n_seen,
        n_bodies=len(header.bodies) or None,
        new_modes=cfg.new_modes,
        extra_modes=header.extra_modes if header.bodies else None,
        modes=modes,
        path=path,
        history=history,
    )
    n = sum(layout)

    def matrix(rows, where, column):
        m = np.zeros((n, n))
        seen = set()
        for r, w in zip(rows, where, strict=True):
            if r.size <= column:
                raise text.error(f"expected at least {column + 1} numbers", w)
            key = (int(r[0]), int(r[1]))
            if key in seen:
                raise text.error(f"entry {key} appears twice in this table", w)
            seen.add(key)
            m[key[0] - 1, key[1] - 1] = r[column]
        return m

    finite = []
    limits: dict[str, np.ndarray] = {}
    for label, content, block_start in blocks:
        if "radiation" not in content:
            raise text.error(f"no added-mass coefficients for period {label}", block_start)
        rows, where = content["radiation"]
        if label in ("infinite", "zero"):
            value = matrix(rows, where, 2)
            if label in limits:
                if not np.allclose(value, limits[label], rtol=1e-6, atol=0):
                    raise text.error(
                        f"the block of period {label} is written twice, with different values",
                        block_start,
                    )
                history.append(f"the period-{label} block is written twice (identical): read once")
            limits[label] = value
        else:
            finite.append((float(label), content, rows, where, block_start))
    if not finite:
        raise text.error("no finite wave period in the log")
    first_pairs = {(int(r[0]), int(r[1])) for r in finite[0][2]}
    for period, _, rows, _, block_start in finite[1:]:
        if {(int(r[0]), int(r[1])) for r in rows} != first_pairs:
            raise text.error(
                f"the added-mass and damping table at period {period:g} s does not have the "
                "same entries as the first period (truncated or edited log?)",
                block_start,
            )
    periods = np.array([p for p, *_ in finite])
    if np.any(periods <= 0):
        raise text.error(f"period {periods[periods <= 0][0]:g} s is not positive", starts[0])
    omega = 2 * np.pi / periods
    order = np.argsort(omega)
    headings0 = sorted(finite[0][1].get("diffraction", finite[0][1].get("haskind", {})))
    _check_memory(n, omega.size, max(len(headings0), 1), path)
    scale_a = rho_v * L ** length_exponents(n, 3, layout)
    a = np.stack([matrix(finite[k][2], finite[k][3], 2) for k in order]) * scale_a
    b = (
        np.stack([matrix(finite[k][2], finite[k][3], 3) for k in order])
        * scale_a
        * omega[order, None, None]
    )

    extra: dict = {}
    if "infinite" in limits:  # infinite period: omega = 0
        extra["added_mass_zero"] = limits["infinite"] * scale_a
    if "zero" in limits:
        extra["added_mass_inf"] = limits["zero"] * scale_a

    def by_heading(kind: str, scale: np.ndarray, real: bool = False):
        """Stack one section over periods and headings; every period must be complete."""
        headings = sorted(finite[0][1].get(kind, {}))
        if not headings:
            return None, None
        first_dofs = None
        out = np.zeros((len(order), len(headings), n), dtype=float if real else complex)
        for kk, k in enumerate(order):
            per_heading = finite[k][1].get(kind, {})
            if sorted(per_heading) != headings:
                raise text.error(
                    f"the {kind} output at period {finite[k][0]:g} s has headings "
                    f"{sorted(per_heading)}, not {headings} as the first period "
                    "(truncated or edited log?)",
                    finite[k][4],
                )
            for h, beta in enumerate(headings):
                rows, where = per_heading[beta]
                dofs = []
                for r, w in zip(rows, where, strict=True):
                    if r.size < 3 or not 1 <= abs(r[0]) <= n or r[0] != int(r[0]):
                        raise text.error("expected a DOF index, a modulus and a phase", w)
                    if int(abs(r[0])) in dofs:
                        raise text.error(f"DOF {int(abs(r[0]))} appears twice here", w)
                    dofs.append(int(abs(r[0])))
                    value = r[1] * np.exp(1j * np.radians(r[2]))
                    out[kk, h, int(abs(r[0])) - 1] = value.real if real else value
                if first_dofs is None:
                    first_dofs = sorted(dofs)
                elif sorted(dofs) != first_dofs:
                    raise text.error(
                        f"the {kind} output at period {finite[k][0]:g} s, heading {beta:g} deg "
                        f"holds DOFs {sorted(dofs)}, not {first_dofs} (a line deleted?)",
                        where[-1] if where else finite[k][4],
                    )
        return out * scale, np.radians(headings)

    force_scale = rho_v * g_v * L ** force_exponents(n, 2, layout)
    x, beta = by_heading("diffraction", force_scale)
    if x is None:
        x, beta = by_heading("haskind", force_scale)
        if x is not None:
            history.append("excitation from the Haskind relations (no diffraction output)")
    if x is not None:
        extra["excitation_force"] = x
        extra["wave_direction"] = beta
    rao, beta_r = by_heading("rao", 1.0 / L ** rotation_flags(n, layout))
    if rao is not None:
        if beta is not None and (beta.shape != beta_r.shape or not np.allclose(beta, beta_r)):
            raise text.error("the RAO headings differ from the excitation headings")
        extra["rao"], extra["wave_direction"] = rao, beta_r
    drift_scale = rho_v * g_v * L ** force_exponents(n, 1, layout)
    drift, beta_d = by_heading("drift_pressure", drift_scale, real=True)
    if drift is None:
        drift, beta_d = by_heading("drift_momentum", drift_scale, real=True)
    if drift is not None and "wave_direction" in extra:
        same = beta_d.shape == extra["wave_direction"].shape
        if not same or not np.allclose(beta_d, extra["wave_direction"]):
            raise text.error("the drift-force headings differ from the excitation headings")
        extra["drift_force"] = drift
    if header.bodies and all(bd.hydrostatics for bd in header.bodies):
        extra["hydrostatic_stiffness"] = _hydrostatics_matrix(header, layout) * (
            rho_v * g_v * L ** length_exponents(n, 2, layout)
        )
        if n != 6 * len(layout):
            history.append(
                "hydrostatics of the generalized modes are not printed in the .out: "
                "their rows are 0 (the run's .hst has them)"
            )
    frc_path = _sibling(path, ".frc")
    frc = None
    if frc_path is not None and frc_path.stat().st_size:
        try:
            frc = _read_frc(frc_path, n, len(layout), cfg.ialtfrc)
        except HydroDataError as exc:
            warn_damage(
                f"not read, so no inertia or external matrices from it: {exc}",
                path=frc_path,
                notes=notes,
            )
    _mass_matrices(
        extra,
        layout,
        rho_v,
        header,
        frc,
        frc_path,
        _Mmx(),
        None,
        path,
        RunSettings(),
        history,
        notes,
        omega.size,
    )
    names = header.body_names
    return make_hydrodb(
        omega[order],
        a,
        b,
        rho=rho_v,
        g=g_v,
        water_depth=header.water_depth if header.water_depth is not None else np.inf,
        source_format="wamit-out",
        source_file=str(path),
        dofs=dof_labels(len(layout) if len(layout) > 1 else None, layout),
        history=history,
        read_warnings=notes,
        ulen=L,
        body_names="\n".join(names) if len(names) == len(layout) else None,
        **extra,
        **_body_attrs(header, layout, RunSettings()),
    )
