"""The gramians of balanced truncation: Lyapunov and positive-real (Riccati).

The pair (M, N) balanced by :mod:`~cummins.radiation.reduce.balancing` is made of these:
the controllability and observability gramians P, Q of the Lyapunov equations
(Unneland (2007) eqs. 5.15–5.16), whose balancing gives the Hankel singular values, and
the minimal solutions R_min, O_min of the positive-real Riccati equations (eqs.
5.43–5.44; Desai & Pal 1984, Green 1988), for which Σ ≤ I (eq. 5.47).

Strictly proper models (D = 0): regularisation
----------------------------------------------
Every radiation model is strictly proper (K(s) = C (sI − A)⁻¹ B, A∞ kept apart), so
D + Dᵀ = 0 and eqs. 5.43–5.44 are singular (Unneland (2007) does not discuss this: the
reduced models of the thesis come from Hankel realizations, whose D ≠ 0). The Riccati and
mixed methods then balance the regularised model G_ε(s) = G(s) + D_ε with the
feedthrough D_ε = δ S⁻², where S = diag(s_i), s_i = 1/√(max_ω |G_ii(jω)|), scales the
DOFs so that every diagonal term peaks at 1, and δ = ε − λ_min(S (D + Dᵀ) S)/2 tops the
scaled feedthrough up to ε I (ε = ``regularization``, default
:data:`DEFAULT_REGULARIZATION`; no regularisation when S D S is already ⪰ ε I). The
Riccati equations are invariant under this congruence, so they are solved on the
scaled model (better conditioned when the DOFs differ by orders of magnitude). If G is
PR, G_ε is strictly PR, its truncations G_ε,r are PR at every order, and the returned
model G_r = G_ε,r − D_ε (its D is the original D) satisfies, exactly,

    G_r(jω) + G_r(jω)ᴴ ⪰ −2 D_ε   for all ω,

i.e. for a SISO model Re G_r(jω) ≥ −ε max_ω |G(jω)|, and for a MIMO model the
DOF-scaled S (G_r + G_rᴴ) S ⪰ −2ε I. The violation is at most ε of the peak response; an
exact passivity enforcement must follow when exact positive realness is needed. A
smaller ε makes the violation smaller and the Riccati equations worse conditioned: as
ε → 0 the balancing tends to that of the singular PR lemma (X B = Cᵀ) and its leading
singular values approach 1. Riccati truncation of a strictly proper model is often much
less accurate than Lyapunov or mixed truncation (Unneland (2007) Table 5.3; the tanker's
heave kernel at 2 states: R² of B 0.63 against 0.99). ``regularization=0`` refuses to
regularise (a singular D + Dᵀ is then an error).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from cummins.errors import FitError
from cummins.radiation.reduce.system import _dof_scale, _system

#: Default ε of the regularising feedthrough for a singular D + Dᵀ (DOF-scaled units:
#: a fraction of each diagonal term's peak |G_ii(jω)|).
DEFAULT_REGULARIZATION = 1e-3
#: A Riccati solution whose smallest eigenvalue is below −PSD_RTOL times its largest
#: is not positive semidefinite: the model is not positive real.
PSD_RTOL = 1e-8
#: Largest relative residual accepted from the Riccati solver.
RICCATI_RTOL = 1e-6


# --------------------------------------------------------------------------- gramians


def lyapunov_gramians(
    a: ArrayLike, b: ArrayLike, c: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Controllability and observability gramians (P, Q) of a stable model.

    A P + P Aᵀ + B Bᵀ = 0 and Aᵀ Q + Q A + Cᵀ C = 0 (Unneland (2007) eqs. 5.15–5.16), by
    Bartels–Stewart (``scipy.linalg.solve_continuous_lyapunov``), symmetrised.
    """
    a, b, c, _ = _system(a, b, c)
    return _lyapunov_p(a, b), _lyapunov_p(a.T, c.T)


