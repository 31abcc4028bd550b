"""`cummins convert`: canonical NetCDF, BEMIO .h5, WAMIT files for HydroDyn, an MSS vessel
struct or a QTF as WAMIT writes it."""

from __future__ import annotations

import warnings
from pathlib import Path

import click
import numpy as np

from cummins.cli.common import (
    console,
    finite,
    force_option,
    main_dimensions_option,
    positive,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_body,
    select_speed,
    speed_option,
    with_main_dimensions,
)
from cummins.cli.option_rules import Command
from cummins.errors import CumminsWarning


@click.command(name="convert", cls=Command)
@click.argument("source", type=click.Path(exists=True))
@click.argument("destination", type=click.Path())
@read_options
@click.option(
    "--axes",
    type=click.Choice(["z-up", "z-down"]),
    default=None,
    help="Axis convention to write: z-up (x fwd, y port, z up: solvers) or z-down "
    "(x fwd, y starboard, z down: Fossen/MSS). Default: .mat files z-down, else as read.",
)
@click.option(
    "--reference-point",
    nargs=3,
    type=finite("m"),
    default=None,
    metavar="X Y Z",
    help="Move the reference point to X Y Z (m, in the axes written).",
)
@click.option(
    "--body",
    metavar="N|NAME",
    default=None,
    help="Of several bodies, write only this one (1-based number or name): its six DOFs "
    "as Surge … Yaw, e.g. for an MSS .mat, which holds one body.",
)
@click.option(
    "--displaced-volume",
    "volumes",
    type=positive("m^3"),
    multiple=True,
    metavar="M3",
    help="Displaced volume of the body (once per body) when the files do not give it "
    "(WAMIT .1/.3 without the .out, HAMS): WEC-Sim's readBEMIOH5 needs it in the .h5.",
)
@click.option(
    "--limit-rows/--no-limit-rows",
    default=True,
    show_default=True,
    help="Of a WAMIT .1 (for HydroDyn, whose input file says the files must hold them): "
    "write the w = inf (PER = 0) and w = 0 (PER = -1) rows the data lack, estimated "
    "(A(inf) by Ogilvie's estimate from A(w), B(w); A(0) the added mass at the lowest "
    "frequency), each said in one line. --no-limit-rows writes only the rows the data hold.",
)
@click.option(
    "--model",
    "model_path",
    type=click.Path(exists=True, dir_okay=False),
    default=None,
    metavar="MODEL.nc",
    help="A radiation model of these data (cummins fit -o MODEL.nc): its state space goes "
    "into the .h5's hydro_coeffs/radiation_damping/state_space (A, B, C, D, it, K), which "
    "WEC-Sim reads. The model must be of these very data (its DOFs and data fingerprint).",
)
@main_dimensions_option(
    "Length between perpendiculars, breadth and draught of the ship in m, when the files "
    "do not give them (WAMIT): an MSS .mat holds them in vessel.main (Lpp, B, T, and "
    "C_B, Lwl, S from them), which MSS's functions read."
)
@speed_option(
    "Of data at several forward speeds, write this one only. Needed for .1, .h5, .12d and "
    ".12s (WAMIT and BEMIO files hold one speed); .nc and .mat hold them all without it."
)
@force_option("Overwrite DESTINATION if it exists.")
@reports_errors
def convert_command(
    source,
    destination,
    format_,
    rho,
    g,
    ulen,
    axes,
    reference_point,
    body,
    volumes,
    limit_rows,
    model_path,
    main_dimensions,
    speed,
    force,
):
    """Convert SOURCE to canonical NetCDF (.nc), a BEMIO .h5 for WEC-Sim, WAMIT numeric
    files (.1, with .3 and .hst) for OpenFAST's HydroDyn, an MSS vessel struct (.mat), or
    its difference- or sum-frequency QTF to a WAMIT .12d/.12s file.

    SOURCE is any file or folder cummins reads (WAMIT, HAMS, NEMOH, AQWA, VERES, Capytaine,
    BEMIO .h5, MSS .mat: see --format).

    \b
    The NetCDF has Capytaine's layout (complex values on a re/im dimension) plus
    cummins' variables (added_mass_inf, ...), in SI units. The .h5 has the layout
    WEC-Sim's readBEMIOH5 reads (normalised coefficients, z-up axes, K(t), K_ex(t)).
    The .1/.3/.hst are nondimensional as WAMIT writes them (rho, g, ULEN: --ulen of a
    WAMIT source, else 1 m) and hold what HydroDyn reads: the .hst the restoring of
    buoyancy and waterplane alone (the weight's terms the data record taken out:
    ElastoDyn adds the weight), the .1 its w = 0 and w = inf rows (estimated when the
    data lack them, see --limit-rows). Moments are about the reference point written,
    which HydroDyn's PtfmRefxt/yt/zt must give: --reference-point 0 0 0 for the usual
    origin on the free surface. The mean drift goes to x.7, x.8 or x.9 by its method
    (HydroDyn's MnDrift), the QTFs to their own files (x.12d, x.12s).

    \b
    Examples:
      cummins convert tanker.1 tanker.nc
      cummins convert tanker.1 tanker.h5
      cummins convert spar.1 spar.h5 --displaced-volume 8029
      cummins convert spar.1 spar.h5 --model spar_model.nc   (with its state space)
      cummins convert semisub.nc semisub.1
      cummins convert input.re7 supply.mat --reference-point 0 0 0
      cummins convert results/ spar.12d       (a NEMOH QTF as WAMIT's, for OpenFAST)
    """
    from cummins.hydrodb import change_axes, move_reference_point
    from cummins.io import write

    to_mat = Path(destination).suffix.lower() == ".mat"
    if Path(destination).suffix.lower() not in (".nc", ".mat", ".h5", ".1", ".12d", ".12s"):
        raise click.BadParameter(
            f"{destination}: write .nc (canonical NetCDF), .h5 (BEMIO, for WEC-Sim), .1 "
            "(WAMIT .1/.3/.hst, for HydroDyn), .mat (MSS vessel struct) or .12d/.12s (the QTF "
            "as WAMIT writes it, for HydroDyn)",
            param_hint="DESTINATION",
        )
    if model_path is not None and Path(destination).suffix.lower() != ".h5":
        raise click.BadParameter(
            f"only a BEMIO .h5 stores a radiation state space, not {destination}: write "
            ".h5, or leave --model out (cummins fit --openfast/--mss writes the model for "
            "OpenFAST or MSS)",
            param_hint="--model",
        )
    if main_dimensions is not None and Path(destination).suffix.lower() not in (".nc", ".mat"):
        raise click.BadParameter(
            f"{destination}: WAMIT, BEMIO and QTF files have no field for the main "
            "dimensions; write .mat (MSS's vessel.main) or .nc",
            param_hint="--main-dimensions",
        )
    prepare_outputs(destination, force=force)
    model = _load_model(model_path) if model_path is not None else None
    ds = read_hydrodb(source, format_, rho, g, ulen)
    if speed is not None or Path(destination).suffix.lower() not in (".nc", ".mat"):
        ds = select_speed(ds, speed)
    if body is not None:
        ds = select_body(ds, body)
    ds = with_main_dimensions(ds, main_dimensions)
    if volumes:
        ds = _with_volumes(ds, volumes)
    if to_mat:
        _check_mss_body(ds)
    if axes is None and to_mat:
        axes = "z-down"
    if axes is not None:
        ds = change_axes(ds, axes)
    if reference_point is not None:
        ds = move_reference_point(ds, reference_point)
    if Path(destination).suffix.lower() == ".1":
        # the commands it prints name the same speed
        again = source if speed is None else f"{source} --speed {speed:g}"
        _write_for_hydrodyn(ds, destination, again, limit_rows, force)
        return
    if model is not None:
        _check_model(model, ds, model_path)
        from cummins.cli.failed_model import warn_failed_model

        warn_failed_model(model.attrs, model_path)  # WEC-Sim would take it silently
    write(ds, destination, force=force, model=model)
    console.print(
        f"wrote {destination} ({ds.attrs.get('axis_convention')} axes, reference point "
        f"{[float(x) for x in ds.attrs['reference_point']]} m)"
    )
    if model is not None:
        orders = [k.order for k in model.as_couplings().couplings if k.order]
        console.print(
            f"with the state space of {Path(model_path).name}: {len(orders)} couplings of "
            f"order {min(orders, default=0)} to {max(orders, default=0)} (total "
            f"{model.total_order} states) in hydro_coeffs/radiation_damping/state_space "
            "(A, B, C/rho, D = 0, it, K/rho)"
        )


