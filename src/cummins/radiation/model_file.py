"""The NetCDF file of a fluid-memory model (:class:`~cummins.radiation.model.RadiationModel`).

This is a public format: other tools may read and write it from this description
alone. A file is NetCDF-4 (HDF5, written with h5netcdf); a NetCDF-3 file with the same
content is read too.

Model
-----
The memory force μ of the Cummins equation, μ(t) = ∫₀ᵗ K(t−τ) ξ̇(τ) dτ (the radiation
force is −A∞ ξ̈ − μ), is approximated by the linear system (Smogeli et al. (2004) eq. 36,
Unneland (2007) eqs. 3.40–3.41)

    χ̇ = A χ + B ξ̇,    μ = C χ + D ξ̇,    D = 0,

whose transfer matrix K(s) = C (sI − A)⁻¹ B approximates K(jω) = B(ω) + jω (A(ω) − A∞),
with time dependence Re{X e^{iωt}}. Inputs are the body velocities ξ̇ (m/s, rad/s),
outputs the memory forces and moments μ (N, N·m), in SI units, in the axes named by the
``axis_convention`` attribute (``"z-up"``: x forward, y to port, z up; ``"z-down"``:
Fossen's body axes), about the point ``reference_point`` when the attribute is present.

The model is assembled from single-input single-output coupling models
K_ij(s) = c (sI − a)⁻¹ b, one per modelled pair (i, j), stacked block-diagonally in the
order of the ``coupling`` dimension: the states of coupling k are contiguous, A holds
its ``a`` as a diagonal block, B its ``b`` in column j of those rows, C its ``c`` in row
i of those columns, and every other entry of A, B, C is zero. A symmetric pair K_ij =
K_ji appears as two couplings with the same matrices.

Since format version 2 a model may also hold **blocks** (after the couplings): MIMO
models K_D(s) = c (sI − a)⁻¹ b of a group D of DOFs sharing their states (the
common-pole identification). The states of block k are contiguous and follow those of
the couplings; A holds its ``a`` as a diagonal block, B its ``b`` in the columns of D,
C its ``c`` in the rows of D (in increasing DOF order). A file without blocks is a valid
version-1 file.

Dimensions and coordinates
--------------------------
``input``, ``output``
    One entry per DOF; coordinates of the same name hold the DOF labels (``Surge`` …
    ``Yaw``, ``body__Surge`` … for several bodies), identical in both.
``state``, ``state2``
    One entry per state (``state2`` is the column dimension of A: NetCDF cannot
    repeat a dimension). May be of length 0.
``coupling``
    One entry per coupling model; its coordinate numbers them 1, 2, … May be of
    length 0.
``block``
    One entry per block (version 2; absent or of length 0 without blocks).

Variables
---------
``A`` (state, state2), float64, 1/s
    State matrix.
``B`` (state, input), ``C`` (output, state), float64
    Input and output matrices; only the product C·B (N/(m/s)/s …) has a physical unit.
``D`` (output, input), float64
    Zero (A∞ is kept separately).
``added_mass_inf`` (output, input), float64, kg, kg·m, kg·m²
    A∞, to use with the model: A(ω) = A∞ + Im K(jω)/ω.
``state_coupling`` (state), int32
    Number (the ``coupling`` coordinate, 1-based) of the coupling owning each state:
    coupling k's ``a``, ``b``, ``c`` are A, B[:, j], C[i, :] restricted to its states;
    0 for a state of a block.
``state_block`` (state), int32
    Number (1-based) of the block owning each state, 0 for a state of a coupling
    (version 2).
``block_dof`` (block, input), int8
    1 where the DOF belongs to the block, 0 elsewhere.
``block_order`` (block), int32; ``block_method``, ``block_note`` (block), string
    The block's number of states, how it was identified (``"vf"``) and its note.
``block_metrics_json`` (block), string
    The fit measures of each pair of the block: a JSON object ``{"i,j": {metric:
    value}}`` (1-based DOF indices, i ≤ j; values in cummins' tagged JSON).
``coupling_influenced``, ``coupling_radiating`` (coupling), int32
    i (force, output) and j (velocity, input) of each coupling, 1-based DOF indices.
``coupling_order`` (coupling), int32
    Number of states of each coupling.
``coupling_method``, ``coupling_note`` (coupling), string
    How each coupling was identified (``"fd"``, ``"realization"``, ``"mss"`` …) and
    what the user should know about it (empty when nothing).
``coupling_<metric>`` (coupling)
    One variable per fit measure (``coupling_r2_added_mass``, ``coupling_r2_damping``,
    ``coupling_passive`` …), with attribute ``cummins_metric`` (its name) and
    ``cummins_metric_type``: ``"float"`` or ``"int"`` — float64, NaN where a coupling
    has no such measure; ``"bool"`` — int8, 1 true, 0 false, −1 absent (with CF
    ``flag_values`` and ``flag_meanings``). A string variable (type ``"str"``, empty
    where absent) is read as a text metric, though cummins writes text metrics to
    ``coupling_metrics_json``.
``coupling_metrics_json`` (coupling), string
    cummins' bookkeeping for an exact round trip: a JSON object with ``order`` (the
    metric names in their original order) and ``extra`` (metrics that have no variable
    of their own: text, arrays, NaN values …, in cummins' tagged JSON). Other tools
    may ignore it and may omit it when writing.

Global attributes
-----------------
``cummins_format`` = ``"cummins-radiation-model"``, ``cummins_format_version`` = 1,
``cummins_version`` (of the writer), ``conventions`` (a summary of this description),
and the model's own attributes (``axis_convention``, ``reference_point``, ``history``,
``source_file`` …). Attributes NetCDF cannot store as they are (``None``, booleans,
dictionaries, matrices, values of reserved names …) are JSON-encoded in
``cummins_json_attrs``, as in cummins' hydrodynamic NetCDF files
(:mod:`cummins.io.netcdf`).

Reading a file written here gives back the model exactly: every matrix, metric, note
and attribute. A file that lacks a required variable, has inconsistent sizes, or whose
A, B, C are not the block-diagonal stack described above raises
:class:`~cummins.errors.HydroDataError` naming the file and what is wrong.
"""

