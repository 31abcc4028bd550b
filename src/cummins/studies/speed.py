"""A study at forward speed: the data at the study's ``speed`` (:func:`select_study_speed`)
and the vessel a time-domain study runs there (:func:`vessel_at_study_speed`), that of
``cummins simulate --speed``: the speed terms that are not memory kept apart and the
memory nearer the data's RAOs (:func:`cummins.radiation.speed.vessel_at_speed`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import SimulationError
from cummins.studies.study import Study, StudyError, at_key


def select_study_speed(ds: xr.Dataset, study: Study) -> xr.Dataset:
    """The data at the study's ``speed`` (within 1 mm/s), required when they hold several
    (a :class:`StudyError` naming the key and the speeds held)."""
    if "forward_speed" not in ds.dims:
        return ds
    speeds = ds.forward_speed.values
    listed = ", ".join(f"{u:g}" for u in speeds)
    if study.speed is None:
        if speeds.size > 1:
            raise StudyError(
                f"{at_key(study.source, 'speed')}: the data hold several forward speeds "
                f"({listed} m/s): choose one"
            )
        return ds.isel(forward_speed=0)
    match = np.flatnonzero(np.abs(speeds - study.speed) <= 1e-3)
    if not match.size:
        raise StudyError(
            f"{at_key(study.source, 'speed')}: no data at {study.speed:g} m/s; the data hold "
            f"{listed} m/s"
        )
    return ds.isel(forward_speed=int(match[0]))


def vessel_at_study_speed(full: xr.Dataset, ds: xr.Dataset, study: Study, damping: Any):
    """The vessel of a time-domain study at speed, and the data of its DOFs; None when the
    study does not run at a speed of data holding zero speed too (or gives a model).

    Parameters
    ----------
    full
        The study's data at every speed (completed with its equation-of-motion keys).
    ds
        The data at the study's speed.
    study
        The study: ``speed``, ``soft_springs``, ``system`` (at speed, DOFs only).
    damping
        Its viscous damping, ``{DOF: value}`` or None.

    Raises
    ------
    StudyError
        ``soft_springs`` without a speed to apply to; a system of joints, PTOs or without
        body coupling at speed; a free ship at speed, directionally unstable (naming the
        keys that hold it).
    """
    if not _speed_terms_apart(full, study):
        if study.soft_springs is not None:
            raise StudyError(
                f"{at_key(study.source, 'soft_springs')}: applies to a ship at a speed > 0 "
                "whose data hold zero speed too"
            )
        return None
    from cummins.hydrodb import select_dofs
    from cummins.radiation.speed import vessel_at_speed

    dofs = None if study.system is None else study.system.dofs
    try:
        vessel = vessel_at_speed(
            full, study.speed, dofs=dofs, soft_springs=study.soft_springs, viscous_damping=damping
        )
    except SimulationError as exc:  # a free ship at speed: the study's keys to give
        message = str(exc)[: -len(exc.hint) - 2] if exc.hint else str(exc)
        raise StudyError(
            f"{at_key(study.source, 'speed')}: {message}",
            hint="give the study soft_springs: 200 (a period in s, surge, sway and yaw held "
            "as by an autopilot) or keep the vertical plane (system: {dofs: [Heave, Pitch]})",
        ) from None
    # the DOFs the vessel has, for the excitation of the cases
    return vessel, ds if dofs is None else select_dofs(ds, dofs)


def _speed_terms_apart(full: xr.Dataset, study: Study) -> bool:
    """Whether a time-domain study runs the vessel at speed with the speed terms kept
    apart (as ``cummins simulate --speed``): a speed > 0, data holding zero speed too, no
    model given. A system of joints or PTOs is refused there (bodies at zero speed); one
    that keeps DOFs only selects them."""
    if not study.speed or study.model is not None or "forward_speed" not in full.dims:
        return False
    if not np.any(np.abs(full.forward_speed.values) <= 1e-3):
        return False
    system = study.system
    if system is not None and (system.joints or system.ptos or not system.body_coupling):
        raise StudyError(
            f"{at_key(study.source, 'system')}: joints, PTOs and body_coupling are for "
            "bodies at zero speed; at a speed a system may keep DOFs only (dofs: [...])"
        )
    return True
