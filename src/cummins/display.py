"""How the figures show a DOF's values: rotations in degrees, numerically-zero series as
"≈ 0", retardation functions up to where they have decayed, phases unwrapped.

The figures of :mod:`cummins.plots` and :mod:`cummins.fit_figures` share these rules so
that a roll angle is read in degrees everywhere, and the sway of a ship in head seas
(10⁻⁷ m of numerical noise) is not autoscaled into something that looks like a signal.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: A series is drawn as "≈ 0" when its peak is below this fraction of the largest peak of
#: the DOFs of its kind (translations with translations, rotations with rotations):
#: numerical noise of a solver is ~10⁻⁷ of the response, a real small response (sway in
#: seas 10° off the bow) ~10⁻².
NEGLIGIBLE = 1e-4

#: K(t) is shown up to where |K| stays below this fraction of its peak (and a little past).
DECAY_FRACTION = 0.01


def rotation_scale(unit: str) -> tuple[float, str]:
    """The factor and unit to show a value of ``unit`` with radians in degrees.

    >>> rotation_scale("rad")
    (57.29577951308232, 'deg')
    >>> rotation_scale("rad/m")
    (57.29577951308232, 'deg/m')
    >>> rotation_scale("rad²·s/rad")[1]
    'deg²·s/rad'
    >>> rotation_scale("m")
    (1.0, 'm')
    """
    if unit.startswith("rad²"):
        return float(np.degrees(1.0)) ** 2, "deg²" + unit[len("rad²") :]
    if unit == "rad" or unit.startswith("rad/") or unit.startswith("rad "):
        return float(np.degrees(1.0)), "deg" + unit[len("rad") :]
    return 1.0, unit


def motion_units(motion, dofs: Sequence[str]) -> list[str]:
    """The unit of each DOF's motion in a run: its ``units`` attribute (``"m | rad …"``),
    else m or rad."""
    from cummins.dofs import is_rotation

    given = str(motion.attrs.get("units", "")).split(" | ")
    return [
        given[k] if k < len(given) and given[k] else ("rad" if is_rotation(str(d)) else "m")
        for k, d in enumerate(dofs)
    ]


def negligible_series(peaks: ArrayLike, rotations: Sequence[bool]) -> NDArray[np.bool_]:
    """Which series are numerically zero: a peak below :data:`NEGLIGIBLE` of the largest
    peak of the series of the same kind (rotation or translation), or exactly zero.

    Parameters
    ----------
    peaks
        The largest absolute value of each series.
    rotations
        Whether each series is a rotation.

    >>> negligible_series([1.0, 2e-7, 0.5, 3e-9, 0.02, 0.0], [0, 0, 0, 1, 1, 1]).tolist()
    [False, True, False, True, False, True]
    """
    peaks = np.abs(np.asarray(peaks, dtype=float))
    kinds = np.asarray(rotations, dtype=bool)
    out = peaks == 0
    for kind in (False, True):
        same = kinds == kind
        if same.any():
            out |= same & (peaks < NEGLIGIBLE * peaks[same].max())
    return out


def mark_negligible(ax, peak: float, unit: str) -> None:
    """Draw a numerically-zero series as a flat line at 0 labelled "≈ 0" with its peak,
    instead of autoscaling its noise."""
    for line in ax.get_lines():
        line.set_ydata(np.zeros_like(np.asarray(line.get_ydata(), dtype=float)))
    ax.set_ylim(-1.0, 1.0)
    ax.set_yticks([0.0])
    ax.text(
        0.5,
        0.6,
        f"≈ 0 (peak {peak:.2g} {unit}: numerically zero)",
        transform=ax.transAxes,
        ha="center",
        va="center",
        fontsize="small",
        color="0.35",
    )


def decay_time(t: ArrayLike, k: ArrayLike, fraction: float = DECAY_FRACTION) -> float:
    """The time after which |K(t)| stays below ``fraction`` of its peak (the last time if
    it never does; 0 for K ≡ 0).

    >>> t = [0.0, 1.0, 2.0, 3.0, 4.0]
    >>> decay_time(t, [0.0, 1.0, 0.5, 0.005, 0.001])
    3.0
    """
    t = np.asarray(t, dtype=float)
    a = np.abs(np.asarray(k, dtype=float))
    if a.size == 0 or not a.max() > 0:
        return 0.0
    above = np.flatnonzero(a >= fraction * a.max())
    return float(t[min(above[-1] + 1, t.size - 1)])


def kernel_window(t: ArrayLike, curves: Sequence[ArrayLike], margin: float = 1.3) -> float:
    """The end of the time axis for K(t) panels: ``margin`` times the latest
    :func:`decay_time` of ``curves``, at most the record's end."""
    t = np.asarray(t, dtype=float)
    end = max((decay_time(t, c) for c in curves), default=float(t[-1]))
    return float(min(t[-1], max(margin * end, t[min(5, t.size - 1)])))