from __future__ import annotations

import json
import math
import os
import re
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins._version import __version__
from cummins.errors import CumminsError, FitError, HydroDataError
from cummins.io.netcdf import (
    JSON_ATTRS,
    VERSION_ATTR,
    decode_attribute,
    decode_attributes,
    encode_attribute,
    encode_attributes,
    load_netcdf,
    save_netcdf,
)
from cummins.radiation.model import (
    CouplingModel,
    MemoryBlock,
    RadiationModel,
    register_file_format,
)
from cummins.validation import guard_radiation_model

__all__ = ["FORMAT_NAME", "FORMAT_VERSION", "read_radiation_model", "write_radiation_model"]

#: Value of the ``cummins_format`` attribute.
FORMAT_NAME = "cummins-radiation-model"
#: Value of the ``cummins_format_version`` attribute.
FORMAT_VERSION = 2
#: Versions this reader takes.
READABLE_VERSIONS = (1, 2)

CONVENTIONS = (
    "cummins radiation model v1: chi' = A chi + B v, mu = C chi + D v (D = 0), "
    "K(s) = C (sI - A)^-1 B ~ B(w) + jw (A(w) - A_inf), time dependence exp(+iwt), SI units; "
    "inputs v = velocities (input), outputs mu = memory forces (output), radiation force "
    "= -A_inf v' - mu; block-diagonal stack of SISO couplings: coupling k owns the states "
    "with state_coupling == k (1-based), a = A[k,k], b = B[k, coupling_radiating-1], "
    "c = C[coupling_influenced-1, k]; DOF indices are 1-based; coupling_<metric>: NaN "
    "(float) or -1 (bool as int8) where absent; blocks (version 2) follow the couplings: "
    "block k owns the states with state_block == k, its DOFs are block_dof == 1"
)

_RESERVED_ATTRS = ("conventions", VERSION_ATTR, "cummins_format", "cummins_format_version")
_COUPLING_FIELDS = ("influenced", "radiating", "order", "method", "note", "metrics_json")
_REQUIRED = (
    "A",
    "B",
    "C",
    "added_mass_inf",
    "state_coupling",
    "coupling_influenced",
    "coupling_radiating",
)
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


