"""Wave spectra, spreading, dispersion and the realisation of a sea as components."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from scipy import integrate

from cummins.seakeeping.waves import (
    WaveComponents,
    cos2s_spreading,
    energy_range,
    harmonic_sum,
    irregular_waves,
    jonswap,
    pierson_moskowitz,
    regular_wave,
    spreading_directions,
    spreading_weights,
    torsethaugen,
    torsethaugen_parameters,
    wave_spectrum,
    wavenumber,
)


def m0(spectrum) -> float:
    """∫₀^∞ S dω by adaptive quadrature, split where the spectra have their features."""
    total = 0.0
    for a, b in ((0.0, 0.3), (0.3, 0.6), (0.6, 1.0), (1.0, 2.0), (2.0, 10.0), (10.0, np.inf)):
        total += integrate.quad(lambda w: float(spectrum(np.array([w]))[0]), a, b, limit=400)[0]
    return total


# --------------------------------------------------------------------------- spectra


@pytest.mark.parametrize("gamma", [1.0, 2.0, 3.3, 5.0, 7.0, 10.0])
@pytest.mark.parametrize(("hs", "tp"), [(4.0, 10.0), (1.5, 6.0)])
def test_jonswap_hs_exact_for_any_gamma(hs, tp, gamma):
    s = functools.partial(jonswap, hs=hs, tp=tp, gamma=gamma)
    assert 4 * np.sqrt(m0(s)) == pytest.approx(hs, rel=1e-8)


def test_jonswap_normalisation_differs_from_the_approximate_factor():
    # Our exact factor: S/S_PM at ω far from the peak (γ^r → 1 there) is 1/(5 I).
    w = np.array([0.2])
    exact = jonswap(w, 4.0, 10.0, gamma=3.3) / pierson_moskowitz(w, 4.0, 10.0)
    approx = 1 - 0.287 * np.log(3.3)
    assert exact[0] == pytest.approx(approx, rel=5e-3)  # close …
    assert abs(exact[0] / approx - 1) > 1e-3  # … but not the same
    big = jonswap(w, 4.0, 10.0, gamma=10.0) / pierson_moskowitz(w, 4.0, 10.0)
    assert abs(big[0] / (1 - 0.287 * np.log(10.0)) - 1) > 0.05  # 7 % off at γ = 10


@pytest.mark.parametrize("gamma", [1.0, 3.3, 7.0])
def test_jonswap_peak_at_tp(gamma):
    tp = 9.0
    w = np.linspace(0.3, 1.5, 240_001)
    s = jonswap(w, 3.0, tp, gamma=gamma)
    assert w[np.argmax(s)] == pytest.approx(2 * np.pi / tp, abs=1e-5)


def test_jonswap_gamma_one_is_pierson_moskowitz():
    w = np.linspace(0.0, 4.0, 500)
    np.testing.assert_allclose(jonswap(w, 2.0, 8.0, gamma=1.0), pierson_moskowitz(w, 2.0, 8.0))
    assert jonswap(np.array([0.0, -1.0]), 2.0, 8.0).tolist() == [0.0, 0.0]


def test_pierson_moskowitz_hs_and_peak():
    s = functools.partial(pierson_moskowitz, hs=5.0, tp=12.0)
    assert 4 * np.sqrt(m0(s)) == pytest.approx(5.0, rel=1e-9)
    w = np.linspace(0.2, 1.2, 200_001)
    assert w[np.argmax(s(w))] == pytest.approx(2 * np.pi / 12.0, abs=1e-5)


@pytest.mark.parametrize(
    ("hs", "tp"), [(4.0, 6.0), (4.0, 8.0), (4.0, 14.0), (2.0, 20.0), (8.0, 12.0), (1.0, 4.0)]
)
def test_torsethaugen_hs_exact(hs, tp):
    s = functools.partial(torsethaugen, hs=hs, tp=tp)
    assert 4 * np.sqrt(m0(s)) == pytest.approx(hs, rel=1e-7)
    peaks = torsethaugen_parameters(hs, tp)
    assert peaks[0]["hs"] ** 2 + peaks[1]["hs"] ** 2 == pytest.approx(hs**2)


@pytest.mark.parametrize(("hs", "tp"), [(4.0, 8.0), (4.0, 14.0), (8.0, 12.0), (2.0, 20.0)])
def test_torsethaugen_primary_peak_at_tp(hs, tp):
    w = np.linspace(0.15, 3.0, 400_001)
    s = torsethaugen(w, hs, tp)
    # the other peak's flank moves the maximum by a few tenths of a percent
    assert 2 * np.pi / w[np.argmax(s)] == pytest.approx(tp, rel=5e-3)


def test_torsethaugen_has_two_peaks_in_swell_and_is_continuous_at_tpf():
    w = np.linspace(0.2, 2.0, 20_001)
    s = torsethaugen(w, 2.0, 20.0)  # swell dominated: wind sea peak near 6.6 H2^(1/3)
    interior = (s[1:-1] > s[:-2]) & (s[1:-1] > s[2:])
    maxima = 2 * np.pi / w[1:-1][interior]
    assert maxima.size == 2
    secondary = torsethaugen_parameters(2.0, 20.0)[1]
    assert sorted(maxima) == pytest.approx(sorted([20.0, secondary["tp"]]), rel=0.03)
    tpf = 6.6 * 4.0 ** (1 / 3)
    below, above = torsethaugen(w, 4.0, tpf * (1 - 1e-9)), torsethaugen(w, 4.0, tpf * (1 + 1e-9))
    np.testing.assert_allclose(below, above, rtol=1e-6, atol=1e-12)


def test_wave_spectrum_names_and_errors():
    assert wave_spectrum("JONSWAP", 2.0, 8.0).keywords == {"hs": 2.0, "tp": 8.0, "gamma": 3.3}
    w = np.linspace(0.1, 3, 50)
    np.testing.assert_array_equal(wave_spectrum("ittc", 2.0, 8.0)(w), pierson_moskowitz(w, 2, 8))
    np.testing.assert_array_equal(wave_spectrum("pm", 2.0, 8.0)(w), pierson_moskowitz(w, 2, 8))
    np.testing.assert_array_equal(wave_spectrum("torsethaugen", 2, 8)(w), torsethaugen(w, 2, 8))
    with pytest.raises(ValueError, match="unknown wave spectrum"):
        wave_spectrum("bretschneider-2", 2.0, 8.0)
    with pytest.raises(ValueError, match="JONSWAP spectrum only"):
        wave_spectrum("pm", 2.0, 8.0, gamma=2.0)
    with pytest.raises(ValueError, match="peak period"):
        jonswap(w, 2.0, 0.0)
    with pytest.raises(ValueError, match="gamma"):
        jonswap(w, 2.0, 8.0, gamma=0.5)


def test_energy_range_leaves_out_a_thousandth():
    s = wave_spectrum("jonswap", 3.0, 9.0)
    lo, hi = energy_range(s)
    inside = integrate.quad(lambda w: float(s(np.array([w]))[0]), lo, hi, limit=400)[0]
    assert inside / m0(s) == pytest.approx(0.999, abs=2e-4)


# --------------------------------------------------------------------------- spreading


@pytest.mark.parametrize("s", [0.0, 1.0, 4.5, 20.0, 300.0])
@pytest.mark.parametrize("mean", [0.0, 2.0, -3.0, 7.5])
def test_cos2s_integrates_to_one(s, mean):
    total = integrate.quad(
        lambda th: float(cos2s_spreading(np.array([th]), mean, s)[0]),
        -np.pi,
        np.pi,
        points=[float(np.mod(mean + np.pi, 2 * np.pi) - np.pi)],
        limit=400,
    )[0]
    assert total == pytest.approx(1.0, rel=1e-8)


def test_cos2s_shape():
    th = np.linspace(-np.pi, np.pi, 3601)
    d = cos2s_spreading(th, 0.5, 10.0)
    assert th[np.argmax(d)] == pytest.approx(0.5, abs=2e-3)
    np.testing.assert_allclose(
        cos2s_spreading(0.5 + th, 0.5, 10), cos2s_spreading(0.5 - th, 0.5, 10)
    )
    assert cos2s_spreading(0.5 + np.pi, 0.5, 10.0) == pytest.approx(0.0)
    with pytest.raises(ValueError):
        cos2s_spreading(th, 0.0, -1.0)


def test_spreading_directions_and_weights():
    directions, weights = spreading_directions(1.0, 8.0, 11)
    assert weights.sum() == pytest.approx(1.0)
    assert directions[5] == pytest.approx(1.0)  # centred on the mean
    assert np.average(directions, weights=weights) == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(weights, weights[::-1])
    # Weights of a database's headings: sum to 1, largest at the mean direction.
    beta = np.radians(np.arange(0, 360, 10.0))
    w = spreading_weights(beta, np.pi, 5.0)
    assert w.sum() == pytest.approx(1.0) and np.argmax(w) == 18
    assert w[0] < 1e-3 * w[18]


# --------------------------------------------------------------------------- dispersion


def test_wavenumber():
    w = np.array([0.2, 0.5, 1.0, 3.0])
    np.testing.assert_allclose(wavenumber(w), w**2 / 9.81)
    for depth in (5.0, 30.0, 300.0):
        k = wavenumber(w, depth=depth, g=9.80665)
        np.testing.assert_allclose(9.80665 * k * np.tanh(k * depth), w**2, rtol=1e-12)
    # shallow water: k → ω/√(gh); deep: k → ω²/g
    assert wavenumber(0.01, depth=10.0)[()] == pytest.approx(0.01 / np.sqrt(9.81 * 10), rel=1e-4)
    assert wavenumber(3.0, depth=100.0)[()] == pytest.approx(9 / 9.81, rel=1e-12)


# --------------------------------------------------------------------------- components


def test_regular_wave_elevation_and_propagation():
    wave = regular_wave(1.5, 8.0, direction=np.radians(30), phase=0.4)
    t = np.linspace(0, 40, 801)
    k = (2 * np.pi / 8.0) ** 2 / 9.81
    x, y = 20.0, -7.0
    shift = k * (x * np.cos(np.radians(30)) + y * np.sin(np.radians(30)))
    expected = 1.5 * np.cos(2 * np.pi / 8.0 * t - shift + 0.4)
    np.testing.assert_allclose(wave.elevation(t, x, y), expected, atol=1e-12)
    assert wave.elevation(0.0) == pytest.approx(1.5 * np.cos(0.4))
    # Finite depth: crests travel at the phase speed ω/k of the dispersion relation.
    kd = wavenumber(2 * np.pi / 8.0, depth=15.0)[()]
    c = (2 * np.pi / 8.0) / kd
    d = 12.0
    along = (d * np.cos(np.radians(30)), d * np.sin(np.radians(30)))
    np.testing.assert_allclose(
        wave.elevation(t + d / c, *along, depth=15.0), wave.elevation(t, depth=15.0), atol=1e-12
    )
    assert len(wave) == 1 and wave.spectrum == "regular" and wave.hs == 3.0


def test_wave_components_validation_and_immutability():
    with pytest.raises(ValueError, match="positive"):
        WaveComponents([0.0], [1.0], [0.0], [0.0])
    with pytest.raises(ValueError, match="values"):
        WaveComponents([1.0, 2.0], [1.0], [0.0, 0.0], [0.0, 0.0])
    with pytest.raises(ValueError, match=">= 0"):
        WaveComponents([1.0], [-1.0], [0.0], [0.0])
    waves = WaveComponents([1.0], [1.0], [0.0], [0.0])
    with pytest.raises(ValueError):
        waves.omega[0] = 2.0
    with pytest.raises(AttributeError):
        waves.omega = np.array([2.0])


def test_harmonic_sum_uniform_and_general_grids_agree():
    rng = np.random.default_rng(5)
    omega = rng.uniform(0.2, 3.0, 50)
    c = rng.normal(size=(50, 3)) + 1j * rng.normal(size=(50, 3))
    t = 1000.0 + 0.05 * np.arange(5000)
    direct = np.cos(np.outer(t, omega)) @ c.real - np.sin(np.outer(t, omega)) @ c.imag
    np.testing.assert_allclose(harmonic_sum(t, omega, c), direct, atol=1e-9)
    jittered = t + rng.uniform(0, 1e-3, t.size)
    direct = np.cos(np.outer(jittered, omega)) @ c.real - np.sin(np.outer(jittered, omega)) @ c.imag
    np.testing.assert_allclose(harmonic_sum(jittered, omega, c), direct, atol=1e-9)
    assert harmonic_sum(t, omega, c[:, 0]).shape == (5000,)


JONSWAP = wave_spectrum("jonswap", 4.0, 10.0)


def test_irregular_waves_energy_and_bins():
    waves = irregular_waves(JONSWAP, duration=3600.0, n_components=150, seed=3)
    lo, hi = waves.attrs["omega_min"], waves.attrs["omega_max"]
    assert (lo, hi) == pytest.approx(energy_range(JONSWAP))
    in_range = integrate.quad(lambda w: float(JONSWAP(np.array([w]))[0]), lo, hi, limit=400)[0]
    assert waves.variance == pytest.approx(in_range, rel=1e-6)  # bin integrals
    assert waves.significant_wave_height == pytest.approx(4.0, rel=1e-3)  # 99.9 % of m0
    edges = np.linspace(lo, hi, 151)
    assert np.all((waves.omega > edges[:-1]) & (waves.omega <= edges[1:]))  # one per bin
    assert waves.bin_width == pytest.approx((hi - lo) / 150)
    assert (waves.spectrum, waves.hs, waves.tp, waves.seed) == ("jonswap", 4.0, 10.0, 3)
    assert np.all(waves.direction == 0.0) and len(waves) == 150


def test_irregular_waves_reproducible():
    a = irregular_waves(JONSWAP, duration=600, seed=42)
    b = irregular_waves(JONSWAP, duration=600, seed=42)
    c = irregular_waves(JONSWAP, duration=600, seed=43)
    np.testing.assert_array_equal(a.omega, b.omega)
    np.testing.assert_array_equal(a.phase, b.phase)
    assert not np.array_equal(a.phase, c.phase)
    fresh = irregular_waves(JONSWAP, duration=600)  # no seed: entropy recorded
    again = irregular_waves(JONSWAP, duration=600, seed=fresh.seed)
    np.testing.assert_array_equal(fresh.phase, again.phase)
    rng = np.random.default_rng(7)
    assert irregular_waves(JONSWAP, duration=600, seed=rng).seed is None


def test_realisation_variance_tends_to_m0():
    waves = irregular_waves(JONSWAP, duration=20_000.0, seed=11)
    t = np.arange(0.0, 40_000.0, 0.25)
    zeta = waves.elevation(t)
    assert abs(zeta.mean()) < 0.02
    assert np.var(zeta) == pytest.approx(waves.variance, rel=0.03)
    assert waves.variance == pytest.approx((4.0 / 4) ** 2, rel=2e-3)


def test_no_repetition_within_the_duration():
    """Equal frequency spacing repeats after 2π/Δω; a random frequency per bin does not."""
    waves = irregular_waves(JONSWAP, duration=3000.0, seed=2)  # 200 components
    period = 2 * np.pi / waves.bin_width  # repetition period of an equally spaced sea: 350 s
    assert period < waves.duration / 5
    # The usual equal spacing: integer multiples of Δω, one in each bin, same amplitudes.
    k0 = np.ceil(waves.attrs["omega_min"] / waves.bin_width)
    centres = waves.bin_width * (k0 + np.arange(len(waves)))
    equal = WaveComponents(centres, waves.amplitude, waves.phase, waves.direction)
    t = np.arange(0.0, waves.duration, 0.5)
    assert equal.autocorrelation(period) == pytest.approx(1.0, abs=1e-9)
    np.testing.assert_allclose(equal.elevation(t + period), equal.elevation(t), atol=1e-9)
    # Time-averaged autocorrelation of the realisation (phase-independent): nowhere back
    # near 1 from 5 peak periods (where the spectrum's own correlation is 0.05) to twice
    # the duration; what remains is the ~1/sqrt(n_eff) noise of a finite sum.
    tau = np.arange(50.0, 2 * waves.duration, 0.25)
    rho = np.abs(waves.autocorrelation(tau))
    assert rho.max() < 0.7
    assert np.median(rho) < 1.0 / np.sqrt(waves.attrs["effective_components"])
    # The record itself: ζ(t + 2π/Δω) is essentially uncorrelated with ζ(t).
    z = waves.elevation(t)
    assert abs(np.corrcoef(z, waves.elevation(t + period))[0, 1]) < 0.3


def test_short_crested_sea():
    waves = irregular_waves(
        JONSWAP,
        duration=3600,
        n_components=80,
        direction=np.pi,
        spreading=6.0,
        n_directions=7,
        seed=1,
    )
    assert len(waves) == 80 * 7
    assert waves.significant_wave_height == pytest.approx(4.0, rel=1e-3)
    directions, weights = spreading_directions(np.pi, 6.0, 7)
    energy = np.array(
        [np.sum(waves.amplitude[np.isclose(waves.direction, d)] ** 2) for d in directions]
    )
    np.testing.assert_allclose(energy / energy.sum(), weights, rtol=1e-10)
    # every (frequency, direction) pair has its own random frequency
    assert np.unique(waves.omega).size == waves.omega.size
    with pytest.raises(ValueError, match="n_directions"):
        irregular_waves(JONSWAP, duration=60, spreading=4.0)
    with pytest.raises(ValueError, match="spreading"):
        irregular_waves(JONSWAP, duration=60, n_directions=3)


def test_irregular_waves_argument_errors():
    with pytest.raises(ValueError, match="duration"):
        irregular_waves(JONSWAP, duration=0)
    with pytest.raises(ValueError, match="omega_min < omega_max"):
        irregular_waves(JONSWAP, duration=60, omega_min=1.0, omega_max=0.5)
    with pytest.raises(ValueError, match="n_components"):
        irregular_waves(JONSWAP, duration=60, n_components=0)
