"""The canonical hydrodynamic database (``HydroDB``).

A ``HydroDB`` is an :class:`xarray.Dataset` with Capytaine's names, always dimensional
and in SI units, whatever solver produced it:

==========================  ==========================================  ===================
variable                    dims                                        unit
==========================  ==========================================  ===================
``added_mass``              omega, influenced_dof, radiating_dof        kg, kg·m, kg·m²
``radiation_damping``       omega, influenced_dof, radiating_dof        kg/s, kg·m/s, …
``added_mass_inf``          influenced_dof, radiating_dof               as added mass
``added_mass_zero``         influenced_dof, radiating_dof               as added mass
``excitation_force``        omega, wave_direction, influenced_dof       N/m, N·m/m (complex)
``Froude_Krylov_force``     omega, wave_direction, influenced_dof       N/m, N·m/m (complex)
``diffraction_force``       omega, wave_direction, influenced_dof       N/m, N·m/m (complex)
``rao``                     omega, wave_direction, radiating_dof        m/m, rad/m (complex)
``drift_force``             omega, wave_direction, influenced_dof       N/m², N·m/m² (mean)
``drift_force_<method>``    as drift_force: the run's other estimates   N/m², N·m/m²
``qtf_difference``          qtf_omega, qtf_omega2, qtf_wave_direction,  N/m², N·m/m² (complex)
                            [qtf_wave_direction2,] influenced_dof
``qtf_sum``                 as qtf_difference                           N/m², N·m/m² (complex)
``hydrostatic_stiffness``   influenced_dof, radiating_dof               N/m, N, N·m/rad
``inertia_matrix``          influenced_dof, radiating_dof               kg, kg·m, kg·m²
``additional_added_mass``   omega, influenced_dof, radiating_dof        as added mass
``additional_damping``      omega, influenced_dof, radiating_dof        as damping
``additional_stiffness``    influenced_dof, radiating_dof               as stiffness
==========================  ==========================================  ===================

Only ``added_mass`` and ``radiation_damping`` are required. The second-order variables
(the QTFs on their own frequency grid, their force convention) are described in
:mod:`cummins.qtf.data`. Coordinates: ``omega``
(rad/s, finite, strictly increasing, > 0; the limits ω = 0 and ω = ∞ live in
``added_mass_zero`` and ``added_mass_inf``), ``wave_direction`` (rad, direction in
which the waves travel, measured from +x towards +y: 0 = following seas, π = head seas),
``influenced_dof`` / ``radiating_dof`` (labels ``Surge`` … ``Yaw``; ``body__Heave`` for
several bodies; made and read by :mod:`cummins.dofs`), and optionally ``forward_speed``
(m/s, scalar or a dimension).

Conventions: time dependence x(t) = Re{X e^{iωt}}; ``added_mass[ω, i, j]`` is the force
in DOF i due to a unit acceleration in DOF j; attributes ``rho`` (kg/m³), ``g`` (m/s²),
``water_depth`` (m, ``inf`` for deep water), ``source_format``, ``source_file``,
``reference_point`` (m, the point about which moments and rotations are taken),
``axis_convention`` (``"z-up"``: x forward, y to port, z up, as WAMIT, NEMOH, AQWA,
Capytaine; ``"z-down"``: Fossen's body axes x forward, y to starboard, z down, as MSS),
and ``history`` (one line per conversion applied since the file was read); readers add
``water_depth_assumed`` when the files do not record the depth, and what the restoring
holds (``restoring_source``, ``restoring_weight_mass``, ``restoring_weight_center``:
:mod:`cummins.restoring`).
Positions (``reference_point``, ``center_of_gravity``, ``center_of_buoyancy``) are
coordinates in the body axes of the dataset, from its coordinate origin."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.dofs import (
    DOF_NAMES,
    bodies,
    body_names,
    is_rigid_body_dof,
    mass_dofs,
    split_dof,
)
from cummins.dofs import dof_index as dof_index
from cummins.dofs import dof_labels as dof_labels
from cummins.dofs import is_rotation as is_rotation
from cummins.errors import AssumptionWarning, HydroDataError
from cummins.kinematics import Z_UP_TO_Z_DOWN, screw_transform
from cummins.qtf.data import second_order_summary

AXIS_CONVENTIONS: dict[str, str] = {
    "z-up": "x forward, y to port, z up (WAMIT, NEMOH, AQWA, Capytaine)",
    "z-down": "x forward, y to starboard, z down (Fossen body axes, MSS)",
}

#: Variables holding a DOF×DOF matrix (influenced_dof, radiating_dof).
MATRIX_VARIABLES: tuple[str, ...] = (
    "added_mass",
    "radiation_damping",
    "added_mass_inf",
    "added_mass_zero",
    "hydrostatic_stiffness",
    "inertia_matrix",
    "additional_added_mass",
    "additional_damping",
    "additional_stiffness",
)
#: Variables holding a generalized force per DOF (influenced_dof).
FORCE_VARIABLES: tuple[str, ...] = (
    "excitation_force",
    "Froude_Krylov_force",
    "diffraction_force",
    "drift_force",
    # second-order loads (cummins.qtf): the other mean-drift estimates and the QTFs,
    # forces and moments about the reference point like the first-order forces
    "drift_force_pressure",
    "drift_force_momentum",
    "drift_force_control_surface",
    "qtf_difference",
    "qtf_sum",
)
#: Variables holding a generalized motion per DOF (radiating_dof).
MOTION_VARIABLES: tuple[str, ...] = ("rao",)

_UNITS = {
    "added_mass": "kg | kg m | kg m^2 (translation-translation | mixed | rotation-rotation)",
    "added_mass_inf": "kg | kg m | kg m^2",
    "added_mass_zero": "kg | kg m | kg m^2",
    "inertia_matrix": "kg | kg m | kg m^2",
    "radiation_damping": "kg/s | kg m/s | kg m^2/s",
    "additional_added_mass": "kg | kg m | kg m^2",
    "additional_damping": "kg/s | kg m/s | kg m^2/s",
    "additional_stiffness": "N/m | N/rad, N | N m/rad",
    "hydrostatic_stiffness": "N/m | N/rad, N | N m/rad",
    "excitation_force": "N/m | N m/m (per metre of wave amplitude)",
    "Froude_Krylov_force": "N/m | N m/m (per metre of wave amplitude)",
    "diffraction_force": "N/m | N m/m (per metre of wave amplitude)",
    "drift_force": "N/m^2 | N m/m^2 (mean drift per squared wave amplitude)",
    "rao": "m/m | rad/m (per metre of wave amplitude)",
}

_LONG_NAMES = {
    "added_mass": "added mass A(omega)",
    "radiation_damping": "radiation (potential) damping B(omega)",
    "added_mass_inf": "infinite-frequency added mass A(inf)",
    "added_mass_zero": "zero-frequency added mass A(0)",
    "inertia_matrix": "rigid-body inertia matrix M_RB",
    "additional_added_mass": "added mass supplied with the data besides the potential-flow "
    "added mass (VERES additional added mass, e.g. an anti-roll tank)",
    "additional_damping": "linear damping supplied with the data besides radiation damping "
    "(WAMIT .frc external damping, MSS viscous damping Bv, VERES roll damping)",
    "additional_stiffness": "linear stiffness supplied with the data besides hydrostatics "
    "(WAMIT .frc external stiffness, e.g. moorings)",
    "hydrostatic_stiffness": "hydrostatic and gravitational restoring matrix C",
    "excitation_force": "first-order wave excitation force (Froude-Krylov + diffraction)",
    "Froude_Krylov_force": "Froude-Krylov force",
    "diffraction_force": "diffraction force",
    "drift_force": "mean second-order wave drift force",
    "rao": "motion response amplitude operator (as computed by the solver)",
}


# ----------------------------------------------------------------- bodies, speeds, matrices


def rename_bodies(ds: xr.Dataset, names: Sequence[str] | None = None) -> xr.Dataset:
    """Relabel the DOFs of a multi-body dataset ``body1__Heave`` → ``<name>__Heave``.

    ``names`` defaults to the names the file gave (``body_names`` attribute). A copy is
    returned; the relabelling is written to ``history``.
    """
    current = [b for b in bodies(ds) if b is not None]
    if not current:
        return ds
    names = list(names) if names is not None else body_names(ds)
    if len(names) != len(current) or len(set(names)) != len(names):
        raise HydroDataError(
            f"{len(names)} body names given ({', '.join(map(str, names))}) for "
            f"{len(current)} bodies ({', '.join(map(str, current))})",
            hint="give one distinct name per body, in the order of the DOFs",
        )
    mapping = dict(zip(current, names, strict=True))

    def relabel(label: str) -> str:
        body, name = split_dof(label)
        return f"{mapping[body]}__{name}" if body is not None else name

    out = ds.copy()
    for dim in ("influenced_dof", "radiating_dof"):
        if dim in out.coords:
            out = out.assign_coords({dim: [relabel(str(v)) for v in out[dim].values]})
    add_history(out, "bodies renamed: " + ", ".join(f"{a} -> {b}" for a, b in mapping.items()))
    return out


def single_speed(ds: xr.Dataset) -> xr.Dataset:
    """The dataset at its one forward speed (the ``forward_speed`` dimension dropped);
    HydroDataError when it holds several: the caller must choose."""
    if "forward_speed" in ds.dims:
        if ds.sizes["forward_speed"] == 1:
            return ds.isel(forward_speed=0)
        speeds = ", ".join(f"{u:g}" for u in ds.forward_speed.values)
        raise HydroDataError(
            f"the dataset holds {ds.sizes['forward_speed']} forward speeds ({speeds} m/s)",
            hint="select one first, e.g. ds.sel(forward_speed=0.0)",
        )
    return ds


def dof_matrix(ds: xr.Dataset, name: str) -> NDArray[np.float64]:
    """``ds[name]`` as a float array (…, influenced_dof, radiating_dof): (n, n), or
    (nω, n, n) for frequency-dependent variables. Always a copy (no DataArray is built)."""
    var = ds.variables[name].transpose(..., "influenced_dof", "radiating_dof")
    return np.array(var.values, dtype=float)


# --------------------------------------------------------------------------- construction


def make_hydrodb(
    omega: ArrayLike,
    added_mass: ArrayLike,
    radiation_damping: ArrayLike,
    *,
    rho: float,
    g: float,
    source_format: str,
    source_file: str = "",
    dofs: Sequence[str] | None = None,
    water_depth: float = np.inf,
    wave_direction: ArrayLike | None = None,
    excitation_force: ArrayLike | None = None,
    froude_krylov_force: ArrayLike | None = None,
    diffraction_force: ArrayLike | None = None,
    rao: ArrayLike | None = None,
    drift_force: ArrayLike | None = None,
    added_mass_inf: ArrayLike | None = None,
    added_mass_zero: ArrayLike | None = None,
    hydrostatic_stiffness: ArrayLike | None = None,
    inertia_matrix: ArrayLike | None = None,
    additional_added_mass: ArrayLike | None = None,
    additional_damping: ArrayLike | None = None,
    additional_stiffness: ArrayLike | None = None,
    forward_speed: float | None = None,
    reference_point: ArrayLike = (0.0, 0.0, 0.0),
    axis_convention: str = "z-up",
    history: Iterable[str] = (),
    read_warnings: Iterable[str] = (),
    **attrs: Any,
) -> xr.Dataset:
    """Assemble and validate a canonical hydrodynamic dataset from arrays.

    Readers call this once they have converted the solver's numbers to SI units; it
    is also the way to build a ``HydroDB`` from arrays of one's own.

    Parameters
    ----------
    omega
        Wave (or encounter) frequencies, rad/s, shape (nω,), finite and > 0; sorted
        here if needed. Put the ω = 0 and ω = ∞ limits in ``added_mass_zero`` and
        ``added_mass_inf``, not in this grid.
    added_mass, radiation_damping
        Shape (nω, n, n): ``[k, i, j]`` is the force in DOF i due to motion in DOF j.
    rho, g
        Water density (kg/m³) and acceleration of gravity (m/s²).
    source_format, source_file
        Provenance, recorded as attributes.
    dofs
        DOF labels (default ``Surge`` … ``Yaw``).
    water_depth
        Metres; ``inf`` for deep water.
    wave_direction
        Directions of wave propagation, rad, shape (nβ,). Required with any of the
        wave-dependent arrays below.
    excitation_force, froude_krylov_force, diffraction_force, rao, drift_force
        Shape (nω, nβ, n): complex first-order forces per metre of wave amplitude
        (N/m, N·m/m), motion RAOs (m/m, rad/m), real mean drift force per squared
        amplitude (N/m², N·m/m²).
    added_mass_inf, added_mass_zero, hydrostatic_stiffness, inertia_matrix
        Shape (n, n).
    additional_added_mass
        Shape (nω, n, n): added mass supplied besides the potential-flow one (VERES
        additional added mass, e.g. of an anti-roll tank).
    additional_damping
        Shape (nω, n, n): linear damping supplied with the data besides the radiation
        damping (WAMIT external damping, MSS viscous damping, VERES roll damping).
    additional_stiffness
        Shape (n, n): linear stiffness supplied besides hydrostatics (moorings).
    forward_speed
        m/s, recorded as a scalar coordinate.
    reference_point
        Point about which moments and rotations are taken, m, in the dataset's axes.
    axis_convention
        ``"z-up"`` or ``"z-down"``, see :data:`AXIS_CONVENTIONS`.
    history
        Lines describing conversions and assumptions (e.g. default density used).
    read_warnings
        Damage the reader worked around (see :func:`cummins.io._common.warn_damage`),
        stored as the ``read_warnings`` attribute (one line each) and repeated by
        ``cummins check`` as findings.
    **attrs
        Further attributes (``body_name``, ``center_of_gravity`` …).

    Returns
    -------
    xarray.Dataset
        The validated ``HydroDB``.

    Raises
    ------
    HydroDataError
        Inconsistent shapes, non-finite values, duplicate frequencies.

    Examples
    --------
    >>> import numpy as np
    >>> w = np.array([0.5, 1.0])
    >>> a = np.tile(np.eye(6), (2, 1, 1)) * 1e3
    >>> ds = make_hydrodb(w, a, a * 0.1, rho=1025.0, g=9.81, source_format="arrays")
    >>> ds.added_mass.sel(influenced_dof="Heave", radiating_dof="Heave").values
    array([1000., 1000.])
    """
    omega = np.asarray(omega, dtype=float).reshape(-1)
    n_omega = omega.size
    labels = list(dofs) if dofs is not None else list(DOF_NAMES)
    n = len(labels)
    where = source_file or source_format

    def matrix3(name: str, value: ArrayLike) -> NDArray:
        arr = np.asarray(value, dtype=float)
        if arr.shape != (n_omega, n, n):
            raise HydroDataError(
                f"{name} has shape {arr.shape}, expected {(n_omega, n, n)} "
                "(frequencies, influenced DOF, radiating DOF)",
                path=where,
            )
        return arr

    data_vars: dict[str, tuple[tuple[str, ...], NDArray]] = {
        "added_mass": (
            ("omega", "influenced_dof", "radiating_dof"),
            matrix3("added_mass", added_mass),
        ),
        "radiation_damping": (
            ("omega", "influenced_dof", "radiating_dof"),
            matrix3("radiation_damping", radiation_damping),
        ),
    }
    for name, value in (
        ("additional_added_mass", additional_added_mass),
        ("additional_damping", additional_damping),
    ):
        if value is not None:
            data_vars[name] = (("omega", "influenced_dof", "radiating_dof"), matrix3(name, value))
    for name, value in (
        ("added_mass_inf", added_mass_inf),
        ("added_mass_zero", added_mass_zero),
        ("hydrostatic_stiffness", hydrostatic_stiffness),
        ("inertia_matrix", inertia_matrix),
        ("additional_stiffness", additional_stiffness),
    ):
        if value is None:
            continue
        arr = np.asarray(value, dtype=float)
        if arr.shape != (n, n):
            raise HydroDataError(f"{name} has shape {arr.shape}, expected {(n, n)}", path=where)
        data_vars[name] = (("influenced_dof", "radiating_dof"), arr)

    coords: dict[str, Any] = {
        "omega": ("omega", omega, {"units": "rad/s", "long_name": "wave frequency"}),
        "influenced_dof": ("influenced_dof", labels),
        "radiating_dof": ("radiating_dof", labels),
    }
    wave_arrays = {
        "excitation_force": (excitation_force, complex, "influenced_dof"),
        "Froude_Krylov_force": (froude_krylov_force, complex, "influenced_dof"),
        "diffraction_force": (diffraction_force, complex, "influenced_dof"),
        "rao": (rao, complex, "radiating_dof"),
        "drift_force": (drift_force, float, "influenced_dof"),
    }
    if any(v[0] is not None for v in wave_arrays.values()):
        if wave_direction is None:
            raise HydroDataError("wave-dependent data given without wave_direction", path=where)
        beta = np.asarray(wave_direction, dtype=float).reshape(-1)
        coords["wave_direction"] = (
            "wave_direction",
            beta,
            {"units": "rad", "long_name": "direction of wave propagation (0 = along +x)"},
        )
        for name, (value, dtype, dof_dim) in wave_arrays.items():
            if value is None:
                continue
            arr = np.asarray(value, dtype=dtype)
            if arr.shape != (n_omega, beta.size, n):
                raise HydroDataError(
                    f"{name} has shape {arr.shape}, expected {(n_omega, beta.size, n)} "
                    "(frequencies, wave directions, DOF)",
                    path=where,
                )
            data_vars[name] = (("omega", "wave_direction", dof_dim), arr)
    if forward_speed is not None:
        coords["forward_speed"] = ((), float(forward_speed), {"units": "m/s"})

    ds = xr.Dataset(data_vars, coords=coords)
    for name in ds.data_vars:
        ds[name].attrs.update(units=_UNITS[name], long_name=_LONG_NAMES[name])
    if axis_convention not in AXIS_CONVENTIONS:
        raise HydroDataError(
            f"unknown axis_convention {axis_convention!r}",
            hint=f"use one of {', '.join(AXIS_CONVENTIONS)}",
        )
    ds.attrs.update(
        rho=float(rho),
        g=float(g),
        water_depth=float(water_depth),
        source_format=str(source_format),
        source_file=str(source_file),
        reference_point=_points(reference_point, "reference_point", where),
        axis_convention=axis_convention,
        time_convention="x(t) = Re{X exp(i omega t)}",
        history="\n".join(history),
    )
    read_warnings = [str(w) for w in read_warnings]
    if read_warnings:
        ds.attrs["read_warnings"] = "\n".join(read_warnings)
    for key, value in attrs.items():
        if value is not None:
            ds.attrs[key] = value

    if np.any(np.diff(omega) <= 0):
        order = np.argsort(omega, kind="stable")
        sorted_omega = omega[order]
        duplicated = sorted_omega[1:][np.diff(sorted_omega) == 0]
        if duplicated.size:
            raise HydroDataError(
                f"frequency {duplicated[0]:.6g} rad/s appears more than once",
                path=where,
                hint="each frequency must appear once; check the file is not two runs joined",
            )
        ds = ds.isel(omega=order)
        add_history(ds, "frequencies sorted into increasing order")
    validate(ds)
    return ds


def _points(value: ArrayLike, name: str, where: str) -> NDArray[np.float64]:
    """Positions as a flat array of 3 coordinates per body."""
    arr = np.asarray(value, dtype=float).reshape(-1)
    if arr.size == 0 or arr.size % 3:
        raise HydroDataError(
            f"{name} needs 3 coordinates per body, got {arr.size} values", path=where
        )
    return arr


def add_history(ds: xr.Dataset, line: str) -> None:
    """Append a line to the dataset's ``history`` attribute (in place)."""
    old = ds.attrs.get("history", "")
    ds.attrs["history"] = f"{old}\n{line}" if old else line


