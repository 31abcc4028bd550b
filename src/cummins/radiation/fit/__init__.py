"""Identification of the fluid memory: one call fits every significant coupling.

:func:`fit_radiation` turns a ``HydroDB`` into a :class:`~cummins.radiation.model.RadiationModel`:

1. **Data**: frequencies flagged by :func:`cummins.repair.find_suspect_frequencies` on a
   DOF's own curves (irregular-frequency spikes, negative damping, an inconsistent first
   frequency) are left out of that DOF's couplings — each costs its own point, nothing
   above it — unless ``exclude_suspect`` is false; so is everything outside
   ``omega_min``…``omega_max``. What was left out is recorded. A pair with A_ij ≠ A_ji
   (or B) beyond 10 % is named in a warning (:func:`asymmetric_pairs`); a difference
   A_ij − A_ji constant over frequency (a panel mesh's) is kept in A∞
   (:func:`antisymmetric_added_mass`).
2. **Couplings**: the significant ones
   (:func:`cummins.radiation.retardation.significant_couplings`);
   negligible couplings (relative threshold) are left out and reported; a symmetric
   pair K_ij = K_ji is fitted once, to the symmetric part of the data, and used twice.
3. **A∞**: the solver's ω = ∞ row when present and consistent with the finite
   frequencies (:func:`inconsistent_added_mass_inf`); otherwise estimated jointly with
   each coupling's model (``"fit"``, Perez & Fossen's idea), regularised towards
   Ogilvie's Kramers–Kronig estimate within its spread, or taken from Ogilvie's relation
   alone (``"ogilvie"``).
4. **What the fit aims at**: with the inertia and the restoring in the data, the
   motions (``weighting="motion"``, :mod:`cummins.radiation.fit.motion`): every error δK_ij(ω)
   weighs its first-order effect on the motion RAOs (δX = −H jω δK X, Falnes (2002)
   eq. 5.8), besides the R² of A and of B. Without them, the R² alone (``"uniform"``).
5. **The model** (``method="vf"``, default): the DOFs that radiate into each other form
   blocks (surge–heave–pitch and sway–roll–yaw of a ship; every DOF of interacting
   bodies), and the couplings of a block share their poles (:mod:`cummins.radiation.fit.vector`:
   vector fitting, Gustavsen & Semlyen (1999)), at the smallest number of poles whose R²
   of A and of B reach the targets (default 0.99 on the diagonal, 0.97 off it) and
   whose motion error is within 80 % of ``motion_tol``; each block is made passive as
   fitted, by the smallest weighted change of its residues, and realized with one state
   per rank of each residue matrix. With ``method="fd"``, ``"realization"`` or
   ``"prony"`` each coupling gets its own model instead
   (:mod:`cummins.radiation.fit.frequency`, :mod:`cummins.radiation.fit.realization`), at the
   smallest order whose R² reaches the target and whose share of the motion error is within its
   budget, up to ``max_order``; diagonal models are positive real.
6. **MIMO** (per-coupling methods): the assembled model made passive
   (:func:`make_passive`), then up to three rounds refit the couplings that carry the
   motion error of the whole model until it is within ``motion_tol`` (1 %) of each
   motion's peak. ``attrs["failures"]`` lists what misses a target
   (:func:`fit_failures`).

The stages are modules, and functions a user can call: the options
(:mod:`cummins.radiation.fit.options`, :class:`FitOptions` and its presets), the data selection
(:mod:`cummins.radiation.fit.data`, :func:`prepare_fit`), the common-pole identification
(:mod:`cummins.radiation.fit.blocks`, :func:`fit_blocks`, on :mod:`cummins.radiation.fit.vector`),
the per-coupling identification (:mod:`cummins.radiation.fit.couplings`,
:func:`fit_per_coupling`, on :mod:`cummins.radiation.fit.frequency` and
:mod:`cummins.radiation.fit.realization`) and its MIMO stage (:mod:`cummins.radiation.fit.mimo`).

7. **Metrics** per coupling (:mod:`cummins.radiation.fit.metrics`); the scoreboard of a model
   against its data, independent of the fit: :mod:`cummins.radiation.fit.scorecard`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import xarray as xr

from cummins.errors import FitError
from cummins.radiation.fit.blocks import fit_blocks
from cummins.radiation.fit.causal_inf import with_causal_inf
from cummins.radiation.fit.couplings import fit_coupling, fit_per_coupling
from cummins.radiation.fit.data import (
    FitData,
    FitInput,
    antisymmetric_added_mass,
    asymmetric_pairs,
    fit_data,
    inconsistent_added_mass_inf,
    model_fit_data,
    prepare_fit,
    range_cut_failures,
)
from cummins.radiation.fit.frequency import FrequencyFit, fit_frequency_domain
from cummins.radiation.fit.mimo import (
    TIE,
    failure_targets,
    fit_failures,
    make_passive,
    refreshed_coupling,
    with_motion_note,
)
from cummins.radiation.fit.motion import JoinedMotion
from cummins.radiation.fit.motion_refinement import refined_on_motions, refinement_wanted
from cummins.radiation.fit.options import (
    ADDED_MASS_INF,
    DEFAULT,
    MAX_FIXED_ORDER,
    MAX_ORDER,
    METHODS,
    MOTION_ACCURACY,
    MOTION_AIM,
    MOTION_FAILURE,
    MOTION_TOL,
    PASSIVITY_OPTIONS,
    PREVIOUS_DEFAULT,
    WEIGHTINGS,
    FitOptions,
)
from cummins.radiation.model import RadiationModel

__all__ = [
    "ADDED_MASS_INF",
    "DEFAULT",
    "MAX_FIXED_ORDER",
    "MAX_ORDER",
    "METHODS",
    "MOTION_ACCURACY",
    "MOTION_AIM",
    "MOTION_FAILURE",
    "MOTION_TOL",
    "PASSIVITY_OPTIONS",
    "PREVIOUS_DEFAULT",
    "TIE",
    "WEIGHTINGS",
    "FitData",
    "FitError",
    "FitInput",
    "FitOptions",
    "FrequencyFit",
    "antisymmetric_added_mass",
    "asymmetric_pairs",
    "failure_targets",
    "fit_blocks",
    "fit_coupling",
    "fit_data",
    "fit_failures",
    "fit_frequency_domain",
    "fit_per_coupling",
    "fit_radiation",
    "inconsistent_added_mass_inf",
    "make_passive",
    "model_fit_data",
    "prepare_fit",
    "range_cut_failures",
    "refreshed_coupling",
    "with_motion_note",
]


def fit_radiation(
    ds: xr.Dataset,
    options: FitOptions | None = None,
    *,
    progress: Callable[[str], None] | None = None,
    joined: JoinedMotion | None = None,
    **overrides: Any,
) -> RadiationModel:
    """Identify state-space models of all significant couplings of the fluid memory.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed (zero speed: symmetric couplings).
    options
        A :class:`~cummins.radiation.fit.options.FitOptions` (default :data:`DEFAULT`; presets
        :data:`MOTION_ACCURACY`, :data:`PREVIOUS_DEFAULT`).
    progress
        Called with a short message before each coupling or block.
    joined
        The mechanics of bodies joined by joints and power take-offs
        (:class:`~cummins.radiation.fit.motion.JoinedMotion`): the motion target and
        weights are those of the joined system's motions (``attrs["motions_of"]``), not
        of free bodies; :func:`cummins.vessel.vessel_from_hydrodb` passes its system's.
    **overrides
        Fields of :class:`~cummins.radiation.fit.options.FitOptions` that override ``options``:
        ``method`` (``"vf"`` default, ``"fd"``, ``"realization"``, ``"prony"``), ``r2``
        (0.99), ``r2_coupling`` (0.97), ``max_order``, ``orders``, ``threshold`` (0.01),
        ``added_mass_inf`` (``"auto"``), ``omega_min``, ``omega_max``,
        ``exclude_suspect`` (True), ``passivity`` (``"mimo"``), ``weighting``
        (``"auto"``), ``motion_tol`` (0.01), ``r2_kernel`` (0.9: R² of K(t) of each
        modelled diagonal term against the data's, with its damping tail). With
        ``method="vf"`` a block is made passive as a whole when it is fitted
        (``passivity="mimo"``) or not at all.

    Returns
    -------
    RadiationModel
        With per-coupling ``metrics`` (per pair of each block for ``"vf"``:
        ``model.modelled``) and ``attrs`` recording the data used, ``mimo_passive``,
        ``motion_error`` and ``failures``.

    Raises
    ------
    FitError
        An unknown or out-of-range option, or a coupling or block that cannot be fitted
        by a stable model.

    Examples
    --------
    >>> import cummins
    >>> model = cummins.fit_radiation(cummins.demo_dataset())
    >>> model.is_stable()
    True
    >>> from cummins.radiation.fit import MOTION_ACCURACY
    >>> accurate = cummins.fit_radiation(cummins.demo_dataset(), MOTION_ACCURACY)
    >>> accurate.total_order > model.total_order
    True
    """
    start = time.perf_counter()
    options = (options or DEFAULT).with_changes(**overrides).checked()
    say = progress or (lambda message: None)
    inp = prepare_fit(ds, options, joined)
    if options.method == "vf":
        plain = options.with_changes(refine_motions=False)
        first, again = {}, {}  # the order searches of the fit and of its refit
        model = fit_blocks(inp, plain, say, first)
        # motions that call for the refinement: made in the refit with A∞ estimated, when
        # there is one (RM3: a whole fit of the blocks fewer)
        causal = options if refinement_wanted(options, model) else plain
        model = with_causal_inf(inp, causal, model, lambda *a: fit_blocks(*a, say, again))
        estimated = "added_mass_inf_estimated" in model.attrs
        if not (estimated and causal is options):
            searched = again if estimated else first
            model = refined_on_motions(
                inp, options, model, lambda *a: fit_blocks(*a, say, searched, only_refined=True)
            )
    else:
        model = fit_per_coupling(inp, options, say)
    return replace(model, attrs={**model.attrs, "elapsed_s": time.perf_counter() - start})
