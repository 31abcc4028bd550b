"""``cummins rao``: coupled motion RAOs of a vessel from its hydrodynamic database."""

from __future__ import annotations

from pathlib import Path

import click
import numpy as np
from rich.table import Table

from cummins.cli.common import (
    check_dof_selection,
    console,
    force_option,
    headings_list,
    non_negative,
    positive,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_speed,
    speed_option,
    stage_progress,
    viscous_damping_option,
    viscous_damping_values,
)
from cummins.cli.option_rules import Command, unique_values
from cummins.cli.system_options import (
    prepare_system_args,
    system_from_options,
    system_options,
)
from cummins.display import peak_index, power_text
from cummins.dofs import bodies, is_rotation

#: Options that take a list of numbers: ``--headings 0 45 90`` (as well as repeated).
_LIST_OPTIONS = ("--headings",)


def _is_number_list(token: str) -> bool:
    parts = [p for p in token.split(",") if p.strip()]
    if not parts:
        return False
    try:
        [float(p) for p in parts]
    except ValueError:
        return False
    return True


def expand_list_options(args: list[str]) -> list[str]:
    """``--headings 0 45 90`` → ``--headings 0 --headings 45 --headings 90``.

    Numbers following a list option are taken as its values until the first token that
    is not a number (an option, or the data file).
    """
    out: list[str] = []
    i = 0
    while i < len(args):
        token = args[i]
        out.append(token)
        i += 1
        if token in _LIST_OPTIONS and i < len(args):
            out.append(args[i])
            i += 1
            while i < len(args) and _is_number_list(args[i]):
                out.extend([token, args[i]])
                i += 1
    return out


