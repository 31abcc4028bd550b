"""High-frequency tails of the radiation damping B(ω) beyond the last data frequency.

The retardation function K(t) = (2/π) ∫₀^∞ B(ω) cos(ωt) dω (Hjulstad (2004) eq. 5.15)
and the Kramers–Kronig integral (2/π) PV ∫₀^∞ B(ν)/(ν² − ω²) dν (Hjulstad (2004)
eq. 5.23) need B beyond the last frequency ω_N. :func:`fit_damping_tail` fits, per
coupling, a decaying continuation anchored at the last data point: an exponential
B_N e^{−α(ω−ω_N)}, whose cosine and sine transforms are known in closed form (de Haan
(2022) §2.5.1), or a power law B_N (ω_N/ω)^n, in closed form for n = 2 (sine and cosine
integrals) and otherwise integrated exactly on a fine geometric grid. A finite-order
radiation model has Re K(jω) ~ ω⁻² at high frequency, so slower power laws are steepened
to :data:`MIN_POWER`. A damping still rising at the last frequency (its peak beyond the
data) is continued along its trend to a knee, then as ω⁻² (``"rising"``), the knee chosen
by the Kramers–Kronig consistency of the data's added mass with it. The same tail is the
one a fitted model must follow beyond the data (:mod:`cummins.radiation.fit.tail`). The
tail's share of ∫B dω is reported by
:func:`cummins.radiation.retardation.retardation_diagnostics` because K(0) depends on it.
:mod:`cummins.radiation.retardation` re-exports these names.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

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
        ``"exponential"`` (B_N e^{−α(ω−ω_N)}), ``"power"`` (B_N (ω_N/ω)^n), ``"rising"``
        (B_N + s (ω − ω_N) up to the knee ω_k, then B_k (ω_k/ω)²: damping still rising at
        the last frequency) or ``"none"``, per coupling (array of str, shape (P,)).
    omega_start
        ω_N, rad/s, the last data frequency (where the tail starts, continuously).
    value
        B_N per coupling, shape (P,).
    rate
        α (s) for exponential tails, n for power tails (2 for rising ones), NaN where
        there is none.
    note
        Why a coupling has no tail, or why its kind was changed, per coupling.
    knee, slope
        ω_k (rad/s) and s of the rising tails, NaN for the others (None: no rising tail).
    """

    kind: NDArray
    omega_start: float
    value: NDArray
    rate: NDArray
    note: NDArray
    knee: NDArray | None = None
    slope: NDArray | None = None

    def _knees(self) -> NDArray:
        """ω_k per coupling: the knee of a rising tail, ω_N for the others."""
        if self.knee is None:
            return np.full(self.kind.size, self.omega_start)
        rising = self.kind == "rising"
        return np.where(rising, self.knee, self.omega_start)

    def _top(self) -> NDArray:
        """B at the knee per coupling (B_N but for rising tails)."""
        if self.slope is None:
            return self.value.astype(float)
        rising = self.kind == "rising"
        gain = np.where(rising, self.slope * (self._knees() - self.omega_start), 0.0)
        return self.value + gain

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
        knees = self._knees()[self.kind == "rising"]
        if knees.size:
            end = max(end, float(knees.max()) * 1e4)
        grid = self.omega_start * np.geomspace(1.0, end / self.omega_start, 800)
        return np.union1d(grid, knees)  # the knees on the grid: exact interpolants

    def at(self, omega: ArrayLike) -> NDArray:
        """B of every tail at ``omega`` (rad/s), shape (len(ω), P): zero before ω_N and
        where a coupling has no tail."""
        x = np.asarray(omega, dtype=float).reshape(-1, 1)
        b = np.zeros((x.shape[0], self.kind.size))
        beyond = x >= self.omega_start
        knee, top = self._knees(), self._top()
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            exp = self.value * np.exp(-self.rate * (x - self.omega_start))
            power = self.value * (self.omega_start / x) ** self.rate
            slope = np.zeros(self.kind.size) if self.slope is None else self.slope
            rising = np.where(
                x <= knee, self.value + slope * (x - self.omega_start), top * (knee / x) ** 2
            )
        for kind, values in (("exponential", exp), ("power", power), ("rising", rising)):
            chosen = self.kind == kind
            b[:, chosen] = np.where(beyond, values[:, chosen], 0.0)
        return b

    def sampled(self) -> tuple[NDArray, NDArray]:
        """(ω, B) of every tail on one fine grid from ω_N, shape (G,), (G, P)."""
        w = self._grid()
        return w, self.at(w)

    def cosine(
        self, t: ArrayLike, columns: ArrayLike | None = None, *, node_form: bool = True
    ) -> NDArray:
        """∫_{ω_N}^∞ B_tail(ω) cos(ωt) dω, shape (len(t), P), or of the couplings
        ``columns`` (indices) alone: the same numbers (the power tails' grid stays that
        of all); ``node_form`` as in :func:`cosine_transform`."""
        return self._transform(t, cos=True, columns=columns, node_form=node_form)

    def sine(self, t: ArrayLike) -> NDArray:
        """∫_{ω_N}^∞ B_tail(ω) sin(ωt) dω, shape (len(t), P)."""
        return self._transform(t, cos=False)

    def _transform(
        self, t: ArrayLike, cos: bool, columns: ArrayLike | None = None, node_form: bool = True
    ) -> NDArray:
        t = np.asarray(t, dtype=float).reshape(-1)
        every = np.arange(self.kind.size)
        which = every if columns is None else every[np.asarray(columns, dtype=int)]
        kinds, rates, values = self.kind[which], self.rate[which], self.value[which]
        out = np.zeros((t.size, which.size))
        exponential = kinds == "exponential"
        if exponential.any():  # closed form (de Haan (2022) §2.5.1)
            a, c = rates[exponential], values[exponential]
            w0, tt = self.omega_start, t[:, None]
            denominator = a**2 + tt**2
            if cos:
                out[:, exponential] = c * (a * np.cos(w0 * tt) - tt * np.sin(w0 * tt)) / denominator
            else:
                out[:, exponential] = c * (a * np.sin(w0 * tt) + tt * np.cos(w0 * tt)) / denominator
        square = (kinds == "power") & (rates == 2.0)
        if square.any():  # closed form with the sine and cosine integrals
            out[:, square] = values[square] * _inverse_square_tail(self.omega_start, t, cos)
        rising = kinds == "rising"
        if rising.any():  # exact: the linear rise, then ω⁻² from the knee
            transform = _cosine(node_form) if cos else sine_transform
            knee, top = self._knees()[which], self._top()[which]
            for k in np.flatnonzero(rising):
                segment = np.array([self.omega_start, knee[k]])
                ends = np.array([values[k], top[k]])
                if knee[k] > self.omega_start:
                    out[:, k] = transform(segment, ends, t)
                out[:, k] += top[k] * _inverse_square_tail(knee[k], t, cos)[:, 0]
        power = (kinds == "power") & ~square
        if power.any():  # exact for the interpolant on a fine geometric grid
            w, b = self.sampled()
            transform = _cosine(node_form) if cos else sine_transform
            out[:, power] = transform(w, b[:, which][:, power], t)
        return out

    def hilbert(self, omega: ArrayLike, columns: ArrayLike | None = None) -> NDArray:
        """PV ∫_{ω_N}^∞ B_tail(ν)/(ν² − ω²) dν at ``omega`` (≤ ω_N), shape (len(ω), P), or
        of the couplings ``columns`` (indices) alone (on the grid of all)."""
        omega = np.asarray(omega, dtype=float).reshape(-1)
        every = np.arange(self.kind.size)
        which = every if columns is None else every[np.asarray(columns, dtype=int)]
        out = np.zeros((omega.size, which.size))
        some = self.kind[which] != "none"
        if some.any():
            w, b = self.sampled()
            out[:, some] = hilbert_pv(w, b[:, which[some]], omega)
        return out

    def area(self) -> NDArray:
        """∫_{ω_N}^∞ B_tail dω per coupling."""
        out = np.zeros(self.kind.size)
        for k, kind in enumerate(self.kind):
            if kind == "exponential":
                out[k] = self.value[k] / self.rate[k]
            elif kind == "power":
                out[k] = self.value[k] * self.omega_start / (self.rate[k] - 1.0)
            elif kind == "rising":
                knee, top = self._knees()[k], self._top()[k]
                out[k] = 0.5 * (self.value[k] + top) * (knee - self.omega_start) + top * knee
        return out


