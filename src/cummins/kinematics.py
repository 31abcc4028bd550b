"""Rigid-body kinematics: cross-product matrix, screw transform, axis reflections.

Notation and equation numbers follow Smogeli, Perez, Fossen & Sørensen, "The Marine
Systems Simulator state-space model representation for dynamically positioned surface
vessels" (Smogeli et al., 2004).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: Sign of each generalized coordinate when going from solver axes (x forward,
#: y to port, z up) to Fossen's body axes (x forward, y to starboard, z down): a
#: rotation of π about x. The transform is its own inverse.
Z_UP_TO_Z_DOWN = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])

#: ShipX/VERES axes (x aft, y to starboard, z up) to solver axes (x forward, y to
#: port, z up): a rotation of π about z. Its own inverse.
X_AFT_TO_X_FORWARD = np.array([-1.0, -1.0, 1.0, -1.0, -1.0, 1.0])


def skew(r: ArrayLike) -> NDArray[np.float64]:
    """Cross-product matrix S(r), such that ``S(r) @ a == np.cross(r, a)``.

    Smogeli et al. (2004) eq. (14).

    Parameters
    ----------
    r
        Vector of length 3.

    Returns
    -------
    ndarray, shape (3, 3)
        The skew-symmetric matrix S(r) = −S(r)ᵀ.

    Examples
    --------
    >>> skew([1.0, 2.0, 3.0]) @ [0.0, 0.0, 1.0]
    array([ 2., -1.,  0.])
    """
    x, y, z = np.asarray(r, dtype=float).reshape(3)
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def screw_transform(r: ArrayLike) -> NDArray[np.float64]:
    """Screw transformation H(r) (Smogeli et al. (2004) eq. 15).

    For a rigid body with generalized velocity ν = [v_O, ω] about a point O, the
    generalized velocity about the point P at ``r`` (from O to P) is ``H(r) @ ν``
    (eq. 16, 43); a generalized force acting at P is moved to O by ``H(r).T @ τ_P``
    (eq. 45), and a matrix M defined about P becomes ``H(r).T @ M @ H(r)`` about O
    (eq. 38).

    Parameters
    ----------
    r
        Vector from O to P, metres, in the body axes.

    Returns
    -------
    ndarray, shape (6, 6)

    Examples
    --------
    A unit yaw rate about O moves a point 2 m forward at 2 m/s to the side:

    >>> screw_transform([2.0, 0.0, 0.0]) @ [0, 0, 0, 0, 0, 1.0]
    array([0., 2., 0., 0., 0., 1.])
    """
    h = np.eye(6)
    h[:3, 3:] = skew(r).T
    return h


def rigid_body_inertia(
    mass: float, center_of_gravity: ArrayLike, inertia_cg: ArrayLike
) -> NDArray[np.float64]:
    """Rigid-body inertia matrix M_RB about the origin (Smogeli et al. (2004) eq. 25).

    M_RB = [[m I, −m S(r_g)], [m S(r_g), I_o]], with I_o = I_g − m S(r_g)² the inertia
    tensor about the origin (parallel-axis theorem).

    Parameters
    ----------
    mass
        kg.
    center_of_gravity
        r_g, m, from the origin, in the body axes.
    inertia_cg
        3×3 inertia tensor about the centre of gravity, kg·m² (or its diagonal).

    Examples
    --------
    >>> m = rigid_body_inertia(2.0, [1.0, 0.0, 0.0], [1.0, 1.0, 1.0])
    >>> float(m[5, 5])  # I_zz about the origin = 1 + 2 · 1²
    3.0
    """
    r = np.asarray(center_of_gravity, dtype=float).reshape(3)
    i_g = np.asarray(inertia_cg, dtype=float)
    if i_g.shape == (3,):
        i_g = np.diag(i_g)
    s = skew(r)
    out = np.zeros((6, 6))
    out[:3, :3] = mass * np.eye(3)
    out[:3, 3:] = -mass * s
    out[3:, :3] = mass * s
    out[3:, 3:] = i_g - mass * s @ s
    return out


def center_of_gravity_from_inertia(m_rb: ArrayLike) -> tuple[float, NDArray[np.float64], float]:
    """Mass, centre of gravity and rigid-body inconsistency of a 6×6 inertia matrix.

    For a rigid body the coupling block M[:3, 3:] equals −m S(r_g), a skew-symmetric
    matrix; r_g is read from it. The inconsistency is ‖M₁₂ + M₁₂ᵀ‖ / ‖M₁₂‖ (0 for a
    rigid body), which exposes matrices typed in by hand with a term missing.

    Returns
    -------
    mass, r_g, inconsistency
    """
    m = np.asarray(m_rb, dtype=float)
    mass = float(m[0, 0])
    block = m[:3, 3:]
    skew_part = 0.5 * (block - block.T)
    norm = float(np.linalg.norm(block))
    inconsistency = float(np.linalg.norm(block + block.T) / (2 * norm)) if norm > 0 else 0.0
    # −m S(r) = skew_part → S(r) = −skew_part / m; S(r)[2,1] = x, S(r)[0,2] = y, S(r)[1,0] = z
    s = -skew_part / mass if mass else np.zeros((3, 3))
    return mass, np.array([s[2, 1], s[0, 2], s[1, 0]]), inconsistency


def rotation_matrix(attitude: ArrayLike) -> NDArray[np.float64]:
    """R_b^n(Θ): body-fixed to north-east-down, zyx Euler angles Θ = (φ, θ, ψ), rad.

    Smogeli et al. (2004) eq. (6); v^n = R v^b (eq. 5). Orthogonal: R⁻¹ = Rᵀ.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(rotation_matrix([0, 0, np.pi / 2]) @ [1, 0, 0], 12)  # bow east
    array([0., 1., 0.])
    """
    phi, theta, psi = (float(a) for a in np.asarray(attitude, dtype=float).reshape(3))
    cf, sf = np.cos(phi), np.sin(phi)
    ct, st = np.cos(theta), np.sin(theta)
    cp, sp = np.cos(psi), np.sin(psi)
    return np.array(
        [
            [cp * ct, -sp * cf + cp * st * sf, sp * sf + cp * cf * st],
            [sp * ct, cp * cf + sf * st * sp, -cp * sf + st * sp * cf],
            [-st, ct * sf, ct * cf],
        ]
    )


def attitude_transform(attitude: ArrayLike) -> NDArray[np.float64]:
    """T_Θ(Θ): body angular velocity (p, q, r) to Euler angle rates, Θ̇ = T_Θ ω
    (Smogeli et al. (2004) eqs. 7–8); singular at θ = ±π/2 (raises ValueError there)."""
    phi, theta, _ = (float(a) for a in np.asarray(attitude, dtype=float).reshape(3))
    ct = np.cos(theta)
    if abs(ct) < 1e-9:
        raise ValueError("the Euler angle rates are undefined at pitch ±90°")
    cf, sf, tt = np.cos(phi), np.sin(phi), np.tan(theta)
    return np.array([[1.0, sf * tt, cf * tt], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]])


def velocity_transform(eta: ArrayLike) -> NDArray[np.float64]:
    """J(Θ) = diag(R_b^n(Θ), T_Θ(Θ)) of η̇ = J(Θ)ν (Smogeli et al. (2004) eqs. 9–10), from the pose
    η = (N, E, D, φ, θ, ψ)."""
    attitude = np.asarray(eta, dtype=float).reshape(6)[3:]
    out = np.zeros((6, 6))
    out[:3, :3] = rotation_matrix(attitude)
    out[3:, 3:] = attitude_transform(attitude)
    return out


def point_motion(
    eta: ArrayLike, nu: ArrayLike, r: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Position in the n-frame and velocity in the b-frame of the point at ``r`` (b-frame,
    from O): x_p^n = η_{1:3} + R(Θ) r (Smogeli et al. (2004) eq. 42), v_p^b = H(r) ν
    (eq. 43, its first three components)."""
    eta = np.asarray(eta, dtype=float).reshape(6)
    position = eta[:3] + rotation_matrix(eta[3:]) @ np.asarray(r, dtype=float)
    velocity = (screw_transform(r) @ np.asarray(nu, dtype=float).reshape(6))[:3]
    return position, velocity


def point_load(force: ArrayLike, r: ArrayLike, moment: ArrayLike | None = None):
    """The generalized force at O of a force (and moment) acting at ``r``, all in the
    b-frame: τ = Hᵀ(r) τ_p (Smogeli et al. (2004) eq. 45), i.e. the force and the moment
    r × F (+ M).

    Examples
    --------
    >>> point_load([0, 0, 1e6], [0, 15, 0])   # 1000 kN down at 15 m to starboard
    array([       0.,        0.,  1000000., 15000000.,        0.,        0.])
    """
    tau_p = np.zeros(6)
    tau_p[:3] = np.asarray(force, dtype=float).reshape(3)
    if moment is not None:
        tau_p[3:] = np.asarray(moment, dtype=float).reshape(3)
    return screw_transform(r).T @ tau_p
