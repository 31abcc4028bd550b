"""Checks of the rigid body: ``inertia`` (M_RB symmetric positive definite, and that of a
rigid body: its coupling block −m S(r_g) skew-symmetric) and ``hydrostatics``
(C33, C44, C55 > 0).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.check.common import _diag_scale, _labels
from cummins.check.report import Finding
from cummins.hydrodb import DOF_NAMES, dof_matrix, split_dof
from cummins.kinematics import center_of_gravity_from_inertia
from cummins.restoring import describe_restoring, recorded_weight, weight_stiffness


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
        zero = _round_off(ds, c)
        for k, label in enumerate(labels):
            name = label.rpartition("__")[2]
            if name in ("Heave", "Roll", "Pitch"):
                if c[k, k] < -zero:
                    out.append(
                        Finding(
                            "hydrostatics",
                            "warning",
                            f"C_{label} = {c[k, k]:.4g} is negative: the body is statically "
                            "unstable in this DOF",
                            where=label,
                            value=float(c[k, k]),
                            advice="check the centre of gravity (negative metacentric "
                            f"height?) and what the restoring holds ({describe_restoring(ds)}): "
                            "--center-of-gravity with --radii-of-gyration makes its weight "
                            "terms those of your body; --restoring-includes-weight no when the "
                            "files hold the hydrostatics alone"
                            + (
                                "; a body on a hinge (a wave-energy flap) is held by it: `rao` "
                                "and `simulate` with its --joint add the joint's pre-load "
                                "stiffness (docs/wec.md, Joint pre-load)"
                                if name != "Heave"
                                else ""
                            ),
                        )
                    )
                elif c[k, k] <= zero:
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
        out.extend(_weight_consistency(ds, labels))
    return out


def _round_off(ds: xr.Dataset, c: np.ndarray) -> float:
    """The size below which a restoring term is zero up to the quadrature's round-off
    (a submerged body's C33 = −1e-11 N/m of Capytaine): 1e-9 of the largest term, or of
    ρ g ∇^(4/3) (the scale of a body's ρ g ∇ GM) when the displaced volume is known."""
    scale = float(np.max(np.abs(c))) if c.size else 0.0
    volume = np.asarray(ds.attrs.get("displaced_volume", np.nan), dtype=float)
    if np.isfinite(volume).any():
        rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
        scale = max(scale, rho * g * float(np.nanmax(volume)) ** (4 / 3))
    return 1e-9 * scale


def _weight_consistency(ds: xr.Dataset, labels: list[str]) -> list[Finding]:
    """The weight the restoring holds against the body the inertia matrix describes: a
    difference in m·(G − O) changes C44, C55 (and C46, C56) by −g Δ(m z_G) … (WAMIT (2020)
    §3.1), which the motions feel; said when it is above 1 % of C44 or C55."""
    weights = recorded_weight(ds)
    if weights is None or "inertia_matrix" not in ds:
        return []
    m = dof_matrix(ds, "inertia_matrix")
    m = m.reshape(-1, m.shape[-2], m.shape[-1])[0]
    c = dof_matrix(ds, "hydrostatic_stiffness")
    c = c.reshape(-1, c.shape[-2], c.shape[-1])[0]
    refs = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float).reshape(-1, 3)
    blocks = _rigid_blocks(labels)
    if len(blocks) != len(weights):
        return []
    out = []
    g = float(ds.attrs["g"])
    axes = str(ds.attrs.get("axis_convention", "z-up"))
    for k, (index, held) in enumerate(zip(blocks, weights, strict=True)):
        mass, r_g, inconsistency = center_of_gravity_from_inertia(m[np.ix_(index, index)])
        ref = refs[k] if len(refs) == len(blocks) else refs[0]
        file_mass = mass if np.isnan(held.mass) else held.mass
        delta = weight_stiffness(mass * r_g, g, axes) - weight_stiffness(
            file_mass * (held.center - ref), g, axes
        )
        if inconsistency > 1e-3:  # no single centre of gravity: compare z alone
            delta[:, 5] = delta[5, :] = 0.0
        roll, pitch = index[3], index[4]
        worst = max(
            abs(delta[3, 3]) / max(abs(c[roll, roll]), 1e-300),
            abs(delta[4, 4]) / max(abs(c[pitch, pitch]), 1e-300),
        )
        if worst > 0.01:
            body = labels[index[0]].rpartition("__")[0] or "the body"
            out.append(
                Finding(
                    "hydrostatics",
                    "warning",
                    f"the restoring of {body} holds the weight of {file_mass:.6g} kg at "
                    f"{np.round(held.center, 4).tolist()} m, but the inertia matrix describes "
                    f"{mass:.6g} kg at {np.round(ref + r_g, 4).tolist()} m: C44 and C55 of "
                    f"that body would change by {delta[3, 3]:.4g} and {delta[4, 4]:.4g} "
                    f"({worst:.0%})",
                    where=labels[index[3]],
                    value=worst,
                    advice="give the body's mass properties (--mass, --center-of-gravity, "
                    "--radii-of-gyration; cummins.with_inertia): the restoring's weight terms "
                    "then follow them",
                )
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
