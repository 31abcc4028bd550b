"""Time-domain simulation of the Cummins equation.

Three solvers of the same equation of :mod:`cummins.vessel` (Ross, Perez & Fossen (2006)
eq. 12; Smogeli et al. (2004) eqs. 32–39),
(M_RB + A∞) ξ̈ + B_v ξ̇ + μ + C ξ = τ:

**State space, exact** (:func:`simulate`, default). The state x = (ξ, ξ̇, χ) of the
linear model ẋ = F x + G τ is advanced with the exact discretisation of the
first-order-hold input (τ linear between samples): x_{k+1} = Φ x_k + Γ₀ τ_k + Γ₁ τ_{k+1},
Φ = e^{FΔt}, Γ₀ + Γ₁ = ∫₀^Δt e^{F(Δt−s)} ds G, Γ₁ = ∫₀^Δt e^{F(Δt−s)} (s/Δt) ds G, all
from one matrix exponential of the augmented matrix (Van Loan 1978). There is no integration
error for the linear part: the only approximation is the hold of the input. The
recursion runs in the eigenvector coordinates of Φ, one first-order IIR filter per mode
(:func:`scipy.signal.lfilter`), so a 3-hour run takes a fraction of a second.

**State space with added nonlinear forces** (``nonlinear_force``): classical fixed-step
Runge–Kutta (4th order) on the same state, the nonlinear force τ_nl(t, ξ, ξ̇) (quadratic
or cubic damping, a user's callback) added to τ.

**Direct convolution** (:func:`simulate_convolution`, the reference). The memory force
μ(t_k) = ∫ K(t_k − s) ξ̇(s) ds by the trapezoidal rule on the samples of K (de Haan (2022)
eq. 2.23, first line; the second line as printed misses Δt), with the K(0)Δt/2 term
implicit, and Newmark's average-acceleration scheme for the rest. Its cost grows with
the length of K in samples: it is the benchmark's reference and a check of the
state-space model against the retardation function of the data.

**Joined bodies and PTOs.** A vessel with joints (:mod:`cummins.mechanics`) is simulated in
its independent coordinates, x = (q, q̇, χ) (:mod:`cummins.vessel`); the run is written in
the body DOFs, ξ = T q, with each PTO's relative displacement, velocity, force and
absorbed power (``pto_*``, dims time × pto).

Initial conditions: ``initial="rest"`` starts from ξ = ξ̇ = 0 and an unloaded memory;
``"steady"`` starts on the periodic (or, for irregular waves, stationary) solution of
the same linear model at t = 0 — the frequency-domain response of every wave component
summed — so that the memory holds the right velocity history from the first step
(de Haan (2022) §3.1.1.2 runs "half a minute of negative time" for the same purpose; with
the state-space model the history is a state and can be set exactly).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.signal import lfilter

from cummins.errors import ArgumentError, CumminsWarning, SimulationError
from cummins.hydrodb import is_rotation
from cummins.mechanics import pto_time_series
from cummins.timedomain.time_step import check_time_step, energy_balance_failure
from cummins.validation import check_simulation_size, positive
from cummins.vessel import Vessel

#: A response larger than this many times the largest static response to the peak
#: force, or not finite, stops the simulation with a SimulationError.
DIVERGENCE_FACTOR = 1e4
#: Φ is used in its eigenvector coordinates when their condition number is below this.
MODAL_CONDITION = 1e8

NonlinearForce = Callable[[float, NDArray[np.float64], NDArray[np.float64]], ArrayLike]
#: Called with the fraction of the work done (0 to 1).
Progress = Callable[[float], None]
_STEPS_PER_REPORT = 2000


def _no_progress(fraction: float) -> None:
    return None


@dataclass(frozen=True)
class Discretization:
    """The exact first-order-hold discretisation of a vessel at step ``dt`` (s)."""

    dt: float
    phi: NDArray[np.float64]
    gamma0: NDArray[np.float64]
    gamma1: NDArray[np.float64]


def discretize(vessel: Vessel, dt: float) -> Discretization:
    """Φ, Γ₀, Γ₁ of x_{k+1} = Φ x_k + Γ₀ τ_k + Γ₁ τ_{k+1} (module docstring).

    The exponential of [[F Δt, G Δt, 0], [0, 0, I], [0, 0, 0]] holds Φ, ∫₀^Δt e^{F(Δt−s)} G ds
    and Γ₁ = ∫₀^Δt e^{F(Δt−s)} G s/Δt ds (Van Loan 1978) in its first block row.
    """
    f, g = vessel.state_space()
    return first_order_hold(f, g, dt)


def first_order_hold(f: ArrayLike, g: ArrayLike, dt: float) -> Discretization:
    """Φ, Γ₀, Γ₁ of x_{k+1} = Φ x_k + Γ₀ u_k + Γ₁ u_{k+1} for ẋ = F x + G u with u linear
    between the samples (first-order hold), exact: one matrix exponential (Van Loan 1978),
    as :func:`discretize`."""
    dt = positive(dt, "the time step dt", "s")
    f = np.asarray(f, dtype=float)
    g = np.asarray(g, dtype=float).reshape(f.shape[0], -1)
    ns, n = g.shape
    z = np.zeros((ns + 2 * n, ns + 2 * n))
    z[:ns, :ns] = f * dt
    z[:ns, ns : ns + n] = g * dt
    z[ns : ns + n, ns + n :] = np.eye(n)
    e = scipy.linalg.expm(z)
    phi, full, ramp = e[:ns, :ns], e[:ns, ns : ns + n], e[:ns, ns + n :]
    # full = ∫₀^Δt e^{F(Δt−s)} G ds; ramp = ∫₀^Δt e^{F(Δt−s)} G s/Δt ds, the weight of τ_{k+1}
    return Discretization(dt, phi, full - ramp, ramp)


def simulate(
    vessel: Vessel,
    t: ArrayLike,
    force: ArrayLike,
    *,
    initial_state: ArrayLike | None = None,
    nonlinear_force: NonlinearForce | None = None,
    progress: Progress | None = None,
) -> xr.Dataset:
    """Simulate the vessel under the external force τ(t) sampled at uniform times ``t``.

    Parameters
    ----------
    vessel
        The linear model (:class:`cummins.vessel.Vessel`); it must be stable.
    t
        Uniform times, s, shape (N,).
    force
        τ at those times, shape (N, n_dofs), N, N·m (linear between samples).
    initial_state
        x(t₀) = (q, q̇, χ) (q = ξ without joints), default zero (at rest).
    nonlinear_force
        τ_nl(t, ξ, ξ̇) added to τ; switches to the Runge–Kutta path.
    progress
        Called with the fraction done (0 to 1) as the run advances (a progress bar).

    Returns
    -------
    xarray.Dataset
        ``motion`` and ``velocity`` (time, dof) in m, rad and m/s, rad/s about the
        database's reference point and axes; ``memory_force`` μ (time, dof);
        ``external_force`` τ (time, dof); with PTOs ``pto_displacement``,
        ``pto_velocity``, ``pto_force`` and ``pto_power`` (time, pto,
        :func:`cummins.mechanics.pto_time_series`); attributes ``method``, ``dt``.

    Raises
    ------
    SimulationError
        Unstable vessel model, non-uniform times, wrong shapes, NaN in the force, or a
        response that diverges (naming the DOF and the time).
    """
    t = np.asarray(t, dtype=float).reshape(-1)
    tau = np.asarray(force, dtype=float)
    n = len(vessel.dofs)
    if tau.shape != (t.size, n):
        raise SimulationError(f"force must have shape ({t.size}, {n}), not {tau.shape}")
    if t.size < 2:
        raise SimulationError("at least two time samples are needed")
    dt = float(t[1] - t[0])
    if not np.allclose(np.diff(t), dt, rtol=1e-9, atol=1e-12 * max(abs(t[-1]), 1.0)):
        raise SimulationError("the times must be uniformly spaced")
    bad = ~np.isfinite(tau)
    if bad.any():
        k, i = np.argwhere(bad)[0]
        raise SimulationError(f"the force is not finite at t = {t[k]:.6g} s in {vessel.dofs[i]}")
    vessel.stability()
    ns = vessel.n_states
    x0 = np.zeros(ns) if initial_state is None else np.asarray(initial_state, dtype=float)
    if x0.shape != (ns,):
        raise SimulationError(f"initial_state must have {ns} values (q, q̇, χ)")
    # outputs y = H x: ξ, ξ̇ and the memory force μ = C_r χ
    h = vessel.output_matrix()
    report = progress or _no_progress
    if nonlinear_force is None:
        y = propagate(discretize(vessel, dt), tau, x0, h, report)
        method = "state space, exact (first-order hold)"
    else:
        x, extra = _runge_kutta(vessel, t, tau, x0, nonlinear_force, report, h)
        y = x @ h.T
        method = "state space, Runge-Kutta 4 (nonlinear forces)"
    _check_divergence(vessel, t, y[:, :n], tau)
    result = _result(vessel, t, y[:, :n], y[:, n : 2 * n], y[:, 2 * n :], tau, method, dt)
    if nonlinear_force is not None:  # its work enters the energy balance
        result["nonlinear_force"] = (("time", "dof"), extra)
        result.nonlinear_force.attrs["units"] = "N | N m"
    return result


def simulate_waves(
    vessel: Vessel,
    ds: xr.Dataset,
    waves,
    *,
    duration: float,
    dt: float,
    initial: str = "steady",
    nonlinear_force: NonlinearForce | None = None,
    progress: Progress | None = None,
    second_order=None,
    first_order: bool = True,
    **excitation_options,
) -> xr.Dataset:
    """Simulate the vessel in a sea of wave components (regular or irregular).

    Parameters
    ----------
    vessel
        The vessel (:func:`cummins.vessel.vessel_from_hydrodb`).
    ds
        The ``HydroDB`` whose ``excitation_force`` drives it (the first-order wave force,
        :func:`cummins.seakeeping.excitation.excitation_coefficients`).
    waves
        :class:`cummins.seakeeping.waves.WaveComponents` (phases at the origin).
    duration, dt
        Length of the run and time step, s (finite, > 0; a run whose arrays would not
        fit in :func:`cummins.validation.memory_limit` is refused before it starts, and
        so is a step longer than :func:`cummins.timedomain.time_step.largest_time_step`:
        fewer than 6 steps per period of the shortest wave component met, or beyond the
        Runge–Kutta path's stability with ``nonlinear_force``).
    initial
        ``"steady"`` (default): start on the stationary solution of the same linear model
        (no start-up transient, no drift of the unrestrained DOFs); ``"rest"``.
    nonlinear_force
        As :func:`simulate`.
    progress
        Called with the fraction done, 0 to 1 (the wave force takes the first fifth).
    second_order
        A second-order force of the same sea
        (:func:`cummins.timedomain.loads.second_order.second_order_force`), added to the
        first-order one; the steady start includes its stationary response (a DOF
        without restoring starts at rest and drifts under the mean force). Zero speed
        only.
    first_order
        Include the first-order wave force (False: a run of the second-order force alone,
        for data without ``excitation_force``).
    **excitation_options
        Passed to :func:`cummins.seakeeping.excitation.excitation_transfer`.

    Returns
    -------
    xarray.Dataset
        :func:`simulate`'s variables and ``wave_elevation`` (time) at the origin, m (at a
        forward speed: the origin moving with the ship, and the force and motions at the
        encounter frequencies, :func:`cummins.seakeeping.excitation.encounter_coefficients`);
        attributes describing the sea (``n_components``, ``seed`` …) and the energy
        balance (``energy_*``, J). A balance that misses by more than
        :data:`cummins.timedomain.time_step.ENERGY_TOLERANCE` of the work done is a failed
        run: attribute ``failure`` and a :class:`~cummins.errors.CumminsWarning`.

    Raises
    ------
    ArgumentError
        A time step too long for the waves (naming ``dt`` and the largest that does).
    """
    from cummins.seakeeping.excitation import (
        encounter_coefficients,
        encounter_frequencies,
        forward_speed,
    )
    from cummins.seakeeping.waves import harmonic_sum

    if initial not in ("steady", "rest"):
        raise ArgumentError(f"initial must be 'steady' or 'rest', not {initial!r}")
    check_simulation_size(duration, dt, vessel.n_states, len(vessel.dofs))
    duration, dt = float(duration), float(dt)
    ds = _on_vessel_dofs(ds, vessel)
    check_time_step(
        dt,
        encounter_frequencies(ds, waves.omega, waves.direction),
        vessel.state_space()[0] if nonlinear_force is not None else None,
    )
    t = np.arange(0.0, duration + 0.5 * dt, dt)
    report = progress or _no_progress
    if first_order:
        omega_e, coefficients = encounter_coefficients(ds, waves, **excitation_options)
        force = harmonic_sum(t, omega_e, coefficients)
        x0 = steady_state(vessel, omega_e, coefficients) if initial == "steady" else None
    else:
        omega_e = waves.omega
        force = np.zeros((t.size, len(vessel.dofs)))
        x0 = np.zeros(vessel.n_states) if initial == "steady" else None
    notes: list[str] = []
    if second_order is not None:
        if forward_speed(ds):
            raise ArgumentError("second-order wave loads are modelled at zero speed only")
        force = force + second_order.time_series(t)
        notes = list(second_order.notes)
        if initial == "steady":
            x2, more = second_order.stationary_state(vessel)
            x0, notes = x0 + x2, notes + more
    report(0.2)
    result = simulate(
        vessel,
        t,
        force,
        initial_state=x0,
        nonlinear_force=nonlinear_force,
        progress=lambda fraction: report(0.2 + 0.8 * fraction),
    )
    result["wave_elevation"] = ("time", harmonic_sum(t, omega_e, waves.complex_amplitude))
    result.wave_elevation.attrs["units"] = "m"
    speed = forward_speed(ds)
    if speed:
        result.wave_elevation.attrs["long_name"] = (
            "wave elevation at the origin moving with the ship"
        )
    balance = energy_balance(vessel, result)
    attrs = {
        "initial": initial,
        "forward_speed": speed,
        "n_components": len(waves),
        **{f"energy_{key}": value for key, value in balance.items()},
    }
    for key in ("spectrum", "hs", "tp", "seed"):
        value = getattr(waves, key, None)
        if value is not None:
            attrs[key] = value
    attrs["first_order"] = int(bool(first_order))
    if second_order is not None:
        attrs["second_order"] = second_order.model
        attrs["second_order_mean_force"] = np.asarray(second_order.mean, dtype=float)
        attrs["second_order_notes"] = "\n".join(notes)
        if second_order.drift_left_out:
            attrs["second_order_drift_left_out"] = np.asarray(second_order.drift_left_out)
    result.attrs.update(attrs)
    failure = energy_balance_failure(result.attrs)
    if failure:
        result.attrs["failure"] = failure
        warnings.warn(failure, CumminsWarning, stacklevel=2)
    return result


def quadratic_damping_force(dofs, coefficients: dict[str, float]) -> NonlinearForce:
    """τ_nl(t, ξ, ξ̇) = −b₂ |ξ̇_i| ξ̇_i on the DOFs of ``coefficients`` ({dof: b₂}, kg/m
    for translations, kg·m²/rad for rotations): the viscous (drag) damping of roll, a
    ``nonlinear_force`` for :func:`simulate`."""
    dofs = list(dofs)
    unknown = [d for d in coefficients if d not in dofs]
    if unknown:
        raise SimulationError(f"unknown DOF {unknown}; the vessel has {', '.join(dofs)}")
    index = np.array([dofs.index(d) for d in coefficients], dtype=int)
    b2 = np.array(list(coefficients.values()), dtype=float)

    def force(t: float, xi: NDArray, v: NDArray) -> NDArray:
        out = np.zeros(len(dofs))
        out[index] = -b2 * np.abs(v[index]) * v[index]
        return out

    return force


def steady_state(
    vessel: Vessel, omega: ArrayLike, force_amplitude: ArrayLike, t0: float = 0.0
) -> NDArray[np.float64]:
    """The state x(t₀) of the stationary response to τ(t) = Re Σ_k F̂_k e^{iω_k t}:
    x = Re Σ_k (iω_k I − F)⁻¹ G F̂_k e^{iω_k t₀} (the same linear model, solved in the
    frequency domain)."""
    f, g = vessel.state_space()
    w = np.asarray(omega, dtype=float).reshape(-1)
    amp = np.asarray(force_amplitude, dtype=complex).reshape(w.size, -1)
    eye = np.eye(f.shape[0])
    x = np.zeros(f.shape[0], dtype=complex)
    for wk, fk in zip(w, amp, strict=True):
        x += np.linalg.solve(1j * wk * eye - f, g @ fk) * np.exp(1j * wk * t0)
    return x.real


def component_motions(
    vessel: Vessel, ds: xr.Dataset, waves, **excitation_options
) -> NDArray[np.complex128]:
    """Complex motion amplitudes x_k (n_components, n_dofs) of the vessel's linear model
    in each wave component: its stationary response is ξ(t) = Re Σ_k x_k e^{iω_k t}
    (ω_e,k at a forward speed, :func:`cummins.seakeeping.excitation.encounter_coefficients`), and
    ½|x_k|² the share of component k in each DOF's variance (m², rad²)."""
    from cummins.seakeeping.excitation import encounter_coefficients

    ds = _on_vessel_dofs(ds, vessel)
    return vessel.response(*encounter_coefficients(ds, waves, **excitation_options))


