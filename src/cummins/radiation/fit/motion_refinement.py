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
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from cummins.errors import FitError
from cummins.radiation.fit.block_passivity import (
    MARGIN,
    PASSIVITY_ITERATIONS,
    BlockSweep,
    ConstraintRows,
    passivity_violations,
)
from cummins.radiation.fit.tail import BOUND_TOLERANCE, TailBounds, beyond_limits
from cummins.radiation.fit.vector import (
    BlockData,
    PoleResidueBlock,
    element_null_spaces,
    residue_equations,
)
from cummins.radiation.passivity.enforcement import FactoredMisfit, least_distance

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


def motion_columns(
    block: PoleResidueBlock, coords: Coordinates, omega: NDArray, sensitivity: NDArray
) -> NDArray[np.complex128]:
    """d r / d z (ω·R, size of z), complex: ``sensitivity`` s (ω, R, m, m) = d r / d K̂
    of the block's DOFs, an element (i, j) entering K̂ at (i, j) and (j, i) (an
    antisymmetric part (p, q), p > q, with + at (p, q) and − at (q, p)), its
    coefficients through jω basis(jω) and its A∞ through jω."""
    where = {d: k for k, d in enumerate(block.dofs)}
    s = 1j * omega
    phi = block.poles.kept_basis(s)
    columns = np.zeros((omega.size, sensitivity.shape[1], coords.size), dtype=complex)
    for e, (i, j) in enumerate(block.elements):
        a, b = where[i], where[j]
        if i == j:
            g = sensitivity[:, :, a, a]
        elif i < j:
            g = sensitivity[:, :, a, b] + sensitivity[:, :, b, a]
        else:
            g = sensitivity[:, :, a, b] - sensitivity[:, :, b, a]
        start, null = coords.offsets[e], coords.nulls[e]
        k = null.shape[1]
        columns[:, :, start : start + k] = g[:, :, None] * (s[:, None] * (phi @ null))[:, None, :]
        if coords.free_inf[e]:
            columns[:, :, start + k] = g * s[:, None]
    return columns.reshape(-1, coords.size)


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
            b = self._forms @ block.coefficients[e]
            top = int(np.argmax(b))
            after = b[top:]
            low = np.minimum.accumulate(after)
            peak_at = int(np.argmax(after - low))
            rise = after[peak_at] - low[peak_at]
            cap = BOUND_TOLERANCE * limits[e][0]
            if rise <= cap:
                continue
            low_at = top + int(np.argmin(after[: peak_at + 1]))
            unit = np.zeros(len(block.dofs))
            unit[where[i]] = 1.0
            form = self._forms[low_at] - self._forms[top + peak_at]
            out.append((form, float(cap - rise), unit, limits[e][0]))
        return out


def refine_block(
    block: PoleResidueBlock,
    data: BlockData,
    linearised: Linearised,
    *,
    motion_tol: float,
    bounds=None,
    steps: int = STEPS,
) -> tuple[PoleResidueBlock, bool]:
    """``block`` (its poles kept) refined on the motions and made passive (module
    docstring): (block, passive). ``linearised``: the block's motions linearised
    (:data:`Linearised`); ``bounds``: further violated linear constraints of a block,
    as :func:`~cummins.radiation.fit.block_passivity.enforce_passivity` takes them (the
    damping beyond the data held under the data's tail). Not passive when the
    programme becomes infeasible or the iterations run out: the caller keeps its own."""
    if linearised(block) is None:  # no Woodbury form of the motions (joined bodies)
        return block, False
    coords = Coordinates.of(block, data)
    fit_r, fit_shift = fit_equations(data, block, coords)
    normal_fit, rhs_fit = fit_r.T @ fit_r, fit_r.T @ fit_shift
    sizes = [null.shape[1] for null in coords.nulls]
    constraint_rows = ConstraintRows(block, coords.nulls, np.r_[0, np.cumsum(sizes)])
    residue = coords.residue_columns()
    w = data.omega[: data.n_data]
    lo, hi = float(w.min()), float(w.max())
    sweep = BlockSweep(block, lo, hi)
    z = coords.pack(block)
    rows, rhs = np.zeros((0, z.size)), np.zeros(0)
    bound = np.zeros(0, dtype=bool)
    last = np.zeros(0, dtype=bool)  # the rows that bound in the last programme, and new ones
    lawson = None
    misfit, transformed = None, np.zeros((0, z.size))
    current, exact = block, False
    for iteration in range(steps + PASSIVITY_ITERATIONS):
        found, _ = passivity_violations(current, lo, hi, exact=exact, sweep=sweep)
        if not found and not exact:
            exact = True
            found, _ = passivity_violations(current, lo, hi, exact=exact, sweep=sweep)
        found = found + ([] if bounds is None else bounds(current))
        if not found and iteration >= steps:
            return current, True
        new = np.zeros((len(found), z.size))
        if found:
            new[:, residue] = constraint_rows(found)
            rows = np.vstack([rows, new])
            rhs = np.r_[rhs, [MARGIN * local - lam for _, lam, _, local in found] + new @ z]
            bound = np.r_[bound, np.zeros(len(found), dtype=bool)]
            last = np.r_[last, np.ones(len(found), dtype=bool)]
        if iteration < steps:  # re-linearised: a Gauss–Newton step, every row transformed
            misfit, lawson = _gauss_newton(
                current, coords, z, linearised, normal_fit, rhs_fit, lawson, motion_tol
            )
            transformed = misfit.transformed(rows) if rhs.size else transformed[:0]
        elif found:  # the misfit frozen: G R⁻¹ of the new rows only
            transformed = np.concatenate([transformed, misfit.transformed_rows(new)])
        if not rhs.size:
            z = misfit.solve(-misfit.shift)
            current = coords.unpack(z, block)
            continue
        try:
            z, active = least_distance(misfit, rows, rhs, transformed, start=last)
        except FitError:
            return current, False
        bound |= active
        last = active
        if rhs.size > z.size:  # as the enforcement prunes its programme
            rows, rhs, transformed, last, bound = (
                rows[bound],
                rhs[bound],
                transformed[bound],
                last[bound],
                bound[bound],
            )
        current = coords.unpack(z, block)
    return current, False


