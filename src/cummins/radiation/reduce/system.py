"""A stable state-space model G(s) = C (sI − A)⁻¹ B + D: its checks, its frequency
response and its H∞ norm.

The matrices of a model to reduce are validated here (shapes, finite entries, every pole
in the open left half-plane: balanced truncation needs a stable model, Unneland (2007)
Ch. 5), as are the options of the reductions (method, order or tolerance, low-frequency
weight). G(jω) is evaluated through the eigen-decomposition of A, or its complex Schur
form when the eigenvectors are ill conditioned; ‖G‖∞ on a frequency sweep refined at its
peaks (a lower estimate, so the order selection of
:mod:`~cummins.radiation.reduce.balancing` stays conservative).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from cummins.errors import FitError

#: Balancing methods: Lyapunov, Riccati (positive real), mixed (P, O) and mixed (R, Q).
METHODS = ("lyapunov", "riccati", "mixed", "mixed-rq")
#: Methods that need the positive-real Riccati equations (and a square, PR model).
PR_METHODS = ("riccati", "mixed", "mixed-rq")
#: Eigenvector condition number up to which frequency responses use the (vectorised)
#: eigen-decomposition of A rather than its Schur form.
MAX_EIGENVECTOR_CONDITION = 1e6
#: Points per decade of the frequency sweeps (‖G‖∞, DOF scales, measured errors).
SWEEP_POINTS_PER_DECADE = 50


# --------------------------------------------------------------------------- checks


def _system(
    a: ArrayLike, b: ArrayLike, c: ArrayLike, d: ArrayLike | None = None
) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Validated float arrays (A n×n, B n×m, C p×n, D p×m) of a stable model.

    1-D ``b`` and ``c`` are taken as a column and a row (SISO convenience); ``d`` None is
    zero, a scalar is accepted for a SISO model.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    c = np.asarray(c, dtype=float)
    if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] == 0:
        raise FitError(f"A must be a non-empty square matrix, not of shape {a.shape}")
    n = a.shape[0]
    b = b.reshape(-1, 1) if b.ndim == 1 else b
    c = c.reshape(1, -1) if c.ndim == 1 else c
    if b.ndim != 2 or b.shape[0] != n:
        raise FitError(f"B must have {n} rows (one per state), not shape {b.shape}")
    if c.ndim != 2 or c.shape[1] != n:
        raise FitError(f"C must have {n} columns (one per state), not shape {c.shape}")
    p, m = c.shape[0], b.shape[1]
    if d is None:
        d = np.zeros((p, m))
    else:
        d = np.asarray(d, dtype=float)
        if d.ndim == 0 and p == m == 1:
            d = d.reshape(1, 1)
        if d.shape != (p, m):
            raise FitError(f"D must have shape ({p}, {m}) (outputs × inputs), not {d.shape}")
    for name, x in (("A", a), ("B", b), ("C", c), ("D", d)):
        if not np.all(np.isfinite(x)):
            raise FitError(f"{name} holds NaN or infinite entries")
    poles = np.linalg.eigvals(a)
    if np.any(poles.real >= 0):
        worst = poles[np.argmax(poles.real)]
        raise FitError(
            f"the model is not stable (pole {worst:.6g} rad/s); balanced truncation needs "
            "every pole in the open left half-plane (split off the unstable part first)"
        )
    return a, b, c, d


def _checked_weight(weight: Any) -> float | None:
    if weight is None or weight == 0:
        return None
    if isinstance(weight, bool) or not isinstance(weight, int | float | np.floating):
        raise FitError(f"low_frequency_weight must be a frequency (rad/s), not {weight!r}")
    if not 0 < weight < math.inf:
        raise FitError(f"low_frequency_weight must be positive and finite, not {weight!r}")
    return float(weight)


def _check_method(method: str) -> None:
    if method not in METHODS:
        raise FitError(f"unknown method {method!r}; use one of {', '.join(METHODS)}")


def _check_order_or_tol(order: Any, tol: Any) -> None:
    if (order is None) == (tol is None):
        raise FitError("give either order or tol (not both, not neither)")
    if tol is not None and not (isinstance(tol, int | float) and 0 < tol < math.inf):
        raise FitError(f"tol must be a positive number, not {tol!r}")


def _checked_order(order: Any, n: int) -> int:
    if isinstance(order, bool) or not isinstance(order, int | np.integer):
        raise FitError(f"the order must be an integer, not {order!r}")
    if not 1 <= order <= n:
        raise FitError(f"order {order} is out of range: the model has {n} states (use 1 … {n})")
    return int(order)


# --------------------------------------------------------------------------- frequency sweeps


def frequency_response(
    a: ArrayLike, b: ArrayLike, c: ArrayLike, d: ArrayLike | None, omega: ArrayLike
) -> NDArray[np.complex128]:
    """G(jω) = C (jωI − A)⁻¹ B + D, shape (len(omega), p, m).

    Through the eigen-decomposition A = V Λ V⁻¹ (vectorised over ω) when V is well
    conditioned (κ(V) ≤ :data:`MAX_EIGENVECTOR_CONDITION`), else through the complex
    Schur form A = Z T Zᴴ, one triangular solve per frequency (a defective A is no
    problem there). ``b``, ``c`` as in :func:`balanced_truncation`.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    c = np.asarray(c, dtype=float)
    b = b.reshape(-1, 1) if b.ndim == 1 else b
    c = c.reshape(1, -1) if c.ndim == 1 else c
    d = np.zeros((c.shape[0], b.shape[1])) if d is None else np.asarray(d, dtype=float)
    w = np.asarray(omega, dtype=float).reshape(-1)
    out = np.empty((w.size, c.shape[0], b.shape[1]), dtype=complex)
    out[:] = d
    if a.size == 0:
        return out
    lam, v = np.linalg.eig(a)
    if np.linalg.cond(v) <= MAX_EIGENVECTOR_CONDITION:
        left, right = c @ v, np.linalg.solve(v, b)
        resolvent = 1.0 / (1j * w[:, None] - lam[None, :])
        return out + np.einsum("pn,fn,nm->fpm", left, resolvent, right, optimize=True)
    t, z = scipy.linalg.schur(a, output="complex")
    bz = z.conj().T @ b
    cz = c @ z
    eye = np.eye(a.shape[0])
    for k, wk in enumerate(w):
        x = scipy.linalg.solve_triangular(1j * wk * eye - t, bz, check_finite=False)
        out[k] += cz @ x
    return out


