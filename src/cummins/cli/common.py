"""Pieces shared by the ``cummins`` commands: consoles, error reporting, read options;
:func:`prepare_outputs` and :func:`note_inputs` (from :mod:`cummins.cli.outputs`)."""

from __future__ import annotations

import contextlib
import functools
import math
import sys
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import NoReturn

import click
import numpy as np
from rich.console import Console, ConsoleDimensions
from rich.markup import escape
from rich.progress import (
    BarColumn,
    Progress,
    SpinnerColumn,
    TaskProgressColumn,
    TextColumn,
    TimeElapsedColumn,
)
from rich.table import Table

from cummins.cli.option_rules import refuse_repeated
from cummins.cli.outputs import note_inputs
from cummins.cli.outputs import prepare_outputs as prepare_outputs  # for the commands
from cummins.errors import (
    ArgumentError,
    CumminsError,
    CumminsWarning,
    OutputExistsError,
)
from cummins.files import files_read, fitted_data_file

#: The width of the output when it is not a terminal (a pipe, a log, CI), unless COLUMNS
#: says otherwise: wide enough for every table, where rich would otherwise take 80.
PIPE_WIDTH = 200


class _Console(Console):
    """A rich console that reads right anywhere: not on a terminal it is
    :data:`PIPE_WIDTH` wide, and the columns of its tables fold a value that does not fit
    onto the next line instead of cutting it ("5.297e…"); JSON stays the machine
    interface."""

    def _size(self) -> ConsoleDimensions:
        size = Console.size.fget(self)
        if self._width is None and "COLUMNS" not in self._environ and not self.is_terminal:
            return ConsoleDimensions(max(size.width, PIPE_WIDTH), size.height)
        return size

    size = property(_size, Console.size.fset)

    def print(self, *objects, **kwargs) -> None:
        for item in objects:
            if isinstance(item, Table):
                for column in item.columns:
                    column.overflow = "fold"
        super().print(*objects, **kwargs)


console = _Console(highlight=False, soft_wrap=True)
err_console = _Console(stderr=True, highlight=False, soft_wrap=True)


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


@contextlib.contextmanager
def stage_progress(description: str) -> Iterator[Callable[[str], None]]:
    """On a terminal, a spinner with ``description``, the current step and the time
    elapsed (gone when done); in a pipe or a log, nothing. Yields ``say(message)``, which
    shows ``message`` as the current step (the ``progress=`` of the library's long work)."""
    with Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TimeElapsedColumn(),
        console=console,
        transient=True,
    ) as bar:
        task = bar.add_task(description, total=None)
        yield lambda message: bar.update(task, description=f"{description}: {message}")


@contextlib.contextmanager
def counted_progress(what: str, total: int) -> Iterator[Callable[[str], None]]:
    """On a terminal, a bar "fitting ``what``" over ``total`` items (couplings, headings)
    with the time elapsed (gone when done); in a pipe or a log, nothing. Yields
    ``say(message)``: each call after the first counts one item done and shows
    ``message`` as the current one (the ``progress=`` of the library's fits)."""
    with Progress(
        TextColumn("fitting {task.description}"),
        BarColumn(),
        TextColumn("{task.completed}/{task.total}"),
        TimeElapsedColumn(),
        console=console,
        transient=True,
    ) as bar:
        task = bar.add_task(what, total=total)
        started: list[str] = []

        def say(message: str) -> None:
            if started:
                bar.advance(task)
            started.append(message)
            bar.update(task, description=message)

        yield say


def exit_status(exc: BaseException) -> int:
    """2 for a bad argument or option (``ArgumentError``, an output that exists), 1 for
    data that cannot be used and every other error of cummins."""
    return 2 if isinstance(exc, (ArgumentError, OutputExistsError)) else 1


def report_error(exc: BaseException) -> NoReturn:
    """Print ``exc`` as one line on standard error and exit with :func:`exit_status`: the
    one place where the commands report their errors."""
    err_console.print(f"[bold red]error:[/] {escape(_one_line(exc))}")
    sys.exit(exit_status(exc))


