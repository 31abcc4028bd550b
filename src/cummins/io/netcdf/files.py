"""NetCDF files at the lowest level: recognising one, finding them in a folder, loading one.

Capytaine ≤ 2.x files are usually NetCDF-3 (``CDF\\x01``/``CDF\\x02``, read with SciPy);
newer ones and cummins' own files are NetCDF-4/HDF5 (h5netcdf). The engine is chosen from
the file's first bytes; CDF-5 is refused with a hint. :func:`merge_complex` joins the
``re``/``im`` parts NetCDF stores complex arrays as.
"""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from cummins.errors import HydroDataError
from cummins.files import note_read

_MAGIC_HDF5 = b"\x89HDF\r\n\x1a\n"
_MAGIC_CLASSIC = (b"CDF\x01", b"CDF\x02")
_MAGIC_CDF5 = b"CDF\x05"


def _magic(path: Path) -> bytes:
    with open(path, "rb") as f:
        return f.read(8)


def _engine(path: Path) -> str:
    """xarray engine for ``path`` from its first bytes; HydroDataError if not NetCDF."""
    try:
        head = _magic(path)
    except FileNotFoundError:
        raise HydroDataError("file not found", path=path) from None
    except IsADirectoryError:
        raise HydroDataError("expected a file, found a directory", path=path) from None
    except OSError as exc:
        raise HydroDataError(f"cannot read the file ({exc.strerror})", path=path) from None
    if not head:
        raise HydroDataError("the file is empty", path=path)
    if head.startswith(_MAGIC_HDF5):
        return "h5netcdf"
    if head[:4] in _MAGIC_CLASSIC:
        return "scipy"
    if head[:4] == _MAGIC_CDF5:
        raise HydroDataError(
            "NetCDF CDF-5 (64-bit data) files are not supported",
            path=path,
            hint="convert the file to NetCDF-4 (nccopy -k nc4 in.nc out.nc) or re-save it "
            "from xarray with engine='h5netcdf'",
        )
    raise HydroDataError(
        "not a NetCDF file (no NetCDF-3 or HDF5 signature)",
        path=path,
        hint="check the file name and format",
    )


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` a NetCDF file holding added mass and damping?"""
    path = Path(path)
    try:
        if _magic(path)[:4] == _MAGIC_CDF5:
            return True  # NetCDF all the same: read_netcdf says why it cannot read it
        engine = _engine(path)
    except (OSError, HydroDataError):
        return False
    try:
        if engine == "h5netcdf":
            import h5py

            with h5py.File(path, "r") as f:
                names = set(f.keys())
        else:
            with xr.open_dataset(path, engine="scipy", decode_cf=False) as ds:
                names = set(ds.variables)
    except Exception:  # any unreadable file is simply not ours
        return False
    return {"added_mass", "radiation_damping"} <= names


_PATTERNS = ("*.nc", "*.nc4", "*.NC")


def sniff_dir(path: Path) -> list[Path]:
    """The NetCDF hydrodynamic databases in a folder (``*.nc``, ``*.nc4``), one per run.

    When the folder itself holds none, its immediate sub-folders are searched: a
    Capytaine case folder keeps its results in ``outputs/`` (beside the legacy
    exporter's ``KH_*.dat`` and ``Hydrostatics_*.dat``), next to the script and meshes.
    """
    path = Path(path)
    found = _netcdf_files(path)
    if found or not path.is_dir():
        return found
    nested: list[Path] = []
    for sub in sorted(p for p in path.iterdir() if p.is_dir() and not p.name.startswith(".")):
        nested.extend(_netcdf_files(sub))
    return nested


def _netcdf_files(folder: Path) -> list[Path]:
    candidates = {p for pattern in _PATTERNS for p in folder.glob(pattern)}
    return sorted(p for p in candidates if p.is_file() and sniff(p))


def load_netcdf(path: Path) -> xr.Dataset:
    """Open a NetCDF file fully into memory; every failure becomes HydroDataError."""
    note_read(path)
    engine = _engine(path)
    try:
        if engine == "h5netcdf":
            import h5py

            with h5py.File(path, "r"):  # fail here, cleanly, on a damaged HDF5 file
                pass
        return xr.load_dataset(path, engine=engine)
    except HydroDataError:
        raise
    except Exception as exc:
        raise HydroDataError(
            f"cannot read the NetCDF file ({type(exc).__name__}: {exc})",
            path=path,
            hint="the file is truncated or damaged; write it again",
        ) from None


def merge_complex(ds: xr.Dataset, where: str | Path | None = None) -> xr.Dataset:
    """Join ``re``/``im`` parts along a ``complex`` dimension into complex arrays."""
    if "complex" not in ds.dims:
        return ds
    labels = [str(v) for v in ds["complex"].values] if "complex" in ds.coords else []
    if sorted(labels) != ["im", "re"]:
        raise HydroDataError(
            f"the 'complex' dimension must have the labels 're' and 'im', found {labels}",
            path=where,
        )
    out = ds.copy()
    for name, var in ds.data_vars.items():
        if "complex" in var.dims:
            value = var.sel(complex="re") + 1j * var.sel(complex="im")
            out[name] = value.drop_vars("complex", errors="ignore").assign_attrs(var.attrs)
    return out.drop_vars("complex")
