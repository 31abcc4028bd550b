"""The order of every coupling of a reduced radiation model.

From a total order (allocated over the couplings to minimise the largest fit error,
minimax), an order per coupling, or a tolerance per coupling (Glover's bound for
Lyapunov truncation, Glover 1984; the measured H∞ change for the positive-real methods);
see :func:`~cummins.radiation.reduce.radiation_model.reduce_radiation_model`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from cummins.errors import FitError
from cummins.radiation.model import RadiationModel
from cummins.radiation.reduce.candidates import (
    MIN_COUPLING_ORDER,
    _Candidate,
    _hinf_change,
    _Unique,
)


def _error_tables(units: list[_Unique]) -> list[dict[int, _Candidate | None]]:
    """The best candidate at every order of every coupling (None: no stable one); the
    full order is the coupling itself (error 0)."""
    return [
        {r: (u.best(r) if r < u.model.order else None) for r in range(u.minimum, u.model.order + 1)}
        for u in units
    ]


def _error(table: dict[int, _Candidate | None], r: int, full: int) -> float:
    if r >= full:
        return 0.0
    found = table.get(r)
    return math.inf if found is None else found.error


def _allocate(
    units: list[_Unique], tables: list[dict[int, _Candidate | None]], total: int
) -> list[int]:
    """Orders per coupling, Σ (entries × order) ≤ ``total``, minimising the largest fit
    error (minimax over the couplings), then filling the budget.

    For a threshold τ each coupling takes its smallest order whose error is ≤ τ; the
    smallest τ whose orders fit the budget is the minimax allocation (exact, although the
    error of a truncation is not monotone in its order). The states left over go, one
    step at a time, where they lower the error most, preferring steps that keep every
    error within the minimax value (a truncation can be worse with one state more; such
    a step is taken only when no other is left; an order without a truncation is stepped
    over), so that the total is ``total`` unless only a symmetric pair could take the last
    state.
    """
    if not units:
        return []
    fulls = [u.model.order for u in units]
    costs = [len(u.entries) for u in units]

    def orders_for(tau: float) -> list[int]:
        return [
            next(r for r in range(u.minimum, n + 1) if _error(t, r, n) <= tau)
            for u, t, n in zip(units, tables, fulls, strict=True)
        ]

    levels = sorted({_error(t, r, n) for t, n in zip(tables, fulls, strict=True) for r in t})
    finite = [tau for tau in levels if not math.isinf(tau)]
    feasible = (
        orders_for(tau)
        for tau in finite
        if sum(c * r for c, r in zip(costs, orders_for(tau), strict=True)) <= total
    )
    orders = next(feasible, None)
    if orders is None:
        lowest = sum(c * r for c, r in zip(costs, orders_for(finite[-1]), strict=True))
        raise FitError(
            f"total order {total} is too low: the couplings have stable truncations from "
            f"{lowest} states on"
        )
    worst = max(_error(t, r, n) for t, r, n in zip(tables, orders, fulls, strict=True))
    budget = total - sum(c * r for c, r in zip(costs, orders, strict=True))
    while budget > 0:
        steps = []
        for index, (t, r, n, c) in enumerate(zip(tables, orders, fulls, costs, strict=True)):
            # the next order with a truncation (one may have none: unstable, or a
            # common-pole block's order between two that split a pair)
            q = next((q for q in range(r + 1, n + 1) if not math.isinf(_error(t, q, n))), None)
            if q is not None and c * (q - r) <= budget:
                steps.append((_error(t, q, n) > worst, _error(t, q, n) - _error(t, r, n), index, q))
        if not steps:
            break
        _, _, index, q = min(steps)
        budget -= costs[index] * (q - orders[index])
        orders[index] = q
        worst = max(worst, _error(tables[index], orders[index], fulls[index]))
    return orders


def _coupling_for_tol(u: _Unique, tol: float) -> _Candidate | None:
    """The smallest order ≥ 2 meeting ``tol`` (relative): Glover's bound (Lyapunov) or
    the measured H∞ change (PR methods); the best-fitting weight at that order."""
    for r in range(u.minimum, u.model.order):
        meeting = []
        for weight in u.weights():
            found = u.candidate(r, weight)
            if found is None:
                continue
            if found.bound is not None:
                ok = found.bound <= tol * u.peak
            else:
                ok = _hinf_change(u.model, found.a, found.b, found.c) <= tol * u.peak
            if ok:
                meeting.append(found)
        if meeting:
            return u.preferred(meeting)
    return None


def _requested(
    model: RadiationModel,
    units: list[_Unique],
    order: Any,
    tol: float | None,
) -> list[_Candidate | None]:
    """The chosen truncation of every unique coupling (None: kept as it is)."""
    if tol is not None:
        return [_coupling_for_tol(u, tol) if u.model.order else None for u in units]
    if isinstance(order, Mapping):
        targets = _mapped_orders(units, order)
        return [
            None if r >= u.model.order else _stable_best(u, r)
            for u, r in zip(units, targets, strict=True)
        ]
    lowest = sum(len(u.entries) * u.minimum for u in units)
    needs = f"its couplings need at least {lowest} (≥ {MIN_COUPLING_ORDER} each)"
    checked_total(order, lowest, model.total_order, needs)
    tables = _error_tables(units)
    orders = _allocate(units, tables, int(order))
    return [
        t.get(r) if r < u.model.order else None
        for u, t, r in zip(units, tables, orders, strict=True)
    ]


def _stable_best(u: _Unique, r: int) -> _Candidate | None:
    """The best candidate at r states, or at the next order with a stable truncation."""
    for order in range(r, u.model.order):
        found = u.best(order)
        if found is not None:
            if order > r:
                u.notes.append(f"no stable truncation to {r} states: {order} kept")
            return found
    return None


def _mapped_orders(units: list[_Unique], order: Mapping) -> list[int]:
    """Orders from a mapping {(i, j): n} (either key of a symmetric pair; others kept)."""
    known = set()
    out = []
    for u in units:
        k = u.model
        keys = [(k.influenced, k.radiating)]
        if len(u.entries) > 1:
            keys.append((k.radiating, k.influenced))
        known.update(keys)
        n = next((order[key] for key in keys if key in order), k.order)
        out.append(checked_order(n, f"coupling {keys[0]}", u.minimum, k.order))
    unknown_keys(order, known)
    return out


def checked_total(order: Any, lowest: int, highest: int, needs: str) -> int:
    """``order`` as the total order of a model of ``highest`` states whose parts need
    ``lowest`` (``needs`` says so in the message)."""
    if isinstance(order, bool) or not isinstance(order, int | np.integer):
        raise FitError(f"order must be an integer (total order) or a mapping, not {order!r}")
    if not lowest <= order <= highest:
        raise FitError(
            f"total order {order} is out of range: the model has {highest} states and {needs}"
        )
    return int(order)


def checked_order(n: Any, what: str, lowest: int, highest: int) -> int:
    """``n`` as the order of ``what`` (an integer in ``lowest`` … ``highest``)."""
    if isinstance(n, bool) or not isinstance(n, int | np.integer):
        raise FitError(f"the order of {what} must be an integer, not {n!r}")
    if not lowest <= n <= highest:
        raise FitError(f"order {n} for {what} is out of range {lowest} … {highest}")
    return int(n)


def unknown_keys(order: Mapping, known: set) -> None:
    """A FitError naming the first key of ``order`` that is not a modelled coupling."""
    unknown = sorted(set(order) - known)
    if unknown:
        raise FitError(f"the model has no coupling {unknown[0]} (0-based DOF indices)")
