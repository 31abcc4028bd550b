"""The pages of an AQWA listing: which structure each describes, and the wave grid.

A listing is printed in pages, each opened by Fortran's carriage control ``1`` alone on
a line. A page about one structure names it in its title block ("… FOR STRUCTURE 2",
"… OF STRUCTURE 2", "STRUCTURE NUMBER 2"); the pages that name none (the input echo,
global parameters, coordinates, the wave frequency table) are common to all. A
listing of several structures prints each structure's pages in turn, in the layout of
a one-structure listing (:func:`structure_view` blanks the other structures' pages,
keeping the line numbers, so that the one-structure readers of :mod:`.lis` read it).

The table "WAVE FREQUENCIES/PERIODS AND DIRECTIONS" (:func:`wave_grid`) comes in two
layouts:

* AQWA 19.1 (the corpus's PEND hull): the frequency rows (``structure index ω Hz T k λ
  size D/L kD`` then ``*UNDEFINED`` in the PARAMETERS column, the structure number on
  the first row of each structure), and on a page of its own "STRUCTURE DIRECTIONS 1 2
  …" with a row ``structure β₁ β₂ …`` per structure;
* AQWA 2023 R1 (BEMRosetta's ``examples/aqwa/line/Box1``, ``Box2``): each structure's
  frequency rows followed, inside the same table, by an indented sub-table "DIRECTIONS
  1 2 3 …" between dashed rules and its row of directions, then a full-width rule
  before the next structure's rows.

Both are read alike; the directions announced by the sub-table's indices must all be
listed, the frequency indices must run 1, 2, … without a gap, and every structure must
have the same frequencies and directions (cummins holds one grid).
"""

from __future__ import annotations

import itertools
import re
from dataclasses import dataclass

import numpy as np

from cummins.io._text import TextFile

_STRUCTURE = re.compile(r"(?:FOR|OF) STRUCTURE (\d+)|STRUCTURE NUMBER (\d+)")
_TITLE = "WAVE FREQUENCIES/PERIODS AND DIRECTIONS"
#: Lines of a page's title block searched for the structure it describes.
_TITLE_LINES = 8


def despace(line: str) -> str:
    """``* * * * H Y D R O   P A R`` → ``****HYDRO PAR`` (AQWA's letter-spaced titles)."""
    return re.sub(r"\s+", " ", re.sub(r"(?<=\S) (?=\S)", "", line.strip()))


@dataclass(frozen=True)
class Page:
    """Lines ``start`` (the carriage control) to ``stop`` (excluded) of a listing, about
    ``structure`` (None: common to all)."""

    start: int
    stop: int
    structure: int | None


def pages(text: TextFile) -> list[Page]:
    """The listing's pages (the text before the first page is common).

    A page starts at a carriage control ``1``, or at a title line (``* * * *``) more than
    a title block below the last start: a listing whose ``1`` was lost still splits at
    the next title, so that no page of one structure is read as part of another's."""
    starts = []
    for i, line in enumerate(text.lines):
        if line.strip() == "1" or (
            "* * * *" in line and (not starts or i - starts[-1] > _TITLE_LINES)
        ):
            starts.append(i)
    bounds = [0, *starts, len(text.lines)]
    out = []
    for start, stop in itertools.pairwise(bounds):
        structure = None
        if start in starts:
            for line in text.lines[start : min(stop, start + 1 + _TITLE_LINES)]:
                m = _STRUCTURE.search(despace(line))
                if m:
                    structure = int(m.group(1) or m.group(2))
                    break
        if stop > start:
            out.append(Page(start, stop, structure))
    return out


#: Lines of the data a structure's pages hold (read per structure): on a page that names
#: no structure, in a listing of several, they would be read for every structure.
_STRUCTURE_DATA = re.compile(
    r"WAVE PERIOD\s*=|WAVE FREQUENCY\s*=|^\s*STIFFNESS MATRIX\s*$|\bGX\s*=|"
    r"VARIATION WITH WAVE PERIOD/FREQUENCY|\(RADIANS/SEC\)|^\s*ADDED\s+MASS\s*$|"
    r"^\s*DAMPING\s*$|CENTRE OF GRAVITY|MESH BASED DISPLACEMENT|INERTIA MATRIX"
)