# --------------------------------------------------------------------------- writing


def write_radiation_model(model: RadiationModel, path: str | os.PathLike[str]) -> Path:
    """Write ``model`` as NetCDF-4 in the layout of the module docstring.

    The file is written to a temporary name and then renamed, so a failure leaves no
    half-written file. An existing file is replaced: :meth:`RadiationModel.save
    <cummins.radiation.model.RadiationModel.save>` does the overwrite check (``force=``).

    Parameters
    ----------
    model
        The model to write.
    path
        Output file (``.nc``).

    Returns
    -------
    Path
        ``path``.
    """
    return save_netcdf(model_to_dataset(model), path)


def model_to_dataset(model: RadiationModel) -> xr.Dataset:
    """The :class:`xarray.Dataset` that :func:`write_radiation_model` writes."""
    dofs = [str(d) for d in model.dofs]
    couplings = model.couplings
    ds = xr.Dataset(
        coords={
            "input": ("input", dofs),
            "output": ("output", dofs),
            "coupling": ("coupling", np.arange(1, len(couplings) + 1, dtype=np.int32)),
        }
    )
    ds["A"] = (("state", "state2"), model.A, {"long_name": "state matrix", "units": "1/s"})
    ds["B"] = (("state", "input"), model.B, {"long_name": "input matrix (velocity to state)"})
    ds["C"] = (("output", "state"), model.C, {"long_name": "output matrix (state to force)"})
    ds["D"] = (("output", "input"), model.D, {"long_name": "feed-through matrix (zero)"})
    ds["added_mass_inf"] = (
        ("output", "input"),
        np.asarray(model.added_mass_inf, dtype=float),
        {"long_name": "infinite-frequency added mass", "units": "kg, kg*m, kg*m^2"},
    )
    ds["state_coupling"] = (
        ("state",),
        (model.state_coupling + 1).astype(np.int32),
        {"long_name": "coupling number (1-based) owning each state"},
    )
    ds["coupling_influenced"] = (
        ("coupling",),
        np.array([k.influenced + 1 for k in couplings], dtype=np.int32),
        {"long_name": "influenced DOF i (force, output), 1-based"},
    )
    ds["coupling_radiating"] = (
        ("coupling",),
        np.array([k.radiating + 1 for k in couplings], dtype=np.int32),
        {"long_name": "radiating DOF j (velocity, input), 1-based"},
    )
    ds["coupling_order"] = (
        ("coupling",),
        np.array([k.order for k in couplings], dtype=np.int32),
        {"long_name": "number of states"},
    )
    ds["coupling_method"] = (("coupling",), _strings([k.method for k in couplings]))
    ds["coupling_note"] = (("coupling",), _strings([k.note for k in couplings]))
    metric_vars, metrics_json = _metric_variables(couplings)
    for name, var in metric_vars.items():
        ds[name] = var
    ds["coupling_metrics_json"] = (("coupling",), _strings(metrics_json))
    _block_variables(ds, model)
    ds.attrs = _file_attributes(model.attrs)
    ds.attrs["cummins_format_version"] = np.int32(2 if model.blocks else 1)
    return ds


def _block_variables(ds: xr.Dataset, model: RadiationModel) -> None:
    """The block variables of version 2 (and ``state_coupling`` 0 on block states); none
    for a model without blocks (a version-1 file)."""
    if not model.blocks:
        return
    count = len(model.couplings)
    owner = model.state_coupling
    ds["state_coupling"].values = np.where(owner < count, owner + 1, 0).astype(np.int32)
    ds["state_block"] = (
        ("state",),
        np.where(owner >= count, owner - count + 1, 0).astype(np.int32),
        {"long_name": "block number (1-based) owning each state, 0 for couplings"},
    )
    blocks = model.blocks
    ds.coords["block"] = ("block", np.arange(1, len(blocks) + 1, dtype=np.int32))
    member = np.zeros((len(blocks), len(model.dofs)), dtype=np.int8)
    for k, block in enumerate(blocks):
        member[k, list(block.dofs)] = 1
    ds["block_dof"] = (("block", "input"), member, {"long_name": "DOF belongs to the block"})
    ds["block_order"] = (
        ("block",),
        np.array([block.order for block in blocks], dtype=np.int32),
        {"long_name": "number of states"},
    )
    ds["block_method"] = (("block",), _strings([block.method for block in blocks]))
    ds["block_note"] = (("block",), _strings([block.note for block in blocks]))
    ds["block_metrics_json"] = (
        ("block",),
        _strings(
            [
                json.dumps(
                    {
                        f"{i + 1},{j + 1}": {
                            str(name): encode_attribute(value, str(name))
                            for name, value in metrics.items()
                        }
                        for (i, j), metrics in block.metrics.items()
                    }
                )
                for block in blocks
            ]
        ),
    )


