"""Recognising WAMIT files by their content: the numeric files ``.1``, ``.3`` (and
``.4``), ``.hst`` (:func:`numeric_kind`) and the ``.out`` log (:func:`is_out_file`); the
runs in a folder (:func:`sniff_dir`) and the sibling files of a run (same stem).
"""

from __future__ import annotations

import os
from pathlib import Path

from cummins.io._text import (
    parse_numbers,
)
from cummins.io.wamit.text import _head_lines, has_out_banner


def numeric_kind(path: str | os.PathLike[str]) -> str | None:
    """Which WAMIT numeric file ``path`` is by its content: ``".1"``, ``".3"``, ``".hst"``,
    or a second-order file: ``".8"`` (mean drift, also ``.7``/``.9``) or ``".12"`` (a QTF,
    ``.10d`` … ``.12s``).

    ``.1`` rows are ``PER I J A [B]``, ``.3`` (and ``.4``) rows ``PER BETA I Mod Pha Re
    Im``, ``.hst`` rows ``I J C``, mean-drift rows ``PER BETA1 BETA2 I Mod Pha Re Im`` and
    QTF rows ``PER1 PER2 BETA1 BETA2 I Mod Pha Re Im`` (I negative for moments in body
    axes); the integer columns must hold DOF indices. A first line of text (a title) is
    allowed; a QTF's must be WAMIT's (NEMOH writes rows of the same width).
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
    if widths == {8} and all(is_dof(abs(r[3])) for r in rows):
        return ".8"
    titled = parse_numbers(first) is None
    if widths == {9} and all(is_dof(abs(r[4])) for r in rows) and (not titled or "WAMIT" in first):
        return ".12"
    return None


def is_out_file(path: str | os.PathLike[str]) -> bool:
    """True if ``path`` is a WAMIT ``.out`` log (by its banner)."""
    try:
        with open(path, "rb") as f:
            head = f.read(4096)
    except OSError:
        return False
    return has_out_banner(head)


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


def _sibling(path: Path, suffix: str) -> Path | None:
    for candidate in (path.with_suffix(suffix), path.with_suffix(suffix.upper())):
        if candidate.is_file():
            return candidate
    return None
