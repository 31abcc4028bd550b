"""Environmental and external loads (cummins.timedomain.loads; Smogeli et al. (2004) §4–5, eqs.
40–55).

Wave loads are checked on the real S-175 data (MSS, z-down axes) against the data
themselves and against cummins.seakeeping.excitation; the other loads against hand computations
and closed forms.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy import integrate

import cummins
from cummins.errors import CumminsError, HydroDataError
from cummins.seakeeping.excitation import excitation_coefficients, excitation_transfer
from cummins.seakeeping.waves import (
    WaveComponents,
    harmonic_sum,
    irregular_waves,
    jonswap,
    regular_wave,
)
from cummins.timedomain import loads as L

ZERO = np.zeros(6)


@pytest.fixture(scope="module")
def s175(shared_data):
    """The S-175 at zero speed (MSS data, z-down: x forward, y starboard, z down)."""
    ds = cummins.read(shared_data / "mss" / "s175" / "s175.mat").isel(forward_speed=0)
    assert ds.attrs["axis_convention"] == "z-down"
    return ds


def _eta(north=0.0, east=0.0, psi=0.0, phi=0.0, theta=0.0):
    return np.array([north, east, 0.0, phi, theta, psi])


def _nu(u=0.0, v=0.0, r=0.0):
    return np.array([u, v, 0.0, 0.0, 0.0, r])


def _head_sea(n=40, seed=3, direction=np.pi):
    return irregular_waves(
        lambda w: jonswap(w, 4.0, 10.0),
        duration=3600.0,
        n_components=n,
        omega_min=0.3,
        omega_max=2.0,
        direction=direction,
        seed=seed,
    )


def _drift_data(ds, dof, beta):
    """The data's drift_force[ω, β, dof] at one data heading, as a function of ω."""
    i = int(np.argmin(np.abs(np.mod(ds.wave_direction.values - beta + np.pi, 2 * np.pi) - np.pi)))
    assert abs(ds.wave_direction.values[i] - np.mod(beta, 2 * np.pi)) < 1e-4
    return ds.drift_force.isel(wave_direction=i).sel(influenced_dof=dof).values


# --------------------------------------------------------------------------- current


def test_current_velocity_follows_eq40_and_relative_velocity_eq49():
    east = L.Current(1.5, np.pi / 2)  # flows towards East
    np.testing.assert_allclose(east.velocity_body(0.0), [0.0, 1.5, 0.0], atol=1e-15)
    # heading East: the current comes from astern
    np.testing.assert_allclose(east.velocity_body(np.pi / 2), [1.5, 0.0, 0.0], atol=1e-15)
    # heading West: from ahead
    np.testing.assert_allclose(east.velocity_body(-np.pi / 2), [-1.5, 0.0, 0.0], atol=1e-15)
    nu = np.array([2.0, 0.1, 0.2, 0.01, 0.02, 0.03])
    nu_r = east.relative_velocity(_eta(psi=np.pi / 2), nu)
    np.testing.assert_allclose(nu_r, nu - [1.5, 0.0, 0.0, 0, 0, 0], atol=1e-15)
    with pytest.raises(CumminsError, match="current speed"):
        L.Current(-1.0, 0.0)


# --------------------------------------------------------------------------- first order


def test_first_order_equals_excitation_force_on_a_grid_heading(s175):
    waves = _head_sea()
    load = L.FirstOrderWaveLoad.from_hydrodb(s175, waves)
    t = np.linspace(0.0, 200.0, 41)
    ref = harmonic_sum(t, waves.omega, excitation_coefficients(s175, waves))
    got = np.array([load.force(ti, ZERO, ZERO) for ti in t])
    assert np.abs(ref[:, [0, 2, 4]]).max() > 1e6  # a real force, not zeros
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    # the same relative heading reached by turning ship and sea together: same force
    turned = WaveComponents(
        waves.omega, waves.amplitude, waves.phase, waves.direction + 0.5 * np.pi
    )
    load_t = L.FirstOrderWaveLoad.from_hydrodb(s175, turned)
    got_t = np.array([load_t.force(ti, _eta(psi=0.5 * np.pi), ZERO) for ti in t])
    np.testing.assert_allclose(got_t, ref, rtol=0, atol=1e-9 * np.abs(ref).max())


