"""The order search of the common-pole identification: the blocks of coupled DOFs, the
score of a fitted block against its targets, and the number of common poles of each
block (:mod:`cummins.radiation.fit.vector`, step 4).

The number of common poles grows until every coupling reaches its R² targets and the
motion error of the block is within its aim; each trial costs a few milliseconds. It
stops early when more poles stop improving the fit, when they stop lessening what
passivity costs the fits that meet the targets before it, or when passivity loses a
coupling at two orders in a row (data that are not passive themselves). When no order meets
every target, the fits closest to them are made passive side by side, the one whose
iterate is the closest going on first: one no closer before passivity than the best
passive fit so far is after it is not tried (passivity does not bring a fit closer to
its targets), an enforcement whose iterate is already far further gives up
(:data:`GIVE_UP`), and the fewest poles among the passive fits nearly as close as the
best is kept.
"""

from __future__ import annotations

from collections.abc import Callable, Generator, Iterator, Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from cummins.errors import FitError
from cummins.radiation.fit.block_passivity import enforce_passivity, enforcement_steps
from cummins.radiation.fit.frequency import r_squared_of, total_variation
from cummins.radiation.fit.tail import (
    PEAK_TOLERANCE,
    BeyondData,
    TailBounds,
    block_beyond_data,
    impulse_r2,
)
from cummins.radiation.fit.vector import (
    BlockData,
    PoleResidueBlock,
    Poles,
    fit_residues_at,
    vector_fit,
)


def block_groups(n: int, pairs) -> list[tuple[tuple[int, ...], tuple[tuple[int, int], ...]]]:
    """The blocks: connected components of the significant pairs (DOFs, pairs i ≤ j)."""
    parent = list(range(n))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, j in pairs:
        parent[root(i)] = root(j)
    modelled = sorted({i for i, j in pairs if i == j})
    groups: dict[int, list[int]] = {}
    for i in modelled:
        groups.setdefault(root(i), []).append(i)
    out = []
    for dofs in sorted(groups.values()):
        members = set(dofs)
        elements = tuple(sorted((i, j) for i, j in pairs if i in members and j in members))
        out.append((tuple(dofs), elements))
    return out


@dataclass(frozen=True)
class BlockScore:
    """How a fitted block meets its targets.

    ``kernel`` holds the R² of K(t) of the diagonal elements (when the data's K(t) is
    known; computed when first read, :class:`KernelR2`: only a kept block's note reads
    them), ``kernel_shortfall`` the largest shortfall below its target in units of the
    allowed 1 − R²; ``beyond`` what the model's damping does beyond the data
    (:func:`cummins.radiation.fit.tail.block_beyond_data`, scored after the passivity
    step), ``tail_excess`` the largest breach of :data:`~cummins.radiation.fit.tail.PEAK_TOLERANCE`
    in units of it (0 when none)."""

    r2: dict[tuple[int, int], tuple[float, float]]
    shortfall: float  # largest R² shortfall below target (0 when met)
    motion_error: float | None  # relative motion error with the block modelled
    passive: bool
    kernel: Mapping[int, float] = field(default_factory=dict)
    beyond: dict[int, BeyondData] = field(default_factory=dict)
    tail_excess: float = 0.0

    @property
    def kernel_shortfall(self) -> float:
        """The largest shortfall of the R² of K(t) below its target (0 when met or not
        judged), in units of the allowed 1 − R²."""
        return self.kernel.shortfall() if isinstance(self.kernel, KernelR2) else 0.0

    def meets(self, motion_aim: float | None) -> bool:
        motion_ok = (
            motion_aim is None or self.motion_error is None or self.motion_error <= motion_aim
        )
        return self.shortfall <= 0 and motion_ok and self.tail_excess <= 0


