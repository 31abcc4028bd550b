"""Benchmark: forward speed on the S-175 (MSS/VERES, 5 speeds 0–10.3 m/s), heave–pitch.

In one run:

* the speed-dependent model K_U = K⁰ + U K¹ + U² K² (Hjulstad (2004) eqs. 3.28–3.36), built from
  one zero-speed fit (K¹, K² derived exactly from it): wall time;
* the reference: one fit per speed (five fits, `fit_per_speed`): wall time and the ratio;
* the forced-motion check (Hjulstad (2004) §12.1, eq. 12.3) of the speed model at 10.29 m/s
  against the frequency-domain force of the STF-corrected data: the largest error.

Run: ``python benchmarks/bench_speed.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import warnings
from importlib import resources
from pathlib import Path

import numpy as np

import cummins
from _timing import timed
from cummins.hydrodb import select_dofs
from cummins.radiation.speed import (
    fit_per_speed,
    forced_motion_error,
    speed_dependent_model,
    stf_speed_terms,
)

OPTIONS = {"omega_max": 2.0, "r2": 0.999, "max_order": 6}


def main() -> None:
    path = Path(str(resources.files("cummins") / "data" / "s175" / "s175.mat"))
    ds = select_dofs(cummins.read(path), ["Heave", "Pitch"])
    zero = ds.sel(forward_speed=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t_model, model = timed(lambda: speed_dependent_model(zero, **OPTIONS), repeat=1)
        t_per, per_speed = timed(lambda: fit_per_speed(ds, **OPTIONS), repeat=1)
    print(
        f"speed-dependent model (one fit, K1 and K2 derived): {t_model:.2f} s; "
        f"one fit per speed (5 fits): {t_per:.2f} s; ratio {t_per / t_model:.1f}x"
    )
    print(f"stable: speed model {model.is_stable()}, per-speed fits {per_speed.is_stable()}")
    speed = float(ds.forward_speed.values[-1])
    reference = stf_speed_terms(zero, speed)
    worst = 0.0
    for pair in (("Heave", "Heave"), ("Heave", "Pitch"), ("Pitch", "Heave"), ("Pitch", "Pitch")):
        result = forced_motion_error(model, reference, speed, np.array([0.3, 0.6, 0.9, 1.2]), pair)
        worst = max(worst, float(np.max(np.abs(result.error))))
    print(
        f"forced motion at {speed:.2f} m/s, time domain against |T(ω)| of the STF data: "
        f"largest error {100 * worst:.2f} % (eq. 12.3)"
    )


if __name__ == "__main__":
    main()
