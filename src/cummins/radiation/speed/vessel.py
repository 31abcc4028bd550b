"""The time-domain vessel of a ship at forward speed (:func:`vessel_at_speed`).

The radiation force at constant speed of Hjulstad (2004) eq. 3.28, with the speed terms
that are not memory kept apart (§6, §10.2): the memory at that speed (derived from the
zero-speed fit or fitted at speed, the nearer to the data kept:
:func:`~cummins.radiation.speed.memory.memory_at_speed`), the U·α∞ damping and the
radiation restoring added to the vessel's damping and stiffness, and soft springs where a
free ship at speed is directionally unstable.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import xarray as xr

from cummins.radiation.speed.errors import SpeedError
from cummins.radiation.speed.kernels import SPEED_FIT_DEFAULTS, speed_dependent_model
from cummins.radiation.speed.memory import (  # noqa: F401  (their earlier home)
    MEMORY_CHOICES,
    MEMORY_DERIVED,
    MEMORY_FITTED,
    SPRING_DAMPING_RATIO,
    memory_at_speed,
)


def vessel_at_speed(
    ds: xr.Dataset,
    speed: float,
    *,
    dofs: Sequence[str] | None = None,
    soft_springs: float | None = None,
    viscous_damping: Any = None,
    additional: bool = True,
    memory: str = "best",
    **fit_options: Any,
):
    """The time-domain :class:`~cummins.vessel.Vessel` of a ship at forward speed U.

    The radiation force at constant speed, Hjulstad (2004) eq. 3.28 with the speed terms
    that are not memory kept apart (§6, §10.2; :class:`SpeedDependentModel`)::

        A∞ ν̇ + K_U * ν + U D¹ ν + (U G¹ + U² G²) η

    with D¹, G¹, G² from the zero-speed fit K⁰ (:func:`speed_dependent_model`). Two
    memories K_U are built and the one whose RAOs at speed are nearer the data's own
    frequency domain is kept (:func:`~cummins.radiation.speed.memory.memory_at_speed`,
    which :func:`~cummins.radiation.speed.per_speed.fit_per_speed` shares; the
    ``speed_memory`` attribute names it, ``speed_motion_error`` is its error):

    - K⁰ + U K¹ + U² K², derived exactly from K⁰ (STF; the G² of the stiffness is then the
      very constant K⁰/s² leaves, whatever K⁰'s A(0) is): right when the data at speed are
      the STF terms of the zero-speed data (strip theory);
    - the data at U less U D¹ and the 1/s terms, fitted
      (:func:`~cummins.radiation.speed.memory.memory_part`), plus the antisymmetric U K¹
      (the per-speed fit is of the symmetric part): for data at speed that hold more than
      STF (transom terms, 3-D panel codes at speed).

    In the vessel: ``radiation`` = K_U with A∞, ``viscous_damping`` += U D¹ (skew: B₃₅ =
    +U A∞₃₃, B₅₃ = −U A∞₃₃ …, no energy), ``stiffness`` += U G¹ + U² G² (pitch: −U² A₃₃(0),
    the destabilising Munk-like moment; yaw likewise). With
    :func:`cummins.timedomain.simulate.simulate_waves` (encounter frequencies) it
    reproduces the ShipX/VERES RAOs of the S-175 at 10.3 m/s within 2.5 % (heave) and 5 %
    (pitch) of their peaks where |ω_e| ≤ 2 rad/s, with the default fit options (the
    derived memory: the fit at speed alone misses by 42 % and 69 %, its A₃₃(0) being the
    K⁰ model's extrapolation, three times the data's at 0.1 rad/s) and with tight ones
    (tests/test_speed.py, tests/test_encounter.py).

    Parameters
    ----------
    ds
        A ``HydroDB`` with a ``forward_speed`` dimension that holds U = 0 (whose A∞ and
        A(0) give D¹, G¹, G²) and ``speed``.
    speed
        U, m/s: one of the data's speeds (within 1 mm/s).
    dofs
        Keep only these DOFs, e.g. ``["Heave", "Pitch"]`` (the vertical plane of a ship
        in head or following seas).
    soft_springs
        Natural period T, s, of weak springs in surge, sway and yaw: their diagonal
        stiffness becomes max(C_ii, 0) + (M_RB + A∞)_ii (2π/T)², i.e. a negative one
        (the yaw Munk moment U² G²₆₆ < 0) is cancelled first — what an autopilot and the
        hull's lift do for a real ship on course; a soft mooring at zero speed. Without
        them a free ship at speed is directionally unstable in potential flow and the
        vessel is refused. Each spring comes with the damping 2ζ(M_RB + A∞)_ii 2π/T,
        ζ = :data:`SPRING_DAMPING_RATIO` (a PD autopilot; without it the sway–yaw
        coupling at speed, U D¹ and U K¹, drives a slow oscillation). Choose T well above
        the wave periods (e.g. 200 s).
    viscous_damping, additional
        As :func:`cummins.vessel.vessel_from_hydrodb`.
    memory
        ``"best"`` (default): build both memories K_U and keep the one nearer the data
        (above); ``"derived"``: K⁰ + U K¹ + U² K² only; ``"fitted"``: the fit at speed
        only.
    **fit_options
        Passed to :func:`cummins.radiation.fit.fit_radiation` for the zero-speed and the at-speed
        memory fits. For the pitch of the S-175 at speed the defaults stop at R² 0.5–0.8
        in the fit at speed; ``omega_max=2.0, r2=0.999, max_order=6`` (the range of
        interest, tighter targets) give R² ≥ 0.999 in the vertical plane. A fit that
        cannot be made passive makes the vessel unstable, and it is refused (below).

    Raises
    ------
    SpeedError
        No zero speed or no ``speed`` in the data.
    SimulationError
        The vessel at speed is unstable (naming the DOF; use ``soft_springs`` or
        ``dofs``).
    """
    from cummins.hydrodb import select_dofs

    if memory not in MEMORY_CHOICES:
        raise SpeedError(f"memory must be 'best', 'derived' or 'fitted', not {memory!r}")
    if soft_springs is not None and not soft_springs > 0:
        raise SpeedError(f"soft_springs must be a period in s > 0, not {soft_springs}")
    options = {**SPEED_FIT_DEFAULTS, **fit_options}
    if dofs is not None:
        ds = select_dofs(ds, dofs)
    speeds = ds.forward_speed.values if "forward_speed" in ds.dims else np.array([])
    listed = ", ".join(f"{u:g}" for u in speeds) or "none"
    zero = [k for k, u in enumerate(speeds) if abs(u) <= 1e-3]
    at = [k for k, u in enumerate(speeds) if abs(u - speed) <= 1e-3]
    if not zero:
        raise SpeedError(
            f"the data hold no zero speed (speeds: {listed} m/s), whose A∞ and A(0) give the "
            "speed terms",
            hint="or build the vessel from the data at that speed as they are: "
            "vessel_from_hydrodb(ds.sel(forward_speed=U)) (pitch at speed is then "
            "misfitted: stf_causality says why)",
        )
    if not at:
        raise SpeedError(f"no data at {speed:g} m/s; the data hold {listed} m/s")
    base = speed_dependent_model(ds.isel(forward_speed=zero[0]), **options)
    kept = memory_at_speed(
        ds.isel(forward_speed=at[0]),
        base,
        memory=memory,
        fit_options=options,
        soft_springs=soft_springs,
        viscous_damping=viscous_damping,
        additional=additional,
    )
    return kept.vessel
