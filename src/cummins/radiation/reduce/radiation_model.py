"""Reduction of a radiation model, coupling by coupling: :func:`reduce_radiation_model`.

:func:`reduce_radiation_model` reduces a :class:`~cummins.radiation.model.RadiationModel`
coupling by coupling (each K_ij is a SISO model), so that the block structure, the
file formats and the symmetry K_ij = K_ji are kept: a symmetric pair is reduced once
and used twice. See its docstring for the allocation of a total order over the
couplings and for what is recorded.

The reduced couplings record how they were reduced and, given the data of the fit, their
measures of fit against the data; :func:`reduction_failures` says what misses its target.
Balanced truncation: Unneland (2007) Ch. 5.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from cummins.errors import FitError
from cummins.radiation.fit import FitData, model_fit_data
from cummins.radiation.fit.frequency import is_positive_real
from cummins.radiation.fit.metrics import coupling_metrics
from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.radiation.reduce.candidates import (
    _Candidate,
    _hinf_change,
    _lowest_real_part,
    _prepared,
    _Unique,
)
from cummins.radiation.reduce.gramians import DEFAULT_REGULARIZATION
from cummins.radiation.reduce.orders import _requested
from cummins.radiation.reduce.system import PR_METHODS, _check_method, _check_order_or_tol
from cummins.validation import guard_hydro_data, guard_radiation_model

if TYPE_CHECKING:
    import xarray as xr

#: Metrics of a fitted coupling computed against the data (stale after a reduction).
DATA_METRICS = (
    "r2_added_mass",
    "r2_damping",
    "r2_magnitude",
    "r2_phase",
    "r2_kernel",
    "hinf_error",
    "hinf_relative",
)


def reduce_radiation_model(
    model: RadiationModel,
    *,
    order: int | Mapping[tuple[int, int], int] | None = None,
    tol: float | None = None,
    method: str = "lyapunov",
    regularization: float = DEFAULT_REGULARIZATION,
    data: xr.Dataset | None = None,
) -> RadiationModel:
    """Reduce a radiation model coupling by coupling (balanced truncation of each K_ij).

    Each coupling is a SISO model; a symmetric pair K_ij = K_ji (two entries with the
    same matrices) is reduced once and used twice, so the block structure, the symmetry
    and the file formats are kept.

    **What is truncated.** The added mass is A(ω) − A∞ = Im K(jω)/ω: an error of K at
    low frequency is amplified by 1/ω in A, so plain balanced truncation of K (uniform
    in frequency) loses the low-frequency added mass first. Each coupling is therefore
    also balanced as the augmented model [K(s), ω₀ K(s)/s] (``low_frequency_weight`` ω₀
    of :func:`balanced_truncation`; K/s = (A − A∞) − jB/ω is stable because K(0) = 0),
    for ω₀ in :data:`WEIGHT_CANDIDATES` × the frequency of the peak of |K|. At each order
    the candidate (unweighted or weighted) that reproduces the unreduced coupling best,
    max(1 − R²_A, 1 − R²_B) (Unneland (2007) eq. 6.19), is kept; it is measured at the
    fitted frequencies of ``data`` when given, else on :data:`MEASURE_POINTS` log-spaced
    frequencies over the fitted range. Every candidate is a balanced truncation: stable
    (Unneland (2007) Theorem 5.2), with Glover's bound on ‖K − K_r‖∞ (from the σ of the
    augmented model when weighted) for ``"lyapunov"``, and positive real up to ε for the
    mixed methods (the weighted P against the Riccati O, Theorem 5.3).

    **Orders.**

    * ``order`` (int): the total order of the MIMO model (a symmetric pair counts twice),
      allocated over the couplings to minimise the largest fit error (minimax over the
      couplings, each at least :data:`MIN_COUPLING_ORDER` states; the total falls one
      short only when the last state could go to a symmetric pair alone).
    * ``order`` (mapping ``{(i, j): n}``, 0-based DOFs, either key of a symmetric pair):
      the order of those couplings; the others are kept.
    * ``tol``: per coupling, the smallest order ≥ 2 whose relative H∞ error is at most
      ``tol`` of max|K|: Glover's bound (``"lyapunov"``, before the DC projection) or the
      measured change (PR methods).

    **Passivity.** With ``"riccati"``, ``"mixed"`` or ``"mixed-rq"`` the diagonal
    couplings (positive real) are truncated with Re K_r ≥ −ε max|K| (``regularization``
    ε, :mod:`~cummins.radiation.reduce.gramians`). The off-diagonal couplings are not
    positive real on their own (there is no per-coupling passivity to keep) and are
    reduced by Lyapunov BT, as is a diagonal coupling that is not positive real (with a
    note). MIMO passivity is not enforced here.

    **Structure.** After truncation the zero K(0) = 0 is re-imposed (when the coupling
    had it) by the smallest H₂ change of c
    (:func:`cummins.radiation.fit.realization.impose_zero_dc`).
    This moves Re K at low frequency by about the DC gain removed and can take a diagonal
    term a little below zero (on the tanker: at most 0.7 % of its peak with Lyapunov,
    0.2 % with the mixed methods); the PR methods prefer, at each order, a candidate
    still within ε after the projection, and the metrics say how far each one is.

    **Record.** Each reduced coupling's metrics hold ``reduction_method``,
    ``reduction_order_before``, ``reduction_order_after``, ``reduction_weight`` (ω₀,
    rad/s; 0: unweighted), ``reduction_fit_error`` (max(1 − R²) against the unreduced
    coupling), ``reduction_error_bound`` (Glover; NaN for the PR methods),
    ``reduction_hinf_change`` (measured max_ω |K − K_r|, after the DC projection) and
    its ``reduction_hinf_relative``, ``dc_change``, ``reduction_regularization`` (ε of
    the PR methods), ``stable`` and, on the diagonal, ``passive`` and
    ``reduction_min_real_relative`` (min(0, min_ω Re K_r)/max|K|, the size of any
    violation); the note says the same in words. The measures of fit against the data
    (:data:`DATA_METRICS`) describe the unreduced model: with ``data`` (the ``HydroDB``
    the model was fitted to) they are recomputed at the fitted frequencies, otherwise
    they are kept as ``<metric>_unreduced``.

    Parameters
    ----------
    model
        The model (stable couplings).
    order, tol
        Exactly one of them (above).
    method
        One of :data:`METHODS`.
    regularization
        ε for the PR methods.
    data
        The data of the fit, to recompute the measures of fit.

    Returns
    -------
    RadiationModel
        With ``attrs`` ``reduction_method``, ``reduction_order_before``,
        ``reduction_order_after`` and a ``history`` line.

    Raises
    ------
    FitError
        Bad order (out of range, below 2 per coupling, unknown coupling) or tol, unknown
        method, unstable coupling; a model with common-pole blocks (refit it with fewer
        poles instead).

    Examples
    --------
    >>> import cummins
    >>> model = cummins.fit_radiation(cummins.demo_dataset(), method="realization")
    >>> small = reduce_radiation_model(model, order=model.total_order - 4)
    >>> small.total_order == model.total_order - 4, small.is_stable()
    (True, True)
    """
    _check_method(method)
    _check_order_or_tol(order, tol)
    guard_radiation_model(model)  # FitError naming the coupling, before LAPACK sees it
    if model.blocks:
        raise FitError(
            "the model holds common-pole blocks (the default identification, method 'vf'), "
            "whose DOFs share their states; balanced truncation here reduces models of "
            "single couplings",
            hint="fit again with fewer common poles (fit_radiation(..., max_order=N) or "
            "orders=...; cummins fit --max-order N), or fit per coupling (method='fd') "
            "and reduce that",
        )
    if data is not None:
        guard_hydro_data(data, what="reduction")
    fitted = None if data is None else model_fit_data(model, data)
    units = _prepared(model, method, regularization, None if fitted is None else fitted.omega)
    chosen = _requested(model, units, order, tol)
    couplings = list(model.couplings)
    for u, candidate in zip(units, chosen, strict=True):
        if candidate is None:
            continue
        reduced = _reduced_coupling(u, candidate)
        for index in u.entries:
            old = model.couplings[index]
            couplings[index] = replace(reduced, influenced=old.influenced, radiating=old.radiating)
    attrs: dict[str, Any] = dict(model.attrs)
    result = RadiationModel(model.dofs, tuple(couplings), model.added_mass_inf, attrs)
    if fitted is not None:
        result = _with_data_metrics(result, fitted)
    line = (
        f"reduced by {method} balanced truncation from {model.total_order} to "
        f"{result.total_order} states"
    )
    history = attrs.get("history")
    attrs.update(
        reduction_method=method,
        reduction_order_before=model.total_order,
        reduction_order_after=result.total_order,
        history=f"{history}\n{line}" if isinstance(history, str) and history else line,
        failures=[*model.attrs.get("failures", []), *reduction_failures(result, tol)],
    )
    return replace(result, attrs=attrs)


#: A reduced coupling whose R² of A or B against the data (or the unreduced model)
#: falls below this is reported as a failure, whatever was asked.
FAILED_R2 = 0.0


def reduction_failures(model: RadiationModel, tol: float | None) -> list[str]:
    """What makes a reduction a failure, one message per coupling (empty: success):
    with ``tol``, a measured change max_ω |K − K_r| above ``tol`` of max|K| (the two-body
    WEC of issue 16: 82× at ``tol`` 0.05, reported as success before); an R² of A or B
    against the reference below :data:`FAILED_R2`; an unstable coupling."""
    out = []
    for k in model.couplings:
        if k.influenced > k.radiating or "reduction_method" not in k.metrics:
            continue
        m = k.metrics
        i, j = model.dofs[k.influenced], model.dofs[k.radiating]
        name = i if i == j else f"{i}-{j}"
        change = m.get("reduction_hinf_relative")
        bound = m.get("reduction_error_bound")
        absolute = m.get("reduction_hinf_change")
        bound_relative = (
            bound * change / absolute
            if bound is not None and not math.isnan(bound) and absolute and change
            else None
        )
        # Lyapunov chose the order by Glover's bound before the zero at s = 0 was
        # re-imposed (which moves K by about the DC gain removed): it misses when both do
        missed = (
            tol is not None
            and change is not None
            and change > tol * (1 + 1e-9)
            and (bound_relative is None or bound_relative > tol * (1 + 1e-9))
        )
        if missed:
            out.append(
                f"{name}: the reduction changed K by {change:.3g} of max|K| (tol {tol:g}): "
                "the tolerance is not met"
            )
        for key, what in (("r2_added_mass", "A"), ("r2_damping", "B")):
            value = m.get(key)
            if value is not None and value < FAILED_R2:
                out.append(f"{name}: R² of {what} {value:.3g} after the reduction")
        if not m.get("stable", True):
            out.append(f"{name}: unstable after the reduction")
    return out


def _reduced_coupling(u: _Unique, x: _Candidate) -> CouplingModel:
    """The coupling model of a chosen truncation, with its metrics and note."""
    k = u.model
    change = _hinf_change(k, x.a, x.b, x.c)
    weighted = f", weighted at ω₀ = {x.weight:.3g} rad/s" if x.weight else ""
    text = f"reduced by {u.method} balanced truncation{weighted} from {k.order} to {x.order} states"
    if x.bound is not None:
        text += f" (Glover bound {x.bound / u.peak:.2g} of max|K|)"
    text += (
        f"; max|K − K_r| = {change / u.peak:.2g} of max|K|; R² of A and B against the "
        f"unreduced coupling ≥ {1 - x.error:.4f}"
    )
    if u.method in PR_METHODS:
        text += f"; Re K_r ≥ −{u.regularization:.2g} max|K| before the DC projection"
    if u.had_zero:
        text += (
            f"; zero at s = 0 re-imposed (K_r(0) was {x.dc_before:.3g}; c changed by "
            f"{100 * x.dc_change:.3g} % in H2)"
        )
    new = CouplingModel(k.influenced, k.radiating, x.a, x.b, x.c, k.method, {}, "")
    metrics: dict[str, Any] = {}
    for key, value in k.metrics.items():
        metrics[f"{key}_unreduced" if key in DATA_METRICS else key] = value
    metrics.update(
        reduction_method=u.method,
        reduction_order_before=k.order,
        reduction_order_after=x.order,
        reduction_weight=float(x.weight or 0.0),
        reduction_fit_error=float(x.error),
        reduction_error_bound=math.nan if x.bound is None else float(x.bound),
        reduction_hinf_change=float(change),
        reduction_hinf_relative=float(change / u.peak) if u.peak > 0 else 0.0,
        dc_change=float(x.dc_change),
        reduction_regularization=float(u.regularization if u.method in PR_METHODS else 0.0),
        stable=new.is_stable(),
    )
    if "order" in metrics:
        metrics["order"] = x.order
    if new.influenced == new.radiating:
        lam, vec = np.linalg.eig(new.a)
        residues = (new.c @ vec) * np.linalg.solve(vec, new.b)
        metrics["passive"] = bool(metrics["stable"]) and is_positive_real(lam, residues)
        lowest = _lowest_real_part(new.a, new.b, new.c)
        metrics["reduction_min_real_relative"] = lowest / u.peak if u.peak > 0 else 0.0
    note = "; ".join(filter(None, [k.note, text, *u.notes]))
    return replace(new, metrics=metrics, note=note)


def _with_data_metrics(model: RadiationModel, fitted: FitData) -> RadiationModel:
    """The measures of fit of the reduced couplings recomputed against the data the model
    was fitted to (:func:`cummins.radiation.fit.model_fit_data`), as the fit computes them."""
    out = []
    for k in model.couplings:
        if "reduction_method" not in k.metrics:
            out.append(k)
            continue
        i, j = k.influenced, k.radiating
        metrics = dict(k.metrics)
        for key in DATA_METRICS:
            metrics.pop(f"{key}_unreduced", None)
        metrics.update(
            coupling_metrics(
                k,
                fitted.omega,
                fitted.added_mass[:, i, j],
                fitted.damping[:, i, j],
                float(model.added_mass_inf[i, j]),
                time=fitted.time,
                kernel=fitted.kernel[:, i, j],
            )
        )
        out.append(replace(k, metrics=metrics))
    return replace(model, couplings=tuple(out))
