"""Marine Systems Simulator (MSS) ``vessel`` structs in MATLAB ``.mat`` files.

MSS (Fossen, cybergalactic/MSS on GitHub) stores a processed vessel as one struct named
``vessel``, written by ``wamit2vessel.m`` or ``veres2vessel.m`` and read by
``vessel2ss.m`` and the Simulink models. Its fields, as found in the MSS files
``tanker.mat`` (from WAMIT), ``supply.mat`` and ``s175.mat`` (from ShipX/VERES):

==================  ==================================================================
``main``            ``name``, ``rho`` (kg/m³), ``g`` (m/s²), ``m`` (kg), ``nabla`` (m³),
                    ``Lpp``, ``B``, ``T`` (m), ``CG``, ``CB`` (m, see below),
                    ``k44`` … (m), ``GM_T``, ``GM_L`` (m)
``MRB``             6×6 rigid-body mass matrix about the reference point (kg, kg·m, kg·m²)
``A``, ``B``, ``C`` 6×6×Nfreq (×Nspeed) added mass, potential damping, restoring
``Bv``              6×6×Nfreq (×Nspeed) viscous damping estimated by MSS
``freqs``           1×Nfreq, rad/s
``headings``        1×Nhead, rad (0:10:350 deg)
``velocities``      1×Nspeed, m/s
``forceRAO``        ``w`` (rad/s), ``amp{1:6}``, ``phase{1:6}``: (Nω, Nhead, Nslot)
``motionRAO``       as ``forceRAO``; amplitudes m/m and rad/m
``driftfrc``        ``w``, ``amp{1:3}``: mean drift in surge, sway and yaw (N/m², N·m/m²)
``roll``            (VERES only) VERES roll damping, ``Bv44`` and the raw ``veres`` rows
==================  ==================================================================

Conventions, checked against the WAMIT and VERES files MSS processed (see the tests):

* Axes are Fossen's body axes (x forward, y to starboard, z down): this reader returns
  ``axis_convention="z-down"`` data as MSS has it, SI units.
* Complex values are ``amp * exp(1j * phase)`` with the phase in radians and time
  dependence Re{X e^{iωt}}; they equal WAMIT's and VERES's complex values after the axis
  change (``tanker.mat`` forceRAO agrees with the WAMIT ``.3`` file to round-off).
* ``headings`` is the direction in which the waves travel, from +x towards +y
  (starboard): the ``wave_direction`` of the z-down dataset.
* MSS (``wamit2vessel``) puts ω = 0 as the first frequency and A(∞) at a last stand-in
  frequency of 10 rad/s, with zero damping at both (``vessel2ss`` relies on this). The
  reader moves a first entry at ω = 0 into ``added_mass_zero``, and a last entry with
  exactly zero damping (the frequency before it having some) into ``added_mass_inf``.
* ``C`` is repeated for every frequency; it must not vary (else the first value is used
  and the history says so).
* ``forceRAO.amp`` etc. have a third index over up to 10 speed slots, of which the first
  ``numel(velocities)`` are used.

Reference point. MSS calls the origin CO of its b-frame the point on the waterline at
Lpp/2 on the centre line. ``main.CG`` is written in two ways: older files (all three
here) give ``[x_g, y_g, KG]`` with KG the height of G above the keel; newer MSS
versions (those that write ``hydrodynamic_reference``, ``'CO'`` or ``'CG'``: the point
the data are about) give the FSD vector from CO. Without that field the reader decides
which from ``MRB``, whose off-diagonal block holds m·r_g about the point the matrices
are taken about: the reference point is CG − r_g, and the interpretation that puts it
on the waterline (z = 0) wins. The dataset's ``reference_point`` is that point, in
z-down coordinates from CO. It is CO for ``tanker.mat`` and ``supply.mat``, and 0.05 m
above the waterline for ``s175.mat`` (VERES computed the S-175 about its CG height and
MSS moved the matrices only along x).

VERES-derived structs (with a ``roll.veres`` field and no ``hydrodynamic_reference``
field), written by the older MSS versions, have ``forceRAO`` and ``motionRAO`` left
about the VERES motion reference point, at the longitudinal position of G, while
``A``, ``B``, ``C`` and ``MRB`` were moved to CO. The reader moves the RAOs to the
reference point of the matrices (``rao_reference`` overrides the detected point), and
notes that the surge row of ``A`` and ``B`` is MSS's estimate (A11 = α A22,
B11 = α B22), not VERES output.

:func:`write_mss` writes any ``HydroDB`` as such a struct (MATLAB v5 file), about the
dataset's reference point, which it records in ``vessel.cummins.reference_point`` (read
back first by this reader) besides ``hydrodynamic_reference`` (``'CO'``/``'CG'``).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import scipy.io
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import HydroDataError
from cummins.hydrodb import (
    DOF_NAMES,
    add_history,
    change_axes,
    make_hydrodb,
    move_reference_point,
    stack_forward_speeds,
)
from cummins.io._common import resolve_rho_g

__all__ = ["read_mss", "sniff", "sniff_dir", "write_mss"]

#: The frequency MSS uses as a stand-in for ω = ∞ (``wamit2vessel``, ``vessel2ss``).
MSS_INFINITE_FREQUENCY = 10.0
#: DOF index (0-based) of the three mean drift components MSS stores in ``driftfrc.amp``.
DRIFT_DOFS = (0, 1, 5)
#: Relative tolerance when matching the frequency lists of the RAO tables to ``freqs``
#: (``driftfrc.w`` of VERES-derived files is rounded to 4 decimals: 0.1047 for 0.10472).
_FREQ_RTOL = 2e-3
_MAT_MAGIC = b"MATLAB 5.0 MAT-file"
_HDF5_MAGIC = b"\x89HDF\r\n\x1a\n"


# --------------------------------------------------------------------------- detection


def _is_mat_v5(path: Path) -> bool:
    with open(path, "rb") as f:
        head = f.read(128)
    return head.startswith(_MAT_MAGIC)


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` a MATLAB file holding an MSS ``vessel`` struct?"""
    path = Path(path)
    if not path.is_file() or not _is_mat_v5(path):
        return False
    try:
        variables = scipy.io.whosmat(str(path))
    except Exception:  # scipy raises many kinds on foreign content
        return False
    return any(name in ("vessel", "RAO") and cls == "struct" for name, _, cls in variables)


