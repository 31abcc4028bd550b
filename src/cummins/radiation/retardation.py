"""Retardation functions K(t), infinite-frequency added mass A∞ and causality diagnostics.

The radiation force of the Cummins equation is −A∞ ξ̈ − ∫₀ᵗ K(t − τ) ξ̇(τ) dτ, with
(Ogilvie; Hjulstad (2004) eqs. 5.11–5.15, Unneland (2007) eqs. 2.46–2.61)

* K(t) = (2/π) ∫₀^∞ B(ω) cos(ωt) dω                              (Hjulstad (2004) eq. 5.15)
* K(t) = −(2/π) ∫₀^∞ ω (A(ω) − A∞) sin(ωt) dω                      (Hjulstad (2004) eq. 5.14)
* B(ω) = ∫₀^∞ K(t) cos(ωt) dt,  A(ω) = A∞ − (1/ω) ∫₀^∞ K(t) sin(ωt) dt  (eqs. 5.11–5.12)
* A(ω) = A∞ + (2/π) PV ∫₀^∞ B(ν) / (ν² − ω²) dν  (Kramers–Kronig, Hjulstad (2004) eq. 5.23)
* c(ω) = ω² (A∞ − A(ω)) − ω ∫₀^∞ K(t) sin(ωt) dt = 0 for consistent data (eq. 5.5)

How cummins evaluates them (see :mod:`cummins.radiation.transforms`): the damping is taken as
piecewise linear between the data points (or a shape-preserving cubic, resampled),
with B(0) = 0 at zero speed, and integrated *exactly* against cos ωt — no aliasing on
coarse or non-uniform grids. Beyond the last frequency a fitted high-frequency tail
(exponential B_N e^{−α(ω−ω_N)}, with its analytic cosine transform, or a power law
B_N (ω_N/ω)^n, integrated exactly on a fine geometric grid;
:mod:`cummins.radiation.damping_tail`, whose names are importable from here as well)
continues the data; the tail's share of ∫B dω is reported because K(0) depends on it.
A∞ is the data row when the solver computed it; otherwise the Ogilvie relation is evaluated at every
frequency through the exact principal-value integral of the Kramers–Kronig relation
(equivalent to (1/ω)∫K(t) sin ωt dt, without truncating K), and the values are
combined robustly (median), with their spread.

All functions take a ``HydroDB`` at one forward speed and return xarray objects with
the dataset's DOF labels. Units: K in kg/s², kg·m/s², kg·m²/s² (as B divided by s).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.arrays import LastAnswer, digest
from cummins.errors import HydroDataError
from cummins.hydrodb import dof_matrix, is_rotation, single_speed
from cummins.radiation.damping_tail import MIN_POWER as MIN_POWER  # re-exported
from cummins.radiation.damping_tail import TAIL_KINDS as TAIL_KINDS  # re-exported
from cummins.radiation.damping_tail import DampingTail as DampingTail  # re-exported
from cummins.radiation.damping_tail import fit_damping_tail, kramers_kronig_integral
from cummins.radiation.infinite_frequency import (
    _added_mass_inf_matrix,
    _kramers_kronig_integral,
    coupling_coords,
)
from cummins.radiation.infinite_frequency import added_mass_inf as added_mass_inf  # re-exported
from cummins.radiation.infinite_frequency import (
    added_mass_inf_per_frequency as added_mass_inf_per_frequency,  # re-exported
)
from cummins.radiation.infinite_frequency import (
    bridged_couplings as bridged_couplings,  # re-exported
)
from cummins.radiation.infinite_frequency import (
    trusted_frequencies as trusted_frequencies,  # re-exported
)
from cummins.radiation.transforms import cosine_transform, sine_transform

INTERPOLATIONS = ("linear", "pchip")

_K_UNITS = "kg/s^2 | kg m/s^2 | kg m^2/s^2 (translation | mixed | rotation)"


# --------------------------------------------------------------------------- helpers


def default_time_grid(
    ds: xr.Dataset, *, threshold: float = 0.01, max_points: int = 20_000
) -> NDArray[np.float64]:
    """A time grid long and fine enough for the retardation functions of ``ds``.

    The step resolves the highest frequency of the data, dt = π/(4 ω_N) (coarser if
    ``max_points`` would otherwise be exceeded). The length is found from K itself: K is
    evaluated up to 2π/ω_min, beyond which the data hold no information (Hjulstad (2004)
    §12.4), and the grid ends at 1.5 times the last time where some coupling still
    exceeds ``threshold`` of its peak (at most 2π/ω_min). Bodies with a long memory in
    one DOF (heave in shallow water) get a long grid, compact ones a short one.

    Returns
    -------
    ndarray
        Times in seconds, uniformly spaced from 0.
    """
    return _default_kernel(ds, threshold, max_points)[0]


def default_retardation_function(
    ds: xr.Dataset, *, threshold: float = 0.01, max_points: int = 20_000, node_form: bool = True
) -> xr.DataArray:
    """:func:`retardation_function` (its ``node_form``) on :func:`default_time_grid`, once."""
    return _default_kernel(ds, threshold, max_points, node_form)[1]


def _default_kernel(ds: xr.Dataset, threshold: float, max_points: int, node_form: bool = True):
    ds = single_speed(ds)
    probe, dt, t_limit = _probe_times(ds.omega.values, max_points)
    kernel = retardation_function(ds, probe, node_form=node_form)
    stop = _kernel_stop(probe, kernel.values.reshape(probe.size, -1), threshold, dt, t_limit)
    if stop is None:
        return probe, kernel
    return probe[:stop], kernel.isel(time=slice(0, stop))


def _probe_times(w: NDArray, max_points: int) -> tuple[NDArray, float, float]:
    """The times :func:`default_time_grid` looks at (up to 2π/ω₀), their step and end."""
    t_limit = 2 * np.pi / w[0]
    dt = max(np.pi / (4 * w[-1]), t_limit / max_points)
    return np.arange(0.0, t_limit + 0.5 * dt, dt), dt, t_limit


def _kernel_stop(probe: NDArray, k: NDArray, threshold: float, dt: float, t_limit: float):
    """How many of the times ``probe`` :func:`default_time_grid` keeps for K(t) ``k``
    (len(probe), P): 1.5 × the last time any coupling is above ``threshold`` of its
    peak; None for a K(t) that is zero throughout (all of them)."""
    peak = np.abs(k).max(axis=0)
    keep = peak > 1e-9 * peak.max()
    if not keep.any():
        return None
    active = np.abs(k[:, keep]) > threshold * peak[keep]
    last = probe[np.flatnonzero(active.any(axis=1))[-1]]
    t_max = min(t_limit, max(1.5 * last, 20 * dt))
    return int(np.searchsorted(probe, t_max + 0.5 * dt))


def default_kernel_values(
    omega: ArrayLike,
    damping: ArrayLike,
    added_mass: ArrayLike,
    *,
    threshold: float = 0.01,
    max_points: int = 20_000,
    node_form: bool = False,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(times, K(t) (len(times), n, n)) of :func:`default_retardation_function` (default
    tail and interpolation, B(0) = 0) from the arrays of one forward speed: ``omega``
    (N,), ``damping`` and ``added_mass`` (N, n, n) — the same numbers, without the
    datasets and the labels (the fit's data stage; ``node_form`` False by default, as
    the fit takes it)."""
    w = np.asarray(omega, dtype=float)
    b = np.asarray(damping, dtype=float)
    n = b.shape[1]
    data = b.reshape(w.size, n * n)
    added = np.asarray(added_mass, dtype=float).reshape(w.size, n * n)
    probe, dt, t_limit = _probe_times(w, max_points)
    grid = _interpolant_grid(w, data, "linear", True)
    k, _ = _kernel_of_arrays(w, data, added, grid, probe, "auto", node_form=node_form)
    values = (2.0 / np.pi) * k.reshape(probe.size, n, n)
    stop = _kernel_stop(probe, values.reshape(probe.size, -1), threshold, dt, t_limit)
    if stop is None:
        return probe, values
    return probe[:stop], values[:stop]


