"""Pieces shared by the writers of :class:`~cummins.radiation.model.RadiationModel` files.

The writers need to know which axes a model is in (``axis_convention``: ``"z-up"`` or
``"z-down"``, see :mod:`cummins.hydrodb`) before converting it with
:func:`cummins.radiation.model.change_model_axes`.
"""

from __future__ import annotations

import os

from cummins.errors import CumminsError
from cummins.hydrodb import AXIS_CONVENTIONS
from cummins.radiation.model import RadiationModel


def resolve_axis_convention(
    model: RadiationModel,
    given: str | None,
    *,
    path: str | os.PathLike[str],
) -> str:
    """The axes ``model`` is in: its ``axis_convention`` attribute, or ``given``.

    Raises
    ------
    CumminsError
        Neither is known, they disagree, or the value is not a known convention.
    """
    recorded = model.attrs.get("axis_convention")
    for value in (recorded, given):
        if value is not None and value not in AXIS_CONVENTIONS:
            raise CumminsError(
                f"{os.fspath(path)}: unknown axis convention {value!r}; "
                f"use one of {', '.join(AXIS_CONVENTIONS)}"
            )
    if recorded is None and given is None:
        raise CumminsError(
            f"{os.fspath(path)}: the model does not record its axes (no axis_convention "
            "attribute); pass axis_convention='z-up' (WAMIT, NEMOH, Capytaine data) or "
            "'z-down' (MSS data)"
        )
    if recorded is not None and given is not None and recorded != given:
        raise CumminsError(
            f"{os.fspath(path)}: axis_convention={given!r} was given but the model records "
            f"{recorded!r}; drop the argument"
        )
    return str(recorded if recorded is not None else given)
