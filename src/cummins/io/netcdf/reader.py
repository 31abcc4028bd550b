"""Reading Capytaine (and cummins) NetCDF: the file's variables mapped to the canonical HydroDB.

:func:`read_netcdf` loads a file (:mod:`cummins.io.netcdf.files`) and
:func:`from_capytaine_dataset` maps Capytaine's variables, dimensions and conventions to
the canonical dataset (complex values conjugated, ω = 0 and ω = ∞ rows to
``added_mass_zero`` / ``added_mass_inf``, unsolved frequencies dropped); for a file
cummins wrote, its extra variables and attributes come back exactly.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import make_hydrodb, stack_forward_speeds
from cummins.io._common import DEPTH_ASSUMED, resolve_rho_g, warn_damage
from cummins.io.netcdf.attributes import (
    CANONICAL_TIME_CONVENTION,
    VERSION_ATTR,
    _python_value,
    decode_attributes,
)
from cummins.io.netcdf.checks import (
    _check_constants,
    _check_coordinates,
    _check_derived_frequencies,
    _check_excitation_sum,
    _check_incoming_wave_convention,
    _check_magnitude,
    _nan_frequencies,
)
from cummins.io.netcdf.files import load_netcdf, merge_complex
from cummins.io.netcdf.layout import (
    DofLayout,
    _assumed_origin,
    _body_attributes,
    _reference_from_inertia,
    dof_layout,
    restoring_attributes,
)
from cummins.io.netcdf.legacy import LegacyExport, _legacy_exporter_files
from cummins.io.netcdf.second_order import capytaine_drift, restore_second_order

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
    >>> from cummins.io.netcdf import write_netcdf
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
        attrs = {**attrs, DEPTH_ASSUMED: 1}

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
        out = restore_second_order(out, raw, where)
        kept = {k: out.attrs[k] for k in ("read_warnings",) if k in out.attrs}
        _restore_attributes(out, raw)
        for key, value in kept.items():
            out.attrs.setdefault(key, value)
    elif "forward_speed" not in out.dims:
        out = capytaine_drift(out, raw, where)
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


def _solver_attributes(file_attrs: dict) -> dict:
    """Capytaine's global attributes (solver settings, version), as plain Python values."""
    out = {}
    for key, value in file_attrs.items():
        name = f"capytaine_{key}" if key in _RESERVED_ATTRS else key
        out[name] = _python_value(value)
    return out


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
    ds.attrs.update(restoring_attributes(extra, attrs, rho))
    return ds


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
