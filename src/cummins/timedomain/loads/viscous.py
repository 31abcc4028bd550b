"""Viscous loads: surge resistance and cross-flow drag, in the current's relative velocity.

* :class:`SurgeResistance`: quadratic surge resistance from the ITTC 1957 friction line
  (Smogeli et al. (2004) eqs. 50–51, 54), with :func:`ittc_friction` and the wetted surface
  estimate :func:`denny_mumford_wetted_surface`;
* :class:`CrossFlowDrag`: cross-flow drag in sway and yaw by strip theory (Smogeli et al.
  (2004) eqs. 52–54), with Hoerner's section drag coefficient
  (:func:`hoerner_drag_coefficient`, :data:`HOERNER_DRAG`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError
from cummins.kinematics import point_load
from cummins.timedomain.loads.base import _frozen_array, _positive, _vector
from cummins.timedomain.loads.current import Current, _relative_velocity

#: Density of sea water, kg/m³ (default of the hydrodynamic loads).
RHO_WATER = 1025.0
#: Kinematic viscosity of sea water at 15 °C, m²/s (ITTC 2011, fresh water 1.14e-6).
NU_WATER = 1.19e-6


def ittc_friction(reynolds: ArrayLike) -> NDArray[np.float64]:
    """ITTC 1957 model–ship correlation line C_f = 0.075 / (log₁₀ Rn − 2)² (Smogeli et al. (2004)
    eq. 51).

    Parameters
    ----------
    reynolds
        Reynolds number Rn = U L / ν (> 100; the line is meant for Rn ≳ 1e5).

    Examples
    --------
    >>> round(float(ittc_friction(1e9)), 7)   # 0.075 / 7²
    0.0015306
    """
    rn = np.asarray(reynolds, dtype=float)
    if np.any(~(rn > 100.0)):
        raise CumminsError("the ITTC 1957 line needs Reynolds numbers above 100")
    return 0.075 / (np.log10(rn) - 2.0) ** 2


def denny_mumford_wetted_surface(
    length: float, breadth: float, draught: float, block_coefficient: float
) -> float:
    """Wetted surface estimate S = 1.7 L T + ∇/T = L (1.7 T + C_B B), m².

    Denny–Mumford formula (Mumford's approximation, as given e.g. by Molland, Turnock &
    Hudson, *Ship Resistance and Propulsion*, 2011, §10.1), with ∇ = C_B L B T. For
    conventional displacement hulls it is within a few per cent.

    Examples
    --------
    >>> round(denny_mumford_wetted_surface(175.0, 25.4, 9.5, 0.57))  # S-175
    5360
    """
    length = _positive(length, "length (m)")
    breadth = _positive(breadth, "breadth (m)")
    draught = _positive(draught, "draught (m)")
    cb = _positive(block_coefficient, "block coefficient")
    return float(length * (1.7 * draught + cb * breadth))


@dataclass(frozen=True)
class SurgeResistance:
    """Quadratic surge resistance from the ITTC 1957 friction line (Smogeli et al. (2004) eqs.
    50–51).

    f_1 = −(ρ/2) S (1 + k) (C_f(Rn) + ΔC_f) |u_r| u_r,  Rn = |u_r| L / ν_w,

    opposing the relative surge velocity u_r = u − U_c cos(β_c − ψ) (eq. 49), applied at
    ``point``: τ = Hᵀ(r_c) [f_1, 0, 0, 0, 0, 0] (eq. 54; the paper suggests r_c =
    [0, 0, T/2] when O is in the waterline). Below ``min_reynolds`` (default 1e5, where
    the line stops being meaningful and diverges towards Rn = 100) C_f is held at its
    value at ``min_reynolds``: the force still goes to 0 as u_r² when u_r → 0.

    Parameters
    ----------
    wetted_surface
        S, m² (:func:`denny_mumford_wetted_surface` estimates it).
    length
        L, m: the length of the Reynolds number (waterline length).
    form_factor
        k, dimensionless viscous form factor (0.1 by default; 0.05–0.4, growing with
        fullness).
    roughness_allowance
        ΔC_f, dimensionless (0 by default; 0.0002–0.0004 for ship hulls).
    density
        ρ_w, kg/m³.
    viscosity
        ν_w, kinematic viscosity of water, m²/s (1.19e-6: sea water at 15 °C).
    current
        The current of the relative velocity (None: still water).
    point
        r_c, m, b-frame.
    min_reynolds
        Rn below which C_f is held constant.
    name
        Name of the load.

    Examples
    --------
    >>> import numpy as np
    >>> load = SurgeResistance(wetted_surface=5000.0, length=175.0)
    >>> float(load.force(0.0, np.zeros(6), [5.0, 0, 0, 0, 0, 0])[0]) < 0  # resists ahead
    True
    """

    wetted_surface: float
    length: float
    form_factor: float = 0.1
    roughness_allowance: float = 0.0
    density: float = RHO_WATER
    viscosity: float = NU_WATER
    current: Current | None = None
    point: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    min_reynolds: float = 1e5
    name: str = "surge resistance"

    def __post_init__(self) -> None:
        _positive(self.wetted_surface, "wetted surface (m²)")
        _positive(self.length, "length (m)")
        _positive(self.density, "water density (kg/m³)")
        _positive(self.viscosity, "kinematic viscosity (m²/s)")
        if not (np.isfinite(self.form_factor) and self.form_factor > -1):
            raise CumminsError(f"form factor must be > -1, got {self.form_factor!r}")
        if not np.isfinite(self.roughness_allowance):
            raise CumminsError("roughness allowance must be finite")
        if not (np.isfinite(self.min_reynolds) and self.min_reynolds > 100):
            raise CumminsError(f"min_reynolds must be > 100, got {self.min_reynolds!r}")
        object.__setattr__(self, "point", _vector(self.point, 3, "resistance point of attack (m)"))

    @classmethod
    def from_main_particulars(
        cls,
        length: float,
        breadth: float,
        draught: float,
        block_coefficient: float,
        **options: Any,
    ) -> SurgeResistance:
        """With S from :func:`denny_mumford_wetted_surface`; ``options`` as the class."""
        s = denny_mumford_wetted_surface(length, breadth, draught, block_coefficient)
        return cls(wetted_surface=s, length=length, **options)

    def friction_coefficient(self, speed: float) -> float:
        """C_f at the relative speed |u_r| (m/s), with the small-Rn guard."""
        rn = max(abs(float(speed)) * self.length / self.viscosity, self.min_reynolds)
        return float(ittc_friction(rn))

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ, shape (6,), N and N·m (eqs. 50, 54)."""
        u_r = float(_relative_velocity(self.current, eta, nu)[0])
        c = (1.0 + self.form_factor) * (self.friction_coefficient(u_r) + self.roughness_allowance)
        f1 = -0.5 * self.density * self.wetted_surface * c * abs(u_r) * u_r
        return point_load([f1, 0.0, 0.0], self.point)


