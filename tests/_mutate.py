"""Damaged copies of real solver files, and the rule every reader must keep with them.

A reader given a damaged file may do one of three things:

* raise :class:`~cummins.HydroDataError` (the message names the file),
* read it with a :class:`~cummins.HydroDataWarning` that says what was lost,
* read exactly the data of the undamaged file (the damage hit a part it does not use:
  a comment, a blank line, a log section, the order of self-describing rows).

Anything else is a defect: another exception, or *different numbers read silently*.
Changes of encoding (UTF-8 byte-order mark, CRLF or CR-only line ends, tabs for spaces)
are not damage: the data must read identically, without a warning.

Besides damage to the text or the bytes (:meth:`Damager.cases`), a file may be damaged
in its *quantities* (:meth:`Damager.quantity_cases`, issue 31): a quantity scaled by 10³
or 10⁻³ or of the wrong sign (a column of a table in every row, as a unit or a sign lost
by a program would do it; a numeric array of a binary file), a companion file emptied,
or one the run always has (:attr:`FuzzCase.removable`) removed. Each number of such a
file still looks like a number: the physics of a floating body has to tell
(:mod:`cummins.check.plausibility`, whose errors :func:`cummins.read` warns about). The
quantities are declared per case (:attr:`FuzzCase.quantities`): those a relation ties to
the others; the test files say which they leave out and why.

Used by the ``test_fuzz_*.py`` files (a few hundred seeded cases per format in CI) and
by ``benchmarks/fuzz_readers.py`` (as many as you like).
"""

from __future__ import annotations

import dataclasses
import random
import shutil
import tempfile
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np
import xarray as xr

import cummins
from cummins import CumminsError, HydroDataError, HydroDataWarning

#: Mutations of a text file. Each changes the file in a way a reader can notice.
TEXT_OPS = ("delete", "duplicate", "swap", "truncate", "garble", "insert", "blank", "cut_line")
#: Junk written into a field by "garble"/"insert": none of it is a plausible number,
#: so a reader that takes it silently has read damage as data.
JUNK = ("1.2.3", "abc", "NaN", "-inf", "1e999", "***", "", "-9.99e99x", "nan nan")
#: Encodings that are not damage.
ENCODINGS = ("bom", "crlf", "cr", "tabs")
#: Damage to a quantity: a column or array scaled by 10^3, 10^-3, or negated.
NUMERIC_OPS = ("scale_up", "scale_down", "negate")
FACTORS = {"scale_up": 1e3, "scale_down": 1e-3, "negate": -1.0}
#: Damage to a companion file: emptied (every target), removed (``FuzzCase.removable``).
FILE_OPS = ("empty", "remove")


@dataclasses.dataclass(frozen=True)
class FuzzCase:
    """A real run to damage.

    Attributes
    ----------
    name
        Test id.
    folder
        The run's folder, relative to ``../shared/data`` (copied whole, recursively).
    entry
        What to read, relative to ``folder`` (``"."`` for the folder itself).
    targets
        Files to damage, relative to ``folder`` (one is chosen per case).
    format
        ``format=`` for :func:`cummins.read` (``None``: detected).
    options
        Further keyword arguments for :func:`cummins.read` (``rho``, ``g`` …).
    swap_blind
        Files whose rows carry no label (wrapped continuation lines, unlabelled matrix
        rows, the same DOF's row in another frequency block): two of their lines swapped
        leave no trace any reader could see. Such swaps are judged ``blind``, counted but
        not a failure; the test that lists a file here says why. An entry
        ``"file:first-last"`` limits this to swaps of two lines within those lines
        (1-based, inclusive), ``"file:same-label"`` to swaps of two rows with the same
        label (the same leading integers, e.g. DOF index I or I J, or the same matrix row
        name X … RZ, and as many fields)
        in blocks told apart only by a header line: the rest of the file is judged as
        usual.
    removable
        Companion files the run always has (the solver or its mesher writes them each
        time: HAMS's ``Input/Hydrostatic.in``, NEMOH's ``KH.dat``): removed, the reader
        must warn, as for a damaged one (:data:`FILE_OPS`).
    quantities
        Quantities of the targets that physics ties to the others (so that a factor of
        10³ or a sign in them must be seen): ``"file:fields"`` for a column of a text
        file (fields 1-based: ``"4"``, ``"4+6+7"`` for |F|, Re F, Im F together,
        ``"2::2"`` for every second field from the second), ``"file:array"`` for a
        binary file (an HDF5 dataset, a MATLAB struct field ``"vessel.A"``); a third
        part ``":scale"`` or ``":negate"`` limits the operations (the sign of a complex
        force is only a phase: no relation sees it).
    reader
        The public function that reads ``entry`` when it is not :func:`cummins.read`
        (an OpenFAST ``.ss`` file, an MSS ``RAO`` struct): called with the path, it
        returns an :class:`xarray.Dataset` or :class:`xarray.DataArray` holding every
        number the function reads (``format`` and ``options`` are then not used).
    """

    name: str
    folder: str
    entry: str
    targets: tuple[str, ...]
    format: str | None = None
    options: tuple[tuple[str, object], ...] = ()
    swap_blind: tuple[str, ...] = ()
    reader: Callable[[Path], xr.Dataset | xr.DataArray] | None = None
    removable: tuple[str, ...] = ()
    quantities: tuple[str, ...] = ()


