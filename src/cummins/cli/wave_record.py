"""``cummins simulate --wave-elevation FILE``: the vessel driven by a wave elevation record."""

from __future__ import annotations

import click
import numpy as np

from cummins.cli.common import console, progress_bar


def run_wave_record(vessel, ds, record_path, heading_deg: float, nonlinear_force=None):
    """Fit the causal excitation model of ``ds`` at the heading, read the record, run.

    Returns the run (:func:`cummins.timedomain.wave_record.simulate_wave_record`) and a
    title for the summary."""
    from cummins.excitation_model import fit_excitation
    from cummins.sysid.records import read_wave_elevation
    from cummins.timedomain.wave_record import simulate_wave_record

    record = read_wave_elevation(record_path)
    t = record.time.values
    with console.status("fitting the excitation model"):
        excitation = fit_excitation(ds, [np.radians(heading_deg)])
    for failure in excitation.attrs.get("failures", []):
        console.print(f"[yellow]note:[/yellow] excitation model: {failure}")
    tc = float(excitation.delays[0])
    if t[-1] - t[0] <= tc:
        raise click.BadParameter(
            f"the record lasts {t[-1] - t[0]:g} s, less than the excitation model's time "
            f"advance t_c = {tc:.3g} s (the force at t needs the elevation at t + t_c)",
            param_hint="--wave-elevation",
        )
    console.print(
        f"wave record {record_path}: {t.size} samples, dt {t[1] - t[0]:g} s; excitation "
        f"model {excitation.total_order} states, t_c {tc:.3g} s (the run ends t_c before "
        "the record; it starts from rest)"
    )
    with progress_bar() as bar:
        task = bar.add_task(f"simulating the record, heading {heading_deg:g}°", total=1.0)
        run = simulate_wave_record(
            vessel,
            excitation,
            t,
            record.values,
            nonlinear_force=nonlinear_force,
            progress=lambda fraction: bar.update(task, completed=fraction),
        )
    run.attrs["wave_record"] = str(record_path)
    return run, f"wave elevation record {record_path}"
