"""Driving a causal excitation model with a record of the wave elevation.

ẋ = A x + B η(t + t_c), F = C x (:mod:`cummins.excitation_model.model`) is integrated
exactly for an elevation linear between its samples (first-order hold, the
discretisation of :func:`cummins.timedomain.simulate.first_order_hold`), from rest at
the first sample. The force at t needs the elevation at t + t_c: a record of
η(t₀ … t_N) gives the force at t₀ … t_N − t_c, the last t_c of the record being the
forecast the model looks ahead into. A t_c that is not a whole number of steps is
handled exactly: the model is then driven by the elevation sampled at t + t_c
(interpolated linearly between the record's samples, the hold the integration assumes).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import SimulationError

__all__ = ["drive_model"]


def _uniform(t: ArrayLike, eta: ArrayLike) -> tuple[NDArray, NDArray, float]:
    times = np.asarray(t, dtype=float).reshape(-1)
    values = np.asarray(eta, dtype=float).reshape(-1)
    if times.size != values.size:
        raise SimulationError(f"{times.size} times but {values.size} wave elevations")
    if times.size < 2:
        raise SimulationError("at least two samples of the wave elevation are needed")
    dt = float(times[1] - times[0])
    if dt <= 0 or not np.allclose(
        np.diff(times), dt, rtol=1e-9, atol=1e-12 * max(abs(times[-1]), 1.0)
    ):
        raise SimulationError("the times of the wave elevation must be uniformly spaced")
    bad = ~np.isfinite(values)
    if bad.any():
        raise SimulationError(
            f"the wave elevation is not finite at t = {times[np.flatnonzero(bad)[0]]:.6g} s"
        )
    return times, values, dt


def drive_model(
    model, t: ArrayLike, elevation: ArrayLike, heading: int = 0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The forces of :meth:`ExcitationModel.force
    <cummins.excitation_model.model.ExcitationModel.force>` (see there): (times, forces).

    Raises
    ------
    SimulationError
        Non-uniform or too few samples, NaN in the record, a record shorter than the
        time advance t_c of the heading.
    """
    from cummins.timedomain.simulate import first_order_hold, propagate

    times, eta, dt = _uniform(t, elevation)
    if not 0 <= heading < np.size(model.headings):
        raise SimulationError(f"heading index {heading} is outside the model's headings")
    tc = float(model.delays[heading])
    usable = times <= times[-1] - tc + 1e-9 * dt
    if usable.sum() < 2:
        raise SimulationError(
            f"the wave record ({times[-1] - times[0]:.6g} s) is shorter than the model's "
            f"time advance t_c = {tc:.6g} s: the force at t needs the elevation at t + t_c"
        )
    out_t = times[usable]
    ahead = np.interp(out_t + tc, times, eta)
    a, b, c = model.state_space(heading)
    n = len(model.dofs)
    if a.shape[0] == 0:
        return out_t, np.zeros((out_t.size, n))
    disc = first_order_hold(a, b[:, None], dt)
    force = propagate(disc, ahead[:, None], np.zeros(a.shape[0]), c)
    return out_t, force
