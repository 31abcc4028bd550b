"""``cummins identify-damping``: viscous damping from motion records."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import click
import numpy as np
from rich.markup import escape

from cummins.cli.common import (
    allow_other_data_option,
    console,
    err_console,
    force_option,
    heading_degrees,
    model_and_data,
    non_negative,
    positive,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_speed,
    speed_option,
    viscous_damping_option,
    viscous_damping_values,
)
from cummins.cli.option_rules import Command, option_rules, unique_values


def data_damping_held(vessel, given, dofs) -> dict[str, float]:
    """The linear damping of ``dofs`` the vessel took from the data's
    ``additional_damping`` (its B_v less the ``given`` --viscous-damping values)."""
    from cummins.vessel import viscous_damping_matrix

    extra = np.diag(vessel.viscous_damping - viscous_damping_matrix(vessel.dofs, given))
    out = {}
    for dof in dofs:
        if dof in vessel.dofs and extra[vessel.dofs.index(dof)] > 0:
            out[dof] = float(extra[vessel.dofs.index(dof)])
    return out


@click.command(name="identify-damping", cls=Command)
@click.argument("records", nargs=-1, required=True, type=click.Path(exists=True, dir_okay=False))
@click.option(
    "--model",
    "model_path",
    metavar="MODEL|DATA",
    type=click.Path(exists=True),
    default=None,
    help="The potential-flow model: a model file of `cummins fit` or the hydrodynamic data "
    "(fitted on the fly). Required, except for --decay with --inertia or --stiffness.",
)
@read_options
@click.option(
    "--dof",
    "dofs",
    multiple=True,
    callback=unique_values,
    default=("Roll",),
    show_default=True,
    help="DOF whose damping is identified (repeatable).",
)
@click.option(
    "--terms",
    default="linear,quadratic,cubic",
    show_default=True,
    help="Damping terms, comma separated: linear (b1 v), quadratic (b2 |v| v), cubic (b3 v^3).",
)
@click.option(
    "--coupling",
    "couplings",
    multiple=True,
    metavar="TERM",
    help="Extra term, e.g. 'Sway acceleration', 'Roll motion' (repeatable).",
)
@click.option("--offset", is_flag=True, help="Also identify a mean force (wind, a list).")
@click.option(
    "--method",
    type=click.Choice(["ols", "bounded"]),
    default="ols",
    show_default=True,
    help="Least squares; bounded keeps damping >= 0.",
)
@click.option(
    "--cutoff",
    type=positive("rad/s"),
    default=None,
    metavar="RAD/S",
    help="Low-pass cut-off of the differentiation (default: 2.5 x the motions' "
    "zero-crossing frequency).",
)
@click.option(
    "--burn-in",
    type=non_negative("s"),
    default=None,
    metavar="S",
    help="Seconds cut at the start of each record (default: the memory's start-up; "
    "with --decay none: cut the release and the fluid memory's transient after it, a few "
    "roll periods).",
)
@click.option(
    "--segment",
    type=positive("s"),
    default=None,
    metavar="S",
    help="Also identify per segment of S seconds and score in-sample and "
    "next-segment re-predictions (segments.nc, segments.png).",
)
@click.option(
    "--heading",
    type=heading_degrees(),
    default=None,
    metavar="DEG",
    help="Wave direction, for records holding a wave elevation instead of forces.",
)
@click.option(
    "--align",
    "align_dof",
    default=None,
    metavar="DOF",
    help="Scale and shift the record's forces so the predicted DOF (e.g. Heave) "
    "matches the measured one (de Haan (2022) §3.2.1), before identifying.",
)
@click.option(
    "--max-lag",
    type=non_negative("s"),
    default=30.0,
    show_default=True,
    metavar="S",
    help="Largest shift --align may apply.",
)
@viscous_damping_option
@click.option(
    "--decay",
    is_flag=True,
    help="The records are roll free decays: classic decay analysis (p1, p2, omega0).",
)
@click.option(
    "--inertia",
    type=positive("kg m^2"),
    default=None,
    metavar="KG M2",
    help="--decay: total roll inertia I44 + A44 for dimensional B1, B2.",
)
@click.option(
    "--stiffness",
    type=positive("N m/rad"),
    default=None,
    metavar="N M/RAD",
    help="--decay: C44 (the inertia is then C44/omega0^2).",
)
@speed_option("Forward speed of DATA.")
@click.option(
    "--report",
    "report_dir",
    type=click.Path(file_okay=False),
    required=True,
    help="Folder for damping.json and the PNG figures.",
)
@allow_other_data_option
@force_option("Overwrite the report's files.")
@option_rules(
    needs={"inertia": "decay", "stiffness": "decay", "max_lag": "align_dof"},
    # a decay analysis fits the roll decay alone: the regression's options do not apply
    excludes=tuple(
        ("decay", name)
        for name in (
            "dofs",
            "terms",
            "couplings",
            "offset",
            "method",
            "cutoff",
            "segment",
            "heading",
            "align_dof",
            "viscous_damping",
        )
    ),
)
@reports_errors
def identify_damping_command(
    records,
    model_path,
    format_,
    rho,
    g,
    ulen,
    dofs,
    terms,
    couplings,
    offset,
    method,
    cutoff,
    burn_in,
    segment,
    heading,
    align_dof,
    max_lag,
    viscous_damping,
    decay,
    inertia,
    stiffness,
    speed,
    report_dir,
    allow_other_data,
    force,
):
    """Identify the damping potential theory leaves out from motion records.

    \b
    RECORDS are CSV files with units in the header, e.g.
        time [s], Roll [deg], Sway [m], Yaw [deg], Roll moment [kN m], ...
    (columns <DOF>, <DOF> velocity, <DOF> force or moment, wave elevation) or NetCDF
    (the run.nc of `cummins simulate` is one). The residual force of the Cummins model,
    tau - (M + A_inf) a - mu - C x, is regressed on the damping terms (least squares,
    autocorrelation-consistent confidence intervals), with collinearity diagnostics:
    a narrow-banded record is flagged, not trusted; negative damping is flagged.
    The motions are then re-predicted with and without the identified damping.

    \b
    Examples:
      cummins identify-damping run.nc --model tanker.1 --dof Roll --report damping
      cummins identify-damping test1.csv test2.csv --model ship.nc --terms linear,quadratic \\
          --method bounded --segment 600 --report damping
      cummins identify-damping decay.csv --decay --model tanker.1 --report decay
    """
    report = Path(report_dir)
    if decay:
        _decay_reports(
            records,
            report,
            model_path,
            format_,
            rho,
            g,
            ulen,
            speed,
            inertia,
            stiffness,
            force,
            burn_in=burn_in,
        )
        return
    from cummins.plots import plot_reprediction, plot_residual_force, save_figure
    from cummins.sysid import (
        alignment,
        apply_alignment,
        excitation_from_elevation,
        identify_damping,
        read_record,
        repredict,
        residual_force,
    )
    from cummins.sysid.identify import trusted_samples
    from cummins.vessel import vessel_from_hydrodb

    if model_path is None:
        raise click.UsageError("--model is required (the potential-flow model to correct)")
    outputs = [report / "damping.json", report / "reprediction.png"]
    outputs += [report / f"residual_{d}.png" for d in dofs]
    if segment:
        outputs += [report / "segments.nc", report / "segments.png"]
    prepare_outputs(*outputs, force=force)
    term_list = tuple(t.strip() for t in terms.split(",") if t.strip())
    model, data_path = model_and_data(model_path)
    ds = select_speed(read_hydrodb(data_path, format_, rho, g, ulen), speed)
    labels = [str(d) for d in ds.influenced_dof.values]
    b_v = viscous_damping_values(viscous_damping, labels)
    with console.status("preparing the potential-flow model"):
        vessel = vessel_from_hydrodb(
            ds, model, viscous_damping=b_v, allow_other_data=allow_other_data
        )
    held = data_damping_held(vessel, b_v, dofs)
    if held:
        listed = ", ".join(f"{dof} {value:.4g}" for dof, value in held.items())
        console.print(
            f"note: the model holds the data's additional_damping (MSS's Bv, WAMIT's "
            f"external damping …): {listed} (N s/m, N m s/rad); the identified terms are "
            "the damping on top of it, and 'potential flow only' below includes it"
        )
    recs = []
    for path in records:
        rec = read_record(path, heading_deg=heading)
        if "excitation_force" not in rec:
            rec = excitation_from_elevation(ds, rec)
        if align_dof:
            base = repredict(rec, vessel, None)
            a = alignment(
                base.motion.sel(dof=align_dof).values,
                rec.motion.sel(dof=align_dof).values,
                float(rec.time.values[1] - rec.time.values[0]),
                max_lag=max_lag,
            )
            console.print(
                f"{path}: forces divided by {a.scale:.4g}, shifted {a.lag:+.3g} s "
                f"(from {align_dof}, correlation {a.correlation:.3f})"
            )
            rec = apply_alignment(rec, a)
        recs.append(rec)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with console.status("identifying"):
            result = identify_damping(
                recs,
                vessel,
                dofs,
                terms=term_list,
                couplings=couplings,
                offset=offset,
                method=method,
                cutoff=cutoff,
                burn_in=burn_in,
            )
    for w in caught:
        err_console.print(f"[yellow]warning:[/] {escape(str(w.message))}", highlight=False)
    _print_estimates(result)
    with console.status("re-predicting"):
        res = residual_force(recs[0], vessel, cutoff=cutoff)
        runs = {
            label: repredict(recs[0], vessel, model, residual=res)
            for label, model in (("potential flow only", None), ("with identified damping", result))
        }
    summary = result.to_dict()
    summary["reprediction"] = {
        label: {d: float(run.correlation.sel(dof=d)) for d in run.dof.values}
        for label, run in runs.items()
    }
    summary["records"] = [str(p) for p in records]
    for label, scores in summary["reprediction"].items():
        text = ", ".join(f"{d} {c:.3f}" for d, c in scores.items() if d in dofs)
        console.print(f"correlation, {label}: {text}")
    save_figure(plot_reprediction(runs, dofs=dofs), report / "reprediction.png", force=force)
    res = res.isel(time=np.flatnonzero(trusted_samples(res, burn_in)))
    for est in result.estimates:
        save_figure(plot_residual_force(res, est), report / f"residual_{est.dof}.png", force=force)
    if segment:
        _segment_report(
            recs[0],
            vessel,
            dofs,
            segment,
            report,
            force,
            {
                "terms": term_list,
                "couplings": couplings,
                "offset": offset,
                "method": method,
                "cutoff": cutoff,
                "burn_in": burn_in,
            },
            summary,
        )
    (report / "damping.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
    console.print(f"wrote {report}/ (damping.json, {len(outputs) - 1} figures and files)")


def _print_estimates(result) -> None:
    from rich.table import Table

    for est in result.estimates:
        table = Table(
            title=f"{est.dof}: identified terms ({est.method}, "
            f"{int(100 * est.confidence)} % intervals)"
        )
        for column in ("term", "value", "interval", "unit", "VIF"):
            table.add_column(column, justify="right")
        for row in est.to_dict()["terms"]:
            lo, hi = row["interval"]
            table.add_row(
                row["name"],
                f"{row['value']:.4g}",
                f"[{lo:.3g}, {hi:.3g}]",
                row["unit"],
                f"{row['vif']:.3g}",
            )
        console.print(table)
        flags = "ILL-CONDITIONED" if est.ill_conditioned else "well conditioned"
        console.print(
            f"  condition number {est.condition_number:.3g} ({flags}), R² "
            f"{est.r2:.3f}, {est.n_samples} samples (~{est.effective_samples:.0f} "
            f"independent), amplitude spread {est.amplitude_spread:.2g}"
        )


def _segment_report(record, vessel, dofs, length, report, force, options, summary) -> None:
    from cummins.io.netcdf import save_netcdf
    from cummins.plots import plot_segment_validation, save_figure
    from cummins.sysid import validate_segments

    with console.status(f"identifying per segment of {length:g} s"):
        validation = validate_segments(record, vessel, dofs, length=length, **options)
    save_netcdf(validation, report / "segments.nc")
    save_figure(plot_segment_validation(validation), report / "segments.png", force=force)
    summary["segments"] = {
        name: np.where(np.isfinite(validation[name].values), validation[name].values, None).tolist()
        for name in ("in_sample", "previous", "baseline")
    }
    summary["segments"]["unstable"] = validation.unstable.values.tolist()
    n_bad = int(validation.unstable.values.sum())
    console.print(
        f"{validation.sizes['segment']} segments: mean correlation in sample "
        f"{np.nanmean(validation.in_sample.values):.3f}, with the previous "
        f"segment's coefficients {np.nanmean(validation.previous.values):.3f}, "
        f"without identified damping {np.nanmean(validation.baseline.values):.3f}"
        + (f"; {n_bad} unstable" if n_bad else "")
    )


def _decay_reports(
    records,
    report,
    model_path,
    format_,
    rho,
    g,
    ulen,
    speed,
    inertia,
    stiffness,
    force,
    *,
    burn_in: float | None = None,
) -> None:
    from cummins.plots import plot_roll_decay, save_figure
    from cummins.sysid import read_record, roll_decay

    outputs = [report / "decay.json"]
    outputs += [report / f"decay_{Path(p).stem}.png" for p in records]
    prepare_outputs(*outputs, force=force)
    ds = None
    if model_path is not None:
        _, data_path = model_and_data(model_path)
        ds = select_speed(read_hydrodb(data_path, format_, rho, g, ulen), speed)
    results = {}
    for path in records:
        rec = read_record(path)
        if "Roll" not in [str(d) for d in rec.dof.values]:
            raise click.UsageError(f"{path} has no Roll column")
        t = rec.time.values
        phi = rec.motion.sel(dof="Roll").values
        if burn_in:  # the release and the memory's transient after it left out
            kept = t >= t[0] + burn_in
            t, phi = t[kept], phi[kept]
        result = roll_decay(t, phi, inertia=inertia, stiffness=stiffness)
        values = dict(result.values)
        if ds is not None and inertia is None and stiffness is None:
            values.update(_dimensional_from_data(ds, values))
        results[str(path)] = values
        save_figure(
            plot_roll_decay(t, phi, result), report / f"decay_{Path(path).stem}.png", force=force
        )
        line = (
            f"{path}: p1 = {values['p1']:.4g} ± {values['p1_std']:.2g} 1/s, "
            f"p2 = {values['p2']:.4g} ± {values['p2_std']:.2g} 1/rad, "
            f"omega0 = {values['omega0']:.4g} rad/s"
        )
        if "B1" in values:
            line += f"; B1 = {values['B1']:.4g} N m s/rad, B2 = {values['B2']:.4g} N m s²/rad²"
        if "B1_viscous" in values:
            line += f" (B1 over the radiation damping: {values['B1_viscous']:.4g})"
        console.print(line)
        if values.get("p2_note") and values.get("p2_significance") != "negative":
            # (a negative p2 is a warning of roll_decay's, printed once already)
            console.print(f"  {values['p2_note']}", highlight=False)
    (report / "decay.json").write_text(json.dumps(results, indent=2), encoding="utf-8")
    console.print(f"wrote {report}/decay.json and {len(records)} figure(s)")


def _dimensional_from_data(ds, values: dict) -> dict:
    """I = M44 + A44(ω0) and B44(ω0) of the data: dimensional B1, B2 and the viscous
    part of B1 (over the radiation damping at ω0)."""
    from cummins.hydrodb import single_speed

    ds = single_speed(ds)
    roll = {"influenced_dof": "Roll", "radiating_dof": "Roll"}
    w0 = values["omega0"]
    w = ds.omega.values
    a44 = float(np.interp(w0, w, ds.added_mass.sel(roll).values))
    b44 = float(np.interp(w0, w, ds.radiation_damping.sel(roll).values))
    m44 = float(ds.inertia_matrix.sel(roll)) if "inertia_matrix" in ds else None
    if m44 is None:
        return {}
    inertia = m44 + a44
    return {
        "inertia": inertia,
        "B1": values["p1"] * inertia,
        "B2": values["p2"] * inertia,
        "B1_std": values["p1_std"] * inertia,
        "B2_std": values["p2_std"] * inertia,
        "B44_radiation_at_omega0": b44,
        "B1_viscous": values["p1"] * inertia - b44,
    }
