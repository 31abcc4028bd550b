"""Plausibility checks on the data of a Capytaine file: damaged numbers, conventions.

A NetCDF file holds no checksum of its own (NetCDF-3) and a damaged number reads like any
other: these checks refuse what no solver writes (a NaN or infinite coordinate, a value
beyond :data:`IMPLAUSIBLE`, ``freq``/``period`` that disagree with ω, an unknown incident
wave convention) and warn about what is used all the same (an excitation force that is not
Froude-Krylov + diffraction, NaN in part of a frequency's results, an unusual ρ or g).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.io._common import warn_damage

#: No added mass, damping, force or stiffness of a floating body reaches this (SI units);
#: a larger value is a damaged number (a flipped exponent byte gives ~1e300).
IMPLAUSIBLE = 1e25


def _check_incoming_wave_convention(raw: xr.Dataset, where, lines: list[str]) -> None:
    """Capytaine 1.x recorded ``incoming_waves_convention``; only ``Nemoh`` (its default,
    the incident potential of Capytaine >= 1.2 and of this reader) is understood."""
    value = raw.attrs.get("incoming_waves_convention")
    if value is None:
        return
    if str(value).strip().lower() != "nemoh":
        raise HydroDataError(
            f"incoming_waves_convention = {value!r}: only Capytaine's 'Nemoh' convention "
            "(its default, the one of Capytaine >= 1.2) is supported",
            path=where,
            hint="recompute the excitation with the default convention",
        )
    lines.append(
        "incoming_waves_convention = Nemoh (Capytaine 1.x): the incident potential of "
        "Capytaine >= 1.2, read as such"
    )


_COORDINATE_NAMES = (
    "wave_direction",
    "rotation_center",
    "center_of_mass",
    "center_of_buoyancy",
    "forward_speed",
)


def _check_coordinates(raw: xr.Dataset, where) -> None:
    """A NaN or infinite coordinate is an error naming it (omega = inf is a limit row)."""
    for name in _COORDINATE_NAMES:
        if name not in raw.variables:
            continue
        values = np.asarray(raw[name].values)
        if values.dtype.kind not in "fiu":
            continue
        values = values.astype(float)
        if not np.all(np.isfinite(values)):
            bad = values.reshape(-1)[~np.isfinite(values.reshape(-1))][0]
            raise HydroDataError(
                f"the coordinate {name} holds {bad!r}",
                path=where,
                hint="every coordinate must be a finite number; the file is damaged",
            )
    if "wave_direction" in raw.variables:
        beta = np.asarray(raw["wave_direction"].values, dtype=float).reshape(-1)
        if np.any(np.abs(beta) > 4 * np.pi):
            raise HydroDataError(
                f"wave_direction {beta[np.abs(beta) > 4 * np.pi][0]!r} rad is not an angle "
                "Capytaine writes (|beta| <= 2 pi)",
                path=where,
                hint="the file is damaged, or holds degrees: Capytaine stores radians",
            )
        if np.unique(beta).size != beta.size:
            raise HydroDataError(
                "a wave direction appears twice",
                path=where,
                quantity=f"wave_direction = {np.round(beta, 6).tolist()} rad",
            )
    omega = np.asarray(raw["omega"].values, dtype=float)
    with np.errstate(invalid="ignore"):
        bad = np.isnan(omega) | ((omega > IMPLAUSIBLE) & np.isfinite(omega))
    if bad.any():
        raise HydroDataError(
            "the coordinate omega holds NaN or a value beyond any wave frequency "
            "(omega = inf, Capytaine's infinite-frequency limit, is allowed)",
            path=where,
            quantity=f"omega = {omega[bad][:4].tolist()}",
        )


def _check_derived_frequencies(raw: xr.Dataset, where) -> None:
    """Capytaine stores freq = omega/2 pi and period = 2 pi/omega beside omega: they must
    agree (to rounding), or omega (or they) were damaged."""
    omega = np.asarray(raw["omega"].values, dtype=float)
    finite = np.isfinite(omega) & (omega > 0)
    for name, expected in (("freq", omega / (2 * np.pi)), ("period", None)):
        if name not in raw.coords or raw[name].dims != ("omega",):
            continue
        values = np.asarray(raw[name].values, dtype=float)
        if expected is None:
            with np.errstate(divide="ignore"):
                expected = 2 * np.pi / omega
        with np.errstate(invalid="ignore"):
            off = ~np.isclose(values[finite], expected[finite], rtol=1e-12, atol=0.0)
        if off.any():
            k = int(np.flatnonzero(finite)[np.flatnonzero(off)[0]])
            raise HydroDataError(
                f"omega[{k}] = {omega[k]!r} rad/s disagrees with {name}[{k}] = {values[k]!r} "
                "(Capytaine writes both from the same frequency)",
                path=where,
                hint="the file is damaged; write it again from the solver",
            )


def _check_constants(rho: float, g: float, where, notes: list[str]) -> None:
    """Warn about a density or gravity no sea-keeping computation uses."""
    if not 9.7 <= g <= 9.9:
        warn_damage(
            f"g = {g!r} m/s^2 is not the acceleration of gravity on Earth (9.78-9.83)",
            path=where,
            notes=notes,
            hint="check the file; the data are used as they are",
        )
    if not 900.0 <= rho <= 1100.0:
        warn_damage(
            f"rho = {rho!r} kg/m^3 is not the density of water",
            path=where,
            notes=notes,
            hint="check the file; the data are used as they are",
        )


def _check_magnitude(arr: xr.DataArray, where) -> None:
    """HydroDataError for a value no physical body has (a damaged number)."""
    values = np.abs(np.asarray(arr.values))
    with np.errstate(invalid="ignore"):
        bad = values > IMPLAUSIBLE
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        raise HydroDataError(
            f"{arr.name} holds {np.asarray(arr.values)[index]!r}, beyond any physical value "
            f"(> {IMPLAUSIBLE:g} in SI units)",
            path=where,
            quantity=_element(arr, index),
            hint="the file is damaged; write it again from the solver",
        )


def _element(arr: xr.DataArray, index: Sequence[int]) -> str:
    parts = []
    for dim, i in zip(arr.dims, index, strict=True):
        value = arr[dim].values[i] if dim in arr.coords else i
        if dim == "omega":
            parts.append(f"omega={float(value):.6g} rad/s")
        elif dim == "wave_direction":
            parts.append(f"wave_direction={np.degrees(float(value)):.6g} deg")
        else:
            parts.append(str(value))
    return f"{arr.name}[{', '.join(parts)}]"


def _check_excitation_sum(arrays: dict, where, notes: list[str]) -> None:
    """Capytaine writes excitation_force as Froude_Krylov_force + diffraction_force,
    computed in double precision: the three must agree to rounding, NaN where NaN."""
    exc = arrays["excitation_force"]
    fk, dif = arrays["Froude_Krylov_force"], arrays["diffraction_force"]
    e, a, b = (np.asarray(x.values) for x in (exc, fk, dif))
    eps = np.finfo(np.asarray(e).real.dtype if e.dtype.kind == "c" else e.dtype).eps
    total = a + b
    nan_e, nan_s = np.isnan(e), np.isnan(total)
    with np.errstate(invalid="ignore"):
        off = np.abs(e - total) > 4 * eps * (np.abs(a) + np.abs(b))
    bad = (nan_e != nan_s) | (off & ~nan_e & ~nan_s)
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        warn_damage(
            f"excitation_force differs from Froude_Krylov_force + diffraction_force at "
            f"{int(bad.sum())} values, first {_element(exc, index)} = {e[index]!r}, sum "
            f"{total[index]!r}: one of the three is damaged; excitation_force is used as stored",
            path=where,
            notes=notes,
            hint="Capytaine writes their sum exactly; write the file again from the solver",
        )


def _nan_frequencies(arrays: dict, omega: np.ndarray, where, notes: list[str]):
    """Frequencies Capytaine could not solve (every value of a variable NaN there), and
    frequencies where only some values are NaN (damage: warned, dropped)."""
    unsolved = np.zeros(omega.size, dtype=bool)
    damaged = np.zeros(omega.size, dtype=bool)
    first: tuple[str, float] | None = None
    for name, arr in arrays.items():
        if "omega" not in arr.dims:
            continue
        nan = np.isnan(np.asarray(arr.values)).reshape(omega.size, -1)
        whole = nan.all(axis=1)
        partial = nan.any(axis=1) & ~whole
        unsolved |= whole
        if partial.any() and first is None:
            first = (name, float(omega[np.flatnonzero(partial)[0]]))
        damaged |= partial
    damaged &= ~unsolved
    if damaged.any():
        name, w = first if first is not None else ("data", float(omega[damaged][0]))
        listed = ", ".join(f"{x:.6g}" for x in omega[damaged][:8])
        warn_damage(
            f"{name} has NaN in some but not all values at omega = {w:.6g} rad/s (Capytaine "
            f"writes NaN for a whole problem it could not solve): {int(damaged.sum())} "
            f"frequenc{'y' if damaged.sum() == 1 else 'ies'} left out (omega = {listed} rad/s)",
            path=where,
            notes=notes,
            hint="the file is damaged; write it again from the solver",
        )
    return unsolved, damaged