def stack_forward_speeds(datasets: Sequence[xr.Dataset]) -> xr.Dataset:
    """Join single-speed datasets along a new ``forward_speed`` dimension.

    Each dataset must carry a scalar ``forward_speed`` coordinate and share the
    frequency grid, wave directions and DOFs.
    """
    if not datasets:
        raise HydroDataError("no datasets to stack")
    for ds in datasets:
        if "forward_speed" not in ds.coords:
            raise HydroDataError("dataset without a forward_speed coordinate cannot be stacked")
    first = datasets[0]
    for ds in datasets[1:]:
        if not np.array_equal(ds.omega.values, first.omega.values):
            raise HydroDataError(
                "datasets at different forward speeds have different frequency grids"
            )
    out = xr.concat(datasets, dim="forward_speed", combine_attrs="override")
    out["forward_speed"].attrs["units"] = "m/s"
    return out


# --------------------------------------------------------------------------- validation


def validate(ds: xr.Dataset) -> xr.Dataset:
    """Check that ``ds`` is a well-formed ``HydroDB``; return it unchanged.

    Structural checks only (dimensions, units attributes, finite values, frequency
    grid). Physical plausibility (symmetry, positive damping …) is the job of
    :func:`cummins.check`.

    Raises
    ------
    HydroDataError
        Naming the variable, frequency and DOF pair at fault.
    """
    where = ds.attrs.get("source_file") or ds.attrs.get("source_format") or None
    for name in ("added_mass", "radiation_damping"):
        if name not in ds:
            raise HydroDataError(f"dataset has no {name!r} variable", path=where)
    for dim in ("omega", "influenced_dof", "radiating_dof"):
        if dim not in ds.dims:
            raise HydroDataError(f"dataset has no {dim!r} dimension", path=where)
    if list(ds.influenced_dof.values) != list(ds.radiating_dof.values):
        raise HydroDataError("influenced_dof and radiating_dof labels differ", path=where)
    omega = ds.omega.values
    if omega.size == 0:
        raise HydroDataError("no frequencies in the data", path=where)
    if not np.all(np.isfinite(omega)):
        raise HydroDataError(
            "the frequency grid contains non-finite values",
            path=where,
            hint="store the omega = infinity limit in added_mass_inf",
        )
    if np.any(omega <= 0):
        raise HydroDataError(
            f"frequency {omega[omega <= 0][0]:g} rad/s is not positive",
            path=where,
            hint="store the omega = 0 limit in added_mass_zero",
        )
    if np.any(np.diff(omega) <= 0):
        k = int(np.argmax(np.diff(omega) <= 0))
        raise HydroDataError(
            f"frequencies are not strictly increasing: {omega[k]:g} then {omega[k + 1]:g} rad/s",
            path=where,
        )
    for var in ds.data_vars.values():
        values = var.values
        bad = ~np.isfinite(values)
        if bad.any():
            raise HydroDataError(
                "non-finite value (NaN or Inf)",
                path=where,
                quantity=_describe_element(var, np.argwhere(bad)[0]),
                hint="the file is damaged or the solver failed at this point; "
                "rerun it or remove the frequency",
            )
    for key in ("rho", "g"):
        value = ds.attrs.get(key)
        if value is None or not np.isfinite(value) or value <= 0:
            raise HydroDataError(
                f"attribute {key!r} must be a positive number, got {value!r}", path=where
            )
    depth = ds.attrs.get("water_depth", np.inf)
    if not depth > 0:
        raise HydroDataError(f"water_depth must be positive or inf, got {depth!r}", path=where)
    return ds


