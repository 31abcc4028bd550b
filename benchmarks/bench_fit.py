"""Benchmark: identification of the whole tanker 6×6 radiation model.

The data MSS ships for its tanker (``tanker.mat``, 58 frequencies from 0.038 to
6.0 rad/s, the same WAMIT run as the bundled demo vessel) fitted, in one run, by

* the default — common poles per block of coupled DOFs (``method="vf"``), passive as
  fitted,
* ``method="fd"`` — one frequency-domain model per coupling, and
* ``method="realization"`` — ERA Hankel-SVD of the sampled K(t),

with the order (for the default: the common poles) and R² of A, B and K(t) of each
coupling; fd and ERA both as identification alone (``passivity="diagonal"``: what MSS's
FDI does) and, for fd, with the MIMO model made passive. The ratios are printed. For the record,
MSS's FDI (its own order search, run non-interactively under Octave on this machine,
issue 4) takes 6.2 s for the 18 couplings, with 5 of them unstable and none passive as
a MIMO model; the ratio of the identification against that figure is printed too.

A second part times the two realization methods on one long kernel (2000 samples of a
two-mode K(t) with 1 % noise, order 10): ERA and Prony, and their ratio (until issue 13's
CI these were timing assertions in the tests; the project keeps timings here).

Run: ``python benchmarks/bench_fit.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


import numpy as np

import cummins
from _timing import SHARED_DATA, timed
from cummins.radiation.fit import fit_radiation
from cummins.radiation.fit.realization import era, prony
from cummins.radiation.passivity import is_passive

DATA = SHARED_DATA / "mss" / "tanker" / "tanker.mat"
MSS_FDI_SECONDS = 6.2  # issue 4: MSS FDI on the same data, this machine, 18 couplings


def report(label: str, seconds: float, model) -> None:
    upper = [c for c in model.modelled if c.influenced <= c.radiating]
    stable = model.is_stable()
    print(
        f"{label}: {seconds:.3f} s, total order {model.total_order}, "
        f"{len(upper)} fitted couplings, all stable {stable}, MIMO passive {is_passive(model)}"
    )
    print("   coupling  order  R2(A)   R2(B)   R2(K(t))  time [ms]")
    for c in upper:
        m = c.metrics
        order = m.get("common_poles", c.order)
        print(
            f"   {c.influenced + 1}{c.radiating + 1:<8d} {order:5d}  {m['r2_added_mass']:.4f}  "
            f"{m['r2_damping']:.4f}  {m['r2_kernel']:.4f}    {1e3 * m['elapsed_s']:7.1f}"
        )


def main() -> None:
    if not DATA.is_file():
        raise SystemExit(f"{DATA} not found: the benchmark needs ../shared/data")
    ds = cummins.read(DATA)
    fit_radiation(ds)  # warm up imports and caches
    t_vf, vf = timed(lambda: fit_radiation(ds))
    t_fd, fd = timed(lambda: fit_radiation(ds, method="fd", passivity="diagonal"))
    t_era, era = timed(lambda: fit_radiation(ds, method="realization", passivity="diagonal"))
    t_mimo, mimo = timed(lambda: fit_radiation(ds, method="fd"))
    report("default: common poles, passive (vf)", t_vf, vf)
    report("fd identification", t_fd, fd)
    report("realization (ERA) identification", t_era, era)
    report("fd, MIMO passive", t_mimo, mimo)
    print(f"ratio fd MIMO passive / default            {t_mimo / t_vf:6.2f}")
    print(f"ratio fd / realization                      {t_fd / t_era:6.2f}")
    print(f"ratio fd MIMO passive / fd identification  {t_mimo / t_fd:6.2f}")
    print(f"ratio MSS FDI (6.2 s, issue 4) / default    {MSS_FDI_SECONDS / t_vf:6.2f}")
    print(f"ratio MSS FDI (6.2 s, issue 4) / fd ident. {MSS_FDI_SECONDS / t_fd:6.2f}")
    long_kernel()


def long_kernel() -> None:
    """ERA and Prony on 2000 samples (one kernel, order 10)."""
    t = np.arange(2000) * 0.02
    rng = np.random.default_rng(0)
    k = (
        np.exp(-0.24 * t) * np.cos(0.76 * t)
        + 0.6 * np.exp(-0.3 * t) * np.cos(1.98 * t)
        + 0.01 * rng.standard_normal(t.size)
    )
    t_era, _ = timed(lambda: era(t, k, 10), repeat=5)
    t_prony, _ = timed(lambda: prony(t, k, 10), repeat=5)
    print(f"2000-sample kernel, order 10: ERA {1e3 * t_era:.1f} ms, Prony {1e3 * t_prony:.1f} ms")
    print(f"ratio Prony / ERA                          {t_prony / t_era:6.2f}")


if __name__ == "__main__":
    main()