def _one_line(exc: BaseException) -> str:
    if isinstance(exc, MemoryError):
        return (
            "not enough memory for this request"
            + (f" ({exc})" if str(exc) else "")
            + ": ask for less (a shorter run, a coarser grid, fewer DOFs)"
        )
    if isinstance(exc, OSError) and not isinstance(exc, CumminsError):
        where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
        return f"{where}{exc.strerror or exc}"
    return " ".join(str(exc).split())


@contextlib.contextmanager
def warnings_as_notes() -> Iterator[None]:
    """Show the warnings raised inside as one-line notes on standard error, each text
    once, without the source line and path Python prints."""
    seen: set[str] = set()

    def show(message, category, filename, lineno, file=None, line=None) -> None:
        text = " ".join(str(message).split())
        if text in seen:
            return
        seen.add(text)
        label = "warning" if issubclass(category, CumminsWarning) else "note"
        err_console.print(f"[yellow]{label}:[/] {escape(text)}")

    with warnings.catch_warnings():
        warnings.simplefilter("always")
        for quiet in (
            DeprecationWarning,
            PendingDeprecationWarning,
            ImportWarning,
            ResourceWarning,
        ):
            warnings.simplefilter("ignore", quiet)
        warnings.showwarning = show
        yield


def run_reporting_errors(function, *args, **kwargs):
    """Call ``function`` with warnings shown as notes; a CumminsError (or an error of the
    file system, or a lack of memory) becomes a one-line message and the exit status of
    :func:`exit_status`."""
    try:
        with warnings_as_notes():
            return function(*args, **kwargs)
    except (CumminsError, OSError, MemoryError) as exc:
        report_error(exc)