# --------------------------------------------------------------------------- K(t)


def _damping_grid(
    ds: xr.Dataset, interpolation: str, zero_frequency: bool
) -> tuple[NDArray, NDArray]:
    """Frequencies and B (N, P) of the piecewise-linear representation of the data."""
    if interpolation not in INTERPOLATIONS:
        raise HydroDataError(
            f"unknown interpolation {interpolation!r}",
            hint=f"use one of {', '.join(INTERPOLATIONS)}",
        )
    w = ds.omega.values
    n = ds.sizes["influenced_dof"]
    b = dof_matrix(ds, "radiation_damping").reshape(w.size, n * n)
    return _interpolant_grid(w, b, interpolation, zero_frequency)


def _interpolant_grid(
    w: NDArray, b: NDArray, interpolation: str, zero_frequency: bool
) -> tuple[NDArray, NDArray]:
    """:func:`_damping_grid` of the arrays: frequencies ``w`` (N,), B ``b`` (N, P)."""
    if zero_frequency:
        w = np.r_[0.0, w]
        b = np.vstack([np.zeros((1, b.shape[1])), b])
    if interpolation == "pchip" and w.size > 2:
        fine = np.unique(
            np.concatenate([np.linspace(w[k], w[k + 1], 5) for k in range(w.size - 1)])
        )
        from scipy.interpolate import PchipInterpolator  # on use: 0.15 s to import

        b = PchipInterpolator(w, b, axis=0)(fine)
        w = fine
    return w, b


