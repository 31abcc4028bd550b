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
