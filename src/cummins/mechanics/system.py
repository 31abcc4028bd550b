"""A multi-body system: which DOFs move, the joints between bodies, the PTOs.

:class:`MechanicalSystem` is a small frozen description that the frequency domain
(:func:`cummins.seakeeping.frequency_domain.motion_rao`), the vessel of the time domain
(:func:`cummins.vessel.vessel_from_hydrodb`) and batch studies all take: the DOFs kept
(the others held at zero, as ``--dof`` does), the joints (:mod:`cummins.mechanics.joints`),
the power take-offs (:mod:`cummins.mechanics.pto`) and whether the radiation coupling
between bodies is kept (``body_coupling``, default True: the complete physics; False as
WEC-Sim by default, :mod:`cummins.mechanics.coupling`). Moorings are stiffness matrices on
the data (``cummins.with_external_terms``, ``--external-stiffness``).

:func:`assemble` applies it to a dataset: the constraint rows of every joint and of every
DOF left out form G; ξ = T q spans its null space (:mod:`cummins.mechanics.constraints`);
the DOFs that cannot move are dropped from the data (exactly); each PTO becomes a row
d over the DOFs that remain. The result, :class:`Assembly`, holds the reduced data, T and
the PTOs; outputs stay in the body DOFs (ξ = T q).

Examples
--------
WEC-Sim's RM3 (float ``body1`` on a PTO sliding along the spar ``body2``, the spar on a
heave-only joint to the ground):

>>> rm3 = MechanicalSystem(
...     joints=(Joint("translational", "body2", "ground", axis=(0, 0, 1)),
...             Joint("translational", "body1", "body2", axis=(0, 0, 1), name="pto")),
...     ptos=(PTO(joint="pto", damping=1.2e6),),
...     body_coupling=False)
>>> rm3.describe()["joints"][1]["kind"]
'translational'
"""

from __future__ import annotations

import json
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import ArgumentError, AssumptionWarning
from cummins.hydrodb import add_history, dof_matrix, select_dofs
from cummins.mechanics.bodies import BodyFrame, body_frame, body_sizes
from cummins.mechanics.constraints import (
    check_inertia,
    held_dofs,
    is_locked,
    null_space_basis,
    selection_restrictions,
)
from cummins.mechanics.coupling import without_body_coupling
from cummins.mechanics.joints import JOINT_KINDS, Joint, joint_rows
from cummins.mechanics.preload import Preload, net_static_forces, preload_stiffness
from cummins.mechanics.pto import PTO, PTOLine, pto_matrices, resolve_pto


@dataclass(frozen=True)
class MechanicalSystem:
    """Bodies joined by joints, with PTOs (module docstring).

    Parameters
    ----------
    joints
        :class:`~cummins.mechanics.joints.Joint` s.
    ptos
        :class:`~cummins.mechanics.pto.PTO` s (named ``pto1``, ``pto2`` … unless named).
    dofs
        The DOFs that may move (None: all); the others are held at zero.
    body_coupling
        Keep the radiation coupling between bodies (default); False leaves it out, as
        WEC-Sim does by default.
    """

    joints: tuple[Joint, ...] = ()
    ptos: tuple[PTO, ...] = ()
    dofs: tuple[str, ...] | None = None
    body_coupling: bool = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "joints", tuple(self.joints))
        object.__setattr__(self, "ptos", tuple(self.ptos))
        for k, joint in enumerate(self.joints):
            if not isinstance(joint, Joint):
                raise ArgumentError(f"joints[{k}] is not a Joint: {joint!r}")
        for k, pto in enumerate(self.ptos):
            if not isinstance(pto, PTO):
                raise ArgumentError(f"ptos[{k}] is not a PTO: {pto!r}")
        if self.dofs is not None:
            dofs = tuple(str(d) for d in self.dofs)
            if not dofs:
                raise ArgumentError("dofs: an empty selection leaves no DOF free")
            object.__setattr__(self, "dofs", dofs)
        names = [p.name for p in self.ptos if p.name]
        if len(set(names)) != len(names):
            raise ArgumentError(f"two PTOs share a name: {', '.join(names)}")
        object.__setattr__(self, "body_coupling", bool(self.body_coupling))

    @property
    def is_plain(self) -> bool:
        """No joint, no PTO, body coupling kept (a DOF selection at most)."""
        return not self.joints and not self.ptos and self.body_coupling

    def describe(self) -> dict[str, Any]:
        """JSON-ready description (stored in the attributes of results)."""
        return {
            "dofs": None if self.dofs is None else list(self.dofs),
            "joints": [j.describe() for j in self.joints],
            "ptos": [p.describe() for p in self.ptos],
            "body_coupling": self.body_coupling,
        }

    def coupling_note(self) -> str:
        """One line: whether the radiation coupling between bodies is in the model."""
        if self.body_coupling:
            return "body coupling on: the radiation coupling between bodies is included"
        return (
            "body coupling off: the radiation coupling between bodies is left out "
            "(as WEC-Sim by default)"
        )


