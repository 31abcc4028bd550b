"""The ``wave_parity`` check: wave forces of a port/starboard symmetric body mirror with
the heading, F(ω, −β) = T F(ω, β), T = diag(1, −1, 1, −1, 1, −1).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.check.common import PARITY_TOL, _speed_suffix, _speeds
from cummins.check.report import Finding
from cummins.hydrodb import DOF_NAMES, split_dof


def _mirror_pairs(beta: np.ndarray) -> list[tuple[int, int]]:
    """Index pairs (k, m) of headings with β_m = −β_k (mod 2π), k ≤ m (k = m on the x
    axis)."""
    b = np.mod(beta, 2 * np.pi)
    pairs = []
    for k, bk in enumerate(b):
        mirror = np.mod(-bk, 2 * np.pi)
        gap = np.abs(np.angle(np.exp(1j * (b - mirror))))
        m = int(np.argmin(gap))
        if gap[m] < 1e-6 and k <= m:
            pairs.append((k, m))
    return pairs


def _check_wave_parity(ds: xr.Dataset) -> list[Finding]:
    """Wave forces of a port/starboard symmetric body mirror with the heading:
    F(ω, −β) = T F(ω, β), T = diag(1, −1, 1, −1, 1, −1) (surge, heave, pitch keep their
    sign; sway, roll, yaw change it). A file that breaks this for a symmetric body holds
    magnitudes instead of signed values, or a sign error (the MSS S-175's yaw drift)."""
    from cummins.seakeeping.excitation import MIRROR_SIGNS, symmetry_evidence

    out: list[Finding] = []
    for sub in _speeds(ds):
        names = [v for v in ("excitation_force", "drift_force") if v in sub]
        if not names or "wave_direction" not in sub.dims:
            continue
        symmetric, _ = symmetry_evidence(sub)
        pairs = _mirror_pairs(sub.wave_direction.values)
        if not symmetric or not any(k != m for k, m in pairs):
            continue
        suffix = _speed_suffix(sub)
        labels = [str(d) for d in sub.influenced_dof.values]
        for name in names:
            f = sub[name].transpose("omega", "wave_direction", "influenced_dof").values
            for i, label in enumerate(labels):
                dof = split_dof(label)[1]
                sign = MIRROR_SIGNS[DOF_NAMES.index(dof)]
                peak = float(np.abs(f[:, :, i]).max())
                if peak == 0:
                    continue
                worst, where = 0.0, None
                for k, m in pairs:
                    mismatch = float(np.abs(f[:, m, i] - sign * f[:, k, i]).max()) / peak
                    if mismatch > worst:
                        worst, where = mismatch, (k, m)
                if worst > PARITY_TOL and where is not None:
                    k, m = where
                    bk, bm = np.degrees(sub.wave_direction.values[[k, m]])
                    out.append(
                        Finding(
                            "wave_parity",
                            "warning",
                            f"{name} of {label}{suffix} does not mirror with the heading "
                            f"although the body is port/starboard symmetric: at {bk:g}° and "
                            f"{bm:g}° it differs from "
                            f"{'the same' if sign > 0 else 'the opposite'} value by "
                            f"{worst:.0%} of its largest value",
                            where=label,
                            value=worst,
                            advice="the file may hold magnitudes instead of signed values, "
                            "or a sign error: check the source (cummins uses the values as "
                            "given; drift and excitation at mirrored headings will differ)",
                        )
                    )
    if not out:
        out.append(
            Finding(
                "wave_parity",
                "ok",
                "wave forces mirror with the heading "
                "(or the body is not symmetric, or no mirrored headings)",
            )
        )
    return out
