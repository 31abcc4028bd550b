"""The AQWA-LINE ``.LIS`` listing (AQWA 19.1 and 2023 R1 layouts; one or more structures).

* "GLOBAL PARAMETERS": water depth, density, gravity; "WAVE FREQUENCIES/PERIODS AND
  DIRECTIONS": the frequencies (rad/s, 5 decimals), wave numbers and directions, in
  either layout (:mod:`cummins.io.aqwa.pages`).
* One "HYDRODYNAMIC PARAMETERS" block per frequency ("WAVE PERIOD = … WAVE FREQUENCY
  = …") with the 6×6 ADDED MASS and DAMPING matrices (5 significant digits), rows the
  influenced DOF (X … RZ), columns the radiating DOF; the first block holds the
  hydrostatic STIFFNESS MATRIX.
* Tables "…-VARIATION WITH WAVE PERIOD/FREQUENCY", one per direction: "FROUDE KRYLOV
  + DIFFRACTION FORCES" (excitation), "DIFFRACTION FORCES", "FROUDE KRYLOV FORCES"
  (amplitude with 3 significant digits, phase in degrees) and "R.A.O.S" (motion RAOs,
  rotations in degrees per metre, converted to rad/m).
* "MASS AND INERTIA PROPERTIES": mass, centre of gravity and inertia matrix.
* "WAVE-DRIFT LOADS FOR UNIT WAVE AMPLITUDE**2": the mean drift
  (:mod:`cummins.io.aqwa.drift`).
* With the LHFR option, "HYDRODYNAMIC PARAMETERS AT LOW & HIGH FREQUENCIES".

Several structures: each structure's pages (:mod:`cummins.io.aqwa.pages`) are read as a
listing of one, about its own centre of gravity, and joined (DOFs ``body1__Surge`` …,
matrices block-diagonal). A listing that prints added mass or damping between structures
(hydrodynamic interaction, AQWA's ``STR#`` labels) is refused: no such listing is public
to check its layout against; the run's ``.AH1`` holds the coupling.

The run's ``.QTF`` beside the listing (same name) is read as its QTFs
(:mod:`cummins.io.aqwa.qtf`). The listing must be in the "Metric: kg, m [N]" unit system
that its header states.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.hydrodb import dof_labels, make_hydrodb
from cummins.io._common import resolve_rho_g, warn_damage
from cummins.io._text import TextFile, check_line_ends, parse_numbers
from cummins.io.aqwa.conventions import (
    _NUMBER,
    ASYMMETRY_LIMIT,
    HIGH_FREQUENCY_LIMIT,
    _complex,
    _depth,
    _limits_history,
    asymmetry,
)
from cummins.io.aqwa.detection import _is_lis
from cummins.io.aqwa.drift import lis_mean_drift
from cummins.io.aqwa.pages import (
    check_structure_pages,
    despace,
    pages,
    structure_view,
    structures,
    wave_grid,
)
from cummins.io.aqwa.qtf import aqwa_second_order
from cummins.qtf.data import with_second_order
from cummins.restoring import weight_record

_ROW_LABELS = ("X", "Y", "Z", "RX", "RY", "RZ")
#: AQWA's E format of a matrix entry (1.2345E+03): a cut number does not fit it.
_MATRIX_FIELD = re.compile(r"-?\d\.\d{3,5}E[-+]\d{2,3}")


_despace = despace


def _normal(line: str) -> str:
    return re.sub(r"\s+", " ", line.strip())


def _value_after(text: TextFile, pattern: str, start: int = 0, stop: int | None = None):
    """(value, line index) of the first ``pattern = number`` in the lines, or (None, -1)."""
    rx = re.compile(pattern + r"[\s.]*=\s*(" + _NUMBER + ")")
    end = len(text.lines) if stop is None else stop
    for i in range(start, end):
        m = rx.search(text.lines[i])
        if m:
            return float(m.group(1)), i
    return None, -1


def _matrix_after(text: TextFile, i: int, stop: int, what: str) -> tuple[np.ndarray, int]:
    """The 6×6 matrix printed as rows ``X …`` … ``RZ …`` after line ``i``."""
    rows = []
    k = i
    while k < stop and len(rows) < 6:
        tokens = text.lines[k].split()
        if tokens and set(tokens) <= set(_ROW_LABELS) and len(tokens) > 1:  # column titles
            k += 1
            continue
        if tokens and tokens[0] == _ROW_LABELS[len(rows)]:
            values = parse_numbers(" ".join(tokens[1:]))
            if values is None or values.size != 6:
                raise text.error(f"expected 6 numbers in row {tokens[0]} of the {what}", k)
            if not np.all(np.isfinite(values)):
                raise text.error(f"non-finite value in the {what}", k)
            cut = next((t for t in tokens[1:] if not _MATRIX_FIELD.fullmatch(t)), None)
            if cut is not None:
                raise text.error(
                    f"{cut!r} in row {tokens[0]} of the {what} is not in AQWA's format "
                    "(1.2345E+03): a cut or edited number",
                    k,
                )
            rows.append(values)
        elif tokens and rows and tokens[0] in _ROW_LABELS:
            raise text.error(f"row {tokens[0]} out of order in the {what}", k)
        elif tokens and rows and not set(tokens[0]) <= set("-"):
            raise text.error(f"the {what} is incomplete (row {_ROW_LABELS[len(rows)]} missing)", k)
        k += 1
    if len(rows) < 6:
        raise text.error(f"the {what} is incomplete (truncated?)", min(k, len(text.lines) - 1))
    return np.vstack(rows), k


def _label_line(text: TextFile, label: str, start: int, stop: int) -> int:
    for k in range(start, min(stop, len(text.lines))):
        if _normal(text.lines[k]) == label:
            return k
    return -1


_TABLES = {
    "FROUDE KRYLOV + DIFFRACTION FORCES-VARIATION WITH WAVE PERIOD/FREQUENCY": "excitation",
    "DIFFRACTION FORCES-VARIATION WITH WAVE PERIOD/FREQUENCY": "diffraction",
    "FROUDE KRYLOV FORCES-VARIATION WITH WAVE PERIOD/FREQUENCY": "froude_krylov",
    "R.A.O.S-VARIATION WITH WAVE PERIOD/FREQUENCY": "rao",
}


def _lis_constants(text: TextFile) -> dict[str, float]:
    out = {}
    for key, pattern in (
        ("depth", r"WATER\s+DEPTH"),
        ("rho", r"DENSITY\s+OF\s+WATER"),
        ("g", r"ACCELERATION\s+DUE\s+TO\s+GRAVITY"),
    ):
        value, i = _value_after(text, pattern)
        if value is None:
            raise text.error(
                f"no {pattern.replace(chr(92) + 's+', ' ')} in the GLOBAL PARAMETERS",
                hint="is the listing complete (truncated?)",
            )
        if not np.isfinite(value) or value < 0 or (key != "depth" and value == 0):
            raise text.error(f"invalid {key} {value:g}", i)
        out[key] = value
    return out


def _label_line_prefix(text: TextFile, prefix: str, start: int, stop: int) -> int:
    for k in range(start, min(stop, len(text.lines))):
        if text.lines[k].strip().startswith(prefix):
            return k
    return -1


def _lis_radiation(text: TextFile, omega: np.ndarray):
    """A and B (nω, 6, 6) from the per-frequency blocks, and the stiffness matrix."""
    rx = re.compile(
        r"WAVE PERIOD\s*=\s*(" + _NUMBER + r")\s+WAVE FREQUENCY\s*=\s*(" + _NUMBER + ")"
    )
    blocks = [(i, float(m.group(2))) for i, line in enumerate(text.lines) if (m := rx.search(line))]
    if not blocks:
        raise text.error("no added mass and damping blocks (WAVE PERIOD = … WAVE FREQUENCY = …)")
    if len(blocks) != omega.size:
        raise text.error(
            f"{len(blocks)} added-mass blocks for {omega.size} frequencies (truncated?)",
            blocks[-1][0],
        )
    a = np.zeros((omega.size, 6, 6))
    b = np.zeros((omega.size, 6, 6))
    starts = [i for i, _ in blocks] + [len(text.lines)]
    for n, (i, w) in enumerate(blocks):
        if abs(w - omega[n]) > 6e-5 + 1e-6 * omega[n]:
            raise text.error(
                f"block for {w:g} rad/s where the frequency table has {omega[n]:g} rad/s", i
            )
        stop = min(starts[n + 1], i + 80)
        label = _label_line(text, "ADDED MASS", i, stop)
        if label < 0:
            raise text.error("no ADDED MASS matrix after this line", i)
        a[n], end = _matrix_after(text, label + 1, stop, f"added mass at {w:g} rad/s")
        label = _label_line(text, "DAMPING", end, stop)
        if label < 0:
            raise text.error("no DAMPING matrix after the added mass", end)
        b[n], _ = _matrix_after(text, label + 1, stop, f"damping at {w:g} rad/s")
    for name, matrices in (("added mass", a), ("damping", b)):
        values = asymmetry(matrices)  # rows are labelled X … RZ, not by frequency
        worst = int(np.argmax(values))
        if values[worst] > ASYMMETRY_LIMIT:
            raise text.error(
                f"the {name} at {omega[worst]:g} rad/s is not symmetric (asymmetry "
                f"{values[worst]:.3g}, AQWA's are below {ASYMMETRY_LIMIT:g}): rows moved "
                "between frequencies or edited?",
                blocks[worst][0],
            )
    label = _label_line(text, "STIFFNESS MATRIX", 0, blocks[0][0])
    stiffness = None
    if label >= 0:
        stiffness, _ = _matrix_after(text, label + 1, blocks[0][0], "stiffness matrix")
    return a, b, stiffness


def _lis_limits(text: TextFile, titles) -> tuple[np.ndarray | None, float | None, float | None]:
    """(A at the high LHFR frequency, that frequency, the low LHFR frequency)."""
    starts = [i for i, t in titles if "HYDRODYNAMIC PARAMETERS AT LOW & HIGH FREQUENCIES" in t]
    if not starts:
        return None, None, None
    start = starts[0]
    stop = next((i for i, _ in titles if i > start and i not in starts), len(text.lines))
    rx = re.compile(r"WAVE FREQUENCY\s*=\s*(" + _NUMBER + r")\s*\(RAD/S\)")
    found = [(i, float(m.group(1))) for i in range(start, stop) if (m := rx.search(text.lines[i]))]
    high = low = None
    a_high = None
    for i, w in found:
        if w >= HIGH_FREQUENCY_LIMIT:
            label = _label_line(text, "ADDED MASS", i, min(stop, i + 20))
            if label < 0:
                raise text.error("no ADDED MASS matrix after this line", i)
            a_high, _ = _matrix_after(text, label + 1, stop, f"added mass at {w:g} rad/s")
            high = w
        else:
            low = w
    return a_high, high, low


def _lis_tables(text: TextFile, titles, n_omega: int):
    """The per-direction tables: {kind: [(direction, freq, 12 values, line)]}."""
    out: dict[str, list] = {}
    for i, title in (
        (i, _normal(text.lines[i]))
        for i in range(len(text.lines))
        if "VARIATION WITH WAVE PERIOD/FREQUENCY" in text.lines[i]
    ):
        kind = _TABLES.get(title)
        if kind is None:
            continue
        rows = out.setdefault(kind, [])
        direction = rows[-1][0] if rows else None
        k = _label_line_prefix(text, "(SECS)", i, i + 8)
        if k < 0:
            raise text.error("table header '(SECS) (RAD/S) (DEGREES) …' not found", i)
        k += 1
        while k < len(text.lines) and (
            not text.lines[k].strip() or set(text.lines[k].strip()) <= set("-")
        ):
            k += 1
        while k < len(text.lines):
            values = parse_numbers(text.lines[k])
            if values is None or values.size not in (14, 15):
                if text.lines[k].strip():
                    break
                k += 1
                continue
            if not np.all(np.isfinite(values)):
                raise text.error("non-finite value in the table", k)
            if values.size == 15:
                direction = float(values[2])
                values = np.delete(values, 2)
            elif direction is None:
                raise text.error("table row without a wave direction", k)
            rows.append((direction, float(values[1]), values[2:], k))
            k += 1
    for rows in out.values():  # fixed columns: a row cut in its last phase ends early
        check_line_ends(text, [row[3] for row in rows])
    return out


def _assemble(text: TextFile, rows, omega, directions, what: str):
    """(amplitude, phase) arrays (nω, nβ, 6) from table rows, checked complete."""
    amplitude = np.full((omega.size, directions.size, 6), np.nan)
    phase = np.full_like(amplitude, np.nan)
    for direction, w, values, line in rows:
        h = np.flatnonzero(np.isclose(directions, direction, atol=0.006))
        n = np.flatnonzero(np.abs(omega - w) <= 6e-4)
        if h.size != 1 or n.size != 1:
            raise text.error(
                f"{what}: row for {w:g} rad/s, {direction:g} deg does not match "
                "the frequency and direction tables",
                line,
            )
        if not np.isnan(amplitude[n[0], h[0], 0]):
            raise text.error(f"{what}: a second row for {w:g} rad/s, {direction:g} deg", line)
        amplitude[n[0], h[0]] = values[0::2]
        phase[n[0], h[0]] = values[1::2]
    if np.isnan(amplitude).any():
        n, h, _ = np.argwhere(np.isnan(amplitude))[0]
        raise text.error(
            f"{what}: no row for {omega[n]:g} rad/s, {directions[h]:g} deg (truncated?)",
            rows[-1][3] if rows else None,
        )
    return amplitude, phase


def _lis_mass(text: TextFile, titles):
    """Mass, inertia matrix about the CG (3×3) and CG from MASS AND INERTIA PROPERTIES."""
    starts = [i for i, t in titles if "MASS AND INERTIA PROPERTIES" in t]
    if not starts:
        return None, None
    start = starts[0]
    stop = min(len(text.lines), start + 80)
    mass = None
    inertia = None
    for k in range(start, stop):
        compact = _despace(text.lines[k])
        if compact.startswith("TOTAL"):
            values = parse_numbers(compact[5:])
            if values is None or values.size < 2:
                raise text.error("expected the element count and the total mass", k)
            mass = float(values[1])
        if "INERTIA MATRIX" in text.lines[k]:
            first = parse_numbers(text.lines[k].split("INERTIA MATRIX", 1)[1])
            rows = [first]
            j = k + 1
            while len(rows) < 3 and j < stop:
                if text.lines[j].strip():
                    rows.append(parse_numbers(text.lines[j]))
                j += 1
            if any(r is None or r.size != 3 for r in rows) or len(rows) < 3:
                raise text.error("expected a 3×3 inertia matrix", k)
            inertia = np.vstack(rows)
            break
    return mass, inertia


def _read_lis(path: Path, rho, g) -> xr.Dataset:
    text = TextFile.read(path)
    if not _is_lis("\n".join(text.lines[:200])):
        raise text.error("not an AQWA listing (no AQWA banner)")
    units = _label_line_prefix(text, "* Hydrodynamic Solver Unit System", 0, 60)
    if units >= 0 and "kg, m" not in text.lines[units]:
        raise text.error(
            f"unit system {text.lines[units].split(':', 1)[-1].strip()!r}",
            units,
            hint="rerun AQWA in the Metric: kg, m [N] system",
        )
    listing = pages(text)
    numbers = structures(listing) or [1]
    grids, first_row = wave_grid(text, listing)
    omega, directions = _one_grid(text, grids, numbers, first_row)
    if len(numbers) > 1:
        check_structure_pages(text, listing)
        coupled = next((i for i, line in enumerate(text.lines) if _COUPLING.search(line)), -1)
        if coupled >= 0:
            raise text.error(
                "added mass or damping between structures (hydrodynamic interaction): a "
                "listing layout cummins has no example of",
                coupled,
                hint="read the run's .AH1 file, which holds the coupling matrices",
            )
    history = [
        f"read AQWA listing {path.name}"
        + (f" ({len(numbers)} structures)" if len(numbers) > 1 else "")
    ]
    constants = _lis_constants(text)
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        constants["rho"],
        constants["g"],
        path=path,
        history=history,
        dimensional=True,
    )
    depth = _depth(constants["depth"])
    notes: list[str] = []
    bodies = [
        _read_structure(
            text if len(numbers) == 1 else structure_view(text, listing, s),
            omega,
            directions,
            depth,
            g_v,
            notes,
        )
        for s in numbers
    ]
    if len(numbers) > 1:
        history.append(
            "the listing prints no added mass or damping between the structures (they were "
            "computed without hydrodynamic interaction): the coupling terms are zero"
        )
    extra, body_history = _joined(bodies, directions, rho_v, g_v)
    history.extend(body_history)
    kinds = set.intersection(*(set(b.tables) for b in bodies))
    lacking = [
        s for s, b in zip(numbers, bodies, strict=True) if b.a_inf is None and b.high is None
    ]
    _lis_completeness(
        text, dict.fromkeys(kinds), lacking if len(numbers) > 1 else bool(lacking), notes
    )
    cg = np.vstack([b.cg for b in bodies])
    n = len(bodies)

    def flat(points):
        return points.reshape(-1) if n > 1 else points[0]

    cb = [b.cb for b in bodies]
    volumes = [b.volume for b in bodies]
    second = aqwa_second_order(path, cgs=cg, depth=depth, g=g_v, dofs=_labels(n), notes=notes)
    ds = make_hydrodb(
        omega,
        _block_diagonal([b.a for b in bodies]),
        _block_diagonal([b.b for b in bodies]),
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format="aqwa",
        source_file=str(path),
        dofs=_labels(n),
        reference_point=flat(cg),
        history=history,
        center_of_gravity=flat(cg),
        center_of_buoyancy=None if any(c is None for c in cb) else flat(np.vstack(cb)),
        displaced_volume=(volumes[0] if n == 1 else None if None in volumes else np.array(volumes)),
        read_warnings=notes,
        **extra,
    )
    if not (second["tables"] or second["history"]):
        return ds
    return with_second_order(ds, second["tables"], history=second["history"], attrs=second["attrs"])


#: The label of a matrix between two structures (AQWA's "STR#" notation).
_COUPLING = re.compile(r"STR\s*#\s*\d")


def _labels(n: int) -> list[str]:
    return dof_labels() if n == 1 else dof_labels([f"body{k + 1}" for k in range(n)])


def _one_grid(text: TextFile, grids: dict, numbers: list[int], line: int):
    """The frequencies and directions every structure shares (cummins holds one grid)."""
    if sorted(grids) != numbers:
        raise text.error(
            f"the wave frequency table lists structures {sorted(grids)}, the listing's pages "
            f"structures {numbers}",
            line,
        )
    omega, directions = grids[numbers[0]]
    for s in numbers[1:]:
        w, d = grids[s]
        if w.shape != omega.shape or not np.allclose(w, omega, rtol=1e-6):
            raise text.error(f"structure {s} has other wave frequencies than structure 1", line)
        if d.shape != directions.shape or not np.allclose(d, directions):
            raise text.error(f"structure {s} has other wave directions than structure 1", line)
    return omega, directions


@dataclass
class _Structure:
    """What the listing gives for one structure (6 DOFs, about its centre of gravity)."""

    a: np.ndarray
    b: np.ndarray
    stiffness: np.ndarray | None
    cg: np.ndarray
    a_inf: np.ndarray | None
    high: float | None
    low: float | None
    tables: dict[str, np.ndarray]
    drift: np.ndarray | None
    drift_history: list[str]
    mass: float | None
    inertia: np.ndarray | None
    cb: np.ndarray | None
    volume: float | None


def _read_structure(text: TextFile, omega, directions, depth, g, notes) -> _Structure:
    """One structure's data from its pages (``text``: a view holding only them and the
    common pages)."""
    titles = [(i, _despace(line)) for i, line in enumerate(text.lines) if "* * * *" in line]
    a, b, stiffness = _lis_radiation(text, omega)
    cg = _lis_cg(text)
    a_inf, high, low = _lis_limits(text, titles)
    tables = {}
    for kind, rows in _lis_tables(text, titles, omega.size).items():
        amplitude, phase = _assemble(text, rows, omega, directions, kind)
        if kind == "rao":
            amplitude[..., 3:] = np.radians(amplitude[..., 3:])
        tables[kind] = _complex(amplitude, phase, omega, directions, cg, depth, g)
    drift, drift_history = lis_mean_drift(text, titles, omega, directions, notes)
    mass, inertia = _lis_mass(text, titles)
    cb = [_value_after(text, key)[0] for key in ("BX", "BY", "BZ")]
    volume, _ = _value_after(text, "MESH BASED DISPLACEMENT")
    return _Structure(
        a,
        b,
        stiffness,
        cg,
        a_inf,
        high,
        low,
        tables,
        drift,
        drift_history,
        mass,
        inertia,
        None if any(v is None for v in cb) else np.array(cb, dtype=float),
        volume,
    )


def _block_diagonal(blocks: list[np.ndarray]) -> np.ndarray:
    """Blocks (…, 6, 6) of the structures → (…, 6n, 6n), zero between structures."""
    n = len(blocks)
    if n == 1:
        return blocks[0]
    out = np.zeros((*blocks[0].shape[:-2], 6 * n, 6 * n))
    for k, block in enumerate(blocks):
        out[..., 6 * k : 6 * k + 6, 6 * k : 6 * k + 6] = block
    return out


def _joined(bodies: list[_Structure], directions, rho, g) -> tuple[dict, list[str]]:
    """The optional variables of all structures (present for every one) and history."""
    n = len(bodies)
    history = [
        f"matrices and forces about the centre of gravity "
        f"{b.cg.tolist()} m (AQWA: WITH RESPECT TO STRUCTURE COG)"
        if n == 1
        else f"structure {k + 1}: matrices and forces about its centre of gravity {b.cg.tolist()} m"
        for k, b in enumerate(bodies)
    ]
    extra: dict = {}
    if all(b.stiffness is not None for b in bodies):
        extra["hydrostatic_stiffness"] = _block_diagonal([b.stiffness for b in bodies])
    if all(b.a_inf is not None for b in bodies):
        extra["added_mass_inf"] = _block_diagonal([b.a_inf for b in bodies])
    first = bodies[0]
    _limits_history(history, extra.get("added_mass_inf"), first.high, first.low, g)
    names = {
        "excitation": "excitation_force",
        "diffraction": "diffraction_force",
        "froude_krylov": "froude_krylov_force",
        "rao": "rao",
    }
    for kind, name in names.items():
        if all(kind in b.tables for b in bodies):
            extra[name] = np.concatenate([b.tables[kind] for b in bodies], axis=-1)
            if kind == "rao":
                history.append("RAO rotations converted from deg/m to rad/m")
    drifts = [b.drift for b in bodies]
    if all(d is not None for d in drifts):
        extra["drift_force"] = np.concatenate(drifts, axis=-1)
        history.extend(first.drift_history)
    elif any(d is not None for d in drifts):
        history.append("mean drift not read: printed for some structures only")
    if any(k in extra for k in (*names.values(), "drift_force")):
        extra["wave_direction"] = np.radians(directions)
        history.append(
            "AQWA phase lags converted: X = |X| exp(-i(phase + k(xG cos b + yG sin b))), "
            "phases referred from the centre of gravity to the origin"
        )
        history.append("excitation amplitudes printed with 3 significant digits in the listing")
    if all(b.mass is not None and b.inertia is not None for b in bodies):
        blocks = []
        for b in bodies:
            m = np.zeros((6, 6))
            m[:3, :3] = b.mass * np.eye(3)
            m[3:, 3:] = b.inertia
            blocks.append(m)
        extra["inertia_matrix"] = _block_diagonal(blocks)
        history.append(
            "inertia matrix from MASS AND INERTIA PROPERTIES (mass "
            + ", ".join(f"{b.mass:.6g}" for b in bodies)
            + " kg, inertia matrix about the centre of gravity)"
        )
    else:
        history.append("no MASS AND INERTIA PROPERTIES in the listing: no inertia_matrix")
    if "hydrostatic_stiffness" in extra:  # about G, where the weight's terms vanish
        weights = [
            b.mass if b.mass is not None else (rho * b.volume if b.volume else np.nan)
            for b in bodies
        ]
        cg = np.vstack([b.cg for b in bodies])
        extra.update(
            weight_record(weights, cg if n > 1 else cg[0], "AQWA's hydrostatic stiffness (about G)")
        )
    return extra, history


def _lis_completeness(text: TextFile, tables: dict, lacking, notes: list[str]) -> None:
    """Warn when the listing ends before the sections it announces.

    AQWA closes every listing with a ``FINISH DATE`` line; the ``OPTIONS`` cards of the
    input echo announce the LHFR block (low and high frequency limits). ``lacking``: the
    structures without that block (a list), or whether the one structure lacks it.
    """
    options = {
        word
        for line in text.lines[:400]
        if line.strip().startswith("OPTIONS")
        for word in line.split()[1:]
    }
    if "LHFR" in options and lacking:
        whose = (
            f" for structure {', '.join(str(s) for s in lacking)}"
            if isinstance(lacking, list)
            else ""
        )
        warn_damage(
            "OPTIONS LHFR announces the HYDRODYNAMIC PARAMETERS AT LOW & HIGH FREQUENCIES, "
            f"but the listing has none{whose} (truncated?): read without added_mass_inf",
            path=text.path,
            line=len(text.lines),
            notes=notes,
        )
    if not any(line.strip().startswith("FINISH DATE") for line in text.lines[-40:]):
        lost = [name for kind, name in _TABLE_NAMES.items() if kind not in tables]
        warn_damage(
            "the listing ends without AQWA's closing 'FINISH DATE' line (truncated, or the "
            "run stopped)"
            + (f": read without {', '.join(lost)} (their tables are missing)" if lost else ""),
            path=text.path,
            line=len(text.lines),
            notes=notes,
        )


_TABLE_NAMES = {
    "excitation": "the excitation force",
    "diffraction": "the diffraction force",
    "froude_krylov": "the Froude-Krylov force",
    "rao": "the RAOs",
}


def _lis_cg(text: TextFile) -> np.ndarray:
    values = [_value_after(text, key) for key in ("GX", "GY", "GZ")]
    if all(v is not None for v, _ in values):
        return np.array([v for v, _ in values])
    k = -1
    for i in range(len(text.lines)):
        if _normal(text.lines[i]).startswith("CENTRE OF GRAVITY"):
            k = i
            break
    if k >= 0:
        numbers = parse_numbers(_normal(text.lines[k])[len("CENTRE OF GRAVITY") :])
        if numbers is not None and numbers.size == 3:
            return numbers
    raise text.error(
        "no centre of gravity (GX, GY, GZ) in the listing",
        hint="AQWA refers all results to it; is the listing complete?",
    )
