"""Low-frequency (manoeuvring) model with constant coefficients (Ross, Perez & Fossen, 2006).

The Cummins equation (Ross, Perez & Fossen (2006) eq. 11) has a frequency-independent
inertia A∞ and a fluid memory ∫K(t − τ) ξ̇(τ) dτ. A manoeuvring or dynamic-positioning
model (eqs. 16–17) replaces the memory by constant coefficients,

    (M_RB + M_A) ν̇ + D ν + G η = τ,

and §3.1 of the paper (Definition 1) says *at which frequency* to take them:

* **Zero-frequency model, surge/sway/yaw** (mass–damper DOFs, little oscillation while
  manoeuvring): the classical hydrodynamic derivatives, the ω → 0 limits of the
  Ogilvie relations (eqs. 8–9),

  M_A = A(0) = A∞ − ∫₀^∞ τ K(τ) dτ                                 (eq. 22, 25)
  D   = B(0) + B_v(0) = ∫₀^∞ K(τ) dτ + β                          (eq. 23, 26)

  At zero speed in deep water B(0) = ∫K dτ = 0: the potential part of the linear
  surge/sway/yaw derivative vanishes and D is the viscous β alone (eq. 26).
* **Natural-frequency model, heave/roll/pitch** (mass–spring–damper DOFs, which move
  at their natural frequency ω₀): ω₀ solves

  ω₀² (M_RB,ii + A_ii(ω₀)) − C_ii = 0                               (eq. 24)

  iteratively, and the coefficients are taken there (eqs. 29–30 for roll),

  M_A = A(ω₀) = A∞ − (1/ω₀) ∫₀^∞ K(τ) sin(ω₀τ) dτ,
  D   = B(ω₀) + B_v(ω₀) = ∫₀^∞ (K(τ) + K_v(τ)) cos(ω₀τ) dτ.

Two routes compute the same numbers and must agree: :func:`lf_model_from_retardation`
integrates K(t) (exactly, for the piecewise-linear K through its samples; the only
error is K's truncation at its last time), and :func:`lf_model_from_frequency_data`
interpolates A(ω), B(ω) (cubic spline) and takes A(0) from the solver's ω = 0 row or a
low-frequency extrapolation. The paper does not say at which frequency a coupling between
DOFs of different frequencies is taken: cummins takes entry (i, j) at min(ω_i, ω_j)
(symmetric, passive; the couplings of the zero-frequency DOFs are their derivatives), or
on request at ω_j, the frequency of the radiating DOF.

Viscous damping B_v(ω) (§3 of the paper, the matrix after eq. 21): :class:`ExponentialDamping`
β e^{−αω} (Ross & Fossen (2005); intended for surge, sway and yaw) and, for roll, where the
paper uses Ikeda et al. (1976), :class:`CriticalDampingFraction` — **a proxy, not Ikeda's
method**: B_v = 2ζ ω₀ (M_RB,ii + A_ii(ω₀)) = 2ζ √(C_ii (M_RB,ii + A_ii(ω₀))), a fraction ζ
of critical damping at the natural frequency (the component-wise Ikeda estimate needs the
hull form, bilge keels and roll amplitude, which a hydrodynamic database does not hold).
Any callable B_v(ω) (a user's Ikeda curve) is accepted too, and ``"data"`` takes the
database's own frequency-dependent ``additional_damping`` (e.g. VERES's viscous roll
damping) at the DOF's frequency.

:func:`compare_with_cummins` runs a free decay or a step force through the LF model and
the full Cummins vessel and reports the difference (the acceptance of issue 8).

Units: SI throughout; masses kg, kg·m, kg·m²; damping kg/s … kg·m²/s; stiffness N/m,
N, N·m/rad; frequencies rad/s.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline

from cummins.errors import CumminsWarning, FitError, HydroDataError, SimulationError
from cummins.hydrodb import dof_matrix, single_speed, split_dof
from cummins.radiation.model import RadiationModel
from cummins.radiation.transforms import cosine_transform, sine_transform
from cummins.validation import check_simulation_size
from cummins.vessel import Vessel, vessel_from_hydrodb

#: DOFs of the zero-frequency sub-model (Ross, Perez & Fossen (2006) Definition 1, item 1).
ZERO_FREQUENCY_DOFS = ("Surge", "Sway", "Yaw")
#: DOFs of the natural-frequency sub-model (Ross, Perez & Fossen (2006) Definition 1, item 2).
NATURAL_FREQUENCY_DOFS = ("Heave", "Roll", "Pitch")

Couplings = Literal["min", "radiating"]


# --------------------------------------------------------------------------- viscous damping


@dataclass(frozen=True)
class ExponentialDamping:
    """Viscous damping B_v(ω) = β e^{−αω} (Ross, Perez & Fossen (2006) §3; Ross & Fossen (2005)).

    Attributes
    ----------
    beta
        β ≥ 0, the zero-frequency viscous damping, kg/s (translation) or kg·m²/s
        (rotation): the constant that enters D of a zero-frequency DOF
        (Ross, Perez & Fossen (2006) eq. 26).
    alpha
        α ≥ 0, the exponential rate, s.

    Examples
    --------
    >>> ExponentialDamping(beta=2.0e5, alpha=1.0)(0.0)
    200000.0
    """

    beta: float
    alpha: float = 0.0

    def __post_init__(self) -> None:
        if not (np.isfinite(self.beta) and self.beta >= 0):
            raise HydroDataError(f"viscous damping beta must be finite and ≥ 0, not {self.beta}")
        if not (np.isfinite(self.alpha) and self.alpha >= 0):
            raise HydroDataError(f"viscous damping alpha must be finite and ≥ 0, not {self.alpha}")

    def __call__(self, omega: float) -> float:
        """B_v at ``omega`` (rad/s)."""
        return float(self.beta * np.exp(-self.alpha * omega))


@dataclass(frozen=True)
class CriticalDampingFraction:
    """Linear viscous damping as a fraction ζ of critical, at the natural frequency.

    B_v = 2ζ ω₀ (M_RB,ii + A_ii(ω₀)), i.e. 2ζ √(C_ii (M_RB,ii + A_ii(ω₀))) when ω₀
    satisfies Ross, Perez & Fossen (2006) eq. 24. A documented **proxy** for the Ikeda roll
    damping B_IKEDA(ω₀) of their eq. 30 (typical ζ for a ship in roll: 0.02–0.10 in total,
    of which the potential part B_44(ω₀) is often the smaller share); it is not Ikeda's
    component method (friction, eddy, lift, bilge keel), which needs the hull form.
    Only for DOFs with restoring (heave, roll, pitch).

    Attributes
    ----------
    zeta
        ζ ≥ 0, dimensionless.
    """

    zeta: float

    def __post_init__(self) -> None:
        if not (np.isfinite(self.zeta) and self.zeta >= 0):
            raise HydroDataError(f"damping fraction zeta must be finite and ≥ 0, not {self.zeta}")


ViscousSpec = (
    ExponentialDamping
    | CriticalDampingFraction
    | Callable[[float], float]
    | float
    | Literal["data"]
)


# --------------------------------------------------------------------------- the model


@dataclass(frozen=True, eq=False)
class LowFrequencyModel:
    """Constant-coefficient LF model (M_RB + M_A) ν̇ + D ν + G η = τ.

    Ross, Perez & Fossen (2006) eq. 17.

    Attributes
    ----------
    dofs
        DOF labels.
    rigid_body_mass
        M_RB (n, n), kg, kg·m, kg·m².
    added_mass
        M_A (n, n), same units; diagonal i at ``frequencies[i]`` (eqs. 22, 25, 29),
        couplings as ``attrs["couplings"]`` says.
    potential_damping
        B_p (n, n), kg/s … kg·m²/s: the potential part of D, likewise (eq. 23 with K
        only, eq. 30 without K_v).
    viscous_damping
        B_v (n, n): the database's constant additional damping (when taken) plus the
        requested viscous model evaluated at each DOF's frequency (eqs. 26, 30).
    stiffness
        G = C (n, n), N/m, N, N·m/rad: hydrostatic plus additional (mooring) stiffness.
    frequencies
        (n,) rad/s: 0 for the zero-frequency DOFs, ω₀ (eq. 24) for the others.
    provenance
        (n,) one sentence per DOF: frequency, route and equations used.
    zero_frequency_damping
        B(0) (n, n) as the route computed it (∫K dτ, eq. 23, or the extrapolated data):
        ≈ 0 at zero speed in deep water; kept as a diagnostic. Whether it enters
        :attr:`potential_damping` is set by ``potential_b0`` of the builders.
    attrs
        Route, options, source file; ``eq24_residual`` per DOF.
    """

    dofs: tuple[str, ...]
    rigid_body_mass: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    potential_damping: NDArray[np.float64]
    viscous_damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    frequencies: NDArray[np.float64]
    provenance: tuple[str, ...]
    zero_frequency_damping: NDArray[np.float64]
    attrs: Mapping[str, Any] = field(default_factory=dict)

    @property
    def damping(self) -> NDArray[np.float64]:
        """D = B_p + B_v (n, n), kg/s … kg·m²/s."""
        return self.potential_damping + self.viscous_damping

    @property
    def mass(self) -> NDArray[np.float64]:
        """M_RB + M_A (n, n)."""
        return self.rigid_body_mass + self.added_mass

    def index(self, dof: str) -> int:
        """Position of ``dof`` in :attr:`dofs` (HydroDataError naming the DOFs if absent)."""
        if dof not in self.dofs:
            raise HydroDataError(
                f"DOF {dof!r} is not in the model", hint=f"DOFs: {', '.join(self.dofs)}"
            )
        return self.dofs.index(dof)

    def eq24_residual(self, dof: str) -> float:
        """ω₀² (M_RB,ii + M_A,ii) − C_ii for ``dof``, N/m or N·m/rad.

        The residual of Ross, Perez & Fossen (2006) eq. 24."""
        i = self.index(dof)
        w = float(self.frequencies[i])
        return float(
            w**2 * (self.rigid_body_mass[i, i] + self.added_mass[i, i]) - self.stiffness[i, i]
        )

    def to_vessel(self) -> Vessel:
        """The model as a :class:`cummins.vessel.Vessel` with no fluid memory.

        Its inertia is M_RB + M_A (the radiation model has no couplings and M_A in place
        of A∞), its damping D and its stiffness G, so :func:`cummins.timedomain.simulate.simulate`
        runs it (state (ξ, ξ̇), 2n states).
        """
        radiation = RadiationModel(
            self.dofs, (), np.array(self.added_mass), {"kind": "low-frequency model"}
        )
        attrs = {**dict(self.attrs), "model": "low-frequency (constant coefficients)"}
        return Vessel(
            self.dofs,
            np.array(self.rigid_body_mass),
            np.array(self.stiffness),
            np.array(self.damping),
            radiation,
            attrs,
        )

    def to_dataset(self) -> xr.Dataset:
        """The coefficients as an ``xarray.Dataset`` (dims influenced_dof, radiating_dof)."""
        dims = ("influenced_dof", "radiating_dof")
        labels = list(self.dofs)
        out = xr.Dataset(
            {
                "inertia_matrix": (dims, self.rigid_body_mass),
                "added_mass": (dims, self.added_mass),
                "potential_damping": (dims, self.potential_damping),
                "viscous_damping": (dims, self.viscous_damping),
                "damping": (dims, self.damping),
                "stiffness": (dims, self.stiffness),
                "zero_frequency_damping": (dims, self.zero_frequency_damping),
                "frequency": ("dof", self.frequencies, {"units": "rad/s"}),
                "provenance": ("dof", np.array(self.provenance, dtype=str)),
            },
            coords={"influenced_dof": labels, "radiating_dof": labels, "dof": labels},
            attrs={
                k: (v if isinstance(v, str | int | float | np.ndarray) else str(v))
                for k, v in self.attrs.items()
            },
        )
        out.attrs["title"] = "low-frequency manoeuvring model (Ross, Perez & Fossen 2006)"
        return out


# --------------------------------------------------------------------------- coefficient sources


class _Coefficients:
    """A(ω), B(ω) (n, n) at any admissible ω ≥ 0, one route."""

    route: str
    zero_note: str
    omega_range: tuple[float, float]

    def __call__(self, omega: float) -> tuple[NDArray, NDArray]:  # pragma: no cover
        raise NotImplementedError


class _FromKernel(_Coefficients):
    """Ross, Perez & Fossen (2006) eqs. 8–9 and 22–23 on a sampled K(t).

    Exact for a piecewise-linear K."""

    route = "retardation function K(t)"

    def __init__(self, kernel: xr.DataArray, a_inf: NDArray) -> None:
        k = kernel.transpose("time", "influenced_dof", "radiating_dof")
        self.t = np.asarray(k.time.values, dtype=float)
        if self.t.size < 2 or np.any(np.diff(self.t) <= 0) or self.t[0] != 0.0:
            raise HydroDataError(
                "the retardation function must be sampled on increasing times from t = 0",
                quantity="retardation_function time",
            )
        self.n = k.shape[1]
        self.k = np.asarray(k.values, dtype=float).reshape(self.t.size, self.n * self.n)
        self.a_inf = np.asarray(a_inf, dtype=float)
        self.omega_range = (0.0, np.inf)
        self.zero_note = (
            f"A(0) = A∞ − ∫τK dτ, B(0) = ∫K dτ over 0–{self.t[-1]:g} s (eqs. 22–23, 25–26)"
        )
        # ∫ K dτ and ∫ τ K dτ, exact for the piecewise-linear K through its samples
        t, f = self.t, self.k
        h = np.diff(t)[:, None]
        f0, f1, t0, t1 = f[:-1], f[1:], t[:-1, None], t[1:, None]
        self.area = np.sum(0.5 * h * (f0 + f1), axis=0).reshape(self.n, self.n)
        moment = h / 6.0 * (f0 * (2 * t0 + t1) + f1 * (t0 + 2 * t1))
        self.moment = np.sum(moment, axis=0).reshape(self.n, self.n)

    def __call__(self, omega: float) -> tuple[NDArray, NDArray]:
        if omega == 0.0:
            return self.a_inf - self.moment, self.area.copy()
        s = sine_transform(self.t, self.k, [omega])[0].reshape(self.n, self.n)
        c = cosine_transform(self.t, self.k, [omega])[0].reshape(self.n, self.n)
        return self.a_inf - s / omega, c


class _FromFrequencyData(_Coefficients):
    """Cubic-spline A(ω), B(ω) of the data; ω = 0 from the solver's row or extrapolated."""

    route = "frequency data A(ω), B(ω)"

    def __init__(self, ds: xr.Dataset, zero_frequency: str, points: int) -> None:
        w = ds.omega.values
        a = dof_matrix(ds, "added_mass")
        b = dof_matrix(ds, "radiation_damping")
        self.omega_range = (float(w[0]), float(w[-1]))
        self.a_spline = CubicSpline(w, a, axis=0)
        self.b_spline = CubicSpline(w, b, axis=0)
        if zero_frequency not in ("auto", "data", "extrapolate"):
            raise HydroDataError(
                f"unknown zero_frequency {zero_frequency!r}",
                hint="use 'auto', 'data' or 'extrapolate'",
            )
        a0_ext, b0_ext = extrapolate_zero_frequency(ds, points=points)
        self.b0 = b0_ext
        use_data = zero_frequency == "data" or (
            zero_frequency == "auto" and "added_mass_zero" in ds
        )
        if use_data:
            if "added_mass_zero" not in ds:
                raise HydroDataError(
                    "the data have no zero-frequency added mass row",
                    path=ds.attrs.get("source_file"),
                    quantity="added_mass_zero",
                    hint="use zero_frequency='extrapolate' or lf_model_from_retardation",
                )
            self.a0 = dof_matrix(ds, "added_mass_zero")
            self.zero_note = "A(0) from the solver's ω = 0 row"
        else:
            self.a0 = a0_ext
            self.zero_note = f"A(0) extrapolated in ω² from the lowest {points} frequencies"
        self.zero_note += (
            f", B(0) extrapolated in ω² from the lowest {points} frequencies (eqs. 20–21)"
        )

    def __call__(self, omega: float) -> tuple[NDArray, NDArray]:
        if omega == 0.0:
            return self.a0.copy(), self.b0.copy()
        lo, hi = self.omega_range
        if not lo <= omega <= hi:
            raise HydroDataError(
                f"ω = {omega:.4g} rad/s is outside the data ({lo:.4g}–{hi:.4g} rad/s)",
                quantity="added_mass, radiation_damping",
                hint="use lf_model_from_retardation, which evaluates any frequency",
            )
        return np.asarray(self.a_spline(omega)), np.asarray(self.b_spline(omega))


