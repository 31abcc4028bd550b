"""BEMIO ``.h5`` files at the lowest level: recognising one, and checked access to its datasets.

A BEMIO file is HDF5 with the groups ``simulation_parameters`` and ``body1/hydro_coeffs``
(a NetCDF-4 file is HDF5 too, but has neither). The accessors read one dataset as a
number, vector, text or array of a known shape, refusing what no solver writes (a
non-finite value, or one beyond ``_IMPLAUSIBLE``) with the dataset's name.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError

_MAGIC_HDF5 = b"\x89HDF\r\n\x1a\n"
#: Values beyond this (SI units, or normalised by ρ, ρg) are damaged numbers.
_IMPLAUSIBLE = 1e25
#: Group holding cummins' exact copy of the dataset in files cummins writes.
COPY_GROUP = "cummins"


def sniff(path: Path) -> bool:
    """Content-based test: an HDF5 file with BEMIO's ``simulation_parameters`` and
    ``body1/hydro_coeffs`` groups (a NetCDF-4 file is HDF5 too, but has neither)."""
    try:
        with open(path, "rb") as f:
            if f.read(8) != _MAGIC_HDF5:
                return False
        import h5py

        with h5py.File(path, "r") as f:
            return "simulation_parameters" in f and "body1/hydro_coeffs" in f
    except Exception:  # any unreadable file is simply not ours
        return False


def sniff_dir(path: Path) -> list[Path]:
    """The BEMIO files of a folder, one per run.

    BEMIO names its file after the solver run it processed (``oswec.out`` →
    ``oswec.h5``): an ``.h5`` beside a file of the same name is a processed copy of
    that run, and the folder reads as the solver's output (give the ``.h5`` itself to
    read it).
    """
    path = Path(path)
    out = []
    for candidate in sorted({*path.glob("*.h5"), *path.glob("*.H5")}):
        if not candidate.is_file() or not sniff(candidate):
            continue
        twins = [p for p in path.glob(f"{candidate.stem}.*") if p.suffix.lower() != ".h5"]
        if not twins:
            out.append(candidate)
    return out


def _number(group, name: str, path: Path) -> float:
    value = np.asarray(group[name][()]).reshape(-1)
    if value.size != 1 or value.dtype.kind not in "fiub":
        raise HydroDataError(f"{group.name}/{name} is not a number", path=path)
    number = float(value[0])
    if not np.isfinite(number) or abs(number) > _IMPLAUSIBLE:
        raise HydroDataError(f"{group.name}/{name} = {number!r} is not a usable number", path=path)
    return number


def _vector(group, name: str, path: Path) -> np.ndarray:
    value = np.asarray(group[name][()])
    if value.dtype.kind not in "fiu":
        raise HydroDataError(f"{group.name}/{name} is not numeric", path=path)
    return value.astype(float).reshape(-1)


def _text(group, name: str) -> str:
    value = group[name][()]
    if isinstance(value, np.ndarray):
        value = value.reshape(-1)[0] if value.size else b""
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    return str(value).strip()


def _text_attr(obj, name: str) -> str:
    value = obj.attrs.get(name)
    if isinstance(value, np.ndarray):
        value = value.reshape(-1)[0] if value.size else b""
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    return str(value).strip().lower() if value is not None else ""


def _depth(sp, path: Path) -> float:
    if "water_depth" not in sp:
        return np.inf
    value = sp["water_depth"][()]
    if isinstance(value, bytes | str) or (
        isinstance(value, np.ndarray) and value.dtype.kind in "SOU"
    ):
        text = _text(sp, "water_depth").lower()
        if text.startswith("inf"):
            return np.inf
        raise HydroDataError(f"water_depth {text!r} is not a depth", path=path)
    depth = _number(sp, "water_depth", path)
    if not depth > 0:
        raise HydroDataError(f"water_depth = {depth!r} m is not positive", path=path)
    return depth


def _finite(values: np.ndarray, name: str, path: Path) -> None:
    with np.errstate(invalid="ignore"):
        bad = ~np.isfinite(values) | (np.abs(values) > _IMPLAUSIBLE)
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        raise HydroDataError(
            f"{name}{list(index)} = {values[index]!r} is not a usable number",
            path=path,
            hint="the file is damaged; write it again with BEMIO",
        )


def _array(
    group, name: str, shape: tuple[int, ...], path: Path, *, allow_nan: bool = False
) -> np.ndarray:
    if name not in group:
        raise HydroDataError(f"no {group.name}/{name} dataset", path=path)
    values = np.asarray(group[name][()])
    if values.dtype.kind not in "fiu":
        raise HydroDataError(f"{group.name}/{name} is not numeric", path=path)
    values = values.astype(float)
    if values.shape != shape:
        raise HydroDataError(
            f"{group.name}/{name} has shape {values.shape}, expected {shape}", path=path
        )
    _finite(np.nan_to_num(values, nan=0.0) if allow_nan else values, f"{group.name}/{name}", path)
    return values
