"""A block's residues refined on the motions themselves, passive at every step.

The vector fit (:mod:`cummins.radiation.fit.vector`) fits K(jω) in a weighted least-squares
sense, the motion weights a first-order bound of each coupling's share of the motion
error (:mod:`cummins.radiation.fit.motion`). Where the data are not Kramers–Kronig
consistent (WEC-Sim's RM3 from WAMIT: the model that follows the damping exactly is 28.9 %
of the peak off the data's motions), a model within the motion target must leave the
damping where the motions allow it, and that trade is not the one a weighted fit of K
makes. Here the motion RAOs enter the fit as they are: with the poles fixed, the model
K̂(jω; z) = jω (basis(jω) · x_e + A∞_e) is linear in the coefficients z (residues in their
null space, and A∞ where the block estimates it), and the motions

    X(ω; z) = Z(ω; z)⁻¹ F(ω),    Z = −ω² M + jω (K̂ + B_v) + C

(Falnes (2002) eq. 5.8) are smooth in z, with δX = −Z⁻¹ (jω δK̂) X. Each step is the
Gauss–Newton step of

    min  ‖R_K z − Q_Kᵀ y_K‖² + Σ_{ω,m,c} ℓ |r_mc(ω) + δr_mc(ω)|² / (tol² n_ω)

(r = (X − X_data)/max_ω |X_data|, the scoreboard's relative motion error; R_K, Q_Kᵀ y_K the
block's weighted equations of K (:func:`cummins.radiation.fit.vector.residue_equations`),
kept so that what the motions do not see stays the vector fit's), subject to the
linearised passivity constraints found so far (the cutting planes of
:func:`cummins.radiation.fit.block_passivity.enforcement_steps`), solved as a
least-distance programme (Lawson & Hanson (1974) ch. 23). The weights ℓ of the motion
residuals follow Lawson's iteration for the minimax approximation (Lawson (1961); Rice &
Usow (1968)): ℓ ← ℓ |r|, so that the least-squares steps aim at the largest error, which is
what the scoreboard judges. After :data:`STEPS` steps the misfit is frozen and the
iteration goes on as a passivity enforcement with that misfit until the exact test
finds no violation: the result is passive and stable (the poles do not move).

The motions aimed at are the user's data's (the scoreboard's: :mod:`cummins.radiation.
fit.scorecard`), not those of the data's passive part the vector fit is made to, and the
couplings no block models are taken as the model has them (K = 0, A∞):
:func:`cummins.radiation.fit.blocks.unmodelled_as_model`. (Aimed at the passive part's
motions, RM3's refined block was 0.40 % off those and 0.96 % off the user's; aimed at the
user's, 0.39 %.)

By default (``refine_motions=None``) the refinement runs when the fit's motions miss their
target (:func:`refinement_wanted`), made in the refit that estimates A∞ when there is one
(:func:`cummins.radiation.fit.causal_inf.with_causal_inf`), and a number of poles whose
Gauss–Newton steps leave the block above the target is given up before its enforcement.
Its cost (RM3 at 20 common poles, 885 coefficients, 4 steps and 22 programmes): the
normal equations of the motions grouped by elements (:func:`motion_normal`), the
passivity checked on the grid and the exact test only when the grid sees nothing
(:class:`BandSweep`), a wider margin of the constraints (:data:`REFINE_MARGIN`): 2.4 →
1.5 s.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from cummins.errors import FitError
from cummins.radiation.fit.block_passivity import (
    PASSIVITY_ITERATIONS,
    BlockSweep,
    ConstraintRows,
    passivity_violations,
)
from cummins.radiation.fit.tail import (
    BOUND_TOLERANCE,
    TailBounds,
    beyond_limits,
    rise_after_top,
)
from cummins.radiation.fit.vector import (
    BlockData,
    PoleResidueBlock,
    element_null_spaces,
    residue_equations,
)
from cummins.radiation.passivity.enforcement import FactoredMisfit, least_distance_multipliers

#: Gauss–Newton steps on the motion misfit (re-linearised, Lawson weights updated) before
#: the misfit is frozen and the iteration finishes as a passivity enforcement. RM3 from
#: WAMIT at 20 common poles: 2.39 % (the vector fit) → 0.50 % after 3 steps, 0.40 % after 5
#: (the block's motion error against the data's passive part).
STEPS = 5

#: Linearised motions of a block: block → (ω, r, s) with r (ω, R) the relative motion
#: errors of the R compared (DOF, load case) motions at the compared frequencies ω and
#: s (ω, R, m, m) their derivatives with respect to K̂ of the block's DOFs
#: (:meth:`cummins.radiation.fit.motion.BlockMotionError.linearised`).
Linearised = Callable[[PoleResidueBlock], tuple[NDArray, NDArray, NDArray]]


@dataclass(frozen=True)
class Coordinates:
    """The free coordinates z of a block at fixed poles: each element's coefficients in
    its null space (:func:`~cummins.radiation.fit.vector.element_null_spaces`), followed
    by its A∞ where the block estimates it."""

    nulls: tuple[NDArray, ...]
    free_inf: NDArray[np.bool_]
    offsets: NDArray[np.int_]  # start of each element's coordinates in z

    @classmethod
    def of(cls, block: PoleResidueBlock, data: BlockData) -> Coordinates:
        nulls = tuple(element_null_spaces(block.elements, block.poles))
        free = np.asarray(data.free_inf, dtype=bool)
        sizes = [null.shape[1] + int(f) for null, f in zip(nulls, free, strict=True)]
        return cls(nulls, free, np.r_[0, np.cumsum(sizes)].astype(int))

    @property
    def size(self) -> int:
        return int(self.offsets[-1])

    def residue_columns(self) -> NDArray[np.int_]:
        """The positions in z of the residue coordinates (the passivity constraints' own
        unknowns, in their order)."""
        return np.concatenate(
            [
                np.arange(start, start + null.shape[1])
                for start, null in zip(self.offsets[:-1], self.nulls, strict=True)
            ]
        ).astype(int)

    def pack(self, block: PoleResidueBlock) -> NDArray[np.float64]:
        """z of ``block`` (its coefficients lie in the null spaces)."""
        out = np.empty(self.size)
        for e, null in enumerate(self.nulls):
            start, k = self.offsets[e], null.shape[1]
            out[start : start + k] = null.T @ block.coefficients[e]
            if self.free_inf[e]:
                out[start + k] = block.added_mass_inf[e]
        return out

    def unpack(self, z: NDArray, block: PoleResidueBlock) -> PoleResidueBlock:
        """``block`` with the coefficients and A∞ of ``z``."""
        x = np.zeros_like(block.coefficients)
        inf = np.array(block.added_mass_inf, dtype=float)
        for e, null in enumerate(self.nulls):
            start, k = self.offsets[e], null.shape[1]
            x[e] = null @ z[start : start + k]
            if self.free_inf[e]:
                inf[e] = z[start + k]
        return PoleResidueBlock(block.dofs, block.elements, block.poles, x, inf)


def fit_equations(data: BlockData, block: PoleResidueBlock, coords: Coordinates):
    """(R_K, Q_Kᵀ y_K): the block's weighted equations of K at its poles in z, each
    element's factored on its own (block-diagonal R_K), so that ‖R_K z − Q_Kᵀ y_K‖² is the
    vector fit's misfit less a constant."""
    factors, shifts = [], []
    for _, _, rows, rhs in residue_equations(data, block.poles, coords.nulls):
        q, r = np.linalg.qr(rows)
        factors.append(r)
        shifts.append(q.T @ rhs)
    return scipy.linalg.block_diag(*factors), np.concatenate(shifts)


