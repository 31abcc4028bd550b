"""Enforcement of MIMO passivity by residue perturbation, and pole augmentation
(Unneland (2007) §3.2).

**Enforcement** (:func:`enforce_passivity`). The output vectors c of the coupling models
(their residues) are perturbed, poles kept, the zero K(0) = 0 kept, each symmetric pair
K_ij = K_ji perturbed alike. Where λ_min < 0 the constraint is linearised in δc,
λ + vᵀ(δΦ)v ≥ margin, and the smallest change in the data-weighted least-squares sense
— the decrease of the R² of A(ω) and of B(ω) of each coupling, to first order — is found
by least-distance programming (Lawson & Hanson's LDP through NNLS). The test is run again
and the step repeated until it passes.

Residue changes alone cannot reshape K outside the data range: :func:`augment_for_passivity`
adds a real pole, residue zero, on the diagonal terms that take part in a violation. The
test it acts on (:func:`passivity_test`) is in :mod:`cummins.radiation.passivity.check`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import nnls

from cummins.errors import FitError
from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.radiation.passivity.check import (
    PASSIVITY_TOLERANCE,
    PassivityReport,
    ViolationBand,
    dof_scaling,
    passivity_test,
)
from cummins.validation import guard_finite, guard_radiation_model

#: Enforcement asks for λ_min ≥ ENFORCEMENT_MARGIN × (the local largest eigenvalue) at the
#: frequencies it corrects, so that the result is not passive by a rounding error only.
ENFORCEMENT_MARGIN = 1e-4
#: Weight of the R² loss of K(t) against those of A and B in the enforcement objective:
#: a guard against a change that reshapes K(jω) beyond the data, not a target.
KERNEL_WEIGHT = 0.05
#: Constraint points spread over each violation band, besides its worst point.
POINTS_PER_BAND = 6


@dataclass(frozen=True)
class PassivityEnforcement:
    """Result of :func:`enforce_passivity`.

    Attributes
    ----------
    model
        The passive model (the input model when it was passive already).
    before, after
        :class:`PassivityReport` of the input and of the result.
    iterations
        Linearised corrections made.
    relative_change
        Per coupling label (``"Heave"``, ``"Sway-Roll"``): ‖δK‖/‖K‖ on the weighting grid.
    """

    model: RadiationModel
    before: PassivityReport
    after: PassivityReport
    iterations: int
    relative_change: dict[str, float]


def enforce_passivity(
    model: RadiationModel,
    *,
    omega: ArrayLike | None = None,
    added_mass: ArrayLike | None = None,
    damping: ArrayLike | None = None,
    time: ArrayLike | None = None,
    kernel: ArrayLike | None = None,
    importance: Callable[[CouplingModel], float] | None = None,
    motion_weight: Callable[[CouplingModel], NDArray | None] | None = None,
    max_iterations: int = 30,
) -> PassivityEnforcement:
    """Make the MIMO model passive by the smallest data-weighted change of the residues.

    The poles, K(0) = 0 and the symmetry K_ij = K_ji are kept; the output vectors c of
    the couplings change by δc = N z (N spans the changes that keep K(0)). The total
    change z from the input model minimises the data misfit

        Σ_couplings Σ_ω (B̂ + δB − B)² / SS_B + (Â + δA − A)² / SS_A,

    (SS: the sum of squares of the data about their mean, so the objective is the sum of
    the couplings' losses of R² of A and of B, plus :data:`KERNEL_WEIGHT` times that of
    K(t) when it is given) subject to the passivity constraints
    linearised at every iteration, λ + vᵀ δΦ v ≥ margin, at the frequencies where the
    current model violates (the worst point of each band and up to
    ``points_per_band`` more) and on the limits ω → 0, ∞; all constraints found so far are
    kept. Each least-squares problem with linear inequality constraints is solved exactly
    as a least-distance programme (:func:`constrained_least_squares`).

    Parameters
    ----------
    model
        A stable :class:`~cummins.radiation.model.RadiationModel`.
    omega
        Frequencies (rad/s) of the data: the fitted frequencies. By default a log grid
        over the model's ``omega_fit_min``…``omega_fit_max`` attributes (else over its
        pole range), with the model itself as the data.
    added_mass, damping
        The data A(ω), B(ω), shape (len(omega), n_dofs, n_dofs), symmetric. Without them
        the model's own response is the reference: the change itself is minimised.
    time, kernel
        K(t) of the data (``kernel``, shape (len(time), n_dofs, n_dofs)): its misfit
        (δK(t)/√SS_K) joins the objective, so that a change shaping K(jω) outside the
        data range does not spoil the retardation function.
    importance
        Weight of each coupling's loss in the objective (default 1 for all). The fit
        gives 1/(R² − target) so that couplings close to their R² target are changed
        least.
    motion_weight
        Per coupling, the weight W(ω) on ``omega`` of its complex error |K̂ − K| in the
        motions (:mod:`cummins.radiation.fit.motion`, already divided by the coupling's error
        budget), or None: rows W·δK join that coupling's misfit, so that the change
        avoids the frequencies where the motions are sensitive.
    max_iterations
        Linearised corrections allowed before giving up.

    Returns
    -------
    PassivityEnforcement

    Raises
    ------
    FitError
        When the model is unstable, or is still not passive after ``max_iterations``
        corrections (the message names the worst frequency), or when the model or the
        data hold non-finite or absurdly scaled values (naming the DOF pair).
    """
    guard_radiation_model(model)
    for name, values in (("added_mass", added_mass), ("damping", damping), ("kernel", kernel)):
        if values is not None:
            guard_finite(values, name, FitError, model.dofs)
    if not model.is_stable():
        raise FitError("passivity enforcement needs a stable model")
    before = passivity_test(model)
    if before.passive:
        return PassivityEnforcement(model, before, before, 0, {})
    if model.blocks:
        raise FitError(
            "the model holds blocks of common-pole models, which this enforcement does not "
            "change (it moves the residues of single couplings)",
            hint="a block is made passive when it is fitted (cummins.radiation.fit.vector); refit "
            "the data with fit_radiation",
        )
    w = fit_range_grid(model) if omega is None else np.asarray(omega, dtype=float)
    groups = _coupling_groups(model)
    bases = [_perturbation_basis(model.couplings[g[0]]) for g in groups]
    misfit = []
    for group, basis in zip(groups, bases, strict=True):
        jac, y = _misfit(model, group, basis, w, added_mass, damping, time, kernel)
        extra = None if motion_weight is None else motion_weight(model.couplings[group[0]])
        if extra is not None:
            jac_m, y_m = _motion_misfit(model, group, basis, w, added_mass, damping, extra)
            jac, y = np.vstack([jac, jac_m]), np.concatenate([y, y_m])
        weight = 1.0 if importance is None else float(importance(model.couplings[group[0]]))
        misfit.append((np.sqrt(weight) * jac, np.sqrt(weight) * y))
    scale = dof_scaling(model)
    size = sum(basis.shape[1] for basis in bases)
    z = np.zeros(size)
    rows: list[NDArray] = []
    rhs: list[float] = []
    current, report, done = model, before, 0
    while not report.passive:
        if done >= max_iterations:
            raise FitError(
                f"the model is still not passive after {done} corrections (λ_min "
                f"{report.min_eigenvalue:.3g} at {report.worst_omega:.4g} rad/s)",
                hint="refit with a lower order or a narrower frequency range "
                "(fit_radiation(..., max_order=...)), or check the data for "
                "non-physical damping (cummins check)",
            )
        new_rows, new_rhs = _constraints(current, report, groups, bases, scale)
        if not new_rows:
            raise FitError(
                f"passivity cannot be enforced: the violation ({report.min_eigenvalue:.3g} at "
                f"{report.worst_omega:.4g} rad/s) does not depend on the residues"
            )
        # linearised at the current z: g·(z_new − z) ≥ h  ⇔  g·z_new ≥ h + g·z
        rows.extend(new_rows)
        rhs.extend(h + float(g @ z) for g, h in zip(new_rows, new_rhs, strict=True))
        z = constrained_least_squares(misfit, np.array(rows), np.array(rhs))
        current = _apply_step(model, groups, bases, z)
        report = passivity_test(current)
        done += 1
    change = {_group_label(model, g): _relative_change(model, current, g[0], w) for g in groups}
    return PassivityEnforcement(current, before, report, done, change)


def augment_for_passivity(
    model: RadiationModel, report: PassivityReport, *, weight: float = 0.2
) -> RadiationModel:
    """The model with one extra real pole, residue zero (the response is unchanged), on
    each diagonal term that takes part in a violation: at the worst frequency of each
    band, on the DOFs carrying more than ``weight`` of the offending eigenvector.

    Residue changes alone cannot reshape K outside the data range (beyond ω_max, below
    ω_min) without spoiling the fit inside it; a pole placed where the model violates
    gives :func:`enforce_passivity` that freedom for one state per DOF and band.
    """
    scale = dof_scaling(model)
    keep = np.flatnonzero(scale > 0)
    extra: dict[int, list[float]] = {}
    for band in _distinct(report.bands):
        k = model.response(np.array([band.worst_omega]))[0]
        k = k[np.ix_(keep, keep)] * scale[keep][:, None] * scale[keep][None, :]
        _, vec = np.linalg.eigh(k + k.conj().T)
        share = np.abs(vec[:, 0]) ** 2
        for n in np.flatnonzero(share > weight):
            extra.setdefault(int(keep[n]), []).append(band.worst_omega)
    couplings = list(model.couplings)
    for n, k in enumerate(couplings):
        if k.influenced != k.radiating or k.influenced not in extra:
            continue
        poles = [w for w in extra[k.influenced] if not np.any(np.isclose(-k.poles().real, w))]
        if not poles:
            continue
        m = len(poles)
        a = scipy.linalg.block_diag(k.a, -np.diag(poles))
        b = np.r_[k.b, np.ones(m)]
        c = np.r_[k.c, np.zeros(m)]
        note = "; ".join(filter(None, [k.note, f"{m} pole(s) added for MIMO passivity"]))
        couplings[n] = replace(k, a=a, b=b, c=c, note=note)
    return replace(model, couplings=tuple(couplings))


# ----------------------------------------------------------------------- internals


def _distinct(bands) -> list[ViolationBand]:
    """The bands less those whose worst point repeats an earlier one's (within 10⁻⁴): a
    zero of Φ where λ_min touches zero, split in two by rounding, gives two bands with
    one minimum at their shared edge — on one BLAS thread count and not on another (the
    cylinder: 62 or 54 states). Augmentation and constraints use each minimum once."""
    out: list[ViolationBand] = []
    for band in bands:
        if any(abs(band.worst_omega - b.worst_omega) <= 1e-4 * b.worst_omega for b in out):
            continue
        out.append(band)
    return out


def fit_range_grid(model: RadiationModel, points: int = 200) -> NDArray:
    """Log grid over the model's fitted range (``omega_fit_min`` … ``omega_fit_max``
    attributes), else over a decade beyond its pole magnitudes."""
    lo, hi = model.attrs.get("omega_fit_min"), model.attrs.get("omega_fit_max")
    if lo is None or hi is None:
        poles = np.concatenate(
            [k.poles() for k in model.couplings if k.order]
            + [b.poles() for b in model.blocks if b.order]
        )
        lo, hi = np.abs(poles).min() / 10, np.abs(poles).max() * 10
    return np.geomspace(float(lo), float(hi), points)


def _coupling_groups(model: RadiationModel) -> list[list[int]]:
    """Indices of the couplings perturbed together: a symmetric pair (identical a, b, c)
    is one group."""
    groups: list[list[int]] = []
    used: set[int] = set()
    for n, k in enumerate(model.couplings):
        if n in used or not k.order:
            continue
        group = [n]
        for m, other in enumerate(model.couplings):
            if (
                m != n
                and m not in used
                and other.influenced == k.radiating
                and other.radiating == k.influenced
                and k.influenced != k.radiating
                and other.a.shape == k.a.shape
                and np.array_equal(other.a, k.a)
                and np.array_equal(other.b, k.b)
                and np.array_equal(other.c, k.c)
            ):
                group.append(m)
        used.update(group)
        groups.append(group)
    return groups


def _group_label(model: RadiationModel, group: Sequence[int]) -> str:
    k = model.couplings[group[0]]
    i, j = sorted((k.influenced, k.radiating))
    return model.dofs[i] if i == j else f"{model.dofs[i]}-{model.dofs[j]}"


def _perturbation_basis(coupling) -> NDArray:
    """Columns N spanning the changes δc = N z that keep K(0) = −c a⁻¹ b unchanged."""
    g0 = np.linalg.solve(coupling.a, coupling.b)
    q, _ = np.linalg.qr(np.c_[g0, np.eye(g0.size)])
    return q[:, 1:]


def _transfer_vectors(coupling, w: NDArray) -> NDArray:
    """g(ω) = (jωI − a)⁻¹ b for each ω, shape (len(w), n): K = c·g."""
    lam, v = np.linalg.eig(coupling.a)
    if np.linalg.cond(v) < 1e10:
        right = np.linalg.solve(v, coupling.b)
        return ((right[None, :] / (1j * w[:, None] - lam[None, :])) @ v.T).astype(complex)
    n = coupling.a.shape[0]
    out = np.empty((w.size, n), dtype=complex)
    for k, wk in enumerate(w):
        out[k] = np.linalg.solve(1j * wk * np.eye(n) - coupling.a, coupling.b)
    return out


def _misfit(model, group, basis, w, added_mass, damping, time, kernel):
    """(J, y) with the data misfit of the coupling = ‖J z + y‖² for δc = N z: rows
    δB/√SS_B and δA/√SS_A per frequency, δK(t)/√SS_K per time (when K(t) of the data is
    given); y the current residuals likewise."""
    k = model.couplings[group[0]]
    i, j = k.influenced, k.radiating
    g = _transfer_vectors(k, w) @ basis
    response = k.frequency_response(w)
    a_model, b_model = response.imag / w, response.real
    if added_mass is not None and damping is not None:
        a_data = np.asarray(added_mass)[:, i, j] - model.added_mass_inf[i, j]
        b_data = np.asarray(damping)[:, i, j]
    else:
        a_data, b_data = a_model, b_model
    parts = [(g.real, b_model, b_data), (g.imag / w[:, None], a_model, a_data)]
    if time is not None and kernel is not None:
        t = np.asarray(time, dtype=float)
        parts.append((_impulse_vectors(k, t) @ basis, k.impulse_response(t), kernel[:, i, j]))
    rows, residuals = [], []
    for n, (jac, fitted, data) in enumerate(parts):
        ss = max(float(np.sum((data - data.mean()) ** 2)), 1e-300) / (
            KERNEL_WEIGHT if n == 2 else 1.0
        )
        rows.append(jac / np.sqrt(ss))
        residuals.append((fitted - data) / np.sqrt(ss))
    return np.vstack(rows), np.concatenate(residuals)


def _motion_misfit(model, group, basis, w, added_mass, damping, weight):
    """(J, y): rows W·Re δK and W·Im δK of the coupling (see ``motion_weight`` of
    :func:`enforce_passivity`), y the current W·(K̂ − K)."""
    k = model.couplings[group[0]]
    i, j = k.influenced, k.radiating
    g = _transfer_vectors(k, w) @ basis
    response = k.frequency_response(w)
    if added_mass is not None and damping is not None:
        data = np.asarray(damping)[:, i, j] + 1j * w * (
            np.asarray(added_mass)[:, i, j] - model.added_mass_inf[i, j]
        )
    else:
        data = response
    weight = np.asarray(weight, dtype=float)
    rows = np.vstack([weight[:, None] * g.real, weight[:, None] * g.imag])
    residual = weight * (response - data)
    return rows, np.concatenate([residual.real, residual.imag])


def _impulse_vectors(coupling, t: NDArray) -> NDArray:
    """e^{a t} b for each t, shape (len(t), n): K(t) = c·(e^{a t} b)."""
    lam, v = np.linalg.eig(coupling.a)
    if np.linalg.cond(v) < 1e10:
        right = np.linalg.solve(v, coupling.b)
        return np.real((right[None, :] * np.exp(np.outer(t, lam))) @ v.T)
    return np.array([scipy.linalg.expm(coupling.a * tk) @ coupling.b for tk in t])


def _constraints(model, report, groups, bases, scale):
    """Linearised rows g·δz ≥ h: at the worst point of each violation band and at
    :data:`POINTS_PER_BAND` points spread over it (where λ < margin), and on the limits."""
    rows, rhs = [], []
    keep = np.flatnonzero(scale > 0)
    points = []
    for band in _distinct(report.bands):
        lo = band.omega_low if band.omega_low > 0 else band.worst_omega / 100.0
        hi = band.omega_high if np.isfinite(band.omega_high) else band.worst_omega * 100.0
        points.extend([band.worst_omega, *np.geomspace(lo, hi, POINTS_PER_BAND + 2)[1:-1]])
    points = np.asarray(points, dtype=float)
    responses = model.response(points) if points.size else np.empty((0, 0, 0))
    transfer = {
        n: _transfer_vectors(model.couplings[n], points) @ basis
        for group, basis in zip(groups, bases, strict=True)
        for n in group
    }
    for p in range(points.size):
        k = responses[p][np.ix_(keep, keep)] * scale[keep][:, None] * scale[keep][None, :]
        lam, vec = np.linalg.eigh(k + k.conj().T)
        local = max(float(np.abs(lam).max()), np.finfo(float).tiny)
        for e in range(lam.size):
            if lam[e] >= ENFORCEMENT_MARGIN * local:
                break
            v = np.zeros(len(model.dofs), dtype=complex)
            v[keep] = vec[:, e] * scale[keep]
            row = []
            for group in groups:
                total = 0.0
                for n in group:
                    c = model.couplings[n]
                    weight = np.conj(v[c.influenced]) * v[c.radiating]
                    total = total + 2.0 * np.real(weight * transfer[n][p])
                row.append(np.broadcast_to(total, transfer[group[0]][p].shape))
            rows.append(np.concatenate(row))
            rhs.append(ENFORCEMENT_MARGIN * local - lam[e])
    if report.high_frequency < -PASSIVITY_TOLERANCE:
        _limit_rows(model, groups, bases, scale, keep, rows, rhs, high=True)
    if report.low_frequency < -PASSIVITY_TOLERANCE:
        _limit_rows(model, groups, bases, scale, keep, rows, rhs, high=False)
    return rows, rhs


def _limit_vector(coupling, high: bool) -> NDArray:
    """x with the coupling's limit coefficient = c·x: −a b (ω → ∞), a⁻³ b (ω → 0)."""
    if high:
        return -(coupling.a @ coupling.b)
    return np.linalg.solve(
        coupling.a, np.linalg.solve(coupling.a, np.linalg.solve(coupling.a, coupling.b))
    )


