"""The reciprocity of the data an identification is fitted to: what the fit does where
A_ij ≠ A_ji or B_ij ≠ B_ji at zero speed.

At zero speed the added mass and damping are symmetric (reciprocity: Newman (1977) ch. 6),
and a model of the symmetric part ½(X + Xᵀ) is what the physics asks for. Solvers do not
always give it: a panel mesh leaves A_ij − A_ji of a few per cent, constant over frequency
(kept in A∞: :func:`antisymmetric_added_mass`), and some runs are far from reciprocal
(WAMIT's RM3 float and spar: A(1,7) = 44.9 but A(7,1) = −14.7 in its own ``.out``). Where
the data's reciprocal part alone cannot reproduce the data's own motions within what the
motion target allows — :func:`motion_error_floor` of a block's pairs made reciprocal,
above :data:`~cummins.radiation.fit.options.MOTION_AIM` × ``motion_tol`` — the block's
couplings are fitted **as given** (:func:`reciprocity_of`): K_ij and K_ji each to its own
data, a non-symmetric K(s) that is still passive in the MIMO sense, K(jω) + K(jω)ᴴ ⪰ 0
(:mod:`cummins.radiation.fit.vector`). Without the inertia no motions say whether the
difference matters: the reciprocal part is fitted, as before, and a note says where it
misses the R² target of a coupling in either direction (``reciprocity="as-given"``
fits them as given). The fit's notes name the couplings and how far from reciprocal
they are; WEC-Sim and MSS fit each coupling as given too.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.hydrodb import dof_matrix
from cummins.radiation.fit.frequency import r_squared
from cummins.radiation.fit.motion import MotionSensitivity
from cummins.radiation.fit.options import MOTION_AIM

if TYPE_CHECKING:
    from cummins.radiation.fit.data import FitData

#: A pair is a candidate for the fit as given when its A_ij − A_ji (less what A∞ keeps)
#: or B_ij − B_ji reaches this fraction of √(max|X_ii| max|X_jj|) at some frequency: a
#: smaller difference moves nothing a model could show.
AS_GIVEN_MIN = 1e-3
#: Pairs named in a block's note (the largest differences first).
NAMED_PAIRS = 3


#: A pair whose A_ij and A_ji (or B) differ by more than this fraction of the larger one
#: (and of the diagonal scale √(X_ii X_jj)) is named: the fit uses their average.
ASYMMETRY_TOL = 0.1


def motion_error_floor(
    sensitivity: MotionSensitivity, measured: FitData, antisymmetric: NDArray
) -> float:
    """The motion error of what the model is fitted to: the data's reciprocal part
    (½(A + Aᵀ), ½(B + Bᵀ) and the antisymmetry kept in A∞; the pairs fitted as given as
    they are) put in the place of the model,
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
    raw: xr.Dataset, keep_dof: NDArray, modelled=None, skip=frozenset()
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
    skip
        Pairs (i, j), i < j, that keep nothing: fitted as given, they estimate their own
        antisymmetric A∞ (:func:`reciprocity_of`).

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
        if (i, j) in skip:
            continue
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


def asymmetric_pairs(data: xr.Dataset, as_given=frozenset()) -> list[str]:
    """One message per DOF pair (i < j) whose A_ij ≠ A_ji or B_ij ≠ B_ji beyond
    :data:`ASYMMETRY_TOL`: the worst frequency and both values. The fit uses
    ½(X_ij + X_ji) (the physics wants them equal at zero speed), or each as given for the
    pairs ``as_given`` (:func:`reciprocity_of`); at zero speed so large a difference can
    mean a DOF order or sign convention mixed up between the two halves of the matrix, at
    forward speed it is physics (the Timman–Newman relations), which the message says."""
    out = []
    labels = [str(d) for d in data.influenced_dof.values]
    w = data.omega.values
    speed = float(data.coords["forward_speed"]) if "forward_speed" in data.coords else 0.0
    advice = "; check the DOF order and signs of the data"
    # both halves of one sign (X_ji a scaled X_ij, not −X_ij): no mixed-up sign
    # convention, but the solver's own asymmetry (HAMS's cylinder: B[Surge, Pitch] −234
    # and B[Pitch, Surge] −303), as cummins check's symmetry finding says
    same_sign = (
        "; both of one sign: the solver's own asymmetry (mesh, solver settings), "
        "not a mixed-up sign convention (cummins check, symmetry, names where)"
    )
    if speed and data.attrs.get("speed_terms_removed"):  # memory_part: vessel_at_speed
        advice = (
            f" (at {speed:g} m/s the difference is physics, X_ij(U) = X_ji(−U): the "
            "memory is fitted to the average and the antisymmetric part is kept apart, "
            "U·A∞ damping and U K¹ of the zero-speed model)"
        )
    elif speed:  # the Timman–Newman relations: X_ij(U) = X_ji(−U), not X_ji(U)
        advice = (
            f" (at {speed:g} m/s the difference is physics, X_ij(U) = X_ji(−U): the "
            "antisymmetric part, the speed terms U·A∞ and U K¹, is lost by this plain fit; "
            "vessel_at_speed and fit_per_speed keep it apart)"
        )
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
                        f"{w[k]:.4g} rad/s ({int(bad.sum())} frequencies): "
                        + (
                            "fitted as given"
                            if (i, j) in as_given
                            else "the fit uses their average"
                        )
                        + (same_sign if not speed and _one_sign(x, i, j, bad) else advice)
                    )
    return out


