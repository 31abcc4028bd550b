"""The ``physical`` check: what no floating body has (errors).

Non-finite coordinates or positions, a negative mass, masses, inertias, added masses,
dampings or wave excitations beyond any floating body (10¹² kg, 10¹⁸ kg·m²,
:func:`cummins.validation.coefficient_limit`), frequencies beyond any water wave
(:data:`cummins.validation.MAX_FREQUENCY`). When it finds an error,
:func:`cummins.check.check` skips the numerical checks.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.check.common import _labels
from cummins.check.report import Finding
from cummins.hydrodb import dof_matrix, split_dof
from cummins.validation import MAX_FREQUENCY, coefficient_limit


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
    w = np.asarray(ds.omega.values, dtype=float)
    if w.size and np.all(np.isfinite(w)) and w.max() > MAX_FREQUENCY:
        out.append(
            Finding(
                "physical",
                "error",
                f"the frequencies reach {w.max():.4g} rad/s (a period of {2 * np.pi / w.max():.3g} "
                f"s), beyond any water wave (at most {MAX_FREQUENCY:.0e} rad/s)",
                where="omega",
                value=float(w.max()),
                advice="the file is damaged or its first column is not what it says (periods "
                "in ms? a scaled column): check it, or rerun the solver",
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
        ("excitation_force", "excitation", "wave excitation per metre of amplitude"),
    ):
        if var not in ds:
            continue
        if var == "excitation_force":  # a vector per DOF: its largest |X_i| on the diagonal
            values = np.abs(ds[var].transpose(..., "influenced_dof").values)
            peak = np.diag(values.reshape(-1, len(labels)).max(axis=0))
        else:
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
