"""The steady harmonic part of a time series: complex amplitudes by least squares.

A regular-wave run settles into x(t) = Re{X e^{iωt}} + a mean; X is fitted over a whole
number of wave periods at the end of the record (the least-squares projection on
cos ωt, −sin ωt and a constant), so that the estimate does not depend on where the time
steps fall on the peaks (half the range of the samples does: by up to 1 − cos(ωΔt/2)).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import ArgumentError


def harmonic_amplitude(
    t: ArrayLike, x: ArrayLike, omega: float, periods: float = 2.0
) -> NDArray[np.complex128]:
    """X of x(t) ≈ Re{X e^{iωt}} + c over the last ``periods`` whole periods (or the whole
    record when shorter), one per column of ``x`` (shape (N,) or (N, k)).

    Examples
    --------
    >>> t = np.arange(0.0, 40.0, 0.1)
    >>> X = harmonic_amplitude(t, 2.0 * np.cos(0.8 * t + 0.3) + 1.0, 0.8)
    >>> print(round(float(abs(X)), 6), round(float(np.angle(X)), 6))
    2.0 0.3
    """
    t = np.asarray(t, dtype=float).reshape(-1)
    values = np.asarray(x, dtype=float)
    if values.shape[0] != t.size:
        raise ArgumentError(f"x has {values.shape[0]} samples for {t.size} times")
    if not omega > 0:
        raise ArgumentError(f"omega must be > 0 rad/s, not {omega}")
    last = last_periods(t, omega, periods)
    tt = t[last]
    basis = np.c_[np.cos(omega * tt), -np.sin(omega * tt), np.ones(tt.size)]
    coef, *_ = np.linalg.lstsq(basis, values[last], rcond=None)
    return coef[0] + 1j * coef[1]


def last_periods(t: ArrayLike, omega: float, periods: float = 10.0) -> NDArray[np.bool_]:
    """The samples of the last ``periods`` whole periods 2π/ω of the record (as many
    whole periods as it holds when fewer; the whole record when it holds none), the
    first sample of the span left out (it repeats the last): the window over which a
    steady regular-wave response is averaged or fitted.

    Examples
    --------
    >>> t = np.arange(0.0, 10.01, 0.5)
    >>> int(last_periods(t, 2 * np.pi / 4.0, 2).sum())   # 2 periods of 4 s at 0.5 s
    16
    """
    t = np.asarray(t, dtype=float).reshape(-1)
    if not omega > 0:
        raise ArgumentError(f"omega must be > 0 rad/s, not {omega}")
    period = 2 * np.pi / omega
    whole = np.floor((t[-1] - t[0]) / period + 1e-9)
    if whole < 1 or t.size < 2:
        return np.ones(t.size, bool)
    span = min(periods, whole) * period
    return t > t[-1] - span + 0.5 * float(np.min(np.diff(t)))