def retardation_function(
    ds: xr.Dataset,
    t: ArrayLike | None = None,
    *,
    tail: str = "auto",
    interpolation: str = "linear",
    zero_frequency: bool = True,
    method: str = "exact",
    node_form: bool = True,
) -> xr.DataArray:
    """Retardation functions K_ij(t) = (2/π) ∫₀^∞ B_ij(ω) cos(ωt) dω of all couplings.

    Hjulstad (2004) eq. 5.15, Unneland (2007) eq. 2.60, Smogeli et al. (2004) eq. 34 (zero speed:
    B(∞) = 0).

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed.
    t
        Times, s (default :func:`default_time_grid`).
    tail
        High-frequency tail beyond the data: ``"auto"`` (the better fitting of an
        exponential and a power law, per coupling), ``"exponential"``, ``"power"`` or
        ``"none"`` (truncate at the last frequency). See :func:`fit_damping_tail`.
    interpolation
        ``"linear"`` (piecewise linear between the data points) or ``"pchip"``
        (shape-preserving cubic, resampled 4× and integrated exactly).
    zero_frequency
        Add the point B(0) = 0 (true at zero speed); otherwise the integral starts at
        the lowest frequency (truncation).
    method
        ``"exact"``: exact integration of the interpolant (Filon-type, see
        :mod:`cummins.radiation.transforms`); ``"trapezoid"``: the plain trapezoid rule on the
        data grid, no tail (the textbook approach, kept as a reference).
    node_form
        As :func:`~cummins.radiation.transforms.cosine_transform`'s (``"exact"``): False,
        the segment form at every time (the same numbers to rounding, slower).

    Returns
    -------
    xarray.DataArray
        ``retardation_function`` with dims (time, influenced_dof, radiating_dof); the
        attributes record the options, and ``tail_kind``/``tail_rate`` coordinates the
        fitted tail of each coupling.

    Examples
    --------
    >>> import cummins
    >>> k = cummins.retardation_function(cummins.demo_dataset(), t=[0.0, 5.0])
    >>> float(k.sel(time=0.0, influenced_dof="Heave", radiating_dof="Heave")) > 0
    True
    """
    ds = single_speed(ds)
    t = default_time_grid(ds) if t is None else np.asarray(t, dtype=float).reshape(-1)
    if np.any(t < 0) or not np.all(np.isfinite(t)):
        raise HydroDataError("times must be finite and non-negative")
    n = ds.sizes["influenced_dof"]
    if method == "trapezoid":
        w = ds.omega.values
        b = dof_matrix(ds, "radiation_damping").reshape(w.size, n * n)
        if zero_frequency:
            w, b = np.r_[0.0, w], np.vstack([np.zeros((1, n * n)), b])
        k = np.trapezoid(np.cos(np.outer(w, t))[:, :, None] * b[:, None, :], w, axis=0)
        tail_fit = fit_damping_tail(w, b, "none")
    elif method == "exact":
        k, tail_fit = _exact_kernel(ds, t, tail, interpolation, zero_frequency, node_form=node_form)
    else:
        raise HydroDataError(f"unknown method {method!r}", hint="use 'exact' or 'trapezoid'")
    values = (2.0 / np.pi) * k.reshape(t.size, n, n)
    coords = {"time": ("time", t, {"units": "s"}), **coupling_coords(ds)}
    coords["tail_kind"] = (
        ("influenced_dof", "radiating_dof"),
        tail_fit.kind.reshape(n, n).astype(str),
    )
    coords["tail_rate"] = (("influenced_dof", "radiating_dof"), tail_fit.rate.reshape(n, n))
    return xr.DataArray(
        values,
        dims=("time", "influenced_dof", "radiating_dof"),
        coords=coords,
        name="retardation_function",
        attrs={
            "units": _K_UNITS,
            "long_name": "retardation function K(t) = (2/pi) int B(w) cos(wt) dw",
            "method": method,
            "tail": tail if method == "exact" else "none",
            "interpolation": interpolation,
            "zero_frequency": int(zero_frequency),
        },
    )