def _limit_rows(model, groups, bases, scale, keep, rows, rhs, *, high: bool) -> None:
    """Rows for the limits −(CAB + (CAB)ᵀ) ⪰ 0 (ω → ∞) and CA⁻³B + (CA⁻³B)ᵀ ⪰ 0 (ω → 0)."""
    n = len(model.dofs)
    matrix = np.zeros((n, n))
    for k in model.couplings:
        if k.order:
            matrix[k.influenced, k.radiating] += k.c @ _limit_vector(k, high)
    sub = matrix[np.ix_(keep, keep)] * scale[keep][:, None] * scale[keep][None, :]
    lam, vec = np.linalg.eigh(sub + sub.T)
    local = max(float(np.abs(lam).max()), np.finfo(float).tiny)
    for e in range(lam.size):
        if lam[e] >= ENFORCEMENT_MARGIN * local:
            break
        v = np.zeros(n)
        v[keep] = vec[:, e] * scale[keep]
        row = []
        for group, basis in zip(groups, bases, strict=True):
            total = np.zeros(basis.shape[1])
            for m in group:
                c = model.couplings[m]
                total += 2.0 * v[c.influenced] * v[c.radiating] * (_limit_vector(c, high) @ basis)
            row.append(total)
        rows.append(np.concatenate(row))
        rhs.append(ENFORCEMENT_MARGIN * local - lam[e])


