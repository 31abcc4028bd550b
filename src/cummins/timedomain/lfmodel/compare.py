""":func:`compare_with_cummins`: the LF model against the full Cummins vessel.

A free decay or a step force run through both by :func:`cummins.timedomain.simulate.simulate`,
and the difference in the DOF concerned (the acceptance of issue 8).
"""

from __future__ import annotations

from typing import Literal

import numpy as np
import xarray as xr

from cummins.errors import SimulationError
from cummins.timedomain.lfmodel.model import LowFrequencyModel
from cummins.validation import check_simulation_size
from cummins.vessel import Vessel


def compare_with_cummins(
    model: LowFrequencyModel,
    vessel: Vessel,
    dof: str,
    *,
    kind: Literal["decay", "step"] = "decay",
    amplitude: float = 0.1,
    duration: float | None = None,
    dt: float | None = None,
) -> xr.Dataset:
    """Free decay or step response of the LF model against the full Cummins vessel.

    Both linear models are run by :func:`cummins.timedomain.simulate.simulate` (exact
    discretisation), so the difference is the modelling, not the integration.

    Parameters
    ----------
    model
        The LF model.
    vessel
        The full Cummins model of the same DOFs (:func:`cummins.vessel.vessel_from_hydrodb`),
        with the same viscous damping.
    dof
        The DOF displaced (``"decay"``) or pushed (``"step"``).
    kind
        ``"decay"``: released from rest at ξ_dof = ``amplitude`` (m or rad) with an
        unloaded memory; ``"step"``: a constant force ``amplitude`` (N or N·m) from t = 0.
    duration
        Seconds; default 10 natural periods for a decay (300 s for a zero-frequency DOF),
        300 s for a step.
    dt
        Step, s; default 1/40 of the natural period (0.5 s for zero-frequency DOFs).

    Returns
    -------
    xarray.Dataset
        ``lf`` and ``cummins`` (time, dof): motions, m or rad; ``difference`` = lf −
        cummins; attributes ``rms_relative`` (RMS of the difference in ``dof`` over the
        RMS of the Cummins response) and ``max_relative`` (max |difference| over max
        |response|).
    """
    from cummins.timedomain.simulate import simulate

    if tuple(vessel.dofs) != tuple(model.dofs):
        raise SimulationError(
            f"the vessel's DOFs {vessel.dofs} differ from the model's {model.dofs}"
        )
    i = model.index(dof)
    w = float(model.frequencies[i])
    period = 2 * np.pi / w if w > 0 else None
    if dt is None:
        dt = period / 40 if period else 0.5
    if duration is None:
        duration = 10 * period if (period and kind == "decay") else 300.0
    n = len(model.dofs)
    check_simulation_size(duration, dt, vessel.n_states, n)
    t = np.arange(0.0, float(duration) + 0.5 * float(dt), float(dt))
    lf_vessel = model.to_vessel()
    force = np.zeros((t.size, n))
    x_lf = np.zeros(lf_vessel.n_states)
    x_full = np.zeros(vessel.n_states)
    if kind == "decay":
        x_lf[i] = x_full[i] = amplitude
    elif kind == "step":
        force[:, i] = amplitude
    else:
        raise SimulationError(f"unknown kind {kind!r}", hint="use 'decay' or 'step'")
    lf = simulate(lf_vessel, t, force, initial_state=x_lf).motion
    full = simulate(vessel, t, force, initial_state=x_full).motion
    diff = lf - full
    ref = full.isel(dof=i).values
    d = diff.isel(dof=i).values
    rms_ref = float(np.sqrt(np.mean(ref**2)))
    out = xr.Dataset({"lf": lf, "cummins": full, "difference": diff})
    out.attrs.update(
        kind=kind,
        dof=dof,
        amplitude=amplitude,
        frequency=w,
        rms_relative=float(np.sqrt(np.mean(d**2)) / rms_ref) if rms_ref > 0 else np.nan,
        max_relative=float(np.abs(d).max() / np.abs(ref).max()) if rms_ref > 0 else np.nan,
    )
    return out