def _strings(values: list[str]) -> NDArray:
    return np.array([str(v) for v in values], dtype=object)


def _metric_kind(value: Any) -> str | None:
    """``"bool"``, ``"int"`` or ``"float"`` for a metric that gets a variable, else None."""
    if isinstance(value, bool | np.bool_):
        return "bool"
    if isinstance(value, int | np.integer):
        return "int" if abs(int(value)) < 2**53 else None
    if isinstance(value, float | np.floating):
        return "float" if not math.isnan(value) else None
    return None


def _metric_variables(couplings) -> tuple[dict[str, xr.Variable], list[str]]:
    """One variable per metric, and the per-coupling JSON bookkeeping."""
    found: dict[str, set[str]] = {}
    for k in couplings:
        for name, value in k.metrics.items():
            kind = _metric_kind(value)
            usable = isinstance(name, str) and _NAME.match(name) and name not in _COUPLING_FIELDS
            if kind is not None and usable:
                found.setdefault(name, set()).add(kind)
    # one type per variable: float if any value is a float, else int, else bool; the
    # values of another type go to the JSON bookkeeping
    kinds = {
        name: next(kind for kind in ("float", "int", "bool") if kind in seen)
        for name, seen in found.items()
    }
    columns: dict[str, list[Any]] = {name: [] for name in kinds}
    metrics_json: list[str] = []
    for k in couplings:
        extra = {}
        for name in kinds:
            value = k.metrics.get(name)
            if name not in k.metrics or _metric_kind(value) != kinds[name]:
                columns[name].append(None)
                if name in k.metrics:
                    extra[name] = encode_attribute(value, name)
            else:
                columns[name].append(value)
        for name, value in k.metrics.items():
            if name not in kinds:
                extra[str(name)] = encode_attribute(value, str(name))
        order = [str(name) for name in k.metrics]
        metrics_json.append(json.dumps({"order": order, "extra": extra}))
    out: dict[str, xr.Variable] = {}
    for name, kind in kinds.items():
        attrs = {"cummins_metric": name, "cummins_metric_type": kind}
        if kind == "bool":
            data = np.array([-1 if v is None else int(bool(v)) for v in columns[name]], np.int8)
            attrs.update(
                flag_values=np.array([-1, 0, 1], np.int8), flag_meanings="absent false true"
            )
        else:
            data = np.array([np.nan if v is None else float(v) for v in columns[name]])
        out[f"coupling_{name}"] = xr.Variable(("coupling",), data, attrs)
    return out, metrics_json


def _file_attributes(model_attrs) -> dict[str, Any]:
    """Global attributes: the format's own, then the model's (reserved names as JSON)."""
    attrs = dict(model_attrs)
    reserved = {key: attrs.pop(key) for key in (*_RESERVED_ATTRS, JSON_ATTRS) if key in attrs}
    out = encode_attributes(attrs)
    if reserved:
        special = json.loads(out.get(JSON_ATTRS, "{}"))
        special.update({key: encode_attribute(value, key) for key, value in reserved.items()})
        out[JSON_ATTRS] = json.dumps(special)
    return {
        "cummins_format": FORMAT_NAME,
        "cummins_format_version": np.int32(FORMAT_VERSION),
        VERSION_ATTR: __version__,
        "conventions": CONVENTIONS,
        **out,
    }


# --------------------------------------------------------------------------- reading


