"""`cummins info`: what a solver output file (or folder) holds."""

from __future__ import annotations

import json
from pathlib import Path

import click
import numpy as np
from rich.table import Table

from cummins.cli.common import console, read_hydrodb, read_options, reports_errors
from cummins.cli.option_rules import Command


def describe_directions(degrees) -> str:
    """Wave directions (deg), sorted, as a range with its step when they are uniform
    ("19: 180 to 360 every 10 deg" for VERES's 180, 190 … 350 and 0 stored for 360: read
    round the circle when only that makes them uniform), else listed; the convention
    said once."""
    raw = np.sort(np.asarray(degrees, dtype=float))

    def uniform(x) -> bool:
        steps = np.diff(x)
        return x.size >= 3 and bool(np.allclose(steps, steps[0], rtol=1e-6, atol=1e-6))

    order = raw
    if raw.size >= 3 and not uniform(raw):
        b = np.sort(np.mod(raw, 360.0))
        gaps = np.diff(np.concatenate([b, [b[0] + 360.0]]))
        turn = np.roll(b, -(int(np.argmax(gaps)) + 1))
        turn = turn[0] + np.mod(turn - turn[0], 360.0)  # increasing, past 360 at the wrap
        order = turn if uniform(turn) else raw
    if uniform(order):
        text = f"{order.size}: {order[0]:g} to {order[-1]:g} every {order[1] - order[0]:g} deg"
    else:
        text = f"{order.size}: " + ", ".join(f"{x:g}" for x in order) + " deg"
    wrapped = "360 stored as 0; " if order[-1] >= 360.0 else ""
    return text + f" ({wrapped}direction of propagation: 0 following, 180 head seas)"


def _point(values) -> str:
    """A point (or a list of points, one per body) with 6 significant digits."""
    if isinstance(values, list | tuple) and values and isinstance(values[0], list | tuple):
        return ", ".join(_point(v) for v in values)
    return "[" + ", ".join(f"{float(v):.6g}" for v in values) + "]"


def second_order_lines(summary: dict) -> list[str]:
    """One line per QTF and mean-drift estimate of :func:`cummins.qtf.second_order_summary`."""
    lines = []
    for name, part in summary.items():
        if name.startswith("qtf_"):
            lo, hi = part["omega_range_rad_s"]
            step = part["omega_spacing_rad_s"]
            spacing = f", dw {step[0]:.3g}" + (
                f"–{step[1]:.3g}" if step[1] > 1.01 * step[0] else ""
            )
            lines.append(
                f"{name}: {part['n_omega']}x{part['n_omega']} frequencies {lo:.3g}–{hi:.3g} rad/s"
                f"{spacing if step else ''}, directions "
                + ", ".join(f"{b:g}" for b in part["wave_directions_deg"])
                + " deg"
                + (" (bi-directional)" if part["bidirectional"] else "")
                + (f" [{part['source']}]" if part["source"] else "")
            )
        else:
            lines.append(f"{name}: mean drift, {part['method'] or 'method not recorded'}")
    return lines


