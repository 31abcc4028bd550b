"""What the AQWA ``.LIS`` and ``.AH1`` readers share: wave number, phases, LHFR rows, the
symmetry a matrix of AQWA's must keep.

Low and high frequency rows (LHFR option). The AH1 header says they are computed at
0.001 and 100 rad/s (the listing prints 0.0018 and 100 rad/s). At 100 rad/s the wave
length 2πg/ω² is 6 mm: shorter than any panel, so the value is the ω → ∞ limit for any
real structure, and cummins stores it as ``added_mass_inf`` (the cross-code test of the
WEC-Sim cylinder finds it within 2 % of WAMIT's ω = ∞ solution). The low-frequency row
is *not* used as A(0): in finite depth the heave added mass keeps changing as ω → 0
(AQWA's A33 at 0.0018 rad/s is 60 % above WAMIT's ω = 0 value for the cylinder), so it
is left out, and ``history`` says so.

Conventions. AQWA prints phase lags: x(t) = |X| cos(ωt − φ), i.e. X = |X| exp(−iφ) in
cummins' exp(+iωt) convention (the listing's velocity RAO phases are the RAO phases
minus 90°, as that requires). Phases are relative to the incident wave at the centre of
gravity (as WEC-Sim's reader assumes); cummins refers them to the global origin by
adding k (x_G cos β + y_G sin β) to φ, k from the dispersion relation
ω² = g k tanh(k h). Wave directions are directions of propagation, anticlockwise from
+x (0 = following seas), as cummins; AQWA often lists both −180° and 180°, kept as two
directions.
"""

from __future__ import annotations

import numpy as np

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"

#: Smallest frequency (rad/s) of an LHFR block taken as the ω → ∞ limit.
HIGH_FREQUENCY_LIMIT = 50.0


# --------------------------------------------------------------------------- shared pieces


def wavenumber(omega: np.ndarray, depth: float, g: float) -> np.ndarray:
    """Wave number k (rad/m) with ω² = g k tanh(k h) (deep water if ``depth`` is inf)."""
    omega = np.asarray(omega, dtype=float)
    k = omega**2 / g
    if not np.isfinite(depth):
        return k
    k = np.maximum(k, omega / np.sqrt(g * depth))  # shallow-water start: converges from above
    for _ in range(100):
        t = np.tanh(k * depth)
        f = g * k * t - omega**2
        df = g * t + g * k * depth * (1 - t**2)
        step = f / df
        k = k - step
        if np.all(np.abs(step) <= 1e-12 * k):
            break
    return k


def _complex(amplitude, phase_deg, omega, beta_deg, cg, depth, g) -> np.ndarray:
    """AQWA (amplitude, phase lag in degrees, relative to the wave at the CG) to cummins.

    Shapes: amplitude/phase (nω, nβ, n); returns X = A exp(−i(φ + k (x_G cos β + y_G sin β))).
    """
    k = wavenumber(omega, depth, g)[:, None]
    beta = np.radians(beta_deg)[None, :]
    shift = k * (cg[0] * np.cos(beta) + cg[1] * np.sin(beta))
    return amplitude * np.exp(-1j * (np.radians(phase_deg) + shift[..., None]))


def _depth(value: float) -> float:
    return value if value > 0 else np.inf


def _limits_history(history: list[str], a_inf, high, low, g: float) -> None:
    if a_inf is None and high is not None:
        history.append(
            f"AQWA's added mass at {high:g} rad/s not used as A(inf): frequency "
            f"below {HIGH_FREQUENCY_LIMIT:g} rad/s"
        )
    if a_inf is not None:
        history.append(
            f"added_mass_inf = AQWA's added mass at {high:g} rad/s (LHFR option; "
            f"wave length {2 * np.pi * g / high**2 * 1000:.2g} mm: the infinite-"
            "frequency limit)"
        )
    if low is not None:
        history.append(
            f"AQWA's low-frequency added mass and damping ({low:g} rad/s, LHFR) "
            "not used as A(0): in finite depth heave A(w) has no settled limit there"
        )


#: Largest asymmetry |M_ij - M_ji| / (sqrt|M_ii M_jj| + 1e-3 sqrt(T_i T_j)) accepted in
#: an AQWA matrix (T: largest diagonal of the same kind over all frequencies). Measured:
#: ≤ 0.69 in the damping, ≤ 0.17 in the added mass of the three AQWA runs of the corpus
#: and the shared data (noise in near-zero couplings); rows swapped or edited give
#: 10–10⁶.
ASYMMETRY_LIMIT = 2.0


def asymmetry(matrices: np.ndarray) -> np.ndarray:
    """Relative asymmetry of each n×n matrix of ``matrices`` (…, n, n), see
    :data:`ASYMMETRY_LIMIT`; 0 for a symmetric matrix."""
    stack = np.asarray(matrices, dtype=float).reshape(-1, *np.shape(matrices)[-2:])
    n = stack.shape[-1]
    diag = np.abs(np.diagonal(stack, axis1=1, axis2=2))
    rot = (np.arange(n) % 6) >= 3
    largest = np.array([diag[:, rot == rot[i]].max() for i in range(n)])
    floor = 1e-3 * np.sqrt(np.outer(largest, largest))
    scale = np.sqrt(diag[:, :, None] * diag[:, None, :]) + floor + np.finfo(float).tiny
    return (np.abs(stack - np.swapaxes(stack, 1, 2)) / scale).max(axis=(1, 2))
