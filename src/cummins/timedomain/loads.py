"""Environmental and external loads of the nonlinear 6-DOF DP/manoeuvring model.

The loads of Smogeli et al. (2004) §4–5 (the DP model of the Marine Systems Simulator),
each a small frozen dataclass with a ``name`` and a method

    force(t, eta, nu) -> ndarray (6,)

giving the generalized force in the b-frame about the origin O, in N and N·m, at time
``t`` (s), pose η = (N, E, D, φ, θ, ψ) (m, rad) and body velocity ν = (u, v, w, p, q, r)
(m/s, rad/s). Anything with that signature is a :class:`Load` (a ``Protocol``), so users
can add their own (moorings, risers, a thruster model) or wrap a function in
:class:`FunctionLoad`. The simulator calls ``force`` at every Runge–Kutta stage:
everything that can be prepared (interpolation tables, wave numbers, strip weights) is
prepared once when the load is built, and a call costs O(number of wave components).

Conventions
-----------
* b-frame: x forward, y to starboard, z down, origin O: the reference point of the
  hydrodynamic data (``reference_point`` of the ``HydroDB``). n-frame: north-east-down.
* Angles in the n-frame are measured clockwise (seen from above) from North, towards
  East, in rad:

  - waves: β_j is the direction the component **travels to** (as
    :class:`cummins.seakeeping.waves.WaveComponents`). The data are looked up at the relative
    direction β_j − ψ, the ``wave_direction`` of a z-down ``HydroDB`` (from body +x
    towards starboard; π: head seas);
  - current: β_c is the direction the current **flows to** (Smogeli et al. (2004) eq. 40);
  - wind: β_w is the direction the wind **comes from** (meteorological convention): a
    ship heading North (ψ = 0) in a wind from β_w = 0 has a head wind, which pushes it
    aft. The relative wind angle γ_rw = β_w − ψ of Smogeli et al. (2004) §5.5 (for a vessel at rest)
    is then the angle, from the bow towards starboard, the wind comes from.

* Time convention of the wave data x(t) = Re{X e^{iωt}}; wave elevation at the n-frame
  point (N, E): ζ = Σ_j ζ_j cos(ω_j t − k_j (N cos β_j + E sin β_j) + φ_j).

Loads
-----
=============================  ==============================================  =========
class                          model                                           Smogeli et al. (2004)
=============================  ==============================================  =========
:class:`Current`               current velocity, relative velocity (no load)   eqs. 40, 49
:class:`FirstOrderWaveLoad`    first-order wave excitation                     eq. 46
:class:`WaveDriftLoad`         mean and slowly varying drift (Newman)          eqs. 47–48
:class:`SurgeResistance`       ITTC 1957 friction line resistance              eqs. 50–51, 54
:class:`CrossFlowDrag`         cross-flow drag in sway and yaw (strips)        eqs. 52–54
:class:`WindLoad`              wind with gusts (Harris, NORSOK)                eq. 55, §4.2
:class:`PointLoad`             force/moment at a point (crane load)            eq. 45
:class:`ConstantLoad`          constant generalized force
:class:`FunctionLoad`          any user function f(t, η, ν)
=============================  ==============================================  =========
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.special import beta as beta_function
from scipy.special import gamma as gamma_function

from cummins.errors import CumminsError, HydroDataError
from cummins.hydrodb import bodies, change_axes, dof_index, single_speed
from cummins.kinematics import point_load, rotation_matrix
from cummins.seakeeping.excitation import MIRROR_SIGNS, excitation_transfer, heading_coverage
from cummins.seakeeping.waves import WaveComponents, harmonic_sum, wavenumber

__all__ = [
    "HOERNER_DRAG",
    "WIND_SPECTRA",
    "ConstantLoad",
    "CrossFlowDrag",
    "Current",
    "FirstOrderWaveLoad",
    "FunctionLoad",
    "Load",
    "ParametricWindCoefficients",
    "PointLoad",
    "SurgeResistance",
    "WaveDriftLoad",
    "Wind",
    "WindCoefficients",
    "WindGust",
    "WindLoad",
    "denny_mumford_wetted_surface",
    "harris",
    "harris_variance",
    "hoerner_drag_coefficient",
    "ittc_friction",
    "load_forces",
    "norsok",
    "norsok_variance",
    "total_force",
    "wind_gust",
]

_TWO_PI = 2.0 * np.pi

#: Density of sea water, kg/m³ (default of the hydrodynamic loads).
RHO_WATER = 1025.0
#: Density of air at 15 °C and 1013.25 hPa (ISO standard atmosphere), kg/m³.
RHO_AIR = 1.225
#: Kinematic viscosity of sea water at 15 °C, m²/s (ITTC 2011, fresh water 1.14e-6).
NU_WATER = 1.19e-6


# --------------------------------------------------------------------------- protocol


@runtime_checkable
class Load(Protocol):
    """A generalized force on the vessel: anything with a ``name`` and this ``force``.

    ``force(t, eta, nu)`` returns the 6-vector (X, Y, Z, K, M, N) in the b-frame about
    O, N and N·m, at time ``t`` (s), pose ``eta`` (N, E, D in m; φ, θ, ψ in rad) and
    body velocity ``nu`` (u, v, w in m/s; p, q, r in rad/s). It must be a deterministic
    function of its arguments (the simulator evaluates it at Runge–Kutta stages, and
    again when a step is repeated).
    """

    name: str

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """Generalized force (6,), N and N·m, b-frame, about O."""
        ...


def _vector(value: ArrayLike, size: int, what: str) -> NDArray[np.float64]:
    arr = np.array(value, dtype=float).reshape(-1)
    if arr.size != size:
        raise CumminsError(f"{what} must have {size} components, got {arr.size}")
    if not np.all(np.isfinite(arr)):
        raise CumminsError(f"{what} has non-finite components: {arr.tolist()}")
    arr.setflags(write=False)
    return arr


def _positive(value: float, what: str, *, allow_zero: bool = False) -> float:
    value = float(value)
    ok = value >= 0 if allow_zero else value > 0
    if not (np.isfinite(value) and ok):
        bound = ">= 0" if allow_zero else "> 0"
        raise CumminsError(f"{what} must be finite and {bound}, got {value!r}")
    return value


def _frozen_array(value: ArrayLike, dtype: Any = float) -> NDArray:
    arr = np.array(value, dtype=dtype)
    arr.setflags(write=False)
    return arr


def _wrap_2pi(angle: ArrayLike) -> NDArray[np.float64]:
    out = np.mod(np.asarray(angle, dtype=float), _TWO_PI)
    return np.where(out >= _TWO_PI, 0.0, out)


class _PeriodicTable:
    """Periodic linear interpolation in angle, one column per wave component.

    ``values`` has shape (m, n, d): m angles (any order, in rad), n components, d DOFs.
    ``__call__(gamma)`` with gamma of shape (n,) (component j at angle gamma[j]) returns
    shape (n, d). The table is extended by one angle on each side (the neighbours across
    0/2π), so one ``searchsorted`` and two gathers do the work.
    """

    def __init__(self, angles: ArrayLike, values: ArrayLike) -> None:
        a = _wrap_2pi(angles)
        v = np.asarray(values)
        order = np.argsort(a, kind="stable")
        a, v = a[order], v[order]
        if a.size == 0:
            raise CumminsError("an interpolation table needs at least one angle")
        if a.size > 1 and np.min(np.diff(a)) <= 0:
            raise CumminsError("the angles of an interpolation table must be distinct")
        self.angles = np.concatenate([[a[-1] - _TWO_PI], a, [a[0] + _TWO_PI]])
        self.inverse_width = 1.0 / np.diff(self.angles)
        self.last = self.angles.size - 2
        self.n_columns = v.shape[1]
        self.columns = np.arange(v.shape[1])
        extended = np.concatenate([v[-1:], v, v[:1]], axis=0)
        self.flat = np.ascontiguousarray(extended.reshape(-1, *v.shape[2:]))

    def __call__(self, gamma: NDArray[np.float64]) -> NDArray:
        g = np.mod(gamma, _TWO_PI)
        i = np.searchsorted(self.angles, g, side="right") - 1
        np.minimum(i, self.last, out=i)
        w = (g - self.angles[i]) * self.inverse_width[i]
        rows = i * self.n_columns + self.columns
        v0 = self.flat.take(rows, axis=0)
        v1 = self.flat.take(rows + self.n_columns, axis=0)
        return v0 + w[:, None] * (v1 - v0)


# --------------------------------------------------------------------------- current


@dataclass(frozen=True)
class Current:
    """A uniform, steady surface current (Smogeli et al. (2004) §4.3).

    Not a load itself: :class:`SurgeResistance` and :class:`CrossFlowDrag` use it for the
    relative velocity ν_r (eq. 49), and the vessel model replaces ν by ν_r in its
    damping terms (eq. 56).

    Parameters
    ----------
    speed
        U_c, m/s, ≥ 0.
    direction
        β_c, rad: the direction the current flows **to**, clockwise from North (π/2: a
        current setting East).

    Examples
    --------
    >>> import numpy as np
    >>> c = Current(1.0, np.pi / 2)            # setting East
    >>> np.round(c.velocity_body(0.0), 12)     # ship heading North: from port to starboard
    array([0., 1., 0.])
    """

    speed: float
    direction: float = 0.0

    def __post_init__(self) -> None:
        _positive(self.speed, "current speed (m/s)", allow_zero=True)
        if not np.isfinite(self.direction):
            raise CumminsError(f"current direction must be finite, got {self.direction!r} rad")

    def velocity_ned(self) -> NDArray[np.float64]:
        """The current velocity in the n-frame (north, east, down), m/s, shape (3,)."""
        return self.speed * np.array([np.cos(self.direction), np.sin(self.direction), 0.0])

    def velocity_body(self, psi: float) -> NDArray[np.float64]:
        """v_c^b = U_c [cos(β_c − ψ), sin(β_c − ψ), 0], m/s (Smogeli et al. (2004) eq. 40).

        ``psi`` is the heading ψ, rad. Only the heading rotates the current (roll and
        pitch are neglected, as in the paper).
        """
        a = self.direction - float(psi)
        return self.speed * np.array([np.cos(a), np.sin(a), 0.0])

    def relative_velocity(self, eta: ArrayLike, nu: ArrayLike) -> NDArray[np.float64]:
        """ν_r = ν − [v_c^b, 0, 0, 0], shape (6,), m/s and rad/s (Smogeli et al. (2004) eq. 49)."""
        nu_r = np.array(nu, dtype=float).reshape(6)
        nu_r[:3] -= self.velocity_body(np.asarray(eta, dtype=float).reshape(6)[5])
        return nu_r


def _relative_velocity(current: Current | None, eta: ArrayLike, nu: ArrayLike) -> NDArray:
    if current is None:
        return np.asarray(nu, dtype=float).reshape(6)
    return current.relative_velocity(eta, nu)


# --------------------------------------------------------------------------- wave data


def _prepare_hydrodb(ds: xr.Dataset, variable: str) -> tuple[xr.Dataset, NDArray[np.int64]]:
    """One speed, z-down axes, one body; the 6-vector index of each ``influenced_dof``."""
    ds = single_speed(ds)
    if variable not in ds:
        raise HydroDataError(
            f"the dataset has no {variable}",
            path=ds.attrs.get("source_file"),
            quantity=variable,
            hint="read a file that holds it (WAMIT .8/.9, VERES, MSS .mat with driftfrc) "
            "or leave this load out"
            if variable == "drift_force"
            else "read the solver's excitation output with the hydrodynamic coefficients",
        )
    if len(bodies(ds)) != 1:
        raise HydroDataError(
            f"the dataset holds {len(bodies(ds))} bodies; a vessel load needs one",
            path=ds.attrs.get("source_file"),
            hint="select one body's DOFs (cummins.hydrodb.select_dofs)",
        )
    if ds.attrs.get("axis_convention", "z-up") != "z-down":
        ds = change_axes(ds, "z-down")
    index = np.array([dof_index(str(d)) for d in ds.influenced_dof.values], dtype=int)
    return ds, index


def _in_six(values: NDArray, index: NDArray[np.int64]) -> NDArray:
    """Values (..., n_dofs) placed into (..., 6) at the DOF positions ``index``."""
    out = np.zeros((*values.shape[:-1], 6), dtype=values.dtype)
    out[..., index] = values
    return out


def _wave_vectors(k: NDArray, direction: NDArray) -> NDArray:
    """(k_j cos β_j, k_j sin β_j), shape (2, n), rad/m: η[:2] @ it is the phase lag
    k_j (N cos β_j + E sin β_j) of the waves at the vessel's origin."""
    return _frozen_array(np.stack([k * np.cos(direction), k * np.sin(direction)]))