def constrained_least_squares(misfit, g: NDArray, h: NDArray) -> NDArray:
    """z minimising Σ_k ‖J_k z_k + y_k‖² subject to G z ≥ h (Lawson & Hanson ch. 23).

    With J = QR per block and x = Rz + Qᵀy the problem becomes the least-distance
    programme min ‖x‖ s.t. (G R⁻¹) x ≥ h + G R⁻¹ Qᵀy, solved through the NNLS problem
    min ‖E u − f‖, E = [Fᵀ; eᵀ], f = (0, …, 0, 1), u ≥ 0 (F x ≥ e the constraints).
    """
    return least_distance(misfit, g, h)[0]


@dataclass(frozen=True)
class FactoredMisfit:
    """The misfit Σ_k ‖J_k z_k + y_k‖² of :func:`least_distance` factored once: J_k = Q_k
    R_k (R_k with a ridge where its diagonal vanishes) and Q_kᵀ y_k, for a programme
    solved many times with the same misfit and more constraints."""

    r_all: NDArray
    shift: NDArray

    def solve(self, rhs: NDArray, trans: str = "N") -> NDArray:
        """R⁻¹ rhs (``trans="T"``: R⁻ᵀ rhs), rhs (n, …). (One solve with the
        block-diagonal R: the blocks one by one round differently, and the order search
        branches on the result.)"""
        return scipy.linalg.solve_triangular(self.r_all, rhs, trans=trans, check_finite=False)

    def transformed(self, g: NDArray) -> NDArray:
        """G R⁻¹ of constraint rows G (R upper triangular, block-diagonal)."""
        return self.solve(np.asarray(g).T, trans="T").T

    def transformed_rows(self, g: NDArray) -> NDArray:
        """:meth:`transformed` of rows G (m, n) to be kept for later programmes, with more
        rows added: a single row is solved as two (a one-column solve rounds differently
        from the many-column one that :func:`least_distance` makes of all its rows)."""
        g = np.asarray(g)
        if g.shape[0] == 1:
            return self.transformed(np.vstack([g, g]))[:1]
        return self.transformed(g)


