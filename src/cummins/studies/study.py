"""A batch study: one vessel and many cases (headings × sea states × seeds), with limits.

The definition only — what :mod:`cummins.studies.batch` runs. A :class:`Study` is read from YAML
(:func:`load_study`, keys :data:`STUDY_KEYS`) or built in Python; its cases are the outer
product of a ``grid`` or an explicit list; :class:`Limit` bounds a statistic of a DOF's
response (units required). Errors name the study file and the key
(:class:`StudyError`).

Examples
--------
>>> import cummins
>>> from cummins.studies.study import Study
>>> study = Study(data=cummins.demo_files() / "tanker.1",
...               grid={"heading": [90, 180], "hs": [2, 4], "tp": [8, 10]},
...               limits={"Roll": "3 deg", "Heave": {"max": "2 m"}})
>>> len(study.all_cases), study.dims
(8, ('heading', 'hs', 'tp'))
"""

from __future__ import annotations

import difflib
import itertools
import math
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from cummins.errors import ArgumentError
from cummins.hydrodb import DOF_NAMES, is_rotation, split_dof
from cummins.mechanics import MechanicalSystem, system_from_mapping
from cummins.studies.equation_of_motion import KEYS as EQUATION_OF_MOTION_KEYS
from cummins.studies.equation_of_motion import normalised_keys
from cummins.studies.pto_sweep import (
    list_swept_pto,
    named_case_values,
    named_sweep,
    swept_pto,
    with_own_values,
)

#: The analyses a study can run on each case.
ANALYSES: dict[str, str] = {
    "rao": "frequency domain: RAOs, response spectra, significant and most probable maximum",
    "simulate": "time domain: simulate_waves in a realisation of the sea, observed statistics",
}
#: Axes of a grid, in the order of the result's dimensions, and their units.
GRID_AXES: dict[str, str] = {
    "heading": "deg",
    "hs": "m",
    "tp": "s",
    "gamma": "1",
    "spreading": "1",
    "seed": "1",
    "pto_damping": "N s/m | N m s/rad",
    "pto_stiffness": "N/m | N m/rad",
}
#: Statistics a limit can bound: the name in the YAML file → the result variable.
STATISTICS: dict[str, str] = {
    "significant": "significant_amplitude",
    "max": "maximum",
}
#: Units accepted in limits: name → (factor to SI, kind).
UNITS: dict[str, tuple[float, str]] = {
    "m": (1.0, "translation"),
    "cm": (0.01, "translation"),
    "mm": (0.001, "translation"),
    "deg": (math.pi / 180.0, "rotation"),
    "°": (math.pi / 180.0, "rotation"),
    "rad": (1.0, "rotation"),
}
#: Keys of a study file.
STUDY_KEYS: dict[str, str] = {
    "name": "a title for the report",
    "data": "hydrodynamic database (any format cummins reads), relative to the study file",
    "model": "radiation model from `cummins fit` (simulate; default: fitted once)",
    "analysis": "rao | simulate",
    "spectrum": "jonswap | pm | torsethaugen",
    "grid": "axes of an outer product: heading (deg), hs (m), tp (s), gamma, spreading, seed; "
    "with a system's PTO also pto_damping (N s/m, N m s/rad) and pto_stiffness",
    "cases": "an explicit list of cases (mappings with the grid's keys, and probability; "
    "with a system's PTO pto_damping and pto_stiffness per case)",
    "duration": "s: exposure of the most probable maximum (rao) or length of each run",
    "dt": "s: time step (simulate)",
    "components": "wave components per direction (simulate)",
    "directions": "directions of a short-crested sea (with spreading)",
    "omega_min": "rad/s, lowest RAO frequency (rao; default: the data's)",
    "omega_max": "rad/s, highest RAO frequency (rao; default: the data's)",
    "n_omega": "number of RAO frequencies (rao)",
    "viscous_damping": "{DOF: value}, linear damping added (kg/s, kg m^2/s)",
    "speed": "m/s: the forward speed to take from data holding several (simulate, data "
    "holding zero speed too: the speed terms kept apart, as simulate --speed)",
    "soft_springs": "s: period of soft springs in surge, sway and yaw of a ship at speed "
    "(simulate, as simulate --soft-springs)",
    **EQUATION_OF_MOTION_KEYS,
    "system": "joints, PTOs, dofs, body_coupling (cummins.mechanics.system_from_mapping); "
    "the results then hold each PTO's mean absorbed power",
    "limits": "{DOF: '3 deg'} or {DOF: {significant: .., max: ..}}",
    "scatter": "{hs: [..], tp: [..], probability: [[..] per hs]} weights of the sea states",
}
#: The keys that apply to one analysis only (the others are refused with it).
ANALYSIS_KEYS: dict[str, tuple[str, ...]] = {
    "rao": ("omega_min", "omega_max", "n_omega"),
    "simulate": ("model", "dt", "components", "soft_springs"),
}
#: Their defaults, where the analysis they apply to is run.
ANALYSIS_DEFAULTS: dict[str, Any] = {"dt": 0.1, "components": 200, "n_omega": 400}
_SWEEP_KEYS = ("pto_damping", "pto_stiffness")
_CASE_KEYS = ("heading", "hs", "tp", "gamma", "spreading", "seed", "probability", *_SWEEP_KEYS)
_BLAS_ENV = {
    "OMP_NUM_THREADS": "1",
    "OPENBLAS_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "VECLIB_MAXIMUM_THREADS": "1",
    "NUMEXPR_NUM_THREADS": "1",
}
_RESULT_KIND = "cummins batch results"