def score_block(
    block: PoleResidueBlock,
    data: BlockData,
    *,
    r2: float,
    r2_coupling: float,
    motion=None,
    passive: bool = False,
    r2_kernel: float | None = None,
    tail: bool = False,
) -> BlockScore:
    """R² of A and B of each pair (on the frequencies it keeps; each direction of a pair
    fitted as given), the shortfall below the targets and, with ``motion`` (a callable:
    block → relative motion error), the motion error; with ``r2_kernel`` (and the data's
    K(t) in ``data``) the R² of K(t) of each diagonal element, and with ``tail`` the
    model's damping beyond the data."""
    w = data.omega[: data.n_data]
    k = block.element_response(w)
    responses = block.pair_values(k.T)
    infs = block.pair_values(block.added_mass_inf)
    scores, shortfall = {}, 0.0
    for (i, j), response in responses.items():
        use, w_use, a_data, b_data, total_a, total_b = _pair_data(data, i, j)
        a_model = infs[(i, j)] + response[use].imag / w_use
        b_model = response[use].real
        pair = (r_squared_of(a_data, a_model, total_a), r_squared_of(b_data, b_model, total_b))
        scores[(i, j)] = pair
        target = r2 if i == j else r2_coupling
        shortfall = max(shortfall, target - min(pair))
    error = None if motion is None else float(motion(block))
    kernel: Mapping[int, float] = {}
    if r2_kernel is not None and data.kernel is not None:
        kernel = KernelR2(block, data, r2_kernel)
    beyond, tail_excess = {}, 0.0
    if tail:
        beyond = block_beyond_data(block, data)
        for found in beyond.values():
            breach = max(found.rise, found.excess) - PEAK_TOLERANCE
            tail_excess = max(tail_excess, breach / PEAK_TOLERANCE)
    return BlockScore(scores, shortfall, error, passive, kernel, beyond, tail_excess)


class KernelR2(Mapping):
    """The R² of K(t) of a fitted block's diagonal elements against the data's, by DOF
    (model index), computed when first read: the order search scores tens of fits and
    iterates, and only the kept block's note reads them (the same numbers)."""

    def __init__(self, block: PoleResidueBlock, data: BlockData, target: float):
        self._block, self._data, self._target = block, data, target
        self._values: dict[int, float] | None = None

    def _computed(self) -> dict[int, float]:
        if self._values is None:
            fitted = self._block.element_impulse(self._data.time)
            self._values = {
                i: impulse_r2(self._data.kernel[e], fitted[:, e])
                for e, (i, j) in enumerate(self._block.elements)
                if i == j
            }
        return self._values

    def __getitem__(self, dof: int) -> float:
        return self._computed()[dof]

    def __iter__(self) -> Iterator[int]:
        return iter(self._computed())

    def __len__(self) -> int:
        return len(self._computed())

    def shortfall(self) -> float:
        """The largest shortfall below the target in units of the allowed 1 − R²."""
        gaps = [(self._target - x) / (1 - self._target) for x in self._computed().values()]
        return max([0.0, *gaps])


def _pair_data(data: BlockData, i: int, j: int) -> tuple:
    """The data's side of the R² of the pair (i, j) (each direction of a pair fitted as
    given), the same for every fit of the block and computed once (``data.cache``):
    (frequencies kept, their ω, A and B there, Σ(y − ȳ)² of A and B, at least n × the
    pair's variance floor when it is fitted as given: :func:`~cummins.radiation.fit.
    frequency.r_squared`)."""
    from cummins.radiation.fit.metrics import pair_floor

    found = data.cache.get(("pair", i, j))
    if found is None:
        e = data.elements.index((min(i, j), max(i, j)))
        use = data.used[:, e]
        floor = (0.0, 0.0)
        if (max(i, j), min(i, j)) in data.elements:  # fitted as given: the pair's spread
            floor = pair_floor(data.added_mass[use], data.damping[use], i, j)
        a_data = np.asarray(data.added_mass[use, i, j], dtype=float)
        b_data = np.asarray(data.damping[use, i, j], dtype=float)
        totals = [total_variation(a_data, floor[0]), total_variation(b_data, floor[1])]
        found = (use, data.omega[: data.n_data][use], a_data, b_data, *totals)
        data.cache[("pair", i, j)] = found
    return found


#: Near-ties in the order search are decided by this margin, not by rounding.
TIE = 1e-6


def _tied(badness: float) -> float:
    """A distance to the targets on the grid of :data:`TIE`: near-ties compare equal."""
    return round(badness / TIE) * TIE


