"""Writing a BEMIO ``.h5`` file in the MATLAB layout WEC-Sim reads, with cummins' exact copy.

Every numeric dataset carries HDF5's Fletcher-32 checksum; the coefficients are written
normalised and about each body's centre of gravity, as WEC-Sim's ``bodyClass`` takes
them; the group ``cummins`` holds the dataset in cummins' NetCDF layout.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from cummins._version import __version__
from cummins.errors import HydroDataError
from cummins.files import replacing
from cummins.hydrodb import (
    DOF_NAMES,
    bodies,
    change_axes,
    dof_matrix,
    single_speed,
    split_dof,
    validate,
)
from cummins.io.bemio.files import COPY_GROUP
from cummins.io.bemio.state_space import _state_space


def write_bemio(ds: xr.Dataset, path: str | os.PathLike[str], *, model=None) -> Path:
    """Write ``ds`` as a BEMIO ``.h5`` file in the MATLAB layout WEC-Sim reads.

    What is written, per body, is what WEC-Sim's ``readBEMIOH5.m`` and ``bodyClass``
    read (module docstring): normalised coefficients, A∞ (Ogilvie's estimate from A(ω),
    B(ω) when the data have none, said in the dataset's description), the radiation
    impulse response K(t) (cummins' exact integral of B(ω), on
    :func:`cummins.radiation.retardation.default_time_grid`), and with ``model`` its state space.
    Not written: the excitation impulse response (WEC-Sim needs it only for
    ``nonlinearHydro``/``yawNonLin``), QTFs, mean drift (its method — momentum or
    control surface — is not known here) and the generalized-mode matrices ``gbm``.
    The coefficients are written about each body's centre of gravity, as WEC-Sim takes
    them (:func:`cummins.move_reference_point`, when the data know it). The whole
    dataset, as given, also goes exactly into the ``cummins`` group.

    Parameters
    ----------
    ds
        A ``HydroDB`` at zero forward speed with excitation and hydrostatic stiffness
        (WEC-Sim needs both) and all six rigid-body DOFs of each body first. A z-down
        (MSS) dataset is converted to WEC-Sim's z-up axes first (said in ``history``).
    path
        Output file. Written to a temporary name first, then renamed.
    model
        A :class:`~cummins.radiation.model.RadiationModel` of the same DOFs: written to
        ``radiation_damping/state_space`` (A, B, C/ρ of each coupling, padded to the
        largest order; ``it`` the orders, ``r2t`` the R² of B when the fit recorded it,
        ``conv`` 1; D = 0; ``K`` the model's impulse response/ρ). A coupling without a
        model gets one stable state with C = 0 (A = −1, B = 1, ``conv`` 0), which adds
        nothing, so that WEC-Sim can assemble the matrices. WEC-Sim itself uses only the
        couplings within each body.

    Returns
    -------
    Path
        ``path``.
    """
    import h5py

    from cummins.hydrodb import add_history
    from cummins.io.netcdf.writer import _checksum_encoding, to_capytaine_layout

    path = Path(path)
    ds = single_speed(validate(ds))
    speed = float(ds.forward_speed) if "forward_speed" in ds.coords else 0.0
    if speed != 0.0:
        raise HydroDataError(
            f"the data are at forward speed {speed:g} m/s; BEMIO files hold zero-speed data",
            path=path,
        )
    if ds.attrs.get("axis_convention", "z-up") != "z-up":
        ds = change_axes(ds, "z-up")
        add_history(ds, "converted to z-up axes for WEC-Sim")
    missing = [v for v in ("excitation_force", "hydrostatic_stiffness") if v not in ds]
    if missing:
        raise HydroDataError(
            f"WEC-Sim needs {' and '.join(missing)}, which the data do not hold",
            path=path,
            hint="read the solver's excitation / hydrostatics files with the run, or "
            "give the stiffness (--stiffness / cummins.with_external_terms is not it: "
            "WEC-Sim wants the hydrostatic matrix)",
        )
    modes = _modes_per_body(ds, path)
    copy = ds
    ds = _about_centre_of_gravity(ds, len(modes))
    rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
    omega = ds.omega.values
    labels = [str(d) for d in ds.influenced_dof.values]
    added = dof_matrix(ds, "added_mass")
    damping = dof_matrix(ds, "radiation_damping")
    stiffness = dof_matrix(ds, "hydrostatic_stiffness")
    inf_note = "Infinite frequency added mass (normalized by rho)"
    if "added_mass_inf" in ds:
        inf = dof_matrix(ds, "added_mass_inf")
    else:
        from cummins.radiation.retardation import added_mass_inf

        inf = np.asarray(
            added_mass_inf(ds).transpose("influenced_dof", "radiating_dof").values, dtype=float
        )
        inf_note += "; estimated by cummins from A(w), B(w) (Ogilvie), not computed by the solver"
    forces = {
        "excitation": ds.excitation_force.transpose(
            "omega", "wave_direction", "influenced_dof"
        ).values
    }
    if "Froude_Krylov_force" in ds:
        forces["excitation/froude-krylov"] = ds.Froude_Krylov_force.transpose(
            "omega", "wave_direction", "influenced_dof"
        ).values
    if "diffraction_force" in ds:
        forces["excitation/scattering"] = ds.diffraction_force.transpose(
            "omega", "wave_direction", "influenced_dof"
        ).values
    from cummins.radiation.retardation import default_time_grid, retardation_function

    t = default_time_grid(ds)
    kernel = retardation_function(ds, t).transpose("time", "influenced_dof", "radiating_dof")
    kernel = np.asarray(kernel.values, dtype=float) / rho
    n_bodies = len(modes)
    names = _body_names(ds, n_bodies)
    cg = _per_body(ds, "center_of_gravity", n_bodies)
    cb = _per_body(ds, "center_of_buoyancy", n_bodies)
    volume = np.asarray(ds.attrs.get("displaced_volume", np.full(n_bodies, np.nan)), dtype=float)
    volume = (
        np.broadcast_to(volume.reshape(-1), (n_bodies,))
        if volume.size in (1, n_bodies)
        else np.full(n_bodies, np.nan)
    )
    ss = _state_space(model, labels, t, rho, path) if model is not None else None

    try:
        with replacing(path) as tmp:
            with h5py.File(tmp, "w") as f:
                text = _text_writer(f)
                number = _number_writer(f)
                text(
                    "bem_data/code",
                    str(ds.attrs.get("bem_code", ds.attrs.get("source_format", ""))),
                )
                text("cummins_version", __version__)
                depth = float(ds.attrs.get("water_depth", np.inf))
                if np.isinf(depth):
                    text("simulation_parameters/water_depth", "infinite")
                else:
                    number("simulation_parameters/water_depth", [[depth]], "Water depth", "m")
                number("simulation_parameters/scaled", [[0.0]], "", "")
                number("simulation_parameters/g", [[g]], "Gravitational acceleration", "m/s^2")
                number("simulation_parameters/rho", [[rho]], "Water density", "kg/m^3")
                number("simulation_parameters/T", (2 * np.pi / omega)[:, None], "Wave periods", "s")
                number("simulation_parameters/w", omega[:, None], "Wave frequencies", "rad/s")
                number(
                    "simulation_parameters/wave_dir",
                    np.degrees(ds.wave_direction.values)[:, None],
                    "Wave direction",
                    "deg",
                )
                start = 0
                for k, m in enumerate(modes):
                    rows = slice(start, start + m)
                    body = f"body{k + 1}"
                    text(f"{body}/properties/name", names[k])
                    number(
                        f"{body}/properties/body_number",
                        [[k + 1.0]],
                        "Number of rigid body from the BEM simulation",
                        "",
                    )
                    number(f"{body}/properties/cb", cb[k][:, None], "Center of buoyancy", "m")
                    number(f"{body}/properties/cg", cg[k][:, None], "Center of gravity", "m")
                    number(f"{body}/properties/disp_vol", [[volume[k]]], "Displaced volume", "m^3")
                    number(f"{body}/properties/dof", [[float(m)]], "Degrees of freedom", "")
                    number(
                        f"{body}/properties/dof_start", [[start + 1.0]], "Degrees of freedom", ""
                    )
                    number(
                        f"{body}/properties/dof_end", [[start + float(m)]], "Degrees of freedom", ""
                    )
                    hc = f"{body}/hydro_coeffs"
                    number(
                        f"{hc}/linear_restoring_stiffness",
                        stiffness[rows, rows] / (rho * g),
                        "Hydrostatic stiffness matrix (normalized by rho*g)",
                        "N/m",
                    )
                    number(f"{hc}/added_mass/inf_freq", inf[rows, :] / rho, inf_note, "kg")
                    number(
                        f"{hc}/added_mass/all",
                        np.transpose(added[:, rows, :], (1, 2, 0)) / rho,
                        "Added mass (normalized by rho)",
                        "kg",
                    )
                    number(
                        f"{hc}/radiation_damping/all",
                        np.transpose(damping[:, rows, :] / omega[:, None, None], (1, 2, 0)) / rho,
                        "Radiation damping (normalized by rho*w)",
                        "N-s/m",
                    )
                    for group, values in forces.items():
                        part = np.transpose(values[:, :, rows], (2, 1, 0)) / (rho * g)
                        what = {
                            "excitation": "excitation",
                            "excitation/froude-krylov": "Froude-Krylov",
                            "excitation/scattering": "scattering",
                        }[group]
                        for key, data, unit in (
                            ("re", part.real, "N"),
                            ("im", part.imag, "N"),
                            ("mag", np.abs(part), "N"),
                            ("phase", np.angle(part), "rad"),
                        ):
                            number(
                                f"{hc}/{group}/{key}",
                                data,
                                f"{key} of {what} force (normalized by rho*g)",
                                unit,
                            )
                    irf = f"{hc}/radiation_damping/impulse_response_fun"
                    number(
                        f"{irf}/K",
                        np.transpose(kernel[:, rows, :], (1, 2, 0)),
                        "Impulse response function (normalized by rho)",
                        "",
                    )
                    number(
                        f"{irf}/t", t[:, None], "Time vector for the impulse resonse function", "s"
                    )
                    number(
                        f"{irf}/w",
                        omega[:, None],
                        "Frequencies of the data the impulse response function integrates",
                        "rad/s",
                    )
                    if ss is not None:
                        sg = f"{hc}/radiation_damping/state_space"
                        for key in ("A", "B", "C", "K"):
                            number(
                                f"{sg}/{key}/all",
                                ss[key][rows],
                                f"State Space {key} Coefficient",
                                "",
                            )
                        number(f"{sg}/D/all", ss["D"][rows], "State Space D Coefficient", "")
                        number(f"{sg}/it", ss["it"][rows], "Order of state space realization", "")
                        number(
                            f"{sg}/r2t", ss["r2t"][rows], "State space curve fitting R**2 value", ""
                        )
                        number(f"{sg}/conv", ss["conv"][rows], "State space conversion status", "")
                    start += m
            layout = to_capytaine_layout(copy)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", category=FutureWarning)
                layout.to_netcdf(
                    tmp,
                    mode="a",
                    group=COPY_GROUP,
                    engine="h5netcdf",
                    encoding=_checksum_encoding(layout),
                )
    except OSError as exc:
        raise HydroDataError(f"cannot write the file ({exc})", path=path) from None
    return path


def _about_centre_of_gravity(ds: xr.Dataset, n_bodies: int) -> xr.Dataset:
    """The data about each body's centre of gravity, as WEC-Sim takes them (when it is
    known and not already the reference point)."""
    from cummins.hydrodb import move_reference_point

    cg = np.concatenate(_per_body(ds, "center_of_gravity", n_bodies))
    point = np.asarray(ds.attrs.get("reference_point", np.zeros(3)), dtype=float).reshape(-1)
    if not np.all(np.isfinite(cg)) or (point.size == cg.size and np.allclose(point, cg)):
        return ds
    return move_reference_point(ds, cg.reshape(n_bodies, 3) if n_bodies > 1 else cg)


def _text_writer(f):
    def write(name: str, value: str) -> None:
        data = (value or " ").encode("utf-8")
        f.create_dataset(name, data=np.bytes_(data))

    return write


def _number_writer(f):
    def write(name: str, values, description: str, units: str) -> None:
        data = np.asarray(values, dtype=float)
        dset = f.create_dataset(name, data=data, fletcher32=data.size > 0)
        dset.attrs["description"] = np.bytes_(description or " ")
        dset.attrs["units"] = np.bytes_(units or " ")

    return write


def _modes_per_body(ds: xr.Dataset, path: Path) -> list[int]:
    """Modes per body; each body's six rigid-body DOFs first, Surge … Yaw."""
    groups = bodies(ds)
    labels = [str(d) for d in ds.influenced_dof.values]
    modes = []
    position = 0
    for body in groups:
        members = [lab for lab in labels if split_dof(lab)[0] == body]
        names = [split_dof(lab)[1] for lab in members]
        if names[:6] != list(DOF_NAMES) or labels[position : position + len(members)] != members:
            raise HydroDataError(
                "WEC-Sim needs the six DOFs Surge … Yaw of each body first"
                + (f" (body {body})" if body else ""),
                path=path,
                hint="read the full 6-DOF data of every body",
            )
        modes.append(len(members))
        position += len(members)
    return modes


def _body_names(ds: xr.Dataset, n: int) -> list[str]:
    stored = [b for b in str(ds.attrs.get("body_names", "")).splitlines() if b]
    if len(stored) == n:
        return stored
    if n == 1 and ds.attrs.get("body_name"):
        return [str(ds.attrs["body_name"])]
    return [f"body{k + 1}" for k in range(n)]


def _per_body(ds: xr.Dataset, key: str, n: int) -> list[np.ndarray]:
    """A position attribute, 3 values per body (NaN when the data do not know it)."""
    value = np.asarray(ds.attrs.get(key, np.full(3 * n, np.nan)), dtype=float).reshape(-1)
    if value.size != 3 * n:
        value = np.full(3 * n, np.nan)
    return [value[3 * k : 3 * k + 3] for k in range(n)]