def _exact_kernel(ds, t, tail, interpolation, zero_frequency, columns=None, node_form=True):
    """(∫ B cos ωt dω of the data's interpolant and its tail, (len(t), n²) or of the
    ``columns`` of the flattened couplings alone; the tail fit)."""
    n, w, b = ds.sizes["influenced_dof"], *_damping_grid(ds, interpolation, zero_frequency)
    data = dof_matrix(ds, "radiation_damping").reshape(ds.sizes["omega"], n * n)
    added = dof_matrix(ds, "added_mass").reshape(ds.sizes["omega"], n * n)
    return _kernel_of_arrays(ds.omega.values, data, added, (w, b), t, tail, columns, node_form)


def _kernel_of_arrays(omega, data, added, grid, t, tail, columns=None, node_form=True):
    """:func:`_exact_kernel` of the arrays: ``omega`` (N,), B ``data`` and A ``added``
    (N, P), ``grid`` the interpolant's frequencies and B (:func:`_interpolant_grid`)."""
    w, b = grid
    tail_fit = fit_damping_tail(omega, data, tail, added_mass=added)
    if columns is not None:
        b = b[:, columns]
    k = cosine_transform(w, b, t, node_form=node_form)
    return k + tail_fit.cosine(t, columns, node_form=node_form), tail_fit


def diagonal_retardation_functions(ds: xr.Dataset, t: ArrayLike, dofs) -> NDArray[np.float64]:
    """K_ii(t) of the DOFs ``dofs`` (indices) alone, shape (len(t), len(dofs)): the numbers
    of :func:`retardation_function` (default options) on its diagonal, without the
    transforms of the other couplings (their tails are fitted all the same: the grid of
    the power-law tails is common to all).

    Read-only: the last answer is kept, by the digest of the data, ``t`` and ``dofs`` (a
    fit and its refit with A∞ estimated ask for the same)."""
    ds, t = single_speed(ds), np.asarray(t, dtype=float).reshape(-1)
    columns = np.asarray(dofs, dtype=int) * (ds.sizes["influenced_dof"] + 1)
    key = digest(
        np.asarray(ds.omega.values, dtype=float),
        dof_matrix(ds, "radiation_damping"),
        dof_matrix(ds, "added_mass"),
        t,
        columns,
    )
    kept = _last_diagonal.get(key)
    if kept is not None:
        return kept
    out = (2.0 / np.pi) * _exact_kernel(ds, t, "auto", "linear", True, columns)[0]
    out.flags.writeable = False
    return _last_diagonal.keep(key, out)


#: The last answer of :func:`diagonal_retardation_functions` (K_ii(t), read-only).
_last_diagonal = LastAnswer()


def retardation_function_from_added_mass(
    ds: xr.Dataset,
    t: ArrayLike | None = None,
    *,
    added_mass_inf: xr.DataArray | None = None,
) -> xr.DataArray:
    """K(t) = −(2/π) ∫₀^{ω_N} ω (A(ω) − A∞) sin(ωt) dω, a cross-check of the damping route.

    Hjulstad (2004) eq. 5.14, Unneland (2007) eq. 2.61. It converges more slowly than the damping
    route (ω(A − A∞) decays like 1/ω) and is truncated at the last frequency: use it to
    check causality (the two routes agree for t > 0 when A and B are a consistent
    pair), not as the retardation function. K(0) is 0 by construction.
    """
    ds = single_speed(ds)
    t = default_time_grid(ds) if t is None else np.asarray(t, dtype=float).reshape(-1)
    a_inf = added_mass_inf if added_mass_inf is not None else _added_mass_inf_matrix(ds)
    n = ds.sizes["influenced_dof"]
    w = ds.omega.values
    f = w[:, None, None] * (dof_matrix(ds, "added_mass") - np.asarray(a_inf))
    f = np.vstack([np.zeros((1, n, n)), f]).reshape(w.size + 1, n * n)
    k = -(2.0 / np.pi) * sine_transform(np.r_[0.0, w], f, t)
    return xr.DataArray(
        k.reshape(t.size, n, n),
        dims=("time", "influenced_dof", "radiating_dof"),
        coords={"time": ("time", t, {"units": "s"}), **coupling_coords(ds)},
        name="retardation_function",
        attrs={"units": _K_UNITS, "long_name": "K(t) from the added mass (sine transform)"},
    )


# --------------------------------------------------------------------------- consistency


def kramers_kronig_added_mass(
    ds: xr.Dataset, *, added_mass_inf: ArrayLike | None = None, tail: str = "auto"
) -> xr.DataArray:
    """A(ω) predicted from B by Kramers–Kronig: A∞ + (2/π) PV ∫ B(ν)/(ν² − ω²) dν (eq. 5.23)."""
    ds = single_speed(ds)
    a_inf = _added_mass_inf_matrix(ds) if added_mass_inf is None else np.asarray(added_mass_inf)
    values = a_inf[None] + _kramers_kronig_integral(ds, tail)
    return xr.DataArray(
        values,
        dims=("omega", "influenced_dof", "radiating_dof"),
        coords={"omega": ds.omega, **coupling_coords(ds)},
        name="added_mass",
        attrs={"long_name": "added mass predicted from the damping (Kramers-Kronig)"},
    )


