"""Pieces shared by the ``cummins`` commands: consoles, error reporting, read options."""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import click
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeElapsedColumn

from cummins.errors import CumminsError

console = Console(highlight=False, soft_wrap=True)
err_console = Console(stderr=True, highlight=False, soft_wrap=True)


def progress_bar() -> Progress:
    """A transient bar for work measured as a fraction (``total=1.0``) or in steps."""
    return Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        TaskProgressColumn(),
        TimeElapsedColumn(),
        console=console,
        transient=True,
    )


def run_reporting_errors(function, *args, **kwargs):
    """Call ``function``; turn a CumminsError into a one-line message and exit status 2."""
    try:
        return function(*args, **kwargs)
    except CumminsError as exc:
        err_console.print(f"[bold red]error:[/] {escape(str(exc))}")
        sys.exit(2)


def reports_errors(func):
    """Decorator form of :func:`run_reporting_errors` for the commands."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        return run_reporting_errors(func, *args, **kwargs)

    return wrapper


def viscous_damping_option(func):
    """--viscous-damping DOF VALUE (repeatable), passed as ``viscous_damping``."""
    return click.option(
        "--viscous-damping",
        "viscous_damping",
        type=(str, float),
        multiple=True,
        metavar="DOF VALUE",
        help="Linear viscous damping B_v on a DOF, e.g. --viscous-damping Roll 5e8 (kg/s, "
        "kg m^2/s; repeatable, repeated values add up). Surge, sway and yaw have no "
        "restoring: without it they drift in a simulation.",
    )(func)


def viscous_damping_values(
    pairs, labels, option: str = "--viscous-damping"
) -> dict[str, float] | None:
    """``{dof: value}`` from the (DOF, value) pairs of ``option`` (None when there are
    none)."""
    if not pairs:
        return None
    values: dict[str, float] = {}
    for dof, value in pairs:
        if dof not in labels:
            raise click.BadParameter(
                f"unknown DOF {dof!r}; the data have {', '.join(labels)}",
                param_hint=option,
            )
        values[dof] = values.get(dof, 0.0) + value
    return values


#: Where :func:`read_options` leaves the mass-property options for :func:`read_hydrodb`.
_EOM_KEY = "cummins.equation_of_motion"
_EOM_OPTIONS = (
    "mass",
    "center_of_gravity",
    "radii_of_gyration",
    "inertia_matrix",
    "external_stiffness",
    "external_damping",
)


def read_options(func):
    """--format, --rho, --g, --ulen: how to read solver files; --mass,
    --center-of-gravity, --radii-of-gyration, --inertia-matrix, --external-stiffness,
    --external-damping: what to complete them with (the terms of the equation of motion
    that the files lack), applied by :func:`read_hydrodb`."""
    decorators = [
        click.option(
            "--format",
            "format_",
            metavar="NAME",
            default=None,
            help="Solver format (wamit, wamit-out, nemoh, aqwa, veres, netcdf, mss); "
            "detected from the content by default.",
        ),
        click.option(
            "--rho",
            type=float,
            default=None,
            metavar="KG/M3",
            help="Water density for nondimensional formats (WAMIT does not record it "
            "everywhere; default 1025).",
        ),
        click.option(
            "--g",
            "g",
            type=float,
            default=None,
            metavar="M/S2",
            help="Acceleration of gravity for nondimensional formats (default 9.81, or "
            "the value in the WAMIT .out).",
        ),
        click.option(
            "--ulen",
            type=float,
            default=None,
            metavar="M",
            help="WAMIT length scale ULEN (default: from the .out, else 1).",
        ),
        click.option(
            "--mass",
            type=float,
            multiple=True,
            metavar="KG",
            help="Mass of the body (repeat once per body, in their order). With "
            "--radii-of-gyration it builds the rigid-body inertia matrix when the files lack "
            "it (or replaces theirs). Default with radii given: rho times the displaced "
            "volume (a freely floating body).",
        ),
        click.option(
            "--center-of-gravity",
            type=(float, float, float),
            multiple=True,
            metavar="X Y Z",
            help="Centre of gravity in m, in the data's axes (once per body; default: the "
            "files' value).",
        ),
        click.option(
            "--radii-of-gyration",
            type=(float, float, float),
            multiple=True,
            metavar="RXX RYY RZZ",
            help="Radii of gyration about the centre of gravity in m (once per body), e.g. "
            "0.35 B, 0.25 L, 0.26 L for a ship.",
        ),
        click.option(
            "--inertia-matrix",
            type=click.Path(exists=True, dir_okay=False),
            default=None,
            metavar="FILE",
            help="The inertia matrix instead: a text file (or .npy) with the n x n matrix of "
            "all DOFs, or a 6 x 6 matrix per body one below the other, about the reference "
            "point (kg, kg m, kg m^2).",
        ),
        click.option(
            "--external-stiffness",
            type=(str, str, float),
            multiple=True,
            metavar="DOF DOF VALUE",
            help="External stiffness (moorings, a PTO spring) added to the restoring, e.g. "
            "--external-stiffness Surge Surge 8e4 (N/m, N m/rad; repeatable; give both (i, j) and "
            "(j, i) for a symmetric coupling).",
        ),
        click.option(
            "--external-damping",
            type=(str, str, float),
            multiple=True,
            metavar="DOF DOF VALUE",
            help="External linear damping (a PTO, dampers) between two DOFs, e.g. "
            "--external-damping body1__Pitch body1__Pitch 1e6 (kg/s, kg m^2/s; repeatable).",
        ),
    ]

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        context = click.get_current_context()
        context.meta[_EOM_KEY] = {name: kwargs.pop(name) for name in _EOM_OPTIONS}
        return func(*args, **kwargs)

    for decorator in reversed(decorators):
        wrapper = decorator(wrapper)
    return wrapper


def read_hydrodb(
    path: str, format_: str | None, rho: float | None, g: float | None, ulen: float | None
):
    """Read ``path`` with the options of :func:`read_options`, completed by the
    mass-property and external-term options of the same command."""
    from cummins.io import read

    ds = read(path, format=format_, rho=rho, g=g, ulen=ulen)
    context = click.get_current_context(silent=True)
    options = context.meta.get(_EOM_KEY) if context is not None else None
    return complete_equation_of_motion(ds, **options) if options else ds


def complete_equation_of_motion(
    ds,
    *,
    mass=(),
    center_of_gravity=(),
    radii_of_gyration=(),
    inertia_matrix=None,
    external_stiffness=(),
    external_damping=(),
):
    """``ds`` with the inertia and external terms of the command-line options."""
    from cummins.mass_properties import read_matrix_file, with_external_terms, with_inertia

    if inertia_matrix is not None:
        if mass or radii_of_gyration or center_of_gravity:
            raise click.UsageError(
                "give either --inertia-matrix or --mass/--center-of-gravity/"
                "--radii-of-gyration, not both"
            )
        ds = with_inertia(ds, matrix=read_matrix_file(inertia_matrix))
    elif radii_of_gyration:
        ds = with_inertia(
            ds,
            mass=list(mass) if mass else None,
            center_of_gravity=[list(c) for c in center_of_gravity] or None,
            radii_of_gyration=[list(r) for r in radii_of_gyration],
        )
    elif mass or center_of_gravity:
        raise click.UsageError(
            "--mass and --center-of-gravity build the inertia matrix together with "
            "--radii-of-gyration RXX RYY RZZ: give the radii too"
        )
    labels = [str(d) for d in ds.influenced_dof.values]
    terms = {}
    for name, given in (("stiffness", external_stiffness), ("damping", external_damping)):
        if given:
            values: dict[tuple[str, str], float] = {}
            for i, j, value in given:
                for dof in (i, j):
                    if dof not in labels:
                        raise click.BadParameter(
                            f"unknown DOF {dof!r}; the data have {', '.join(labels)}",
                            param_hint=f"--external-{name}",
                        )
                values[(i, j)] = values.get((i, j), 0.0) + value
            terms[name] = values
    return with_external_terms(ds, **terms) if terms else ds


def prepare_outputs(*paths, force: bool) -> None:
    """Before any work: refuse to overwrite without ``--force``, create missing folders."""
    from cummins.errors import check_writable

    for path in paths:
        if path:
            check_writable(path, force)
    for path in paths:
        if path:
            Path(path).parent.mkdir(parents=True, exist_ok=True)


def select_speed(ds, speed: float | None):
    """The data at one forward speed (``--speed``): required when there are several, and
    one of them (within 1 mm/s), never the nearest."""
    if "forward_speed" not in ds.dims:
        return ds
    speeds = ds.forward_speed.values
    listed = ", ".join(f"{u:g}" for u in speeds)
    if speed is None:
        if speeds.size > 1:
            raise click.UsageError(
                f"the data hold several forward speeds: choose one with --speed ({listed} m/s)"
            )
        return ds.isel(forward_speed=0)
    matches = [k for k, u in enumerate(speeds) if abs(u - speed) <= 1e-3]
    if not matches:
        raise click.UsageError(f"no data at --speed {speed:g} m/s; the data hold {listed} m/s")
    return ds.isel(forward_speed=matches[0])


def model_and_data(path):
    """(model or None, data path): a model file names the data it was fitted to."""
    from cummins.io.model_netcdf import FORMAT_NAME
    from cummins.radiation import RadiationModel

    p = Path(path)
    if p.is_file() and p.suffix.lower() == ".nc":
        import h5py

        try:
            with h5py.File(p, "r") as f:
                kind = f.attrs.get("cummins_format")
        except OSError:
            kind = None
        if isinstance(kind, bytes):
            kind = kind.decode()
        if kind == FORMAT_NAME:
            model = RadiationModel.load(p)
            source = model.attrs.get("source_file")
            if not source or not Path(source).exists():
                raise click.UsageError(
                    f"{p} does not name an existing data file ({source!r}): give the data "
                    "file instead (the model is then fitted again)"
                )
            return model, source
    return None, path
