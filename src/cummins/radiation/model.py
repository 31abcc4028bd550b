"""State-space models of the fluid memory: the ``RadiationModel``.

The radiation force of the Cummins equation is −A∞ ξ̈ − μ with μ(t) = ∫₀ᵗ K(t−τ) ξ̇(τ) dτ.
cummins represents the convolution by a linear state-space model (Smogeli et al. (2004)
eq. 36, Unneland (2007) eqs. 3.40–3.41)

    χ̇ = A_r χ + B_r ξ̇,    μ = C_r χ + D_r ξ̇,    D_r = 0,

whose transfer matrix approximates K(s), with K(jω) = B(ω) + jω (A(ω) − A∞). Each
significant coupling K_ij is identified as a single-input single-output model (see
:mod:`cummins.radiation.fit`), and the MIMO model stacks them block-diagonally: coupling (i, j)
owns a block of states driven by ξ̇_j and read by μ_i. A symmetric pair K_ij = K_ji is
fitted once and appears twice (two blocks with the same matrices), so the assembled
model is symmetric, as the physics requires at zero speed.

The DOFs that radiate into each other can also share their states: a
:class:`MemoryBlock` is a MIMO model K_D(s) = c (sI − a)⁻¹ b of a group of DOFs D
(the common-pole identification of :mod:`cummins.radiation.fit.vector`), driven by the velocities
of D and read by their forces. A model holds couplings, blocks or both; a DOF pair is
modelled by one of them only.

Units: inputs are velocities (m/s, rad/s) in ``input`` DOF order, outputs forces and
moments (N, N·m) in ``output`` order; the state has no physical unit.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError, FitError, check_writable
from cummins.radiation.shared_modal import ModalForm

if TYPE_CHECKING:
    import scipy.signal


class SisoStateSpace:
    """Methods shared by the SISO models K(s) = c (sI − a)⁻¹ b (attributes a, b, c)."""

    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]

    @property
    def order(self) -> int:
        """Number of states."""
        return int(self.a.shape[0])

    def poles(self) -> NDArray[np.complex128]:
        """Eigenvalues of ``a`` (rad/s)."""
        return np.linalg.eigvals(self.a) if self.order else np.empty(0, dtype=complex)

    def is_stable(self) -> bool:
        """True when every pole has a negative real part."""
        return bool(np.all(self.poles().real < 0))

    def frequency_response(self, omega: ArrayLike) -> NDArray[np.complex128]:
        """K(jω) = c (jωI − a)⁻¹ b at ``omega`` (rad/s)."""
        return siso_frequency_response(self.a, self.b, self.c, omega)

    def impulse_response(self, t: ArrayLike) -> NDArray[np.float64]:
        """K(t) = c e^{a t} b at ``t`` (s)."""
        return siso_impulse_response(self.a, self.b, self.c, t)


@dataclass(frozen=True)
class CouplingModel(SisoStateSpace):
    """SISO state-space model of one coupling, K_ij(s) = c (sI − a)⁻¹ b.

    Attributes
    ----------
    influenced, radiating
        0-based DOF indices i (force) and j (velocity).
    a, b, c
        State matrix (n, n), input vector (n,), output vector (n,).
    method
        How it was identified (``"fd"``, ``"realization"``, ``"prony"``, ``"mss"`` …).
    metrics
        Fit measures (``r2_added_mass``, ``r2_damping``, ``stable``, ``passive`` …).
    note
        Anything the user should know (target not met, frequencies excluded …).
    """

    influenced: int
    radiating: int
    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    method: str = ""
    metrics: Mapping[str, Any] = field(default_factory=dict)
    note: str = ""

    def transposed(self) -> CouplingModel:
        """The same model for the symmetric coupling (j, i)."""
        return CouplingModel(
            self.radiating,
            self.influenced,
            self.a,
            self.b,
            self.c,
            self.method,
            self.metrics,
            self.note,
        )


@dataclass(frozen=True)
class MemoryBlock:
    """MIMO state-space model of the fluid memory of a group of DOFs that share their
    states: K_D(s) = c (sI − a)⁻¹ b for the DOFs D = ``dofs``.

    Attributes
    ----------
    dofs
        0-based DOF indices of the block, in the order of the inputs of ``b`` and the
        outputs of ``c``.
    a, b, c
        State matrix (n, n), input matrix (n, m), output matrix (m, n), m = len(dofs).
    method
        How it was identified (``"vf"``: common-pole vector fitting).
    metrics
        Fit measures per modelled pair, ``{(i, j): {...}}`` with model indices i ≤ j.
    note
        Anything the user should know.
    """

    dofs: tuple[int, ...]
    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    method: str = "vf"
    metrics: Mapping[tuple[int, int], Mapping[str, Any]] = field(default_factory=dict)
    note: str = ""

    @property
    def order(self) -> int:
        """Number of states."""
        return int(np.shape(self.a)[0])

    def poles(self) -> NDArray[np.complex128]:
        """Eigenvalues of ``a``."""
        return np.linalg.eigvals(self.a) if self.order else np.empty(0, dtype=complex)

    def is_stable(self) -> bool:
        """All poles in the open left half-plane."""
        return bool(np.all(self.poles().real < 0))

    def element(self, i: int, j: int) -> CouplingModel:
        """K_ij of the block as a SISO model (model indices; the block's own states, so
        not minimal), with the pair's metrics."""
        ii, jj = self.dofs.index(i), self.dofs.index(j)
        key = self._metrics_key(i, j)
        return CouplingModel(
            i,
            j,
            np.asarray(self.a, dtype=float),
            np.asarray(self.b, dtype=float)[:, jj],
            np.asarray(self.c, dtype=float)[ii, :],
            self.method,
            dict(self.metrics.get(key, {})),
            self.note,
        )

    def element_minimal(self, i: int, j: int, rtol: float = 1e-10) -> CouplingModel:
        """K_ij of the block as a minimal SISO model: the block's modes, those with the
        same pole merged (a residue matrix of rank r gives r equal poles) and those whose
        residue in K_ij is below ``rtol`` of the largest left out; real Jordan form
        (1/(s − p) for a real pole, a 2×2 block for a pair). Exact up to the dropped
        modes."""
        ii, jj = self.dofs.index(i), self.dofs.index(j)
        key = self._metrics_key(i, j)
        a, b, c = (np.asarray(x, dtype=float) for x in (self.a, self.b, self.c))
        if not self.order:
            empty = np.zeros(0)
            return CouplingModel(i, j, np.zeros((0, 0)), empty, empty, self.method)
        lam, v = np.linalg.eig(a)
        if np.linalg.cond(v) > 1e10:  # defective: keep the block's states
            return self.element(i, j)
        residue = (c[ii] @ v) * np.linalg.solve(v, b[:, jj])
        poles: list[complex] = []
        sums: list[complex] = []
        for p, r in zip(lam, residue, strict=True):
            if p.imag < 0:
                continue  # the conjugate carries it
            for k, q in enumerate(poles):
                if abs(p - q) <= 1e-8 * max(abs(p), 1e-300):
                    sums[k] += r
                    break
            else:
                poles.append(complex(p))
                sums.append(complex(r))
        top = max((abs(r) for r in sums), default=0.0)
        blocks_a, blocks_c, blocks_b = [], [], []
        for p, r in zip(poles, sums, strict=True):
            if abs(r) <= rtol * top:
                continue
            if abs(p.imag) <= 1e-12 * abs(p):
                blocks_a.append(np.array([[p.real]]))
                blocks_b.append([1.0])
                blocks_c.append([r.real])
            else:  # r/(s − p) + r̄/(s − p̄) = c (sI − a)⁻¹ b
                blocks_a.append(np.array([[p.real, p.imag], [-p.imag, p.real]]))
                blocks_b.append([2.0, 0.0])
                blocks_c.append([r.real, r.imag])
        if not blocks_a:
            empty = np.zeros(0)
            return CouplingModel(i, j, np.zeros((0, 0)), empty, empty, self.method)
        import scipy.linalg

        return CouplingModel(
            i,
            j,
            scipy.linalg.block_diag(*blocks_a),
            np.concatenate(blocks_b),
            np.concatenate(blocks_c),
            self.method,
            dict(self.metrics.get(key, {})),
            self.note,
        )

    def _metrics_key(self, i: int, j: int) -> tuple[int, int]:
        """The key of pair (i, j) in :attr:`metrics`: (i, j) itself for a pair fitted as
        given (each direction has its measures), else (min, max)."""
        return (i, j) if (i, j) in self.metrics else (min(i, j), max(i, j))

    def is_symmetric(self, rtol: float = 1e-9) -> bool:
        """Whether K_D(s) = K_D(s)ᵀ (reciprocity, zero speed): a block whose couplings were
        fitted as given is not. Tested on K(jω) at the magnitudes of its poles and a
        decade either side, to ``rtol`` of max|K|."""
        if not self.order or len(self.dofs) < 2:
            return True
        poles = np.abs(self.poles())
        w = np.geomspace(poles.min() / 10, poles.max() * 10, 64)
        a, b, c = (np.asarray(x, dtype=float) for x in (self.a, self.b, self.c))
        lam, v = np.linalg.eig(a)
        if np.linalg.cond(v) < 1e10:
            k = np.einsum("ik,wk,kj->wij", c @ v, 1.0 / (1j * w[:, None] - lam[None, :]),
                          np.linalg.solve(v, b))  # fmt: skip
        else:
            eye = np.eye(self.order)
            k = np.array([c @ np.linalg.solve(1j * x * eye - a, b) for x in w])
        top = float(np.abs(k).max())
        return bool(np.abs(k - np.swapaxes(k, 1, 2)).max() <= rtol * max(top, 1e-300))

    def pairs(self) -> list[tuple[int, int]]:
        """The modelled pairs (i, j), both orders, in row-major order."""
        keys = set(self.metrics) or {(min(i, j), max(i, j)) for i in self.dofs for j in self.dofs}
        out = set()
        for i, j in keys:
            out |= {(i, j), (j, i)}
        return sorted(out)