class _UniformPeriodicTable:
    """Interpolation in angle on the uniform grid γ_h = 2πh/m, one column per component.

    ``values`` has shape (m, n, d). ``order=3``: periodic cubic Hermite with central
    difference slopes (Catmull–Rom: exact at the nodes, continuous slope, error O(Δγ³));
    ``order=1``: linear. Each call is a floor, two or four gathers and a weighted sum.
    """

    def __init__(self, values: ArrayLike, order: int) -> None:
        v = np.asarray(values)
        if order not in (1, 3):
            raise CumminsError(f"interpolation order must be 1 or 3, got {order!r}")
        if v.shape[0] < 4:
            raise CumminsError(f"a heading table needs at least 4 headings, got {v.shape[0]}")
        self.order = order
        self.m = v.shape[0]
        self.per_radian = self.m / _TWO_PI
        self.n_columns = v.shape[1]
        self.columns = np.arange(v.shape[1])
        extended = np.concatenate([v[-1:], v, v[:2]], axis=0)  # extended[h + 1] = v[h]
        self.flat = np.ascontiguousarray(extended.reshape(-1, *v.shape[2:]))

    def _stencil(self, gamma: NDArray[np.float64]) -> tuple[NDArray, list[NDArray]]:
        """Rows of the nodes around each γ_j and their weights, shape (n,) each."""
        x = np.mod(gamma, _TWO_PI) * self.per_radian
        i = x.astype(np.intp)
        np.minimum(i, self.m - 1, out=i)
        t = x - i
        rows = i * self.n_columns + self.columns  # extended[i] = v[i − 1]
        if self.order == 1:
            return rows + self.n_columns, [1.0 - t, t]
        # Catmull–Rom weights ½(−t³+2t²−t), ½(3t³−5t²+2), ½(−3t³+4t²+t), ½(t³−t²)
        s = t - 1.0
        ts = 0.5 * t * s
        w0 = ts * s
        w3 = ts * t
        w1 = (1.5 * t - 2.5) * t * t + 1.0
        return rows, [-w0, w1, 1.0 + w0 - w1 - w3, w3]

    def __call__(self, gamma: NDArray[np.float64]) -> NDArray:
        """The interpolated values, shape (n, d)."""
        rows, weights = self._stencil(gamma)
        out = 0.0
        for q, w in enumerate(weights):
            out = out + w[:, None] * self.flat.take(rows + q * self.n_columns, axis=0)
        return out

    def contract(self, gamma: NDArray[np.float64], coefficients: NDArray) -> NDArray:
        """Σ_j c_j T_j(γ_j), shape (d,): the interpolation folded into the sum."""
        rows, weights = self._stencil(gamma)
        out = 0.0
        for q, w in enumerate(weights):
            out = out + (coefficients * w) @ self.flat.take(rows + q * self.n_columns, axis=0)
        return out


