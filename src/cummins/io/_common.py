"""Pieces shared by the readers: physical constants, units of nondimensional data."""

from __future__ import annotations

import os
import warnings
from collections.abc import Sequence

import numpy as np

from cummins.errors import AssumptionWarning, HydroDataError, HydroDataWarning

#: Sea-water density and gravity used when a nondimensional file does not record them.
DEFAULT_RHO = 1025.0
DEFAULT_G = 9.81

#: How the messages of the library tell a user to give a constant the files lack: the
#: command-line option and the keyword of :func:`cummins.read` (a batch study says its
#: own key instead: :func:`cummins.studies.wording.study_wording`).
CONSTANT_CHOICES = {
    "rho": "--rho (rho=)",
    "g": "--g (g=)",
    "ulen": "--ulen (ulen=)",
    "water_depth": "--water-depth M (water_depth=)",
}


def resolve_constant(
    name: str,
    given: float | None,
    in_file: float | None,
    default: float | None,
    *,
    unit: str,
    path: str | os.PathLike[str],
    history: list[str],
    dimensional: bool,
    source: str | None = None,
) -> float:
    """Decide the value of ρ, g or a length scale, and record where it came from.

    Parameters
    ----------
    name
        ``"rho"``, ``"g"`` or ``"ulen"``, as the keyword the user passes.
    given
        Value passed by the user, or ``None``.
    in_file
        Value recorded in the file(s), or ``None``.
    default
        Value used when neither is known; ``None`` makes that an error.
    dimensional
        True when the file's numbers are already dimensional: then a given value
        that differs from the file's one is an error, since it cannot change the data.
        For nondimensional data the given value wins (with a note).
    source
        Where ``in_file`` comes from when the file does not record it (such as a
        program's fixed constant), for the history; by default the file.
    """
    if given is not None:
        given = float(given)
        if not np.isfinite(given) or given <= 0:
            raise HydroDataError(f"{name} must be a positive number, got {given!r}", path=path)
    if in_file is not None and given is not None and not np.isclose(given, in_file, rtol=1e-6):
        if dimensional:
            raise HydroDataError(
                f"{name} = {given:g} {unit} was given but the file records {in_file:g} {unit}",
                path=path,
                hint=f"the data are dimensional, computed with {name} = {in_file:g}; "
                f"drop the {name} option",
            )
        where = "the file records" if source is None else f"{source}:"
        history.append(f"{name} = {given:g} {unit} (given; {where} {in_file:g} {unit})")
        return given
    if in_file is not None:
        history.append(f"{name} = {in_file:g} {unit} ({source or 'from the file'})")
        return float(in_file)
    if given is not None:
        history.append(f"{name} = {given:g} {unit} (given)")
        return given
    if default is None:
        raise HydroDataError(
            f"the file does not record {name}",
            path=path,
            hint=f"pass {name}= (--{name} on the command line)",
        )
    history.append(
        f"{name} = {default:g} {unit} (not recorded in the file: default; pass {name}= to change)"
    )
    assume(
        f"{name} is not recorded in the files read: {default:g} {unit} assumed; give "
        f"{CONSTANT_CHOICES.get(name, f'--{name} ({name}=)')} if the run used another value",
        path=path,
    )
    return default


#: Attribute of a dataset whose ``water_depth`` was not recorded by its files (deep water
#: assumed): :func:`cummins.hydrodb.water_depth` warns where a result depends on it.
DEPTH_ASSUMED = "water_depth_assumed"


def assume(message: str, *, path: str | os.PathLike[str] | None) -> None:
    """An :class:`~cummins.errors.AssumptionWarning` naming the file: a value a result
    depends on was assumed, not read (the reader also writes it to ``history``)."""
    where = f"{os.path.basename(os.fspath(path))}: " if path else ""
    warnings.warn(AssumptionWarning(where + message), stacklevel=3)


def resolve_rho_g(
    rho: float | None,
    g: float | None,
    file_rho: float | None,
    file_g: float | None,
    *,
    path: str | os.PathLike[str],
    history: list[str],
    dimensional: bool,
    defaults: bool = True,
    sources: tuple[str | None, str | None] = (None, None),
) -> tuple[float, float]:
    """Water density and gravity of a file, with :func:`resolve_constant` for each.

    ``defaults=False`` makes a value that is neither given nor in the file an error
    instead of falling back on :data:`DEFAULT_RHO` / :data:`DEFAULT_G`; ``sources`` are
    the ``source`` of ρ and of g (:func:`resolve_constant`).
    """
    common = {"path": path, "history": history, "dimensional": dimensional}
    rho_v = resolve_constant(
        "rho",
        rho,
        file_rho,
        DEFAULT_RHO if defaults else None,
        unit="kg/m^3",
        source=sources[0],
        **common,
    )
    g_v = resolve_constant(
        "g", g, file_g, DEFAULT_G if defaults else None, unit="m/s^2", source=sources[1], **common
    )
    return rho_v, g_v


def rotation_flags(n: int, modes: Sequence[int] | None = None) -> np.ndarray:
    """1 for the rotational DOFs (Roll, Pitch, Yaw of each body), else 0, for n DOFs.

    ``modes`` gives the number of modes of each body (six rigid-body modes, then the
    generalized modes of that body); by default six per body (one body when n is not a
    multiple of six). Generalized modes (7, 8 … of a body) count as translations: WAMIT
    normalizes them like modes 1–3 (WAMIT User Manual v7, ch. 8, generalized modes:
    the mode amplitude has the dimension of length).
    """
    if modes is None:
        modes = [6] * (n // 6) if n % 6 == 0 and n else [n]
    modes = [int(m) for m in modes]
    if sum(modes) != n:
        raise HydroDataError(f"{n} DOFs do not split into bodies of {modes} modes")
    flags = [1 if 3 <= k < 6 else 0 for m in modes for k in range(m)]
    return np.asarray(flags, dtype=int)


def length_exponents(n: int, offset: int, modes: Sequence[int] | None = None) -> np.ndarray:
    """Exponent of the length scale L for each (i, j) entry of an n×n matrix.

    WAMIT-style nondimensionalization scales an entry by L^(offset + a_i + a_j), where
    a = 0 for translations and generalized modes, 1 for rotations (see
    :func:`rotation_flags`). For added mass ``offset`` is 3 (L³, L⁴, L⁵); for
    hydrostatics 2 (L², L³, L⁴).
    """
    rot = rotation_flags(n, modes)
    return offset + rot[:, None] + rot[None, :]


def force_exponents(n: int, offset: int, modes: Sequence[int] | None = None) -> np.ndarray:
    """Exponent of L for each entry of a force vector: ``offset`` + 1 for moments."""
    return offset + rotation_flags(n, modes)


def warn_damage(
    message: str,
    *,
    path: str | os.PathLike[str] | None,
    notes: list[str],
    line: int | None = None,
    hint: str | None = None,
) -> str:
    """Report damage a reader could work around: a :class:`HydroDataWarning` now, and
    the same text appended to ``notes``, which the reader stores as the dataset's
    ``read_warnings`` attribute (``make_hydrodb(read_warnings=notes)``) so that
    ``cummins check`` repeats it as a finding.

    Use it only where the rest of the data is usable and what was lost is said in the
    message (never a silent zero or a silently dropped variable); damage that leaves
    the data unusable is a :class:`~cummins.errors.HydroDataError`.

    Returns the text, formatted like a ``HydroDataError`` (file, line, message, hint).
    """
    text = str(HydroDataError(message, path=path, line=line, hint=hint))
    warnings.warn(HydroDataWarning(text), stacklevel=3)
    notes.append(text)
    return text
