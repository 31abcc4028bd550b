"""The data an identification is fitted to: the first stage of
:func:`cummins.radiation.fit.fit_radiation`, a function a user can call (:func:`prepare_fit`).

* **Frequencies**: the fitting range; a suspect frequency
  (:func:`cummins.repair.find_suspect_frequencies`, run on each DOF's own curves) costs
  that point, and only to the couplings of the DOFs whose curves it spoils; the data
  bridged over each coupling's left-out points for what needs every frequency (K(t), the
  MIMO passivity step, metrics; Ogilvie's A∞ bridges the damping only over each pair's
  own points that are not a sharp resonance).
* **A∞**: the solver's ω = ∞ row when present and consistent with the finite
  frequencies (:func:`inconsistent_added_mass_inf`), else estimated; Ogilvie's estimate
  and its spread as the prior.
* **What the fit aims at**: the motion sensitivity (:mod:`cummins.radiation.fit.motion`) when the
  data hold the inertia and the restoring.
* **Couplings**: the significant ones; a pair with A_ij ≠ A_ji beyond 10 % is named in
  a warning (:func:`asymmetric_pairs`). A difference A_ij − A_ji that is constant over
  frequency is kept in A∞, the memory fitted to the average
  (:func:`antisymmetric_added_mass`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.arrays import at_frequency
from cummins.check import copied_dofs
from cummins.errors import CumminsWarning, FitError, HydroDataError
from cummins.hydrodb import dof_matrix, single_speed
from cummins.radiation.fingerprint import data_fingerprint
from cummins.radiation.fit.frequency import r_squared
from cummins.radiation.fit.motion import (
    JoinedMotion,
    MotionSensitivity,
    fitted_frequencies,
    motion_sensitivity,
    statically_unstable,
)
from cummins.radiation.fit.options import FitOptions
from cummins.radiation.fit.order_search import block_groups
from cummins.radiation.fit.reciprocity import (
    ANTISYMMETRY_CONSTANT,  # noqa: F401 (the names of the data stage before the split)
    ANTISYMMETRY_MAX,  # noqa: F401
    ANTISYMMETRY_MIN,  # noqa: F401
    ASYMMETRY_TOL,  # noqa: F401
    Reciprocity,
    antisymmetric_added_mass,
    asymmetric_pairs,
    motion_error_floor,
    passive_hermitian_part,
    reciprocity_of,
)
from cummins.radiation.fit.scorecard import data_frequencies
from cummins.radiation.infinite_frequency import added_mass_inf as estimate_added_mass_inf
from cummins.radiation.infinite_frequency import bridged_couplings
from cummins.radiation.model import RadiationModel
from cummins.radiation.retardation import (
    default_kernel_values,
    default_retardation_function,
    significant_couplings,
)
from cummins.radiation.transforms import shared_kernels
from cummins.repair import (
    Judged,
    find_suspect_frequencies,
    irregular_frequency_spans,
    limit_frequency_range,
    nearest_passive_damping,
    remove_suspect_frequencies,
    suspects_by_dof,
)
from cummins.validation import guard_hydro_data


@dataclass(frozen=True)
class BeyondRange:
    """The diagonal curves of the DOFs whose points reach beyond the fitting range.

    Attributes
    ----------
    omega
        The frequencies the scoreboard judges a model on, in and out of the range, rad/s.
    curves
        ``{label: (A_ii, B_ii)}`` at ``omega``.
    """

    omega: NDArray[np.float64]
    curves: dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]]


@dataclass(frozen=True)
class FitInput:
    """The prepared data of an identification (:func:`prepare_fit`).

    Attributes
    ----------
    ds
        The data as given (one forward speed).
    raw, data
        The data at the fitted frequencies, and the same bridged over each coupling's
        left-out points.
    keep_dof
        (omega, n_dofs): which frequencies each DOF keeps.
    labels
        DOF labels.
    measured
        :class:`FitData` of ``data`` (symmetric parts, K(t)).
    added_mass, damping
        Symmetric parts of ``raw`` (omega, n, n).
    a_inf_mode
        ``"data"``, ``"fit"`` or ``"ogilvie"``: how A∞ is had.
    a_inf
        The data's A∞ (mode ``"data"``) or Ogilvie's estimate.
    ogilvie, ogilvie_spread
        Ogilvie's A∞ and its spread over frequency (at least 0.5 %).
    weighting
        The weighting resolved (``"motion"``, ``"uniform"``, ``"response"``).
    sensitivity
        The motion sensitivity (``weighting="motion"``), else None.
    pairs, negligible
        The significant couplings (i ≤ j) and the rest.
    antisymmetric_added_mass
        (n, n) antisymmetric part of the data's added mass that is constant over the
        fitted frequencies, which the model's A∞ keeps (:func:`antisymmetric_added_mass`);
        zero for reciprocal data and for the pairs fitted as given.
    reciprocity
        What :func:`cummins.radiation.fit.reciprocity.reciprocity_of` decided: the pairs
        (i, j), i < j, fitted as given, K_ij ≠ K_ji (:attr:`as_given`; ``added_mass``,
        ``damping`` and ``measured`` hold them as they are), and why.
    attrs
        The provenance the model will carry (source, options, what was left out, notes).
    beyond_range
        The DOFs that keep frequencies outside the fitting range (cut where every
        modelled DOF keeps its points), with their curves in and out of it
        (:func:`range_cut_failures`); None when no DOF does.
    resonant_dofs
        Indices of the DOFs that keep a sharp resonance of the data in the fit because the
        motions depend on it (a piston or gap mode: :func:`cummins.repair.suspects_by_dof`);
        a block of theirs that misses its targets is fitted again with poles as lightly
        damped as :data:`cummins.radiation.fit.vector.RESONANCE_MIN_DAMPING`.
    estimated_inf
        Indices of the DOFs whose A∞ the blocks estimate though ``a_inf`` is the data's
        row (:mod:`cummins.radiation.fit.causal_inf`).
    reference
        The motion sensitivity of the user's data (``sensitivity`` is the passive part's,
        which the fit aims at): what the scoreboard and the motion refinement judge.
    """

    ds: xr.Dataset
    raw: xr.Dataset
    data: xr.Dataset
    keep_dof: NDArray[np.bool_]
    labels: tuple[str, ...]
    measured: FitData
    added_mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    a_inf_mode: str
    a_inf: NDArray[np.float64]
    ogilvie: NDArray[np.float64]
    ogilvie_spread: NDArray[np.float64]
    weighting: str
    sensitivity: MotionSensitivity | None
    pairs: list[tuple[int, int]]
    negligible: list[tuple[int, int]]
    antisymmetric_added_mass: NDArray[np.float64]
    attrs: dict[str, Any] = field(default_factory=dict)
    beyond_range: BeyondRange | None = None
    reciprocity: Reciprocity = field(default_factory=Reciprocity)
    resonant_dofs: tuple[int, ...] = ()
    estimated_inf: tuple[int, ...] = ()
    reference: MotionSensitivity | None = None

    @property
    def as_given(self) -> frozenset[tuple[int, int]]:
        """The pairs fitted as given (:attr:`reciprocity`)."""
        return self.reciprocity.as_given


def prepare_fit(
    ds: xr.Dataset, options: FitOptions, joined: JoinedMotion | None = None, judged: Judged = ()
) -> FitInput:
    """The first stage of an identification: the data selected and prepared as the fit
    will use them (module docstring). ``options`` as checked by
    :meth:`~cummins.radiation.fit.options.FitOptions.checked`; ``joined``: the mechanics
    whose motions the fit aims at (:class:`~cummins.radiation.fit.motion.JoinedMotion`);
    ``judged``: data whose suspect frequencies were found already, with what was found
    (:func:`cummins.repair.suspects_by_dof`)."""
    with shared_kernels():  # the Kramers–Kronig integrals' logarithms once per grid
        return _prepare_fit(ds, options, joined, judged)


def _prepare_fit(
    ds: xr.Dataset, options: FitOptions, joined: JoinedMotion | None, judged: Judged
) -> FitInput:
    """:func:`prepare_fit`'s work (``judged``: data whose suspect frequencies were found
    already, :func:`cummins.repair.suspects_by_dof`)."""
    ds = single_speed(ds)
    guard_hydro_data(ds)  # non-finite or absurd values: FitError naming the DOF pair
    given = ds  # the data as the user gave them: the model's fingerprint
    method = options.method
    # a passive model is fitted to the data's passive part (a non-passive B(ω) makes the
    # passivity step move every coupling of a block); what is said about the data, and
    # the motions the model is compared with, stay the user's
    user, passive_part = ds, None
    if options.passivity != "none":
        ds, passive_part = nearest_passive_damping(ds, significant_couplings(ds, options.threshold))
    raw, keep_dof, sound, data_notes, resonant_dofs = _fit_data(
        ds, options.omega_min, options.omega_max, options.exclude_suspect, judged
    )
    every_frequency = raw  # for Ogilvie's A∞, before the range is cut
    if passive_part is not None and passive_part.note():
        data_notes.insert(0, passive_part.note())
    # the data with each coupling's suspect points bridged: for K(t), the
    # MIMO passivity step and the metrics after it (not extrapolated: the range ends
    # where the modelled DOFs stop keeping their points; a DOF without damping of its
    # own, not modelled, does not cut the others' range)
    bridged = _bridged_dataset(raw, keep_dof)  # a new one (points bridged): kept if not cut
    modelled = sorted({i for i, j in significant_couplings(bridged) if i == j})
    clean_rows = _common_frequencies(keep_dof)
    span = _common_frequencies(keep_dof[:, modelled]) if modelled else clean_rows
    inside = np.arange(span[0], span[-1] + 1)
    clean = raw.isel(omega=clean_rows)  # Ogilvie's A∞: where every DOF is sound
    data_notes += _range_cut_notes(raw, keep_dof, inside)
    beyond_range = _beyond_range(raw, keep_dof, inside)
    whole = inside.size == raw.sizes["omega"] and bridged is not raw
    raw, keep_dof = raw.isel(omega=inside), keep_dof[inside]
    data = bridged if whole else _bridged_dataset(raw, keep_dof)
    if user is ds:
        user = data
    else:  # the user's own data at the same frequencies, bridged alike
        user = _bridged_dataset(user.sel(omega=raw.omega.values), keep_dof)
    excluded = [float(x) for x in raw.omega.values[~keep_dof.all(axis=1)]]
    fitted = set(raw.omega.values)  # once: in the comprehension it was rebuilt per point
    excluded += [float(x) for x in ds.omega.values if x not in fitted]
    excluded = sorted(excluded)
    joint = method in ("fd", "vf")
    a_inf_mode = options.added_mass_inf
    if a_inf_mode == "auto":
        a_inf_mode = "data" if "added_mass_inf" in data else ("fit" if joint else "ogilvie")
    if a_inf_mode == "data" and "added_mass_inf" not in data:
        raise HydroDataError(
            "the data have no infinite-frequency added mass",
            path=ds.attrs.get("source_file"),
            hint="use added_mass_inf='fit' or 'ogilvie'",
        )
    if a_inf_mode == "fit" and not joint:
        raise FitError("the joint A∞ estimate needs method='fd'; use added_mass_inf='ogilvie'")
    # Ogilvie's A∞ (the prior of a fitted A∞): the Kramers–Kronig integral over the
    # damping bridged over each pair's suspect points only, sharp features kept, and the
    # median over the frequencies both DOFs keep. Taken where every DOF is sound, as
    # before, it lost the damping at every point where one DOF is suspect: the tanker's
    # above 3.4 of 6 rad/s (A∞ 1.5 % off the solver's row, now 1.3 %), the 2015 WAMIT
    # OSWEC's (9.5 %, now 1.6 %); and bridged, a resonance of the MHK RM1's surge at
    # 2 rad/s (3.6 %, now 0.8 %)
    ogilvie_estimate = estimate_added_mass_inf(
        every_frequency.drop_vars("added_mass_inf", errors="ignore"), method="ogilvie", kept=sound
    )
    ogilvie = ogilvie_estimate.values
    # uncertainty of Ogilvie's estimate: its spread over frequency, at least 0.5 %
    ogilvie_spread = np.maximum(ogilvie_estimate.spread.values, 0.005 * np.abs(ogilvie))
    if options.added_mass_inf == "auto" and a_inf_mode == "data":
        inconsistent = inconsistent_added_mass_inf(clean, ogilvie, ogilvie_spread)
        if inconsistent:
            a_inf_mode = "fit" if joint else "ogilvie"
            data_notes.append(
                "the data's infinite-frequency added mass disagrees with its finite "
                f"frequencies ({'; '.join(inconsistent)}): not used, A∞ estimated "
                f"({a_inf_mode}); pass added_mass_inf='data' to use it anyway"
            )
    a_inf = dof_matrix(data, "added_mass_inf") if a_inf_mode == "data" else ogilvie.copy()
    labels = tuple(str(d) for d in data.influenced_dof.values)
    weighting = options.weighting
    if weighting == "auto":
        known = {"inertia_matrix", "hydrostatic_stiffness"} <= set(data)
        weighting = "motion" if known and joint else "uniform"
    reference = None  # the user's motions
    if weighting == "motion":
        reference = motion_sensitivity(user, added_mass_inf=a_inf, joined=joined)
        if reference is None:
            raise FitError(
                "weighting='motion' needs inertia_matrix and hydrostatic_stiffness in the data",
                hint="use weighting='uniform' or data with the rigid-body inertia and restoring",
            )
    pairs = significant_couplings(data, options.threshold)
    antisymmetric, kept = np.zeros((len(labels), len(labels))), []
    reciprocity = Reciprocity()
    if method == "vf" and float(ds.coords.get("forward_speed", 0.0)) == 0.0:
        # at speed A_ij ≠ A_ji is physical; the per-coupling fit compares every
        # coupling with the symmetric data and its A∞ (it keeps A∞ symmetric)
        antisymmetric, kept = antisymmetric_added_mass(raw, keep_dof, modelled)
        # a pair whose X_ji alone is significant counts here: averaged with a small
        # X_ij, or left out, it can move the motions most (RM3's spar sway-heave)
        either = significant_couplings(data, options.threshold, either=True)
        reciprocity = reciprocity_of(
            user,
            keep_dof,
            block_groups(len(labels), either),
            antisymmetric,
            reference,
            option=options.reciprocity,
            motion_tol=options.motion_tol,
            r2_coupling=options.coupling_target,
        )
        if reciprocity.as_given:
            fitted = as_given_data(raw, data, pairs, reciprocity, keep_dof, modelled)
            floors = (
                motion_floor(reference, fitted[1], reciprocity.as_given, fitted[3]),
                motion_floor(reference, data, frozenset(), antisymmetric),
            )
            if reference is None or floors[0] < floors[1]:
                raw, data, pairs, antisymmetric, kept, note = fitted
                data_notes += reciprocity.notes + [note] * bool(note)
            else:  # its passive part is no closer to the data's motions than the average
                data_notes.append(
                    "the data are not reciprocal, but fitted as given their passive part "
                    f"would be {100 * floors[0]:.3g} % off their own motions, the reciprocal "
                    f"part's {100 * floors[1]:.3g} %: the reciprocal part is fitted"
                )
                reciprocity = Reciprocity(floors=reciprocity.floors)
        else:
            data_notes += reciprocity.notes
    elif method != "vf" and options.reciprocity == "as-given":
        raise FitError(
            f"reciprocity='as-given' needs method='vf' (the {method!r} fit models the "
            "reciprocal part of each coupling)"
        )
    elif method == "fd" and reference is not None and options.reciprocity == "auto":
        # the per-coupling fit (and the speed terms built from it) models the reciprocal
        # part: say when that is further from the motions than the fit aims
        either = significant_couplings(data, options.threshold, either=True)
        found = reciprocity_of(
            user,
            keep_dof,
            block_groups(len(labels), either),
            np.zeros((len(labels), len(labels))),
            reference,
            motion_tol=options.motion_tol,
            r2_coupling=options.coupling_target,
        )
        if found.as_given:
            data_notes.append(
                "the data are not reciprocal beyond what the motions allow (their reciprocal "
                f"part alone is {100 * max(found.floors.values()):.3g} % off their own "
                "motions); the per-coupling fit models that part, method='vf' fits such "
                "couplings as given"
            )
    for message in asymmetric_pairs(user, reciprocity.as_given):
        warnings.warn(message, CumminsWarning, stacklevel=3)
        data_notes.append(message)
    data_notes += kept
    sensitivity = reference
    if reference is not None and data is not user:  # the fit aims at the passive part
        sensitivity = motion_sensitivity(data, added_mass_inf=a_inf, joined=joined)
    measured = fit_data(data, reciprocity.as_given)
    n = len(labels)
    negligible = [(i, j) for i in range(n) for j in range(i, n) if (i, j) not in pairs]
    a_raw = dof_matrix(raw, "added_mass")
    b_raw = dof_matrix(raw, "radiation_damping")
    w = data.omega.values
    attrs = {
        "source_file": str(ds.attrs.get("source_file", "")),
        "source_format": str(ds.attrs.get("source_format", "")),
        "data_fingerprint": data_fingerprint(given),
        "history": str(data.attrs.get("history", "")),
        "axis_convention": str(ds.attrs.get("axis_convention", "z-up")),
        "reference_point": np.asarray(
            ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float
        ),
        "method": method,
        "r2_target": options.r2,
        "r2_coupling_target": options.coupling_target,
        "max_order": options.max_order,
        "threshold": options.threshold,
        "added_mass_inf_method": a_inf_mode,
        "excluded_frequencies": [float(x) for x in excluded],
        "negligible_couplings": [
            labels[i] if i == j else f"{labels[i]}-{labels[j]}" for i, j in negligible
        ],
        "data_notes": data_notes
        + [
            f"{labels[i]}: no radiation damping in the data, not modelled"
            for i, j in negligible
            if i == j
        ],
        "omega_fit_min": float(w[0]),
        "omega_fit_max": float(w[-1]),
    }
    if reciprocity.as_given:
        floors = [x for x in reciprocity.floors.values() if x is not None]
        if floors:
            attrs["reciprocal_motion_error_floor"] = float(max(floors))
        attrs["couplings_as_given"] = [
            f"{labels[i]}-{labels[j]}" for i, j in sorted(reciprocity.as_given)
        ]
    if joined is not None and reference is not None:
        attrs["motions_of"] = joined.describe()
    if "body_coupling" in ds.attrs:  # data of a mechanical system (assemble): on or off
        attrs["body_coupling"] = str(ds.attrs["body_coupling"])
    if reference is None:
        attrs["motions_unjudged"] = motions_unjudged(user, options.weighting)
    if reference is not None:
        # the floor: what the model is fitted to (the data's passive part, reciprocal but
        # for the pairs fitted as given) against the user's motions
        attrs["motion_error_floor"] = motion_error_floor(reference, measured, antisymmetric)
        attrs["statically_unstable"] = statically_unstable(user, joined)
    return FitInput(
        ds=ds,
        raw=raw,
        data=data,
        keep_dof=keep_dof,
        labels=labels,
        measured=measured,
        added_mass=reciprocal_part(a_raw, reciprocity.as_given),
        damping=reciprocal_part(b_raw, reciprocity.as_given),
        a_inf_mode=a_inf_mode,
        a_inf=a_inf,
        ogilvie=ogilvie,
        ogilvie_spread=ogilvie_spread,
        weighting=weighting,
        sensitivity=sensitivity,
        reference=reference,
        pairs=pairs,
        negligible=negligible,
        attrs=attrs,
        beyond_range=beyond_range,
        antisymmetric_added_mass=antisymmetric,
        reciprocity=reciprocity,
        resonant_dofs=resonant_dofs,
    )


def motions_unjudged(data: xr.Dataset, weighting: str) -> str:
    """Why the motions do not judge a fit of ``data`` (its weighting is not by the
    motions): what the data lack of the inertia and the restoring, or the weighting the
    user chose."""
    missing = [
        what
        for what, name in (("inertia", "inertia_matrix"), ("restoring", "hydrostatic_stiffness"))
        if name not in data
    ]
    if missing == ["inertia"]:
        return "the data lack the inertia: give it, e.g. --mass, --radii-of-gyration"
    if missing:
        return f"the data lack the {' and the '.join(missing)}"
    return f"weighting={weighting!r} does not judge the motions"


def as_given_data(raw, data, pairs, reciprocity: Reciprocity, keep_dof, modelled):
    """What a fit with the pairs ``reciprocity.as_given`` fitted as given uses: (raw,
    data, pairs, antisymmetric A∞ kept, its notes, a note): the data made passive as a
    non-reciprocal model must be (:func:`~cummins.radiation.fit.reciprocity.
    passive_hermitian_part`), the pairs with those added, the constant A_ij − A_ji kept
    in A∞ but for them (each keeps its own, :attr:`Reciprocity.added_mass_inf`)."""
    given = reciprocity.as_given
    antisymmetric, kept = antisymmetric_added_mass(raw, keep_dof, modelled, skip=given)
    pairs = sorted(set(pairs) | given)
    blocks = block_groups(keep_dof.shape[1], pairs)
    inf = reciprocity.added_mass_inf
    raw, _ = passive_hermitian_part(raw, blocks, given, inf)
    data, note = passive_hermitian_part(data, blocks, given, inf)
    return raw, data, pairs, antisymmetric, kept, note


def motion_floor(reference, data: xr.Dataset, as_given, antisymmetric) -> float:
    """:func:`~cummins.radiation.fit.reciprocity.motion_error_floor` of ``data`` (reciprocal
    but for ``as_given``, with the antisymmetric A∞ kept) against ``reference``'s motions;
    0 without motions."""
    if reference is None:
        return 0.0
    a = reciprocal_part(dof_matrix(data, "added_mass"), as_given)
    b = reciprocal_part(dof_matrix(data, "radiation_damping"), as_given)
    return motion_error_floor(
        reference, FitData(data.omega.values, a, b, None, None), antisymmetric
    )


def reciprocal_part(x: NDArray, as_given=frozenset()) -> NDArray:
    """½(X + Xᵀ) of matrices (…, n, n), but for the pairs ``as_given`` (i, j): kept as
    they are (:func:`cummins.radiation.fit.reciprocity.reciprocity_of`)."""
    out = 0.5 * (x + np.swapaxes(x, -1, -2))
    for i, j in as_given:
        out[..., i, j], out[..., j, i] = x[..., i, j], x[..., j, i]
    return out


#: The data's A∞_ii is taken as inconsistent with A(ω) when it differs from Ogilvie's
#: estimate by more than this fraction of the largest |A_ii(ω)| and 5 spreads of the
#: estimate (AQWA's "100 rad/s" row of the PEND hull: 52.1 kg where A(18.8 rad/s) is
#: 2.2 kg and Ogilvie's estimate 3.4 kg; the rows of the MSS tanker and of 7 corpus
#: WAMIT/AQWA runs pass).
A_INF_INCONSISTENT = 0.25


def inconsistent_added_mass_inf(data: xr.Dataset, ogilvie, spread) -> list[str]:
    """The diagonal terms whose ω = ∞ row contradicts the finite frequencies
    (:data:`A_INF_INCONSISTENT`), as ``"Surge 52.1 vs 2.04"``."""
    if "added_mass_inf" not in data:
        return []
    labels = [str(d) for d in data.influenced_dof.values]
    row = np.diag(dof_matrix(data, "added_mass_inf"))
    a = np.abs(np.diagonal(dof_matrix(data, "added_mass"), axis1=1, axis2=2)).max(axis=0)
    out = []
    for i, label in enumerate(labels):
        gap = abs(row[i] - ogilvie[i, i])
        if gap > A_INF_INCONSISTENT * a[i] and gap > 5 * spread[i, i]:
            out.append(f"{label} {row[i]:.4g} vs {ogilvie[i, i]:.4g}")
    return out


@dataclass(frozen=True)
class FitData:
    """What the couplings of a model are measured against: the symmetric parts of the data.

    Attributes
    ----------
    omega
        The fitted frequencies, rad/s.
    added_mass, damping
        ½(X + Xᵀ) of A(ω) and B(ω), shape (len(omega), n_dofs, n_dofs); X_ij and X_ji
        as they are for a pair fitted as given.
    time, kernel
        K(t) of the symmetric damping on the default time grid (≤ 500 points), for the
        R² of K(t).
    """

    omega: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    time: NDArray[np.float64]
    kernel: NDArray[np.float64]


def fit_data(data: xr.Dataset, as_given=frozenset()) -> FitData:
    """:class:`FitData` of a ``HydroDB`` already restricted to the fitted frequencies: its
    reciprocal part, but for the pairs ``as_given`` (i, j), kept as they are."""
    a_all, b_all = dof_matrix(data, "added_mass"), dof_matrix(data, "radiation_damping")
    b, damping = data.radiation_damping, reciprocal_part(b_all, as_given)
    # the segment form at every time: the order search follows these numbers (K(0) is
    # an equation of the fits) and, over many relocations, their last digits (the node
    # form's rounding moved the WAMIT OSWEC's R² of B from 0.277 to 0.281); ½(B + Bᵀ)
    # on the arrays (the dataset's numbers) unless the labels need aligning
    if as_given or np.array_equal(b.influenced_dof.values, b.radiating_dof.values):
        time, kernel = default_kernel_values(data.omega.values, damping, a_all, max_points=500)
    else:
        swapped = b.rename(influenced_dof="radiating_dof", radiating_dof="influenced_dof")
        found = default_retardation_function(
            data.assign(radiation_damping=(0.5 * (b + swapped)).transpose(*b.dims)),
            max_points=500,
            node_form=False,
        ).transpose("time", "influenced_dof", "radiating_dof")
        time, kernel = found.time.values, found.values
    return FitData(data.omega.values, reciprocal_part(a_all, as_given), damping, time, kernel)


def model_fit_data(model: RadiationModel, ds: xr.Dataset) -> FitData:
    """The data a model was fitted to, as :func:`fit_radiation` used them: its DOFs, the
    frequencies in ``omega_fit_min`` … ``omega_fit_max`` less its ``excluded_frequencies``
    (the model's attributes), one forward speed; reciprocal but for the pairs its
    ``couplings_as_given`` names."""
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    dofs = list(model.dofs)
    try:
        ds = ds.sel(influenced_dof=dofs, radiating_dof=dofs)
    except KeyError as exc:
        raise FitError(f"the data do not hold the model's DOFs {dofs}") from exc
    keep = fitted_frequencies(model, ds.omega.values)
    if not keep.any():
        raise FitError("the data have no frequency in the model's fitted range")
    named = {str(x) for x in np.atleast_1d(model.attrs.get("couplings_as_given", []) or [])}
    as_given = frozenset(
        (i, j)
        for i in range(len(dofs))
        for j in range(i + 1, len(dofs))
        if f"{dofs[i]}-{dofs[j]}" in named
    )
    return fit_data(ds.isel(omega=np.flatnonzero(keep)), as_given)


def response_weights(data: xr.Dataset) -> NDArray[np.float64]:
    """ω/|Z_ii(ω)| per frequency and DOF (see ``weighting`` of :func:`fit_radiation`)."""
    for name in ("inertia_matrix", "hydrostatic_stiffness"):
        if name not in data:
            raise FitError(
                f"weighting='response' needs {name} in the data",
                hint="use weighting='uniform' or data with the rigid-body inertia and restoring",
            )
    w = data.omega.values
    a = np.diagonal(dof_matrix(data, "added_mass"), axis1=1, axis2=2)
    b = np.diagonal(dof_matrix(data, "radiation_damping"), axis1=1, axis2=2)
    m = np.diag(dof_matrix(data, "inertia_matrix"))
    c = np.diag(dof_matrix(data, "hydrostatic_stiffness"))
    z = np.abs(-(w**2)[:, None] * (m + a) + 1j * w[:, None] * b + c)
    sensitivity = w[:, None] / np.maximum(z, 1e-300)
    return sensitivity / np.sqrt(np.mean(sensitivity**2, axis=0))


def _fit_data(
    ds, omega_min, omega_max, exclude_suspect, judged: Judged = ()
) -> tuple[xr.Dataset, NDArray[np.bool_], NDArray[np.bool_], list[str], tuple[int, ...]]:
    """The data to fit, which frequencies each DOF keeps (omega, dof), which hold sound
    data (those and its suspect points that are sharp features of the data:
    :func:`cummins.repair.sharp_features`), what the user should know and the DOFs that
    keep a sharp resonance the motions depend on.

    A suspect frequency (:func:`cummins.repair.find_suspect_frequencies`, run on each
    DOF's own curves) costs that point, and only to the couplings of the DOFs whose curves
    it spoils: the other DOFs keep it, and no frequency above it is dropped with it.
    """
    data = limit_frequency_range(ds, omega_min, omega_max)
    notes = []
    outside = ds.sizes["omega"] - data.sizes["omega"]
    if outside:
        notes.append(f"{outside} frequencies outside the fitting range left out")
    labels = [str(d) for d in data.influenced_dof.values]
    w = data.omega.values
    keep = np.ones((w.size, len(labels)), dtype=bool)
    sound = np.zeros_like(keep)  # suspect points that are sharp features of the data
    resonant: list[int] = []
    if exclude_suspect == "above_first":  # the rule of the previous default
        cleaned, suspects = remove_suspect_frequencies(data, above_first=True)
        for s in suspects:
            notes.append(f"{s.omega:.4g} rad/s left out: {s.quantity}, {s.reason}")
        dropped = ~np.isin(w, cleaned.omega.values)
        keep[dropped, :] = False
        if dropped.sum() > len(suspects):
            notes.append(
                f"{int(dropped.sum()) - len(suspects)} more frequencies above "
                f"{min(s.omega for s in suspects):.4g} rad/s left out with it"
            )
    elif exclude_suspect:
        own = suspects_by_dof(data, judged)
        resonances = []
        for d, label in enumerate(labels):
            for s in own[label].suspects:  # a sharp resonance the motions depend on stays
                if s.omega not in own[label].kept:
                    keep[at_frequency(w, s.omega), d] = False
            for omega in own[label].features:
                sound[at_frequency(w, omega), d] = True
            if any(r.kept and r.motion_change is not None for r in own[label].resonances):
                resonant.append(d)  # a resonance the motions depend on
            resonances += [r.description(label) for r in own[label].resonances]
        for s in find_suspect_frequencies(data):
            if not keep[at_frequency(w, s.omega)].all():
                notes.append(f"{s.omega:.4g} rad/s left out: {s.quantity}, {s.reason}")
        notes += resonances
        for span in irregular_frequency_spans(data, own):
            notes.append(
                f"{span.dof}: {span.description()}; fitted below {span.omega_start:.4g} rad/s "
                "(omega_max, --omega-max) the model follows the consistent part"
            )
        for d, label in enumerate(labels):
            dropped = int((~keep[:, d]).sum())
            if dropped and keep[:, d].sum() < MIN_KEPT_FREQUENCIES:
                keep[:, d] = True
                notes.append(
                    f"{label}: {dropped} of {w.size} frequencies look suspect; all kept, "
                    "too few would be left (check the data: cummins check)"
                )
            elif dropped:
                notes.append(
                    f"{label}: {dropped} suspect frequencies left out of its couplings "
                    f"({w[~keep[:, d]].min():.4g}–{w[~keep[:, d]].max():.4g} rad/s)"
                )
    for finding in copied_dofs(data):
        if finding.severity != "ok":
            notes.append(f"{finding.message}: {finding.advice}")
    return data, keep, sound | keep, notes, tuple(resonant)


def _range_cut_notes(raw: xr.Dataset, keep_dof: NDArray, inside: NDArray) -> list[str]:
    """What the fitting range, cut where every DOF keeps its points, takes from DOFs
    whose own curves are fine there (they are not fitted there: say so, in one note)."""
    w = raw.omega.values
    cut = np.ones(w.size, dtype=bool)
    cut[inside] = False
    lost = {
        str(label): int((cut & keep_dof[:, d]).sum())
        for d, label in enumerate(raw.influenced_dof.values)
    }
    lost = {label: n for label, n in lost.items() if n}
    if not lost:
        return []
    return [
        f"fitting range {w[inside[0]]:.4g}–{w[inside[-1]]:.4g} rad/s, the frequencies every "
        "DOF keeps: outside it the model is not fitted, though these DOFs' own curves look "
        "sound there: " + ", ".join(f"{label} ({n})" for label, n in lost.items())
    ]


def _beyond_range(raw: xr.Dataset, keep_dof: NDArray, inside: NDArray) -> BeyondRange | None:
    """:attr:`FitInput.beyond_range`: the diagonal curves of the DOFs that keep points
    outside the fitting range, at the frequencies the scoreboard judges a model on
    (:func:`cummins.radiation.fit.scorecard.data_frequencies`)."""
    cut = np.ones(raw.sizes["omega"], dtype=bool)
    cut[inside] = False
    lost = [d for d in range(keep_dof.shape[1]) if (cut & keep_dof[:, d]).any()]
    if not lost:
        return None
    judged = data_frequencies(raw)
    a, b = dof_matrix(raw, "added_mass"), dof_matrix(raw, "radiation_damping")
    labels = raw.influenced_dof.values
    curves = {str(labels[d]): (a[judged, d, d], b[judged, d, d]) for d in lost}
    return BeyondRange(raw.omega.values[judged], curves)


#: A DOF's R² over the frequencies beyond the fitting range may fall this far below the
#: target before the fit reports it as a failure (a target missed inside the range is a
#: note: the data decide it; a model gone astray outside it is a failure).
RANGE_CUT_SLACK = 0.05


def range_cut_failures(model: RadiationModel, inp: FitInput, r2: float) -> list[str]:
    """The DOFs whose own sound curves reach beyond the fitting range (cut by other DOFs'
    suspect points) and that the model, not fitted there, misses: R² of A or B below
    ``r2`` − :data:`RANGE_CUT_SLACK` over the frequencies no DOF's curves make suspect,
    in and out of the range (the scoreboard's measure), and by more than that slack below
    the R² inside the range alone (a DOF missed inside the range, where it is fitted, is
    the data's or the order's: a note of the block, not this failure). One message
    naming them all, for ``attrs["failures"]`` (a model extrapolated where the data are
    sound is not a success), or none."""
    beyond = inp.beyond_range
    if beyond is None:
        return []
    w = beyond.omega
    low = float(model.attrs.get("omega_fit_min", w.min()))
    top = float(model.attrs.get("omega_fit_max", w.max()))
    inside = (w >= low * (1 - 1e-12)) & (w <= top * (1 + 1e-12))
    k = model.response(w)
    a_inf = np.asarray(model.added_mass_inf, dtype=float)
    missed = []
    for label, (a, b) in beyond.curves.items():
        if label not in model.dofs:
            continue
        i = model.dofs.index(label)
        if not np.any(k[:, i, i]):
            continue
        curves = (a, b, a_inf[i, i] + k[:, i, i].imag / w, k[:, i, i].real)
        scores = _r2_of_curves(*curves, np.ones(w.size, dtype=bool))
        within = _r2_of_curves(*curves, inside) if inside.sum() > 2 else {"A": 1.0, "B": 1.0}
        lost = [
            x
            for x in scores
            if scores[x] < r2 - RANGE_CUT_SLACK and scores[x] < within[x] - RANGE_CUT_SLACK
        ]
        if lost:
            worst = min(lost, key=lambda x: scores[x])
            missed.append(f"{label} {worst} {scores[worst]:.3g}")
    if not missed:
        return []
    outside = []
    if w.min() < low * (1 - 1e-12):
        outside.append(f"below {low:.4g}")
    if w.max() > top * (1 + 1e-12):
        outside.append(f"above {top:.4g}")
    return [
        f"fitted on {low:.4g}–{top:.4g} rad/s only (other DOFs' suspect points cut the "
        f"range), the model misses these DOFs' curves {' and '.join(outside)} rad/s (R² "
        f"over the data's frequencies {w.min():.4g}–{w.max():.4g} rad/s less the suspect "
        f"ones, target {r2}): {', '.join(missed)}; choose omega_min/omega_max, or check "
        "the data (cummins check)"
    ]


def _r2_of_curves(a, b, a_model, b_model, rows) -> dict[str, float]:
    """R² of A and of B at the frequencies ``rows``."""
    return {"A": r_squared(a[rows], a_model[rows]), "B": r_squared(b[rows], b_model[rows])}


def _common_frequencies(keep: NDArray) -> NDArray[np.intp]:
    """The frequencies (indices) every column of ``keep`` keeps; all of them when fewer
    than :data:`MIN_KEPT_FREQUENCIES` would be left."""
    common = np.flatnonzero(keep.all(axis=1))
    return common if common.size >= MIN_KEPT_FREQUENCIES else np.arange(keep.shape[0])


#: A DOF keeps all its frequencies when fewer than this many would be left.
MIN_KEPT_FREQUENCIES = 8


def _bridged_dataset(data: xr.Dataset, keep: NDArray) -> xr.Dataset:
    """``data`` with A(ω) and B(ω) bridged over each coupling's suspect points
    (:func:`cummins.radiation.infinite_frequency.bridged_couplings`)."""
    if keep.all():
        return data
    w = data.omega.values
    values = {name: var.values for name, var in data.data_vars.items()}
    for name in ("added_mass", "radiation_damping"):
        dims = data[name].dims  # the variable's own order, the coupling's axes last
        order = [dims.index(d) for d in ("omega", "influenced_dof", "radiating_dof")]
        bridged = bridged_couplings(np.transpose(values[name], order), w, keep)
        values[name] = np.transpose(bridged, np.argsort(order))
    return data.copy(data=values)  # the rest shared, without the merge of an assign
