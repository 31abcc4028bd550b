"""Second-order data in NetCDF: cummins' QTF variables and Capytaine's far-field drift.

A cummins file stores ``qtf_difference`` / ``qtf_sum`` as the other complex variables:
conjugated to Capytaine's e^{−iωt} and split along ``complex`` (``re``, ``im``), on their
own coordinates ``qtf_omega``, ``qtf_omega2``, ``qtf_wave_direction`` (and
``qtf_wave_direction2``); reading conjugates them back (:func:`restore_second_order`).

Capytaine (3.0, ``capytaine.post_pro.far_field_mean_drift_force``) computes the
horizontal mean drift by the far-field (momentum) method as ``drift_force_surge``,
``drift_force_sway`` and ``drift_force_yaw`` with dims (``omega``, ``wave_direction_k``,
``wave_direction_l``) — the mean force of two waves of one frequency and directions
β_k, β_l — or merged as ``drift_force`` with ``influenced_dof`` (Surge, Sway, Yaw). A
Capytaine file that holds them gives ``drift_force`` (β_k = β_l, real part; heave, roll
and pitch are not computed by the method: zero, said in ``history``)
(:func:`capytaine_drift`). No corpus Capytaine file holds them.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.qtf.data import (
    DIRECTION,
    DIRECTION2,
    OMEGA,
    QTF_VARIABLES,
    QTFTable,
    with_second_order,
)

_CAPYTAINE_DRIFT = {
    "drift_force_surge": "Surge",
    "drift_force_sway": "Sway",
    "drift_force_yaw": "Yaw",
}


def restore_second_order(out: xr.Dataset, raw: xr.Dataset, where=None) -> xr.Dataset:
    """``out`` with the QTFs of a cummins NetCDF ``raw`` (complex values merged, in
    Capytaine's e^{−iωt}: conjugated back)."""
    tables = []
    for kind, name in QTF_VARIABLES.items():
        if name not in raw.data_vars:
            continue
        var = raw[name]
        order = [OMEGA, "qtf_omega2", DIRECTION, DIRECTION2, "influenced_dof"]
        if not set(var.dims) <= set(order) or not np.iscomplexobj(var.values):
            raise HydroDataError(f"{name} has dims {var.dims}, not a cummins QTF", path=where)
        var = var.transpose(*[d for d in order if d in var.dims])
        labels = [str(d) for d in var.influenced_dof.values]
        if labels != [str(d) for d in out.influenced_dof.values]:
            raise HydroDataError(f"{name} has other DOFs than the data", path=where)
        tables.append(
            QTFTable(
                kind,
                np.asarray(var[OMEGA].values, dtype=float),
                np.asarray(var[DIRECTION].values, dtype=float),
                np.conj(np.asarray(var.values, dtype=complex)),
                tuple(labels),
                DIRECTION2 in var.dims,
            )
        )
    if not tables:
        return out
    return with_second_order(out, tables)


def capytaine_drift(out: xr.Dataset, raw: xr.Dataset, where=None) -> xr.Dataset:
    """``out`` with ``drift_force`` from Capytaine's far-field drift variables of ``raw``
    (module docstring); ``out`` itself when there are none."""
    parts = {dof: raw[name] for name, dof in _CAPYTAINE_DRIFT.items() if name in raw.data_vars}
    merged = raw.get("drift_force")
    if not parts and merged is not None and "wave_direction_k" in merged.dims:
        parts = {str(d): merged.sel(influenced_dof=d) for d in merged.influenced_dof.values}
    if not parts:
        return out
    if "drift_force" in out:
        return out
    labels = [str(d) for d in out.influenced_dof.values]
    if "wave_direction" not in out.dims:
        raise HydroDataError(
            "the file has Capytaine's mean drift but no wave_direction of its own", path=where
        )
    beta = out.wave_direction.values
    values = np.zeros((out.sizes["omega"], beta.size, len(labels)))
    for dof, var in parts.items():
        if dof not in labels or not {"omega", "wave_direction_k", "wave_direction_l"} <= set(
            var.dims
        ):
            raise HydroDataError(
                f"Capytaine's mean drift of {dof} does not fit the data", path=where
            )
        k = np.asarray(var["wave_direction_k"].values, dtype=float)
        for b, direction in enumerate(beta):
            hit = np.flatnonzero(np.isclose(k, direction, atol=1e-9))
            if hit.size != 1:
                raise HydroDataError(
                    f"Capytaine's mean drift has no wave direction {np.degrees(direction):g} deg",
                    path=where,
                )
            diag = var.isel(wave_direction_k=hit[0]).sel(
                wave_direction_l=var["wave_direction_l"].values[hit[0]]
            )
            w = np.asarray(diag["omega"].values, dtype=float)
            keep = np.isin(np.round(w, 12), np.round(out.omega.values, 12))
            if keep.sum() != out.sizes["omega"]:
                raise HydroDataError(
                    "Capytaine's mean drift is not on the data's frequencies", path=where
                )
            values[:, b, labels.index(dof)] = np.real(np.asarray(diag.values)[keep])
    missing = [d for d in labels if d not in parts]
    note = (
        "drift_force from Capytaine's far-field mean drift ("
        + ", ".join(parts)
        + ")"
        + (f"; {', '.join(missing)} not computed by it: 0" if missing else "")
    )
    return with_second_order(
        out,
        drift={"drift_force": (values, "far field (momentum), Capytaine")},
        history=[note],
        attrs={"drift_force": {"dofs_computed": " ".join(parts)}},
    )