class ListOptionsCommand(Command):
    """A click command whose list options take several values after one flag."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        return super().parse_args(ctx, prepare_system_args(ctx, expand_list_options(list(args))))


def parse_headings(values: tuple[str, ...]) -> list[float]:
    """Headings in degrees from ``--headings`` values (each may be a comma list; see
    :func:`cummins.cli.common.headings_list`)."""
    return headings_list(values, "--headings")


@click.command(name="rao", cls=ListOptionsCommand)
@click.argument("path", type=click.Path(exists=True))
@read_options
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    required=True,
    help="NetCDF file for the RAOs (variable rao: complex on a re/im dimension).",
)
@click.option(
    "--headings",
    multiple=True,
    metavar="DEG ...",
    help="Wave directions in degrees, the direction the waves travel (0 = along +x, "
    "following seas; 180 = head seas): --headings 0 45 90, or comma-separated. "
    "Default: the data's headings.",
)
@click.option(
    "--omega-min",
    type=non_negative("rad/s"),
    default=None,
    metavar="RAD/S",
    help="Lowest frequency.",
)
@click.option(
    "--omega-max", type=positive("rad/s"), default=None, metavar="RAD/S", help="Highest frequency."
)
@click.option(
    "--n-omega",
    type=click.IntRange(1, 100_000),
    default=None,
    metavar="N",
    help="Number of frequencies, equally spaced (default: the data's frequencies, or 200 "
    "when --omega-min/--omega-max are given).",
)
@viscous_damping_option
@click.option(
    "--no-additional",
    is_flag=True,
    help="Leave out the additional damping, added mass and stiffness of the data "
    "(WAMIT external damping, MSS viscous damping, VERES roll damping).",
)
@click.option(
    "--dof",
    "dofs",
    multiple=True,
    callback=unique_values,
    metavar="NAME",
    help="Only these DOFs move (repeatable), e.g. --dof body1__Heave --dof body2__Heave; "
    "the others are held at zero.",
)
@system_options
@click.option(
    "--plot",
    "plot_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Also write rao.png (|RAO| and phase per DOF) in this folder, and with --pto "
    "pto.png (each PTO's power, force and relative-motion RAOs against the wave period).",
)
@speed_option()
@force_option()
@reports_errors
def rao_command(
    path,
    format_,
    rho,
    g,
    ulen,
    output,
    headings,
    omega_min,
    omega_max,
    n_omega,
    viscous_damping,
    no_additional,
    dofs,
    system_options,
    plot_dir,
    speed,
    force,
):
    """Coupled motion RAOs per metre of wave amplitude (m/m, rad/m).

    \b
    Solves [-w^2 (M + A(w)) + i w (B(w) + B_add + B_v) + C] X = F(w, beta) at every
    frequency and heading, with the inertia, restoring and excitation of the data.
    Between the data frequencies A, B and F are interpolated and the equation is
    solved there (the RAO itself is never interpolated, so sharp resonances are
    resolved). Headings missing on one side of a port/starboard symmetric hull are
    mirrored. A statically unstable body (the restoring, with moorings and
    --external-stiffness, has a negative eigenvalue) has no equilibrium: the RAOs are
    written but a warning names the DOF and the file's rao attribute static_stability
    says it (`cummins simulate` refuses the same body).

    \b
    Several bodies: --joint joins them (or a body to the ground) and --pto puts a damper
    (and spring) on a relative motion; the equation is then T^T Z T q = T^T F with X = T q
    in the DOFs that can move, and the file also holds each PTO's relative motion
    (pto_displacement), force (pto_force) and mean absorbed power 0.5 c w^2 |x|^2 per
    unit wave amplitude squared (pto_power, W/m^2). --no-body-coupling leaves out the
    radiation coupling between bodies, as WEC-Sim does by default (docs/wec.md).

    \b
    Examples:
      cummins rao tanker.1 -o rao.nc --plot rao-plots
      cummins rao tanker.1 -o rao.nc --headings 0 45 90 135 180 --omega-min 0.2
          --omega-max 1.5 --n-omega 300 --viscous-damping Roll 5e8
    """
    from cummins.seakeeping.excitation import heading_coverage
    from cummins.seakeeping.frequency_domain import motion_rao, save_rao

    plot_file = str(Path(plot_dir) / "rao.png") if plot_dir else None
    prepare_outputs(output, plot_file, force=force, folders=[plot_dir])
    ds = select_speed(read_hydrodb(path, format_, rho, g, ulen), speed)
    omega = None
    if omega_min is not None or omega_max is not None or n_omega is not None:
        w = ds.omega.values
        lo = float(w[0]) if omega_min is None else omega_min
        hi = float(w[-1]) if omega_max is None else omega_max
        n = 200 if n_omega is None else n_omega
        if n < 1 or not hi >= lo:
            raise click.BadParameter(
                "need --n-omega >= 1 and --omega-max >= --omega-min", param_hint="--n-omega"
            )
        omega = np.linspace(lo, hi, n)
        from cummins.seakeeping.frequency_domain import _outside_data

        if _outside_data(ds, np.array([lo, hi])).any():
            raise click.BadParameter(
                f"{lo:.4g} to {hi:.4g} rad/s reaches outside the data's range, "
                f"{w[0]:.4g} to {w[-1]:.4g} rad/s (A, B and F are not extrapolated)",
                param_hint="--omega-min/--omega-max",
            )
    beta = np.radians(parse_headings(headings)) if headings else None
    labels = [str(d) for d in ds.influenced_dof.values]
    check_dof_selection(ds, dofs)
    system = system_from_options(system_options, dofs)
    if system is None and (dofs or len(bodies(ds)) > 1):
        from cummins.mechanics import MechanicalSystem

        # several bodies: through the system, so that the body coupling is stated
        system = MechanicalSystem(dofs=tuple(dofs) or None)
    pto_file = None
    if plot_dir and system is not None and system.ptos:  # before the work, as rao.png
        pto_file = str(Path(plot_dir) / "pto.png")
        prepare_outputs(pto_file, force=force)
    if system is not None:
        from cummins.cli.system_options import print_system
        from cummins.mechanics import assemble

        assembly = assemble(ds, system)
        labels = list(assembly.dofs)
        print_system(assembly)
    damping = viscous_damping_values(viscous_damping, labels)
    with stage_progress("solving the equation of motion at every frequency and heading"):
        rao = motion_rao(
            ds, omega, beta, viscous_damping=damping, additional=not no_additional, system=system
        )
    pto = None
    if system is not None and system.ptos:
        from cummins.seakeeping.frequency_domain import pto_rao

        pto = pto_rao(rao, ds, system)
    if "excitation_force" in ds and "wave_direction" in ds.dims:
        coverage = heading_coverage(ds)
        if coverage.mirror_used:
            console.print(f"headings: {coverage.reason}")
    console.print(f"terms: {rao.attrs['terms']}")
    console.print(rao_table(rao))
    if omega is None and system is None:
        apart = rao_against_data(rao, ds)
        from cummins.io.mss.reader import RAO_BY_CUMMINS

        if apart and ds["rao"].attrs.get("description") == RAO_BY_CUMMINS:
            listed = ", ".join(f"{dof} {100 * v:.0f} %" for dof, v in apart.items())
            console.print(
                f"note: the motion RAOs the file holds (cummins', computed when it was "
                f"written) differ from these by more than {100 * RAO_DATA_TOLERANCE:.0f} % "
                f"of their peak: {listed}: the options given here (damping, stiffness, "
                "inertia) differ from the data's"
            )
        elif apart:
            listed = ", ".join(f"{dof} {100 * v:.0f} %" for dof, v in apart.items())
            console.print(
                f"note: the data's own motion RAOs (the solver's) differ from these by more "
                f"than {100 * RAO_DATA_TOLERANCE:.0f} % of their peak: {listed} (largest "
                "difference of |RAO| over the headings): the solver used terms the data do "
                "not hold (VERES' viscous roll damping, MSS's surge estimates …); "
                "--viscous-damping DOF B adds damping"
            )
            shifted = resonance_shifts(rao, ds, list(apart))
            if shifted:
                console.print(
                    "note: "
                    + "; ".join(
                        f"{dof} peaks at {ours:.3g} rad/s, the solver's at {theirs:.3g} rad/s"
                        for dof, (ours, theirs) in shifted.items()
                    )
                    + ": damping moves a resonance little (under 5 % below 20 % of "
                    "critical), so the solver's inertia or restoring likely differ from the "
                    "data's (mass properties, GM, added mass)"
                )
    if pto is not None:
        console.print(pto_table(pto))
    save_rao(rao, output, force=force, pto=pto)
    console.print(f"wrote {output}")
    if plot_file:
        from cummins.plots import plot_rao, save_figure

        with stage_progress("drawing the RAOs"):
            save_figure(plot_rao(rao), plot_file, force=force)
        console.print(f"wrote {plot_file}")
    if pto_file:
        from cummins.cli.html_pto import plot_pto_rao, pto_units
        from cummins.plots import save_figure

        save_figure(plot_pto_rao(pto, pto_units(pto.pto)), pto_file, force=force)
        console.print(f"wrote {pto_file}")


#: A DOF whose |RAO| differs from the data's own by more than this fraction of its peak
#: is named by ``cummins rao``.
RAO_DATA_TOLERANCE = 0.05


def rao_against_data(rao, ds) -> dict[str, float]:
    """The DOFs whose computed |RAO| differs from the data's own ``rao`` (the solver's
    motion RAOs, same frequencies) by more than RAO_DATA_TOLERANCE of the data's peak,
    with that largest difference over the headings both hold (fraction of the peak)."""
    if "rao" not in ds or "wave_direction" not in ds["rao"].dims:
        return {}
    data = ds["rao"]
    if data.sizes["omega"] != rao.sizes["omega"] or not np.allclose(
        data.omega.values, rao.omega.values, rtol=1e-9
    ):
        return {}
    data_beta = np.mod(data.wave_direction.values, 2 * np.pi)
    out = {}
    for j, beta in enumerate(np.mod(rao.wave_direction.values, 2 * np.pi)):
        near = np.flatnonzero(np.isclose(data_beta, beta, atol=1e-6))
        if near.size == 0:
            continue
        for dof in rao.dof.values:
            if str(dof) not in data.radiating_dof.values:
                continue
            ref = np.abs(data.isel(wave_direction=near[0]).sel(radiating_dof=str(dof)).values)
            ours = np.abs(rao.isel(wave_direction=j).sel(dof=dof).values)
            peak = ref.max()
            if peak > 0 and np.isfinite(ref).all():
                out[str(dof)] = max(out.get(str(dof), 0.0), float(np.abs(ours - ref).max() / peak))
    return {dof: v for dof, v in out.items() if v > RAO_DATA_TOLERANCE}


def resonance_shifts(rao, ds, dofs, tolerance: float = 0.05) -> dict[str, tuple[float, float]]:
    """The DOFs of ``dofs`` with restoring whose |RAO| peaks, at the heading of the data's
    largest, at a frequency more than ``tolerance`` (relative) and two frequency steps
    from the data's own ``rao`` peak, both peaks inside the frequency range (not the
    long-wave limit of heave)."""
    data = ds["rao"]
    w = rao.omega.values
    data_beta = np.mod(data.wave_direction.values, 2 * np.pi)
    restoring = ds["hydrostatic_stiffness"]
    out = {}
    for dof in dofs:
        if float(restoring.sel(influenced_dof=dof, radiating_dof=dof)) <= 0:
            continue  # no resonance to move
        ref = np.abs(data.sel(radiating_dof=dof).transpose("omega", "wave_direction").values)
        k_ref, b_ref = np.unravel_index(int(np.argmax(ref)), ref.shape)
        near = np.flatnonzero(
            np.isclose(np.mod(rao.wave_direction.values, 2 * np.pi), data_beta[b_ref], atol=1e-6)
        )
        if near.size == 0:
            continue
        ours = np.abs(rao.isel(wave_direction=near[0]).sel(dof=dof).values)
        k_ours = int(np.argmax(ours))
        inside = all(0 < k < w.size - 1 for k in (k_ref, k_ours))
        apart = abs(w[k_ours] - w[k_ref]) > tolerance * w[k_ref] and abs(k_ours - k_ref) >= 2
        if inside and apart:
            out[dof] = (float(w[k_ours]), float(w[k_ref]))
    return out


def pto_table(pto) -> Table:
    """Largest mean absorbed power per unit wave amplitude squared of each PTO, with the
    frequency and heading where it occurs."""
    table = Table(title="PTOs: mean absorbed power 0.5 c w^2 |x|^2 per unit wave amplitude^2")
    for column in ("PTO", "max power", "at ω (rad/s)", "period (s)", "heading (deg)"):
        table.add_column(column, justify="right")
    w = pto.omega.values
    for name in pto.pto.values:
        power = pto.pto_power.sel(pto=name).transpose("omega", "wave_direction").values
        i, j = peak_index(power)
        table.add_row(
            str(name),
            power_text(power[i, j], "/m²"),
            f"{w[i]:.4g}",
            f"{2 * np.pi / w[i]:.4g}",
            f"{np.degrees(pto.wave_direction.values[j]):.4g}",
        )
    return table


def rao_table(rao) -> Table:
    """Largest |RAO| of each DOF, with the frequency and heading where it occurs."""
    w = rao.omega.values
    table = Table(
        title=f"Motion RAOs: {w.size} frequencies ({w[0]:.4g}–{w[-1]:.4g} rad/s), "
        f"{rao.sizes['wave_direction']} headings"
    )
    for column in ("DOF", "max |RAO|", "unit", "at ω [rad/s]", "period [s]", "heading [deg]"):
        table.add_column(column, justify="right")
    for dof in rao.dof.values:
        amp = np.abs(rao.sel(dof=dof).transpose("omega", "wave_direction").values)
        i, j = peak_index(amp)
        rotation = is_rotation(dof)
        table.add_row(
            str(dof),
            f"{amp[i, j]:.4g}",
            "rad/m" if rotation else "m/m",
            f"{w[i]:.4g}",
            f"{2 * np.pi / w[i]:.4g}",
            f"{np.degrees(rao.wave_direction.values[j]):.4g}",
        )
    return table
