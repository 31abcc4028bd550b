"""What the checks share: their relative tolerances and the per-DOF, per-speed helpers.

The tolerances are relative (dimensionless); the helpers scale a matrix by its diagonal
(D^{-1/2} X D^{-1/2}, D = peak |X_ii|), list the DOF labels and split a dataset into its
forward speeds.
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

if TYPE_CHECKING:
    from cummins.radiation.fit.data import FitInput
    from cummins.repair import Judged

#: Relative tolerances of the checks.
SYMMETRY_TOL = 0.02
NEGATIVE_DAMPING_TOL = 1e-3
DECAY_TOL = 0.05
LOW_FREQUENCY_TOL = 0.2  # |B_ii(ω_min)| / peak
K_END_TOL = 0.05  # |K(t_max)| / max|K|
K_INTEGRAL_TOL = 0.1  # |∫K dt| / ∫|K| dt
TAIL_TOL = 0.2  # share of ∫B dω in the extrapolated tail
A_INF_TOL = 0.05  # relative spread, or distance from the data row
KK_TOL = 0.1  # relative Kramers-Kronig error
PARITY_TOL = 0.05  # |F(β) − T F(−β)| / max|F| of a DOF, port/starboard symmetric body


def _diag_scale(values: np.ndarray) -> np.ndarray:
    """1/√(peak |X_ii|) per DOF (1 where the DOF is identically zero)."""
    peak = np.max(
        np.abs(np.diagonal(values, axis1=-2, axis2=-1)).reshape(-1, values.shape[-1]), axis=0
    )
    with np.errstate(divide="ignore"):
        scale = np.where(peak > 0, 1.0 / np.sqrt(peak), 0.0)
    return scale


def _labels(ds: xr.Dataset) -> list[str]:
    return [str(d) for d in ds.influenced_dof.values]


def _speeds(ds: xr.Dataset) -> list[xr.Dataset]:
    if "forward_speed" in ds.dims:
        return [ds.isel(forward_speed=k) for k in range(ds.sizes["forward_speed"])]
    return [ds]


def _speed_suffix(ds: xr.Dataset) -> str:
    """`` at U = … m/s`` for a slice at non-zero forward speed, else empty."""
    if "forward_speed" in ds.coords and ds.forward_speed.ndim == 0 and float(ds.forward_speed):
        return f" at U = {float(ds.forward_speed):g} m/s"
    return ""


class PreparedFits:
    """:func:`cummins.radiation.fit.data.prepare_fit` of each forward speed's data with the
    default options, once for every check that reads it (the reciprocity and the forbidden
    couplings: twice 0.15 s on WEC-Sim's RM3, 12 DOFs), its warnings silenced; None where
    the data cannot be fitted (other checks say why). ``judged``: each speed's suspect
    frequencies, found once (:func:`cummins.repair.suspects_by_dof`)."""

    def __init__(self, judged: Judged = ()):
        self.judged = judged
        self._done: list[tuple[xr.Dataset, FitInput | None]] = []

    def __call__(self, ds: xr.Dataset) -> FitInput | None:
        from cummins.errors import CumminsError
        from cummins.radiation.fit.data import prepare_fit
        from cummins.radiation.fit.options import DEFAULT

        for data, found in self._done:
            if data is ds or data.identical(ds):
                return found
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                found = prepare_fit(ds, DEFAULT.checked(), judged=self.judged)
        except (CumminsError, ValueError, ArithmeticError):
            found = None
        self._done.append((ds, found))
        return found
