"""How well a fluid-memory model matches the data (Unneland (2007) §6.1, Tables 6.2–6.8).

Per coupling: R² of A(ω), of B(ω), of |K(jω)| and of ∠K(jω) at the fitted frequencies,
R² of K(t) against the retardation function of the data, the H∞ error max_ω |K − K̂|
(absolute and relative to max |K|), stability, and for diagonal terms positive realness.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from cummins.radiation.fit.frequency import is_positive_real, r_squared
from cummins.radiation.model import CouplingModel


def coupling_metrics(
    model: CouplingModel,
    omega: ArrayLike,
    added_mass: ArrayLike,
    damping: ArrayLike,
    added_mass_inf: float,
    *,
    time: ArrayLike | None = None,
    kernel: ArrayLike | None = None,
) -> dict[str, float | bool | None]:
    """Fit measures of one coupling model against its data.

    Parameters
    ----------
    model
        The SISO model K_ij(s).
    omega, added_mass, damping
        Data at the fitted frequencies (rad/s; A and B of the coupling).
    added_mass_inf
        A∞ of the coupling used with the model.
    time, kernel
        K(t) of the data on a time grid, for ``r2_kernel`` (optional).

    Returns
    -------
    dict
        ``r2_added_mass``, ``r2_damping``, ``r2_magnitude``, ``r2_phase``, ``r2_kernel``
        (None without ``kernel``), ``hinf_error`` (force/velocity units), ``hinf_relative``,
        ``stable``, ``passive`` (None off the diagonal), ``n_frequencies``.
    """
    w = np.asarray(omega, dtype=float)
    a = np.asarray(added_mass, dtype=float)
    b = np.asarray(damping, dtype=float)
    k_model = model.frequency_response(w)
    k_data = b + 1j * w * (a - added_mass_inf)
    error = np.abs(k_model - k_data)
    scale = float(np.abs(k_data).max()) or 1.0
    metrics: dict[str, float | bool | None] = {
        "r2_added_mass": r_squared(a, added_mass_inf + k_model.imag / w),
        "r2_damping": r_squared(b, k_model.real),
        "r2_magnitude": r_squared(np.abs(k_data), np.abs(k_model)),
        "r2_phase": r_squared(np.unwrap(np.angle(k_data)), np.unwrap(np.angle(k_model))),
        "r2_kernel": None,
        "hinf_error": float(error.max()),
        "hinf_relative": float(error.max() / scale),
        "stable": model.is_stable(),
        "passive": None,
        "n_frequencies": int(w.size),
    }
    if time is not None and kernel is not None:
        fitted = model.impulse_response(time)
        metrics["r2_kernel"] = r_squared(kernel, fitted)
        metrics["kernel_zero"] = float(fitted[0])
        metrics["kernel_zero_data"] = float(np.asarray(kernel)[0])
    if model.influenced == model.radiating:
        lam, vec = np.linalg.eig(model.a)
        residues = (model.c @ vec) * np.linalg.solve(vec, model.b)
        metrics["passive"] = bool(metrics["stable"]) and is_positive_real(lam, residues)
    return metrics
