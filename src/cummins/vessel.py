"""The linear vessel model of the Cummins equation.

The equation (Smogeli et al. (2004) eqs. 32–39; Ross, Perez & Fossen (2006) eq. 12) is

    (M_RB + A∞) ξ̈ + B_v ξ̇ + μ + C ξ = τ,      μ = C_r χ,   χ̇ = A_r χ + B_r ξ̇,

with ξ the 6 (or 6N) generalized displacements about the database's reference point
(m, rad, in its axes), M_RB the rigid-body inertia, A∞ the infinite-frequency added mass,
B_v a linear viscous damping added by the user, C the restoring matrix (hydrostatic plus
any additional stiffness of the database: moorings), μ the fluid-memory force of the
radiation model (A_r, B_r, C_r) identified by :func:`cummins.radiation.fit.fit_radiation`, and τ the
external (wave) force. With the state x = (ξ, ξ̇, χ):

    ẋ = F x + G τ,   F = [[0, I, 0], [−M⁻¹C, −M⁻¹B_v, −M⁻¹C_r], [0, B_r, A_r]],
                     G = [0; M⁻¹; 0],   M = M_RB + A∞.

Its frequency response is that of the frequency-domain equation with the model's
K(jω) = B(ω) + jω(A(ω) − A∞) in place of the data:
[−ω²M + jω (B_v + K(jω)) + C] X = F, i.e. −ω²(M_RB + A(ω)) + jω(B(ω) + B_v) + C.

**Joined bodies and PTOs** (:mod:`cummins.mechanics`). A vessel may carry the basis T
(n × m) of the motions its joints allow, ξ = T q, and PTOs, each adding k d dᵀ to C and
c d dᵀ to B_v. The state is then x = (q, q̇, χ) and

    F = [[0, I, 0], [−M_q⁻¹C_q, −M_q⁻¹B_q, −M_q⁻¹TᵀC_r], [0, B_r T, A_r]],
    G = [0; M_q⁻¹Tᵀ; 0],   M_q = TᵀMT, C_q = TᵀCT, B_q = TᵀB_vT:

the memory is driven by the body velocities T q̇ and its force enters through Tᵀ (the
constraint forces do no work on the allowed motions). The input τ and the outputs ξ = T q,
ξ̇ = T q̇, μ stay in the body DOFs (:meth:`Vessel.output_matrix`).
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import ArgumentError, HydroDataError, HydroDataWarning, SimulationError
from cummins.hydrodb import dof_matrix, single_speed
from cummins.mechanics import MechanicalSystem, PTOLine, assemble, pto_matrices
from cummins.mechanics.coupling import cross_body_mask
from cummins.radiation.fingerprint import check_model_data
from cummins.radiation.model import RadiationModel
from cummins.restoring import (
    INSTABILITY_HINT,
    instability_message,
    static_instability,
    unrestrained_message,
    unrestrained_modes,
)


@dataclass(frozen=True, eq=False)
class Vessel:
    """A rigid body with its hydrostatics and fluid memory, ready to simulate.

    Attributes
    ----------
    dofs
        DOF labels (``Surge`` … ``Yaw``).
    rigid_body_mass
        M_RB (n, n), kg, kg·m, kg·m².
    stiffness
        C (n, n), N/m, N, N·m/rad: hydrostatic plus additional (mooring) stiffness.
    viscous_damping
        B_v (n, n), linear, N·s/m …; zero by default.
    radiation
        The fluid-memory model; its ``added_mass_inf`` is the A∞ used.
    attrs
        Provenance: source file, reference point, axis convention.
    constraint
        T (n × m), ξ = T q: the motions the joints allow (None: every DOF free).
    ptos
        The PTOs (:class:`cummins.mechanics.PTOLine` over ``dofs``); their stiffness and
        damping are not in ``stiffness`` and ``viscous_damping``, they are added to them
        (:attr:`restoring`, :attr:`damping`).
    """

    dofs: tuple[str, ...]
    rigid_body_mass: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    viscous_damping: NDArray[np.float64]
    radiation: RadiationModel
    attrs: Mapping[str, Any] = field(default_factory=dict)
    constraint: NDArray[np.float64] | None = None
    ptos: tuple[PTOLine, ...] = ()

    def __post_init__(self) -> None:
        n = len(self.dofs)
        if self.constraint is not None:
            t = np.asarray(self.constraint, dtype=float)
            if t.ndim != 2 or t.shape[0] != n or not 1 <= t.shape[1] <= n:
                raise SimulationError(f"the constraint basis T must be {n} x m, not {t.shape}")
            object.__setattr__(self, "constraint", t)
        object.__setattr__(self, "ptos", tuple(self.ptos))
        for pto in self.ptos:
            if np.shape(pto.direction) != (n,):
                raise SimulationError(f"PTO {pto.name} is not resolved on the vessel's {n} DOFs")

    def __repr__(self) -> str:  # not its matrices: a notebook's echo in one line
        joints = "" if self.constraint is None else f", {self.constraint.shape[1]} motions free"
        ptos = f", PTOs {', '.join(p.name for p in self.ptos)}" if self.ptos else ""
        source = f"; from {self.attrs['source_file']!r}" if "source_file" in self.attrs else ""
        return (
            f"Vessel({len(self.dofs)} DOFs {', '.join(self.dofs)}{joints}{ptos}; radiation: "
            f"{self.radiation.total_order} states{source})"
        )

    @property
    def added_mass_inf(self) -> NDArray[np.float64]:
        """A∞ (n, n) of the radiation model."""
        return np.asarray(self.radiation.added_mass_inf, dtype=float)

    @property
    def mass(self) -> NDArray[np.float64]:
        """M = M_RB + A∞ (n, n)."""
        return self.rigid_body_mass + self.added_mass_inf

    @property
    def basis(self) -> NDArray[np.float64]:
        """T (n × m): ξ = T q (the identity when no joint constrains the DOFs)."""
        return np.eye(len(self.dofs)) if self.constraint is None else self.constraint

    @property
    def n_coordinates(self) -> int:
        """m, the number of independent coordinates q."""
        return self.basis.shape[1]

    @property
    def pto_stiffness(self) -> NDArray[np.float64]:
        """Σ k d dᵀ of the PTOs (n × n)."""
        return pto_matrices(self.ptos, len(self.dofs))[0]

    @property
    def pto_damping(self) -> NDArray[np.float64]:
        """Σ c d dᵀ of the PTOs (n × n)."""
        return pto_matrices(self.ptos, len(self.dofs))[1]

    @property
    def restoring(self) -> NDArray[np.float64]:
        """C + the PTOs' stiffness (n × n)."""
        return self.stiffness + self.pto_stiffness

    @property
    def damping(self) -> NDArray[np.float64]:
        """B_v + the PTOs' damping (n × n)."""
        return self.viscous_damping + self.pto_damping

    @property
    def n_states(self) -> int:
        """2m + the order of the radiation model (m = n without joints)."""
        return 2 * self.n_coordinates + self.radiation.total_order

    def state_space(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(F, G) of ẋ = F x + G τ, x = (q, q̇, χ) (q = ξ without joints; module
        docstring); τ (n) in the body DOFs."""
        t = self.basis
        m, r = t.shape[1], self.radiation.total_order
        m_inv = np.linalg.inv(t.T @ self.mass @ t)
        f = np.zeros((2 * m + r, 2 * m + r))
        f[:m, m : 2 * m] = np.eye(m)
        f[m : 2 * m, :m] = -m_inv @ (t.T @ self.restoring @ t)
        f[m : 2 * m, m : 2 * m] = -m_inv @ (t.T @ self.damping @ t)
        if r:
            f[m : 2 * m, 2 * m :] = -m_inv @ (t.T @ self.radiation.C)
            f[2 * m :, m : 2 * m] = self.radiation.B @ t
            f[2 * m :, 2 * m :] = self.radiation.A
        g = np.zeros((2 * m + r, len(self.dofs)))
        g[m : 2 * m] = m_inv @ t.T
        return f, g

    def output_matrix(self) -> NDArray[np.float64]:
        """H (3n × n_states): (ξ, ξ̇, μ) = H x, the body motions, velocities and memory
        force from the state (q, q̇, χ)."""
        t = self.basis
        n, m = t.shape
        out = np.zeros((3 * n, self.n_states))
        out[:n, :m] = t
        out[n : 2 * n, m : 2 * m] = t
        if self.radiation.total_order:
            out[2 * n :, 2 * m :] = self.radiation.C
        return out

    def impedance(self, omega: ArrayLike) -> NDArray[np.complex128]:
        """Z(ω) = −ω²M + jω (B_v + B_pto + K(jω)) + C + C_pto, shape (len(omega), n, n),
        in the body DOFs: Z X = F (the memory force is K(jω) times the velocity jωX)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        k = self.radiation.response(w)
        return (
            -(w**2)[:, None, None] * self.mass
            + 1j * w[:, None, None] * (self.damping + k)
            + self.restoring
        )

    def response(self, omega: ArrayLike, force: ArrayLike) -> NDArray[np.complex128]:
        """X(ω) = T (TᵀZ(ω)T)⁻¹ TᵀF for complex force amplitudes F, shape (len(omega),
        n) (X = Z⁻¹F without joints)."""
        z = self.impedance(omega)
        f = np.asarray(force, dtype=complex).reshape(z.shape[0], -1)
        if self.constraint is None:
            return np.linalg.solve(z, f[..., None])[..., 0]
        t = self.constraint
        q = np.linalg.solve(t.T @ z @ t, (f @ t)[..., None])[..., 0]
        return q @ t.T

    def stability(self) -> NDArray[np.complex128]:
        """Eigenvalues of F; raises :class:`SimulationError` when one is in the right
        half-plane (naming the DOF that dominates its mode), first of all for a restoring
        with a negative eigenvalue (:func:`cummins.restoring.static_instability`, the
        sentence :func:`cummins.motion_rao` warns with)."""
        unstable = static_instability(self.restoring, self.dofs, self.basis)
        if unstable:
            raise SimulationError(instability_message(unstable), hint=INSTABILITY_HINT)
        f, _ = self.state_space()
        lam, vec = np.linalg.eig(f)
        scale = max(float(np.abs(lam).max()), 1e-12)
        # a DOF without restoring or damping (free drift) is a double eigenvalue at 0, which
        # rounding splits by about √ε·‖F‖ (7e-8 1/s on the GBM barge's sway with another
        # BLAS): a growth that small is no instability
        bad = np.flatnonzero(lam.real > 10 * np.sqrt(np.finfo(float).eps) * scale)
        if bad.size:
            k = bad[np.argmax(lam.real[bad])]
            t = self.basis
            m = t.shape[1]
            mode = np.abs(t @ vec[:m, k]) + np.abs(t @ vec[m : 2 * m, k])
            dof = self.dofs[int(np.argmax(mode))]
            raise SimulationError(
                f"the vessel model is unstable: eigenvalue {lam[k]:.4g} 1/s, mode dominated "
                f"by {dof}",
                hint="check the restoring matrix (negative stiffness?) and that the "
                "radiation model is passive (cummins.radiation.passivity.passivity_test)"
                + (
                    "; a body held by a joint with a buoyancy other than its weight needs "
                    "the moment of that net force about the joint as a stiffness "
                    "(docs/wec.md, Limitations)"
                    if self.constraint is not None
                    else ""
                ),
            )
        return lam


#: What each variable a vessel needs is, where solvers write it, and how to give it.
_HOW_TO_GIVE = {
    "inertia_matrix": (
        "the rigid-body inertia (mass, centre of gravity, radii of gyration)",
        "WAMIT writes it only from a .frc with the mass properties, NEMOH in Mechanics/Inertia"
        ".dat, MSS in its .mat; the solver's output often leaves it out",
        "give it with cummins.with_inertia(ds, mass=…, center_of_gravity=…, "
        "radii_of_gyration=…) or, on the command line, --mass KG --center-of-gravity X Y Z "
        "--radii-of-gyration RX RY RZ (or --inertia-matrix FILE; --mass alone when only "
        "translations move, e.g. --dof Heave)",
    ),
    "hydrostatic_stiffness": (
        "the hydrostatic restoring matrix",
        "WAMIT writes it to the .hst, NEMOH to Mesh/KH.dat, AQWA to the .LIS",
        "put that file beside the data, or add it with cummins.make_hydrodb(..., "
        "hydrostatic_stiffness=C)",
    ),
}


def missing_data_message(ds: xr.Dataset, names, what: str) -> None:
    """HydroDataError naming the first of ``names`` the data lack, what it is, where solvers
    write it and how to give it (``what``: what needs it, e.g. "a simulation")."""
    for name in names:
        if name in ds:
            continue
        meaning, where, how = _HOW_TO_GIVE.get(name, (name, "", "add it to the data"))
        source = ds.attrs.get("source_file")
        have = [n for n in _HOW_TO_GIVE if n in ds]
        also = f" (they have {', '.join(have)})" if have else ""
        raise HydroDataError(
            f"the data have no {name!r}{also}: {what} needs {meaning}; {where}",
            path=source,
            hint=how[0].upper() + how[1:],
        )


def vessel_from_hydrodb(
    ds: xr.Dataset,
    model: RadiationModel | None = None,
    *,
    viscous_damping: ArrayLike | None = None,
    additional: bool = True,
    system: MechanicalSystem | None = None,
    allow_other_data: bool = False,
    **fit_options: Any,
) -> Vessel:
    """The :class:`Vessel` of a ``HydroDB``, fitting its radiation model when none is given.

    Parameters
    ----------
    ds
        One forward speed; needs ``inertia_matrix`` and ``hydrostatic_stiffness``;
        ``additional_stiffness`` (moorings) is added to C when present.
    model
        A radiation model of the same DOFs (default: :func:`cummins.radiation.fit.fit_radiation` of
        ``ds`` with ``fit_options``), fitted to these data: a model whose data fingerprint
        differs is refused (:func:`cummins.radiation.fingerprint.check_model_data`).
    allow_other_data
        Use ``model`` with data other than its own (what differs is then a warning).
    viscous_damping
        B_v as :func:`viscous_damping_matrix` takes it: an (n, n) matrix, the n diagonal
        values, a DataArray or ``{dof: value}`` (added to the data's own, below).
    additional
        Take the database's ``additional_stiffness`` (moorings) into C and its
        ``additional_damping`` (WAMIT external damping, MSS ``Bv``, VERES viscous roll
        damping) into B_v — as :func:`cummins.seakeeping.frequency_domain.motion_rao` does. A linear
        time-domain model has one constant B_v: entries of ``additional_damping`` that
        vary with frequency (MSS's surge/sway/yaw estimates) are left out with a
        warning naming them; give the value you want through ``viscous_damping``.
        Frequency-dependent ``additional_added_mass`` is likewise left out.
    system
        Joints, PTOs, the DOFs that move and the body coupling
        (:class:`cummins.mechanics.MechanicalSystem`): the vessel holds the DOFs that can
        move (the data's others are held at zero and left out), the basis T of the
        allowed motions and the PTOs; with ``body_coupling=False`` the radiation model is
        fitted to data without the cross-body terms (a ``model`` given must have none).
        ``viscous_damping`` is then over the DOFs that can move.
    fit_options
        Passed to :func:`cummins.radiation.fit.fit_radiation` when ``model`` is None; with
        joints or PTOs the fit aims at the motions of the joined system
        (:class:`cummins.radiation.fit.motion.JoinedMotion`), not of free bodies.

    Returns
    -------
    Vessel
        ``attrs["viscous_damping_source"]`` says where each part of B_v came from; with a
        system, ``attrs`` also hold its description (:meth:`cummins.mechanics.Assembly.attrs`).
    """
    from cummins.radiation.fit import fit_radiation

    ds = single_speed(ds)
    assembly = None
    if system is not None:
        assembly = assemble(ds, system)
        ds = assembly.ds
    dofs = tuple(str(d) for d in ds.influenced_dof.values)
    missing_data_message(ds, ("inertia_matrix", "hydrostatic_stiffness"), "a simulation")
    m_rb = dof_matrix(ds, "inertia_matrix")
    c = dof_matrix(ds, "hydrostatic_stiffness")
    b_v = viscous_damping_matrix(dofs, viscous_damping)
    sources = ["given" if viscous_damping is not None else "none given"]
    if additional:
        if "additional_stiffness" in ds:
            c = c + dof_matrix(ds, "additional_stiffness")
        if "additional_damping" in ds:
            b_v = b_v + _constant_part(ds, "additional_damping", dofs, given=b_v, said=sources)
            sources.append("database additional_damping (frequency-independent entries)")
    if model is None:
        # the fit aims at the motions of the joined system, not of free bodies
        joined = None if assembly is None else assembly.joined_motion()
        model = fit_radiation(ds, joined=joined, **fit_options)
    else:
        check_model_data(model, ds, allow_other_data=allow_other_data)
        _check_model_coupling(model, assembly is None or assembly.system.body_coupling)
    if tuple(model.dofs) != dofs:
        raise SimulationError(
            f"the radiation model's DOFs {model.dofs} differ from the data's {dofs}",
            hint="fit the model with the same DOFs (cummins fit takes the same --dof, "
            "--joint, --pto and --no-body-coupling options), or give the data",
        )
    attrs = {
        "source_file": str(ds.attrs.get("source_file", "")),
        "reference_point": np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0))),
        "axis_convention": str(ds.attrs.get("axis_convention", "z-up")),
        "viscous_damping_source": "; ".join(sources),
    }
    springs = c if assembly is None else c + assembly.pto_matrices()[0]
    loose = unrestrained_modes(springs, dofs)
    if loose:
        attrs["unrestrained_modes"] = unrestrained_message(loose)
        warnings.warn(attrs["unrestrained_modes"], HydroDataWarning, stacklevel=2)
    if assembly is None:
        return Vessel(dofs, m_rb, c, b_v, model, attrs)
    if not assembly.system.body_coupling:
        _check_no_body_coupling(model, ds)
    return Vessel(
        dofs,
        m_rb,
        c,
        b_v,
        model,
        {**attrs, **assembly.attrs()},
        constraint=assembly.basis if assembly.is_constrained else None,
        ptos=assembly.ptos,
    )