def _on_vessel_dofs(ds: xr.Dataset, vessel: Vessel) -> xr.Dataset:
    """The data on the vessel's DOFs: a vessel with joints holds only the DOFs that can
    move (the wave forces on the others do no work)."""
    labels = [str(d) for d in ds.influenced_dof.values]
    if labels == list(vessel.dofs):
        return ds
    missing = [d for d in vessel.dofs if d not in labels]
    if missing:
        raise SimulationError(
            f"the data have no DOF {missing[0]!r} of the vessel",
            hint="give the data the vessel was built from",
        )
    from cummins.hydrodb import select_dofs

    return select_dofs(ds, list(vessel.dofs))


def simulate_convolution(
    vessel: Vessel,
    t: ArrayLike,
    force: ArrayLike,
    kernel: ArrayLike,
    *,
    added_mass_inf: ArrayLike | None = None,
    velocity_history: ArrayLike | None = None,
    initial_motion: ArrayLike | None = None,
    oversampling: int = 1,
) -> xr.Dataset:
    """The reference solver: direct convolution of K(t) (de Haan (2022) eq. 2.23).

    Parameters
    ----------
    vessel
        Supplies M_RB, C, B_v (its radiation model is not used).
    t, force
        As :func:`simulate`.
    kernel
        K at j Δt/``oversampling``, j = 0 … L·oversampling, shape (L·oversampling + 1, n,
        n) (the retardation function of the data, or the model's impulse response).
    added_mass_inf
        A∞ to use with that kernel (default: the vessel's).
    velocity_history
        ξ̇ at the L times before t₀, oldest first, shape (L, n) (default: at rest).
    initial_motion
        (ξ(t₀), ξ̇(t₀)), default zero.
    oversampling
        With 1, the trapezoidal rule on the samples of K (eq. 2.23). With m > 1, K given
        m times finer: the convolution weights W_j = ∫ K(s) φ_j(s) ds of the hat functions
        φ_j of a velocity linear between the time steps, integrated on the fine samples —
        the rule stays exact for piecewise-linear velocities while K varies quickly
        within a step (its initial drop).
    """
    t = np.asarray(t, dtype=float).reshape(-1)
    tau = np.asarray(force, dtype=float)
    k = np.asarray(kernel, dtype=float)
    n = len(vessel.dofs)
    if vessel.constraint is not None or vessel.ptos:
        raise SimulationError(
            "the direct convolution solves free bodies only: simulate joints and PTOs with "
            "the state-space model (simulate)"
        )
    dt = float(t[1] - t[0])
    if k.ndim != 3 or k.shape[1:] != (n, n):
        raise SimulationError(f"kernel must have shape (L + 1, {n}, {n}), not {k.shape}")
    if oversampling < 1 or (k.shape[0] - 1) % oversampling:
        raise SimulationError(
            f"kernel has {k.shape[0]} samples: it needs oversampling·L + 1 of them"
        )
    kw = _convolution_weights(k, dt, oversampling)  # W_j, j = 0 … L
    length = kw.shape[0] - 1
    a_inf = vessel.added_mass_inf if added_mass_inf is None else np.asarray(added_mass_inf)
    mass = vessel.rigid_body_mass + a_inf
    c, b_v = vessel.stiffness, vessel.viscous_damping
    history = np.zeros((length + t.size, n))
    if velocity_history is not None:
        history[:length] = np.asarray(velocity_history, dtype=float).reshape(length, n)
    xi = np.zeros((t.size, n))
    v = np.zeros((t.size, n))
    if initial_motion is not None:
        xi[0], v[0] = (np.asarray(x, dtype=float) for x in initial_motion)
    history[length] = v[0]
    b_tilde = b_v + kw[0]
    lhs = scipy.linalg.lu_factor(mass + 0.5 * dt * b_tilde + 0.25 * dt**2 * c)
    # the memory force without the implicit j = 0 term, at step k (velocities k−1 … k−L)
    rev = kw[1:][::-1]  # K_L … K_1, against history rows k … k+L−1 (oldest first)

    def memory_past(step: int) -> NDArray:
        past = history[step : step + length]
        return np.einsum("jab,jb->a", rev, past)

    mu = memory_past(0) + kw[0] @ v[0]
    a = np.linalg.solve(mass, tau[0] - b_v @ v[0] - mu - c @ xi[0])
    memory = np.zeros((t.size, n))
    memory[0] = mu
    for step in range(t.size - 1):
        h = memory_past(step + 1)
        rhs = (
            tau[step + 1]
            - h
            - b_tilde @ (v[step] + 0.5 * dt * a)
            - c @ (xi[step] + dt * v[step] + 0.25 * dt**2 * a)
        )
        a_new = scipy.linalg.lu_solve(lhs, rhs)
        v[step + 1] = v[step] + 0.5 * dt * (a + a_new)
        xi[step + 1] = xi[step] + dt * v[step] + 0.25 * dt**2 * (a + a_new)
        history[length + step + 1] = v[step + 1]
        memory[step + 1] = h + kw[0] @ v[step + 1]
        a = a_new
    _check_divergence(vessel, t, xi, tau)
    return _result(vessel, t, xi, v, memory, tau, "direct convolution (trapezoid, Newmark)", dt)


