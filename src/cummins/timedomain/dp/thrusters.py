"""Thrusters and thrust allocation of the DP controller.

A thruster layout (:class:`Thrusters`: tunnel, main and azimuth thrusters) and its
allocation (:class:`Allocation`): the weighted pseudo-inverse f = W⁻¹Bᵀ(BW⁻¹Bᵀ)⁻¹τ of the
extended thrust formulation (Fossen (2021), control allocation), saturation of each
thruster, and the generalized force the saturated thrusters deliver (Smogeli et al. (2004)
eq. 45 for the force of each thruster at its position).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.kinematics import point_load
from cummins.timedomain.dp.base import _DOF3_NAMES, DOF3, DPConfigError

ThrusterKind = Literal["tunnel", "main", "azimuth"]
_KINDS = ("tunnel", "main", "azimuth")


@dataclass(frozen=True, eq=False)
class Allocation:
    """The result of :meth:`Thrusters.allocate`.

    Attributes
    ----------
    demanded
        The generalized force asked for, (surge N, sway N, yaw N·m).
    forces
        Thruster forces after saturation, shape (n, 2): (fx, fy) of each thruster in the
        b-frame, N (fy = 0 for a main propeller, fx = 0 for a tunnel thruster).
    unsaturated
        The same before saturation (the weighted pseudo-inverse solution).
    delivered
        The generalized force of the saturated thrusters, 6-vector in the b-frame about O
        (N, N·m), including roll and pitch moments of thrusters not at the level of O.
    saturated
        Per thruster: was it scaled down to its maximum thrust?
    """

    demanded: NDArray[np.float64]
    forces: NDArray[np.float64]
    unsaturated: NDArray[np.float64]
    delivered: NDArray[np.float64]
    saturated: NDArray[np.bool_]

    @property
    def thrust(self) -> NDArray[np.float64]:
        """Thrust magnitude of each thruster, N."""
        return np.hypot(self.forces[:, 0], self.forces[:, 1])

    @property
    def azimuth_angle(self) -> NDArray[np.float64]:
        """Direction of each thrust in the b-frame, rad from x towards y (atan2(fy, fx))."""
        return np.arctan2(self.forces[:, 1], self.forces[:, 0])


@dataclass(frozen=True, eq=False)
class Thrusters:
    """A thruster layout and its generalized-force allocation (Fossen 2021, control allocation).

    Parameters
    ----------
    positions
        Shape (n, 2) or (n, 3): (x, y[, z]) of each thruster in the b-frame, m from O
        (z down; thrusters below O give roll and pitch moments; z = 0 if not given).
    kinds
        Per thruster: ``"tunnel"`` (fixed, transverse force fy), ``"main"`` (fixed,
        longitudinal fx, either sign) or ``"azimuth"`` (rotatable: fx and fy).
    max_thrust
        Per thruster (or one for all), N > 0; an azimuth's limit is on √(fx² + fy²).
    weights
        Per thruster (or one for all), > 0: the cost weights W of the allocation (a
        larger weight uses that thruster less). Default 1.
    names
        Optional labels.

    Raises
    ------
    DPConfigError
        For wrong shapes or kinds, non-positive limits or weights, or a layout that cannot
        produce a surge force, a sway force or a yaw moment (e.g. all tunnel thrusters at
        the same x and no azimuth).

    Examples
    --------
    >>> t = Thrusters.typical(100.0, 1e5)
    >>> a = t.allocate([0.0, 5e4, 1e6])
    >>> np.allclose(a.delivered[[0, 1, 5]], [0.0, 5e4, 1e6])
    True
    """

    positions: NDArray[np.float64]
    kinds: tuple[ThrusterKind, ...]
    max_thrust: NDArray[np.float64]
    weights: NDArray[np.float64] | None = None
    names: tuple[str, ...] | None = None
    _b3: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _b6: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _pinv: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _columns: tuple[tuple[int, int], ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        pos = np.asarray(self.positions, dtype=float)
        if pos.ndim != 2 or pos.shape[1] not in (2, 3) or pos.shape[0] == 0:
            raise DPConfigError(
                f"thruster positions must have shape (n, 2) or (n, 3), got {pos.shape}"
            )
        n = pos.shape[0]
        if pos.shape[1] == 2:
            pos = np.column_stack([pos, np.zeros(n)])
        if not np.all(np.isfinite(pos)):
            raise DPConfigError("thruster positions hold non-finite values")
        kinds = (self.kinds,) if isinstance(self.kinds, str) else tuple(self.kinds)
        if len(kinds) != n:
            raise DPConfigError(f"{len(kinds)} thruster kinds for {n} positions")
        for i, k in enumerate(kinds):
            if k not in _KINDS:
                raise DPConfigError(
                    f"thruster {i}: unknown kind {k!r}", hint=f"use one of {', '.join(_KINDS)}"
                )
        fmax = np.broadcast_to(np.asarray(self.max_thrust, dtype=float), (n,)).copy()
        if not np.all(np.isfinite(fmax) & (fmax > 0.0)):
            raise DPConfigError(f"max_thrust must be finite and > 0 N, got {fmax.tolist()}")
        w = np.ones(n) if self.weights is None else np.asarray(self.weights, dtype=float)
        w = np.broadcast_to(w, (n,)).copy()
        if not np.all(np.isfinite(w) & (w > 0.0)):
            raise DPConfigError(f"thruster weights must be finite and > 0, got {w.tolist()}")
        names = None if self.names is None else tuple(str(x) for x in self.names)
        if names is not None and len(names) != n:
            raise DPConfigError(f"{len(names)} thruster names for {n} thrusters")

        columns: list[tuple[int, int]] = []  # (thruster, component 0=fx / 1=fy)
        for i, k in enumerate(kinds):
            if k in ("main", "azimuth"):
                columns.append((i, 0))
            if k in ("tunnel", "azimuth"):
                columns.append((i, 1))
        b6 = np.zeros((6, len(columns)))
        for j, (i, c) in enumerate(columns):
            unit = np.zeros(3)
            unit[c] = 1.0
            b6[:, j] = point_load(unit, pos[i])
        b3 = b6[list(DOF3), :]
        missing = []  # which of surge, sway, yaw cannot be set on its own?
        for dof in range(3):
            target = np.eye(3)[dof]
            sol, *_ = np.linalg.lstsq(b3, target, rcond=None)
            if np.linalg.norm(b3 @ sol - target) > 1e-8:
                missing.append(_DOF3_NAMES[dof])
        if missing:
            raise DPConfigError(
                "the thrusters cannot produce every combination of surge, sway and yaw: "
                f"{' and '.join(missing)} cannot be set independently "
                f"(kinds {list(kinds)}, positions x, y = {pos[:, :2].tolist()} m)",
                hint="add a tunnel thruster or an azimuth away from the others "
                "(yaw needs transverse thrusters at different x), or a main propeller (surge)",
            )
        winv = np.array([1.0 / w[i] for i, _ in columns])
        bw = b3 * winv  # B W⁻¹
        pinv = bw.T @ np.linalg.inv(bw @ b3.T)  # W⁻¹Bᵀ(BW⁻¹Bᵀ)⁻¹
        pos.setflags(write=False)
        fmax.setflags(write=False)
        w.setflags(write=False)
        for name, value in (
            ("positions", pos),
            ("kinds", kinds),
            ("max_thrust", fmax),
            ("weights", w),
            ("names", names),
            ("_b3", b3),
            ("_b6", b6),
            ("_pinv", pinv),
            ("_columns", tuple(columns)),
        ):
            object.__setattr__(self, name, value)

    @classmethod
    def typical(
        cls, length: float, max_thrust: float, depth: float = 0.0, beam: float | None = None
    ) -> Thrusters:
        """A common DP layout for a ship of length ``length`` (m), origin amidships.

        Two tunnel thrusters in the bow (x = 0.42 L and 0.36 L) and two azimuth thrusters
        aft (x = −0.45 L, y = ±B/4 with B = ``beam``, default L/7), all with the same
        ``max_thrust`` (N) and at ``depth`` (m, z below O).

        Examples
        --------
        >>> Thrusters.typical(100.0, 1e5).kinds
        ('tunnel', 'tunnel', 'azimuth', 'azimuth')
        """
        if not (np.isfinite(length) and length > 0.0):
            raise DPConfigError(f"ship length must be > 0 m, got {length}")
        b = length / 7.0 if beam is None else float(beam)
        pos = [
            [0.42 * length, 0.0, depth],
            [0.36 * length, 0.0, depth],
            [-0.45 * length, -b / 4.0, depth],
            [-0.45 * length, b / 4.0, depth],
        ]
        return cls(
            positions=np.array(pos),
            kinds=("tunnel", "tunnel", "azimuth", "azimuth"),
            max_thrust=max_thrust,
            names=("bow tunnel 1", "bow tunnel 2", "azimuth port", "azimuth starboard"),
        )

    @property
    def count(self) -> int:
        """Number of thrusters."""
        return len(self.kinds)

    def configuration_matrix(self, full: bool = False) -> NDArray[np.float64]:
        """The extended thrust configuration matrix B: τ = B f.

        Shape (3, m) for (surge, sway, yaw), or (6, m) with ``full=True``; f holds one
        force for each tunnel or main thruster and two (fx, fy) for each azimuth, in the
        order of :meth:`forces_from_vector`.
        """
        return (self._b6 if full else self._b3).copy()

    def weight_matrix(self) -> NDArray[np.float64]:
        """The diagonal weight matrix W of the extended force vector."""
        return np.diag([self.weights[i] for i, _ in self._columns])

    def forces_from_vector(self, f: ArrayLike) -> NDArray[np.float64]:
        """Map an extended force vector f (m,) to (fx, fy) per thruster, shape (n, 2)."""
        f = np.asarray(f, dtype=float).reshape(-1)
        out = np.zeros((self.count, 2))
        for value, (i, c) in zip(f, self._columns, strict=True):
            out[i, c] = value
        return out

    def allocate(self, tau: ArrayLike) -> Allocation:
        """Distribute a generalized force on the thrusters and saturate them.

        f = W⁻¹Bᵀ(BW⁻¹Bᵀ)⁻¹ τ is the exact solution of B f = τ of least weighted norm
        fᵀ W f (Fossen 2021, unconstrained allocation by Lagrange multipliers). Each
        thruster is then scaled down to its maximum thrust (an azimuth's fx and fy
        together, so its direction is kept), and the delivered force is B₆ f_sat.

        Parameters
        ----------
        tau
            (surge N, sway N, yaw N·m), or a 6-vector (only indices 0, 1, 5 are used).
        """
        t = np.asarray(tau, dtype=float).reshape(-1)
        if t.size == 6:
            t = t[list(DOF3)]
        if t.size != 3:
            raise DPConfigError(f"tau must have 3 or 6 components, got {t.size}")
        f = self._pinv @ t
        unsat = self.forces_from_vector(f)
        mag = np.hypot(unsat[:, 0], unsat[:, 1])
        scale = np.minimum(1.0, self.max_thrust / np.maximum(mag, 1e-300))
        forces = unsat * scale[:, None]
        f_sat = np.array([forces[i, c] for i, c in self._columns])
        return Allocation(
            demanded=t,
            forces=forces,
            unsaturated=unsat,
            delivered=self._b6 @ f_sat,
            saturated=scale < 1.0,
        )
