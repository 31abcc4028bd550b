"""ANSYS AQWA-LINE output: the ``.LIS`` listing and the ``.AH1`` hydrodynamic database.

Both files are dimensional, in the unit system of the run (cummins requires the
"Metric: kg, m [N]" system that the listing header states). All matrices and forces
are printed "WITH RESPECT TO STRUCTURE COG": cummins records the centre of gravity as
``reference_point`` (AQWA's fixed reference axes: z up, x and y in the mean free
surface, as cummins).

``.LIS`` (read for a single structure; use the ``.AH1`` for several):

* "GLOBAL PARAMETERS": water depth, density, gravity; "WAVE FREQUENCIES/PERIODS AND
  DIRECTIONS": the frequencies (rad/s, 5 decimals), wave numbers and directions.
* One "HYDRODYNAMIC PARAMETERS" block per frequency ("WAVE PERIOD = … WAVE FREQUENCY
  = …") with the 6×6 ADDED MASS and DAMPING matrices (5 significant digits), rows the
  influenced DOF (X … RZ), columns the radiating DOF; the first block holds the
  hydrostatic STIFFNESS MATRIX.
* Tables "…-VARIATION WITH WAVE PERIOD/FREQUENCY", one per direction: "FROUDE KRYLOV
  + DIFFRACTION FORCES" (excitation), "DIFFRACTION FORCES", "FROUDE KRYLOV FORCES"
  (amplitude with 3 significant digits, phase in degrees) and "R.A.O.S" (motion RAOs,
  rotations in degrees per metre, converted to rad/m).
* "MASS AND INERTIA PROPERTIES": mass, centre of gravity and inertia matrix.
* With the LHFR option, "HYDRODYNAMIC PARAMETERS AT LOW & HIGH FREQUENCIES".

``.AH1`` (any number of structures): a ``*`` header, then ``nbodies ndirections
nfrequencies`` with the directions and frequencies, and keyword sections GENERAL
(depth, ρ, g), COG, COB, DISPLACEMENT, MASS, HYDSTIFFNESS, ADDEDMASS and DAMPING
(records ``body body frequency`` + 6×6), FORCERAO (records ``body direction
frequency``: 6 amplitudes then 6 phases in degrees) and, with LHFR, ADDEDMASS_LF,
DAMPING_LF and ADDEDMASS_HF. It has the same 5-digit A and B as the listing, 5-digit
excitation amplitudes, but no RAOs and no Froude-Krylov/diffraction split.

Low and high frequency rows (LHFR option). The AH1 header says they are computed at
0.001 and 100 rad/s (the listing prints 0.0018 and 100 rad/s). At 100 rad/s the wave
length 2πg/ω² is 6 mm: shorter than any panel, so the value is the ω → ∞ limit for any
real structure, and cummins stores it as ``added_mass_inf`` (the cross-code test of the
WEC-Sim cylinder finds it within 2 % of WAMIT's ω = ∞ solution). The low-frequency row
is *not* used as A(0): in finite depth the heave added mass keeps changing as ω → 0
(AQWA's A33 at 0.0018 rad/s is 60 % above WAMIT's ω = 0 value for the cylinder), so it
is left out, and ``history`` says so.

Conventions. AQWA prints phase lags: x(t) = |X| cos(ωt − φ), i.e. X = |X| exp(−iφ) in
cummins' exp(+iωt) convention (the listing's velocity RAO phases are the RAO phases
minus 90°, as that requires). Phases are relative to the incident wave at the centre of
gravity (as WEC-Sim's reader assumes); cummins refers them to the global origin by
adding k (x_G cos β + y_G sin β) to φ. Wave directions are directions of propagation,
anticlockwise from +x (0 = following seas), as cummins; AQWA often lists both −180°
and 180°, kept as two directions.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import dof_labels, make_hydrodb
from cummins.io._common import resolve_rho_g, warn_damage
from cummins.io._text import TextFile, parse_numbers

__all__ = ["read_aqwa", "sniff", "sniff_dir"]

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"
_ROW_LABELS = ("X", "Y", "Z", "RX", "RY", "RZ")

#: Smallest frequency (rad/s) of an LHFR block taken as the ω → ∞ limit.
HIGH_FREQUENCY_LIMIT = 50.0


# --------------------------------------------------------------------------- detection


def _head(path: Path, size: int = 8192) -> str:
    with open(path, "rb") as f:
        return f.read(size).decode("utf-8-sig", errors="replace")


def _is_lis(head: str) -> bool:
    upper = head.upper()
    return "AQWA" in upper and ("DECK" in upper or "* * * *" in upper)


def _is_ah1(head: str) -> bool:
    lines = [line for line in head.splitlines() if line.strip()]
    body = [line for line in lines if not line.lstrip().startswith("*")]
    if not body:
        return False
    first = parse_numbers(body[0])
    if first is None or first.size < 3 or not np.all(first[:3] == np.round(first[:3])):
        return False
    keywords = {line.strip() for line in body}
    return bool(keywords & {"GENERAL", "COG", "ADDEDMASS", "HYDSTIFFNESS"})


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` an AQWA ``.LIS`` listing or ``.AH1`` database?"""
    path = Path(path)
    if not path.is_file():
        return False
    head = _head(path, 65536)
    return _is_lis(head[:8192]) or _is_ah1(head)


