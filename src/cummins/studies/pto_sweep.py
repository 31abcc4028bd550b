"""A PTO's damping (and stiffness) as axes of a batch study, and the best damping.

A study with a ``system:`` holding PTOs may sweep one PTO's damping c (N s/m, or N m s/rad
for a rotation) and stiffness k (N/m, N m/rad) as axes of its grid::

    grid: {heading: [180], hs: [1, 2], tp: [6, 8, 10], pto_damping: [1e5, 3e5, 1e6]}

With one PTO the axis is its own; with several, ``pto_damping: {float: [..]}`` names the
one swept (the others keep the values of their entries). A study with a list of cases
gives each case its values instead, ``{heading: 180, hs: 2, tp: 8, pto_damping: 3e5}``
(``{float: 3e5}`` with several PTOs), with the same checks (:func:`list_swept_pto`); a case
without them is recorded at the PTO's own values (:func:`with_own_values`). Every case
(sea state × damping) is then solved with that PTO's values (:func:`case_system`): in the
frequency domain its own RAOs; in the time domain a vessel per value, all on the one
radiation model fitted before the cases (the fit does not depend on the PTO's values, only
which motions it aims at: it is made at the smallest damping of the sweep, the most
resonant system).

:func:`best_pto_damping` reads the results: per sea state the damping of the list with the
largest mean absorbed power Σ_PTOs ``pto_mean_power`` (``pto_damping_best``, its power
``pto_mean_power_best``, and ``pto_damping_best_at_edge`` where that is the first or the
last value: the optimum may lie beyond the list); with a scatter diagram, the mean power
per damping weighted by the sea states' probabilities (``pto_mean_power_site``) and the
best single damping for the site (``pto_damping_site_best``). For one body in heave in a
regular wave of frequency ω the power is ½ c ω² |X|² with
X = F / (C − ω²(m + A) + iω(B + c)), largest at c = √(B² + (ω(m + A) − C/ω)²): the optimum
of a purely resistive load, whose resistance equals the magnitude of the body's own
mechanical impedance (Falnes (2002), the power absorbed by an oscillating body).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import ArgumentError

#: The grid axes of a PTO sweep → (units of a translation, units of a rotation).
SWEEP_AXES: dict[str, tuple[str, str]] = {
    "pto_damping": ("N s/m", "N m s/rad"),
    "pto_stiffness": ("N/m", "N m/rad"),
}


#: What a list of cases says of the best damping (a grid's sea states × dampings only).
LIST_NOTE = (
    "best PTO damping not computed: the cases are a list (each case's pto_damping is in "
    "the results); a grid axis, grid: {pto_damping: [..]}, gives the best per sea state"
)


def pto_names(system: Any) -> list[str]:
    """The PTOs' names as results label them (``pto1``, ``pto2`` … when unnamed)."""
    if system is None:
        return []
    return [p.name or f"pto{k + 1}" for k, p in enumerate(system.ptos)]


def named_sweep(grid: Any, where: str, example: str = "[..]") -> tuple[Any, str | None]:
    """``grid`` with a sweep axis written ``{pto name: [values]}`` made a plain list, and
    the PTO it names (None when no axis names one). ``where`` names the grid's key (or a
    list's case, whose ``example`` value is ``"value"``)."""
    if not isinstance(grid, Mapping):
        return grid, None
    out = dict(grid)
    named: dict[str, str] = {}
    for axis in SWEEP_AXES:
        value = out.get(axis)
        if not isinstance(value, Mapping):
            continue
        if len(value) != 1:
            raise ArgumentError(
                f"{where}.{axis}: name one PTO and its values, e.g. {axis}: {{pto1: {example}}}"
            )
        ((name, values),) = value.items()
        named[axis] = str(name)
        out[axis] = values
    if len(set(named.values())) > 1:
        raise ArgumentError(
            f"{where}: pto_damping and pto_stiffness name different PTOs "
            f"({', '.join(named.values())}): one PTO is swept per study"
        )
    return out, next(iter(named.values()), None)