def reports_errors(func):
    """Decorator form of :func:`run_reporting_errors` for the commands."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        return run_reporting_errors(func, *args, **kwargs)

    return wrapper


class Number(click.FloatRange):
    """A finite float in a range, with its unit in the messages (``--dt 0`` → "0.0 is not
    in the range x>0 s"); NaN is refused, and infinity unless ``infinite`` (a water depth)."""

    def __init__(
        self,
        min: float | None = None,
        max: float | None = None,
        *,
        min_open: bool = False,
        max_open: bool = False,
        unit: str = "",
        infinite: bool = False,
    ) -> None:
        super().__init__(min, max, min_open=min_open, max_open=max_open)
        self.unit = unit
        self.infinite = infinite

    def convert(self, value, param, ctx):
        x = click.FLOAT.convert(value, param, ctx)
        if math.isnan(x) or (math.isinf(x) and not self.infinite):
            self.fail(f"{value!r} is not a finite number{_unit(self.unit)}", param, ctx)
        if self.min is None and self.max is None:
            return x
        return super().convert(x, param, ctx)

    def _describe_range(self) -> str:
        if self.min is None and self.max is None:
            return f"finite{_unit(self.unit)}"
        return super()._describe_range() + _unit(self.unit)


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def positive(unit: str = "") -> Number:
    """Finite and > 0 (durations, time steps, periods, lengths)."""
    return Number(0.0, min_open=True, unit=unit)


def non_negative(unit: str = "") -> Number:
    """Finite and >= 0 (wave heights, amplitudes, damping)."""
    return Number(0.0, unit=unit)


def finite(unit: str = "") -> Number:
    """Any finite number (headings, coordinates)."""
    return Number(unit=unit)


#: Headings, wave and wind directions: degrees in one turn either way (a larger value is
#: a typing error, not a direction).
HEADING_RANGE = (-360.0, 360.0)


def heading_degrees(unit: str = "deg") -> Number:
    """A direction in degrees within ±360 (:data:`HEADING_RANGE`)."""
    return Number(*HEADING_RANGE, unit=unit)


def headings_list(values, option: str = "--headings") -> list[float]:
    """Directions in degrees from a repeatable option (``--headings 0 --headings 90,180``:
    commas or spaces), each finite and within one turn (:data:`HEADING_RANGE`), none twice
    (0 and 360 are one direction)."""
    out: list[float] = []
    for value in values:
        for part in str(value).replace(",", " ").split():
            try:
                x = float(part)
            except ValueError:
                x = math.nan
            if not math.isfinite(x):
                raise click.BadParameter(
                    f"{part!r} is not a finite number of degrees", param_hint=option
                )
            if not HEADING_RANGE[0] <= x <= HEADING_RANGE[1]:
                raise click.BadParameter(
                    f"{part} deg is beyond one turn ({HEADING_RANGE[0]:g} to "
                    f"{HEADING_RANGE[1]:g} deg)",
                    param_hint=option,
                )
            twin = [
                y
                for y in out
                if math.isclose((x - y) % 360.0, 0.0, abs_tol=1e-9)
                or math.isclose((x - y) % 360.0, 360.0, abs_tol=1e-9)
            ]
            if twin:
                raise click.BadParameter(
                    f"{twin[0]:g} and {x:g} deg are one direction; give each once",
                    param_hint=option,
                )
            out.append(x)
    return out


def speed_option(help: str = "Forward speed to use when the data hold several."):
    """--speed M/S (a finite number of m/s), passed as ``speed``."""
    return click.option("--speed", type=finite("m/s"), default=None, metavar="M/S", help=help)


def main_dimensions_option(help: str):
    """--main-dimensions LPP B T (m), passed as ``main_dimensions`` (None if not given)."""
    return click.option(
        "--main-dimensions",
        type=(positive("m"), positive("m"), positive("m")),
        default=None,
        metavar="LPP B T",
        help=help,
    )


def with_main_dimensions(ds, dimensions):
    """The data with the ship's main dimensions (Lpp, B, T in m) as the attributes
    ``ship_length``, ``ship_breadth``, ``ship_draught`` (replacing the data's), said in
    ``history``; ``dimensions`` None: the data as they are."""
    if dimensions is None:
        return ds
    from cummins.hydrodb import add_history

    out = ds.copy()
    keys = ("ship_length", "ship_breadth", "ship_draught")
    for key, value in zip(keys, dimensions, strict=True):
        out.attrs[key] = float(value)
    add_history(out, "main dimensions given: Lpp, B, T = {:g}, {:g}, {:g} m".format(*dimensions))
    return out


def force_option(help: str = "Overwrite the output files."):
    """--force: overwrite outputs that exist (without it a command refuses to)."""
    return click.option("--force", is_flag=True, help=help)


def allow_other_data_option(func):
    """--allow-other-data: use a model with data whose fingerprint differs from those it
    was fitted to (a warning instead of the refusal), passed as ``allow_other_data``."""
    return click.option(
        "--allow-other-data",
        is_flag=True,
        help="Use the model with data other than those it was fitted to (their DOFs, rho, "
        "g, frequencies or A(w), B(w) differ): what differs is then a warning, not an error.",
    )(func)


def viscous_damping_option(func):
    """--viscous-damping DOF VALUE (repeatable), passed as ``viscous_damping``."""
    return click.option(
        "--viscous-damping",
        "viscous_damping",
        type=(str, non_negative()),
        multiple=True,
        metavar="DOF VALUE",
        help="Linear viscous damping B_v on a DOF, e.g. --viscous-damping Roll 5e8 (kg/s, "
        "kg m^2/s; repeatable, once per DOF), added to the data's own constant "
        "additional_damping (MSS's Bv, WAMIT's external damping). Surge, sway and yaw "
        "have no restoring: without it they drift in a simulation.",
    )(func)


def check_dof_selection(ds, dofs) -> None:
    """Refuse a ``--dof`` the data do not have (naming the DOFs they have)."""
    from cummins.dofs import named_dof_hint

    labels = [str(d) for d in ds.influenced_dof.values]
    unknown = [d for d in dofs if d not in labels]
    if unknown:
        meant = named_dof_hint(ds, unknown[0])
        raise click.BadParameter(
            f"unknown DOF {unknown[0]!r}; "
            + (f"{meant}; " if meant else "")
            + f"the data have {', '.join(labels)}",
            param_hint="--dof",
        )


def viscous_damping_values(
    pairs, labels, option: str = "--viscous-damping"
) -> dict[str, float] | None:
    """``{dof: value}`` from the (DOF, value) pairs of ``option`` (None when there are
    none)."""
    if not pairs:
        return None
    refuse_repeated(pairs, option, key=lambda pair: pair[0])
    values: dict[str, float] = {}
    for dof, value in pairs:
        if dof not in labels:
            raise click.BadParameter(
                f"unknown DOF {dof!r}; the data have {', '.join(labels)}",
                param_hint=option,
            )
        values[dof] = value
    return values


#: Where :func:`read_options` leaves the mass-property options for :func:`read_hydrodb`.
_EOM_KEY = "cummins.equation_of_motion"
#: … and ``--water-depth``.
_DEPTH_KEY = "cummins.water_depth"
_EOM_OPTIONS = (
    "mass",
    "center_of_gravity",
    "radii_of_gyration",
    "inertia_matrix",
    "external_stiffness",
    "external_damping",
    "restoring_includes_weight",
)


def _check_format(ctx, param, value):
    """--format NAME: one of the readers' names (a usage error otherwise)."""
    if value is None:
        return None
    from cummins.io import FORMATS

    names = [str(name) for name in FORMATS]
    if value.lower() not in names:
        raise click.BadParameter(f"unknown format {value!r}; choose one of {', '.join(names)}")
    return value.lower()


def format_names() -> str:
    """The formats read, ``name (what it is)``, from the readers' registry."""
    from cummins.io import FORMATS

    return "; ".join(f"{name} ({f.description})" for name, f in FORMATS.items())


def read_options(func=None, *, equation_of_motion: bool = True):
    """--format, --rho, --g, --ulen, --water-depth: how to read solver files; --mass,
    --center-of-gravity, --radii-of-gyration, --inertia-matrix, --external-stiffness,
    --external-damping: what to complete them with (the terms of the equation of motion
    that the files lack), applied by :func:`read_hydrodb`. ``equation_of_motion=False``
    (``@read_options(equation_of_motion=False)``): the reading options alone, for a
    command whose result the inertia and external terms do not change (``kernel``)."""
    if func is None:
        return functools.partial(read_options, equation_of_motion=equation_of_motion)
    decorators = [
        click.option(
            "--format",
            "format_",
            metavar="NAME",
            default=None,
            callback=_check_format,
            help=f"Solver format, detected from the content by default: {format_names()}.",
        ),
        click.option(
            "--rho",
            type=positive("kg/m^3"),
            default=None,
            metavar="KG/M3",
            help="Water density for nondimensional formats (WAMIT does not record it "
            "everywhere; default 1025).",
        ),
        click.option(
            "--g",
            "g",
            type=positive("m/s^2"),
            default=None,
            metavar="M/S2",
            help="Acceleration of gravity for nondimensional formats (default 9.81, or "
            "the value in the WAMIT .out).",
        ),
        click.option(
            "--ulen",
            type=positive("m"),
            default=None,
            metavar="M",
            help="WAMIT length scale ULEN (default: from the .out, else 1).",
        ),
        click.option(
            "--water-depth",
            type=Number(0.0, min_open=True, unit="m", infinite=True),
            default=None,
            metavar="M",
            help="Water depth in m (inf for deep water) when the files do not record it "
            "(WAMIT without its .out, NEMOH without Nemoh.cal, VERES): the depth of the "
            "wave numbers, the travel phase of the wave force and the wave loads. Default: "
            "deep water, with a warning where a result depends on it.",
        ),
    ]
    equation_of_motion_options = [
        click.option(
            "--mass",
            type=positive("kg"),
            multiple=True,
            metavar="KG",
            help="Mass of the body (repeat once per body, in their order). With "
            "--radii-of-gyration it builds the rigid-body inertia matrix when the files lack "
            "it (or replaces theirs). Default with radii given: rho times the displaced "
            "volume (a freely floating body).",
        ),
        click.option(
            "--center-of-gravity",
            type=(finite("m"), finite("m"), finite("m")),
            multiple=True,
            metavar="X Y Z",
            help="Centre of gravity in m, in the data's axes (once per body; default: the "
            "files' value).",
        ),
        click.option(
            "--radii-of-gyration",
            type=(positive("m"), positive("m"), positive("m")),
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
            "--restoring-includes-weight",
            type=click.Choice(["yes", "no"]),
            default=None,
            help="Whether the files' restoring holds the weight's terms (C44, C55 -m g z_G; "
            "C46, C56 m g x_G, m g y_G), when they do not say (OpenFAST's WAMIT files: no; "
            "`cummins info` tells what was detected). The restoring is then made that of "
            "the mass and centre of gravity of the inertia (given or the files').",
        ),
        click.option(
            "--external-stiffness",
            type=(str, str, finite()),
            multiple=True,
            metavar="DOF DOF VALUE",
            help="External stiffness (moorings, a PTO spring) added to the restoring, e.g. "
            "--external-stiffness Surge Surge 8e4 (N/m, N m/rad; repeatable; give both (i, j) and "
            "(j, i) for a symmetric coupling).",
        ),
        click.option(
            "--external-damping",
            type=(str, str, finite()),
            multiple=True,
            metavar="DOF DOF VALUE",
            help="External linear damping (a PTO, dampers) between two DOFs, e.g. "
            "--external-damping body1__Pitch body1__Pitch 1e6 (kg/s, kg m^2/s; repeatable).",
        ),
    ]

    if equation_of_motion:
        decorators += equation_of_motion_options

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        context = click.get_current_context()
        context.meta[_EOM_KEY] = {name: kwargs.pop(name) for name in _EOM_OPTIONS if name in kwargs}
        context.meta[_DEPTH_KEY] = kwargs.pop("water_depth")
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

    context = click.get_current_context(silent=True)
    depth = context.meta.get(_DEPTH_KEY) if context is not None else None
    with files_read() as used:
        ds = read(path, format=format_, rho=rho, g=g, ulen=ulen, water_depth=depth)
    note_inputs(path, *used)
    options = context.meta.get(_EOM_KEY) if context is not None else None
    if not options:
        return ds
    moving = tuple(context.params.get("dofs") or ()) if context is not None else ()
    ds = complete_equation_of_motion(ds, **options, moving=moving)
    if options.get("mass") and not (moving or context.params.get("joints")):
        from cummins.mass_properties import equilibrium_notes

        for line in equilibrium_notes(ds):  # free bodies: a mass far from ρ∇ is held
            console.print(f"note: {line}", highlight=False)
    return ds


def complete_equation_of_motion(
    ds,
    *,
    mass=(),
    center_of_gravity=(),
    radii_of_gyration=(),
    inertia_matrix=None,
    external_stiffness=(),
    external_damping=(),
    restoring_includes_weight=None,
    moving=(),
):
    """``ds`` with the inertia and external terms of the command-line options, its
    restoring holding the weight of that inertia. With ``moving`` (``--dof``) naming
    translations only, ``--mass`` needs no radii of gyration: no rotation moves, and
    1 m stands in for them (said so)."""
    from cummins.mass_properties import read_matrix_file, with_given_terms

    restoring = {"yes": "total", "no": "hydrostatic", None: None}[restoring_includes_weight]
    from cummins.dofs import is_rotation

    translations = bool(moving) and not any(is_rotation(d) for d in moving)
    if inertia_matrix is None and not radii_of_gyration and mass and translations:
        radii_of_gyration = ((1.0, 1.0, 1.0),) * len(mass)  # any: no rotation moves
        console.print(
            "radii of gyration not needed: only translations move (--dof "
            + " --dof ".join(moving)
            + "); 1 m written in their place"
        )
    for name, given in (("stiffness", external_stiffness), ("damping", external_damping)):
        refuse_repeated(given, f"--external-{name}", key=lambda t: (t[0], t[1]), what="pair")
    matrix = None
    if inertia_matrix is not None:
        note_inputs(inertia_matrix)
        matrix = read_matrix_file(inertia_matrix)
    return with_given_terms(
        ds,
        mass=mass,
        center_of_gravity=center_of_gravity,
        radii_of_gyration=radii_of_gyration,
        matrix=matrix,
        restoring=restoring,
        external_stiffness=external_stiffness,
        external_damping=external_damping,
        name=lambda key: "--" + key.replace("_", "-"),
    )


def select_speed(ds, speed: float | None):
    """The data at one forward speed (``--speed``): required when there are several, and
    one of them (within 1 mm/s), never the nearest."""
    if "forward_speed" not in ds.dims:
        if speed is not None:
            held = float(ds.forward_speed) if "forward_speed" in ds.coords else 0.0
            if not np.isfinite(speed) or abs(speed - held) > 1e-3:
                raise click.BadParameter(
                    f"the data hold one forward speed, {held:g} m/s, not {speed:g} m/s: "
                    "give data computed at that speed, or leave --speed out",
                    param_hint="--speed",
                )
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


def cummins_model_format(path) -> str | None:
    """The ``cummins_format`` attribute of a model file written by cummins (NetCDF-4:
    ``"cummins-radiation-model"``, ``"cummins-excitation-model"``), or None for any other
    file (known by its content: an HDF5 file of any name)."""
    from cummins.files import is_hdf5

    if not is_hdf5(path):
        return None
    import h5py  # here: a text file (most solvers' output) need not load it

    try:
        with h5py.File(path, "r") as f:
            kind = f.attrs.get("cummins_format")
    except OSError:
        return None
    return kind.decode() if isinstance(kind, bytes) else kind


def model_and_data(path):
    """(model or None, data path): a model file names the data it was fitted to."""
    from cummins.radiation.model import RadiationModel
    from cummins.radiation.model_file import FORMAT_NAME

    p = Path(path)
    note_inputs(p)
    if cummins_model_format(p) != FORMAT_NAME:
        return None, path
    model = RadiationModel.load(p)
    found, named = fitted_data_file(model.attrs, p)
    if found is None:
        raise click.UsageError(
            f"{p} does not name an existing data file ({named!r}, looked for as recorded "
            f"and beside the model): give the data file instead (the model is then fitted "
            "again)"
        )
    return model, str(found)


def select_body(ds, body: str, option: str = "--body"):
    """The six rigid-body DOFs of one body of a multi-body dataset (``--body N``, 1-based,
    or the body's label prefix or name), relabelled ``Surge`` … ``Yaw``, with that body's
    reference point, centre of gravity and buoyancy (:func:`cummins.select_dofs`)."""
    from cummins.hydrodb import DOF_NAMES, bodies, body_names, select_dofs

    groups = bodies(ds)
    if groups == [None]:
        raise click.BadParameter("the data hold one body: leave --body out", param_hint=option)
    names = body_names(ds)
    choices = [str(g) for g in groups]
    if str(body).isdigit() and 1 <= int(body) <= len(groups):
        k = int(body) - 1
    elif str(body) in choices:
        k = choices.index(str(body))
    elif str(body) in names and len(names) == len(groups):
        k = names.index(str(body))
    else:
        listed = ", ".join(
            f"{n + 1} ({c}{'' if len(names) != len(groups) or names[n] == c else ', ' + names[n]})"
            for n, c in enumerate(choices)
        )
        raise click.BadParameter(f"no body {body!r}; the data hold {listed}", param_hint=option)
    prefix = choices[k]
    labels = [f"{prefix}__{name}" for name in DOF_NAMES]
    have = [str(d) for d in ds.influenced_dof.values]
    missing = [label for label in labels if label not in have]
    if missing:
        raise click.BadParameter(
            f"body {prefix} lacks {', '.join(missing)}: it has no six rigid-body DOFs",
            param_hint=option,
        )
    out = select_dofs(ds, labels)
    out = out.assign_coords(
        {dim: list(DOF_NAMES) for dim in ("influenced_dof", "radiating_dof") if dim in out.coords}
    )
    for key in (
        "reference_point",
        "center_of_gravity",
        "center_of_buoyancy",
        "restoring_weight_center",
    ):
        if key in out.attrs:
            values = np.asarray(out.attrs[key], dtype=float).reshape(-1)
            if values.size == 3 * len(groups):
                out.attrs[key] = values[3 * k : 3 * k + 3]
    for key in ("restoring_weight_mass", "displaced_volume"):
        values = np.atleast_1d(np.asarray(out.attrs.get(key, []), dtype=float)).reshape(-1)
        if values.size == len(groups) > 1:
            out.attrs[key] = float(values[k])
    name = names[k] if len(names) == len(groups) else prefix
    out.attrs["body_name"] = name
    out.attrs.pop("body_names", None)
    history = str(out.attrs.get("history", ""))
    out.attrs["history"] = (history + "\n" if history else "") + (
        f"body {k + 1} of {len(groups)} ({name}) selected: its six DOFs relabelled Surge … Yaw"
    )
    return out
