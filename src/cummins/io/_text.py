"""Reading numeric text files written by Fortran solvers, with errors that name the line."""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError
from cummins.files import note_read

#: A Fortran-style real: 1.0, -1.E+03, 1.0D-02, .5, 12 — also when numbers run together
#: without a space ("1.2E+03-4.5E+01"), as fixed-width Fortran output sometimes does.
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?")
_NON_NUMERIC = re.compile(r"[^\s0-9.eEdD+\-]")


@dataclass(frozen=True)
class TextFile:
    """The lines of a text file, for parsing with line-accurate error messages.

    Line numbers in messages are 1-based, as an editor shows them; indices in the
    methods are 0-based, as Python counts.
    """

    path: Path
    lines: tuple[str, ...]

    @classmethod
    def read(cls, path: str | os.PathLike[str]) -> TextFile:
        """Read ``path``; a missing, empty or binary file raises :class:`HydroDataError`."""
        p = Path(path)
        note_read(p)
        try:
            raw = p.read_bytes()
        except FileNotFoundError:
            raise HydroDataError("file not found", path=p) from None
        except IsADirectoryError:
            raise HydroDataError("expected a file, found a directory", path=p) from None
        except OSError as exc:
            raise HydroDataError(f"cannot read the file ({exc.strerror})", path=p) from None
        return cls.from_bytes(p, raw)

    @classmethod
    def from_bytes(cls, path: Path, raw: bytes) -> TextFile:
        """The text of ``raw``, the bytes read from ``path`` (see :meth:`read`, which
        also records the file as read); an empty or binary content raises
        :class:`HydroDataError`."""
        p = path
        if not raw.strip():
            raise HydroDataError("the file is empty", path=p)
        if b"\x00" in raw[:65536]:
            raise HydroDataError(
                "this is a binary file, not a text output file",
                path=p,
                hint="check the file name and format",
            )
        text = raw.decode("utf-8-sig", errors="replace")  # a byte-order mark is not text
        return cls(p, tuple(text.splitlines()))

    def __len__(self) -> int:
        return len(self.lines)

    def error(self, message: str, index: int | None = None, **kwargs) -> HydroDataError:
        """A :class:`HydroDataError` at line ``index`` (0-based) of this file."""
        return HydroDataError(
            message, path=self.path, line=None if index is None else index + 1, **kwargs
        )

    def numbers(self, index: int, count: int | None = None, *, at_least: int | None = None):
        """The numbers on line ``index`` (0-based) as a float array.

        Parameters
        ----------
        index
            0-based line index.
        count
            Exact number of values expected (error otherwise).
        at_least
            Minimum number of values expected.
        """
        if index >= len(self.lines):
            raise self.error("the file ends too early (truncated?)", len(self.lines) - 1)
        values = parse_numbers(self.lines[index])
        if values is None:
            raise self.error(f"expected numbers, found {self.lines[index].strip()[:60]!r}", index)
        if count is not None and values.size != count:
            raise self.error(f"expected {count} numbers, found {values.size}", index)
        if at_least is not None and values.size < at_least:
            raise self.error(f"expected at least {at_least} numbers, found {values.size}", index)
        return values

    def find(self, pattern: str | re.Pattern[str], start: int = 0, stop: int | None = None) -> int:
        """Index of the first line at or after ``start`` matching ``pattern`` (regex), or −1."""
        rx = re.compile(pattern) if isinstance(pattern, str) else pattern
        end = len(self.lines) if stop is None else min(stop, len(self.lines))
        for i in range(start, end):
            if rx.search(self.lines[i]):
                return i
        return -1


def check_cut_numbers(text: TextFile, lines, columns, *, minimum_rows: int = 10) -> None:
    """Error on a number shorter than the others of its column in fixed-format output.

    Fortran solvers write every value of a column in the same format (``0.123456E+05``):
    a value with fewer characters than all but at most one in fifty of the others (at
    least one deviant is allowed for) is a cut or edited line, which would otherwise
    read as a plausible smaller number. Free-format columns (widths that vary) and
    tables shorter than ``minimum_rows`` are not checked.

    Parameters
    ----------
    text
        The file.
    lines
        0-based indices of the table's lines.
    columns
        Indices of the whitespace-separated fields to check (the values, not labels).
    """
    lines = [int(i) for i in lines]
    if len(lines) < minimum_rows:
        return
    fields = [text.lines[i].split() for i in lines]
    widths = [len(f) for f in fields]
    for c in columns:
        rows = [k for k, w in enumerate(widths) if w > c]
        if len(rows) < minimum_rows:
            continue
        digits = [fields[k][c].lstrip("+-") for k in rows]
        lengths = np.fromiter(map(len, digits), int, len(rows))
        values, counts = np.unique(lengths, return_counts=True)
        if counts.max() < lengths.size - max(1, int(0.02 * lengths.size)):
            continue  # free format: no fixed width to check against
        usual = values[np.argmax(counts)]
        short = np.flatnonzero(lengths < usual)
        if short.size:
            k = rows[short[0]]
            raise text.error(
                f"the number {fields[k][c]!r} is shorter than the others of its column "
                f"({lengths[short[0]]} characters, not {usual}): a cut or edited line",
                lines[k],
                hint="the file is damaged; take it again from the solver run",
            )


