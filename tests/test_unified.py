"""The nonlinear 6-DOF model of Smogeli et al. (2004) (cummins.timedomain.unified) and its
kinematics."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import cummins
from cummins.errors import SimulationError
from cummins.kinematics import (
    attitude_transform,
    point_load,
    point_motion,
    rotation_matrix,
    screw_transform,
    velocity_transform,
)
from cummins.seakeeping.excitation import excitation_coefficients
from cummins.seakeeping.waves import irregular_waves, wave_spectrum
from cummins.timedomain.simulate import simulate
from cummins.timedomain.unified import (
    UnifiedVessel,
    coriolis_rigid_body,
    simulate_unified,
    unified_vessel,
)

angles = st.floats(-1.4, 1.4)


def _rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _ry(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


@given(angles, angles, st.floats(-np.pi, np.pi))
@settings(max_examples=60, deadline=None)
def test_rotation_matrix_is_the_zyx_product_and_orthogonal(phi, theta, psi):
    """Eq. 6 = R_z(ψ) R_y(θ) R_x(φ); R⁻¹ = Rᵀ, det R = 1; J's blocks (eq. 10)."""
    r = rotation_matrix([phi, theta, psi])
    np.testing.assert_allclose(r, _rz(psi) @ _ry(theta) @ _rx(phi), atol=1e-12)
    np.testing.assert_allclose(r.T @ r, np.eye(3), atol=1e-12)
    assert np.linalg.det(r) == pytest.approx(1.0)
    j = velocity_transform([1.0, 2.0, 3.0, phi, theta, psi])
    np.testing.assert_allclose(j[:3, :3], r)
    np.testing.assert_allclose(j[3:, 3:], attitude_transform([phi, theta, psi]))
    np.testing.assert_array_equal(j[:3, 3:], 0.0)


@given(angles, angles)
@settings(max_examples=40, deadline=None)
def test_attitude_transform_gives_the_euler_angle_rates(phi, theta):
    """Eq. 8 against its definition ω = φ̇ e_x + θ̇ R_x(φ)ᵀ e_y + ψ̇ (R_y(θ)R_x(φ))ᵀ e_z."""
    rates = np.array([0.3, -0.2, 0.5])
    omega = (
        rates[0] * np.array([1.0, 0, 0])
        + rates[1] * _rx(phi).T @ [0, 1.0, 0]
        + rates[2] * (_ry(theta) @ _rx(phi)).T @ [0, 0, 1.0]
    )
    np.testing.assert_allclose(attitude_transform([phi, theta, 0.0]) @ omega, rates, atol=1e-10)


def test_attitude_transform_singular_at_ninety_degrees_pitch():
    with pytest.raises(ValueError, match="90"):
        attitude_transform([0.0, np.pi / 2, 0.0])


def test_point_load_by_hand():
    """A 1000 kN crane load hanging 15 m to starboard (Smogeli et al. (2004) §7): heave force and
    a heeling moment to starboard, r × F by hand."""
    f = np.array([0.0, 0.0, 1e6])
    r = np.array([0.0, 15.0, 0.0])
    tau = point_load(f, r)
    np.testing.assert_allclose(tau[:3], f)
    np.testing.assert_allclose(tau[3:], [15.0 * 1e6, 0.0, 0.0])
    # any point and force: the moment is r × F, and H(r)ᵀ of eq. 45
    rng = np.random.default_rng(0)
    for _ in range(5):
        f, r, m = rng.normal(size=(3, 3))
        tau = point_load(f, r, m)
        np.testing.assert_allclose(tau[3:], np.cross(r, f) + m)
        np.testing.assert_allclose(tau, screw_transform(r).T @ np.concatenate([f, m]))


def test_point_motion_is_the_rigid_body_velocity():
    eta = np.array([10.0, -5.0, 1.0, 0.1, -0.05, 0.7])
    nu = np.array([1.0, 0.2, -0.1, 0.02, 0.03, -0.04])
    r = np.array([20.0, 5.0, -3.0])
    position, velocity = point_motion(eta, nu, r)
    np.testing.assert_allclose(position, eta[:3] + rotation_matrix(eta[3:]) @ r)
    np.testing.assert_allclose(velocity, nu[:3] + np.cross(nu[3:], r))


def test_coriolis_does_no_work():
    """νᵀC_RB(ν)ν = 0 (skew-symmetric C_RB): the Coriolis force exchanges no energy."""
    m_rb = cummins.kinematics.rigid_body_inertia(1e7, [2.0, 0.1, -1.0], np.diag([1e9, 2e10, 2e10]))
    rng = np.random.default_rng(1)
    for _ in range(10):
        nu = rng.normal(size=6)
        assert abs(nu @ coriolis_rigid_body(m_rb, nu)) < 1e-6 * np.abs(m_rb).max()


# --------------------------------------------------------------------------- the model


