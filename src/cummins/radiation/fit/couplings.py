"""The per-coupling identification (``method="fd"``, ``"realization"``, ``"prony"``):
each significant coupling K_ij gets its own SISO model at the smallest order whose R² of
A and of B reach the target and whose share of the motion error is within its budget
(:func:`fit_coupling`); the assembled MIMO model is made passive and refined against the
motion error (:mod:`cummins.radiation.fit.mimo`). :func:`fit_per_coupling` runs the whole stage on
the prepared data (:func:`cummins.radiation.fit.data.prepare_fit`).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from cummins.errors import FitError
from cummins.radiation.fit.data import (
    FitInput,
    prepare_fit,
    range_cut_failures,
    response_weights,
)
from cummins.radiation.fit.frequency import FrequencyFit, fit_frequency_domain, pruned_poles
from cummins.radiation.fit.metrics import coupling_metrics
from cummins.radiation.fit.mimo import (
    MOTION_SLACK,
    TIE,
    failure_targets,
    fit_failures,
    make_passive,
    motion_rounds,
    with_motion_note,
)
from cummins.radiation.fit.options import FitOptions
from cummins.radiation.fit.realization import modal_realization
from cummins.radiation.model import CouplingModel, RadiationModel, symmetric_couplings

#: Share of the motion error each coupling may take at first (× motion_tol): the rounds
#: of the order search tighten it where the model misses.
INITIAL_BUDGET = 1.2


def fit_per_coupling(
    inp: FitInput, options: FitOptions, say: Callable[[str], None] = lambda message: None
) -> RadiationModel:
    """The per-coupling identification of the prepared data (module docstring): every
    significant coupling fitted, the MIMO model assembled and (``passivity="mimo"``) made
    passive, with motion weights the rounds against the motion error; when the
    motion-weighted model cannot be made passive, the R²-only identification if that
    one is passive. ``attrs["failures"]`` lists what misses a target."""
    labels, keep_dof, sensitivity = inp.labels, inp.keep_dof, inp.sensitivity
    measured, a_inf = inp.measured, inp.a_inf.copy()
    ogilvie, ogilvie_spread = inp.ogilvie, inp.ogilvie_spread
    method, motion_tol, orders = options.method, options.motion_tol, options.orders
    t, kernel = measured.time, measured.kernel
    a_raw, b_raw, w_all = inp.added_mass, inp.damping, inp.data.omega.values
    weights = response_weights(inp.data) if inp.weighting == "response" else None
    budgets = dict.fromkeys(inp.pairs, INITIAL_BUDGET * motion_tol)

    def fit_one(i: int, j: int, min_order: int = 2) -> CouplingModel:
        name = labels[i] if i == j else f"{labels[i]}-{labels[j]}"
        say(f"{name}")
        use = keep_dof[:, i] & keep_dof[:, j]
        w = w_all[use]
        a_ij, b_ij = a_raw[use, i, j], b_raw[use, i, j]
        fixed = (orders or {}).get((i, j), (orders or {}).get((j, i)))
        started = time.perf_counter()
        coupling, a_inf_ij = fit_coupling(
            method,
            w,
            a_ij,
            b_ij,
            t,
            kernel[:, i, j],
            a_inf=None if inp.a_inf_mode == "fit" else 0.5 * (a_inf[i, j] + a_inf[j, i]),
            guess=0.5 * (ogilvie[i, j] + ogilvie[j, i]),
            spread=0.5 * (ogilvie_spread[i, j] + ogilvie_spread[j, i]),
            passive=options.passivity != "none" and i == j,
            crit=Criterion(
                options.r2 if i == j else options.coupling_target,
                w,
                a_ij,
                b_ij,
                None if sensitivity is None else sensitivity.coupling_weight(i, j)[use],
                budgets[(i, j)] if sensitivity is not None else None,
            ),
            max_order=options.max_order,
            fixed=fixed,
            name=name,
            weight=None if weights is None else np.sqrt(weights[use, i] * weights[use, j]),
            min_order=min_order,
        )
        a_inf[i, j] = a_inf[j, i] = a_inf_ij
        model = CouplingModel(i, j, coupling.a, coupling.b, coupling.c, method, {}, coupling.note)
        metrics = coupling_metrics(model, w, a_ij, b_ij, a_inf_ij, time=t, kernel=kernel[:, i, j])
        metrics.update(coupling.extra)
        metrics["n_excluded_frequencies"] = int((~use).sum())
        metrics["elapsed_s"] = time.perf_counter() - started
        return replace(model, metrics=metrics)

    models = {(i, j): fit_one(i, j) for i, j in inp.pairs}

    def assemble(last_resort: bool = False) -> RadiationModel:
        out = RadiationModel(
            tuple(labels), symmetric_couplings(list(models.values())), a_inf.copy(), inp.attrs
        )
        if options.passivity == "mimo":
            say("MIMO passivity")
            out = make_passive(
                out,
                measured,
                r2=options.r2,
                r2_coupling=options.coupling_target,
                sensitivity=sensitivity,
                motion_tol=motion_tol,
                last_resort=last_resort,
            )
        return out

    target_args = failure_targets(options, sensitivity)
    model = assemble()
    if sensitivity is not None:
        fixed_pairs = {tuple(sorted(p)) for p in (orders or {})}
        model = motion_rounds(
            model,
            models,
            budgets,
            sensitivity,
            measured,
            motion_tol,
            options.max_order,
            fit_one,
            assemble,
            fixed_pairs,
        )
    if options.passivity == "mimo" and sensitivity is not None:
        degraded = [f for f in fit_failures(model, **target_args) if "MIMO passivity took" in f]
        if degraded:  # the last resort: lighter motion rows in the passivity step
            again = assemble(last_resort=True)
            error, per_dof = sensitivity.model_error(again)
            again = replace(
                again,
                attrs={
                    **model.attrs,
                    **again.attrs,
                    "motion_error": float(error),
                    "motion_error_by_dof": [float(x) for x in per_dof],
                },
            )
            if not [f for f in fit_failures(again, **target_args) if "MIMO passivity took" in f]:
                model = again
    if sensitivity is not None:
        model = with_motion_note(model, motion_tol)
    failures = fit_failures(model, **target_args)
    if (
        options.passivity == "mimo"
        and sensitivity is not None
        and not model.attrs.get("mimo_passive")
    ):
        # never a non-passive model when one can be had: the R²-only identification
        # (the sphere: surge–pitch damping rank-1, B15² ≈ B11 B55 to 0.3 %, which the
        # motion-weighted blocks overshoot beyond the residues' reach)
        uniform = options.with_changes(weighting="uniform")
        fallback = fit_per_coupling(prepare_fit(inp.ds, uniform), uniform, say)
        if fallback.attrs.get("mimo_passive"):
            error, per_dof = sensitivity.model_error(fallback)
            note = (
                "the motion-weighted model could not be made passive: fitted by the R² of "
                f"A and B alone (motion error {100 * error:.2f} %)"
            )
            attrs = {
                **fallback.attrs,
                "data_notes": [*fallback.attrs.get("data_notes", []), note],
                "motion_error": float(error),
                "motion_error_by_dof": [float(x) for x in per_dof],
                "motion_target": float(motion_tol),
            }
            model = replace(fallback, attrs=attrs)
            failures = fit_failures(model, **{**target_args, "motion_tol": motion_tol})
    failures += range_cut_failures(model, inp, options.r2)
    return replace(model, attrs={**model.attrs, "failures": failures})


class _Siso:
    """(a, b, c) of a fitted coupling, its note, (frequency domain) the fit itself and
    method-specific metrics (realization: the Hankel singular values)."""

    def __init__(self, a, b, c, note: str = "", fit: FrequencyFit | None = None, extra=None):
        self.a, self.b, self.c, self.note, self.fit = a, b, c, note, fit
        self.extra = dict(extra or {})

    @property
    def order(self) -> int:
        return int(self.a.shape[0])


#: Orders whose linearised fit comes within this much of the R² target get the full
#: (nonlinear, passivity-enforcing) fit: it often lifts a lower order over the target.
SCREENING_MARGIN = 0.05
#: Leading Hankel singular values kept in a realization's metrics.
HANKEL_VALUES_REPORTED = 20


@dataclass(frozen=True)
class Criterion:
    """When a fit of one coupling is good enough: R² of A and of B ≥ ``target`` and, with a
    motion sensitivity W (:mod:`cummins.radiation.fit.motion`), max_ω W |K̂ − K| ≤ ``budget``.

    :meth:`score` folds both into one number that is ≥ ``target`` exactly when both
    hold: min(R², target + SLACK (1 − e/budget)).
    """

    target: float
    omega: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    weight: NDArray[np.float64] | None = None
    budget: float | None = None

    def motion_error(self, k_model: NDArray, a_inf: float) -> float:
        if self.weight is None:
            return 0.0
        k_data = self.damping + 1j * self.omega * (self.added_mass - a_inf)
        return float(np.max(self.weight * np.abs(k_model - k_data)))

    def score(self, r2a: float, r2b: float, k_model: NDArray | None, a_inf: float) -> float:
        r2 = min(r2a, r2b)
        if self.weight is None or self.budget is None or k_model is None:
            return r2
        e = self.motion_error(k_model, a_inf)
        return min(r2, self.target + MOTION_SLACK * (1.0 - e / self.budget))

    def fit_score(self, fit: FrequencyFit) -> float:
        return self.score(
            fit.r2_added_mass,
            fit.r2_damping,
            fit.frequency_response(self.omega),
            fit.added_mass_inf,
        )


def fit_coupling(
    method,
    w,
    a,
    b,
    t,
    kernel,
    *,
    a_inf,
    guess,
    spread,
    passive,
    crit: Criterion,
    max_order,
    fixed,
    name,
    weight=None,
    min_order: int = 2,
) -> tuple[_Siso, float]:
    """Fit one coupling at the fixed order, or the smallest order meeting ``crit``.

    Frequency domain: every order is first fitted by the cheap linearised step alone; the
    full fit runs on the orders that come close to the target, lowest first.
    """
    target = crit.target
    first = max(2, min(min_order, max_order))
    candidates = [fixed] if fixed else list(range(first, max_order + 1))
    screening: dict[int, float] = {}
    fd = {"weight": weight, "error_weight": crit.weight}
    if method == "fd" and not fixed:
        screened = []
        for n in candidates:
            try:
                quick = fit_frequency_domain(
                    w,
                    a,
                    b,
                    n,
                    added_mass_inf=a_inf,
                    added_mass_inf_guess=guess,
                    added_mass_inf_spread=spread,
                    refine=False,
                    **fd,
                )
            except FitError:
                continue
            score = round(crit.fit_score(quick), 7)
            screening[n] = score
            if score >= target - SCREENING_MARGIN:
                screened.append(n)
            if score >= target:
                break
        candidates = screened or candidates
    best: tuple[float, _Siso, float] | None = None
    errors = []
    remaining = [n for n in range(first, max_order + 1) if n not in candidates] if not fixed else []
    for n in [*candidates, *remaining]:  # the screened orders first, then the others
        try:
            siso, a_inf_fit, score, ok_passive = _fit_order(
                method,
                w,
                a,
                b,
                t,
                kernel,
                n,
                a_inf=a_inf,
                guess=guess,
                spread=spread,
                passive=passive,
                crit=crit,
                weight=weight,
            )
        except FitError as exc:
            errors.append(f"order {n}: {exc}")
            continue
        score = round(score - (0.0 if ok_passive else 1.0), 7)
        if best is None or score > best[0] + TIE:
            best = (score, siso, a_inf_fit)
        if score >= target:
            break
    if best is None:
        raise FitError(f"coupling {name}: no stable model ({'; '.join(errors)})")
    close = screening.get(best[1].order - 1, -np.inf) >= target - SCREENING_MARGIN
    if method == "fd" and not fixed and best[0] >= target and close and best[1].order > first:
        best = _try_lower_orders(
            best,
            w,
            a,
            b,
            a_inf=a_inf,
            guess=guess,
            spread=spread,
            passive=passive,
            crit=crit,
            weight=weight,
        )
    score, siso, a_inf_fit = best
    if score < target and not fixed:
        siso.note = "; ".join(
            filter(None, [siso.note, f"R² target {target} not reached up to order {max_order}"])
        )
    return siso, a_inf_fit


def _try_lower_orders(best, w, a, b, *, a_inf, guess, spread, passive, crit, weight=None):
    """One order lower, started from the fit's poles less its weakest mode, if it still
    meets the criterion (the linearised step has found a local optimum; the pruned start
    often finds a better one). Trying the second-weakest mode as well found no lower
    order on the tanker, supply vessel or S-175 and cost 40 % of the whole fit."""
    if best[1].order > 2:
        fit = best[1].fit
        found = None
        for start in pruned_poles(fit.poles, fit.residues)[:1]:  # the weakest mode
            try:
                lower = fit_frequency_domain(
                    w,
                    a,
                    b,
                    start.size,
                    added_mass_inf=a_inf,
                    added_mass_inf_guess=guess,
                    added_mass_inf_spread=spread,
                    passive=passive,
                    target=crit.target,
                    refine=True,
                    initial_poles=start,
                    weight=weight,
                    error_weight=crit.weight,
                )
            except FitError:
                continue
            if crit.fit_score(lower) >= crit.target and (lower.passive or not passive):
                found = lower
                break
        if found is None:
            return best
        am, bm, cm = modal_realization(found.poles, found.residues)
        siso = _Siso(
            am,
            bm,
            cm,
            "; ".join(
                filter(None, [found.note, "started from the pruned poles of the next order"])
            ),
            found,
        )
        best = (crit.fit_score(found), siso, found.added_mass_inf)
    return best


def _fit_order(method, w, a, b, t, kernel, n, *, a_inf, guess, spread, passive, crit, weight=None):
    from cummins.radiation.fit.frequency import is_positive_real, r_squared

    if method == "fd":
        fit: FrequencyFit = fit_frequency_domain(
            w,
            a,
            b,
            n,
            added_mass_inf=a_inf,
            added_mass_inf_guess=guess,
            added_mass_inf_spread=spread,
            passive=passive,
            target=crit.target,
            weight=weight,
            error_weight=crit.weight,
            # the linearised fit may reach the R² target and miss the motion budget
            refine=True if crit.weight is not None else "auto",
        )
        am, bm, cm = modal_realization(fit.poles, fit.residues)
        return (
            _Siso(am, bm, cm, fit.note, fit),
            fit.added_mass_inf,
            crit.fit_score(fit),
            fit.passive or not passive,
        )
    from cummins.radiation.fit import realization

    realize = realization.era if method == "realization" else realization.prony
    result = realize(t, kernel, n)
    k = CouplingModel(0, 0, result.a, result.b, result.c).frequency_response(w)
    r2a = r_squared(a, a_inf + k.imag / w)
    r2b = r_squared(b, k.real)
    ok = True
    if passive:
        lam, vec = np.linalg.eig(result.a)
        residues = (result.c @ vec) * np.linalg.solve(vec, result.b)
        ok = is_positive_real(lam, residues)
    extra = {}
    sigma = np.asarray(result.hankel_singular_values, dtype=float)
    if sigma.size:
        # the ERA order criterion: σ_{n+1}/σ_1, and the leading values (K units × s)
        extra["hankel_sv_ratio"] = float(sigma[n] / sigma[0]) if sigma.size > n else 0.0
        extra["hankel_singular_values"] = sigma[:HANKEL_VALUES_REPORTED].tolist()
    siso = _Siso(result.a, result.b, result.c, result.note, extra=extra)
    return siso, a_inf, crit.score(r2a, r2b, k, a_inf), ok
