"""Smoothed motions and their derivatives: the low-pass filter of the damping identification.

Velocities and accelerations are differentiated from the measured motions in the
frequency domain below a cut-off (2.5 times the motions' zero-crossing frequency by
default, :func:`default_cutoff`), and the excitation force is low-passed by the same
filter: the equation of motion (de Haan (2022) eq. 2.21), linear in ξ, holds exactly
between the filtered signals, so the filter adds no bias to the linear terms while it
removes the noise that differentiation amplifies. Used by :mod:`cummins.sysid.identify`,
which re-exports these names.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import IdentificationError
from cummins.sysid.records import time_step


def zero_crossing_period(x: NDArray, dt: float) -> float:
    """Mean zero-up-crossing period of a signal about its mean, s (inf without one)."""
    y = x - x.mean()
    up = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    if up.size < 2:
        return float("inf")
    return float((up[-1] - up[0]) * dt / (up.size - 1))


def default_cutoff(record: xr.Dataset) -> float:
    """Cut-off of the low-pass filter, rad/s: 2.5 times the highest mean zero-crossing
    frequency of the recorded motions (the velocities' band passes; the measurement noise
    above, which differentiation amplifies, is removed), at most 0.8 × Nyquist."""
    dt = time_step(record)
    periods = [zero_crossing_period(x, dt) for x in record.motion.values.T]
    finite = [p for p in periods if np.isfinite(p)]
    nyquist = np.pi / dt
    if not finite:
        return 0.8 * nyquist
    return float(min(2.5 * 2 * np.pi / min(finite), 0.8 * nyquist))


def _lowpass(omega: NDArray, cutoff: float) -> NDArray:
    """1 up to ``cutoff``, a cosine taper to 0 at 1.5 × ``cutoff``."""
    x = np.clip((omega - cutoff) / (0.5 * cutoff), 0.0, 1.0)
    return 0.5 * (1.0 + np.cos(np.pi * x))


def filtered_derivatives(
    x: NDArray, dt: float, cutoff: float, orders: Sequence[int] = (0, 1, 2)
) -> list[NDArray]:
    """d^k/dt^k of a low-passed signal (time along axis 0), k in ``orders``.

    The same zero-phase filter H(ω) (:func:`_lowpass`) multiplies (iω)^k x̂(ω): the
    filtered ξ, ξ̇, ξ̈ are exactly derivatives of one another and any linear relation
    between the raw signals (the equation of motion) holds between the filtered ones.
    The linear trend is removed first and the ends are extended by reflection, which
    keeps the periodic transform from joining the last sample to the first.
    """
    x = np.asarray(x, dtype=float)
    n = x.shape[0]
    t = np.arange(n) * dt
    slope = (x[-1] - x[0]) / (t[-1] - t[0])
    trend = x[0] + np.multiply.outer(t, slope)
    pad = min(n - 1, int(np.ceil(4 * 2 * np.pi / cutoff / dt)))
    y = np.pad(x - trend, [(pad, pad)] + [(0, 0)] * (x.ndim - 1), mode="reflect")
    spectrum = np.fft.rfft(y, axis=0)
    omega = 2 * np.pi * np.fft.rfftfreq(y.shape[0], dt)
    h = _lowpass(omega, cutoff).reshape(-1, *([1] * (x.ndim - 1)))
    out = []
    for k in orders:
        d = np.fft.irfft(spectrum * h * (1j * omega.reshape(h.shape)) ** k, y.shape[0], axis=0)
        d = d[pad : pad + n]
        if k == 0:
            d = d + trend
        elif k == 1:
            d = d + slope
        out.append(d)
    return out


def motion_derivatives(record: xr.Dataset, cutoff: float | None = None) -> xr.Dataset:
    """ξ, ξ̇, ξ̈ of a record, low-passed below ``cutoff`` rad/s (default
    :func:`default_cutoff`) and differentiated in the frequency domain
    (:func:`filtered_derivatives`); a measured ``velocity`` is used for ξ̇ and
    differentiated once. The ``excitation_force`` gets the same filter.

    Returns a Dataset with ``motion``, ``velocity``, ``acceleration`` (time, dof) and
    ``excitation_force`` when the record has one; attributes ``cutoff`` (rad/s) and
    ``edge`` (s): the filter's transients at each end, cut from any regression.
    """
    dt = time_step(record)
    cutoff = default_cutoff(record) if cutoff is None else float(cutoff)
    if not 0 < cutoff < np.pi / dt:
        raise IdentificationError(
            f"the cut-off {cutoff:g} rad/s must lie between 0 and the Nyquist frequency "
            f"{np.pi / dt:.4g} rad/s"
        )
    edge = 2 * 2 * np.pi / cutoff
    if record.sizes["time"] * dt < 4 * edge:
        raise IdentificationError(
            f"the record ({record.sizes['time'] * dt:g} s) is too short for the cut-off "
            f"{cutoff:g} rad/s (the filter needs {4 * edge:.3g} s)"
        )
    x = record.motion.values
    if "velocity" in record:
        xf = filtered_derivatives(x, dt, cutoff, (0,))[0]
        vf, af = filtered_derivatives(record.velocity.values, dt, cutoff, (0, 1))
    else:
        xf, vf, af = filtered_derivatives(x, dt, cutoff)
    out = {"motion": xf, "velocity": vf, "acceleration": af}
    if "excitation_force" in record:
        out["excitation_force"] = filtered_derivatives(
            record.excitation_force.values, dt, cutoff, (0,)
        )[0]
    return xr.Dataset(
        {k: (("time", "dof"), v) for k, v in out.items()},
        coords={"time": record.time.values, "dof": record.dof.values},
        attrs={"cutoff": cutoff, "edge": edge},
    )
