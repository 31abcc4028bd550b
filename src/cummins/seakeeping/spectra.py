"""Sea-state spectra: one-sided wave spectra S(ω) and the range holding their energy.

Spectra are one-sided, S(ω) in m²·s/rad, with ∫₀^∞ S dω = m₀ = (H_s/4)². Every spectrum
here is normalised so that 4√m₀ = H_s exactly (to quadrature accuracy, 1e-10), not with
the usual approximate closed-form factors:

* :func:`pierson_moskowitz`: the ITTC / Bretschneider two-parameter spectrum,
  S = (5/16) H_s² ω_p⁴ ω⁻⁵ exp(−(5/4)(ω_p/ω)⁴), exactly normalised in closed form.
* :func:`jonswap`: the same shape times the peak enhancement γ^r(ω), r = exp(−(ω −
  ω_p)²/(2σ²ω_p²)), σ = σ_a below ω_p and σ_b above. The usual normalising factor
  (1 − 0.287 ln γ) is an approximation (0.2 % off at γ = 3.3, 1.8 % at γ = 7, 7 % at
  γ = 10); here the integral of the normalised shape ∫₀^∞ x⁻⁵ e^{−1.25 x⁻⁴} γ^{r(x)} dx
  (x = ω/ω_p) is computed once per (γ, σ_a, σ_b) by adaptive quadrature and divides the
  shape.
* :func:`torsethaugen`: the simplified double-peaked spectrum of
  Torsethaugen & Haver (2004) (as in DNV-RP-C205 §3.5.6), a wind-sea and a swell peak,
  each of the form x⁻⁴ e^{−x⁻⁴} γ^{r(x)} normalised numerically to carry H_j²/16, with
  H₁² + H₂² = H_s².

:func:`wave_spectrum` binds a spectrum's parameters by name (for
:func:`cummins.seakeeping.waves.irregular_waves` and the CLI); :func:`energy_range` gives
the frequency range holding all but a fraction of its energy. All are re-exported by
:mod:`cummins.seakeeping.waves`.
"""

from __future__ import annotations

import functools
import math
import warnings
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import ArgumentError, CumminsWarning
from cummins.validation import non_negative, positive

__all__ = [
    "SPECTRA",
    "energy_range",
    "jonswap",
    "pierson_moskowitz",
    "range_within_data",
    "torsethaugen",
    "torsethaugen_parameters",
    "wave_spectrum",
]

#: Standard gravity, m/s² (the default of the wave functions; a ``HydroDB`` has its own ``g``).
G = 9.81

Spectrum = Callable[[NDArray[np.float64]], NDArray[np.float64]]


@functools.lru_cache(maxsize=256)
def _shape_integral(n: int, gamma: float, sigma_a: float, sigma_b: float) -> float:
    """∫₀^∞ x⁻ⁿ exp(−(n/4) x⁻⁴) γ^{r(x)} dx, r = exp(−(x − 1)²/(2σ²)), σ = σ_a (x ≤ 1), σ_b."""

    def shape(x: float) -> float:
        if x <= 0.0:
            return 0.0
        sigma = sigma_a if x <= 1.0 else sigma_b
        r = math.exp(-((x - 1.0) ** 2) / (2.0 * sigma**2))
        return x ** (-n) * math.exp(-(n / 4.0) * x ** (-4)) * gamma**r

    width = 8.0 * max(sigma_a, sigma_b)
    pieces = [(0.0, max(1.0 - width, 0.05)), (max(1.0 - width, 0.05), 1.0)]
    pieces += [(1.0, 1.0 + width), (1.0 + width, np.inf)]
    from scipy.integrate import quad  # on use: 0.15 s to import

    total = 0.0
    for a, b in pieces:
        value, _ = quad(shape, a, b, epsabs=0.0, epsrel=1e-12, limit=200)
        total += value
    return total