def factored_misfit(misfit) -> FactoredMisfit:
    """:class:`FactoredMisfit` of ``[(J_k, y_k)]``."""
    if isinstance(misfit, FactoredMisfit):
        return misfit
    r_blocks, qty = [], []
    for jac, y in misfit:
        q, r = np.linalg.qr(jac)
        ridge = 1e-8 * max(float(np.abs(r).max()), 1e-300)
        r = r + ridge * np.eye(r.shape[0]) * (np.abs(np.diag(r)) < ridge)
        r_blocks.append(r)
        qty.append(q.T @ y)
    return FactoredMisfit(scipy.linalg.block_diag(*r_blocks), np.concatenate(qty))


def least_distance(
    misfit,
    g: NDArray | None,
    h: NDArray,
    transformed: NDArray | None = None,
    start: NDArray | None = None,
) -> tuple[NDArray, NDArray[np.bool_]]:
    """:func:`constrained_least_squares`, and which constraints hold with equality at the
    solution (their NNLS multiplier u is positive): the others can be left out of the next
    linearisation without changing its solution. ``misfit``: ``[(J_k, y_k)]`` or its
    :func:`factored_misfit` (factored once for many programmes). ``transformed``: G R⁻¹
    when known (the rows kept from earlier programmes: :meth:`FactoredMisfit.transformed_rows`
    of each batch; the triangular solves of all rows at every programme were a tenth of
    an enforcement's time). ``g`` is not read when ``transformed`` holds more than one
    row (it may be None then). ``start``: a boolean mask of the rows likely to bind
    (those that bound in the last programme of an enforcement, and its new rows): the
    NNLS is solved on those alone, then on those it violates too
    (:func:`working_set_nnls`)."""
    z, u = least_distance_multipliers(misfit, g, h, transformed, start)
    return z, u > 0


