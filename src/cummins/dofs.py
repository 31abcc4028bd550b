"""DOF labels of a ``HydroDB``: ``Surge`` … ``Yaw``, body prefixes, generalized modes.

The ``influenced_dof`` and ``radiating_dof`` coordinates of a ``HydroDB`` (see
:mod:`cummins.hydrodb`) are labelled ``Surge``, ``Sway``, ``Heave``, ``Roll``, ``Pitch``,
``Yaw`` for one body, ``body1__Surge`` … for several (the prefix before ``__`` names the
body), and ``Mode7``, ``Mode8`` … for a body's generalized modes. This module makes the
labels and reads them back: which body, which mode, rotation or translation.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from cummins.errors import HydroDataError

if TYPE_CHECKING:
    import xarray as xr

DOF_NAMES: tuple[str, ...] = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


def dof_labels(
    bodies: Sequence[str] | int | None = None, modes: int | Sequence[int] = 6
) -> list[str]:
    """DOF labels for one body (``Surge`` … ``Yaw``) or several (``body1__Surge`` …).

    Every reader labels the DOFs this way, whatever names the solver gives its bodies,
    so that the same body reads with the same labels from every format: several bodies
    are ``body1``, ``body2`` … in the order of the file, and the names the file gives
    them are kept in the dataset's ``body_names`` attribute (see :func:`body_names`;
    :func:`~cummins.hydrodb.rename_bodies` relabels).

    Parameters
    ----------
    bodies
        The number of bodies (labels ``body1`` …), or their names; ``None`` or one body:
        labels without a prefix.
    modes
        Modes per body (one int for all, or one per body): the six rigid-body modes,
        then generalized modes (flexible, piston …) labelled ``Mode7``, ``Mode8`` … by
        their mode number within the body, as WAMIT numbers them.

    Examples
    --------
    >>> dof_labels()[:3]
    ['Surge', 'Sway', 'Heave']
    >>> dof_labels(2)[6]
    'body2__Surge'
    >>> dof_labels(["buoy", "float"])[6]
    'float__Surge'
    >>> dof_labels(modes=8)[6:]
    ['Mode7', 'Mode8']
    """
    if isinstance(bodies, int | np.integer):
        names: list[str] = [f"body{k + 1}" for k in range(int(bodies))]
    else:
        names = list(bodies or [])
    count = max(len(names), 1)
    per_body = [int(modes)] * count if isinstance(modes, int | np.integer) else list(modes)
    if len(per_body) != count:
        raise HydroDataError(f"{len(per_body)} mode counts given for {count} bodies")
    if any(m < 1 for m in per_body):
        raise HydroDataError(f"a body needs at least one mode, got {per_body}")
    labels: list[str] = []
    for k in range(count):
        body_modes = list(DOF_NAMES[: per_body[k]]) + [
            f"Mode{j + 1}" for j in range(len(DOF_NAMES), per_body[k])
        ]
        prefix = f"{names[k]}__" if len(names) > 1 else ""
        labels.extend(prefix + m for m in body_modes)
    return labels


def body_names(ds: xr.Dataset) -> list[str]:
    """The names the solver file gave its bodies (``body_names`` attribute, one line per
    body), or the labels' body prefixes (``body1`` …) when it gave none."""
    stored = [b for b in str(ds.attrs.get("body_names", "")).splitlines() if b]
    found = [b for b in bodies(ds) if b is not None]
    if stored and len(stored) == max(len(found), 1):
        return stored
    return found


def named_dof_hint(ds: xr.Dataset, label: str) -> str:
    """For a DOF named with the file's name of its body (``flap__Pitch``, as Capytaine
    names it) where the data say ``body1__Pitch``: "flap__Pitch is body1__Pitch here";
    empty otherwise."""
    names, prefixes = body_names(ds), bodies(ds)
    if len(names) != len(prefixes):
        return ""
    labels = [str(d) for d in ds.influenced_dof.values]
    return numbered_dof_hint(label, names, prefixes, labels)


def numbered_dof_hint(label: str, names, prefixes, labels) -> str:
    """:func:`named_dof_hint` given the bodies' names in the file, their prefixes in the
    data (by body) and the data's DOF labels."""
    body, name = split_dof(label)
    if body is None or body not in names:
        return ""
    prefix = prefixes[list(names).index(body)]
    meant = f"{prefix}__{name}" if prefix else name
    if meant not in labels:
        return ""
    return f"{label} is {meant} here (DOFs are named by the bodies' numbers)"


def split_dof(label: str) -> tuple[str | None, str]:
    """Split ``"body__Heave"`` into ``("body", "Heave")``; ``"Heave"`` into ``(None, "Heave")``."""
    body, sep, name = str(label).rpartition("__")
    return (body if sep else None), name


def is_rotation(label: str) -> bool:
    """True for a rotational DOF (``Roll``, ``Pitch``, ``Yaw``, of any body): its
    displacement is in rad, its moments in N·m."""
    return split_dof(label)[1] in DOF_NAMES[3:]


def dof_index(label: str) -> int:
    """Index of a DOF label within its body: 0…5 for ``Surge`` … ``Yaw`` (``"Pitch"`` → 4),
    6, 7 … for the generalized modes ``Mode7``, ``Mode8`` …"""
    _, name = split_dof(label)
    if name in DOF_NAMES:
        return DOF_NAMES.index(name)
    if name.startswith("Mode") and name[4:].isdigit() and int(name[4:]) > len(DOF_NAMES):
        return int(name[4:]) - 1
    raise HydroDataError(
        f"unknown DOF label {label!r}",
        hint=f"DOF labels are {', '.join(DOF_NAMES)}, then Mode7, Mode8 … for generalized modes",
    )


def is_rigid_body_dof(label: str) -> bool:
    """True for the six rigid-body modes (``Surge`` … ``Yaw``, of any body)."""
    return split_dof(label)[1] in DOF_NAMES


def bodies(ds: xr.Dataset) -> list[str | None]:
    """The bodies of a dataset, in DOF order (``[None]`` for a single unnamed body)."""
    seen: list[str | None] = []
    for label in ds["influenced_dof"].values:
        body, _ = split_dof(label)
        if body not in seen:
            seen.append(body)
    return seen


def mass_dofs(labels) -> list[int]:
    """The DOFs whose inertia is a body's mass: the surges, else each body's first
    translation (sway or heave); none for a file of rotations alone, whose inertia is a
    moment of inertia (kg·m²), not a mass."""
    names = [split_dof(d) for d in labels]
    surge = [k for k, (_, name) in enumerate(names) if name == "Surge"]
    if surge:
        return surge
    first: dict[str | None, int] = {}
    for k, (body, name) in enumerate(names):
        if name in ("Sway", "Heave"):
            first.setdefault(body, k)
    return list(first.values())
