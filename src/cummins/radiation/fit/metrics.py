"""How well a fluid-memory model matches the data (Unneland (2007) §6.1, Tables 6.2–6.8).

Per coupling: R² of A(ω), of B(ω), of |K(jω)| and of ∠K(jω) at the fitted frequencies,
R² of K(t) against the retardation function of the data, the H∞ error max_ω |K − K̂|
(absolute and relative to max |K|), stability, and for diagonal terms positive realness.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from cummins.radiation.fit.frequency import is_positive_real, r_squared
from cummins.radiation.model import (
    CouplingModel,
    as_modal_form,
    siso_frequency_response,
    siso_impulse_response,
)


def coupling_metrics(
    model: CouplingModel,
    omega: ArrayLike,
    added_mass: ArrayLike,
    damping: ArrayLike,
    added_mass_inf: float,
    *,
    time: ArrayLike | None = None,
    kernel: ArrayLike | None = None,
    floor: tuple[float, float] = (0.0, 0.0),
    modal=None,
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
    floor
        Smallest variances of A and of B taken by their R² (a direction of a pair
        fitted as given: the pair's spread, :func:`pair_floor`).
    modal
        :func:`cummins.radiation.model.modal_form` of ``model.a`` when known (the pairs of
        a block share it).

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
    modal = as_modal_form(modal, model.a)
    k_model = siso_frequency_response(model.a, model.b, model.c, w, modal)
    k_data = b + 1j * w * (a - added_mass_inf)
    error = np.abs(k_model - k_data)
    scale = float(np.abs(k_data).max()) or 1.0
    metrics: dict[str, float | bool | None] = {
        "r2_added_mass": r_squared(a, added_mass_inf + k_model.imag / w, floor[0]),
        "r2_damping": r_squared(b, k_model.real, floor[1]),
        "r2_magnitude": r_squared(np.abs(k_data), np.abs(k_model)),
        "r2_phase": r_squared(np.unwrap(np.angle(k_data)), np.unwrap(np.angle(k_model))),
        "r2_kernel": None,
        "hinf_error": float(error.max()),
        "hinf_relative": float(error.max() / scale),
        "stable": bool(np.all(modal[0].real < 0)),  # the decision of model.is_stable()
        "passive": None,
        "n_frequencies": int(w.size),
    }
    if time is not None and kernel is not None:
        impulse = siso_impulse_response(model.a, model.b, model.c, time, modal)
        metrics["r2_kernel"] = r_squared(kernel, impulse)
        metrics["kernel_zero"] = float(impulse[0])
        metrics["kernel_zero_data"] = float(np.asarray(kernel)[0])
    if model.influenced == model.radiating:
        lam, vec, _ = modal
        b = np.asarray(model.b, dtype=float)
        residues = (model.c @ vec) * (modal.solved(b) if b.ndim == 1 else np.linalg.solve(vec, b))
        metrics["passive"] = bool(metrics["stable"]) and is_positive_real(lam, residues)
    return metrics


def pair_floor(added_mass: ArrayLike, damping: ArrayLike, i: int, j: int) -> tuple[float, float]:
    """The variance floors (A, B) of the R² of each direction of a pair (i, j) fitted as
    given: the mean of the variances of X_ij and X_ji over the frequencies given
    (``added_mass``, ``damping``: (omega, n, n)), the spread its fit is weighed by
    (:func:`cummins.radiation.fit.vector.block_data`). A direction near zero beside
    the other is then judged at the pair's scale, not at its own noise."""
    out = []
    for x in (np.asarray(added_mass, dtype=float), np.asarray(damping, dtype=float)):
        out.append(float(0.5 * (np.var(x[:, i, j]) + np.var(x[:, j, i]))))
    return out[0], out[1]