def sniff_dir(path: Path) -> list[Path]:
    """The AQWA runs in a folder: each ``.LIS``, and each ``.AH1`` without a ``.LIS``."""
    path = Path(path)
    files = sorted(p for p in path.iterdir() if p.is_file())
    lis = [p for p in files if p.suffix.lower() == ".lis" and _is_lis(_head(p))]
    stems = {p.stem.lower() for p in lis}
    ah1 = [
        p
        for p in files
        if p.suffix.lower() == ".ah1" and p.stem.lower() not in stems and _is_ah1(_head(p, 65536))
    ]
    return lis + ah1


# --------------------------------------------------------------------------- shared pieces


def wavenumber(omega: np.ndarray, depth: float, g: float) -> np.ndarray:
    """Wave number k (rad/m) with ω² = g k tanh(k h) (deep water if ``depth`` is inf)."""
    omega = np.asarray(omega, dtype=float)
    k = omega**2 / g
    if not np.isfinite(depth):
        return k
    k = np.maximum(k, omega / np.sqrt(g * depth))  # shallow-water start: converges from above
    for _ in range(100):
        t = np.tanh(k * depth)
        f = g * k * t - omega**2
        df = g * t + g * k * depth * (1 - t**2)
        step = f / df
        k = k - step
        if np.all(np.abs(step) <= 1e-12 * k):
            break
    return k


def _complex(amplitude, phase_deg, omega, beta_deg, cg, depth, g) -> np.ndarray:
    """AQWA (amplitude, phase lag in degrees, relative to the wave at the CG) to cummins.

    Shapes: amplitude/phase (nω, nβ, n); returns X = A exp(−i(φ + k (x_G cos β + y_G sin β))).
    """
    k = wavenumber(omega, depth, g)[:, None]
    beta = np.radians(beta_deg)[None, :]
    shift = k * (cg[0] * np.cos(beta) + cg[1] * np.sin(beta))
    return amplitude * np.exp(-1j * (np.radians(phase_deg) + shift[..., None]))


def _depth(value: float) -> float:
    return value if value > 0 else np.inf


# --------------------------------------------------------------------------- .LIS


def _despace(line: str) -> str:
    """``* * * * H Y D R O   P A R`` → ``****HYDRO PAR`` (AQWA's letter-spaced titles)."""
    return re.sub(r"\s+", " ", re.sub(r"(?<=\S) (?=\S)", "", line.strip()))


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


@dataclass
class _Lis:
    text: TextFile
    titles: list[tuple[int, str]] = field(default_factory=list)


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


def _leading_numbers(line: str) -> list[float]:
    values = []
    for token in line.split():
        try:
            values.append(float(token))
        except ValueError:
            break
    return values


