"""``cummins demo``: the whole pipeline on a bundled real vessel.

The demo runs each stage cummins has on the MSS tanker (WAMIT output bundled with the
package, MIT licence) and writes what each stage produces into one folder. It grows
with the project: every new stage adds its step here.
"""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import click

from cummins.cli.common import console, force_option, prepare_outputs, reports_errors
from cummins.cli.option_rules import Command
from cummins.errors import check_writable


@dataclass(frozen=True)
class DemoStep:
    """One thing the demo did: a short title, what came out, the files it wrote, and
    whether the result reached its target (the demo marks a step that did not with "!",
    never with a check mark)."""

    title: str
    detail: str
    files: tuple[Path, ...] = ()
    ok: bool = True


#: Files the demo writes, relative to its output folder.
DEMO_FILES = (
    "tanker.nc",
    "tanker_mss.mat",
    "check.txt",
    "check.json",
    "added_mass_damping.png",
    "excitation.png",
    "kernel.nc",
    "retardation.png",
    "retardation_couplings.png",
    "reconstruction.png",
    "added_mass_inf.png",
    "tanker_model.nc",
    "fit.json",
    "tanker.ss",
    "tankerABC.mat",
    "tanker_reduced.nc",
    "run.nc",
    "time_series.png",
    "response_spectra.png",
    "lf_model.nc",
    "lf_model.png",
    "dp/run.nc",
    "dp/pose.png",
    "dp/wave_and_radiation_forces.png",
    "dp/loads.png",
    "dp/watch_circle.png",
)

#: Folder (inside the output folder) of the per-coupling fit plots, ``fit_<coupling>.png``.
FIT_PLOTS = "fit"