def energy_balance(vessel: Vessel, result: xr.Dataset) -> dict[str, float]:
    """Work done on and by the vessel over the run, J (trapezoid in time).

    ``input`` ∫ξ̇ᵀτ, ``nonlinear`` ∫ξ̇ᵀτ_nl (the work of the run's ``nonlinear_force``,
    negative when it dissipates), ``viscous`` ∫ξ̇ᵀB_vξ̇, ``pto`` ∫ξ̇ᵀB_ptoξ̇ (absorbed by
    the PTOs' dampers), ``radiated`` ∫ξ̇ᵀμ (≥ 0 from rest for a passive model),
    ``mechanical_change`` ΔE of E = ½ξ̇ᵀMξ̇ + ½ξᵀ(C + C_pto)ξ, ``residual`` input +
    nonlinear − viscous − pto − radiated − mechanical change (a numerical error, relative
    to the input in
    ``relative_residual``), ``radiated_min`` the smallest running radiated work (negative:
    energy came out of the fluid memory). With joints the constraint forces do no work
    on the allowed motions ξ̇ = T q̇, so the same sums hold in the body DOFs.
    """
    t = result.time.values
    v = result.velocity.values
    xi = result.motion.values
    tau = result.external_force.values
    mu = result.memory_force.values
    mass = vessel.mass
    p_in = np.einsum("ti,ti->t", v, tau)
    p_v = np.einsum("ti,ij,tj->t", v, vessel.viscous_damping, v)
    p_pto = np.einsum("ti,ij,tj->t", v, vessel.pto_damping, v)
    p_r = np.einsum("ti,ti->t", v, mu)
    p_nl = (
        np.einsum("ti,ti->t", v, result.nonlinear_force.values)
        if "nonlinear_force" in result
        else np.zeros(t.size)
    )
    energy = 0.5 * np.einsum("ti,ij,tj->t", v, mass, v) + 0.5 * np.einsum(
        "ti,ij,tj->t", xi, vessel.restoring, xi
    )

    def integral(p):
        return np.concatenate([[0.0], np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(t))])

    work_in, work_v, work_r = integral(p_in), integral(p_v), integral(p_r)
    work_pto, work_nl = integral(p_pto), integral(p_nl)
    residual = (
        work_in[-1]
        + work_nl[-1]
        - work_v[-1]
        - work_pto[-1]
        - work_r[-1]
        - (energy[-1] - energy[0])
    )
    scale = max(abs(work_in[-1]), float(np.abs(energy).max()), 1e-300)
    return {
        "input": float(work_in[-1]),
        "nonlinear": float(work_nl[-1]),
        "viscous": float(work_v[-1]),
        "pto": float(work_pto[-1]),
        "radiated": float(work_r[-1]),
        "mechanical_change": float(energy[-1] - energy[0]),
        "residual": float(residual),
        "relative_residual": float(abs(residual) / scale),
        "radiated_min": float(work_r.min()),
    }


