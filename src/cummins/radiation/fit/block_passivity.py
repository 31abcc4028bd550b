"""Passivity of a common-pole block (:mod:`cummins.radiation.fit.vector`, step 3): where
K(jω) + K(jω)ᴴ has a negative eigenvalue (:func:`passivity_violations`) and the smallest
weighted residue change that removes every one (:func:`enforce_passivity`).

K(jω) + K(jω)ᴴ = 2 Re K(jω) ⪰ 0 at all frequencies (Unneland (2007) Prop. 3.4; for a
block with pairs fitted as given, 2(Re K_s + j Im K_a), eq. 3.13) is enforced on the
residues of the whole block by the smallest weighted change of the fit (linearised
eigenvalue constraints, accumulated; Gustavsen & Semlyen (2001)'s residue perturbation,
solved as a least-distance programme, Lawson & Hanson (1974)). The violations are
looked for on a dense grid while it sees any (the deep ones of the first iterations),
then between the exact crossings of the Hamiltonian pencil
(:func:`cummins.radiation.passivity.imaginary_axis_zeros`), which also find the bands
narrower than the grid: a block is passive only when that exact test finds none. The
poles do not move, so the model stays stable.
"""

from __future__ import annotations

import threading
import weakref
from collections.abc import Generator

import numpy as np
from numpy.typing import NDArray

from cummins.errors import FitError
from cummins.radiation.fit.tail import kernel_zero_form
from cummins.radiation.fit.vector import (
    BlockData,
    PoleResidueBlock,
    Poles,
    _element_matrix,
    _stacked,
    element_null_spaces,
    is_antisymmetric,
)

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
#: the data do not see stay put. A compromise, not a gap in the spectrum (the Jacobian's
#: singular values fall smoothly to 1e-5 of the largest): smaller ridges, or ridges
#: relative to each column's norm, helped the HAMS cylinders and worsened the NEMOH two
#: bodies on the 38 cases (BENCHMARKS.md, the ridge, 2026-12-06).
RIDGE = 1e-3
#: Frequencies of the passivity check: from CHECK_SPAN⁻¹ ω_min to CHECK_SPAN ω_max.
CHECK_SPAN = 1e3
CHECK_POINTS = 1500
#: At most this many local minima of λ_min per violation band give constraints at once.
MINIMA = 8
#: How often (iterations) :func:`enforce_passivity` asks its ``give_up`` (and
#: :func:`enforcement_steps` yields its iterate).
GIVE_UP_EVERY = 3
#: λ_min on the check grid: a point is positive definite, its eigenvalues not computed,
#: where the Cholesky factorisation of its matrix M less POSITIVE_SHIFT × tr M runs to
#: the end (:func:`lowest_eigenvalues`).
POSITIVE_SHIFT = 1e-9


#: The last exact test of :func:`passivity_violations` in this thread (``.value``: a weak
#: reference to its block, the crossings found), for :func:`exact_crossings`.
_last_exact = threading.local()


def exact_crossings(block: PoleResidueBlock) -> NDArray | None:
    """The crossings (rad/s) that the last exact test of :func:`passivity_violations`
    found when it was of ``block`` itself (the same object), else None: the enforcement
    and the motion refinement end on an exact test of the block they return, which the
    model's test (:func:`~cummins.radiation.passivity.passivity_test`) need not repeat
    (its pencil's QZ: 0.12 s at 200 states). The crossings of S K S are those of K for
    any nonsingular S: the block's DOF scaling and the model's give the same."""
    last = getattr(_last_exact, "value", None)  # read once: this thread's last test
    if last is None or last[0]() is not block:
        return None
    return last[1]