def test_first_order_interpolates_the_relative_heading(s175):
    waves = _head_sea()
    cubic = L.FirstOrderWaveLoad.from_hydrodb(s175, waves)  # 2.5°, Catmull–Rom
    linear = L.FirstOrderWaveLoad.from_hydrodb(
        s175, waves, heading_step=np.radians(5.0), heading_interpolation="linear"
    )
    assert cubic.transfer.shape == (144, len(waves), 6)
    assert linear.transfer.shape == (72, len(waves), 6)
    scale = np.abs(cubic.transfer).max(axis=(0, 1))  # largest |T| of each DOF
    worst_cubic = worst_linear = 0.0
    for psi in np.linspace(-np.pi, np.pi, 25)[:-1] + 0.017:
        exact = excitation_transfer(s175, waves.omega, waves.direction - psi)
        worst_cubic = max(worst_cubic, (np.abs(cubic.transfer_at(psi) - exact) / scale).max())
        worst_linear = max(worst_linear, (np.abs(linear.transfer_at(psi) - exact) / scale).max())
    assert worst_cubic < 5e-3
    assert worst_linear > 3 * worst_cubic  # why the default is cubic
    # waves travelling to starboard (ship heading West, waves travelling North):
    # much more sway than in head seas
    beam = cubic.transfer_at(-np.pi / 2)
    assert np.abs(beam[:, 1]).max() > 10 * np.abs(cubic.transfer_at(0.0)[:, 1]).max()
    # the force interpolates the same table as transfer_at
    eta = _eta(psi=0.4)
    c = waves.complex_amplitude * np.exp(1j * waves.omega * 3.0)
    np.testing.assert_allclose(
        cubic.force(3.0, eta, ZERO), (c @ cubic.transfer_at(0.4)).real, rtol=1e-12
    )


def test_first_order_includes_the_phase_of_the_vessel_position(s175):
    waves = _head_sea(n=20, direction=np.pi - 0.4)
    load = L.FirstOrderWaveLoad.from_hydrodb(s175, waves)
    north, east = 120.0, -35.0
    k = waves.omega**2 / float(s175.attrs["g"])
    shifted = WaveComponents(
        waves.omega,
        waves.amplitude,
        waves.phase - k * (north * np.cos(waves.direction) + east * np.sin(waves.direction)),
        waves.direction,
    )
    t = np.linspace(0.0, 60.0, 13)
    ref = harmonic_sum(t, waves.omega, excitation_coefficients(s175, shifted))
    heading = -0.4  # the waves (β = π − 0.4) meet the ship head on: γ = π, a grid heading
    ref_psi = harmonic_sum(
        t,
        waves.omega,
        shifted.complex_amplitude[:, None]
        * excitation_transfer(s175, waves.omega, waves.direction - heading),
    )
    got = np.array([load.force(ti, _eta(north, east, psi=heading), ZERO) for ti in t])
    np.testing.assert_allclose(got, ref_psi, atol=1e-9 * np.abs(ref_psi).max())
    assert np.abs(ref_psi - ref).max() > 0.1 * np.abs(ref).max()  # heading mattered
    off = L.FirstOrderWaveLoad.from_hydrodb(s175, waves, position_phase=False)
    away = np.array([off.force(ti, _eta(north, east), ZERO) for ti in t])
    at_origin = np.array([load.force(ti, ZERO, ZERO) for ti in t])
    np.testing.assert_allclose(away, at_origin, atol=1e-9 * np.abs(at_origin).max())


def test_first_order_out_of_range_frequency_raises(s175):
    waves = regular_wave(1.0, 2 * np.pi / 5.0)  # 5 rad/s, above the data
    with pytest.raises(HydroDataError, match="outside the data's range"):
        L.FirstOrderWaveLoad.from_hydrodb(s175, waves)
    zero = L.FirstOrderWaveLoad.from_hydrodb(s175, waves, extrapolate="zero")
    np.testing.assert_array_equal(zero.force(3.0, ZERO, ZERO), np.zeros(6))


# --------------------------------------------------------------------------- drift