@dataclass(frozen=True)
class Reciprocity:
    """What :func:`reciprocity_of` decided.

    Attributes
    ----------
    as_given
        The pairs (i, j), i < j, fitted as given (K_ij ≠ K_ji).
    notes
        One per block fitted as given: why, and how far from reciprocal.
    floors
        Per block (its DOFs): the motion error of the data with the block's pairs made
        reciprocal, against the data's own motions (None without the inertia).
    added_mass_inf
        (n, n) the antisymmetric part of A∞ of the pairs fitted as given: ½(A_ij − A_ji)
        at ω → 0 (the data's ω = 0 row, else their lowest frequency), zero elsewhere.
        A model passive as K + Kᴴ ⪰ 0 has its antisymmetric added mass equal at ω → 0 and
        ω → ∞ (:mod:`cummins.radiation.fit.vector`), and at ω → 0, where the damping
        vanishes, jω(A_ij − A_ji − 2A∞_ij) alone would decide the sign of K + Kᴴ: the
        data's low-frequency value is the one passivity leaves (WEC-Sim's RM3: 0.4 % off
        the data's motions; the ω = ∞ row's: 8 %).
    """

    as_given: frozenset[tuple[int, int]] = frozenset()
    notes: list[str] = field(default_factory=list)
    floors: dict[tuple[int, ...], float | None] = field(default_factory=dict)
    added_mass_inf: NDArray[np.float64] | None = None


def reciprocity_of(
    user: xr.Dataset,
    keep_dof: NDArray,
    blocks,
    antisymmetric: NDArray,
    sensitivity: MotionSensitivity | None,
    *,
    option: str = "auto",
    motion_tol: float,
    r2_coupling: float,
) -> Reciprocity:
    """Which pairs of which blocks are fitted as given (module docstring).

    Parameters
    ----------
    user
        The user's data at the fitted frequencies (one speed, zero).
    keep_dof
        (omega, n) which frequencies each DOF keeps.
    blocks
        ``[(dofs, elements)]``: the blocks of coupled DOFs and their pairs (i ≤ j).
    antisymmetric
        The constant A_ij − A_ji kept in A∞ (:func:`antisymmetric_added_mass`), halved.
    sensitivity
        The motion sensitivity of ``user`` (None without inertia or restoring).
    option
        One of :data:`cummins.radiation.fit.options.RECIPROCITY_OPTIONS`.
    motion_tol, r2_coupling
        The targets: a block whose reciprocal part is further than
        :data:`~cummins.radiation.fit.options.MOTION_AIM` × ``motion_tol`` from the data's
        motions is fitted as given (without motions, a note where the reciprocal part
        reaches R² < ``r2_coupling`` on a pair, either direction).
    """
    if option == "average":
        return Reciprocity()
    labels = [str(d) for d in user.influenced_dof.values]
    a, b = dof_matrix(user, "added_mass"), dof_matrix(user, "radiation_damping")
    as_given: set[tuple[int, int]] = set()
    notes, floors = [], {}
    for dofs, elements in blocks:
        far = {}
        for i, j in elements:
            if i == j:
                continue
            use = keep_dof[:, i] & keep_dof[:, j]
            if use.sum() < 2:
                continue
            parts = _asymmetry(a[use], b[use], i, j, antisymmetric[i, j])
            if max(parts.values()) >= AS_GIVEN_MIN:
                far[(i, j)] = parts
        if not far:
            continue
        name = "-".join(labels[d] for d in dofs)
        floor = None
        if sensitivity is not None:
            floor = _block_floor(sensitivity, a, b, far, antisymmetric)
            floors[tuple(dofs)] = floor
            aim = MOTION_AIM * motion_tol
            if option == "auto" and floor <= aim:
                continue
            why = (
                f"their reciprocal part alone is {100 * floor:.3g} % off their own motions "
                f"(the fit aims at {100 * aim:.2g} %)"
            )
        else:
            # no motions to judge by: the reciprocal part, as before (measured: judged by
            # the R² of its couplings instead, single bodies whose small couplings are
            # noise, a WAMIT WEC3 and plate, OC4 semi, lost R² on their diagonals)
            worst, where = _worst_reciprocal_r2(a, b, keep_dof, far, antisymmetric, labels)
            if option == "auto":
                if worst < r2_coupling:
                    notes.append(
                        f"{name}: the data are not reciprocal: their reciprocal part, which "
                        f"the fit models, reaches R² {worst:.3g} on {where} (target "
                        f"{r2_coupling}); without the inertia no motions say whether it "
                        "matters: reciprocity='as-given' (--reciprocity as-given) fits K_ij "
                        "and K_ji each"
                    )
                continue
            why = f"their reciprocal part reaches R² {worst:.3g} on {where}"
        as_given |= set(far)
        named = sorted(far, key=lambda p: -max(far[p].values()))[:NAMED_PAIRS]
        listed = ", ".join(
            f"{labels[i]}-{labels[j]} (A {100 * far[(i, j)]['A']:.3g} %, "
            f"B {100 * far[(i, j)]['B']:.3g} %)"
            for i, j in named
        )
        notes.append(
            f"{name}: the data are not reciprocal (A_ij ≠ A_ji, B_ij ≠ B_ji): {why}; "
            f"{len(far)} couplings fitted as given, K_ij and K_ji each to its own data "
            f"(largest |X_ij − X_ji| of √(X_ii X_jj): {listed}), passive as "
            "K(jω) + K(jω)ᴴ ⪰ 0"
        )
    zero = dof_matrix(user, "added_mass_zero") if "added_mass_zero" in user else a[0]
    inf = np.zeros_like(zero)
    for i, j in as_given:
        inf[i, j] = 0.5 * (zero[i, j] - zero[j, i])
        inf[j, i] = -inf[i, j]
    return Reciprocity(frozenset(as_given), notes, floors, inf)