def _load_model(path):
    """The radiation model of a ``cummins fit`` file (a one-line error for another file)."""
    from cummins.cli.common import cummins_model_format
    from cummins.radiation.model import RadiationModel
    from cummins.radiation.model_file import FORMAT_NAME

    if cummins_model_format(path) != FORMAT_NAME:
        raise click.BadParameter(
            f"{path} is not a radiation model file: give the output of cummins fit -o "
            "MODEL.nc (or cummins reduce)",
            param_hint="--model",
        )
    return RadiationModel.load(path)


def _check_model(model, ds, path) -> None:
    """Refuse a model of other DOFs or other data than those written (exit status 2)."""
    from cummins.errors import ArgumentError, HydroDataError
    from cummins.hydrodb import single_speed
    from cummins.radiation.fingerprint import check_model_data

    try:
        check_model_data(model, single_speed(ds), model_name=f"--model {Path(path).name}")
    except HydroDataError as exc:
        raise ArgumentError(
            f"{exc.message}: its state space is not that of the data written "
            f"({Path(str(ds.attrs.get('source_file', '')) or '?').name}, after any "
            "--body, --axes or --reference-point)",
            hint="Give the model fitted to these data (cummins fit DATA -o MODEL.nc), "
            "convert without the options that change the data, or leave --model out",
        ) from None


