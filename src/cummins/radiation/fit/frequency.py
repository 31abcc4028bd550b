"""Frequency-domain identification of one coupling K_ij(s) of the fluid memory.

Model structure (Unneland (2007) §3.3, eq. 3.61): a strictly proper rational function of order
n with relative degree one, a zero at s = 0 and a Hurwitz denominator,

    K(s) = (b_{n−1} s^{n−1} + … + b₁ s) / (s^n + a_{n−1} s^{n−1} + … + a₀),

fitted to K(jω) = B(ω) + jω (A(ω) − A∞) at the data frequencies. Three steps:

1. **Levy's linearised least squares** (Unneland (2007) eq. 4.35): minimise Σ |N(jω) − K D(jω)|²,
   linear in the coefficients, then **Sanathanan–Koerner iterations**, which divide each
   equation by |D(jω)| of the previous iterate so that the linearised error tends to the
   true error N/D − K. Frequencies are scaled by ω_s = √(ω_min ω_max) for conditioning.
2. The poles (roots of D) are made stable — unstable ones are reflected into the left
   half-plane — and written in a parameterisation that cannot leave it: real poles −e^u,
   complex pairs −e^u ± j v.
3. **Nonlinear refinement** (``scipy.optimize.least_squares``) of the pole parameters by
   variable projection: for given poles the residues (and A∞, when it is estimated
   jointly) follow from a linear least-squares problem with the constraint K(0) = 0, so
   only the poles are iterated. The residual is the misfit in B and in A, each divided by
   the spread of the data, so that the fit aims directly at the R² of A and of B.

A∞ can be estimated jointly (Perez & Fossen's idea of fitting the added mass with its
high-frequency limit): A(ω) = A∞ + Im K(jω)/ω is linear in A∞, which simply becomes one
more linear unknown of step 3. For a diagonal coupling the fit can be required to be
positive real (Re K(jω) ≥ 0 at all frequencies, Unneland (2007) Prop. 3.4): the residues are
then re-solved with the poles fixed, minimising the same misfit subject to Re K(jω) ≥ 0
on a dense grid from 10⁻³ ω_min to 10³ ω_max (a small quadratic programme), until the
exact positive-real test passes.

Only stable models leave this module (a :class:`~cummins.errors.FitError` otherwise).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import least_squares, minimize, minimize_scalar

from cummins.errors import FitError

#: Iterations of the Sanathanan–Koerner loop.
SK_ITERATIONS = 15
#: Smallest relative damping |Re p| / |Im p| of a complex pole: radiation memory has no
#: undamped modes, and a needle-sharp resonance fitted to noise would break passivity.
STABILITY_MARGIN = 1e-2
#: Smallest decay rate of any pole, in units of the scaling frequency ω_s.
MIN_DECAY = 1e-6
#: Default total weight of the motion-error equations against the R² ones
#: (``error_emphasis`` of :func:`fit_frequency_domain`).
ERROR_EMPHASIS = 10.0
#: Positive realness is tested as Re K(jω) ≥ −PR_TOLERANCE · max_ω |K(jω)|: a negative
#: real part a million times smaller than the memory force itself is rounding, not energy.
PR_TOLERANCE = 1e-6


@dataclass(frozen=True)
class FrequencyFit:
    """Result of fitting one coupling in the frequency domain.

    Attributes
    ----------
    poles, residues
        K(s) = Σ r/(s − p) (complex pairs both listed), rad/s and force/velocity·rad/s.
    added_mass_inf
        A∞ used (given) or estimated jointly.
    order
        Number of poles.
    r2_added_mass, r2_damping
        R² of A(ω) and B(ω) at the fitted frequencies.
    passive
        Re K(jω) ≥ 0 for all ω (exact test), for any coupling (meaningful on diagonals).
    note
        What happened (poles reflected, passivity penalty active …).
    """

    poles: NDArray[np.complex128]
    residues: NDArray[np.complex128]
    added_mass_inf: float
    order: int
    r2_added_mass: float
    r2_damping: float
    passive: bool
    note: str = ""

    def frequency_response(self, omega: ArrayLike) -> NDArray[np.complex128]:
        """K(jω) of the fitted model."""
        s = 1j * np.asarray(omega, dtype=float)
        return (self.residues[None, :] / (s[:, None] - self.poles[None, :])).sum(axis=1)


def r_squared(y: ArrayLike, y_model: ArrayLike, floor: float = 0.0) -> float:
    """Coefficient of determination 1 − Σ(y − ŷ)² / Σ(y − ȳ)² (Unneland (2007) eq. 6.19);
    with ``floor``, the variance of y is taken as at least ``floor`` (a direction of a pair
    fitted as given that is small beside the other is judged at the pair's spread)."""
    y = np.asarray(y, dtype=float)
    return r_squared_of(y, y_model, total_variation(y, floor))


def total_variation(y: NDArray, floor: float = 0.0) -> float:
    """Σ(y − ȳ)², at least n × ``floor``: the denominator of :func:`r_squared`."""
    return max(float(np.sum((y - y.mean()) ** 2)), y.size * floor)


def r_squared_of(y: NDArray, y_model: ArrayLike, total: float) -> float:
    """:func:`r_squared` with its denominator ``total`` (:func:`total_variation`) given:
    the same for every model of the same data."""
    y_model = np.asarray(y_model, dtype=float)
    if total == 0:
        return 1.0 if np.allclose(y, y_model) else 0.0
    return float(1.0 - np.sum((y - y_model) ** 2) / total)


# --------------------------------------------------------------------------- step 1


def _levy_sanathanan_koerner(x: NDArray, y: NDArray, w_re: NDArray, w_im: NDArray, n: int):
    """Denominator coefficients (monic, ascending) by Levy + SK iterations, scaled units."""
    s = 1j * x
    # unknowns: b_1 … b_{n-1} (numerator, zero at 0), a_0 … a_{n-1} (denominator)
    num_basis = np.stack([s**k for k in range(1, n)], axis=1) if n > 1 else np.zeros((x.size, 0))
    den_basis = np.stack([s**k for k in range(n)], axis=1)
    phi = np.hstack([num_basis, -y[:, None] * den_basis])
    target = y * s**n
    weight = np.ones(x.size)
    a = np.zeros(n)
    for _ in range(SK_ITERATIONS):
        rows = np.vstack([phi.real * (w_re * weight)[:, None], phi.imag * (w_im * weight)[:, None]])
        rhs = np.concatenate([target.real * w_re * weight, target.imag * w_im * weight])
        theta, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
        a_new = theta[n - 1 :]
        d = s**n + den_basis @ a_new
        weight = 1.0 / np.maximum(np.abs(d), 1e-12 * np.abs(d).max())
        converged = np.allclose(a_new, a, rtol=1e-8, atol=1e-12)
        a = a_new
        if converged:
            break
    return a


def _stable_poles(a: NDArray) -> tuple[NDArray, list[str]]:
    """Roots of s^n + Σ a_k s^k, unstable ones reflected into the left half-plane."""
    poles = np.roots(np.r_[1.0, a[::-1]])
    notes = []
    unstable = poles.real >= 0
    if unstable.any():
        notes.append(f"{int(unstable.sum())} unstable pole(s) of the linear fit reflected")
    re = -np.maximum(np.abs(poles.real), STABILITY_MARGIN * np.abs(poles.imag) + MIN_DECAY)
    return re + 1j * poles.imag, notes


# --------------------------------------------------------------------------- step 3


def _pole_parameters(poles: NDArray) -> tuple[NDArray, int]:
    """(u…, v…) with real poles −e^u first, then complex pairs −e^u + j v (v > 0)."""
    real = np.sort(poles[np.abs(poles.imag) <= 1e-9 * np.abs(poles)].real)
    cplx = poles[poles.imag > 1e-9 * np.abs(poles)]
    n_real = real.size
    decay_real = np.maximum(-real - MIN_DECAY, 1e-12)
    decay_cplx = np.maximum(-cplx.real - STABILITY_MARGIN * np.abs(cplx.imag) - MIN_DECAY, 1e-12)
    params = np.r_[np.log(decay_real), np.log(decay_cplx), cplx.imag]
    return params, n_real


def _parameter_bounds(size: int, n_real: int) -> tuple[NDArray, NDArray]:
    """Bounds keeping the poles within 10⁻⁸…10⁴ of the scaling frequency (scaled units)."""
    n_cplx = (size - n_real) // 2
    lower = np.r_[np.full(n_real + n_cplx, np.log(1e-8)), np.full(n_cplx, -1e4)]
    upper = np.r_[np.full(n_real + n_cplx, np.log(1e4)), np.full(n_cplx, 1e4)]
    return lower, upper


def _poles_from_parameters(params: NDArray, n_real: int) -> NDArray:
    n_cplx = (params.size - n_real) // 2
    real = -(np.exp(params[:n_real]) + MIN_DECAY)
    omega = params[n_real + n_cplx :]
    decay = np.exp(params[n_real : n_real + n_cplx])
    sigma = -(decay + STABILITY_MARGIN * np.abs(omega) + MIN_DECAY)
    return np.r_[real, sigma + 1j * omega, sigma - 1j * omega].astype(complex)


def _basis(poles: NDArray, s: NDArray, n_real: int) -> NDArray:
    """Real-coefficient basis of Σ r/(s − p): columns for real poles, then (Re r, Im r) pairs."""
    n_cplx = (poles.size - n_real) // 2
    out = np.empty((s.size, n_real + 2 * n_cplx), dtype=complex)
    out[:, :n_real] = 1.0 / (s[:, None] - poles[None, :n_real])
    upper = poles[n_real : n_real + n_cplx]
    inv_upper = 1.0 / (s[:, None] - upper[None, :])
    inv_lower = 1.0 / (s[:, None] - np.conj(upper)[None, :])
    out[:, n_real::2] = inv_upper + inv_lower  # coefficient Re r
    out[:, n_real + 1 :: 2] = 1j * (inv_upper - inv_lower)  # coefficient Im r
    return out


def _residues(coef: NDArray, poles: NDArray, n_real: int) -> NDArray:
    n_cplx = (poles.size - n_real) // 2
    real = coef[:n_real].astype(complex)
    pairs = coef[n_real:].reshape(n_cplx, 2)
    r = pairs[:, 0] + 1j * pairs[:, 1]
    return np.r_[real, r, np.conj(r)]


@dataclass(frozen=True)
class _Problem:
    """Everything the variable-projection residual needs (scaled units)."""

    x: NDArray  # ω/ω_s
    a_data: NDArray  # (A − A∞_ref)·ω_s/κ  (scaled "added mass deviation")
    b_data: NDArray  # B/κ
    sigma_a: NDArray  # per frequency: σ_A / weight
    sigma_b: NDArray  # per frequency: σ_B / weight
    joint: bool
    dense: NDArray  # dense frequencies for the passivity constraints (scaled)
    prior_weight: float = 0.0  # weight of the row δ = 0 tying A∞ to its starting value


def _linear_system(problem: _Problem, poles: NDArray, n_real: int):
    """Weighted least-squares system (matrix, rhs) and null-space basis of K(0) = 0."""
    s = 1j * problem.x
    basis = _basis(poles, s, n_real)  # K(jx) = basis @ coef
    # rows: B misfit (Re K − B)/σ_B, A misfit (Im K/x + δ − A)/σ_A  (δ: A∞ correction)
    rows_b = basis.real / problem.sigma_b[:, None]
    rows_a = (basis.imag / problem.x[:, None]) / problem.sigma_a[:, None]
    if problem.joint:
        rows_b = np.hstack([rows_b, np.zeros((s.size, 1))])
        rows_a = np.hstack([rows_a, (1.0 / problem.sigma_a)[:, None]])
    matrix = np.vstack([rows_b, rows_a])
    rhs = np.r_[problem.b_data / problem.sigma_b, problem.a_data / problem.sigma_a]
    if problem.joint and problem.prior_weight > 0:
        prior = np.zeros((1, matrix.shape[1]))
        prior[0, -1] = problem.prior_weight
        matrix = np.vstack([matrix, prior])
        rhs = np.r_[rhs, 0.0]
    # K(0) = Σ r/(−p) = 0: the basis at s = 0, real part (the imaginary part is 0 by symmetry)
    constraint = _basis(poles, np.array([0.0 + 0.0j]), n_real).real
    if problem.joint:
        constraint = np.hstack([constraint, np.zeros((1, 1))])
    return matrix, rhs, _constraint_basis(constraint[0])


def _constraint_basis(c: NDArray) -> NDArray:
    """Basis N of {x : c·x = 0}: eliminate the largest component of c (cheaper than an SVD)."""
    k = int(np.argmax(np.abs(c)))
    n = c.size
    basis = np.zeros((n, n - 1))
    others = np.delete(np.arange(n), k)
    basis[others, np.arange(n - 1)] = 1.0
    basis[k, :] = -c[others] / c[k]
    return basis


def _linear_solution(problem: _Problem, poles: NDArray, n_real: int):
    """Residue coefficients (and A∞ offset) minimising the weighted misfit, K(0) = 0."""
    matrix, rhs, free = _linear_system(problem, poles, n_real)
    z, *_ = np.linalg.lstsq(matrix @ free, rhs, rcond=None)
    coef = free @ z
    return coef, matrix @ coef - rhs


def _passive_solution(problem: _Problem, poles: NDArray, n_real: int, extra: NDArray):
    """Residues minimising the misfit subject to Re K(jω) ≥ 0 on a dense grid (and at
    ``extra`` frequencies, scaled), with K(0) = 0: residue perturbation for passivity."""
    matrix, rhs, free = _linear_system(problem, poles, n_real)
    resonances = [
        np.abs(p.imag) + np.abs(p.real) * np.linspace(-10.0, 10.0, 41) for p in poles if p.imag > 0
    ]
    grid = np.concatenate([problem.dense, extra, *resonances])
    grid = np.unique(grid[grid > 0])
    rows = _basis(poles, 1j * grid, n_real).real
    if problem.joint:
        rows = np.hstack([rows, np.zeros((grid.size, 1))])
    norms = np.linalg.norm(rows, axis=1, keepdims=True)
    g = (rows / np.where(norms > 0, norms, 1.0)) @ free
    m = matrix @ free
    z0, *_ = np.linalg.lstsq(m, rhs, rcond=None)
    scale = float(np.linalg.norm(rhs)) or 1.0
    result = minimize(
        lambda z: np.sum((m @ z - rhs) ** 2) / scale**2,
        z0,
        jac=lambda z: 2 * m.T @ (m @ z - rhs) / scale**2,
        constraints=[{"type": "ineq", "fun": lambda z: g @ z, "jac": lambda z: g}],
        method="SLSQP",
        options={"maxiter": 300, "ftol": 1e-12},
    )
    coef = free @ result.x
    return coef


def _objective(params: NDArray, problem: _Problem, n_real: int) -> NDArray:
    poles = _poles_from_parameters(params, n_real)
    return _linear_solution(problem, poles, n_real)[1]


#: Weight of the equation K(0) = 0 in the variable-projection problem of the nonlinear
#: step (the final residues satisfy it exactly).
CONSTRAINT_WEIGHT = 1e6


def _rows(problem: _Problem, values: NDArray, at_zero: NDArray) -> NDArray:
    """Rows of the weighted least-squares problem for basis columns ``values`` (M × q)
    and their values at s = 0 (q,): B rows, A rows, the K(0) row, the prior row."""
    rows = [
        values.real / problem.sigma_b[:, None],
        values.imag / (problem.x * problem.sigma_a)[:, None],
        CONSTRAINT_WEIGHT * at_zero.real[None, :],
    ]
    if problem.joint and problem.prior_weight > 0:
        rows.append(np.zeros((1, values.shape[1])))
    return np.vstack(rows)


def _varpro(params: NDArray, problem: _Problem, n_real: int) -> tuple[NDArray, NDArray]:
    """Residual and (Kaufman) Jacobian of the variable-projection problem.

    r = Φ(θ) c(θ) − y with c = Φ⁺ y; J ≈ (I − Φ Φ⁺) ∂Φ/∂θ c (Kaufman, 1975), the
    derivatives of the partial-fraction basis being exact: ∂(s − p)⁻¹/∂p = (s − p)⁻².
    """
    poles = _poles_from_parameters(params, n_real)
    s = 1j * problem.x
    zero = np.array([0.0 + 0.0j])
    phi = _rows(problem, _basis(poles, s, n_real), _basis(poles, zero, n_real)[0])
    y = np.r_[problem.b_data / problem.sigma_b, problem.a_data / problem.sigma_a, 0.0]
    if problem.joint:
        extra = np.r_[np.zeros(s.size), 1.0 / problem.sigma_a, 0.0]
        if problem.prior_weight > 0:
            extra = np.r_[extra, problem.prior_weight]
            y = np.r_[y, 0.0]
        phi = np.hstack([phi, extra[:, None]])
    q, r_mat = np.linalg.qr(phi)
    coef = np.linalg.lstsq(r_mat, q.T @ y, rcond=None)[0]
    residual = phi @ coef - y
    n_cplx = (poles.size - n_real) // 2
    jac = np.empty((y.size, params.size))
    for k in range(params.size):
        if k < n_real:  # real pole −(e^u + m)
            p = poles[k]
            dp = -np.exp(params[k])
            g, g0 = 1.0 / (s - p), -1.0 / p
            d = (g**2 * dp)[:, None] * coef[k]
            d0 = np.array([g0**2 * dp * coef[k]])
        else:
            c = (k - n_real) % n_cplx
            p = poles[n_real + c]
            if k < n_real + n_cplx:  # decay parameter u
                dp = -np.exp(params[k]) + 0j
            else:  # frequency parameter v
                dp = -STABILITY_MARGIN * np.sign(params[k]) + 1j
            g, g2 = 1.0 / (s - p), 1.0 / (s - np.conj(p))
            d_first = g**2 * dp + g2**2 * np.conj(dp)
            d_second = 1j * (g**2 * dp - g2**2 * np.conj(dp))
            a0, b0 = 1.0 / p**2, 1.0 / np.conj(p) ** 2
            d0_first = a0 * dp + b0 * np.conj(dp)
            d0_second = 1j * (a0 * dp - b0 * np.conj(dp))
            col = n_real + 2 * c
            d = (d_first * coef[col] + d_second * coef[col + 1])[:, None]
            d0 = np.array([d0_first * coef[col] + d0_second * coef[col + 1]])
        v = _rows(problem, d, d0)[:, 0]  # the prior row does not depend on the poles
        jac[:, k] = v - q @ (q.T @ v)
    return residual, jac


class _VarproCache:
    """Shares one evaluation between least_squares' ``fun`` and ``jac`` calls."""

    def __init__(self, problem: _Problem, n_real: int):
        self.problem, self.n_real, self.key, self.value = problem, n_real, None, None

    def _get(self, params: NDArray):
        key = params.tobytes()
        if key != self.key:
            self.key, self.value = key, _varpro(params, self.problem, self.n_real)
        return self.value

    def residual(self, params: NDArray) -> NDArray:
        return self._get(params)[0]

    def jacobian(self, params: NDArray) -> NDArray:
        return self._get(params)[1]


def _objective_passive(params: NDArray, problem: _Problem, n_real: int, weight: float) -> NDArray:
    """The misfit plus the violations of Re K ≥ 0 on the dense grid, relative to |K| there."""
    poles = _poles_from_parameters(params, n_real)
    coef, misfit = _linear_solution(problem, poles, n_real)
    k = _basis(poles, 1j * problem.dense, n_real) @ coef[: poles.size]
    violation = np.minimum(k.real, 0.0) / np.maximum(np.abs(k), 1e-300)
    return np.r_[misfit, weight * violation]


# --------------------------------------------------------------------------- driver


def fit_frequency_domain(
    omega: ArrayLike,
    added_mass: ArrayLike,
    damping: ArrayLike,
    order: int,
    *,
    added_mass_inf: float | None = None,
    added_mass_inf_guess: float | None = None,
    added_mass_inf_spread: float | None = None,
    passive: bool = False,
    refine: bool | str = "auto",
    target: float = 0.99,
    initial_poles: ArrayLike | None = None,
    weight: ArrayLike | None = None,
    error_weight: ArrayLike | None = None,
    error_emphasis: float = ERROR_EMPHASIS,
) -> FrequencyFit:
    """Fit K(s) of the given order to A(ω), B(ω) of one coupling.

    Parameters
    ----------
    omega
        Frequencies, rad/s (> 0), increasing.
    added_mass, damping
        A(ω) and B(ω) of the coupling at ``omega``.
    order
        Number of poles n ≥ 2.
    added_mass_inf
        A∞ of the coupling; ``None`` estimates it jointly with the model.
    added_mass_inf_guess
        Starting value of A∞ for the joint estimate (e.g. Ogilvie's); default A(ω_max).
    added_mass_inf_spread
        Uncertainty of ``added_mass_inf_guess`` (same units). When given, the joint
        estimate is regularised towards the guess: one more equation (A∞ − guess)/spread
        weighted like all the added-mass equations together, so that the data decide
        where they are informative and the guess where the model would extrapolate.
    passive
        Require Re K(jω) ≥ 0 (diagonal couplings).
    refine
        Run the nonlinear refinement: ``True``, ``False``, or ``"auto"`` (only when the
        linearised fit misses ``target`` or is not passive as required).
    target
        R² of A and B that makes the linearised fit good enough (``refine="auto"``).
    initial_poles
        Start from these poles (rad/s; ``order`` of them, conjugate pairs complete)
        instead of the Levy/Sanathanan–Koerner step.
    weight
        Relative weight of each frequency in the least squares (positive, normalised to
        RMS 1): the frequency weighting W(ω) of Unneland (2007) eq. 4.35. The reported R² stay
        unweighted.
    error_weight
        Weight W(ω) ≥ 0 of the complex error |K̂(jω) − K(jω)| (any unit): the motion
        sensitivity of :mod:`cummins.radiation.fit.motion`. Its equations join those of the R² of
        A and B (which keep the fit sound where the motions are insensitive), scaled so
        that they weigh ``error_emphasis`` times as much in total.
    error_emphasis
        See ``error_weight``.

    Returns
    -------
    FrequencyFit

    Raises
    ------
    FitError
        Too few frequencies for the order, or no stable model could be found.
    """
    w = np.asarray(omega, dtype=float)
    a = np.asarray(added_mass, dtype=float)
    b = np.asarray(damping, dtype=float)
    if order < 2:
        raise FitError("the model order must be at least 2 (a zero at s = 0 and relative degree 1)")
    if w.size < order + 2:
        raise FitError(f"{w.size} frequencies are too few for order {order}")
    joint = added_mass_inf is None
    a_ref = float(
        added_mass_inf_guess
        if joint and added_mass_inf_guess is not None
        else a[-1]
        if joint
        else added_mass_inf
    )
    omega_s = float(np.sqrt(w[0] * w[-1]))
    x = w / omega_s
    k_data = b + 1j * w * (a - a_ref)
    kappa = float(np.abs(k_data).max()) or 1.0
    y = k_data / kappa
    sigma_b = max(float(np.std(b)), 1e-12 * np.abs(b).max(), np.finfo(float).tiny) / kappa
    sigma_a = max(float(np.std(a)), 1e-12 * np.abs(a).max(), np.finfo(float).tiny) * omega_s / kappa
    if weight is None:
        relative = np.ones(w.size)
    else:
        relative = np.asarray(weight, dtype=float).reshape(-1)
        if relative.size != w.size or not np.all(np.isfinite(relative)) or np.any(relative <= 0):
            raise FitError(f"the weights must be {w.size} positive finite numbers")
        relative = relative / np.sqrt(np.mean(relative**2))
    sigma_b, sigma_a = sigma_b / relative, sigma_a / relative
    if error_weight is not None:
        sigma_b, sigma_a = _with_error_weight(
            np.asarray(error_weight, dtype=float).reshape(-1), x, sigma_b, sigma_a, error_emphasis
        )
    # Step 1: Levy + SK on K (weights: B misfit / σ_B, A misfit = Im/ω / σ_A)
    if initial_poles is None:
        den = _levy_sanathanan_koerner(x, y, 1.0 / sigma_b, 1.0 / (x * sigma_a), order)
        poles, notes = _stable_poles(den)
    else:
        start = np.asarray(initial_poles, dtype=complex) / omega_s
        if start.size != order:
            raise FitError(f"{start.size} initial poles for order {order}")
        poles, notes = _stable_poles(np.real(np.poly(start))[1:][::-1])
    params, n_real = _pole_parameters(poles)
    params = np.clip(params, *_parameter_bounds(params.size, n_real))
    problem = _Problem(
        x=x,
        a_data=(a - a_ref) * omega_s / kappa,
        b_data=b / kappa,
        sigma_a=sigma_a,
        sigma_b=sigma_b,
        joint=joint,
        dense=np.geomspace(x[0] * 1e-3, x[-1] * 1e3, 200),
        prior_weight=(
            np.sqrt(x.size) / (added_mass_inf_spread * omega_s / kappa)
            if joint and added_mass_inf_spread
            else 0.0
        ),
    )
    fit = _assemble(params, n_real, problem, omega_s, kappa, a_ref, w, a, b)
    # Step 3: variable projection over the pole parameters (stable by construction)
    good_enough = min(fit.r2_added_mass, fit.r2_damping) >= target and (fit.passive or not passive)
    if refine is True or (refine == "auto" and not good_enough):
        cache = _VarproCache(problem, n_real)
        result = _least_squares(cache.residual, params, n_real, (), jac=cache.jacobian)
        refined = _assemble(result.x, n_real, problem, omega_s, kappa, a_ref, w, a, b)
        if _score(refined) >= _score(fit):
            params, fit = result.x, refined
            notes.append("refined by nonlinear least squares")
    if passive and not fit.passive:
        # move the poles to where a passive fit is good, then fix the residues exactly
        weight = float(np.sqrt(x.size))
        result = _least_squares(_objective_passive, params, n_real, (problem, n_real, weight))
        params = result.x
        fit = _assemble(params, n_real, problem, omega_s, kappa, a_ref, w, a, b)
        notes.append("poles refined with a passivity penalty")
    extra = np.empty(0)
    for attempt in range(4):
        if not passive or fit.passive:
            break
        coef = _passive_solution(problem, _poles_from_parameters(params, n_real), n_real, extra)
        fit = _assemble(params, n_real, problem, omega_s, kappa, a_ref, w, a, b, coef=coef)
        extra = np.r_[extra, _negative_real_part_frequencies(fit) / omega_s]
        if attempt == 0:
            notes.append("residues adjusted for passivity")
    if passive and not fit.passive:
        notes.append("not passive after residue adjustment")
    if not np.all(fit.poles.real < 0):
        raise FitError("no stable model found")
    return FrequencyFit(
        fit.poles,
        fit.residues,
        fit.added_mass_inf,
        fit.order,
        fit.r2_added_mass,
        fit.r2_damping,
        fit.passive,
        "; ".join(notes),
    )


def _with_error_weight(
    weight: NDArray, x: NDArray, sigma_b: NDArray, sigma_a: NDArray, emphasis: float
) -> tuple[NDArray, NDArray]:
    """σ_B, σ_A per frequency with the equations λ W (K̂ − K) added to the R² ones:
    1/σ_B² + (λW)² and 1/σ_A² + (λWx)², λ such that Σ(λW)² = ``emphasis`` Σ 1/σ_B²."""
    if weight.size != x.size or not np.all(np.isfinite(weight)) or np.any(weight < 0):
        raise FitError(f"the error weights must be {x.size} finite numbers ≥ 0")
    sigma_b = np.broadcast_to(sigma_b, x.shape)
    sigma_a = np.broadcast_to(sigma_a, x.shape)
    total = float(np.sum(weight**2))
    if total <= 0:
        return sigma_b, sigma_a
    lam2 = emphasis * float(np.sum(sigma_b**-2.0)) / total
    inv_b = sigma_b**-2.0 + lam2 * weight**2
    inv_a = sigma_a**-2.0 + lam2 * (weight * x) ** 2
    return 1.0 / np.sqrt(inv_b), 1.0 / np.sqrt(inv_a)


def _least_squares(objective, params: NDArray, n_real: int, args: tuple, jac="2-point"):
    """``scipy.optimize.least_squares`` within the pole-parameter bounds.

    The tolerances stop it once the R² no longer changes in the fifth digit; a fit that
    needs more is better served by another order.
    """
    lower, upper = _parameter_bounds(params.size, n_real)
    margin = 1e-9 * (upper - lower)
    start = np.clip(np.nan_to_num(params), lower + margin, upper - margin)
    return least_squares(
        objective,
        start,
        args=args,
        jac=jac,
        method="trf",
        x_scale="jac",
        bounds=(lower, upper),
        ftol=1e-6,
        xtol=1e-6,
        max_nfev=30 * (params.size + 1),
    )


def pruned_poles(poles: ArrayLike, residues: ArrayLike) -> list[NDArray[np.complex128]]:
    """Starting poles for the next lower order, from a fit of order n.

    Each candidate drops one mode: a real pole (giving n − 1 poles), or a complex pair
    replaced by one real pole at its natural frequency (also n − 1). The modes with the
    smallest contribution |r|/|Re p| come first.
    """
    p = np.asarray(poles, dtype=complex)
    r = np.asarray(residues, dtype=complex)
    modes = [k for k in range(p.size) if p[k].imag >= 0]
    modes.sort(key=lambda k: abs(r[k]) / max(abs(p[k].real), 1e-300))
    out = []
    for k in modes:
        if abs(p[k].imag) <= 1e-9 * abs(p[k]):
            out.append(np.delete(p, k))
        else:
            partner = int(np.argmin(np.abs(p - np.conj(p[k])) + (np.arange(p.size) == k) * 1e300))
            rest = np.delete(p, [k, partner])
            out.append(np.r_[rest, -abs(p[k])])
    return out


def _score(fit: FrequencyFit) -> float:
    return min(fit.r2_added_mass, fit.r2_damping)


def _negative_real_part_frequencies(fit: FrequencyFit) -> NDArray:
    """Frequencies (rad/s) where Re K(jω) < 0, on a fine grid around the data (for re-solving)."""
    scale = float(np.abs(fit.poles).max())
    grid = np.geomspace(scale * 1e-4, scale * 1e4, 4000)
    return grid[fit.frequency_response(grid).real < 0]


def _assemble(params, n_real, problem, omega_s, kappa, a_ref, w, a, b, coef=None) -> FrequencyFit:
    poles_scaled = _poles_from_parameters(params, n_real)
    if coef is None:
        coef, _ = _linear_solution(problem, poles_scaled, n_real)
    residues_scaled = _residues(coef[: poles_scaled.size], poles_scaled, n_real)
    a_inf = a_ref + (coef[-1] * kappa / omega_s if problem.joint else 0.0)
    poles = poles_scaled * omega_s
    residues = residues_scaled * kappa * omega_s
    s = 1j * w
    k = (residues[None, :] / (s[:, None] - poles[None, :])).sum(axis=1)
    return FrequencyFit(
        poles=poles,
        residues=residues,
        added_mass_inf=float(a_inf),
        order=poles.size,
        r2_added_mass=r_squared(a, a_inf + k.imag / w),
        r2_damping=r_squared(b, k.real),
        passive=is_positive_real(poles, residues),
    )


def minimum_real_part(poles: ArrayLike, residues: ArrayLike) -> tuple[float, float, float]:
    """min_ω Re K(jω), where it occurs, and max_ω |K(jω)|, for K(s) = Σ r/(s − p).

    K is evaluated in partial fractions (well conditioned whatever the spread of the
    poles) on a logarithmic grid of 100 points per decade from 10⁻³ min|p| to 10³ max|p|,
    refined around every resonance |Im p| ± 10 |Re p|; each local minimum on the grid is
    then polished with a bounded scalar minimisation. Beyond the grid the asymptotes
    Re K ≈ c₀ ω² (ω → 0) and Re K ≈ c∞ / ω² (ω → ∞) decide, with c∞ = −Σ Re(r p).
    """
    return _real_part_search(poles, residues, None)


def _real_part_search(poles: ArrayLike, residues: ArrayLike, tolerance: float | None):
    """:func:`minimum_real_part`; with ``tolerance``, only as far as the verdict
    min Re K ≥ −tolerance · max|K| needs (:func:`is_positive_real`): the polish stops once
    a value below that is found, and a local minimum is not polished where
    :func:`_bracket_floor` proves the bracket stays above it — the same verdict."""
    p = np.asarray(poles, dtype=complex)
    r = np.asarray(residues, dtype=complex)
    if p.size == 0:
        return 0.0, 0.0, 0.0
    mags = np.abs(p)
    hi = mags.max() * 1e3
    lo = max(mags.min() * 1e-3, hi * 1e-14)
    n = int(np.ceil(100 * np.log10(hi / lo)))
    resonances = [abs(q.imag) + abs(q.real) * np.linspace(-10, 10, 81) for q in p if q.imag > 0]
    grid = np.concatenate([np.geomspace(lo, hi, n), *resonances])
    grid = np.unique(grid[grid > 0])
    response = _partial_fractions(r, p, grid)  # K(jω) on the grid, once
    values = np.real(response)
    k_max = float(np.abs(response).max())
    best, where = float(values.min()), float(grid[np.argmin(values)])
    threshold = None if tolerance is None else -tolerance * max(k_max, np.finfo(float).tiny)
    if threshold is not None and best < threshold:
        return best, where, k_max  # the polish only lowers it
    interior = np.flatnonzero((values[1:-1] <= values[:-2]) & (values[1:-1] <= values[2:])) + 1

    def re_k_at(w):  # one frequency: np.sum's reduction, without the arrays' overhead
        return np.add.reduce(r / (1j * w - p), axis=None).real

    for k in interior[np.argsort(values[interior])[:20]]:
        if (
            threshold is not None
            and _bracket_floor(grid[k - 1 : k + 2], values[k - 1 : k + 2], p, r) >= threshold
        ):
            continue  # its polish cannot reach below the verdict's threshold
        res = minimize_scalar(
            re_k_at,
            bounds=(grid[k - 1], grid[k + 1]),
            method="bounded",
            options={"xatol": 1e-10 * grid[k]},
        )
        if res.fun < best:
            best, where = float(res.fun), float(res.x)
            if threshold is not None and best < threshold:
                return best, where, k_max
    c_inf = float(-np.sum((r * p).real))
    if c_inf < 0:  # Re K ≈ c∞/ω² beyond the grid: negative there
        best, where = min(best, c_inf / hi**2), hi
    return best, where, k_max


#: Rows of the grid :func:`_partial_fractions` sums at once: its terms stay in cache.
RESPONSE_ROWS = 256


def _partial_fractions(r: NDArray, p: NDArray, grid: NDArray) -> NDArray[np.complex128]:
    """Σ_k r_k/(jω − p_k) at each ω of ``grid``, by blocks of :data:`RESPONSE_ROWS` rows:
    the numbers of the whole (len(grid), len(p)) array's row sums (each row's own
    pairwise sum), a third of the time for 90 poles on 1500 points (no page faults)."""
    out = np.empty(grid.size, dtype=complex)
    for start in range(0, grid.size, RESPONSE_ROWS):
        rows = grid[start : start + RESPONSE_ROWS, None]
        out[start : start + RESPONSE_ROWS] = (r / (1j * rows - p)).sum(axis=1)
    return out


#: :func:`_bracket_floor`'s allowance for rounding, in units of Σ |r| / dist(p, jω): the
#: grid's values and the polish's each carry a few units of round-off of that sum.
BRACKET_ROUNDING = 1e-9


def _bracket_floor(x: NDArray, values: NDArray, p: NDArray, r: NDArray) -> float:
    """A lower bound of f(ω) = Re K(jω), K(s) = Σ r/(s − p), over ω in [x₀, x₂] from its
    values at the three points x₀ < x₁ < x₂, the larger of two, each less
    :data:`BRACKET_ROUNDING` for the values' and the polish's rounding:

    * the straight line through the values at the ends of [x₀, x₁] and of [x₁, x₂] less
      its interpolation error |f″|/2 · (ω − a)(b − ω) ≤ Σ |r|/d³ · (b − a)²/4
      (|f″| ≤ 2 Σ |r|/d³, d the distance of p from the segment j[x₀, x₂]);
    * the least of the quadratic through the three on the bracket less its interpolation
      error |f‴|/6 · |(ω − x₀)(ω − x₁)(ω − x₂)| ≤ Σ |r|/d⁴ · h³/4 (|f‴| ≤ 6 Σ |r|/d⁴,
      h = x₂ − x₀), the rounding × its Lebesgue constant on the bracket, ≤ h/(x₁ − x₀) +
      h/(x₂ − x₁) + h²/(4 (x₁ − x₀)(x₂ − x₁)).

    −∞ where no bound is had."""
    x0, x1, x2 = (float(v) for v in x)
    v0, v1, v2 = (float(v) for v in values)
    gap = np.maximum(np.maximum(x0 - p.imag, p.imag - x2), 0.0)
    d2 = p.real**2 + gap**2
    if not (np.all(d2 > 0) and np.isfinite(v0 + v1 + v2)):
        return -np.inf
    size = np.abs(r)
    distance = np.sqrt(d2)
    rounding = BRACKET_ROUNDING * float(np.sum(size / distance))
    bend = float(np.sum(size / (d2 * distance))) / 4
    lines = min(v0, v1) - bend * (x1 - x0) ** 2, min(v1, v2) - bend * (x2 - x1) ** 2
    floor = min(lines) - 2.0 * rounding
    h = x2 - x0
    f01 = (v1 - v0) / (x1 - x0)
    curvature = ((v2 - v1) / (x2 - x1) - f01) / h
    low = min(v0, v1, v2)
    if curvature > 0:
        top = min(max(0.5 * (x0 + x1) - f01 / (2 * curvature), x0), x2)
        low = min(low, v0 + f01 * (top - x0) + curvature * (top - x0) * (top - x1))
    spread = h / (x1 - x0) + h / (x2 - x1) + h * h / (4 * (x1 - x0) * (x2 - x1))
    cubic = float(np.sum(size / d2**2)) * h**3 / 4
    quadratic = low - cubic - (2.0 + spread) * rounding
    if np.isfinite(quadratic):
        floor = max(floor, quadratic)
    return floor


def is_positive_real(poles: ArrayLike, residues: ArrayLike) -> bool:
    """Re K(jω) ≥ −PR_TOLERANCE · max|K| for all ω ≥ 0, K(s) = Σ r/(s − p), stable poles.

    See :func:`minimum_real_part` for how the minimum is found.
    """
    poles = np.asarray(poles, dtype=complex)
    if np.any(poles.real >= 0):
        return False
    minimum, _, k_max = _real_part_search(poles, residues, PR_TOLERANCE)
    return bool(minimum >= -PR_TOLERANCE * max(k_max, np.finfo(float).tiny))