def sniff_dir(path: Path) -> list[Path]:
    """The MSS vessel files (``*.mat`` holding a ``vessel`` struct) in a folder."""
    return sorted(p for p in Path(path).glob("*.mat") if sniff(p))


# --------------------------------------------------------------------------- struct access


def load_mat_struct(path: Path, name: str, missing_hint: str) -> np.void:
    """The 1×1 struct ``name`` of a MATLAB (v5–v7) .mat file, or a HydroDataError naming
    the file (v7.3/HDF5, unreadable, no such struct, not a struct)."""
    if not path.is_file():
        raise HydroDataError("file not found", path=path)
    with open(path, "rb") as f:
        head = f.read(128)
    if head.startswith(_HDF5_MAGIC) or b"MATLAB 7.3" in head:
        raise HydroDataError(
            "MATLAB v7.3 (HDF5) .mat files are not supported",
            path=path,
            hint=f"in MATLAB, save the struct again with save(file, '{name}', '-v7')",
        )
    try:
        content = scipy.io.loadmat(str(path), squeeze_me=False, struct_as_record=True)
    except Exception as exc:  # scipy raises ValueError, TypeError, OSError … on damage
        raise HydroDataError(
            f"not a readable MATLAB .mat file ({exc})",
            path=path,
            hint="check the file was saved by MATLAB (save -v7) and is complete",
        ) from None
    if name not in content:
        names = ", ".join(k for k in content if not k.startswith("__")) or "none"
        raise HydroDataError(
            f"no '{name}' struct in the file (variables: {names})", path=path, hint=missing_hint
        )
    value = content[name]
    if value.dtype.names is None or value.size != 1:
        raise HydroDataError(f"'{name}' is not a 1×1 struct", path=path)
    return value.reshape(-1)[0]


