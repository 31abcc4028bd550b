"""The infinite-frequency added mass of DOFs whose data are not causal with the data's
own ω = ∞ row.

A causal model's added mass is A(ω) = A∞ + the Kramers–Kronig transform of its damping
(Ogilvie (1964) eq. 15; Perez & Fossen (2008) eq. 12). Where a DOF's A(ω) is far from
that transform with the solver's A∞ row (:func:`~cummins.radiation.retardation.kramers_kronig_error`
above :data:`NONCAUSAL`), a model held to that row can follow the data's added mass only
with damping the data do not have, and a lightly damped resonance of the motions then
moves: WEC-Sim's RM3 from WAMIT, whose spar pitch added mass is 97 % of its variation
off the transform, has its spar pitch RAO 14 % of its peak off the data's at 0.34 rad/s.

When the motions miss their target and such DOFs are among those that miss it, the
blocks are fitted once more with A∞ of those DOFs estimated with the rest of the model
(the joint estimate, Perez & Fossen (2008) §4, with Ogilvie's estimate as its prior), the
data's row kept for every other DOF, and the fit nearer the data's motions is kept
(:func:`with_causal_inf`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from cummins.radiation.model import RadiationModel

#: A DOF whose A(ω) is further than this from the Kramers–Kronig transform of its B(ω)
#: (relative, :func:`cummins.radiation.retardation.kramers_kronig_error`, with the model's
#: A∞) cannot be followed by a causal model: a motion error there is the data's.
NONCAUSAL = 0.5


def estimated_inf(added_mass_inf: NDArray[np.float64], dofs) -> NDArray[np.float64]:
    """``added_mass_inf`` with the rows and columns of ``dofs`` NaN: what
    :func:`cummins.radiation.fit.vector.block_data` estimates."""
    out = np.array(added_mass_inf, dtype=float)
    if len(dofs):
        index = np.asarray(dofs, dtype=int)
        out[index, :] = np.nan
        out[:, index] = np.nan
    return out


def kramers_kronig_misfit(inp, model: RadiationModel) -> NDArray[np.float64]:
    """Per DOF, how far the data's A(ω) is from the Kramers–Kronig transform of their
    B(ω) with the model's A∞ (relative, as
    :func:`~cummins.radiation.retardation.kramers_kronig_error`)."""
    from cummins.radiation.retardation import kramers_kronig_error

    inf = np.asarray(model.added_mass_inf, dtype=float)
    return np.diag(kramers_kronig_error(inp.data, added_mass_inf=0.5 * (inf + inf.T)).values)


def noncausal_indices(inp, model: RadiationModel, missed, error=None) -> list[int]:
    """The DOFs among ``missed`` (a mask) whose data are not causal with the model's A∞
    (:data:`NONCAUSAL`; ``error``: :func:`kramers_kronig_misfit`, when known)."""
    if error is None:
        error = kramers_kronig_misfit(inp, model)
    return [d for d in range(len(inp.labels)) if missed[d] and error[d] > NONCAUSAL]


def noncausal_dofs(inp, model: RadiationModel, missed) -> list[str]:
    """:func:`noncausal_indices` as ``"body2__Pitch (98 %)"``."""
    error = kramers_kronig_misfit(inp, model)
    return [
        f"{inp.labels[d]} ({100 * error[d]:.3g} %)"
        for d in noncausal_indices(inp, model, missed, error)
    ]


def with_causal_inf(
    inp, options, model: RadiationModel, fit: Callable[..., RadiationModel]
) -> RadiationModel:
    """``model``, or the blocks fitted again by ``fit`` (``fit(inp, options)``) with A∞
    estimated for the DOFs whose data are not causal with the data's ω = ∞ row, when
    those miss the motion target and the refit comes nearer the data's motions (module
    docstring). Only for ``added_mass_inf="auto"`` with the data's row in use; the model
    kept records ``attrs["added_mass_inf_estimated"]`` (labels) and says so in its
    ``data_notes``."""
    error = model.attrs.get("motion_error")
    tol = model.attrs.get("motion_target")
    if (
        options.added_mass_inf != "auto"
        or inp.a_inf_mode != "data"
        or inp.estimated_inf
        or error is None
        or tol is None
        or error <= tol
    ):
        return model
    missed = np.asarray(model.attrs.get("motion_error_by_dof", []), dtype=float) > tol
    if missed.size != len(inp.labels):
        return model
    dofs = noncausal_indices(inp, model, missed)
    if not dofs:
        return model
    refit = fit(replace(inp, estimated_inf=tuple(dofs)), options)
    error_refit = refit.attrs.get("motion_error")
    names = ", ".join(inp.labels[d] for d in dofs)
    if error_refit is None:
        return model
    if error_refit >= error:
        note = (
            f"A∞ of {names} estimated with the model instead of the data's ω = ∞ row (their "
            f"added mass is far from the Kramers–Kronig transform of their damping with it) "
            f"did not bring the motions nearer the data ({100 * error_refit:.3g} % against "
            f"{100 * error:.3g} %): the data's row kept"
        )
        notes = [*model.attrs.get("data_notes", []), note]
        return replace(model, attrs={**model.attrs, "data_notes": notes})
    note = (
        f"A∞ of {names} estimated with the model, the data's ω = ∞ row kept for the other "
        "DOFs: their added mass is far from the Kramers–Kronig transform of their damping "
        f"with the row (cummins check: retardation); motion error {100 * error:.3g} % with "
        f"the row, {100 * error_refit:.3g} % so"
    )
    attrs = {
        **refit.attrs,
        "added_mass_inf_estimated": [inp.labels[d] for d in dofs],
        "data_notes": [*refit.attrs.get("data_notes", []), note],
    }
    return replace(refit, attrs=attrs)
