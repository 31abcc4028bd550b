"""The stiffness of the static loads the joints carry (joint pre-load).

The data's restoring C is that of each body floating freely about its reference point o.
A body whose buoyancy ρg∇ differs from its weight mg is held by its joints: the net
static force F = (ρ∇ − m) g ẑ goes through them. As the body turns about a joint's axis
instead of about o, o moves on a circle and F does work to second order in the rotation:
a stiffness the free body's C does not hold. About a hinge of axis a through h,

    K = F·(o − h) − (F·a)(a·(o − h)),

F (z_o − z_h) for a horizontal hinge (a flap held down by a hinge below it: positive,
restoring). In general (Lagrange's multipliers of the constraints, the textbook
linearisation of a constrained system about its static equilibrium): with the exact
constraints g(ξ) = 0, whose linearisation are the joint rows G ξ = 0, the reactions ν
solve Gᵀν = −f₀ (f₀ the static forces on the DOFs, here the net forces F of each body on
its translations), and the constrained system's stiffness is

    C_q = Tᵀ (C − Σ_k ν_k ∇²g_k) T.

A row that holds the relative translation of two bodies at a point p along a fixed
direction n has ∇²g = Hₙ(p − o_body) on the body's rotations and −Hₙ(p − o_base) on the
base's, with Hₙ(v) = ½(n vᵀ + v nᵀ) − (n·v) I (from u(p) = u(o) + R(θ)(p − o) to second
order, R(θ)v ≈ v + θ × v + ½ θ × (θ × v)); rows on the rotations, and on the ground, have
none (for a joint to the ground exactly; between two moving bodies, a joint whose
directions turn with its base adds terms in the reactions of those rows: left out, and
said so when such a reaction is not zero). Where the joints cannot carry f₀ (Tᵀf₀ ≠ 0:
a float whose buoyancy is not its weight on a PTO along the vertical, a hinge beside the
force's line), the mean position is not an equilibrium: a warning names the coordinate.

:func:`preload_stiffness` computes it; :func:`cummins.mechanics.assemble` adds it to the
data's ``additional_stiffness`` (said in ``history``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.dofs import DOF_NAMES
from cummins.hydrodb import dof_matrix
from cummins.mechanics.bodies import BodyFrame
from cummins.mechanics.joints import Joint, normal_basis

#: A reaction or a residual force below this fraction of the largest static force counts
#: as zero.
NEGLIGIBLE = 1e-9
#: A body whose buoyancy and weight differ by less than this fraction of them floats
#: freely: the difference is the rounding of the numbers they come from, not a load for
#: the joints to carry — a mass given to six digits (WEC-Sim's RM3: 725 833 kg against
#: ρ∇ = 725 833.3 kg), or a mass and a volume both printed to five (AQWA's listing: up to
#: 5e-5 each; the floating OWC's water column, 1.4e-5, warned of at 1e-5). A real
#: imbalance that small would add 1e-4 of the weight times its lever arm to a
#: restoring of the weight times the metacentric height.
BALANCED = 1e-4


@dataclass(frozen=True)
class Preload:
    """What the joints' static loads add (:func:`preload_stiffness`).

    Attributes
    ----------
    stiffness
        n × n, over the data's DOFs (N/m, N, N·m/rad), symmetric.
    forces
        The net static force (ρ∇ − m) g of each body, N (upward positive).
    unbalanced
        ``(coordinate, value)`` of the static forces the joints do not carry (Tᵀ f₀),
        N or N·m: the mean position is not an equilibrium there.
    left_out
        The joints whose rows carry a reaction whose second-order terms are not included
        (directions turning with a moving base).
    """

    stiffness: NDArray[np.float64]
    forces: NDArray[np.float64]
    unbalanced: tuple[tuple[str, float], ...] = ()
    left_out: tuple[str, ...] = ()


def net_static_forces(ds: xr.Dataset, frame: BodyFrame) -> NDArray[np.float64] | None:
    """(ρ∇_b − m_b) g of each body, N (z up), from the data's ``displaced_volume`` and the
    mass of ``inertia_matrix`` (0 for a body within :data:`BALANCED` of floating freely);
    None when the data lack either."""
    volume = ds.attrs.get("displaced_volume")
    if volume is None or "inertia_matrix" not in ds:
        return None
    volumes = np.atleast_1d(np.asarray(volume, dtype=float)).reshape(-1)
    count = len(frame.prefixes)
    if volumes.size == 1:
        volumes = np.repeat(volumes, count)
    if volumes.size != count or not np.all(np.isfinite(volumes)):
        return None
    inertia = dof_matrix(ds, "inertia_matrix")
    rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
    out = np.zeros(count)
    for b in range(count):
        k = frame.dof_index(b, "Heave")
        if k is None:
            return None
        out[b] = net_buoyancy(rho * volumes[b], inertia[k, k]) * g
    return out


def net_buoyancy(buoyancy: float, mass: float) -> float:
    """ρ∇ − m of a body, kg (``buoyancy`` ρ∇ and ``mass`` m in kg): 0 within
    :data:`BALANCED` of floating freely, the rounding of the numbers they come from."""
    if abs(buoyancy - mass) > BALANCED * max(abs(buoyancy), abs(mass)):
        return buoyancy - mass
    return 0.0


def _hessian_form(n: NDArray, v: NDArray) -> NDArray[np.float64]:
    """Hₙ(v) = ½(n vᵀ + v nᵀ) − (n·v) I: the second derivative of n·(R(θ)v) in θ."""
    return 0.5 * (np.outer(n, v) + np.outer(v, n)) - float(n @ v) * np.eye(3)


def _rotations(frame: BodyFrame, body: int | None) -> list[int | None]:
    """The DOF indices of the body's roll, pitch and yaw (None where the data lack one)."""
    if body is None:
        return [None, None, None]
    return [frame.dof_index(body, name) for name in DOF_NAMES[3:]]