def kramers_kronig_error(
    ds: xr.Dataset, *, added_mass_inf: ArrayLike | None = None, tail: str = "auto"
) -> xr.DataArray:
    """Relative disagreement between A(ω) and its Kramers–Kronig prediction from B.

    ‖A − A_KK‖ / ‖A − A∞‖ over the trusted frequencies, per coupling (RMS norms;
    Hjulstad (2004) eq. 5.23, Unneland (2007) eq. 2.63): 0 for a causal, consistent pair. Couplings
    whose A − A∞ is negligible compared with the diagonal terms get the error scaled by
    √(|A_ii − A∞_ii| |A_jj − A∞_jj|) instead.
    """
    ds = single_speed(ds)
    a_inf = _added_mass_inf_matrix(ds) if added_mass_inf is None else np.asarray(added_mass_inf)
    a = dof_matrix(ds, "added_mass")
    predicted = kramers_kronig_added_mass(ds, added_mass_inf=a_inf, tail=tail).values
    keep = trusted_frequencies(ds)
    dev = np.sqrt(np.mean((a - a_inf[None])[keep] ** 2, axis=0))
    err = np.sqrt(np.mean((a - predicted)[keep] ** 2, axis=0))
    diag = np.diag(dev)
    scale = np.maximum(dev, 1e-3 * np.sqrt(np.outer(diag, diag)))
    with np.errstate(invalid="ignore", divide="ignore"):
        rel = np.where(scale > 0, err / scale, 0.0)
    return xr.DataArray(
        rel,
        dims=("influenced_dof", "radiating_dof"),
        coords=coupling_coords(ds),
        name="kramers_kronig_error",
        attrs={"long_name": "relative Kramers-Kronig error of A(w) predicted from B(w)"},
    )


#: A DOF's A(ω) departs from what its B(ω) implies where Ogilvie's A∞ estimate at that
#: frequency (:func:`added_mass_inf_per_frequency`) is further than CAUSAL_DEPARTURE × the
#: DOF's scale from its median over the trusted frequencies; the scale is the larger of
#: that median and the median |A_ii(ω)|.
CAUSAL_DEPARTURE = 0.1
#: … and the data are said to depart from a frequency on when that holds there and at
#: this share of the frequencies above it (an irregular frequency's pole crosses the
#: median now and then), over at least three frequencies.
CAUSAL_DEPARTURE_SHARE = 0.8


def causal_limits(
    ds: xr.Dataset, *, tol: float = CAUSAL_DEPARTURE
) -> dict[str, tuple[float, float]]:
    """Per DOF, where A(ω) stops agreeing with what B(ω) implies, to the last frequency.

    For a causal pair, A(ω) − (2/π) PV∫ B(ν)/(ν² − ω²) dν is the same constant A∞ at every
    frequency (Kramers–Kronig, Hjulstad (2004) eq. 5.23). Near an irregular frequency of a
    panel method A(ω) takes a pole's shape, B(ω) a spike, and the A(ω) above it is often
    off for the rest of the data (the ITI barge from WAMIT without irregular-frequency
    removal: heave's estimate 30 % below its median from 2.8 to the last frequency,
    5 rad/s, while the spikes end at 3.9 rad/s). A model, causal by construction, cannot
    follow such data there; fitted below that frequency the same data give a model that
    meets its targets.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed.
    tol
        Departure of the per-frequency estimate from its median, as a fraction of the
        DOF's scale (:data:`CAUSAL_DEPARTURE`).

    Returns
    -------
    dict
        DOF label → (ω₀, departure): the data depart from ω₀ (rad/s) to the last
        frequency (:data:`CAUSAL_DEPARTURE_SHARE` of them at least, in the upper half
        of the data), the median departure there as a fraction of the scale. DOFs whose
        data agree are absent.
    """
    ds = single_speed(ds)
    w = ds.omega.values
    if w.size < 6:
        return {}
    n = ds.sizes["influenced_dof"]  # Ogilvie's A∞ per frequency of the diagonal alone
    diagonal = np.arange(n) * (n + 1)
    a, b = (dof_matrix(ds, x).reshape(w.size, n * n) for x in ("added_mass", "radiation_damping"))
    estimate = a[:, diagonal] - kramers_kronig_integral(w, b, a, columns=diagonal)
    added_mass = np.abs(a[:, diagonal])
    trusted = trusted_frequencies(ds)
    out = {}
    for i, label in enumerate(str(d) for d in ds.influenced_dof.values):
        curve = estimate[:, i]
        if not np.all(np.isfinite(curve)):
            continue
        centre = float(np.median(curve[trusted]))
        scale = max(abs(centre), float(np.median(added_mass[:, i])))
        if not scale > 1e-6 * added_mass.max():
            continue
        off = np.abs(curve - centre) / scale
        departs = off > tol
        share = np.cumsum(departs[::-1])[::-1] / np.arange(w.size, 0, -1)
        start = np.flatnonzero(departs & (share >= CAUSAL_DEPARTURE_SHARE))
        start = start[start <= w.size - 3]
        # the departure must hold above a consistent part, not be the data's whole
        if start.size and start[0] >= w.size // 2:
            out[label] = (float(w[start[0]]), float(np.median(off[start[0] :])))
    return out


