"""What a fluid-memory model must do beyond the data: decay as the data's damping tail.

The data end at ω_N, the radiation damping does not: K(t) = (2/π) ∫₀^∞ B(ω) cos(ωt) dω
(Hjulstad (2004) eq. 5.15) takes B beyond ω_N from the damping tail fitted to the last
points (:func:`cummins.radiation.damping_tail.fit_damping_tail`: an exponential, a power
law no slower than ω⁻², nothing where B has decayed). The identification is held to the
same tail, so that the model and the data's K(t) agree on what lies beyond the data:

* :func:`tail_equations` — the tail sampled beyond ω_N as equations of the fit, each
  weighing as the data points it stands for at the data's own density. By Parseval's
  relation ∫₀^∞ (K̂ − K)² dt = (2/π) ∫₀^∞ (B̂ − B)² dω, an error of B beyond the data costs
  K(t) as much as the same error inside it; the integral of B beyond ω_N is part of K(0).
* :func:`damping_beyond_data` — the check of a model (after the passivity step, which
  can itself raise the damping beyond the data): its B_ii beyond ω_N must stay below the
  data's peak B_ii and have no peak of its own (:data:`PEAK_TOLERANCE`).
* :func:`impulse_r2` — R² of K(t) of the model against the data's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.arrays import LastAnswer, digest
from cummins.radiation.damping_tail import DampingTail, fit_damping_tail
from cummins.radiation.model import siso_impulse_response

#: The tail equations span ω_N … TAIL_SPAN ω_N (beyond, a rational model's damping
#: decays as ω⁻², at the rate of the slowest tail admitted).
TAIL_SPAN = 30.0
#: Number of tail equations (geometric spacing from the first, just beyond ω_N).
TAIL_POINTS = 24
TAIL_START = 1.02
#: Weight of the tail equations against the data's (1: as the data points they stand
#: for, at the data's mean spacing).
TAIL_WEIGHT = 1.0
#: The check beyond the data looks from ω_N to CHECK_SPAN ω_N (the passivity constraints
#: reach 10³ ω_N).
CHECK_SPAN = 1e3
CHECK_POINTS = 2000
#: A model's B_ii beyond the data may exceed the :func:`envelope` of the data's tail by
#: this fraction of the data's peak, and rise by as much after its largest value beyond
#: the data, before it counts as a peak of its own. (A tolerance decaying as (ω_N/ω)²
#: instead held the model so tight that the tanker's RAO error went from 0.45 to 1.15 %
#: and the supply vessel's R² of B to 0.89; the area such an excess adds is held by the
#: K(0) equation, :func:`kernel_zero_equation`.)
PEAK_TOLERANCE = 0.05


def tail_frequencies(omega_last: float) -> NDArray[np.float64]:
    """The frequencies of the tail equations beyond ``omega_last`` (rad/s)."""
    return float(omega_last) * np.geomspace(TAIL_START, TAIL_SPAN, TAIL_POINTS)


def tail_equations(
    omega: ArrayLike,
    damping: ArrayLike,
    use: ArrayLike,
    tail_omega: ArrayLike,
    added_mass: ArrayLike | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], DampingTail]:
    """The data's damping tail at ``tail_omega`` and the weight of each point.

    Parameters
    ----------
    omega, damping
        The data's frequencies (rad/s) and B of one coupling.
    use
        Which frequencies the coupling keeps: the tail starts at the last one.
    tail_omega
        Frequencies beyond the data (:func:`tail_frequencies`).
    added_mass
        A of the coupling: where a damping still rising at the last frequency turns
        (:func:`~cummins.radiation.damping_tail.fit_damping_tail`).

    Returns
    -------
    b_tail, weight, tail
        B of :func:`cummins.radiation.damping_tail.fit_damping_tail` of the kept points at
        ``tail_omega`` (zero before the tail's start, and where the data have no tail:
        decayed, or changing sign), and the weight of each equation relative to one data
        point's: √(Δω_k / δω) × :data:`TAIL_WEIGHT`, Δω_k the band the point stands for,
        δω the data's spacing where they end (the last three intervals); and the tail.
    """
    w = np.asarray(omega, dtype=float)
    b = np.asarray(damping, dtype=float)
    keep = np.asarray(use, dtype=bool)
    x = np.asarray(tail_omega, dtype=float)
    if keep.sum() < 2:
        return np.zeros(x.size), np.zeros(x.size), fit_damping_tail(w, b, "none")
    wk, bk = w[keep], b[keep]
    ak = None if added_mass is None else np.asarray(added_mass, dtype=float)[keep]
    tail = fit_damping_tail(wk, bk, added_mass=ak)
    b_tail = tail.at(x)[:, 0]
    edges = np.r_[wk[-1], np.sqrt(x[1:] * x[:-1]), x[-1] * np.sqrt(x[-1] / x[-2])]
    band = np.clip(np.diff(edges), 0.0, None)
    spacing = float(np.mean(np.diff(wk[-4:])))  # the data's density where they end
    # as sure as the damping has decayed: a damping still near its peak at the last
    # frequency leaves its continuation to the added mass (Kramers–Kronig)
    sure = certainty(tail, float(np.abs(bk).max()))
    weight = TAIL_WEIGHT * sure * np.sqrt(band / spacing) * (x > wk[-1])
    return b_tail, weight, tail


#: A damping still rising at the last frequency may peak beyond it anywhere up to
#: PLATEAU × its tail's knee, not above the tail's top; then it decays as ω⁻².
PLATEAU = 2.0


def certainty(tail: DampingTail, peak: float) -> float:
    """How sure the data's damping tail of one coupling is: 1 − |B_N|/peak (1 where the
    damping has decayed at the last frequency, 0 where it is still at its peak there)."""
    return 1.0 - min(abs(float(tail.value[0])) / peak, 1.0) if peak > 0 else 1.0


def envelope(tail: DampingTail, omega: ArrayLike, peak: float) -> NDArray[np.float64]:
    """What a model's damping beyond the data may reach at ``omega`` (rad/s ≥ ω_N), from
    the data's damping tail of one coupling and the data's ``peak``: the tail where it is
    sure (:func:`certainty`: the damping has decayed at the last frequency; the tail is
    then below the data's peak), a plateau where it is not — the tail's top (B_N, or its
    value at the knee of a damping still rising, :func:`fit_damping_tail`) up to
    :data:`PLATEAU` × the knee and ω⁻² beyond: the data do not tell how the damping turns
    there, so the model's may turn anywhere under it (a smooth peak, not the tail's
    corner) — and between the two in proportion."""
    x = np.asarray(omega, dtype=float)
    sure = certainty(tail, peak)
    knee = float(tail.omega_start)
    top = float(tail.value[0])
    if tail.kind[0] == "rising":
        knee = float(tail.knee[0])
        top = float(tail.value[0] + tail.slope[0] * (tail.knee[0] - tail.omega_start))
    end = PLATEAU * knee
    plateau = np.where(x <= end, abs(top), abs(top) * (end / np.maximum(x, end)) ** 2)
    return sure * tail.at(x)[:, 0] + (1.0 - sure) * plateau


def block_tail_equations(
    omega: ArrayLike,
    added_mass: NDArray,
    damping: NDArray,
    used: NDArray,
    elements,
    tail_omega: ArrayLike,
) -> list[tuple[NDArray[np.float64], NDArray[np.float64], DampingTail]]:
    """:func:`tail_equations` of every element (i, j) of a block (``added_mass``,
    ``damping``: (ω, n, n); ``used``: (ω, elements)), the damping matrix kept coherent
    beyond the data: a coupling's tail is its last correlation B_ij/√(B_ii B_jj) times the
    geometric mean of its DOFs' tails, so that the tail of a passive damping matrix is
    passive too (each coupling's own fit, changing sign or not, could make it indefinite,
    which the passivity step then had to undo beyond the data); its weight is the
    geometric mean of theirs. The tail object of a coupling is its own fit.

    The last block's answer is kept (its arrays read-only), by the digest of the
    arguments: a fit and its refit with A∞ estimated (:mod:`~cummins.radiation.fit.
    causal_inf`) ask for the same block's tails, which A∞ does not change."""
    w = np.asarray(omega, dtype=float)
    key = digest(
        [tuple(e) for e in elements],
        *(np.asarray(x) for x in (w, added_mass, damping, used, tail_omega)),
    )
    kept = _last_tails.get(key)
    if kept is not None:
        return list(kept)
    out = _block_tail_equations(w, added_mass, damping, used, elements, tail_omega)
    for b_tail, weight, _ in out:
        for x in (b_tail, weight):
            if isinstance(x, np.ndarray):
                x.flags.writeable = False
    return list(_last_tails.keep(key, tuple(out)))


