"""``cummins dp-demo``: the dynamic-positioning scenario of Smogeli et al. (2004) §7."""

from __future__ import annotations

import math
from pathlib import Path

import click

from cummins.cli.common import (
    Number,
    console,
    force_option,
    heading_degrees,
    main_dimensions_option,
    non_negative,
    note_inputs,
    positive,
    prepare_outputs,
    progress_bar,
    reports_errors,
)
from cummins.cli.option_rules import Command, option_rules
from cummins.cli.second_order import keep_suspect_option, second_order_option
from cummins.validation import check_simulation_size


@click.command(name="dp-demo", cls=Command)
@click.option(
    "-o",
    "--output",
    "folder",
    type=click.Path(file_okay=False),
    required=True,
    help="Folder for run.nc and the PNG figures.",
)
@click.option("--duration", type=positive("s"), default=600.0, show_default=True, metavar="S")
@click.option(
    "--dt",
    type=positive("s"),
    default=0.2,
    show_default=True,
    metavar="S",
    help="Time step (Runge-Kutta 4).",
)
@click.option(
    "--seed",
    type=click.IntRange(0, 2**63 - 1),
    default=1,
    show_default=True,
    help="Random wave phases.",
)
@click.option(
    "--current",
    "current_speed",
    type=non_negative("m/s"),
    default=0.0,
    show_default=True,
    metavar="M/S",
    help="Current speed (from --current-from).",
)
@click.option(
    "--current-from", type=heading_degrees(), default=0.0, show_default=True, metavar="DEG"
)
@click.option(
    "--wind",
    "wind_speed",
    type=non_negative("m/s"),
    default=0.0,
    show_default=True,
    metavar="M/S",
    help="Mean wind speed at 10 m, with NORSOK gusts.",
)
@click.option("--wind-from", type=heading_degrees(), default=30.0, show_default=True, metavar="DEG")
@click.option(
    "--data",
    "data_path",
    type=click.Path(exists=True),
    default=None,
    help="The vessel: any file cummins reads that holds what DP needs (an MSS vessel "
    ".mat such as supply.mat or tanker.mat, or VERES/WAMIT files with mean drift and main "
    "dimensions), at zero speed; default: MSS's S-175, bundled with cummins.",
)
@click.option(
    "--water-depth",
    type=Number(0.0, min_open=True, unit="m", infinite=True),
    default=None,
    metavar="M",
    help="Water depth of the --data files in m (inf for deep water) when they do not "
    "record it (VERES, MSS structs): the wave numbers of the wave loads. Default: deep "
    "water, with a warning.",
)
@main_dimensions_option(
    help="Length between perpendiculars, breadth and draught of the --data vessel in m, "
    "when its files do not give them (WAMIT: MSS's tanker is 246 46 10); they size the "
    "surge resistance, the cross-flow drag, the wind areas and the thrusters' positions.",
)
@click.option(
    "--yaw-setpoint",
    type=heading_degrees(),
    default=0.0,
    show_default=True,
    metavar="DEG",
    help="DP set-point in yaw (clockwise from North). The ship starts heading North with "
    "the waves from 45 deg off its starboard bow; a set-point turns it (45: head seas), "
    "and every wave load follows its relative heading.",
)
@second_order_option(
    "newman",
    "Wave drift, each at the instantaneous relative heading of the waves (the data's "
    "headings interpolated, mirrored for a symmetric hull; beyond them the nearest "
    "heading's values, with a note): newman (mean and slowly "
    "varying drift by Newman's approximation, the paper's), mean (the data's mean drift "
    "alone), full (the data's QTF, and its sum-frequency QTF when it has one; the bundled "
    "S-175 has none: it then stops with an error) or none.",
)
@keep_suspect_option
@force_option("Overwrite the files of an earlier run.")
@option_rules(
    needs={
        "current_from": ("current_speed", lambda v: v > 0, "above 0"),
        "wind_from": ("wind_speed", lambda v: v > 0, "above 0"),
        "water_depth": "data_path",
        "main_dimensions": "data_path",
    }
)
@reports_errors
def dp_demo_command(
    folder,
    duration,
    dt,
    seed,
    current_speed,
    current_from,
    wind_speed,
    wind_from,
    data_path,
    water_depth,
    main_dimensions,
    yaw_setpoint,
    second_order,
    keep_suspect,
    force,
):
    """A ship on DP in a seaway (the S-175 unless --data), a crane load at t = 100 s.

    \b
    The scenario of Smogeli et al. (2004) §7, with the nonlinear 6-DOF model of the
    Marine Systems Simulator (their eq. 56): body-fixed kinematics, the fluid memory as
    a state-space model fitted to the MSS data, first-order wave forces and the wave
    drift at the instantaneous relative heading, ITTC surge resistance and cross-flow
    drag, optional current and wind, a nonlinear PID with a wave filter and thrust
    allocation to four thrusters. Sea: JONSWAP Hs 4 m, wp 0.60 rad/s, gamma 3.3,
    short-crested, from 45 deg off the starboard bow. At t = 100 s a 1000 kN crane load
    hangs 15 m to starboard: the ship heels to a new mean roll angle, checked against
    the static heel of its restoring. With --data another vessel takes the S-175's
    place: its own dimensions and its MSS Bv (at the lowest frequency) as linear
    damping of surge, sway and yaw; data lacking what the scenario needs (mean drift,
    main dimensions ...) stop with one line naming it.

    \b
    Writes DIR/run.nc (eta: North, East, Down, Roll, Pitch, Yaw in m and rad, NED; nu:
    body velocities; each load's force, the thrust, the fluid memory force) and
    pose.png, wave_and_radiation_forces.png, loads.png, watch_circle.png.

    \b
    Example:
      cummins dp-demo -o dp --duration 600 --seed 1
      cummins dp-demo -o dp_supply --duration 200 --data supply.mat
      cummins dp-demo -o dp_turn --duration 300 --yaw-setpoint 60 --second-order mean
    """
    from cummins.cli.dp_scenario import (
        CRANE_TIME,
        HEEL_CHECK_DURATION,
        HEEL_SETTLE,
        run_scenario,
        scenario_data,
        write_scenario_plots,
    )
    from cummins.io.netcdf import save_netcdf

    out = Path(folder)
    names = ["run.nc", "pose.png", "wave_and_radiation_forces.png", "loads.png", "watch_circle.png"]
    note_inputs(data_path)
    prepare_outputs(*(out / n for n in names), force=force)
    # before the model is built: the run's size (the S-175 model has about 60 states)
    check_simulation_size(duration, dt, 60, 54, option="--duration")
    ds, damping = scenario_data(
        data_path, second_order, water_depth=water_depth, main_dimensions=main_dimensions
    )
    with progress_bar() as bar:
        task = bar.add_task(f"simulating {duration:g} s of DP", total=1.0)
        scenario = run_scenario(
            ds,
            duration=duration,
            dt=dt,
            seed=seed,
            current_speed=current_speed,
            current_from_deg=current_from,
            wind_speed=wind_speed,
            wind_from_deg=wind_from,
            second_order=second_order,
            keep_suspect=keep_suspect,
            yaw_setpoint=math.radians(yaw_setpoint),
            viscous_damping=damping,
            progress=lambda fraction: bar.update(task, completed=fraction),
        )
    for load in scenario.loads:  # what the second-order load assumes (headings, grid)
        for line in getattr(load, "notes", ()):
            console.print(f"note: {load.name}: {line}")
    save_netcdf(scenario.run, out / "run.nc")
    for file in [out / "run.nc", *write_scenario_plots(scenario, out, force=force)]:
        console.print(f"wrote {file}")
    a = scenario.run.attrs
    console.print(
        f"watch circle {a['check_watch_circle_m']:.2f} m, largest yaw {a['check_max_yaw_deg']:.2f}°"
    )
    if "check_static_heel_deg" in a:
        console.print(
            f"mean roll {a['check_mean_roll_before_deg']:.3f}° before the crane load, "
            f"{a['check_mean_roll_after_deg']:.3f}° after it; static heel "
            f"{a['check_static_heel_deg']:.3f}° ({100 * a['check_heel_error']:+.1f} %)"
        )
    else:
        console.print(
            f"note: no heel check: the crane load starts at {CRANE_TIME:g} s and the mean roll "
            f"is taken from {HEEL_SETTLE:g} s after it; --duration over "
            f"{HEEL_CHECK_DURATION:g} s compares it with the static heel"
        )