def test_drift_of_a_regular_head_wave_equals_the_data(s175):
    j = 23
    omega = float(s175.omega[j])
    surge = _drift_data(s175, "Surge", np.pi)[j]
    assert surge < -5e4  # head seas push the S-175 aft
    for slowly in (True, False):
        load = L.WaveDriftLoad.from_hydrodb(
            s175, regular_wave(2.0, 2 * np.pi / omega, np.pi), slowly_varying=slowly
        )
        tau = load.force(17.0, ZERO, ZERO)
        assert tau[0] == pytest.approx(4.0 * surge, rel=1e-9)
    # heading East in waves travelling East: following seas (γ = 0) data
    follow = L.WaveDriftLoad.from_hydrodb(s175, regular_wave(2.0, 2 * np.pi / omega, np.pi / 2))
    assert follow.force(0.0, _eta(psi=np.pi / 2), ZERO)[0] == pytest.approx(
        4.0 * _drift_data(s175, "Surge", 0.0)[j], rel=1e-9
    )
    # heading East in waves travelling South: they travel to starboard (γ = π/2)
    beam = L.WaveDriftLoad.from_hydrodb(s175, regular_wave(2.0, 2 * np.pi / omega, np.pi))
    sway = beam.force(0.0, _eta(psi=np.pi / 2), ZERO)[1]
    assert sway == pytest.approx(4.0 * _drift_data(s175, "Sway", np.pi / 2)[j], rel=1e-9)
    assert sway > 0


def test_drift_mean_of_an_irregular_head_sea_equals_the_data(s175):
    waves = _head_sea(n=60)
    load = L.WaveDriftLoad.from_hydrodb(s175, waves)
    w = s175.omega.values
    expected = np.sum(
        waves.amplitude**2 * np.interp(waves.omega, w, _drift_data(s175, "Surge", np.pi))
    )
    mean = load.mean_force(0.0)
    assert mean[0] == pytest.approx(expected, rel=1e-10)
    assert expected < 0
    assert abs(mean[1]) < 1e-6 * abs(mean[0])  # no sway drift in head seas


def test_drift_time_average_is_the_mean_drift(s175):
    # commensurate frequencies: the slowly varying part averages to zero over 2π/ω₀
    w0 = 0.02
    omega = w0 * np.arange(20, 60)
    rng = np.random.default_rng(7)
    waves = WaveComponents(
        omega,
        0.2 + rng.uniform(size=omega.size),
        rng.uniform(0, 2 * np.pi, omega.size),
        np.full(omega.size, np.pi - 0.3),
    )
    load = L.WaveDriftLoad.from_hydrodb(s175, waves)
    period = 2 * np.pi / w0
    t = np.arange(512) * period / 512  # > 2 × the largest difference frequency
    series = np.array([load.force(ti, ZERO, ZERO) for ti in t])
    mean = load.mean_force(0.0)
    np.testing.assert_allclose(series.mean(axis=0), mean, rtol=1e-9, atol=1e-9 * np.abs(mean).max())
    assert series[:, 0].std() > 0.1 * abs(mean[0])  # and it does vary slowly
    steady = L.WaveDriftLoad.from_hydrodb(s175, waves, slowly_varying=False)
    np.testing.assert_allclose(steady.force(123.0, ZERO, ZERO), mean, rtol=1e-12)


def test_drift_of_two_components_oscillates_at_the_difference_frequency(s175):
    j1, j2 = 20, 23
    w = s175.omega.values
    t11, t22 = _drift_data(s175, "Surge", np.pi)[[j1, j2]]
    waves = WaveComponents([w[j1], w[j2]], [1.5, 1.0], [0.3, 2.0], [np.pi, np.pi])
    load = L.WaveDriftLoad.from_hydrodb(s175, waves)
    t = np.linspace(0.0, 400.0, 801)
    got = np.array([load.force(ti, ZERO, ZERO)[0] for ti in t])
    dw = w[j2] - w[j1]
    expected = 1.5**2 * t11 + 1.0**2 * t22 + 1.5 * 1.0 * (t11 + t22) * np.cos(dw * t + 2.0 - 0.3)
    np.testing.assert_allclose(got, expected, rtol=1e-10, atol=1e-8 * abs(expected).max())
    assert got.max() - got.min() == pytest.approx(2 * 1.5 * abs(t11 + t22), rel=1e-3)
    # away from the origin the group phase shifts by −(k₂ − k₁) N cos β
    north = 80.0
    k = np.array([w[j1], w[j2]]) ** 2 / float(s175.attrs["g"])
    shift = -(k[1] - k[0]) * north * np.cos(np.pi)
    away = np.array([load.force(ti, _eta(north), ZERO)[0] for ti in t])
    expected = 1.5**2 * t11 + t22 + 1.5 * (t11 + t22) * np.cos(dw * t + 2.0 - 0.3 + shift)
    np.testing.assert_allclose(away, expected, rtol=1e-10, atol=1e-8 * abs(expected).max())
    # a point of attack forward of O adds the yaw moment x f_2 (eq. 48)
    beam = WaveComponents([w[j1]], [1.0], [0.0], [np.pi / 2])
    at_o = L.WaveDriftLoad.from_hydrodb(s175, beam).force(0.0, ZERO, ZERO)
    fwd = L.WaveDriftLoad.from_hydrodb(s175, beam, point=[10.0, 0.0, 0.0]).force(0.0, ZERO, ZERO)
    assert fwd[5] == pytest.approx(at_o[5] + 10.0 * at_o[1], rel=1e-12)


