"""Time-domain simulation of the Cummins equation against the frequency domain (issue 6).

References: scipy's adaptive ODE solver (the discretisation), the frequency-domain
solution of the same model (steady state), the direct-convolution solver, energy.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import cummins
from cummins.errors import SimulationError
from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.timedomain.simulate import (
    discretize,
    energy_balance,
    simulate,
    simulate_convolution,
    steady_state,
)
from cummins.vessel import Vessel, vessel_from_hydrodb

VISCOUS = [1e6, 1e6, 0.0, 0.0, 0.0, 1e10]  # surge, sway, yaw need some (no restoring)


@pytest.fixture(scope="module")
def tanker_vessel(tanker_wamit):
    return vessel_from_hydrodb(tanker_wamit, viscous_damping=VISCOUS)


def _one_dof(stiffness: float = 4.0, damping: float = 0.3) -> Vessel:
    k = CouplingModel(
        0, 0, np.array([[0.0, 1.0], [-1.0, -0.8]]), np.array([0.0, 1.0]), np.array([0.0, 0.5])
    )
    model = RadiationModel(("Heave",), (k,), np.array([[0.5]]))
    return Vessel(("Heave",), np.eye(1), np.array([[stiffness]]), np.array([[damping]]), model)


def test_the_discretisation_is_exact_for_a_force_linear_between_samples():
    vessel = _one_dof()
    f, g = vessel.state_space()
    dt, t = 0.37, np.arange(0, 12, 0.37)
    force = np.sin(1.3 * t)[:, None] + 0.2 * t[:, None]
    x0 = np.array([0.1, -0.2, 0.05, 0.0])

    def rate(tk, x):
        u = np.interp(tk, t, force[:, 0])  # the same piecewise-linear input
        return f @ x + g[:, 0] * u

    reference = solve_ivp(
        rate, (t[0], t[-1]), x0, t_eval=t, rtol=1e-11, atol=1e-13, max_step=dt / 20
    ).y.T
    result = simulate(vessel, t, force, initial_state=x0)
    np.testing.assert_allclose(result.motion.values[:, 0], reference[:, 0], atol=1e-8)
    np.testing.assert_allclose(result.velocity.values[:, 0], reference[:, 1], atol=1e-8)
    disc = discretize(vessel, dt)
    np.testing.assert_allclose(
        disc.gamma0 + disc.gamma1, np.linalg.solve(f, (disc.phi - np.eye(4)) @ g)
    )


@pytest.mark.parametrize(
    ("relative", "options"),
    [
        ("mss/tanker/tanker.1", {}),
        ("mss/supply/supply.mat", {}),
        ("wecsim/sphere/sphere_hydrodynamics.nc", {}),
    ],
)
def test_regular_waves_reach_the_frequency_domain_response(shared_data, relative, options):
    """Steady state in regular waves, periods 5–25 s, several headings: the amplitude and
    phase of every DOF equal the frequency-domain solution of the same equation within
    0.1 % and 0.1° (surge, sway, yaw with viscous damping)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        ds = cummins.read(shared_data / relative, **options)
    if "forward_speed" in ds.dims:
        ds = ds.sel(forward_speed=0.0)
    vessel = vessel_from_hydrodb(ds, viscous_damping=VISCOUS if "sphere" not in relative else None)
    headings = ds.wave_direction.values
    picks = headings[np.linspace(0, headings.size - 1, 3).astype(int)]
    dt = 0.05
    for period in (5.0, 9.0, 14.0, 25.0):
        w = 2 * np.pi / period
        for beta in picks:
            f = ds.excitation_force.sel(wave_direction=beta).transpose("omega", "influenced_dof")
            force = np.array(
                [
                    np.interp(w, ds.omega.values, f.values[:, i].real)
                    + 1j * np.interp(w, ds.omega.values, f.values[:, i].imag)
                    for i in range(f.shape[1])
                ]
            )
            expected = vessel.response([w], [force])[0]
            t = np.arange(0.0, 4 * period, dt)
            tau = np.real(force[None, :] * np.exp(1j * w * t[:, None]))
            run = simulate(vessel, t, tau, initial_state=steady_state(vessel, [w], [force]))
            last = t >= 2 * period
            basis = np.c_[np.cos(w * t[last]), -np.sin(w * t[last])]
            coef, *_ = np.linalg.lstsq(basis, run.motion.values[last], rcond=None)
            got = coef[0] + 1j * coef[1]
            scale = np.abs(expected)
            for i, dof in enumerate(vessel.dofs):
                if scale[i] < 1e-6 * scale.max() or (dof == "Yaw" and "sphere" in relative):
                    continue
                assert abs(got[i]) / scale[i] - 1 == pytest.approx(0, abs=1e-3), (dof, period)
                assert abs(np.angle(got[i] / expected[i], deg=True)) < 0.1, (dof, period)