def _peak(
    omega: NDArray[np.float64],
    hs: float,
    tp: float,
    gamma: float,
    sigma_a: float,
    sigma_b: float,
    n: int,
) -> NDArray[np.float64]:
    """A peak H²/(16 ω_p) · x⁻ⁿ e^{−(n/4)x⁻⁴} γ^{r(x)} / ∫(…)dx: carries exactly H²/16."""
    omega = np.asarray(omega, dtype=float)
    out = np.zeros(omega.shape)
    if hs == 0.0:
        return out
    wp = 2.0 * np.pi / tp
    pos = omega > 0
    x = omega[pos] / wp
    sigma = np.where(x <= 1.0, sigma_a, sigma_b)
    r = np.exp(-((x - 1.0) ** 2) / (2.0 * sigma**2))
    with np.errstate(over="ignore", under="ignore"):
        shape = x ** (-n) * np.exp(-(n / 4.0) * x ** (-4.0)) * gamma**r
    norm = _shape_integral(n, float(gamma), float(sigma_a), float(sigma_b))
    out[pos] = hs**2 / (16.0 * wp) * shape / norm
    return out


def _check_sea(hs: float, tp: float) -> tuple[float, float]:
    hs = non_negative(hs, "the significant wave height hs", "m")
    tp = positive(tp, "the peak period tp", "s")
    return hs, tp


def jonswap(
    omega: ArrayLike,
    hs: float,
    tp: float,
    gamma: float = 3.3,
    sigma_a: float = 0.07,
    sigma_b: float = 0.09,
) -> NDArray[np.float64]:
    """JONSWAP spectrum S(ω), m²·s/rad, normalised so that 4√m₀ = H_s exactly.

    S(ω) = H_s²/(16 ω_p I) · x⁻⁵ exp(−(5/4) x⁻⁴) γ^{exp(−(x−1)²/(2σ²))}, x = ω/ω_p,
    ω_p = 2π/T_p, σ = σ_a for ω ≤ ω_p, σ_b above (Hasselmann et al. 1973; the form of
    de Haan (2022) §1.9 with α_J eliminated in favour of H_s), I = ∫₀^∞ x⁻⁵ e^{−1.25x⁻⁴} γ^{…} dx
    computed by quadrature (I = 1/5 for γ = 1, the Pierson–Moskowitz spectrum). The
    common factor (1 − 0.287 ln γ) approximates 1/(5I); it is not used.

    Parameters
    ----------
    omega
        Frequencies, rad/s (values ≤ 0 give 0).
    hs
        Significant wave height H_s = 4√m₀, m.
    tp
        Peak period, s: the maximum of S is at ω_p = 2π/T_p exactly.
    gamma
        Peak enhancement factor γ ≥ 1.
    sigma_a, sigma_b
        Relative widths of the peak enhancement below and above ω_p.

    Returns
    -------
    numpy.ndarray
        S(ω) with the shape of ``omega``, m²·s/rad.

    Examples
    --------
    >>> import numpy as np
    >>> w = np.geomspace(0.05, 100.0, 40000)
    >>> s = jonswap(w, hs=4.0, tp=10.0)
    >>> round(4 * float(np.sqrt(np.trapezoid(s, w))), 4)
    4.0
    """
    hs, tp = _check_sea(hs, tp)
    if not gamma >= 1.0:
        raise ArgumentError(f"JONSWAP gamma must be >= 1, got {gamma!r}")
    if not (sigma_a > 0 and sigma_b > 0):
        raise ArgumentError("JONSWAP sigma_a and sigma_b must be positive")
    return _peak(np.asarray(omega, dtype=float), hs, tp, gamma, sigma_a, sigma_b, 5)


