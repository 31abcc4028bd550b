"""Salvesen–Tuck–Faltinsen speed terms on zero-speed data (:func:`stf_speed_terms`).

Hjulstad (2004) eqs. 3.29, 3.33, 5.45–5.46, 10.1, §6; aft-section terms omitted as in
the thesis. In impedance form, Z(ω) = B(ω) + jω A(ω) (force −Z·velocity, cummins'
convention x(t) = Re{X e^{jωt}}), with s = jω::

    Z_U = Z₀ + (U/s)(Z₀E − EᵀZ₀) − (U²/s²) EᵀZ₀E,   E = e_heave e_pitchᵀ − e_sway e_yawᵀ

which is, term by term, A₃₅ = A⁰₃₅ − U B⁰₃₃/ω², B₃₅ = B⁰₃₅ + U A⁰₃₃ (eq. 3.33/10.1),
A₅₃ = A⁰₅₃ + U B⁰₃₃/ω², B₅₃ = B⁰₅₃ − U A⁰₃₃ (the thesis' code, App. C.2–C.3),
A₅₅ = A⁰₅₅ + U²A⁰₃₃/ω², B₅₅ = B⁰₅₅ + U²B⁰₃₃/ω² (eqs. 3.29, 5.45–5.46), the mirror
terms in sway–yaw (26, 62, 66) and the surge/roll couplings (15, 51, 46, 64) of the
thesis' ``AugmentWithBinf`` table (§6). The expressions are the same in z-up and in
Fossen's z-down axes (every term flips sign twice or not at all); on the S-175
(ShipX/VERES strip theory, z-down) they reproduce the data at 10.29 m/s from the
data at 0 m/s to within 0.8 % of each term's peak above the first frequency
(tests/test_speed.py).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.hydrodb import add_history, dof_matrix, single_speed, split_dof
from cummins.radiation.speed.errors import SpeedError


def speed_coupling_matrix(labels: Sequence[str]) -> NDArray[np.float64]:
    """E = e_heave e_pitchᵀ − e_sway e_yawᵀ over ``labels`` (module docstring).

    Entries whose two DOFs are not both present are left out.

    Raises
    ------
    SpeedError
        For several bodies (the STF terms are for one ship).
    """
    names = [split_dof(str(label)) for label in labels]
    if len({body for body, _ in names}) > 1:
        raise SpeedError("STF speed terms are defined for one body; select one body's DOFs")
    index = {name: k for k, (_, name) in enumerate(names)}
    e = np.zeros((len(labels), len(labels)))
    if "Heave" in index and "Pitch" in index:
        e[index["Heave"], index["Pitch"]] = 1.0
    if "Sway" in index and "Yaw" in index:
        e[index["Sway"], index["Yaw"]] = -1.0
    return e


def _speed_impedance(z0: NDArray, omega: NDArray, e: NDArray, speed: float) -> NDArray:
    s = 1j * omega[:, None, None]
    first = z0 @ e - e.T @ z0
    second = e.T @ z0 @ e
    return z0 + speed / s * first - speed**2 / s**2 * second


def stf_speed_terms(ds: xr.Dataset, speed: float) -> xr.Dataset:
    """Zero-speed A(ω), B(ω) with the Salvesen–Tuck–Faltinsen speed terms at ``speed``.

    Hjulstad (2004) eqs. 3.29, 3.33, 5.45–5.46, 10.1 and §6 (aft-section terms omitted),
    in the matrix form of the module docstring. Only ``added_mass`` and
    ``radiation_damping`` change; ``added_mass_inf`` (if present) stays (the STF terms
    vanish in A as ω → ∞); B(∞) becomes U·α∞ in the couplings
    (:attr:`SpeedDependentModel.damping_inf`).

    Parameters
    ----------
    ds
        A ``HydroDB`` at zero speed (one speed; a ``forward_speed`` other than 0 is an
        error: the terms would be applied twice).
    speed
        Forward speed U, m/s.

    Returns
    -------
    xarray.Dataset
        A copy with the corrected coefficients and a scalar ``forward_speed``.

    Examples
    --------
    >>> import cummins, numpy as np
    >>> ds = cummins.demo_dataset()
    >>> fast = stf_speed_terms(ds, 5.0)
    >>> w = ds.omega.values
    >>> a33 = ds.added_mass.sel(influenced_dof="Heave", radiating_dof="Heave").values
    >>> b35 = fast.radiation_damping.sel(influenced_dof="Heave", radiating_dof="Pitch")
    >>> b35_0 = ds.radiation_damping.sel(influenced_dof="Heave", radiating_dof="Pitch")
    >>> bool(np.allclose(b35 - b35_0, 5.0 * a33))
    True
    """
    ds = _zero_speed(ds)
    labels = [str(d) for d in ds.influenced_dof.values]
    w = ds.omega.values
    if np.any(w <= 0):
        raise SpeedError("the STF speed terms need omega > 0 (they scale with 1/omega^2)")
    z0 = dof_matrix(ds, "radiation_damping") + 1j * w[:, None, None] * dof_matrix(ds, "added_mass")
    z = _speed_impedance(z0, w, speed_coupling_matrix(labels), float(speed))
    out = ds.copy()
    dims = ("omega", "influenced_dof", "radiating_dof")
    if speed == 0:  # exactly the input (no round trip through Z = B + jωA)
        return out.assign_coords(forward_speed=0.0)
    out["added_mass"] = (dims, z.imag / w[:, None, None], ds.added_mass.attrs)
    out["radiation_damping"] = (dims, z.real, ds.radiation_damping.attrs)
    out = out.assign_coords(forward_speed=float(speed))
    out.forward_speed.attrs["units"] = "m/s"
    add_history(
        out, f"STF speed terms (Hjulstad (2004) eqs. 3.29, 3.33) applied for U = {speed:g} m/s"
    )
    return out


def _zero_speed(ds: xr.Dataset) -> xr.Dataset:
    if "forward_speed" in ds.dims:
        if 0.0 not in ds.forward_speed.values:
            raise SpeedError("the dataset has no zero-speed data for the STF speed terms")
        ds = ds.sel(forward_speed=0.0)
    if "forward_speed" in ds.coords and float(ds.forward_speed) != 0.0:
        raise SpeedError(
            f"the dataset is at {float(ds.forward_speed):g} m/s: STF speed terms apply to "
            "zero-speed data",
            hint="select forward_speed=0",
        )
    return single_speed(ds)