@dataclass(frozen=True, eq=False)
class FirstOrderWaveLoad:
    """First-order wave excitation at the instantaneous heading (Smogeli et al. (2004) eq. 46).

    τ_W1^i(t) = Σ_j ζ_j |T^i_j| cos(ω_j t + φ_j − k_j (N cos β_j + E sin β_j) + arg T^i_j),
    T^i_j = T^i(ω_j, β_j − ψ),

    with T the ``excitation_force`` of the data (N/m, N·m/m, phase relative to the wave
    elevation at O), looked up at the relative direction β_j − ψ of each component and
    at the vessel's horizontal position (N, E) (m), so that a drifting or turning vessel
    stays consistent with the elevation :meth:`WaveComponents.elevation` gives there.
    Forces are in the data's (z-down) axes about its reference point: the b-frame about
    O. Roll and pitch do not enter (Smogeli et al. (2004) Assumption A1).

    Build it with :meth:`from_hydrodb`, which tabulates T(ω_j, γ_h) for every component
    on a uniform grid of relative headings γ_h = 2πh/m (every 2.5° by default) with
    :func:`cummins.seakeeping.excitation.excitation_transfer` (frequency and heading interpolation,
    mirroring of half-plane data); each call interpolates that table periodically in
    γ_j = β_j − ψ, by a cubic (Catmull–Rom, default) or linearly. On a grid heading,
    and with the vessel at (0, 0), the force equals
    :func:`cummins.seakeeping.excitation.excitation_force`.

    Why cubic: the excitation of short waves turns quickly with the heading (the wave
    crest runs along the hull: a phase of order k (L/2) Δcos γ, 3 rad per 5° at
    ω = 2 rad/s on the 175 m S-175). Over all headings and 200 components of a JONSWAP
    sea (ω 0.3–2 rad/s) the S-175 table departs from ``excitation_transfer`` by at most
    (fraction of each DOF's largest |T|): linear 9 % at 5°, 2.4 % at 2.5°, 0.6 % at 1°;
    cubic 2.8 % at 5°, 0.34 % at 2.5°.

    Attributes
    ----------
    waves
        The sea state (directions β_j in the n-frame, clockwise from North).
    transfer
        T(ω_j, γ_h), complex, shape (m, n, 6), N/m and N·m/m, at γ_h = 2πh/m (zero for
        DOFs the data lack).
    wavenumbers
        k_j, rad/m, shape (n,).
    heading_interpolation
        ``"cubic"`` (default) or ``"linear"``.
    position_phase
        Include the phase of the vessel's horizontal position (default True).
    name
        Name of the load.
    """

    waves: WaveComponents
    transfer: NDArray[np.complex128]
    wavenumbers: NDArray[np.float64]
    heading_interpolation: str = "cubic"
    position_phase: bool = True
    name: str = "first-order waves"
    _table: _UniformPeriodicTable = field(init=False, repr=False)
    _amplitude: NDArray[np.complex128] = field(init=False, repr=False)
    _k: NDArray[np.float64] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        n = len(self.waves)
        transfer = np.asarray(self.transfer, dtype=complex)
        if transfer.ndim != 3 or transfer.shape[1:] != (n, 6):
            raise CumminsError(
                f"transfer has shape {transfer.shape}; expected (n_headings, n_components, 6) "
                f"with {n} components"
            )
        k = np.asarray(self.wavenumbers, dtype=float).reshape(-1)
        if k.size != n:
            raise CumminsError(f"{k.size} wave numbers for {n} wave components")
        orders = {"cubic": 3, "linear": 1}
        if self.heading_interpolation not in orders:
            raise CumminsError(
                f"heading_interpolation must be 'cubic' or 'linear', "
                f"got {self.heading_interpolation!r}"
            )
        object.__setattr__(self, "transfer", _frozen_array(transfer, complex))
        object.__setattr__(self, "wavenumbers", _frozen_array(k))
        table = _UniformPeriodicTable(transfer, orders[self.heading_interpolation])
        object.__setattr__(self, "_table", table)
        object.__setattr__(self, "_amplitude", self.waves.complex_amplitude)
        object.__setattr__(self, "_k", _wave_vectors(k, self.waves.direction))

    @property
    def headings(self) -> NDArray[np.float64]:
        """Relative headings γ_h = 2πh/m of the table, rad, shape (m,)."""
        m = self.transfer.shape[0]
        return np.arange(m) * (_TWO_PI / m)

    @classmethod
    def from_hydrodb(
        cls,
        ds: xr.Dataset,
        waves: WaveComponents,
        *,
        heading_step: float = np.radians(2.5),
        heading_interpolation: str = "cubic",
        position_phase: bool = True,
        name: str = "first-order waves",
        **options: Any,
    ) -> FirstOrderWaveLoad:
        """Tabulate the excitation of every component of ``waves`` over relative headings.

        Parameters
        ----------
        ds
            A ``HydroDB`` at one forward speed with ``excitation_force`` (z-up data are
            turned to z-down axes first; the reference point is the b-frame origin O).
        waves
            The sea state.
        heading_step
            Largest spacing of the table in relative heading, rad (2.5° by default: 144
            headings; rounded down to divide 360°). The table holds
            m × n × 6 complex numbers (2.2 MB for 200 components at 2.5°) and takes
            about 0.4 s to build for 200 components.
        heading_interpolation, position_phase, name
            As the attributes.
        **options
            Passed to :func:`cummins.seakeeping.excitation.excitation_transfer` (``extrapolate``,
            ``method``, ``mirror`` …): components outside the data's frequency range
            raise unless ``extrapolate="zero"``.
        """
        ds, index = _prepare_hydrodb(ds, "excitation_force")
        step = _positive(heading_step, "heading_step (rad)")
        m = max(int(np.ceil(_TWO_PI / step - 1e-9)), 4)
        headings = np.arange(m) * (_TWO_PI / m)
        n = len(waves)
        omega = np.tile(waves.omega, m)
        gamma = np.repeat(headings, n)
        t = excitation_transfer(ds, omega, gamma, **options).reshape(m, n, -1)
        k = wavenumber(
            waves.omega, float(ds.attrs.get("water_depth", np.inf)), float(ds.attrs.get("g", 9.81))
        )
        return cls(waves, _in_six(t, index), k, heading_interpolation, position_phase, name)

    def transfer_at(self, psi: float) -> NDArray[np.complex128]:
        """T(ω_j, β_j − ψ) of every component, shape (n, 6), N/m and N·m/m."""
        return self._table(self.waves.direction - float(psi))

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ_W1(t), shape (6,), N and N·m, b-frame about O (eq. 46)."""
        eta = np.asarray(eta, dtype=float)
        phase = self.waves.omega * float(t)
        if self.position_phase:
            phase = phase - eta[:2] @ self._k
        c = self._amplitude * np.exp(1j * phase)
        return self._table.contract(self.waves.direction - eta[5], c).real


def _frequency_weights(
    w: NDArray[np.float64], targets: NDArray[np.float64], extrapolate: str, where: str | None
) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.bool_]]:
    """Linear interpolation in ω: lower index, weight of the upper point, inside mask."""
    tol = 1e-9 * w[-1]
    inside = (targets >= w[0] - tol) & (targets <= w[-1] + tol)
    if not inside.all():
        if extrapolate == "raise":
            bad = targets[~inside][0]
            raise HydroDataError(
                f"frequency {bad:.6g} rad/s is outside the data's range "
                f"{w[0]:.6g} to {w[-1]:.6g} rad/s",
                path=where,
                quantity="drift_force",
                hint="limit the wave components to that range, or pass extrapolate='zero' "
                "(no drift outside it) or 'nearest' (the end values)",
            )
        if extrapolate not in ("zero", "nearest"):
            raise ValueError(
                f"extrapolate must be 'raise', 'zero' or 'nearest', got {extrapolate!r}"
            )
    x = np.clip(targets, w[0], w[-1])
    i = np.clip(np.searchsorted(w, x, side="right") - 1, 0, max(w.size - 2, 0))
    if w.size == 1:
        return i, np.zeros(x.size), inside
    weight = (x - w[i]) / (w[i + 1] - w[i])
    return i, weight, inside


@dataclass(frozen=True, eq=False)
class WaveDriftLoad:
    """Mean and slowly varying wave drift, Newman's approximation (Smogeli et al. (2004) eqs.
    47–48).

    τ_W2^i = Σ_j Σ_k ζ_j ζ_k T^i_jk cos(θ_k − θ_j),  T_jk = ½ (T_jj + T_kk),

    θ_j = ω_j t + φ_j − k_j (N cos β_j + E sin β_j), with T_jj = T^i(ω_j, β_j − ψ) the
    mean drift force per squared wave amplitude (``drift_force`` of the data, N/m² and
    N·m/m²) at the instantaneous relative heading. The double sum is evaluated in
    O(n) operations by the identity

        Σ_j Σ_k ζ_j ζ_k ½(T_jj + T_kk) cos(θ_k − θ_j) = Re[(Σ_j T_jj ζ_j e^{iθ_j}) ·
        conj(Σ_k ζ_k e^{iθ_k})]

    (the two halves of ½(T_jj + T_kk) give equal sums). The mean part (j = k) is
    Σ_j ζ_j² T_jj; ``slowly_varying=False`` keeps only it. The mean drift is valid for
    long- and short-crested seas; the slowly varying part (j ≠ k) is strictly valid for
    long-crested seas only (Smogeli et al. (2004) §5.3): in a spread sea it is an approximation
    that pairs components of all directions.

    The force acts at ``point`` (b-frame; τ_W2 = Hᵀ(r_W2) [τ^1 … τ^6], eq. 48): the
    point about which the drift data are given, O by default (cummins readers move all
    data to the reference point O).

    Build it with :meth:`from_hydrodb`: T(ω_j, β_h) is interpolated linearly in ω for
    every component at the data's own headings β_h (completed by port/starboard
    mirroring when the data cover a half-plane), and each call interpolates linearly
    and periodically in β_j − ψ.

    Attributes
    ----------
    waves
        The sea state.
    headings
        Relative headings of the table, rad, shape (m,).
    drift
        T(ω_j, γ_h), shape (m, n, 6), N/m² and N·m/m².
    wavenumbers
        k_j, rad/m, shape (n,).
    slowly_varying
        Include the slowly varying part (default True).
    point
        Point of attack r_W2, m, b-frame (default O).
    position_phase
        Include the phase of the vessel's horizontal position (default True).
    name
        Name of the load.
    """

    waves: WaveComponents
    headings: NDArray[np.float64]
    drift: NDArray[np.float64]
    wavenumbers: NDArray[np.float64]
    slowly_varying: bool = True
    point: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    position_phase: bool = True
    name: str = "wave drift"
    _table: _PeriodicTable = field(init=False, repr=False)
    _k: NDArray[np.float64] = field(init=False, repr=False)
    _offset: bool = field(init=False, repr=False)

    def __post_init__(self) -> None:
        n = len(self.waves)
        drift = np.asarray(self.drift, dtype=float)
        headings = np.asarray(self.headings, dtype=float).reshape(-1)
        if drift.shape != (headings.size, n, 6):
            raise CumminsError(
                f"drift has shape {drift.shape}; expected (n_headings, n_components, 6) "
                f"= ({headings.size}, {n}, 6)"
            )
        k = np.asarray(self.wavenumbers, dtype=float).reshape(-1)
        if k.size != n:
            raise CumminsError(f"{k.size} wave numbers for {n} wave components")
        object.__setattr__(self, "headings", _frozen_array(headings))
        object.__setattr__(self, "drift", _frozen_array(drift))
        object.__setattr__(self, "wavenumbers", _frozen_array(k))
        object.__setattr__(self, "point", _vector(self.point, 3, "drift point of attack (m)"))
        object.__setattr__(self, "_table", _PeriodicTable(headings, drift))
        object.__setattr__(self, "_k", _wave_vectors(k, self.waves.direction))
        object.__setattr__(self, "_offset", bool(np.any(self.point != 0.0)))

    @classmethod
    def from_hydrodb(
        cls,
        ds: xr.Dataset,
        waves: WaveComponents,
        *,
        slowly_varying: bool = True,
        extrapolate: str = "raise",
        mirror: bool | None = None,
        max_heading_gap: float = np.pi / 2,
        point: ArrayLike = (0.0, 0.0, 0.0),
        position_phase: bool = True,
        name: str = "wave drift",
    ) -> WaveDriftLoad:
        """Tabulate the mean drift coefficients of every component of ``waves``.

        Parameters
        ----------
        ds
            A ``HydroDB`` at one forward speed with ``drift_force`` (N/m², N·m/m² per
            squared amplitude); z-up data are turned to z-down axes first.
        waves
            The sea state.
        slowly_varying
            Include the slowly varying part (Newman); False: the mean drift only.
        extrapolate
            Components outside the data's frequency range: ``"raise"`` (default),
            ``"zero"`` (no drift there) or ``"nearest"`` (the end value: the
            short-wave limit of full reflection above the range).
        mirror
            Complete half-plane headings by port/starboard symmetry: None decides as
            :func:`cummins.seakeeping.excitation.heading_coverage` does (from the excitation and
            radiation data; no mirroring without ``excitation_force``), True, False.
        max_heading_gap
            Widest arc without data (rad) across which to interpolate; a wider gap
            raises HydroDataError.
        point, position_phase, name
            As the attributes.

        Raises
        ------
        HydroDataError
            No ``drift_force`` in the dataset, a frequency out of range, a heading gap.
        """
        ds, index = _prepare_hydrodb(ds, "drift_force")
        where = ds.attrs.get("source_file")
        if "wave_direction" not in ds["drift_force"].dims:
            raise HydroDataError("drift_force has no wave_direction dimension", path=where)
        use = mirror if (mirror is not None or "excitation_force" in ds) else False
        coverage = heading_coverage(ds, mirror=use)
        gaps = coverage.gaps(max_heading_gap)
        if gaps:
            a, b = gaps[0]
            raise HydroDataError(
                f"drift_force has no heading between {np.degrees(a):.4g}° and "
                f"{np.degrees(b):.4g}° (relative wave directions)",
                path=where,
                quantity="drift_force",
                hint="pass mirror=True if the hull is port/starboard symmetric, or "
                "max_heading_gap= to interpolate across the gap",
            )
        data = ds["drift_force"].transpose("omega", "wave_direction", "influenced_dof").values
        data = np.asarray(data, dtype=float)[:, coverage.source, :]
        if coverage.mirror_used:
            signs = MIRROR_SIGNS[index]
            data = np.where(coverage.mirrored[None, :, None], data * signs, data)
        w = ds.omega.values.astype(float)
        i, weight, inside = _frequency_weights(w, waves.omega, extrapolate, where)
        hi = np.minimum(i + 1, w.size - 1)
        at = (1.0 - weight)[:, None, None] * data[i] + weight[:, None, None] * data[hi]
        if extrapolate == "zero":
            at[~inside] = 0.0
        table = _in_six(np.transpose(at, (1, 0, 2)), index)  # (m, n, 6)
        k = wavenumber(
            waves.omega, float(ds.attrs.get("water_depth", np.inf)), float(ds.attrs.get("g", 9.81))
        )
        return cls(
            waves, coverage.directions, table, k, slowly_varying, point, position_phase, name
        )

    def drift_at(self, psi: float) -> NDArray[np.float64]:
        """T_jj = T(ω_j, β_j − ψ) of every component, shape (n, 6), N/m² and N·m/m²."""
        return self._table(self.waves.direction - float(psi))

    def mean_force(self, psi: float) -> NDArray[np.float64]:
        """The mean drift Σ_j ζ_j² T_jj at heading ψ (rad), shape (6,), N and N·m, at O."""
        return self._at_point((self.waves.amplitude**2) @ self.drift_at(psi))

    def _at_point(self, tau: NDArray[np.float64]) -> NDArray[np.float64]:
        """Hᵀ(r_W2) τ (eq. 48); τ itself when the point is O."""
        return point_load(tau[:3], self.point, tau[3:]) if self._offset else tau

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ_W2(t), shape (6,), N and N·m, b-frame about O (eqs. 47–48)."""
        eta = np.asarray(eta, dtype=float)
        t_jj = self.drift_at(eta[5])
        if not self.slowly_varying:
            tau = (self.waves.amplitude**2) @ t_jj
        else:
            phase = self.waves.omega * float(t) + self.waves.phase
            if self.position_phase:
                phase = phase - eta[:2] @ self._k
            c = self.waves.amplitude * np.exp(1j * phase)
            tau = (np.conj(c.sum()) * (c @ t_jj)).real
        return self._at_point(tau)