def _sweep(poles: NDArray, points_per_decade: int = SWEEP_POINTS_PER_DECADE) -> NDArray:
    """Log grid from 10⁻² to 10² times the range of the pole magnitudes, refined at every
    lightly damped resonance (|Im p| ± 3|Re p|)."""
    mags = np.abs(poles[np.abs(poles) > 0]) if np.any(np.abs(poles) > 0) else np.ones(1)
    lo, hi = mags.min() * 1e-2, mags.max() * 1e2
    count = max(int(np.ceil(points_per_decade * np.log10(hi / lo))), 2)
    resonant = [p for p in poles if p.imag > 0 and -p.real < p.imag]
    peaks = [abs(p.imag) + abs(p.real) * np.linspace(-3, 3, 13) for p in resonant]
    grid = np.concatenate([np.geomspace(lo, hi, count), *peaks])
    return np.unique(grid[grid > 0])


def _gain(g: NDArray) -> NDArray:
    """Largest singular value of each G(jω_k) (|G| for SISO)."""
    if g.shape[1] == 1 and g.shape[2] == 1:
        return np.abs(g[:, 0, 0])
    return np.linalg.svd(g, compute_uv=False)[:, 0]


def _refined_peak(
    gain: Callable[[float], float], grid: NDArray, values: NDArray, count: int = 3
) -> tuple[float, float]:
    """The largest of ``values`` refined by a bounded scalar search around the ``count``
    highest local maxima (between their grid neighbours, in log ω)."""
    from scipy.optimize import minimize_scalar

    best = int(np.argmax(values))
    peak, where = float(values[best]), float(grid[best])
    inner = np.flatnonzero(
        (values[1:-1] >= values[:-2]) & (values[1:-1] >= values[2:]) & (values[1:-1] > 0)
    )
    for i in (inner + 1)[np.argsort(values[inner + 1])[::-1][:count]]:
        found = minimize_scalar(
            lambda x: -gain(float(np.exp(x))),
            bounds=(np.log(grid[i - 1]), np.log(grid[i + 1])),
            method="bounded",
            options={"xatol": 1e-7},
        )
        if -found.fun > peak:
            peak, where = float(-found.fun), float(np.exp(found.x))
    return peak, where


def hinf_norm(
    a: ArrayLike, b: ArrayLike, c: ArrayLike, d: ArrayLike | None = None
) -> tuple[float, float]:
    """‖G‖∞ = max_ω σ_max(G(jω)) of a stable model, and the frequency (rad/s) of the peak.

    Evaluated on a sweep (:data:`SWEEP_POINTS_PER_DECADE` per decade from 10⁻² to 10²
    times the pole range, refined at every lightly damped resonance), at ω = 0 and
    ω = ∞ (where G = D), and refined by a bounded search around the highest maxima. A
    sweep can only miss a peak, so this is a lower estimate of the norm (exact to the
    search tolerance when the sweep brackets the peak).
    """
    a, b, c, d = _system(a, b, c, d)
    grid = _sweep(np.linalg.eigvals(a))
    values = _gain(frequency_response(a, b, c, d, grid))
    peak, where = _refined_peak(
        lambda w: float(_gain(frequency_response(a, b, c, d, [w]))[0]), grid, values
    )
    at_zero = float(np.linalg.norm(d - c @ np.linalg.solve(a, b), 2))
    at_infinity = float(np.linalg.norm(d, 2))
    if at_zero > peak:
        peak, where = at_zero, 0.0
    if at_infinity > peak:
        peak, where = at_infinity, math.inf
    return peak, where


def _dof_scale(a: NDArray, b: NDArray, c: NDArray, d: NDArray) -> NDArray:
    """s_i = 1/√max_ω |G_ii(jω)| on the sweep (the largest diagonal peak for a zero G_ii)."""
    grid = np.concatenate([[0.0], _sweep(np.linalg.eigvals(a))])
    g = frequency_response(a, b, c, d, grid)
    peak = np.abs(np.diagonal(g, axis1=1, axis2=2)).max(axis=0)
    peak = np.maximum(peak, np.abs(np.diag(d)))
    if not np.any(peak > 0):
        raise FitError("every diagonal term of G is zero: nothing sets the DOF scales")
    peak = np.where(peak > 0, peak, peak.max())
    return 1.0 / np.sqrt(peak)
