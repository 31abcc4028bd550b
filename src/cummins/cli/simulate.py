"""``cummins simulate``: the vessel in waves, in the time domain."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import click
import numpy as np
from rich.markup import escape

from cummins.cli.common import (
    Number,
    allow_other_data_option,
    check_dof_selection,
    console,
    force_option,
    heading_degrees,
    model_and_data,
    non_negative,
    positive,
    prepare_outputs,
    progress_bar,
    read_hydrodb,
    read_options,
    reports_errors,
    select_speed,
    speed_option,
    viscous_damping_option,
    viscous_damping_values,
)
from cummins.cli.option_rules import option_rules, unique_values
from cummins.cli.second_order import (
    build_second_order,
    keep_suspect_option,
    second_order_option,
    sum_frequency_option,
)
from cummins.cli.system_options import SystemCommand, system_from_options, system_options
from cummins.timedomain.time_step import (
    DEFAULT_DT,
    ENERGY_TOLERANCE,
    STEPS_PER_PERIOD,
    STEPS_PER_SHORTEST_PERIOD,
    default_time_step,
)
from cummins.validation import check_simulation_size


@click.command(name="simulate", cls=SystemCommand)
@click.argument("path", metavar="DATA|MODEL", type=click.Path(exists=True))
@read_options
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), required=True, help="NetCDF file of the run."
)
@click.option(
    "--hs", type=positive("m"), default=None, metavar="M", help="Significant wave height."
)
@click.option("--tp", type=positive("s"), default=None, metavar="S", help="Peak period.")
@click.option(
    "--spectrum",
    type=click.Choice(["jonswap", "pm", "torsethaugen"]),
    default="jonswap",
    show_default=True,
    help="Wave spectrum (pm: Pierson-Moskowitz / ITTC).",
)
@click.option(
    "--gamma", type=Number(1.0), default=3.3, show_default=True, help="JONSWAP peakedness."
)
@click.option(
    "--heading",
    type=heading_degrees(),
    default=None,
    metavar="DEG",
    help="Direction the waves travel, degrees: 0 following seas (along +x), 180 head seas "
    "(default: 180, or the data's heading when they hold only one).",
)
@click.option(
    "--spreading",
    type=non_negative(),
    default=None,
    metavar="S",
    help="Short-crested seas: cos-2s spreading exponent s (with --directions).",
)
@click.option(
    "--directions",
    type=click.IntRange(min=2),
    default=9,
    show_default=True,
    help="With --spreading.",
)
@click.option(
    "--components",
    type=click.IntRange(min=1),
    default=200,
    show_default=True,
    help="Wave components.",
)
@click.option(
    "--duration",
    type=positive("s"),
    default=3 * 3600.0,
    show_default=True,
    metavar="S",
    help="Length of the run, s (3 hours: the usual sea-state duration; a regular wave "
    "starts steady, a few periods show it).",
)
@click.option(
    "--dt",
    type=positive("s"),
    default=None,
    metavar="S",
    help=f"Time step (default: {DEFAULT_DT:g} s, or the wave period (--wave-period, --tp) "
    f"/ {STEPS_PER_PERIOD} when shorter: tank-scale waves). A step with fewer than "
    f"{STEPS_PER_SHORTEST_PERIOD} steps per period of the shortest wave component is "
    "refused; a run whose energy balance misses by more than "
    f"{ENERGY_TOLERANCE:.0%} fails (exit status 3).",
)
@click.option(
    "--seed",
    type=click.IntRange(0, 2**63 - 1),
    default=None,
    help="Random phases (a run is repeatable); without it a seed is drawn, printed and "
    "recorded in the run (attribute seed).",
)
@click.option(
    "--regular", is_flag=True, help="Regular waves instead (--wave-period, --wave-amplitude)."
)
@click.option(
    "--wave-elevation",
    "wave_record",
    type=click.Path(exists=True, dir_okay=False),
    default=None,
    metavar="FILE",
    help="A record of the wave elevation at the origin instead of a sea state: CSV with "
    "units in the header ('time [s], wave elevation [m]') or a run.nc, travelling towards "
    "--heading; the force is the causal excitation model's (fit-excitation), from rest.",
)
@click.option(
    "--wave-period",
    type=positive("s"),
    default=None,
    metavar="S",
    help="With --regular: the wave's period, s (the encounter period differs at --speed).",
)
@click.option(
    "--wave-amplitude",
    type=non_negative("m"),
    default=1.0,
    show_default=True,
    metavar="M",
    help="With --regular: the wave's amplitude (half its height), m.",
)
@viscous_damping_option
@click.option(
    "--quadratic-damping",
    "quadratic_damping",
    type=(str, non_negative()),
    multiple=True,
    metavar="DOF VALUE",
    help="Quadratic viscous damping b2 |v| v on a DOF, e.g. --quadratic-damping Roll 2e10 "
    "(kg m^2/rad for roll, kg/m for translations; repeatable; the run then uses the "
    "Runge-Kutta path).",
)
@click.option(
    "--start",
    type=click.Choice(["steady", "rest"]),
    default="steady",
    show_default=True,
    help="steady: start on the stationary solution (no transient); rest: from rest.",
)
@click.option(
    "--accurate",
    is_flag=True,
    help="Fit the radiation model for closer agreement with the data's RAOs: within "
    "0.2 % of each DOF's peak instead of 1 % (a few more states; where the data "
    "cannot give that, never further from the RAOs than the default).",
)
@speed_option(
    "Forward speed of DATA. The waves are met at the encounter frequencies; when DATA "
    "hold zero speed too, the speed terms (U D1, U G1 + U^2 G2, Hjulstad) are kept "
    "apart from the memory, which is K0 + U K1 + U^2 K2 derived from the zero-speed fit "
    "or a fit at speed, whichever meets the data's RAOs at speed better (printed; "
    "cummins.radiation.speed.vessel_at_speed)."
)
@click.option(
    "--dof",
    "dofs",
    multiple=True,
    callback=unique_values,
    metavar="NAME",
    help="Simulate only these DOFs (repeatable), e.g. --dof Heave --dof Pitch: the vertical "
    "plane of a ship in head or following seas; the others are held at zero.",
)
@system_options
@click.option(
    "--soft-springs",
    type=positive("s"),
    default=None,
    metavar="S",
    help="At speed: springs of this period in surge, sway and yaw (with 0.7 of critical "
    "damping), cancelling the yaw Munk moment first: what the autopilot does; without them "
    "a free 6-DOF ship at speed is unstable and refused.",
)
@click.option(
    "--plot",
    "plot_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="PNGs: time series and response spectra against the frequency domain.",
)
@second_order_option()
@sum_frequency_option
@keep_suspect_option
@allow_other_data_option
@force_option()
@option_rules(
    needs={
        "wave_period": "regular",
        "wave_amplitude": "regular",
        "directions": "spreading",
        "gamma": ("spectrum", "jonswap"),
        "soft_springs": "speed",
    },
    excludes=tuple(
        ("regular", name)
        for name in ("hs", "tp", "spectrum", "gamma", "spreading", "components", "seed")
    ),
)
@reports_errors
def simulate_command(
    path,
    format_,
    rho,
    g,
    ulen,
    output,
    hs,
    tp,
    spectrum,
    gamma,
    heading,
    spreading,
    directions,
    components,
    duration,
    dt,
    seed,
    regular,
    wave_record,
    wave_period,
    wave_amplitude,
    viscous_damping,
    quadratic_damping,
    start,
    accurate,
    speed,
    dofs,
    soft_springs,
    system_options,
    plot_dir,
    second_order,
    sum_frequency,
    keep_suspect,
    allow_other_data,
    force,
):
    """Simulate the vessel in waves: the Cummins equation with a state-space fluid memory.

    \b
    DATA is a hydrodynamic database (any format cummins reads; the radiation model is
    fitted on the fly, passive) or MODEL a model file from `cummins fit` (its data are
    read from the file it was fitted to; data that differ from those the model records —
    DOFs, rho, g, frequencies, A(w), B(w) — are refused unless --allow-other-data). The
    excitation is the first-order wave force
    of the database; the run holds motion and velocity (time, dof) about the database's
    reference point and axes, and the wave elevation at the origin. A statically
    unstable body (a negative eigenvalue of the restoring with moorings and
    --external-stiffness, named by its DOF: the check `cummins rao` warns with) is
    refused.

    \b
    Several bodies: --joint joins them (or a body to the ground), --pto puts a linear
    damper (and spring) on a relative motion; the run then holds each PTO's relative
    displacement, velocity, force and absorbed power (pto_*), and the mean power is
    printed. --no-body-coupling leaves out the radiation coupling between bodies, as
    WEC-Sim does by default (docs/wec.md).

    \b
    Examples:
      cummins simulate tanker.1 --hs 4 --tp 10 --heading 150 --duration 1800 -o run.nc
      cummins simulate tanker.1 --regular --wave-period 9 --wave-amplitude 1 -o reg.nc
      cummins simulate s175.mat --speed 10.29 --dof Heave --dof Pitch --hs 4 --tp 10 -o s.nc
      cummins simulate rm3.out --rho 1000 --mass 725833 --mass 886687 ... --joint
          translational body2 ground --joint translational body1 body2 --pto-damping 1.2e6
          --no-body-coupling --regular --wave-period 8 --wave-amplitude 1.25 -o rm3.nc
      cummins simulate marin_semi.1 --dof Surge --mass 1.4e7 --external-stiffness Surge
        Surge 9e4 --external-damping Surge Surge 5.7e5 --second-order full --hs 6 --tp 10
        -o slow_drift.nc

    \b
    --second-order adds the second-order force of the same sea (docs/second_order.md);
    data without first-order excitation (the OC4 semi's WAMIT files) then run with the
    second-order force alone.
    """
    from cummins.seakeeping import waves as wv
    from cummins.timedomain.simulate import quadratic_damping_force, simulate_waves
    from cummins.vessel import vessel_from_hydrodb

    if wave_record:
        if regular or hs is not None or tp is not None or speed:
            raise click.UsageError("--wave-elevation replaces --hs/--tp/--regular (zero speed)")
        if second_order != "none":
            raise click.UsageError(
                "--second-order needs the sea as wave components (--hs/--tp or --regular); "
                "a --wave-elevation record drives the first-order force only: leave "
                "--second-order out, or give the sea by --hs/--tp"
            )
    elif regular:
        if wave_period is None:
            raise click.UsageError("--regular needs --wave-period")
    elif hs is None or tp is None:
        raise click.UsageError("irregular waves need --hs and --tp (or use --regular)")
    if dt is None:
        dt = default_time_step(wave_period if regular else tp)
        if dt < DEFAULT_DT:
            console.print(f"time step {dt:.4g} s: the wave period / {STEPS_PER_PERIOD} (--dt)")
    prepare_outputs(output, force=force, folders=[plot_dir])
    # the run's size before any work: the states are at least the DOFs' positions and
    # velocities (the fluid memory adds its own, checked again once it is fitted)
    check_simulation_size(duration, dt, 12, 6, option="--duration")
    system = system_from_options(system_options, dofs)
    model, data_path = model_and_data(path)
    data = read_hydrodb(data_path, format_, rho, g, ulen)
    if system is None and speed is None:
        from cummins.hydrodb import bodies

        if len(bodies(data)) > 1:  # through the system, so that the body coupling is stated
            from cummins.mechanics import MechanicalSystem

            system = MechanicalSystem(dofs=tuple(dofs) or None)
    if dofs:
        from cummins.hydrodb import select_dofs

        check_dof_selection(data, dofs)
        if system is None:  # with joints the selection is part of the system
            data = select_dofs(data, list(dofs))
    ds = select_speed(data, speed)
    from cummins.vessel import missing_data_message

    missing_data_message(ds, ("inertia_matrix", "hydrostatic_stiffness"), "a simulation")
    at_speed = (
        model is None
        and speed
        and "forward_speed" in data.dims
        and bool(np.any(np.abs(data.forward_speed.values) <= 1e-3))
    )
    check_simulation_size(
        duration, dt, 2 * ds.sizes["influenced_dof"], ds.sizes["influenced_dof"], "--duration"
    )
    if accurate and at_speed:
        raise click.UsageError(
            "--accurate tightens the motion target of the zero-speed fit; at --speed the "
            "memory is built with the speed terms kept apart (vessel_at_speed) and judged "
            "by its RAOs at speed, printed after the fit: leave --accurate out"
        )
    if soft_springs is not None and not at_speed:
        raise click.UsageError(
            "--soft-springs applies to a ship at --speed U > 0 whose data hold zero speed too"
        )
    labels = [str(d) for d in ds.influenced_dof.values]
    if system is not None:
        if at_speed:
            raise click.UsageError(
                "joints, PTOs and --no-body-coupling are for bodies at zero speed: leave "
                "--speed out"
            )
        from cummins.cli.system_options import print_system
        from cummins.mechanics import assemble

        assembly = assemble(ds, system)
        labels = list(assembly.dofs)
        print_system(assembly)
    b_v = viscous_damping_values(viscous_damping, labels)
    b_q = viscous_damping_values(quadratic_damping, labels, "--quadratic-damping")
    if heading is None:
        heading = 180.0
        if "wave_direction" in ds.dims and ds.sizes["wave_direction"] == 1:
            heading = float(np.degrees(ds.wave_direction.values[0]))
            if abs(heading - 180.0) > 1e-9:
                console.print(f"heading {heading:g}°: the data's only one (--heading)")
    direction = np.radians(heading)
    sea = None
    if wave_record:
        title = f"wave elevation record {wave_record}"
    elif regular:
        sea = wv.regular_wave(wave_amplitude, wave_period, direction)
        title = f"regular waves, amplitude {wave_amplitude:g} m, period {wave_period:g} s"
    else:
        shape = wv.wave_spectrum(spectrum, hs, tp, gamma=gamma if spectrum == "jonswap" else None)
        sea = wv.irregular_waves(
            shape,
            duration=duration,
            data=ds,  # components within the data's frequencies (a note says so)
            n_components=components,
            direction=direction,
            spreading=spreading,
            n_directions=directions if spreading else 1,
            seed=seed,
        )
        title = f"{spectrum}, Hs {hs:g} m, Tp {tp:g} s, {len(sea)} components"
        if seed is None:
            console.print(f"seed {sea.seed} drawn (repeat this sea with --seed {sea.seed})")
    if sea is not None:  # before the radiation model is fitted
        _check_time_step(dt, ds, sea)
    from cummins.radiation.fit import MOTION_ACCURACY

    fit_options = MOTION_ACCURACY if accurate and model is None else {}
    with console.status("fitting the radiation model" if model is None else "preparing"):
        if at_speed:
            from cummins.radiation.speed import vessel_at_speed

            vessel = vessel_at_speed(
                data, speed, soft_springs=soft_springs, viscous_damping=b_v, **fit_options
            )
        else:
            vessel = vessel_from_hydrodb(
                ds,
                model,
                viscous_damping=b_v,
                system=system,
                allow_other_data=allow_other_data,
                **fit_options,
            )
    from cummins.cli.failed_model import warn_failed_model

    inherited = warn_failed_model(
        vessel.radiation.attrs, path, "fitted" if model is None else "model"
    )
    if at_speed:
        _print_speed_check(vessel.attrs)
    if sea is not None and spreading:
        _check_spread_directions(ds, vessel, sea, heading, spreading, directions)
    nonlinear = quadratic_damping_force(vessel.dofs, b_q) if b_q else None
    if sea is not None and nonlinear is not None:  # the Runge-Kutta path's stability
        _check_time_step(dt, ds, sea, vessel.state_space()[0])
    if wave_record:
        from cummins.cli.wave_record import run_wave_record

        run, title = run_wave_record(vessel, ds, wave_record, heading, nonlinear)
    else:
        second = build_second_order(
            ds, sea, second_order, sum_frequency=sum_frequency, keep_suspect=keep_suspect
        )
        first_order = "excitation_force" in ds or second is None
        if not first_order:
            console.print("note: the data have no first-order excitation: second-order force only")
        if second is not None and second_order != "mean" and sea is not None:
            _note_lightly_damped(vessel, sea, b_q)
        with progress_bar() as bar:
            task = bar.add_task(
                f"simulating {duration:g} s, {title}, heading {heading:g}°", total=1.0
            )
            with warnings.catch_warnings():  # a failed balance is printed as a failure
                warnings.filterwarnings("ignore", "the energy balance misses")
                run = simulate_waves(
                    vessel,
                    ds,
                    sea,
                    duration=duration,
                    dt=dt,
                    initial=start,
                    nonlinear_force=nonlinear,
                    progress=lambda fraction: bar.update(task, completed=fraction),
                    second_order=second,
                    first_order=first_order,
                )
    if sea is not None and sea.seed is not None:
        run.attrs["seed"] = int(sea.seed)  # an int64: HDF5 stores it; --seed repeats the run
    if speed:
        title += f", {speed:g} m/s"
    title += f", heading {heading:g}°"
    run.attrs.update(
        {
            "heading_deg": heading,
            "sea": title,
            "source_file": str(ds.attrs.get("source_file", "")),
            "radiation_model_order": vessel.radiation.total_order,
            **inherited,
            **{k: vessel.attrs[k] for k in SPEED_CHECK_ATTRS if k in vessel.attrs},
            **{f"quadratic_damping_{d}": b for d, b in (b_q or {}).items()},
        }
    )
    _summary(run, regular=regular)
    if vessel.ptos:
        from cummins.cli.system_options import print_pto_run

        left_out = [
            option
            for option, given in (
                ("--quadratic-damping", bool(b_q)),
                ("--second-order", second_order != "none" and not wave_record),
            )
            if given
        ]
        reference, record = print_pto_run(
            run, vessel, sea, ds, system, b_v, regular=regular, left_out=left_out
        )
        # the report shows them beside the run's: the solution for the run's wave
        # components, and the same solution on the run's own record of them
        for name, power, what in (
            ("", reference, "for the run's wave components"),
            ("_record", record, "over the run's own record of its wave components"),
        ):
            if power is not None:
                run[f"pto_mean_power_frequency_domain{name}"] = (
                    "pto",
                    np.asarray(power, dtype=float),
                    {
                        "units": "W",
                        "long_name": "mean absorbed power of the linear frequency-domain "
                        f"solution {what}",
                        "left_out": ", ".join(left_out) or "none",
                    },
                )
    from cummins.io.netcdf import save_netcdf

    save_netcdf(run, output)
    console.print(f"wrote {output}")
    if plot_dir:
        from cummins.cli.pipeline import write_simulation_plots

        waves = sea if sea is not None else wv.regular_wave(0.0, 10.0, direction)  # no spectra
        for file in write_simulation_plots(run, vessel, ds, waves, Path(plot_dir), force=force):
            console.print(f"wrote {file}")
    failure = run.attrs.get("failure")
    if failure:
        console.print(f"[bold red]failure:[/bold red] {escape(failure)}", highlight=False)
        sys.exit(SIMULATION_FAILED)


#: What the run file records of a vessel at speed (:func:`_print_speed_check`).
SPEED_CHECK_ATTRS = ("speed_memory", "speed_motion_error", "speed_motion_error_by_dof")


def _print_speed_check(attrs) -> None:
    """The RAO error of the vessel at speed against the data's own frequency domain
    (:func:`cummins.radiation.speed.checks.speed_motion_error`), one line."""
    from cummins.radiation.speed.checks import SPEED_MOTION_TOL

    error = attrs.get("speed_motion_error")
    if error is None:
        return
    memory = attrs.get("speed_memory")
    line = (
        "RAOs at speed of the time-domain vessel"
        + (f" (memory {memory})" if memory else "")
        + f" against the data's frequency domain: "
        f"{attrs.get('speed_motion_error_by_dof', '')} of each peak"
    )
    if error > SPEED_MOTION_TOL:
        line += f" (above {100 * SPEED_MOTION_TOL:g} %: statistics may differ by a few %)"
        console.print(f"[yellow]note:[/] {escape(line)}", highlight=False)
    else:
        console.print(escape(line), highlight=False)


#: The exit status of a run whose energy balance fails (as a failed fit's).
SIMULATION_FAILED = 3


def _check_spread_directions(ds, vessel, sea, heading, spreading, directions) -> None:
    """Refuse a short-crested sea whose directions leave the data's headings, naming
    --spreading: the heading interpolation's error would ask for another --heading, which
    the user gave (the directions of the cos-2s bins beside it are what lie outside). The
    data are those of the DOFs the vessel moves (as ``simulate_waves`` takes them)."""
    from cummins.errors import ArgumentError, HydroDataError
    from cummins.hydrodb import select_dofs
    from cummins.seakeeping.excitation import excitation_transfer

    if "excitation_force" not in ds:
        return
    if [str(d) for d in ds.influenced_dof.values] != list(vessel.dofs):
        ds = select_dofs(ds, list(vessel.dofs))
    unique = np.unique(sea.direction)
    try:
        excitation_transfer(ds, np.full(unique.size, ds.omega.values[0]), unique)
    except HydroDataError as exc:
        offset = np.degrees(np.angle(np.exp(1j * (unique - np.radians(heading)))))
        gap = getattr(exc, "message", str(exc))  # not its hint: another --heading
        raise ArgumentError(
            f"--spreading {spreading:g}: the spread sea's {directions} directions reach "
            f"{heading + offset.min():.4g}° to {heading + offset.max():.4g}° about --heading "
            f"{heading:g}°, beyond the data's headings ({gap})",
            hint="give a larger s (a narrower spread), or data computed for more headings",
        ) from None


def _note_lightly_damped(vessel, sea, quadratic=None) -> None:
    """Name the modes below the sea's peak frequency that the slowly varying force drives
    at resonance with less than 1 % of critical damping (:mod:`cummins.timedomain.modes`);
    those of a DOF with quadratic damping given (``quadratic``), which the linear model's
    eigenvalues do not hold, are left out."""
    from cummins.timedomain.modes import lightly_damped_modes

    if np.isfinite(sea.tp) and sea.tp > 0:
        peak = 2 * np.pi / float(sea.tp)
    else:  # regular waves, a record's components: the largest
        peak = float(np.asarray(sea.omega)[int(np.argmax(np.abs(sea.amplitude)))])
    modes = [m for m in lightly_damped_modes(vessel, below=peak) if m.dof not in (quadratic or {})]
    if not modes:
        return
    listed = ", ".join(
        f"{mode.dof} {mode.period:.3g} s ({100 * mode.zeta:.2g} % of critical)" for mode in modes
    )
    console.print(
        f"[yellow]note:[/] {escape(f'lightly damped modes below the sea peak: {listed}')}: the "
        "slowly varying force drives them at resonance, and only the damping given limits "
        "their response (radiation damping vanishes at low frequency): give the moorings' "
        "and the viscous damping (--external-damping, --viscous-damping, "
        "--quadratic-damping)",
        highlight=False,
    )


def _check_time_step(dt, ds, sea, state_matrix=None) -> None:
    """Refuse a --dt too long for the sea's components as the vessel meets them
    (:func:`cummins.timedomain.time_step.check_time_step`)."""
    from cummins.seakeeping.excitation import encounter_frequencies
    from cummins.timedomain.time_step import check_time_step

    omega_e = encounter_frequencies(ds, sea.omega, sea.direction)
    check_time_step(dt, omega_e, state_matrix, option="--dt")


def _summary(run, regular: bool = False) -> None:
    """The run's motion statistics (:func:`cummins.timedomain.statistics.motion_statistics`,
    rotations in degrees) and its energy balance."""
    from rich.table import Table

    from cummins.timedomain.statistics import motion_statistics

    table = Table(title=f"{run.attrs.get('sea', '')}: {run.time.values[-1]:g} s")
    first = "amplitude" if regular else "significant amplitude (2σ)"
    mean = "second_order" in run.attrs  # the mean drift offsets the body
    columns = ("DOF", *(("mean",) if mean else ()), first, "max |ξ|", "unit")
    for column in columns:
        table.add_column(column, justify="right")
    rows = motion_statistics(run, regular)
    for row in rows:
        table.add_row(
            row.dof,
            *((f"{row.mean:.4g}",) if mean else ()),
            f"{row.amplitude:.4g}",
            f"{row.maximum:.4g}",
            row.unit,
        )
    console.print(table)
    _say_large_rotations(rows)
    pto = f", PTOs {run.attrs['energy_pto']:.4g} J" if run.attrs.get("energy_pto") else ""
    work = run.attrs.get("energy_nonlinear")
    nonlinear = f", nonlinear forces {work:.4g} J" if work else ""
    console.print(
        f"energy: in {run.attrs['energy_input']:.4g} J{nonlinear}, radiated "
        f"{run.attrs['energy_radiated']:.4g} J, viscous {run.attrs['energy_viscous']:.4g} J"
        f"{pto}, balance error "
        f"{run.attrs['energy_relative_residual']:.2g}"
    )


#: Degrees: a rotation beyond which the linear model's small-motion assumption is said to
#: be far from holding (sin θ ≈ θ to 5 % at 30°).
LARGE_ROTATION = 30.0


def _say_large_rotations(rows) -> None:
    """One note when a rotation of the run exceeds :data:`LARGE_ROTATION`: the equation
    of motion, the restoring and the joints are linearised about the mean position
    (small motions), and potential flow has no viscous damping."""
    large = [r for r in rows if r.unit == "deg" and r.maximum > LARGE_ROTATION]
    if not large:
        return
    worst = max(large, key=lambda r: r.maximum)
    console.print(
        f"[yellow]note:[/] {escape(worst.dof)} turns by up to {worst.maximum:.3g}° "
        f"({np.radians(worst.maximum):.3g} rad): the model is linear (small motions: the "
        "restoring, the wave loads and the joints about the mean position) and holds no "
        "viscous damping unless given (--viscous-damping, --quadratic-damping); take "
        "motions this large as a resonance to damp, not a prediction",
        highlight=False,
    )
