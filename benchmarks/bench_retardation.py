"""Benchmark: retardation functions of all 36 couplings of the tanker on 2000 time points.

Compares, in one run, cummins' exact (Filon-type) integration of the piecewise-linear
damping with the plain trapezoid rule on the data grid (the textbook approach):

* time for the 36 couplings × 2000 times, both methods;
* accuracy on the tanker's own frequency grid for a system whose K(t) is known in
  closed form (a sum of damped modes with the tanker's time scales): max error / max|K|;
* on the real tanker data, the difference of each method from a brute-force reference
  (trapezoid on a 200× refined piecewise-linear grid, which converges to the integral
  of the interpolant): it shows the aliasing of the trapezoid rule on a coarse grid.

Run: ``python benchmarks/bench_retardation.py``.
"""

from __future__ import annotations

import numpy as np

import cummins
from _timing import timed
from cummins.hydrodb import make_hydrodb
from cummins.radiation.retardation import retardation_function

N_TIMES = 2000
REPEAT = 5


def best_time(function) -> float:
    return timed(function, REPEAT)[0]


def analytic_case(omega: np.ndarray):
    """Passive K(s) = Σ r s/(s² + 2ζω₀s + ω₀²) on every coupling, and its impulse response."""
    r, zeta, w0 = np.array([1.0, 0.6]), np.array([0.35, 0.5]), np.array([0.6, 1.2])
    s = 1j * omega[:, None]
    k = (r * s / (s**2 + 2 * zeta * w0 * s + w0**2)).sum(axis=1)
    ones = np.ones((6, 6))
    ds = make_hydrodb(
        omega,
        10.0 + (k.imag / omega)[:, None, None] * ones,
        k.real[:, None, None] * ones,
        rho=1025.0,
        g=9.81,
        source_format="synthetic",
    )

    def exact(t):
        sigma, wd = zeta * w0, w0 * np.sqrt(1 - zeta**2)
        tt = t[:, None]
        return (r * np.exp(-sigma * tt) * (np.cos(wd * tt) - sigma / wd * np.sin(wd * tt))).sum(1)

    return ds, exact


def refined_reference(ds, t: np.ndarray) -> np.ndarray:
    """Trapezoid on a 200× refined piecewise-linear grid (B(0) = 0): the interpolant's integral."""
    w = np.r_[0.0, ds.omega.values]
    b = np.vstack([np.zeros((1, 36)), ds.radiation_damping.values.reshape(-1, 36)])
    fine = np.unique(np.concatenate([np.linspace(w[k], w[k + 1], 201) for k in range(w.size - 1)]))
    bf = np.stack([np.interp(fine, w, b[:, j]) for j in range(36)], axis=1)
    out = np.empty((t.size, 36))
    for start in range(0, t.size, 200):
        c = np.cos(np.outer(fine, t[start : start + 200]))
        out[start : start + 200] = np.trapezoid(c[:, :, None] * bf[:, None, :], fine, axis=0)
    return (2 / np.pi) * out


def main() -> None:
    ds = cummins.demo_dataset()
    t = np.linspace(0.0, 60.0, N_TIMES)
    t_exact = best_time(lambda: retardation_function(ds, t))
    t_trap = best_time(lambda: retardation_function(ds, t, method="trapezoid"))
    print(f"tanker, 36 couplings x {N_TIMES} times ({ds.sizes['omega']} frequencies):")
    print(f"  exact (Filon + tail)   {t_exact * 1e3:8.1f} ms")
    print(
        f"  trapezoid on the data  {t_trap * 1e3:8.1f} ms   (exact/trapezoid time ratio "
        f"{t_exact / t_trap:.2f})"
    )

    syn, exact = analytic_case(ds.omega.values)
    k_true = exact(t)
    print("analytic system on the tanker's frequency grid (error / max|K|):")
    for label, kwargs in (
        ("exact, tail auto", {}),
        ("exact, no tail", {"tail": "none"}),
        ("trapezoid", {"method": "trapezoid"}),
    ):
        k = retardation_function(syn, t, **kwargs).values[:, 2, 2]
        err = np.abs(k - k_true)
        late = t > 20
        print(
            f"  {label:18s} max {err.max() / np.abs(k_true).max():.2e}   "
            f"t > 20 s {err[late].max() / np.abs(k_true).max():.2e}"
        )

    reference = refined_reference(ds, t)
    scale = np.abs(reference).max(axis=0)
    keep = scale > 0
    print("real tanker data, difference from the integral of the interpolant (/ max|K|):")
    for label, method in (("exact, no tail", "exact"), ("trapezoid", "trapezoid")):
        k = retardation_function(ds, t, method=method, tail="none").values.reshape(t.size, 36)
        rel = np.abs(k - reference)[:, keep].max(axis=0) / scale[keep]
        print(f"  {label:18s} worst coupling {rel.max():.2e}, median {np.median(rel):.2e}")


if __name__ == "__main__":
    main()
