"""``cummins lf-model``: the constant-coefficient manoeuvring model (Ross, Perez & Fossen, 2006)."""

from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path

import click
import numpy as np

from cummins.cli.common import (
    Number,
    console,
    force_option,
    non_negative,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_speed,
    speed_option,
)
from cummins.cli.option_rules import Command


@click.command(name="lf-model", cls=Command)
@click.argument("path", metavar="DATA", type=click.Path(exists=True))
@read_options
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    required=True,
    help="NetCDF file of the model (M_A, D, G, frequencies, provenance).",
)
@click.option(
    "--route",
    type=click.Choice(["frequency", "kernel"]),
    default="frequency",
    show_default=True,
    help="frequency: from A(w), B(w) (the solver's w = 0 row when present); "
    "kernel: from the retardation functions K(t).",
)
@click.option(
    "--surge-damping",
    type=(non_negative("kg/s"), non_negative("s/rad")),
    default=None,
    metavar="BETA ALPHA",
    help="Viscous surge damping beta exp(-alpha w) (kg/s, s/rad); also "
    "--sway-damping, --yaw-damping.",
)
@click.option(
    "--sway-damping",
    type=(non_negative("kg/s"), non_negative("s/rad")),
    default=None,
    metavar="BETA ALPHA",
)
@click.option(
    "--yaw-damping",
    type=(non_negative("kg m^2/s"), non_negative("s/rad")),
    default=None,
    metavar="BETA ALPHA",
)
@click.option(
    "--roll-damping",
    type=Number(0.0, 1.0),
    default=None,
    metavar="ZETA",
    help="Viscous roll damping as a fraction of critical at the roll natural "
    "frequency (a proxy for Ikeda's estimate).",
)
@click.option(
    "--data-damping",
    "data_damping",
    multiple=True,
    metavar="DOF",
    help="Take this DOF's viscous damping from the data's additional_damping (MSS's Bv) "
    "at the DOF's frequency (w = 0 for surge, sway, yaw: the lowest frequency's value); "
    "repeat it, or 'all' for every DOF the data damp. The Python form: "
    "viscous={dof: 'data'}.",
)
@click.option(
    "--compare",
    "compare_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Also simulate decays (heave, roll, pitch) and steps (surge, sway, yaw) "
    "of the LF model and of the full Cummins model; write the PNGs here.",
)
@click.option(
    "--plot",
    "plot_file",
    type=click.Path(dir_okay=False),
    default=None,
    help="PNG of A(w) and B(w) with the chosen values marked (seed Figs. 1-2).",
)
@speed_option("Forward speed of DATA.")
@click.option(
    "--manoeuvring-speed",
    "manoeuvring_speed",
    type=Number(unit="m/s"),
    default=None,
    metavar="U",
    help="The ship moving ahead at U m/s: add to the model of the zero-speed data the "
    "linearised Coriolis and centripetal forces of the rigid body and the added mass "
    "about u = U (Fossen 2011: sway (m + A11) U r, the Munk moments (A22 - A11) U v in "
    "yaw and (A11 - A33) U w in pitch ...), written as speed_terms.",
)
@force_option()
@reports_errors
def lf_model_command(
    path,
    format_,
    rho,
    g,
    ulen,
    output,
    route,
    surge_damping,
    sway_damping,
    yaw_damping,
    roll_damping,
    data_damping,
    compare_dir,
    plot_file,
    speed,
    manoeuvring_speed,
    force,
):
    """Derive the constant-coefficient low-frequency model (M_RB + M_A) v' + D v + G eta = tau.

    \b
    Ross, Perez & Fossen (2006): surge, sway and yaw take the zero-frequency limits
    (the hydrodynamic derivatives: M_A = A(0), D = B(0) + viscous, B(0) = 0 at zero speed),
    heave, roll and pitch the values at their natural frequency w0, found by iterating
    w0^2 (M_RB + A(w0)) = C (eq. 24). The model is the one control engineers use for
    DP and manoeuvring; --compare shows what it loses against the Cummins model.

    \b
    Examples:
      cummins lf-model tanker.1 -o lf.nc --plot lf.png
      cummins lf-model tanker.1 -o lf.nc --route kernel --roll-damping 0.05 --compare lf-cmp
      cummins lf-model supply.mat -o lf.nc --data-damping all
      cummins lf-model s175.mat --speed 0 --manoeuvring-speed 10.29 -o lf20kn.nc
    """
    from rich.markup import escape
    from rich.table import Table

    from cummins.timedomain.lfmodel import (
        CriticalDampingFraction,
        ExponentialDamping,
        lf_model_from_frequency_data,
        lf_model_from_retardation,
    )
    from cummins.timedomain.lfmodel.builders import DATA_DAMPING_ADVICE

    outputs = [output, plot_file]
    if compare_dir:
        outputs += [Path(compare_dir) / f"{kind}_{d}.png" for kind, d in _COMPARISONS]
    prepare_outputs(*outputs, force=force, folders=[compare_dir])
    ds = select_speed(read_hydrodb(path, format_, rho, g, ulen), speed)
    at_speed = float(ds.coords["forward_speed"]) if "forward_speed" in ds.coords else 0.0
    if at_speed and manoeuvring_speed is not None:
        raise click.UsageError(
            f"--manoeuvring-speed adds the speed terms to the model of zero-speed data; these "
            f"are the data at {at_speed:g} m/s: give --speed 0 (or data at zero speed)"
        )
    if manoeuvring_speed is not None and compare_dir:
        raise click.UsageError(
            "--compare runs the Cummins model at zero speed; leave it out with "
            "--manoeuvring-speed (or compare the zero-speed model)"
        )
    if at_speed:
        from cummins.cli.common import err_console

        err_console.print(
            f"[yellow]warning:[/] at {at_speed:g} m/s this model is the zero-speed theory "
            "applied to data at speed: the speed terms (U·A∞ damping such as B26 = −U·A22, "
            "B62 = +U·A22, the derivatives Y_r, N_v of a manoeuvring model, and the "
            "antisymmetric A35/A53) are averaged or set to zero, not modelled; build the "
            "model of the zero-speed data with the linearised speed terms instead: "
            f"--speed 0 --manoeuvring-speed {at_speed:g}",
            highlight=False,
        )
    viscous = {}
    for dof, spec in (("Surge", surge_damping), ("Sway", sway_damping), ("Yaw", yaw_damping)):
        if spec is not None:
            viscous[dof] = ExponentialDamping(*spec)
    if roll_damping is not None:
        viscous["Roll"] = CriticalDampingFraction(roll_damping)
    viscous.update(_data_damping(ds, data_damping, viscous))
    build = lf_model_from_frequency_data if route == "frequency" else lf_model_from_retardation
    with (
        console.status("deriving the low-frequency model"),
        warnings.catch_warnings(record=True) as caught,
    ):
        warnings.simplefilter("always")
        model = build(ds, viscous=viscous or None)
    if manoeuvring_speed is not None:
        from cummins.timedomain.lfmodel.speed import at_forward_speed

        model = at_forward_speed(model, manoeuvring_speed)
    for w in caught:  # the library's advice names its keyword; here: the option
        text = str(w.message).replace(DATA_DAMPING_ADVICE, "--data-damping DOF (or all)")
        warnings.warn_explicit(text, w.category, w.filename, w.lineno)
    table = Table(title=f"low-frequency model of {Path(path).name} ({route} route)")
    for column in ("DOF", "frequency [rad/s]", "M_RB + M_A", "D", "G"):
        table.add_column(column, justify="right")
    for k, dof in enumerate(model.dofs):
        table.add_row(
            dof,
            f"{model.frequencies[k]:.4g}",
            f"{model.mass[k, k]:.4g}",
            f"{model.damping[k, k]:.4g}",
            f"{model.stiffness[k, k]:.4g}",
        )
    console.print(table)
    console.print("taken as (equations of Ross, Perez & Fossen (2006)):")
    for line in model.provenance:  # whole sentences, wrapped at the terminal's width
        console.print(f"  {escape(line)}", highlight=False)
    if manoeuvring_speed is not None:
        _print_speed_terms(model, manoeuvring_speed)
    from cummins.io.netcdf import save_netcdf

    save_netcdf(model.to_dataset(), output)
    console.print(f"wrote {output}")
    if plot_file:
        from cummins.plots import plot_lf_model, save_figure

        console.print(f"wrote {save_figure(plot_lf_model(ds, model), plot_file, force=force)}")
    if compare_dir:
        _compare(ds, model, Path(compare_dir), force)