def least_distance_multipliers(
    misfit,
    g: NDArray | None,
    h: NDArray,
    transformed: NDArray | None = None,
    start: NDArray | None = None,
    warm: NDArray | None = None,
) -> tuple[NDArray, NDArray]:
    """:func:`least_distance` with the NNLS multipliers u themselves (one per row) in
    place of u > 0. ``warm``: the multipliers of the last programme when this one holds
    its rows first, the same misfit and the same right-hand sides, and rows more (an
    enforcement's iterations with the misfit frozen): the NNLS is continued from them
    (:func:`warm_nnls`), scipy's from ``start`` when that gives up."""
    factored = factored_misfit(misfit)
    shift = factored.shift
    if transformed is not None and len(transformed) > 1:
        f = np.ascontiguousarray(transformed)
    else:  # one row: the one-column solve, as ever
        f = factored.transformed(g)  # G R⁻¹
    e = h + f @ shift
    norms = np.linalg.norm(f, axis=1)
    norms[norms == 0] = 1.0
    f, e = f / norms[:, None], e / norms
    n = f.shape[1]
    matrix = np.vstack([f.T, e[None, :]])
    target = np.zeros(n + 1)
    target[-1] = 1.0
    u = None if warm is None else warm_nnls(matrix, target, warm)
    if u is None and start is None:
        u, _ = nnls(matrix, target, maxiter=50 * matrix.shape[1])
    elif u is None:
        u = working_set_nnls(matrix, target, start)
    residual = matrix @ u - target
    if abs(residual[-1]) < 1e-12:
        raise FitError("passivity enforcement: the linearised constraints are infeasible")
    x = -residual[:n] / residual[-1]
    return factored.solve(x - shift), u