def _embedded(h3: NDArray, index: Sequence[int | None], n: int) -> NDArray[np.float64]:
    out = np.zeros((n, n))
    for a, i in enumerate(index):
        for b, j in enumerate(index):
            if i is not None and j is not None:
                out[i, j] += h3[a, b]
    return out


def joint_row_hessians(joint: Joint, frame: BodyFrame) -> tuple[NDArray[np.float64], NDArray]:
    """(∇²g_k of each row of :func:`cummins.mechanics.joints.joint_rows`' G, (rows, n, n);
    the rows whose second-order terms are left out: directions that turn with a moving
    base) — module docstring."""
    body = frame.resolve(joint.body, joint.where)
    base = frame.resolve(joint.base, joint.where)
    point = frame.points[body] if joint.point is None else np.asarray(joint.point)
    n = frame.n
    e = np.asarray(joint.axis, dtype=float)
    normal = normal_basis(e)
    axes = np.eye(3)

    def translation(direction: NDArray) -> NDArray[np.float64]:
        arm = point - frame.points[body]
        out = _embedded(_hessian_form(direction, arm), _rotations(frame, body), n)
        if base is not None:
            out -= _embedded(
                _hessian_form(direction, point - frame.points[base]), _rotations(frame, base), n
            )
        return out

    zero = np.zeros((n, n))
    moving = base is not None
    if joint.kind in ("fixed", "revolute"):  # the whole relative translation at p
        trans = [translation(a) for a in axes]
        rot_count = 3 if joint.kind == "fixed" else 2
        rows = trans + [zero] * rot_count
        turning = [False] * 3 + [moving] * rot_count
    elif joint.kind == "translational":
        rows = [translation(a) for a in normal] + [zero] * 3
        turning = [moving] * 5
    else:  # planar
        rows = [translation(e)] + [zero] * 2
        turning = [moving] * 3
    return np.array(rows), np.array(turning, dtype=bool)


def preload_stiffness(
    frame: BodyFrame,
    joints: Sequence[Joint],
    g: NDArray[np.float64],
    basis: NDArray[np.float64],
    coordinates: Sequence[str],
    forces: NDArray[np.float64],
) -> Preload:
    """The stiffness the static forces ``forces`` (one per body, N, upward) add through
    the constraints (module docstring). ``g``: every constraint row (the joints' rows
    first, in order, then the DOF selection's); ``basis``: T over all the DOFs, its
    columns the ``coordinates``."""
    n = frame.n
    if not np.any(forces):
        return Preload(np.zeros((n, n)), forces)
    f0 = np.zeros(n)
    for b, force in enumerate(forces):
        k = frame.dof_index(b, "Heave")
        if k is not None:
            f0[k] = force
    scale = float(np.abs(forces).max())
    free = basis.T @ f0  # the static forces on the free coordinates
    unbalanced = tuple(
        (coordinates[k], float(value))
        for k, value in enumerate(free)
        if abs(value) > NEGLIGIBLE * scale * max(float(np.abs(basis[:, k]).max()), 1.0)
    )
    nu = np.linalg.lstsq(g.T, -f0, rcond=None)[0] if g.size else np.zeros(0)
    stiffness = np.zeros((n, n))
    left_out = []
    start = 0
    for joint in joints:
        hessians, turning = joint_row_hessians(joint, frame)
        count = hessians.shape[0]
        reactions = nu[start : start + count]
        stiffness -= np.einsum("k,kij->ij", reactions, hessians)
        if np.any(np.abs(reactions[turning]) > NEGLIGIBLE * scale):
            left_out.append(joint.label)
        start += count
    stiffness = 0.5 * (stiffness + stiffness.T)
    return Preload(stiffness, forces, unbalanced, tuple(left_out))