class BlockSweep:
    """What every sweep of one enforcement shares (the poles do not move): the check grid,
    the basis of the poles there, the positions of the elements in the block matrix."""

    def __init__(self, block: PoleResidueBlock, omega_min: float, omega_max: float):
        self.grid = np.geomspace(omega_min / CHECK_SPAN, omega_max * CHECK_SPAN, CHECK_POINTS)
        self.basis = block.poles.basis(1j * self.grid)
        self.basis_real = np.ascontiguousarray(self.basis.real)
        self.basis_imag = np.ascontiguousarray(self.basis.imag)
        where = {d: k for k, d in enumerate(block.dofs)}
        self.size = len(block.dofs)
        self.rows = np.array([where[i] for i, _ in block.elements], dtype=int)
        self.columns = np.array([where[j] for _, j in block.elements], dtype=int)
        self.anti = np.array([is_antisymmetric(x) for x in block.elements], dtype=bool)
        self._last: tuple | None = None  # (coefficients, scaled_grid's answer)
        self.range = (omega_min, omega_max)
        self.band_extra: NDArray | None = None  # the last exact test's points off the grid

    def extend(self, block: PoleResidueBlock, points: NDArray) -> None:
        """The grid with ``points`` added (the basis there computed)."""
        self.grid = np.union1d(self.grid, points)
        self.basis = block.poles.basis(1j * self.grid)
        self.basis_real = np.ascontiguousarray(self.basis.real)
        self.basis_imag = np.ascontiguousarray(self.basis.imag)
        self._last = None

    def scaled_grid(self, block: PoleResidueBlock) -> tuple[NDArray, GridLows, NDArray]:
        """(S H S, its λ_min as a :class:`GridLows`, the diagonal of S) on the grid
        for the block (H its :meth:`hermitian_part`, S the DOF scaling of
        :func:`passivity_violations`), kept for the last block asked: an enforcement
        whose grid sweep finds nothing asks again for the same iterate, exactly."""
        if self._last is not None and self._last[0] is block.coefficients:
            return self._last[1]
        k_grid = self.hermitian_part(block)
        peak = np.abs(np.diagonal(k_grid, axis1=1, axis2=2)).max(axis=0)
        dof_scale = np.where(peak > 0, 1.0 / np.sqrt(np.where(peak > 0, peak, 1.0)), 0.0)
        scaled = k_grid * np.outer(dof_scale, dof_scale)[None]
        found = (scaled, GridLows(scaled), dof_scale)
        self._last = (block.coefficients, found)
        return found

    def hermitian_part(self, block: PoleResidueBlock) -> NDArray:
        """:meth:`PoleResidueBlock.hermitian_part` on the grid (the same numbers)."""
        omega = self.grid[:, None]
        imag, real = self.product_parts(block.coefficients)
        # jω × product as numpy's complex product rounds it: (0 + jω)(x + jy) = (0x − ωy)
        # + j(0y + ωx), 0x and 0y zero
        values = 0.0 - omega * imag
        if not self.anti.any():
            out = np.zeros((self.grid.size, self.size, self.size))
            out[:, self.rows, self.columns] = values
            out[:, self.columns, self.rows] = values
            return out
        anti = 0.0 + omega * real
        out = np.zeros((self.grid.size, self.size, self.size), dtype=complex)
        sym = ~self.anti
        rows, columns = self.rows[sym], self.columns[sym]
        out.real[:, rows, columns] = values
        out.real[:, columns, rows] = values
        rows, columns = self.rows[self.anti], self.columns[self.anti]
        out.imag[:, rows, columns] = 0.0 + anti
        out.imag[:, columns, rows] = 0.0 - anti
        return out

    def product_parts(self, coefficients: NDArray) -> tuple[NDArray, NDArray]:
        """(Im P of the symmetric elements, Re P of the antisymmetric ones), P = basis · xᵀ
        on the grid: only those parts enter the Hermitian part. Each is the real product
        of that part of the basis, which gives numpy's complex product's numbers at a
        quarter of the work — not when a part is a single element (a matrix–vector
        product, which rounds otherwise): the complex product then."""
        sym = ~self.anti
        counts = int(sym.sum()), int(self.anti.sum())
        if min(counts) == 1 or counts == (1, 0):
            product = self.basis @ coefficients.T
            return product.imag[:, sym], product.real[:, self.anti]
        if not counts[1]:
            return self.basis_imag @ coefficients.T, np.zeros((self.grid.size, 0))
        return (
            self.basis_imag @ coefficients[sym].T,
            self.basis_real @ coefficients[self.anti].T,
        )


