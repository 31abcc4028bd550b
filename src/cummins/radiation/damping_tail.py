"""High-frequency tails of the radiation damping B(ω) beyond the last data frequency.

The retardation function K(t) = (2/π) ∫₀^∞ B(ω) cos(ωt) dω (Hjulstad (2004) eq. 5.15)
and the Kramers–Kronig integral (2/π) PV ∫₀^∞ B(ν)/(ν² − ω²) dν (Hjulstad (2004)
eq. 5.23) need B beyond the last frequency ω_N. :func:`fit_damping_tail` fits, per
coupling, a decaying continuation anchored at the last data point: an exponential
B_N e^{−α(ω−ω_N)}, whose cosine and sine transforms are known in closed form (de Haan
(2022) §2.5.1), or a power law B_N (ω_N/ω)^n, in closed form for n = 2 (sine and cosine
integrals) and otherwise integrated exactly on a fine geometric grid. A finite-order
radiation model has Re K(jω) ~ ω⁻² at high frequency, so slower power laws are steepened
to :data:`MIN_POWER`. The tail's share of ∫B dω is reported by
:func:`cummins.radiation.retardation.retardation_diagnostics` because K(0) depends on it.
:mod:`cummins.radiation.retardation` re-exports these names.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import sici

from cummins.errors import HydroDataError
from cummins.radiation.transforms import cosine_transform, hilbert_pv, sine_transform

TAIL_KINDS = ("exponential", "power", "auto", "none")

#: Slowest power-law decay of a damping tail. A finite-order (rational, relative degree
#: one) radiation model has Re K(jω) ~ ω⁻² at high frequency; a slower decay fitted on a
#: truncated range would put an unbounded share of ∫B dω in the extrapolation.
MIN_POWER = 2.0


@dataclass(frozen=True)
class DampingTail:
    """High-frequency continuation of B(ω) beyond the last frequency, per coupling.

    Attributes
    ----------
    kind
        ``"exponential"`` (B_N e^{−α(ω−ω_N)}), ``"power"`` (B_N (ω_N/ω)^n) or ``"none"``,
        per coupling (array of str, shape (P,)).
    omega_start
        ω_N, rad/s, the last data frequency (where the tail starts, continuously).
    value
        B_N per coupling, shape (P,).
    rate
        α (s) for exponential tails, n for power tails, NaN where there is none.
    note
        Why a coupling has no tail, or why its kind was changed, per coupling.
    """

    kind: NDArray
    omega_start: float
    value: NDArray
    rate: NDArray
    note: NDArray

    def _grid(self) -> NDArray:
        """Geometric grid from ω_N on which every tail is below 1e-8 of B_N at the end."""
        finite = self.rate[np.isfinite(self.rate)]
        kinds = set(self.kind.tolist())
        end = self.omega_start * 2.0
        if "power" in kinds:
            n = finite[self.kind[np.isfinite(self.rate)] == "power"].min()
            end = max(end, self.omega_start * 1e-8 ** (-1.0 / n))
        if "exponential" in kinds:
            alpha = finite[self.kind[np.isfinite(self.rate)] == "exponential"].min()
            end = max(end, self.omega_start + 18.5 / alpha)
        return self.omega_start * np.geomspace(1.0, end / self.omega_start, 800)

    def sampled(self) -> tuple[NDArray, NDArray]:
        """(ω, B) of every tail on one fine grid from ω_N, shape (G,), (G, P)."""
        w = self._grid()
        b = np.zeros((w.size, self.kind.size))
        x = w[:, None]
        with np.errstate(over="ignore", invalid="ignore"):
            exp = self.value * np.exp(-self.rate * (x - self.omega_start))
            power = self.value * (self.omega_start / x) ** self.rate
        b[:, self.kind == "exponential"] = exp[:, self.kind == "exponential"]
        b[:, self.kind == "power"] = power[:, self.kind == "power"]
        return w, b

    def cosine(self, t: ArrayLike) -> NDArray:
        """∫_{ω_N}^∞ B_tail(ω) cos(ωt) dω, shape (len(t), P)."""
        return self._transform(t, cos=True)

    def sine(self, t: ArrayLike) -> NDArray:
        """∫_{ω_N}^∞ B_tail(ω) sin(ωt) dω, shape (len(t), P)."""
        return self._transform(t, cos=False)

    def _transform(self, t: ArrayLike, cos: bool) -> NDArray:
        t = np.asarray(t, dtype=float).reshape(-1)
        out = np.zeros((t.size, self.kind.size))
        exponential = self.kind == "exponential"
        if exponential.any():  # closed form (de Haan (2022) §2.5.1)
            a, c = self.rate[exponential], self.value[exponential]
            w0, tt = self.omega_start, t[:, None]
            denominator = a**2 + tt**2
            if cos:
                out[:, exponential] = c * (a * np.cos(w0 * tt) - tt * np.sin(w0 * tt)) / denominator
            else:
                out[:, exponential] = c * (a * np.sin(w0 * tt) + tt * np.cos(w0 * tt)) / denominator
        square = (self.kind == "power") & (self.rate == 2.0)
        if square.any():  # closed form with the sine and cosine integrals
            out[:, square] = self.value[square] * _inverse_square_tail(self.omega_start, t, cos)
        power = (self.kind == "power") & ~square
        if power.any():  # exact for the interpolant on a fine geometric grid
            w, b = self.sampled()
            transform = cosine_transform if cos else sine_transform
            out[:, power] = transform(w, b[:, power], t)
        return out

    def hilbert(self, omega: ArrayLike) -> NDArray:
        """PV ∫_{ω_N}^∞ B_tail(ν)/(ν² − ω²) dν at ``omega`` (≤ ω_N), shape (len(ω), P)."""
        omega = np.asarray(omega, dtype=float).reshape(-1)
        out = np.zeros((omega.size, self.kind.size))
        some = self.kind != "none"
        if some.any():
            w, b = self.sampled()
            out[:, some] = hilbert_pv(w, b[:, some], omega)
        return out

    def area(self) -> NDArray:
        """∫_{ω_N}^∞ B_tail dω per coupling."""
        out = np.zeros(self.kind.size)
        for k, kind in enumerate(self.kind):
            if kind == "exponential":
                out[k] = self.value[k] / self.rate[k]
            elif kind == "power":
                out[k] = self.value[k] * self.omega_start / (self.rate[k] - 1.0)
        return out


def _inverse_square_tail(a: float, t: NDArray, cos: bool) -> NDArray:
    """∫_a^∞ (a/ω)² cos(ωt) dω (or sin), shape (len(t), 1), by parts:

    a² [cos(at)/a − t (π/2 − Si(at))]  and  a² [sin(at)/a − t Ci(at)]   (t ≥ 0).
    """
    tt = np.abs(t)[:, None]
    si, ci = sici(a * tt)
    if cos:
        return a * np.cos(a * tt) - a**2 * tt * (0.5 * np.pi - si)
    with np.errstate(invalid="ignore"):
        sine = a * np.sin(a * tt) - a**2 * np.where(tt > 0, tt * ci, 0.0)
    return np.sign(t)[:, None] * sine


def fit_damping_tail(
    omega: ArrayLike,
    damping: ArrayLike,
    kind: str = "auto",
    *,
    points: int | None = None,
    negligible: float = 1e-4,
) -> DampingTail:
    """Fit a decaying high-frequency tail to the last points of B(ω), per coupling.

    The tail is anchored at the last data point (continuous) and its decay rate is
    fitted by least squares to ln|B| over the last ``points`` frequencies: against ω
    for an exponential, against ln ω for a power law. ``"auto"`` takes the better of
    the two (smaller log residual). A coupling gets no tail when B has already decayed
    there (|B_N| below ``negligible`` × its peak), when B changes sign or is zero in the
    fitting window, or when the fitted curve does not decay (α ≤ 0, n ≤ 1): the reason
    is recorded in ``note``. Power laws decaying slower than ω⁻² are steepened to
    :data:`MIN_POWER`; an exponential whose area B_N/α exceeds twice that of the ω⁻²
    law, B_N ω_N (α ω_N < 1/2: a window that hardly decays, such as a noisy
    off-diagonal term), is replaced by the ω⁻² law.

    Parameters
    ----------
    omega
        Frequencies, rad/s, increasing, shape (N,).
    damping
        B, shape (N, P) (P couplings) or (N,).
    kind
        ``"exponential"``, ``"power"``, ``"auto"`` or ``"none"``.
    points
        Width of the fitting window (default: a tenth of the data, at least 4).
    """
    if kind not in TAIL_KINDS:
        raise HydroDataError(
            f"unknown tail kind {kind!r}", hint=f"use one of {', '.join(TAIL_KINDS)}"
        )
    w = np.asarray(omega, dtype=float)
    b = np.asarray(damping, dtype=float).reshape(w.size, -1)
    p = b.shape[1]
    kinds = np.full(p, "none", dtype=object)
    rates = np.full(p, np.nan)
    notes = np.full(p, "", dtype=object)
    if kind == "none":
        notes[:] = "no tail requested"
        return DampingTail(kinds, float(w[-1]), b[-1].copy(), rates, notes)
    m = points or max(4, w.size // 10)
    m = min(m, w.size)
    ww = w[-m:]
    for k in range(p):
        window = b[-m:, k]
        peak = np.abs(b[:, k]).max()
        if peak == 0 or abs(b[-1, k]) <= negligible * peak:
            notes[k] = "damping has decayed at the last frequency"
            continue
        if np.any(window == 0) or np.any(np.sign(window) != np.sign(window[-1])):
            notes[k] = "damping changes sign near the last frequency: no tail fitted"
            continue
        y = np.log(np.abs(window))
        candidates = []
        if kind in ("exponential", "auto"):
            slope, intercept = np.polyfit(ww, y, 1)
            residual = np.sum((y - (slope * ww + intercept)) ** 2)
            if -slope > 0:
                candidates.append((residual, "exponential", -slope))
        if kind in ("power", "auto"):
            lw = np.log(ww)
            slope, intercept = np.polyfit(lw, y, 1)
            residual = np.sum((y - (slope * lw + intercept)) ** 2)
            if -slope > 1:
                candidates.append((residual, "power", max(-slope, MIN_POWER)))
        if not candidates:
            notes[k] = "damping does not decay near the last frequency: no tail fitted"
            continue
        _, kinds[k], rates[k] = min(candidates)
        if kinds[k] == "exponential" and rates[k] * w[-1] < 0.5 * (MIN_POWER - 1):
            # area B_N/α over twice that of the slowest admissible power law, B_N ω_N/(n−1)
            kinds[k], rates[k] = "power", MIN_POWER
            notes[k] = "exponential decay much slower than the ω⁻² law: ω⁻² used"
    return DampingTail(kinds, float(w[-1]), b[-1].copy(), rates, notes)
