"""The ``cummins`` command line.

Every command prints what it did; errors are reported in one line naming the file, line,
option or quantity at fault, without a traceback: exit status 2 for a bad option or
argument (a value out of range, an output that exists without --force, a path under a
file), 1 for data that cannot be used (and for `check`, data that fail it). Warnings are
shown once each as one-line notes.
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import click
from rich.markup import escape
from rich.table import Table

from cummins._version import __version__
from cummins.cli_batch import batch_command, report_command
from cummins.cli_bem import bem_command
from cummins.cli_common import (
    console,
    finite,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_body,
)
from cummins.cli_dp import dp_demo_command
from cummins.cli_fit import fit_command
from cummins.cli_kernel import kernel_command
from cummins.cli_lfmodel import lf_model_command
from cummins.cli_rao import rao_command
from cummins.cli_reduce import reduce_command
from cummins.cli_simulate import simulate_command
from cummins.cli_sysid import identify_damping_command
from cummins.errors import CumminsWarning


@click.group(
    context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100},
)
@click.version_option(__version__, "--version", "-V", prog_name="cummins")
def main() -> None:
    """cummins: from frequency-domain hydrodynamics to time-domain vessel models.

    \b
    The pipeline, one command per stage:
      cummins info FILE        what is in a solver output file (or folder)
      cummins check FILE       is the data physically usable? (symmetry, B >= 0, A-inf, decay)
      cummins convert IN OUT   write canonical NetCDF (.nc) or an MSS vessel struct (.mat)
      cummins bem MESH         compute a database with Capytaine (pip install cummins[bem])
      cummins kernel FILE      retardation functions K(t), A-infinity, causality diagnostics
      cummins fit FILE         stable, passive state-space models of the fluid memory
      cummins reduce MODEL     fewer states by balanced truncation, passive again
      cummins rao DATA         coupled motion RAOs, frequency domain (the reference)
      cummins simulate DATA    the vessel in regular or irregular waves, time domain
      cummins identify-damping RECORDS --model DATA
                               viscous (roll) damping from motion records or decays
      cummins dp-demo -o DIR   the nonlinear 6-DOF DP model (Smogeli et al., 2004) on the S-175
      cummins lf-model DATA    constant-coefficient manoeuvring model (Ross, Perez & Fossen, 2006)
      cummins batch STUDY      many cases (headings x sea states) on Dask; operability
      cummins report FILE      a self-contained HTML page of a data, model, run or results file
      cummins demo             run all of it on a bundled real vessel (WAMIT tanker)

    \b
    Formats read (detected from the content): WAMIT .1/.3/.hst/.out, NEMOH .tec,
    AQWA .LIS/.AH1, ShipX/VERES .re7/.re8/.re1, Capytaine NetCDF, MSS .mat.
    Nondimensional WAMIT files take --rho, --g and --ulen.

    Run `cummins COMMAND --help` for the options of a command.
    """


@main.command()
@click.argument("path", type=click.Path(exists=True))
@read_options
@click.option("--json", "as_json", is_flag=True, help="Print the description as JSON.")
@reports_errors
def info(path, format_, rho, g, ulen, as_json):
    """Describe what PATH holds: format, DOFs, frequencies, headings, constants used.

    \b
    Example:
      cummins info tanker.1
      cummins info results/ --format nemoh --json
    """
    from cummins.hydrodb import describe

    ds = read_hydrodb(path, format_, rho, g, ulen)
    d = describe(ds)
    if as_json:
        click.echo(json.dumps(d, indent=2))
        return
    table = Table(show_header=False, box=None, pad_edge=False)
    table.add_column(style="bold")
    table.add_column()
    table.add_row("file", f"{d['source_file']} ({d['source_format']})")
    table.add_row("DOFs", ", ".join(d["dofs"]))
    table.add_row(
        "frequencies",
        f"{d['n_omega']} from {d['omega_min_rad_s']:.4g} to {d['omega_max_rad_s']:.4g} rad/s "
        f"(periods {d['period_range_s'][0]:.3g}–{d['period_range_s'][1]:.4g} s)",
    )
    if d["wave_directions_deg"]:
        betas = d["wave_directions_deg"]
        table.add_row(
            "wave directions", f"{len(betas)}: " + ", ".join(f"{b:g}" for b in betas) + " deg"
        )
    table.add_row("forward speeds", ", ".join(f"{u:g}" for u in d["forward_speeds_m_s"]) + " m/s")
    table.add_row("variables", ", ".join(d["variables"]))
    table.add_row("rho, g", f"{d['rho_kg_m3']:g} kg/m³, {d['g_m_s2']:g} m/s²")
    table.add_row("water depth", f"{d['water_depth_m']:g} m")
    table.add_row("axes", str(d["axis_convention"]))
    table.add_row("reference point", f"{d['reference_point_m']} m")
    for key, label in (
        ("center_of_gravity_m", "centre of gravity"),
        ("center_of_buoyancy_m", "centre of buoyancy"),
    ):
        if key in d:
            table.add_row(label, f"{d[key]} m")
    if "mass_kg" in d:
        table.add_row("mass", f"{d['mass_kg']:.6g} kg")
    for k, line in enumerate(d["history"]):
        table.add_row("provenance" if k == 0 else "", line)
    console.print(table)


@main.command("check")
@click.argument("path", type=click.Path(exists=True))
@read_options
@click.option(
    "--json",
    "json_path",
    metavar="FILE",
    type=click.Path(dir_okay=False, allow_dash=True),
    default=None,
    help="Also write the report as JSON to FILE ('-' for standard output only).",
)
@click.option("--strict", is_flag=True, help="Exit with status 1 on warnings too, not only errors.")
@click.option("--force", is_flag=True, help="Overwrite the --json FILE if it exists.")
@reports_errors
def check_command(path, format_, rho, g, ulen, json_path, strict, force):
    """Check that the data in PATH are physically usable, and say where not.

    \b
    Tests: frequency grid; symmetry of A and B; B positive semidefinite per
    frequency (eigenvalues); A-infinity positive definite; decay of B at the highest
    frequency; inertia and restoring; DOFs copied from others. Exit status 0 when
    the data are usable (warnings allowed), 1 when not (or on warnings with --strict).

    \b
    Example:
      cummins check tanker.1
      cummins check cylinder.LIS --json report.json
    """
    from cummins.check import check

    if json_path and json_path != "-":
        prepare_outputs(json_path, force=force)
    ds = read_hydrodb(path, format_, rho, g, ulen)
    report = check(ds)
    if json_path == "-":
        click.echo(report.to_json())
    else:
        _print_report(report)
        if json_path:
            Path(json_path).write_text(report.to_json() + "\n", encoding="utf-8")
            console.print(f"JSON report written to {json_path}")
    failed = not report.ok or (strict and report.worst() == "warning")
    sys.exit(1 if failed else 0)


def _print_report(report) -> None:
    styles = {"ok": "green", "info": "cyan", "warning": "yellow", "error": "bold red"}
    console.print(f"[bold]Checks of {escape(report.source)}[/]")
    for f in report:
        # escaped: "[body1__Heave]" is no markup tag (rich would drop it)
        where = escape(f" [{f.where}]") if f.where else ""
        console.print(
            f"  [{styles[f.severity]}]{f.severity:7}[/] {escape(f.check)}{where}: "
            f"{escape(f.message)}"
        )
        if f.advice:
            console.print(f"          → {escape(f.advice)}", style="dim")
    verdict = "[green]usable[/]" if report.ok else "[bold red]NOT usable as it is[/]"
    console.print(f"Result: {verdict} (worst finding: {report.worst()})")


@main.command()
@click.argument("source", type=click.Path(exists=True))
@click.argument("destination", type=click.Path())
@read_options
@click.option(
    "--axes",
    type=click.Choice(["z-up", "z-down"]),
    default=None,
    help="Axis convention to write: z-up (x fwd, y port, z up: solvers) or z-down "
    "(x fwd, y starboard, z down: Fossen/MSS). Default: .mat files z-down, else as read.",
)
@click.option(
    "--reference-point",
    nargs=3,
    type=finite("m"),
    default=None,
    metavar="X Y Z",
    help="Move the reference point to X Y Z (m, in the axes written).",
)
@click.option(
    "--body",
    metavar="N|NAME",
    default=None,
    help="Of several bodies, write only this one (1-based number or name): its six DOFs "
    "as Surge … Yaw, e.g. for an MSS .mat, which holds one body.",
)
@click.option("--force", is_flag=True, help="Overwrite DESTINATION if it exists.")
@reports_errors
def convert(source, destination, format_, rho, g, ulen, axes, reference_point, body, force):
    """Convert SOURCE to canonical NetCDF (.nc), a BEMIO .h5 for WEC-Sim, or an MSS
    vessel struct (.mat).

    \b
    The NetCDF has Capytaine's layout (complex values on a re/im dimension) plus
    cummins' variables (added_mass_inf, ...), in SI units. The .h5 has the layout
    WEC-Sim's readBEMIOH5 reads (normalised coefficients, z-up axes, K(t)).

    \b
    Examples:
      cummins convert tanker.1 tanker.nc
      cummins convert tanker.1 tanker.h5
      cummins convert input.re7 supply.mat --reference-point 0 0 0
    """
    from cummins.hydrodb import change_axes, move_reference_point
    from cummins.io import write

    to_mat = Path(destination).suffix.lower() == ".mat"
    if Path(destination).suffix.lower() not in (".nc", ".mat", ".h5"):
        raise click.BadParameter(
            f"{destination}: write .nc (canonical NetCDF), .h5 (BEMIO, for WEC-Sim) or .mat "
            "(MSS vessel struct)",
            param_hint="DESTINATION",
        )
    prepare_outputs(destination, force=force)
    ds = read_hydrodb(source, format_, rho, g, ulen)
    if body is not None:
        ds = select_body(ds, body)
    if to_mat:
        _check_mss_body(ds)
    if axes is None and to_mat:
        axes = "z-down"
    if axes is not None:
        ds = change_axes(ds, axes)
    if reference_point is not None:
        ds = move_reference_point(ds, reference_point)
    write(ds, destination, force=force)
    console.print(
        f"wrote {destination} ({ds.attrs.get('axis_convention')} axes, reference point "
        f"{[float(x) for x in ds.attrs['reference_point']]} m)"
    )


def _check_mss_body(ds) -> None:
    """An MSS struct holds one rigid body: say how to choose one, and what it will lack."""
    from cummins.hydrodb import DOF_NAMES, bodies

    labels = [str(d) for d in ds.influenced_dof.values]
    if labels != list(DOF_NAMES):
        groups = bodies(ds)
        several = groups != [None]
        raise click.BadParameter(
            f"an MSS vessel struct holds one body with six DOFs (Surge … Yaw); the data "
            f"have {len(labels)} DOFs"
            + (
                f" of {len(groups)} bodies: choose one with --body 1 … {len(groups)}"
                if several
                else ""
            ),
            param_hint="DESTINATION",
        )
    for name, what in (
        ("inertia_matrix", "MRB (the rigid-body inertia) is written as zeros"),
        ("hydrostatic_stiffness", "C (the restoring) is written as zeros"),
    ):
        if name not in ds:
            warnings.warn(
                f"the data have no {name}: {what}; MSS needs it to simulate. Give it with "
                "cummins.with_inertia(...) / --mass … --radii-of-gyration … (inertia) or "
                "the solver's hydrostatics file",
                CumminsWarning,
                stacklevel=2,
            )


@main.command()
@click.option(
    "-o",
    "--output",
    "outdir",
    type=click.Path(file_okay=False),
    default="cummins-demo",
    show_default=True,
    help="Folder to write the results to.",
)
@click.option("--force", is_flag=True, help="Overwrite the files of an earlier demo run.")
@reports_errors
def demo(outdir, force):
    """Run the pipeline on a bundled real vessel (the MSS tanker, WAMIT output).

    Reads the WAMIT files, checks them, writes canonical NetCDF and an MSS .mat, and
    plots added mass, damping and excitation, all into the output folder.
    """
    from cummins.demo import run_demo

    prepare_outputs(force=force, folders=[outdir])
    with console.status("starting") as status:
        steps = run_demo(outdir, force=force, progress=lambda m: status.update(m))
    for step in steps:
        console.print(f"[bold green]✓[/] [bold]{step.title}[/]: {step.detail}")
        for f in step.files:
            console.print(f"    {f}")
    console.print(f"All results in {Path(outdir).resolve()}")


main.add_command(bem_command)  # works without Capytaine: it then says how to install it
main.add_command(kernel_command)
main.add_command(fit_command)
main.add_command(reduce_command)
main.add_command(rao_command)
main.add_command(simulate_command)
main.add_command(identify_damping_command)
main.add_command(dp_demo_command)
main.add_command(lf_model_command)
main.add_command(batch_command)  # works without Dask: it then says how to install it
main.add_command(report_command)


if __name__ == "__main__":  # pragma: no cover
    main()
