"""How a wave table breaks port/starboard symmetry: at which headings, and in which pattern.

A body symmetric about its x–z plane has F(ω, −β) = T F(ω, β), T = diag(1, −1, 1, −1, 1,
−1) (sway, roll and yaw change sign under y → −y), for the excitation, the motion RAOs
and the mean drift alike. The ``wave_parity`` check (:mod:`cummins.check.waves`) measures
it per DOF over the pairs of mirrored headings (:func:`mirror_pairs`,
:func:`parity_mismatch`); where a table breaks it, the pattern of the break tells a
processing error from an asymmetric hull (:func:`break_pattern`):

* ``"shifted"`` — F(β + π) = T F(β) on the broken pairs: the values of one half-plane
  repeated at β + 180°, in the same order, with the mirror's signs, instead of at
  360° − β. MSS's ``wamit2vessel.m`` fills ``driftfrc`` at 190–350° so from 10–170°
  (while its first-order tables there are the mirror images): MSS's ``tanker.mat``, to
  the last digit;
* ``"sign_kept"`` — F_i(−β) = −T_ii F_i(β): mirrored without the DOF's change of sign.
  MSS's ``read_veres_WD.m`` mirrors the yaw drift, its third column, as if it were
  heave's (MSS's ``supply.mat`` and ``s175.mat``, about the VERES motion reference point);
* ``"sign_kept_about"`` — the yaw moment is ``"sign_kept"`` about another point x_P on the
  x axis: with M_P = M_O + (x_O − x_P) F_y (the moment moved along x) and F_y mirroring,
  M_O(−β) − M_O(β) = 2 (x_O − x_P) F_y(β), x_P the least-squares fit. The MSS VERES
  structs read by cummins, whose drift is moved from the VERES point (at the x of G) to CO:
  x_P is that point.

A pattern is accepted when it holds to :data:`PATTERN_TOL` of the DOF's largest value on
every broken pair (MSS's copies are exact; single precision leaves 10⁻⁷).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

#: Residual, relative to the DOF's largest value, below which a pattern of the break holds.
PATTERN_TOL = 1e-3


def mirror_pairs(beta: NDArray) -> list[tuple[int, int]]:
    """Index pairs (k, m) of headings with β_m = −β_k (mod 2π), k ≤ m (k = m on the x
    axis: 0 and π)."""
    b = np.mod(np.asarray(beta, dtype=float), 2 * np.pi)
    pairs = []
    for k, bk in enumerate(b):
        mirror = np.mod(-bk, 2 * np.pi)
        gap = np.abs(np.angle(np.exp(1j * (b - mirror))))
        m = int(np.argmin(gap))
        if gap[m] < 1e-6 and k <= m:
            pairs.append((k, m))
    return pairs


def parity_mismatch(values: NDArray, pairs: list[tuple[int, int]], signs: NDArray) -> NDArray:
    """max_ω |F_i(−β) − T_ii F_i(β)| / max |F_i| per pair and DOF.

    Parameters
    ----------
    values
        The table, shape (omega, wave_direction, dof), real or complex.
    pairs
        The mirrored headings (:func:`mirror_pairs`).
    signs
        T_ii per DOF (1 or −1).

    Returns
    -------
    numpy.ndarray
        Shape (len(pairs), dof); 0 for a DOF that is identically zero.
    """
    peak = np.abs(values).max(axis=(0, 1))
    scale = np.where(peak > 0, peak, 1.0)
    out = np.zeros((len(pairs), values.shape[2]))
    for p, (k, m) in enumerate(pairs):
        out[p] = np.abs(values[:, m] - signs * values[:, k]).max(axis=0) / scale
    return out


def _nearest(beta: NDArray, target: float) -> int | None:
    gap = np.abs(np.angle(np.exp(1j * (np.asarray(beta, dtype=float) - target))))
    j = int(np.argmin(gap))
    return j if gap[j] < 1e-6 else None


def break_pattern(
    values: NDArray,
    beta: NDArray,
    broken: list[tuple[int, int]],
    sign: float,
    *,
    sway: NDArray | None = None,
    x_reference: float = 0.0,
) -> tuple[str | None, float | None]:
    """The pattern of a DOF's break of mirror symmetry (module docstring).

    Parameters
    ----------
    values
        The DOF's table, shape (omega, wave_direction).
    beta
        The headings, rad.
    broken
        The pairs (k, m) of :func:`mirror_pairs` the DOF breaks, k ≠ m.
    sign
        The DOF's T_ii.
    sway
        For a yaw DOF, the same body's sway table, to test ``"sign_kept_about"``.
    x_reference
        x of the point the table is about, m (the dataset's ``reference_point``).

    Returns
    -------
    (str or None, float or None)
        ``"shifted"``, ``"sign_kept"``, ``"sign_kept_about"`` or None; and x_P (m) for
        ``"sign_kept_about"``.
    """
    if not broken:
        return None, None
    peak = float(np.abs(values).max())
    if peak == 0:
        return None, None
    tol = PATTERN_TOL * peak
    shifted = []
    for k, _ in broken:
        j = _nearest(beta, float(beta[k]) + np.pi)
        if j is None:
            shifted = []
            break
        shifted.append(float(np.abs(values[:, j] - sign * values[:, k]).max()))
    if shifted and max(shifted) <= tol:
        return "shifted", None
    kept = max(float(np.abs(values[:, m] + sign * values[:, k]).max()) for k, m in broken)
    if kept <= tol:
        return "sign_kept", None
    if sway is None:
        return None, None
    delta = np.concatenate([values[:, m] - values[:, k] for k, m in broken])
    arm = np.concatenate([2.0 * sway[:, k] for k, _ in broken])
    if not np.all(np.isfinite(arm)) or float(np.vdot(arm, arm).real) == 0:
        return None, None
    if np.abs(np.concatenate([sway[:, m] + sway[:, k] for k, m in broken])).max() > (
        PATTERN_TOL * float(np.abs(sway).max())
    ):
        return None, None  # the sway itself does not mirror: no point to find
    shift = float((np.vdot(arm, delta) / np.vdot(arm, arm)).real)
    if float(np.abs(delta - shift * arm).max()) <= tol:
        return "sign_kept_about", x_reference - shift
    return None, None


def degree_ranges(degrees: list[float]) -> str:
    """Headings in degrees as runs of the smallest step among them: ``"190–350°"``,
    ``"10°, 40–60°"``."""
    values = sorted({round(float(d), 6) for d in degrees})
    if not values:
        return ""
    steps = np.diff(values)
    step = float(steps.min()) if steps.size else 0.0
    runs: list[list[float]] = [[values[0]]]
    for v in values[1:]:
        if step > 0 and abs(v - runs[-1][-1] - step) < 1e-6:
            runs[-1].append(v)
        else:
            runs.append([v])
    return ", ".join(f"{r[0]:g}°" if len(r) == 1 else f"{r[0]:g}–{r[-1]:g}°" for r in runs)
