"""Roll decay analysis: linear and quadratic damping from a free-decay record.

The record is modelled as the free decay of

    φ̈ + p₁ φ̇ + p₂ |φ̇| φ̇ + ω₀² φ = 0                                   (1)

(per unit of the total roll inertia I₄₄ + A₄₄; ITTC Recommended Procedure 7.5-02-07-04.5,
Himeno 1981). Two estimates:

**Decrement** (the classic analysis). The extremes φ_n of the record (alternating sides)
give the decrement per half cycle Δφ = φ_n − φ_{n+1} at the mean amplitude
φ_m = (φ_n + φ_{n+1})/2. Equating the energy lost over a half cycle of φ = φ_m sin ω₀t
to the work of the damping of (1):

    Δφ = (π p₁ / (2ω₀)) φ_m + (4/3) p₂ φ_m²                             (2)

a straight line through the origin in (φ_m, Δφ/φ_m) — linear least squares gives p₁,
p₂ and their standard errors; ω₀ from the mean half period and the damping. It is
exact to first order in the damping.

**Fit** (default). (1) is integrated and its parameters (p₁, p₂, ω₀, the initial angle
and rate, and a mean heel) are adjusted to the whole record by nonlinear least squares,
starting from the decrement estimate; the standard errors are those of the
least-squares Jacobian. It holds for any damping and any record length.

With ``inertia`` (I₄₄ + A₄₄, kg·m²) or ``stiffness`` (C₄₄, N·m/rad; I = C₄₄/ω₀²)
the dimensional B₁ = p₁ I (N·m·s/rad) and B₂ = p₂ I (N·m·s²/rad²) are given too.
"""

from __future__ import annotations

import itertools
import warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.integrate
import scipy.optimize
import scipy.stats
from numpy.typing import ArrayLike, NDArray

from cummins.errors import IdentificationError

#: Extremes needed: three half cycles.
MIN_EXTREMES = 4


@dataclass(frozen=True)
class RollDecay:
    """Result of :func:`roll_decay`.

    Keys (``result["p1"]``): ``p1`` (1/s), ``p2`` (1/rad), ``omega0`` (rad/s), their
    standard errors ``p1_std``, ``p2_std``, ``omega0_std``, and with an inertia or
    stiffness ``B1`` (N·m·s/rad), ``B2`` (N·m·s²/rad²), ``inertia`` (kg·m²).

    Attributes
    ----------
    values
        The keys above.
    method
        ``fit`` or ``decrement``.
    amplitudes, decrements
        φ_m and Δφ of the half cycles (rad), for the decrement plot.
    extremes_time, extremes
        Times (s) and angles (rad, about the mean heel) of the extremes.
    offset
        Mean heel angle the record decays to, rad.
    """

    values: dict
    method: str
    amplitudes: NDArray[np.float64]
    decrements: NDArray[np.float64]
    extremes_time: NDArray[np.float64]
    extremes: NDArray[np.float64]
    offset: float
    attrs: dict = field(default_factory=dict)

    def __getitem__(self, key: str) -> float:
        return self.values[key]

    def keys(self):
        return self.values.keys()

    def equivalent_damping_ratio(self, amplitude: ArrayLike) -> NDArray[np.float64]:
        """ζ_eq(φ_a) = (p₁ + 8/(3π) ω₀ φ_a p₂) / (2ω₀): the linear damping ratio that
        dissipates the same energy per cycle at amplitude φ_a (rad)."""
        a = np.asarray(amplitude, dtype=float)
        p1, p2, w0 = self["p1"], self["p2"], self["omega0"]
        return (p1 + 8 / (3 * np.pi) * w0 * a * p2) / (2 * w0)

    def simulate(self, t: ArrayLike) -> NDArray[np.float64]:
        """The fitted decay (1) at times t (s), rad, including the mean heel."""
        tt = np.asarray(t, dtype=float) - self.attrs["t0"]
        out = np.full(tt.shape, np.nan)
        after = tt >= 0
        out[after] = _decay(
            tt[after],
            self["p1"],
            self["p2"],
            self["omega0"],
            self.attrs["phi0"],
            self.attrs["rate0"],
        )
        return out + self.offset


