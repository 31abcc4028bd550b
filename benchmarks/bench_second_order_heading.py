"""Benchmark: the second-order load of the DP model at the instantaneous relative heading
against the same load held at a fixed heading, and the tanker's drift yaw moment over a
heading change.

In one run of the script:

1. **Cost per call** of ``SecondOrderWaveLoad.force`` (the DP model calls it once per
   step), following the heading (``follow_heading=True``, the default) and held at ψ₀
   (``False``), on the WAMIT tanker (bundled): ``mean`` and ``newman`` from its mean drift
   (19 headings 0–180°, mirrored), and ``full`` from a QTF of several headings made of
   that drift (Newman's form, the only multi-heading QTF of real data at hand: the
   corpus's QTFs have one heading each), JONSWAP H_s 4 m, T_p 10 s, long-crested (60
   components) and short-crested (40 frequencies × 5 directions); the ratio of each.
2. **The DP scenario** (``dp-demo``'s, the S-175, 300 s) with its drift a
   ``SecondOrderWaveLoad`` (Newman's, from the mean drift), following the heading and held
   at 0°, and the ratio (build and run).
3. **The tanker's drift yaw moment over a 30° heading change**: the mean drift of the
   sea of (1), long-crested, as the relative heading goes from head seas (180°) to 150°
   in steps of 5°, and the moment it would keep held at head seas (zero by symmetry).
4. **Construction of the following load** (``from_hydrodb``, ``full`` from the QTF of
   (1)), short-crested seas of 40 × 5, 100 × 9 and 200 × 9 components (the last
   ``cummins simulate``'s default): now, the forms held at ψ₀ deferred to their first
   use, against the construction as it was before, which built them too (the same
   construction followed by their build, ``load.difference``), and the ratio.

Run: ``python benchmarks/bench_second_order_heading.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time
import warnings

import numpy as np

import cummins
from _timing import timed
from cummins.qtf import QTFTable, with_second_order
from cummins.seakeeping.waves import irregular_waves, wave_spectrum
from cummins.timedomain.loads import SecondOrderWaveLoad

CALLS = 2000


def _tanker():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(cummins.demo_files() / "tanker.1")
    ds = ds.isel(omega=ds.omega.values < 3.0)
    t = ds.drift_force.transpose("omega", "wave_direction", "influenced_dof").values
    q = (0.5 * (t[:, None] + t[None, :])).astype(complex)
    dofs = tuple(str(d) for d in ds.influenced_dof.values)
    table = QTFTable("difference", ds.omega.values, ds.wave_direction.values, q, dofs)
    return ds, with_second_order(ds, [table])


def _per_call(load) -> float:
    """Best of three: mean time of one force() call, µs, the vessel yawing slowly."""
    eta = np.zeros(6)

    def calls():
        for k in range(CALLS):
            eta[5] = 0.2 * np.sin(0.01 * k)
            load.force(0.2 * k, eta, eta)

    best, _ = timed(calls, 3)
    return 1e6 * best / CALLS


def main() -> None:
    print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores)")
    ds, dq = _tanker()
    shape = wave_spectrum("jonswap", 4.0, 10.0)
    seas = {
        "long-crested, 60 components": irregular_waves(
            shape, duration=600, n_components=60, direction=np.pi, seed=1, omega_max=2.9, data=ds
        ),
        "short-crested, 40 x 5 components": irregular_waves(
            shape,
            duration=600,
            n_components=40,
            direction=np.pi,
            spreading=5,
            n_directions=5,
            seed=1,
            omega_max=2.9,
            data=ds,
        ),
    }
    print(f"1. SecondOrderWaveLoad.force, tanker, {CALLS} calls, per call:")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name, sea in seas.items():
            for model in ("mean", "newman", "full"):
                data = dq if model == "full" else ds
                follow = SecondOrderWaveLoad.from_hydrodb(data, sea, model=model)
                held = SecondOrderWaveLoad.from_hydrodb(
                    data, sea, model=model, follow_heading=False
                )
                a, b = _per_call(follow), _per_call(held)
                print(
                    f"   {name}, {model:6s}: following {a:7.1f} us, fixed heading {b:7.1f} us "
                    f"({a / b:.2f}x)"
                )

    from cummins.cli.dp_scenario import build_scenario, s175_data, simulate_scenario

    s175 = s175_data()

    def scenario(follow: bool):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model, loads, controller, sea = build_scenario(
                s175, duration=300.0, seed=1, second_order="none"
            )
            drift = SecondOrderWaveLoad.from_hydrodb(
                s175, sea, model="newman", name="wave drift", follow_heading=follow
            )
            return simulate_scenario(model, (*loads, drift), controller, duration=300.0, dt=0.2)

    t_follow, _ = timed(lambda: scenario(True), 2)
    t_held, _ = timed(lambda: scenario(False), 2)
    print(
        f"2. dp-demo scenario (S-175, 300 s, 1500 steps, 200 components, the drift a "
        f"SecondOrderWaveLoad 'newman'): following {t_follow:.2f} s, held at 0 deg "
        f"{t_held:.2f} s ({t_follow / t_held:.2f}x)"
    )

    sea = seas["long-crested, 60 components"]
    load = SecondOrderWaveLoad.from_hydrodb(ds, sea, model="mean")
    print("3. tanker, JONSWAP Hs 4 m, Tp 10 s, long-crested, mean drift against the heading:")
    print("   relative heading  surge (kN)  sway (kN)  yaw (MN m)")
    start = time.perf_counter()
    for change in range(0, 35, 5):
        f = load.force(0.0, np.array([0, 0, 0, 0, 0, np.radians(change)]), np.zeros(6))
        print(
            f"   {180 - change:6d} deg         {f[0] / 1e3:9.1f} {f[1] / 1e3:10.1f} "
            f"{f[5] / 1e6:10.2f}"
        )
    print(f"   (evaluated in {1e3 * (time.perf_counter() - start):.1f} ms)")
    _construction(ds, dq, shape)


def _construction(ds, dq, shape) -> None:
    """Section 4: the following load built with its fixed-heading forms deferred, against
    the same load with them built (what ``from_hydrodb`` did before)."""
    print("4. SecondOrderWaveLoad.from_hydrodb, full QTF, following the heading, construction:")
    for n, m in ((40, 5), (100, 9), (200, 9)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sea = irregular_waves(
                shape,
                duration=600,
                n_components=n,
                direction=np.pi,
                spreading=5,
                n_directions=m,
                seed=1,
                omega_max=2.9,
                data=ds,
            )

            def lazy(sea=sea):
                return SecondOrderWaveLoad.from_hydrodb(dq, sea, model="full")

            def eager(sea=sea):
                load = lazy(sea)
                return load.difference  # the forms held at psi0, as built before

            t_lazy, _ = timed(lazy, 3)
            t_eager, _ = timed(eager, 2)
        print(
            f"   short-crested {n} x {m} = {n * m} components: deferred {t_lazy:.3f} s, "
            f"built as before {t_eager:.3f} s ({t_eager / t_lazy:.1f}x)"
        )


if __name__ == "__main__":
    main()