def passivity_violations(
    block: PoleResidueBlock,
    omega_min: float,
    omega_max: float,
    exact: bool = True,
    sweep: BlockSweep | None = None,
) -> tuple[list[tuple[float, float, NDArray, float]], NDArray]:
    """(g, λ, w, λ_scale) of the points where S Re K(jω) S (DOF-scaled: s_i =
    1/√max_ω |K_ii(jω)|, as :func:`cummins.radiation.passivity.dof_scaling`, so that translations
    and rotations weigh alike) has a negative eigenvalue λ below −:data:`VIOLATION`, at the
    worst point of each band between exact crossings and a few points across it, and of
    the limits ω → 0, ∞ (:func:`limit_forms`) below −VIOLATION × their largest
    eigenvalue: g the linear form giving each element of Re K there from its
    coefficients, w = S v (v the eigenvector: wᵀ Re K w = λ) and the largest |λ| there;
    and S.

    With pairs fitted as given, the matrix is the Hermitian part Re K_s + j Im K_a
    (:meth:`PoleResidueBlock.hermitian_part`), g the complex form of K (jω basis(jω)),
    of which a symmetric part takes the real part and an antisymmetric one the
    imaginary, and w complex.

    ``exact=False`` takes the bands from the sign changes of λ_min on the grid alone: no
    pencil to factor (its QZ is most of the sweep's cost on a 12-DOF block), but a band
    narrower than the grid's spacing is not seen. ``sweep``: the :class:`BlockSweep` of
    the block's poles and range (made here when not given)."""
    from cummins.radiation.passivity import band_points

    sweep = sweep or BlockSweep(block, omega_min, omega_max)
    grid = sweep.grid
    scaled, lows, dof_scale = sweep.scaled_grid(block)
    points = grid
    if exact:
        low_all = lows.exact()
        a, b, c = block.coordinate_realization()
        b, c = b * dof_scale[None, :], dof_scale[:, None] * c  # S K S: well conditioned
        # every point once: the grid, five inside each band between crossings, its midpoint
        poles = np.abs(np.concatenate([block.poles.real, block.poles.pairs]))
        edges, extra = band_points(a, b, c, grid, poles.min() if poles.size else None)
        _last_exact.value = (weakref.ref(block), edges[1:-1])
        sweep.band_extra = extra
        order = np.argsort(np.concatenate([grid, extra]))
        points = np.concatenate([grid, extra])[order]
        extra_scaled = block.hermitian_part(extra) * np.outer(dof_scale, dof_scale)[None]
        # λ_min of each matrix alone (lowest_eigenvalues): the grid's kept
        low_all = np.concatenate([low_all, lowest_eigenvalues(extra_scaled)])[order]
        scaled = np.concatenate([scaled, extra_scaled])[order]
    if not exact:
        low_all = lows.for_bands()  # the same bands, minima and worst points
        negative = low_all < 0
        change = np.flatnonzero(negative[1:] != negative[:-1])
        edges = np.concatenate([[0.0], np.sqrt(grid[change] * grid[change + 1]), [np.inf]])
        inside = (grid[change] < edges[1:-1]) & (edges[1:-1] < grid[change + 1])
        if not inside.all():  # a point on an edge: in no band, the runs of signs are not
            low_all = lows.exact()  # the bands (the same signs)
    out, chosen = [], []
    # between consecutive crossings the sign of λ_min is constant
    starts = np.searchsorted(points, edges, side="right")
    stops = np.searchsorted(points, edges, side="left")
    firsts, lasts = starts[:-1], stops[1:]
    firsts, lasts = firsts[lasts > firsts], lasts[lasts > firsts]
    # the local minima of λ_min inside the bands (beyond a band's ends: +∞)
    before = np.concatenate([[np.inf], low_all[:-1]])
    after = np.concatenate([low_all[1:], [np.inf]])
    before[firsts], after[lasts - 1] = np.inf, np.inf
    minimum = (low_all < -VIOLATION) & (low_all <= before) & (low_all <= after)
    for first, last in zip(firsts.tolist(), lasts.tolist(), strict=True):
        low = low_all[first:last]
        worst = int(np.argmin(low))
        if low[worst] >= -VIOLATION:  # S K S: the diagonal peaks are 1
            continue
        minima = np.flatnonzero(minimum[first:last])
        spread = np.arange(5) * (last - first - 1) // 4  # 5 across, as linspace truncated
        chosen.append(
            first
            + np.unique(np.concatenate([[worst], minima[np.argsort(low[minima])][:MINIMA], spread]))
        )
    if chosen:
        at = np.concatenate(chosen)
        forms = 1j * points[at, None] * block.poles.basis(1j * points[at])
        if block.symmetric:
            forms = np.real(forms)
        lam_at, vec_at = np.linalg.eigh(scaled[at])
        local = np.abs(lam_at).max(axis=1)
        point, e = np.nonzero(lam_at < 0)
        vectors = dof_scale * vec_at[point, :, e]
        out.extend(
            (forms[k], float(lam_at[k, j]), v, float(local[k]))
            for k, j, v in zip(point, e, vectors, strict=True)
        )
    # the limits ω → 0 and ω → ∞, where Re K vanishes as ω² L₀ and L_∞/ω² (an
    # antisymmetric part, whose constraints remove its 1/ω and ω terms, adds an
    # antisymmetric real part there: no share of K + Kᴴ)
    for form in limit_forms(block.poles):
        values = np.where(sweep.anti, 0.0, block.coefficients @ form)
        matrix = _element_matrix(block, values) * np.outer(dof_scale, dof_scale)
        lam, vec = np.linalg.eigh(matrix)
        local = float(np.abs(lam).max())
        for e in np.flatnonzero(lam < -VIOLATION * local):
            out.append((form, float(lam[e]), dof_scale * vec[:, e], local))
    return out, dof_scale