def reconstruct_added_mass_damping(
    kernel: xr.DataArray, added_mass_inf: ArrayLike, omega: ArrayLike
) -> xr.Dataset:
    """A(ω) and B(ω) from K(t) (Ogilvie; Hjulstad (2004) eqs. 5.11–5.12).

    B(ω) = ∫₀^{t_max} K(t) cos(ωt) dt and A(ω) = A∞ − (1/ω) ∫₀^{t_max} K(t) sin(ωt) dt,
    integrated exactly for the piecewise-linear K through its samples (truncated at
    the last time: K should have decayed there).

    Parameters
    ----------
    kernel
        Retardation functions (time, influenced_dof, radiating_dof).
    added_mass_inf
        A∞, (n, n).
    omega
        Frequencies, rad/s (> 0).

    Returns
    -------
    xarray.Dataset
        ``added_mass`` and ``radiation_damping`` on dims (omega, influenced_dof,
        radiating_dof).
    """
    t = kernel.time.values
    k = kernel.transpose("time", "influenced_dof", "radiating_dof").values
    n = k.shape[1]
    w = np.asarray(omega, dtype=float).reshape(-1)
    flat = k.reshape(t.size, n * n)
    b = cosine_transform(t, flat, w).reshape(w.size, n, n)
    a = np.asarray(added_mass_inf)[None] - (sine_transform(t, flat, w) / w[:, None]).reshape(
        w.size, n, n
    )
    dims = ("omega", "influenced_dof", "radiating_dof")
    coords = {
        "omega": ("omega", w, {"units": "rad/s"}),
        "influenced_dof": kernel.influenced_dof.values,
        "radiating_dof": kernel.radiating_dof.values,
    }
    return xr.Dataset({"added_mass": (dims, a), "radiation_damping": (dims, b)}, coords=coords)


def radiation_restoring(
    kernel: xr.DataArray, ds: xr.Dataset, added_mass_inf: ArrayLike
) -> xr.DataArray:
    """Hjulstad's radiation restoring coefficient c(ω) (Hjulstad (2004) eq. 5.5).

    c(ω) = ω² (A∞ − A(ω)) − ω ∫₀^{t_max} K(t) sin(ωt) dt, at the data frequencies:
    zero for consistent A, B, K and A∞; its size (N/m, N·m/rad) shows where they
    disagree (low-frequency truncation, irregular frequencies, an unsettled K).
    """
    ds = single_speed(ds)
    t = kernel.time.values
    k = kernel.transpose("time", "influenced_dof", "radiating_dof").values
    n = k.shape[1]
    w = ds.omega.values
    s = sine_transform(t, k.reshape(t.size, n * n), w).reshape(w.size, n, n)
    c = (
        w[:, None, None] ** 2 * (np.asarray(added_mass_inf)[None] - dof_matrix(ds, "added_mass"))
        - w[:, None, None] * s
    )
    return xr.DataArray(
        c,
        dims=("omega", "influenced_dof", "radiating_dof"),
        coords={"omega": ds.omega, **coupling_coords(ds)},
        name="radiation_restoring",
        attrs={"long_name": "radiation restoring coefficient c(w) (0 for consistent data)"},
    )


