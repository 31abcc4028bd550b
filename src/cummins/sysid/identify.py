"""Viscous damping from motion records: residual force and linear regression.

The Cummins equation of the potential-flow model (de Haan (2022) eq. 2.14), with the damping
the model lacks, D(ξ̇), moved to the right:

    D(ξ̇) = τ − [(M_RB + A∞) ξ̈ + μ + B_v ξ̇ + C ξ] ≡ F_res          (de Haan (2022) eq. 2.21)

— the thesis prints [C]ξ̇ where the restoring force is [C]ξ, and writes the memory term
∫K(t − s)ξ̇(s)ds, here the state-space memory μ = C_r χ, χ̇ = A_r χ + B_r ξ̇ (Smogeli et al. (2004)
eqs.
32–36) driven by the measured velocities. B_v is whatever linear damping the vessel model
already holds; the identified coefficients add to it. The damping of a DOF i is modelled
(de Haan (2022) eq. 2.22) as

    D_i = b₁ ξ̇_i + b₂ |ξ̇_i| ξ̇_i + b₃ ξ̇_i³  [+ Σ corrections of M, B, C entries + a mean force]

linear in its coefficients, so ordinary, weighted or bounded (b ≥ 0) least squares
identify it. The estimates come with the diagnostics de Haan lacked:

* **collinearity** — the condition number of the regressors scaled to unit length
  (Belsley, Kuh & Welsch 1980: above 30 the split between terms is ill determined) and
  the variance inflation factor VIF_k = 1/(1 − R²_k) of each term;
* **confidence intervals** from a covariance that allows for the residual's
  autocorrelation (Newey & West 1987, Bartlett weights): sampled records are strongly
  autocorrelated and the textbook σ²(XᵀX)⁻¹ would be far too confident;
* **flags**: a damping estimate below zero, a term whose interval is wider than its value
  (the data do not determine it), ill-conditioning.

Velocities and accelerations are differentiated from the measured motions in the
frequency domain below a cut-off (2.5 times the motions' zero-crossing frequency by
default), and the excitation force is low-passed by the same filter: the equation of
motion, linear in ξ, holds exactly between the filtered signals, so the filter adds no
bias to the linear terms while it removes the noise that differentiation amplifies
(:mod:`cummins.sysid.signals`, whose functions are importable from here as well).
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import scipy.optimize
import scipy.signal
import scipy.stats
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import IdentificationError
from cummins.hydrodb import DOF_NAMES, is_rotation
from cummins.sysid.records import time_step
from cummins.sysid.signals import default_cutoff as default_cutoff  # re-exported
from cummins.sysid.signals import filtered_derivatives, motion_derivatives
from cummins.sysid.signals import zero_crossing_period as zero_crossing_period  # re-exported
from cummins.vessel import Vessel

#: Kinds of regressors and their value from (ξ_j, ξ̇_j, ξ̈_j).
KINDS = ("linear", "quadratic", "cubic", "motion", "velocity", "acceleration", "offset")
#: Kinds that are damping (bounded ≥ 0 by ``method="bounded"``, flagged when negative).
DAMPING_KINDS = ("linear", "quadratic", "cubic")
#: Condition number of the unit-length regressors above which the estimate is flagged
#: ill-conditioned (Belsley, Kuh & Welsch 1980 call 30 "strong" collinearity).
CONDITION_LIMIT = 30.0
#: A term is "not determined" when its confidence half-width exceeds this fraction of |b|.
UNDETERMINED = 1.0
#: Spread of the velocity envelope (90th/10th percentile) below which a record is too
#: narrow-banded to separate amplitude-dependent damping (a Gaussian sea gives 4.7).
AMPLITUDE_SPREAD_LIMIT = 2.0


@dataclass(frozen=True)
class Regressor:
    """One term of the residual-force model of a DOF.

    ``kind`` ``linear`` ξ̇_j, ``quadratic`` |ξ̇_j|ξ̇_j, ``cubic`` ξ̇_j³ (damping of DOF j,
    normally j = the DOF itself), ``motion`` ξ_j, ``velocity`` ξ̇_j, ``acceleration``
    ξ̈_j (corrections to C, B, M entries, e.g. the sway acceleration in roll that de Haan
    identifies), ``offset`` a constant (a mean force: wind, current, a heel).
    """

    kind: str
    dof: str = ""

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise IdentificationError(f"unknown regressor kind {self.kind!r}; use {KINDS}")
        if self.kind != "offset" and self.dof not in DOF_NAMES:
            raise IdentificationError(f"unknown DOF {self.dof!r}; use {', '.join(DOF_NAMES)}")

    @property
    def name(self) -> str:
        v = f"{self.dof} velocity"
        return {
            "linear": v,
            "quadratic": f"|{v}| {v}",
            "cubic": f"{v}^3",
            "motion": f"{self.dof} motion",
            "velocity": f"{v} (coupling)",
            "acceleration": f"{self.dof} acceleration",
            "offset": "mean force",
        }[self.kind]

    def values(self, motion: NDArray, velocity: NDArray, acceleration: NDArray, dofs) -> NDArray:
        if self.kind == "offset":
            return np.ones(motion.shape[0])
        j = list(dofs).index(self.dof)
        v = velocity[:, j]
        return {
            "linear": lambda: v,
            "quadratic": lambda: np.abs(v) * v,
            "cubic": lambda: v**3,
            "motion": lambda: motion[:, j],
            "velocity": lambda: v,
            "acceleration": lambda: acceleration[:, j],
        }[self.kind]()

    def unit(self, target: str) -> str:
        """Unit of the coefficient in the equation of DOF ``target``."""
        force = "N m" if is_rotation(target) else "N"
        if self.kind == "offset":
            return force
        x = "rad" if is_rotation(self.dof) else "m"
        return {
            "linear": f"{force} s/{x}",
            "quadratic": f"{force} s^2/{x}^2",
            "cubic": f"{force} s^3/{x}^3",
            "motion": f"{force}/{x}",
            "velocity": f"{force} s/{x}",
            "acceleration": f"{force} s^2/{x}",
        }[self.kind]


def damping_terms(
    dof: str, terms: Sequence[str] = ("linear", "quadratic"), *, offset: bool = False
) -> tuple[Regressor, ...]:
    """The damping regressors of ``dof`` (``linear``, ``quadratic``, ``cubic``), and a
    mean force when ``offset``."""
    out = tuple(Regressor(kind, dof) for kind in terms)
    return (*out, Regressor("offset")) if offset else out


def parse_regressor(text: str) -> Regressor:
    """``"Sway acceleration"``, ``"Roll motion"``, ``"Pitch velocity"``, ``"Roll
    quadratic"``, ``"offset"`` → :class:`Regressor`."""
    words = text.replace("_", " ").split()
    if [w.lower() for w in words] in (["offset"], ["mean", "force"]):
        return Regressor("offset")
    if len(words) != 2:
        raise IdentificationError(
            f"cannot read the term {text!r}",
            hint="write '<DOF> <kind>', e.g. 'Sway acceleration', 'Roll motion', "
            "'Roll cubic', or 'offset'",
        )
    dof = next((d for d in DOF_NAMES if d.lower() == words[0].lower()), words[0])
    return Regressor(words[1].lower(), dof)