def test_drift_outside_the_frequency_range(s175):
    waves = regular_wave(2.0, 2 * np.pi / 5.0, np.pi)  # 5 rad/s, above the data (π rad/s)
    with pytest.raises(HydroDataError, match="outside the data's range"):
        L.WaveDriftLoad.from_hydrodb(s175, waves)
    zero = L.WaveDriftLoad.from_hydrodb(s175, waves, extrapolate="zero")
    np.testing.assert_array_equal(zero.force(0.0, ZERO, ZERO), np.zeros(6))
    nearest = L.WaveDriftLoad.from_hydrodb(s175, waves, extrapolate="nearest")
    last = _drift_data(s175, "Surge", np.pi)[-1]
    assert nearest.force(0.0, ZERO, ZERO)[0] == pytest.approx(4.0 * last, rel=1e-12)


def test_z_up_data_give_the_same_loads(s175):
    z_up = cummins.hydrodb.change_axes(s175, "z-up")
    assert z_up.attrs["axis_convention"] == "z-up"
    waves = _head_sea(n=15, direction=np.pi - 0.5)
    eta = _eta(30.0, -10.0, psi=0.2)
    for build in (L.FirstOrderWaveLoad.from_hydrodb, L.WaveDriftLoad.from_hydrodb):
        down, up = build(s175, waves), build(z_up, waves)
        for t in (0.0, 13.0):
            f_down, f_up = down.force(t, eta, ZERO), up.force(t, eta, ZERO)
            np.testing.assert_allclose(f_up, f_down, atol=1e-9 * np.abs(f_down).max())


def test_drift_needs_drift_data(s175):
    with pytest.raises(HydroDataError, match="drift_force"):
        L.WaveDriftLoad.from_hydrodb(s175.drop_vars("drift_force"), _head_sea(n=5))


def test_drift_half_plane_data_is_mirrored(s175):
    beta = s175.wave_direction.values
    half = s175.isel(wave_direction=np.flatnonzero(beta <= np.pi + 1e-6))
    omega = float(s175.omega[25])
    waves = regular_wave(1.0, 2 * np.pi / omega, 1.5 * np.pi)  # to port: a mirrored heading
    full = L.WaveDriftLoad.from_hydrodb(s175, waves).mean_force(0.0)
    mirrored = L.WaveDriftLoad.from_hydrodb(half, waves).mean_force(0.0)
    assert full[1] < 0  # waves travelling to port push to port
    # surge and sway only: the S-175 yaw drift of the MSS file is even in the heading
    # (vessel.driftfrc.amp{3} is the same at 90° and 270°), not odd as for a symmetric hull
    np.testing.assert_allclose(mirrored[[0, 1]], full[[0, 1]], rtol=1e-9)
    with pytest.raises(HydroDataError, match="no heading between"):
        L.WaveDriftLoad.from_hydrodb(half, waves, mirror=False)


# --------------------------------------------------------------------------- viscous


