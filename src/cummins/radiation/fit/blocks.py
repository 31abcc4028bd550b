"""The common-pole identification of a whole model (``method="vf"``, the default): every
block of coupled DOFs fitted with common poles and made passive as fitted
(:mod:`cummins.radiation.fit.vector`), assembled as :class:`~cummins.radiation.model.MemoryBlock`
models
with their per-pair metrics and the model's motion error.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from cummins.errors import FitError
from cummins.radiation.fit import order_search, vector
from cummins.radiation.fit.block_passivity import exact_crossings
from cummins.radiation.fit.causal_inf import estimated_inf, noncausal_dofs
from cummins.radiation.fit.data import FitInput, range_cut_failures
from cummins.radiation.fit.metrics import coupling_metrics, pair_floor
from cummins.radiation.fit.mimo import (
    coordinate_notes,
    failure_targets,
    fit_failures,
    with_motion_note,
)
from cummins.radiation.fit.motion import (
    BlockMotionError,
    coordinate_dofs,
    coordinate_r_squared,
)
from cummins.radiation.fit.motion_refinement import refined_block
from cummins.radiation.fit.options import MOTION_AIM, MOTION_TOL, FitOptions
from cummins.radiation.fit.tail import fine_kernel_metrics, fine_time_grid
from cummins.radiation.model import MemoryBlock, RadiationModel, modal_form
from cummins.radiation.passivity import passivity_test
from cummins.radiation.retardation import diagonal_retardation_functions


def fit_blocks(
    inp: FitInput,
    options: FitOptions,
    say: Callable[[str], None] = lambda message: None,
    searched: dict | None = None,
    only_refined: bool = False,
) -> RadiationModel | None:
    """Every block of coupled DOFs of the prepared data fitted with common poles (module
    docstring); ``attrs`` hold ``mimo_passive``, the motion error and ``failures``.
    ``searched``: each block's order search by its DOFs, and each block as made when not
    refined (its metrics), filled by this call and taken from it by the next (the same
    ``inp``): the motion refinement of the fit kept
    (:func:`cummins.radiation.fit.motion_refinement.refined_on_motions`) does not search
    again, nor measure again a block it does not refine. ``only_refined``: None when no
    block is refined (the model would be the last one's)."""
    labels, w, keep_dof, pairs = inp.labels, inp.data.omega.values, inp.keep_dof, inp.pairs
    added_mass, damping, measured = inp.added_mass, inp.damping, inp.measured
    a_inf = None if inp.a_inf_mode == "fit" else inp.a_inf
    prior = (
        0.5 * (inp.ogilvie + inp.ogilvie.T),
        0.5 * (inp.ogilvie_spread + inp.ogilvie_spread.T),
    )
    sensitivity, attrs = inp.sensitivity, inp.attrs
    r2, r2_coupling, max_order = options.r2, options.coupling_target, options.max_order
    orders, motion_tol, passive = options.orders, options.motion_tol, options.passivity == "mimo"
    n = len(labels)
    positive = w > 0
    omega = w[positive]
    a_data, b_data = added_mass[positive], damping[positive]
    keep = keep_dof[positive]
    # A∞ of what no block models stays the data's row, else Ogilvie's estimate
    inf = prior[0].copy() if a_inf is None else 0.5 * (a_inf + a_inf.T)
    antisymmetric = inp.antisymmetric_added_mass
    k_data = None
    if sensitivity is not None:
        rows = sensitivity.compared_frequencies()
        wk = sensitivity.omega[rows]
        k_data = measured.damping[rows] + 1j * wk[:, None, None] * (
            measured.added_mass[rows] + antisymmetric
        )
        block_motion = BlockMotionError(sensitivity, k_data)
    if k_data is not None and options.refine_motions is not False:
        # the refinement's: the couplings no block models as the model will have them
        # and the user's motions, not the passive part's the fit aims at
        judged = sensitivity if inp.reference is None else inp.reference
        model_motion = BlockMotionError(
            replace(sensitivity, motions=judged.motions, compared=judged.compared),
            unmodelled_as_model(k_data, wk, inp.negligible, inf + antisymmetric),
        )
    motion_aim = MOTION_AIM * motion_tol if sensitivity is not None else None
    blocks, notes, tail_failures = [], [], []
    crossings = []  # per block, its last exact test's crossings when known (exact_crossings)
    any_refined = False
    done: list = []  # (name, dofs, elements, poles, score, pole floor) of each block fitted
    # K(t) of the data at the step of the default grid: the R² of K(t) the fit is judged by
    fine_time = fine_time_grid(measured.time, float(w.max()))
    diagonal = sorted({i for i, j in pairs if i == j})  # the diagonal terms alone
    fine_values = diagonal_retardation_functions(inp.data, fine_time, diagonal)
    fine_kernel = dict(zip(diagonal, fine_values.T, strict=True))

    def search(dofs, elements, fixed_count, identify):
        """The block's order search: at the poles of a twin block fitted before
        (:func:`mirror_block`) when it shares them well, else its own (with poles as
        lightly damped as a sharp resonance the motions depend on, or the default
        target's fit, when either is closer); (data, fit, score, notes, pole floor)."""
        shared = None
        twin = None if fixed_count else mirror_block(done, dofs, elements, a_data, b_data)
        if twin is not None:  # the twin's poles, this block's residues
            twin_name, twin_poles, twin_score, twin_floor, difference = twin
            shared = identify(motion_tol, motion_aim, min_damping=twin_floor, poles=twin_poles)
            if not shares_well(shared[2], twin_score, r2, motion_aim):
                shared = None
        if shared is not None:
            data, fitted, score, block_notes = shared
            floor = twin_floor
            block_notes.append(
                f"the {fitted.poles.count} common poles of the {twin_name} block, whose "
                f"diagonal A and B differ from these by {difference:.2%} at most (as an "
                "axisymmetric body's two horizontal blocks): residues fitted to these data"
            )
        else:
            data, fitted, score, block_notes = identify(motion_tol, motion_aim)
            floor = vector.MIN_DAMPING
            if set(dofs) & set(inp.resonant_dofs) and not score.meets(motion_aim):
                # a sharp resonance the motions depend on (a piston or gap mode) and the
                # targets missed: poles as lightly damped as the resonance, when that brings
                # the block closer to its targets
                sharp = identify(motion_tol, motion_aim, min_damping=vector.RESONANCE_MIN_DAMPING)
                if order_search.closeness(sharp[2], r2, motion_aim) < order_search.closeness(
                    score, r2, motion_aim
                ):
                    data, fitted, score, block_notes = sharp
                    floor = vector.RESONANCE_MIN_DAMPING
                    block_notes.append(
                        f"a sharp resonance kept: poles damped down to {floor:.0%} of critical "
                        f"(else {vector.MIN_DAMPING:.0%})"
                    )
            if motion_aim is not None and motion_tol < MOTION_TOL and not score.meets(motion_aim):
                # a tighter motion target weighs the motions more, and passivity can then cost
                # them more than it costs the default's fit (the supply vessel's heave-pitch
                # block: 0.55 % at 10 common poles against the default's 0.29 % at 9): the
                # tighter target never keeps a block further from it than the default's
                default = identify(MOTION_TOL, MOTION_AIM * MOTION_TOL, min_damping=floor)
                if order_search.closeness(default[2], r2, motion_aim) < order_search.closeness(
                    score, r2, motion_aim
                ):
                    # its own notes (a miss of the default's targets among them), not those
                    # of the fits set aside
                    data, fitted, score, block_notes = default
                    block_notes.append(
                        f"the default's fit ({fitted.poles.count} common poles) is closer to "
                        "the tighter motion target than the fits made for it: kept"
                    )
                    if score.meets(MOTION_AIM * MOTION_TOL) and not score.meets(motion_aim):
                        block_notes.append(
                            order_search.targets_not_met(
                                fitted.poles.count,
                                score,
                                r2=r2,
                                r2_coupling=r2_coupling,
                                r2_kernel=options.r2_kernel,
                                motion_aim=motion_aim,
                                labels=labels,
                            )
                        )
        return data, fitted, score, block_notes, floor

    for dofs, elements in order_search.block_groups(n, pairs):
        say("block " + "-".join(labels[d] for d in dofs))
        # a pair fitted as given adds its antisymmetric part (j, i) after the others
        elements = elements + tuple((j, i) for i, j in elements if (i, j) in inp.as_given)
        used = np.stack([keep[:, i] & keep[:, j] for i, j in elements], axis=1)

        def motion(block, dofs=dofs):
            if k_data is None:
                return 0.0
            return block_motion(dofs, model_k(block, dofs))

        def refined_motions(dofs=dofs):
            """The block's motion error and its linearisation, every other coupling as
            the model has it (:func:`unmodelled_as_model`)."""
            return (
                lambda fit: model_motion(dofs, model_k(fit, dofs)),
                lambda fit: model_motion.linearised(dofs, model_k(fit, dofs)),
            )

        def model_k(block, dofs=dofs):
            """K̂ + jω A∞ of the block at the compared frequencies (the motions' K)."""
            local = block.response(wk)
            a_block = np.zeros((len(dofs), len(dofs)))
            for (i, j), value in block.pair_values(block.added_mass_inf).items():
                ii, jj = dofs.index(i), dofs.index(j)
                a_block[ii, jj] = value
                if i <= j and (j, i) not in block.elements:  # one value for both
                    a_block[jj, ii] = value
            a_block += antisymmetric[np.ix_(dofs, dofs)]
            return local + 1j * wk[:, None, None] * a_block

        fixed = [
            (orders or {}).get((i, j), (orders or {}).get((j, i)))
            for i, j in elements
            if (orders or {}).get((i, j), (orders or {}).get((j, i)))
        ]
        fixed_count = max(fixed) if fixed else None
        started = time.perf_counter()
        name = "-".join(labels[d] for d in dofs)

        def identify(
            tol: float,
            aim: float | None,
            dofs=dofs,
            elements=elements,
            used=used,
            motion=motion,
            fixed_count=fixed_count,
            name=name,
            min_damping=vector.MIN_DAMPING,
            poles=None,
        ):
            """The block's data weighted for motion target ``tol`` and its fit, its poles
            damped at least ``min_damping`` of critical (or at ``poles``)."""
            data = vector.block_data(
                dofs,
                elements,
                omega,
                a_data,
                b_data,
                used,
                added_mass_inf=None if a_inf is None else estimated_inf(inf, inp.estimated_inf),
                motion_weight=None if sensitivity is None else sensitivity.coupling_weight,
                motion_tol=tol,
                prior=prior,
                antisymmetric_inf=inp.reciprocity.added_mass_inf,
                time=measured.time,
                kernel=measured.kernel,
                min_damping=min_damping,
            )
            try:
                found = order_search.identify_block(
                    data,
                    r2=r2,
                    r2_coupling=r2_coupling,
                    max_count=max_order,
                    motion=motion if k_data is not None else None,
                    motion_aim=aim,
                    fixed_count=fixed_count,
                    passive=passive,
                    r2_kernel=options.r2_kernel,
                    labels=labels,
                    unjudged=inp.attrs.get("motions_unjudged"),
                    poles=poles,
                )
            except FitError as exc:
                raise FitError(f"{name}: {exc}") from None
            return data, *found

        if searched is not None and dofs in searched:  # this block's search, made before
            data, fitted, score, block_notes, floor = searched[dofs]
            block_notes = list(block_notes)
        else:
            data, fitted, score, block_notes, floor = search(dofs, elements, fixed_count, identify)
            if searched is not None:
                searched[dofs] = (data, fitted, score, list(block_notes), floor)
        refined = None
        if options.refine_motions is not False and passive and motion_aim is not None:
            if not score.meets(motion_aim):  # the motions themselves fitted
                counts = (fitted.poles.count, fixed_count or max_order)
                refined = refined_block(data, fitted, score, counts, refined_motions(), options)
            if refined is not None:
                fitted, score, block_notes = refined[0], refined[1], refined[2](block_notes, labels)
        made = None if searched is None or refined is not None else searched.get(("made", dofs))
        if made is not None:  # this block as the last fit made it: its metrics kept
            block, inf_values, done_entry, block_notes, failed = made
            for (i, j), value in inf_values:
                inf[i, j] = value
            blocks.append(block)
            crossings.append(None)
            done.append(done_entry)
            notes += [f"{name}: {x}" for x in block_notes]
            tail_failures += failed
            continue
        any_refined |= refined is not None
        a, b, c = fitted.realization()
        inf_values = []
        for (i, j), value in fitted.pair_values(fitted.added_mass_inf).items():
            inf_values.append(((i, j), value))  # a pair fitted as given: each its own
            if i <= j and (j, i) not in fitted.elements:
                inf_values.append(((j, i), value))
        for (i, j), value in inf_values:
            inf[i, j] = value
        note = "; ".join(block_notes)
        block = MemoryBlock(dofs, a, b, c, "vf", {}, note)
        metrics = {}
        before = None  # the R² of the fit before passivity (the order search's, or again)
        if passive and refined is None:  # a refined block's R² is traded for the motions
            plain = data.plain_fits.get(fitted.poles.count, (None, None))
            if plain[0] is None or plain[0].poles is not fitted.poles:
                plain = (None, score_before(data, fitted.poles, r2, r2_coupling))
            before = plain[1]
        modal = modal_form(block.a)  # shared by its pairs' metrics
        ordered = [(i, j) for i, j in elements if i <= j]
        ordered += [(i, j) for j, i in ordered if (j, i) in inp.as_given]
        for i, j in ordered:
            use = used[:, elements.index((min(i, j), max(i, j)))]
            view = replace(block.element(i, j), metrics={})
            as_given = (min(i, j), max(i, j)) in inp.as_given
            # K(t) of a diagonal term at the data's full time resolution (the target, issue
            # 31) stands for that on the default grid: that one only off the diagonal
            coarse = i != j
            m = coupling_metrics(
                view,
                omega[use],
                a_data[use, i, j],
                b_data[use, i, j],
                inf[i, j],
                time=measured.time if coarse else None,
                kernel=measured.kernel[:, i, j] if coarse else None,
                floor=pair_floor(a_data[use], b_data[use], i, j) if as_given else (0.0, 0.0),
                modal=modal,
            )
            if i == j:  # r2_kernel, then kernel_zero(_data) after n_frequencies, as before
                m.update(fine_kernel_metrics(fine_kernel[i], view, fine_time, modal))
            m["n_excluded_frequencies"] = int((~use).sum())
            m["common_poles"] = fitted.poles.count
            if as_given:
                m["as_given"] = True
            if before is not None:
                m["r2_added_mass_before"], m["r2_damping_before"] = before.r2[(i, j)]
            metrics[(i, j)] = m
        elapsed = time.perf_counter() - started
        for m in metrics.values():
            m["elapsed_s"] = elapsed
        blocks.append(replace(block, metrics=metrics))
        crossings.append(exact_crossings(fitted))
        done.append((name, dofs, elements, fitted.poles, score, floor))
        notes += [f"{name}: {x}" for x in block_notes]
        failed = [
            found.describe(labels[i], float(omega[-1]))
            for i, found in score.beyond.items()
            if not found.ok()
        ]
        tail_failures += failed
        if searched is not None and refined is None:
            searched[("made", dofs)] = (blocks[-1], inf_values, done[-1], block_notes, failed)
    if only_refined and not any_refined:
        return None
    model = RadiationModel(
        tuple(labels),
        (),
        inf + antisymmetric,
        {**attrs, "data_notes": [*attrs.get("data_notes", []), *notes]},
        tuple(blocks),
    )
    extra: dict = {}
    if inp.estimated_inf:  # A∞ of these estimated, the data's row elsewhere (causal_inf)
        extra["added_mass_inf_estimated"] = [labels[d] for d in inp.estimated_inf]
    if passive:
        # one block: the crossings of its last exact test are the model's (no second QZ)
        dynamic = [k for k, b in enumerate(blocks) if b.order]
        known = None
        if len(dynamic) == 1 and crossings[dynamic[0]] is not None:
            known = (blocks[dynamic[0]].dofs, crossings[dynamic[0]])
        report = passivity_test(model, known=known)
        extra["mimo_passive"] = bool(report.passive)
    if sensitivity is not None:
        error, per_dof = sensitivity.model_error(model)
        extra.update(
            motion_error=float(error),
            motion_error_by_dof=[float(x) for x in per_dof],
            motion_target=float(motion_tol),
        )
        if error > motion_tol:  # what the data's causality allows (the failure says it)
            extra["noncausal_dofs"] = noncausal_dofs(inp, model, per_dof > motion_tol)
        if sensitivity.basis is not None:  # what the joined system holds: Tᵀ K T
            extra["coordinate_r2"] = coordinate_r_squared(
                omega, a_data, b_data, model, sensitivity.basis, labels
            )
            extra["coordinate_dofs"] = coordinate_dofs(sensitivity.basis, labels)
    model = replace(model, attrs={**model.attrs, **extra})
    if sensitivity is not None:
        model = with_motion_note(model, motion_tol)
    waived = coordinate_notes(model, r2, r2_coupling)
    if waived:  # the joined system holds Tᵀ K T, not its bodies' DOFs one by one
        notes_now = [*model.attrs.get("data_notes", []), *waived]
        model = replace(model, attrs={**model.attrs, "data_notes": notes_now})
    failures = fit_failures(model, **failure_targets(options, sensitivity))
    failures += range_cut_failures(model, inp, options.r2)
    failures += tail_failures  # the model's damping beyond the data (fit/tail.py)
    return replace(model, attrs={**model.attrs, "failures": failures})


def unmodelled_as_model(k_data, omega, negligible, added_mass_inf):
    """The data's K(jω) + jω A(ω) at ``omega`` (ω, n, n) with the ``negligible`` pairs
    (i ≤ j) as a model has them: K = 0, the added mass its A∞ (``added_mass_inf``)."""
    out = k_data.copy()
    for i, j in negligible:
        out[:, i, j] = 1j * omega * added_mass_inf[i, j]
        out[:, j, i] = 1j * omega * added_mass_inf[j, i]
    return out


def score_before(data, poles, r2: float, r2_coupling: float):
    """The score (R²) of the block's fit at ``poles`` before passivity."""
    plain_block = vector.fit_residues_at(data, poles)
    return order_search.score_block(plain_block, data, r2=r2, r2_coupling=r2_coupling)


#: A block whose DOFs' diagonal A and B are within SHARED_POLES (the largest difference
#: over the frequencies, relative to the larger of the two's largest value) of those of a
#: block fitted before it, with as many DOFs and pairs, takes that block's common poles and
#: fits only its residues — an axisymmetric body's sway–roll block and its surge–pitch
#: block, whose data differ by the panels' asymmetry (HAMS cylinders 0.6 %, the WAMIT
#: drift sphere 3.4 %, the monopile 0.04 %) — when that leaves it as near its targets
#: as the twin (:func:`shares_well`); else its own order search.
SHARED_POLES = 0.05


def mirror_block(done, dofs, elements, a_data, b_data):
    """(name, poles, score, pole floor, difference) of the block of ``done`` whose
    diagonal data match those of ``dofs`` DOF for DOF within :data:`SHARED_POLES` (the
    largest relative difference), or None."""
    for name, their_dofs, their_elements, poles, score, floor in done:
        if len(their_dofs) != len(dofs) or len(their_elements) != len(elements):
            continue
        left, worst = list(their_dofs), 0.0
        for d in dofs:
            found = [(diagonal_difference(a_data, b_data, d, t), t) for t in left]
            difference, match = min(found)
            if not difference <= SHARED_POLES:
                break
            left.remove(match)
            worst = max(worst, difference)
        else:
            return name, poles, score, floor, worst
    return None


def diagonal_difference(a_data, b_data, d: int, t: int) -> float:
    """The largest difference between A (and B) of DOF ``d`` and of DOF ``t`` over the
    frequencies, relative to the larger of their largest values (NaN when not finite)."""
    out = 0.0
    for values in (a_data, b_data):
        one, two = values[:, d, d], values[:, t, t]
        scale = max(np.abs(one).max(), np.abs(two).max())
        out = max(out, float(np.abs(one - two).max() / scale) if scale > 0 else 0.0)
    return out


def shares_well(score, twin_score, r2: float, motion_aim) -> bool:
    """A block at its twin's poles is kept when it is as near its targets as the twin is
    to its own (within :data:`~cummins.radiation.fit.order_search.NEAR`), and passive when
    the twin is."""
    if twin_score.passive and not score.passive:
        return False
    if score.meets(motion_aim):
        return True
    near = order_search.distance(score, r2, motion_aim)
    return near <= order_search.distance(twin_score, r2, motion_aim) + order_search.NEAR