#: The last answer of :func:`block_tail_equations` (the tails, read-only).
_last_tails = LastAnswer()


def _block_tail_equations(w, added_mass, damping, used, elements, tail_omega) -> list:
    """:func:`block_tail_equations` computed."""
    out: list = [None] * len(elements)
    diagonal = {}
    for e, (i, j) in enumerate(elements):
        if i == j:
            out[e] = tail_equations(
                w, damping[:, i, i], used[:, e], tail_omega, added_mass[:, i, i]
            )
            diagonal[i] = (e, out[e])
    for e, (i, j) in enumerate(elements):
        if i == j:
            continue
        own = tail_equations(w, damping[:, i, j], used[:, e], tail_omega, added_mass[:, i, j])
        if i not in diagonal or j not in diagonal or not used[:, e].any():
            out[e] = own
            continue
        (_, (b_i, w_i, _)), (_, (b_j, w_j, _)) = diagonal[i], diagonal[j]
        last = int(np.flatnonzero(used[:, e])[-1])
        scale = np.sqrt(abs(damping[last, i, i] * damping[last, j, j]))
        rho = float(np.clip(damping[last, i, j] / scale, -1.0, 1.0)) if scale > 0 else 0.0
        out[e] = (rho * np.sqrt(np.abs(b_i * b_j)), np.sqrt(w_i * w_j), own[2])
    return out


