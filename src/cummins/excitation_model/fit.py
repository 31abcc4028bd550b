"""Identification of causal state-space excitation models from the data's F(ω, β).

Per heading β the time advance t_c comes from the excitation impulse response
(:func:`~cummins.excitation_model.impulse.causal_delay`: the energy of K_ex before −t_c
at most ``causality`` of its total for every DOF; where a DOF then misses its target,
the heading is fitted again with the t_c of each DOF alone and those of 1/10 and 1/100
of ``causality`` (:func:`delay_candidates`), and the first that meets every target is
kept, else the closest), or is given. Per DOF the causal response

    H(jω) = F(ω, β) e^{−jω t_c} ≈ c (jωI − a)⁻¹ b

is fitted by vector fitting with stable poles (Gustavsen & Semlyen (1999); the
relaxed pole relocation of :func:`cummins.radiation.fit.vector.relocate`, poles
reflected into the left half-plane with a relative damping of at least 5 %), residues
by linear least squares, realized in real modal form
(:func:`cummins.radiation.fit.modal.modal_realization`). Strictly proper (D = 0).

What is fitted, and the target
------------------------------
The **fitting grid** of a heading is the data frequencies, with points added by the
interpolation of :func:`~cummins.seakeeping.excitation.excitation_transfer` (Hermite,
travel phase removed: what the frequency-domain synthesis of the same sea uses) where
two data frequencies of the wave band are further apart than π/(4 t_c), so that the
phase of e^{−jωt_c} turns by at most 45° between points and the model is judged between the
data too; and ω = 0 with the long-wave limit F(0) (the hydrostatic force of a uniform
rise, :func:`~cummins.excitation_model.impulse.zero_frequency_force`) when the data
hold the hydrostatic stiffness and start above 0. The **wave band** of a DOF is where
|F| > ``band`` (1 %) of its peak. The error measure is the normalised RMS error of the
complex response over the band, as an integral over frequency,

    NRMSE = √( ∫_band |F̂(ω) − F(ω)|² dω / ∫_band |F(ω)|² dω ),

F̂ = c (jωI − a)⁻¹ b e^{jωt_c}, evaluated by the trapezoid rule on the fitting grid
(without the added ω = 0; on a uniform data grid that resolves the phase it is the
plain RMS over the data frequencies). The least-squares weights are those of the same
integral: √Δω/peak in the band, ``OUT_OF_BAND`` times that outside.

The order (states) grows 2, 4, … (by 4 while the error is above 3 times the target)
until NRMSE ≤ ``nrmse`` (default 3 %), then one state fewer is tried; the search
stops at ``max_order`` or after :data:`STALL` orders that do not lower the error by
2 %. A DOF that misses its target keeps its best fit
(the fewest states within 1 % of the lowest error) and the model's ``attrs["failures"]``
says so (``cummins fit-excitation`` exits with status 3). The floor of the error is set
by t_c: what K_ex holds before −t_c no causal model can represent (about
√``causality`` of the response); a long body in oblique waves (a ship) has a long,
two-pulse K_ex (bow and stern) that needs many states.

``method="realization"`` identifies each model instead by Kung's realization (ERA,
:func:`cummins.radiation.fit.realization.era`) of the shifted impulse response
K_ex(t − t_c), t ≥ 0, at the same orders and against the same target.

A DOF the waves of a heading do not excite (a spar's sway in head seas:
:func:`~cummins.excitation_model.impulse.excited_dofs`) gets no states.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import FitError
from cummins.excitation_model.impulse import (
    CAUSALITY,
    _check_zero_speed,
    _directions,
    causal_delay,
    causal_delays,
    excitation_irf,
    excited_dofs,
    force_on_grid,
    zero_frequency_force,
)
from cummins.excitation_model.model import DofExcitation, ExcitationModel
from cummins.radiation.fit.modal import modal_realization
from cummins.radiation.fit.vector import BlockData, Poles, _same_poles, relocate, starting_poles
from cummins.radiation.model import siso_frequency_response
from cummins.validation import in_range, positive

__all__ = [
    "METHODS",
    "NRMSE_TARGET",
    "fit_excitation",
    "fit_response",
    "fitting_grid",
    "heading_grid",
    "model_nrmse",
    "nrmse",
]

#: Identification methods: vector fitting of the response, or ERA of the impulse response.
METHODS = ("vf", "realization")
#: Default target of the normalised RMS error over the wave band (module docstring).
NRMSE_TARGET = 0.03
#: The wave band: |F| above this fraction of the DOF's peak.
BAND = 0.01
#: Default highest order (states per DOF and heading).
MAX_ORDER = 60
#: Weight of the points outside the band, relative to those inside.
OUT_OF_BAND = 0.3
#: Pole relocation iterations (at most).
ITERATIONS = 10
#: The poles are relocated on at most about this many frequencies.
RELOCATION_POINTS = 300
#: The order search stops after this many orders that do not lower the error by 2 %.
STALL = 4
#: Far from the target (error above FAR times it) the order grows by 4, else by 2.
FAR = 3.0
#: With the automatic t_c, a heading where a DOF misses its target is fitted again at
#: up to this many other advances (:func:`delay_candidates`).
MORE_DELAYS = 4

#: K_ex(t) for the automatic t_c is sampled at at most this many times (t_c to 1/2000 of
#: the span ±2π/ω_min).
DELAY_POINTS = 4000
#: The fitting grid: at most π/(PHASE_STEPS t_c) between two frequencies (45°).
PHASE_STEPS = 4


def fitting_grid(
    omega: ArrayLike, delay: float, keep: ArrayLike | None = None
) -> NDArray[np.float64]:
    """The data frequencies with points added where two are further apart than
    π/(4 t_c) (module docstring), sorted, within the data's range; with ``keep`` (a
    boolean per data frequency: the wave band) only in the intervals that touch it."""
    w = np.asarray(omega, dtype=float)
    if delay <= 0 or w.size < 2:
        return w.copy()
    inside = np.ones(w.size, dtype=bool) if keep is None else np.asarray(keep, dtype=bool)
    step = np.pi / (PHASE_STEPS * delay)
    parts = []
    for k in range(w.size - 1):
        count = int(np.ceil((w[k + 1] - w[k]) / step)) if inside[k] or inside[k + 1] else 1
        parts.append(np.linspace(w[k], w[k + 1], max(count, 1) + 1)[:-1])
    return np.r_[np.concatenate(parts), w[-1]]


def _spacing(omega: NDArray) -> NDArray[np.float64]:
    """Trapezoid weights of a grid: ∫ f dω ≈ Σ f_k Δ_k."""
    if omega.size < 2:
        return np.ones(omega.size)
    edges = np.r_[omega[0], 0.5 * (omega[1:] + omega[:-1]), omega[-1]]
    return np.diff(edges)


def nrmse(
    fitted: ArrayLike, data: ArrayLike, band: ArrayLike, omega: ArrayLike | None = None
) -> float:
    """√(∫_band |F̂ − F|² dω / ∫_band |F|² dω) by the trapezoid rule on ``omega`` (the
    plain sums over the points without it): the error measure of the module docstring."""
    f_hat, f = np.asarray(fitted), np.asarray(data)
    inside = np.asarray(band, dtype=bool)
    dw = np.ones(f.size) if omega is None else _spacing(np.asarray(omega, dtype=float))
    denominator = float(np.sum((np.abs(f) ** 2 * dw)[inside]))
    if denominator == 0:
        return 0.0
    return float(np.sqrt(np.sum((np.abs(f_hat - f) ** 2 * dw)[inside]) / denominator))


@dataclass(frozen=True)
class _Fit:
    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    error: float

    @property
    def order(self) -> int:
        return int(self.a.shape[0])


def _vector_fit(omega, values, weight, count) -> tuple[NDArray, NDArray, NDArray]:
    """(a, b, c) with ``count`` states of H ≈ Σ r/(s − p), D = 0: relaxed vector fitting
    (the poles on at most :data:`RELOCATION_POINTS` points, every k-th with its weight
    times √k; the residues on all)."""
    step = int(np.ceil(omega.size / RELOCATION_POINTS))
    rows = np.arange(0, omega.size, step)
    data = BlockData(
        (0,), ((0, 0),), omega[rows], values[None, rows], np.sqrt(step) * weight[None, rows],
        np.sqrt(step) * weight[None, rows], np.zeros(1), rows.size,
    )  # fmt: skip
    poles = starting_poles(omega[omega > 0], count)
    for _ in range(ITERATIONS):
        moved = relocate(data, poles)
        converged = _same_poles(moved, poles)
        poles = moved
        if converged:
            break
    # a real pole the relocation put at the origin would integrate: give it a decay
    floor = 1e-3 * float(omega[omega > 0].min())
    poles = Poles(np.minimum(poles.real, -floor), poles.pairs)
    phi = poles.basis(1j * omega)
    rows = np.vstack([weight[:, None] * phi.real, weight[:, None] * phi.imag])
    rhs = np.r_[weight * values.real, weight * values.imag]
    x, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
    nr = poles.real.size
    p, r = list(poles.real.astype(complex)), list(x[:nr].astype(complex))
    for k, pair in enumerate(poles.pairs):
        residue = x[nr + 2 * k] + 1j * x[nr + 2 * k + 1]
        p += [pair, np.conj(pair)]
        r += [residue, np.conj(residue)]
    return modal_realization(np.array(p), np.array(r))


def _realization(t, k, count) -> tuple[NDArray, NDArray, NDArray]:
    """(a, b, c) of Kung's realization of the samples ``k`` at ``t`` ≥ 0 (no zero at s=0)."""
    from cummins.radiation.fit.realization import era

    model = era(t, k, order=count, zero_dc=False, max_order=max(count, 1))
    return model.a, model.b, model.c


