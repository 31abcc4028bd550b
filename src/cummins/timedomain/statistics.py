"""The motion statistics of a run, as ``cummins simulate`` prints them and the report shows.

Per DOF: the significant amplitude 2σ of an irregular sea, or the amplitude of the steady
oscillation in a regular wave (half the range over the last wave period, or over the whole
run when it is shorter), the mean and the largest |ξ|. Rotations are given in degrees (the
run file keeps radians, its ``units`` attribute says so).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from cummins.display import motion_units, rotation_scale


@dataclass(frozen=True)
class MotionStatistic:
    """One DOF's statistics in ``unit`` (the run's, deg for a rotation in rad)."""

    dof: str
    mean: float
    amplitude: float
    maximum: float
    unit: str


def is_regular(run: xr.Dataset) -> bool:
    """Whether ``run`` is a regular-wave run (its ``spectrum`` attribute)."""
    return str(run.attrs.get("spectrum", "")) == "regular"


def motion_statistics(run: xr.Dataset, regular: bool | None = None) -> list[MotionStatistic]:
    """The statistics of ``run.motion`` per DOF (module docstring); ``regular`` defaults
    to :func:`is_regular`."""
    regular = is_regular(run) if regular is None else regular
    t = run.time.values
    period = float(run.attrs.get("tp", np.nan)) if regular else np.nan
    last = t >= t[-1] - period if np.isfinite(period) and period < t[-1] else np.ones(t.size, bool)
    out = []
    dofs = [str(d) for d in run.dof.values]
    for k, (dof, unit) in enumerate(zip(dofs, motion_units(run.motion, dofs), strict=True)):
        scale, shown = rotation_scale(unit)
        xi = run.motion.values[:, k] * scale
        size = 0.5 * np.ptp(xi[last]) if regular else 2 * xi.std()
        out.append(
            MotionStatistic(dof, float(xi.mean()), float(size), float(np.abs(xi).max()), shown)
        )
    return out
