"""The truncations of one common-pole block: MIMO balanced truncation with K(0) = 0 and
passivity restored in the truncated states.

A :class:`~cummins.radiation.model.MemoryBlock` (the default identification) holds the
fluid memory of a group of DOFs in shared states. It is balanced as one MIMO model
(Unneland (2007) Ch. 5; unweighted and with the low-frequency weights ω₀ of
:data:`~cummins.radiation.reduce.candidates.WEIGHT_CANDIDATES`, as a coupling is) and
truncated to r states. A truncation of a symmetric K is symmetric (Lyapunov, Riccati) or
nearly so (the mixed methods, Unneland (2007) §6.3.3); it has lost the zero K(0) = 0 and
in general the positive realness. Both are restored *in the r states*: the truncation is
written in modal form with symmetric residues of the rank of their poles
(:mod:`~cummins.radiation.reduce.modal`), and its vectors u_k are moved so that

* K(0) = −Σ_k σ_k u_k u_kᵀ/p_k (+ conjugates) = 0 exactly (Unneland (2007) eq. 3.48),
  by Gauss–Newton steps of minimum norm, each term weighted by its H₂ size
  |u_k|/√|Re p_k| (the constraint is quadratic in u);
* Re K(jω) ⪰ 0 at all frequencies and in the limits ω → 0, ∞ (Unneland (2007)
  Prop. 3.4): the negative eigenvalues found on a sweep and between the exact crossings of
  the Hamiltonian pencil (:func:`cummins.radiation.passivity.imaginary_axis_zeros`) are
  linearised in u, and each step is the smallest change of the response on the fitted
  range (linearised at the truncation, every coupling weighted by its spread so that
  small couplings keep their R²; plus the H₂ sizes, for what the range leaves free) that
  meets them, with K(0) = 0 as equality constraints: a least-distance programme (Lawson &
  Hanson (1974); :func:`cummins.radiation.passivity.least_distance`), repeated until no
  violation is left — Gustavsen & Semlyen (2001)'s residue perturbation applied to the
  rank-limited residues.

The poles do not move, so the truncation stays stable; the order does not grow.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from cummins.errors import FitError
from cummins.radiation.model import MemoryBlock
from cummins.radiation.reduce.balancing import _balance, _Balanced, _gramian_pair
from cummins.radiation.reduce.candidates import candidate_weights
from cummins.radiation.reduce.gramians import _regularised
from cummins.radiation.reduce.modal import ModalBlock, at_infinity, at_zero, modal_form
from cummins.radiation.reduce.system import PR_METHODS, _gain, _sweep, frequency_response

#: Passivity in the truncated states: a violation is λ_min(S Re K S) below −VIOLATION
#: times the largest eigenvalue (S: the DOF scaling 1/√max|K_ii|); each linearised
#: constraint asks for MARGIN × the largest |λ| at its point, so that the next sweep does
#: not find it again (as the common-pole fit, :mod:`cummins.radiation.fit.vector`).
VIOLATION = 1e-8
MARGIN = 1e-3
#: The same for the limits ω → 0, ∞ (below the exact test's tolerance 1e-6).
LIMIT_VIOLATION = 1e-7
LIMIT_MARGIN = 1e-6
#: At most this many correction steps (each a least-distance programme).
STRUCTURE_ITERATIONS = 15
#: A correction that would change the vectors by more than this (relative, H₂
#: sizes) ends the attempt: the linearisation no longer holds and the truncation would be
#: ruined (a truncation whose ω⁻² tail has the wrong sign, say; more states will do).
LARGEST_CHANGE = 0.25
#: K(0) counts as zero below this, relative to max|K|.
DC_TOLERANCE = 1e-12
#: A coupling of a block is compared with the unreduced one by max(1 − R²) over A and B,
#: with its spread floored at this fraction of √(spread_ii spread_jj) (a coupling a
#: hundred times smaller than its diagonals is not held to its own shape).
COUPLING_FLOOR = 1e-2
#: A truncation whose passivity correction takes its fit error max(1 − R²) above
#: PASSIVITY_COST × its error before + PASSIVITY_FLOOR is not used (the sphere's surge–pitch
#: block at 4 of 8 states: 0.3 → 900); the order search goes on to more states.
PASSIVITY_COST = 2.0
PASSIVITY_FLOOR = 1e-3
#: :meth:`BlockUnit.first_passive` tries every order of a block of up to LINEAR_UP_TO
#: states, and LINEAR_ORDERS one by one in a larger one before it doubles its steps.
LINEAR_UP_TO = 40
LINEAR_ORDERS = 6
#: Points per decade of the sweep on which passivity is checked and corrected.
SWEEP_POINTS = 60


@dataclass(frozen=True)
class BlockCandidate:
    """One truncation of a block, K(0) = 0 restored (and passive when ``passive``)."""

    order: int
    weight: float | None  # ω₀, rad/s
    modal: ModalBlock
    error: float  # max over its couplings of max(1 − R²_A, 1 − R²_B) against the block
    change: float  # max_ω σ_max(K − K_r) on the sweep, relative to the block's ‖K‖∞
    passive: bool = False
    dc_change: float = 0.0  # relative change of the vectors u for K(0) = 0
    passivity_change: float = 0.0  # relative change of the vectors u for passivity
    iterations: int = 0


@dataclass
class BlockUnit:
    """A block to reduce and what its truncations are measured against."""

    block: MemoryBlock
    index: int
    method: str
    grid: NDArray  # measurement frequencies
    regularization: float
    response: NDArray = field(default_factory=lambda: np.zeros(0, dtype=complex))
    sweep: NDArray = field(default_factory=lambda: np.zeros(0))
    sweep_response: NDArray = field(default_factory=lambda: np.zeros(0, dtype=complex))
    peak: float = 0.0
    peak_omega: float = 0.0
    scale: NDArray = field(default_factory=lambda: np.zeros(0))
    scaled: tuple = ()
    reference: _Reference | None = None
    notes: list[str] = field(default_factory=list)
    cache: dict = field(default_factory=dict)
    raw: dict = field(default_factory=dict)

    @property
    def minimum(self) -> int:
        return min(2, self.block.order)

    @property
    def model(self) -> MemoryBlock:  # the allocation reads ``model.order``
        return self.block

    @property
    def entries(self) -> list[int]:
        return [self.index]

    def weights(self) -> list[float | None]:
        return candidate_weights(self.method, self.peak_omega)

    def balanced(self, weight: float | None) -> _Balanced | None:
        if weight not in self.cache:
            a, b, c = self.scaled
            d = np.zeros((c.shape[0], b.shape[1]))
            try:
                reg = (
                    _regularised(a, b, c, d, self.regularization)
                    if self.method in PR_METHODS
                    else None
                )
                self.cache[weight] = _balance(
                    a, b, c, d, *_gramian_pair(self.method, a, b, c, reg, weight)
                )
            except (FitError, np.linalg.LinAlgError, ValueError):
                self.cache[weight] = None
        return self.cache[weight]

    def truncation(self, r: int, weight: float | None) -> BlockCandidate | None:
        """The truncation to r states for ω₀ = ``weight`` with K(0) = 0 restored (not yet
        passive); None when it is not stable or past the numerical rank."""
        key = (r, weight)
        if key not in self.raw:
            self.raw[key] = self._truncation(r, weight)
        return self.raw[key]

    def _truncation(self, r: int, weight: float | None) -> BlockCandidate | None:
        balanced = self.balanced(weight)
        if balanced is None or r > balanced.rank:
            return None
        a, b, c = balanced.truncated(r)
        if not np.all(np.isfinite(a)) or np.any(np.linalg.eigvals(a).real >= 0):
            return None
        modal = modal_form(a, b, c)
        if modal.order != r or not np.all(np.isfinite(modal.vectors)):
            return None
        fixed, dc_change = zero_dc(modal, self.peak)
        if fixed is None:
            return None
        return self._measured(r, weight, fixed, dc_change=dc_change)

    def _measured(self, r, weight, modal: ModalBlock, **extra) -> BlockCandidate:
        error = block_fit_error(self.grid, self.response, modal.response(self.grid))
        change = float(_gain(modal.response(self.sweep) - self.sweep_response).max())
        return BlockCandidate(r, weight, modal, error, change / self.peak, **extra)

    def best(self, r: int) -> BlockCandidate | None:
        """The truncation to r states with the smallest fit error (before passivity)."""
        found = [x for w in self.weights() if (x := self.truncation(r, w)) is not None]
        return min(found, key=lambda x: x.error) if found else None

    def passive(self, x: BlockCandidate) -> BlockCandidate:
        """The candidate made passive in its own states (module docstring)."""
        modal, passive, change, iterations = make_passive(
            x.modal, self.reference, float(self.grid.min()), float(self.grid.max()), self.peak
        )
        return self._measured(
            x.order,
            x.weight,
            modal,
            passive=passive,
            dc_change=x.dc_change,
            passivity_change=change,
            iterations=iterations,
        )

    def passive_at(self, r: int, tol: float | None = None) -> BlockCandidate | None:
        """The passive truncation to r states (within ``tol`` of the block's ‖K‖∞ when
        given): the candidates in the order of their fit error, the first that the
        correction makes passive without ruining it; None when none is."""
        found = [x for w in self.weights() if (x := self.truncation(r, w)) is not None]
        for x in sorted(found, key=lambda x: x.error):
            if tol is not None and x.change > tol:
                continue  # (the correction seldom lowers the change)
            if _wrong_tail(x.modal):
                continue
            y = self.passive(x)
            if not y.passive or (tol is not None and y.change > tol * (1 + 1e-9)):
                continue
            if y.error > PASSIVITY_COST * x.error + PASSIVITY_FLOOR:
                continue  # a correction that ruins the truncation: the next order will do
            return y
        return None

    def first_passive(self, start: int, tol: float | None = None) -> BlockCandidate | None:
        """The passive truncation (:meth:`passive_at`) at the smallest order from ``start``
        on: every order of a block of up to :data:`LINEAR_UP_TO` states; in a larger one
        :data:`LINEAR_ORDERS` orders one by one, then doubling steps and bisection, so that
        a block whose truncations are passive only near its full order costs a few
        attempts, not one per order (the orders with a passive truncation need not be
        contiguous, so a smaller one may be missed there). With ``tol``, the search
        starts at the first order whose truncation is within it."""
        n = self.block.order
        if tol is not None:
            start = next(
                (
                    r
                    for r in range(start, n)
                    if any((x := self.truncation(r, w)) is not None and x.change <= tol
                           for w in self.weights())
                ),
                n,
            )  # fmt: skip
        tried: dict[int, BlockCandidate | None] = {}

        def at(r: int) -> BlockCandidate | None:
            if r not in tried:
                tried[r] = self.passive_at(r, tol)
            return tried[r]

        low, r, step = start - 1, start, 1
        while r < n and at(r) is None:
            if n > LINEAR_UP_TO and r - start >= LINEAR_ORDERS - 1:
                step *= 2
            low, r = r, r + step
        if r >= n:
            if n - 1 <= low or at(n - 1) is None:
                return None
            r = n - 1
        while r - low > 1:  # at(r) is passive, at(low) is not (or low < start)
            middle = (low + r) // 2
            if at(middle) is not None:
                r = middle
            else:
                low = middle
        return tried[r]


#: A truncation whose limit lim ω² Re K (ω → ∞) has an eigenvalue below −WRONG_TAIL × its
#: largest is not corrected: its memory decays with the wrong sign in some direction,
#: which rank-limited residues fix only by a large change. (The limit ω → 0 is often
#: indefinite after a truncation, far below the fitted range, and cheap to correct.)
WRONG_TAIL = 0.01


def _wrong_tail(modal: ModalBlock) -> bool:
    values = np.linalg.eigvalsh(modal.value(at_infinity).real)
    return bool(values[0] < -WRONG_TAIL * np.abs(values).max())


def prepared_block(
    block: MemoryBlock, index: int, method: str, regularization: float, grid: NDArray
) -> BlockUnit:
    """A block with its reference responses, ‖K‖∞ and DOF scaling. Everything is done
    on the scaled block S K S (s_i = 1/√max_ω |K_ii|): a ship's surge memory is 10⁵
    times smaller than its pitch memory and would otherwise be truncated first."""
    if not block.is_stable():
        worst = block.poles()[np.argmax(block.poles().real)]
        raise FitError(
            f"the block of DOFs {block.dofs} (0-based) is not stable: a pole at {worst:.3g}",
            hint="balanced truncation needs a stable model; fit it again (cummins fit), "
            "which returns stable blocks",
        )
    unit = BlockUnit(block, index, method, np.asarray(grid, dtype=float), regularization)
    a, b, c = (np.asarray(x, dtype=float) for x in (block.a, block.b, block.c))
    sweep = _sweep(np.linalg.eigvals(a), SWEEP_POINTS)
    diagonal = np.abs(np.diagonal(frequency_response(a, b, c, None, sweep), axis1=1, axis2=2))
    peaks = diagonal.max(axis=0)
    if np.any(peaks <= 0):
        raise FitError(f"block {block.dofs} has a DOF without memory of its own")
    unit.scale = 1.0 / np.sqrt(peaks)
    unit.scaled = (a, b * unit.scale[None, :], unit.scale[:, None] * c)
    unit.response = frequency_response(*unit.scaled, None, unit.grid)
    unit.sweep = sweep
    unit.sweep_response = frequency_response(*unit.scaled, None, sweep)
    gains = _gain(unit.sweep_response)
    top = int(np.argmax(gains))
    unit.peak, unit.peak_omega = float(gains[top]), float(sweep[top])
    unit.reference = _reference(unit.grid, *unit.scaled)
    return unit


#: The passivity correction measures its change on at most this many frequencies.
FIT_POINTS = 40


@dataclass(frozen=True)
class _Reference:
    """How the passivity correction measures a change of the block: K_ij(jω), i ≤ j, at
    ``omega``, each pair's Re K (B) and Im K/ω (A − A∞) weighted by 1/their spread over ω
    in the unreduced (scaled) block (floored at :data:`COUPLING_FLOOR` of the
    diagonals'), so that every coupling's R² counts, not only the largest."""

    omega: NDArray
    weight_real: NDArray  # (pairs,)
    weight_imag: NDArray  # (n_omega, pairs): includes the 1/ω

    def jacobian(self, modal: ModalBlock) -> NDArray:
        """The weighted rows of d K_ij(jω)/du (real parts, then imaginary)."""
        jac = modal.response_jacobian(self.omega)
        g, p, n = jac.shape
        real = (jac.real * self.weight_real[None, :, None]).reshape(g * p, n)
        imag = (jac.imag * self.weight_imag[:, :, None]).reshape(g * p, n)
        return np.vstack([real, imag])


def _reference(grid: NDArray, a: NDArray, b: NDArray, c: NDArray) -> _Reference:
    """The :class:`_Reference` of a block on (at most :data:`FIT_POINTS` of) ``grid``."""
    grid = np.asarray(grid, dtype=float)
    if grid.size > FIT_POINTS:
        grid = grid[np.unique(np.linspace(0, grid.size - 1, FIT_POINTS).round().astype(int))]
    k = frequency_response(a, b, c, None, grid)
    upper = np.triu_indices(k.shape[1])
    spreads = []
    for part in (k.real, k.imag / grid[:, None, None]):
        spread = part.std(axis=0)
        diagonal = np.diagonal(spread)
        floor = COUPLING_FLOOR * np.sqrt(np.outer(diagonal, diagonal))
        spread = np.maximum(spread, np.maximum(floor, np.finfo(float).tiny))
        spreads.append(spread[upper] * np.sqrt(grid.size))
    return _Reference(
        grid,
        1.0 / spreads[0],
        1.0 / (grid[:, None] * spreads[1][None, :]),
    )


def block_fit_error(omega: NDArray, reference: NDArray, reduced: NDArray) -> float:
    """max over the couplings i ≤ j of max(1 − R² of B, 1 − R² of A − A∞) of a reduced
    block against the unreduced one (B = Re K, A − A∞ = Im K/ω: Unneland (2007)
    eq. 2.55; R² eq. 6.19), each coupling's spread floored at :data:`COUPLING_FLOOR` of
    its diagonals'."""
    w = np.asarray(omega, dtype=float)
    parts = []
    inverse = 1.0 / w[:, None, None]
    for ref, red in (
        (reference.real, reduced.real),
        (reference.imag * inverse, reduced.imag * inverse),
    ):
        spread = np.sum((ref - ref.mean(axis=0)) ** 2, axis=0)
        diag = np.diagonal(spread)
        floor = COUPLING_FLOOR**2 * np.sqrt(np.outer(diag, diag))
        spread = np.maximum(spread, floor)
        residual = np.sum((ref - red) ** 2, axis=0)
        with np.errstate(divide="ignore", invalid="ignore"):
            parts.append(np.where(spread > 0, residual / spread, np.where(residual > 0, np.inf, 0)))
    return float(np.max(np.maximum(*parts)))


# ----------------------------------------------------------------------------- structure


def _weights(modal: ModalBlock) -> NDArray:
    """Scale of each parameter: the H₂ size of its term, |u_k|/√|Re p_k| (floored)."""
    out = []
    for p, u, pair in zip(modal.poles, modal.vectors, modal.is_pair, strict=True):
        out += [np.linalg.norm(u) / np.sqrt(abs(p.real))] * (2 * u.size if pair else u.size)
    w = np.asarray(out, dtype=float)
    return np.maximum(w, 1e-9 * max(float(w.max(initial=0.0)), np.finfo(float).tiny))


def _dc_rows(modal: ModalBlock) -> tuple[NDArray, NDArray]:
    """K(0) (its upper triangle) and its derivative, (n_eq,), (n_eq, n_par)."""
    upper = np.triu_indices(modal.size)
    value = modal.dc()[upper]
    jac = modal.derivative(lambda p: -1.0 / p).real[:, upper[0], upper[1]].T
    return value, jac


def zero_dc(modal: ModalBlock, peak: float, steps: int = 12) -> tuple[ModalBlock | None, float]:
    """The modal block with K(0) = 0 by the smallest weighted change of its vectors
    (Gauss–Newton, minimum norm), and the relative size of that change; None when it
    does not converge."""
    x0 = modal.parameters()
    w = _weights(modal)
    current = modal
    for _ in range(steps):
        value, jac = _dc_rows(current)
        if np.abs(value).max(initial=0.0) <= DC_TOLERANCE * peak:
            change = np.linalg.norm((current.parameters() - x0) * w)
            return current, float(change / max(np.linalg.norm(x0 * w), np.finfo(float).tiny))
        y, *_ = np.linalg.lstsq(jac / w[None, :], -value, rcond=None)
        current = current.with_parameters(current.parameters() + y / w)
    return None, math.inf


@dataclass(frozen=True)
class _Point:
    """A point where Re K was found negative: ω, or ``LOW``/``HIGH`` for the limits ω → 0,
    ∞; the eigenvector w there (wᵀ Re K w = λ) and the largest |λ| there."""

    where: float
    vector: NDArray
    local: float


#: The limits of Re K: lim Re K/ω² (ω → 0) = Σ R_k/p_k³ and lim ω² Re K (ω → ∞) = −Σ R_k p_k.
LOW, HIGH = -1.0, -2.0


def _pole_values(where: NDArray, poles: NDArray) -> NDArray[np.complex128]:
    """f(p) of each point (P,) at each pole (terms,): 1/(jω − p), 1/p³ (LOW), −p (HIGH)."""
    where = np.asarray(where, dtype=float)[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        at = 1.0 / (1j * np.where(where > 0, where, 1.0) - poles[None, :])
    return np.where(where == LOW, at_zero(poles), np.where(where == HIGH, at_infinity(poles), at))


def _rows(modal: ModalBlock, points: list[_Point]) -> tuple[NDArray, NDArray]:
    """wᵀ Re K w at every point (current λ) and its derivative by the parameters."""
    where = np.array([p.where for p in points])
    w = np.array([p.vector for p in points])
    fp = _pole_values(where, modal.poles)
    fq = _pole_values(where, np.conj(modal.poles))
    values, rows = modal.form_gradients(w, fp, fq)
    return rows, values


def _violations(modal: ModalBlock, lo: float, hi: float) -> list[_Point]:
    """Where S Re K S has an eigenvalue below −VIOLATION × its largest (the worst point of
    each band between crossings, its local minima and a few across it), and the limits."""
    from cummins.radiation.passivity import band_points

    grid = _sweep(np.r_[modal.poles, lo + 0j, hi + 0j], SWEEP_POINTS)
    edges, extra = band_points(*modal.realization(), grid)
    points = np.unique(np.r_[grid, extra])
    points = points[points > 0]
    lam, vec = np.linalg.eigh(modal.response(points).real)
    top = max(float(np.abs(lam).max()), np.finfo(float).tiny)
    out = []
    for x, y in itertools.pairwise(edges):
        inside = np.flatnonzero((points > x) & (points < y))
        if not inside.size:
            continue
        low = lam[inside, 0]
        if low.min() >= -VIOLATION * top:
            continue
        minima = np.flatnonzero(
            (low < -VIOLATION * top)
            & (low <= np.r_[np.inf, low[:-1]])
            & (low <= np.r_[low[1:], np.inf])
        )
        spread = np.linspace(0, inside.size - 1, 5).astype(int)
        chosen = np.r_[int(np.argmin(low)), minima[np.argsort(low[minima])][:8], spread]
        for q in np.unique(chosen):
            k = inside[q]
            local = float(np.abs(lam[k]).max())
            for e in np.flatnonzero(lam[k] < 0):
                out.append(_Point(float(points[k]), vec[k, :, e], local))
    for where, f in ((LOW, at_zero), (HIGH, at_infinity)):
        limit = modal.value(f).real
        values, vectors = np.linalg.eigh(limit)
        local = float(np.abs(values).max())
        for e in np.flatnonzero(values < -LIMIT_VIOLATION * local):
            # a limit matrix may be singular (a DOF combination with no ω⁻² tail): only
            # what the test would see, and no margin, which a rank-limited residue could
            # only buy by a large change
            out.append(_Point(where, vectors[:, e], local * LIMIT_MARGIN / MARGIN))
    return out


def make_passive(
    modal: ModalBlock, reference: _Reference, lo: float, hi: float, peak: float
) -> tuple[ModalBlock, bool, float, int]:
    """The modal block with K(0) = 0 and Re K(jω) ⪰ 0, its vectors fitted to the unreduced
    block (module docstring): (block, passive, relative change of the vectors,
    iterations)."""
    from cummins.radiation.passivity import least_distance

    x0 = modal.parameters()
    w = _weights(modal)
    size = max(float(np.linalg.norm(x0 * w)), np.finfo(float).tiny)
    current = modal
    points: list[_Point] = []

    def change() -> float:
        return float(np.linalg.norm((current.parameters() - x0) * w)) / size

    # the smallest change from the truncation: of the weighted response on the fitted
    # range (linearised there) and, for what it leaves free (terms out of the range), of
    # the vectors' H₂ sizes; its triangular factor stands for it (‖J δ‖ = ‖R δ‖)
    objective = np.linalg.qr(np.vstack([reference.jacobian(modal), np.diag(w) / size]), mode="r")

    for iteration in range(STRUCTURE_ITERATIONS):
        # the quadratic part of the last step moved K(0): back to zero first, or Re K(0)
        # ≠ 0 shows as a violation at ω → 0 that no step along the constraints can reach
        fixed, _ = zero_dc(current, peak)
        if fixed is None:
            break
        current = fixed
        found = _violations(current, lo, hi)
        if not found:
            return current, True, change(), iteration
        points += found
        # K(0) = 0 to first order: steps δ = N z in the null space of its derivative
        _, jac = _dc_rows(current)
        _, sv, vt = np.linalg.svd(jac / w[None, :])
        rank = int(np.sum(sv > 1e-12 * max(sv.max(initial=0.0), np.finfo(float).tiny)))
        null = vt[rank:].T / w[:, None]
        rows, lam = _rows(current, points)
        rhs = MARGIN * np.array([p.local for p in points]) - lam
        offset = objective @ (current.parameters() - x0)
        try:
            z, _ = least_distance([(objective @ null, offset)], rows @ null, rhs)
        except FitError:
            break
        moved = current.parameters() + null @ z
        if np.linalg.norm((moved - x0) * w) > LARGEST_CHANGE * size:
            break  # a truncation that only a large change makes passive: not this one
        current = current.with_parameters(moved)
    value, _ = _dc_rows(current)
    ok = not _violations(current, lo, hi) and np.abs(value).max() <= DC_TOLERANCE * peak
    return current, ok, change(), STRUCTURE_ITERATIONS
