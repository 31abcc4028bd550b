"""Marine Systems Simulator (MSS) fluid-memory models: the ``vesselABC`` struct.

MSS (Fossen, cybergalactic/MSS on GitHub) fits the fluid memory of a ``vessel`` struct
with ``vessel2ss.m`` (using the FDI toolbox, ``FDIRadMod``) and saves the struct
``vesselABC`` to ``<name>ABC.mat``, which its Simulink templates load. Its fields, as in
MSS's ``tankerABC.mat``, ``supplyABC.mat`` and ``s175ABC.mat``:

==============================  ==========================================================
``Ar``, ``Br``, ``Cr``, ``Dr``  6×6 cell arrays: ``{i, j}`` holds the SISO model
                                K_ij(s) = Cr (sI − Ar)⁻¹ Br + Dr from the velocity of DOF
                                j to the memory force on DOF i (``vessel2ss`` identifies
                                ``vessel.A(i, j, :)``, ``vessel.B(i, j, :)``, force i due
                                to motion j), ``Ar`` n×n, ``Br`` n×1, ``Cr`` 1×n (from
                                MATLAB's ``tf2ss``), ``Dr`` = 0
``MRB``                         6×6 rigid-body mass matrix (kg, kg·m, kg·m²)
``MA``                          6×6 added mass used with the models: A(∞) from WAMIT;
                                for VERES data the A∞ estimated by the FDI fit for the
                                fitted couplings (upper triangle), A at the highest
                                frequency elsewhere — so it need not be symmetric
``G``                           6×6 restoring matrix (N/m, N, N·m/rad …)
``Minv``                        inv(MRB + MA)
``r_g``                         1×3 vector from the origin CO to the centre of gravity (m)
==============================  ==========================================================

Zero-speed models of the couplings a port–starboard symmetric ship has: (1,1), (1,3),
(1,5), (2,2), (2,4), (2,6), (3,3), (3,5), (4,4), (4,6), (5,5), (6,6), the transposed
cells being copies. A coupling without data holds the scalar 0 in all four cells; cells
of other couplings are empty (``[]``).

Conventions: Fossen's body axes (x forward, y to starboard, z down: cummins'
``"z-down"``), SI units, time dependence Re{X e^{iωt}}, K(jω) = B(ω) + jω(A(ω) − MA)
(checked against the ``vessel`` structs in the tests). The Simulink models add the
memory force as −μ, with μ the output of these models, as cummins does.

:func:`read_mss_abc` returns a :class:`~cummins.radiation.model.RadiationModel` with method
``"mss"``, ``added_mass_inf`` = ``MA``, and attributes ``axis_convention="z-down"``,
``inertia_matrix`` (``MRB``), ``hydrostatic_stiffness`` (``G``) and ``mss_r_g``
(``r_g``); cells holding zeros or nothing give no coupling.

:func:`write_mss_abc` writes such a struct, always in z-down axes (a z-up model is
converted exactly: ``c`` of coupling (i, j) times T_i T_j, A∞, ``MRB`` and ``G`` as
T M T, positions as (x, −y, −z), with T = diag(1, −1, −1, 1, −1, −1)). It lays out the
cells as MSS does (zeros for the symmetric-ship couplings the model lacks, ``[]`` for
the others) and adds a field ``vesselABC.cummins`` (ignored by MSS) holding the DOF
labels, each coupling's method, metrics and note and the model's attributes as JSON,
so that :func:`read_mss_abc` gives the written model back exactly.
"""

from __future__ import annotations

import json
import os
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import scipy.io
from numpy.typing import ArrayLike, NDArray

from cummins._version import __version__
from cummins.errors import HydroDataError, HydroDataWarning, check_writable
from cummins.files import replacing
from cummins.hydrodb import DOF_NAMES
from cummins.io._model_common import resolve_axis_convention
from cummins.io.mss import load_mat_struct
from cummins.io.mss.points import _rigid_body_cg
from cummins.io.netcdf import decode_attribute, encode_attribute
from cummins.radiation.model import CouplingModel, RadiationModel, change_model_axes

__all__ = ["MSS_COUPLINGS", "read_mss_abc", "write_mss_abc"]

#: The couplings (0-based i, j) ``vessel2ss`` always fills, with a model or with zeros.
MSS_COUPLINGS: frozenset[tuple[int, int]] = frozenset(
    pair
    for i, j in ((0, 0), (0, 2), (0, 4), (1, 1), (1, 3), (1, 5), (2, 2), (2, 4), (3, 3),
                 (3, 5), (4, 4), (5, 5))
    for pair in ((i, j), (j, i))
)  # fmt: skip
_CELLS = ("Ar", "Br", "Cr", "Dr")
_JSON_FORMAT = "cummins-radiation-model-json 1"


# --------------------------------------------------------------------------- writing


