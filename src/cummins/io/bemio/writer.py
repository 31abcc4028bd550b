"""Writing a BEMIO ``.h5`` file in the MATLAB layout WEC-Sim reads, with cummins' exact copy.

Every numeric dataset carries HDF5's Fletcher-32 checksum; the coefficients are written
normalised and about each body's centre of gravity, as WEC-Sim's ``bodyClass`` takes
them, one group per function of :mod:`cummins.io.bemio.groups`; the group ``cummins``
holds the dataset in cummins' NetCDF layout.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import CumminsWarning, HydroDataError
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
from cummins.io.bemio.groups import (
    BODY_GROUPS,
    BemioData,
    BodyRows,
    H5Out,
    write_simulation_parameters,
)
from cummins.io.bemio.state_space import _state_space


def write_bemio(
    ds: xr.Dataset,
    path: str | os.PathLike[str],
    *,
    model=None,
    excitation_irf: bool = True,
) -> Path:
    """Write ``ds`` as a BEMIO ``.h5`` file in the MATLAB layout WEC-Sim reads.

    What is written, per body, is what WEC-Sim's ``readBEMIOH5.m`` and ``bodyClass``
    read (:mod:`cummins.io.bemio.groups`, one function per group; the list is in
    ``docs/openfast_wecsim.md``): normalised coefficients, A∞ (Ogilvie's estimate from
    A(ω), B(ω) when the data have none, said in the dataset's description), the
    displaced volume (``properties/disp_vol``, which WEC-Sim's "equilibrium" mass is
    ρ times) **where the data know it** — elsewhere the dataset is left out and a
    warning says so (WEC-Sim's reader then stops at it rather than taking NaN) —, the
    Froude–Krylov and scattering forces where the data hold them, the radiation impulse
    response K(t) (cummins' exact integral of B(ω), on
    :func:`cummins.radiation.retardation.default_time_grid`), the excitation impulse
    response K_ex(t) (:func:`cummins.excitation_model.excitation_irf`, on its symmetric
    default grid), the ``components`` copies of the older MATLAB writer, and with
    ``model`` its state space. Not written: QTFs, mean drift (its method — momentum or
    control surface — is not known here) and the generalized-mode matrices ``gbm``. The
    coefficients are written about each body's centre of gravity, as WEC-Sim takes them
    (:func:`cummins.move_reference_point`, when the data know it), and so is the model's
    state space (:func:`cummins.radiation.moved_model.moved_model`: K' = Hᵀ K H, exactly).
    The whole dataset, as given, also goes exactly into the ``cummins`` group.

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
    excitation_irf
        Write ``excitation/impulse_response_fun`` (default).

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
            hint="read with the run "
            + "; ".join(
                {
                    "excitation_force": "the excitation file beside it (WAMIT .3 or its "
                    ".out, NEMOH ExcitationForce.tec, VERES .re8)",
                    "hydrostatic_stiffness": "the hydrostatics (WAMIT .hst or its .out, "
                    "NEMOH KH.dat): WEC-Sim wants the hydrostatic matrix, an external "
                    "stiffness is not it",
                }[v]
                for v in missing
            ),
        )
    modes = _modes_per_body(ds, path)
    copy = ds
    about_cg = _about_centre_of_gravity(ds, len(modes))
    if model is not None and about_cg is not ds:
        # the state space about the same point as the coefficients, exactly
        from cummins.radiation.moved_model import moved_model

        model = moved_model(model, ds, about_cg.attrs["reference_point"])
    data = bemio_data(about_cg, modes, model, path, excitation_irf)
    for k, volume in enumerate(data.volume):
        if not np.isfinite(volume):
            warnings.warn(
                CumminsWarning(
                    f"{path}: the displaced volume of body {k + 1} is not in the data: "
                    f"body{k + 1}/properties/disp_vol is left out, and WEC-Sim's readBEMIOH5 "
                    "stops there; give it (cummins convert --displaced-volume M3, or the "
                    "solver's .out with the run)"
                ),
                stacklevel=2,
            )
    try:
        with replacing(path) as tmp:
            with h5py.File(tmp, "w") as f:
                out = H5Out(f)
                code = str(ds.attrs.get("bem_code", ds.attrs.get("source_format", "")))
                depth = float(ds.attrs.get("water_depth", np.inf))
                write_simulation_parameters(out, data, depth, code)
                start = 0
                for k, m in enumerate(modes):
                    body = BodyRows(k + 1, start, m)
                    for group in BODY_GROUPS:
                        group(out, data, body)
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


#: At most this many times of the excitation impulse response written (BEMIO's
#: ``excitationIRF`` writes 1001 by default); the values at them are exact whatever the step.
IRF_POINTS = 2001


def bemio_data(
    ds: xr.Dataset, modes: list[int], model, path: Path, excitation_irf: bool = True
) -> BemioData:
    """The :class:`~cummins.io.bemio.groups.BemioData` of ``ds`` (z-up, about each
    body's centre of gravity): matrices, forces, impulse responses, state space."""
    from cummins.radiation.retardation import (
        added_mass_inf,
        default_time_grid,
        retardation_function,
    )

    n_bodies = len(modes)
    labels = [str(d) for d in ds.influenced_dof.values]
    inf_note = "Infinite frequency added mass (normalized by rho)"
    if "added_mass_inf" in ds:
        inf = dof_matrix(ds, "added_mass_inf")
    else:
        inf = np.asarray(
            added_mass_inf(ds).transpose("influenced_dof", "radiating_dof").values, dtype=float
        )
        inf_note += "; estimated by cummins from A(w), B(w) (Ogilvie), not computed by the solver"
    forces = {}
    for group, name in (
        ("excitation", "excitation_force"),
        ("excitation/froude-krylov", "Froude_Krylov_force"),
        ("excitation/scattering", "diffraction_force"),
    ):
        if name in ds:
            forces[group] = ds[name].transpose("omega", "wave_direction", "influenced_dof").values
    t = default_time_grid(ds)
    kernel = retardation_function(ds, t).transpose("time", "influenced_dof", "radiating_dof")
    exc = None
    if excitation_irf:
        from cummins.excitation_model import excitation_irf as irf

        k_ex = irf(ds, max_points=IRF_POINTS).transpose("time", "wave_direction", "influenced_dof")
        exc = (k_ex.time.values, np.asarray(k_ex.values, dtype=float))
    rho = float(ds.attrs["rho"])
    return BemioData(
        rho=rho,
        g=float(ds.attrs["g"]),
        omega=ds.omega.values,
        directions=ds.wave_direction.values,
        names=_body_names(ds, n_bodies),
        cg=_per_body(ds, "center_of_gravity", n_bodies),
        cb=_per_body(ds, "center_of_buoyancy", n_bodies),
        volume=_volumes(ds, n_bodies),
        added=dof_matrix(ds, "added_mass"),
        damping=dof_matrix(ds, "radiation_damping"),
        stiffness=dof_matrix(ds, "hydrostatic_stiffness"),
        added_inf=inf,
        added_inf_note=inf_note,
        forces=forces,
        radiation_irf=(t, np.asarray(kernel.values, dtype=float)),
        excitation_irf=exc,
        state_space=_state_space(model, labels, t, rho, path) if model is not None else None,
        ds=ds,
    )


def _volumes(ds: xr.Dataset, n_bodies: int) -> np.ndarray:
    """The displaced volume of each body, m³, NaN where the data do not know it."""
    from cummins.restoring import body_volumes

    volume = body_volumes(ds, n_bodies)
    return np.where(volume > 0, volume, np.nan)


def _about_centre_of_gravity(ds: xr.Dataset, n_bodies: int) -> xr.Dataset:
    """The data about each body's centre of gravity, as WEC-Sim takes them (when it is
    known and not already the reference point)."""
    from cummins.hydrodb import move_reference_point

    cg = np.concatenate(_per_body(ds, "center_of_gravity", n_bodies))
    point = np.asarray(ds.attrs.get("reference_point", np.zeros(3)), dtype=float).reshape(-1)
    if not np.all(np.isfinite(cg)) or (point.size == cg.size and np.allclose(point, cg)):
        return ds
    return move_reference_point(ds, cg.reshape(n_bodies, 3) if n_bodies > 1 else cg)


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
