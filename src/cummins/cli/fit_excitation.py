"""``cummins fit-excitation``: causal state-space models of the wave excitation."""

from __future__ import annotations

import json
import sys
import time
from dataclasses import replace
from pathlib import Path

import click
import numpy as np
from rich import box
from rich.markup import escape
from rich.table import Table

from cummins.cli.common import (
    Number,
    console,
    counted_progress,
    finite,
    force_option,
    non_negative,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_speed,
    speed_option,
)

#: Exit status when the model was written but a DOF misses its NRMSE target.
FIT_FAILED = 3


@click.command(name="fit-excitation")
@click.argument("path", type=click.Path(exists=True))
@read_options
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    required=True,
    help="NetCDF file for the model (a, b, c per heading and DOF, t_c per heading).",
)
@click.option(
    "--heading",
    "headings",
    type=finite("deg"),
    multiple=True,
    metavar="DEG",
    help="Direction of wave travel to model, degrees (0 following seas, 180 head seas; "
    "repeatable); default every heading of the data.",
)
@click.option(
    "--delay",
    type=non_negative("s"),
    default=None,
    metavar="S",
    help="Time advance t_c of the model (it is driven by the elevation at t + t_c); "
    "default: chosen from the excitation impulse response (--causality).",
)
@click.option(
    "--causality",
    type=Number(0.0, 0.5, min_open=True, max_open=True),
    default=1e-3,
    show_default=True,
    help="Automatic t_c: the share of the energy of K_ex(t) left before -t_c (tried "
    "again at 1/10 and 1/100 of it where a DOF misses its target).",
)
@click.option(
    "--nrmse",
    type=Number(0.0, 1.0, min_open=True, max_open=True),
    default=0.03,
    show_default=True,
    help="Target normalised RMS error of the complex response F(w) over the wave band "
    "(|F| above 1 %% of its peak).",
)
@click.option(
    "--max-order",
    type=click.IntRange(1, 200),
    default=60,
    show_default=True,
    help="Most states per DOF and heading.",
)
@click.option(
    "--order",
    type=click.IntRange(1, 200),
    default=None,
    help="Fit every DOF with this many states (no search).",
)
@click.option(
    "--method",
    type=click.Choice(["vf", "realization"]),
    default="vf",
    show_default=True,
    help="vf: vector fitting of F(w) exp(-jw t_c); realization: Kung/ERA on the shifted "
    "impulse response K_ex(t - t_c).",
)
@click.option(
    "--json",
    "json_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write a summary as JSON (per heading and DOF: states, NRMSE; t_c).",
)
@click.option(
    "--plot",
    "plot_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Write one PNG per heading: |F| and phase, data against the model, and K_ex(t).",
)
@click.option(
    "--openfast",
    type=click.Path(dir_okay=False),
    default=None,
    help="Also write the model as an OpenFAST HydroDyn .ssexctn file (ExctnMod = 2; one "
    "heading: give --heading DEG, HydroDyn's WaveDir).",
)
@speed_option()
@force_option()
@reports_errors
def fit_excitation_command(
    path,
    format_,
    rho,
    g,
    ulen,
    output,
    headings,
    delay,
    causality,
    nrmse,
    max_order,
    order,
    method,
    json_path,
    plot_dir,
    openfast,
    speed,
    force,
):
    """Identify causal state-space models of the wave excitation, per heading and DOF.

    \b
    The wave force as the output of a stable linear system driven by the wave
    elevation at the origin, advanced by t_c:  x' = A x + B eta(t + t_c),  F = C x,
    whose response C (jwI - A)^-1 B exp(jw t_c) reproduces the data's excitation
    F(w). The excitation impulse response K_ex(t) = (1/2pi) int F(w) exp(iwt) dw is
    not causal (it starts before t = 0); t_c is the smallest advance that leaves at
    most --causality of its energy before -t_c. Each DOF is fitted by vector fitting
    (stable poles) with the fewest states whose NRMSE over the wave band meets
    --nrmse. A DOF the waves do not excite gets no states. A model that misses a
    target is written and the command exits with status 3.

    \b
    Examples:
      cummins fit-excitation spar.1 -o spar_excitation.nc --heading 0 --openfast spar.ssexctn
      cummins fit-excitation spar.1 -o spar_excitation.nc --plot exc-plots
      cummins fit-excitation tanker.1 -o exc.nc --heading 180 --delay 40 --max-order 80
    """
    from cummins.excitation_model import fit_excitation

    prepare_outputs(output, json_path, openfast, force=force, folders=[plot_dir])
    ds = select_speed(read_hydrodb(path, format_, rho, g, ulen), speed)
    if openfast:
        check_openfast_output(ds, headings)
    directions = None if not headings else np.radians(np.asarray(headings, dtype=float))
    total = len(headings) if headings else (ds.sizes.get("wave_direction", 0) or 1)
    start = time.perf_counter()
    with counted_progress("headings", total) as progress:
        model = fit_excitation(
            ds,
            directions,
            delay=delay,
            causality=causality,
            nrmse_target=nrmse,
            max_order=max_order,
            order=order,
            method=method,
            progress=progress,
        )
    elapsed = time.perf_counter() - start
    console.print(excitation_table(model))
    for note in model.attrs.get("data_notes", []):
        console.print(f"[yellow]data:[/yellow] {escape(note)}")
    console.print(
        f"{model.total_order} states over {len(model.headings)} heading(s), every model "
        f"stable: {model.is_stable()}, {elapsed:.2f} s"
    )
    model = replace(model, attrs={**model.attrs, "data_file": str(Path(path).resolve())})
    model.save(output, force=force)
    console.print(f"wrote {output}")
    if json_path:
        summary = excitation_summary(model, elapsed)
        Path(json_path).write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
        console.print(f"wrote {json_path}")
    if openfast:
        from cummins.cli.fit import reference_point_clause
        from cummins.io.openfast_excitation import (
            openfast_ssexctn_from_model,
            write_openfast_ssexctn,
        )

        write_openfast_ssexctn(model, openfast, force=force)
        # the file's heading, HydroDyn's z-up one in (-180, 180], which WaveDir must equal
        written = openfast_ssexctn_from_model(model).heading
        given = float(np.degrees(model.headings[0]))
        axes = model.attrs.get("axis_convention", "z-up")
        console.print(
            f"wrote {openfast} (HydroDyn ExctnMod = 2: WaveDir {written:g} deg"
            + (
                f", the data's {given:g} deg in their {axes} axes"
                if abs(np.angle(np.exp(1j * np.radians(written - given)))) > 1e-9 or axes != "z-up"
                else ""
            )
            + f", t_c {model.delays[0]:.4g} s, {int(model.orders[0].sum())} states)"
            + reference_point_clause(model.attrs)
        )
    if plot_dir:
        from cummins.excitation_model.figures import plot_excitation_fit
        from cummins.plots import save_figure

        for h, beta in enumerate(model.headings):
            name = f"excitation_{np.degrees(beta):g}deg.png"
            file = save_figure(
                plot_excitation_fit(ds, model, h), Path(plot_dir) / name, force=force
            )
            console.print(f"wrote {file}")
    failures = model.attrs.get("failures", [])
    for failure in failures:
        console.print(f"[bold red]failure:[/bold red] {escape(failure)}", highlight=False)
    if failures:
        sys.exit(FIT_FAILED)


