"""The fingerprint of the data a radiation model was fitted to, and the check that a
model is used with those data.

A fluid-memory model belongs to one body's added mass and damping: simulated with
another vessel's data (its inertia, restoring and wave forces) it gives motions that
are nobody's. :func:`data_fingerprint` records, at fit time, what identifies the data —
the DOFs, ρ and g, the frequency range, the source file's name and SHA-256, and the
diagonal A(ω), B(ω) at up to 12 of the data's own frequencies — in the model's
``data_fingerprint`` attribute (JSON in the model file; files written before it have
none). :func:`check_model_data` compares a model with the data it is about to be used
with and refuses what differs, naming it, unless the user says the pairing is meant
(``allow_other_data=True``, ``--allow-other-data``); without a fingerprint it compares
the DOFs and A∞ (the data's ω = ∞ row or Ogilvie's estimate) and warns that it could do
no more.
"""

from __future__ import annotations

import hashlib
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import CumminsWarning, HydroDataError
from cummins.hydrodb import dof_matrix

#: Frequencies of the data kept in the fingerprint.
SIGNATURE_POINTS = 12
#: Relative agreement of A(ω), B(ω) at the fingerprint's frequencies (of each DOF's
#: largest value): the same file read twice agrees exactly, another body by far more.
SIGNATURE_TOLERANCE = 1e-6
#: A∞ of the model against the data's (row or Ogilvie's estimate) when there is no
#: fingerprint: a fit's A∞ is within a few per cent of either, another body's is not.
ADDED_MASS_INF_TOLERANCE = 0.25


def data_fingerprint(ds: xr.Dataset) -> dict[str, Any]:
    """What identifies the data of a fit (module docstring), JSON-ready."""
    labels = [str(d) for d in ds.influenced_dof.values]
    w = ds.omega.values.astype(float)
    pick = np.unique(np.linspace(0, w.size - 1, min(SIGNATURE_POINTS, w.size)).astype(int))
    a = np.diagonal(dof_matrix(ds, "added_mass"), axis1=-2, axis2=-1)
    b = np.diagonal(dof_matrix(ds, "radiation_damping"), axis1=-2, axis2=-1)
    source = str(ds.attrs.get("source_file", "") or "")
    return {
        "dofs": labels,
        "rho": float(ds.attrs.get("rho", np.nan)),
        "g": float(ds.attrs.get("g", np.nan)),
        "n_omega": int(w.size),
        "omega_min": float(w[0]),
        "omega_max": float(w[-1]),
        "source_name": Path(source).name if source else "",
        "source_sha256": _sha256(source),
        "omega": [float(x) for x in w[pick]],
        "added_mass": a[pick].tolist(),
        "radiation_damping": b[pick].tolist(),
    }


