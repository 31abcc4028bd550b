"""Line-level reading of WAMIT files: the text without a byte-order mark, title lines,
numeric tables with the damage checks of fixed-format Fortran output (cut numbers,
missing-value markers beyond :data:`MAX_ABS_VALUE`), and the leading numbers of a line
of an input file.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from cummins.files import note_read
from cummins.io._text import (
    TextFile,
    check_cut_numbers,
    numeric_table,
    parse_numbers,
)

#: Largest magnitude a WAMIT number can plausibly have; beyond it a value is a
#: missing-value marker (−9.99E99) or damage.
MAX_ABS_VALUE = 1e30


def _read_text(path: Path) -> TextFile:
    """:meth:`TextFile.read` without a UTF-8 byte-order mark (not damage)."""
    return _without_bom(TextFile.read(path))


def _without_bom(text: TextFile) -> TextFile:
    """``text`` without a (second) UTF-8 byte-order mark at its start."""
    if text.lines and text.lines[0].startswith("\ufeff"):
        return TextFile(text.path, (text.lines[0][1:], *text.lines[1:]))
    return text


def has_out_banner(raw: bytes) -> bool:
    """True if ``raw``, the first bytes of a file, start a WAMIT ``.out`` log (its banner
    within the first 4096 bytes)."""
    head = raw[:4096].decode("utf-8", errors="replace")
    return "WAMIT" in head and ("Version" in head or "POTEN" in head or "Output from" in head)


def _read_out_log(path: Path) -> TextFile | None:
    """The text of the WAMIT ``.out`` log ``path``, the file read once; ``None`` when it
    cannot be read or has no WAMIT banner (not a log). An empty or binary log raises
    :class:`HydroDataError` as :meth:`TextFile.read` does."""
    try:
        raw = Path(path).read_bytes()
    except OSError:
        return None
    if not has_out_banner(raw):
        return None
    note_read(Path(path))
    return _without_bom(TextFile.from_bytes(Path(path), raw))


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


def _leading_numbers(line: str) -> list[float]:
    """The numbers at the start of a line of an input file (comments may follow)."""
    out: list[float] = []
    for token in line.split():
        value = parse_numbers(token)
        if value is None or value.size != 1:
            break
        out.append(float(value[0]))
    return out