def element_sensitivities(block: PoleResidueBlock, sensitivity: NDArray) -> NDArray:
    """d r / d K̂_e (ω, R, elements), complex: ``sensitivity`` s (ω, R, m, m) = d r / d K̂
    of the block's DOFs, an element (i, j) entering K̂ at (i, j) and (j, i) (an
    antisymmetric part (p, q), p > q, with + at (p, q) and − at (q, p))."""
    where = {d: k for k, d in enumerate(block.dofs)}
    out = np.empty((*sensitivity.shape[:2], len(block.elements)), dtype=complex)
    for e, (i, j) in enumerate(block.elements):
        a, b = where[i], where[j]
        if i == j:
            out[:, :, e] = sensitivity[:, :, a, a]
        elif i < j:
            out[:, :, e] = sensitivity[:, :, a, b] + sensitivity[:, :, b, a]
        else:
            out[:, :, e] = sensitivity[:, :, a, b] - sensitivity[:, :, b, a]
    return out


def element_maps(coords: Coordinates, count: int) -> tuple[NDArray, NDArray]:
    """(N, chosen): N (elements, count + 1, K) maps each element's coordinates (its
    null-space coefficients, then its A∞ where free; K the most of any, the rest zero)
    to the common basis [jω basis(jω), jω]; chosen: the positions of z in the padded
    (elements × K) coordinates, in z's order."""
    sizes = np.diff(coords.offsets)
    width = int(sizes.max(initial=0))
    maps = np.zeros((len(coords.nulls), count + 1, width))
    for e, null in enumerate(coords.nulls):
        k = null.shape[1]
        maps[e, :count, :k] = null
        if coords.free_inf[e]:
            maps[e, count, k] = 1.0
    chosen = np.concatenate([e * width + np.arange(size) for e, size in enumerate(sizes)])
    return maps, chosen.astype(int)