@dataclasses.dataclass(frozen=True)
class Outcome:
    kind: str  # "error", "warned", "same", "different", "crash", "blind" (see swap_blind)
    detail: str


def mutate_text(text: str, op: str, rng: random.Random) -> str:
    """``text`` with one seeded mutation ``op`` (see :data:`TEXT_OPS`)."""
    lines = text.splitlines()
    n = len(lines)
    if n == 0:
        return text
    i, j = rng.randrange(n), rng.randrange(n)
    junk = rng.choice(JUNK)
    if op == "delete":
        del lines[i]
    elif op == "duplicate":
        lines.insert(i, lines[i])
    elif op == "swap":
        lines[i], lines[j] = lines[j], lines[i]
    elif op == "truncate":
        return text[: rng.randrange(max(len(text), 1))]
    elif op == "garble":
        fields = lines[i].split()
        if fields:
            fields[rng.randrange(len(fields))] = junk
            lines[i] = "  ".join(fields)
    elif op == "insert":
        lines.insert(i, junk)
    elif op == "blank":
        lines[i] = ""
    elif op == "cut_line":
        lines[i] = lines[i][: rng.randrange(max(len(lines[i]), 1))]
    else:
        raise ValueError(op)
    return "\n".join(lines) + "\n"


def _quantity(entry: str) -> tuple[str, str, tuple[str, ...]]:
    """(target, selector, operations) of a :attr:`FuzzCase.quantities` entry."""
    target, _, selector = entry.partition(":")
    for suffix, ops in ((":scale", ("scale_up", "scale_down")), (":negate", ("negate",))):
        if selector.endswith(suffix):
            return target, selector.removesuffix(suffix), ops
    return target, selector, NUMERIC_OPS


def _real(field: str) -> float | None:
    """The value of a field written as a real number (a point or an exponent: integers
    are indices and flags, not quantities), else None."""
    if not any(c in field for c in ".eEdD") or field.lstrip("+-")[:1].isalpha():
        return None
    try:
        value = float(field.replace("D", "E").replace("d", "e"))
    except ValueError:
        return None
    return value if np.isfinite(value) else None


def _fields(selector: str, count: int) -> list[int]:
    """0-based field indices of ``"4"``, ``"4+6+7"`` or ``"2::2"`` (every second from 2)
    in a row of ``count`` fields (1-based in the selector, as an editor counts)."""
    if "::" in selector:
        start, step = (int(v) for v in selector.split("::"))
        return list(range(start - 1, count, step))
    return [int(v) - 1 for v in selector.split("+")]


def scale_column(text: str, selector: str, op: str) -> str:
    """``text`` with the fields of ``selector`` (:func:`_fields`) scaled (:data:`FACTORS`)
    in every row where they all are real numbers (a point or an exponent: integers are
    indices and flags): a column of a table, as a unit or a sign lost by a program would
    change it."""
    lines = text.splitlines()
    factor = FACTORS[op]
    for j, line in enumerate(lines):
        fields = line.split()
        index = _fields(selector, len(fields))
        if not index or max(index) >= len(fields):
            continue
        values = [_real(fields[k]) for k in index]
        if any(v is None for v in values):
            continue
        for k, value in zip(index, values, strict=True):
            fields[k] = f"{value * factor:.6E}"
        indent = line[: len(line) - len(line.lstrip())]
        lines[j] = indent + "  ".join(fields)
    return "\n".join(lines) + "\n"


def scale_array(path: Path, name: str, op: str) -> None:
    """Scale (:data:`FACTORS`) the numeric array ``name`` of a binary file in place: an
    HDF5 dataset (NetCDF-4, BEMIO; ``"a+b"`` for several), or a field of a MATLAB struct
    (``"vessel.A"``; every cell of a cell array: ``"vessel.forceRAO.amp"``)."""
    factor = FACTORS[op]
    if path.read_bytes()[:4] == b"\x89HDF":
        import h5py

        with h5py.File(path, "r+") as f:
            for part in name.split("+"):
                f[part][...] = f[part][()] * factor
        return
    import scipy.io

    content = scipy.io.loadmat(path, squeeze_me=False, struct_as_record=True)
    keys = name.split(".")
    holder, value = None, content[keys[0]]
    for key in keys[1:]:
        holder, value = value.flat[0], value.flat[0][key]
    if value.dtype == object:
        for k in range(value.size):
            value.flat[k] = value.flat[k] * factor
    else:
        holder[keys[-1]] = value * factor
    scipy.io.savemat(path, {k: v for k, v in content.items() if not k.startswith("__")})


