"""WAMIT numeric files, nondimensional: ``.1`` (added mass and damping per frequency,
with the ω = 0 and ω = ∞ limit rows), ``.3`` and ``.4`` (excitation and motion RAOs per
frequency, heading and DOF) and ``.hst`` (hydrostatics).

The limit rows: in a period column, −1 is T = ∞ (ω = 0) and 0 is T = 0 (ω = ∞); in a
frequency or wavenumber column (HAMS), 0 is ω = 0 and −1 is ω = ∞. A wavenumber column
gives ω by the dispersion relation ω² = g k tanh(k h) (deep water ω² = g k).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError
from cummins.io._text import (
    TextFile,
)
from cummins.io.wamit.text import _numeric_rows, _read_text, _title_lines

#: First-column kinds of the numeric files.
FIRST_COLUMNS = ("period", "omega", "wavenumber", "wavenumber_deep", "wavelength")


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
    periods = np.asarray(periods, dtype=float)
    starts = np.flatnonzero(np.diff(periods, prepend=np.nan) != 0)
    interleaved = np.unique(periods[starts]).size < starts.size
    keys = np.column_stack([periods, key_columns])
    if interleaved or np.unique(keys, axis=0).shape[0] < len(keys):  # the loop names the line
        _period_block_error(text, periods, where, key_columns)
    ends = [*starts[1:], periods.size]
    return [(float(periods[a]), np.arange(a, b)) for a, b in zip(starts, ends, strict=True)]


def _period_block_error(
    text: TextFile, periods: np.ndarray, where: np.ndarray, key_columns: np.ndarray
) -> None:
    """The error of :func:`_period_blocks` at the first row in fault: a key seen before,
    or a period whose rows are not contiguous."""
    seen_at: dict[float, int] = {}
    keys_seen: dict[tuple, int] = {}
    keys = key_columns.tolist()
    previous = None
    for r, per in enumerate(periods.tolist()):
        key = (per, *keys[r])
        if key in keys_seen:
            raise text.error(
                f"entry {tuple(float(k) for k in key)} appears twice (first on line "
                f"{where[keys_seen[key]] + 1})",
                where[r],
                hint="the file is damaged or two runs were joined",
            )
        keys_seen[key] = r
        if per != previous:
            if per in seen_at:
                raise text.error(
                    f"rows of period {per:g} are not contiguous (also on line "
                    f"{where[seen_at[per]] + 1}): the first column is out of order",
                    where[r],
                    hint="WAMIT writes one block per period; the file seems edited or damaged",
                )
            seen_at[per] = r
            previous = per


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
    if n_file < n:
        # WAMIT writes every entry of the matrix of all n modes: a shorter file is cut
        # (cut in its first line, the all-zero restoring would read as a good one)
        raise text.error(
            f"the file lists the entries of a {n_file}×{n_file} matrix, the run has {n} "
            "modes (truncated?)",
            len(text) - 1,
        )
    if not seen[:n_file, :n_file].all():
        a, b = np.argwhere(~seen[:n_file, :n_file])[0]
        raise text.error(
            f"entry C({a + 1},{b + 1}) missing: the file lists every entry of the "
            f"{n_file}×{n_file} matrix (truncated or edited?)",
            len(text) - 1,
        )
    return c