#: :func:`working_set_nnls`: a column left out is optimal at zero while its gradient
#: component is below WORKING_SET_TOLERANCE × its norm × the target's norm.
WORKING_SET_TOLERANCE = 1e-12


def working_set_nnls(matrix: NDArray, target: NDArray, working: NDArray) -> NDArray:
    """u ≥ 0 minimising ‖E u − f‖ (E ``matrix``, f ``target``), solved on the columns of
    the boolean mask ``working`` alone, then with the columns left out whose gradient
    component Eⱼᵀ(f − E u) is positive added, until there is none: u is then optimal for
    all columns (the Karush–Kuhn–Tucker conditions of NNLS in Lawson & Hanson (1974) ch. 23
    Thm 23.4, hold for the whole E). In a least-distance programme (:func:`least_distance`)
    a column is a constraint and a positive gradient component a violated one, so this is
    the programme solved on the constraints likely to bind, the others checked after.

    Each solve is scipy's :func:`scipy.optimize.nnls` (Lawson & Hanson's algorithm), whose
    cost grows with the columns: an enforcement's programme holds a few hundred, of which
    a few dozen bind.
    """
    working = np.asarray(working, dtype=bool).copy()
    norms = np.linalg.norm(matrix, axis=0)
    tolerance = WORKING_SET_TOLERANCE * norms * float(np.linalg.norm(target))
    u = np.zeros(matrix.shape[1])
    while True:
        columns = np.flatnonzero(working)
        u[:] = 0.0
        if columns.size:
            u[columns], _ = nnls(matrix[:, columns], target, maxiter=50 * columns.size)
        gradient = matrix.T @ (target - matrix @ u)
        violated = ~working & (gradient > tolerance)
        if not violated.any():
            return u
        working |= violated