@dataclass(frozen=True)
class DampingEstimate:
    """The identified residual-force model of one DOF.

    Attributes
    ----------
    dof
        The equation (DOF) identified.
    regressors
        The terms, in the order of ``coefficients``.
    coefficients
        b_k, in the units of :meth:`Regressor.unit`.
    standard_errors
        Autocorrelation-consistent (Newey–West) standard errors of b_k.
    confidence
        Level of ``intervals`` (0.95).
    intervals
        (n_terms, 2) lower and upper confidence limits.
    condition_number
        Of the regressors scaled to unit length.
    vif
        Variance inflation factor of each term (1 when it is uncorrelated with the others).
    r2
        Share of the residual force's variance explained by the terms.
    method
        ``ols``, ``wls`` or ``bounded``.
    n_samples, effective_samples
        Samples used, and the number of independent ones the autocorrelation leaves.
    at_bound
        Terms the bounded estimate holds at zero.
    amplitude_spread
        Ratio of the 90th to the 10th percentile of the DOF's velocity envelope: about
        4.7 for a Gaussian sea (Rayleigh envelope), near 1 in regular waves, where
        amplitude-dependent damping cannot be told from linear damping.
    """

    dof: str
    regressors: tuple[Regressor, ...]
    coefficients: NDArray[np.float64]
    standard_errors: NDArray[np.float64]
    confidence: float
    intervals: NDArray[np.float64]
    condition_number: float
    vif: NDArray[np.float64]
    r2: float
    method: str
    n_samples: int
    effective_samples: float
    at_bound: tuple[str, ...] = ()
    amplitude_spread: float = float("nan")
    attrs: dict = field(default_factory=dict)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(r.name for r in self.regressors)

    def __getitem__(self, name: str) -> float:
        """The coefficient of a term by its name or kind (``"quadratic"``)."""
        for r, b in zip(self.regressors, self.coefficients, strict=True):
            if name in (r.name, r.kind):
                return float(b)
        raise KeyError(name)

    @property
    def negative(self) -> tuple[str, ...]:
        """Damping terms estimated below zero (physically wrong, and a model that can
        gain energy: flagged)."""
        return tuple(
            r.name
            for r, b in zip(self.regressors, self.coefficients, strict=True)
            if r.kind in DAMPING_KINDS and b < 0
        )

    @property
    def undetermined(self) -> tuple[str, ...]:
        """Terms whose confidence interval is wider than their value: the data do not
        determine them."""
        half = 0.5 * (self.intervals[:, 1] - self.intervals[:, 0])
        return tuple(
            r.name
            for r, b, h in zip(self.regressors, self.coefficients, half, strict=True)
            if h > UNDETERMINED * abs(b)
        )

    @property
    def narrow_banded(self) -> bool:
        """Amplitude-dependent terms asked for, but the velocity amplitude hardly varies
        (:attr:`amplitude_spread` below :data:`AMPLITUDE_SPREAD_LIMIT`)."""
        nonlinear = any(r.kind in ("quadratic", "cubic") for r in self.regressors)
        return nonlinear and self.amplitude_spread < AMPLITUDE_SPREAD_LIMIT

    @property
    def ill_conditioned(self) -> bool:
        """The split between the terms is not to be trusted: collinear regressors
        (condition number over :data:`CONDITION_LIMIT`) with a term the data leave
        undetermined, or a narrow-banded record (:attr:`narrow_banded`)."""
        collinear = self.condition_number > CONDITION_LIMIT and bool(self.undetermined)
        return collinear or self.narrow_banded

    def warnings(self) -> list[str]:
        """Plain-language flags, empty when the estimate is sound."""
        out = []
        if self.negative:
            out.append(
                f"{self.dof}: negative damping estimated for {', '.join(self.negative)} — "
                "physically wrong and a model that can gain energy; use method='bounded' "
                "(--method bounded) or fewer terms"
            )
        if self.narrow_banded:
            out.append(
                f"{self.dof}: the velocity amplitude varies only by a factor "
                f"{self.amplitude_spread:.2g} over the record (narrow-banded, e.g. regular "
                "waves): amplitude-dependent (quadratic, cubic) damping cannot be told from "
                "linear damping — only the equivalent linear damping at this amplitude is "
                "determined; identify 'linear' alone or add records of other amplitudes"
            )
        elif self.ill_conditioned:
            out.append(
                f"{self.dof}: the regressors are collinear (condition number "
                f"{self.condition_number:.3g}, VIF up to {self.vif.max():.3g}) and "
                f"{', '.join(self.undetermined)} not determined by the data — a "
                "narrow-banded record cannot separate the terms: use broader-banded or "
                "several sea states' records, or fewer terms"
            )
        elif self.undetermined:
            out.append(
                f"{self.dof}: {', '.join(self.undetermined)} not determined by the data "
                "(confidence interval wider than the value)"
            )
        return out

    def damping_force(self, velocity: NDArray) -> NDArray:
        """The damping part (linear, quadratic, cubic terms of this DOF) at velocities
        of that DOF, N or N·m."""
        v = np.asarray(velocity, dtype=float)
        out = np.zeros_like(v)
        for r, b in zip(self.regressors, self.coefficients, strict=True):
            if r.kind in DAMPING_KINDS and r.dof == self.dof:
                out += b * {"linear": v, "quadratic": np.abs(v) * v, "cubic": v**3}[r.kind]
        return out

    def to_dict(self) -> dict:
        return {
            "dof": self.dof,
            "method": self.method,
            "confidence": self.confidence,
            "terms": [
                {
                    "name": r.name,
                    "kind": r.kind,
                    "dof": r.dof,
                    "value": float(b),
                    "standard_error": float(s),
                    "interval": [float(lo), float(hi)],
                    "unit": r.unit(self.dof),
                    "vif": float(f),
                }
                for r, b, s, (lo, hi), f in zip(
                    self.regressors,
                    self.coefficients,
                    self.standard_errors,
                    self.intervals,
                    self.vif,
                    strict=True,
                )
            ],
            "condition_number": self.condition_number,
            "r2": self.r2,
            "n_samples": self.n_samples,
            "effective_samples": self.effective_samples,
            "negative": list(self.negative),
            "undetermined": list(self.undetermined),
            "ill_conditioned": self.ill_conditioned,
            "amplitude_spread": self.amplitude_spread,
            "narrow_banded": self.narrow_banded,
            "at_bound": list(self.at_bound),
            "warnings": self.warnings(),
            **{k: v for k, v in self.attrs.items() if isinstance(v, int | float | str)},
        }