def check_openfast_output(ds, headings) -> None:
    """Before the fit: a .ssexctn holds one heading and the six DOFs of each body."""
    from cummins.hydrodb import DOF_NAMES, split_dof

    names = [split_dof(str(d))[1] for d in ds.influenced_dof.values]
    if not names or len(names) % 6 or names != list(DOF_NAMES) * (len(names) // 6):
        raise click.BadParameter(
            f"HydroDyn's .ssexctn holds the six DOFs of each body; the data have {len(names)} DOFs",
            param_hint="--openfast",
        )
    count = len(headings) if headings else ds.sizes.get("wave_direction", 1)
    if count != 1:
        raise click.BadParameter(
            "HydroDyn reads one heading per .ssexctn (it must equal its WaveDir): give one "
            "--heading DEG",
            param_hint="--openfast",
        )


def excitation_table(model) -> Table:
    """Per heading and DOF: states, NRMSE over the band, the band; t_c per heading."""
    table = Table(
        title=f"wave excitation model ({model.attrs.get('method')}; NRMSE target "
        f"{model.attrs.get('nrmse_target', float('nan')):g})",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        collapse_padding=True,
    )
    for column in ("heading", "t_c [s]", "DOF", "states", "NRMSE", "band [rad/s]", "met"):
        table.add_column(column, justify="left" if column == "DOF" else "right")
    for h, beta in enumerate(model.headings):
        for d, label in enumerate(model.dofs):
            part = model.model(h, d)
            if not part.order:
                continue
            m = part.metrics
            table.add_row(
                f"{np.degrees(beta):g}°",
                f"{model.delays[h]:.3g}",
                str(label),
                str(part.order),
                f"{m['nrmse']:.4f}",
                f"{m['band_min']:.3g}–{m['band_max']:.3g}",
                "yes" if m["target_met"] else "NO",
            )
    return table


def excitation_summary(model, elapsed: float) -> dict:
    """The ``--json`` summary."""
    return {
        "headings_deg": [float(np.degrees(b)) for b in model.headings],
        "delays_s": [float(x) for x in model.delays],
        "models": [
            {
                "heading_deg": float(np.degrees(model.headings[m.heading])),
                "dof": model.dofs[m.dof],
                "states": m.order,
                "nrmse": float(m.metrics.get("nrmse", 0.0)),
                "target_met": bool(m.metrics.get("target_met", True)),
            }
            for m in model.models
        ],
        "total_states": model.total_order,
        "stable": model.is_stable(),
        "failures": list(model.attrs.get("failures", [])),
        "elapsed_s": elapsed,
    }
