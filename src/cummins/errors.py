"""The exception family of cummins.

Every error that cummins raises on purpose derives from :class:`CumminsError`, so a
script can catch them all with one ``except``. Messages say *what* is wrong, *where*
(file and line, quantity, DOF pair or frequency) and *what to do*.
"""

from __future__ import annotations

import os


class CumminsError(Exception):
    """Base class of all errors raised by cummins on purpose.

    ``hint`` (keyword) says what to do; it is appended to the message.
    """

    def __init__(self, message: str = "", *args: object, hint: str | None = None) -> None:
        self.hint = hint
        super().__init__(f"{message}. {hint}" if hint else message, *args)


class HydroDataError(CumminsError, ValueError):
    """Hydrodynamic data that cannot be read or is not physically usable.

    Parameters
    ----------
    message
        What is wrong, in plain language.
    path
        The file at fault, if any.
    line
        1-based line number in ``path``, if known.
    quantity
        The quantity at fault (e.g. ``"added_mass[Heave, Pitch] at omega=0.52 rad/s"``).
    hint
        What the user can do about it.

    Examples
    --------
    >>> str(HydroDataError("expected 4 numbers, found 3", path="ship.1", line=12))
    'ship.1, line 12: expected 4 numbers, found 3'
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | os.PathLike[str] | None = None,
        line: int | None = None,
        quantity: str | None = None,
        hint: str | None = None,
    ) -> None:
        self.message = message
        self.path = None if path is None else os.fspath(path)
        self.line = line
        self.quantity = quantity
        self.hint = hint
        super().__init__(self._format())

    def _format(self) -> str:
        where = []
        if self.path is not None:
            where.append(self.path)
        if self.line is not None:
            where.append(f"line {self.line}")
        text = ", ".join(where)
        text = f"{text}: {self.message}" if text else self.message
        if self.quantity:
            text += f" ({self.quantity})"
        if self.hint:
            text += f". {self.hint}"
        return text

    def __reduce__(self):  # keep the keyword arguments through pickling (Dask, multiprocessing)
        return (
            _rebuild_hydro_data_error,
            (self.message, self.path, self.line, self.quantity, self.hint),
        )


def _rebuild_hydro_data_error(message, path, line, quantity, hint) -> HydroDataError:
    return HydroDataError(message, path=path, line=line, quantity=quantity, hint=hint)


class FitError(CumminsError):
    """A model could not be identified to the required standard (stable, accurate)."""


class SimulationError(CumminsError):
    """A time-domain simulation failed (diverged, bad input)."""


class IdentificationError(CumminsError):
    """Coefficients cannot be identified from the records given (too short, no excitation,
    a DOF or term the records do not hold)."""


class ArgumentError(CumminsError, ValueError):
    """A value given by the user (a function argument or a command-line option) is not
    usable: not finite, out of range, of the wrong unit or too large to compute.

    The message names the argument, the value given, the accepted range with its unit,
    and what to pass instead. The command line prints it on one line and exits with
    status 2, as for any other usage error.
    """


class CumminsWarning(UserWarning):
    """Base class of the warnings cummins issues on purpose."""


class HydroDataWarning(CumminsWarning):
    """The data were read, but part of them is damaged or suspect (a sibling file that
    cannot be parsed, a table shorter than its header announces …).

    Readers also record the text in the dataset's ``read_warnings`` attribute, so that
    ``cummins check`` repeats it as a finding long after the warning scrolled by.
    """


class AssumptionWarning(CumminsWarning):
    """A value the result depends on was assumed, not read (a density, a depth, a length
    scale, what a restoring matrix holds): the text names it and how to give it."""


class StaticInstabilityWarning(CumminsWarning):
    """The restoring matrix has a negative eigenvalue: the body has no stable equilibrium
    to oscillate about (:func:`cummins.restoring.static_instability`)."""


class OutputExistsError(CumminsError, FileExistsError):
    """Refusing to overwrite an existing file without ``force=True`` / ``--force``."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = os.fspath(path)
        super().__init__(
            f"{self.path} exists; refusing to overwrite it. "
            "Choose another name or pass force=True (--force on the command line)."
        )


def check_writable(path: str | os.PathLike[str], force: bool) -> None:
    """Raise :class:`OutputExistsError` if ``path`` exists and ``force`` is false."""
    if not force and os.path.exists(path):
        raise OutputExistsError(path)