def _check_model_coupling(model: RadiationModel, body_coupling: bool) -> None:
    """ArgumentError when the body coupling is kept but ``model`` was fitted without it
    (``attrs["body_coupling"] == "off"``, ``cummins fit --no-body-coupling``): its memory
    lacks the cross-body radiation the equations then count on, and its A∞ the cross-body
    terms (the other way round, :func:`_check_no_body_coupling`). A model of one body's
    DOFs has no coupling to miss."""
    off = str(model.attrs.get("body_coupling", "")) == "off"
    if body_coupling and off and cross_body_mask(model.dofs).any():
        raise ArgumentError(
            "the radiation model was fitted with the body coupling off (--no-body-coupling, "
            "body_coupling=False), but the system keeps it: the run would leave out the "
            "cross-body radiation memory",
            hint="give --no-body-coupling (body_coupling=False) as at its fit, or fit the "
            "model again with the coupling (without the option)",
        )


def _check_no_body_coupling(model: RadiationModel, ds: xr.Dataset) -> None:
    """ArgumentError when a radiation model given with ``body_coupling=False`` couples
    bodies (its A∞ or K(jω) has cross-body terms)."""
    mask = cross_body_mask(model.dofs)
    if not mask.any():
        return
    w = ds.omega.values[:: max(1, ds.sizes["omega"] // 20)]
    k = np.abs(model.response(w)).max(axis=0) + np.abs(model.added_mass_inf)
    if np.any(k[mask] > 0):
        raise ArgumentError(
            "body_coupling is off but the radiation model given couples the bodies",
            hint="fit the model on data without the cross-body terms "
            "(cummins.mechanics.without_body_coupling), or give the data to fit it",
        )


def viscous_damping_matrix(dofs, viscous_damping: Any) -> NDArray[np.float64]:
    """B_v as an (n, n) array for the DOF labels ``dofs``: from an (n, n) matrix, n
    diagonal values, a DataArray with ``influenced_dof``/``radiating_dof``, or
    ``{dof: value}`` for a diagonal one (kg/s, kg·m²/s …); zeros for None.

    Raises
    ------
    HydroDataError
        A DOF that is not in ``dofs``, a wrong shape, non-finite values.
    """
    labels = [str(d) for d in dofs]
    n = len(labels)
    if viscous_damping is None:
        return np.zeros((n, n))
    if isinstance(viscous_damping, Mapping):
        out = np.zeros((n, n))
        for dof, value in viscous_damping.items():
            if str(dof) not in labels:
                raise HydroDataError(
                    f"viscous damping given for DOF {dof!r}, which is not in the data",
                    hint=f"DOFs: {', '.join(labels)}",
                )
            k = labels.index(str(dof))
            out[k, k] = float(value)
        return out
    if isinstance(viscous_damping, xr.DataArray):
        viscous_damping = viscous_damping.sel(
            influenced_dof=labels, radiating_dof=labels
        ).transpose("influenced_dof", "radiating_dof")
    arr = np.asarray(viscous_damping, dtype=float)
    if arr.shape == (n,):
        arr = np.diag(arr)
    if arr.shape != (n, n):
        raise HydroDataError(
            f"viscous_damping has shape {arr.shape}, expected {(n, n)} or {(n,)} for DOFs "
            f"{', '.join(labels)}"
        )
    if not np.all(np.isfinite(arr)):
        raise HydroDataError("viscous_damping has non-finite values")
    return arr


def _constant_part(
    ds: xr.Dataset,
    name: str,
    dofs: tuple[str, ...],
    *,
    given: NDArray[np.float64] | None = None,
    said: list[str] | None = None,
) -> NDArray[np.float64]:
    """The frequency-independent entries of ``ds[name]``; a warning names the others,
    but for the entries whose DOFs have a damping ``given`` by the user (MSS's surge,
    sway and yaw estimates where --viscous-damping replaces them): those are only
    appended to ``said`` (the vessel's ``viscous_damping_source``)."""
    values = ds[name]
    if "omega" not in values.dims:
        return dof_matrix(ds, name)
    stack = values.transpose("omega", "influenced_dof", "radiating_dof").values.astype(float)
    spread = stack.max(axis=0) - stack.min(axis=0)
    constant = spread <= 1e-9 * np.maximum(np.abs(stack).max(axis=0), 1e-300)
    covered = np.zeros_like(constant)
    if given is not None:
        on_dof = np.diag(given) != 0
        covered = (given != 0) | (on_dof[:, None] & on_dof[None, :])

    def listed(mask) -> list[str]:
        return [
            f"{dofs[i]}-{dofs[j]} ({stack[:, i, j].min():.3g} to {stack[:, i, j].max():.3g})"
            for i, j in zip(*np.nonzero(mask), strict=True)
        ]

    varying = listed(~constant & ~covered)
    replaced = listed(~constant & covered)
    if replaced and said is not None:
        said.append(f"{name} varying with frequency replaced by the given: {', '.join(replaced)}")
    if varying:
        warnings.warn(
            f"{name} varies with frequency for {', '.join(varying)}: a linear time-domain "
            "model cannot hold it and these entries are left out; pass the value you want "
            "as viscous_damping (--viscous-damping DOF VALUE)",
            UserWarning,
            stacklevel=3,
        )
    return np.where(constant, stack[0], 0.0)
