"""`cummins info`: what a solver output file (or folder) holds."""

from __future__ import annotations

import json

import click
from rich.table import Table

from cummins.cli.common import console, read_hydrodb, read_options, reports_errors
from cummins.cli.option_rules import Command


@click.command(name="info", cls=Command)
@click.argument("path", type=click.Path(exists=True))
@read_options
@click.option("--json", "as_json", is_flag=True, help="Print the description as JSON.")
@reports_errors
def info_command(path, format_, rho, g, ulen, as_json):
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
