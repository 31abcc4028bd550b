"""ShipX/VERES strip-theory results: ``.re7``, ``.re8``, ``.re1`` and ``.re2`` files.

VERES (SINTEF Ocean) writes one text file per quantity, all with the same header: six
lines of text (title with the VERES version, run, ship and loading condition), then
``RHOSW GRAV`` (kg/m³, m/s²), ``LPP BREADTH DRAUGHT`` (m), ``LCG VCG`` (m: G aft of
Lpp/2, above the baseline), and the counts ``NOVEL NOHEAD NOFREQ NDOF``. Then, for each
speed, a line ``VEL SINK TRIM XMTN ZMTN`` (m/s, m, deg, and the motion reference point:
m aft of Lpp/2 and above the baseline), for each heading a line with the heading (deg),
for each wave frequency a line with the frequency (rad/s) and the data:

``.re7``  hydrodynamic coefficients, dimensional. Version 2 (line 10 reads ``-1 2``)
          has, after the counts, the 6×6 rigid-body mass matrix and per frequency six
          6×6 matrices: added mass, additional added mass, damping, additional damping,
          restoring, additional restoring, then a line of viscous roll damping (linear,
          quadratic, linearized). Version 1 has no ``-1 2`` line and only added mass,
          damping and restoring.
``.re8``  wave excitation per metre of wave amplitude: lines ``DOF Re Im`` (or
          ``DOF Re Im ReFK ImFK ReD ImD ReD0 ImD0`` with the Froude-Krylov and
          diffraction parts).
``.re1``  motion transfer functions, lines ``DOF Re Im`` (m/m, rad/m).
``.re2``  added resistance and mean drift: per speed and heading a line ``VEL HEAD``,
          then per frequency ``ω  R_x  F_y  M_z`` nondimensional, made dimensional with
          ρ g B²/L (forces) and ρ g B² (moment), as MSS's ``read_veres_WD.m`` does.

Conventions, checked against the data (see the tests):

* Axes: x aft, y to starboard, z up (MSS converts with diag(−1, 1, −1, −1, 1, −1) to
  Fossen axes). The reader rotates by π about z to cummins' z-up axes (x forward, y to
  port): matrices T M T, forces and motions T F with T = diag(−1, −1, 1, −1, −1, 1).
* Headings: VERES heading β_V is the direction of wave travel measured from +x (aft)
  towards +y (starboard), so 0 is head seas and 180 following seas: the heave and
  pitch excitation in long waves (imaginary pitch moment ρ g k ∫x² b dx with the sign of
  the direction of travel) and the surge motion −i of a particle in the wave say so.
  In cummins' axes the waves travel at β = β_V + π.
* Time dependence Re{X e^{iωt}}, as cummins: the ``.re1`` motions equal
  [−ω²(M + A + A_add) + iω(B + B_add + B_roll) + C]⁻¹ F of the ``.re7``/``.re8`` data
  (with −iω the heave and pitch responses come out wrong by tens of per cent).
* Moments and motions are about the motion reference point (XMTN, 0, ZMTN), which the
  dataset records as ``reference_point`` = (−XMTN, 0, ZMTN − T) in global coordinates
  (origin at Lpp/2, centre line, waterline; z up).
* Frequencies are wave frequencies. At forward speed VERES gives A and B for each
  heading (they depend on the encounter frequency); the reader takes them from the
  heading nearest 90° (beam seas, encounter = wave frequency), as MSS does.
* The additional added mass of version 2 (e.g. an anti-roll tank) goes to
  ``additional_added_mass`` (the motion RAOs of the ``.re1`` include it), additional
  damping and the linear viscous roll damping to ``additional_damping``, additional
  restoring to ``additional_stiffness``.

The ``.re7`` file is required (it holds the added mass); ``.re8``, ``.re1`` and
``.re2`` with the same stem are read when present. :func:`read_veres_transfer_function`
reads a ``.re8`` or ``.re1`` file alone.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import HydroDataError
from cummins.hydrodb import (
    DOF_NAMES,
    add_history,
    make_hydrodb,
    move_reference_point,
    stack_forward_speeds,
)
from cummins.io._common import DEPTH_ASSUMED, resolve_rho_g
from cummins.io._text import TextFile, check_cut_numbers
from cummins.kinematics import X_AFT_TO_X_FORWARD
from cummins.restoring import weight_record

__all__ = ["read_veres", "read_veres_transfer_function", "sniff", "sniff_dir"]

#: Title words of the first line of each VERES result file.
KINDS = {
    ".re7": "HYDRODYNAMIC COEFFICIENTS",
    ".re8": "WAVE EXCITATION FORCE TRANSFER FUNCTIONS",
    ".re1": "MOTION TRANSFER FUNCTIONS",
    ".re2": "ADDED RESISTANCE",
}
_T = np.diag(X_AFT_TO_X_FORWARD)
_NDOF = 6
_DOF_INDICES = np.arange(1.0, 7.0)


# --------------------------------------------------------------------------- detection


def file_kind(path: str | os.PathLike[str]) -> str | None:
    """Which VERES result file ``path`` is (``".re7"`` …), from its first line."""
    try:
        with open(path, "rb") as f:
            first = f.readline(400).decode("utf-8", errors="replace").upper()
    except OSError:
        return None
    if "VERES" not in first:
        return None
    for kind, title in KINDS.items():
        if title in first:
            return kind
    return None


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` a VERES ``.re7``, ``.re8``, ``.re1`` or ``.re2``?"""
    return Path(path).is_file() and file_kind(path) is not None


