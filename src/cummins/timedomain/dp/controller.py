"""The nonlinear DP PID: its gains and the sampled controller.

:class:`DPGains` (with pole placement from the LF vessel model, :meth:`DPGains.from_vessel`)
and :class:`DPController`, which chains the wave filter, the PID
τ = −K_p Rᵀ(ψ̂) e − K_d ν̂ − K_i Rᵀ(ψ̂) ∫ e dt with anti-windup, and the thrust
allocation (Fossen (2021), PID control for dynamic positioning).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import SimulationError
from cummins.timedomain.dp.base import (
    DOF3,
    DPConfigError,
    _as_3x3,
    _check_psd,
    _pose3,
    rotation_3dof,
    wrap_angle,
)
from cummins.timedomain.dp.thrusters import Allocation, Thrusters
from cummins.timedomain.dp.wave_filter import WaveFilter


@dataclass(frozen=True, eq=False)
class DPGains:
    """Gains of the nonlinear DP PID controller (Fossen 2021, DP PID control).

    τ = −K_p Rᵀ(ψ̂) e − K_d ν̂ − K_i Rᵀ(ψ̂) z, ż = e, in (surge, sway, yaw).

    Parameters
    ----------
    kp
        Proportional gain, 3×3 (or its diagonal): N/m (surge, sway), N·m/rad (yaw).
    kd
        Derivative gain on the body velocity ν̂ = (u, v, r): N·s/m, N·m·s/rad.
    ki
        Integral gain: N/(m·s), N·m/(rad·s).
    integral_limit
        Anti-windup clamp: the largest magnitude of each component (surge N, sway N,
        yaw N·m) of the integral force K_i Rᵀ z; the integral state is scaled down (its
        direction kept) to respect all three. A scalar applies to all; ``inf`` (default)
        disables the clamp (conditional integration during thruster saturation remains).

    Raises
    ------
    DPConfigError
        For a gain that is not positive semi-definite (e.g. a negative diagonal), a wrong
        shape, or a negative integral limit.
    """

    kp: NDArray[np.float64]
    kd: NDArray[np.float64]
    ki: NDArray[np.float64]
    integral_limit: NDArray[np.float64] = field(default_factory=lambda: np.full(3, np.inf))

    def __post_init__(self) -> None:
        for name, unit in (("kp", "N/m, N·m/rad"), ("kd", "N·s/m, N·m·s/rad"), ("ki", "N/(m·s)")):
            a = _as_3x3(getattr(self, name), name)
            _check_psd(a, name, unit)
            a.setflags(write=False)
            object.__setattr__(self, name, a)
        lim = np.broadcast_to(np.asarray(self.integral_limit, dtype=float), (3,)).copy()
        if np.any(np.isnan(lim)) or np.any(lim < 0.0):
            raise DPConfigError(
                f"integral_limit must be ≥ 0 (N, N, N·m), got {lim.tolist()}",
                hint="use inf for no clamp",
            )
        lim.setflags(write=False)
        object.__setattr__(self, "integral_limit", lim)

    @classmethod
    def from_vessel(
        cls,
        mass: ArrayLike,
        damping: ArrayLike,
        bandwidth: float = 0.05,
        relative_damping: float = 0.9,
        integral_ratio: float = 0.1,
        integral_limit: ArrayLike = np.inf,
    ) -> DPGains:
        """Gains placing the linearised closed-loop LF poles (pole placement).

        For the LF model M ν̇ + D ν = τ linearised at ψ = 0 (η̇ = ν) with the PID above,
        the closed loop is M s³ + (D + K_d) s² + K_p s + K_i = 0 per DOF. Choosing

        K_p = M (ω_n² + 2ζω_n a),  K_d = M (2ζω_n + a) − D,  K_i = M a ω_n²,

        with a = ``integral_ratio`` · ω_n, factors it as
        M (s² + 2ζω_n s + ω_n²)(s + a): a complex pair with natural frequency ω_n and
        relative damping ζ and a slow real integral pole at −a — exactly, also for full
        (coupled) M and D. This is Fossen's (2021, DP PID tuning) choice K_p = M ω_n²,
        K_d = 2ζω_n M − D, K_i ≈ K_p ω_n/10, corrected so that the integral action does not
        move the pair. If the open-loop damping D already exceeds M(2ζω_n + a), K_d is
        clipped to zero in those directions (its symmetric part is projected on the
        positive semi-definite matrices) and the closed loop is more damped than asked.

        Parameters
        ----------
        mass
            LF inertia M = M_RB + A(ω→0) for surge, sway, yaw: 3×3, its diagonal, or a
            6×6 matrix (rows/columns 0, 1, 5 are used). kg, kg·m, kg·m².
        damping
            Linear LF damping D, same shapes. kg/s, kg·m/s, kg·m²/s.
        bandwidth
            ω_n, rad/s (0.03–0.1 rad/s is usual for DP: well below the wave frequencies).
        relative_damping
            ζ (0.7–1 recommended).
        integral_ratio
            a/ω_n: the integral pole relative to the bandwidth (0 disables integral action).
        integral_limit
            See the class parameters; N, N, N·m.

        Examples
        --------
        >>> g = DPGains.from_vessel(np.diag([1.0, 1.0, 1.0]), np.zeros(3), 0.1, 1.0, 0.0)
        >>> np.diag(g.kp).round(6).tolist(), np.diag(g.kd).round(6).tolist()
        ([0.01, 0.01, 0.01], [0.2, 0.2, 0.2])
        """
        m = _as_3x3(mass, "mass")
        d = _as_3x3(damping, "damping")
        if not (np.isfinite(bandwidth) and bandwidth > 0.0):
            raise DPConfigError(f"bandwidth must be > 0 rad/s, got {bandwidth}")
        if not (np.isfinite(relative_damping) and relative_damping > 0.0):
            raise DPConfigError(f"relative_damping must be > 0, got {relative_damping}")
        if not (np.isfinite(integral_ratio) and integral_ratio >= 0.0):
            raise DPConfigError(f"integral_ratio must be ≥ 0, got {integral_ratio}")
        if np.linalg.eigvalsh(0.5 * (m + m.T))[0] <= 0.0:
            raise DPConfigError(
                "mass is not positive definite", hint="pass M_RB + A(0) for surge, sway, yaw"
            )
        w, z = float(bandwidth), float(relative_damping)
        a = integral_ratio * w
        kp = m * (w**2 + 2.0 * z * w * a)
        kd = m * (2.0 * z * w + a) - d
        ki = m * (a * w**2)
        sym = 0.5 * (kd + kd.T)
        val, vec = np.linalg.eigh(sym)
        if val[0] < 0.0:  # too much open-loop damping: no negative derivative gain
            kd = (vec * np.clip(val, 0.0, None)) @ vec.T + 0.5 * (kd - kd.T)
        return cls(kp=kp, kd=kd, ki=ki, integral_limit=integral_limit)


class DPController:
    """Sampled DP controller: wave filter, nonlinear PID and thrust allocation.

    Call :meth:`update` once per time step with the measured pose; it returns the
    generalized thrust force to hold until the next call. Stateful (filter, integrator,
    last output); :meth:`reset` returns it to its initial state.

    Parameters
    ----------
    gains
        :class:`DPGains`.
    thrusters
        Optional :class:`Thrusters`; without them the commanded force is returned as is
        (ideal, unlimited actuators).
    wave_filter
        :class:`WaveFilter` settings (default ``WaveFilter()``), or ``None`` for no wave
        filtering: the controller then acts on the raw measurement and estimates the
        velocity by backward differences (for comparison only: it will chase the
        wave-frequency motion).
    setpoint
        Desired (N m, E m, ψ rad), or a 6-DOF pose; ``None`` holds the first measured
        position and heading.

    Attributes
    ----------
    tau_commanded
        The last PID output, 6-vector (N, N·m), b-frame.
    tau_delivered
        The last generalized force of the (saturated) thrusters; equals ``tau_commanded``
        without thrusters. This is what :meth:`update` returns.
    eta_lf
        Last filtered pose (N m, E m, ψ rad wrapped to (−π, π]).
    nu_lf
        Last estimated LF body velocity (u m/s, v m/s, r rad/s).
    error
        Last n-frame error (N − N_d, E − E_d, wrapped ψ − ψ_d).
    integral
        The integral state ∫ e dt (m·s, m·s, rad·s), n-frame.
    allocation
        The last :class:`Allocation`, or ``None``.

    Notes
    -----
    The measurement y_k at t_k is held over the interval (t_{k−1}, t_k] when propagating
    the filter (no extra sample delay); the integral is the rectangle sum Σ e_k Δt_k.
    Anti-windup: the integral force is clamped to ``gains.integral_limit`` and, while a
    thruster saturates, a component of the integral is not allowed to grow in magnitude.
    """

    def __init__(
        self,
        gains: DPGains,
        thrusters: Thrusters | None = None,
        wave_filter: WaveFilter | None = WaveFilter(),  # noqa: B008 (a frozen dataclass)
        setpoint: ArrayLike | None = None,
    ) -> None:
        if not isinstance(gains, DPGains):
            raise DPConfigError(f"gains must be DPGains, got {type(gains).__name__}")
        if thrusters is not None and not isinstance(thrusters, Thrusters):
            raise DPConfigError(f"thrusters must be Thrusters, got {type(thrusters).__name__}")
        if wave_filter is not None and not isinstance(wave_filter, WaveFilter):
            raise DPConfigError(
                f"wave_filter must be WaveFilter or None, got {type(wave_filter).__name__}"
            )
        self.gains = gains
        self.thrusters = thrusters
        self.wave_filter = wave_filter
        self._initial_setpoint = None if setpoint is None else _pose3(setpoint, "setpoint")
        if self._initial_setpoint is not None:
            self._initial_setpoint[2] = wrap_angle(self._initial_setpoint[2])
        self._discrete_cache: dict[float, tuple[NDArray, NDArray]] = {}
        self.reset()

    # ---- state

    def reset(self) -> None:
        """Forget all history: filter and integrator states, last outputs, time."""
        self.setpoint: NDArray[np.float64] | None = (
            None if self._initial_setpoint is None else self._initial_setpoint.copy()
        )
        self._t: float | None = None
        self._psi_raw = 0.0  # last measured heading (wrapped as given)
        self._y = np.zeros(3)  # last measurement with unwrapped heading
        order = 1 if self.wave_filter is None else int(self.wave_filter.order)
        self._x = np.zeros((3, order))  # filter states, per DOF (value, derivatives…)
        self.integral = np.zeros(3)
        self.error = np.zeros(3)
        self.eta_lf = np.zeros(3)
        self.nu_lf = np.zeros(3)
        self.tau_commanded = np.zeros(6)
        self.tau_delivered = np.zeros(6)
        self.allocation: Allocation | None = None

    def set_setpoint(self, setpoint: ArrayLike) -> None:
        """Change the desired (N m, E m, ψ rad) (or a 6-DOF pose); takes effect at the
        next :meth:`update`. The integral state is kept (it holds the environmental
        force estimate)."""
        self.setpoint = _pose3(setpoint, "setpoint")
        self.setpoint[2] = wrap_angle(self.setpoint[2])

    # ---- the step

    def update(self, t: float, eta: ArrayLike) -> NDArray[np.float64]:
        """One controller step at time ``t`` (s) with the measured pose ``eta``.

        Parameters
        ----------
        t
            Time, s; strictly increasing between calls (a repeated ``t`` returns the
            previous output unchanged).
        eta
            Measured pose (N, E, D, φ, θ, ψ) m, rad (or (N, E, ψ)), including wave motion
            and noise.

        Returns
        -------
        ndarray, shape (6,)
            The generalized thrust force in the b-frame about O (N, N·m): what the
            thrusters deliver after allocation and saturation (or the PID output without
            thrusters). Roll and pitch moments are non-zero only for thrusters with z ≠ 0.

        Raises
        ------
        SimulationError
            For a non-finite measurement or a time going backwards.
        """
        try:
            y = _pose3(eta, "measured pose")
        except DPConfigError as exc:
            raise SimulationError(f"DP controller at t = {t} s: {exc}") from None
        t = float(t)
        if not np.isfinite(t):
            raise SimulationError(f"DP controller: time must be finite, got {t}")
        if self._t is None:
            dt = 0.0
            psi_u = float(y[2])
            meas = np.array([y[0], y[1], psi_u])
            self._x[:] = 0.0
            self._x[:, 0] = meas  # start in steady state at the first measurement
            if self.setpoint is None:
                self.setpoint = np.array([y[0], y[1], wrap_angle(y[2])])
        else:
            dt = t - self._t
            if dt < 0.0:
                raise SimulationError(
                    f"DP controller: time went backwards from {self._t} s to {t} s",
                    hint="call reset() before restarting a simulation",
                )
            if dt == 0.0:
                return self.tau_delivered.copy()
            psi_u = self._y[2] + wrap_angle(y[2] - self._psi_raw)
            meas = np.array([y[0], y[1], psi_u])
            if self.wave_filter is None:
                self._x[:, 0] = meas
            else:
                ad, bd = self._discrete(dt)
                self._x = self._x @ ad.T + np.outer(meas, bd)
        if self.wave_filter is None:
            eta_hat = meas
            eta_dot = np.zeros(3) if dt == 0.0 else (meas - self._y) / dt
        else:
            eta_hat = self._x[:, 0].copy()
            eta_dot = self._x[:, 1].copy() if self._x.shape[1] > 1 else np.zeros(3)
            if self._x.shape[1] == 1 and dt > 0.0:  # first order: the state derivative
                eta_dot = self.wave_filter.cutoff * (meas - eta_hat)
        self._t, self._psi_raw, self._y = t, float(y[2]), meas

        rot = rotation_3dof(float(eta_hat[2]))
        e = eta_hat - self.setpoint
        e[2] = wrap_angle(e[2])
        if dt > 0.0:
            step = e * dt
            if self.allocation is not None and np.any(self.allocation.saturated):
                # conditional integration: do not let the integral grow while saturated
                step = np.where(self.integral * step > 0.0, 0.0, step)
            self.integral = self.integral + step
            self._clamp_integral(rot)
        nu = rot.T @ eta_dot
        g = self.gains
        tau3 = -g.kp @ (rot.T @ e) - g.kd @ nu - g.ki @ (rot.T @ self.integral)

        commanded = np.zeros(6)
        commanded[list(DOF3)] = tau3
        if self.thrusters is None:
            delivered = commanded.copy()
            self.allocation = None
        else:
            self.allocation = self.thrusters.allocate(tau3)
            delivered = self.allocation.delivered
        self.error = e
        self.eta_lf = np.array([eta_hat[0], eta_hat[1], wrap_angle(eta_hat[2])])
        self.nu_lf = nu
        self.tau_commanded = commanded
        self.tau_delivered = delivered
        return delivered.copy()

    def _discrete(self, dt: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        key = round(dt, 12)
        if key not in self._discrete_cache:
            if len(self._discrete_cache) > 64:  # many distinct steps: keep the cache small
                self._discrete_cache.clear()
            assert self.wave_filter is not None
            self._discrete_cache[key] = self.wave_filter.discrete(dt)
        return self._discrete_cache[key]

    def _clamp_integral(self, rot: NDArray[np.float64]) -> None:
        lim = self.gains.integral_limit
        if np.all(np.isinf(lim)):
            return
        force = np.abs(self.gains.ki @ (rot.T @ self.integral))
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(force > lim, lim / force, 1.0)
        self.integral = self.integral * float(np.min(ratio))

    # ---- output

    @property
    def thruster_forces(self) -> NDArray[np.float64] | None:
        """Last (fx, fy) of each thruster after saturation, shape (n, 2), N; or None."""
        return None if self.allocation is None else self.allocation.forces.copy()

    @property
    def saturated(self) -> bool:
        """Did any thruster saturate at the last step?"""
        return bool(self.allocation is not None and np.any(self.allocation.saturated))

    def state_dict(self) -> dict[str, Any]:
        """The last step's signals, for a simulator to store (copies).

        Keys: ``time`` (s), ``tau_commanded``, ``tau_delivered`` (6,) (N, N·m),
        ``eta_lf`` (N, E, ψ), ``nu_lf`` (u, v, r), ``error`` (3,), ``integral`` (3,),
        ``setpoint`` (3,), ``saturated`` (bool) and, with thrusters, ``thruster_forces``
        (n, 2) N.
        """
        out: dict[str, Any] = {
            "time": self._t,
            "tau_commanded": self.tau_commanded.copy(),
            "tau_delivered": self.tau_delivered.copy(),
            "eta_lf": self.eta_lf.copy(),
            "nu_lf": self.nu_lf.copy(),
            "error": self.error.copy(),
            "integral": self.integral.copy(),
            "setpoint": None if self.setpoint is None else self.setpoint.copy(),
            "saturated": self.saturated,
        }
        if self.thrusters is not None:
            out["thruster_forces"] = (
                np.zeros((self.thrusters.count, 2))
                if self.allocation is None
                else self.allocation.forces.copy()
            )
        return out
