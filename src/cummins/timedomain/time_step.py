"""The time step of a run: the largest that resolves the sea, and the energy balance after.

The state-space solver of :mod:`cummins.timedomain.simulate` is exact for the linear
dynamics; its one approximation is the first-order hold of the wave force (τ linear
between the samples). A harmonic of frequency ω sampled every Δt and held linearly
passes to the vessel with the gain of the triangle (first-order-hold) kernel,
sinc²(ωΔt / 2π) = sinc²(1/N) at N steps per period (the linear interpolator of
Oppenheim & Schafer (2010)), so the steady amplitude falls short by about (π/N)²/3 —
0.09 % at N = 60, 0.8 % at 20, 9 % at 6, 60 % at the Nyquist limit N = 2, beyond which
the component folds onto a wrong frequency. Measured on the tanker (regular waves of 6
and 9 s): amplitude errors −10 % at N = 6, −4 % at 10, −1.3 % at 20, −0.25 % at 60, and
the energy balance's residual 0.094, 0.033, 0.008, 0.0009 — both following sinc²(1/N).

:data:`STEPS_PER_SHORTEST_PERIOD` sets the step that is refused before the run: fewer
steps than that per period of the shortest wave component (at its encounter frequency).
An irregular sea's shortest components carry little of its energy: the JONSWAP
(Hs 4 m, Tp 10 s) on the tanker keeps its motions' standard deviations within 0.2 % of
those at 0.05 s down to 5.2 steps per shortest period (0.3 s), 2 % at 1.6 (1 s, beyond
Nyquist), 10–60 % at 0.8 (2 s). A regular wave, all its energy at one frequency, needs
more: the energy balance after the run (:data:`ENERGY_TOLERANCE`) is the check that
sees it.

The Runge–Kutta path (nonlinear forces) is an explicit scheme: it is stable while
|λ|Δt stays inside the region of RK4, which holds the half-disc |λΔt| ≤ 2.5 of the left
half-plane (its boundary crosses the real axis at −2.785 and the imaginary axis at
±2√2; Hairer & Wanner (1996) §IV.2); the fastest eigenvalue λ of the vessel's state
matrix (its fluid memory's fastest pole) then bounds the step too.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from cummins.errors import ArgumentError

#: At least this many time steps per period of the shortest wave component: the
#: first-order hold then passes ≥ 91 % of its force amplitude (sinc²(1/6)).
STEPS_PER_SHORTEST_PERIOD = 6
#: |λ| Δt of the Runge–Kutta path at most (the fastest eigenvalue λ of the state matrix).
RUNGE_KUTTA_REACH = 2.5
#: The time step of a run, s, unless the waves ask for a shorter one
#: (:func:`default_time_step`).
DEFAULT_DT = 0.05
#: Time steps per wave period at least by default (regular: the period; irregular: the
#: peak period): the steady power of a linear run is then within 0.2 % of the frequency
#: domain's (a tank-scale Wavestar at T = 1 s: −1.7 % at 20 steps per period, −0.1 % at
#: 100; the error falls as the square of the step).
STEPS_PER_PERIOD = 60
#: A run whose energy balance misses by more than this share of the work done on the
#: vessel (``energy_relative_residual``) is a failed run: 0.0001 at the default step in
#: the tanker's irregular sea, 0.001 at 60 steps per period of a regular wave, 0.008 at 20.
ENERGY_TOLERANCE = 0.01


def default_time_step(period: float | None) -> float:
    """:data:`DEFAULT_DT`, or ``period`` / :data:`STEPS_PER_PERIOD` when shorter, s."""
    if period is None:
        return DEFAULT_DT
    return min(DEFAULT_DT, float(period) / STEPS_PER_PERIOD)


def largest_time_step(omega: ArrayLike, state_matrix: ArrayLike | None = None) -> tuple[float, str]:
    """The largest time step that resolves the waves (and the Runge–Kutta path's fastest
    dynamics), s, and the reason, for messages.

    Parameters
    ----------
    omega
        Frequencies of the wave components the vessel meets, rad/s (encounter
        frequencies at a forward speed; signs ignored; zeros are a mean force).
    state_matrix
        F of ẋ = F x + G τ (:meth:`cummins.vessel.Vessel.state_space`) when the run takes
        the Runge–Kutta path (nonlinear forces); None for the exact path, whose linear
        dynamics no step limits.

    Returns
    -------
    (float, str)
        Δt_max = min(2π/(N ω_max), 2.5/|λ|_max) (module docstring) and what sets it.
    """
    w = np.abs(np.asarray(omega, dtype=float).reshape(-1))
    w = w[np.isfinite(w) & (w > 0)]
    limit, reason = np.inf, ""
    if w.size:
        period = 2 * np.pi / float(w.max())
        limit = period / STEPS_PER_SHORTEST_PERIOD
        reason = (
            f"{STEPS_PER_SHORTEST_PERIOD} steps per period of the shortest wave component "
            f"({period:.3g} s, {w.max():.3g} rad/s)"
        )
    if state_matrix is not None:
        fastest = float(np.abs(np.linalg.eigvals(np.asarray(state_matrix, dtype=float))).max())
        if fastest > 0 and RUNGE_KUTTA_REACH / fastest < limit:
            limit = RUNGE_KUTTA_REACH / fastest
            reason = (
                f"the Runge-Kutta path's stability with the model's fastest pole "
                f"({fastest:.3g} rad/s; |lambda| dt <= {RUNGE_KUTTA_REACH:g})"
            )
    return float(limit), reason


def check_time_step(
    dt: float, omega: ArrayLike, state_matrix: ArrayLike | None = None, option: str = "dt"
) -> None:
    """Refuse a step larger than :func:`largest_time_step` with an
    :class:`~cummins.errors.ArgumentError` naming ``option`` and the largest step that
    would do."""
    limit, reason = largest_time_step(omega, state_matrix)
    if float(dt) > limit:
        raise ArgumentError(
            f"{option} = {float(dt):g} s is too long for this run: it needs {reason}; "
            f"give {option} <= {_round_down(limit)} s"
        )


def energy_balance_failure(attrs) -> str | None:
    """The failure of a run whose energy balance misses by more than
    :data:`ENERGY_TOLERANCE` (its ``energy_relative_residual``), or None."""
    residual = float(attrs.get("energy_relative_residual", np.nan))
    if not residual > ENERGY_TOLERANCE:
        return None
    return (
        f"the energy balance misses by {residual:.2g} of the work done on the vessel "
        f"(over {ENERGY_TOLERANCE:g}): the time step {float(attrs.get('dt', np.nan)):g} s "
        "is too long for these waves or forces: shorten it (--dt)"
    )


def _round_down(value: float) -> str:
    """``value`` to 3 significant digits, rounded down (a step that does)."""
    if not np.isfinite(value) or value <= 0:
        return f"{value:g}"
    scale = 10.0 ** (np.floor(np.log10(value)) - 2)
    return f"{np.floor(value / scale) * scale:.3g}"
