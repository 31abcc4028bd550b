"""Benchmark: a 240-case time-domain batch study on one and on two local Dask workers.

The bundled tanker (WAMIT, default passive fit, made once before the cases), JONSWAP
seas: 4 headings (90–180°) × 3 H_s (2, 3, 4 m) × 5 T_p (7–15 s) × 4 seeds = 240 cases,
each a 30-minute run at dt 0.05 s (36 000 steps, 200 components), statistics per DOF
and two limits. In one run of this script:

* the study on a local cluster of one worker process, then of two (single-threaded,
  BLAS limited to one thread), end to end: cluster start, the fit, every case, saving
  the parts, gathering and writing the results;
* the ratio of the two wall times, and a check that both results are identical (every
  variable, bitwise). The load average before each run is printed: on a 2-core machine
  any other work takes the second core and the ratio with it.

Run: ``python benchmarks/bench_batch.py [seeds]`` (needs ``pip install cummins[dask]``;
``seeds``, 4 by default, the number of seeds of each sea state: 1 runs 60 cases, the
test suite's run of every script).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import sys
import tempfile
import time
from pathlib import Path

import xarray as xr

import cummins
from cummins.studies.batch import Study, run_study

STUDY = {
    "analysis": "simulate",
    "grid": {
        "heading": [90, 120, 150, 180],
        "hs": [2.0, 3.0, 4.0],
        "tp": [7.0, 9.0, 11.0, 13.0, 15.0],
        "seed": [1, 2, 3, 4],
    },
    "duration": 1800.0,
    "dt": 0.05,
    "components": 200,
    "viscous_damping": {"Surge": 1e6, "Sway": 1e6, "Roll": 5e8, "Yaw": 1e10},
    "limits": {"Roll": "4 deg", "Pitch": {"max": "3 deg"}},
}


def _run(study: Study, folder: Path, workers: int):
    load = os.getloadavg()[0]
    print(f"  (load average before the {workers}-worker run: {load:.2f} on {os.cpu_count()} cores)")
    start, cpu = time.perf_counter(), time.process_time()
    run = run_study(study, folder / f"results_{workers}.nc", workers=workers)
    elapsed = time.perf_counter() - start
    print(f"  (CPU time of this client process: {time.process_time() - cpu:.1f} s)")
    return elapsed, run


def main() -> None:
    seeds = int(sys.argv[1]) if len(sys.argv) > 1 else len(STUDY["grid"]["seed"])
    grid = {**STUDY["grid"], "seed": list(range(1, seeds + 1))}
    study = Study(data=cummins.demo_files() / "tanker.1", **{**STUDY, "grid": grid})
    n = len(study.all_cases)
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        t1, one = _run(study, folder, 1)
        print(f"{n} cases ({study.duration:g} s at dt {study.dt} s each), 1 worker:  {t1:6.1f} s")
        t2, two = _run(study, folder, 2)
        print(f"{n} cases ({study.duration:g} s at dt {study.dt} s each), 2 workers: {t2:6.1f} s")
    print(
        f"speed-up 2 workers / 1 worker: {t1 / t2:.2f}x ({one.workers} and {two.workers} workers)"
    )
    xr.testing.assert_identical(one.results, two.results)
    print("results identical on 1 and 2 workers (every variable, bitwise): yes")
    print(f"per case on 1 worker: {1000 * t1 / n:.0f} ms end to end")


if __name__ == "__main__":
    main()
