"""Reduction of a radiation model: :func:`reduce_radiation_model`.

:func:`reduce_radiation_model` reduces a :class:`~cummins.radiation.model.RadiationModel`
coupling by coupling (each K_ij is a SISO model), so that the block structure, the
file formats and the symmetry K_ij = K_ji are kept: a symmetric pair is reduced once
and used twice; a model of common-pole blocks block by block
(:mod:`~cummins.radiation.reduce.blocks`). See its docstring for the allocation of a
total order and for what is recorded.

The reduced couplings record how they were reduced and, given the data of the fit, their
measures of fit against the data; :func:`reduction_failures` says what misses its target.
Balanced truncation: Unneland (2007) Ch. 5.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from cummins.errors import FitError
from cummins.radiation.fit import FitData, model_fit_data
from cummins.radiation.fit.frequency import is_positive_real
from cummins.radiation.fit.metrics import coupling_metrics
from cummins.radiation.model import CouplingModel, MemoryBlock, RadiationModel
from cummins.radiation.reduce.blocks import BlockCandidate, BlockUnit, prepared_block
from cummins.radiation.reduce.candidates import (
    _Candidate,
    _hinf_change,
    _lowest_real_part,
    _measurement_grid,
    _prepared,
    _Unique,
)
from cummins.radiation.reduce.gramians import DEFAULT_REGULARIZATION
from cummins.radiation.reduce.modal import ModalBlock
from cummins.radiation.reduce.orders import (
    _allocate,
    _requested,
    checked_order,
    checked_total,
    unknown_keys,
)
from cummins.radiation.reduce.system import PR_METHODS, _check_method, _check_order_or_tol
from cummins.validation import guard_hydro_data, guard_radiation_model

if TYPE_CHECKING:
    import xarray as xr
    from numpy.typing import NDArray

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
    progress: Callable[[str], object] | None = None,
) -> RadiationModel:
    """Reduce a radiation model coupling by coupling (balanced truncation of each K_ij), or
    block by block for a model of common-pole blocks.

    **Blocks** (the default identification, :class:`~cummins.radiation.model.MemoryBlock`):
    each block is balanced as one MIMO model with its DOFs scaled alike (S K S,
    s_i = 1/√max_ω |K_ii|), unweighted and low-frequency weighted as below, and truncated;
    K(0) = 0 and passivity (Re K(jω) ⪰ 0, Unneland (2007) Prop. 3.4) are restored in the
    truncated states by the smallest change of its modal vectors
    (:mod:`~cummins.radiation.reduce.blocks`): no state is added and the model stays
    symmetric. ``order`` (int) is allocated over the blocks by the same minimax, a mapping
    names a block by any pair of its DOFs, ``tol`` bounds the measured change
    max_ω σ_max(S (K − K_r) S) relative to max_ω σ_max(S K S). A truncation that cannot be
    made passive, or whose correction would more than double its misfit, is not used:
    the next order is tried and the block's note says which was kept (the block is kept
    whole when none is). The metrics of every pair hold ``reduction_*`` as below (no
    Glover bound: NaN), ``passivity_change`` and ``passive`` (of the block); the measures
    of fit of the unreduced block stay as ``<metric>_unreduced``, and an R² below
    :data:`FAILED_R2` is a failure only when the reduction made it so.

    **Couplings.** Each coupling is a SISO model; a symmetric pair K_ij = K_ji (two entries with the
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
    progress
        Called with a short message as each block or coupling is reduced (the command
        line shows it).

    Returns
    -------
    RadiationModel
        With ``attrs`` ``reduction_method``, ``reduction_order_before``,
        ``reduction_order_after`` and a ``history`` line.

    Raises
    ------
    FitError
        Bad order (out of range, below 2 per coupling, unknown coupling, two orders for
        one block) or tol, unknown method, unstable coupling or block; a total order for
        a model holding both blocks and single couplings (give ``tol``).

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
    if data is not None:
        guard_hydro_data(data, what="reduction")
    say = progress or (lambda message: None)
    fitted = None if data is None else model_fit_data(model, data)
    if model.blocks:
        result = _reduced_blocks(model, order, tol, method, regularization, fitted, say)
        return _recorded(model, result, method, tol)
    say(f"balancing {len(model.couplings)} couplings ({method})")
    units = _prepared(model, method, regularization, None if fitted is None else fitted.omega)
    chosen = _requested(model, units, order, tol)
    couplings = list(model.couplings)
    for u, candidate in zip(units, chosen, strict=True):
        if candidate is None:
            continue
        say(f"truncating coupling {u.entries[0] + 1} of {len(couplings)}")
        reduced = _reduced_coupling(u, candidate)
        for index in u.entries:
            old = model.couplings[index]
            couplings[index] = replace(reduced, influenced=old.influenced, radiating=old.radiating)
    result = RadiationModel(model.dofs, tuple(couplings), model.added_mass_inf, dict(model.attrs))
    if fitted is not None:
        result = _with_data_metrics(result, fitted)
    return _recorded(model, result, method, tol)


def _recorded(
    model: RadiationModel, result: RadiationModel, method: str, tol: float | None
) -> RadiationModel:
    """The reduced model with the reduction's ``attrs``: method, orders, history, failures."""
    attrs: dict[str, Any] = dict(result.attrs)
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


def _reduced_blocks(
    model: RadiationModel,
    order: Any,
    tol: float | None,
    method: str,
    regularization: float,
    fitted: FitData | None,
    say: Callable[[str], object] = lambda message: None,
) -> RadiationModel:
    """A model of common-pole blocks reduced block by block (:mod:`~cummins.radiation.
    reduce.blocks`): each chosen truncation passive, with K(0) = 0, in its own states."""
    if model.couplings and tol is None:
        raise FitError(
            "the model holds both common-pole blocks and single couplings: reduce it "
            "with a tolerance (tol=..., cummins reduce --tol)"
        )
    # a block fitted as given (K_ij ≠ K_ji) is kept whole: its truncations would be written
    # with symmetric residues (reduce/blocks.py), which it has not
    given = [k for k, block in enumerate(model.blocks) if not block.is_symmetric()]
    n = len(model.blocks)
    units = []
    for index, block in enumerate(model.blocks):
        if index in given:
            continue
        say(f"block {index + 1} of {n} ({block.order} states): balanced truncations")
        grid = _block_grid(model, block, fitted)
        units.append(prepared_block(block, index, method, regularization, grid))
    order = _without_blocks(model, order, given)
    chosen = _requested_blocks(units, order, tol) if units else []
    blocks = list(model.blocks)
    for k in given:
        note = (
            f"not reduced: its couplings are fitted as given (K_ij ≠ K_ji), which the "
            f"block truncation (symmetric residues) does not keep; kept at its "
            f"{model.blocks[k].order} states"
        )
        blocks[k] = replace(blocks[k], note="; ".join(filter(None, [blocks[k].note, note])))
    for unit, candidate in zip(units, chosen, strict=True):
        if candidate is not None:
            say(f"block {unit.index + 1} of {n}: K(0) = 0 and passivity in its states")
            blocks[unit.index] = _reduced_block(unit, candidate, fitted, model)
        elif unit.notes:
            blocks[unit.index] = replace(
                unit.block, note="; ".join(filter(None, [unit.block.note, *unit.notes]))
            )
    couplings = model.couplings
    if model.couplings:
        reduced = reduce_radiation_model(
            replace(model, blocks=()), tol=tol, method=method, regularization=regularization
        )
        couplings = reduced.couplings
    return RadiationModel(
        model.dofs, couplings, model.added_mass_inf, dict(model.attrs), tuple(blocks)
    )


def _without_blocks(model: RadiationModel, order: Any, given: list[int]) -> Any:
    """The order asked of the blocks that are reduced: a total less the states of the
    blocks ``given`` (kept whole); a mapping that names one of them is refused."""
    if not given or order is None:
        return order
    if isinstance(order, Mapping):
        for k in given:
            dofs = model.blocks[k].dofs
            if any(i in dofs and j in dofs for i, j in order):
                raise FitError(
                    f"the block of DOFs {', '.join(model.dofs[d] for d in dofs)} cannot be "
                    "reduced: its couplings are fitted as given (K_ij ≠ K_ji, data that are not "
                    f"reciprocal) and the block truncation keeps symmetric residues only; it "
                    f"keeps its {model.blocks[k].order} states",
                    hint="reduce the other blocks, or fit with reciprocity='average' "
                    "(cummins fit --reciprocity average) for a reciprocal model",
                )
        return order
    kept = sum(model.blocks[k].order for k in given)
    if int(order) <= kept:
        raise FitError(
            f"a total order of {order} is not enough: the blocks whose couplings are fitted as "
            f"given (K_ij ≠ K_ji) are kept whole, {kept} states",
            hint="ask for more states, or fit with reciprocity='average'",
        )
    return int(order) - kept


def _block_grid(model: RadiationModel, block: MemoryBlock, fitted: FitData | None) -> NDArray:
    """Where a block's truncations are compared with it: the fitted frequencies of the
    data when given, else as for a coupling (:data:`MEASURE_POINTS` over the fitted range)."""
    view = block.element(block.dofs[0], block.dofs[0])
    return _measurement_grid(model, view, None if fitted is None else fitted.omega)


def _requested_blocks(
    units: list[BlockUnit], order: Any, tol: float | None
) -> list[BlockCandidate | None]:
    """The chosen passive truncation of every block (None: kept as it is)."""
    if tol is not None:
        out = []
        for u in units:
            found = u.first_passive(u.minimum, tol)
            if found is None and u.block.order > u.minimum:
                u.notes.append(
                    f"no passive truncation with K(0) = 0 within tol {tol:g} below "
                    f"{u.block.order} states: kept"
                )
            out.append(found)
        return out
    if isinstance(order, Mapping):
        targets = _mapped_block_orders(units, order)
    else:
        lowest = sum(u.minimum for u in units)
        total = sum(u.block.order for u in units)
        checked_total(order, lowest, total, f"its blocks need at least {lowest}")
        tables = [
            {
                r: u.best(r) if r < u.block.order else None
                for r in range(u.minimum, u.block.order + 1)
            }
            for u in units
        ]
        targets = _allocate(units, tables, int(order))  # type: ignore[arg-type]
    out = []
    for u, r in zip(units, targets, strict=True):
        found = u.first_passive(r) if r < u.block.order else None
        if found is not None and found.order > r:
            u.notes.append(f"no passive truncation to {r} states: {found.order} kept")
        if found is None and r < u.block.order:
            u.notes.append(f"no passive truncation to {r} states: the block is kept")
        out.append(found)
    return out


def _mapped_block_orders(units: list[BlockUnit], order: Mapping) -> list[int]:
    """Block orders from a mapping {(i, j): n}: a pair of DOFs of a block names the block."""
    out = []
    known = set()
    for u in units:
        keys = [key for key in order if key[0] in u.block.dofs and key[1] in u.block.dofs]
        known.update(keys)
        values = {order[key] for key in keys}
        if len(values) > 1:
            raise FitError(
                f"the DOFs {u.block.dofs} share their states (one block): give them one order, "
                f"not {sorted(values)}"
            )
        n = values.pop() if values else u.block.order
        out.append(checked_order(n, f"block {u.block.dofs}", u.minimum, u.block.order))
    unknown_keys(order, known)
    return out


def _reduced_block(
    unit: BlockUnit, x: BlockCandidate, fitted: FitData | None, model: RadiationModel
) -> MemoryBlock:
    """The memory block of a chosen truncation (DOF scaling undone), with its metrics."""
    block = unit.block
    modal = ModalBlock(x.modal.poles, x.modal.vectors / unit.scale[None, :], x.modal.signs)
    a, b, c = modal.realization()
    weighted = f", weighted at ω₀ = {x.weight:.3g} rad/s" if x.weight else ""
    text = (
        f"reduced by {unit.method} balanced truncation of the block{weighted} from "
        f"{block.order} to {x.order} states; K(0) = 0 restored ({100 * x.dc_change:.2g} % "
        f"change) and made passive ({100 * x.passivity_change:.2g} % change) in those states; "
        f"max σ(S(K − K_r)S) = {x.change:.2g} of max σ(S K S); R² of A and B against the "
        f"unreduced block ≥ {1 - x.error:.4f}"
    )
    reduced = MemoryBlock(block.dofs, a, b, c, block.method, {}, "")
    stable = reduced.is_stable()
    metrics = {}
    for key, old in block.metrics.items():
        m: dict[str, Any] = {
            f"{name}_unreduced" if name in DATA_METRICS else name: value
            for name, value in old.items()
        }
        if fitted is not None:  # against the data as the fit was (the unreduced kept)
            i, j = key
            # the data are symmetrised, as in the fit: the symmetric A∞
            inf = 0.5 * float(model.added_mass_inf[i, j] + model.added_mass_inf[j, i])
            m.update(_data_metrics(reduced.element(i, j), fitted, inf))
        m.update(
            **_record(unit.method, block.order, x.order, x.weight, x.error, None),
            reduction_hinf_relative=float(x.change),
            dc_change=float(x.dc_change),
            passivity_change=float(x.passivity_change),
            stable=stable,
            passive=bool(x.passive),
        )
        metrics[key] = m
    note = "; ".join(filter(None, [block.note, text, *unit.notes]))
    return replace(reduced, metrics=metrics, note=note)


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
        out += _r2_failures(name, m)
        if not m.get("stable", True):
            out.append(f"{name}: unstable after the reduction")
    for block in model.blocks:
        name = "-".join(model.dofs[d] for d in block.dofs)
        first = next(iter(block.metrics.values()), {})
        if "reduction_method" not in first:
            continue
        change = first.get("reduction_hinf_relative")
        if tol is not None and change is not None and change > tol * (1 + 1e-9):
            out.append(
                f"block {name}: the reduction changed S K S by {change:.3g} of its maximum "
                f"(tol {tol:g}): the tolerance is not met"
            )
        for (i, j), m in block.metrics.items():
            out += _r2_failures(model.dofs[i] if i == j else f"{model.dofs[i]}-{model.dofs[j]}", m)
        if not first.get("stable", True):
            out.append(f"block {name}: unstable after the reduction")
        if not first.get("passive", True):
            out.append(f"block {name}: not passive after the reduction")
    return out


def _r2_failures(name: str, metrics: Mapping) -> list[str]:
    """An R² of A or B below :data:`FAILED_R2` that the unreduced model (when its value is
    recorded) did not have, said."""
    out = []
    for key, what in (("r2_added_mass", "A"), ("r2_damping", "B")):
        value, before = metrics.get(key), metrics.get(f"{key}_unreduced")
        if value is not None and value < FAILED_R2:
            if before is not None and before < FAILED_R2:
                continue  # the fit's own failure, reported by the fit
            out.append(f"{name}: R² of {what} {value:.3g} after the reduction")
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
        **_record(u.method, k.order, x.order, x.weight, x.error, x.bound),
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


def _record(
    method: str, before: int, after: int, weight: float | None, error: float, bound: float | None
) -> dict[str, Any]:
    """The metrics every reduced coupling or block pair records (see
    :func:`reduce_radiation_model`)."""
    return {
        "reduction_method": method,
        "reduction_order_before": before,
        "reduction_order_after": after,
        "reduction_weight": float(weight or 0.0),
        "reduction_fit_error": float(error),
        "reduction_error_bound": math.nan if bound is None else float(bound),
    }


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
        metrics.update(_data_metrics(k, fitted, float(model.added_mass_inf[i, j])))
        out.append(replace(k, metrics=metrics))
    return replace(model, couplings=tuple(out))


def _data_metrics(k: CouplingModel, fitted: FitData, added_mass_inf: float) -> dict[str, Any]:
    """The measures of fit of coupling k (its ``influenced``, ``radiating`` pair) against
    the data, as the fit computes them."""
    i, j = k.influenced, k.radiating
    return coupling_metrics(
        k,
        fitted.omega,
        fitted.added_mass[:, i, j],
        fitted.damping[:, i, j],
        added_mass_inf,
        time=fitted.time,
        kernel=fitted.kernel[:, i, j],
    )
