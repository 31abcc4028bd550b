"""Benchmark: WEC-Sim's RM3 in the time domain against the frequency domain (issue 30).

In one run, for WEC-Sim's RM3 set-up (the corpus README: ρ = 1000, the float on a PTO
of 1.2 MN·s/m sliding along the spar, H = 2.5 m, T = 8 s): the steady float, spar and
relative heave and the mean power of `simulate` (default fit, dt 0.1 s) against the
frequency-domain solution of the same equations with the data's A, B, F, without and
with body coupling and with the spar on WEC-Sim's planar joint; the wall time of the fit
and of a 3-hour irregular run (Pierson–Moskowitz Hs 2.5 m, Tp 8 s) with its mean power
against the frequency domain's.

Run: ``python benchmarks/bench_wec.py`` (``CUMMINS_SHARED_DATA`` or ../shared/data).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import warnings
from pathlib import Path

import numpy as np

import cummins
from _timing import SHARED_DATA, timed
from cummins.mechanics import PTO, Joint, MechanicalSystem
from cummins.seakeeping.frequency_domain import motion_rao, pto_rao
from cummins.seakeeping.waves import irregular_waves, regular_wave, wave_spectrum
from cummins.timedomain.harmonics import harmonic_amplitude
from cummins.timedomain.simulate import simulate_waves
from cummins.vessel import vessel_from_hydrodb

MASS = [725833.0, 886687.0]
INERTIA = [[20907301.0, 21306090.66, 37085481.11], [94419614.57, 94407091.24, 28542224.82]]


def rm3_data():
    data = Path(os.environ.get("CUMMINS_SHARED_DATA", SHARED_DATA))
    ds = cummins.read(data / "corpus" / "WEC-Sim" / "wamit_RM3_2body" / "rm3.out", rho=1000.0)
    radii = [list(np.sqrt(np.array(i) / m)) for i, m in zip(INERTIA, MASS, strict=True)]
    return cummins.with_inertia(
        ds,
        mass=MASS,
        center_of_gravity=[[0, 0, -0.72], [0, 0, -21.29]],
        radii_of_gyration=radii,
    )


def system(spar: str, coupling: bool) -> MechanicalSystem:
    first = Joint(spar, "body2", "ground", axis=None if spar == "planar" else (0, 0, 1))
    return MechanicalSystem(
        joints=(first, Joint("translational", "body1", "body2", axis=(0, 0, 1), name="pto")),
        ptos=(PTO(joint="pto", damping=1.2e6),),
        body_coupling=coupling,
    )


def regular(ds, label: str, sys_: MechanicalSystem, amplitude=1.25, period=8.0) -> None:
    omega = 2 * np.pi / period
    fit_time, vessel = timed(lambda: vessel_from_hydrodb(ds, system=sys_), repeat=1)
    run = simulate_waves(
        vessel, ds, regular_wave(amplitude, period, 0.0), duration=20 * period, dt=0.1
    )
    t = run.time.values
    motion = harmonic_amplitude(t, run.motion.values, omega, 5)
    delta = harmonic_amplitude(t, run.pto_displacement.values[:, 0], omega, 5)
    power = run.pto_power.values[t > t[-1] - 5 * period + 1e-6, 0].mean()
    rao = motion_rao(ds, [omega], [0.0], system=sys_)
    pto = pto_rao(rao, ds, sys_)
    x = amplitude * rao.values[0, 0]
    fd_delta = amplitude * pto.pto_displacement.values[0, 0, 0]
    fd_power = amplitude**2 * pto.pto_power.values[0, 0, 0]
    parts = [
        f"{dof} {abs(x[k]):.4f} m {100 * (abs(motion[k]) / abs(x[k]) - 1):+.2f} %"
        for k, dof in enumerate(rao.dof.values)
        if dof.endswith("Heave")
    ]
    print(
        f"{label}: fit {fit_time:.2f} s ({vessel.radiation.total_order} states, "
        f"{vessel.n_coordinates} coordinates); "
        + "; ".join(parts)
        + f"; relative {abs(fd_delta):.4f} m {100 * (abs(delta) / abs(fd_delta) - 1):+.2f} %"
        + f"; power {fd_power / 1e3:.2f} kW (frequency domain), {power / 1e3:.2f} kW "
        f"({100 * (power / fd_power - 1):+.2f} %)"
    )


def irregular(ds) -> None:
    sys_ = system("translational", False)
    vessel = vessel_from_hydrodb(ds, system=sys_)
    shape = wave_spectrum("pm", 2.5, 8.0)
    w_data = ds.omega.values
    sea = irregular_waves(
        shape,
        duration=10800.0,
        n_components=200,
        direction=0.0,
        seed=1,
        omega_min=0.5,
        omega_max=float(w_data[-1]),
    )
    run_time, run = timed(
        lambda: simulate_waves(vessel, ds, sea, duration=10800.0, dt=0.1), repeat=1
    )
    w = np.linspace(0.5, float(w_data[-1]), 2000)
    rao = motion_rao(ds, w, [0.0], system=sys_)
    density = 2 * pto_rao(rao, ds, sys_).pto_power.values[:, 0, 0] * shape(w)
    expected = np.trapezoid(density, w)
    epsilon = np.sqrt(2 * np.pi * np.trapezoid(density**2, w) / 10800.0) / expected
    got = run.pto_power.mean().item()
    print(
        f"irregular PM Hs 2.5 m Tp 8 s, 3 h at dt 0.1 s: run {run_time:.2f} s; mean power "
        f"{got / 1e3:.2f} kW against {expected / 1e3:.2f} kW ({100 * (got / expected - 1):+.2f} "
        f"%; the record's standard error {100 * epsilon:.1f} %)"
    )


def main() -> None:
    ds = rm3_data()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the planar case: the non-reciprocal surge-pitch data
        regular(ds, "RM3 heave, no body coupling", system("translational", False))
        regular(ds, "RM3 heave, body coupling", system("translational", True))
        regular(ds, "RM3 planar spar (WEC-Sim examples/RM3)", system("planar", False))
        irregular(ds)


if __name__ == "__main__":
    main()
