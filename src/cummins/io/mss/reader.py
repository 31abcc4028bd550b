""":func:`read_mss`: an MSS ``vessel`` struct (``.mat``) into a canonical ``HydroDB``.

The struct's matrices, frequency grid and wave tables (:mod:`cummins.io.mss.grid`), its
reference point (:mod:`cummins.io.mss.points`) and what :func:`cummins.io.mss.write_mss`
kept in ``vessel.cummins``, per forward speed; the conventions are those of
:mod:`cummins.io.mss`.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import HydroDataError
from cummins.hydrodb import (
    DOF_NAMES,
    add_history,
    make_hydrodb,
    move_reference_point,
    stack_forward_speeds,
)
from cummins.io._common import resolve_rho_g
from cummins.io.mss.grid import _as_4d, _frequency_grid, _wave_table, _WaveTable
from cummins.io.mss.matfile import (
    _field,
    _has,
    _numeric,
    _scalar,
    _substruct,
    _text,
    load_mat_struct,
)
from cummins.io.mss.points import _points, _rigid_body_cg
from cummins.io.mss.rao import _holds_rao_struct, read_force_rao
from cummins.restoring import weight_record


def _select_speed(velocities: NDArray, speed: float | None, path: Path) -> list[int]:
    if speed is None:
        return list(range(velocities.size))
    hit = np.flatnonzero(np.isclose(velocities, speed, rtol=1e-4, atol=1e-3))
    if hit.size == 0:
        listing = ", ".join(f"{v:g}" for v in velocities)
        raise HydroDataError(
            f"no data at forward speed {speed:g} m/s",
            path=path,
            hint=f"vessel.velocities holds {listing} m/s",
        )
    return [int(hit[0])]


def _move_waves(ds: xr.Dataset, point: NDArray, target: NDArray) -> xr.Dataset:
    """Move only the wave quantities from ``point`` to ``target`` (same axes)."""
    names = [n for n in ("excitation_force", "rao", "drift_force") if n in ds]
    if not names or np.allclose(point, target):
        return ds
    part = ds[names].assign_attrs(reference_point=np.asarray(point, dtype=float))
    moved = move_reference_point(part, target)
    out = ds.copy()
    for n in names:
        out[n] = moved[n]
    return out


def read_mss(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    speed: float | None = None,
    rao_reference: ArrayLike | None = None,
    drift_as_stored: bool = False,
) -> xr.Dataset:
    """Read an MSS ``vessel`` struct (``.mat``) into a canonical ``HydroDB``.

    Parameters
    ----------
    path
        The ``.mat`` file (MATLAB v5/v7, as MSS saves it).
    rho, g
        Water density (kg/m³) and gravity (m/s²). The data are dimensional: a value
        differing from ``vessel.main.rho`` / ``main.g`` is an error; used only when the
        struct does not record them (default 1025 and 9.81).
    speed
        Forward speed (m/s) to select from ``vessel.velocities``; by default all speeds
        are read, along a ``forward_speed`` dimension when there are several.
    rao_reference
        Point (m, z-down, from CO) about which ``forceRAO``, ``motionRAO`` and
        ``driftfrc`` are given, when it differs from the matrices' reference point;
        detected for VERES-derived structs (see :mod:`cummins.io.mss`).
    drift_as_stored
        Keep ``driftfrc`` at 190–350° as the struct stores it. By default, where it breaks
        the port/starboard mirror that the struct's first-order tables keep (MSS's
        processing: :func:`mirrored_mss_drift`), those headings take the mirror image of
        10–170°, and ``history`` says so.

    Returns
    -------
    xarray.Dataset
        ``HydroDB`` with ``axis_convention="z-down"``.

    Raises
    ------
    HydroDataError
        Not an MSS file, or damaged or inconsistent content (naming the field).
    """
    path = Path(path)
    try:
        ds = _read_mss(path, rho, g, speed, rao_reference)
    except HydroDataError:
        raise
    except (KeyError, IndexError, ValueError, TypeError, AttributeError) as exc:
        raise HydroDataError(
            f"unexpected content in the vessel struct ({type(exc).__name__}: {exc})",
            path=path,
            hint="the file may be damaged or not written by MSS",
        ) from None
    return ds if drift_as_stored else mirrored_mss_drift(ds)


def mirrored_mss_drift(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with ``drift_force`` at the headings in (180°, 360°) replaced by the mirror
    image T F(360° − β) of (0°, 180°), T = diag(1, −1, 1, −1, 1, −1), when the drift breaks
    the port/starboard mirror there in one of MSS's patterns although the first-order
    tables keep it (:func:`cummins.check.waves.mss_drift_fill`); else ``ds`` itself.

    MSS fills ``driftfrc`` at 190–350° from 10–170° in processing (``wamit2vessel.m``
    copies them in the same order, ``read_veres_WD.m`` mirrors the yaw moment without its
    sign change: :mod:`cummins.check.parity`), while 0–180° are the solver's (MSS's
    ``tanker.mat`` equals its ``tanker.9``, ``supply.mat`` its VERES ``.re2``): the
    tanker's surge drift at 190° pushed the ship forward in nearly head seas, the S-175's
    yaw drift moment at 225° had the wrong sign.
    """
    from cummins.check.parity import degree_ranges
    from cummins.check.waves import MSS_FILL, mss_drift_fill
    from cummins.seakeeping.headings import mirror_headings

    found = mss_drift_fill(ds)
    if not found:
        return ds
    beta = np.mod(ds.wave_direction.values, 2 * np.pi)
    solver = np.flatnonzero(beta <= np.pi + 1e-9)  # the half-plane the solver computed
    mirrored, _ = mirror_headings(ds.isel(wave_direction=solver), mirror=True)
    target = np.flatnonzero(beta > np.pi + 1e-9)
    out = ds.copy()
    out["drift_force"] = ds.drift_force.copy()
    out["drift_force"][{"wave_direction": target}] = (
        mirrored.drift_force.sel(wave_direction=beta[target], method="nearest")
        .transpose(*ds.drift_force.dims)
        .values
    )
    dofs = ", ".join(dict.fromkeys(str(f.where) for f in found))
    fills = "; ".join(dict.fromkeys(MSS_FILL[f.details["pattern"]] for f in found))
    headings = sorted({h for f in found for h in f.details["headings_deg"]})
    add_history(
        out,
        f"drift_force at {degree_ranges(np.degrees(beta[target]).tolist())}: the mirror image "
        f"of the solver's 0–180° (the struct's {dofs} at {degree_ranges(headings)} broke "
        f"the port/starboard mirror its first-order tables keep: {fills}); "
        "read(..., drift_as_stored=True) keeps the struct's values",
    )
    return out


