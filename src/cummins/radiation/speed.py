"""Forward speed: encounter frequency, per-speed models, STF speed terms, K⁰/K¹/K².

Hjulstad (2004), ch. 3, 5.3–5.4, 6, 10 and 12.1. Three ways to give a
radiation model a forward speed U (m/s):

1. **Per-speed fits** (:func:`fit_per_speed`): one :class:`~cummins.radiation.model.RadiationModel`
   per speed of a multi-speed database (``forward_speed`` dimension, e.g. the MSS S-175
   at 5 speeds), blended linearly in U between the two neighbouring fitted speeds
   (:meth:`SpeedModels.at`).
2. **Salvesen–Tuck–Faltinsen speed terms on zero-speed data** (:func:`stf_speed_terms`,
   Hjulstad (2004) eqs. 3.29, 3.33, 5.45–5.46, 10.1, §6; aft-section terms omitted as in
   the thesis). In impedance form, Z(ω) = B(ω) + jω A(ω) (force −Z·velocity, cummins'
   convention x(t) = Re{X e^{jωt}}), with s = jω::

       Z_U = Z₀ + (U/s)(Z₀E − EᵀZ₀) − (U²/s²) EᵀZ₀E,   E = e_heave e_pitchᵀ − e_sway e_yawᵀ

   which is, term by term, A₃₅ = A⁰₃₅ − U B⁰₃₃/ω², B₃₅ = B⁰₃₅ + U A⁰₃₃ (eq. 3.33/10.1),
   A₅₃ = A⁰₅₃ + U B⁰₃₃/ω², B₅₃ = B⁰₅₃ − U A⁰₃₃ (the thesis' code, App. C.2–C.3),
   A₅₅ = A⁰₅₅ + U²A⁰₃₃/ω², B₅₅ = B⁰₅₅ + U²B⁰₃₃/ω² (eqs. 3.29, 5.45–5.46), the mirror
   terms in sway–yaw (26, 62, 66) and the surge/roll couplings (15, 51, 46, 64) of the
   thesis' ``AugmentWithBinf`` table (§6). The expressions are the same in z-up and in
   Fossen's z-down axes (every term flips sign twice or not at all); on the S-175
   (ShipX/VERES strip theory, z-down) they reproduce the data at 10.29 m/s from the
   data at 0 m/s to within 0.8 % of each term's peak above the first frequency
   (tests/test_speed.py).
3. **Speed kernels** (:func:`speed_dependent_model`, eqs. 3.28–3.36): the memory
   kernel K_U = K⁰ + U K¹ + U² K² (eq. 3.28), with K⁰ the fitted zero-speed model and
   K¹, K² derived *exactly* from it instead of by separate transforms: since
   Z₀(s) = K⁰(s) + s A∞, the STF terms are K⁰(s)/s and K⁰(s)/s² plus constants. For a
   coupling model K(s) = c (sI − a)⁻¹ b **[derived, not in thesis]**::

       K(s)/s  = c a⁻¹ (sI − a)⁻¹ b − (c a⁻¹ b)/s
       K(s)/s² = c a⁻² (sI − a)⁻¹ b − (c a⁻² b)/s − (c a⁻¹ b)/s²

   so K¹ and K² have the *same poles* as K⁰ (stable when K⁰ is) and new output vectors.
   The terms that are not memory are kept separately, as in the thesis: the U·α∞
   infinite-frequency damping (eqs. 3.35 and §6: B₃₅(∞) = +U A∞₃₃, B₅₃(∞) = −U A∞₃₃,
   B₂₆(∞) = −U A∞₂₂, B₆₂(∞) = +U A∞₂₂ …) and the 1/s terms, which act on the
   displacement: a *radiation restoring* stiffness (Hjulstad (2004) §10.2: "the
   subtracted constant corresponds to a pure integrator … a radiation restoring
   coefficient"). In pitch it is C₅₅ = −U² A₃₃(0) (a destabilising, Munk-like moment;
   A₃₃(0) of the model). c a⁻¹ b = K⁰(0) vanishes for fitted models (zero DC), so the 1/s² term is
   zero to rounding; its size is recorded in ``attrs`` and it is not modelled.

The causality problem Hjulstad finds (§5.3–5.4: STF terms in 1/ω² cannot form a
Kramers–Kronig pair) is reported, not hidden, by :func:`stf_causality`, which runs
:func:`cummins.radiation.retardation.kramers_kronig_error` on the STF-corrected data. Forced-motion
verification (§12.1, eqs. 12.1–12.3) is :func:`forced_motion_error`.

Encounter frequency (:func:`encounter_frequency`): heading β is the direction in which
the waves travel, relative to the ship's x axis (cummins' ``wave_direction``): β = 0
following seas, β = π (180°) head seas. A wave ζ = a cos(ωt − k(x cos β + y sin β)) seen
from x = U t has ω_e = ω − k U cos β = ω − ω² U cos β / g (deep water, k = ω²/g).
"""

from __future__ import annotations

import bisect
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import scipy.linalg
import scipy.signal
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError, FitError, SimulationError
from cummins.hydrodb import add_history, dof_matrix, single_speed, split_dof
from cummins.radiation.model import CouplingModel, RadiationModel

__all__ = [
    "ForcedMotionResult",
    "SpeedDependentModel",
    "SpeedModels",
    "encounter_frequency",
    "encounter_spectrum",
    "fit_per_speed",
    "forced_motion_error",
    "speed_coupling_matrix",
    "speed_dependent_model",
    "stf_causality",
    "stf_speed_terms",
    "vessel_at_speed",
    "wave_frequency",
]

G = 9.81


class SpeedError(CumminsError, ValueError):
    """A forward-speed computation cannot be done as asked (speed out of range, a
    singular encounter-frequency mapping, data without the DOFs the speed terms need)."""


# --------------------------------------------------------------------------- encounter frequency


#: Fit options the speed-dependent fits start from: the motion weighting that
#: :func:`cummins.radiation.fit.fit_radiation` uses by default weights the error by the zero-speed
#: equation of motion, which is not the one at speed; the memory parts are fitted by R²
#: over the frequencies below the first suspect one, as before motion weighting. Fit a K⁰
#: for :func:`speed_dependent_model` with the same options. The speed terms K¹, K² are
#: derived coupling by coupling (``method="fd"``: one SISO model per coupling), not from
#: the common-pole blocks of the zero-speed default.
SPEED_FIT_DEFAULTS: dict[str, Any] = {
    "method": "fd",
    "weighting": "uniform",
    "exclude_suspect": "above_first",
}


