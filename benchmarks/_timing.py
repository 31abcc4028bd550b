"""Shared by the benchmark scripts: best-of timing and the location of the shared data."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

#: ../shared/data next to the repository (the real solver output).
SHARED_DATA = Path(__file__).resolve().parents[2] / "shared" / "data"


def timed(function: Callable[[], Any], repeat: int = 3) -> tuple[float, Any]:
    """(best wall time in s over ``repeat`` calls, the last result)."""
    best, result = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def forget_kept_answers() -> None:
    """:func:`cummins.arrays.forget_kept_answers` of the ``cummins`` imported (nothing for a
    tree from before it): called before each timed fit, so that a repeated fit of the same
    data does not find the answers the first one kept, which a user's single fit does not."""
    try:
        from cummins.arrays import forget_kept_answers as forget
    except ImportError:
        return
    forget()
