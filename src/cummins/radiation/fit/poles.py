"""The common poles of a block in real form (:class:`Poles`): the basis of the partial
fractions at given frequencies and the poles' state-space form, for the vector fitting
of :mod:`cummins.radiation.fit.vector`."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class Poles:
    """Common poles in real form: ``real`` (negative) and ``pairs`` (Im > 0)."""

    real: NDArray[np.float64]
    pairs: NDArray[np.complex128]

    @property
    def count(self) -> int:
        """Number of real parameters per coupling (a pair counts two)."""
        return self.real.size + 2 * self.pairs.size

    def basis(self, s: NDArray, constant: bool = False) -> NDArray[np.complex128]:
        """Columns 1/(s − p) for real p; 1/(s − p) + 1/(s − p̄) and j/(s − p) − j/(s − p̄)
        for a pair (coefficients a, b: residue a + jb at p); with ``constant``, a last
        column of ones (the relocation's σ). Written into one array (the numbers of a
        stack of the parts, without its copies)."""
        s = np.asarray(s, dtype=complex)
        nr, count = self.real.size, self.count
        out = np.empty((s.size, count + int(constant)), dtype=complex)
        out[:, :nr] = 1.0 / (s[:, None] - self.real[None, :])
        if self.pairs.size:
            one = 1.0 / (s[:, None] - self.pairs[None, :])
            two = 1.0 / (s[:, None] - np.conj(self.pairs)[None, :])
            out[:, nr:count:2] = one + two
            out[:, nr + 1 : count : 2] = 1j * (one - two)
        if constant:
            out[:, count] = 1.0
        return out

    def kept_basis(self, s: NDArray) -> NDArray[np.complex128]:
        """:meth:`basis`, kept (read-only) for the next call at the same ``s``: a fit's
        scores and its passivity enforcement evaluate it at the data's frequencies again.
        At the leading frequencies of a kept ``s`` (the scores' data frequencies, the
        residues' data and tail), the leading rows of its basis: each row is computed from
        its own frequency alone, so they are the numbers :meth:`basis` would give."""
        s = np.asarray(s, dtype=complex)
        kept = self.__dict__.setdefault("_kept", {})
        key = s.tobytes()
        if key not in kept:
            for other, values in kept.items():
                if len(other) > len(key) and other.startswith(key):
                    return values[: s.size]
            if len(kept) > 2:  # the last few frequencies only
                kept.clear()
            kept[key] = self.basis(s)
            kept[key].flags.writeable = False
        return kept[key]

    def state_form(self) -> tuple[NDArray, NDArray]:
        """(Λ, b) with basis(s) = (sI − Λ)⁻¹ b written in the same real coordinates."""
        n = self.count
        lam, b = np.zeros((n, n)), np.zeros(n)
        nr = self.real.size
        lam[:nr, :nr] = np.diag(self.real)
        b[:nr] = 1.0
        for k, p in enumerate(self.pairs):
            i = nr + 2 * k
            lam[i : i + 2, i : i + 2] = [[p.real, p.imag], [-p.imag, p.real]]
            b[i] = 2.0
        return lam, b

    def residue_sum(self) -> NDArray[np.float64]:
        """The linear form of the coefficients giving Σ_k R_k (conjugates included)."""
        v = np.zeros(self.count)
        v[: self.real.size] = 1.0
        v[self.real.size :: 2] = 2.0
        return v