def modal_form(a: ArrayLike) -> tuple[NDArray, NDArray, bool]:
    """(λ, V, usable) of ``a``: its eigen-decomposition and whether V is well enough
    conditioned for the modal sums of :func:`siso_frequency_response` (shared by the pairs
    of one block: one decomposition instead of one per pair)."""
    a = np.asarray(a, dtype=float)
    if a.size == 0:
        return ModalForm(np.zeros(0, dtype=complex), np.zeros((0, 0), dtype=complex), True)
    lam, v = np.linalg.eig(a)
    return ModalForm(lam, v, bool(np.linalg.cond(v) < 1e10))


def as_modal_form(modal, a: ArrayLike) -> ModalForm:
    """``modal`` as a :class:`ModalForm` (a plain (λ, V, usable) wrapped; None: the
    :func:`modal_form` of ``a``)."""
    if modal is None:
        return modal_form(a)
    return modal if isinstance(modal, ModalForm) else ModalForm(*modal)


def siso_frequency_response(
    a: ArrayLike, b: ArrayLike, c: ArrayLike, omega: ArrayLike, modal=None
) -> NDArray:
    """c (jωI − a)⁻¹ b for each ω, through the eigen-decomposition of ``a`` (``modal``:
    its :func:`modal_form`, when known).

    Falls back to a linear solve per frequency when ``a`` is defective.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float).reshape(-1)
    c = np.asarray(c, dtype=float).reshape(-1)
    s = 1j * np.asarray(omega, dtype=float).reshape(-1)
    if a.size == 0:
        return np.zeros(s.size, dtype=complex)
    modal = as_modal_form(modal, a)
    lam, v, usable = modal
    if usable:
        return ((c @ v) * modal.solved(b)) @ (1.0 / (s[None, :] - lam[:, None]))
    eye = np.eye(a.shape[0])
    return np.array([c @ np.linalg.solve(si * eye - a, b) for si in s])


def siso_impulse_response(
    a: ArrayLike, b: ArrayLike, c: ArrayLike, t: ArrayLike, modal=None
) -> NDArray:
    """c e^{a t} b for each t, through the eigen-decomposition of ``a`` (``modal``: its
    :func:`modal_form`, when known)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float).reshape(-1)
    c = np.asarray(c, dtype=float).reshape(-1)
    grid = t
    t = np.asarray(t, dtype=float).reshape(-1)
    if a.size == 0:
        return np.zeros(t.size)
    modal = as_modal_form(modal, a)
    _, v, usable = modal
    if usable:  # V⁻¹ b and e^{λ t} shared by a block's pairs
        return np.real(modal.exponentials(grid) @ ((c @ v) * modal.solved(b)))
    from scipy.linalg import expm

    return np.array([c @ expm(a * ti) @ b for ti in t])


