"""The frequency-domain model: motion RAOs, response spectra and significant amplitudes.

For a harmonic wave of unit amplitude, frequency ω and direction β, with x(t) =
Re{X e^{iωt}}, the linear equation of motion (de Haan (2022) eqs. 2.3–2.4) is

    [−ω² (M_RB + A(ω) + A_add(ω)) + iω (B(ω) + B_add(ω) + B_v) + C + C_add] X = F(ω, β),

with M_RB the ``inertia_matrix``, A, B the ``added_mass`` and ``radiation_damping``,
A_add, B_add, C_add the ``additional_added_mass``, ``additional_damping`` and
``additional_stiffness`` of the dataset when present (``additional=False`` leaves them
out), C the ``hydrostatic_stiffness``, B_v a viscous damping matrix of one's own and F
the ``excitation_force``. X is the coupled motion RAO: m/m for translations, rad/m for
rotations, phase relative to the wave elevation at the origin; it is found by solving
the 6N × 6N system at each (ω, β) (never by inverting a matrix).

The RAO is computed, not interpolated: at frequencies between those of the data, A, B
and F are interpolated (they are smooth; :mod:`cummins.seakeeping.excitation` for F) and the
system is solved there. A lightly damped resonance (de Haan (2022) §3.1.2: roll, with a 180°
phase turn within one Δω of the database) is thereby resolved as finely as asked, which
no interpolation of the RAO itself can do.

**Forward speed.** For data at a forward speed U (a ``forward_speed`` coordinate, e.g. the
MSS S-175 from ShipX/VERES), the vessel meets a wave of frequency ω and direction β at
the encounter frequency ω_e = ω − k(ω) U cos β (Hjulstad (2004) §3; deep water k = ω²/g): the
excitation F(ω, β) is tabulated per *wave* frequency, while the radiation coefficients
A, B are functions of the frequency of the motion, ω_e. So the RAO at speed is

    [−ω_e² (M_RB + A(|ω_e|)) + iω_e B(|ω_e|) + C] X = F(ω, β),   x(t) = Re{X e^{iω_e t}}

(:func:`cummins.seakeeping.excitation.encounter_frequencies`). A negative ω_e (waves overtaking the
ship in following seas) is allowed: A and B are even in ω, so Z(−|ω_e|) is the conjugate
of Z(|ω_e|). Strip-theory tables at speed refer F (and their RAOs) to e^{i|ω_e|t}, i.e.
they hold the conjugate of F where ω_e < 0; cummins takes F̄ there
(:func:`cummins.seakeeping.excitation.encounter_excitation`), so that every RAO and every time
series refers to e^{iω_e t} and to the same wave phase. Checked against ShipX/VERES: the
S-175 heave and pitch RAOs of ``s175.mat`` at all 5 speeds and 36 headings are
reproduced, complex, within 0.85 % (heave) and 2.2 % (pitch) of their peaks (VERES' own
RAO conjugated where ω_e < 0; tests/test_encounter.py), where the same data solved at
ω are off by up to 68 %; taking F as printed for ω_e < 0 instead gives 3 % in heave.
Where |ω_e| lies outside the frequencies of the data (long waves in following seas,
short waves in head seas) A and B are held at the nearest data frequency, and the RAO
says so (attribute ``encounter_outside_data``). The response spectrum and the
significant amplitudes below stay on the wave-frequency axis: the variance is the same
on either axis.

**Joined bodies and PTOs** (``system``, :mod:`cummins.mechanics`): with the motions the
joints allow, ξ = T q, and each PTO's k d dᵀ and c d dᵀ added to Z, the RAO solves
Tᵀ Z(ω) T q = Tᵀ F and is X = T q, in the body DOFs that can move.

The response spectrum of DOF j to a wave spectrum S(ω) in one direction is
S_j(ω) = |X_j(ω, β)|² S(ω) (de Haan (2022) eq. 2.5); in a short-crested sea with spreading
D(θ), S_j(ω) = Σ_β w_β |X_j(ω, β)|² S(ω), w_β = ∫_bin D dθ. The significant amplitude is
2√m₀ (m₀ = ∫S_j dω), the single amplitude equivalent of H_s/2 for the waves: half the
significant double amplitude 4√m₀.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import (
    ArgumentError,
    HydroDataError,
    HydroDataWarning,
    StaticInstabilityWarning,
)
from cummins.hydrodb import dof_matrix, single_speed
from cummins.mechanics import MechanicalSystem, assemble
from cummins.restoring import (
    INSTABILITY_HINT,
    instability_message,
    restoring_matrix,
    static_instability,
    unrestrained_message,
    unrestrained_modes,
)
from cummins.seakeeping.excitation import (
    INTERPOLATION_METHODS,
    _interpolate_frequency,
    _where,
    encounter_excitation,
    encounter_frequencies,
    excitation_transfer,
    forward_speed,
)
from cummins.validation import check_memory, finite_values
from cummins.vessel import missing_data_message, viscous_damping_matrix

__all__ = [
    "impedance",
    "load_pto_rao",
    "load_rao",
    "motion_rao",
    "motion_transfer",
    "pto_rao",
    "response_spectrum",
    "save_rao",
    "significant_amplitude",
    "spectral_moment",
]

_RAO_UNITS = "m/m | rad/m (translation | rotation, per metre of wave amplitude)"


def _frequency_matrix(
    ds: xr.Dataset, name: str, omega: NDArray[np.float64], method: str
) -> NDArray[np.float64]:
    """``ds[name]`` (omega, i, j) at the frequencies ``omega`` (within the data's range)."""
    values = dof_matrix(ds, name)
    if "omega" not in ds[name].dims:  # one matrix at every frequency (external damping)
        return np.broadcast_to(values, (omega.size, *values.shape))
    w = ds.omega.values.astype(float)
    same = omega.size == w.size and np.array_equal(omega, w)
    if same:
        return values
    index = np.searchsorted(w, omega)
    exact = (index < w.size) & (w[np.minimum(index, w.size - 1)] == omega)
    out = np.empty((omega.size, *values.shape[1:]))
    out[exact] = values[index[exact]]
    if (~exact).any():
        interp = _interpolate_frequency(w, values.astype(complex), omega[~exact], method)
        out[~exact] = interp.real
    return out


def _outside_data(ds: xr.Dataset, omega: NDArray[np.float64]) -> NDArray[np.bool_]:
    """True where |ω| lies outside the data's frequencies (by more than 1e-9 of the last)."""
    data_w = ds.omega.values
    tol = 1e-9 * data_w[-1]
    w = np.abs(omega)
    return (w < data_w[0] - tol) | (w > data_w[-1] + tol)


def impedance(
    ds: xr.Dataset,
    omega: ArrayLike,
    *,
    viscous_damping: Any = None,
    additional: bool = True,
    method: str = "hermite",
    outside: str = "raise",
) -> NDArray[np.complex128]:
    """Z(ω) = −ω²(M_RB + A + A_add) + iω(B + B_add + B_v) + C + C_add, shape (n, N, N).

    Parameters
    ----------
    ds
        A ``HydroDB`` (one forward speed) with ``inertia_matrix`` and
        ``hydrostatic_stiffness``.
    omega
        Frequencies of the motion, rad/s, within the data's range (A and B are
        interpolated between the data frequencies, by ``method`` as in
        :func:`cummins.seakeeping.excitation.excitation_transfer`). A negative ω (an encounter
        frequency in following seas) takes A and B at |ω|: Z(−ω) is the conjugate of Z(ω).
    viscous_damping
        B_v: an (N, N) matrix, a DataArray with ``influenced_dof``/``radiating_dof``, or
        ``{dof: value}`` for a diagonal one (kg/s, kg·m²/s …); None for none.
    additional
        Include the dataset's ``additional_added_mass``, ``additional_damping`` and
        ``additional_stiffness`` (WAMIT external damping, MSS viscous damping, VERES roll
        damping, moorings).
    outside
        ``"raise"`` (default) for |ω| outside the data's frequencies; ``"hold"``: take A
        and B (and the additional terms) at the nearest data frequency there (the
        encounter frequencies of a ship at speed, :func:`motion_rao`).

    Raises
    ------
    HydroDataError
        Missing inertia or restoring, frequency outside the data.
    """
    ds = single_speed(ds)
    where = _where(ds)
    missing_data_message(ds, ("inertia_matrix", "hydrostatic_stiffness"), "computing the motions")
    if method not in INTERPOLATION_METHODS:
        raise ArgumentError(
            f"unknown method {method!r}; use one of {', '.join(INTERPOLATION_METHODS)}"
        )
    if outside not in ("raise", "hold"):
        raise ArgumentError(f"outside must be 'raise' or 'hold', not {outside!r}")
    w = np.asarray(omega, dtype=float).reshape(-1)
    data_w = ds.omega.values
    beyond = _outside_data(ds, w)
    if beyond.any() and outside == "raise":
        raise HydroDataError(
            f"frequency {w[beyond][0]:.6g} rad/s is outside the data's range "
            f"{data_w[0]:.6g} to {data_w[-1]:.6g} rad/s",
            path=where,
            hint="the added mass and damping are not known there: choose frequencies "
            "within that range",
        )
    at = np.clip(np.abs(w), data_w[0], data_w[-1])
    mass = dof_matrix(ds, "inertia_matrix")[None] + _frequency_matrix(ds, "added_mass", at, method)
    damping = _frequency_matrix(ds, "radiation_damping", at, method)
    stiffness = dof_matrix(ds, "hydrostatic_stiffness")
    if additional:
        if "additional_added_mass" in ds:
            mass = mass + _frequency_matrix(ds, "additional_added_mass", at, method)
        if "additional_damping" in ds:
            damping = damping + _frequency_matrix(ds, "additional_damping", at, method)
        if "additional_stiffness" in ds:
            stiffness = stiffness + dof_matrix(ds, "additional_stiffness")
    if viscous_damping is not None:
        labels = [str(d) for d in ds.influenced_dof.values]
        damping = damping + viscous_damping_matrix(labels, viscous_damping)[None]
    ww = w[:, None, None]
    return -(ww**2) * mass + 1j * ww * damping + stiffness[None]


def _solve(z: NDArray[np.complex128], f: NDArray[np.complex128], where, omega) -> NDArray:
    """Solve z[k] x[k] = f[k] for every k; HydroDataError naming a singular frequency."""
    try:
        return np.linalg.solve(z, f[..., None])[..., 0]
    except np.linalg.LinAlgError:
        for k in range(z.shape[0]):
            if np.linalg.matrix_rank(z[k]) < z.shape[-1]:
                raise HydroDataError(
                    f"the equation of motion is singular at omega = {omega[k]:.6g} rad/s",
                    path=where,
                    hint="a DOF has no mass, damping or restoring there; check inertia_matrix "
                    "and hydrostatic_stiffness, or add viscous damping",
                ) from None
        raise


def motion_transfer(
    ds: xr.Dataset,
    omega: ArrayLike,
    direction: ArrayLike,
    *,
    viscous_damping: Any = None,
    additional: bool = True,
    method: str = "hermite",
    mirror: bool | None = None,
    extrapolate: str = "raise",
) -> NDArray[np.complex128]:
    """Motion RAOs at pairs (ω_k, β_k): solve the equation of motion at each, shape (n, N).

    The frequency-domain counterpart of a time-domain run in the same sea:
    ``cummins.seakeeping.excitation.wave_response(waves, motion_transfer(ds, waves.omega,
    waves.direction), t)`` is the steady-state linear motion (m, rad); at a forward
    speed the motion oscillates at the encounter frequencies: pass
    ``cummins.seakeeping.excitation.encounter_frequencies(ds, waves.omega, waves.direction)`` as
    ``wave_response``'s fourth argument (module docstring). Arguments as
    :func:`motion_rao` and :func:`cummins.seakeeping.excitation.excitation_transfer`; with
    ``extrapolate="zero"`` the RAO is 0 at frequencies outside the data.
    """
    ds = single_speed(ds)
    w = np.asarray(omega, dtype=float).reshape(-1)
    beta = np.broadcast_to(np.asarray(direction, dtype=float), np.shape(omega)).reshape(-1)
    force = excitation_transfer(ds, w, beta, extrapolate=extrapolate, method=method, mirror=mirror)
    out = np.zeros_like(force)
    inside = ~_outside_data(ds, w)
    if inside.any():
        moving = forward_speed(ds) != 0.0
        we = encounter_frequencies(ds, w[inside], beta[inside])
        force[inside] = encounter_excitation(force[inside], we)
        z = impedance(
            ds,
            we,
            viscous_damping=viscous_damping,
            additional=additional,
            method=method,
            outside="hold" if moving else "raise",
        )
        out[inside] = _solve(z, force[inside], _where(ds), we)
    return out


def motion_rao(
    ds: xr.Dataset,
    omega: ArrayLike | None = None,
    wave_direction: ArrayLike | None = None,
    *,
    viscous_damping: Any = None,
    additional: bool = True,
    method: str = "hermite",
    mirror: bool | None = None,
    system: MechanicalSystem | None = None,
) -> xr.DataArray:
    """Coupled motion RAOs X(ω, β) per metre of wave amplitude (module docstring).

    Parameters
    ----------
    ds
        A ``HydroDB`` (one forward speed) with ``inertia_matrix``,
        ``hydrostatic_stiffness`` and ``excitation_force``.
    omega
        Frequencies, rad/s (default: the data's). Between the data frequencies A, B and
        F are interpolated and the equation solved there; outside the range: error.
    wave_direction
        Directions of wave travel, rad (default: the data's; others are interpolated,
        mirrored for port/starboard symmetric bodies, see
        :func:`cummins.seakeeping.excitation.excitation_transfer`).
    viscous_damping
        Extra linear damping B_v: (N, N) matrix, DataArray, or ``{dof: value}``.
    additional
        Include the dataset's additional added mass, damping and stiffness.
    method
        Frequency interpolation of A, B and F (``"hermite"`` default).
    mirror
        Port/starboard mirroring of the headings (None: decide from the data).
    system
        Joints, PTOs, the DOFs that move and the body coupling
        (:class:`cummins.mechanics.MechanicalSystem`): the RAO solves Tᵀ Z T q = Tᵀ F
        with the PTOs' stiffness and damping in Z, X = T q over the DOFs that can move;
        ``viscous_damping`` is then over those DOFs. The PTOs' response:
        :func:`pto_rao`.

    Returns
    -------
    xarray.DataArray
        ``rao``, complex, dims (omega, wave_direction, dof), m/m and rad/m, phase
        relative to the wave elevation at the origin (x(t) = Re{X e^{iωt}}). At a
        forward speed: the coordinate ``encounter_frequency`` (omega, wave_direction),
        x(t) = Re{X e^{iω_e t}} at the origin moving with the ship, and the attributes
        ``forward_speed`` and ``encounter_outside_data`` (module docstring).

    Warns
    -----
    StaticInstabilityWarning
        The restoring (with the additional stiffness) has a negative eigenvalue: the body
        has no equilibrium, its RAOs mean nothing; the RAO's attribute
        ``static_stability`` says it too (:func:`cummins.restoring.static_instability`,
        the check the time domain refuses such a body with).

    Raises
    ------
    HydroDataError
        No inertia, restoring or excitation; frequency out of range; direction in a gap
        of the headings; singular system.

    Examples
    --------
    >>> import cummins
    >>> from cummins.seakeeping.frequency_domain import motion_rao
    >>> rao = motion_rao(cummins.demo_dataset(), wave_direction=[3.141592653589793])
    >>> round(float(abs(rao.sel(dof="Heave")[0, 0])), 3)   # long waves: heave follows them
    1.0
    """
    ds = single_speed(ds)
    assembly = None if system is None else assemble(ds, system)
    if assembly is not None:
        ds = assembly.ds
    w = ds.omega.values.astype(float) if omega is None else np.asarray(omega, float).reshape(-1)
    if wave_direction is None:
        if "wave_direction" not in ds.dims:
            raise HydroDataError("the dataset has no wave directions", path=_where(ds))
        beta = ds.wave_direction.values.astype(float)
    else:
        beta = np.asarray(wave_direction, dtype=float).reshape(-1)
    if w.size == 0 or beta.size == 0:
        raise ArgumentError("no frequencies or no directions asked for")
    finite_values(w, "omega", "rad/s")
    finite_values(beta, "wave_direction", "rad")
    n_dofs = ds.sizes["influenced_dof"]
    check_memory(
        w.size * beta.size * (n_dofs * n_dofs * 16 * 4 + n_dofs * 16 * 3),
        f"RAOs at {w.size} frequencies x {beta.size} directions ({n_dofs} DOFs)",
        hint="Ask for fewer frequencies (--n-omega) or headings",
    )
    ww, bb = np.meshgrid(w, beta, indexing="ij")
    force = excitation_transfer(
        ds, ww.reshape(-1), bb.reshape(-1), method=method, mirror=mirror
    ).reshape(w.size, beta.size, -1)
    speed = forward_speed(ds)
    options = {"viscous_damping": viscous_damping, "additional": additional, "method": method}
    basis = None
    if assembly is not None and assembly.is_constrained:
        basis = assembly.basis
    if speed == 0.0:
        z = _with_ptos(impedance(ds, w, **options), w, assembly)
        zq, fq = _project(z, force, basis)
        try:
            x = np.linalg.solve(zq[:, None], fq[..., None])[..., 0]
        except np.linalg.LinAlgError:
            x = np.stack([_solve(zq, fq[:, j], _where(ds), w) for j in range(beta.size)], 1)
    else:
        we = encounter_frequencies(ds, ww, bb)
        force = encounter_excitation(force, we)
        z = impedance(ds, we.reshape(-1), outside="hold", **options)
        z = _with_ptos(z, we.reshape(-1), assembly)
        n = force.shape[-1]
        zq, fq = _project(z, force.reshape(-1, n), basis)
        x = _solve(zq, fq, _where(ds), we.reshape(-1))
        x = x.reshape(*force.shape[:-1], x.shape[-1])
    if basis is not None:
        x = x @ basis.T
    labels = [str(d) for d in ds.influenced_dof.values]
    included = ["inertia_matrix", "added_mass", "radiation_damping", "hydrostatic_stiffness"]
    if additional:
        included += [
            v
            for v in ("additional_added_mass", "additional_damping", "additional_stiffness")
            if v in ds
        ]
    if viscous_damping is not None:
        included.append("viscous_damping (given)")
    attrs = {}
    if assembly is not None:
        if assembly.ptos:
            included.append("PTO stiffness and damping")
        if basis is not None:
            included.append("joints (T^T Z T q = T^T F, X = T q)")
        attrs.update(assembly.attrs())
    c = restoring_matrix(ds, additional)
    if assembly is not None and assembly.ptos:
        c = c + assembly.pto_matrices()[0]
    loose = unrestrained_modes(c, labels)
    if loose:
        attrs["unrestrained_modes"] = unrestrained_message(loose)
        warnings.warn(attrs["unrestrained_modes"], HydroDataWarning, stacklevel=2)
    unstable = static_instability(c, labels, basis)
    if unstable:  # the same sentence the time domain refuses with (Vessel.stability)
        attrs["static_stability"] = instability_message(unstable)
        warnings.warn(
            StaticInstabilityWarning(f"{attrs['static_stability']}. {INSTABILITY_HINT}"),
            stacklevel=2,
        )
    coords = {}
    if speed != 0.0:
        data_w = ds.omega.values
        held = _outside_data(ds, we)
        slow = np.abs(we) < data_w[0]
        free = [label for k, label in enumerate(labels) if c[k, k] <= 0.0]
        if slow.any() and free:
            warnings.warn(
                f"at {int(slow.sum())} (omega, wave_direction) pairs the encounter frequency "
                f"is below the data's lowest, {data_w[0]:.4g} rad/s (following seas, "
                f"omega_e near 0): {', '.join(free)} have no restoring, so their linear "
                "response grows without limit as omega_e -> 0; their RAOs there are not "
                "meaningful (A and B are held at the lowest data frequency)",
                HydroDataWarning,
                stacklevel=2,
            )
        attrs |= {
            "forward_speed": speed,
            "encounter_outside_data": int(held.sum()),
            "encounter_note": "x(t) = Re{X exp(i omega_e t)}, omega_e the encounter frequency; "
            f"A and B held at the nearest data frequency for {int(held.sum())} of "
            f"{held.size} (omega, wave_direction) pairs whose |omega_e| is outside "
            f"{data_w[0]:.4g} to {data_w[-1]:.4g} rad/s",
        }
        coords["encounter_frequency"] = (
            ("omega", "wave_direction"),
            we,
            {"units": "rad/s", "long_name": "encounter frequency (signed)"},
        )
    return xr.DataArray(
        x,
        dims=("omega", "wave_direction", "dof"),
        coords={
            "omega": ("omega", w, {"units": "rad/s", "long_name": "wave frequency"}),
            "wave_direction": (
                "wave_direction",
                beta,
                {"units": "rad", "long_name": "direction of wave propagation (0 = along +x)"},
            ),
            "dof": ("dof", labels),
            **coords,
        },
        name="rao",
        attrs={
            "units": _RAO_UNITS,
            "long_name": "coupled motion RAO per metre of wave amplitude",
            "time_convention": "x(t) = Re{X exp(i omega t)}",
            "phase_reference": "incident wave elevation at the origin (0, 0)",
            "terms": ", ".join(included),
            "axis_convention": ds.attrs.get("axis_convention", "z-up"),
            "reference_point": np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0))),
            "interpolation": method,
            "source_file": str(ds.attrs.get("source_file", "")),
            **attrs,
        },
    )