def swept_pto(
    grid: Sequence[tuple[str, tuple]],
    system: Any,
    named: str | None,
    where: str,
    example: str = "[..]",
):
    """The name of the PTO a grid's sweep axes set (None without a sweep axis), its
    values checked: a system with a PTO, the PTO named when there are several, dampings
    ≥ 0. ``where`` names the grid's key (``study.yaml: grid``)."""
    axes = {name: values for name, values in grid if name in SWEEP_AXES}
    if not axes:
        return None
    axis = next(iter(axes))
    names = pto_names(system)
    if not names:
        raise ArgumentError(
            f"{where}.{axis}: the study has no PTO to sweep",
            hint="give a system: with a PTO (a joint's pto: {damping: ..}, or ptos: [..]); "
            "docs/guide/wec.md",
        )
    if named is None and len(names) > 1:
        raise ArgumentError(
            f"{where}.{axis}: the system has {len(names)} PTOs ({', '.join(names)}): name "
            f"the one swept, {axis}: {{{names[0]}: {example}}}"
        )
    name = named or names[0]
    if name not in names:
        raise ArgumentError(f"{where}.{axis}: no PTO {name!r}; the PTOs are {', '.join(names)}")
    check_damping(axes.get("pto_damping", ()), where)
    return name


def check_damping(values: Sequence[float], where: str) -> None:
    """Refuse a negative PTO damping (``where``: the key holding ``values``)."""
    negative = [v for v in values if v < 0]
    if negative:
        raise ArgumentError(
            f"{where}.pto_damping: {negative[0]:g} is negative: a PTO's damping is >= 0 "
            "(it absorbs power)"
        )


def named_case_values(
    cases: Sequence[Any], key: Callable[[int], str]
) -> tuple[list[Any], list[str | None]]:
    """The cases of a list with a value written ``{pto name: value}`` made plain, and the
    PTO each names (None where it does not); ``key(k)`` names the k-th case."""
    plain, names = [], []
    for k, case in enumerate(cases):
        out, name = named_sweep(case, key(k), example="value")
        plain.append(out)
        names.append(name)
    return plain, names


def list_swept_pto(
    cases: Sequence[Any], names: Sequence[str | None], system: Any, key: Callable[[int], str]
) -> str | None:
    """The PTO whose values the cases of a list set (None when no case carries
    ``pto_damping`` or ``pto_stiffness``), checked as a grid's (:func:`swept_pto`), each
    case under its own key (``key(k)``): one PTO per study (every case that names one names
    the same, and with several PTOs every case names it), dampings ≥ 0."""
    carrying = [k for k, c in enumerate(cases) if any(_values(c).values())]
    if not carrying:
        return None
    first = {}
    for k in carrying:
        if names[k] is not None:
            first.setdefault(names[k], k)
    if len(first) > 1:
        (one, i), (other, j) = list(first.items())[:2]
        raise ArgumentError(
            f"{key(j)}: names the PTO {other!r}, cases[{i}] names {one!r}: "
            "one PTO is swept per study"
        )
    for k in carrying:
        check_damping([v for v in [cases[k].pto_damping] if v is not None], key(k))
    axes = [
        (axis, tuple(v for c in cases if (v := getattr(c, axis)) is not None))
        for axis in SWEEP_AXES
    ]
    named = next(iter(first), None)
    name = swept_pto([a for a in axes if a[1]], system, named, key(carrying[0]), "value")
    several = pto_names(system)
    for k in carrying:
        if len(several) > 1 and names[k] is None:
            axis = next(a for a, v in _values(cases[k]).items() if v)
            raise ArgumentError(
                f"{key(k)}.{axis}: the system has {len(several)} PTOs ({', '.join(several)}): "
                f"name the one, {axis}: {{{name}: value}}, as the other cases do"
            )
    return name


def _values(case: Any) -> dict[str, bool]:
    return {axis: getattr(case, axis) is not None for axis in SWEEP_AXES}


