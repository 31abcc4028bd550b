"""Per-speed fits of a multi-speed database (:func:`fit_per_speed`).

One radiation model per forward speed, fitted to the data at that speed less the speed
terms that are not memory (:func:`memory_part`: the U·α∞ damping and the radiation
restoring of Hjulstad (2004) §6, §10.2), plus the antisymmetric U K¹ of the zero-speed
model (:mod:`~cummins.radiation.speed.kernels`), which the per-speed fits of symmetric
pairs lose. The result is a :class:`~cummins.radiation.speed.blending.SpeedModels`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import scipy.linalg
import scipy.signal
import xarray as xr
from numpy.typing import ArrayLike

from cummins.errors import CumminsError, FitError
from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.radiation.speed.blending import SpeedModels
from cummins.radiation.speed.errors import SpeedError
from cummins.radiation.speed.kernels import (
    SPEED_FIT_DEFAULTS,
    SpeedDependentModel,
    speed_dependent_model,
)


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


def fit_per_speed(
    ds: xr.Dataset,
    *,
    dofs: Sequence[str] | None = None,
    speed_terms: str = "remove",
    **fit_options: Any,
) -> SpeedModels:
    """Fit one radiation model per forward speed of a multi-speed database.

    Parameters
    ----------
    ds
        A ``HydroDB`` with a ``forward_speed`` dimension (or a single speed).
    dofs
        Keep only these DOFs (e.g. ``["Heave", "Pitch"]``), default all.
    speed_terms
        ``"remove"`` (default): fit the memory part (:func:`memory_part`) at each speed,
        with D¹ and G¹, G² from the zero-speed data (which ``ds`` must hold), and keep
        them in the result (:meth:`SpeedModels.impedance` adds them back); ``"keep"``:
        fit the data as they are (pitch at speed then misses: the STF terms are not
        causal, and :func:`stf_causality` says so).
    **fit_options
        Passed to :func:`cummins.radiation.fit.fit_radiation`.

    Returns
    -------
    SpeedModels

    Notes
    -----
    :func:`cummins.radiation.fit.fit_radiation` fits a coupling pair (i, j), (j, i) once, to the
    symmetric part of the data. At forward speed the data are *not* symmetric (STF:
    B₃₅ − B₅₃ = 2 U A⁰₃₃), so the antisymmetric speed part of the couplings is lost by
    these per-speed fits; :func:`speed_dependent_model` keeps it.

    Raises
    ------
    FitError
        Naming the speed whose fit failed.
    """
    from cummins.hydrodb import select_dofs
    from cummins.radiation.fit import fit_radiation

    if dofs is not None:
        ds = select_dofs(ds, dofs)
    if "forward_speed" in ds.dims:
        per_speed = [ds.isel(forward_speed=k) for k in range(ds.sizes["forward_speed"])]
    else:
        per_speed = [ds]
    if speed_terms not in ("remove", "keep"):
        raise SpeedError(f"speed_terms must be 'remove' or 'keep', not {speed_terms!r}")
    d1 = g = None
    if speed_terms == "remove":
        zero = [d for d in per_speed if float(d.coords.get("forward_speed", 0.0)) == 0.0]
        if not zero:
            raise SpeedError(
                "the data have no zero speed, whose A∞ and A(0) give the speed terms",
                hint="pass speed_terms='keep' to fit the data as they are",
            )
        base = speed_dependent_model(zero[0], **{**SPEED_FIT_DEFAULTS, **fit_options})
        d1, g = base.damping_inf, base.restoring
    speeds, models = [], []
    # fit_radiation fits the symmetric part of a pair; the antisymmetric part at speed is
    # U K¹ exactly (STF: ±(U/s) Z⁰, less U D¹), taken from the zero-speed model
    for d in per_speed:
        u = float(d.forward_speed) if "forward_speed" in d.coords else 0.0
        if d1 is None:
            try:
                model = fit_radiation(d, **{**SPEED_FIT_DEFAULTS, **fit_options})
            except CumminsError as exc:
                raise FitError(f"forward speed {u:g} m/s: {exc}") from exc
        else:
            model = _memory_model_at(d, u, base, fit_options)
        speeds.append(u)
        models.append(model)
    order = np.argsort(speeds)
    return SpeedModels(
        tuple(float(speeds[k]) for k in order),
        tuple(models[k] for k in order),
        {
            "source_file": str(ds.attrs.get("source_file", "")),
            "fit_options": dict(fit_options),
            "speed_terms": speed_terms,
        },
        d1,
        g,
    )


def _memory_model_at(
    d: xr.Dataset, speed: float, base: SpeedDependentModel, fit_options: Mapping[str, Any]
) -> RadiationModel:
    """The memory model at ``speed`` of the one-speed data ``d``: the fit of
    :func:`memory_part` plus U K¹ (``base.k0`` itself at U = 0)."""
    from cummins.radiation.fit import fit_radiation

    if speed == 0.0:
        return base.k0  # the zero-speed fit the speed terms came from
    try:
        model = fit_radiation(
            memory_part(d, speed, base.damping_inf, base.restoring),
            **{**SPEED_FIT_DEFAULTS, **fit_options},
        )
    except CumminsError as exc:
        raise FitError(f"forward speed {speed:g} m/s: {exc}") from exc
    return _with_speed_kernel(model, base.k1, speed)


def _with_speed_kernel(model: RadiationModel, k1: RadiationModel, speed: float) -> RadiationModel:
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