def identify_block(
    data: BlockData,
    *,
    r2: float,
    r2_coupling: float,
    max_count: int,
    motion=None,
    motion_aim: float | None = None,
    fixed_count: int | None = None,
    passive: bool = True,
    r2_kernel: float | None = None,
    labels=None,
    unjudged: str | None = None,
    poles: Poles | None = None,
) -> tuple[PoleResidueBlock, BlockScore, list[str]]:
    """The block at the smallest number of common poles that meets the targets and is
    passive (module docstring, step 4); the best passive one when none does (``labels``:
    the DOF labels, by model index, that its notes name; ``unjudged``: why no motions
    judge it, when none do). With ``poles``, the block's residues at those poles only
    (another block's, :func:`cummins.radiation.fit.blocks.fit_blocks`), made passive."""
    if poles is not None:
        fixed_count = poles.count
    counts = [fixed_count] if fixed_count else list(range(2, max_count + 1))
    fewest = int(data.used.sum(axis=0).min())
    counts = [c for c in counts if c + 2 <= fewest]
    if not counts:
        raise FitError(
            f"{fewest} frequencies are too few for a model of order {fixed_count or 2}",
            hint="a fluid-memory model needs the added mass and damping at many "
            "frequencies (tens) over the range of the motions",
        )
    notes: list[str] = []
    plain_fits: list[tuple[float, int, PoleResidueBlock]] = []
    tried: dict[int, tuple[tuple[bool, float], PoleResidueBlock, BlockScore]] = {}

    def scored(block: PoleResidueBlock, is_passive: bool = False) -> BlockScore:
        return score_block(
            block,
            data,
            r2=r2,
            r2_coupling=r2_coupling,
            motion=motion,
            passive=is_passive,
            r2_kernel=r2_kernel,
            tail=True,
        )

    def passivated(count: int, fitted: PoleResidueBlock, bound: float = np.inf) -> bool:
        """The fit made passive and scored; True when it meets every target. With a
        ``bound``, the enforcement gives up once its iterate is further from the targets
        (passivity brings no fit closer: that fit would not be kept). The damping beyond
        the data is held under the data's tail in the same programme."""
        last: list = [None, None]  # the iterate give_up scored last, and its score
        if passive:
            give_up = None
            if np.isfinite(bound):

                def give_up(block: PoleResidueBlock) -> bool:
                    last[:] = block, scored(block)
                    return distance(last[1], r2, motion_aim) > bound

            block, is_passive, _ = enforce_passivity(
                fitted, data, give_up=give_up, bounds=TailBounds(data)
            )
        else:
            block, is_passive = fitted, True
        if block is last[0]:  # the enforcement ended on the iterate give_up scored
            score = replace(last[1], passive=is_passive)
        else:
            score = scored(block, is_passive)
        tried[count] = (closeness(score, r2, motion_aim), block, score)
        return is_passive and score.meets(motion_aim)

    stalled, best_plain = 0, np.inf
    # passivity that loses a coupling of fits that met every target before it, order
    # after order: the data (not passive themselves), not the order, limit the block
    passive_lost, passive_stalled, best_passive = 0, 0, np.inf
    done = False
    for count in counts:
        try:
            fitted = vector_fit(data, count) if poles is None else fit_residues_at(data, poles)
        except np.linalg.LinAlgError:
            continue
        plain = score_block(
            fitted, data, r2=r2, r2_coupling=r2_coupling, motion=motion, r2_kernel=r2_kernel
        )
        bad = distance(plain, r2, motion_aim)
        plain_fits.append((bad, count, fitted))
        data.plain_fits[count] = (fitted, plain)
        if bad < (1 - IMPROVEMENT) * best_plain or bad == 0:
            best_plain, stalled = min(bad, best_plain), 0
        else:
            stalled += 1
        if plain.meets(motion_aim):
            # bounded by the passive fits of fewer poles, as the finalists: one given up
            # is judged below by its last iterate (the pyHAMS cylinder's 19 common poles,
            # given up after 3 iterations at 4 times the 18's distance, had run 43 to end
            # 1.3 times as far; both lose a coupling, the search stops there either way)
            if passivated(count, fitted, GIVE_UP * (nearest_passive(tried) + NEAR)):
                done = True
                break
            lost = tried[count][2].shortfall >= LOST
            passive_lost = passive_lost + 1 if lost else 0
            if passive_lost >= PASSIVE_PATIENCE:
                notes.append(
                    f"passivity loses a coupling at {passive_lost} orders in a row that fit "
                    "the data before it: the data are not passive (`cummins check`)"
                )
                done = True
                break
            # nor does a passivity cost that more poles do not lessen
            badness = tried[count][0][1]
            if badness < (1 - IMPROVEMENT) * best_passive:
                best_passive, passive_stalled = badness, 0
            else:
                passive_stalled += 1
            if passive_stalled >= PASSIVE_STALL:
                done = True
                break
        if stalled >= PATIENCE:
            break
    if not done:  # nothing met every target: the best few fits, made passive
        finalists = sorted(plain_fits, key=lambda x: (x[0], x[1]))[:FINALISTS]
        if passive:
            made_passive_nearest_first(
                [f for f in finalists if f[1] not in tried],
                tried,
                lambda fitted: enforcement_steps(fitted, data, bounds=TailBounds(data)),
                scored,
                r2=r2,
                motion_aim=motion_aim,
            )
        else:
            for bad, count, fitted in finalists:
                if _tied(bad) >= nearest_passive(tried):
                    break
                if count not in tried:
                    passivated(count, fitted)
    if not tried:
        raise FitError("no stable model could be fitted")
    count = kept_count({c: key for c, (key, _, _) in tried.items()})
    _, block, score = tried[count]
    if not score.passive:
        notes.append(f"not passive at {count} common poles")
    if not score.meets(motion_aim):
        notes.append(
            targets_not_met(
                count,
                score,
                r2=r2,
                r2_coupling=r2_coupling,
                r2_kernel=r2_kernel,
                motion_aim=motion_aim,
                labels=labels,
                unjudged=unjudged,
            )
        )
    return block, score, notes


