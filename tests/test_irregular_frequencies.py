"""Irregular frequencies that spoil the added mass beyond their spikes (issue 16).

A panel method without irregular-frequency removal puts a pole's shape in A(ω) and a
spike in B(ω) near each irregular frequency. The spike test finds the points near it;
on the ITI barge (WAMIT, ROSCO) heave's A(ω) stays 30 % below what B(ω) implies from
2.8 rad/s to the last frequency, 5 rad/s, while the spikes end at 3.9 rad/s. The default
fit, holding those points, needs 76 states and reports three couplings failed; fitted
below 2.8 rad/s the same data give a model that meets every target. The check and the
fit's notes now say where and what to do.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import cummins
from _synthetic import one_dof_hydrodb, read_quietly
from cummins.radiation.fit import fit_radiation
from cummins.radiation.fit.scorecard import scorecard
from cummins.radiation.retardation import causal_limits
from cummins.repair import irregular_frequency_spans


@pytest.fixture(scope="module")
def barge(corpus):
    return read_quietly(corpus / "ROSCO" / "wamit_ITI_barge_5MW_Baseline" / "Barge.1")


def test_the_barge_spans_start_where_its_added_mass_leaves_causality(barge):
    """Heave from 2.75–2.85 rad/s, surge and sway from 3.4–3.5 rad/s (the frequencies
    where WAMIT's A(ω) leaves the Kramers–Kronig transform of its B(ω) by more than
    10 % for good), each holding that DOF's suspect frequencies; roll, pitch and yaw
    have none."""
    spans = {s.dof: s for s in irregular_frequency_spans(barge)}
    assert set(spans) == {"Surge", "Sway", "Heave"}
    assert 2.75 <= spans["Heave"].omega_start <= 2.85
    for dof in ("Surge", "Sway"):
        assert 3.4 <= spans[dof].omega_start <= 3.5
    for span in spans.values():
        assert span.departure > 0.2  # far beyond the 10 % that defines the span
        assert all(w >= span.omega_start for w in span.suspects) and span.suspects


def test_fitted_below_the_span_the_barge_meets_its_targets(barge):
    """The note's advice, followed: at ω ≤ 2.8 rad/s no coupling fails, every diagonal
    R² of A and B ≥ 0.99 (independent scorecard), passive, and far fewer states than
    the default fit through the spoiled data (76, three couplings failed)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        full = fit_radiation(barge)
        start = min(s.omega_start for s in irregular_frequency_spans(barge))
        below = fit_radiation(barge, omega_max=start)
    notes = " ".join(full.attrs["data_notes"])
    assert f"fitted below {start:.4g} rad/s" in notes
    assert full.attrs["failures"] and not below.attrs.get("failures")
    card = scorecard(barge.sel(omega=barge.omega[barge.omega <= start]), below)
    assert card.passive and card.stable
    assert min(card.r2_added_mass, card.r2_damping) >= 0.99
    assert card.total_order <= 0.6 * scorecard(barge, full).total_order


def test_the_check_says_where_and_what_to_do(barge):
    found = {
        f.where: f
        for f in cummins.check(barge).by_check("suspect_frequencies")
        if f.details and "omega_start" in f.details
    }
    assert set(found) == {"Surge", "Sway", "Heave"}
    heave = found["Heave"]
    assert heave.severity == "warning"
    assert f"--omega-max {heave.details['omega_start']:.4g}" in heave.advice


@pytest.mark.parametrize(
    "case",
    [
        "mss/tanker/tanker.1",
        "mss/supply/supply.mat",
        "wecsim/cylinder/cylinder_nemoh/cylinder_hydrodynamics.nc",
        "corpus/WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar",
        "corpus/WEC-Sim_Applications/wamit_monopile/monopile.out",
    ],
)
def test_consistent_data_have_no_span(shared_data, case):
    """Ships with irregular-frequency spikes of their own (the tanker's 3.6–4.5 rad/s)
    and offshore structures whose added mass stays a causal pair with their damping."""
    assert irregular_frequency_spans(read_quietly(shared_data / case)) == ()


def test_a_departure_without_spikes_is_not_called_an_irregular_frequency(corpus):
    """The RAFT Capytaine float's surge estimate departs over its last 7 of 28
    frequencies (2.2–2.8 rad/s), with no spike there: data that end before the damping
    has decayed (the unknown tail), not an irregular frequency; no span, and fitting
    below 2.2 rad/s would not help (its heave then fails)."""
    ds = read_quietly(corpus / "RAFT" / "capytaine_integration_float" / "floatData.nc")
    assert "Surge" in causal_limits(ds)
    assert irregular_frequency_spans(ds) == ()


def test_a_causal_pair_has_no_departure():
    """An analytic causal pair (one complex pole pair, K strictly proper): no DOF departs,
    whatever the sampling; the same pair with A(ω) shifted by 30 % of A∞ above 2 rad/s
    departs from the first shifted frequency."""
    w = np.linspace(0.05, 5.0, 100)
    pole, residue = -0.3 + 1.0j, -2.0e6j  # Ã(s) = A∞ + R/(s − p) + R̄/(s − p̄)
    s = 1j * w
    a_tilde = residue / (s - pole) + np.conj(residue) / (s - np.conj(pole))
    a_inf = 5.0e6
    added = a_inf + a_tilde.real
    damping = -w * a_tilde.imag
    assert damping.min() > 0
    ds = one_dof_hydrodb(w, added, damping)
    assert causal_limits(ds) == {}
    shifted = added - 0.3 * a_inf * (w >= 4.0)
    spoiled = one_dof_hydrodb(w, shifted, damping)
    start, departure = causal_limits(spoiled)["Heave"]
    assert start == pytest.approx(w[w >= 4.0][0])
    assert departure == pytest.approx(0.3 * a_inf / max(a_inf, np.median(np.abs(added))), rel=0.2)
