"""The checks of the wave forces: ``wave_parity`` — those of a port/starboard symmetric
body mirror with the heading, F(ω, −β) = T F(ω, β), T = diag(1, −1, 1, −1, 1, −1);
``long_wave_limit`` — the heave excitation of long waves is the restoring, C33.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.check.common import PARITY_TOL, _speed_suffix, _speeds
from cummins.check.report import Finding
from cummins.hydrodb import DOF_NAMES, bodies, dof_matrix, split_dof


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
                    if k == m:  # a heading its own mirror (0°, 180°): there it must vanish
                        where_text = f"at {bk:g}°, its own mirror heading, it should be 0 but is"
                    else:
                        where_text = (
                            f"at {bk:g}° and {bm:g}° it differs from "
                            f"{'the same' if sign > 0 else 'the opposite'} value by"
                        )
                    out.append(
                        Finding(
                            "wave_parity",
                            "warning",
                            f"{name} of {label}{suffix} does not mirror with the heading "
                            f"although the body is port/starboard symmetric: {where_text} "
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


#: As ω → 0 the incident wave's pressure is hydrostatic, ρ g η at every depth, and the
#: heave excitation per metre of wave amplitude tends to ρ g A_wp = C33 (Newman (1977)
#: §6.17; the diffraction force vanishes with ω), departing from it by about k times the
#: body's depth. Judged where the lowest frequency is a long wave for the body (k times
#: the larger of √A_wp and ∇/A_wp at most LONG_WAVE): beyond LONG_WAVE_TOL apart, the
#: excitation and the restoring do not describe one body (other meshes, a restoring
#: that holds a mooring, a force about another point), and the heave RAO does not tend
#: to 1. The corpus, where judged (23 cases): 0.935–1.002, but AQWA's floating OWC (0.75
#: and 0.59) and the WAMIT plate (≈ 0: a thin plate whose heave excitation does not
#: see the waterplane of its hydrostatics).
LONG_WAVE = 0.06
LONG_WAVE_TOL = 0.1


def _body_depth(ds: xr.Dataset, label: str, waterplane: float) -> float:
    """The length over which a long wave must not vary for the body of ``label``: its
    waterplane's breadth √A_wp, or its mean draught ∇/A_wp when deeper (a spar's
    bottom feels e^{−kT} of the surface's pressure); without ∇, the breadth."""
    from cummins.restoring import body_volumes

    names = bodies(ds)
    volume = body_volumes(ds, len(names))[names.index(split_dof(label)[0])]
    depth = np.sqrt(waterplane)
    if np.isfinite(volume) and waterplane > 0:
        depth = max(depth, float(volume) / waterplane)
    return depth


def long_wave_heave_ratios(ds: xr.Dataset) -> dict[str, tuple[float, float]]:
    """|F₃(ω_min)| / C₃₃ of each body's heave where the lowest frequency is a long wave
    for it (:data:`LONG_WAVE`), the force the mean over the headings: {heave label:
    (ratio, ω_min)}. Empty without excitation or restoring."""
    from cummins.seakeeping.waves import wavenumber

    if "excitation_force" not in ds or "hydrostatic_stiffness" not in ds:
        return {}
    rho, g = float(ds.attrs.get("rho", 1025.0)), float(ds.attrs.get("g", 9.81))
    depth = float(ds.attrs.get("water_depth", np.inf))
    omega = ds.omega.values.astype(float)
    lowest = int(np.argmin(omega))
    k = float(wavenumber(omega[lowest], depth=depth if depth > 0 else np.inf, g=g))
    force = ds.excitation_force.isel(omega=lowest)
    c = dof_matrix(ds, "hydrostatic_stiffness")
    labels = [str(d) for d in ds.influenced_dof.values]
    out = {}
    for i, label in enumerate(labels):
        if split_dof(label)[1] != "Heave" or c[i, i] <= 0:
            continue
        if k * _body_depth(ds, label, c[i, i] / (rho * g)) > LONG_WAVE:
            continue
        f3 = float(np.abs(force.sel(influenced_dof=label).values).mean())
        out[label] = (f3 / float(c[i, i]), float(omega[lowest]))
    return out


def _check_long_wave_limit(ds: xr.Dataset) -> list[Finding]:
    """The heave excitation of long waves against the restoring (:data:`LONG_WAVE_TOL`)."""
    out: list[Finding] = []
    for sub in _speeds(ds):
        if _speed_suffix(sub):
            continue  # at speed the encounter frequency, not the wave's, is low
        for label, (ratio, omega) in long_wave_heave_ratios(sub).items():
            if abs(ratio - 1.0) <= LONG_WAVE_TOL:
                out.append(
                    Finding(
                        "long_wave_limit",
                        "ok",
                        f"heave excitation at {omega:.3g} rad/s is {ratio:.3f} × C33",
                        where=label,
                        value=ratio,
                    )
                )
                continue
            out.append(
                Finding(
                    "long_wave_limit",
                    "warning",
                    f"the heave excitation of long waves ({omega:.3g} rad/s) is "
                    f"{ratio:.3g} × C33, where it tends to C33 = ρ g A_wp: the excitation "
                    "and the restoring do not describe the same body, and the heave RAO "
                    f"tends to {ratio:.3g}, not 1, in long waves",
                    where=label,
                    value=ratio,
                    advice="check that both come from the same run and mesh, and that the "
                    "restoring holds no mooring or other body's terms",
                )
            )
    return out
