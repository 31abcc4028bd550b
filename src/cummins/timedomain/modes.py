"""The lightly damped modes of a vessel's linear model: what a slow-drift force resonates.

The eigenvalues λ of the state matrix F of ẋ = F x + G τ
(:meth:`cummins.vessel.Vessel.state_space`: inertia, restoring, the damping given and the
fluid memory) are the modes of the linear model; an oscillatory pair
λ = −ζω_n ± iω_n√(1 − ζ²) has the natural frequency ω_n = |λ| and the damping ratio
ζ = −Re λ / |λ|. Radiation damping vanishes as
ω → 0, so the modes of a moored floating body in surge, sway and yaw, and its heave,
roll and pitch far below the wave frequencies, are damped by almost nothing but what is
given: the slowly varying second-order force drives them at resonance, and their
response is then set by that damping alone (Faltinsen (1990) ch. 5, the slow-drift
response of a moored structure; Pinkster (1980)). :func:`lightly_damped_modes` names them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Mode", "lightly_damped_modes"]


@dataclass(frozen=True)
class Mode:
    """One oscillatory mode of the linear model.

    Attributes
    ----------
    omega
        Natural frequency ω_n = |λ|, rad/s.
    zeta
        Damping ratio −Re λ / |λ|.
    dof
        The body DOF that holds most of the mode's kinetic energy (M_ii |ξ_i|²).
    """

    omega: float
    zeta: float
    dof: str

    @property
    def period(self) -> float:
        """Natural period 2π/ω_n, s."""
        return float(2 * np.pi / self.omega)


def lightly_damped_modes(vessel, *, below: float, zeta_max: float = 0.01) -> list[Mode]:
    """The oscillatory modes of ``vessel`` with ω_n < ``below`` and ζ < ``zeta_max``.

    Parameters
    ----------
    vessel
        A :class:`cummins.vessel.Vessel`.
    below
        rad/s: only modes of lower natural frequency (e.g. the sea's peak frequency, below
        which the difference-frequency force acts).
    zeta_max
        Damping ratio below which a mode is listed (1 % of critical).

    Returns
    -------
    list of Mode
        One per pair of complex eigenvalues, by natural frequency.
    """
    f, _ = vessel.state_space()
    values, vectors = np.linalg.eig(f)
    t = vessel.basis
    m = t.shape[1]
    weight = np.abs(np.diag(vessel.mass))
    out = []
    for k in np.flatnonzero(values.imag > 0):
        lam = values[k]
        omega = float(abs(lam))
        zeta = float(-lam.real / omega)
        if omega >= below or zeta >= zeta_max:
            continue
        xi = t @ vectors[:m, k]
        energy = weight * np.abs(xi) ** 2
        out.append(Mode(omega, zeta, str(vessel.dofs[int(np.argmax(energy))])))
    return sorted(out, key=lambda mode: mode.omega)
