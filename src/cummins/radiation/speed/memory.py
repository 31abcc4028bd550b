"""The memory of a ship at one forward speed, and the choice between its two builds.

At a speed U ≠ 0 of data that hold zero speed too, the radiation force is split as in
Hjulstad (2004) eq. 3.28, §6, §10.2: the memory K_U, the U·α∞ damping U D¹ and the
radiation restoring U G¹ + U² G² (the 1/s terms), D¹ and G from the zero-speed fit K⁰
(:func:`~cummins.radiation.speed.kernels.speed_dependent_model`). K_U is built two ways
(:func:`memory_at_speed`):

- K⁰ + U K¹ + U² K², derived exactly from K⁰ (the Salvesen–Tuck–Faltinsen terms; G² is
  then the very constant K⁰/s² leaves, whatever K⁰'s A(0) is): right when the data at
  speed are the STF terms of the zero-speed data (strip theory);
- the data at U less U D¹ and the 1/s terms (:func:`memory_part`), fitted, plus the
  antisymmetric U K¹ (the fit is of the symmetric part of a pair): for data at speed
  that hold more than STF (transom terms, 3-D panel codes at speed);

and the one whose RAOs at speed are nearer the data's own frequency domain
(:func:`~cummins.radiation.speed.checks.speed_motion_error`) is kept. The time-domain
vessel (:func:`~cummins.radiation.speed.vessel.vessel_at_speed`) and the per-speed models
(:func:`~cummins.radiation.speed.per_speed.fit_per_speed`) both choose here.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import scipy.linalg
import xarray as xr
from numpy.typing import ArrayLike

from cummins.errors import CumminsError, FitError, SimulationError
from cummins.hydrodb import split_dof
from cummins.radiation.fingerprint import data_fingerprint
from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.radiation.speed.errors import SpeedError
from cummins.radiation.speed.kernels import SPEED_FIT_DEFAULTS, SpeedDependentModel

#: Damping ratio of the soft springs of :func:`memory_at_speed` (and ``vessel_at_speed``).
SPRING_DAMPING_RATIO = 0.7

#: The memories :func:`memory_at_speed` builds at U ≠ 0 (the ``speed_memory`` it records
#: names the one kept), and K⁰ itself at U = 0.
MEMORY_FITTED = "fitted to the data at speed (speed terms removed), plus U K1"
MEMORY_DERIVED = "K0 + U K1 + U^2 K2 derived from the zero-speed fit (STF)"
MEMORY_ZERO = "K0, the zero-speed fit"

#: The values of ``memory=``: keep the nearer of both, or build one only.
MEMORY_CHOICES = ("best", "derived", "fitted")


def memory_part(
    ds: xr.Dataset, speed: float, damping_inf: ArrayLike, restoring: ArrayLike
) -> xr.Dataset:
    """The data at ``speed`` less the speed terms that are not memory: B − U D¹ and
    A + (U G¹ + U² G²)/ω² (the U·α∞ damping and the radiation-restoring 1/s parts of
    Hjulstad (2004) §6, §10.2, as :func:`speed_dependent_model` separates them). What is
    left is the causal memory the per-speed fit can identify: without this, the U²B₃₃/ω² term
    of pitch (STF) is not the damping of a causal system (Hjulstad (2004) eqs. 5.47–5.51)."""
    d1 = np.asarray(damping_inf, dtype=float)
    g = np.asarray(restoring, dtype=float)
    w = ds.omega.values
    out = ds.copy()
    out["radiation_damping"] = ds.radiation_damping - speed * d1
    out["added_mass"] = ds.added_mass + (speed * g[0] + speed**2 * g[1]) / w[:, None, None] ** 2
    out.attrs["speed_terms_removed"] = 1
    out.attrs["history"] = (
        str(ds.attrs.get("history", ""))
        + f"\nspeed terms U D1, (U G1 + U^2 G2)/s removed at {speed:g} m/s"
    ).strip()
    return out


@dataclass(frozen=True)
class MemoryAtSpeed:
    """The memory kept at one speed (:func:`memory_at_speed`).

    Attributes
    ----------
    speed
        U, m/s.
    source
        Which memory was kept: :data:`MEMORY_DERIVED`, :data:`MEMORY_FITTED` or, at U = 0,
        :data:`MEMORY_ZERO`.
    model
        The memory K_U with A∞ (its ``data_fingerprint`` that of the data at U).
    vessel
        The vessel at U it was judged with (speed terms in its damping and stiffness,
        attributes ``speed_memory``, ``speed_motion_error``); None when it was not judged
        (one memory asked for, data without inertia or restoring).
    errors
        The RAO error (:func:`~cummins.radiation.speed.checks.speed_motion_error`) of every
        memory judged, by source; the kept one's is the smallest.
    """

    speed: float
    source: str
    model: RadiationModel
    vessel: Any = None
    errors: Mapping[str, float] = field(default_factory=dict)

    @property
    def error(self) -> float:
        """The kept memory's RAO error (NaN when it was not judged)."""
        return float(self.errors.get(self.source, np.nan))


