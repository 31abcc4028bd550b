"""Reading a BEMIO ``.h5`` file, MATLAB or Python (2015) layout, into the canonical ``HydroDB``.

Both layouts share the group names; the reader tells them apart (``comps`` vs
``components``, the ``scaled`` flag), undoes BEMIO's normalisation (A/ρ, B/(ρω), C and
F/(ρg)), checks the redundant copies BEMIO writes (``components``, ``mag``/``phase``) and,
for a file cummins wrote, gives back the exact copy of its ``cummins`` group.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.files import note_read
from cummins.hydrodb import dof_labels, make_hydrodb
from cummins.io._common import DEPTH_ASSUMED, warn_damage
from cummins.io.bemio.files import (
    _IMPLAUSIBLE,
    COPY_GROUP,
    _array,
    _depth,
    _finite,
    _number,
    _text,
    _text_attr,
    _vector,
)
from cummins.restoring import SOURCE, weight_record


def read_bemio(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
) -> xr.Dataset:
    """Read a BEMIO ``.h5`` file (either layout, see the module docstring).

    Parameters
    ----------
    path
        The ``.h5`` file.
    rho, g
        kg/m³, m/s². The file records the values it was made with; a value given here
        may only confirm them.

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB``. Several bodies are ``body1__Surge`` …, the file's names in
        ``body_names``; generalized modes ``Mode7`` ….

    Raises
    ------
    HydroDataError
        Not a BEMIO file, damaged, inconsistent shapes.
    """
    import h5py

    path = Path(path)
    if not path.is_file():
        raise HydroDataError("file not found", path=path)
    note_read(path)
    try:
        with h5py.File(path, "r") as f:
            ds = _read_open(f, path, rho, g)
    except HydroDataError:
        raise
    except Exception as exc:
        raise HydroDataError(
            f"cannot read the BEMIO file ({type(exc).__name__}: {exc})",
            path=path,
            hint="the file is truncated or damaged; write it again",
        ) from None
    return ds


def _read_open(f, path: Path, rho, g) -> xr.Dataset:
    from cummins.io._common import resolve_rho_g

    if "simulation_parameters" not in f or "body1" not in f:
        raise HydroDataError(
            "not a BEMIO file (no simulation_parameters or body1 group)", path=path
        )
    sp = f["simulation_parameters"]
    notes: list[str] = []
    lines: list[str] = [f"read {path.name} (BEMIO .h5)"]
    names = [k for k in f if k.startswith("body") and k[4:].isdigit()]
    n_bodies = len(names)
    if [f"body{k + 1}" for k in range(n_bodies)] != sorted(names, key=lambda s: int(s[4:])):
        raise HydroDataError(
            f"body groups {sorted(names)} are not body1 … body{n_bodies}", path=path
        )
    am0 = f["body1/hydro_coeffs/added_mass"]
    python = "comps" in am0
    if "scaled" in sp:
        normalised = float(_number(sp, "scaled", path)) == 0.0
    else:
        normalised = not python and "components" in am0
    layout = "Python bemio (2015)" if python else "MATLAB BEMIO"
    lines.append(
        f"{layout} layout; coefficients "
        + ("normalised (A/rho, B/(rho w), C and F/(rho g))" if normalised else "dimensional")
    )
    file_rho = _number(sp, "rho", path)
    file_g = _number(sp, "g", path)
    rho_v, g_v = resolve_rho_g(
        rho, g, file_rho, file_g, path=path, history=lines, dimensional=True, defaults=False
    )
    omega = _vector(sp, "w", path)
    if "T" in sp:
        period = _vector(sp, "T", path)
        if period.shape != omega.shape or not np.allclose(
            period * omega, 2 * np.pi, rtol=1e-9, atol=0.0
        ):
            raise HydroDataError(
                "simulation_parameters/w and T disagree (T = 2 pi / w)",
                path=path,
                hint="the file is damaged; write it again with BEMIO",
            )
    if not np.all(np.isfinite(omega)) or np.any(omega <= 0) or np.any(omega > _IMPLAUSIBLE):
        raise HydroDataError("frequencies must be finite and positive", path=path)
    order = np.argsort(omega, kind="stable")
    if np.any(np.diff(omega[order]) == 0):
        raise HydroDataError("a frequency appears twice in simulation_parameters/w", path=path)
    beta = _vector(sp, "wave_dir", path)
    unit = _text_attr(sp["wave_dir"], "units")
    degrees = unit.startswith("deg") if unit else not python
    if not np.all(np.isfinite(beta)) or np.any(np.abs(beta) > (720.0 if degrees else 4 * np.pi)):
        raise HydroDataError(f"wave directions {beta.tolist()} are not angles", path=path)
    if np.unique(beta).size != beta.size:
        raise HydroDataError("a wave direction appears twice", path=path)
    beta_rad = np.radians(beta) if degrees else beta
    depth = _depth(sp, path)
    if "water_depth" not in sp:
        lines.append("water depth not recorded in the file: deep water assumed")

    modes = []
    for k in range(n_bodies):
        props = f[f"body{k + 1}/properties"]
        modes.append(round(_number(props, "dof", path)) if "dof" in props else 6)
    total = sum(modes)
    n_w, n_b = omega.size, beta.size
    added = np.empty((n_w, total, total))
    damping = np.empty((n_w, total, total))
    inf = np.full((total, total), np.nan)
    stiffness = np.zeros((total, total))
    have_stiffness = True
    forces: dict[str, np.ndarray] = {}
    body_names, cg, cb, volume = [], [], [], []
    start = 0
    for k, m in enumerate(modes):
        body = f[f"body{k + 1}"]
        rows = slice(start, start + m)
        coeffs = body["hydro_coeffs"]
        a = _array(coeffs, "added_mass/all", (m, total, n_w), path)
        b = _array(coeffs, "radiation_damping/all", (m, total, n_w), path)
        _check_components(coeffs, "added_mass", a, python, path, notes)
        _check_components(coeffs, "radiation_damping", b, python, path, notes)
        added[:, rows, :] = np.transpose(a, (2, 0, 1))
        damping[:, rows, :] = np.transpose(b, (2, 0, 1))
        if "added_mass/inf_freq" in coeffs:
            inf[rows, :] = _array(coeffs, "added_mass/inf_freq", (m, total), path)
        if "linear_restoring_stiffness" in coeffs:
            c = np.asarray(coeffs["linear_restoring_stiffness"][()], dtype=float)
            if c.shape == (m, m):
                stiffness[rows, rows] = c
            elif c.shape == (m, total):
                stiffness[rows, :] = c
            else:
                raise HydroDataError(
                    f"body{k + 1}/hydro_coeffs/linear_restoring_stiffness has shape {c.shape}, "
                    f"expected {(m, m)}",
                    path=path,
                )
            _finite(c, f"body{k + 1}/hydro_coeffs/linear_restoring_stiffness", path)
        else:
            have_stiffness = False
        for key, group in (
            ("excitation_force", "excitation"),
            ("froude_krylov_force", "excitation/froude-krylov"),
            ("diffraction_force", "excitation/scattering"),
        ):
            if f"{group}/re" not in coeffs or f"{group}/im" not in coeffs:
                continue
            optional = key != "excitation_force"
            re = _array(coeffs, f"{group}/re", (m, n_b, n_w), path, allow_nan=optional)
            im = _array(coeffs, f"{group}/im", (m, n_b, n_w), path, allow_nan=optional)
            value = re + 1j * im
            if optional and np.isnan(value).all():
                if k == 0:
                    lines.append(f"{group} holds NaN only (not computed by the solver): left out")
                continue
            if optional and np.isnan(value).any():
                warn_damage(
                    f"{coeffs.name}/{group} has NaN in some values: left out",
                    path=path,
                    notes=notes,
                    hint="the file is damaged; write it again with BEMIO",
                )
                continue
            _check_polar(coeffs, group, value, path, notes)
            forces.setdefault(key, np.full((n_w, n_b, total), np.nan, dtype=complex))
            forces[key][:, :, rows] = np.transpose(value, (2, 1, 0))
        props = body["properties"]
        body_names.append(_text(props, "name") if "name" in props else "")
        for store, name in ((cg, "cg"), (cb, "cb")):
            store.append(_vector(props, name, path) if name in props else np.full(3, np.nan))
        volume.append(_number(props, "disp_vol", path) if "disp_vol" in props else np.nan)
        start += m

    for key in list(forces):
        if np.isnan(forces[key]).any():
            if key == "excitation_force":
                raise HydroDataError("excitation/re, im are missing for some bodies", path=path)
            del forces[key]
    if normalised:
        added *= rho_v
        damping *= rho_v * omega[:, None, None]
        inf *= rho_v
        stiffness *= rho_v * g_v
        for key in forces:
            forces[key] *= rho_v * g_v
        lines.append("coefficients made dimensional: A*rho, B*rho*w, C*rho*g, F*rho*g")
    if np.isnan(inf).any():
        if not np.isnan(inf).all():
            raise HydroDataError("added_mass/inf_freq is missing for some bodies", path=path)
        inf = None
    if "excitation_force" in forces:
        for key in ("froude_krylov_force", "diffraction_force"):
            if key in forces and not np.all(np.isfinite(forces[key])):
                del forces[key]

    cg_all = np.concatenate(cg)
    labels = dof_labels(n_bodies if n_bodies > 1 else None, modes=modes)
    attrs: dict[str, Any] = {}
    if n_bodies > 1:
        attrs["body_names"] = "\n".join(body_names)
    elif body_names[0]:
        attrs["body_name"] = body_names[0]
    if np.all(np.isfinite(cg_all)):
        attrs["center_of_gravity"] = cg_all
        reference = cg_all
        lines.append(
            "reference point = each body's centre of gravity (BEMIO/WEC-Sim coefficients "
            "are about it)"
        )
    else:
        reference = np.zeros(3 * n_bodies)
        lines.append("no centre of gravity in the file: reference point assumed at the origin")
    cb_all = np.concatenate(cb)
    if np.all(np.isfinite(cb_all)):
        attrs["center_of_buoyancy"] = cb_all
    vol = np.asarray(volume, dtype=float)
    if np.all(np.isfinite(vol)):
        attrs["displaced_volume"] = float(vol[0]) if n_bodies == 1 else vol
    if have_stiffness:
        attrs.update(_restoring_weight(attrs, rho_v, n_bodies))
    if "water_depth" not in sp:
        attrs[DEPTH_ASSUMED] = 1
    if "bem_data/code" in f:
        attrs["bem_code"] = _text(f, "bem_data/code")
    elif "bem_code" in sp:
        attrs["bem_code"] = _text(sp, "bem_code")
    lines.append("wave directions in " + ("degrees" if degrees else "radians") + " in the file")

    ds = make_hydrodb(
        omega[order],
        added[order],
        damping[order],
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format="bemio",
        source_file=str(path),
        dofs=labels,
        wave_direction=beta_rad if forces else None,
        added_mass_inf=inf,
        hydrostatic_stiffness=stiffness if have_stiffness else None,
        reference_point=reference[:3] if n_bodies == 1 else np.zeros(3),
        history=lines,
        read_warnings=notes,
        **{k: v[order] for k, v in forces.items()},
        **attrs,
    )
    if n_bodies > 1:
        ds.attrs["reference_point"] = reference
    if COPY_GROUP in f:
        return _cummins_copy(path, ds, notes)
    return ds


def _cummins_copy(path: Path, ds: xr.Dataset, notes: list[str]) -> xr.Dataset:
    """The exact dataset of a file cummins wrote, checked against the BEMIO datasets."""
    from cummins.io.netcdf import from_capytaine_dataset

    try:
        raw = xr.load_dataset(path, group=COPY_GROUP, engine="h5netcdf")
    except Exception as exc:
        raise HydroDataError(
            f"cannot read the {COPY_GROUP!r} group ({type(exc).__name__}: {exc})",
            path=path,
            hint="the file is damaged; write it again",
        ) from None
    copy = from_capytaine_dataset(raw, source_file=str(path), _path=path)
    reference = copy
    point = np.asarray(ds.attrs["reference_point"], dtype=float).reshape(-1)
    moved = not np.allclose(np.asarray(copy.attrs["reference_point"]).reshape(-1), point)
    if moved:
        from cummins.hydrodb import move_reference_point

        n_bodies = point.size // 3
        reference = move_reference_point(
            copy, point.reshape(n_bodies, 3) if n_bodies > 1 else point
        )
    for name in (
        "added_mass",
        "radiation_damping",
        "added_mass_inf",
        "hydrostatic_stiffness",
        "excitation_force",
    ):
        if name not in ds or name not in reference or (moved and name == "hydrostatic_stiffness"):
            continue
        a, b = ds[name].values, reference[name].values
        if a.shape != b.shape or not np.allclose(a, b, rtol=1e-9, atol=1e-12 * np.abs(b).max()):
            warn_damage(
                f"the BEMIO dataset of {name} differs from the {COPY_GROUP!r} copy cummins "
                "wrote: the copy is used",
                path=path,
                notes=notes,
                hint="the file was edited by another program, or damaged",
            )
    if notes:
        old = str(copy.attrs.get("read_warnings", ""))
        copy.attrs["read_warnings"] = "\n".join([line for line in [old] if line] + notes)
    return copy


def _check_components(coeffs, name: str, full: np.ndarray, python: bool, path, notes) -> None:
    """``comps/comp_i_j`` (Python) or ``components/i_j`` (MATLAB, second column) hold
    the same numbers as ``all``: a difference is damage (warned; ``all`` is used)."""
    group = coeffs[name]
    sub = "comps" if python else "components"
    if sub not in group:
        return
    m, total, _ = full.shape
    for key in group[sub]:
        digits = key.removeprefix("comp_").split("_")
        if len(digits) != 2 or not all(d.isdigit() for d in digits):
            continue
        i, j = int(digits[0]) - 1, int(digits[1]) - 1
        if not (0 <= i < m and 0 <= j < total):
            continue
        values = np.asarray(group[sub][key][()], dtype=float)
        column = values.reshape(-1) if values.ndim == 1 else values[:, -1]
        if column.shape != full[i, j].shape or not np.array_equal(column, full[i, j]):
            warn_damage(
                f"{group.name}/{sub}/{key} differs from {group.name}/all[{i}, {j}] (BEMIO "
                "writes the same numbers in both): 'all' is used",
                path=path,
                notes=notes,
                hint="the file is damaged; write it again with BEMIO",
            )
            return


#: Relative difference (to the largest |F|) between ``mag``·e^{i·``phase``} and
#: ``re`` + i``im`` that is damage when all four are stored in double precision; in
#: single precision (float32, rounding 6·10⁻⁸ per number) it is :data:`POLAR_ULPS` units
#: of that precision.
POLAR_TOL = 1e-9
POLAR_ULPS = 64


def _check_polar(coeffs, group: str, value: np.ndarray, path, notes) -> None:
    """``mag``/``phase`` are |F| and arg F of ``re``/``im``: a difference beyond the
    precision the four are stored in is damage (warned; ``re``/``im`` are used, so the
    numbers read do not depend on it)."""
    if f"{group}/mag" not in coeffs or f"{group}/phase" not in coeffs:
        return
    stored = [coeffs[f"{group}/{key}"] for key in ("re", "im", "mag", "phase")]
    mag = np.asarray(stored[2][()], dtype=float)
    phase = np.asarray(stored[3][()], dtype=float)
    if mag.shape != value.shape or phase.shape != value.shape:
        return
    resolution = max(
        np.finfo(d.dtype).eps if np.issubdtype(d.dtype, np.floating) else 0.0 for d in stored
    )
    tol = max(POLAR_TOL, POLAR_ULPS * float(resolution))
    scale = max(float(np.nanmax(np.abs(value))), 1e-300)
    with np.errstate(invalid="ignore"):
        off = np.abs(mag * np.exp(1j * phase) - value) > tol * scale
    if off.any() or not np.all(np.isfinite(mag)) or not np.all(np.isfinite(phase)):
        warn_damage(
            f"{coeffs.name}/{group}/mag and phase differ from re and im (BEMIO writes |F| and "
            "arg F of the same numbers): re and im are used",
            path=path,
            notes=notes,
            hint="the file is damaged; write it again with BEMIO",
        )


def _restoring_weight(attrs: dict, rho: float, n_bodies: int) -> dict:
    """What BEMIO's ``linear_restoring_stiffness`` holds (:mod:`cummins.restoring`): the
    solver's restoring about each body's centre of gravity (``properties/cg``), where the
    weight's terms vanish, so it holds the hydrostatics about G and the weight of ρ∇ at G
    alike; without ``cg`` nothing is recorded."""
    name = "BEMIO's linear_restoring_stiffness"
    if "center_of_gravity" not in attrs:
        return {SOURCE: f"{name} (no centre of gravity in the file)"}
    volumes = np.atleast_1d(np.asarray(attrs.get("displaced_volume", np.nan), dtype=float))
    masses = rho * volumes if volumes.size == n_bodies else [np.nan] * n_bodies
    return weight_record(
        masses, attrs["center_of_gravity"], f"{name} (about each body's centre of gravity)"
    )
