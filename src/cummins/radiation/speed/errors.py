"""The error of the forward-speed computations (Hjulstad (2004)): :class:`SpeedError`."""

from __future__ import annotations

from cummins.errors import CumminsError


class SpeedError(CumminsError, ValueError):
    """A forward-speed computation cannot be done as asked (speed out of range, a
    singular encounter-frequency mapping, data without the DOFs the speed terms need)."""
