"""The checks of the wave forces: ``wave_parity`` — those of a port/starboard symmetric
body mirror with the heading, F(ω, −β) = T F(ω, β), T = diag(1, −1, 1, −1, 1, −1);
``long_wave_limit`` — the heave excitation of long waves is the restoring, C33.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.check.common import PARITY_TOL, _speed_suffix, _speeds
from cummins.check.parity import break_pattern, degree_ranges, mirror_pairs, parity_mismatch
from cummins.check.report import Finding
from cummins.hydrodb import DOF_NAMES, bodies, dof_matrix, split_dof


def _check_wave_parity(ds: xr.Dataset) -> list[Finding]:
    """Wave forces of a port/starboard symmetric body mirror with the heading:
    F(ω, −β) = T F(ω, β), T = diag(1, −1, 1, −1, 1, −1) (surge, heave, pitch keep their
    sign; sway, roll, yaw change it). A file that breaks this for a symmetric body holds
    magnitudes instead of signed values, or a sign error (the MSS S-175's yaw drift), or
    one half-plane copied in the wrong order (the MSS tanker's drift): the finding names
    the headings, the pattern (:func:`cummins.check.parity.break_pattern`) and whether the
    first-order tables of the same headings mirror."""
    from cummins.seakeeping.excitation import symmetry_evidence

    out: list[Finding] = []
    for sub in _speeds(ds):
        names = [v for v in ("excitation_force", "drift_force") if v in sub]
        if not names or "wave_direction" not in sub.dims:
            continue
        symmetric, _ = symmetry_evidence(sub)
        beta = sub.wave_direction.values
        pairs = mirror_pairs(beta)
        if not symmetric or not any(k != m for k, m in pairs):
            continue
        labels = [str(d) for d in sub.influenced_dof.values]
        signs = np.array([_mirror_sign(x) for x in labels])
        first = [  # the first-order tables' worst mismatch, to place the drift's
            float(parity_mismatch(_table(sub, v), pairs, signs).max())
            for v in ("excitation_force", "rao")
            if v in sub and _table(sub, v).shape[2] == len(labels)
        ]
        for name in names:
            f = _table(sub, name)
            mismatch = parity_mismatch(f, pairs, signs)
            for i, label in enumerate(labels):
                if mismatch[:, i].max() <= PARITY_TOL:
                    continue
                context = {
                    "first_order": max(first) if name == "drift_force" and first else None,
                    "sway": _sway_of(f, labels, label),
                }
                out.append(
                    _parity_finding(sub, name, label, f[:, :, i], pairs, mismatch[:, i], context)
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


def drift_mirror_note(ds: xr.Dataset) -> str | None:
    """One line on a mean drift that breaks the port/starboard mirror where the first-order
    tables of the same headings keep it (the ``wave_parity`` warnings of the drift, MSS's
    own structs'), or None: the drift loads warn with it, as they use the data as given."""
    found = _drift_alone_breaks(ds)
    if not found:
        return None
    dofs = ", ".join(dict.fromkeys(str(f.where) for f in found))
    headings = sorted({h for f in found for h in f.details.get("headings_deg", [])})
    at = f" at {degree_ranges(headings)}" if headings else ""
    explained = next((f.advice for f in found if f.details.get("pattern")), None)
    return f"drift_force of {dofs} is not the port/starboard mirror image{at} although the " + (
        f"first-order excitation is; {explained}"
        if explained
        else "first-order excitation is: used as given (cummins check, wave_parity, says how)"
    )


def mss_drift_fill(ds: xr.Dataset) -> list[Finding]:
    """The ``wave_parity`` warnings of an MSS struct's drift whose break is one of MSS's
    fills of 190–350° (:data:`MSS_FILL`) where the first-order tables mirror: what
    :func:`cummins.io.mss.reader.mirrored_mss_drift` mends."""
    if ds.attrs.get("source_format") != "mss" or "drift_force" not in ds:
        return []
    return [
        f
        for f in _drift_alone_breaks(ds)
        if f.details.get("pattern") in MSS_FILL and f.details.get("headings_deg")
    ]


def _drift_alone_breaks(ds: xr.Dataset) -> list[Finding]:
    """The ``wave_parity`` warnings of a table that breaks the mirror where the first-order
    tables of the same headings keep it (only the drift's carry ``first_order_mismatch``)."""
    return [
        f
        for f in _check_wave_parity(ds)
        if f.severity == "warning" and (f.details or {}).get("first_order_mismatch") is not None
    ]


def _mirror_sign(label: str) -> float:
    """T_ii of a DOF label (1 for a mode that is not a rigid-body DOF)."""
    from cummins.seakeeping.excitation import MIRROR_SIGNS

    dof = split_dof(label)[1]
    return float(MIRROR_SIGNS[DOF_NAMES.index(dof)]) if dof in DOF_NAMES else 1.0


def _table(ds: xr.Dataset, name: str) -> np.ndarray:
    """``name`` as (omega, wave_direction, dof)."""
    dof = "influenced_dof" if "influenced_dof" in ds[name].dims else "radiating_dof"
    return ds[name].transpose("omega", "wave_direction", dof).values


def _sway_of(f: np.ndarray, labels: list[str], label: str) -> np.ndarray | None:
    """The sway column of the body of a yaw ``label``, for the moved-moment pattern."""
    body, dof = split_dof(label)
    if dof != "Yaw":
        return None
    for j, other in enumerate(labels):
        if split_dof(other) == (body, "Sway"):
            return f[:, :, j]
    return None


def _parity_finding(
    sub: xr.Dataset,
    name: str,
    label: str,
    values: np.ndarray,
    pairs: list[tuple[int, int]],
    mismatch: np.ndarray,
    context: dict,
) -> Finding:
    """The ``wave_parity`` warning of one DOF of one table: where, how much, the pattern."""
    beta = sub.wave_direction.values
    degrees = np.round(np.degrees(np.mod(beta, 2 * np.pi)), 6)
    sign = _mirror_sign(label)
    worst = int(np.argmax(mismatch))
    k, m = pairs[worst]
    value = float(mismatch[worst])
    broken = [pair for pair, x in zip(pairs, mismatch, strict=True) if x > PARITY_TOL]
    apart = [(a, b) for a, b in broken if a != b]
    if k == m:  # a heading its own mirror (0°, 180°): there it must vanish
        where_text = f"at {degrees[k]:g}°, its own mirror heading, it should be 0 but is"
    else:
        where_text = (
            f"at {degrees[k]:g}° and {degrees[m]:g}° it differs from "
            f"{'the same' if sign > 0 else 'the opposite'} value by"
        )
    text = (
        f"{name} of {label}{_speed_suffix(sub)} does not mirror with the heading although "
        f"the body is port/starboard symmetric: {where_text} {value:.0%} of its largest value"
    )
    details: dict = {"worst_pair_deg": [float(degrees[k]), float(degrees[m])]}
    upper = [float(degrees[b]) for _, b in apart]
    lower = [float(degrees[a]) for a, _ in apart]
    if apart:
        text += (
            f"; the headings {degree_ranges(upper)} are not the mirror images of "
            f"{degree_ranges(lower)}"
        )
        details.update(headings_deg=upper, mirrors_deg=lower)
    x_ref = float(np.asarray(sub.attrs.get("reference_point", np.zeros(3)), float).ravel()[0])
    pattern, x_point = break_pattern(
        values, beta, apart, sign, sway=context["sway"], x_reference=x_ref
    )
    details["pattern"] = pattern
    if pattern == "shifted":
        text += (
            f": they hold the values of {degree_ranges(lower)} in the same order (β + 180°)"
            + (", the sign changed," if sign < 0 else "")
            + " instead of those at 360° − β"
        )
    elif pattern == "sign_kept":
        text += ": they hold the same values with the sign kept where the mirror changes it"
    elif pattern == "sign_kept_about":
        text += (
            f": they hold the mirror with the sign kept about x = {x_point:.4g} m, the data "
            f"being about x = {x_ref:.4g} m"
        )
        details["point_x"] = x_point
    first = context["first_order"]
    if first is not None and first <= PARITY_TOL:
        text += (
            f"; the first-order tables mirror at the same headings (to {first:.1g} of their "
            "largest values): the drift alone breaks the symmetry, not the hull"
        )
        details["first_order_mismatch"] = first
    return Finding(
        "wave_parity",
        "warning",
        text,
        where=label,
        value=value,
        advice=_parity_advice(sub, name, pattern),
        details=details,
    )


#: What MSS does to fill 190–350° from the 0–180° it computes, per pattern of the break.
MSS_FILL = {
    "shifted": "MSS's wamit2vessel.m copies driftfrc's 10–170° to 190–350° in the same "
    "order (its first-order tables it mirrors)",
    "sign_kept": "MSS's read_veres_WD.m mirrors the yaw drift (its third column) with heave's sign",
    "sign_kept_about": "MSS's read_veres_WD.m mirrors the yaw drift (its third column) "
    "with heave's sign, about the VERES motion reference point",
}


def _parity_advice(sub: xr.Dataset, name: str, pattern: str | None) -> str:
    """What to do about a table that does not mirror: MSS's fill named when recognised."""
    if sub.attrs.get("source_format") == "mss" and name == "drift_force" and pattern:
        return (
            f"{MSS_FILL[pattern]}; cummins.read mirrors the solver's 0–180° there by "
            "default, these values were kept (read(..., drift_as_stored=True); "
            "docs/guide/mss.md)"
        )
    return (
        "the file may hold magnitudes instead of signed values, or a sign error: check the "
        "source (cummins uses the values as given; drift and excitation at mirrored headings "
        "will differ)"
    )


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