def encounter_frequency(
    omega: ArrayLike, speed: float, heading: float, g: float = G
) -> NDArray[np.float64]:
    """Encounter frequency ω_e = ω − ω² U cos β / g (deep water), rad/s.

    Parameters
    ----------
    omega
        Wave frequencies ω, rad/s.
    speed
        Forward speed U, m/s (along the ship's x axis).
    heading
        Direction β in which the waves *travel*, relative to x, rad: 0 following seas,
        π/2 beam seas (travelling to +y), π head seas (cummins' ``wave_direction``).
    g
        Acceleration of gravity, m/s².

    Returns
    -------
    numpy.ndarray
        ω_e, rad/s, signed: negative when the waves overtake the ship faster than their
        phase passes it (following seas, ω > g/(U cos β)).

    Notes
    -----
    Head seas (cos β < 0): ω_e > ω, monotonic. Following seas (cos β > 0): ω_e(ω) has
    a maximum ω_e = g/(4 U cos β) at ω = g/(2 U cos β), i.e. at τ = ω_e U cos β / g = 1/4
    (equivalently ω U cos β / g = 1/2); there dω_e/dω = 0, a response spectrum mapped
    to ω_e is singular, and each ω_e below the maximum comes from up to three wave
    frequencies (:func:`wave_frequency`).

    Examples
    --------
    >>> import numpy as np
    >>> float(encounter_frequency(0.5, 10.0, np.pi, g=9.81).round(4))  # head seas
    0.7548
    >>> float(encounter_frequency(0.4905, 10.0, 0.0, g=9.81).round(5))  # tau = 1/4
    0.24525
    """
    w = np.asarray(omega, dtype=float)
    return w - w**2 * speed * np.cos(heading) / g


def wave_frequency(
    omega_e: float, speed: float, heading: float, g: float = G
) -> NDArray[np.float64]:
    """All wave frequencies ω ≥ 0 with encounter frequency ``omega_e`` (inverse mapping).

    Solves (U cos β / g) ω² − ω + ω_e = 0 (see :func:`encounter_frequency`).

    Returns
    -------
    numpy.ndarray
        Sorted ω ≥ 0, rad/s. Head and beam seas: one value. Following seas
        (cos β > 0): two for 0 < ω_e < g/(4 U cos β) (τ = ω_e U cos β / g < 1/4), the
        double root g/(2 U cos β) at τ = 1/4, none above it (empty array); one for
        ω_e ≤ 0 (waves overtaking the ship).

    Raises
    ------
    SpeedError
        For a negative ω_e where no wave frequency produces it.

    Examples
    --------
    >>> wave_frequency(0.2, 10.0, 0.0, g=9.81).round(4)
    array([0.2798, 0.7012])
    >>> wave_frequency(0.7548, 10.0, 3.141592653589793, g=9.81).round(3)
    array([0.5])
    """
    c = speed * np.cos(heading) / g
    if abs(c) < 1e-12:
        roots = np.array([omega_e], dtype=float)
    else:
        disc = 1.0 - 4.0 * c * omega_e
        if disc < 0:
            return np.empty(0)
        r = np.sqrt(disc)
        roots = np.unique(np.array([(1.0 - r) / (2.0 * c), (1.0 + r) / (2.0 * c)]))
    out = np.sort(roots[roots >= 0])
    if out.size == 0:
        raise SpeedError(
            f"no wave frequency has the encounter frequency {omega_e:g} rad/s at "
            f"U = {speed:g} m/s, heading {np.degrees(heading):g} deg"
        )
    return out


