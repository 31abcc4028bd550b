"""The DP controller example: wave filter, nonlinear PID, thrust allocation
(cummins.timedomain.dp)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from cummins.errors import CumminsError, SimulationError
from cummins.kinematics import point_load
from cummins.timedomain.dp import (
    DPConfigError,
    DPController,
    DPGains,
    Thrusters,
    WaveFilter,
    rotation_3dof,
    wrap_angle,
)

# An S-175-like container ship at low speed: m = 2.5e7 kg, LF inertia M = M_RB + A(0)
# (surge, sway, yaw) and linear damping with time constants of 100–150 s.
MASS = np.diag([2.7e7, 4.0e7, 6.0e10])
DAMPING = np.diag([2.7e7 / 150.0, 4.0e7 / 100.0, 6.0e10 / 100.0])
LENGTH = 175.0


def simulate(controller, duration, dt, tau_env=(0.0, 0.0, 0.0), wave=None, eta0=None, events=()):
    """Integrate M ν̇ + D ν = τ_env + τ_thrust, η̇ = R(ψ)ν (RK4, zero-order hold of the
    controller output). ``wave(t)`` adds wave-frequency motion to the measurement;
    ``events`` are (time, setpoint) changes. Returns t, η (true), τ (surge, sway, yaw) and
    whether a thruster saturated, per step."""
    tau_env = np.asarray(tau_env, dtype=float)
    eta = np.zeros(3) if eta0 is None else np.asarray(eta0, dtype=float).copy()
    nu = np.zeros(3)
    n = round(duration / dt)
    t = np.arange(n + 1) * dt
    etas, taus, saturated = np.zeros((n + 1, 3)), np.zeros((n + 1, 3)), np.zeros(n + 1, bool)
    pending = sorted(events, key=lambda e: e[0])

    def rate(eta, nu, tau):
        return rotation_3dof(eta[2]) @ nu, np.linalg.solve(MASS, tau + tau_env - DAMPING @ nu)

    for k in range(n + 1):
        while pending and pending[0][0] <= t[k] + 1e-9:
            controller.set_setpoint(pending.pop(0)[1])
        meas = eta + (0.0 if wave is None else wave(t[k]))
        tau = controller.update(t[k], [meas[0], meas[1], 0.0, 0.0, 0.0, meas[2]])[[0, 1, 5]]
        etas[k], taus[k], saturated[k] = eta, tau, controller.saturated
        if k == n:
            break
        k1 = rate(eta, nu, tau)
        k2 = rate(eta + 0.5 * dt * k1[0], nu + 0.5 * dt * k1[1], tau)
        k3 = rate(eta + 0.5 * dt * k2[0], nu + 0.5 * dt * k2[1], tau)
        k4 = rate(eta + dt * k3[0], nu + dt * k3[1], tau)
        eta = eta + dt / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        nu = nu + dt / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
    return t, etas, taus, saturated


def amplitude_at(t, x, omega):
    """Fourier amplitude of x(t) at omega over a whole number of periods at the end."""
    period = 2 * np.pi / omega
    dt = t[1] - t[0]
    n = int(np.floor((t[-1] - t[0]) / period) * period / dt)
    tt, xx = t[-n:], x[-n:]
    return 2.0 * abs(np.mean((xx - xx.mean()) * np.exp(-1j * omega * tt)))


@pytest.fixture(scope="module")
def gains():
    return DPGains.from_vessel(MASS, DAMPING, bandwidth=0.05, relative_damping=0.9)


# --------------------------------------------------------------------------- closed loop


def test_holds_position_against_constant_environmental_force():
    """200 kN at 30° plus 5 MN·m: the vessel is pushed off, then the integral brings it
    back to the setpoint, and the thrusters end up cancelling the environment."""
    gains = DPGains.from_vessel(MASS, DAMPING, integral_limit=(1e6, 1e6, 1e8))
    thrusters = Thrusters.typical(LENGTH, 8e5, depth=5.0)
    ctrl = DPController(gains, thrusters, setpoint=(0.0, 0.0, 0.0))
    direction = np.radians(30.0)
    env = np.array([2e5 * np.cos(direction), 2e5 * np.sin(direction), 5e6])
    _, eta, tau, _ = simulate(ctrl, 1500.0, 1.0, tau_env=env)
    assert np.max(np.hypot(eta[:, 0], eta[:, 1])) > 0.5  # it was pushed off
    assert np.max(np.hypot(eta[:, 0], eta[:, 1])) < 5.0  # but not far
    assert np.hypot(*eta[-1, :2]) < 0.1
    assert abs(np.degrees(eta[-1, 2])) < 0.1
    np.testing.assert_allclose(tau[-1], -env, rtol=1e-2, atol=1e-3 * np.abs(env).max())
    state = ctrl.state_dict()
    assert not state["saturated"]
    # thrusters below O produce roll and pitch moments: τ = Σ point_load(f_i, r_i)
    expected = sum(
        point_load([fx, fy, 0.0], r)
        for (fx, fy), r in zip(state["thruster_forces"], thrusters.positions, strict=True)
    )
    np.testing.assert_allclose(state["tau_delivered"], expected, rtol=1e-9, atol=1e-6)
    assert abs(state["tau_delivered"][3]) > 1e4


@pytest.mark.parametrize(
    ("setpoint", "dof", "step"),
    [((5.0, 0.0, 0.0), 0, 5.0), ((0.0, 5.0, 0.0), 1, 5.0), ((0.0, 0.0, 0.1), 2, 0.1)],
)
def test_setpoint_change_is_reached_with_small_overshoot(gains, setpoint, dof, step):
    ctrl = DPController(gains, Thrusters.typical(LENGTH, 8e5), setpoint=(0.0, 0.0, 0.0))
    _, eta, _, _ = simulate(ctrl, 900.0, 1.0, events=[(100.0, setpoint)])
    response = eta[:, dof] / step
    assert np.all(np.abs(response[:100]) < 1e-9)  # nothing happens before the change
    assert np.max(response) < 1.2  # overshoot < 20 %
    assert np.max(response) > 0.95  # and it gets there
    assert abs(response[-1] - 1.0) < 0.02
    others = [i for i in range(3) if i != dof]
    assert np.max(np.abs(eta[:, others[0]])) < 0.05 * (1.0 if others[0] == 2 else 5.0)


def test_heading_setpoint_across_180_degrees_turns_the_short_way(gains):
    """Heading 179°, setpoint −179°: a 2° turn through 180°, not 358° the other way;
    the filter sees the measured heading jump from +π to −π and must not."""
    ctrl = DPController(gains, setpoint=(0.0, 0.0, np.radians(-179.0)))
    _, eta, tau, _ = simulate(ctrl, 600.0, 1.0, eta0=(0.0, 0.0, np.radians(179.0)))
    assert tau[0, 2] > 0.0  # starboard turn: increasing ψ
    assert np.degrees(np.max(eta[:, 2])) < 181.5  # the true heading, unwrapped
    assert np.degrees(np.min(eta[:, 2])) > 178.9
    assert abs(np.degrees(wrap_angle(eta[-1, 2] - np.radians(-179.0)))) < 0.05
    assert abs(np.degrees(ctrl.eta_lf[2]) + 179.0) < 0.05  # reported wrapped


def test_yaw_error_is_wrapped(gains):
    ctrl = DPController(gains, setpoint=(0.0, 0.0, np.radians(179.0)))
    tau = ctrl.update(0.0, [0.0, 0.0, 0.0, 0.0, 0.0, np.radians(-179.0)])
    assert np.degrees(ctrl.error[2]) == pytest.approx(2.0)
    assert tau[5] == pytest.approx(-gains.kp[2, 2] * np.radians(2.0))
    assert wrap_angle(-np.pi) == np.pi
    assert wrap_angle(np.pi) == np.pi
    np.testing.assert_allclose(wrap_angle([3 * np.pi / 2, -3 * np.pi / 2]), [-np.pi / 2, np.pi / 2])


def test_wave_filter_attenuates_wave_frequency_thrust_tenfold(gains):
    """1 m of surge motion at 0.6 rad/s in the measurement: the thrust's content at
    0.6 rad/s is ≥ 10 times smaller with the wave filter than without it."""

    def wave(t):
        return np.array([np.sin(0.6 * t), 0.5 * np.cos(0.6 * t), np.radians(1.0) * np.sin(0.6 * t)])

    amplitudes = {}
    for label, wave_filter in (("filtered", WaveFilter()), ("raw", None)):
        ctrl = DPController(gains, wave_filter=wave_filter, setpoint=(0.0, 0.0, 0.0))
        t, _, tau, _ = simulate(ctrl, 400.0, 0.5, wave=wave)
        amplitudes[label] = [amplitude_at(t[300:], tau[300:, i], 0.6) for i in range(3)]
    raw, filtered = np.array(amplitudes["raw"]), np.array(amplitudes["filtered"])
    assert raw[0] > 0.5 * gains.kd[0, 0] * 0.6  # without the filter it chases the waves
    assert np.all(raw / filtered >= 10.0), raw / filtered


def test_holds_position_in_a_seaway_with_measurement_noise():
    """Environmental force, wave motion at three frequencies and white position noise:
    with the wave filter the thrusters stay unsaturated and the vessel within 0.5 m and
    0.3°; without it the controller chases the waves into saturation."""
    rng = np.random.default_rng(1)
    noise = rng.normal(size=(2401, 3)) * [0.3, 0.3, np.radians(0.2)]
    phases = rng.uniform(0.0, 2 * np.pi, size=3)
    amplitude = np.array([0.5, 0.35, np.radians(0.5)])

    def wave(t):
        motion = sum(np.sin(w * t + p) for w, p in zip((0.45, 0.6, 0.8), phases, strict=True))
        return amplitude * motion + noise[round(t / 0.5)]

    gains = DPGains.from_vessel(MASS, DAMPING, integral_limit=(1e6, 1e6, 1e8))
    env = np.array([1.5e5, 1.0e5, 3.0e6])
    results = {}
    for label, wave_filter in (("filtered", WaveFilter()), ("raw", None)):
        ctrl = DPController(gains, Thrusters.typical(LENGTH, 8e5), wave_filter, (0.0, 0.0, 0.0))
        _, eta, _, saturated = simulate(ctrl, 1200.0, 0.5, tau_env=env, wave=wave)
        results[label] = (eta[1200:], np.mean(saturated[1200:]))
    eta, saturated = results["filtered"]
    assert np.max(np.hypot(eta[:, 0], eta[:, 1])) < 0.5
    assert np.degrees(np.max(np.abs(eta[:, 2]))) < 0.3
    assert saturated == 0.0
    eta_raw, saturated_raw = results["raw"]
    assert saturated_raw > 0.5
    assert np.max(np.hypot(eta_raw[:, 0], eta_raw[:, 1])) > 1.0


def test_wave_filter_is_a_unit_gain_low_pass_exactly_discretised():
    wf = WaveFilter(cutoff=0.2, order=3)
    assert wf.gain(0.0) == pytest.approx(1.0)
    assert wf.gain(0.2) == pytest.approx(1 / np.sqrt(2))
    assert wf.gain(0.6) == pytest.approx(1 / np.sqrt(1 + 3.0**6))
    a, _ = wf.continuous()
    ad, bd = wf.discrete(0.7)
    np.testing.assert_allclose(ad, scipy.linalg.expm(a * 0.7), rtol=1e-12)
    # two half steps equal one whole step for a held input (exact discretisation)
    ah, bh = wf.discrete(0.35)
    np.testing.assert_allclose(ah @ ah, ad, rtol=1e-12)
    np.testing.assert_allclose(ah @ bh + bh, bd, rtol=1e-12)
    # a constant input is a fixed point: the filter has unit DC gain
    x = np.array([1.0, 0.0, 0.0])
    np.testing.assert_allclose(ad @ x + bd * 1.0, x, atol=1e-12)


def test_velocity_estimate_tracks_a_slow_drift(gains):
    """A vessel drifting at 0.2 m/s north, heading 90° (bow east): the estimated body
    velocity is sway −0.2 m/s (to port) once the filter has settled."""
    ctrl = DPController(gains, setpoint=(0.0, 0.0, np.pi / 2))
    for k in range(400):
        ctrl.update(0.5 * k, [0.1 * k, 0.0, 0.0, 0.0, 0.0, np.pi / 2])
    np.testing.assert_allclose(ctrl.nu_lf, [0.0, -0.2, 0.0], atol=1e-6)


# --------------------------------------------------------------------------- gains


def test_gains_from_vessel_place_the_closed_loop_poles():
    """Linearised at ψ = 0 with coupled M and D: the poles of
    M ë + (D + K_d) ė + K_p e + K_i ∫e = 0 are three pairs with ω_n and ζ as asked and
    three real integral poles at −0.1 ω_n."""
    mass = MASS.copy()
    mass[1, 2] = mass[2, 1] = 3.0e8  # sway–yaw coupling, kg·m
    damping = DAMPING.copy()
    damping[1, 2] = damping[2, 1] = 1.0e6
    wn, zeta = 0.06, 0.85
    g = DPGains.from_vessel(mass, damping, bandwidth=wn, relative_damping=zeta)
    minv = np.linalg.inv(mass)
    z, eye = np.zeros((3, 3)), np.eye(3)
    # state (∫e, e, ν), ė = ν
    a = np.block(
        [
            [z, eye, z],
            [z, z, eye],
            [-minv @ g.ki, -minv @ g.kp, -minv @ (damping + g.kd)],
        ]
    )
    poles = np.linalg.eigvals(a)
    pairs = poles[np.abs(poles.imag) > 1e-9]
    real = poles[np.abs(poles.imag) <= 1e-9]
    assert len(pairs) == 6
    np.testing.assert_allclose(np.abs(pairs), wn, rtol=1e-6)
    np.testing.assert_allclose(-pairs.real / np.abs(pairs), zeta, rtol=1e-6)
    np.testing.assert_allclose(real, -0.1 * wn, rtol=1e-5)
    assert np.all(np.linalg.eigvalsh(0.5 * (g.kd + g.kd.T)) >= 0.0)


def test_gains_from_vessel_never_give_negative_derivative_gain():
    g = DPGains.from_vessel(MASS, 10.0 * MASS, bandwidth=0.05)  # time constant 0.1 s
    assert np.all(np.linalg.eigvalsh(g.kd) >= -1e-9 * np.abs(g.kd).max())
    np.testing.assert_allclose(g.kd, 0.0, atol=1e-6 * np.abs(MASS).max())


def test_integral_force_is_clamped(gains):
    limit = np.array([2e4, 2e4, 1e6])
    g = DPGains(gains.kp, gains.kd, gains.ki, integral_limit=limit)
    ctrl = DPController(g, setpoint=(0.0, 0.0, 0.0))
    for k in range(2000):  # a large constant offset the controller cannot move
        ctrl.update(float(k), [20.0, -20.0, 0.0, 0.0, 0.0, 0.3])
        force = np.abs(g.ki @ (rotation_3dof(ctrl.eta_lf[2]).T @ ctrl.integral))
        assert np.all(force <= limit * (1 + 1e-12))
    assert np.max(force / limit) == pytest.approx(1.0)


def test_integral_does_not_wind_up_while_thrusters_saturate(gains):
    """A force far beyond the thrusters' capacity: while they saturate, no component
    of the integral grows in magnitude."""
    ctrl = DPController(gains, Thrusters.typical(LENGTH, 2e4), setpoint=(0.0, 0.0, 0.0))
    previous, was_saturated, grew = None, False, []
    for k in range(300):
        ctrl.update(float(k), [0.02 * k, 0.01 * k, 0.0, 0.0, 0.0, 1e-4 * k])
        if previous is not None and was_saturated:
            grew.append(np.any(np.abs(ctrl.integral) > np.abs(previous) + 1e-15))
        previous, was_saturated = ctrl.integral.copy(), ctrl.saturated
    assert len(grew) > 100  # it did saturate
    assert not any(grew)


# --------------------------------------------------------------------------- allocation


@pytest.fixture(scope="module")
def layout():
    return Thrusters(
        positions=[[70.0, 0.0, 4.0], [60.0, 0.0, 4.0], [-80.0, -6.0, 6.0], [-80.0, 6.0, 6.0]],
        kinds=("tunnel", "tunnel", "azimuth", "azimuth"),
        max_thrust=[3e5, 3e5, 6e5, 6e5],
        weights=[1.0, 2.0, 1.0, 1.5],
    )


def test_allocation_is_exact_for_a_feasible_force(layout):
    tau = np.array([1.5e5, -2.0e5, 8.0e6])
    result = layout.allocate(tau)
    assert not np.any(result.saturated)
    np.testing.assert_allclose(result.delivered[[0, 1, 5]], tau, rtol=1e-9)
    assert result.delivered[2] == 0.0
    b = layout.configuration_matrix()
    f = np.concatenate(
        [[result.forces[0, 1], result.forces[1, 1]], result.forces[2], result.forces[3]]
    )
    np.testing.assert_allclose(b @ f, tau, rtol=1e-9)
    # tunnels give only sway, the 6-DOF force is the sum of the thruster point loads
    assert np.all(result.forces[:2, 0] == 0.0)
    expected = sum(
        point_load([fx, fy, 0.0], r)
        for (fx, fy), r in zip(result.forces, layout.positions, strict=True)
    )
    np.testing.assert_allclose(result.delivered, expected, rtol=1e-9, atol=1e-6)
    # a 6-vector is accepted (heave, roll, pitch ignored)
    other = layout.allocate([tau[0], tau[1], 1e9, 1e9, 1e9, tau[2]])
    np.testing.assert_allclose(other.forces, result.forces)


def test_allocation_has_the_least_weighted_norm(layout):
    tau = np.array([1.0e5, 5.0e4, -3.0e6])
    b = layout.configuration_matrix()
    w = layout.weight_matrix()
    result = layout.allocate(tau)
    f = np.concatenate([result.unsaturated[:2, 1], result.unsaturated[2], result.unsaturated[3]])
    null = scipy.linalg.null_space(b)
    assert null.shape[1] == 3
    rng = np.random.default_rng(7)
    for _ in range(20):
        g = f + null @ rng.normal(scale=1e5, size=null.shape[1])
        np.testing.assert_allclose(b @ g, tau, rtol=1e-9, atol=1e-6)  # also exact
        assert g @ w @ g > f @ w @ f
    # and it is the weighted least-norm solution: W f lies in the range of Bᵀ
    assert np.allclose(null.T @ (w @ f), 0.0, atol=1e-9 * np.linalg.norm(w @ f))


def test_saturation_is_respected_and_azimuths_keep_their_direction(layout):
    tau = np.array([2.0e6, 1.5e6, -1.0e8])  # far beyond capacity
    result = layout.allocate(tau)
    assert np.all(result.thrust <= layout.max_thrust * (1 + 1e-12))
    assert np.any(result.saturated)
    for i in (2, 3):  # azimuth pairs scaled together: same angle before and after
        before = np.arctan2(result.unsaturated[i, 1], result.unsaturated[i, 0])
        assert result.azimuth_angle[i] == pytest.approx(before)
        if result.saturated[i]:
            assert result.thrust[i] == pytest.approx(layout.max_thrust[i])
    np.testing.assert_array_less(np.abs(result.delivered[[0, 1, 5]]), np.abs(tau))


def test_typical_layout_and_bad_layouts_are_rejected():
    t = Thrusters.typical(LENGTH, 5e5)
    assert t.count == 4
    assert t.configuration_matrix().shape == (3, 6)
    assert t.configuration_matrix(full=True).shape == (6, 6)
    with pytest.raises(DPConfigError, match="yaw"):  # two tunnels at the same x, one main
        Thrusters([[50.0, 0.0], [50.0, 0.0], [-80.0, 0.0]], ("tunnel", "tunnel", "main"), 1e5)
    with pytest.raises(DPConfigError, match="surge"):
        Thrusters([[50.0, 0.0], [-50.0, 0.0]], ("tunnel", "tunnel"), 1e5)
    with pytest.raises(DPConfigError, match="unknown kind"):
        Thrusters([[50.0, 0.0]], ("bow",), 1e5)
    with pytest.raises(DPConfigError, match="max_thrust"):
        Thrusters([[50.0, 0.0], [-50.0, 0.0]], ("azimuth", "azimuth"), [1e5, 0.0])
    with pytest.raises(DPConfigError, match="weights"):
        Thrusters([[50.0, 0.0], [-50.0, 0.0]], ("azimuth", "azimuth"), 1e5, weights=[1, -1])
    with pytest.raises(DPConfigError, match="shape"):
        Thrusters(np.zeros((2, 4)), ("azimuth", "azimuth"), 1e5)


# --------------------------------------------------------------------------- settings, state


def test_bad_gains_and_filters_raise(gains):
    with pytest.raises(DPConfigError, match="kp"):
        DPGains(kp=[-1.0, 1.0, 1.0], kd=[1.0, 1.0, 1.0], ki=[0.0, 0.0, 0.0])
    with pytest.raises(DPConfigError, match="kd"):
        DPGains(kp=np.eye(3), kd=[[1.0, 3.0, 0.0], [3.0, 1.0, 0.0], [0.0, 0.0, 1.0]], ki=0.0)
    with pytest.raises(DPConfigError, match="integral_limit"):
        DPGains(gains.kp, gains.kd, gains.ki, integral_limit=-1.0)
    with pytest.raises(DPConfigError, match="shape"):
        DPGains(kp=np.eye(2), kd=np.eye(3), ki=np.eye(3))
    with pytest.raises(DPConfigError, match="bandwidth"):
        DPGains.from_vessel(MASS, DAMPING, bandwidth=-0.05)
    with pytest.raises(DPConfigError, match="positive definite"):
        DPGains.from_vessel(-MASS, DAMPING)
    with pytest.raises(DPConfigError, match="order"):
        WaveFilter(order=0)
    with pytest.raises(DPConfigError, match="cutoff"):
        WaveFilter(cutoff=0.0)
    with pytest.raises(DPConfigError):
        DPController(gains, setpoint=(0.0, 0.0))
    assert issubclass(DPConfigError, CumminsError)
    assert issubclass(DPConfigError, ValueError)


def test_controller_time_and_measurement_errors(gains):
    ctrl = DPController(gains)
    first = ctrl.update(0.0, [1.0, 2.0, 0.0, 0.0, 0.0, 0.1])
    np.testing.assert_allclose(ctrl.setpoint, [1.0, 2.0, 0.1])  # holds the first pose
    np.testing.assert_allclose(first, 0.0, atol=1e-9)
    second = ctrl.update(1.0, [1.5, 2.0, 0.0, 0.0, 0.0, 0.1])
    np.testing.assert_array_equal(ctrl.update(1.0, [9.0, 9.0, 0, 0, 0, 1.0]), second)
    with pytest.raises(SimulationError, match="backwards"):
        ctrl.update(0.5, [1.0, 2.0, 0.0, 0.0, 0.0, 0.1])
    with pytest.raises(SimulationError, match="non-finite"):
        ctrl.update(2.0, [np.nan, 2.0, 0.0, 0.0, 0.0, 0.1])


def test_reset_and_state_dict(gains):
    thrusters = Thrusters.typical(LENGTH, 5e5)
    ctrl = DPController(gains, thrusters, setpoint=(0.0, 0.0, 0.0))
    poses = [[0.3 * k, -0.1 * k, 0.0, 0.01, 0.0, 0.002 * k] for k in range(30)]
    first = [ctrl.update(float(k), p) for k, p in enumerate(poses)]
    state = ctrl.state_dict()
    assert set(state) >= {
        "time",
        "tau_commanded",
        "tau_delivered",
        "eta_lf",
        "nu_lf",
        "error",
        "integral",
        "setpoint",
        "saturated",
        "thruster_forces",
    }
    assert state["time"] == 29.0
    assert state["thruster_forces"].shape == (4, 2)
    assert state["tau_commanded"].shape == state["tau_delivered"].shape == (6,)
    np.testing.assert_array_equal(state["tau_delivered"], first[-1])
    state["tau_delivered"][:] = 0.0  # a copy
    assert np.any(ctrl.tau_delivered != 0.0)
    ctrl.set_setpoint((1.0, 1.0, 4.0))
    ctrl.reset()
    np.testing.assert_array_equal(ctrl.setpoint, [0.0, 0.0, 0.0])
    again = [ctrl.update(float(k), p) for k, p in enumerate(poses)]
    np.testing.assert_array_equal(np.array(again), np.array(first))