def _with_ptos(z: NDArray, omega: NDArray, assembly) -> NDArray:
    """Z + C_pto + iω B_pto (Z unchanged without PTOs)."""
    if assembly is None or not assembly.ptos:
        return z
    stiffness, damping = assembly.pto_matrices()
    return z + stiffness + 1j * np.asarray(omega)[:, None, None] * damping


def _project(z: NDArray, force: NDArray, basis) -> tuple[NDArray, NDArray]:
    """(TᵀZT, TᵀF) for Z (k, n, n) and F (k, …, n); unchanged without joints."""
    if basis is None:
        return z, force
    return basis.T @ z @ basis, force @ basis


def pto_rao(rao: xr.DataArray, ds: xr.Dataset, system: MechanicalSystem) -> xr.Dataset:
    """The PTOs' response per metre of wave amplitude, from a :func:`motion_rao` of the
    same data and system.

    Returns
    -------
    xarray.Dataset
        ``pto_displacement`` Δ̂ = dᵀX (complex, m/m or rad/m), ``pto_force`` −(k + iωc)Δ̂
        (complex, N/m or N·m/m, on the PTO's first body) and ``pto_power`` ½ c ω² |Δ̂|²,
        the mean power absorbed in a regular wave of unit amplitude (W/m²; times the
        amplitude squared in a wave of amplitude a), dims (omega, wave_direction, pto).
        At a forward speed ω is the encounter frequency.
    """
    from cummins.mechanics import pto_frequency_response

    assembly = assemble(single_speed(ds), system)
    if not assembly.ptos:
        raise ArgumentError("the system has no PTO")
    lines = [line.on([str(d) for d in rao.dof.values], assembly.dofs) for line in assembly.ptos]
    if "encounter_frequency" in rao.coords:
        w = rao.encounter_frequency.values
    else:
        w = rao.omega.values[:, None] * np.ones(rao.sizes["wave_direction"])
    x = rao.transpose("omega", "wave_direction", "dof").values
    out = pto_frequency_response(lines, w, x)
    dims = ("omega", "wave_direction", "pto")
    units = [line.units for line in lines]

    def unit(key: str, per: str) -> str:
        return " | ".join(dict.fromkeys(f"{u[key]}{per}" for u in units))

    coords = {
        "omega": rao.omega,
        "wave_direction": rao.wave_direction,
        "pto": ("pto", [line.name for line in lines]),
    }
    result = xr.Dataset(
        {
            "pto_displacement": (
                dims,
                out["displacement"],
                {"units": unit("displacement", "/m"), "long_name": "PTO relative displacement RAO"},
            ),
            "pto_force": (
                dims,
                out["force"],
                {"units": unit("force", "/m"), "long_name": "PTO force RAO, -(k + i omega c) x"},
            ),
            "pto_power": (
                dims,
                out["power"],
                {
                    "units": "W/m^2",
                    "long_name": "mean absorbed power per unit wave amplitude squared, "
                    "0.5 c omega^2 |x|^2",
                },
            ),
        },
        coords=coords,
    )
    result.pto.attrs["description"] = "\n".join(f"{p.name}: {p.description}" for p in lines)
    return result


