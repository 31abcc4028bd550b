"""Wave excitation: interpolation in frequency and heading, mirroring, τ(t)."""

from __future__ import annotations

import numpy as np
import pytest

import cummins
from cummins.errors import HydroDataError
from cummins.seakeeping.excitation import (
    INTERPOLATION_METHODS,
    excitation_coefficients,
    excitation_force,
    excitation_transfer,
    heading_coverage,
    leave_one_out_error,
    wave_response,
)
from cummins.seakeeping.waves import (
    WaveComponents,
    harmonic_sum,
    irregular_waves,
    regular_wave,
    wave_spectrum,
    wavenumber,
)


@pytest.fixture(scope="module")
def tanker(shared_data):
    return cummins.read(shared_data / "mss" / "tanker" / "tanker.1")


@pytest.fixture(scope="module")
def tanker_mss(shared_data):
    """MSS's processed tanker (its own mirroring to 0…350°), in the z-up axes of WAMIT."""
    return cummins.change_axes(cummins.read(shared_data / "mss" / "tanker" / "tanker.mat"), "z-up")


@pytest.fixture(scope="module")
def supply(shared_data):
    return cummins.read(shared_data / "mss" / "supply" / "input.re7")


def grid(ds, beta=None):
    w = ds.omega.values
    b = ds.wave_direction.values if beta is None else np.asarray(beta)
    ww, bb = np.meshgrid(w, b, indexing="ij")
    return w, b, ww.reshape(-1), bb.reshape(-1)


def test_exact_at_the_data_points(tanker):
    w, b, ww, bb = grid(tanker)
    f = excitation_transfer(tanker, ww, bb).reshape(w.size, b.size, 6)
    ref = tanker.excitation_force.transpose("omega", "wave_direction", "influenced_dof").values
    np.testing.assert_allclose(f, ref, rtol=1e-12, atol=1e-9 * np.abs(ref).max())


def test_mirrored_headings_match_mss(tanker, tanker_mss):
    """The WAMIT .3 file holds 0…180°; mirrored to 190…350° it equals MSS's forceRAO."""
    cover = heading_coverage(tanker)
    assert cover.mirror_used and cover.directions.size == 36 and "symmetric" in cover.reason
    w, b, ww, bb = grid(tanker, tanker_mss.wave_direction.values)
    f = excitation_transfer(tanker, ww, bb).reshape(w.size, b.size, 6)
    ref = tanker_mss.excitation_force.transpose("omega", "wave_direction", "influenced_dof").values
    for d in range(6):
        err = np.abs(f[..., d] - ref[..., d]).max() / np.abs(ref[..., d]).max()
        assert err < 2e-6, (d, err)


def test_supply_headings_mirrored_from_the_other_side(supply):
    """VERES gives 0° and 180…350°: the 10…170° side is mirrored."""
    cover = heading_coverage(supply)
    assert cover.mirror_used and cover.directions.size == 36
    f90 = excitation_transfer(supply, supply.omega.values, np.pi / 2)
    f270 = supply.excitation_force.sel(wave_direction=3 * np.pi / 2, method="nearest").values
    np.testing.assert_allclose(f90, f270 * np.array([1, -1, 1, -1, 1, -1]), rtol=1e-12)


def test_no_mirroring_for_an_unsymmetric_body(tanker):
    bent = tanker.copy(deep=True)
    bent["added_mass"].loc[{"influenced_dof": "Heave", "radiating_dof": "Roll"}] = 0.1 * float(
        np.sqrt(
            bent.added_mass.sel(influenced_dof="Heave", radiating_dof="Heave").max()
            * bent.added_mass.sel(influenced_dof="Roll", radiating_dof="Roll").max()
        )
    )
    cover = heading_coverage(bent)
    assert not cover.mirror_used and "Heave, Roll" in cover.reason
    excitation_transfer(bent, [0.5], [np.radians(45)])  # inside the data: fine
    with pytest.raises(HydroDataError, match=r"wave direction 270° lies in a gap.*180°"):
        excitation_transfer(bent, [0.5], [np.radians(270)])
    forced = excitation_transfer(bent, [0.5], [np.radians(270)], mirror=True)
    normal = excitation_transfer(tanker, [0.5], [np.radians(270)])
    np.testing.assert_allclose(forced, normal)
    with pytest.raises(HydroDataError, match="gap"):
        excitation_transfer(tanker, [0.5], [np.radians(270)], mirror=False)


def test_single_heading_data(shared_data):
    sphere = cummins.read(shared_data / "wecsim" / "sphere" / "sphere.1", rho=1000.0)
    w = sphere.omega.values[10:20]
    f = excitation_transfer(sphere, w, 2 * np.pi)  # 360° is 0°
    np.testing.assert_allclose(f, sphere.excitation_force.isel(wave_direction=0).values[10:20])
    with pytest.raises(HydroDataError, match=r"direction 90° asked for.*one heading \(0°\)"):
        excitation_transfer(sphere, w, np.pi / 2)