def extrapolate_zero_frequency(
    ds: xr.Dataset, *, points: int = 4
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A(0) and B(0) by a least-squares fit of c₀ + c₂ω² to the lowest ``points`` frequencies.

    A(ω) and B(ω) are even functions of ω (A(ω) = A∞ + Im K(jω)/ω and B = Re K(jω) for a
    real kernel), so their expansion about ω = 0 has no odd term. The limits of
    Ross, Perez & Fossen (2006) eqs. 20–21.

    Returns
    -------
    (ndarray, ndarray)
        A(0) (n, n), kg, kg·m, kg·m²; B(0) (n, n), kg/s … kg·m²/s.
    """
    ds = single_speed(ds)
    w = ds.omega.values[:points]
    if w.size < 2:
        raise HydroDataError("at least two frequencies are needed to extrapolate to ω = 0")
    x = np.c_[np.ones(w.size), w**2]
    out = []
    for name in ("added_mass", "radiation_damping"):
        y = dof_matrix(ds, name)[:points]
        coef = np.linalg.lstsq(x, y.reshape(w.size, -1), rcond=None)[0]
        out.append(coef[0].reshape(y.shape[1:]))
    return out[0], out[1]


# --------------------------------------------------------------------------- builders


def _is_zero_frequency_dof(label: str) -> bool:
    return split_dof(label)[1] in ZERO_FREQUENCY_DOFS


def natural_frequency(
    coefficients: Callable[[float], tuple[NDArray, NDArray]],
    mass: float,
    stiffness: float,
    index: int,
    *,
    dof: str = "",
    tol: float = 1e-10,
    max_iter: int = 100,
) -> tuple[float, int]:
    """ω₀ of Ross, Perez & Fossen (2006) eq. 24 by fixed-point iteration.

    ω ← √(C_ii / (M_RB,ii + A_ii(ω))).

    Parameters
    ----------
    coefficients
        ω ↦ (A(ω), B(ω)), (n, n) each.
    mass, stiffness
        M_RB,ii (kg or kg·m²) and C_ii (N/m or N·m/rad), > 0.
    index
        i, the DOF's position.
    dof
        Label used in error messages.
    tol
        Converged when |ω_{k+1} − ω_k| ≤ tol · ω_k.
    max_iter
        Iterations before giving up.

    Returns
    -------
    (float, int)
        ω₀ (rad/s) and the number of iterations.

    Raises
    ------
    HydroDataError
        C_ii ≤ 0 (no restoring) or M_RB,ii + A_ii(ω) ≤ 0.
    FitError
        The iteration does not converge (the last iterates are in the message).
    """
    if not stiffness > 0:
        raise HydroDataError(
            f"{dof}: restoring C = {stiffness:.4g} ≤ 0, so there is no natural frequency "
            "(Ross, Perez & Fossen (2006) eq. 24)",
            quantity=f"hydrostatic_stiffness[{dof}, {dof}]",
            hint=f"give the frequency with frequencies={{{dof!r}: ω}} or check the hydrostatics",
        )
    omega: float | None = None  # first pass: A(0), the other limit of the inertia
    history: list[float] = []
    for k in range(max_iter):
        a_ii = float(coefficients(0.0 if omega is None else omega)[0][index, index])
        total = mass + a_ii
        if not total > 0:
            raise HydroDataError(
                f"{dof}: M_RB + A = {total:.4g} ≤ 0 at ω = {omega} rad/s",
                quantity=f"added_mass[{dof}, {dof}]",
            )
        new = float(np.sqrt(stiffness / total))
        history.append(new)
        if omega is not None and abs(new - omega) <= tol * omega:
            return new, k
        omega = new
    last = ", ".join(f"{x:.6g}" for x in history[-4:])
    raise FitError(
        f"{dof}: the natural frequency of Ross, Perez & Fossen (2006) eq. 24 did not converge "
        f"in {max_iter} fixed-point iterations (last iterates {last} rad/s)",
        hint=f"give it with frequencies={{{dof!r}: ω}} or raise max_iter",
    )


def _viscous_value(
    spec: ViscousSpec, dof: str, omega: float, mass: float, added: float
) -> tuple[float, str]:
    if isinstance(spec, CriticalDampingFraction):
        if omega <= 0:
            raise HydroDataError(
                f"{dof}: a fraction of critical damping needs a natural frequency, and "
                f"{dof} is a zero-frequency DOF",
                quantity=f"viscous damping of {dof}",
                hint="use ExponentialDamping(beta, alpha) for surge, sway and yaw",
            )
        return 2 * spec.zeta * omega * (mass + added), f"B_v = 2ζω₀(M+A), ζ = {spec.zeta:g}"
    if isinstance(spec, ExponentialDamping):
        return spec(omega), f"B_v = β e^(−αω), β = {spec.beta:g}, α = {spec.alpha:g}"
    if callable(spec):
        return float(spec(omega)), "B_v(ω) given"
    return float(spec), "B_v constant"


def _database_damping(ds: xr.Dataset, spec: str, dof: str, i: int, omega: float):
    """The database's own ``additional_damping`` B_v,ii(ω) at ``omega`` (``"data"``)."""
    if spec != "data":
        raise HydroDataError(
            f"unknown viscous damping {spec!r} for {dof}",
            hint="give 'data', a number, a callable B_v(ω) or ExponentialDamping/"
            "CriticalDampingFraction",
        )
    if "additional_damping" not in ds:
        raise HydroDataError(
            f"{dof}: viscous='data' asks for the database's additional_damping, which "
            "these data do not hold",
            path=ds.attrs.get("source_file"),
            quantity=f"additional_damping[{dof}, {dof}]",
        )
    var = ds["additional_damping"].transpose(..., "influenced_dof", "radiating_dof")
    if "omega" not in var.dims:
        return float(var.values[i, i]), "B_v from the database (constant)"
    values = var.transpose("omega", ...).values[:, i, i].astype(float)
    value = float(np.interp(omega, ds.omega.values, values))
    return value, f"B_v from the database's additional_damping at ω = {omega:.4g} rad/s"


def _nonnegative_damping(
    ds: xr.Dataset, coefficients: _Coefficients, dof: str, i: int, omega: float, value: float
) -> tuple[float, str]:
    """B_ii(ω₀) of a passive body is ≥ 0; a negative value from a route (a few N·s/m where
    B_ii peaks at 10⁵: the truncation error of K(t), or a cubic spline undershooting where
    the data are nearly zero) is replaced by the data's own B_ii(ω₀), interpolated
    linearly, with a warning. Data negative at ω₀ themselves are refused."""
    w = ds.omega.values
    b = dof_matrix(ds, "radiation_damping")[:, i, i]
    peak = float(np.max(np.abs(b)))
    if not w[0] <= omega <= w[-1]:
        raise HydroDataError(
            f"{dof}: the potential damping at the natural frequency ω₀ = {omega:.4g} rad/s "
            f"comes out negative ({value:.4g}) from the {coefficients.route}, and ω₀ is "
            f"outside the data ({w[0]:.4g}–{w[-1]:.4g} rad/s) to check it against",
            path=ds.attrs.get("source_file"),
            quantity=f"radiation_damping[{dof}, {dof}]",
            hint="give data that cover the natural frequency, or the frequency with "
            f"frequencies={{{dof!r}: ω}} (--route frequency on the command line)",
        )
    from_data = float(np.interp(omega, w, b))
    if from_data < 0:
        raise HydroDataError(
            f"{dof}: the data's damping is negative at the natural frequency ω₀ = "
            f"{omega:.4g} rad/s ({from_data:.4g}, peak {peak:.4g}): a low-frequency model "
            "with it would be unstable",
            path=ds.attrs.get("source_file"),
            quantity=f"radiation_damping[{dof}, {dof}]",
            hint="remove the suspect frequencies first (cummins.repair."
            "remove_suspect_frequencies), or add viscous damping for this DOF",
        )
    how = (
        f"the {coefficients.route} gave B(ω₀) = {value:.4g} < 0 (its error, {abs(value):.2g}, "
        f"is {abs(value) / max(peak, 1e-300):.1e} of the peak {peak:.4g} but exceeds B(ω₀) "
        f"itself): B(ω₀) = {from_data:.4g} interpolated linearly in the data instead"
    )
    warnings.warn(f"{dof}: {how}", CumminsWarning, stacklevel=4)
    return from_data, how


def _build(
    ds: xr.Dataset,
    coefficients: _Coefficients,
    *,
    viscous: Mapping[str, ViscousSpec] | None,
    frequencies: Mapping[str, float] | None,
    couplings: Couplings,
    additional: bool,
    potential_b0: str,
    tol: float,
    max_iter: int,
) -> LowFrequencyModel:
    if potential_b0 not in ("zero", "computed"):
        raise HydroDataError(
            f"unknown potential_b0 {potential_b0!r}", hint="use 'zero' or 'computed'"
        )
    dofs = tuple(str(d) for d in ds.influenced_dof.values)
    n = len(dofs)
    # M_RB, C (with moorings) and the database's constant B_v exactly as the full vessel
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        base = vessel_from_hydrodb(
            ds, RadiationModel(dofs, (), np.zeros((n, n))), additional=additional
        )
    for w in caught:  # the vessel's advice, restated for the LF model
        message = str(w.message)
        if issubclass(w.category, UserWarning) and "varies with frequency" in message:
            message = message.split(": a linear")[0] + (
                ": the low-frequency model leaves these entries out unless you ask for "
                "viscous={dof: 'data'}, which takes them at the DOF's frequency"
            )
        warnings.warn(message, w.category, stacklevel=3)
    m_rb, c = base.rigid_body_mass, base.stiffness
    if couplings not in ("min", "radiating"):
        raise HydroDataError(f"unknown couplings {couplings!r}", hint="use 'min' or 'radiating'")
    for name in list(viscous or {}) + list(frequencies or {}):
        if name not in dofs:
            raise HydroDataError(
                f"DOF {name!r} is not in the data", hint=f"DOFs: {', '.join(dofs)}"
            )
    chosen = np.zeros(n)
    notes: list[str] = []
    iterations: dict[str, int] = {}
    for i, dof in enumerate(dofs):
        if frequencies and dof in frequencies:
            chosen[i] = float(frequencies[dof])
            if not (np.isfinite(chosen[i]) and chosen[i] >= 0):
                raise HydroDataError(
                    f"{dof}: the frequency given, {chosen[i]}, must be finite and ≥ 0 rad/s"
                )
            notes.append(f"ω = {chosen[i]:.6g} rad/s given")
        elif _is_zero_frequency_dof(dof):
            chosen[i] = 0.0
            notes.append(f"zero-frequency model; {coefficients.zero_note}")
        else:
            chosen[i], iterations[dof] = natural_frequency(
                coefficients, m_rb[i, i], c[i, i], i, dof=dof, tol=tol, max_iter=max_iter
            )
            notes.append(
                f"natural-frequency model, ω₀ = {chosen[i]:.6g} rad/s from eq. 24 "
                f"({iterations[dof]} iterations); A(ω₀), B(ω₀) from the "
                f"{coefficients.route} (eqs. 29–30)"
            )
    cache: dict[float, tuple[NDArray, NDArray]] = {}
    m_a = np.zeros((n, n))
    b_p = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            w = float(chosen[j] if couplings == "radiating" else min(chosen[i], chosen[j]))
            if w not in cache:
                cache[w] = coefficients(w)
            m_a[i, j] = cache[w][0][i, j]
            b_p[i, j] = 0.0 if (w == 0.0 and potential_b0 == "zero") else cache[w][1][i, j]
    if couplings == "min":  # the data's own small asymmetry (K_ij ≠ K_ji) averaged out
        m_a = 0.5 * (m_a + m_a.T)
        b_p = 0.5 * (b_p + b_p.T)
    for i, dof in enumerate(dofs):
        if chosen[i] > 0 and b_p[i, i] < 0:
            b_p[i, i], how = _nonnegative_damping(
                ds, coefficients, dof, i, float(chosen[i]), b_p[i, i]
            )
            notes[i] += f"; {how}"
    b0 = coefficients(0.0)[1]
    if couplings == "symmetric":
        m_a = 0.5 * (m_a + m_a.T)
        b_p = 0.5 * (b_p + b_p.T)
    b_v = np.array(base.viscous_damping)
    for dof, spec in (viscous or {}).items():
        i = dofs.index(dof)
        if isinstance(spec, str):
            value, how = _database_damping(ds, spec, dof, i, float(chosen[i]))
            b_v[i, i] = value  # replaces the constant part taken above, if any
        else:
            value, how = _viscous_value(spec, dof, float(chosen[i]), m_rb[i, i], m_a[i, i])
            b_v[i, i] += value
        notes[i] += f"; {how} → {value:.4g}"
    provenance = tuple(f"{dof}: {note}" for dof, note in zip(dofs, notes, strict=True))
    model = LowFrequencyModel(
        dofs=dofs,
        rigid_body_mass=m_rb,
        added_mass=m_a,
        potential_damping=b_p,
        viscous_damping=b_v,
        stiffness=c,
        frequencies=chosen,
        provenance=provenance,
        zero_frequency_damping=b0,
        attrs={
            "route": coefficients.route,
            "couplings": couplings,
            "potential_b0": potential_b0,
            "source_file": str(ds.attrs.get("source_file", "")),
            "viscous_damping_source": str(base.attrs.get("viscous_damping_source", "")),
            "reference_point": np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0))),
            "axis_convention": str(ds.attrs.get("axis_convention", "z-up")),
        },
    )
    return model