def motion_normal(
    block: PoleResidueBlock,
    coords: Coordinates,
    omega: NDArray,
    weighted: NDArray,
    residual: NDArray,
) -> tuple[NDArray, NDArray]:
    """(Re JᴴJ, Re Jᴴ y) of the weighted motion Jacobian J = d r / d z (rows (ω, R): an
    element e's columns g_e(ω, R) ⊗ φ(ω) N_e, ``weighted`` = the scaled g
    (:func:`element_sensitivities`), φ = [jω basis(jω), jω], N_e :func:`element_maps`)
    and the weighted ``residual`` y (ω, R), without J: the block (e, f) of Re JᴴJ is
    N_eᵀ T_ef N_f, T_ef = Re Σ_ω H_ef(ω) φ(ω)ᴴ φ(ω), H_ef = Σ_R ḡ_e g_f — the same sums
    as the product of the (ω·R) × z Jacobian, grouped by the elements, and each computed
    once by the symmetries T_fe = T_efᵀ, Re φ̄_a φ_b symmetric and Im φ̄_a φ_b
    antisymmetric in (a, b) (RM3 at 20 common poles: a tenth of the arithmetic)."""
    s = 1j * omega
    phi = np.concatenate([s[:, None] * block.poles.kept_basis(s), s[:, None]], axis=1)
    count, n_el = phi.shape[1], weighted.shape[2]
    outer = np.conj(phi)[:, :, None] * phi[:, None, :]  # (ω, p+1, p+1)
    h = np.conj(weighted).transpose(0, 2, 1) @ weighted  # (ω, E, E)
    e_of, f_of = np.triu_indices(n_el)
    a_of, b_of = np.triu_indices(count)
    a_off, b_off = np.triu_indices(count, 1)
    sym = h.real[:, e_of, f_of].T @ outer.real[:, a_of, b_of]
    anti = h.imag[:, e_of, f_of].T @ outer.imag[:, a_off, b_off]
    t = np.empty((e_of.size, count, count))
    t[:, a_of, b_of] = sym
    t[:, b_of, a_of] = sym
    t[:, a_off, b_off] -= anti
    t[:, b_off, a_off] += anti
    maps, chosen = element_maps(coords, count - 1)
    pairs = maps[e_of].transpose(0, 2, 1) @ t @ maps[f_of]  # (pairs, K, K)
    width = maps.shape[2]
    padded = np.empty((n_el, width, n_el, width))
    padded[f_of, :, e_of, :] = pairs.transpose(0, 2, 1)
    padded[e_of, :, f_of, :] = pairs
    normal = padded.reshape(n_el * width, -1)[np.ix_(chosen, chosen)]
    # Re Jᴴ y: Σ_ω φ̄(ω) Σ_R ḡ_e y, mapped by N_e
    projected = np.einsum("wre,wr->we", np.conj(weighted), residual)
    per_basis = (np.conj(phi).T @ projected).real  # (p+1, E)
    rhs = np.einsum("eak,ae->ek", maps, per_basis).reshape(-1)[chosen]
    return normal, rhs


