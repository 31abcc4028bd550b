"""The table "Statistics per case" of a batch study's report (:mod:`cummins.cli.html_report`)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.cli.html_page import _note, table_html
from cummins.hydrodb import is_rotation


def cases_body(results: xr.Dataset, most: int = 40) -> str:
    """One row per case: its axes (every one: heading, hs, tp, γ, spreading, seed, a PTO's
    damping or stiffness, in their units), the significant amplitude per DOF and, with
    limits, the worst response/limit ratio; the ``most`` worst cases if there are more
    (without limits: the first ``most``)."""
    dims = list(results.operable.dims)
    has_limits = results.sizes.get("criterion", 0) > 0
    if not has_limits:  # a study without limits: its criterion variables are empty
        results = results.drop_dims("criterion", errors="ignore")
    stacked = results.stack(_row=dims) if len(dims) > 1 else results.rename({dims[0]: "_row"})
    n = stacked.sizes["_row"]
    worst = stacked.limit_ratio.max("criterion").values if has_limits else np.zeros(n)
    order = np.argsort(-worst, kind="stable")[:most] if n > most else np.arange(n)
    # the axes: the levels of the stacked grid, or the coordinates of a list of cases
    keys = [
        k for k, c in stacked.coords.items() if c.dims == ("_row",) and k not in ("_row", "case")
    ]
    dofs = [str(d) for d in results.dof.values]
    header = [
        f"{k} [{stacked[k].attrs['units']}]" if "units" in stacked[k].attrs else k for k in keys
    ]
    header += [f"{d} 2σ [{'deg' if is_rotation(d) else 'm'}]" for d in dofs]
    header += ["worst ratio", "operable"] if has_limits else []
    rows, classes = [], []
    for k in order:
        case = stacked.isel(_row=int(k))
        sig = case.significant_amplitude.values
        values = [float(case[key].values) for key in keys]
        values += [
            float(np.degrees(s) if is_rotation(d) else s) for d, s in zip(dofs, sig, strict=True)
        ]
        cls = [""] * len(values)
        if has_limits:
            ok = bool(case.operable.values)
            values += [float(worst[k]), ok]
            cls += ["", "good" if ok else "bad"]
        rows.append(values)
        classes.append(cls)
    if n <= most:
        intro = f"All {n} cases."
    elif has_limits:
        intro = f"The {most} cases with the largest response/limit ratio of {n}."
    else:
        intro = f"The first {most} cases of {n} (no limits to rank them by)."
    intro += " 2σ: significant single amplitude (2√m0 in the frequency domain)."
    return _note(intro) + table_html(header, rows, classes=classes)
