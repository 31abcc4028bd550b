"""Regular-wave runs of a fitted model against the data's motion RAOs (issue 16's check
that the time domain reproduces the frequency domain), shared by the multi-body tests."""

from __future__ import annotations

import numpy as np


def regular_wave_errors(ds, model, periods, heading: int = 0, dt: float = 0.05):
    """For each nominal period (s), the data frequency nearest to it, a run of three wave
    periods in regular waves of that heading started on the steady state, its motion
    amplitudes fitted over the last two periods, against ``motion_rao`` of the data; both
    with 2 % of critical damping. Returns (period, largest error relative to each DOF's
    peak RAO over the data frequencies ≥ 0.15 rad/s, that DOF) per period; DOFs whose peak
    is below 10⁻³ of the largest are not compared."""
    from cummins.radiation.fit.scorecard import critical_damping
    from cummins.seakeeping.frequency_domain import motion_rao
    from cummins.timedomain.simulate import simulate, steady_state
    from cummins.vessel import vessel_from_hydrodb

    damping = critical_damping(ds, added_mass_inf=model.added_mass_inf)
    vessel = vessel_from_hydrodb(ds, model, viscous_damping=np.diag(damping))
    beta = float(ds.wave_direction.values[heading])
    terms = {"additional": False, "viscous_damping": vessel.viscous_damping}
    omega = ds.omega.values
    band = omega[np.isfinite(omega) & (omega >= 0.15)]
    peak = np.abs(motion_rao(ds, band, [beta], **terms).values[:, 0]).max(axis=0)
    compared = peak > 1e-3 * peak.max()
    f = ds.excitation_force.sel(wave_direction=beta).transpose("omega", "influenced_dof")
    out = []
    for nominal in periods:
        k = int(np.argmin(np.abs(omega - 2 * np.pi / nominal)))
        w = float(omega[k])
        period = 2 * np.pi / w
        force = f.values[k]
        t = np.arange(0.0, 3 * period, dt)
        tau = np.real(force[None, :] * np.exp(1j * w * t[:, None]))
        run = simulate(vessel, t, tau, initial_state=steady_state(vessel, [w], [force]))
        last = t >= period
        basis = np.c_[np.cos(w * t[last]), -np.sin(w * t[last])]
        coef, *_ = np.linalg.lstsq(basis, run.motion.values[last], rcond=None)
        got = coef[0] + 1j * coef[1]
        expected = motion_rao(ds, [w], [beta], **terms).values[0, 0]
        error = np.abs(got - expected)[compared] / peak[compared]
        out.append((period, float(error.max()), np.asarray(vessel.dofs)[compared][error.argmax()]))
    return out
