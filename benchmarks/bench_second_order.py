"""Benchmark: a 3-hour irregular-sea run with the full QTF against the first-order run.

In one run of the script:

1. **The OC3 spar** (NEMOH v3.0.2, corpus ``WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar``: the
   first-order coefficients and a 26 × 26 difference- and sum-frequency QTF), moored in
   surge, sway (natural period 100 s) and yaw, JONSWAP H_s 6 m, T_p 16.5 s, heading 0°,
   200 components over the QTF's frequencies, dt 0.05 s, 3 hours (216 000 steps),
   stationary start: the first-order run, then the same run with the full second-order
   force (building the factorised force, the force over the run, the stationary state,
   the simulation), and the ratio.
2. **A 100 × 100 QTF**: the OC4 semisubmersible's difference- and sum-frequency QTFs
   (WAMIT, 56 × 56) interpolated onto 100 frequencies over 0.25–3 rad/s, the second-order
   surge force of a 3-hour sea (H_s 6 m, T_p 10 s, 200 components, dt 0.05 s): long-crested
   (the exact form on the grid) and short-crested (cos-2s, s = 4, 9 directions × 40
   frequencies: the truncated eigen-decomposition of the 360 × 360 pair matrices), timed
   against the spar's first-order run of (1).

Run: ``python benchmarks/bench_second_order.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time
from pathlib import Path

import numpy as np

import cummins
from _timing import SHARED_DATA, timed
from cummins.qtf import QTFTable, interpolate, qtf_table, with_second_order
from cummins.seakeeping.waves import irregular_waves, wave_spectrum
from cummins.timedomain.loads import second_order_force
from cummins.timedomain.simulate import simulate_waves
from cummins.vessel import vessel_from_hydrodb

DURATION, DT, COMPONENTS = 3 * 3600.0, 0.05, 200


def _data(relative: str):
    return cummins.read(Path(os.environ.get("CUMMINS_SHARED_DATA", SHARED_DATA)) / relative)


def _spar():
    ds = _data("corpus/WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar")
    mass = float(ds.inertia_matrix.sel(influenced_dof="Surge", radiating_dof="Surge"))
    a11 = float(ds.added_mass.sel(influenced_dof="Surge", radiating_dof="Surge").isel(omega=0))
    k = (2 * np.pi / 100.0) ** 2 * (mass + a11)
    b = 2 * 0.2 * np.sqrt(k * (mass + a11))
    yaw = float(ds.inertia_matrix.sel(influenced_dof="Yaw", radiating_dof="Yaw"))
    ds = cummins.with_external_terms(
        ds,
        stiffness={("Surge", "Surge"): k, ("Sway", "Sway"): k, ("Yaw", "Yaw"): 0.004 * yaw},
        damping={("Surge", "Surge"): b, ("Sway", "Sway"): b, ("Yaw", "Yaw"): 0.05 * yaw},
    )
    return ds, vessel_from_hydrodb(ds)


def _regridded_oc4(n: int = 100):
    ds = _data("corpus/WEIS/ss_fitting_OC4_semi/marin_semi.1")
    ds = cummins.select_dofs(ds, ["Surge"])
    w = np.linspace(0.25, 3.0, n)
    tables = []
    for kind in ("difference", "sum"):
        q = qtf_table(ds, kind)
        values = interpolate(q, w[:, None], w[None, :], 0.0, 0.0)[:, :, None, :]
        tables.append(QTFTable(kind, w, q.directions, values, q.dofs))
    return with_second_order(ds.drop_vars(["qtf_difference", "qtf_sum"]), tables)


def main() -> None:
    print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores)")
    ds, vessel = _spar()
    table = qtf_table(ds)
    shape = wave_spectrum("jonswap", 6.0, 16.5)
    sea = irregular_waves(
        shape,
        duration=DURATION,
        n_components=COMPONENTS,
        seed=1,
        omega_min=table.omega[0],
        omega_max=table.omega[-1],
    )
    t1, first = timed(lambda: simulate_waves(vessel, ds, sea, duration=DURATION, dt=DT), 2)

    def full():
        force = second_order_force(ds, sea, model="full")
        return simulate_waves(vessel, ds, sea, duration=DURATION, dt=DT, second_order=force)

    t2, both = timed(full, 2)
    print(
        f"OC3 spar, {DURATION / 3600:g} h, dt {DT} s, {COMPONENTS} components, "
        f"{vessel.n_states} states:"
    )
    print(f"  first-order run: {t1:.2f} s")
    print(
        f"  with the full difference- and sum-frequency QTF ({table.omega.size} x "
        f"{table.omega.size}): {t2:.2f} s ({t2 / t1:.1f}x the first-order run)"
    )
    surge = both.motion.sel(dof="Surge").values - first.motion.sel(dof="Surge").values
    print(
        f"  surge from the second-order force: mean {surge.mean():.3g} m, std {surge.std():.3g} m"
    )

    oc4 = _regridded_oc4(100)
    t = np.arange(0.0, DURATION + 0.5 * DT, DT)
    shape = wave_spectrum("jonswap", 6.0, 10.0)
    long_crested = irregular_waves(shape, duration=DURATION, n_components=COMPONENTS, seed=1)
    start = time.perf_counter()
    force = second_order_force(oc4, long_crested, model="full")
    series = force.time_series(t)
    t3 = time.perf_counter() - start
    print(
        f"100 x 100 QTF (OC4 regridded), surge, {COMPONENTS} components, long-crested: "
        f"{t3:.2f} s for {t.size:,} steps ({t3 / t1:.1f}x the spar's first-order run); "
        f"force std {series[:, 0].std():.4g} N"
    )
    spread = irregular_waves(
        shape, duration=DURATION, n_components=40, spreading=4.0, n_directions=9, seed=1
    )
    # the regridded QTF at -180, -90, 0, 90 deg (its 0 deg values): the sea spreads ±103 deg
    q = qtf_table(oc4, "difference")
    four = QTFTable(
        "difference",
        q.omega,
        np.radians([-180.0, -90.0, 0.0, 90.0]),
        np.repeat(q.values, 4, axis=2),
        q.dofs,
    )
    wide = with_second_order(oc4.drop_vars(["qtf_difference", "qtf_sum"]), [four])
    start = time.perf_counter()
    force = second_order_force(wide, spread, model="full")
    series = force.time_series(t)
    t4 = time.perf_counter() - start
    print(
        f"100 x 100 QTF, surge, short-crested ({len(spread)} components): {t4:.2f} s "
        f"({force.difference.columns.shape[1]} terms kept at 1e-3), "
        f"{t4 / t1:.1f}x the spar's first-order run"
    )


if __name__ == "__main__":
    main()
