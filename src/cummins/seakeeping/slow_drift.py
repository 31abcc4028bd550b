"""Slow drift in the frequency domain: the mean and slowly varying second-order force and
the low-frequency response of a moored body, with the full QTF or Newman's approximation.

With the force convention of :mod:`cummins.qtf.data` (F⁻(t) = Re Σ_i Σ_j c_i c_j* Q⁻ e^{i(ω_i
− ω_j)t}, the full square) and a Gaussian sea of one-sided spectrum S(ω) (amplitudes
a_i² = 2 S(ω_i) Δω, independent uniform phases):

* the mean force F̄ = Σ a_i² Q⁻(ω_i, ω_i) = 2 ∫ S(ω) Q⁻(ω, ω) dω;
* each unordered pair (i, j) adds 2 a_i a_j |Q⁻_ij| cos(μ_ij t + …), of variance
  2 a_i² a_j² |Q⁻_ij|² = 8 S_i S_j |Q⁻_ij|² Δω², so the one-sided spectrum of the slowly
  varying part is S_F(μ) = 8 ∫₀^∞ S(ω) S(ω + μ) |Q⁻(ω + μ, ω)|² dω (Pinkster (1980);
  Faltinsen (1990) ch. 5, with T_ij the same QTF) and its cross-spectra between DOFs k,
  l: S_F,kl(μ) = 8 ∫ S(ω) S(ω + μ) Q⁻_k(ω + μ, ω) Q⁻_l(ω + μ, ω)* dω; the variance of the
  slowly varying force is ∫₀^∞ S_F(μ) dμ;
* the low-frequency response x(μ) = H(μ) F(μ), H = Z⁻¹ the body's transfer function (its
  added mass and damping at the difference frequency, a mooring stiffness, a linear
  damping), has the one-sided spectral matrix S_x(μ) = H(μ) S_F(μ) H(μ)ᴴ.

Newman's approximation Q⁻(ω₁, ω₂) ≈ ½(Q⁻(ω₁, ω₁) + Q⁻(ω₂, ω₂)) (Newman (1974)) uses only
the mean drift (the diagonal); :func:`newman_vs_full` compares the standard deviations of
the force and of the moored response each way, per DOF, so that one sees when it is
enough (it is, where the QTF varies little across μ ≲ the natural frequency).

Short-crested seas: directions β_d with weights w_d (Σ w_d = 1, from
:func:`cummins.seakeeping.waves.spreading_directions`), the double sum over direction pairs
with Q(ω₁, ω₂, β_d, β_e) (a unidirectional QTF at the mean direction: the approximation of
:mod:`cummins.qtf.interpolation`).

:func:`qtf_grid_advice` says what a QTF's grid covers: the seas whose energy lies within
its frequencies, and the difference frequencies it resolves — a slow-drift resonance at
μ_n = 2π/T_n needs grid spacing Δω ≤ μ_n/2 (at least two off-diagonals below μ_n), below
which the force is interpolated from the mean drift and the first off-diagonal only.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import ArgumentError
from cummins.qtf.data import QTFTable
from cummins.qtf.interpolation import interpolate
from cummins.seakeeping.spectra import energy_range, jonswap
from cummins.seakeeping.waves import spreading_directions

Spectrum = Callable[[NDArray[np.float64]], NDArray[np.float64]]


# --------------------------------------------------------------------------- grid advice


@dataclass(frozen=True)
class GridAdvice:
    """What a QTF's frequency grid covers (:func:`qtf_grid_advice`).

    Attributes
    ----------
    spacing
        Largest step Δω of the grid, rad/s.
    omega_range
        The grid's range (ω_min, ω_max), rad/s.
    longest_resolved_period
        Longest slow-drift natural period T_n the grid resolves, π/Δω (Δω ≤ μ_n/2), s.
    peak_periods
        Peak periods (T_p min, T_p max) of JONSWAP seas (γ 3.3) with 99 % of their
        energy within the grid, s (NaN if none).
    energy_outside
        Share of a given spectrum's energy outside the grid (None without one).
    notes
        One line per finding.
    """

    spacing: float
    omega_range: tuple[float, float]
    longest_resolved_period: float
    peak_periods: tuple[float, float]
    energy_outside: float | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)


def _energy_share_outside(spectrum: Spectrum, lo: float, hi: float) -> float:
    w = np.geomspace(1e-3, 1e2, 20000)
    s = np.asarray(spectrum(w), dtype=float)
    total = np.trapezoid(s, w)
    inside = (w >= lo) & (w <= hi)
    return float(1.0 - np.trapezoid(np.where(inside, s, 0.0), w) / total) if total > 0 else 0.0


def _jonswap_peak_periods(lo: float, hi: float) -> tuple[float, float]:
    """Peak periods of JONSWAP (γ 3.3) seas whose 99 % energy range is inside [lo, hi]."""
    tp = np.geomspace(1.0, 40.0, 120)
    ok = []
    for t in tp:
        a, b = energy_range(lambda w, t=t: jonswap(w, 1.0, t), 1e-2)
        ok.append(a >= lo and b <= hi)
    ok = np.asarray(ok)
    if not ok.any():
        return (np.nan, np.nan)
    return float(tp[ok].min()), float(tp[ok].max())


def qtf_grid_advice(
    table: QTFTable,
    *,
    spectrum: Spectrum | None = None,
    natural_periods: dict[str, float] | None = None,
) -> GridAdvice:
    """What the QTF's grid covers, and whether it suits a sea and the moored modes.

    Parameters
    ----------
    table
        The QTF.
    spectrum
        S(ω) of the sea it will be used in (optional): the share of its energy outside
        the grid has no second-order force.
    natural_periods
        Natural periods of the slow-drift modes, s, by DOF (optional): each needs
        Δω ≤ π/T_n.

    Returns
    -------
    GridAdvice
    """
    w = table.omega
    step = float(np.diff(w).max()) if w.size > 1 else np.inf
    lo, hi = float(w[0]), float(w[-1])
    longest = np.pi / step if np.isfinite(step) else 0.0
    peaks = _jonswap_peak_periods(lo, hi)
    notes = [
        f"the QTF covers {lo:.3g}–{hi:.3g} rad/s in steps of up to {step:.3g} rad/s: JONSWAP "
        + (
            f"seas (gamma 3.3) of peak period {peaks[0]:.3g}–{peaks[1]:.3g} s have 99 % of "
            "their energy inside"
            if np.isfinite(peaks[0])
            else "seas have energy outside it whatever their peak period"
        ),
        f"it resolves slow-drift natural periods up to {longest:.3g} s (dw <= pi/T_n); the "
        f"force at difference frequencies below {2 * step:.3g} rad/s is interpolated between "
        "the mean drift and the first off-diagonal",
    ]
    outside = None
    if spectrum is not None:
        outside = _energy_share_outside(spectrum, lo, hi)
        if outside > 1e-3:
            notes.append(
                f"{100 * outside:.2g} % of the sea's energy lies outside the QTF's frequencies: "
                "no second-order force from it"
            )
    for dof, period in (natural_periods or {}).items():
        need = np.pi / float(period)
        if step > need:
            notes.append(
                f"{dof}: natural period {period:.4g} s (mu_n = {2 * np.pi / period:.3g} rad/s) "
                f"needs dw <= {need:.3g} rad/s; the grid has {step:.3g}"
            )
    return GridAdvice(step, (lo, hi), longest, peaks, outside, tuple(notes))


# --------------------------------------------------------------------------- force spectra


def _directions(
    direction: float, spreading: float | None, n_directions: int
) -> tuple[NDArray, NDArray]:
    if spreading is None:
        return np.array([float(direction)]), np.ones(1)
    return spreading_directions(direction, spreading, n_directions)


def _integration_grid(table: QTFTable, spectrum: Spectrum, n: int) -> NDArray:
    lo, hi = energy_range(spectrum, 1e-4)
    lo, hi = max(lo, table.omega[0]), min(hi, table.omega[-1])
    if not hi > lo:
        raise ArgumentError(
            "the sea has no energy within the QTF's frequencies "
            f"{table.omega[0]:.4g}–{table.omega[-1]:.4g} rad/s"
        )
    return np.linspace(lo, hi, n)


def _diagonal(table: QTFTable, omega: NDArray, beta: NDArray) -> NDArray:
    """Re Q(ω, ω, β, β) (bilinear, as the time domain), shape (*omega.shape, d)."""
    return interpolate(table, omega, omega, beta, beta).real


def mean_drift(
    table: QTFTable,
    spectrum: Spectrum,
    *,
    direction: float = 0.0,
    spreading: float | None = None,
    n_directions: int = 9,
    n_omega: int = 4000,
) -> xr.DataArray:
    """The mean second-order force 2 Σ_d w_d ∫ S(ω) Q⁻(ω, ω, β_d, β_d) dω per DOF (N, N·m).

    Parameters
    ----------
    table
        The difference-frequency QTF.
    spectrum
        S(ω), m²·s/rad.
    direction, spreading, n_directions
        Mean direction of travel (rad) and the cos-2s spreading (None: long-crested).
    n_omega
        Points of the trapezoidal rule over the sea's energy range within the QTF.
    """
    w = _integration_grid(table, spectrum, n_omega)
    s = np.asarray(spectrum(w), dtype=float)
    betas, weights = _directions(direction, spreading, n_directions)
    total = np.zeros(len(table.dofs))
    for b, wd in zip(betas, weights, strict=True):
        q = _diagonal(table, w, np.full(w.shape, b))
        total += wd * 2.0 * np.trapezoid(s[:, None] * q, w, axis=0)
    return xr.DataArray(total, dims="influenced_dof", coords={"influenced_dof": list(table.dofs)})


def slow_drift_spectrum(
    table: QTFTable,
    spectrum: Spectrum,
    mu: ArrayLike,
    *,
    direction: float = 0.0,
    spreading: float | None = None,
    n_directions: int = 9,
    newman: bool = False,
    n_omega: int = 1000,
) -> xr.DataArray:
    """The one-sided cross-spectra S_F,kl(μ) of the slowly varying force (module docstring).

    Parameters
    ----------
    table
        The difference-frequency QTF.
    spectrum
        S(ω), m²·s/rad.
    mu
        Difference frequencies μ > 0, rad/s.
    direction, spreading, n_directions
        As :func:`mean_drift`.
    newman
        Use Newman's approximation ½(Q(ω₁, ω₁) + Q(ω₂, ω₂)) instead of the QTF.
    n_omega
        Points of the trapezoidal rule in ω.

    Returns
    -------
    xarray.DataArray
        Complex (Hermitian in the DOFs), dims (``mu``, ``influenced_dof``,
        ``influenced_dof_2``), N²·s/rad (N²·m²·s/rad for moments).
    """
    mu = np.asarray(mu, dtype=float).reshape(-1)
    if np.any(mu <= 0) or not np.all(np.isfinite(mu)):
        raise ArgumentError("the difference frequencies mu must be finite and > 0 (rad/s)")
    w = _integration_grid(table, spectrum, n_omega)
    s1 = np.asarray(spectrum(w), dtype=float)
    betas, weights = _directions(direction, spreading, n_directions)
    d = len(table.dofs)
    out = np.zeros((mu.size, d, d), dtype=complex)
    chunk = max(1, 200_000 // w.size)
    dw = w[1] - w[0]
    for b1, w1 in zip(betas, weights, strict=True):
        low = _diagonal(table, w, np.full(w.shape, b1)) if newman else None
        for b2, w2 in zip(betas, weights, strict=True):
            for start in range(0, mu.size, chunk):
                m = mu[start : start + chunk, None]
                hi = w[None, :] + m  # the higher frequency of the pair, Q(ω + μ, ω): e^{+iμt}
                s2 = np.asarray(spectrum(hi.reshape(-1)), dtype=float).reshape(hi.shape)
                if newman:
                    q = 0.5 * (_diagonal(table, hi, np.full(hi.shape, b2)) + low[None]).astype(
                        complex
                    )
                    q[hi > table.omega[-1]] = 0.0
                else:
                    q = interpolate(table, hi, w[None, :], b2, b1)
                weight = (8.0 * w1 * w2 * dw) * s1[None, :] * s2
                out[start : start + chunk] += np.swapaxes(weight[..., None] * q, 1, 2) @ np.conj(q)
    labels = list(table.dofs)
    return xr.DataArray(
        out,
        dims=("mu", "influenced_dof", "influenced_dof_2"),
        coords={"mu": mu, "influenced_dof": labels, "influenced_dof_2": labels},
        attrs={
            "units": "N^2 s/rad (force), N^2 m^2 s/rad (moment)",
            "long_name": "one-sided cross-spectra of the slowly varying second-order force",
            "approximation": "Newman" if newman else "full QTF",
        },
    )


# --------------------------------------------------------------------------- response


def response_spectrum(force_spectrum: xr.DataArray, transfer: ArrayLike) -> xr.DataArray:
    """S_x(μ) = H(μ) S_F(μ) H(μ)ᴴ, one-sided, from the force cross-spectra and the
    transfer functions H(μ) (nμ, n, n) of the body (x = H F; e.g. ``inv(Z(μ))`` of
    :meth:`cummins.vessel.Vessel.impedance` or
    :func:`cummins.seakeeping.frequency_domain.impedance`)."""
    h = np.asarray(transfer, dtype=complex)
    sf = force_spectrum.values
    if h.shape != sf.shape:
        raise ArgumentError(f"transfer functions of shape {h.shape}; the force spectra {sf.shape}")
    sx = h @ sf @ np.conj(np.swapaxes(h, 1, 2))
    return force_spectrum.copy(data=sx).assign_attrs(
        units="m^2 s/rad (translation), rad^2 s/rad (rotation)",
        long_name="one-sided cross-spectra of the slow-drift motions",
    )


def standard_deviation(spectra: xr.DataArray) -> xr.DataArray:
    """√∫ S_kk(μ) dμ per DOF (trapezoidal rule over the spectra's μ)."""
    mu = spectra.mu.values
    diag = np.real(np.diagonal(spectra.values, axis1=1, axis2=2))
    var = np.trapezoid(diag, mu, axis=0)
    return xr.DataArray(
        np.sqrt(np.maximum(var, 0.0)),
        dims="influenced_dof",
        coords={"influenced_dof": spectra.influenced_dof.values},
    )


@dataclass(frozen=True)
class SlowDriftComparison:
    """Newman against the full QTF (:func:`newman_vs_full`): per DOF, the standard
    deviations of the slowly varying force and (with a transfer function) of the
    response each way, and the mean force."""

    mean_force: xr.DataArray
    force_std_full: xr.DataArray
    force_std_newman: xr.DataArray
    response_std_full: xr.DataArray | None = None
    response_std_newman: xr.DataArray | None = None

    def table(self) -> xr.Dataset:
        """All of it as one dataset (dim ``influenced_dof``)."""
        data = {
            "mean_force": self.mean_force,
            "force_std_full": self.force_std_full,
            "force_std_newman": self.force_std_newman,
        }
        if self.response_std_full is not None:
            data["response_std_full"] = self.response_std_full
            data["response_std_newman"] = self.response_std_newman
        return xr.Dataset(data)


def newman_vs_full(
    table: QTFTable,
    spectrum: Spectrum,
    *,
    mu: ArrayLike | None = None,
    transfer: Callable[[NDArray], NDArray] | None = None,
    **sea,
) -> SlowDriftComparison:
    """The slow-drift force (and response) standard deviations with the full QTF and with
    Newman's approximation, per DOF.

    Parameters
    ----------
    table
        The difference-frequency QTF.
    spectrum
        S(ω), m²·s/rad.
    mu
        Difference frequencies, rad/s (default: 400 from 10⁻³ to 0.5 rad/s or the QTF's
        span if smaller: the slowly varying band, periods above 12.6 s, where Newman's
        approximation is meant to hold; the force's standard deviations are over it).
    transfer
        μ → H(μ) (nμ, n, n) of the body, for the response (optional).
    **sea
        ``direction``, ``spreading``, ``n_directions`` as :func:`mean_drift`.
    """
    if mu is None:
        mu = np.linspace(1e-3, min(0.5, float(table.omega[-1] - table.omega[0])), 400)
    mu = np.asarray(mu, dtype=float)
    full = slow_drift_spectrum(table, spectrum, mu, **sea)
    newman = slow_drift_spectrum(table, spectrum, mu, newman=True, **sea)
    out = {
        "mean_force": mean_drift(table, spectrum, **sea),
        "force_std_full": standard_deviation(full),
        "force_std_newman": standard_deviation(newman),
    }
    if transfer is not None:
        h = transfer(mu)
        out["response_std_full"] = standard_deviation(response_spectrum(full, h))
        out["response_std_newman"] = standard_deviation(response_spectrum(newman, h))
    return SlowDriftComparison(**out)