def check_line_ends(text: TextFile, lines, *, minimum_rows: int = 10) -> None:
    """Error on a row that ends before the others of its table in fixed-column output.

    Fortran writes every row of a table in one format, numbers right-aligned in fields
    of fixed width, so every row ends at the same column; a row that ends before all
    but at most one in fifty of the others (at least one deviant is allowed for) was
    cut short, which a number of free width (a phase in whole degrees: ``-177`` cut to
    ``-17``) would otherwise hide. Tables whose rows end at varying columns, shorter
    than ``minimum_rows``, or holding tabs (columns unknown) are not checked.

    Parameters
    ----------
    text
        The file.
    lines
        0-based indices of the table's lines (rows of one layout: same fields).
    """
    lines = [int(i) for i in lines]
    if len(lines) < minimum_rows or any("\t" in text.lines[i] for i in lines):
        return
    ends = np.fromiter((len(text.lines[i].rstrip()) for i in lines), int, len(lines))
    values, counts = np.unique(ends, return_counts=True)
    if counts.max() < ends.size - max(1, int(0.02 * ends.size)):
        return  # free format: rows of varying length
    usual = values[np.argmax(counts)]
    short = np.flatnonzero(ends < usual)
    if short.size:
        raise text.error(
            f"this row ends at column {ends[short[0]]}, the others of its table at "
            f"column {usual}: a cut or edited line",
            lines[short[0]],
            hint="the file is damaged; take it again from the solver run",
        )


def parse_numbers(line: str) -> np.ndarray | None:
    """All numbers of a line, or ``None`` if the line holds anything but numbers.

    Fortran ``D`` exponents are accepted, as are numbers written without a space
    between them. NaN and Inf, as some solvers write them, are returned as such (the
    dataset validation then reports them with their frequency and DOF).

    Examples
    --------
    >>> parse_numbers(" 1.0D+00  -2.5E-01 3")
    array([ 1.  , -0.25,  3.  ])
    >>> parse_numbers("1.2E+03-4.5E+01")
    array([1200.,  -45.])
    >>> parse_numbers("PERIOD = 3") is None
    True
    """
    fields = line.split()
    if not fields:
        return np.empty(0)
    try:
        return np.array([float(f.replace("D", "E").replace("d", "e")) for f in fields])
    except ValueError:
        pass
    lowered = line.lower()
    if "nan" in lowered or "inf" in lowered:
        try:
            return np.array([float(f) for f in fields])
        except ValueError:
            return None
    if _NON_NUMERIC.search(line):
        return None
    found = _NUMBER.findall(line)
    if not found or "".join(found) != "".join(fields):
        return None
    return np.array([float(f.replace("D", "E").replace("d", "e")) for f in found])


def numeric_table(
    text: TextFile, start: int = 0, stop: int | None = None, *, columns: int | tuple[int, ...]
) -> tuple[np.ndarray, np.ndarray]:
    """Parse the numeric rows of ``text.lines[start:stop]``, skipping blank lines.

    Parameters
    ----------
    columns
        Allowed numbers of values per row (an int or a tuple of ints). Rows with
        fewer values are padded with NaN up to the largest allowed width.

    Returns
    -------
    table : ndarray, shape (nrows, max(columns))
    line_index : ndarray of int, shape (nrows,)
        0-based line index of each row, for error messages.
    """
    allowed = (columns,) if isinstance(columns, int) else tuple(columns)
    width = max(allowed)
    end = len(text.lines) if stop is None else stop
    where = [i for i in range(start, end) if text.lines[i].strip()]
    if not where:
        raise text.error("no numeric data found", start)
    fast = _fast_table(text, where, allowed, width)
    if fast is not None:
        return fast, np.asarray(where)
    rows: list[np.ndarray] = []
    for i in where:  # slow path: find the first bad line and say what is wrong with it
        line = text.lines[i]
        values = parse_numbers(line)
        if values is None:
            raise text.error(f"expected a row of numbers, found {line.strip()[:60]!r}", i)
        if values.size not in allowed:
            expected = " or ".join(str(c) for c in allowed)
            raise text.error(f"expected {expected} numbers on the row, found {values.size}", i)
        if not np.all(np.isfinite(values)):
            raise text.error(
                "non-finite value (NaN or Inf) in the data",
                i,
                hint="the solver failed at this point; rerun it or remove the frequency",
            )
        if values.size < width:
            values = np.concatenate([values, np.full(width - values.size, np.nan)])
        rows.append(values)
    return np.vstack(rows), np.asarray(where)


def _fast_table(
    text: TextFile, where: list[int], allowed: tuple[int, ...], width: int
) -> np.ndarray | None:
    """Vectorised parse of well-formed rows; ``None`` sends the caller to the slow path."""
    fields = [text.lines[i].split() for i in where]
    sizes = np.fromiter((len(f) for f in fields), dtype=int, count=len(fields))
    if not np.isin(sizes, allowed).all():
        return None
    table = np.full((len(fields), width), np.nan)
    try:
        for size in np.unique(sizes):
            rows = np.flatnonzero(sizes == size)
            values = np.array([fields[r] for r in rows], dtype=float)
            table[rows, :size] = values
    except ValueError:
        return None
    for size in np.unique(sizes):
        rows = np.flatnonzero(sizes == size)
        if not np.isfinite(table[rows, :size]).all():
            return None
    return table