# --------------------------------------------------------------------------- internals


def _convolution_weights(k: NDArray, dt: float, m: int) -> NDArray:
    """W_j = ∫ K(s) φ_j(s) ds for the hat functions φ_j of step Δt (trapezoid on the m
    fine samples per step; for m = 1: Δt w_j K_j with w = ½, 1, …, 1, ½)."""
    fine = np.arange(k.shape[0]) * (dt / m)
    length = (k.shape[0] - 1) // m
    out = np.zeros((length + 1, *k.shape[1:]))
    h = dt / m
    for j in range(length + 1):
        lo, hi = max(0, (j - 1) * m), min(k.shape[0], (j + 1) * m + 1)
        hat = np.clip(1.0 - np.abs(fine[lo:hi] / dt - j), 0.0, None)
        q = np.full(hi - lo, h)
        q[[0, -1]] = 0.5 * h  # trapezoid on the fine samples under the hat
        out[j] = np.einsum("s,s,sab->ab", q, hat, k[lo:hi])
    return out


def propagate(
    disc: Discretization, tau: NDArray, x0: NDArray, h: NDArray, report: Progress = _no_progress
) -> NDArray:
    """Outputs y_k = H x_k of the first-order-hold recursion, computed modally: with
    Φ = V Λ V⁻¹ each mode z = V⁻¹x obeys z_k = λ z_{k−1} + d_k, a first-order IIR filter
    (:func:`scipy.signal.lfilter`), and y = (H V) z. The inputs enter the modes through
    V⁻¹Γ (n_states × n_dofs), so no product scales with n_states² per step."""
    lam, vec = np.linalg.eig(disc.phi)
    if np.linalg.cond(vec) < MODAL_CONDITION:
        inv = np.linalg.inv(vec)
        # x is real: of each conjugate pair of modes one is filtered and counted twice
        tol = 1e-12 * max(float(np.abs(lam).max()), 1e-300)
        keep = np.flatnonzero(lam.imag >= -tol)
        double = np.where(lam.imag[keep] > tol, 2.0, 1.0)
        gains = (inv[keep] @ disc.gamma0, inv[keep] @ disc.gamma1)
        drive = (gains[0] @ tau[:-1].T + gains[1] @ tau[1:].T).astype(complex)  # (modes, time)
        z0 = inv[keep] @ x0
        z = np.empty((keep.size, tau.shape[0]), dtype=complex)
        z[:, 0] = z0
        for m, mode in enumerate(keep):
            # z_k = λ z_{k−1} + d_k (k ≥ 1): an IIR filter of d_1 … whose state is λ z_0
            z[m, 1:] = lfilter([1.0], [1.0, -lam[mode]], drive[m], zi=[lam[mode] * z0[m]])[0]
            report((m + 1) / keep.size)
        out = ((h @ vec[:, keep]) * double) @ z
        return np.ascontiguousarray(out.real.T)
    drive = tau[:-1] @ disc.gamma0.T + tau[1:] @ disc.gamma1.T
    x = np.empty((tau.shape[0], x0.size))
    x[0] = x0
    for k in range(1, tau.shape[0]):
        x[k] = disc.phi @ x[k - 1] + drive[k - 1]
        if k % _STEPS_PER_REPORT == 0:
            report(k / (tau.shape[0] - 1))
    report(1.0)
    return x @ h.T


