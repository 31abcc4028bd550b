"""BEMIO ``.h5``: WEC-Sim's hydrodynamic data file (read both layouts, write MATLAB's).

WEC-Sim (NREL/Sandia) runs on an HDF5 file that its pre-processor BEMIO writes from a
solver's output. Two layouts are in use:

* **MATLAB BEMIO** (``writeBEMIOH5.m``, read by WEC-Sim's ``readBEMIOH5.m``), the one in
  use today. MATLAB writes column-major arrays after ``permute(X, [3 2 1])``, so that
  h5py (row-major) sees, per body b with m DOFs starting at row n of the full matrices:

  ======================================================  ===========================
  dataset (under ``body<b>/``)                            h5py shape, element
  ======================================================  ===========================
  ``hydro_coeffs/added_mass/all``                         (m, N, nω): A(n+i, j, ω)/ρ
  ``hydro_coeffs/added_mass/inf_freq``                    (m, N): A∞(n+i, j)/ρ
  ``hydro_coeffs/radiation_damping/all``                  (m, N, nω): B(n+i, j, ω)/(ρω)
  ``hydro_coeffs/excitation/re``, ``im`` (``mag``,        (m, nβ, nω): F(n+i, β, ω)/(ρg)
  ``phase``; ``froude-krylov/…``, ``scattering/…``)
  ``hydro_coeffs/linear_restoring_stiffness``             (m, m): C/(ρg)
  ``hydro_coeffs/radiation_damping/impulse_response_fun`` ``K`` (m, N, nt): K(t)/ρ, ``t``
  ``hydro_coeffs/radiation_damping/state_space``          ``A/all`` (m, N, o, o), ``B/all``
                                                          (m, N, o, 1), ``C/all`` (m, N, 1,
                                                          o) /ρ, ``D/all``, ``K/all``,
                                                          ``it`` (orders), ``r2t``, ``conv``
  ``properties/name``, ``cg``, ``cb``, ``disp_vol``,      m, m, m³; ``dof`` modes per body
  ``dof``, ``dof_start``, ``dof_end``, ``body_number``
  ======================================================  ===========================

  and ``simulation_parameters/`` ``rho``, ``g``, ``w`` (rad/s), ``T`` (s), ``wave_dir``
  (degrees), ``water_depth`` (m, or the text ``infinite``), ``scaled`` (0: the
  coefficients are normalised as above; WEC-Sim multiplies them by ρ, ρω, ρg), and
  ``bem_data/code``. The normalisations are those of BEMIO's ``hydro`` structure (the
  datasets' ``description`` attributes say "normalized by rho", "rho*w", "rho*g") and of
  WEC-Sim's ``bodyClass`` which undoes them (``.*rho``, ``.*rho.*w``, ``.*rho.*g``; the
  state-space ``C`` too). Older MATLAB files also hold ``components/<i>_<j>`` copies
  (nω × 2: period, value) of every coefficient.
* **Python bemio (2015)** (``bemio.io.output.write_hdf5``): the same group names with
  ``comps/comp_<i>_<j>`` copies, wave directions in radians, no ``scaled`` flag, and
  *dimensional* coefficients (measured: the OSWEC file equals its WAMIT ``.out`` made
  dimensional with the file's ρ = 1000 kg/m³, g = 9.81 m/s² to 1e-12).

Conventions: WAMIT's (BEMIO converts NEMOH and Capytaine data to them): time dependence
e^{+iωt}, z up, β the direction the waves travel from +x towards +y, coefficients about
each body's centre of gravity (WEC-Sim requires it; the corpus files' WAMIT ``.out``
twins have XBODY = cg), which becomes ``reference_point`` here.

Writing (:func:`write_bemio`) produces the MATLAB layout above, every numeric dataset
with HDF5's Fletcher-32 checksum, and adds a group ``cummins`` holding the dataset in
cummins' NetCDF layout (:func:`cummins.io.netcdf.to_capytaine_layout`), which WEC-Sim
ignores and which makes read → write → read exact (the normalised copies are checked
against it on reading).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from cummins._version import __version__
from cummins.errors import HydroDataError
from cummins.hydrodb import (
    DOF_NAMES,
    bodies,
    change_axes,
    dof_labels,
    dof_matrix,
    make_hydrodb,
    single_speed,
    split_dof,
    validate,
)
from cummins.io._common import warn_damage

__all__ = ["read_bemio", "read_bemio_state_space", "sniff", "sniff_dir", "write_bemio"]

_MAGIC_HDF5 = b"\x89HDF\r\n\x1a\n"
#: Values beyond this (SI units, or normalised by ρ, ρg) are damaged numbers.
_IMPLAUSIBLE = 1e25
#: Group holding cummins' exact copy of the dataset in files cummins writes.
COPY_GROUP = "cummins"


# --------------------------------------------------------------------------- detection


def sniff(path: Path) -> bool:
    """Content-based test: an HDF5 file with BEMIO's ``simulation_parameters`` and
    ``body1/hydro_coeffs`` groups (a NetCDF-4 file is HDF5 too, but has neither)."""
    try:
        with open(path, "rb") as f:
            if f.read(8) != _MAGIC_HDF5:
                return False
        import h5py

        with h5py.File(path, "r") as f:
            return "simulation_parameters" in f and "body1/hydro_coeffs" in f
    except Exception:  # any unreadable file is simply not ours
        return False


def sniff_dir(path: Path) -> list[Path]:
    """The BEMIO files of a folder, one per run.

    BEMIO names its file after the solver run it processed (``oswec.out`` →
    ``oswec.h5``): an ``.h5`` beside a file of the same name is a processed copy of
    that run, and the folder reads as the solver's output (give the ``.h5`` itself to
    read it).
    """
    path = Path(path)
    out = []
    for candidate in sorted({*path.glob("*.h5"), *path.glob("*.H5")}):
        if not candidate.is_file() or not sniff(candidate):
            continue
        twins = [p for p in path.glob(f"{candidate.stem}.*") if p.suffix.lower() != ".h5"]
        if not twins:
            out.append(candidate)
    return out


# --------------------------------------------------------------------------- reading


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


def _number(group, name: str, path: Path) -> float:
    value = np.asarray(group[name][()]).reshape(-1)
    if value.size != 1 or value.dtype.kind not in "fiub":
        raise HydroDataError(f"{group.name}/{name} is not a number", path=path)
    number = float(value[0])
    if not np.isfinite(number) or abs(number) > _IMPLAUSIBLE:
        raise HydroDataError(f"{group.name}/{name} = {number!r} is not a usable number", path=path)
    return number


def _vector(group, name: str, path: Path) -> np.ndarray:
    value = np.asarray(group[name][()])
    if value.dtype.kind not in "fiu":
        raise HydroDataError(f"{group.name}/{name} is not numeric", path=path)
    return value.astype(float).reshape(-1)


def _text(group, name: str) -> str:
    value = group[name][()]
    if isinstance(value, np.ndarray):
        value = value.reshape(-1)[0] if value.size else b""
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    return str(value).strip()


def _text_attr(obj, name: str) -> str:
    value = obj.attrs.get(name)
    if isinstance(value, np.ndarray):
        value = value.reshape(-1)[0] if value.size else b""
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    return str(value).strip().lower() if value is not None else ""


def _depth(sp, path: Path) -> float:
    if "water_depth" not in sp:
        return np.inf
    value = sp["water_depth"][()]
    if isinstance(value, bytes | str) or (
        isinstance(value, np.ndarray) and value.dtype.kind in "SOU"
    ):
        text = _text(sp, "water_depth").lower()
        if text.startswith("inf"):
            return np.inf
        raise HydroDataError(f"water_depth {text!r} is not a depth", path=path)
    depth = _number(sp, "water_depth", path)
    if not depth > 0:
        raise HydroDataError(f"water_depth = {depth!r} m is not positive", path=path)
    return depth


def _finite(values: np.ndarray, name: str, path: Path) -> None:
    with np.errstate(invalid="ignore"):
        bad = ~np.isfinite(values) | (np.abs(values) > _IMPLAUSIBLE)
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        raise HydroDataError(
            f"{name}{list(index)} = {values[index]!r} is not a usable number",
            path=path,
            hint="the file is damaged; write it again with BEMIO",
        )


def _array(
    group, name: str, shape: tuple[int, ...], path: Path, *, allow_nan: bool = False
) -> np.ndarray:
    if name not in group:
        raise HydroDataError(f"no {group.name}/{name} dataset", path=path)
    values = np.asarray(group[name][()])
    if values.dtype.kind not in "fiu":
        raise HydroDataError(f"{group.name}/{name} is not numeric", path=path)
    values = values.astype(float)
    if values.shape != shape:
        raise HydroDataError(
            f"{group.name}/{name} has shape {values.shape}, expected {shape}", path=path
        )
    _finite(np.nan_to_num(values, nan=0.0) if allow_nan else values, f"{group.name}/{name}", path)
    return values


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


def _check_polar(coeffs, group: str, value: np.ndarray, path, notes) -> None:
    """``mag``/``phase`` are |F| and arg F of ``re``/``im``: a difference is damage."""
    if f"{group}/mag" not in coeffs or f"{group}/phase" not in coeffs:
        return
    mag = np.asarray(coeffs[f"{group}/mag"][()], dtype=float)
    phase = np.asarray(coeffs[f"{group}/phase"][()], dtype=float)
    if mag.shape != value.shape or phase.shape != value.shape:
        return
    scale = max(float(np.nanmax(np.abs(value))), 1e-300)
    with np.errstate(invalid="ignore"):
        off = np.abs(mag * np.exp(1j * phase) - value) > 1e-9 * scale
    if off.any() or not np.all(np.isfinite(mag)) or not np.all(np.isfinite(phase)):
        warn_damage(
            f"{coeffs.name}/{group}/mag and phase differ from re and im (BEMIO writes |F| and "
            "arg F of the same numbers): re and im are used",
            path=path,
            notes=notes,
            hint="the file is damaged; write it again with BEMIO",
        )


def read_bemio_state_space(path: str | os.PathLike[str]):
    """The radiation state-space models BEMIO fitted (``radiationIRFSS``), as a
    :class:`~cummins.radiation.model.RadiationModel` (memory term μ = K * q̇, SI units).

    Per coupling (i, j) the first ``it(i, j)`` states of ``A/all``, ``B/all``,
    ``C/all`` (×ρ, as WEC-Sim's ``bodyClass`` does) form one SISO model; couplings with
    a zero ``C`` contribute nothing and are left out. ``D`` is not used (WEC-Sim does
    not use it either). A∞ is the file's ``inf_freq`` × ρ.

    Raises
    ------
    HydroDataError
        No state space in the file, or inconsistent shapes.
    """
    import h5py

    from cummins.radiation.model import CouplingModel, RadiationModel

    path = Path(path)
    ds = read_bemio(path)
    n = ds.sizes["influenced_dof"]
    rho = float(ds.attrs["rho"])
    couplings = []
    try:
        with h5py.File(path, "r") as f:
            start = 0
            k = 1
            while f"body{k}" in f:
                group = f"body{k}/hydro_coeffs/radiation_damping/state_space"
                if group not in f:
                    raise HydroDataError(f"no {group} in the file", path=path)
                ss = f[group]
                orders = np.asarray(ss["it"][()], dtype=float)
                m = orders.shape[0]
                a_all = np.asarray(ss["A/all"][()], dtype=float)
                b_all = np.asarray(ss["B/all"][()], dtype=float)
                c_all = np.asarray(ss["C/all"][()], dtype=float)
                for i in range(m):
                    for j in range(n):
                        o = round(float(orders[i, j]))
                        if o <= 0:
                            continue
                        c = c_all[i, j, 0, :o] * rho
                        if not np.any(c):
                            continue
                        couplings.append(
                            CouplingModel(
                                start + i,
                                j,
                                a_all[i, j, :o, :o].copy(),
                                b_all[i, j, :o, 0].copy(),
                                c,
                                method="bemio-ss",
                            )
                        )
                start += m
                k += 1
    except HydroDataError:
        raise
    except Exception as exc:
        raise HydroDataError(
            f"cannot read the state-space models ({type(exc).__name__}: {exc})", path=path
        ) from None
    inf = dof_matrix(ds, "added_mass_inf") if "added_mass_inf" in ds else np.full((n, n), np.nan)
    attrs = {"axis_convention": "z-up", "source_format": "bemio", "source_file": str(path)}
    return RadiationModel(
        tuple(str(d) for d in ds.influenced_dof.values), tuple(couplings), inf, attrs
    )


# --------------------------------------------------------------------------- writing


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
    from cummins.io.netcdf import _checksum_encoding, to_capytaine_layout

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

    tmp = path.with_name(f".{path.name}.tmp")
    try:
        with h5py.File(tmp, "w") as f:
            text = _text_writer(f)
            number = _number_writer(f)
            text("bem_data/code", str(ds.attrs.get("bem_code", ds.attrs.get("source_format", ""))))
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
                number(f"{body}/properties/dof_start", [[start + 1.0]], "Degrees of freedom", "")
                number(f"{body}/properties/dof_end", [[start + float(m)]], "Degrees of freedom", "")
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
                number(f"{irf}/t", t[:, None], "Time vector for the impulse resonse function", "s")
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
                            f"{sg}/{key}/all", ss[key][rows], f"State Space {key} Coefficient", ""
                        )
                    number(f"{sg}/D/all", ss["D"][rows], "State Space D Coefficient", "")
                    number(f"{sg}/it", ss["it"][rows], "Order of state space realization", "")
                    number(f"{sg}/r2t", ss["r2t"][rows], "State space curve fitting R**2 value", "")
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
        os.replace(tmp, path)
    except OSError as exc:
        raise HydroDataError(f"cannot write the file ({exc})", path=path) from None
    finally:
        if tmp.exists():
            tmp.unlink()
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


def _state_space(model, labels: Sequence[str], t: np.ndarray, rho: float, path: Path) -> dict:
    """BEMIO's per-coupling arrays (h5py order, all DOFs as rows) of a RadiationModel."""
    dofs = [str(d) for d in model.dofs]
    if dofs != list(labels):
        raise HydroDataError(
            f"the model's DOFs ({', '.join(dofs)}) are not the data's ({', '.join(labels)})",
            path=path,
        )
    n = len(labels)
    model = model.as_couplings()  # BEMIO stores one state-space model per coupling
    by_pair = {(k.influenced, k.radiating): k for k in model.couplings}
    order = max([k.order for k in model.couplings] + [1])
    a = np.zeros((n, n, order, order))
    b = np.zeros((n, n, order, 1))
    c = np.zeros((n, n, 1, order))
    it = np.ones((n, n))
    r2 = np.full((n, n), np.nan)
    conv = np.zeros((n, n))
    kernel = np.zeros((n, n, t.size))
    for i in range(n):
        for j in range(n):
            coupling = by_pair.get((i, j))
            if coupling is None or coupling.order == 0:
                a[i, j, 0, 0], b[i, j, 0, 0] = -1.0, 1.0
                continue
            o = coupling.order
            a[i, j, :o, :o] = coupling.a
            b[i, j, :o, 0] = coupling.b
            c[i, j, 0, :o] = coupling.c / rho
            it[i, j] = o
            conv[i, j] = 1.0
            kernel[i, j] = coupling.impulse_response(t) / rho
            metric = dict(coupling.metrics).get("r2_damping", dict(coupling.metrics).get("r2_B"))
            if metric is not None:
                r2[i, j] = float(metric)
    return {
        "A": a,
        "B": b,
        "C": c,
        "D": np.zeros((n, n)),
        "K": kernel,
        "it": it,
        "r2t": r2,
        "conv": conv,
    }