#: Weight of the K(0) equation of a diagonal element: 1 weighs an error of K(0) as a
#: uniform error of B over 0 … ω_N of the same area weighs in all of its damping
#: equations together.
KERNEL_WEIGHT = 1.0


def kernel_zero_form(poles) -> NDArray[np.float64]:
    """The linear form of K(0) in the coefficients of an element (poles of
    :class:`~cummins.radiation.fit.vector.Poles`): K(s) = Σ x p/(s − p) + Σ [(a + jb) p/(s − p)
    + c.c.] (Σ R_k = 0), so K(0⁺) = Σ x p + Σ 2 (a Re p − b Im p)."""
    form = np.zeros(poles.count)
    nr = poles.real.size
    form[:nr] = poles.real
    form[nr::2], form[nr + 1 :: 2] = 2 * poles.pairs.real, -2 * poles.pairs.imag
    return form


def kernel_zero_equation(data, e: int) -> tuple[float, float] | None:
    """(weight, K(0) of the data) of element ``e`` of a block's data
    (:class:`~cummins.radiation.fit.vector.BlockData`), a diagonal one with the data's
    K(t): K(0) = (2/π) ∫₀^∞ B dω holds the damping beyond the data (its tail) too, the
    area a model that decays too slowly there overshoots (issue 31: the supply vessel's
    roll, K(0) 3.0·10⁸ against 7.7·10⁷). The weight: :data:`KERNEL_WEIGHT` /
    ((2/π) ω_N σ_B), σ_B the spread of the element's damping, times the share of ∫B dω
    that lies in the data (K(0) is only as sure as the tail it holds: the PEND hull's
    sway, whose damping is still 65 % of its peak at the last frequency, kept its motion
    error at 6.7 % with the full weight); None off the diagonal or without the data's K(t)."""
    i, j = data.elements[e]
    if i != j or data.kernel is None or data.time is None or data.time[0] != 0.0:
        return None
    use = data.used[:, e]
    spread = float(np.std(data.damping[use, i, i])) if use.any() else 0.0
    if spread <= 0:
        return None
    w = data.omega[: data.n_data][use]
    inside = float(np.trapezoid(np.r_[0.0, data.damping[use, i, i]], np.r_[0.0, w]))
    beyond = float(data.tails[e].area()[0]) if data.tails is not None else 0.0
    share = inside / (inside + beyond) if inside + beyond > 0 else 0.0
    weight = KERNEL_WEIGHT * max(share, 0.0) / ((2.0 / np.pi) * float(w[-1]) * spread)
    return weight, float(data.kernel[e, 0])