def write_mss_abc(
    model: RadiationModel,
    path: str | os.PathLike[str],
    *,
    inertia_matrix: ArrayLike | None = None,
    hydrostatic_stiffness: ArrayLike | None = None,
    center_of_gravity: ArrayLike | None = None,
    axis_convention: str | None = None,
    force: bool = False,
) -> Path:
    """Write ``model`` as an MSS ``vesselABC`` struct (MATLAB v5 ``.mat``).

    What is written (see the module docstring): the couplings in the ``Ar``, ``Br``,
    ``Cr``, ``Dr`` cells, ``MA`` = A∞, ``MRB``, ``G``, ``Minv`` = inv(MRB + MA) and
    ``r_g``, all in Fossen's z-down axes about the model's reference point (MSS takes
    CO: Lpp/2, centre line, waterline). ``r_g`` is G − reference point, from the centre
    of gravity given or recorded, else from the m·r_g block of ``MRB`` (MRB about CO,
    Fossen (2021) ch. 3). Values that are not known are written as NaN (``MRB``,
    ``G``, ``Minv``, ``r_g``), so that a simulation using them fails visibly, and a
    :class:`~cummins.errors.HydroDataWarning` names them.

    Parameters
    ----------
    model
        A single-body model (six DOFs).
    path
        Output ``.mat`` file (MSS names it ``<vessel name>ABC.mat``).
    inertia_matrix, hydrostatic_stiffness
        6×6 MRB and G in the model's axes; default: the model's attributes of these
        names, else NaN.
    center_of_gravity
        Position of G in the model's axes, from the same origin as the model's
        ``reference_point`` attribute (r_g = G − reference point); default: the
        ``center_of_gravity`` attribute, else the ``mss_r_g`` attribute (files read
        from MSS), else the m·r_g block of ``MRB``, else NaN. Values given here are
        also recorded, under these names, in the attributes of the written model
        (``vesselABC.cummins``).
    axis_convention
        The model's axes when it does not record them (``axis_convention`` attribute);
        a ``"z-up"`` model is converted.
    force
        Overwrite an existing file.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    check_writable(path, force)
    if len(model.dofs) != 6:
        raise HydroDataError(
            f"the model has {len(model.dofs)} DOFs; MSS vesselABC holds one body (6 DOFs)",
            path=path,
        )
    current = resolve_axis_convention(model, axis_convention, path=path)
    attrs = dict(model.attrs)
    given = {
        "inertia_matrix": inertia_matrix,
        "hydrostatic_stiffness": hydrostatic_stiffness,
        "center_of_gravity": center_of_gravity,
    }
    for key, value in given.items():
        if value is not None:
            attrs[key] = np.asarray(value, dtype=float)
    # one SISO model per coupling: a common-pole block is written pair by pair
    model = RadiationModel(model.dofs, model.as_couplings().couplings, model.added_mass_inf, attrs)
    z_down = change_model_axes(model, "z-down", current=current)
    struct = _vessel_abc(z_down, path)
    try:
        with replacing(path) as tmp:
            scipy.io.savemat(str(tmp), {"vesselABC": struct}, do_compression=True, oned_as="row")
    except OSError as exc:
        raise HydroDataError(f"cannot write the file ({exc})", path=path) from None
    return path


def _vessel_abc(model: RadiationModel, path: Path) -> dict[str, Any]:
    cells = {name: np.empty((6, 6), dtype=object) for name in _CELLS}
    for i in range(6):
        for j in range(6):
            k = model.coupling(i, j)
            if k is not None:
                values = (
                    np.asarray(k.a, dtype=float).reshape(k.order, k.order),
                    np.asarray(k.b, dtype=float).reshape(-1, 1),
                    np.asarray(k.c, dtype=float).reshape(1, -1),
                    np.zeros((1, 1)),
                )
            elif (i, j) in MSS_COUPLINGS:
                values = tuple(np.zeros((1, 1)) for _ in _CELLS)
            else:
                values = tuple(np.zeros((0, 0)) for _ in _CELLS)
            for name, value in zip(_CELLS, values, strict=True):
                cells[name][i, j] = value
    attrs = model.attrs
    mrb = _matrix_attr(attrs, "inertia_matrix", path)
    g = _matrix_attr(attrs, "hydrostatic_stiffness", path)
    ma = np.asarray(model.added_mass_inf, dtype=float)
    total = mrb + ma
    minv = np.linalg.inv(total) if np.all(np.isfinite(total)) else np.full((6, 6), np.nan)
    r_g = _r_g(attrs, mrb, path)
    unknown = [
        name
        for name, value in (("MRB", mrb), ("G", g), ("r_g", r_g))
        if not np.all(np.isfinite(value))
    ]
    if unknown:
        warnings.warn(
            f"{path.name}: vesselABC.{', '.join(unknown)} unknown, written as NaN "
            "(give the mass properties: inertia matrix, restoring, centre of gravity)",
            HydroDataWarning,
            stacklevel=4,
        )
    return {
        **cells,
        "MRB": mrb,
        "MA": ma,
        "G": g,
        "Minv": minv,
        "r_g": r_g.reshape(1, 3),
        "cummins": {
            "format": _JSON_FORMAT,
            "cummins_version": __version__,
            "axes": "z-down (x forward, y to starboard, z down)",
            "model_json": json.dumps(_model_json(model)),
        },
    }


def _matrix_attr(attrs, key: str, path: Path) -> NDArray[np.float64]:
    if key not in attrs or attrs[key] is None:
        return np.full((6, 6), np.nan)
    value = np.asarray(attrs[key], dtype=float)
    if value.shape != (6, 6):
        raise HydroDataError(f"{key} must be 6×6, got shape {value.shape}", path=path)
    return value


def _r_g(attrs, mrb: NDArray, path: Path) -> NDArray[np.float64]:
    """r_g: the centre of gravity given or recorded, else MRB's m·r_g block, else NaN."""
    if attrs.get("center_of_gravity") is not None:
        cg = np.asarray(attrs["center_of_gravity"], dtype=float).reshape(-1)
        point = np.asarray(attrs.get("reference_point", np.zeros(3)), dtype=float).reshape(-1)
        if cg.size != 3 or point.size != 3:
            raise HydroDataError(
                "center_of_gravity and reference_point must be 3-vectors (one body)", path=path
            )
        return cg - point
    if attrs.get("mss_r_g") is not None:
        return np.asarray(attrs["mss_r_g"], dtype=float).reshape(3)
    if np.all(np.isfinite(mrb)):
        r_g = _rigid_body_cg(mrb)
        if r_g is not None:
            return np.asarray(r_g, dtype=float)
    return np.full(3, np.nan)