class BeyondBounds:
    """The damping beyond the data held as the order search's check judges it
    (:func:`cummins.radiation.fit.tail.damping_beyond_data`), as linear constraints in
    the form of :class:`~cummins.radiation.fit.tail.TailBounds`: under the envelope of
    the data's tail (TailBounds itself) and without a peak of its own, a rise of B_ii
    beyond ω_N above its lowest value since its largest one by more than
    :data:`~cummins.radiation.fit.tail.BOUND_TOLERANCE` of the data's peak (the
    constraint B_ii(ω_peak) − B_ii(ω_low) ≤ that, at the worst rise). The motions do not
    see beyond the data, and a step that follows them can raise the damping there: RM3's
    float pitch at 20 common poles, a peak of 28 % of its data's at 8 rad/s (data to 5.2)."""

    def __init__(self, data: BlockData):
        self.data = data
        self.tail = TailBounds(data)
        self._poles = None
        self._forms = None

    def __call__(self, block: PoleResidueBlock) -> list:
        out = self.tail(block)
        grid, limits = beyond_limits(self.data)
        if block.poles is not self._poles:
            self._poles = block.poles
            self._forms = np.real(1j * grid[:, None] * block.poles.kept_basis(1j * grid))
        where = {d: k for k, d in enumerate(block.dofs)}
        for e, (i, j) in enumerate(block.elements):
            if i != j or limits[e][0] <= 0:
                continue
            rise, low_at = rise_after_top(self._forms @ block.coefficients[e])
            k = int(np.argmax(rise))
            cap = BOUND_TOLERANCE * limits[e][0]
            if rise[k] <= cap:
                continue
            unit = np.zeros(len(block.dofs))
            unit[where[i]] = 1.0
            form = self._forms[low_at[k]] - self._forms[k]
            out.append((form, float(cap - rise[k]), unit, limits[e][0]))
        return out


