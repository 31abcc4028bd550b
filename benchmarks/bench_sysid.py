"""Benchmark: damping identification from a 1-hour 6-DOF record of the tanker.

The bundled tanker (WAMIT, fitted passive radiation model), beam-quartering JONSWAP
Hs 6 m, Tp 11 s, known linear + quadratic + cubic roll damping, dt 0.1 s, 1 hour, 2 %
noise on motions and force. In one run:

* the fluid-memory force of the residual F_res (de Haan (2022) eq. 2.21) by the state-space
  model driven by the measured velocities (what ``identify_damping`` uses) against
  the direct convolution with the model's K(t) (de Haan (2022) eq. 2.23, the thesis' method):
  wall times, their ratio, and the difference of the two memory forces;
* the whole identification (residual, regression, covariance, diagnostics): wall time,
  the coefficients against the truth;
* a roll-decay analysis (ODE fit) of a 240-s decay.

Run: ``python benchmarks/bench_sysid.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import warnings

import numpy as np
import scipy.integrate

import cummins
from _timing import timed
from cummins.seakeeping.waves import irregular_waves, wave_spectrum
from cummins.sysid import identify_damping, make_record, roll_decay
from cummins.sysid.identify import memory_response
from cummins.timedomain.simulate import simulate_waves

DURATION, DT = 3600.0, 0.1


def main() -> None:
    ds = cummins.demo_dataset()
    vessel = cummins.vessel_from_hydrodb(ds, viscous_damping=[1e6, 1e6, 0, 0, 0, 1e10])
    inertia, stiffness = vessel.mass[3, 3], vessel.stiffness[3, 3]
    truth = np.array([0.03 * 2 * np.sqrt(stiffness * inertia), 0.4 * inertia, 5 * inertia])

    def roll_damping(t, xi, v):
        f = np.zeros(6)
        f[3] = -(truth[0] * v[3] + truth[1] * abs(v[3]) * v[3] + truth[2] * v[3] ** 3)
        return f

    sea = irregular_waves(
        wave_spectrum("jonswap", 6.0, 11.0, gamma=1.0),
        duration=DURATION,
        n_components=200,
        direction=np.radians(100),
        seed=4,
    )
    run = simulate_waves(vessel, ds, sea, duration=DURATION, dt=DT, nonlinear_force=roll_damping)
    rng = np.random.default_rng(0)
    x, f = run.motion.values, run.external_force.values
    record = make_record(
        run.time.values,
        x + 0.02 * x.std(0) * rng.standard_normal(x.shape),
        list(vessel.dofs),
        excitation_force=f + 0.02 * f.std(0) * rng.standard_normal(f.shape),
    )
    t, v = run.time.values, run.velocity.values
    print(
        f"record: {DURATION:g} s at {DT:g} s, 6 DOFs, radiation model of "
        f"{vessel.radiation.total_order} states"
    )

    t_ss, (mu_ss, _) = timed(lambda: memory_response(vessel, t, v))
    length = round(60.0 / DT)  # K(t) to 60 s, as the thesis' 30 s doubled
    kernel = vessel.radiation.impulse_response(np.arange(length + 1) * DT).values
    weights = np.full(length + 1, DT)
    weights[[0, -1]] = 0.5 * DT

    def convolution():
        mu = np.zeros_like(v)
        for k in range(t.size):
            j = min(k, length)
            past = v[k - j : k + 1][::-1]  # ξ̇(t_k − s), s = 0 … jΔt
            mu[k] = np.einsum("s,sab,sb->a", weights[: j + 1], kernel[: j + 1], past)
        return mu

    t_conv, mu_conv = timed(convolution, repeat=1)
    roll = 3
    diff = np.sqrt(np.mean((mu_ss[length:, roll] - mu_conv[length:, roll]) ** 2))
    print(
        f"memory force, state space: {t_ss:.3f} s; direct convolution (K to 60 s): "
        f"{t_conv:.2f} s; ratio {t_conv / t_ss:.0f}x; roll RMS difference "
        f"{diff / mu_ss[:, roll].std():.2%} of its RMS"
    )

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t_id, model = timed(lambda: identify_damping(record, vessel, ["Roll"]), repeat=1)
    est = model["Roll"]
    inside = [lo <= b <= hi for b, (lo, hi) in zip(truth, est.intervals, strict=True)]
    print(
        f"identification (residual, regression, intervals, diagnostics): {t_id:.2f} s; "
        f"coefficients / truth {np.round(est.coefficients / truth, 3)}, truth inside the "
        f"95 % intervals: {inside}"
    )

    td = np.arange(0, 240, 0.1)
    sol = scipy.integrate.solve_ivp(
        lambda _, y: [y[1], -0.02 * y[1] - 0.3 * abs(y[1]) * y[1] - 0.25 * y[0]],
        (0, td[-1]),
        [0.2, 0.0],
        t_eval=td,
        rtol=1e-10,
        atol=1e-12,
    )
    t_decay, decay = timed(lambda: roll_decay(td, sol.y[0]), repeat=1)
    print(
        f"roll decay fit, 240 s: {t_decay:.2f} s; p1 {decay['p1']:.4f} (0.02), "
        f"p2 {decay['p2']:.4f} (0.3)"
    )


if __name__ == "__main__":
    main()
