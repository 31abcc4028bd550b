"""Linear constraints G ξ = 0 eliminated exactly: ξ = T q.

The columns of T span the null space of G (every motion the joints allow, and no other).
T is built by generalized coordinate partitioning (Wehage & Haug (1982)): a QR
factorisation of G with column pivoting picks r = rank G dependent DOFs (the pivots,
translations before rotations: a hinge's coordinate is its angle), the others are the
independent coordinates q, and

    ξ_dep = −G_dep⁺ G_ind ξ_ind,   T = [I on the independent DOFs; −G_dep⁺ G_ind],

so every q is one of the DOFs (``coordinates`` names them) and T is exact (G T = 0 to
rounding). The equation of motion of the constrained system follows by projection
(virtual work: the constraint forces do no work on allowed motions):

    Tᵀ Z(ω) T q = Tᵀ F   (frequency domain),
    M_q = TᵀMT, B_q = TᵀBT, C_q = TᵀCT, the memory driven by T q̇, its force Tᵀμ (time).

A DOF whose row of T is zero cannot move at all: it is held at zero, and is dropped from
the data (exactly, as ``select_dofs``: its forces do no work).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from cummins.dofs import is_rotation
from cummins.errors import ArgumentError

#: Relative size below which a pivot of G's QR factorisation (G's columns scaled to unit
#: norm) counts as zero: the rank decision.
RANK_TOLERANCE = 1e-9
#: The weight of a rotation's column of G in the pivoting (translations 1): below 1, a
#: rotation is kept as an independent coordinate where a translation can be eliminated
#: instead (the pivots are the largest columns).
ROTATION_WEIGHT = 0.5
#: A row of T smaller than this (relative to T's largest entry) is a DOF held at zero.
HELD_TOLERANCE = 1e-9
#: The constrained inertia TᵀM_RB T (scaled by its diagonal) must have eigenvalues above
#: this: below, a coordinate has no inertia of its own.
INERTIA_TOLERANCE = 1e-8


def null_space_basis(
    g: NDArray[np.float64], labels: Sequence[str]
) -> tuple[NDArray[np.float64], tuple[str, ...]]:
    """(T, coordinates): a basis of the null space of G (n DOFs) whose columns are
    the independent DOFs ``coordinates`` (module docstring). With no constraint rows,
    T = I.

    Raises
    ------
    ArgumentError
        The constraints leave no DOF free.
    """
    n = len(labels)
    g = np.asarray(g, dtype=float).reshape(-1, n)
    if g.shape[0] == 0 or not np.any(g):
        return np.eye(n), tuple(labels)
    scale = np.linalg.norm(g, axis=0)
    # a rotation is the coordinate where it can be: the pivots (the dependent DOFs) are
    # taken among the translations first, so that a hinge's coordinate is its angle, not
    # the swing of the body's reference point (rad, its generalized force in N·m)
    prefer = np.array([ROTATION_WEIGHT if is_rotation(x) else 1.0 for x in labels])
    scaled = g / np.where(scale > 0, scale, 1.0) * prefer
    _, r, pivots = scipy.linalg.qr(scaled, mode="economic", pivoting=True)
    diagonal = np.abs(np.diag(r))
    rank = int(np.sum(diagonal > RANK_TOLERANCE * max(float(diagonal.max()), 1e-300)))
    if rank >= n:
        raise ArgumentError(
            "the joints and DOF selection leave no DOF free: every motion is constrained",
            hint="check the joints (a fixed joint, or a joint to the ground on every body) "
            "and the --dof selection",
        )
    dependent = np.sort(pivots[:rank])
    independent = np.sort(pivots[rank:])
    t = np.zeros((n, independent.size))
    t[independent, np.arange(independent.size)] = 1.0
    if rank:
        t[dependent] = -np.linalg.lstsq(g[:, dependent], g[:, independent], rcond=None)[0]
    return t, tuple(labels[i] for i in independent)


def selection_restrictions(
    joint_rows: NDArray[np.float64], labels: Sequence[str], listed: Sequence[str]
) -> tuple[int, int, tuple[str, ...]]:
    """(kept, allowed, culprits): how a DOF selection restricts the motions the joints
    leave to the DOFs it lists.

    ``allowed`` is the number of independent motions of the ``listed`` DOFs under the
    joints alone (rows ``joint_rows``), ``kept`` that number once every DOF not listed is
    held at zero, and ``culprits`` the DOFs not listed whose holding takes a motion from
    the listed ones: those the joints move with them (a hinged body's heave at its
    reference point, that follows the pitch of the bodies it is hinged to). Holding a
    DOF that moves only with others not listed (the surge of a whole chain) takes
    nothing from the listed DOFs and is not a culprit.
    """
    labels = list(labels)
    n = len(labels)
    joints = np.asarray(joint_rows, dtype=float).reshape(-1, n)
    listed_index = [labels.index(d) for d in listed if d in labels]
    unlisted = [i for i, d in enumerate(labels) if d not in set(listed)]

    def rank_of_listed(rows: NDArray[np.float64]) -> int:
        t = null_space_basis(rows, labels)[0][listed_index]
        norms = np.linalg.norm(t, axis=1)
        t = t[norms > 0] / norms[norms > 0, None]
        if t.size == 0:
            return 0
        s = np.linalg.svd(t, compute_uv=False)
        return int(np.sum(s > 1e-8 * s[0]))

    def holding(indices: Sequence[int]) -> NDArray[np.float64]:
        held = np.zeros((len(indices), n))
        held[np.arange(len(indices)), list(indices)] = 1.0
        return np.vstack([joints, held])

    allowed = rank_of_listed(joints)
    kept = rank_of_listed(holding(unlisted))
    if kept >= allowed:
        return kept, allowed, ()
    culprits = tuple(
        labels[i]
        for i in unlisted
        if rank_of_listed(holding([j for j in unlisted if j != i])) > kept
    )
    return kept, allowed, culprits


def held_dofs(t: NDArray[np.float64]) -> NDArray[np.bool_]:
    """True for the DOFs whose row of T is zero: they cannot move."""
    size = np.abs(t).max(axis=1)
    return size <= HELD_TOLERANCE * max(float(np.abs(t).max()), 1e-300)


def is_locked(rows: NDArray[np.float64], t: NDArray[np.float64]) -> bool:
    """True when the relative motions ``rows`` ξ are zero for every allowed motion ξ = T q
    (relative to the sizes of the rows and of T)."""
    rows = np.atleast_2d(rows)
    scale = np.linalg.norm(rows) * max(float(np.abs(t).max()), 1e-300)
    return bool(np.linalg.norm(rows @ t) <= 1e-9 * max(scale, 1e-300))


def check_inertia(
    mass: NDArray[np.float64], t: NDArray[np.float64], labels: Sequence[str], what: str
) -> None:
    """ArgumentError when TᵀMT is singular: a coordinate (or a combination of them) the
    constraints leave free has no inertia in ``mass`` (``what`` says which matrix).

    The test: the eigenvalues of D TᵀMT D, D = diag(TᵀMT)^(−1/2), must exceed
    :data:`INERTIA_TOLERANCE` (the matrix scaled to a unit diagonal, so translations and
    rotations compare); the message names the DOFs of the eigenvector of the smallest.
    """
    mq = t.T @ mass @ t
    mq = 0.5 * (mq + mq.T)
    diagonal = np.diag(mq)
    if np.any(diagonal <= 0):
        k = int(np.argmin(diagonal))
        moves = _dominant(t[:, k], labels)
        raise ArgumentError(
            f"the constrained system has no {what} in the motion of {moves}: its equation "
            "of motion is singular",
            hint="give the inertia of every body that can move (--mass, "
            "--radii-of-gyration, --inertia-matrix), or constrain that motion",
        )
    scale = 1.0 / np.sqrt(diagonal)
    lam, vec = np.linalg.eigh(scale[:, None] * mq * scale[None, :])
    if lam[0] <= INERTIA_TOLERANCE * max(float(lam[-1]), 1e-300):
        moves = _dominant(t @ (scale * vec[:, 0]), labels)
        raise ArgumentError(
            f"the constrained system's {what} is singular (relative eigenvalue "
            f"{lam[0] / lam[-1]:.2g} < {INERTIA_TOLERANCE:g}): the motion {moves} has no inertia",
            hint="check the inertia matrix of those bodies",
        )


def _dominant(vector: NDArray[np.float64], labels: Sequence[str]) -> str:
    size = np.abs(vector)
    order = np.argsort(size)[::-1]
    keep = [labels[i] for i in order if size[i] > 0.1 * size[order[0]]][:4]
    return " + ".join(keep)