def truncate_retardation(
    kernel: xr.DataArray, t_max: float, *, method: str = "subtract", taper_fraction: float = 0.05
) -> xr.DataArray:
    """End K(t) at ``t_max`` so that it is exactly zero there (Hjulstad (2004) §10.2).

    ``"subtract"``: K̃(t) = K(t) − K(t_max) for t ≤ t_max (the subtracted constant acts
    like a small restoring term); ``"taper"``: multiply the last ``taper_fraction`` of
    [0, t_max] by a linear ramp from 1 to 0. Times beyond t_max are dropped.
    """
    t = kernel.time.values
    if not t[0] < t_max <= t[-1]:
        raise HydroDataError(
            f"t_max = {t_max:g} s is outside the kernel's times {t[0]:g}–{t[-1]:g} s"
        )
    k = kernel.sel(time=slice(None, t_max))
    if k.time.values[-1] < t_max:  # put a sample exactly at t_max
        end = kernel.interp(time=[t_max])
        k = xr.concat([k, end], dim="time")
    if method == "subtract":
        out = k - k.isel(time=-1)
    elif method == "taper":
        tt = k.time.values
        start = t_max * (1 - taper_fraction)
        ramp = np.clip((t_max - tt) / (t_max - start), 0.0, 1.0)
        out = k * xr.DataArray(ramp, dims="time", coords={"time": tt})
    else:
        raise HydroDataError(
            f"unknown truncation method {method!r}", hint="use 'subtract' or 'taper'"
        )
    out.attrs = {**kernel.attrs, "truncation": f"{method} at {t_max:g} s"}
    out.name = kernel.name
    return out


# --------------------------------------------------------------------------- diagnostics