def lf_model_from_retardation(
    ds: xr.Dataset,
    kernel: xr.DataArray | None = None,
    *,
    added_mass_inf: ArrayLike | None = None,
    viscous: Mapping[str, ViscousSpec] | None = None,
    frequencies: Mapping[str, float] | None = None,
    couplings: Couplings = "min",
    additional: bool = True,
    potential_b0: Literal["zero", "computed"] = "zero",
    tol: float = 1e-10,
    max_iter: int = 100,
) -> LowFrequencyModel:
    """The LF model from the retardation function K(t) and A∞ (Ross, Perez & Fossen (2006) §3.1).

    Zero-frequency DOFs (surge, sway, yaw): M_A = A∞ − ∫τK dτ (eqs. 22, 25) and
    D = ∫K dτ + B_v(0) (eqs. 23, 26). Natural-frequency DOFs (heave, roll, pitch): ω₀
    from eq. 24 by fixed-point iteration, M_A = A∞ − (1/ω₀)∫K sin ω₀τ dτ (eq. 29) and
    D = ∫K cos ω₀τ dτ + B_v(ω₀) (eq. 30). The integrals are exact for the
    piecewise-linear K through its samples, truncated at its last time. The first
    moment ∫τK dτ weights the late, small part of K: on the bundled tanker A(0) from
    the default grid (88.7 s) is within 3 % of A(0) − A∞ of the solver's ω = 0 row, and
    moves by about as much with the grid's length.

    Parameters
    ----------
    ds
        ``HydroDB`` at one forward speed (zero speed is what Ross, Perez & Fossen (2006)
        assume), with ``inertia_matrix`` and ``hydrostatic_stiffness``.
    kernel
        K(t) (time from 0, influenced_dof, radiating_dof), kg/s² …; default
        :func:`cummins.radiation.retardation.default_retardation_function` of ``ds``.
    added_mass_inf
        A∞ (n, n); default :func:`cummins.radiation.retardation.added_mass_inf` of ``ds``.
    viscous
        ``{dof: spec}``: :class:`ExponentialDamping`, :class:`CriticalDampingFraction`,
        a callable B_v(ω) or a constant, evaluated at the DOF's frequency and added to
        the diagonal of D; or ``"data"``: the database's own ``additional_damping``
        (e.g. a VERES viscous roll damping curve, which a time-domain vessel cannot
        take because it varies with ω) interpolated linearly at that frequency (held
        at its first value below the lowest frequency), replacing the constant part.
    frequencies
        ``{dof: ω}`` (rad/s) to impose a DOF's frequency (e.g. measured in a decay test).
    couplings
        ``"min"`` (default): entry (i, j) at min(ω_i, ω_j), then symmetrised (the mean
        with its transpose removes the data's small asymmetry), so M_A and D are
        symmetric and a coupling with a zero-frequency DOF takes the zero-frequency values (no
        potential damping: D stays positive semi-definite); ``"radiating"``: entry
        (i, j) at ω_j, the frequency of the motion that causes the force — asymmetric,
        and D may then be indefinite (a free sway coupled to a damped roll).
    additional
        Take the database's ``additional_stiffness`` into G and its constant
        ``additional_damping`` into B_v, as :func:`cummins.vessel.vessel_from_hydrodb`.
    potential_b0
        ``"zero"`` (default): the potential part of D in the zero-frequency DOFs is
        B(0) = ∫K dτ = 0, its value at zero speed in deep water (then
        Ross, Perez & Fossen (2006) eq. 26 leaves the viscous β alone); ``"computed"``:
        the number the route gives, which is that zero plus truncation noise of either
        sign (a slightly negative value makes a free DOF unstable). The computed value is
        kept in :attr:`LowFrequencyModel.zero_frequency_damping` either way.
    tol, max_iter
        Convergence of eq. 24 (see :func:`natural_frequency`).

    Returns
    -------
    LowFrequencyModel

    Examples
    --------
    >>> import cummins
    >>> from cummins.timedomain.lfmodel import lf_model_from_retardation
    >>> lf = lf_model_from_retardation(cummins.demo_dataset())
    >>> [round(float(w), 3) for w in lf.frequencies]
    [0.0, 0.0, 0.651, 0.489, 0.689, 0.0]
    """
    from cummins.radiation import retardation

    ds = single_speed(ds)
    if kernel is None:
        kernel = retardation.default_retardation_function(ds)
    if added_mass_inf is None:
        added_mass_inf = retardation.added_mass_inf(ds).values
    labels = [str(d) for d in ds.influenced_dof.values]
    kernel = kernel.sel(influenced_dof=labels, radiating_dof=labels)
    a_inf = np.asarray(added_mass_inf, dtype=float)
    return _build(
        ds,
        _FromKernel(kernel, a_inf),
        viscous=viscous,
        frequencies=frequencies,
        couplings=couplings,
        additional=additional,
        potential_b0=potential_b0,
        tol=tol,
        max_iter=max_iter,
    )


