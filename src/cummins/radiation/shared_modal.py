"""The eigen-decomposition of a block's state matrix as its pairs share it
(:func:`cummins.radiation.model.modal_form`), with what the pairs' responses compute
from it alike."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


class ModalForm(tuple):
    """:func:`modal_form`'s (λ, V, usable), which also keeps the matrices e^{λ t} of the
    last time grids asked (:meth:`exponentials`): the pairs of a block share them, and
    each pair's impulse response is then one product (RM3's 200-state block: 55 pairs,
    the same exponentials computed once a grid instead of once a pair)."""

    #: Time grids kept (the coarse grid of the couplings and the fine one of the
    #: diagonal terms).
    KEPT = 2

    def __new__(cls, lam, v, usable):
        out = super().__new__(cls, (lam, v, usable))
        out._grids = []
        out._solved = {}
        return out

    def solved(self, b: NDArray) -> NDArray:
        """V⁻¹ b (``b`` a vector of floats), kept by its values: the pairs of a block
        with the same input DOF share it (numpy's solve, the same numbers)."""
        key = b.tobytes()
        if key not in self._solved:
            self._solved[key] = np.linalg.solve(self[1], b)
        return self._solved[key]

    def exponentials(self, t: ArrayLike) -> NDArray:
        """e^{λ t} (len(t), len(λ)) for the time grid ``t`` (kept by the identity of
        ``t``: the caller's array, not to be changed in place)."""
        for grid, values in self._grids:
            if grid is t:
                return values
        values = np.exp(np.outer(np.asarray(t, dtype=float).reshape(-1), self[0]))
        self._grids = [*self._grids[-(self.KEPT - 1) :], (t, values)]
        return values
