"""Diagnostics of a hydrodynamic database: is it physically usable, and where not?

:func:`check` runs every test below and returns a :class:`CheckReport`; nothing is
changed in the data. Each finding says what was measured, where, and what to do.

* ``frequency_grid`` — range and spacing of the finite frequencies; whether ω = 0 and
  ω = ∞ limits are present.
* ``symmetry`` — A(ω) and B(ω) symmetric (zero speed): worst relative asymmetry per DOF
  pair, |X_ij − X_ji| / √(max|X_ii| · max|X_jj|).
* ``damping_positive`` — B(ω) positive semidefinite at each frequency: eigenvalues of
  the symmetric part of the diagonally scaled matrix D^{-1/2} B D^{-1/2}
  (D = peak |B_ii|), not determinants; negative diagonal entries are named, and a
  diagonal term negative at most frequencies, its largest magnitude included (the sign
  flipped, not irregular frequencies), is an error.
* ``added_mass_inf`` — A∞ symmetric positive definite (eigenvalues, scaled likewise).
* ``damping_decay`` — |B_ii(ω_max)| / max_ω |B_ii|: the retardation function needs
  B to have decayed at the end of the data; and |B_ii(ω_min)| / max|B_ii|, since it
  assumes B(0) = 0 below the first frequency.
* ``physical`` — what no floating body has (errors): non-finite coordinates or positions,
  a negative mass, masses, inertias, added masses or dampings beyond any floating body
  (10¹² kg, 10¹⁸ kg·m², :func:`cummins.validation.coefficient_limit`); the numerical
  checks below are skipped then.
* ``inertia``, ``hydrostatics`` — M_RB symmetric positive definite; C33, C44, C55 > 0.
* ``copied_dof`` — a DOF that is an exact scaled copy of another (strip-theory codes
  approximate surge by scaling sway).
* ``finite`` — NaN/Inf anywhere (validation of the dataset already refuses them).
* ``suspect_frequencies`` — spikes and clearly negative damping
  (:func:`cummins.repair.find_suspect_frequencies`).
* ``retardation`` — per significant coupling: K(0), ∫K dt against B(0) = 0,
  K(t_max)/max|K|, the tail's share of ∫B dω, the Ogilvie estimate of A∞ and its spread
  over frequency (and its distance from the solver's ω = ∞ row), and the
  Kramers–Kronig error (:func:`cummins.radiation.retardation.retardation_diagnostics`).
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from dataclasses import asdict, dataclass, field

import numpy as np
import xarray as xr

from cummins.hydrodb import DOF_NAMES, dof_matrix, is_rotation, split_dof, validate
from cummins.kinematics import center_of_gravity_from_inertia
from cummins.radiation.retardation import retardation_diagnostics
from cummins.repair import find_suspect_frequencies
from cummins.validation import coefficient_limit

SEVERITIES = ("ok", "info", "warning", "error")

#: Relative tolerances of the checks.
SYMMETRY_TOL = 0.02
NEGATIVE_DAMPING_TOL = 1e-3
DECAY_TOL = 0.05
LOW_FREQUENCY_TOL = 0.2  # |B_ii(ω_min)| / peak
K_END_TOL = 0.05  # |K(t_max)| / max|K|
K_INTEGRAL_TOL = 0.1  # |∫K dt| / ∫|K| dt
TAIL_TOL = 0.2  # share of ∫B dω in the extrapolated tail
A_INF_TOL = 0.05  # relative spread, or distance from the data row
KK_TOL = 0.1  # relative Kramers-Kronig error
PARITY_TOL = 0.05  # |F(β) − T F(−β)| / max|F| of a DOF, port/starboard symmetric body


@dataclass(frozen=True)
class Finding:
    """One result of a check.

    Attributes
    ----------
    check
        Name of the check (``"symmetry"``, ``"damping_positive"`` …).
    severity
        ``"ok"``, ``"info"``, ``"warning"`` or ``"error"``.
    message
        What was found, in plain language.
    where
        The DOF pair, DOF or frequency concerned, if any.
    value
        The measured number behind the finding (relative, dimensionless), if any.
    advice
        What to do about it, if anything.
    details
        The numbers behind the finding, by name (for ``--json`` users).
    """

    check: str
    severity: str
    message: str
    where: str | None = None
    value: float | None = None
    advice: str | None = None
    details: dict | None = None


@dataclass(frozen=True)
class CheckReport:
    """All findings of :func:`check` on one dataset."""

    source: str
    findings: tuple[Finding, ...] = field(default_factory=tuple)

    def __iter__(self) -> Iterator[Finding]:
        return iter(self.findings)

    @property
    def ok(self) -> bool:
        """True when no finding is an error."""
        return not any(f.severity == "error" for f in self.findings)

    def worst(self) -> str:
        """The most severe severity present (``"ok"`` if none)."""
        ranks = [SEVERITIES.index(f.severity) for f in self.findings] or [0]
        return SEVERITIES[max(ranks)]

    def by_check(self, name: str) -> list[Finding]:
        """Findings of one check."""
        return [f for f in self.findings if f.check == name]

    def to_dict(self) -> dict:
        """JSON-ready dictionary: ``{"source", "ok", "worst", "findings": [...]}``."""
        return {
            "source": self.source,
            "ok": self.ok,
            "worst": self.worst(),
            "findings": [asdict(f) for f in self.findings],
        }

    def to_json(self, **kwargs) -> str:
        """The report as JSON text."""
        return json.dumps(self.to_dict(), indent=2, **kwargs)

    def to_text(self) -> str:
        """A readable report, one finding per paragraph."""
        marks = {"ok": "ok     ", "info": "info   ", "warning": "WARNING", "error": "ERROR  "}
        lines = [f"Checks of {self.source}"]
        for f in self.findings:
            where = f" [{f.where}]" if f.where else ""
            lines.append(f"  {marks[f.severity]} {f.check}{where}: {f.message}")
            if f.advice:
                lines.append(f"          → {f.advice}")
        lines.append(
            "Result: "
            + ("usable" if self.ok else "NOT usable as it is")
            + f" (worst: {self.worst()})"
        )
        return "\n".join(lines)


def _diag_scale(values: np.ndarray) -> np.ndarray:
    """1/√(peak |X_ii|) per DOF (1 where the DOF is identically zero)."""
    peak = np.max(
        np.abs(np.diagonal(values, axis1=-2, axis2=-1)).reshape(-1, values.shape[-1]), axis=0
    )
    with np.errstate(divide="ignore"):
        scale = np.where(peak > 0, 1.0 / np.sqrt(peak), 0.0)
    return scale


def _labels(ds: xr.Dataset) -> list[str]:
    return [str(d) for d in ds.influenced_dof.values]


def _speeds(ds: xr.Dataset) -> list[xr.Dataset]:
    if "forward_speed" in ds.dims:
        return [ds.isel(forward_speed=k) for k in range(ds.sizes["forward_speed"])]
    return [ds]


def _speed_suffix(ds: xr.Dataset) -> str:
    """`` at U = … m/s`` for a slice at non-zero forward speed, else empty."""
    if "forward_speed" in ds.coords and ds.forward_speed.ndim == 0 and float(ds.forward_speed):
        return f" at U = {float(ds.forward_speed):g} m/s"
    return ""


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
                    advice="the radiation force must dissipate energy; these frequencies cannot "
                    "be fitted by a passive model: exclude or repair them",
                )
            )
        else:
            out.append(
                Finding(
                    "damping_positive",
                    "ok",
                    f"B(ω) positive semidefinite at all {w.size} frequencies{suffix} "
                    f"(smallest scaled eigenvalue {rel.min():.2g})",
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


def _check_rigid_body(ds: xr.Dataset) -> list[Finding]:
    out = []
    labels = _labels(ds)
    if "inertia_matrix" in ds:
        m = dof_matrix(ds, "inertia_matrix")
        m = m.reshape(-1, m.shape[-2], m.shape[-1])[0]
        s = _diag_scale(m)
        scaled = m * s[:, None] * s[None, :]
        asym = float(np.max(np.abs(scaled - scaled.T)))
        eig = np.linalg.eigvalsh(0.5 * (scaled + scaled.T))
        if asym > 1e-6 or eig[0] <= 0:
            out.append(
                Finding(
                    "inertia",
                    "error",
                    f"the inertia matrix is not symmetric positive definite (asymmetry {asym:.2g}, "
                    f"smallest scaled eigenvalue {eig[0]:.3g})",
                    advice="check the mass, centre of gravity and radii of gyration",
                )
            )
        else:
            out.append(Finding("inertia", "ok", "inertia matrix symmetric positive definite"))
        for index in _rigid_blocks(labels):
            block_labels = [labels[i] for i in index]
            out.extend(_rigid_body_consistency(m[np.ix_(index, index)], block_labels))
    if "hydrostatic_stiffness" in ds:
        c = dof_matrix(ds, "hydrostatic_stiffness")
        c = c.reshape(-1, c.shape[-2], c.shape[-1])[0]
        for k, label in enumerate(labels):
            name = label.rpartition("__")[2]
            if name in ("Heave", "Roll", "Pitch"):
                if c[k, k] < 0:
                    out.append(
                        Finding(
                            "hydrostatics",
                            "warning",
                            f"C_{label} = {c[k, k]:.4g} is negative: the body is statically "
                            "unstable in this DOF",
                            where=label,
                            value=float(c[k, k]),
                            advice="check the centre of gravity (negative metacentric height?)",
                        )
                    )
                elif c[k, k] == 0:
                    out.append(
                        Finding(
                            "hydrostatics",
                            "info",
                            f"C_{label} is zero (submerged or moored body?)",
                            where=label,
                        )
                    )
        if not any(f.check == "hydrostatics" for f in out):
            out.append(
                Finding("hydrostatics", "ok", "restoring in heave, roll and pitch is positive")
            )
    return out


def _rigid_blocks(labels: list[str]) -> list[list[int]]:
    """Indices of the six rigid-body modes of each body that has all six (its generalized
    modes, ``Mode7`` …, left out)."""
    blocks = []
    for body in dict.fromkeys(split_dof(label)[0] for label in labels):
        index = [
            labels.index(f"{body}__{name}" if body else name)
            for name in DOF_NAMES
            if (f"{body}__{name}" if body else name) in labels
        ]
        if len(index) == len(DOF_NAMES):
            blocks.append(index)
    return blocks


def _rigid_body_consistency(m: np.ndarray, labels: list[str]) -> list[Finding]:
    """The mass-moment coupling block of a rigid body is −m S(r_g): skew-symmetric."""
    mass, r_g, inconsistency = center_of_gravity_from_inertia(m)
    if inconsistency <= 1e-3:
        return [
            Finding(
                "inertia",
                "ok",
                "inertia matrix is that of a rigid body "
                f"(centre of gravity {np.round(r_g, 4).tolist()} m from the reference point)",
                where=split_dof(labels[0])[0],
            )
        ]
    block = m[:3, 3:]
    pairs = []
    for (i, j), axis in (((1, 2), "x"), ((2, 0), "y"), ((0, 1), "z")):
        # −m S(r): block[i, j] = m r_axis = −block[j, i]
        if not np.isclose(block[i, j], -block[j, i], rtol=1e-3, atol=1e-9 * abs(mass)):
            pairs.append(
                f"M[{labels[i]}, {labels[3 + j]}] = {block[i, j]:.4g} but −M[{labels[j]}, "
                f"{labels[3 + i]}] = {-block[j, i]:.4g} (these give {axis}_g = "
                f"{block[i, j] / mass:.4g} and {-block[j, i] / mass:.4g} m)"
            )
    return [
        Finding(
            "inertia",
            "warning",
            "the inertia matrix is not that of a rigid body: " + "; ".join(pairs),
            value=inconsistency,
            advice="a coupling term was probably left out when the matrix was typed in; "
            "rebuild it from mass, centre of gravity and radii of gyration "
            "(cummins.with_inertia; --mass, --radii-of-gyration)",
            where=split_dof(labels[0])[0],
        )
    ]


def copied_dofs(ds: xr.Dataset) -> list[Finding]:
    """DOFs whose diagonal A and B are an exact constant multiple of another's (strip
    theory's surge from sway), one ``copied_dof`` finding per pair (also used by the fit)."""
    out = []
    labels = _labels(ds)
    sub = _speeds(ds)[0]
    a = np.diagonal(
        sub.added_mass.transpose("omega", "influenced_dof", "radiating_dof").values,
        axis1=1,
        axis2=2,
    )
    b = np.diagonal(
        sub.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").values,
        axis1=1,
        axis2=2,
    )
    n = len(labels)
    for i in range(n):
        for j in range(i + 1, n):
            ra = _constant_ratio(a[:, i], a[:, j])
            rb = _constant_ratio(b[:, i], b[:, j])
            if ra is None or rb is None:
                continue
            out.append(
                Finding(
                    "copied_dof",
                    "info",
                    f"{labels[i]} and {labels[j]} are exact scaled copies of each other "
                    f"(A ratio {ra:.4g}, B ratio {rb:.4g})",
                    where=f"{labels[i]}-{labels[j]}",
                    advice="strip-theory codes approximate surge by scaling sway; the "
                    "fluid memory of the copied DOF is then no more than a guess",
                )
            )
    return out