def _runge_kutta(
    vessel, t, tau, x0, nonlinear_force, report=_no_progress, h=None
) -> tuple[NDArray, NDArray]:
    """The states at the times ``t`` (RK4), and the nonlinear force at them (its value at
    each step's first stage, the last one evaluated once more)."""
    f, g = vessel.state_space()
    n = len(vessel.dofs)
    motion = (vessel.output_matrix() if h is None else h)[: 2 * n]  # (ξ, ξ̇) = H x
    dt = t[1] - t[0]
    x = np.empty((t.size, x0.size))
    x[0] = x0
    forces = np.empty((t.size, n))

    def nonlinear(tk, xk):
        y = motion @ xk
        return np.asarray(nonlinear_force(tk, y[:n], y[n:]), dtype=float)

    def rate(tk, xk, force):
        return f @ xk + g @ (force + nonlinear(tk, xk))

    for k in range(t.size - 1):
        mid = 0.5 * (tau[k] + tau[k + 1])
        xk = x[k]
        forces[k] = nonlinear(t[k], xk)
        k1 = f @ xk + g @ (tau[k] + forces[k])
        k2 = rate(t[k] + dt / 2, xk + dt / 2 * k1, mid)
        k3 = rate(t[k] + dt / 2, xk + dt / 2 * k2, mid)
        k4 = rate(t[k + 1], xk + dt * k3, tau[k + 1])
        x[k + 1] = xk + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if not np.all(np.isfinite(x[k + 1])):
            _check_divergence(vessel, t[: k + 2], x[: k + 2] @ motion[:n].T, tau[: k + 2])
        if (k + 1) % _STEPS_PER_REPORT == 0:
            report((k + 1) / (t.size - 1))
    forces[-1] = nonlinear(t[-1], x[-1])
    report(1.0)
    return x, forces


