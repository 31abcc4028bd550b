"""Reduction to a motion tolerance: the fewest states whose motions stay near the data's.

``tol`` of :func:`~cummins.radiation.reduce.reduce_radiation_model` bounds the change of the
DOF-scaled K(jω); what a user checks is the motions, and near a lightly damped resonance
a small change of K is a large change of the RAO (the tanker at ``tol`` 0.02: 0.54 →
1.43 % of each DOF's peak motion; the OC3 Hywind spar 0.14 → 2.99 %). Here the block
reduction is run at the tolerances of :data:`MOTION_SEARCH`, by bisection (the motion
error grows with the tolerance), and the largest whose motion error is within
``motion_tol`` is kept. The error is the one the fit measured the full model by
(:func:`cummins.radiation.fit.motion.fit_motion_error`: 2 % of critical damping, the
excitation at up to four headings, each DOF's peak, on the frequencies the fit kept — its
suspect frequencies left out), so that the unreduced model scores the fit's own
``motion_error`` (the AQWA PEND hull: 0.40 %, where the scoreboard's
:func:`~cummins.radiation.fit.scorecard.motion_rao_error` over every frequency, the spikes
the fit left out included, says 1.73 %).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import xarray as xr

from cummins.errors import FitError
from cummins.radiation.fit.motion import JoinedMotion, fit_motion_error
from cummins.radiation.model import RadiationModel
from cummins.radiation.reduce.radiation_model import reduce_radiation_model

#: The tolerances of the block reduction tried, largest (fewest states) first.
MOTION_SEARCH = (0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001)


def reduce_to_motion_tolerance(
    model: RadiationModel,
    data: xr.Dataset,
    motion_tol: float = 0.01,
    *,
    method: str = "lyapunov",
    progress: Callable[[str], object] | None = None,
    joined: JoinedMotion | None = None,
) -> RadiationModel:
    """The reduced model with the fewest states whose motions are within ``motion_tol``.

    Parameters
    ----------
    model
        A model of common-pole blocks (the default fit).
    data
        The data it was fitted to, with the inertia, the restoring and the excitation.
    motion_tol
        Largest motion-RAO error, a fraction of each DOF's peak motion (0.01: 1 %).
    method
        Balanced truncation method of the blocks.
    progress
        Called with a short message at each tolerance tried and each block reduced.
    joined
        The joined system a joined fit aimed at (``Assembly.joined_motion()``, with
        ``data`` the assembly's): its motions are the ones compared.

    Returns
    -------
    RadiationModel
        The reduction at the largest tolerance of :data:`MOTION_SEARCH` (found by
        bisection) that meets ``motion_tol`` and fails nothing the unreduced model did
        not; ``attrs`` hold ``reduction_tol`` (the tolerance used), ``motion_error`` and
        ``motion_error_unreduced``. When none does, the unreduced model, with a note
        saying so; when the unreduced model's own motions are further than
        ``motion_tol`` from the data's, the same, with a failure (no reduction can meet
        it).

    Raises
    ------
    FitError
        A per-coupling model (give ``tol`` or ``order``), or ``motion_tol`` outside (0, 1).
    HydroDataError
        Data without inertia, restoring or excitation.

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.demo_dataset()
    >>> small = reduce_to_motion_tolerance(cummins.fit_radiation(ds), ds, 0.02)
    >>> small.attrs["motion_error"] <= 0.02
    True
    """
    if not 0.0 < motion_tol < 1.0:
        raise FitError(f"motion_tol = {motion_tol} is not a fraction between 0 and 1")
    if not model.blocks:
        raise FitError(
            "a motion tolerance reduces a model of common-pole blocks (the default fit)",
            hint="reduce a per-coupling model with tol or order, or refit with method='vf'",
        )
    unreduced = fit_motion_error(data, model, joined)[0]  # HydroDataError without the inertia
    known = set(model.attrs.get("failures", []))
    base = {"motion_error_unreduced": unreduced, "motion_tol": motion_tol}
    if unreduced > motion_tol:
        failure = (
            f"the unreduced model's motions are already {unreduced:.2%} of their peak from "
            f"the data's (motion_tol {motion_tol:.2%}): no reduction can meet it"
        )
        return _noted(model, {**base, "motion_error": unreduced}, failure=failure)

    say = progress or (lambda message: None)

    def within(tol: float) -> RadiationModel | None:
        say(f"trying tol {tol:g}")
        reduced = reduce_radiation_model(model, tol=tol, method=method, data=data, progress=say)
        if set(reduced.attrs.get("failures", [])) - known:
            return None
        error = fit_motion_error(data, reduced, joined)[0]
        if error > motion_tol:
            return None
        attrs = {**reduced.attrs, **base, "reduction_tol": tol, "motion_error": error}
        return replace(reduced, attrs=attrs)

    # bisection over the tolerances (the motion error grows with them): the largest that
    # meets motion_tol in three or four reductions instead of eight
    lo, hi, best = 0, len(MOTION_SEARCH), None
    while lo < hi:
        mid = (lo + hi) // 2
        found = within(MOTION_SEARCH[mid])
        if found is None:
            lo = mid + 1
        else:
            best, hi = found, mid
    if best is not None:
        return best
    note = (
        f"no reduction down to tol {MOTION_SEARCH[-1]:g} keeps the motions within "
        f"{motion_tol:.2%} of the data's: the model is kept as it was"
    )
    return _noted(model, {**base, "motion_error": unreduced}, note=note)


def _noted(model, attrs, *, failure: str | None = None, note: str | None = None):
    """The unreduced model with ``attrs`` and a failure or a data note added."""
    out = {**model.attrs, **attrs}
    if failure:
        out["failures"] = [*model.attrs.get("failures", []), failure]
    if note:
        out["data_notes"] = [*model.attrs.get("data_notes", []), note]
    return replace(model, attrs=out)
