"""The exact passivity test of a radiation model and the dense sweep (Unneland (2007) §3.2).

The map from the body velocities ξ̇ to the memory force μ is passive:
K(jω) + K(jω)ᴴ = 2 B(ω) ⪰ 0 for all ω (Unneland (2007) Prop. 3.4, eq. 3.24; the MIMO criterion
λ_min[K(jω) + Kᵀ(−jω)] ≥ 0, eq. 3.13). A model that is not can feed energy into a
simulation. Positive-real diagonal terms do not make the MIMO model passive: the
couplings must not outweigh them anywhere.

**Test** (:func:`passivity_test`). The DOFs are scaled by D^{-1/2}, D = the peak |K_ii|
over frequency, so that units do not decide the answer (a congruence: it changes no
sign). The frequencies where an eigenvalue of Φ(jω) = K(jω) + Kᵀ(−jω) crosses zero are
the imaginary-axis zeros of the para-Hermitian system Φ(s), realised as

    A_Φ = diag(A, −Aᵀ),  B_Φ = [B; Cᵀ],  C_Φ = [C, −Bᵀ],  D_Φ = D + Dᵀ,

and computed as the finite generalized eigenvalues of the Rosenbrock pencil
([[A_Φ, B_Φ], [C_Φ, D_Φ]], diag(I, 0)): the zeros of Φ. This is the Hamiltonian test
in a form that needs no (D + Dᵀ)⁻¹, which does not exist for a radiation model (D = 0).
Between two consecutive crossings the sign of λ_min is constant, so one evaluation per
interval decides it; a dense sweep (:func:`default_sweep`) is added as a safeguard, and
the two limits are checked on their own: Φ(jω) ≈ −(CAB + (CAB)ᵀ)/ω² for ω → ∞ and
Φ(jω) ≈ ω² (CA⁻³B + (CA⁻³B)ᵀ) for ω → 0 (a radiation model has K(0) = 0). A model that
is not symmetric (couplings fitted as given) has K + Kᴴ = 2(Re K_s + j Im K_a): the
test is the same, and at the ends its terms −j(CB − (CB)ᵀ)/ω and −jω(CA⁻²B − (CA⁻²B)ᵀ),
which would dominate them, must vanish.

The enforcement that acts on this test's report is in
:mod:`cummins.radiation.passivity.enforcement`.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize_scalar

from cummins.radiation.model import RadiationModel
from cummins.validation import guard_radiation_model

#: A model is called passive when the smallest scaled eigenvalue of K + Kᴴ is above
#: −PASSIVITY_TOLERANCE times the largest one over frequency.
PASSIVITY_TOLERANCE = 1e-6
#: A zero of Φ(s) with |Re s| ≤ AXIS_TOLERANCE·|s| is taken as a crossing candidate: the
#: two crossings of a shallow, narrow dip of λ_min are a near-double zero that rounding
#: moves off the axis (1.6·10⁻⁵ on the ITI barge's yaw, a dip of −10⁻⁷ at 0.649 rad/s);
#: a candidate that is not a crossing only splits a band whose sign is tested anyway.
AXIS_TOLERANCE = 1e-3
#: Zeros of Φ(s) closer to the origin than ORIGIN_TOLERANCE × the slowest pole are the
#: double zero at s = 0 that K(0) = 0 puts there (split by rounding), not crossings.
ORIGIN_TOLERANCE = 1e-4
#: An antisymmetric part of CB or CA⁻²B below this fraction of the matrix is rounding (a
#: model fitted as given has them symmetric by construction); beyond it K + Kᴴ is
#: indefinite at that end (:func:`passivity_test`).
ANTISYMMETRY_TOLERANCE = 1e-8
#: Crossings closer than SAME_CROSSING (relative) are one: the zeros ±jω of Φ(s) come in
#: pairs whose |Im s| differ in the last bits, by a rounding path that depends on the BLAS
#: kernel (Sandybridge gave 1.395465 twice where others gave it once).
SAME_CROSSING = 1e-8


@dataclass(frozen=True)
class PassivitySweep:
    """Result of :func:`passivity_sweep`.

    Attributes
    ----------
    omega
        Frequencies of the sweep, rad/s.
    min_eigenvalue
        λ_min of the scaled K + Kᴴ at each frequency, relative to the largest
        eigenvalue over the sweep (dimensionless).
    passive
        Whether the minimum stays above −:data:`PASSIVITY_TOLERANCE`.
    worst_omega
        Frequency of the smallest eigenvalue, rad/s.
    """

    omega: np.ndarray
    min_eigenvalue: np.ndarray
    passive: bool
    worst_omega: float


@dataclass(frozen=True)
class ViolationBand:
    """A frequency interval where the model is not passive.

    Attributes
    ----------
    omega_low, omega_high
        Ends of the interval (crossings of λ_min through zero), rad/s; ``inf`` when it
        reaches infinity.
    worst_omega
        Frequency of the smallest eigenvalue inside, rad/s.
    min_eigenvalue
        That eigenvalue of the scaled K + Kᴴ, relative to the largest over frequency.
    """

    omega_low: float
    omega_high: float
    worst_omega: float
    min_eigenvalue: float


@dataclass(frozen=True)
class PassivityReport:
    """Result of :func:`passivity_test`.

    Attributes
    ----------
    passive
        True when no band violates by more than :data:`PASSIVITY_TOLERANCE` and both
        limits ω → 0, ω → ∞ are positive semidefinite.
    min_eigenvalue
        Smallest scaled eigenvalue of K + Kᴴ found (relative to the largest), with
        ``worst_omega`` its frequency (rad/s).
    crossings
        Frequencies where an eigenvalue of K + Kᴴ crosses zero (rad/s), from the pencil.
    bands
        The intervals of non-passivity.
    high_frequency, low_frequency
        λ_min of the limits: of −(CAB + (CAB)ᵀ) and of CA⁻³B + (CA⁻³B)ᵀ, scaled, relative
        to the largest eigenvalue of the same matrix (NaN when the matrix is zero).
    dofs
        The DOFs tested: those with a diagonal model (the others have no memory force;
        a DOF with couplings but no diagonal term makes the model not passive).
    """

    passive: bool
    min_eigenvalue: float
    worst_omega: float
    crossings: NDArray[np.float64]
    bands: tuple[ViolationBand, ...]
    high_frequency: float
    low_frequency: float
    dofs: tuple[str, ...]


def default_sweep(model: RadiationModel, points_per_decade: int = 100) -> np.ndarray:
    """Log grid from 10⁻³ to 10³ times the range of the model's pole magnitudes, refined
    around each lightly damped resonance."""
    parts = [k.poles() for k in model.couplings] + [b.poles() for b in model.blocks]
    poles = np.concatenate(parts) if parts else np.array([1.0])
    mags = np.abs(poles[np.abs(poles) > 0]) if np.any(np.abs(poles) > 0) else np.array([1.0])
    lo, hi = mags.min() * 1e-3, mags.max() * 1e3
    n = int(np.ceil(points_per_decade * np.log10(hi / lo)))
    resonances = [abs(p.imag) + abs(p.real) * np.linspace(-5, 5, 41) for p in poles if p.imag > 0]
    grid = np.concatenate([np.geomspace(lo, hi, n), *resonances])
    return np.unique(grid[grid > 0])


def dof_scaling(
    model: RadiationModel, omega: ArrayLike | None = None, *, response: NDArray | None = None
) -> NDArray[np.float64]:
    """s_i = 1/√(max_ω |K_ii(jω)|) (0 for a DOF without a diagonal model): S K S is
    dimensionless and the DOFs weigh alike. ``response``: K(jω) at ``omega`` when the
    caller has it."""
    w = default_sweep(model) if omega is None else np.asarray(omega, dtype=float)
    scale = np.zeros(len(model.dofs))
    k = model.response(w) if response is None else response
    diagonal = np.abs(np.diagonal(k, axis1=1, axis2=2)).max(axis=0)
    for i in range(len(model.dofs)):
        modelled = model.coupling(i, i)
        if modelled is not None and modelled.order and diagonal[i] > 0:
            scale[i] = 1.0 / np.sqrt(diagonal[i])
    return scale


def passivity_sweep(model: RadiationModel, omega: ArrayLike | None = None) -> PassivitySweep:
    """λ_min(K(jω) + K(jω)ᴴ) of the MIMO model on a dense sweep (Unneland (2007) eq. 3.13).

    The DOFs are scaled by :func:`dof_scaling`, so that translations and rotations weigh
    alike, and the eigenvalues are relative to the largest one; both scales are taken on
    :func:`default_sweep`, whatever ``omega`` is, so that the values compare with
    :func:`passivity_test`'s exactly.
    """
    w = default_sweep(model) if omega is None else np.asarray(omega, dtype=float)
    reference = default_sweep(model)
    scale = dof_scaling(model, reference)
    lam = _scaled_eigenvalues(model, w, scale)
    top = max(
        float(_scaled_eigenvalues(model, reference, scale)[:, -1].max()), np.finfo(float).tiny
    )
    low = lam[:, 0] / top
    worst = int(np.argmin(low))
    return PassivitySweep(w, low, bool(low[worst] >= -PASSIVITY_TOLERANCE), float(w[worst]))


def imaginary_axis_zeros(
    a: ArrayLike,
    b: ArrayLike,
    c: ArrayLike,
    d: ArrayLike | None = None,
    *,
    slowest: float | None = None,
) -> NDArray[np.float64]:
    """Frequencies ω > 0 (rad/s) where K(jω) + K(jω)ᴴ is singular, K(s) = C(sI − A)⁻¹B + D.

    The zeros of Φ(s) = K(s) + Kᵀ(−s) on the imaginary axis, as the finite eigenvalues of
    its Rosenbrock pencil (module docstring): no inverse of D + Dᵀ is needed. Zeros within
    :data:`AXIS_TOLERANCE` (relative) of the axis are returned, sorted, the pair ±jω
    once (:data:`SAME_CROSSING`); s = 0 is left
    out (a radiation model has K(0) = 0). ``slowest``: the smallest |eigenvalue| of A,
    when the caller knows the poles (else computed: an eigenproblem of A's size).
    """
    a, b, c = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (a, b, c))
    n, m = a.shape[0], b.shape[1]
    if n == 0:
        return np.empty(0)
    d = np.zeros((m, m)) if d is None else np.asarray(d, dtype=float)
    s = _pencil_zeros(a, b, c, d)
    # the zeros at s = 0 (K(0) = 0) come out as a cluster of size ~ε^(1/multiplicity)
    if slowest is None:
        slowest = np.abs(np.linalg.eigvals(a)).min()
    s = s[np.isfinite(s) & (np.abs(s) > ORIGIN_TOLERANCE * slowest)]
    on_axis = np.abs(s.real) <= AXIS_TOLERANCE * np.abs(s)
    crossings = np.sort(np.abs(s[on_axis].imag))
    if crossings.size < 2:
        return crossings
    new = np.r_[True, np.diff(crossings) > SAME_CROSSING * crossings[1:]]
    return crossings[new]


def _pencil_zeros(a: NDArray, b: NDArray, c: NDArray, d: NDArray) -> NDArray:
    """The finite eigenvalues of the Rosenbrock pencil of Φ (module docstring), by QZ."""
    n, m = a.shape[0], b.shape[1]
    # [[A, 0, B], [0, −Aᵀ, Cᵀ], [C, −Bᵀ, D + Dᵀ]] and diag(I, I, 0), written in place
    pencil = np.zeros((2 * n + m, 2 * n + m))
    pencil[:n, :n] = a
    pencil[n : 2 * n, n : 2 * n] = -a.T
    pencil[:n, 2 * n :] = b
    pencil[n : 2 * n, 2 * n :] = c.T
    pencil[2 * n :, :n] = c
    pencil[2 * n :, n : 2 * n] = -b.T
    pencil[2 * n :, 2 * n :] = d + d.T
    mass = np.zeros_like(pencil)
    mass[np.arange(2 * n), np.arange(2 * n)] = 1.0
    alpha, beta = scipy.linalg.eig(pencil, mass, right=False, homogeneous_eigvals=True)
    finite = np.abs(beta) > 1e-9 * np.abs(alpha) + 1e-300
    return alpha[finite] / beta[finite]


def passivity_test(
    model: RadiationModel, *, known: tuple[Sequence[int], NDArray] | None = None
) -> PassivityReport:
    """Exact passivity test of the MIMO model: crossings, bands, limits (module docstring).

    ``known``: (DOF indices, crossings) of an exact test of the same K(s) over those DOFs
    (another realization of it, its DOFs scaled otherwise: the crossings are the same),
    used when the DOFs this test keeps are those; else the crossings are computed.

    Returns
    -------
    PassivityReport
    """
    guard_radiation_model(model)  # non-finite or absurd matrices: FitError naming the pair
    labels = tuple(model.dofs)
    sweep = default_sweep(model)
    # once, for the scaling and the sweep's eigenvalues (by BLAS: the sweep of a large
    # block is thousands of frequencies)
    response = model.response(sweep, batched=True)
    scale = dof_scaling(model, sweep, response=response)
    diagonal = scale > 0
    touched = np.zeros(len(labels), dtype=bool)
    for k in model.couplings:
        if k.order:
            touched[[k.influenced, k.radiating]] = True
    for block in model.blocks:
        if block.order:
            touched[list(block.dofs)] = True
    orphan = touched & ~diagonal
    keep = np.flatnonzero(diagonal)
    tested = tuple(labels[i] for i in keep)
    if keep.size == 0:
        return PassivityReport(True, 0.0, float("nan"), np.empty(0), (), np.nan, np.nan, tested)
    a, b, c = _scaled_mimo(model, scale, keep)
    # A's eigenvalues: those of the model's couplings and blocks (kept by the response)
    poles = [m[2] for m in model._modal] + [m[0] for m in model._block_modal]
    poles = np.abs(np.concatenate(poles)) if poles else np.zeros(0)
    if known is not None and sorted(known[0]) == keep.tolist():
        crossings = np.asarray(known[1], dtype=float)
    else:
        crossings = imaginary_axis_zeros(a, b, c, slowest=poles.min() if poles.size else None)
    lam_sweep = _scaled_eigenvalues(model, sweep, scale, response)
    top = max(float(np.abs(lam_sweep).max()), np.finfo(float).tiny)
    low_sweep = lam_sweep[:, 0] / top

    def lam_min(w: float) -> float:
        return float(_scaled_eigenvalues(model, np.array([w]), scale)[0, 0]) / top

    # between consecutive crossings the sign of λ_min is constant: the sweep points and
    # one midpoint per interval decide it
    edges = np.unique(np.concatenate([[0.0], crossings, [np.inf]]))
    bands = []
    worst = int(np.argmin(low_sweep))
    worst_w, worst_v = float(sweep[worst]), float(low_sweep[worst])
    for lo, hi in itertools.pairwise(edges):
        inside = (sweep > lo) & (sweep < hi)
        mid = midpoint(lo, hi, sweep)
        ws = np.r_[sweep[inside], mid]
        vs = np.r_[low_sweep[inside], lam_min(mid)]
        k = int(np.argmin(vs))
        w_min, v_min = float(ws[k]), float(vs[k])
        if v_min >= 0:
            continue
        w_min, v_min = _refine_minimum(lam_min, lo, hi, w_min, v_min)
        if v_min < worst_v:
            worst_w, worst_v = w_min, v_min
        if v_min < -PASSIVITY_TOLERANCE:
            bands.append(ViolationBand(float(lo), float(hi), w_min, v_min))
    high = _limit_eigenvalue(-(c @ a @ b), c @ b)
    low = 0.0
    if a.size:
        inverse = np.linalg.inv(a)
        low = _limit_eigenvalue(
            c @ np.linalg.matrix_power(inverse, 3) @ b, c @ np.linalg.matrix_power(inverse, 2) @ b
        )
    passive = (
        not bands
        and not orphan.any()
        and not (high < -PASSIVITY_TOLERANCE)
        and not (low < -PASSIVITY_TOLERANCE)
    )
    return PassivityReport(
        bool(passive),
        float(worst_v),
        float(worst_w),
        crossings,
        tuple(bands),
        float(high),
        float(low),
        tested,
    )


def is_passive(model: RadiationModel) -> bool:
    """True when the MIMO model passes :func:`passivity_test`."""
    return passivity_test(model).passive


# ----------------------------------------------------------------------- internals


def _scaled_eigenvalues(
    model: RadiationModel, w: NDArray, scale: NDArray, response: NDArray | None = None
) -> NDArray:
    """Ascending eigenvalues of S (K + Kᴴ) S at each ω, over the DOFs with scale > 0
    (``response``: K(jω) at ``w`` when known)."""
    keep = np.flatnonzero(scale > 0)
    k = (model.response(w) if response is None else response)[:, keep][:, :, keep]
    s = scale[keep]
    herm = (k + np.conj(np.swapaxes(k, 1, 2))) * s[None, :, None] * s[None, None, :]
    return np.linalg.eigvalsh(herm)


def _scaled_mimo(model: RadiationModel, scale: NDArray, keep: NDArray):
    a, b, c = model.A, model.B, model.C
    return a, b[:, keep] * scale[keep], c[keep] * scale[keep][:, None]


def midpoint(lo: float, hi: float, sweep: NDArray) -> float:
    """A frequency inside (lo, hi) for testing the sign of λ_min there (hi may be ∞)."""
    if np.isinf(hi):
        return 10.0 * max(lo, sweep[-1])
    if lo <= 0:
        return min(hi, sweep[0]) / 10.0
    return float(np.sqrt(lo * hi))


def band_points(
    a: NDArray, b: NDArray, c: NDArray, grid: NDArray, slowest: float | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The crossings of K(s) = C(sI − A)⁻¹B (:func:`imaginary_axis_zeros`; ``slowest``
    the smallest |eigenvalue| of A when known) as band edges (0 and ∞ included), and the
    frequencies to test besides ``grid``: each band's midpoint and five points across
    each finite band, those not already in ``grid``."""
    crossings = imaginary_axis_zeros(a, b, c, slowest=slowest) if np.size(a) else np.zeros(0)
    edges = np.unique(np.concatenate([[0.0], crossings, [np.inf]]))
    middle = [midpoint(lo, hi, grid) for lo, hi in itertools.pairwise(edges)]
    lo, hi = edges[:-1], edges[1:]
    finite = (lo > 0) & np.isfinite(hi)
    across = lo[finite, None] * (hi[finite] / lo[finite])[:, None] ** (np.arange(1, 6) / 6.0)
    return edges, np.setdiff1d(np.concatenate([middle, across.ravel()]), grid)


def _refine_minimum(lam_min, lo: float, hi: float, w0: float, v0: float) -> tuple[float, float]:
    """The minimum of λ_min(ω) in (lo, hi) near w0, searched on log ω: over the band, and
    polished within ±1 % of the best point (a band-wide bounded search can stop
    in a local minimum, or 10⁻⁵ short of the sweep's own minimum)."""
    left = np.log(lo) if lo > 0 else np.log(w0) - 3.0
    right = np.log(hi) if np.isfinite(hi) else np.log(w0) + 3.0
    best_w, best_v = w0, v0
    for a, b, tol in ((left, right, 1e-4), (None, None, 1e-9)):
        if a is None:  # polish within ±1 % of the best point
            centre = np.log(best_w)
            a, b = max(left, centre - 0.01), min(right, centre + 0.01)
        if not b > a:
            continue
        result = minimize_scalar(
            lambda x: lam_min(float(np.exp(x))),
            bounds=(a, b),
            method="bounded",
            options={"xatol": tol},
        )
        if result.fun < best_v:
            best_w, best_v = float(np.exp(result.x)), float(result.fun)
    return best_w, best_v


def _limit_eigenvalue(matrix: NDArray, leading: NDArray | None = None) -> float:
    """λ_min / λ_max(abs) of the symmetric part of ``matrix`` (NaN for a zero matrix): the
    limit of K + Kᴴ at one end, scaled. ``leading`` is the term of K one order before it
    (CB, the 1/ω term as ω → ∞; CA⁻²B, the ω term as ω → 0): symmetric, it leaves K + Kᴴ
    alone; with an antisymmetric part beyond :data:`ANTISYMMETRY_TOLERANCE` of itself (a
    model that is not reciprocal and not made passive as such), K + Kᴴ tends to
    ∓j(M − Mᵀ)/ω or jω(M − Mᵀ), whose eigenvalues come in pairs ±: −1."""
    if leading is not None:
        anti = np.abs(leading - leading.T).max(initial=0.0)
        if anti > ANTISYMMETRY_TOLERANCE * np.abs(leading).max(initial=0.0):
            return -1.0
    sym = matrix + matrix.T
    lam = np.linalg.eigvalsh(sym)
    top = np.abs(lam).max()
    return float(lam[0] / top) if top > 0 else float("nan")