@click.command(name="info", cls=Command)
@click.argument("path", type=click.Path(exists=True))
@read_options
@click.option("--json", "as_json", is_flag=True, help="Print the description as JSON.")
@reports_errors
def info_command(path, format_, rho, g, ulen, as_json):
    """Describe what PATH holds: format, DOFs, frequencies, headings, constants used,
    and where the restoring came from (whether it holds the weight's terms, for which
    mass and centre of gravity). A model file of `cummins fit` or `cummins fit-excitation`
    is described as a model: DOFs, states, stability, passivity, the data it was fitted
    to and its failures.

    \b
    Example:
      cummins info tanker.1
      cummins info results/ --format nemoh --json
    """
    from cummins.hydrodb import describe

    model = model_description(path)
    if model is not None:  # a model file of cummins fit / fit-excitation, not data
        given = [
            option
            for option, value in (
                ("--format", format_),
                ("--rho", rho),
                ("--g", g),
                ("--ulen", ulen),
            )
            if value is not None
        ]
        if given:
            raise click.UsageError(
                f"{path} is a model file, not solver data: {', '.join(given)} apply to data "
                "(the model records the constants it was fitted with)"
            )
        if as_json:
            click.echo(json.dumps(model, indent=2))
            return
        for key, value in model.items():
            if key != "failures":
                console.print(f"[bold]{key}[/]  {value}", highlight=False)
        for line in model["failures"]:
            console.print(f"failure: {line}", highlight=False)
        return
    ds = read_hydrodb(path, format_, rho, g, ulen)
    d = describe(ds)
    if as_json:
        click.echo(json.dumps(d, indent=2))
        return
    table = Table(show_header=False, box=None, pad_edge=False)
    table.add_column(style="bold")
    table.add_column()
    table.add_row("file", _file_row(path, format_, d))
    table.add_row("DOFs", ", ".join(d["dofs"]))
    table.add_row(
        "frequencies",
        f"{d['n_omega']} from {d['omega_min_rad_s']:.4g} to {d['omega_max_rad_s']:.4g} rad/s "
        f"(periods {d['period_range_s'][0]:.3g}–{d['period_range_s'][1]:.4g} s)",
    )
    if d["wave_directions_deg"]:
        betas = d["wave_directions_deg"]
        table.add_row("wave directions", describe_directions(betas))
    table.add_row("forward speeds", ", ".join(f"{u:g}" for u in d["forward_speeds_m_s"]) + " m/s")
    table.add_row("variables", ", ".join(d["variables"]))
    table.add_row("rho, g", f"{d['rho_kg_m3']:g} kg/m³, {d['g_m_s2']:g} m/s²")
    table.add_row(
        "water depth",
        f"{d['water_depth_m']:g} m"
        + (
            " (not recorded in the files: assumed; --water-depth)"
            if d["water_depth_assumed"]
            else ""
        ),
    )
    table.add_row("axes", str(d["axis_convention"]))
    table.add_row("reference point", f"{_point(d['reference_point_m'])} m")
    for key, label in (
        ("center_of_gravity_m", "centre of gravity"),
        ("center_of_buoyancy_m", "centre of buoyancy"),
    ):
        if key in d:
            table.add_row(label, f"{_point(d[key])} m")
    for key, label, unit in (
        ("displaced_volume_m3", "displaced volume", "m³"),
        ("mass_kg", "mass", "kg"),
    ):
        if key in d:
            values = d[key] if isinstance(d[key], list) else [d[key]]
            table.add_row(label, ", ".join(f"{v:.6g}" for v in values) + f" {unit}")
    if "restoring" in d:
        table.add_row("restoring", d["restoring"])
    for k, line in enumerate(second_order_lines(d.get("second_order", {}))):
        table.add_row("second order" if k == 0 else "", line)
    for k, line in enumerate(d["history"]):
        table.add_row("provenance" if k == 0 else "", line)
    console.print(table)


def model_description(path) -> dict | None:
    """What a model file written by ``cummins fit`` or ``cummins fit-excitation`` holds
    (kind, DOFs, states, stability, passivity, the data it was fitted to, its failures),
    or None when ``path`` is not one."""
    from cummins.cli.common import cummins_model_format

    if Path(path).suffix.lower() in (".ss", ".ssexctn"):
        return openfast_description(path)
    kind = cummins_model_format(path)
    if kind is None:
        return None
    from cummins.excitation_model.model_file import FORMAT_NAME as EXCITATION
    from cummins.radiation.model_file import FORMAT_NAME as RADIATION

    if kind == RADIATION:
        from cummins.cli.fit import fit_summary
        from cummins.radiation.model import RadiationModel

        model = RadiationModel.load(path)
        summary = fit_summary(model, float(model.attrs.get("elapsed_s", 0.0)))
        out = {
            "file": str(path),
            "kind": "radiation model (cummins fit): the fluid memory K(t) as a state space",
            "dofs": ", ".join(model.dofs),
            "states": summary["total_order"],
            "blocks": len(summary["blocks"]),
            "stable": summary["mimo_stable"],
            "passive": summary["mimo_passive"],
        }
        if model.attrs.get("motions_of"):  # fitted for a mechanical system: say which
            out["fitted_for"] = str(model.attrs["motions_of"])
        if model.attrs.get("body_coupling"):
            out["body_coupling"] = str(model.attrs["body_coupling"])
    elif kind == EXCITATION:
        import numpy as np

        from cummins.cli.fit_excitation import excitation_summary
        from cummins.excitation_model import ExcitationModel

        model = ExcitationModel.load(path)
        summary = excitation_summary(model, float(model.attrs.get("elapsed_s", 0.0)))
        out = {
            "file": str(path),
            "kind": "wave excitation model (cummins fit-excitation): force from the wave "
            "elevation, time advance t_c per heading",
            "dofs": ", ".join(model.dofs),
            "headings_deg": ", ".join(f"{np.degrees(b):g}" for b in model.headings),
            "states": summary["total_states"],
            "stable": summary["stable"],
        }
    else:
        return None
    out["fitted_to"] = str(model.attrs.get("source_file", "")) or "not recorded"
    out["failures"] = summary["failures"]
    return out


