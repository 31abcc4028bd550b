"""NEMOH's Tecplot result files: ``RadiationCoefficients.tec``, the force files, ``IRF.tec``.

Each file is a ``VARIABLES`` header, then zones of ``I`` rows of numbers (rows that
Fortran wrapped over several lines are joined); every zone repeats the same frequency
column, ω in rad/s unless the ``VARIABLES`` header says ``f (Hz)`` or ``T (s)`` (v3
"output freq type" 2 or 3), or ``Nemoh.cal`` asks for it.

* ``ExcitationForce.tec``, ``DiffractionForce.tec``, ``FKForce.tec``: one zone per wave
  direction ("… - beta = β deg"), rows ω, then (|F|, phase) per force. NEMOH's
  exp(−iωt) amplitudes are conjugated to cummins' exp(+iωt), F = |F|·exp(−i·phase).
  Phases are in radians (v2, v3.0); a file whose phases exceed π in magnitude is read
  as degrees (documented for later v3 releases).
* ``IRF.tec``: NEMOH's own A(∞), column "AddedMass k" of zone "DoF j" being
  ``added_mass_inf[influenced=k, radiating=j]``, accepted only when its K(t) is the
  cosine transform (2/π)∫B(ω)cos(ωt)dω of the run's damping, computed as NEMOH does
  (trapezoidal rule on the run's grid).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cummins.io._text import TextFile, check_cut_numbers, parse_numbers
from cummins.io.nemoh.files import _NUMBER, RADIATION_FILE

#: Largest relative mismatch between IRF.tec's K(t) and the one computed from the
#: run's damping for the IRF file to be accepted (same formula, same data: ~1e-6).
IRF_TOLERANCE = 0.05


# --------------------------------------------------------------------------- Tecplot files


@dataclass
class _Zone:
    title: str
    table: np.ndarray  # (rows, width)
    line: int  # 0-based index of the zone header line


@dataclass
class _Tecplot:
    text: TextFile
    variables: str
    zones: list[_Zone]

    @property
    def path(self) -> Path:
        return self.text.path


_ZONE_COUNT = re.compile(r"\bI\s*=\s*(\d+)", re.IGNORECASE)
_ZONE_TITLE = re.compile(r'T\s*=\s*"([^"]*)"', re.IGNORECASE)


def _read_tecplot(path: Path) -> _Tecplot:
    """Parse a NEMOH Tecplot file: header, then zones of ``I`` rows of numbers.

    Rows that Fortran wrapped over several lines (more than 80 values) are joined.
    """
    text = TextFile.read(path)
    lines = text.lines
    first = next((i for i, line in enumerate(lines) if line.strip()), None)
    if first is None or not lines[first].strip().upper().startswith("VARIABLES"):
        raise text.error(
            "not a NEMOH Tecplot file (no VARIABLES header)",
            first or 0,
            hint='NEMOH result files start with VARIABLES="w (rad/s)"',
        )
    zone_lines = [
        i for i in range(first, len(lines)) if lines[i].lstrip().lower().startswith("zone")
    ]
    if not zone_lines:
        raise text.error("no Zone in the file (truncated?)", len(lines) - 1)
    header = " ".join(lines[first : zone_lines[0]])
    names = re.findall(r'"([^"]*)"', header)
    width = len(names) if names and header.strip().upper().startswith('VARIABLES="') else 0
    zones: list[_Zone] = []
    for z, start in enumerate(zone_lines):
        stop = zone_lines[z + 1] if z + 1 < len(zone_lines) else len(lines)
        zone_line = lines[start]
        count_match = _ZONE_COUNT.search(zone_line)
        if count_match is None:
            raise text.error("zone header without its row count (I=…)", start)
        title_match = _ZONE_TITLE.search(zone_line)
        title = title_match.group(1) if title_match else zone_line.strip()
        table = _zone_rows(text, start + 1, stop, int(count_match.group(1)), width)
        if width == 0:
            width = table.shape[1]
        zones.append(_Zone(title.strip(), table, start))
    return _Tecplot(text, lines[first].strip(), zones)


def _zone_rows(text: TextFile, start: int, stop: int, count: int, width: int) -> np.ndarray:
    """``count`` rows of ``width`` numbers between lines ``start`` and ``stop``."""
    rows: list[np.ndarray] = []
    pending: list[np.ndarray] = []
    pending_size = 0
    for i in range(start, stop):
        line = text.lines[i]
        if not line.strip():
            continue
        values = parse_numbers(line)
        if values is None:
            raise text.error(f"expected a row of numbers, found {line.strip()[:60]!r}", i)
        if not np.all(np.isfinite(values)):
            raise text.error(
                "non-finite value (NaN or Inf) in the data",
                i,
                hint="the solver failed at this point; rerun it or remove the frequency",
            )
        if len(rows) == count:
            raise text.error(
                f"more rows than the {count} the zone header announces",
                i,
                hint="the file is damaged or was edited",
            )
        if width == 0:
            width = values.size
        pending.append(values)
        pending_size += values.size
        if pending_size == width:
            rows.append(np.concatenate(pending))
            pending, pending_size = [], 0
        elif pending_size > width:
            raise text.error(f"expected {width} numbers on the row, found {pending_size}", i)
    if pending or len(rows) != count:
        raise text.error(
            f"the zone announces {count} rows but has {len(rows)} complete ones (truncated?)",
            stop - 1,
        )
    numbered = [i for i in range(start, stop) if text.lines[i].strip()]
    check_cut_numbers(text, numbered, range(max(len(text.lines[i].split()) for i in numbered)))
    if width < 3 or width % 2 == 0:
        raise text.error(
            f"rows of {width} numbers: expected the frequency and pairs of values", start
        )
    return np.vstack(rows)


def _frequency_unit(tec: _Tecplot, cal_unit: int | None) -> str:
    """``"rad/s"``, ``"Hz"`` or ``"s"`` for the first column of a Tecplot file."""
    head = tec.variables.lower().replace(" ", "")
    if "rad/s" in head:
        return "rad/s"
    if "(hz)" in head:
        return "Hz"
    if "(s)" in head:
        return "s"
    return {2: "Hz", 3: "s"}.get(cal_unit or 1, "rad/s")


def _to_omega(values: np.ndarray, unit: str) -> np.ndarray:
    if unit == "Hz":
        return 2 * np.pi * values
    if unit == "s":
        with np.errstate(divide="ignore"):
            return 2 * np.pi / values
    return values


def _frequencies(tec: _Tecplot, cal_unit: int | None) -> tuple[np.ndarray, str]:
    """The common frequency column of all zones, as ω (rad/s), checked."""
    unit = _frequency_unit(tec, cal_unit)
    reference = tec.zones[0].table[:, 0]
    for zone in tec.zones[1:]:
        column = zone.table[:, 0]
        if column.shape != reference.shape or not np.allclose(column, reference, rtol=1e-6, atol=0):
            k = int(np.argmax(~np.isclose(column, reference, rtol=1e-6, atol=0)))
            raise tec.text.error(
                f"zone {zone.title!r} has other frequencies than the first zone "
                f"({column[k]:g} instead of {reference[k]:g})",
                zone.line + 1 + k,
                hint="the file is damaged or edited: each zone repeats the same frequencies",
            )
    step = np.diff(reference)
    if reference.size > 1 and not (np.all(step > 0) or np.all(step < 0)):
        k = int(np.argmax(step <= 0) if step[0] > 0 else np.argmax(step >= 0))
        raise tec.text.error(
            f"the frequency column is not monotonic ({reference[k]:g} then {reference[k + 1]:g})",
            tec.zones[0].line + 2 + k,
            hint="NEMOH writes the frequencies in order; the file seems edited or damaged",
        )
    if np.any(reference <= 0):
        k = int(np.argmax(reference <= 0))
        raise tec.text.error(
            f"frequency {reference[k]:g} {unit} is not positive", tec.zones[0].line + 1 + k
        )
    return _to_omega(reference, unit), unit


# --------------------------------------------------------------------------- forces


@dataclass
class _Forces:
    path: Path
    omega: np.ndarray
    beta_deg: np.ndarray
    values: np.ndarray  # complex, (n_omega, n_beta, n_forces), exp(+iωt)
    degrees: bool


_BETA = re.compile(r"beta\s*=\s*(" + _NUMBER + ")", re.IGNORECASE)


def _read_forces(path: Path, cal_unit: int | None) -> _Forces:
    tec = _read_tecplot(path)
    omega, _ = _frequencies(tec, cal_unit)
    betas = []
    for zone in tec.zones:
        match = _BETA.search(zone.title)
        if match is None:
            raise tec.text.error(
                f"zone title {zone.title!r} does not give the wave direction (beta = …)", zone.line
            )
        betas.append(float(match.group(1)))
    beta = np.asarray(betas)
    if np.unique(beta).size != beta.size:
        raise tec.text.error("the same wave direction appears in two zones", tec.zones[-1].line)
    table = np.stack([zone.table[:, 1:] for zone in tec.zones], axis=1)  # (nω, nβ, 2nf)
    magnitude, phase = table[..., 0::2], table[..., 1::2]
    degrees = bool(np.abs(phase).max() > np.pi + 1e-3) if phase.size else False
    if degrees:
        phase = np.radians(phase)
    return _Forces(tec.path, omega, beta, magnitude * np.exp(-1j * phase), degrees)


# --------------------------------------------------------------------------- IRF.tec


def _irf_added_mass(
    path: Path, omega: np.ndarray, damping: np.ndarray, n_dofs: int, n_forces: int
) -> tuple[np.ndarray | None, str]:
    """NEMOH's A(∞) from ``IRF.tec`` (forces × DOFs), or None with the reason.

    The file is accepted only if its K(t) on the diagonal matches the cosine transform
    of ``damping`` (nω, forces, DOFs) computed with NEMOH's trapezoidal rule.
    """
    tec = _read_tecplot(path)
    if len(tec.zones) != n_dofs or tec.zones[0].table.shape[1] != 1 + 2 * n_forces:
        return None, (
            f"{path.name} has {len(tec.zones)} zones of "
            f"{(tec.zones[0].table.shape[1] - 1) // 2} forces, the run "
            f"{n_dofs} DOFs and {n_forces} forces: not from this run"
        )
    time = tec.zones[0].table[:, 0]
    order = np.argsort(omega)
    w, b = omega[order], damping[order]
    worst = 0.0
    diagonal = [np.abs(b[:, j, j]).max() for j in range(min(n_dofs, n_forces))]
    for j, size in enumerate(diagonal):
        if size <= 1e-6 * max(diagonal):  # no damping in this DOF (e.g. yaw of a cylinder)
            continue
        k_file = tec.zones[j].table[:, 2 + 2 * j]
        k_run = 2 / np.pi * np.trapezoid(b[:, j, j][:, None] * np.cos(np.outer(w, time)), w, axis=0)
        scale = np.abs(k_run).max()
        mismatch = min(np.abs(k_file - k_run).max(), np.abs(k_file + k_run).max()) / scale
        worst = max(worst, mismatch)
    if worst > IRF_TOLERANCE:
        return None, (
            f"{path.name} not used, so no added_mass_inf: its K(t) differs from "
            "(2/pi)∫B cos(wt)dw of "
            f"{RADIATION_FILE} by {worst:.3g} (relative; {IRF_TOLERANCE:g} allowed), "
            "so it belongs to another run"
        )
    a_inf = np.stack([zone.table[0, 1::2] for zone in tec.zones], axis=1)  # (forces, DOFs)
    return a_inf, (
        f"added_mass_inf from NEMOH's IRF.tec ('AddedMass' columns; its K(t) "
        f"matches the run's damping to {worst:.2g})"
    )
