"""The header of a WAMIT ``.out`` log: the constants (g, ULEN, ρ, water depth) and,
per body, the origin (XBODY, YBODY, ZBODY), volumes, centres of buoyancy and gravity,
radii of gyration and hydrostatic coefficients; the hydrostatic matrix built from them
(C46 and C56 are the gravitational moments WAMIT adds, unsymmetric as in the ``.hst``).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from cummins.io._text import (
    TextFile,
    parse_numbers,
)
from cummins.io.wamit.text import MAX_ABS_VALUE

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


def _hydrostatics_matrix(header: _OutHeader, layout: list[int]) -> np.ndarray:
    n = sum(layout)
    c = np.zeros((n, n))
    offset = 0
    for body, m in zip(header.bodies, layout, strict=False):
        c[offset : offset + 6, offset : offset + 6] = _hydrostatics_from_out(body.hydrostatics)
        offset += m
    return c