@dataclass(frozen=True)
class RadiationModel:
    """MIMO state-space model of the fluid memory, with its provenance.

    Attributes
    ----------
    dofs
        DOF labels, inputs and outputs alike (``Surge`` … ``Yaw``).
    couplings
        One :class:`CouplingModel` per modelled (i, j); symmetric pairs appear as two
        entries with the same matrices. Couplings not listed are zero.
    added_mass_inf
        A∞ (n, n), kg, kg·m, kg·m², used with the model: A(ω) = A∞ + Im K(jω)/ω.
    attrs
        Provenance: source file, history, options, A∞ method …
    blocks
        :class:`MemoryBlock` models of groups of DOFs sharing their states (the pairs
        inside a block are not in ``couplings``).

    Examples
    --------
    >>> import numpy as np
    >>> k = CouplingModel(2, 2, np.array([[-1.0]]), np.array([1.0]), np.array([2.0]))
    >>> model = RadiationModel(("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"), (k,),
    ...                        np.eye(6))
    >>> model.total_order, model.A.shape
    (1, (1, 1))
    """

    dofs: tuple[str, ...]
    couplings: tuple[CouplingModel, ...]
    added_mass_inf: NDArray[np.float64]
    attrs: Mapping[str, Any] = field(default_factory=dict)
    blocks: tuple[MemoryBlock, ...] = ()

    def __post_init__(self) -> None:
        n = len(self.dofs)
        if np.shape(self.added_mass_inf) != (n, n):
            raise CumminsError(f"added_mass_inf must be {n}×{n}")
        seen = set()
        for k in self.couplings:
            key = (k.influenced, k.radiating)
            if key in seen:
                raise CumminsError(f"coupling {key} is given twice")
            if not (0 <= k.influenced < n and 0 <= k.radiating < n):
                raise CumminsError(f"coupling {key} is outside the {n} DOFs")
            seen.add(key)
        owned: set[int] = set()
        for block in self.blocks:
            m = len(block.dofs)
            if not all(0 <= d < n for d in block.dofs) or len(set(block.dofs)) != m:
                raise CumminsError(f"block {block.dofs} is not a set of the {n} DOFs")
            if owned & set(block.dofs):
                raise CumminsError(f"DOFs {sorted(owned & set(block.dofs))} are in two blocks")
            owned |= set(block.dofs)
            r = block.order
            if np.shape(block.b) != (r, m) or np.shape(block.c) != (m, r):
                raise CumminsError(f"block {block.dofs}: b must be {r}×{m} and c {m}×{r}")
        inside = {key for key in seen if key[0] in owned and key[1] in owned}
        if any(key[0] in b.dofs and key[1] in b.dofs for key in inside for b in self.blocks):
            raise CumminsError("a coupling lies inside a block: model each pair once")

    # ------------------------------------------------------------------ MIMO matrices

    @functools.cached_property
    def _mimo(self) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        n = len(self.dofs)
        total = sum(k.order for k in self.couplings) + sum(k.order for k in self.blocks)
        a = np.zeros((total, total))
        b = np.zeros((total, n))
        c = np.zeros((n, total))
        owner = np.zeros(total, dtype=int)
        start = 0
        for index, k in enumerate(self.couplings):
            stop = start + k.order
            a[start:stop, start:stop] = k.a
            b[start:stop, k.radiating] = k.b
            c[k.influenced, start:stop] = k.c
            owner[start:stop] = index
            start = stop
        for index, block in enumerate(self.blocks, start=len(self.couplings)):
            stop = start + block.order
            dofs = list(block.dofs)
            a[start:stop, start:stop] = block.a
            b[start:stop][:, dofs] = block.b
            c[dofs, start:stop] = block.c
            owner[start:stop] = index
            start = stop
        return a, b, c, owner

    @property
    def A(self) -> NDArray:
        """State matrix A_r (n_states, n_states)."""
        return self._mimo[0]

    @property
    def B(self) -> NDArray:
        """Input matrix B_r (n_states, n_dofs)."""
        return self._mimo[1]

    @property
    def C(self) -> NDArray:
        """Output matrix C_r (n_dofs, n_states)."""
        return self._mimo[2]

    @property
    def D(self) -> NDArray:
        """Feed-through D_r = 0 (n_dofs, n_dofs): A∞ is kept separate."""
        n = len(self.dofs)
        return np.zeros((n, n))

    @property
    def state_coupling(self) -> NDArray[np.int_]:
        """Index in :attr:`couplings` of the coupling owning each state (blocks follow the
        couplings: block k owns the states marked ``len(couplings) + k``)."""
        return self._mimo[3]

    def as_couplings(self) -> RadiationModel:
        """The same K(s) with every block written as one minimal SISO model per pair
        (:meth:`MemoryBlock.element_minimal`): for the file formats that store one model
        per coupling (MSS ``vesselABC``, BEMIO, OpenFAST's states per radiating DOF). More
        states than the block (its shared states are repeated per pair). A block that is
        not symmetric (:meth:`MemoryBlock.is_symmetric`: couplings fitted as given) gives
        K_ij and K_ji as two models."""
        if not self.blocks:
            return self
        couplings = list(self.couplings)
        for block in self.blocks:
            symmetric = block.is_symmetric()
            for i, j in block.pairs():
                if i <= j or not symmetric:  # fitted as given: K_ij and K_ji each
                    k = block.element_minimal(i, j)
                    couplings.append(k)
                    if i != j and symmetric:
                        couplings.append(k.transposed())
        couplings.sort(key=lambda k: (k.influenced, k.radiating))
        return RadiationModel(self.dofs, tuple(couplings), self.added_mass_inf, self.attrs)

    @property
    def modelled(self) -> tuple[CouplingModel, ...]:
        """Every modelled pair (i, j) as a SISO model: the couplings, and each pair of
        every block as :meth:`MemoryBlock.element` (with the block's states), sorted."""
        views = list(self.couplings)
        for block in self.blocks:
            views += [block.element(i, j) for i, j in block.pairs()]
        return tuple(sorted(views, key=lambda k: (k.influenced, k.radiating)))

    @property
    def total_order(self) -> int:
        """Number of states of the MIMO model."""
        return int(self.A.shape[0])

    def __repr__(self) -> str:  # not every pole and residue: .summary() tables the fit
        return (
            f"RadiationModel({len(self.dofs)} DOFs {', '.join(self.dofs)}: {self.total_order} "
            f"states, {len(self.couplings)} couplings, {len(self.blocks)} blocks, "
            f"stable={self.is_stable()})"
        )

    def coupling(self, i: int | str, j: int | str) -> CouplingModel | None:
        """The model of coupling (i, j) (indices or DOF labels), or None; a pair inside
        a block as :meth:`MemoryBlock.element`."""
        i = self.dofs.index(i) if isinstance(i, str) else i
        j = self.dofs.index(j) if isinstance(j, str) else j
        for k in self.couplings:
            if (k.influenced, k.radiating) == (i, j):
                return k
        for block in self.blocks:
            if (i, j) in block.pairs():
                return block.element(i, j)
        return None

    def is_stable(self) -> bool:
        """True when every coupling and block model is stable (hence the MIMO model)."""
        return all(k.is_stable() for k in self.couplings) and all(
            b.is_stable() for b in self.blocks
        )

    # ------------------------------------------------------------------ responses

    def _labels(self) -> dict:
        return {"influenced_dof": list(self.dofs), "radiating_dof": list(self.dofs)}

    @functools.cached_property
    def _modal(self) -> list[tuple[int, int, NDArray, NDArray | None]]:
        """(i, j, poles, residues) per coupling; residues None when ``a`` is defective."""
        out = []
        for k in self.couplings:
            if not k.order:
                continue
            lam, v = np.linalg.eig(k.a)
            if np.linalg.cond(v) < 1e10:
                out.append((k.influenced, k.radiating, lam, (k.c @ v) * np.linalg.solve(v, k.b)))
            else:
                out.append((k.influenced, k.radiating, lam, None))
        return out

    def response(self, omega: ArrayLike, *, batched: bool = False) -> NDArray[np.complex128]:
        """K(jω) as an array (len(omega), n_dofs, n_dofs): :meth:`frequency_response`
        without the labels, for repeated evaluation. ``batched``: a block's modal sums as
        matrix products (the same values to rounding, a sum ordered otherwise; 20× faster
        on RM3's 200-state block over the passivity test's sweep)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        n = len(self.dofs)
        out = np.zeros((w.size, n, n), dtype=complex)
        s = 1j * w
        for (i, j, lam, residues), k in zip(
            self._modal, [k for k in self.couplings if k.order], strict=True
        ):
            if residues is None:
                out[:, i, j] = k.frequency_response(w)
            else:
                out[:, i, j] = (1.0 / (s[:, None] - lam[None, :])) @ residues
        for block, (lam, left, right) in zip(self.blocks, self._block_modal, strict=True):
            dofs = np.asarray(block.dofs)
            if left is None:
                eye = np.eye(block.order)
                values = np.array(
                    [block.c @ np.linalg.solve(1j * x * eye - block.a, block.b) for x in w]
                )
            elif batched:  # Σ_k (c V)_ik (V⁻¹ b)_kj / (s − λ_k): one product
                outer = (left.T[:, :, None] * right[:, None, :]).reshape(lam.size, -1)
                values = ((1.0 / (s[:, None] - lam[None, :])) @ outer).reshape(
                    w.size, *left.shape[:1], -1
                )
            else:  # c V diag(1/(s − λ)) V⁻¹ b
                values = np.einsum("ik,wk,kj->wij", left, 1.0 / (s[:, None] - lam[None, :]), right)
            out[:, dofs[:, None], dofs[None, :]] = values
        return out

    @functools.cached_property
    def _block_modal(self) -> list[tuple[NDArray, NDArray | None, NDArray | None]]:
        """(poles, c V, V⁻¹ b) per block; (poles, None, None) when ``a`` is defective."""
        out = []
        for block in self.blocks:
            if not block.order:
                out.append(
                    (np.empty(0), np.zeros((len(block.dofs), 0)), np.zeros((0, len(block.dofs))))
                )
                continue
            lam, v = np.linalg.eig(block.a)
            if np.linalg.cond(v) < 1e10:
                out.append((lam, block.c @ v, np.linalg.solve(v, block.b)))
            else:
                out.append((lam, None, None))
        return out

    def frequency_response(self, omega: ArrayLike) -> xr.DataArray:
        """K(jω) = C (jωI − A)⁻¹ B, dims (omega, influenced_dof, radiating_dof)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        out = self.response(w)
        return xr.DataArray(
            out,
            dims=("omega", "influenced_dof", "radiating_dof"),
            coords={"omega": w, **self._labels()},
            name="memory_transfer_function",
        )

    def added_mass(self, omega: ArrayLike) -> xr.DataArray:
        """A(ω) = A∞ + Im K(jω)/ω of the model (kg, kg·m, kg·m²)."""
        k = self.frequency_response(omega)
        out = self.added_mass_inf[None] + k.imag / k.omega.values[:, None, None]
        return out.rename("added_mass")

    def radiation_damping(self, omega: ArrayLike) -> xr.DataArray:
        """B(ω) = Re K(jω) of the model (kg/s, kg·m/s, kg·m²/s)."""
        return self.frequency_response(omega).real.rename("radiation_damping")

    def impulse_response(self, t: ArrayLike) -> xr.DataArray:
        """K(t) = C e^{At} B, dims (time, influenced_dof, radiating_dof)."""
        t = np.asarray(t, dtype=float).reshape(-1)
        n = len(self.dofs)
        out = np.zeros((t.size, n, n))
        for k in self.couplings:
            out[:, k.influenced, k.radiating] = k.impulse_response(t)
        for block in self.blocks:
            for i, j in block.pairs():
                out[:, i, j] = block.element(i, j).impulse_response(t)
        return xr.DataArray(
            out,
            dims=("time", "influenced_dof", "radiating_dof"),
            coords={"time": t, **self._labels()},
            name="retardation_function",
        )

    # ------------------------------------------------------------------ exports

    def to_scipy(self) -> scipy.signal.StateSpace:
        """The MIMO model as :class:`scipy.signal.StateSpace` (continuous time)."""
        import scipy.signal

        if self.total_order == 0:
            raise FitError("the model has no states")
        return scipy.signal.StateSpace(self.A, self.B, self.C, self.D)

    def to_control(self):
        """The MIMO model as a python-control ``StateSpace`` (needs ``pip install control``)."""
        try:
            import control
        except ImportError as exc:
            raise CumminsError(
                "python-control is not installed",
            ) from exc
        return control.ss(
            self.A, self.B, self.C, self.D, inputs=list(self.dofs), outputs=list(self.dofs)
        )

    def summary(self) -> list[dict]:
        """One dictionary per modelled pair (:attr:`modelled`): i, j (1-based), order,
        method and metrics (a pair of a block gives the block's order)."""
        rows = []
        for k in self.modelled:
            rows.append(
                {
                    "i": k.influenced + 1,
                    "j": k.radiating + 1,
                    "order": k.order,
                    "method": k.method,
                    **dict(k.metrics),
                    "note": k.note,
                }
            )
        return rows

    # ------------------------------------------------------------------ files

    def save(self, path: str | os.PathLike[str], *, force: bool = False) -> Path:
        """Write the model as NetCDF (the layout of :mod:`cummins.radiation.model_file`).

        An existing file is replaced only with ``force=True``.
        """
        p = Path(path)
        check_writable(p, force)
        _file_format("write")(self, p)
        return p

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> RadiationModel:
        """Read a model written by :meth:`save`."""
        return _file_format("read")(path)


