"""Checks of the numbers a user gives, before any work starts.

Every public function that takes a sea state, a duration, a time step, a count or a
tolerance checks it here, and the command line checks its options with the click types of
:mod:`cummins.cli_common` built on the same rules. A value that is not usable raises
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
            f"{name} must hold finite numbers{_unit(unit)}; value {index} is {_show(arr[where])}"
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
            hint="give a smaller time step or a longer duration",
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
        hint=f"shorten {names[0]} or lengthen {names[1]}",
    )
    return n_steps
