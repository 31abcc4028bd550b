"""The companion files of a NEMOH run: its square matrices and ``Hydrostatics.dat``.

``KH.dat`` (the 6×6 hydrostatic stiffness per body, N/m, N, N·m/rad, as NEMOH wrote
it), ``Mechanics/Inertia.dat``, ``Kh.dat``, ``Km.dat`` and ``Badd.dat`` hold a 6N×6N
matrix, one row per line, symmetric to the printed digits; ``Hydrostatics.dat`` the
centre of buoyancy ``XF YF ZF``, the centre of gravity ``XG YG ZG``, the displaced
volume (m³) and, in v3, the mass. With several bodies they come as ``KH_0.dat`` … per
body in the order of ``Nemoh.cal`` (a ``KH.dat`` beside them is the mesher's file of
the last mesh it processed).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from cummins.io._text import TextFile, parse_numbers
from cummins.io.nemoh.files import _NUMBER, _find, _Run

# --------------------------------------------------------------------------- companion files

#: Magnitude beyond any floating body's coefficient (kg·m² of a 10⁹ kg hull 10³ m from
#: its reference point is 10¹⁵): larger numbers are sentinels (-9.99e99) or damage.
IMPLAUSIBLE = 1e20

#: Largest relative asymmetry |M - Mᵀ| / max|M| of the matrices NEMOH writes
#: (KH.dat, Inertia.dat: symmetric to the printed digits, 1e-7 in the corpus).
SYMMETRY_TOLERANCE = 1e-4


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
