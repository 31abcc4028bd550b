"""The scoreboard of an identified radiation model: how it compares with the data it
came from, measured independently of the fit's own metrics (project issue 16).

Each function takes the data set ``ds`` (a ``HydroDB``) and a
:class:`~cummins.radiation.model.RadiationModel` of its DOFs:

* :func:`diagonal_r2` — R² of A(ω) and of B(ω) of every modelled diagonal term, recomputed
  from the model's K(jω) and A∞ against the data (A(ω) = A∞ + Im K(jω)/ω,
  B(ω) = Re K(jω); Unneland (2007) eq. 6.19), at the data's finite frequencies less
  those :func:`cummins.repair.find_suspect_frequencies` flags.
* :func:`passivity_margin` — λ_min(K(jω) + K(jω)ᴴ) / max_ω ‖K(jω)‖ on 3000 log-spaced
  frequencies from 10⁻³ to 50 rad/s; passive when ≥ −10⁻⁶ (Unneland (2007) Prop. 3.4).
* :func:`motion_rao_error` — the largest difference between the motion RAOs of the
  time-domain model (:meth:`cummins.vessel.Vessel.response`) and those of the data
  (:func:`cummins.seakeeping.frequency_domain.motion_rao`), relative to each DOF's peak, with 2 % of
  critical damping added on every DOF with restoring (and without the entries of the
  data's additional damping that vary with frequency, which a linear time-domain model
  cannot hold: :func:`constant_additional_damping`).
* :func:`added_mass_inf_error` — the model's A∞ against the data's ω = ∞ row.
* :func:`kernel_r2` — R² of K_ii(t) against the data's K(t) (with its damping tail):
  by Parseval's relation it weighs the damping at every frequency, beyond the data too.
* :func:`damping_beyond` — the model's B_ii beyond the data's last frequency against the
  data's peak and damping tail (issue 31: B → 0 as ω grows, no new peak).
* :func:`scorecard` — all of these, with the total order and stability, as one
  :class:`Scorecard`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import HydroDataError
from cummins.hydrodb import dof_matrix, single_speed
from cummins.radiation.fit.frequency import r_squared
from cummins.radiation.fit.motion import compared_motions
from cummins.radiation.fit.tail import (
    BeyondData,
    check_frequencies,
    damping_beyond_data,
)
from cummins.radiation.model import RadiationModel

#: Frequencies of the independent passivity check, rad/s (issue 16).
PASSIVITY_GRID = np.geomspace(1e-3, 50.0, 3000)
#: Passive when λ_min(K + Kᴴ) ≥ −PASSIVITY_TOLERANCE · max‖K‖ on the grid.
PASSIVITY_TOLERANCE = 1e-6
#: Fraction of critical damping added on each DOF with restoring for the RAO comparison.
DAMPING_RATIO = 0.02
#: Full-scale data (ω_max below this, rad/s) are compared from RAO_OMEGA_MIN up.
FULL_SCALE_OMEGA_MAX = 10.0
#: Lowest frequency of the RAO comparison on full-scale data, rad/s.
RAO_OMEGA_MIN = 0.15
#: Number of headings of the RAO comparison, spread over the data's.
RAO_HEADINGS = 4


@dataclass(frozen=True)
class RaoError:
    """Result of :func:`motion_rao_error`.

    Attributes
    ----------
    error
        max over headings and DOFs of max_ω |X_model − X_data| / max_ω |X_data|.
    worst_dof, worst_heading, worst_omega
        Where it occurs (label, rad, rad/s).
    per_dof
        The error of each DOF (max over headings); NaN for DOFs not compared.
    omega, headings
        The frequencies (rad/s) and headings (rad) compared.
    viscous_damping
        The diagonal B_v used (2 % of critical), N·s/m, N·m·s/rad.
    """

    error: float
    worst_dof: str
    worst_heading: float
    worst_omega: float
    per_dof: dict[str, float]
    omega: NDArray[np.float64]
    headings: NDArray[np.float64]
    viscous_damping: NDArray[np.float64]


@dataclass(frozen=True)
class Scorecard:
    """The scoreboard of one model (see the module docstring).

    Attributes
    ----------
    total_order
        States of the MIMO model.
    r2_added_mass, r2_damping
        Smallest diagonal R² of A and of B (:func:`diagonal_r2`), and where (``worst_*``).
    stable
        Every pole in the open left half-plane.
    passive, passivity_margin
        The independent check (:func:`passivity_margin`).
    rao_error
        :func:`motion_rao_error` (None without inertia, restoring or excitation).
    added_mass_inf_error
        :func:`added_mass_inf_error` (None without the data's ω = ∞ row).
    fit_seconds
        Time of the identification, when :func:`scorecard` ran it.
    notes
        What could not be measured and why.
    r2_kernel, worst_r2_kernel
        Smallest R² of K_ii(t) over the modelled diagonal (:func:`kernel_r2`), and where.
    beyond_ratio, worst_beyond
        Largest max of the model's B_ii beyond the data over the data's max B_ii
        (:func:`damping_beyond`), and where.
    beyond_ok
        Every modelled B_ii beyond the data under the data's damping tail and without a
        peak of its own (:meth:`cummins.radiation.fit.tail.BeyondData.ok`).
    """

    total_order: int
    r2_added_mass: float
    r2_damping: float
    worst_r2_added_mass: str
    worst_r2_damping: str
    stable: bool
    passive: bool
    passivity_margin: float
    rao_error: RaoError | None
    added_mass_inf_error: float | None
    fit_seconds: float | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)
    r2_kernel: float = float("nan")
    worst_r2_kernel: str = ""
    beyond_ratio: float = float("nan")
    worst_beyond: str = ""
    beyond_ok: bool = True

    def row(self) -> dict[str, object]:
        """The scoreboard columns as a flat dictionary."""
        return {
            "order": self.total_order,
            "r2_A": self.r2_added_mass,
            "r2_B": self.r2_damping,
            "stable": self.stable,
            "passive": self.passive,
            "rao_error": None if self.rao_error is None else self.rao_error.error,
            "rao_worst": None if self.rao_error is None else self.rao_error.worst_dof,
            "a_inf_error": self.added_mass_inf_error,
            "r2_K": self.r2_kernel,
            "beyond": self.beyond_ratio,
            "beyond_ok": self.beyond_ok,
            "fit_s": self.fit_seconds,
        }


def data_frequencies(ds: xr.Dataset) -> NDArray[np.bool_]:
    """Finite, positive data frequencies not flagged by the suspect-frequency detector."""
    from cummins.repair import find_suspect_frequencies

    w = ds.omega.values.astype(float)
    keep = np.isfinite(w) & (w > 0)
    try:
        suspects = find_suspect_frequencies(ds.isel(omega=np.flatnonzero(keep)))
    except HydroDataError:
        suspects = ()
    for s in suspects:
        keep &= ~np.isclose(w, s.omega, rtol=1e-12, atol=0.0)
    return keep


def diagonal_r2(ds: xr.Dataset, model: RadiationModel) -> dict[str, tuple[float, float]]:
    """R² of A(ω) and of B(ω) of each modelled diagonal term against the data.

    Recomputed from the model alone: A_model = A∞_model + Im K_ii(jω)/ω and
    B_model = Re K_ii(jω), against the data's A_ii and B_ii at their finite frequencies
    less the suspect ones (:func:`cummins.repair.find_suspect_frequencies`) — the fit's
    own metrics are not used. DOFs without a diagonal model (no radiation damping in the
    data) are left out.

    Returns
    -------
    dict
        ``{dof: (r2_added_mass, r2_damping)}``.
    """
    ds = single_speed(ds).sel(influenced_dof=list(model.dofs), radiating_dof=list(model.dofs))
    keep = np.flatnonzero(data_frequencies(ds))
    w = ds.omega.values[keep].astype(float)
    a = dof_matrix(ds, "added_mass")[keep]
    b = dof_matrix(ds, "radiation_damping")[keep]
    k = model.response(w)
    a_inf = np.asarray(model.added_mass_inf, dtype=float)
    out = {}
    for i, dof in enumerate(model.dofs):
        if model.coupling(i, i) is None and not np.any(k[:, i, i]):
            continue
        out[dof] = (
            r_squared(a[:, i, i], a_inf[i, i] + k[:, i, i].imag / w),
            r_squared(b[:, i, i], k[:, i, i].real),
        )
    return out


def modelled_diagonal(model: RadiationModel, k: NDArray) -> list[int]:
    """The DOFs with a diagonal model (``k``: K(jω) of the model, (ω, n, n))."""
    return [
        i for i in range(len(model.dofs)) if model.coupling(i, i) is not None or np.any(k[:, i, i])
    ]


def passive_part(ds: xr.Dataset, model: RadiationModel) -> xr.Dataset:
    """The data of the model's DOFs with the damping of the significant pairs made
    positive semi-definite where it is not (:func:`cummins.repair.nearest_passive_damping`
    of :func:`cummins.radiation.retardation.significant_couplings` at the model's
    ``threshold``, as the fit takes it, before it looks for suspect frequencies): what
    K(t) and the tail of a passive model are measured against."""
    from cummins.radiation.retardation import significant_couplings
    from cummins.repair import nearest_passive_damping

    ds = ds.sel(influenced_dof=list(model.dofs), radiating_dof=list(model.dofs))
    pairs = significant_couplings(ds, float(model.attrs.get("threshold", 0.01)))
    ds = nearest_passive_damping(ds, pairs)[0] if pairs else ds
    return hermitian_passive_part(ds, model)


def hermitian_passive_part(ds: xr.Dataset, model: RadiationModel) -> xr.Dataset:
    """``ds`` made passive, as the fit makes it, for the pairs the model fits as given
    (K_ij ≠ K_ji: :func:`cummins.radiation.fit.reciprocity.passive_hermitian_part` with the
    model's blocks and antisymmetric A∞); ``ds`` itself when it has none."""
    from cummins.radiation.fit.reciprocity import passive_hermitian_part

    blocks, given = [], set()
    for block in model.blocks:
        elements = sorted({(min(i, j), max(i, j)) for i, j in block.metrics})
        given |= {
            (min(i, j), max(i, j)) for (i, j), m in block.metrics.items() if m.get("as_given")
        }
        blocks.append((tuple(block.dofs), tuple(elements)))
    if not given:
        return ds
    inf = np.asarray(model.added_mass_inf, dtype=float)
    anti = np.zeros_like(inf)
    for i, j in given:
        anti[i, j] = 0.5 * (inf[i, j] - inf[j, i])
        anti[j, i] = -anti[i, j]
    return passive_hermitian_part(ds, blocks, frozenset(given), anti)[0]


def fitted_range(ds: xr.Dataset, model: RadiationModel) -> xr.Dataset:
    """``ds`` over the model's fitted range (``omega_fit_min`` … ``omega_fit_max``): beyond
    it the damping tail takes over, as in the data's K(t) the fit was measured against
    (the tanker's pitch, fitted to 3.4 rad/s where its irregular frequencies start, had
    the negative and spiking damping of 3.65–5.98 rad/s in its K(t): R² 0.75 against
    0.995)."""
    lo, hi = model.attrs.get("omega_fit_min"), model.attrs.get("omega_fit_max")
    if lo is None or hi is None:
        return ds
    w = ds.omega.values
    return ds.isel(omega=np.flatnonzero((w >= lo * (1 - 1e-12)) & (w <= hi * (1 + 1e-12))))


def own_frequencies(ds: xr.Dataset, dofs, omega=None) -> dict[str, NDArray[np.bool_]]:
    """Per DOF: the finite, positive frequencies less the suspect frequencies of that DOF's
    own curves (:func:`cummins.repair.suspects_by_dof`), as the fit leaves them out of its
    couplings: not the points of a sharp resonance the fit keeps (``DofSuspects.kept``:
    the MHK RM1's surge at 1.96–2.24 rad/s, R² of K(t) 0.89 bridged against the fit's
    0.98), nor those of the other DOFs (a spike of an irregular frequency near the
    last frequency would otherwise set the damping tail the data's K(t) takes, and a
    point another DOF spoils bridged a resonance the DOF keeps: the MHK RM1's surge at
    1.9 rad/s, R² of K(t) 0.86 against the fit's 0.90). The suspects are found on all of
    ``ds`` (as the fit finds them, before it cuts its range), the mask is on ``omega``
    (default: the frequencies of ``ds``)."""
    from cummins.repair import suspects_by_dof

    w = (ds.omega.values if omega is None else np.asarray(omega)).astype(float)
    every = ds.omega.values.astype(float)
    finite = np.isfinite(w) & (w > 0)
    try:
        own = suspects_by_dof(ds.isel(omega=np.flatnonzero(np.isfinite(every) & (every > 0))))
    except HydroDataError:
        own = {}
    out = {}
    for dof in dofs:
        keep = finite.copy()
        for suspect in own[dof].suspects if dof in own else ():
            if suspect.omega not in own[dof].kept:
                keep &= ~np.isclose(w, suspect.omega, rtol=1e-12, atol=0.0)
        out[dof] = keep
    return out


def own_data(ds: xr.Dataset, dof: str, keep: NDArray[np.bool_]) -> xr.Dataset:
    """The data of one DOF's diagonal term as the fit measures it: its added mass and
    damping bridged (linearly) over the frequencies it does not keep
    (:func:`own_frequencies`), up to the last one it keeps — so that its damping tail is
    fitted to the same points (:func:`cummins.radiation.infinite_frequency.bridged_couplings`)."""
    from cummins.radiation.infinite_frequency import bridged_couplings

    last = int(np.flatnonzero(keep)[-1])
    one = ds.sel(influenced_dof=[dof], radiating_dof=[dof]).isel(omega=slice(0, last + 1))
    w = one.omega.values.astype(float)
    kept = keep[: last + 1, None]
    out = one
    for name in ("added_mass", "radiation_damping"):
        var = one[name].transpose("omega", "influenced_dof", "radiating_dof")
        bridged = bridged_couplings(var.values, w, kept, from_zero=name == "radiation_damping")
        out = out.assign({name: var.copy(data=bridged)})
    return out


def kernel_r2(ds: xr.Dataset, model: RadiationModel) -> dict[str, float]:
    """R² of K_ii(t) of each modelled diagonal term against the data's.

    The data's K(t) is :func:`cummins.radiation.retardation.retardation_function` (with
    its damping tail beyond the last frequency) of the DOF's data bridged over the suspect
    frequencies (:func:`own_data`), on the default time grid of the data less the
    suspect frequencies; the model's is its impulse response there. By Parseval's
    relation it weighs the damping error at every frequency alike, beyond the data too.

    Returns
    -------
    dict
        ``{dof: r2}`` over the DOFs of :func:`diagonal_r2`.
    """
    from cummins.radiation.retardation import default_time_grid, retardation_function

    full = passive_part(single_speed(ds), model)
    ds = fitted_range(full, model)
    t = default_time_grid(ds.isel(omega=np.flatnonzero(data_frequencies(ds))))
    fitted = np.asarray(model.impulse_response(t), dtype=float)
    k = model.response(ds.omega.values[ds.omega.values > 0].astype(float))
    dofs = [model.dofs[i] for i in modelled_diagonal(model, k)]
    kept = own_frequencies(full, dofs, ds.omega.values)
    out = {}
    for dof in dofs:
        i = model.dofs.index(dof)
        data = retardation_function(own_data(ds, dof, kept[dof]), t).values[:, 0, 0]
        out[dof] = r_squared(data, fitted[:, i, i])
    return out


def damping_beyond(ds: xr.Dataset, model: RadiationModel) -> dict[str, BeyondData]:
    """The model's B_ii beyond the data's last frequency against the data's peak B_ii and
    the data's damping tail (:func:`cummins.radiation.damping_tail.fit_damping_tail` of the
    DOF's data bridged over the suspect frequencies, :func:`own_data`, as its K(t) takes
    it), per modelled diagonal term (:func:`cummins.radiation.fit.tail.damping_beyond_data`,
    from ω_N to 10³ ω_N): B → 0 as ω grows, under the data's tail, no peak of its own."""
    from cummins.radiation.damping_tail import fit_damping_tail

    full = passive_part(single_speed(ds), model)
    ds = fitted_range(full, model)
    w_all = ds.omega.values.astype(float)
    k = model.response(w_all[w_all > 0])
    dofs = [model.dofs[i] for i in modelled_diagonal(model, k)]
    kept = own_frequencies(full, dofs, ds.omega.values)
    out = {}
    for dof in dofs:
        i = model.dofs.index(dof)
        one = own_data(ds, dof, kept[dof])
        w = one.omega.values.astype(float)
        b = one.radiation_damping.values.reshape(w.size)
        a = one.added_mass.values.reshape(w.size)
        grid = check_frequencies(float(w[-1]))
        tail = fit_damping_tail(w, b, added_mass=a)
        peak = float(np.abs(b).max())
        out[dof] = damping_beyond_data(model.response(grid)[:, i, i].real, grid, peak, tail)
    return out


def passivity_margin(model: RadiationModel, omega: ArrayLike | None = None) -> float:
    """min_ω λ_min(K(jω) + K(jω)ᴴ) / max_ω ‖K(jω)‖₂ on ``omega`` (default
    :data:`PASSIVITY_GRID`: 3000 log-spaced frequencies, 10⁻³–50 rad/s).

    An independent check of passivity (Unneland (2007) Prop. 3.4): a dense sweep of the
    model's own K(jω), no crossing test, no scaling of the DOFs. Passive when
    ≥ −:data:`PASSIVITY_TOLERANCE`.
    """
    w = PASSIVITY_GRID if omega is None else np.asarray(omega, dtype=float)
    if model.total_order == 0:
        return 0.0
    k = model.response(w)
    herm = k + np.conj(np.swapaxes(k, 1, 2))
    lam = np.linalg.eigvalsh(herm)[:, 0]
    scale = float(np.linalg.norm(k, ord=2, axis=(1, 2)).max()) or 1.0
    return float(lam.min() / scale)


def _headings(ds: xr.Dataset, count: int) -> NDArray[np.float64]:
    beta = np.asarray(ds.wave_direction.values, dtype=float)
    if beta.size <= count:
        return beta
    index = np.unique(np.round(np.linspace(0, beta.size - 1, count)).astype(int))
    return beta[index]


def critical_damping(
    ds: xr.Dataset, ratio: float = DAMPING_RATIO, added_mass_inf: ArrayLike | None = None
) -> NDArray[np.float64]:
    """b_ii = 2 ζ √(C_ii (M_ii + A∞_ii)) on each DOF with C_ii > 0, else 0.

    C is the hydrostatic plus any additional (mooring) stiffness; A∞ the data's ω = ∞
    row, else ``added_mass_inf``, else Ogilvie's estimate from the finite frequencies.
    """
    from cummins.radiation.infinite_frequency import added_mass_inf as estimate

    c = np.diag(dof_matrix(ds, "hydrostatic_stiffness")).copy()
    if "additional_stiffness" in ds:
        c = c + np.diag(dof_matrix(ds, "additional_stiffness"))
    m = np.diag(dof_matrix(ds, "inertia_matrix"))
    if "added_mass_inf" in ds:
        a_inf = np.diag(dof_matrix(ds, "added_mass_inf"))
    elif added_mass_inf is not None:
        a_inf = np.diag(np.asarray(added_mass_inf, dtype=float))
    else:
        a_inf = np.diag(estimate(ds, method="ogilvie").values)
    total = m + a_inf
    ok = (c > 0) & (total > 0)
    return np.where(ok, 2.0 * ratio * np.sqrt(np.where(ok, c * total, 0.0)), 0.0)


def motion_rao_error(
    ds: xr.Dataset,
    model: RadiationModel,
    *,
    headings: int = RAO_HEADINGS,
    damping_ratio: float = DAMPING_RATIO,
) -> RaoError:
    """How far the motions of the time-domain model are from the data's (issue 16).

    B_v = ``damping_ratio`` of critical damping on each DOF with C_ii > 0
    (:func:`critical_damping`); X_data = ``motion_rao(ds, ω, β, viscous_damping=B_v)`` at
    the data frequencies (those ≥ 0.15 rad/s for full-scale data, ω_max < 10 rad/s) and
    ``headings`` headings spread over the data's; X_model = ``Vessel.response`` of
    ``vessel_from_hydrodb(ds, model, viscous_damping=B_v)`` with the data's excitation at
    the same (ω, β). The error is max over headings and DOFs of
    max_ω |X_model − X_data| / max_ω |X_data|; a (heading, DOF) whose peak is below
    :data:`cummins.radiation.fit.motion.NEGLIGIBLE_MOTION` of the DOF's peak over the headings or of
    the largest peak of its kind at that heading is not compared (the sway of a
    symmetric ship in head seas is rounding noise).

    Raises
    ------
    HydroDataError
        Without inertia, restoring or excitation.
    """
    import warnings

    from cummins.seakeeping.frequency_domain import motion_rao
    from cummins.vessel import vessel_from_hydrodb

    ds = single_speed(ds)
    for name in ("inertia_matrix", "hydrostatic_stiffness", "excitation_force"):
        if name not in ds:
            raise HydroDataError(
                f"the motion-RAO error needs {name} in the data",
                path=ds.attrs.get("source_file"),
                hint="the motions need the rigid-body inertia, the restoring and the wave "
                "excitation; without them compare K (R² of A and B, or reduce's tol)",
            )
    dofs = list(model.dofs)
    ds = constant_additional_damping(ds.sel(influenced_dof=dofs, radiating_dof=dofs))
    w_all = ds.omega.values.astype(float)
    finite = np.isfinite(w_all) & (w_all > 0)
    w = w_all[finite]
    if w.max() < FULL_SCALE_OMEGA_MAX:
        w = w[w >= RAO_OMEGA_MIN]
    beta = _headings(ds, headings)
    b_v = np.diag(critical_damping(ds, damping_ratio, model.added_mass_inf))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        x_data = motion_rao(ds, w, beta, viscous_damping=b_v)
        vessel = vessel_from_hydrodb(ds, model, viscous_damping=b_v)
    x_data = x_data.transpose("omega", "wave_direction", "dof")
    force = ds.excitation_force.sel(omega=w, wave_direction=beta)
    force = force.rename({d: "dof" for d in force.dims if d not in ("omega", "wave_direction")})
    force = force.sel(dof=dofs).transpose("omega", "wave_direction", "dof").values
    x_model = np.stack(
        [vessel.response(w, force[:, h, :]) for h in range(beta.size)], axis=1
    )  # (omega, heading, dof)
    x = x_data.values
    peak = np.abs(x).max(axis=0)  # (heading, dof)
    diff = np.abs(x_model - x).max(axis=0)
    compared = compared_motions(peak.T, dofs).T
    ratio = np.where(compared, diff / np.where(peak > 0, peak, 1.0), np.nan)
    per_dof = {
        dof: float(np.nanmax(ratio[:, d])) if compared[:, d].any() else float("nan")
        for d, dof in enumerate(dofs)
    }
    if not compared.any():
        return RaoError(0.0, "", float("nan"), float("nan"), per_dof, w, beta, b_v)
    h, d = np.unravel_index(int(np.nanargmax(ratio)), ratio.shape)
    k = int(np.argmax(np.abs(x_model[:, h, d] - x[:, h, d])))
    return RaoError(float(ratio[h, d]), dofs[d], float(beta[h]), float(w[k]), per_dof, w, beta, b_v)


def constant_additional_damping(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with the entries of ``additional_damping`` that vary with frequency set to
    zero (MSS's surge, sway and yaw estimates): a linear time-domain model holds one
    constant B_v, and :func:`cummins.vessel.vessel_from_hydrodb` leaves them out, so the
    RAOs of the data are compared without them too."""
    if "additional_damping" not in ds or "omega" not in ds.additional_damping.dims:
        return ds
    d = ds.additional_damping
    spread = d.max("omega") - d.min("omega")
    constant = spread <= 1e-9 * np.abs(d).max("omega").clip(min=1e-300)
    return ds.assign(additional_damping=d.where(constant, 0.0))


def added_mass_inf_error(ds: xr.Dataset, model: RadiationModel) -> float | None:
    """max_i |A∞_model,ii − A∞_data,ii| / |A∞_data,ii| over the diagonal terms with a
    model, or None when the data have no ω = ∞ row.

    DOFs whose A∞ is below 10⁻³ of the largest A(ω) of their kind (translation,
    rotation, generalized mode) are measured against that scale instead (A∞ of the yaw
    of an axisymmetric body is zero).
    """
    from cummins.hydrodb import is_rotation

    ds = single_speed(ds)
    if "added_mass_inf" not in ds:
        return None
    dofs = list(model.dofs)
    ds = ds.sel(influenced_dof=dofs, radiating_dof=dofs)
    data = np.diag(dof_matrix(ds, "added_mass_inf"))
    a = np.abs(np.diagonal(dof_matrix(ds, "added_mass"), axis1=1, axis2=2)).max(axis=0)
    kind = np.array([is_rotation(d) for d in dofs])
    fitted = np.diag(np.asarray(model.added_mass_inf, dtype=float))
    errors = []
    for i in range(len(dofs)):
        if model.coupling(i, i) is None:
            continue
        scale = max(abs(data[i]), 1e-3 * float(a[kind == kind[i]].max()))
        errors.append(abs(fitted[i] - data[i]) / scale)
    return float(max(errors)) if errors else None


def scorecard(
    ds: xr.Dataset,
    model: RadiationModel | None = None,
    *,
    fit: Callable[[xr.Dataset], RadiationModel] | None = None,
    reference_added_mass_inf: xr.Dataset | None = None,
) -> Scorecard:
    """The scoreboard of ``model`` (or of ``fit(ds)``, timed) against ``ds``.

    Parameters
    ----------
    ds
        The data (one forward speed is taken).
    model
        The model; or None, and ``fit`` (default :func:`cummins.radiation.fit.fit_radiation`) is
        run and timed.
    reference_added_mass_inf
        Data holding the ω = ∞ row to compare A∞ with, when ``ds`` had it removed to
        measure the estimate from the finite frequencies.
    """
    ds = single_speed(ds)
    seconds = None
    if model is None:
        from cummins.radiation.fit import fit_radiation

        run = fit or fit_radiation
        start = time.perf_counter()
        model = run(ds)
        seconds = time.perf_counter() - start
    notes = []
    r2 = diagonal_r2(ds, model)
    worst_a = min(r2, key=lambda d: r2[d][0]) if r2 else ""
    worst_b = min(r2, key=lambda d: r2[d][1]) if r2 else ""
    margin = passivity_margin(model)
    try:
        rao = motion_rao_error(ds, model)
    except HydroDataError as exc:
        rao = None
        notes.append(f"no RAO error: {exc}")
    reference = ds if reference_added_mass_inf is None else reference_added_mass_inf
    a_inf = added_mass_inf_error(reference, model)
    kernel = kernel_r2(ds, model) if r2 else {}
    worst_k = min(kernel, key=lambda d: kernel[d]) if kernel else ""
    beyond = damping_beyond(ds, model) if r2 else {}
    worst_beyond = max(beyond, key=lambda d: beyond[d].ratio) if beyond else ""
    return Scorecard(
        total_order=model.total_order,
        r2_added_mass=r2[worst_a][0] if r2 else float("nan"),
        r2_damping=r2[worst_b][1] if r2 else float("nan"),
        worst_r2_added_mass=worst_a,
        worst_r2_damping=worst_b,
        stable=model.is_stable(),
        passive=margin >= -PASSIVITY_TOLERANCE,
        passivity_margin=margin,
        rao_error=rao,
        added_mass_inf_error=a_inf,
        fit_seconds=seconds,
        notes=tuple(notes),
        r2_kernel=kernel[worst_k] if kernel else float("nan"),
        worst_r2_kernel=worst_k,
        beyond_ratio=beyond[worst_beyond].ratio if beyond else float("nan"),
        worst_beyond=worst_beyond,
        beyond_ok=all(found.ok() for found in beyond.values()),
    )
