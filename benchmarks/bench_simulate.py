"""Benchmark: a 3-hour irregular-sea run of the tanker, state space against convolution.

The bundled tanker (WAMIT, fitted passive radiation model, 6 DOFs), JONSWAP Hs 4 m,
Tp 10 s, γ 3.3, 200 components, waves from 150°, dt 0.05 s, 3 hours (216 000 steps),
started on the stationary solution. In one run:

* the state-space solver (exact first-order-hold discretisation, modal recursion) with
  the wave excitation: wall time and its ratio to real time;
* the direct-convolution solver (de Haan (2022) eq. 2.23 with oversampled hat weights, the
  model's K(t) to 100 s) on the same run: wall time and the ratio to the state space;
* the accuracy of both against the exact stationary response of the same linear model
  (the sum of the frequency-domain responses of the components), RMS error / RMS.

Run: ``python benchmarks/bench_simulate.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import functools
import time

import numpy as np

import cummins
from _timing import timed
from cummins.seakeeping.excitation import excitation_coefficients
from cummins.seakeeping.waves import harmonic_sum, irregular_waves, jonswap
from cummins.timedomain.simulate import simulate, simulate_convolution, simulate_waves, steady_state
from cummins.vessel import vessel_from_hydrodb

DURATION, DT, COMPONENTS = 3 * 3600.0, 0.05, 200
VISCOUS = [1e6, 1e6, 0.0, 0.0, 0.0, 1e10]


def main() -> None:
    ds = cummins.demo_dataset()
    vessel = vessel_from_hydrodb(ds, viscous_damping=VISCOUS)
    sea = irregular_waves(
        functools.partial(jonswap, hs=4.0, tp=10.0, gamma=3.3),
        duration=DURATION,
        n_components=COMPONENTS,
        direction=np.radians(150.0),
        seed=1,
    )
    t_ss, run = timed(lambda: simulate_waves(vessel, ds, sea, duration=DURATION, dt=DT), 3)
    print(
        f"state space: {DURATION / 3600:g} h, dt {DT} s, {COMPONENTS} components, "
        f"{vessel.n_states} states: {t_ss:.2f} s, {DURATION / t_ss:,.0f}x faster than real time"
    )
    t = run.time.values
    c = excitation_coefficients(ds, sea)
    tau = harmonic_sum(t, sea.omega, c)
    x0 = steady_state(vessel, sea.omega, c)
    t_solve, solved = timed(lambda: simulate(vessel, t, tau, initial_state=x0), 3)
    # the exact stationary response of the same model: Σ_k Re{X_k e^{iω_k t}}
    motion = vessel.response(sea.omega, c)
    exact = harmonic_sum(t, sea.omega, motion)
    velocity = 1j * sea.omega[:, None] * motion
    m = 10
    lags = np.arange(0.0, 100.0 + DT / 2, DT)
    kernel = vessel.radiation.impulse_response(np.arange((lags.size - 1) * m + 1) * DT / m).values
    past = harmonic_sum(-lags[1:][::-1], sea.omega, velocity)
    start = (exact[0], harmonic_sum(t[:1], sea.omega, velocity)[0])
    began = time.perf_counter()
    convolution = simulate_convolution(
        vessel, t, tau, kernel, velocity_history=past, initial_motion=start, oversampling=m
    )
    t_cv = time.perf_counter() - began
    rms = np.sqrt((exact**2).mean(0))
    err_ss = np.sqrt(((solved.motion.values - exact) ** 2).mean(0)) / rms
    err_cv = np.sqrt(((convolution.motion.values - exact) ** 2).mean(0)) / rms
    print(f"  integration alone (excitation given): {t_solve:.2f} s")
    print(f"direct convolution, K(t) to {lags[-1]:g} s ({lags.size} lags): {t_cv:.1f} s")
    print(f"ratio convolution / state space (integration): {t_cv / t_solve:.0f}")
    print("RMS error / RMS against the exact stationary response, per DOF:")
    print("  state space ", " ".join(f"{e:.1e}" for e in err_ss))
    print("  convolution ", " ".join(f"{e:.1e}" for e in err_cv))


if __name__ == "__main__":
    main()