def _asymmetry(a: NDArray, b: NDArray, i: int, j: int, constant: float) -> dict[str, float]:
    """max_ω |X_ij − X_ji| / √(max|X_ii| max|X_jj|) for A (less the constant part kept in
    A∞) and B."""
    out = {}
    for symbol, x, offset in (("A", a, 2 * constant), ("B", b, 0.0)):
        scale = np.sqrt(np.abs(x[:, i, i]).max() * np.abs(x[:, j, j]).max())
        diff = np.abs(x[:, i, j] - x[:, j, i] - offset).max()
        out[symbol] = float(diff / scale) if scale > 0 else 0.0
    return out


def _block_floor(sensitivity: MotionSensitivity, a, b, pairs, antisymmetric) -> float:
    """The motion error of the data with ``pairs`` made reciprocal (their average, and the
    constant part of A_ij − A_ji that A∞ keeps), against the data's own motions."""
    rows = sensitivity.compared_frequencies()
    w = sensitivity.omega[rows][:, None, None]
    k = b[rows] + 1j * w * a[rows]
    for i, j in pairs:
        for p, q in ((i, j), (j, i)):
            average = 0.5 * (b[rows, p, q] + b[rows, q, p]) + 1j * w[:, 0, 0] * (
                0.5 * (a[rows, p, q] + a[rows, q, p]) + antisymmetric[p, q]
            )
            k[:, p, q] = average
    return sensitivity.error_of(k, np.zeros(antisymmetric.shape))[0]


def _worst_reciprocal_r2(a, b, keep_dof, pairs, antisymmetric, labels) -> tuple[float, str]:
    """The smallest R² of the reciprocal part of ``pairs`` against X_ij and X_ji, and
    where (``"A[Surge, Pitch]"``)."""
    worst, where = np.inf, ""
    for i, j in pairs:
        use = keep_dof[:, i] & keep_dof[:, j]
        for symbol, x, offset in (("A", a, antisymmetric), ("B", b, 0.0 * antisymmetric)):
            average = 0.5 * (x[use, i, j] + x[use, j, i])
            for p, q in ((i, j), (j, i)):
                value = r_squared(x[use, p, q], average + offset[p, q])
                if value < worst:
                    worst, where = value, f"{symbol}[{labels[p]}, {labels[q]}]"
    return float(worst), where


