"""The excitation impulse response K_ex(t) and the time advance t_c that makes it causal.

The first-order wave force on a body is the output of a linear system driven by the
incident wave elevation η(t) at the origin (Falnes (2002) ch. 5, its time-domain
section; Falnes (1995)):

    F(t) = ∫ K_ex(τ) η(t − τ) dτ,
    K_ex(t) = (1/2π) ∫_{−∞}^{∞} F(ω) e^{iωt} dω = (1/π) ∫₀^∞ Re{F(ω) e^{iωt}} dω,

with F(ω) the ``excitation_force`` of a ``HydroDB`` (cummins' convention x(t) =
Re{X e^{iωt}}, phase relative to the incident elevation at the origin,
:mod:`cummins.seakeeping.excitation`) and F(−ω) = F̄(ω) (K_ex is real). K_ex is **not
causal**: a wave reaches the body's far side after it passes the origin, and the
pressure field of a dispersive wave group runs ahead of its crest, so K_ex(t) ≠ 0 for
t < 0 (Falnes (1995)). Shifted by a time advance t_c, K_ex(t − t_c) is causal *enough*
to be the impulse response of a finite state-space model driven by η(t + t_c) — what
HydroDyn's ``SS_Excitation`` integrates (Yu & Falnes (1995)), and what a
model-predictive controller fed with a wave forecast needs.

How it is evaluated
-------------------
F is interpolated on a fine grid (each data interval cut into ``refine`` parts, at
least :data:`FINE_POINTS` points in all) by
:func:`cummins.seakeeping.excitation.excitation_transfer` (Hermite interpolation with
the wave's travel phase removed: exact at the data), and the piecewise-linear
interpolant is integrated exactly against cos ωt and sin ωt
(:mod:`cummins.radiation.transforms`):

    K_ex(t) = (1/π) [∫ Re F(ω) cos ωt dω − ∫ Im F(ω) sin ωt dω].

Below the lowest data frequency the force of a long wave tends to the hydrostatic
force of a uniform rise of the water, F(0) = ±C[:, heave] (+ in z-up axes, − in z-down:
the body sinking by η relative to the water; summed over the heave columns of every
body), the limit cummins uses between ω = 0 and the first frequency when the data hold
the hydrostatic stiffness (``zero_frequency="hydrostatic"``), and says so; without it
the integral starts at the first frequency. Above the last frequency the force is taken
as zero (the data say nothing there; K_ex then carries the truncation's ripple of
period 2π/ω_max).

The time advance
----------------
:func:`causal_delay` picks, per heading, the smallest t_c ≥ 0 such that for every DOF
the energy of K_ex before −t_c, ∫_{−∞}^{−t_c} K_ex² dt, is at most ``fraction`` of its
total energy ∫ K_ex² dt. What is left before −t_c cannot be represented by a causal
model: its share bounds the model's error (by Parseval, a fraction ε of the energy
costs a relative L² error of about √ε: 3 % for ε = 10⁻³).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import HydroDataError
from cummins.hydrodb import is_rotation, single_speed, split_dof
from cummins.radiation.transforms import fourier_transform

__all__ = [
    "CAUSALITY",
    "causal_delay",
    "causal_delays",
    "default_irf_times",
    "excitation_irf",
    "excited_dofs",
    "zero_frequency_force",
]

#: Default share of the energy of K_ex(t) allowed before −t_c (:func:`causal_delay`).
CAUSALITY = 1e-3
#: The interpolated force the transform integrates has at least about this many points
#: (each data interval cut into ⌈FINE_POINTS / n_ω⌉ parts, unless ``refine`` is given).
FINE_POINTS = 400
#: A DOF whose largest |F| at a heading is below this fraction of its largest over all
#: headings (or below ``NUMERICAL_ZERO`` of the largest DOF of its kind there) is not
#: excited at that heading (a spar's sway in head seas): no model, no states.
NOT_EXCITED = 1e-3
NUMERICAL_ZERO = 1e-3


def _check_zero_speed(ds: xr.Dataset) -> xr.Dataset:
    ds = single_speed(ds)
    speed = float(ds.forward_speed) if "forward_speed" in ds.coords else 0.0
    if speed != 0.0:
        raise HydroDataError(
            f"the data are at forward speed {speed:g} m/s: the excitation is then a "
            "function of the encounter frequency, which a model driven by the wave "
            "elevation at a fixed point does not represent",
            path=ds.attrs.get("source_file"),
            hint="use data at zero speed (a moored or station-keeping body)",
        )
    if "excitation_force" not in ds:
        raise HydroDataError(
            "the dataset has no excitation_force",
            path=ds.attrs.get("source_file"),
            hint="read the solver's excitation file too (WAMIT .3, NEMOH ExcitationForce.tec, "
            "VERES .re8)",
        )
    return ds


def zero_frequency_force(ds: xr.Dataset) -> NDArray[np.float64] | None:
    """F(ω → 0): the hydrostatic force of a uniform rise of the water, per metre.

    ± the sum of the heave columns of the hydrostatic stiffness (+ in z-up axes, − in
    z-down), N/m and N·m/m, DOFs in the order of ``influenced_dof``; ``None`` when the
    data hold no ``hydrostatic_stiffness`` (or it is all zero). A long wave lifts the
    water around the body uniformly: the body feels what it would feel sinking by η.
    """
    if "hydrostatic_stiffness" not in ds:
        return None
    c = np.asarray(
        ds.hydrostatic_stiffness.transpose("influenced_dof", "radiating_dof").values, dtype=float
    )
    if not np.any(c) or not np.all(np.isfinite(c)):
        return None
    labels = [str(d) for d in ds.radiating_dof.values]
    heave = [k for k, label in enumerate(labels) if split_dof(label)[1] == "Heave"]
    if not heave:
        return None
    sign = -1.0 if ds.attrs.get("axis_convention", "z-up") == "z-down" else 1.0
    return sign * c[:, heave].sum(axis=1)


def _directions(ds: xr.Dataset, wave_direction: ArrayLike | None) -> NDArray[np.float64]:
    if wave_direction is None:
        return np.asarray(ds.wave_direction.values, dtype=float).reshape(-1)
    beta = np.asarray(wave_direction, dtype=float).reshape(-1)
    if beta.size == 0 or not np.all(np.isfinite(beta)):
        raise HydroDataError(f"wave directions {beta.tolist()} are not usable (rad)")
    return beta


def force_on_grid(
    ds: xr.Dataset,
    directions: NDArray[np.float64],
    omega: NDArray[np.float64],
) -> NDArray[np.complex128]:
    """F(ω, β) at the given frequencies (within the data's range) and directions,
    shape (nω, nβ, n_dofs): :func:`~cummins.seakeeping.excitation.excitation_transfer`."""
    from cummins.seakeeping.excitation import excitation_transfer

    out = np.empty((omega.size, directions.size, ds.sizes["influenced_dof"]), dtype=complex)
    for k, beta in enumerate(directions):
        out[:, k, :] = excitation_transfer(ds, omega, np.full(omega.size, beta))
    return out


def _fine_force(
    ds: xr.Dataset, directions: NDArray, refine: int | None, zero_frequency: str
) -> tuple[NDArray, NDArray, str]:
    """The fine grid, F on it (nω, nβ, n), and a note on the low-frequency end."""
    w = np.asarray(ds.omega.values, dtype=float)
    if w.size < 2:
        raise HydroDataError(
            "the excitation is known at one frequency: no impulse response",
            path=ds.attrs.get("source_file"),
        )
    if refine is None:
        refine = max(1, int(np.ceil(FINE_POINTS / w.size)))
    parts = [np.linspace(w[k], w[k + 1], refine + 1)[:-1] for k in range(w.size - 1)]
    fine = np.r_[np.concatenate(parts), w[-1]]
    force = force_on_grid(ds, directions, fine)
    if zero_frequency not in ("hydrostatic", "none"):
        raise ValueError(f"zero_frequency must be 'hydrostatic' or 'none', not {zero_frequency!r}")
    f0 = zero_frequency_force(ds) if zero_frequency == "hydrostatic" else None
    if w[0] <= 0:
        note = "the data start at omega = 0"
    elif f0 is None:
        note = (
            f"no force below the first frequency {w[0]:.4g} rad/s (the data hold no "
            "hydrostatic stiffness for the long-wave limit)"
        )
        if zero_frequency == "none":
            note = f"no force below the first frequency {w[0]:.4g} rad/s (as asked)"
    else:
        fine = np.r_[0.0, fine]
        force = np.concatenate([np.broadcast_to(f0, (1, directions.size, f0.size)), force])
        note = (
            f"between omega = 0 and the first frequency {w[0]:.4g} rad/s the force is "
            "interpolated to the long-wave limit F(0) = the hydrostatic force of a uniform "
            "rise of the water"
        )
    return fine, force, note


def default_irf_times(
    ds: xr.Dataset, *, threshold: float = 0.01, max_points: int = 20_000
) -> NDArray[np.float64]:
    """A time grid, symmetric about 0, long and fine enough for K_ex(t) of ``ds``.

    dt = π/(2 ω_max), half the Nyquist step of the data (coarser if ``max_points``
    would be exceeded); the span is found
    from K_ex itself as :func:`cummins.radiation.retardation.default_time_grid` does: up
    to ±2π/ω_min (the data hold no information beyond), ending at 1.5 times the last
    time, on either side, where some DOF and heading still exceeds ``threshold`` of its
    peak.
    """
    return excitation_irf(ds, threshold=threshold, max_points=max_points).time.values


def _probe_times(ds: xr.Dataset, max_points: int) -> NDArray[np.float64]:
    w = np.asarray(ds.omega.values, dtype=float)
    t_limit = 2 * np.pi / float(w[w > 0].min())
    dt = max(np.pi / (2 * w[-1]), 2 * t_limit / max_points)
    half = np.arange(0.0, t_limit + 0.5 * dt, dt)
    return np.r_[-half[:0:-1], half]


def _trimmed(k: NDArray, probe: NDArray, threshold: float) -> NDArray[np.bool_]:
    """The times of the probe grid the default grid keeps (see default_irf_times)."""
    flat = k.reshape(probe.size, -1)
    peak = np.abs(flat).max(axis=0)
    keep = peak > 1e-9 * max(float(peak.max()), np.finfo(float).tiny)
    if not keep.any():
        return np.ones(probe.size, dtype=bool)
    active = np.abs(flat[:, keep]) > threshold * peak[keep]
    reach = float(np.abs(probe[np.flatnonzero(active.any(axis=1))]).max())
    dt = float(probe[1] - probe[0])
    t_max = min(float(probe[-1]), max(1.5 * reach, 20 * dt))
    return np.abs(probe) <= t_max + 0.5 * dt


def excitation_irf(
    ds: xr.Dataset,
    t: ArrayLike | None = None,
    *,
    wave_direction: ArrayLike | None = None,
    zero_frequency: str = "hydrostatic",
    refine: int | None = None,
    threshold: float = 0.01,
    max_points: int = 20_000,
) -> xr.DataArray:
    """The excitation impulse response K_ex(t) = (1/2π) ∫ F(ω) e^{iωt} dω.

    Falnes (2002) ch. 5 (time domain), module docstring: K_ex is non-causal; F(t) =
    ∫ K_ex(τ) η(t − τ) dτ with η the incident elevation at the origin.

    Parameters
    ----------
    ds
        A ``HydroDB`` at zero forward speed with ``excitation_force``.
    t
        Times, s (negative and positive); default :func:`default_irf_times`.
    wave_direction
        Directions of wave travel, rad (0 following seas, π head seas); default the
        data's. Between the data's headings the force is interpolated
        (:func:`~cummins.seakeeping.excitation.excitation_transfer`).
    zero_frequency
        ``"hydrostatic"`` (default): below the first frequency the force goes linearly
        to the long-wave limit :func:`zero_frequency_force` when the data hold the
        hydrostatic stiffness; ``"none"``: the integral starts at the first frequency.
    refine
        Parts each data interval is cut into for the interpolated force (module
        docstring); default ⌈:data:`FINE_POINTS` / n_ω⌉.
    threshold, max_points
        Of the default times (:func:`default_irf_times`).

    Returns
    -------
    xarray.DataArray
        ``excitation_irf`` (time, wave_direction, influenced_dof), N/(m·s) and
        N·m/(m·s); attribute ``low_frequency`` says what was assumed below the data.

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.read(cummins.demo_files() / "tanker.1")
    >>> k = excitation_irf(ds, [-5.0, 0.0, 5.0], wave_direction=[3.14159])
    >>> k.dims
    ('time', 'wave_direction', 'influenced_dof')
    """
    ds = _check_zero_speed(ds)
    times = _probe_times(ds, max_points) if t is None else np.asarray(t, dtype=float).reshape(-1)
    if times.size == 0 or not np.all(np.isfinite(times)):
        raise HydroDataError("the times of the impulse response must be finite")
    directions = _directions(ds, wave_direction)
    fine, force, note = _fine_force(ds, directions, refine, zero_frequency)
    k = fourier_transform(fine, force, times).real / np.pi
    if t is None:
        keep = _trimmed(k, times, threshold)
        times, k = times[keep], k[keep]
    units = ["N m/(m s)" if is_rotation(str(d)) else "N/(m s)" for d in ds.influenced_dof.values]
    return xr.DataArray(
        k,
        dims=("time", "wave_direction", "influenced_dof"),
        coords={
            "time": times,
            "wave_direction": directions,
            "influenced_dof": ds.influenced_dof.values,
        },
        name="excitation_irf",
        attrs={
            "long_name": "excitation impulse response K_ex(t) = (1/2 pi) int F(w) exp(iwt) dw",
            "units": " | ".join(dict.fromkeys(units)),
            "low_frequency": note,
            "high_frequency": f"F = 0 above the last frequency {float(ds.omega[-1]):.4g} rad/s",
        },
    )


def excited_dofs(force: NDArray[np.complex128], labels) -> NDArray[np.bool_]:
    """(nβ, n) True where a DOF is excited at a heading (:data:`NOT_EXCITED`).

    ``force`` is F (nω, nβ, n). A DOF is not excited at a heading when its largest |F|
    there is below :data:`NOT_EXCITED` of its largest over all headings, or below
    :data:`NUMERICAL_ZERO` of the largest DOF of its kind (translations, rotations) at
    that heading (the numerical zeros of a symmetric body).
    """
    peak = np.abs(force).max(axis=0)  # (nβ, n)
    overall = peak.max(axis=0)  # (n,)
    rotation = np.array([is_rotation(str(label)) for label in labels])
    kind_peak = np.zeros_like(peak)
    for mask in (rotation, ~rotation):
        if mask.any():
            kind_peak[:, mask] = peak[:, mask].max(axis=1, keepdims=True)
    return (
        (peak > NOT_EXCITED * overall[None, :]) & (peak > NUMERICAL_ZERO * kind_peak) & (peak > 0)
    )


def causal_delay(
    irf: xr.DataArray,
    fraction: float = CAUSALITY,
    excited: NDArray[np.bool_] | None = None,
) -> NDArray[np.float64]:
    """The time advance t_c per heading (module docstring), s.

    The smallest t_c ≥ 0 on the grid of ``irf`` with ∫_{−∞}^{−t_c} K_ex² dt ≤
    ``fraction`` · ∫ K_ex² dt for every excited DOF (``excited`` (nβ, n): default all
    with a nonzero K_ex): the largest of :func:`causal_delays`.

    Parameters
    ----------
    irf
        :func:`excitation_irf` on a grid reaching far enough before 0.
    fraction
        Share of the energy allowed before −t_c, in (0, 1).
    excited
        Which DOFs count at each heading (:func:`excited_dofs`).

    Returns
    -------
    numpy.ndarray
        t_c per heading of ``irf``, s.

    Examples
    --------
    >>> import numpy as np, xarray as xr
    >>> t = np.linspace(-20, 20, 4001)
    >>> k = xr.DataArray(np.exp(-(t + 3.0) ** 2)[:, None, None],
    ...                  dims=("time", "wave_direction", "influenced_dof"),
    ...                  coords={"time": t})
    >>> round(float(causal_delay(k, 1e-3)[0]), 2)  # a Gaussian centred at t = -3 s
    4.55
    """
    per_dof = causal_delays(irf, fraction, excited)
    return np.max(np.where(np.isnan(per_dof), 0.0, per_dof), axis=1, initial=0.0)


def causal_delays(
    irf: xr.DataArray,
    fraction: float = CAUSALITY,
    excited: NDArray[np.bool_] | None = None,
) -> NDArray[np.float64]:
    """The time advance of each DOF on its own, (nβ, n), s; NaN where not excited
    (:func:`causal_delay` takes the largest per heading)."""
    if not 0 < fraction < 1:
        raise ValueError(f"fraction must be in (0, 1), not {fraction!r}")
    k = np.asarray(irf.transpose("time", "wave_direction", "influenced_dof").values, dtype=float)
    t = np.asarray(irf["time"].values, dtype=float)
    energy = np.cumsum(k**2, axis=0)
    total = energy[-1]  # (nβ, n)
    if excited is None:
        excited = total > 0
    out = np.full(total.shape, np.nan)
    for b in range(k.shape[1]):
        for d in np.flatnonzero(excited[b] & (total[b] > 0)):
            share = energy[:, b, d] / total[b, d]
            first = int(np.searchsorted(share, fraction, side="right"))
            out[b, d] = max(-t[min(first, t.size - 1)], 0.0)
    return out
