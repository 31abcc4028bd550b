"""The options of an identification: one frozen :class:`FitOptions`, and its presets.

:func:`cummins.radiation.fit.fit_radiation` takes a ``FitOptions`` and/or keyword overrides of its
fields; the presets are named instances (:data:`DEFAULT`, :data:`MOTION_ACCURACY`,
:data:`PREVIOUS_DEFAULT`). A ``FitOptions`` is also a read-only mapping of the fields it
sets away from the defaults, so that ``fit_radiation(ds, **MOTION_ACCURACY)`` and
``{**preset, "r2": 0.999}`` keep working.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, fields, replace
from typing import Any

from cummins.errors import FitError
from cummins.validation import guard_fit_arguments

METHODS = ("vf", "fd", "realization", "prony")
PASSIVITY_OPTIONS = ("mimo", "diagonal", "none")
ADDED_MASS_INF = ("auto", "data", "fit", "ogilvie")
WEIGHTINGS = ("auto", "motion", "response", "uniform")
#: How a pair with A_ij ≠ A_ji is fitted (:mod:`cummins.radiation.fit.reciprocity`).
RECIPROCITY_OPTIONS = ("auto", "average", "as-given")
#: Default ``max_order`` per method: the number of common poles of a block (``"vf"``),
#: the order of one coupling otherwise.
MAX_ORDER = {"vf": 20, "fd": 10, "realization": 10, "prony": 10}
#: Default largest relative motion error of a fit (``motion_tol``): the scoreboard's 1 %
#: (issue 16). A fit above it is reported as a failure (``attrs["failures"]``).
MOTION_TOL = 0.01
#: A motion error above MOTION_FAILURE × motion_tol makes the fit a failure; above
#: motion_tol only, a note.
MOTION_FAILURE = 2.0
#: The order search aims at this fraction of ``motion_tol``: room for the frequencies
#: the fit does not see (suspect points, the data beyond the fitted range).
MOTION_AIM = 0.8
#: Default target R² of K(t) of each modelled diagonal term (issue 31): K(t) weighs the
#: damping at every frequency alike (Parseval), beyond the data too, so it measures that
#: the model decays there as the data's damping tail.
R2_KERNEL = 0.9
#: When the motions cannot judge a fit (the data lack the inertia or the restoring, or
#: the weighting is not by the motions), a diagonal term's R² of A or B below
#: UNJUDGED_R2 is a failure, as the R² of K(t) below R2_KERNEL is: nothing then shows that
#: what the model misses costs the motions nothing (with them, the motion error decides,
#: and such a block is a note). The ITI barge's heave, R² of A 0.58 over the range its
#: irregular frequencies spoil, is one; the same fit below them meets 0.99.
UNJUDGED_R2 = 0.9
#: Highest order a user may fix for a coupling: beyond it, a typing error, not a model.
MAX_FIXED_ORDER = 40


@dataclass(frozen=True)
class FitOptions(Mapping):
    """What an identification aims at and how (:func:`cummins.radiation.fit.fit_radiation`).

    Attributes
    ----------
    method
        ``"vf"`` (default): common poles per block of coupled DOFs, vector fitting
        (:mod:`cummins.radiation.fit.vector`); ``"fd"``: one frequency-domain model per coupling;
        ``"realization"`` (Kung/ERA on K(t)) or ``"prony"``, per coupling.
    r2
        Target R² of A(ω) and of B(ω) of each diagonal term.
    r2_coupling
        Target of the off-diagonal couplings (``None``: ``r2``).
    max_order
        Highest order tried: common poles of a block (``"vf"``, default 20), the order
        of one coupling otherwise (default 10); ``None``: the method's default.
    orders
        Fixed orders, ``{(i, j): n}`` with 0-based DOF indices; with ``"vf"`` the number
        of poles of the block holding the pair (the largest given for the block).
    threshold
        Couplings below this fraction of the diagonal terms are left out.
    added_mass_inf
        ``"auto"`` (the data's ω = ∞ row when present and consistent, else estimated;
        estimated for the DOFs whose added mass is far from causal with the row when
        their motions miss the target: :mod:`cummins.radiation.fit.causal_inf`),
        ``"data"`` (the row everywhere), ``"fit"`` (joint estimate, frequency domain) or
        ``"ogilvie"``.
    omega_min, omega_max
        Fitting range, rad/s.
    exclude_suspect
        Leave out the suspect frequencies, each costing its own point to the couplings of
        the DOFs whose curves it spoils; ``"above_first"``: the rule of the previous
        default, every frequency above the first suspect one left out too.
    passivity
        ``"mimo"`` (default): the model made passive; ``"diagonal"``: positive-real
        diagonal models only (per coupling; with ``"vf"`` as ``"none"``); ``"none"``:
        stability only.
    weighting
        ``"auto"``: ``"motion"`` when the data hold the inertia and the restoring (and
        the method is ``"vf"`` or ``"fd"``), else ``"uniform"``; ``"response"``: ω/|Z_ii|
        (per coupling only).
    motion_tol
        Largest relative motion error of the model, 2 % of critical damping (1 %).
    reciprocity
        ``"auto"`` (default): a block's couplings are fitted as given, K_ij ≠ K_ji, where
        the data's reciprocal part alone misses the motion aim (without the inertia, no
        motions: the reciprocal part, and a note), else to the reciprocal part
        ½(X_ij + X_ji);
        ``"average"``: always the reciprocal part; ``"as-given"``: every pair that is
        not reciprocal (:mod:`cummins.radiation.fit.reciprocity`; ``"vf"`` only).
    r2_kernel
        Target R² of K(t) of each modelled diagonal term against the data's K(t) (with
        its damping tail beyond the last frequency: the model must decay as the data's
        tail); ``None``: not a target.
    refine_motions
        ``None`` (default): when the fit's motions miss their target ``motion_tol``, each
        block that misses its motion aim after the order search has its residues refined
        on the motion RAOs themselves, passive at every step
        (:mod:`cummins.radiation.fit.motion_refinement`), at its number of common poles
        and at ``max_order``, aiming at the user's motions; a number of poles whose
        Gauss–Newton steps leave the block above the target is given up before its
        passivity enforcement (the enforcement only takes the motions further). A
        refined block is kept when its motions are nearer the data's and its R² of K(t)
        and damping beyond the data are no worse (its R² of A and B may fall: the
        motions judge them; ``"vf"`` only). WEC-Sim's RM3 3.73 → 0.39 % of the peak.
        ``True``: whenever the motions miss the aim (``MOTION_AIM × motion_tol``), and
        every number of poles enforced to the end (the closest passive one kept);
        ``False``: never.
    """

    method: str = "vf"
    r2: float = 0.99
    r2_coupling: float | None = 0.97
    max_order: int | None = None
    orders: Mapping[tuple[int, int], int] | None = None
    threshold: float = 0.01
    added_mass_inf: str = "auto"
    omega_min: float | None = None
    omega_max: float | None = None
    exclude_suspect: bool | str = True
    passivity: str = "mimo"
    weighting: str = "auto"
    motion_tol: float = MOTION_TOL
    reciprocity: str = "auto"
    r2_kernel: float | None = R2_KERNEL
    refine_motions: bool | None = None

    # ------------------------------------------------------------------ a mapping of
    # the fields set away from the defaults (``fit_radiation(ds, **preset)``)

    def _set(self) -> dict[str, Any]:
        default = _DEFAULTS
        return {
            f.name: getattr(self, f.name)
            for f in fields(self)
            if getattr(self, f.name) != getattr(default, f.name)
        }

    def __getitem__(self, key: str) -> Any:
        return self._set()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._set())

    def __len__(self) -> int:
        return len(self._set())

    __hash__ = None  # ``orders`` is a mapping

    # ------------------------------------------------------------------

    def with_changes(self, **changes: Any) -> FitOptions:
        """A copy with some fields changed; an unknown name is a :class:`FitError`."""
        known = {f.name for f in fields(self)}
        unknown = sorted(set(changes) - known)
        if unknown:
            raise FitError(
                f"unknown fit option(s) {', '.join(unknown)}; use {', '.join(sorted(known))}"
            )
        return replace(self, **changes)

    def checked(self) -> FitOptions:
        """The options validated (every value a :class:`FitError` naming it and what to
        use), with ``max_order`` resolved to the method's default."""
        guard_fit_arguments(
            r2=self.r2,
            r2_coupling=self.r2_coupling,
            threshold=self.threshold,
            omega_min=self.omega_min,
            omega_max=self.omega_max,
        )
        for name, value, allowed in (
            ("method", self.method, METHODS),
            ("weighting", self.weighting, WEIGHTINGS),
            ("passivity option", self.passivity, PASSIVITY_OPTIONS),
            ("reciprocity option", self.reciprocity, RECIPROCITY_OPTIONS),
        ):
            if value not in allowed:
                raise FitError(f"unknown {name} {value!r}; use one of {', '.join(allowed)}")
        if self.refine_motions not in (None, True, False):
            raise FitError(
                f"refine_motions is {self.refine_motions!r}: use None (when the motions "
                "miss their target), True or False"
            )
        if self.r2_kernel is not None and not 0.0 < self.r2_kernel < 1.0:
            raise FitError(f"r2_kernel is {self.r2_kernel}: use a value between 0 and 1, or None")
        max_order = MAX_ORDER[self.method] if self.max_order is None else self.max_order
        if max_order < 2:
            raise FitError(
                f"max_order is {max_order}: a radiation model needs at least 2 states "
                "(a zero at s = 0 and relative degree 1)"
            )
        for pair, n in (self.orders or {}).items():
            if not 2 <= n <= MAX_FIXED_ORDER:
                raise FitError(
                    f"the order fixed for coupling {pair} is {n}: use 2 to {MAX_FIXED_ORDER}"
                )
        if self.added_mass_inf not in ADDED_MASS_INF:
            raise FitError(
                f"unknown added_mass_inf option {self.added_mass_inf!r}; use one of "
                f"{', '.join(ADDED_MASS_INF)}"
            )
        return replace(self, max_order=max_order)

    @property
    def coupling_target(self) -> float:
        """The R² target off the diagonal."""
        return self.r2 if self.r2_coupling is None else self.r2_coupling


