"""``cummins batch``: a study of many cases on a Dask cluster, with operability."""

from __future__ import annotations

from pathlib import Path

import click
import numpy as np
from rich.markup import escape
from rich.table import Table

from cummins.cli.common import (
    console,
    force_option,
    note_inputs,
    prepare_outputs,
    progress_bar,
    reports_errors,
    run_reporting_errors,
)
from cummins.cli.option_rules import Command, option_rules
from cummins.cli.outputs import output_written
from cummins.display import power_text


@click.command(name="batch", cls=Command)
@click.argument("study_file", metavar="STUDY", type=click.Path(dir_okay=False))
@click.option(
    "-o",
    "--output",
    type=click.Path(),
    default=None,
    help="Results: NetCDF (.nc) or Zarr (.zarr). Finished cases are kept in OUTPUT.parts "
    "until the end: run the same command again to resume an interrupted study.",
)
@click.option(
    "--scheduler",
    metavar="ADDR",
    default=None,
    help="Address of a running Dask scheduler (e.g. tcp://10.0.0.5:8786); default: a local "
    "cluster on this machine.",
)
@click.option(
    "--workers",
    type=click.IntRange(min=1),
    default=None,
    metavar="N",
    help="Worker processes of the local cluster (default: one per core).",
)
@click.option(
    "--example",
    is_flag=True,
    help="First write an example study (the bundled tanker) to STUDY; with -o, then run it.",
)
@force_option("Overwrite OUTPUT (and STUDY with --example).")
@option_rules(needs={"workers": "output", "scheduler": "output"})
@reports_errors
def batch_command(study_file, output, scheduler, workers, example, force):
    """Run a study of many cases (headings x sea states x seeds) on a Dask cluster.

    \b
    STUDY is a YAML file (`cummins batch --example study.yaml` writes a commented
    one): the vessel data (and a model file; what the files lack as keys named as
    simulate's options: rho, g, ulen, water_depth, mass, center_of_gravity,
    radii_of_gyration, inertia_matrix, external_stiffness, external_damping), the
    analysis — `rao`, frequency domain: significant amplitude 2 sqrt(m0) and most
    probable maximum per DOF, or `simulate`, time domain: the same from a run in a
    realisation of the sea —, the cases as a grid (heading, hs, tp, gamma,
    spreading, seed) or a list, and limits such as `Roll: 4 deg` (significant) or
    `Heave: {max: 2.5 m}`. With a `system:` of joints and PTOs the results hold each
    PTO's mean power, and the grid may sweep a PTO's damping (`pto_damping: [3.0e+5,
    1.0e+6, 3.0e+6]`, N s/m or N m s/rad): the best damping per sea state and for
    the scatter diagram are printed.

    \b
    Cases run in parallel on Dask (pip install cummins[dask]): a local cluster of
    single-threaded processes, or --scheduler ADDR (its workers need cummins
    installed; the data are sent to them). Each finished case is saved at once;
    after an interruption, the same command computes only the missing ones.
    Results: one dataset with dims (heading, hs, tp, ..., dof), the response/limit
    ratios and `operable` per case; printed: operability per heading and the
    limiting Hs per heading and Tp. `cummins report OUTPUT -o report.html` draws them.

    \b
    Examples:
      cummins batch --example study.yaml
      cummins batch study.yaml -o results.nc --workers 2
      cummins batch study.yaml -o results.zarr --scheduler tcp://10.0.0.5:8786
    """
    from cummins.studies.batch import example_study_text, load_study, run_study

    study_path = Path(study_file)
    if scheduler and workers:
        raise click.UsageError("--workers sizes a local cluster: not with --scheduler")
    if example:
        prepare_outputs(study_path, force=force)
        here = (study_path.parent / "tanker.1").exists()
        from cummins import demo_files

        data = "tanker.1" if here else str(demo_files() / "tanker.1")
        study_path.write_text(example_study_text(data), encoding="utf-8")
        output_written(study_path)
        console.print(f"wrote {study_path} (an example study: edit it, then run it with -o)")
        if output is None:
            return
    elif output is None:
        raise click.UsageError("give the results file with -o/--output")
    elif not study_path.exists():
        raise click.BadParameter(f"{study_path} does not exist", param_hint="STUDY")
    study = load_study(study_path)
    _require_dask()
    note_inputs(study_path, study.data, study.model)
    prepare_outputs(output, force=force)
    n = len(study.all_cases)
    console.print(
        f"{study.name or study_path.name}: {n} cases, analysis {study.analysis}, "
        f"data {study.data.name}"
    )
    with progress_bar() as bar:
        task = bar.add_task(f"{n} cases", total=n)
        run = run_study(
            study,
            output,
            scheduler=scheduler,
            workers=workers,
            force=force,
            progress=lambda done, total: bar.update(task, completed=done),
            say=lambda message: console.print(message),
            on_prepared=_say_failed_model,
        )
    where = f"{run.workers} workers" if run.workers else "nothing to compute"
    console.print(
        f"{run.computed} cases computed, {run.skipped} resumed from saved parts ({where}) "
        f"in {run.elapsed:.1f} s"
    )
    if "pto_mean_power" in run.results:
        for name in run.results.pto.values:
            power = run.results.pto_mean_power.sel(pto=name).values
            console.print(
                f"{name}: mean absorbed power {power_text(np.nanmin(power))} to "
                f"{power_text(np.nanmax(power))} over the cases (pto_mean_power)"
            )
    _print_tables(run.results)
    _print_pto_sweep(run.results)
    console.print(f"wrote {output}")


