"""MSS ``RAO`` structs: the force RAOs MSS writes from VERES (:func:`read_force_rao`).

Such a file holds no added mass, damping or restoring: :func:`cummins.io.mss.read_mss`
refuses it and names this reader.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES
from cummins.io.mss.matfile import _cells, _field, _numeric, load_mat_struct


def _holds_rao_struct(path: Path) -> bool:
    import scipy.io  # here: reading a file of another format need not load it

    try:
        variables = scipy.io.whosmat(str(path))
    except Exception:
        return False
    names = {name for name, _, cls in variables if cls == "struct"}
    return "RAO" in names and "vessel" not in names


def read_force_rao(path: str | os.PathLike[str], *, axes: str = "z-down") -> xr.DataArray:
    """The force RAOs of an MSS ``RAO`` struct as an ``excitation_force`` DataArray.

    MSS writes such a struct (``RAO.Amp{1:6}``, ``RAO.Phase{1:6}``: Freq × Dir × Vel
    tables; ``RAO.Freq`` rad/s, ``RAO.Dir`` rad, ``RAO.Vel`` m/s; ``.m`` text twin "3D
    table of RAO Amplitudes (Freq, Dir, Vel)") when it processes VERES force RAOs
    (``input.re8``), with the conventions of its ``vessel.forceRAO``: complex value
    amp·e^{i·phase} for x(t) = Re{X e^{iωt}}, Fossen's z-down body axes, ``Dir`` the
    direction the waves travel relative to x (0 following, π head seas). Amplitudes are
    N/m and N·m/m (per metre of wave amplitude).

    Parameters
    ----------
    path
        The ``.mat`` file.
    axes
        ``"z-down"`` (as stored) or ``"z-up"`` (T = diag(1, −1, −1, 1, −1, −1), β → −β).

    Returns
    -------
    xarray.DataArray
        Complex, dims (forward_speed, omega, wave_direction, influenced_dof), DOFs
        ``Surge`` … ``Yaw``; attributes ``axis_convention``, ``units``, ``source_file``.

    Raises
    ------
    HydroDataError
        No RAO struct, wrong shapes, non-finite values.
    """
    from cummins.kinematics import Z_UP_TO_Z_DOWN

    path = Path(path)
    rao = load_mat_struct(path, "RAO", "MSS RAO files hold a struct named RAO")
    where = "RAO"
    freq = _numeric(_field(rao, "Freq", path, where), path, "RAO.Freq").reshape(-1)
    heading = _numeric(_field(rao, "Dir", path, where), path, "RAO.Dir").reshape(-1)
    speed = _numeric(_field(rao, "Vel", path, where), path, "RAO.Vel").reshape(-1)
    amp = _cells(_field(rao, "Amp", path, where), path, "RAO.Amp")
    phase = _cells(_field(rao, "Phase", path, where), path, "RAO.Phase")
    if len(amp) != 6 or len(phase) != 6:
        raise HydroDataError(
            f"expected 6 amplitude and phase tables, found {len(amp)} and {len(phase)}",
            path=path,
            quantity="RAO.Amp, RAO.Phase",
        )
    for name, v in (("RAO.Freq", freq), ("RAO.Dir", heading), ("RAO.Vel", speed)):
        if v.size == 0 or not np.all(np.isfinite(v)):
            raise HydroDataError("empty or non-finite", path=path, quantity=name)
    if np.any(freq <= 0) or np.any(np.diff(freq) <= 0):
        raise HydroDataError(
            "frequencies must be positive and increasing", path=path, quantity="RAO.Freq"
        )
    shape = (freq.size, heading.size, speed.size)
    values = np.empty((speed.size, freq.size, heading.size, 6), dtype=complex)
    for k in range(6):
        a = amp[k].reshape(amp[k].shape + (1,) * (3 - amp[k].ndim))
        ph = phase[k].reshape(phase[k].shape + (1,) * (3 - phase[k].ndim))
        for label, arr in ((f"RAO.Amp{{{k + 1}}}", a), (f"RAO.Phase{{{k + 1}}}", ph)):
            if arr.shape != shape:
                raise HydroDataError(
                    f"has shape {arr.shape}, expected {shape} (Freq, Dir, Vel)",
                    path=path,
                    quantity=label,
                )
            if not np.all(np.isfinite(arr)):
                raise HydroDataError("non-finite value", path=path, quantity=label)
        values[..., k] = np.moveaxis(a * np.exp(1j * ph), 2, 0)
    beta = heading
    if axes == "z-up":
        values = values * np.asarray(Z_UP_TO_Z_DOWN)
        beta = np.mod(-heading, 2 * np.pi)
        beta[np.isclose(beta, 2 * np.pi)] = 0.0
        order = np.argsort(beta)
        beta, values = beta[order], values[:, :, order, :]
    elif axes != "z-down":
        raise HydroDataError(f"unknown axes {axes!r}", hint="use 'z-down' or 'z-up'")
    return xr.DataArray(
        values,
        dims=("forward_speed", "omega", "wave_direction", "influenced_dof"),
        coords={
            "forward_speed": ("forward_speed", speed, {"units": "m/s"}),
            "omega": ("omega", freq, {"units": "rad/s"}),
            "wave_direction": ("wave_direction", beta, {"units": "rad"}),
            "influenced_dof": list(DOF_NAMES),
        },
        name="excitation_force",
        attrs={
            "units": "N/m | N m/m (per metre of wave amplitude)",
            "axis_convention": axes,
            "time_convention": "x(t) = Re{X exp(i omega t)}",
            "source_file": str(path),
            "source_format": "mss-rao",
        },
    )
