"""A PTO's damping (and stiffness) as axes of a batch study, and the best damping.

A study with a ``system:`` holding PTOs may sweep one PTO's damping c (N s/m, or N m s/rad
for a rotation) and stiffness k (N/m, N m/rad) as axes of its grid::

    grid: {heading: [180], hs: [1, 2], tp: [6, 8, 10], pto_damping: [1e5, 3e5, 1e6]}

With one PTO the axis is its own; with several, ``pto_damping: {float: [..]}`` names the
one swept (the others keep the values of their entries). Every case (sea state × damping)
is then solved with that PTO's values (:func:`case_system`): in the frequency domain its
own RAOs; in the time domain a vessel per value, all on the one radiation model fitted
before the cases (the fit does not depend on the PTO's values, only which motions it aims
at: it is made at the smallest damping of the sweep, the most resonant system).

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

from collections.abc import Mapping, Sequence
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


def pto_names(system: Any) -> list[str]:
    """The PTOs' names as results label them (``pto1``, ``pto2`` … when unnamed)."""
    if system is None:
        return []
    return [p.name or f"pto{k + 1}" for k, p in enumerate(system.ptos)]


def named_sweep(grid: Any, where: str) -> tuple[Any, str | None]:
    """``grid`` with a sweep axis written ``{pto name: [values]}`` made a plain list, and
    the PTO it names (None when no axis names one). ``where`` names the grid's key."""
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
                f"{where}.{axis}: name one PTO and its values, e.g. {axis}: {{pto1: [..]}}"
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


def swept_pto(grid: Sequence[tuple[str, tuple]], system: Any, named: str | None, where: str):
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
            f"the one swept, {axis}: {{{names[0]}: [..]}}"
        )
    name = named or names[0]
    if name not in names:
        raise ArgumentError(f"{where}.{axis}: no PTO {name!r}; the PTOs are {', '.join(names)}")
    negative = [v for v in axes.get("pto_damping", ()) if v < 0]
    if negative:
        raise ArgumentError(
            f"{where}.pto_damping: {negative[0]:g} is negative: a PTO's damping is >= 0 "
            "(it absorbs power)"
        )
    return name


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
    (seeds) of a sea state are averaged first. ``results`` unchanged without a sweep."""
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