def _model_json(model: RadiationModel) -> dict[str, Any]:
    return {
        "dofs": list(model.dofs),
        "couplings": [
            {
                "i": k.influenced,
                "j": k.radiating,
                "method": k.method,
                "note": k.note,
                "metrics": {str(n): encode_attribute(v, str(n)) for n, v in k.metrics.items()},
            }
            for k in model.couplings
        ],
        "attrs": {str(n): encode_attribute(v, str(n)) for n, v in model.attrs.items()},
    }


# --------------------------------------------------------------------------- reading


def read_mss_abc(path: str | os.PathLike[str]) -> RadiationModel:
    """Read an MSS ``vesselABC`` struct (``<name>ABC.mat``) into a ``RadiationModel``.

    Parameters
    ----------
    path
        The ``.mat`` file written by MSS's ``vessel2ss`` or by :func:`write_mss_abc`.

    Returns
    -------
    RadiationModel
        In z-down axes; for MSS's files, method ``"mss"`` and ``added_mass_inf`` =
        ``MA``; for files written by cummins, the written model exactly.

    Raises
    ------
    HydroDataError
        Missing or unreadable file, no ``vesselABC`` struct, missing fields, cells of
        inconsistent sizes, or a nonzero ``Dr``.
    """
    path = Path(path)
    struct = load_mat_struct(
        path,
        "vesselABC",
        "MSS writes the fluid-memory models to <name>ABC.mat with vessel2ss; "
        "a 'vessel' struct holds hydrodynamic data (cummins.read)",
    )
    cells = {name: _cell_array(struct, name, path) for name in _CELLS}
    added = _field_matrix(struct, "MA", path, required=True)
    stored = _stored_model(struct, path)
    found: dict[tuple[int, int], tuple[NDArray, NDArray, NDArray]] = {}
    for i in range(6):
        for j in range(6):
            block = _cell_model(cells, i, j, path)
            if block is not None:
                found[(i, j)] = block
    if stored is None:
        couplings = tuple(
            CouplingModel(i, j, a, b, c, method="mss") for (i, j), (a, b, c) in found.items()
        )
        return RadiationModel(DOF_NAMES, couplings, added, _mss_attributes(struct, path))
    dofs, entries, attrs = stored
    couplings = []
    for entry in entries:
        key = (entry["i"], entry["j"])
        if key not in found:
            raise HydroDataError(
                f"vesselABC.cummins lists coupling ({key[0] + 1}, {key[1] + 1}) but its cells "
                "are empty",
                path=path,
                hint="the file was edited; delete the cummins field to read the cells alone",
            )
        a, b, c = found.pop(key)
        couplings.append(
            CouplingModel(*key, a, b, c, entry["method"], entry["metrics"], entry["note"])
        )
    if found:
        i, j = next(iter(found))
        raise HydroDataError(
            f"cell ({i + 1}, {j + 1}) holds a model that vesselABC.cummins does not list",
            path=path,
            hint="the file was edited; delete the cummins field to read the cells alone",
        )
    return RadiationModel(dofs, tuple(couplings), added, attrs)