def lowest_eigenvalues(matrices: NDArray) -> NDArray:
    """λ_min of each Hermitian matrix M of a stack (m, n, n), as
    :func:`numpy.linalg.eigvalsh` gives it (the same numbers), except where M is proven
    positive definite: there σ/2 > 0, a lower bound (σ = :data:`POSITIVE_SHIFT` tr M).

    The proof: the Cholesky factorisation of M − σI, run in floating point (the whole
    stack at once), reaches its end with positive pivots. Its factor R is then the exact
    one of H = M − σI + E with ‖E‖₂ ≤ n γ_{n+1} ‖H‖₂ (Higham (2002) Thm 10.3 and ‖|R|‖₂²
    ≤ n ‖R‖₂²; γ_k = k u / (1 − k u), u the unit round-off; a few times that in complex
    arithmetic), and H ≻ 0, so ‖H‖₂ ≤ tr H ≤ tr M + n ‖E‖₂: λ_min(M) ≥ σ − ‖E‖₂ ≥ σ −
    1.01 n (n + 1) u tr M, above σ/2 for n up to 1000. eigvalsh's own λ_min, within a
    small multiple of n u ‖M‖₂ of the true one, is then above zero too: a point whose
    sign is decided within rounding of zero goes to eigvalsh."""
    return GridLows(matrices).exact()  # the proof at every point, eigvalsh at the rest


def cholesky_passes(matrices: NDArray, shift: NDArray) -> NDArray:
    """Whether the Cholesky factorisation of each M − shift · I of a stack (m, n, n), run
    in floating point (the whole stack at once), reaches its end with positive pivots:
    then λ_min(M) > shift − ‖E‖₂, ‖E‖₂ ≤ 1.01 n (n + 1) u tr(M − shift · I) (a few times
    that in complex arithmetic; :func:`lowest_eigenvalues`)."""
    n = matrices.shape[-1]
    positive = np.isfinite(shift)
    # the lower triangle, column by column: a[i][j] for i ≥ j, each a vector over the stack
    a = [[matrices[:, i, j] for j in range(i + 1)] for i in range(n)]
    conjugate = np.conj if np.iscomplexobj(matrices) else (lambda x: x)
    with np.errstate(all="ignore"):
        for k in range(n):
            pivot = a[k][k].real - shift
            positive &= pivot > 0
            if k == n - 1:
                break
            root = np.sqrt(np.where(positive, pivot, 1.0))
            column = [a[i][k] / root for i in range(k + 1, n)]
            for i in range(k + 1, n):
                for j in range(k + 1, i + 1):
                    a[i][j] = a[i][j] - column[i - k - 1] * conjugate(column[j - k - 1])
    return positive


#: :class:`GridLows`: the eigenvectors of every SAMPLE_EVERY-th point not proven positive
#: definite bound λ_min above at the others (Rayleigh quotients).
SAMPLE_EVERY = 16
#: :class:`GridLows`: below this many points not proven positive definite, or for 2 × 2
#: matrices (0.2 µs each), eigvalsh at all of them costs less than the bounds.
BOUND_FROM = 256