class StudyError(ArgumentError):
    """A study definition that cannot be run: names the file and key at fault (a bad
    argument of ``cummins batch``: exit status 2)."""


def at_key(source: Path | None, key: str) -> str:
    """Where in a study a key is: "<file>: <key>" (the key alone for a study built in
    Python)."""
    return f"{source}: {key}" if source else key


# --------------------------------------------------------------------------- definition


def _number(value: Any, key: str, source: Path | None = None) -> float:
    """A finite float from a number or a numeric string (YAML reads ``5e8`` as text)."""
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise StudyError(f"{at_key(source, key)}: {value!r} is not a number") from None
    if not math.isfinite(out) or isinstance(value, bool):
        raise StudyError(f"{at_key(source, key)}: {value!r} is not a finite number")
    return out


def parse_limit_value(text: Any, dof: str, key: str = "limits", source: Path | None = None):
    """(value in SI, text) of a limit such as ``"5 deg"`` or ``"1.5 m"`` on ``dof``.

    Rotations (Roll, Pitch, Yaw) take ``deg`` or ``rad``, translations ``m``, ``cm`` or
    ``mm``; a unit is required (no silent degrees-or-radians guess).

    Examples
    --------
    >>> round(parse_limit_value("5 deg", "Roll")[0], 6)
    0.087266
    >>> parse_limit_value("20 cm", "Heave")[0]
    0.2
    """
    where = at_key(source, key)
    match = re.fullmatch(r"\s*([-+0-9.eE]+)\s*([A-Za-z°]+)\s*", str(text))
    if match is None:
        kind = "deg or rad" if is_rotation(dof) else "m, cm or mm"
        raise StudyError(
            f"{where}: {text!r} is not a value with a unit",
            hint=f"write e.g. '3 {kind.split()[0]}'",
        )
    value = _number(match.group(1), key, source)
    unit = match.group(2).lower()
    if unit not in UNITS:
        raise StudyError(f"{where}: unknown unit {unit!r}; use {', '.join(UNITS)}")
    factor, kind = UNITS[unit]
    wanted = "rotation" if is_rotation(dof) else "translation"
    if kind != wanted:
        raise StudyError(
            f"{where}: {dof} is a {wanted}: {unit!r} does not apply",
            hint="rotations take deg or rad, translations m, cm or mm",
        )
    if not value > 0:
        raise StudyError(f"{where}: a limit must be positive, not {text!r}")
    return value * factor, f"{match.group(1)} {unit}"


