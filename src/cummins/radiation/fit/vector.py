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
   change of the fit (linearised eigenvalue constraints, accumulated; Gustavsen &
   Semlyen (2001)'s residue perturbation, solved as a least-distance programme, Lawson &
   Hanson (1974)). The violations are looked for on a dense grid while it sees any (the
   deep ones of the first iterations), then between the exact crossings of the
   Hamiltonian pencil (:func:`cummins.radiation.passivity.imaginary_axis_zeros`), which
   also find the bands narrower than the grid: a block is passive only when that exact
   test finds none. The poles do not move, so the model stays stable.
4. **Order**: the number of common poles grows until every coupling reaches its R²
   targets and the motion error of the block is within its aim
   (:mod:`cummins.radiation.fit.order_search`).
5. **Realization**: Gilbert's realization of the pole–residue form, one state per rank
   of each residue matrix (a surge–pitch pair whose damping is rank one, as on a sphere
   about a point off its centre, costs one state per pole, not two).

The result is one :class:`~cummins.radiation.model.MemoryBlock` per block.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from cummins.errors import FitError
from cummins.radiation.damping_tail import DampingTail
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
#: No pole beyond POLE_SPAN × the highest data frequency in magnitude: the data do not
#: ask for one, the damping tail beyond them decays without one (issue 31), and a fast
#: pole makes the model stiff (the tanker's relocation, without the tail's equations,
#: found a real pole at −36.8 rad/s, 11 × its 3.4 rad/s: a Runge–Kutta run at 0.1 s with
#: quadratic roll damping diverged).
POLE_SPAN = 3.0
#: Initial relative damping of the starting poles.
START_DAMPING = 0.01
#: Passivity: a violation is λ_min(Re K) < −VIOLATION · max ‖K‖ on the check grid.
VIOLATION = 1e-8
#: Passivity: each linearised constraint asks for λ ≥ MARGIN × the largest |λ| there, an
#: overshoot so that the next sweep does not find the band violated again (1e-5 took
#: 2.5× the iterations: 203 against 79 on the NEMOH Cubes, same orders and RAO errors).
MARGIN = 1e-3
#: Passivity enforcement iterations.
PASSIVITY_ITERATIONS = 120
#: The passivity programme keeps every constraint until it has PRUNE_ROWS times as many
#: as unknowns; then those that have never bound are left out (the WAMIT OSWEC 2015's
#: non-passive data built 9 000 constraints on 275 unknowns: 300 s for the fit, now 43 s).
PRUNE_ROWS = 1
#: Regularisation of the residue change (× the norm of the misfit Jacobian): directions
#: the data do not see stay put.
RIDGE = 1e-3
#: Frequencies of the passivity check: from CHECK_SPAN⁻¹ ω_min to CHECK_SPAN ω_max.
CHECK_SPAN = 1e3
CHECK_POINTS = 1500
#: At most this many local minima of λ_min per violation band give constraints at once.
MINIMA = 8
#: Residue-matrix eigenvalues below RANK_TOL × the largest of the block cost no state.
RANK_TOL = 0.0


# ----------------------------------------------------------------------------- poles


@dataclass(frozen=True)
class Poles:
    """Common poles in real form: ``real`` (negative) and ``pairs`` (Im > 0)."""

    real: NDArray[np.float64]
    pairs: NDArray[np.complex128]

    @property
    def count(self) -> int:
        """Number of real parameters per coupling (a pair counts two)."""
        return self.real.size + 2 * self.pairs.size

    def basis(self, s: NDArray) -> NDArray[np.complex128]:
        """Columns 1/(s − p) for real p; 1/(s − p) + 1/(s − p̄) and j/(s − p) − j/(s − p̄)
        for a pair (coefficients a, b: residue a + jb at p)."""
        s = np.asarray(s, dtype=complex)
        cols = [1.0 / (s[:, None] - self.real[None, :])]
        if self.pairs.size:
            one = 1.0 / (s[:, None] - self.pairs[None, :])
            two = 1.0 / (s[:, None] - np.conj(self.pairs)[None, :])
            pair = np.empty((s.size, 2 * self.pairs.size), dtype=complex)
            pair[:, 0::2] = one + two
            pair[:, 1::2] = 1j * (one - two)
            cols.append(pair)
        return np.hstack(cols)

    def state_form(self) -> tuple[NDArray, NDArray]:
        """(Λ, b) with basis(s) = (sI − Λ)⁻¹ b written in the same real coordinates."""
        n = self.count
        lam, b = np.zeros((n, n)), np.zeros(n)
        nr = self.real.size
        lam[:nr, :nr] = np.diag(self.real)
        b[:nr] = 1.0
        for k, p in enumerate(self.pairs):
            i = nr + 2 * k
            lam[i : i + 2, i : i + 2] = [[p.real, p.imag], [-p.imag, p.real]]
            b[i] = 2.0
        return lam, b

    def residue_sum(self) -> NDArray[np.float64]:
        """The linear form of the coefficients giving Σ_k R_k (conjugates included)."""
        v = np.zeros(self.count)
        v[: self.real.size] = 1.0
        v[self.real.size :: 2] = 2.0
        return v