def test_frequency_range(tanker):
    w = tanker.omega.values
    with pytest.raises(HydroDataError, match=r"frequency 7 rad/s is outside.*0.0383402 to 5.98399"):
        excitation_transfer(tanker, [1.0, 7.0], [0.0, 0.0])
    f = excitation_transfer(tanker, [0.01, 1.0, 7.0], np.pi, extrapolate="zero")
    assert np.all(f[[0, 2]] == 0) and np.all(f[1] != 0)
    np.testing.assert_allclose(f[1], excitation_transfer(tanker, [1.0], [np.pi])[0])
    end = excitation_transfer(tanker, [w[-1]], [np.pi])  # the end points are inside
    np.testing.assert_allclose(end[0], tanker.excitation_force.isel(omega=-1, wave_direction=-1))


def test_forward_speeds_must_be_selected(shared_data):
    s175 = cummins.read(shared_data / "mss" / "s175" / "s175.mat")
    with pytest.raises(HydroDataError, match="forward speeds"):
        excitation_transfer(s175, [0.5], [0.0])
    one = s175.isel(forward_speed=0)
    assert excitation_transfer(one, [0.5], [0.0]).shape == (1, 6)


# --------------------------------------------------------------------------- accuracy


def test_leave_one_out_real_data(tanker, supply):
    """Each frequency left out in turn and predicted from the rest (real WAMIT, VERES data).

    Errors are fractions of the DOF's largest force. In the lower half of the frequencies
    (where the grids resolve the force), the default local cubic is 10–100 times better
    than linear interpolation; in the upper half of the tanker's grid the force turns by
    more than 90° per step and no interpolation can be trusted (reported, not tested).
    """
    for ds, limit in ((tanker, 1e-4), (supply, 1e-4)):
        low = ds.omega.values <= np.median(ds.omega.values)
        default = leave_one_out_error(ds).values[low]
        linear = leave_one_out_error(ds, method="linear").values[low]
        assert np.nanmedian(default) < limit
        assert np.nanmedian(linear) > 5 * np.nanmedian(default)
        assert np.nanpercentile(default, 95) < 0.03
    # Headings (10° apart): periodic cubic spline on the mirrored circle.
    low = tanker.omega.values <= np.median(tanker.omega.values)
    cubic = leave_one_out_error(tanker, axis="wave_direction").values[low]
    linear = leave_one_out_error(tanker, axis="wave_direction", heading_method="linear").values[low]
    assert np.nanmedian(cubic) < 2e-5 and np.nanmax(cubic) < 0.02
    assert np.nanmedian(linear) > 50 * np.nanmedian(cubic)


def peaked_dataset(step: float, zeta: float = 0.02, shift: float = 0.0):
    """A one-DOF 'Heave' database whose excitation is a sharp resonance at ω = 1."""
    w = np.arange(0.3, 2.0 + step / 2, step) + 0.0123
    f = 1e6 / (1 - w**2 + 2j * zeta * w)
    k = wavenumber(w)
    f = f * np.exp(-1j * k * shift)  # the same force on a body centred at x = shift
    one = np.ones((w.size, 1, 1))
    return cummins.make_hydrodb(
        w,
        1e5 * one,
        1e4 * one,
        rho=1025.0,
        g=9.81,
        source_format="synthetic",
        dofs=["Heave"],
        wave_direction=[0.0],
        excitation_force=f[:, None, None],
        center_of_buoyancy=[shift, 0.0, -1.0],
    )


def test_peaked_transfer_function_converges():
    """A resonance (half-power width 0.04 rad/s) sampled every 0.02 … 0.0025 rad/s."""
    fine = np.linspace(0.35, 1.95, 4001)
    exact = 1e6 / (1 - fine**2 + 0.04j * fine)
    errors = {}
    for step in (0.02, 0.01, 0.005, 0.0025):
        ds = peaked_dataset(step)
        for method in INTERPOLATION_METHODS:
            got = excitation_transfer(ds, fine, 0.0, method=method)[:, 0]
            errors[method, step] = np.abs(got - exact).max() / np.abs(exact).max()
    # third order: halving the step divides the error by about 8 once the peak is resolved
    assert errors["hermite", 0.005] / errors["hermite", 0.0025] > 6
    assert errors["hermite", 0.005] < 0.005  # 8 points across the half-power band
    assert errors["hermite", 0.01] < 0.03
    for step in (0.005, 0.0025):  # better than linear and PCHIP once resolved
        assert errors["hermite", step] < 0.5 * errors["pchip", step]
        assert errors["hermite", step] < 0.2 * errors["linear", step]
    # under-resolved (one point per half-power band): every method is off by > 10 %
    assert min(errors[m, 0.02] for m in INTERPOLATION_METHODS) > 0.05