def lf_model_from_frequency_data(
    ds: xr.Dataset,
    *,
    zero_frequency: Literal["auto", "data", "extrapolate"] = "auto",
    points: int = 4,
    viscous: Mapping[str, ViscousSpec] | None = None,
    frequencies: Mapping[str, float] | None = None,
    couplings: Couplings = "min",
    additional: bool = True,
    potential_b0: Literal["zero", "computed"] = "zero",
    tol: float = 1e-10,
    max_iter: int = 100,
) -> LowFrequencyModel:
    """The LF model directly from A(ω), B(ω).

    Ross, Perez & Fossen (2006) eqs. 20–21, 24, and 18–19 at ω₀.

    The same model as :func:`lf_model_from_retardation` computed without K(t): A and B
    are interpolated by cubic splines at ω₀ (eq. 24 solved on the spline); A(0) is the
    solver's ω = 0 row (``"data"``) or an even extrapolation c₀ + c₂ω² of the lowest
    ``points`` frequencies (``"extrapolate"``; ``"auto"``: the row when present); B(0)
    is always extrapolated (≈ 0 at zero speed). ω₀ must lie within the data.

    Parameters are those of :func:`lf_model_from_retardation` plus ``zero_frequency``
    and ``points`` (see :func:`extrapolate_zero_frequency`).

    Examples
    --------
    >>> import cummins
    >>> from cummins.timedomain.lfmodel import lf_model_from_frequency_data
    >>> lf = lf_model_from_frequency_data(cummins.demo_dataset())
    >>> abs(lf.eq24_residual("Roll")) < 1e-6 * float(lf.stiffness[3, 3])
    True
    """
    ds = single_speed(ds)
    return _build(
        ds,
        _FromFrequencyData(ds, zero_frequency, points),
        viscous=viscous,
        frequencies=frequencies,
        couplings=couplings,
        additional=additional,
        potential_b0=potential_b0,
        tol=tol,
        max_iter=max_iter,
    )