def _has(struct: np.void | None, name: str) -> bool:
    return struct is not None and struct.dtype.names is not None and name in struct.dtype.names


def _field(struct: np.void, name: str, path: Path, owner: str = "vessel") -> Any:
    if not _has(struct, name):
        raise HydroDataError(
            f"the struct has no field {owner}.{name}",
            path=path,
            quantity=f"{owner}.{name}",
            hint="this does not look like a complete MSS vessel struct",
        )
    return struct[name]


def _substruct(struct: np.void, name: str) -> np.void | None:
    if not _has(struct, name):
        return None
    value = struct[name]
    if not isinstance(value, np.ndarray) or value.dtype.names is None or value.size != 1:
        return None
    return value.reshape(-1)[0]


def _numeric(value: Any, path: Path, name: str) -> NDArray[np.float64]:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise HydroDataError("expected a numeric array", path=path, quantity=name) from None
    return arr


def _scalar(struct: np.void | None, name: str, path: Path, owner: str) -> float | None:
    if not _has(struct, name):
        return None
    arr = _numeric(struct[name], path, f"{owner}.{name}").reshape(-1)
    if arr.size != 1 or not np.isfinite(arr[0]):
        return None
    return float(arr[0])


def _text(struct: np.void | None, name: str) -> str | None:
    if not _has(struct, name):
        return None
    value = np.asarray(struct[name]).reshape(-1)
    if value.size == 1 and isinstance(value[0], str):
        return value[0]
    if value.dtype.kind == "U" and value.size:
        return "".join(str(v) for v in value)
    return None


def _cells(value: Any, path: Path, name: str) -> list[NDArray[np.float64]]:
    """A MATLAB cell array of numeric arrays (``amp{1:6}``) as a list of float arrays."""
    arr = np.asarray(value)
    if arr.dtype != object:
        raise HydroDataError("expected a cell array", path=path, quantity=name)
    return [_numeric(c, path, f"{name}{{{k + 1}}}") for k, c in enumerate(arr.reshape(-1))]


# --------------------------------------------------------------------------- reading


@dataclass(frozen=True)
class _Grid:
    """Which entries of ``vessel.freqs`` are ω = 0, ω = ∞ and the finite grid."""

    omega: NDArray[np.float64]
    finite: slice
    zero: int | None
    infinite: int | None


def _frequency_grid(freqs: NDArray, damping: NDArray, path: Path, history: list[str]) -> _Grid:
    """Split ``freqs`` into ω = 0, the finite grid and MSS's stand-in for ω = ∞.

    ``damping`` has shape (6, 6, nfreq, nspeed).
    """
    if freqs.size == 0:
        raise HydroDataError("vessel.freqs is empty", path=path, quantity="vessel.freqs")
    if not np.all(np.isfinite(freqs)):
        raise HydroDataError("non-finite frequency", path=path, quantity="vessel.freqs")
    if np.any(np.diff(freqs) <= 0):
        k = int(np.argmax(np.diff(freqs) <= 0))
        raise HydroDataError(
            f"frequencies are not strictly increasing ({freqs[k]:g} then {freqs[k + 1]:g} rad/s)",
            path=path,
            quantity="vessel.freqs",
        )
    if freqs[0] < 0:
        raise HydroDataError("negative frequency", path=path, quantity="vessel.freqs")
    start, stop = 0, freqs.size
    zero = infinite = None
    if freqs[0] == 0:
        zero, start = 0, 1
        history.append("first entry of vessel.freqs is omega = 0: its A is added_mass_zero")
    if stop - start >= 3:
        last, before = damping[:, :, -1], damping[:, :, -2]
        if not np.any(last) and np.any(before):
            infinite, stop = freqs.size - 1, freqs.size - 1
            ratio = freqs[-1] / freqs[-2]
            history.append(
                f"last entry of vessel.freqs ({freqs[-1]:g} rad/s, {ratio:.2f} x the one "
                "before) has exactly zero damping: taken as MSS's stand-in for omega = "
                "infinity (WAMIT period 0); its A is added_mass_inf"
            )
    if stop <= start:
        raise HydroDataError("no finite frequency in vessel.freqs", path=path)
    return _Grid(freqs[start:stop], slice(start, stop), zero, infinite)


