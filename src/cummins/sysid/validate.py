"""Re-prediction of recorded motions with identified damping, and its scores.

De Haan (2022) §3.2.4 judges an identification by re-predicting the measured motions
with the identified coefficients and computing the correlation coefficient between
prediction and measurement per DOF and segment, both *in sample* (coefficients of the
same segment) and *out of sample* (coefficients of the previous segment, as a real
application would use them). His identified roll damping was sometimes negative and the
re-predictions then diverged; here such a model is refused with a
:class:`~cummins.errors.SimulationError` naming the DOF, never a run full of NaN.
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import IdentificationError, SimulationError
from cummins.sysid.identify import (
    DAMPING_KINDS,
    DampingModel,
    identify_damping,
    residual_force,
)
from cummins.sysid.records import segments as cut_segments
from cummins.vessel import Vessel


def identified_vessel(vessel: Vessel, model: DampingModel) -> tuple[Vessel, NDArray, object]:
    """The vessel with the identified linear terms folded into its matrices, the constant
    force of any ``offset`` (n,), and the nonlinear force τ_nl(t, ξ, ξ̇) of the quadratic
    and cubic terms (None when there are none).

    The residual F_res = Σ b_k φ_k is force the vessel model lacked on the left-hand side
    of its equation: an acceleration term adds to M, a motion term to C, a velocity term
    to B_v, the offset is a constant force on the left; quadratic and cubic damping enter
    as −b₂|ξ̇|ξ̇ − b₃ξ̇³ on the right.

    Raises
    ------
    SimulationError
        The resulting linear model is unstable (e.g. a negative linear damping larger
        than the radiation damping), naming the DOF.
    """
    n = len(vessel.dofs)
    mass = vessel.rigid_body_mass.copy()
    stiffness = vessel.stiffness.copy()
    damping = vessel.viscous_damping.copy()
    constant = np.zeros(n)
    quadratic: list[tuple[int, int, str, float]] = []
    for est in model.estimates:
        i = vessel.dofs.index(est.dof)
        for r, b in zip(est.regressors, est.coefficients, strict=True):
            j = vessel.dofs.index(r.dof) if r.kind != "offset" else i
            if r.kind in ("linear", "velocity"):
                damping[i, j] += b
            elif r.kind == "motion":
                stiffness[i, j] += b
            elif r.kind == "acceleration":
                mass[i, j] += b
            elif r.kind == "offset":
                constant[i] += b
            else:
                quadratic.append((i, j, r.kind, float(b)))
    out = dataclasses.replace(
        vessel,
        rigid_body_mass=mass,
        stiffness=stiffness,
        viscous_damping=damping,
        attrs={**vessel.attrs, "identified_damping": True},
    )
    negative = [f"{e.dof} ({', '.join(e.negative)})" for e in model.estimates if e.negative]
    try:
        out.stability()
    except SimulationError as exc:
        raise SimulationError(
            f"the model with the identified coefficients is unstable ({exc})"
            + (f"; negative damping was identified for {'; '.join(negative)}" if negative else ""),
            hint="identify again with method='bounded' or fewer terms; the data do not "
            "support these coefficients",
        ) from None
    if not quadratic:
        return out, constant, None

    def nonlinear_force(t, xi, v):
        f = np.zeros(n)
        for i, j, kind, b in quadratic:
            f[i] -= b * (np.abs(v[j]) * v[j] if kind == "quadratic" else v[j] ** 3)
        return f

    return out, constant, nonlinear_force


def prediction_scores(predicted: xr.DataArray, measured: xr.DataArray) -> xr.Dataset:
    """Per DOF: Pearson ``correlation`` (the score of de Haan (2022)), ``rms_error``
    relative to the measured RMS, and ``std_ratio`` σ_predicted/σ_measured."""
    p = predicted.values
    m = measured.sel(dof=predicted.dof).values
    pc, mc = p - p.mean(0), m - m.mean(0)
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = (pc * mc).sum(0) / np.sqrt((pc**2).sum(0) * (mc**2).sum(0))
        rms = np.sqrt(((p - m) ** 2).mean(0)) / np.sqrt((m**2).mean(0))
        ratio = p.std(0) / m.std(0)
    dof = predicted.dof.values
    return xr.Dataset(
        {
            "correlation": ("dof", corr),
            "rms_error": ("dof", rms),
            "std_ratio": ("dof", ratio),
        },
        coords={"dof": dof},
    )


def repredict(
    record: xr.Dataset,
    vessel: Vessel,
    model: DampingModel | None = None,
    *,
    cutoff: float | None = None,
    history: xr.Dataset | None = None,
    residual: xr.Dataset | None = None,
) -> xr.Dataset:
    """Re-predict a record's motions from its excitation force with the vessel model and
    the identified damping (none: the potential-flow model alone, the baseline).

    The run starts from the measured state at the record's first sample: ξ, ξ̇ from the
    smoothed record and the memory state χ from the measured velocity history (de Haan:
    "in the field, the measured motion history plays this role"); ``history`` is a longer
    record that contains this one (its earlier samples load the memory; default: the
    record itself, whose memory then starts empty at its first sample). ``residual`` is
    :func:`~cummins.sysid.identify.residual_force` of that history (or record) when it has
    been computed already: the smoothed signals and the memory states are taken from it.

    Returns
    -------
    xarray.Dataset
        ``motion`` (predicted) and ``measured`` (time, dof) of the record's DOFs,
        :func:`prediction_scores` as variables ``correlation``, ``rms_error``,
        ``std_ratio``; attribute ``method``.

    Raises
    ------
    SimulationError
        The identified model is unstable or the run diverges (naming DOF and time).
    """
    from cummins.sysid.identify import full_motions
    from cummins.timedomain.simulate import simulate

    source = record if history is None else history
    res = residual_force(source, vessel, cutoff=cutoff) if residual is None else residual
    t_all = res.time.values
    start = int(np.argmin(np.abs(t_all - float(record.time.values[0]))))
    stop = start + record.sizes["time"]
    if stop > t_all.size:
        raise IdentificationError("the history does not contain the record")
    signals = res.isel(time=slice(start, stop))
    full = full_motions(signals[["motion", "velocity", "excitation_force"]], vessel)
    if model is None:
        run_vessel, constant, nonlinear = vessel, np.zeros(len(vessel.dofs)), None
    else:
        run_vessel, constant, nonlinear = identified_vessel(vessel, model)
    raw = full_motions(record[["motion", "excitation_force"]], vessel)
    x0 = np.concatenate([full["motion"][0], full["velocity"][0], res.chi.values[start]])
    t = record.time.values
    tau = raw["excitation_force"] - constant
    with np.errstate(over="ignore", invalid="ignore"):
        run = simulate(run_vessel, t, tau, initial_state=x0, nonlinear_force=nonlinear)
    dofs = [str(d) for d in record.dof.values]
    predicted = run.motion.sel(dof=dofs)
    measured = record.motion.sel(dof=dofs)
    scores = prediction_scores(predicted, measured)
    out = xr.Dataset(
        {"motion": predicted, "measured": measured, **scores.data_vars},
        attrs={"method": run.attrs["method"], "identified": model is not None},
    )
    return out


def validate_segments(
    record: xr.Dataset,
    vessel: Vessel,
    dofs: Sequence[str] = ("Roll",),
    *,
    length: float,
    **identify_options,
) -> xr.Dataset:
    """Identify per segment, and score in-sample and next-segment re-predictions
    (de Haan (2022) §3.2.4).

    For segment k: coefficients from k (with intervals and flags), the correlation of
    the re-prediction of k with them (``in_sample``), of k with the coefficients of k − 1
    (``previous``, what a real application would use), and of the model without
    identified damping (``baseline``). A segment whose identified model is unstable gets
    NaN scores and ``unstable`` True — the failure de Haan's Fig. D.5 shows as gaps.

    Returns
    -------
    xarray.Dataset
        dims (segment, dof[, term]): ``coefficient``, ``lower``, ``upper`` (segment,
        dof, term); ``in_sample``, ``previous``, ``baseline`` correlations (segment,
        dof); ``unstable``, ``ill_conditioned``, ``negative`` (segment, dof).
    """
    parts = cut_segments(record, length)
    terms = tuple(identify_options.get("terms", ("linear", "quadratic", "cubic")))
    n_seg, n_dof, n_term = len(parts), len(dofs), len(terms)
    coef = np.full((n_seg, n_dof, n_term), np.nan)
    lower, upper = coef.copy(), coef.copy()
    scores = {
        name: np.full((n_seg, n_dof), np.nan) for name in ("in_sample", "previous", "baseline")
    }
    flags = {
        name: np.zeros((n_seg, n_dof), bool) for name in ("unstable", "ill_conditioned", "negative")
    }
    models: list[DampingModel | None] = []
    # the signals and memory states of the whole record, for every re-prediction
    history = residual_force(record, vessel, cutoff=identify_options.get("cutoff"))
    for k, part in enumerate(parts):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = identify_damping(part, vessel, dofs, **identify_options)
        models.append(model)
        for i, d in enumerate(dofs):
            est = model[d]
            for j, kind in enumerate(terms):
                idx = [r.kind for r in est.regressors].index(kind)
                coef[k, i, j] = est.coefficients[idx]
                lower[k, i, j], upper[k, i, j] = est.intervals[idx]
            flags["ill_conditioned"][k, i] = est.ill_conditioned
            flags["negative"][k, i] = bool(est.negative)
        for name, m in (
            ("in_sample", model),
            ("baseline", None),
            ("previous", models[k - 1] if k else None),
        ):
            if name == "previous" and k == 0:
                continue
            try:
                run = repredict(part, vessel, m, history=record, residual=history)
            except SimulationError:
                if name == "in_sample":
                    flags["unstable"][k] = True
                continue
            scores[name][k] = run.correlation.sel(dof=list(dofs)).values
    return xr.Dataset(
        {
            "coefficient": (("segment", "dof", "term"), coef),
            "lower": (("segment", "dof", "term"), lower),
            "upper": (("segment", "dof", "term"), upper),
            **{name: (("segment", "dof"), v) for name, v in scores.items()},
            **{name: (("segment", "dof"), v) for name, v in flags.items()},
        },
        coords={
            "segment": np.arange(n_seg),
            "dof": list(dofs),
            "term": list(terms),
            "start_time": ("segment", [float(p.time.values[0]) for p in parts]),
        },
        attrs={"segment_length": float(length), "damping_kinds": ", ".join(DAMPING_KINDS)},
    )
