"""The mean drift in a BEMIO ``.h5``: where WEC-Sim's layout has a place for it.

WEC-Sim's ``writeBEMIOH5.m`` stores the mean drift of each method a run computed as
``body<k>/hydro_coeffs/mean_drift/{control_surface,momentum_conservation,
pressure_integration}/val``, shaped like the excitation (DOF × direction × frequency in
MATLAB's order) and normalised by ρ g; ``readBEMIOH5.m`` takes ``control_surface``
(``meanDriftForce = 1``) or ``momentum_conservation`` (``= 2``) and its ``bodyClass``
multiplies by ρ g. Each of cummins' ``drift_force`` and ``drift_force_<method>`` goes to
the group of its method; a mean drift of no WAMIT method (AQWA's listing, MSS,
Capytaine's far field) goes to ``momentum_conservation`` when it is a far-field estimate,
else to ``control_surface``, with its true method in the ``description`` attribute.

WEC-Sim's QTF datasets (``excitation/QTF<k>/Diff<dof>`` …, written by newer BEMIO and not
read by ``readBEMIOH5.m``) are not written: the QTFs travel in the file's exact cummins
copy group, which :func:`cummins.read` restores.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import xarray as xr

from cummins.qtf.data import DRIFT_ALTERNATIVES

_GROUPS = {
    "control surface": "control_surface",
    "pressure integration": "pressure_integration",
    "momentum": "momentum_conservation",
    "far field": "momentum_conservation",
}


def _group(method: str, taken: set[str]) -> str:
    for key, group in _GROUPS.items():
        if key in method and group not in taken:
            return group
    return "control_surface" if "control_surface" not in taken else "pressure_integration"


def write_mean_drift(
    number: Callable, prefix: str, ds: xr.Dataset, rows: slice, rho: float, g: float
) -> None:
    """Write the mean-drift estimates of ``ds`` (its DOFs ``rows`` of one body) under
    ``prefix`` (``body<k>/hydro_coeffs``) with the BEMIO writer's ``number`` function."""
    taken: set[str] = set()
    for name in ("drift_force", *DRIFT_ALTERNATIVES):
        if name not in ds:
            continue
        method = str(ds[name].attrs.get("method", "mean drift"))
        group = _group(method, taken)
        if group in taken:
            continue
        taken.add(group)
        values = ds[name].transpose("omega", "wave_direction", "influenced_dof").values
        number(
            f"{prefix}/mean_drift/{group}/val",
            np.transpose(values[:, :, rows], (2, 1, 0)) / (rho * g),
            f"Value of mean drift force ({method}; normalized by rho*g, per squared wave "
            "amplitude)",
            "",
        )
