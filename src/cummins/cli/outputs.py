"""The files a command writes, checked before any work: no output over an existing file
without ``--force``, none under a file or in a folder that cannot be written, two outputs
never on one file, and never an output over a file the command reads (its data, a run's
companion files, a model, a study), ``--force`` or not (:func:`prepare_outputs`,
:func:`note_inputs`)."""

from __future__ import annotations

import os
from pathlib import Path

import click

from cummins.errors import ArgumentError, check_writable
from cummins.files import refuse_overwriting_inputs

#: Where the files a command reads and writes are kept (``click.Context.meta``).
_FILES_KEY = "cummins.files"


def _command_files() -> dict[str, list[Path]] | None:
    context = click.get_current_context(silent=True)
    if context is None:
        return None
    return context.meta.setdefault(_FILES_KEY, {"inputs": [], "outputs": []})


def _parameters() -> list[tuple[click.Parameter, str, list]]:
    """The command's parameters with a label (the longest option name, or the argument's
    name) and the paths among their values."""
    context = click.get_current_context(silent=True)
    if context is None:
        return []
    out = []
    for param in context.command.params:
        value = context.params.get(param.name or "")
        values = list(value) if isinstance(value, (list, tuple)) else [value]
        if isinstance(param, click.Option):
            label = max(param.opts, key=len)
        else:
            label = param.human_readable_name
        out.append((param, label, [v for v in values if isinstance(v, (str, os.PathLike))]))
    return out


def _output_labels(outputs: list[Path]) -> list[str | None]:
    """The option (or argument) each output was given as, in order: options first, then
    arguments from the last (outputs follow inputs on a command line)."""
    params = _parameters()
    ordered = [p for p in params if isinstance(p[0], click.Option)]
    ordered += [p for p in reversed(params) if not isinstance(p[0], click.Option)]
    used: set[tuple[int, int]] = set()
    labels: list[str | None] = []
    for path in outputs:
        label = None
        for k, (_, name, values) in enumerate(ordered):
            for m, value in enumerate(values):
                if (k, m) not in used and Path(value) == Path(path):
                    used.add((k, m))
                    label = name
                    break
            if label:
                break
        labels.append(label)
    return labels


def _argument_inputs(outputs: list[Path]) -> list[Path]:
    """The command's positional arguments that name existing files (DATA, MODEL, PATH …):
    inputs known before anything is read. An argument is an output (``convert``'s
    DESTINATION) when its value is an output that no option gives."""
    params = _parameters()
    by_options = {
        os.fspath(v)
        for param, _, values in params
        if isinstance(param, click.Option)
        for v in values
    }
    wanted = {os.fspath(o) for o in outputs}
    found = []
    for param, _, values in params:
        if isinstance(param, click.Option):
            continue
        for value in values:
            path = Path(value)
            is_output = os.fspath(path) in wanted and os.fspath(path) not in by_options
            if path.is_file() and not is_output:
                found.append(path)
    return found


def note_inputs(*paths) -> None:
    """Record files the command reads (:func:`read_hydrodb` adds a run's companion files:
    :func:`cummins.files.files_read`); an output of the same command that is one of them
    is refused (:func:`cummins.files.refuse_overwriting_inputs`), ``--force`` or not."""
    files = _command_files()
    if files is None:
        return
    files["inputs"].extend(Path(p) for p in paths if p)
    refuse_overwriting_inputs(
        files["outputs"], files["inputs"], labels=_output_labels(files["outputs"])
    )


def prepare_outputs(*paths, force: bool, folders=()) -> None:
    """Before any work: refuse to overwrite without ``--force``, refuse a path under an
    existing file (or a folder where a file is to be written), two outputs on one file,
    and an output over a file the command reads (:func:`note_inputs`: whichever of the
    two is called first, the second refuses), create missing folders.

    ``folders`` are output folders (``--plot DIR``): checked the same way, not created.
    """
    files = [Path(p) for p in paths if p]
    dirs = [Path(p) for p in folders if p]
    known = _command_files()
    if known is not None:
        known["inputs"].extend(_argument_inputs(files))
        known["outputs"].extend(files)
        refuse_overwriting_inputs(
            known["outputs"], known["inputs"], labels=_output_labels(known["outputs"])
        )
    else:
        refuse_overwriting_inputs(files, ())
    for path in files:
        if path.is_dir() and path.suffix.lower() != ".zarr":  # a Zarr store is a folder
            raise ArgumentError(
                f"{path} is a folder: cannot write a file there",
                hint="Give the name of a file",
            )
        check_writable(path, force)
    for path in [*files, *dirs]:
        _check_parents(path)
    for path in dirs:
        if path.exists() and not path.is_dir():
            raise ArgumentError(
                f"{path} is a file, not a folder", hint="Give the name of a folder for the output"
            )
    for path in files:
        path.parent.mkdir(parents=True, exist_ok=True)


def _check_parents(path: Path) -> None:
    """ArgumentError when a folder above ``path`` exists as a file or is not writable."""
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise ArgumentError(
                    f"cannot write {path}: {parent} is a file, not a folder",
                    hint="Choose an output path in a folder",
                )
            if not os.access(parent, os.W_OK | os.X_OK):
                raise ArgumentError(
                    f"cannot write {path}: the folder {parent} is not writable",
                    hint="Choose an output path in a folder you may write to",
                )
            return


def output_written(path) -> None:
    """``path`` is written: from now on the command may read it (``batch --example``
    writes the study, then runs it), so it is no longer guarded as an output."""
    files = _command_files()
    if files is not None:
        files["outputs"] = [p for p in files["outputs"] if Path(p) != Path(path)]