def fit_response(
    omega: ArrayLike,
    force: ArrayLike,
    delay: float,
    *,
    target: float = NRMSE_TARGET,
    band: float = BAND,
    max_order: int = MAX_ORDER,
    order: int | None = None,
    zero: complex | None = None,
    method: str = "vf",
    impulse: tuple[ArrayLike, ArrayLike] | None = None,
) -> tuple[NDArray, NDArray, NDArray, dict, str]:
    """The causal model of one DOF at one heading (module docstring).

    Parameters
    ----------
    omega, force
        The fitting grid (rad/s, > 0, increasing; :func:`fitting_grid`) and F there
        (N/m or N·m/m).
    delay
        t_c, s.
    target, band, max_order
        NRMSE target, wave band (fraction of the peak), highest order.
    order
        A fixed order instead of the search.
    zero
        F(0) to fit at ω = 0 as well (the long-wave limit), or None (``"vf"``).
    method
        ``"vf"`` or ``"realization"``; the latter needs ``impulse`` = (τ, K_ex(τ − t_c)),
        τ uniform from 0.

    Returns
    -------
    (a, b, c, metrics, note)
    """
    w = np.asarray(omega, dtype=float)
    f = np.asarray(force, dtype=complex)
    peak = float(np.abs(f).max())
    in_band = np.abs(f) > band * peak
    h = f * np.exp(-1j * w * delay)
    if method == "vf":
        weight = np.where(in_band, 1.0, OUT_OF_BAND) * np.sqrt(_spacing(w)) / peak
        w_fit, h_fit, weight_fit = w, h, weight
        if zero is not None and w.min() > 0:
            w_fit = np.r_[0.0, w]
            h_fit = np.r_[complex(zero), h]
            weight_fit = np.r_[np.sqrt(np.median(_spacing(w))) / peak, weight]

        def identify(count):
            return _vector_fit(w_fit, h_fit, weight_fit, count)
    elif method == "realization":
        if impulse is None:
            raise FitError("the realization method needs the impulse response K_ex(t)")
        tau, k = (np.asarray(v, dtype=float) for v in impulse)

        def identify(count):
            return _realization(tau, k, count)
    else:
        raise FitError(f"unknown method {method!r}; use one of {', '.join(METHODS)}")

    tried: dict[int, _Fit] = {}

    def get(count: int) -> _Fit:
        if count not in tried:
            try:
                a, b, c = identify(count)
            except FitError:
                a, b, c = np.zeros((0, 0)), np.zeros(0), np.zeros(0)
            response = siso_frequency_response(a, b, c, w)
            error = nrmse(response, h, in_band, w) if a.size else np.inf
            tried[count] = _Fit(a, b, c, error)
        return tried[count]

    if order is not None:
        chosen = get(order)
    else:
        best, stalled, count = None, 0, 2
        while count <= max_order:
            fit = get(count)
            if fit.error <= target:
                if get(count - 1).error <= target:
                    fit = get(count - 1)
                best = fit
                break
            if best is None or fit.error < 0.98 * best.error:
                best, stalled = fit, 0
            else:
                stalled += 1
                if stalled >= STALL:
                    break
            count += 2 if fit.error < FAR * target else 4
        if best is None or best.error > target:
            lowest = min(fit.error for fit in tried.values())
            best = min(
                (fit for fit in tried.values() if fit.error <= 1.01 * lowest),
                key=lambda fit: fit.order,
            )
        chosen = best
    if chosen.order == 0:
        raise FitError(f"no stable model found (method {method})")
    met = chosen.error <= target
    metrics = {
        "nrmse": chosen.error,
        "target_met": bool(met),
        "band_min": float(w[in_band].min()),
        "band_max": float(w[in_band].max()),
        "peak": peak,
        "orders_tried": len(tried),
    }
    note = ""
    if not met and order is None:
        note = (
            f"NRMSE {chosen.error:.3g} above the target {target:g} at up to {max(tried)} "
            "states: a longer time advance (smaller --causality) or a higher --max-order"
        )
    elif not met:
        note = f"NRMSE {chosen.error:.3g} above the target {target:g} at the order asked for"
    return chosen.a, chosen.b, chosen.c, metrics, note