# --------------------------------------------------------------------------- viscous loads


def ittc_friction(reynolds: ArrayLike) -> NDArray[np.float64]:
    """ITTC 1957 model–ship correlation line C_f = 0.075 / (log₁₀ Rn − 2)² (Smogeli et al. (2004)
    eq. 51).

    Parameters
    ----------
    reynolds
        Reynolds number Rn = U L / ν (> 100; the line is meant for Rn ≳ 1e5).

    Examples
    --------
    >>> round(float(ittc_friction(1e9)), 7)   # 0.075 / 7²
    0.0015306
    """
    rn = np.asarray(reynolds, dtype=float)
    if np.any(~(rn > 100.0)):
        raise CumminsError("the ITTC 1957 line needs Reynolds numbers above 100")
    return 0.075 / (np.log10(rn) - 2.0) ** 2


def denny_mumford_wetted_surface(
    length: float, breadth: float, draught: float, block_coefficient: float
) -> float:
    """Wetted surface estimate S = 1.7 L T + ∇/T = L (1.7 T + C_B B), m².

    Denny–Mumford formula (Mumford's approximation, as given e.g. by Molland, Turnock &
    Hudson, *Ship Resistance and Propulsion*, 2011, §10.1), with ∇ = C_B L B T. For
    conventional displacement hulls it is within a few per cent.

    Examples
    --------
    >>> round(denny_mumford_wetted_surface(175.0, 25.4, 9.5, 0.57))  # S-175
    5360
    """
    length = _positive(length, "length (m)")
    breadth = _positive(breadth, "breadth (m)")
    draught = _positive(draught, "draught (m)")
    cb = _positive(block_coefficient, "block coefficient")
    return float(length * (1.7 * draught + cb * breadth))