#: Measured 2026-12-02 (default model; the same on 1 and 2 BLAS threads and the
#: Sandybridge kernel): worst amplitude error (% of the peak) and phase error (°):
#: tanker heave 1.32 %, 0.97°; supply heave 0.38 %, pitch 0.20°; sphere surge
#: 0.65 %, 0.30°.
REGULAR_WAVE_MEASURED = {"tanker": (1.32, 0.97), "supply": (0.38, 0.20), "sphere": (0.65, 0.30)}


@pytest.mark.parametrize(
    "relative",
    [
        # the data's own viscous roll damping (MSS Bv) is used by both sides
        "mss/tanker/tanker.mat",
        "mss/supply/supply.mat",
        "wecsim/sphere/sphere_hydrodynamics.nc",
    ],
)
def test_regular_waves_reproduce_the_data_raos(shared_data, relative):
    """Acceptance: steady-state amplitude and phase of a simulation in regular waves
    (periods 5–25 s, four headings) of the *default* time-domain model
    (``vessel_from_hydrodb`` with the default identification) against the coupled RAOs
    of the *data* (``motion_rao``, itself checked against WAMIT's and VERES's RAOs in
    test_frequency_domain), with the damping of issue 16's RAO comparison (2 % of
    critical on each DOF with restoring; surge, sway and yaw of the ships some viscous
    damping): the complex error within 2 % of each DOF's largest RAO at that heading
    (issue 16: never above 2 %), the phase within 2° where the RAO is above half that
    peak (below it, a 2 % error of the peak is a larger angle of a smaller amplitude: the
    complex error measures it). Measured: :data:`REGULAR_WAVE_MEASURED`. Against the
    frequency-domain solution of the same model the simulation agrees to 0.1 %/0.1°
    (test_regular_waves_reach_the_frequency_domain_response)."""
    from cummins.radiation.fit.scorecard import critical_damping
    from cummins.seakeeping.frequency_domain import motion_rao
    from cummins.seakeeping.waves import regular_wave
    from cummins.timedomain.simulate import simulate_waves

    ds = cummins.read(shared_data / relative)
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    sphere = "sphere" in relative
    damping = critical_damping(ds) + (0.0 if sphere else np.asarray(VISCOUS))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # MSS's frequency-dependent Bv
        vessel = vessel_from_hydrodb(ds, viscous_damping=damping)
    headings = ds.wave_direction.values[
        np.linspace(0, ds.sizes["wave_direction"] - 1, 4).astype(int)
    ]
    headings = np.unique(headings)
    periods = np.array([5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 14.0, 16.0, 18.0, 21.0, 25.0])
    same_terms = {"additional": False, "viscous_damping": vessel.viscous_damping}
    rao = motion_rao(ds, 2 * np.pi / periods, headings, **same_terms).values
    band = np.linspace(2 * np.pi / 25, 2 * np.pi / 5, 400)
    peak = np.abs(motion_rao(ds, band, headings, **same_terms).values).max(axis=0)
    worst = np.zeros((2, len(vessel.dofs)))
    for ib, beta in enumerate(headings):
        for ip, period in enumerate(periods):
            w = 2 * np.pi / period
            run = simulate_waves(
                vessel, ds, regular_wave(1.0, period, beta), duration=3 * period, dt=0.05
            )
            t = run.time.values
            last = t >= period
            basis = np.c_[np.cos(w * t[last]), -np.sin(w * t[last])]
            coef, *_ = np.linalg.lstsq(basis, run.motion.values[last], rcond=None)
            got, expected = coef[0] + 1j * coef[1], rao[ip, ib]
            significant = peak[ib] > 1e-6 * peak.max()
            with np.errstate(divide="ignore", invalid="ignore"):
                error = np.where(significant, np.abs(got - expected) / peak[ib], 0.0)
                large = np.abs(expected) > 0.5 * peak[ib]
                ratio = np.where(large & significant, got / expected, 1.0)
            phase = np.abs(np.angle(ratio, deg=True))
            worst = np.maximum(worst, [error, phase])
    for i, dof in enumerate(vessel.dofs):
        assert worst[0, i] < 0.02, (dof, worst[:, i])
        assert worst[1, i] < 2.0, (dof, worst[:, i])