# --------------------------------------------------------------------------- spectra


def _spectrum_on(omega: NDArray, spectrum_values: ArrayLike | Callable) -> NDArray:
    if callable(spectrum_values):
        values = np.asarray(spectrum_values(omega), dtype=float)
    else:
        values = np.asarray(spectrum_values, dtype=float).reshape(-1)
    if values.shape != omega.shape:
        raise ArgumentError(
            f"spectrum values have shape {values.shape}, the RAO has {omega.size} frequencies"
        )
    if not np.all(np.isfinite(values)) or np.any(values < 0):
        raise ArgumentError("spectrum values must be finite and non-negative")
    return values


def response_spectrum(
    rao: xr.DataArray,
    spectrum_values: ArrayLike | Callable,
    *,
    direction_weights: ArrayLike | None = None,
) -> xr.DataArray:
    """Response spectra S_j(ω) = |X_j(ω)|² S(ω), dims (omega, dof).

    Parameters
    ----------
    rao
        From :func:`motion_rao`: dims (omega, dof) or (omega, wave_direction, dof).
    spectrum_values
        S(ω) at ``rao.omega`` (m²·s/rad), or a callable S(ω) such as
        :func:`cummins.seakeeping.waves.wave_spectrum`.
    direction_weights
        Short-crested sea: w_β ≥ 0 for each ``rao.wave_direction``, summing to 1 (e.g.
        :func:`cummins.seakeeping.waves.spreading_weights`); S_j = Σ_β w_β |X_j(ω, β)|² S(ω).
        Without
        it the RAO must hold one direction.

    Returns
    -------
    xarray.DataArray
        ``response_spectrum``, m²·s/rad for translations, rad²·s/rad for rotations.
    """
    omega = rao.omega.values.astype(float)
    s = _spectrum_on(omega, spectrum_values)
    power = np.abs(rao) ** 2
    if "wave_direction" in rao.dims:
        n = rao.sizes["wave_direction"]
        if direction_weights is None:
            if n != 1:
                raise ArgumentError(
                    f"the RAO holds {n} wave directions: select one "
                    "(rao.sel(wave_direction=...)) or give direction_weights"
                )
            power = power.isel(wave_direction=0, drop=True)
        else:
            wts = np.asarray(direction_weights, dtype=float).reshape(-1)
            if wts.size != n or np.any(wts < 0) or not np.isclose(wts.sum(), 1.0, atol=1e-6):
                raise ArgumentError(
                    f"direction_weights must be {n} non-negative numbers summing to 1"
                )
            power = (power * xr.DataArray(wts, dims="wave_direction")).sum("wave_direction")
    elif direction_weights is not None:
        raise ArgumentError("direction_weights given but the RAO has no wave_direction dimension")
    out = (power * xr.DataArray(s, dims="omega", coords={"omega": rao.omega})).transpose(
        "omega", ...
    )
    out.name = "response_spectrum"
    out.attrs = {
        "units": "m^2 s/rad | rad^2 s/rad (translation | rotation)",
        "long_name": "response spectrum |RAO|^2 S(omega)",
    }
    return out