@dataclass(frozen=True)
class SurgeResistance:
    """Quadratic surge resistance from the ITTC 1957 friction line (Smogeli et al. (2004) eqs.
    50–51).

    f_1 = −(ρ/2) S (1 + k) (C_f(Rn) + ΔC_f) |u_r| u_r,  Rn = |u_r| L / ν_w,

    opposing the relative surge velocity u_r = u − U_c cos(β_c − ψ) (eq. 49), applied at
    ``point``: τ = Hᵀ(r_c) [f_1, 0, 0, 0, 0, 0] (eq. 54; the paper suggests r_c =
    [0, 0, T/2] when O is in the waterline). Below ``min_reynolds`` (default 1e5, where
    the line stops being meaningful and diverges towards Rn = 100) C_f is held at its
    value at ``min_reynolds``: the force still goes to 0 as u_r² when u_r → 0.

    Parameters
    ----------
    wetted_surface
        S, m² (:func:`denny_mumford_wetted_surface` estimates it).
    length
        L, m: the length of the Reynolds number (waterline length).
    form_factor
        k, dimensionless viscous form factor (0.1 by default; 0.05–0.4, growing with
        fullness).
    roughness_allowance
        ΔC_f, dimensionless (0 by default; 0.0002–0.0004 for ship hulls).
    density
        ρ_w, kg/m³.
    viscosity
        ν_w, kinematic viscosity of water, m²/s (1.19e-6: sea water at 15 °C).
    current
        The current of the relative velocity (None: still water).
    point
        r_c, m, b-frame.
    min_reynolds
        Rn below which C_f is held constant.
    name
        Name of the load.

    Examples
    --------
    >>> import numpy as np
    >>> load = SurgeResistance(wetted_surface=5000.0, length=175.0)
    >>> float(load.force(0.0, np.zeros(6), [5.0, 0, 0, 0, 0, 0])[0]) < 0  # resists ahead
    True
    """

    wetted_surface: float
    length: float
    form_factor: float = 0.1
    roughness_allowance: float = 0.0
    density: float = RHO_WATER
    viscosity: float = NU_WATER
    current: Current | None = None
    point: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    min_reynolds: float = 1e5
    name: str = "surge resistance"

    def __post_init__(self) -> None:
        _positive(self.wetted_surface, "wetted surface (m²)")
        _positive(self.length, "length (m)")
        _positive(self.density, "water density (kg/m³)")
        _positive(self.viscosity, "kinematic viscosity (m²/s)")
        if not (np.isfinite(self.form_factor) and self.form_factor > -1):
            raise CumminsError(f"form factor must be > -1, got {self.form_factor!r}")
        if not np.isfinite(self.roughness_allowance):
            raise CumminsError("roughness allowance must be finite")
        if not (np.isfinite(self.min_reynolds) and self.min_reynolds > 100):
            raise CumminsError(f"min_reynolds must be > 100, got {self.min_reynolds!r}")
        object.__setattr__(self, "point", _vector(self.point, 3, "resistance point of attack (m)"))

    @classmethod
    def from_main_particulars(
        cls,
        length: float,
        breadth: float,
        draught: float,
        block_coefficient: float,
        **options: Any,
    ) -> SurgeResistance:
        """With S from :func:`denny_mumford_wetted_surface`; ``options`` as the class."""
        s = denny_mumford_wetted_surface(length, breadth, draught, block_coefficient)
        return cls(wetted_surface=s, length=length, **options)

    def friction_coefficient(self, speed: float) -> float:
        """C_f at the relative speed |u_r| (m/s), with the small-Rn guard."""
        rn = max(abs(float(speed)) * self.length / self.viscosity, self.min_reynolds)
        return float(ittc_friction(rn))

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ, shape (6,), N and N·m (eqs. 50, 54)."""
        u_r = float(_relative_velocity(self.current, eta, nu)[0])
        c = (1.0 + self.form_factor) * (self.friction_coefficient(u_r) + self.roughness_allowance)
        f1 = -0.5 * self.density * self.wetted_surface * c * abs(u_r) * u_r
        return point_load([f1, 0.0, 0.0], self.point)


#: Hoerner's 2-D cross-flow drag coefficient of a ship section against B/(2T): pairs
#: (B/(2T), C_D) digitised from Hoerner (1965), *Fluid-Dynamic Drag*, as tabulated in the
#: MSS function ``Hoerner.m`` (Fossen; data as in Leite et al. 1998, Appl. Ocean Res. 20).
HOERNER_DRAG = np.array(
    [
        [0.0108623, 1.96608],
        [0.176606, 1.96573],
        [0.353025, 1.89756],
        [0.451863, 1.78718],
        [0.472838, 1.58374],
        [0.492877, 1.27862],
        [0.493252, 1.21082],
        [0.558473, 1.08356],
        [0.646401, 0.998631],
        [0.833589, 0.87959],
        [0.988002, 0.828415],
        [1.30807, 0.759941],
        [1.63918, 0.691442],
        [1.85998, 0.657076],
        [2.31288, 0.630693],
        [2.59998, 0.596186],
        [3.00877, 0.586846],
        [3.45075, 0.585909],
        [3.7379, 0.559877],
        [4.00309, 0.559315],
    ]
)
HOERNER_DRAG.setflags(write=False)


def hoerner_drag_coefficient(breadth: ArrayLike, draught: ArrayLike) -> NDArray[np.float64]:
    """Hoerner's 2-D cross-flow drag coefficient C_D(B/(2T)) of a ship section.

    Linear interpolation in :data:`HOERNER_DRAG` (Hoerner 1965; the curve of MSS
    ``Hoerner.m``), held at the end values outside B/(2T) ∈ [0.011, 4.0] (deep, narrow
    sections: 1.97; flat, wide ones: 0.56).

    Parameters
    ----------
    breadth, draught
        Section breadth B and draught T, m (arrays broadcast).

    Examples
    --------
    >>> round(float(hoerner_drag_coefficient(25.4, 9.5)), 3)   # S-175: B/2T = 1.34
    0.754
    """
    b = np.asarray(breadth, dtype=float)
    t = np.asarray(draught, dtype=float)
    if np.any(~(b > 0)) or np.any(~(t > 0)):
        raise CumminsError("Hoerner's drag coefficient needs positive breadth and draught (m)")
    return np.interp(b / (2.0 * t), HOERNER_DRAG[:, 0], HOERNER_DRAG[:, 1])


@dataclass(frozen=True, eq=False)
class CrossFlowDrag:
    """Cross-flow drag in sway and yaw by strip theory (Smogeli et al. (2004) eqs. 52–54).

    f_2 = −(ρ/2) ∫ T(x) C_D(x) v_r^x |v_r^x| dx,  f_6 = −(ρ/2) ∫ x T(x) C_D(x) v_r^x |v_r^x| dx,

    v_r^x(x) = v_r + r x the relative cross-flow velocity of the strip at x (m from O,
    forward), v_r = v − U_c sin(β_c − ψ) (eq. 49). The integrals are sums over strips
    (midpoint rule). The signs make the loads oppose the motion (the paper's eqs. 52–54
    combine to a force along it; MSS ``crossFlowDrag.m`` has these signs): a sway to
    starboard gives a force to port, a yaw rate a moment against it. Applied at
    ``point``: τ = Hᵀ(r_c) [0, f_2, 0, 0, 0, f_6] (eq. 54). ``force`` returns this τ,
    which is −d(ν_r) of eq. 56: it is added to the right-hand side like every load.

    Attributes
    ----------
    x
        Strip centres, m, b-frame x from O, shape (n,).
    width
        Strip lengths dx, m, shape (n,) (or a scalar).
    draught
        T(x), m, shape (n,) (or a scalar).
    drag_coefficient
        C_D(x), 2-D drag coefficient, shape (n,) (or a scalar).
    density
        ρ_w, kg/m³.
    current
        Current of the relative velocity (None: still water).
    point
        r_c, m, b-frame (default O).
    name
        Name of the load.

    Examples
    --------
    >>> import numpy as np
    >>> drag = CrossFlowDrag.from_main_particulars(100.0, 20.0, 8.0, drag_coefficient=1.0)
    >>> tau = drag.force(0.0, np.zeros(6), [0, 1.0, 0, 0, 0, 0])    # 1 m/s to starboard
    >>> float(tau[1])                                               # −ρ/2 C_D T L v|v|
    -410000.0
    """

    x: NDArray[np.float64]
    width: NDArray[np.float64]
    draught: NDArray[np.float64]
    drag_coefficient: NDArray[np.float64]
    density: float = RHO_WATER
    current: Current | None = None
    point: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    name: str = "cross-flow drag"
    _weights: NDArray[np.float64] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        x = np.array(self.x, dtype=float).reshape(-1)
        if x.size == 0 or not np.all(np.isfinite(x)):
            raise CumminsError("cross-flow drag needs finite strip positions x (m)")
        arrays = {}
        for name, what in (
            ("width", "strip width (m)"),
            ("draught", "strip draught (m)"),
            ("drag_coefficient", "drag coefficient"),
        ):
            value = np.array(np.broadcast_to(np.asarray(getattr(self, name), float), x.shape))
            if np.any(~np.isfinite(value)) or np.any(value < 0):
                raise CumminsError(f"cross-flow {what} must be finite and >= 0")
            arrays[name] = value
        _positive(self.density, "water density (kg/m³)")
        for name, value in (("x", x), *arrays.items()):
            object.__setattr__(self, name, _frozen_array(value))
        object.__setattr__(self, "point", _vector(self.point, 3, "drag point of attack (m)"))
        weights = (
            0.5 * self.density * arrays["width"] * arrays["draught"] * arrays["drag_coefficient"]
        )
        object.__setattr__(self, "_weights", _frozen_array(weights))

    @classmethod
    def from_main_particulars(
        cls,
        length: float,
        breadth: float,
        draught: float,
        *,
        drag_coefficient: float | str = "hoerner",
        n_strips: int = 40,
        x_aft: float | None = None,
        density: float = RHO_WATER,
        current: Current | None = None,
        point: ArrayLike = (0.0, 0.0, 0.0),
        name: str = "cross-flow drag",
    ) -> CrossFlowDrag:
        """A box-like hull: constant draught and C_D over ``n_strips`` equal strips.

        Parameters
        ----------
        length, breadth, draught
            L_pp, B, T, m.
        drag_coefficient
            ``"hoerner"`` (default: :func:`hoerner_drag_coefficient` (B, T)) or a
            constant C_D.
        n_strips
            Number of strips (midpoint rule; exact for pure sway, error O(1/n²) with
            yaw).
        x_aft
            x of the aft end, m (default −L/2: the hull centred on O).
        density, current, point, name
            As the attributes.
        """
        length = _positive(length, "length (m)")
        draught = _positive(draught, "draught (m)")
        n = int(n_strips)
        if n < 1:
            raise CumminsError(f"n_strips must be at least 1, got {n_strips!r}")
        if isinstance(drag_coefficient, str):
            if drag_coefficient.lower() != "hoerner":
                raise CumminsError(
                    f"unknown drag coefficient {drag_coefficient!r}; use 'hoerner' or a number"
                )
            cd = float(hoerner_drag_coefficient(breadth, draught))
        else:
            cd = _positive(drag_coefficient, "drag coefficient", allow_zero=True)
        start = -0.5 * length if x_aft is None else float(x_aft)
        dx = length / n
        x = start + dx * (np.arange(n) + 0.5)
        return cls(x, dx, draught, cd, density, current, point, name)

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ, shape (6,), N and N·m (eqs. 52–54)."""
        nu_r = _relative_velocity(self.current, eta, nu)
        vx = nu_r[1] + nu_r[5] * self.x
        q = self._weights * vx * np.abs(vx)
        return point_load([0.0, -q.sum(), 0.0], self.point, [0.0, 0.0, -(q @ self.x)])