@dataclass(frozen=True)
class Limit:
    """A criterion: ``statistic`` (``"significant"`` or ``"max"``) of ``dof`` ≤ ``value``.

    ``value`` in SI units (m or rad); ``text`` as written (``"5 deg"``).
    """

    dof: str
    statistic: str
    value: float
    text: str

    @property
    def label(self) -> str:
        """``"Roll significant <= 5 deg"``."""
        return f"{self.dof} {self.statistic} <= {self.text}"


def _parse_limits(raw: Any, source: Path | None) -> tuple[Limit, ...]:
    if raw is None:
        return ()
    if isinstance(raw, Sequence) and all(isinstance(x, Limit) for x in raw):
        return tuple(raw)
    if not isinstance(raw, Mapping):
        raise StudyError(f"{at_key(source, 'limits')}: expected a mapping DOF: limit")
    out = []
    for dof, spec in raw.items():
        dof = str(dof)
        key = f"limits.{dof}"
        if split_dof(dof)[1] not in DOF_NAMES:
            raise StudyError(
                f"{at_key(source, key)}: unknown DOF {dof!r}", hint=f"DOFs: {', '.join(DOF_NAMES)}"
            )
        items = spec.items() if isinstance(spec, Mapping) else [("significant", spec)]
        for statistic, text in items:
            if statistic not in STATISTICS:
                raise StudyError(
                    f"{at_key(source, f'{key}.{statistic}')}: unknown statistic; use "
                    f"{' or '.join(STATISTICS)}"
                )
            value, written = parse_limit_value(text, dof, f"{key}.{statistic}", source)
            out.append(Limit(dof, str(statistic), value, written))
    return tuple(out)


@dataclass(frozen=True)
class Case:
    """One sea state (and realisation) of a study.

    Attributes
    ----------
    heading
        Direction the waves travel, degrees (0 following seas, 180 head seas).
    hs, tp
        Significant wave height (m) and peak period (s).
    gamma
        JONSWAP peakedness (None: 3.3).
    spreading
        cos-2s exponent s of a short-crested sea (None: long-crested).
    seed
        Random phases (``simulate``; None: derived from the case).
    probability
        Weight of the sea state in operability (list studies; grids use ``scatter``).
    pto_damping, pto_stiffness
        The swept PTO's damping and stiffness (a grid's PTO sweep, or a list case's;
        None: the system's).
    """

    heading: float
    hs: float
    tp: float
    gamma: float | None = None
    spreading: float | None = None
    seed: int | None = None
    probability: float | None = None
    pto_damping: float | None = None
    pto_stiffness: float | None = None

    def parameters(self) -> dict[str, Any]:
        """What determines the result (not the probability), JSON-ready (a PTO's swept
        values only when given: the ids of the cases of other studies do not change)."""
        sweep = {k: float(getattr(self, k)) for k in _SWEEP_KEYS if getattr(self, k) is not None}
        return {
            "heading": float(self.heading),
            "hs": float(self.hs),
            "tp": float(self.tp),
            "gamma": None if self.gamma is None else float(self.gamma),
            "spreading": None if self.spreading is None else float(self.spreading),
            "seed": None if self.seed is None else int(self.seed),
            **sweep,
        }

    @property
    def label(self) -> str:
        """``"heading 180 deg, Hs 4 m, Tp 10 s"`` (+ the optional parameters)."""
        text = f"heading {self.heading:g} deg, Hs {self.hs:g} m, Tp {self.tp:g} s"
        for name in ("gamma", "spreading", "seed", *_SWEEP_KEYS):
            value = getattr(self, name)
            if value is not None:
                text += f", {name} {value:g}"
        return text


