"""The second-order difference-frequency flow of two regular waves, and the long-wave force
it puts on a small floating body: an independent reference for the sign of a QTF.

Two waves travel along +x in water of depth h, ζ = Re Σ_n c_n e^{i(ω_n t − k_n x)} (e^{+iωt},
as cummins), potential φ₁ = Re Σ (i g c_n/ω_n) cosh k_n(z+h)/cosh k_n h e^{iθ_n}. The
difference-frequency potential φ₂ = Re Φ c₁c₂* cosh K(z+h)/cosh K h e^{i(θ₁−θ₂)},
K = |k₁ − k₂|, solves the combined free-surface condition

    φ₂,tt + g φ₂,z = −∂_t |∇φ₁|² + (1/g) φ₁,t ∂_z(φ₁,tt + g φ₁,z)     (z = 0)

(Sharma and Dean (1981); the bound "set-down" long wave). A body small against both wave
lengths feels, per c₁c₂* (the full-square convention of :mod:`cummins.qtf.data`):

* in surge, the inertia of the bound flow, (ρV + A₁₁) ∂u₂/∂t at its centre (Morison's
  inertia term with C_M = 1 + A₁₁/ρV);
* in heave, the restoring of a floater that follows the second-order Lagrangian surface
  elevation Z₂, (C₃₃ − (m + A₃₃) μ²) Z₂, μ = ω₁ − ω₂.

For the 2 m box of AQWA 2023 R1 (BEMRosetta's Box1) at (0.1, 0.4) rad/s in 70 m of water
these give +98.6i and −966 N/m² against AQWA's printed −0.0023 + 95.2i and −954.6.
"""

from __future__ import annotations

import numpy as np

G = 9.81


def wavenumber(omega: float, depth: float, g: float = G) -> float:
    """k of ω² = g k tanh(k h)."""
    k = max(omega**2 / g, omega / np.sqrt(g * depth))
    for _ in range(100):
        t = np.tanh(k * depth)
        k -= (g * k * t - omega**2) / (g * t + g * k * depth * (1 - t * t))
    return k


def _fields(omega: float, k: float, z: float, depth: float) -> dict:
    """First-order complex amplitudes per unit c at depth z (x = 0)."""
    f = np.cosh(k * (z + depth)) / np.cosh(k * depth)
    fz = k * np.sinh(k * (z + depth)) / np.cosh(k * depth)
    phi, phiz = 1j * G / omega * f, 1j * G / omega * fz
    return {
        "phit": 1j * omega * phi,
        "phitz": 1j * omega * phiz,
        "phizz": 1j * G / omega * k * k * f,
        "u": -1j * k * phi,
        "w": phiz,
        "wx": -1j * k * phiz,
        "wz": 1j * G / omega * k * k * f,
        "X": (-1j * k * phi) / (1j * omega),
        "Z": phiz / (1j * omega),
    }


def _pair(a1, b2, a2, b1) -> complex:
    """The c₁c₂* coefficient of Re(a₁) Re(b₂) + Re(a₂) Re(b₁), per the full square."""
    return 0.25 * (a1 * np.conj(b2) + np.conj(a2) * b1)


def small_body_forces(
    omega1: float,
    omega2: float,
    depth: float,
    *,
    mass: float,
    a11: float,
    a33: float,
    c33: float,
    z: float,
) -> tuple[complex, complex]:
    """(surge, heave) difference-frequency force per c₁c₂* (N/m²) on a small floater of
    ``mass`` (neutrally buoyant), added masses ``a11``, ``a33``, heave restoring ``c33``,
    centre at depth ``z`` (module docstring)."""
    k1, k2 = wavenumber(omega1, depth), wavenumber(omega2, depth)
    mu, dk = omega1 - omega2, k1 - k2
    f1, f2 = _fields(omega1, k1, 0.0, depth), _fields(omega2, k2, 0.0, depth)
    grad2 = _pair(f1["u"], f2["u"], f2["u"], f1["u"]) + _pair(f1["w"], f2["w"], f2["w"], f1["w"])
    l1 = -(omega1**2) * f1["w"] + G * f1["phizz"]
    l2 = -(omega2**2) * f2["w"] + G * f2["phizz"]
    forcing = -1j * mu * grad2 + _pair(f1["phit"], l2, f2["phit"], l1) / G
    big_k = abs(dk)
    phi2 = forcing / (G * big_k * np.tanh(big_k * depth) - mu**2)
    u2 = -1j * dk * phi2 * np.cosh(big_k * (z + depth)) / np.cosh(big_k * depth)
    surge = (mass + a11) * 1j * mu * u2
    w_lagrange = (
        phi2 * big_k * np.tanh(big_k * depth)
        + _pair(f1["X"], f2["wx"], f2["X"], f1["wx"])
        + _pair(f1["Z"], f2["wz"], f2["Z"], f1["wz"])
    )
    heave = (c33 - (mass + a33) * mu**2) * w_lagrange / (1j * mu)
    return complex(surge), complex(heave)