# --------------------------------------------------------------------------- wind


def harris(
    omega: ArrayLike,
    mean_speed: float,
    *,
    drag_coefficient: float = 0.0026,
    length_scale: float = 1800.0,
) -> NDArray[np.float64]:
    """Harris (1971) wind gust spectrum S(ω), (m/s)²·s/rad, one-sided.

    In frequency f (Hz): S_f = 4 κ L Ū₁₀ / (2 + x²)^{5/6}, x = f L / Ū₁₀ (DNV, 2000,
    *Environmental conditions and environmental loads*; Smogeli et al. (2004) §4.2); here
    S(ω) = S_f(ω/2π)/(2π). Its variance is :func:`harris_variance`,
    σ² = 4 κ Ū₁₀² · 2^{−1/3} √π Γ(1/3) / (2 Γ(5/6)) ≈ 6.68 κ Ū₁₀², whatever L.

    Parameters
    ----------
    omega
        Frequencies, rad/s (≤ 0 gives 0).
    mean_speed
        Ū₁₀, the mean wind speed at 10 m, m/s (> 0).
    drag_coefficient
        κ, the surface drag coefficient (typically 0.002–0.003 over the open sea).
    length_scale
        L, m (1800 m in Harris' fit).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy import integrate
    >>> value, _ = integrate.quad(lambda w: harris(w, 10.0), 0, np.inf, limit=500)
    >>> round(value / harris_variance(10.0), 6)
    1.0
    """
    u = _positive(mean_speed, "mean wind speed (m/s)")
    kappa = _positive(drag_coefficient, "surface drag coefficient")
    scale = _positive(length_scale, "length scale (m)")
    w = np.asarray(omega, dtype=float)
    f = w / _TWO_PI
    s = 4.0 * kappa * scale * u / (2.0 + (f * scale / u) ** 2) ** (5.0 / 6.0) / _TWO_PI
    return np.where(w > 0, s, 0.0)


def harris_variance(mean_speed: float, *, drag_coefficient: float = 0.0026) -> float:
    """Variance σ² of the :func:`harris` gust, (m/s)²: 4 κ Ū² 2^{−1/3} √π Γ(1/3)/(2Γ(5/6))."""
    u = _positive(mean_speed, "mean wind speed (m/s)")
    kappa = _positive(drag_coefficient, "surface drag coefficient")
    integral = (
        2.0 ** (-1.0 / 3.0) * np.sqrt(np.pi) * gamma_function(1 / 3) / (2 * gamma_function(5 / 6))
    )
    return float(4.0 * kappa * u**2 * integral)


_NORSOK_N = 0.468


def norsok(omega: ArrayLike, mean_speed: float, *, height: float = 10.0) -> NDArray[np.float64]:
    """NORSOK N-003 (1999) wind spectrum (the API RP 2A / Frøya spectrum) S(ω), (m/s)²·s/rad.

    In frequency f (Hz): S_f = 320 (U₀/10)² (z/10)^{0.45} / (1 + f̃ⁿ)^{5/(3n)},
    f̃ = 172 f (z/10)^{2/3} (U₀/10)^{−0.75}, n = 0.468, with U₀ the one-hour mean wind
    speed at 10 m (m/s) and z the height above the sea (m); S(ω) = S_f(ω/2π)/(2π). Its
    variance is :func:`norsok_variance`, (A/(c n)) B(1/n, 2/(3n)) with A the numerator,
    c = 172 (z/10)^{2/3} (U₀/10)^{−0.75} and B the beta function.

    Parameters
    ----------
    omega
        Frequencies, rad/s (≤ 0 gives 0).
    mean_speed
        U₀, m/s (> 0).
    height
        z, m (> 0).
    """
    a, c = _norsok_constants(mean_speed, height)
    w = np.asarray(omega, dtype=float)
    f = np.maximum(w, 0.0) / _TWO_PI
    s = a / (1.0 + (c * f) ** _NORSOK_N) ** (5.0 / (3.0 * _NORSOK_N)) / _TWO_PI
    return np.where(w > 0, s, 0.0)


def _norsok_constants(mean_speed: float, height: float) -> tuple[float, float]:
    u = _positive(mean_speed, "mean wind speed (m/s)")
    z = _positive(height, "height (m)")
    a = 320.0 * (u / 10.0) ** 2 * (z / 10.0) ** 0.45
    c = 172.0 * (z / 10.0) ** (2.0 / 3.0) * (u / 10.0) ** (-0.75)
    return a, c


def norsok_variance(mean_speed: float, *, height: float = 10.0) -> float:
    """Variance σ² of the :func:`norsok` gust, (m/s)²: (A/(c n)) B(1/n, 2/(3n))."""
    a, c = _norsok_constants(mean_speed, height)
    n = _NORSOK_N
    return float(a / (c * n) * beta_function(1.0 / n, 2.0 / (3.0 * n)))


#: Wind gust spectra by name: S(ω, mean_speed, **options), (m/s)²·s/rad.
WIND_SPECTRA: dict[str, Callable[..., NDArray[np.float64]]] = {"harris": harris, "norsok": norsok}


@dataclass(frozen=True, eq=False)
class WindGust:
    """A gust time series U_g(t) = Σ_k a_k cos(ω_k t + φ_k), m/s (Smogeli et al. (2004) §4.2).

    A deterministic function of t (the simulator may evaluate any time, in any order).
    Build it from a spectrum with :func:`wind_gust`.

    Attributes
    ----------
    omega
        ω_k, rad/s, shape (n,).
    amplitude
        a_k, m/s.
    phase
        φ_k, rad.
    spectrum
        Name of the spectrum realised ("" if built by hand).
    seed
        Seed of the random frequencies and phases, if any.
    """

    omega: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    phase: NDArray[np.float64]
    spectrum: str = ""
    seed: int | None = None

    def __post_init__(self) -> None:
        w = _frozen_array(np.asarray(self.omega, dtype=float).reshape(-1))
        for name in ("omega", "amplitude", "phase"):
            value = np.asarray(getattr(self, name), dtype=float).reshape(-1)
            if value.size != w.size:
                raise CumminsError(f"WindGust.{name} has {value.size} values, omega has {w.size}")
            if not np.all(np.isfinite(value)):
                raise CumminsError(f"WindGust.{name} has non-finite values")
            object.__setattr__(self, name, _frozen_array(value))

    @property
    def variance(self) -> float:
        """Σ a_k²/2, (m/s)²."""
        return float(np.sum(self.amplitude**2) / 2.0)

    def __call__(self, t: float) -> float:
        """U_g(t), m/s, at one time t (s)."""
        return float(self.amplitude @ np.cos(self.omega * float(t) + self.phase))

    def series(self, t: ArrayLike) -> NDArray[np.float64]:
        """U_g at many times (any shape), m/s."""
        t = np.asarray(t, dtype=float)
        c = self.amplitude * np.exp(1j * self.phase)
        return harmonic_sum(t.reshape(-1), self.omega, c).reshape(t.shape)