def pierson_moskowitz(omega: ArrayLike, hs: float, tp: float) -> NDArray[np.float64]:
    """Pierson–Moskowitz spectrum in its two-parameter (ITTC, Bretschneider) form.

    S(ω) = (5/16) H_s² ω_p⁴ ω⁻⁵ exp(−(5/4)(ω_p/ω)⁴), ω_p = 2π/T_p: the ITTC (1978)
    spectrum A/ω⁵ exp(−B/ω⁴) written with the peak period (T_p = 1.408 T_z = 1.296 T_1).
    ∫₀^∞ S dω = H_s²/16 in closed form. Units as :func:`jonswap` (which it equals for γ = 1).
    """
    hs, tp = _check_sea(hs, tp)
    omega = np.asarray(omega, dtype=float)
    wp = 2.0 * np.pi / tp
    out = np.zeros(omega.shape)
    pos = omega > 0
    with np.errstate(over="ignore", under="ignore"):
        out[pos] = (
            5.0 / 16.0 * hs**2 * wp**4 * omega[pos] ** -5.0 * np.exp(-1.25 * (wp / omega[pos]) ** 4)
        )
    return out


def torsethaugen_parameters(hs: float, tp: float, *, g: float = G) -> list[dict[str, float]]:
    """The two peaks of the simplified Torsethaugen spectrum: [primary, secondary].

    Torsethaugen & Haver (2004), "Simplified double peak spectral model for ocean
    waves", ISOPE (also DNV-RP-C205 §3.5.6). With T_pf = 6.6 H_s^{1/3} (peak period of a
    fully developed sea), T_l = 2√H_s, T_u = 25 s:

    * wind dominated (T_p ≤ T_pf), ε_l = (T_pf − T_p)/(T_pf − T_l) clipped to [0, 1]:
      r = 0.7 + 0.3 exp(−(ε_l/0.5)²); primary H₁ = r H_s, T₁ = T_p,
      γ₁ = 35 (2π H₁/(g T_p²))^0.857; secondary (swell) H₂ = √(1 − r²) H_s,
      T₂ = T_pf + 2 s, γ₂ = 1;
    * swell dominated (T_p > T_pf), ε_u = (T_p − T_pf)/(T_u − T_pf) clipped to [0, 1]:
      r = 0.6 + 0.4 exp(−(ε_u/0.3)²); primary H₁ = r H_s, T₁ = T_p,
      γ₁ = 35 (2π H_s/(g T_pf²))^0.857 (1 + 6 ε_u); secondary (wind sea)
      H₂ = √(1 − r²) H_s, T₂ = 6.6 H₂^{1/3}, γ₂ = 1.

    γ is at least 1 (the steepness formula gives less for low, long seas).
    Each entry: ``hs``, ``tp``, ``gamma`` and ``kind`` ("wind" or "swell").
    """
    hs, tp = _check_sea(hs, tp)
    tpf = 6.6 * hs ** (1.0 / 3.0)
    if tp <= tpf:
        tl = 2.0 * np.sqrt(hs)
        eps = float(np.clip((tpf - tp) / (tpf - tl), 0.0, 1.0)) if tpf > tl else 1.0
        r = 0.7 + 0.3 * np.exp(-((eps / 0.5) ** 2))
        h1 = r * hs
        gamma1 = 35.0 * (2.0 * np.pi * h1 / (g * tp**2)) ** 0.857
        h2 = np.sqrt(max(1.0 - r**2, 0.0)) * hs
        primary = {"hs": h1, "tp": tp, "gamma": max(gamma1, 1.0), "kind": "wind"}
        secondary = {"hs": h2, "tp": tpf + 2.0, "gamma": 1.0, "kind": "swell"}
    else:
        eps = float(np.clip((tp - tpf) / (25.0 - tpf), 0.0, 1.0)) if tpf < 25.0 else 1.0
        r = 0.6 + 0.4 * np.exp(-((eps / 0.3) ** 2))
        h1 = r * hs
        gamma_f = 35.0 * (2.0 * np.pi * hs / (g * tpf**2)) ** 0.857
        h2 = np.sqrt(max(1.0 - r**2, 0.0)) * hs
        primary = {"hs": h1, "tp": tp, "gamma": max(gamma_f * (1.0 + 6.0 * eps), 1.0)}
        primary["kind"] = "swell"
        secondary = {"hs": h2, "tp": 6.6 * h2 ** (1.0 / 3.0) if h2 > 0 else tp, "gamma": 1.0}
        secondary["kind"] = "wind"
    return [primary, secondary]


