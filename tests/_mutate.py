"""Damaged copies of real solver files, and the rule every reader must keep with them.

A reader given a damaged file may do one of three things:

* raise :class:`~cummins.HydroDataError` (the message names the file),
* read it with a :class:`~cummins.HydroDataWarning` that says what was lost,
* read exactly the data of the undamaged file (the damage hit a part it does not use:
  a comment, a blank line, a log section, the order of self-describing rows).

Anything else is a defect: another exception, or *different numbers read silently*.
Changes of encoding (UTF-8 byte-order mark, CRLF or CR-only line ends, tabs for spaces)
are not damage: the data must read identically, without a warning.

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
        label (the same leading integers, e.g. DOF index I or I J, and as many fields)
        in blocks told apart only by a header line: the rest of the file is judged as
        usual.
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

    def judge(self, target: str, content: bytes, *, encoding_only: bool = False) -> Outcome:
        """Write ``content`` over ``target``, read the case, and say what the reader did."""
        path = self.work / target
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


def _label(fields: list[str]) -> tuple[str, ...]:
    """The leading integer fields of a row (its label: a DOF index, an I J pair)."""
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
