"""What the motions are sensitive to: the weights that turn an error of the fluid memory
K_ij(jω) into an error of the motion RAOs.

The frequency-domain equation of motion is Z(ω) X = F with
Z = −ω²(M_RB + A(ω)) + jω(B(ω) + B_v) + C (Falnes (2002) eq. 5.8; Unneland (2007)
eq. 2.30). A model K̂ = K + δK of K(jω) = B + jω(A − A∞) changes it by jω δK, and to
first order

    δX = −H (jω δK) X,     H = Z⁻¹,

so that the error of DOF m's motion in the load case c, relative to that motion's peak
over frequency (the issue-16 RAO error), is bounded by Σ_ij W_ij(ω) |δK_ij(ω)| with

    W_ij(ω) = max_{m, c} ω |H_mi(ω)| |X_jc(ω)| / max_ω' |X_mc(ω')|.

Bodies joined by joints move as X = T q (T the constraint basis, q the free
coordinates: :mod:`cummins.mechanics`) and power take-offs add their stiffness and
damping to Z: then H = T (Tᵀ Z T)⁻¹ Tᵀ, the same first-order relation, so a fit made
for a joined system spends its accuracy on the motions that system has
(:class:`JoinedMotion`).

The load cases c are the wave excitation at up to four headings when the data have it,
otherwise a unit force on each DOF. A symmetric pair K_ij = K_ji, modelled once, weighs
W_ij + W_ji. The weights are computed from the data themselves (A, B, inertia,
restoring, 2 % of critical damping on each DOF with restoring, as the scoreboard of
:mod:`cummins.radiation.fit.scorecard` uses), so the fit spends its accuracy where the motions
react: at the resonances, where B is small and the motion large.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.arrays import at_frequency
from cummins.hydrodb import dof_matrix

#: A motion (DOF, load case) whose peak is below this fraction of the largest peak of
#: the same DOF over the load cases, or of the largest peak of its kind (translations,
#: rotations, generalized modes) in the same load case, is not weighed: the sway of a
#: symmetric ship in head seas is rounding noise.
NEGLIGIBLE_MOTION = 1e-3


def dof_kind(label: str) -> str:
    """``"translation"``, ``"rotation"`` or ``"mode"``: DOFs whose motions share a unit."""
    from cummins.hydrodb import is_rigid_body_dof, is_rotation

    if not is_rigid_body_dof(label):
        return "mode"
    return "rotation" if is_rotation(label) else "translation"


def compared_motions(peak: NDArray, labels) -> NDArray[np.bool_]:
    """Which (DOF, load case) motions are compared, from their peaks (n_dofs, n_cases):
    see :data:`NEGLIGIBLE_MOTION`."""
    peak = np.asarray(peak, dtype=float)
    kinds = np.array([dof_kind(str(lab)) for lab in labels])
    out = (peak > 0) & (peak >= NEGLIGIBLE_MOTION * peak.max(axis=1, keepdims=True))
    for kind in set(kinds):
        rows = kinds == kind
        out[rows] &= peak[rows] >= NEGLIGIBLE_MOTION * peak[rows].max(axis=0, keepdims=True)
    return out


#: Headings of the wave excitation used as load cases.
HEADINGS = 4
#: Full-scale data (ω_max below this, rad/s) are judged from RAO_OMEGA_MIN up, as the
#: scoreboard does (:mod:`cummins.radiation.fit.scorecard`).
FULL_SCALE_OMEGA_MAX = 10.0
#: rad/s, see FULL_SCALE_OMEGA_MAX.
RAO_OMEGA_MIN = 0.15


@dataclass(frozen=True)
class JoinedMotion:
    """The mechanics the motions of a fit are those of (bodies joined, power take-offs).

    Attributes
    ----------
    basis
        (n, k) constraint basis T of the DOFs: X = T q (None: every DOF free).
    stiffness, damping
        (n, n) stiffness and damping added to the equation of motion (the power
        take-offs': :meth:`cummins.mechanics.Assembly.pto_matrices`), SI.
    """

    basis: NDArray[np.float64] | None
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]

    def describe(self) -> str:
        """One line: what the fit's motions are those of."""
        parts = []
        if self.basis is not None:
            parts.append(f"{self.basis.shape[1]} free coordinates of {self.basis.shape[0]} DOFs")
        if np.any(self.stiffness) or np.any(self.damping):
            parts.append("the power take-offs' stiffness and damping")
        return "the joined system's motions (" + ", ".join(parts or ["no joint"]) + ")"


def coordinate_labels(basis: NDArray, labels) -> tuple[str, ...]:
    """The label of each free coordinate of a constraint ``basis`` T (n, k): the DOF whose
    row of T is that column's unit vector (:func:`cummins.mechanics.constraints.null_space_basis`
    builds T so), else ``q1``, ``q2`` …"""
    out = []
    for c in range(basis.shape[1]):
        unit = np.zeros(basis.shape[1])
        unit[c] = 1.0
        rows = [r for r in range(basis.shape[0]) if np.array_equal(basis[r], unit)]
        out.append(str(labels[rows[0]]) if rows else f"q{c + 1}")
    return tuple(out)


def coordinate_dofs(basis: NDArray, labels) -> dict[str, tuple[str, ...]]:
    """The DOFs each free coordinate of a constraint ``basis`` moves (its own first): the
    rows of its column of T that are not zero."""
    names = coordinate_labels(basis, labels)
    out = {}
    for c, q in enumerate(names):
        moved = [str(labels[r]) for r in np.flatnonzero(basis[:, c])]
        out[q] = (q, *(d for d in moved if d != q))
    return out


def coordinate_r_squared(
    omega: NDArray,
    added_mass: NDArray,
    damping: NDArray,
    model,
    basis: NDArray,
    labels,
) -> dict[str, tuple[float, float]]:
    """R² of A and of B of each free coordinate q_c of a joined system: of its diagonal
    t_cᵀ A(ω) t_c and t_cᵀ B(ω) t_c (t_c the column of T), the model's against the
    data's (``added_mass``, ``damping`` (ω, n, n) at ``omega``). What the joined system's
    equation of motion holds of the fluid memory is Tᵀ K T (Falnes (2002) eq. 5.8 with
    X = T q): a body's DOF that moves only with others (a flap's surge and pitch about
    its hinge) is not judged alone by it."""
    from cummins.radiation.fit.frequency import r_squared

    k = model.response(omega)
    a_model = np.asarray(model.added_mass_inf)[None] + k.imag / omega[:, None, None]
    out = {}
    for c, name in enumerate(coordinate_labels(basis, labels)):
        t = basis[:, c]

        def along(values, t=t):
            return np.einsum("i,wij,j->w", t, values, t)

        out[name] = (
            r_squared(along(added_mass), along(a_model)),
            r_squared(along(damping), along(k.real)),
        )
    return out


def transfer(z: NDArray, basis: NDArray | None) -> NDArray:
    """H = Z⁻¹, or T (Tᵀ Z T)⁻¹ Tᵀ with a constraint ``basis`` T, of Z (ω, n, n); the
    pseudo-inverse where Z (Tᵀ Z T) is singular."""
    zz = z if basis is None else np.einsum("ni,wnm,mj->wij", basis, z, basis)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            h = np.linalg.inv(zz)
        except np.linalg.LinAlgError:
            h = np.linalg.pinv(zz)
    return h if basis is None else np.einsum("ni,wij,mj->wnm", basis, h, basis)


@dataclass(frozen=True)
class MotionSensitivity:
    """W_ij(ω) of the module docstring at the fitted frequencies.

    Attributes
    ----------
    omega
        Frequencies, rad/s.
    weight
        W, shape (len(omega), n, n), in 1/(force/velocity): W_ij |δK_ij| is the
        contribution of δK_ij to the relative motion error.
    load
        What the load cases are (``"wave excitation at 4 headings"``, ``"unit forces"``).
    """

    omega: NDArray[np.float64]
    weight: NDArray[np.float64]
    load: str
    rigid_body_mass: NDArray[np.float64] | None = None
    stiffness: NDArray[np.float64] | None = None
    viscous_damping: NDArray[np.float64] | None = None
    forces: NDArray[np.complex128] | None = None
    motions: NDArray[np.complex128] | None = None
    compared: NDArray[np.bool_] | None = None
    basis: NDArray[np.float64] | None = None

    def on(self, omega: NDArray) -> NDArray[np.float64]:
        """W at ``omega`` (the fitted frequencies: W itself; others interpolated)."""
        omega = np.asarray(omega, dtype=float)
        if omega.shape == self.omega.shape and np.allclose(omega, self.omega, rtol=1e-12):
            return self.weight
        n = self.weight.shape[1]
        out = np.empty((omega.size, n, n))
        for i in range(n):
            for j in range(n):
                out[:, i, j] = np.interp(omega, self.omega, self.weight[:, i, j])
        return out

    def model_error(self, model) -> tuple[float, NDArray[np.float64]]:
        """The relative motion error of a radiation model against the data's motions on
        the same load cases: max over cases of max_ω |X_model − X_data| / max_ω |X_data|,
        per DOF (the issue-16 RAO error at the fitted frequencies; on full-scale data,
        ω_max < 10 rad/s, those ≥ 0.15 rad/s), and its maximum."""
        rows = self.compared_frequencies()
        return self.error_of(model.response(self.omega[rows]), model.added_mass_inf)

    def compared_frequencies(self) -> NDArray[np.bool_]:
        """Which of :attr:`omega` the motion error compares (on full-scale data,
        ω_max < 10 rad/s, those ≥ 0.15 rad/s)."""
        w = self.omega
        return w >= RAO_OMEGA_MIN if w.max() < FULL_SCALE_OMEGA_MAX else np.ones(w.size, bool)

    def error_of(self, k, added_mass_inf) -> tuple[float, NDArray[np.float64]]:
        """:meth:`model_error` of K(jω) given at the compared frequencies
        (:meth:`compared_frequencies`), with its A∞."""
        rows = self.compared_frequencies()
        w = self.omega[rows]
        z = (
            -(w**2)[:, None, None] * (self.rigid_body_mass + np.asarray(added_mass_inf))
            + 1j * w[:, None, None] * (self.viscous_damping + k)
            + self.stiffness
        )
        if self.basis is None:
            x_model = np.linalg.solve(z, self.forces[rows])
        else:  # X = T (Tᵀ Z T)⁻¹ Tᵀ F
            t = self.basis
            q = np.linalg.solve(
                np.einsum("ni,wnm,mj->wij", t, z, t), np.einsum("ni,wnc->wic", t, self.forces[rows])
            )
            x_model = np.einsum("ni,wic->wnc", t, q)
        x_data = self.motions[rows]
        peak = np.abs(x_data).max(axis=0)
        ratio = np.abs(x_model - x_data).max(axis=0) / np.where(peak > 0, peak, 1.0)
        ratio = np.where(self.compared, ratio, 0.0)
        per_dof = ratio.max(axis=1)
        return float(per_dof.max()), per_dof

    def coupling_weight(self, i: int, j: int) -> NDArray[np.float64]:
        """W of the coupling (i, j) modelled once for both K_ij and K_ji."""
        if i == j:
            return self.weight[:, i, i]
        return self.weight[:, i, j] + self.weight[:, j, i]

    def coupling_error(self, i: int, j: int, delta_k: NDArray) -> float:
        """max_ω W_ij |δK_ij| (the coupling's share of the relative motion error)."""
        return float(np.max(self.coupling_weight(i, j) * np.abs(delta_k)))

    def motion_error(self, delta_k: NDArray) -> float:
        """First-order bound of the relative motion error of a whole model:
        max over m, c of max_ω |H (jω δK) X| / peak, evaluated with W (the triangle
        inequality over couplings): max_ω max_i Σ_j W_ij |δK_ij|."""
        return float(np.max(np.sum(self.weight * np.abs(delta_k), axis=2)))


def statically_unstable(data: xr.Dataset, joined: JoinedMotion | None = None) -> list[str]:
    """The DOFs in which the system whose motions judge a fit is statically unstable,
    as ``"body1__Pitch (C = -1.934e+06)"``: the negative eigenvalues of its restoring
    (hydrostatics, weight, moorings; with ``joined``, the power take-offs' springs, on
    the free coordinates: :func:`cummins.restoring.static_instability`). Such a system
    has no equilibrium to oscillate about, so its motion RAOs are no steady state to
    judge a model by (Capytaine's OSWEC flap floating freely: its pitch restoring is
    −1.9·10⁶ N·m/rad without the hinge). Empty without the restoring."""
    from cummins.restoring import restoring_matrix, static_instability

    if "hydrostatic_stiffness" not in data:
        return []
    c, basis = restoring_matrix(data), None
    if joined is not None:
        c, basis = c + joined.stiffness, joined.basis
    labels = [str(d) for d in data.influenced_dof.values]
    return [u.describe() for u in static_instability(c, labels, basis)]


def motion_sensitivity(
    data: xr.Dataset,
    *,
    damping_ratio: float = 0.02,
    added_mass_inf=None,
    joined: JoinedMotion | None = None,
) -> MotionSensitivity | None:
    """The motion sensitivity of ``data`` (fitted frequencies, one speed), or None when
    the data lack the inertia or the restoring; with ``joined``, of the motions of the
    joined system (constraints, power take-offs). The motions compared
    (:func:`compared_motions`) are judged by their peaks over the frequencies the error
    compares, as the scoreboard judges them (WEC-Sim's RM3 in head seas: the sway, no
    restoring, drifts at 0.02 rad/s to 0.4 % of the surge, 0.01 % from 0.15 rad/s up)."""
    from cummins.radiation.fit.scorecard import critical_damping

    if "inertia_matrix" not in data or "hydrostatic_stiffness" not in data:
        return None
    w = data.omega.values.astype(float)
    n = data.sizes["influenced_dof"]
    a = dof_matrix(data, "added_mass")
    b = dof_matrix(data, "radiation_damping")
    m = dof_matrix(data, "inertia_matrix")
    c = dof_matrix(data, "hydrostatic_stiffness")
    if "additional_stiffness" in data:
        c = c + dof_matrix(data, "additional_stiffness")
    b_v = np.diag(critical_damping(data, damping_ratio, added_mass_inf))
    if "additional_damping" in data and "omega" not in data.additional_damping.dims:
        b_v = b_v + dof_matrix(data, "additional_damping")
    basis = None
    if joined is not None:
        c = c + joined.stiffness
        b_v = b_v + joined.damping
        basis = joined.basis
    z = -(w**2)[:, None, None] * (m + a) + 1j * w[:, None, None] * (b + b_v) + c
    h = transfer(z, basis)
    forces, load = _load_cases(data, n)
    x = np.einsum("wmk,wkc->wmc", h, forces)  # (omega, dof, case)
    peak = np.abs(x).max(axis=0)  # (dof, case)
    judged = w >= RAO_OMEGA_MIN if w.max() < FULL_SCALE_OMEGA_MAX else np.ones(w.size, bool)
    compared = compared_motions(np.abs(x[judged]).max(axis=0), data.influenced_dof.values)
    inv_peak = np.where(compared, 1.0 / np.where(peak > 0, peak, 1.0), 0.0)
    # W_ij = max_{m,c} ω |H_mi| |X_jc| / P_mc
    abs_h = np.abs(h)  # (omega, m, i)
    abs_x = np.abs(x)  # (omega, j, c)
    weight = np.zeros((w.size, n, n))
    for mm in range(n):
        cases = np.flatnonzero(compared[mm])
        if not cases.size:
            continue
        scaled = abs_x[:, :, cases] * inv_peak[mm, cases][None, None, :]  # (omega, j, c)
        per_j = scaled.max(axis=2)  # (omega, j)
        weight = np.maximum(weight, abs_h[:, mm, :, None] * per_j[:, None, :])
    weight *= w[:, None, None]
    return MotionSensitivity(
        w, np.nan_to_num(weight), load, m, c, b_v, np.asarray(forces), x, compared, basis
    )


def _load_cases(data: xr.Dataset, n: int) -> tuple[NDArray[np.complex128], str]:
    """Forces (omega, dof, case): the excitation at up to :data:`HEADINGS` headings, or
    unit forces."""
    if "excitation_force" in data and "wave_direction" in data.excitation_force.dims:
        f = data.excitation_force
        beta = f.wave_direction.values
        if beta.size > HEADINGS:
            index = np.unique(np.round(np.linspace(0, beta.size - 1, HEADINGS)).astype(int))
            f = f.isel(wave_direction=index)
        other = [d for d in f.dims if d not in ("omega", "wave_direction")]
        values = f.transpose("omega", *other, "wave_direction").values
        if values.shape[:2] == (data.sizes["omega"], n) and np.all(np.isfinite(values)):
            return values.astype(
                complex
            ), f"wave excitation at {f.sizes['wave_direction']} headings"
    eye = np.broadcast_to(np.eye(n, dtype=complex), (data.sizes["omega"], n, n))
    return np.array(eye), "unit forces"


def fitted_frequencies(model, omega) -> NDArray[np.bool_]:
    """Which of ``omega`` (rad/s) a fitted model was fitted to: those within its
    ``omega_fit_min`` … ``omega_fit_max`` less its ``excluded_frequencies`` (the suspect
    points the fit left out; model attributes). A model without them: every frequency."""
    w = np.asarray(omega, dtype=float)
    keep = np.ones(w.size, dtype=bool)
    lo, hi = model.attrs.get("omega_fit_min"), model.attrs.get("omega_fit_max")
    if lo is not None and hi is not None:
        keep &= (w >= float(lo) * (1 - 1e-12)) & (w <= float(hi) * (1 + 1e-12))
    for excluded in model.attrs.get("excluded_frequencies", []) or []:
        keep &= ~at_frequency(w, float(excluded))
    return keep


def fit_motion_error(
    data: xr.Dataset, model, joined: JoinedMotion | None = None
) -> tuple[float, NDArray[np.float64]]:
    """The motion error of ``model`` as its fit measured it (``attrs["motion_error"]``):
    :meth:`MotionSensitivity.model_error` on the data's frequencies the fit kept
    (:func:`fitted_frequencies`), the excitation at up to four headings, 2 % of critical
    damping — so that a reduced model is judged by the measure its full model was; with
    ``joined``, on the motions of the joined system a joined fit aimed at (its
    constraints and power take-offs). Returns the error and its value per DOF.

    Raises
    ------
    HydroDataError
        Data without the inertia or the restoring, or none of the fitted frequencies.
    """
    from cummins.errors import HydroDataError
    from cummins.hydrodb import single_speed

    dofs = list(model.dofs)
    ds = single_speed(data).sel(influenced_dof=dofs, radiating_dof=dofs)
    keep = fitted_frequencies(model, ds.omega.values)
    sensitivity = None
    if keep.any():
        sensitivity = motion_sensitivity(
            ds.isel(omega=np.flatnonzero(keep)),
            added_mass_inf=model.added_mass_inf,
            joined=joined,
        )
    if sensitivity is None:
        raise HydroDataError(
            "the motion error needs inertia_matrix and hydrostatic_stiffness in the data, "
            "at the frequencies the model was fitted to",
            path=ds.attrs.get("source_file"),
            hint="give the data the model was fitted to (with the mass properties)",
        )
    return sensitivity.model_error(model)


class BlockMotionError:
    """:meth:`MotionSensitivity.error_of` of the data's K(jω) with one block's DOFs
    modelled, for the many fits of an order search: Z = Z₀ + P Δ Pᵀ, Z₀ the data's (K of
    the data, A∞ zero), Δ = jω (K̂ − K)_D on the block's DOFs D, so that (Woodbury)

        X = X₀ − (Z₀⁻¹ P) (I + Δ Pᵀ Z₀⁻¹ P)⁻¹ Δ Pᵀ X₀,

    an m × m system per frequency (m = |D|) instead of the n × n one, Z₀⁻¹ P and X₀ solved
    once per block. The same error to rounding (X − X_data is formed as the difference
    X₀ − X_data plus the change, not as the difference of two solutions). Without free
    bodies (a constraint basis) or where Z₀ is singular, :meth:`MotionSensitivity.error_of`
    itself."""

    def __init__(self, sensitivity: MotionSensitivity, k_data: NDArray):
        self.sensitivity = sensitivity
        self.k_data = k_data
        self.omega = sensitivity.omega[sensitivity.compared_frequencies()]
        self._bases: dict = {}

    def _base(self, dofs: tuple[int, ...]):
        if dofs in self._bases:
            return self._bases[dofs]
        sens, w = self.sensitivity, self.omega
        base = None
        if sens.basis is None:
            rows = sens.compared_frequencies()
            n = self.k_data.shape[1]
            z = (
                -(w**2)[:, None, None] * (sens.rigid_body_mass + np.zeros((n, n)))
                + 1j * w[:, None, None] * (sens.viscous_damping + self.k_data)
                + sens.stiffness
            )
            columns = np.zeros((n, len(dofs)), dtype=complex)
            columns[list(dofs), range(len(dofs))] = 1.0
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("error")
                    solved = np.linalg.solve(
                        z,
                        np.concatenate(
                            [sens.forces[rows], np.broadcast_to(columns, (w.size, n, len(dofs)))],
                            axis=2,
                        ),
                    )
            except (np.linalg.LinAlgError, RuntimeWarning):
                solved = None
            if solved is not None and np.all(np.isfinite(solved)):
                cases = sens.forces.shape[2]
                x0, hp = solved[:, :, :cases], solved[:, :, cases:]
                x_data = sens.motions[rows]
                peak = np.abs(x_data).max(axis=0)
                base = (
                    x0 - x_data,
                    hp,
                    hp[:, list(dofs), :],
                    x0[:, list(dofs), :],
                    np.where(peak > 0, peak, 1.0),
                    self.k_data[:, list(dofs)][:, :, list(dofs)],
                )
        self._bases[dofs] = base
        return base

    def linearised(self, dofs: tuple[int, ...], k_block: NDArray) -> tuple | None:
        """The motions with ``k_block`` linearised: (ω, r, s), r (ω, R) the relative errors
        (X − X_data)/max_ω |X_data| of the R compared (DOF, load case) motions and s
        (ω, R, m, m) = ∂r/∂K̂_ab of the block's DOFs: δX = −Z⁻¹P (jω δK̂) PᵀX (Falnes
        (2002) eq. 5.8 differentiated), Z⁻¹P = (Z₀⁻¹P)(I + Δ PᵀZ₀⁻¹P)⁻¹ and PᵀX = PᵀX₀ −
        PᵀZ₀⁻¹P y as in :meth:`__call__`. None where :meth:`__call__` has no Woodbury form."""
        base = self._base(tuple(dofs))
        if base is None:
            return None
        offset, hp, g, px0, peak, k_data = base
        w = self.omega
        delta = 1j * w[:, None, None] * (k_block - k_data)
        s = delta @ g
        m = len(dofs)
        s[:, range(m), range(m)] += 1.0
        y = np.linalg.solve(s, delta @ px0)
        moved = np.swapaxes(np.linalg.solve(np.swapaxes(s, 1, 2), np.swapaxes(hp, 1, 2)), 1, 2)
        x_block = px0 - g @ y
        dof, case = np.nonzero(self.sensitivity.compared)
        scale = 1.0 / peak[dof, case]
        residual = (offset - hp @ y)[:, dof, case] * scale
        across = moved[:, dof, :][:, :, :, None]  # (ω, R, a, 1)
        along = np.swapaxes(x_block[:, :, case], 1, 2)[:, :, None, :]  # (ω, R, 1, b)
        derivative = -(1j * w)[:, None, None, None] * (across * along)
        return w, residual, derivative * scale[None, :, None, None]

    def __call__(self, dofs: tuple[int, ...], k_block: NDArray) -> float:
        """The relative motion error with K of the DOFs ``dofs`` (model indices) given as
        ``k_block`` (ω, m, m) at the compared frequencies, the others the data's."""
        base = self._base(tuple(dofs))
        if base is None:
            k = self.k_data.copy()
            index = np.asarray(dofs)
            k[:, index[:, None], index[None, :]] = k_block
            return self.sensitivity.error_of(k, np.zeros(k.shape[1:]))[0]
        offset, hp, g, px0, peak, k_data = base
        delta = 1j * self.omega[:, None, None] * (k_block - k_data)
        rhs = delta @ px0
        s = delta @ g
        m = len(dofs)
        s[:, range(m), range(m)] += 1.0
        if m == 1:
            y = rhs / s
        elif m == 2:
            det = s[:, 0, 0] * s[:, 1, 1] - s[:, 0, 1] * s[:, 1, 0]
            y = np.empty_like(rhs)
            y[:, 0] = (s[:, 1, 1, None] * rhs[:, 0] - s[:, 0, 1, None] * rhs[:, 1]) / det[:, None]
            y[:, 1] = (s[:, 0, 0, None] * rhs[:, 1] - s[:, 1, 0, None] * rhs[:, 0]) / det[:, None]
        else:
            y = np.linalg.solve(s, rhs)
        error = offset - hp @ y
        ratio = np.abs(error).max(axis=0) / peak
        ratio = np.where(self.sensitivity.compared, ratio, 0.0)
        return float(ratio.max())