def test_ittc_friction_line_and_surge_resistance_by_hand():
    assert float(L.ittc_friction(1e7)) == pytest.approx(0.075 / 25.0, rel=1e-14)
    assert float(L.ittc_friction(1e9)) == pytest.approx(0.075 / 49.0, rel=1e-14)
    res = L.SurgeResistance(
        wetted_surface=5000.0, length=175.0, form_factor=0.2, roughness_allowance=4e-4
    )
    u = 5.0
    rn = u * 175.0 / 1.19e-6
    cf = 0.075 / (math.log10(rn) - 2) ** 2
    expected = -0.5 * 1025.0 * 5000.0 * 1.2 * (cf + 4e-4) * u * u
    tau = res.force(0.0, ZERO, _nu(u=u))
    assert tau[0] == pytest.approx(expected, rel=1e-12)
    np.testing.assert_array_equal(tau[1:], 0.0)
    assert res.force(0.0, ZERO, _nu(u=-u))[0] == pytest.approx(-expected, rel=1e-12)
    # slow: C_f held at Rn = 1e5, finite, force → 0 quadratically
    slow = 1e-4
    cf_min = 0.075 / 3.0**2
    assert res.force(0.0, ZERO, _nu(u=slow))[0] == pytest.approx(
        -0.5 * 1025.0 * 5000.0 * 1.2 * (cf_min + 4e-4) * slow**2, rel=1e-12
    )
    assert np.all(res.force(0.0, ZERO, ZERO) == 0.0)
    # at rest in a current flowing North, heading North: dragged along (+x)
    drift = dataclasses.replace(res, current=L.Current(1.0, 0.0))
    assert drift.force(0.0, ZERO, ZERO)[0] > 0
    # Denny–Mumford: S = L (1.7 T + C_B B)
    est = L.SurgeResistance.from_main_particulars(175.0, 25.4, 9.5, 0.57)
    assert est.wetted_surface == pytest.approx(175.0 * (1.7 * 9.5 + 0.57 * 25.4))


def test_cross_flow_drag_of_a_uniform_hull_matches_closed_forms():
    rho, cd, draught, length = 1025.0, 0.9, 8.0, 120.0
    drag = L.CrossFlowDrag.from_main_particulars(
        length, 20.0, draught, drag_coefficient=cd, n_strips=2000
    )
    v = 0.7
    tau = drag.force(0.0, ZERO, _nu(v=v))
    assert tau[1] == pytest.approx(-0.5 * rho * cd * draught * length * v * abs(v), rel=1e-12)
    assert tau[1] < 0  # sway to starboard: force to port
    assert abs(tau[5]) < 1e-9 * abs(tau[1]) * length
    assert drag.force(0.0, ZERO, _nu(v=-v))[1] == pytest.approx(-tau[1], rel=1e-12)
    r = 0.01
    yaw = drag.force(0.0, ZERO, _nu(r=r))
    # ∫ x · (r x)|r x| dx over [−L/2, L/2] = r|r| L⁴/32
    assert yaw[5] == pytest.approx(
        -0.5 * rho * cd * draught * r * abs(r) * length**4 / 32, rel=1e-5
    )
    assert yaw[5] < 0  # opposes the yaw rate
    assert abs(yaw[1]) < 1e-9 * abs(yaw[5])
    assert drag.force(0.0, ZERO, _nu(r=-r))[5] > 0
    # current setting East, vessel at rest heading North: pushed to starboard
    with_current = dataclasses.replace(drag, current=L.Current(0.5, np.pi / 2))
    assert with_current.force(0.0, ZERO, ZERO)[1] == pytest.approx(
        0.5 * rho * cd * draught * length * 0.25, rel=1e-12
    )
    # a point of attack below O adds the roll moment −z f_2 (eq. 54)
    deep = dataclasses.replace(drag, point=np.array([0.0, 0.0, 4.0]))
    low = deep.force(0.0, ZERO, _nu(v=v))
    assert low[3] == pytest.approx(-4.0 * tau[1], rel=1e-12)
    assert low[3] > 0  # keel pushed to port: heel to starboard


#: Hoerner's 2-D cross-flow drag coefficient C_D against B/(2T), as digitised by Leite,
#: Aranha, Umeda & de Conti (1998, Appl. Ocean Res. 20) and published in MSS's Hoerner.m
#: (Fossen 2007): the literature values, kept here apart from the module's own copy so
#: that a transcription error in either is caught.
LITERATURE_HOERNER = [
    (0.0108623, 1.96608),
    (0.176606, 1.96573),
    (0.353025, 1.89756),
    (0.451863, 1.78718),
    (0.472838, 1.58374),
    (0.492877, 1.27862),
    (0.493252, 1.21082),
    (0.558473, 1.08356),
    (0.646401, 0.998631),
    (0.833589, 0.87959),
    (0.988002, 0.828415),
    (1.30807, 0.759941),
    (1.63918, 0.691442),
    (1.85998, 0.657076),
    (2.31288, 0.630693),
    (2.59998, 0.596186),
    (3.00877, 0.586846),
    (3.45075, 0.585909),
    (3.7379, 0.559877),
    (4.00309, 0.559315),
]


