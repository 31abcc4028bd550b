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

import itertools
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.check import copied_dofs
from cummins.errors import CumminsWarning, FitError, HydroDataError
from cummins.hydrodb import dof_matrix, single_speed
from cummins.radiation.fit.frequency import r_squared
from cummins.radiation.fit.motion import MotionSensitivity, motion_sensitivity
from cummins.radiation.fit.options import FitOptions
from cummins.radiation.fit.scorecard import data_frequencies
from cummins.radiation.model import RadiationModel
from cummins.radiation.retardation import added_mass_inf as estimate_added_mass_inf
from cummins.radiation.retardation import (
    bridged_couplings,
    default_retardation_function,
    significant_couplings,
)
from cummins.repair import (
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
        zero for reciprocal data.
    attrs
        The provenance the model will carry (source, options, what was left out, notes).
    beyond_range
        The DOFs that keep frequencies outside the fitting range (cut where every
        modelled DOF keeps its points), with their curves in and out of it
        (:func:`range_cut_failures`); None when no DOF does.
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


def prepare_fit(ds: xr.Dataset, options: FitOptions) -> FitInput:
    """The first stage of an identification: the data selected and prepared as the fit
    will use them (module docstring). ``options`` as checked by
    :meth:`~cummins.radiation.fit.options.FitOptions.checked`."""
    ds = single_speed(ds)
    guard_hydro_data(ds)  # non-finite or absurd values: FitError naming the DOF pair
    method = options.method
    # a passive model is fitted to the data's passive part (a non-passive B(ω) makes the
    # passivity step move every coupling of a block); what is said about the data, and
    # the motions the model is compared with, stay the user's
    user, passive_part = ds, None
    if options.passivity != "none":
        ds, passive_part = nearest_passive_damping(ds, significant_couplings(ds, options.threshold))
    raw, keep_dof, sound, data_notes = _fit_data(
        ds, options.omega_min, options.omega_max, options.exclude_suspect
    )
    every_frequency = raw  # for Ogilvie's A∞, before the range is cut
    if passive_part is not None and passive_part.note():
        data_notes.insert(0, passive_part.note())
    # the data with each coupling's suspect points bridged: for K(t), the
    # MIMO passivity step and the metrics after it (not extrapolated: the range ends
    # where the modelled DOFs stop keeping their points; a DOF without damping of its
    # own, not modelled, does not cut the others' range)
    modelled = sorted(
        {i for i, j in significant_couplings(_bridged_dataset(raw, keep_dof)) if i == j}
    )
    clean_rows = _common_frequencies(keep_dof)
    span = _common_frequencies(keep_dof[:, modelled]) if modelled else clean_rows
    inside = np.arange(span[0], span[-1] + 1)
    clean = raw.isel(omega=clean_rows)  # Ogilvie's A∞: where every DOF is sound
    data_notes += _range_cut_notes(raw, keep_dof, inside)
    beyond_range = _beyond_range(raw, keep_dof, inside)
    raw, keep_dof = raw.isel(omega=inside), keep_dof[inside]
    data = _bridged_dataset(raw, keep_dof)
    if user is ds:
        user = data
    else:  # the user's own data at the same frequencies, bridged alike
        user = _bridged_dataset(user.sel(omega=raw.omega.values), keep_dof)
    excluded = [float(x) for x in raw.omega.values[~keep_dof.all(axis=1)]]
    excluded += [float(x) for x in ds.omega.values if x not in set(raw.omega.values)]
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
    for message in asymmetric_pairs(user):
        warnings.warn(message, CumminsWarning, stacklevel=3)
        data_notes.append(message)
    weighting = options.weighting
    if weighting == "auto":
        known = {"inertia_matrix", "hydrostatic_stiffness"} <= set(data)
        weighting = "motion" if known and joint else "uniform"
    sensitivity = None
    if weighting == "motion":
        sensitivity = motion_sensitivity(data, added_mass_inf=a_inf)
        if sensitivity is None:
            raise FitError(
                "weighting='motion' needs inertia_matrix and hydrostatic_stiffness in the data",
                hint="use weighting='uniform' or data with the rigid-body inertia and restoring",
            )
    pairs = significant_couplings(data, options.threshold)
    antisymmetric, kept = np.zeros((len(labels), len(labels))), []
    if method == "vf" and float(ds.coords.get("forward_speed", 0.0)) == 0.0:
        # at speed A_ij ≠ A_ji is physical; the per-coupling fit compares every
        # coupling with the symmetric data and its A∞ (it keeps A∞ symmetric)
        antisymmetric, kept = antisymmetric_added_mass(raw, keep_dof, modelled)
    data_notes += kept
    measured = fit_data(data)
    n = len(labels)
    negligible = [(i, j) for i in range(n) for j in range(i, n) if (i, j) not in pairs]
    a_raw = dof_matrix(raw, "added_mass")
    b_raw = dof_matrix(raw, "radiation_damping")
    w = data.omega.values
    attrs = {
        "source_file": str(ds.attrs.get("source_file", "")),
        "source_format": str(ds.attrs.get("source_format", "")),
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
    if sensitivity is not None:
        # the floor: the data's passive reciprocal part against the user's motions
        reference = sensitivity
        if user is not data:
            reference = motion_sensitivity(user, added_mass_inf=a_inf)
        attrs["motion_error_floor"] = motion_error_floor(reference, measured, antisymmetric)
    return FitInput(
        ds=ds,
        raw=raw,
        data=data,
        keep_dof=keep_dof,
        labels=labels,
        measured=measured,
        added_mass=0.5 * (a_raw + np.swapaxes(a_raw, 1, 2)),
        damping=0.5 * (b_raw + np.swapaxes(b_raw, 1, 2)),
        a_inf_mode=a_inf_mode,
        a_inf=a_inf,
        ogilvie=ogilvie,
        ogilvie_spread=ogilvie_spread,
        weighting=weighting,
        sensitivity=sensitivity,
        pairs=pairs,
        negligible=negligible,
        attrs=attrs,
        beyond_range=beyond_range,
        antisymmetric_added_mass=antisymmetric,
    )


#: A pair whose A_ij and A_ji (or B) differ by more than this fraction of the larger one
#: (and of the diagonal scale √(X_ii X_jj)) is named: the fit uses their average.
ASYMMETRY_TOL = 0.1


def motion_error_floor(
    sensitivity: MotionSensitivity, measured: FitData, antisymmetric: NDArray
) -> float:
    """The motion error of the data's own reciprocal part: what the model is fitted to
    (½(A + Aᵀ), ½(B + Bᵀ) and the antisymmetry kept in A∞) put in the place of the model,
    against the data's motions (:meth:`MotionSensitivity.error_of`): an estimate of what
    the data's averaged matrices alone give. A motion error far above it is the fit's,
    near it the data's (their damping's asymmetry, or A_ij − A_ji that varies over
    frequency)."""
    rows = sensitivity.compared_frequencies()
    w = sensitivity.omega[rows][:, None, None]
    k = measured.damping[rows] + 1j * w * (measured.added_mass[rows] + antisymmetric)
    return sensitivity.error_of(k, np.zeros(antisymmetric.shape))[0]


#: A pair's antisymmetric added mass ½(A_ij − A_ji) is kept in A∞ when its mean over the
#: frequencies the pair keeps is between ANTISYMMETRY_MIN and ANTISYMMETRY_MAX of
#: √(max|A_ii| max|A_jj|) (the notes print the whole difference A_ij − A_ji, twice it)
#: and it departs from that mean by at most
#: ANTISYMMETRY_CONSTANT of the mean: constant over frequency and a few per cent, what a
#: solver's mesh gives (the RM3-like float and spar: 0.5–1.1 %, constant to 2–6 % of
#: itself). A sign or DOF-order mix-up is not constant; a larger difference is data
#: that contradict reciprocity (the corpus's Capytaine OSWEC, flap and base: up to
#: 17 %), named by :func:`asymmetric_pairs` and not kept.
ANTISYMMETRY_MIN = 1e-3
ANTISYMMETRY_MAX = 0.05
ANTISYMMETRY_CONSTANT = 0.25


def antisymmetric_added_mass(
    raw: xr.Dataset, keep_dof: NDArray, modelled=None
) -> tuple[NDArray, list[str]]:
    """The part of A_ij ≠ A_ji that the model keeps in A∞, and a note per pair.

    At zero speed the added mass is symmetric (reciprocity: Newman (1977) ch. 6); panel
    methods return A_ij ≠ A_ji by a few per cent on coarse meshes (Capytaine's direct
    method on an RM3-like float and spar: the spar's surge–pitch and pitch–surge added
    mass 2.2 % of √(A_ii A_jj) apart, constant to 6 % of that over 0.1–3.5 rad/s). The
    memory K(s) is fitted to the average ½(A_ij + A_ji): an antisymmetric
    jω(A_ij − A_ji) in K(jω) cannot be passive as ω → 0, where K + Kᴴ is dominated by it.
    A difference that is *constant over frequency* is kept in A∞ instead (antisymmetric,
    ½(A_ij − A_ji) above and its negative below the diagonal), where it changes nothing
    of the memory and the model's motions follow the data's: on that float and spar the
    spar's pitch at its lightly damped resonance (0.25 rad/s) was 8 % off the data's
    RAO with the average alone, 0.50 % with the difference in A∞. Only the
    common-pole identification (``method="vf"``) at zero speed keeps it (at forward speed
    A_ij ≠ A_ji is physical).

    Parameters
    ----------
    raw
        The data at the fitted frequencies (one speed).
    keep_dof
        (omega, n) which frequencies each DOF keeps (:func:`prepare_fit`).
    modelled
        The DOFs whose memory is modelled (those with damping of their own), default
        all: a pair with another DOF (the yaw of an axisymmetric body, whose added mass
        is rounding noise) keeps nothing.

    Returns
    -------
    antisymmetric : ndarray, shape (n, n)
        Zero but for the pairs whose mean difference is between
        :data:`ANTISYMMETRY_MIN` and :data:`ANTISYMMETRY_MAX` of √(max|A_ii| max|A_jj|)
        and varies over frequency by at most :data:`ANTISYMMETRY_CONSTANT` of itself.
    notes : list of str
        One per pair kept, with the size of the difference.
    """
    a = dof_matrix(raw, "added_mass")
    labels = [str(d) for d in raw.influenced_dof.values]
    n = len(labels)
    out = np.zeros((n, n))
    notes = []
    dofs = range(n) if modelled is None else sorted(modelled)
    for i, j in itertools.combinations(dofs, 2):
        use = keep_dof[:, i] & keep_dof[:, j]
        if use.sum() < 2:
            continue
        half = 0.5 * (a[use, i, j] - a[use, j, i])
        mean = float(np.mean(half))
        scale = np.sqrt(np.abs(a[use, i, i]).max() * np.abs(a[use, j, j]).max())
        if not scale > 0 or not ANTISYMMETRY_MIN * scale <= abs(mean) <= ANTISYMMETRY_MAX * scale:
            continue
        if np.abs(half - mean).max() > ANTISYMMETRY_CONSTANT * abs(mean):
            continue
        out[i, j], out[j, i] = mean, -mean
        notes.append(
            f"A[{labels[i]}, {labels[j]}] − A[{labels[j]}, {labels[i]}] = {2 * mean:.5g} "
            f"({200 * abs(mean) / scale:.2g} % of √(A_ii A_jj)), constant over frequency: "
            "kept in A∞, the memory fitted to their average"
        )
    return out, notes


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


def asymmetric_pairs(data: xr.Dataset) -> list[str]:
    """One message per DOF pair (i < j) whose A_ij ≠ A_ji or B_ij ≠ B_ji at zero speed
    beyond :data:`ASYMMETRY_TOL`: the worst frequency and both values. The fit uses
    ½(X_ij + X_ji) (the physics wants them equal); so large a difference usually means a
    DOF order or sign convention mixed up between the two halves of the matrix."""
    out = []
    labels = [str(d) for d in data.influenced_dof.values]
    w = data.omega.values
    for name, symbol in (("added_mass", "A"), ("radiation_damping", "B")):
        x = dof_matrix(data, name)
        diag = np.abs(np.diagonal(x, axis1=1, axis2=2)).max(axis=0)
        for i in range(len(labels)):
            for j in range(i + 1, len(labels)):
                diff = np.abs(x[:, i, j] - x[:, j, i])
                scale = np.maximum(np.abs(x[:, i, j]), np.abs(x[:, j, i]))
                floor = ASYMMETRY_TOL * np.sqrt(diag[i] * diag[j])
                bad = (diff > ASYMMETRY_TOL * scale) & (diff > floor)
                if bad.any():
                    k = int(np.argmax(np.where(bad, diff, -1.0)))
                    out.append(
                        f"{symbol}[{labels[i]}, {labels[j]}] = {x[k, i, j]:.5g} but "
                        f"{symbol}[{labels[j]}, {labels[i]}] = {x[k, j, i]:.5g} at "
                        f"{w[k]:.4g} rad/s ({int(bad.sum())} frequencies): the fit uses their "
                        "average; check the DOF order and signs of the data"
                    )
    return out


@dataclass(frozen=True)
class FitData:
    """What the couplings of a model are measured against: the symmetric parts of the data.

    Attributes
    ----------
    omega
        The fitted frequencies, rad/s.
    added_mass, damping
        ½(X + Xᵀ) of A(ω) and B(ω), shape (len(omega), n_dofs, n_dofs).
    time, kernel
        K(t) of the symmetric damping on the default time grid (≤ 500 points), for the
        R² of K(t).
    """

    omega: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    time: NDArray[np.float64]
    kernel: NDArray[np.float64]


def fit_data(data: xr.Dataset) -> FitData:
    """:class:`FitData` of a ``HydroDB`` already restricted to the fitted frequencies."""
    b = data.radiation_damping
    swapped = b.rename(influenced_dof="radiating_dof", radiating_dof="influenced_dof")
    kernel = default_retardation_function(
        data.assign(radiation_damping=(0.5 * (b + swapped)).transpose(*b.dims)),
        max_points=500,
    ).transpose("time", "influenced_dof", "radiating_dof")
    a_all, b_all = dof_matrix(data, "added_mass"), dof_matrix(data, "radiation_damping")
    return FitData(
        data.omega.values,
        0.5 * (a_all + np.swapaxes(a_all, 1, 2)),
        0.5 * (b_all + np.swapaxes(b_all, 1, 2)),
        kernel.time.values,
        kernel.values,
    )


def model_fit_data(model: RadiationModel, ds: xr.Dataset) -> FitData:
    """The data a model was fitted to, as :func:`fit_radiation` used them: its DOFs, the
    frequencies in ``omega_fit_min`` … ``omega_fit_max`` less its ``excluded_frequencies``
    (the model's attributes), one forward speed."""
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    dofs = list(model.dofs)
    try:
        ds = ds.sel(influenced_dof=dofs, radiating_dof=dofs)
    except KeyError as exc:
        raise FitError(f"the data do not hold the model's DOFs {dofs}") from exc
    w = ds.omega.values
    keep = np.ones(w.size, dtype=bool)
    lo, hi = model.attrs.get("omega_fit_min"), model.attrs.get("omega_fit_max")
    if lo is not None and hi is not None:
        keep &= (w >= float(lo) * (1 - 1e-12)) & (w <= float(hi) * (1 + 1e-12))
    for excluded in model.attrs.get("excluded_frequencies", []) or []:
        keep &= ~np.isclose(w, float(excluded), rtol=1e-12, atol=0.0)
    if not keep.any():
        raise FitError("the data have no frequency in the model's fitted range")
    return fit_data(ds.isel(omega=np.flatnonzero(keep)))


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
    ds, omega_min, omega_max, exclude_suspect
) -> tuple[xr.Dataset, NDArray[np.bool_], NDArray[np.bool_], list[str]]:
    """The data to fit, which frequencies each DOF keeps (omega, dof), which hold sound
    data (those and its suspect points that are sharp features of the data:
    :func:`cummins.repair.sharp_features`) and what the user should know.

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
        for s in find_suspect_frequencies(data):
            notes.append(f"{s.omega:.4g} rad/s left out: {s.quantity}, {s.reason}")
        own = suspects_by_dof(data)
        for d, label in enumerate(labels):
            for s in own[label].suspects:
                keep[np.isclose(w, s.omega, rtol=1e-12, atol=0.0), d] = False
            for omega in own[label].features:
                sound[np.isclose(w, omega, rtol=1e-12, atol=0.0), d] = True
            if own[label].features:
                notes.append(
                    f"{label}: {own[label].feature_description()}; kept for A∞'s estimate and "
                    "left out of the fit (a broadband model does not follow it)"
                )
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
    return data, keep, sound | keep, notes


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
    (:func:`cummins.radiation.retardation.bridged_couplings`)."""
    if keep.all():
        return data
    w = data.omega.values
    out = data
    for name in ("added_mass", "radiation_damping"):
        var = data[name].transpose("omega", "influenced_dof", "radiating_dof")
        out = out.assign({name: var.copy(data=bridged_couplings(var.values, w, keep))})
    return out