def test_state_space_and_direct_convolution_agree(tanker_vessel, tanker_wamit):
    """25 wave components from the database, 20 min, both solvers started on the
    stationary solution: RMS difference below 1 % of the response RMS in every DOF."""
    vessel, ds = tanker_vessel, tanker_wamit
    rng = np.random.default_rng(1)
    f = ds.excitation_force.isel(wave_direction=12).transpose("omega", "influenced_dof").values
    ks = np.arange(15, 40)
    w = ds.omega.values[ks]
    amplitude = f[ks] * (0.5 * np.exp(1j * rng.uniform(0, 2 * np.pi, ks.size)))[:, None]
    motion = vessel.response(w, amplitude)
    dt, m = 0.05, 10
    t = np.arange(0.0, 1200.0, dt)
    tau = np.real(np.exp(1j * np.outer(t, w)) @ amplitude)
    ss = simulate(vessel, t, tau, initial_state=steady_state(vessel, w, amplitude))
    lags = np.arange(0.0, 100.0 + dt / 2, dt)
    kernel = vessel.radiation.impulse_response(np.arange((lags.size - 1) * m + 1) * dt / m).values
    past = np.real(np.exp(1j * np.outer(-lags[1:][::-1], w)) @ (1j * w[:, None] * motion))
    start = (np.real(motion.sum(0)), np.real((1j * w[:, None] * motion).sum(0)))
    cv = simulate_convolution(
        vessel, t, tau, kernel, velocity_history=past, initial_motion=start, oversampling=m
    )
    rms = np.sqrt((ss.motion.values**2).mean(0))
    diff = np.sqrt(((ss.motion.values - cv.motion.values) ** 2).mean(0))
    assert np.all(diff < 0.01 * rms), diff / rms
    # and both follow the superposition of the frequency-domain solutions
    fd = np.real(np.exp(1j * np.outer(t, w)) @ motion)
    assert np.all(np.sqrt(((ss.motion.values - fd) ** 2).mean(0)) < 1e-3 * rms)