def delay_candidates(irf, causality: float, excited) -> list[list[float]]:
    """The advances t_c tried per heading, in order: the rule's (every DOF's energy
    before −t_c at most ``causality``), then the advance of each DOF alone below it (a DOF
    whose K_ex reaches far back need not set every DOF's t_c), then those of
    ``causality``/10 and /100; at most 1 + :data:`MORE_DELAYS`."""
    per_dof = causal_delays(irf, causality, excited)
    longer = [causal_delay(irf, causality / f, excited) for f in (10.0, 100.0)]
    out = []
    for h in range(per_dof.shape[0]):
        values = per_dof[h][~np.isnan(per_dof[h])]
        first = float(values.max()) if values.size else 0.0
        shorter = sorted({float(v) for v in values if v < first}, reverse=True)
        order = [first, *shorter[:2], *(float(x[h]) for x in longer)]
        out.append(list(dict.fromkeys(order))[: 1 + MORE_DELAYS])
    return out


def heading_grid(
    ds: xr.Dataset, beta: float, delay: float, band: float = BAND
) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """(ω, F) the DOFs of one heading are fitted and judged on: the fitting grid
    (:func:`fitting_grid`, refined in the wave band of any DOF) and F there, (nω, n)."""
    data_w = np.asarray(ds.omega.values, dtype=float)
    data_f = force_on_grid(ds, np.array([beta]), data_w)[:, 0, :]
    in_band = np.any(np.abs(data_f) > band * np.abs(data_f).max(axis=0), axis=1)
    w = fitting_grid(data_w, delay, in_band)
    return w, force_on_grid(ds, np.array([beta]), w)[:, 0, :]


