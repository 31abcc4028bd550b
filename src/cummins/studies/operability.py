"""Operability: response limits applied to the statistics of a batch study.

A criterion (:class:`cummins.studies.study.Limit`) bounds one statistic of one DOF: the
significant single amplitude 2√m₀ (``significant``) or the maximum (``max``: most probable
maximum in the frequency domain, observed maximum in the time domain), in m or rad.

* :func:`exceedance` adds to the results, per case and criterion, the ratio
  response/limit (``limit_ratio``) and whether it exceeds 1 (``limit_exceeded``), and per
  case whether every criterion holds (``operable``).
* :func:`operability` is the fraction of the sea states in which the vessel is operable,
  per heading: the sea states (H_s, T_p and, when they vary, γ and spreading) weighted by
  the study's scatter diagram (``probability``), equally without one. A sea state with
  several realisations (seeds) counts as operable only when all of them are.
* :func:`limiting_hs` is the largest H_s meeting every criterion per heading and T_p: the
  responses are linear in the wave height (the same seed gives the same phases), so each
  case gives H_s / max(response/limit) exactly; the smallest over H_s, γ, spreading and
  seeds is taken.

A PTO sweep's axes (``pto_damping``, ``pto_stiffness``: :mod:`cummins.studies.pto_sweep`)
are of the design, not of the sea: both are given per value of them.

Examples
--------
>>> import numpy as np, xarray as xr
>>> from cummins.studies.study import Limit
>>> stats = xr.Dataset(
...     {"significant_amplitude": (("hs", "dof"), [[0.5], [1.5]]),
...      "maximum": (("hs", "dof"), [[1.0], [3.0]])},
...     coords={"hs": [1.0, 3.0], "dof": ["Heave"]})
>>> out = exceedance(stats, [Limit("Heave", "significant", 1.0, "1 m")])
>>> out.operable.values.tolist(), out.limit_ratio.values[:, 0].tolist()
([True, False], [0.5, 1.5])
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd
import xarray as xr

__all__ = [
    "beyond_grid_note",
    "exceedance",
    "limiting_hs",
    "limiting_hs_text",
    "operability",
    "sea_states",
]

#: Case axes that describe a sea state (the rest, ``seed``, are realisations of it).
SEA_KEYS = ("heading", "gamma", "spreading", "hs", "tp")
#: Case axes of the design (a PTO sweep): operability and limiting H_s are given per value.
DESIGN_KEYS = ("pto_damping", "pto_stiffness")


def exceedance(results: xr.Dataset, limits: Sequence) -> xr.Dataset:
    """``results`` with ``limit_ratio``, ``limit_exceeded`` (…, criterion) and ``operable``.

    Parameters
    ----------
    results
        Statistics per case and ``dof``: ``significant_amplitude`` and ``maximum`` (m, rad).
    limits
        :class:`cummins.studies.study.Limit` criteria (SI values). With none, every case is
        operable and the criterion dimension is empty.
    """
    from cummins.studies.study import STATISTICS

    out = results.drop_vars(
        [v for v in ("limit_ratio", "limit_exceeded", "operable") if v in results]
        + [c for c in results.coords if str(c).startswith("criterion")]
    )
    case_dims = [d for d in results.significant_amplitude.dims if d != "dof"]
    ratios = [
        results[STATISTICS[lim.statistic]].sel(dof=lim.dof, drop=True) / lim.value for lim in limits
    ]
    if ratios:
        ratio = xr.concat(ratios, dim="criterion").transpose(*case_dims, "criterion")
    else:
        shape = [results.sizes[d] for d in case_dims]
        ratio = xr.DataArray(
            np.zeros((*shape, 0)),
            dims=(*case_dims, "criterion"),
            coords={d: results[d] for d in case_dims if d in results.coords},
        )
    ratio = ratio.assign_coords(
        criterion=("criterion", [lim.label for lim in limits]),
        criterion_dof=("criterion", [lim.dof for lim in limits]),
        criterion_statistic=("criterion", [lim.statistic for lim in limits]),
        criterion_limit=("criterion", np.array([lim.value for lim in limits], dtype=float)),
        criterion_text=("criterion", [lim.text for lim in limits]),
    )
    out["limit_ratio"] = ratio
    out.limit_ratio.attrs = {"long_name": "response / limit", "units": "1"}
    out["limit_exceeded"] = ratio > 1.0
    out["operable"] = (ratio <= 1.0).all("criterion")
    out.operable.attrs["long_name"] = "every criterion holds"
    return out


def _case_table(results: xr.Dataset) -> pd.DataFrame:
    """One row per case: its axes, ``operable``, the worst ratio and the probability."""
    table = xr.Dataset(
        {
            "operable": results.operable,
            "ratio": results.limit_ratio.max("criterion")
            if results.sizes.get("criterion", 0)
            else xr.zeros_like(results.operable, dtype=float),
        }
    )
    if "probability" in results:
        table["probability"] = results.probability.broadcast_like(results.operable)
    else:
        table["probability"] = xr.ones_like(results.operable, dtype=float)
    frame = table.to_dataframe().reset_index()
    for key in ("gamma", "spreading"):  # a list study's missing values: one group
        if key in frame:
            frame[key] = frame[key].fillna(-1.0)
    return frame


def sea_states(results: xr.Dataset) -> pd.DataFrame:
    """One row per sea state (the cases merged over their seeds): ``operable`` (all
    seeds), the worst ``ratio``, its ``probability``; indexed by the sea-state keys."""
    frame = _case_table(results)
    keys = [k for k in (*SEA_KEYS, *DESIGN_KEYS) if k in frame]
    return frame.groupby(keys).agg(
        operable=("operable", "all"), ratio=("ratio", "max"), probability=("probability", "max")
    )


def operability(results: xr.Dataset) -> xr.DataArray:
    """Fraction of the sea states (weighted by ``probability``) in which every criterion
    holds, per heading, 0 to 1. The sea states are the study's (H_s, T_p, γ, spreading)
    combinations; their realisations (seeds) must all meet the criteria."""
    states = sea_states(results).reset_index()
    by = [states[k] for k in ("heading", *DESIGN_KEYS) if k in states]
    grouped = (states.probability * states.operable).groupby(by).sum() / (
        states.probability.groupby(by).sum()
    )
    out = grouped.to_xarray().rename("operability")
    out.heading.attrs["units"] = "deg"
    out.attrs = {
        "units": "1",
        "long_name": "operability: share of the sea states meeting every criterion",
        "weights": "scatter diagram" if "probability" in results else "equal",
    }
    return out


def limiting_hs(results: xr.Dataset) -> xr.DataArray:
    """Largest H_s meeting every criterion per heading and T_p, m, within the H_s computed.

    The responses are linear in the wave height: a case with worst ratio r at H_s gives
    H_s / r; the smallest over the H_s values, γ, spreading and seeds is the limit. A
    limit above the largest H_s computed at that heading and T_p is not extrapolated: the
    value is that H_s (a lower bound: every sea state computed meets the criteria) and the
    coordinate ``beyond_grid`` is True — "> 4 m (beyond the grid)", never 132 m from a
    linear scaling far outside the study (without limits: every entry).
    """
    states = sea_states(results).reset_index()
    with np.errstate(divide="ignore"):
        scaled = pd.Series(states.hs.to_numpy() / states.ratio.to_numpy())
    groups = [states[k] for k in ("heading", "tp", *DESIGN_KEYS) if k in states]
    limit = scaled.groupby(groups).min().to_xarray()
    top = states.hs.groupby(groups).max().to_xarray()
    beyond = limit > top
    out = limit.where(~beyond, top).rename("limiting_hs")
    out = out.assign_coords(beyond_grid=beyond)
    out.heading.attrs["units"] = "deg"
    out.tp.attrs["units"] = "s"
    out.beyond_grid.attrs["long_name"] = (
        "the limit is above the largest Hs computed (limiting_hs holds that Hs, a lower bound)"
    )
    out.attrs = {
        "units": "m",
        "long_name": "limiting significant wave height (linear scaling of the responses, "
        "within the Hs computed)",
        "hs_max": float(states.hs.max()),
    }
    return out


def limiting_hs_text(value: float, beyond: bool) -> str:
    """A limiting H_s as a table prints it: "2.31", or "> 4" beyond the grid (with
    :func:`beyond_grid_note` under the table)."""
    if not np.isfinite(value):
        return "-"
    return f"> {value:.3g}" if beyond else f"{value:.3g}"


def beyond_grid_note(lim: xr.DataArray) -> str:
    """The note under a table of :func:`limiting_hs` with entries beyond the grid, or ""."""
    beyond = lim.beyond_grid.values.astype(bool)
    if not beyond.any():
        return ""
    top = float(np.nanmax(lim.values[beyond]))
    return (
        f"> {top:.3g} m: beyond the grid — every sea state computed, up to Hs {top:.3g} m, "
        "meets the criteria; the limit is not extrapolated beyond it"
    )
