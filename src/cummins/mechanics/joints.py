"""Joints between two bodies, or between a body and the ground, as linear constraints.

A joint ties ``body`` to ``base`` (another body or the ground) at a point p. Their relative
motion there is

    δ = [u_body(p) − u_base(p); θ_body − θ_base] = (P_body(p) − P_base(p)) ξ

(:mod:`cummins.mechanics.bodies`). With e the joint's axis and (e₁, e₂) two unit vectors
normal to it, each kind of joint sets some components of δ to zero — rows of the
constraint G ξ = 0 — and leaves the others free:

=============== ======================================== ==================================
kind            constrained (rows of G)                  free
=============== ======================================== ==================================
fixed           all six                                  none (the bodies move as one)
translational   e₁·u, e₂·u, θ (3)                        e·u: sliding along the axis
revolute        u (3), e₁·θ, e₂·θ                        e·θ: rotation about the axis
                                                         through p
planar          e·u, e₁·θ, e₂·θ (e the plane's normal)   the two translations in the plane
                                                         and the rotation about e
=============== ======================================== ==================================

WEC-Sim's "Floating (3DOF)" constraint is the planar joint with e = (0, 1, 0): surge,
heave and pitch free. For a translational or planar joint the point does not matter (the
rotations it leaves are those about e, which move every point alike along e's normal
plane), for a revolute joint it does: the body turns about the axis through p. Rows are
linearised about the mean position (small motions), as the equation of motion is.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from cummins.errors import ArgumentError
from cummins.mechanics.bodies import GROUND, BodyFrame

#: The joints, and what each leaves free.
JOINT_KINDS: dict[str, str] = {
    "fixed": "no relative motion (a weld; a body fixed to the ground)",
    "translational": "sliding along the axis only (a prismatic joint)",
    "revolute": "rotation about the axis through the point only (a hinge)",
    "planar": "the two translations in the plane normal to the axis and the rotation "
    "about it (default axis (0, 1, 0): surge, heave, pitch; WEC-Sim's Floating (3DOF))",
}
#: Other names of the joints: the textbooks' prismatic and hinge, WEC-Sim's Rotational.
JOINT_ALIASES: dict[str, str] = {
    "prismatic": "translational",
    "hinge": "revolute",
    "rotational": "revolute",
}
#: The default axis of each kind (the normal of the plane for a planar joint).
DEFAULT_AXIS: dict[str, tuple[float, float, float]] = {
    "fixed": (0.0, 0.0, 1.0),
    "translational": (0.0, 0.0, 1.0),
    "revolute": (0.0, 1.0, 0.0),
    "planar": (0.0, 1.0, 0.0),
}


def unit_vector(value, where: str, what: str = "axis") -> tuple[float, float, float]:
    """A finite, non-zero 3-vector scaled to unit length; ArgumentError otherwise."""
    try:
        v = np.asarray(value, dtype=float).reshape(3)
    except (TypeError, ValueError):
        raise ArgumentError(f"{where}: the {what} must be three numbers, not {value!r}") from None
    norm = float(np.linalg.norm(v))
    if not np.all(np.isfinite(v)) or not norm > 0:
        raise ArgumentError(f"{where}: the {what} must be finite and not zero, not {v.tolist()}")
    return tuple(float(x) for x in v / norm)


def point_vector(value, where: str) -> tuple[float, float, float] | None:
    """A finite 3-vector (m) or None."""
    if value is None:
        return None
    try:
        v = np.asarray(value, dtype=float).reshape(3)
    except (TypeError, ValueError):
        raise ArgumentError(f"{where}: the point must be three numbers, not {value!r}") from None
    if not np.all(np.isfinite(v)):
        raise ArgumentError(f"{where}: the point must be finite, not {v.tolist()}")
    return tuple(float(x) for x in v)


def normal_basis(axis) -> NDArray[np.float64]:
    """Two unit vectors (rows, 2 × 3) normal to ``axis`` and to each other."""
    e = np.asarray(axis, dtype=float).reshape(1, 3)
    _, _, vt = np.linalg.svd(e)
    return vt[1:]


@dataclass(frozen=True)
class Joint:
    """A joint between ``body`` and ``base`` (a body, or ``"ground"``).

    Parameters
    ----------
    kind
        ``"fixed"``, ``"translational"``, ``"revolute"`` or ``"planar"``
        (:data:`JOINT_KINDS`).
    body, base
        Body names as :meth:`cummins.mechanics.bodies.BodyFrame.resolve` takes them
        (``body1``, the file's name for the body, its number) or ``"ground"``.
    axis
        The sliding direction (translational), the hinge axis (revolute) or the normal of
        the plane (planar), in the data's axes; scaled to unit length (default
        :data:`DEFAULT_AXIS`).
    point
        A point on the axis, m, in the data's axes (the data's global origin, as the
        reference points): required for a revolute joint, where it places the hinge;
        for the other kinds the constraints do not depend on it (default: ``body``'s
        reference point).
    name
        A label for messages (default: the kind and the bodies).
    origin
        Where the joint was given (``--joint revolute flap ground``, a YAML key), for
        error messages.
    """

    kind: str
    body: str
    base: str = GROUND
    axis: tuple[float, float, float] | None = None
    point: tuple[float, float, float] | None = None
    name: str = ""
    origin: str = ""

    def __post_init__(self) -> None:
        where = self.where
        kind = str(self.kind).lower()
        kind = JOINT_ALIASES.get(kind, kind)
        if kind not in JOINT_KINDS:
            raise ArgumentError(
                f"{where}: unknown joint {self.kind!r}",
                hint=f"joints: {', '.join(JOINT_KINDS)} (WEC-Sim's Rotational is revolute, "
                "its Floating (3DOF) planar)",
            )
        object.__setattr__(self, "kind", kind)
        if str(self.body).strip().lower() == str(self.base).strip().lower():
            raise ArgumentError(
                f"{where}: a joint needs two different bodies, not {self.body!r} twice"
            )
        if str(self.body).strip().lower() == GROUND:
            raise ArgumentError(
                f"{where}: name the moving body first and the ground second "
                f"({kind} {self.base} {GROUND})"
            )
        axis = DEFAULT_AXIS[kind] if self.axis is None else unit_vector(self.axis, where)
        object.__setattr__(self, "axis", axis)
        object.__setattr__(self, "point", point_vector(self.point, where))
        if kind == "revolute" and self.point is None:
            raise ArgumentError(
                f"{where}: a revolute joint needs the point its axis passes through",
                hint="give it (--point X Y Z after the --joint, in m, in the data's axes)",
            )

    @property
    def label(self) -> str:
        """The name, or ``"revolute flap-ground"``."""
        return self.name or f"{self.kind} {self.body}-{self.base}"

    @property
    def where(self) -> str:
        """Where the joint comes from, for messages."""
        return self.origin or f"joint {self.name or self.kind + ' ' + self.body + '-' + self.base}"

    def describe(self) -> dict:
        """JSON-ready description."""
        return {
            "kind": self.kind,
            "body": self.body,
            "base": self.base,
            "axis": list(self.axis or ()),
            "point": None if self.point is None else list(self.point),
            "name": self.label,
        }


def relative_motion(joint_body: int | None, joint_base: int | None, point, frame: BodyFrame):
    """P_body(p) − P_base(p) (6 × n): [relative translation at p; relative rotation]."""
    return frame.point_motion(joint_body, point) - frame.point_motion(joint_base, point)


def joint_rows(joint: Joint, frame: BodyFrame) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(G, F): the rows of the constraint G ξ = 0 the joint imposes and the rows F ξ of the
    relative motions it leaves free (module docstring), each over all the data's DOFs.

    Raises
    ------
    ArgumentError
        A body the data do not have.
    """
    body = frame.resolve(joint.body, joint.where)
    base = frame.resolve(joint.base, joint.where)
    if body is None:
        raise ArgumentError(f"{joint.where}: the moving body cannot be the ground")
    if body == base:
        raise ArgumentError(f"{joint.where}: {joint.body!r} and {joint.base!r} are the same body")
    point = frame.points[body] if joint.point is None else np.asarray(joint.point)
    rel = relative_motion(body, base, point, frame)
    e = np.asarray(joint.axis, dtype=float)
    normal = normal_basis(e)
    trans, rot = rel[:3], rel[3:]
    if joint.kind == "fixed":
        return rel, np.zeros((0, frame.n))
    if joint.kind == "translational":
        return np.vstack([normal @ trans, rot]), (e @ trans)[None]
    if joint.kind == "revolute":
        return np.vstack([trans, normal @ rot]), (e @ rot)[None]
    # planar: e is the normal of the plane
    return np.vstack([(e @ trans)[None], normal @ rot]), np.vstack(
        [normal @ trans, (e @ rot)[None]]
    )


def free_motion_of(joint: Joint, frame: BodyFrame) -> tuple[NDArray[np.float64], bool]:
    """The one relative motion a translational or revolute joint leaves free, as a row d
    (Δ = d·ξ, m or rad), and whether it is a rotation: what a PTO on the joint acts on.

    Raises
    ------
    ArgumentError
        A fixed joint (nothing free) or a planar one (three motions: say which with a
        PTO of its own along an axis).
    """
    if joint.kind not in ("translational", "revolute"):
        raise ArgumentError(
            f"{joint.where}: a PTO acts on the one motion a translational or revolute joint "
            f"leaves free; a {joint.kind} joint leaves "
            + ("none" if joint.kind == "fixed" else "three")
            + (
                ""
                if joint.kind == "fixed"
                else ": give a PTO between the bodies along or about an axis instead"
            )
        )
    _, free = joint_rows(joint, frame)
    return free[0], joint.kind == "revolute"
