"""What the source left in the data: ``read_damage`` (damage the reader worked around),
``copied_dof`` (a DOF that is an exact scaled copy of another: strip-theory codes
approximate surge by scaling sway; equal surge and sway, roll and pitch of one body are
an axisymmetric body's, the same DOF of two bodies equal are identical bodies placed
symmetrically, and both are said to be fine) and ``suspect_frequencies`` (spikes and
clearly negative damping, :func:`cummins.repair.find_suspect_frequencies`; those that are
a sharp resonance of the data, :func:`cummins.repair.sharp_features`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from cummins.check.common import _labels, _speed_suffix, _speeds
from cummins.check.report import Finding
from cummins.dofs import split_dof
from cummins.repair import (
    RESONANCE_MOTION,
    Judged,
    find_suspect_frequencies,
    irregular_frequency_spans,
    suspects_by_dof,
)


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
            symmetry = _symmetric_pair(labels[i], labels[j], ra, rb)
            if symmetry:
                out.append(
                    Finding(
                        "copied_dof",
                        "ok",
                        f"{labels[i]} and {labels[j]} are equal, as for {symmetry}",
                        where=f"{labels[i]}-{labels[j]}",
                    )
                )
                continue
            out.append(
                Finding(
                    "copied_dof",
                    "info",
                    f"{labels[i]} and {labels[j]} are exact scaled copies of each other "
                    f"(A ratio {ra:.4g}, B ratio {rb:.4g})",
                    where=f"{labels[i]}-{labels[j]}",
                    advice=_copy_advice(labels[i], labels[j]),
                )
            )
    return out


def _copy_advice(one: str, two: str) -> str:
    (body_one, dof_one), (body_two, dof_two) = split_dof(one), split_dof(two)
    if body_one == body_two and {dof_one, dof_two} == {"Surge", "Sway"}:
        return (
            "strip-theory codes approximate surge by scaling sway; the fluid memory of the "
            "copied DOF is then no more than a guess"
        )
    return "a solver computes each DOF on its own: check that both were computed, not copied"


def _check_suspect_frequencies(ds: xr.Dataset, judged: Judged = ()) -> list[Finding]:
    """The ``suspect_frequencies`` findings (``judged``: the data
    :func:`~cummins.repair.suspects_by_dof` has judged already, with what it found)."""
    out = []
    for sub in _speeds(ds):
        suffix = _speed_suffix(sub)
        own = suspects_by_dof(sub, judged)
        # a frequency every DOF that flags it calls a sharp resonance is physics
        resonant = set().union(*(found.features for found in own.values()))
        for found in own.values():
            resonant -= {s.omega for s in found.suspects if s.omega not in found.features}
        suspects = [s for s in find_suspect_frequencies(sub) if s.omega not in resonant]
        if not suspects:
            message = "no spikes or clearly negative damping"
            if resonant:
                message = "no irregular frequency: the points that look like spikes are sharp "
                message += "resonances of the data (below)"
            out.append(Finding("suspect_frequencies", "ok", message + suffix))
        else:
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
                    advice="spikes and negative damping are irregular frequencies of panel "
                    "methods or solver failures; remove them before fitting (cummins kernel "
                    "--remove-suspect, cummins.repair.remove_suspect_frequencies)",
                    details={
                        "omega": [s.omega for s in suspects],
                        "quantity": [s.quantity for s in suspects],
                        "reason": [s.reason for s in suspects],
                    },
                )
            )
        for label, found in own.items():
            for resonance in found.resonances:
                # one the motions depend on, left out as it runs to the data's end
                missed = resonance.at_end and (resonance.motion_change or 0.0) > RESONANCE_MOTION
                out.append(
                    Finding(
                        "suspect_frequencies",
                        "warning" if missed else "info",
                        resonance.description(label) + suffix,
                        where=label,
                        value=resonance.motion_change,
                        advice="physics, not an error: keep its points (cummins fit keeps "
                        "those the motions depend on, and every one for A∞); a finer "
                        "frequency grid there resolves the resonance"
                        if resonance.kept
                        else "data beyond it (a higher last frequency) let the fit keep a "
                        "resonance the motions depend on; its points stay for A∞"
                        if resonance.at_end
                        else "keep its points (the fit leaves them out of the model, which "
                        "does not follow a peak of a few points the motions hardly depend "
                        "on, but keeps them for A∞); a finer frequency grid there resolves "
                        "the resonance",
                        details={
                            "omega": list(resonance.omega),
                            "kept": resonance.kept,
                            "damping_share": resonance.damping_share,
                        },
                    )
                )
        for span in irregular_frequency_spans(sub, own):
            out.append(
                Finding(
                    "suspect_frequencies",
                    "warning",
                    span.description() + suffix,
                    where=span.dof,
                    value=span.departure,
                    advice=f"fit below {span.omega_start:.4g} rad/s (cummins fit --omega-max "
                    f"{span.omega_start:.4g}), or rerun the solver with irregular-frequency "
                    "removal (WAMIT IRR ≥ 1, a lid in NEMOH or Capytaine, AQWA's lid)",
                    details={"omega_start": span.omega_start, "suspects": list(span.suspects)},
                )
            )
    return out


#: DOF pairs that are equal on a body symmetric about its vertical axis.
AXISYMMETRIC_PAIRS = ({"Surge", "Sway"}, {"Roll", "Pitch"})


def _symmetric_pair(one: str, two: str, ra: float, rb: float) -> str:
    """What symmetry makes two DOFs' A and B equal, or "" when none does: surge and sway
    (roll and pitch) of one body are an axisymmetric body's, not a strip-theory copy
    (which scales sway by a factor other than 1); the same DOF of two bodies, identical
    bodies placed symmetrically (the outer buoys of a row of three)."""
    if abs(ra - 1.0) > 1e-6 or abs(rb - 1.0) > 1e-6:
        return ""
    (body_one, dof_one), (body_two, dof_two) = split_dof(one), split_dof(two)
    if body_one == body_two and {dof_one, dof_two} in AXISYMMETRIC_PAIRS:
        return "a body symmetric about the vertical axis (a buoy, spar or cylinder)"
    if body_one != body_two and dof_one == dof_two:
        return "identical bodies placed symmetrically (an array's mirror images)"
    return ""


def _constant_ratio(x: np.ndarray, y: np.ndarray) -> float | None:
    """x / y if it is the same number (to 1e-6) at 3 or more points where both are non-zero."""
    both = (x != 0) & (y != 0)
    if both.sum() < 3 or np.any((x == 0) != (y == 0)):
        return None
    ratio = x[both] / y[both]
    if np.ptp(ratio) <= 1e-6 * abs(np.mean(ratio)):
        return float(np.mean(ratio))
    return None
