"""Assembling a NEMOH run's dataset (:func:`read_nemoh`) from its result files, the
``Nemoh.cal`` and the companion files (the modules of :mod:`cummins.io.nemoh`)."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES, dof_labels, make_hydrodb
from cummins.io._common import (
    CONSTANT_CHOICES,
    DEPTH_ASSUMED,
    assume,
    resolve_rho_g,
    warn_damage,
)
from cummins.io._text import TextFile
from cummins.io.nemoh.cal import _body_point, _mode_name, _NemohCal, _read_cal
from cummins.io.nemoh.files import (
    _FORCE_FILES,
    _IRF_FILE,
    RADIATION_FILE,
    _find,
    _locate,
    _Run,
    _subfolder,
)
from cummins.io.nemoh.hydrostatics import _BodyInfo, _hydrostatics
from cummins.io.nemoh.qtf import nemoh_second_order
from cummins.io.nemoh.tecplot import (
    _Forces,
    _frequencies,
    _irf_added_mass,
    _read_forces,
    _read_tecplot,
)
from cummins.qtf.data import with_second_order

__all__ = ["read_nemoh"]

# --------------------------------------------------------------------------- reader


def _labels(
    text: TextFile | None, cal: _NemohCal | None, n_dofs: int, n_forces: int, notes: list[str]
):
    """Radiating and influenced DOF labels, the reference point(s) and the mesh names.

    Labels are positional (``body1__Surge`` … for several bodies, as every reader of
    cummins writes them); the mesh names go to the ``body_names`` attribute.
    """
    if cal is None or text is None:
        if n_dofs % 6 or n_forces != n_dofs:
            raise HydroDataError(
                f"{n_dofs} DOFs and {n_forces} forces without Nemoh.cal",
                hint="put the run's Nemoh.cal next to the results folder",
            )
        nb = n_dofs // 6
        labels = dof_labels(nb if nb > 1 else None)
        return labels, labels, np.zeros((nb, 3)), []
    nb = len(cal.bodies)
    radiating: list[str] = []
    influenced: list[str] = []
    points = []
    for k, body in enumerate(cal.bodies):
        prefix = f"body{k + 1}__" if nb > 1 else ""
        for modes, out, what in (
            (body.dofs, radiating, "degrees of freedom"),
            (body.forces, influenced, "generalised forces"),
        ):
            local = [_mode_name(text, m, p, len(modes)) for p, m in enumerate(modes)]
            if len(set(local)) != len(local):
                raise text.error(f"body {k + 1} ({body.name}) lists a DOF twice", modes[0].line)
            order = [DOF_NAMES.index(d) for d in local]
            if order != sorted(order):
                warn_damage(
                    f"the {what} of body {k + 1} ({body.name}) are listed as "
                    f"{', '.join(local)}, not in the order Surge…Yaw: read in the order given",
                    path=text.path,
                    line=modes[0].line + 1,
                    notes=notes,
                    hint="NEMOH's own files list them in order; check that Nemoh.cal was "
                    "not edited after the run",
                )
            out.extend(prefix + d for d in local)
        points.append(_body_point(text, body))
    return radiating, influenced, np.vstack(points), [b.name for b in cal.bodies]


def _frequency_note(run: _Run, cal: _NemohCal, omega: np.ndarray, unit: str) -> str:
    """History line when ``Nemoh.cal`` and the results disagree on the frequencies."""
    lo, hi, kind = cal.frequency_range
    cal_unit = {1: "rad/s", 2: "Hz", 3: "s"}.get(kind, "rad/s")
    note = (
        f"Nemoh.cal asks for {cal.n_frequencies} frequencies ({lo:g}-{hi:g} {cal_unit}) but "
        f"{RADIATION_FILE} holds {omega.size} ({omega.min():.4g}-{omega.max():.4g} rad/s): the "
        "results' frequencies are used (they are what the solver computed; Nemoh.cal was "
        "changed after the run"
    )
    index = _find(run.results, "index.dat")
    if index is not None:
        try:
            first = TextFile.read(index).numbers(0)
        except HydroDataError:
            first = None
        if first is not None and first.size and first[0] == omega.size:
            note += f"; {index.name}, which NEMOH's preprocessor wrote for the run, also lists "
            note += f"{omega.size}"
    return note + ")"


def read_nemoh(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
) -> xr.Dataset:
    """Read a NEMOH v2 or v3 run into a canonical ``HydroDB``.

    Parameters
    ----------
    path
        The results folder, the run folder (holding ``Nemoh.cal`` and ``results/``),
        ``Nemoh.cal``, or any of the result files (``RadiationCoefficients.tec``,
        ``ExcitationForce.tec``, ``DiffractionForce.tec``, ``FKForce.tec``, ``IRF.tec``).
    rho, g
        Water density (kg/m³) and gravity (m/s²). NEMOH's output is dimensional: they
        may only confirm the values of ``Nemoh.cal`` (a different value is an error).
        Without ``Nemoh.cal`` they are recorded as given (default 1025 kg/m³, 9.81 m/s²).

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB`` (SI units, exp(+iωt), z-up axes) about the rotation point
        of ``Nemoh.cal``: ``added_mass``, ``radiation_damping``, and when present
        ``excitation_force``, ``diffraction_force``, ``Froude_Krylov_force``,
        ``hydrostatic_stiffness``, ``inertia_matrix`` (``Mechanics/Inertia.dat``),
        ``additional_stiffness`` / ``additional_damping`` (``Mechanics/Km.dat``,
        ``Badd.dat``, when not zero), ``added_mass_inf`` (from a matching ``IRF.tec``).
        Several bodies are labelled ``body1__Surge`` …, the mesh names in the attribute
        ``body_names``.

    Raises
    ------
    HydroDataError
        Missing, damaged or mutually inconsistent files, naming the file and line.
    """
    run = _locate(Path(path))
    history = [f"read NEMOH results from {run.results}"]
    notes: list[str] = []
    cal = _read_cal(run.cal) if run.cal is not None else None
    cal_unit = cal.output_unit if cal is not None else None

    tec = _read_tecplot(run.radiation)
    omega, unit = _frequencies(tec, cal_unit)
    width = tec.zones[0].table.shape[1]
    if any(zone.table.shape[1] != width for zone in tec.zones):
        raise tec.text.error("zones have different numbers of columns")
    n_dofs, n_forces = len(tec.zones), (width - 1) // 2
    if cal is not None:
        history.append(
            f"constants, bodies and DOFs from {run.cal.name} (NEMOH {cal.version} layout)"
        )
        skipped = [f"{b.name} ({b.extra_lines})" for b in cal.bodies if b.extra_lines]
        if skipped:
            history.append(
                f"{run.cal.name}: lines of additional information skipped, as NEMOH does "
                f"(meant for generalised modes, which NEMOH does not compute): {', '.join(skipped)}"
            )
        expected = (sum(len(b.dofs) for b in cal.bodies), sum(len(b.forces) for b in cal.bodies))
        if (n_dofs, n_forces) != expected:
            raise tec.text.error(
                f"{n_dofs} radiation zones of {n_forces} forces, but Nemoh.cal defines "
                f"{expected[0]} DOFs and {expected[1]} forces",
                hint="the results and Nemoh.cal come from different runs",
            )
        if omega.size != cal.n_frequencies:
            history.append(_frequency_note(run, cal, omega, unit))
    else:
        history.append(
            "no Nemoh.cal found: DOFs taken as Surge…Yaw about (0, 0, 0), "
            "water depth unknown (recorded as inf)"
        )
        assume(
            "no Nemoh.cal beside the results: the DOFs are taken as Surge…Yaw about "
            "(0, 0, 0) and the depth as deep water; put the run's Nemoh.cal there (or give "
            f"{', '.join(CONSTANT_CHOICES[k] for k in ('rho', 'g', 'water_depth'))})",
            path=run.radiation,
        )
    if unit != "rad/s":
        history.append(f"frequency column of {run.radiation.name} in {unit}, converted to rad/s")
    qtf = _subfolder(run.results, "qtf")
    if qtf is None and cal is not None and cal.qtf:
        history.append("Nemoh.cal asks for QTFs, but there is no results/QTF folder")
    cal_text = TextFile.read(run.cal) if cal is not None else None
    dofs, force_labels, points, body_names = _labels(cal_text, cal, n_dofs, n_forces, notes)
    missing = [d for d in dofs if d not in force_labels]
    if missing:
        raise HydroDataError(
            f"DOF {missing[0]} has no matching generalised force in Nemoh.cal",
            path=run.cal,
            hint="cummins needs square added-mass matrices",
        )
    pick = np.array([force_labels.index(d) for d in dofs])
    if len(pick) < len(force_labels):
        history.append(
            "forces without a matching DOF dropped: "
            + ", ".join(f for f in force_labels if f not in dofs)
        )

    table = np.stack([zone.table for zone in tec.zones], axis=2)  # (nω, width, DOFs)
    added_mass = table[:, 1::2, :][:, pick, :]
    damping = table[:, 2::2, :][:, pick, :]

    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        cal.rho if cal else None,
        cal.g if cal else None,
        path=run.cal or run.radiation,
        history=history,
        dimensional=True,
    )
    depth = cal.depth if cal is not None else np.inf

    extra: dict = {}
    forces = {kind: _find(run.results, name) for kind, name in _FORCE_FILES.items()}
    read = {kind: _read_forces(p, cal_unit) for kind, p in forces.items() if p is not None}
    if read:
        extra.update(_force_arrays(read, omega, pick, n_forces, cal, history))
        history.append(
            "NEMOH's exp(-iwt) complex amplitudes conjugated to exp(+iwt) (F = |F| exp(-i phase))"
        )

    irf = _find(run.results, _IRF_FILE)
    if irf is not None:
        try:
            a_inf, note = _irf_added_mass(irf, omega, table[:, 2::2, :], n_dofs, n_forces)
        except HydroDataError as exc:  # optional file: the rest of the run is still good
            a_inf, note = None, f"{irf.name} not used, so no added_mass_inf: unreadable ({exc})"
        history.append(note)
        if a_inf is None:
            warn_damage(note, path=irf, notes=notes)
        else:
            extra["added_mass_inf"] = a_inf[pick, :]

    bodies = _BodyInfo(dofs, points, body_names)
    extra.update(_hydrostatics(run, bodies, omega, extra, (rho_v, g_v, depth), history, notes))
    n_bodies = points.shape[0]
    reference = points.reshape(-1) if n_bodies > 1 else points[0]
    second = nemoh_second_order(
        run.results, qtf, dofs=list(dofs), pick=pick, rho=rho_v, g=g_v, notes=notes
    )
    ds = make_hydrodb(
        omega,
        added_mass,
        damping,
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format="nemoh",
        source_file=str(run.radiation),
        dofs=dofs,
        reference_point=reference,
        history=history,
        read_warnings=notes,
        nemoh_version=cal.version if cal is not None else None,
        **{DEPTH_ASSUMED: 1 if cal is None else None},
        body_name=body_names[0] if len(body_names) == 1 else None,
        body_names="\n".join(body_names) if n_bodies > 1 and body_names else None,
        **extra,
    )
    if not second["tables"]:
        return ds
    return with_second_order(ds, second["tables"], history=second["history"], attrs=second["attrs"])


def _force_arrays(read: dict[str, _Forces], omega, pick, n_forces, cal, history) -> dict:
    """Excitation, diffraction and Froude-Krylov arrays, checked against each other."""
    out: dict = {}
    reference = next(iter(read.values()))
    for kind, forces in read.items():
        name = forces.path.name
        if forces.values.shape[2] != n_forces:
            raise HydroDataError(
                f"{forces.values.shape[2]} forces per row, {RADIATION_FILE} has {n_forces}",
                path=forces.path,
            )
        if forces.omega.shape != omega.shape or not np.allclose(forces.omega, omega, rtol=1e-5):
            raise HydroDataError(
                f"other frequencies than {RADIATION_FILE}",
                path=forces.path,
                hint="the files come from different runs",
            )
        if forces.beta_deg.shape != reference.beta_deg.shape or not np.allclose(
            forces.beta_deg, reference.beta_deg, atol=1e-6
        ):
            raise HydroDataError(
                f"other wave directions than {reference.path.name}", path=forces.path
            )
        history.append(
            f"{kind.replace('_', '-')} force from {name} (phases in "
            f"{'degrees' if forces.degrees else 'radians'})"
        )
        out[kind] = forces.values[:, :, pick]
    if cal is not None and reference.beta_deg.size != cal.n_directions:
        history.append(
            f"Nemoh.cal asks for {cal.n_directions} wave directions, {reference.path.name} "
            f"holds {reference.beta_deg.size}: the results' directions are used"
        )
    result = {"wave_direction": np.radians(reference.beta_deg)}
    if "excitation" in out:
        result["excitation_force"] = out["excitation"]
    elif "diffraction" in out and "froude_krylov" in out:
        result["excitation_force"] = out["diffraction"] + out["froude_krylov"]
        history.append("excitation force = diffraction + Froude-Krylov")
    if "diffraction" in out:
        result["diffraction_force"] = out["diffraction"]
    if "froude_krylov" in out:
        result["froude_krylov_force"] = out["froude_krylov"]
    return result