def _read_mss(path, rho, g, speed, rao_reference) -> xr.Dataset:
    if _holds_rao_struct(path):
        rao = read_force_rao(path)
        raise HydroDataError(
            "an MSS RAO struct: it holds force RAOs only ("
            f"{rao.sizes['influenced_dof']} DOFs, {rao.sizes['omega']} frequencies, "
            f"{rao.sizes['wave_direction']} headings, {rao.sizes['forward_speed']} speeds), "
            "no added mass, damping or restoring",
            path=path,
            hint="cummins.io.mss.read_force_rao(path) returns them as an excitation_force "
            "array; for a HydroDB, read the solver run they were processed from",
        )
    vessel = load_mat_struct(
        path,
        "vessel",
        "MSS vessel files hold a struct named vessel; *ABC.mat files hold "
        "fitted models (vesselABC), not hydrodynamic data",
    )
    main = _substruct(vessel, "main")
    extras = _substruct(vessel, "cummins")
    history: list[str] = [f"read MSS vessel struct from {path.name}"]
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        _scalar(main, "rho", path, "vessel.main"),
        _scalar(main, "g", path, "vessel.main"),
        path=path,
        history=history,
        dimensional=True,
    )

    freqs = _numeric(_field(vessel, "freqs", path), path, "vessel.freqs").reshape(-1)
    velocities = (
        np.atleast_1d(_numeric(vessel["velocities"], path, "vessel.velocities").reshape(-1))
        if _has(vessel, "velocities")
        else np.zeros(1)
    )
    if velocities.size == 0:
        velocities = np.zeros(1)
    if not np.all(np.isfinite(velocities)):
        raise HydroDataError(
            "non-finite forward speed (NaN or Inf)",
            path=path,
            quantity="vessel.velocities",
            hint="the file is damaged",
        )
    nspeed = velocities.size
    a_all = _as_4d(
        _numeric(_field(vessel, "A", path), path, "vessel.A"), freqs.size, nspeed, path, "A"
    )
    b_all = _as_4d(
        _numeric(_field(vessel, "B", path), path, "vessel.B"), freqs.size, nspeed, path, "B"
    )
    grid = _frequency_grid(freqs, b_all, path, history)
    omega = grid.omega
    c_all = (
        _as_4d(_numeric(vessel["C"], path, "vessel.C"), freqs.size, nspeed, path, "C")
        if _has(vessel, "C")
        else None
    )
    bv_all = (
        _as_4d(_numeric(vessel["Bv"], path, "vessel.Bv"), freqs.size, nspeed, path, "Bv")
        if _has(vessel, "Bv")
        else None
    )
    mrb = None
    if _has(vessel, "MRB"):
        mrb = _numeric(vessel["MRB"], path, "vessel.MRB")
        if mrb.shape != (6, 6):
            raise HydroDataError(
                f"has shape {mrb.shape}, expected (6, 6)", path=path, quantity="vessel.MRB"
            )
        if not np.any(mrb):
            mrb = None

    headings = (
        _numeric(vessel["headings"], path, "vessel.headings").reshape(-1)
        if _has(vessel, "headings")
        else np.empty(0)
    )
    waves: dict[str, _WaveTable] = {}
    for name in ("forceRAO", "motionRAO", "driftfrc"):
        if headings.size == 0:
            break
        table = _wave_table(vessel, name, omega, headings.size, nspeed, path, history)
        if table is not None:
            waves[name] = table

    points = _points(vessel, main, mrb, path, history)
    legacy_veres = _substruct(vessel, "roll") is not None and not _has(
        vessel, "hydrodynamic_reference"
    )
    wave_point = points.reference
    if rao_reference is not None:
        wave_point = np.asarray(rao_reference, dtype=float).reshape(3)
    elif legacy_veres and mrb is not None and waves:
        r_g = _rigid_body_cg(mrb)
        if r_g is not None:
            wave_point = points.reference + np.array([r_g[0], 0.0, 0.0])
            history.append(
                "VERES-derived struct of an older MSS version: forceRAO, motionRAO "
                "and driftfrc are about the VERES motion reference point (at the x of G), "
                "not CO; moved to the matrices' reference point"
            )
    if legacy_veres:
        history.append(
            "surge row and column of A and B: MSS estimate A11 = alpha*A22, "
            "B11 = alpha*B22 (ABCtransform.m), not strip-theory output"
        )
    if "driftfrc" in waves:
        history.append(
            "drift_force: MSS gives surge, sway and yaw only; heave, roll and pitch set to 0"
        )
        if extras is None and np.any(np.mod(headings, 2 * np.pi) > np.pi + 1e-6):
            history.append(
                "drift_force read as stored at every heading: MSS fills 190-350 deg itself, "
                "not always as the port/starboard mirror of 10-170 deg (cummins check, "
                "wave_parity, names the headings)"
            )
    if bv_all is not None and np.any(bv_all):
        history.append("additional_damping = vessel.Bv (MSS viscous damping estimate)")
    extra_attrs = _extras(extras, path, history)
    if "water_depth" not in extra_attrs:
        history.append(
            "water depth not recorded in MSS structs: deep water, as MSS's simulators take "
            "it (k = w^2/g)"
        )
    datasets = []
    for s in _select_speed(velocities, speed, path):
        sl = grid.finite
        kw: dict[str, Any] = {}
        if grid.zero is not None:
            kw["added_mass_zero"] = a_all[:, :, grid.zero, s]
        if grid.infinite is not None:
            kw["added_mass_inf"] = a_all[:, :, grid.infinite, s]
        elif "added_mass_inf" in extra_attrs:
            kw["added_mass_inf"] = extra_attrs["added_mass_inf"]
        if "added_mass_zero" not in kw and "added_mass_zero" in extra_attrs:
            kw["added_mass_zero"] = extra_attrs["added_mass_zero"]
        if c_all is not None:
            kw["hydrostatic_stiffness"] = _constant_stiffness(
                c_all[:, :, sl, s], history, velocities[s], nspeed, path
            )
        if "additional_stiffness" in extra_attrs:
            kw["additional_stiffness"] = extra_attrs["additional_stiffness"]
        if mrb is not None:
            kw["inertia_matrix"] = mrb
        if bv_all is not None and np.any(bv_all):
            kw["additional_damping"] = np.moveaxis(bv_all[:, :, sl, s], 2, 0)
        if waves:
            kw["wave_direction"] = headings
        if "forceRAO" in waves:
            kw["excitation_force"] = waves["forceRAO"].values[s]
        if "motionRAO" in waves:
            kw["rao"] = waves["motionRAO"].values[s]
        if "driftfrc" in waves:
            kw["drift_force"] = waves["driftfrc"].values[s]
        attrs = {
            "body_name": _text(main, "name"),
            "center_of_gravity": points.center_of_gravity,
            "center_of_buoyancy": points.center_of_buoyancy,
            "displaced_volume": _scalar(main, "nabla", path, "vessel.main"),
            "ship_length": _scalar(main, "Lpp", path, "vessel.main"),
            "ship_breadth": _scalar(main, "B", path, "vessel.main"),
            "ship_draught": _scalar(main, "T", path, "vessel.main"),
        }
        if c_all is not None and "restoring" in extra_attrs:
            attrs.update(extra_attrs["restoring"])
        elif c_all is not None and points.center_of_gravity is not None:
            # Fossen's G is rho g V GM: the hydrostatics and the weight at main.CG
            mass = mrb[0, 0] if mrb is not None else _scalar(main, "m", path, "vessel.main")
            attrs.update(
                weight_record(
                    [np.nan if mass is None else float(mass)],
                    points.center_of_gravity,
                    "vessel.C (MSS: Fossen's G = rho g V GM, the weight at main.CG)",
                )
            )
        ds = make_hydrodb(
            omega,
            np.moveaxis(a_all[:, :, sl, s], 2, 0),
            np.moveaxis(b_all[:, :, sl, s], 2, 0),
            rho=rho_v,
            g=g_v,
            water_depth=extra_attrs.get("water_depth", np.inf),
            source_format="mss",
            source_file=str(path),
            dofs=list(DOF_NAMES),
            forward_speed=float(velocities[s]),
            reference_point=points.reference,
            axis_convention="z-down",
            history=[*extra_attrs.get("history", []), *history],
            **kw,
            **attrs,
        )
        if "rao" in ds and extra_attrs.get("rao_source"):
            ds["rao"].attrs["description"] = RAO_BY_CUMMINS
        datasets.append(_move_waves(ds, wave_point, points.reference))
    if len(datasets) == 1:
        return datasets[0]
    out = stack_forward_speeds(datasets)
    add_history(out, f"{len(datasets)} forward speeds from vessel.velocities")
    return out


