"""Checks of the radiation coefficients A(ω), B(ω) and A∞ against what physics requires.

* ``frequency_grid`` — range and spacing of the finite frequencies; ω = 0 and ω = ∞ rows.
* ``symmetry`` — A(ω), B(ω) and A∞ symmetric at zero speed.
* ``damping_positive`` — B(ω) positive semidefinite (eigenvalues of the diagonally scaled
  symmetric part), negative diagonal terms named, a flipped sign an error.
* ``added_mass_inf`` — A∞ and M_RB + A∞ positive definite.
* ``damping_decay`` — B_ii small at ω_max (the retardation function's truncation) and
  at ω_min (K(t) assumes B(0) = 0).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.check.common import (
    DECAY_TOL,
    LOW_FREQUENCY_TOL,
    NEGATIVE_DAMPING_TOL,
    SYMMETRY_TOL,
    _diag_scale,
    _labels,
    _speed_suffix,
    _speeds,
)
from cummins.check.report import Finding
from cummins.hydrodb import dof_matrix, is_rotation
from cummins.repair import PASSIVE_LIMIT


def _check_grid(ds: xr.Dataset) -> list[Finding]:
    w = ds.omega.values
    dw = np.diff(w)
    uniform = dw.size == 0 or np.allclose(dw, dw.mean(), rtol=1e-3)
    msg = (
        f"{w.size} frequencies from {w[0]:.4g} to {w[-1]:.4g} rad/s "
        f"({2 * np.pi / w[-1]:.3g}–{2 * np.pi / w[0]:.4g} s), "
        + ("uniform spacing" if uniform else f"spacing {dw.min():.3g}–{dw.max():.3g} rad/s")
    )
    out = [Finding("frequency_grid", "ok", msg)]
    have = [name for name in ("added_mass_zero", "added_mass_inf") if name in ds]
    if "added_mass_inf" not in ds:
        out.append(
            Finding(
                "frequency_grid",
                "info",
                "no infinite-frequency added mass A∞ in the data",
                advice="time-domain models need A∞: estimate it from A(ω), B(ω) "
                "(Ogilvie's relation) or rerun the solver with ω = ∞",
            )
        )
    else:
        out.append(Finding("frequency_grid", "ok", "limits present: " + ", ".join(have)))
    if w.size < 20:
        out.append(
            Finding(
                "frequency_grid",
                "warning",
                f"only {w.size} frequencies",
                advice="retardation functions and fits need a finer grid (50+ frequencies)",
            )
        )
    return out


def _check_symmetry(ds: xr.Dataset) -> list[Finding]:
    out: list[Finding] = []
    labels = _labels(ds)
    for sub in _speeds(ds):
        speed = float(sub.forward_speed) if "forward_speed" in sub.coords else 0.0
        if speed != 0.0:
            out.append(
                Finding(
                    "symmetry",
                    "info",
                    f"not tested at U = {speed:g} m/s: forward speed makes A and B non-symmetric",
                )
            )
            continue
        suffix = _speed_suffix(sub)
        for name in ("added_mass", "radiation_damping", "added_mass_inf"):
            if name not in sub:
                continue
            x = dof_matrix(sub, name)
            x = x.reshape(-1, x.shape[-2], x.shape[-1])
            s = _diag_scale(x)
            scaled = x * s[:, None] * s[None, :]
            asym = np.abs(scaled - np.swapaxes(scaled, 1, 2))
            k, i, j = np.unravel_index(np.argmax(asym), asym.shape)
            worst = float(asym[k, i, j])
            at = f" at {sub.omega.values[k]:.4g} rad/s" if name != "added_mass_inf" else ""
            if worst > SYMMETRY_TOL:
                bad = np.max(asym, axis=(1, 2)) > SYMMETRY_TOL
                count = (
                    f" ({int(bad.sum())} of {bad.size} frequencies, "
                    f"{_frequency_span(sub.omega.values[bad])})"
                    if name != "added_mass_inf"
                    else ""
                )
                out.append(
                    Finding(
                        "symmetry",
                        "warning",
                        f"{name} is not symmetric{suffix}{count}: relative asymmetry "
                        f"{worst:.3g}{at}",
                        where=f"{labels[i]}-{labels[j]}",
                        value=worst,
                        advice="at zero speed A and B must be symmetric; asymmetry confined to "
                        "a few frequencies points to irregular frequencies, everywhere to the "
                        "mesh or solver settings",
                    )
                )
            else:
                out.append(
                    Finding(
                        "symmetry",
                        "ok",
                        f"{name} symmetric{suffix} (worst relative asymmetry {worst:.2g}, "
                        f"{labels[i]}-{labels[j]}{at})",
                        value=worst,
                    )
                )
    return out


def _check_damping(ds: xr.Dataset) -> list[Finding]:
    out: list[Finding] = []
    labels = _labels(ds)
    for sub in _speeds(ds):
        suffix = _speed_suffix(sub)
        b = sub.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").values
        w = sub.omega.values
        diag = np.diagonal(b, axis1=1, axis2=2)
        peak = np.max(np.abs(diag), axis=0)
        negligible = _negligible_dofs(peak, labels)
        for k, label in enumerate(labels):
            if negligible[k]:
                continue
            rel = diag[:, k] / peak[k]
            neg = rel < -NEGATIVE_DAMPING_TOL
            if _sign_flipped(rel, w) and peak[k] >= SIGNIFICANT_DOF * _kind_peak(peak, labels, k):
                # negative at most frequencies, its largest magnitude included: not the
                # spikes of irregular frequencies but damping of the wrong sign
                out.append(
                    Finding(
                        "damping_positive",
                        "error",
                        f"B_{label} is negative at {int(neg.sum())} of {w.size} frequencies"
                        f"{suffix}, its largest value included ({diag[:, k].min():.4g} at "
                        f"{w[int(np.argmin(rel))]:.4g} rad/s): the body would draw energy from "
                        "the waves it radiates",
                        where=label,
                        value=float(rel.min()),
                        advice="the damping's sign is flipped (a time convention or axis "
                        "error in the file or the reader): check the file and the solver's "
                        "output settings",
                    )
                )
            elif neg.any():
                worst = int(np.argmin(rel))
                out.append(
                    Finding(
                        "damping_positive",
                        "warning",
                        f"B_{label} is negative at {int(neg.sum())} of {w.size} frequencies"
                        f"{suffix} ({_frequency_span(w[neg])}), down to {rel[worst]:.3g} of its "
                        f"peak at {w[worst]:.4g} rad/s",
                        where=label,
                        value=float(rel[worst]),
                        advice="negative damping is unphysical (typically irregular frequencies "
                        "of the panel method): exclude these frequencies or rerun the solver "
                        "with irregular-frequency removal",
                    )
                )
        sym = 0.5 * (b + np.swapaxes(b, 1, 2))[:, ~negligible][:, :, ~negligible]
        s = _diag_scale(sym)
        scaled = sym * s[None, :, None] * s[None, None, :]
        labels = [label for label, z in zip(labels, negligible, strict=True) if not z]
        eig = np.linalg.eigvalsh(scaled)
        lam_min = eig[:, 0]
        lam_max = max(float(np.max(eig[:, -1])), np.finfo(float).tiny)
        rel = lam_min / lam_max
        neg = rel < -NEGATIVE_DAMPING_TOL
        if neg.any():
            worst = int(np.argmin(rel))
            _, vecs = np.linalg.eigh(scaled[worst])
            dominant = np.argsort(np.abs(vecs[:, 0]))[::-1][:2]
            out.append(
                Finding(
                    "damping_positive",
                    "warning",
                    f"B(ω) is not positive semidefinite at {int(neg.sum())} of {w.size} "
                    f"frequencies{suffix} ({_frequency_span(w[neg])}); worst eigenvalue "
                    f"{rel[worst]:.3g} of the largest, at {w[worst]:.4g} rad/s, mainly "
                    f"{' and '.join(labels[d] for d in dominant)}",
                    where=f"{w[worst]:.4g} rad/s",
                    value=float(rel[worst]),
                    advice="the radiation force must dissipate energy: a passive model is "
                    "fitted to the nearest passive damping (cummins.repair."
                    f"nearest_passive_damping) where it is within {PASSIVE_LIMIT:g} of the "
                    "scaled peak; exclude or repair the frequencies further off",
                )
            )
        else:
            out.append(
                Finding(
                    "damping_positive",
                    "ok",
                    f"B(ω) positive semidefinite at all {w.size} frequencies{suffix} "
                    f"(smallest scaled eigenvalue {rel.min():.2g}"
                    + (
                        f", within the solver's noise {-NEGATIVE_DAMPING_TOL:g}: `cummins "
                        "fit` takes the nearest positive semidefinite damping where it is "
                        "below zero and says so)"
                        if rel.min() < 0
                        else ")"
                    ),
                    value=float(rel.min()),
                )
            )
    return out


#: A DOF whose peak |B_ii| is below this fraction of the largest of its kind (translation
#: or rotation) is too small for its sign to be an error (a bottom-mounted base, noise).
SIGNIFICANT_DOF = 1e-3


def _kind_peak(peak: np.ndarray, labels: list[str], k: int) -> float:
    """The largest peak |B_jj| of the DOFs of the kind of DOF k (translation or rotation)."""
    same = [j for j, label in enumerate(labels) if is_rotation(label) == is_rotation(labels[k])]
    return float(np.max(peak[same]))


def _sign_flipped(rel: np.ndarray, w: np.ndarray) -> bool:
    """B_ii / max|B_ii| negative at most frequencies, at its largest magnitude, and over
    at least four times the area where it is positive: damping of the wrong sign."""
    negative = rel < -NEGATIVE_DAMPING_TOL
    if negative.sum() <= 0.5 * w.size or rel.min() > -1.0 + 1e-12:
        return False
    if w.size < 2:
        return True
    below = np.trapezoid(np.clip(-rel, 0.0, None), w)
    above = np.trapezoid(np.clip(rel, 0.0, None), w)
    return bool(below >= 4.0 * above)


def _frequency_span(w: np.ndarray) -> str:
    if w.size == 1:
        return f"{w[0]:.4g} rad/s"
    return f"{w.min():.4g}–{w.max():.4g} rad/s"


def _negligible_dofs(diagonal: np.ndarray, labels: list[str]) -> np.ndarray:
    """DOFs whose diagonal term is < 1e-6 of the largest of their kind (translation or rotation).

    An axisymmetric body has no yaw added mass or damping; solvers then print noise
    (1e-8 where roll is 1e2), which must not be read as a physical value.
    """
    rotation = np.array([is_rotation(label) for label in labels])
    peak = np.abs(diagonal)
    out = np.zeros(len(labels), dtype=bool)
    for kind in (rotation, ~rotation):
        if kind.any():
            out[kind] = peak[kind] <= 1e-6 * peak[kind].max()
    return out


def _check_added_mass_inf(ds: xr.Dataset) -> list[Finding]:
    if "added_mass_inf" not in ds:
        return []
    labels = _labels(ds)
    out = []
    for sub in _speeds(ds):
        a = dof_matrix(sub, "added_mass_inf")
        zero = _negligible_dofs(np.diag(a), labels)
        if zero.any():
            names = ", ".join(labels[k] for k in np.flatnonzero(zero))
            out.append(
                Finding(
                    "added_mass_inf",
                    "info",
                    f"A∞ is negligible for {names} (normal for an axisymmetric body in yaw)",
                    where=names,
                )
            )
        keep = ~zero
        s = _diag_scale(a)
        scaled = (a * s[:, None] * s[None, :])[np.ix_(keep, keep)]
        if scaled.size == 0:
            continue
        eig = np.linalg.eigvalsh(0.5 * (scaled + scaled.T))
        if eig[0] < -1e-6:
            out.append(
                Finding(
                    "added_mass_inf",
                    "error",
                    f"A∞ is not positive semidefinite (scaled eigenvalues {eig[0]:.3g} … "
                    f"{eig[-1]:.3g})",
                    value=float(eig[0]),
                    advice="the infinite-frequency added mass must store kinetic energy: check "
                    "the ω = ∞ data of the solver",
                )
            )
        else:
            out.append(
                Finding(
                    "added_mass_inf",
                    "ok",
                    f"A∞ positive definite on {int(keep.sum())} DOFs (scaled eigenvalues "
                    f"{eig[0]:.3g} … {eig[-1]:.3g})",
                    value=float(eig[0]),
                )
            )
        if "inertia_matrix" in sub:
            m = dof_matrix(sub, "inertia_matrix") + a
            sm = _diag_scale(m)
            eig_m = np.linalg.eigvalsh(0.5 * (m + m.T) * sm[:, None] * sm[None, :])
            if eig_m[0] <= 1e-9:
                out.append(
                    Finding(
                        "added_mass_inf",
                        "error",
                        f"M_RB + A∞ is not positive definite (smallest scaled eigenvalue "
                        f"{eig_m[0]:.3g})",
                        value=float(eig_m[0]),
                        advice="the time-domain mass matrix must be invertible: check the "
                        "inertia matrix and the ω = ∞ data",
                    )
                )
    return out


def _check_decay(ds: xr.Dataset) -> list[Finding]:
    out = []
    labels = _labels(ds)
    for sub in _speeds(ds):
        suffix = _speed_suffix(sub)
        b = np.diagonal(
            sub.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").values,
            axis1=1,
            axis2=2,
        )
        w = sub.omega.values
        peak = np.max(np.abs(b), axis=0)
        negligible = _negligible_dofs(peak, labels)
        for k, label in enumerate(labels):
            if negligible[k]:
                out.append(
                    Finding(
                        "damping_decay",
                        "info",
                        f"B_{label} is negligible at every frequency{suffix}",
                        where=label,
                    )
                )
                continue
            start = abs(b[0, k]) / peak[k]
            if start > LOW_FREQUENCY_TOL:
                out.append(
                    Finding(
                        "damping_decay",
                        "warning",
                        f"B_{label} is already {start:.0%} of its peak at ω_min = "
                        f"{w[0]:.4g} rad/s{suffix}",
                        where=label,
                        value=float(start),
                        advice="the data do not reach low enough frequencies (or come from "
                        "strip theory, whose damping does not vanish as ω → 0); K(t) assumes "
                        "B(0) = 0 and its long-time part and A(ω) near ω_min are uncertain",
                    )
                )
            tail = abs(b[-1, k]) / peak[k]
            if tail > DECAY_TOL:
                out.append(
                    Finding(
                        "damping_decay",
                        "warning",
                        f"B_{label} has not decayed at ω_max = {w[-1]:.4g} rad/s{suffix}: "
                        f"{tail:.2g} of its peak",
                        where=label,
                        value=float(tail),
                        advice="the retardation function will be truncated: extend the "
                        "frequency range or use a high-frequency tail",
                    )
                )
            else:
                out.append(
                    Finding(
                        "damping_decay",
                        "ok",
                        f"B_{label} decayed to {tail:.2g} of its peak at ω_max{suffix}",
                        where=label,
                        value=float(tail),
                    )
                )
    return out
