"""The vessel driven by a record of the wave elevation: measured or forecast η(t).

For wave-energy control studies and for replaying a wave-probe record: the first-order
wave force is the output of the causal excitation model (:mod:`cummins.excitation_model`:
ẋ = A x + B η(t + t_c), F = C x), driven by the elevation at the origin, and the vessel
(:class:`cummins.vessel.Vessel`) by that force (:func:`cummins.timedomain.simulate.simulate`,
exact for forces linear between the samples). Both start from rest at the first sample:
the past of the record is unknown, so the first few natural periods and the model's
memory (its slowest decay) carry a start-up transient. The force at t needs η(t + t_c):
the run ends t_c before the record does (the model's look-ahead).

The same sea given as wave components is simulated by
:func:`cummins.timedomain.simulate.simulate_waves` through the frequency-domain synthesis
of the force; the two agree to the fit error of the excitation model (``tests``).
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from cummins.errors import CumminsWarning

__all__ = ["simulate_wave_record"]

#: Share of the elevation's variance outside the excitation data's frequencies above
#: which a warning says so (the model's response there is its extrapolation).
OUTSIDE_WARNING = 0.01


def simulate_wave_record(
    vessel,
    excitation,
    t: ArrayLike,
    elevation: ArrayLike,
    *,
    heading: int = 0,
    nonlinear_force=None,
    progress=None,
) -> xr.Dataset:
    """Simulate ``vessel`` under the wave force of ``excitation`` driven by η(t).

    Parameters
    ----------
    vessel
        The vessel (:func:`cummins.vessel.vessel_from_hydrodb`), DOFs as ``excitation``'s.
    excitation
        :class:`~cummins.excitation_model.model.ExcitationModel` of the same DOFs.
    t, elevation
        The record: uniform times (s) and the incident wave elevation at the origin (m).
    heading
        Index of the heading of ``excitation`` (the direction the waves travel).
    nonlinear_force, progress
        As :func:`cummins.timedomain.simulate.simulate`.

    Returns
    -------
    xarray.Dataset
        :func:`~cummins.timedomain.simulate.simulate`'s variables on the record's times
        up to its end less t_c, and ``wave_elevation`` (time); attributes
        ``excitation_delay`` (t_c, s), ``excitation_states``, ``initial`` = ``"rest"``,
        the energy balance (``energy_*``, J).
    """
    from cummins.errors import SimulationError
    from cummins.timedomain.simulate import energy_balance, simulate
    from cummins.timedomain.time_step import ENERGY_TOLERANCE

    if tuple(vessel.dofs) != tuple(excitation.dofs):
        raise SimulationError(
            f"the vessel's DOFs {list(vessel.dofs)} are not the excitation model's "
            f"{list(excitation.dofs)}"
        )
    times, force = excitation.force(t, elevation, heading)
    _warn_outside(excitation, np.asarray(t, dtype=float), np.asarray(elevation, dtype=float))
    run = simulate(vessel, times, force, nonlinear_force=nonlinear_force, progress=progress)
    eta = np.interp(times, np.asarray(t, dtype=float), np.asarray(elevation, dtype=float))
    run["wave_elevation"] = ("time", eta, {"units": "m", "long_name": "wave elevation record"})
    balance = energy_balance(vessel, run)
    run.attrs.update(
        {
            "initial": "rest",
            "excitation": "causal state-space model driven by the wave elevation record",
            "excitation_delay": float(excitation.delays[heading]),
            "excitation_states": int(excitation.orders[heading].sum()),
            "heading_deg": float(np.degrees(excitation.headings[heading])),
            **{f"energy_{key}": value for key, value in balance.items()},
        }
    )
    residual = float(run.attrs["energy_relative_residual"])
    if residual > ENERGY_TOLERANCE:  # the record's own step is the run's: said, not failed
        warnings.warn(
            f"the record's energy balance misses by {residual:.2g} of the work done (over "
            f"{ENERGY_TOLERANCE:g}): its step {float(run.attrs['dt']):g} s is coarse for its "
            "waves; resample the record finer for a closer run",
            CumminsWarning,
            stacklevel=2,
        )
    return run


def _warn_outside(excitation, t, eta) -> None:
    """Warn when much of the record's variance lies outside the data's frequencies."""
    low, high = excitation.attrs.get("omega_min"), excitation.attrs.get("omega_max")
    if low is None or high is None or eta.size < 4:
        return
    spectrum = np.abs(np.fft.rfft(eta - eta.mean())) ** 2
    omega = 2 * np.pi * np.fft.rfftfreq(eta.size, float(t[1] - t[0]))
    total = float(spectrum.sum())
    if total <= 0:
        return
    outside = float(spectrum[(omega < low) | (omega > high)].sum()) / total
    if outside > OUTSIDE_WARNING:
        warnings.warn(
            CumminsWarning(
                f"{outside:.1%} of the wave record's variance lies outside the frequencies of "
                f"the excitation data ({low:.3g}–{high:.3g} rad/s): the force there is the "
                "model's extrapolation"
            ),
            stacklevel=3,
        )