#: :func:`warm_nnls` gives up (the caller solves the programme otherwise) after this
#: many changes of its passive set per column.
WARM_CHANGES = 3


def warm_nnls(matrix: NDArray, target: NDArray, warm: NDArray) -> NDArray | None:
    """u ≥ 0 minimising ‖E u − f‖ (E ``matrix``, f ``target``), continued from ``warm``:
    the solution for E's first columns (E and f otherwise the same). None when it gives
    up: a Cholesky factorisation fails (columns dependent to rounding) or the passive
    set changes more than :data:`WARM_CHANGES` times per column.

    Lawson & Hanson's NNLS (1974, ch. 23, Algorithm NNLS) started at ``warm`` — optimal
    for the first columns, so a feasible point whose gradient is non-positive there —
    rather than at u = 0: each outer step takes the column of largest (normalised)
    gradient component Eⱼᵀ(f − E u) into the passive set P, the inner loop moves u towards
    the least-squares solution on P and drops the columns that reach zero. This is the
    dual view of Goldfarb & Idnani's (1983) active-set method for a sequence of
    least-distance programmes, each the last with constraints added: the constraints
    that bound stay bound, and only the new ones that the last solution violates are
    taken in, one at a time. Each least-squares solve on P is a Cholesky factorisation
    of the cross-products (EᵀE)_PP (Bro & De Jong's (1997) "fast NNLS"), of the size of
    P (RM3's refined block: 160 of 886 rows), the products of a column formed once, when
    it enters P; the optimality test uses E itself: at return u meets the
    Karush–Kuhn–Tucker conditions of NNLS (Lawson & Hanson Thm 23.4), every gradient
    component of a column out of P at most :data:`WORKING_SET_TOLERANCE` × ‖Eⱼ‖ × ‖f‖.
    """
    norms = np.maximum(np.linalg.norm(matrix, axis=0), np.finfo(float).tiny)
    tolerance = WORKING_SET_TOLERANCE * norms * float(np.linalg.norm(target))
    u = np.zeros(matrix.shape[1])
    u[: warm.size] = np.maximum(warm, 0.0)
    factor = _PassiveCholesky(matrix, np.flatnonzero(u > 0))
    if not factor.ok:
        return None
    projected = matrix.T @ target
    for _ in range(WARM_CHANGES * matrix.shape[1]):
        gradient = matrix.T @ (target - matrix @ u)
        violated = gradient > tolerance
        violated[factor.order] = False
        if not violated.any():
            return u
        if not factor.add(int(np.argmax(np.where(violated, gradient / norms, -np.inf)))):
            return None
        while True:  # inner loop: towards the least-squares solution on P
            columns = np.asarray(factor.order)
            trial = np.zeros_like(u)
            trial[columns] = factor.solve(projected[columns])
            at = np.flatnonzero(trial[columns] <= 0)
            if not at.size:
                u = trial
                break
            moving = columns[at]
            ratio = u[moving] / (u[moving] - trial[moving])
            u += float(ratio.min()) * (trial - u)
            gone = set(moving[ratio <= ratio.min()].tolist())
            gone.update(columns[u[columns] <= 0].tolist())
            for column in sorted(gone, key=factor.order.index, reverse=True):
                factor.remove(column)
            u[list(gone)] = 0.0
    return None