def _poles_from(values: NDArray, limit: float = np.inf) -> Poles:
    """Sorted, stable, damped poles in real form from a set closed under conjugation, none
    beyond ``limit`` (rad/s) in magnitude (:data:`POLE_SPAN`)."""
    values = np.asarray(values, dtype=complex)
    size = np.abs(values)
    values = np.where(size > limit, values * limit / np.where(size > 0, size, 1.0), values)
    scale = np.abs(values) + np.finfo(float).tiny
    is_real = np.abs(values.imag) <= 1e-9 * scale
    real = -np.abs(values[is_real].real)
    pairs = values[~is_real & (values.imag > 0)]
    decay = np.maximum(np.abs(pairs.real), MIN_DAMPING * np.abs(pairs))
    pairs = -decay + 1j * np.abs(pairs.imag)
    real = np.where(real == 0, -np.finfo(float).eps, real)
    return Poles(np.sort(real)[::-1], pairs[np.argsort(pairs.imag)])


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
        A∞ of each element when it is given (then not estimated), else None.
    n_data
        The number of data frequencies (the first ``n_data`` of ``omega``).
    inf_guess, inf_spread
        When A∞ is estimated: a prior per element (Ogilvie's estimate and its spread);
        one more equation (A∞ − guess)/spread weighs like all the added-mass equations
        of the element together, so that the data decide where they are informative
        and the prior where the model would extrapolate.
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
    tail_weight: float = 1.0,
    time=None,
    kernel=None,
) -> BlockData:
    """Equations of a block (see :class:`BlockData`).

    ``added_mass``, ``damping``: symmetric parts of the data (omega, n, n); ``used``:
    (omega, n_elements) which frequencies each coupling keeps; ``motion_weight``:
    callable (i, j) → W_ij(ω) of :class:`cummins.radiation.fit.motion.MotionSensitivity` or None;
    ``prior``: (guess, spread) matrices of A∞ when it is estimated; ``tail_weight``: a
    factor on the weight of the damping tail beyond the data
    (:func:`cummins.radiation.fit.tail.tail_equations`); ``time``, ``kernel``: the data's
    K(t) (time, n, n), for the R² of K(t) of the diagonal elements.
    """
    w = np.asarray(omega, dtype=float)
    tail = tail_frequencies(w.max())
    values, wr, wi, tails = [], [], [], []
    beyond = block_tail_equations(w, added_mass, damping, used, elements, tail)
    for e, (i, j) in enumerate(elements):
        use = used[:, e]
        n_use = max(int(use.sum()), 1)
        a_ij, b_ij = added_mass[:, i, j], damping[:, i, j]
        floor_a = 1e-3 * np.sqrt(np.std(added_mass[:, i, i]) * np.std(added_mass[:, j, j]))
        floor_b = 1e-3 * np.sqrt(np.std(damping[:, i, i]) * np.std(damping[:, j, j]))
        spread_a = max(float(np.std(a_ij[use])), floor_a, np.finfo(float).tiny)
        spread_b = max(float(np.std(b_ij[use])), floor_b, np.finfo(float).tiny)
        r_a = np.full(w.size, 1.0 / spread_a) / np.sqrt(n_use)
        r_b = w / spread_b / np.sqrt(n_use)
        if motion_weight is not None:
            m = motion_weight(i, j) * w / motion_tol / np.sqrt(n_use)
            r_a, r_b = np.hypot(r_a, m), np.hypot(r_b, m)
        r_a, r_b = np.where(use, r_a, 0.0), np.where(use, r_b, 0.0)
        offset = 0.0 if added_mass_inf is None else added_mass_inf[i, j]
        # beyond the data: the data's damping tail, weighed as the data it stands for
        b_tail, weight, element_tail = beyond[e]
        tails.append(element_tail)
        values.append(np.r_[a_ij - offset - 1j * b_ij / w, -1j * b_tail / tail])
        wr.append(np.r_[r_a, np.zeros(tail.size)])
        wi.append(np.r_[r_b, tail_weight * weight * tail / spread_b / np.sqrt(n_use)])
    fixed = guess = spread = None
    if added_mass_inf is not None:
        fixed = np.array([added_mass_inf[i, j] for i, j in elements])
    elif prior is not None:
        guess = np.array([prior[0][i, j] for i, j in elements])
        spread = np.array([prior[1][i, j] for i, j in elements])
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
    )