def test_hoerner_curve():
    """C_D(B/2T) against the literature table: at its points, linearly between them (as
    MSS interpolates), held at the ends; the flat-plate limit near 2 (Hoerner 1965)."""
    ratio, cd = np.array(LITERATURE_HOERNER).T
    assert L.HOERNER_DRAG.shape == (ratio.size, 2)
    for r, c in LITERATURE_HOERNER:
        assert float(L.hoerner_drag_coefficient(2.0 * r, 1.0)) == pytest.approx(c, rel=1e-9)
    between = 0.5 * (ratio[:-1] + ratio[1:])
    expected = cd[:-1] + (between - ratio[:-1]) / np.diff(ratio) * np.diff(cd)
    np.testing.assert_allclose(L.hoerner_drag_coefficient(2.0 * between, 1.0), expected, rtol=1e-9)
    assert float(L.hoerner_drag_coefficient(0.001, 10.0)) == pytest.approx(cd[0])
    assert float(L.hoerner_drag_coefficient(100.0, 1.0)) == pytest.approx(cd[-1])
    assert 1.9 < cd[0] < 2.05  # a flat plate across the flow
    # the S-175 (B = 25.4 m, T = 9.5 m): B/2T = 1.3368, between 1.30807 and 1.63918
    drag = L.CrossFlowDrag.from_main_particulars(175.0, 25.4, 9.5)
    by_hand = 0.759941 + (25.4 / 19.0 - 1.30807) / (1.63918 - 1.30807) * (0.691442 - 0.759941)
    assert drag.drag_coefficient[0] == pytest.approx(by_hand, rel=1e-9)


# --------------------------------------------------------------------------- wind


def test_gust_spectra_integrate_to_their_variance():
    # Harris: σ² = 4 κ U² ∫₀^∞ (2 + x²)^(−5/6) dx, the integral by quadrature here
    integral, _ = integrate.quad(lambda x: (2 + x * x) ** (-5 / 6), 0, np.inf)
    for u, kappa in ((10.0, 0.0026), (25.0, 0.002)):
        expected = 4 * kappa * u * u * integral
        assert L.harris_variance(u, drag_coefficient=kappa) == pytest.approx(expected, rel=1e-9)
        value, _ = integrate.quad(
            lambda w, u=u, k=kappa: L.harris(w, u, drag_coefficient=k)[()], 0, np.inf, limit=400
        )
        assert value == pytest.approx(expected, rel=1e-6)
    # NORSOK N-003: the formula in Hz, by hand, at one point
    u, z, f = 20.0, 30.0, 0.01
    ft = 172 * f * (z / 10) ** (2 / 3) * (u / 10) ** -0.75
    s_f = 320 * (u / 10) ** 2 * (z / 10) ** 0.45 / (1 + ft**0.468) ** (5 / (3 * 0.468))
    w = 2 * np.pi * f
    assert float(L.norsok(w, u, height=z)) == pytest.approx(s_f / (2 * np.pi), rel=1e-12)
    for u, z in ((10.0, 10.0), (30.0, 50.0)):
        value, _ = integrate.quad(
            lambda x, u=u, z=z: L.norsok(x, u, height=z)[()], 0, np.inf, limit=400
        )
        assert value == pytest.approx(L.norsok_variance(u, height=z), rel=1e-6)
    # turbulence intensity of the usual magnitude (σ/U ~ 0.1)
    assert 0.05 < math.sqrt(L.norsok_variance(10.0)) / 10.0 < 0.15
    assert 0.05 < math.sqrt(L.harris_variance(10.0)) / 10.0 < 0.2


def test_wind_gust_realisation():
    gust = L.wind_gust(12.0, "harris", n_components=150, seed=11)
    lo, hi = 2 * np.pi / 3600, 2 * np.pi * 0.5
    in_range, _ = integrate.quad(
        lambda w: L.harris(w, 12.0)[()], lo, hi, limit=400, points=[0.01, 0.1]
    )
    assert gust.variance == pytest.approx(in_range, rel=1e-6)
    assert gust.variance > 0.9 * L.harris_variance(12.0)
    assert np.all((gust.omega >= lo) & (gust.omega <= hi))
    again = L.wind_gust(12.0, "harris", n_components=150, seed=11)
    assert gust(321.0) == again(321.0)  # deterministic in t and seed
    t = np.linspace(0, 3 * 3600.0, 20001)
    series = gust.series(t)
    assert series[1234] == pytest.approx(gust(t[1234]), abs=1e-12)
    assert np.var(series) == pytest.approx(gust.variance, rel=0.3)
    other = L.wind_gust(12.0, "harris", n_components=150, seed=12)
    assert other(321.0) != gust(321.0)
    with pytest.raises(CumminsError, match="unknown wind spectrum"):
        L.wind_gust(10.0, "kaimal")