def _extremes(t: NDArray, phi: NDArray) -> tuple[NDArray, NDArray]:
    """Times and values of the extremes between successive zero crossings, refined by a
    parabola through the largest sample and its neighbours."""
    sign = np.sign(phi)
    crossings = np.flatnonzero(sign[:-1] * sign[1:] < 0) + 1
    bounds = np.concatenate([[0], crossings, [phi.size]])
    times, values = [], []
    dt = t[1] - t[0]
    for lo, hi in itertools.pairwise(bounds):
        if hi - lo < 3:
            continue
        k = lo + int(np.argmax(np.abs(phi[lo:hi])))
        if k in (0, phi.size - 1) or (k in (lo, hi - 1) and lo == 0):
            continue  # the record starts (or ends) mid-cycle: not an extreme
        if k == hi - 1 and hi == phi.size:
            continue
        y0, y1, y2 = phi[k - 1], phi[k], phi[k + 1]
        denom = y0 - 2 * y1 + y2
        shift = 0.5 * (y0 - y2) / denom if denom != 0 else 0.0
        shift = float(np.clip(shift, -1, 1))
        times.append(t[k] + shift * dt)
        values.append(y1 - 0.25 * (y0 - y2) * shift)
    return np.asarray(times), np.asarray(values)


def _usable(times: NDArray, values: NDArray, noise: float) -> int:
    """How many leading extremes belong to the decay: stop where the amplitude sinks
    to the noise (< 5 σ) or a half period strays by more than 25 % from the median of
    the first ones (zero crossings of the noise)."""
    amp = np.abs(values)
    half = np.diff(times)
    if half.size == 0:
        return values.size
    typical = float(np.median(half[: max(3, min(8, half.size))]))
    for k in range(1, values.size):
        if amp[k] < 5 * noise or abs(half[k - 1] - typical) > 0.25 * typical:
            return k
    return values.size


def _rate(y, _, p1, p2, w0):
    return (y[1], -p1 * y[1] - p2 * abs(y[1]) * y[1] - w0 * w0 * y[0])