_DEFAULTS = FitOptions()

#: The default identification.
DEFAULT = _DEFAULTS
#: For simulations that must reproduce the frequency-domain RAOs of the data more
#: closely than the default (``cummins simulate --accurate``): a motion error within
#: 0.2 % of each DOF's peak instead of 1 %. Measured by the scoreboard
#: (cummins.radiation.fit.scorecard, 2 % critical damping): MSS tanker 0.14 % at 51 states
#: (default 0.54 % at 42), WEC-Sim sphere 0.21 % at 30 (0.66 % at 22); on the supply
#: vessel 0.29 % at 50 (default 0.30 % at 44): where passivity costs the fits made for the
#: tighter target more than the default's (its heave-pitch block), the default's block is
#: kept and a note says so. Its motions missing 0.2 %, the default's refinement on the
#: motions runs (``refine_motions``; 2026-12-06): the supply vessel 0.24 → 0.16 % (48
#: states), the WEC-Sim sphere 0.29 → 0.19 % (31 → 40 states), +0.03–0.05 s.
MOTION_ACCURACY = FitOptions(motion_tol=0.002)
#: The default identification before issue 16 (per coupling, uniform weighting, R²
#: targets only, every frequency above the first suspect one left out), for comparisons
#: (benchmarks/bench_identification.py).
PREVIOUS_DEFAULT = FitOptions(method="fd", weighting="uniform", exclude_suspect="above_first")