class _PassiveCholesky:
    """The Cholesky factor R (RᵀR = (EᵀE)_PP) of :func:`warm_nnls`'s passive set P, in
    the order its columns entered: a column added is a row and a column more of R (a
    triangular solve); a column removed leaves R upper Hessenberg from its place on,
    made triangular again by a QR factorisation of that trailing part (the updating of
    a factorisation, Golub & Van Loan (2013) §6.5): O(|P|²) a change rather than a new
    factorisation."""

    def __init__(self, matrix: NDArray, columns: NDArray):
        self.matrix = matrix
        self.order = [int(c) for c in columns]
        self.ok = True
        self.r = np.zeros((0, 0))
        if columns.size:
            sub = matrix[:, columns]
            try:
                self.r = scipy.linalg.cholesky(sub.T @ sub, lower=False, check_finite=False)
            except np.linalg.LinAlgError:
                self.ok = False

    def add(self, column: int) -> bool:
        """P with ``column`` (False when it depends on P's columns to rounding)."""
        e = self.matrix[:, column]
        k = len(self.order)
        r = np.zeros(0)
        if k:
            g = self.matrix[:, self.order].T @ e
            r = _triangular(self.r, g, transposed=True)
        rest = float(e @ e - r @ r)
        if not rest > ADDED_PIVOT * float(e @ e):
            return False
        grown = np.zeros((k + 1, k + 1))
        grown[:k, :k] = self.r
        grown[:k, k] = r
        grown[k, k] = np.sqrt(rest)
        self.r = grown
        self.order.append(column)
        return True

    def remove(self, column: int) -> None:
        """P without ``column``."""
        p = self.order.index(column)
        r = np.delete(self.r, p, axis=1)
        if p < r.shape[1]:
            trailing = scipy.linalg.qr(r[p:, p:], mode="r", check_finite=False)[0]
            r[p:, p:] = 0.0
            r[p : p + trailing.shape[0], p:] = trailing
        self.r = np.ascontiguousarray(np.triu(r[:-1]))
        del self.order[p]

    def solve(self, rhs: NDArray) -> NDArray:
        """(EᵀE)_PP⁻¹ rhs."""
        if not self.order:
            return np.zeros(0)
        return _triangular(self.r, _triangular(self.r, rhs, transposed=True), transposed=False)


def _triangular(r: NDArray, rhs: NDArray, transposed: bool) -> NDArray:
    """R⁻ᵀ rhs (``transposed``) or R⁻¹ rhs, R upper triangular: the LAPACK call (trtrs) of
    :func:`scipy.linalg.solve_triangular` with ``check_finite=False`` (the same numbers),
    without its checks and conversions, a tenth of a small solve's time: the passive set's
    updates make thousands of them (RM3's refinement)."""
    if r.flags.f_contiguous:
        x, info = _TRTRS(r, rhs, lower=0, trans=int(transposed))
    else:  # as scipy: the transposed system, trtrs expecting Fortran ordering
        x, info = _TRTRS(r.T, rhs, lower=1, trans=int(not transposed))
    if info != 0:
        raise np.linalg.LinAlgError(f"triangular solve: LAPACK trtrs info {info}")
    return x


_TRTRS = scipy.linalg.lapack.dtrtrs


#: :class:`_PassiveCholesky`: a column whose part orthogonal to P's columns has a squared
#: norm below ADDED_PIVOT × its own is taken as dependent on them.
ADDED_PIVOT = 1e-14


def _apply_step(model, groups, bases, step) -> RadiationModel:
    """The model with c ← c + N z for each group."""
    couplings = list(model.couplings)
    start = 0
    for group, basis in zip(groups, bases, strict=True):
        stop = start + basis.shape[1]
        delta = basis @ step[start:stop]
        for n in group:
            couplings[n] = replace(couplings[n], c=couplings[n].c + delta)
        start = stop
    return replace(model, couplings=tuple(couplings))


def _relative_change(before: RadiationModel, after: RadiationModel, n: int, w: NDArray) -> float:
    k0 = before.couplings[n].frequency_response(w)
    k1 = after.couplings[n].frequency_response(w)
    return float(np.linalg.norm(k1 - k0) / max(np.linalg.norm(k0), 1e-300))
