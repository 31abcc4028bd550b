"""The library's hints said as a study's keys: where a message tells the user of a
command to give ``--rho``, ``--water-depth``, ``--heading`` or
``--restoring-includes-weight``, a batch study's log names the study's key (``rho``,
``water_depth``, ``grid.heading``, ``restoring_includes_weight``), the option it has.

The library writes each such hint from one constant
(:data:`cummins.io._common.CONSTANT_CHOICES`,
:data:`cummins.seakeeping.headings.HEADING_CHOICE`,
:data:`cummins.restoring.INCLUDES_WEIGHT_CHOICE`); :func:`study_wording` replaces it,
:func:`study_warnings` re-issues the warnings raised while a study is prepared or a case
runs in those words. A case runs in a worker process: :func:`recorded_warnings` keeps its
warnings with its results and :func:`reissue_warnings` shows them where the study runs.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from cummins.io._common import CONSTANT_CHOICES
from cummins.restoring import INCLUDES_WEIGHT_CHOICE, INSTABILITY_HINT
from cummins.seakeeping.headings import HEADING_CHOICE

#: The study's keys that choose a case's heading.
HEADING_KEYS = "the study's heading: grid.heading or a case's heading, deg"


def study_wording(text: str, source: Path | None = None) -> str:
    """``text`` with the command-line hints of :data:`CONSTANT_CHOICES` and
    :data:`HEADING_CHOICE` replaced by the keys of the study defined in ``source``."""
    for key, choice in CONSTANT_CHOICES.items():
        text = text.replace(choice, _key(key, source))
    text = text.replace(INCLUDES_WEIGHT_CHOICE, f"{_key('restoring_includes_weight', source)}: yes")
    text = text.replace(INSTABILITY_HINT, _instability_hint(source))
    return text.replace(HEADING_CHOICE, HEADING_KEYS)


def _instability_hint(source: Path | None) -> str:
    """:data:`~cummins.restoring.INSTABILITY_HINT` in the study's keys."""
    where = f" of {Path(source).name}" if source else ""
    return (
        "Check the centre of gravity and whether the restoring holds the weight's terms "
        f"(cummins info says where C came from; the keys center_of_gravity and "
        f"restoring_includes_weight{where}), or give the hinge or mooring that holds the body "
        "(external_stiffness); a negative PTO stiffness (a PTO's stiffness, pto_stiffness, "
        "reactive control) must stay smaller than the restoring it acts against"
    )


def _key(key: str, source: Path | None) -> str:
    """The study's ``key``, named with the file that defines the study."""
    return f"the key {key} of {Path(source).name}" if source else f"the study key {key}"


@contextmanager
def study_warnings(source: Path | None = None) -> Iterator[None]:
    """Re-issue the warnings raised inside (same category, same origin) in the words of
    the study defined in ``source`` (:func:`study_wording`), once the work inside ends
    (also with an error), each text from one place once; the caller's filters apply to
    them then."""
    caught: list[warnings.WarningMessage] = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            yield
    finally:
        seen: set[tuple] = set()
        for w in caught:
            text = str(w.message)
            if (text, w.category, w.filename, w.lineno) in seen:
                continue
            seen.add((text, w.category, w.filename, w.lineno))
            worded = study_wording(text, source)
            message = w.message
            if worded != text:
                try:
                    message = w.category(worded)
                except TypeError:  # a warning class built otherwise: as raised
                    message = w.message
            warnings.warn_explicit(message, w.category, w.filename, w.lineno)


#: The key of a case's results that carries its warnings from the worker.
WARNINGS_KEY = "_warnings"


@contextmanager
def recorded_warnings() -> Iterator[list[tuple[type[Warning], str]]]:
    """Record the warnings raised inside, each (category, text) once, instead of showing
    them: a case's worker sends them with its results (:data:`WARNINGS_KEY`) for
    :func:`reissue_warnings` to show where the study runs — the worker's own stderr
    would print each raw, with the path and line of the code, once per case."""
    out: list[tuple[type[Warning], str]] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield out
        finally:
            for w in caught:
                item = (w.category, str(w.message))
                if item not in out:
                    out.append(item)


def reissue_warnings(items: list[tuple[type[Warning], str]]) -> None:
    """Issue again the warnings :func:`recorded_warnings` kept (the command line shows
    each text once, as a one-line note)."""
    for category, text in items:
        warnings.warn(text, category, stacklevel=2)