def _stacked(m: NDArray, wr: NDArray, wi: NDArray) -> NDArray:
    return np.vstack([wr[:, None] * m.real, wi[:, None] * m.imag])


# ----------------------------------------------------------------------------- fitting


def relocate(data: BlockData, poles: Poles) -> Poles:
    """One relaxed vector-fitting relocation of the common poles (fast QR)."""
    s = 1j * data.omega
    phi = poles.basis(s)
    n = phi.shape[1]
    ones = np.ones((s.size, 1))
    own = phi if data.fixed_inf is not None else np.hstack([phi, ones])
    sigma = np.hstack([phi, ones])
    k = own.shape[1]
    f, wr, wi = data.values, data.weight_real, data.weight_imag
    # one QR per element, stacked: [own, −f σ] weighted, real rows over imaginary rows
    m = np.concatenate([np.broadcast_to(own, (f.shape[0], *own.shape)), -f[:, :, None] * sigma], 2)
    r = np.linalg.qr(np.concatenate([wr[:, :, None] * m.real, wi[:, :, None] * m.imag], 1), "r")
    blocks = list(r[:, k : k + n + 1, k:])
    scale = np.sqrt(float(np.sum((wr * f.real) ** 2 + (wi * f.imag) ** 2))) / s.size
    norm = scale * np.real(sigma.sum(axis=0))
    lhs = np.vstack([*blocks, norm[None, :]])
    rhs = np.zeros(lhs.shape[0])
    rhs[-1] = scale * s.size
    x, *_ = np.linalg.lstsq(lhs, rhs, rcond=None)
    c, d = x[:n], x[n]
    if abs(d) < 1e-8 * max(1.0, float(np.abs(c).max())):  # relaxation failed: σ(∞) = 1
        stack = np.vstack(blocks)
        c, *_ = np.linalg.lstsq(stack[:, :n], -stack[:, n], rcond=None)
        d = 1.0
    lam, b = poles.state_form()
    limit = POLE_SPAN * float(data.omega[: data.n_data].max())
    return _poles_from(np.linalg.eigvals(lam - np.outer(b, c) / d), limit)


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
    )


def _same_poles(one: Poles, two: Poles) -> bool:
    """The relocation has converged: the same poles to CONVERGED (relative)."""
    if one.real.size != two.real.size or one.pairs.size != two.pairs.size:
        return False
    x = np.r_[one.real, one.pairs]
    y = np.r_[two.real, two.pairs]
    return bool(np.all(np.abs(x - y) <= CONVERGED * np.abs(y)))


def residue_null_space(poles: Poles) -> NDArray[np.float64]:
    """Orthonormal basis of the coefficient vectors with Σ R_k = 0."""
    v = poles.residue_sum()
    q, _ = np.linalg.qr(np.c_[v, np.eye(v.size)[:, : v.size - 1]])
    return q[:, 1:]