def read_radiation_model(path: str | os.PathLike[str]) -> RadiationModel:
    """Read a model file in the layout of the module docstring.

    Parameters
    ----------
    path
        A ``.nc`` file written by :func:`write_radiation_model` (or by another tool
        following the module docstring).

    Returns
    -------
    RadiationModel

    Raises
    ------
    HydroDataError
        The file is missing, not NetCDF, or not a consistent radiation-model file
        (the message names what is missing or wrong), or holds numbers no model of a
        floating body has (NaN, infinity, an absurd A∞: ``guard_radiation_model``).
    """
    path = Path(path)
    raw = load_netcdf(path)
    model = dataset_to_model(raw, path)
    try:
        guard_radiation_model(model)
    except FitError as exc:
        raise HydroDataError(str(exc), path=path) from None
    return model


def dataset_to_model(raw: xr.Dataset, path: str | os.PathLike[str] | None = None):
    """Inverse of :func:`model_to_dataset`; ``path`` is used in error messages."""
    missing = [name for name in _REQUIRED if name not in raw.variables]
    if missing:
        raise HydroDataError(
            f"not a cummins radiation-model file: missing variable(s) {', '.join(missing)}",
            path=path,
            hint="write the model with RadiationModel.save or follow the layout of "
            "cummins.radiation.model_file",
        )
    dofs = _dof_labels(raw, path)
    n = len(dofs)
    a = _matrix(raw, "A", ("state", "state2"), path)
    b = _matrix(raw, "B", ("state", "input"), path)
    c = _matrix(raw, "C", ("output", "state"), path)
    added = _matrix(raw, "added_mass_inf", ("output", "input"), path)
    total = a.shape[0]
    if a.shape != (total, total) or b.shape != (total, n) or c.shape != (n, total):
        raise HydroDataError(
            f"inconsistent sizes: A {a.shape}, B {b.shape}, C {c.shape} for {n} DOFs",
            path=path,
        )
    if "D" in raw.variables:
        d = _matrix(raw, "D", ("output", "input"), path)
        if np.any(d != 0):
            raise HydroDataError(
                "D is not zero: cummins models have no feed-through",
                path=path,
                hint="add D to A∞ as a constant force term instead",
            )
    version = raw.attrs.get("cummins_format_version", 1)
    if int(version) not in READABLE_VERSIONS:
        raise HydroDataError(
            f"cummins_format_version {version} is newer than this cummins reads "
            f"({max(READABLE_VERSIONS)})",
            path=path,
            hint="update cummins",
        )
    couplings = _couplings(raw, a, b, c, n, path)
    blocks = _blocks(raw, a, b, c, n, path)
    try:
        model = RadiationModel(tuple(dofs), couplings, added, _model_attributes(raw, path), blocks)
    except CumminsError as exc:
        raise HydroDataError(str(exc), path=path) from None
    _check_assembly(model, a, b, c, path)
    return model


def _blocks(raw: xr.Dataset, a, b, c, n: int, path) -> tuple[MemoryBlock, ...]:
    """The blocks of a version-2 file (none in a version-1 file)."""
    count = raw.sizes.get("block", 0)
    if not count:
        return ()
    for name in ("state_block", "block_dof"):
        if name not in raw.variables:
            raise HydroDataError(f"missing variable {name} (the file has blocks)", path=path)
    owner = _integers(raw["state_block"].values, path)
    member = raw["block_dof"].transpose("block", "input").values
    methods = raw["block_method"].values if "block_method" in raw else [""] * count
    notes = raw["block_note"].values if "block_note" in raw else [""] * count
    texts = raw["block_metrics_json"].values if "block_metrics_json" in raw else [""] * count
    out = []
    for k in range(count):
        states = np.flatnonzero(owner == k + 1)
        dofs = tuple(int(d) for d in np.flatnonzero(member[k]))
        if not dofs:
            raise HydroDataError(f"block {k + 1} has no DOFs (block_dof)", path=path)
        if states.size and np.any(np.diff(states) != 1):
            raise HydroDataError(f"block {k + 1}: its states are not contiguous", path=path)
        metrics = {}
        if str(texts[k]):
            try:
                info = json.loads(str(texts[k]))
                for key, values in info.items():
                    i, j = (int(x) - 1 for x in key.split(","))
                    metrics[(i, j)] = {
                        name: decode_attribute(item) for name, item in values.items()
                    }
            except (ValueError, KeyError, TypeError, AttributeError) as exc:
                raise HydroDataError(
                    f"block {k + 1}: unreadable block_metrics_json ({exc})",
                    path=path,
                    hint="the file was edited or damaged",
                ) from None
        out.append(
            MemoryBlock(
                dofs,
                a[np.ix_(states, states)],
                b[np.ix_(states, list(dofs))],
                c[np.ix_(list(dofs), states)],
                str(methods[k]),
                metrics,
                str(notes[k]),
            )
        )
    return tuple(out)


