"""Benchmark: the low-frequency manoeuvring model of the bundled tanker (Ross, Perez & Fossen,
2006).

In one run: the model from A(ω), B(ω) and from K(t) (wall times, and how far the two
routes' natural frequencies differ), and one hour of a 6-DOF response to a step force
with the LF model (12 states, no memory) against the Cummins model (12 + the radiation
model's states): wall times and the ratio.

Run: ``python benchmarks/bench_lfmodel.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import warnings

import numpy as np

import cummins
from _timing import timed
from cummins.timedomain.lfmodel import lf_model_from_frequency_data, lf_model_from_retardation
from cummins.timedomain.simulate import simulate
from cummins.vessel import vessel_from_hydrodb


def main() -> None:
    ds = cummins.demo_dataset()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t_freq, lf = timed(lambda: lf_model_from_frequency_data(ds))
        t_kern, lf_k = timed(lambda: lf_model_from_retardation(ds))
        vessel = vessel_from_hydrodb(ds, viscous_damping=np.diag(lf.viscous_damping))
    spread = np.max(np.abs(lf.frequencies - lf_k.frequencies) / np.maximum(lf.frequencies, 1e-9))
    print(
        f"LF model from A, B: {t_freq:.3f} s; from K(t): {t_kern:.3f} s; natural "
        f"frequencies of the two routes within {100 * spread:.2f} %"
    )
    t = np.arange(0.0, 3600.0, 0.1)
    force = np.zeros((t.size, 6))
    force[:, 1] = 1e5  # a 100 kN side force
    lf_vessel = lf.to_vessel()
    t_lf, _ = timed(lambda: simulate(lf_vessel, t, force))
    t_full, _ = timed(lambda: simulate(vessel, t, force))
    print(
        f"1 hour, 6 DOFs, dt 0.1 s: LF model ({lf_vessel.n_states} states) {t_lf:.3f} s, "
        f"Cummins model ({vessel.n_states} states) {t_full:.3f} s; ratio {t_full / t_lf:.1f}x"
    )


if __name__ == "__main__":
    main()