def _has(struct: np.void, name: str) -> bool:
    return name in (struct.dtype.names or ())


def _cell_array(struct: np.void, name: str, path: Path) -> NDArray:
    if not _has(struct, name):
        raise HydroDataError(f"vesselABC has no field {name!r}", path=path)
    cells = struct[name]
    if cells.dtype != object or cells.shape != (6, 6):
        raise HydroDataError(
            f"vesselABC.{name} must be a 6×6 cell array, got {cells.dtype} {cells.shape}",
            path=path,
        )
    return cells


def _cell_model(cells, i: int, j: int, path: Path):
    """(a, b, c) of cell (i, j), or None when it is empty or all zero."""
    where = f"cell ({i + 1}, {j + 1})"
    a, b, c, d = (_as_float(cells[name][i, j], f"{where} of {name}", path) for name in _CELLS)
    if d.size and np.any(d != 0):
        raise HydroDataError(
            f"{where}: Dr = {d.reshape(-1)[0]:g} is not zero",
            path=path,
            hint="cummins models have no feed-through; add it to MA",
        )
    if a.size == 0 and b.size == 0 and c.size == 0:
        return None
    n = a.shape[0] if a.ndim == 2 else -1
    if a.shape != (n, n) or b.size != n or c.size != n:
        raise HydroDataError(
            f"{where}: Ar {a.shape}, Br {b.shape}, Cr {c.shape} do not form a state-space model",
            path=path,
        )
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b)) and np.all(np.isfinite(c))):
        raise HydroDataError(f"{where}: NaN or Inf in Ar, Br or Cr", path=path)
    if not np.any(b) or not np.any(c):
        return None  # vessel2ss's placeholder for a coupling without data: K = 0
    return a, b.reshape(-1), c.reshape(-1)


def _as_float(value, where: str, path: Path) -> NDArray[np.float64]:
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise HydroDataError(f"{where}: expected a numeric matrix", path=path) from None


def _field_matrix(struct: np.void, name: str, path: Path, *, required: bool = False):
    if not _has(struct, name):
        if required:
            raise HydroDataError(f"vesselABC has no field {name!r}", path=path)
        return None
    value = _as_float(struct[name], f"vesselABC.{name}", path)
    if value.shape != (6, 6):
        raise HydroDataError(f"vesselABC.{name} must be 6×6, got {value.shape}", path=path)
    return value


def _mss_attributes(struct: np.void, path: Path) -> dict[str, Any]:
    attrs: dict[str, Any] = {
        "axis_convention": "z-down",
        "source_format": "mss-abc",
        "source_file": str(path),
    }
    for field, key in (("MRB", "inertia_matrix"), ("G", "hydrostatic_stiffness")):
        value = _field_matrix(struct, field, path)
        if value is not None and np.all(np.isfinite(value)):
            attrs[key] = value
    if _has(struct, "r_g"):
        r_g = _as_float(struct["r_g"], "vesselABC.r_g", path).reshape(-1)
        if r_g.size == 3 and np.all(np.isfinite(r_g)):
            attrs["mss_r_g"] = r_g
    attrs["history"] = (
        f"read from the MSS vesselABC struct {path.name}: fluid-memory models of "
        "vessel2ss (FDI toolbox), MA taken as added_mass_inf"
    )
    return attrs


def _stored_model(struct: np.void, path: Path):
    """(dofs, coupling entries, attrs) from ``vesselABC.cummins``, or None."""
    if not _has(struct, "cummins"):
        return None
    try:
        info = struct["cummins"].reshape(-1)[0]
        if str(np.asarray(info["format"]).reshape(-1)[0]) != _JSON_FORMAT:
            return None
        data = json.loads(str(np.asarray(info["model_json"]).reshape(-1)[0]))
        dofs = tuple(str(d) for d in data["dofs"])
        entries = [
            {
                "i": int(e["i"]),
                "j": int(e["j"]),
                "method": str(e["method"]),
                "note": str(e["note"]),
                "metrics": {n: decode_attribute(v) for n, v in e["metrics"].items()},
            }
            for e in data["couplings"]
        ]
        attrs = {n: decode_attribute(v) for n, v in data["attrs"].items()}
    except (ValueError, KeyError, TypeError, IndexError, AttributeError) as exc:
        raise HydroDataError(
            f"unreadable vesselABC.cummins field ({type(exc).__name__}: {exc})",
            path=path,
            hint="the file was edited or damaged; delete the cummins field to read the cells alone",
        ) from None
    if len(dofs) != 6:
        raise HydroDataError("vesselABC.cummins does not list 6 DOFs", path=path)
    return dofs, entries, attrs
