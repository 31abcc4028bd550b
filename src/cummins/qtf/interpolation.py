"""A QTF between its grid points: bilinear in (ω₁, ω₂), linear in the wave directions.

Q(ω₁, ω₂) between the grid points is the bilinear interpolation of its real and imaginary
parts (the interpolation is linear, so it is the same as interpolating the complex
values); a pair with a frequency outside the grid has no second-order force (zero), and
:class:`Coverage` says which share of the sea's energy that leaves out. Between wave
directions the interpolation is linear on the circle (periodic when the data go round
it); across a gap wider than ``max_gap`` it is refused. Unidirectional data (both waves
of a pair travelling the same way) give the pair of two components of different
directions β_i, β_j its value at their mean direction: an approximation for
short-crested seas (a bi-directional QTF has the values themselves), which the loads say
when they make it.

Because the same one-dimensional weights are used for ω₁ and ω₂, the interpolated
difference QTF keeps the symmetry Q(ω_j, ω_i) = Q(ω_i, ω_j)* exactly, and the sum QTF
Q(ω_j, ω_i) = Q(ω_i, ω_j).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import HydroDataError
from cummins.qtf.data import QTFTable

_TWO_PI = 2.0 * np.pi


@dataclass(frozen=True)
class Coverage:
    """Which wave components fall on the QTF's frequency grid.

    Attributes
    ----------
    inside
        Per component: its frequency is within [ω_min, ω_max] of the grid.
    omega_range
        The grid's range, rad/s.
    energy_outside
        Share of the sea's variance Σ a²/2 carried by the components outside (0–1).
    """

    inside: NDArray[np.bool_]
    omega_range: tuple[float, float]
    energy_outside: float

    def note(self) -> str | None:
        """A one-line note when components fall outside, else None."""
        if self.inside.all():
            return None
        lo, hi = self.omega_range
        return (
            f"{int((~self.inside).sum())} wave components ({100 * self.energy_outside:.2g} % of "
            f"the sea's variance) lie outside the QTF's frequencies {lo:.4g}–{hi:.4g} rad/s: "
            "no second-order force from the pairs they form"
        )


def coverage(table: QTFTable, omega: ArrayLike, amplitude: ArrayLike) -> Coverage:
    """The :class:`Coverage` of components of frequencies ``omega`` (rad/s) and
    amplitudes ``amplitude`` (m) by the grid of ``table``."""
    w = np.asarray(omega, dtype=float).reshape(-1)
    a2 = np.asarray(amplitude, dtype=float).reshape(-1) ** 2
    lo, hi = float(table.omega[0]), float(table.omega[-1])
    inside = (w >= lo * (1 - 1e-12)) & (w <= hi * (1 + 1e-12))
    total = a2.sum()
    outside = float(a2[~inside].sum() / total) if total > 0 else 0.0
    return Coverage(inside, (lo, hi), outside)


def frequency_weights(
    grid: NDArray[np.float64], x: ArrayLike
) -> tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.bool_]]:
    """Linear interpolation on ``grid``: the left node i, the weight t of node i + 1 and
    whether x is inside [grid₀, grid₋₁]; value = (1 − t) v[i] + t v[i+1]."""
    x = np.asarray(x, dtype=float)
    n = grid.size
    inside = (x >= grid[0] * (1 - 1e-12)) & (x <= grid[-1] * (1 + 1e-12))
    if n == 1:
        return np.zeros(x.shape, dtype=np.intp), np.zeros(x.shape), inside
    xc = np.clip(x, grid[0], grid[-1])
    i = np.clip(np.searchsorted(grid, xc, side="right") - 1, 0, n - 2)
    t = (xc - grid[i]) / (grid[i + 1] - grid[i])
    return i, t, inside


def weight_matrix(grid: NDArray[np.float64], x: ArrayLike) -> NDArray[np.float64]:
    """The (len(x), len(grid)) matrix W of linear interpolation: v(x) = W v; rows of
    points outside the grid are zero."""
    x = np.asarray(x, dtype=float).reshape(-1)
    i, t, inside = frequency_weights(grid, x)
    w = np.zeros((x.size, grid.size))
    rows = np.arange(x.size)
    w[rows, i] = (1.0 - t) * inside
    if grid.size > 1:
        w[rows, i + 1] += t * inside
    return w


def direction_weights(
    directions: NDArray[np.float64], beta: ArrayLike, *, max_gap: float = np.pi / 2, what="QTF"
) -> tuple[NDArray[np.intp], NDArray[np.intp], NDArray[np.float64]]:
    """Linear interpolation in direction on the circle: nodes a, b and the weight t of b
    (value = (1 − t) v[a] + t v[b]) for each β (rad).

    A direction within 10⁻⁶ rad of a data direction takes it; otherwise the two data
    directions around it (on the circle) must be at most ``max_gap`` apart.

    Raises
    ------
    HydroDataError
        A direction in a gap of the data wider than ``max_gap`` (one data direction: any
        other direction).
    """
    a, b, t, outside = direction_stencil(directions, beta, max_gap=max_gap)
    if outside.any():
        k = int(np.argmax(outside.reshape(-1)))
        angle = float(np.degrees(np.mod(np.asarray(beta, dtype=float).reshape(-1)[k], _TWO_PI)))
        have = ", ".join(f"{x:.4g}" for x in np.degrees(directions))
        raise HydroDataError(
            f"the {what} has no wave direction near {angle:.4g} deg (it has {have} deg)",
            hint="waves from the directions the solver computed, or a run with more "
            "directions; for a symmetric hull the directions may be mirrored first",
        )
    return a, b, t


def direction_stencil(
    directions: NDArray[np.float64], beta: ArrayLike, *, max_gap: float = np.pi / 2
) -> tuple[NDArray[np.intp], NDArray[np.intp], NDArray[np.float64], NDArray[np.bool_]]:
    """:func:`direction_weights` without the refusal: a direction in a gap of the data
    wider than ``max_gap`` (or any other direction than the only one) takes the value of
    the nearest data direction, and ``outside`` marks it. Returns (a, b, t, outside)."""
    return DirectionStencil(directions, max_gap)(beta)


class DirectionStencil:
    """:func:`direction_stencil` on fixed data directions, prepared once (for a load
    that looks directions up at every time step)."""

    def __init__(self, directions: ArrayLike, max_gap: float = np.pi / 2) -> None:
        d = np.mod(np.asarray(directions, dtype=float).reshape(-1), _TWO_PI)
        self.order = np.argsort(d)
        self.sorted = d[self.order]
        m = self.sorted.size
        self.m = m
        right = np.roll(self.sorted, -1)
        span = np.mod(right - self.sorted, _TWO_PI)
        self.span = np.where((span == 0) & (m > 1), _TWO_PI, span)  # from node k to k + 1
        self.wide = (self.span > max_gap) | (m == 1)

    def __call__(
        self, beta: ArrayLike
    ) -> tuple[NDArray[np.intp], NDArray[np.intp], NDArray[np.float64], NDArray[np.bool_]]:
        beta = np.mod(np.asarray(beta, dtype=float), _TWO_PI)
        m = self.m
        lo = (np.searchsorted(self.sorted, beta, side="right") - 1) % m
        hi = (lo + 1) % m
        span = self.span[lo]
        off = np.mod(beta - self.sorted[lo], _TWO_PI)
        off_lo = np.minimum(off, _TWO_PI - off)  # distances on the circle
        exact_lo = off_lo <= 1e-6
        off_hi = np.mod(self.sorted[hi] - beta, _TWO_PI)
        off_hi = np.minimum(off_hi, _TWO_PI - off_hi)
        exact_hi = off_hi <= 1e-6
        t = off / np.where(span > 0, span, 1.0)
        outside = ~(exact_lo | exact_hi) & self.wide[lo]
        near_lo = exact_lo | (outside & (off_lo <= off_hi))
        t = np.where(near_lo, 0.0, np.where(exact_hi | outside, 1.0, t))
        return self.order[lo], self.order[hi], t, outside


def _unique_direction_weights(directions, beta, max_gap):
    """:func:`direction_weights` computed once per distinct direction."""
    unique, inverse = np.unique(beta, return_inverse=True)
    a, b, t = direction_weights(directions, unique, max_gap=max_gap)
    inverse = inverse.reshape(-1)
    return a[inverse], b[inverse], t[inverse]


def mean_direction(b1: NDArray, b2: NDArray) -> NDArray:
    """The circular mean of two directions (rad), ambiguity of opposite ones resolved
    towards b1."""
    delta = np.mod(b2 - b1 + np.pi, _TWO_PI) - np.pi
    return b1 + 0.5 * delta


def interpolate(
    table: QTFTable,
    omega1: ArrayLike,
    omega2: ArrayLike,
    beta1: ArrayLike = 0.0,
    beta2: ArrayLike | None = None,
    *,
    max_gap: float = np.pi / 2,
) -> NDArray[np.complex128]:
    """Q(ω₁, ω₂, β₁, β₂) of every DOF at arbitrary points (arrays broadcast together).

    Parameters
    ----------
    table
        The QTF.
    omega1, omega2
        Frequencies, rad/s.
    beta1, beta2
        Directions of travel, rad (``beta2`` None: the same as ``beta1``).
    max_gap
        Widest gap between data directions to interpolate across, rad.

    Returns
    -------
    numpy.ndarray
        Complex, shape (*broadcast shape, n_dofs); zero where a frequency is outside the
        grid.
    """
    beta2 = beta1 if beta2 is None else beta2
    w1, w2, b1, b2 = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (omega1, omega2, beta1, beta2))
    )
    shape = w1.shape
    w1, w2, b1, b2 = (v.reshape(-1) for v in (w1, w2, b1, b2))
    i, ti, in1 = frequency_weights(table.omega, w1)
    j, tj, in2 = frequency_weights(table.omega, w2)
    n1 = np.minimum(i + 1, table.omega.size - 1)
    n2 = np.minimum(j + 1, table.omega.size - 1)
    corners = ((i, j, (1 - ti) * (1 - tj)), (n1, j, ti * (1 - tj)), (i, n2, (1 - ti) * tj))
    corners += ((n1, n2, ti * tj),)
    d = len(table.dofs)
    n, m = table.omega.size, table.directions.size
    flat = table.values.reshape(-1, d)  # rows (i, j, a[, b]) in C order: one gather per corner
    out = np.zeros((w1.size, d), dtype=complex)
    if table.bidirectional:
        a0, a1, ta = _unique_direction_weights(table.directions, b1, max_gap)
        c0, c1, tc = _unique_direction_weights(table.directions, b2, max_gap)
        heads = (
            (a0 * m + c0, (1 - ta) * (1 - tc)),
            (a1 * m + c0, ta * (1 - tc)),
            (a0 * m + c1, (1 - ta) * tc),
            (a1 * m + c1, ta * tc),
        )
        per_pair = m * m
    else:
        a0, a1, ta = _unique_direction_weights(table.directions, mean_direction(b1, b2), max_gap)
        heads = ((a0, 1 - ta), (a1, ta))
        per_pair = m
    heads = tuple((h, wh) for h, wh in heads if np.any(wh))  # one direction: one corner
    for ri, ci, wf in corners:
        if not np.any(wf):
            continue
        base = (ri * n + ci) * per_pair
        for h, wh in heads:
            out += (wf * wh)[:, None] * np.take(flat, base + h, axis=0)
    out[~(in1 & in2)] = 0.0
    return out.reshape(*shape, len(table.dofs))


def pair_matrix(
    table: QTFTable,
    dof: int,
    omega: ArrayLike,
    directions: ArrayLike,
    *,
    max_gap: float = np.pi / 2,
) -> NDArray[np.complex128]:
    """M[i, j] = Q_dof(ω_i, ω_j, β_i, β_j) over every pair of N wave components (N × N).

    Built block by block over the components' distinct directions (one block per pair
    of directions: W_g Q(β_g, β_h) W_hᵀ, W the frequency weights), so a sea of a few
    thousand components costs a few matrix products, not N² gathers. Components outside
    the frequency grid give zero rows and columns. Hermitian for a difference QTF,
    symmetric for a sum QTF (module docstring).
    """
    omega = np.asarray(omega, dtype=float).reshape(-1)
    beta = np.asarray(directions, dtype=float).reshape(-1)
    if beta.size != omega.size:
        raise HydroDataError(f"{beta.size} directions for {omega.size} wave components")
    unique, group = np.unique(np.round(np.mod(beta, _TWO_PI), 12), return_inverse=True)
    if unique.size > 64:  # no block structure to use: pointwise
        w1, w2 = np.meshgrid(omega, omega, indexing="ij")
        b1, b2 = np.meshgrid(beta, beta, indexing="ij")
        return interpolate(table, w1, w2, b1, b2, max_gap=max_gap)[..., dof]
    weights = weight_matrix(table.omega, omega)
    first = np.array([beta[group == g][0] for g in range(unique.size)])
    out = np.zeros((omega.size, omega.size), dtype=complex)
    members = [np.flatnonzero(group == g) for g in range(unique.size)]
    for g in range(unique.size):
        for h in range(unique.size):
            q = at_directions(table, dof, first[g], first[h], max_gap)
            rows, cols = members[g], members[h]
            out[np.ix_(rows, cols)] = weights[rows] @ q @ weights[cols].T
    return out


def at_directions(
    table: QTFTable, dof: int, beta1: float, beta2: float, max_gap: float = np.pi / 2
) -> NDArray[np.complex128]:
    """Q_dof(ω_a, ω_b, β₁, β₂) on the frequency grid (n × n), linear in direction (a
    unidirectional QTF at the mean direction of β₁ and β₂)."""
    if table.bidirectional:
        a0, a1, ta = direction_weights(table.directions, np.array([beta1]), max_gap=max_gap)
        c0, c1, tc = direction_weights(table.directions, np.array([beta2]), max_gap=max_gap)
        v = table.values[..., dof]
        return (
            (1 - ta[0]) * (1 - tc[0]) * v[:, :, a0[0], c0[0]]
            + ta[0] * (1 - tc[0]) * v[:, :, a1[0], c0[0]]
            + (1 - ta[0]) * tc[0] * v[:, :, a0[0], c1[0]]
            + ta[0] * tc[0] * v[:, :, a1[0], c1[0]]
        )
    mean = mean_direction(np.array([beta1]), np.array([beta2]))
    a0, a1, ta = direction_weights(table.directions, mean, max_gap=max_gap)
    v = table.values[..., dof]
    return (1 - ta[0]) * v[:, :, a0[0]] + ta[0] * v[:, :, a1[0]]
