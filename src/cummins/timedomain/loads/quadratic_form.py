"""A second-order force as a few harmonic sums: the double sum over pairs of components,
factorised once so that a 3-hour record costs O(N) per time step, not O(N²).

With u_i(t) = e^{i(ω_i t + φ_i)} the unit phasors of the N wave components and
K^d_ij = a_i a_j Q_d(ω_i, ω_j, β_i, β_j) the amplitude-weighted QTF of DOF d over the
component pairs (:func:`cummins.qtf.pair_matrix`), the second-order force of
:mod:`cummins.qtf.data` is

    F⁻_d(t) = Re Σ_i Σ_j u_i ū_j K⁻^d_ij,     F⁺_d(t) = Re Σ_i Σ_j u_i u_j K⁺^d_ij.

For components of one direction (a long-crested sea) the bilinear interpolation makes
K exactly A W Q_d Wᵀ A, W the (N × n) interpolation weights on the QTF's grid of n
frequencies: F_d = Re gᵀ Q_d op(g) with the n harmonic sums g = Σ_i u_i a_i W_i·, the
same for every DOF and exact (:func:`grid_form`: a 100 × 100 QTF costs 100 sums).
Otherwise (short-crested seas) K is factorised per DOF:
K⁻ is Hermitian: K⁻ = V Λ Vᴴ gives F⁻ = Σ_r λ_r |Σ_i u_i V_ir|², a sum of squared
magnitudes of harmonic sums. K⁺ is complex symmetric: K⁺ = W S Vᴴ (SVD) gives
F⁺ = Re Σ_r s_r (Σ_i u_i W_ir)(Σ_i u_i V̄_ir). A smooth QTF makes K numerically low
rank: the terms are kept, largest first, until the left-out ones weigh at most ``tol``
of the whole (Σ_dropped λ_r² ≤ tol² Σ λ_r², i.e. about ``tol`` of the force's standard
deviation, the slowly varying force of a random-phase sea having variance ∝ ‖K‖_F²).
Above :data:`DENSE_LIMIT` components the decomposition is randomised (Halko et al.
(2011), algorithms 4.1 and 5.3, the sample doubled until the captured Frobenius norm
meets ``tol``). Newman's approximation K_ij = ½ a_i a_j (T_i + T_j) is the exact
rank-two form Re[(Σ_i u_i a_i T_i)(Σ_j ū_j a_j)] (:func:`newman_form`).

:class:`QuadraticForm` holds the coefficient columns (N × m) and, per DOF, the columns
it uses and a small matrix B^d: F_d = Re Σ_kl g_k B^d_kl op(g_l). On a uniform time grid
the harmonic sums are demodulated by a carrier e^{iω_c t} (ω_c the middle of the
components' frequencies): the products of difference sums carry only |ω_i − ω_j| ≤ 2Ω,
those of sum sums 2ω_c ± 2Ω, so they are computed on a grid coarse enough for 2Ω (8
points per period) and interpolated (cubic spline: within 0.1 % of the standard
deviation on the OC4 semi) to the simulation's steps (:func:`time_series`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline

from cummins.seakeeping.waves import harmonic_sum

#: Largest number of components decomposed densely (above: randomised).
DENSE_LIMIT = 800
#: Points per period of the highest frequency of the demodulated products.
POINTS_PER_PERIOD = 8


@dataclass(frozen=True)
class QuadraticForm:
    """F_d(t) = Re Σ_k Σ_l g_{c_k}(t) B^d_kl op(g_{c_l}(t)) for each DOF d, with the harmonic
    sums g_c(t) = Σ_i u_i(t) C_ic and op the complex conjugate (difference frequencies)
    or nothing (sum frequencies).

    Attributes
    ----------
    omega, phase
        The components' frequencies (rad/s) and phases (rad), shape (N,).
    columns
        C, complex, shape (N, m).
    blocks
        Per DOF: the columns c it uses (indices into C) and the matrix B^d (len(c) ×
        len(c)), complex.
    difference
        True: difference frequencies (op = conjugate); False: sum frequencies.
    """

    omega: NDArray[np.float64]
    phase: NDArray[np.float64]
    columns: NDArray[np.complex128]
    blocks: tuple[tuple[NDArray[np.intp], NDArray[np.complex128]], ...]
    difference: bool

    @property
    def n_dofs(self) -> int:
        """Number of DOFs."""
        return len(self.blocks)

    @property
    def terms(self) -> int:
        """The size of the form: Σ_d (number of columns used)²."""
        return int(sum(c.size**2 for c, _ in self.blocks))

    def _combine(self, g: NDArray[np.complex128]) -> NDArray[np.complex128]:
        """Σ_kl g_k B_kl op(g_l) per DOF, complex, shape (..., n_dofs)."""
        out = np.zeros((*g.shape[:-1], self.n_dofs), dtype=complex)
        for d, (cols, b) in enumerate(self.blocks):
            if cols.size == 0:
                continue
            gb = g[..., cols]
            other = np.conj(gb) if self.difference else gb
            out[..., d] = np.sum(gb * (other @ b.T), axis=-1)
        return out

    def at(self, t: float, shift: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """F(t), shape (n_dofs,): O(N·m) — the load of a simulation stepped by a solver.
        ``shift`` subtracts a phase per component (the vessel's position, rad)."""
        phase = self.omega * float(t) + self.phase
        if shift is not None:
            phase = phase - shift
        g = np.exp(1j * phase) @ self.columns
        return self._combine(g).real

    def time_series(self, t: ArrayLike) -> NDArray[np.float64]:
        """F(t) at uniform times ``t`` (s), shape (nt, n_dofs)."""
        return time_series([self], t)

    def pair_matrices(self) -> NDArray[np.complex128]:
        """K^d = C_c B^d op(C_c)ᵀ reconstructed, shape (n_dofs, N, N)."""
        n = self.omega.size
        out = np.zeros((self.n_dofs, n, n), dtype=complex)
        for d, (cols, b) in enumerate(self.blocks):
            c = self.columns[:, cols]
            out[d] = c @ b @ (np.conj(c).T if self.difference else c.T)
        return out

    def stationary_state(
        self, state_matrix: NDArray, input_matrix: NDArray
    ) -> tuple[NDArray[np.float64], list[str]]:
        """x(0) of the stationary response of ẋ = F x + G τ to this force (τ = F_d(t)).

        x(0) = Re Σ_ij (iμ_ij I − F)⁻¹ G f_ij with f_ij = u_i(0) op(u_j(0)) K_ij and
        μ_ij = ω_i ∓ ω_j, through the eigen-decomposition of F (one pass over the
        pairs per mode). A mode with λ ≈ 0 (a DOF with no restoring) has no stationary
        response to the mean force: those terms are left out (and the notes say so).
        """
        lam, vec = np.linalg.eig(state_matrix)
        gm = np.linalg.solve(vec, input_matrix)  # modal input, (ns, n_dofs)
        u = np.exp(1j * self.phase)
        if self.difference:
            mu = self.omega[:, None] - self.omega[None, :]
            weights = u[:, None] * np.conj(u)[None, :]
        else:
            mu = self.omega[:, None] + self.omega[None, :]
            weights = u[:, None] * u[None, :]
        f = self.pair_matrices() * weights[None]  # (n_dofs, N, N)
        scale = max(float(np.abs(lam).max()), 1e-12)
        q = np.zeros(lam.size, dtype=complex)
        notes: list[str] = []
        for mode, lm in enumerate(lam):
            if not np.any(gm[mode]):
                continue
            denominator = 1j * mu - lm
            tiny = np.abs(denominator) <= 1e-9 * scale
            if tiny.any():
                denominator = np.where(tiny, np.inf, denominator)
                if not notes:
                    notes.append(
                        "a DOF without restoring has no stationary response to the mean "
                        "force: it starts at rest and drifts"
                    )
            q[mode] = np.einsum("d,dij,ij->", gm[mode], f, 1.0 / denominator)
        return (vec @ q).real, notes


def time_series(forms: list[QuadraticForm], t: ArrayLike) -> NDArray[np.float64]:
    """Σ of the forms' F(t) at uniform times ``t`` (s), shape (nt, n_dofs).

    The harmonic sums are demodulated by the carrier e^{iω_c t} and computed on a grid
    coarse enough for the products' band (module docstring), once for forms that share
    their columns (the difference and sum QTFs of a long-crested sea).
    """
    t = np.asarray(t, dtype=float).reshape(-1)
    first = forms[0]
    out = np.zeros((t.size, first.n_dofs))
    if t.size == 0:
        return out
    carrier = 0.5 * (first.omega.min() + first.omega.max())
    top = 2.0 * float(np.max(np.abs(first.omega - carrier)))  # the products' highest frequency
    dt = (t[-1] - t[0]) / (t.size - 1) if t.size > 1 else 1.0
    coarse_dt = 2 * np.pi / (POINTS_PER_PERIOD * top) if top > 0 else np.inf
    if coarse_dt >= 2 * dt and t.size > 8:
        grid = np.linspace(t[0], t[-1], max(int(np.ceil((t[-1] - t[0]) / coarse_dt)) + 1, 4))
    else:
        grid = t
    done: list[tuple[NDArray, NDArray]] = []
    for form in forms:
        if form.columns.shape[1] == 0:
            continue
        g = next((h for c, h in done if c is form.columns or np.array_equal(c, form.columns)), None)
        if g is None:
            coefficients = form.columns * np.exp(1j * form.phase)[:, None]
            both = np.concatenate([coefficients, -1j * coefficients], axis=1)
            h = harmonic_sum(grid, form.omega - carrier, both)
            m = form.columns.shape[1]
            g = h[:, :m] + 1j * h[:, m:]
            done.append((form.columns, g))
        combined = form._combine(g)
        if grid is not t:
            combined = CubicSpline(grid, combined, axis=0)(t)
        if not form.difference:
            combined = combined * np.exp(2j * carrier * t)[:, None]
        out += combined.real
    return out


def _keep(values: NDArray[np.float64], tol: float) -> int:
    """How many of the values (sorted by decreasing magnitude) to keep so that the
    squares of the rest weigh at most tol² of all."""
    energy = values**2
    total = energy.sum()
    if total == 0:
        return 0
    tail = np.cumsum(energy[::-1])[::-1]  # tail[r] = Σ_{s ≥ r}
    ok = np.flatnonzero(np.append(tail[1:], 0.0) <= tol**2 * total)
    return int(ok[0]) + 1


def _randomized_range(k: NDArray, rank: int, rng: np.random.Generator) -> NDArray:
    n = k.shape[0]
    omega = rng.standard_normal((n, rank)) + 1j * rng.standard_normal((n, rank))
    y = k @ omega
    y = k @ (k.conj().T @ y)  # one power iteration: a sharper range for a slow decay
    q, _ = np.linalg.qr(y)
    return q


def hermitian_terms(
    k: NDArray[np.complex128], tol: float, *, seed: int = 0
) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """λ_r, V_r (largest |λ| first) of the Hermitian K, truncated at ``tol``."""
    n = k.shape[0]
    k = 0.5 * (k + k.conj().T)
    norm2 = float(np.sum(np.abs(k) ** 2))
    if norm2 == 0:
        return np.zeros(0), np.zeros((n, 0), dtype=complex)
    if n <= DENSE_LIMIT:
        lam, vec = np.linalg.eigh(k)
    else:
        rng = np.random.default_rng(seed)
        rank = 64
        while True:
            q = _randomized_range(k, min(rank, n), rng)
            lam, u = np.linalg.eigh(q.conj().T @ k @ q)
            if norm2 - np.sum(lam**2) <= tol**2 * norm2 or rank >= n:
                vec = q @ u
                break
            rank *= 2
    order = np.argsort(-np.abs(lam))
    lam, vec = lam[order], vec[:, order]
    keep = _keep(np.abs(lam), tol)
    return lam[:keep], vec[:, :keep]


def symmetric_terms(
    k: NDArray[np.complex128], tol: float, *, seed: int = 0
) -> tuple[NDArray[np.float64], NDArray[np.complex128], NDArray[np.complex128]]:
    """s_r, W_r, V_r of the SVD K = W S Vᴴ (largest first), truncated at ``tol``."""
    n = k.shape[0]
    norm2 = float(np.sum(np.abs(k) ** 2))
    if norm2 == 0:
        return np.zeros(0), np.zeros((n, 0), dtype=complex), np.zeros((n, 0), dtype=complex)
    if n <= DENSE_LIMIT:
        w, s, vh = np.linalg.svd(k)
    else:
        rng = np.random.default_rng(seed)
        rank = 64
        while True:
            q = _randomized_range(k, min(rank, n), rng)
            ub, s, vh = np.linalg.svd(q.conj().T @ k, full_matrices=False)
            if norm2 - np.sum(s**2) <= tol**2 * norm2 or rank >= n:
                w = q @ ub
                break
            rank *= 2
    keep = _keep(s, tol)
    return s[:keep], w[:, :keep], vh[:keep].conj().T


def full_form(
    omega: NDArray,
    phase: NDArray,
    matrices: list[NDArray[np.complex128]],
    *,
    difference: bool,
    tol: float,
) -> QuadraticForm:
    """The factorised form of K^d (one N × N matrix per DOF, already amplitude-weighted),
    truncated at ``tol`` (module docstring)."""
    n = len(omega)
    columns, blocks, m = [], [], 0
    for k in matrices:
        if difference:
            lam, vec = hermitian_terms(k, tol)
            columns.append(vec)
            blocks.append((np.arange(m, m + lam.size, dtype=np.intp), np.diag(lam).astype(complex)))
            m += lam.size
        else:
            s, w, v = symmetric_terms(k, tol)
            r = s.size
            columns.extend([w, np.conj(v)])
            b = np.zeros((2 * r, 2 * r), dtype=complex)
            b[np.arange(r), r + np.arange(r)] = s  # Re Σ_r s_r g_{W_r} g_{V̄_r}
            blocks.append((np.arange(m, m + 2 * r, dtype=np.intp), b))
            m += 2 * r
    return QuadraticForm(
        np.asarray(omega, dtype=float),
        np.asarray(phase, dtype=float),
        np.concatenate(columns, axis=1) if columns else np.zeros((n, 0), dtype=complex),
        tuple(blocks),
        difference,
    )


def grid_form(
    omega: NDArray,
    phase: NDArray,
    amplitude: NDArray,
    weights: NDArray[np.float64],
    grid_values: list[NDArray[np.complex128]],
    *,
    difference: bool,
) -> QuadraticForm:
    """The exact form of a QTF interpolated linearly on its grid, for components of one
    direction: K^d = A W Q_d Wᵀ A (W the (N × n) interpolation weights, Q_d the QTF on
    the grid at that direction), so F_d = Re gᵀ Q_d op(g) with the n harmonic sums
    g = Σ_i u_i a_i W_i· — the same sums for every DOF, no truncation. Grid points no
    component uses are left out."""
    used = np.flatnonzero(np.any(weights != 0, axis=0))
    columns = (amplitude[:, None] * weights[:, used]).astype(complex)
    idx = np.arange(used.size, dtype=np.intp)
    blocks = tuple((idx, np.asarray(q)[np.ix_(used, used)]) for q in grid_values)
    return QuadraticForm(
        np.asarray(omega, dtype=float), np.asarray(phase, dtype=float), columns, blocks, difference
    )


def newman_form(
    omega: NDArray, phase: NDArray, amplitude: NDArray, drift: NDArray[np.float64]
) -> QuadraticForm:
    """Newman's approximation K_ij = ½ a_i a_j (T_i + T_j) of every DOF (``drift`` T,
    shape (N, n_dofs)): F_d = Re[(Σ_i u_i a_i T_id)(Σ_j ū_j a_j)] (Newman (1974);
    Smogeli et al. (2004) eq. 47)."""
    d = drift.shape[1]
    columns = np.concatenate([amplitude[:, None] * drift, amplitude[:, None]], axis=1)
    one = np.array([[0.0, 1.0], [0.0, 0.0]], dtype=complex)
    blocks = tuple((np.array([k, d], dtype=np.intp), one) for k in range(d))
    return QuadraticForm(
        np.asarray(omega, dtype=float),
        np.asarray(phase, dtype=float),
        columns.astype(complex),
        blocks,
        True,
    )
