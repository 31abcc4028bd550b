"""Finding and removing bad frequencies in hydrodynamic data (off by default, always reported).

Panel methods without irregular-frequency removal produce spikes and negative damping
near the eigenfrequencies of the interior problem (WAMIT tanker above 3.4 rad/s);
strip-theory codes can return an inconsistent lowest frequency (ShipX supply vessel at
0.105 rad/s). :func:`find_suspect_frequencies` detects both kinds; nothing is changed
until the user calls :func:`remove_frequencies` (or the ``--remove-irregular`` options
of the command line), and every removal is written to the dataset's ``history``.

Detection, per diagonal term of A(ω) and B(ω):

* negative damping below −1 % of the term's peak (smaller negative values are noise
  around zero where the damping has decayed; ``cummins check`` still reports them);
* a spike: the value differs from the straight line through its two neighbours by more
  than ``spike_threshold`` of the curve's range and by more than ``mad_factor`` times
  the median such difference, *and* in the opposite direction from its neighbours'
  own differences (a curved but smooth curve gives differences of one sign). End
  points, tested against the line through the next two points, must be off by four
  times ``spike_threshold``. Points are flagged one at a time, worst first, and the
  test is repeated without them, so that a bad point does not make its neighbours
  look bad. A point is judged only where its neighbours lie within
  :data:`SPIKE_SPAN` (25 %) of its frequency, and the lowest frequency always: on
  coarser sampling a sound peak looks like a spike.

:func:`sharp_features` tells the suspect points of a real, sharp resonance (A(ω) follows
B(ω) through them: Kramers–Kronig) from those of an irregular frequency.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.arrays import at_frequency, column_medians
from cummins.errors import HydroDataError
from cummins.hydrodb import add_history, dof_matrix, validate
from cummins.radiation.damping_tail import kramers_kronig_integral
from cummins.radiation.infinite_frequency import bridged_couplings, with_coupling_values
from cummins.radiation.retardation import causal_limits

#: Negative diagonal damping below this fraction of its peak makes a frequency suspect.
NEGATIVE_DAMPING = 0.01


@dataclass(frozen=True)
class SuspectFrequency:
    """A frequency whose data look wrong, and why.

    Attributes
    ----------
    omega
        rad/s.
    quantity
        The worst quantity there, e.g. ``"radiation_damping[Heave, Heave]"``.
    reason
        In plain language, with the size of the problem.
    score
        Size of the deviation as a fraction of the curve's range (or of the damping peak
        for negative damping).
    """

    omega: float
    quantity: str
    reason: str
    score: float


def _leave_one_out_residual(w: NDArray, x: NDArray) -> NDArray:
    """x_k minus the straight line through its neighbours (end points: extrapolated);
    ``x`` (N,) or (N, curves)."""
    r = np.empty_like(x)
    if w.size < 3:
        return np.zeros_like(x)
    inner = slice(1, -1)
    frac = ((w[inner] - w[:-2]) / (w[2:] - w[:-2])).reshape((-1,) + (1,) * (x.ndim - 1))
    r[inner] = x[inner] - (x[:-2] + frac * (x[2:] - x[:-2]))
    r[0] = x[0] - (x[1] + (x[2] - x[1]) * (w[0] - w[1]) / (w[2] - w[1]))
    r[-1] = x[-1] - (x[-2] + (x[-2] - x[-3]) * (w[-1] - w[-2]) / (w[-2] - w[-3]))
    return r


#: A point is tested for a spike only when the neighbours its line runs through lie
#: within this fraction of its frequency: on coarser sampling (the WAMIT OSWEC's periods
#: 8, 7, 6, 5, 4, 3, 2, 1 s) a sound peak looks like a spike, and each point taken out
#: would make its neighbours look like the next one. The lowest frequency is always
#: tested (as an end point: four times the threshold), where A and B flatten out and a
#: strip-theory or low-frequency panel result is often wrong (ShipX's 0.105 rad/s).
SPIKE_SPAN = 0.25


def _judged_points(w: NDArray) -> NDArray[np.bool_]:
    """Which points of ``w`` are sampled finely enough around them (:data:`SPIKE_SPAN`)
    for the straight line of :func:`_leave_one_out_residual` to judge them."""
    if w.size < 3:
        return np.zeros(w.size, dtype=bool)
    span = np.empty_like(w)
    span[1:-1] = w[2:] - w[:-2]
    span[0], span[-1] = 0.0, w[-1] - w[-3]
    return span <= SPIKE_SPAN * np.abs(w)


def _diagonal_curves(ds: xr.Dataset) -> list[tuple[str, NDArray]]:
    curves = []
    labels = [str(d) for d in ds.influenced_dof.values]
    for name in ("added_mass", "radiation_damping"):
        x = dof_matrix(ds, name)
        diag = np.diagonal(x, axis1=1, axis2=2)
        size = np.abs(diag).max(axis=0)
        for i, label in enumerate(labels):
            if size[i] > 1e-6 * size.max():
                curves.append((f"{name}[{label}, {label}]", diag[:, i]))
    return curves


def find_suspect_frequencies(
    ds: xr.Dataset, *, spike_threshold: float = 0.05, mad_factor: float = 10.0
) -> tuple[SuspectFrequency, ...]:
    """Frequencies where the diagonal added mass or damping look wrong.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed.
    spike_threshold
        Minimum deviation from the neighbours, as a fraction of the curve's range.
    mad_factor
        Minimum deviation as a multiple of the median deviation of the curve.

    Returns
    -------
    tuple of SuspectFrequency
        Sorted by frequency; empty for clean data.
    """
    if "forward_speed" in ds.dims:
        raise HydroDataError("select one forward speed first", hint="ds.sel(forward_speed=...)")
    w = ds.omega.values
    curves = _diagonal_curves(ds)
    found: dict[float, SuspectFrequency] = {}
    for quantity, x in curves:
        if quantity.startswith("radiation_damping"):
            peak = np.abs(x).max()
            for k in np.flatnonzero(x < -NEGATIVE_DAMPING * peak):
                score = float(-x[k] / peak)
                _keep_worst(
                    found,
                    SuspectFrequency(
                        float(w[k]),
                        quantity,
                        f"negative damping, {x[k] / peak:.3g} of its peak",
                        score,
                    ),
                )
    keep = np.ones(w.size, dtype=bool)
    names = [quantity for quantity, _ in curves]
    values = np.stack([x for _, x in curves], axis=1) if curves else np.zeros((w.size, 0))
    for _ in range(max(1, w.size // 3)):
        idx = np.flatnonzero(keep)
        if idx.size < 4 or not names:
            break
        # every curve at once: its worst point, then the worst curve (the first on a tie)
        x = values[idx]
        r = _leave_one_out_residual(w[idx], x)
        spread = x.max(axis=0) - x.min(axis=0)  # np.ptp's numbers
        flat, size, sign = spread == 0, np.abs(r), np.sign(r)
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = size / spread
        rel[size <= mad_factor * column_medians(size)] = 0.0
        isolated = np.ones(r.shape, dtype=bool)  # opposite to both neighbours' residuals
        isolated[1:-1] = (sign[1:-1] != sign[:-2]) & (sign[1:-1] != sign[2:])
        rel[~isolated] = 0.0
        rel[[0, -1]] = np.where(rel[[0, -1]] > 4 * spike_threshold, rel[[0, -1]], 0.0)
        rel[~_judged_points(w[idx])] = 0.0
        rel[:, flat] = 0.0
        j = np.argmax(rel, axis=0)
        best = rel[j, np.arange(rel.shape[1])]
        best[flat | ~(best > spike_threshold)] = -np.inf
        c = int(np.argmax(best))
        if best[c] == -np.inf:
            break
        score, k, quantity = float(best[c]), int(idx[j[c]]), names[c]
        signed = float(r[j[c], c] / spread[c])
        keep[k] = False
        _keep_worst(
            found,
            SuspectFrequency(
                float(w[k]),
                quantity,
                f"spike: {abs(signed):.0%} of the curve's range off the line through "
                "its neighbours",
                score,
            ),
        )
    return tuple(sorted(found.values(), key=lambda s: s.omega))


@dataclass(frozen=True)
class IrregularFrequencySpan:
    """The frequencies, from ``omega_start`` to the last, where an irregular frequency
    spoils a DOF's added mass beyond its spikes (:func:`irregular_frequency_spans`).

    Attributes
    ----------
    dof
        DOF label.
    omega_start
        First frequency of the span, rad/s; the data below it are a causal pair.
    departure
        Median departure of Ogilvie's A∞ estimate over the span, as a fraction of the
        DOF's scale (:func:`cummins.radiation.retardation.causal_limits`).
    suspects
        The DOF's suspect frequencies inside the span, rad/s.
    """

    dof: str
    omega_start: float
    departure: float
    suspects: tuple[float, ...]

    def description(self) -> str:
        """What the data do there, in one sentence (without the DOF)."""
        return (
            f"A(ω) departs from what B(ω) implies from {self.omega_start:.4g} rad/s to the "
            f"last frequency (Kramers–Kronig: Ogilvie's A∞ estimate {self.departure:.0%} of "
            f"its scale off), around {len(self.suspects)} suspect frequencies: an irregular "
            "frequency spoils more than its spikes, and no causal model follows the data there"
        )


def irregular_frequency_spans(
    ds: xr.Dataset, suspects: Mapping[str, DofSuspects] | None = None
) -> tuple[IrregularFrequencySpan, ...]:
    """The DOFs whose added mass an irregular frequency spoils to the end of the data.

    An irregular frequency of a panel method without irregular-frequency removal puts a
    pole's shape in A(ω) and a spike in B(ω); the spike test
    (:func:`find_suspect_frequencies`) finds the points near it, but A(ω) can stay off
    for the rest of the data (the ITI barge from WAMIT: heave 34 % off what B(ω) implies
    from 2.8 to 5 rad/s, spikes at 3.1–3.9 rad/s only). A span is reported where
    A(ω) departs from the Kramers–Kronig transform of B(ω) to the last frequency
    (:func:`cummins.radiation.retardation.causal_limits`) *and* holds suspect frequencies
    of that DOF's own curves: a departure without spikes near the end of the data is
    more likely the unknown damping tail (data that end before B has decayed).

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed.
    suspects
        Per DOF label, the suspects of its own curves (:func:`suspects_by_dof`) when the
        caller has them already; else :func:`find_suspect_frequencies` is run on the
        DOFs that depart.

    Returns
    -------
    tuple of IrregularFrequencySpan
        In DOF order; empty for data without such spans.
    """
    out = []
    for label, (start, departure) in causal_limits(ds).items():
        if suspects is None:
            own = find_suspect_frequencies(ds.sel(influenced_dof=[label], radiating_dof=[label]))
        else:
            own = suspects[label].suspects if label in suspects else ()
        inside = tuple(float(x.omega) for x in own if x.omega >= start)
        if inside:
            out.append(IrregularFrequencySpan(label, start, departure, inside))
    return tuple(out)


#: A group of suspect points is a sharp feature of the data when Ogilvie's A∞ estimate
#: around it, with the points kept, departs from its median by at most this fraction of
#: its departure with the points bridged (:func:`sharp_features`) ...
FEATURE_RATIO = 0.5
#: ... and bridging them moves the estimate by more than this fraction of the DOF's
#: largest added mass (below it, the points matter to no estimate).
FEATURE_MIN_DEPARTURE = 0.01


def sharp_features(ds: xr.Dataset, suspects: Sequence[SuspectFrequency]) -> tuple[float, ...]:
    """The suspect frequencies of one DOF that are a sharp feature of its data, not an
    error: its A(ω) follows its B(ω) through them (Kramers–Kronig).

    A resonance between the hulls or columns of a platform, or of the water in a moonpool
    or a gap, gives B(ω) a narrow peak and A(ω) the matching swing; sampled at a few per
    cent of ω they look like spikes (:func:`find_suspect_frequencies`). An irregular
    frequency of a panel method looks the same but breaks the Kramers–Kronig relation
    between A and B. Each group of two or more adjacent suspect points of the DOF's own
    curves (negative damping excepted) is judged by Ogilvie's A∞ estimate at each
    frequency, A(ω) − (2/π) PV∫ B(ν)/(ν² − ω²) dν, the same constant at every frequency
    for a causal pair (Hjulstad (2004) eq. 5.23): over the group and a neighbour on each
    side, its largest departure from its median with the group's points kept against the
    same with them bridged (linear interpolation; the DOF's other suspect points bridged
    in both). A group that keeps the estimate flatter by :data:`FEATURE_RATIO` is a
    feature. The corpus's WAMIT MHK RM1 platform: surge damping peaks at 2.1 rad/s (0.58
    of its maximum, five points flagged) and the estimate stays within 4.5 % of its scale
    through it, 27 % off with the points bridged; the AQWA PEND hull's heave spikes at
    10.7–11.3 rad/s (an irregular frequency): 8.5 % off with them, 1.8 % without.

    A resonance sampled by a few points (a moonpool's piston mode on a 0.1 rad/s grid)
    fails that test at its own points, where the piecewise-linear B(ω) misses the peak's
    shape, but its damping still explains A(ω) on its flanks: a group where B(ω) peaks
    (above the line through its neighbours) and the estimate on the :data:`FLANK` sound
    points on each side departs by at most :data:`FLANK_RATIO` of its departure with the
    group bridged, itself above :data:`FLANK_MIN_DEPARTURE` of the scale, is a feature
    too. Measured: the piston mode of a ring with a moonpool (inner radius 3 m, outer
    5 m, 1 m draft, Capytaine on 0.1 rad/s; 4 points flagged) 0.6 % of its scale with the
    points kept, 23 % bridged; of the irregular frequencies in the corpus, none passes
    (the Capytaine COER's at 33.9 rad/s: 0.7 %, 2.1 %; the WAMIT sphere's surge at
    6.2 rad/s, a dip of B: 0.6 %, 6 %).

    Parameters
    ----------
    ds
        A ``HydroDB`` of one DOF (its diagonal term) at one forward speed.
    suspects
        That DOF's suspect frequencies (:func:`find_suspect_frequencies` of ``ds``).

    Returns
    -------
    tuple of float
        The suspect frequencies (rad/s) that belong to a sharp feature.
    """
    return tuple(x for group in sharp_resonances(ds, suspects) for x in group)


def sharp_resonances(
    ds: xr.Dataset, suspects: Sequence[SuspectFrequency]
) -> tuple[tuple[float, ...], ...]:
    """:func:`sharp_features` group by group: the frequencies (rad/s) of each group of
    adjacent suspect points that is a sharp resonance of the data."""
    w = ds.omega.values
    if w.size < 6 or ds.sizes["influenced_dof"] != 1:
        return ()
    suspect, spike = np.zeros(w.size, dtype=bool), np.zeros(w.size, dtype=bool)
    for s in suspects:
        at = at_frequency(w, s.omega)
        suspect |= at
        if not s.reason.startswith("negative"):
            spike |= at
    index = np.flatnonzero(spike)
    groups = [g for g in np.split(index, np.flatnonzero(np.diff(index) > 1) + 1) if g.size > 1]
    a = ds.added_mass.values.reshape(w.size)
    b = ds.radiation_damping.values.reshape(w.size)
    scale = float(np.abs(a).max())
    if not groups or suspect.all() or scale == 0.0:
        return ()

    def estimate(bridged: NDArray[np.bool_]) -> NDArray[np.float64]:
        """Ogilvie's A∞ at each frequency with the ``bridged`` points bridged, less its
        median (the numbers of
        :func:`~cummins.radiation.infinite_frequency.added_mass_inf_per_frequency`, on arrays)."""
        kept = ~bridged
        a_kept, b_kept = np.interp(w, w[kept], a[kept]), np.interp(w, w[kept], b[kept])
        curve = a_kept - kramers_kronig_integral(w, b_kept[:, None], a_kept[:, None])[:, 0]
        return curve - np.median(curve[~suspect])

    without = estimate(suspect)
    background = np.interp(w, w[~suspect], b[~suspect])  # B bridged over every suspect point
    features: list[tuple[float, ...]] = []
    for group in groups:
        window = np.arange(max(group[0] - 1, 0), min(group[-1] + 2, w.size))
        others = suspect.copy()
        others[group] = False
        with_group = estimate(others)
        kept = float(np.abs(with_group[window]).max())
        bridged = float(np.abs(without[window]).max())
        if bridged > FEATURE_MIN_DEPARTURE * scale and kept <= FEATURE_RATIO * bridged:
            features.append(tuple(float(x) for x in w[group]))
            continue
        flanks = _flanks(group, suspect)
        if not flanks.size or float(np.sum(b[group] - background[group])) <= 0.0:
            continue  # a dip of B is no resonance's (the WAMIT sphere's surge at 6.2 rad/s)
        kept = float(np.abs(with_group[flanks]).max())
        bridged = float(np.abs(without[flanks]).max())
        if bridged > FLANK_MIN_DEPARTURE * scale and kept <= FLANK_RATIO * bridged:
            features.append(tuple(float(x) for x in w[group]))
    return tuple(features)


#: A group of suspect points that fails the test of its own points is still a resonance
#: when, on its flanks (the :data:`FLANK` sound points on each side), Ogilvie's estimate
#: departs by at most FLANK_RATIO of its departure with the group bridged ...
FLANK_RATIO = 0.25
#: ... that departure with the group bridged is above this fraction of the DOF's largest
#: added mass (the peak carries much of the DOF's damping) ...
FLANK_MIN_DEPARTURE = 0.05
#: ... and B(ω) peaks there (above the line through the flanks, on the whole).
FLANK = 2


def _flanks(group: NDArray[np.intp], suspect: NDArray[np.bool_]) -> NDArray[np.intp]:
    """The :data:`FLANK` points on each side of ``group`` that are not suspect."""
    left = [i for i in range(group[0] - 1, -1, -1) if not suspect[i]][:FLANK]
    right = [i for i in range(group[-1] + 1, suspect.size) if not suspect[i]][:FLANK]
    return np.array(left + right, dtype=np.intp)


#: A sharp resonance is kept in the fit when the motions depend on it: with its points
#: bridged (the DOF's couplings there), the motion RAOs of the data move by more than
#: this fraction of a motion's peak (2 % of critical damping on the DOFs with restoring,
#: the wave excitation at 4 headings: :func:`cummins.radiation.fit.motion.motion_sensitivity`).
#: Measured: a moonpool's piston mode (``tests/data/moonpool_capytaine.nc``) 32 %, the
#: semisubmersible's heave feature at 1.2–1.4 rad/s 0.02 % (left out, as before: putting
#: it back cost its R² of B 0.995 → 0.991 for no RAO gain).
RESONANCE_MOTION = 0.005
#: Without the inertia and the restoring to judge the motions by, a sharp resonance is
#: kept when its damping peak is at least this fraction of the DOF's largest.
RESONANCE_PEAK = 0.5


@dataclass(frozen=True)
class SharpResonance:
    """A group of suspect points of one DOF that is a sharp resonance of the data
    (:func:`sharp_resonances`), and whether the fit keeps it.

    Attributes
    ----------
    omega
        Its suspect frequencies, rad/s.
    damping_share
        Its largest |B_ii| over the DOF's largest.
    motion_change
        The largest change of a motion RAO, relative to that motion's peak, when the
        resonance is bridged (:data:`RESONANCE_MOTION`); None without the inertia and
        the restoring.
    kept
        Whether the fit keeps its points (the motions depend on it; else it stays out
        of the fit, as a broadband model does not follow a peak of a few points, and
        in Ogilvie's A∞).
    at_end
        Whether it runs to the data's last frequency (then never kept).
    """

    omega: tuple[float, ...]
    damping_share: float
    motion_change: float | None
    kept: bool
    at_end: bool = False

    def description(self, label: str) -> str:
        """One sentence: where it is, why it is physics, whether the fit keeps it."""
        where = f"{min(self.omega):.4g}–{max(self.omega):.4g} rad/s"
        text = (
            f"a piston/gap resonance at {where} in {label} (a sharp resonance of the data, "
            "not an irregular frequency: its points look like spikes, but A(ω) follows B(ω) "
            "through them, Kramers–Kronig)"
        )
        if self.kept and self.motion_change is not None:
            return text + (
                f", kept: without it the motions move by {self.motion_change:.1%} of their peak"
            )
        if self.kept:
            return text + (
                f", kept: its damping peak is {self.damping_share:.2g} of the DOF's largest "
                "(no inertia and restoring to judge the motions by)"
            )
        left = "left out of the fit, kept for A∞'s estimate"
        change = self.motion_change
        if self.at_end:  # its "peak" may be where the data end
            moved = (
                ""
                if change is None
                else f" (without it the motions move by {change:.1%} of their peak)"
            )
            return text + f"; it runs to the data's last frequency: {left}{moved}"
        if change is not None:
            return text + f"; the motions hardly depend on it ({change:.2%} of their peak): {left}"
        return text + f"; its damping peak is {self.damping_share:.2g} of the DOF's largest: {left}"


@dataclass(frozen=True)
class DofSuspects:
    """The suspect frequencies of one DOF's own curves (:func:`suspects_by_dof`).

    Attributes
    ----------
    suspects
        :func:`find_suspect_frequencies` of the DOF alone.
    resonances
        Those of them that are a sharp resonance of the data, not an error
        (:func:`sharp_resonances`), group by group.
    """

    suspects: tuple[SuspectFrequency, ...]
    resonances: tuple[SharpResonance, ...] = ()

    @property
    def features(self) -> tuple[float, ...]:
        """The suspect frequencies (rad/s) that belong to a sharp resonance."""
        return tuple(x for r in self.resonances for x in r.omega)

    @property
    def kept(self) -> tuple[float, ...]:
        """The suspect frequencies (rad/s) of the sharp resonances the fit keeps."""
        return tuple(x for r in self.resonances if r.kept for x in r.omega)


#: Datasets :func:`suspects_by_dof` has judged, each with what it found.
Judged = Sequence[tuple[xr.Dataset, Mapping[str, "DofSuspects"]]]


def suspects_by_dof(ds: xr.Dataset, judged: Judged = ()) -> dict[str, DofSuspects]:
    """Per DOF label, the suspect frequencies of its own curves and those that are a sharp
    resonance, with whether the fit keeps it (what the fit leaves out of each DOF's
    couplings, and ``cummins check`` reports).

    A sharp resonance is kept when the motions depend on it (:data:`RESONANCE_MOTION`),
    or, without the inertia and restoring, when its damping peak is a large part of the
    DOF's (:data:`RESONANCE_PEAK`) — but never one that runs to the data's last
    frequency: its "peak" is where the data end, and A(ω) follows B(ω) through it only
    with the damping tail assumed beyond them (the NEMOH two cubes' body2 pitch at
    1.56–2 rad/s: kept, it took the fit to 1.95 rad/s, where body1's sway fell to R² 0.56
    from 0.995 and body2's yaw was modelled at −5.3).

    ``judged``: datasets already judged, with what was found; for one ``identical`` to
    ``ds`` that is the answer (``cummins check`` judges each forward speed's data once,
    for its checks and the fit it prepares: ~30–50 ms each time).
    """
    for data, found in judged:
        if data is ds or data.identical(ds):
            return dict(found)
    labels = [str(d) for d in ds.influenced_dof.values]
    found, groups = {}, {}
    curves = ds[["added_mass", "radiation_damping"]]  # all the tests read of each DOF
    radiating = [str(d) for d in ds.radiating_dof.values]
    for d, label in enumerate(labels):  # by position: sel's selection, a quarter the time
        one = curves.isel(influenced_dof=[d], radiating_dof=[radiating.index(label)])
        found[label] = find_suspect_frequencies(one)
        groups[label] = sharp_resonances(one, found[label])
    if not any(groups.values()):
        return {label: DofSuspects(found[label]) for label in labels}
    motions = _motion_change(ds, groups)
    w = ds.omega.values
    b = np.abs(np.diagonal(dof_matrix(ds, "radiation_damping"), axis1=1, axis2=2))
    out = {}
    for d, label in enumerate(labels):
        resonances = []
        for k, group in enumerate(groups[label]):
            at = np.isin(w, group)
            share = float(b[at, d].max() / b[:, d].max()) if b[:, d].max() > 0 else 0.0
            change = motions.get((label, k))
            kept = change > RESONANCE_MOTION if change is not None else share >= RESONANCE_PEAK
            at_end = bool(max(group) >= w[-1])  # not a resonance inside the data
            resonances.append(SharpResonance(group, share, change, kept and not at_end, at_end))
        out[label] = DofSuspects(found[label], tuple(resonances))
    return out


def _motion_change(ds: xr.Dataset, groups) -> dict[tuple[str, int], float]:
    """Per (DOF label, group index) of ``groups``, the largest change of the data's
    motion RAOs, relative to each motion's peak, when that group's points are bridged
    in the DOF's couplings (A and B; the excitation as it is); empty without the inertia
    and the restoring."""
    from cummins.radiation.fit.motion import motion_sensitivity  # the fit imports repair

    if "forward_speed" in ds.dims or "inertia_matrix" not in ds:
        return {}
    sensitivity = motion_sensitivity(ds)
    if sensitivity is None or not np.all(np.isfinite(sensitivity.motions)):
        return {}
    labels = [str(d) for d in ds.influenced_dof.values]
    w = ds.omega.values
    a, b = dof_matrix(ds, "added_mass"), dof_matrix(ds, "radiation_damping")
    rows = sensitivity.compared_frequencies()
    out = {}
    for label, found in groups.items():
        d = labels.index(label)
        for k, group in enumerate(found):
            keep = np.ones((w.size, len(labels)), dtype=bool)
            keep[np.isin(w, group), d] = False
            ab, bb = bridged_couplings(a, w, keep), bridged_couplings(b, w, keep)
            memory = bb[rows] + 1j * w[rows, None, None] * ab[rows]
            out[(label, k)] = sensitivity.error_of(memory, np.zeros(a.shape[1:]))[0]
    return out


def _keep_worst(found: dict[float, SuspectFrequency], item: SuspectFrequency) -> None:
    if item.omega not in found or item.score > found[item.omega].score:
        found[item.omega] = item


def remove_frequencies(ds: xr.Dataset, omega: ArrayLike, *, reason: str = "") -> xr.Dataset:
    """A copy of ``ds`` without the given frequencies (matched to 1e-9 relative).

    The removal and its ``reason`` are written to ``history``. At least three
    frequencies must remain.
    """
    targets = np.atleast_1d(np.asarray(omega, dtype=float))
    w = ds.omega.values
    drop = np.zeros(w.size, dtype=bool)
    for target in targets:
        match = np.isclose(w, target, rtol=1e-9, atol=0)
        if not match.any():
            raise HydroDataError(f"frequency {target:g} rad/s is not in the data")
        drop |= match
    if (~drop).sum() < 3:
        raise HydroDataError("removing these frequencies would leave fewer than three")
    out = ds.isel(omega=np.flatnonzero(~drop))
    out.attrs = dict(ds.attrs)
    listed = ", ".join(f"{x:.4g}" for x in w[drop])
    add_history(
        out,
        f"removed {int(drop.sum())} frequencies ({listed} rad/s)"
        + (f": {reason}" if reason else ""),
    )
    return validate(out)


def limit_frequency_range(
    ds: xr.Dataset, omega_min: float | None = None, omega_max: float | None = None
) -> xr.Dataset:
    """A copy of ``ds`` keeping only omega_min ≤ ω ≤ omega_max (recorded in ``history``)."""
    w = ds.omega.values
    lo = -np.inf if omega_min is None else omega_min
    hi = np.inf if omega_max is None else omega_max
    keep = (w >= lo) & (w <= hi)
    if keep.sum() < 3:
        if omega_min is None and omega_max is None:
            raise HydroDataError(
                f"fewer than three frequencies: the data hold {w.size} "
                f"({', '.join(f'{x:.4g}' for x in w)} rad/s)",
                path=ds.attrs.get("source_file"),
                hint="fitting, K(t) and A∞ need the solver run at many frequencies "
                "(typically 50–200 from well below the first resonance to where B has decayed)",
            )
        raise HydroDataError(
            f"fewer than three frequencies between {lo:g} and {hi:g} rad/s",
            path=ds.attrs.get("source_file"),
            hint=f"the data cover {w[0]:.4g}–{w[-1]:.4g} rad/s",
        )
    if keep.all():
        return ds
    out = ds.isel(omega=np.flatnonzero(keep))
    out.attrs = dict(ds.attrs)
    add_history(out, f"frequency range limited to {w[keep][0]:.4g}–{w[keep][-1]:.4g} rad/s")
    return out


def remove_suspect_frequencies(
    ds: xr.Dataset, *, above_first: bool = False, **detection
) -> tuple[xr.Dataset, tuple[SuspectFrequency, ...]]:
    """Detect (:func:`find_suspect_frequencies`) and remove suspect frequencies.

    Parameters
    ----------
    above_first
        Also drop every frequency above the first suspect one that lies above the
        frequency of peak damping: irregular frequencies of panel methods get denser
        towards high frequencies, and the data between them are rarely trustworthy.
    **detection
        Passed to :func:`find_suspect_frequencies`.

    Returns
    -------
    (dataset, suspects)
    """
    suspects = find_suspect_frequencies(ds, **detection)
    if not suspects:
        return ds, suspects
    w = ds.omega.values
    drop = {s.omega for s in suspects}
    reason = "suspect (spikes or negative damping)"
    if above_first:
        b = np.abs(
            np.diagonal(
                ds.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").values,
                axis1=1,
                axis2=2,
            )
        )
        w_peak = float(np.median(w[np.argmax(b, axis=0)]))
        high = [s.omega for s in suspects if s.omega > w_peak]
        if high:
            drop |= set(w[w >= min(high)].tolist())
            reason += f"; all frequencies from {min(high):.4g} rad/s up (irregular frequencies)"
    return remove_frequencies(ds, sorted(drop), reason=reason), suspects


#: :func:`nearest_passive_damping` leaves a frequency alone where the DOF-scaled damping
#: matrix has an eigenvalue below −PASSIVE_LIMIT (a fifth of the diagonal's peak): data
#: that far from passive are not noise, and projecting them would invent data (the
#: OSWEC's base body, fixed to the seabed in WEC-Sim: −3.7).
PASSIVE_LIMIT = 0.2


@dataclass(frozen=True)
class PassiveDamping:
    """What :func:`nearest_passive_damping` changed: the frequencies (rad/s) whose damping
    matrix was made positive semi-definite, the most negative DOF-scaled eigenvalue
    there and its frequency, and the frequencies left alone (beyond
    :data:`PASSIVE_LIMIT`)."""

    changed: tuple[float, ...]
    worst: float
    worst_omega: float
    left: tuple[float, ...]

    def note(self) -> str | None:
        """One line for the fit's notes (None when nothing changed)."""
        if not self.changed:
            return None
        text = (
            f"B(ω) not positive semi-definite at {len(self.changed)} frequencies (worst "
            f"eigenvalue {self.worst:.3g} of the DOF-scaled peak, {self.worst_omega:.4g} "
            "rad/s): fitted to its nearest passive part"
        )
        if self.left:
            text += f"; {len(self.left)} frequencies further from passive left as they are"
        return text


def nearest_passive_damping(
    ds: xr.Dataset, pairs, *, limit: float = PASSIVE_LIMIT
) -> tuple[xr.Dataset, PassiveDamping]:
    """The data with B(ω) replaced, frequency by frequency, by its nearest positive
    semi-definite matrix where it is not one (Higham (1988)).

    Radiation damping is positive semi-definite at every frequency (the energy radiated
    by any motion is positive: Newman (1977) ch. 6); solvers return slightly indefinite
    matrices where a coupling is nearly rank one (a vertical cylinder's sway–roll about
    its waterline: B₂₄² ≈ B₂₂ B₄₄, and HAMS's B₄₄ falls below B₂₄²/B₂₂ by numerical
    noise). A passive model cannot follow such data and its passivity step, moving
    every coupling of the block, costs far more than the data's error. Only the
    ``pairs`` (i, j) are projected — the couplings a model will hold; the others are
    zero in it and stay as they are here; a DOF coupled to none is left to the suspect
    test, its negative damping a bad point rather than noise — after the DOF scaling of
    the passivity check (s_i = 1/√max_ω |B_ii|): the negative eigenvalues of
    S ½(B + Bᵀ) S, the unmodelled pairs set to zero, are set to zero and the
    antisymmetric part is kept. Frequencies further from passive than ``limit`` are
    left alone.

    One projection, not the nearest matrix with that sparsity: the projection fills the
    unmodelled pairs, which are written back as they were, so the modelled pairs alone
    are passive up to a small remainder (HAMS cylinder: the smallest scaled eigenvalue
    −0.093 before, −0.0008 after; NEMOH two cubes −0.048, −9·10⁻⁷), which the fit's
    passivity step takes up.

    Parameters
    ----------
    ds
        Canonical dataset at one speed.
    pairs
        Index pairs (i, j), i ≤ j, of the couplings to project (those with i == j are
        the DOFs).
    limit
        Most negative DOF-scaled eigenvalue that is projected.

    Returns
    -------
    (dataset, report)
        ``report`` is a :class:`PassiveDamping`.
    """
    b = dof_matrix(ds, "radiation_damping")
    w = ds.omega.values
    n = b.shape[1]
    mask = np.zeros((n, n), dtype=bool)
    for i, j in pairs:
        mask[i, j] = mask[j, i] = True
    # a DOF coupled to none is left to the suspect test: its negative damping is a bad
    # point (an irregular frequency), not the noise of a nearly rank-one coupling
    dofs = np.flatnonzero(np.diag(mask) & (mask.sum(axis=1) > 1))
    peak = np.array([np.nanmax(np.abs(b[:, i, i])) for i in dofs])
    if dofs.size < 2 or not np.all(peak > 0):
        return ds, PassiveDamping((), 0.0, float("nan"), ())
    scale = 1.0 / np.sqrt(peak)
    sub = np.ix_(dofs, dofs)
    inside = mask[sub]
    out = b.copy()
    changed, worst, worst_omega = [], 0.0, float("nan")
    matrices = b[:, dofs][:, :, dofs]
    finite = np.flatnonzero(np.all(np.isfinite(matrices), axis=(1, 2)))
    symmetric = np.where(inside, 0.5 * (matrices + np.swapaxes(matrices, 1, 2)), 0.0)
    values, vectors = np.zeros((0, dofs.size)), np.zeros((0, dofs.size, dofs.size))
    if finite.size:  # every frequency at once (LAPACK matrix by matrix all the same)
        values, vectors = np.linalg.eigh(symmetric[finite] * np.outer(scale, scale))
    negative = np.flatnonzero(values[:, 0] < 0)
    far = values[negative, 0] < -limit
    left = [float(x) for x in w[finite[negative[far]]]]
    near = negative[~far]  # every projected frequency at once: the numbers of one by one
    if near.size:
        k, lam, vec = finite[near], values[near], vectors[near]
        matrix = matrices[k]
        nearest = (vec * np.maximum(lam, 0.0)[:, None, :]) @ np.swapaxes(vec, 1, 2)
        nearest = nearest / np.outer(scale, scale)
        at = np.ix_(k, dofs, dofs)
        out[at] = np.where(inside, nearest + 0.5 * (matrix - np.swapaxes(matrix, 1, 2)), matrix)
        changed = [float(x) for x in w[k]]
        first = int(np.argmin(lam[:, 0]))  # the first of the worst, as a strict < kept it
        worst, worst_omega = float(lam[first, 0]), float(w[k[first]])
    if not changed:
        return ds, PassiveDamping((), 0.0, float("nan"), tuple(left))
    result = with_coupling_values(ds, "radiation_damping", out)  # an assign's, faster
    return result, PassiveDamping(tuple(changed), worst, worst_omega, tuple(left))
