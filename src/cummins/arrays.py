"""Array helpers that give numpy's numbers without its wrappers, for the loops of the data
stage of a fit and of ``cummins check``: a frequency matched on a grid
(:func:`at_frequency`, some hundreds of times per fit), the median of each column
(:func:`column_medians`, once per pass of the suspect-frequency test)."""

from __future__ import annotations

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
