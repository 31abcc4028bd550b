"""External and user loads, and the sums of loads.

* :class:`PointLoad`: a force and moment at a point of the vessel, in the b- or n-frame,
  switched on and off in time (a crane load; Smogeli et al. (2004) eq. 45);
* :class:`ConstantLoad`: a constant generalized force;
* :class:`FunctionLoad`: any user function f(t, η, ν) (moorings, risers, a thruster model);
* :func:`load_forces` and :func:`total_force`: the forces of a set of :class:`Load`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError
from cummins.kinematics import point_load, rotation_matrix
from cummins.timedomain.loads.base import Load, _positive, _vector


@dataclass(frozen=True)
class PointLoad:
    """A force (and moment) acting at a point of the vessel (Smogeli et al. (2004) eq. 45).

    τ = Hᵀ(r) [F^b, M^b] · s(t): F (N) and M (N·m) are given in the b-frame
    (``frame="body"``, they turn with the vessel: a thrust, a towline fixed on deck) or
    in the n-frame (``frame="ned"``: a suspended crane load whose weight acts along
    NED down, rotated into the b-frame by R_b^n(Θ)ᵀ before the transform). The time
    factor s(t) is 0 before ``start``, rises linearly to 1 over ``ramp`` seconds, and
    is 0 again from ``stop`` on.

    Parameters
    ----------
    force
        F, N, shape (3,).
    point
        r, m, b-frame, from O.
    moment
        M, N·m, shape (3,), same frame as the force (None: no moment).
    frame
        ``"body"`` or ``"ned"``.
    start, ramp, stop
        s; ``stop`` None: never stops.
    name
        Name of the load.

    Examples
    --------
    1000 kN hanging 15 m to starboard heels the vessel to starboard (positive roll):

    >>> import numpy as np
    >>> crane = PointLoad([0.0, 0.0, 1e6], [0.0, 15.0, 0.0], frame="ned")
    >>> crane.force(0.0, np.zeros(6), np.zeros(6))[[2, 3]]
    array([ 1000000., 15000000.])
    """

    force_vector: NDArray[np.float64]
    point: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    moment: NDArray[np.float64] | None = None
    frame: str = "body"
    start: float = 0.0
    ramp: float = 0.0
    stop: float | None = None
    name: str = "point load"

    def __post_init__(self) -> None:
        object.__setattr__(self, "force_vector", _vector(self.force_vector, 3, "force (N)"))
        object.__setattr__(self, "point", _vector(self.point, 3, "point of attack (m)"))
        if self.moment is not None:
            object.__setattr__(self, "moment", _vector(self.moment, 3, "moment (N·m)"))
        if self.frame not in ("body", "ned"):
            raise CumminsError(f"frame must be 'body' or 'ned', got {self.frame!r}")
        if not np.isfinite(self.start):
            raise CumminsError(f"start must be finite, got {self.start!r} s")
        _positive(self.ramp, "ramp (s)", allow_zero=True)
        if self.stop is not None and not self.stop > self.start:
            raise CumminsError(f"stop ({self.stop} s) must come after start ({self.start} s)")

    def factor(self, t: float) -> float:
        """s(t): 0 before start, linear ramp to 1, 0 from stop on."""
        t = float(t)
        if t < self.start or (self.stop is not None and t >= self.stop):
            return 0.0
        if self.ramp > 0.0 and t < self.start + self.ramp:
            return (t - self.start) / self.ramp
        return 1.0

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ, shape (6,), N and N·m, b-frame about O (eq. 45)."""
        s = self.factor(t)
        if s == 0.0:
            return np.zeros(6)
        f, m = self.force_vector, self.moment
        if self.frame == "ned":
            r_t = rotation_matrix(np.asarray(eta, dtype=float)[3:6]).T
            f = r_t @ f
            m = None if m is None else r_t @ m
        return s * point_load(f, self.point, m)


@dataclass(frozen=True)
class ConstantLoad:
    """A constant generalized force (6,), N and N·m, b-frame about O.

    Examples
    --------
    >>> float(ConstantLoad("bollard", [1e5, 0, 0, 0, 0, 0]).force(0.0, None, None)[0])
    100000.0
    """

    name: str
    value: NDArray[np.float64]

    def __post_init__(self) -> None:
        object.__setattr__(self, "value", _vector(self.value, 6, f"load {self.name!r}"))

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """The constant value (a copy)."""
        return np.array(self.value)


@dataclass(frozen=True)
class FunctionLoad:
    """Any function f(t, η, ν) → (6,) as a load (moorings, risers, a thruster model).

    Examples
    --------
    A linear spring of 1e5 N/m holding the vessel at the origin in surge:

    >>> import numpy as np
    >>> spring = FunctionLoad("mooring", lambda t, eta, nu: np.r_[-1e5 * eta[0], np.zeros(5)])
    >>> float(spring.force(0.0, np.r_[2.0, np.zeros(5)], np.zeros(6))[0])
    -200000.0
    """

    name: str
    function: Callable[[float, NDArray[np.float64], NDArray[np.float64]], ArrayLike]

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise CumminsError(f"load {self.name!r}: function must be callable")

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """f(t, η, ν) as a float array (6,)."""
        out = np.asarray(self.function(t, eta, nu), dtype=float).reshape(-1)
        if out.size != 6:
            raise CumminsError(
                f"load {self.name!r} returned {out.size} components; a generalized force has 6"
            )
        return out


def load_forces(
    loads: Iterable[Load], t: float, eta: ArrayLike, nu: ArrayLike
) -> dict[str, NDArray[np.float64]]:
    """Each load's generalized force (6,), N and N·m, by name (names must be unique)."""
    eta = np.asarray(eta, dtype=float).reshape(6)
    nu = np.asarray(nu, dtype=float).reshape(6)
    out: dict[str, NDArray[np.float64]] = {}
    for load in loads:
        if load.name in out:
            raise CumminsError(
                f"two loads are named {load.name!r}", hint="give each load a distinct name"
            )
        out[load.name] = np.asarray(load.force(t, eta, nu), dtype=float).reshape(6)
    return out


def total_force(
    loads: Iterable[Load] | Mapping[str, Load], t: float, eta: ArrayLike, nu: ArrayLike
) -> NDArray[np.float64]:
    """Σ of the loads' generalized forces, shape (6,), N and N·m, b-frame about O.

    Examples
    --------
    >>> import numpy as np
    >>> loads = [ConstantLoad("a", [1, 0, 0, 0, 0, 0]), ConstantLoad("b", [2, 0, 0, 0, 0, 1])]
    >>> total_force(loads, 0.0, np.zeros(6), np.zeros(6))
    array([3., 0., 0., 0., 0., 1.])
    """
    eta = np.asarray(eta, dtype=float).reshape(6)
    nu = np.asarray(nu, dtype=float).reshape(6)
    items = loads.values() if isinstance(loads, Mapping) else loads
    total = np.zeros(6)
    for load in items:
        total += np.asarray(load.force(t, eta, nu), dtype=float).reshape(6)
    return total