def model_nrmse(ds: xr.Dataset, model: ExcitationModel) -> NDArray[np.float64]:
    """The NRMSE of every (heading, DOF) of ``model`` against the data ``ds`` (zero
    speed), measured as the fit measures it (module docstring: on :func:`heading_grid`
    with the model's t_c, over the DOF's wave band of ``model.attrs["band"]``); (nβ, n),
    NaN where a DOF has no states. On the data the model was fitted to it is the
    recorded ``metrics["nrmse"]``; a difference says the data are not those."""
    ds = _check_zero_speed(ds)
    band = float(model.attrs.get("band", BAND))
    out = np.full(model.orders.shape, np.nan)
    for h, beta in enumerate(model.headings):
        w, force = heading_grid(ds, float(beta), float(model.delays[h]), band)
        fitted = model.frequency_response(w)[:, h, :]
        for d in range(len(model.dofs)):
            if model.model(h, d).order:
                f = force[:, d]
                inside = np.abs(f) > band * np.abs(f).max()
                out[h, d] = nrmse(fitted[:, d], f, inside, w)
    return out


def _fit_heading(ds, beta, heading, excited, zero, delay, options) -> list[DofExcitation]:
    """The models of every DOF at one heading, for one t_c."""
    w, force = heading_grid(ds, beta, delay, options["band"])
    impulse = None
    if options["method"] == "realization":
        dt = np.pi / (4 * float(w[-1]))
        tau = np.arange(0.0, delay + 2 * np.pi / float(w[w > 0].min()), dt)
        k = excitation_irf(ds, tau - delay, wave_direction=[beta]).values[:, 0, :]
    out = []
    for d in range(force.shape[1]):
        if not excited[d]:
            metrics = {"nrmse": 0.0, "target_met": True, "peak": float(np.abs(force[:, d]).max())}
            empty = (np.zeros((0, 0)), np.zeros(0), np.zeros(0))
            out.append(DofExcitation(d, heading, *empty, metrics, "not excited: no states"))
            continue
        f0 = None if zero is None or w[0] <= 0 else zero[d]
        if options["method"] == "realization":
            impulse = (tau, k[:, d])
        a, b, c, metrics, note = fit_response(
            w, force[:, d], delay, zero=f0, impulse=impulse, **options
        )
        out.append(DofExcitation(d, heading, a, b, c, metrics, note))
    return out


