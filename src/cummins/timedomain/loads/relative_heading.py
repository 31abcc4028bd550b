"""The second-order wave force at the vessel's instantaneous relative heading.

A vessel on DP yaws — it weathervanes, turns to a new heading, follows a set-point
change in yaw — and its wave drift follows the relative direction β_i − ψ(t) of each
wave component, as the first-order force does (Smogeli et al. (2004) eq. 46, where the
excitation is taken at β_j − ψ; eq. 47 for the mean drift). :class:`HeadingTable` holds the
data at each of their directions γ_a (after port/starboard mirroring:
:func:`cummins.seakeeping.headings.mirror_headings` for ``drift_force``,
:func:`cummins.qtf.headings.mirrored_qtf` for a QTF) and interpolates the force linearly
in the relative direction at every call — the interpolation of the fixed-heading load
(:mod:`cummins.qtf.interpolation`: linear in direction), so that at the heading ψ₀ the
force equals that load's to rounding, and a force linear in Q is interpolated exactly:

* ``mean``: F̄(ψ) = Σ_g Σ_{i∈g} a_i² T_i(β_g − ψ), T_i(γ_a) tabulated per component
  (the QTF's diagonal or ``drift_force``, linear in ω) and summed per direction g of
  the sea once: O(G) per call;
* ``newman``: F(t, ψ) = Re[(Σ_i u_i a_i T_i(β_i − ψ))(Σ_j ū_j a_j)] (Newman (1974)):
  O(N) per call;
* ``full``: the components of each direction g make n harmonic sums on the QTF's
  frequencies, s_g(t) = Σ_{i∈g} u_i a_i W_i· (W the bilinear weights, as
  :func:`~cummins.timedomain.loads.quadratic_form.grid_form`), and

      F_d(t, ψ) = Re Σ_g Σ_h s_gᵀ Q_d(γ_gh − ψ) op(s_h),

  γ_gh the mean direction of g and h for a unidirectional QTF (each of β_g, β_h for a
  bi-directional one), Q_d linear between the data directions: per call, one n × n
  product per data direction the pairs use (2 for a long-crested sea, against the
  fixed heading's 1) — exact, no truncation (the fixed-heading form of a short-crested
  sea is truncated at ``tol``).

A relative direction in a gap of the data wider than ``max_gap`` (data over an arc that
no mirroring completes) takes the values of the nearest data direction, and a warning says
so once, with the time and the data's directions; data of one direction are held at it
for every heading (the load's notes say so).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from cummins.errors import AssumptionWarning
from cummins.qtf.data import QTFTable
from cummins.qtf.interpolation import DirectionStencil, mean_direction, weight_matrix

_TWO_PI = 2.0 * np.pi


def _directions_text(directions: NDArray[np.float64]) -> str:
    """The data's directions in degrees, 12 at most."""
    deg = np.degrees(np.mod(directions, _TWO_PI))
    text = ", ".join(f"{x:.4g}" for x in deg[:12])
    return text + (" …" if deg.size > 12 else "") + " deg"


@dataclass(frozen=True)
class QTFStack:
    """A QTF on the frequencies a sea uses, direction by direction: ``values`` (m, d, n, n)
    (unidirectional) or (m, m, d, n, n) (bi-directional), complex, N/m² and N·m/m²;
    ``difference`` (conjugate the second sums) or sum frequencies."""

    values: NDArray[np.complex128]
    bidirectional: bool
    difference: bool


def qtf_stack(table: QTFTable, used: NDArray[np.intp]) -> QTFStack:
    """The :class:`QTFStack` of ``table`` on its frequencies ``used`` (indices)."""
    v = table.values[np.ix_(used, used)]  # (n, n, m[, m], d)
    v = np.moveaxis(v, (0, 1), (-2, -1))  # (m[, m], d, n, n)
    return QTFStack(np.ascontiguousarray(v), table.bidirectional, table.kind == "difference")


