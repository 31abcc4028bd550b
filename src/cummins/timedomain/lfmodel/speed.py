"""The low-frequency model of a ship moving ahead (:func:`at_forward_speed`).

A manoeuvring model is linearised about the steady motion ν₀ = (U, 0, 0, 0, 0, 0).
Rigid body and fluid each carry a Coriolis and centripetal force C(ν)ν of Kirchhoff's
form (Fossen (2011) Thm. 3.2 for the rigid body with M_RB, Thm. 6.2 for the added mass
with M_A): with p = M ν split into p₁ (force) and p₂ (moment) and ν into the linear
velocity v and the angular velocity ω,

    C(ν)ν = [ω × p₁ ;  v × p₁ + ω × p₂].

Its Jacobian at ν₀ **[derived, not in the seeds]**, with a₀ = M₁₁ v₀, b₀ = M₂₁ v₀ and
v₀ = U e₁, is the speed matrix

    N(U) = [[0, −S(a₀)], [−S(a₀) + S(v₀) M₁₁, S(v₀) M₁₂ − S(b₀)]],

added to the model's damping: (M_RB + M_A) ν̇ + (D + N_RB(U) + N_A(U)) ν + G η = τ.
In surge, sway and yaw it is the linear manoeuvring model of Fossen (2011) §7.1: sway
(m + A₁₁)U r, yaw the Munk moment (A₂₂ − A₁₁)U v and (m x_g + A₂₆)U r; in the vertical
plane heave −(m + A₁₁)U q and the pitch Munk moment (A₁₁ − A₃₃)U w. The added mass is the
model's own M_A (the zero-frequency values of surge, sway and yaw, Ross, Perez & Fossen
(2006) Definition 1), the potential damping its zero-speed B; the speed's other effects
on the hull (lift, the rudder, the propeller) are the user's viscous damping.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES, split_dof
from cummins.kinematics import skew
from cummins.timedomain.lfmodel.model import LowFrequencyModel


def speed_matrix(mass: ArrayLike, speed: float) -> NDArray[np.float64]:
    """N(U) (6, 6): the Jacobian of Kirchhoff's Coriolis and centripetal force C(ν)ν of
    the inertia ``mass`` (6, 6, symmetric: M_RB or M_A, surge … yaw) at ν₀ = (U, 0, …, 0)
    (module docstring), kg/s, kg·m/s, kg·m²/s.

    Examples
    --------
    >>> m = np.diag([1.0e6, 1.5e6, 1.2e6, 1.0e8, 3.0e9, 3.0e9])
    >>> n = speed_matrix(m, 5.0)
    >>> float(n[5, 1])  # the Munk moment (M22 − M11) U
    2500000.0
    """
    m = np.asarray(mass, dtype=float)
    v0 = np.array([float(speed), 0.0, 0.0])
    a0, b0 = m[:3, :3] @ v0, m[3:, :3] @ v0
    out = np.zeros((6, 6))
    out[:3, 3:] = -skew(a0)
    out[3:, :3] = -skew(a0) + skew(v0) @ m[:3, :3]
    out[3:, 3:] = skew(v0) @ m[:3, 3:] - skew(b0)
    return out


#: Entries of N(U) below this fraction of its largest are round-off, not speed terms.
SPEED_TERM_FLOOR = 1e-9


def speed_term_entries(speed_terms: ArrayLike, dofs) -> list[tuple[str, str, float]]:
    """The entries of N(U) that are speed terms, (row DOF, column DOF, value), row by
    row: those above :data:`SPEED_TERM_FLOOR` of the largest (``cummins lf-model`` prints
    them, ``cummins report`` tabulates them)."""
    n = np.asarray(speed_terms, dtype=float)
    floor = SPEED_TERM_FLOOR * np.abs(n).max() if n.size else 0.0
    labels = [str(d) for d in dofs]
    return [
        (labels[i], labels[j], float(n[i, j]))
        for i in range(n.shape[0])
        for j in range(n.shape[1])
        if abs(n[i, j]) > floor
    ]


def at_forward_speed(model: LowFrequencyModel, speed: float) -> LowFrequencyModel:
    """The low-frequency model of the ship moving ahead at ``speed`` U, m/s: the model
    (built from zero-speed data) with N_RB(U) + N_A(U) (module docstring) in
    :attr:`~LowFrequencyModel.speed_terms`.

    Raises
    ------
    HydroDataError
        A model of several bodies or of DOFs other than the rigid-body ones (the
        linearisation is of one rigid hull), or a speed that is not finite.
    """
    if not np.isfinite(speed):
        raise HydroDataError(f"the forward speed must be finite, not {speed}")
    parts = [split_dof(d) for d in model.dofs]
    names = [name for _, name in parts]
    if len({body for body, _ in parts}) > 1 or not set(names) <= set(DOF_NAMES):
        raise HydroDataError(
            "speed terms are those of one rigid hull; the model's DOFs are "
            + ", ".join(model.dofs),
            hint="derive the model of each hull from its own DOFs",
        )
    index = [DOF_NAMES.index(name) for name in names]
    full = {}
    for key, matrix in (("rb", model.rigid_body_mass), ("a", model.added_mass)):
        six = np.zeros((6, 6))
        six[np.ix_(index, index)] = 0.5 * (matrix + matrix.T)
        full[key] = speed_matrix(six, speed)[np.ix_(index, index)]
    return replace(
        model,
        speed_terms=full["rb"] + full["a"],
        attrs={
            **dict(model.attrs),
            "forward_speed": float(speed),
            "speed_terms": "N_RB(U) + N_A(U): the linearised Coriolis and centripetal "
            "forces of the rigid body and the added mass about u = U (Fossen (2011) "
            "Thm. 3.2, 6.2; §7.1)",
        },
    )