def spectral_moment(response_spectrum: xr.DataArray, order: int = 0) -> xr.DataArray:
    """m_n = ∫ ωⁿ S(ω) dω by the trapezoidal rule on the spectrum's frequencies, dims (dof)."""
    w = response_spectrum.omega
    return (response_spectrum * w**order).integrate("omega")


def significant_amplitude(response_spectrum: xr.DataArray) -> xr.DataArray:
    """Significant (single) amplitude 2√m₀ of each response, dims (dof): m or rad.

    m₀ = ∫ S_j(ω) dω (trapezoidal rule on the spectrum's frequencies: compute the RAO
    on a grid fine enough for its peaks, which :func:`motion_rao` can do). 2√m₀ is the
    single-amplitude counterpart of H_s/2 for the waves (the significant double
    amplitude, crest to trough, is 4√m₀).
    """
    out = 2.0 * np.sqrt(spectral_moment(response_spectrum, 0))
    out.name = "significant_amplitude"
    out.attrs = {
        "units": "m | rad (translation | rotation)",
        "long_name": "significant single amplitude 2 sqrt(m0)",
    }
    return out


# --------------------------------------------------------------------------- figure


# --------------------------------------------------------------------------- files


def save_rao(rao: xr.DataArray, path, *, force: bool = False, pto: xr.Dataset | None = None):
    """Write a RAO from :func:`motion_rao` (and the PTOs' response, :func:`pto_rao`, as
    ``pto_*`` variables on a ``pto`` dimension) to NetCDF-4 in Capytaine's layout.

    As every NetCDF file cummins writes (:mod:`cummins.io.netcdf`): the complex values
    are conjugated to Capytaine's time convention x(t) = Re{X e^{−iωt}} and split along a
    leading dimension ``complex`` (``re``, ``im``), so ``xarray.open_dataset`` and
    Capytaine's ``merge_complex_values`` read them; the attribute ``time_convention``
    says so. :func:`load_rao` gives back the RAO in cummins' convention.
    """
    from cummins.errors import check_writable
    from cummins.io.netcdf import FILE_TIME_CONVENTION, encode_attributes, save_netcdf

    check_writable(path, force)
    value = np.conj(rao.transpose("omega", "wave_direction", "dof").values)
    attrs = dict(rao.attrs)
    attrs["time_convention"] = FILE_TIME_CONVENTION
    out = xr.Dataset(
        {
            "rao": xr.DataArray(
                np.stack([value.real, value.imag]),
                dims=("complex", "omega", "wave_direction", "dof"),
                attrs=encode_attributes(attrs),
            )
        },
        coords={
            "complex": ("complex", ["re", "im"]),
            "omega": ("omega", rao.omega.values, dict(rao.omega.attrs)),
            "wave_direction": (
                "wave_direction",
                rao.wave_direction.values,
                {
                    **rao.wave_direction.attrs,
                    "degrees": np.degrees(rao.wave_direction.values),
                },
            ),
            "dof": ("dof", [str(d) for d in rao.dof.values]),
        },
    )
    if pto is not None:
        for name, var in pto.data_vars.items():
            values = var.transpose("omega", "wave_direction", "pto").values
            if np.iscomplexobj(values):
                values = np.conj(values)
                out[name] = (
                    ("complex", "omega", "wave_direction", "pto"),
                    np.stack([values.real, values.imag]),
                    encode_attributes(dict(var.attrs)),
                )
            else:
                out[name] = (("omega", "wave_direction", "pto"), values, dict(var.attrs))
        out = out.assign_coords(pto=("pto", [str(p) for p in pto.pto.values], dict(pto.pto.attrs)))
    out.attrs = encode_attributes(
        {
            "title": "cummins motion RAO",
            "time_convention": FILE_TIME_CONVENTION,  # the file's, said on the file too
            **_version_attr(),
        }
    )
    return save_netcdf(out, path)