# The model's file format (cummins.radiation.model_file) imports this module and registers
# its reader and writer here when cummins.radiation is imported: the dependency runs one
# way, from the format to the model, and save/load need no import of the format.
_FILE_FORMAT: dict[str, Callable[..., Any]] = {}


def register_file_format(
    read: Callable[[str | os.PathLike[str]], RadiationModel],
    write: Callable[[RadiationModel, Path], Any],
) -> None:
    """Set the functions :meth:`RadiationModel.load` and :meth:`RadiationModel.save` use."""
    _FILE_FORMAT.update(read=read, write=write)


def _file_format(which: str) -> Callable[..., Any]:
    if which not in _FILE_FORMAT:  # only when cummins.radiation.model_file failed to load
        raise CumminsError(
            "no file format is registered for radiation models",
            hint="import cummins.radiation (it registers cummins.radiation.model_file)",
        )
    return _FILE_FORMAT[which]


#: Model attributes holding a position (x, y, z) per body, flipped with the axes.
POSITION_ATTRS: tuple[str, ...] = (
    "reference_point",
    "center_of_gravity",
    "center_of_buoyancy",
    "mss_r_g",
)
#: Model attributes holding a DOF×DOF matrix, transformed as T M T with the axes.
MATRIX_ATTRS: tuple[str, ...] = ("inertia_matrix", "hydrostatic_stiffness")


