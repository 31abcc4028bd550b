"""Capytaine NetCDF, and cummins' own NetCDF, which is the same layout.

File format
-----------
Capytaine (``cpt.io.xarray.save_dataset_as_netcdf`` / ``export_dataset``) writes the
:class:`xarray.Dataset` of ``BEMSolver.fill_dataset`` to NetCDF. Capytaine ≤ 2.x
files are usually NetCDF-3 (``CDF\\x01``/``CDF\\x02``, read here with SciPy); newer
ones and cummins' own files are NetCDF-4/HDF5 (read and written with h5netcdf).

* ``added_mass``, ``radiation_damping``: dims ``omega``, ``radiating_dof``,
  ``influenced_dof`` in any order (Capytaine 2 stores (omega, radiating_dof,
  influenced_dof), Capytaine 3 (omega, influenced_dof, radiating_dof)); dims are
  matched by name. Units SI: kg, kg·m, kg·m²; kg/s …
* ``excitation_force``, ``Froude_Krylov_force``, ``diffraction_force``: complex, N/m
  and N·m/m per metre of wave amplitude, dims omega, wave_direction, influenced_dof.
  NetCDF has no complex type: complex arrays carry an extra leading dimension
  ``complex`` with labels ``re``, ``im``.
* ``hydrostatic_stiffness``, ``inertia_matrix``: influenced_dof × radiating_dof.
* ``rho``, ``g``, ``water_depth`` (``inf`` = deep water) and ``forward_speed`` are
  scalar coordinates (a dimension when several values were computed).
* Capytaine ≥ 2 may solve ω = 0 and ω = ∞: those rows of ``added_mass`` become
  ``added_mass_zero`` / ``added_mass_inf`` here (damping is 0 there; diffraction is
  undefined, stored as NaN).
* ``freq``, ``period``, ``wavenumber``, ``wavelength`` (and with forward speed
  ``encounter_omega``, ``encounter_wave_direction``) are coordinates derived from ω:
  dropped. Capytaine 3 also stores ``rotation_center``, ``center_of_mass``,
  ``center_of_buoyancy``, ``disp_mass``: they become the attributes
  ``reference_point``, ``center_of_gravity``, ``center_of_buoyancy`` and
  ``displaced_volume``.
* Several bodies: DOF labels ``body__Heave``, as in cummins.
* Problems Capytaine could not solve (e.g. finite depth with kh < 0.1, where its
  finite-depth Green function is not implemented) are stored as NaN; those frequencies
  are dropped here, and the dataset's ``history`` says which.

Conventions
-----------
Capytaine's time dependence is x(t) = Re{X e^{-iωt}} (incident wave potential
φ₀ = −i g/ω e^{kz} e^{ik(x cos β + y sin β)}); cummins uses Re{X e^{+iωt}}, so every
complex value is conjugated on read and on write. Axes are z-up (x forward, y to port,
z up) and β is the direction of propagation from +x towards +y, as in cummins.
Rotational DOFs are about Capytaine's ``rotation_center``; files written by
Capytaine 2 do not record it (it defaults to the centre of mass when the body has one,
else the origin): pass ``reference_point=`` when you know it.

Files written by :func:`write_netcdf` use Capytaine's layout and conventions (so that
``xr.open_dataset`` and ``cpt.io.xarray.merge_complex_values`` work on them) and add
cummins' own variables (``added_mass_inf``, ``added_mass_zero``, ``rao``,
``drift_force``, ``additional_damping``, ``additional_stiffness``) and attributes
(``cummins_version``; attributes NetCDF cannot hold, such as ``None``, booleans or
dictionaries, go JSON-encoded into ``cummins_json_attrs``). Reading such a file gives
back the written dataset exactly.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from cummins._version import __version__
from cummins.errors import HydroDataError
from cummins.hydrodb import (
    DOF_NAMES,
    bodies,
    make_hydrodb,
    split_dof,
    stack_forward_speeds,
    validate,
)
from cummins.io._common import resolve_rho_g, warn_damage

__all__ = ["from_capytaine_dataset", "read_netcdf", "sniff", "sniff_dir", "write_netcdf"]

_MAGIC_HDF5 = b"\x89HDF\r\n\x1a\n"
_MAGIC_CLASSIC = (b"CDF\x01", b"CDF\x02")
_MAGIC_CDF5 = b"CDF\x05"

#: Attribute holding, JSON-encoded, the attributes NetCDF cannot store natively.
JSON_ATTRS = "cummins_json_attrs"
#: Attribute marking a file written by cummins (value: the cummins version).
VERSION_ATTR = "cummins_version"
#: Time convention of the numbers stored in the file (Capytaine's).
FILE_TIME_CONVENTION = (
    "x(t) = Re{X exp(-i omega t)} (Capytaine's convention; cummins conjugates on read)"
)
CANONICAL_TIME_CONVENTION = "x(t) = Re{X exp(i omega t)}"

#: Coordinates derived from omega (or forward speed) that the canonical dataset drops.
_DERIVED_COORDS = (
    "freq",
    "period",
    "wavenumber",
    "wavelength",
    "encounter_omega",
    "encounter_wave_direction",
)
_FREQUENCY_DIMS = ("omega", "freq", "period", "wavenumber", "wavelength")

#: variable name → (make_hydrodb keyword, canonical dims, complex?)
_VARIABLES: dict[str, tuple[str, tuple[str, ...], bool]] = {
    "added_mass": ("added_mass", ("omega", "influenced_dof", "radiating_dof"), False),
    "radiation_damping": (
        "radiation_damping",
        ("omega", "influenced_dof", "radiating_dof"),
        False,
    ),
    "additional_damping": (
        "additional_damping",
        ("omega", "influenced_dof", "radiating_dof"),
        False,
    ),
    "added_mass_inf": ("added_mass_inf", ("influenced_dof", "radiating_dof"), False),
    "added_mass_zero": ("added_mass_zero", ("influenced_dof", "radiating_dof"), False),
    "hydrostatic_stiffness": ("hydrostatic_stiffness", ("influenced_dof", "radiating_dof"), False),
    "inertia_matrix": ("inertia_matrix", ("influenced_dof", "radiating_dof"), False),
    "additional_stiffness": ("additional_stiffness", ("influenced_dof", "radiating_dof"), False),
    "excitation_force": (
        "excitation_force",
        ("omega", "wave_direction", "influenced_dof"),
        True,
    ),
    "Froude_Krylov_force": (
        "froude_krylov_force",
        ("omega", "wave_direction", "influenced_dof"),
        True,
    ),
    "diffraction_force": (
        "diffraction_force",
        ("omega", "wave_direction", "influenced_dof"),
        True,
    ),
    "rao": ("rao", ("omega", "wave_direction", "radiating_dof"), True),
    "drift_force": ("drift_force", ("omega", "wave_direction", "influenced_dof"), False),
}

#: Canonical attributes set by the reader itself (never copied from Capytaine's attrs).
_RESERVED_ATTRS = (
    "rho",
    "g",
    "water_depth",
    "source_format",
    "source_file",
    "reference_point",
    "axis_convention",
    "time_convention",
    "history",
)


# --------------------------------------------------------------------------- detection


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


# --------------------------------------------------------------------------- reading


def load_netcdf(path: Path) -> xr.Dataset:
    """Open a NetCDF file fully into memory; every failure becomes HydroDataError."""
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


def read_netcdf(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    forward_speed: float | None = None,
    reference_point: Sequence[float] | None = None,
    siblings: bool = True,
) -> xr.Dataset:
    """Read a Capytaine (or cummins) NetCDF file into a canonical ``HydroDB``.

    Parameters
    ----------
    path
        The ``.nc`` file.
    rho, g
        Water density (kg/m³) and gravity (m/s²). The file records them and its numbers
        are dimensional: a value given here may only confirm the file's.
    forward_speed
        m/s. For a file with several forward speeds, the speed to read (default: all,
        stacked along a ``forward_speed`` dimension); otherwise it must match the file.
    reference_point
        Capytaine's rotation centre, m, when the file does not record it (Capytaine 2).
        If the file records one, a different value is an error.
    siblings
        Also read the files Capytaine's legacy exporter
        (``capytaine.io.legacy.export_hydrostatics``) writes beside the ``.nc``:
        ``KH.dat`` / ``KH_<i>.dat`` (hydrostatic stiffness per body, used when the
        ``.nc`` has none, compared with it otherwise) and ``Hydrostatics.dat`` /
        ``Hydrostatics_<i>.dat`` (centres of buoyancy and gravity, displaced volume).

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB``: SI units, e^{+iωt}, z-up axes, ω = 0 and ω = ∞ in
        ``added_mass_zero`` / ``added_mass_inf``.

    Raises
    ------
    HydroDataError
        Not NetCDF, truncated, missing variables, inconsistent dimensions.

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.demo_dataset()
    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "tanker.nc"
    >>> _ = write_netcdf(ds, out)
    >>> read_netcdf(out).identical(ds)
    True
    """
    path = Path(path)
    raw = load_netcdf(path)
    try:
        legacy = _legacy_exporter_files(path.parent) if siblings else None
        return from_capytaine_dataset(
            raw,
            rho=rho,
            g=g,
            forward_speed=forward_speed,
            reference_point=reference_point,
            source_file=str(path),
            _path=path,
            _legacy=legacy,
        )
    except HydroDataError:
        raise
    except (KeyError, IndexError, ValueError, TypeError, AttributeError) as exc:
        raise HydroDataError(
            f"unexpected content ({type(exc).__name__}: {exc})",
            path=path,
            hint="the file does not follow Capytaine's layout; open it with xarray to inspect it",
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


def from_capytaine_dataset(
    raw: xr.Dataset,
    *,
    rho: float | None = None,
    g: float | None = None,
    forward_speed: float | None = None,
    reference_point: Sequence[float] | None = None,
    source_file: str = "",
    source_format: str = "capytaine",
    history: Iterable[str] = (),
    _path: Path | None = None,
    _legacy: LegacyExport | None = None,
    **attrs: Any,
) -> xr.Dataset:
    """Convert a Capytaine dataset (in memory or read from NetCDF) to a ``HydroDB``.

    Works on the output of ``cpt.BEMSolver().fill_dataset`` / ``cpt.assemble_dataset``
    (complex arrays) and on what ``xr.open_dataset`` gives for a Capytaine file (real
    arrays with a ``complex`` dimension). Complex values are conjugated (e^{-iωt} →
    e^{+iωt}); ω = 0 and ω = ∞ rows of the added mass become ``added_mass_zero`` and
    ``added_mass_inf``; frequencies where Capytaine stored NaN are dropped.

    Parameters
    ----------
    raw
        The Capytaine dataset.
    rho, g, forward_speed, reference_point
        As in :func:`read_netcdf`.
    source_file, source_format
        Provenance attributes.
    history
        Lines to put first in the ``history`` attribute.
    **attrs
        Further attributes for the dataset.
    """
    where = _path if _path is not None else (source_file or None)
    for name in ("added_mass", "radiation_damping"):
        if name not in raw.data_vars:
            raise HydroDataError(
                f"no {name!r} variable: this is not a hydrodynamic database",
                path=where,
                hint="Capytaine writes added_mass and radiation_damping when radiation "
                "problems were solved (fill_dataset with radiating_dof)",
            )
    raw = merge_complex(raw.copy(), where)
    raw = _normalise_frequency_dim(raw, where)
    ours = VERSION_ATTR in raw.attrs
    lines = list(history)
    notes: list[str] = []
    if _path is not None and not ours:
        version = raw.attrs.get("capytaine_version")
        lines.insert(
            0, f"read {Path(source_file).name}" + (f" (Capytaine {version})" if version else "")
        )
    _check_incoming_wave_convention(raw, where, lines)
    raw = _squeeze_extra_dims(raw, where)
    _check_coordinates(raw, where)
    _check_derived_frequencies(raw, where)
    layout = dof_layout(raw, where, None if ours else lines, keep=ours)

    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        _scalar(raw, "rho"),
        _scalar(raw, "g"),
        path=where or "dataset",
        history=lines,
        dimensional=True,
        defaults=False,
    )
    depth = _scalar(raw, "water_depth")
    if depth is None:
        depth = math.inf
        lines.append("water_depth not recorded in the file: deep water assumed")

    _check_constants(rho_v, g_v, where, notes)

    raw = _select_forward_speed(raw, forward_speed, where, lines)
    point, body_attrs = _body_attributes(raw, reference_point, where, lines, rho_v, layout)
    if _legacy is not None and not ours:
        legacy_attrs = _legacy.attributes(layout, where, lines, notes)
        for key, value in legacy_attrs.items():
            body_attrs.setdefault(key, value)
    if reference_point is None and _assumed_origin(raw):
        point = _reference_from_inertia(raw, layout, body_attrs, point, lines, where)
    extra_attrs = {} if ours else _solver_attributes(raw.attrs)
    extra_attrs.update(body_attrs)
    extra_attrs.update(attrs)
    common = (layout, _legacy if not ours else None, notes)

    if "forward_speed" in raw.dims:
        speeds = raw["forward_speed"].values
        parts = [
            _one_speed(
                raw.sel(forward_speed=v),
                rho_v,
                g_v,
                depth,
                point,
                source_file,
                source_format,
                list(lines),
                extra_attrs,
                where,
                *common,
            )
            for v in speeds
        ]
        out = stack_forward_speeds(parts)
    else:
        out = _one_speed(
            raw,
            rho_v,
            g_v,
            depth,
            point,
            source_file,
            source_format,
            lines,
            extra_attrs,
            where,
            *common,
        )
    if ours:
        out = _restore_extra_variables(out, raw)
        kept = {k: out.attrs[k] for k in ("read_warnings",) if k in out.attrs}
        _restore_attributes(out, raw)
        for key, value in kept.items():
            out.attrs.setdefault(key, value)
    return out


def _normalise_frequency_dim(raw: xr.Dataset, where) -> xr.Dataset:
    """Make ``omega`` the frequency dimension (Capytaine may index by period etc.)."""
    if "omega" in raw.dims:
        return raw
    for dim in _FREQUENCY_DIMS[1:]:
        if dim in raw.dims:
            if "omega" in raw.coords and raw["omega"].dims == (dim,):
                return raw.swap_dims({dim: "omega"})
            values = np.asarray(raw[dim].values, dtype=float)
            if dim == "freq":
                return raw.assign_coords(omega=(dim, 2 * np.pi * values)).swap_dims({dim: "omega"})
            if dim == "period":
                with np.errstate(divide="ignore"):
                    omega = np.where(values == 0, np.inf, 2 * np.pi / values)
                return raw.assign_coords(omega=(dim, omega)).swap_dims({dim: "omega"})
            raise HydroDataError(
                f"the frequency dimension is {dim!r} and the file has no 'omega' coordinate",
                path=where,
                hint="save the dataset with Capytaine's omega coordinate (assemble_dataset(..., "
                "omega=True))",
            )
    raise HydroDataError("no frequency dimension ('omega') in the file", path=where)


def _scalar(raw: xr.Dataset, name: str) -> float | None:
    """A scalar coordinate (or attribute) as float, or None."""
    if name in raw.coords or name in raw.data_vars:
        values = np.asarray(raw[name].values, dtype=float).reshape(-1)
        if values.size != 1:
            return None
        return float(values[0])
    value = raw.attrs.get(name)
    if value is None:
        return None
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


_KNOWN_DIMS = {
    "omega",
    "influenced_dof",
    "radiating_dof",
    "wave_direction",
    "forward_speed",
    "space_coordinate",
    "body",
}


def _squeeze_extra_dims(raw: xr.Dataset, where) -> xr.Dataset:
    """Scalar-ize size-1 dimensions like ``rho``, ``g``, ``water_depth``; refuse others."""
    used = [raw[name] for name in _VARIABLES if name in raw.data_vars]
    for dim in sorted({d for var in used for d in var.dims} - _KNOWN_DIMS):
        size = raw.sizes[dim]
        if size == 1:
            raw = raw.isel({dim: 0})
            continue
        raise HydroDataError(
            f"the data have a dimension {dim!r} with {size} values",
            path=where,
            hint=f"a HydroDB holds one value of {dim}: select one with xarray "
            f"(ds.sel({dim}=...)) and pass the dataset to cummins.io.netcdf."
            "from_capytaine_dataset",
        )
    for name in ("added_mass", "radiation_damping"):
        if "wave_direction" in raw[name].dims:
            if raw.sizes["wave_direction"] > 1:
                raise HydroDataError(
                    f"{name} depends on the wave direction (forward speed: encounter frequency)",
                    path=where,
                    hint="a HydroDB holds radiation data for one encounter-frequency grid: "
                    "select one wave direction with xarray before converting",
                )
            raw[name] = raw[name].isel(wave_direction=0, drop=True)
    return raw


def _select_forward_speed(raw: xr.Dataset, speed: float | None, where, lines: list[str]):
    if "forward_speed" in raw.dims:
        if speed is None:
            return raw
        speeds = np.asarray(raw["forward_speed"].values, dtype=float)
        match = np.flatnonzero(np.isclose(speeds, speed, rtol=1e-9, atol=1e-9))
        if match.size == 0:
            raise HydroDataError(
                f"no forward speed {speed:g} m/s in the file",
                path=where,
                hint=f"available: {', '.join(f'{s:g}' for s in speeds)} m/s",
            )
        lines.append(f"forward speed {speeds[match[0]]:g} m/s selected")
        return raw.isel(forward_speed=int(match[0]))
    in_file = _scalar(raw, "forward_speed")
    if speed is not None:
        if in_file is not None and not np.isclose(in_file, speed, rtol=1e-9, atol=1e-9):
            raise HydroDataError(
                f"forward_speed = {speed:g} m/s was given but the file records {in_file:g} m/s",
                path=where,
                hint="the data were computed at the file's speed; drop the forward_speed option",
            )
        if in_file is None:
            lines.append(f"forward speed {speed:g} m/s (given)")
            raw = raw.assign_coords(forward_speed=float(speed))
    return raw


def _vector(da: xr.DataArray) -> np.ndarray:
    """(space_coordinate,) or (body, space_coordinate) → flat array of 3·n values."""
    if "space_coordinate" in da.dims:
        da = da.transpose(..., "space_coordinate")
    return np.asarray(da.values, dtype=float).reshape(-1)


def _body_attributes(raw, given, where, lines: list[str], rho: float, layout: DofLayout):
    """Reference point (rotation centre), CG, CB, displaced volume, body name."""
    attrs: dict[str, Any] = {}
    recorded = None
    if "rotation_center" in raw.variables:
        recorded = _vector(raw["rotation_center"])
    elif "reference_point" in raw.attrs:
        recorded = np.asarray(raw.attrs["reference_point"], dtype=float).reshape(-1)
    if given is not None:
        point = np.asarray(given, dtype=float).reshape(-1)
        if recorded is not None and (
            recorded.shape != point.shape or not np.allclose(recorded, point, atol=1e-9)
        ):
            raise HydroDataError(
                f"reference_point {point.tolist()} was given but the file records the "
                f"rotation centre {recorded.tolist()}",
                path=where,
                hint="the data are about the recorded point: read them as they are and "
                "use cummins.move_reference_point",
            )
        if recorded is None:
            lines.append(f"reference point (rotation centre) {point.tolist()} m (given)")
    elif recorded is not None:
        point = recorded
        if "rotation_center" in raw.variables:
            lines.append(f"reference point = Capytaine's rotation_center {point.tolist()} m")
    else:
        point = np.zeros(3)
        lines.append(
            "the file does not record Capytaine's rotation centre: assumed at the origin "
            "(pass reference_point= if the body was defined with another one)"
        )
    if point.size % 3 or point.size == 0:
        raise HydroDataError(
            f"reference point must have 3 coordinates per body, got {point.size}", path=where
        )
    if "center_of_mass" in raw.variables:
        attrs["center_of_gravity"] = _vector(raw["center_of_mass"])
    if "center_of_buoyancy" in raw.variables:
        attrs["center_of_buoyancy"] = _vector(raw["center_of_buoyancy"])
    if "disp_mass" in raw.variables and raw["disp_mass"].size == 1:
        attrs["displaced_volume"] = float(raw["disp_mass"].values) / rho
    for name in ("body_name", "body"):
        if name in raw.coords and raw[name].size == 1:
            attrs["body_name"] = str(np.asarray(raw[name].values).reshape(-1)[0])
            break
    if len(layout.body_names) > 1 and layout.labels != layout.file_labels:
        attrs["body_names"] = "\n".join(layout.body_names)
    elif layout.body_names and layout.body_names[0] and "body_name" not in attrs:
        attrs["body_name"] = layout.body_names[0]
    return point if point.size > 3 else point.reshape(3), attrs


def _check_incoming_wave_convention(raw: xr.Dataset, where, lines: list[str]) -> None:
    """Capytaine 1.x recorded ``incoming_waves_convention``; only ``Nemoh`` (its default,
    the incident potential of Capytaine >= 1.2 and of this reader) is understood."""
    value = raw.attrs.get("incoming_waves_convention")
    if value is None:
        return
    if str(value).strip().lower() != "nemoh":
        raise HydroDataError(
            f"incoming_waves_convention = {value!r}: only Capytaine's 'Nemoh' convention "
            "(its default, the one of Capytaine >= 1.2) is supported",
            path=where,
            hint="recompute the excitation with the default convention",
        )
    lines.append(
        "incoming_waves_convention = Nemoh (Capytaine 1.x): the incident potential of "
        "Capytaine >= 1.2, read as such"
    )


_COORDINATE_NAMES = (
    "wave_direction",
    "rotation_center",
    "center_of_mass",
    "center_of_buoyancy",
    "forward_speed",
)


def _check_coordinates(raw: xr.Dataset, where) -> None:
    """A NaN or infinite coordinate is an error naming it (omega = inf is a limit row)."""
    for name in _COORDINATE_NAMES:
        if name not in raw.variables:
            continue
        values = np.asarray(raw[name].values)
        if values.dtype.kind not in "fiu":
            continue
        values = values.astype(float)
        if not np.all(np.isfinite(values)):
            bad = values.reshape(-1)[~np.isfinite(values.reshape(-1))][0]
            raise HydroDataError(
                f"the coordinate {name} holds {bad!r}",
                path=where,
                hint="every coordinate must be a finite number; the file is damaged",
            )
    if "wave_direction" in raw.variables:
        beta = np.asarray(raw["wave_direction"].values, dtype=float).reshape(-1)
        if np.any(np.abs(beta) > 4 * np.pi):
            raise HydroDataError(
                f"wave_direction {beta[np.abs(beta) > 4 * np.pi][0]!r} rad is not an angle "
                "Capytaine writes (|beta| <= 2 pi)",
                path=where,
                hint="the file is damaged, or holds degrees: Capytaine stores radians",
            )
        if np.unique(beta).size != beta.size:
            raise HydroDataError(
                "a wave direction appears twice",
                path=where,
                quantity=f"wave_direction = {np.round(beta, 6).tolist()} rad",
            )
    omega = np.asarray(raw["omega"].values, dtype=float)
    with np.errstate(invalid="ignore"):
        bad = np.isnan(omega) | ((omega > IMPLAUSIBLE) & np.isfinite(omega))
    if bad.any():
        raise HydroDataError(
            "the coordinate omega holds NaN or a value beyond any wave frequency "
            "(omega = inf, Capytaine's infinite-frequency limit, is allowed)",
            path=where,
            quantity=f"omega = {omega[bad][:4].tolist()}",
        )


def _check_derived_frequencies(raw: xr.Dataset, where) -> None:
    """Capytaine stores freq = omega/2 pi and period = 2 pi/omega beside omega: they must
    agree (to rounding), or omega (or they) were damaged."""
    omega = np.asarray(raw["omega"].values, dtype=float)
    finite = np.isfinite(omega) & (omega > 0)
    for name, expected in (("freq", omega / (2 * np.pi)), ("period", None)):
        if name not in raw.coords or raw[name].dims != ("omega",):
            continue
        values = np.asarray(raw[name].values, dtype=float)
        if expected is None:
            with np.errstate(divide="ignore"):
                expected = 2 * np.pi / omega
        with np.errstate(invalid="ignore"):
            off = ~np.isclose(values[finite], expected[finite], rtol=1e-12, atol=0.0)
        if off.any():
            k = int(np.flatnonzero(finite)[np.flatnonzero(off)[0]])
            raise HydroDataError(
                f"omega[{k}] = {omega[k]!r} rad/s disagrees with {name}[{k}] = {values[k]!r} "
                "(Capytaine writes both from the same frequency)",
                path=where,
                hint="the file is damaged; write it again from the solver",
            )


def _check_constants(rho: float, g: float, where, notes: list[str]) -> None:
    """Warn about a density or gravity no sea-keeping computation uses."""
    if not 9.7 <= g <= 9.9:
        warn_damage(
            f"g = {g!r} m/s^2 is not the acceleration of gravity on Earth (9.78-9.83)",
            path=where,
            notes=notes,
            hint="check the file; the data are used as they are",
        )
    if not 900.0 <= rho <= 1100.0:
        warn_damage(
            f"rho = {rho!r} kg/m^3 is not the density of water",
            path=where,
            notes=notes,
            hint="check the file; the data are used as they are",
        )


def _assumed_origin(raw: xr.Dataset) -> bool:
    return "rotation_center" not in raw.variables and "reference_point" not in raw.attrs


def _reference_from_inertia(raw, layout: DofLayout, attrs: dict, point, lines, where):
    """Capytaine 2 does not record the rotation centre, but its rigid-body inertia
    matrix is about it: M = [[m I, -m S(r)], [m S(r), I]] with r the centre of mass
    relative to the rotation centre (Fossen 2021 eq. 3.44). Given the centre of mass
    (the legacy exporter's ``Hydrostatics*.dat`` or Capytaine 3's ``center_of_mass``),
    the rotation centre is the centre of mass less r. Returns ``point`` unchanged when
    that cannot be done."""
    if "inertia_matrix" not in raw.data_vars or "center_of_gravity" not in attrs:
        return point
    cog = np.asarray(attrs["center_of_gravity"], dtype=float).reshape(-1, 3)
    n_bodies = len(layout.body_names)
    if cog.shape[0] != n_bodies:
        return point
    matrix = raw["inertia_matrix"].transpose("influenced_dof", "radiating_dof")
    matrix = np.asarray(
        matrix.sel(
            influenced_dof=list(layout.file_labels), radiating_dof=list(layout.file_labels)
        ).values,
        dtype=float,
    )
    centres = []
    for body in range(n_bodies):
        block = layout.rigid_block(body)
        if block is None:
            return point
        m = matrix[np.ix_(block, block)]
        mass = m[0, 0]
        if not np.all(np.isfinite(m)) or not mass > 0:
            return point
        lower = m[3:6, 0:3] / mass
        r = np.array([lower[2, 1], lower[0, 2], lower[1, 0]])
        centres.append(cog[body] - r)
    derived = np.concatenate(centres)
    derived[np.abs(derived) < 1e-12] = 0.0
    for k, line in enumerate(lines):
        if line.startswith("the file does not record Capytaine's rotation centre"):
            lines[k] = (
                "the file does not record Capytaine's rotation centre: "
                f"{np.round(derived, 9).tolist()} m, the centre of gravity less the offset "
                "that the rigid-body inertia_matrix gives (its mass-moment coupling)"
            )
    return derived if derived.size > 3 else derived.reshape(3)


@dataclass(frozen=True)
class LegacyExport:
    """What Capytaine's legacy exporter (``export_hydrostatics``) wrote beside a ``.nc``.

    Attributes
    ----------
    stiffness_files, hydrostatics_files
        ``KH.dat`` or ``KH_0.dat``, ``KH_1.dat`` … and ``Hydrostatics*.dat``, by body.
    stiffness
        The 6×6 matrices (N/m, N, N·m/rad) of the ``KH`` files, in the same order.
    centre_of_buoyancy, centre_of_gravity, volume
        ``XF``/``XG`` columns and ``Displacement`` of the ``Hydrostatics`` files.
    """

    stiffness_files: tuple[Path, ...]
    stiffness: tuple[np.ndarray, ...]
    hydrostatics_files: tuple[Path, ...]
    centre_of_buoyancy: tuple[np.ndarray, ...]
    centre_of_gravity: tuple[np.ndarray, ...]
    volume: tuple[float, ...]

    def attributes(self, layout: DofLayout, where, lines: list[str], notes: list[str]) -> dict:
        """Centres and volume as dataset attributes (one per body)."""
        n = len(layout.body_names)
        if not self.hydrostatics_files:
            return {}
        if len(self.hydrostatics_files) != n:
            warn_damage(
                f"{len(self.hydrostatics_files)} Hydrostatics*.dat files beside the NetCDF "
                f"file for {n} bodies: they are not used",
                path=where,
                notes=notes,
            )
            return {}
        lines.append(
            "centres of gravity and buoyancy and displaced volume from "
            + ", ".join(f.name for f in self.hydrostatics_files)
        )
        volume = np.asarray(self.volume, dtype=float)
        return {
            "center_of_gravity": np.concatenate(self.centre_of_gravity),
            "center_of_buoyancy": np.concatenate(self.centre_of_buoyancy),
            "displaced_volume": float(volume[0]) if n == 1 else volume,
        }

    def stiffness_matrix(self, layout, where, lines, notes, stored):
        """The hydrostatic stiffness in the canonical DOFs: the ``KH`` files' when the
        ``.nc`` has none (None otherwise, after comparing them with the stored one)."""
        n = len(layout.body_names)
        if not self.stiffness_files:
            return None
        names = ", ".join(f.name for f in self.stiffness_files)
        if len(self.stiffness_files) != n:
            warn_damage(
                f"{len(self.stiffness_files)} KH*.dat files ({names}) beside the NetCDF file "
                f"for {n} bodies: they are not used",
                path=where,
                notes=notes,
            )
            return None
        size = len(layout.labels)
        full = np.zeros((size, size))
        for body, matrix in enumerate(self.stiffness):
            block = layout.rigid_block(body)
            if block is None:
                return None
            full[np.ix_(block, block)] = matrix
        if stored is None:
            lines.append(f"hydrostatic_stiffness from {names} (not in the NetCDF file)")
            return full
        values = np.asarray(stored.values, dtype=float)
        # the KH files print 7 significant digits (%E): agreement to 1e-6 of the block scale
        for body, (path, matrix) in enumerate(
            zip(self.stiffness_files, self.stiffness, strict=True)
        ):
            block = layout.rigid_block(body)
            if block is None:
                continue
            part = values[np.ix_(block, block)]
            scale = max(float(np.nanmax(np.abs(matrix))), 1e-300)
            with np.errstate(invalid="ignore"):
                off = np.abs(part - matrix) > 1e-6 * scale + 1e-6 * np.abs(matrix)
            if off.any():
                i, j = (int(x) for x in np.argwhere(off)[0])
                warn_damage(
                    f"hydrostatic_stiffness[{layout.labels[block[i]]}, "
                    f"{layout.labels[block[j]]}] = {part[i, j]!r} but {path.name} gives "
                    f"{matrix[i, j]!r}: the NetCDF file's value is used",
                    path=where,
                    notes=notes,
                    hint="one of the two files is damaged",
                )
                return None
        lines.append(f"hydrostatic_stiffness agrees with {names}")
        return None


def _legacy_exporter_files(folder: Path) -> LegacyExport | None:
    """The ``KH*.dat`` and ``Hydrostatics*.dat`` files of Capytaine's legacy exporter."""
    if any((folder / name).is_file() for name in ("Nemoh.cal", "nemoh.cal")):
        return None  # NEMOH's own KH.dat / Hydrostatics.dat, not Capytaine's exporter
    stiffness_files = _numbered(folder, "KH")
    hydro_files = _numbered(folder, "Hydrostatics")
    if not stiffness_files and not hydro_files:
        return None
    stiffness = tuple(_read_kh(f) for f in stiffness_files)
    parsed = [_read_hydrostatics(f) for f in hydro_files]
    return LegacyExport(
        tuple(stiffness_files),
        stiffness,
        tuple(hydro_files),
        tuple(p[0] for p in parsed),
        tuple(p[1] for p in parsed),
        tuple(p[2] for p in parsed),
    )


