"""``cummins kernel``: retardation functions, A∞ and causality diagnostics of a file."""

from __future__ import annotations

from pathlib import Path

import click
import numpy as np
from rich.table import Table

from cummins.cli.common import (
    console,
    force_option,
    positive,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_speed,
    speed_option,
    stage_progress,
)
from cummins.cli.option_rules import Command, option_rules
from cummins.files import replacing


@click.command(name="kernel", cls=Command)
@click.argument("path", type=click.Path(exists=True))
@read_options(equation_of_motion=False)
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    required=True,
    help="NetCDF file for K(t), A-infinity and the diagnostics.",
)
@click.option(
    "--plot",
    "plot_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Also write PNG figures (K(t), A and B rebuilt from K, A-infinity) here.",
)
@click.option(
    "--t-max",
    type=positive("s"),
    default=None,
    metavar="S",
    help="Length of K(t), s (default: 40/omega_c, at most 2 pi/omega_min).",
)
@click.option(
    "--dt",
    type=positive("s"),
    default=None,
    metavar="S",
    help="Time step of K(t), s (default: t_max/1000).",
)
@click.option(
    "--tail",
    type=click.Choice(["auto", "exponential", "power", "none"]),
    default="auto",
    show_default=True,
    help="High-frequency continuation of B beyond the data.",
)
@click.option(
    "--interpolation",
    type=click.Choice(["linear", "pchip"]),
    default="linear",
    show_default=True,
    help="Interpolation of B between the data points.",
)
@click.option(
    "--omega-max",
    type=positive("rad/s"),
    default=None,
    metavar="RAD/S",
    help="Ignore the data above this frequency (e.g. the first irregular frequency).",
)
@click.option(
    "--remove-suspect/--keep-suspect",
    default=True,
    show_default=True,
    help="Leave out the frequencies where a DOF's own curves have spikes or clearly "
    "negative damping (irregular frequencies), as the fit does, each reported; sharp "
    "resonances the motions depend on stay. --keep-suspect integrates them as they are "
    "(a note lists them).",
)
@click.option(
    "--above-first",
    is_flag=True,
    help="Also remove everything above the first suspect frequency past the damping "
    "peak (irregular frequencies get denser upwards).",
)
@click.option(
    "--truncate",
    type=click.Choice(["subtract", "taper"]),
    default=None,
    help="Make K exactly zero at t_max: subtract K(t_max), or taper the last 5 %.",
)
@speed_option()
@force_option()
@option_rules(needs={"above_first": ("remove_suspect", bool, "(the default, not --keep-suspect)")})
@reports_errors
def kernel_command(
    path,
    format_,
    rho,
    g,
    ulen,
    output,
    plot_dir,
    t_max,
    dt,
    tail,
    interpolation,
    omega_max,
    remove_suspect,
    above_first,
    truncate,
    speed,
    force,
):
    """Retardation functions K(t) of all couplings, A-infinity, and how far to trust them.

    \b
    K(t) = (2/pi) int_0^inf B(w) cos(wt) dw is integrated exactly for the
    piecewise-linear damping (no aliasing on coarse grids), with B(0) = 0 and a
    fitted high-frequency tail. A-infinity is the solver's row when there is one,
    else Ogilvie's estimate combined over frequency. Per significant coupling the
    table gives K(0), K(t_max), the tail's share of the damping area, the A-infinity
    estimate and its spread, and the Kramers-Kronig error. Suspect frequencies
    (irregular frequencies, spikes) are left out first, as the fit leaves them out.

    \b
    Examples:
      cummins kernel tanker.1 -o K.nc --plot kernel-plots
      cummins kernel tanker.1 -o K.nc --above-first --truncate subtract
      cummins kernel tanker.1 -o K_raw.nc --keep-suspect
    """
    from cummins.cli.pipeline import kernel_stage, write_kernel_plots

    prepare_outputs(output, force=force, folders=[plot_dir])
    ds = select_speed(read_hydrodb(path, format_, rho, g, ulen), speed)
    with stage_progress("K(t) of every coupling and A∞"):
        result, ds = kernel_stage(
            ds,
            t_max=t_max,
            dt=dt,
            tail=tail,
            interpolation=interpolation,
            omega_max=omega_max,
            remove_suspect=remove_suspect,
            above_first=above_first,
            truncate=truncate,
            say=console.print,
        )
    console.print(kernel_table(result))
    with replacing(output) as tmp:
        result.to_netcdf(tmp, engine="h5netcdf")
    console.print(f"wrote {output}")
    if plot_dir:
        with stage_progress("drawing K(t), A and B rebuilt from it, A∞"):
            files = write_kernel_plots(result, ds, Path(plot_dir), force=force)
        for file in files:
            console.print(f"wrote {file}")


def kernel_table(result) -> Table:
    """The per-coupling summary printed by ``cummins kernel``."""
    labels = [str(d) for d in result.influenced_dof.values]
    table = Table(
        title=f"K(t) to {result.attrs['t_max']:.3g} s; A∞ used: "
        f"{result.attrs['added_mass_inf_method']}"
    )
    for column in (
        "coupling",
        "K(0)",
        "K(t_max)/max|K|",
        "tail",
        "A∞ estimate",
        "± spread",
        "A∞ data",
        "KK error",
    ):
        table.add_column(column, justify="right")
    for i, j in zip(*np.nonzero(np.triu(result.significant.values)), strict=True):
        row = result.isel(influenced_dof=i, radiating_dof=j)
        data = float(row.added_mass_inf_data)
        table.add_row(
            labels[i] if i == j else f"{labels[i]}-{labels[j]}",
            f"{float(row.K0):.4g}",
            f"{float(row.k_end_ratio):.2g}",
            f"{float(row.tail_fraction):.0%}",
            f"{float(row.added_mass_inf_estimate):.4g}",
            f"{float(row.added_mass_inf_spread):.2g}",
            "—" if not np.isfinite(data) else f"{data:.4g}",
            f"{float(row.kramers_kronig_error):.1%}",
        )
    return table