def fit_residues(data: BlockData, poles: Poles) -> tuple[NDArray, NDArray]:
    """Coefficients (n_elements, count) with Σ R_k = 0, and A∞ per element."""
    s = 1j * data.omega
    phi = poles.basis(s)
    null = residue_null_space(poles)
    m = phi @ null
    if data.fixed_inf is None:
        m = np.hstack([m, np.ones((s.size, 1))])
    x = np.zeros((len(data.elements), poles.count))
    inf = np.zeros(len(data.elements)) if data.fixed_inf is None else data.fixed_inf.copy()
    for e, (f, wr, wi) in enumerate(
        zip(data.values, data.weight_real, data.weight_imag, strict=True)
    ):
        rows = _stacked(m, wr, wi)
        rhs = np.concatenate([wr * f.real, wi * f.imag])
        if data.fixed_inf is None and data.inf_guess is not None and data.inf_spread[e] > 0:
            # the prior: weighs like all the added-mass equations together (their
            # weights are 1/spread of A over √n each)
            weight = 1.0 / data.inf_spread[e]
            prior_row = np.zeros(m.shape[1])
            prior_row[-1] = weight
            rows = np.vstack([rows, prior_row])
            rhs = np.r_[rhs, weight * data.inf_guess[e]]
        zero = kernel_zero_equation(data, e)
        if zero is not None:  # K(0): the damping beyond the data is data too
            form = np.zeros(m.shape[1])
            form[: null.shape[1]] = kernel_zero_form(poles) @ null
            rows = np.vstack([rows, zero[0] * form])
            rhs = np.r_[rhs, zero[0] * zero[1]]
        z, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
        x[e] = null @ z[: null.shape[1]]
        if data.fixed_inf is None:
            inf[e] = z[-1]
    return x, inf


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
        return 1j * w[:, None] * (self.poles.basis(1j * w) @ self.coefficients.T)

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

    def residue_matrices(self) -> list[tuple[complex, NDArray]]:
        """(p_k, M_k) with K(s) = Σ M_k/(s − p_k) over real poles and the upper member
        of each pair (its conjugate carries M̄_k)."""
        where = {d: k for k, d in enumerate(self.dofs)}
        m, nr = len(self.dofs), self.poles.real.size
        out = []
        for k, p in enumerate(self.poles.real):
            r = np.zeros((m, m))
            for e, (i, j) in enumerate(self.elements):
                r[where[i], where[j]] = r[where[j], where[i]] = self.coefficients[e, k]
            out.append((complex(p), r * p))
        for k, p in enumerate(self.poles.pairs):
            r = np.zeros((m, m), dtype=complex)
            for e, (i, j) in enumerate(self.elements):
                value = self.coefficients[e, nr + 2 * k] + 1j * self.coefficients[e, nr + 2 * k + 1]
                r[where[i], where[j]] = r[where[j], where[i]] = value
            out.append((complex(p), r * p))
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
        """Gilbert's realization (a, b, c), block DOF order; residue ranks below
        ``rank_tol`` × the largest residue eigenvalue are dropped."""
        terms = self.residue_matrices()
        m = len(self.dofs)
        top = max((float(np.abs(mk).max()) for _, mk in terms), default=0.0)
        a_blocks, b_blocks, c_blocks = [], [], []
        for p, mk in terms:
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
    thinned = _thinned(data)
    for _ in range(ITERATIONS):
        moved = relocate(thinned, poles)
        converged = _same_poles(moved, poles)
        poles = moved
        if converged:
            break
    coefficients, inf = fit_residues(data, poles)
    return PoleResidueBlock(data.dofs, data.elements, poles, coefficients, inf)


# ----------------------------------------------------------------------------- passivity