@dataclass(frozen=True, eq=False)
class HeadingTable:
    """The second-order force of a sea at any relative heading (module docstring).

    Attributes
    ----------
    model
        ``"mean"``, ``"newman"`` or ``"full"``.
    omega, phase, amplitude, direction
        The sea's components: rad/s, rad, m, and the direction of travel in the n-frame
        (rad), shape (N,).
    directions
        γ_a, the data's directions (after mirroring), rad, shape (m,).
    drift
        T_i(γ_a), the mean drift per squared amplitude of each component at each data
        direction, shape (m, N, d), N/m² and N·m/m² (zero outside the data's frequencies).
    columns
        a_i W_i·, the amplitude-weighted interpolation weights of the components on the
        difference QTF's frequencies the sea uses, shape (N, n) (``"full"``), else None.
    difference
        The difference QTF on those frequencies (``"full"``).
    sum_columns, sum
        The same for the sum QTF (None without sum frequencies).
    max_gap
        Widest gap between data directions to interpolate across, rad.
    what
        What the data are ("QTF", "mean drift"), for the warning.
    held
        The data have one direction: held at every heading.
    """

    model: str
    omega: NDArray[np.float64]
    phase: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    direction: NDArray[np.float64]
    directions: NDArray[np.float64]
    drift: NDArray[np.float64]
    columns: NDArray[np.float64] | None = None
    difference: QTFStack | None = None
    sum_columns: NDArray[np.float64] | None = None
    sum: QTFStack | None = None
    max_gap: float = np.pi / 2
    what: str = "QTF"
    held: bool = False
    _group: NDArray[np.intp] = field(init=False, repr=False)
    _group_direction: NDArray[np.float64] = field(init=False, repr=False)
    _group_mean: NDArray[np.float64] = field(init=False, repr=False)
    _members: NDArray[np.float64] = field(init=False, repr=False)
    _pair_direction: NDArray[np.float64] = field(init=False, repr=False)
    _lookup: DirectionStencil = field(init=False, repr=False)
    _warned: list = field(init=False, repr=False, default_factory=list)

    def __post_init__(self) -> None:
        beta = np.round(np.mod(self.direction, _TWO_PI), 12)
        unique, group = np.unique(beta, return_inverse=True)
        group = group.reshape(-1)
        first = np.array([self.direction[group == g][0] for g in range(unique.size)])
        members = (group[None, :] == np.arange(unique.size)[:, None]).astype(float)  # (G, N)
        a2 = self.amplitude**2
        # Σ_{i∈g} a_i² T_i(γ_a): the mean force of each direction g at each data direction
        group_mean = np.einsum("gi,i,aid->agd", members, a2, self.drift)
        object.__setattr__(self, "_group", group)
        object.__setattr__(self, "_group_direction", first)
        object.__setattr__(self, "_group_mean", group_mean)
        object.__setattr__(self, "_members", members)
        object.__setattr__(self, "_pair_direction", mean_direction(first[:, None], first[None, :]))
        object.__setattr__(self, "_lookup", DirectionStencil(self.directions, self.max_gap))

    @property
    def n_dofs(self) -> int:
        """Number of DOFs."""
        return self.drift.shape[2]

    def _stencil(self, relative: NDArray[np.float64], t: float):
        """Linear weights in the data directions at ``relative`` (rad); a direction
        outside them is held at the nearest (warned once)."""
        a0, a1, w, outside = self._lookup(relative)
        if outside.any() and not self.held and not self._warned:
            self._warned.append(t)
            angle = float(np.degrees(np.mod(relative.reshape(-1)[np.argmax(outside)], _TWO_PI)))
            warnings.warn(
                f"at t = {t:.6g} s the relative wave direction {angle:.4g} deg lies outside "
                f"the {self.what}'s directions ({_directions_text(self.directions)}, gaps "
                f"over {np.degrees(self.max_gap):.4g} deg not bridged): the second-order force "
                "takes the nearest direction's values there",
                AssumptionWarning,
                stacklevel=4,
            )
        return a0, a1, w

    def drift_at(self, psi: float, t: float = 0.0) -> NDArray[np.float64]:
        """T_i(β_i − ψ) of every component, shape (N, d), N/m² and N·m/m²."""
        a0, a1, w = self._stencil(self._group_direction - float(psi), t)
        g = self._group
        n = self.omega.size
        flat = self.drift.reshape(-1, self.n_dofs)
        rows = np.arange(n)
        lo = flat.take(a0[g] * n + rows, axis=0)
        hi = flat.take(a1[g] * n + rows, axis=0)
        return lo + w[g][:, None] * (hi - lo)

    def mean_force(self, psi: float, t: float = 0.0) -> NDArray[np.float64]:
        """The mean force Σ_i a_i² T_i(β_i − ψ), shape (d,), N and N·m."""
        a0, a1, w = self._stencil(self._group_direction - float(psi), t)
        groups = np.arange(a0.size)
        lo = self._group_mean[a0, groups]
        hi = self._group_mean[a1, groups]
        return (lo + w[:, None] * (hi - lo)).sum(axis=0)

    def force(self, t: float, psi: float, shift: NDArray | None = None) -> NDArray[np.float64]:
        """F(t) at the heading ψ (rad), shape (d,), N and N·m; ``shift`` the phase lag of
        each component at the vessel's position (rad)."""
        if self.model == "mean":
            return self.mean_force(psi, t)
        phase = self.omega * float(t) + self.phase
        if shift is not None:
            phase = phase - shift
        u = np.exp(1j * phase)
        if self.model == "newman":
            v = self.amplitude * u
            return (np.conj(v.sum()) * (v @ self.drift_at(psi, t))).real
        by_direction = self._members * u[None, :]  # (G, N)
        out = self._quadratic(self.difference, by_direction @ self.columns, psi, t)
        if self.sum is not None:
            out = out + self._quadratic(self.sum, by_direction @ self.sum_columns, psi, t)
        return out

    def _quadratic(self, stack: QTFStack, s: NDArray, psi: float, t: float) -> NDArray:
        """Re Σ_gh s_gᵀ Q(γ_gh − ψ) op(s_h) per DOF (module docstring), as
        Re Σ_a Σ_kl Q_a[k, l] R_a[k, l] with R_a = Σ_gh w_a,gh s_g[k] op(s_h)[l]: the
        outer products of the sums weighted per data direction a the pairs use, then
        one product with the QTF of those directions."""
        other = np.conj(s) if stack.difference else s
        if stack.bidirectional:
            a0, a1, w = self._stencil(self._group_direction - float(psi), t)
            used, inverse = np.unique(np.concatenate([a0, a1]), return_inverse=True)
            weights = np.zeros((used.size, a0.size))
            groups = np.arange(a0.size)
            weights[inverse[: a0.size], groups] += 1.0 - w
            weights[inverse[a0.size :], groups] += w
            left = weights @ s  # (u, n): Σ_g w_a,g s_g
            right = weights @ other
            r = left[:, None, :, None] * right[None, :, None, :]  # (u, u, n, n)
            q = stack.values[np.ix_(used, used)]  # (u, u, d, n, n)
            return np.einsum("abdkl,abkl->d", q, r).real
        a0, a1, w = self._stencil(self._pair_direction - float(psi), t)
        pairs = a0.size
        used, inverse = np.unique(np.concatenate([a0.ravel(), a1.ravel()]), return_inverse=True)
        weights = np.zeros((used.size, pairs))
        index = np.arange(pairs)
        weights[inverse[:pairs], index] += 1.0 - w.ravel()
        weights[inverse[pairs:], index] += w.ravel()
        g = s.shape[0]
        r = s.T @ (weights.reshape(used.size, g, g) @ other)  # (u, n, n)
        q = stack.values[used]  # (u, d, n, n)
        n2 = r.shape[1] * r.shape[2]
        return (q.reshape(used.size, -1, n2) @ r.reshape(used.size, n2, 1)).sum(axis=0)[:, 0].real


