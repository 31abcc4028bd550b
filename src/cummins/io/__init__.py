"""Readers and writers of hydrodynamic data, with format detection by content.

``read(path)`` returns a canonical ``HydroDB`` (see :mod:`cummins.hydrodb`) from:

========= ================================================================== ==============
format    files                                                              module
========= ================================================================== ==============
wamit     WAMIT ``.1`` (+ ``.3``, ``.hst``, ``.frc``, ``.out``)              :mod:`.wamit`
wamit-out WAMIT ``.out`` log on its own                                      :mod:`.wamit`
hams      HAMS project (``Input/ControlFile.in`` + ``Output*/Wamit_format``) :mod:`.hams`
nemoh     NEMOH v2/v3 ``RadiationCoefficients.tec`` … (file or folder)       :mod:`.nemoh`
aqwa      ANSYS AQWA ``.LIS`` (or ``.AH1``)                                  :mod:`.aqwa`
veres     ShipX/VERES ``.re7`` (+ ``.re8``, ``.re1``)                        :mod:`.veres`
netcdf    Capytaine NetCDF (and cummins' own, which is the same layout)      :mod:`.netcdf`
bemio     WEC-Sim's BEMIO ``.h5`` (MATLAB and 2015 Python layouts)           :mod:`.bemio`
mss       Marine Systems Simulator ``vessel`` struct (``.mat``)              :mod:`.mss`
========= ================================================================== ==============

``write(ds, path)`` writes canonical NetCDF (``.nc``), a BEMIO ``.h5`` for WEC-Sim, or
an MSS ``vessel`` ``.mat``.
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from cummins.errors import ArgumentError, HydroDataError, check_writable

if TYPE_CHECKING:
    import xarray as xr


@dataclass(frozen=True)
class Format:
    """A file format cummins reads.

    Attributes
    ----------
    name
        Short name, as passed to ``read(..., format=name)``.
    description
        What the user has on disk, in a few words.
    module
        Module implementing ``sniff(path) -> bool``, ``sniff_dir(path) -> list[Path]``
        and the reader function ``reader``.
    reader
        Name of the reader function in ``module``.
    nondimensional
        True if the files are nondimensional (``rho``, ``g``, ``ulen`` matter).
    sniff_function, sniff_dir_function
        Names of the detection functions in ``module`` (``sniff_dir_function=None``:
        the format is never detected in a folder).
    """

    name: str
    description: str
    module: str
    reader: str
    nondimensional: bool = False
    sniff_function: str = "sniff"
    sniff_dir_function: str | None = "sniff_dir"

    def _module(self):
        return importlib.import_module(self.module)

    def sniff(self, path: Path) -> bool:
        try:
            return bool(getattr(self._module(), self.sniff_function)(path))
        except (OSError, ValueError, HydroDataError):
            return False

    def sniff_dir(self, path: Path) -> list[Path]:
        if self.sniff_dir_function is None:
            return []
        try:
            return list(getattr(self._module(), self.sniff_dir_function)(path))
        except (OSError, ValueError, HydroDataError):
            return []

    def read(self, path: Path, **options) -> xr.Dataset:
        function: Callable[..., xr.Dataset] = getattr(self._module(), self.reader)
        return function(path, **options)


FORMATS: dict[str, Format] = {
    f.name: f
    for f in (
        Format(
            "wamit",
            "WAMIT numeric files .1/.3/.hst (+ .frc, .out)",
            "cummins.io.wamit",
            "read_wamit",
            nondimensional=True,
        ),
        Format(
            "wamit-out",
            "WAMIT .out log",
            "cummins.io.wamit",
            "read_wamit_out",
            nondimensional=True,
            sniff_function="is_out_file",
            sniff_dir_function=None,
        ),
        Format(
            "hams",
            "HAMS project (Input/ControlFile.in + Output*/Wamit_format)",
            "cummins.io.hams",
            "read_hams",
            nondimensional=True,
        ),
        Format(
            "nemoh",
            "NEMOH v2/v3 results (RadiationCoefficients.tec, ...)",
            "cummins.io.nemoh",
            "read_nemoh",
        ),
        Format("aqwa", "ANSYS AQWA .LIS / .AH1", "cummins.io.aqwa", "read_aqwa"),
        Format("veres", "ShipX/VERES .re7/.re8/.re1", "cummins.io.veres", "read_veres"),
        Format("netcdf", "Capytaine / cummins NetCDF", "cummins.io.netcdf", "read_netcdf"),
        Format("bemio", "WEC-Sim BEMIO .h5", "cummins.io.bemio", "read_bemio"),
        Format("mss", "MSS vessel struct .mat", "cummins.io.mss", "read_mss"),
    )
}


def _formats_hint(path: Path) -> str:
    """The formats read, and for an OpenFAST state-space file where it is read."""
    hint = "supported: " + "; ".join(f.description for f in FORMATS.values())
    if path.suffix.lower() in (".ss", ".ssexctn"):
        hint += (
            ". An OpenFAST state-space model (.ss, .ssexctn) is described by `cummins info` "
            "and read by cummins.io.openfast.read_openfast_ss / read_openfast_ssexctn"
        )
    return hint


def detect_format(path: str | os.PathLike[str]) -> tuple[str, Path]:
    """Find the format of a file or folder by its content.

    Returns
    -------
    (format name, file to read)
        For a folder, the file the reader starts from.

    Raises
    ------
    HydroDataError
        Nothing recognised, or a folder holding several runs or several solvers' output.
    """
    p = Path(path)
    if not p.exists():
        raise HydroDataError("no such file or folder", path=p)
    if p.is_dir():
        found = [(name, f) for name, fmt in FORMATS.items() for f in fmt.sniff_dir(p)]
        if not found:
            raise HydroDataError(
                "no solver output recognised in this folder",
                path=p,
                hint=_formats_hint(p),
            )
        if len(found) > 1:
            listing = ", ".join(f"{name}: {f.name}" for name, f in found)
            if len({name for name, _ in found}) == 1:
                example = p / found[0][1].relative_to(p)
                hint = (
                    f"read one run by its file, e.g. cummins.read('{example}') "
                    f"or `cummins info {example}`"
                )
            else:
                hint = "pass one file, or format= (--format) to choose the solver"
            raise HydroDataError(f"this folder holds several runs ({listing})", path=p, hint=hint)
        return found[0]
    if p.stat().st_size == 0:
        raise HydroDataError("the file is empty", path=p)
    names = [name for name, fmt in FORMATS.items() if fmt.sniff(p)]
    if not names:
        from cummins.io.hydrodyn_input import hydrodyn_hint

        hydrodyn = hydrodyn_hint(p)
        if hydrodyn is not None:
            raise HydroDataError("not solver output", path=p, hint=hydrodyn)
        raise HydroDataError(
            "unrecognised file format",
            path=p,
            hint=_formats_hint(p),
        )
    if len(names) > 1:
        raise HydroDataError(
            f"the content fits several formats ({', '.join(names)})",
            path=p,
            hint="pass format= (--format) to choose",
        )
    return names[0], p


def read(
    path: str | os.PathLike[str],
    format: str | None = None,
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    water_depth: float | None = None,
    **options,
) -> xr.Dataset:
    """Read hydrodynamic data into a canonical ``HydroDB`` (an :class:`xarray.Dataset`).

    Parameters
    ----------
    path
        A solver output file, or a folder holding one run.
    format
        Force a format (see :data:`FORMATS`); detected from the content by default.
    rho, g, ulen
        Water density (kg/m³), gravity (m/s²) and length scale (m) for nondimensional
        formats (WAMIT). For dimensional formats they may only confirm the file's values.
        A value the files do not record is assumed (1025 kg/m³, 9.81 m/s², 1 m) with an
        :class:`~cummins.errors.AssumptionWarning`.
    water_depth
        m (``inf`` for deep water), for files that do not record it (WAMIT numeric files
        without their ``.out``, NEMOH without ``Nemoh.cal``, VERES, BEMIO without
        ``water_depth``): the depth of the wave kinematics (wave numbers, the travel phase
        of the wave force, encounter frequencies, drift and wave loads). Without it those
        take deep water, with an ``AssumptionWarning`` where a result depends on it. A
        value that contradicts the files' is an error.
    **options
        Passed to the format's reader (e.g. ``siblings=False`` for WAMIT).

    Returns
    -------
    xarray.Dataset
        Dimensional, SI units; see :mod:`cummins.hydrodb` for names and conventions.

    Raises
    ------
    HydroDataError
        Unreadable, damaged or inconsistent files, naming the file and line.

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.read(cummins.demo_files() / "tanker.1")
    >>> ds.added_mass.dims
    ('omega', 'influenced_dof', 'radiating_dof')
    """
    if format is None:
        name, target = detect_format(path)
    else:
        if format not in FORMATS:
            raise HydroDataError(
                f"unknown format {format!r}", hint=f"choose one of {', '.join(FORMATS)}"
            )
        name, target = format, Path(path)
        if target.is_dir():
            files = FORMATS[name].sniff_dir(target)
            if len(files) != 1:
                raise HydroDataError(
                    f"expected one {name} run in this folder, found {len(files)}", path=target
                )
            target = files[0]
    fmt = FORMATS[name]
    constants = {k: v for k, v in (("rho", rho), ("g", g), ("ulen", ulen)) if v is not None}
    if "ulen" in constants and not fmt.nondimensional:
        constants.pop("ulen")
    if water_depth is not None:
        water_depth = float(water_depth)
        if not water_depth > 0:  # NaN, zero, negative
            raise ArgumentError(
                f"water_depth must be > 0 m (inf for deep water), got {water_depth!r}"
            )
        if name in ("wamit", "wamit-out"):  # a wavenumber column is read with it
            options["water_depth"] = water_depth
    ds = fmt.read(target, **constants, **options)
    if water_depth is not None:
        ds = _given_depth(ds, water_depth, target)
    # numbers no floating body has (a quantity scaled by 10^3, a flipped sign) warn here,
    # for the commands that do not run cummins check (deferred: check imports radiation,
    # whose model file imports io)
    from cummins.check.plausibility import warn_implausible

    warn_implausible(ds)
    return ds


def _given_depth(ds: xr.Dataset, depth: float, path: Path) -> xr.Dataset:
    """The data at the water depth the user gives: taken where the files record none, an
    error where they record another."""
    from cummins.hydrodb import add_history
    from cummins.io._common import DEPTH_ASSUMED

    recorded = float(ds.attrs.get("water_depth", float("inf")))
    if ds.attrs.get(DEPTH_ASSUMED):
        out = ds.copy()
        out.attrs["water_depth"] = depth
        del out.attrs[DEPTH_ASSUMED]
        add_history(out, f"water depth = {depth:g} m (given)")
        return out
    same = recorded == depth or abs(recorded - depth) <= 1e-6 * abs(depth)
    if not same:
        raise HydroDataError(
            f"water_depth = {depth:g} m was given but the files record {recorded:g} m",
            path=path,
            hint="the coefficients were computed at the recorded depth: drop --water-depth",
        )
    return ds


def write(ds: xr.Dataset, path: str | os.PathLike[str], *, force: bool = False, model=None) -> Path:
    """Write a ``HydroDB`` to ``.nc`` (Capytaine-compatible NetCDF), ``.h5`` (BEMIO, the
    layout WEC-Sim reads), ``.1`` (WAMIT ``.1``/``.3``/``.hst``, nondimensional with the
    data's ``ulen`` or 1 m: :func:`cummins.io.wamit.numeric_writer.write_wamit`), ``.mat``
    (MSS) or, of its QTFs, ``.12d``/``.12s`` (WAMIT's second-order files, which OpenFAST
    HydroDyn reads: :mod:`cummins.io.wamit.qtf_writer`).

    Refuses to overwrite an existing file unless ``force=True``. ``model`` (a fitted
    :class:`~cummins.radiation.model.RadiationModel`) goes into a ``.h5`` file's state-space
    datasets (see :func:`cummins.io.bemio.write_bemio`).
    """
    p = Path(path)
    check_writable(p, force)
    suffix = p.suffix.lower()
    if model is not None and suffix != ".h5":
        raise HydroDataError(
            f"a radiation model can only be written with the data to .h5, not {suffix}",
            path=p,
            hint="save the model with model.save(...) or cummins fit --openfast/--mss",
        )
    if suffix == ".nc":
        from cummins.io.netcdf import write_netcdf

        write_netcdf(ds, p)
    elif suffix in (".h5", ".hdf5"):
        from cummins.io.bemio import write_bemio

        write_bemio(ds, p, model=model)
    elif suffix == ".mat":
        from cummins.io.mss import write_mss

        write_mss(ds, p)
    elif suffix in (".12d", ".12s"):
        from cummins.io.wamit.qtf_writer import write_wamit_qtf

        write_wamit_qtf(ds, p, force=True)  # the overwrite check is above
    elif suffix == ".1":
        from cummins.io.wamit.numeric_writer import write_wamit

        write_wamit(ds, p, ulen=float(ds.attrs.get("ulen", 1.0)), force=force)
    else:
        raise HydroDataError(
            f"cannot write {suffix or 'files without an extension'}",
            path=p,
            hint="use .nc (NetCDF, Capytaine layout), .h5 (BEMIO, for WEC-Sim), .1 (WAMIT "
            ".1/.3/.hst, for HydroDyn), .mat (MSS vessel struct) or .12d/.12s (a WAMIT QTF "
            "file, for OpenFAST HydroDyn)",
        )
    return p


__all__ = ["FORMATS", "Format", "detect_format", "read", "write"]