def _numbered(folder: Path, stem: str) -> list[Path]:
    """``<stem>_0.dat``, ``<stem>_1.dat`` … in order, or ``[<stem>.dat]``."""
    numbered = []
    k = 0
    while (folder / f"{stem}_{k}.dat").is_file():
        numbered.append(folder / f"{stem}_{k}.dat")
        k += 1
    if numbered:
        return numbered
    single = folder / f"{stem}.dat"
    return [single] if single.is_file() else []


def _without_bom(text):
    """The text without a UTF-8 byte-order mark (an encoding, not damage)."""
    if text.lines and text.lines[0].startswith("\ufeff"):
        return type(text)(text.path, (text.lines[0][1:], *text.lines[1:]))
    return text


def _read_kh(path: Path) -> np.ndarray:
    from cummins.io._text import TextFile

    text = _without_bom(TextFile.read(path))
    rows = [k for k, line in enumerate(text.lines) if line.strip()]
    if len(rows) != 6:
        raise text.error(
            f"expected 6 rows of the 6x6 hydrostatic stiffness, found {len(rows)}",
            rows[-1] if rows else 0,
        )
    matrix = np.empty((6, 6))
    for r, k in enumerate(rows):
        values = text.numbers(k, 6)
        if not np.all(np.isfinite(values)) or np.any(np.abs(values) > IMPLAUSIBLE):
            raise text.error("not a finite stiffness value", k)
        matrix[r] = values
    return matrix