def _constant_stiffness(
    c: NDArray, history: list[str], speed: float, nspeed: int, path: Path
) -> NDArray:
    """The restoring matrix from ``C(:, :, freq)``, which MSS repeats for every frequency.

    A non-finite entry at any frequency is damage, not a value to pass over unseen."""
    if not np.all(np.isfinite(c)):
        k = np.argwhere(~np.isfinite(c))[0]
        raise HydroDataError(
            f"non-finite value (NaN or Inf) at C({k[0] + 1}, {k[1] + 1}, {k[2] + 1})",
            path=path,
            quantity="vessel.C",
            hint="the file is damaged",
        )
    first = c[:, :, 0]
    scale = max(float(np.abs(c).max()), 1e-300)
    deviation = float(np.abs(c - first[:, :, None]).max()) / scale
    if deviation > 1e-9:
        where = f" at {speed:g} m/s" if nspeed > 1 else ""
        history.append(
            f"vessel.C varies with frequency{where} (by {deviation:.2g} of its "
            "largest entry): the value at the first finite frequency is used"
        )
    return first


#: ``rao``'s description when the struct's motionRAO was computed by cummins
#: (:func:`cummins.io.mss.writer._with_motion_rao`), not by the solver.
RAO_BY_CUMMINS = "motion RAOs computed by cummins (motion_rao), not by the solver"