def nearest_passive(tried: dict) -> float:
    """The distance to the targets of the closest passive fit of ``tried`` (count → (key
    of :func:`closeness`, block, score)); ∞ when none is passive."""
    return min((key[1] for key, _, _ in tried.values() if not key[0]), default=np.inf)


@dataclass
class _Finalist:
    """A finalist of the order search on its way to passivity: its rank among the
    finalists, its number of common poles, the plain fit, the distance to the targets of
    its latest iterate (of the plain fit before its enforcement starts), its enforcement
    (:func:`~cummins.radiation.fit.block_passivity.enforcement_steps`) and its latest
    iterate with that iterate's score."""

    rank: int
    count: int
    fitted: PoleResidueBlock
    distance: float
    steps: Generator | None = None
    last: tuple[PoleResidueBlock, BlockScore] | None = None


def made_passive_nearest_first(
    finalists: list[tuple[float, int, PoleResidueBlock]],
    tried: dict,
    start: Callable[[PoleResidueBlock], Generator],
    scored: Callable[..., BlockScore],
    *,
    r2: float,
    motion_aim: float | None,
) -> None:
    """The finalists (distance before passivity, count, plain fit; the closest first) made
    passive into ``tried`` (count → (key of :func:`closeness`, block, score)), their
    enforcements run side by side: each stretch of :data:`~cummins.radiation.fit.
    block_passivity.GIVE_UP_EVERY` iterations goes to the finalist whose iterate is the
    closest to the targets. Passivity brings no fit closer, so the first to end passive
    bounds the others early: one further than :data:`GIVE_UP` × (the closest passive fit
    + :data:`NEAR`) gives up (recorded not passive, at that iterate), and one not started
    that is no closer before passivity than the closest passive fit is not tried.

    Made passive one after the other, the closest first, the first ran without a bound
    (no fit was passive yet): the HAMS cylinder's 20 common poles ran 39 iterations (0.5 s
    of its 1.3–1.5 s) to end at 9 times the distance of the kept 17; side by side it gives
    up after 3, once the 17 has ended, and the others run as before. Were each iterate
    no closer to the targets than the one before it (passivity only takes a fit away from
    them), no finalist would run further than one after the other, nor would another fit
    be kept; the iterates come back a little at times (the cylinder's 18: 46.7, then 39.2),
    and the 38 cases of ``benchmarks/bench_identification.py`` give the same models bit
    for bit."""
    waiting = [_Finalist(k, count, fitted, bad) for k, (bad, count, fitted) in enumerate(finalists)]
    while waiting:
        finalist = min(waiting, key=lambda f: (f.distance, f.rank))
        nearest = nearest_passive(tried)
        if finalist.steps is None:
            if _tied(finalist.distance) >= nearest:  # nor any other not started
                waiting = [f for f in waiting if f.steps is not None]
                continue
            finalist.steps = start(finalist.fitted)
        elif finalist.distance > GIVE_UP * (nearest + NEAR):
            block, score = finalist.last
            tried[finalist.count] = (closeness(score, r2, motion_aim), block, score)
            waiting.remove(finalist)
            continue
        try:
            block, _ = next(finalist.steps)
        except StopIteration as end:
            block, is_passive, _ = end.value
            if finalist.last is not None and block is finalist.last[0]:
                score = replace(finalist.last[1], passive=is_passive)
            else:
                score = scored(block, is_passive)
            tried[finalist.count] = (closeness(score, r2, motion_aim), block, score)
            waiting.remove(finalist)
            continue
        finalist.last = block, scored(block)
        finalist.distance = distance(finalist.last[1], r2, motion_aim)