def _version_attr() -> dict[str, str]:
    from cummins._version import __version__

    return {"cummins_version": __version__}


def load_rao(path) -> xr.DataArray:
    """Read a file written by :func:`save_rao` (cummins' convention x(t) = Re{X e^{iωt}})."""
    from cummins.io.netcdf import CANONICAL_TIME_CONVENTION, decode_attributes

    try:
        with xr.open_dataset(path, engine="h5netcdf") as f:
            raw = f.load()
    except (OSError, ValueError) as exc:
        raise HydroDataError(f"cannot read the RAO file ({exc})", path=path) from None
    if "rao" not in raw or "complex" not in raw["rao"].dims:
        raise HydroDataError("no complex 'rao' variable in the file", path=path)
    var = raw["rao"]
    value = var.sel(complex="re").values + 1j * var.sel(complex="im").values
    attrs = decode_attributes(var.attrs, where=path)
    attrs["time_convention"] = CANONICAL_TIME_CONVENTION
    dims = tuple(d for d in var.dims if d != "complex")
    coords = {d: (d, raw[d].values, dict(raw[d].attrs)) for d in dims}
    coords["wave_direction"][2].pop("degrees", None)
    return xr.DataArray(np.conj(value), dims=dims, coords=coords, name="rao", attrs=attrs)


def load_pto_rao(path) -> xr.Dataset:
    """The PTOs' response of a file written by :func:`save_rao` with ``pto`` (cummins'
    convention x(t) = Re{X e^{iωt}})."""
    try:
        with xr.open_dataset(path, engine="h5netcdf") as f:
            raw = f.load()
    except (OSError, ValueError) as exc:
        raise HydroDataError(f"cannot read the RAO file ({exc})", path=path) from None
    names = [n for n in raw.data_vars if str(n).startswith("pto_")]
    if not names:
        raise HydroDataError("no PTO variables (pto_*) in the file", path=path)
    out = {}
    for name in names:
        var = raw[name]
        if "complex" in var.dims:
            value = var.sel(complex="re").values + 1j * var.sel(complex="im").values
            out[name] = (tuple(d for d in var.dims if d != "complex"), np.conj(value), var.attrs)
        else:
            out[name] = var.drop_vars("complex", errors="ignore")
    return xr.Dataset(out).drop_vars("complex", errors="ignore")
