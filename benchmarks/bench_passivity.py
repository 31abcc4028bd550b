"""Benchmark: passivity test and enforcement of the whole tanker 6×6 model.

The identified tanker model (MSS's ``tanker.mat``, ``passivity="diagonal"``: 54 states,
not passive as a MIMO system) is tested, in one run, by

* the exact test (:func:`cummins.radiation.passivity.passivity_test`: crossings from the pencil of
  K(s) + Kᵀ(−s), one evaluation per interval, the limits), and
* a dense sweep of λ_min(K + Kᴴ) on 100 000 log-spaced frequencies (the reference: what
  a user without the exact test would do, and still only a sample),

and then made passive (:func:`cummins.radiation.passivity.enforce_passivity` with the data). The
ratio of the times and the agreement of the two tests are printed.

Run: ``python benchmarks/bench_passivity.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


import numpy as np

import cummins
from _timing import SHARED_DATA, timed
from cummins.radiation.fit import PREVIOUS_DEFAULT, fit_radiation
from cummins.radiation.passivity import enforce_passivity, passivity_sweep, passivity_test

DATA = SHARED_DATA / "mss" / "tanker" / "tanker.mat"


def main() -> None:
    if not DATA.is_file():
        raise SystemExit(f"{DATA} not found: the benchmark needs ../shared/data")
    ds = cummins.read(DATA)
    # per-coupling models (the enforcement moves their residues; the default common-pole
    # blocks are made passive as they are fitted)
    model = fit_radiation(ds, PREVIOUS_DEFAULT, passivity="diagonal")
    grid = np.geomspace(1e-3, 1e3, 100_000)
    t_exact, report = timed(lambda: passivity_test(model))
    t_sweep, sweep = timed(lambda: passivity_sweep(model, grid))
    print(f"tanker 6x6, {model.total_order} states, identification only:")
    print(
        f"  exact test   {t_exact * 1e3:8.1f} ms  passive {report.passive}, "
        f"{report.crossings.size} crossings, {len(report.bands)} bands, "
        f"worst {report.min_eigenvalue:.3g} at {report.worst_omega:.4g} rad/s"
    )
    print(
        f"  dense sweep  {t_sweep * 1e3:8.1f} ms  passive {sweep.passive}, "
        f"worst {sweep.min_eigenvalue.min():.3g} at {sweep.worst_omega:.4g} rad/s "
        f"({grid.size} frequencies)"
    )
    print(f"  ratio sweep / exact  {t_sweep / t_exact:6.2f}")
    w = ds.omega.values[ds.omega.values <= model.attrs["omega_fit_max"]]
    a = ds.added_mass.transpose("omega", "influenced_dof", "radiating_dof").values[: w.size]
    b = ds.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").values[: w.size]
    t_enforce, result = timed(lambda: enforce_passivity(model, omega=w, added_mass=a, damping=b))
    after = passivity_sweep(result.model, grid)
    print(
        f"  enforcement  {t_enforce * 1e3:8.1f} ms  {result.iterations} corrections, "
        f"passive {result.after.passive} (dense sweep: worst {after.min_eigenvalue.min():.3g}), "
        f"largest relative change {max(result.relative_change.values()):.3f}"
    )
    print(f"  ratio enforcement / exact test  {t_enforce / t_exact:6.2f}")


if __name__ == "__main__":
    main()
