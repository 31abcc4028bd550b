"""The checks of the second-order data (:mod:`cummins.qtf`): the QTFs' symmetries, their
diagonal against the mean drift the run writes, the run's mean-drift methods against each
other, and what the QTF's frequency grid covers and resolves.

* ``qtf_symmetry`` — Q⁻(ω₂, ω₁) = Q⁻(ω₁, ω₂)* (Q⁺(ω₂, ω₁) = Q⁺(ω₁, ω₂)) and a real mean
  drift Q⁻(ω, ω), measured per DOF relative to its largest |Q|;
* ``qtf_mean_drift`` — Re Q⁻(ω, ω, β, β) against every mean-drift estimate of the run
  (``drift_force``, ``drift_force_<method>``) at the QTF's frequencies inside the drift's
  range, per DOF both compute, relative to the drift's peak;
* ``drift_methods`` — the run's mean-drift estimates against each other (pressure
  integration converges slowest with the panels: the corpus sphere's parts from the
  control surface above ~5 rad/s);
* ``drift_suspect`` — the mean drift at the suspect frequencies of the radiation data
  (:func:`cummins.qtf.suspect_drift.drift_at_suspects`): irregular frequencies spoil it
  too (the WAMIT tanker's heave, 3000 times its largest elsewhere);
* ``qtf_grid`` — the seas the QTF's frequencies cover and the slow-drift natural periods
  its spacing resolves (:func:`cummins.seakeeping.slow_drift.qtf_grid_advice`), and a
  mean drift that changes by more than half its peak between two grid frequencies (a
  resonance the grid barely resolves, where interpolation is uncertain).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from cummins.check.common import _speed_suffix, _speeds
from cummins.check.report import Finding
from cummins.qtf.data import DRIFT_ALTERNATIVES, QTF_VARIABLES, qtf_table, significant_dofs
from cummins.qtf.suspect_drift import DRIFT_SUSPECT_RATIO

if TYPE_CHECKING:
    from cummins.repair import Judged

#: |Q(ω₂, ω₁) − Q(ω₁, ω₂)*| (or the imaginary part of the mean drift) over max|Q| of a DOF.
QTF_SYMMETRY_TOL = 0.01
#: |Re Q(ω, ω) − F̄(ω)| over max|F̄| of a DOF.
QTF_DRIFT_TOL = 0.1
#: Two mean-drift estimates of a run: difference over the peak.
DRIFT_METHODS_TOL = 0.1
#: A mean drift that changes by more than this share of its peak between grid points.
QTF_STEP_TOL = 0.5
#: A DOF whose largest value is below this share of the largest of its kind (forces or
#: moments) is numerical noise (sway, roll, yaw in head seas): not judged.
SIGNIFICANT = 0.01


def _significant(peaks: np.ndarray, labels) -> np.ndarray:
    return significant_dofs(peaks, labels, SIGNIFICANT)


def _check_second_order(ds: xr.Dataset, judged: Judged = ()) -> list[Finding]:
    """The second-order findings (``judged``: the data
    :func:`~cummins.repair.suspects_by_dof` has judged already, with what it found)."""
    out: list[Finding] = []
    for kind, name in QTF_VARIABLES.items():
        if name in ds:
            out.extend(_symmetry(ds, kind))
    for sub in _speeds(ds):  # the mean drift may depend on the forward speed
        if QTF_VARIABLES["difference"] in sub:
            out.extend(_against_drift(sub))
        out.extend(_drift_methods(sub))
        out.extend(_drift_at_suspects(sub, judged))
    if QTF_VARIABLES["difference"] in ds:
        out.extend(_grid(ds))
    return out


def _symmetry(ds: xr.Dataset, kind: str) -> list[Finding]:
    table = qtf_table(ds, kind)
    v = table.values
    if table.bidirectional:
        mirror = np.swapaxes(np.swapaxes(v, 0, 1), 2, 3)
    else:
        mirror = np.swapaxes(v, 0, 1)
    if kind == "difference":
        mirror = np.conj(mirror)
    n = table.omega.size
    off = ~np.eye(n, dtype=bool)
    scale = np.abs(v).reshape(-1, v.shape[-1]).max(axis=0)
    worst, where, what = 0.0, None, ""
    for k, label in enumerate(table.dofs):
        if scale[k] == 0:
            continue
        err = np.abs(v[..., k] - mirror[..., k])[off].max() / scale[k]
        if err > worst:
            worst, where, what = float(err), label, "the mirror pairs"
        if kind == "difference":
            diag = np.diagonal(v[..., k], axis1=0, axis2=1)
            if table.bidirectional:
                diag = np.diagonal(diag, axis1=0, axis2=1)
            imag = float(np.abs(diag.imag).max() / scale[k])
            if imag > worst:
                worst, where, what = imag, label, "the imaginary part of the mean drift"
    rule = "Q(w2, w1) = Q(w1, w2)*" if kind == "difference" else "Q(w2, w1) = Q(w1, w2)"
    if worst > QTF_SYMMETRY_TOL:
        return [
            Finding(
                "qtf_symmetry",
                "warning",
                f"the {kind}-frequency QTF breaks {rule}: {what} reach "
                f"{100 * worst:.2g} % of its largest value",
                where=where,
                value=worst,
                advice="the file may be edited, or the triangles come from different runs",
            )
        ]
    return [
        Finding(
            "qtf_symmetry",
            "ok",
            f"the {kind}-frequency QTF keeps {rule} (within {100 * worst:.2g} % of its "
            "largest value, the worst DOF)",
            value=worst,
        )
    ]


def _drift_estimates(ds: xr.Dataset) -> list[str]:
    return [n for n in ("drift_force", *DRIFT_ALTERNATIVES) if n in ds]


def _computed(ds: xr.Dataset, name: str) -> list[str]:
    listed = ds[name].attrs.get("dofs_computed")
    labels = [str(d) for d in ds.influenced_dof.values]
    return [d for d in str(listed).split() if d in labels] if listed else labels


def _against_drift(ds: xr.Dataset) -> list[Finding]:
    table = qtf_table(ds, "difference")
    estimates = _drift_estimates(ds)
    if not estimates:
        return [
            Finding(
                "qtf_mean_drift",
                "info",
                "the run holds a QTF but no separate mean drift to compare its diagonal with",
            )
        ]
    diag = table.diagonal().real  # (n, m, d)
    out = []
    labels = [str(d) for d in ds.influenced_dof.values]
    for name in estimates:
        drift = ds[name].transpose("omega", "wave_direction", "influenced_dof")
        w = ds.omega.values
        # the QTF's grid may be printed to other digits than the drift's (AQWA: 0.0999969
        # against 0.1): a frequency within 1e-4 of the drift's range is compared
        inside = (table.omega >= w[0] * (1 - 1e-4)) & (table.omega <= w[-1] * (1 + 1e-4))
        peaks = np.abs(drift.values).max(axis=(0, 1))
        keep = _significant(peaks, labels)
        worst, where = 0.0, None
        compared = 0
        for a, beta in enumerate(table.directions):
            hit = _same_direction(ds.wave_direction.values, beta)
            if hit is None or not inside.any():
                continue
            for dof in _computed(ds, name):
                k = table.dofs.index(dof)
                peak = peaks[labels.index(dof)]
                if peak == 0 or not keep[labels.index(dof)]:
                    continue
                f = drift.values[:, hit, labels.index(dof)]
                at = np.interp(table.omega[inside], w, f)
                err = np.abs(diag[inside, a, k] - at)
                compared += 1
                if err.max() / peak > worst:
                    i = int(np.argmax(err))
                    worst = float(err.max() / peak)
                    where = f"{dof}, {table.omega[inside][i]:.4g} rad/s"
        if not compared:
            out.append(
                Finding(
                    "qtf_mean_drift",
                    "info",
                    f"the QTF and {name} share no wave direction and frequency to compare",
                )
            )
            continue
        method = ds[name].attrs.get("method", name)
        severity = "warning" if worst > QTF_DRIFT_TOL else "ok"
        out.append(
            Finding(
                "qtf_mean_drift",
                severity,
                f"the QTF's diagonal differs from the mean drift {name} ({method}) by up to "
                f"{100 * worst:.2g} % of its peak",
                where=where,
                value=worst,
                advice=(
                    "a QTF of another run, or a drift of another method than the QTF's: "
                    "compare with the run's estimate of the same method"
                    if severity == "warning"
                    else None
                ),
            )
        )
    return out


def _same_direction(directions: np.ndarray, beta: float) -> int | None:
    """The index of ``beta`` (rad) among ``directions``: the same value (AQWA lists both
    −180° and 180°), else the same angle modulo 2π; None if absent."""
    exact = np.flatnonzero(np.isclose(directions, beta, atol=1e-6))
    if exact.size:
        return int(exact[0])
    wrapped = np.angle(np.exp(1j * (np.asarray(directions) - beta)))
    hit = np.flatnonzero(np.abs(wrapped) < 1e-6)
    return int(hit[0]) if hit.size else None


def _drift_methods(ds: xr.Dataset) -> list[Finding]:
    if "drift_force" not in ds:
        return []
    out = []
    base = ds.drift_force.transpose("omega", "wave_direction", "influenced_dof").values
    w = ds.omega.values
    labels = [str(d) for d in ds.influenced_dof.values]
    for name in DRIFT_ALTERNATIVES:
        if name not in ds:
            continue
        other = ds[name].transpose("omega", "wave_direction", "influenced_dof").values
        peaks = np.abs(base).reshape(-1, base.shape[-1]).max(axis=0)
        keep = _significant(peaks, labels)
        common = [
            d
            for d in _computed(ds, name)
            if d in _computed(ds, "drift_force") and keep[labels.index(d)]
        ]
        worst, where, part = 0.0, None, None
        for dof in common:
            k = labels.index(dof)
            peak = max(np.abs(base[..., k]).max(), np.abs(other[..., k]).max())
            if peak == 0:
                continue
            err = np.abs(base[..., k] - other[..., k]).max(axis=1) / peak
            if err.max() > worst:
                worst = float(err.max())
                where = f"{dof}, {w[int(np.argmax(err))]:.4g} rad/s"
                over = np.flatnonzero(err > DRIFT_METHODS_TOL)
                part = float(w[over[0]]) if over.size else None
        a, b = ds.drift_force.attrs.get("method", "drift_force"), ds[name].attrs.get("method", name)
        if worst > DRIFT_METHODS_TOL:
            out.append(
                Finding(
                    "drift_methods",
                    "warning",
                    f"the mean drift by {b} parts from {a} from {part:.4g} rad/s, by up to "
                    f"{100 * worst:.2g} % of the peak",
                    where=where,
                    value=worst,
                    advice="the panels are too coarse for the shortest waves: trust the "
                    "control surface or momentum conservation there, or refine the mesh",
                )
            )
        else:
            out.append(
                Finding(
                    "drift_methods",
                    "ok",
                    f"the mean drift by {b} agrees with {a} within {100 * worst:.2g} % of the peak",
                    value=worst,
                )
            )
    return out


def _drift_at_suspects(ds: xr.Dataset, judged: Judged) -> list[Finding]:
    from cummins.qtf.suspect_drift import drift_at_suspects, drift_suspect_frequencies

    if "drift_force" not in ds:
        return []
    found = drift_at_suspects(ds, drift_suspect_frequencies(ds, judged))
    if found is None:
        return []
    listed = ", ".join(f"{x:.4g}" for x in found.omega)
    message = (
        f"the mean drift at the {len(found.omega)} suspect frequencies{_speed_suffix(ds)} "
        f"({listed} rad/s): {found.dof} up to {found.ratio:.3g} times its largest elsewhere "
        f"({found.value:.3g} at {found.at[0]:.4g} rad/s, {found.at[1]:g} deg)"
    )
    advice = (
        "irregular frequencies spoil the drift with the damping; simulate leaves these "
        "frequencies out of the mean drift (--keep-suspect keeps them); rerun the solver "
        "with irregular-frequency removal (WAMIT IRR >= 1) for the drift there"
    )
    severity = "warning" if found.ratio > DRIFT_SUSPECT_RATIO else "info"
    return [
        Finding(
            "drift_suspect",
            severity,
            message,
            where=f"{found.dof}, {found.at[0]:.4g} rad/s",
            value=found.ratio,
            advice=advice,
            details={"omega": list(found.omega)},
        )
    ]


def _grid(ds: xr.Dataset) -> list[Finding]:
    from cummins.seakeeping.slow_drift import qtf_grid_advice

    table = qtf_table(ds, "difference")
    advice = qtf_grid_advice(table)
    out = [
        Finding(
            "qtf_grid",
            "info",
            "; ".join(advice.notes),
            value=advice.spacing,
            details={
                "spacing_rad_s": advice.spacing,
                "omega_range_rad_s": list(advice.omega_range),
                "longest_resolved_period_s": advice.longest_resolved_period,
                "jonswap_peak_periods_s": list(advice.peak_periods),
            },
        )
    ]
    diag = table.diagonal().real
    keep = _significant(np.abs(diag).reshape(-1, diag.shape[-1]).max(axis=0), table.dofs)
    for k, dof in enumerate(table.dofs):
        d = diag[..., k]
        peak = np.abs(d).max()
        if not keep[k] or table.omega.size < 2:
            continue
        step = np.abs(np.diff(d, axis=0)).max(axis=1) / peak
        if step.max() > QTF_STEP_TOL:
            i = int(np.argmax(step))
            out.append(
                Finding(
                    "qtf_grid",
                    "warning",
                    f"the mean drift of {dof} changes by {100 * step.max():.3g} % of its peak "
                    f"between {table.omega[i]:.4g} and {table.omega[i + 1]:.4g} rad/s: a "
                    "resonance the grid barely resolves, where interpolation is uncertain",
                    where=dof,
                    value=float(step.max()),
                    advice="compute the QTF on a finer grid there, or check the mass "
                    "properties the solver's motions used",
                )
            )
    return out