def passive_hermitian_part(
    data: xr.Dataset, blocks, as_given, antisymmetric_inf: NDArray
) -> tuple[xr.Dataset, str]:
    """The data with the couplings fitted as given made passive as a model fitted as given
    must be: frequency by frequency, the Hermitian part H = ½(B + Bᵀ) + jω(½(A − Aᵀ) −
    A∞ₐ) (that of K(jω) + K(jω)ᴴ, A∞ₐ the antisymmetric A∞ the model keeps:
    :attr:`Reciprocity.added_mass_inf`) of each block holding such a pair, DOF-scaled as
    the passivity check scales it (s_i = 1/√max_ω B_ii) and its unmodelled pairs set to
    zero, has its negative eigenvalues set to zero (Higham (1988), as
    :func:`cummins.repair.nearest_passive_damping` does for ½(B + Bᵀ)); ½(B + Bᵀ) of the
    modelled pairs and ½(A − Aᵀ) of those fitted as given take the result, ½(A + Aᵀ) and
    ½(B − Bᵀ) stay. A passive model is fitted to it (the passivity step then costs little,
    as for the damping alone); the data are not passive there when A_ij − A_ji varies more
    over frequency than the damping allows — WEC-Sim's RM3, whose projection moves the
    motions by 0.4 %. Returns the data and a note (empty when nothing moved)."""
    a = dof_matrix(data, "added_mass")
    b = dof_matrix(data, "radiation_damping")
    w = data.omega.values
    a_out, b_out = a.copy(), b.copy()
    count, worst, worst_omega = 0, 0.0, float("nan")
    for dofs, elements in blocks:
        if not any((i, j) in as_given for i, j in elements):
            continue
        d = np.asarray(dofs)
        local = {dof: k for k, dof in enumerate(dofs)}
        inside = np.zeros((d.size, d.size), dtype=bool)
        for i, j in elements:
            inside[local[i], local[j]] = inside[local[j], local[i]] = True
        given = np.zeros_like(inside)
        for i, j in elements:
            if (i, j) in as_given:
                given[local[i], local[j]] = given[local[j], local[i]] = True
        sub = np.ix_(np.arange(w.size), d, d)
        sym_b = 0.5 * (b[sub] + np.swapaxes(b[sub], 1, 2))
        anti_a = 0.5 * (a[sub] - np.swapaxes(a[sub], 1, 2)) - antisymmetric_inf[np.ix_(d, d)]
        h = np.where(inside, sym_b, 0.0) + 1j * w[:, None, None] * np.where(given, anti_a, 0.0)
        peak = np.abs(np.diagonal(sym_b, axis1=1, axis2=2)).max(axis=0)
        if not np.all(peak > 0):
            continue
        scale = 1.0 / np.sqrt(peak)
        lam, vec = np.linalg.eigh(h * np.outer(scale, scale)[None])
        bad = lam[:, 0] < 0
        if not bad.any():
            continue
        k = int(np.argmin(lam[:, 0]))
        if lam[k, 0] < worst:
            worst, worst_omega = float(lam[k, 0]), float(w[k])
        count += int(bad.sum())
        fixed = np.einsum("wik,wk,wjk->wij", vec, np.maximum(lam, 0.0), vec.conj())
        fixed = fixed / np.outer(scale, scale)[None]
        new_b = np.where(inside, fixed.real, sym_b) + 0.5 * (b[sub] - np.swapaxes(b[sub], 1, 2))
        new_anti = np.where(given, fixed.imag / w[:, None, None], anti_a)
        new_a = (
            0.5 * (a[sub] + np.swapaxes(a[sub], 1, 2)) + new_anti + antisymmetric_inf[np.ix_(d, d)]
        )
        rows = np.flatnonzero(bad)
        a_out[np.ix_(rows, d, d)] = new_a[rows]
        b_out[np.ix_(rows, d, d)] = new_b[rows]
    if not count:
        return data, ""
    out = data.copy()
    for name, values in (("added_mass", a_out), ("radiation_damping", b_out)):
        var = data[name].transpose("omega", "influenced_dof", "radiating_dof")
        out[name] = var.copy(data=values).transpose(*data[name].dims)
    note = (
        f"the couplings fitted as given are not passive as a non-reciprocal model must be "
        f"(K + Kᴴ = B + Bᵀ + 2jω(½(A − Aᵀ) − A∞ₐ) ⪰ 0) at {count} frequencies (worst "
        f"eigenvalue {worst:.3g} of the DOF-scaled damping peak, {worst_omega:.4g} rad/s): "
        "fitted to its nearest passive part"
    )
    return out, note


def _one_sign(x: np.ndarray, i: int, j: int, bad: np.ndarray) -> bool:
    """X_ij and X_ji of one sign at every frequency where they differ too much
    (:func:`asymmetric_pairs`)."""
    return bool(np.all(x[bad, i, j] * x[bad, j, i] > 0))
