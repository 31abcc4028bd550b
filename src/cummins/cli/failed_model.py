"""A failed model never flows on silently: the one line the commands print when a
radiation model they use missed its fit targets, and what their result files record.

``cummins fit`` writes what makes a model a failure into the model file
(``attrs["failures"]``: not passive, a coupling the passivity step took below its
target, a motion error above twice its target; exit status 3). ``simulate``, ``reduce``,
``report`` and ``convert --model`` (the BEMIO .h5 for WEC-Sim) given such a model, and
``simulate`` fitting one on the fly, say so in one line, and ``simulate``'s run file and
the reduced model carry the failures (``model_failures``; the reduced model in its own
``failures``). ``cummins
fit-excitation`` records its failures the same way (a DOF above its NRMSE target; exit
status 3), and ``report`` of its model file says so in the same line.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from rich.markup import escape

from cummins.cli.common import err_console
from cummins.radiation.model import MODEL_FAILURES as ATTRIBUTE
from cummins.radiation.model import model_failures as model_failures

#: The line names this many failures (the motion error first), then how many more.
SHOWN = 2

#: How the line names the model, by where it comes from.
_WHOSE = {
    "model": "this model missed its fit targets",
    "fitted": "the radiation model fitted to these data missed its targets",
    "result": "the radiation model this file was made with missed its fit targets",
}


def failed_model_line(
    failures: list[str], source: str, kind: str = "model", command: str = "cummins fit"
) -> str:
    """The one line: where the model comes from (``kind``: ``"model"`` a model file,
    ``"fitted"`` fitted on the fly to the data ``source``, ``"result"`` a file made with
    a model), what it missed (each failure up to its first parenthesis), the exit status
    of the ``command`` that fitted it, and that the results inherit it."""
    short = [f.split(" (")[0].rstrip(":;, ") for f in failures]
    short.sort(key=lambda f: not f.startswith("motion error"))  # what users check first
    missed = "; ".join(short[:SHOWN])
    if len(short) > SHOWN:
        missed += f" and {len(short) - SHOWN} more"
    status = f"{command} would exit 3" if kind == "fitted" else f"{command} exit 3"
    return f"{source}: {_WHOSE[kind]}: {missed} ({status}); results inherit it"


def warn_failed_model(
    attrs: Mapping, source, kind: str = "model", command: str = "cummins fit"
) -> dict[str, str]:
    """Print the one line (:func:`failed_model_line`) when ``attrs`` (a model's, or a
    result file's) hold failures; return the attributes a result made with that model
    records (empty when none)."""
    failures = model_failures(attrs)
    if not failures:
        return {}
    name = Path(str(source)).name if source else "the model"
    err_console.print(
        f"[yellow]warning:[/] {escape(failed_model_line(failures, name, kind, command))}"
    )
    return {ATTRIBUTE: "\n".join(failures)}


def warn_failed_file(path) -> None:
    """:func:`warn_failed_model` of a file's own attributes when it is a NetCDF-4 file made
    by cummins (a radiation or excitation model, a run, an RAO file); other files say
    nothing."""
    from cummins.files import is_hdf5

    p = Path(path)
    if not is_hdf5(p):  # by content, as the report tells the kind: any name
        return
    import h5py

    from cummins.errors import HydroDataError
    from cummins.io.netcdf.attributes import decode_attributes

    try:
        with h5py.File(p, "r") as f:
            attrs = decode_attributes(dict(f.attrs), p)
    except (OSError, HydroDataError):
        return  # not HDF5 (a NetCDF-3 data file), or damaged: the report says so
    attrs = {k: v.decode() if isinstance(v, bytes) else v for k, v in attrs.items()}
    from cummins.excitation_model.model_file import FORMAT_NAME as EXCITATION

    command = (
        "cummins fit-excitation" if attrs.get("cummins_format") == EXCITATION else "cummins fit"
    )
    kind = "model" if attrs.get("failures") else "result"
    warn_failed_model(attrs, p, kind, command)