def check_structure_pages(text: TextFile, listing: list[Page]) -> None:
    """Error on a page of a several-structure listing that holds a structure's data but
    names no structure (its title lost or edited): it cannot be told whose it is."""
    for page in listing:
        if page.structure is not None:
            continue
        for k in range(page.start, page.stop):
            if _STRUCTURE_DATA.search(text.lines[k]):
                raise text.error(
                    "structure data on a page that names no structure (its title lost or "
                    "edited?): in a listing of several structures it cannot be told whose",
                    k,
                )


def structures(listing: list[Page]) -> list[int]:
    """The structure numbers the pages name, in increasing order."""
    return sorted({p.structure for p in listing if p.structure is not None})


def structure_view(text: TextFile, listing: list[Page], structure: int) -> TextFile:
    """The listing with the pages of every other structure blanked (same line numbers)."""
    lines = list(text.lines)
    for page in listing:
        if page.structure is not None and page.structure != structure:
            lines[page.start : page.stop] = [""] * (page.stop - page.start)
    return TextFile(text.path, tuple(lines))


# --------------------------------------------------------------------------- wave grid


@dataclass
class _Grid:
    omega: list[float]
    index: list[int]
    directions: list[float]
    announced: list[int]
    first_line: int


def _is_rule(line: str) -> bool:
    stripped = line.strip()
    return bool(stripped) and set(stripped) <= set("-")


def _is_int(token: str) -> bool:
    return token.isdigit()


def _number(token: str) -> float | None:
    try:
        value = float(token)
    except ValueError:
        return None
    return value if np.isfinite(value) else None


def wave_grid(text: TextFile, listing: list[Page]) -> tuple[dict[int, tuple], int]:
    """Frequencies (rad/s) and directions (deg) of each structure, and the table's line.

    Returns
    -------
    grids, line
        {structure: (omega, directions)}, checked complete; the 0-based line of the
        table's first row (for messages).
    """
    tables = [
        p
        for p in listing
        if any(_TITLE in despace(line) for line in text.lines[p.start : p.start + 4])
    ]
    if not tables:
        raise text.error(f"no {_TITLE} table (truncated?)")
    grids: dict[int, _Grid] = {}
    for page in tables:
        _read_page(text, page, grids)
    if not grids:
        raise text.error("the wave frequency table is empty", tables[0].start)
    out = {}
    for structure, grid in sorted(grids.items()):
        out[structure] = _checked(text, structure, grid)
    return out, min(g.first_line for g in grids.values())


def _read_page(text: TextFile, page: Page, grids: dict[int, _Grid]) -> None:
    """The rows of one page of the table into ``grids``."""
    mode = None  # "frequency" or "direction"
    inner = False  # the directions sub-table inside the frequency table, as AQWA 2023 R1 prints it
    current: int | None = max(grids) if grids else None  # structure of the last rows
    for k in range(page.start + 1, page.stop):
        line = text.lines[k]
        stripped = line.strip()
        if not stripped or stripped.startswith("*") or set(stripped) <= set("- "):
            if inner and _is_rule(line) and not line.startswith("  "):
                mode, inner = "frequency", False  # full-width rule: the next structure
            continue
        words = stripped.split()
        if words[0] == "STRUCTURE":
            mode = "direction" if "DIRECTIONS" in words else "frequency"
            if mode == "direction":
                targets = list(grids)
                _announce(text, k, words[words.index("DIRECTIONS") + 1 :], grids, targets)
            continue
        if words[0] == "DIRECTIONS":
            if current is None:
                raise text.error("a directions sub-table before any frequency row", k)
            mode, inner = "direction", True
            _announce(text, k, words[1:], grids, [current])
            continue
        if words[0].startswith("("):  # the second header line: units
            continue
        if mode is None:
            raise text.error(f"expected the table's header, found {stripped[:60]!r}", k)
        if mode == "frequency":
            current = _frequency_row(text, k, words, grids, current)
            continue
        if not inner and _is_int(words[0]):  # AQWA 19.1: "structure β₁ β₂ …"
            current = int(words[0])
            if current not in grids:
                raise text.error(f"directions of structure {current}, which has no frequencies", k)
            words = words[1:]
        if current is None:
            raise text.error("a row of directions before any frequency row", k)
        _direction_row(text, k, words, grids[current])


