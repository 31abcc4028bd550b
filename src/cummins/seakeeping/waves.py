"""Sea states: directional spreading, wave components, the dispersion relation.

A linear (Airy) sea is a sum of harmonic components (Smogeli et al. (2004) §4.1, de Haan (2022)
§1.9)

    ζ(x, y, t) = Σ_k a_k cos(ω_k t − k_k (x cos β_k + y sin β_k) + φ_k),

with amplitude a_k (m), frequency ω_k (rad/s), wave number k_k from the dispersion
relation ω² = g k tanh(k h), direction of travel β_k (rad, from +x towards +y: 0 =
waves travelling along +x, as the ``wave_direction`` of a ``HydroDB``) and phase φ_k.
In the convention of cummins, x(t) = Re{X e^{iωt}}, the component is Re{a_k e^{iφ_k}
e^{−i k_k (x cos β_k + y sin β_k)} e^{iω_k t}}: its complex amplitude at the origin is
a_k e^{iφ_k}, the phase reference of the excitation forces of a ``HydroDB``.

The sea-state spectra S(ω) (:func:`jonswap`, :func:`pierson_moskowitz`,
:func:`torsethaugen`, :func:`wave_spectrum`, :func:`energy_range`) live in
:mod:`cummins.seakeeping.spectra` and are importable from here as well. This module holds
the directional spreading, :func:`cos2s_spreading`: Longuet-Higgins' D(θ) = C(s)
cos^{2s}((θ − θ̄)/2) on (−π, π], C(s) = Γ(s+1)/(2√π Γ(s+½)) so that ∫D dθ = 1; the
dispersion relation (:func:`wavenumber`); the summation of harmonic components
(:func:`harmonic_sum`); and the components themselves.

:func:`irregular_waves` realises a spectrum as :class:`WaveComponents`: n equal
frequency bins, one frequency drawn at random (uniformly) inside each bin, amplitude
a_k = √(2 ∫_bin S dω) (so Σ a_k²/2 is the spectrum's variance over the range exactly),
random phases. Equally spaced frequencies would make the realisation periodic with period
2π/Δω (200 components over 1.5 rad/s repeat every 840 s); with a random frequency in
each bin the time-averaged autocorrelation Σ (a_k²/2) cos(ω_k τ) has no such peak
(:meth:`WaveComponents.autocorrelation`), whatever the duration.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins.errors import ArgumentError
from cummins.seakeeping.spectra import (
    SPECTRA,
    G,
    Spectrum,
    _describe_spectrum,
    energy_range,
    jonswap,
    pierson_moskowitz,
    range_within_data,
    torsethaugen,
    torsethaugen_parameters,
    wave_spectrum,
)
from cummins.validation import check_memory, count, non_negative, number, positive

__all__ = [
    "SPECTRA",
    "WaveComponents",
    "cos2s_spreading",
    "energy_range",
    "harmonic_sum",
    "irregular_waves",
    "jonswap",
    "pierson_moskowitz",
    "regular_wave",
    "spreading_directions",
    "spreading_weights",
    "torsethaugen",
    "torsethaugen_parameters",
    "wave_spectrum",
    "wavenumber",
]


# --------------------------------------------------------------------------- spreading


def _wrap(angle: ArrayLike) -> NDArray[np.float64]:
    """Angles wrapped into (−π, π]."""
    a = np.mod(np.asarray(angle, dtype=float) + np.pi, 2.0 * np.pi) - np.pi
    return np.where(a == -np.pi, np.pi, a)


def cos2s_spreading(theta: ArrayLike, mean_direction: float, s: float) -> NDArray[np.float64]:
    """Longuet-Higgins cos-2s directional spreading D(θ), 1/rad.

    D(θ) = C(s) cos^{2s}((θ − θ̄)/2), C(s) = Γ(s + 1)/(2√π Γ(s + ½)), so that
    ∫_{−π}^{π} D dθ = 1 for any s ≥ 0 (s = 0: uniform 1/2π; s ≈ 15–75: swell, 1–10: wind
    sea). θ − θ̄ is wrapped into (−π, π], so any θ, θ̄ (rad) may be given.

    Examples
    --------
    >>> import numpy as np
    >>> th = np.linspace(-np.pi, np.pi, 20001)
    >>> round(float(np.trapezoid(cos2s_spreading(th, 0.3, 10.0), th)), 6)
    1.0
    """
    s = float(s)
    if not (np.isfinite(s) and s >= 0):
        raise ArgumentError(f"the spreading exponent s must be finite and >= 0, got {s!r}")
    delta = _wrap(np.asarray(theta, dtype=float) - float(mean_direction))
    from scipy.special import gammaln  # on use: SciPy's import is 0.1 s

    c = np.exp(gammaln(s + 1.0) - gammaln(s + 0.5)) / (2.0 * np.sqrt(np.pi))
    base = np.clip(np.cos(delta / 2.0), 0.0, None)
    with np.errstate(under="ignore"):
        return c * base ** (2.0 * s)


def spreading_directions(
    mean_direction: float, s: float, n_directions: int, *, fraction: float = 1e-3
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Directions and energy weights discretising a cos-2s spreading.

    ``n_directions`` equal-width bins cover the central sector (θ̄ − Θ, θ̄ + Θ) holding all
    but ``fraction`` of the energy (the whole circle for small s); each bin is
    represented by its centre and weighted by ∫_bin D dθ, the weights normalised to sum
    to 1 (the left-out tails are shared out in proportion).

    Returns
    -------
    directions, weights
        Arrays of length ``n_directions``: rad (wrapped to (−π, π] about 0) and
        dimensionless weights summing to 1.
    """
    n = int(n_directions)
    if n < 1:
        raise ArgumentError(f"n_directions must be at least 1, got {n_directions!r}")
    if n == 1:
        return np.array([float(mean_direction)]), np.ones(1)
    grid = np.linspace(-np.pi, np.pi, 20001)
    d = cos2s_spreading(grid, 0.0, s)
    from scipy.integrate import cumulative_trapezoid  # on use

    cdf = cumulative_trapezoid(d, grid, initial=0.0)
    half = float(np.pi - np.interp(fraction / 2 * cdf[-1], cdf, grid + np.pi))
    half = min(max(half, 1e-6), np.pi)
    edges = np.linspace(-half, half, n + 1)
    centres = 0.5 * (edges[:-1] + edges[1:])
    # Bin integrals by 16-point Gauss-Legendre quadrature.
    x, wq = np.polynomial.legendre.leggauss(16)
    lo, hi = edges[:-1, None], edges[1:, None]
    pts = 0.5 * (hi - lo) * x[None, :] + 0.5 * (hi + lo)
    weights = (0.5 * (hi - lo) * wq[None, :] * cos2s_spreading(pts, 0.0, s)).sum(axis=1)
    weights = weights / weights.sum()
    return _wrap(centres + float(mean_direction)), weights


