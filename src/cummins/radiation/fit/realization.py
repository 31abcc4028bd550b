"""Time-domain realization of a retardation function: Kung/ERA and Prony.

Given uniformly spaced samples k[m] = K(t₀ + m Δt), m = 0 … M−1, of the retardation
function of one coupling, find a stable SISO state-space model

    K(s) = c (sI − a)⁻¹ b,        K(t) = c e^{at} b,

with the structure a fluid-memory model must have (Unneland (2007) §3.3, eq. 3.61): strictly
proper (D = 0, relative degree 1, K(0⁺) = c b) and, at zero speed, a zero at s = 0
(K(s=0) = −c a⁻¹ b = B(0) = 0).

Two identifiers are provided:

:func:`era`
    Kung's Hankel-SVD realization in the form of the Eigensystem Realization Algorithm
    (Unneland (2007) eqs. 4.16–4.27; Kung (1978); Juang & Pappa (1985)).
:func:`prony`
    Prony's method: least-squares linear prediction for the characteristic polynomial,
    its roots as discrete poles, residues by least squares.

Both return a :class:`Realization`; :meth:`Realization.to_coupling` turns it into a
:class:`cummins.radiation.model.CouplingModel`. :func:`modal_realization` (also used by the
frequency-domain fitter; in :mod:`cummins.radiation.fit.modal`, importable from here as
well) builds a real block-diagonal (a, b, c) from poles and residues.

Why there is no 1/Δt error (impulse invariance)
-----------------------------------------------
The samples of a *continuous* impulse response are exactly the Markov parameters of a
discrete system with the same b and c:

    k[m] = K(m Δt) = c e^{a m Δt} b = c A_dᵐ b,      A_d = e^{a Δt},

starting at m = 0 (there is no discrete feed-through: k[0] = K(0⁺) = c b). The Hankel
factorisation therefore delivers c and b of the continuous model directly, and only the
state matrix needs converting, exactly, by the matrix logarithm a = log(A_d)/Δt (computed
through the eigen-decomposition A_d = V diag(z) V⁻¹, λ = log z / Δt on the principal
branch, then realified by :func:`modal_realization`). No Δt factor enters b or c, D = 0
exactly, and frequencies are not warped.

MATLAB's ``imp2ss``, used in the thesis, instead treats its input as the *pulse* response
h_d of a discrete system (h_d[0] = D_d) and converts with the inverse Tustin transform
(Unneland (2007) eqs. 4.28–4.31). Tustin maps z = 1 to s = 0, so the continuous DC gain
equals Σ h_d[m]; with h_d[m] = K(mΔt) that is Σ K(mΔt) ≈ (1/Δt)∫K dt, i.e. the model is
about 1/Δt too large unless the samples are first scaled by Δt (a scaling the thesis does
not mention). Tustin also leaves D ≠ 0 (relative degree 0, the "wrong structure" of the
thesis's TD models) and warps frequencies (ω_c = (2/Δt) tan(ω_d Δt/2)). The test suite
checks that a known K(t) sampled at two different Δt gives the same continuous model.

Modes the logarithm cannot map, and unstable modes
--------------------------------------------------
An identified discrete pole z is handled as follows (the decision is written to
:attr:`Realization.note`):

* z on or near the negative real axis, |arg z| > (1 − ``NYQUIST_MARGIN``) π, or z = 0:
  the mode alternates (almost) sign from one sample to the next. A real z < 0 has no
  real continuous counterpart of the same order (log z = log|z| + jπ), and near the axis
  the principal logarithm is ill-conditioned (a small change of z moves the continuous
  frequency from +π/Δt to −π/Δt). Such modes carry sampling artefacts (noise, spikes),
  not the smooth K(t) of the data, so they are **discarded** (a Tustin fallback would keep
  them as fast spurious real poles whose response does not reproduce the samples anyway).
* |z| ≥ 1 (Re λ ≥ 0): the pole is **reflected** into the left half-plane,
  λ → −max(Re λ, 1/T) + j Im λ (T the record length: a slower decay cannot be told from
  a constant on the record), and the residues of the reflected modes are re-fitted by
  linear least squares to what the other modes leave of the samples.

In :func:`era` the other modes keep their residues (dropping a mode is a modal
truncation of the ERA model); re-fitting all residues after dropping modes was tried and
rejected: with noisy samples the many fast, nearly collinear noise modes get huge,
cancelling residues. :func:`prony` fits all residues by least squares by construction.
An unstable model is never returned: the final model is checked and
:class:`~cummins.errors.FitError` raised if a pole has Re λ ≥ 0 (which the rules above
make impossible).

The zero at s = 0
-----------------
With ``zero_dc=True`` the constraint c a⁻¹ b = 0 is imposed by the smallest change of c
in the H₂ sense: minimise ‖δK‖²_H₂ = δc P δcᵀ (P the controllability gramian,
a P + P aᵀ + b bᵀ = 0, so that ∫₀^∞ (δc e^{at} b)² dt = δc P δcᵀ) subject to
(c + δc) g = 0, g = a⁻¹ b, giving δc = −(c g) P⁻¹g / (gᵀ P⁻¹ g). This is the orthogonal
projection of c in balanced coordinates; it does not depend on the state coordinates.
The relative change ‖δK‖_H₂ / ‖K‖_H₂ is :attr:`Realization.dc_change`.

Hankel size and order selection
-------------------------------
The Hankel matrix has at most ``hankel_size`` (default 200) rows and columns, so one
realization costs one symmetric eigen-decomposition of at most 200 × 200 (≈ 7 ms
single-threaded; the matrix is symmetric, so its SVD is its eigen-decomposition, twice as
fast as ``svd``). Its row and column lags are the same set ℓ: all of 0 … L
(L = ⌊(M−2)/2⌋, every sample used) when L + 1 ≤ ``hankel_size``; for longer records the
first ``hankel_size``/2 lags are consecutive and the rest evenly spread up to L, so that
the matrix still spans the whole record. Rows and columns are weighted by √(Δt w_ℓ), w_ℓ
the trapezoid weights of the lags, and the shifted matrix H₁[i, j] = k[ℓ_i + ℓ_j + 1]
gives A_d = Σ^{-1/2} Uᵀ H₁ V Σ^{-1/2} (Juang & Pappa's form of Kung's shift, Unneland (2007)
eq. 4.24). For finite-order data the realization is exact for any lag set whose first lags
are consecutive (the observability and controllability matrices keep full rank); with
consecutive lags and unit weights it is Kung's algorithm.

The singular values returned are those of the weighted matrix. They approximate the
Hankel singular values of the *continuous* K(s) (the weights make the matrix a
trapezoid-rule discretisation of the Hankel operator u ↦ ∫₀^∞ K(t + τ) u(τ) dτ), so they
do not depend on Δt (error O(Δt²) plus the truncation of the record; tested against the
gramians).

The order is ``order`` when given (capped at the numerical rank, σ > 10⁻¹² σ₁, with a
note); otherwise the smallest n with 2 Σ_{k>n} σ_k ≤ ``tol`` σ₁ (the rule of ``imp2ss``,
after the Glover bound 2 Σ σ_tail on the H∞ error of balanced truncation), ``tol``
defaulting to :data:`DEFAULT_TOL`. It is never above ``max_order``. The rule sums the
noise floor too: on noisy samples it runs to ``max_order``, so give the order (or a
larger ``tol``) there.

Limitations
-----------
ERA estimates A_d from a one-sample shift. With white noise on heavily oversampled data
(Δt far below the time scales of K) that shift carries little information and the poles
degrade (1 % noise, three modes: 5 % response error at Δt = 0.1–0.2 s, 20 % at 0.05 s).
:func:`prony` with its Steiglitz–McBride refinement is the better estimator for noisy
samples. A near-defective A_d (repeated poles, eigenvector condition number above
:data:`MAX_EIGENVECTOR_CONDITION`) is converted with the real matrix logarithm
(``scipy.linalg.logm``) instead of the modal route; there an unstable or Nyquist pole is
an error rather than reflected or discarded.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from cummins.errors import FitError
from cummins.radiation.fit.modal import modal_realization
from cummins.radiation.model import CouplingModel, SisoStateSpace

#: Relative tolerance of the default order selection 2 Σ σ_tail ≤ tol σ₁ (as ``imp2ss``).
DEFAULT_TOL = 0.01
#: Largest order :func:`era` selects or accepts unless told otherwise.
MAX_ORDER = 20
#: Largest number of Hankel rows (and columns).
HANKEL_SIZE = 200
#: Discrete poles with |arg z| > (1 − NYQUIST_MARGIN) π are discarded (Nyquist artefacts).
NYQUIST_MARGIN = 0.05
#: Eigenvector condition number above which ERA converts with the matrix logarithm
#: (logm) instead of the modal route (near-defective A_d, e.g. repeated poles).
MAX_EIGENVECTOR_CONDITION = 1e6
#: A reflected pole gets a decay rate of at least 1/(RECORDS × T), T the record length:
#: a slower decay cannot be told from a constant on the record.
RECORDS = 1.0
#: Singular values below RANK_TOL σ₁ are rounding errors: the order is capped there.
RANK_TOL = 1e-12
#: Default number of Steiglitz–McBride iterations refining Prony's poles.
PRONY_ITERATIONS = 5


@dataclass(frozen=True, eq=False)
class Realization(SisoStateSpace):
    """A SISO continuous-time model K(s) = c (sI − a)⁻¹ b identified from samples of K(t).

    Attributes
    ----------
    a, b, c
        Real state matrix (n, n), input vector (n,), output vector (n,). D = 0.
    hankel_singular_values
        Singular values of the (weighted) Hankel matrix, approximating the Hankel singular
        values of K(s), in K's units × s (:func:`era`); empty for :func:`prony`.
    dt
        Sampling interval of the data, s.
    note
        What was done beyond the plain algorithm: discarded or reflected poles,
        least-squares re-fit of residues, size of the DC projection, logm conversion.
    method
        ``"realization"`` (ERA) or ``"prony"``.
    dc_change
        ‖δK‖_H₂ / ‖K‖_H₂ of the projection imposing K(0) = 0 (0 when not imposed).
    """

    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    hankel_singular_values: NDArray[np.float64]
    dt: float
    note: str = ""
    method: str = "realization"
    dc_change: float = 0.0

    def to_coupling(
        self,
        influenced: int,
        radiating: int,
        method: str | None = None,
        metrics: Mapping[str, Any] | None = None,
    ) -> CouplingModel:
        """The model as the :class:`~cummins.radiation.model.CouplingModel` of coupling (i, j).

        Parameters
        ----------
        influenced, radiating
            0-based DOF indices i (force) and j (velocity).
        method
            Default :attr:`method`.
        metrics
            Fit measures to store; ``order``, ``stable`` and ``dc_change`` are added
            unless given.
        """
        merged: dict[str, Any] = {
            "order": self.order,
            "stable": self.is_stable(),
            "dc_change": self.dc_change,
        }
        merged.update(metrics or {})
        return CouplingModel(
            influenced,
            radiating,
            self.a.copy(),
            self.b.copy(),
            self.c.copy(),
            method or self.method,
            merged,
            self.note,
        )


# --------------------------------------------------------------------------- input checks


def _uniform_samples(t: ArrayLike, k: ArrayLike) -> tuple[NDArray, NDArray, float]:
    """Validate (t, k) and return them as float arrays with the time step."""
    t = np.asarray(t, dtype=float).reshape(-1)
    k = np.asarray(k, dtype=float).reshape(-1)
    if t.size != k.size:
        raise FitError(f"{t.size} times but {k.size} samples of K(t)")
    if t.size < 4:
        raise FitError(f"only {t.size} samples of K(t); need at least 4 (and ≫ the order)")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(k))):
        bad = np.flatnonzero(~(np.isfinite(t) & np.isfinite(k)))[0]
        raise FitError(f"K(t) or t is not finite at sample {bad} (t = {t[bad]:.6g} s)")
    if t[0] < 0:
        raise FitError(f"the first time is negative ({t[0]:.6g} s); K(t) is causal, t ≥ 0")
    dt = (t[-1] - t[0]) / (t.size - 1)
    step = np.diff(t)
    if dt <= 0 or np.max(np.abs(step - dt)) > 1e-6 * dt:
        worst = int(np.argmax(np.abs(step - dt)))
        raise FitError(
            f"the time grid is not uniform (step {step[worst]:.6g} s at t = {t[worst]:.6g} s, "
            f"mean {dt:.6g} s); evaluate K(t) on a uniform grid, e.g. "
            "np.arange(M) * dt"
        )
    if not np.any(k):
        raise FitError("K(t) is identically zero: nothing to realize")
    return t, k, float(dt)


def _check_order(order: int, available: int, max_order: int, what: str) -> int:
    if int(order) != order or order < 1:
        raise FitError(f"the order must be a positive integer, not {order!r}")
    order = int(order)
    if order > max_order:
        raise FitError(
            f"order {order} is above max_order = {max_order}; pass a larger max_order if "
            "you really want it"
        )
    if order > available:
        raise FitError(f"order {order} needs more samples: {what} allow at most {available}")
    return order


# --------------------------------------------------------------------------- poles


@dataclass
class _PoleReport:
    discarded: list[complex] = field(default_factory=list)
    reflected: list[tuple[complex, complex]] = field(default_factory=list)

    def text(self, dt: float) -> str:
        parts = []
        if self.discarded:
            zs = ", ".join(f"{z:.4g}" for z in self.discarded)
            parts.append(
                f"discarded {len(self.discarded)} mode(s) with discrete poles on or near "
                f"the negative real axis or at 0 (z = {zs}; Nyquist {np.pi / dt:.4g} rad/s)"
            )
        if self.reflected:
            ps = ", ".join(f"{old:.4g} → {new:.4g}" for old, new in self.reflected)
            parts.append(
                f"reflected {len(self.reflected)} unstable mode(s) ({ps} rad/s), residues "
                "re-fitted by least squares"
            )
        return "; ".join(parts)


def _continuous_poles(
    z: NDArray[np.complex128], dt: float, record: float
) -> tuple[NDArray[np.complex128], NDArray[np.bool_], NDArray[np.bool_], _PoleReport]:
    """λ = log(z)/Δt for the usable discrete poles; reflect unstable ones.

    Returns the continuous poles of the kept modes, the mask of kept modes (over z), the
    mask of reflected modes (over the kept ones) and a report.
    """
    report = _PoleReport()
    z = np.asarray(z, dtype=complex)
    scale = max(float(np.max(np.abs(z))), 1.0)
    keep = (np.abs(np.angle(z)) <= (1.0 - NYQUIST_MARGIN) * np.pi) & (np.abs(z) > 1e-12 * scale)
    report.discarded = [complex(v) for v in z[~keep] if v.imag >= 0]
    lam = np.log(z[keep]) / dt
    lam = np.where(np.abs(lam.imag) <= 1e-12 * np.abs(lam), lam.real + 0j, lam)
    floor = 1.0 / (RECORDS * record)
    unstable = lam.real >= 0
    for old in lam[unstable]:
        if old.imag >= 0:
            report.reflected.append((complex(old), complex(-max(old.real, floor), old.imag)))
    lam = np.where(unstable, -np.maximum(lam.real, floor) + 1j * lam.imag, lam)
    return lam, keep, unstable, report


def _residues_least_squares(
    t: NDArray, k: NDArray, poles: NDArray[np.complex128]
) -> NDArray[np.complex128]:
    """Residues ρ of K(t) = Σ ρ_r e^{p_r t} fitted to the samples by linear least squares.

    The poles must be closed under conjugation; the basis is real (e^{pt} for a real
    pole, Re and Im of e^{pt} for the member of a pair with Im p > 0), so the residues of
    a pair come out conjugate.
    """
    columns, owners = [], []
    for index, p in enumerate(poles):
        if p.imag < 0:
            continue
        e = np.exp(p * t)
        if p.imag == 0:
            columns.append(e.real)
            owners.append((index, "real"))
        else:
            columns.extend([e.real, e.imag])
            owners.extend([(index, "re"), (index, "im")])
    basis = np.column_stack(columns)
    norms = np.linalg.norm(basis, axis=0)
    norms[norms == 0] = 1.0
    coef = np.linalg.lstsq(basis / norms, k, rcond=None)[0] / norms
    rho = np.zeros(poles.size, dtype=complex)
    for (index, kind), value in zip(owners, coef, strict=True):
        if kind == "real":
            rho[index] = value
        elif kind == "re":
            rho[index] += value / 2
        else:
            rho[index] -= 1j * value / 2
    for index, p in enumerate(poles):
        if p.imag < 0:
            partner = int(np.argmin(np.abs(poles - np.conj(p))))
            rho[index] = np.conj(rho[partner])
    return rho


def _sorted_modes(poles: NDArray, residues: NDArray) -> tuple[NDArray, NDArray]:
    """Order modes by natural frequency |p| (slowest first), conjugates adjacent.

    The residue of the lower member of each pair is set to the conjugate of the upper
    one's (they differ by rounding only when computed from an eigen-decomposition).
    """
    order = np.lexsort((-poles.imag, np.abs(poles)))
    poles, residues = poles[order], residues[order].copy()
    for index in np.flatnonzero(poles.imag < 0):
        partner = int(np.argmin(np.abs(poles - np.conj(poles[index]))))
        residues[index] = np.conj(residues[partner])
    return poles, residues


# --------------------------------------------------------------------------- structure


def impose_zero_dc(a: NDArray, b: NDArray, c: NDArray) -> tuple[NDArray[np.float64], float, float]:
    """The smallest (H₂) change of c giving K(0) = −c a⁻¹ b = 0 (Unneland (2007) eqs. 3.44–3.48).

    Minimises δc P δcᵀ = ‖δK‖²_H₂ (P the controllability gramian, a P + P aᵀ + b bᵀ = 0)
    subject to (c + δc) a⁻¹ b = 0: δc = −(c g) P⁻¹g / (gᵀ P⁻¹ g), g = a⁻¹ b.

    Parameters
    ----------
    a, b, c
        A stable SISO model.

    Returns
    -------
    (c_new, dc_before, relative_change)
        The new output vector, K(0) before the change, and ‖δK‖_H₂ / ‖K‖_H₂.
    """
    g = np.linalg.solve(a, b)
    dc_before = float(-(c @ g))
    if dc_before == 0.0:
        return c.copy(), 0.0, 0.0
    gram = scipy.linalg.solve_continuous_lyapunov(a, -np.outer(b, b))
    gram = 0.5 * (gram + gram.T)
    direction = np.linalg.lstsq(gram, g, rcond=None)[0]
    delta = -(c @ g) * direction / (g @ direction)
    norm = float(c @ gram @ c)
    change = float(np.sqrt(max(delta @ gram @ delta, 0.0) / norm)) if norm > 0 else np.inf
    return c + delta, dc_before, change


def _finish(
    a: NDArray,
    b: NDArray,
    c: NDArray,
    *,
    zero_dc: bool,
    sigma: NDArray,
    dt: float,
    notes: list[str],
    method: str,
) -> Realization:
    """Impose the zero at s = 0, check stability, and package the result."""
    eig = np.linalg.eigvals(a) if a.size else np.empty(0)
    if a.size == 0:
        raise FitError("no usable mode is left after discarding the Nyquist artefacts")
    if np.any(eig.real >= 0):
        raise FitError(
            f"the realization has unstable poles {eig[eig.real >= 0]} rad/s; lower the order"
        )
    change = 0.0
    if zero_dc:
        c, dc_before, change = impose_zero_dc(a, b, c)
        notes.append(
            f"zero at s = 0 imposed: K(s=0) was {dc_before:.4g}; c changed by "
            f"{100 * change:.3g} % (H2 norm of the impulse-response change)"
        )
    return Realization(
        a=a,
        b=b,
        c=c,
        hankel_singular_values=sigma,
        dt=dt,
        note="; ".join(n for n in notes if n),
        method=method,
        dc_change=change,
    )


def _from_discrete_poles(
    t: NDArray,
    k: NDArray,
    dt: float,
    z: NDArray[np.complex128],
    residues: NDArray[np.complex128] | None,
) -> tuple[NDArray, NDArray, NDArray, str]:
    """Continuous modal model from discrete poles (and residues if trusted)."""
    record = max(t[-1] - t[0], dt)
    lam, keep, moved, report = _continuous_poles(z, dt, record)
    if lam.size == 0:
        raise FitError(
            "every identified pole lies on the negative real axis (Nyquist artefacts); "
            "the samples alternate in sign: check K(t) and its time step"
        )
    if residues is None:
        rho = _residues_least_squares(t, k, lam)
    else:
        rho = residues[keep] * np.exp(-lam * t[0])
        if moved.any():
            # only the reflected modes' residues are re-fitted, to what the others leave
            rho[moved] = 0.0
            rest = np.real(np.exp(np.outer(t, lam)) @ rho)
            rho[moved] = _residues_least_squares(t, k - rest, lam[moved])
    lam, rho = _sorted_modes(lam, rho)
    a, b, c = modal_realization(lam, rho, rtol=1e-9)
    return a, b, c, report.text(dt)


# --------------------------------------------------------------------------- ERA


def hankel_lags(samples: int, size: int = HANKEL_SIZE) -> tuple[NDArray[np.int_], NDArray]:
    """Row/column lags of the Hankel matrix and their quadrature weights.

    All lags 0 … L, L = ⌊(samples − 2)/2⌋, when they are at most ``size``; otherwise
    ``size``/2 consecutive lags followed by lags evenly spread up to L. The weights are
    those of the trapezoid rule on the lags (1 inside a run of consecutive lags, ½ at
    both ends), so that Σ w_ℓ f(ℓ) ≈ ∫₀ᴸ f.
    """
    if size < 4:
        raise FitError(f"hankel_size must be at least 4, not {size}")
    last = (samples - 2) // 2
    if last < 1:
        raise FitError(f"{samples} samples are too few for a Hankel matrix")
    if last + 1 <= size:
        lags = np.arange(last + 1)
    else:
        head = size // 2
        tail = np.round(np.linspace(head, last, size - head)).astype(int)
        lags = np.unique(np.concatenate([np.arange(head), tail]))
    edges = np.concatenate([[lags[0]], 0.5 * (lags[1:] + lags[:-1]), [lags[-1]]])
    return lags, np.diff(edges).astype(float)


def select_order(sigma: ArrayLike, tol: float, max_order: int = MAX_ORDER) -> int:
    """Smallest n with 2 Σ_{k>n} σ_k ≤ tol σ₁ (the ``imp2ss`` rule), at most ``max_order``.

    Examples
    --------
    >>> select_order([10.0, 5.0, 0.01, 0.001], tol=0.01)
    2
    """
    s = np.asarray(sigma, dtype=float)
    if s.size == 0 or s[0] <= 0:
        raise FitError("the Hankel matrix is zero: nothing to realize")
    if tol <= 0:
        raise FitError(f"tol must be positive, not {tol}")
    tail = np.concatenate([np.cumsum(s[::-1])[::-1], [0.0]])  # tail[n] = Σ_{k≥n} s_k
    n = int(np.flatnonzero(2.0 * tail <= tol * s[0])[0])
    return max(1, min(n, max_order, s.size))


def era(
    t: ArrayLike,
    k: ArrayLike,
    order: int | None = None,
    *,
    tol: float | None = None,
    zero_dc: bool = True,
    max_order: int = MAX_ORDER,
    hankel_size: int = HANKEL_SIZE,
) -> Realization:
    """Kung's Hankel-SVD realization (ERA) of a retardation function from its samples.

    Unneland (2007) eqs. 4.16–4.27 (Hankel matrix, SVD, shift), with the exact
    impulse-invariant conversion a = log(A_d)/Δt instead of the inverse Tustin of
    eqs. 4.28–4.31 (see the module docstring: no 1/Δt scaling error, D = 0, no frequency
    warping).

    Parameters
    ----------
    t
        Uniformly spaced times, s, t[0] ≥ 0 (usually 0).
    k
        K(t) at ``t`` (kg/s², kg·m/s², kg·m²/s²).
    order
        Number of states; default: chosen from the Hankel singular values with ``tol``.
    tol
        Order selection 2 Σ σ_tail ≤ tol σ₁ (default :data:`DEFAULT_TOL`); ignored when
        ``order`` is given.
    zero_dc
        Impose K(s = 0) = 0 (zero speed, Unneland (2007) eq. 3.48) by the smallest H₂
        change of c.
    max_order
        Upper bound of the order, selected or given.
    hankel_size
        Largest number of Hankel rows and columns (cost: one SVD of this size).

    Returns
    -------
    Realization
        Stable; its ``note`` says what was done to poles and to the DC gain.

    Raises
    ------
    FitError
        Non-uniform or too short grid, order above ``max_order`` or the number of Hankel
        rows, no usable mode. (An order above the numerical rank of the Hankel matrix is
        lowered to it, with a note.)

    Examples
    --------
    >>> t = np.arange(400) * 0.05
    >>> k = np.exp(-t) * (np.cos(np.sqrt(3) * t) - np.sin(np.sqrt(3) * t) / np.sqrt(3))
    >>> model = era(t, k, order=2)          # K(s) = s / (s² + 2s + 4), Unneland (2007) Ex. 3.1
    >>> np.sort_complex(model.poles()).round(6)
    array([-1.-1.732051j, -1.+1.732051j])
    """
    t, k, dt = _uniform_samples(t, k)
    lags, weights = hankel_lags(t.size, hankel_size)
    index = lags[:, None] + lags[None, :]
    w = np.sqrt(dt * weights)
    h0 = w[:, None] * k[index] * w[None, :]
    h1 = w[:, None] * k[index + 1] * w[None, :]
    # h0 is symmetric (same lags for rows and columns): its SVD is its eigen-decomposition
    # h0 = Q diag(μ) Qᵀ with σ = |μ|, U = Q, V = Q sign(μ) (eigh is twice as fast as svd)
    mu, q = np.linalg.eigh(h0)
    rank_order = np.argsort(-np.abs(mu))
    mu, q = mu[rank_order], q[:, rank_order]
    sigma = np.abs(mu)
    u, vt = q, np.where(mu < 0, -1.0, 1.0)[:, None] * q.T
    if sigma[0] <= 0:
        raise FitError("the Hankel matrix of K(t) is zero: nothing to realize")
    if order is None:
        n = select_order(sigma, DEFAULT_TOL if tol is None else tol, max_order)
    else:
        n = _check_order(order, lags.size, max_order, f"{lags.size} Hankel rows")
    notes: list[str] = []
    rank = int(np.count_nonzero(sigma > sigma[0] * RANK_TOL))
    if n > rank:
        notes.append(
            f"order reduced from {n} to {rank}, the numerical rank of the Hankel matrix "
            f"(σ_{rank + 1}/σ_1 = {sigma[rank] / sigma[0]:.1e})"
        )
        n = rank
    root = np.sqrt(sigma[:n])
    observability = u[:, :n] * root  # rows c A_d^ℓ, weighted
    controllability = root[:, None] * vt[:n]  # columns A_d^ℓ b, weighted
    a_d = (observability.T @ h1 @ controllability.T) / np.outer(sigma[:n], sigma[:n])
    c_d = observability[0] / w[0]
    b_d = controllability[:, 0] / w[0]
    z, vectors = np.linalg.eig(a_d)
    if np.linalg.cond(vectors) < MAX_EIGENVECTOR_CONDITION:
        residues = (c_d @ vectors) * np.linalg.solve(vectors, b_d)
        a, b, c, text = _from_discrete_poles(t, k, dt, z, residues)
        notes.append(text)
    else:
        a, b, c = _logm_conversion(a_d, b_d, c_d, dt, t[0])
        notes.append("near-defective A_d: converted with the real matrix logarithm")
    return _finish(a, b, c, zero_dc=zero_dc, sigma=sigma, dt=dt, notes=notes, method="realization")


def _logm_conversion(
    a_d: NDArray, b_d: NDArray, c_d: NDArray, dt: float, t0: float
) -> tuple[NDArray, NDArray, NDArray]:
    """a = logm(A_d)/Δt for a near-defective A_d (repeated poles)."""
    z = np.linalg.eigvals(a_d)
    if np.any(np.abs(z) >= 1) or np.any(np.abs(np.angle(z)) > (1 - NYQUIST_MARGIN) * np.pi):
        raise FitError(
            "the discrete model is near-defective and has unstable or Nyquist poles "
            f"(z = {z}); lower the order or use prony()"
        )
    log = scipy.linalg.logm(a_d)
    a = np.real(log) / dt
    b = scipy.linalg.expm(-a * t0) @ b_d if t0 else b_d
    return a, b, c_d


# --------------------------------------------------------------------------- Prony


def prony(
    t: ArrayLike,
    k: ArrayLike,
    order: int,
    *,
    zero_dc: bool = True,
    iterations: int = PRONY_ITERATIONS,
    max_order: int = MAX_ORDER,
) -> Realization:
    """Prony's method: K(t_m) = Σ_r ρ_r z_rᵐ, poles by linear prediction.

    1. Linear prediction (Prony): the characteristic polynomial
       A(z) = 1 + α₁ z⁻¹ + … + α_n z⁻ⁿ solves k[m] = −Σ_i α_i k[m−i], m = n … M−1, in the
       least-squares sense.
    2. Refinement (``iterations`` > 0; Steiglitz & McBride 1965): the samples and a unit
       pulse are filtered by 1/A(z) of the previous iterate (its roots reflected into the
       unit circle) and the equation-error problem A(z) k = B(z) δ (numerator degree
       n − 1) is solved again. Its fixed points are the least-squares fits of the samples
       by the impulse response of B/A (the output error), which the plain linear
       prediction does not minimise: on the tanker's heave and pitch kernels the
       refinement is the difference between R²(A) ≈ 0.8 and ≈ 0.999. ``iterations=0``
       gives the classical Prony method.
    3. The roots z_r of A give λ_r = log(z_r)/Δt (Nyquist and unstable roots handled as in
       :func:`era`); the residues ρ_r of K(t) = Σ ρ_r e^{λ_r t} are fitted to all samples by
       linear least squares; the model is realized in real modal form
       (:func:`modal_realization`), D = 0, and the zero at s = 0 imposed as in :func:`era`.

    Parameters
    ----------
    t, k
        Uniformly spaced times (s) and K(t).
    order
        Number of poles n (states).
    zero_dc
        Impose K(s = 0) = 0.
    iterations
        Steiglitz–McBride iterations (stops earlier when the polynomial settles).
    max_order
        Upper bound of ``order``.

    Returns
    -------
    Realization
        With empty ``hankel_singular_values``.

    Examples
    --------
    >>> t = np.arange(400) * 0.05
    >>> k = np.exp(-t) * (np.cos(np.sqrt(3) * t) - np.sin(np.sqrt(3) * t) / np.sqrt(3))
    >>> np.sort_complex(prony(t, k, 2).poles()).round(6)
    array([-1.-1.732051j, -1.+1.732051j])
    """
    t, k, dt = _uniform_samples(t, k)
    n = _check_order(order, (t.size - 1) // 2, max_order, f"{t.size} samples")
    if iterations < 0:
        raise FitError(f"iterations must be ≥ 0, not {iterations}")
    lagged = _lagged(k, n, 1)[n:]
    scale = np.linalg.norm(lagged, axis=0)
    scale[scale == 0] = 1.0
    alpha = np.linalg.lstsq(lagged / scale, -k[n:], rcond=None)[0] / scale
    poly, done = _steiglitz_mcbride(k, np.concatenate([[1.0], alpha]), iterations)
    notes = [f"Steiglitz–McBride refinement: {done} iteration(s)" if done else ""]
    z = np.roots(poly)
    z = np.where(np.abs(z.imag) <= 1e-12 * np.abs(z), z.real + 0j, z)
    a, b, c, text = _from_discrete_poles(t, k, dt, z, None)
    notes.append(text)
    return _finish(a, b, c, zero_dc=zero_dc, sigma=np.empty(0), dt=dt, notes=notes, method="prony")


def _lagged(x: NDArray, count: int, first: int) -> NDArray:
    """Matrix whose column j is x delayed by first + j samples (zeros before the start)."""
    padded = np.concatenate([np.zeros(first + count), x])
    index = np.arange(x.size)[:, None] - np.arange(first, first + count)[None, :]
    return padded[index + first + count]


def _stable_polynomial(poly: NDArray) -> NDArray:
    """The polynomial with its roots outside (or on) the unit circle reflected inside."""
    roots = np.roots(poly)
    radius = np.abs(roots)
    if np.all(radius < 1.0):
        return poly
    inside = np.where(radius >= 1.0, roots / np.maximum(radius, 1.0) ** 2, roots)
    inside = np.where(np.abs(inside) > 1.0 - 1e-6, inside * (1.0 - 1e-6), inside)
    return np.real(np.poly(inside))


def _steiglitz_mcbride(k: NDArray, poly: NDArray, iterations: int) -> tuple[NDArray, int]:
    """Refine the denominator A(z) of an impulse-response model B(z)/A(z) of ``k``.

    Returns the polynomial and the number of iterations done; an iteration producing
    non-finite numbers stops the refinement with the previous polynomial.
    """
    from scipy.signal import lfilter  # lazily: scipy.signal takes 0.5 s to import

    n = poly.size - 1
    impulse = np.zeros(k.size)
    impulse[0] = 1.0
    done = 0
    for _ in range(iterations):
        denominator = _stable_polynomial(poly)
        filtered = lfilter([1.0], denominator, k)
        pulse = lfilter([1.0], denominator, impulse)
        regressors = np.hstack([-_lagged(filtered, n, 1), _lagged(pulse, n, 0)])
        scale = np.linalg.norm(regressors, axis=0)
        scale[scale == 0] = 1.0
        theta = np.linalg.lstsq(regressors / scale, filtered, rcond=None)[0] / scale
        new = np.concatenate([[1.0], theta[:n]])
        if not np.all(np.isfinite(new)):
            break
        done += 1
        settled = np.linalg.norm(new - poly) <= 1e-10 * np.linalg.norm(poly)
        poly = new
        if settled:
            break
    return poly, done