def _announce(text: TextFile, k: int, words: list[str], grids, targets: list[int]) -> None:
    """The direction indices a "DIRECTIONS 1 2 …" header announces, for ``targets``."""
    if not words or not all(_is_int(w) for w in words):
        raise text.error("expected the direction numbers after DIRECTIONS", k)
    if not targets:
        raise text.error("a directions table before any frequency row", k)
    for structure in targets:
        grids[structure].announced.extend(int(w) for w in words)


def _frequency_row(text, k, words, grids, current) -> int:
    leading = 0
    while leading < len(words) and _is_int(words[leading]):
        leading += 1
    if leading == 2:
        current = int(words[0])
        if current < 1:
            raise text.error(f"structure number {current} is not positive", k)
        grids.setdefault(current, _Grid([], [], [], [], k))
    elif leading != 1 or current is None:
        raise text.error(
            f"expected 'structure index frequency …' or 'index frequency …', found "
            f"{' '.join(words)[:60]!r}",
            k,
        )
    values = [_number(w) for w in words[leading : leading + 8]]
    rest = words[leading + 8 :]
    if (
        len(values) != 8
        or any(v is None for v in values)
        or len(rest) > 1
        or (rest and _number(rest[0]) is not None)
    ):
        raise text.error(
            "expected 8 numbers (rad/s, Hz, s, wave number, wave length, element size, "
            f"D/L, kD) and the PARAMETERS column, found {' '.join(words[leading:])[:70]!r}",
            k,
        )
    grid = grids[current]
    grid.index.append(int(words[leading - 1]))
    grid.omega.append(values[0])
    return current


def _direction_row(text: TextFile, k: int, words: list[str], grid: _Grid) -> None:
    values = [_number(w) for w in words]
    if not values or any(v is None for v in values) or not all("." in w for w in words):
        raise text.error(f"expected a row of directions (deg), found {' '.join(words)[:60]!r}", k)
    grid.directions.extend(values)


def _checked(text: TextFile, structure: int, grid: _Grid) -> tuple[np.ndarray, np.ndarray]:
    omega = np.asarray(grid.omega)
    if omega.size == 0:
        raise text.error(f"no wave frequencies for structure {structure}", grid.first_line)
    if grid.index != list(range(1, omega.size + 1)):
        bad = next(i for i, n in enumerate(grid.index) if n != i + 1)
        raise text.error(
            f"structure {structure}: frequency number {grid.index[bad]} where {bad + 1} was "
            "expected (a row lost or moved?)",
            grid.first_line,
        )
    if np.any(omega <= 0) or np.any(np.diff(omega) <= 0):
        raise text.error(
            f"structure {structure}: the wave frequencies are not positive and increasing",
            grid.first_line,
        )
    directions = np.asarray(grid.directions)
    if directions.size == 0:
        raise text.error(
            f"no wave directions for structure {structure} in the listing", grid.first_line
        )
    if grid.announced and grid.announced != list(range(1, directions.size + 1)):
        raise text.error(
            f"structure {structure}: the directions table announces {len(grid.announced)} "
            f"directions and lists {directions.size}",
            grid.first_line,
        )
    if np.any(np.abs(directions) > 720):
        raise text.error(f"structure {structure}: a direction beyond ±720 deg", grid.first_line)
    return omega, directions