def heading_table(
    model: str,
    omega: NDArray[np.float64],
    phase: NDArray[np.float64],
    amplitude: NDArray[np.float64],
    direction: NDArray[np.float64],
    directions: NDArray[np.float64],
    drift: NDArray[np.float64],
    *,
    difference: QTFTable | None = None,
    sum_table: QTFTable | None = None,
    max_gap: float = np.pi / 2,
    what: str = "QTF",
) -> HeadingTable:
    """The :class:`HeadingTable` of a sea (n-frame directions ``direction``) from the
    per-direction drift ``drift`` (m, N, d) on ``directions`` and, for ``"full"``, the
    (mirrored) QTF tables, which must have ``directions``; components off a QTF's
    frequencies have no force from it."""
    parts: list = [None, None, None, None]
    for k, table in enumerate((difference, sum_table) if model == "full" else ()):
        if table is None:
            continue
        if not np.allclose(np.mod(table.directions, _TWO_PI), np.mod(directions, _TWO_PI)):
            raise ValueError("the QTF tables must have the directions of the drift table")
        weights = weight_matrix(table.omega, omega)
        used = np.flatnonzero(np.any(weights != 0, axis=0))
        parts[2 * k] = amplitude[:, None] * weights[:, used]
        parts[2 * k + 1] = qtf_stack(table, used)
    return HeadingTable(
        model,
        np.asarray(omega, dtype=float),
        np.asarray(phase, dtype=float),
        np.asarray(amplitude, dtype=float),
        np.asarray(direction, dtype=float),
        np.asarray(directions, dtype=float),
        np.asarray(drift, dtype=float),
        *parts,
        max_gap,
        what,
        np.asarray(directions).size == 1,
    )