def note_kernel_window(ax, t_shown: float, t_record: float) -> None:
    """Say on a K(t) panel cut at ``t_shown`` where the record ends."""
    if t_shown < 0.999 * t_record:
        ax.text(
            0.99,
            0.95,
            f"|K| < {DECAY_FRACTION:.0%} of its peak beyond; record to {t_record:.3g} s",
            transform=ax.transAxes,
            ha="right",
            va="top",
            fontsize="x-small",
            color="0.35",
        )


def unwrapped_phase_deg(x: ArrayLike, tiny: float = 0.0) -> NDArray[np.float64]:
    """The phase of the complex series ``x`` in degrees, unwrapped (no jumps of 360°), NaN
    where |x| ≤ ``tiny`` (noise); each stretch between such gaps is unwrapped on its own.

    >>> unwrapped_phase_deg(np.exp(1j * np.radians([170.0, 180.0, 190.0]))).round(6).tolist()
    [170.0, 180.0, 190.0]
    """
    x = np.asarray(x).reshape(-1)
    phase = np.full(x.shape, np.nan)
    good = np.concatenate([np.abs(x) > tiny, [False]])
    edges = np.flatnonzero(np.diff(np.concatenate([[False], good]).astype(int)))
    for start, stop in zip(edges[::2], edges[1::2], strict=True):
        phase[start:stop] = np.degrees(np.unwrap(np.angle(x[start:stop])))
    return phase


def wrapped_phase_deg(x: ArrayLike, tiny: float = 0.0) -> NDArray[np.float64]:
    """The phase of the complex series ``x`` in degrees, in (−180°, 180°], NaN where
    |x| ≤ ``tiny`` (the phase of a negligible amplitude says nothing); draw it with
    :func:`phase_line`.

    >>> wrapped_phase_deg(np.exp(1j * np.radians([170.0, 190.0, 0.0])), 0.5).round(6).tolist()
    [170.0, -170.0, 0.0]
    """
    x = np.asarray(x).reshape(-1)
    phase = np.degrees(np.angle(x))
    phase[np.abs(x) <= tiny] = np.nan
    return phase


def phase_line(
    w: ArrayLike, phase_deg: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(w, phase)`` with a NaN inserted wherever the wrapped phase jumps by more than
    180° between two neighbours, so that its line breaks there instead of crossing the
    panel (as seakeeping tools draw a phase in ±180°).

    >>> phase_line([1.0, 2.0, 3.0], [170.0, -170.0, -160.0])[1].tolist()
    [170.0, nan, -170.0, -160.0]
    """
    w = np.asarray(w, dtype=float).reshape(-1)
    phase = np.asarray(phase_deg, dtype=float).reshape(-1)
    wraps = np.flatnonzero(np.abs(np.diff(phase)) > 180.0) + 1
    return np.insert(w, wraps, np.nan), np.insert(phase, wraps, np.nan)


def power_text(watts: float, per: str = "", digits: int = 4) -> str:
    """A power in the unit that reads best: W below 1 kW (a tank-scale buoy's 0.0408 W,
    not 4.08e-05 kW), kW below 1000 kW, MW above; ``per`` follows the unit (``"/m²"``
    for a power per unit wave amplitude squared).

    >>> power_text(0.0408)
    '0.0408 W'
    >>> power_text(278_330.0)
    '278.3 kW'
    >>> power_text(2.5e6, "/m²")
    '2.5 MW/m²'
    >>> power_text(float("nan"))
    'nan W'
    """
    factor, unit = power_unit(watts)
    return f"{watts / factor:.{digits}g} {unit}{per}"


def power_unit(watts: float) -> tuple[float, str]:
    """(factor, unit) of :func:`power_text` for a power of this size (an axis's largest).

    >>> power_unit(28.2), power_unit(-4.6e3)
    ((1.0, 'W'), (1000.0, 'kW'))
    """
    return _prefixed_unit(watts, "W")


def energy_unit(joules: float) -> tuple[float, str]:
    """(factor, unit) to show an energy of this size: J below 1 kJ (a tank-scale buoy's
    8.7 J, not 8.7e-06 MJ), kJ below 1000 kJ, MJ above, as :func:`power_unit`.

    >>> energy_unit(8.7), energy_unit(2.2e7)
    ((1.0, 'J'), (1000000.0, 'MJ'))
    """
    return _prefixed_unit(joules, "J")


def _prefixed_unit(value: float, base: str) -> tuple[float, str]:
    size = abs(value)
    for factor, prefix in ((1e6, "M"), (1e3, "k")):
        if size >= factor:
            return factor, prefix + base
    return 1.0, base


def peak_index(values: ArrayLike, rtol: float = 1e-9) -> tuple[int, int]:
    """(frequency, heading) of the largest of ``values`` (omega, heading): among headings
    whose peaks tie within ``rtol`` (an axisymmetric buoy's, the same at every heading up
    to the solver's rounding) the first, so that a table does not name the heading the
    rounding picked (60° of 0, 30, 60 and 90°) as if the peak were there."""
    a = np.abs(np.nan_to_num(np.asarray(values, dtype=float)))
    peaks = a.max(axis=0)
    j = int(np.flatnonzero(peaks >= peaks.max() * (1.0 - rtol))[0])
    return int(np.argmax(a[:, j])), j