def coupling_sizes(ds: xr.Dataset, *, either: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """The size of each coupling as the fit judges it, and which DOFs it models.

    The size of (i, j) is the larger of max|B_ij| and the range of A_ij, each over the
    geometric mean of the same measure for the two diagonal terms (0 where that mean is
    0); a DOF is modelled unless its damping is negligible (below 10⁻⁶) against the
    other DOFs of its kind (translations, rotations: the yaw of an axisymmetric body).
    With ``either``, X_ij and X_ji count alike (the larger).

    Returns
    -------
    sizes : numpy.ndarray
        (n, n), dimensionless; 1 on a diagonal that varies.
    modelled : numpy.ndarray
        (n,), bool.
    """
    ds = single_speed(ds)
    b = np.abs(dof_matrix(ds, "radiation_damping")).max(axis=0)
    a = np.ptp(dof_matrix(ds, "added_mass"), axis=0)
    if either:
        a, b = np.maximum(a, a.T), np.maximum(b, b.T)
    labels = [str(d) for d in ds.influenced_dof.values]
    rotation = np.array([is_rotation(lab) for lab in labels])
    diag_b = np.diag(b)
    modelled = np.array(
        [diag_b[i] > 1e-6 * diag_b[rotation == rotation[i]].max() for i in range(len(labels))]
    )
    sizes = np.zeros(b.shape)
    for m in (a, b):
        scale = np.sqrt(np.outer(np.diag(m), np.diag(m)))
        with np.errstate(divide="ignore", invalid="ignore"):
            sizes = np.maximum(sizes, np.where(scale > 0, m / scale, 0.0))
    return sizes, modelled


def significant_couplings(
    ds: xr.Dataset, threshold: float = 0.01, *, either: bool = False
) -> list[tuple[int, int]]:
    """(i, j) with i ≤ j whose damping or added-mass variation is not negligible.

    A coupling is kept when max|B_ij| or the range of A_ij exceeds ``threshold`` times
    the geometric mean of the same measure for B_ii and B_jj (or A_ii, A_jj)
    (:func:`coupling_sizes`); diagonal terms are kept unless they are negligible against
    the other DOFs of their kind (e.g. the yaw of an axisymmetric body), and the
    couplings of such a DOF are left out too (a DOF without damping cannot have coupled
    damping in passive data). With ``either``, a pair is kept when X_ij or X_ji is (data
    that are not reciprocal: :mod:`cummins.radiation.fit.reciprocity`); else X_ij decides.
    """
    sizes, modelled = coupling_sizes(ds, either=either)
    n = sizes.shape[0]
    out = []
    for i in range(n):
        for j in range(i, n):
            if i == j:
                if modelled[i]:
                    out.append((i, j))
                continue
            if not (modelled[i] and modelled[j]):
                continue  # no damping of its own: its couplings are numerical noise
            if sizes[i, j] > threshold:
                out.append((i, j))
    return out


def retardation_diagnostics(
    ds: xr.Dataset, t: ArrayLike | None = None, *, tail: str = "auto"
) -> xr.Dataset:
    """Per-coupling numbers that say how far K(t) and A∞ can be trusted.

    Returns
    -------
    xarray.Dataset
        On dims (influenced_dof, radiating_dof):

        * ``K0`` — K(0) = (2/π)∫B dω (kg/s² …), ``k_integral`` — ∫₀^{t_max} K dt, which
          must equal B(0) = 0 at zero speed (kg/s …), ``k_end_ratio`` — |K(t_max)|/max|K|;
        * ``tail_fraction`` — share of ∫B dω in the extrapolated tail;
        * ``added_mass_inf_estimate`` and ``added_mass_inf_spread`` — Ogilvie estimate
          and half the inter-quartile range over frequency; ``added_mass_inf_data`` — the
          solver's row (NaN when absent);
        * ``kramers_kronig_error`` — see :func:`kramers_kronig_error`;
        * ``significant`` — the coupling is not negligible (:func:`significant_couplings`).
    """
    ds = single_speed(ds)
    t = default_time_grid(ds) if t is None else np.asarray(t, dtype=float)
    kernel = retardation_function(ds, t, tail=tail)
    k = kernel.values
    n = k.shape[1]
    w = ds.omega.values
    data_b = dof_matrix(ds, "radiation_damping").reshape(w.size, n * n)
    added = dof_matrix(ds, "added_mass").reshape(w.size, n * n)
    tail_fit = fit_damping_tail(w, data_b, tail, added_mass=added)
    area_data = np.trapezoid(np.vstack([np.zeros((1, n * n)), data_b]), np.r_[0.0, w], axis=0)
    area_tail = tail_fit.area()
    with np.errstate(invalid="ignore", divide="ignore"):
        tail_fraction = np.where(
            np.abs(area_data) + np.abs(area_tail) > 0,
            np.abs(area_tail) / (np.abs(area_data) + np.abs(area_tail)),
            0.0,
        ).reshape(n, n)
        peak = np.abs(k).max(axis=0)
        end_ratio = np.where(peak > 0, np.abs(k[-1]) / peak, 0.0)
    estimate = added_mass_inf(ds, method="ogilvie", tail=tail)
    a_inf = dof_matrix(ds, "added_mass_inf") if "added_mass_inf" in ds else np.full((n, n), np.nan)
    kk = kramers_kronig_error(
        ds, added_mass_inf=estimate.values if "added_mass_inf" not in ds else None, tail=tail
    )
    significant = np.zeros((n, n), dtype=bool)
    for i, j in significant_couplings(ds):
        significant[i, j] = significant[j, i] = True
    dims = ("influenced_dof", "radiating_dof")
    out = xr.Dataset(
        {
            "K0": (dims, k[0]),
            "k_integral": (dims, np.trapezoid(k, t, axis=0)),
            "k_end_ratio": (dims, end_ratio),
            "tail_fraction": (dims, tail_fraction),
            "added_mass_inf_estimate": (dims, estimate.values),
            "added_mass_inf_spread": (dims, estimate.spread.values),
            "added_mass_inf_data": (dims, a_inf),
            "kramers_kronig_error": (dims, kk.values),
            "significant": (dims, significant),
        },
        coords={
            **coupling_coords(ds),
            "tail_kind": kernel.tail_kind,
            "tail_rate": kernel.tail_rate,
        },
        attrs={"t_max": float(t[-1]), "tail": tail},
    )
    return out


def retardation_dataset(
    ds: xr.Dataset, t: ArrayLike | None = None, *, tail: str = "auto", interpolation: str = "linear"
) -> xr.Dataset:
    """Everything ``cummins kernel`` writes: K(t), A∞ and the diagnostics, as one dataset.

    Variables: ``retardation_function`` (time, influenced_dof, radiating_dof);
    ``added_mass_inf`` (the data row when present, else the Ogilvie estimate; with its
    ``spread``); ``added_mass_inf_per_frequency`` (omega, influenced_dof, radiating_dof);
    and those of :func:`retardation_diagnostics`. Attributes carry the source file,
    its history and the options used.
    """
    ds = single_speed(ds)
    t = default_time_grid(ds) if t is None else np.asarray(t, dtype=float).reshape(-1)
    kernel = retardation_function(ds, t, tail=tail, interpolation=interpolation)
    used = added_mass_inf(ds, tail=tail)
    out = retardation_diagnostics(ds, t, tail=tail)
    out["retardation_function"] = kernel.drop_vars(["tail_kind", "tail_rate"])
    out["added_mass_inf"] = used.drop_vars("spread")
    out["added_mass_inf"].attrs = {"method": used.attrs["method"], "units": used.attrs["units"]}
    out["added_mass_inf_per_frequency"] = added_mass_inf_per_frequency(ds, tail=tail)
    out.attrs.update(
        source_file=str(ds.attrs.get("source_file", "")),
        source_format=str(ds.attrs.get("source_format", "")),
        history=str(ds.attrs.get("history", "")),
        interpolation=interpolation,
        added_mass_inf_method=used.attrs["method"],
    )
    return out
