"""The terms of the equation of motion a study file gives: what ``cummins simulate`` and
``cummins convert`` take as options (``--rho``, ``--g``, ``--ulen``, ``--water-depth``, ``--mass``,
``--center-of-gravity``, ``--radii-of-gyration``, ``--inertia-matrix``,
``--restoring-includes-weight``, ``--external-stiffness``, ``--external-damping``), as
study keys of the same meaning, applied by the same functions
(:func:`cummins.io.read`'s ``rho``/``g``/``ulen``/``water_depth``,
:func:`cummins.mass_properties.with_inertia`,
:func:`cummins.mass_properties.complete_restoring`,
:func:`cummins.mass_properties.with_external_terms`) to the data before any case is
built; and the check that the data then hold what the analysis needs (the inertia, the
restoring), made before any Dask work starts.

Examples
--------
A study of the OC3 spar, whose WAMIT files hold no inertia: its mass ρ∇ (no ``mass``:
freely floating), centre of gravity and radii of gyration, and the moorings' linearised
stiffness in surge and sway::

    data: spar.1
    center_of_gravity: [0, 0, -78]
    radii_of_gyration: [23.8, 23.8, 4.69]
    external_stiffness: [[Surge, Surge, 41180], [Sway, Sway, 41180]]
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import ArgumentError, HydroDataError
from cummins.mass_properties import check_inertia_terms

#: The study keys of the equation of motion: key → its meaning (the CLI option of the
#: same name says the same).
KEYS: dict[str, str] = {
    "rho": "kg/m^3: water density of nondimensional formats (--rho; default 1025)",
    "g": "m/s^2: acceleration of gravity of nondimensional formats (--g; default 9.81)",
    "ulen": "m: WAMIT's length scale ULEN (--ulen; default from the .out, else 1)",
    "water_depth": "m (.inf: deep water) where the files record none (--water-depth; "
    "default deep water, with a warning where a result depends on it)",
    "mass": "kg, one per body (--mass; with radii_of_gyration; default rho x volume)",
    "center_of_gravity": "[x, y, z] m, one per body, the data's axes (--center-of-gravity)",
    "radii_of_gyration": "[rxx, ryy, rzz] m about the centre of gravity, one per body "
    "(--radii-of-gyration)",
    "inertia_matrix": "a file of the n x n inertia matrix about the reference point, "
    "relative to the study file (--inertia-matrix)",
    "restoring_includes_weight": "yes | no: whether the files' restoring holds the "
    "weight's terms (--restoring-includes-weight)",
    "external_stiffness": "[[DOF, DOF, value], ..] added to the restoring: moorings, a PTO "
    "spring (--external-stiffness; N/m, N m/rad)",
    "external_damping": "[[DOF, DOF, value], ..] linear damping: a PTO, dampers "
    "(--external-damping; kg/s, kg m^2/s)",
}
#: What each analysis needs in the data, and the keys that give it.
NEEDED: dict[str, tuple[str, str]] = {
    "inertia_matrix": (
        "the rigid-body inertia",
        "mass, center_of_gravity and radii_of_gyration (or inertia_matrix)",
    ),
    "hydrostatic_stiffness": (
        "the hydrostatic restoring",
        "external_stiffness (then the whole restoring), or put the solver's restoring file "
        "(WAMIT .hst, NEMOH KH.dat) beside the data",
    ),
}


def _where(source: Path | None, key: str) -> str:
    return f"{source}: {key}" if source else key


def _positive(value: Any, key: str, source: Path | None) -> float:
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise ArgumentError(f"{_where(source, key)}: {value!r} is not a number") from None
    if isinstance(value, bool) or not np.isfinite(out) or not out > 0:
        raise ArgumentError(f"{_where(source, key)}: {value!r} is not a positive number")
    return out


def _per_body(value: Any, width: int | None, key: str, source: Path | None) -> tuple:
    """One value (``width`` None) or one vector of ``width`` per body, as a tuple of
    floats or of tuples; the numbers' own checks are :func:`with_inertia`'s."""
    if value is None:
        return ()
    items = value if isinstance(value, Sequence) and not isinstance(value, str) else [value]
    if width is not None and items and not isinstance(items[0], Sequence | np.ndarray):
        items = [items]  # one body: [x, y, z]
    out = []
    for item in items:
        try:
            if width is None:
                out.append(float(item))
                continue
            vector = tuple(float(v) for v in item)
        except (TypeError, ValueError):
            raise ArgumentError(f"{_where(source, key)}: {item!r} is not a number") from None
        if len(vector) != width:
            raise ArgumentError(
                f"{_where(source, key)}: {list(vector)} is not {width} numbers (one list per body)"
            )
        out.append(vector)
    return tuple(out)


def _triples(value: Any, key: str, source: Path | None) -> tuple[tuple[str, str, float], ...]:
    """``[[DOF, DOF, value], ..]`` as the CLI's ``--external-stiffness DOF DOF VALUE``:
    each pair once."""
    if value is None:
        return ()
    if not isinstance(value, Sequence) or isinstance(value, str):
        raise ArgumentError(f"{_where(source, key)}: expected a list of [DOF, DOF, value]")
    out: list[tuple[str, str, float]] = []
    for item in value:
        if (
            not isinstance(item, Sequence)
            or isinstance(item, str)
            or len(item) != 3
            or isinstance(item[2], bool)
        ):
            raise ArgumentError(f"{_where(source, key)}: {item!r} is not [DOF, DOF, value]")
        try:
            number = float(item[2])
        except (TypeError, ValueError):
            raise ArgumentError(f"{_where(source, key)}: {item[2]!r} is not a number") from None
        if not np.isfinite(number):
            raise ArgumentError(f"{_where(source, key)}: {item[2]!r} is not a finite number")
        pair = (str(item[0]), str(item[1]))
        if any(p[:2] == pair for p in out):
            raise ArgumentError(f"{_where(source, key)}: the pair {' '.join(pair)} is repeated")
        out.append((*pair, number))
    return tuple(out)


def normalised_keys(values: Mapping[str, Any], source: Path | None) -> dict[str, Any]:
    """The study's equation-of-motion keys checked and normalised (numbers, tuples), as
    the CLI checks its options: mass and centre of gravity build the inertia together
    with the radii of gyration; the inertia matrix excludes them."""
    out: dict[str, Any] = {}
    for key in ("rho", "g", "ulen"):
        out[key] = None if values.get(key) is None else _positive(values[key], key, source)
    depth = values.get("water_depth")
    if depth is not None:  # .inf (YAML's infinity) or inf: deep water
        deep = str(depth).strip().lower() in ("inf", ".inf")
        depth = math.inf if deep else _positive(depth, "water_depth", source)
    out["water_depth"] = depth
    out["mass"] = _per_body(values.get("mass"), None, "mass", source)
    for key in ("center_of_gravity", "radii_of_gyration"):
        out[key] = _per_body(values.get(key), 3, key, source)
    matrix = values.get("inertia_matrix")
    if matrix is not None and not isinstance(matrix, str | Path):
        matrix = tuple(tuple(float(x) for x in row) for row in np.atleast_2d(matrix))
    out["inertia_matrix"] = matrix
    weight = values.get("restoring_includes_weight")
    if weight is not None:
        given = weight
        weight = {True: "yes", False: "no"}.get(weight, str(weight).lower())
        if weight not in ("yes", "no"):
            raise ArgumentError(
                f"{_where(source, 'restoring_includes_weight')}: {given!r} is not yes or no"
            )
    out["restoring_includes_weight"] = weight
    for key in ("external_stiffness", "external_damping"):
        out[key] = _triples(values.get(key), key, source)
    try:
        check_inertia_terms(
            mass=out["mass"],
            center_of_gravity=out["center_of_gravity"],
            radii_of_gyration=out["radii_of_gyration"],
            matrix_given=matrix is not None,
        )
    except ArgumentError as exc:
        raise ArgumentError(f"{source}: {exc}" if source else str(exc)) from None
    return out


def complete_study_data(ds: xr.Dataset, study) -> xr.Dataset:
    """``ds`` completed with the study's inertia and external terms (the function behind
    the CLI's options, :func:`cummins.mass_properties.with_given_terms`); errors name the
    study file and key."""
    from cummins.mass_properties import read_matrix_file, with_given_terms

    matrix = study.inertia_matrix
    if isinstance(matrix, str | Path):
        matrix = read_matrix_file(str(matrix))
    try:
        return with_given_terms(
            ds,
            mass=study.mass,
            center_of_gravity=study.center_of_gravity,
            radii_of_gyration=study.radii_of_gyration,
            matrix=matrix,
            restoring={"yes": "total", "no": "hydrostatic", None: None}[
                study.restoring_includes_weight
            ],
            external_stiffness=study.external_stiffness,
            external_damping=study.external_damping,
        )
    except ArgumentError as exc:
        raise ArgumentError(f"{study.source}: {exc}" if study.source else str(exc)) from None


def check_study_data(ds: xr.Dataset, study) -> None:
    """A :class:`~cummins.errors.HydroDataError` in one line when the data (completed by
    the study's keys) lack what the analysis needs, naming the study keys to add."""
    for name, (meaning, keys) in NEEDED.items():
        if name in ds:
            continue
        file = Path(str(study.data)).name
        where = f" to {Path(study.source).name}" if study.source else ""
        raise HydroDataError(
            f"the data have no {name!r}: analysis {study.analysis} needs {meaning}; "
            f"add{where} the study keys {keys}",
            path=file,
        )