def _extras(extras: np.void | None, path: Path, history: list[str]) -> dict[str, Any]:
    """What :func:`write_mss` stored in ``vessel.cummins`` for lossless round trips."""
    if extras is None:
        return {}
    out: dict[str, Any] = {}
    text = _text(extras, "history")
    if text:
        out["history"] = [*text.splitlines(), "(lines above: history before write_mss)"]
    depth = _scalar(extras, "water_depth", path, "vessel.cummins")
    if depth is not None and depth > 0:
        out["water_depth"] = depth
    if _has(extras, "restoring_source"):  # what C holds, as cummins recorded it
        out["restoring"] = {"restoring_source": _text(extras, "restoring_source")}
        if _has(extras, "restoring_weight_mass") and _has(extras, "restoring_weight_center"):
            out["restoring"].update(
                restoring_weight_mass=float(
                    _numeric(extras["restoring_weight_mass"], path, "vessel.cummins").ravel()[0]
                ),
                restoring_weight_center=_numeric(
                    extras["restoring_weight_center"], path, "vessel.cummins"
                ).reshape(-1)[:3],
            )
    if _has(extras, "rao_source"):  # motionRAO of cummins, not of the solver
        out["rao_source"] = _text(extras, "rao_source")
        history.append("motionRAO computed by cummins when the struct was written")
    for name in ("added_mass_inf", "added_mass_zero", "additional_stiffness"):
        if _has(extras, name):
            value = _numeric(extras[name], path, f"vessel.cummins.{name}")
            if value.shape == (6, 6):
                out[name] = value
                history.append(f"{name} from vessel.cummins (written by cummins)")
    return out