@dataclass(frozen=True, eq=False)
class Assembly:
    """A :class:`MechanicalSystem` applied to a dataset (:func:`assemble`).

    Attributes
    ----------
    system
        The description.
    ds
        The data on the DOFs that can move (cross-body radiation terms zero with
        ``body_coupling=False``).
    basis
        T (n × m): ξ = T q over ``ds``'s DOFs.
    coordinates
        The DOFs chosen as the independent coordinates q.
    ptos
        The PTOs resolved on ``ds``'s DOFs.
    held
        The DOFs of the data that cannot move (dropped from ``ds``).
    preload
        One line: the stiffness the joints' pre-load adds to each coordinate
        (:mod:`cummins.mechanics.preload`), empty when it adds none.
    """

    system: MechanicalSystem
    ds: xr.Dataset
    basis: NDArray[np.float64]
    coordinates: tuple[str, ...]
    ptos: tuple[PTOLine, ...]
    held: tuple[str, ...]
    preload: str = ""

    @property
    def dofs(self) -> tuple[str, ...]:
        """The DOFs of ``ds`` (those that can move)."""
        return tuple(str(d) for d in self.ds.influenced_dof.values)

    @property
    def is_constrained(self) -> bool:
        """True when T is not the identity."""
        n, m = self.basis.shape
        return n != m or not np.array_equal(self.basis, np.eye(n))

    def pto_matrices(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(stiffness, damping) the PTOs add, n × n."""
        return pto_matrices(self.ptos, len(self.dofs))

    def joined_motion(self):
        """The mechanics a radiation fit aims at
        (:class:`~cummins.radiation.fit.motion.JoinedMotion`: T and the PTOs' stiffness
        and damping), None when the bodies are neither constrained nor joined by a PTO."""
        if not (self.is_constrained or self.ptos):
            return None
        from cummins.radiation.fit.motion import JoinedMotion

        return JoinedMotion(self.basis if self.is_constrained else None, *self.pto_matrices())

    def attrs(self) -> dict[str, str]:
        """Attributes for results: ``body_coupling`` (on/off), ``system`` (JSON),
        ``constrained_coordinates``, ``held_dofs``, ``ptos`` (one line each) and
        ``joint_preload`` when the joints' pre-load adds a stiffness."""
        return {
            **({"joint_preload": self.preload} if self.preload else {}),
            "body_coupling": "on" if self.system.body_coupling else "off",
            "body_coupling_note": self.system.coupling_note(),
            "system": json.dumps(self.system.describe()),
            "constrained_coordinates": ", ".join(self.coordinates),
            "held_dofs": ", ".join(self.held),
            "ptos": "\n".join(f"{p.name}: {p.description}" for p in self.ptos),
        }


def assemble(ds: xr.Dataset, system: MechanicalSystem) -> Assembly:
    """Apply ``system`` to ``ds`` (module docstring).

    Parameters
    ----------
    ds
        A ``HydroDB`` with all the DOFs of its bodies (select DOFs through
        ``system.dofs``, not before: the reference points are stored per body).
    system
        The description.

    Raises
    ------
    ArgumentError
        A joint or PTO on a body or DOF the data do not have; constraints that leave no
        DOF free; a joint or PTO the other constraints lock (contradictory joints and
        DOF selection); a motion left free without inertia.
    """
    frame = body_frame(ds)
    labels = list(frame.labels)
    rows: list[NDArray] = []
    free: list[tuple[Joint, NDArray]] = []
    for joint in system.joints:
        g, f = joint_rows(joint, frame)
        rows.append(g)
        if f.size:
            free.append((joint, f))
    if system.dofs is not None:
        unknown = [d for d in system.dofs if d not in labels]
        if unknown:
            raise ArgumentError(
                f"dofs: the data have no DOF {unknown[0]!r}", hint=f"DOFs: {', '.join(labels)}"
            )
        for i, label in enumerate(labels):
            if label not in system.dofs:
                row = np.zeros((1, frame.n))
                row[0, i] = 1.0
                rows.append(row)
    lines = [resolve_pto(p, k + 1, frame, system.joints) for k, p in enumerate(system.ptos)]
    _unique_names(lines)
    g = np.vstack(rows) if rows else np.zeros((0, frame.n))
    try:
        t, coordinates = null_space_basis(g, labels)
    except ArgumentError:
        if system.dofs is None or not system.joints:
            raise
        joints_only = np.vstack([joint_rows(j, frame)[0] for j in system.joints])
        _, free_dofs = null_space_basis(joints_only, labels)  # raises if the joints alone do
        raise ArgumentError(
            f"the joints and the DOF selection ({', '.join(system.dofs)}) contradict each "
            f"other: together they leave no DOF free, the joints alone let "
            f"{', '.join(free_dofs)} move",
            hint="keep DOFs the joints let move, or leave the DOF selection out",
        ) from None
    if system.dofs is not None and system.joints:
        _warn_selection(np.vstack(rows[: len(system.joints)]), labels, system.dofs)
    _warn_far_points(ds, frame, system)
    selection = "the DOF selection" if system.dofs is not None else ""
    for joint, f in free:
        if is_locked(f, t):
            others = " and ".join(x for x in (selection, "the other joints") if x)
            raise ArgumentError(
                f"{joint.where}: the {joint.kind} joint cannot move: {others} hold the "
                f"motion it leaves free ({JOINT_KINDS[joint.kind].split(' (')[0]})",
                hint="the joint and the DOF selection contradict each other: keep the DOFs "
                "the joint moves, or leave the DOF selection out",
            )
    for pto, line in zip(system.ptos, lines, strict=True):
        if is_locked(line.direction, t):
            raise ArgumentError(
                f"{pto.where}: the PTO's motion ({line.description}) is held at zero by the "
                "joints and DOF selection: it can absorb nothing",
                hint="check the DOFs, the axis and the joints",
            )
    held = held_dofs(t)
    keep = [label for label, h in zip(labels, held, strict=True) if not h]
    out = ds if system.body_coupling else without_body_coupling(ds)
    if held.any():
        out = select_dofs(out, keep)
    basis = t[~held]
    coordinates = tuple(c for c in coordinates if c in keep)
    ptos = tuple(line.on(keep, labels) for line in lines)
    if "inertia_matrix" in out:
        check_inertia(dof_matrix(out, "inertia_matrix"), basis, keep, "rigid-body inertia")
    preload = _joint_preload(ds, frame, system, g, t, coordinates)
    note = ""
    if preload is not None:
        out = _with_preload(out, preload, [labels.index(k) for k in keep])
        note = preload_note(preload, t, coordinates)
    if out is ds:  # the caller's data keep their attributes
        out = ds.copy()
    out.attrs["body_coupling"] = "on" if system.body_coupling else "off"
    if not system.is_plain or held.any():
        add_history(
            out,
            f"mechanical system: {len(system.joints)} joints, {len(ptos)} PTOs; "
            f"coordinates {', '.join(coordinates)}"
            + (f"; held at zero: {', '.join(np.asarray(labels)[held])}" if held.any() else ""),
        )
    held_labels = tuple(np.asarray(labels)[held].tolist())
    return Assembly(system, out, basis, coordinates, ptos, held_labels, note)


def preload_note(preload: Preload, t: NDArray[np.float64], coordinates: Sequence[str]) -> str:
    """One line: the stiffness the joints' pre-load adds to each coordinate q, the
    diagonal of Tᵀ K T (N/m, N·m/rad), and the static forces that cause it; empty when
    it adds none."""
    from cummins.dofs import is_rotation

    added = np.diag(t.T @ preload.stiffness @ t)
    scale = max(float(np.abs(preload.stiffness).max()), 1e-300)
    terms = [
        f"{value:+.4g} {'N·m/rad' if is_rotation(name) else 'N/m'} on {name}"
        for name, value in zip(coordinates, added, strict=True)
        if abs(value) > 1e-9 * scale
    ]
    if not terms:
        return ""
    forces = ", ".join(f"{f:.6g} N" for f in preload.forces)
    return (
        f"joint pre-load: {', '.join(terms)} (the bodies' net static forces (ρ∇ − m)g = "
        f"{forces}, carried by the joints)"
    )


#: A joint's or a PTO's point farther than this many body lengths from the bodies it
#: ties is taken for a slip of units or axes, and warned of.
FAR_POINT = 10.0


def _warn_selection(joint_rows: NDArray, labels: Sequence[str], listed: Sequence[str]) -> None:
    """A warning when the DOF selection takes from the DOFs it lists motions the joints
    give them (:func:`~cummins.mechanics.constraints.selection_restrictions`): every DOF
    not listed is held at zero, even one the joints move with the DOFs listed."""
    kept, allowed, culprits = selection_restrictions(joint_rows, labels, listed)
    if kept >= allowed:
        return
    held = f"holds {', '.join(culprits)} at zero" if culprits else "holds DOFs at zero"
    warnings.warn(
        f"the DOF selection (--dof) {held}, which the joints move with the DOFs listed: "
        f"they keep {kept} of the {allowed} independent motions the joints alone give "
        "them. List those DOFs too if they should follow the joints, or hold what should "
        "not move with a joint to the ground (--joint planar BODY ground: surge, heave, "
        "pitch)",
        AssumptionWarning,
        stacklevel=4,
    )


def _warn_far_points(ds: xr.Dataset, frame: BodyFrame, system: MechanicalSystem) -> None:
    """A warning for each revolute joint or PTO whose point lies more than
    :data:`FAR_POINT` body lengths (:func:`~cummins.mechanics.bodies.body_sizes`, and the
    distance between the two bodies) from the bodies it ties: a hinge given in mm, or in
    other axes than the data's, turns the body about a far axis, a near translation."""
    sizes = body_sizes(ds, frame)
    items = [(j.where, j.body, j.base, j.point) for j in system.joints if j.kind == "revolute"]
    items += [(p.where, p.body, p.base, p.point) for p in system.ptos if p.body is not None]
    for where, body_name, base_name, point in items:
        if point is None:
            continue
        body, base = frame.resolve(body_name, where), frame.resolve(base_name, where)
        tied = [b for b in (body, base) if b is not None]
        scale = max(float(sizes[b]) for b in tied)
        if len(tied) == 2:
            scale = max(scale, float(np.linalg.norm(frame.points[body] - frame.points[base])))
        distance = min(float(np.linalg.norm(np.asarray(point) - frame.points[b])) for b in tied)
        if scale > 0 and distance > FAR_POINT * scale:
            nearest = min(tied, key=lambda b: np.linalg.norm(np.asarray(point) - frame.points[b]))
            warnings.warn(
                f"{where}: the point {list(point)} m is {distance:.4g} m from "
                f"{frame.body_label(nearest)}'s reference point, {distance / scale:.0f} times "
                f"the bodies' length scale ({scale:.3g} m: their size and spacing): check "
                "its units (m) and axes (the data's, from the global origin)",
                AssumptionWarning,
                stacklevel=4,
            )


def _joint_preload(ds, frame, system, g, t, coordinates) -> Preload | None:
    """The joints' pre-load (:mod:`cummins.mechanics.preload`), its warnings given; None
    without joints, or when the data lack a body's displaced volume or mass (a warning
    says the pre-load is then left out)."""
    if not system.joints:
        return None
    forces = net_static_forces(ds, frame)
    if forces is None:
        warnings.warn(
            "the joints' pre-load is not included: the data lack the displaced volume or "
            "the mass of a body, so the static force (ρ∇ − m)g the joints carry is unknown "
            "(a body held by a hinge with buoyancy above its weight gains the stiffness "
            "F·(z_o − z_h) about it)",
            AssumptionWarning,
            stacklevel=3,
        )
        return None
    preload = preload_stiffness(frame, system.joints, g, t, coordinates, forces)
    for coordinate, value in preload.unbalanced:
        warnings.warn(
            f"the mean position is not a static equilibrium: the joints leave a static "
            f"load of {value:.4g} N (N·m for a rotation) on {coordinate} (the bodies' "
            f"buoyancy less weight, {', '.join(f'{f:.4g} N' for f in preload.forces)}); "
            "the linear model is about the mean position all the same",
            AssumptionWarning,
            stacklevel=3,
        )
    if preload.left_out:
        warnings.warn(
            f"the second-order terms of the static reactions of {', '.join(preload.left_out)} "
            "(directions that turn with a moving base) are not included in the pre-load "
            "stiffness",
            AssumptionWarning,
            stacklevel=3,
        )
    return preload


def _with_preload(ds: xr.Dataset, preload: Preload, keep: Sequence[int]) -> xr.Dataset:
    """``ds`` (on the DOFs ``keep`` of the full data) with the pre-load stiffness added to
    its ``additional_stiffness`` (:func:`cummins.mass_properties.with_external_terms`),
    said in ``history``."""
    from cummins.mass_properties import with_external_terms

    added = preload.stiffness[np.ix_(keep, keep)]
    if not np.any(np.abs(added) > 0):
        return ds
    forces = ", ".join(f"{f:.6g} N" for f in preload.forces)
    return with_external_terms(
        ds,
        stiffness=added,
        source=f"joint pre-load: the bodies' static forces (ρ∇ − m)g = {forces} carried "
        "by the joints",
    )


def _unique_names(lines: Sequence[PTOLine]) -> None:
    names = [line.name for line in lines]
    for name in names:
        if names.count(name) > 1:
            raise ArgumentError(f"two PTOs are called {name!r}: name them apart")


# --------------------------------------------------------------------------- from YAML


def system_from_mapping(raw: Any, where: str = "system") -> MechanicalSystem:
    """A :class:`MechanicalSystem` from a mapping (a study file's ``system:`` entry)::

        dofs: [body1__Heave, body2__Heave]      # optional
        body_coupling: false                    # default true
        joints:
          - {kind: translational, body: body2, base: ground, axis: [0, 0, 1]}
          - {kind: translational, body: body1, base: body2, axis: [0, 0, 1],
             pto: {damping: 1.2e6}}             # a PTO on this joint's free motion
        ptos:
          - {dofs: [body1__Heave, body2__Heave], damping: 1.2e6}

    Errors name the key (``system.joints[1].axis``).
    """
    if not isinstance(raw, Mapping):
        raise ArgumentError(f"{where}: expected a mapping (dofs, body_coupling, joints, ptos)")
    allowed = {"dofs", "body_coupling", "joints", "ptos"}
    unknown = sorted(set(map(str, raw)) - allowed)
    if unknown:
        raise ArgumentError(f"{where}.{unknown[0]}: unknown key; use {', '.join(sorted(allowed))}")
    joints: list[Joint] = []
    ptos: list[PTO] = []
    for k, item in enumerate(_sequence(raw.get("joints", ()), f"{where}.joints")):
        key = f"{where}.joints[{k}]"
        fields = _fields(item, key, {"kind", "body", "base", "axis", "point", "name", "pto"})
        pto = fields.pop("pto", None)
        if "kind" not in fields or "body" not in fields:
            raise ArgumentError(f"{key}: a joint needs kind and body (and base: default ground)")
        joint = Joint(**fields, origin=key)
        joints.append(joint)
        if pto is not None:
            extra = _fields(pto, f"{key}.pto", {"damping", "stiffness", "name"})
            ptos.append(PTO(joint=str(k + 1), origin=f"{key}.pto", **extra))
    pto_keys = {
        "dofs",
        "joint",
        "body",
        "base",
        "kind",
        "axis",
        "point",
        "damping",
        "stiffness",
        "name",
    }
    for k, item in enumerate(_sequence(raw.get("ptos", ()), f"{where}.ptos")):
        key = f"{where}.ptos[{k}]"
        fields = _fields(item, key, pto_keys)
        if "dofs" in fields:
            fields["dofs"] = tuple(_sequence(fields["dofs"], f"{key}.dofs"))
        ptos.append(PTO(**fields, origin=key))
    dofs = raw.get("dofs")
    coupling = raw.get("body_coupling", True)
    if not isinstance(coupling, bool):
        raise ArgumentError(f"{where}.body_coupling: true or false, not {coupling!r}")
    return MechanicalSystem(
        tuple(joints),
        tuple(ptos),
        None if dofs is None else tuple(_sequence(dofs, f"{where}.dofs")),
        coupling,
    )


def _sequence(value: Any, key: str) -> list:
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence):
        raise ArgumentError(f"{key}: expected a list")
    return list(value)


def _fields(item: Any, key: str, allowed: set[str]) -> dict[str, Any]:
    if not isinstance(item, Mapping):
        raise ArgumentError(f"{key}: expected a mapping ({', '.join(sorted(allowed))})")
    unknown = sorted(set(map(str, item)) - allowed)
    if unknown:
        raise ArgumentError(f"{key}.{unknown[0]}: unknown key; use {', '.join(sorted(allowed))}")
    return {str(k): v for k, v in item.items()}