def sniff_dir(path: Path) -> list[Path]:
    """The VERES runs in a folder: one ``.re7`` per run (else the ``.re8``/``.re1`` files,
    so that reading them says the ``.re7`` is missing)."""
    files = [p for p in sorted(Path(path).iterdir()) if p.is_file()]
    kinds = {p: file_kind(p) for p in files if p.suffix.lower().startswith(".re")}
    runs = [p for p, k in kinds.items() if k == ".re7"]
    if runs:
        return runs
    stems = {}
    for p, k in kinds.items():
        if k in (".re8", ".re1"):
            stems.setdefault(p.with_suffix(""), p)
    return list(stems.values())


# --------------------------------------------------------------------------- parsing


@dataclass(frozen=True)
class _Header:
    rho: float
    g: float
    lpp: float
    breadth: float
    draught: float
    lcg: float
    vcg: float


@dataclass(frozen=True)
class _Speed:
    speed: float
    sinkage: float
    trim: float
    xmtn: float
    zmtn: float


class _Cursor:
    """Reads a VERES file line by line, with errors naming the line.

    The numbers of all lines from ``index`` on are converted in one go (a few
    milliseconds for the 26 000 lines of a ``.re7``); a line that does not hold the
    expected count falls back to :meth:`TextFile.numbers`, which says what is wrong.
    """

    def __init__(self, text: TextFile, index: int) -> None:
        self.text = text
        self.index = index
        lines = text.lines[index:]
        self._counts = np.array([len(line.split()) for line in lines] + [0])
        self._offsets = np.concatenate([[0], np.cumsum(self._counts)])
        try:
            self._values = np.array(" ".join(lines).split(), dtype=float)
        except ValueError:  # garbled or run-together numbers: parse line by line
            self._values = None
        self._start = index
        if self._values is not None and not np.all(np.isfinite(self._values)):
            bad = int(np.argmax(~np.isfinite(self._values)))
            line = int(np.searchsorted(self._offsets, bad, side="right")) - 1
            raise text.error(
                "non-finite value (NaN or Inf)",
                index + line,
                hint="the solver failed at this point or the file is damaged",
            )

    def take(self, count: int) -> NDArray[np.float64]:
        k = self.index - self._start
        if self._values is not None and k < len(self._counts) - 1 and self._counts[k] == count:
            values = self._values[self._offsets[k] : self._offsets[k] + count]
        else:
            values = self.text.numbers(self.index, count)
            if not np.all(np.isfinite(values)):
                raise self.text.error("non-finite value (NaN or Inf)", self.index)
        self.index += 1
        return values

    def rows(self, nrows: int, count: int) -> NDArray[np.float64]:
        """The next ``nrows`` lines of ``count`` numbers each, shape (nrows, count)."""
        k = self.index - self._start
        if (
            self._values is not None
            and np.all(self._counts[k : k + nrows] == count)
            and (k + nrows < len(self._counts))
        ):
            start = self._offsets[k]
            self.index += nrows
            return self._values[start : start + nrows * count].reshape(nrows, count)
        return np.vstack([self.take(count) for _ in range(nrows)])

    def error(self, message: str, back: int = 1, **kwargs) -> HydroDataError:
        return self.text.error(message, self.index - back, **kwargs)