def _check_suspect_frequencies(ds: xr.Dataset) -> list[Finding]:
    out = []
    for sub in _speeds(ds):
        suffix = _speed_suffix(sub)
        suspects = find_suspect_frequencies(sub)
        if not suspects:
            out.append(
                Finding(
                    "suspect_frequencies", "ok", f"no spikes or clearly negative damping{suffix}"
                )
            )
            continue
        listed = ", ".join(f"{s.omega:.4g}" for s in suspects)
        worst = max(suspects, key=lambda s: s.score)
        out.append(
            Finding(
                "suspect_frequencies",
                "warning",
                f"{len(suspects)} suspect frequencies{suffix} ({listed} rad/s); worst at "
                f"{worst.omega:.4g} rad/s: {worst.quantity}, {worst.reason}",
                where=f"{worst.omega:.4g} rad/s",
                value=worst.score,
                advice="spikes and negative damping are irregular frequencies of panel methods or "
                "solver failures; remove them before fitting (cummins kernel --remove-suspect, "
                "cummins.repair.remove_suspect_frequencies)",
                details={
                    "omega": [s.omega for s in suspects],
                    "quantity": [s.quantity for s in suspects],
                    "reason": [s.reason for s in suspects],
                },
            )
        )
    return out


def _check_retardation(ds: xr.Dataset) -> list[Finding]:
    out = []
    labels = _labels(ds)
    for sub in _speeds(ds):
        if float(sub.forward_speed) if "forward_speed" in sub.coords else 0.0:
            out.append(
                Finding(
                    "retardation",
                    "info",
                    f"not evaluated{_speed_suffix(sub)}: forward speed needs the speed-"
                    "dependent kernels (see cummins.radiation.speed)",
                )
            )
            continue
        d = retardation_diagnostics(sub)
        diag_est = np.abs(np.diag(d.added_mass_inf_estimate.values))
        for i, j in zip(*np.nonzero(np.triu(d.significant.values)), strict=True):
            out.append(_retardation_finding(d, int(i), int(j), labels, diag_est))
    return out


