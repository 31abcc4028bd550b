"""A radiation model about another reference point: the screw transform of
:func:`cummins.move_reference_point` applied to the model, exactly.

With H the screw transformation of the data's DOFs (Smogeli et al. (2004) eq. 38, each
body's six rigid-body modes; generalized modes unchanged), a matrix about the old point
becomes Hᵀ M H about the new one. The fluid memory is linear in the velocities and gives
a force, so K'(s) = Hᵀ K(s) H and A∞' = Hᵀ A∞ H: the state space keeps its states and
poles (a = A), with b' = B H and c' = Hᵀ C. Stability is kept (the same A), and
passivity too: K' + K'ᴴ = Hᵀ (K + Kᴴ) H is a congruence of a positive semidefinite
matrix. The file formats that store one model per coupling (BEMIO) then write each
coupling's minimal realization (:meth:`RadiationModel.as_couplings`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from cummins.errors import HydroDataError
from cummins.radiation.model import MemoryBlock, RadiationModel


def moved_model(model: RadiationModel, ds: xr.Dataset, point: ArrayLike) -> RadiationModel:
    """``model`` (of the data ``ds``, about their reference point) about ``point``.

    Parameters
    ----------
    model
        A radiation model of the DOFs of ``ds``.
    ds
        The data it was fitted to: their ``reference_point`` and bodies give H.
    point
        The new reference point, m, (3,) or (n_bodies, 3), in the data's axes.

    Returns
    -------
    RadiationModel
        One memory block over all DOFs, K'(s) = Hᵀ K(s) H, A∞' = Hᵀ A∞ H, its history
        saying so.

    Examples
    --------
    >>> import numpy as np, cummins
    >>> ds = cummins.demo_dataset()
    >>> model = cummins.fit_radiation(ds)
    >>> there = moved_model(model, ds, [10.0, 0.0, -2.0])
    >>> moved = cummins.move_reference_point(ds, [10.0, 0.0, -2.0])
    >>> back = moved_model(there, moved, ds.attrs["reference_point"])
    >>> w = np.array([0.3, 0.6, 1.2])
    >>> k, k_back = model.response(w), back.response(w)
    >>> bool(np.abs(k_back - k).max() < 1e-9 * np.abs(k).max())
    True
    """
    from cummins.hydrodb import per_body_transform, reference_points
    from cummins.kinematics import screw_transform

    labels = [str(d) for d in ds.influenced_dof.values]
    if [str(d) for d in model.dofs] != labels:
        raise HydroDataError(
            f"the model's DOFs ({', '.join(map(str, model.dofs))}) are not the data's",
            hint="move the model of these data",
        )
    old = reference_points(ds)
    new = np.broadcast_to(np.asarray(point, dtype=float).reshape(-1, 3), old.shape)
    r = old - new
    h = per_body_transform(ds, lambda k: screw_transform(r[k]))
    block = MemoryBlock(
        tuple(range(len(labels))), model.A, model.B @ h, h.T @ model.C, note="moved"
    )
    history = str(model.attrs.get("history", ""))
    moved = f"{np.round(old, 6).tolist()} to {np.round(new, 6).tolist()} m"
    attrs = {
        **model.attrs,
        "reference_point": new.reshape(-1) if new.shape[0] > 1 else new[0].copy(),
        "history": (history + "\n" if history else "") + f"model moved from {moved}",
    }
    return RadiationModel(model.dofs, (), h.T @ model.added_mass_inf @ h, attrs, (block,))
