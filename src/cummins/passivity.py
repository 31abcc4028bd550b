"""Passivity of radiation models (seed 001 §3.2).

The map from velocities ξ̇ to the memory force μ is passive: K(jω) + K(jω)ᴴ = 2 B(ω) ⪰ 0
for all ω (seed 001 Prop. 3.4, eq. 3.24). A fitted model that is not passive can feed
energy into a simulation. This module tests it on a dense frequency sweep,
λ_min(K(jω) + K(jω)ᴴ) ≥ 0 (seed 001 eq. 3.13), after scaling the DOFs so that units do
not decide the answer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from cummins.radiation import RadiationModel

#: A model is called passive when the smallest scaled eigenvalue of K + Kᴴ is above
#: −PASSIVITY_TOLERANCE times the largest one over the sweep.
PASSIVITY_TOLERANCE = 1e-6


@dataclass(frozen=True)
class PassivitySweep:
    """Result of :func:`passivity_sweep`.

    Attributes
    ----------
    omega
        Frequencies of the sweep, rad/s.
    min_eigenvalue
        λ_min of the scaled K + Kᴴ at each frequency, relative to the largest
        eigenvalue over the sweep (dimensionless).
    passive
        Whether the minimum stays above −:data:`PASSIVITY_TOLERANCE`.
    worst_omega
        Frequency of the smallest eigenvalue, rad/s.
    """

    omega: np.ndarray
    min_eigenvalue: np.ndarray
    passive: bool
    worst_omega: float


def default_sweep(model: RadiationModel, points_per_decade: int = 100) -> np.ndarray:
    """Log grid from 10⁻³ to 10³ times the range of the model's pole magnitudes, refined
    around each lightly damped resonance."""
    poles = (
        np.concatenate([k.poles() for k in model.couplings]) if model.couplings else np.array([1.0])
    )
    mags = np.abs(poles[np.abs(poles) > 0]) if np.any(np.abs(poles) > 0) else np.array([1.0])
    lo, hi = mags.min() * 1e-3, mags.max() * 1e3
    n = int(np.ceil(points_per_decade * np.log10(hi / lo)))
    resonances = [abs(p.imag) + abs(p.real) * np.linspace(-5, 5, 41) for p in poles if p.imag > 0]
    grid = np.concatenate([np.geomspace(lo, hi, n), *resonances])
    return np.unique(grid[grid > 0])


def passivity_sweep(model: RadiationModel, omega: ArrayLike | None = None) -> PassivitySweep:
    """λ_min(K(jω) + K(jω)ᴴ) of the MIMO model on a dense sweep (seed 001 eq. 3.13).

    The DOFs are scaled by D^{-1/2}, D = diag of the largest |K_ii| over the sweep, so that
    translations and rotations weigh alike.
    """
    w = default_sweep(model) if omega is None else np.asarray(omega, dtype=float)
    k = model.frequency_response(w).values
    herm = k + np.conj(np.swapaxes(k, 1, 2))
    diag = np.abs(np.diagonal(k, axis1=1, axis2=2)).max(axis=0)
    scale = np.where(diag > 0, 1.0 / np.sqrt(np.where(diag > 0, diag, 1.0)), 0.0)
    scaled = herm * scale[None, :, None] * scale[None, None, :]
    eig = np.linalg.eigvalsh(scaled)
    top = max(float(eig[:, -1].max()), np.finfo(float).tiny)
    lam = eig[:, 0] / top
    worst = int(np.argmin(lam))
    return PassivitySweep(w, lam, bool(lam[worst] >= -PASSIVITY_TOLERANCE), float(w[worst]))


def is_passive(model: RadiationModel) -> bool:
    """True when the MIMO model passes :func:`passivity_sweep`."""
    return passivity_sweep(model).passive