def _retardation_finding(d: xr.Dataset, i: int, j: int, labels: list[str], diag_est) -> Finding:
    pair = labels[i] if i == j else f"{labels[i]}-{labels[j]}"
    k0 = float(d.K0.values[i, j])
    integral = float(d.k_integral.values[i, j])
    end = float(d.k_end_ratio.values[i, j])
    tail = float(d.tail_fraction.values[i, j])
    est = float(d.added_mass_inf_estimate.values[i, j])
    spread = float(d.added_mass_inf_spread.values[i, j])
    row = float(d.added_mass_inf_data.values[i, j])
    kk = float(d.kramers_kronig_error.values[i, j])
    scale = np.sqrt(diag_est[i] * diag_est[j]) or 1.0
    t_max = d.attrs["t_max"]
    abs_integral = abs(integral) / max(abs(k0) * t_max, np.finfo(float).tiny)
    problems, advice = [], []
    if end > K_END_TOL:
        problems.append(f"K has not decayed by t = {t_max:.3g} s ({end:.2g} of its peak)")
        advice.append("use a longer time grid or truncate with cut-and-subtract")
    if i == j and abs_integral > K_INTEGRAL_TOL:
        problems.append(f"∫K dt = {integral:.3g} is not close to B(0) = 0")
        advice.append("low-frequency data are missing or inconsistent")
    if tail > TAIL_TOL:
        problems.append(f"{tail:.0%} of ∫B dω lies in the extrapolated tail")
        advice.append("K(0) rests on the tail model: extend the frequency range")
    if spread / scale > A_INF_TOL:
        problems.append(f"the A∞ estimates vary by ±{spread / scale:.1%} over frequency")
        advice.append("A(ω) and B(ω) are not a consistent pair at some frequencies")
    if np.isfinite(row) and abs(est - row) / scale > A_INF_TOL:
        problems.append(
            f"the ω = ∞ row differs from the Ogilvie estimate by {abs(est - row) / scale:.1%}"
        )
        advice.append("check the solver's infinite-frequency computation")
    if kk > KK_TOL:
        problems.append(f"Kramers–Kronig error {kk:.1%}")
        advice.append(
            "A(ω) and B(ω) are not causal as given (irregular frequencies, "
            "truncated or strip-theory speed terms)"
        )
    row_text = f", data row {row:.4g}" if np.isfinite(row) else ""
    message = (
        f"K(0) = {k0:.4g}, K(t_max)/max|K| = {end:.2g}, tail {tail:.0%} of ∫B; "
        f"A∞ estimate {est:.4g} ± {spread:.2g}{row_text}; KK error {kk:.1%}"
    )
    if problems:
        message += " — " + "; ".join(problems)
    return Finding(
        "retardation",
        "warning" if problems else "ok",
        message,
        where=pair,
        value=kk,
        advice="; ".join(dict.fromkeys(advice)) or None,
        details={
            "K0": k0,
            "k_integral": integral,
            "k_end_ratio": end,
            "tail_fraction": tail,
            "added_mass_inf_estimate": est,
            "added_mass_inf_spread": spread,
            "added_mass_inf_data": row if np.isfinite(row) else None,
            "kramers_kronig_error": kk,
            "t_max": t_max,
        },
    )