def encounter_spectrum(
    omega: ArrayLike,
    spectrum: ArrayLike,
    speed: float,
    heading: float,
    g: float = G,
    *,
    margin: float = 0.02,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Map a wave spectrum S(ω) to encounter frequency: S_e(ω_e) = S(ω) / |dω_e/dω|.

    Energy-preserving per frequency band (S_e dω_e = S dω), with
    dω_e/dω = 1 − 2 ω U cos β / g.

    Parameters
    ----------
    omega, spectrum
        Wave frequencies (rad/s) and spectral density (m²·s/rad, or any unit per rad/s).
    speed, heading, g
        As :func:`encounter_frequency`.
    margin
        Refuse frequencies with |dω_e/dω| < ``margin`` (the τ = 1/4 singularity).

    Returns
    -------
    (omega_e, spectrum_e)
        Encounter frequencies (rad/s, in the order of ``omega``: not monotonic in
        following seas) and the mapped density.

    Raises
    ------
    SpeedError
        When a frequency lies within ``margin`` of τ = 1/4, naming it.
    """
    w = np.asarray(omega, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    jac = 1.0 - 2.0 * w * speed * np.cos(heading) / g
    bad = np.abs(jac) < margin
    if np.any(bad):
        w_bad = float(w[np.argmax(bad)])
        raise SpeedError(
            f"the encounter-frequency mapping is singular near omega = {w_bad:g} rad/s "
            f"(tau = omega_e U cos(beta)/g = 1/4 at omega = {g / (2 * speed * np.cos(heading)):g}"
            f" rad/s for U = {speed:g} m/s, heading {np.degrees(heading):g} deg)",
            hint="integrate responses over wave frequency instead, or leave out that band",
        )
    return encounter_frequency(w, speed, heading, g), s / np.abs(jac)


# --------------------------------------------------------------------------- per-speed fits


def _blend(models: Sequence[tuple[float, RadiationModel]]) -> RadiationModel:
    """Σ w_k K_k as one state-space model: the couplings' blocks stacked, outputs scaled."""
    first = models[0][1]
    n = len(first.dofs)
    parts: dict[tuple[int, int], list[tuple[float, CouplingModel]]] = {}
    for weight, model in models:
        if model.dofs != first.dofs:
            raise SpeedError("models at different speeds have different DOFs")
        for k in model.couplings:
            parts.setdefault((k.influenced, k.radiating), []).append((weight, k))
    couplings = []
    for (i, j), items in sorted(parts.items()):
        a = scipy.linalg.block_diag(*[k.a for _, k in items])
        b = np.concatenate([k.b for _, k in items])
        c = np.concatenate([w * k.c for w, k in items])
        couplings.append(CouplingModel(i, j, a, b, c, "speed-blend"))
    a_inf = sum(w * m.added_mass_inf for w, m in models)
    return RadiationModel(first.dofs, tuple(couplings), np.asarray(a_inf).reshape(n, n))


@dataclass(frozen=True)
class SpeedModels:
    """Radiation models fitted at several forward speeds, blended between them.

    Attributes
    ----------
    speeds
        Fitted forward speeds, m/s, increasing.
    models
        One :class:`~cummins.radiation.model.RadiationModel` per speed.

    Notes
    -----
    :meth:`at` between two fitted speeds U_a < U < U_b returns the linear blend
    K_U(s) = (1 − λ) K_a(s) + λ K_b(s), λ = (U − U_a)/(U_b − U_a), and A∞ likewise,
    realised as one state-space model (both models' states, outputs scaled by 1 − λ and
    λ). So the frequency responses *and* the time-domain memory forces are interpolated
    linearly in U; the poles are those of the two fitted models, hence stable. A
    simulation with a varying speed can run every fitted model on the same velocity and
    blend their outputs with the weights of the current speed (at most two non-zero);
    this stays stable for any U(t), since the weights act on outputs only. Outside the
    fitted range: :class:`SpeedError`.

    When the speed terms that are not memory were taken out before fitting
    (``damping_inf`` D¹ and ``restoring`` G¹, G², :func:`fit_per_speed`), the radiation
    force at speed U is the models' memory plus U D¹ ν + (U G¹ + U² G²) η
    (:meth:`impedance`), as in :class:`SpeedDependentModel`.
    """

    speeds: tuple[float, ...]
    models: tuple[RadiationModel, ...]
    attrs: Mapping[str, Any] = field(default_factory=dict)
    damping_inf: NDArray[np.float64] | None = None
    restoring: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        if len(self.speeds) != len(self.models) or not self.speeds:
            raise SpeedError("SpeedModels needs one model per speed, at least one")
        if any(b <= a for a, b in zip(self.speeds, self.speeds[1:], strict=False)):
            raise SpeedError(f"speeds must increase: {self.speeds}")

    def _weights(self, speed: float) -> list[tuple[float, int]]:
        u = float(speed)
        lo, hi = self.speeds[0], self.speeds[-1]
        if not lo - 1e-9 <= u <= hi + 1e-9:
            raise SpeedError(
                f"speed {u:g} m/s is outside the fitted speeds {lo:g} … {hi:g} m/s",
                hint="extrapolation in speed is not supported; fit data at that speed",
            )
        for k, s in enumerate(self.speeds):
            if abs(u - s) <= 1e-9 * max(1.0, abs(s)):
                return [(1.0, k)]
        k = bisect.bisect_right(self.speeds, u)
        ua, ub = self.speeds[k - 1], self.speeds[k]
        lam = (u - ua) / (ub - ua)
        return [(1.0 - lam, k - 1), (lam, k)]

    def at(self, speed: float) -> RadiationModel:
        """The model at ``speed`` (m/s): the fitted model itself at a fitted speed
        (the same object), else the linear blend of its two neighbours (class notes)."""
        weights = self._weights(speed)
        if len(weights) == 1:
            return self.models[weights[0][1]]
        return _blend([(w, self.models[k]) for w, k in weights])

    def response(self, omega: ArrayLike, speed: float) -> NDArray[np.complex128]:
        """K_U(jω) (len(omega), n, n) at ``speed``, linear in U between fitted speeds."""
        weights = self._weights(speed)
        return sum(w * self.models[k].response(omega) for w, k in weights)

    def impedance(self, omega: ArrayLike, speed: float) -> NDArray[np.complex128]:
        """Z_U(jω) = jω A∞ + K_U(jω) + U D¹ + (U G¹ + U² G²)/(jω): the radiation force
        per unit body velocity, to compare with B_U(ω) + jω A_U(ω) of the data."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        weights = self._weights(speed)
        a_inf = sum(wk * np.asarray(self.models[k].added_mass_inf) for wk, k in weights)
        z = 1j * w[:, None, None] * a_inf + self.response(w, speed)
        if self.damping_inf is not None:
            u = float(speed)
            z = z + u * self.damping_inf
            z = z + (u * self.restoring[0] + u**2 * self.restoring[1]) / (1j * w[:, None, None])
        return z

    def is_stable(self) -> bool:
        """True when every fitted model is stable (then so is every blend)."""
        return all(m.is_stable() for m in self.models)


def with_encounter_frequency(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with the coordinate ``encounter_frequency`` (forward_speed, omega,
    wave_direction), rad/s: the frequency at which the vessel meets each wave component
    of the data's wave-frequency tables (excitation, RAOs), ω_e = ω − ω²U cos β/g
    (:func:`encounter_frequency`); one speed: (omega, wave_direction)."""
    g = float(ds.attrs.get("g", G))
    w = ds.omega.values[:, None]
    beta = ds.wave_direction.values[None, :]
    if "forward_speed" in ds.dims:
        u = ds.forward_speed.values
        we = np.stack([encounter_frequency(w, float(uk), beta, g) for uk in u])
        dims = ("forward_speed", "omega", "wave_direction")
    else:
        u = float(ds.coords["forward_speed"]) if "forward_speed" in ds.coords else 0.0
        we = encounter_frequency(w, u, beta, g)
        dims = ("omega", "wave_direction")
    return ds.assign_coords(
        encounter_frequency=(
            dims,
            np.asarray(we),
            {"units": "rad/s", "long_name": "encounter frequency"},
        )
    )


def memory_part(
    ds: xr.Dataset, speed: float, damping_inf: ArrayLike, restoring: ArrayLike
) -> xr.Dataset:
    """The data at ``speed`` less the speed terms that are not memory: B − U D¹ and
    A + (U G¹ + U² G²)/ω² (the U·α∞ damping and the radiation-restoring 1/s parts of
    Hjulstad (2004) §6, §10.2, as :func:`speed_dependent_model` separates them). What is
    left is the causal memory the per-speed fit can identify: without this, the U²B₃₃/ω² term
    of pitch (STF) is not the damping of a causal system (Hjulstad (2004) eqs. 5.47–5.51)."""
    d1 = np.asarray(damping_inf, dtype=float)
    g = np.asarray(restoring, dtype=float)
    w = ds.omega.values
    out = ds.copy()
    out["radiation_damping"] = ds.radiation_damping - speed * d1
    out["added_mass"] = ds.added_mass + (speed * g[0] + speed**2 * g[1]) / w[:, None, None] ** 2
    out.attrs["history"] = (
        str(ds.attrs.get("history", ""))
        + f"\nspeed terms U D1, (U G1 + U^2 G2)/s removed at {speed:g} m/s"
    ).strip()
    return out


def fit_per_speed(
    ds: xr.Dataset,
    *,
    dofs: Sequence[str] | None = None,
    speed_terms: str = "remove",
    **fit_options: Any,
) -> SpeedModels:
    """Fit one radiation model per forward speed of a multi-speed database.

    Parameters
    ----------
    ds
        A ``HydroDB`` with a ``forward_speed`` dimension (or a single speed).
    dofs
        Keep only these DOFs (e.g. ``["Heave", "Pitch"]``), default all.
    speed_terms
        ``"remove"`` (default): fit the memory part (:func:`memory_part`) at each speed,
        with D¹ and G¹, G² from the zero-speed data (which ``ds`` must hold), and keep
        them in the result (:meth:`SpeedModels.impedance` adds them back); ``"keep"``:
        fit the data as they are (pitch at speed then misses: the STF terms are not
        causal, and :func:`stf_causality` says so).
    **fit_options
        Passed to :func:`cummins.radiation.fit.fit_radiation`.

    Returns
    -------
    SpeedModels

    Notes
    -----
    :func:`cummins.radiation.fit.fit_radiation` fits a coupling pair (i, j), (j, i) once, to the
    symmetric part of the data. At forward speed the data are *not* symmetric (STF:
    B₃₅ − B₅₃ = 2 U A⁰₃₃), so the antisymmetric speed part of the couplings is lost by
    these per-speed fits; :func:`speed_dependent_model` keeps it.

    Raises
    ------
    FitError
        Naming the speed whose fit failed.
    """
    from cummins.hydrodb import select_dofs
    from cummins.radiation.fit import fit_radiation

    if dofs is not None:
        ds = select_dofs(ds, dofs)
    if "forward_speed" in ds.dims:
        per_speed = [ds.isel(forward_speed=k) for k in range(ds.sizes["forward_speed"])]
    else:
        per_speed = [ds]
    if speed_terms not in ("remove", "keep"):
        raise SpeedError(f"speed_terms must be 'remove' or 'keep', not {speed_terms!r}")
    d1 = g = None
    if speed_terms == "remove":
        zero = [d for d in per_speed if float(d.coords.get("forward_speed", 0.0)) == 0.0]
        if not zero:
            raise SpeedError(
                "the data have no zero speed, whose A∞ and A(0) give the speed terms",
                hint="pass speed_terms='keep' to fit the data as they are",
            )
        base = speed_dependent_model(zero[0], **{**SPEED_FIT_DEFAULTS, **fit_options})
        d1, g = base.damping_inf, base.restoring
    speeds, models = [], []
    # fit_radiation fits the symmetric part of a pair; the antisymmetric part at speed is
    # U K¹ exactly (STF: ±(U/s) Z⁰, less U D¹), taken from the zero-speed model
    for d in per_speed:
        u = float(d.forward_speed) if "forward_speed" in d.coords else 0.0
        if d1 is None:
            try:
                model = fit_radiation(d, **{**SPEED_FIT_DEFAULTS, **fit_options})
            except CumminsError as exc:
                raise FitError(f"forward speed {u:g} m/s: {exc}") from exc
        else:
            model = _memory_model_at(d, u, base, fit_options)
        speeds.append(u)
        models.append(model)
    order = np.argsort(speeds)
    return SpeedModels(
        tuple(float(speeds[k]) for k in order),
        tuple(models[k] for k in order),
        {
            "source_file": str(ds.attrs.get("source_file", "")),
            "fit_options": dict(fit_options),
            "speed_terms": speed_terms,
        },
        d1,
        g,
    )


def _memory_model_at(
    d: xr.Dataset, speed: float, base: SpeedDependentModel, fit_options: Mapping[str, Any]
) -> RadiationModel:
    """The memory model at ``speed`` of the one-speed data ``d``: the fit of
    :func:`memory_part` plus U K¹ (``base.k0`` itself at U = 0)."""
    from cummins.radiation.fit import fit_radiation

    if speed == 0.0:
        return base.k0  # the zero-speed fit the speed terms came from
    try:
        model = fit_radiation(
            memory_part(d, speed, base.damping_inf, base.restoring),
            **{**SPEED_FIT_DEFAULTS, **fit_options},
        )
    except CumminsError as exc:
        raise FitError(f"forward speed {speed:g} m/s: {exc}") from exc
    return _with_speed_kernel(model, base.k1, speed)


#: Damping ratio of the soft springs of :func:`vessel_at_speed`.
SPRING_DAMPING_RATIO = 0.7


def vessel_at_speed(
    ds: xr.Dataset,
    speed: float,
    *,
    dofs: Sequence[str] | None = None,
    soft_springs: float | None = None,
    viscous_damping: Any = None,
    additional: bool = True,
    **fit_options: Any,
):
    """The time-domain :class:`~cummins.vessel.Vessel` of a ship at forward speed U.

    The radiation force at constant speed, Hjulstad (2004) eq. 3.28 with the speed terms
    that are not memory kept apart (§6, §10.2; :class:`SpeedDependentModel`)::

        A∞ ν̇ + K_U * ν + U D¹ ν + (U G¹ + U² G²) η

    where K_U is fitted to the data at U less U D¹ and the 1/s terms
    (:func:`memory_part`), plus the antisymmetric U K¹ (the per-speed fit is of the
    symmetric part). In the vessel: ``radiation`` = K_U with A∞, ``viscous_damping`` +=
    U D¹ (skew: B₃₅ = +U A∞₃₃, B₅₃ = −U A∞₃₃ …, no energy), ``stiffness`` += U G¹ + U² G²
    (pitch: −U² A₃₃(0), the destabilising Munk-like moment; yaw likewise). With
    :func:`cummins.timedomain.simulate.simulate_waves` (encounter frequencies) it reproduces the
    ShipX/VERES RAOs of the S-175 at 10.3 m/s within 1.5 % (heave) and 4.5 % (pitch) of
    their peaks where |ω_e| ≤ 2 rad/s (tests/test_speed.py).

    Parameters
    ----------
    ds
        A ``HydroDB`` with a ``forward_speed`` dimension that holds U = 0 (whose A∞ and
        A(0) give D¹, G¹, G²) and ``speed``.
    speed
        U, m/s: one of the data's speeds (within 1 mm/s).
    dofs
        Keep only these DOFs, e.g. ``["Heave", "Pitch"]`` (the vertical plane of a ship
        in head or following seas).
    soft_springs
        Natural period T, s, of weak springs in surge, sway and yaw: their diagonal
        stiffness becomes max(C_ii, 0) + (M_RB + A∞)_ii (2π/T)², i.e. a negative one
        (the yaw Munk moment U² G²₆₆ < 0) is cancelled first — what an autopilot and the
        hull's lift do for a real ship on course; a soft mooring at zero speed. Without
        them a free ship at speed is directionally unstable in potential flow and the
        vessel is refused. Each spring comes with the damping 2ζ(M_RB + A∞)_ii 2π/T,
        ζ = :data:`SPRING_DAMPING_RATIO` (a PD autopilot; without it the sway–yaw
        coupling at speed, U D¹ and U K¹, drives a slow oscillation). Choose T well above
        the wave periods (e.g. 200 s).
    viscous_damping, additional
        As :func:`cummins.vessel.vessel_from_hydrodb`.
    **fit_options
        Passed to :func:`cummins.radiation.fit.fit_radiation` for the zero-speed and the at-speed
        memory fits. For the pitch of the S-175 at speed the defaults stop at R² 0.5–0.8;
        ``omega_max=2.0, r2=0.999, max_order=6`` (the range of interest, tighter targets)
        give R² ≥ 0.999 in the vertical plane. A fit that cannot be made passive makes the
        vessel unstable, and it is refused (below).

    Raises
    ------
    SpeedError
        No zero speed or no ``speed`` in the data.
    SimulationError
        The vessel at speed is unstable (naming the DOF; use ``soft_springs`` or
        ``dofs``).
    """
    from cummins.hydrodb import select_dofs
    from cummins.vessel import vessel_from_hydrodb

    options = {**SPEED_FIT_DEFAULTS, **fit_options}
    if dofs is not None:
        ds = select_dofs(ds, dofs)
    speeds = ds.forward_speed.values if "forward_speed" in ds.dims else np.array([])
    listed = ", ".join(f"{u:g}" for u in speeds) or "none"
    zero = [k for k, u in enumerate(speeds) if abs(u) <= 1e-3]
    at = [k for k, u in enumerate(speeds) if abs(u - speed) <= 1e-3]
    if not zero:
        raise SpeedError(
            f"the data hold no zero speed (speeds: {listed} m/s), whose A∞ and A(0) give the "
            "speed terms",
            hint="or build the vessel from the data at that speed as they are: "
            "vessel_from_hydrodb(ds.sel(forward_speed=U)) (pitch at speed is then "
            "misfitted: stf_causality says why)",
        )
    if not at:
        raise SpeedError(f"no data at {speed:g} m/s; the data hold {listed} m/s")
    data = ds.isel(forward_speed=at[0])
    u = float(data.forward_speed)
    base = speed_dependent_model(ds.isel(forward_speed=zero[0]), **options)
    model = _memory_model_at(data, u, base, options)
    vessel = vessel_from_hydrodb(
        data, model, viscous_damping=viscous_damping, additional=additional
    )
    stiffness = vessel.stiffness + u * base.restoring[0] + u**2 * base.restoring[1]
    labels = list(vessel.dofs)
    damping = vessel.viscous_damping + u * base.damping_inf
    springs = []
    if soft_springs is not None:
        if not soft_springs > 0:
            raise SpeedError(f"soft_springs must be a period in s > 0, not {soft_springs}")
        mass, omega_s = vessel.mass, 2 * np.pi / soft_springs
        for k, label in enumerate(labels):
            if split_dof(label)[1] in ("Surge", "Sway", "Yaw"):
                stiffness[k, k] = max(stiffness[k, k], 0.0) + mass[k, k] * omega_s**2
                damping[k, k] += 2 * SPRING_DAMPING_RATIO * mass[k, k] * omega_s
                springs.append(label)
    attrs = {
        **dict(vessel.attrs),
        "forward_speed": u,
        "speed_terms": "U D1 in viscous_damping, U G1 + U^2 G2 in stiffness, U K1 in radiation",
        "soft_springs": f"{soft_springs:g} s on {', '.join(springs)}" if springs else "none",
    }
    out = replace(
        vessel,
        viscous_damping=damping,
        stiffness=stiffness,
        attrs=attrs,
    )
    try:
        out.stability()
    except SimulationError as exc:
        message = str(exc)[: -len(exc.hint) - 2] if exc.hint else str(exc)
        raise SimulationError(
            f"at {u:g} m/s: {message}",
            hint="a free ship at speed is directionally unstable in potential flow (yaw Munk "
            "moment): pass soft_springs (a period, e.g. 200 s; CLI --soft-springs) or keep "
            "the vertical plane (dofs=['Heave', 'Pitch']; CLI --dof Heave --dof Pitch)",
        ) from None
    return out


def _with_speed_kernel(model: RadiationModel, k1: RadiationModel, speed: float) -> RadiationModel:
    """``model`` plus U K¹ (the antisymmetric speed kernel), coupling by coupling: the
    blocks of a coupling are stacked, the fitted coupling keeps its metrics."""
    parts = {(k.influenced, k.radiating): k for k in model.couplings}
    for k in k1.couplings:
        key = (k.influenced, k.radiating)
        extra = CouplingModel(*key, k.a, k.b, speed * k.c, "STF speed kernel U K1")
        base = parts.get(key)
        if base is None:
            parts[key] = extra
            continue
        parts[key] = CouplingModel(
            *key,
            scipy.linalg.block_diag(base.a, extra.a),
            np.concatenate([base.b, extra.b]),
            np.concatenate([base.c, extra.c]),
            base.method,
            base.metrics,
            (base.note + "; " if base.note else "") + "plus U K1 (STF, antisymmetric)",
        )
    couplings = tuple(parts[key] for key in sorted(parts))
    return RadiationModel(model.dofs, couplings, model.added_mass_inf, model.attrs)


# --------------------------------------------------------------------------- STF speed terms


def speed_coupling_matrix(labels: Sequence[str]) -> NDArray[np.float64]:
    """E = e_heave e_pitchᵀ − e_sway e_yawᵀ over ``labels`` (module docstring).

    Entries whose two DOFs are not both present are left out.

    Raises
    ------
    SpeedError
        For several bodies (the STF terms are for one ship).
    """
    names = [split_dof(str(label)) for label in labels]
    if len({body for body, _ in names}) > 1:
        raise SpeedError("STF speed terms are defined for one body; select one body's DOFs")
    index = {name: k for k, (_, name) in enumerate(names)}
    e = np.zeros((len(labels), len(labels)))
    if "Heave" in index and "Pitch" in index:
        e[index["Heave"], index["Pitch"]] = 1.0
    if "Sway" in index and "Yaw" in index:
        e[index["Sway"], index["Yaw"]] = -1.0
    return e


def _speed_impedance(z0: NDArray, omega: NDArray, e: NDArray, speed: float) -> NDArray:
    s = 1j * omega[:, None, None]
    first = z0 @ e - e.T @ z0
    second = e.T @ z0 @ e
    return z0 + speed / s * first - speed**2 / s**2 * second


def stf_speed_terms(ds: xr.Dataset, speed: float) -> xr.Dataset:
    """Zero-speed A(ω), B(ω) with the Salvesen–Tuck–Faltinsen speed terms at ``speed``.

    Hjulstad (2004) eqs. 3.29, 3.33, 5.45–5.46, 10.1 and §6 (aft-section terms omitted),
    in the matrix form of the module docstring. Only ``added_mass`` and
    ``radiation_damping`` change; ``added_mass_inf`` (if present) stays (the STF terms
    vanish in A as ω → ∞); B(∞) becomes U·α∞ in the couplings
    (:attr:`SpeedDependentModel.damping_inf`).

    Parameters
    ----------
    ds
        A ``HydroDB`` at zero speed (one speed; a ``forward_speed`` other than 0 is an
        error: the terms would be applied twice).
    speed
        Forward speed U, m/s.

    Returns
    -------
    xarray.Dataset
        A copy with the corrected coefficients and a scalar ``forward_speed``.

    Examples
    --------
    >>> import cummins, numpy as np
    >>> ds = cummins.demo_dataset()
    >>> fast = stf_speed_terms(ds, 5.0)
    >>> w = ds.omega.values
    >>> a33 = ds.added_mass.sel(influenced_dof="Heave", radiating_dof="Heave").values
    >>> b35 = fast.radiation_damping.sel(influenced_dof="Heave", radiating_dof="Pitch")
    >>> b35_0 = ds.radiation_damping.sel(influenced_dof="Heave", radiating_dof="Pitch")
    >>> bool(np.allclose(b35 - b35_0, 5.0 * a33))
    True
    """
    ds = _zero_speed(ds)
    labels = [str(d) for d in ds.influenced_dof.values]
    w = ds.omega.values
    if np.any(w <= 0):
        raise SpeedError("the STF speed terms need omega > 0 (they scale with 1/omega^2)")
    z0 = dof_matrix(ds, "radiation_damping") + 1j * w[:, None, None] * dof_matrix(ds, "added_mass")
    z = _speed_impedance(z0, w, speed_coupling_matrix(labels), float(speed))
    out = ds.copy()
    dims = ("omega", "influenced_dof", "radiating_dof")
    if speed == 0:  # exactly the input (no round trip through Z = B + jωA)
        return out.assign_coords(forward_speed=0.0)
    out["added_mass"] = (dims, z.imag / w[:, None, None], ds.added_mass.attrs)
    out["radiation_damping"] = (dims, z.real, ds.radiation_damping.attrs)
    out = out.assign_coords(forward_speed=float(speed))
    out.forward_speed.attrs["units"] = "m/s"
    add_history(
        out, f"STF speed terms (Hjulstad (2004) eqs. 3.29, 3.33) applied for U = {speed:g} m/s"
    )
    return out


def _zero_speed(ds: xr.Dataset) -> xr.Dataset:
    if "forward_speed" in ds.dims:
        if 0.0 not in ds.forward_speed.values:
            raise SpeedError("the dataset has no zero-speed data for the STF speed terms")
        ds = ds.sel(forward_speed=0.0)
    if "forward_speed" in ds.coords and float(ds.forward_speed) != 0.0:
        raise SpeedError(
            f"the dataset is at {float(ds.forward_speed):g} m/s: STF speed terms apply to "
            "zero-speed data",
            hint="select forward_speed=0",
        )
    return single_speed(ds)


# --------------------------------------------------------------------------- K0, K1, K2


@dataclass(frozen=True)
class SpeedDependentModel:
    """Radiation model K_U = K⁰ + U K¹ + U² K² plus the non-memory speed terms.

    Force on the body (N, N·m) for body velocity ν (m/s, rad/s) and displacement η::

        τ = −A∞ ν̇ − (K⁰ + U K¹ + U² K²) * ν − U D¹ ν − (U G¹ + U² G²) η

    (``*`` convolution; Hjulstad (2004) eq. 3.28, with b = U·α∞ of §6/App. C.3).

    For a speed U(t) varying in a simulation, the states of K⁰, K¹, K² are driven by ν
    alone and U, U² scale their *outputs*, so the memory stays stable for any U(t).
    Hjulstad scales the inputs instead (§10.5, "rather arbitrary"); the two agree at
    constant speed only (a speed that varies in time, or a turn, breaks the steady-speed
    assumption of eq. 3.28, so neither choice is exact then).

    Attributes
    ----------
    k0
        The zero-speed model (the one given or fitted, unchanged).
    k1, k2
        Models of the linear and quadratic speed kernels (units of K⁰ per m/s, per m²/s²),
        same poles as the K⁰ couplings they come from.
    damping_inf
        D¹ (n, n): infinite-frequency damping per unit speed, B_U(∞) = U D¹ (kg/m, …):
        the U·α∞ terms, e.g. D¹₃₅ = +A∞₃₃, D¹₅₃ = −A∞₃₃.
    restoring
        G¹, G² (2, n, n): radiation restoring stiffness per U and per U² (the 1/s parts,
        module docstring), e.g. G²₅₅ = −A₃₃(0) of the model.
    attrs
        Provenance, and ``dropped_double_integrator``: max |c a⁻¹ b| of the K⁰ couplings
        used (should be ~0).
    """

    k0: RadiationModel
    k1: RadiationModel
    k2: RadiationModel
    damping_inf: NDArray[np.float64]
    restoring: NDArray[np.float64]
    attrs: Mapping[str, Any] = field(default_factory=dict)

    @property
    def dofs(self) -> tuple[str, ...]:
        """DOF labels."""
        return self.k0.dofs

    def response(self, omega: ArrayLike, speed: float) -> NDArray[np.complex128]:
        """Memory kernel K_U(jω) = K⁰ + U K¹ + U² K² (len(omega), n, n); at U = 0 this is
        ``k0.response(omega)`` exactly (the same array operations)."""
        r0 = self.k0.response(omega)
        if speed == 0:
            return r0
        return r0 + speed * self.k1.response(omega) + speed**2 * self.k2.response(omega)

    def impedance(self, omega: ArrayLike, speed: float) -> NDArray[np.complex128]:
        """Total radiation impedance Z_U(ω) = B_U + jω A_U = jω A∞ + K_U(jω) + U D¹
        + (U G¹ + U² G²)/(jω) (len(omega), n, n), kg/s …; compare with the data's
        B + jω A (:func:`stf_speed_terms`)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        s = 1j * w[:, None, None]
        z = s * self.k0.added_mass_inf[None] + self.response(w, speed)
        if speed == 0:
            return z
        stiff = speed * self.restoring[0] + speed**2 * self.restoring[1]
        return z + speed * self.damping_inf[None] + stiff[None] / s

    def added_mass_damping(
        self, omega: ArrayLike, speed: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """A_U(ω), B_U(ω) of the model (the STF-corrected coefficients it represents)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        z = self.impedance(w, speed)
        return z.imag / w[:, None, None], z.real

    def memory_model(self, speed: float) -> RadiationModel:
        """K_U at a fixed speed as one :class:`RadiationModel` (K⁰ itself at U = 0)."""
        if speed == 0:
            return self.k0
        return _blend([(1.0, self.k0), (float(speed), self.k1), (float(speed) ** 2, self.k2)])

    def radiation_force(
        self, t: ArrayLike, velocity: ArrayLike, speed: ArrayLike, motion: ArrayLike | None = None
    ) -> NDArray[np.float64]:
        """The speed-dependent radiation force without the A∞ν̇ term, for a speed that
        varies in time: μ(t) = (K⁰ * ν) + U(t) (K¹ * ν) + U(t)² (K² * ν) + U(t) D¹ ν(t)
        + (U(t) G¹ + U(t)² G²) η(t), N and N·m, shape (len(t), n).

        Each of K⁰, K¹, K² runs as its own state-space model on the velocity (from rest,
        :func:`scipy.signal.lsim`); U(t) scales their outputs, so the memory is stable for
        any speed history (class notes). ``speed`` is a scalar or one value per time (m/s);
        ``motion`` η is needed for the restoring terms (default zero)."""
        t = np.asarray(t, dtype=float).reshape(-1)
        v = np.asarray(velocity, dtype=float).reshape(t.size, -1)
        u = np.broadcast_to(np.asarray(speed, dtype=float), t.shape)
        eta = np.zeros_like(v) if motion is None else np.asarray(motion, float).reshape(v.shape)
        out = np.zeros_like(v)
        for power, model in enumerate((self.k0, self.k1, self.k2)):
            if model.total_order == 0:
                continue
            _, y, _ = scipy.signal.lsim(model.to_scipy(), v, t - t[0])
            out += (u**power)[:, None] * np.asarray(y).reshape(v.shape)
        out += u[:, None] * (v @ self.damping_inf.T)
        out += (u[:, None] * (eta @ self.restoring[0].T)) + (u**2)[:, None] * (
            eta @ self.restoring[1].T
        )
        return out

    def is_stable(self) -> bool:
        """True when K⁰, K¹ and K² are stable (then K_U is, for any U(t))."""
        return self.k0.is_stable() and self.k1.is_stable() and self.k2.is_stable()


def _same(p: CouplingModel, q: CouplingModel) -> bool:
    return all(np.array_equal(x, y) for x, y in ((p.a, q.a), (p.b, q.b), (p.c, q.c)))


def _distinct_sources(model: RadiationModel, e: NDArray, power: int):
    """{(i, j): {source coupling: σ}} for the U^power term of the module docstring."""
    n = len(model.dofs)
    if power == 1:  # Z₀E − EᵀZ₀: (i, j) ← Σ_l Z_il E_lj − Σ_k E_ki Z_kj
        terms = [(i, l, i, j, e[l, j]) for i in range(n) for l in range(n) for j in range(n)]
        terms += [(k, j, i, j, -e[k, i]) for i in range(n) for k in range(n) for j in range(n)]
    else:  # −EᵀZ₀E: (i, j) ← −Σ E_ki Z_kl E_lj
        terms = [
            (k, l, i, j, -e[k, i] * e[l, j])
            for i in range(n)
            for j in range(n)
            for k in range(n)
            for l in range(n)
        ]
    out: dict[tuple[int, int], dict[int, tuple[CouplingModel, float]]] = {}
    for k, l, i, j, sigma in terms:
        if sigma == 0:
            continue
        source = model.coupling(k, l)
        if source is None:
            continue
        slot = out.setdefault((i, j), {})
        # symmetric pairs share their matrices: count them as one source
        key = next(
            (
                key
                for key, (m, _) in slot.items()
                if m.a is source.a
                or (np.array_equal(m.a, source.a) and np.array_equal(m.c, source.c))
            ),
            id(source),
        )
        m, total = slot.get(key, (source, 0.0))
        slot[key] = (m, total + sigma)
    return out


def speed_dependent_model(
    ds: xr.Dataset, model: RadiationModel | None = None, **fit_options: Any
) -> SpeedDependentModel:
    """K⁰, K¹, K² models of the forward-speed formulation of Hjulstad (2004) eqs. 3.28–3.36.

    Parameters
    ----------
    ds
        Zero-speed ``HydroDB`` (3-D panel data or the zero-speed strip-theory data).
    model
        The zero-speed model K⁰; fitted with :func:`cummins.radiation.fit.fit_radiation`
        (``**fit_options``) when not given.

    Returns
    -------
    SpeedDependentModel
        K¹, K² built exactly from the K⁰ couplings (module docstring): K¹₃₅ = K⁰₃₃/s
        (eq. 3.35: the cosine transform of α₃₃ − α∞₃₃ is the integral of K₃₃),
        K¹₅₃ = −K¹₃₅ (App. C.2), K²₅₅ from −K⁰₃₃/s² (eq. 3.32), D¹₃₅ = A∞₃₃ (eq. 3.35,
        the subtracted U α∞), K¹₅₅ = 0 (eq. 3.31), K²₃₅ = 0 (eq. 3.36), and the
        sway–yaw mirror terms.

    Raises
    ------
    FitError
        When a K⁰ coupling that a speed term needs has a singular state matrix.
    """
    ds = _zero_speed(ds)
    if model is None:
        from cummins.radiation.fit import fit_radiation

        model = fit_radiation(ds, **{**SPEED_FIT_DEFAULTS, **fit_options})
    if model.blocks:
        raise FitError(
            "the speed terms are built coupling by coupling, and this K⁰ holds common-pole blocks",
            hint="fit K⁰ with fit_radiation(ds, **SPEED_FIT_DEFAULTS) (method='fd'), or "
            "leave model out",
        )
    labels = list(model.dofs)
    n = len(labels)
    e = speed_coupling_matrix(labels)
    a_inf = model.added_mass_inf
    damping_inf = a_inf @ e - e.T @ a_inf
    restoring = np.zeros((2, n, n))
    restoring[1] = -(e.T @ a_inf @ e)
    dropped = 0.0
    built: list[RadiationModel] = []
    for power in (1, 2):
        couplings = []
        for (i, j), sources in sorted(_distinct_sources(model, e, power).items()):
            blocks = []
            for source, sigma in sources.values():
                if sigma == 0:
                    continue
                try:
                    inv = np.linalg.inv(source.a)
                except np.linalg.LinAlgError:
                    raise FitError(
                        f"coupling {labels[source.influenced]}-{labels[source.radiating]}: "
                        "singular state matrix, K/s has no state-space form"
                    ) from None
                c1 = source.c @ inv
                dc = float(c1 @ source.b)  # K(0) = −c a⁻¹ b
                if power == 1:
                    blocks.append((source.a, source.b, sigma * c1))
                    restoring[0, i, j] += -sigma * dc
                else:
                    c2 = c1 @ inv
                    blocks.append((source.a, source.b, sigma * c2))
                    restoring[1, i, j] += -sigma * float(c2 @ source.b)
                    dropped = max(dropped, abs(dc))
            if blocks:
                couplings.append(
                    CouplingModel(
                        i,
                        j,
                        scipy.linalg.block_diag(*[a for a, _, _ in blocks]),
                        np.concatenate([b for _, b, _ in blocks]),
                        np.concatenate([c for _, _, c in blocks]),
                        f"speed-K{power}",
                        note=f"K{power} from K0/s^{power} (Hjulstad (2004) eq. 3.28)",
                    )
                )
        built.append(RadiationModel(model.dofs, tuple(couplings), np.zeros((n, n))))
    return SpeedDependentModel(
        model,
        built[0],
        built[1],
        damping_inf,
        restoring,
        {"dropped_double_integrator": dropped, "source_file": model.attrs.get("source_file", "")},
    )


# --------------------------------------------------------------------------- causality


def stf_causality(
    ds: xr.Dataset, speed: float, *, threshold: float = 0.1, added_mass_inf: ArrayLike | None = None
) -> tuple[xr.DataArray, list[str]]:
    """Kramers–Kronig check of the STF-corrected data (Hjulstad (2004) §5.3–5.4, eq. 5.23).

    The corrected damping minus its infinite-frequency part U·D¹ (D¹ = A∞E − EᵀA∞)
    and the corrected added mass are tested with
    :func:`cummins.radiation.retardation.kramers_kronig_error`, with the zero-speed A∞ (the STF
    terms vanish in A as ω → ∞). Hjulstad shows that the U²/ω² terms (pitch, yaw) cannot
    form a causal pair (eqs. 5.47–5.51); the check says which couplings fail.

    Parameters
    ----------
    ds
        Zero-speed ``HydroDB``.
    speed
        U, m/s.
    threshold
        Relative KK error above which a coupling is reported as not causal.
    added_mass_inf
        A∞ (n, n); default the data's, else Ogilvie's estimate from the zero-speed data.

    Returns
    -------
    (errors, non_causal)
        The relative KK error per coupling (influenced_dof, radiating_dof) and the
        labels (``"Pitch"``, ``"Heave-Pitch"``) of the couplings above ``threshold``,
        only couplings whose speed terms are non-zero.
    """
    from cummins.radiation.retardation import added_mass_inf as estimate

    zero = _zero_speed(ds)
    a_inf = estimate(zero).values if added_mass_inf is None else np.asarray(added_mass_inf, float)
    labels = [str(d) for d in zero.influenced_dof.values]
    e = speed_coupling_matrix(labels)
    corrected = stf_speed_terms(zero, speed)
    d1 = a_inf @ e - e.T @ a_inf
    corrected["radiation_damping"] = corrected.radiation_damping - speed * xr.DataArray(
        d1, dims=("influenced_dof", "radiating_dof")
    )
    errors = _kk(corrected.drop_vars("forward_speed"), a_inf)
    z_speed = dof_matrix(corrected, "radiation_damping") - dof_matrix(zero, "radiation_damping")
    z_speed = np.abs(z_speed) + np.abs(
        dof_matrix(corrected, "added_mass") - dof_matrix(zero, "added_mass")
    )
    touched = np.any(z_speed > 0, axis=0)
    flagged = [
        labels[i] if i == j else f"{labels[i]}-{labels[j]}"
        for i in range(len(labels))
        for j in range(len(labels))
        if touched[i, j] and errors.values[i, j] > threshold
    ]
    errors.attrs["speed"] = float(speed)
    errors.attrs["threshold"] = threshold
    return errors, flagged


def _kk(ds: xr.Dataset, a_inf: NDArray) -> xr.DataArray:
    from cummins.radiation.retardation import kramers_kronig_error

    return kramers_kronig_error(ds, added_mass_inf=a_inf)


# --------------------------------------------------------------------------- forced motion


@dataclass(frozen=True)
class ForcedMotionResult:
    """Forced-motion verification of one coupling (Hjulstad (2004) §12.1).

    Attributes
    ----------
    omega
        Motion frequencies, rad/s.
    td_amplitude
        Steady force amplitude of the time-domain simulation per unit motion amplitude
        (N/m, N·m/rad …).
    fd_amplitude
        |T(ω)| = ω |B(ω) + jω A(ω)| of the data (eq. 12.1 with the missing i restored,
        cf. eq. 10.4).
    error
        (td − fd)/fd (eq. 12.3).
    """

    omega: NDArray[np.float64]
    td_amplitude: NDArray[np.float64]
    fd_amplitude: NDArray[np.float64]
    error: NDArray[np.float64]
    speed: float
    dof: tuple[str, str]


def _coupling_state_space(model: SpeedDependentModel, speed: float, i: int, j: int):
    parts = []
    for weight, part in ((1.0, model.k0), (speed, model.k1), (speed**2, model.k2)):
        k = part.coupling(i, j)
        if k is not None and weight != 0 and k.order:
            parts.append((k.a, k.b, weight * k.c))
    if not parts:
        return None
    a = scipy.linalg.block_diag(*[p[0] for p in parts])
    b = np.concatenate([p[1] for p in parts])[:, None]
    c = np.concatenate([p[2] for p in parts])[None, :]
    return a, b, c


def forced_motion_error(
    model: SpeedDependentModel,
    data: xr.Dataset,
    speed: float,
    omega: ArrayLike | None = None,
    dof: tuple[str, str] = ("Heave", "Heave"),
    *,
    periods: int = 12,
    steps_per_period: int = 80,
) -> ForcedMotionResult:
    """Force amplitude of a time-domain forced-motion run against |T(ω)| of the data.

    Hjulstad (2004) §12.1: the radiating DOF moves as q(t) = sin ωt (unit amplitude, m or
    rad); the force on the influenced DOF is (eq. 12.2, cummins' sign: the force the body
    exerts on the fluid) F = A∞ q̈ + U D¹ q̇ + (K⁰ + U K¹ + U² K²) * q̇ + (U G¹ + U² G²) q,
    the memory term simulated through the state-space models (:func:`scipy.signal.lsim`,
    linear interpolation of the input) from rest until the memory has settled (at least
    ``periods`` periods and 6 time constants of the slowest pole), then its maximum
    |F| over the last period is taken (as the thesis does) and compared with the
    frequency-domain amplitude of the data (eq. 12.3).

    Parameters
    ----------
    model
        The speed-dependent model.
    data
        The frequency-domain data at ``speed`` (e.g. :func:`stf_speed_terms` output, or a
        strip-theory dataset at that speed), one speed.
    speed
        U, m/s.
    omega
        Test frequencies, rad/s (default the data's).
    dof
        (influenced, radiating) DOF labels.

    Raises
    ------
    SpeedError
        Unknown DOF labels, or a frequency outside the data.
    """
    data = single_speed(data)
    labels = list(model.dofs)
    try:
        i, j = labels.index(dof[0]), labels.index(dof[1])
    except ValueError:
        raise SpeedError(f"DOF pair {dof} is not in the model ({', '.join(labels)})") from None
    w_data = data.omega.values
    w = w_data.copy() if omega is None else np.asarray(omega, dtype=float).reshape(-1)
    if np.any(w < w_data[0] - 1e-12) or np.any(w > w_data[-1] + 1e-12):
        raise SpeedError(
            f"test frequencies must lie within the data, {w_data[0]:g} … {w_data[-1]:g} rad/s"
        )
    a_d = data.added_mass.sel(influenced_dof=dof[0], radiating_dof=dof[1]).values
    b_d = data.radiation_damping.sel(influenced_dof=dof[0], radiating_dof=dof[1]).values
    fd = w * np.abs(np.interp(w, w_data, b_d) + 1j * w * np.interp(w, w_data, a_d))
    ss = _coupling_state_space(model, float(speed), i, j)
    slowest = 0.0
    if ss is not None:
        slowest = float(np.max(1.0 / np.abs(np.linalg.eigvals(ss[0]).real)))
    a_inf = model.k0.added_mass_inf[i, j]
    d = speed * model.damping_inf[i, j]
    g = speed * model.restoring[0, i, j] + speed**2 * model.restoring[1, i, j]
    td = np.empty_like(w)
    for n, wn in enumerate(w):
        period = 2 * np.pi / wn
        count = max(periods, int(np.ceil(6 * slowest / period)) + 1)
        t = np.linspace(0.0, count * period, count * steps_per_period + 1)
        qdot = wn * np.cos(wn * t)
        force = -a_inf * wn**2 * np.sin(wn * t) + d * qdot + g * np.sin(wn * t)
        if ss is not None:
            system = scipy.signal.StateSpace(ss[0], ss[1], ss[2], np.zeros((1, 1)))
            _, y, _ = scipy.signal.lsim(system, qdot, t, interp=True)
            force = force + y
        last = t >= t[-1] - period - 1e-12
        td[n] = np.max(np.abs(force[last]))
    with np.errstate(divide="ignore", invalid="ignore"):
        err = (td - fd) / fd
    return ForcedMotionResult(w, td, fd, err, float(speed), (str(dof[0]), str(dof[1])))