def _as_4d(arr: NDArray, nfreq: int, nspeed: int, path: Path, name: str) -> NDArray:
    """6×6×Nfreq(×Nspeed) as shape (6, 6, nfreq, nspeed)."""
    if arr.ndim == 2:
        arr = arr[:, :, None]
    if arr.ndim == 3:
        arr = arr[:, :, :, None]
    if arr.ndim != 4 or arr.shape[:3] != (6, 6, nfreq) or arr.shape[3] not in (1, nspeed):
        raise HydroDataError(
            f"has shape {arr.shape}, expected (6, 6, {nfreq}) or (6, 6, {nfreq}, {nspeed})",
            path=path,
            quantity=f"vessel.{name}",
        )
    if arr.shape[3] != nspeed:
        arr = np.repeat(arr, nspeed, axis=3)
    return arr


def _match_frequencies(w: NDArray, omega: NDArray) -> NDArray[np.intp] | None:
    """Index into ``w`` of each ``omega`` (tolerance :data:`_FREQ_RTOL`), or None."""
    if w.size == 0:
        return None
    idx = np.abs(w[None, :] - omega[:, None]).argmin(axis=1)
    if np.all(np.abs(w[idx] - omega) <= _FREQ_RTOL * omega):
        return idx
    return None


@dataclass(frozen=True)
class _WaveTable:
    """A ``forceRAO``/``motionRAO``/``driftfrc`` table on the dataset's grid."""

    values: NDArray  # (nspeed, nomega, nhead, 6)
    note: str | None = None


def _wave_table(
    vessel: np.void,
    name: str,
    omega: NDArray,
    nhead: int,
    nspeed: int,
    path: Path,
    history: list[str],
) -> _WaveTable | None:
    table = _substruct(vessel, name)
    if table is None:
        return None
    w = _numeric(_field(table, "w", path, f"vessel.{name}"), path, f"vessel.{name}.w").reshape(-1)
    amp = _cells(_field(table, "amp", path, f"vessel.{name}"), path, f"vessel.{name}.amp")
    drift = name == "driftfrc"
    if drift:
        phase = None
        if len(amp) < 3:
            raise HydroDataError(
                f"expected 3 drift components (surge, sway, yaw), found {len(amp)}",
                path=path,
                quantity="vessel.driftfrc.amp",
            )
        extra = [a for a in amp[3:] if np.any(a)]
        if extra:
            history.append(
                "driftfrc.amp{4:end} are not all zero: ignored (MSS stores "
                "surge, sway and yaw drift in amp{1:3})"
            )
        amp = amp[:3]
    else:
        phase = _cells(_field(table, "phase", path, f"vessel.{name}"), path, f"vessel.{name}.phase")
        if len(amp) != 6 or len(phase) != 6:
            raise HydroDataError(
                f"expected 6 amplitude and phase tables, found {len(amp)} and {len(phase)}",
                path=path,
                quantity=f"vessel.{name}",
            )
    index = _match_frequencies(w, omega)
    if index is None:
        history.append(
            f"vessel.{name} not read: its {w.size} frequencies ({w.min():g}-{w.max():g} "
            f"rad/s) do not cover the {omega.size} frequencies of vessel.A"
            if w.size
            else f"vessel.{name} not read: no frequencies"
        )
        return None

    def cube(a: NDArray, label: str) -> NDArray:
        if a.ndim == 2:
            a = a[:, :, None]
        if a.ndim != 3 or a.shape[0] != w.size or a.shape[1] != nhead or a.shape[2] < nspeed:
            raise HydroDataError(
                f"has shape {a.shape}, expected ({w.size}, {nhead}, >= {nspeed}) "
                "(frequencies, headings, speeds)",
                path=path,
                quantity=label,
            )
        return a[index][:, :, :nspeed]

    out = np.zeros((nspeed, omega.size, nhead, 6), dtype=float if drift else complex)
    for k, a in enumerate(amp):
        a3 = cube(a, f"vessel.{name}.amp{{{k + 1}}}")
        if drift:
            out[..., DRIFT_DOFS[k]] = np.moveaxis(a3, 2, 0)
        else:
            p3 = cube(phase[k], f"vessel.{name}.phase{{{k + 1}}}")
            out[..., k] = np.moveaxis(a3 * np.exp(1j * p3), 2, 0)
    return _WaveTable(out)