def _constant_ratio(x: np.ndarray, y: np.ndarray) -> float | None:
    """x / y if it is the same number (to 1e-6) at 3 or more points where both are non-zero."""
    both = (x != 0) & (y != 0)
    if both.sum() < 3 or np.any((x == 0) != (y == 0)):
        return None
    ratio = x[both] / y[both]
    if np.ptp(ratio) <= 1e-6 * abs(np.mean(ratio)):
        return float(np.mean(ratio))
    return None


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


def _check_physical(ds: xr.Dataset) -> list[Finding]:
    """What no floating body can have: non-finite coordinates or positions, a negative
    mass, masses, inertias, added masses or dampings beyond any floating body
    (:func:`cummins.validation.coefficient_limit`: 10¹² kg, 10¹⁸ kg·m²)."""
    out: list[Finding] = []
    for name, coord in ds.coords.items():
        if not np.issubdtype(coord.dtype, np.number):
            continue
        values = np.asarray(coord.values, dtype=complex if coord.dtype.kind == "c" else float)
        bad = ~np.isfinite(values)
        if bad.any():
            out.append(
                Finding(
                    "physical",
                    "error",
                    f"the coordinate {name} holds {int(bad.sum())} non-finite value(s) "
                    f"(position {int(np.argwhere(bad.reshape(-1))[0][0])})",
                    where=str(name),
                    advice="the file is damaged: every frequency, direction and speed must "
                    "be a finite number",
                )
            )
    for key in ("reference_point", "center_of_gravity", "center_of_buoyancy"):
        if key in ds.attrs:
            try:
                values = np.asarray(ds.attrs[key], dtype=float).reshape(-1)
            except (TypeError, ValueError):
                values = np.array([np.nan])
            if not np.all(np.isfinite(values)):
                out.append(
                    Finding(
                        "physical",
                        "error",
                        f"the {key.replace('_', ' ')} is not a finite position: "
                        f"{values.tolist()} m",
                        where=key,
                        advice="give the position in metres (the file is damaged)",
                    )
                )
    labels = _labels(ds)
    if "inertia_matrix" in ds:
        m = dof_matrix(ds, "inertia_matrix")
        m = m.reshape(-1, m.shape[-2], m.shape[-1])[0]
        for k, label in enumerate(labels):
            name = split_dof(label)[1]
            if name in ("Surge", "Sway", "Heave") and m[k, k] < 0:
                out.append(
                    Finding(
                        "physical",
                        "error",
                        f"the mass in {label} is negative ({m[k, k]:.4g} kg)",
                        where=label,
                        value=float(m[k, k]),
                        advice="give the body's mass (cummins.with_inertia(...) / --mass)",
                    )
                )
    for var, kind, what in (
        ("inertia_matrix", "mass", "inertia"),
        ("added_mass", "mass", "added mass"),
        ("added_mass_inf", "mass", "added mass A∞"),
        ("added_mass_zero", "mass", "added mass A(0)"),
        ("radiation_damping", "damping", "damping"),
    ):
        if var not in ds:
            continue
        values = ds[var].transpose(..., "influenced_dof", "radiating_dof").values
        peak = np.max(np.abs(values.reshape(-1, len(labels), len(labels))), axis=0)
        for i, row in enumerate(labels):
            for j, col in enumerate(labels):
                if j < i:
                    continue
                limit = coefficient_limit(row, col, kind)
                if peak[i, j] > limit or (j != i and peak[j, i] > limit):
                    size = max(peak[i, j], peak[j, i])
                    pair = row if i == j else f"{row}-{col}"
                    out.append(
                        Finding(
                            "physical",
                            "error",
                            f"the {what} [{pair}] reaches {size:.4g} in SI units, beyond any "
                            f"floating body (at most {limit:.0e})",
                            where=pair,
                            value=float(size),
                            advice="the file is damaged or not in SI units (a WAMIT file "
                            "read with the wrong --ulen/--rho?): check it, or rerun the solver",
                        )
                    )
    if not out:
        out.append(
            Finding(
                "physical",
                "ok",
                "coordinates finite; masses, inertias, added masses and dampings within the "
                "range of floating bodies",
            )
        )
    return out