def wind_gust(
    mean_speed: float,
    spectrum: str | Callable[..., NDArray[np.float64]] = "harris",
    *,
    n_components: int = 100,
    omega_min: float = _TWO_PI / 3600.0,
    omega_max: float = _TWO_PI * 0.5,
    seed: int | None = None,
    **options: Any,
) -> WindGust:
    """Realise a gust spectrum as a sum of harmonics (Smogeli et al. (2004) §4.2).

    The range [ω_min, ω_max] is cut into ``n_components`` bins equally spaced in
    log ω (the gust energy sits at low frequency: a Harris spectrum is flat below
    f ≈ Ū/L, 0.006 Hz at 10 m/s); each bin gets one frequency drawn uniformly inside it,
    the amplitude a_k = √(2 ∫_bin S dω) (16-point Gauss–Legendre) and a random phase, so
    Σ a_k²/2 equals the spectrum's variance over the range, and the series does not
    repeat.

    Parameters
    ----------
    mean_speed
        Mean wind speed at 10 m, m/s.
    spectrum
        ``"harris"``, ``"norsok"`` or a function S(ω, mean_speed, **options).
    n_components
        Number of harmonics.
    omega_min, omega_max
        Range, rad/s (default: periods of one hour to 2 s).
    seed
        Integer seed of the random frequencies and phases (None: drawn at random and
        recorded in the result).
    **options
        Passed to the spectrum (``drag_coefficient``, ``length_scale``, ``height``).

    Examples
    --------
    >>> g = wind_gust(10.0, "norsok", seed=1)
    >>> g(100.0) == wind_gust(10.0, "norsok", seed=1)(100.0)
    True
    """
    if isinstance(spectrum, str):
        try:
            function = WIND_SPECTRA[spectrum.lower()]
        except KeyError:
            raise CumminsError(
                f"unknown wind spectrum {spectrum!r}; use one of {', '.join(WIND_SPECTRA)}"
            ) from None
        label = spectrum.lower()
    else:
        function, label = spectrum, getattr(spectrum, "__name__", "custom")
    n = int(n_components)
    if n < 1:
        raise CumminsError(f"n_components must be at least 1, got {n_components!r}")
    lo = _positive(omega_min, "omega_min (rad/s)")
    hi = _positive(omega_max, "omega_max (rad/s)")
    if not hi > lo:
        raise CumminsError(f"omega_max ({hi} rad/s) must exceed omega_min ({lo} rad/s)")
    if seed is None:
        seed = int(np.random.SeedSequence().entropy)
    rng = np.random.default_rng(int(seed))
    edges = np.geomspace(lo, hi, n + 1)
    a, b = edges[:-1], edges[1:]
    x, wq = np.polynomial.legendre.leggauss(16)
    points = 0.5 * (b - a)[:, None] * x[None, :] + 0.5 * (b + a)[:, None]
    values = np.asarray(function(points, mean_speed, **options), dtype=float)
    energy = (0.5 * (b - a)[:, None] * wq[None, :] * values).sum(axis=1)
    omega = a + (b - a) * rng.uniform(size=n)
    phase = rng.uniform(0.0, _TWO_PI, size=n)
    return WindGust(omega, np.sqrt(2.0 * np.maximum(energy, 0.0)), phase, label, int(seed))


@dataclass(frozen=True)
class Wind:
    """Wind: mean speed at 10 m, direction it comes from, optional gust (Smogeli et al. (2004)
    §4.2).

    U_w(t) = Ū_w + U_g(t).

    Parameters
    ----------
    speed
        Ū_w, the mean wind speed at 10 m, m/s, ≥ 0.
    direction
        β_w, rad: the direction the wind comes **from**, clockwise from North
        (meteorological convention: 0 is a northerly wind, blowing towards South).
    gust
        The gust U_g(t) (None: a steady wind).

    Examples
    --------
    >>> import numpy as np
    >>> np.round(Wind(10.0, 0.0).velocity_body(0.0, 0.0), 12)  # head wind, ship heading N
    array([-10.,  -0.])
    """

    speed: float
    direction: float = 0.0
    gust: WindGust | None = None

    def __post_init__(self) -> None:
        _positive(self.speed, "wind speed (m/s)", allow_zero=True)
        if not np.isfinite(self.direction):
            raise CumminsError(f"wind direction must be finite, got {self.direction!r} rad")

    def speed_at(self, t: float) -> float:
        """U_w(t) = Ū_w + U_g(t), m/s."""
        return self.speed + (self.gust(t) if self.gust is not None else 0.0)

    def velocity_body(self, t: float, psi: float) -> NDArray[np.float64]:
        """The air velocity (x, y) in the b-frame at heading ψ (rad), m/s, shape (2,).

        −U_w(t) [cos(β_w − ψ), sin(β_w − ψ)]: the air moves away from β_w.
        """
        a = self.direction - float(psi)
        return -self.speed_at(t) * np.array([np.cos(a), np.sin(a)])


def _mirror_table(angles: NDArray, values: NDArray, signs: NDArray) -> tuple[NDArray, NDArray]:
    """Complete a table given on [0, π] by C(−γ) = signs · C(γ)."""
    a = _wrap_2pi(angles)
    inner = (a > 1e-9) & (a < np.pi - 1e-9)
    return (
        np.concatenate([a, _TWO_PI - a[inner]]),
        np.concatenate([values, values[inner] * signs], axis=0),
    )


@dataclass(frozen=True, eq=False)
class WindCoefficients:
    """Tabulated wind coefficients C_X, C_Y, C_N against the relative wind angle γ.

    γ is the angle the relative wind comes **from**, rad, from the bow towards
    starboard (0: head wind; π/2: wind from starboard; Smogeli et al. (2004) §5.5 γ_wr = β_w − ψ
    for a vessel at rest). Coefficients in the b-frame (x forward, y starboard, z
    down): a head wind has C_X < 0, a wind from starboard C_Y < 0. Fossen's *Handbook*
    (2021, §10.1) writes γ_rw = −atan2(v_rw, u_rw) = −γ; a table in that angle becomes
    ``WindCoefficients(-angles, cx, cy, cn)``.

    Interpolated linearly and periodically. A table covering only [0, π] (data for one
    side, as Blendermann's and Isherwood's) is completed by port/starboard symmetry,
    C_X(−γ) = C_X(γ), C_Y(−γ) = −C_Y(γ), C_N(−γ) = −C_N(γ), unless ``symmetric=False``.

    Parameters
    ----------
    angles
        γ, rad, shape (m,), distinct modulo 2π.
    cx, cy, cn
        Dimensionless coefficients, shape (m,): f_1 = q C_X A_F, f_2 = q C_Y A_L,
        f_6 = q C_N A_L L_oa, q = ½ ρ_a V_rw².
    symmetric
        Complete a [0, π] table by symmetry (default True).
    """

    angles: NDArray[np.float64]
    cx: NDArray[np.float64]
    cy: NDArray[np.float64]
    cn: NDArray[np.float64]
    symmetric: bool = True
    _table: _PeriodicTable = field(init=False, repr=False)

    def __post_init__(self) -> None:
        angles = np.array(self.angles, dtype=float).reshape(-1)
        values = np.stack(
            [np.asarray(getattr(self, c), dtype=float).reshape(-1) for c in ("cx", "cy", "cn")],
            axis=1,
        )
        if values.shape[0] != angles.size:
            raise CumminsError(
                f"wind coefficient table: {angles.size} angles but {values.shape[0]} rows "
                "of cx, cy, cn"
            )
        if not (np.all(np.isfinite(angles)) and np.all(np.isfinite(values))):
            raise CumminsError("wind coefficient table has non-finite values")
        for name, value in (("angles", angles), *zip(("cx", "cy", "cn"), values.T, strict=True)):
            object.__setattr__(self, name, _frozen_array(value))
        a = _wrap_2pi(angles)
        if self.symmetric and np.all(a <= np.pi + 1e-9):
            a, values = _mirror_table(a, values, np.array([1.0, -1.0, -1.0]))
        object.__setattr__(self, "_table", _PeriodicTable(a, values[:, None, :]))

    def __call__(self, gamma: float) -> NDArray[np.float64]:
        """(C_X, C_Y, C_N) at the relative wind angle γ (rad)."""
        return self._table(np.array([float(gamma)]))[0]


@dataclass(frozen=True)
class ParametricWindCoefficients:
    """C_X = −c_x cos γ, C_Y = −c_y sin γ, C_N = −c_n sin 2γ (Fossen, *Handbook*, 2021 §10.1).

    γ as in :class:`WindCoefficients` (comes from, bow towards starboard; Fossen's
    γ_rw = −γ, with which his C_X = −c_x cos γ_rw, C_Y = c_y sin γ_rw, C_N = c_n sin 2γ_rw
    are these). Head wind: drag aft; wind from starboard: force to port; wind on the
    starboard bow (γ = 45°): bow pushed to port (C_N < 0). Fossen's ranges for ships:
    c_x 0.50–0.90, c_y 0.70–0.95, c_n 0.05–0.20; the defaults are mid-range.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(ParametricWindCoefficients()(np.pi / 2), 12)   # wind from starboard
    array([-0. , -0.8, -0. ])
    """

    c_x: float = 0.7
    c_y: float = 0.8
    c_n: float = 0.1

    def __call__(self, gamma: float) -> NDArray[np.float64]:
        """(C_X, C_Y, C_N) at the relative wind angle γ (rad)."""
        g = float(gamma)
        return np.array([-self.c_x * np.cos(g), -self.c_y * np.sin(g), -self.c_n * np.sin(2 * g)])

    def table(self, angles: ArrayLike) -> WindCoefficients:
        """The coefficients tabulated at ``angles`` (rad)."""
        a = np.asarray(angles, dtype=float).reshape(-1)
        c = np.array([self(g) for g in a])
        return WindCoefficients(a, c[:, 0], c[:, 1], c[:, 2], symmetric=False)