def _dof_labels(raw: xr.Dataset, path) -> list[str]:
    for name in ("input", "output"):
        if name not in raw.coords:
            raise HydroDataError(f"the coordinate {name!r} (DOF labels) is missing", path=path)
    inputs = [str(v) for v in raw["input"].values]
    outputs = [str(v) for v in raw["output"].values]
    if inputs != outputs:
        raise HydroDataError(
            f"input DOFs {inputs} differ from output DOFs {outputs}",
            path=path,
            hint="a radiation model maps the velocities of all DOFs to forces on the same DOFs",
        )
    return inputs


def _matrix(raw: xr.Dataset, name: str, dims: tuple[str, str], path) -> NDArray:
    var = raw[name]
    if set(var.dims) != set(dims) or var.ndim != 2:
        raise HydroDataError(
            f"variable {name} has dimensions {var.dims}, expected {dims}", path=path
        )
    values = np.asarray(var.transpose(*dims).values, dtype=float)
    if not np.all(np.isfinite(values)) and name != "added_mass_inf":
        raise HydroDataError(f"variable {name} holds NaN or Inf", path=path)
    return values


def _coupling_column(raw: xr.Dataset, name: str, count: int, path, default=None) -> NDArray:
    if name not in raw.variables:
        if default is None:
            raise HydroDataError(f"missing variable {name}", path=path)
        return np.array([default] * count, dtype=object)
    var = raw[name]
    if var.dims != ("coupling",):
        raise HydroDataError(f"variable {name} must have the dimension (coupling,)", path=path)
    return var.values


def _couplings(raw: xr.Dataset, a, b, c, n: int, path) -> tuple[CouplingModel, ...]:
    count = raw.sizes.get("coupling", 0)
    influenced = _integers(_coupling_column(raw, "coupling_influenced", count, path), path)
    radiating = _integers(_coupling_column(raw, "coupling_radiating", count, path), path)
    owner = raw["state_coupling"]
    if owner.dims != ("state",):
        raise HydroDataError("variable state_coupling must have the dimension (state,)", path=path)
    owner = _integers(owner.values, path)
    numbers = (
        _integers(raw["coupling"].values, path)
        if "coupling" in raw.coords
        else np.arange(1, count + 1)
    )
    for label, values in (("coupling_influenced", influenced), ("coupling_radiating", radiating)):
        bad = values[(values < 1) | (values > n)]
        if bad.size:
            raise HydroDataError(
                f"{label} holds {int(bad[0])}, outside the DOFs 1…{n} (indices are 1-based)",
                path=path,
            )
    unowned = np.setdiff1d(owner[owner > 0], numbers)
    if unowned.size:
        raise HydroDataError(
            f"state_coupling refers to coupling {int(unowned[0])}, which does not exist",
            path=path,
        )
    methods = _coupling_column(raw, "coupling_method", count, path, default="")
    notes = _coupling_column(raw, "coupling_note", count, path, default="")
    metrics = _metrics(raw, count, path)
    orders = (
        _integers(raw["coupling_order"].values, path) if "coupling_order" in raw.variables else None
    )
    out = []
    for k in range(count):
        states = np.flatnonzero(owner == numbers[k])
        where = f"coupling {k + 1} ({int(influenced[k])}, {int(radiating[k])})"
        if orders is not None and states.size != orders[k]:
            raise HydroDataError(
                f"{where}: coupling_order is {int(orders[k])} but state_coupling gives it "
                f"{states.size} states",
                path=path,
            )
        if states.size and np.any(np.diff(states) != 1):
            raise HydroDataError(f"{where}: its states are not contiguous", path=path)
        i, j = int(influenced[k]) - 1, int(radiating[k]) - 1
        out.append(
            CouplingModel(
                i,
                j,
                a[np.ix_(states, states)],
                b[states, j],
                c[i, states],
                str(methods[k]),
                metrics[k],
                str(notes[k]),
            )
        )
    if not np.array_equal(owner[owner > 0], np.repeat(numbers, [k.order for k in out])):
        raise HydroDataError(
            "the states are not stacked in the order of the coupling dimension",
            path=path,
            hint="state_coupling must be non-decreasing along the coupling coordinate",
        )
    return tuple(out)