def memory_response(
    vessel: Vessel, t: NDArray, velocity: NDArray
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The fluid-memory force μ(t) (time, n) and state χ(t) (time, order) of the vessel's
    radiation model driven by the velocities (time, n), from χ(t₀) = 0 (velocities linear
    between samples: :func:`scipy.signal.lsim`)."""
    model = vessel.radiation
    n = len(vessel.dofs)
    if model.total_order == 0:
        return np.zeros((t.size, n)), np.zeros((t.size, 0))
    _, mu, chi = scipy.signal.lsim(model.to_scipy(), velocity, t - t[0])
    mu = np.asarray(mu).reshape(t.size, n)
    chi = np.asarray(chi).reshape(t.size, -1)
    return mu, chi


def memory_time(vessel: Vessel, fraction: float = 0.02, longest: float = 600.0) -> float:
    """Time after which every retardation function of the vessel's model stays below
    ``fraction`` of its peak, s: the memory's start-up, cut from the residual because the
    history before the record is unknown."""
    model = vessel.radiation
    if model.total_order == 0:
        return 0.0
    t = np.linspace(0.0, longest, 3001)
    k = np.abs(model.impulse_response(t).values).reshape(t.size, -1)
    peak = k.max(axis=0)
    live = peak > 0
    above = k[:, live] > fraction * peak[live]
    last = [np.flatnonzero(col)[-1] if col.any() else 0 for col in above.T]
    return float(t[max(last)]) if last else 0.0


def _vessel_dofs(vessel: Vessel, record: xr.Dataset) -> list[int]:
    dofs = [str(d) for d in record.dof.values]
    missing = [d for d in dofs if d not in vessel.dofs]
    if missing:
        raise IdentificationError(
            f"the record holds {', '.join(missing)}, which the vessel model has not",
            hint=f"the model's DOFs are {', '.join(vessel.dofs)}",
        )
    return [vessel.dofs.index(d) for d in dofs]


def full_motions(record_signals: xr.Dataset, vessel: Vessel) -> dict[str, NDArray]:
    """The record's signals on all the vessel's DOFs (DOFs not recorded are taken as
    zero, with a warning when the model couples them to recorded ones)."""
    idx = _vessel_dofs(vessel, record_signals)
    n = len(vessel.dofs)
    absent = [d for k, d in enumerate(vessel.dofs) if k not in idx]
    if absent:
        m = vessel.mass + np.abs(vessel.stiffness)
        coupled = [d for d in absent if np.any(m[np.ix_(idx, [vessel.dofs.index(d)])] != 0)]
        if coupled:
            warnings.warn(
                f"the record has no {', '.join(coupled)}, which the model couples to the "
                "recorded DOFs: they are taken as zero",
                stacklevel=3,
            )
    out = {}
    for name in ("motion", "velocity", "acceleration", "excitation_force"):
        if name in record_signals:
            full = np.zeros((record_signals.sizes["time"], n))
            full[:, idx] = record_signals[name].values
            out[name] = full
    return out


def residual_force(
    record: xr.Dataset,
    vessel: Vessel,
    *,
    cutoff: float | None = None,
) -> xr.Dataset:
    """F_res = τ − [(M_RB + A∞)ξ̈ + μ + B_v ξ̇ + Cξ] of every recorded DOF (module
    docstring; de Haan (2022) eq. 2.21 with Cξ for the printed Cξ̇).

    Parameters
    ----------
    record
        A record with ``motion`` and ``excitation_force``
        (:func:`cummins.sysid.records.read_record`).
    vessel
        The potential-flow model (:func:`cummins.vessel.vessel_from_hydrodb`) in the
        record's axes and reference point.
    cutoff
        Low-pass cut-off of the differentiation, rad/s (default :func:`default_cutoff`).

    Returns
    -------
    xarray.Dataset
        ``residual_force`` (time, dof) N or N·m, with the smoothed ``motion``,
        ``velocity``, ``acceleration``, ``excitation_force`` and the ``memory_force``
        (time, dof) of the recorded DOFs; the memory state ``chi`` (time, state);
        attributes ``memory_time`` (s: samples before it are not trustworthy, the memory
        starts empty), ``edge`` (s: the filter's transients at both ends), ``cutoff``.
    """
    if "excitation_force" not in record:
        raise IdentificationError(
            "the record has no excitation force",
            hint="add the predicted or measured wave force, or a wave elevation "
            "(cummins.sysid.excitation_from_elevation)",
        )
    signals = motion_derivatives(record, cutoff)
    full = full_motions(signals, vessel)
    t = record.time.values
    mu, chi = memory_response(vessel, t, full["velocity"])
    inertia = full["acceleration"] @ vessel.mass.T
    restoring = full["motion"] @ vessel.stiffness.T
    damping = full["velocity"] @ vessel.viscous_damping.T
    residual = full["excitation_force"] - inertia - mu - restoring - damping
    idx = _vessel_dofs(vessel, record)
    out = signals.copy()
    out["memory_force"] = (("time", "dof"), mu[:, idx])
    out["residual_force"] = (("time", "dof"), residual[:, idx])
    out["chi"] = (("time", "state"), chi)
    out.attrs.update({"memory_time": memory_time(vessel), "dt": time_step(record)})
    return out


# --------------------------------------------------------------------------- regression


def trusted_samples(res: xr.Dataset, burn_in: float | None = None) -> NDArray[np.bool_]:
    """Samples of a :func:`residual_force` result after the memory's start-up (or
    ``burn_in`` s) and away from the filter's transients at both ends."""
    t = res.time.values
    start = res.attrs["memory_time"] if burn_in is None else burn_in
    start = max(start, res.attrs["edge"])
    keep = (t >= t[0] + start) & (t <= t[-1] - res.attrs["edge"])
    return keep


def _hac_covariance(x: NDArray, e: NDArray, w: NDArray) -> tuple[NDArray, float]:
    """Newey–West (Bartlett) covariance of the least-squares estimate and the effective
    number of samples; the bandwidth is three integral time scales of the residual."""
    n = e.size
    xw = x * w[:, None]
    u = xw * (w * e)[:, None]
    bread = np.linalg.pinv(xw.T @ xw)
    ew = w * e
    ew = ew - ew.mean()
    spectrum = np.fft.rfft(ew, 2 * n)
    acf = np.fft.irfft(np.abs(spectrum) ** 2)[:n]
    acf = acf / acf[0] if acf[0] > 0 else np.zeros(n)
    first_zero = np.flatnonzero(acf <= 0)
    stop = int(first_zero[0]) if first_zero.size else n
    scale = float(1.0 + 2.0 * acf[1:stop].sum())
    lags = int(min(n // 4, max(1, np.ceil(3 * scale))))
    meat = u.T @ u
    for lag in range(1, lags + 1):
        weight = 1.0 - lag / (lags + 1)
        g = u[lag:].T @ u[:-lag]
        meat += weight * (g + g.T)
    cov = bread @ meat @ bread
    return cov, n / max(scale, 1.0)


def _vif(x: NDArray, offset: NDArray[np.bool_]) -> NDArray:
    """Variance inflation factors (centred; the constant term gets 1)."""
    out = np.ones(x.shape[1])
    cols = np.flatnonzero(~offset)
    if cols.size > 1:
        xc = x[:, cols] - x[:, cols].mean(axis=0)
        corr = np.corrcoef(xc, rowvar=False)
        with np.errstate(all="ignore"):
            out[cols] = np.diag(np.linalg.pinv(corr))
    return out


def fit_terms(
    y: NDArray,
    x: NDArray,
    regressors: Sequence[Regressor],
    dof: str,
    *,
    method: str = "ols",
    weights: NDArray | None = None,
    confidence: float = 0.95,
) -> DampingEstimate:
    """Least squares of y ≈ X b with the diagnostics of :class:`DampingEstimate`.

    ``method`` ``ols``; ``wls`` with ``weights`` (one per sample, e.g. the inverse
    standard deviation of each sample's error); ``bounded``: damping terms ≥ 0
    (:func:`scipy.optimize.lsq_linear`), the interval of a term held at 0 starting at 0.
    """
    if method not in ("ols", "wls", "bounded"):
        raise IdentificationError(f"method must be 'ols', 'wls' or 'bounded', not {method!r}")
    if method == "wls" and weights is None:
        raise IdentificationError("method='wls' needs weights (one per sample)")
    n, p = x.shape
    if n <= 3 * p:
        raise IdentificationError(
            f"{n} samples for {p} terms of {dof}: the record is too short",
            hint="use a longer record or fewer terms",
        )
    w = np.ones(n) if weights is None else np.sqrt(np.asarray(weights, dtype=float))
    if w.shape != (n,) or not np.all(np.isfinite(w)) or np.any(w < 0):
        raise IdentificationError("weights must be finite, non-negative, one per sample")
    scale = np.linalg.norm(x * w[:, None], axis=0)
    dead = [r.name for r, s in zip(regressors, scale, strict=True) if s == 0]
    if dead:
        raise IdentificationError(
            f"the record does not excite {', '.join(dead)} (zero throughout)",
            hint="drop the term or use a record in which it moves",
        )
    xs = x / scale
    xsw = xs * w[:, None]
    yw = y * w
    lower = np.array([0.0 if r.kind in DAMPING_KINDS else -np.inf for r in regressors])
    at_bound: tuple[str, ...] = ()
    if method == "bounded":
        sol = scipy.optimize.lsq_linear(xsw, yw, bounds=(lower, np.inf), lsmr_tol="auto")
        beta = sol.x
        held = (lower == 0) & (beta <= 1e-12 * max(np.abs(beta).max(), 1e-300))
        beta = np.where(held, 0.0, beta)
        at_bound = tuple(r.name for r, h in zip(regressors, held, strict=True) if h)
    else:
        beta = np.linalg.lstsq(xsw, yw, rcond=None)[0]
    e = y - xs @ beta
    cov, effective = _hac_covariance(xs, e, w)
    se = np.sqrt(np.clip(np.diag(cov), 0, None)) / scale
    b = beta / scale
    z = scipy.stats.norm.ppf(0.5 + 0.5 * confidence)
    intervals = np.stack([b - z * se, b + z * se], 1)
    if method == "bounded":
        intervals[:, 0] = np.maximum(intervals[:, 0], np.where(lower == 0, 0.0, -np.inf))
    unit = xs / np.linalg.norm(xs, axis=0)
    offset = np.array([r.kind == "offset" for r in regressors])
    total = float(np.sum(w**2 * (y - np.average(y, weights=w**2)) ** 2))
    r2 = 1.0 - float(np.sum((w * e) ** 2)) / total if total > 0 else float("nan")
    return DampingEstimate(
        dof=dof,
        regressors=tuple(regressors),
        coefficients=b,
        standard_errors=se,
        confidence=confidence,
        intervals=intervals,
        condition_number=float(np.linalg.cond(unit)),
        vif=_vif(x, offset),
        r2=r2,
        method=method,
        n_samples=n,
        effective_samples=float(effective),
        at_bound=at_bound,
    )


@dataclass(frozen=True)
class DampingModel:
    """The identified damping of one or more DOFs (one :class:`DampingEstimate` each)."""

    estimates: tuple[DampingEstimate, ...]
    attrs: dict = field(default_factory=dict)

    def __getitem__(self, dof: str) -> DampingEstimate:
        for e in self.estimates:
            if e.dof == dof:
                return e
        raise KeyError(dof)

    @property
    def dofs(self) -> tuple[str, ...]:
        return tuple(e.dof for e in self.estimates)

    def warnings(self) -> list[str]:
        return [w for e in self.estimates for w in e.warnings()]

    def to_dict(self) -> dict:
        return {
            "estimates": [e.to_dict() for e in self.estimates],
            **{k: v for k, v in self.attrs.items() if isinstance(v, int | float | str)},
        }


def regressor_matrix(res: xr.Dataset, regressors: Sequence[Regressor]) -> NDArray:
    """The values of the regressors (time, term) over a :func:`residual_force` result.

    A nonlinear term g(ξ̇) (quadratic, cubic) makes harmonics that the low-pass filter
    removed from the residual force: it is filtered by the same filter, so both sides
    of F_res = Σ b_k φ_k see the same frequency response (the linear terms are filtered
    already)."""
    dofs = [str(x) for x in res.dof.values]
    for r in regressors:
        if r.kind != "offset" and r.dof not in dofs:
            raise IdentificationError(
                f"the record has no {r.dof} for the term {r.name}",
                hint=f"it holds {', '.join(dofs)}",
            )
    m, v, a = res.motion.values, res.velocity.values, res.acceleration.values
    x = np.stack([r.values(m, v, a, dofs) for r in regressors], 1)
    nonlinear = [k for k, r in enumerate(regressors) if r.kind in ("quadratic", "cubic")]
    if nonlinear:
        x[:, nonlinear] = filtered_derivatives(
            x[:, nonlinear], res.attrs["dt"], res.attrs["cutoff"], (0,)
        )[0]
    return x


def identify_damping(
    records: xr.Dataset | Sequence[xr.Dataset],
    vessel: Vessel,
    dofs: Sequence[str] = ("Roll",),
    *,
    terms: Sequence[str] = ("linear", "quadratic", "cubic"),
    couplings: Sequence[str | Regressor] = (),
    offset: bool = False,
    method: str = "ols",
    weights: Sequence | None = None,
    cutoff: float | None = None,
    burn_in: float | None = None,
    confidence: float = 0.95,
) -> DampingModel:
    """Identify the damping the potential-flow model lacks from motion records.

    Parameters
    ----------
    records
        One record or several (segments, sea states, tests): their samples are pooled.
        Each needs ``motion`` of the DOFs and ``excitation_force``
        (:mod:`cummins.sysid.records`).
    vessel
        The potential-flow model (:func:`cummins.vessel.vessel_from_hydrodb`); its
        ``viscous_damping`` is kept and the estimate adds to it.
    dofs
        The equations to identify, e.g. ``("Roll",)``.
    terms
        Damping terms of each DOF: ``linear`` b₁ξ̇, ``quadratic`` b₂|ξ̇|ξ̇, ``cubic``
        b₃ξ̇³ (de Haan (2022) eq. 2.22).
    couplings
        Extra terms, e.g. ``"Sway acceleration"``, ``"Roll motion"`` (corrections of the
        model's M, C entries: :class:`Regressor`).
    offset
        Also fit a mean force (wind, current, a list).
    method
        ``"ols"``, ``"wls"`` (with ``weights``, one array per record) or ``"bounded"``
        (damping ≥ 0).
    cutoff
        Low-pass cut-off of the differentiation, rad/s (:func:`default_cutoff`).
    burn_in
        Seconds cut at the start of each record (default: the memory's start-up,
        :func:`memory_time`).
    confidence
        Level of the confidence intervals.

    Returns
    -------
    DampingModel
        One :class:`DampingEstimate` per DOF, with intervals and flags; its warnings are
        also issued as Python warnings.

    Raises
    ------
    IdentificationError
        No excitation force, a DOF not in the record or the model, too few samples, a
        term that is zero throughout.

    Examples
    --------
    See ``docs`` and ``tests/test_sysid.py``: a record simulated with known roll damping
    is identified within the intervals reported.
    """
    recs = [records] if isinstance(records, xr.Dataset) else list(records)
    if not recs:
        raise IdentificationError("no records given")
    if weights is not None and len(weights) != len(recs):
        raise IdentificationError("give one weight array per record")
    extra = [parse_regressor(c) if isinstance(c, str) else c for c in couplings]
    rows = []  # per record: residuals, motions (trusted samples), and the record
    for k, rec in enumerate(recs):
        for d in dofs:
            if d not in [str(x) for x in rec.dof.values]:
                raise IdentificationError(
                    f"record {rec.attrs.get('source_file', k)} has no {d} motion",
                    hint=f"it holds {', '.join(map(str, rec.dof.values))}",
                )
        res = residual_force(rec, vessel, cutoff=cutoff)
        keep = trusted_samples(res, burn_in)
        if keep.sum() < 10:
            raise IdentificationError(
                f"record {rec.attrs.get('source_file', k)} lasts "
                f"{rec.time.values[-1] - rec.time.values[0]:g} s: nothing is left after the "
                f"memory's start-up of {res.attrs['memory_time']:g} s",
                hint="use longer records, or give burn_in",
            )
        w = None if weights is None else np.asarray(weights[k], dtype=float)[keep]
        rows.append((res, keep, w))
    estimates = []
    for d in dofs:
        regs = (*damping_terms(d, terms, offset=offset), *extra)
        xs, ys, ws = [], [], []
        for res, keep, w in rows:
            xs.append(regressor_matrix(res, regs)[keep])
            ys.append(res.residual_force.sel(dof=d).values[keep])
            ws.append(np.ones(ys[-1].size) if w is None else w)
        estimate = fit_terms(
            np.concatenate(ys),
            np.concatenate(xs),
            regs,
            d,
            method=method,
            weights=None if weights is None else np.concatenate(ws),
            confidence=confidence,
        )
        envelope = np.concatenate(
            [
                np.abs(scipy.signal.hilbert(res.velocity.sel(dof=d).values))[keep]
                for res, keep, _ in rows
            ]
        )
        p10, p90 = np.percentile(envelope, [10, 90])
        spread = float(p90 / p10) if p10 > 0 else float("inf")
        estimates.append(dataclasses.replace(estimate, amplitude_spread=spread))
    model = DampingModel(
        tuple(estimates),
        attrs={
            "n_records": len(recs),
            "cutoff": float(rows[0][0].attrs["cutoff"]),
            "memory_time": float(rows[0][0].attrs["memory_time"]),
        },
    )
    for text in model.warnings():
        warnings.warn(text, stacklevel=2)
    return model
