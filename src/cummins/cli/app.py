"""The ``cummins`` command line.

Every command prints what it did; errors are reported in one line naming the file, line,
option or quantity at fault, without a traceback: exit status 2 for a bad option or
argument (a value out of range, an output that exists without --force, a path under a
file), 1 for data that cannot be used (and for `check`, data that fail it). Warnings are
shown once each as one-line notes.
"""

from __future__ import annotations

import atexit
import gc
import importlib
import sys
from collections.abc import Iterator
from contextlib import contextmanager

import click

from cummins._version import __version__

#: The commands, in the order ``cummins --help`` lists them, and where each is defined.
#: A command's module is imported when the command is run or its help is shown, so that
#: ``cummins --help`` and ``cummins info`` do not wait for SciPy or matplotlib.
COMMANDS: dict[str, str] = {
    "info": "cummins.cli.info:info_command",
    "check": "cummins.cli.check:check_command",
    "convert": "cummins.cli.convert:convert_command",
    "demo": "cummins.cli.demo:demo_command",
    # works without Capytaine: it then says how to install it
    "bem": "cummins.cli.bem:bem_command",
    "kernel": "cummins.cli.kernel:kernel_command",
    "fit": "cummins.cli.fit:fit_command",
    "fit-excitation": "cummins.cli.fit_excitation:fit_excitation_command",
    "reduce": "cummins.cli.reduce:reduce_command",
    "rao": "cummins.cli.rao:rao_command",
    "simulate": "cummins.cli.simulate:simulate_command",
    "identify-damping": "cummins.cli.sysid:identify_damping_command",
    "dp-demo": "cummins.cli.dp:dp_demo_command",
    "lf-model": "cummins.cli.lfmodel:lf_model_command",
    # works without Dask: it then says how to install it
    "batch": "cummins.cli.batch:batch_command",
    "report": "cummins.cli.report:report_command",
}


#: The commands that use Dask (``batch`` runs its cases on ``dask.distributed``; ``bem``
#: runs Capytaine, whose use of optional packages cummins does not control). The others
#: run with Dask kept out of xarray's sight (:func:`dask_kept_out`).
USES_DASK = frozenset({"batch", "bem"})


@contextmanager
def dask_kept_out() -> Iterator[None]:
    """Run a command that uses no Dask without xarray importing it.

    With Dask installed (the ``[dask]`` extra), xarray imports ``dask.array`` at the
    first ``Variable`` it builds, to ask whether the data are a Dask array
    (``as_compatible_data`` → ``array_type("dask")``): 0.3 s of every command, more
    than the rest of ``cummins info``. Python's documented way to make a module
    unimportable, ``sys.modules[name] = None``, makes xarray see no Dask, as in the
    default install. This is done only in a fresh process — neither Dask nor xarray
    imported yet, so that every check xarray caches (``module_available``, its duck-array
    types) says the same, "no Dask" — and Dask is importable again when the command
    ends (xarray keeps its view for the rest of the process: in-memory NumPy data,
    which is all these commands build).
    """
    fresh = not any(name in sys.modules for name in ("dask", "xarray"))
    if fresh:
        sys.modules["dask"] = None  # type: ignore[assignment]
    try:
        yield
    finally:
        if fresh and "dask" in sys.modules and sys.modules["dask"] is None:
            del sys.modules["dask"]


#: The young generation's size at which the garbage collector runs while a command runs
#: (Python's default: 700). The start-up of a command (NumPy, pandas, xarray: 70 000
#: objects that live to the end) otherwise runs some 260 collections, two of them full
#: (0.06–0.09 s of ``cummins info``) that find nothing to free; mypy runs with the same
#: setting for the same reason (``mypy.build``: ``gc.set_threshold(200 * 1000, 30, 30)``).
#: Reference cycles are still freed, later.
GC_THRESHOLD = (200_000, 30, 30)


@contextmanager
def fewer_collections() -> Iterator[None]:
    """Run a command with the garbage collector's threshold :data:`GC_THRESHOLD`, the
    previous one again afterwards."""
    before = gc.get_threshold()
    gc.set_threshold(*GC_THRESHOLD)
    try:
        yield
    finally:
        gc.set_threshold(*before)