def _read_hydrostatics(path: Path) -> tuple[np.ndarray, np.ndarray, float]:
    """``XF = … - XG = …`` (three lines: x, y, z) and ``Displacement = …``."""
    import re

    from cummins.io._text import TextFile

    text = _without_bom(TextFile.read(path))
    pattern = re.compile(r"^\s*[XYZ]F\s*=\s*(\S+)\s*-\s*[XYZ]G\s*=\s*(\S+)\s*$", re.IGNORECASE)
    buoyancy, gravity, volume = [], [], None
    for k, line in enumerate(text.lines):
        if not line.strip():
            continue
        match = pattern.match(line)
        if match and len(buoyancy) < 3:
            try:
                buoyancy.append(float(match.group(1)))
                gravity.append(float(match.group(2)))
            except ValueError:
                raise text.error("expected 'XF = <number> - XG = <number>'", k) from None
            continue
        if line.strip().lower().startswith("displacement") and volume is None:
            try:
                volume = float(line.split("=", 1)[1].split()[0])
            except (IndexError, ValueError):
                raise text.error("expected 'Displacement = <volume>'", k) from None
            continue
        if "=" in line and volume is not None:
            continue  # further "name = value" lines (waterplane area, mass …) are not used
        raise text.error("expected three lines 'XF = … - XG = …' and 'Displacement = …'", k)
    centres = np.array(buoyancy + gravity, dtype=float)
    if len(buoyancy) != 3 or volume is None:
        raise text.error(
            "expected three lines 'XF = … - XG = …' (x, y, z) and 'Displacement = …'",
            len(text) - 1,
        )
    if not np.all(np.isfinite(centres)) or not (np.isfinite(volume) and volume > 0):
        raise text.error("non-finite centre or non-positive displacement", len(text) - 1)
    return np.array(buoyancy), np.array(gravity), float(volume)


