"""The ``retardation`` check, per significant coupling.

K(0), ∫K dt against B(0) = 0, K(t_max)/max|K|, the tail's share of ∫B dω, the Ogilvie
estimate of A∞ and its spread over frequency (and its distance from the solver's ω = ∞
row), and the Kramers–Kronig error
(:func:`cummins.radiation.retardation.retardation_diagnostics`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.check.common import (
    A_INF_TOL,
    K_END_TOL,
    K_INTEGRAL_TOL,
    KK_TOL,
    TAIL_TOL,
    _labels,
    _speed_suffix,
    _speeds,
)
from cummins.check.report import Finding
from cummins.radiation.retardation import retardation_diagnostics


def _check_retardation(ds: xr.Dataset) -> list[Finding]:
    out = []
    labels = _labels(ds)
    for sub in _speeds(ds):
        if float(sub.forward_speed) if "forward_speed" in sub.coords else 0.0:
            out.append(
                Finding(
                    "retardation",
                    "info",
                    f"not evaluated{_speed_suffix(sub)}: forward speed needs the speed-"
                    "dependent kernels (see cummins.radiation.speed)",
                )
            )
            continue
        d = retardation_diagnostics(sub)
        diag_est = np.abs(np.diag(d.added_mass_inf_estimate.values))
        for i, j in zip(*np.nonzero(np.triu(d.significant.values)), strict=True):
            out.append(_retardation_finding(d, int(i), int(j), labels, diag_est))
    return out


def _retardation_finding(d: xr.Dataset, i: int, j: int, labels: list[str], diag_est) -> Finding:
    pair = labels[i] if i == j else f"{labels[i]}-{labels[j]}"
    k0 = float(d.K0.values[i, j])
    integral = float(d.k_integral.values[i, j])
    end = float(d.k_end_ratio.values[i, j])
    tail = float(d.tail_fraction.values[i, j])
    est = float(d.added_mass_inf_estimate.values[i, j])
    spread = float(d.added_mass_inf_spread.values[i, j])
    row = float(d.added_mass_inf_data.values[i, j])
    kk = float(d.kramers_kronig_error.values[i, j])
    scale = np.sqrt(diag_est[i] * diag_est[j]) or 1.0
    t_max = d.attrs["t_max"]
    abs_integral = abs(integral) / max(abs(k0) * t_max, np.finfo(float).tiny)
    problems, advice = [], []
    if end > K_END_TOL:
        problems.append(f"K has not decayed by t = {t_max:.3g} s ({end:.2g} of its peak)")
        advice.append("use a longer time grid or truncate with cut-and-subtract")
    if i == j and abs_integral > K_INTEGRAL_TOL:
        problems.append(f"∫K dt = {integral:.3g} is not close to B(0) = 0")
        advice.append("low-frequency data are missing or inconsistent")
    if tail > TAIL_TOL:
        problems.append(f"{tail:.0%} of ∫B dω lies in the extrapolated tail")
        advice.append("K(0) rests on the tail model: extend the frequency range")
    if spread / scale > A_INF_TOL:
        problems.append(f"the A∞ estimates vary by ±{spread / scale:.1%} over frequency")
        advice.append("A(ω) and B(ω) are not a consistent pair at some frequencies")
    if np.isfinite(row) and abs(est - row) / scale > A_INF_TOL:
        problems.append(
            f"the ω = ∞ row differs from the Ogilvie estimate by {abs(est - row) / scale:.1%}"
        )
        advice.append("check the solver's infinite-frequency computation")
    if kk > KK_TOL:
        problems.append(f"Kramers–Kronig error {kk:.1%}")
        advice.append(
            "A(ω) and B(ω) are not causal as given (irregular frequencies, "
            "truncated or strip-theory speed terms)"
        )
    row_text = f", data row {row:.4g}" if np.isfinite(row) else ""
    message = (
        f"K(0) = {k0:.4g}, K(t_max)/max|K| = {end:.2g}, tail {tail:.0%} of ∫B; "
        f"A∞ estimate {est:.4g} ± {spread:.2g}{row_text}; KK error {kk:.1%}"
    )
    if problems:
        message += " — " + "; ".join(problems)
    return Finding(
        "retardation",
        "warning" if problems else "ok",
        message,
        where=pair,
        value=kk,
        advice="; ".join(dict.fromkeys(advice)) or None,
        details={
            "K0": k0,
            "k_integral": integral,
            "k_end_ratio": end,
            "tail_fraction": tail,
            "added_mass_inf_estimate": est,
            "added_mass_inf_spread": spread,
            "added_mass_inf_data": row if np.isfinite(row) else None,
            "kramers_kronig_error": kk,
            "t_max": t_max,
        },
    )
