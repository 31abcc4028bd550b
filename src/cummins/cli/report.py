"""`cummins report`: a self-contained HTML page of a data, model, RAO, run or results file."""

from __future__ import annotations

import click

from cummins.cli.common import (
    console,
    force_option,
    prepare_outputs,
    read_options,
    reports_errors,
)
from cummins.cli.option_rules import Command


@click.command(name="report", cls=Command)
@click.argument("path", metavar="FILE|MODEL|RUN", type=click.Path(exists=True))
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), required=True, help="The HTML page."
)
@click.option(
    "--kind",
    type=click.Choice(
        ["data", "model", "excitation-model", "rao", "run", "dp", "lf", "kernel", "batch"]
    ),
    default=None,
    help="What PATH is (default: detected from its content); a kind given must be what "
    "the file holds.",
)
@read_options
@force_option("Overwrite OUTPUT.")
@reports_errors
def report_command(path, output, kind, format_, rho, g, ulen, force):
    """Write a self-contained HTML report of a file: figures and tables, no links out.

    \b
    What it shows depends on what the file is (detected from its content):
      data file/folder   data checks, A(w), B(w), excitation, K(t), motion RAOs
      model (cummins fit) per-coupling orders and R², K(t), data against the model
      excitation model   states, t_c and NRMSE per heading and DOF, |F| and K_ex(t)
      (fit-excitation)   against the data (read with the model's rho, g)
      RAO file (rao)     RAOs and their largest values; with PTOs the power RAO,
                         PTO force and relative-motion RAOs
      run (simulate)     statistics, time series, response spectra; with PTOs the
                         mean power, energy, force/velocity/power time series
      run (dp-demo)      checks (heel, watch circle), pose, every load, track
      LF model (lf-model) the constant coefficients and where each was taken
      K(t) (kernel)      the diagnostics of every significant coupling, K(t)
      results (batch)    the study, operability per heading, limiting Hs, cases;
                         with PTOs the power matrix over Hs x Tp (table, heat map)
    The figures are embedded PNGs and the style is inline: the page opens offline.

    \b
    Examples:
      cummins report tanker.1 -o tanker.html
      cummins report exc.nc -o exc.html
      cummins report results.nc -o report.html
      cummins report run.nc -o run.html --force
    """
    from cummins.cli.html_report import write_report

    prepare_outputs(output, force=force)
    from cummins.cli.failed_model import warn_failed_file

    warn_failed_file(path)
    with console.status("drawing the report"):
        written = write_report(
            path,
            output,
            force=force,
            kind=kind,
            read_options={"format": format_, "rho": rho, "g": g, "ulen": ulen},
        )
    size = written.stat().st_size / 1e6
    console.print(f"wrote {written} ({size:.1f} MB)")