def _header(text: TextFile, kind: str) -> tuple[_Header, _Cursor]:
    first = text.lines[0].upper() if text.lines else ""
    if "VERES" not in first or KINDS[kind] not in first:
        raise text.error(
            f"not a VERES {kind} file (first line should read '{KINDS[kind]} - VERES …')",
            0,
            hint="check the file name and extension",
        )
    if len(text) < 10:
        raise text.error("the file ends inside the header (truncated?)", len(text) - 1)
    cur = _Cursor(text, 6)
    rho, g = cur.take(2)
    lpp, breadth, draught = cur.take(3)
    if kind == ".re2":
        lcg = vcg = float("nan")
    else:
        lcg, vcg = cur.take(2)
    for name, value in (("density", rho), ("gravity", g), ("Lpp", lpp), ("breadth", breadth)):
        if not value > 0:
            raise text.error(
                f"{name} must be positive, found {value:g}",
                6 if name in ("density", "gravity") else 7,
            )
    return _Header(rho, g, lpp, breadth, draught, lcg, vcg), cur


def _counts(cur: _Cursor, n: int) -> list[int]:
    values = cur.take(n)
    if np.any(values < 1) or np.any(values != np.round(values)):
        raise cur.error("the counts (speeds, headings, frequencies, DOF) must be positive integers")
    return [int(v) for v in values]


def _expect_lines(cur: _Cursor, needed: int) -> None:
    """Fail early (before allocating) when the counts announce more lines than follow."""
    available = len(cur.text) - cur.index
    if needed > available:
        raise cur.error(
            f"the counts on this line announce {needed} more lines of data, but the file "
            f"ends after {available} (line {len(cur.text)}): truncated file or wrong counts",
        )


def _speed_line(cur: _Cursor) -> _Speed:
    return _Speed(*(float(v) for v in cur.take(5)))


class _Grid:
    """Collects headings and frequencies and checks they repeat identically."""

    def __init__(self, cur: _Cursor, nhead: int, nfreq: int) -> None:
        self.cur = cur
        self.headings = np.full(nhead, np.nan)
        self.freqs = np.full(nfreq, np.nan)

    def heading(self, h: int, value: float) -> None:
        self._check(self.headings, h, value, "heading", "deg")

    def frequency(self, k: int, value: float) -> None:
        if self.freqs[k] != self.freqs[k]:  # NaN: first block
            if not value > 0:
                raise self.cur.error(f"frequency {value:g} rad/s is not positive")
            if k > 0 and not value > self.freqs[k - 1]:
                raise self.cur.error(
                    f"frequency {value:g} rad/s does not increase (previous "
                    f"{self.freqs[k - 1]:g}): the frequency column is out of order",
                    hint="the file seems edited or damaged",
                )
        self._check(self.freqs, k, value, "frequency", "rad/s")

    def _check(self, store: NDArray, k: int, value: float, what: str, unit: str) -> None:
        old = float(store[k])
        if old != old:  # NaN: first occurrence
            store[k] = value
        elif abs(value - old) > 1e-6 * abs(old) + 1e-9:
            raise self.cur.error(
                f"{what} {value:g} {unit} differs from the {what} {store[k]:g} {unit} at the "
                "same position in the first block (damaged or joined file?)"
            )