def _describe_element(var: xr.DataArray, index: Sequence[int]) -> str:
    parts = []
    for dim, i in zip(var.dims, index, strict=True):
        value = var[dim].values[i] if dim in var.coords else i
        if dim == "omega":
            parts.append(f"omega={float(value):.6g} rad/s")
        elif dim == "wave_direction":
            parts.append(f"wave_direction={np.degrees(float(value)):.6g} deg")
        elif dim == "forward_speed":
            parts.append(f"forward_speed={float(value):.6g} m/s")
        else:
            parts.append(str(value))
    return f"{var.name}[{', '.join(parts)}]"


# --------------------------------------------------------------------------- selection


def select_dofs(ds: xr.Dataset, dofs: Sequence[str]) -> xr.Dataset:
    """Keep only the given DOFs (in both ``influenced_dof`` and ``radiating_dof``).

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.demo_dataset()
    >>> cummins.select_dofs(ds, ["Heave", "Pitch"]).added_mass.shape
    (58, 2, 2)
    """
    labels = [str(d) for d in ds.influenced_dof.values]
    missing = [d for d in dofs if d not in labels]
    if missing:
        raise HydroDataError(
            f"DOF {missing[0]!r} is not in the data", hint=f"available: {', '.join(labels)}"
        )
    return ds.sel(influenced_dof=list(dofs), radiating_dof=list(dofs))


