"""Viscous damping B_v(ω) of the LF model (Ross, Perez & Fossen (2006) §3, the matrix after eq. 21).

:class:`ExponentialDamping` β e^{−αω} (Ross & Fossen (2005); intended for surge, sway and
yaw) and, for roll, where the paper uses Ikeda et al. (1976),
:class:`CriticalDampingFraction` — **a proxy, not Ikeda's method**: B_v = 2ζ ω₀ (M_RB,ii +
A_ii(ω₀)), a fraction ζ of critical damping at the natural frequency. Any callable B_v(ω)
or constant is accepted too (:data:`ViscousSpec`), and ``"data"`` takes the database's own
frequency-dependent ``additional_damping`` at the DOF's frequency.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError


@dataclass(frozen=True)
class ExponentialDamping:
    """Viscous damping B_v(ω) = β e^{−αω} (Ross, Perez & Fossen (2006) §3; Ross & Fossen (2005)).

    Attributes
    ----------
    beta
        β ≥ 0, the zero-frequency viscous damping, kg/s (translation) or kg·m²/s
        (rotation): the constant that enters D of a zero-frequency DOF
        (Ross, Perez & Fossen (2006) eq. 26).
    alpha
        α ≥ 0, the exponential rate, s.

    Examples
    --------
    >>> ExponentialDamping(beta=2.0e5, alpha=1.0)(0.0)
    200000.0
    """

    beta: float
    alpha: float = 0.0

    def __post_init__(self) -> None:
        if not (np.isfinite(self.beta) and self.beta >= 0):
            raise HydroDataError(f"viscous damping beta must be finite and ≥ 0, not {self.beta}")
        if not (np.isfinite(self.alpha) and self.alpha >= 0):
            raise HydroDataError(f"viscous damping alpha must be finite and ≥ 0, not {self.alpha}")

    def __call__(self, omega: float) -> float:
        """B_v at ``omega`` (rad/s)."""
        return float(self.beta * np.exp(-self.alpha * omega))


@dataclass(frozen=True)
class CriticalDampingFraction:
    """Linear viscous damping as a fraction ζ of critical, at the natural frequency.

    B_v = 2ζ ω₀ (M_RB,ii + A_ii(ω₀)), i.e. 2ζ √(C_ii (M_RB,ii + A_ii(ω₀))) when ω₀
    satisfies Ross, Perez & Fossen (2006) eq. 24. A documented **proxy** for the Ikeda roll
    damping B_IKEDA(ω₀) of their eq. 30 (typical ζ for a ship in roll: 0.02–0.10 in total,
    of which the potential part B_44(ω₀) is often the smaller share); it is not Ikeda's
    component method (friction, eddy, lift, bilge keel), which needs the hull form.
    Only for DOFs with restoring (heave, roll, pitch).

    Attributes
    ----------
    zeta
        ζ ≥ 0, dimensionless.
    """

    zeta: float

    def __post_init__(self) -> None:
        if not (np.isfinite(self.zeta) and self.zeta >= 0):
            raise HydroDataError(f"damping fraction zeta must be finite and ≥ 0, not {self.zeta}")


ViscousSpec = (
    ExponentialDamping
    | CriticalDampingFraction
    | Callable[[float], float]
    | float
    | Literal["data"]
)


def _viscous_value(
    spec: ViscousSpec, dof: str, omega: float, mass: float, added: float
) -> tuple[float, str]:
    if isinstance(spec, CriticalDampingFraction):
        if omega <= 0:
            raise HydroDataError(
                f"{dof}: a fraction of critical damping needs a natural frequency, and "
                f"{dof} is a zero-frequency DOF",
                quantity=f"viscous damping of {dof}",
                hint="use ExponentialDamping(beta, alpha) for surge, sway and yaw",
            )
        return 2 * spec.zeta * omega * (mass + added), f"B_v = 2ζω₀(M+A), ζ = {spec.zeta:g}"
    if isinstance(spec, ExponentialDamping):
        return spec(omega), f"B_v = β e^(−αω), β = {spec.beta:g}, α = {spec.alpha:g}"
    if callable(spec):
        return float(spec(omega)), "B_v(ω) given"
    return float(spec), "B_v constant"


def _database_damping(ds: xr.Dataset, spec: str, dof: str, i: int, omega: float):
    """The database's own ``additional_damping`` B_v,ii(ω) at ``omega`` (``"data"``)."""
    if spec != "data":
        raise HydroDataError(
            f"unknown viscous damping {spec!r} for {dof}",
            hint="give 'data', a number, a callable B_v(ω) or ExponentialDamping/"
            "CriticalDampingFraction",
        )
    if "additional_damping" not in ds:
        raise HydroDataError(
            f"{dof}: viscous='data' asks for the database's additional_damping, which "
            "these data do not hold",
            path=ds.attrs.get("source_file"),
            quantity=f"additional_damping[{dof}, {dof}]",
        )
    var = ds["additional_damping"].transpose(..., "influenced_dof", "radiating_dof")
    if "omega" not in var.dims:
        return float(var.values[i, i]), "B_v from the database (constant)"
    values = var.transpose("omega", ...).values[:, i, i].astype(float)
    value = float(np.interp(omega, ds.omega.values, values))
    return value, f"B_v from the database's additional_damping at ω = {omega:.4g} rad/s"