def _write_for_hydrodyn(ds, destination, source, limit_rows, force) -> None:
    """The WAMIT .1/.3/.hst for HydroDyn, with one line per change or estimate, the
    HydroDyn inputs the files imply, and where the QTFs go."""
    from cummins.errors import AssumptionWarning
    from cummins.hydrodb import change_axes
    from cummins.io.wamit.hydrodyn import hydrodyn_data
    from cummins.io.wamit.numeric_writer import drift_files, write_wamit

    if ds.attrs.get("axis_convention", "z-up") != "z-up":
        ds = change_axes(ds, "z-up")
    prepared = hydrodyn_data(ds, limits=limit_rows)
    for line in prepared.assumptions:
        warnings.warn(AssumptionWarning(line), stacklevel=2)
    files = write_wamit(
        prepared.ds,
        destination,
        ulen=float(ds.attrs.get("ulen", 1.0)),
        force=force,
        hydrodyn=False,
    )
    point = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float)
    console.print(
        f"wrote {', '.join(str(f) for f in files)} (WAMIT's z-up axes, moments about "
        f"{np.round(point, 6).tolist()} m)"
    )
    for line in prepared.notes:
        console.print(line)
    if "excitation_force" not in ds:
        console.print(
            f"no {Path(destination).with_suffix('.3').name}: the data hold no wave excitation "
            "(read the solver's excitation file with the run); without it HydroDyn needs "
            "ExctnMod = 0 (no wave excitation), its .3 being read for ExctnMod = 1"
        )
    if "hydrostatic_stiffness" not in ds:
        console.print(
            f"no {Path(destination).with_suffix('.hst').name}: the data hold no hydrostatics "
            "(read the solver's .hst or KH file with the run), and HydroDyn reads the .hst "
            "of its PotFile with PotMod = 1"
        )
    console.print("HydroDyn: " + "; ".join(prepared.settings))
    if np.any(point.reshape(-1, 3)[:, 2] != 0):
        console.print(
            "  PtfmRefzt must be the reference point's z (HydroDyn refuses it with "
            "NBodyMod=2): for moments about the origin on the free surface, convert again "
            "with --reference-point 0 0 0"
        )
    held = [name for name in ("qtf_difference", "qtf_sum") if name in ds]
    if held:
        stem = Path(destination).with_suffix("")
        files = {"qtf_difference": f"{stem}.12d", "qtf_sum": f"{stem}.12s"}
        console.print(
            "the data's QTFs are not in the .1: write them with "
            + " and ".join(f"cummins convert {source} {files[name]}" for name in held)
            + " (HydroDyn's DiffQTF/SumQTF = 12"
            + ("" if "drift_force" in ds else "; MnDrift = 12 takes the mean drift from the .12d")
            + ")"
        )
    drifts = drift_files(prepared.ds)[0]
    if drifts:
        stem = Path(destination).with_suffix("")
        methods = {
            suffix: prepared.ds[name].attrs.get("method") or "method not recorded"
            for suffix, name in drifts.items()
        }
        written = [f"{stem.name}{suffix} ({method})" for suffix, method in methods.items()]
        console.print(
            f"the mean drift: {', '.join(written)}; HydroDyn's MnDrift (or NewmanApp) = "
            + " or ".join(suffix[1:] for suffix in drifts)
            + f" reads it (for WEC-Sim a BEMIO .h5: cummins convert {source} "
            f"{stem.with_suffix('.h5')})"
        )


def _with_volumes(ds, volumes):
    """The data with ``displaced_volume`` given on the command line (one per body)."""
    from cummins.hydrodb import add_history, bodies

    count = len(bodies(ds))
    if len(volumes) != count:
        raise click.BadParameter(
            f"give one volume per body: the data hold {count}, {len(volumes)} given",
            param_hint="--displaced-volume",
        )
    out = ds.copy()
    out.attrs["displaced_volume"] = float(volumes[0]) if count == 1 else [float(v) for v in volumes]
    add_history(out, f"displaced volume given: {', '.join(f'{v:g}' for v in volumes)} m^3")
    return out


def _check_mss_body(ds) -> None:
    """An MSS struct holds one rigid body: say how to choose one, and what it will lack."""
    from cummins.hydrodb import DOF_NAMES, bodies

    labels = [str(d) for d in ds.influenced_dof.values]
    if labels != list(DOF_NAMES):
        groups = bodies(ds)
        several = groups != [None]
        raise click.BadParameter(
            f"an MSS vessel struct holds one body with six DOFs (Surge … Yaw); the data "
            f"have {len(labels)} DOFs"
            + (
                f" of {len(groups)} bodies: choose one with --body 1 … {len(groups)}"
                if several
                else ""
            ),
            param_hint="DESTINATION",
        )
    for name, what in (
        ("inertia_matrix", "MRB (the rigid-body inertia) is written as zeros"),
        ("hydrostatic_stiffness", "C (the restoring) is written as zeros"),
    ):
        if name not in ds:
            warnings.warn(
                f"the data have no {name}: {what}; MSS needs it to simulate. Give it with "
                "cummins.with_inertia(...) / --mass … --radii-of-gyration … (inertia) or "
                "the solver's hydrostatics file",
                CumminsWarning,
                stacklevel=2,
            )