def _case_from_mapping(raw: Any, k: int, source: Path | None) -> Case:
    key = f"cases[{k}]"
    if isinstance(raw, Case):
        return raw
    if not isinstance(raw, Mapping):
        raise StudyError(f"{at_key(source, key)}: expected a mapping heading/hs/tp/...")
    unknown = sorted(set(map(str, raw)) - set(_CASE_KEYS))
    if unknown:
        raise StudyError(
            f"{at_key(source, f'{key}.{unknown[0]}')}: unknown key; a case takes "
            f"{', '.join(_CASE_KEYS)}"
        )
    for needed in ("heading", "hs", "tp"):
        if needed not in raw:
            raise StudyError(f"{at_key(source, key)}: missing {needed!r}")
    values = {n: _number(raw[n], f"{key}.{n}", source) for n in raw}
    if "seed" in values:
        values["seed"] = int(values["seed"])
    return _checked_case(Case(**values), key, source)


def _checked_case(case: Case, key: str, source: Path | None) -> Case:
    if not -360.0 <= case.heading <= 360.0:
        raise StudyError(f"{at_key(source, key)}: heading {case.heading:g} deg is beyond one turn")
    for name, unit in (("hs", "m"), ("tp", "s")):
        if not getattr(case, name) > 0:  # the axis and the value at fault
            value = getattr(case, name)
            raise StudyError(f"{at_key(source, f'{key}.{name}')}: {value:g} {unit} is not positive")
    if case.gamma is not None and not case.gamma >= 1:
        raise StudyError(f"{at_key(source, key)}: gamma must be >= 1")
    if case.spreading is not None and not case.spreading >= 0:
        raise StudyError(f"{at_key(source, key)}: spreading must be >= 0")
    if case.probability is not None and not case.probability >= 0:
        raise StudyError(f"{at_key(source, key)}: probability must be >= 0")
    return case


def _normalise_grid(raw: Any, source: Path | None) -> tuple[tuple[str, tuple], ...]:
    if isinstance(raw, tuple) and all(isinstance(p, tuple) and len(p) == 2 for p in raw):
        raw = dict(raw)  # already normalised (dataclasses.replace)
    if not isinstance(raw, Mapping):
        raise StudyError(f"{at_key(source, 'grid')}: expected a mapping of axes")
    unknown = sorted(set(map(str, raw)) - set(GRID_AXES))
    if unknown:
        raise StudyError(
            f"{at_key(source, f'grid.{unknown[0]}')}: unknown axis; axes are {', '.join(GRID_AXES)}"
        )
    for needed in ("heading", "hs", "tp"):
        if needed not in raw:
            raise StudyError(f"{at_key(source, 'grid')}: missing axis {needed!r}")
    axes = []
    for name in GRID_AXES:
        if name not in raw:
            continue
        values = raw[name]
        if isinstance(values, str) or not isinstance(values, Sequence | np.ndarray):
            values = [values]
        numbers = [_number(v, f"grid.{name}", source) for v in values]
        if name == "seed":
            numbers = [int(v) for v in numbers]
        if not numbers:
            raise StudyError(f"{at_key(source, f'grid.{name}')}: no values (an empty list)")
        if len(set(numbers)) != len(numbers):
            raise StudyError(f"{at_key(source, f'grid.{name}')}: repeated values")
        if name == "heading" and not all(-360.0 <= v <= 360.0 for v in numbers):
            raise StudyError(
                f"{at_key(source, 'grid.heading')}: headings are degrees within one turn "
                "(-360 to 360)"
            )
        axes.append((name, tuple(numbers)))
    return tuple(axes)


