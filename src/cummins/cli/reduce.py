"""``cummins reduce``: fewer states for a radiation model, passive as a MIMO system."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import click
import numpy as np
from rich.markup import escape
from rich.table import Table

from cummins.cli.common import (
    Number,
    allow_other_data_option,
    console,
    force_option,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_speed,
    speed_option,
    stage_progress,
)
from cummins.cli.option_rules import option_rules
from cummins.cli.system_options import SystemCommand, system_from_options, system_options
from cummins.files import write_text


@click.command(name="reduce", cls=SystemCommand)
@click.argument("model_path", metavar="MODEL", type=click.Path(exists=True, dir_okay=False))
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    required=True,
    help="NetCDF file for the reduced model.",
)
@click.option(
    "--order",
    type=click.IntRange(min=1),
    default=None,
    help="Total number of states of the reduced MIMO model (a symmetric pair counts "
    "twice), allocated over the couplings (or common-pole blocks) so that the worst fit is "
    "the best possible.",
)
@click.option(
    "--tol",
    type=Number(0.0, 1.0, min_open=True),
    default=None,
    help="Instead of --order: per coupling, the smallest order whose relative H-infinity "
    "error (Glover's bound for lyapunov) is at most TOL; per common-pole block, the "
    "smallest passive truncation whose measured change (DOFs scaled alike) is at most TOL.",
)
@click.option(
    "--motion-tol",
    type=Number(0.0, 1.0, min_open=True),
    default=None,
    help="Instead of --order or --tol, for a default model (common-pole blocks) and --data "
    "with the inertia and restoring: the fewest states whose motion RAOs (2 % of critical "
    "damping, four headings) stay within MOTION_TOL of each DOF's peak, e.g. 0.01.",
)
@click.option(
    "--method",
    type=click.Choice(["lyapunov", "mixed", "mixed-rq", "riccati"]),
    default="lyapunov",
    show_default=True,
    help="lyapunov: balanced truncation with an error bound; mixed: mixed-gramian "
    "(positive-real preserving, cheaper than riccati); riccati: positive-real balancing.",
)
@click.option(
    "--data",
    "data_path",
    type=click.Path(exists=True),
    default=None,
    help="The hydrodynamic data the model was fitted to: R-squared against them, and the "
    "passivity correction weighted by them (default: against the unreduced model).",
)
@read_options
@speed_option("Speed of --data.")
@click.option(
    "--passive/--no-passive",
    default=True,
    show_default=True,
    help="Make the reduced MIMO model passive (smallest weighted change of the residues; "
    "a model of common-pole blocks is always made passive by its reduction).",
)
@click.option(
    "--json",
    "json_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write a summary as JSON.",
)
@click.option(
    "--dof",
    "dofs",
    multiple=True,
    metavar="DOF",
    help="With --data: the DOFs that move (repeatable), as the model's fit took them.",
)
@system_options
@allow_other_data_option
@force_option()
@option_rules(needs={"speed": "data_path"})
@reports_errors
def reduce_command(
    model_path,
    output,
    order,
    tol,
    motion_tol,
    method,
    data_path,
    format_,
    rho,
    g,
    ulen,
    speed,
    passive,
    json_path,
    dofs,
    system_options,
    allow_other_data,
    force,
):
    """Reduce the order of a radiation model by balanced truncation.

    \b
    MODEL is a model file written by `cummins fit`. A per-coupling model (fit --method
    fd or realization): each coupling K_ij is truncated in its balanced coordinates (the
    added mass A = A-inf + Im K/w is weighted at low frequency so it is kept), the zero
    K(0) = 0 is restored, symmetric pairs stay symmetric, and the MIMO model is then
    made passive again. A default model (common-pole blocks): each block is truncated
    as one MIMO model, then K(0) = 0 and passivity are restored in its own states; where
    that would ruin a truncation, more states are kept (said in the model's notes). The
    table compares every coupling with the data (--data) or with the unreduced model.

    \b
    Examples:
      cummins reduce tanker_era.nc -o tanker_small.nc --order 54
      cummins reduce tanker_era.nc -o small.nc --tol 0.02 --method mixed --data tanker.1
      cummins reduce tanker_model.nc -o tanker_small.nc --tol 0.02 --data tanker.1
      cummins reduce tanker_model.nc -o tanker_1pc.nc --motion-tol 0.01 --data tanker.1

    \b
    A model fitted for joined bodies (fit --joint, --pto, --dof, --no-body-coupling) is
    compared with --data given the same options, on the joined system's motions:
      cummins reduce flap_model.nc -o flap_small.nc --motion-tol 0.01 --data oswec.out
        --rho 1000 --mass 127000 --mass 999 ... --joint fixed body2 ground --joint
        revolute body1 body2 --axis 0 1 0 --point 0 0 -8.9 --pto-damping 1.2e5
    """
    from cummins.cli.pipeline import reduce_stage
    from cummins.radiation.model import RadiationModel

    if sum(x is not None for x in (order, tol, motion_tol)) != 1:
        raise click.UsageError("give exactly one of --order, --tol and --motion-tol")
    if motion_tol is not None and data_path is None:
        raise click.UsageError(
            "--motion-tol compares the motions with the data's: give --data (the file the "
            "model was fitted to, with the inertia and restoring)"
        )
    system = system_from_options(system_options, dofs)
    if (system is not None or dofs) and data_path is None:
        raise click.UsageError(
            "--dof, --joint, --pto and --no-body-coupling describe the system of --data, as "
            "the model's fit took them: give --data"
        )
    prepare_outputs(output, json_path, force=force)
    model = RadiationModel.load(model_path)
    from cummins.cli.failed_model import warn_failed_model

    warn_failed_model(model.attrs, model_path)  # the reduced model keeps its failures
    data = joined = None
    if data_path:
        from cummins.cli.fit import joined_data
        from cummins.radiation.fingerprint import check_model_data

        data = select_speed(read_hydrodb(data_path, format_, rho, g, ulen), speed)
        lacking = [v for v in ("inertia_matrix", "hydrostatic_stiffness") if v not in data]
        if motion_tol is not None and lacking:
            raise click.UsageError(
                f"--motion-tol compares motions: {Path(data_path).name} holds no "
                f"{' and no '.join(lacking)}; give the body's inertia (--mass, "
                "--center-of-gravity, --radii-of-gyration or --inertia-matrix) and its "
                "moorings (--external-stiffness), as to cummins fit"
            )
        data, joined = joined_data(data, system, dofs)
        aim = model.attrs.get("motions_of")
        if aim and system is None and not dofs:
            console.print(
                f"[yellow]note:[/] {escape(Path(model_path).name)} was fitted for {escape(aim)}:"
                " the motions compared are the free bodies' unless --data gets the same "
                "--joint, --pto, --dof and --no-body-coupling options as its fit",
                highlight=False,
            )
        check_model_data(
            model, data, allow_other_data=allow_other_data, model_name=Path(model_path).name
        )
    with stage_progress(f"reducing {model.total_order} states ({method})") as say:
        reduced, corrected, reference = reduce_stage(
            model,
            order=order,
            tol=tol,
            method=method,
            data=data,
            passive=passive,
            motion_tol=motion_tol,
            progress=say,
            joined=joined,
        )
    against = "the data" if data is not None else "the unreduced model"
    console.print(reduction_table(model, reduced, reference, against))
    summary = reduction_summary(model, reduced, corrected, reference)
    console.print(
        f"{model.total_order} → {reduced.total_order} states, every model stable: "
        f"{summary['mimo_stable']}, MIMO passive: {summary['mimo_passive']}"
    )
    if motion_tol is not None:
        console.print(_motion_line(reduced))
    reduced.save(output, force=force)
    console.print(f"wrote {output}")
    if json_path:
        write_text(json_path, json.dumps(summary, indent=2) + "\n")
        console.print(f"wrote {json_path}")
    failures = [
        f for f in reduced.attrs.get("failures", []) if f not in model.attrs.get("failures", [])
    ]
    for failure in failures:
        console.print(f"[bold red]failure:[/bold red] {escape(failure)}", highlight=False)
    unjudged = model.attrs.get("motions_unjudged")
    if motion_tol is not None and unjudged and any("already" in f for f in failures):
        console.print(
            f"[yellow]note:[/yellow] {Path(model_path).name} was fitted without the motions "
            f"to aim at ({escape(str(unjudged))}): fit again with the options given here "
            "(cummins fit DATA --mass … -o MODEL.nc): that fit aims at these motions, "
            "and its model is the one to reduce",
            highlight=False,
        )
    if failures:
        sys.exit(REDUCE_FAILED)


def _motion_line(reduced) -> str:
    """What the motion tolerance gave: the motion-RAO errors and the tolerance used."""
    a = reduced.attrs
    line = (
        f"motion-RAO error {a['motion_error']:.2%} of the peak (unreduced "
        f"{a['motion_error_unreduced']:.2%}, target {a['motion_tol']:.2%})"
    )
    if "reduction_tol" in a:
        line += f", reduced at --tol {a['reduction_tol']:g}"
    kept = [n for n in a.get("data_notes", []) if n.startswith("no reduction down to tol")]
    return line + "".join(f"\n  note: {n}" for n in kept)


#: Exit status of ``cummins reduce`` when the model was written but misses its tolerance
#: or a coupling's R² went negative (``reduced.attrs["failures"]``).
REDUCE_FAILED = 3


def reduction_summary(model, reduced, corrected, reference) -> dict:
    """The ``--json`` summary: orders before and after, R² against the reference."""
    from cummins.radiation.passivity import is_passive

    before = {(k.influenced, k.radiating): k.order for k in model.modelled}
    couplings = []
    for k in reduced.modelled:
        r2a, r2b = _r2(k, reduced, reference)
        couplings.append(
            {
                "i": k.influenced + 1,
                "j": k.radiating + 1,
                "order_before": before.get((k.influenced, k.radiating)),
                "order": k.order,
                "r2_added_mass": r2a,
                "r2_damping": r2b,
                "stable": bool(k.is_stable()),
            }
        )
    return {
        "couplings": couplings,
        "order_before": model.total_order,
        "total_order": reduced.total_order,
        "mimo_stable": reduced.is_stable(),
        "mimo_passive": is_passive(reduced),
        "passivity_corrections": reduced.attrs.get(
            "passivity_iterations", 0 if corrected is None else None
        ),
    }


def _r2(k, model, reference) -> tuple[float, float]:
    """R² of A and of B of coupling k against the reference (data or unreduced model)."""
    from cummins.radiation.fit.metrics import coupling_metrics

    i, j = k.influenced, k.radiating
    m = coupling_metrics(
        k,
        reference.omega,
        reference.added_mass[:, i, j],
        reference.damping[:, i, j],
        0.5 * float(model.added_mass_inf[i, j] + model.added_mass_inf[j, i]),  # symmetric data
    )
    return float(m["r2_added_mass"]), float(m["r2_damping"])


def reduction_table(model, reduced, reference, against: str) -> Table:
    """Per coupling: order before and after, R² of A and B against the reference,
    Glover's bound relative to the coupling's peak |K| (lyapunov), passivity."""
    method = reduced.attrs.get("reduction_method")
    table = Table(
        title=f"reduced model ({method + '; ' if method else ''}R² against {against})",
        caption="states: of the coupling's model, or of the block of common poles it belongs to"
        if reduced.blocks
        else None,
    )
    for column in ("coupling", "states", "R² A", "R² B", "bound/max|K|", "passive"):
        table.add_column(column, justify="right")
    before = {(k.influenced, k.radiating): k.order for k in model.modelled}
    w = reference.omega
    for k in reduced.modelled:
        if k.influenced > k.radiating:
            continue
        i, j = k.influenced, k.radiating
        r2a, r2b = _r2(k, reduced, reference)
        peak = np.abs(
            reference.damping[:, i, j]
            + 1j * w * (reference.added_mass[:, i, j] - reduced.added_mass_inf[i, j])
        ).max()
        bound = k.metrics.get("reduction_error_bound")
        relative = "—" if bound is None or bound != bound or not peak else f"{bound / peak:.3g}"
        passive = k.metrics.get("passive")
        a, b = reduced.dofs[i], reduced.dofs[j]
        table.add_row(
            a if a == b else f"{a}-{b}",
            f"{before.get((i, j), k.order)} → {k.order}",
            f"{r2a:.4f}",
            f"{r2b:.4f}",
            relative,
            "—" if passive is None else ("yes" if passive else "NO"),
        )
    return table
