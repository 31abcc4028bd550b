"""The MIMO stage of the per-coupling identification: the assembled model made passive
(:func:`make_passive`), the model-level rounds against the motion error
(:func:`motion_rounds`), and what makes a fit a failure (:func:`fit_failures`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cummins.errors import FitError
from cummins.radiation.fit.data import FitData
from cummins.radiation.fit.metrics import coupling_metrics
from cummins.radiation.fit.motion import MotionSensitivity
from cummins.radiation.fit.options import (
    MOTION_AIM,
    MOTION_FAILURE,
    MOTION_TOL,
    UNJUDGED_R2,
    FitOptions,
)
from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.radiation.passivity import augment_for_passivity, enforce_passivity, passivity_test

#: Smallest R² margin above the target used to weigh a coupling in passivity enforcement.
PASSIVITY_SLACK_FLOOR = 1e-3
#: Scale of the motion term of the per-coupling criterion (in units of R²)
#: (:class:`cummins.radiation.fit.couplings.Criterion`), and of the motion rows of the passivity
#: step.
MOTION_SLACK = 0.01


def failure_targets(options: FitOptions, sensitivity) -> dict:
    """The keyword arguments of :func:`cummins.radiation.fit.mimo.fit_failures` for ``options``."""
    return {
        "r2": options.r2,
        "r2_coupling": options.coupling_target,
        "passivity": options.passivity,
        "motion_tol": options.motion_tol if sensitivity is not None else None,
        "r2_kernel": options.r2_kernel,
    }


def fit_failures(
    model: RadiationModel,
    *,
    r2: float = 0.99,
    r2_coupling: float = 0.97,
    passivity: str = "mimo",
    motion_tol: float | None = None,
    r2_kernel: float | None = None,
) -> list[str]:
    """What makes a fit a failure, one message each (empty: success).

    * MIMO passivity asked for and not reached;
    * a coupling that a later step (MIMO passivity) took below its R² target, or lowered
      by more than 0.05 when it was already below (``r2_added_mass_before`` …);
    * a relative motion error (``attrs["motion_error"]``) above
      :data:`MOTION_FAILURE` × ``motion_tol`` (issue 16: "≤ 1 %, never above 2 %"; between
      the two, a data note says so);
    * a diagonal term whose K(t) is further from the data's than ``r2_kernel`` (R²):
      the model does not decay beyond the data as the data's damping tail (issue 31);
    * when no motions judge the fit (``motion_tol`` None; why: ``attrs["motions_unjudged"]``),
      a diagonal term whose R² of A or B is below :data:`UNJUDGED_R2`.

    Else a target that the identification itself did not reach is a note of the
    coupling, not a failure: the motions decide whether it matters (see the note).

    A fit for bodies joined by joints (``attrs["coordinate_r2"]``) is judged by what the
    joined system holds of it, Tᵀ K T: a pair of the bodies' DOFs that passivity took
    below its target is not a failure when every free coordinate that moves either DOF
    meets ``r2`` in A and B (:func:`coordinates_meet`): the DOFs move only with their
    coordinates (a flap's surge and pitch about its hinge); :func:`coordinate_notes`
    says so.
    """
    out = []
    if passivity == "mimo" and not model.attrs.get("mimo_passive", True):
        out.append("the MIMO model is not passive")
    for k in model.modelled:
        if k.influenced > k.radiating:
            continue
        i, j = model.dofs[k.influenced], model.dofs[k.radiating]
        if not coordinates_meet(model, {i, j}, r2):
            out += passivity_losses(model, k, r2, r2_coupling)
        kernel = k.metrics.get("r2_kernel")
        if r2_kernel is not None and i == j and kernel is not None and kernel < r2_kernel:
            out.append(kernel_failure(i, k.metrics, r2_kernel))
        unjudged = model.attrs.get("motions_unjudged")
        if motion_tol is None and unjudged and i == j:
            named = " ".join(out)
            for what, key in (("A", "r2_added_mass"), ("B", "r2_damping")):
                value = k.metrics.get(key)
                if value is None or value >= UNJUDGED_R2 or f"{i}: " in named:
                    continue
                out.append(
                    f"{i}: R² of {what} {value:.4f} < {UNJUDGED_R2:g}, and no motions judge "
                    f"whether that matters ({unjudged})"
                )
    error = model.attrs.get("motion_error")
    if motion_tol is not None and error is not None and error > MOTION_FAILURE * motion_tol:
        out.append(
            f"motion error {100 * error:.2f} % of the peak motion (target "
            f"{100 * motion_tol:.2g} %, never above {100 * MOTION_FAILURE * motion_tol:.2g} %;"
            f" {_floor_clause(model)})"
        )
    return out


def passivity_losses(model: RadiationModel, k: CouplingModel, r2: float, r2_coupling: float):
    """The failures of coupling ``k`` that a later step (passivity) took below its R²
    target, or lowered by more than 0.05 when it was already below."""
    target = r2 if k.influenced == k.radiating else r2_coupling
    i, j = model.dofs[k.influenced], model.dofs[k.radiating]
    name = i if i == j else f"{i}-{j}"
    out = []
    for what, key in (("A", "r2_added_mass"), ("B", "r2_damping")):
        before = k.metrics.get(f"{key}_before")
        after = k.metrics.get(key)
        if before is None or after is None:
            continue
        if after < min(target, before) - 1e-3 and (before >= target or after < before - 0.05):
            step = "passivity" if k.method == "vf" else "MIMO passivity"
            out.append(
                f"{name}: {step} took the R² of {what} from {before:.4f} to "
                f"{after:.4f} (target {target})"
            )
    return out


def coordinate_notes(model: RadiationModel, r2: float, r2_coupling: float) -> list[str]:
    """The passivity losses of the bodies' DOFs that :func:`fit_failures` does not count,
    their coordinates meeting ``r2`` (a joined fit), one note each naming them."""
    out = []
    for k in model.modelled:
        i, j = model.dofs[k.influenced], model.dofs[k.radiating]
        if k.influenced > k.radiating or not coordinates_meet(model, {i, j}, r2):
            continue
        out += [
            f"{loss}: not a failure, the joined system moves these DOFs only through its "
            f"coordinates ({coordinate_note(model, {i, j})})"
            for loss in passivity_losses(model, k, r2, r2_coupling)
        ]
    return out


def judging_coordinates(model: RadiationModel, dofs) -> list[str]:
    """The free coordinates of the model's joined system that move any of ``dofs``
    (``attrs["coordinate_dofs"]``); empty for a fit of free bodies."""
    moving = model.attrs.get("coordinate_dofs") or {}
    return [q for q, moved in moving.items() if set(moved) & set(dofs)]


def coordinates_meet(model: RadiationModel, dofs, r2: float) -> bool:
    """Whether every free coordinate that moves any of ``dofs`` (:func:`judging_coordinates`)
    holds the R² of A and of B (``attrs["coordinate_r2"]``,
    :func:`~cummins.radiation.fit.motion.coordinate_r_squared`) at ``r2``; False for a
    fit of free bodies."""
    values = model.attrs.get("coordinate_r2") or {}
    judging = judging_coordinates(model, dofs)
    return bool(judging) and all(min(values[q]) >= r2 for q in judging)


def coordinate_note(model: RadiationModel, dofs) -> str:
    """The R² of A and B of each free coordinate that moves any of ``dofs``, and the DOFs
    it moves besides its own."""
    values = model.attrs.get("coordinate_r2") or {}
    moving = model.attrs.get("coordinate_dofs") or {}
    parts = []
    for q in judging_coordinates(model, dofs):
        others = list(moving[q])[1:]
        with_it = f" (moving {', '.join(others)} with it)" if others else ""
        a, b = values[q]
        parts.append(f"{q}{with_it}: R² of A {a:.4f}, of B {b:.4f}")
    return "; ".join(parts)


def kernel_failure(label: str, metrics: dict, r2_kernel: float) -> str:
    """The failure of a diagonal term whose R² of K(t) misses ``r2_kernel``, with K(0) of
    the model and of the data: K(0) = (2/π) ∫₀^∞ B dω, so a model that does not decay
    beyond the data as the data's damping tail shows there."""
    text = f"{label}: R² of K(t) {metrics['r2_kernel']:.3f} < {r2_kernel:g}"
    zero, data = metrics.get("kernel_zero"), metrics.get("kernel_zero_data")
    if zero is not None and data is not None:
        text += f" (K(0) {zero:.3g} against the data's {data:.3g}, with its damping tail)"
    return text


def make_passive(
    model: RadiationModel,
    measured: FitData,
    *,
    r2: float = 0.99,
    r2_coupling: float = 0.97,
    augment: bool = True,
    sensitivity: MotionSensitivity | None = None,
    motion_tol: float = MOTION_TOL,
    last_resort: bool = False,
) -> RadiationModel:
    """The model made passive as a MIMO system
    (:func:`cummins.radiation.passivity.enforce_passivity`),
    with the metrics of every changed coupling recomputed and the change noted.

    Each coupling's R² loss weighs 1/(R² − target) (``r2`` on the diagonal,
    ``r2_coupling`` off it; the couplings' metrics must be against ``measured``): the
    couplings with room above their target take the change. When residue changes alone
    would push a diagonal term below its target, the enforcement is tried again with a
    pole added where the model violates (:func:`cummins.radiation.passivity.augment_for_passivity`),
    and the better result is kept (unless ``augment`` is false: the order then stays). A
    model that cannot be made passive is returned as it
    is, with ``mimo_passive`` false and the reason in ``data_notes``.
    """

    def target(k: CouplingModel) -> float:
        return r2 if k.influenced == k.radiating else r2_coupling

    def importance(k: CouplingModel) -> float:
        return 1.0 / max(_score(k) - target(k), PASSIVITY_SLACK_FLOOR)

    motion_scale = [PASSIVITY_MOTION_WEIGHT]

    def motion_weight(k: CouplingModel):
        if sensitivity is None:
            return None
        i, j = k.influenced, k.radiating
        weight = motion_scale[0] * np.sqrt(MOTION_SLACK) / motion_tol
        return weight * sensitivity.coupling_weight(i, j)

    def attempt(start: RadiationModel):
        result = enforce_passivity(
            start,
            omega=measured.omega,
            added_mass=measured.added_mass,
            damping=measured.damping,
            time=measured.time,
            kernel=measured.kernel,
            importance=importance,
            motion_weight=motion_weight if sensitivity is not None else None,
        )
        couplings = [
            refreshed_coupling(old, new, measured, model.added_mass_inf, "MIMO passivity")
            for old, new in zip(start.couplings, result.model.couplings, strict=True)
        ]
        shortfall = max(
            (
                min(target(k), _score(old)) - _score(k)
                for old, k in zip(start.couplings, couplings, strict=True)
            ),
            default=0.0,
        )
        return result, tuple(couplings), shortfall

    tried = []
    failures = []
    try:
        tried.append(attempt(model))
    except FitError as exc:
        failures.append(str(exc))
    first = tried[0] if tried else None
    needs_more = first is None or (
        first[0].iterations
        and any(
            _score(k) < min(target(k), _score(old)) - TIE
            for old, k in zip(model.couplings, first[1], strict=True)
            if k.influenced == k.radiating
        )
    )
    if augment and needs_more:
        report = first[0].before if first is not None else passivity_test(model)
        try:
            tried.append(attempt(augment_for_passivity(model, report)))
        except FitError as exc:
            failures.append(str(exc))
    best = min((_shortfall(model.couplings, x[1], target, True) for x in tried), default=np.inf)
    if best > SHORTFALL_TOLERANCE:  # no attempt, or every one costs a diagonal its target
        # the data may be (nearly) rank-deficient — DOFs coupled kinematically, e.g. surge
        # and pitch of a sphere about a point off its centre, B15² ≈ B11 B55 — so that the
        # small misfit of separately fitted couplings breaks passivity beyond what the
        # residues can repair without cost: shrink the off-diagonal models a little
        for factor in COUPLING_SHRINK:
            try:
                found = attempt(_shrunk_couplings(model, factor))
            except FitError as exc:
                failures.append(str(exc))
                continue
            note = f"coupling models scaled by {factor:g} for MIMO passivity"
            couplings = tuple(
                replace(k, note="; ".join(filter(None, [k.note, note])))
                if k.influenced != k.radiating
                else k
                for k in found[1]
            )
            shortfall = _shortfall(model.couplings, couplings, target)
            tried.append((found[0], couplings, shortfall))
            if shortfall <= SHORTFALL_TOLERANCE:
                break
    best = min((_shortfall(model.couplings, x[1], target, True) for x in tried), default=np.inf)
    if best > SHORTFALL_TOLERANCE and sensitivity is not None and last_resort:
        motion_scale[0] = PASSIVITY_MOTION_WEIGHT_LAST
        try:
            tried.append(attempt(model))
        except FitError as exc:
            failures.append(str(exc))
    if not tried:
        notes = [
            *model.attrs.get("data_notes", []),
            f"MIMO passivity not enforced: {failures[0]}",
        ]
        return replace(model, attrs={**model.attrs, "mimo_passive": False, "data_notes": notes})

    # deterministic choice: the smallest shortfall, ties to the first (fewer states)
    def preference(x):
        """Every coupling within its target first, then the smallest motion error (with a
        sensitivity), then the smallest total R² loss below the targets (the sum over
        the couplings: a change spread over all of them is not better than one); ties to
        the earlier attempt."""
        diagonal_ok = x[2] <= SHORTFALL_TOLERANCE
        motion = 0.0
        if sensitivity is not None:
            motion = sensitivity.model_error(replace(model, couplings=x[1]))[0]
        losses = [
            max(0.0, min(target(k), _score(old)) - _score(k) - TIE)
            for old, k in zip(model.couplings, x[1], strict=True)
        ]
        return (not diagonal_ok, round(motion, 5), round(sum(losses), 6))

    result, couplings, _ = min(tried, key=preference)
    attrs = {
        **model.attrs,
        "mimo_passive": result.after.passive,
        "passivity_iterations": result.iterations,
        "passivity_worst_before": result.before.min_eigenvalue,
        "passivity_worst_omega_before": result.before.worst_omega,
    }
    return replace(model, couplings=couplings, attrs=attrs)


#: Rounds of the model-level order search against the motion error.
MOTION_ROUNDS = 4


def motion_rounds(
    model,
    models,
    budgets,
    sensitivity,
    measured,
    motion_tol,
    max_order,
    fit_one,
    assemble,
    fixed_pairs=frozenset(),
):
    """Refit the couplings that carry the motion error of the assembled (passive) model
    until it meets ``motion_tol`` (:meth:`MotionSensitivity.model_error`): each round,
    the couplings whose share max W|δK| is at least half of the largest share among the
    DOFs that miss get half their budget and start one order above their current one.
    A round that does not lower the error is undone, and its couplings are not chosen
    again. The error reached goes to
    ``attrs["motion_error"]``."""
    error, per_dof = sensitivity.model_error(model)
    aim = MOTION_AIM * motion_tol
    no_gain: set = set()  # couplings whose refit did not lower the error
    for _ in range(MOTION_ROUNDS):
        if error <= aim:
            break
        shares = _motion_shares(model, sensitivity, measured, per_dof, aim)
        if not shares:
            break
        top = max(shares.values())
        chosen = [
            p
            for p, e in sorted(shares.items())
            if e >= 0.5 * top
            and models[p].order < max_order
            and p not in fixed_pairs
            and p not in no_gain
        ]
        if not chosen:
            break
        saved = {p: (models[p], budgets[p]) for p in chosen}
        for p in chosen:
            budgets[p] = min(budgets[p], shares[p]) / 2.0
            models[p] = fit_one(*p, min_order=models[p].order + 1)
        candidate = assemble()
        new_error, new_per_dof = sensitivity.model_error(candidate)
        if new_error < error - TIE:
            model, error, per_dof = candidate, new_error, new_per_dof
        else:
            for p, (old, budget) in saved.items():
                models[p], budgets[p] = old, budget
            no_gain.update(chosen)
    return replace(
        model,
        attrs={
            **model.attrs,
            "motion_error": float(error),
            "motion_error_by_dof": [float(x) for x in per_dof],
            "motion_target": float(motion_tol),
        },
    )


def _motion_shares(model, sensitivity, measured, per_dof, motion_tol) -> dict:
    """max_ω W_ij |δK_ij| of each fitted coupling (i ≤ j) touching a DOF that misses."""
    w = measured.omega
    k = model.response(w)
    k_data = measured.damping + 1j * w[:, None, None] * (
        measured.added_mass - np.asarray(model.added_mass_inf)[None]
    )
    weight = sensitivity.on(w)
    missing = {d for d, e in enumerate(per_dof) if e > motion_tol}
    out = {}
    for c in model.couplings:
        i, j = c.influenced, c.radiating
        if i > j or not ({i, j} & missing):
            continue
        ww = weight[:, i, i] if i == j else weight[:, i, j] + weight[:, j, i]
        out[(i, j)] = float(np.max(ww * np.abs(k[:, i, j] - k_data[:, i, j])))
    return out


#: Factors tried on the off-diagonal models when the MIMO passivity step finds no
#: solution (:func:`make_passive`), largest first.
#: Empty: measured, the shrunk models never kept a case passive that the other attempts
#: did not (the sphere stays at λ_min −0.9 %), and they won the choice on the supply
#: vessel with 9 couplings degraded; the mechanism is kept for experiments.
COUPLING_SHRINK: tuple[float, ...] = ()


#: Differences of R² or of the motion error below this are ties: rounding (another BLAS,
#: another thread count) must not decide a branch of the search (issue 16, target 5).
TIE = 1e-6
#: A passivity step within this much of every diagonal's R² target is accepted (as by
#: fit_failures): below it the next attempts are tried.
SHORTFALL_TOLERANCE = 1e-3
#: Weight of the motion rows in the MIMO passivity step, against the couplings' R² losses.
PASSIVITY_MOTION_WEIGHT = 1.0
#: ... and the lighter weight of the last attempt, when every other one costs a diagonal
#: its target (measured: 0.1 keeps the tanker's roll at R² 0.999 with heave–pitch fixed
#: at 3 states, where 1.0 takes it to 0.96; as the default it loses the RAOs 0.5 %).
PASSIVITY_MOTION_WEIGHT_LAST = 0.1


def _shortfall(before, after, target, diagonal: bool = False) -> float:
    """The largest loss below its target of a coupling (R², ≤ 0: none); of a diagonal
    term only with ``diagonal``."""
    return max(
        (
            min(target(k), _score(old)) - _score(k)
            for old, k in zip(before, after, strict=True)
            if not diagonal or k.influenced == k.radiating
        ),
        default=0.0,
    )


def _shrunk_couplings(model: RadiationModel, factor: float) -> RadiationModel:
    couplings = tuple(
        k if k.influenced == k.radiating else replace(k, c=np.asarray(k.c) * factor)
        for k in model.couplings
    )
    return replace(model, couplings=couplings)


def _score(k: CouplingModel) -> float:
    return min(k.metrics["r2_added_mass"], k.metrics["r2_damping"])


def refreshed_coupling(
    old: CouplingModel, new: CouplingModel, measured: FitData, added_mass_inf, why: str
) -> CouplingModel:
    """``new`` (a changed ``old``) with its metrics recomputed against the data and the
    change of R² noted (``why``: what changed it); ``new`` itself if c is unchanged."""
    if old.a.shape == new.a.shape and np.array_equal(old.c, new.c) and np.array_equal(old.a, new.a):
        return new
    i, j = new.influenced, new.radiating
    metrics = coupling_metrics(
        new,
        measured.omega,
        measured.added_mass[:, i, j],
        measured.damping[:, i, j],
        float(np.asarray(added_mass_inf)[i, j]),
        time=measured.time,
        kernel=measured.kernel[:, i, j],
    )
    for key in ("r2_added_mass", "r2_damping"):
        if f"{key}_before" not in old.metrics and key in old.metrics:
            metrics[f"{key}_before"] = old.metrics[key]
    for key, value in old.metrics.items():
        metrics.setdefault(key, value)
    before = old.metrics.get("r2_added_mass"), old.metrics.get("r2_damping")
    change = f"{why}: R² of A {metrics['r2_added_mass']:.4f}, of B {metrics['r2_damping']:.4f}"
    if None not in before:
        change = (
            f"{why}: R² of A {before[0]:.4f} → {metrics['r2_added_mass']:.4f}, "
            f"of B {before[1]:.4f} → {metrics['r2_damping']:.4f}"
        )
    return replace(new, metrics=metrics, note="; ".join(filter(None, [new.note, change])))


def _floor_clause(model: RadiationModel) -> str:
    """What limits the motion error: the set-up (a statically unstable system,
    ``attrs["statically_unstable"]``), the data (their reciprocal part alone is as far
    from their motions, ``attrs["motion_error_floor"]``; a DOF whose added mass no causal
    model follows, ``attrs["noncausal_dofs"]``, which may limit it: the share it costs is
    not measured — the data with that added mass replaced by the transform were further
    from their own motions than the model on WEC-Sim's RM3 (23 % against 0.40 %), so that
    substitution is no floor) or the fit."""
    floor, error = model.attrs.get("motion_error_floor"), model.attrs.get("motion_error")
    unstable = list(model.attrs.get("statically_unstable", []) or [])
    if unstable:  # no steady state: what the motions are compared with is no system's
        return (
            "the set-up limits it: the system is statically unstable in "
            f"{', '.join(unstable)}, a negative eigenvalue of its restoring (hydrostatics, "
            "weight, moorings), so its motion RAOs are no steady state to judge a model "
            "by; hold the body (a joint, a mooring, --dof) or check its centre of gravity"
        )
    noncausal = list(model.attrs.get("noncausal_dofs", []) or [])
    if noncausal:
        estimated = model.attrs.get("added_mass_inf_estimated") or []
        row = model.attrs.get("added_mass_inf_method") == "data"
        source = "the data's ω = ∞ row" if row else "the fitted A∞"
        if row and estimated:
            source = f"the model's A∞ (estimated for {', '.join(estimated)}, else the data's row)"

        return (
            f"the data may limit it: the added mass of {', '.join(noncausal)} is that far "
            f"from the Kramers–Kronig transform of its damping with {source} (cummins "
            "check: retardation), which no causal model follows (how much of the motion "
            "error that accounts for is not measured)"
            + (
                "; added_mass_inf='fit' (--added-mass-inf fit) lets the model choose A∞"
                if row and not estimated
                else ""
            )
        )
    if floor is None or error is None:
        return "the data's own consistency may limit it"
    reciprocal = model.attrs.get("reciprocal_motion_error_floor")
    if model.attrs.get("couplings_as_given") and reciprocal is not None:
        return (
            "the data limit it: they are not reciprocal (their reciprocal part alone is "
            f"{100 * reciprocal:.3g} % off their own motions), fitted as given, and a passive "
            "model (K + Kᴴ ⪰ 0) follows a non-reciprocal part only as far as the damping "
            "allows: its antisymmetric damping integrates to zero over frequency, and "
            "none is passive where the damping matrix is singular (cummins check: "
            "reciprocity)"
        )
    if floor >= 0.5 * error:
        return (
            f"the data limit it: their reciprocal part alone is {100 * floor:.2f} % off "
            "their own motions (A_ij ≠ A_ji or B_ij ≠ B_ji: cummins check)"
        )
    return (
        f"the data's reciprocal part alone is within {100 * floor:.2f} %; the rest is the "
        "model's: its order, or a passivity the data lack (cummins check)"
    )


def with_motion_note(model: RadiationModel, motion_tol: float) -> RadiationModel:
    """The model with a data note when its motion error (``attrs["motion_error"]``) is
    above the target ``motion_tol``."""
    error = model.attrs.get("motion_error")
    if error is None or error <= motion_tol:
        return model
    note = (
        f"motion error {100 * error:.2f} % of the peak motion, above the target "
        f"{100 * motion_tol:.2g} % ({_floor_clause(model)})"
    )
    notes = [*model.attrs.get("data_notes", []), note]
    return replace(model, attrs={**model.attrs, "data_notes": notes})
