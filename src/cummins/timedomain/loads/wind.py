"""Wind: gust spectra and their realisation, the wind, wind coefficients and the wind load.

* gust spectra :func:`harris` (Harris, 1971) and :func:`norsok` (NORSOK N-003, 1999) with
  their variances, realised as a sum of harmonics by :func:`wind_gust`
  (:class:`WindGust`; Smogeli et al. (2004) §4.2);
* :class:`Wind`: mean speed, direction it comes from and gust;
* wind coefficients against the relative wind angle: tabulated
  (:class:`WindCoefficients`) or Fossen's parametric form
  (:class:`ParametricWindCoefficients`);
* :class:`WindLoad`: the wind force and moment (Smogeli et al. (2004) eq. 55).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import beta as beta_function
from scipy.special import gamma as gamma_function

from cummins.errors import CumminsError
from cummins.kinematics import point_load
from cummins.seakeeping.waves import harmonic_sum
from cummins.timedomain.loads.base import (
    _TWO_PI,
    _frozen_array,
    _PeriodicTable,
    _positive,
    _vector,
    _wrap_2pi,
)

#: Density of air at 15 °C and 1013.25 hPa (ISO standard atmosphere), kg/m³.
RHO_AIR = 1.225


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
        ``"harris"``, ``"norsok"`` or a function ``S(ω, mean_speed, **options)``.
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
