"""Forward speed: encounter frequency, per-speed models, STF speed terms, K⁰/K¹/K².

Hjulstad (2004), ch. 3, 5.3–5.4, 6, 10 and 12.1. Three ways to give a
radiation model a forward speed U (m/s):

1. **Per-speed models** (:func:`fit_per_speed`, :mod:`~cummins.radiation.speed.per_speed`):
   one memory per speed of a multi-speed database, the speed terms that are not memory
   kept apart, blended linearly in U between the two neighbouring speeds
   (:class:`SpeedModels`, :mod:`~cummins.radiation.speed.blending`).
2. **Salvesen–Tuck–Faltinsen speed terms on zero-speed data** (:func:`stf_speed_terms`,
   :mod:`~cummins.radiation.speed.stf`; Hjulstad (2004) eqs. 3.29, 3.33, 5.45–5.46, 10.1, §6).
3. **Speed kernels** (:func:`speed_dependent_model`, :mod:`~cummins.radiation.speed.kernels`,
   eqs. 3.28–3.36): K_U = K⁰ + U K¹ + U² K², with K¹, K² derived exactly from K⁰.

The memory at one speed is K⁰ + U K¹ + U² K² (3.) or a fit of the data at that speed
less the speed terms, whichever gives RAOs nearer the data's
(:func:`memory_at_speed`, :mod:`~cummins.radiation.speed.memory`): the per-speed models
and the time-domain vessel at speed, :func:`vessel_at_speed`
(:mod:`~cummins.radiation.speed.vessel`), choose there alike; encounter frequencies are in
:mod:`~cummins.radiation.speed.encounter`, :class:`SpeedError` in
:mod:`~cummins.radiation.speed.errors`.

The causality problem Hjulstad finds (§5.3–5.4: STF terms in 1/ω² cannot form a
Kramers–Kronig pair) is reported, not hidden, by :func:`stf_causality`, which runs
:func:`cummins.radiation.retardation.kramers_kronig_error` on the STF-corrected data. Forced-motion
verification (§12.1, eqs. 12.1–12.3) is :func:`forced_motion_error`.
"""

# Every name of the module before the split stays importable from here.
from cummins.radiation.speed.blending import SpeedModels
from cummins.radiation.speed.checks import (
    ForcedMotionResult,
    forced_motion_error,
    stf_causality,
)
from cummins.radiation.speed.encounter import (  # noqa: F401
    G,
    encounter_frequency,
    encounter_spectrum,
    wave_frequency,
    with_encounter_frequency,
)
from cummins.radiation.speed.errors import SpeedError  # noqa: F401
from cummins.radiation.speed.kernels import (  # noqa: F401
    SPEED_FIT_DEFAULTS,
    SpeedDependentModel,
    speed_dependent_model,
)
from cummins.radiation.speed.memory import (  # noqa: F401
    MemoryAtSpeed,
    memory_at_speed,
    memory_part,
)
from cummins.radiation.speed.per_speed import fit_per_speed
from cummins.radiation.speed.stf import (
    speed_coupling_matrix,
    stf_speed_terms,
)
from cummins.radiation.speed.vessel import (  # noqa: F401
    SPRING_DAMPING_RATIO,
    vessel_at_speed,
)

__all__ = [
    "ForcedMotionResult",
    "MemoryAtSpeed",
    "SpeedDependentModel",
    "SpeedModels",
    "encounter_frequency",
    "encounter_spectrum",
    "fit_per_speed",
    "forced_motion_error",
    "memory_at_speed",
    "speed_coupling_matrix",
    "speed_dependent_model",
    "stf_causality",
    "stf_speed_terms",
    "vessel_at_speed",
    "wave_frequency",
]
