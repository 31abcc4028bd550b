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

Modules
-------
:mod:`~cummins.io.netcdf.files` (detection, loading), :mod:`~cummins.io.netcdf.reader`
(the mapping to the canonical dataset), :mod:`~cummins.io.netcdf.layout` (DOFs and
bodies), :mod:`~cummins.io.netcdf.checks` (damaged numbers, conventions),
:mod:`~cummins.io.netcdf.legacy` (the legacy exporter's ``KH*.dat``,
``Hydrostatics*.dat``), :mod:`~cummins.io.netcdf.attributes` (attribute encoding) and
:mod:`~cummins.io.netcdf.writer`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cummins._lazy import lazy_attributes
from cummins.io.netcdf.files import load_netcdf, merge_complex, sniff, sniff_dir  # noqa: F401

#: Where the names of the package live; imported on first use (PEP 562), so that
#: recognising a file of another format (``cummins.io.detect_format`` asks every format)
#: imports the detection module only.
_LAZY = {
    "CANONICAL_TIME_CONVENTION": "attributes",
    "FILE_TIME_CONVENTION": "attributes",
    "JSON_ATTRS": "attributes",
    "VERSION_ATTR": "attributes",
    "decode_attribute": "attributes",
    "decode_attributes": "attributes",
    "encode_attribute": "attributes",
    "encode_attributes": "attributes",
    "IMPLAUSIBLE": "checks",
    "DofLayout": "layout",
    "dof_layout": "layout",
    "LegacyExport": "legacy",
    "from_capytaine_dataset": "reader",
    "read_netcdf": "reader",
    "save_netcdf": "writer",
    "to_capytaine_layout": "writer",
    "write_netcdf": "writer",
}

if TYPE_CHECKING:  # pragma: no cover
    from cummins.io.netcdf.attributes import (  # noqa: F401
        CANONICAL_TIME_CONVENTION,
        FILE_TIME_CONVENTION,
        JSON_ATTRS,
        VERSION_ATTR,
        decode_attribute,
        decode_attributes,
        encode_attribute,
        encode_attributes,
    )
    from cummins.io.netcdf.checks import IMPLAUSIBLE  # noqa: F401
    from cummins.io.netcdf.layout import DofLayout, dof_layout  # noqa: F401
    from cummins.io.netcdf.legacy import LegacyExport  # noqa: F401
    from cummins.io.netcdf.reader import from_capytaine_dataset, read_netcdf
    from cummins.io.netcdf.writer import save_netcdf, to_capytaine_layout, write_netcdf  # noqa: F401

__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, globals())


__all__ = ["from_capytaine_dataset", "read_netcdf", "sniff", "sniff_dir", "write_netcdf"]