def _gauss_newton(
    block, coords, z, linearised, normal_fit, rhs_fit, lawson, motion_tol
) -> tuple[FactoredMisfit, NDArray]:
    """(misfit ‖R z + shift‖², R upper triangular; Lawson weights) of a step: the fit's
    normal equations plus the motion residuals linearised at ``block`` (z), weighed by
    Lawson's weights (updated from the residuals)."""
    omega, residual, sensitivity = linearised(block)
    r = residual.reshape(-1)
    jac = motion_columns(block, coords, omega, sensitivity)
    lawson = np.ones(r.size) if lawson is None else lawson * np.abs(r)
    lawson = lawson / max(float(lawson.mean()), np.finfo(float).tiny)
    scale = np.sqrt(lawson) / (motion_tol * np.sqrt(omega.size))
    used = np.flatnonzero(np.abs(jac).max(axis=0) > 0)  # the columns the motions see
    weighted = scale[:, None] * jac[:, used]
    target = weighted @ z[used] - scale * r
    stacked = np.vstack([weighted.real, weighted.imag])
    normal, rhs = normal_fit.copy(), rhs_fit.copy()
    normal[np.ix_(used, used)] += stacked.T @ stacked
    rhs[used] += stacked.T @ np.r_[target.real, target.imag]
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
    before = motion(kept)
    targets = {"r2": options.r2, "r2_coupling": options.coupling_target}
    best = None
    for count in dict.fromkeys(counts):
        start = data.plain_fits.get(count, (None, None))[0]
        try:
            start = vector.vector_fit(data, count) if start is None else start
            block, passive = refine_block(
                start, data, linearised, motion_tol=options.motion_tol, bounds=BeyondBounds(data)
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


def refined_on_motions(inp, options, model, fit):
    """``model`` (the blocks fitted by ``fit(inp, options)`` without the refinement, the
    A∞ of :mod:`cummins.radiation.fit.causal_inf` decided), or, with
    ``options.refine_motions`` and its motions off their aim, the blocks fitted again
    with it (:func:`refined_block`), the A∞ estimated for the same DOFs, when that
    brings the motions nearer the data's. Refined in the final fit only (with the
    refinement in both, the RM3's took 18 s instead of 8), ``fit`` reusing its order
    searches (``searched`` of :func:`~cummins.radiation.fit.blocks.fit_blocks`)."""
    from dataclasses import replace

    from cummins.radiation.fit.options import MOTION_AIM

    error = model.attrs.get("motion_error")
    if not options.refine_motions or error is None or error <= MOTION_AIM * options.motion_tol:
        return model
    estimated = model.attrs.get("added_mass_inf_estimated") or []
    dofs = tuple(inp.labels.index(label) for label in estimated)
    refit = fit(replace(inp, estimated_inf=dofs), options)
    if refit.attrs.get("motion_error", np.inf) >= error:
        return model
    # the notes said after the blocks were fitted (the A∞ estimated), not the blocks' own
    names = tuple("-".join(inp.labels[d] for d in block.dofs) + ": " for block in model.blocks)
    notes = list(refit.attrs.get("data_notes", []))
    notes += [
        n for n in model.attrs.get("data_notes", []) if n not in notes and not n.startswith(names)
    ]
    return replace(refit, attrs={**refit.attrs, "data_notes": notes})