def _file_row(path, format_, d) -> str:
    """The file read, and the solver's file its data came from when they differ (a
    NetCDF, BEMIO .h5 or MSS .mat that cummins wrote keeps the source's provenance)."""
    source, kind = d.get("source_file"), d.get("source_format")
    read = Path(path)
    if not source:
        return f"{path} ({kind})"
    origin = Path(str(source))
    if origin.resolve() == read.resolve() or (
        read.is_dir() and read.resolve() in origin.resolve().parents
    ):
        return f"{source} ({kind})"
    if format_ is None:
        from cummins.errors import HydroDataError
        from cummins.io import detect_format

        try:
            format_ = detect_format(read)[0]
        except (HydroDataError, OSError, ValueError):  # only a label: the file was read
            format_ = "?"
    # a file of the same run (WAMIT's .12d, .3 or .hst given for its .1)
    if format_ == kind and origin.stem == read.stem and origin.parent == read.parent:
        return f"{source} ({kind})"
    return f"{path} ({format_}): the data of {source} ({kind})"


def openfast_description(path) -> dict:
    """What an OpenFAST state-space file holds: a radiation model (``.ss``, SS_Fitting's,
    HydroDyn's ``RdtnMod = 2``) or an excitation model (``.ssexctn``, or an ``.ss`` that
    holds one): its DOFs, states per DOF and stability (the eigenvalues of A)."""
    from cummins.dofs import DOF_NAMES
    from cummins.io._text import TextFile
    from cummins.io.openfast import (
        is_excitation_file,
        read_openfast_ss,
        read_openfast_ssexctn,
    )

    excitation = Path(path).suffix.lower() == ".ssexctn" or is_excitation_file(TextFile.read(path))
    content = read_openfast_ssexctn(path) if excitation else read_openfast_ss(path)
    a = np.asarray(content.A, dtype=float)
    poles = np.linalg.eigvals(a) if a.size else np.zeros(0)
    slowest = float(poles.real.max()) if poles.size else 0.0
    counts = np.asarray(content.states_per_dof, dtype=int)
    names = [
        f"{DOF_NAMES[k % 6]}" + (f" (body {k // 6 + 1})" if counts.size > 6 else "")
        for k in range(counts.size)
    ]
    modelled = [f"{name}: {n}" for name, n in zip(names, counts, strict=True) if n > 0]
    out = {
        "file": str(path),
        "kind": (
            "OpenFAST excitation state space (SS_Excitation_Fitting, HydroDyn ExctnMod = 2): "
            "the wave force from the elevation"
            if excitation
            else "OpenFAST radiation state space (SS_Fitting, HydroDyn RdtnMod = 2): the "
            "fluid memory K(t)"
        ),
        "title": content.title.strip(),
        "states": int(a.shape[0]),
        "states_per_dof": ", ".join(modelled) or "none",
        "stable": bool(slowest < 0),
        "slowest_pole": f"Re = {slowest:.4g} 1/s",
    }
    if excitation:
        out["heading_deg"] = float(content.heading)
        offset = content.time_offset
        out["time_offset_s"] = (
            "not recorded (SS_Fitting's time-domain layout, which HydroDyn cannot read)"
            if offset is None
            else float(offset)
        )
    out["failures"] = [] if slowest < 0 else ["A has eigenvalues with Re >= 0: not stable"]
    return out