def refine_block(
    block: PoleResidueBlock,
    data: BlockData,
    linearised: Linearised,
    *,
    motion_tol: float,
    bounds=None,
    steps: int = STEPS,
    give_up: float | None = None,
) -> tuple[PoleResidueBlock, bool]:
    """``block`` (its poles kept) refined on the motions and made passive (module
    docstring): (block, passive). ``linearised``: the block's motions linearised
    (:data:`Linearised`); ``bounds``: further violated linear constraints of a block,
    as :func:`~cummins.radiation.fit.block_passivity.enforce_passivity` takes them (the
    damping beyond the data held under the data's tail). Not passive when the
    programme becomes infeasible or the iterations run out: the caller keeps its own.

    The Gauss–Newton steps stop early when a step brings the motion error down by less
    than :data:`STALL` of itself (Lawson's iteration has converged as far as these poles
    allow); ``give_up``: a motion error above which the block is given up (not passive)
    when the steps end, before the enforcement — the passivity the enforcement adds
    only takes the motions further from the data (each constraint restricts the least-
    squares step), so a block that misses it before does not meet it after. Each
    enforcement iteration checks on the grid (and the points of the bands the last
    exact test found), the exact test (:func:`~cummins.radiation.passivity.
    imaginary_axis_zeros`) only when the grid sees nothing (:class:`BandSweep`). Once the
    misfit is frozen each programme holds the last one's rows and more, with the same
    right-hand sides: its NNLS is continued from the last one's multipliers
    (:func:`~cummins.radiation.passivity.enforcement.warm_nnls`)."""
    first = linearised(block)
    if first is None:  # no Woodbury form of the motions (joined bodies)
        return block, False
    coords = Coordinates.of(block, data)
    fit_r, fit_shift = fit_equations(data, block, coords)
    normal_fit, rhs_fit = fit_r.T @ fit_r, fit_r.T @ fit_shift
    sizes = [null.shape[1] for null in coords.nulls]
    constraint_rows = ConstraintRows(block, coords.nulls, np.r_[0, np.cumsum(sizes)])
    residue = coords.residue_columns()
    w = data.omega[: data.n_data]
    sweep = BandSweep(block, float(w.min()), float(w.max()))
    z = coords.pack(block)
    rows, rhs = np.zeros((0, z.size)), np.zeros(0)
    bound = np.zeros(0, dtype=bool)
    last = np.zeros(0, dtype=bool)  # the rows that bound in the last programme, and new ones
    lawson, errors = None, []
    u = np.zeros(0)  # the last programme's multipliers, one per row
    misfit, transformed = None, np.zeros((0, z.size))
    current, stepping = block, True
    for iteration in range(steps + PASSIVITY_ITERATIONS):
        found = sweep.violations(current) + ([] if bounds is None else bounds(current))
        if stepping:  # re-linearised: the motion error of the iterate, and a step
            linear = first if iteration == 0 else linearised(current)
            errors.append(float(np.abs(linear[1]).max()))
            stepping = iteration < steps and not stalled(errors)
            if not stepping and give_up is not None and min(errors) > give_up:
                return current, False
        if not found and not stepping and misfit is not None:
            return current, True
        new = np.zeros((len(found), z.size))
        if found:
            new[:, residue] = constraint_rows(found)
            rows = np.vstack([rows, new])
            rhs = np.r_[rhs, [REFINE_MARGIN * local - lam for _, lam, _, local in found] + new @ z]
            bound = np.r_[bound, np.zeros(len(found), dtype=bool)]
            last = np.r_[last, np.ones(len(found), dtype=bool)]
        stepped = stepping or misfit is None
        if stepped:  # a Gauss–Newton step, every row transformed
            misfit, lawson = _gauss_newton(
                current, coords, z, linear, normal_fit, rhs_fit, lawson, motion_tol
            )
            transformed = misfit.transformed(rows) if rhs.size else transformed[:0]
        elif found:  # the misfit frozen: G R⁻¹ of the new rows only
            transformed = np.concatenate([transformed, misfit.transformed_rows(new)])
        if not rhs.size:
            z = misfit.solve(-misfit.shift)
            current = coords.unpack(z, block)
            continue
        try:
            z, u = least_distance_multipliers(
                misfit, rows, rhs, transformed, start=last, warm=None if stepped else u
            )
        except FitError:
            return current, False
        active = u > 0
        bound |= active
        last = active
        if rhs.size > z.size:  # as the enforcement prunes its programme
            rows, rhs, transformed, last, u, bound = (
                rows[bound],
                rhs[bound],
                transformed[bound],
                last[bound],
                u[bound],
                bound[bound],
            )
        current = coords.unpack(z, block)
    return current, False


#: The Gauss–Newton steps stop when the last brought the motion error down by less than
#: STALL of itself (RM3 at 20 common poles: 2.39, 1.40, 0.84, 0.43, 0.40 %: the fifth
#: step is not made).
STALL = 0.1

#: The constraints of the refinement ask for λ ≥ REFINE_MARGIN × the largest |λ| there
#: (the enforcement's :data:`~cummins.radiation.fit.block_passivity.MARGIN` is 1e-3): the
#: motion steps move the residues far, and a wider overshoot keeps the next sweep from
#: finding the same band again. RM3 at 20 common poles: 1e-3 52 programmes, 2.4 s, the
#: block 0.39 % off; 3e-3 1.7 s, 0.39 %; 1e-2 1.2 s, 0.45 %.
REFINE_MARGIN = 3e-3


def stalled(errors: list[float]) -> bool:
    """Whether the last Gauss–Newton step brought the motion error (``errors``, one per
    linearisation) down by less than :data:`STALL` of itself."""
    return len(errors) > 1 and errors[-1] > (1.0 - STALL) * errors[-2]