#: Hoerner's 2-D cross-flow drag coefficient of a ship section against B/(2T): pairs
#: (B/(2T), C_D) digitised from Hoerner (1965), *Fluid-Dynamic Drag*, as tabulated in the
#: MSS function ``Hoerner.m`` (Fossen; data as in Leite et al. 1998, Appl. Ocean Res. 20).
HOERNER_DRAG = np.array(
    [
        [0.0108623, 1.96608],
        [0.176606, 1.96573],
        [0.353025, 1.89756],
        [0.451863, 1.78718],
        [0.472838, 1.58374],
        [0.492877, 1.27862],
        [0.493252, 1.21082],
        [0.558473, 1.08356],
        [0.646401, 0.998631],
        [0.833589, 0.87959],
        [0.988002, 0.828415],
        [1.30807, 0.759941],
        [1.63918, 0.691442],
        [1.85998, 0.657076],
        [2.31288, 0.630693],
        [2.59998, 0.596186],
        [3.00877, 0.586846],
        [3.45075, 0.585909],
        [3.7379, 0.559877],
        [4.00309, 0.559315],
    ]
)
HOERNER_DRAG.setflags(write=False)


def hoerner_drag_coefficient(breadth: ArrayLike, draught: ArrayLike) -> NDArray[np.float64]:
    """Hoerner's 2-D cross-flow drag coefficient C_D(B/(2T)) of a ship section.

    Linear interpolation in :data:`HOERNER_DRAG` (Hoerner 1965; the curve of MSS
    ``Hoerner.m``), held at the end values outside B/(2T) ∈ [0.011, 4.0] (deep, narrow
    sections: 1.97; flat, wide ones: 0.56).

    Parameters
    ----------
    breadth, draught
        Section breadth B and draught T, m (arrays broadcast).

    Examples
    --------
    >>> round(float(hoerner_drag_coefficient(25.4, 9.5)), 3)   # S-175: B/2T = 1.34
    0.754
    """
    b = np.asarray(breadth, dtype=float)
    t = np.asarray(draught, dtype=float)
    if np.any(~(b > 0)) or np.any(~(t > 0)):
        raise CumminsError("Hoerner's drag coefficient needs positive breadth and draught (m)")
    return np.interp(b / (2.0 * t), HOERNER_DRAG[:, 0], HOERNER_DRAG[:, 1])


