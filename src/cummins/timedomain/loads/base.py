"""What every load shares: the :class:`Load` protocol and the helpers of the load modules.

A load of the nonlinear 6-DOF model of Smogeli et al. (2004) §4–5 is anything with a
``name`` and ``force(t, eta, nu) -> ndarray (6,)`` (:class:`Load`). Besides the protocol
this module holds the input checks the load classes use and the periodic interpolation
in angle of the wave-drift and wind tables (:class:`_PeriodicTable`).
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError

_TWO_PI = 2.0 * np.pi


@runtime_checkable
class Load(Protocol):
    """A generalized force on the vessel: anything with a ``name`` and this ``force``.

    ``force(t, eta, nu)`` returns the 6-vector (X, Y, Z, K, M, N) in the b-frame about
    O, N and N·m, at time ``t`` (s), pose ``eta`` (N, E, D in m; φ, θ, ψ in rad) and
    body velocity ``nu`` (u, v, w in m/s; p, q, r in rad/s). It must be a deterministic
    function of its arguments (the simulator evaluates it at Runge–Kutta stages, and
    again when a step is repeated).
    """

    name: str

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """Generalized force (6,), N and N·m, b-frame, about O."""
        ...


def _vector(value: ArrayLike, size: int, what: str) -> NDArray[np.float64]:
    arr = np.array(value, dtype=float).reshape(-1)
    if arr.size != size:
        raise CumminsError(f"{what} must have {size} components, got {arr.size}")
    if not np.all(np.isfinite(arr)):
        raise CumminsError(f"{what} has non-finite components: {arr.tolist()}")
    arr.setflags(write=False)
    return arr


def _positive(value: float, what: str, *, allow_zero: bool = False) -> float:
    value = float(value)
    ok = value >= 0 if allow_zero else value > 0
    if not (np.isfinite(value) and ok):
        bound = ">= 0" if allow_zero else "> 0"
        raise CumminsError(f"{what} must be finite and {bound}, got {value!r}")
    return value


def _frozen_array(value: ArrayLike, dtype: Any = float) -> NDArray:
    arr = np.array(value, dtype=dtype)
    arr.setflags(write=False)
    return arr


def _wrap_2pi(angle: ArrayLike) -> NDArray[np.float64]:
    out = np.mod(np.asarray(angle, dtype=float), _TWO_PI)
    return np.where(out >= _TWO_PI, 0.0, out)


class _PeriodicTable:
    """Periodic linear interpolation in angle, one column per wave component.

    ``values`` has shape (m, n, d): m angles (any order, in rad), n components, d DOFs.
    ``__call__(gamma)`` with gamma of shape (n,) (component j at angle gamma[j]) returns
    shape (n, d). The table is extended by one angle on each side (the neighbours across
    0/2π), so one ``searchsorted`` and two gathers do the work.
    """

    def __init__(self, angles: ArrayLike, values: ArrayLike) -> None:
        a = _wrap_2pi(angles)
        v = np.asarray(values)
        order = np.argsort(a, kind="stable")
        a, v = a[order], v[order]
        if a.size == 0:
            raise CumminsError("an interpolation table needs at least one angle")
        if a.size > 1 and np.min(np.diff(a)) <= 0:
            raise CumminsError("the angles of an interpolation table must be distinct")
        self.angles = np.concatenate([[a[-1] - _TWO_PI], a, [a[0] + _TWO_PI]])
        self.inverse_width = 1.0 / np.diff(self.angles)
        self.last = self.angles.size - 2
        self.n_columns = v.shape[1]
        self.columns = np.arange(v.shape[1])
        extended = np.concatenate([v[-1:], v, v[:1]], axis=0)
        self.flat = np.ascontiguousarray(extended.reshape(-1, *v.shape[2:]))

    def __call__(self, gamma: NDArray[np.float64]) -> NDArray:
        g = np.mod(gamma, _TWO_PI)
        i = np.searchsorted(self.angles, g, side="right") - 1
        np.minimum(i, self.last, out=i)
        w = (g - self.angles[i]) * self.inverse_width[i]
        rows = i * self.n_columns + self.columns
        v0 = self.flat.take(rows, axis=0)
        v1 = self.flat.take(rows + self.n_columns, axis=0)
        return v0 + w[:, None] * (v1 - v0)
