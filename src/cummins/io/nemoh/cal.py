"""``Nemoh.cal``, the input file of a NEMOH run (v2 and v3 layouts).

What cummins takes from it: ρ, g, water depth (``0`` means deep water), the bodies
(named after their mesh files), the degrees of freedom and generalised forces (type 1 =
translation along a direction, type 2 = rotation about an axis through a point, the
point about which the body's moments and rotations are defined), the numbers of
frequencies and wave directions, and in v3 the unit of the frequency column of the
output files and the QTF flag. v2 writes the frequency line as ``N wmin wmax``
(rad/s); v3 as ``type N min max`` and adds the RAO / output-frequency-unit lines and a
QTF section.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES
from cummins.io._text import TextFile
from cummins.io.nemoh.files import _NUMBER

# --------------------------------------------------------------------------- Nemoh.cal


@dataclass
class _Mode:
    """A degree of freedom or generalised force line of ``Nemoh.cal``."""

    kind: int  # 1 translation, 2 rotation
    direction: np.ndarray
    point: np.ndarray
    line: int


@dataclass
class _Body:
    name: str
    dofs: list[_Mode]
    forces: list[_Mode]
    extra_lines: int = 0  # lines of "additional information", skipped as NEMOH does


@dataclass
class _NemohCal:
    path: Path
    rho: float
    g: float
    depth: float
    bodies: list[_Body]
    version: str
    n_frequencies: int
    n_directions: int
    output_unit: int | None = None
    frequency_range: tuple[float, float, int] = (0.0, 0.0, 1)  # min, max, unit (1 rad/s …)
    qtf: bool = False


class _Cursor:
    """Walks the value lines of ``Nemoh.cal`` (the part before ``!`` of each line)."""

    def __init__(self, text: TextFile, start: int) -> None:
        self.text = text
        self.i = start

    def line(self) -> tuple[str, int]:
        while self.i < len(self.text.lines) and not self.text.lines[self.i].strip():
            self.i += 1
        if self.i >= len(self.text.lines):
            raise self.text.error("Nemoh.cal ends too early (truncated?)", len(self.text.lines) - 1)
        i = self.i
        self.i += 1
        return self.text.lines[i].split("!", 1)[0].strip(), i

    def numbers(self, what: str, at_least: int = 1) -> tuple[np.ndarray, int]:
        content, i = self.line()
        values = [
            float(v.replace("D", "E").replace("d", "e")) for v in re.findall(_NUMBER, content)
        ]
        leftover = re.sub(_NUMBER, "", content).strip()
        if len(values) < at_least or leftover:
            raise self.text.error(
                f"expected {what} ({at_least} number{'s' if at_least > 1 else ''}), "
                f"found {content[:60]!r}",
                i,
            )
        array = np.asarray(values)
        if not np.all(np.isfinite(array)):
            raise self.text.error(f"non-finite value in {what}", i)
        return array, i

    def count(self, what: str, maximum: int = 10000) -> int:
        values, i = self.numbers(what)
        n = values[0]
        if n != round(n) or n < 0 or n > maximum:
            raise self.text.error(f"{what} must be a whole number, found {n:g}", i)
        return int(n)

    def header(self, keyword: str) -> None:
        content, i = self.line()
        if not content.startswith("---") or keyword not in content.lower():
            raise self.text.error(f"expected the '--- {keyword}' section header", i)


def _read_cal(path: Path) -> _NemohCal:
    """Parse ``Nemoh.cal`` (v2 or v3 layout)."""
    text = TextFile.read(path)
    start = next(
        (
            i
            for i, line in enumerate(text.lines)
            if "environment" in line.lower() and line.strip().startswith("---")
        ),
        None,
    )
    if start is None:
        raise text.error("no '--- Environment' section: not a Nemoh.cal file", 0)
    cur = _Cursor(text, start + 1)
    rho = cur.numbers("the water density RHO")[0][0]
    g = cur.numbers("gravity G")[0][0]
    depth = cur.numbers("the water depth")[0][0]
    cur.numbers("the wave measurement point", 2)
    if rho <= 0 or g <= 0 or depth < 0:
        raise text.error("RHO and G must be positive and the depth not negative", start + 1)
    cur.header("floating bodies")
    n_bodies = cur.count("the number of bodies", 1000)
    if n_bodies == 0:
        raise text.error("Nemoh.cal describes no body", cur.i - 1)
    bodies = [_read_body(cur) for _ in range(n_bodies)]
    cur.header("load cases")
    freq, freq_line = cur.numbers("the frequency range", 3)
    if freq.size >= 4:
        version, n_freq = "v3", freq[1]
        f_range = (float(freq[2]), float(freq[3]), int(freq[0]) if freq[0] in (1, 2, 3) else 1)
    else:
        version, n_freq = "v2", freq[0]
        f_range = (float(freq[1]), float(freq[2]), 1)
    if n_freq != round(n_freq) or n_freq < 1:
        raise text.error(
            f"number of frequencies must be a positive whole number, found {n_freq:g}", freq_line
        )
    n_dir = cur.count("the number of wave directions")
    output_unit = None
    qtf = False
    if version == "v3":
        output_unit = _output_unit(cur)
        qtf = _qtf_flag(cur)
    return _NemohCal(
        path,
        float(rho),
        float(g),
        np.inf if depth == 0 else float(depth),
        bodies,
        version,
        int(n_freq),
        n_dir,
        output_unit,
        f_range,
        qtf,
    )


def _qtf_flag(cur: _Cursor) -> bool:
    """v3 QTF flag (first value line of the ``--- QTF`` section), False if absent."""
    for i in range(cur.i, len(cur.text.lines)):
        line = cur.text.lines[i].strip()
        if line.startswith("--") and "qtf" in line.lower():
            for j in range(i + 1, len(cur.text.lines)):
                content = cur.text.lines[j].split("!", 1)[0].strip()
                if content:
                    return content.split()[0] == "1"
            return False
    return False


def _output_unit(cur: _Cursor) -> int | None:
    """v3 "output freq type" (6th value line of the post-processing section)."""
    try:
        cur.header("post processing")
        for _ in range(5):
            cur.line()
        values, _ = cur.numbers("the output frequency type")
    except HydroDataError:
        return None
    unit = values[0]
    return int(unit) if unit in (1.0, 2.0, 3.0) else None


def _read_body(cur: _Cursor) -> _Body:
    cur.header("body")
    content, i = cur.line()
    tokens = content.split()
    if not tokens:
        raise cur.text.error("expected the name of the mesh file", i)
    name = re.split(r"[\\/]", tokens[0])[-1].rsplit(".", 1)[0] or "body"
    cur.numbers("the number of points and panels", 2)
    dofs = [_read_mode(cur) for _ in range(cur.count("the number of degrees of freedom", 1000))]
    forces = [_read_mode(cur) for _ in range(cur.count("the number of generalised forces", 1000))]
    # the lines of "additional information" were meant for generalised modes, which
    # NEMOH never implemented: v2 skips them, v3 reads the count line only ("reserved");
    # the DOFs and forces above are all there is, and the results hold those
    n_extra = cur.count("the number of lines of additional information", 1000)
    for _ in range(n_extra):
        cur.line()
    return _Body(name, dofs, forces, n_extra)


def _read_mode(cur: _Cursor) -> _Mode:
    values, i = cur.numbers("a DOF line: type, direction (3), point (3)", 7)
    kind = values[0]
    if kind == 3.0:
        raise cur.text.error(
            "DOF type 3 (a generalised mode): NEMOH does not compute it (its preprocessor "
            "stops: 'radiation case 3 not implemented yet'), so no results of this run hold it",
            i,
            hint="NEMOH computes translations (type 1) and rotations (type 2); for generalised "
            "modes use WAMIT (NEWMDS) or Capytaine (any DOF field)",
        )
    if kind not in (0.0, 1.0, 2.0):
        raise cur.text.error(f"unknown DOF type {kind:g} (1 translation, 2 rotation)", i)
    return _Mode(int(kind), values[1:4], values[4:7], i)


def _mode_name(text: TextFile, mode: _Mode, position: int, count: int) -> str:
    """Surge … Yaw for a rigid-body DOF line of ``Nemoh.cal``."""
    d = mode.direction
    axis = int(np.argmax(np.abs(d)))
    unit = np.zeros(3)
    unit[axis] = 1.0
    if not np.allclose(d, unit, atol=1e-6):
        raise text.error(
            f"DOF direction {d.tolist()} is not along x, y or z",
            mode.line,
            hint="cummins reads rigid-body DOFs along the body axes only",
        )
    if mode.kind == 1:
        return DOF_NAMES[axis]
    if mode.kind == 2:
        return DOF_NAMES[3 + axis]
    if count == 6 and axis == position % 3:  # type 0 (inactive) in a full 6-DOF list
        return DOF_NAMES[position]
    raise text.error("cannot tell translation from rotation for a DOF of type 0", mode.line)


def _body_point(text: TextFile, body: _Body) -> np.ndarray:
    """The point about which the rotations and moments of a body are defined."""
    modes = [m for m in (*body.dofs, *body.forces) if m.kind == 2]
    if not modes:
        return np.zeros(3)
    point = modes[0].point
    for mode in modes[1:]:
        if not np.allclose(mode.point, point, atol=1e-9):
            raise text.error(
                f"rotations/moments about different points ({point.tolist()} and "
                f"{mode.point.tolist()})",
                mode.line,
                hint="cummins needs one reference point per body; rerun NEMOH with one point",
            )
    return point