@dataclass(frozen=True, eq=False)
class CrossFlowDrag:
    """Cross-flow drag in sway and yaw by strip theory (Smogeli et al. (2004) eqs. 52–54).

    f_2 = −(ρ/2) ∫ T(x) C_D(x) v_r^x |v_r^x| dx,  f_6 = −(ρ/2) ∫ x T(x) C_D(x) v_r^x |v_r^x| dx,

    v_r^x(x) = v_r + r x the relative cross-flow velocity of the strip at x (m from O,
    forward), v_r = v − U_c sin(β_c − ψ) (eq. 49). The integrals are sums over strips
    (midpoint rule). The signs make the loads oppose the motion (the paper's eqs. 52–54
    combine to a force along it; MSS ``crossFlowDrag.m`` has these signs): a sway to
    starboard gives a force to port, a yaw rate a moment against it. Applied at
    ``point``: τ = Hᵀ(r_c) [0, f_2, 0, 0, 0, f_6] (eq. 54). ``force`` returns this τ,
    which is −d(ν_r) of eq. 56: it is added to the right-hand side like every load.

    Attributes
    ----------
    x
        Strip centres, m, b-frame x from O, shape (n,).
    width
        Strip lengths dx, m, shape (n,) (or a scalar).
    draught
        T(x), m, shape (n,) (or a scalar).
    drag_coefficient
        C_D(x), 2-D drag coefficient, shape (n,) (or a scalar).
    density
        ρ_w, kg/m³.
    current
        Current of the relative velocity (None: still water).
    point
        r_c, m, b-frame (default O).
    name
        Name of the load.

    Examples
    --------
    >>> import numpy as np
    >>> drag = CrossFlowDrag.from_main_particulars(100.0, 20.0, 8.0, drag_coefficient=1.0)
    >>> tau = drag.force(0.0, np.zeros(6), [0, 1.0, 0, 0, 0, 0])    # 1 m/s to starboard
    >>> float(tau[1])                                               # −ρ/2 C_D T L v|v|
    -410000.0
    """

    x: NDArray[np.float64]
    width: NDArray[np.float64]
    draught: NDArray[np.float64]
    drag_coefficient: NDArray[np.float64]
    density: float = RHO_WATER
    current: Current | None = None
    point: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    name: str = "cross-flow drag"
    _weights: NDArray[np.float64] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        x = np.array(self.x, dtype=float).reshape(-1)
        if x.size == 0 or not np.all(np.isfinite(x)):
            raise CumminsError("cross-flow drag needs finite strip positions x (m)")
        arrays = {}
        for name, what in (
            ("width", "strip width (m)"),
            ("draught", "strip draught (m)"),
            ("drag_coefficient", "drag coefficient"),
        ):
            value = np.array(np.broadcast_to(np.asarray(getattr(self, name), float), x.shape))
            if np.any(~np.isfinite(value)) or np.any(value < 0):
                raise CumminsError(f"cross-flow {what} must be finite and >= 0")
            arrays[name] = value
        _positive(self.density, "water density (kg/m³)")
        for name, value in (("x", x), *arrays.items()):
            object.__setattr__(self, name, _frozen_array(value))
        object.__setattr__(self, "point", _vector(self.point, 3, "drag point of attack (m)"))
        weights = (
            0.5 * self.density * arrays["width"] * arrays["draught"] * arrays["drag_coefficient"]
        )
        object.__setattr__(self, "_weights", _frozen_array(weights))

    @classmethod
    def from_main_particulars(
        cls,
        length: float,
        breadth: float,
        draught: float,
        *,
        drag_coefficient: float | str = "hoerner",
        n_strips: int = 40,
        x_aft: float | None = None,
        density: float = RHO_WATER,
        current: Current | None = None,
        point: ArrayLike = (0.0, 0.0, 0.0),
        name: str = "cross-flow drag",
    ) -> CrossFlowDrag:
        """A box-like hull: constant draught and C_D over ``n_strips`` equal strips.

        Parameters
        ----------
        length, breadth, draught
            L_pp, B, T, m.
        drag_coefficient
            ``"hoerner"`` (default: :func:`hoerner_drag_coefficient` (B, T)) or a
            constant C_D.
        n_strips
            Number of strips (midpoint rule; exact for pure sway, error O(1/n²) with
            yaw).
        x_aft
            x of the aft end, m (default −L/2: the hull centred on O).
        density, current, point, name
            As the attributes.
        """
        length = _positive(length, "length (m)")
        draught = _positive(draught, "draught (m)")
        n = int(n_strips)
        if n < 1:
            raise CumminsError(f"n_strips must be at least 1, got {n_strips!r}")
        if isinstance(drag_coefficient, str):
            if drag_coefficient.lower() != "hoerner":
                raise CumminsError(
                    f"unknown drag coefficient {drag_coefficient!r}; use 'hoerner' or a number"
                )
            cd = float(hoerner_drag_coefficient(breadth, draught))
        else:
            cd = _positive(drag_coefficient, "drag coefficient", allow_zero=True)
        start = -0.5 * length if x_aft is None else float(x_aft)
        dx = length / n
        x = start + dx * (np.arange(n) + 0.5)
        return cls(x, dx, draught, cd, density, current, point, name)

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ, shape (6,), N and N·m (eqs. 52–54)."""
        nu_r = _relative_velocity(self.current, eta, nu)
        vx = nu_r[1] + nu_r[5] * self.x
        q = self._weights * vx * np.abs(vx)
        return point_load([0.0, -q.sum(), 0.0], self.point, [0.0, 0.0, -(q @ self.x)])
