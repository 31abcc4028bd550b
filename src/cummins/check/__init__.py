"""Diagnostics of a hydrodynamic database: is it physically usable, and where not?

:func:`check` runs every test below and returns a :class:`CheckReport`; nothing is
changed in the data. Each finding says what was measured, where, and what to do.

* ``frequency_grid`` — range and spacing of the finite frequencies; whether ω = 0 and
  ω = ∞ limits are present.
* ``symmetry`` — A(ω) and B(ω) symmetric (zero speed): worst relative asymmetry per DOF
  pair, |X_ij − X_ji| / √(max|X_ii| · max|X_jj|).
* ``forbidden_couplings`` — per body, the radiation couplings its own symmetry forbids
  (port/starboard, judged from the excitation's mirror; rotational about z, from the
  surge/sway and roll/pitch diagonals): a warning where they are as large as the
  couplings ``cummins fit`` models and larger than the body's measured asymmetry
  explains (:mod:`cummins.check.forbidden_couplings`).
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
* ``plausibility`` — what every floating body keeps between its quantities, so that one
  scaled by 10³ or of the wrong sign stands out (errors): mass against ρ∇ and against
  the waterplane C33/(ρg), A(ω)'s variation against what B(ω) implies (Kramers–Kronig),
  excitation against damping (Haskind), the frequencies against the body's size, the
  sign of C33 and of external damping; natural periods far from the data (warning)
  (:mod:`cummins.check.plausibility`).
* ``inertia``, ``hydrostatics`` — M_RB symmetric positive definite; C33, C44, C55 > 0.
* ``copied_dof`` — a DOF that is an exact scaled copy of another (strip-theory codes
  approximate surge by scaling sway).
* ``finite`` — NaN/Inf anywhere (validation of the dataset already refuses them).
* ``suspect_frequencies`` — spikes and clearly negative damping
  (:func:`cummins.repair.find_suspect_frequencies`), and the DOFs whose added mass an
  irregular frequency spoils to the end of the data
  (:func:`cummins.repair.irregular_frequency_spans`); suspect points through which A(ω)
  follows B(ω) are named as a sharp resonance of the data (info,
  :func:`cummins.repair.sharp_features`).
* ``retardation`` — per significant coupling: K(0), ∫K dt against B(0) = 0,
  K(t_max)/max|K|, the tail's share of ∫B dω, the Ogilvie estimate of A∞ and its spread
  over frequency (and its distance from the solver's ω = ∞ row), and the
  Kramers–Kronig error (:func:`cummins.radiation.retardation.retardation_diagnostics`).
* ``long_wave_limit`` — each body's heave excitation of long waves against its C33
  (:func:`cummins.check.waves.long_wave_heave_ratios`).
* ``qtf_symmetry``, ``qtf_mean_drift``, ``drift_methods``, ``qtf_grid`` — the second-order
  data (:mod:`~cummins.check.second_order`): the QTFs' symmetries, their diagonal against
  the run's mean drift, the mean-drift methods against each other, what the QTF's grid
  covers and resolves.

The checks live in modules by subject: :mod:`~cummins.check.coefficients` (frequency
grid, symmetry, damping, A∞, decay), :mod:`~cummins.check.physical`,
:mod:`~cummins.check.plausibility`,
:mod:`~cummins.check.rigid_body` (inertia, hydrostatics), :mod:`~cummins.check.artefacts`
(read damage, copied DOFs, suspect frequencies), :mod:`~cummins.check.retardation`,
:mod:`~cummins.check.waves` (wave parity), :mod:`~cummins.check.forbidden_couplings`;
the report in :mod:`~cummins.check.report`, the tolerances in :mod:`~cummins.check.common`.
"""

from __future__ import annotations

from functools import partial

import xarray as xr

from cummins.check.artefacts import _check_read_warnings, _check_suspect_frequencies, copied_dofs
from cummins.check.coefficients import (
    SIGNIFICANT_DOF,
    _check_added_mass_inf,
    _check_damping,
    _check_decay,
    _check_grid,
    _check_symmetry,
)
from cummins.check.common import (
    A_INF_TOL,
    DECAY_TOL,
    K_END_TOL,
    K_INTEGRAL_TOL,
    KK_TOL,
    LOW_FREQUENCY_TOL,
    NEGATIVE_DAMPING_TOL,
    PARITY_TOL,
    SYMMETRY_TOL,
    TAIL_TOL,
    PreparedFits,
    _speeds,
)
from cummins.check.forbidden_couplings import _check_forbidden_couplings
from cummins.check.physical import _check_physical
from cummins.check.plausibility import plausibility_findings
from cummins.check.reciprocity import _check_reciprocity
from cummins.check.report import SEVERITIES, CheckReport, Finding
from cummins.check.retardation import _check_retardation
from cummins.check.rigid_body import _check_rigid_body
from cummins.check.second_order import _check_second_order
from cummins.check.waves import _check_long_wave_limit, _check_wave_parity
from cummins.hydrodb import validate
from cummins.repair import suspects_by_dof

__all__ = [
    "A_INF_TOL",
    "DECAY_TOL",
    "KK_TOL",
    "K_END_TOL",
    "K_INTEGRAL_TOL",
    "LOW_FREQUENCY_TOL",
    "NEGATIVE_DAMPING_TOL",
    "PARITY_TOL",
    "SEVERITIES",
    "SIGNIFICANT_DOF",
    "SYMMETRY_TOL",
    "TAIL_TOL",
    "CheckReport",
    "Finding",
    "check",
    "copied_dofs",
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
    ['Surge', 'Sway']
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
    # each speed's suspect frequencies, found once for the checks and the fit that use them
    judged = [(sub, suspects_by_dof(sub)) for sub in _speeds(ds)]
    prepared = PreparedFits(judged)  # and the fit's preparation of each, once
    for part in (
        _check_read_warnings,
        plausibility_findings,
        _check_grid,
        _check_symmetry,
        partial(_check_reciprocity, judged=judged, prepared=prepared),
        partial(_check_forbidden_couplings, judged=judged, prepared=prepared),
        _check_damping,
        _check_added_mass_inf,
        _check_decay,
        _check_rigid_body,
        copied_dofs,
        partial(_check_suspect_frequencies, judged=judged),
        _check_retardation,
        _check_wave_parity,
        _check_long_wave_limit,
        partial(_check_second_order, judged=judged),
    ):
        findings.extend(part(ds))
    return CheckReport(source=str(source), findings=tuple(findings))
