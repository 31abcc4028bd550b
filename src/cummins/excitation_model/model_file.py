"""The NetCDF file of a causal excitation model (:class:`~cummins.excitation_model.model.
ExcitationModel`).

A public format: other tools may read and write it from this description alone.
NetCDF-4 (HDF5, written with h5netcdf; every numeric array with HDF5's Fletcher-32
checksum), one file per model.

Model
-----
For each heading h (direction of wave travel β_h, rad: 0 following seas, π head seas)
and DOF d, a single-input single-output system driven by the incident wave elevation
at the origin η (m), advanced by the heading's t_c (s):

    ẋ = a x + b η(t + t_c),    F_d = c x,

F_d the first-order wave force or moment (N, N·m) in the axes named by the
``axis_convention`` attribute about ``reference_point``; frequency response
F_d(ω)/η(ω) = c (jωI − a)⁻¹ b e^{jωt_c} with time dependence Re{X e^{iωt}} (the data's
``excitation_force``). Stacked by DOF (the states of a DOF contiguous, in DOF order),
the models of one heading form the MIMO system of HydroDyn's ``.ssexctn``: A
block-diagonal, B the stacked b, C the c of each DOF in its row.

Dimensions and coordinates
--------------------------
``wave_direction`` (β, rad), ``influenced_dof`` (labels ``Surge`` … ``Yaw``,
``body1__Surge`` … for several bodies), ``model`` (one per (heading, DOF), heading-major:
model k is heading k // n_dof, DOF k % n_dof), ``state`` and ``state2`` (the largest
order of any model; may be 0).

Variables
---------
``delay`` (wave_direction), float64, s
    t_c of each heading.
``order`` (model), int32
    Number of states n_k of each model (0: the DOF is not excited at that heading).
``a`` (model, state, state2), ``b`` (model, state), ``c`` (model, state), float64
    Each model's matrices in the first n_k rows/columns; the rest zero (padding).
``nrmse`` (model), float64
    NRMSE of the complex response over the wave band (:mod:`cummins.excitation_model.fit`).
``note`` (model), string
    What the user should know about each fit (empty when nothing).
``metrics_json`` (model), string
    Every fit measure of each model (JSON object), for an exact round trip.

Global attributes
-----------------
``cummins_format`` = ``"cummins-excitation-model"``, ``cummins_format_version`` = 1,
``cummins_version``, ``conventions`` (a summary of the above), and the model's own
(``source_file``, ``rho``, ``g``, ``axis_convention``, ``nrmse_target``, ``failures`` …;
values NetCDF cannot store as they are JSON-encoded in ``cummins_json_attrs``).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import xarray as xr

from cummins._version import __version__
from cummins.errors import CumminsError, HydroDataError
from cummins.excitation_model.model import DofExcitation, ExcitationModel
from cummins.io.netcdf import (
    VERSION_ATTR,
    decode_attribute,
    decode_attributes,
    encode_attribute,
    encode_attributes,
    load_netcdf,
    save_netcdf,
)

__all__ = ["FORMAT_NAME", "read_excitation_model", "write_excitation_model"]

#: Value of the ``cummins_format`` attribute.
FORMAT_NAME = "cummins-excitation-model"
FORMAT_VERSION = 1
CONVENTIONS = (
    "cummins excitation model v1: per heading h and DOF d, x' = a x + b eta(t + delay[h]), "
    "F_d = c x; F_d(w)/eta(w) = c (jwI - a)^-1 b exp(jw delay[h]), time dependence exp(+iwt); "
    "eta = incident wave elevation at the origin (m), F in N, N m, SI units; model k is "
    "heading k // n_dof, DOF k % n_dof; its matrices are the first order[k] rows/columns "
    "of a, b, c"
)
_REQUIRED = ("delay", "order", "a", "b", "c")


def write_excitation_model(model: ExcitationModel, path: str | os.PathLike[str]) -> Path:
    """Write ``model`` as NetCDF-4 in the layout of the module docstring (no overwrite
    check: :meth:`ExcitationModel.save` does it)."""
    return save_netcdf(model_to_dataset(model), path)


def model_to_dataset(model: ExcitationModel) -> xr.Dataset:
    """The :class:`xarray.Dataset` :func:`write_excitation_model` writes."""
    count = len(model.models)
    size = max((m.order for m in model.models), default=0)
    a = np.zeros((count, size, size))
    b = np.zeros((count, size))
    c = np.zeros((count, size))
    for k, m in enumerate(model.models):
        a[k, : m.order, : m.order], b[k, : m.order], c[k, : m.order] = m.a, m.b, m.c
    ds = xr.Dataset(
        coords={
            "wave_direction": ("wave_direction", np.asarray(model.headings, dtype=float)),
            "influenced_dof": ("influenced_dof", [str(d) for d in model.dofs]),
            "model": ("model", np.arange(1, count + 1, dtype=np.int32)),
        }
    )
    ds["wave_direction"].attrs = {"units": "rad", "long_name": "direction of wave travel"}
    ds["delay"] = ("wave_direction", np.asarray(model.delays, dtype=float), {"units": "s"})
    ds["order"] = ("model", np.array([m.order for m in model.models], dtype=np.int32))
    ds["a"] = (("model", "state", "state2"), a, {"units": "1/s"})
    ds["b"] = (("model", "state"), b)
    ds["c"] = (("model", "state"), c)
    ds["nrmse"] = ("model", np.array([float(m.metrics.get("nrmse", np.nan)) for m in model.models]))
    ds["note"] = ("model", np.array([m.note for m in model.models], dtype=object))
    ds["metrics_json"] = (
        "model",
        np.array(
            [
                json.dumps({k: encode_attribute(v, k) for k, v in m.metrics.items()})
                for m in model.models
            ],
            dtype=object,
        ),
    )
    attrs = encode_attributes(dict(model.attrs))
    ds.attrs = {
        "cummins_format": FORMAT_NAME,
        "cummins_format_version": np.int32(FORMAT_VERSION),
        VERSION_ATTR: __version__,
        "conventions": CONVENTIONS,
        **attrs,
    }
    return ds


def read_excitation_model(path: str | os.PathLike[str]) -> ExcitationModel:
    """Read a file in the layout of the module docstring.

    Raises
    ------
    HydroDataError
        Not such a file, a variable missing, inconsistent sizes, an unstable model.
    """
    path = Path(path)
    raw = load_netcdf(path)
    return dataset_to_model(raw, path)


def dataset_to_model(raw: xr.Dataset, path=None) -> ExcitationModel:
    """Inverse of :func:`model_to_dataset`; ``path`` for the messages."""
    if raw.attrs.get("cummins_format") != FORMAT_NAME:
        raise HydroDataError(
            f"not a cummins excitation-model file (cummins_format is "
            f"{raw.attrs.get('cummins_format')!r})",
            path=path,
            hint="write it with cummins fit-excitation or ExcitationModel.save",
        )
    missing = [name for name in _REQUIRED if name not in raw.variables]
    if missing:
        raise HydroDataError(f"missing variable(s) {', '.join(missing)}", path=path)
    headings = np.asarray(raw.wave_direction.values, dtype=float)
    dofs = tuple(str(d) for d in raw.influenced_dof.values)
    order = np.asarray(raw["order"].values, dtype=int)
    a, b, c = (np.asarray(raw[name].values, dtype=float) for name in ("a", "b", "c"))
    n = len(dofs)
    if order.size != headings.size * n or a.shape[0] != order.size:
        raise HydroDataError(
            f"{order.size} models for {headings.size} headings × {n} DOFs", path=path
        )
    if order.size and (order.min() < 0 or order.max() > a.shape[1]):
        raise HydroDataError("an order is outside the size of the matrices", path=path)
    notes = [str(x) for x in raw["note"].values] if "note" in raw else [""] * order.size
    metrics = []
    for k in range(order.size):
        text = str(raw["metrics_json"].values[k]) if "metrics_json" in raw else "{}"
        try:
            metrics.append({key: decode_attribute(v) for key, v in json.loads(text).items()})
        except (ValueError, TypeError, KeyError) as exc:
            raise HydroDataError(
                f"unreadable metrics of model {k + 1} ({exc})", path=path
            ) from None
    models = []
    for k, r in enumerate(order):
        heading, dof = divmod(k, n)
        part = DofExcitation(
            dof, heading, a[k, :r, :r].copy(), b[k, :r].copy(), c[k, :r].copy(), metrics[k],
            notes[k],
        )  # fmt: skip
        if r and not part.is_stable():
            raise HydroDataError(
                f"model {k + 1} ({dofs[dof]}, {np.degrees(headings[heading]):g} deg) is unstable",
                path=path,
                hint="the file is damaged or edited",
            )
        models.append(part)
    attrs = decode_attributes(
        {k: v for k, v in raw.attrs.items() if k not in ("cummins_format", "conventions")},
        where=path,
    )
    attrs.pop("cummins_format_version", None)
    attrs.pop(VERSION_ATTR, None)
    try:
        return ExcitationModel(
            dofs, headings, np.asarray(raw["delay"].values, dtype=float), tuple(models), attrs
        )
    except CumminsError as exc:
        raise HydroDataError(str(exc), path=path) from None
