"""The bodies of a dataset as joints and power take-offs see them.

Each body of a ``HydroDB`` moves with the six DOFs ``body__Surge`` … ``body__Yaw``
(``Surge`` … ``Yaw`` for a single body) about its own reference point o (the dataset's
``reference_point`` attribute, one row of three per body: WAMIT's XBODY origins). With
small motions, a point p of the body moves by

    u(p) = u(o) + θ × (p − o),

(Smogeli et al. (2004) eq. 16: the screw transform H(p − o)), so the translation of p and
the rotation of the body are linear in the DOF vector ξ: [u(p); θ] = P_b(p) ξ, with P_b(p)
a 6 × n matrix that is H(p − o) on the body's six DOFs and zero elsewhere. The ground is a
body that does not move (P = 0). Joints and PTOs are written with these matrices.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.dofs import DOF_NAMES, bodies, body_names, numbered_dof_hint
from cummins.errors import ArgumentError, HydroDataError
from cummins.kinematics import screw_transform

if TYPE_CHECKING:
    import xarray as xr

#: The name of the ground (a body that does not move) in joints and PTOs.
GROUND = "ground"


@dataclass(frozen=True, eq=False)
class BodyFrame:
    """DOF labels, bodies and reference points of a dataset (all its DOFs).

    Attributes
    ----------
    labels
        Every DOF label of the data, in order.
    prefixes
        The body prefix of each body (``body1`` …; None for a single unprefixed body).
    names
        The names the solver file gave the bodies (or the prefixes).
    points
        Reference point of each body, (n_bodies, 3), m, in the data's axes.
    """

    labels: tuple[str, ...]
    prefixes: tuple[str | None, ...]
    names: tuple[str, ...]
    points: NDArray[np.float64]

    @property
    def n(self) -> int:
        """Number of DOFs."""
        return len(self.labels)

    def body_label(self, index: int) -> str:
        """``body1`` … (``body`` for a single unprefixed body)."""
        return self.prefixes[index] or "body"

    def resolve(self, name: str, where: str) -> int | None:
        """The index of the body called ``name`` (its prefix, the file's name for it, or
        its 1-based number; ``body``/``body1`` for a single body), None for the ground.

        Raises
        ------
        ArgumentError
            No such body (``where`` says which joint or PTO named it).
        """
        text = str(name).strip()
        if text.lower() == GROUND:
            return None
        for k, prefix in enumerate(self.prefixes):
            if text == (prefix or "") or text == self.names[k]:
                return k
        if len(self.prefixes) == 1 and self.prefixes[0] is None and text in ("body", "body1"):
            return 0
        if text.isdigit() and 1 <= int(text) <= len(self.prefixes):
            return int(text) - 1
        listed = ", ".join(
            self.body_label(k)
            + ("" if self.names[k] == self.body_label(k) else f" ({self.names[k]})")
            for k in range(len(self.prefixes))
        )
        raise ArgumentError(
            f"{where}: the data have no body {text!r}",
            hint=f"the bodies are {listed}, or '{GROUND}'",
        )

    def dof(self, label: str, where: str) -> int:
        """The index of the DOF ``label``; ArgumentError naming ``where`` if it is absent."""
        if label in self.labels:
            return self.labels.index(label)
        meant = numbered_dof_hint(label, self.names, self.prefixes, self.labels)
        raise ArgumentError(
            f"{where}: the data have no DOF {label!r}",
            hint=(f"{meant}; " if meant else "") + f"DOFs: {', '.join(self.labels)}",
        )

    def dof_index(self, body: int, name: str) -> int | None:
        """The index of body ``body``'s DOF ``name`` (``"Heave"``, ``"Pitch"`` …), None
        when the data lack it."""
        prefix = self.prefixes[body]
        label = f"{prefix}__{name}" if prefix else name
        return self.labels.index(label) if label in self.labels else None

    def point_motion(self, body: int | None, point: ArrayLike) -> NDArray[np.float64]:
        """P_b(p) (6 × n): [u(p); θ] of body ``body`` (None: the ground, zeros) in terms
        of the DOF vector ξ, u(p) = u(o) + θ × (p − o) (module docstring). DOFs the data
        lack are held at zero."""
        out = np.zeros((6, self.n))
        if body is None:
            return out
        h = screw_transform(np.asarray(point, dtype=float).reshape(3) - self.points[body])
        for j, name in enumerate(DOF_NAMES):
            index = self.dof_index(body, name)
            if index is not None:
                out[:, index] = h[:, j]
        return out


def body_frame(ds: xr.Dataset) -> BodyFrame:
    """The :class:`BodyFrame` of a ``HydroDB`` (before any DOF is selected: the reference
    points are stored per body of the file).

    Raises
    ------
    HydroDataError
        A ``reference_point`` attribute that does not hold one point, or one per body.
    """
    labels = tuple(str(d) for d in ds.influenced_dof.values)
    prefixes = tuple(bodies(ds))
    names = body_names(ds)
    if len(names) != len(prefixes):
        names = [p or "body" for p in prefixes]
    raw = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float).reshape(-1)
    if raw.size % 3:
        raise HydroDataError(f"reference_point holds {raw.size} numbers, not 3 per body")
    points = raw.reshape(-1, 3)
    if points.shape[0] == 1:
        points = np.repeat(points, len(prefixes), axis=0)
    elif points.shape[0] != len(prefixes):
        raise HydroDataError(
            f"reference_point holds {points.shape[0]} points for {len(prefixes)} bodies",
            hint="select the DOFs after applying joints (MechanicalSystem(dofs=...)), not before",
        )
    return BodyFrame(labels, prefixes, tuple(str(n) for n in names), points)


def body_sizes(ds: xr.Dataset, frame: BodyFrame) -> NDArray[np.float64]:
    """A length of each body, m: the larger of ∇^⅓ (the data's ``displaced_volume``) and
    its largest radius of gyration about its reference point, √(I_ii / m) (the data's
    ``inertia_matrix``); 0 for a body the data give neither for. A yardstick for points
    given by the user (a hinge a thousand body lengths away is a unit slip), not a
    dimension of the hull."""
    count = len(frame.prefixes)
    sizes = np.zeros(count)
    volume = ds.attrs.get("displaced_volume")
    if volume is not None:
        volumes = np.atleast_1d(np.asarray(volume, dtype=float)).reshape(-1)
        if volumes.size in (1, count):
            volumes = np.broadcast_to(volumes, (count,))
            sizes = np.where(np.isfinite(volumes) & (volumes > 0), np.abs(volumes) ** (1 / 3), 0)
    if "inertia_matrix" in ds:
        from cummins.hydrodb import dof_matrix

        inertia = dof_matrix(ds, "inertia_matrix")
        for b in range(count):
            k = frame.dof_index(b, "Heave")
            mass = inertia[k, k] if k is not None else 0.0
            moments = [
                inertia[i, i] for i in map(frame.dof_index, [b] * 3, DOF_NAMES[3:]) if i is not None
            ]
            if mass > 0 and moments:
                sizes[b] = max(sizes[b], float(np.sqrt(max(max(moments), 0.0) / mass)))
    return sizes
