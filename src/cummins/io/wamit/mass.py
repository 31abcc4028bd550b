"""Mass properties of a WAMIT run (→ ``inertia_matrix``, about the body origin, body
axes), its external matrices, and the body points in global coordinates.

* ``.frc`` alternative form 2: the IMASS matrix as given (n×n, dimensional), with IDAMP
  and ISTIF as ``additional_damping`` and ``additional_stiffness``;
* ``.frc`` alternative form 1, or the ``.out`` header, which prints what WAMIT used:
  mass m = ρ∇ (a freely floating body; ∇ the mean of VOLX, VOLY, VOLZ, as WAMIT's
  ``.mmx`` shows), centre of gravity (x_g, y_g from the centre of buoyancy, z_g = VCG),
  and the radii of gyration r_ij about the body-origin axes: I_ij = m r_ij |r_ij|
  (WAMIT User Manual v7, §4.3 and §3.4). Radii of gyration all zero are WAMIT's
  placeholder (no rotational inertia given): no inertia matrix is built from them;
* else the ``.mmx`` normalized mass matrix × ρ.

The reference point, CG and CB are recorded in global coordinates (origin on the mean
free surface).
"""

from __future__ import annotations

import numpy as np

from cummins.io._common import (
    warn_damage,
)
from cummins.io.wamit.frc import _ForceControl
from cummins.io.wamit.out_header import _OutBody, _OutHeader
from cummins.io.wamit.settings import RunSettings
from cummins.kinematics import skew
from cummins.restoring import SOURCE, weight_record