def memory_at_speed(
    data: xr.Dataset,
    base: SpeedDependentModel,
    *,
    memory: str = "best",
    fit_options: Mapping[str, Any] | None = None,
    soft_springs: float | None = None,
    viscous_damping: Any = None,
    additional: bool = True,
    require_stable: bool = True,
) -> MemoryAtSpeed:
    """Build the memory K_U of the one-speed ``data`` both ways and keep the nearer one.

    The two memories (module docstring) share D¹, G¹, G² of ``base``; each goes into the
    vessel at U (:func:`cummins.vessel.vessel_from_hydrodb` with U D¹ added to its damping
    and U G¹ + U² G² to its stiffness), whose RAOs at the encounter frequencies are
    compared with the data's frequency domain
    (:func:`~cummins.radiation.speed.checks.speed_motion_error`): the smaller error wins.

    Parameters
    ----------
    data
        The ``HydroDB`` at U (one speed; inertia and restoring needed to judge).
    base
        The zero-speed model K⁰ with its speed terms (:func:`speed_dependent_model`).
    memory
        ``"best"`` (both, the nearer kept), ``"derived"`` or ``"fitted"`` (that one only).
        At U = 0 the memory is ``base.k0``.
    fit_options
        Passed to :func:`cummins.radiation.fit.fit_radiation` for the fit at speed (on
        top of :data:`SPEED_FIT_DEFAULTS`).
    soft_springs, viscous_damping, additional
        Of the vessel judged, as :func:`~cummins.radiation.speed.vessel.vessel_at_speed`
        (DOFs held by soft springs are left out of the error).
    require_stable
        Refuse a vessel that is unstable (:class:`SimulationError` naming the DOF; the other
        memory is kept if its vessel is stable). False judges it all the same: for memories
        that are not run in this vessel (:func:`fit_per_speed`; a free ship at speed is
        directionally unstable in potential flow, whatever its memory).

    Raises
    ------
    SpeedError
        ``memory`` is none of :data:`MEMORY_CHOICES`.
    HydroDataError
        ``memory="best"`` and the data lack inertia or restoring.
    SimulationError
        ``require_stable`` and no vessel is stable.
    FitError
        The fit at speed failed, naming the speed.
    """
    from cummins.vessel import missing_data_message

    if memory not in MEMORY_CHOICES:
        raise SpeedError(f"memory must be 'best', 'derived' or 'fitted', not {memory!r}")
    u = float(data.forward_speed) if "forward_speed" in data.coords else 0.0
    options = {**SPEED_FIT_DEFAULTS, **(fit_options or {})}
    candidates = {}
    if u == 0.0:  # both are K⁰
        candidates[MEMORY_ZERO] = base.k0
    else:
        if memory != "derived":
            candidates[MEMORY_FITTED] = _fitted_memory(data, u, base, options)
        if memory != "fitted":
            derived = replace(base.memory_model(u), attrs=dict(base.k0.attrs))
            candidates[MEMORY_DERIVED] = derived
    # the memory of these very data (speed terms taken out): their fingerprint
    fingerprint = data_fingerprint(data)
    candidates = {
        source: replace(model, attrs={**model.attrs, "data_fingerprint": fingerprint})
        for source, model in candidates.items()
    }
    needed = ("inertia_matrix", "hydrostatic_stiffness")
    if len(candidates) == 1 and not all(name in data for name in needed):
        ((source, model),) = candidates.items()
        return MemoryAtSpeed(u, source, model)
    missing_data_message(
        data,
        needed,
        "choosing the memory at speed by its RAOs (memory='best'; or choose "
        "memory='derived' or 'fitted')",
    )
    built, refusal = [], None
    for source, model in candidates.items():
        try:
            vessel, springs = _vessel(
                data, model, base, u, soft_springs, viscous_damping, additional, source
            )
            if require_stable:
                _check_stability(vessel, u)
        except SimulationError as exc:
            refusal = refusal or exc
            continue
        built.append(_judged(vessel, data, springs))
    if not built:
        raise refusal
    errors = {v.attrs["speed_memory"]: v.attrs["speed_motion_error"] for v in built}
    kept = min(built, key=lambda vessel: vessel.attrs["speed_motion_error"])
    return MemoryAtSpeed(u, kept.attrs["speed_memory"], kept.radiation, kept, errors)