def _integers(values, path) -> NDArray[np.int64]:
    values = np.asarray(values)
    if values.dtype.kind not in "iuf" or (
        values.dtype.kind == "f" and not np.all(np.isfinite(values) & (values == np.round(values)))
    ):
        raise HydroDataError(f"expected integer indices, found {values[:5]!r}", path=path)
    return values.astype(np.int64)


def _metrics(raw: xr.Dataset, count: int, path) -> list[dict[str, Any]]:
    """Per-coupling metric dictionaries from the ``coupling_<metric>`` variables."""
    columns: dict[str, tuple[str, NDArray]] = {}
    for name, var in raw.data_vars.items():
        if not name.startswith("coupling_") or var.dims != ("coupling",):
            continue
        if name[len("coupling_") :] in _COUPLING_FIELDS:
            continue
        metric = str(var.attrs.get("cummins_metric", name[len("coupling_") :]))
        default = "str" if var.dtype.kind in "OSU" else "float"
        kind = str(var.attrs.get("cummins_metric_type", default))
        if kind not in ("bool", "int", "float", "str") or (kind == "str") != (default == "str"):
            raise HydroDataError(
                f"variable {name}: unknown cummins_metric_type {kind!r}", path=path
            )
        columns[metric] = (kind, var.values)
    bookkeeping = _coupling_column(raw, "coupling_metrics_json", count, path, default="")
    out = []
    for k in range(count):
        values: dict[str, Any] = {}
        for metric, (kind, column) in columns.items():
            value = column[k]
            if kind == "str":
                if str(value):
                    values[metric] = str(value)
            elif kind == "bool":
                if int(value) >= 0:
                    values[metric] = bool(value)
            elif not np.isnan(value):
                values[metric] = int(value) if kind == "int" else float(value)
        out.append(_extra_metrics(str(bookkeeping[k]), values, k, path))
    return out


def _extra_metrics(text: str, values: dict[str, Any], k: int, path) -> dict[str, Any]:
    """Apply the ``coupling_metrics_json`` bookkeeping: extra metrics and their order."""
    if not text:
        return values
    try:
        info = json.loads(text)
        extra = {name: decode_attribute(item) for name, item in info.get("extra", {}).items()}
        order = [str(name) for name in info.get("order", [])]
    except (ValueError, KeyError, TypeError, AttributeError) as exc:
        raise HydroDataError(
            f"coupling {k + 1}: unreadable coupling_metrics_json ({exc})",
            path=path,
            hint="the file was edited or damaged",
        ) from None
    merged = {**values, **extra}
    ordered = {name: merged[name] for name in order if name in merged}
    ordered.update({name: value for name, value in merged.items() if name not in ordered})
    return ordered


def _model_attributes(raw: xr.Dataset, path) -> dict[str, Any]:
    native = {k: v for k, v in raw.attrs.items() if k not in _RESERVED_ATTRS}
    return decode_attributes(native, where=path)


def _check_assembly(model: RadiationModel, a, b, c, path) -> None:
    """A, B, C must be exactly the block-diagonal stack of the couplings read."""
    for name, expected, found in (("A", model.A, a), ("B", model.B, b), ("C", model.C, c)):
        if not np.array_equal(expected, found):
            rows, cols = np.nonzero(expected != found)
            raise HydroDataError(
                f"{name}[{rows[0] + 1}, {cols[0] + 1}] = {found[rows[0], cols[0]]:g} lies "
                "outside the blocks of the couplings and blocks (state_coupling, "
                "coupling_influenced, coupling_radiating, state_block, block_dof)",
                path=path,
                hint="A must be block-diagonal, B and C nonzero only in each coupling's "
                "column j and row i",
            )


register_file_format(read_radiation_model, write_radiation_model)