def _normalise_scatter(
    raw: Any, grid, source: Path | None
) -> tuple[tuple[float, float, float], ...]:
    if raw is None:
        return ()
    if isinstance(raw, Sequence) and all(isinstance(x, tuple) for x in raw):
        return tuple(raw)
    key = "scatter"
    if grid is None:
        raise StudyError(
            f"{at_key(source, key)}: a scatter diagram needs a grid; give each case a "
            "probability in a list study"
        )
    if not isinstance(raw, Mapping) or set(raw) != {"hs", "tp", "probability"}:
        raise StudyError(f"{at_key(source, key)}: expected hs: [..], tp: [..], probability: [[..]]")
    hs = [_number(v, "scatter.hs", source) for v in raw["hs"]]
    tp = [_number(v, "scatter.tp", source) for v in raw["tp"]]
    table = np.array(
        [[_number(v, "scatter.probability", source) for v in row] for row in raw["probability"]]
    )
    if table.shape != (len(hs), len(tp)) or np.any(table < 0) or not table.sum() > 0:
        raise StudyError(
            f"{at_key(source, 'scatter.probability')}: needs {len(hs)} rows (one per hs) of "
            f"{len(tp)} non-negative numbers (one per tp), not all zero"
        )
    axes = dict(grid)
    if sorted(hs) != sorted(axes["hs"]) or sorted(tp) != sorted(axes["tp"]):
        raise StudyError(
            f"{at_key(source, key)}: its hs and tp must be the grid's hs and tp values"
        )
    return tuple((h, t, float(table[i, j])) for i, h in enumerate(hs) for j, t in enumerate(tp))