@dataclass(frozen=True)
class BeyondData:
    """A model's damping beyond the data, of one DOF (:func:`damping_beyond_data`).

    Attributes
    ----------
    ratio
        max of the model's B_ii beyond ω_N over the data's max B_ii.
    omega
        Where the model's B_ii beyond ω_N is largest, rad/s.
    excess
        The largest excess of the model's B_ii over the :func:`envelope` of the data's
        damping tail, over the data's max B_ii (0 when it stays under it).
    excess_omega
        Where, rad/s (NaN without one).
    rise
        After the model's largest B_ii beyond ω_N: the largest rise of its B_ii above its
        lowest value since, over the data's max B_ii (a peak of its own, 0 when it only
        decays from there).
    peak_omega
        Where that rise peaks, rad/s (NaN without one).
    """

    ratio: float
    omega: float
    excess: float
    excess_omega: float
    rise: float
    peak_omega: float

    def ok(self, tolerance: float = PEAK_TOLERANCE) -> bool:
        """Under the envelope of the data's tail and no peak of its own, within
        ``tolerance`` of the data's peak (for data whose damping decays at the last
        frequency: below the data's peak)."""
        return max(self.excess, self.rise) <= tolerance

    def describe(self, label: str, omega_last: float) -> str:
        """One line: what the model does beyond the data."""
        where = f"beyond the data's last frequency ({omega_last:.4g} rad/s)"
        if self.excess >= self.rise:
            return (
                f"{label}: the model's damping {where} exceeds the data's damping tail at "
                f"{self.excess_omega:.4g} rad/s by {self.excess:.2g} of the data's peak "
                f"(allowed {PEAK_TOLERANCE:g}; it reaches {self.ratio:.3g}× the data's peak "
                f"at {self.omega:.4g} rad/s)"
            )
        return (
            f"{label}: the model's damping peaks again {where}, {self.rise:.2g} of the "
            f"data's peak above its lowest value, at {self.peak_omega:.4g} rad/s"
        )


def check_frequencies(omega_last: float) -> NDArray[np.float64]:
    """The frequencies of the check beyond the data (ω_N … :data:`CHECK_SPAN` ω_N)."""
    return float(omega_last) * np.geomspace(1.0, CHECK_SPAN, CHECK_POINTS)


def damping_beyond_data(
    b_model: ArrayLike,
    omega: ArrayLike,
    data_peak: float,
    tail: DampingTail | None = None,
    limit: NDArray | None = None,
) -> BeyondData:
    """How the model's damping ``b_model`` at ``omega`` (beyond the data, increasing,
    from ω_N: :func:`check_frequencies`) compares with the data's peak ``data_peak`` and
    with the :func:`envelope` of the data's damping ``tail`` (optional; ``limit``: that
    envelope at ``omega``, when known)."""
    b = np.asarray(b_model, dtype=float)
    w = np.asarray(omega, dtype=float)
    scale = float(data_peak) if data_peak > 0 else 1.0
    top = int(np.argmax(b))
    excess, excess_omega = 0.0, float("nan")
    if tail is not None:
        over = b - (envelope(tail, w, scale) if limit is None else limit)
        k = int(np.argmax(over))
        if over[k] > 0:
            excess, excess_omega = float(over[k] / scale), float(w[k])
    rise, _ = rise_after_top(b)
    where = int(np.argmax(rise))
    return BeyondData(
        float(b[top] / scale),
        float(w[top]),
        excess,
        excess_omega,
        float(rise[where] / scale),
        float(w[where]) if rise[where] > 0 else float("nan"),
    )