class BandSweep(BlockSweep):
    """The passivity check of an enforcement: :func:`passivity_violations` on the grid
    alone while it sees a violation, else the exact test; after an exact test that finds
    one, the grid takes the points of its bands, so that the next iterations see those
    bands narrower than the grid without the pencil (its QZ: 0.12 s at 200 states, the
    grid's sweep 0.01 s), and the exact test is made again only when that grid sees
    nothing."""

    def violations(self, block: PoleResidueBlock) -> list:
        lo, hi = self.range
        found, _ = passivity_violations(block, lo, hi, exact=False, sweep=self)
        if found:
            return found
        found, _ = passivity_violations(block, lo, hi, exact=True, sweep=self)
        if found and self.band_extra is not None and self.band_extra.size:
            self.extend(block, self.band_extra)
        return found


def _gauss_newton(
    block, coords, z, linear, normal_fit, rhs_fit, lawson, motion_tol
) -> tuple[FactoredMisfit, NDArray]:
    """(misfit ‖R z + shift‖², R upper triangular; Lawson weights) of a step: the fit's
    normal equations plus the motion residuals linearised at ``block`` (z; ``linear``:
    :data:`Linearised`'s answer there), weighed by Lawson's weights (updated from the
    residuals)."""
    omega, residual, sensitivity = linear
    r = residual.reshape(-1)
    lawson = np.ones(r.size) if lawson is None else lawson * np.abs(r)
    lawson = lawson / max(float(lawson.mean()), np.finfo(float).tiny)
    scale = (np.sqrt(lawson) / (motion_tol * np.sqrt(omega.size))).reshape(residual.shape)
    weighted = element_sensitivities(block, sensitivity) * scale[:, :, None]
    # the step: min ‖R_K z − Q_Kᵀ y_K‖² + ‖J z − (J z₀ − scale r)‖²
    gram, projected = motion_normal(block, coords, omega, weighted, scale * residual)
    normal = normal_fit + gram
    rhs = rhs_fit + gram @ z - projected
    factor = scipy.linalg.cholesky(normal, lower=False)
    shift = -scipy.linalg.solve_triangular(factor, rhs, trans="T")
    return FactoredMisfit(factor, shift), lawson


def refined_block(data: BlockData, kept: PoleResidueBlock, score, counts, motions, options):
    """(block, score, notes) of a block that misses its motion aim after the order
    search (``kept``: its fit, ``score`` its score), refined on the motions
    (:func:`refine_block`) at each of ``counts`` common poles in turn (the order search's
    kept number, then ``max_order``: the order search's plain fit there, else a new one),
    the first whose motions meet their aim, else the passive one with the smallest motion
    error; kept when that is below ``kept``'s and the block no further from the targets
    that are failures whatever the motions (the R² of K(t), the damping beyond the data);
    else None. The R² of A and B may fall: the motions judge them
    (:func:`~cummins.radiation.fit.mimo.fit_failures`). ``motions``: the block's motion
    error and its linearisation (callables of a block), every other coupling as the
    model has it; ``notes``: a callable (the order search's notes, the DOF labels) → the
    block's notes, the refinement said and the targets it misses named anew."""
    from cummins.radiation.fit import order_search, vector
    from cummins.radiation.fit.options import MOTION_AIM

    motion, linearised = motions
    aim = MOTION_AIM * options.motion_tol
    # the default's (refine_motions None): a number of poles the steps leave above the
    # target is given up before its enforcement
    give_up = options.motion_tol if options.refine_motions is None else None
    before = motion(kept)
    targets = {"r2": options.r2, "r2_coupling": options.coupling_target}
    best = None
    for count in dict.fromkeys(counts):
        start = data.plain_fits.get(count, (None, None))[0]
        try:
            start = vector.vector_fit(data, count) if start is None else start
            block, passive = refine_block(
                start,
                data,
                linearised,
                motion_tol=options.motion_tol,
                bounds=BeyondBounds(data),
                give_up=give_up,
            )
        except np.linalg.LinAlgError:  # a singular step: the search's block stays
            continue
        if not passive:
            continue
        found = order_search.score_block(
            block,
            data,
            **targets,
            motion=motion,
            passive=True,
            r2_kernel=options.r2_kernel,
            tail=True,
        )
        if best is None or found.motion_error < best[1].motion_error:
            best = (block, found)
        if found.motion_error <= aim:
            break
    if (
        best is None
        or best[1].motion_error >= before
        or best[1].kernel_shortfall > max(score.kernel_shortfall, 0.0)
        or best[1].tail_excess > max(score.tail_excess, 0.0)
    ):
        return None
    block, found = best

    def notes(searched: list[str], labels) -> list[str]:
        kept = [n for n in searched if not n.startswith("targets not met")]
        kept.append(
            f"residues refined on the motions at {block.poles.count} common poles, passive "
            f"(motion error {100 * before:.3g} % → {100 * found.motion_error:.3g} %"
            "): the R² of A and B traded where the motions allow it"
        )
        if not found.meets(aim):
            kept.append(
                order_search.targets_not_met(
                    block.poles.count,
                    found,
                    **targets,
                    r2_kernel=options.r2_kernel,
                    motion_aim=aim,
                    labels=labels,
                )
            )
        return kept

    return block, found, notes