def _axis_signs(dofs) -> NDArray[np.float64]:
    """T of the axis change per DOF label: (1, −1, −1, 1, −1, −1) on each body's rigid
    modes, 1 on generalized modes (``Mode7`` …: their amplitude is defined by the solver's
    mode shape, which turns with the axes), as :func:`cummins.hydrodb.change_axes` does."""
    from cummins.hydrodb import dof_index, is_rigid_body_dof
    from cummins.kinematics import Z_UP_TO_Z_DOWN

    try:
        return np.array(
            [Z_UP_TO_Z_DOWN[dof_index(d)] if is_rigid_body_dof(d) else 1.0 for d in dofs]
        )
    except CumminsError as exc:
        raise CumminsError(f"cannot change the axes of this model: {exc}") from None


def change_model_axes(
    model: RadiationModel, to: str, *, current: str | None = None
) -> RadiationModel:
    """The model in another axis convention (z-up solver axes ↔ Fossen's z-down axes).

    With T = diag(1, −1, −1, 1, −1, −1) per body (:data:`cummins.kinematics.Z_UP_TO_Z_DOWN`),
    K(s) becomes T K(s) T: coupling (i, j) keeps its poles (``a``, ``b``) and its output
    vector becomes T_i T_j c. A∞ and the matrix attributes become T M T, the position
    attributes (x, −y, −z); ``axis_convention`` is set and ``history`` says what was
    done. Exact (sign changes only).

    Parameters
    ----------
    model
        The model.
    to
        ``"z-up"`` or ``"z-down"``.
    current
        The model's axes, when its ``axis_convention`` attribute does not say
        (default ``"z-up"`` then).
    """
    from cummins.hydrodb import AXIS_CONVENTIONS

    for value in (to, current):
        if value is not None and value not in AXIS_CONVENTIONS:
            raise CumminsError(
                f"unknown axis convention {value!r}; use one of {', '.join(AXIS_CONVENTIONS)}"
            )
    current = current or model.attrs.get("axis_convention", "z-up")
    attrs: dict[str, Any] = dict(model.attrs)
    attrs["axis_convention"] = to
    if current == to:
        return replace(model, attrs=attrs)
    t = _axis_signs(model.dofs)
    n = t.size
    couplings = tuple(
        replace(k, c=np.asarray(k.c, dtype=float) * (t[k.influenced] * t[k.radiating]))
        for k in model.couplings
    )
    blocks = tuple(
        replace(
            block,
            b=np.asarray(block.b, dtype=float) * t[list(block.dofs)][None, :],
            c=t[list(block.dofs)][:, None] * np.asarray(block.c, dtype=float),
        )
        for block in model.blocks
    )
    flip = np.array([1.0, -1.0, -1.0])
    for key in POSITION_ATTRS:
        if key in attrs and np.size(attrs[key]) and np.size(attrs[key]) % 3 == 0:
            attrs[key] = (np.asarray(attrs[key], dtype=float).reshape(-1, 3) * flip).reshape(-1)
    for key in MATRIX_ATTRS:
        if key in attrs and np.shape(attrs[key]) == (n, n):
            attrs[key] = t[:, None] * np.asarray(attrs[key], dtype=float) * t[None, :]
    line = f"axes changed from {current} to {to} ({AXIS_CONVENTIONS[to]})"
    history = attrs.get("history")
    attrs["history"] = f"{history}\n{line}" if isinstance(history, str) and history else line
    added = t[:, None] * np.asarray(model.added_mass_inf, dtype=float) * t[None, :]
    return RadiationModel(model.dofs, couplings, added, attrs, blocks)


def symmetric_couplings(models: Sequence[CouplingModel]) -> tuple[CouplingModel, ...]:
    """Add the transposed copy (j, i) of every off-diagonal model fitted for i < j."""
    out: list[CouplingModel] = []
    present = {(k.influenced, k.radiating) for k in models}
    for k in models:
        out.append(k)
        if k.influenced != k.radiating and (k.radiating, k.influenced) not in present:
            out.append(k.transposed())
    return tuple(sorted(out, key=lambda k: (k.influenced, k.radiating)))


#: The attribute of a result (a run, a batch study's results) that records the failures
#: of the radiation model it was made with, one per line.
MODEL_FAILURES = "model_failures"


def model_failures(attrs: Mapping) -> list[str]:
    """The failures of a model (its ``failures``: the targets its fit missed) or those a
    result records (:data:`MODEL_FAILURES`), as a list of sentences."""
    found = attrs.get("failures") or attrs.get(MODEL_FAILURES) or []
    if isinstance(found, str):
        found = found.splitlines()
    return [str(f) for f in found if str(f).strip()]