@dataclass(frozen=True)
class Study:
    """A batch study: a vessel, an analysis, its cases and the limits to check.

    Parameters mirror the keys of a study file (:data:`STUDY_KEYS`, :func:`load_study`);
    ``grid`` and ``limits`` may be given as mappings, ``cases`` as mappings or
    :class:`Case`\\ s. Paths are used as given (:func:`load_study` resolves them against
    the study file's folder). ``swept_pto`` is derived: the PTO whose damping and
    stiffness the grid's ``pto_damping`` and ``pto_stiffness`` set, or a list's cases
    (:mod:`cummins.studies.pto_sweep`: the system's only PTO, or the one named,
    ``pto_damping: {name: [..]}``, ``{name: value}`` in a case).

    Examples
    --------
    >>> s = Study(data="tanker.1", analysis="simulate", grid={"heading": 180, "hs": [2, 3],
    ...           "tp": 9, "seed": [1, 2]}, duration=600)
    >>> s.dims, [c.seed for c in s.all_cases]
    (('heading', 'hs', 'tp', 'seed'), [1, 2, 1, 2])
    """

    data: Path
    analysis: str = "rao"
    model: Path | None = None
    grid: Any = None
    cases: Any = ()
    spectrum: str = "jonswap"
    duration: float = 10800.0
    dt: float | None = None
    components: int | None = None
    directions: int = 9
    omega_min: float | None = None
    omega_max: float | None = None
    n_omega: int | None = None
    viscous_damping: Any = None
    speed: float | None = None
    soft_springs: float | None = None
    limits: Any = ()
    scatter: Any = ()
    name: str = ""
    source: Path | None = None
    system: Any = None
    rho: float | None = None
    g: float | None = None
    ulen: float | None = None
    mass: Any = ()
    center_of_gravity: Any = ()
    radii_of_gyration: Any = ()
    inertia_matrix: Any = None
    restoring_includes_weight: str | None = None
    external_stiffness: Any = ()
    external_damping: Any = ()
    water_depth: float | None = None
    swept_pto: str | None = None

    def __post_init__(self) -> None:
        src = self.source
        set_ = object.__setattr__

        def case_key(k: int) -> str:
            return at_key(src, f"cases[{k}]")

        set_(self, "data", Path(self.data))
        if self.model is not None:
            set_(self, "model", Path(self.model))
        if self.analysis not in ANALYSES:
            raise StudyError(
                f"{at_key(src, 'analysis')}: unknown analysis {self.analysis!r}; use "
                f"{' or '.join(ANALYSES)}"
            )
        for analysis, keys in ANALYSIS_KEYS.items():
            for key in keys:
                if analysis != self.analysis and getattr(self, key) is not None:
                    raise StudyError(
                        f"{at_key(src, key)}: applies to analysis: {analysis}, not to this "
                        f"study's analysis: {self.analysis}: remove it"
                    )
                if analysis == self.analysis and getattr(self, key) is None:
                    set_(self, key, ANALYSIS_DEFAULTS.get(key))
        try:
            terms = normalised_keys({k: getattr(self, k) for k in EQUATION_OF_MOTION_KEYS}, src)
        except ArgumentError as exc:
            raise StudyError(str(exc)) from None
        for key, value in terms.items():
            set_(self, key, value)
        from cummins.seakeeping.waves import SPECTRA

        if str(self.spectrum).lower() not in SPECTRA:
            raise StudyError(
                f"{at_key(src, 'spectrum')}: unknown spectrum {self.spectrum!r}; use "
                f"{', '.join(SPECTRA)}"
            )
        if (self.grid is None) == (not self.cases):
            raise StudyError(f"{at_key(src, 'grid')}: give either a grid or a list of cases")
        if self.grid is not None:
            try:
                grid, named = named_sweep(self.grid, at_key(src, "grid"))
            except ArgumentError as exc:
                raise StudyError(str(exc)) from None
            set_(self, "grid", _normalise_grid(grid, src))
            set_(self, "swept_pto", named or self.swept_pto)
            set_(self, "cases", ())
        else:
            try:
                raw, named_cases = named_case_values(self.cases, case_key)
            except ArgumentError as exc:
                raise StudyError(str(exc)) from None
            named_cases = [  # a Case of Python: the PTO of swept_pto (dataclasses.replace)
                self.swept_pto if isinstance(c, Case) else n
                for c, n in zip(self.cases, named_cases, strict=True)
            ]
            set_(self, "cases", tuple(_case_from_mapping(c, k, src) for k, c in enumerate(raw)))
        for key in ("duration", "dt", "soft_springs"):
            if getattr(self, key) is None:
                continue
            if not _number(getattr(self, key), key, src) > 0:
                raise StudyError(f"{at_key(src, key)}: must be positive")
            set_(self, key, float(getattr(self, key)))
        for key, least in (("components", 1), ("directions", 2), ("n_omega", 2)):
            if getattr(self, key) is None:
                continue
            value = _number(getattr(self, key), key, src)
            if value != int(value) or value < least:
                raise StudyError(f"{at_key(src, key)}: must be an integer >= {least}")
            set_(self, key, int(value))
        for key in ("omega_min", "omega_max", "speed"):
            if getattr(self, key) is not None:
                set_(self, key, _number(getattr(self, key), key, src))
        damping = self.viscous_damping or {}
        if isinstance(damping, tuple):
            damping = dict(damping)
        if not isinstance(damping, Mapping):
            raise StudyError(f"{at_key(src, 'viscous_damping')}: expected a mapping DOF: value")
        set_(
            self,
            "viscous_damping",
            tuple((str(d), _number(v, f"viscous_damping.{d}", src)) for d, v in damping.items()),
        )
        if self.system is not None and not isinstance(self.system, MechanicalSystem):
            try:
                set_(self, "system", system_from_mapping(self.system, at_key(src, "system")))
            except ArgumentError as exc:
                raise StudyError(str(exc)) from None
        try:
            if self.grid is not None:
                swept = swept_pto(self.grid, self.system, self.swept_pto, at_key(src, "grid"))
            else:
                swept = list_swept_pto(self.cases, named_cases, self.system, case_key)
                set_(self, "cases", with_own_values(self.cases, self.system, swept))
        except ArgumentError as exc:
            raise StudyError(str(exc)) from None
        set_(self, "swept_pto", swept)
        set_(self, "limits", _parse_limits(self.limits, src))
        set_(self, "scatter", _normalise_scatter(self.scatter or None, self.grid, src))
        if self.analysis == "rao":
            seeds = self.grid and dict(self.grid).get("seed")
            if seeds or any(c.seed is not None for c in self.cases):
                raise StudyError(
                    f"{at_key(src, 'seed')}: seeds apply to analysis: simulate (the frequency "
                    "domain has no random phases)"
                )

    @cached_property
    def all_cases(self) -> tuple[Case, ...]:
        """Every case: the grid's outer product (last axis fastest) or the list."""
        if self.grid is None:
            return self.cases
        names = [name for name, _ in self.grid]
        out = []
        for values in itertools.product(*(v for _, v in self.grid)):
            out.append(
                _checked_case(Case(**dict(zip(names, values, strict=True))), "grid", self.source)
            )
        return tuple(out)

    @property
    def dims(self) -> tuple[str, ...]:
        """Dimensions of the results: the grid's axes, or ``("case",)``."""
        return tuple(name for name, _ in self.grid) if self.grid is not None else ("case",)

    def settings(self) -> dict[str, Any]:
        """What every case's result depends on, besides the data and the case (JSON-ready)."""
        out: dict[str, Any] = {
            "analysis": self.analysis,
            "spectrum": str(self.spectrum).lower(),
            "duration": self.duration,
            "viscous_damping": [list(p) for p in self.viscous_damping],
            "speed": self.speed,
        }
        if self.analysis == "simulate" and self.speed:  # the memory at speed is chosen
            out["memory_at_speed"] = "nearer of derived and fitted"  # (memory_at_speed)
        if self.soft_springs is not None:
            out["soft_springs"] = self.soft_springs
        if self.system is not None:
            out["system"] = self.system.describe()
        if self.swept_pto is not None:
            out["swept_pto"] = self.swept_pto
        if self.water_depth is not None:
            out["water_depth"] = self.water_depth
        if self.ulen is not None:  # a length scale of the data: in the case ids
            out["ulen"] = self.ulen
        if self.analysis == "rao":
            out.update(omega_min=self.omega_min, omega_max=self.omega_max, n_omega=self.n_omega)
        else:
            out.update(dt=self.dt, components=self.components, directions=self.directions)
        return out

    def describe(self) -> dict[str, Any]:
        """The whole definition, JSON-ready (stored in the results' attributes)."""
        return {
            "name": self.name,
            "data": str(self.data),
            "model": None if self.model is None else str(self.model),
            **self.settings(),
            "grid": None if self.grid is None else {n: list(v) for n, v in self.grid},
            "cases": [{**c.parameters(), "probability": c.probability} for c in self.cases],
            "limits": [
                {"dof": lim.dof, "statistic": lim.statistic, "limit": lim.text}
                for lim in self.limits
            ],
            "scatter": [list(s) for s in self.scatter],
            **{
                k: _json_ready(getattr(self, k))
                for k in EQUATION_OF_MOTION_KEYS
                if getattr(self, k) not in (None, ())
            },
        }