def _solver_attributes(file_attrs: dict) -> dict:
    """Capytaine's global attributes (solver settings, version), as plain Python values."""
    out = {}
    for key, value in file_attrs.items():
        name = f"capytaine_{key}" if key in _RESERVED_ATTRS else key
        out[name] = _python_value(value)
    return out


def _python_value(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    return value


@dataclass(frozen=True)
class DofLayout:
    """How the file's DOFs map to the canonical ones.

    Attributes
    ----------
    file_labels
        The file's labels, in canonical order (to select the data with).
    labels
        The canonical labels: ``Surge`` … ``Yaw`` for one body, ``body1__Surge`` … for
        several (positional, see :func:`cummins.hydrodb.dof_labels`); a DOF that is not
        a rigid-body mode (a hinge, a flexible mode) keeps the name the file gives it.
    body_names
        The names the file gives the bodies, in order (empty strings when it gives none).
    body_index
        The body (0-based) of each canonical DOF.
    """

    file_labels: tuple[str, ...]
    labels: tuple[str, ...]
    body_names: tuple[str, ...]
    body_index: tuple[int, ...]

    def rigid_block(self, body: int) -> list[int] | None:
        """Indices of the six rigid-body DOFs of ``body`` in Surge … Yaw order, or None."""
        names = [
            split_dof(lab)[1]
            for lab, b in zip(self.labels, self.body_index, strict=True)
            if b == body
        ]
        positions = [k for k, b in enumerate(self.body_index) if b == body]
        if names[:6] != list(DOF_NAMES):
            return None
        return positions[:6]


def dof_layout(
    raw: xr.Dataset, where, lines: list[str] | None = None, *, keep: bool = False
) -> DofLayout:
    """The canonical DOF labels and order of a Capytaine dataset.

    Capytaine names a body's DOFs after the dictionary of the body (``Surge`` … for
    ``rigid_body_dofs``, any name for others) in the order of that dictionary (Capytaine
    1.1 sorted them alphabetically: ``Heave, Pitch, Roll, Surge, Sway, Yaw``), and joins
    several bodies as ``<body name>__<DOF>``. Here the rigid-body modes of each body come
    first in the order Surge … Yaw, then the other DOFs in the file's order, and several
    bodies are labelled ``body1__…``, ``body2__…`` in the order of the file.
    ``keep=True`` (files cummins wrote, whose labels are already canonical) keeps the
    file's labels and order.
    """
    influenced = [str(v) for v in raw["influenced_dof"].values]
    radiating = [str(v) for v in raw["radiating_dof"].values]
    for label in influenced + radiating:
        if not label or not label.isascii() or not label.isprintable():
            raise HydroDataError(
                f"DOF label {label!r} is not printable text",
                path=where,
                hint="the file is damaged (DOF labels are ASCII names such as 'Heave')",
            )
    if sorted(influenced) != sorted(radiating) or len(set(influenced)) != len(influenced):
        raise HydroDataError(
            "radiating and influenced DOFs differ (radiation solved for some DOFs only?)",
            path=where,
            quantity=f"radiating: {', '.join(radiating)}; influenced: {', '.join(influenced)}",
            hint="solve the radiation problems of every DOF",
        )
    groups: dict[str | None, list[str]] = {}
    for label in influenced:
        body, _ = split_dof(label)
        groups.setdefault(body, []).append(label)
    if None in groups and len(groups) > 1:
        raise HydroDataError(
            "some DOF labels name a body and others do not",
            path=where,
            quantity=", ".join(influenced),
            hint="label every DOF <body>__<DOF> (as Capytaine does for several bodies)",
        )
    several = len(groups) > 1
    if keep:
        index = {body: k for k, body in enumerate(groups)}
        return DofLayout(
            tuple(influenced),
            tuple(influenced),
            tuple(body or "" for body in groups),
            tuple(index[split_dof(label)[0]] for label in influenced),
        )
    file_labels: list[str] = []
    labels: list[str] = []
    body_index: list[int] = []
    for k, members in enumerate(groups.values()):
        rigid = sorted(
            (m for m in members if split_dof(m)[1] in DOF_NAMES),
            key=lambda m: DOF_NAMES.index(split_dof(m)[1]),
        )
        others = [m for m in members if split_dof(m)[1] not in DOF_NAMES]
        for member in rigid + others:
            name = split_dof(member)[1]
            file_labels.append(member)
            labels.append(f"body{k + 1}__{name}" if several else name)
            body_index.append(k)
    names = tuple(body or "" for body in groups)
    if lines is not None:
        if [split_dof(f)[1] for f in file_labels] != [split_dof(f)[1] for f in influenced]:
            lines.append(
                "DOFs reordered from the file's order ("
                + ", ".join(influenced)
                + ") to rigid-body modes first, Surge ... Yaw"
            )
        if several:
            lines.append(
                f"{len(groups)} bodies labelled body1 ... body{len(groups)} in the order of "
                "the file; the file's names (" + ", ".join(names) + ") are kept in body_names"
            )
        custom = sorted({split_dof(f)[1] for f in file_labels} - set(DOF_NAMES))
        if custom:
            lines.append(
                "DOFs that are not rigid-body modes keep the file's names: " + ", ".join(custom)
            )
    return DofLayout(tuple(file_labels), tuple(labels), names, tuple(body_index))


def _canonical_array(raw: xr.Dataset, name: str, dims: tuple[str, ...], labels, where):
    """Values of ``raw[name]`` in canonical dim order, DOFs in ``labels`` (file) order."""
    var = raw[name]
    missing = [d for d in dims if d not in var.dims]
    leftover = [d for d in var.dims if d not in dims]
    if missing or leftover:
        raise HydroDataError(
            f"{name} has dimensions {var.dims}, expected {dims}",
            path=where,
        )
    var = var.transpose(*dims)
    index = {d: list(labels) for d in ("influenced_dof", "radiating_dof") if d in dims}
    return var.sel(index)


#: No added mass, damping, force or stiffness of a floating body reaches this (SI units);
#: a larger value is a damaged number (a flipped exponent byte gives ~1e300).
IMPLAUSIBLE = 1e25


def _one_speed(
    raw,
    rho,
    g,
    depth,
    point,
    source_file,
    source_format,
    lines,
    attrs,
    where,
    layout: DofLayout,
    legacy: LegacyExport | None,
    notes: list[str],
):
    """Canonical dataset of one forward speed."""
    notes = list(notes)
    omega = np.asarray(raw["omega"].values, dtype=float)
    if np.any(np.isnan(omega)) or np.any(omega < 0):
        raise HydroDataError(
            "frequencies must be >= 0 (and not NaN)",
            path=where,
            quantity=f"omega = {omega.tolist()[:8]}",
        )
    arrays = {
        name: _canonical_array(raw, name, dims, layout.file_labels, where)
        for name, (_, dims, _) in _VARIABLES.items()
        if name in raw.data_vars
    }
    for arr in arrays.values():
        _check_magnitude(arr, where)
    if "excitation_force" not in arrays and {"Froude_Krylov_force", "diffraction_force"} <= set(
        arrays
    ):
        arrays["excitation_force"] = arrays["Froude_Krylov_force"] + arrays["diffraction_force"]
        lines.append(
            "no excitation_force in the file: excitation_force = Froude_Krylov_force + "
            "diffraction_force"
        )
    elif {"excitation_force", "Froude_Krylov_force", "diffraction_force"} <= set(arrays):
        _check_excitation_sum(arrays, where, notes)

    extra: dict[str, Any] = {}
    zero, inf = omega == 0, np.isinf(omega)
    for mask, key, label in ((zero, "added_mass_zero", "0"), (inf, "added_mass_inf", "infinity")):
        if not mask.any():
            continue
        limit = arrays["added_mass"].isel(omega=int(np.flatnonzero(mask)[0])).values
        if key in arrays:
            lines.append(f"omega = {label} rows ignored: the file has a {key} variable")
        elif np.all(np.isfinite(limit)):
            extra[key] = limit
            lines.append(f"added mass at omega = {label} stored as {key}")
        else:
            lines.append(f"added mass at omega = {label} not usable (NaN): {key} omitted")
    finite = ~(zero | inf)
    for name, arr in list(arrays.items()):
        if "omega" in arr.dims:
            arrays[name] = arr.isel(omega=np.flatnonzero(finite))
    omega = omega[finite]

    unsolved, damaged = _nan_frequencies(arrays, omega, where, notes)
    if (unsolved | damaged).all():
        raise HydroDataError(
            "no finite frequency with complete results (all NaN)",
            path=where,
            hint="Capytaine stores NaN for problems it could not solve",
        )
    if unsolved.any():
        listed = ", ".join(f"{w:.6g}" for w in omega[unsolved][:12])
        more = " …" if unsolved.sum() > 12 else ""
        count = int(unsolved.sum())
        lines.append(
            f"{count} frequenc{'y' if count == 1 else 'ies'} dropped where Capytaine stored NaN "
            f"(problems it could not solve): omega = {listed}{more} rad/s"
        )
    if (unsolved | damaged).any():
        keep = np.flatnonzero(~(unsolved | damaged))
        for name, arr in list(arrays.items()):
            if "omega" in arr.dims:
                arrays[name] = arr.isel(omega=keep)
        omega = omega[keep]
    for name, arr in list(arrays.items()):
        if "omega" not in arr.dims and np.isnan(arr.values).any():
            bad = np.argwhere(np.isnan(arr.values))
            cells = ", ".join(f"[{layout.labels[i]}, {layout.labels[j]}]" for i, j in bad[:4]) + (
                " …" if len(bad) > 4 else ""
            )
            warn_damage(
                f"{name} has NaN at {cells}: the variable is left out of the data",
                path=where,
                notes=notes,
                hint="Capytaine writes NaN where it cannot compute a value (DOFs that are "
                "not rigid-body modes); give the matrix yourself (cummins.with_inertia, "
                "--mass/--inertia-matrix) if it is needed",
            )
            del arrays[name]

    if legacy is not None:
        stored = arrays.get("hydrostatic_stiffness")
        stiffness = legacy.stiffness_matrix(layout, where, lines, notes, stored)
        if stiffness is not None:
            arrays["hydrostatic_stiffness"] = xr.DataArray(
                stiffness, dims=("influenced_dof", "radiating_dof")
            )

    for name, arr in arrays.items():
        keyword, _, is_complex = _VARIABLES[name]
        values = arr.values
        if is_complex:
            values = np.conj(values.astype(complex))
        elif np.iscomplexobj(values):
            raise HydroDataError(f"{name} should be real but is complex", path=where)
        extra[keyword] = values
    if any(_VARIABLES[n][2] for n in arrays):
        lines.append("complex values conjugated: Capytaine's exp(-i omega t) to exp(+i omega t)")
        extra["wave_direction"] = np.asarray(raw["wave_direction"].values, dtype=float).reshape(-1)

    speed = _scalar(raw, "forward_speed")
    added_mass = extra.pop("added_mass")
    damping = extra.pop("radiation_damping")
    ds = make_hydrodb(
        omega,
        added_mass,
        damping,
        rho=rho,
        g=g,
        water_depth=depth,
        source_format=source_format,
        source_file=source_file,
        dofs=list(layout.labels),
        forward_speed=speed,
        reference_point=point if point.size == 3 else np.zeros(3),
        history=lines,
        read_warnings=notes,
        **extra,
    )
    if point.size > 3:  # several bodies: one point per body (make_hydrodb takes one)
        ds.attrs["reference_point"] = point
    ds.attrs.update({k: v for k, v in attrs.items() if v is not None})
    return ds


def _check_magnitude(arr: xr.DataArray, where) -> None:
    """HydroDataError for a value no physical body has (a damaged number)."""
    values = np.abs(np.asarray(arr.values))
    with np.errstate(invalid="ignore"):
        bad = values > IMPLAUSIBLE
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        raise HydroDataError(
            f"{arr.name} holds {np.asarray(arr.values)[index]!r}, beyond any physical value "
            f"(> {IMPLAUSIBLE:g} in SI units)",
            path=where,
            quantity=_element(arr, index),
            hint="the file is damaged; write it again from the solver",
        )


def _element(arr: xr.DataArray, index: Sequence[int]) -> str:
    parts = []
    for dim, i in zip(arr.dims, index, strict=True):
        value = arr[dim].values[i] if dim in arr.coords else i
        if dim == "omega":
            parts.append(f"omega={float(value):.6g} rad/s")
        elif dim == "wave_direction":
            parts.append(f"wave_direction={np.degrees(float(value)):.6g} deg")
        else:
            parts.append(str(value))
    return f"{arr.name}[{', '.join(parts)}]"


def _check_excitation_sum(arrays: dict, where, notes: list[str]) -> None:
    """Capytaine writes excitation_force as Froude_Krylov_force + diffraction_force,
    computed in double precision: the three must agree to rounding, NaN where NaN."""
    exc = arrays["excitation_force"]
    fk, dif = arrays["Froude_Krylov_force"], arrays["diffraction_force"]
    e, a, b = (np.asarray(x.values) for x in (exc, fk, dif))
    eps = np.finfo(np.asarray(e).real.dtype if e.dtype.kind == "c" else e.dtype).eps
    total = a + b
    nan_e, nan_s = np.isnan(e), np.isnan(total)
    with np.errstate(invalid="ignore"):
        off = np.abs(e - total) > 4 * eps * (np.abs(a) + np.abs(b))
    bad = (nan_e != nan_s) | (off & ~nan_e & ~nan_s)
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        warn_damage(
            f"excitation_force differs from Froude_Krylov_force + diffraction_force at "
            f"{int(bad.sum())} values, first {_element(exc, index)} = {e[index]!r}, sum "
            f"{total[index]!r}: one of the three is damaged; excitation_force is used as stored",
            path=where,
            notes=notes,
            hint="Capytaine writes their sum exactly; write the file again from the solver",
        )


def _nan_frequencies(arrays: dict, omega: np.ndarray, where, notes: list[str]):
    """Frequencies Capytaine could not solve (every value of a variable NaN there), and
    frequencies where only some values are NaN (damage: warned, dropped)."""
    unsolved = np.zeros(omega.size, dtype=bool)
    damaged = np.zeros(omega.size, dtype=bool)
    first: tuple[str, float] | None = None
    for name, arr in arrays.items():
        if "omega" not in arr.dims:
            continue
        nan = np.isnan(np.asarray(arr.values)).reshape(omega.size, -1)
        whole = nan.all(axis=1)
        partial = nan.any(axis=1) & ~whole
        unsolved |= whole
        if partial.any() and first is None:
            first = (name, float(omega[np.flatnonzero(partial)[0]]))
        damaged |= partial
    damaged &= ~unsolved
    if damaged.any():
        name, w = first if first is not None else ("data", float(omega[damaged][0]))
        listed = ", ".join(f"{x:.6g}" for x in omega[damaged][:8])
        warn_damage(
            f"{name} has NaN in some but not all values at omega = {w:.6g} rad/s (Capytaine "
            f"writes NaN for a whole problem it could not solve): {int(damaged.sum())} "
            f"frequenc{'y' if damaged.sum() == 1 else 'ies'} left out (omega = {listed} rad/s)",
            path=where,
            notes=notes,
            hint="the file is damaged; write it again from the solver",
        )
    return unsolved, damaged


# --------------------------------------------------------------------------- attributes


def _is_native(key: Any, value: Any) -> bool:
    """Can NetCDF store this attribute as it is, and give it back unchanged?"""
    if not isinstance(key, str) or not key or key.startswith("_") or key == JSON_ATTRS:
        return False
    if isinstance(value, str):
        return "\x00" not in value
    if isinstance(value, bool | np.bool_):
        return False
    if isinstance(value, int | float | np.integer | np.floating):
        return not isinstance(value, int) or -(2**63) <= value < 2**63
    if isinstance(value, np.ndarray):
        return value.ndim == 1 and value.size >= 2 and value.dtype.kind in "if"
    return False


def encode_attribute(value: Any, key: str) -> Any:
    """Tagged JSON form of an attribute value NetCDF cannot store as it is."""
    if value is None:
        return {"type": "none"}
    if isinstance(value, bool | np.bool_):
        return {"type": "bool", "value": bool(value)}
    if isinstance(value, str):
        return {"type": "str", "value": value}
    if isinstance(value, int | np.integer):
        return {"type": "int", "value": int(value)}
    if isinstance(value, float | np.floating):
        return {"type": "float", "value": float(value)}
    if isinstance(value, complex | np.complexfloating):
        return {"type": "complex", "re": float(value.real), "im": float(value.imag)}
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "c":
            return {
                "type": "ndarray",
                "dtype": value.dtype.str,
                "shape": list(value.shape),
                "re": value.real.reshape(-1).tolist(),
                "im": value.imag.reshape(-1).tolist(),
            }
        if value.dtype.kind not in "biufU":
            raise HydroDataError(f"attribute {key!r}: arrays of {value.dtype} cannot be stored")
        return {
            "type": "ndarray",
            "dtype": value.dtype.str,
            "shape": list(value.shape),
            "data": value.reshape(-1).tolist(),
        }
    if isinstance(value, list | tuple):
        return {"type": type(value).__name__, "items": [encode_attribute(v, key) for v in value]}
    if isinstance(value, dict):
        if not all(isinstance(k, str) for k in value):
            raise HydroDataError(f"attribute {key!r}: dictionary keys must be strings")
        return {"type": "dict", "items": {k: encode_attribute(v, key) for k, v in value.items()}}
    raise HydroDataError(
        f"attribute {key!r} of type {type(value).__name__} cannot be stored in NetCDF",
        hint="convert it to a string, a number or an array before writing",
    )


def decode_attribute(item: dict) -> Any:
    kind = item["type"]
    if kind == "none":
        return None
    if kind in ("bool", "str", "int", "float"):
        return {"bool": bool, "str": str, "int": int, "float": float}[kind](item["value"])
    if kind == "complex":
        return complex(item["re"], item["im"])
    if kind == "ndarray":
        dtype = np.dtype(item["dtype"])
        if "re" in item:
            flat = np.asarray(item["re"], dtype=float) + 1j * np.asarray(item["im"], dtype=float)
        else:
            flat = np.asarray(item["data"])
        return flat.astype(dtype).reshape(item["shape"])
    if kind in ("list", "tuple"):
        items = [decode_attribute(v) for v in item["items"]]
        return items if kind == "list" else tuple(items)
    if kind == "dict":
        return {k: decode_attribute(v) for k, v in item["items"].items()}
    raise ValueError(f"unknown attribute type {kind!r}")


def encode_attributes(attrs: dict) -> dict:
    """Attributes as NetCDF can store them (the rest JSON-encoded in ``cummins_json_attrs``)."""
    native: dict[str, Any] = {}
    special: dict[str, Any] = {}
    for key, value in attrs.items():
        if _is_native(key, value):
            native[key] = str(value) if isinstance(value, np.str_) else value
        else:
            special[str(key)] = encode_attribute(value, str(key))
    if special:
        native[JSON_ATTRS] = json.dumps(special)
    return native


def decode_attributes(attrs: dict, where=None) -> dict:
    """Inverse of :func:`encode_attributes` (NumPy scalars become Python scalars)."""
    out = {k: _python_value(v) for k, v in attrs.items() if k != JSON_ATTRS}
    if JSON_ATTRS in attrs:
        try:
            special = json.loads(str(attrs[JSON_ATTRS]))
            out.update({k: decode_attribute(v) for k, v in special.items()})
        except (ValueError, KeyError, TypeError, AttributeError) as exc:
            raise HydroDataError(
                f"unreadable {JSON_ATTRS} attribute ({exc})",
                path=where,
                hint="the file was edited or damaged",
            ) from None
    return out


def _restore_extra_variables(out: xr.Dataset, raw: xr.Dataset) -> xr.Dataset:
    """For a file written by cummins: keep data variables cummins does not know about.

    They were written like the others (complex values conjugated) and come back on the
    same coordinates; a variable that does not fit them is left out.
    """
    for name, var in raw.data_vars.items():
        if name in _VARIABLES or name in out.variables:
            continue
        if not all(d in out.dims and raw.sizes[d] == out.sizes[d] for d in var.dims):
            continue
        values = np.conj(var.values) if np.iscomplexobj(var.values) else var.values
        out[name] = xr.DataArray(values, dims=var.dims)
    return out


def _restore_attributes(out: xr.Dataset, raw: xr.Dataset) -> None:
    """For a file written by cummins: give back its attributes exactly (in place)."""
    attrs = decode_attributes(raw.attrs)
    attrs.pop(VERSION_ATTR, None)
    attrs["time_convention"] = CANONICAL_TIME_CONVENTION
    for key in ("rho", "g", "water_depth"):
        attrs[key] = out.attrs[key]
    out.attrs.clear()
    out.attrs.update(attrs)
    for name in list(out.variables):
        if name in raw.variables:
            out[name].attrs = decode_attributes(raw[name].attrs)


# --------------------------------------------------------------------------- writing


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
    """Write ``ds`` (h5netcdf) to a temporary name, then rename it to ``path``: a failure
    leaves no half-written file. No overwrite check (the callers do it).

    With ``checksum`` every numeric array carries HDF5's Fletcher-32 checksum filter
    (a standard HDF5 filter that netCDF-C, h5py and MATLAB read transparently), so a
    damaged copy is refused on reading instead of giving different numbers."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp")
    encoding = _checksum_encoding(ds) if checksum else None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", category=FutureWarning)
            ds.to_netcdf(tmp, engine="h5netcdf", encoding=encoding)
        os.replace(tmp, path)
    except OSError as exc:
        raise HydroDataError(f"cannot write the file ({exc})", path=path) from None
    finally:
        if tmp.exists():
            tmp.unlink()
    return path


def _checksum_encoding(ds: xr.Dataset) -> dict[str, dict[str, Any]]:
    """Fletcher-32 for every non-scalar numeric variable (HDF5 filters need chunks)."""
    encoding: dict[str, dict[str, Any]] = {}
    for name, var in ds.variables.items():
        if var.ndim >= 1 and var.size > 0 and var.dtype.kind in "biufc":
            encoding[str(name)] = {"fletcher32": True}
    return encoding