#: A note names at most this many targets missed (the worst first).
NAMED = 3


def targets_not_met(
    count: int,
    score: BlockScore,
    *,
    r2: float,
    r2_coupling: float,
    r2_kernel: float | None = None,
    motion_aim: float | None = None,
    labels=None,
    unjudged: str | None = None,
) -> str:
    """The note of a block that no number of common poles brings to every target: which
    targets it misses (R² of A or B of which coupling, R² of K(t), the damping beyond the
    data, the motion error), the worst first, and whether it matters — whether the
    block's motions meet their aim (then the RAOs do not show it)."""

    def name(i: int, j: int) -> str:
        one, two = (labels[i], labels[j]) if labels is not None else (str(i), str(j))
        return one if i == j else f"{one}-{two}"

    missed = []  # (shortfall in units of what the target allows, text)
    for (i, j), pair in score.r2.items():
        target = r2 if i == j else r2_coupling
        for what, value in zip("AB", pair, strict=True):
            if value < target:
                missed.append(
                    (
                        (target - value) / (1 - target),
                        f"R² of {what} of {name(i, j)} {value:.4f} < {target:g}",
                    )
                )
    if r2_kernel is not None:
        for i, value in score.kernel.items():
            if value < r2_kernel:
                missed.append(
                    (
                        (r2_kernel - value) / (1 - r2_kernel),
                        f"R² of K(t) of {name(i, i)} {value:.3f} < {r2_kernel:g}",
                    )
                )
    for i, found in score.beyond.items():
        if not found.ok():
            missed.append((np.inf, f"{name(i, i)}'s damping beyond the data"))
    motion = score.motion_error
    if motion_aim is not None and motion is not None and motion > motion_aim:
        missed.append(
            (
                (motion - motion_aim) / motion_aim,
                f"motion error {100 * motion:.2f} % > its aim {100 * motion_aim:.2g} %",
            )
        )
    missed.sort(key=lambda x: -x[0])
    what = "; ".join(text for _, text in missed[:NAMED])
    if len(missed) > NAMED:
        what += f" and {len(missed) - NAMED} more"
    if not score.passive:
        what = "not passive" + (f"; {what}" if what else "")
    if motion_aim is None or motion is None:
        matters = f"no motions to judge it by ({unjudged or 'no inertia or no restoring'})"
    elif motion <= motion_aim:
        matters = (
            f"the motions meet their aim ({100 * motion:.2f} % ≤ {100 * motion_aim:.2g} %), "
            "so this costs nothing the RAOs show"
        )
    else:
        matters = "the motions miss their aim: the RAOs show it"
    return f"targets not met at any number of common poles (kept {count}): {what}; {matters}"