def spreading_weights(
    directions: ArrayLike, mean_direction: float, s: float
) -> NDArray[np.float64]:
    """Energy weights of given directions under a cos-2s spreading, summing to 1.

    Each direction stands for the arc between the midpoints to its neighbours on the
    circle (sorted, periodic); its weight is ∫_arc D dθ (:func:`cos2s_spreading`, 64-point
    Gauss–Legendre per arc), divided by the sum so that the weights add up to 1 even when
    the directions cover only part of the circle. For
    :func:`cummins.seakeeping.frequency_domain.response_spectrum` over the headings of a database.
    """
    beta = np.asarray(directions, dtype=float).reshape(-1)
    if beta.size == 0:
        raise ArgumentError("no directions given")
    if beta.size == 1:
        return np.ones(1)
    b = np.mod(beta, 2.0 * np.pi)
    order = np.argsort(b)
    sb = b[order]
    nxt = np.append(sb[1:], sb[0] + 2.0 * np.pi)
    prv = np.insert(sb[:-1], 0, sb[-1] - 2.0 * np.pi)
    lo, hi = 0.5 * (prv + sb), 0.5 * (sb + nxt)
    x, wq = np.polynomial.legendre.leggauss(64)
    pts = 0.5 * (hi - lo)[:, None] * x[None, :] + 0.5 * (hi + lo)[:, None]
    w = (0.5 * (hi - lo)[:, None] * wq[None, :] * cos2s_spreading(pts, mean_direction, s)).sum(1)
    out = np.empty_like(w)
    out[order] = w
    total = out.sum()
    if not total > 0:
        raise ArgumentError("the directions carry no energy of this spreading")
    return out / total


# --------------------------------------------------------------------------- dispersion