def _rigid_inertia(mass: float, cg: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """6×6 inertia about the body origin: I_ij = m r_ij |r_ij| (WAMIT v7 §4.3)."""
    s = skew(np.asarray(cg, dtype=float))
    out = np.zeros((6, 6))
    out[:3, :3] = mass * np.eye(3)
    out[:3, 3:] = -mass * s
    out[3:, :3] = mass * s
    out[3:, 3:] = mass * radii * np.abs(radii)
    return out


def _inertia_from_mass_properties(
    modes: list[int],
    rho: float,
    bodies: list[_OutBody],
    frc: _ForceControl | None,
    frc_name: str,
    out_name: str,
    history: list[str],
) -> np.ndarray | None:
    """Block-diagonal inertia from m = ρ∇, CG and radii of gyration of each body."""
    blocks = []
    for k, m_k in enumerate(modes):
        label = f"body {k + 1}: " if len(modes) > 1 else ""
        body = bodies[k] if k < len(bodies) else None
        volume = None if body is None or body.volumes is None else float(np.mean(body.volumes))
        radii, cg, source = None, None, None
        if body is not None and body.radii_of_gyration is not None:
            radii, cg, source = body.radii_of_gyration, body.center_of_gravity, out_name
        elif frc is not None and frc.form == 1 and k < len(frc.radii_of_gyration):
            radii, source = frc.radii_of_gyration[k], frc_name
            cb = body.center_of_buoyancy if body is not None else None
            cg = None if cb is None else np.array([cb[0], cb[1], frc.vcg[k]])
        if radii is None:
            return None
        if not np.any(radii):
            history.append(
                f"no inertia matrix: {label}{source} gives radii of gyration all zero "
                "(WAMIT's placeholder when the rotational inertia is not given); give the "
                "radii (cummins.with_inertia(ds, radii_of_gyration=...), or "
                "--radii-of-gyration RXX RYY RZZ; the mass defaults to rho*volume) or the "
                "whole matrix (--inertia-matrix FILE)"
            )
            return None
        if volume is None or cg is None:
            history.append(
                f"no inertia matrix: {label}radii of gyration in {source}, but the .out gives "
                "no volume or centre of gravity"
            )
            return None
        if m_k > 6:
            history.append(
                f"no inertia matrix: {label}radii of gyration give the rigid-body inertia, but "
                f"not the mass of its {m_k - 6} generalized modes (.frc form 2 needed)"
            )
            return None
        mass = rho * volume
        blocks.append(_rigid_inertia(mass, cg, radii))
        history.append(
            f"inertia matrix {label}from {source}: m = rho * V = {mass:.6g} kg (freely floating; "
            f"V = {volume:.6g} m^3, the mean of VOLX, VOLY, VOLZ in {out_name}), CG "
            f"{np.round(cg, 6).tolist()} m, radii of gyration about the body-origin axes"
        )
    n = sum(modes)
    out = np.zeros((n, n))
    offset = 0
    for block in blocks:
        out[offset : offset + 6, offset : offset + 6] = block
        offset += 6
    return out


def _mass_matrices(
    extra,
    layout,
    rho_v,
    header,
    frc,
    frc_path,
    mmx,
    mmx_path,
    out_path,
    settings,
    history,
    notes,
    n_omega,
) -> None:
    """Inertia and external matrices into ``extra``, from the best source the run has."""
    n = sum(layout)
    frc_name = frc_path.name if frc_path is not None else ".frc"
    out_name = out_path.name if out_path is not None else ".out"
    inertia = None
    if frc is not None and frc.form == 2:
        if mmx.external is not None and mmx.external[0].shape == (n, n):
            for name, a, b in zip(
                ("IMASS", "IDAMP", "ISTIF"),
                (frc.mass, frc.damping, frc.stiffness),
                mmx.external,
                strict=True,
            ):
                a = np.zeros((n, n)) if a is None else a
                if not np.allclose(a, b, rtol=1e-5, atol=1e-6 * (np.abs(b).max() + 1e-30)):
                    k = np.unravel_index(np.argmax(np.abs(a - b)), a.shape)
                    warn_damage(
                        f"{name}({k[0] + 1},{k[1] + 1}) = {a[k]:g} but {mmx_path.name}, WAMIT's "
                        f"echo of it, says {b[k]:g}: the .frc is not the run's (or damaged); "
                        "its matrices are not used",
                        path=frc_path,
                        notes=notes,
                    )
                    frc = None
                    break
        if frc is not None and frc.mass is not None:
            inertia = frc.mass
            history.append(f"inertia matrix from {frc_name} (IMASS, alternative form 2, as given)")
        if frc is not None and frc.damping is not None and np.any(frc.damping):
            extra["additional_damping"] = np.broadcast_to(frc.damping, (n_omega, n, n))
            history.append(f"external damping from {frc_name} (IDAMP) as additional_damping")
        if frc is not None and frc.stiffness is not None and np.any(frc.stiffness):
            extra["additional_stiffness"] = frc.stiffness
            history.append(f"external stiffness from {frc_name} (ISTIF) as additional_stiffness")
    elif settings.inertia_matrix is not None:
        inertia = settings.inertia_matrix
    else:
        inertia = _inertia_from_mass_properties(
            layout, rho_v, header.bodies, frc, frc_name, out_name, history
        )
        if (
            inertia is None
            and not header.bodies
            and mmx.normalized_mass is not None
            and mmx.normalized_mass.shape == (n, n)
        ):
            inertia = rho_v * mmx.normalized_mass
            history.append(
                f"inertia matrix from {mmx_path.name} (WAMIT's normalized mass matrix × rho)"
            )
    if inertia is not None:
        if inertia.shape != (n, n):
            warn_damage(
                f"the mass matrix is {inertia.shape[0]}×{inertia.shape[1]}, the data {n}×{n}: "
                "not used",
                path=frc_path,
                notes=notes,
            )
        elif np.any(inertia):
            extra["inertia_matrix"] = inertia
    for name in ("additional_damping", "additional_stiffness"):
        value = getattr(settings, name)
        if value is not None and np.any(value) and name not in extra:
            extra[name] = (
                np.broadcast_to(value, (n_omega, n, n)) if name == "additional_damping" else value
            )


def _body_attrs(header: _OutHeader, layout: list[int], settings: RunSettings) -> dict:
    """Reference point, CG, CB in global coordinates (origin on the free surface)."""
    nb = len(layout)
    origin = np.zeros((nb, 3))
    if settings.reference_point is not None:
        origin[:] = np.asarray(settings.reference_point, dtype=float).reshape(-1, 3)[:nb]
    for k, body in enumerate(header.bodies[:nb]):
        origin[k] = body.origin
    attrs: dict = {"reference_point": origin.reshape(-1) if nb > 1 else origin[0]}
    bodies = header.bodies[:nb]
    if len(bodies) == nb:
        cg = [b.center_of_gravity for b in bodies]
        if all(c is not None for c in cg):
            attrs["center_of_gravity"] = (np.vstack(cg) + origin).reshape(-1)
        cb = [b.center_of_buoyancy for b in bodies]
        if all(c is not None for c in cb):
            attrs["center_of_buoyancy"] = (np.vstack(cb) + origin).reshape(-1)
        if all(b.volumes is not None for b in bodies):  # VOLX, VOLY, VOLZ: their mean
            volumes = np.array([float(np.mean(b.volumes)) for b in bodies])
            attrs["displaced_volume"] = float(volumes[0]) if nb == 1 else volumes
    return attrs


def _restoring_weight(name, header: _OutHeader, layout, frc, rho, settings, out_path) -> dict:
    """What WAMIT's restoring holds (:mod:`cummins.restoring`): its "hydrostatic and
    gravitational restoring" adds the weight of m = ρ∇ at the centre of gravity of the
    run's input (WAMIT (2020) §3.1: C₄₄ = ρg(∫y²dS + ∇z_B) − m g z_G, C₄₆ = −ρg∇x_B +
    m g x_G …), which the ``.out`` prints; without the ``.out``, the ``.frc``'s XCG (form 2)
    or VCG (form 1) with the body's own mass. Without either (OpenFAST's files, another
    program's typed matrix) nothing is recorded."""
    nb = len(layout)
    program = "WAMIT" if settings.source_format == "wamit" else settings.source_format.upper()
    bodies = header.bodies[:nb]
    origin = np.zeros((nb, 3))
    for k, body in enumerate(bodies):
        origin[k] = body.origin
    if len(bodies) == nb and all(
        b.center_of_gravity is not None and b.volumes is not None for b in bodies
    ):
        masses = [rho * float(np.mean(b.volumes)) for b in bodies]
        centers = np.vstack([b.center_of_gravity for b in bodies]) + origin
        return weight_record(
            masses,
            centers,
            f"{name} ({program}'s hydrostatic and gravitational restoring: m = rho V at the "
            f"centre of gravity {out_path.name} prints)",
        )
    if frc is not None and frc.form == 2 and frc.center_of_gravity is not None and nb == 1:
        return weight_record(
            [np.nan],
            frc.center_of_gravity,
            f"{name} ({program}'s hydrostatic and gravitational restoring: m = rho V at the "
            ".frc's XCG)",
        )
    if frc is not None and frc.form == 1 and len(frc.vcg) == nb:
        centers = np.column_stack([np.zeros(nb), np.zeros(nb), frc.vcg])
        return weight_record(
            [np.nan] * nb,
            centers,
            f"{name} ({program}'s hydrostatic and gravitational restoring: m = rho V at the "
            ".frc's VCG; no .out, x_G and y_G taken at the origin)",
        )
    if settings.source_format == "hams":
        return {SOURCE: f"{name} (the restoring matrix typed in HAMS's Hydrostatic.in)"}
    return {
        SOURCE: f"{name} (no .out or .frc says which centre of gravity {program} used; "
        "OpenFAST's files hold the hydrostatics alone)"
    }
