"""First-order wave excitation: transfer functions at any frequency and heading, and τ(t).

The first-order wave force on a body in a sea of harmonic components (de Haan (2022) §1.9,
Smogeli et al. (2004) §5; x(t) = Re{X e^{iωt}}) is

    τ(t) = Σ_k a_k Re{F(ω_k, β_k) e^{i(ω_k t + φ_k)}},

with F the ``excitation_force`` of a ``HydroDB`` (N/m, N·m/m per metre of wave amplitude,
phase relative to the incident elevation at the origin (0, 0)) and a_k, φ_k, ω_k, β_k
the components of :class:`cummins.seakeeping.waves.WaveComponents` (phase at the origin).

Interpolation (:func:`excitation_transfer`)
--------------------------------------------
The components' frequencies and directions are not those of the database, so F is
interpolated. De Haan (2022) §3.1.2 shows that a *sharply peaked* transfer function (its
roll RAO, with a 180° phase turn within one Δω) cannot be interpolated safely either as
amplitude and phase (the phase goes the wrong way round) or in the complex plane (the
amplitude dips to ~0 between two large values). cummins therefore never interpolates the
motion RAO: :mod:`cummins.seakeeping.frequency_domain` solves the equation of motion at the new
frequencies with interpolated A(ω), B(ω) and F(ω), which are smooth. What remains is to
interpolate F well:

1. **Travel phase removed.** The excitation of a body centred at (x_c, y_c) lags the
   elevation at the origin by k(ω)·ℓ(β), ℓ = x_c cos β + y_c sin β (k from the dispersion
   relation, with the dataset's g and water depth). G(ω, β) = F e^{+ik ℓ} is slowly
   varying; F is rebuilt as G e^{−ikℓ} at the new (ω, β). The centre is the body's centre
   of buoyancy (``center_of_buoyancy`` attribute), else its ``reference_point``
   (``phase_center=`` overrides: a point, or ``"origin"`` for no removal).
2. **Frequency**: the real and imaginary parts of G are interpolated separately, by a
   local cubic Hermite interpolant whose slopes are the second-order (three-point,
   non-uniform) finite differences of the data (``method="hermite"``, default). It is
   exact at the data, third-order accurate where the data resolve F, and local (a spike
   at an irregular frequency disturbs two intervals, not the whole curve as a global
   spline would). Interpolating real and imaginary parts passes a zero of F correctly,
   unlike amplitude/phase interpolation; the phase rotation that makes plain complex
   interpolation cut corners has been removed in step 1. Leave-one-out errors on the
   tanker (WAMIT, 58 frequencies), median over all headings and DOFs, as a fraction of
   max_ω |F|: 1.4e-5 in the lower half of the frequencies (PCHIP 2.2e-4, linear 1.3e-3,
   global cubic spline 4.5e-6 but 2.1 at worst where it overshoots). ``method=``
   ``"pchip"``, ``"linear"``, ``"cubic"`` (not-a-knot spline), ``"akima"`` (modified
   Akima) or ``"amplitude-phase"`` (PCHIP on |G|, linear on its unwrapped phase; the
   best of them for an isolated resonance, the worst near zeros) can be chosen;
   :func:`leave_one_out_error` measures them on any dataset.
3. **Heading**: periodic over 2π; when the data cover only one half-plane and the body is
   port/starboard symmetric (judged from the data, or ``mirror=True``), the other half is
   mirrored; a periodic cubic spline on the circle of available headings, and a direction
   in a gap wider than ``max_heading_gap`` is an error that names it
   (:mod:`cummins.seakeeping.headings`).

Outside the frequency range of the data the force is not known: a
:class:`~cummins.errors.HydroDataError` names the frequency and the range, unless
``extrapolate="zero"`` is asked for (the force is then 0 there).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import (
    Akima1DInterpolator,
    CubicHermiteSpline,
    CubicSpline,
    PchipInterpolator,
)

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES, bodies, single_speed, split_dof, water_depth
from cummins.seakeeping.headings import (
    MIRROR_SIGNS,
    HeadingCoverage,
    _heading_weights,
    _where,
    heading_coverage,
)
from cummins.seakeeping.headings import SYMMETRY_TOLERANCE as SYMMETRY_TOLERANCE
from cummins.seakeeping.headings import symmetry_evidence as symmetry_evidence
from cummins.seakeeping.waves import WaveComponents, harmonic_sum, wavenumber

__all__ = [
    "FORCE_VARIABLES",
    "INTERPOLATION_METHODS",
    "HeadingCoverage",
    "encounter_coefficients",
    "encounter_excitation",
    "encounter_frequencies",
    "excitation_coefficients",
    "excitation_force",
    "excitation_transfer",
    "forward_speed",
    "heading_coverage",
    "leave_one_out_error",
    "wave_response",
]

#: Frequency interpolation methods of :func:`excitation_transfer`.
INTERPOLATION_METHODS = ("hermite", "pchip", "linear", "cubic", "akima", "amplitude-phase")
#: Variables of a ``HydroDB`` that :func:`excitation_transfer` interpolates.
FORCE_VARIABLES = ("excitation_force", "Froude_Krylov_force", "diffraction_force")

# --------------------------------------------------------------------------- helpers


def _force(ds: xr.Dataset, variable: str) -> NDArray[np.complex128]:
    if variable not in FORCE_VARIABLES:
        raise HydroDataError(
            f"{variable!r} is not a wave force variable",
            hint=f"use one of {', '.join(FORCE_VARIABLES)}; motion RAOs are not interpolated "
            "(cummins.seakeeping.frequency_domain.motion_transfer solves for them instead)",
        )
    if variable not in ds:
        raise HydroDataError(
            f"the dataset has no {variable!r}",
            path=_where(ds),
            hint="read the solver's excitation file too (WAMIT .3, NEMOH ExcitationForce.tec, "
            "VERES .re8)",
        )
    return ds[variable].transpose("omega", "wave_direction", "influenced_dof").values


# --------------------------------------------------------------------------- frequency


def _phase_centers(ds: xr.Dataset, phase_center) -> NDArray[np.float64]:
    """Horizontal centre (x, y) of the body of each DOF, m: shape (n_dofs, 2)."""
    labels = [str(d) for d in ds.influenced_dof.values]
    groups = bodies(ds)
    if phase_center is None or (isinstance(phase_center, str) and phase_center == "origin"):
        return np.zeros((len(labels), 2))
    if isinstance(phase_center, str):
        if phase_center != "auto":
            raise ValueError(
                f"phase_center must be 'auto', 'origin' or a point, not {phase_center!r}"
            )
        for key in ("center_of_buoyancy", "reference_point"):
            if key in ds.attrs:
                pts = np.asarray(ds.attrs[key], dtype=float).reshape(-1)
                if pts.size == 3 * len(groups):
                    points = pts.reshape(-1, 3)[:, :2]
                    break
        else:
            points = np.zeros((len(groups), 2))
    else:
        points = np.asarray(phase_center, dtype=float).reshape(-1)
        if points.size in (2, 3):
            points = np.tile(points[:2], (len(groups), 1))
        elif points.size == 3 * len(groups):
            points = points.reshape(-1, 3)[:, :2]
        else:
            raise ValueError("phase_center must be a point (x, y[, z]) or one per body")
    index = {body: k for k, body in enumerate(groups)}
    return np.array([points[index[split_dof(label)[0]]] for label in labels])


def _interpolate_frequency(
    omega: NDArray[np.float64], values: NDArray[np.complex128], targets: NDArray, method: str
) -> NDArray[np.complex128]:
    """Interpolate ``values`` (nω, …) complex, along axis 0, at ``targets`` (within range)."""
    if omega.size == 1:
        return np.broadcast_to(values[0], (targets.size, *values.shape[1:])).copy()
    if method == "amplitude-phase":
        amp = PchipInterpolator(omega, np.abs(values), axis=0)(targets)
        phase = np.unwrap(np.angle(values), axis=0)
        flat = phase.reshape(omega.size, -1)
        ph = np.stack([np.interp(targets, omega, flat[:, j]) for j in range(flat.shape[1])], 1)
        return amp * np.exp(1j * ph.reshape(targets.size, *values.shape[1:]))
    stacked = np.stack([values.real, values.imag], axis=-1)
    if method == "linear" or omega.size == 2:
        flat = stacked.reshape(omega.size, -1)
        out = np.stack([np.interp(targets, omega, flat[:, j]) for j in range(flat.shape[1])], 1)
        out = out.reshape(targets.size, *stacked.shape[1:])
    elif method == "hermite":
        slopes = np.gradient(stacked, omega, axis=0, edge_order=2)
        out = CubicHermiteSpline(omega, stacked, slopes, axis=0)(targets)
    elif method == "pchip":
        out = PchipInterpolator(omega, stacked, axis=0)(targets)
    elif method == "cubic":
        out = CubicSpline(omega, stacked, axis=0, bc_type="not-a-knot")(targets)
    elif method == "akima":
        out = Akima1DInterpolator(omega, stacked, axis=0, method="makima")(targets)
    else:
        raise ValueError(
            f"unknown interpolation method {method!r}; use one of {INTERPOLATION_METHODS}"
        )
    return out[..., 0] + 1j * out[..., 1]


def excitation_transfer(
    ds: xr.Dataset,
    omega: ArrayLike,
    direction: ArrayLike,
    *,
    extrapolate: str = "raise",
    method: str = "hermite",
    mirror: bool | None = None,
    phase_center: str | ArrayLike | None = "auto",
    max_heading_gap: float = np.pi / 2,
    heading_method: str = "cubic",
    variable: str = "excitation_force",
) -> NDArray[np.complex128]:
    """The excitation force per metre of wave amplitude at given frequencies and directions.

    Parameters
    ----------
    ds
        A ``HydroDB`` (one forward speed) with ``excitation_force``.
    omega
        Frequencies, rad/s, shape (n,).
    direction
        Directions of wave travel, rad, shape (n,) (or a scalar for all): the pairs
        (ω_k, β_k) are evaluated, not a grid.
    extrapolate
        ``"raise"`` (default): a frequency outside the data's range raises
        HydroDataError; ``"zero"``: the force is 0 there.
    method
        Frequency interpolation of the phase-corrected force (module docstring):
        ``"hermite"`` (default), ``"pchip"``, ``"linear"``, ``"cubic"``, ``"akima"``,
        ``"amplitude-phase"``.
    mirror
        Use port/starboard symmetry to complete the headings: None (decide from the
        data), True, False (:func:`heading_coverage`).
    phase_center
        Centre (x, y) whose travel phase is removed before interpolating: ``"auto"``
        (centre of buoyancy, else the reference point), ``"origin"`` (none), or a point.
    max_heading_gap
        Widest arc (rad) between available headings across which to interpolate.
    heading_method
        ``"cubic"`` (periodic cubic spline, default) or ``"linear"`` along the headings.
    variable
        ``"excitation_force"``, ``"Froude_Krylov_force"`` or ``"diffraction_force"``.

    Returns
    -------
    numpy.ndarray
        Complex, shape (n, n_dofs), N/m and N·m/m, DOFs in the order of
        ``ds.influenced_dof``; phase relative to the wave elevation at the origin.

    Raises
    ------
    HydroDataError
        No excitation in the data, frequency out of range, direction in a gap.
    """
    ds = single_speed(ds)
    where = _where(ds)
    force = _force(ds, variable)
    if extrapolate not in ("raise", "zero"):
        raise ValueError(f"extrapolate must be 'raise' or 'zero', got {extrapolate!r}")
    if method not in INTERPOLATION_METHODS:
        raise ValueError(
            f"unknown method {method!r}; use one of {', '.join(INTERPOLATION_METHODS)}"
        )
    w_t = np.asarray(omega, dtype=float).reshape(-1)
    b_t = np.broadcast_to(np.asarray(direction, dtype=float), np.shape(omega)).reshape(-1)
    if not (np.all(np.isfinite(w_t)) and np.all(np.isfinite(b_t))):
        raise HydroDataError("non-finite frequency or direction asked for", path=where)
    w = ds.omega.values.astype(float)
    n_dofs = force.shape[2]
    out = np.zeros((w_t.size, n_dofs), dtype=complex)
    tol = 1e-9 * w[-1]
    inside = (w_t >= w[0] - tol) & (w_t <= w[-1] + tol)
    if not inside.all() and extrapolate == "raise":
        bad = w_t[~inside][0]
        raise HydroDataError(
            f"frequency {bad:.6g} rad/s is outside the data's range "
            f"{w[0]:.6g} to {w[-1]:.6g} rad/s",
            path=where,
            quantity=variable,
            hint="limit the wave components to that range (omega_min/omega_max), or pass "
            "extrapolate='zero' to neglect the force outside it",
        )
    if not inside.any():
        return out
    coverage = heading_coverage(ds, mirror=mirror)
    g = float(ds.attrs.get("g", 9.81))
    depth = water_depth(ds, "the travel phase of the wave force between headings")
    centers = _phase_centers(ds, phase_center)  # (n_dofs, 2)

    # Forces on the available headings (mirrored where needed), travel phase removed.
    signs = np.ones(n_dofs)
    if coverage.mirror_used:
        signs = np.array(
            [MIRROR_SIGNS[DOF_NAMES.index(split_dof(str(d))[1])] for d in ds.influenced_dof.values]
        )
    f_all = force[:, coverage.source, :]
    f_all = np.where(coverage.mirrored[None, :, None], f_all * signs[None, None, :], f_all)
    k = wavenumber(w, depth, g)
    ell = (
        centers[None, :, 0] * np.cos(coverage.directions)[:, None]
        + centers[None, :, 1] * np.sin(coverage.directions)[:, None]
    )  # (nβ, n_dofs)
    smooth = f_all * np.exp(1j * k[:, None, None] * ell[None, :, :])

    w_in = np.clip(w_t[inside], w[0], w[-1])
    g_w = _interpolate_frequency(w, smooth, w_in, method)  # (m, nβ, n_dofs)
    weights = _heading_weights(coverage, b_t[inside], max_heading_gap, where, heading_method)
    g_t = np.einsum("kb,kbd->kd", weights, g_w)
    k_t = wavenumber(w_in, depth, g)
    ell_t = (
        centers[None, :, 0] * np.cos(b_t[inside])[:, None]
        + centers[None, :, 1] * np.sin(b_t[inside])[:, None]
    )
    out[inside] = g_t * np.exp(-1j * k_t[:, None] * ell_t)
    return out


# --------------------------------------------------------------------------- time series


def wave_response(
    waves: WaveComponents,
    transfer: ArrayLike,
    t: ArrayLike,
    encounter_frequency: ArrayLike | None = None,
) -> NDArray[np.float64]:
    """Σ_k a_k Re{H_k e^{i(ω_k t + φ_k)}}: the linear response to a sea of components.

    Parameters
    ----------
    waves
        The sea state.
    transfer
        H_k per metre of wave amplitude, complex, shape (n,) or (n, m) (e.g. from
        :func:`excitation_transfer`, or motion RAOs from
        :func:`cummins.seakeeping.frequency_domain.motion_transfer`), phase relative to the
        elevation at the origin.
    t
        Times, s, shape (nt,).
    encounter_frequency
        For a ship at speed, ω_e of each component (:func:`encounter_frequencies`), with
        H referred to e^{iω_e t} (as :func:`cummins.seakeeping.frequency_domain.motion_transfer`
        gives it): the response is then Σ_k a_k Re{H_k e^{i(ω_e,k t + φ_k)}}.

    Returns
    -------
    numpy.ndarray
        Shape (nt,) or (nt, m), in the units of H times metres.
    """
    h = np.asarray(transfer, dtype=complex)
    if h.shape[0] != len(waves):
        raise ValueError(f"transfer has {h.shape[0]} rows for {len(waves)} wave components")
    c = waves.complex_amplitude.reshape((-1,) + (1,) * (h.ndim - 1)) * h
    w = waves.omega if encounter_frequency is None else encounter_frequency
    return harmonic_sum(t, np.asarray(w, dtype=float).reshape(-1), c)


def forward_speed(ds: xr.Dataset) -> float:
    """The forward speed U of a one-speed ``HydroDB`` (its ``forward_speed`` coordinate),
    m/s; 0 when it has none."""
    ds = single_speed(ds)
    if "forward_speed" in ds.coords and ds.forward_speed.ndim == 0:
        return float(ds.forward_speed)
    return 0.0


def encounter_frequencies(
    ds: xr.Dataset, omega: ArrayLike, direction: ArrayLike
) -> NDArray[np.float64]:
    """Encounter frequency ω_e = ω − k(ω) U cos β of the dataset's forward speed, rad/s.

    Parameters
    ----------
    ds
        A ``HydroDB`` of one forward speed U (m/s, the ``forward_speed`` coordinate; 0 or
        none: ω_e = ω exactly).
    omega
        Wave frequencies ω, rad/s.
    direction
        Directions of wave travel β, rad (0 following seas, π head seas), broadcast
        against ``omega``.

    Returns
    -------
    numpy.ndarray
        ω_e, signed (negative where following waves overtake the ship faster than their
        phase passes it; module docstring), shape of the broadcast inputs. k from the
        dispersion relation at the data's ``water_depth`` and ``g``
        (:func:`cummins.seakeeping.waves.wavenumber`), as
        :func:`cummins.radiation.speed.encounter_frequency`
        does in deep water.

    Examples
    --------
    >>> import cummins, numpy as np
    >>> from importlib import resources
    >>> s175 = cummins.read(str(resources.files("cummins") / "data" / "s175" / "s175.mat"))
    >>> ds = s175.isel(forward_speed=4)   # 10.29 m/s (20 kn); head seas: beta = pi
    >>> round(float(encounter_frequencies(ds, 0.5, np.pi)), 3)
    0.762
    """
    w, beta = np.broadcast_arrays(
        np.asarray(omega, dtype=float), np.asarray(direction, dtype=float)
    )
    speed = forward_speed(ds)
    if speed == 0.0:
        return w.copy()
    g = float(ds.attrs.get("g", 9.81))
    depth = water_depth(ds, "the encounter frequencies")
    return w - wavenumber(w, depth, g) * speed * np.cos(beta)


def encounter_excitation(
    force: ArrayLike, encounter_frequency: ArrayLike
) -> NDArray[np.complex128]:
    """Excitation amplitudes of data at speed referred to e^{iω_e t}: F̄ where ω_e < 0.

    Strip-theory codes (ShipX/VERES) tabulate the force of a wave met at a negative
    encounter frequency against |ω_e|, i.e. referred to e^{i|ω_e|t}; the force on the
    ship is then Re{F a e^{i|ω_e|t}} for the wave Re{ā e^{i|ω_e|t}} = Re{a e^{iω_e t}}
    at its origin. Conjugating F there puts force and wave on one convention,
    Re{F̄ a e^{iω_e t}} (:mod:`cummins.seakeeping.frequency_domain`, forward speed).

    Parameters
    ----------
    force
        F(ω, β), shape (..., n_dofs), N/m, N·m/m.
    encounter_frequency
        ω_e of each (ω, β), shape ``force.shape[:-1]``, rad/s.
    """
    f = np.asarray(force, dtype=complex)
    negative = np.asarray(encounter_frequency, dtype=float) < 0
    return np.where(negative[..., None], np.conj(f), f)


def encounter_coefficients(
    ds: xr.Dataset, waves: WaveComponents, **options
) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """(ω_e, c): the wave force on the ship at the data's forward speed,
    τ(t) = Re Σ_k c_k e^{iω_e,k t}, with c_k = a_k e^{iφ_k} F(ω_k, β_k) (F̄ where
    ω_e < 0, :func:`encounter_excitation`), shapes (n,) and (n, n_dofs). At zero speed
    ω_e = ω and c is :func:`excitation_coefficients`. ``options`` go to
    :func:`excitation_transfer`."""
    we = encounter_frequencies(ds, waves.omega, waves.direction)
    f = excitation_transfer(ds, waves.omega, waves.direction, **options)
    return we, waves.complex_amplitude[:, None] * encounter_excitation(f, we)


def excitation_coefficients(
    ds: xr.Dataset, waves: WaveComponents, **options
) -> NDArray[np.complex128]:
    """c_k = a_k e^{iφ_k} F(ω_k, β_k), shape (n, n_dofs): τ(t) = Re Σ_k c_k e^{iω_k t}.

    Compute once, then :func:`cummins.seakeeping.waves.harmonic_sum` (t, waves.omega, c) gives
    τ at any times cheaply (a simulator calling it step by step). ``options`` go to
    :func:`excitation_transfer`.
    """
    f = excitation_transfer(ds, waves.omega, waves.direction, **options)
    return waves.complex_amplitude[:, None] * f


def excitation_force(
    ds: xr.Dataset, waves: WaveComponents, t: ArrayLike, **options
) -> NDArray[np.float64]:
    """First-order wave excitation τ(t) = Σ_k a_k Re{F(ω_k, β_k) e^{i(ω_k t + φ_k)}}.

    At a forward speed (data with a ``forward_speed``), the force on the moving ship:
    ω_e in place of ω (:func:`encounter_coefficients`).

    Parameters
    ----------
    ds
        A ``HydroDB`` with ``excitation_force`` (one forward speed).
    waves
        The sea state (phases at the origin, where the force's phase is referred).
    t
        Times, s, shape (nt,).
    **options
        Passed to :func:`excitation_transfer` (``extrapolate``, ``method``, ``mirror`` …).

    Returns
    -------
    numpy.ndarray
        Shape (nt, n_dofs): N and N·m, DOFs in the order of ``ds.influenced_dof``.

    Notes
    -----
    The sum is evaluated by :func:`cummins.seakeeping.waves.harmonic_sum`: in blocks of times, with
    no Python loop over times (200 components × 200 000 uniform times × 6 DOFs: about
    0.25 s).
    """
    we, c = encounter_coefficients(ds, waves, **options)
    return harmonic_sum(np.asarray(t, dtype=float).reshape(-1), we, c)


# --------------------------------------------------------------------------- diagnostics


def leave_one_out_error(
    ds: xr.Dataset,
    *,
    method: str = "hermite",
    axis: str = "omega",
    phase_center: str | ArrayLike | None = "auto",
    mirror: bool | None = None,
    variable: str = "excitation_force",
    heading_method: str = "cubic",
    dofs: Sequence[str] | None = None,
) -> xr.DataArray:
    """Interpolation error of the force at each data point when that point is left out.

    Each interior frequency (``axis="omega"``) or each heading (``axis="wave_direction"``)
    is removed in turn and predicted by :func:`excitation_transfer` from the others.
    Leaving a point out doubles the local spacing, so this overestimates the error of
    interpolating between the full data (by about 2ᵖ for a method of order p).

    Returns
    -------
    xarray.DataArray
        |F_interp − F| / max |F| (the largest force of that DOF over all frequencies
        and headings), dims (omega, wave_direction, influenced_dof); NaN where not
        evaluated (end frequencies, a heading whose removal opens a gap, DOFs not excited).
    """
    ds = single_speed(ds)
    force = _force(ds, variable)
    w = ds.omega.values
    beta = ds.wave_direction.values
    err = np.full(force.shape, np.nan)
    scale = np.abs(force).max(axis=(0, 1), keepdims=True)
    options = {
        "method": method,
        "phase_center": phase_center,
        "mirror": mirror,
        "variable": variable,
        "heading_method": heading_method,
    }
    if axis == "omega":
        for j in range(1, w.size - 1):
            sub = ds.isel(omega=np.delete(np.arange(w.size), j))
            pred = excitation_transfer(sub, np.full(beta.size, w[j]), beta, **options)
            err[j] = np.abs(pred - force[j])
    elif axis == "wave_direction":
        cover = heading_coverage(ds, mirror=mirror)
        for j in range(beta.size):
            sub = ds.isel(wave_direction=np.delete(np.arange(beta.size), j))
            sub_mirror = cover.mirror_used if mirror is None else mirror
            try:
                pred = excitation_transfer(
                    sub, w, np.full(w.size, beta[j]), **{**options, "mirror": sub_mirror}
                )
            except HydroDataError:
                continue
            err[:, j] = np.abs(pred - force[:, j])
    else:
        raise ValueError("axis must be 'omega' or 'wave_direction'")
    with np.errstate(invalid="ignore", divide="ignore"):
        rel = np.where(scale > 0, err / scale, np.nan)
    out = xr.DataArray(
        rel,
        dims=("omega", "wave_direction", "influenced_dof"),
        coords={"omega": w, "wave_direction": beta, "influenced_dof": ds.influenced_dof.values},
        name="leave_one_out_error",
        attrs={"method": method, "axis": axis, "units": "1 (fraction of the DOF's max |F|)"},
    )
    if dofs is not None:
        out = out.sel(influenced_dof=list(dofs))
    return out