# --------------------------------------------------------------------------- transforms


def per_body_transform(ds: xr.Dataset, block) -> NDArray[np.float64]:
    """Block-diagonal matrix with ``block(body_index)`` (6×6) on the six rigid-body modes of
    each body and the identity on its generalized modes (``Mode7`` …), which stay as they
    are: their amplitudes are defined by the solver's mode shapes, not by the axes."""
    from scipy.linalg import block_diag  # here: reading a file need not load scipy.linalg

    labels = [str(d) for d in ds.influenced_dof.values]
    blocks = []
    start = 0
    for k, body in enumerate(bodies(ds)):
        own = [lab for lab in labels if split_dof(lab)[0] == body]
        expected = [f"{body}__{d}" if body else d for d in DOF_NAMES]
        extra = own[6:]
        if (
            labels[start : start + len(own)] != own
            or own[:6] != expected
            or any(is_rigid_body_dof(lab) for lab in extra)
        ):
            raise HydroDataError(
                "this transform needs all six DOFs of each body in the order Surge … Yaw "
                "(then its generalized modes)",
                hint="read the full 6-DOF data, transform, then select_dofs",
            )
        blocks.append(block_diag(block(k), np.eye(len(extra))))
        start += len(own)
    return block_diag(*blocks)


def _apply(ds: xr.Dataset, left: NDArray, right: NDArray, motion: NDArray) -> xr.Dataset:
    """Return a copy with matrices L·M·R, forces L·F, motions motion·X."""
    out = ds.copy(deep=True)
    for name in MATRIX_VARIABLES:
        if name in out:
            v = out[name].transpose(..., "influenced_dof", "radiating_dof")
            out[name] = v.copy(data=left @ v.values @ right).transpose(*ds[name].dims)
    for name in FORCE_VARIABLES:
        if name in out:
            v = out[name].transpose(..., "influenced_dof")
            out[name] = v.copy(data=v.values @ left.T).transpose(*ds[name].dims)
    for name in MOTION_VARIABLES:
        if name in out:
            v = out[name].transpose(..., "radiating_dof")
            out[name] = v.copy(data=v.values @ motion.T).transpose(*ds[name].dims)
    return out