def rise_after_top(b: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """A peak of its own of the damping ``b`` beyond the data (on :func:`check_frequencies`),
    as :class:`BeyondData` measures it: at each point after the largest value of ``b``, its
    rise above the lowest value since (0 at and before the largest value), and the index of
    that lowest value (its first point; the point itself before the largest value). For a
    given position of the largest value, ``rise ≤ c`` at every point is the set of linear
    inequalities b_k − b_m ≤ c (top ≤ m ≤ k), a broken one met at its lowest m
    (:class:`cummins.radiation.fit.motion_refinement.BeyondBounds`)."""
    b = np.asarray(b, dtype=float)
    top = int(np.argmax(b))
    after = b[top:]
    low = np.minimum.accumulate(after)
    rise = np.zeros(b.size)
    rise[top:] = after - low
    low_at = np.arange(b.size)
    lower = np.r_[True, after[1:] < low[:-1]]  # where a new lowest value is first reached
    low_at[top:] = top + np.maximum.accumulate(np.where(lower, np.arange(after.size), 0))
    return rise, low_at


def block_beyond_data(block, data) -> dict[int, BeyondData]:
    """:func:`damping_beyond_data` of each diagonal element of a fitted block
    (:class:`~cummins.radiation.fit.vector.PoleResidueBlock`) against its data
    (:class:`~cummins.radiation.fit.vector.BlockData`), keyed by DOF (model index)."""
    grid, limits = beyond_limits(data)
    k = block.element_response(grid).real
    out = {}
    for e, (i, j) in enumerate(block.elements):
        if i != j:
            continue
        peak, limit = limits[e]
        tail = None if data.tails is None else data.tails[e]
        out[i] = damping_beyond_data(k[:, e], grid, peak, tail, limit)
    return out


def beyond_limits(data) -> tuple[NDArray, dict]:
    """The check frequencies beyond a block's data and, per diagonal element, the data's
    peak damping and the :func:`envelope` of its tail there (None without tails), the same
    for every fit of the block: computed once (``data.cache``)."""
    found = data.cache.get("beyond")
    if found is None:
        grid = check_frequencies(float(data.omega[data.n_data - 1]))
        limits = {}
        for e, (i, j) in enumerate(data.elements):
            if i == j:
                peak = float(np.abs(data.damping[data.used[:, e], i, i]).max(initial=0.0))
                scale = peak if peak > 0 else 1.0
                tail = None if data.tails is None else data.tails[e]
                limits[e] = (peak, None if tail is None else envelope(tail, grid, scale))
        found = data.cache["beyond"] = (grid, limits)
    return found


#: The bound the passivity step puts on the damping beyond the data: the
#: :func:`envelope` of the data's tail plus this fraction of the data's peak (half the
#: check's tolerance, room for the frequencies between those constrained).
BOUND_TOLERANCE = 0.5 * PEAK_TOLERANCE


class TailBounds:
    """Where a diagonal element's damping beyond the data exceeds the :func:`envelope` of
    the data's tail by more than :data:`BOUND_TOLERANCE` of the data's peak, as linear
    constraints of the passivity step
    (:func:`cummins.radiation.fit.block_passivity.enforce_passivity`): called with a block
    of ``data``, the list of (g, q, v, scale) with g the linear form of −B_ii(ω) in the
    element's coefficients, q = cap − B (< 0) its current value, v the unit vector of the
    DOF and the data's peak as scale; the worst point of each band where the bound is
    broken. The check grid, the linear forms of the poles there and each element's cap
    are computed once for the poles (which one enforcement does not move).

    It holds the check's first clause only (:meth:`BeyondData.ok`: under the envelope);
    the second, no peak of its own, is linear too (:func:`rise_after_top`) and the motion
    refinement holds it (:class:`~cummins.radiation.fit.motion_refinement.BeyondBounds`).
    Held here as well (its broken bands as these, at BOUND_TOLERANCE or at the check's
    PEAK_TOLERANCE), no block the order search makes passive fails the check, but the
    38 cases score worse: the NEMOH two bodies 209 → 214 states and 3 → 4 failures (the
    peak beyond the data traded for passivity's cost to R² of roll's A and B), the
    AQWA PEND hull 47 → 55 states at BOUND_TOLERANCE (BENCHMARKS.md, the passivity step's
    bound beyond the data, 2026-12-06)."""

    def __init__(self, data):
        self.data = data
        self._poles = None
        self._caps: tuple = ()

    def _prepare(self, block) -> tuple:
        grid, limits = beyond_limits(self.data)
        forms = np.real(1j * grid[:, None] * block.poles.kept_basis(1j * grid))
        caps = []
        for e, (i, j) in enumerate(block.elements):
            if i != j:
                continue
            peak, limit = limits[e]
            if peak > 0:
                caps.append((e, i, peak, limit + BOUND_TOLERANCE * peak))
        return forms, caps

    def __call__(self, block) -> list[tuple[NDArray, float, NDArray, float]]:
        if self.data.tails is None:
            return []
        if block.poles is not self._poles:
            self._poles, self._caps = block.poles, self._prepare(block)
        forms, caps = self._caps
        where = {d: k for k, d in enumerate(block.dofs)}
        out = []
        for e, i, peak, cap in caps:
            room = cap - forms @ block.coefficients[e]
            broken = room < 0
            if not broken.any():
                continue
            unit = np.zeros(len(block.dofs))
            unit[where[i]] = 1.0
            edges = np.flatnonzero(np.diff(np.concatenate([[0], broken, [0]]).astype(int)))
            for first, stop in zip(edges[::2], edges[1::2], strict=True):
                # the worst point and five across the band
                band = np.arange(first, stop)
                spread = band[np.linspace(0, band.size - 1, 5).astype(int)]
                for k in np.unique(np.concatenate([[band[np.argmin(room[band])]], spread])):
                    out.append((-forms[k], float(room[k]), unit, peak))
        return out


#: Most points of the time grid of the R² of K(t) a fit is judged by: the step
#: π/(4 ω_max) of the default grid over the fit's own K(t) span, coarsened beyond (500
#: points passed the Capytaine OSWEC's sway at 0.900 where the scoreboard's full
#: resolution gives 0.894; 20 000, the COER's at 80 rad/s, took 3 s).
FINE_KERNEL_POINTS = 2000


def fine_time_grid(time: ArrayLike, omega_max: float) -> NDArray[np.float64]:
    """Times (s) from 0 to the end of ``time`` at the step π/(4 ω_max) of the default
    grid (:func:`cummins.radiation.retardation.default_time_grid`), at most
    :data:`FINE_KERNEL_POINTS`."""
    end = float(np.asarray(time, dtype=float)[-1])
    step = max(np.pi / (4.0 * omega_max), end / (FINE_KERNEL_POINTS - 1))
    return np.arange(0.0, end + 0.5 * step, step)


def fine_kernel_metrics(kernel: ArrayLike, model, time: ArrayLike, modal=None) -> dict[str, float]:
    """``r2_kernel``, ``kernel_zero`` and ``kernel_zero_data`` of a diagonal term: the
    data's K(t) ``kernel`` at ``time`` (:func:`fine_time_grid`) against the impulse
    response of its ``model`` (a SISO view: ``a``, ``b``, ``c``; ``modal``: the
    :func:`~cummins.radiation.model.modal_form` of its ``a`` when known)."""
    kernel = np.asarray(kernel, dtype=float)
    fitted = np.asarray(siso_impulse_response(model.a, model.b, model.c, time, modal))
    return {
        "r2_kernel": impulse_r2(kernel, fitted),
        "kernel_zero": float(fitted[0]),
        "kernel_zero_data": float(kernel[0]),
    }


def impulse_r2(kernel: ArrayLike, model: ArrayLike) -> float:
    """R² of the model's K(t) against the data's
    (:func:`cummins.radiation.fit.frequency.r_squared`)."""
    from cummins.radiation.fit.frequency import r_squared

    return r_squared(np.asarray(kernel, dtype=float), np.asarray(model, dtype=float))
