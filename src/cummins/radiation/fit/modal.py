"""Real modal realization of a pole–residue model: K(s) = Σ_r ρ_r / (s − p_r) as (a, b, c).

A retardation function identified as poles and residues (by the frequency-domain fitter,
:mod:`cummins.radiation.fit.frequency`, or from the discrete poles of Kung/ERA and Prony,
:mod:`cummins.radiation.fit.realization`) is realized as a real, block-diagonal, strictly
proper state-space model (D = 0, the structure of Unneland (2007) §3.3, eq. 3.61): one
1×1 block per real pole and one 2×2 block per complex-conjugate pair.
:mod:`cummins.radiation.fit.realization` re-exports :func:`modal_realization`.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from cummins.errors import FitError


def modal_realization(
    poles: ArrayLike, residues: ArrayLike, *, rtol: float = 1e-9
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Real block-diagonal (a, b, c) of K(s) = Σ_r ρ_r / (s − p_r).

    A real pole p with residue ρ gives the 1×1 block a = p, b = √|ρ|, c = sign(ρ) √|ρ|.
    A complex pair p = σ ± jω (ω > 0) with residues α ± jβ gives

        a = [[σ, ω], [−ω, σ]],   b = [g, 0],   c = [2α/g, 2β/g],   g = √(2|ρ|),

    whose transfer function is (2α (s − σ) − 2β ω) / ((s − σ)² + ω²), the sum of the two
    conjugate terms. Blocks appear in the order of the poles (first member of each pair).

    Parameters
    ----------
    poles, residues
        Complex (or real) arrays of equal length. Complex poles must come in conjugate
        pairs with conjugate residues; a pole is taken as real when
        |Im p| ≤ ``rtol`` |p| (its residue's imaginary part is then dropped).
    rtol
        Relative tolerance for "real" and for matching conjugates.

    Returns
    -------
    (a, b, c)
        Shapes (n, n), (n,), (n,).

    Raises
    ------
    FitError
        When a complex pole has no conjugate partner, or its residue is not conjugate.

    Examples
    --------
    K(s) = s/(s² + 2s + 5) has the residue p/(p − p̄) = 0.5 + 0.25j at p = −1 + 2j:

    >>> a, b, c = modal_realization([-1 + 2j, -1 - 2j], [0.5 + 0.25j, 0.5 - 0.25j])
    >>> a
    array([[-1.,  2.],
           [-2., -1.]])
    >>> k_j = c @ np.linalg.solve(1j * np.eye(2) - a, b)  # K(j) = j/(4 + 2j) = 0.1 + 0.2j
    >>> bool(np.isclose(k_j, 0.1 + 0.2j))
    True
    """
    p = np.atleast_1d(np.asarray(poles, dtype=complex)).ravel()
    r = np.atleast_1d(np.asarray(residues, dtype=complex)).ravel()
    if p.shape != r.shape:
        raise FitError(f"{p.size} poles but {r.size} residues; give one residue per pole")
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(r))):
        raise FitError("poles and residues must be finite")
    scale = np.maximum(np.abs(p), np.finfo(float).tiny)
    is_real = np.abs(p.imag) <= rtol * scale
    used = np.zeros(p.size, dtype=bool)
    blocks: list[tuple[NDArray, NDArray, NDArray]] = []
    for k in range(p.size):
        if used[k]:
            continue
        used[k] = True
        if is_real[k]:
            rho = float(r[k].real)
            g = np.sqrt(abs(rho))
            blocks.append((np.array([[p[k].real]]), np.array([g]), np.array([np.sign(rho) * g])))
            continue
        partner = _conjugate_partner(p, used, is_real, k, rtol)
        rho_k, rho_partner = r[k], r[partner]
        if abs(rho_k - np.conj(rho_partner)) > rtol * max(abs(rho_k), abs(rho_partner)) + (
            np.finfo(float).tiny
        ):
            raise FitError(
                f"the residues {rho_k:.6g} and {rho_partner:.6g} of the conjugate poles "
                f"{p[k]:.6g}, {p[partner]:.6g} are not conjugate: K(t) would not be real"
            )
        used[partner] = True
        upper = p[k] if p[k].imag > 0 else p[partner]
        rho = rho_k if p[k].imag > 0 else rho_partner
        sigma, omega = upper.real, upper.imag
        g = np.sqrt(2.0 * abs(rho))
        if g == 0.0:
            b_block, c_block = np.zeros(2), np.zeros(2)
        else:
            b_block = np.array([g, 0.0])
            c_block = np.array([2.0 * rho.real / g, 2.0 * rho.imag / g])
        blocks.append((np.array([[sigma, omega], [-omega, sigma]]), b_block, c_block))
    if not blocks:
        return np.zeros((0, 0)), np.zeros(0), np.zeros(0)
    a = scipy.linalg.block_diag(*(blk[0] for blk in blocks))
    b = np.concatenate([blk[1] for blk in blocks])
    c = np.concatenate([blk[2] for blk in blocks])
    return a, b, c


def _conjugate_partner(p: NDArray, used: NDArray, is_real: NDArray, k: int, rtol: float) -> int:
    candidates = np.flatnonzero(~used & ~is_real)
    if candidates.size:
        distance = np.abs(p[candidates] - np.conj(p[k]))
        best = candidates[np.argmin(distance)]
        if distance.min() <= rtol * abs(p[k]) * 10 + 1e-300:
            return int(best)
    raise FitError(
        f"the complex pole {p[k]:.6g} has no conjugate partner; give complex poles in "
        "conjugate pairs"
    )