def wavenumber(omega: ArrayLike, depth: float = np.inf, g: float = G) -> NDArray[np.float64]:
    """Wave number k (rad/m) from the dispersion relation ω² = g k tanh(k h).

    Deep water (``depth`` infinite): k = ω²/g. Finite depth: Newton iterations from
    k = max(ω²/g, ω/√(gh)) (which converge from above, monotonically), to 1e-14
    relative. ω = 0 gives k = 0.

    Examples
    --------
    >>> round(float(wavenumber(1.0, depth=10.0)), 6)
    0.121582
    """
    omega = np.abs(np.asarray(omega, dtype=float))
    k = omega**2 / g
    depth = float(depth)
    if not np.isfinite(depth):
        return k
    if not depth > 0:
        raise ArgumentError(f"water depth must be positive, got {depth!r} m")
    k = np.maximum(k, omega / np.sqrt(g * depth))
    for _ in range(100):
        t = np.tanh(k * depth)
        f = g * k * t - omega**2
        df = g * t + g * k * depth * (1.0 - t**2)
        step = np.divide(f, df, out=np.zeros_like(k), where=df > 0)
        k = k - step
        if np.all(np.abs(step) <= 1e-14 * np.maximum(k, 1e-300)):
            break
    return k


# --------------------------------------------------------------------------- summation

#: Largest number of (time × component) terms evaluated at once by :func:`harmonic_sum`.
_CHUNK_TERMS = 2_000_000
#: Block length of the uniform-grid algorithm of :func:`harmonic_sum`.
_BLOCK = 1024


