"""Encounter frequency: the frequency at which a ship at forward speed meets the waves.

Encounter frequency (:func:`encounter_frequency`): heading β is the direction in which
the waves travel, relative to the ship's x axis (cummins' ``wave_direction``): β = 0
following seas, β = π (180°) head seas. A wave ζ = a cos(ωt − k(x cos β + y sin β)) seen
from x = U t has ω_e = ω − k U cos β = ω − ω² U cos β / g (deep water, k = ω²/g).
The mapping of a wave spectrum to encounter frequency, its inverse and the
``encounter_frequency`` coordinate of a dataset are here too (Hjulstad (2004) ch. 3).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.radiation.speed.errors import SpeedError

G = 9.81


def encounter_frequency(
    omega: ArrayLike, speed: float, heading: float, g: float = G
) -> NDArray[np.float64]:
    """Encounter frequency ω_e = ω − ω² U cos β / g (deep water), rad/s.

    Parameters
    ----------
    omega
        Wave frequencies ω, rad/s.
    speed
        Forward speed U, m/s (along the ship's x axis).
    heading
        Direction β in which the waves *travel*, relative to x, rad: 0 following seas,
        π/2 beam seas (travelling to +y), π head seas (cummins' ``wave_direction``).
    g
        Acceleration of gravity, m/s².

    Returns
    -------
    numpy.ndarray
        ω_e, rad/s, signed: negative when the waves overtake the ship faster than their
        phase passes it (following seas, ω > g/(U cos β)).

    Notes
    -----
    Head seas (cos β < 0): ω_e > ω, monotonic. Following seas (cos β > 0): ω_e(ω) has
    a maximum ω_e = g/(4 U cos β) at ω = g/(2 U cos β), i.e. at τ = ω_e U cos β / g = 1/4
    (equivalently ω U cos β / g = 1/2); there dω_e/dω = 0, a response spectrum mapped
    to ω_e is singular, and each ω_e below the maximum comes from up to three wave
    frequencies (:func:`wave_frequency`).

    Examples
    --------
    >>> import numpy as np
    >>> float(encounter_frequency(0.5, 10.0, np.pi, g=9.81).round(4))  # head seas
    0.7548
    >>> float(encounter_frequency(0.4905, 10.0, 0.0, g=9.81).round(5))  # tau = 1/4
    0.24525
    """
    w = np.asarray(omega, dtype=float)
    return w - w**2 * speed * np.cos(heading) / g


def wave_frequency(
    omega_e: float, speed: float, heading: float, g: float = G
) -> NDArray[np.float64]:
    """All wave frequencies ω ≥ 0 with encounter frequency ``omega_e`` (inverse mapping).

    Solves (U cos β / g) ω² − ω + ω_e = 0 (see :func:`encounter_frequency`).

    Returns
    -------
    numpy.ndarray
        Sorted ω ≥ 0, rad/s. Head and beam seas: one value. Following seas
        (cos β > 0): two for 0 < ω_e < g/(4 U cos β) (τ = ω_e U cos β / g < 1/4), the
        double root g/(2 U cos β) at τ = 1/4, none above it (empty array); one for
        ω_e ≤ 0 (waves overtaking the ship).

    Raises
    ------
    SpeedError
        For a negative ω_e where no wave frequency produces it.

    Examples
    --------
    >>> wave_frequency(0.2, 10.0, 0.0, g=9.81).round(4)
    array([0.2798, 0.7012])
    >>> wave_frequency(0.7548, 10.0, 3.141592653589793, g=9.81).round(3)
    array([0.5])
    """
    c = speed * np.cos(heading) / g
    if abs(c) < 1e-12:
        roots = np.array([omega_e], dtype=float)
    else:
        disc = 1.0 - 4.0 * c * omega_e
        if disc < 0:
            return np.empty(0)
        r = np.sqrt(disc)
        roots = np.unique(np.array([(1.0 - r) / (2.0 * c), (1.0 + r) / (2.0 * c)]))
    out = np.sort(roots[roots >= 0])
    if out.size == 0:
        raise SpeedError(
            f"no wave frequency has the encounter frequency {omega_e:g} rad/s at "
            f"U = {speed:g} m/s, heading {np.degrees(heading):g} deg"
        )
    return out


def encounter_spectrum(
    omega: ArrayLike,
    spectrum: ArrayLike,
    speed: float,
    heading: float,
    g: float = G,
    *,
    margin: float = 0.02,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Map a wave spectrum S(ω) to encounter frequency: S_e(ω_e) = S(ω) / |dω_e/dω|.

    Energy-preserving per frequency band (S_e dω_e = S dω), with
    dω_e/dω = 1 − 2 ω U cos β / g.

    Parameters
    ----------
    omega, spectrum
        Wave frequencies (rad/s) and spectral density (m²·s/rad, or any unit per rad/s).
    speed, heading, g
        As :func:`encounter_frequency`.
    margin
        Refuse frequencies with |dω_e/dω| < ``margin`` (the τ = 1/4 singularity).

    Returns
    -------
    (omega_e, spectrum_e)
        Encounter frequencies (rad/s, in the order of ``omega``: not monotonic in
        following seas) and the mapped density.

    Raises
    ------
    SpeedError
        When a frequency lies within ``margin`` of τ = 1/4, naming it.
    """
    w = np.asarray(omega, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    jac = 1.0 - 2.0 * w * speed * np.cos(heading) / g
    bad = np.abs(jac) < margin
    if np.any(bad):
        w_bad = float(w[np.argmax(bad)])
        raise SpeedError(
            f"the encounter-frequency mapping is singular near omega = {w_bad:g} rad/s "
            f"(tau = omega_e U cos(beta)/g = 1/4 at omega = {g / (2 * speed * np.cos(heading)):g}"
            f" rad/s for U = {speed:g} m/s, heading {np.degrees(heading):g} deg)",
            hint="integrate responses over wave frequency instead, or leave out that band",
        )
    return encounter_frequency(w, speed, heading, g), s / np.abs(jac)


def with_encounter_frequency(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with the coordinate ``encounter_frequency`` (forward_speed, omega,
    wave_direction), rad/s: the frequency at which the vessel meets each wave component
    of the data's wave-frequency tables (excitation, RAOs), ω_e = ω − ω²U cos β/g
    (:func:`encounter_frequency`); one speed: (omega, wave_direction)."""
    g = float(ds.attrs.get("g", G))
    w = ds.omega.values[:, None]
    beta = ds.wave_direction.values[None, :]
    if "forward_speed" in ds.dims:
        u = ds.forward_speed.values
        we = np.stack([encounter_frequency(w, float(uk), beta, g) for uk in u])
        dims = ("forward_speed", "omega", "wave_direction")
    else:
        u = float(ds.coords["forward_speed"]) if "forward_speed" in ds.coords else 0.0
        we = encounter_frequency(w, u, beta, g)
        dims = ("omega", "wave_direction")
    return ds.assign_coords(
        encounter_frequency=(
            dims,
            np.asarray(we),
            {"units": "rad/s", "long_name": "encounter frequency"},
        )
    )
