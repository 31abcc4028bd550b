"""The frequency grid and the wave tables of an MSS ``vessel`` struct, read.

``vessel.freqs`` split into ω = 0, the finite grid and MSS's stand-in for ω = ∞
(:func:`_frequency_grid`); the 6×6×Nfreq(×Nspeed) matrices as one shape
(:func:`_as_4d`); ``forceRAO``, ``motionRAO`` and ``driftfrc`` matched to that grid
(:func:`_wave_table`). The conventions are those of :mod:`cummins.io.mss`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from cummins.errors import HydroDataError
from cummins.io.mss.matfile import DRIFT_DOFS, _cells, _field, _numeric, _substruct

#: Relative tolerance when matching the frequency lists of the RAO tables to ``freqs``
#: (``driftfrc.w`` of VERES-derived files is rounded to 4 decimals: 0.1047 for 0.10472).
_FREQ_RTOL = 2e-3


@dataclass(frozen=True)
class _Grid:
    """Which entries of ``vessel.freqs`` are ω = 0, ω = ∞ and the finite grid."""

    omega: NDArray[np.float64]
    finite: slice
    zero: int | None
    infinite: int | None


def _frequency_grid(freqs: NDArray, damping: NDArray, path: Path, history: list[str]) -> _Grid:
    """Split ``freqs`` into ω = 0, the finite grid and MSS's stand-in for ω = ∞.

    ``damping`` has shape (6, 6, nfreq, nspeed).
    """
    if freqs.size == 0:
        raise HydroDataError("vessel.freqs is empty", path=path, quantity="vessel.freqs")
    if not np.all(np.isfinite(freqs)):
        raise HydroDataError("non-finite frequency", path=path, quantity="vessel.freqs")
    if np.any(np.diff(freqs) <= 0):
        k = int(np.argmax(np.diff(freqs) <= 0))
        raise HydroDataError(
            f"frequencies are not strictly increasing ({freqs[k]:g} then {freqs[k + 1]:g} rad/s)",
            path=path,
            quantity="vessel.freqs",
        )
    if freqs[0] < 0:
        raise HydroDataError("negative frequency", path=path, quantity="vessel.freqs")
    start, stop = 0, freqs.size
    zero = infinite = None
    if freqs[0] == 0:
        zero, start = 0, 1
        history.append("first entry of vessel.freqs is omega = 0: its A is added_mass_zero")
    if stop - start >= 3:
        last, before = damping[:, :, -1], damping[:, :, -2]
        if not np.any(last) and np.any(before):
            infinite, stop = freqs.size - 1, freqs.size - 1
            ratio = freqs[-1] / freqs[-2]
            history.append(
                f"last entry of vessel.freqs ({freqs[-1]:g} rad/s, {ratio:.2f} x the one "
                "before) has exactly zero damping: taken as MSS's stand-in for omega = "
                "infinity (WAMIT period 0); its A is added_mass_inf"
            )
    if stop <= start:
        raise HydroDataError("no finite frequency in vessel.freqs", path=path)
    return _Grid(freqs[start:stop], slice(start, stop), zero, infinite)


def _as_4d(arr: NDArray, nfreq: int, nspeed: int, path: Path, name: str) -> NDArray:
    """6×6×Nfreq(×Nspeed) as shape (6, 6, nfreq, nspeed)."""
    if arr.ndim == 2:
        arr = arr[:, :, None]
    if arr.ndim == 3:
        arr = arr[:, :, :, None]
    if arr.ndim != 4 or arr.shape[:3] != (6, 6, nfreq) or arr.shape[3] not in (1, nspeed):
        raise HydroDataError(
            f"has shape {arr.shape}, expected (6, 6, {nfreq}) or (6, 6, {nfreq}, {nspeed})",
            path=path,
            quantity=f"vessel.{name}",
        )
    if arr.shape[3] != nspeed:
        arr = np.repeat(arr, nspeed, axis=3)
    return arr


def _match_frequencies(w: NDArray, omega: NDArray) -> NDArray[np.intp] | None:
    """Index into ``w`` of each ``omega`` (tolerance :data:`_FREQ_RTOL`), or None."""
    if w.size == 0:
        return None
    idx = np.abs(w[None, :] - omega[:, None]).argmin(axis=1)
    if np.all(np.abs(w[idx] - omega) <= _FREQ_RTOL * omega):
        return idx
    return None


@dataclass(frozen=True)
class _WaveTable:
    """A ``forceRAO``/``motionRAO``/``driftfrc`` table on the dataset's grid."""

    values: NDArray  # (nspeed, nomega, nhead, 6)
    note: str | None = None


def _wave_table(
    vessel: np.void,
    name: str,
    omega: NDArray,
    nhead: int,
    nspeed: int,
    path: Path,
    history: list[str],
) -> _WaveTable | None:
    table = _substruct(vessel, name)
    if table is None:
        return None
    w = _numeric(_field(table, "w", path, f"vessel.{name}"), path, f"vessel.{name}.w").reshape(-1)
    amp = _cells(_field(table, "amp", path, f"vessel.{name}"), path, f"vessel.{name}.amp")
    drift = name == "driftfrc"
    if drift:
        phase = None
        if len(amp) < 3:
            raise HydroDataError(
                f"expected 3 drift components (surge, sway, yaw), found {len(amp)}",
                path=path,
                quantity="vessel.driftfrc.amp",
            )
        extra = [a for a in amp[3:] if np.any(a)]
        if extra:
            history.append(
                "driftfrc.amp{4:end} are not all zero: ignored (MSS stores "
                "surge, sway and yaw drift in amp{1:3})"
            )
        amp = amp[:3]
    else:
        phase = _cells(_field(table, "phase", path, f"vessel.{name}"), path, f"vessel.{name}.phase")
        if len(amp) != 6 or len(phase) != 6:
            raise HydroDataError(
                f"expected 6 amplitude and phase tables, found {len(amp)} and {len(phase)}",
                path=path,
                quantity=f"vessel.{name}",
            )
    index = _match_frequencies(w, omega)
    if index is None:
        history.append(
            f"vessel.{name} not read: its {w.size} frequencies ({w.min():g}-{w.max():g} "
            f"rad/s) do not cover the {omega.size} frequencies of vessel.A"
            if w.size
            else f"vessel.{name} not read: no frequencies"
        )
        return None

    def cube(a: NDArray, label: str) -> NDArray:
        if a.ndim == 2:
            a = a[:, :, None]
        if a.ndim != 3 or a.shape[0] != w.size or a.shape[1] != nhead or a.shape[2] < nspeed:
            raise HydroDataError(
                f"has shape {a.shape}, expected ({w.size}, {nhead}, >= {nspeed}) "
                "(frequencies, headings, speeds)",
                path=path,
                quantity=label,
            )
        return a[index][:, :, :nspeed]

    out = np.zeros((nspeed, omega.size, nhead, 6), dtype=float if drift else complex)
    for k, a in enumerate(amp):
        a3 = cube(a, f"vessel.{name}.amp{{{k + 1}}}")
        if drift:
            out[..., DRIFT_DOFS[k]] = np.moveaxis(a3, 2, 0)
        else:
            p3 = cube(phase[k], f"vessel.{name}.phase{{{k + 1}}}")
            out[..., k] = np.moveaxis(a3 * np.exp(1j * p3), 2, 0)
    return _WaveTable(out)