@pytest.fixture(scope="module")
def s175(shared_data):
    return cummins.read(shared_data / "mss" / "s175" / "s175.mat").isel(forward_speed=0)


@pytest.fixture(scope="module")
def s175_model(s175):
    return unified_vessel(s175, viscous_damping={"Surge": 2e5, "Sway": 1e6, "Yaw": 1e10})


class _Waves:
    """The first-order wave force of fixed components (no heading dependence): the
    force of the linear simulator, as a load."""

    name = "waves"

    def __init__(self, coefficients, omega):
        self.coefficients, self.omega = coefficients, omega

    def force(self, t, eta, nu):
        return np.real(self.coefficients.T @ np.exp(1j * self.omega * t))


@pytest.fixture(scope="module")
def wave_runs(s175, s175_model):
    sea = irregular_waves(
        wave_spectrum("jonswap", 2.0, 2 * np.pi / 0.6),
        duration=600,
        n_components=100,
        direction=np.radians(-135),
        seed=1,
    )
    load = _Waves(excitation_coefficients(s175, sea, extrapolate="zero"), sea.omega)
    linear_kinematics = dataclasses.replace(s175_model, kinematics="linear")
    runs = {
        "nonlinear": simulate_unified(s175_model, duration=600, dt=0.1, loads=[load]),
        "linear": simulate_unified(linear_kinematics, duration=600, dt=0.1, loads=[load]),
    }
    t = runs["linear"].time.values
    force = np.stack([load.force(tk, None, None) for tk in t])
    runs["cummins"] = simulate(s175_model.vessel, t, force)
    return runs


def test_without_nonlinear_terms_it_is_the_linear_cummins_simulator(wave_runs):
    """Acceptance: kinematics linearised, no Coriolis, linear loads: the unified model
    (Runge–Kutta) equals the linear simulator (exact discretisation) to < 1 % RMS in every
    DOF (measured: < 0.06 %)."""
    a = wave_runs["linear"].eta.values
    b = wave_runs["cummins"].motion.values
    error = np.sqrt(np.mean((a - b) ** 2, axis=0) / np.mean(b**2, axis=0))
    assert np.all(error < 0.01), error
    np.testing.assert_allclose(
        wave_runs["linear"].memory_force.values,
        wave_runs["cummins"].memory_force.values,
        atol=0.01 * np.abs(wave_runs["cummins"].memory_force.values).max(),
    )


def test_nonlinear_kinematics_small_motions(wave_runs):
    """With J(Θ): heave, roll, pitch still within 1 % of the linear simulator; the
    horizontal drift that appears is the second-order kinematics ((J(Θ) − I)ν, e.g.
    ⟨θ ẇ⟩ moves the ship north) integrated along the linear run."""
    nl = wave_runs["nonlinear"].eta.values
    lin = wave_runs["cummins"].motion.values
    for k in (2, 3, 4):
        assert np.sqrt(np.mean((nl[:, k] - lin[:, k]) ** 2) / np.mean(lin[:, k] ** 2)) < 0.01
    nu = wave_runs["cummins"].velocity.values
    extra = np.stack(
        [(velocity_transform(e) - np.eye(6)) @ n for e, n in zip(lin, nu, strict=True)]
    )
    predicted = np.cumsum(extra, axis=0) * 0.1
    for k in (0, 1, 5):
        diff = nl[:, k] - lin[:, k]
        assert np.sqrt(np.mean((diff - predicted[:, k]) ** 2) / np.mean(diff**2)) < 0.05


def test_unified_model_checks(s175_model):
    with pytest.raises(SimulationError, match="kinematics"):
        dataclasses.replace(s175_model, kinematics="quadratic")
    vessel = s175_model.vessel
    z_up = dataclasses.replace(vessel, attrs={**vessel.attrs, "axis_convention": "z-up"})
    with pytest.raises(SimulationError, match="z down"):
        UnifiedVessel(z_up)

    class Bad:
        name = "bad"

        def force(self, t, eta, nu):
            return np.full(6, np.nan) if t > 1 else np.zeros(6)

    with pytest.raises(SimulationError, match="load 'bad'"):
        simulate_unified(s175_model, duration=5, dt=0.5, loads=[Bad()])


def test_screw_transform_moves_the_origin(s175, s175_model):
    """The data's reference point W 10 m forward of the body origin O: the mass about O
    is H(r_w)ᵀ M H(r_w) (eq. 38a), still symmetric."""
    r_w = np.array([10.0, 0.0, 0.0])
    moved = dataclasses.replace(s175_model, r_w=r_w)
    h = screw_transform(r_w)
    np.testing.assert_allclose(moved.mass, h.T @ s175_model.mass @ h)
    np.testing.assert_allclose(moved.mass, moved.mass.T, atol=1e-6 * np.abs(moved.mass).max())