def _print_speed_terms(model, speed: float) -> None:
    """The speed terms N(U) of :func:`cummins.timedomain.lfmodel.speed.at_forward_speed`,
    one line each (:func:`~cummins.timedomain.lfmodel.speed.speed_term_entries`)."""
    from cummins.timedomain.lfmodel.speed import speed_term_entries

    console.print(
        f"speed terms at {speed:g} m/s (linearised Coriolis and centripetal forces of the "
        "rigid body and the added mass, Fossen (2011); in D + N(U)):",
        highlight=False,
    )
    for row, column, value in speed_term_entries(model.speed_terms, model.dofs):
        console.print(f"  N[{row}, {column}] = {value:.4g}", highlight=False)


def _data_damping(ds, names, given) -> dict[str, str]:
    """``--data-damping``: {DOF: 'data'} for the DOFs named ('all': every DOF whose
    diagonal of ``additional_damping`` is nonzero somewhere); a DOF not in the data, one
    given another damping option, or data without ``additional_damping``: exit 2."""
    if not names:
        return {}
    dofs = [str(d) for d in ds.influenced_dof.values]
    if "additional_damping" not in ds:
        raise click.BadParameter(
            "the data hold no additional_damping (MSS's Bv, a WAMIT/VERES viscous "
            "matrix): give the damping with --surge-damping … instead",
            param_hint="--data-damping",
        )
    values = ds["additional_damping"].transpose(..., "influenced_dof", "radiating_dof").values
    if "all" in names:
        diagonal = np.abs(np.diagonal(values, axis1=-2, axis2=-1)).reshape(-1, len(dofs))
        chosen = [d for k, d in enumerate(dofs) if np.any(diagonal[:, k] > 0)]
    else:
        chosen = list(dict.fromkeys(names))
    for name in chosen:
        if name not in dofs:
            raise click.BadParameter(
                f"unknown DOF {name!r}; use {', '.join(dofs)} or all", param_hint="--data-damping"
            )
        if name in given and "all" not in names:
            raise click.BadParameter(
                f"{name} already has its damping from --{name.lower()}-damping",
                param_hint="--data-damping",
            )
    return {name: "data" for name in chosen if name not in given}


_COMPARISONS = (
    ("decay", "Heave"),
    ("decay", "Roll"),
    ("decay", "Pitch"),
    ("step", "Surge"),
    ("step", "Sway"),
    ("step", "Yaw"),
)


def _compare(ds, model, folder: Path, force: bool) -> None:
    from cummins.plots import plot_lf_comparison, save_figure
    from cummins.timedomain.lfmodel import compare_with_cummins
    from cummins.vessel import vessel_from_hydrodb

    with console.status("fitting the Cummins model for the comparison"):
        # the same viscous damping in both models (the LF model's holds the data's own)
        vessel = dataclasses.replace(
            vessel_from_hydrodb(ds), viscous_damping=np.asarray(model.viscous_damping)
        )
    for kind, dof in _COMPARISONS:
        if dof not in model.dofs:
            continue
        result = compare_with_cummins(model, vessel, dof, kind=kind)
        file = save_figure(
            plot_lf_comparison(result, dof, kind), folder / f"{kind}_{dof}.png", force=force
        )
        console.print(
            f"{kind} of {dof}: RMS difference {100 * result.attrs['rms_relative']:.1f} %"
            f" of the Cummins response; wrote {file}"
        )