def encode_text(text: str, encoding: str) -> bytes:
    """``text`` re-encoded in a way that is not damage (see :data:`ENCODINGS`)."""
    body = text.replace("\r\n", "\n").replace("\r", "\n")
    if encoding == "bom":
        return b"\xef\xbb\xbf" + body.encode("utf-8")
    if encoding == "crlf":
        return body.replace("\n", "\r\n").encode("utf-8")
    if encoding == "cr":
        return body.replace("\n", "\r").encode("utf-8")
    if encoding == "tabs":
        return "\n".join(line.replace("  ", "\t") for line in body.split("\n")).encode("utf-8")
    raise ValueError(encoding)


def mutate_bytes(data: bytes, rng: random.Random) -> bytes:
    """Binary damage: truncation, or a run of flipped bytes."""
    n = len(data)
    if rng.random() < 0.5:
        return data[: rng.randrange(max(n, 1))]
    buf = bytearray(data)
    start = rng.randrange(n)
    for k in range(1 + rng.randrange(16)):
        buf[(start + 37 * k) % n] ^= 0xFF
    return bytes(buf)


def _read(path: Path, case: FuzzCase) -> tuple[xr.Dataset, list[str]]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if case.reader is None:
            ds = cummins.read(path, format=case.format, **dict(case.options))
        else:
            ds = case.reader(path)
            if isinstance(ds, xr.DataArray):
                ds = ds.to_dataset(name=ds.name or "data")
    damage = [str(w.message) for w in caught if issubclass(w.category, HydroDataWarning)]
    return ds, damage


def same_data(a: xr.Dataset, b: xr.Dataset) -> str | None:
    """``None`` when two datasets hold the same numbers, else what differs."""
    for name in sorted(set(a.data_vars) | set(b.data_vars)):
        if name not in a or name not in b:
            return f"variable {name} only in {'the original' if name in a else 'the copy'}"
    for name in sorted(set(a.variables)):
        va, vb = a[name], b[name]
        if va.dims != vb.dims or va.shape != vb.shape:
            return f"{name}: shape {dict(va.sizes)} vs {dict(vb.sizes)}"
        x, y = np.asarray(va.values), np.asarray(vb.values)
        if x.dtype.kind in "fc" or y.dtype.kind in "fc":
            if not np.allclose(x, y, rtol=1e-9, atol=0.0, equal_nan=True):
                k = np.unravel_index(np.argmax(np.abs(x - y)), x.shape) if x.shape else ()
                return f"{name}{list(k)}: {x[k] if x.shape else x} vs {y[k] if y.shape else y}"
        elif not np.array_equal(x, y):
            return f"{name}: values differ"
    return None


