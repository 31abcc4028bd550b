"""A symmetric MIMO memory model in modal form, with rank-limited residues.

A truncated common-pole block K_r(s) = c (sI − a)⁻¹ b of m DOFs with r states is written

    K_r(s) = Σ_k σ_k u_k u_kᵀ / (s − p_k)  [+ the conjugate term ū_k ū_kᵀ / (s − p̄_k) of a pair],

one term per state of a real pole (u_k real, σ_k = ±1) and per pair of states of a complex
pair (u_k complex, σ_k = 1): the residue matrices are symmetric (K_ij = K_ji) and of the
rank their pole's multiplicity allows, so the realization keeps the r states. The
vectors u_k are the parameters of the structural corrections of
:mod:`~cummins.radiation.reduce.blocks` (the zero K(0) = 0 and passivity), which keep
that form: a change of u_k changes its residue without adding a state. Every value of the
model and its derivatives with respect to the parameters are sums Σ_k σ_k u_k u_kᵀ f(p_k)
(+ ū_k ū_kᵀ f(p̄_k)) for some f: f(p) = 1/(jω − p) for K(jω), −1/p for K(0) and, for the
limits of Re K (Unneland (2007) Prop. 3.4 requires them positive semidefinite),
−p for lim ω² Re K(jω) (ω → ∞) and 1/p³ for lim Re K(jω)/ω² (ω → 0).

A complex symmetric residue R is factored as R = Σ_i u_i u_iᵀ (Takagi; Horn & Johnson
(2013) §4.4) through the real symmetric matrix [[Re R, Im R], [Im R, −Re R]]: its
eigenvector [x; y] of eigenvalue σ > 0 gives u = √σ (x + j y).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

#: Eigenvalues of a within this (relative) of each other are one pole of multiplicity > 1
#: (a common pole with a rank-2 residue comes out of a truncation split by ~1e-7, each
#: member with a residue that is not symmetric on its own).
SAME_POLE = 1e-5


@dataclass(frozen=True)
class ModalBlock:
    """K(s) = Σ_k σ_k u_k u_kᵀ/(s − p_k) (+ conjugates of the pairs) (module docstring).

    Attributes
    ----------
    poles
        (terms,) complex: a real pole, or the member of a pair with Im p > 0.
    vectors
        (terms, m) complex u_k (real for a real pole).
    signs
        (terms,) σ_k: ±1 for a real pole, 1 for a pair.
    """

    poles: NDArray[np.complex128]
    vectors: NDArray[np.complex128]
    signs: NDArray[np.float64]

    @property
    def is_pair(self) -> NDArray[np.bool_]:
        return self.poles.imag != 0

    @property
    def order(self) -> int:
        """Number of states: one per real term, two per pair."""
        return int(np.sum(np.where(self.is_pair, 2, 1)))

    @property
    def size(self) -> int:
        """Number of DOFs m."""
        return int(self.vectors.shape[1])

    def value(self, f: Callable[[NDArray], NDArray]) -> NDArray[np.complex128]:
        """Σ_k σ_k u_k u_kᵀ f(p_k) + (pairs) ū_k ū_kᵀ f(p̄_k), (m, m)."""
        outer = self.signs[:, None, None] * self.vectors[:, :, None] * self.vectors[:, None, :]
        out = np.einsum("k,kij->ij", f(self.poles), outer)
        pair = self.is_pair
        if pair.any():
            out = out + np.einsum("k,kij->ij", f(np.conj(self.poles[pair])), np.conj(outer[pair]))
        return out

    def response(self, omega: NDArray) -> NDArray[np.complex128]:
        """K(jω), (n_omega, m, m)."""
        s = 1j * np.asarray(omega, dtype=float)
        outer = self.signs[:, None, None] * self.vectors[:, :, None] * self.vectors[:, None, :]
        out = np.einsum("wk,kij->wij", 1.0 / (s[:, None] - self.poles[None, :]), outer)
        pair = self.is_pair
        if pair.any():
            inverse = 1.0 / (s[:, None] - np.conj(self.poles[pair])[None, :])
            out += np.einsum("wk,kij->wij", inverse, np.conj(outer[pair]))
        return out

    def dc(self) -> NDArray[np.float64]:
        """K(0), (m, m)."""
        return self.value(lambda p: -1.0 / p).real

    def _columns(self) -> tuple[NDArray, NDArray]:
        """Where each term's parameters are: the columns of u (or Re u) (terms, m) and of
        Im u of the pairs (pairs, m)."""
        m, pair = self.size, self.is_pair
        width = np.where(pair, 2 * m, m)
        start = np.r_[0, np.cumsum(width)[:-1]].astype(int)
        columns = start[:, None] + np.arange(m)[None, :]
        return columns, columns[pair] + m

    @property
    def n_parameters(self) -> int:
        return int(np.sum(np.where(self.is_pair, 2, 1))) * self.size

    def parameters(self) -> NDArray[np.float64]:
        """The real parameters: u_k of a real term, then (Re u_k, Im u_k) of a pair."""
        first, second = self._columns()
        x = np.zeros(self.n_parameters)
        x[first.ravel()] = self.vectors.real.ravel()
        x[second.ravel()] = self.vectors[self.is_pair].imag.ravel()
        return x

    def with_parameters(self, x: NDArray) -> ModalBlock:
        """The same poles and signs with the parameters ``x``."""
        first, second = self._columns()
        vectors = x[first].astype(complex)
        vectors[self.is_pair] += 1j * x[second]
        return ModalBlock(self.poles, vectors, self.signs)

    def derivative(self, f: Callable[[NDArray], NDArray]) -> NDArray[np.complex128]:
        """d value(f)/d parameters, (n_parameters, m, m)."""
        m = self.size
        eye = np.eye(m)
        # d(u uᵀ)/du_c = e_c uᵀ + u e_cᵀ: (terms, c, i, j)
        d = (
            eye[None, :, :, None] * self.vectors[:, None, None, :]
            + self.vectors[:, None, :, None] * eye[None, :, None, :]
        )
        fp = f(self.poles)[:, None, None, None]
        fq = f(np.conj(self.poles))[:, None, None, None]
        pair = self.is_pair
        first = np.where(pair[:, None, None, None], d * fp + np.conj(d) * fq,
                         self.signs[:, None, None, None] * d * fp)  # fmt: skip
        second = (1j * d * fp - 1j * np.conj(d) * fq)[pair]
        out = np.zeros((self.n_parameters, m, m), dtype=complex)
        columns, imaginary = self._columns()
        out[columns.ravel()] = first.reshape(-1, m, m)
        out[imaginary.ravel()] = second.reshape(-1, m, m)
        return out

    def response_jacobian(self, omega: NDArray) -> NDArray[np.complex128]:
        """d K_ij(jω)/d parameters of the pairs i ≤ j (row-major upper triangle),
        (n_omega, pairs, n_parameters): d(u uᵀ)_ij/du_c is u_j for c = i plus u_i for
        c = j."""
        s = 1j * np.asarray(omega, dtype=float)
        fp = 1.0 / (s[:, None] - self.poles[None, :])
        fq = 1.0 / (s[:, None] - np.conj(self.poles)[None, :])
        pair, u = self.is_pair, self.vectors
        columns, imaginary = self._columns()
        upper = np.triu_indices(self.size)
        out = np.zeros((s.size, upper[0].size, self.n_parameters), dtype=complex)
        for q, (i, j) in enumerate(zip(*upper, strict=True)):
            for c, other in ((i, j), (j, i)):
                v = u[:, other]
                first = np.where(pair, v * fp + np.conj(v) * fq, self.signs * v * fp)
                out[:, q, columns[:, c]] += first
                if pair.any():
                    out[:, q, imaginary[:, c]] += (1j * (v * fp - np.conj(v) * fq))[:, pair]
        return out

    def form_gradients(
        self, w: NDArray, fp: NDArray, fq: NDArray
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """wₖᵀ Re value(fₖ) wₖ for P real vectors wₖ (P, m) and P functions given by their
        values at the poles, fp = fₖ(p_t), and at the conjugates, fq = fₖ(p̄_t) (P, terms);
        and their derivatives by the parameters, (P,) and (P, n_parameters): what
        :meth:`derivative` gives, contracted with wₖ on both sides, without forming it."""
        uw = w @ self.vectors.T  # (P, terms)
        pair = self.is_pair
        values = (self.signs * uw**2 * fp).real.sum(axis=1)
        values += (np.conj(uw[:, pair]) ** 2 * fq[:, pair]).real.sum(axis=1)
        alpha = 2 * self.signs * uw * fp  # d(wᵀ u uᵀ w f)/du_c = 2 w_c (uᵀw) f
        beta = 2 * np.conj(uw) * fq
        first = np.where(pair, (alpha + beta).real, alpha.real)  # Re u (a pair) or u
        second = (beta - alpha).imag  # Im u of a pair
        columns, imaginary = self._columns()
        rows = np.zeros((w.shape[0], self.n_parameters))
        rows[:, columns.ravel()] = (first[:, :, None] * w[:, None, :]).reshape(w.shape[0], -1)
        block = second[:, pair, None] * w[:, None, :]
        rows[:, imaginary.ravel()] = block.reshape(w.shape[0], -1)
        return values, rows

    def realization(self) -> tuple[NDArray, NDArray, NDArray]:
        """(a, b, c): one state per real term, a 2×2 block per pair."""
        a_blocks, b_blocks, c_blocks = [], [], []
        terms = zip(self.poles, self.vectors, self.signs, self.is_pair, strict=True)
        for p, u, sign, pair in terms:
            if pair:  # u uᵀ/(s − p) + ū ūᵀ/(s − p̄) = c (sI − a)⁻¹ b
                a_blocks.append(np.array([[p.real, -p.imag], [p.imag, p.real]]))
                b_blocks.append(np.vstack([u.real, u.imag]))
                c_blocks.append(np.column_stack([2 * u.real, -2 * u.imag]))
            else:
                a_blocks.append(np.array([[p.real]]))
                b_blocks.append(u.real[None, :])
                c_blocks.append(sign * u.real[:, None])
        m = self.size
        if not a_blocks:
            return np.zeros((0, 0)), np.zeros((0, m)), np.zeros((m, 0))
        return scipy.linalg.block_diag(*a_blocks), np.vstack(b_blocks), np.hstack(c_blocks)


def at_zero(p: NDArray) -> NDArray:
    """f of lim Re K(jω)/ω² (ω → 0) = Σ R_k/p_k³ (module docstring)."""
    return 1.0 / p**3


def at_infinity(p: NDArray) -> NDArray:
    """f of lim ω² Re K(jω) (ω → ∞) = −Σ R_k p_k (module docstring)."""
    return -p


def modal_form(a: NDArray, b: NDArray, c: NDArray) -> ModalBlock:
    """The modal form of a stable model with a symmetric transfer matrix (module
    docstring): the residues of equal poles summed, made exactly symmetric and factored
    at the rank of the pole's multiplicity (their largest terms), so that the order is
    kept."""
    lam, v = np.linalg.eig(np.asarray(a, dtype=float))
    x = np.asarray(c, dtype=float) @ v
    y = np.linalg.solve(v, np.asarray(b, dtype=float))
    groups: list[list] = []  # [pole, residue, multiplicity]
    for k, p in enumerate(lam):
        if p.imag < 0:
            continue  # its conjugate carries it
        residue = np.outer(x[:, k], y[k])
        if p.imag == 0:  # LAPACK returns a real eigenvalue of a real matrix exactly real
            residue = residue.real
        for g in groups:
            if abs(g[0] - p) <= SAME_POLE * abs(p):
                g[0] = (g[0] * g[2] + p) / (g[2] + 1)  # their mean
                g[1] = g[1] + residue
                g[2] += 1
                break
        else:
            groups.append([complex(p), residue, 1])
    poles, vectors, signs = [], [], []
    m = np.shape(c)[0]
    for p, residue, count in groups:
        residue = 0.5 * (residue + residue.T)
        if p.imag == 0:
            values, q = np.linalg.eigh(np.real(residue))
            for e in np.argsort(-np.abs(values))[:count]:
                poles.append(p)
                vectors.append(np.sqrt(abs(values[e])) * q[:, e] + 0j)
                signs.append(1.0 if values[e] >= 0 else -1.0)
        else:
            big = np.block([[residue.real, residue.imag], [residue.imag, -residue.real]])
            values, q = np.linalg.eigh(big)
            for e in np.argsort(-values)[:count]:
                poles.append(p)
                vectors.append(np.sqrt(max(values[e], 0.0)) * (q[:m, e] + 1j * q[m:, e]))
                signs.append(1.0)
    return ModalBlock(
        np.array(poles, dtype=complex),
        np.array(vectors, dtype=complex).reshape(len(poles), m),
        np.array(signs, dtype=float),
    )