def harmonic_sum(t: ArrayLike, omega: ArrayLike, coefficients: ArrayLike) -> NDArray[np.float64]:
    """Re Σ_k c_k e^{iω_k t} at every time t, vectorised and chunked.

    Parameters
    ----------
    t
        Times, s, shape (nt,).
    omega
        Frequencies, rad/s, shape (n,).
    coefficients
        Complex amplitudes c_k, shape (n,) or (n, m).

    Returns
    -------
    numpy.ndarray
        Shape (nt,) or (nt, m).

    Notes
    -----
    On a uniform time grid t_j = t₀ + jΔt (the usual case) the times are taken in
    blocks of 1024: e^{iω(t_b + sΔt)} = e^{iωt_b} e^{iωsΔt}, where the second factor is
    the same for every block, so each block costs one real matrix product
    (1024 × 2n)·(2n × m) and no trigonometric function. Other grids evaluate
    cos and sin of ωt in chunks of about 2·10⁶ terms. No Python loop runs over single
    times: 200 components × 200 000 times × 6 DOFs take about 0.2 s.
    """
    t = np.asarray(t, dtype=float).reshape(-1)
    omega = np.asarray(omega, dtype=float).reshape(-1)
    c = np.asarray(coefficients, dtype=complex)
    squeeze = c.ndim == 1
    c = c.reshape(omega.size, -1)
    out = np.zeros((t.size, c.shape[1]))
    if t.size == 0 or omega.size == 0:
        return out[:, 0] if squeeze else out
    dt = (t[-1] - t[0]) / (t.size - 1) if t.size > 1 else 0.0
    uniform = (
        t.size > 2 * _BLOCK
        and dt > 0
        and np.max(np.abs(t - (t[0] + dt * np.arange(t.size)))) <= 1e-9 * dt
    )
    if uniform:
        s = dt * np.arange(_BLOCK)
        phase = np.outer(s, omega)
        basis = np.concatenate([np.cos(phase), -np.sin(phase)], axis=1)  # (B, 2n)
        for start in range(0, t.size, _BLOCK):
            stop = min(start + _BLOCK, t.size)
            cb = c * np.exp(1j * omega * (t[0] + start * dt))[:, None]
            out[start:stop] = basis[: stop - start] @ np.concatenate([cb.real, cb.imag])
    else:
        rows = max(1, _CHUNK_TERMS // omega.size)
        for start in range(0, t.size, rows):
            phase = np.outer(t[start : start + rows], omega)
            out[start : start + rows] = np.cos(phase) @ c.real - np.sin(phase) @ c.imag
    return out[:, 0] if squeeze else out


# --------------------------------------------------------------------------- components


def _readonly(value: ArrayLike, name: str) -> NDArray[np.float64]:
    arr = np.array(value, dtype=float).reshape(-1)
    if not np.all(np.isfinite(arr)):
        raise ArgumentError(f"WaveComponents.{name} has non-finite values")
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, eq=False)
class WaveComponents:
    """A sea state as a finite sum of harmonic wave components.

    ζ(x, y, t) = Σ_k a_k cos(ω_k t − k_k (x cos β_k + y sin β_k) + φ_k) (module docstring).

    Attributes
    ----------
    omega
        Frequencies ω_k, rad/s, shape (n,), > 0.
    amplitude
        Amplitudes a_k, m, ≥ 0.
    phase
        Phases φ_k, rad: the phase of component k at the origin (0, 0) at t = 0.
    direction
        Directions of travel β_k, rad, from +x towards +y (0: along +x, π: head seas
        for a ship heading along +x), as ``wave_direction`` in a ``HydroDB``.
    spectrum
        Name of the spectrum realised ("" when built by hand, "regular" for one wave).
    hs, tp
        Significant wave height (m) and peak period (s) asked for (NaN if none); for a
        regular wave its height 2a and period.
    seed
        Seed of the random generator (integer entropy) when the phases and
        frequencies were drawn at random; with it :func:`irregular_waves` gives the same
        components again.
    duration
        The duration (s) the realisation was made for, if any.
    bin_width
        Width Δω of the frequency bins (rad/s), if any.
    spreading
        The cos-2s exponent s of short-crested seas, if any.
    """

    omega: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    phase: NDArray[np.float64]
    direction: NDArray[np.float64]
    spectrum: str = ""
    hs: float = np.nan
    tp: float = np.nan
    seed: int | None = None
    duration: float | None = None
    bin_width: float | None = None
    spreading: float | None = None
    attrs: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for name in ("omega", "amplitude", "phase", "direction"):
            object.__setattr__(self, name, _readonly(getattr(self, name), name))
        n = self.omega.size
        for name in ("amplitude", "phase", "direction"):
            if getattr(self, name).size != n:
                raise ArgumentError(
                    f"WaveComponents.{name} has {getattr(self, name).size} values, omega has {n}"
                )
        if np.any(self.omega <= 0):
            raise ArgumentError("WaveComponents.omega must be positive (rad/s)")
        if np.any(self.amplitude < 0):
            raise ArgumentError("WaveComponents.amplitude must be >= 0 (m)")

    def __len__(self) -> int:
        return int(self.omega.size)

    @property
    def variance(self) -> float:
        """m₀ of the realisation, Σ a_k²/2, m²."""
        return float(np.sum(self.amplitude**2) / 2.0)

    @property
    def significant_wave_height(self) -> float:
        """4√m₀ of the realisation, m."""
        return float(4.0 * np.sqrt(self.variance))

    @property
    def complex_amplitude(self) -> NDArray[np.complex128]:
        """a_k e^{iφ_k}: the complex elevation amplitude of each component at the origin, m."""
        return self.amplitude * np.exp(1j * self.phase)

    def wavenumber(self, *, g: float = G, depth: float = np.inf) -> NDArray[np.float64]:
        """Wave numbers k_k, rad/m (:func:`wavenumber`)."""
        return wavenumber(self.omega, depth, g)

    def elevation(
        self,
        t: ArrayLike,
        x: float = 0.0,
        y: float = 0.0,
        *,
        g: float = G,
        depth: float = np.inf,
    ) -> NDArray[np.float64]:
        """Free-surface elevation ζ(t) at the point (x, y), m.

        ζ(t) = Σ_k a_k cos(ω_k t − k_k (x cos β_k + y sin β_k) + φ_k), k_k from the
        dispersion relation with gravity ``g`` (m/s²) and water ``depth`` (m, ``inf``:
        deep water). ``t`` in s, any shape; the result has the shape of ``t``.
        """
        t_arr = np.asarray(t, dtype=float)
        k = self.wavenumber(g=g, depth=depth)
        shift = k * (float(x) * np.cos(self.direction) + float(y) * np.sin(self.direction))
        c = self.amplitude * np.exp(1j * (self.phase - shift))
        return harmonic_sum(t_arr.reshape(-1), self.omega, c).reshape(t_arr.shape)

    def autocorrelation(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Normalised time-averaged autocorrelation ρ(τ) = Σ a_k² cos(ω_k τ) / Σ a_k².

        It is the limit of the autocorrelation of ζ(t) at a fixed point over a long
        record, whatever the phases; a realisation that repeats with period T has
        ρ(T) = 1.
        """
        tau = np.asarray(tau, dtype=float)
        weights = self.amplitude**2
        total = weights.sum()
        if total == 0:
            return np.zeros(tau.shape)
        return harmonic_sum(tau.reshape(-1), self.omega, weights / total).reshape(tau.shape)


def regular_wave(
    amplitude: float, period: float, direction: float = 0.0, phase: float = 0.0
) -> WaveComponents:
    """One regular (monochromatic) wave: amplitude (m), period (s), direction and phase (rad).

    Examples
    --------
    >>> w = regular_wave(1.0, 10.0)
    >>> float(w.elevation(0.0)), len(w)
    (1.0, 1)
    """
    period = positive(period, "the wave period", "s")
    amplitude = non_negative(amplitude, "the wave amplitude", "m")
    direction = number(direction, "the wave direction", "rad")
    phase = number(phase, "the wave phase", "rad")
    return WaveComponents(
        omega=[2.0 * np.pi / period],
        amplitude=[amplitude],
        phase=[phase],
        direction=[direction],
        spectrum="regular",
        hs=2.0 * float(amplitude),
        tp=float(period),
    )


def _generator(seed: Any) -> tuple[np.random.Generator, int | None]:
    """A numpy Generator and the integer seed that reproduces it (None for a Generator)."""
    if isinstance(seed, np.random.Generator):
        return seed, None
    if seed is None:
        # a fresh seed that fits an int64, so that a run file can record it (HDF5 has no
        # 128-bit integers) and ``seed=`` / ``--seed`` can make the same sea again
        drawn = int(np.random.SeedSequence().generate_state(2, np.uint32).view(np.uint64)[0])
        drawn &= 2**63 - 1
        return np.random.default_rng(drawn), drawn
    if isinstance(seed, np.random.SeedSequence):
        return np.random.default_rng(seed), (
            int(seed.entropy) if isinstance(seed.entropy, int) else None
        )
    return np.random.default_rng(int(seed)), int(seed)


def irregular_waves(
    spectrum: Spectrum,
    *,
    duration: float,
    n_components: int = 200,
    omega_min: float | None = None,
    omega_max: float | None = None,
    direction: float = 0.0,
    spreading: float | None = None,
    n_directions: int = 1,
    seed: int | np.random.Generator | None = None,
    data=None,
) -> WaveComponents:
    """Realise a wave spectrum as random-phase harmonic components.

    Frequencies: ``n_components`` equal bins of width Δω on [ω_min, ω_max], one
    frequency drawn uniformly inside each bin; amplitude a = √(2 ∫_bin S dω) (16-point
    Gauss–Legendre per bin), so Σ a²/2 equals the spectrum's energy on the range; phases
    uniform on [0, 2π). Because the frequencies are not commensurate, the realisation
    does not repeat after 2π/Δω as an equally spaced one would: its autocorrelation
    (:meth:`WaveComponents.autocorrelation`) stays small at every lag from a few peak
    periods to well beyond ``duration``.

    The statistical quality of a realisation is set by its effective number of
    components n_eff = (Σa²)²/Σa⁴ (``attrs["effective_components"]``): a JONSWAP
    (γ = 3.3) realised with 200 components over its 99.9 % range has n_eff ≈ 23, and
    its autocorrelation keeps random excursions of order 1/√n_eff (up to ~0.5 over an
    hour of lags) where the spectrum's own has decayed. Raise ``n_components`` or narrow
    the range for long records.

    Short-crested seas (``spreading=s``): each frequency bin is realised in
    ``n_directions`` directions (:func:`spreading_directions`), each pair with its own
    random frequency in the bin and amplitude √(2 w_j ∫_bin S dω): n_components ×
    n_directions components, frequency-major.

    Parameters
    ----------
    spectrum
        S(ω), m²·s/rad, vectorised, e.g. ``functools.partial(jonswap, hs=4, tp=10)`` or
        :func:`wave_spectrum`.
    duration
        Length of the simulation the waves are made for, s (recorded; must be > 0).
    n_components
        Number of frequency bins.
    omega_min, omega_max
        Frequency range, rad/s. Default: :func:`energy_range` (all but 0.1 % of the
        energy, 0.05 % left out at each end), within the frequencies of ``data``.
    direction
        Mean direction of travel, rad (0: along +x; π: head seas).
    spreading
        cos-2s exponent s (None: long-crested, one direction).
    n_directions
        Number of directions with ``spreading``.
    seed
        Integer seed or numpy ``Generator``; None draws a fresh seed (0 to 2⁶³ − 1, so
        that it fits an int64 in a run file), recorded in ``WaveComponents.seed`` so that
        the sea can be made again. The frequencies
        are drawn first, then the phases.
    data
        The ``HydroDB`` the waves will drive (or its frequencies, rad/s): the default
        range is limited to its frequencies, whose excitation is not extrapolated, with
        a :class:`~cummins.errors.CumminsWarning` when that cuts the spectrum
        (:func:`~cummins.seakeeping.spectra.range_within_data`; ``cummins simulate`` does
        the same).

    Returns
    -------
    WaveComponents

    Examples
    --------
    >>> waves = irregular_waves(wave_spectrum("jonswap", 4.0, 10.0), duration=3600, seed=1)
    >>> len(waves), round(float(waves.significant_wave_height), 2)
    (200, 4.0)
    """
    duration = positive(duration, "duration", "s")
    n = count(n_components, "n_components")
    direction = number(direction, "the mean wave direction", "rad")
    n_dirs = 1 if spreading is None else int(n_directions)
    # 16 quadrature nodes (and their S values) per bin, five arrays per component
    check_memory(
        n * (16 * 3 * 8 + n_dirs * 6 * 8),
        f"a sea of {n:g} components x {n_dirs} directions",
        hint="Ask for fewer components (--components) or directions (--directions)",
    )
    if omega_min is None or omega_max is None:
        if data is None:
            lo, hi = energy_range(spectrum)
        else:
            omega = data.omega.values if hasattr(data, "omega") else data
            lo, hi = range_within_data(spectrum, omega)
        omega_min = lo if omega_min is None else omega_min
        omega_max = hi if omega_max is None else omega_max
    lo, hi = float(omega_min), float(omega_max)
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 <= lo < hi):
        raise ArgumentError(f"need 0 <= omega_min < omega_max, got {lo!r} and {hi!r} rad/s")
    if spreading is None:
        if n_directions != 1:
            raise ArgumentError("n_directions > 1 needs a spreading exponent (spreading=s)")
        directions, dir_weights = np.array([float(direction)]), np.ones(1)
    else:
        if n_directions < 2:
            raise ArgumentError("short-crested seas (spreading=s) need n_directions >= 2")
        directions, dir_weights = spreading_directions(direction, spreading, n_directions)
    m = directions.size

    edges = np.linspace(lo, hi, n + 1)
    width = (hi - lo) / n
    x, wq = np.polynomial.legendre.leggauss(16)
    nodes = edges[:-1, None] + 0.5 * width * (x[None, :] + 1.0)
    s_nodes = np.asarray(spectrum(nodes.reshape(-1)), dtype=float).reshape(nodes.shape)
    if not np.all(np.isfinite(s_nodes)) or np.any(s_nodes < 0):
        raise ArgumentError("the spectrum must return finite, non-negative values of S(omega)")
    energy = 0.5 * width * (s_nodes * wq[None, :]).sum(axis=1)  # ∫_bin S dω, (n,)

    rng, seed_used = _generator(seed)
    u = 1.0 - rng.random((n, m))  # (0, 1]
    omega = edges[:-1, None] + width * u
    omega = np.maximum(omega, np.finfo(float).tiny)
    phase = rng.uniform(0.0, 2.0 * np.pi, size=(n, m))
    amplitude = np.sqrt(2.0 * energy[:, None] * dir_weights[None, :])
    name, hs, tp = _describe_spectrum(spectrum)
    return WaveComponents(
        omega=omega.reshape(-1),
        amplitude=amplitude.reshape(-1),
        phase=phase.reshape(-1),
        direction=np.broadcast_to(directions[None, :], (n, m)).reshape(-1),
        spectrum=name,
        hs=hs,
        tp=tp,
        seed=seed_used,
        duration=duration,
        bin_width=width,
        spreading=None if spreading is None else float(spreading),
        attrs={
            "spectrum_parameters": dict(getattr(spectrum, "keywords", None) or {}),
            "effective_components": float(
                np.sum(amplitude**2) ** 2 / max(np.sum(amplitude**4), np.finfo(float).tiny)
            ),
            "omega_min": lo,
            "omega_max": hi,
            "n_components": n,
            "n_directions": m,
            "mean_direction": float(direction),
        },
    )