def torsethaugen(omega: ArrayLike, hs: float, tp: float) -> NDArray[np.float64]:
    """Torsethaugen double-peaked (wind sea + swell) spectrum, simplified 2004 form.

    S(ω) = Σ_{j=1,2} H_j²/(16 ω_pj I_j) · x_j⁻⁴ exp(−x_j⁻⁴) γ_j^{r(x_j)}, x_j = ω/ω_pj,
    σ = 0.07/0.09 (Torsethaugen & Haver 2004; DNV-RP-C205 §3.5.6, whose G₀ = 3.26 and
    A_γ = (1 + 1.1 (ln γ)^1.19)/γ approximate 1/I_j); the peak parameters are those of
    :func:`torsethaugen_parameters`. Each peak is normalised by quadrature, so
    4√m₀ = H_s exactly. The peak at T_p is the primary one: S is largest there
    unless the secondary peak is within a few percent of it (near T_p = T_pf).

    Parameters
    ----------
    omega
        Frequencies, rad/s.
    hs, tp
        Significant wave height (m) and peak period of the primary peak (s).
    """
    omega = np.asarray(omega, dtype=float)
    out = np.zeros(omega.shape)
    for peak in torsethaugen_parameters(hs, tp):
        if peak["hs"] > 0:
            out += _peak(omega, peak["hs"], peak["tp"], peak["gamma"], 0.07, 0.09, 4)
    return out


#: Names accepted by :func:`wave_spectrum`.
SPECTRA: dict[str, str] = {
    "jonswap": "JONSWAP (gamma default 3.3)",
    "pm": "Pierson-Moskowitz / ITTC / Bretschneider (two-parameter)",
    "ittc": "alias of pm",
    "torsethaugen": "Torsethaugen double-peaked (simplified 2004 form)",
}


def wave_spectrum(
    name: str, hs: float, tp: float, gamma: float | None = None
) -> Callable[[ArrayLike], NDArray[np.float64]]:
    """A spectrum S(ω) with its parameters bound, for :func:`irregular_waves` and the CLI.

    Parameters
    ----------
    name
        ``"jonswap"``, ``"pm"`` (or ``"ittc"``, ``"bretschneider"``, ``"pierson-moskowitz"``),
        ``"torsethaugen"`` (case-insensitive).
    hs, tp
        Significant wave height (m) and peak period (s).
    gamma
        JONSWAP peak enhancement (default 3.3); not accepted by the other spectra.

    Returns
    -------
    callable
        A :func:`functools.partial` of the spectrum function (its ``func`` and
        ``keywords`` say which spectrum and parameters).

    Examples
    --------
    >>> s = wave_spectrum("jonswap", hs=2.0, tp=8.0, gamma=2.0)
    >>> s.keywords["gamma"], float(s(2 * 3.141592653589793 / 8.0)) > 0
    (2.0, True)
    """
    key = str(name).strip().lower().replace("_", "-")
    _check_sea(hs, tp)
    if key == "jonswap":
        return functools.partial(
            jonswap, hs=float(hs), tp=float(tp), gamma=3.3 if gamma is None else float(gamma)
        )
    if gamma is not None:
        raise ArgumentError(f"gamma applies to the JONSWAP spectrum only, not to {name!r}")
    if key in ("pm", "ittc", "bretschneider", "pierson-moskowitz"):
        return functools.partial(pierson_moskowitz, hs=float(hs), tp=float(tp))
    if key == "torsethaugen":
        return functools.partial(torsethaugen, hs=float(hs), tp=float(tp))
    raise ArgumentError(f"unknown wave spectrum {name!r}; choose one of {', '.join(SPECTRA)}")