def _fitted_memory(
    d: xr.Dataset, speed: float, base: SpeedDependentModel, options: Mapping[str, Any]
) -> RadiationModel:
    """The fit of :func:`memory_part` of the one-speed data ``d`` plus U K¹."""
    from cummins.radiation.fit import fit_radiation

    try:
        model = fit_radiation(memory_part(d, speed, base.damping_inf, base.restoring), **options)
    except CumminsError as exc:
        raise FitError(f"forward speed {speed:g} m/s: {exc}") from exc
    return with_speed_kernel(model, base.k1, speed)


def with_speed_kernel(model: RadiationModel, k1: RadiationModel, speed: float) -> RadiationModel:
    """``model`` plus U K¹ (the antisymmetric speed kernel), coupling by coupling: the
    blocks of a coupling are stacked, the fitted coupling keeps its metrics."""
    parts = {(k.influenced, k.radiating): k for k in model.couplings}
    for k in k1.couplings:
        key = (k.influenced, k.radiating)
        extra = CouplingModel(*key, k.a, k.b, speed * k.c, "STF speed kernel U K1")
        base = parts.get(key)
        if base is None:
            parts[key] = extra
            continue
        parts[key] = CouplingModel(
            *key,
            scipy.linalg.block_diag(base.a, extra.a),
            np.concatenate([base.b, extra.b]),
            np.concatenate([base.c, extra.c]),
            base.method,
            base.metrics,
            (base.note + "; " if base.note else "") + "plus U K1 (STF, antisymmetric)",
        )
    couplings = tuple(parts[key] for key in sorted(parts))
    return RadiationModel(model.dofs, couplings, model.added_mass_inf, model.attrs)


def _vessel(data, model, base, u, soft_springs, viscous_damping, additional, source):
    """The vessel at speed ``u`` with the memory ``model`` (K_U with A∞) and the speed
    terms of ``base``, and the DOFs its soft springs hold."""
    from cummins.vessel import vessel_from_hydrodb

    vessel = vessel_from_hydrodb(
        data, model, viscous_damping=viscous_damping, additional=additional
    )
    stiffness = vessel.stiffness + u * base.restoring[0] + u**2 * base.restoring[1]
    labels = list(vessel.dofs)
    damping = vessel.viscous_damping + u * base.damping_inf
    springs = []
    if soft_springs is not None:
        mass, omega_s = vessel.mass, 2 * np.pi / soft_springs
        for k, label in enumerate(labels):
            if split_dof(label)[1] in ("Surge", "Sway", "Yaw"):
                stiffness[k, k] = max(stiffness[k, k], 0.0) + mass[k, k] * omega_s**2
                damping[k, k] += 2 * SPRING_DAMPING_RATIO * mass[k, k] * omega_s
                springs.append(label)
    terms = "U K1 + U^2 K2" if source == MEMORY_DERIVED else "U K1"
    attrs = {
        **dict(vessel.attrs),
        "forward_speed": u,
        "speed_terms": "U D1 in viscous_damping, U G1 + U^2 G2 in stiffness, "
        + (f"{terms} in radiation" if u else "none at zero speed"),
        "soft_springs": f"{soft_springs:g} s on {', '.join(springs)}" if springs else "none",
        "speed_memory": source,
    }
    return replace(vessel, viscous_damping=damping, stiffness=stiffness, attrs=attrs), springs


def _check_stability(vessel, u: float) -> None:
    try:
        vessel.stability()
    except SimulationError as exc:
        message = str(exc)[: -len(exc.hint) - 2] if exc.hint else str(exc)
        raise SimulationError(
            f"at {u:g} m/s: {message}",
            hint="a free ship at speed is directionally unstable in potential flow (yaw Munk "
            "moment): give soft springs (--soft-springs 200, a period in s; Python: "
            "soft_springs=200) or keep the vertical plane (--dof Heave --dof Pitch; "
            "Python: dofs=['Heave', 'Pitch'])",
        ) from None


def _judged(vessel, data: xr.Dataset, springs):
    """``vessel`` with its RAO error against ``data`` in its attributes (the DOFs held by
    ``springs`` left out: the data do not have them)."""
    from cummins.radiation.speed.checks import speed_motion_error

    error, per_dof = speed_motion_error(vessel, data, leave_out=springs)
    return replace(
        vessel,
        attrs={
            **vessel.attrs,
            "speed_motion_error": error,
            "speed_motion_error_by_dof": ", ".join(
                f"{k} {100 * e:.2g} %" for k, e in per_dof.items()
            ),
        },
    )