class Damager:
    """Copies of one case, damaged or re-encoded, read and judged against the original."""

    def __init__(self, shared_data: Path, case: FuzzCase) -> None:
        self.case = case
        self.source = shared_data / case.folder
        self._tmp = tempfile.TemporaryDirectory()
        self.work = Path(self._tmp.name) / "run"
        shutil.copytree(self.source, self.work)
        self.original, self.original_warnings = _read(self.work / case.entry, case)

    def close(self) -> None:
        self._tmp.cleanup()

    def __enter__(self) -> Damager:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _restore(self, target: str) -> None:
        shutil.copy(self.source / target, self.work / target)

    def judge(self, target: str, content: bytes | None, *, encoding_only: bool = False) -> Outcome:
        """Write ``content`` over ``target`` (None: remove it; the file as it is when the
        caller damaged it in place: ``...``), read the case, and say what the reader did."""
        path = self.work / target
        if content is None:
            path.unlink()
        elif content is not ...:
            path.chmod(0o644)
            path.write_bytes(content)
        try:
            ds, damage = _read(self.work / self.case.entry, self.case)
        except HydroDataError as exc:
            if encoding_only:
                return Outcome("different", f"re-encoding is not damage, but: {exc}")
            text = str(exc)
            if not text.strip():
                return Outcome("crash", "HydroDataError without a message")
            return Outcome("error", text)
        except CumminsError as exc:  # another family member: acceptable, but say so
            return Outcome("error", f"{type(exc).__name__}: {exc}")
        except Exception as exc:  # anything else is the defect we look for
            return Outcome("crash", f"{type(exc).__name__}: {exc}")
        finally:
            self._restore(target)
        new = [w for w in damage if w not in self.original_warnings]
        if new and not encoding_only:
            return Outcome("warned", new[0])
        difference = same_data(self.original, ds)
        if difference is None:
            return Outcome("same", "")
        return Outcome("different", difference)

    def cases(self, n: int, seed: int) -> Iterator[tuple[str, str, Outcome]]:
        """``n`` seeded damaged copies: (target, mutation, outcome)."""
        rng = random.Random(seed)
        for _ in range(n):
            target = rng.choice(self.case.targets)
            data = (self.source / target).read_bytes()
            if _is_binary(data):
                yield target, "bytes", self.judge(target, mutate_bytes(data, rng))
                continue
            op = rng.choice(TEXT_OPS)
            text = data.decode("utf-8", errors="replace")
            content = mutate_text(text, op, rng).encode("utf-8")
            if content == data:
                continue
            outcome = self.judge(target, content)
            if op == "swap" and outcome.kind == "different" and self._blind(target, text, content):
                outcome = Outcome("blind", outcome.detail)
            yield target, op, outcome

    def quantity_cases(
        self, n: int | None = None, seed: int = 0
    ) -> Iterator[tuple[str, str, Outcome]]:
        """Copies damaged in a declared quantity (:attr:`FuzzCase.quantities`, each with
        its operations of :data:`NUMERIC_OPS`): every one (``n`` None) or ``n`` seeded
        picks; then every target emptied and every :attr:`FuzzCase.removable` file
        removed (:data:`FILE_OPS`): (target, mutation, outcome)."""
        pairs = [
            (target, selector, op)
            for target, selector, ops in map(_quantity, self.case.quantities)
            for op in ops
        ]
        if n is not None:
            rng = random.Random(seed)
            pairs = [rng.choice(pairs) for _ in range(n)] if pairs else []
        for target, selector, op in pairs:
            data = (self.source / target).read_bytes()
            if _is_binary(data):
                path = self.work / target
                path.chmod(0o644)
                scale_array(path, selector, op)
                outcome = self.judge(target, ...)
            else:
                text = data.decode("utf-8", errors="replace")
                outcome = self.judge(target, scale_column(text, selector, op).encode("utf-8"))
            yield target, f"{op} {selector}", outcome
        for target in self.case.targets:
            yield target, "empty", self.judge(target, b"")
        for target in self.case.removable:
            yield target, "remove", self.judge(target, None)

    def _blind(self, target: str, text: str, content: bytes) -> bool:
        """Whether the swap that made ``content`` is one :attr:`FuzzCase.swap_blind` allows."""
        if target in self.case.swap_blind:
            return True
        before, after = text.splitlines(), content.decode("utf-8").splitlines()
        moved = [k + 1 for k, (x, y) in enumerate(zip(before, after, strict=False)) if x != y]
        for entry in self.case.swap_blind:
            name, _, span = entry.rpartition(":")
            if name != target or not span or len(moved) != 2:
                continue
            if span == "same-label":
                a, b = (before[k - 1].split() for k in moved)
                if len(a) == len(b) and _label(a) and _label(a) == _label(b):
                    return True
                continue
            first, last = (int(v) for v in span.split("-"))
            if all(first <= k <= last for k in moved):
                return True
        return False

    def encodings(self) -> Iterator[tuple[str, str, Outcome]]:
        """Every text target in every encoding of :data:`ENCODINGS`."""
        for target in self.case.targets:
            data = (self.source / target).read_bytes()
            if _is_binary(data):
                continue
            text = data.decode("utf-8", errors="replace")
            for encoding in ENCODINGS:
                yield (
                    target,
                    encoding,
                    self.judge(target, encode_text(text, encoding), encoding_only=True),
                )


#: Row labels of a 6×6 matrix printed by AQWA's listing (X … RZ): they name the row, not
#: the frequency of the block.
_MATRIX_ROWS = {"X", "Y", "Z", "RX", "RY", "RZ"}


def _label(fields: list[str]) -> tuple[str, ...]:
    """The leading integer fields of a row (its label: a DOF index, an I J pair), or the
    row name of a printed matrix (X … RZ)."""
    if fields and fields[0] in _MATRIX_ROWS:
        return (fields[0],)
    out = []
    for field in fields:
        if not field.lstrip("+-").isdigit():
            break
        out.append(field)
    return tuple(out)


def _is_binary(data: bytes) -> bool:
    return b"\x00" in data[:4096] or data[:4] in (b"CDF\x01", b"CDF\x02", b"\x89HDF")


def failures(outcomes) -> list[str]:
    """The outcomes that break the rule, as readable lines."""
    return [
        f"{target} [{op}]: {o.kind}: {o.detail[:300]}"
        for target, op, o in outcomes
        if o.kind in ("crash", "different")
    ]