@dataclass(frozen=True)
class WindLoad:
    """Wind force and moment (Smogeli et al. (2004) eq. 55).

    f_i = ½ ρ_a C_wi(γ_rw) A_wi V_rw², i ∈ {1, 2, 6}, A_w1 = A_F (frontal), A_w2 = A_L
    (lateral), A_w6 = A_L L_oa,

    with the relative wind V_rw = v_air^b − (u, v): the air velocity of :class:`Wind` in
    the b-frame (rotated by the heading ψ only) minus the vessel's horizontal velocity,
    V_rw its magnitude and γ_rw = atan2(−V_y, −V_x) the angle it comes from, bow towards
    starboard (= β_w − ψ for a vessel at rest). The wind speed is the one at 10 m
    (:class:`Wind`), the usual reference height of wind coefficients; give the speed at
    the coefficients' own reference height if it differs. The forces act at ``point`` (b-frame,
    e.g. the centre of the lateral wind area, above O: z < 0):
    τ = Hᵀ(r_wind) [f_1, f_2, 0, 0, 0, f_6] (eq. 45), which adds the heeling moment.

    Parameters
    ----------
    wind
        The wind (mean speed at 10 m, direction it comes from, gust).
    frontal_area, lateral_area
        A_F and A_L, projected areas above the waterline, m².
    length_overall
        L_oa, m.
    coefficients
        :class:`ParametricWindCoefficients` (default) or a :class:`WindCoefficients` table
        (any callable γ ↦ (C_X, C_Y, C_N)).
    point
        r_wind, m, b-frame.
    density
        ρ_a, kg/m³ (1.225).
    name
        Name of the load.
    """

    wind: Wind
    frontal_area: float
    lateral_area: float
    length_overall: float
    coefficients: Callable[[float], NDArray[np.float64]] = field(
        default_factory=ParametricWindCoefficients
    )
    point: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    density: float = RHO_AIR
    name: str = "wind"

    def __post_init__(self) -> None:
        _positive(self.frontal_area, "frontal wind area (m²)", allow_zero=True)
        _positive(self.lateral_area, "lateral wind area (m²)", allow_zero=True)
        _positive(self.length_overall, "length overall (m)")
        _positive(self.density, "air density (kg/m³)")
        object.__setattr__(self, "point", _vector(self.point, 3, "wind point of attack (m)"))

    def relative_wind(
        self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]
    ) -> tuple[float, float]:
        """(V_rw in m/s, γ_rw in rad) at time t, pose η and velocity ν."""
        eta = np.asarray(eta, dtype=float)
        nu = np.asarray(nu, dtype=float)
        rel = self.wind.velocity_body(t, eta[5]) - nu[:2]
        return float(np.hypot(rel[0], rel[1])), float(np.arctan2(-rel[1], -rel[0]))

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ_wind, shape (6,), N and N·m (eq. 55)."""
        speed, gamma = self.relative_wind(t, eta, nu)
        q = 0.5 * self.density * speed**2
        c = np.asarray(self.coefficients(gamma), dtype=float)
        f1 = q * c[0] * self.frontal_area
        f2 = q * c[1] * self.lateral_area
        f6 = q * c[2] * self.lateral_area * self.length_overall
        return point_load([f1, f2, 0.0], self.point, [0.0, 0.0, f6])


# --------------------------------------------------------------------------- external loads


@dataclass(frozen=True)
class PointLoad:
    """A force (and moment) acting at a point of the vessel (Smogeli et al. (2004) eq. 45).

    τ = Hᵀ(r) [F^b, M^b] · s(t): F (N) and M (N·m) are given in the b-frame
    (``frame="body"``, they turn with the vessel: a thrust, a towline fixed on deck) or
    in the n-frame (``frame="ned"``: a suspended crane load whose weight acts along
    NED down, rotated into the b-frame by R_b^n(Θ)ᵀ before the transform). The time
    factor s(t) is 0 before ``start``, rises linearly to 1 over ``ramp`` seconds, and
    is 0 again from ``stop`` on.

    Parameters
    ----------
    force
        F, N, shape (3,).
    point
        r, m, b-frame, from O.
    moment
        M, N·m, shape (3,), same frame as the force (None: no moment).
    frame
        ``"body"`` or ``"ned"``.
    start, ramp, stop
        s; ``stop`` None: never stops.
    name
        Name of the load.

    Examples
    --------
    1000 kN hanging 15 m to starboard heels the vessel to starboard (positive roll):

    >>> import numpy as np
    >>> crane = PointLoad([0.0, 0.0, 1e6], [0.0, 15.0, 0.0], frame="ned")
    >>> crane.force(0.0, np.zeros(6), np.zeros(6))[[2, 3]]
    array([ 1000000., 15000000.])
    """

    force_vector: NDArray[np.float64]
    point: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    moment: NDArray[np.float64] | None = None
    frame: str = "body"
    start: float = 0.0
    ramp: float = 0.0
    stop: float | None = None
    name: str = "point load"

    def __post_init__(self) -> None:
        object.__setattr__(self, "force_vector", _vector(self.force_vector, 3, "force (N)"))
        object.__setattr__(self, "point", _vector(self.point, 3, "point of attack (m)"))
        if self.moment is not None:
            object.__setattr__(self, "moment", _vector(self.moment, 3, "moment (N·m)"))
        if self.frame not in ("body", "ned"):
            raise CumminsError(f"frame must be 'body' or 'ned', got {self.frame!r}")
        if not np.isfinite(self.start):
            raise CumminsError(f"start must be finite, got {self.start!r} s")
        _positive(self.ramp, "ramp (s)", allow_zero=True)
        if self.stop is not None and not self.stop > self.start:
            raise CumminsError(f"stop ({self.stop} s) must come after start ({self.start} s)")

    def factor(self, t: float) -> float:
        """s(t): 0 before start, linear ramp to 1, 0 from stop on."""
        t = float(t)
        if t < self.start or (self.stop is not None and t >= self.stop):
            return 0.0
        if self.ramp > 0.0 and t < self.start + self.ramp:
            return (t - self.start) / self.ramp
        return 1.0

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """τ, shape (6,), N and N·m, b-frame about O (eq. 45)."""
        s = self.factor(t)
        if s == 0.0:
            return np.zeros(6)
        f, m = self.force_vector, self.moment
        if self.frame == "ned":
            r_t = rotation_matrix(np.asarray(eta, dtype=float)[3:6]).T
            f = r_t @ f
            m = None if m is None else r_t @ m
        return s * point_load(f, self.point, m)


@dataclass(frozen=True)
class ConstantLoad:
    """A constant generalized force (6,), N and N·m, b-frame about O.

    Examples
    --------
    >>> float(ConstantLoad("bollard", [1e5, 0, 0, 0, 0, 0]).force(0.0, None, None)[0])
    100000.0
    """

    name: str
    value: NDArray[np.float64]

    def __post_init__(self) -> None:
        object.__setattr__(self, "value", _vector(self.value, 6, f"load {self.name!r}"))

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """The constant value (a copy)."""
        return np.array(self.value)


@dataclass(frozen=True)
class FunctionLoad:
    """Any function f(t, η, ν) → (6,) as a load (moorings, risers, a thruster model).

    Examples
    --------
    A linear spring of 1e5 N/m holding the vessel at the origin in surge:

    >>> import numpy as np
    >>> spring = FunctionLoad("mooring", lambda t, eta, nu: np.r_[-1e5 * eta[0], np.zeros(5)])
    >>> float(spring.force(0.0, np.r_[2.0, np.zeros(5)], np.zeros(6))[0])
    -200000.0
    """

    name: str
    function: Callable[[float, NDArray[np.float64], NDArray[np.float64]], ArrayLike]

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise CumminsError(f"load {self.name!r}: function must be callable")

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """f(t, η, ν) as a float array (6,)."""
        out = np.asarray(self.function(t, eta, nu), dtype=float).reshape(-1)
        if out.size != 6:
            raise CumminsError(
                f"load {self.name!r} returned {out.size} components; a generalized force has 6"
            )
        return out


# --------------------------------------------------------------------------- sums


def load_forces(
    loads: Iterable[Load], t: float, eta: ArrayLike, nu: ArrayLike
) -> dict[str, NDArray[np.float64]]:
    """Each load's generalized force (6,), N and N·m, by name (names must be unique)."""
    eta = np.asarray(eta, dtype=float).reshape(6)
    nu = np.asarray(nu, dtype=float).reshape(6)
    out: dict[str, NDArray[np.float64]] = {}
    for load in loads:
        if load.name in out:
            raise CumminsError(
                f"two loads are named {load.name!r}", hint="give each load a distinct name"
            )
        out[load.name] = np.asarray(load.force(t, eta, nu), dtype=float).reshape(6)
    return out


def total_force(
    loads: Iterable[Load] | Mapping[str, Load], t: float, eta: ArrayLike, nu: ArrayLike
) -> NDArray[np.float64]:
    """Σ of the loads' generalized forces, shape (6,), N and N·m, b-frame about O.

    Examples
    --------
    >>> import numpy as np
    >>> loads = [ConstantLoad("a", [1, 0, 0, 0, 0, 0]), ConstantLoad("b", [2, 0, 0, 0, 0, 1])]
    >>> total_force(loads, 0.0, np.zeros(6), np.zeros(6))
    array([3., 0., 0., 0., 0., 1.])
    """
    eta = np.asarray(eta, dtype=float).reshape(6)
    nu = np.asarray(nu, dtype=float).reshape(6)
    items = loads.values() if isinstance(loads, Mapping) else loads
    total = np.zeros(6)
    for load in items:
        total += np.asarray(load.force(t, eta, nu), dtype=float).reshape(6)
    return total