def test_wind_load_directions_and_magnitudes():
    rho, a_f, a_l, loa = 1.225, 400.0, 2000.0, 180.0
    coef = L.ParametricWindCoefficients(c_x=0.6, c_y=0.9, c_n=0.1)
    head = L.WindLoad(L.Wind(15.0, 0.0), a_f, a_l, loa, coefficients=coef)
    tau = head.force(0.0, ZERO, ZERO)  # heading North, wind from North
    assert tau[0] == pytest.approx(-0.5 * rho * 0.6 * a_f * 15.0**2, rel=1e-12)
    assert np.abs(tau[1:]).max() < 1e-9 * abs(tau[0])
    # heading East in a wind from the North: wind from port pushes to starboard
    port = head.force(0.0, _eta(psi=np.pi / 2), ZERO)
    assert port[1] == pytest.approx(0.5 * rho * 0.9 * a_l * 15.0**2, rel=1e-12)
    # heading East in a wind from the East: a head wind again
    east = L.WindLoad(L.Wind(15.0, np.pi / 2), a_f, a_l, loa, coefficients=coef)
    np.testing.assert_allclose(
        east.force(0.0, _eta(psi=np.pi / 2), ZERO), tau, atol=1e-9 * abs(tau[0])
    )
    # the same wind on a ship heading North comes from starboard: pushes to port
    side = east.force(0.0, ZERO, ZERO)
    assert side[1] == pytest.approx(-0.5 * rho * 0.9 * a_l * 15.0**2, rel=1e-12)
    assert abs(side[0]) < 1e-9 * abs(side[1])
    # wind on the starboard bow (45°): bow pushed to port
    bow = L.WindLoad(L.Wind(15.0, np.pi / 4), a_f, a_l, loa, coefficients=coef)
    assert bow.force(0.0, ZERO, ZERO)[5] == pytest.approx(
        -0.5 * rho * 0.1 * a_l * loa * 15.0**2, rel=1e-12
    )
    # calm air, ship making 5 m/s ahead: a 5 m/s head wind
    calm = L.WindLoad(L.Wind(0.0, 0.0), a_f, a_l, loa, coefficients=coef)
    assert calm.force(0.0, ZERO, _nu(u=5.0))[0] == pytest.approx(
        -0.5 * rho * 0.6 * a_f * 25.0, rel=1e-12
    )
    speed, gamma = calm.relative_wind(0.0, ZERO, _nu(u=5.0, v=5.0))
    assert speed == pytest.approx(math.hypot(5, 5))
    assert gamma == pytest.approx(np.pi / 4)  # moving ahead and to starboard
    # centre of wind pressure 10 m above O: wind from starboard heels to port
    high = dataclasses.replace(east, point=np.array([0.0, 0.0, -10.0]))
    heel = high.force(0.0, ZERO, ZERO)
    assert heel[3] == pytest.approx(10.0 * side[1], rel=1e-12)
    assert heel[3] < 0


def test_wind_load_with_gust_and_tables():
    gust = L.wind_gust(10.0, "norsok", seed=5)
    load = L.WindLoad(L.Wind(10.0, 0.0, gust), 300.0, 1500.0, 150.0)
    for t in (0.0, 77.0, 1000.0):
        speed = 10.0 + gust(t)
        assert load.force(t, ZERO, ZERO)[0] == pytest.approx(
            -0.5 * 1.225 * 0.7 * 300.0 * speed**2, rel=1e-12
        )
    param = L.ParametricWindCoefficients()
    angles = np.radians(np.arange(0.0, 181.0, 10.0))
    half = param.table(angles)
    table = L.WindCoefficients(angles, half.cx, half.cy, half.cn)  # completed by symmetry
    for deg in (0.0, 40.0, 180.0, -40.0, 220.0):
        np.testing.assert_allclose(table(np.radians(deg)), param(np.radians(deg)), atol=1e-12)
    mid = table(np.radians(-55.0))
    assert np.abs(mid - param(np.radians(-55.0))).max() < 0.02  # linear between nodes
    assert mid[1] > 0  # wind from port pushes to starboard
    tabled = dataclasses.replace(load, coefficients=table)
    np.testing.assert_allclose(
        tabled.force(5.0, ZERO, ZERO), load.force(5.0, ZERO, ZERO), rtol=1e-12
    )
    with pytest.raises(CumminsError, match="angles"):
        L.WindCoefficients([0.0, 1.0], [1.0], [1.0], [1.0])


