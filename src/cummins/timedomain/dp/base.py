"""The 3-DOF (surge, sway, yaw) conventions and checks shared by the parts of the DP controller.

:data:`DOF3`, the indices of surge, sway and yaw in a 6-vector; :func:`wrap_angle`; the
horizontal-plane rotation :func:`rotation_3dof` (R_b^n(0, 0, ψ) of Smogeli et al. (2004)
eq. 6, Fossen (2021) 3-DOF kinematics); the error :class:`DPConfigError` and the input
checks of gains, poses and thruster layouts.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError
from cummins.kinematics import rotation_matrix

#: Indices of surge, sway and yaw in a 6-DOF vector.
DOF3 = (0, 1, 5)
_DOF3_NAMES = ("surge", "sway", "yaw")


class DPConfigError(CumminsError, ValueError):
    """A DP controller, gain set, wave filter or thruster layout that cannot work
    (negative gains, wrong shapes, thrusters unable to produce a force or moment, …)."""


def wrap_angle(angle: ArrayLike) -> Any:
    """Wrap an angle (rad) to the interval (−π, π].

    Examples
    --------
    >>> round(float(np.degrees(wrap_angle(np.radians(179.0) - np.radians(-179.0)))), 9)
    -2.0
    >>> float(wrap_angle(-np.pi))
    3.141592653589793
    """
    a = np.pi - np.mod(np.pi - np.asarray(angle, dtype=float), 2.0 * np.pi)
    return float(a) if a.ndim == 0 else a


def rotation_3dof(psi: float) -> NDArray[np.float64]:
    """R(ψ) of the horizontal-plane kinematics η̇ = R(ψ)ν for (N, E, ψ) and (u, v, r).

    [[cos ψ, −sin ψ, 0], [sin ψ, cos ψ, 0], [0, 0, 1]]: the upper-left block is
    R_b^n(0, 0, ψ) (Smogeli et al. (2004) eq. 6), yaw maps to itself (Fossen (2021), 3-DOF
    kinematics).

    Examples
    --------
    >>> np.round(rotation_3dof(np.pi / 2) @ [1.0, 0.0, 0.0], 12)  # bow east
    array([0., 1., 0.])
    """
    out = np.eye(3)
    out[:2, :2] = rotation_matrix([0.0, 0.0, psi])[:2, :2]
    return out


def _as_3x3(value: ArrayLike, name: str) -> NDArray[np.float64]:
    """A 3×3 (surge, sway, yaw) matrix from a scalar, 3-vector (diagonal), 3×3 or 6×6."""
    a = np.asarray(value, dtype=float)
    if a.ndim == 0:
        a = np.full(3, float(a))
    if a.shape == (3,):
        a = np.diag(a)
    elif a.shape == (6, 6):
        a = a[np.ix_(DOF3, DOF3)]
    if a.shape != (3, 3):
        raise DPConfigError(
            f"{name} must be a 3×3 (surge, sway, yaw) matrix, a 3-vector (its diagonal) "
            f"or a 6×6 matrix, not shape {a.shape}"
        )
    if not np.all(np.isfinite(a)):
        raise DPConfigError(f"{name} holds non-finite values: {a.tolist()}")
    return a


def _check_psd(a: NDArray[np.float64], name: str, unit: str) -> None:
    sym = 0.5 * (a + a.T)
    eig = np.linalg.eigvalsh(sym)
    scale = max(float(np.max(np.abs(sym))), 1e-300)
    if np.any(np.diag(a) < 0.0) or eig[0] < -1e-9 * scale:
        raise DPConfigError(
            f"gain {name} is not positive semi-definite (diagonal {np.diag(a).tolist()} {unit}, "
            f"smallest eigenvalue of its symmetric part {eig[0]:.3g})",
            hint="gains must be ≥ 0; a negative gain destabilises the loop",
        )


def _pose3(eta: ArrayLike, name: str) -> NDArray[np.float64]:
    a = np.asarray(eta, dtype=float).reshape(-1)
    if a.size == 6:
        a = a[list(DOF3)]
    if a.size != 3:
        raise DPConfigError(
            f"{name} must be (N, E, ψ) or a 6-DOF pose (N, E, D, φ, θ, ψ), got {a.size} values"
        )
    if not np.all(np.isfinite(a)):
        raise DPConfigError(f"{name} holds non-finite values: {a.tolist()}")
    return a