def _lis_frequencies(text: TextFile, titles) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Frequencies (rad/s), wave numbers (rad/m) and directions (deg) of the listing."""
    starts = [i for i, t in titles if t.startswith("****WAVE FREQUENCIES/PERIODS AND DIRECTIONS")]
    if not starts:
        raise text.error("no WAVE FREQUENCIES/PERIODS AND DIRECTIONS table (truncated?)")
    omega, k_table, directions = [], [], []
    first_row = -1
    for start in starts:
        header = _label_line_prefix(text, "STRUCTURE", start, start + 12)
        if header < 0:
            continue
        is_direction = "DIRECTIONS" in text.lines[header]
        k = next(
            (
                j
                for j in range(header + 1, min(header + 6, len(text.lines)))
                if _is_rule(text.lines[j])
            ),
            -1,
        )
        if k < 0:
            raise text.error("table header without its dashed rule", header)
        k += 1
        while k < len(text.lines) and not _is_rule(text.lines[k]):
            line = text.lines[k]
            if line.strip() == "1":  # Fortran carriage control: the table goes on overleaf
                break
            values = _leading_numbers(line)
            if not values:
                if line.strip():
                    raise text.error(f"expected a row of numbers, found {line.strip()[:60]!r}", k)
                k += 1
                continue
            if is_direction:
                directions.extend(values[1:] if not directions else values)
            else:
                if len(values) == 10:
                    values = values[1:]
                if len(values) != 9:
                    raise text.error(
                        f"expected 9 numbers in the frequency table, found {len(values)}", k
                    )
                if first_row < 0:
                    first_row = k
                omega.append(values[1])
                k_table.append(values[4])
            k += 1
    if not omega:
        raise text.error("the wave frequency table is empty", starts[0])
    if not directions:
        raise text.error("no wave directions in the listing", starts[0])
    return np.asarray(omega), np.asarray(k_table), np.asarray(directions), first_row


def _is_rule(line: str) -> bool:
    stripped = line.strip()
    return bool(stripped) and set(stripped) <= set("-")


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
    titles = [(i, _despace(line)) for i, line in enumerate(text.lines) if "* * * *" in line]
    structures = {int(m.group(1)) for _, t in titles if (m := re.search(r"FOR STRUCTURE (\d+)", t))}
    if len(structures) > 1:
        raise text.error(
            f"the listing describes {len(structures)} structures",
            hint="read the .AH1 file of the run, which cummins reads for several structures",
        )
    history = [f"read AQWA listing {path.name}"]
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
    omega, _, directions, _ = _lis_frequencies(text, titles)
    a, b, stiffness = _lis_radiation(text, omega)
    cg = _lis_cg(text)
    history.append(
        f"matrices and forces about the centre of gravity {cg.tolist()} m "
        "(AQWA: WITH RESPECT TO STRUCTURE COG)"
    )

    extra: dict = {}
    if stiffness is not None:
        extra["hydrostatic_stiffness"] = stiffness
    a_inf, high, low = _lis_limits(text, titles)
    _limits_history(history, a_inf, high, low, g_v)
    if a_inf is not None:
        extra["added_mass_inf"] = a_inf
    tables = _lis_tables(text, titles, omega.size)
    names = {
        "excitation": "excitation_force",
        "diffraction": "diffraction_force",
        "froude_krylov": "froude_krylov_force",
        "rao": "rao",
    }
    for kind, rows in tables.items():
        amplitude, phase = _assemble(text, rows, omega, directions, kind)
        if kind == "rao":
            amplitude[..., 3:] = np.radians(amplitude[..., 3:])
            history.append("RAO rotations converted from deg/m to rad/m")
        extra[names[kind]] = _complex(amplitude, phase, omega, directions, cg, depth, g_v)
    if tables:
        extra["wave_direction"] = np.radians(directions)
        history.append(
            "AQWA phase lags converted: X = |X| exp(-i(phase + k(xG cos b + yG sin b))), "
            "phases referred from the centre of gravity to the origin"
        )
        history.append("excitation amplitudes printed with 3 significant digits in the listing")
    mass, inertia = _lis_mass(text, titles)
    if mass is not None and inertia is not None:
        m = np.zeros((6, 6))
        m[:3, :3] = mass * np.eye(3)
        m[3:, 3:] = inertia
        extra["inertia_matrix"] = m
        history.append(
            f"inertia matrix from MASS AND INERTIA PROPERTIES (mass {mass:.6g} kg, inertia "
            "matrix about the centre of gravity)"
        )
    else:
        history.append("no MASS AND INERTIA PROPERTIES in the listing: no inertia_matrix")
    notes: list[str] = []
    _lis_completeness(text, tables, a_inf is not None or high is not None, notes)
    cb = np.array([_value_after(text, key)[0] for key in ("BX", "BY", "BZ")])
    volume, _ = _value_after(text, "MESH BASED DISPLACEMENT")
    return make_hydrodb(
        omega,
        a,
        b,
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format="aqwa",
        source_file=str(path),
        dofs=dof_labels(),
        reference_point=cg,
        history=history,
        center_of_gravity=cg,
        center_of_buoyancy=cb if not any(v is None for v in cb) else None,
        displaced_volume=volume,
        read_warnings=notes,
        **extra,
    )


def _lis_completeness(text: TextFile, tables: dict, has_lhfr: bool, notes: list[str]) -> None:
    """Warn when the listing ends before the sections it announces.

    AQWA closes every listing with a ``FINISH DATE`` line; the ``OPTIONS`` cards of the
    input echo announce the LHFR block (low and high frequency limits).
    """
    options = {
        word
        for line in text.lines[:400]
        if line.strip().startswith("OPTIONS")
        for word in line.split()[1:]
    }
    if "LHFR" in options and not has_lhfr:
        warn_damage(
            "OPTIONS LHFR announces the HYDRODYNAMIC PARAMETERS AT LOW & HIGH FREQUENCIES, "
            "but the listing has none (truncated?): read without added_mass_inf",
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


def _limits_history(history: list[str], a_inf, high, low, g: float) -> None:
    if a_inf is None and high is not None:
        history.append(
            f"AQWA's added mass at {high:g} rad/s not used as A(inf): frequency "
            f"below {HIGH_FREQUENCY_LIMIT:g} rad/s"
        )
    if a_inf is not None:
        history.append(
            f"added_mass_inf = AQWA's added mass at {high:g} rad/s (LHFR option; "
            f"wave length {2 * np.pi * g / high**2 * 1000:.2g} mm: the infinite-"
            "frequency limit)"
        )
    if low is not None:
        history.append(
            f"AQWA's low-frequency added mass and damping ({low:g} rad/s, LHFR) "
            "not used as A(0): in finite depth heave A(w) has no settled limit there"
        )


# --------------------------------------------------------------------------- .AH1


@dataclass
class _Section:
    name: str
    rows: list[np.ndarray]
    lines: list[int]


def _ah1_sections(text: TextFile) -> tuple[list[float], list[int], dict[str, _Section], str]:
    """Header numbers, their lines, the keyword sections and the ``*`` header text."""
    header = []
    numbers: list[float] = []
    number_lines: list[int] = []
    sections: dict[str, _Section] = {}
    current: _Section | None = None
    for i, line in enumerate(text.lines):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith("*") and not sections and not numbers:
            header.append(stripped)
            continue
        if re.fullmatch(r"[A-Z][A-Z_0-9]*", stripped):
            if stripped in sections:
                raise text.error(f"section {stripped} appears twice", i)
            current = sections[stripped] = _Section(stripped, [], [])
            continue
        values = parse_numbers(line)
        if values is None:
            raise text.error(f"expected a row of numbers, found {stripped[:60]!r}", i)
        if not np.all(np.isfinite(values)):
            raise text.error("non-finite value (NaN or Inf) in the data", i)
        if current is None:
            numbers.extend(values.tolist())
            number_lines.extend([i] * values.size)
        else:
            current.rows.append(values)
            current.lines.append(i)
    return numbers, number_lines, sections, "\n".join(header)


def _records(text: TextFile, section: _Section, n_index: int, n_rows: int):
    """Records of ``n_rows`` lines: ``n_index`` indices + 6 values, then rows of 6.

    Values are in AQWA's E format (1.2345E+06), except the second row of a FORCERAO
    record (phases, -178.71)."""
    out = []
    r = 0
    rows, lines = section.rows, section.lines
    while r < len(rows):
        first = rows[r]
        if first.size != n_index + 6:
            raise text.error(
                f"{section.name}: expected {n_index} indices and 6 values, "
                f"found {first.size} numbers",
                lines[r],
            )
        index = first[:n_index]
        if np.any(index != np.round(index)) or np.any(index < 1):
            raise text.error(f"{section.name}: indices must be positive whole numbers", lines[r])
        _check_fields(text, section.name, lines[r], n_index, _AH1_FIELDS[0])
        block = [first[n_index:]]
        for extra in range(1, n_rows):
            if r + extra >= len(rows):
                raise text.error(f"{section.name}: record incomplete (truncated?)", lines[-1])
            if rows[r + extra].size != 6:
                raise text.error(
                    f"{section.name}: expected 6 numbers, found {rows[r + extra].size}",
                    lines[r + extra],
                )
            phases = section.name == "FORCERAO" and extra == 1
            _check_fields(text, section.name, lines[r + extra], 0, _AH1_FIELDS[1 if phases else 0])
            block.append(rows[r + extra])
        out.append((index.astype(int), np.vstack(block), lines[r]))
        r += n_rows
    return out


#: The fixed formats AQWA writes the values of an AH1 record in: 1.2345E+06 (matrices,
#: amplitudes) or -178.71 (phases), one format per row.
_AH1_FIELDS = (re.compile(r"-?\d\.\d{4}E[-+]\d\d"), re.compile(r"-?\d+\.\d\d"))

#: Largest asymmetry |M_ij - M_ji| / (sqrt|M_ii M_jj| + 1e-3 sqrt(T_i T_j)) accepted in
#: an AQWA matrix (T: largest diagonal of the same kind over all frequencies). Measured:
#: ≤ 0.69 in the damping, ≤ 0.17 in the added mass of the three AQWA runs of the corpus
#: and the shared data (noise in near-zero couplings); rows swapped or edited give
#: 10–10⁶.
ASYMMETRY_LIMIT = 2.0


def _check_fields(text: TextFile, section: str, line: int, n_index: int, form) -> None:
    """A record row must be written in AQWA's fixed format ``form`` (a cut number, or a
    row of phases among matrix rows, is not)."""
    fields = text.lines[line].split()[n_index:]
    bad = next((f for f in fields if not form.fullmatch(f)), None)
    if bad is not None:
        raise text.error(
            f"{section}: {bad!r} is not written in AQWA's format for this row (cut, moved or "
            "edited?)",
            line,
        )


def asymmetry(matrices: np.ndarray) -> np.ndarray:
    """Relative asymmetry of each n×n matrix of ``matrices`` (…, n, n), see
    :data:`ASYMMETRY_LIMIT`; 0 for a symmetric matrix."""
    stack = np.asarray(matrices, dtype=float).reshape(-1, *np.shape(matrices)[-2:])
    n = stack.shape[-1]
    diag = np.abs(np.diagonal(stack, axis1=1, axis2=2))
    rot = (np.arange(n) % 6) >= 3
    largest = np.array([diag[:, rot == rot[i]].max() for i in range(n)])
    floor = 1e-3 * np.sqrt(np.outer(largest, largest))
    scale = np.sqrt(diag[:, :, None] * diag[:, None, :]) + floor + np.finfo(float).tiny
    return (np.abs(stack - np.swapaxes(stack, 1, 2)) / scale).max(axis=(1, 2))


def _check_symmetric(text: TextFile, section: _Section, matrices: np.ndarray, omega=None):
    """HydroDataError when a matrix of ``section`` is far from symmetric (rows swapped)."""
    values = asymmetry(matrices)
    worst = int(np.argmax(values))
    if values[worst] > ASYMMETRY_LIMIT:
        where = f" at {omega[worst]:g} rad/s" if omega is not None else ""
        raise text.error(
            f"{section.name}: the matrix{where} is not symmetric (asymmetry "
            f"{values[worst]:.3g}, AQWA's are below {ASYMMETRY_LIMIT:g}): rows swapped or edited?",
            section.lines[0],
        )


def _ah1_require(text: TextFile, sections: dict[str, _Section], name: str) -> _Section:
    if name not in sections or not sections[name].rows:
        raise text.error(f"no {name} section (truncated?)", len(text.lines) - 1)
    return sections[name]


def _ah1_matrices(text, sections, name, nb, nf, with_frequency: bool) -> np.ndarray:
    """ADDEDMASS/DAMPING (nf, 6nb, 6nb) or *_LF/_HF (6nb, 6nb) from their records."""
    section = _ah1_require(text, sections, name)
    n_index = 3 if with_frequency else 2
    shape = (nf, 6 * nb, 6 * nb) if with_frequency else (6 * nb, 6 * nb)
    out = np.full(shape, np.nan)
    for index, block, line in _records(text, section, n_index, 6):
        i, j = index[0] - 1, index[1] - 1
        if i >= nb or j >= nb or (with_frequency and index[2] > nf):
            raise text.error(f"{name}: index {index.tolist()} out of range", line)
        target = out[index[2] - 1] if with_frequency else out
        view = target[6 * i : 6 * i + 6, 6 * j : 6 * j + 6]
        if not np.isnan(view).all():
            raise text.error(f"{name}: record {index.tolist()} appears twice", line)
        view[...] = block
    if np.isnan(out).any():
        where = np.argwhere(np.isnan(out))[0]
        raise text.error(
            f"{name}: missing record for {(where // 6 + 1).tolist()} (truncated?)",
            section.lines[-1],
        )
    _check_symmetric(text, section, out)
    return out


def _ah1_per_body(text, sections, name, nb) -> np.ndarray:
    """MASS / HYDSTIFFNESS: one 6×6 per body (first row prefixed by the body index)."""
    section = _ah1_require(text, sections, name)
    out = np.zeros((6 * nb, 6 * nb))
    records = _records(text, section, 1, 6)
    if len(records) != nb:
        raise text.error(f"{name}: {len(records)} matrices for {nb} bodies", section.lines[-1])
    for index, block, line in records:
        k = index[0] - 1
        if k >= nb:
            raise text.error(f"{name}: body {index[0]} out of range", line)
        out[6 * k : 6 * k + 6, 6 * k : 6 * k + 6] = block
    _check_symmetric(text, section, out)
    return out


def _ah1_points(text, sections, name, nb) -> np.ndarray | None:
    if name not in sections:
        return None
    section = sections[name]
    points = np.full((nb, 3), np.nan)
    for row, line in zip(section.rows, section.lines, strict=True):
        if row.size != 4 or row[0] != round(row[0]) or not 1 <= row[0] <= nb:
            raise text.error(f"{name}: expected 'body x y z'", line)
        points[int(row[0]) - 1] = row[1:]
    if np.isnan(points).any():
        raise text.error(f"{name}: a body is missing", section.lines[-1] if section.lines else None)
    return points


def _ah1_lhfr(header: str) -> tuple[float, float]:
    """Low and high LHFR frequencies (rad/s) stated in the AH1 header (0.001 and 100)."""
    flat = re.sub(r"\s*\n\s*\*\s*", " ", header.upper())
    found = []
    for which, default in (("LOW", 0.001), ("HIGH", 100.0)):
        m = re.search(which + r"-\s*FREQUENCY\s*\((" + _NUMBER + r")\s*RAD/S\)", flat)
        found.append(float(m.group(1)) if m else default)
    return found[0], found[1]


def _ah1_header(text: TextFile, numbers: list[float], lines: list[int]):
    """Bodies, directions (deg) and frequencies (rad/s) of the numeric AH1 header.

    File version 5 (AQWA 2022 R1) writes one block ``body nh nf directions frequencies``
    per structure (``1 3 100 …`` then ``2 3 100 …``); one block whose first number is
    above 1 is read as the older ``nbodies nh nf …`` (one set for all structures).
    """
    blocks = []
    pos = 0
    while pos < len(numbers):
        if len(numbers) - pos < 3:
            raise text.error("expected 'body directions frequencies' in the header", lines[pos])
        first, nh, nf = numbers[pos : pos + 3]
        if min(first, nh, nf) < 1 or any(v != round(v) for v in (first, nh, nf)) or first > 100:
            raise text.error("invalid numbers of bodies, directions or frequencies", lines[pos])
        nh, nf = int(nh), int(nf)
        end = pos + 3 + nh + nf
        if end > len(numbers):
            raise text.error(
                f"expected {nh} directions and {nf} frequencies, found {len(numbers) - pos - 3} "
                "numbers",
                lines[-1],
            )
        blocks.append(
            (
                int(first),
                np.asarray(numbers[pos + 3 : pos + 3 + nh]),
                np.asarray(numbers[pos + 3 + nh : end]),
                lines[pos],
            )
        )
        pos = end
    if len(blocks) == 1:
        return blocks[0][0], blocks[0][1], blocks[0][2]
    for k, (index, directions, omega, line) in enumerate(blocks):
        if index != k + 1:
            raise text.error(f"header block of body {index} where body {k + 1} was expected", line)
        if directions.shape != blocks[0][1].shape or not np.allclose(directions, blocks[0][1]):
            raise text.error("the bodies have different wave directions", line)
        if omega.shape != blocks[0][2].shape or not np.allclose(omega, blocks[0][2]):
            raise text.error("the bodies have different wave frequencies", line)
    return len(blocks), blocks[0][1], blocks[0][2]


def _read_ah1(path: Path, rho, g) -> xr.Dataset:
    text = TextFile.read(path)
    numbers, number_lines, sections, header = _ah1_sections(text)
    if len(numbers) < 3:
        raise text.error("expected 'bodies directions frequencies' after the header")
    nb, directions, omega = _ah1_header(text, numbers, number_lines)
    nh, nf = directions.size, omega.size
    notes: list[str] = []
    version = re.search(r"FILE VERSION NO\s*(\d+)", header)
    history = [
        f"read AQWA hydrodynamic database {path.name} (file version "
        f"{version.group(1) if version else '?'}; {nb} structure{'s' if nb > 1 else ''})"
    ]
    if not any(
        p.suffix.lower() == ".lis" and p.stem.lower() == path.stem.lower()
        for p in path.parent.iterdir()
    ):
        history.append(
            f"no {path.stem}.LIS beside the database: read without what only the listing "
            "holds (motion RAOs, the Froude-Krylov/diffraction split, the structures' names); "
            "rho, g and depth from GENERAL, mass and inertia from MASS, excitation from "
            "FORCERAO"
        )
    general = _ah1_require(text, sections, "GENERAL").rows[0]
    if general.size >= 4:
        depth, rho_f, g_f = general[1:4]
    elif general.size == 3:
        depth, rho_f, g_f = general
    else:
        raise text.error(
            "GENERAL: expected depth, density and gravity", sections["GENERAL"].lines[0]
        )
    if rho_f <= 0 or g_f <= 0 or depth < 0:
        raise text.error(
            "GENERAL: density and gravity must be positive", sections["GENERAL"].lines[0]
        )
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        float(rho_f),
        float(g_f),
        path=path,
        history=history,
        dimensional=True,
    )
    depth = _depth(float(depth))
    cog = _ah1_points(text, sections, "COG", nb)
    if cog is None:
        raise text.error("no COG section: AQWA refers all results to the centre of gravity")
    history.append("matrices and forces about the centre(s) of gravity (COG section)")
    a = _ah1_matrices(text, sections, "ADDEDMASS", nb, nf, True)
    b = _ah1_matrices(text, sections, "DAMPING", nb, nf, True)
    extra: dict = {}
    extra["hydrostatic_stiffness"] = _ah1_per_body(text, sections, "HYDSTIFFNESS", nb)
    if "MASS" in sections:
        extra["inertia_matrix"] = _ah1_per_body(text, sections, "MASS", nb)
        masses = np.diag(extra["inertia_matrix"])[0::6]
        history.append(
            "inertia matrix from the MASS section (about each centre of gravity; mass "
            + ", ".join(f"{m:.6g}" for m in masses)
            + " kg)"
        )
    else:
        history.append("no MASS section: no inertia_matrix")
    low, high = _ah1_lhfr(header)
    if "ADDEDMASS_HF" in sections and high >= HIGH_FREQUENCY_LIMIT:
        extra["added_mass_inf"] = _ah1_matrices(text, sections, "ADDEDMASS_HF", nb, nf, False)
    _limits_history(
        history,
        extra.get("added_mass_inf"),
        high if "ADDEDMASS_HF" in sections else None,
        low if "ADDEDMASS_LF" in sections else None,
        g_v,
    )
    if "FORCERAO" not in sections:
        warn_damage(
            "no FORCERAO section, which AQWA writes after DAMPING: the file seems truncated; "
            "read without the excitation force",
            path=path,
            line=len(text.lines),
            notes=notes,
        )
    else:
        amplitude = np.full((nf, nh, 6 * nb), np.nan)
        phase = np.full_like(amplitude, np.nan)
        for index, block, line in _records(text, sections["FORCERAO"], 3, 2):
            k, h, n = index - 1
            if k >= nb or h >= nh or n >= nf:
                raise text.error(f"FORCERAO: index {index.tolist()} out of range", line)
            if not np.isnan(amplitude[n, h, 6 * k]):
                raise text.error(f"FORCERAO: record {index.tolist()} appears twice", line)
            amplitude[n, h, 6 * k : 6 * k + 6] = block[0]
            phase[n, h, 6 * k : 6 * k + 6] = block[1]
        if np.isnan(amplitude).any():
            n, h, d = np.argwhere(np.isnan(amplitude))[0]
            raise text.error(
                f"FORCERAO: no record for body {d // 6 + 1}, direction {h + 1}, "
                f"frequency {n + 1} (truncated?)",
                sections["FORCERAO"].lines[-1],
            )
        x = np.empty_like(amplitude, dtype=complex)
        for k in range(nb):
            s = slice(6 * k, 6 * k + 6)
            x[..., s] = _complex(
                amplitude[..., s], phase[..., s], omega, directions, cog[k], depth, g_v
            )
        extra["excitation_force"] = x
        extra["wave_direction"] = np.radians(directions)
        history.append(
            "AQWA phase lags converted: X = |X| exp(-i(phase + k(xG cos b + yG sin b))), "
            "phases referred from the centre of gravity to the origin"
        )
    cob = _ah1_points(text, sections, "COB", nb)
    volume = _ah1_volumes(text, sections, nb)
    names = [f"body{k + 1}" for k in range(nb)]

    def flat(points: np.ndarray | None) -> np.ndarray | None:
        return None if points is None else (points.reshape(-1) if nb > 1 else points[0])

    return make_hydrodb(
        omega,
        a,
        b,
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format="aqwa",
        source_file=str(path),
        dofs=dof_labels(names),
        reference_point=flat(cog),
        history=history,
        center_of_gravity=flat(cog),
        center_of_buoyancy=flat(cob),
        displaced_volume=volume,
        read_warnings=notes,
        **extra,
    )


def _ah1_volumes(text: TextFile, sections: dict[str, _Section], nb: int):
    """Displaced volumes (m³) of the DISPLACEMENT section: a float, one per body, or None."""
    if "DISPLACEMENT" not in sections:
        return None
    section = sections["DISPLACEMENT"]
    volumes = np.full(nb, np.nan)
    for row, line in zip(section.rows, section.lines, strict=True):
        if row.size != 2 or row[0] != round(row[0]) or not 1 <= row[0] <= nb:
            raise text.error("DISPLACEMENT: expected 'body volume'", line)
        volumes[int(row[0]) - 1] = row[1]
    if np.isnan(volumes).any():
        raise text.error("DISPLACEMENT: a body is missing", section.lines[-1])
    return float(volumes[0]) if nb == 1 else volumes


# --------------------------------------------------------------------------- reader


def read_aqwa(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
) -> xr.Dataset:
    """Read an AQWA-LINE ``.LIS`` listing or ``.AH1`` database into a ``HydroDB``.

    Parameters
    ----------
    path
        The ``.LIS`` (one structure; gives also RAOs and the Froude-Krylov/diffraction
        split) or the ``.AH1`` file (any number of structures), or a folder holding one
        run (the ``.LIS`` is preferred when both are there).
    rho, g
        Water density (kg/m³) and gravity (m/s²). AQWA's output is dimensional: they
        may only confirm the file's values (a different value is an error).

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB`` about the centre of gravity (``reference_point``), SI,
        exp(+iωt), z-up axes, phases relative to the wave at the global origin.

    Raises
    ------
    HydroDataError
        Unreadable, truncated or inconsistent files, naming file and line.
    """
    path = Path(path)
    if not path.exists():
        raise HydroDataError("no such file or folder", path=path)
    if path.is_dir():
        runs = sniff_dir(path)
        if len(runs) != 1:
            raise HydroDataError(
                f"expected one AQWA run (.LIS or .AH1) in the folder, found {len(runs)}",
                path=path,
                hint="pass the file to read",
            )
        path = runs[0]
    text_head = _head(path, 65536)
    if _is_lis(text_head[:8192]):
        return _read_lis(path, rho, g)
    if _is_ah1(text_head):
        return _read_ah1(path, rho, g)
    raise HydroDataError("not an AQWA .LIS or .AH1 file (unrecognised content)", path=path)