@dataclass(frozen=True)
class _Re7:
    header: _Header
    version: int
    speeds: list[_Speed]
    headings: NDArray  # deg, VERES convention
    freqs: NDArray
    mass: NDArray  # 6×6, VERES axes
    blocks: NDArray  # (nspeed, nhead, nfreq, nblock, 6, 6)
    roll: NDArray  # (nspeed, nhead, nfreq, 3)


def _read_re7(path: Path) -> _Re7:
    text = TextFile.read(path)
    header, cur = _header(text, ".re7")
    marker = text.numbers(cur.index)
    if marker.size == 2 and marker[0] == -1:
        version = int(marker[1])
        if version != 2:
            raise cur.text.error(
                f"unknown .re7 file version {marker[1]:g}",
                cur.index,
                hint="versions 1 and 2 are supported",
            )
        cur.index += 1
    elif marker.size == 4:
        version = 1
    else:
        raise cur.text.error(
            "expected '-1 2' (version 2) or the counts NOVEL NOHEAD NOFREQ NDOF (version 1)",
            cur.index,
        )
    nvel, nhead, nfreq, ndof = _counts(cur, 4)
    if ndof != _NDOF:
        raise cur.error(
            f"NDOF = {ndof}: only rigid-body runs with 6 DOF are supported "
            "(air-cushion runs have 7)"
        )
    nblock = 6 if version == 2 else 3
    _expect_lines(cur, 6 + nvel * (1 + nhead * (1 + nfreq * (2 + 6 * nblock))))
    mass = np.vstack([cur.take(6) for _ in range(6)])
    blocks = np.empty((nvel, nhead, nfreq, nblock, 6, 6))
    roll = np.empty((nvel, nhead, nfreq, 3))
    grid = _Grid(cur, nhead, nfreq)
    speeds = []
    matrix_lines: list[int] = []
    first_line = np.empty((nvel, nhead, nfreq), dtype=int)
    for v in range(nvel):
        speeds.append(_speed_line(cur))
        for h in range(nhead):
            grid.heading(h, cur.take(1)[0])
            for k in range(nfreq):
                grid.frequency(k, cur.take(1)[0])
                first_line[v, h, k] = cur.index
                matrix_lines.extend(range(cur.index, cur.index + 6 * nblock))
                blocks[v, h, k] = cur.rows(6 * nblock, 6).reshape(nblock, 6, 6)
                roll[v, h, k] = cur.take(3)
    check_cut_numbers(text, matrix_lines, range(6))
    for v, speed in enumerate(speeds):
        if speed.speed == 0:
            _check_headings_alike(text, blocks[v], first_line[v], grid.headings)
    return _Re7(header, version, speeds, grid.headings, grid.freqs, mass, blocks, roll)


def _check_headings_alike(text: TextFile, blocks: NDArray, first_line: NDArray, headings) -> None:
    """At zero speed the matrices of every heading are the same (VERES writes them per
    heading for the encounter frequency, which equals the wave frequency without speed;
    the MSS supply: identical to the last digit): a row that differs was moved or edited.
    """
    scale = np.abs(blocks).max(axis=(0, 1, 3, 4), keepdims=True)  # per matrix
    off = np.abs(blocks - blocks[:1]) > 1e-6 * np.maximum(scale, 1e-300)
    if not off.any():
        return
    h, k, b, r, _ = np.argwhere(off)[0]
    raise text.error(
        f"at zero speed this row differs from the same row for heading {headings[0]:g} deg "
        f"(VERES writes the same matrices for every heading without speed): a row moved or "
        "edited?",
        int(first_line[h, k]) + 6 * int(b) + int(r),
        hint="the file is damaged; take it again from the VERES run",
    )