def reference_points(ds: xr.Dataset) -> NDArray[np.float64]:
    points = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float)
    return points.reshape(-1, 3)


def move_reference_point(ds: xr.Dataset, point: ArrayLike) -> xr.Dataset:
    """Express the data about another reference point (the screw transform).

    With r the vector from the new point O to the old point W, matrices become
    ``H(r)ᵀ M H(r)``, forces ``H(r)ᵀ F`` (Smogeli et al. (2004) eqs. 15, 38, 45) and motions
    ``H(−r) ξ`` (eq. 16 inverted). This is exact for added mass, damping, inertia and
    wave forces, and for a restoring holding the weight of ρ∇; one of a weight m ≠ ρ∇ (0: the
    hydrostatics alone) gets C₄₄, C₅₅ −(ρ∇ − m)gΔz … (:func:`~cummins.restoring.moved_restoring`).

    Parameters
    ----------
    ds
        A ``HydroDB`` with all six DOFs of each body.
    point
        New reference point, m, in the dataset's axes (shape (3,), or (nbodies, 3)).

    Returns
    -------
    xarray.Dataset
        A new dataset; ``attrs["reference_point"]`` is updated.

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.demo_dataset()
    >>> moved = cummins.move_reference_point(ds, [10.0, 0.0, 0.0])
    >>> back = cummins.move_reference_point(moved, ds.attrs["reference_point"])
    >>> bool(abs(back.added_mass - ds.added_mass).max() < 1e-6 * abs(ds.added_mass).max())
    True
    """
    old = reference_points(ds)
    new = np.broadcast_to(np.asarray(point, dtype=float).reshape(-1, 3), old.shape)
    r = old - new
    h = per_body_transform(ds, lambda k: screw_transform(r[k]))
    h_inv = per_body_transform(ds, lambda k: screw_transform(-r[k]))
    from cummins.restoring import moved_restoring  # restoring imports this module

    out, note = moved_restoring(_apply(ds, h.T, h, h_inv), old, new)
    out.attrs["reference_point"] = new.reshape(-1) if new.shape[0] > 1 else new[0].copy()
    moved = f"{np.round(old, 6).tolist()} to {np.round(new, 6).tolist()} m"
    add_history(out, f"reference point moved from {moved}" + (f" ({note})" if note else ""))
    return out