class GridLows:
    """λ_min of a stack of Hermitian matrices (the check grid's) computed where the band
    logic of :func:`passivity_violations` needs it: :meth:`exact` gives
    :func:`lowest_eigenvalues` itself, :meth:`for_bands` values that give the grid-only
    band logic the same bands, local minima and worst points — hence the same
    constraints — without `eigvalsh` at the points inside a negative band proven not to
    be a local minimum.

    The proofs, u the unit round-off and τ = 2⁻⁴⁰ n² (‖M‖_F + |t|) (far above the
    rounding of each step: a small multiple of n² u): the Rayleigh quotient xᴴMx/xᴴx of
    any x is ≥ λ_min(M), and eigvalsh's λ̂ is within a small multiple of n u ‖M‖₂ of
    λ_min, so U = quotient + τ ≥ λ̂ (U < 0: the point is violated, its sign known); a
    Cholesky factorisation of M − (m + τ) I that runs to its end
    (:func:`cholesky_passes`) gives λ̂ > m + τ/2 with m = min U of its neighbours in
    its band: the point is above a neighbour, no local minimum nor a band's worst, and
    m + τ/2 stands for it (below λ̂, above the neighbour's own stand-in or value). Where
    a computed neighbour's λ̂ lies above that stand-in, the comparison is not decided:
    eigvalsh there too. (The Cholesky test's error, ≤ ~4 n² (n + 1) u (‖M‖_F + |t|), is
    below τ/2 for n up to a few hundred.)"""

    def __init__(self, matrices: NDArray):
        self.matrices = matrices
        count, n = matrices.shape[0], matrices.shape[-1]
        self.values = np.full(count, np.nan)
        self.known = np.zeros(count, dtype=bool)
        self.solved = 0  # how many eigenvalue problems eigvalsh has solved
        if n == 1:  # eigvalsh's value: the element itself
            self.values[:] = matrices[:, 0, 0].real
            self.known[:] = True
            return
        shift = POSITIVE_SHIFT * np.trace(matrices, axis1=1, axis2=2).real
        positive = cholesky_passes(matrices, shift) & (shift > 0)  # False for NaN
        self.values[positive] = 0.5 * shift[positive]
        self.known[positive] = True
        self.scale = 2.0**-40 * n * n

    def _compute(self, where: NDArray) -> None:
        """eigvalsh's λ_min at the indices ``where`` not known yet."""
        where = where[~self.known[where]]
        if where.size:
            self.values[where] = np.linalg.eigvalsh(self.matrices[where])[:, 0]
            self.solved += where.size
            self.known[where] = True

    def exact(self) -> NDArray:
        """:func:`lowest_eigenvalues` of the stack (the same numbers)."""
        self._compute(np.flatnonzero(~self.known))
        return self.values

    def _upper_bounds(self, rest: NDArray) -> tuple[NDArray, NDArray]:
        """(U ≥ eigvalsh's λ_min, ‖M‖_F) at the indices ``rest`` (NaN elsewhere): U the
        Rayleigh quotient of the eigenvector of the nearest of every
        :data:`SAMPLE_EVERY`-th of them, + τ."""
        upper, norm = np.full(self.values.size, np.nan), np.full(self.values.size, np.nan)
        sub = self.matrices[rest]
        flat = sub.reshape(rest.size, -1)
        flat = flat.view(float) if np.iscomplexobj(flat) else flat
        norm[rest] = np.sqrt(np.einsum("ki,ki->k", flat, flat))
        samples = np.arange(0, rest.size, SAMPLE_EVERY)
        x = np.linalg.eigh(sub[samples])[1][:, :, 0]
        nearest = (np.arange(rest.size) + SAMPLE_EVERY // 2) // SAMPLE_EVERY
        x = x[np.minimum(nearest, samples.size - 1)]
        image = (sub @ x[:, :, None])[:, :, 0]
        quotient = (x.conj() * image).sum(axis=1).real / (x.conj() * x).sum(axis=1).real
        upper[rest] = quotient + self.scale * norm[rest]
        return upper, norm

    def for_bands(self) -> NDArray:
        """Values for the grid-only band logic of :func:`passivity_violations`: λ̂ where
        known, else a stand-in (class docstring) that decides every comparison that logic
        makes as λ̂ does (bands: the runs of one sign)."""
        if self.matrices.shape[-1] < 3 or np.count_nonzero(~self.known) < BOUND_FROM:
            return self.exact()
        upper, norm = self._upper_bounds(np.flatnonzero(~self.known))
        # the sign: violated where U < 0, else eigvalsh
        self._compute(np.flatnonzero(~self.known & ~(upper < 0)))
        negative = np.where(self.known, self.values < 0, True)
        band = np.concatenate([[0], np.cumsum(negative[1:] != negative[:-1])])
        bound = np.where(self.known, self.values, upper)
        left = np.concatenate([[np.inf], np.where(band[1:] == band[:-1], bound[:-1], np.inf)])
        right = np.concatenate([np.where(band[1:] == band[:-1], bound[1:], np.inf), [np.inf]])
        rest = np.flatnonzero(~self.known)
        m = np.minimum(left[rest], right[rest])
        tau = self.scale * (norm[rest] + np.abs(m))
        shift = m + tau
        above = cholesky_passes(self.matrices[rest], shift) & np.isfinite(shift)
        out = self.values.copy()
        out[rest[above]] = m[above] + 0.5 * tau[above]
        self._compute(rest[~above])
        out[rest[~above]] = self.values[rest[~above]]
        # a computed point's comparison with a stand-in neighbour: decided only when the
        # stand-in is not below it
        stand = ~self.known
        same = band[1:] == band[:-1]
        undecided = same & (
            (self.known[:-1] & stand[1:] & (out[1:] < out[:-1]))
            | (stand[:-1] & self.known[1:] & (out[:-1] < out[1:]))
        )
        pairs = np.flatnonzero(undecided)
        fix = np.unique(np.concatenate([pairs[stand[pairs]], pairs[stand[pairs + 1]] + 1]))
        self._compute(fix)
        out[fix] = self.values[fix]
        return out


def limit_forms(poles: Poles) -> tuple[NDArray, NDArray]:
    """The linear forms g (one per coefficient) of the limits of Re K: L_∞ = lim ω² Re K
    (= −C A B = −Σ R_k p_k²) and L₀ = lim Re K / ω² (= C A⁻³ B = Σ R_k / p_k²), each
    element of L being g · x_e; kept (read-only) with the poles, which every sweep of an
    enforcement shares."""
    kept = poles.__dict__.get("_limit_forms")
    if kept is None:
        kept = poles.__dict__["_limit_forms"] = _limit_forms(poles)
    return kept


def _limit_forms(poles: Poles) -> tuple[NDArray, NDArray]:
    """:func:`limit_forms`, computed."""
    high, low = np.zeros(poles.count), np.zeros(poles.count)
    nr = poles.real.size
    high[:nr], low[:nr] = -(poles.real**2), 1.0 / poles.real**2
    squared, inverse = poles.pairs**2, 1.0 / poles.pairs**2
    high[nr::2], high[nr + 1 :: 2] = -2 * squared.real, 2 * squared.imag
    low[nr::2], low[nr + 1 :: 2] = 2 * inverse.real, -2 * inverse.imag
    high.flags.writeable = low.flags.writeable = False
    return high, low


def enforce_passivity(
    block: PoleResidueBlock, data: BlockData, *, give_up=None, bounds=None
) -> tuple[PoleResidueBlock, bool, int]:
    """The block with the smallest weighted residue change that makes K(jω) + K(jω)ᴴ ⪰ 0
    at all frequencies (module docstring, step 3): (block, passive, iterations).
    ``give_up``: called with the iterate every :data:`GIVE_UP_EVERY` iterations; when it
    returns True the enforcement stops there (not passive): the caller knows it would
    not keep the result. ``bounds``: a callable (block → more violated linear
    constraints, in the form of :func:`passivity_violations`' (g, λ, w, scale)) that the
    same programme meets: the damping beyond the data held under the data's tail
    (:class:`cummins.radiation.fit.tail.TailBounds`), so that the passivity
    step does not raise it there."""
    steps = enforcement_steps(block, data, bounds=bounds)
    try:
        while True:
            current, iterations = next(steps)
            if give_up is not None and give_up(current):
                return current, False, iterations
    except StopIteration as end:
        return end.value


def enforcement_steps(
    block: PoleResidueBlock, data: BlockData, *, bounds=None
) -> Generator[tuple[PoleResidueBlock, int], None, tuple[PoleResidueBlock, bool, int]]:
    """:func:`enforce_passivity` one stretch at a time: a generator that yields (iterate,
    iterations) every :data:`GIVE_UP_EVERY` iterations and returns (block, passive,
    iterations), so that a caller can run several enforcements side by side and stop
    each where it would not keep it (the same iterates as one run to the end)."""
    from cummins.radiation.passivity.enforcement import factored_misfit, least_distance

    w = data.omega[: data.n_data]
    s = 1j * data.omega
    basis_s = block.poles.kept_basis(s)
    nulls = element_null_spaces(block.elements, block.poles)
    sizes = [null.shape[1] for null in nulls]
    offsets = np.r_[0, np.cumsum(sizes)]
    misfit = []
    for e, (wr, wi, null) in enumerate(zip(data.weight_real, data.weight_imag, nulls, strict=True)):
        if not null.shape[1]:
            continue  # an antisymmetric part with no free coefficient
        phi = basis_s @ null
        jac = _stacked(phi, wr, wi)
        zero = data.kernel_zero_equations[e]
        if zero is not None:  # K(0), as the residues were fitted
            jac = np.vstack([jac, zero[0] * kernel_zero_form(block.poles) @ null])
        ridge = RIDGE * np.linalg.norm(jac, 2)
        # ‖J z‖ = ‖R z‖: the small triangular factor stands for the whole misfit
        r = np.linalg.qr(np.vstack([jac, ridge * np.eye(null.shape[1])]), mode="r")
        misfit.append((r, np.zeros(null.shape[1])))
    misfit = factored_misfit(misfit)  # once: every programme below shares it
    constraint_rows = ConstraintRows(block, nulls, offsets)
    lo, hi = float(w.min()), float(w.max())
    sweep = BlockSweep(block, lo, hi)
    rows, rhs = [], []
    transformed = np.zeros((0, offsets[-1]))
    bound = np.zeros(0, dtype=bool)
    active = np.zeros(0, dtype=bool)
    start = block.coefficients
    delta = np.zeros(offsets[-1])
    current = block
    # the grid while it sees violations, then the exact crossings to the end (the narrow
    # bands they find come back for a few iterations): half the sweeps' cost on two
    # bodies, and the grid alone took twice the iterations on the ITI barge
    exact = False
    for iteration in range(PASSIVITY_ITERATIONS):
        found, _ = passivity_violations(current, lo, hi, exact=exact, sweep=sweep)
        if not found and not exact:
            exact = True
            found, _ = passivity_violations(current, lo, hi, exact=exact, sweep=sweep)
        found = found + ([] if bounds is None else bounds(current))
        if not found:
            return current, True, iteration
        new = constraint_rows(found)
        # the programme is solved on the rows that bound in the last one and the new ones,
        # then on any of the others that the solution violates
        guess = np.concatenate([active, np.ones(len(new), dtype=bool)])
        for row, (_, lam, _, local) in zip(new, found, strict=True):
            rows.append(row)
            rhs.append(MARGIN * local - lam + row @ delta)
        # G R⁻¹ of the new rows only, the others kept
        transformed = np.concatenate([transformed, misfit.transformed_rows(new)])
        try:
            # the rows themselves are read only while there is one (their G R⁻¹ is kept)
            g = np.array(rows) if len(rows) == 1 else None
            delta, active = least_distance(misfit, g, np.array(rhs), transformed, start=guess)
        except FitError:
            return current, False, iteration
        # once the programme is large, a constraint that has never bound is left out of
        # the next ones (were it violated again, the next sweep finds it); one that has
        # bound is kept, or the iteration goes round in circles
        bound = np.concatenate([bound, np.zeros(len(rows) - bound.size, dtype=bool)]) | active
        if len(rows) > PRUNE_ROWS * delta.size:
            rows = [r for r, a in zip(rows, bound, strict=True) if a]
            rhs = [h for h, a in zip(rhs, bound, strict=True) if a]
            transformed = transformed[bound]
            active = active[bound]
            bound = bound[bound]
        if block.symmetric:  # one null space: one product
            change = (nulls[0] @ delta.reshape(len(nulls), sizes[0]).T).T
        else:
            change = np.array(
                [null @ delta[offsets[e] : offsets[e + 1]] for e, null in enumerate(nulls)]
            )
        current = PoleResidueBlock(
            block.dofs, block.elements, block.poles, start + change, block.added_mass_inf
        )
        if iteration % GIVE_UP_EVERY == GIVE_UP_EVERY - 1:
            yield current, iteration + 1
    found, _ = passivity_violations(current, lo, hi, sweep=sweep)
    return current, not found, PASSIVITY_ITERATIONS


class ConstraintRows:
    """The linearised constraints of violations (:func:`passivity_violations`' (g, λ, w,
    scale)): d(wᴴ H w)/dz for the free coefficients z of every element (x_e = N_e z_e),
    H = Re K_s + j Im K_a, w the (scaled) eigenvector. A symmetric element (i, j) enters
    H at (i, j) and (j, i) through Re g, an antisymmetric one (p, q) as ±j Im g: wᴴ H w
    gains 2 Re(w̄_i w_j) Re(g)·x (|w_i|² on the diagonal) and −2 Im(w̄_p w_q) Im(g)·x.

    Made once per enforcement (the elements and null spaces do not change); each call
    gives the rows of all the violations of an iteration at once. The weights are
    computed with the operations of one scalar at a time (|w_i|² as a power, w̄_i w_j
    without fused multiply-adds), so that each row is the same to the last bit whether
    the violations come together or one by one: the programme, and the order search
    after it, branch on them."""

    def __init__(self, block: PoleResidueBlock, nulls, offsets):
        where = {d: k for k, d in enumerate(block.dofs)}
        self.size = int(offsets[-1])
        free = [e for e in range(len(block.elements)) if offsets[e + 1] > offsets[e]]
        pairs = [block.elements[e] for e in free]
        self.first = np.array([where[i] for i, _ in pairs], dtype=int)
        self.second = np.array([where[j] for _, j in pairs], dtype=int)
        self.diagonal = np.array([i == j for i, j in pairs], dtype=bool)
        self.anti = np.array([i > j for i, j in pairs], dtype=bool)
        self.sizes = np.array([offsets[e + 1] - offsets[e] for e in free], dtype=int)
        keys: dict = {}  # g·N per null space and part (real, imaginary)
        for e in free:
            keys.setdefault((id(nulls[e]), is_antisymmetric(block.elements[e])), nulls[e])
        self.keys = [(anti, null) for (_, anti), null in keys.items()]
        index = {key: k for k, key in enumerate(keys)}
        key_of = [index[(id(nulls[e]), is_antisymmetric(block.elements[e]))] for e in free]
        self.key_of = np.array(key_of, dtype=int)

    def weights(self, vectors: NDArray) -> NDArray:
        """(m, elements) the factor of each element's g·N in the row of each w (m, n)."""
        i, j = self.first, self.second
        if not np.iscomplexobj(vectors):  # w_i w_i, 2 w_i w_j, and −2 Im(w_p w_q) = −0
            out = 2 * vectors[:, i] * vectors[:, j]
            out[:, self.diagonal] = vectors[:, i[self.diagonal]] * vectors[:, i[self.diagonal]]
            out[:, self.anti] = -0.0
            return out
        # w̄_i w_j as numpy's complex scalar product: (a − jb)(c + jd) = (ac − (−b)d) + …
        real, imag = vectors.real, -vectors.imag
        ac, bd = real[:, i] * vectors.real[:, j], imag[:, i] * vectors.imag[:, j]
        ad, bc = real[:, i] * vectors.imag[:, j], imag[:, i] * vectors.real[:, j]
        out = 2.0 * (ac - bd)
        out[:, self.anti] = -2.0 * (ad + bc)[:, self.anti]
        diagonal = np.abs(vectors[:, i[self.diagonal]])
        out[:, self.diagonal] = np.float_power(diagonal, 2.0)  # |w_i| ** 2, as pow
        return out

    def __call__(self, found) -> NDArray:
        """(m, unknowns) the rows of the violations ``found``."""
        if not found:
            return np.zeros((0, self.size))
        weights = np.empty((len(found), self.sizes.size))
        complex_vector = np.array([np.iscomplexobj(v) for _, _, v, _ in found], dtype=bool)
        for kind in (False, True):
            chosen = np.flatnonzero(complex_vector == kind)
            if chosen.size:
                weights[chosen] = self.weights(np.array([found[k][2] for k in chosen]))
        # g·N one form at a time (a matrix product of all of them rounds differently): a
        # stack of one-row products, each the vector–matrix product of one form
        forms = np.array([g for g, _, _, _ in found])
        projected = [
            ((forms.imag if anti else forms.real)[:, None, :] @ null)[:, 0, :]
            for anti, null in self.keys
        ]
        factors = np.concatenate([projected[k] for k in self.key_of], axis=1)
        return np.repeat(weights, self.sizes, axis=1) * factors