def _say_failed_model(context) -> None:
    """The one line of :mod:`cummins.cli.failed_model` when the radiation model of a
    time-domain study (its model file, or the one fitted to its data) missed its fit
    targets; the results record it (``model_failures``). The exit status stays that of
    ``cummins simulate`` on such a model: 0, the cases are computed."""
    if context.vessel is None:
        return
    from cummins.cli.failed_model import warn_failed_model

    study = context.study
    source = study.model if study.model is not None else study.data
    warn_failed_model(
        context.vessel.radiation.attrs, source, "model" if study.model is not None else "fitted"
    )


def _require_dask() -> None:
    """One line and exit status 2 without Dask (it names the extra to install)."""
    from cummins.studies.batch import _dask

    run_reporting_errors(_dask)


def _print_tables(results) -> None:
    from cummins.studies.operability import (
        beyond_grid_note,
        limiting_hs,
        limiting_hs_text,
        operability,
    )

    if not results.sizes.get("criterion", 0):
        console.print("no limits in the study: no operability table")
        return
    op = operability(results)
    criteria = "; ".join(str(c) for c in results.criterion.values)
    table = Table(title=escape(f"Operability ({op.attrs['weights']} weights): {criteria}"))
    frame = op.to_dataframe().reset_index()
    keys = [c for c in frame.columns if c != "operability"]
    for key in keys:
        table.add_column(escape("heading [deg]") if key == "heading" else key, justify="right")
    table.add_column("operability", justify="right")
    for _, row in frame.iterrows():
        table.add_row(*(f"{row[k]:g}" for k in keys), f"{100 * row['operability']:.1f} %")
    console.print(table)
    lim = limiting_hs(results)
    if "tp" not in lim.dims or "heading" not in lim.dims:
        return
    # rows: heading and every other axis (a PTO's damping, gamma, spreading), columns: Tp
    keys = ["heading", *(d for d in lim.dims if d not in ("heading", "tp"))]
    lim = lim.transpose(*keys, "tp")
    units = {"heading": "deg"} | {
        k: results[k].attrs["units"] for k in keys if "units" in results[k].attrs
    }
    names = ", ".join(f"{k} [{units[k]}]" if k in units else k for k in keys)
    grid = Table(title=escape(f"Limiting Hs [m] per {names} (rows) and Tp [s] (columns)"))
    for key in keys:
        grid.add_column(key, justify="right")
    for tp in lim.tp.values:
        grid.add_column(f"{tp:g}", justify="right")
    for index in np.ndindex(*lim.shape[:-1]):
        row = lim[index]
        grid.add_row(
            *(f"{float(lim[k][i]):g}" for k, i in zip(keys, index, strict=True)),
            *(
                limiting_hs_text(v, b)
                for v, b in zip(row.values, row.beyond_grid.values, strict=True)
            ),
        )
    console.print(grid)
    note = beyond_grid_note(lim)
    if note:
        console.print(escape(note), highlight=False)


def _print_pto_sweep(results) -> None:
    """The best PTO damping of a sweep (:func:`cummins.studies.pto_sweep.best_pto_damping`):
    a table per heading of the best damping and its power per H_s (rows) and T_p
    (columns), "*" where it is the end of the list; with a scatter diagram, the mean power
    per damping over it and the best single damping for the site."""
    if "pto_damping_best_note" in results.attrs:  # a list of cases
        console.print(f"note: {escape(results.attrs['pto_damping_best_note'])}", highlight=False)
    if "pto_damping_best" not in results:
        return
    best = results.pto_damping_best
    units = results.pto_damping.attrs.get("units", "")
    edge_note = False
    if set(best.dims) == {"heading", "hs", "tp"}:
        for heading in best.heading.values:
            one = results.sel(heading=heading)
            title = f"Best PTO damping [{units}] (mean power), heading {heading:g} deg"
            table = Table(title=escape(f"{title}: Hs [m] (rows), Tp [s] (columns)"))
            table.add_column("Hs", justify="right")
            for tp in one.tp.values:
                table.add_column(f"{tp:g}", justify="right")
            for hs in one.hs.values:
                cells = []
                for tp in one.tp.values:
                    cell = one.sel(hs=hs, tp=tp)
                    edge = bool(cell.pto_damping_best_at_edge)
                    edge_note |= edge
                    text = f"{float(cell.pto_damping_best):.3g}{'*' if edge else ''}"
                    cells.append(
                        f"{text} ({power_text(float(cell.pto_mean_power_best), digits=3)})"
                    )
                table.add_row(f"{hs:g}", *cells)
            console.print(table)
    else:
        console.print(
            f"best PTO damping per case: pto_damping_best (dims {', '.join(best.dims)}) "
            "in the results"
        )
    if "pto_damping_site_best" in results:
        site = results.pto_mean_power_site
        for index in np.ndindex(*results.pto_damping_site_best.shape):
            at = dict(zip(results.pto_damping_site_best.dims, index, strict=True))
            curve = site.isel(at)
            label = ", ".join(f"{d} {float(results[d][i]):g}" for d, i in at.items())
            listed = "; ".join(
                f"{c:.3g}: {power_text(float(p), digits=3)}"
                for c, p in zip(results.pto_damping.values, curve.values, strict=True)
            )
            chosen = results.pto_damping_site_best.isel(at)
            edge = bool(results.pto_damping_site_best_at_edge.isel(at))
            edge_note |= edge
            console.print(
                escape(
                    f"site ({label}), mean power over the scatter diagram per damping [{units}]: "
                    f"{listed}; best {float(chosen):.3g}{'*' if edge else ''} {units}, "
                    f"{power_text(float(results.pto_mean_power_site_best.isel(at)))}"
                ),
                highlight=False,
            )
    if edge_note:
        console.print(
            "* the smallest or largest damping of the list: the optimum may lie beyond it"
        )