def passivity_violations(
    block: PoleResidueBlock, omega_min: float, omega_max: float, exact: bool = True
) -> tuple[list[tuple[float, float, NDArray, float]], NDArray]:
    """(g, λ, w, λ_scale) of the points where S Re K(jω) S (DOF-scaled: s_i =
    1/√max_ω |K_ii(jω)|, as :func:`cummins.radiation.passivity.dof_scaling`, so that translations
    and rotations weigh alike) has a negative eigenvalue λ below −:data:`VIOLATION`, at the
    worst point of each band between exact crossings and a few points across it, and of
    the limits ω → 0, ∞ (:func:`limit_forms`) below −VIOLATION × their largest
    eigenvalue: g the linear form giving each element of Re K there from its
    coefficients, w = S v (v the eigenvector: wᵀ Re K w = λ) and the largest |λ| there;
    and S.

    ``exact=False`` takes the bands from the sign changes of λ_min on the grid alone: no
    pencil to factor (its QZ is most of the sweep's cost on a 12-DOF block), but a band
    narrower than the grid's spacing is not seen."""
    from cummins.radiation.passivity import band_points

    grid = np.geomspace(omega_min / CHECK_SPAN, omega_max * CHECK_SPAN, CHECK_POINTS)
    k_grid = block.response(grid).real
    peak = np.abs(np.diagonal(k_grid, axis1=1, axis2=2)).max(axis=0)
    dof_scale = np.where(peak > 0, 1.0 / np.sqrt(np.where(peak > 0, peak, 1.0)), 0.0)
    if exact:
        a, b, c = block.coordinate_realization()
        b, c = b * dof_scale[None, :], dof_scale[:, None] * c  # S K S: well conditioned
        # every point once: the grid, five inside each band between crossings, its midpoint
        edges, extra = band_points(a, b, c, grid)
        points = np.r_[grid, extra]
        order = np.argsort(points)
        points = points[order]
        k_all = np.concatenate([k_grid, block.response(extra).real])[order]
        lam_all, vec_all = np.linalg.eigh(k_all * np.outer(dof_scale, dof_scale)[None])
    else:
        points = grid
        lam_all, vec_all = np.linalg.eigh(k_grid * np.outer(dof_scale, dof_scale)[None])
        negative = lam_all[:, 0] < 0
        change = np.flatnonzero(negative[1:] != negative[:-1])
        edges = np.r_[0.0, np.sqrt(grid[change] * grid[change + 1]), np.inf]
    out, chosen = [], []
    # between consecutive crossings the sign of λ_min is constant
    starts = np.searchsorted(points, edges, side="right")
    stops = np.searchsorted(points, edges, side="left")
    for first, last in zip(starts[:-1], stops[1:], strict=True):
        if last <= first:
            continue
        inside = np.arange(first, last)
        lam = lam_all[inside]
        worst = int(np.argmin(lam[:, 0]))
        if lam[worst, 0] >= -VIOLATION:  # S K S: the diagonal peaks are 1
            continue
        low = lam[:, 0]
        minima = np.flatnonzero(
            (low < -VIOLATION) & (low <= np.r_[np.inf, low[:-1]]) & (low <= np.r_[low[1:], np.inf])
        )
        spread = np.linspace(0, inside.size - 1, 5).astype(int)
        chosen.append(
            inside[np.unique(np.r_[worst, minima[np.argsort(low[minima])][:MINIMA], spread])]
        )
    if chosen:
        at = np.concatenate(chosen)
        forms = np.real(1j * points[at, None] * block.poles.basis(1j * points[at]))
        for form, lam, vec in zip(forms, lam_all[at], vec_all[at], strict=True):
            local = float(np.abs(lam).max())
            for e in np.flatnonzero(lam < 0):
                out.append((form, float(lam[e]), dof_scale * vec[:, e], local))
    # the limits ω → 0 and ω → ∞, where Re K vanishes as ω² L₀ and L_∞/ω²
    for form in limit_forms(block.poles):
        matrix = _element_matrix(block, block.coefficients @ form) * np.outer(dof_scale, dof_scale)
        lam, vec = np.linalg.eigh(matrix)
        local = float(np.abs(lam).max())
        for e in np.flatnonzero(lam < -VIOLATION * local):
            out.append((form, float(lam[e]), dof_scale * vec[:, e], local))
    return out, dof_scale


def limit_forms(poles: Poles) -> tuple[NDArray, NDArray]:
    """The linear forms g (one per coefficient) of the limits of Re K: L_∞ = lim ω² Re K
    (= −C A B = −Σ R_k p_k²) and L₀ = lim Re K / ω² (= C A⁻³ B = Σ R_k / p_k²), each
    element of L being g · x_e."""
    high, low = np.zeros(poles.count), np.zeros(poles.count)
    nr = poles.real.size
    high[:nr], low[:nr] = -(poles.real**2), 1.0 / poles.real**2
    squared, inverse = poles.pairs**2, 1.0 / poles.pairs**2
    high[nr::2], high[nr + 1 :: 2] = -2 * squared.real, 2 * squared.imag
    low[nr::2], low[nr + 1 :: 2] = 2 * inverse.real, -2 * inverse.imag
    return high, low


def _element_matrix(block: PoleResidueBlock, values: NDArray) -> NDArray:
    """The symmetric m×m matrices of one value per element (block DOF order): ``values``
    (n_elements, …) gives (…, m, m), in its dtype."""
    values = np.asarray(values)
    where = {d: k for k, d in enumerate(block.dofs)}
    m = len(block.dofs)
    out = np.zeros((*values.shape[1:], m, m), dtype=np.result_type(values, float))
    for e, (i, j) in enumerate(block.elements):
        out[..., where[i], where[j]] = out[..., where[j], where[i]] = values[e]
    return out