#: The default's refinement is not tried on a model whose motion error is above
#: LINEAR_LIMIT of the peak motion: motions further from the data's than the data's own
#: size are not a trade of residues at fixed poles that steps linearised about the model
#: (δX = −Z⁻¹ jω δK̂ X) can make — the model's motions are not the data's at all (the
#: free OSWEC from Capytaine, its flap out of static equilibrium: 564 %; its default
#: refinement gave nothing up to 0.6 s later).
LINEAR_LIMIT = 1.0


def refinement_wanted(options, model) -> bool:
    """Whether ``model``'s motions call for the refinement: ``refine_motions`` None (the
    default) when they miss their target ``motion_tol`` (and are within
    :data:`LINEAR_LIMIT`, of a statically stable system: the RAOs of an unstable one are
    no steady state, ``attrs["statically_unstable"]``), True when they miss the aim
    (:data:`~cummins.radiation.fit.options.MOTION_AIM` × ``motion_tol``), False never."""
    from cummins.radiation.fit.options import MOTION_AIM

    error = model.attrs.get("motion_error")
    if options.refine_motions is False or error is None:
        return False
    if options.refine_motions is None:
        stable = not model.attrs.get("statically_unstable")
        return stable and options.motion_tol < error <= LINEAR_LIMIT
    return error > MOTION_AIM * options.motion_tol


def refined_on_motions(inp, options, model, fit):
    """``model`` (the blocks fitted by ``fit(inp, options)`` without the refinement, the
    A∞ of :mod:`cummins.radiation.fit.causal_inf` decided), or, when its motions call
    for it (:func:`refinement_wanted`), the blocks fitted again with it
    (:func:`refined_block`), the A∞ estimated for the same DOFs, when that brings the
    motions nearer the data's. Refined in the final fit only (with the refinement in
    both, the RM3's took 18 s instead of 8), ``fit`` reusing its order searches and the
    blocks it does not refine (``searched`` of
    :func:`~cummins.radiation.fit.blocks.fit_blocks`), and None when it refines none."""
    from dataclasses import replace

    if not refinement_wanted(options, model):
        return model
    error = model.attrs["motion_error"]
    estimated = model.attrs.get("added_mass_inf_estimated") or []
    dofs = tuple(inp.labels.index(label) for label in estimated)
    refit = fit(replace(inp, estimated_inf=dofs), options)
    if refit is None or refit.attrs.get("motion_error", np.inf) >= error:
        return model
    # the notes said after the blocks were fitted (the A∞ estimated), not the blocks' own
    names = tuple("-".join(inp.labels[d] for d in block.dofs) + ": " for block in model.blocks)
    notes = list(refit.attrs.get("data_notes", []))
    notes += [
        n for n in model.attrs.get("data_notes", []) if n not in notes and not n.startswith(names)
    ]
    return replace(refit, attrs={**refit.attrs, "data_notes": notes})