@dataclass(frozen=True)
class _TransferFunctions:
    header: _Header
    speeds: list[_Speed]
    headings: NDArray
    freqs: NDArray
    values: NDArray  # complex (nspeed, nhead, nfreq, 6), VERES axes
    froude_krylov: NDArray | None
    diffraction: NDArray | None


def _read_tf(path: Path, kind: str) -> _TransferFunctions:
    text = TextFile.read(path)
    header, cur = _header(text, kind)
    nvel, nhead, nfreq, ndof = _counts(cur, 4)
    if ndof != _NDOF:
        raise cur.error(f"NDOF = {ndof}: only rigid-body runs with 6 DOF are supported")
    _expect_lines(cur, nvel * (1 + nhead * (1 + nfreq * 7)))
    width = text.numbers(min(cur.index + 3, len(text) - 1)).size
    if width not in (3, 9):
        raise cur.text.error(
            f"expected rows 'DOF Re Im' (3 numbers) or with the Froude-Krylov and "
            f"diffraction parts (9), found {width}",
            cur.index + 3,
        )
    parts = np.empty((nvel, nhead, nfreq, 6, (width - 1) // 2), dtype=complex)
    grid = _Grid(cur, nhead, nfreq)
    speeds = []
    row_lines: list[int] = []
    for v in range(nvel):
        speeds.append(_speed_line(cur))
        for h in range(nhead):
            grid.heading(h, cur.take(1)[0])
            for k in range(nfreq):
                grid.frequency(k, cur.take(1)[0])
                row_lines.extend(range(cur.index, cur.index + 6))
                rows = cur.rows(6, width)
                dofs = rows[:, 0]
                if not np.array_equal(np.sort(dofs), _DOF_INDICES):
                    raise cur.error(
                        f"DOF indices {dofs.tolist()} in these 6 rows: expected each of 1…6 once",
                        back=6,
                    )
                parts[v, h, k, dofs.astype(int) - 1] = rows[:, 1::2] + 1j * rows[:, 2::2]
    check_cut_numbers(text, row_lines, range(1, width))
    fk = diffraction = None
    if width == 9:
        fk, diffraction = parts[..., 1], parts[..., 2]
    return _TransferFunctions(
        header, speeds, grid.headings, grid.freqs, parts[..., 0], fk, diffraction
    )


@dataclass(frozen=True)
class _Drift:
    speeds: NDArray
    headings: NDArray
    freqs: NDArray
    values: NDArray  # (nspeed, nhead, nfreq, 6), dimensional, VERES axes


def _read_re2(path: Path) -> _Drift:
    text = TextFile.read(path)
    header, cur = _header(text, ".re2")
    nvel, nhead, nfreq = _counts(cur, 3)
    _expect_lines(cur, nvel * nhead * (1 + nfreq))
    values = np.zeros((nvel, nhead, nfreq, 6))
    speeds = np.empty(nvel)
    grid = _Grid(cur, nhead, nfreq)
    scale = (
        header.rho * header.g * header.breadth**2 * np.array([1 / header.lpp, 1 / header.lpp, 1.0])
    )
    for v in range(nvel):
        for h in range(nhead):
            speeds[v], heading = cur.take(2)
            grid.heading(h, heading)
            start = cur.index
            rows = cur.rows(nfreq, 4)
            for k in range(nfreq):
                cur.index = start + k + 1  # so that an error names row k
                grid.frequency(k, rows[k, 0])
            values[v, h, :, [0, 1, 5]] = (rows[:, 1:] * scale).T
    return _Drift(speeds, grid.headings, grid.freqs, values)


# --------------------------------------------------------------------------- assembling


def _sibling(path: Path, suffix: str) -> Path | None:
    for candidate in (path.with_suffix(suffix), path.with_suffix(suffix.upper())):
        if candidate.is_file():
            return candidate
    return None


def _same(a: NDArray, b: NDArray, atol: float) -> bool:
    return a.shape == b.shape and bool(np.allclose(a, b, rtol=1e-6, atol=atol))


def _check_sibling(
    re7: _Re7,
    path: Path,
    speeds: NDArray,
    headings: NDArray,
    freqs: NDArray,
    freq_atol: float = 1e-9,
) -> None:
    """The sibling file must describe the same speeds, headings and frequencies."""
    ref_speeds = np.array([s.speed for s in re7.speeds])
    for what, mine, theirs, atol in (
        ("forward speeds (m/s)", speeds, ref_speeds, 1e-6),
        ("headings (deg)", headings, re7.headings, 1e-6),
        ("frequencies (rad/s)", freqs, re7.freqs, freq_atol),
    ):
        if not _same(mine, theirs, atol):
            raise HydroDataError(
                f"its {what} differ from those of the .re7 file "
                f"({np.round(mine[:6], 4).tolist()}… vs {np.round(theirs[:6], 4).tolist()}…)",
                path=path,
                hint="the .re7, .re8, .re1 and .re2 files must come from the same VERES run",
            )


def _beam_heading(headings: NDArray) -> int:
    return int(np.argmin(np.abs(np.mod(headings, 360.0) - 90.0)))


def _canonical_directions(headings_deg: NDArray) -> tuple[NDArray, NDArray]:
    """cummins wave directions (rad) of VERES headings, and the order that sorts them."""
    beta = np.mod(np.radians(headings_deg) + np.pi, 2 * np.pi)
    beta[np.isclose(beta, 2 * np.pi)] = 0.0
    order = np.argsort(beta, kind="stable")
    return beta[order], order


def _flip(m: NDArray) -> NDArray:
    """T M T for a stack of 6×6 matrices (VERES to cummins axes)."""
    return _T @ m @ _T


def read_veres(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    speed: float | None = None,
) -> xr.Dataset:
    """Read a ShipX/VERES run (``.re7`` + ``.re8``, ``.re1``, ``.re2``) into a ``HydroDB``.

    Parameters
    ----------
    path
        Any of the run's result files (or its stem); the ``.re7`` with the same stem is
        required, the others are read when present.
    rho, g
        Density (kg/m³) and gravity (m/s²): the files are dimensional and record both,
        so a differing value is an error.
    speed
        Forward speed (m/s) to read; by default all speeds of the run, along a
        ``forward_speed`` dimension when there are several.

    Returns
    -------
    xarray.Dataset
        ``HydroDB`` in cummins' z-up axes, about the VERES motion reference point.

    Raises
    ------
    HydroDataError
        Missing ``.re7``, malformed files (naming file and line), or siblings from
        another run.
    """
    path = Path(path)
    re7_path = path if file_kind(path) == ".re7" else _sibling(path, ".re7")
    if re7_path is None:
        raise HydroDataError(
            f"no {path.with_suffix('.re7').name} next to it: the added mass and damping of a "
            "VERES run are in the .re7 file, which cummins needs",
            path=path.with_suffix(".re7"),
            hint="export the .re7 from ShipX with the other result files; the excitation "
            "or motions alone can be read with read_veres_transfer_function",
        )
    re7 = _read_re7(re7_path)
    history = [
        f"read {re7_path.name} (.re7 version {re7.version})",
        "water depth not recorded in VERES files: deep water assumed",
    ]
    head = re7.header
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        head.rho,
        head.g,
        path=re7_path,
        history=history,
        dimensional=True,
        defaults=False,
    )

    waves: dict[str, NDArray] = {}
    re8_path = _sibling(re7_path, ".re8")
    if re8_path is not None:
        tf = _read_tf(re8_path, ".re8")
        _check_sibling(re7, re8_path, np.array([s.speed for s in tf.speeds]), tf.headings, tf.freqs)
        waves["excitation_force"] = tf.values
        if tf.froude_krylov is not None:
            waves["froude_krylov_force"] = tf.froude_krylov
            waves["diffraction_force"] = tf.diffraction
        history.append(f"excitation from {re8_path.name}")
    re1_path = _sibling(re7_path, ".re1")
    if re1_path is not None:
        tf = _read_tf(re1_path, ".re1")
        _check_sibling(re7, re1_path, np.array([s.speed for s in tf.speeds]), tf.headings, tf.freqs)
        waves["rao"] = tf.values
        history.append(f"motion RAOs from {re1_path.name}")
    re2_path = _sibling(re7_path, ".re2")
    if re2_path is not None:
        drift = _read_re2(re2_path)
        _check_sibling(re7, re2_path, drift.speeds, drift.headings, drift.freqs, freq_atol=6e-5)
        waves["drift_force"] = drift.values
        history.append(
            f"mean drift (surge: added resistance, sway, yaw) from {re2_path.name}, times "
            "rho g B^2/Lpp (forces) and rho g B^2 (yaw); heave, roll and pitch set to 0"
        )

    hi = _beam_heading(re7.headings)
    history.append(
        f"A, B, C from the heading {re7.headings[hi]:g} deg block (beam seas, encounter "
        "frequency = wave frequency); omega is the wave frequency"
    )
    history.append(
        "axes: VERES x aft, y starboard, z up rotated by pi about z to x forward, "
        "y port, z up; wave direction = VERES heading + 180 deg"
    )
    history.append("water depth not recorded in the VERES files: deep water assumed")
    beta, order = _canonical_directions(re7.headings)
    selected = _select_speeds(re7, speed, re7_path)
    datasets = []
    for v in selected:
        datasets.append(
            _speed_dataset(re7, v, hi, waves, beta, order, rho_v, g_v, re7_path, list(history))
        )
    first_point = datasets[0].attrs["reference_point"]
    for k, ds in enumerate(datasets):
        if not np.allclose(ds.attrs["reference_point"], first_point):
            datasets[k] = move_reference_point(ds, first_point)
    if len(datasets) == 1:
        return datasets[0]
    out = stack_forward_speeds(datasets)
    add_history(out, f"{len(datasets)} forward speeds")
    return out


def _select_speeds(re7: _Re7, speed: float | None, path: Path) -> list[int]:
    speeds = np.array([s.speed for s in re7.speeds])
    if speed is None:
        return list(range(speeds.size))
    hit = np.flatnonzero(np.isclose(speeds, speed, rtol=1e-4, atol=1e-3))
    if hit.size == 0:
        raise HydroDataError(
            f"no data at forward speed {speed:g} m/s",
            path=path,
            hint="the run has " + ", ".join(f"{s:g}" for s in speeds) + " m/s",
        )
    return [int(hit[0])]


def _speed_dataset(
    re7: _Re7,
    v: int,
    hi: int,
    waves: dict[str, NDArray],
    beta: NDArray,
    order: NDArray,
    rho: float,
    g: float,
    path: Path,
    history: list[str],
) -> xr.Dataset:
    head, sp = re7.header, re7.speeds[v]
    blocks = re7.blocks[v, hi]  # (nfreq, nblock, 6, 6)
    if re7.version == 2:
        a, a_add, b, b_add, c, c_add = (blocks[:, k] for k in range(6))
    else:
        a, b, c = (blocks[:, k] for k in range(3))
        a_add = b_add = c_add = np.zeros_like(a)
    extra: dict = {
        "hydrostatic_stiffness": _flip(_frequency_independent(c, "restoring", history)),
        "inertia_matrix": _flip(re7.mass),
    }
    damping = b_add.copy()
    damping[:, 3, 3] += re7.roll[v, hi, :, 0]
    if np.any(damping):
        extra["additional_damping"] = _flip(damping)
        history.append(
            "additional_damping = additional damping matrix + linear viscous "
            "roll damping of the .re7 (the quadratic and linearized roll damping "
            "are not included)"
        )
    if np.any(c_add):
        extra["additional_stiffness"] = _flip(
            _frequency_independent(c_add, "additional restoring", history)
        )
    if np.any(a_add):
        extra["additional_added_mass"] = _flip(a_add)
        history.append(
            "additional_added_mass = the .re7 additional added mass (e.g. an anti-roll "
            "tank; the .re1 motion RAOs include it)"
        )
    if sp.sinkage or sp.trim:
        history.append(
            f"sinkage {sp.sinkage:g} m and trim {sp.trim:g} deg at "
            f"{sp.speed:g} m/s are not applied to the reference point"
        )
    if waves:
        extra["wave_direction"] = beta
        for name, values in waves.items():
            data = values[v][order].transpose(1, 0, 2)  # (nfreq, nhead, 6)
            extra[name] = data @ _T
    return make_hydrodb(
        re7.freqs,
        _flip(a),
        _flip(b),
        rho=rho,
        g=g,
        source_format="veres",
        source_file=str(path),
        dofs=list(DOF_NAMES),
        forward_speed=sp.speed,
        reference_point=(-sp.xmtn, 0.0, sp.zmtn - head.draught),
        history=history,
        center_of_gravity=np.array([-head.lcg, 0.0, head.vcg - head.draught]),
        **weight_record(  # VERES's restoring is rho g V GM: the weight at LCG, VCG
            [float(re7.mass[0, 0])],
            [-head.lcg, 0.0, head.vcg - head.draught],
            f"{path.name} restoring (VERES: rho g V GM, the weight at LCG, VCG)",
        ),
        ship_length=head.lpp,
        **{DEPTH_ASSUMED: 1},
        ship_breadth=head.breadth,
        ship_draught=head.draught,
        **extra,
    )


def _frequency_independent(m: NDArray, what: str, history: list[str]) -> NDArray:
    first = m[0]
    scale = max(float(np.abs(m).max()), 1e-300)
    if float(np.abs(m - first[None]).max()) > 1e-7 * scale:
        history.append(
            f"the {what} matrix varies with frequency: its value at the lowest frequency is used"
        )
    return first


def read_veres_transfer_function(path: str | os.PathLike[str]) -> xr.DataArray:
    """Read a VERES ``.re8`` (excitation) or ``.re1`` (motion RAO) file on its own.

    Parameters
    ----------
    path
        The ``.re8`` or ``.re1`` file.

    Returns
    -------
    xarray.DataArray
        Complex, dims (``forward_speed``, ``omega``, ``wave_direction``, ``dof``), in
        cummins' z-up axes and wave directions, about the motion reference point
        (attribute ``reference_point``); N/m, N·m/m or m/m, rad/m.
    """
    path = Path(path)
    kind = file_kind(path)
    if kind not in (".re8", ".re1"):
        raise HydroDataError("not a VERES .re8 or .re1 file", path=path)
    tf = _read_tf(path, kind)
    beta, order = _canonical_directions(tf.headings)
    values = tf.values[:, order].transpose(0, 2, 1, 3) @ _T
    sp = tf.speeds[0]
    return xr.DataArray(
        values,
        dims=("forward_speed", "omega", "wave_direction", "dof"),
        coords={
            "forward_speed": ("forward_speed", [s.speed for s in tf.speeds], {"units": "m/s"}),
            "omega": ("omega", tf.freqs, {"units": "rad/s"}),
            "wave_direction": ("wave_direction", beta, {"units": "rad"}),
            "dof": list(DOF_NAMES),
        },
        name="excitation_force" if kind == ".re8" else "rao",
        attrs={
            "source_file": str(path),
            "reference_point": np.array([-sp.xmtn, 0.0, sp.zmtn - tf.header.draught]),
            "axis_convention": "z-up",
            "time_convention": "x(t) = Re{X exp(i omega t)}",
        },
    )
