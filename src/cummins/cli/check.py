"""`cummins check`: is the data physically usable, and where not."""

from __future__ import annotations

import sys

import click
from rich.markup import escape

from cummins.cli.common import (
    console,
    force_option,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
)
from cummins.cli.option_rules import Command
from cummins.files import write_text


@click.command(name="check", cls=Command)
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
@force_option("Overwrite the --json FILE if it exists.")
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
            write_text(json_path, report.to_json() + "\n")
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