def _check_read_warnings(ds: xr.Dataset) -> list[Finding]:
    """Damage the reader worked around (``read_warnings``), repeated as warnings."""
    lines = [w for w in str(ds.attrs.get("read_warnings", "")).splitlines() if w.strip()]
    return [
        Finding(
            "read_damage",
            "warning",
            line,
            advice="the data were read without the damaged part: check the file, or "
            "re-run the solver",
        )
        for line in lines
    ]


def check(ds: xr.Dataset) -> CheckReport:
    """Run all diagnostics on a ``HydroDB``.

    Parameters
    ----------
    ds
        A canonical dataset (as returned by :func:`cummins.read`).

    Returns
    -------
    CheckReport
        Findings with severities ``ok``/``info``/``warning``/``error``; ``report.ok`` is
        False when the data cannot be used as they are. ``report.to_text()`` and
        ``report.to_json()`` format it.

    Examples
    --------
    >>> import cummins
    >>> report = cummins.check(cummins.demo_dataset())
    >>> [f.where for f in report.by_check("damping_positive") if f.severity == "warning"][:2]
    ['Heave', 'Roll']
    """
    validate(ds)
    source = ds.attrs.get("source_file") or ds.attrs.get("source_format", "dataset")
    findings: list[Finding] = [Finding("finite", "ok", "no NaN or Inf values")]
    physical = _check_physical(ds)
    findings.extend(physical)
    if any(f.severity == "error" for f in physical):
        # values no floating body has: the numerical checks would only repeat them in
        # overflows and failed eigenvalue problems
        findings.extend(_check_read_warnings(ds))
        return CheckReport(source=str(source), findings=tuple(findings))
    for part in (
        _check_read_warnings,
        _check_grid,
        _check_symmetry,
        _check_damping,
        _check_added_mass_inf,
        _check_decay,
        _check_rigid_body,
        copied_dofs,
        _check_suspect_frequencies,
        _check_retardation,
        _check_wave_parity,
    ):
        findings.extend(part(ds))
    return CheckReport(source=str(source), findings=tuple(findings))