def _check_divergence(vessel: Vessel, t: NDArray, xi: NDArray, tau: NDArray) -> None:
    """SimulationError when ξ is not finite or exceeds DIVERGENCE_FACTOR × the static
    response to the peak force (per DOF; DOFs without restoring are judged by their
    drift against the largest displacement scale)."""
    finite = np.isfinite(xi)
    if not finite.all():
        k, i = np.argwhere(~finite)[0]
        raise SimulationError(
            f"the simulation diverged: {vessel.dofs[i]} is not finite at t = {t[k]:.6g} s",
            hint="check the stability of added nonlinear forces and the time step",
        )
    peak = np.abs(tau).max(axis=0)
    stiff = np.abs(np.diag(vessel.restoring))
    static = np.where(stiff > 0, peak / np.where(stiff > 0, stiff, 1.0), 0.0)
    scale = np.where(static > 0, static, max(float(static.max()), 1.0))
    limit = DIVERGENCE_FACTOR * np.maximum(scale, 1e-6)
    over = np.abs(xi) > limit
    if over.any():
        k, i = np.argwhere(over)[0]
        raise SimulationError(
            f"the simulation diverged: |{vessel.dofs[i]}| = {abs(xi[k, i]):.4g} at "
            f"t = {t[k]:.6g} s, over {DIVERGENCE_FACTOR:g} times its static response",
            hint="a DOF without restoring (surge, sway, yaw) drifts under a mean force: "
            "add viscous damping or a mooring stiffness; otherwise check the model's "
            "passivity and any nonlinear forces",
        )