def kept_count(keys: dict[int, tuple[bool, float]]) -> int:
    """The number of common poles kept among those made passive, from their keys (not
    passive, distance to the targets): the fewest that meets every target; short of them,
    the fewest among those within :data:`NEAR` of the closest (the passive first)."""
    best = min(keys.values())
    if best[1] == 0:
        return min(c for c, key in keys.items() if key == best)
    return min(c for c, (flag, bad) in keys.items() if flag == best[0] and bad <= best[1] + NEAR)


#: The order search stops when PATIENCE more poles in a row have not improved the fit
#: (before passivity) by IMPROVEMENT of its distance to the targets.
PATIENCE = 4
IMPROVEMENT = 0.02
#: When no fit meets every target, the FINALISTS closest to them (before passivity) are
#: made passive and the best passive one is kept.
FINALISTS = 5
#: The order search also stops when passivity has lost a coupling (R² more than LOST
#: below its target: worse than the data's mean) on PASSIVE_PATIENCE fits in a row that
#: met every target before it (the WAMIT OSWEC 2015 with targets 0.98/0.96: the base's
#: negative roll damping costs its R² of A below zero once passive, and the search stops
#: at 10 common poles; at the default targets its plain fits meet them only at 12, the
#: most its base roll's 14 kept frequencies allow). A passivity step that costs a little
#: (the usual case on sound data) does not stop it.
PASSIVE_PATIENCE = 2
LOST = 1.0
#: Nor does it go on when PASSIVE_STALL more counts in a row, their fits meeting every
#: target before passivity, have not lessened what passivity costs by IMPROVEMENT (the
#: RAFT float's heave: 0.01–0.08 of R² at 7 … 20 poles; 3 or 4 give the same models on
#: every corpus case, 3 is 0.5 s faster on the NEMOH two cubes).
PASSIVE_STALL = 3
#: A passivity enforcement of the order search (a finalist's, or one of a fit meeting
#: every target before passivity) gives up when its iterate is further from the targets
#: than GIVE_UP × (the best passive fit's distance + NEAR): it would end further still and
#: not be kept (the RAFT float's surge-pitch block: 4 of its 5 finalists end at 6–7 times
#: the best; each took 20–25 iterations).
GIVE_UP = 2.0
#: When no order meets every target, passive fits closer to them by less than NEAR (in
#: units of the allowed 1 − R², a tenth: R² within 0.001) are equally good, and the
#: fewest poles among them is kept (the ITI barge: 15 or 20 common poles on its surge–
#: pitch block, R² 0.9785 or 0.9790 after passivity).
NEAR = 0.1


def closeness(score: BlockScore, r2: float, motion_aim: float | None) -> tuple[bool, float]:
    """The key that ranks fits made passive: not passive, then the :func:`distance` to the
    targets on the grid of :data:`TIE` (the smaller the closer)."""
    return (not score.passive, _tied(distance(score, r2, motion_aim)))


def distance(score: BlockScore, r2: float, motion_aim: float | None) -> float:
    """Distance of a fit to its targets: the R² shortfall in units of the allowed 1 − R²,
    plus the motion error's excess in units of its aim.

    The shortfall is the mean of the largest one over all pairs and the largest one over
    the diagonal: the same when a diagonal term is the furthest from its target, but a
    coupling that no order follows (the NEMOH two cubes' yaw–yaw coupling between the
    bodies, noise at 1 % of the diagonal: R² 0 at 4 … 16 common poles) no longer hides
    that more poles still bring the diagonal closer (their yaw: R² of A 0.14 → 0.90)."""
    diagonal = max((r2 - min(pair) for (i, j), pair in score.r2.items() if i == j), default=0.0)
    out = 0.5 * (max(score.shortfall, 0.0) + max(diagonal, 0.0)) / (1.0 - r2)
    out += max(score.tail_excess, 0.0)
    if motion_aim and score.motion_error is not None:
        out += max(score.motion_error - motion_aim, 0.0) / motion_aim
    return out