def change_axes(ds: xr.Dataset, to: str) -> xr.Dataset:
    """Change the axis convention between solver axes and Fossen's body axes.

    ``"z-up"`` (x forward, y to port, z up) and ``"z-down"`` (x forward, y to
    starboard, z down) differ by a rotation of π about x: with T = diag(1, −1, −1, 1,
    −1, −1), matrices become T M T, forces and motions T F, positions (x, −y, −z), and
    a wave travelling at angle β from +x towards +y travels at −β in the new axes.

    Parameters
    ----------
    ds
        A ``HydroDB`` with all six DOFs of each body.
    to
        ``"z-up"`` or ``"z-down"``.

    Returns
    -------
    xarray.Dataset
        A new dataset (or ``ds`` itself when it already has that convention).
    """
    if to not in AXIS_CONVENTIONS:
        raise HydroDataError(
            f"unknown axis convention {to!r}", hint=f"use one of {', '.join(AXIS_CONVENTIONS)}"
        )
    current = ds.attrs.get("axis_convention", "z-up")
    if current == to:
        return ds
    t = per_body_transform(ds, lambda k: np.diag(Z_UP_TO_Z_DOWN))
    out = _apply(ds, t, t, t)
    flip = np.array([1.0, -1.0, -1.0])
    for key in (
        "reference_point",
        "center_of_gravity",
        "center_of_buoyancy",
        "restoring_weight_center",
    ):
        if key in out.attrs:
            out.attrs[key] = (
                np.asarray(out.attrs[key], dtype=float).reshape(-1, 3) * flip
            ).reshape(-1)
    if "wave_direction" in out.dims:
        beta = np.mod(-out.wave_direction.values, 2 * np.pi)
        beta[np.isclose(beta, 2 * np.pi)] = 0.0
        out = out.assign_coords(wave_direction=("wave_direction", beta, ds.wave_direction.attrs))
        out = out.sortby("wave_direction")
    for dim in ("qtf_wave_direction", "qtf_wave_direction2"):  # the QTFs' own directions
        if dim in out.dims:
            beta = np.mod(-out[dim].values, 2 * np.pi)
            beta[np.isclose(beta, 2 * np.pi)] = 0.0
            out = out.assign_coords({dim: (dim, beta, ds[dim].attrs)}).sortby(dim)
    out.attrs["axis_convention"] = to
    add_history(out, f"axes changed from {current} to {to} ({AXIS_CONVENTIONS[to]})")
    return out