def _json_ready(value: Any) -> Any:
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, tuple):
        return [_json_ready(v) for v in value]
    return value


def load_study(path: str | os.PathLike[str]) -> Study:
    """Read a study file (YAML, :func:`example_study_text` shows every key).

    Paths in the file (``data``, ``model``) are relative to the file's folder.

    Raises
    ------
    StudyError
        Unreadable YAML (with its line), an unknown key, a missing data file, a limit
        without a unit or on an unknown DOF, … — naming the file and the key.
    """
    import yaml

    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise StudyError(f"{path}: cannot read the study file ({exc.strerror})") from None
    except UnicodeDecodeError as exc:
        line = path.read_bytes()[: exc.start].count(b"\n") + 1
        raise StudyError(
            f"{path}, line {line}: not a text file (byte {exc.start + 1} is not UTF-8)",
            hint="A study is a YAML text file: `cummins batch --example study.yaml` writes one",
        ) from None
    try:
        raw = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = f", line {mark.line + 1}" if mark is not None else ""
        problem = getattr(exc, "problem", None) or str(exc)
        raise StudyError(f"{path}{line}: not valid YAML ({problem})") from None
    if not isinstance(raw, Mapping):
        raise StudyError(f"{path}: expected a mapping of keys ({', '.join(STUDY_KEYS)})")
    unknown = sorted(set(map(str, raw)) - set(STUDY_KEYS))
    if unknown:
        near = difflib.get_close_matches(unknown[0], STUDY_KEYS, n=1)  # a typo's key
        hint = (
            f"did you mean {near[0]!r}? " if near else ""
        ) + f"the keys are {', '.join(STUDY_KEYS)}"
        raise StudyError(f"{path}: unknown key {unknown[0]!r}", hint=hint)
    if "data" not in raw:
        raise StudyError(f"{path}: missing key 'data' (the hydrodynamic database)")
    values = dict(raw)
    for key in ("data", "model", "inertia_matrix"):
        if key == "inertia_matrix" and not isinstance(values.get(key), str):
            continue  # a matrix written in the study
        if values.get(key) is not None:
            file = path.parent / str(values[key])
            if not file.exists():
                raise StudyError(f"{path}: {key}: {file} does not exist")
            values[key] = file
    values.setdefault("cases", ())
    return Study(**values, source=path)


