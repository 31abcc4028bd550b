"""A QTF's wave directions completed by port/starboard mirroring, as the first order's.

A port/starboard symmetric hull whose QTF covers one half-plane of directions (0…π, as
a ship's run over its starboard side) has it on the other by the reflection y → −y:

    Q(ω₁, ω₂, −β) = T Q(ω₁, ω₂, β),   T = diag(1, −1, 1, −1, 1, −1)

(surge, heave, pitch symmetric; sway, roll, yaw change sign: the rule of
:mod:`cummins.seakeeping.headings` for the excitation and the mean drift, which holds for
any quantity of the wave field that is a force on the hull). Whether the hull is
symmetric is judged as for the first order (:func:`~cummins.seakeeping.headings.symmetry_evidence`:
no coupling of symmetric and antisymmetric motions in A and B, none excited along the x
axis, a centre of buoyancy on y = 0) and, in addition, from the QTF itself: its sway, roll
and yaw in waves along the x axis must vanish (below 10⁻³ of the largest |Q| of their
kind). Bi-directional QTFs are not mirrored (the pairs of a mirrored and an unmirrored
direction would need data the file does not hold).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.hydrodb import DOF_NAMES, split_dof
from cummins.qtf.data import QTFTable, qtf_table
from cummins.seakeeping.headings import (
    MIRROR_SIGNS,
    SYMMETRY_TOLERANCE,
    HeadingCoverage,
    heading_coverage,
)

_TWO_PI = 2.0 * np.pi


def mirrored_qtf(
    ds: xr.Dataset, kind: str = "difference", *, mirror: bool | None = None
) -> tuple[QTFTable, HeadingCoverage]:
    """The dataset's QTF on the directions of :func:`heading_coverage` (module docstring).

    Parameters
    ----------
    ds
        A ``HydroDB`` of one body with ``qtf_difference`` (or ``qtf_sum``).
    kind
        ``"difference"`` or ``"sum"``.
    mirror
        None: mirror a half-plane QTF when the hull looks symmetric; True: mirror (one
        body); False: never.

    Returns
    -------
    (QTFTable, HeadingCoverage)
        The table (directions in [0, 2π), sorted; the data's own values where they have
        the direction) and what was mirrored, and why (not).
    """
    table = qtf_table(ds, kind)
    if table.bidirectional:
        return table, _unmirrored(table, "a bi-directional QTF is not mirrored")
    if mirror is None:
        quiet = _antisymmetric_along_x(table)
        if quiet:
            return table, _unmirrored(table, f"not mirrored: {quiet}")
    names = [split_dof(d)[1] for d in table.dofs]
    if mirror is not False and any(n not in DOF_NAMES for n in names):
        return table, _unmirrored(table, "not mirrored: generalized modes")
    coverage = heading_coverage(ds, mirror=mirror, directions=table.directions)
    values = table.values[:, :, coverage.source, :]
    if coverage.mirror_used:
        signs = np.array([MIRROR_SIGNS[DOF_NAMES.index(n)] for n in names])
        values = np.where(coverage.mirrored[None, None, :, None], values * signs, values)
    mirrored = QTFTable(table.kind, table.omega, coverage.directions, values, table.dofs)
    return mirrored, coverage


def _unmirrored(table: QTFTable, reason: str) -> HeadingCoverage:
    m = table.directions.size
    return HeadingCoverage(
        np.mod(table.directions, _TWO_PI), np.arange(m), np.zeros(m, dtype=bool), False, reason
    )


def _antisymmetric_along_x(table: QTFTable) -> str | None:
    """Why the QTF itself says the hull is not symmetric (its sway, roll or yaw in waves
    along the x axis), or None."""
    beta = np.mod(table.directions, _TWO_PI)
    along = np.flatnonzero(
        (np.abs(beta) < 1e-6) | (np.abs(beta - np.pi) < 1e-6) | (np.abs(beta - _TWO_PI) < 1e-6)
    )
    names = [split_dof(d)[1] for d in table.dofs]
    if not along.size or any(n not in DOF_NAMES for n in names):
        return None
    size = np.abs(table.values).max(axis=(0, 1, 2))  # per DOF
    rotation = np.array([DOF_NAMES.index(n) >= 3 for n in names])
    for k, name in enumerate(names):
        if MIRROR_SIGNS[DOF_NAMES.index(name)] > 0:
            continue
        peak = size[rotation == rotation[k]].max()
        value = np.abs(table.values[:, :, along, k]).max()
        if peak > 0 and value > SYMMETRY_TOLERANCE * peak:
            return (
                f"the QTF's {table.dofs[k]} in waves along the x axis is "
                f"{value / peak:.2g} of its largest of that kind"
            )
    return None