def _rigid_body_cg(mrb: NDArray) -> NDArray | None:
    """r_g (FSD, from the matrices' reference point) from MRB = [m I, −m S(r_g); …].

    Each coordinate appears twice in the upper-right block (e.g. m·x_g at (2, 6) and
    −m·x_g at (3, 5), 1-based); mass matrices typed by hand (the tanker's WAMIT ``.frc``)
    sometimes fill only one of them, so a zero entry defers to its partner.
    """
    m = mrb[0, 0]
    if not m > 0:
        return None
    pairs = ((mrb[1, 5], -mrb[2, 4]), (-mrb[0, 5], mrb[2, 3]), (mrb[0, 4], -mrb[1, 3]))
    r_g = [a if b == 0 else b if a == 0 else 0.5 * (a + b) for a, b in pairs]
    return np.asarray(r_g, dtype=float) / m


_FSD = "the FSD vector from CO"
_KEEL = "x_g, y_g, KG (KG: height of G above the keel)"


@dataclass(frozen=True)
class _Points:
    reference: NDArray
    center_of_gravity: NDArray | None
    center_of_buoyancy: NDArray | None


def _points(
    vessel: np.void, main: np.void | None, mrb: NDArray | None, path: Path, history: list[str]
) -> _Points:
    """Reference point, CG and CB in z-down coordinates from CO (see module docstring)."""

    def vec(name: str) -> NDArray | None:
        if not _has(main, name):
            return None
        v = _numeric(main[name], path, f"vessel.main.{name}").reshape(-1)
        return v if v.size == 3 and np.all(np.isfinite(v)) else None

    cg_raw, cb_raw = vec("CG"), vec("CB")
    cg_raw = None if cg_raw is None else cg_raw + 0.0  # no negative zeros
    cb_raw = None if cb_raw is None else cb_raw + 0.0
    draft = _scalar(main, "T", path, "vessel.main")
    r_g = _rigid_body_cg(mrb) if mrb is not None else None
    extras = _substruct(vessel, "cummins")
    if _has(extras, "reference_point"):
        # Written by write_mss: main.CG is the FSD vector from CO, the data are about
        # the point recorded here.
        ref = _numeric(extras["reference_point"], path, "vessel.cummins.reference_point")
        ref = ref.reshape(-1)
        if ref.size != 3 or not np.all(np.isfinite(ref)):
            raise HydroDataError(
                "expected 3 coordinates", path=path, quantity="vessel.cummins.reference_point"
            )
        history.append(
            f"data about {np.round(ref, 6).tolist()} m (z-down, from CO), as recorded by "
            "cummins in vessel.cummins.reference_point"
        )
        return _Points(ref + 0.0, cg_raw, cb_raw)
    declared = _text(vessel, "hydrodynamic_reference")
    if declared is not None:
        # Newer MSS: main.CG is the FSD vector from CO; matrices about CO or CG.
        cg, cb = cg_raw, cb_raw
        if declared.upper() == "CG" and cg is not None:
            ref = cg.copy()
        else:
            ref = np.zeros(3)
        history.append(
            f"vessel.hydrodynamic_reference = '{declared}': data about "
            f"{np.round(ref, 6).tolist()} m (z-down, from CO)"
        )
        return _Points(ref, cg, cb)
    if cg_raw is None:
        history.append("vessel.main.CG missing: reference point taken as CO")
        return _Points(np.zeros(3), None, None)
    keel = None if draft is None else np.array([cg_raw[0], cg_raw[1], draft - cg_raw[2]])
    options = [(_FSD, cg_raw)] + ([] if keel is None else [(_KEEL, keel)])
    if r_g is None:
        label, cg = options[-1]
        label = f"{label} = {np.round(cg_raw, 6).tolist()} m"
        history.append(
            f"vessel.main.CG read as {label}; MRB has no mass: reference point taken as CO"
        )
        return _Points(np.zeros(3), cg, None)
    label, cg = min(options, key=lambda option: abs(option[1][2] - r_g[2]))
    label = f"{label} = {np.round(cg_raw, 6).tolist()} m"
    # main.CG of VERES-derived files holds single-precision values (7.3000002):
    # round the point to 0.01 mm.
    ref = np.round(cg - r_g, 5) + 0.0
    cb = None
    if cb_raw is not None:
        cb = cb_raw if label == _FSD else np.array([cb_raw[0], cb_raw[1], draft - cb_raw[2]])
    history.append(
        f"vessel.main.CG read as {label}; with r_g = {np.round(r_g, 6).tolist()} m from "
        f"MRB the matrices are about {np.round(ref, 6).tolist()} m (z-down, from CO)"
    )
    return _Points(ref, cg, cb)


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
        detected for VERES-derived structs (see the module docstring).

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
        return _read_mss(path, rho, g, speed, rao_reference)
    except HydroDataError:
        raise
    except (KeyError, IndexError, ValueError, TypeError, AttributeError) as exc:
        raise HydroDataError(
            f"unexpected content in the vessel struct ({type(exc).__name__}: {exc})",
            path=path,
            hint="the file may be damaged or not written by MSS",
        ) from None


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
    if bv_all is not None and np.any(bv_all):
        history.append("additional_damping = vessel.Bv (MSS viscous damping estimate)")
    extra_attrs = _extras(extras, path, history)
    if "water_depth" not in extra_attrs:
        history.append("water depth not recorded in MSS structs: deep water assumed")
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
    for name in ("added_mass_inf", "added_mass_zero", "additional_stiffness"):
        if _has(extras, name):
            value = _numeric(extras[name], path, f"vessel.cummins.{name}")
            if value.shape == (6, 6):
                out[name] = value
                history.append(f"{name} from vessel.cummins (written by cummins)")
    return out


