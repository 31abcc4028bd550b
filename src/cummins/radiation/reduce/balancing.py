"""Balanced truncation of a stable state-space model (Unneland (2007) Ch. 5).

The model is brought into coordinates in which the two matrices (M, N) of the method
(:mod:`~cummins.radiation.reduce.gramians`) are equal and diagonal, Σ (Unneland (2007)
eq. 5.14), and its r leading states are kept (eq. 5.13). :func:`balanced_truncation`
returns a :class:`BalancedTruncation`; :func:`glover_bound` is the H∞ bound of Lyapunov
truncation (Glover 1984).

Square-root algorithm
---------------------
Table 5.1 of Unneland (2007) inverts a Cholesky factor of M. Here only factors are used
and nothing is inverted (Tombs & Postlethwaite 1987, Laub et al. 1987): with
M = L_M L_Mᵀ, N = L_N L_Nᵀ and the SVD L_Nᵀ L_M = U Σ Vᵀ,

    T = Σ^{-1/2} Uᵀ L_Nᵀ,      T⁻¹ = L_M V Σ^{-1/2}

(restricted to the leading r columns for a truncation), which satisfies T T⁻¹ = I and
T M Tᵀ = T⁻ᵀ N T⁻¹ = Σ. The factors come from the symmetric eigen-decomposition of the
computed M and N (eigenvalues below rounding clipped to zero), so a singular or nearly
singular gramian (a non-minimal model) is handled: the states with
σ_k ≤ :data:`RANK_RTOL` σ₁ are neither controllable nor observable to working
precision and are never kept (a requested order above that numerical rank is lowered to
it, with a note). Hammarling's method would give the factors more accurately than the
eigen-decomposition of the gramians; with it, the Hankel singular values of a model whose
σ span eight decades still come out within about 10⁻⁶ (relative), the small ones
included, and the test suite checks 10⁻⁸ on a model with σ from 2 down to 10⁻⁴.

Low-frequency weighting
-----------------------
With ``low_frequency_weight`` ω₀ the Lyapunov gramians are those of the augmented model

    G_aug(s) = [C; ω₀ C A⁻¹] (sI − A)⁻¹ [B, ω₀ A⁻¹B],

i.e. P of the input matrix [B, ω₀ A⁻¹B] and Q of the output matrix [C; ω₀ C A⁻¹] (both
for ``"lyapunov"``, P for ``"mixed"``, Q for ``"mixed-rq"``; the Riccati gramians are
never weighted). Its blocks are G(s) − D and ω₀ (G(s) − G(0))/s, which is stable, so
the weight grows as ω₀/ω below ω₀ and the states that matter at low frequency are kept.
For a radiation model K(0) = 0 and K(jω)/(jω) = (A(ω) − A∞) − jB(ω)/ω (Unneland (2007)
eq. 2.55): the weighting balances the added mass, whose error is the error of K amplified by
1/ω, together with the damping. The (1, 1) block of the truncated G_aug is the
truncated G, so Lyapunov truncations stay stable (when σ_r > σ_{r+1}) and Glover's
bound, now on the σ of G_aug, still bounds ‖G − G_r‖∞ (it is larger than the unweighted
one); mixed truncations stay PR, since one gramian from the PR equations balanced
against any positive definite matrix gives PR truncations (Unneland (2007) Theorem 5.3;
for stability alone, Theorem 5.2).

Order selection
---------------
``order`` gives the number of states kept. ``tol`` selects the smallest order meeting a
relative error target, relative to ‖G‖∞ (estimated on a frequency sweep refined at its
peaks; the sweep can only underestimate the norm, so the rule stays conservative):

* ``"lyapunov"``: the guaranteed bound, 2 Σ_{distinct k>r} σ_k ≤ tol ‖G‖∞, never
  splitting a group of equal σ;
* the PR methods, which have no H∞ bound: the error measured on the sweep,
  max_ω σ_max(G − G_r) ≤ tol ‖G‖∞ (the order is found by bisection; the returned order
  meets the target on the sweep).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import FitError
from cummins.radiation.reduce.gramians import (
    DEFAULT_REGULARIZATION,
    _balancing_svd,
    _lyapunov_p,
    _padded,
    _pr_gramians,
    _psd_factor,
    _Regularised,
    _regularised,
)
from cummins.radiation.reduce.system import (
    PR_METHODS,
    _check_method,
    _check_order_or_tol,
    _checked_order,
    _checked_weight,
    _gain,
    _sweep,
    _system,
    frequency_response,
    hinf_norm,
)

#: Balancing singular values at or below RANK_RTOL σ₁ are numerically zero.
RANK_RTOL = 1e-12
#: Singular values closer than DISTINCT_RTOL (relative) or RANK_RTOL σ₁ count as one
#: value in the Glover bound (a symmetric pair of identical blocks repeats each σ).
DISTINCT_RTOL = 1e-9


# --------------------------------------------------------------------------- result


@dataclass(frozen=True, eq=False)
class BalancedTruncation:
    """A reduced model G_r(s) = c (sI − a)⁻¹ b + d and how it was obtained.

    Attributes
    ----------
    a, b, c, d
        Reduced matrices, shapes (r, r), (r, m), (p, r), (p, m); ``d`` is the original D
        (balanced truncation keeps the feedthrough, Unneland (2007) eq. 5.13).
    singular_values
        Σ of the balancing, descending, one per state of the original model (zeros past
        the numerical rank): Hankel singular values (``"lyapunov"``), the PR-balanced
        values, all ≤ 1 (``"riccati"``), or the mixed-gramian values.
    order
        r, the number of states kept.
    method
        One of :data:`METHODS`.
    error_bound
        ``"lyapunov"``: 2 Σ σ_k over the distinct discarded values (Glover's bound on
        ‖G − G_r‖∞; Unneland (2007) eq. 5.22 omits the factor 2); NaN when the order
        splits a group of equal σ (no bound then). ``None`` for the PR methods.
    regularization
        δ of the regularising feedthrough D_ε = δ S⁻² (DOF-scaled units; 0: none).
    feedthrough_shift
        D_ε (p, p) in the model's units (zeros: none). The returned model satisfies
        G_r(jω) + G_r(jω)ᴴ ⪰ −2 D_ε for a PR original (PR methods).
    dof_scale
        s_i = 1/√max_ω|G_ii(jω)| used for the regularisation (PR methods; else empty).
    low_frequency_weight
        ω₀ of the low-frequency weighting used (None: unweighted).
    note
        What the user should know: order lowered to the numerical rank, split groups,
        instability of a truncation, regularisation.
    """

    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    d: NDArray[np.float64]
    singular_values: NDArray[np.float64]
    order: int
    method: str
    error_bound: float | None = None
    regularization: float = 0.0
    feedthrough_shift: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))
    dof_scale: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    low_frequency_weight: float | None = None
    note: str = ""

    def poles(self) -> NDArray[np.complex128]:
        """Eigenvalues of ``a`` (rad/s)."""
        return np.linalg.eigvals(self.a) if self.order else np.empty(0, dtype=complex)

    def is_stable(self) -> bool:
        """True when every pole of the reduced model has a negative real part."""
        return bool(np.all(self.poles().real < 0))

    def frequency_response(self, omega: ArrayLike) -> NDArray[np.complex128]:
        """G_r(jω), shape (len(omega), p, m)."""
        return frequency_response(self.a, self.b, self.c, self.d, omega)


# --------------------------------------------------------------------------- balancing


@dataclass(frozen=True)
class _Balanced:
    """The balanced realization up to the numerical rank (truncations are its leading
    blocks) and the balancing singular values."""

    a: NDArray
    b: NDArray
    c: NDArray
    d: NDArray
    sigma: NDArray  # all n values, zeros past the rank
    rank: int

    def truncated(self, r: int) -> tuple[NDArray, NDArray, NDArray]:
        return self.a[:r, :r].copy(), self.b[:r].copy(), self.c[:, :r].copy()


def _balance(a: NDArray, b: NDArray, c: NDArray, d: NDArray, m: NDArray, n: NDArray) -> _Balanced:
    """Square-root balancing of (M, N): T = Σ^{-1/2} Uᵀ L_Nᵀ, T⁻¹ = L_M V Σ^{-1/2}."""
    l_m, l_n = _psd_factor(m), _psd_factor(n)
    u, sigma, vt = _balancing_svd(l_m, l_n)
    if sigma.size == 0 or sigma[0] <= 0:
        raise FitError("the model has no controllable and observable state: G(s) = D")
    rank = int(np.count_nonzero(sigma > RANK_RTOL * sigma[0]))
    root = np.sqrt(sigma[:rank])
    left = (l_n @ u[:, :rank]) / root  # Tᵀ
    right = (l_m @ vt[:rank].T) / root  # T⁻¹
    return _Balanced(left.T @ a @ right, left.T @ b, c @ right, d, _padded(sigma, a.shape[0]), rank)


def _gramian_pair(
    method: str,
    a: NDArray,
    b: NDArray,
    c: NDArray,
    reg: _Regularised | None,
    weight: float | None = None,
) -> tuple[NDArray, NDArray]:
    """(M, N) of the method: M transforms as T M Tᵀ, N as T⁻ᵀ N T⁻¹.

    With a low-frequency ``weight`` ω₀ the Lyapunov gramians are those of the augmented
    model (module docstring): P of the input matrix [B, ω₀ A⁻¹B], Q of the output matrix
    [C; ω₀ C A⁻¹]. The Riccati gramians are never weighted.
    """
    p_input, q_output = b, c
    if weight:
        p_input = np.hstack([b, weight * np.linalg.solve(a, b)])
        q_output = np.vstack([c, weight * np.linalg.solve(a.T, c.T).T])
    if method == "lyapunov":
        return _lyapunov_p(a, p_input), _lyapunov_p(a.T, q_output.T)
    assert reg is not None
    which = {"riccati": "ro", "mixed": "o", "mixed-rq": "r"}[method]
    r, o = _pr_gramians(a, b, c, reg, which)
    m = _lyapunov_p(a, p_input) if r is None else r
    n = _lyapunov_p(a.T, q_output.T) if o is None else o
    return m, n


def glover_bound(sigma: ArrayLike, order: int) -> float:
    """2 Σ σ_k over the distinct values among σ_{order+1} … σ_n (Glover 1984).

    The H∞ bound of Lyapunov balanced truncation, ‖G − G_r‖∞ ≤ 2 Σ_{distinct k>r} σ_k
    (Unneland (2007) eq. 5.22 omits the factor 2, an erratum). Values closer than
    :data:`DISTINCT_RTOL` (relative) count once. NaN when ``order`` splits a group of equal
    values (the bound does not apply).

    Examples
    --------
    >>> glover_bound([3.0, 2.0, 0.5, 0.5, 0.1], 2)
    1.2
    """
    s = np.asarray(sigma, dtype=float)
    if not 0 <= order <= s.size:
        raise FitError(f"order {order} is out of range 0 … {s.size}")
    if order == s.size:
        return 0.0
    if order > 0 and _same(s[order - 1], s[order], s[0]):
        return math.nan
    tail = s[order:]
    distinct = [tail[0]]
    for value in tail[1:]:
        if not _same(distinct[-1], value, s[0]):
            distinct.append(value)
    return float(2.0 * np.sum(distinct))


def _same(x: float, y: float, top: float) -> bool:
    return abs(x - y) <= DISTINCT_RTOL * max(abs(x), abs(y)) + RANK_RTOL * abs(top)


def balanced_truncation(
    a: ArrayLike,
    b: ArrayLike,
    c: ArrayLike,
    d: ArrayLike | None = None,
    *,
    order: int | None = None,
    tol: float | None = None,
    method: str = "lyapunov",
    regularization: float = DEFAULT_REGULARIZATION,
    low_frequency_weight: float | None = None,
) -> BalancedTruncation:
    """Reduce a stable continuous-time model by balanced truncation (Unneland (2007) Ch. 5).

    Square-root form of Unneland (2007) Table 5.1 with the (M, N) pair of ``method``
    (package docstring): Lyapunov (eqs. 5.15–5.16), Riccati / positive-real (eqs. 5.43–5.47),
    mixed (P, O) (eqs. 5.83–5.84, Theorem 5.1) or mixed (R, Q) (eqs. 5.85–5.86). For a
    strictly proper model the PR methods use the regularised feedthrough D_ε and
    guarantee G_r + G_rᴴ ⪰ −2 D_ε (:mod:`~cummins.radiation.reduce.gramians`).

    Parameters
    ----------
    a, b, c, d
        The model: A (n, n) with every eigenvalue in the open left half-plane, B (n, m),
        C (p, n), D (p, m) (default zero). 1-D ``b``, ``c`` are a column and a row.
    order
        Number of states kept, 1 … n (lowered, with a note, to the numerical rank).
    tol
        Instead of ``order``: the smallest order whose relative H∞ error is at most
        ``tol`` (guaranteed bound for ``"lyapunov"``, measured on a sweep for the PR
        methods; module docstring).
    method
        ``"lyapunov"``, ``"riccati"``, ``"mixed"`` (P, O) or ``"mixed-rq"`` (R, Q).
    regularization
        ε of the feedthrough added for the PR Riccati equations when D + Dᵀ is singular
        or small, as a fraction of each DOF's peak |G_ii(jω)| (PR methods only; 0: no
        regularisation, a singular D + Dᵀ is then an error).
    low_frequency_weight
        ω₀ (rad/s) of the low-frequency weighting (module docstring); None: unweighted.

    Returns
    -------
    BalancedTruncation
        The reduced matrices, Σ, the bound (Lyapunov) and the regularisation used.

    Raises
    ------
    FitError
        Unstable A, inconsistent shapes, NaN, order out of range, both or neither of
        ``order`` and ``tol``, a non-square or non-positive-real model for the PR methods.

    Examples
    --------
    Two modes far apart, K(s) = s/(s² + 0.2 s + 1) + 0.01 s/(s² + 2 s + 100):

    >>> a = [[-0.1, 1, 0, 0], [-1, -0.1, 0, 0], [0, 0, -1, 10], [0, 0, -10, -1]]
    >>> b = [1.0, 0.0, 1.0, 0.0]
    >>> c = [1.0, 0.0, 0.01, 0.0]
    >>> red = balanced_truncation(a, b, c, order=2)
    >>> red.order, bool(red.error_bound < 0.01), red.is_stable()
    (2, True, True)
    """
    _check_method(method)
    _check_order_or_tol(order, tol)
    a, b, c, d = _system(a, b, c, d)
    n = a.shape[0]
    if order is not None:
        order = _checked_order(order, n)
    weight = _checked_weight(low_frequency_weight)
    reg = _regularised(a, b, c, d, regularization) if method in PR_METHODS else None
    balanced = _balance(a, b, c, d, *_gramian_pair(method, a, b, c, reg, weight))
    notes: list[str] = []
    if weight and method == "riccati":
        notes.append("low_frequency_weight ignored: both Riccati gramians are unweighted")
    if reg is not None and reg.delta > 0:
        notes.append(
            f"D + Dᵀ regularised with D_ε = {reg.delta:.3g} S⁻² (DOF-scaled feedthrough "
            f"{reg.delta:.3g} I): G_r + G_rᴴ ⪰ −2 D_ε"
        )
    if order is None:
        r = _order_for_tol(balanced, method, float(tol))
    else:
        r = order
        if r > balanced.rank:
            notes.append(
                f"order lowered from {r} to {balanced.rank}, the numerical rank "
                f"(σ_{balanced.rank + 1}/σ_1 ≤ {RANK_RTOL:g})"
            )
            r = balanced.rank
    bound = glover_bound(balanced.sigma, r) if method == "lyapunov" else None
    if r < n and _same(balanced.sigma[r - 1], balanced.sigma[r], balanced.sigma[0]):
        notes.append(
            f"order {r} splits a group of equal singular values (σ = {balanced.sigma[r]:.6g}): "
            "stability and the error bound are not guaranteed; choose an order between groups"
        )
    a_r, b_r, c_r = balanced.truncated(r)
    if np.any(np.linalg.eigvals(a_r).real >= 0):
        notes.append("the truncation is not stable")
    return BalancedTruncation(
        a=a_r,
        b=b_r,
        c=c_r,
        d=d.copy(),
        singular_values=balanced.sigma,
        order=r,
        method=method,
        error_bound=bound,
        regularization=0.0 if reg is None else reg.delta,
        feedthrough_shift=np.zeros((0, 0)) if reg is None else reg.shift,
        dof_scale=np.zeros(0) if reg is None else reg.scale,
        low_frequency_weight=None if method == "riccati" else weight,
        note="; ".join(notes),
    )


def _order_for_tol(balanced: _Balanced, method: str, tol: float) -> int:
    """Smallest order meeting ``tol`` relative to ‖G‖∞ (module docstring)."""
    sigma, rank = balanced.sigma, balanced.rank
    a_full, b_full, c_full = balanced.truncated(rank)
    norm = hinf_norm(a_full, b_full, c_full, balanced.d)[0]
    if norm == 0:
        return 1
    if method == "lyapunov":
        for r in range(1, rank + 1):
            bound = glover_bound(sigma, r)
            if not math.isnan(bound) and bound <= tol * norm:
                return r
        return rank
    grid = _sweep(np.linalg.eigvals(a_full))
    full = frequency_response(a_full, b_full, c_full, balanced.d, grid)

    def meets(r: int) -> bool:
        reduced = frequency_response(*balanced.truncated(r), balanced.d, grid)
        return float(_gain(full - reduced).max()) <= tol * norm

    lo, hi = 1, rank  # meets(rank) holds: the balanced realization is exact
    while lo < hi:
        mid = (lo + hi) // 2
        if meets(mid):
            hi = mid
        else:
            lo = mid + 1
    return lo