def run_demo(
    outdir: str | os.PathLike[str],
    *,
    force: bool = False,
    progress: Callable[[str], None] | None = None,
) -> list[DemoStep]:
    """Run the demo pipeline and write its outputs into ``outdir``.

    Parameters
    ----------
    outdir
        Folder to write to (created if needed).
    force
        Overwrite files of an earlier demo run; without it, existing files are an error.
    progress
        Called with a short message as each step starts (the CLI shows it).

    Returns
    -------
    list of DemoStep
        What was done, in order.
    """
    import numpy as np

    from cummins import demo_files
    from cummins.check import check
    from cummins.cli.pipeline import kernel_stage, write_kernel_plots
    from cummins.hydrodb import change_axes, describe, move_reference_point
    from cummins.io import read, write
    from cummins.plots import plot_added_mass_damping, plot_excitation, save_figure
    from cummins.radiation.infinite_frequency import added_mass_inf

    out = Path(outdir)
    for name in DEMO_FILES:
        check_writable(out / name, force)
    for earlier in (out / FIT_PLOTS).glob("*.png"):
        check_writable(earlier, force)
    out.mkdir(parents=True, exist_ok=True)
    say = progress or (lambda message: None)
    steps: list[DemoStep] = []

    say("reading the bundled tanker (WAMIT .1/.3/.hst/.frc/.out)")
    ds = read(demo_files() / "tanker.1")
    info = describe(ds)
    steps.append(
        DemoStep(
            "read",
            f"WAMIT tanker: {info['n_omega']} frequencies "
            f"{info['omega_min_rad_s']:.3g}–{info['omega_max_rad_s']:.3g} rad/s, "
            f"{len(info['wave_directions_deg'])} headings, ρ = {info['rho_kg_m3']:g} kg/m³, "
            f"g = {info['g_m_s2']:g} m/s², mass {info.get('mass_kg', float('nan')):.4g} kg",
        )
    )

    say("checking the data")
    report = check(ds)
    (out / "check.txt").write_text(report.to_text() + "\n", encoding="utf-8")
    (out / "check.json").write_text(report.to_json() + "\n", encoding="utf-8")
    counts = {s: sum(f.severity == s for f in report) for s in ("warning", "error")}
    steps.append(
        DemoStep(
            "check",
            f"{counts['warning']} warnings, {counts['error']} errors "
            "(negative damping at the irregular frequencies near 3.9 rad/s is expected)",
            (out / "check.txt", out / "check.json"),
        )
    )

    say("writing the canonical NetCDF and an MSS vessel struct")
    write(ds, out / "tanker.nc", force=force)
    fossen = move_reference_point(change_axes(ds, "z-down"), [0.0, 0.0, 0.0])
    write(fossen, out / "tanker_mss.mat", force=force)
    steps.append(
        DemoStep(
            "convert",
            "canonical NetCDF (Capytaine layout) and MSS .mat (Fossen axes, about the origin)",
            (out / "tanker.nc", out / "tanker_mss.mat"),
        )
    )

    say("plotting added mass, damping and excitation")
    figures = (
        save_figure(plot_added_mass_damping(ds), out / "added_mass_damping.png", force=force),
        save_figure(
            plot_excitation(ds, headings_deg=[0, 45, 90, 135, 180]),
            out / "excitation.png",
            force=force,
        ),
    )
    steps.append(DemoStep("plot", "A(ω), B(ω) per DOF; excitation magnitude and phase", figures))

    say("retardation functions and A∞ (irregular frequencies removed first)")
    suspects: list[str] = []
    result, repaired = kernel_stage(
        ds, remove_suspect=True, above_first=True, truncate="subtract", say=suspects.append
    )
    result.to_netcdf(out / "kernel.nc", engine="h5netcdf")
    estimate = np.diag(added_mass_inf(repaired.drop_vars("added_mass_inf")).values)
    deviation = np.abs(estimate / np.diag(repaired.added_mass_inf.values) - 1).max()
    plots = write_kernel_plots(result, repaired, out, force=force)
    steps.append(
        DemoStep(
            "kernel",
            f"removed {ds.sizes['omega'] - repaired.sizes['omega']} frequencies above "
            f"{repaired.omega.values[-1]:.3g} rad/s (irregular frequencies); K(t) of all "
            f"couplings to {result.attrs['t_max']:.3g} s; A∞ estimated from A(ω), B(ω) "
            f"alone is within {deviation:.1%} of WAMIT's ω = ∞ row on the diagonal",
            (out / "kernel.nc", *plots),
        )
    )

    say("fitting state-space models of the fluid memory (every significant coupling)")
    fit_step, model = _fit_step(ds, out, force)
    steps.append(fit_step)

    say("the fit reduced to the fewest states that keep the motions within 1 %")
    steps.append(_reduce_step(ds, model, out, force))

    say("the tanker in a sea state, time domain, against the frequency domain")
    steps.append(_simulate_step(ds, model, out, force))

    say("the low-frequency manoeuvring model (Ross, Perez & Fossen, 2006)")
    steps.append(_lf_step(ds, out, force))

    say("dynamic positioning of the S-175 with a crane load, 5 minutes (Smogeli et al., 2004)")
    steps.append(_dp_step(out, force))

    (out / "demo_summary.json").write_text(
        json.dumps(
            [
                {"step": s.title, "detail": s.detail, "files": [str(f) for f in s.files]}
                for s in steps
            ],
            indent=2,
        )
        + "\n",
        encoding="utf-8",
    )
    return steps


def _fit_step(ds, out: Path, force: bool) -> tuple[DemoStep, object]:
    """Identification of every coupling, the model file, its exports and plots."""
    import time

    from cummins.cli.fit import fit_summary
    from cummins.cli.pipeline import write_fit_plots, write_model_mss_abc
    from cummins.io.openfast import write_openfast_ss
    from cummins.radiation.fit import fit_radiation

    start = time.perf_counter()
    model = fit_radiation(ds)
    elapsed = time.perf_counter() - start
    model.save(out / "tanker_model.nc", force=force)
    summary = fit_summary(model, elapsed)
    (out / "fit.json").write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
    write_openfast_ss(model, out / "tanker.ss", force=force)
    write_model_mss_abc(model, ds, out / "tankerABC.mat", force=force)
    (out / FIT_PLOTS).mkdir(exist_ok=True)
    plots = write_fit_plots(model, ds, out / FIT_PLOTS, force=force)
    diagonal = [k.metrics for k in model.modelled if k.influenced == k.radiating]
    fitted = sum(k.influenced <= k.radiating for k in model.modelled)
    failures = model.attrs.get("failures", [])
    step = DemoStep(
        "fit",
        f"{fitted} couplings fitted in {elapsed:.2f} s, total order {model.total_order}, "
        f"{'every model stable' if summary['mimo_stable'] else 'UNSTABLE MODELS'}, "
        f"diagonal models {'' if all(m['passive'] for m in diagonal) else 'NOT '}positive "
        "real, smallest diagonal R² of A "
        f"{min(m['r2_added_mass'] for m in diagonal):.4f} and of B "
        f"{min(m['r2_damping'] for m in diagonal):.4f} "
        f"({len(model.attrs['excluded_frequencies'])} irregular frequencies left out); "
        "exported for OpenFAST (.ss) and MSS (ABC .mat)"
        + "".join(f"; failure: {f}" for f in failures),
        (
            out / "tanker_model.nc",
            out / "fit.json",
            out / "tanker.ss",
            out / "tankerABC.mat",
            *plots,
        ),
        ok=bool(summary["mimo_stable"] and summary["mimo_passive"] and not failures),
    )
    return step, model