def _describe_spectrum(spectrum: Callable) -> tuple[str, float, float]:
    """(name, hs, tp) of a spectrum made by :func:`wave_spectrum` or a partial of ours."""
    if isinstance(spectrum, functools.partial):
        kw = spectrum.keywords or {}
        name = getattr(spectrum.func, "__name__", "custom")
        return name, float(kw.get("hs", np.nan)), float(kw.get("tp", np.nan))
    return getattr(spectrum, "__name__", "custom"), np.nan, np.nan


def energy_range(
    spectrum: Spectrum, fraction: float = 1e-3, *, omega_max: float = 1e3
) -> tuple[float, float]:
    """Frequency range (rad/s) holding all but ``fraction`` of a spectrum's energy.

    ``fraction``/2 is left out below and above. S is evaluated on a geometric grid
    (1e-3 … ``omega_max`` rad/s, 8000 points) and integrated by the trapezoidal rule.

    Examples
    --------
    >>> lo, hi = energy_range(wave_spectrum("pm", 4.0, 10.0))
    >>> round(lo, 3), round(hi, 3)
    (0.4, 4.443)
    """
    if not 0 < fraction < 1:
        raise ArgumentError(f"fraction must be between 0 and 1, got {fraction!r}")
    w = np.geomspace(1e-3, omega_max, 8000)
    s = np.asarray(spectrum(w), dtype=float)
    if s.shape != w.shape or not np.all(np.isfinite(s)) or np.any(s < 0):
        raise ArgumentError("the spectrum must return finite, non-negative values of S(omega)")
    from scipy.integrate import cumulative_trapezoid  # on use

    cumulative = cumulative_trapezoid(s, w, initial=0.0)
    total = cumulative[-1]
    if not total > 0:
        raise ArgumentError("the spectrum carries no energy between 1e-3 and 1e3 rad/s")
    lo = float(np.interp(fraction / 2 * total, cumulative, w))
    hi = float(np.interp((1 - fraction / 2) * total, cumulative, w))
    return lo, hi


def range_within_data(spectrum: Spectrum, omega_data: ArrayLike) -> tuple[float, float]:
    """The range of :func:`energy_range`, limited to the frequencies a database holds
    (``omega_data``, rad/s): wave components beyond them could not be given a force (the
    excitation is not extrapolated). A warning says so, with the share of the spectrum's
    energy left out, when the limit cuts the range (a :class:`~cummins.errors.
    CumminsWarning` from 1 % of the energy, a note below).

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     lo, hi = range_within_data(wave_spectrum("pm", 4.0, 10.0), [0.3, 2.0])
    >>> round(lo, 3), hi, "1.3 % of the spectrum's energy" in str(caught[0].message)
    (0.4, 2.0, True)
    """
    lo, hi = energy_range(spectrum)
    w = np.asarray(omega_data, dtype=float).reshape(-1)
    band = (max(lo, float(w.min())), min(hi, float(w.max())))
    if band[0] >= band[1]:
        raise ArgumentError(
            f"the spectrum's energy ({lo:.4g} to {hi:.4g} rad/s) lies outside the data's "
            f"frequencies, {w.min():.4g} to {w.max():.4g} rad/s: no wave component can be "
            "given a force"
        )
    if band != (lo, hi):
        grid = np.geomspace(1e-3, 1e3, 8000)
        s = np.asarray(spectrum(grid), dtype=float)
        inside = (grid >= band[0]) & (grid <= band[1])
        left_out = 1.0 - np.trapezoid(s[inside], grid[inside]) / np.trapezoid(s, grid)
        warnings.warn(
            f"wave components limited to the data's frequencies, {band[0]:.4g} to "
            f"{band[1]:.4g} rad/s (the spectrum's energy lies within {lo:.4g} to "
            f"{hi:.4g} rad/s; {100 * left_out:.2g} % of the spectrum's energy left out)",
            CumminsWarning if left_out >= 0.01 else UserWarning,  # a note below 1 %
            stacklevel=3,
        )
    return band
