"""The nonlinear 6-DOF vessel model of the Marine Systems Simulator (Smogeli et al. (2004) eq. 56).

The "unified" model of Smogeli et al. (2004) keeps the kinematics between the
Earth-fixed north-east-down frame (n) and the body (b) nonlinear and the hydrodynamics
linear, the fluid memory a state-space model, and adds every other force by
superposition:

    η̇ = J(Θ) ν                                                           (eq. 9)
    M ν̇ = −D ν_r − J*ᵀ C_r χ − g(η) − C_RB(ν) ν + Σ τ_load + τ_P            (eq. 56)
    χ̇ = A_r χ + B_r J* ν_r                                               (eq. 36, 39c)

with η = (N, E, D, φ, θ, ψ), ν = (u, v, w, p, q, r), ν_r = ν − (v_c^b, 0) the velocity
relative to the current (eqs. 40, 49), J(Θ) = diag(R_b^n, T_Θ) (eqs. 6–10) and
J* = H(r_w) (eqs. 15, 22c) the screw transform from the body origin O to the origin W of
the hydrodynamic data (the seakeeping h-frame). Following eq. 38,

    M = M_RB + J*ᵀ A∞ J*,   D = J*ᵀ B_v J*,   g(η) = J*ᵀ G J* η̃,

with M_RB, A∞, B_v (the constant viscous damping) and G (hydrostatic plus mooring
stiffness) as the data give them about W, and η̃ = (N, E, D, φ, θ, ψ − ψ₀) (the restoring
acts on heave, roll and pitch; assumption A1: small roll and pitch for the h-frame
transforms, not for the kinematics). C_RB(ν)ν, the rigid-body Coriolis and centripetal
force (Fossen 2011, Thm. 3.2), is neglected by Smogeli et al. (2004) (assumption A2, low
speed) and optional here. τ_load are the loads of :mod:`cummins.timedomain.loads` (first-order and
drift wave forces, current drag, wind, point loads), each a small object with
``force(t, η, ν)`` returning a b-frame generalized force about O; τ_P the thrust of a
controller (:mod:`cummins.timedomain.dp`), sampled once per time step.

The data must be in Fossen's body axes (x forward, y starboard, z down): use
:func:`cummins.change_axes` (``"z-down"``) on WAMIT/VERES data (:func:`unified_vessel`
does it).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import SimulationError
from cummins.kinematics import screw_transform, skew, velocity_transform
from cummins.validation import check_simulation_size
from cummins.vessel import Vessel

#: Labels of the pose η (n-frame) and of the body velocity ν.
POSE = ("North", "East", "Down", "Roll", "Pitch", "Yaw")
VELOCITY = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
_STEPS_PER_REPORT = 500


def coriolis_rigid_body(m_rb: NDArray, nu: NDArray) -> NDArray[np.float64]:
    """C_RB(ν)ν from the rigid-body inertia matrix (Fossen 2011, Thm. 3.2):
    C_RB = [[0, −S(M₁₁ν₁ + M₁₂ν₂)], [−S(M₁₁ν₁ + M₁₂ν₂), −S(M₂₁ν₁ + M₂₂ν₂)]]."""
    v1, v2 = nu[:3], nu[3:]
    a = m_rb[:3, :3] @ v1 + m_rb[:3, 3:] @ v2
    b = m_rb[3:, :3] @ v1 + m_rb[3:, 3:] @ v2
    return np.concatenate([-skew(a) @ v2, -skew(a) @ v1 - skew(b) @ v2])


@dataclass(frozen=True, eq=False)
class UnifiedVessel:
    """The vessel of Smogeli et al. (2004) eq. 56, built on the linear
    :class:`cummins.vessel.Vessel`.

    Attributes
    ----------
    vessel
        The linear model about W in Fossen's axes (M_RB, A∞, B_v, G, radiation model).
    r_w
        From the body origin O to W, m, b-frame (0: O is the data's reference point).
    coriolis
        Include the rigid-body Coriolis and centripetal force C_RB(ν)ν.
    current
        A :class:`cummins.timedomain.loads.Current` (its velocity enters ν_r), or None.
    yaw0
        ψ₀, rad: the heading about which a yaw stiffness (mooring) acts.
    kinematics
        ``"nonlinear"`` (default): η̇ = J(Θ)ν; ``"linear"``: η̇ = ν, which with
        ``coriolis=False`` and linear loads makes the model the linear Cummins equation
        of :mod:`cummins.timedomain.simulate` (a check, and for small motions a close one).
    """

    vessel: Vessel
    r_w: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    coriolis: bool = False
    current: Any = None
    yaw0: float = 0.0
    kinematics: str = "nonlinear"

    def __post_init__(self) -> None:
        if len(self.vessel.dofs) != 6:
            raise SimulationError(
                f"the unified model needs the 6 rigid-body DOFs, the vessel has {self.vessel.dofs}"
            )
        if str(self.vessel.attrs.get("axis_convention", "z-down")) != "z-down":
            raise SimulationError(
                "the vessel is not in Fossen's axes (x forward, y starboard, z down)",
                hint="build it with cummins.timedomain.unified.unified_vessel, which converts "
                "the data",
            )
        if self.kinematics not in ("nonlinear", "linear"):
            raise SimulationError(
                f"kinematics must be 'nonlinear' or 'linear', not {self.kinematics!r}"
            )
        j = screw_transform(self.r_w)
        object.__setattr__(self, "r_w", np.asarray(self.r_w, dtype=float).reshape(3))
        object.__setattr__(self, "_j", j)
        m_rb = j.T @ self.vessel.rigid_body_mass @ j
        mass = m_rb + j.T @ self.vessel.added_mass_inf @ j
        object.__setattr__(self, "_m_rb", m_rb)
        object.__setattr__(self, "_mass", mass)
        object.__setattr__(self, "_mass_inv", np.linalg.inv(mass))
        object.__setattr__(self, "_damping", j.T @ self.vessel.viscous_damping @ j)
        object.__setattr__(self, "_restoring", j.T @ self.vessel.stiffness @ j)
        rad = self.vessel.radiation
        object.__setattr__(self, "_ar", rad.A if rad.total_order else np.zeros((0, 0)))
        object.__setattr__(self, "_br", (rad.B @ j) if rad.total_order else np.zeros((0, 6)))
        object.__setattr__(self, "_cr", (j.T @ rad.C) if rad.total_order else np.zeros((6, 0)))

    @property
    def j_star(self) -> NDArray[np.float64]:
        """J* = H(r_w) (eq. 22c)."""
        return self._j

    @property
    def mass(self) -> NDArray[np.float64]:
        """M = M_RB + J*ᵀA∞J* about O (eq. 38a)."""
        return self._mass

    @property
    def damping(self) -> NDArray[np.float64]:
        """D = J*ᵀ B_v J* (eq. 38b)."""
        return self._damping

    @property
    def restoring(self) -> NDArray[np.float64]:
        """G about O, g(η) = G η̃ (eq. 38d, linear)."""
        return self._restoring

    @property
    def n_states(self) -> int:
        """12 + the order of the radiation model."""
        return 12 + self._ar.shape[0]

    def relative_velocity(self, eta: NDArray, nu: NDArray) -> NDArray[np.float64]:
        """ν_r = ν − (v_c^b, 0) (eq. 49)."""
        if self.current is None:
            return nu
        return self.current.relative_velocity(eta, nu)

    def restoring_force(self, eta: NDArray) -> NDArray[np.float64]:
        """g(η) = G η̃, η̃ = (N, E, D, φ, θ, ψ − ψ₀) wrapped in yaw."""
        e = np.array(eta, dtype=float)
        e[5] = (e[5] - self.yaw0 + np.pi) % (2 * np.pi) - np.pi
        return self._restoring @ e

    def memory_force(self, chi: NDArray) -> NDArray[np.float64]:
        """μ = J*ᵀ C_r χ (eq. 38c), b-frame."""
        return self._cr @ chi

    def rates(
        self, t: float, x: NDArray, load: NDArray
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(ẋ, μ) of x = (η, ν, χ) under the total load τ (6,) (module docstring)."""
        eta, nu, chi = x[:6], x[6:12], x[12:]
        nu_r = self.relative_velocity(eta, nu)
        mu = self._cr @ chi
        force = load - self._damping @ nu_r - mu - self.restoring_force(eta)
        if self.coriolis:
            force = force - coriolis_rigid_body(self._m_rb, nu)
        out = np.empty_like(x)
        out[:6] = velocity_transform(eta) @ nu if self.kinematics == "nonlinear" else nu
        out[6:12] = self._mass_inv @ force
        out[12:] = self._ar @ chi + self._br @ nu_r
        return out, mu


def unified_vessel(
    ds: xr.Dataset,
    model=None,
    *,
    viscous_damping: Any = None,
    r_w: ArrayLike = (0.0, 0.0, 0.0),
    coriolis: bool = False,
    current: Any = None,
    kinematics: str = "nonlinear",
    **fit_options: Any,
) -> UnifiedVessel:
    """The :class:`UnifiedVessel` of a ``HydroDB`` (one speed) in Fossen's axes.

    The data are turned to z-down axes if needed (:func:`cummins.change_axes`), the
    radiation model fitted (or ``model``, which must be in the same axes), and the
    linear :class:`~cummins.vessel.Vessel` built by
    :func:`~cummins.vessel.vessel_from_hydrodb` (``viscous_damping`` and the data's
    constant additional damping in B_v).
    """
    from cummins.hydrodb import change_axes, single_speed
    from cummins.vessel import vessel_from_hydrodb

    ds = single_speed(ds)
    if str(ds.attrs.get("axis_convention", "z-up")) != "z-down":
        if model is not None:
            raise SimulationError(
                "the data are not in z-down axes: give the data only (the model is fitted "
                "in Fossen's axes), or a model fitted to cummins.change_axes(ds, 'z-down')"
            )
        ds = change_axes(ds, "z-down")
    vessel = vessel_from_hydrodb(ds, model, viscous_damping=viscous_damping, **fit_options)
    return UnifiedVessel(
        vessel, np.asarray(r_w, dtype=float), coriolis, current, kinematics=kinematics
    )


def _no_progress(fraction: float) -> None:
    return None


def simulate_unified(
    model: UnifiedVessel,
    *,
    duration: float,
    dt: float,
    loads: Sequence = (),
    slow_loads: Sequence = (),
    controller=None,
    initial_pose: ArrayLike | None = None,
    initial_state: ArrayLike | None = None,
    measurement_noise: ArrayLike | None = None,
    seed: int | None = None,
    progress: Callable[[float], None] | None = None,
) -> xr.Dataset:
    """Simulate the unified model (fixed-step 4th-order Runge–Kutta).

    Parameters
    ----------
    model
        The :class:`UnifiedVessel`.
    duration, dt
        Length and time step, s.
    loads
        Objects with ``name`` and ``force(t, eta, nu) -> (6,)`` (:mod:`cummins.timedomain.loads`),
        evaluated at every Runge–Kutta stage; each one's force at the steps is recorded.
    slow_loads
        Loads that vary slowly (drift, current drag, wind, a crane): evaluated once per
        step, at its start, and held over it, like a sampled control force — a quarter of
        the cost, an error of the order of Δt × their rate of change.
    controller
        An object with ``update(t, eta_measured) -> (6,)``
        (:class:`cummins.timedomain.dp.DPController`),
        called once per step; its thrust is held over the step (a sampled controller).
    initial_pose
        η(0) (6,), default 0 (at rest, memory empty).
    initial_state
        The whole state (η, ν, χ) instead (e.g. the stationary state of the linear model).
    measurement_noise
        Standard deviation of white noise on each measured pose component (6,), m, rad.
    seed
        Of the measurement noise.
    progress
        Called with the fraction done.

    Returns
    -------
    xarray.Dataset
        ``eta`` (time, dof: North … Yaw; m, rad, NED), ``nu`` (time, velocity: Surge …
        Yaw; m/s, rad/s, body), ``memory_force`` (time, velocity), one variable
        ``force_<name>`` per load and ``thrust`` (commanded by the controller), all
        b-frame generalized forces about O (N, N·m).

    Raises
    ------
    SimulationError
        A state that is not finite or exceeds physical bounds (naming the DOF and the
        time), a load that does not return 6 finite values.
    """
    # the states and, per step, η, ν and the force of every load (6 each)
    check_simulation_size(duration, dt, model.n_states, 6 * (4 + len(loads) + len(slow_loads)))
    duration, dt = float(duration), float(dt)
    t = np.arange(0.0, duration + 0.5 * dt, dt)
    ns = model.n_states
    if initial_state is not None:
        x = np.asarray(initial_state, dtype=float).reshape(ns).copy()
    else:
        x = np.zeros(ns)
        if initial_pose is not None:
            x[:6] = np.asarray(initial_pose, dtype=float).reshape(6)
    fast = len(loads)
    loads = [*loads, *slow_loads]
    names = [str(getattr(load, "name", type(load).__name__)) for load in loads]
    if len(set(names)) != len(names):
        raise SimulationError(f"two loads have the same name: {names}")
    rng = np.random.default_rng(seed)
    noise = None if measurement_noise is None else np.asarray(measurement_noise, float)
    report = progress or _no_progress
    out_x = np.empty((t.size, 12))
    out_mu = np.empty((t.size, 6))
    out_loads = np.zeros((len(loads), t.size, 6))
    out_thrust = np.zeros((t.size, 6))

    indexed = list(enumerate(loads))
    every_stage, once_a_step = indexed[:fast], indexed[fast:]

    def load_at(tk, xk, which, record=None):
        total = np.zeros(6)
        for k, load in which:
            f = np.asarray(load.force(tk, xk[:6], xk[6:12]), dtype=float)
            if f.shape != (6,) or not np.all(np.isfinite(f)):
                raise SimulationError(
                    f"load {names[k]!r} returned {f!r} at t = {tk:.6g} s: it must return "
                    "6 finite values (N, N m)"
                )
            if record is not None:
                out_loads[k, record] = f
            total += f
        return total

    thrust = np.zeros(6)
    for k in range(t.size):
        tk = t[k]
        if controller is not None:
            measured = x[:6] if noise is None else x[:6] + noise * rng.standard_normal(6)
            thrust = np.asarray(controller.update(tk, measured), dtype=float).reshape(6)
        out_thrust[k] = thrust
        held = thrust + load_at(tk, x, once_a_step, k)
        k1, mu = model.rates(tk, x, load_at(tk, x, every_stage, k) + held)
        out_x[k] = x[:12]
        out_mu[k] = mu
        if k == t.size - 1:
            break
        half = tk + 0.5 * dt
        x2 = x + 0.5 * dt * k1
        k2, _ = model.rates(half, x2, load_at(half, x2, every_stage) + held)
        x3 = x + 0.5 * dt * k2
        k3, _ = model.rates(half, x3, load_at(half, x3, every_stage) + held)
        x4 = x + dt * k3
        k4, _ = model.rates(tk + dt, x4, load_at(tk + dt, x4, every_stage) + held)
        x = x + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        if not np.all(np.isfinite(x[:12])) or abs(x[3]) > 1.2 or abs(x[4]) > 1.2:
            i = int(np.argmax(~np.isfinite(x[:12]) | (np.abs(x[:12]) > 1e9)))
            what = (POSE + VELOCITY)[i] if i < 12 else "state"
            if abs(x[3]) > 1.2 or abs(x[4]) > 1.2:
                what = "Roll" if abs(x[3]) > 1.2 else "Pitch"
            raise SimulationError(
                f"the simulation diverged: {what} at t = {t[k + 1]:.6g} s (roll or pitch "
                "beyond 70°, or not finite)",
                hint="check the loads (a wrong sign makes energy), the time step, and the "
                "controller gains",
            )
        if k % _STEPS_PER_REPORT == 0:
            report(k / (t.size - 1))
    report(1.0)
    return _result(t, out_x, out_mu, out_loads, names, out_thrust, controller)


def _result(t, x, mu, loads, names, thrust, controller) -> xr.Dataset:
    units_pose = ["m", "m", "m", "rad", "rad", "rad"]
    units_vel = ["m/s", "m/s", "m/s", "rad/s", "rad/s", "rad/s"]
    data = {
        "eta": (
            ("time", "dof"),
            x[:, :6],
            {"units": " | ".join(units_pose), "long_name": "pose in the north-east-down frame"},
        ),
        "nu": (
            ("time", "velocity"),
            x[:, 6:],
            {"units": " | ".join(units_vel), "long_name": "body-fixed velocity"},
        ),
        "memory_force": (
            ("time", "velocity"),
            mu,
            {"units": "N | N m", "long_name": "fluid memory force"},
        ),
    }
    for k, name in enumerate(names):
        data[f"force_{name}"] = (("time", "velocity"), loads[k], {"units": "N | N m"})
    if controller is not None:
        data["thrust"] = (
            ("time", "velocity"),
            thrust,
            {"units": "N | N m", "long_name": "thrust of the controller"},
        )
    ds = xr.Dataset(
        data,
        coords={"time": ("time", t, {"units": "s"}), "dof": list(POSE), "velocity": list(VELOCITY)},
        attrs={
            "method": "unified model (Smogeli et al. (2004) eq. 56), Runge-Kutta 4",
            "dt": float(t[1] - t[0]),
            "loads": ", ".join(names),
        },
    )
    return ds