def enforce_passivity(
    block: PoleResidueBlock, data: BlockData, bounds=None
) -> tuple[PoleResidueBlock, bool, int]:
    """The block with the smallest weighted residue change that makes Re K(jω) ⪰ 0 at all
    frequencies (module docstring, step 3): (block, passive, iterations).

    ``bounds``: a callable (block → more violated linear constraints, in the form of
    :func:`passivity_violations`' (g, λ, w, scale)) that the same programme meets: the
    damping beyond the data held under the data's tail
    (:func:`cummins.radiation.fit.tail.tail_bound_violations`), so that the passivity
    step does not raise it there."""
    from cummins.radiation.passivity import least_distance

    w = data.omega[: data.n_data]
    s = 1j * data.omega
    null = residue_null_space(block.poles)
    q = null.shape[1]
    phi = block.poles.basis(s) @ null
    misfit = []
    for e, (wr, wi) in enumerate(zip(data.weight_real, data.weight_imag, strict=True)):
        jac = _stacked(phi, wr, wi)
        zero = kernel_zero_equation(data, e)
        if zero is not None:  # K(0), as the residues were fitted
            jac = np.vstack([jac, zero[0] * kernel_zero_form(block.poles) @ null])
        ridge = RIDGE * np.linalg.norm(jac, 2)
        # ‖J z‖ = ‖R z‖: the small triangular factor stands for the whole misfit
        r = np.linalg.qr(np.vstack([jac, ridge * np.eye(q)]), mode="r")
        misfit.append((r, np.zeros(q)))
    where = {d: k for k, d in enumerate(block.dofs)}
    rows, rhs = [], []
    bound = np.zeros(0, dtype=bool)
    start = block.coefficients
    delta = np.zeros(len(block.elements) * q)
    current = block
    # the grid while it sees violations, then the exact crossings to the end (the narrow
    # bands they find come back for a few iterations): half the sweeps' cost on two
    # bodies, and the grid alone took twice the iterations on the ITI barge
    exact = False
    for iteration in range(PASSIVITY_ITERATIONS):
        found, _ = passivity_violations(current, float(w.min()), float(w.max()), exact=exact)
        if not found and not exact:
            exact = True
            found, _ = passivity_violations(current, float(w.min()), float(w.max()), exact=exact)
        found = found + ([] if bounds is None else bounds(current))
        if not found:
            return current, True, iteration
        for form, lam, vec, local in found:
            basis = form @ null
            row = np.zeros(len(block.elements) * q)
            for e, (i, j) in enumerate(block.elements):
                vi, vj = vec[where[i]], vec[where[j]]
                row[e * q : (e + 1) * q] = (vi * vi if i == j else 2 * vi * vj) * basis
            rows.append(row)
            rhs.append(MARGIN * local - lam + row @ delta)
        try:
            delta, active = least_distance(misfit, np.array(rows), np.array(rhs))
        except FitError:
            return current, False, iteration
        # once the programme is large, a constraint that has never bound is left out of
        # the next ones (were it violated again, the next sweep finds it); one that has
        # bound is kept, or the iteration goes round in circles
        bound = np.r_[bound, np.zeros(len(rows) - bound.size, dtype=bool)] | active
        if len(rows) > PRUNE_ROWS * delta.size:
            rows = [r for r, a in zip(rows, bound, strict=True) if a]
            rhs = [h for h, a in zip(rhs, bound, strict=True) if a]
            bound = bound[bound]
        change = (null @ delta.reshape(len(block.elements), q).T).T
        current = PoleResidueBlock(
            block.dofs, block.elements, block.poles, start + change, block.added_mass_inf
        )
    found, _ = passivity_violations(current, float(w.min()), float(w.max()))
    return current, not found, PASSIVITY_ITERATIONS


def fit_residues_at(data: BlockData, poles: Poles) -> PoleResidueBlock:
    """The unconstrained fit of the block at given poles (before passivity)."""
    coefficients, inf = fit_residues(data, poles)
    return PoleResidueBlock(data.dofs, data.elements, poles, coefficients, inf)
