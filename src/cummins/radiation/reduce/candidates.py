"""The truncations of one radiation coupling, and what each is measured against.

Each coupling K_ij of a :class:`~cummins.radiation.model.RadiationModel` is a SISO model;
a symmetric pair K_ij = K_ji is one coupling used twice. A coupling is balanced
unweighted and with the low-frequency weights ω₀ of :data:`WEIGHT_CANDIDATES`
(:mod:`~cummins.radiation.reduce.balancing`), every truncation gets its zero K(0) = 0
back when the coupling had it, and is measured against the unreduced coupling by
max(1 − R²_A, 1 − R²_B) (Unneland (2007) eq. 6.19; B = Re K and A − A∞ = Im K/ω,
eq. 2.55); the best candidate at each order is what
:func:`~cummins.radiation.reduce.radiation_model.reduce_radiation_model` chooses from.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from cummins.errors import FitError
from cummins.radiation.fit.realization import impose_zero_dc
from cummins.radiation.model import CouplingModel, RadiationModel, siso_frequency_response
from cummins.radiation.reduce.balancing import _balance, _Balanced, _gramian_pair, glover_bound
from cummins.radiation.reduce.gramians import _regularised
from cummins.radiation.reduce.system import PR_METHODS, _refined_peak, _sweep, hinf_norm

#: Low-frequency weights ω₀ tried per coupling by :func:`reduce_radiation_model`, as
#: multiples of the frequency of the coupling's peak |K(jω)| (None: unweighted).
WEIGHT_CANDIDATES = (None, 0.25, 0.5, 1.0)
#: Frequencies on which a reduced coupling is compared with the unreduced one.
MEASURE_POINTS = 200
#: Smallest order of a reduced radiation coupling (relative degree 1 and a zero at s = 0
#: need two states).
MIN_COUPLING_ORDER = 2


# --------------------------------------------------------------------------- radiation models


def candidate_weights(method: str, peak_omega: float) -> list[float | None]:
    """The low-frequency weights ω₀ a model is balanced with: :data:`WEIGHT_CANDIDATES` ×
    the frequency of its peak |K| (None: unweighted; only that for ``"riccati"``, whose
    gramians are never weighted, or without a finite peak frequency)."""
    if method == "riccati" or not 0 < peak_omega < math.inf:
        return [None]
    return [None if m is None else m * peak_omega for m in WEIGHT_CANDIDATES]


@dataclass(frozen=True)
class _Candidate:
    """One truncation of one coupling (K(0) = 0 re-imposed when the coupling had it)."""

    order: int
    weight: float | None  # ω₀, rad/s
    a: NDArray
    b: NDArray
    c: NDArray
    error: float  # max(1 − R²_A, 1 − R²_B) against the unreduced coupling
    bound: float | None  # Glover bound (Lyapunov), before the DC projection
    dc_before: float
    dc_change: float
    violation: float = 0.0  # PR methods: max(0, −min_ω Re K_r)/max|K|, after the projection


@dataclass
class _Unique:
    """A coupling to reduce, the indices of its entries in the model (1, or 2 for a
    symmetric pair) and what its candidate truncations are measured against."""

    model: CouplingModel
    entries: list[int]
    method: str = "lyapunov"
    grid: NDArray = field(default_factory=lambda: np.zeros(0))
    response: NDArray = field(default_factory=lambda: np.zeros(0, dtype=complex))
    peak: float = 0.0
    peak_omega: float = 0.0
    had_zero: bool = False
    regularization: float = 0.0
    notes: list[str] = field(default_factory=list)
    cache: dict[float | None, _Balanced | None] = field(default_factory=dict)

    @property
    def minimum(self) -> int:
        return min(MIN_COUPLING_ORDER, self.model.order)

    def weights(self) -> list[float | None]:
        """The candidate ω₀ (:func:`candidate_weights`)."""
        return candidate_weights(self.method, self.peak_omega)

    def balanced(self, weight: float | None) -> _Balanced | None:
        """The balanced realization of the coupling for ω₀ = ``weight`` (cached; None when
        the coupling has no such realization)."""
        if weight not in self.cache:
            k = self.model
            a, b, c, d = k.a, k.b[:, None], k.c[None, :], np.zeros((1, 1))
            reg = (
                _regularised(a, b, c, d, self.regularization) if self.method in PR_METHODS else None
            )
            try:
                self.cache[weight] = _balance(
                    a, b, c, d, *_gramian_pair(self.method, a, b, c, reg, weight)
                )
            except FitError:
                self.cache[weight] = None
        return self.cache[weight]

    def candidate(self, r: int, weight: float | None) -> _Candidate | None:
        """The truncation to r states for ω₀ = ``weight`` (None if not stable or past the
        numerical rank)."""

        balanced = self.balanced(weight)
        if balanced is None or r > balanced.rank:
            return None
        a, b, c = balanced.truncated(r)
        b, c = b[:, 0], c[0]
        if np.any(np.linalg.eigvals(a).real >= 0):
            return None
        dc_before, dc_change = 0.0, 0.0
        if self.had_zero:
            c, dc_before, dc_change = impose_zero_dc(a, b, c)
        bound = glover_bound(balanced.sigma, r) if self.method == "lyapunov" else None
        error = _fit_error(self.grid, self.response, siso_frequency_response(a, b, c, self.grid))
        violation = 0.0
        if self.method in PR_METHODS and self.peak > 0:
            violation = -_lowest_real_part(a, b, c) / self.peak
        return _Candidate(r, weight, a, b, c, error, bound, dc_before, dc_change, violation)

    def best(self, r: int) -> _Candidate | None:
        """The candidate truncation to r states with the smallest fit error; for the PR
        methods, among those whose Re K_r stays above −ε max|K| after the DC projection
        (else the least violating)."""
        found = [x for w in self.weights() if (x := self.candidate(r, w)) is not None]
        return self.preferred(found) if found else None

    def preferred(self, found: list[_Candidate]) -> _Candidate:
        """The smallest fit error among the candidates within the PR allowance (PR
        methods: violation ≤ ε), else the least violating."""
        allowed = self.regularization * (1 + 1e-6)
        return min(found, key=lambda x: (max(x.violation - allowed, 0.0), x.error))


def _fit_error(omega: NDArray, reference: NDArray, reduced: NDArray) -> float:
    """max(1 − R² of B, 1 − R² of A − A∞) of a reduced coupling against the unreduced
    one on ``omega``: B = Re K and A − A∞ = Im K/ω (Unneland (2007) eq. 2.55; R² eq. 6.19)."""
    error = 0.0
    for ref, red in (
        (reference.real, reduced.real),
        (reference.imag / omega, reduced.imag / omega),
    ):
        spread = float(np.sum((ref - ref.mean()) ** 2))
        residual = float(np.sum((ref - red) ** 2))
        error = max(
            error, residual / spread if spread > 0 else (0.0 if residual == 0 else math.inf)
        )
    return error


def _unique_couplings(model: RadiationModel) -> list[_Unique]:
    """Each coupling once; a symmetric copy (j, i) with the same matrices joins (i, j)."""
    out: list[_Unique] = []
    owner: dict[tuple[int, int], _Unique] = {}
    for index, k in enumerate(model.couplings):
        mirror = owner.get((k.radiating, k.influenced))
        if mirror is not None and _same_matrices(mirror.model, k):
            mirror.entries.append(index)
            continue
        unique = _Unique(k, [index])
        owner[(k.influenced, k.radiating)] = unique
        out.append(unique)
    return out


def _same_matrices(x: CouplingModel, y: CouplingModel) -> bool:
    return all(np.array_equal(getattr(x, name), getattr(y, name)) for name in ("a", "b", "c"))


def _measurement_grid(model: RadiationModel, k: CouplingModel, omega: NDArray | None) -> NDArray:
    """Where a reduced coupling is compared with the unreduced one: the fitted
    frequencies of the data when given; else :data:`MEASURE_POINTS` log-spaced points
    over the fitted range (``omega_fit_min`` … ``omega_fit_max``) when the model records
    it, or a decade either side of the coupling's poles. Log spacing, as most solvers'
    grids are denser at low frequency, where A(ω) is sensitive to K."""
    if omega is not None and omega.size:
        return omega
    lo, hi = model.attrs.get("omega_fit_min"), model.attrs.get("omega_fit_max")
    if lo is not None and hi is not None and 0 < float(lo) < float(hi) < math.inf:
        return np.geomspace(float(lo), float(hi), MEASURE_POINTS)
    mags = np.abs(k.poles())
    return np.geomspace(mags.min() / 10, mags.max() * 10, MEASURE_POINTS)


def _prepared(
    model: RadiationModel, method: str, regularization: float, omega: NDArray | None = None
) -> list[_Unique]:
    """The unique couplings with their method, reference response, peak and DC zero."""
    units = _unique_couplings(model)
    for u in units:
        k = u.model
        if not k.order:
            continue
        if not k.is_stable():
            raise FitError(f"coupling {(k.influenced, k.radiating)} is not stable")
        u.method, u.regularization = method, regularization
        if method in PR_METHODS and k.influenced != k.radiating:
            u.method = "lyapunov"
            u.notes.append(
                f"off-diagonal coupling reduced by Lyapunov BT ({method} needs a PR model)"
            )
        u.peak, u.peak_omega = hinf_norm(k.a, k.b, k.c)
        u.grid = _measurement_grid(model, k, omega)
        u.response = k.frequency_response(u.grid)
        u.had_zero = abs(_dc_gain(k.a, k.b, k.c)) <= 1e-9 * max(u.peak, np.finfo(float).tiny)
        if u.method != "lyapunov" and u.balanced(None) is None:
            u.method = "lyapunov"
            u.cache.clear()
            u.notes.append(f"{method} BT impossible (not positive real): reduced by Lyapunov BT")
    return units


def _lowest_real_part(a: NDArray, b: NDArray, c: NDArray) -> float:
    """min_ω Re K(jω) of a SISO model on the sweep, refined around the lowest minima."""
    grid = _sweep(np.linalg.eigvals(a))
    values = -siso_frequency_response(a, b, c, grid).real
    peak, _ = _refined_peak(
        lambda w: float(-siso_frequency_response(a, b, c, [w]).real[0]), grid, values
    )
    return min(-peak, 0.0)


def _dc_gain(a: NDArray, b: NDArray, c: NDArray) -> float:
    return float(-(c @ np.linalg.solve(a, b)))


def _hinf_change(k: CouplingModel, a_r: NDArray, b_r: NDArray, c_r: NDArray) -> float:
    """max_ω |K − K_r| of the error system (block-diagonal realization)."""
    a_e = scipy.linalg.block_diag(k.a, a_r)
    b_e = np.concatenate([k.b, b_r])
    c_e = np.concatenate([k.c, -c_r])
    return hinf_norm(a_e, b_e, c_e)[0]
