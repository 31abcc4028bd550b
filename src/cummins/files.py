"""The files a call reads and writes: which files a read used, and how an output replaces
an earlier one.

* :func:`files_read` records the files the readers open inside it (the readers call
  :func:`note_read` where they open a file they take numbers from: a WAMIT run's ``.3``,
  ``.hst``, ``.frc`` and ``.out``, a HAMS project's ``Hydrostatic.in``, NEMOH's
  ``KH.dat`` …; files only sniffed for their format are not recorded). The command line
  refuses to write an output over any of them (:func:`same_file`), ``--force`` or not.
* :func:`replacing` writes an output through a temporary file of its own in the target
  folder (a unique name, so two runs writing the same path at once do not share it) and
  renames it over the target at the end (:func:`os.replace`, atomic on one file system):
  a failure leaves the earlier file as it was and no half-written one.
* :func:`fitted_data_file` finds the data file a saved model was fitted to.
* :func:`is_hdf5` tells an HDF5 file (NetCDF-4, a cummins model or result, BEMIO's
  ``.h5``) by its content, whatever its name.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterable, Iterator, Sequence
from contextvars import ContextVar
from pathlib import Path

_READ: ContextVar[list[Path] | None] = ContextVar("cummins_files_read", default=None)


def note_read(path: str | os.PathLike[str]) -> None:
    """Record ``path`` as read by the innermost :func:`files_read` (nothing outside one)."""
    record = _READ.get()
    if record is not None:
        record.append(Path(path))


@contextlib.contextmanager
def files_read() -> Iterator[list[Path]]:
    """Collect the files the readers open inside the ``with`` block.

    Yields
    ------
    list of Path
        Filled as the readers open files (in that order, possibly with repetitions).

    Examples
    --------
    >>> import cummins
    >>> from cummins.files import files_read
    >>> with files_read() as used:
    ...     ds = cummins.read(cummins.demo_files() / "tanker.1")
    >>> sorted({p.suffix for p in used})
    ['.1', '.3', '.frc', '.hst', '.out']
    """
    record: list[Path] = []
    outer = _READ.get()
    token = _READ.set(record)
    try:
        yield record
    finally:
        _READ.reset(token)
        if outer is not None:
            outer.extend(record)


def same_file(a: str | os.PathLike[str], b: str | os.PathLike[str]) -> bool:
    """Whether ``a`` and ``b`` name one file: the same resolved path (symbolic links and
    ``..`` followed), or, when both exist, the same inode (a hard link, another mount)."""
    pa, pb = Path(a), Path(b)
    if os.path.normcase(os.path.realpath(pa)) == os.path.normcase(os.path.realpath(pb)):
        return True
    try:
        return pa.exists() and pb.exists() and os.path.samefile(pa, pb)
    except OSError:
        return False


@contextlib.contextmanager
def replacing(path: str | os.PathLike[str]) -> Iterator[Path]:
    """A temporary path to write ``path`` through: renamed over ``path`` when the block
    ends without an exception, removed otherwise.

    The temporary file is created in ``path``'s folder with a unique name
    (:func:`tempfile.mkstemp`: ``.<name>.<random>.tmp``), so concurrent writers of one
    path never share it; the last to finish wins, and neither fails.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "out.txt"
    >>> with replacing(target) as tmp:
    ...     _ = tmp.write_text("done")
    >>> target.read_text()
    'done'
    """
    target = Path(path)
    handle, name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    os.close(handle)
    tmp = Path(name)
    try:
        yield tmp
        # mkstemp makes the file private (0600): an output keeps the mode of the file it
        # replaces, or gets that of an ordinary new file
        mode = target.stat().st_mode & 0o777 if target.exists() else 0o644
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    finally:
        if tmp.exists():
            tmp.unlink()


def write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` through :func:`replacing`; no overwrite check
    (the callers do it)."""
    target = Path(path)
    with replacing(target) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return target


def refuse_overwriting_inputs(
    outputs: Iterable[str | os.PathLike[str] | None],
    inputs: Iterable[str | os.PathLike[str]],
    *,
    labels: Sequence[str | None] = (),
) -> None:
    """Raise :class:`~cummins.errors.ArgumentError` when an output is one of the files
    read (:func:`same_file`), or two outputs are one file: ``force`` never allows it.

    Parameters
    ----------
    outputs
        The files to be written (``None`` entries are skipped).
    inputs
        The files read (a run's companion files included: :func:`files_read`).
    labels
        Optional names of the outputs for the message (the option each was given as),
        in their order.
    """
    from cummins.errors import ArgumentError

    given = [(Path(p), k) for k, p in enumerate(outputs) if p]
    read = [Path(p) for p in dict.fromkeys(os.fspath(p) for p in inputs)]

    def label(index: int, path: Path) -> str:
        what = labels[index] if index < len(labels) else None
        return f"{what} {path}" if what else str(path)

    for n, (out, k) in enumerate(given):
        for other, m in given[:n]:
            if same_file(out, other):
                raise ArgumentError(
                    f"{label(m, other)} and {label(k, out)} name one file: two outputs "
                    "cannot share it",
                    hint="Give each output its own file name",
                )
        if not out.exists():
            continue  # a file that does not exist yet is read by no one
        for source in read:
            if same_file(out, source):
                also = "" if out.name == source.name else f" (as {source})"
                raise ArgumentError(
                    f"{label(k, out)} is a file this command reads{also}: writing the output "
                    "there would destroy its input, with --force or not",
                    hint="Give the output another name",
                )


#: The HDF5 format signature (HDF5 File Format Specification, "Format Signature").
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"


def is_hdf5(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` is an HDF5 file, by its content: the HDF5 signature at byte 0, or
    at 512, 1024, 2048 … bytes after a user block (where the HDF5 specification lets the
    superblock begin), whatever the file is called. False for a folder, a missing or an
    unreadable file.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.NamedTemporaryFile(suffix=".model", delete=False) as f:
    ...     _ = f.write(bytes(512) + HDF5_SIGNATURE)  # after a user block of 512 bytes
    >>> is_hdf5(f.name), is_hdf5(tempfile.gettempdir())
    (True, False)
    """
    try:
        with open(path, "rb") as f:
            size = os.fstat(f.fileno()).st_size
            offset = 0
            while offset + len(HDF5_SIGNATURE) <= size:
                f.seek(offset)
                if f.read(len(HDF5_SIGNATURE)) == HDF5_SIGNATURE:
                    return True
                offset = 512 if offset == 0 else 2 * offset
    except OSError:
        return False
    return False


def fitted_data_file(attrs, model_path: str | os.PathLike[str]) -> tuple[Path | None, str | None]:
    """(the data file a saved model was fitted to, or None; the name recorded). The file
    ``cummins fit`` was given (``data_file``), else the solver file the data name
    (``source_file``: a NetCDF written by ``convert`` keeps its solver's, so a model fitted
    to it before ``data_file`` existed names the solver file); as recorded (a relative
    path from the current folder), else by its name beside the model file (a folder moved
    or copied whole)."""
    named = attrs.get("data_file") or attrs.get("source_file")
    if not named:
        return None, None
    for candidate in (Path(str(named)), Path(model_path).parent / Path(str(named)).name):
        if candidate.is_file():
            return candidate, str(named)
    return None, str(named)
