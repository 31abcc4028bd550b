"""At which frequency each DOF's coefficients are taken (Ross, Perez & Fossen (2006) Definition 1).

Surge, sway and yaw are zero-frequency DOFs; heave, roll and pitch natural-frequency
DOFs, whose ω₀ solves ω₀² (M_RB,ii + A_ii(ω₀)) − C_ii = 0 (eq. 24):
:func:`natural_frequency`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from cummins.errors import FitError, HydroDataError
from cummins.hydrodb import split_dof

#: DOFs of the zero-frequency sub-model (Ross, Perez & Fossen (2006) Definition 1, item 1).
ZERO_FREQUENCY_DOFS = ("Surge", "Sway", "Yaw")
#: DOFs of the natural-frequency sub-model (Ross, Perez & Fossen (2006) Definition 1, item 2).
NATURAL_FREQUENCY_DOFS = ("Heave", "Roll", "Pitch")


def _is_zero_frequency_dof(label: str) -> bool:
    return split_dof(label)[1] in ZERO_FREQUENCY_DOFS


def natural_frequency(
    coefficients: Callable[[float], tuple[NDArray, NDArray]],
    mass: float,
    stiffness: float,
    index: int,
    *,
    dof: str = "",
    tol: float = 1e-10,
    max_iter: int = 100,
) -> tuple[float, int]:
    """ω₀ of Ross, Perez & Fossen (2006) eq. 24 by fixed-point iteration.

    ω ← √(C_ii / (M_RB,ii + A_ii(ω))).

    Parameters
    ----------
    coefficients
        ω ↦ (A(ω), B(ω)), (n, n) each.
    mass, stiffness
        M_RB,ii (kg or kg·m²) and C_ii (N/m or N·m/rad), > 0.
    index
        i, the DOF's position.
    dof
        Label used in error messages.
    tol
        Converged when |ω_{k+1} − ω_k| ≤ tol · ω_k.
    max_iter
        Iterations before giving up.

    Returns
    -------
    (float, int)
        ω₀ (rad/s) and the number of iterations.

    Raises
    ------
    HydroDataError
        C_ii ≤ 0 (no restoring) or M_RB,ii + A_ii(ω) ≤ 0.
    FitError
        The iteration does not converge (the last iterates are in the message).
    """
    if not stiffness > 0:
        raise HydroDataError(
            f"{dof}: restoring C = {stiffness:.4g} ≤ 0, so there is no natural frequency "
            "(Ross, Perez & Fossen (2006) eq. 24)",
            quantity=f"hydrostatic_stiffness[{dof}, {dof}]",
            hint=f"give the frequency with frequencies={{{dof!r}: ω}} or check the hydrostatics",
        )
    omega: float | None = None  # first pass: A(0), the other limit of the inertia
    history: list[float] = []
    for k in range(max_iter):
        a_ii = float(coefficients(0.0 if omega is None else omega)[0][index, index])
        total = mass + a_ii
        if not total > 0:
            raise HydroDataError(
                f"{dof}: M_RB + A = {total:.4g} ≤ 0 at ω = {omega} rad/s",
                quantity=f"added_mass[{dof}, {dof}]",
            )
        new = float(np.sqrt(stiffness / total))
        history.append(new)
        if omega is not None and abs(new - omega) <= tol * omega:
            return new, k
        omega = new
    last = ", ".join(f"{x:.6g}" for x in history[-4:])
    raise FitError(
        f"{dof}: the natural frequency of Ross, Perez & Fossen (2006) eq. 24 did not converge "
        f"in {max_iter} fixed-point iterations (last iterates {last} rad/s)",
        hint=f"give it with frequencies={{{dof!r}: ω}} or raise max_iter",
    )
