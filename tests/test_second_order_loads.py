"""The second-order wave force in the time domain against its definition and the
frequency domain, on the QTFs of the corpus: the OC4 semisubmersible (WAMIT .12d/.12s)
and the OC3 spar (NEMOH v3).

References: the double sum Σ_i Σ_j evaluated directly (the factorisation must reproduce
it), the existing Newman load of the DP model (WaveDriftLoad), the frequency domain —
2∫S(ω)Q(ω, ω)dω for the mean, S_F(μ) = 8∫S(ω)S(ω+μ)|Q(ω+μ, ω)|²dω for the spectrum
(Pinkster (1980)), with the χ² band of a Welch estimate, and the stationary response
H(μ)F of a moored body.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy import signal, stats

import cummins
from cummins.qtf import QTFTable, interpolate, pair_matrix, qtf_table, with_second_order
from cummins.seakeeping import slow_drift as sd
from cummins.seakeeping.waves import WaveComponents, irregular_waves, wave_spectrum
from cummins.timedomain.loads import SecondOrderWaveLoad, WaveDriftLoad, second_order_force
from cummins.timedomain.simulate import simulate_waves
from cummins.vessel import vessel_from_hydrodb

OC4 = "corpus/WEIS/ss_fitting_OC4_semi/marin_semi.1"
SPAR = "corpus/WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar"
SPHERE = "corpus/WEC-Sim_Applications/wamit_mean_drift_sphere/outputFiles/sphere.1"


@pytest.fixture(scope="module")
def oc4(shared_data):
    return cummins.read(shared_data / OC4)


def _direct(ds, waves, t, dof, kind="difference"):
    """Re Σ_i Σ_j c_i op(c_j) Q(ω_i, ω_j, β_i, β_j) e^{i(ω_i ∓ ω_j)t}, pair by pair."""
    q = qtf_table(ds, kind)
    m = pair_matrix(q, dof, waves.omega, waves.direction)
    c = waves.amplitude * np.exp(1j * (waves.omega * t + waves.phase))
    return float((c @ m @ (np.conj(c) if kind == "difference" else c)).real)


def test_long_crested_force_is_the_double_sum(oc4):
    sea = irregular_waves(wave_spectrum("jonswap", 6.0, 10.0), duration=600, seed=3)
    load = second_order_force(oc4, sea, model="full")
    t = np.arange(0.0, 600.0001, 0.1)
    series = load.time_series(t)
    for k in (0, 1234, 5000):
        for dof in (0, 2, 4):
            expected = _direct(oc4, sea, t[k], dof) + _direct(oc4, sea, t[k], dof, "sum")
            scale = np.abs(series[:, dof]).max()
            assert abs(series[k, dof] - expected) < 2e-3 * scale
            assert abs(load.difference.at(t[k])[dof] + load.sum.at(t[k])[dof] - expected) < (
                1e-9 * scale
            )


def test_short_crested_force_within_its_truncation(oc4):
    """A spread sea (9 directions; the OC4 QTF has one, 0°: the pairs take it at their mean
    direction within ±60°): the truncated factorisation is within 1 % of the force's
    standard deviation of the double sum."""
    sea = irregular_waves(
        wave_spectrum("jonswap", 6.0, 10.0),
        duration=600,
        n_components=40,
        spreading=4.0,
        n_directions=3,
        seed=2,
    )
    # give the QTF three directions (the same values) so that the spread sea is covered
    base = qtf_table(oc4, "difference")
    betas = np.radians([-90.0, 0.0, 90.0])
    values = np.repeat(base.values, 3, axis=2)
    table = QTFTable("difference", base.omega, betas, values, base.dofs)
    data = with_second_order(oc4.drop_vars(["qtf_difference", "qtf_sum"]), [table])
    load = second_order_force(data, sea, model="full")
    assert any("mean direction" in n for n in load.notes)
    t = np.linspace(0, 600, 61)
    series = load.time_series(np.arange(0, 600.0001, 0.1))
    std = series[:, 0].std()
    for tk in t[::10]:
        assert abs(load.difference.at(tk)[0] - _direct(data, sea, tk, 0)) < 0.01 * std


@pytest.fixture(scope="module")
def tanker_head_seas():
    """The demo tanker's .out and JONSWAP Hs 4 m, Tp 10 s in head seas over its
    frequencies (200 components, seed 1)."""
    ds = cummins.read(cummins.demo_files() / "tanker.out")
    w = ds.omega.values
    waves = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0), duration=600, n_components=200,
        direction=np.pi, seed=1, omega_min=w[0], omega_max=w[-1],
    )  # fmt: skip
    return ds, waves


def test_newman_matches_the_dp_models_wave_drift(shared_data):
    """The sphere's mean drift (WAMIT .7): Newman's force of the linear model equals
    WaveDriftLoad's (the DP model's, Smogeli et al. eqs. 47–48) in surge. Its drift at its
    15 suspect frequencies is no larger than elsewhere (0.85 times, sway): both keep it
    by default, with no warning (they left it out, with one each, before)."""
    ds = cummins.read(shared_data / SPHERE)
    sea = irregular_waves(wave_spectrum("jonswap", 0.5, 2.5), duration=300, seed=4)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ours = second_order_force(ds, sea, model="newman")
        theirs = WaveDriftLoad.from_hydrodb(ds, sea, extrapolate="zero", max_heading_gap=7.0)
    assert not [w for w in caught if "suspect" in str(w.message)]
    assert ours.drift_left_out == ()
    assert any("kept at the 15 suspect frequencies" in n for n in ours.notes)
    kept = second_order_force(ds, sea, model="newman", keep_suspect=True)
    for t in (0.0, 17.3, 211.0):
        assert ours.difference.at(t)[0] == pytest.approx(
            theirs.force(t, np.zeros(6), np.zeros(6))[0], rel=1e-9
        )
        assert ours.difference.at(t)[0] == kept.difference.at(t)[0]
    mean = second_order_force(ds, sea, model="mean")
    assert np.allclose(mean.time_series([0.0, 1.0]), ours.mean)


def test_the_dp_drift_leaves_out_the_suspect_frequencies(tanker_head_seas):
    """The demo tanker's .out in head seas (the irregular frequencies of
    test_the_mean_drift_leaves_out_the_suspect_frequencies): the DP model's WaveDriftLoad
    (z-down body axes) has the mean force of the linear model's second-order load, the
    suspect frequencies left out by default as there, kept with keep_suspect=True;
    before, it kept them always (heave mean −9.0e4 N, not +2.9e3 N)."""
    ds, waves = tanker_head_seas
    sign = np.array([1, -1, -1, 1, -1, -1])  # z-up to z-down
    heave = 2
    means = {}
    for keep in (False, True):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            linear = second_order_force(ds, waves, model="mean", keep_suspect=keep).mean
            dp = WaveDriftLoad.from_hydrodb(
                ds, waves, slowly_varying=False, keep_suspect=keep
            ).mean_force(0.0)
        scale = np.abs(linear).max()
        np.testing.assert_allclose(dp, sign * linear, rtol=1e-9, atol=1e-9 * scale)
        means[keep] = dp[heave]
    assert means[True] > 0 > means[False]  # z-down: −9.0e4 N up is +9.0e4 N down
    assert abs(means[True]) > 5 * abs(means[False])
    with pytest.warns(cummins.CumminsWarning, match="left out at the 9 suspect frequencies"):
        WaveDriftLoad.from_hydrodb(ds, waves)


def test_the_dp_load_is_the_force_in_body_axes(oc4):
    sea = irregular_waves(wave_spectrum("jonswap", 6.0, 10.0), duration=300, seed=5)
    linear = second_order_force(oc4, sea, model="full")
    dp = SecondOrderWaveLoad.from_hydrodb(oc4, sea, model="full")
    sign = np.array([1, -1, -1, 1, -1, -1])  # z-up to z-down, the heading 0 in both
    for t in (0.0, 42.0):
        expected = sign * (linear.difference.at(t) + linear.sum.at(t))
        assert np.allclose(dp.force(t, np.zeros(6), np.zeros(6)), expected, rtol=1e-9)
    # 100 m north the waves arrive later: the force is the one of 100/c_g... shifted phases
    moved = dp.force(0.0, np.array([100.0, 0, 0, 0, 0, 0]), np.zeros(6))
    assert not np.allclose(moved, dp.force(0.0, np.zeros(6), np.zeros(6)))


def _long_force(ds, hs, tp, duration, n, seed):
    surge = cummins.select_dofs(ds, ["Surge"])
    table = qtf_table(surge)
    shape = wave_spectrum("jonswap", hs, tp)
    sea = irregular_waves(
        shape,
        duration=duration,
        n_components=n,
        seed=seed,
        omega_min=table.omega[0],
        omega_max=table.omega[-1],
    )
    load = second_order_force(surge, sea, model="full", sum_frequency=False)
    t = np.arange(0.0, duration + 1e-9, 0.5)
    return load, load.time_series(t)[:, 0], table, shape


@pytest.mark.parametrize(
    ("case", "tp", "duration", "n"),
    [(OC4, 10.0, 12 * 3600.0, 800), (SPAR, 16.5, 20 * 3600.0, 1200)],
    ids=["oc4", "oc3-spar"],
)
def test_mean_and_spectrum_of_a_long_record(shared_data, case, tp, duration, n):
    """The mean of the simulated surge drift force against 2∫S Q(ω, ω) dω (to 1 %;
    measured: OC4 +0.1 %, spar within ±0.5 % over four seeds), and its Welch spectrum
    (Hann, no overlap, 4096 samples: K segments, 2K degrees of freedom) against S_F(μ)
    on 0.01 < μ < 0.5 rad/s: at least 95 % of the bins inside the 99 % χ² band (99 %
    expected), their mean ratio within 6 % (measured 0.97–1.01)."""
    ds = cummins.read(shared_data / case)
    _, force, table, shape = _long_force(ds, 6.0, tp, duration, n, seed=1)
    mean = float(sd.mean_drift(table, shape)[0])
    assert force.mean() == pytest.approx(mean, rel=0.01)
    nper = 4096
    freq, psd = signal.welch(force, fs=2.0, nperseg=nper, noverlap=0, window="hann")
    mu, measured = 2 * np.pi * freq, psd / (2 * np.pi)
    band = (mu > 0.01) & (mu < 0.5)
    expected = sd.slow_drift_spectrum(table, shape, mu[band]).values[:, 0, 0].real
    k = force.size // nper
    lo, hi = stats.chi2.ppf([0.005, 0.995], 2 * k) / (2 * k)
    ratio = measured[band] / expected
    assert np.mean((ratio > lo) & (ratio < hi)) > 0.95
    assert ratio.mean() == pytest.approx(1.0, abs=0.06)


def _moored_surge(oc4, zeta=0.2, period=100.0, mass=1.4e7):
    surge = cummins.select_dofs(oc4, ["Surge"])
    surge = cummins.with_inertia(surge, matrix=[[mass]])
    a11 = float(surge.added_mass.interp(omega=2 * np.pi / period).squeeze())
    k = (2 * np.pi / period) ** 2 * (mass + a11)
    b = 2 * zeta * np.sqrt(k * (mass + a11))
    surge = cummins.with_external_terms(
        surge, stiffness={("Surge", "Surge"): k}, damping={("Surge", "Surge"): b}
    )
    return surge, vessel_from_hydrodb(surge), k


def test_bichromatic_waves_start_stationary(oc4):
    """Two waves: the moored surge is the mean offset F̄/k plus the stationary response
    Re[H(μ) 2 c₁c₂* Q(ω₁, ω₂) e^{iμt}] from the first step (the steady start)."""
    surge, vessel, k = _moored_surge(oc4)
    sea = WaveComponents([0.6, 0.66], [2.0, 1.5], [0.3, 1.1], [0.0, 0.0])
    load = second_order_force(surge, sea, model="full", sum_frequency=False)
    run = simulate_waves(
        vessel, surge, sea, duration=300, dt=0.1, second_order=load, first_order=False
    )
    q = qtf_table(surge)
    q12 = complex(interpolate(q, 0.66, 0.6, 0.0, 0.0)[0])
    c = sea.amplitude * np.exp(1j * sea.phase)
    mu = 0.06
    h = 1.0 / vessel.impedance([mu])[0, 0, 0]
    t = run.time.values
    mean = load.mean[0] / k
    expected = mean + (h * 2 * c[1] * np.conj(c[0]) * q12 * np.exp(1j * mu * t)).real
    x = run.motion.sel(dof="Surge").values
    assert np.abs(x - expected).max() < 0.005 * np.abs(expected - mean).max() + 1e-9


def test_moored_surge_in_3_hour_seas_against_the_frequency_domain(oc4):
    """OC4 surge alone, M = 1.4e7 kg, a mooring of natural period 100 s (k = 8.98e4 N/m
    with A11 at 0.063 rad/s) and 20 % of critical damping (5.7e5 N s/m), full difference
    QTF, JONSWAP Hs 6 m, Tp 10 s, heading 0°, 600 components, 3 hours at 0.1 s: the
    standard deviation of each run against √∫ H S_F Hᴴ dμ = 0.761 m. A single 3-hour
    record of this narrow-banded response scatters by about ±5 % (seeds 1–6: +2.2, −5.1,
    −6.7, +1.0, −6.4, +3.2 %): their mean within 5 % (−2.0 % measured), each run within
    12 %; the mean offset F̄/k within 3 % (−1.3 … +0.0 % measured)."""
    surge, vessel, k = _moored_surge(oc4)
    shape = wave_spectrum("jonswap", 6.0, 10.0)
    mu = np.linspace(1e-3, 1.0, 1500)
    spectra = sd.slow_drift_spectrum(qtf_table(surge), shape, mu)
    h = np.linalg.inv(vessel.impedance(mu))
    expected = float(sd.standard_deviation(sd.response_spectrum(spectra, h))[0])
    stds = []
    for seed in range(1, 7):
        sea = irregular_waves(shape, duration=10800, n_components=600, seed=seed)
        load = second_order_force(surge, sea, model="full", sum_frequency=False)
        run = simulate_waves(
            vessel, surge, sea, duration=10800, dt=0.1, second_order=load, first_order=False
        )
        x = run.motion.sel(dof="Surge").values
        stds.append(x.std())
        assert x.mean() == pytest.approx(load.mean[0] / k, rel=0.03)
    assert np.all(np.abs(np.array(stds) / expected - 1) < 0.12)
    assert np.mean(stds) == pytest.approx(expected, rel=0.05)


def test_the_mean_drift_leaves_out_the_suspect_frequencies(tanker_head_seas):
    """The demo tanker's .out, JONSWAP Hs 4 Tp 10 in head seas: WAMIT's drift at the 9
    irregular frequencies (3.65–5.98 rad/s, heave ~1e7–1e8 N/m² against ~1e5 below) made
    the mean heave force −8e4 N; by default they are left out, with a warning and in
    the load, and the mean equals that of the data cut below 3.5 rad/s (to round-off).
    keep_suspect=True gives the old force (measured, seed 1: heave −9.0e4 N against
    +2.9e3 N, surge +14 %, pitch +38 %)."""
    ds, waves = tanker_head_seas
    w = ds.omega.values
    with pytest.warns(cummins.CumminsWarning, match="left out at the 9 suspect frequencies"):
        load = second_order_force(ds, waves, model="mean")
    assert len(load.drift_left_out) == 9 and min(load.drift_left_out) == pytest.approx(3.653, 1e-3)
    cut = ds.isel(omega=np.flatnonzero(w < 3.5))
    reference = second_order_force(cut, waves, model="mean", keep_suspect=True)
    assert np.allclose(load.mean, reference.mean, rtol=1e-12, atol=1e-9 * np.abs(load.mean).max())
    kept = second_order_force(ds, waves, model="mean", keep_suspect=True)
    heave = list(load.dofs).index("Heave")
    assert kept.drift_left_out == ()
    assert load.mean[heave] > 0 > kept.mean[heave]
    assert abs(kept.mean[heave]) > 5 * abs(load.mean[heave])


def test_the_drift_of_a_symmetric_hull_is_mirrored_as_the_first_order():
    """tanker.1 (headings 0–180°, its drift from tanker.out beside it): waves from 270°
    stopped with 'no wave direction near 270 deg'; now the mean force is that of 90° with
    sway, roll and yaw of the other sign (T = diag(1, −1, 1, −1, 1, −1)), exactly."""
    ds = cummins.read(cummins.demo_files() / "tanker.1")
    assert ds.drift_force.attrs["method"] == "pressure integration, tanker.out"

    def mean(direction):
        sea = irregular_waves(
            wave_spectrum("jonswap", 4.0, 10.0), duration=300, n_components=100,
            direction=np.radians(direction), seed=2,
        )  # fmt: skip
        with pytest.warns(cummins.CumminsWarning, match="suspect"):
            return second_order_force(ds, sea, model="mean").mean

    starboard, port = mean(90.0), mean(270.0)
    assert np.abs(starboard[[1, 3, 5]]).min() > 1e3  # sway, roll, yaw driven
    np.testing.assert_allclose(port, starboard * [1, -1, 1, -1, 1, -1], rtol=1e-12)


def test_the_no_qtf_errors_say_the_same():
    """simulate --second-order full and qtf_table name the same files (AQWA .QTF was
    missing from the first)."""
    from cummins.qtf import qtf_table

    ds = cummins.read(cummins.demo_files() / "tanker.1")
    sea = irregular_waves(wave_spectrum("jonswap", 4.0, 10.0), duration=60, seed=1)
    with pytest.raises(cummins.HydroDataError) as full:
        second_order_force(ds, sea, model="full")
    with pytest.raises(cummins.HydroDataError) as table:
        qtf_table(ds, "difference")
    from cummins.qtf.data import NO_QTF_HINT

    for error in (full, table):
        assert NO_QTF_HINT in " ".join(str(error.value).split()) and "AQWA .QTF" in NO_QTF_HINT
    assert "--second-order newman" in str(full.value)