def _lyapunov_p(a: NDArray, b: NDArray) -> NDArray:
    p = scipy.linalg.solve_continuous_lyapunov(a, -b @ b.T)
    return 0.5 * (p + p.T)


def _psd_factor(x: NDArray) -> NDArray:
    """L (n × k) with L Lᵀ = X for a symmetric positive semidefinite X, from its
    eigen-decomposition; eigenvalues at rounding level (or negative) are dropped, so L
    has as many columns as X has numerically positive eigenvalues."""
    lam, v = np.linalg.eigh(0.5 * (x + x.T))
    top = max(float(lam[-1]), 0.0)
    keep = lam > top * x.shape[0] * np.finfo(float).eps
    return v[:, keep] * np.sqrt(lam[keep])


def hankel_singular_values(a: ArrayLike, b: ArrayLike, c: ArrayLike) -> NDArray[np.float64]:
    """Hankel singular values σ₁ ≥ … ≥ σ_n of a stable model (√eig(P Q), eqs. 5.15–5.16).

    Computed as the singular values of L_Qᵀ L_P (L the square-root factors of the
    gramians), never from the product P Q; zeros past the numerical rank.

    Examples
    --------
    K(s) = 1/(s + 1): P = Q = 1/2, σ₁ = 1/2.

    >>> hankel_singular_values([[-1.0]], [[1.0]], [[1.0]])
    array([0.5])
    """
    p, q = lyapunov_gramians(a, b, c)
    return _padded(_balancing_svd(_psd_factor(p), _psd_factor(q))[1], p.shape[0])


def _padded(sigma: NDArray, n: int) -> NDArray:
    out = np.zeros(n)
    out[: min(sigma.size, n)] = sigma[:n]
    return out


def _riccati(a: NDArray, b: NDArray, c: NDArray, r: NDArray, which: str) -> NDArray:
    """Minimal solution X of Aᵀ X + X A + (X B − Cᵀ) R⁻¹ (Bᵀ X − C) = 0, R = D + Dᵀ ≻ 0.

    scipy's ``solve_continuous_are`` solves Aᵀ X + X A − (X B + S) R̃⁻¹ (Bᵀ X + Sᵀ) + Q = 0
    for its stabilising solution; with Q = 0, S = −Cᵀ and R̃ = −(D + Dᵀ) it is eq. 5.44,
    and for a PR model the stabilising solution is the minimal one (O_min; Willems
    1971), which Σ ≤ I confirms (tested).
    """
    n = a.shape[0]
    try:
        x = scipy.linalg.solve_continuous_are(a, b, np.zeros((n, n)), -r, s=-c.T)
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise FitError(
            f"the positive-real Riccati equation ({which}) has no stabilising solution "
            f"({exc}); the model is probably not positive real"
        ) from exc
    x = 0.5 * (x + x.T)
    quadratic = (x @ b - c.T) @ np.linalg.solve(r, b.T @ x - c)
    linear = a.T @ x
    residual = np.linalg.norm(linear + linear.T + quadratic, 1)
    scale = 2 * np.linalg.norm(linear, 1) + np.linalg.norm(quadratic, 1)
    if not np.all(np.isfinite(x)) or residual > RICCATI_RTOL * max(scale, np.finfo(float).tiny):
        raise FitError(
            f"the positive-real Riccati equation ({which}) was not solved accurately "
            f"(relative residual {residual / scale:.2g}); the model is probably not "
            "positive real, or too close to the boundary: raise regularization"
        )
    lam = np.linalg.eigvalsh(x)
    if lam[0] < -PSD_RTOL * max(abs(lam[-1]), np.finfo(float).tiny):
        raise FitError(
            f"the positive-real Riccati equation ({which}) has an indefinite solution "
            f"(eigenvalues {lam[0]:.3g} … {lam[-1]:.3g}): the model is not positive real"
        )
    return x


