"""Array helpers that give numpy's numbers without its wrappers, for the loops of the data
stage of a fit and of ``cummins check``: a frequency matched on a grid
(:func:`at_frequency`, some hundreds of times per fit), the median of each column
(:func:`column_medians`, once per pass of the suspect-frequency test); and the last
answer of a function kept by the digest of its arguments (:class:`LastAnswer`)."""

from __future__ import annotations

import hashlib
import threading
import weakref
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray


def at_frequency(omega: ArrayLike, target: float, rtol: float = 1e-12) -> NDArray[np.bool_]:
    """Which of ``omega`` equal ``target`` to ``rtol`` (relative to ``target``): the answer
    of ``np.isclose(omega, target, rtol=rtol, atol=0.0)`` — |ω − target| ≤ rtol |target| for
    a finite target, ω == target otherwise — without its wrappers (a sixth of the time)."""
    w = np.asarray(omega)
    if not np.isfinite(target):
        return np.isclose(w, target, rtol=rtol, atol=0.0)
    return np.abs(w - target) <= rtol * abs(target)


def column_medians(x: NDArray[np.float64]) -> NDArray[np.float64]:
    """``np.median(x, axis=0)`` of a 2-D float array with at least one row, the same
    numbers: the middle order statistic, or the two middle ones' (a + b)/2 as
    :func:`numpy.mean` gives it; NaN in a column with a NaN."""
    n = x.shape[0]
    half = n // 2
    part = np.partition(x, [half - 1, half, n - 1] if n % 2 == 0 else [half, n - 1], axis=0)
    middle = part[half] if n % 2 else (part[half - 1] + part[half]) / 2
    return np.where(np.isnan(part[-1]), np.nan, middle)


def digest(*parts) -> bytes:
    """The SHA-256 digest of ``parts``: arrays by their shape, dtype and bytes, anything
    else by its ``repr`` — the key of a :class:`LastAnswer`."""
    out = hashlib.sha256()
    for part in parts:
        if isinstance(part, np.ndarray):
            out.update(f"{part.shape}{part.dtype}".encode())
            out.update(np.ascontiguousarray(part).tobytes())
        else:
            out.update(repr(part).encode())
    return out.digest()


class LastAnswer:
    """One function's last answer, kept by the :func:`digest` of its arguments: a fit and
    its refit with A∞ estimated ask for the same numbers of the same data. Per thread (a
    fit of another thread neither reads nor replaces it); the caller makes what it keeps
    read-only, so that no one changes the answer the next caller gets."""

    #: Every instance, for :func:`forget_kept_answers`.
    instances: ClassVar[weakref.WeakSet] = weakref.WeakSet()

    def __init__(self) -> None:
        self._local = threading.local()
        LastAnswer.instances.add(self)

    def get(self, key: bytes):
        """The answer kept under ``key``, else None."""
        last = getattr(self._local, "last", None)
        return last[1] if last is not None and last[0] == key else None

    def keep(self, key: bytes, answer):
        """``answer`` kept under ``key`` (replacing the last), and returned."""
        self._local.last = (key, answer)
        return answer

    def clear(self) -> None:
        """Nothing kept."""
        self._local.last = None


def forget_kept_answers() -> None:
    """Every :class:`LastAnswer` of this thread emptied: a benchmark's repeated fit of the
    same data then costs what a user's single fit does."""
    for kept in list(LastAnswer.instances):
        kept.clear()
