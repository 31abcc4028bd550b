"""Identifying viscous damping from motion records (de Haan, 2022).

Potential theory leaves out viscous damping, which dominates roll. This package
estimates it from records of the motions (and the wave force or elevation), says when the
records cannot support the estimate, and re-predicts the motions with it:

* :mod:`~cummins.sysid.records` — reading (CSV with units, NetCDF), segments, scale and
  time-shift alignment of predicted and measured signals, force from wave elevation;
* :mod:`~cummins.sysid.identify` — residual force of the Cummins model and least squares
  of linear, quadratic, cubic damping (and coupling terms) with collinearity diagnostics
  and confidence intervals;
* :mod:`~cummins.sysid.signals` — the low-pass filter and the frequency-domain
  derivatives of the records that the identification works on;
* :mod:`~cummins.sysid.decay` — classic roll-decay analysis (decrement and ODE fit);
* :mod:`~cummins.sysid.validate` — re-prediction and its correlation scores, in sample
  and on the next segment.
"""

from cummins.sysid.decay import RollDecay, roll_decay
from cummins.sysid.identify import (
    DampingEstimate,
    DampingModel,
    Regressor,
    damping_terms,
    identify_damping,
    motion_derivatives,
    residual_force,
)
from cummins.sysid.records import (
    Alignment,
    alignment,
    apply_alignment,
    excitation_from_elevation,
    make_record,
    read_record,
    segments,
    validate_record,
)
from cummins.sysid.validate import (
    identified_vessel,
    prediction_scores,
    repredict,
    validate_segments,
)

__all__ = [
    "Alignment",
    "DampingEstimate",
    "DampingModel",
    "Regressor",
    "RollDecay",
    "alignment",
    "apply_alignment",
    "damping_terms",
    "excitation_from_elevation",
    "identified_vessel",
    "identify_damping",
    "make_record",
    "motion_derivatives",
    "prediction_scores",
    "read_record",
    "repredict",
    "residual_force",
    "roll_decay",
    "segments",
    "validate_record",
    "validate_segments",
]
