"""Per-speed models of a multi-speed database (:func:`fit_per_speed`).

One radiation memory per forward speed, with the speed terms that are not memory (the
U·α∞ damping and the radiation restoring of Hjulstad (2004) §6, §10.2) kept apart, chosen
as the time-domain vessel at speed chooses
(:func:`~cummins.radiation.speed.memory.memory_at_speed`): K⁰ + U K¹ + U² K² derived
from the zero-speed fit, or the data at that speed less the speed terms fitted
(:func:`memory_part`) plus the antisymmetric U K¹, whichever gives RAOs nearer the data's.
The result is a :class:`~cummins.radiation.speed.blending.SpeedModels`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import CumminsError, FitError
from cummins.radiation.speed.blending import SpeedModels
from cummins.radiation.speed.errors import SpeedError
from cummins.radiation.speed.kernels import SPEED_FIT_DEFAULTS, speed_dependent_model
from cummins.radiation.speed.memory import (  # noqa: F401  (memory_part: its earlier home)
    MEMORY_CHOICES,
    memory_at_speed,
    memory_part,
)

#: What ``speed_memory`` records with ``speed_terms="keep"``: no choice is made.
MEMORY_AS_THEY_ARE = "fitted to the data at speed as they are (speed terms as memory)"


def fit_per_speed(
    ds: xr.Dataset,
    *,
    dofs: Sequence[str] | None = None,
    speed_terms: str = "remove",
    memory: str = "best",
    **fit_options: Any,
) -> SpeedModels:
    """One radiation model per forward speed of a multi-speed database.

    Parameters
    ----------
    ds
        A ``HydroDB`` with a ``forward_speed`` dimension (or a single speed).
    dofs
        Keep only these DOFs (e.g. ``["Heave", "Pitch"]``), default all.
    speed_terms
        ``"remove"`` (default): keep the speed terms that are not memory (D¹ and G¹, G²
        from the zero-speed fit, which ``ds`` must hold) apart, in the result
        (:meth:`SpeedModels.impedance` adds them back), and build the memory at each speed
        as :func:`~cummins.radiation.speed.vessel.vessel_at_speed` does (``memory``);
        ``"keep"``: fit the data as they are (pitch at speed then misses: the STF terms
        are not causal, and :func:`stf_causality` says so).
    memory
        With ``speed_terms="remove"``, at each speed U ≠ 0: ``"best"`` (default) builds
        K⁰ + U K¹ + U² K² derived from the zero-speed fit and the fit of the data at U
        less the speed terms (plus U K¹), and keeps the one whose RAOs at speed are nearer
        the data's frequency domain (:func:`~cummins.radiation.speed.memory.memory_at_speed`,
        the very choice of ``vessel_at_speed``; the free vessel is judged, without soft
        springs, stable or not: these memories are not run in it; it needs the data's
        inertia and restoring); ``"derived"`` or ``"fitted"``: that one only.
    **fit_options
        Passed to :func:`cummins.radiation.fit.fit_radiation` (on top of
        :data:`SPEED_FIT_DEFAULTS`), for K⁰ and the fits at speed.

    Returns
    -------
    SpeedModels
        Its ``attrs`` record the choice per speed, in the order of ``speeds``:
        ``speed_memory`` (which memory was kept: ``memory.MEMORY_DERIVED``,
        ``MEMORY_FITTED``, ``MEMORY_ZERO`` at U = 0 or :data:`MEMORY_AS_THEY_ARE`),
        ``speed_motion_error`` (its RAO error, relative to each DOF's peak; NaN where it
        was not judged) and ``speed_motion_errors`` (the error of every memory built, by
        name).

    Notes
    -----
    :func:`cummins.radiation.fit.fit_radiation` fits a coupling pair (i, j), (j, i) once, to the
    symmetric part of the data. At forward speed the data are *not* symmetric (STF:
    B₃₅ − B₅₃ = 2 U A⁰₃₃): the fits at speed get the antisymmetric part from K⁰ (U K¹),
    the derived memory has it by construction; with ``speed_terms="keep"`` it is lost.

    Raises
    ------
    FitError
        Naming the speed whose fit failed.
    HydroDataError
        ``memory="best"`` and the data lack inertia or restoring.
    """
    from cummins.hydrodb import select_dofs
    from cummins.radiation.fit import fit_radiation

    if speed_terms not in ("remove", "keep"):
        raise SpeedError(f"speed_terms must be 'remove' or 'keep', not {speed_terms!r}")
    if memory not in MEMORY_CHOICES:
        raise SpeedError(f"memory must be 'best', 'derived' or 'fitted', not {memory!r}")
    if speed_terms == "keep" and memory == "derived":
        raise SpeedError(
            "memory='derived' keeps the speed terms apart: it needs speed_terms='remove'"
        )
    if dofs is not None:
        ds = select_dofs(ds, dofs)
    if "forward_speed" in ds.dims:
        per_speed = [ds.isel(forward_speed=k) for k in range(ds.sizes["forward_speed"])]
    else:
        per_speed = [ds]
    options = {**SPEED_FIT_DEFAULTS, **fit_options}
    base = None
    if speed_terms == "remove":
        zero = [d for d in per_speed if float(d.coords.get("forward_speed", 0.0)) == 0.0]
        if not zero:
            raise SpeedError(
                "the data have no zero speed, whose A∞ and A(0) give the speed terms",
                hint="pass speed_terms='keep' to fit the data as they are",
            )
        base = speed_dependent_model(zero[0], **options)
    speeds, models, kept, error, errors = [], [], [], [], []
    for d in per_speed:
        u = float(d.forward_speed) if "forward_speed" in d.coords else 0.0
        if base is None:
            try:
                model = fit_radiation(d, **options)
            except CumminsError as exc:
                raise FitError(f"forward speed {u:g} m/s: {exc}") from exc
            source, judged = MEMORY_AS_THEY_ARE, {}
        else:
            choice = memory_at_speed(
                d, base, memory=memory, fit_options=options, require_stable=False
            )
            model, source, judged = choice.model, choice.source, dict(choice.errors)
        speeds.append(u)
        models.append(model)
        kept.append(source)
        error.append(float(judged.get(source, np.nan)))
        errors.append(judged)
    order = np.argsort(speeds)
    return SpeedModels(
        tuple(float(speeds[k]) for k in order),
        tuple(models[k] for k in order),
        {
            "source_file": str(ds.attrs.get("source_file", "")),
            "fit_options": dict(fit_options),
            "speed_terms": speed_terms,
            "memory": memory,
            "speed_memory": tuple(kept[k] for k in order),
            "speed_motion_error": tuple(error[k] for k in order),
            "speed_motion_errors": tuple(errors[k] for k in order),
        },
        None if base is None else base.damping_inf,
        None if base is None else base.restoring,
    )
