"""The two routes to A(ω), B(ω) at any admissible ω ≥ 0 (Ross, Perez & Fossen (2006) §3.1).

From the retardation function K(t) and A∞ (eqs. 8–9 and 22–23, exact for the
piecewise-linear K through its samples) or from the frequency data by cubic splines,
with A(0) from the solver's ω = 0 row or :func:`extrapolate_zero_frequency` (eqs. 20–21).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import NDArray
from scipy.interpolate import CubicSpline

from cummins.errors import HydroDataError
from cummins.hydrodb import dof_matrix, single_speed
from cummins.radiation.transforms import cosine_transform, sine_transform


class _Coefficients:
    """A(ω), B(ω) (n, n) at any admissible ω ≥ 0, one route."""

    route: str
    zero_note: str
    omega_range: tuple[float, float]

    def __call__(self, omega: float) -> tuple[NDArray, NDArray]:  # pragma: no cover
        raise NotImplementedError


class _FromKernel(_Coefficients):
    """Ross, Perez & Fossen (2006) eqs. 8–9 and 22–23 on a sampled K(t).

    Exact for a piecewise-linear K."""

    route = "retardation function K(t)"

    def __init__(self, kernel: xr.DataArray, a_inf: NDArray) -> None:
        k = kernel.transpose("time", "influenced_dof", "radiating_dof")
        self.t = np.asarray(k.time.values, dtype=float)
        if self.t.size < 2 or np.any(np.diff(self.t) <= 0) or self.t[0] != 0.0:
            raise HydroDataError(
                "the retardation function must be sampled on increasing times from t = 0",
                quantity="retardation_function time",
            )
        self.n = k.shape[1]
        self.k = np.asarray(k.values, dtype=float).reshape(self.t.size, self.n * self.n)
        self.a_inf = np.asarray(a_inf, dtype=float)
        self.omega_range = (0.0, np.inf)
        self.zero_note = (
            f"A(0) = A∞ − ∫τK dτ, B(0) = ∫K dτ over 0–{self.t[-1]:g} s (eqs. 22–23, 25–26)"
        )
        # ∫ K dτ and ∫ τ K dτ, exact for the piecewise-linear K through its samples
        t, f = self.t, self.k
        h = np.diff(t)[:, None]
        f0, f1, t0, t1 = f[:-1], f[1:], t[:-1, None], t[1:, None]
        self.area = np.sum(0.5 * h * (f0 + f1), axis=0).reshape(self.n, self.n)
        moment = h / 6.0 * (f0 * (2 * t0 + t1) + f1 * (t0 + 2 * t1))
        self.moment = np.sum(moment, axis=0).reshape(self.n, self.n)

    def __call__(self, omega: float) -> tuple[NDArray, NDArray]:
        if omega == 0.0:
            return self.a_inf - self.moment, self.area.copy()
        s = sine_transform(self.t, self.k, [omega])[0].reshape(self.n, self.n)
        c = cosine_transform(self.t, self.k, [omega])[0].reshape(self.n, self.n)
        return self.a_inf - s / omega, c


class _FromFrequencyData(_Coefficients):
    """Cubic-spline A(ω), B(ω) of the data; ω = 0 from the solver's row or extrapolated."""

    route = "frequency data A(ω), B(ω)"

    def __init__(self, ds: xr.Dataset, zero_frequency: str, points: int) -> None:
        w = ds.omega.values
        a = dof_matrix(ds, "added_mass")
        b = dof_matrix(ds, "radiation_damping")
        self.omega_range = (float(w[0]), float(w[-1]))
        self.a_spline = CubicSpline(w, a, axis=0)
        self.b_spline = CubicSpline(w, b, axis=0)
        if zero_frequency not in ("auto", "data", "extrapolate"):
            raise HydroDataError(
                f"unknown zero_frequency {zero_frequency!r}",
                hint="use 'auto', 'data' or 'extrapolate'",
            )
        a0_ext, b0_ext = extrapolate_zero_frequency(ds, points=points)
        self.b0 = b0_ext
        use_data = zero_frequency == "data" or (
            zero_frequency == "auto" and "added_mass_zero" in ds
        )
        if use_data:
            if "added_mass_zero" not in ds:
                raise HydroDataError(
                    "the data have no zero-frequency added mass row",
                    path=ds.attrs.get("source_file"),
                    quantity="added_mass_zero",
                    hint="use zero_frequency='extrapolate' or lf_model_from_retardation",
                )
            self.a0 = dof_matrix(ds, "added_mass_zero")
            self.zero_note = "A(0) from the solver's ω = 0 row"
        else:
            self.a0 = a0_ext
            self.zero_note = f"A(0) extrapolated in ω² from the lowest {points} frequencies"
        self.zero_note += (
            f", B(0) extrapolated in ω² from the lowest {points} frequencies (eqs. 20–21)"
        )

    def __call__(self, omega: float) -> tuple[NDArray, NDArray]:
        if omega == 0.0:
            return self.a0.copy(), self.b0.copy()
        lo, hi = self.omega_range
        if not lo <= omega <= hi:
            raise HydroDataError(
                f"ω = {omega:.4g} rad/s is outside the data ({lo:.4g}–{hi:.4g} rad/s)",
                quantity="added_mass, radiation_damping",
                hint="use lf_model_from_retardation, which evaluates any frequency",
            )
        return np.asarray(self.a_spline(omega)), np.asarray(self.b_spline(omega))


def extrapolate_zero_frequency(
    ds: xr.Dataset, *, points: int = 4
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A(0) and B(0) by a least-squares fit of c₀ + c₂ω² to the lowest ``points`` frequencies.

    A(ω) and B(ω) are even functions of ω (A(ω) = A∞ + Im K(jω)/ω and B = Re K(jω) for a
    real kernel), so their expansion about ω = 0 has no odd term. The limits of
    Ross, Perez & Fossen (2006) eqs. 20–21.

    Returns
    -------
    (ndarray, ndarray)
        A(0) (n, n), kg, kg·m, kg·m²; B(0) (n, n), kg/s … kg·m²/s.
    """
    ds = single_speed(ds)
    w = ds.omega.values[:points]
    if w.size < 2:
        raise HydroDataError("at least two frequencies are needed to extrapolate to ω = 0")
    x = np.c_[np.ones(w.size), w**2]
    out = []
    for name in ("added_mass", "radiation_damping"):
        y = dof_matrix(ds, name)[:points]
        coef = np.linalg.lstsq(x, y.reshape(w.size, -1), rcond=None)[0]
        out.append(coef[0].reshape(y.shape[1:]))
    return out[0], out[1]
