"""The current: a uniform, steady surface current and the relative velocity ν_r.

Smogeli et al. (2004) §4.3: the current velocity in the b-frame (eq. 40) and the relative
velocity ν_r = ν − [v_c^b, 0, 0, 0] (eq. 49) that the viscous loads
(:mod:`cummins.timedomain.loads.viscous`) and the vessel model's damping (eq. 56) use.
:class:`Current` is not a load itself.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError
from cummins.timedomain.loads.base import _positive


@dataclass(frozen=True)
class Current:
    """A uniform, steady surface current (Smogeli et al. (2004) §4.3).

    Not a load itself: :class:`SurgeResistance` and :class:`CrossFlowDrag` use it for the
    relative velocity ν_r (eq. 49), and the vessel model replaces ν by ν_r in its
    damping terms (eq. 56).

    Parameters
    ----------
    speed
        U_c, m/s, ≥ 0.
    direction
        β_c, rad: the direction the current flows **to**, clockwise from North (π/2: a
        current setting East).

    Examples
    --------
    >>> import numpy as np
    >>> c = Current(1.0, np.pi / 2)            # setting East
    >>> np.round(c.velocity_body(0.0), 12)     # ship heading North: from port to starboard
    array([0., 1., 0.])
    """

    speed: float
    direction: float = 0.0

    def __post_init__(self) -> None:
        _positive(self.speed, "current speed (m/s)", allow_zero=True)
        if not np.isfinite(self.direction):
            raise CumminsError(f"current direction must be finite, got {self.direction!r} rad")

    def velocity_ned(self) -> NDArray[np.float64]:
        """The current velocity in the n-frame (north, east, down), m/s, shape (3,)."""
        return self.speed * np.array([np.cos(self.direction), np.sin(self.direction), 0.0])

    def velocity_body(self, psi: float) -> NDArray[np.float64]:
        """v_c^b = U_c [cos(β_c − ψ), sin(β_c − ψ), 0], m/s (Smogeli et al. (2004) eq. 40).

        ``psi`` is the heading ψ, rad. Only the heading rotates the current (roll and
        pitch are neglected, as in the paper).
        """
        a = self.direction - float(psi)
        return self.speed * np.array([np.cos(a), np.sin(a), 0.0])

    def relative_velocity(self, eta: ArrayLike, nu: ArrayLike) -> NDArray[np.float64]:
        """ν_r = ν − [v_c^b, 0, 0, 0], shape (6,), m/s and rad/s (Smogeli et al. (2004) eq. 49)."""
        nu_r = np.array(nu, dtype=float).reshape(6)
        nu_r[:3] -= self.velocity_body(np.asarray(eta, dtype=float).reshape(6)[5])
        return nu_r


def _relative_velocity(current: Current | None, eta: ArrayLike, nu: ArrayLike) -> NDArray:
    if current is None:
        return np.asarray(nu, dtype=float).reshape(6)
    return current.relative_velocity(eta, nu)