@pytest.mark.parametrize(
    ("relative", "options"),
    [
        ("mss/tanker/tanker.1", {}),
        ("mss/supply/supply.mat", {}),
        ("wecsim/sphere/sphere_hydrodynamics.nc", {}),
    ],
)
def test_free_decay_never_gains_energy(shared_data, relative, options):
    """Released from a displaced, moving state with the memory at rest, the mechanical
    energy of a passive model never exceeds its initial value, and the work balance
    closes."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        ds = cummins.read(shared_data / relative, **options)
    if "forward_speed" in ds.dims:
        ds = ds.sel(forward_speed=0.0)
    vessel = vessel_from_hydrodb(ds)
    assert cummins.radiation.passivity.passivity_test(vessel.radiation).passive
    n = len(vessel.dofs)
    x0 = np.zeros(vessel.n_states)
    x0[:n] = [0.5, 0.5, 1.0, 0.1, 0.02, 0.05][:n]
    x0[n : 2 * n] = [0.2, 0.2, 0.3, 0.02, 0.01, 0.01][:n]
    t = np.arange(0.0, 400.0, 0.05)
    run = simulate(vessel, t, np.zeros((t.size, n)), initial_state=x0)
    v, xi = run.velocity.values, run.motion.values
    energy = 0.5 * np.einsum("ti,ij,tj->t", v, vessel.mass, v) + 0.5 * np.einsum(
        "ti,ij,tj->t", xi, vessel.stiffness, xi
    )
    assert energy.max() <= energy[0] * (1 + 1e-9)
    balance = energy_balance(vessel, run)
    assert balance["radiated_min"] >= -1e-6 * energy[0]  # the memory gives nothing back
    assert balance["relative_residual"] < 1e-3


def test_unstable_models_and_bad_input_are_refused():
    unstable = _one_dof(stiffness=-1.0)
    t = np.arange(0.0, 10.0, 0.1)
    with pytest.raises(SimulationError, match=r"unstable.*Heave"):
        simulate(unstable, t, np.zeros((t.size, 1)))
    vessel = _one_dof()
    with pytest.raises(SimulationError, match="uniformly"):
        simulate(vessel, np.r_[t[:5], t[6:]], np.zeros((t.size - 1, 1)))
    bad = np.zeros((t.size, 1))
    bad[7] = np.nan
    with pytest.raises(SimulationError, match=r"not finite at t = 0\.7 s in Heave"):
        simulate(vessel, t, bad)
    with pytest.raises(SimulationError, match="shape"):
        simulate(vessel, t, np.zeros((t.size, 2)))


def test_nonlinear_forces(tanker_vessel):
    """A zero nonlinear force gives the linear result (Runge–Kutta against the exact
    path); quadratic roll damping lowers the roll response; a force that feeds energy in
    without bound is caught as a divergence, naming the DOF."""
    vessel = _one_dof()
    t = np.arange(0.0, 30.0, 0.02)
    force = np.sin(1.1 * t)[:, None]
    exact = simulate(vessel, t, force)
    rk = simulate(vessel, t, force, nonlinear_force=lambda tk, x, v: np.zeros(1))
    np.testing.assert_allclose(rk.motion.values, exact.motion.values, atol=1e-7)
    damped = simulate(vessel, t, force, nonlinear_force=lambda tk, x, v: -2.0 * v * np.abs(v))
    assert np.abs(damped.motion.values[-500:]).max() < np.abs(exact.motion.values[-500:]).max()
    with pytest.raises(SimulationError, match=r"diverged.*Heave"):
        simulate(vessel, t, force, nonlinear_force=lambda tk, x, v: 50.0 * x**3)


def test_irregular_seas_reproduce_the_data_response_spectra(shared_data):
    """Acceptance: a 3-hour run of the tanker in a JONSWAP sea (Hs 4 m, Tp 10 s, 250
    components, bow-quartering) — the Welch spectrum of each motion follows the
    frequency-domain response spectrum |X|²S of the data's RAOs, and the significant
    amplitudes 2√m₀ agree within 5 % (measured ≤ 1.3 % for heave, roll, pitch; the
    spectra differ by ≤ 4.3 % of their peak, RMS)."""
    from scipy.signal import welch

    from cummins.seakeeping.frequency_domain import (
        motion_rao,
        response_spectrum,
        significant_amplitude,
    )
    from cummins.seakeeping.waves import irregular_waves, wave_spectrum
    from cummins.timedomain.simulate import simulate_waves

    ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.mat")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # MSS's frequency-dependent Bv
        vessel = vessel_from_hydrodb(ds, viscous_damping=VISCOUS)
    spectrum = wave_spectrum("jonswap", 4.0, 10.0, gamma=3.3)
    beta = np.radians(150.0)
    duration, dt = 3 * 3600.0, 0.05
    sea = irregular_waves(spectrum, duration=duration, n_components=250, direction=beta, seed=7)
    run = simulate_waves(vessel, ds, sea, duration=duration, dt=dt)
    w = np.linspace(sea.omega.min(), sea.omega.max(), 2000)
    rao = motion_rao(ds, w, [beta], additional=False, viscous_damping=vessel.viscous_damping)
    fd = response_spectrum(rao, spectrum)
    expected = significant_amplitude(fd)
    freq, psd = welch(run.motion.values, fs=1 / dt, nperseg=8192, axis=0)
    omega, td = 2 * np.pi * freq, psd / (2 * np.pi)  # one-sided, per rad/s
    band = (omega >= w[0]) & (omega <= w[-1])
    for i, dof in enumerate(vessel.dofs):
        if dof not in ("Heave", "Roll", "Pitch"):
            continue
        reference = float(expected.sel(dof=dof))
        assert 2 * run.motion.values[:, i].std() == pytest.approx(reference, rel=0.05), dof
        m0 = np.trapezoid(td[band, i], omega[band])
        assert 2 * np.sqrt(m0) == pytest.approx(reference, rel=0.05), dof
        # the spectra themselves: RMS difference within a tenth of the peak
        on = np.interp(omega[band], w, fd.sel(dof=dof).values)
        difference = np.sqrt(np.mean((td[band, i] - on) ** 2))
        assert difference < 0.1 * on.max(), (dof, difference / on.max())


def test_the_simulation_does_not_depend_on_blas_threads(tanker_wamit):
    """The tanker identified and simulated (600 s, a force of five sines in every DOF)
    with 1 and with 2 BLAS threads: the same motions to 10⁻⁹ of each DOF's largest. The
    conftest runs the suite on one thread (OPENBLAS_NUM_THREADS=1), so this is where two
    threads are exercised (the fit alone: test_identification_targets.py). Measured
    2026-12-02: 7.6e-15 (yaw) on the machine's kernel (Haswell), 4.8e-11 (surge) under
    OPENBLAS_CORETYPE=Sandybridge: the bound is 21× the worst."""
    import threadpoolctl

    t = np.arange(0.0, 600.0, 0.25)
    rng = np.random.default_rng(3)
    amplitude = np.array([1e5, 1e6, 1e6, 1e8, 1e9, 1e8])
    w, phase = rng.uniform(0.2, 1.2, (5, 6)), rng.uniform(0.0, 2 * np.pi, (5, 6))
    force = (amplitude * np.sin(t[:, None, None] * w + phase)).sum(axis=1)
    motions = []
    for threads in (1, 2):
        with threadpoolctl.threadpool_limits(threads):
            assert all(
                info["num_threads"] == threads
                for info in threadpoolctl.threadpool_info()
                if info["user_api"] == "blas"
            )
            vessel = vessel_from_hydrodb(tanker_wamit, viscous_damping=VISCOUS)
            motions.append(simulate(vessel, t, force).motion.values)
    scale = np.abs(motions[0]).max(axis=0)
    assert np.all(scale > 0)
    np.testing.assert_array_less(np.abs(motions[1] - motions[0]).max(axis=0), 1e-9 * scale)


@pytest.mark.parametrize(("amplitude", "noted"), [(2.0, True), (0.5, False)])
def test_rotations_beyond_the_small_motions_are_said(tmp_path, amplitude, noted):
    """The row of three buoys (``tests/data/three_buoys_capytaine.nc``, no viscous
    damping) in 6 s waves pitches by 44–48° at 2 m of amplitude (a flap on its hinge ran
    to 70° without a word): a note says the linear model does not hold there; at 0.5 m,
    12° and no note."""
    from pathlib import Path

    from click.testing import CliRunner

    from cummins.cli import main

    data = Path(__file__).parent / "data" / "three_buoys_capytaine.nc"
    wave = ["--regular", "--wave-period", "6", "--wave-amplitude", str(amplitude)]
    args = ["simulate", str(data), *wave, "--heading", "0", "--duration", "60"]
    result = CliRunner().invoke(main, [*args, "-o", str(tmp_path / "run.nc")])
    assert result.exit_code == 0, result.output
    said = " ".join(result.output.split())
    assert ("the model is linear (small motions" in said) is noted
    if noted:
        import re

        turned = re.search(r"(body\d__Pitch) turns by up to ([0-9.]+)°", said)
        assert turned is not None, said
        assert float(turned[2]) > 40  # measured 48.1° (body3)