def with_own_values(cases: Sequence[Any], system: Any, name: str | None) -> tuple[Any, ...]:
    """The cases of a list with the values a case leaves out (of the sweep keys some case
    gives) set to the PTO ``name``'s own: each case's results record what it ran."""
    if name is None:
        return tuple(cases)
    own = system.ptos[pto_names(system).index(name)]
    given = [a for a in SWEEP_AXES if any(getattr(c, a) is not None for c in cases)]
    return tuple(
        replace(
            c, **{a: float(getattr(own, a[len("pto_") :])) for a in given if getattr(c, a) is None}
        )
        for c in cases
    )


def case_system(system: Any, name: str | None, damping: float | None, stiffness: float | None):
    """``system`` with the PTO ``name``'s damping and stiffness replaced by those given
    (None: its own); ``system`` itself when nothing is swept."""
    if name is None or (damping is None and stiffness is None):
        return system
    ptos = list(system.ptos)
    k = pto_names(system).index(name)
    values = {"damping": damping, "stiffness": stiffness}
    ptos[k] = replace(ptos[k], **{key: v for key, v in values.items() if v is not None})
    return replace(system, ptos=tuple(ptos))


def sweep_units(assembly: Any, name: str | None) -> dict[str, str]:
    """The units of the sweep axes for the PTO ``name`` of an assembled system."""
    if name is None:
        return {}
    line = next(p for p in assembly.ptos if p.name == name)
    return {axis: units[int(line.rotational)] for axis, units in SWEEP_AXES.items()}


def best_pto_damping(results: xr.Dataset) -> xr.Dataset:
    """``results`` with the best damping of a sweep (module docstring): per sea state
    ``pto_damping_best``, ``pto_mean_power_best`` (W, all PTOs) and
    ``pto_damping_best_at_edge``; with a scatter diagram over (hs, tp) also
    ``pto_mean_power_site`` (per damping), ``pto_damping_site_best``,
    ``pto_mean_power_site_best`` and ``pto_damping_site_best_at_edge``. The realisations
    (seeds) of a sea state are averaged first. ``results`` unchanged without a sweep; the
    results of a list of cases carrying their dampings get the attribute
    ``pto_damping_best_note`` (:data:`LIST_NOTE`) instead."""
    listed = "pto_damping" in results.coords and "pto_damping" not in results.dims
    if listed and "pto_mean_power" in results:
        return results.assign_attrs(pto_damping_best_note=LIST_NOTE)
    if "pto_damping" not in results.dims or "pto_mean_power" not in results:
        return results
    out = results.copy()
    total = results.pto_mean_power.sum("pto", min_count=1)
    if "seed" in total.dims:
        total = total.mean("seed")
    units = results.pto_damping.attrs.get("units", "")
    _add_best(out, total, "", "the sea state", units)
    if "probability" in results and set(results.probability.dims) == {"hs", "tp"}:
        site = (total * results.probability).sum(("hs", "tp"), min_count=1)
        out["pto_mean_power_site"] = site.assign_attrs(
            units="W",
            long_name="mean power absorbed by the PTOs over the scatter diagram "
            "(sum of probability x pto_mean_power over hs and tp)",
        )
        _add_best(out, site, "_site", "the site (scatter diagram)", units)
    return out


def _add_best(out: xr.Dataset, power: xr.DataArray, tag: str, what: str, units: str) -> None:
    k = power.fillna(-np.inf).argmax("pto_damping")
    values = out.pto_damping.values
    best = xr.DataArray(values[k.values], dims=k.dims, coords=k.coords)
    out[f"pto_damping{tag}_best"] = best.assign_attrs(
        units=units,
        long_name=f"the damping of the list with the largest mean absorbed power for {what}",
    )
    out[f"pto_mean_power{tag}_best"] = power.isel(pto_damping=k, drop=True).assign_attrs(
        units="W", long_name=f"mean power absorbed by the PTOs at pto_damping{tag}_best"
    )
    below = (best == values.min()) & (values.min() > 0)  # no damping below zero
    edge = below | (best == values.max())
    out[f"pto_damping{tag}_best_at_edge"] = edge.assign_attrs(
        long_name="the best damping is the smallest or largest of the list: the optimum "
        "may lie beyond it"
    )