@dataclass(frozen=True)
class _Regularised:
    """The feedthrough used in the PR Riccati equations and how it was chosen."""

    d: NDArray  # D + D_ε
    shift: NDArray  # D_ε
    delta: float
    scale: NDArray  # s_i


def _regularised(
    a: NDArray, b: NDArray, c: NDArray, d: NDArray, regularization: float
) -> _Regularised:
    """D + D_ε with D_ε = δ S⁻², δ = max(0, ε − λ_min(S (D + Dᵀ) S)/2) (module docstring)."""
    if c.shape[0] != b.shape[1]:
        raise FitError(
            f"positive-real balancing needs a square model (as many outputs as inputs), "
            f"not {c.shape[0]} × {b.shape[1]}"
        )
    if not (isinstance(regularization, int | float) and 0 <= regularization < math.inf):
        raise FitError(f"regularization must be ≥ 0, not {regularization!r}")
    s = _dof_scale(a, b, c, d)
    lowest = float(np.linalg.eigvalsh(s[:, None] * (d + d.T) * s[None, :])[0]) / 2
    delta = max(0.0, float(regularization) - lowest) if regularization > 0 else 0.0
    if lowest <= 0 and delta == 0:
        raise FitError(
            "D + Dᵀ is singular (a strictly proper model): the positive-real Riccati "
            "equations need regularization > 0"
        )
    shift = np.diag(delta / s**2)
    return _Regularised(d + shift, shift, delta, s)


def positive_real_gramians(
    a: ArrayLike,
    b: ArrayLike,
    c: ArrayLike,
    d: ArrayLike | None = None,
    *,
    regularization: float = DEFAULT_REGULARIZATION,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Minimal solutions (R_min, O_min) of the PR Riccati equations and the D_ε used.

    A R + R Aᵀ + (R Cᵀ − B)(D + Dᵀ)⁻¹(C R − Bᵀ) = 0 (Unneland (2007) eq. 5.43, required-supply
    gramian) and Aᵀ O + O A + (O B − Cᵀ)(D + Dᵀ)⁻¹(Bᵀ O − C) = 0 (eq. 5.44,
    available-storage gramian), with D replaced by D + D_ε when D + Dᵀ is singular or
    small (module docstring). R_min = O_max⁻¹, so √eig(R_min O_min) ≤ 1 (eq. 5.47).

    Returns
    -------
    (R_min, O_min, D_ε)

    Raises
    ------
    FitError
        When the model (with D + D_ε) is not positive real: no stabilising or no
        positive semidefinite solution.
    """
    a, b, c, d = _system(a, b, c, d)
    reg = _regularised(a, b, c, d, regularization)
    r, o = _pr_gramians(a, b, c, reg)
    assert r is not None and o is not None
    return r, o, reg.shift


def _pr_gramians(
    a: NDArray, b: NDArray, c: NDArray, reg: _Regularised, which: str = "ro"
) -> tuple[NDArray | None, NDArray | None]:
    """(R_min, O_min) solved on the DOF-scaled model (B S, S C, S D S): the equations are
    invariant under this congruence and better conditioned. Only those in ``which``."""
    s = reg.scale
    bs, cs = b * s[None, :], s[:, None] * c
    sym = s[:, None] * (reg.d + reg.d.T) * s[None, :]
    o = _riccati(a, bs, cs, sym, "available storage O, eq. 5.44") if "o" in which else None
    r = _riccati(a.T, cs.T, bs.T, sym, "required supply R, eq. 5.43") if "r" in which else None
    return r, o


def _balancing_svd(l_m: NDArray, l_n: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """U, Σ, Vᵀ of L_Nᵀ L_M (the square-root form of Table 5.1, step 3)."""
    if l_m.shape[1] == 0 or l_n.shape[1] == 0:
        return np.zeros((l_n.shape[1], 0)), np.zeros(0), np.zeros((0, l_m.shape[1]))
    return np.linalg.svd(l_n.T @ l_m, full_matrices=False)
