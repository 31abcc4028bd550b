"""The input files of a WAMIT run read besides its output: ``.cfg`` (NEWMDS per body,
IALTFRC, IPEROUT/IPERIO), ``.pot`` (the bodies' geometry file names) and ``.mmx``
(WAMIT's echo of the normalized mass matrix and of the external force matrices).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from cummins.io._text import (
    parse_numbers,
)
from cummins.io.wamit.text import _leading_numbers, _numeric_rows, _read_text


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
