"""The mean drift tables of an AQWA ``.LIS``: "WAVE-DRIFT LOADS FOR UNIT WAVE AMPLITUDE**2".

One table per DOF (``SURGE(X)`` … ``YAW(RZ)``; AQWA 19.1 prints each on a page of its
own, AQWA 2023 R1 the six in turn under one title), headed "DUE TO (RADIANS/SEC)" and the
wave directions (degrees), then one row per frequency: ω and the mean drift force per
squared wave amplitude in each direction (N/m², N·m/m², three significant digits),
about the centre of gravity in AQWA's fixed reference axes (z up, as the rest of the
listing). The values are real: a mean force. The corpus's PEND hull (AQWA 19.1) prints
them for its 100 frequencies and 5 directions, −180° and 180° both, as the excitation.
A damaged table does not stop the listing from reading: the drift is left out with a
warning. The full QTF of the run is AQWA's ``.QTF`` file (:mod:`cummins.io.aqwa.qtf`).
"""

from __future__ import annotations

import numpy as np

from cummins.errors import HydroDataError
from cummins.io._common import warn_damage
from cummins.io._text import TextFile, check_cut_numbers, parse_numbers

_TITLE = "WAVE-DRIFT LOADS FOR UNIT WAVE AMPLITUDE"
_DOF_LABELS = ("SURGE(X)", "SWAY(Y)", "HEAVE(Z)", "ROLL(RX)", "PITCH(RY)", "YAW(RZ)")


def _blocks(
    text: TextFile, titles
) -> list[tuple[int, np.ndarray, int, list[tuple[int, np.ndarray]]]]:
    """Each table: (DOF index, directions in degrees, header line, rows (line, values));
    ``titles`` are the listing's despaced title lines (index, text)."""
    out = []
    starts = [i for i, title in titles if _TITLE in title]
    for s, start in enumerate(starts):
        stop = starts[s + 1] if s + 1 < len(starts) else len(text.lines)
        header = next((k for k in range(start, stop) if "(RADIANS/SEC)" in text.lines[k]), -1)
        if header < 0:
            raise text.error("drift table without its '(RADIANS/SEC)' header", start)
        directions = parse_numbers(text.lines[header].split("(RADIANS/SEC)", 1)[1])
        if directions is None or directions.size == 0:
            raise text.error("no wave directions on the drift table's header", header)
        k = header + 1
        tables: list[tuple[int, list[tuple[int, np.ndarray]]]] = []
        while k < stop:
            stripped = text.lines[k].strip()
            label = stripped.replace(" ", "")
            if label in _DOF_LABELS:  # AQWA 19.1: one per page; AQWA 2023: all six in turn
                tables.append((_DOF_LABELS.index(label), []))
            elif stripped == "1" and tables and tables[-1][1]:  # carriage control: next page
                break
            elif tables and stripped:
                values = parse_numbers(stripped)
                if values is None:
                    if tables[-1][1]:
                        break
                    raise text.error(f"expected a row of numbers, found {stripped[:60]!r}", k)
                if values.size != directions.size + 1:
                    raise text.error(
                        f"expected {directions.size + 1} numbers (frequency and one per "
                        f"direction), found {values.size}",
                        k,
                    )
                if not np.all(np.isfinite(values)):
                    raise text.error("non-finite value in the drift table", k)
                tables[-1][1].append((k, values))
            k += 1
        if not tables or not all(rows for _, rows in tables):
            raise text.error("drift table without a DOF label or rows", header)
        for dof, rows in tables:
            # fixed-width E-format values: a row cut inside its last number is damage
            check_cut_numbers(text, [k for k, _ in rows], range(1, directions.size + 1))
            out.append((dof, directions, header, rows))
    return out


def lis_mean_drift(
    text: TextFile, titles, omega: np.ndarray, directions: np.ndarray, notes: list[str]
) -> tuple[np.ndarray | None, list[str]]:
    """The listing's mean drift (nω, nβ, 6) on its frequencies and directions (degrees),
    or None (no drift tables, or damaged ones: then a warning in ``notes``); ``titles``
    as the listing reader finds them (despaced)."""
    try:
        blocks = _blocks(text, titles)
    except HydroDataError as exc:
        warn_damage(f"mean drift not read: {exc}", path=text.path, notes=notes)
        return None, []
    if not blocks:
        return None, []
    values = np.full((omega.size, directions.size, 6), np.nan)
    try:
        for dof, heads, header, rows in blocks:
            h = [np.flatnonzero(np.isclose(directions, d, atol=0.006)) for d in heads]
            if any(x.size != 1 for x in h):
                raise text.error("the drift table's directions do not match the listing's", header)
            columns = np.array([x[0] for x in h])
            for line, row in rows:
                n = np.flatnonzero(np.abs(omega - row[0]) <= 6e-4)
                if n.size != 1:
                    raise text.error(
                        f"drift row at {row[0]:g} rad/s is not one of the listing's frequencies",
                        line,
                    )
                if not np.all(np.isnan(values[n[0], columns, dof])):
                    raise text.error(f"a second drift row at {row[0]:g} rad/s", line)
                values[n[0], columns, dof] = row[1:]
        present = ~np.all(np.isnan(values), axis=(0, 1))
        gap = np.isnan(values) & present[None, None, :]
        if gap.any():
            n, h, d = np.argwhere(gap)[0]
            raise text.error(
                f"no mean drift of {_DOF_LABELS[d]} at {omega[n]:g} rad/s, "
                f"{directions[h]:g} deg (truncated or edited?)",
                blocks[-1][3][-1][0],
            )
    except HydroDataError as exc:
        warn_damage(f"mean drift not read: {exc}", path=text.path, notes=notes)
        return None, []
    missing = [_DOF_LABELS[d] for d in range(6) if not present[d]]
    history = [
        "drift_force from the listing's WAVE-DRIFT LOADS FOR UNIT WAVE AMPLITUDE**2 "
        "(3 significant digits, about the centre of gravity)"
        + (f"; {', '.join(missing)} not printed: 0" if missing else "")
    ]
    return np.nan_to_num(values, nan=0.0), history
