"""Writing NetCDF: a ``HydroDB`` in Capytaine's layout and conventions, any dataset safely.

:func:`to_capytaine_layout` gives the dataset as it is written (complex values conjugated
to Capytaine's e^{-iωt} and split into ``re``/``im``; ρ, g, depth and the rotation centre
as coordinates; attributes encoded, :mod:`cummins.io.netcdf.attributes`);
:func:`save_netcdf` writes any dataset to NetCDF-4 through a temporary file, with HDF5's
Fletcher-32 checksum on every numeric array.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from cummins._version import __version__
from cummins.errors import HydroDataError
from cummins.files import replacing
from cummins.hydrodb import bodies, validate
from cummins.io.netcdf.attributes import FILE_TIME_CONVENTION, VERSION_ATTR, encode_attributes


def to_capytaine_layout(ds: xr.Dataset) -> xr.Dataset:
    """The dataset as it is written to NetCDF: Capytaine's layout and conventions.

    Complex arrays are conjugated (e^{+iωt} → e^{-iωt}) and split along a leading
    ``complex`` dimension (``re``, ``im``); ``rho``, ``g``, ``water_depth`` become scalar
    coordinates; the reference point is also stored as Capytaine's ``rotation_center``.
    """
    validate(ds)
    out = xr.Dataset()
    has_complex = False
    for name, var in ds.data_vars.items():
        attrs = encode_attributes(var.attrs)
        if np.iscomplexobj(var.values):
            has_complex = True
            value = np.conj(var.values)
            out[name] = xr.DataArray(
                np.stack([value.real, value.imag]), dims=("complex", *var.dims), attrs=attrs
            )
        else:
            out[name] = xr.DataArray(var.values, dims=var.dims, attrs=attrs)
    for name, coord in ds.coords.items():
        out.coords[name] = xr.Variable(coord.dims, coord.values, encode_attributes(coord.attrs))
    if has_complex:
        out.coords["complex"] = ("complex", ["re", "im"])
    for key in ("rho", "g", "water_depth"):
        out.coords[key] = float(ds.attrs[key])
    point = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float)
    names = bodies(ds)
    if point.size == 3:
        out.coords["rotation_center"] = ("space_coordinate", point.reshape(3))
    elif point.size == 3 * len(names):
        out.coords["rotation_center"] = (("body", "space_coordinate"), point.reshape(-1, 3))
        out.coords["body"] = ("body", [str(b) for b in names])
    out.coords["space_coordinate"] = ("space_coordinate", ["x", "y", "z"])
    attrs = {k: v for k, v in ds.attrs.items() if k not in ("rho", "g", "water_depth")}
    attrs["time_convention"] = FILE_TIME_CONVENTION
    attrs[VERSION_ATTR] = __version__
    out.attrs = encode_attributes(attrs)
    return out


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write a ``HydroDB`` to NetCDF-4 in Capytaine's layout (see the module docstring).

    The data are written in the dataset's axes (attribute ``axis_convention``);
    Capytaine's are z-up, so convert a z-down (MSS) dataset with
    :func:`cummins.change_axes` first if the file is meant for Capytaine users.

    The file is written to a temporary name first and then renamed, so a failure
    leaves no half-written file. An existing file is replaced: use
    :func:`cummins.write` (``force=``) for the overwrite check.

    Parameters
    ----------
    ds
        A valid ``HydroDB``.
    path
        Output file (``.nc``).

    Returns
    -------
    Path
        ``path``.
    """
    return save_netcdf(to_capytaine_layout(ds), path)


def save_netcdf(ds: xr.Dataset, path: str | os.PathLike[str], *, checksum: bool = True) -> Path:
    """Write ``ds`` (h5netcdf) to a temporary file of its own, then rename it to ``path``
    (:func:`cummins.files.replacing`): a failure leaves no half-written file. No overwrite
    check (the callers do it).

    With ``checksum`` every numeric array carries HDF5's Fletcher-32 checksum filter
    (a standard HDF5 filter that netCDF-C, h5py and MATLAB read transparently), so a
    damaged copy is refused on reading instead of giving different numbers."""
    path = Path(path)
    encoding = _checksum_encoding(ds) if checksum else None
    try:
        with replacing(path) as tmp, warnings.catch_warnings():
            warnings.simplefilter("ignore", category=FutureWarning)
            _to_h5netcdf(ds, tmp, encoding)
    except OSError as exc:
        raise HydroDataError(f"cannot write the file ({exc})", path=path) from None
    return path


def _to_h5netcdf(ds: xr.Dataset, path: Path, encoding: dict | None) -> None:
    """``ds.to_netcdf(path, engine="h5netcdf", encoding=encoding)``. An in-memory dataset
    (no dask chunks) goes to xarray's h5netcdf store directly (``Dataset.dump_to_store``,
    what ``to_netcdf`` does for it), under HDF5's process lock only: ``to_netcdf`` and the
    store's default write lock first ask dask which scheduler runs, which imports
    dask.distributed — a quarter of a second of every command that writes a file, when
    dask is installed."""
    if any(v.chunks is not None for v in ds.variables.values()):
        ds.to_netcdf(path, engine="h5netcdf", encoding=encoding)
        return
    from xarray.backends import H5NetCDFStore
    from xarray.backends.locks import HDF5_LOCK

    unlimited = ds.encoding.get("unlimited_dims")
    store = H5NetCDFStore.open(path, mode="w", lock=HDF5_LOCK)
    try:
        ds.dump_to_store(
            store,
            encoding=encoding or {},
            unlimited_dims={unlimited} if isinstance(unlimited, str) else unlimited,
        )
    finally:
        store.close()


def _checksum_encoding(ds: xr.Dataset) -> dict[str, dict[str, Any]]:
    """Fletcher-32 for every non-scalar numeric variable (HDF5 filters need chunks)."""
    encoding: dict[str, dict[str, Any]] = {}
    for name, var in ds.variables.items():
        if var.ndim >= 1 and var.size > 0 and var.dtype.kind in "biufc":
            encoding[str(name)] = {"fletcher32": True}
    return encoding