def _sha256(path: str) -> str:
    """SHA-256 of the file's bytes ('' when it is not a readable file)."""
    try:
        p = Path(path)
        if not path or not p.is_file():
            return ""
        digest = hashlib.sha256()
        with p.open("rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                digest.update(chunk)
        return digest.hexdigest()
    except OSError:
        return ""


def model_data_differences(model, ds: xr.Dataset) -> tuple[list[str], bool]:
    """What differs between the data ``model`` was fitted to and ``ds`` (one line each),
    and whether the model records a fingerprint."""
    labels = [str(d) for d in ds.influenced_dof.values]
    if list(model.dofs) != labels:
        return [f"DOFs {', '.join(model.dofs)} in the model, {', '.join(labels)} in the data"], (
            "data_fingerprint" in model.attrs
        )
    fp = model.attrs.get("data_fingerprint")
    if not isinstance(fp, dict):
        return _added_mass_inf_difference(model, ds), False
    out = []
    for key, unit in (("rho", "kg/m^3"), ("g", "m/s^2")):
        value = float(ds.attrs.get(key, np.nan))
        if not np.isclose(value, fp.get(key, np.nan), rtol=1e-9):
            out.append(f"{key} {fp.get(key):g} {unit} at the fit, {value:g} {unit} here")
    out += _signature_differences(fp, ds, labels)
    if out:
        name = Path(str(ds.attrs.get("source_file", "") or "")).name
        if fp.get("source_name") and fp.get("source_name") != name:
            out.append(f"fitted to {fp['source_name']}, used with {name or 'data in memory'}")
    return out, True


def _signature_differences(fp: dict, ds: xr.Dataset, labels: list[str]) -> list[str]:
    """A(ω), B(ω) of the fingerprint against the data at the frequencies both hold."""
    w = ds.omega.values.astype(float)
    a = np.diagonal(dof_matrix(ds, "added_mass"), axis1=-2, axis2=-1)
    b = np.diagonal(dof_matrix(ds, "radiation_damping"), axis1=-2, axis2=-1)
    omegas = np.asarray(fp.get("omega", []), dtype=float)
    matched = [
        (k, int(np.argmin(np.abs(w - x))))
        for k, x in enumerate(omegas)
        if np.min(np.abs(w - x)) <= 1e-9 * max(abs(x), 1.0)
    ]
    if len(matched) < min(3, omegas.size):
        return [
            f"the data's frequencies ({w.size}, {w[0]:.4g} to {w[-1]:.4g} rad/s) are not "
            f"those of the fit ({fp.get('n_omega')}, {fp.get('omega_min', np.nan):.4g} to "
            f"{fp.get('omega_max', np.nan):.4g} rad/s)"
        ]
    out = []
    for name, data in (("added mass", a), ("damping", b)):
        key = "added_mass" if name == "added mass" else "radiation_damping"
        recorded = np.asarray(fp.get(key, []), dtype=float)
        if recorded.shape != (omegas.size, len(labels)):
            continue
        ks, js = zip(*matched, strict=True)
        theirs, ours = recorded[list(ks)], data[list(js)]
        scale = np.maximum(np.abs(theirs).max(axis=0), np.abs(ours).max(axis=0))
        error = np.abs(theirs - ours).max(axis=0) / np.where(scale > 0, scale, 1.0)
        worst = int(np.argmax(error))
        if error[worst] > SIGNATURE_TOLERANCE:
            out.append(
                f"the {name} of {labels[worst]} differs from the fit's data by "
                f"{error[worst]:.3g} of its largest value"
            )
    return out


def _added_mass_inf_difference(model, ds: xr.Dataset) -> list[str]:
    """A∞ of the model against the data's ω = ∞ row, else Ogilvie's estimate (diagonal)."""
    from cummins.radiation.infinite_frequency import added_mass_inf

    labels = [str(d) for d in ds.influenced_dof.values]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        data = added_mass_inf(ds).transpose("influenced_dof", "radiating_dof").values
    ours = np.diag(np.asarray(model.added_mass_inf, dtype=float))
    theirs = np.diag(np.asarray(data, dtype=float))
    scale = np.maximum(np.abs(ours), np.abs(theirs))
    error = np.abs(ours - theirs) / np.where(scale > 0, scale, 1.0)
    worst = int(np.argmax(error))
    if error[worst] > ADDED_MASS_INF_TOLERANCE:
        return [
            f"A-infinity of {labels[worst]} is {ours[worst]:.4g} in the model and "
            f"{theirs[worst]:.4g} in the data"
        ]
    return []


def check_model_data(
    model, ds: xr.Dataset, *, allow_other_data: bool = False, model_name: str = "the model"
) -> None:
    """Refuse to use ``model`` with data other than those it was fitted to.

    Parameters
    ----------
    model
        A :class:`~cummins.radiation.model.RadiationModel`.
    ds
        The data it is about to be used with (one forward speed).
    allow_other_data
        The pairing is meant (a model fitted to the same body computed otherwise): what
        differs is a warning instead of an error. Different DOFs are an error always.
    model_name
        How to name the model in messages (its file).

    A model that names no source and records no fingerprint (one built in a script, a
    memoryless placeholder) is not checked.

    Raises
    ------
    HydroDataError
        What differs (DOFs, ρ, g, frequencies, A(ω), B(ω), A∞), one clause each.

    Warns
    -----
    CumminsWarning
        A model file without a fingerprint (written before it existed): only its DOFs and
        A∞ could be compared; or, with ``allow_other_data``, what differs.
    """
    if "data_fingerprint" not in model.attrs and not model.attrs.get("source_file"):
        # built in a script, from no file and no fit: its DOFs are checked by its user
        return
    differences, has_fingerprint = model_data_differences(model, ds)
    where = str(ds.attrs.get("source_file", "") or "") or None
    dofs_differ = bool(differences) and differences[0].startswith("DOFs ")
    if not has_fingerprint and not dofs_differ:
        warnings.warn(
            CumminsWarning(
                f"{model_name} records no fingerprint of its data (written by an earlier "
                "cummins): only its DOFs and A-infinity could be compared with the data; "
                "fit it again to record it"
            ),
            stacklevel=2,
        )
    if not differences:
        return
    text = f"{model_name} was fitted to other data: " + "; ".join(differences)
    if allow_other_data and not dofs_differ:
        warnings.warn(CumminsWarning(text + " (used anyway: --allow-other-data)"), stacklevel=2)
        return
    hint = (
        "give the data it was fitted to, fit the model to these data, or say "
        "--allow-other-data (allow_other_data=True) if the pairing is meant"
    )
    if dofs_differ:  # never allowed: the model's DOFs are not the data's
        hint = "give the data it was fitted to, or fit the model to these data"
        moving = [str(d) for d in ds.influenced_dof.values]
        if "body_coupling" in ds.attrs and set(moving) < set(model.dofs):
            # data of a mechanical system (assemble): its joints hold DOFs the model has
            text = (
                f"{model_name} holds {len(model.dofs)} DOFs, fitted to data without these "
                f"joints or DOF selection, which let only {', '.join(moving)} move"
            )
            hint = (
                "fit the model with the same --dof, --joint, --pto and --no-body-coupling "
                "options as here (system= in Python): it then holds the DOFs that move and "
                "aims at the joined system's motions; or give the data to fit it"
            )
        elif model.attrs.get("motions_of"):
            hint = (
                f"it was fitted for joined bodies ({model.attrs['motions_of']}): give the "
                "same --dof, --joint, --pto and --no-body-coupling options as its fit "
                "(system= in Python), or fit the model to these data"
            )
    raise HydroDataError(text, path=where, hint=hint)


__all__ = ["check_model_data", "data_fingerprint", "model_data_differences"]