def example_study_text(data: str = "tanker.1") -> str:
    """A commented example study (the bundled tanker's operability), as YAML text."""
    return f"""\
# cummins batch study: run with `cummins batch study.yaml -o results.nc`
name: tanker operability, frequency domain
data: {data}          # any file cummins reads (relative to this file)
# model: tanker_model.nc   # analysis: simulate only; default: one passive fit
analysis: rao             # rao (frequency domain) | simulate (time domain)
spectrum: jonswap         # jonswap | pm | torsethaugen
duration: 10800           # s: exposure of the most probable maximum (rao), or run length
n_omega: 300              # RAO frequencies over the data's range (rao)
# dt: 0.1                 # s, time step (simulate)
# components: 200         # wave components (simulate)
grid:                     # outer product of the axes; or `cases:` a list of mappings
  heading: [90, 135, 180] # deg, direction the waves travel: 180 head seas
  hs: [1, 2, 3, 4]        # m
  tp: [6, 8, 10, 12, 14]  # s
  # gamma: [1, 3.3]       # JONSWAP peakedness
  # spreading: [4]        # cos-2s exponent: short-crested seas
  # seed: [1, 2, 3]       # simulate: realisations (default: one per case)
  # pto_damping: [3.0e+5, 1.0e+6, 3.0e+6]  # with a system's PTO: N s/m (N m s/rad);
  #                       # the best per sea state and for the scatter diagram is added
viscous_damping:
  Roll: 5.0e+8            # kg m^2/s
# what the files lack, as simulate's options (--mass ...), one value or list per body:
# rho: 1025              # kg/m^3, g: 9.81 (nondimensional formats)
# ulen: 1                # m: WAMIT's length scale ULEN, as --ulen (default from the .out)
# mass: 1.2e8            # kg; with center_of_gravity and radii_of_gyration
# center_of_gravity: [0, 0, -2]
# radii_of_gyration: [14, 60, 60]
# external_stiffness: [[Surge, Surge, 8.0e+4]]   # moorings (N/m); external_damping too
# system:                # several bodies: joints, PTOs (docs/wec.md); adds pto_mean_power
#   body_coupling: false
#   joints: [{{kind: translational, body: body1, base: body2, pto: {{damping: 1.2e6}}}}]
limits:                   # significant single amplitude 2 sqrt(m0) unless `max:`
  Roll: 4 deg
  Pitch: 2 deg
  Heave: {{max: 2.5 m}}     # most probable maximum (rao) / observed maximum (simulate)
# scatter:                # probabilities of the sea states (rows: hs, columns: tp)
#   hs: [1, 2, 3, 4]
#   tp: [6, 8, 10, 12, 14]
#   probability: [[.05, .1, .1, .05, .02], [.03, .1, .1, .06, .02],
#                 [.01, .05, .08, .05, .02], [0, .02, .05, .04, .05]]
"""
