"""Identification of the fluid memory: one call fits every significant coupling.

:func:`fit_radiation` turns a ``HydroDB`` into a :class:`~cummins.radiation.RadiationModel`:

1. **Data**: frequencies flagged by :func:`cummins.repair.find_suspect_frequencies`
   (irregular-frequency spikes, negative damping, an inconsistent first frequency) are
   left out of the fit, and with them every frequency above the first irregular one
   (:func:`cummins.repair.remove_suspect_frequencies` with ``above_first``), unless
   ``exclude_suspect`` is false; so is everything outside ``omega_min``…``omega_max``.
   What was left out is recorded.
2. **Couplings**: the significant ones (:func:`cummins.retardation.significant_couplings`);
   negligible couplings (relative threshold) are left out and reported; a symmetric
   pair K_ij = K_ji is fitted once, to the symmetric part of the data, and used twice.
3. **A∞**: the solver's ω = ∞ row when present; otherwise estimated jointly with each
   coupling's model (``"fit"``, Perez & Fossen's idea), regularised towards Ogilvie's
   Kramers–Kronig estimate within its spread — A(ω) and B(ω) on a truncated frequency
   range hardly constrain A∞ by themselves (the R² of the fit changes by 10⁻⁴ when A∞
   moves by 3 % on the tanker), the causality relation does — or taken from Ogilvie's
   relation alone (``"ogilvie"``).
4. **Each coupling**: frequency-domain fit (:mod:`cummins.fit.frequency`) or time-domain
   realization of K(t) (:mod:`cummins.fit.realization`, Kung/ERA or Prony), at the
   smallest order whose R² of A and of B reaches the target (default 0.99), up to
   ``max_order``; users can fix the order of any coupling. Every returned model is
   stable; diagonal models are required to be positive real.
5. **Metrics** per coupling (:mod:`cummins.fit.metrics`) and the MIMO assembly.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from dataclasses import replace

import numpy as np
import xarray as xr

from cummins.check import copied_dofs
from cummins.errors import FitError, HydroDataError
from cummins.fit.frequency import FrequencyFit, fit_frequency_domain, pruned_poles
from cummins.fit.metrics import coupling_metrics
from cummins.fit.realization import modal_realization
from cummins.radiation import CouplingModel, RadiationModel, symmetric_couplings
from cummins.repair import limit_frequency_range, remove_suspect_frequencies
from cummins.retardation import (
    added_mass_inf as estimate_added_mass_inf,
)
from cummins.retardation import default_retardation_function, significant_couplings

METHODS = ("fd", "realization", "prony")
ADDED_MASS_INF = ("auto", "data", "fit", "ogilvie")

__all__ = ["METHODS", "FitError", "FrequencyFit", "fit_frequency_domain", "fit_radiation"]


def fit_radiation(
    ds: xr.Dataset,
    *,
    method: str = "fd",
    r2: float = 0.99,
    r2_coupling: float | None = 0.97,
    max_order: int = 10,
    orders: Mapping[tuple[int, int], int] | None = None,
    threshold: float = 0.01,
    added_mass_inf: str = "auto",
    omega_min: float | None = None,
    omega_max: float | None = None,
    exclude_suspect: bool = True,
    passive: bool = True,
    progress: Callable[[str], None] | None = None,
) -> RadiationModel:
    """Identify state-space models of all significant couplings of the fluid memory.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed (zero speed: symmetric couplings).
    method
        ``"fd"`` (frequency domain, default), ``"realization"`` (Kung/ERA on K(t)) or
        ``"prony"``.
    r2
        Target R² of A(ω) and of B(ω) that selects the order of each diagonal term.
    r2_coupling
        Target for the off-diagonal couplings (``None``: same as ``r2``). Couplings matter less to
        the motions and are harder to fit: a lower target keeps the model compact.
    max_order
        Highest order tried.
    orders
        Fixed orders for some couplings, ``{(i, j): n}`` with 0-based DOF indices.
    threshold
        Couplings below this fraction of the diagonal terms are left out.
    added_mass_inf
        ``"auto"`` (data row if present, else ``"fit"``), ``"data"``, ``"fit"`` (joint
        estimate, frequency domain only) or ``"ogilvie"``.
    omega_min, omega_max
        Fitting range, rad/s.
    exclude_suspect
        Leave out the suspect frequencies (see module docstring).
    passive
        Require positive-real diagonal models.
    progress
        Called with a short message before each coupling.

    Returns
    -------
    RadiationModel
        With per-coupling ``metrics`` and ``attrs`` recording the data used.

    Raises
    ------
    FitError
        When a coupling cannot be fitted by a stable model.

    Examples
    --------
    >>> import cummins
    >>> model = cummins.fit_radiation(cummins.demo_dataset())
    >>> model.is_stable()
    True
    """
    start = time.perf_counter()
    if method not in METHODS:
        raise FitError(f"unknown method {method!r}; use one of {', '.join(METHODS)}")
    if max_order < 2:
        raise FitError(
            f"max_order is {max_order}: a radiation model needs at least 2 states "
            "(a zero at s = 0 and relative degree 1)"
        )
    for pair, n in (orders or {}).items():
        if not 2 <= n <= MAX_FIXED_ORDER:
            raise FitError(
                f"the order fixed for coupling {pair} is {n}: use 2 to {MAX_FIXED_ORDER}"
            )
    if added_mass_inf not in ADDED_MASS_INF:
        raise FitError(
            f"unknown added_mass_inf option {added_mass_inf!r}; use one of "
            f"{', '.join(ADDED_MASS_INF)}"
        )
    if "forward_speed" in ds.dims:
        if ds.sizes["forward_speed"] != 1:
            raise HydroDataError(
                "the data hold several forward speeds",
                hint="select one first, e.g. ds.sel(forward_speed=0.0)",
            )
        ds = ds.isel(forward_speed=0)
    say = progress or (lambda message: None)
    data, excluded, data_notes = _fit_data(ds, omega_min, omega_max, exclude_suspect)
    a_inf_mode = added_mass_inf
    if a_inf_mode == "auto":
        a_inf_mode = (
            "data" if "added_mass_inf" in data else ("fit" if method == "fd" else "ogilvie")
        )
    if a_inf_mode == "data" and "added_mass_inf" not in data:
        raise HydroDataError(
            "the data have no infinite-frequency added mass",
            path=ds.attrs.get("source_file"),
            hint="use added_mass_inf='fit' or 'ogilvie'",
        )
    if a_inf_mode == "fit" and method != "fd":
        raise FitError("the joint A∞ estimate needs method='fd'; use added_mass_inf='ogilvie'")
    ogilvie_estimate = estimate_added_mass_inf(
        data.drop_vars("added_mass_inf", errors="ignore"), method="ogilvie"
    )
    ogilvie = ogilvie_estimate.values
    # uncertainty of Ogilvie's estimate: its spread over frequency, at least 0.5 %
    ogilvie_spread = np.maximum(ogilvie_estimate.spread.values, 0.005 * np.abs(ogilvie))
    a_inf = _matrix(data, "added_mass_inf") if a_inf_mode == "data" else ogilvie.copy()

    labels = [str(d) for d in data.influenced_dof.values]
    w = data.omega.values
    a_all = _matrix(data, "added_mass")
    b_all = _matrix(data, "radiation_damping")
    pairs = significant_couplings(data, threshold)
    all_pairs = [(i, j) for i in range(len(labels)) for j in range(i, len(labels))]
    negligible = [p for p in all_pairs if p not in pairs]
    # K(t) of the symmetric part of the data (what is fitted), for the R² of K(t)
    b = data.radiation_damping
    swapped = b.rename(influenced_dof="radiating_dof", radiating_dof="influenced_dof")
    kernel_data = default_retardation_function(
        data.assign(radiation_damping=(0.5 * (b + swapped)).transpose(*b.dims)),
        max_points=500,
    )
    t, kernel = kernel_data.time.values, kernel_data.values
    models: list[CouplingModel] = []
    for i, j in pairs:
        name = labels[i] if i == j else f"{labels[i]}-{labels[j]}"
        say(f"{name}")
        a_ij = 0.5 * (a_all[:, i, j] + a_all[:, j, i])
        b_ij = 0.5 * (b_all[:, i, j] + b_all[:, j, i])
        fixed = (orders or {}).get((i, j), (orders or {}).get((j, i)))
        started = time.perf_counter()
        coupling, a_inf_ij = _fit_coupling(
            method,
            w,
            a_ij,
            b_ij,
            t,
            kernel[:, i, j],
            a_inf=None if a_inf_mode == "fit" else 0.5 * (a_inf[i, j] + a_inf[j, i]),
            guess=0.5 * (ogilvie[i, j] + ogilvie[j, i]),
            spread=0.5 * (ogilvie_spread[i, j] + ogilvie_spread[j, i]),
            passive=passive and i == j,
            target=r2 if i == j or r2_coupling is None else r2_coupling,
            max_order=max_order,
            fixed=fixed,
            i=i,
            j=j,
            name=name,
        )
        a_inf[i, j] = a_inf[j, i] = a_inf_ij
        model = CouplingModel(i, j, coupling.a, coupling.b, coupling.c, method, {}, coupling.note)
        metrics = coupling_metrics(model, w, a_ij, b_ij, a_inf_ij, time=t, kernel=kernel[:, i, j])
        metrics.update(coupling.extra)
        metrics["elapsed_s"] = time.perf_counter() - started
        models.append(replace(model, metrics=metrics))
    attrs = {
        "source_file": str(ds.attrs.get("source_file", "")),
        "source_format": str(ds.attrs.get("source_format", "")),
        "history": str(data.attrs.get("history", "")),
        "axis_convention": str(ds.attrs.get("axis_convention", "z-up")),
        "reference_point": np.asarray(
            ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float
        ),
        "method": method,
        "r2_target": r2,
        "r2_coupling_target": r2 if r2_coupling is None else r2_coupling,
        "max_order": max_order,
        "threshold": threshold,
        "added_mass_inf_method": a_inf_mode,
        "excluded_frequencies": [float(x) for x in excluded],
        "negligible_couplings": [
            labels[i] if i == j else f"{labels[i]}-{labels[j]}" for i, j in negligible
        ],
        "data_notes": data_notes
        + [
            f"{labels[i]}: no radiation damping in the data, not modelled"
            for i, j in negligible
            if i == j
        ],
        "omega_fit_min": float(w[0]),
        "omega_fit_max": float(w[-1]),
        "elapsed_s": time.perf_counter() - start,
    }
    return RadiationModel(tuple(labels), symmetric_couplings(models), a_inf, attrs)


def _matrix(ds: xr.Dataset, name: str) -> np.ndarray:
    """A copy (never a view: the caller's dataset must stay untouched)."""
    return np.array(ds[name].transpose(..., "influenced_dof", "radiating_dof").values)


def _fit_data(
    ds, omega_min, omega_max, exclude_suspect
) -> tuple[xr.Dataset, list[float], list[str]]:
    """The data to fit, the frequencies left out and what the user should know about them."""
    data = limit_frequency_range(ds, omega_min, omega_max)
    notes = []
    outside = ds.sizes["omega"] - data.sizes["omega"]
    if outside:
        notes.append(f"{outside} frequencies outside the fitting range left out")
    if exclude_suspect:
        before = data.sizes["omega"]
        data, suspects = remove_suspect_frequencies(data, above_first=True)
        for s in suspects:
            notes.append(f"{s.omega:.4g} rad/s left out: {s.quantity}, {s.reason}")
        others = before - data.sizes["omega"] - len(suspects)
        if others > 0:
            first = min(s.omega for s in suspects)
            notes.append(
                f"{others} more frequencies above {first:.4g} rad/s left out with it "
                "(irregular frequencies get denser upwards)"
            )
    excluded = sorted(set(ds.omega.values.tolist()) - set(data.omega.values.tolist()))
    for finding in copied_dofs(data):
        notes.append(f"{finding.message}: {finding.advice}")
    return data, excluded, notes


class _Siso:
    """(a, b, c) of a fitted coupling, its note, (frequency domain) the fit itself and
    method-specific metrics (realization: the Hankel singular values)."""

    def __init__(self, a, b, c, note: str = "", fit: FrequencyFit | None = None, extra=None):
        self.a, self.b, self.c, self.note, self.fit = a, b, c, note, fit
        self.extra = dict(extra or {})

    @property
    def order(self) -> int:
        return int(self.a.shape[0])


#: Orders whose linearised fit comes within this much of the R² target get the full
#: (nonlinear, passivity-enforcing) fit: it often lifts a lower order over the target.
SCREENING_MARGIN = 0.05
#: Leading Hankel singular values kept in a realization's metrics.
HANKEL_VALUES_REPORTED = 20
#: Highest order a user may fix for a coupling: beyond it, a typing error, not a model.
MAX_FIXED_ORDER = 40


def _fit_coupling(
    method,
    w,
    a,
    b,
    t,
    kernel,
    *,
    a_inf,
    guess,
    spread,
    passive,
    target,
    max_order,
    fixed,
    i,
    j,
    name,
) -> tuple[_Siso, float]:
    """Fit one coupling at the fixed order, or the smallest order reaching the target.

    Frequency domain: every order is first fitted by the cheap linearised step alone; the
    full fit runs on the orders that come close to the target, lowest first.
    """
    candidates = [fixed] if fixed else list(range(2, max_order + 1))
    screening: dict[int, float] = {}
    if method == "fd" and not fixed:
        screened = []
        for n in candidates:
            try:
                quick = fit_frequency_domain(
                    w,
                    a,
                    b,
                    n,
                    added_mass_inf=a_inf,
                    added_mass_inf_guess=guess,
                    added_mass_inf_spread=spread,
                    refine=False,
                )
            except FitError:
                continue
            score = min(quick.r2_added_mass, quick.r2_damping)
            screening[n] = score
            if score >= target - SCREENING_MARGIN:
                screened.append(n)
            if score >= target:
                break
        candidates = screened or candidates
    best: tuple[float, _Siso, float] | None = None
    errors = []
    remaining = [n for n in range(2, max_order + 1) if n not in candidates] if not fixed else []
    for n in [*candidates, *remaining]:  # the screened orders first, then the others
        try:
            siso, a_inf_fit, r2a, r2b, ok_passive = _fit_order(
                method,
                w,
                a,
                b,
                t,
                kernel,
                n,
                a_inf=a_inf,
                guess=guess,
                spread=spread,
                passive=passive,
                target=target,
            )
        except FitError as exc:
            errors.append(f"order {n}: {exc}")
            continue
        score = min(r2a, r2b) - (0.0 if ok_passive else 1.0)
        if best is None or score > best[0]:
            best = (score, siso, a_inf_fit)
        if min(r2a, r2b) >= target and ok_passive:
            break
    if best is None:
        raise FitError(f"coupling {name}: no stable model ({'; '.join(errors)})")
    close = screening.get(best[1].order - 1, -np.inf) >= target - SCREENING_MARGIN
    if method == "fd" and not fixed and best[0] >= target and close:
        best = _try_lower_orders(
            best, w, a, b, a_inf=a_inf, guess=guess, spread=spread, passive=passive, target=target
        )
    score, siso, a_inf_fit = best
    if score < target and not fixed:
        siso.note = "; ".join(
            filter(None, [siso.note, f"R² target {target} not reached up to order {max_order}"])
        )
    return siso, a_inf_fit


def _try_lower_orders(best, w, a, b, *, a_inf, guess, spread, passive, target):
    """One order lower, started from the fit's poles less its weakest mode, if it still
    reaches the target (the linearised step has found a local optimum; the pruned start
    often finds a better one). Trying the second-weakest mode as well found no lower
    order on the tanker, supply vessel or S-175 and cost 40 % of the whole fit."""
    if best[1].order > 2:
        fit = best[1].fit
        found = None
        for start in pruned_poles(fit.poles, fit.residues)[:1]:  # the weakest mode
            try:
                lower = fit_frequency_domain(
                    w,
                    a,
                    b,
                    start.size,
                    added_mass_inf=a_inf,
                    added_mass_inf_guess=guess,
                    added_mass_inf_spread=spread,
                    passive=passive,
                    target=target,
                    refine=True,
                    initial_poles=start,
                )
            except FitError:
                continue
            if min(lower.r2_added_mass, lower.r2_damping) >= target and (
                lower.passive or not passive
            ):
                found = lower
                break
        if found is None:
            return best
        am, bm, cm = modal_realization(found.poles, found.residues)
        siso = _Siso(
            am,
            bm,
            cm,
            "; ".join(
                filter(None, [found.note, "started from the pruned poles of the next order"])
            ),
            found,
        )
        best = (min(found.r2_added_mass, found.r2_damping), siso, found.added_mass_inf)
    return best


def _fit_order(method, w, a, b, t, kernel, n, *, a_inf, guess, spread, passive, target):
    from cummins.fit.frequency import is_positive_real, r_squared

    if method == "fd":
        fit: FrequencyFit = fit_frequency_domain(
            w,
            a,
            b,
            n,
            added_mass_inf=a_inf,
            added_mass_inf_guess=guess,
            added_mass_inf_spread=spread,
            passive=passive,
            target=target,
        )
        am, bm, cm = modal_realization(fit.poles, fit.residues)
        return (
            _Siso(am, bm, cm, fit.note, fit),
            fit.added_mass_inf,
            fit.r2_added_mass,
            fit.r2_damping,
            fit.passive or not passive,
        )
    from cummins.fit import realization

    realize = realization.era if method == "realization" else realization.prony
    result = realize(t, kernel, n)
    k = CouplingModel(0, 0, result.a, result.b, result.c).frequency_response(w)
    r2a = r_squared(a, a_inf + k.imag / w)
    r2b = r_squared(b, k.real)
    ok = True
    if passive:
        lam, vec = np.linalg.eig(result.a)
        residues = (result.c @ vec) * np.linalg.solve(vec, result.b)
        ok = is_positive_real(lam, residues)
    extra = {}
    sigma = np.asarray(result.hankel_singular_values, dtype=float)
    if sigma.size:
        # the ERA order criterion: σ_{n+1}/σ_1, and the leading values (K units × s)
        extra["hankel_sv_ratio"] = float(sigma[n] / sigma[0]) if sigma.size > n else 0.0
        extra["hankel_singular_values"] = sigma[:HANKEL_VALUES_REPORTED].tolist()
    return _Siso(result.a, result.b, result.c, result.note, extra=extra), a_inf, r2a, r2b, ok