# --------------------------------------------------------------------------- writing


def _speed_slices(ds: xr.Dataset) -> tuple[list[xr.Dataset], NDArray]:
    if "forward_speed" in ds.dims:
        speeds = np.asarray(ds.forward_speed.values, dtype=float)
        return [ds.isel(forward_speed=k) for k in range(speeds.size)], speeds
    speed = float(ds.forward_speed) if "forward_speed" in ds.coords else 0.0
    return [ds], np.array([speed])


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


def _main_struct(ds: xr.Dataset, mrb: NDArray | None, point: NDArray, name: str) -> dict:
    """``vessel.main``; ``CG`` and ``CB`` as FSD vectors from CO (current MSS convention)."""
    main: dict[str, Any] = {"name": name, "rho": float(ds.attrs["rho"]), "g": float(ds.attrs["g"])}
    r_g = _rigid_body_cg(mrb) if mrb is not None else None
    if r_g is not None:
        m = float(mrb[0, 0])
        main["m"] = m
        main["nabla"] = float(ds.attrs.get("displaced_volume", m / ds.attrs["rho"]))
        main["k44"], main["k55"], main["k66"] = (
            float(np.sqrt(max(mrb[k, k], 0.0) / m)) for k in (3, 4, 5)
        )
    if "center_of_gravity" in ds.attrs:
        main["CG"] = np.asarray(ds.attrs["center_of_gravity"], dtype=float).reshape(1, 3)
    elif r_g is not None:
        main["CG"] = (point + r_g)[None, :]
    if "center_of_buoyancy" in ds.attrs:
        main["CB"] = np.asarray(ds.attrs["center_of_buoyancy"], dtype=float).reshape(1, 3)
    for key, attr in (("Lpp", "ship_length"), ("B", "ship_breadth"), ("T", "ship_draught")):
        if attr in ds.attrs:
            main[key] = float(ds.attrs[attr])
    return main


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
    data, not completed by symmetry), ``velocities``, ``forceRAO``, ``motionRAO`` and
    ``driftfrc`` (surge, sway and yaw only: heave, roll and pitch drift are lost) when
    present, ``main`` (``name``, ``rho``, ``g``, ``m``, ``nabla``, ``CG`` and ``CB`` as
    FSD vectors from CO, ``k44`` …, ``Lpp``, ``B``, ``T`` when known) and
    ``hydrodynamic_axes = 'FSD'``, as current MSS does. ``vessel.cummins`` keeps the
    history, the reference point and what MSS has no field for; MSS ignores it.

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
    if "wave_direction" in ds.dims:
        ds = ds.assign_coords(wave_direction=np.mod(ds.wave_direction.values, 2 * np.pi))
    out = change_axes(ds, "z-down")
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
    if not with_limits:
        for name in ("added_mass_inf", "added_mass_zero"):
            if name in first:
                extras[name] = first[name].values
    if "additional_stiffness" in first:
        extras["additional_stiffness"] = first["additional_stiffness"].values
    vessel["cummins"] = extras
    try:
        scipy.io.savemat(str(path), {"vessel": vessel}, do_compression=True, oned_as="row")
    except OSError as exc:
        raise HydroDataError(f"cannot write the file ({exc.strerror or exc})", path=path) from None
    return path


