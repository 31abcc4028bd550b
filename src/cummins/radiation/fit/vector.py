"""Common-pole identification of the fluid memory: vector fitting of whole DOF blocks.

The DOFs that radiate into each other (the connected components of the significant
couplings: surge–heave–pitch and sway–roll–yaw of a ship, the twelve DOFs of two
interacting bodies) are fitted together, every coupling of a block with the **same
poles** (Gustavsen & Semlyen (1999), vector fitting):

    Ã(s) = A∞ + Σ_k R_k / (s − p_k),     K(s) = s (Ã(s) − A∞) = Σ_k R_k p_k / (s − p_k),

with Ã(jω) = A(ω) − j B(ω)/ω the complex added mass of the data, R_k symmetric residue
matrices (real for a real pole, complex for a pair) and Σ_k R_k = 0, so that K is
strictly proper and K(0) = 0 (Unneland (2007) eqs. 3.44–3.48: the properties a
radiation model must have). A∞ is the constant term of the fit (Perez & Fossen's joint
estimate), or the data's ω = ∞ row when it is consistent.

**Couplings fitted as given.** Where the data are not reciprocal (A_ij ≠ A_ji, B_ij ≠
B_ji) beyond what the motions allow (:mod:`cummins.radiation.fit.data`), a pair is fitted
as its symmetric part ½(X_ij + X_ji) (the element (i, j), i < j) and its antisymmetric
part ½(X_ji − X_ij) (the element (j, i), listed after the symmetric ones): the residue
matrices are then not symmetric. Passivity asks K(jω) + K(jω)ᴴ = 2(Re K_s + j Im K_a) ⪰ 0
(Unneland (2007) eq. 3.13), which an antisymmetric part can meet only if it vanishes
faster than the symmetric damping at both ends: its residues have Σ R_k = Σ R_k/p_k =
Σ R_k p_k = 0 (no antisymmetric jω term as ω → 0, K(t = 0) symmetric), and its A∞ is
the data's antisymmetric added mass at ω → 0, where passivity pins it (the model's
antisymmetric added mass is A∞'s at both ends).

1. **Poles**: relaxed vector fitting (Gustavsen (2006)) with the fast QR solution of
   Deschrijver et al. (2008): every coupling of the block contributes its rows to one
   small least-squares problem for the common poles, which are reflected into the left
   half-plane and kept at a relative damping of at least :data:`MIN_DAMPING`.
2. **Residues and A∞**: one linear least-squares problem per coupling, with Σ R_k = 0.
   The equations weigh what the R² targets of A and B measure and, when the data hold
   the inertia and the restoring, what the motions are sensitive to
   (:mod:`cummins.radiation.fit.motion`). The data are extended beyond the last frequency by a
   damping tail B ∝ ω⁻² (the rate the model itself has), weakly weighted, so that
   nothing unphysical is fitted beyond the data.
3. **Passivity**: K(jω) + K(jω)ᴴ = 2 Re K(jω) ⪰ 0 at all frequencies (Unneland (2007)
   Prop. 3.4) is enforced on the residues of the whole block by the smallest weighted
   change of the fit (:mod:`cummins.radiation.fit.block_passivity`). The poles do not
   move, so the model stays stable.
4. **Order**: the number of common poles grows until every coupling reaches its R²
   targets and the motion error of the block is within its aim
   (:mod:`cummins.radiation.fit.order_search`).
5. **Realization**: Gilbert's realization of the pole–residue form, one state per rank
   of each residue matrix (a surge–pitch pair whose damping is rank one, as on a sphere
   about a point off its centre, costs one state per pole, not two).

The result is one :class:`~cummins.radiation.model.MemoryBlock` per block.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
import scipy.linalg.lapack
from numpy.typing import NDArray

from cummins.radiation.damping_tail import DampingTail
from cummins.radiation.fit.poles import Poles
from cummins.radiation.fit.tail import (
    block_tail_equations,
    kernel_zero_equation,
    kernel_zero_form,
    tail_frequencies,
)

#: Iterations of the pole relocation (at most; it stops when the poles move by less
#: than CONVERGED, relative).
ITERATIONS = 12
CONVERGED = 1e-6
#: The pole relocation uses at most about this many data frequencies (every k-th).
RELOCATION_POINTS = 300
#: Smallest relative damping |Re p| / |p| of a complex pole (radiation memory is broadband:
#: a needle-sharp resonance would be fitted to an irregular-frequency spike).
MIN_DAMPING = 0.05
#: ... and in a block with a DOF that keeps a sharp resonance the motions depend on (a
#: moonpool's piston mode, a gap resonance: :func:`cummins.repair.suspects_by_dof`) and that
#: misses its targets at MIN_DAMPING: fitted again with this floor, kept when closer to
#: them (:func:`cummins.radiation.fit.blocks.fit_blocks`). Measured on rings with a
#: moonpool (Capytaine, ``tests/data/make_moonpool.py``), motion error of the scoreboard:
#: r 3–5 m, 0.1 rad/s (``moonpool_sharp``) 1.08 % → 0.20 %, r 1.5–3.5 m 22 % → 0.18 %,
#: r 2–4 m 3.8 % → 0.22 %; lowered for every block instead, five corpus cases (the ITI
#: barge, PEND hull, NEMOH two cubes, RM3, the drift sphere) fitted worse.
RESONANCE_MIN_DAMPING = 0.01
#: No pole beyond POLE_SPAN × the highest data frequency in magnitude: the data do not
#: ask for one, the damping tail beyond them decays without one (issue 31), and a fast
#: pole makes the model stiff (the tanker's relocation, without the tail's equations,
#: found a real pole at −36.8 rad/s, 11 × its 3.4 rad/s: a Runge–Kutta run at 0.1 s with
#: quadratic roll damping diverged).
POLE_SPAN = 3.0
#: Initial relative damping of the starting poles.
START_DAMPING = 0.01
#: Residue-matrix eigenvalues below RANK_TOL × the largest of the block cost no state.
RANK_TOL = 0.0


# ----------------------------------------------------------------------------- poles


_TINY, _EPS = np.finfo(float).tiny, np.finfo(float).eps


def _poles_from(values: NDArray, limit: float = np.inf, min_damping: float = MIN_DAMPING) -> Poles:
    """Sorted, stable, damped poles in real form from a set closed under conjugation: each
    first drawn in to ``limit`` (rad/s) in magnitude (:data:`POLE_SPAN`), then a pair's
    decay raised to at least ``min_damping`` (:data:`MIN_DAMPING`) × its magnitude, its
    frequency kept — so a floored pair's damping ratio is ζ/√(1 + ζ²) (0.0499 for
    ζ = 0.05), and its magnitude may exceed ``limit`` by that factor √(1 + ζ²)."""
    values = np.asarray(values, dtype=complex)
    size = np.abs(values)
    if size.max(initial=0.0) > limit:
        beyond = size > limit
        values = np.where(beyond, values * limit / np.where(size > 0, size, 1.0), values)
        size = np.abs(values)
    imag = values.imag
    is_real = np.abs(imag) <= 1e-9 * (size + _TINY)
    real = -np.abs(values.real[is_real])
    upper = ~is_real & (imag > 0)
    pairs = values[upper]
    # each pair written as −max(|Re p|, ζ|p|) + j|Im p|, in place
    out = np.empty(pairs.size, dtype=complex)
    out.real = -np.maximum(np.abs(pairs.real), min_damping * size[upper])
    out.imag = np.abs(pairs.imag)
    real[real == 0] = -_EPS
    real.sort()
    return Poles(real[::-1], out[np.argsort(out.imag)])


def starting_poles(omega: NDArray, count: int) -> Poles:
    """``count`` real parameters: pairs with imaginary parts log-spaced over the data's
    frequencies (a real pole more when ``count`` is odd, at the geometric mean)."""
    lo, hi = float(omega[omega > 0].min()), float(omega.max())
    beta = np.geomspace(lo, hi, max(count // 2, 1)) if count >= 2 else np.zeros(0)
    pairs = -START_DAMPING * beta + 1j * beta
    real = np.array([-np.sqrt(lo * hi)]) if count % 2 else np.zeros(0)
    return Poles(real, pairs)


# ----------------------------------------------------------------------------- data


@dataclass(frozen=True)
class BlockData:
    """What one block is fitted to.

    Attributes
    ----------
    dofs
        Indices of the block's DOFs in the model.
    elements
        (i, j) model indices, i ≤ j, of the fitted couplings.
    omega
        Frequencies of the equations (the data's, then the tail), rad/s.
    values
        Ã(ω) − A∞ (when A∞ is given) or Ã(ω) per element, (n_elements, n_omega).
    weight_real, weight_imag
        Weights of the real and imaginary parts of each equation.
    fixed_inf
        A∞ of each element when it is given (then not estimated; NaN for an element whose
        A∞ is estimated: the symmetric ones beside an antisymmetric part), else None.
    n_data
        The number of data frequencies (the first ``n_data`` of ``omega``).
    inf_guess, inf_spread
        When A∞ is estimated: a prior per element (Ogilvie's estimate and its spread);
        one more equation (A∞ − guess)/spread weighs like all the added-mass equations
        of the element together, so that the data decide where they are informative
        and the prior where the model would extrapolate.
    min_damping
        The smallest relative damping |Re p| / |p| the pole relocation allows.
    """

    dofs: tuple[int, ...]
    elements: tuple[tuple[int, int], ...]
    omega: NDArray[np.float64]
    values: NDArray[np.complex128]
    weight_real: NDArray[np.float64]
    weight_imag: NDArray[np.float64]
    fixed_inf: NDArray[np.float64] | None
    n_data: int
    added_mass: NDArray[np.float64] = field(repr=False, default=None)
    damping: NDArray[np.float64] = field(repr=False, default=None)
    used: NDArray[np.bool_] = field(repr=False, default=None)
    inf_guess: NDArray[np.float64] | None = field(repr=False, default=None)
    inf_spread: NDArray[np.float64] | None = field(repr=False, default=None)
    tails: tuple[DampingTail, ...] | None = field(repr=False, default=None)
    time: NDArray[np.float64] | None = field(repr=False, default=None)
    kernel: NDArray[np.float64] | None = field(repr=False, default=None)
    min_damping: float = MIN_DAMPING

    @property
    def free_inf(self) -> NDArray[np.bool_]:
        """Which elements estimate their A∞."""
        if self.fixed_inf is None:
            return np.ones(len(self.elements), dtype=bool)
        return np.isnan(self.fixed_inf)

    # What every fit of the block shares, computed once (the order search fits one block
    # at tens of orders, each in about a dozen relocations).

    @functools.cached_property
    def kernel_zero_equations(self) -> tuple[tuple[float, float] | None, ...]:
        """:func:`~cummins.radiation.fit.tail.kernel_zero_equation` of each element."""
        return tuple(kernel_zero_equation(self, e) for e in range(len(self.elements)))

    @functools.cached_property
    def cache(self) -> dict:
        """What the scores of every fit share (the data's side), filled as they ask."""
        return {}

    @functools.cached_property
    def plain_fits(self) -> dict:
        """The order search's fits before passivity and their scores, by count."""
        return {}

    @functools.cached_property
    def relocation_data(self) -> BlockData:
        """The equations of the pole relocation (:func:`_thinned`)."""
        return _thinned(self)

    @functools.cached_property
    def relocation_rows(self) -> tuple[float, tuple[tuple[NDArray, ...], ...]]:
        """(scale, groups) of :func:`relocate`: the norm of the weighted data over the
        number of frequencies, and for the elements with A∞ given, then estimated:
        (indices, −values, real weights, imaginary weights), the last three (rows, 1, ω)."""
        f, wr, wi = self.values, self.weight_real, self.weight_imag
        scale = np.sqrt(float(np.sum((wr * f.real) ** 2 + (wi * f.imag) ** 2))) / self.omega.size
        groups = []
        for estimated in (False, True):
            rows = np.flatnonzero(self.free_inf == estimated)
            groups.append((rows, -f[rows][:, None, :], wr[rows][:, None, :], wi[rows][:, None, :]))
        return scale, tuple(groups)


def is_antisymmetric(element: tuple[int, int]) -> bool:
    """Whether an element (p, q) of a block is the antisymmetric part ½(X_pq − X_qp) of a
    pair fitted as given (p > q), not a symmetric part (p ≤ q)."""
    return element[0] > element[1]


def block_data(
    dofs,
    elements,
    omega,
    added_mass,
    damping,
    used,
    *,
    added_mass_inf=None,
    motion_weight=None,
    motion_tol: float = 0.01,
    prior=None,
    antisymmetric_inf=None,
    tail_weight: float = 1.0,
    time=None,
    kernel=None,
    min_damping: float = MIN_DAMPING,
) -> BlockData:
    """Equations of a block (see :class:`BlockData`).

    ``added_mass``, ``damping``: the data (omega, n, n), symmetric but for the pairs
    fitted as given; ``used``: (omega, n_elements) which frequencies each coupling keeps;
    ``motion_weight``: callable (i, j) → W_ij(ω) of
    :class:`cummins.radiation.fit.motion.MotionSensitivity` or None; ``prior``: (guess,
    spread) matrices of A∞ when it is estimated (symmetric); ``antisymmetric_inf``: the
    antisymmetric part of A∞ of the pairs fitted as given (their A at ω → 0, where
    passivity pins it: :mod:`cummins.radiation.fit.reciprocity`); ``added_mass_inf``:
    the A∞ matrix when it is given, NaN where an element estimates it
    (:mod:`cummins.radiation.fit.causal_inf`), None when every element does;
    ``tail_weight``: a
    factor on the weight of the damping tail beyond the data
    (:func:`cummins.radiation.fit.tail.tail_equations`); ``time``, ``kernel``: the data's
    K(t) (time, n, n), for the R² of K(t) of the diagonal elements; ``min_damping``: the
    smallest relative damping of a pole (:data:`MIN_DAMPING`, or
    :data:`RESONANCE_MIN_DAMPING` for a block that keeps a sharp resonance).

    An element (i, j), i ≤ j, is fitted to ½(X_ij + X_ji); an antisymmetric one (p, q),
    p > q (:func:`is_antisymmetric`), to ½(X_pq − X_qp), with the weights of its pair:
    the least-squares misfit of the two is then that of X_pq and X_qp each. Beyond the
    data a symmetric element follows the data's damping tail (of the symmetric parts);
    an antisymmetric one has no tail equation (its damping integrates to zero, K(t = 0)
    symmetric: what it owes, it may put beyond the data).
    """
    w = np.asarray(omega, dtype=float)
    tail = tail_frequencies(w.max())
    values, wr, wi, tails = [], [], [], []
    given = {(q, p) for p, q in elements if p > q}  # pairs fitted as given
    symmetric = [e for e, (i, j) in enumerate(elements) if i <= j]
    beyond = dict(
        zip(
            symmetric,
            block_tail_equations(
                w,
                0.5 * (added_mass + np.swapaxes(added_mass, 1, 2)),
                0.5 * (damping + np.swapaxes(damping, 1, 2)),
                used[:, symmetric],
                [elements[e] for e in symmetric],
                tail,
            ),
            strict=True,
        )
    )
    for e, (i, j) in enumerate(elements):
        use = used[:, e]
        n_use = max(int(use.sum()), 1)
        floor_a = 1e-3 * np.sqrt(np.std(added_mass[:, i, i]) * np.std(added_mass[:, j, j]))
        floor_b = 1e-3 * np.sqrt(np.std(damping[:, i, i]) * np.std(damping[:, j, j]))
        if (min(i, j), max(i, j)) not in given:
            a_ij, b_ij = added_mass[:, i, j], damping[:, i, j]
            spread_a = max(float(np.std(a_ij[use])), floor_a, np.finfo(float).tiny)
            spread_b = max(float(np.std(b_ij[use])), floor_b, np.finfo(float).tiny)
        else:  # a pair fitted as given: its parts, weighed as each direction's
            sign = -1.0 if i > j else 1.0
            a_ij = 0.5 * (added_mass[:, i, j] + sign * added_mass[:, j, i])
            b_ij = 0.5 * (damping[:, i, j] + sign * damping[:, j, i])
            spread_a = max(
                _pair_spread(added_mass[use, i, j], added_mass[use, j, i]),
                floor_a,
                np.finfo(float).tiny,
            )
            spread_b = max(
                _pair_spread(damping[use, i, j], damping[use, j, i]), floor_b, np.finfo(float).tiny
            )
        r_a = np.full(w.size, 1.0 / spread_a) / np.sqrt(n_use)
        r_b = w / spread_b / np.sqrt(n_use)
        if motion_weight is not None:
            m = motion_weight(i, j) * w / motion_tol / np.sqrt(n_use)
            r_a, r_b = np.hypot(r_a, m), np.hypot(r_b, m)
        r_a, r_b = np.where(use, r_a, 0.0), np.where(use, r_b, 0.0)
        offset = 0.0
        if i > j:
            offset = antisymmetric_inf[i, j]
        elif added_mass_inf is not None and np.isfinite(added_mass_inf[i, j]):
            offset = added_mass_inf[i, j]
        # beyond the data: the data's damping tail, weighed as the data it stands for
        b_tail, weight, element_tail = beyond.get(e, (np.zeros(tail.size), 0.0, None))
        tails.append(element_tail)
        values.append(np.r_[a_ij - offset - 1j * b_ij / w, -1j * b_tail / tail])
        wr.append(np.r_[r_a, np.zeros(tail.size)])
        wi.append(np.r_[r_b, tail_weight * weight * tail / spread_b / np.sqrt(n_use)])
    fixed = guess = spread = None
    if added_mass_inf is not None or any(i > j for i, j in elements):
        # an antisymmetric part's A∞ is given (its A at ω → 0); a symmetric one's is
        # estimated (NaN) unless ``added_mass_inf`` is given
        fixed = np.array(
            [
                antisymmetric_inf[i, j]
                if i > j
                else (np.nan if added_mass_inf is None else added_mass_inf[i, j])
                for i, j in elements
            ]
        )
    if prior is not None and (added_mass_inf is None or np.isnan(added_mass_inf).any()):
        guess = np.array([prior[0][i, j] if i <= j else 0.0 for i, j in elements])
        spread = np.array([prior[1][i, j] if i <= j else 0.0 for i, j in elements])
    return BlockData(
        tuple(dofs),
        tuple(elements),
        np.r_[w, tail],
        np.array(values),
        np.array(wr),
        np.array(wi),
        fixed,
        w.size,
        added_mass,
        damping,
        used,
        guess,
        spread,
        tuple(tails),
        None if kernel is None else np.asarray(time, dtype=float),
        None if kernel is None else np.array([kernel[:, i, j] for i, j in elements]),
        min_damping,
    )


def _pair_spread(one: NDArray, two: NDArray) -> float:
    """The spread of a pair fitted as given: the root mean square of the spreads of X_ij
    and X_ji (each direction's, as its R² measures it)."""
    return float(np.sqrt(0.5 * (np.var(one) + np.var(two))))


def _stacked(m: NDArray, wr: NDArray, wi: NDArray) -> NDArray:
    return np.vstack([wr[:, None] * m.real, wi[:, None] * m.imag])


# ----------------------------------------------------------------------------- fitting


def relocate(data: BlockData, poles: Poles) -> Poles:
    """One relaxed vector-fitting relocation of the common poles (fast QR)."""
    s = 1j * data.omega
    sigma = poles.basis(s, constant=True)  # [phi, 1]
    n = poles.count
    scale, groups = data.relocation_rows
    # one QR per element, stacked: [own, −f σ] weighted, real rows over imaginary rows
    # (own: the element's basis, with a constant when its A∞ is estimated); the trailing
    # blocks of their R, written in place, then the normalisation row
    lhs = np.empty((len(data.elements) * (n + 1) + 1, n + 1))
    n_w = s.size
    columns = np.ascontiguousarray(sigma.T)  # by column, frequency-contiguous
    for estimated, (rows, minus_f, wre, wie) in zip((False, True), groups, strict=True):
        if not rows.size:
            continue
        own = columns if estimated else columns[:n]
        k = own.shape[0]
        fs = minus_f * columns[None]
        # each element's matrix in column-major order (LAPACK's, factored in place)
        stack = np.empty((rows.size, k + n + 1, 2 * n_w))
        np.multiply(wre, own.real[None], out=stack[:, :k, :n_w])
        np.multiply(wie, own.imag[None], out=stack[:, :k, n_w:])
        np.multiply(wre, fs.real, out=stack[:, k:, :n_w])
        np.multiply(wie, fs.imag, out=stack[:, k:, n_w:])
        for e, matrix in zip(rows.tolist(), stack, strict=True):
            _r_factor(matrix.T, k, lhs[e * (n + 1) : (e + 1) * (n + 1)])
    lhs[-1] = scale * np.real(sigma.sum(axis=0))
    rhs = np.zeros(lhs.shape[0])
    rhs[-1] = scale * s.size
    x = _least_squares(lhs, rhs)
    c, d = x[:n], x[n]
    if abs(d) < 1e-8 * max(1.0, float(np.abs(c).max())):  # relaxation failed: σ(∞) = 1
        stack = lhs[:-1]
        c = _least_squares(stack[:, :n], -stack[:, n])
        d = 1.0
    lam, b = poles.state_form()
    limit = POLE_SPAN * float(data.omega[: data.n_data].max())
    return _poles_from(_eigenvalues(lam - np.outer(b, c) / d), limit, data.min_damping)


def _eigenvalues(matrix: NDArray) -> NDArray[np.complex128]:
    """The eigenvalues of a real square ``matrix``: LAPACK's dgeev without eigenvectors,
    its workspace as ``numpy.linalg.eigvals`` asks for it (the same values), without that
    wrapper's checks but the one for infinities and NaNs."""
    if not np.isfinite(matrix).all():
        raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
    wr, wi, _, _, info = scipy.linalg.lapack.dgeev(
        matrix, compute_vl=0, compute_vr=0, lwork=_eig_workspace(matrix.shape[0])
    )
    if info:
        raise np.linalg.LinAlgError(f"eigenvalues did not converge (LAPACK info {info})")
    return wr + 1j * wi


@functools.lru_cache(maxsize=64)
def _eig_workspace(size: int) -> int:
    """dgeev's optimal workspace for a size × size matrix without eigenvectors."""
    return int(scipy.linalg.lapack.dgeev_lwork(size, compute_vl=0, compute_vr=0)[0])


def _least_squares(matrix: NDArray, rhs: NDArray) -> NDArray:
    """The minimum-norm least-squares solution of ``matrix`` x = ``rhs``: LAPACK's dgelsd
    with the cut-off of ``numpy.linalg.lstsq(rcond=None)`` (machine ε × the larger
    dimension), the same numbers without that wrapper's checks (the relocation solves one
    per iteration, the residues one per element and order)."""
    rows, columns = matrix.shape
    if rows < columns:  # LAPACK's right-hand side holds the solution
        rhs = np.concatenate([rhs, np.zeros(columns - rows)])
    lwork, iwork = _lstsq_workspace(rows, columns)
    x, _, _, info = scipy.linalg.lapack.dgelsd(
        matrix, rhs, lwork=lwork, size_iwork=iwork, cond=_EPS * max(rows, columns)
    )
    if info:
        raise np.linalg.LinAlgError(f"least squares failed (LAPACK info {info})")
    return x[:columns]


@functools.lru_cache(maxsize=256)
def _lstsq_workspace(rows: int, columns: int) -> tuple[int, int]:
    """dgelsd's optimal workspace and integer workspace for one right-hand side."""
    lwork, iwork, _ = scipy.linalg.lapack.dgelsd_lwork(rows, columns, 1, -1)
    return int(lwork), int(iwork)


def _r_factor(matrix: NDArray, start: int, out: NDArray) -> None:
    """The trailing block R[start:, start:] of the triangular factor R of the Householder
    QR of a Fortran-ordered ``matrix`` (rows ≥ columns), factored in place, written to
    ``out``: LAPACK's dgeqrf with its optimal workspace, as ``numpy.linalg.qr(mode="r")``
    calls it (the same R, bit for bit), without the copies."""
    rows, columns = matrix.shape
    qr, _, _, info = scipy.linalg.lapack.dgeqrf(
        matrix, lwork=_qr_workspace(rows, columns), overwrite_a=1
    )
    if info:
        raise np.linalg.LinAlgError(f"QR factorisation failed (LAPACK info {info})")
    out[...] = qr[start:columns, start:]
    out[_strictly_lower(columns - start)] = 0.0


@functools.lru_cache(maxsize=64)
def _strictly_lower(size: int) -> tuple[NDArray, NDArray]:
    """The indices below the diagonal of a square matrix of ``size``."""
    return np.tril_indices(size, -1)


@functools.lru_cache(maxsize=256)
def _qr_workspace(rows: int, columns: int) -> int:
    """dgeqrf's optimal workspace for a rows × columns matrix."""
    return int(scipy.linalg.lapack.dgeqrf_lwork(rows, columns)[0])


def _thinned(data: BlockData) -> BlockData:
    """The equations of the pole relocation: every k-th data frequency when there are
    more than RELOCATION_POINTS (the weights scaled by √k, so that the equations keep
    their total weight), without the damping tail beyond the data: the poles come from
    the data, the residues are then fitted to all, tail included. (With the tail's
    equations, which carry real weight since issue 31, the relocation placed poles for
    them erratically: the supply vessel's R² of B 0.69 or 0.99 as their number went
    from 12 to 24, and 56 states against 43 without them.)"""
    step = max(int(np.ceil(data.n_data / RELOCATION_POINTS)), 1)
    rows = np.arange(0, data.n_data, step)
    scale = np.sqrt(step)
    return BlockData(
        data.dofs,
        data.elements,
        data.omega[rows],
        data.values[:, rows],
        data.weight_real[:, rows] * scale,
        data.weight_imag[:, rows] * scale,
        data.fixed_inf,
        int(np.ceil(data.n_data / step)),
        min_damping=data.min_damping,
    )


def _same_poles(one: Poles, two: Poles) -> bool:
    """The relocation has converged: the same poles to CONVERGED (relative)."""
    if one.real.size != two.real.size or one.pairs.size != two.pairs.size:
        return False
    real = np.abs(one.real - two.real) <= CONVERGED * np.abs(two.real)
    pairs = np.abs(one.pairs - two.pairs) <= CONVERGED * np.abs(two.pairs)
    return bool(real.all() and pairs.all())


def residue_null_space(poles: Poles) -> NDArray[np.float64]:
    """Orthonormal basis of the coefficient vectors with Σ R_k = 0."""
    v = poles.residue_sum()
    q, _ = np.linalg.qr(np.c_[v, np.eye(v.size)[:, : v.size - 1]])
    return q[:, 1:]


def antisymmetric_null_space(poles: Poles) -> NDArray[np.float64]:
    """Orthonormal basis of the coefficient vectors of an antisymmetric part: Σ R_k = 0
    (K(0) = 0, strictly proper), Σ R_k/p_k = 0 (no jω term as ω → 0: the model's
    antisymmetric added mass tends to its A∞ at zero frequency) and Σ R_k p_k = 0
    (K(t = 0) symmetric: no 1/ω term as ω → ∞), each sum over the conjugates too; without
    them K + Kᴴ is indefinite at one end (module docstring). Fewer than four coefficients
    leave none."""
    nr = poles.real.size
    count = poles.count
    forms = np.zeros((count, 3))
    forms[:, 0] = poles.residue_sum()
    forms[:nr, 1], forms[:nr, 2] = 1.0 / poles.real, poles.real
    inverse = 1.0 / poles.pairs
    forms[nr::2, 1], forms[nr + 1 :: 2, 1] = 2 * inverse.real, -2 * inverse.imag
    forms[nr::2, 2], forms[nr + 1 :: 2, 2] = 2 * poles.pairs.real, -2 * poles.pairs.imag
    if count <= 3:
        return np.zeros((count, 0))
    q, _ = np.linalg.qr(np.c_[forms, np.eye(count)[:, : count - 3]])
    return q[:, 3:]


def element_null_spaces(elements, poles: Poles) -> list[NDArray[np.float64]]:
    """The null space of each element's coefficients: :func:`residue_null_space`, or
    :func:`antisymmetric_null_space` for an antisymmetric part."""
    null = residue_null_space(poles)
    anti = antisymmetric_null_space(poles) if any(map(is_antisymmetric, elements)) else None
    return [anti if is_antisymmetric(x) else null for x in elements]


def fit_residues(data: BlockData, poles: Poles) -> tuple[NDArray, NDArray]:
    """Coefficients (n_elements, count) with Σ R_k = 0 (and the antisymmetric parts'
    constraints), and A∞ per element."""
    free = data.free_inf
    x = np.zeros((len(data.elements), poles.count))
    inf = np.zeros(len(data.elements)) if data.fixed_inf is None else data.fixed_inf.copy()
    nulls = element_null_spaces(data.elements, poles)
    for e, null, rows, rhs in residue_equations(data, poles, nulls):
        z = _least_squares(rows, rhs)
        x[e] = null @ z[: null.shape[1]]
        if free[e]:
            inf[e] = z[-1]
    return x, inf


def residue_equations(data: BlockData, poles: Poles, nulls):
    """Each element's weighted equations at ``poles`` (e, null space, rows, rhs) in its
    coefficients in ``nulls[e]`` (:func:`element_null_spaces`), then A∞ when estimated:
    real rows over imaginary, the prior of A∞, K(0) (:func:`fit_residues` solves them)."""
    s = 1j * data.omega
    phi = poles.kept_basis(s)
    free = data.free_inf
    columns: dict = {}
    n_s = s.size
    for e, (f, wr, wi, null) in enumerate(
        zip(data.values, data.weight_real, data.weight_imag, nulls, strict=True)
    ):
        key = (id(null), bool(free[e]))
        if key not in columns:
            m = phi @ null
            columns[key] = np.hstack([m, np.ones((s.size, 1))]) if free[e] else m
        m = columns[key]
        prior = free[e] and data.inf_guess is not None and data.inf_spread[e] > 0
        zero = data.kernel_zero_equations[e]
        rows = np.zeros((2 * n_s + int(prior) + (zero is not None), m.shape[1]))
        rhs = np.empty(rows.shape[0])
        np.multiply(wr[:, None], m.real, out=rows[:n_s])
        np.multiply(wi[:, None], m.imag, out=rows[n_s : 2 * n_s])
        np.multiply(wr, f.real, out=rhs[:n_s])
        np.multiply(wi, f.imag, out=rhs[n_s : 2 * n_s])
        if prior:
            # weighs as all the added-mass equations (each 1/spread of A over √n)
            weight = 1.0 / data.inf_spread[e]
            rows[2 * n_s, -1] = weight
            rhs[2 * n_s] = weight * data.inf_guess[e]
        if zero is not None:  # K(0): the damping beyond the data is data too
            form = np.zeros(m.shape[1])
            form[: null.shape[1]] = kernel_zero_form(poles) @ null
            rows[-1], rhs[-1] = zero[0] * form, zero[0] * zero[1]
        yield e, null, rows, rhs


@dataclass(frozen=True)
class PoleResidueBlock:
    """A fitted block in pole–residue form: K_ij(jω) = jω basis(jω) · x_e."""

    dofs: tuple[int, ...]
    elements: tuple[tuple[int, int], ...]
    poles: Poles
    coefficients: NDArray[np.float64]
    added_mass_inf: NDArray[np.float64]

    def element_response(self, omega: NDArray) -> NDArray[np.complex128]:
        """K of each element, (n_omega, n_elements)."""
        w = np.asarray(omega, dtype=float)
        return 1j * w[:, None] * (self.poles.kept_basis(1j * w) @ self.coefficients.T)

    def element_impulse(self, t: NDArray) -> NDArray[np.float64]:
        """K(t) of each element, (n_t, n_elements): K(s) = Σ x p/(s − p) over the real
        poles and (a + jb) p/(s − p) + c.c. over the pairs (Σ R_k = 0), so K(t) =
        Σ x p e^{pt} + 2 Re[(a + jb) p e^{pt}]."""
        t = np.asarray(t, dtype=float).reshape(-1, 1)
        nr = self.poles.real.size
        real = self.poles.real[None, :]
        out = (real * np.exp(real * t)) @ self.coefficients[:, :nr].T
        if self.poles.pairs.size:
            p = self.poles.pairs[None, :]
            residue = self.coefficients[:, nr::2] + 1j * self.coefficients[:, nr + 1 :: 2]
            out = out + 2.0 * np.real((p * np.exp(p * t)) @ residue.T)
        return out

    def response(self, omega: NDArray) -> NDArray[np.complex128]:
        """K(jω) of the block, (n_omega, m, m), local DOF order."""
        return _element_matrix(self, self.element_response(omega).T)

    def hermitian_part(self, omega: NDArray) -> NDArray:
        """½(K(jω) + K(jω)ᴴ) = Re K_s + j Im K_a, (n_omega, m, m): real (Re K) for a
        symmetric block, Hermitian for one with pairs fitted as given."""
        if self.symmetric:
            return self.response(omega).real
        values = self.element_response(omega)
        anti = np.array([is_antisymmetric(x) for x in self.elements])
        values = np.where(anti[None, :], 1j * values.imag, values.real + 0j)
        return _element_matrix(self, values.T)

    @property
    def symmetric(self) -> bool:
        """No pair fitted as given: K(s) and the residue matrices are symmetric."""
        return not any(map(is_antisymmetric, self.elements))

    def pair_values(self, values: NDArray) -> dict[tuple[int, int], NDArray]:
        """The values of the ordered pairs (i, j) (model indices) from one value per
        element (``values`` (n_elements, …)): a symmetric element gives (i, j); a pair
        fitted as given gives X_ij = s − a and X_ji = s + a from its symmetric part s and
        its antisymmetric part a = ½(X_ji − X_ij) (element (j, i))."""
        values = np.asarray(values)
        anti = {(q, p): e for e, (p, q) in enumerate(self.elements) if p > q}
        out = {}
        for e, (i, j) in enumerate(self.elements):
            if i > j:
                continue
            if (i, j) in anti:
                a = values[anti[(i, j)]]
                out[(i, j)], out[(j, i)] = values[e] - a, values[e] + a
            else:
                out[(i, j)] = values[e]
        return out

    def residue_matrices(self) -> list[tuple[complex, NDArray]]:
        """(p_k, M_k) with K(s) = Σ M_k/(s − p_k) over real poles and the upper member
        of each pair (its conjugate carries M̄_k)."""
        nr = self.poles.real.size
        out = []
        for k, p in enumerate(self.poles.real):
            out.append((complex(p), _element_matrix(self, self.coefficients[:, k]) * p))
        for k, p in enumerate(self.poles.pairs):
            value = self.coefficients[:, nr + 2 * k] + 1j * self.coefficients[:, nr + 2 * k + 1]
            out.append((complex(p), _element_matrix(self, value) * p))
        return out

    def coordinate_realization(self) -> tuple[NDArray, NDArray, NDArray]:
        """(a, b, c) of K(s) in the poles' real coordinates, one state per DOF and real
        parameter (:meth:`Poles.state_form` ⊗ I): not minimal, but built without a
        factorisation, for the passivity sweep. K(s) = s C(sI − Λ⊗I)⁻¹(β⊗I) =
        C(Λ⊗I)(sI − Λ⊗I)⁻¹(β⊗I), the constant C(β⊗I) being zero in the residue null space."""
        lam, beta = self.poles.state_form()
        m = len(self.dofs)
        x = _element_matrix(self, self.coefficients)  # (parameters, m, m)
        a = np.kron(lam, np.eye(m))
        c = x.transpose(1, 0, 2).reshape(m, -1)  # [X_1 X_2 …], X_k the matrix of parameter k
        return a, np.kron(beta[:, None], np.eye(m)), c @ a

    def realization(self, rank_tol: float = RANK_TOL) -> tuple[NDArray, NDArray, NDArray]:
        """Gilbert's realization (a, b, c), block DOF order: one state per rank of each
        residue matrix (eigenvalues of a symmetric real one, singular values otherwise:
        R = U Σ Vᴴ); ranks below ``rank_tol`` × the largest residue entry are dropped."""
        terms = self.residue_matrices()
        m = len(self.dofs)
        top = max((float(np.abs(mk).max()) for _, mk in terms), default=0.0)
        a_blocks, b_blocks, c_blocks = [], [], []
        symmetric = self.symmetric
        for p, mk in terms:
            if p.imag == 0 and not symmetric:  # a real residue matrix R = U Σ Vᵀ
                u, sv, vh = np.linalg.svd(mk.real)
                keep = sv > rank_tol * top
                r = int(keep.sum())
                if r:
                    a_blocks.append(p.real * np.eye(r))
                    b_blocks.append(vh[keep])
                    c_blocks.append(u[:, keep] * sv[keep])
                continue
            if p.imag == 0:
                lam, u = np.linalg.eigh(mk.real)
                keep = np.abs(lam) > rank_tol * top
                r = int(keep.sum())
                if r:
                    a_blocks.append(p.real * np.eye(r))
                    b_blocks.append(u[:, keep].T)
                    c_blocks.append(u[:, keep] * lam[keep])
                continue
            u, sv, vh = np.linalg.svd(mk)
            keep = sv > rank_tol * top
            r = int(keep.sum())
            if not r:
                continue
            c1, b1 = u[:, keep] * sv[keep], vh[keep]
            eye = np.eye(r)
            a_blocks.append(np.block([[p.real * eye, -p.imag * eye], [p.imag * eye, p.real * eye]]))
            b_blocks.append(np.vstack([b1.real, b1.imag]))
            c_blocks.append(np.hstack([2 * c1.real, -2 * c1.imag]))
        if not a_blocks:
            return np.zeros((0, 0)), np.zeros((0, m)), np.zeros((m, 0))
        return scipy.linalg.block_diag(*a_blocks), np.vstack(b_blocks), np.hstack(c_blocks)


def vector_fit(data: BlockData, count: int) -> PoleResidueBlock:
    """Common poles (``count`` real parameters), residues and A∞ of a block."""
    poles = starting_poles(data.omega[: data.n_data], count)
    thinned = data.relocation_data
    for _ in range(ITERATIONS):
        moved = relocate(thinned, poles)
        converged = _same_poles(moved, poles)
        poles = moved
        if converged:
            break
    coefficients, inf = fit_residues(data, poles)
    return PoleResidueBlock(data.dofs, data.elements, poles, coefficients, inf)


def _element_matrix(block: PoleResidueBlock, values: NDArray) -> NDArray:
    """The m×m matrices of one value per element (block DOF order): ``values``
    (n_elements, …) gives (…, m, m), in its dtype; symmetric but for the antisymmetric
    parts (p, q), p > q, added at (p, q) and subtracted at (q, p)."""
    values = np.asarray(values)
    where = {d: k for k, d in enumerate(block.dofs)}
    m = len(block.dofs)
    out = np.zeros((*values.shape[1:], m, m), dtype=np.result_type(values, float))
    for e, (i, j) in enumerate(block.elements):
        if i <= j:
            out[..., where[i], where[j]] = out[..., where[j], where[i]] = values[e]
    for e, (i, j) in enumerate(block.elements):
        if i > j:
            out[..., where[i], where[j]] += values[e]
            out[..., where[j], where[i]] -= values[e]
    return out


def fit_residues_at(data: BlockData, poles: Poles) -> PoleResidueBlock:
    """The unconstrained fit of the block at given poles (before passivity)."""
    coefficients, inf = fit_residues(data, poles)
    return PoleResidueBlock(data.dofs, data.elements, poles, coefficients, inf)
