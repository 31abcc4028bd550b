"""Checks of the numbers a user gives, before any work starts.

Every public function that takes a sea state, a duration, a time step, a count or a
tolerance checks it here, and the command line checks its options with the click types of
:mod:`cummins.cli.common` built on the same rules. A value that is not usable raises
:class:`cummins.errors.ArgumentError` (a ``ValueError`` too) whose message names the
argument, the value given, the range accepted with its unit, and what to pass instead:

>>> positive(0.0, "dt", "s")
Traceback (most recent call last):
...
cummins.errors.ArgumentError: dt must be a finite number > 0 s, not 0

Requests whose arrays would not fit in memory are refused before anything is allocated
(:func:`check_memory`): the message says how much memory they need and what to change.
The limit is :data:`MEMORY_LIMIT` bytes, or ``CUMMINS_MEMORY_LIMIT`` (GiB) from the
environment.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from typing import Any

import numpy as np

from cummins.errors import ArgumentError

#: Largest working memory one request may need, bytes (default 8 GiB; the environment
#: variable ``CUMMINS_MEMORY_LIMIT`` in GiB takes precedence).
MEMORY_LIMIT = 8 * 2**30


def _show(value: Any) -> str:
    try:
        return f"{float(value):g}"
    except (TypeError, ValueError, OverflowError):
        return repr(value)


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def number(value: Any, name: str, unit: str = "") -> float:
    """``value`` as a finite float, else :class:`ArgumentError` naming ``name``."""
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ArgumentError(f"{name} must be a number{_unit(unit)}, not {value!r}") from None
    if not math.isfinite(x):
        raise ArgumentError(f"{name} must be a finite number{_unit(unit)}, not {_show(x)}")
    return x


def in_range(
    value: Any,
    name: str,
    unit: str = "",
    *,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    high_open: bool = False,
    hint: str | None = None,
) -> float:
    """``value`` as a finite float within [low, high] (open ends with ``low_open`` /
    ``high_open``), else :class:`ArgumentError`.

    >>> in_range(1.5, "r2", low=0, high=1, low_open=True)
    Traceback (most recent call last):
    ...
    cummins.errors.ArgumentError: r2 must be a finite number > 0 and <= 1, not 1.5
    """
    parts = []
    if low is not None:
        parts.append(f"{'>' if low_open else '>='} {low:g}")
    if high is not None:
        parts.append(f"{'<' if high_open else '<='} {high:g}")
    wanted = f"a finite number {' and '.join(parts)}".rstrip() + _unit(unit)
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ArgumentError(f"{name} must be {wanted}, not {value!r}", hint=hint) from None
    bad = not math.isfinite(x)
    if low is not None:
        bad |= x <= low if low_open else x < low
    if high is not None:
        bad |= x >= high if high_open else x > high
    if bad:
        raise ArgumentError(f"{name} must be {wanted}, not {_show(x)}", hint=hint)
    return x


def positive(value: Any, name: str, unit: str = "", *, hint: str | None = None) -> float:
    """A finite number > 0 (a duration, a time step, a period …)."""
    return in_range(value, name, unit, low=0.0, low_open=True, hint=hint)


def non_negative(value: Any, name: str, unit: str = "", *, hint: str | None = None) -> float:
    """A finite number >= 0 (a wave height, an amplitude, a damping coefficient …)."""
    return in_range(value, name, unit, low=0.0, hint=hint)


def count(
    value: Any, name: str, *, minimum: int = 1, maximum: int | None = None, what: str = ""
) -> int:
    """An integer ``minimum <= value <= maximum`` (a number of components, an order …)."""
    try:
        as_float = float(value)
        n = int(value)
    except (TypeError, ValueError, OverflowError):
        raise ArgumentError(f"{name} must be a whole number, not {value!r}") from None
    if n != as_float:
        raise ArgumentError(f"{name} must be a whole number, not {value!r}")
    if n < minimum or (maximum is not None and n > maximum):
        wanted = f">= {minimum}" + ("" if maximum is None else f" and <= {maximum}")
        raise ArgumentError(f"{name} must be a whole number {wanted}{_unit(what)}, not {n}")
    return n


def finite_values(values: Iterable[Any], name: str, unit: str = "") -> np.ndarray:
    """A float array whose every value is finite, else the first bad one is named."""
    arr = np.asarray(values, dtype=float)
    bad = ~np.isfinite(arr)
    if bad.any():
        where = tuple(int(i) for i in np.argwhere(bad)[0])
        index = where[0] if len(where) == 1 else where
        raise ArgumentError(
            f"{name} must hold finite numbers{f' (in {unit})' if unit else ''}; value {index} "
            f"is {_show(arr[where])}"
        )
    return arr


def memory_limit() -> int:
    """The memory one request may use, bytes (``CUMMINS_MEMORY_LIMIT`` GiB or
    :data:`MEMORY_LIMIT`)."""
    text = os.environ.get("CUMMINS_MEMORY_LIMIT")
    if text:
        try:
            gib = float(text)
        except ValueError:
            gib = float("nan")
        if math.isfinite(gib) and gib > 0:
            return int(gib * 2**30)
    return MEMORY_LIMIT


def format_bytes(n_bytes: float) -> str:
    """``1.5 GiB``, ``146 TiB`` …"""
    value = float(n_bytes)
    for unit in ("bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"):
        if abs(value) < 1024 or unit == "EiB":
            return f"{value:.0f} {unit}" if unit == "bytes" else f"{value:.3g} {unit}"
        value /= 1024
    return f"{value:.3g} EiB"  # pragma: no cover


def check_memory(n_bytes: float, what: str, *, hint: str) -> None:
    """Refuse a request whose arrays need more than :func:`memory_limit` bytes.

    Parameters
    ----------
    n_bytes
        Memory the request needs (an estimate from the array sizes), bytes.
    what
        The request, e.g. ``"a run of 2e+13 time steps x 6 DOFs"``.
    hint
        What to change (which option or argument, in which direction).
    """
    limit = memory_limit()
    if not n_bytes <= limit:  # also refuses NaN
        raise ArgumentError(
            f"{what} needs about {format_bytes(n_bytes)} of memory, more than the "
            f"{format_bytes(limit)} allowed",
            hint=f"{hint} (or set CUMMINS_MEMORY_LIMIT to a larger number of GiB)",
        )


def time_steps(duration: Any, dt: Any) -> int:
    """Number of samples of ``t = 0, dt, … duration`` after checking both (s)."""
    duration = positive(duration, "duration", "s")
    dt = positive(dt, "time step dt", "s")
    if dt > duration:
        raise ArgumentError(
            f"the time step dt = {dt:g} s is longer than the duration {duration:g} s",
            hint="Give a smaller time step or a longer duration",
        )
    steps = math.floor(duration / dt + 0.5) + 1
    return int(steps)


def simulation_memory(n_steps: int, n_states: int, n_dofs: int) -> float:
    """Bytes a linear simulation of ``n_steps`` needs: the modal recursion keeps a complex
    drive and state per mode and step (2 × 16 bytes × states), the force, the outputs
    and the result's motion, velocity, memory and external force (about 10 × 8 bytes ×
    DOFs), per step."""
    return float(n_steps) * (32.0 * n_states + 80.0 * n_dofs + 16.0)


def check_simulation_size(
    duration: Any, dt: Any, n_states: int, n_dofs: int, option: str = "duration"
) -> int:
    """The number of time steps of a run, after refusing one too large to hold.

    The hint names ``--duration``/``--dt`` when ``option`` starts with ``--``.
    """
    n_steps = time_steps(duration, dt)
    need = simulation_memory(n_steps, n_states, n_dofs)
    names = ("--duration", "--dt") if option.startswith("--") else ("duration", "dt")
    check_memory(
        need,
        f"a run of {n_steps:.4g} time steps x {n_states} states ({n_dofs} DOFs)",
        hint=f"Shorten {names[0]} or lengthen {names[1]}",
    )
    return n_steps


# --------------------------------------------------------------------------- physical scales

#: No floating body is heavier, kg (the largest ships displace about 6·10⁸ kg).
MAX_MASS = 1e12
#: Lever arm no floating body exceeds, m: moments of inertia up to MAX_MASS·MAX_LENGTH².
MAX_LENGTH = 1e3
#: Frequency scale turning a mass coefficient into the largest damping, rad/s.
MAX_RATE = 1e2
#: Acceleration scale turning a mass into the largest wave force per metre of wave
#: amplitude, m/s² per m (ρ g A_wp of a waterplane of 10⁸ m², with room to spare).
MAX_WAVE_FORCE_RATE = 1e2
#: No water wave is faster, rad/s (a period of 0.6 ms: capillary ripples are slower).
MAX_FREQUENCY = 1e4


def coefficient_limit(dof_i: str, dof_j: str, kind: str = "mass") -> float:
    """The largest |value| a mass-like (``kind="mass"``: inertia, added mass, kg, kg·m,
    kg·m²) or damping (``"damping"``, ×:data:`MAX_RATE`) coefficient between two rigid-body
    DOFs can have for any floating body: :data:`MAX_MASS` × :data:`MAX_LENGTH`^(number of
    rotations); a wave excitation of DOF ``dof_i`` per metre of amplitude
    (``"excitation"``): :data:`MAX_MASS` × :data:`MAX_WAVE_FORCE_RATE` (× :data:`MAX_LENGTH`
    for a moment). ``inf`` for a generalized mode (its scale is the mode shape's)."""
    from cummins.hydrodb import is_rigid_body_dof, is_rotation

    if not (is_rigid_body_dof(dof_i) and is_rigid_body_dof(dof_j)):
        return math.inf
    rotations = int(is_rotation(dof_i)) + int(is_rotation(dof_j))
    if kind == "excitation":  # a force or moment per metre of wave amplitude, DOF i
        return MAX_MASS * MAX_WAVE_FORCE_RATE * MAX_LENGTH ** int(is_rotation(dof_i))
    return MAX_MASS * MAX_LENGTH**rotations * (MAX_RATE if kind == "damping" else 1.0)


def _pair(ds, index: tuple[int, ...], dims: tuple[str, ...]) -> str:
    where = []
    for dim, k in zip(dims, index, strict=True):
        value = ds[dim].values[k] if dim in ds.coords else k
        if dim == "omega":
            where.append(f"omega = {float(value):.4g} rad/s")
        elif dim == "forward_speed":
            where.append(f"speed {float(value):g} m/s")
        elif dim == "wave_direction":
            where.append(f"direction {math.degrees(float(value)):g} deg")
        elif dim not in ("influenced_dof", "radiating_dof", "complex"):
            where.append(f"{dim} {value}")
    labels = [str(ds[d].values[k]) for d, k in zip(dims, index, strict=True) if d.endswith("_dof")]
    pair = labels[0] if len(set(labels)) == 1 else "-".join(labels)
    return pair + (f" at {', '.join(where)}" if where else "")


#: Hydrodynamic coefficients the guards look at, with their kind of scale.
GUARDED = {
    "added_mass": "mass",
    "added_mass_inf": "mass",
    "added_mass_zero": "mass",
    "radiation_damping": "damping",
}


def guard_hydro_data(ds, error: type[Exception] | None = None, *, what: str = "fit") -> None:
    """Refuse data a fit, a passivity test or a reduction cannot use: non-finite added mass
    or damping, or values beyond any floating body (:func:`coefficient_limit`), naming
    the DOF pair and frequency, before LAPACK sees them.

    ``error`` is the exception raised (default :class:`cummins.errors.FitError`).
    """
    from cummins.errors import FitError

    error = error or FitError
    source = ds.attrs.get("source_file") if hasattr(ds, "attrs") else None
    origin = f" in {source}" if source else ""
    for name, kind in GUARDED.items():
        if name not in ds:
            continue
        arr = ds[name]
        dims = tuple(arr.dims)
        if "influenced_dof" not in dims or "radiating_dof" not in dims:
            continue
        values = np.asarray(arr.values, dtype=float)
        rows = [str(d) for d in ds.influenced_dof.values]
        cols = [str(d) for d in ds.radiating_dof.values]
        ii, jj = dims.index("influenced_dof"), dims.index("radiating_dof")
        shape = [1] * values.ndim
        shape[ii], shape[jj] = len(rows), len(cols)
        limit = np.array([[coefficient_limit(r, c, kind) for c in cols] for r in rows])
        limit = limit if ii < jj else limit.T
        with np.errstate(invalid="ignore"):
            bad = ~np.isfinite(values) | (np.abs(values) > limit.reshape(shape))
        if not bad.any():
            continue
        index = tuple(int(k) for k in np.argwhere(bad)[0])
        value = values[index]
        pair = _pair(ds, index, dims)
        count_bad = int(bad.sum())
        more = f" ({count_bad} values in all)" if count_bad > 1 else ""
        if not math.isfinite(value):
            reason = f"{name} [{pair}] is {value:g}{more}{origin}: not a number the {what} can use"
        else:
            lim = float(
                limit.reshape(shape)[
                    tuple(0 if s == 1 else k for s, k in zip(shape, index, strict=True))
                ]
            )
            reason = (
                f"{name} [{pair}] is {value:.4g}{more}{origin}: beyond any floating body "
                f"(|value| > {lim:.0e} in SI units)"
            )
        raise error(
            reason,
            hint="The file is damaged or not in SI units: check it with `cummins check`, "
            "repair or rerun the solver, or select the DOFs that are sound",
        )


def guard_state_space(
    a: Any, b: Any, c: Any, name: str = "the model", error: type[Exception] | None = None
) -> None:
    """Refuse a state-space model (a, b, c) with non-finite entries or entries beyond
    1e30 (no fluid-memory model of a floating body comes near), before LAPACK sees them."""
    from cummins.errors import FitError

    error = error or FitError
    for label, m in (("A", a), ("B", b), ("C", c)):
        arr = np.asarray(m, dtype=float)
        with np.errstate(invalid="ignore"):
            bad = ~np.isfinite(arr) | (np.abs(arr) > 1e30)
        if bad.any():
            index = tuple(int(k) for k in np.argwhere(bad)[0])
            raise error(
                f"{name}: matrix {label} holds {arr[index]:g} at {index}, which no "
                "fluid-memory model can hold",
                hint="Refit the model from sound data (cummins fit)",
            )


def guard_radiation_model(model, error: type[Exception] | None = None) -> None:
    """:func:`guard_state_space` on every coupling of a ``RadiationModel`` (named by its DOF
    pair) and a finite, physically scaled A∞."""
    from cummins.errors import FitError

    error = error or FitError
    dofs = list(model.dofs)
    for k in model.couplings:
        a, b = dofs[k.influenced], dofs[k.radiating]
        pair = a if a == b else f"{a}-{b}"
        guard_state_space(k.a, k.b, k.c, f"the model of coupling {pair}", error)
    for block in getattr(model, "blocks", ()):
        name = "-".join(dofs[d] for d in block.dofs)
        guard_state_space(block.a, block.b, block.c, f"the model of the block {name}", error)
    a_inf = np.asarray(model.added_mass_inf, dtype=float)
    for i, row in enumerate(dofs):
        for j, col in enumerate(dofs):
            value = a_inf[i, j]
            if not (math.isfinite(value) and abs(value) <= coefficient_limit(row, col)):
                pair = row if i == j else f"{row}-{col}"
                raise error(
                    f"the model's A-infinity [{pair}] is {value:g}: not a usable added mass",
                    hint="Refit the model from sound data (cummins fit)",
                )


def guard_fit_arguments(
    *,
    r2: Any = None,
    r2_coupling: Any = None,
    threshold: Any = None,
    omega_min: Any = None,
    omega_max: Any = None,
) -> None:
    """The targets and ranges of a fit: R² in (0, 1) (1 is never reached: the search would
    end at the highest order), a threshold in [0, 1), frequencies finite and >= 0."""
    for name, value in (("r2", r2), ("r2_coupling", r2_coupling)):
        if value is not None:
            in_range(
                value,
                name,
                low=0.0,
                high=1.0,
                low_open=True,
                high_open=True,
                hint="Give a target R-squared such as 0.99",
            )
    if threshold is not None:
        in_range(threshold, "threshold", low=0.0, high=1.0, high_open=True)
    for name, value in (("omega_min", omega_min), ("omega_max", omega_max)):
        if value is not None:
            non_negative(value, name, "rad/s")
    if omega_min is not None and omega_max is not None and not omega_max > omega_min:
        raise ArgumentError(
            f"omega_max ({omega_max:g} rad/s) must be above omega_min ({omega_min:g} rad/s)"
        )


def guard_finite(
    values: Any,
    name: str,
    error: type[Exception] | None = None,
    dofs: Iterable[str] | None = None,
    limit: float = 1e30,
) -> None:
    """Refuse an array (…, n, n) of coefficients with a non-finite entry or one beyond
    ``limit``: the message names the DOF pair when ``dofs`` are given."""
    from cummins.errors import FitError

    error = error or FitError
    arr = np.asarray(values, dtype=float)
    with np.errstate(invalid="ignore"):
        bad = ~np.isfinite(arr) | (np.abs(arr) > limit)
    if not bad.any():
        return
    index = tuple(int(k) for k in np.argwhere(bad)[0])
    labels = list(dofs) if dofs is not None else []
    where = str(index)
    if labels and arr.ndim >= 2 and arr.shape[-1] == arr.shape[-2] == len(labels):
        i, j = index[-2], index[-1]
        where = labels[i] if i == j else f"{labels[i]}-{labels[j]}"
        if arr.ndim > 2:
            where += f" (sample {index[:-2] if arr.ndim > 3 else index[0]})"
    raise error(
        f"{name} [{where}] is {arr[index]:g}: not a value the computation can use",
        hint="Check the data with `cummins check`; repair them or select the sound DOFs",
    )