def _result(vessel, t, xi, v, memory, tau, method, dt) -> xr.Dataset:
    dof = list(vessel.dofs)
    units = [_unit(d) for d in dof]
    ds = xr.Dataset(
        {
            "motion": (("time", "dof"), xi),
            "velocity": (("time", "dof"), v),
            "memory_force": (("time", "dof"), memory),
            "external_force": (("time", "dof"), tau),
        },
        coords={"time": t, "dof": dof},
        attrs={
            "method": method,
            "dt": dt,
            "reference_point": np.asarray(vessel.attrs.get("reference_point", (0, 0, 0))),
            "axis_convention": str(vessel.attrs.get("axis_convention", "z-up")),
        },
    )
    ds.time.attrs["units"] = "s"
    ds.motion.attrs["units"] = " | ".join(units)
    ds.velocity.attrs["units"] = " | ".join(f"{u}/s" for u in units)
    ds.memory_force.attrs["units"] = "N | N m"
    ds.external_force.attrs["units"] = "N | N m"
    if vessel.ptos:
        ds = ds.assign(pto_time_series(vessel.ptos, xi, v)).assign_coords(
            pto=[p.name for p in vessel.ptos]
        )
        ds.pto.attrs["description"] = "\n".join(f"{p.name}: {p.description}" for p in vessel.ptos)
    for key in ("body_coupling", "body_coupling_note", "system", "constrained_coordinates"):
        if key in vessel.attrs:
            ds.attrs[key] = str(vessel.attrs[key])
    return ds


def _unit(dof: str) -> str:
    return "rad" if is_rotation(dof) else "m"
