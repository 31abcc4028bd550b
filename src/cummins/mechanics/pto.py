"""Power take-offs: a linear spring and damper on a relative motion.

A PTO acts on one relative displacement Δ = dᵀξ (m or rad) of the DOF vector ξ:

* between two DOFs, ``dofs=("body1__Heave", "body2__Heave")``: d = e₁ − e₂ (the second
  may be ``"ground"``);
* on the motion a translational or revolute joint leaves free, ``joint=...``: sliding
  along its axis, or rotation about it;
* between two bodies (or a body and the ground) along an axis, ``kind="translational"``:
  Δ = e·(u_body(p) − u_base(p)) at the point p (default: ``body``'s reference point), or
  about an axis, ``kind="rotational"``: Δ = e·(θ_body − θ_base).

Its force on the system is −d (kΔ + cΔ̇) (on ``body`` along +e, the opposite on ``base``),
so that the equation of motion gains the stiffness k d dᵀ and the damping c d dᵀ. The
power it absorbs is P = (kΔ + cΔ̇) Δ̇, whose mean in a steady harmonic motion
Δ(t) = Re{Δ̂ e^{iωt}} is ½ c ω² |Δ̂|² (the time-average power of a mechanical resistance,
Falnes (2002); the spring's share averages to zero). Per metre of wave amplitude a RAO's
power is in W/m².
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.dofs import is_rotation
from cummins.errors import ArgumentError
from cummins.mechanics.bodies import GROUND, BodyFrame
from cummins.mechanics.joints import (
    Joint,
    free_motion_of,
    point_vector,
    relative_motion,
    unit_vector,
)

#: What a PTO between two bodies acts on.
PTO_KINDS = ("translational", "rotational")


@dataclass(frozen=True)
class PTO:
    """A linear power take-off (module docstring): give ``dofs``, ``joint`` or ``body``.

    Parameters
    ----------
    damping
        c ≥ 0: N·s/m (translation) or N·m·s/rad (rotation).
    stiffness
        k: N/m or N·m/rad (negative for a reactive control that softens the system: the
        model's stability is checked).
    dofs
        (DOF, DOF or ``"ground"``): Δ = ξ₁ − ξ₂.
    joint
        The name of a joint of the system (or its 1-based number) whose free motion the
        PTO acts on (a translational or revolute joint).
    body, base
        Bodies (``base`` may be ``"ground"``) for a PTO along or about ``axis``.
    kind
        With ``body``: ``"translational"`` (along ``axis``, at ``point``) or
        ``"rotational"`` (about ``axis``).
    axis
        Unit vector (scaled), default (0, 0, 1).
    point
        Where the relative translation is taken, m (default: ``body``'s reference point).
    name
        The label of the PTO in results (default ``pto1``, ``pto2`` … in order).
    origin
        Where it was given, for error messages.
    """

    damping: float = 0.0
    stiffness: float = 0.0
    dofs: tuple[str, str] | None = None
    joint: str | int | None = None
    body: str | None = None
    base: str = GROUND
    kind: str = "translational"
    axis: tuple[float, float, float] | None = None
    point: tuple[float, float, float] | None = None
    name: str = ""
    origin: str = ""

    def __post_init__(self) -> None:
        where = self.where
        given = [k for k in ("dofs", "joint", "body") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ArgumentError(
                f"{where}: a PTO acts between two DOFs (dofs), on a joint (joint) or between "
                f"two bodies (body, base, axis): give one of them, not {', '.join(given) or 'none'}"
            )
        for key in ("damping", "stiffness"):
            try:
                value = float(getattr(self, key))
            except (TypeError, ValueError):
                raise ArgumentError(f"{where}: the {key} must be a number") from None
            if not np.isfinite(value):
                raise ArgumentError(f"{where}: the {key} must be finite, not {value}")
            object.__setattr__(self, key, value)
        if self.damping < 0:
            raise ArgumentError(
                f"{where}: the damping must be >= 0 (a PTO absorbs power), not {self.damping:g}"
            )
        if self.dofs is not None:
            pair = tuple(str(d) for d in self.dofs)
            if len(pair) != 2 or pair[0] == pair[1]:
                raise ArgumentError(f"{where}: a PTO between DOFs needs two different DOFs")
            object.__setattr__(self, "dofs", pair)
        if self.kind not in PTO_KINDS:
            raise ArgumentError(
                f"{where}: kind must be {' or '.join(PTO_KINDS)}, not {self.kind!r}"
            )
        if self.axis is not None:
            object.__setattr__(self, "axis", unit_vector(self.axis, where))
        object.__setattr__(self, "point", point_vector(self.point, where))

    @property
    def where(self) -> str:
        """Where the PTO comes from, for messages."""
        if self.origin:
            return self.origin
        if self.dofs is not None:
            return f"PTO {self.name or ''} between {self.dofs[0]} and {self.dofs[1]}".replace(
                "  ", " "
            )
        if self.joint is not None:
            return f"PTO {self.name or ''} on joint {self.joint}".replace("  ", " ")
        return f"PTO {self.name or ''} between {self.body} and {self.base}".replace("  ", " ")

    def describe(self) -> dict:
        """JSON-ready description."""
        out: dict = {"name": self.name, "damping": self.damping, "stiffness": self.stiffness}
        if self.dofs is not None:
            out["dofs"] = list(self.dofs)
        elif self.joint is not None:
            out["joint"] = self.joint
        else:
            out.update(
                body=self.body,
                base=self.base,
                kind=self.kind,
                axis=list(self.axis or (0.0, 0.0, 1.0)),
                point=None if self.point is None else list(self.point),
            )
        return out


@dataclass(frozen=True, eq=False)
class PTOLine:
    """A PTO resolved on a set of DOFs: Δ = ``direction`` · ξ.

    Attributes
    ----------
    name
        Its label (the ``pto`` coordinate of results).
    direction
        d (n,), over the DOFs it was resolved on.
    stiffness, damping
        k, c.
    rotational
        Δ in rad (forces in N·m) rather than m (N).
    description
        One line: what it acts on.
    """

    name: str
    direction: NDArray[np.float64]
    stiffness: float
    damping: float
    rotational: bool
    description: str

    @property
    def units(self) -> dict[str, str]:
        """Units of Δ, Δ̇, the force and the power."""
        if self.rotational:
            return {"displacement": "rad", "velocity": "rad/s", "force": "N m", "power": "W"}
        return {"displacement": "m", "velocity": "m/s", "force": "N", "power": "W"}

    def on(self, labels: Sequence[str], source: Sequence[str]) -> PTOLine:
        """The same PTO on the DOFs ``labels`` (a subset of ``source``, the DOFs it was
        resolved on; the DOFs left out are held at zero)."""
        index = [list(source).index(str(d)) for d in labels]
        return PTOLine(
            self.name,
            self.direction[index],
            self.stiffness,
            self.damping,
            self.rotational,
            self.description,
        )


def resolve_pto(pto: PTO, k: int, frame: BodyFrame, joints: Sequence[Joint]) -> PTOLine:
    """The :class:`PTOLine` of ``pto`` (the ``k``-th, 1-based) over all the data's DOFs.

    Raises
    ------
    ArgumentError
        A DOF, body or joint the data (or the system) do not have; a PTO between a
        translation and a rotation; a joint with no single free motion.
    """
    where = pto.where
    name = pto.name or f"pto{k}"
    if pto.dofs is not None:
        first, second = pto.dofs
        d = np.zeros(frame.n)
        d[frame.dof(first, where)] = 1.0
        text = f"{first} relative to "
        if second.lower() == GROUND:
            text += GROUND
        else:
            d[frame.dof(second, where)] = -1.0
            if is_rotation(first) != is_rotation(second):
                raise ArgumentError(
                    f"{where}: {first} and {second} are not both translations or both "
                    "rotations: their difference is not a displacement"
                )
            text += second
        return PTOLine(name, d, pto.stiffness, pto.damping, is_rotation(first), text)
    if pto.joint is not None:
        joint = _find_joint(pto, joints)
        d, rotational = free_motion_of(joint, frame)
        motion = "rotation about" if rotational else "translation along"
        text = (
            f"{motion} {_axis_text(joint.axis)} of {joint.body} relative to {joint.base} "
            f"({joint.label})"
        )
        return PTOLine(name, d, pto.stiffness, pto.damping, rotational, text)
    body = _resolve_body_or_dof(frame, str(pto.body), where)
    base = frame.resolve(pto.base, where)
    if body is None or body == base:
        raise ArgumentError(f"{where}: a PTO needs a moving body and another body or the ground")
    axis = np.asarray(pto.axis or (0.0, 0.0, 1.0))
    point = frame.points[body] if pto.point is None else np.asarray(pto.point)
    rel = relative_motion(body, base, point, frame)
    rotational = pto.kind == "rotational"
    d = axis @ (rel[3:] if rotational else rel[:3])
    motion = "rotation about" if rotational else "translation along"
    text = f"{motion} {_axis_text(axis)} of {pto.body} relative to {pto.base}"
    return PTOLine(name, d, pto.stiffness, pto.damping, rotational, text)


def _resolve_body_or_dof(frame: BodyFrame, name: str, where: str) -> int | None:
    """The body a PTO between bodies names; a name that is neither a body nor a DOF (the
    command line takes ``--pto A B`` for DOFs too) is refused naming both lists, and one
    that differs from a DOF only in case says which it means."""
    try:
        return frame.resolve(name, where)
    except ArgumentError as exc:
        near = [label for label in frame.labels if label.lower() == name.lower()]
        meant = f"did you mean the DOF {near[0]!r} (names are case-sensitive)? " if near else ""
        raise ArgumentError(
            f"{where}: the data have no body or DOF {name!r}",
            hint=f"{meant}the DOFs are {', '.join(frame.labels)}; {exc.hint}",
        ) from None


def _find_joint(pto: PTO, joints: Sequence[Joint]) -> Joint:
    key = str(pto.joint)
    for joint in joints:
        if key in (joint.name, joint.label):
            return joint
    if key.isdigit() and 1 <= int(key) <= len(joints):
        return joints[int(key) - 1]
    listed = ", ".join(f"{k + 1} ({j.label})" for k, j in enumerate(joints)) or "none"
    raise ArgumentError(f"{pto.where}: no joint {key!r}; the joints are {listed}")


def _axis_text(axis) -> str:
    return "(" + ", ".join(f"{x:.4g}" for x in np.asarray(axis, dtype=float)) + ")"


def pto_matrices(
    lines: Sequence[PTOLine], n: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(Σ k d dᵀ, Σ c d dᵀ): the stiffness and damping the PTOs add (n × n)."""
    stiffness = np.zeros((n, n))
    damping = np.zeros((n, n))
    for line in lines:
        outer = np.outer(line.direction, line.direction)
        stiffness += line.stiffness * outer
        damping += line.damping * outer
    return stiffness, damping


def pto_time_series(
    lines: Sequence[PTOLine], motion: ArrayLike, velocity: ArrayLike
) -> dict[str, xr.DataArray]:
    """``pto_displacement`` Δ, ``pto_velocity`` Δ̇, ``pto_force`` −(kΔ + cΔ̇) (on the
    first body, along or about the axis) and ``pto_power`` (kΔ + cΔ̇)Δ̇ (absorbed,
    W), dims (time, pto), from ξ and ξ̇ (time, n)."""
    xi = np.asarray(motion, dtype=float)
    v = np.asarray(velocity, dtype=float)
    d = np.stack([line.direction for line in lines], axis=1)
    k = np.array([line.stiffness for line in lines])
    c = np.array([line.damping for line in lines])
    delta, rate = xi @ d, v @ d
    force = -(k * delta + c * rate)
    units = [line.units for line in lines]
    return {
        "pto_displacement": _variable(delta, units, "displacement", "PTO relative displacement"),
        "pto_velocity": _variable(rate, units, "velocity", "PTO relative velocity"),
        "pto_force": _variable(force, units, "force", "PTO force on the first body, -(k x + c v)"),
        "pto_power": _variable(-force * rate, units, "power", "power absorbed by the PTO"),
    }


def _variable(values, units, key: str, long_name: str) -> xr.DataArray:
    return xr.DataArray(
        values,
        dims=("time", "pto"),
        attrs={"units": " | ".join(dict.fromkeys(u[key] for u in units)), "long_name": long_name},
    )


def pto_frequency_response(
    lines: Sequence[PTOLine], omega: ArrayLike, motion: ArrayLike
) -> dict[str, NDArray]:
    """Per unit wave amplitude, from complex motions X (..., n) at the frequencies ω
    (broadcast against X's leading axes): ``displacement`` Δ̂ = dᵀX, ``force``
    −(k + iωc)Δ̂ and the mean absorbed ``power`` ½ c ω² |Δ̂|² (W/m²), each (..., n_pto)."""
    x = np.asarray(motion, dtype=complex)
    w = np.asarray(omega, dtype=float)
    w = w.reshape(w.shape + (1,) * (x.ndim - 1 - w.ndim))[..., None]
    d = np.stack([line.direction for line in lines], axis=1)
    k = np.array([line.stiffness for line in lines])
    c = np.array([line.damping for line in lines])
    delta = x @ d
    return {
        "displacement": delta,
        "force": -(k + 1j * w * c) * delta,
        "power": 0.5 * c * w**2 * np.abs(delta) ** 2,
    }
