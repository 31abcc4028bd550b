"""How a Capytaine file's DOFs and bodies map to the canonical ones.

:func:`dof_layout` orders and labels the DOFs (rigid-body modes first, Surge … Yaw;
several bodies ``body1__…``); the body attributes are the reference point (Capytaine's
rotation centre, or when Capytaine 2 did not record it, the one its rigid-body inertia
matrix implies: Fossen (2021) eq. 3.44), centres of gravity and buoyancy, displaced
volume and body names.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES, split_dof
from cummins.restoring import SOURCE, weight_record


@dataclass(frozen=True)
class DofLayout:
    """How the file's DOFs map to the canonical ones.

    Attributes
    ----------
    file_labels
        The file's labels, in canonical order (to select the data with).
    labels
        The canonical labels: ``Surge`` … ``Yaw`` for one body, ``body1__Surge`` … for
        several (positional, see :func:`cummins.hydrodb.dof_labels`); a DOF that is not
        a rigid-body mode (a hinge, a flexible mode) keeps the name the file gives it,
        and so does a DOF that names no body beside DOFs that do (a DOF of the system,
        such as WecOptTool's ``Surge`` of a float and spar together), after the bodies'.
    body_names
        The names the file gives the bodies, in order (empty strings when it gives none).
    body_index
        The body (0-based) of each canonical DOF; −1 for a DOF of no body.
    """

    file_labels: tuple[str, ...]
    labels: tuple[str, ...]
    body_names: tuple[str, ...]
    body_index: tuple[int, ...]

    def rigid_block(self, body: int) -> list[int] | None:
        """Indices of the six rigid-body DOFs of ``body`` in Surge … Yaw order, or None."""
        names = [
            split_dof(lab)[1]
            for lab, b in zip(self.labels, self.body_index, strict=True)
            if b == body
        ]
        positions = [k for k, b in enumerate(self.body_index) if b == body]
        if names[:6] != list(DOF_NAMES):
            return None
        return positions[:6]


def dof_layout(
    raw: xr.Dataset, where, lines: list[str] | None = None, *, keep: bool = False
) -> DofLayout:
    """The canonical DOF labels and order of a Capytaine dataset.

    Capytaine names a body's DOFs after the dictionary of the body (``Surge`` … for
    ``rigid_body_dofs``, any name for others) in the order of that dictionary (Capytaine
    1.1 sorted them alphabetically: ``Heave, Pitch, Roll, Surge, Sway, Yaw``), and joins
    several bodies as ``<body name>__<DOF>``. Here the rigid-body modes of each body come
    first in the order Surge … Yaw, then the other DOFs in the file's order, and several
    bodies are labelled ``body1__…``, ``body2__…`` in the order of the file.
    ``keep=True`` (files cummins wrote, whose labels are already canonical) keeps the
    file's labels and order.
    """
    influenced = [str(v) for v in raw["influenced_dof"].values]
    radiating = [str(v) for v in raw["radiating_dof"].values]
    for label in influenced + radiating:
        if not label or not label.isascii() or not label.isprintable():
            raise HydroDataError(
                f"DOF label {label!r} is not printable text",
                path=where,
                hint="the file is damaged (DOF labels are ASCII names such as 'Heave')",
            )
    if sorted(influenced) != sorted(radiating) or len(set(influenced)) != len(influenced):
        raise HydroDataError(
            "radiating and influenced DOFs differ (radiation solved for some DOFs only?)",
            path=where,
            quantity=f"radiating: {', '.join(radiating)}; influenced: {', '.join(influenced)}",
            hint="solve the radiation problems of every DOF",
        )
    groups: dict[str | None, list[str]] = {}
    for label in influenced:
        body, _ = split_dof(label)
        groups.setdefault(body, []).append(label)
    # DOFs that name no body beside bodies that are named (WecOptTool's float__Heave,
    # spar__Heave, Surge, Pitch) are DOFs of the system as the file defines them
    # (motion fields over several bodies): they keep their labels, after the bodies'
    shared = groups.pop(None) if None in groups and len(groups) > 1 else []
    several = len(groups) > 1 or bool(shared)
    if keep:
        index = {body: k for k, body in enumerate(groups)}
        return DofLayout(
            tuple(influenced),
            tuple(influenced),
            tuple(body or "" for body in groups),
            tuple(index.get(split_dof(label)[0], -1) for label in influenced),
        )
    file_labels: list[str] = []
    labels: list[str] = []
    body_index: list[int] = []
    for k, members in enumerate(groups.values()):
        rigid = sorted(
            (m for m in members if split_dof(m)[1] in DOF_NAMES),
            key=lambda m: DOF_NAMES.index(split_dof(m)[1]),
        )
        others = [m for m in members if split_dof(m)[1] not in DOF_NAMES]
        for member in rigid + others:
            name = split_dof(member)[1]
            file_labels.append(member)
            labels.append(f"body{k + 1}__{name}" if several else name)
            body_index.append(k)
    file_labels += shared
    labels += shared
    body_index += [-1] * len(shared)
    names = tuple(body or "" for body in groups)
    if lines is not None:
        if [split_dof(f)[1] for f in file_labels] != [split_dof(f)[1] for f in influenced]:
            lines.append(
                "DOFs reordered from the file's order ("
                + ", ".join(influenced)
                + ") to rigid-body modes first, Surge ... Yaw"
            )
        if len(groups) > 1:
            lines.append(
                f"{len(groups)} bodies labelled body1 ... body{len(groups)} in the order of "
                "the file; the file's names (" + ", ".join(names) + ") are kept in body_names"
            )
        elif shared:
            lines.append(f"body {names[0]} labelled body1; its name is kept in body_names")
        if shared:
            lines.append(
                f"DOFs {', '.join(shared)} name no body: DOFs of the system as the file "
                "defines them (motion fields over the bodies, e.g. both bodies in surge), "
                "kept under their names after the bodies' DOFs, with the file's rotation "
                "centre as their reference point"
            )
        custom = sorted({split_dof(f)[1] for f in file_labels} - set(DOF_NAMES))
        if custom:
            lines.append(
                "DOFs that are not rigid-body modes keep the file's names: " + ", ".join(custom)
            )
    return DofLayout(tuple(file_labels), tuple(labels), names, tuple(body_index))


def _vector(da: xr.DataArray) -> np.ndarray:
    """(space_coordinate,) or (body, space_coordinate) → flat array of 3·n values."""
    if "space_coordinate" in da.dims:
        da = da.transpose(..., "space_coordinate")
    return np.asarray(da.values, dtype=float).reshape(-1)


def _body_attributes(raw, given, where, lines: list[str], rho: float, layout: DofLayout):
    """Reference point (rotation centre), CG, CB, displaced volume, body name."""
    attrs: dict[str, Any] = {}
    recorded = None
    if "rotation_center" in raw.variables:
        recorded = _vector(raw["rotation_center"])
    elif "reference_point" in raw.attrs:
        recorded = np.asarray(raw.attrs["reference_point"], dtype=float).reshape(-1)
    if given is not None:
        point = np.asarray(given, dtype=float).reshape(-1)
        if recorded is not None and (
            recorded.shape != point.shape or not np.allclose(recorded, point, atol=1e-9)
        ):
            raise HydroDataError(
                f"reference_point {point.tolist()} was given but the file records the "
                f"rotation centre {recorded.tolist()}",
                path=where,
                hint="the data are about the recorded point: read them as they are and "
                "use cummins.move_reference_point",
            )
        if recorded is None:
            lines.append(f"reference point (rotation centre) {point.tolist()} m (given)")
    elif recorded is not None:
        point = recorded
        if "rotation_center" in raw.variables:
            lines.append(f"reference point = Capytaine's rotation_center {point.tolist()} m")
    else:
        point = np.zeros(3)
        lines.append(
            "the file does not record Capytaine's rotation centre: assumed at the origin "
            "(pass reference_point= if the body was defined with another one)"
        )
    if point.size % 3 or point.size == 0:
        raise HydroDataError(
            f"reference point must have 3 coordinates per body, got {point.size}", path=where
        )
    if "center_of_mass" in raw.variables:
        attrs["center_of_gravity"] = _vector(raw["center_of_mass"])
    if "center_of_buoyancy" in raw.variables:
        attrs["center_of_buoyancy"] = _vector(raw["center_of_buoyancy"])
    if "disp_mass" in raw.variables and raw["disp_mass"].size == 1:
        attrs["displaced_volume"] = float(raw["disp_mass"].values) / rho
    elif "disp_mass" in raw.variables and _per_body(raw["disp_mass"], layout.body_names):
        mass = raw["disp_mass"]  # a multibody's, one per body: in the order of the DOFs
        attrs["displaced_volume"] = np.array(
            [float(mass.sel(body=name)) / rho for name in layout.body_names]
        )
    for name in ("body_name", "body"):
        if name in raw.coords and raw[name].size == 1:
            attrs["body_name"] = str(np.asarray(raw[name].values).reshape(-1)[0])
            break
    if len(layout.body_names) > 1 and layout.labels != layout.file_labels:
        attrs["body_names"] = "\n".join(layout.body_names)
    elif layout.body_names and layout.body_names[0] and "body_name" not in attrs:
        attrs["body_name"] = layout.body_names[0]
    return point if point.size > 3 else point.reshape(3), attrs


def _assumed_origin(raw: xr.Dataset) -> bool:
    return "rotation_center" not in raw.variables and "reference_point" not in raw.attrs


def _reference_from_inertia(raw, layout: DofLayout, attrs: dict, point, lines, where):
    """Capytaine 2 does not record the rotation centre, but its rigid-body inertia
    matrix is about it: M = [[m I, -m S(r)], [m S(r), I]] with r the centre of mass
    relative to the rotation centre (Fossen 2021 eq. 3.44). Given the centre of mass
    (the legacy exporter's ``Hydrostatics*.dat`` or Capytaine 3's ``center_of_mass``),
    the rotation centre is the centre of mass less r. Returns ``point`` unchanged when
    that cannot be done."""
    if "inertia_matrix" not in raw.data_vars or "center_of_gravity" not in attrs:
        return point
    cog = np.asarray(attrs["center_of_gravity"], dtype=float).reshape(-1, 3)
    n_bodies = len(layout.body_names)
    if cog.shape[0] != n_bodies:
        return point
    matrix = raw["inertia_matrix"].transpose("influenced_dof", "radiating_dof")
    matrix = np.asarray(
        matrix.sel(
            influenced_dof=list(layout.file_labels), radiating_dof=list(layout.file_labels)
        ).values,
        dtype=float,
    )
    centres = []
    for body in range(n_bodies):
        block = layout.rigid_block(body)
        if block is None:
            return point
        m = matrix[np.ix_(block, block)]
        mass = m[0, 0]
        if not np.all(np.isfinite(m)) or not mass > 0:
            return point
        lower = m[3:6, 0:3] / mass
        r = np.array([lower[2, 1], lower[0, 2], lower[1, 0]])
        centres.append(cog[body] - r)
    derived = np.concatenate(centres)
    derived[np.abs(derived) < 1e-12] = 0.0
    for k, line in enumerate(lines):
        if line.startswith("the file does not record Capytaine's rotation centre"):
            lines[k] = (
                "the file does not record Capytaine's rotation centre: "
                f"{np.round(derived, 9).tolist()} m, the centre of gravity less the offset "
                "that the rigid-body inertia_matrix gives (its mass-moment coupling)"
            )
    return derived if derived.size > 3 else derived.reshape(3)


def _per_body(values: xr.DataArray, names) -> bool:
    """Whether ``values`` hold one number per body of ``names`` on a ``body`` coordinate."""
    if values.dims != ("body",) or "body" not in values.coords or len(names) < 2:
        return False
    return sorted(str(b) for b in values.body.values) == sorted(str(n) for n in names)


def restoring_attributes(extra: dict, attrs: dict, rho: float) -> dict:
    """What Capytaine's ``hydrostatic_stiffness`` holds (:mod:`cummins.restoring`): its
    ``compute_hydrostatic_stiffness`` adds the weight of the body's mass (its
    ``inertia_matrix``'s, else the displaced mass ρ∇) at its ``center_of_mass`` to the
    hydrostatics (C₄₄ = ρg(∫y²dA + ∇z_B) − m g z_G …); a file that does not record the
    centre of mass (Capytaine 1 and 2 without the legacy exporter's files) says nothing."""
    if "hydrostatic_stiffness" not in extra:
        return {}
    if "center_of_gravity" not in attrs:
        return {
            SOURCE: "Capytaine's hydrostatic_stiffness (the file does not record the centre "
            "of mass it was computed with)"
        }
    centers = np.asarray(attrs["center_of_gravity"], dtype=float).reshape(-1, 3)
    n = len(centers)
    masses = [np.nan] * n
    inertia = extra.get("inertia_matrix")
    if inertia is not None and np.shape(inertia)[0] >= 6 * n:
        masses = [float(np.asarray(inertia)[6 * k, 6 * k]) for k in range(n)]
    elif "displaced_volume" in attrs:
        volumes = np.atleast_1d(np.asarray(attrs["displaced_volume"], dtype=float))
        if volumes.size == n:
            masses = list(rho * volumes)
    return weight_record(
        masses,
        centers,
        "Capytaine's hydrostatic_stiffness (hydrostatics and the weight of the body's mass "
        "at its center_of_mass)",
    )
