"""Second-order wave loads in the data: quadratic transfer functions and mean drift.

:mod:`~cummins.qtf.data` holds the canonical form (variables ``qtf_difference``,
``qtf_sum``, ``drift_force`` and its alternatives, the force convention every reader
converts to, :class:`QTFTable`) and :mod:`~cummins.qtf.interpolation` the values between
grid points (bilinear in (ω₁, ω₂), linear in direction) and over the pairs of a sea's
components. The readers are in :mod:`cummins.io` (WAMIT, NEMOH, AQWA, Capytaine), the
checks in :mod:`cummins.check.second_order`, the loads in
:mod:`cummins.timedomain.loads.second_order` and the statistics in
:mod:`cummins.seakeeping.slow_drift`. See ``docs/second_order.md``.
"""

from __future__ import annotations

from cummins.qtf.data import (
    CONVENTION,
    DIRECTION,
    DIRECTION2,
    DRIFT_ALTERNATIVES,
    DRIFT_METHODS,
    OMEGA,
    OMEGA2,
    QTF_VARIABLES,
    QTFTable,
    complete_square,
    has_qtf,
    qtf_table,
    second_order_summary,
    with_second_order,
)
from cummins.qtf.interpolation import (
    Coverage,
    at_directions,
    coverage,
    direction_weights,
    frequency_weights,
    interpolate,
    pair_matrix,
    weight_matrix,
)

__all__ = [
    "CONVENTION",
    "DIRECTION",
    "DIRECTION2",
    "DRIFT_ALTERNATIVES",
    "DRIFT_METHODS",
    "OMEGA",
    "OMEGA2",
    "QTF_VARIABLES",
    "Coverage",
    "QTFTable",
    "at_directions",
    "complete_square",
    "coverage",
    "direction_weights",
    "frequency_weights",
    "has_qtf",
    "interpolate",
    "pair_matrix",
    "qtf_table",
    "second_order_summary",
    "weight_matrix",
    "with_second_order",
]