def test_travel_phase_is_removed_before_interpolating():
    """A body 300 m from the origin: F turns by k·300 m; interpolating G = F e^{ikℓ} is far
    more accurate than interpolating F itself."""
    ds = peaked_dataset(0.01, zeta=0.2, shift=300.0)
    fine = np.linspace(0.35, 1.95, 2001)
    exact = 1e6 / (1 - fine**2 + 0.4j * fine) * np.exp(-1j * wavenumber(fine) * 300.0)
    auto = excitation_transfer(ds, fine, 0.0)[:, 0]
    origin = excitation_transfer(ds, fine, 0.0, phase_center="origin")[:, 0]
    e_auto = np.abs(auto - exact).max() / np.abs(exact).max()
    e_origin = np.abs(origin - exact).max() / np.abs(exact).max()
    assert e_auto < 2e-5 and e_origin > 100 * e_auto
    given = excitation_transfer(ds, fine, 0.0, phase_center=(300.0, 0.0))[:, 0]
    np.testing.assert_allclose(given, auto)


# --------------------------------------------------------------------------- time series


def test_regular_wave_force_is_the_transfer_function(tanker):
    """τ(t) = a |F| cos(ωt + φ + ∠F) for one component, at a data frequency and heading."""
    w0 = float(tanker.omega.values[25])
    wave = regular_wave(2.0, 2 * np.pi / w0, direction=np.pi, phase=0.3)
    t = np.linspace(0.0, 60.0, 301)
    tau = excitation_force(tanker, wave, t)
    f = tanker.excitation_force.isel(omega=25).sel(wave_direction=np.pi, method="nearest").values
    expected = 2.0 * np.abs(f) * np.cos(w0 * t[:, None] + 0.3 + np.angle(f))
    np.testing.assert_allclose(tau, expected, atol=1e-9 * np.abs(f).max())


def test_excitation_force_is_the_sum_over_components(tanker):
    waves = irregular_waves(
        wave_spectrum("jonswap", 5.0, 11.0),
        duration=600,
        n_components=40,
        direction=np.radians(150),
        spreading=8.0,
        n_directions=3,
        seed=9,
    )
    t = np.linspace(0.0, 100.0, 5001)  # uniform: the block algorithm
    tau = excitation_force(tanker, waves, t)
    f = excitation_transfer(tanker, waves.omega, waves.direction)
    brute = sum(
        a * np.real(fk[None, :] * np.exp(1j * (w * t[:, None] + p)))
        for a, w, p, fk in zip(waves.amplitude, waves.omega, waves.phase, f, strict=True)
    )
    np.testing.assert_allclose(tau, brute, atol=1e-9 * np.abs(brute).max())
    # linear in the wave amplitude
    double = WaveComponents(waves.omega, 2 * waves.amplitude, waves.phase, waves.direction)
    np.testing.assert_allclose(excitation_force(tanker, double, t), 2 * tau)
    c = excitation_coefficients(tanker, waves)
    np.testing.assert_allclose(harmonic_sum(t[::7], waves.omega, c), tau[::7])
    np.testing.assert_allclose(wave_response(waves, f, t[::7]), tau[::7])


def test_excitation_force_of_a_long_simulation(tanker):
    """200 components × 200 000 times × 6 DOFs, as a long simulation needs them."""
    waves = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0), duration=20_000, omega_max=5.9, seed=1
    )
    t = 0.1 * np.arange(200_000)
    tau = excitation_force(tanker, waves, t)
    assert tau.shape == (200_000, 6) and np.all(np.isfinite(tau))
    # every chunk of the long record is the harmonic sum written out here, at times
    # spread over the whole record (the first, the last, and across chunk boundaries)
    f = excitation_transfer(tanker, waves.omega, waves.direction)
    picks = np.unique(np.r_[0, 199_999, np.linspace(0, 199_999, 41).astype(int)])
    phase = waves.omega[None, :] * t[picks, None] + waves.phase[None, :]
    brute = np.real((waves.amplitude[None, :] * np.exp(1j * phase)) @ f)
    np.testing.assert_allclose(tau[picks], brute, atol=1e-9 * np.abs(tau).max())
    # linear in the amplitudes at every time (nothing lost to chunking)
    half = WaveComponents(waves.omega, 0.5 * waves.amplitude, waves.phase, waves.direction)
    np.testing.assert_allclose(excitation_force(tanker, half, t[::997]), 0.5 * tau[::997])