def water_depth(ds: xr.Dataset, use: str = "the wave numbers") -> float:
    """The data's water depth, m (``inf``: deep water). When the files did not record it
    (the attribute ``water_depth_assumed``), an :class:`~cummins.errors.AssumptionWarning`
    says that ``use`` takes deep water, and how to give the depth."""
    depth = float(ds.attrs.get("water_depth", np.inf))
    if ds.attrs.get("water_depth_assumed"):
        import warnings

        from cummins.io._common import CONSTANT_CHOICES

        source = str(ds.attrs.get("source_file", "") or "")
        name = source.replace("\\", "/").rsplit("/", 1)[-1] + ": " if source else ""
        warnings.warn(
            AssumptionWarning(
                f"{name}the water depth is not recorded in the files: deep water assumed for "
                f"{use}; give {CONSTANT_CHOICES['water_depth']} if the run had a finite depth"
            ),
            stacklevel=3,
        )
    return depth


def describe(ds: xr.Dataset) -> dict[str, Any]:
    """A short, JSON-ready description of a ``HydroDB`` (what ``cummins info`` prints)."""
    w = ds.omega.values
    info: dict[str, Any] = {
        "source_format": ds.attrs.get("source_format"),
        "source_file": ds.attrs.get("source_file"),
        "dofs": [str(d) for d in ds.influenced_dof.values],
        "bodies": [b for b in bodies(ds) if b is not None],
        "n_omega": int(w.size),
        "omega_min_rad_s": float(w.min()),
        "omega_max_rad_s": float(w.max()),
        "period_range_s": [float(2 * np.pi / w.max()), float(2 * np.pi / w.min())],
        "wave_directions_deg": (
            [float(b) for b in np.degrees(ds.wave_direction.values)]
            if "wave_direction" in ds.dims
            else []
        ),
        "forward_speeds_m_s": (
            [float(u) for u in np.atleast_1d(ds.forward_speed.values)]
            if "forward_speed" in ds.coords
            else [0.0]
        ),
        "variables": sorted(str(v) for v in ds.data_vars),
        "rho_kg_m3": float(ds.attrs["rho"]),
        "g_m_s2": float(ds.attrs["g"]),
        "water_depth_m": float(ds.attrs.get("water_depth", np.inf)),
        "water_depth_assumed": bool(ds.attrs.get("water_depth_assumed", False)),
        "axis_convention": ds.attrs.get("axis_convention"),
        "reference_point_m": [float(x) for x in np.ravel(ds.attrs.get("reference_point", []))],
        "history": [line for line in str(ds.attrs.get("history", "")).splitlines() if line],
    }
    for key in ("center_of_gravity", "center_of_buoyancy"):
        if key in ds.attrs:
            info[f"{key}_m"] = [float(x) for x in np.ravel(ds.attrs[key])]
    # one number for one body, a list of one per body for several
    if "displaced_volume" in ds.attrs:
        volumes = [float(x) for x in np.ravel(ds.attrs["displaced_volume"])]
        info["displaced_volume_m3"] = volumes[0] if len(volumes) == 1 else volumes  # per body
    if "forward_speed" in ds.dims:  # mass and restoring: at the speed nearest zero
        ds = ds.isel(forward_speed=int(np.argmin(np.abs(ds.forward_speed.values))))
    if "inertia_matrix" in ds:
        m = np.diag(dof_matrix(ds, "inertia_matrix"))  # rotations alone: no mass
        if masses := [float(m[k]) for k in mass_dofs(ds.influenced_dof.values)]:
            info["mass_kg"] = masses[0] if len(masses) == 1 else masses
    if "hydrostatic_stiffness" in ds:
        from cummins.restoring import describe_restoring

        info["restoring"] = describe_restoring(ds)
    second = second_order_summary(ds)
    if second:
        info["second_order"] = second
    return info