# --------------------------------------------------------------------------- external


def test_crane_load_in_ned_frame_by_hand():
    weight = 1e6  # 1000 kN, along NED down
    crane = L.PointLoad([0.0, 0.0, weight], [0.0, 15.0, 0.0], frame="ned", name="crane")
    tau = crane.force(0.0, ZERO, ZERO)
    np.testing.assert_allclose(tau, [0, 0, weight, 15.0 * weight, 0, 0])
    phi = 0.1  # heeled to starboard: the weight has a sway component in the b-frame
    tau = crane.force(0.0, _eta(phi=phi, psi=0.7), ZERO)
    f_b = weight * np.array([0.0, np.sin(phi), np.cos(phi)])
    m_b = np.cross([0.0, 15.0, 0.0], f_b)
    np.testing.assert_allclose(tau, np.r_[f_b, m_b], atol=1e-6)
    assert tau[3] == pytest.approx(15.0 * weight * np.cos(phi))
    # fixed to the hull (b-frame): heel does not turn it
    body = dataclasses.replace(crane, frame="body")
    np.testing.assert_allclose(
        body.force(0.0, _eta(phi=phi), ZERO), [0, 0, weight, 15.0 * weight, 0, 0]
    )
    # a pure moment in the n-frame, yaw about down, is unchanged by the heading
    twist = L.PointLoad([0, 0, 0], [10.0, 0, 0], moment=[0, 0, 5e5], frame="ned")
    np.testing.assert_allclose(twist.force(0, _eta(psi=1.0), ZERO), [0, 0, 0, 0, 0, 5e5])


def test_point_load_timing():
    load = L.PointLoad([1e5, 0, 0], [-80.0, 0, 0], start=10.0, ramp=20.0, stop=100.0)
    assert np.all(load.force(5.0, ZERO, ZERO) == 0)
    assert load.force(20.0, ZERO, ZERO)[0] == pytest.approx(0.5e5)
    assert load.force(30.0, ZERO, ZERO)[0] == pytest.approx(1e5)
    assert load.force(99.9, ZERO, ZERO)[0] == pytest.approx(1e5)
    assert np.all(load.force(100.0, ZERO, ZERO) == 0)
    with pytest.raises(CumminsError, match="frame"):
        L.PointLoad([1, 0, 0], frame="NED-ish")
    with pytest.raises(CumminsError, match="stop"):
        L.PointLoad([1, 0, 0], start=5.0, stop=1.0)


def test_user_loads_sum_and_protocol(s175):
    spring = L.FunctionLoad("mooring", lambda t, eta, nu: np.r_[-1e5 * eta[0], np.zeros(5)])
    const = L.ConstantLoad("thrust", [2e5, 0, 0, 0, 0, 1e6])
    drag = L.CrossFlowDrag.from_main_particulars(175.0, 25.4, 9.5)
    waves = L.FirstOrderWaveLoad.from_hydrodb(s175, _head_sea(n=10))
    loads = [spring, const, drag, waves, L.WindLoad(L.Wind(10.0, 1.0), 300, 1500, 180)]
    for load in loads:
        assert isinstance(load, L.Load)
    eta, nu = _eta(3.0, psi=0.1), _nu(1.0, 0.2, 0.001)
    parts = L.load_forces(loads, 12.0, eta, nu)
    assert list(parts) == ["mooring", "thrust", "cross-flow drag", "first-order waves", "wind"]
    np.testing.assert_allclose(L.total_force(loads, 12.0, eta, nu), sum(parts.values()))
    assert parts["mooring"][0] == -3e5
    with pytest.raises(CumminsError, match="two loads are named"):
        L.load_forces([const, const], 0.0, eta, nu)
    bad = L.FunctionLoad("bad", lambda t, eta, nu: np.zeros(3))
    with pytest.raises(CumminsError, match="returned 3 components"):
        bad.force(0.0, eta, nu)
    with pytest.raises(dataclasses.FrozenInstanceError):
        const.name = "other"