def exit_without_collecting() -> None:
    """Have the interpreter's exit skip the garbage collector's passes over the objects
    alive then (``gc.freeze`` at exit, an ``atexit`` function run after the commands').

    At exit, Python collects garbage over every object still alive — the modules of
    NumPy, pandas, xarray, SciPy — before it frees them: 0.09 s of CPU time after
    ``cummins info`` that finds nothing to collect. Frozen objects are freed all the same
    (the memory goes back with the process); only ``__del__`` of objects in reference
    cycles, which Python does not promise to run at exit, are not run. Files are closed
    by the commands themselves, and ``atexit`` functions (h5py's, Dask's) run as before."""
    atexit.unregister(gc.freeze)  # once, however many commands run in the process
    atexit.register(gc.freeze)


class LazyGroup(click.Group):
    """A group whose commands (:data:`COMMANDS`) are imported when first asked for, and
    run with fewer garbage collections (:func:`fewer_collections`,
    :func:`exit_without_collecting`) and without Dask unless they use it
    (:data:`USES_DASK`)."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return [*COMMANDS, *(n for n in super().list_commands(ctx) if n not in COMMANDS)]

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name in self.commands or cmd_name not in COMMANDS:
            return super().get_command(ctx, cmd_name)
        module, _, name = COMMANDS[cmd_name].partition(":")
        command = getattr(importlib.import_module(module), name)
        self.commands[cmd_name] = command
        return command

    def resolve_command(self, ctx: click.Context, args: list[str]):
        # before the command's module is imported (it may import xarray); the group's
        # context leaves dask_kept_out when the command has run
        if args and args[0] in COMMANDS and not ctx.resilient_parsing:
            exit_without_collecting()
            ctx.with_resource(fewer_collections())
            if args[0] not in USES_DASK:
                ctx.with_resource(dask_kept_out())
        return super().resolve_command(ctx, args)

    def format_help_text(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        super().format_help_text(ctx, formatter)
        formatter.write_paragraph()
        with formatter.indentation():
            formatter.write_text(formats_read())


def formats_read() -> str:
    """The sentence of ``cummins --help`` that lists the formats read, from the readers'
    registry (:data:`cummins.io.FORMATS`)."""
    from cummins.io import FORMATS

    listed = "; ".join(f.description for f in FORMATS.values())
    return (
        f"Formats read (detected from the content, or --format NAME): {listed}. "
        "Nondimensional files (WAMIT, HAMS) take --rho, --g and --ulen."
    )


@click.group(
    cls=LazyGroup,
    context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100},
)
@click.version_option(__version__, "--version", "-V", prog_name="cummins")
def main() -> None:
    """cummins: from frequency-domain hydrodynamics to time-domain vessel models.

    \b
    The pipeline, one command per stage:
      cummins info FILE        what is in a solver output file (or folder)
      cummins check FILE       is the data physically usable? (symmetry, B >= 0, A-inf, decay)
      cummins convert IN OUT   write NetCDF (.nc), BEMIO .h5 (WEC-Sim), WAMIT .1/.3/.hst
                               or a QTF .12d/.12s (HydroDyn), an MSS vessel struct (.mat)
      cummins bem MESH         compute a database with Capytaine (pip install cummins[bem])
      cummins kernel FILE      retardation functions K(t), A-infinity, causality diagnostics
      cummins fit FILE         stable, passive state-space models of the fluid memory
      cummins fit-excitation FILE
                               causal state-space models of the wave excitation (OpenFAST)
      cummins reduce MODEL     fewer states by balanced truncation, passive again
      cummins rao DATA         coupled motion RAOs, frequency domain (the reference)
      cummins simulate DATA    the vessel in regular or irregular waves, time domain
      cummins identify-damping RECORDS --model DATA
                               viscous (roll) damping from motion records or decays
      cummins dp-demo -o DIR   the nonlinear 6-DOF DP model (Smogeli et al., 2004) on the S-175
      cummins lf-model DATA    constant-coefficient manoeuvring model (Ross, Perez & Fossen, 2006)
      cummins batch STUDY      many cases (headings x sea states) on Dask; operability
      cummins report FILE      a self-contained HTML page of a data, model, run or results file
      cummins demo             run all of it on a bundled real vessel (WAMIT tanker)

    Run `cummins COMMAND --help` for the options of a command.
    """


if __name__ == "__main__":  # pragma: no cover
    main()