def _reduce_step(ds, model, out: Path, force: bool) -> DemoStep:
    """The fit reduced to the fewest states whose motion RAOs stay within 1 % of the
    data's (``cummins reduce model.nc --data tanker.1 --motion-tol 0.01``), passive."""
    from cummins.cli.pipeline import reduce_stage

    tolerance = 0.01
    reduced, _, _ = reduce_stage(model, motion_tol=tolerance, data=ds)
    reduced.save(out / "tanker_reduced.nc", force=force)
    error = float(reduced.attrs["motion_error"])
    failures = reduced.attrs.get("failures", [])
    passive = bool(reduced.attrs.get("mimo_passive"))
    ok = passive and error <= tolerance and not failures
    return DemoStep(
        "reduce",
        f"the fit reduced by balanced truncation from {model.total_order} to "
        f"{reduced.total_order} states, passive: {passive}, motion RAOs within "
        f"{error:.2%} of the data's (tolerance {tolerance:.0%}; the unreduced fit "
        f"{float(reduced.attrs['motion_error_unreduced']):.2%})"
        + "".join(f"; failure: {f}" for f in failures),
        (out / "tanker_reduced.nc",),
        ok=ok,
    )


def _simulate_step(ds, model, out: Path, force: bool) -> DemoStep:
    """Half an hour in a JONSWAP sea from 150°, checked against the frequency domain."""
    import functools

    import numpy as np

    from cummins.cli.pipeline import write_simulation_plots
    from cummins.io.netcdf import save_netcdf
    from cummins.seakeeping.waves import irregular_waves, jonswap
    from cummins.timedomain.simulate import component_motions, simulate_waves
    from cummins.vessel import vessel_from_hydrodb

    vessel = vessel_from_hydrodb(ds, model, viscous_damping=[1e6, 1e6, 0, 0, 0, 1e10])
    sea = irregular_waves(
        functools.partial(jonswap, hs=4.0, tp=10.0),
        duration=1800.0,
        n_components=200,
        direction=np.radians(150.0),
        seed=1,
    )
    run = simulate_waves(vessel, ds, sea, duration=1800.0, dt=0.05)
    run.attrs["sea"] = "JONSWAP Hs 4 m, Tp 10 s, waves from 150°, 200 components"
    save_netcdf(run, out / "run.nc")
    plots = write_simulation_plots(run, vessel, ds, sea, out, force=force)
    # significant amplitudes: time domain against the frequency domain of the same model
    x = component_motions(vessel, ds, sea)
    fd = 2 * np.sqrt(0.5 * (np.abs(x) ** 2).sum(axis=0))
    td = 2 * run.motion.values.std(axis=0)
    worst = float(np.max(np.abs(td / fd - 1)[2:5]))
    return DemoStep(
        "simulate",
        f"30 min in a JONSWAP sea (Hs 4 m, Tp 10 s, from 150°): heave significant amplitude "
        f"{td[2]:.3g} m, roll {np.degrees(td[3]):.3g}°, pitch {np.degrees(td[4]):.3g}°; "
        f"heave, roll, pitch within {worst:.1%} of the frequency domain"
        + ("" if worst <= SIMULATION_AGREEMENT else f" (more than {SIMULATION_AGREEMENT:.0%})"),
        (out / "run.nc", *plots),
        ok=worst <= SIMULATION_AGREEMENT,
    )


