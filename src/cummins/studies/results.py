"""The results file of a batch study: NetCDF or Zarr, written and read back.

:func:`write_results` writes what :func:`cummins.studies.batch.gather_results` gathered,
:func:`load_results` reads it (refusing a file that is not a study's results) and
:func:`is_results` tells a Dataset of results from other files (``cummins report``).
"""

from __future__ import annotations

import os
import shutil
import warnings
from pathlib import Path

import xarray as xr

from cummins.errors import CumminsError, check_writable
from cummins.studies.study import _RESULT_KIND, StudyError

__all__ = ["is_results", "load_results", "write_results"]


def write_results(results: xr.Dataset, path: str | os.PathLike[str], *, force: bool = False):
    """Write gathered results as NetCDF, or Zarr when ``path`` ends in ``.zarr``."""
    path = Path(path)
    check_writable(path, force)
    out = results.copy()
    for name in ("case_id",):
        out[name] = out[name].astype(str)
    if path.suffix.lower() == ".zarr":
        try:
            import zarr  # noqa: F401
        except ImportError:
            raise CumminsError("writing Zarr needs the zarr package: pip install zarr") from None
        if path.exists():
            shutil.rmtree(path)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # zarr's notes on its format-3 specification
            out.to_zarr(path, mode="w", zarr_format=2, consolidated=True)
        return path
    from cummins.io.netcdf import save_netcdf

    return save_netcdf(out, path)


def load_results(path: str | os.PathLike[str]) -> xr.Dataset:
    """Read results written by :func:`run_study` (NetCDF or Zarr)."""
    path = Path(path)
    try:
        if path.suffix.lower() == ".zarr":
            ds = xr.open_zarr(path).load()
        else:
            with xr.open_dataset(path, engine="h5netcdf") as f:
                ds = f.load()
    except (OSError, ValueError) as exc:
        raise StudyError(f"{path}: cannot read the results ({exc})") from None
    if ds.attrs.get("cummins_kind") != _RESULT_KIND:
        raise StudyError(f"{path}: not the results of a cummins batch study")
    return ds


def is_results(ds: xr.Dataset) -> bool:
    """True for a Dataset of batch results."""
    return ds.attrs.get("cummins_kind") == _RESULT_KIND
