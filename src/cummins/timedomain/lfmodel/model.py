""":class:`LowFrequencyModel`: the constant-coefficient LF model (M_RB + M_A) ν̇ + D ν + G η = τ.

Ross, Perez & Fossen (2006) eq. 17; as a :class:`cummins.vessel.Vessel` with no fluid
memory (:meth:`LowFrequencyModel.to_vessel`) or an ``xarray.Dataset``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import HydroDataError
from cummins.radiation.model import RadiationModel
from cummins.vessel import Vessel


@dataclass(frozen=True, eq=False)
class LowFrequencyModel:
    """Constant-coefficient LF model (M_RB + M_A) ν̇ + D ν + G η = τ.

    Ross, Perez & Fossen (2006) eq. 17.

    Attributes
    ----------
    dofs
        DOF labels.
    rigid_body_mass
        M_RB (n, n), kg, kg·m, kg·m².
    added_mass
        M_A (n, n), same units; diagonal i at ``frequencies[i]`` (eqs. 22, 25, 29),
        couplings as ``attrs["couplings"]`` says.
    potential_damping
        B_p (n, n), kg/s … kg·m²/s: the potential part of D, likewise (eq. 23 with K
        only, eq. 30 without K_v).
    viscous_damping
        B_v (n, n): the database's constant additional damping (when taken) plus the
        requested viscous model evaluated at each DOF's frequency (eqs. 26, 30).
    stiffness
        G = C (n, n), N/m, N, N·m/rad: hydrostatic plus additional (mooring) stiffness.
    frequencies
        (n,) rad/s: 0 for the zero-frequency DOFs, ω₀ (eq. 24) for the others.
    provenance
        (n,) one sentence per DOF: frequency, route and equations used.
    zero_frequency_damping
        B(0) (n, n) as the route computed it (∫K dτ, eq. 23, or the extrapolated data):
        ≈ 0 at zero speed in deep water; kept as a diagnostic. Whether it enters
        :attr:`potential_damping` is set by ``potential_b0`` of the builders.
    attrs
        Route, options, source file; ``eq24_residual`` per DOF.
    speed_terms
        N(U) (n, n), kg/s …: the linearised Coriolis and centripetal forces of a ship
        moving ahead at ``attrs["forward_speed"]``
        (:func:`~cummins.timedomain.lfmodel.speed.at_forward_speed`), zero at zero speed;
        not symmetric (the Munk moments). It acts like a damping:
        (M_RB + M_A) ν̇ + (D + N(U)) ν + G η = τ.
    """

    dofs: tuple[str, ...]
    rigid_body_mass: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    potential_damping: NDArray[np.float64]
    viscous_damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    frequencies: NDArray[np.float64]
    provenance: tuple[str, ...]
    zero_frequency_damping: NDArray[np.float64]
    attrs: Mapping[str, Any] = field(default_factory=dict)
    speed_terms: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        if self.speed_terms is None:
            object.__setattr__(self, "speed_terms", np.zeros_like(self.added_mass))

    @property
    def damping(self) -> NDArray[np.float64]:
        """D = B_p + B_v (n, n), kg/s … kg·m²/s."""
        return self.potential_damping + self.viscous_damping

    @property
    def mass(self) -> NDArray[np.float64]:
        """M_RB + M_A (n, n)."""
        return self.rigid_body_mass + self.added_mass

    def index(self, dof: str) -> int:
        """Position of ``dof`` in :attr:`dofs` (HydroDataError naming the DOFs if absent)."""
        if dof not in self.dofs:
            raise HydroDataError(
                f"DOF {dof!r} is not in the model", hint=f"DOFs: {', '.join(self.dofs)}"
            )
        return self.dofs.index(dof)

    def eq24_residual(self, dof: str) -> float:
        """ω₀² (M_RB,ii + M_A,ii) − C_ii for ``dof``, N/m or N·m/rad.

        The residual of Ross, Perez & Fossen (2006) eq. 24."""
        i = self.index(dof)
        w = float(self.frequencies[i])
        return float(
            w**2 * (self.rigid_body_mass[i, i] + self.added_mass[i, i]) - self.stiffness[i, i]
        )

    def to_vessel(self) -> Vessel:
        """The model as a :class:`cummins.vessel.Vessel` with no fluid memory.

        Its inertia is M_RB + M_A (the radiation model has no couplings and M_A in place
        of A∞), its damping D + N(U) and its stiffness G, so
        :func:`cummins.timedomain.simulate.simulate` runs it (state (ξ, ξ̇), 2n states).
        """
        radiation = RadiationModel(
            self.dofs, (), np.array(self.added_mass), {"kind": "low-frequency model"}
        )
        attrs = {**dict(self.attrs), "model": "low-frequency (constant coefficients)"}
        return Vessel(
            self.dofs,
            np.array(self.rigid_body_mass),
            np.array(self.stiffness),
            np.array(self.damping + self.speed_terms),
            radiation,
            attrs,
        )

    def to_dataset(self) -> xr.Dataset:
        """The coefficients as an ``xarray.Dataset`` (dims influenced_dof, radiating_dof)."""
        dims = ("influenced_dof", "radiating_dof")
        labels = list(self.dofs)
        out = xr.Dataset(
            {
                "inertia_matrix": (dims, self.rigid_body_mass),
                "added_mass": (dims, self.added_mass),
                "potential_damping": (dims, self.potential_damping),
                "viscous_damping": (dims, self.viscous_damping),
                "damping": (dims, self.damping),
                "stiffness": (dims, self.stiffness),
                "speed_terms": (dims, self.speed_terms),
                "zero_frequency_damping": (dims, self.zero_frequency_damping),
                "frequency": ("dof", self.frequencies, {"units": "rad/s"}),
                "provenance": ("dof", np.array(self.provenance, dtype=str)),
            },
            coords={"influenced_dof": labels, "radiating_dof": labels, "dof": labels},
            attrs={
                k: (v if isinstance(v, str | int | float | np.ndarray) else str(v))
                for k, v in self.attrs.items()
            },
        )
        out.attrs["title"] = "low-frequency manoeuvring model (Ross, Perez & Fossen 2006)"
        return out