def _cosine(node_form: bool):
    """:func:`cosine_transform` with its ``node_form`` set."""
    return lambda x, f, y: cosine_transform(x, f, y, node_form=node_form)


def kramers_kronig_integral(
    omega: ArrayLike,
    damping: ArrayLike,
    added_mass: ArrayLike,
    tail: str = "auto",
    columns: ArrayLike | None = None,
) -> NDArray:
    """(2/π) PV ∫₀^∞ B(ν)/(ν² − ω²) dν at the frequencies ``omega`` (rad/s, increasing) of
    the damping B (shape (N, P)): the piecewise-linear B from B(0) = 0 and its tail
    (:func:`fit_damping_tail` of kind ``tail``, with the ``added_mass`` A(ω), (N, P)), exact
    (Hjulstad (2004) eq. 5.23); shape (N, P), or (N, len(columns)) of the couplings
    ``columns`` alone (the tails fitted to all: the same numbers). A(ω) less it is
    Ogilvie's A∞ at each ω."""
    w = np.asarray(omega, dtype=float)
    b = np.asarray(damping, dtype=float).reshape(w.size, -1)
    fitted = fit_damping_tail(w, b, tail, added_mass=added_mass)
    if columns is not None:
        b = b[:, np.asarray(columns, dtype=int)]
    x, f = np.r_[0.0, w], np.vstack([np.zeros((1, b.shape[1])), b])
    total = hilbert_pv(x, f, w) + fitted.hilbert(w, columns)
    return (2.0 / np.pi) * total


