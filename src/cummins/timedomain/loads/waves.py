"""Wave loads: first-order wave excitation and mean and slowly varying wave drift.

* :class:`FirstOrderWaveLoad`: the first-order wave excitation at the instantaneous
  relative heading and position of the vessel (Smogeli et al. (2004) eq. 46), from a table
  of the excitation transfer function over relative headings;
* :class:`WaveDriftLoad`: the mean and slowly varying drift by Newman's approximation
  (Smogeli et al. (2004) eqs. 47–48), from the mean drift coefficients of the data.

Both are built from a ``HydroDB`` (``from_hydrodb``) and a sea state
(:class:`cummins.seakeeping.waves.WaveComponents`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError, HydroDataError, HydroDataWarning
from cummins.hydrodb import bodies, change_axes, dof_index, single_speed, water_depth
from cummins.kinematics import point_load
from cummins.qtf.suspect_drift import suspects_left_out
from cummins.seakeeping.excitation import MIRROR_SIGNS, excitation_transfer, heading_coverage
from cummins.seakeeping.waves import WaveComponents, wavenumber
from cummins.timedomain.loads.base import (
    _TWO_PI,
    _frozen_array,
    _PeriodicTable,
    _positive,
    _vector,
)


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


def warn_drift_mirror(ds: xr.Dataset, stacklevel: int = 3) -> None:
    """A :class:`~cummins.errors.HydroDataWarning` when the mean drift breaks the port/
    starboard mirror where the first-order tables keep it
    (:func:`cummins.check.waves.drift_mirror_note`: MSS's own structs at 190–350°)."""
    import warnings

    from cummins.check.waves import drift_mirror_note

    note = drift_mirror_note(ds)
    if note:
        source = ds.attrs.get("source_file") or "the data"
        warnings.warn(HydroDataWarning(f"{source}: {note}"), stacklevel=stacklevel)


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
            waves.omega,
            water_depth(ds, "the wave numbers of the wave loads"),
            float(ds.attrs.get("g", 9.81)),
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
        keep_suspect: bool = False,
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
        keep_suspect
            Keep the drift at the suspect frequencies of the radiation data (irregular
            frequencies: :func:`cummins.qtf.suspect_drift.suspects_left_out`, said in a
            warning); by default they are left out, bridged linearly between their sound
            neighbours, as by the second-order loads of ``cummins simulate``.

        Raises
        ------
        HydroDataError
            No ``drift_force`` in the dataset, a frequency out of range, a heading gap.
        """
        ds, index = _prepare_hydrodb(ds, "drift_force")
        where = ds.attrs.get("source_file")
        if "wave_direction" not in ds["drift_force"].dims:
            raise HydroDataError("drift_force has no wave_direction dimension", path=where)
        warn_drift_mirror(ds)
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
        left_out = suspects_left_out(ds, keep_suspect, [], stacklevel=3)
        if left_out:  # the data's range still decides what is outside it
            _frequency_weights(w, waves.omega, extrapolate, where)
            sound = ~np.isin(w, left_out)
            w, data = w[sound], data[sound]
            if extrapolate == "raise":  # above the last sound frequency: no drift
                extrapolate = "zero"
        i, weight, inside = _frequency_weights(w, waves.omega, extrapolate, where)
        hi = np.minimum(i + 1, w.size - 1)
        at = (1.0 - weight)[:, None, None] * data[i] + weight[:, None, None] * data[hi]
        if extrapolate == "zero":
            at[~inside] = 0.0
        table = _in_six(np.transpose(at, (1, 0, 2)), index)  # (m, n, 6)
        k = wavenumber(
            waves.omega,
            water_depth(ds, "the wave numbers of the wave loads"),
            float(ds.attrs.get("g", 9.81)),
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
