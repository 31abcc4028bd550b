"""Leaving out the hydrodynamic interaction between bodies (WEC-Sim's default).

A multi-body BEM run gives the radiation coefficients of every pair of DOFs, including
the force on one body due to the motion of another (A_ij(ω), B_ij(ω) with i and j on
different bodies). WEC-Sim leaves these out unless body-to-body interaction is switched
on (``simu.b2b = 1``); to compare with it, :func:`without_body_coupling` sets them to
zero in A(ω), B(ω), A∞ and A(0) — before any fit and frequency-domain solve. The
excitation and the hydrostatics of each body are kept: the diffraction of the waves by
the other bodies stays in the excitation force, as it does in WEC-Sim. The complete
physics keeps the coupling (the default everywhere).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.dofs import split_dof
from cummins.hydrodb import add_history

#: The radiation variables whose cross-body terms are left out.
RADIATION_VARIABLES = ("added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero")


def cross_body_mask(labels) -> np.ndarray:
    """(n, n) True where the two DOFs belong to different bodies."""
    owner = [split_dof(str(label))[0] for label in labels]
    return np.array([[a != b for b in owner] for a in owner], dtype=bool)


def without_body_coupling(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with the radiation coupling between bodies set to zero (module docstring).

    Returns a copy; ``history`` and the attribute ``body_coupling = "off"`` say so. A
    single body is returned unchanged (but for the attribute).
    """
    labels = [str(d) for d in ds.influenced_dof.values]
    mask = cross_body_mask(labels)
    out = ds.copy()
    out.attrs["body_coupling"] = "off"
    if not mask.any():
        return out
    keep = xr.DataArray(
        ~mask,
        dims=("influenced_dof", "radiating_dof"),
        coords={"influenced_dof": labels, "radiating_dof": labels},
    )
    changed = []
    for name in RADIATION_VARIABLES:
        if name in out and {"influenced_dof", "radiating_dof"} <= set(out[name].dims):
            out[name] = out[name].where(keep, 0.0).transpose(*ds[name].dims)
            out[name].attrs = dict(ds[name].attrs)
            changed.append(name)
    add_history(
        out,
        "radiation coupling between bodies left out (zero cross-body "
        + ", ".join(changed)
        + "), as WEC-Sim does by default",
    )
    return out
