""":func:`write_mss`: any ``HydroDB`` as an MSS ``vessel`` struct (MATLAB v5 ``.mat``).

About the dataset's reference point, in Fossen's axes, recorded in
``vessel.cummins.reference_point`` (read back first by :func:`cummins.io.mss.read_mss`)
besides ``hydrodynamic_reference`` (``'CO'``/``'CG'``).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import HydroDataError, HydroDataWarning
from cummins.files import replacing
from cummins.hydrodb import DOF_NAMES, add_history, change_axes
from cummins.io.mss.matfile import DRIFT_DOFS, MSS_INFINITE_FREQUENCY
from cummins.io.mss.points import _rigid_body_cg


def _speed_slices(ds: xr.Dataset) -> tuple[list[xr.Dataset], NDArray]:
    if "forward_speed" in ds.dims:
        speeds = np.asarray(ds.forward_speed.values, dtype=float)
        return [ds.isel(forward_speed=k) for k in range(speeds.size)], speeds
    speed = float(ds.forward_speed) if "forward_speed" in ds.coords else 0.0
    return [ds], np.array([speed])


def _with_motion_rao(ds: xr.Dataset, path: Path) -> xr.Dataset:
    """The data with motion RAOs for ``vessel.motionRAO``: the solver's, else cummins'.

    MSS's ``wamit2vessel`` fills ``motionRAO`` from WAMIT's ``.4`` and its VERES readers
    from ``.re1``; data without them (WAMIT's ``.1 .3 .hst .frc``) get the RAOs of the
    coupled equation of motion, [−ω²(M + A) + iω(B + B_add) + C + C_add] X = F
    (:func:`cummins.seakeeping.frequency_domain.motion_rao`, de Haan (2022) eqs. 2.3–2.4),
    as WAMIT computes its ``.4``; a warning says so, or why none are written."""
    if "rao" in ds or "excitation_force" not in ds or "wave_direction" not in ds.dims:
        return ds
    missing = [v for v in ("inertia_matrix", "hydrostatic_stiffness") if v not in ds]
    if "forward_speed" in ds.dims and ds.sizes["forward_speed"] > 1:
        missing.append("one forward speed (the data hold several)")
    if missing:
        warnings.warn(
            f"{path.name}: vessel.motionRAO not written: the data hold no motion RAOs, and "
            f"lack {', '.join(missing)} to compute them (give the inertia: --mass, "
            "--center-of-gravity, --radii-of-gyration)",
            HydroDataWarning,
            stacklevel=3,
        )
        return ds
    from cummins.errors import AssumptionWarning
    from cummins.io.mss.reader import RAO_BY_CUMMINS
    from cummins.seakeeping.frequency_domain import motion_rao

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            rao = motion_rao(ds)
    except (HydroDataError, ValueError, np.linalg.LinAlgError) as exc:
        warnings.warn(
            f"{path.name}: vessel.motionRAO not written: the data hold no motion RAOs and "
            f"cummins' could not be computed ({exc})",
            HydroDataWarning,
            stacklevel=3,
        )
        return ds
    out = ds.copy()
    out["rao"] = rao.rename(dof="radiating_dof").transpose(
        "omega", "wave_direction", "radiating_dof"
    )
    out["rao"].attrs = {"description": RAO_BY_CUMMINS}
    add_history(out, "motion RAOs computed by cummins.seakeeping.frequency_domain.motion_rao")
    warnings.warn(
        f"{path.name}: vessel.motionRAO computed by cummins (the data hold no solver RAOs): "
        "the coupled equation of motion with the data's inertia, restoring and additional "
        "damping (no viscous roll damping), as WAMIT's .4",
        AssumptionWarning,
        stacklevel=3,
    )
    return out


def _matrix_stack(datasets: Sequence[xr.Dataset], name: str, with_limits: bool) -> NDArray:
    """6×6×N×S array of a (omega, i, j) variable, with the ω = 0 / ∞ entries if asked."""
    out = []
    for d in datasets:
        v = d[name].transpose("omega", "influenced_dof", "radiating_dof").values
        if with_limits:
            if name == "added_mass":
                first, last = d["added_mass_zero"].values, d["added_mass_inf"].values
            elif name == "radiation_damping":
                first = last = np.zeros((6, 6))
            else:  # hold the edge values (viscous damping estimates)
                first, last = v[0], v[-1]
            v = np.concatenate([first[None], v, last[None]])
        out.append(np.moveaxis(v, 0, 2))
    return np.stack(out, axis=3)


def _rao_struct(datasets: Sequence[xr.Dataset], name: str, omega: NDArray) -> dict:
    values = np.stack(
        [d[name].transpose("omega", "wave_direction", ...).values for d in datasets], axis=3
    )  # (nω, nβ, 6, nspeed)
    amp = np.empty((1, 6), dtype=object)
    phase = np.empty((1, 6), dtype=object)
    for k in range(6):
        amp[0, k] = np.abs(values[:, :, k, :])
        phase[0, k] = np.angle(values[:, :, k, :])
    return {"w": omega[None, :], "amp": amp, "phase": phase}


def _drift_struct(datasets: Sequence[xr.Dataset], omega: NDArray) -> dict:
    values = np.stack(
        [d["drift_force"].transpose("omega", "wave_direction", ...).values for d in datasets],
        axis=3,
    )
    amp = np.empty((1, 3), dtype=object)
    for k, dof in enumerate(DRIFT_DOFS):
        amp[0, k] = values[:, :, dof, :]
    return {"w": omega[None, :], "amp": amp}


def _radii_of_gyration(mrb: NDArray, r_g: NDArray) -> tuple[float, float, float]:
    """k44, k55, k66 (m): radii of gyration about axes through CG, as MSS's ``rbody``
    takes them (M_RB = H(r_g)ᵀ diag(m, m, m, m k44², m k55², m k66²) H(r_g), Fossen
    (2011) §3.3); the parallel-axis theorem takes m(|r_g|² − r_g,i²) off MRB's diagonal."""
    m = float(mrb[0, 0])
    offset = float(r_g @ r_g) - r_g**2
    return tuple(  # type: ignore[return-value]
        float(np.sqrt(max(mrb[3 + i, 3 + i] / m - offset[i], 0.0))) for i in range(3)
    )


def _main_struct(ds: xr.Dataset, mrb: NDArray | None, point: NDArray, name: str) -> dict:
    """``vessel.main``; ``CG`` and ``CB`` as FSD vectors from CO (current MSS convention)."""
    main: dict[str, Any] = {"name": name, "rho": float(ds.attrs["rho"]), "g": float(ds.attrs["g"])}
    r_g = _rigid_body_cg(mrb) if mrb is not None else None
    if r_g is not None:
        m = float(mrb[0, 0])
        main["m"] = m
        main["nabla"] = float(ds.attrs.get("displaced_volume", m / ds.attrs["rho"]))
        main["k44"], main["k55"], main["k66"] = _radii_of_gyration(mrb, r_g)
    if "center_of_gravity" in ds.attrs:
        main["CG"] = np.asarray(ds.attrs["center_of_gravity"], dtype=float).reshape(1, 3)
    elif r_g is not None:
        main["CG"] = (point + r_g)[None, :]
    if "center_of_buoyancy" in ds.attrs:
        main["CB"] = np.asarray(ds.attrs["center_of_buoyancy"], dtype=float).reshape(1, 3)
    for key, attr in (("Lpp", "ship_length"), ("B", "ship_breadth"), ("T", "ship_draught")):
        if attr in ds.attrs:
            main[key] = float(ds.attrs[attr])
    main.update(_stability_fields(ds, main))
    return main


#: The ``main`` fields MSS's functions read (vessel2ss: CG, T; vessel2simscape: CG, CB,
#: T; the natural periods and viscous_skin: GM_T, GM_L, C_B, Lwl, S, m, nabla, k44 …).
MAIN_FIELDS = ("m", "nabla", "Lpp", "B", "T", "CG", "CB", "GM_T", "GM_L", "C_B", "Lwl", "S")


def _stability_fields(ds: xr.Dataset, main: dict) -> dict[str, float]:
    """GM_T, GM_L from the restoring (as MSS builds G from them: G44 = ρg∇GM_T,
    G55 = ρg∇GM_L + G33 x_F², x_F = −G35/G33; Fossen (2021) ch. 4), C_B = ∇/(Lpp B T),
    and MSS's own approximations Lwl = Lpp and S = B (Lpp + 2T) (``veres2vessel``)."""
    out: dict[str, float] = {}
    nabla = main.get("nabla")
    if nabla and "hydrostatic_stiffness" in ds:
        c = ds["hydrostatic_stiffness"].transpose(..., "influenced_dof", "radiating_dof")
        c = np.asarray(c.values, dtype=float).reshape(-1, 6, 6)[0]
        weight = float(main["rho"]) * float(main["g"]) * float(nabla)
        if c[3, 3] > 0:
            out["GM_T"] = float(c[3, 3] / weight)
        if c[4, 4] > 0 and c[2, 2] > 0:
            out["GM_L"] = float((c[4, 4] - c[2, 4] * c[4, 2] / c[2, 2]) / weight)
    if nabla and all(k in main for k in ("Lpp", "B", "T")):
        out["C_B"] = float(nabla / (main["Lpp"] * main["B"] * main["T"]))
    if "Lpp" in main:
        out["Lwl"] = float(main["Lpp"])
        if "B" in main and "T" in main:
            out["S"] = float(main["B"] * (main["Lpp"] + 2 * main["T"]))
    return out


def _complete_headings(ds: xr.Dataset, path: Path) -> xr.Dataset:
    """Headings over the full circle, as MSS's ``waveForceRAO`` needs (it wraps β into
    [0, 2π) and extrapolates outside the table): one half-plane mirrored for a
    port/starboard symmetric hull (:func:`cummins.seakeeping.headings.mirror_headings`,
    the reader's rule), else a warning naming the arc without data."""
    from cummins.seakeeping.headings import mirror_headings

    try:
        out, coverage = mirror_headings(ds)
    except HydroDataError:  # several speeds or bodies the symmetry cannot be judged on
        return ds
    if coverage.mirror_used:
        added = int(coverage.mirrored.sum())
        add_history(out, f"write_mss: {added} headings added by port/starboard symmetry")
    gaps = coverage.gaps(np.pi / 4)
    if gaps:
        a, b = gaps[0]
        warnings.warn(
            f"{path.name}: no wave heading between {np.degrees(a):.4g}° and "
            f"{np.degrees(b):.4g}° ({coverage.reason}): MSS's waveForceRAO extrapolates "
            "there; give data for all headings",
            HydroDataWarning,
            stacklevel=3,
        )
    return out


def write_mss(ds: xr.Dataset, path: str | os.PathLike[str]) -> Path:
    """Write a ``HydroDB`` as an MSS ``vessel`` struct (MATLAB v5 ``.mat``).

    The data are converted to Fossen's axes (``change_axes(ds, "z-down")``) and written
    about the dataset's reference point. MSS takes the matrices about CO (for ships:
    Lpp/2, centre line, waterline, the origin of cummins' positions): move the data
    there first (``move_reference_point(ds, [0, 0, 0])``, ``cummins convert
    --reference-point 0 0 0``) for use in MSS. ``hydrodynamic_reference`` is written as
    ``'CO'`` or ``'CG'`` when the point is one of these, and the point itself in
    ``vessel.cummins.reference_point``. With both ``added_mass_zero`` and ``added_mass_inf`` and all
    frequencies below 10 rad/s, ``freqs`` is written as MSS's WAMIT layout
    ``[0, ω…, 10]`` with A(0), A(∞) and zero damping at the ends; otherwise ``freqs``
    holds the finite grid only (the VERES layout) and the limits go to
    ``vessel.cummins``. Also written: ``MRB`` (zeros if unknown), ``C`` repeated per
    frequency, ``Bv`` (``additional_damping``, else zeros), ``headings`` (rad, as in the
    data, not completed by symmetry), ``velocities``, ``forceRAO``, ``motionRAO`` (the
    solver's, else cummins', :func:`_with_motion_rao`) and ``driftfrc`` (surge, sway and yaw
    only: heave, roll and pitch drift are lost) when present, ``main`` (``name``, ``rho``,
    ``g``, ``m``, ``nabla``, ``CG`` and ``CB`` as FSD vectors from CO, ``k44`` … (about CG),
    ``Lpp``, ``B``, ``T``, ``GM_T``, ``GM_L``, ``C_B``, ``Lwl``, ``S`` when known:
    :func:`_stability_fields`; a warning names those the data do not give, and data about a
    point other than CO or CG) and ``hydrodynamic_axes = 'FSD'``, as current MSS does.
    ``vessel.cummins`` keeps the history, the reference point and what MSS has no field
    for; MSS ignores it.

    Parameters
    ----------
    ds
        A single-body ``HydroDB`` with all six DOFs.
    path
        Output ``.mat`` file (overwritten).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    labels = [str(d) for d in ds.influenced_dof.values]
    if labels != list(DOF_NAMES):
        raise HydroDataError(
            "an MSS vessel struct holds one body with six DOFs (Surge … Yaw)",
            path=path,
            hint="select one body's six DOFs first",
        )
    computed = "rao" not in ds
    ds = _with_motion_rao(ds, path)
    computed = computed and "rao" in ds
    if "wave_direction" in ds.dims:
        ds = ds.assign_coords(wave_direction=np.mod(ds.wave_direction.values, 2 * np.pi))
    out = change_axes(ds, "z-down")
    if "wave_direction" in out.dims:  # MSS's headings, in its axes
        out = _complete_headings(out, path)
    point = np.asarray(out.attrs.get("reference_point", np.zeros(3)), dtype=float).reshape(-1)
    if point.size != 3:
        raise HydroDataError("expected one reference point (3 coordinates)", path=path)
    datasets, speeds = _speed_slices(out)
    omega = np.asarray(out.omega.values, dtype=float)
    with_limits = (
        "added_mass_zero" in out and "added_mass_inf" in out and omega[-1] < MSS_INFINITE_FREQUENCY
    )
    freqs = np.concatenate([[0.0], omega, [MSS_INFINITE_FREQUENCY]]) if with_limits else omega
    nf = freqs.size
    first = datasets[0]
    mrb = first["inertia_matrix"].values if "inertia_matrix" in first else None
    main = _main_struct(out, mrb, point, str(out.attrs.get("body_name") or path.stem))
    vessel: dict[str, Any] = {
        "main": main,
        "velocities": speeds[None, :],
        "freqs": freqs[None, :],
        "A": _matrix_stack(datasets, "added_mass", with_limits),
        "B": _matrix_stack(datasets, "radiation_damping", with_limits),
        "MRB": mrb if mrb is not None else np.zeros((6, 6)),
        "hydrodynamic_axes": "FSD",
    }
    if not np.any(point):
        vessel["hydrodynamic_reference"] = "CO"
    elif "CG" in main and np.allclose(main["CG"].ravel(), point, atol=1e-9):
        vessel["hydrodynamic_reference"] = "CG"
    else:
        warnings.warn(
            f"{path.name}: the data are about {(np.round(point, 4) + 0.0).tolist()} m, neither CO "
            "nor CG: MSS's functions take them about CO (Lpp/2, centre line, waterline), "
            "as its own supply.mat; move them first (cummins convert --reference-point "
            "0 0 0, cummins.move_reference_point(ds, [0, 0, 0]))",
            HydroDataWarning,
            stacklevel=2,
        )
    lacking = [key for key in MAIN_FIELDS if key not in main]
    if lacking:
        warnings.warn(
            f"{path.name}: vessel.main lacks {', '.join(lacking)} (not in the data)"
            + (
                "; --main-dimensions LPP B T (the attributes ship_length, ship_breadth, "
                "ship_draught) gives Lpp, B, T, and C_B, Lwl, S follow"
                if {"Lpp", "B", "T"} & set(lacking)
                else ""
            ),
            HydroDataWarning,
            stacklevel=2,
        )
    c = np.stack(
        [
            np.repeat(
                (
                    d["hydrostatic_stiffness"].values
                    if "hydrostatic_stiffness" in d
                    else np.zeros((6, 6))
                )[:, :, None],
                nf,
                axis=2,
            )
            for d in datasets
        ],
        axis=3,
    )
    vessel["C"] = c
    if "additional_damping" in first:
        vessel["Bv"] = _matrix_stack(datasets, "additional_damping", with_limits)
    else:
        vessel["Bv"] = np.zeros((6, 6, nf, speeds.size))
    if speeds.size == 1:
        for key in ("A", "B", "C", "Bv"):
            vessel[key] = vessel[key][:, :, :, 0]
    elif np.array_equal(vessel["Bv"], np.repeat(vessel["Bv"][..., :1], speeds.size, axis=3)):
        # one viscous estimate for every speed: 6×6×Nfreq, as MSS's own s175.mat
        vessel["Bv"] = vessel["Bv"][:, :, :, 0]
    if "wave_direction" in out.dims:
        vessel["headings"] = np.asarray(out.wave_direction.values, dtype=float)[None, :]
        if "excitation_force" in out:
            vessel["forceRAO"] = _rao_struct(datasets, "excitation_force", omega)
        if "rao" in out:
            vessel["motionRAO"] = _rao_struct(datasets, "rao", omega)
        if "drift_force" in out:
            vessel["driftfrc"] = _drift_struct(datasets, omega)
    extras: dict[str, Any] = {
        "history": str(out.attrs.get("history", "")),
        "source_format": str(out.attrs.get("source_format", "")),
        "source_file": str(out.attrs.get("source_file", "")),
        "water_depth": float(out.attrs.get("water_depth", np.inf)),
        "reference_point": point[None, :],
    }
    if computed:
        extras["rao_source"] = "cummins motion_rao"
    if not with_limits:
        for name in ("added_mass_inf", "added_mass_zero"):
            if name in first:
                extras[name] = first[name].values
    if "additional_stiffness" in first:
        extras["additional_stiffness"] = first["additional_stiffness"].values
    for key in ("restoring_source", "restoring_weight_mass", "restoring_weight_center"):
        if key in out.attrs:  # what C holds (cummins.restoring): MSS's G need not
            extras[key] = out.attrs[key]
    vessel["cummins"] = extras
    try:
        import scipy.io  # here: reading files of other formats need not load it

        with replacing(path) as tmp:
            scipy.io.savemat(str(tmp), {"vessel": vessel}, do_compression=True, oned_as="row")
    except OSError as exc:
        raise HydroDataError(f"cannot write the file ({exc.strerror or exc})", path=path) from None
    return path
