"""The infinite-frequency added mass A∞: the solver's ω = ∞ row, or Ogilvie's estimate
from A(ω) and B(ω).

A∞ = A(ω) + (1/ω) ∫₀^∞ K(t) sin(ωt) dt holds at every frequency (Ogilvie; de Haan (2022)
eq. 2.16, Unneland (2007) eq. 2.46). Evaluated through the Kramers–Kronig relation
(Hjulstad (2004) eq. 5.23) with the exact principal-value integral of the piecewise-linear
damping and its tail (:mod:`cummins.radiation.damping_tail`), it gives one estimate per
frequency; their median over the trusted frequencies is the estimate, half their
inter-quartile range its spread. The names are importable from
:mod:`cummins.radiation.retardation` as well.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.arrays import LastAnswer, digest
from cummins.errors import HydroDataError
from cummins.hydrodb import dof_matrix, single_speed
from cummins.radiation.damping_tail import kramers_kronig_integral


def coupling_coords(ds: xr.Dataset) -> dict:
    """The DOF coordinates of a matrix of couplings of ``ds`` (influenced, radiating)."""
    return {"influenced_dof": ds.influenced_dof.values, "radiating_dof": ds.radiating_dof.values}


#: The last answer of :func:`_kramers_kronig_integral` (read-only). A fit asks for the
#: same data's integral three times (Ogilvie's A∞, the causality of the data with the
#: model's A∞ before and after its refit).
_last_integral = LastAnswer()


def _kramers_kronig_integral(ds: xr.Dataset, tail: str) -> NDArray:
    """(2/π) PV ∫₀^∞ B(ν)/(ν² − ω²) dν at the data frequencies, shape (nω, n, n),
    read-only (the last data's kept: the same numbers for the same bytes)."""
    w = np.asarray(ds.omega.values, dtype=float)
    n = ds.sizes["influenced_dof"]
    b = dof_matrix(ds, "radiation_damping").reshape(w.size, n * n)
    a = dof_matrix(ds, "added_mass").reshape(w.size, n * n)
    key = digest(tail, w, b, a)
    kept = _last_integral.get(key)
    if kept is not None:
        return kept
    integral = kramers_kronig_integral(w, b, a, tail).reshape(w.size, n, n)
    integral.flags.writeable = False
    return _last_integral.keep(key, integral)


def added_mass_inf_per_frequency(ds: xr.Dataset, *, tail: str = "auto") -> xr.DataArray:
    """The Ogilvie estimate of A∞ at each frequency: A(ω) − (2/π) PV∫ B(ν)/(ν² − ω²) dν.

    This is A∞ = A(ω) + (1/ω) ∫₀^∞ K(t) sin(ωt) dt (de Haan (2022) eq. 2.16,
    Unneland (2007) eq. 2.46) evaluated in the frequency domain through the
    Kramers–Kronig relation (Hjulstad (2004) eq. 5.23), exactly for the piecewise-linear
    damping with its tail. For consistent data the result is the same at every
    frequency; its variation measures the data's inconsistency and the effect of the
    unknown tail (largest near the last frequency).
    """
    ds = single_speed(ds)
    values = dof_matrix(ds, "added_mass") - _kramers_kronig_integral(ds, tail)
    return xr.DataArray(
        values,
        dims=("omega", "influenced_dof", "radiating_dof"),
        coords={"omega": ds.omega, **coupling_coords(ds)},
        name="added_mass_inf",
        attrs={
            "units": ds.added_mass.attrs.get("units", ""),
            "long_name": "A(inf) estimated at each frequency",
        },
    )


def trusted_frequencies(ds: xr.Dataset) -> NDArray[np.bool_]:
    """Frequencies used to combine per-frequency estimates (mask over ``ds.omega``).

    Excludes the last frequency (where the estimate depends most on the unknown tail)
    and every frequency where a diagonal damping term is negative (irregular
    frequencies of panel methods), unless that would leave fewer than three.
    """
    ds = single_speed(ds)
    b = np.diagonal(dof_matrix(ds, "radiation_damping"), axis1=1, axis2=2)
    peak = np.abs(b).max(axis=0)
    negative = np.any(b < -1e-3 * peak, axis=1)
    keep = ~negative
    keep[-1] = False
    if keep.sum() < 3:
        keep = np.ones(ds.sizes["omega"], dtype=bool)
    return keep


def with_coupling_values(ds: xr.Dataset, name: str, values: NDArray) -> xr.Dataset:
    """``ds`` with the variable ``name`` (ω, influenced, radiating DOFs) holding ``values``
    given in that order, in the variable's own order of axes: an assign's dataset, without
    its merge (the other variables shared)."""
    dims = ds[name].dims
    order = [dims.index(d) for d in ("omega", "influenced_dof", "radiating_dof")]
    data = {key: var.values for key, var in ds.data_vars.items()}
    data[name] = np.transpose(values, np.argsort(order))
    return ds.copy(data=data)


def bridged_couplings(
    values: ArrayLike, omega: ArrayLike, kept: ArrayLike, *, from_zero: bool = False
) -> NDArray[np.float64]:
    """``values`` (omega, n, n) with each coupling (i, j) replaced, at the frequencies DOF i
    or j leaves out (``kept``: omega × DOF), by the linear interpolation of the points
    both keep; below the first kept point the first value holds, or with ``from_zero``
    the line from 0 at ω = 0 (the damping: then the same integral as without the points).
    A coupling whose DOFs keep no point is left as it is."""
    w = np.asarray(omega, dtype=float)
    kept = np.asarray(kept, dtype=bool)
    out = np.array(values, dtype=float, copy=True)
    start = np.zeros(1 if from_zero else 0)
    both = kept[:, :, None] & kept[:, None, :]
    grids: dict = {}  # the points both keep and those bridged, once for (i, j) and (j, i)
    for i, j in zip(*np.nonzero(both.any(axis=0) & ~both.all(axis=0)), strict=True):
        key = (min(i, j), max(i, j))
        if key not in grids:
            mask = both[:, i, j]
            grids[key] = (mask, ~mask, w[~mask], np.concatenate([start, w[mask]]))
        mask, gap, at, points = grids[key]
        out[gap, i, j] = np.interp(at, points, np.concatenate([start, out[mask, i, j]]))
    return out


def _added_mass_inf_matrix(ds: xr.Dataset) -> NDArray:
    if "added_mass_inf" in ds:
        return dof_matrix(ds, "added_mass_inf")
    return added_mass_inf(ds, method="ogilvie").values


def added_mass_inf(
    ds: xr.Dataset, method: str = "auto", *, tail: str = "auto", kept: ArrayLike | None = None
) -> xr.DataArray:
    """Infinite-frequency added mass A∞, from the data or estimated.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed.
    method
        ``"data"``: the solver's ω = ∞ row (error if absent); ``"ogilvie"``: the median
        over the trusted frequencies (:func:`trusted_frequencies`) of the Ogilvie
        estimate at each frequency (:func:`added_mass_inf_per_frequency`); ``"auto"``:
        the data row when present, else the estimate.
    tail
        Damping tail used by the estimate (see :func:`fit_damping_tail`).
    kept
        Optional (omega, dof) mask of the frequencies whose data each DOF keeps. Pair
        (i, j) then takes B_ij bridged linearly over the points either DOF leaves out
        (from B = 0 at ω = 0 below the first kept one: the same integral as without
        those points) and the median over the trusted frequencies both keep (all the
        trusted ones when fewer than three).

    Returns
    -------
    xarray.DataArray
        (influenced_dof, radiating_dof), with a coordinate ``spread`` of the same shape:
        half the inter-quartile range of the per-frequency estimates (same units; zero
        for the data row), and attribute ``method`` saying which was used.

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.demo_dataset().drop_vars("added_mass_inf")
    >>> a = cummins.added_mass_inf(ds)
    >>> a.attrs["method"]
    'ogilvie'
    """
    ds = single_speed(ds)
    if method not in ("auto", "data", "ogilvie"):
        raise HydroDataError(f"unknown method {method!r}", hint="use 'auto', 'data' or 'ogilvie'")
    if method == "data" or (method == "auto" and "added_mass_inf" in ds):
        if "added_mass_inf" not in ds:
            raise HydroDataError(
                "the data have no infinite-frequency added mass",
                path=ds.attrs.get("source_file"),
                hint="use method='ogilvie' to estimate it from A(ω) and B(ω)",
            )
        values = dof_matrix(ds, "added_mass_inf")
        spread = np.zeros_like(values)
        used = "data"
    else:
        if kept is not None:
            kept = np.asarray(kept, dtype=bool)
            damping = dof_matrix(ds, "radiation_damping")  # (omega, i, j) when canonical
            bridged = bridged_couplings(damping, ds.omega.values, kept, from_zero=True)
            ds = with_coupling_values(ds, "radiation_damping", bridged)
        curve = added_mass_inf_per_frequency(ds, tail=tail).values
        keep = trusted_frequencies(ds)
        values = np.median(curve[keep], axis=0)
        q75, q25 = np.percentile(curve[keep], [75, 25], axis=0)
        spread = 0.5 * (q75 - q25)
        pairs = np.ndindex(curve.shape[1:]) if kept is not None else ()
        for i, j in pairs:
            use = keep & kept[:, i] & kept[:, j]
            if 3 <= use.sum() < keep.sum():
                values[i, j] = np.median(curve[use, i, j])
                q75, q25 = np.percentile(curve[use, i, j], [75, 25])
                spread[i, j] = 0.5 * (q75 - q25)
        used = "ogilvie"
    return xr.DataArray(
        values,
        dims=("influenced_dof", "radiating_dof"),
        coords={**coupling_coords(ds), "spread": (("influenced_dof", "radiating_dof"), spread)},
        name="added_mass_inf",
        attrs={"method": used, "units": ds.added_mass.attrs.get("units", "")},
    )