def fit_excitation(
    ds: xr.Dataset,
    wave_direction: ArrayLike | None = None,
    *,
    delay: float | Sequence[float] | None = None,
    causality: float = CAUSALITY,
    nrmse_target: float = NRMSE_TARGET,
    band: float = BAND,
    max_order: int = MAX_ORDER,
    order: int | None = None,
    method: str = "vf",
    progress: Callable[[str], None] | None = None,
) -> ExcitationModel:
    """Causal state-space models of the wave excitation, per heading and DOF.

    Module docstring: t_c from the excitation impulse response, vector fitting of
    F(ω) e^{−jωt_c} with stable poles, order against an NRMSE target over the wave band.

    Parameters
    ----------
    ds
        A ``HydroDB`` at zero forward speed with ``excitation_force``.
    wave_direction
        Directions of wave travel to model, rad (0 following seas, π head seas);
        default every heading of the data.
    delay
        t_c, s (one for all headings, or one per heading) instead of the automatic one.
    causality
        Share of the energy of K_ex allowed before −t_c (automatic t_c), in (0, 0.5).
    nrmse_target
        Target NRMSE of the complex response over the wave band, in (0, 1).
    band
        The wave band: |F| above this fraction of its peak, in (0, 1).
    max_order
        Highest number of states per DOF and heading.
    order
        Fit every DOF with this number of states (no search).
    method
        ``"vf"`` (vector fitting of the response, default) or ``"realization"`` (ERA of
        the shifted impulse response).
    progress
        Called with a short text before each heading.

    Returns
    -------
    ExcitationModel
        Stable; ``attrs`` hold the options, the per-heading t_c rule, the notes on the
        data and ``failures`` (DOFs whose NRMSE misses the target).

    Examples
    --------
    >>> import cummins, numpy as np
    >>> ds = cummins.read(cummins.demo_files() / "tanker.1")
    >>> model = fit_excitation(ds, [np.pi])
    >>> model.is_stable(), bool(model.delays[0] > 0)
    (True, True)
    """
    started = time.perf_counter()
    ds = _check_zero_speed(ds)
    in_range(causality, "causality", low=0.0, high=0.5, low_open=True, high_open=True)
    in_range(nrmse_target, "the NRMSE target", low=0.0, high=1.0, low_open=True, high_open=True)
    in_range(band, "the wave band", low=0.0, high=1.0, low_open=True, high_open=True)
    positive(max_order, "max_order", "states")
    if method not in METHODS:
        raise FitError(f"unknown method {method!r}; use one of {', '.join(METHODS)}")
    directions = _directions(ds, wave_direction)
    w = np.asarray(ds.omega.values, dtype=float)
    labels = [str(d) for d in ds.influenced_dof.values]
    force = force_on_grid(ds, directions, w)
    excited = excited_dofs(force, labels)
    zero = zero_frequency_force(ds)
    if delay is None:
        irf = excitation_irf(ds, wave_direction=directions, max_points=DELAY_POINTS)
        candidates = delay_candidates(irf, causality, excited)
        delay_rule = (
            f"automatic: the energy of K_ex(t) before -t_c is at most {causality:g} of its "
            "total for every DOF; where a DOF then misses the NRMSE target, the t_c of each "
            f"DOF alone and those of {causality / 10:g} and {causality / 100:g} are tried: "
            "the first that meets every target is kept, else the closest (then the fewest "
            "states)"
        )
        low_note = irf.attrs["low_frequency"]
    else:
        given = np.broadcast_to(np.asarray(delay, dtype=float), directions.shape).copy()
        if not np.all(np.isfinite(given)) or np.any(given < 0):
            raise FitError(f"the time advance t_c must be >= 0 s, not {delay!r}")
        candidates = [[float(x)] for x in given]
        delay_rule = "given"
        low_note = ""
    models: list[DofExcitation] = []
    failures: list[str] = []
    chosen = np.zeros(directions.size)
    options = {
        "target": nrmse_target,
        "band": band,
        "max_order": int(max_order),
        "order": order,
        "method": method,
    }
    for h, beta in enumerate(directions):
        if progress is not None:
            progress(f"heading {np.degrees(beta):g} deg")
        best = None
        for tc in dict.fromkeys(float(x) for x in candidates[h]):
            fits = _fit_heading(ds, beta, h, excited[h], zero, tc, options)
            worst = max((m.metrics["nrmse"] / nrmse_target for m in fits if m.order), default=0.0)
            score = (max(worst, 1.0), sum(m.order for m in fits))
            if best is None or score < best[0]:
                best = (score, tc, fits)
            if worst <= 1.0:
                break
        _, chosen[h], fits = best
        models.extend(fits)
        failures += [
            f"{labels[m.dof]} at {np.degrees(beta):g} deg: NRMSE {m.metrics['nrmse']:.3g} above "
            f"the target {nrmse_target:g}"
            for m in fits
            if not m.metrics["target_met"]
        ]
    delays = chosen
    notes = [line for line in [low_note] if line]
    if zero is not None and w[0] > 0:
        notes.append("fitted at omega = 0 too: the long-wave limit (hydrostatic force)")
    attrs = {
        "method": method,
        "nrmse_target": nrmse_target,
        "band": band,
        "causality": causality,
        "delay_rule": delay_rule,
        "max_order": int(max_order),
        "failures": failures,
        "data_notes": notes,
        "elapsed_s": time.perf_counter() - started,
        "omega_min": float(w.min()),
        "omega_max": float(w.max()),
    }
    for key in ("source_file", "source_format", "rho", "g", "water_depth", "axis_convention"):
        if key in ds.attrs:
            attrs[key] = ds.attrs[key]
    if "reference_point" in ds.attrs:
        attrs["reference_point"] = np.asarray(ds.attrs["reference_point"], dtype=float)
    return ExcitationModel(
        tuple(labels), directions, np.asarray(delays, float), tuple(models), attrs
    )