def _decay(t, p1, p2, w0, phi0, rate0):
    """φ(t) of eq. (1) at times t ≥ 0 from φ(0) = phi0, φ̇(0) = rate0 (LSODA)."""
    grid = np.concatenate([[0.0], t]) if t[0] > 0 else t
    size = max(abs(phi0), abs(rate0) / max(abs(w0), 1e-9), 1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an unphysical trial of the fit: NaN, handled
        y, info = scipy.integrate.odeint(
            _rate,
            [phi0, rate0],
            grid,
            args=(p1, p2, w0),
            rtol=1e-8,
            atol=1e-11 * size,
            full_output=True,
        )
    if info["message"] != "Integration successful.":
        return np.full(t.size, np.nan)
    return y[-t.size :, 0]


def _decrement(times, extremes, cubic=False):
    """p₁, p₂, ω₀ and standard errors from eq. (2)."""
    amp = np.abs(extremes)
    mean = 0.5 * (amp[:-1] + amp[1:])
    dec = amp[:-1] - amp[1:]
    x = np.stack([mean, mean**2], 1)
    coef, *_ = np.linalg.lstsq(x, dec, rcond=None)
    dof = max(dec.size - 2, 1)
    resid = dec - x @ coef
    s2 = float(resid @ resid) / dof
    cov = s2 * np.linalg.pinv(x.T @ x)
    half = np.diff(times)
    wd = np.pi / float(np.mean(half))
    # first guess of ω₀ from the damped frequency and the mean damping ratio
    zeta = float(np.clip(coef[0] / np.pi + (4 / 3) * coef[1] * mean.mean() / np.pi, 0, 0.9))
    w0 = wd / np.sqrt(1 - zeta**2)
    scale = np.array([2 * w0 / np.pi, 3 / 4])
    p = coef * scale
    p_std = np.sqrt(np.clip(np.diag(cov), 0, None)) * scale
    w0_std = wd * float(np.std(half, ddof=1) / np.mean(half)) / np.sqrt(half.size)
    return p, p_std, w0, w0_std, mean, dec


#: Level of the confidence intervals the decay's terms are judged by (as
#: :func:`cummins.sysid.identify_damping`'s).
CONFIDENCE = 0.95

#: A quadratic term whose share of the equivalent linear damping at the record's largest
#: amplitude is below this is negligible whatever its interval (a noise-free record gives
#: intervals that measure only the integrator's error).
NEGLIGIBLE_SHARE = 0.01


def _quadratic_judgement(values: dict, amplitude: float) -> dict:
    """Whether p₂ is significant: its 95 % interval p₂ ± 1.96σ (normal, as the damping
    identification's) and its share of ζ_eq at the largest amplitude (eq. 2's
    8/(3π) ω₀ φ_a p₂ against p₁).

    Returns ``p2_interval``, ``p2_share``, ``p2_significance`` (``"positive"``,
    ``"not significant"`` or ``"negative"``) and ``p2_note`` (empty for a significant
    positive term; else the sentence that says it, completed by the caller)."""
    z = scipy.stats.norm.ppf(0.5 + 0.5 * CONFIDENCE)
    p1, p2, w0 = values["p1"], values["p2"], values["omega0"]
    low, high = p2 - z * values["p2_std"], p2 + z * values["p2_std"]
    quadratic = 8 / (3 * np.pi) * w0 * amplitude * p2
    share = abs(quadratic) / max(abs(p1) + abs(quadratic), 1e-300)
    interval = f"{CONFIDENCE:.0%} interval [{low:.3g}, {high:.3g}] 1/rad"
    at = f"{share:.1%} of the damping at {np.degrees(amplitude):.3g}°"
    if low <= 0 <= high or share < NEGLIGIBLE_SHARE:
        verdict = "not significant"
        why = "includes 0" if low <= 0 <= high else f"but only {at}"
        note = (
            f"p2 = {p2:.3g} 1/rad is not significant ({interval} {why}): the decay is "
            "linear as far as the record tells"
        )
    elif p2 < 0:
        verdict = "negative"
        note = (
            f"negative quadratic roll damping p2 = {p2:.3g} 1/rad ({interval}, {at}): "
            "physically wrong (damping that weakens as the amplitude grows); is the record "
            "a free decay, the restoring linear, the release clean? (The fluid memory's "
            "transient after the release shows so too, by a few % of p1: identify again "
            "with the first cycles cut, --burn-in, to tell)"
        )
    else:
        verdict, note = "positive", ""
    return {
        "p2_interval": [float(low), float(high)],
        "p2_share": float(share),
        "p2_significance": verdict,
        "p2_note": note,
    }


#: A positive p₂ that changes by more than this share of itself, and by more than its
#: 95 % intervals allow, when the first cycle after the release is left out is said to
#: depend on it (:func:`roll_decay`): a linear Cummins decay of the supply vessel
#: (MSS, 10°) gives p₂ 0.055 1/rad "significant", not significant with the first
#: cycles cut; an ODE decay with p₂ = 0.3 changes by 1e-6.
RELEASE_CHANGE = 0.25


def _release_judgement(t, phi, second_cycle: float, values: dict, method: str) -> dict:
    """``p2_without_first_cycle`` and, when p₂ depends on the first cycle
    (:data:`RELEASE_CHANGE`), the ``p2_note`` that says so."""
    k = int(np.searchsorted(t, second_cycle))
    try:
        cut = roll_decay(t[k:], phi[k:], method=method, release_check=False)
    except IdentificationError:
        return {}
    p2, p2_cut = values["p2"], cut["p2"]
    z = scipy.stats.norm.ppf(0.5 + 0.5 * CONFIDENCE)
    allowed = z * float(np.hypot(values["p2_std"], cut["p2_std"]))
    out: dict = {"p2_without_first_cycle": float(p2_cut)}
    if abs(p2_cut - p2) > max(allowed, RELEASE_CHANGE * abs(p2)):
        low, high = cut["p2_interval"]
        out["p2_note"] = (
            f"p2 = {p2:.3g} 1/rad depends on the first cycle after the release: without it "
            f"p2 = {p2_cut:.3g} 1/rad ({CONFIDENCE:.0%} interval [{low:.3g}, {high:.3g}], "
            f"{cut['p2_significance']}); what follows the release (a fluid memory's "
            "transient in a simulated decay, an unclean release in a test) is taken for "
            "quadratic damping: identify again with the first cycles cut (--burn-in) to tell"
        )
    return out


def _linear_decrement(times, extremes, w0) -> tuple[float, float]:
    """p₁ and its standard error from eq. (2) without the quadratic term."""
    amp = np.abs(extremes)
    mean = 0.5 * (amp[:-1] + amp[1:])
    ratio = (amp[:-1] - amp[1:]) / mean
    c = float(np.mean(ratio))
    se = float(np.std(ratio, ddof=1) / np.sqrt(ratio.size)) if ratio.size > 1 else 0.0
    scale = 2 * w0 / np.pi
    return c * scale, se * scale


def roll_decay(
    t: ArrayLike,
    phi: ArrayLike,
    inertia: float | None = None,
    stiffness: float | None = None,
    *,
    method: str = "fit",
    release_check: bool = True,
) -> RollDecay:
    """Linear and quadratic roll damping from a free-decay record (module docstring).

    Parameters
    ----------
    t
        Uniformly sampled times, s.
    phi
        Roll angle, rad, from the release on (the record may include a constant heel).
    inertia
        Total roll inertia I₄₄ + A₄₄(ω₀), kg·m², for dimensional coefficients.
    stiffness
        C₄₄, N·m/rad: the inertia is then C₄₄/ω₀² (when ``inertia`` is not given).
    method
        ``"fit"`` (default, the ODE fitted to the whole record) or ``"decrement"``.
    release_check
        When p₂ comes out significantly positive, identify again without the first cycle
        and say in ``p2_note`` when p₂ depends on it (:data:`RELEASE_CHANGE`): what
        happens just after the release — a fluid memory's transient, an unclean release
        — is then taken for quadratic damping (``p2_without_first_cycle``).

    Returns
    -------
    RollDecay
        ``p1`` (1/s), ``p2`` (1/rad), ``omega0`` (rad/s) of φ̈ + p₁φ̇ + p₂|φ̇|φ̇ + ω₀²φ = 0,
        with standard errors; ``B1``, ``B2`` with an inertia or stiffness.

    Raises
    ------
    IdentificationError
        Non-uniform or non-finite samples, fewer than four extremes (three half cycles),
        a record that does not decay.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 120, 0.05)
    >>> phi = 0.2 * np.exp(-0.05 * t) * np.cos(0.6 * t)       # p1 = 0.1 1/s
    >>> r = roll_decay(t, phi)
    >>> round(r["p1"], 3), round(r["omega0"], 3)
    (0.1, 0.602)
    """
    t = np.asarray(t, dtype=float).reshape(-1)
    phi = np.asarray(phi, dtype=float).reshape(-1)
    if method not in ("fit", "decrement"):
        raise IdentificationError(f"method must be 'fit' or 'decrement', not {method!r}")
    if t.shape != phi.shape or t.size < 10:
        raise IdentificationError("t and phi need the same length, at least 10 samples")
    bad = ~np.isfinite(phi) | ~np.isfinite(t)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise IdentificationError(f"the record is not finite at sample {k} (t = {t[k]:.6g} s)")
    dt = float(t[1] - t[0])
    if not dt > 0 or np.any(np.abs(np.diff(t) - dt) > 1e-3 * dt):
        raise IdentificationError("the times must be uniformly spaced and increasing")
    if np.ptp(phi) > 2.0:
        raise IdentificationError(
            f"the roll angle spans {np.ptp(phi):.3g}: degrees, not radians?",
            hint="give phi in rad (numpy.radians)",
        )
    # the heel it decays to: the mean of the last cycles is biased by the decay, so
    # start from the median and let the fit adjust it
    offset = float(np.median(phi[phi.size // 2 :]))
    # noise of the record: the second difference of a smooth signal sampled finely is
    # tiny; that of white noise has variance 6σ²
    noise = float(np.std(np.diff(phi, 2)) / np.sqrt(6))
    times, ext = _extremes(t, phi - offset)
    keep = _usable(times, ext, noise)
    times, ext = times[:keep], ext[:keep]
    if ext.size < MIN_EXTREMES:
        raise IdentificationError(
            f"the record has {ext.size} extremes; a decay analysis needs at least "
            f"{MIN_EXTREMES} (three half cycles)",
            hint="record longer, or release from a larger angle",
        )
    amp = np.abs(ext)
    if amp[-1] >= amp[0]:
        raise IdentificationError(
            f"the record does not decay ({np.degrees(amp[0]):.3g}° → {np.degrees(amp[-1]):.3g}°)",
            hint="is it a free decay (no waves, no forcing)?",
        )
    p, p_std, w0, w0_std, mean, dec = _decrement(times, ext)
    values = {
        "p1": float(p[0]),
        "p2": float(p[1]),
        "omega0": float(w0),
        "p1_std": float(p_std[0]),
        "p2_std": float(p_std[1]),
        "omega0_std": float(w0_std),
    }
    # start of the decay model: at the first extreme (rate zero)
    start = int(np.searchsorted(t, times[0]))
    stop = min(t.size, int(np.searchsorted(t, times[-1])) + 1)
    phi0, rate0 = float(ext[0]), 0.0
    t0 = float(times[0])
    if method == "fit":
        # the samples of the usable half cycles, at most ~3000 of them (the fit's cost)
        step = max(1, (stop - start) // 3000)
        span = slice(start, stop, step)
        values, offset, phi0, rate0 = _fit(t[span], phi[span], values, offset, t0, ext[0])
    values.update(_quadratic_judgement(values, float(amp[0])))
    if release_check and values["p2_significance"] == "positive" and ext.size - 2 >= MIN_EXTREMES:
        values.update(_release_judgement(t, phi, times[2], values, method))
    if values["p2_note"]:  # what the record says without the quadratic term
        if method == "fit":
            linear, *_ = _fit(t[span], phi[span], values, offset, t0, ext[0], quadratic=False)
            p1_linear, p1_linear_std = linear["p1"], linear["p1_std"]
        else:
            p1_linear, p1_linear_std = _linear_decrement(times, ext, float(w0))
        values["p1_linear"], values["p1_linear_std"] = float(p1_linear), float(p1_linear_std)
        values["p2_note"] += (
            f"; the linear-only fit gives p1 = {p1_linear:.4g} ± {1.96 * p1_linear_std:.2g} 1/s"
        )
        if values["p2_significance"] == "negative":
            warnings.warn(values["p2_note"], stacklevel=2)
    result = RollDecay(
        values=values,
        method=method,
        amplitudes=mean,
        decrements=dec,
        extremes_time=times,
        extremes=ext,
        offset=offset,
        attrs={"phi0": phi0, "rate0": rate0, "t0": t0},
    )
    if inertia is None and stiffness is not None:
        inertia = float(stiffness) / values["omega0"] ** 2
    if inertia is not None:
        values.update(
            {
                "inertia": float(inertia),
                "B1": values["p1"] * inertia,
                "B2": values["p2"] * inertia,
                "B1_std": values["p1_std"] * inertia,
                "B2_std": values["p2_std"] * inertia,
            }
        )
    return result


def _fit(t, phi, start_values, offset, t0, phi0, quadratic=True):
    """Least squares of the ODE (1) against the record from its first extreme (without
    ``quadratic``: with p₂ held at zero)."""
    tt = t - t0
    mask = tt >= 0
    y = phi[mask]
    free = np.array([True, quadratic, True, True, True, True])

    def residual(q_free):
        q = np.zeros(6)
        q[free] = q_free
        p1, p2, w0, a0, r0, off = q
        out = _decay(tt[mask], p1, p2, w0, a0, r0) + off - y
        return np.where(np.isfinite(out), out, 1e3)

    q0 = np.array(
        [
            start_values["p1"],
            start_values["p2"] if quadratic else 0.0,
            start_values["omega0"],
            phi0,
            0.0,
            offset,
        ]
    )
    scale = np.array(
        [
            max(abs(q0[0]), 1e-3 * q0[2]),
            max(abs(q0[1]), 1e-3),
            q0[2],
            abs(phi0),
            abs(phi0) * q0[2],
            abs(phi0),
        ]
    )
    sol = scipy.optimize.least_squares(
        residual,
        q0[free],
        x_scale=scale[free],
        method="lm",
        xtol=1e-10,
        ftol=1e-10,
        max_nfev=400,
        # far above the integrator's tolerance, or the Jacobian is noise: at 1e-5 a
        # purely linear 12° decay stopped at p₂ = −0.0024 1/rad (misfit 2e-5 rad), at
        # 1e-3 it ends at −4e-6 (misfit 3e-8 rad)
        diff_step=1e-3,
    )
    if not sol.success or not np.all(np.isfinite(sol.x)):
        raise IdentificationError("the decay model could not be fitted to the record")
    n, k = y.size, int(free.sum())
    s2 = 2 * sol.cost / max(n - k, 1)
    cov = s2 * np.linalg.pinv(sol.jac.T @ sol.jac)
    std = np.zeros(6)
    std[free] = np.sqrt(np.clip(np.diag(cov), 0, None))
    q = np.zeros(6)
    q[free] = sol.x
    p1, p2, w0, a0, r0, off = q
    values = {
        "p1": float(p1),
        "p2": float(p2),
        "omega0": float(w0),
        "p1_std": float(std[0]),
        "p2_std": float(std[1]),
        "omega0_std": float(std[2]),
        "rms_misfit": float(np.sqrt(2 * sol.cost / n)),
    }
    return values, float(off), float(a0), float(r0)