#: The statistical scatter of a 30-minute record's significant amplitudes about the
#: frequency domain's (a few per cent): beyond it the demo's simulation step is marked.
SIMULATION_AGREEMENT = 0.10


def _lf_step(ds, out: Path, force: bool) -> DemoStep:
    """Constant coefficients at ω = 0 (surge, sway, yaw) and at ω₀ (heave, roll, pitch)."""
    from cummins.io.netcdf import save_netcdf
    from cummins.plots import plot_lf_model, save_figure
    from cummins.timedomain.lfmodel import lf_model_from_frequency_data

    lf = lf_model_from_frequency_data(ds)
    save_netcdf(lf.to_dataset(), out / "lf_model.nc")
    figure = save_figure(plot_lf_model(ds, lf), out / "lf_model.png", force=force)
    w0 = {d: lf.frequencies[lf.index(d)] for d in ("Heave", "Roll", "Pitch")}
    return DemoStep(
        "lf-model",
        "manoeuvring model: surge, sway, yaw at ω = 0 (A(0) from WAMIT's ω = 0 row), "
        + ", ".join(f"{d} at ω₀ = {w:.3g} rad/s" for d, w in w0.items())
        + " (eq. 24 iterated)",
        (out / "lf_model.nc", figure),
    )


def _dp_step(out: Path, force: bool) -> DemoStep:
    """The S-175 on DP, a 1000 kN crane load at t = 100 s (bundled MSS data)."""
    from cummins.cli.dp_scenario import run_scenario, write_scenario_plots
    from cummins.io.netcdf import save_netcdf

    folder = out / "dp"
    folder.mkdir(exist_ok=True)
    scenario = run_scenario(duration=300.0)
    save_netcdf(scenario.run, folder / "run.nc")
    plots = write_scenario_plots(scenario, folder, force=force)
    a = scenario.run.attrs
    return DemoStep(
        "dp",
        f"nonlinear 6-DOF model, Hs 4 m from 45° off the bow: watch circle "
        f"{a['check_watch_circle_m']:.2f} m; the crane load heels the ship by "
        f"{a['check_mean_roll_after_deg'] - a['check_mean_roll_before_deg']:.2f}° "
        f"(static heel {a['check_static_heel_deg']:.2f}°)",
        (folder / "run.nc", *plots),
    )


@click.command(name="demo", cls=Command)
@click.option(
    "-o",
    "--output",
    "outdir",
    type=click.Path(file_okay=False),
    default="cummins-demo",
    show_default=True,
    help="Folder to write the results to.",
)
@force_option("Overwrite the files of an earlier demo run.")
@reports_errors
def demo_command(outdir, force):
    """Run the pipeline on a bundled real vessel (the MSS tanker, WAMIT output).

    Reads the WAMIT files, checks them, writes canonical NetCDF and an MSS .mat, plots
    added mass, damping and excitation, computes K(t), fits, reduces and exports the
    radiation model, simulates the tanker in a sea against the frequency domain, derives
    its manoeuvring model and runs a DP case, all into the output folder. Each step says
    whether it reached its target; the exit status is 3 when one did not.
    """
    prepare_outputs(force=force, folders=[outdir])
    with console.status("starting") as status:
        steps = run_demo(outdir, force=force, progress=lambda m: status.update(m))
    for step in steps:
        mark = "[bold green]✓[/]" if step.ok else "[bold yellow]![/]"
        console.print(f"{mark} [bold]{step.title}[/]: {step.detail}")
        for f in step.files:
            console.print(f"    {f}")
    missed = [step.title for step in steps if not step.ok]
    console.print(f"All results in {Path(outdir).resolve()}")
    if missed:
        console.print(
            f"[bold yellow]![/] {len(missed)} step(s) did not reach their targets: "
            + ", ".join(missed)
        )
        sys.exit(DEMO_MISSED)


#: Exit status of a demo with a step that missed its target (as ``fit`` and ``reduce``).
DEMO_MISSED = 3