# --------------------------------------------------------------------------- comparison


def compare_with_cummins(
    model: LowFrequencyModel,
    vessel: Vessel,
    dof: str,
    *,
    kind: Literal["decay", "step"] = "decay",
    amplitude: float = 0.1,
    duration: float | None = None,
    dt: float | None = None,
) -> xr.Dataset:
    """Free decay or step response of the LF model against the full Cummins vessel.

    Both linear models are run by :func:`cummins.timedomain.simulate.simulate` (exact
    discretisation), so the difference is the modelling, not the integration.

    Parameters
    ----------
    model
        The LF model.
    vessel
        The full Cummins model of the same DOFs (:func:`cummins.vessel.vessel_from_hydrodb`),
        with the same viscous damping.
    dof
        The DOF displaced (``"decay"``) or pushed (``"step"``).
    kind
        ``"decay"``: released from rest at ξ_dof = ``amplitude`` (m or rad) with an
        unloaded memory; ``"step"``: a constant force ``amplitude`` (N or N·m) from t = 0.
    duration
        Seconds; default 10 natural periods for a decay (300 s for a zero-frequency DOF),
        300 s for a step.
    dt
        Step, s; default 1/40 of the natural period (0.5 s for zero-frequency DOFs).

    Returns
    -------
    xarray.Dataset
        ``lf`` and ``cummins`` (time, dof): motions, m or rad; ``difference`` = lf −
        cummins; attributes ``rms_relative`` (RMS of the difference in ``dof`` over the
        RMS of the Cummins response) and ``max_relative`` (max |difference| over max
        |response|).
    """
    from cummins.timedomain.simulate import simulate

    if tuple(vessel.dofs) != tuple(model.dofs):
        raise SimulationError(
            f"the vessel's DOFs {vessel.dofs} differ from the model's {model.dofs}"
        )
    i = model.index(dof)
    w = float(model.frequencies[i])
    period = 2 * np.pi / w if w > 0 else None
    if dt is None:
        dt = period / 40 if period else 0.5
    if duration is None:
        duration = 10 * period if (period and kind == "decay") else 300.0
    n = len(model.dofs)
    check_simulation_size(duration, dt, vessel.n_states, n)
    t = np.arange(0.0, float(duration) + 0.5 * float(dt), float(dt))
    lf_vessel = model.to_vessel()
    force = np.zeros((t.size, n))
    x_lf = np.zeros(lf_vessel.n_states)
    x_full = np.zeros(vessel.n_states)
    if kind == "decay":
        x_lf[i] = x_full[i] = amplitude
    elif kind == "step":
        force[:, i] = amplitude
    else:
        raise SimulationError(f"unknown kind {kind!r}", hint="use 'decay' or 'step'")
    lf = simulate(lf_vessel, t, force, initial_state=x_lf).motion
    full = simulate(vessel, t, force, initial_state=x_full).motion
    diff = lf - full
    ref = full.isel(dof=i).values
    d = diff.isel(dof=i).values
    rms_ref = float(np.sqrt(np.mean(ref**2)))
    out = xr.Dataset({"lf": lf, "cummins": full, "difference": diff})
    out.attrs.update(
        kind=kind,
        dof=dof,
        amplitude=amplitude,
        frequency=w,
        rms_relative=float(np.sqrt(np.mean(d**2)) / rms_ref) if rms_ref > 0 else np.nan,
        max_relative=float(np.abs(d).max() / np.abs(ref).max()) if rms_ref > 0 else np.nan,
    )
    return out


__all__ = [
    "NATURAL_FREQUENCY_DOFS",
    "ZERO_FREQUENCY_DOFS",
    "CriticalDampingFraction",
    "ExponentialDamping",
    "LowFrequencyModel",
    "compare_with_cummins",
    "extrapolate_zero_frequency",
    "lf_model_from_frequency_data",
    "lf_model_from_retardation",
    "natural_frequency",
]
