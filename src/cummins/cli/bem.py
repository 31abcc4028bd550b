"""``cummins bem``: compute a HydroDB with Capytaine and save it as NetCDF."""

from __future__ import annotations

import math
import time
from pathlib import Path

import click
import numpy as np
from rich.markup import escape

from cummins.cli.common import (
    Number,
    err_console,
    finite,
    force_option,
    headings_list,
    positive,
    prepare_outputs,
    reports_errors,
)
from cummins.cli.option_rules import Command, option_rules
from cummins.io._common import DEFAULT_G, DEFAULT_RHO


def _headings(values: tuple[str, ...]) -> list[float]:
    """Headings in degrees from ``--headings 0 --headings 90,180`` style options (default
    180: head seas)."""
    return headings_list(values, "--headings") or [180.0]


@click.command(name="bem", cls=Command)
@click.argument("mesh", required=False, type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--hull",
    type=click.Choice(["box", "wigley"]),
    help="Parametric hull instead of a mesh file (needs --length, --beam, --draft).",
)
@click.option("--length", type=positive("m"), help="Hull length L, m.")
@click.option("--beam", type=positive("m"), help="Hull beam B, m.")
@click.option("--draft", type=positive("m"), help="Hull draft T, m.")
@click.option(
    "--resolution",
    type=click.IntRange(2, 400),
    default=20,
    show_default=True,
    help="Panels along the length of a parametric hull (across the beam and draft as wide). "
    "Too coarse for the shortest wave and A, B come out non-symmetric: a warning says so "
    "after the run.",
)
@click.option(
    "--omega-min", type=positive("rad/s"), required=True, help="Lowest wave frequency, rad/s."
)
@click.option(
    "--omega-max", type=positive("rad/s"), required=True, help="Highest wave frequency, rad/s."
)
@click.option(
    "--n-omega",
    type=click.IntRange(1, 10_000),
    default=40,
    show_default=True,
    help="Number of frequencies, evenly spaced from --omega-min to --omega-max (1: one "
    "frequency, --omega-min = --omega-max). Radiation fits and K(t) need the resonances "
    "resolved: 30 or more over the range (a warning below 20).",
)
@click.option(
    "--headings",
    multiple=True,
    help="Wave directions in degrees (0 = waves travelling along +x, 180 = head "
    "seas); repeat the option or separate by commas. Default 180.",
)
@click.option(
    "--depth",
    type=Number(0.0, min_open=True, unit="m", infinite=True),
    default=math.inf,
    help="Water depth, m (default: deep water).",
)
@click.option(
    "--rho",
    type=positive("kg/m^3"),
    default=DEFAULT_RHO,
    show_default=True,
    help="Water density, kg/m^3.",
)
@click.option(
    "--g",
    "gravity",
    type=positive("m/s^2"),
    default=DEFAULT_G,
    show_default=True,
    help="Gravity, m/s^2.",
)
@click.option(
    "--cog",
    type=finite("m"),
    nargs=3,
    default=None,
    metavar="X Y Z",
    help="Centre of mass, m (default: on the waterline above the centre of buoyancy). "
    "Rotations are about it.",
)
@click.option("--no-limits", is_flag=True, help="Do not solve omega = 0 and omega = infinity.")
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False, path_type=Path),
    required=True,
    help="Output NetCDF file (.nc).",
)
@force_option("Overwrite the output file if it exists.")
@option_rules(needs={"length": "hull", "beam": "hull", "draft": "hull", "resolution": "hull"})
@reports_errors
def bem_command(
    mesh,
    hull,
    length,
    beam,
    draft,
    resolution,
    omega_min,
    omega_max,
    n_omega,
    headings,
    depth,
    rho,
    gravity,
    cog,
    no_limits,
    output,
    force,
):
    """Compute added mass, damping, excitation and hydrostatics with Capytaine.

    MESH is a mesh file Capytaine reads (WAMIT .gdf, NEMOH .dat, .stl ...); or use
    --hull box|wigley with --length --beam --draft. The result is saved as canonical
    NetCDF (Capytaine layout), e.g.

    \b
        cummins bem --hull box --length 20 --beam 8 --draft 2 \\
            --omega-min 0.2 --omega-max 2 --n-omega 30 --headings 180 -o barge.nc
    """
    from cummins import bem
    from cummins.io.netcdf import write_netcdf

    if (mesh is None) == (hull is None):
        raise click.UsageError("give either a MESH file or --hull box|wigley")
    if hull is not None:
        missing = [
            n for n, v in (("--length", length), ("--beam", beam), ("--draft", draft)) if v is None
        ]
        if missing:
            raise click.UsageError(f"--hull {hull} needs {', '.join(missing)}")
    # every argument is checked before Capytaine is looked for (exit status 2 first)
    directions = np.radians(_headings(headings))
    if n_omega == 1 and omega_min != omega_max:
        raise click.BadParameter(
            f"one frequency is --omega-min = --omega-max (got {omega_min:g} and "
            f"{omega_max:g} rad/s)",
            param_hint="--n-omega 1",
        )
    if n_omega > 1 and not omega_min < omega_max:
        raise click.BadParameter(
            f"{omega_min:g} rad/s is not below --omega-max {omega_max:g} rad/s",
            param_hint="--omega-min",
        )
    omega = bem.default_omegas(omega_min, omega_max, n_omega)
    prepare_outputs(output, force=force)
    if hull is not None:
        geometry = bem.hull_mesh(hull, length, beam, draft, resolution=resolution)
    else:
        geometry = mesh
    started = time.perf_counter()
    ds = bem.compute_hydrodb(
        geometry,
        omega,
        wave_direction=directions,
        water_depth=depth,
        rho=rho,
        g=gravity,
        center_of_mass=cog,
        limits=not no_limits,
        progress=True,
    )
    write_netcdf(ds, output)
    for line in bem.describe(ds):
        click.echo(line)
    click.echo(f"saved {output} ({time.perf_counter() - started:.1f} s)")
    for line in bem.data_warnings(ds, resolution if hull is not None else None):
        err_console.print(f"[yellow]warning:[/] {escape(line)}", highlight=False)