def _inverse_square_tail(a: float, t: NDArray, cos: bool) -> NDArray:
    """∫_a^∞ (a/ω)² cos(ωt) dω (or sin), shape (len(t), 1), by parts:

    a² [cos(at)/a − t (π/2 − Si(at))]  and  a² [sin(at)/a − t Ci(at)]   (t ≥ 0).
    """
    tt = np.abs(t)[:, None]
    from scipy.special import sici  # on use: 0.1 s to import

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
    added_mass: ArrayLike | None = None,
) -> DampingTail:
    """Fit a decaying high-frequency tail to the last points of B(ω), per coupling.

    The tail is anchored at the last data point (continuous) and its decay rate is
    fitted by least squares to ln|B| over the last ``points`` frequencies: against ω
    for an exponential, against ln ω for a power law. ``"auto"`` takes the better of
    the two (smaller log residual). A coupling gets no tail when B has already decayed
    there (|B_N| below ``negligible`` × its peak), or when B changes sign or is zero in
    the fitting window: the reason is recorded in ``note``. A power law that decays
    slower than ω⁻² is steepened to the ω⁻² law (:data:`MIN_POWER`, a finite-order
    model's rate); an exponential whose area B_N/α exceeds twice that of the ω⁻² law,
    B_N ω_N (α ω_N < 1/2: a window that hardly decays, such as a noisy off-diagonal
    term), is replaced by the ω⁻² law too.

    Where the fitted curve does not decay (α ≤ 0, n ≤ 1: B still rising at the last
    frequency, its peak beyond the data) and B_N is at least :data:`RISING_MIN` of the
    peak (below, no tail: noise on a decayed damping), the damping must decay beyond it, at a
    rate the damping alone does not tell: it is continued along its trend (the slope s of a
    straight line through the window, |B| not falling: s ≥ 0 for a positive B, ≤ 0 for a
    negative coupling: the tail of −B is minus that of B) up to a knee ω_k, then decays as ω⁻²
    (``"rising"``; ω_k = ω_N is the ω⁻² law from the last point). The added mass tells
    where: A(ω) − A∞ is the Kramers–Kronig transform of B over all frequencies
    (Hjulstad (2004) eq. 5.23), so with ``added_mass`` the knee among
    :data:`RISE_KNEES` × ω_N that makes the data most consistent is taken — the one whose
    per-frequency estimates of A∞ (Ogilvie's, over the upper half of the frequencies)
    spread least — or no tail, when that is more consistent still (a rise that is the
    data's error). Without it, ω_k = ω_N.

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
    added_mass
        A(ω) of the same couplings, shape (N, P) or (N,): chooses where a damping still
        rising at the last frequency turns (above).
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
    slopes = np.full(p, np.nan)
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
        if not candidates and abs(b[-1, k]) < RISING_MIN * peak:
            notes[k] = "damping does not decay near the last frequency but is small there: no tail"
            continue
        if not candidates:
            # still rising (or flat) at the last frequency: continued along its trend to
            # a knee (chosen below), then ω⁻²
            kinds[k], rates[k] = "rising", MIN_POWER
            # |B| not falling: the trend of B's own sign (a coupling may be negative)
            sign = float(np.sign(window[-1]))
            slopes[k] = sign * max(sign * float(np.polyfit(ww, window, 1)[0]), 0.0)
            notes[k] = "damping still rising at the last frequency: continued to a knee, then ω⁻²"
            continue
        _, kinds[k], rates[k] = min(candidates)
        if kinds[k] == "exponential" and rates[k] * w[-1] < 0.5 * (MIN_POWER - 1):
            # area B_N/α over twice that of the slowest admissible power law, B_N ω_N/(n−1)
            kinds[k], rates[k] = "power", MIN_POWER
            notes[k] = "exponential decay much slower than the ω⁻² law: ω⁻² used"
    knees = np.where(kinds == "rising", w[-1], np.nan)
    rising = np.flatnonzero(kinds == "rising")
    if rising.size and added_mass is not None:
        a = np.asarray(added_mass, dtype=float).reshape(w.size, -1)
        knees[rising] = _consistent_knees(w, b[:, rising], a[:, rising], slopes[rising])
    for k in rising:
        if np.isnan(knees[k]):  # the added mass is most consistent without a tail
            kinds[k], rates[k] = "none", np.nan
            notes[k] = "damping does not decay at the last frequency, but its added mass is "
            notes[k] += "most consistent with none beyond it: no tail"
        else:
            notes[k] += f" at {knees[k]:.4g} rad/s"
    return DampingTail(kinds, float(w[-1]), b[-1].copy(), rates, notes, knees, slopes)


#: A damping that does not decay at the last frequency is continued (``"rising"``) only
#: when it is still at least this fraction of its peak there: below, the rise is noise
#: on a damping that has decayed (WAMIT's cylinder heave, 0.25 % of its peak at 21 rad/s
#: and rising: continued, K(0) 4 % above NEMOH's for the same body).
RISING_MIN = 0.1
#: Where a damping still rising at the last frequency may turn, × ω_N (1: at once).
RISE_KNEES = (1.0, 1.1, 1.25, 1.5, 1.75, 2.0)
#: ... but not above this multiple of the last value (in magnitude): the data do not tell
#: more.
RISE_LIMIT = 2.0


def _consistent_knees(w: NDArray, b: NDArray, a: NDArray, slopes: NDArray) -> NDArray:
    """The knee (rad/s) of each rising tail that makes A(ω) most consistent with B(ω):
    the spread (standard deviation) of Ogilvie's A∞ = A(ω) − (2/π) PV∫₀^∞ B/(ν² − ω²) dν
    over the upper half of the frequencies (at least five, the last left out: the
    integral is singular there for a truncated B) is smallest (:func:`fit_damping_tail`);
    NaN where no tail at all is more consistent (a rise that is the data's error: the
    tanker's yaw, irregular frequencies up to its last one, whose Ogilvie A∞ went from
    1.27 to 2.07 % off WAMIT's row with a rising tail).
    The tail's part is exact: the linear rise by :func:`hilbert_pv`, the ω⁻² decay from
    the knee k in closed form, ∫_k^∞ (k/ν)²/(ν² − ω²) dν = (k/ω)² [ln((k + ω)/(k − ω))/(2ω)
    − 1/k] for ω < k."""
    upper = w >= 0.5 * w[-1]
    upper[-6:] = True
    upper[-1] = False
    y = w[upper]
    x = np.r_[0.0, w]
    inner = hilbert_pv(x, np.vstack([np.zeros((1, b.shape[1])), b]), y)
    best = np.std(a[upper] - (2.0 / np.pi) * inner, axis=0)  # no tail at all: NaN
    knees = np.full(b.shape[1], np.nan)
    for factor in RISE_KNEES:
        knee = factor * w[-1]
        top = b[-1] + slopes * (knee - w[-1])
        tail = (
            top
            * (knee / y[:, None]) ** 2
            * (np.log((knee + y[:, None]) / (knee - y[:, None])) / (2 * y[:, None]) - 1 / knee)
        )
        if knee > w[-1]:
            tail = tail + hilbert_pv(np.array([w[-1], knee]), np.vstack([b[-1], top]), y)
        estimate = a[upper] - (2.0 / np.pi) * (inner + tail)
        spread = np.std(estimate, axis=0)
        better = (np.abs(top) <= RISE_LIMIT * np.abs(b[-1])) & (spread < best)
        best = np.where(better, spread, best)
        knees = np.where(better, knee, knees)
    return knees