# --------------------------------------------------------------------------- RAO structs


def _holds_rao_struct(path: Path) -> bool:
    try:
        variables = scipy.io.whosmat(str(path))
    except Exception:
        return False
    names = {name for name, _, cls in variables if cls == "struct"}
    return "RAO" in names and "vessel" not in names


def read_force_rao(path: str | os.PathLike[str], *, axes: str = "z-down") -> xr.DataArray:
    """The force RAOs of an MSS ``RAO`` struct as an ``excitation_force`` DataArray.

    MSS writes such a struct (``RAO.Amp{1:6}``, ``RAO.Phase{1:6}``: Freq × Dir × Vel
    tables; ``RAO.Freq`` rad/s, ``RAO.Dir`` rad, ``RAO.Vel`` m/s; ``.m`` text twin "3D
    table of RAO Amplitudes (Freq, Dir, Vel)") when it processes VERES force RAOs
    (``input.re8``), with the conventions of its ``vessel.forceRAO``: complex value
    amp·e^{i·phase} for x(t) = Re{X e^{iωt}}, Fossen's z-down body axes, ``Dir`` the
    direction the waves travel relative to x (0 following, π head seas). Amplitudes are
    N/m and N·m/m (per metre of wave amplitude).

    Parameters
    ----------
    path
        The ``.mat`` file.
    axes
        ``"z-down"`` (as stored) or ``"z-up"`` (T = diag(1, −1, −1, 1, −1, −1), β → −β).

    Returns
    -------
    xarray.DataArray
        Complex, dims (forward_speed, omega, wave_direction, influenced_dof), DOFs
        ``Surge`` … ``Yaw``; attributes ``axis_convention``, ``units``, ``source_file``.

    Raises
    ------
    HydroDataError
        No RAO struct, wrong shapes, non-finite values.
    """
    from cummins.hydrodb import DOF_NAMES
    from cummins.kinematics import Z_UP_TO_Z_DOWN

    path = Path(path)
    rao = load_mat_struct(path, "RAO", "MSS RAO files hold a struct named RAO")
    where = "RAO"
    freq = _numeric(_field(rao, "Freq", path, where), path, "RAO.Freq").reshape(-1)
    heading = _numeric(_field(rao, "Dir", path, where), path, "RAO.Dir").reshape(-1)
    speed = _numeric(_field(rao, "Vel", path, where), path, "RAO.Vel").reshape(-1)
    amp = _cells(_field(rao, "Amp", path, where), path, "RAO.Amp")
    phase = _cells(_field(rao, "Phase", path, where), path, "RAO.Phase")
    if len(amp) != 6 or len(phase) != 6:
        raise HydroDataError(
            f"expected 6 amplitude and phase tables, found {len(amp)} and {len(phase)}",
            path=path,
            quantity="RAO.Amp, RAO.Phase",
        )
    for name, v in (("RAO.Freq", freq), ("RAO.Dir", heading), ("RAO.Vel", speed)):
        if v.size == 0 or not np.all(np.isfinite(v)):
            raise HydroDataError("empty or non-finite", path=path, quantity=name)
    if np.any(freq <= 0) or np.any(np.diff(freq) <= 0):
        raise HydroDataError(
            "frequencies must be positive and increasing", path=path, quantity="RAO.Freq"
        )
    shape = (freq.size, heading.size, speed.size)
    values = np.empty((speed.size, freq.size, heading.size, 6), dtype=complex)
    for k in range(6):
        a = amp[k].reshape(amp[k].shape + (1,) * (3 - amp[k].ndim))
        ph = phase[k].reshape(phase[k].shape + (1,) * (3 - phase[k].ndim))
        for label, arr in ((f"RAO.Amp{{{k + 1}}}", a), (f"RAO.Phase{{{k + 1}}}", ph)):
            if arr.shape != shape:
                raise HydroDataError(
                    f"has shape {arr.shape}, expected {shape} (Freq, Dir, Vel)",
                    path=path,
                    quantity=label,
                )
            if not np.all(np.isfinite(arr)):
                raise HydroDataError("non-finite value", path=path, quantity=label)
        values[..., k] = np.moveaxis(a * np.exp(1j * ph), 2, 0)
    beta = heading
    if axes == "z-up":
        values = values * np.asarray(Z_UP_TO_Z_DOWN)
        beta = np.mod(-heading, 2 * np.pi)
        beta[np.isclose(beta, 2 * np.pi)] = 0.0
        order = np.argsort(beta)
        beta, values = beta[order], values[:, :, order, :]
    elif axes != "z-down":
        raise HydroDataError(f"unknown axes {axes!r}", hint="use 'z-down' or 'z-up'")
    return xr.DataArray(
        values,
        dims=("forward_speed", "omega", "wave_direction", "influenced_dof"),
        coords={
            "forward_speed": ("forward_speed", speed, {"units": "m/s"}),
            "omega": ("omega", freq, {"units": "rad/s"}),
            "wave_direction": ("wave_direction", beta, {"units": "rad"}),
            "influenced_dof": list(DOF_NAMES),
        },
        name="excitation_force",
        attrs={
            "units": "N/m | N m/m (per metre of wave amplitude)",
            "axis_convention": axes,
            "time_convention": "x(t) = Re{X exp(i omega t)}",
            "source_file": str(path),
            "source_format": "mss-rao",
        },
    )
