"""The passivity sweep of the common-pole fit (issue 16: fit time).

Each iteration of the passivity enforcement looks for the frequencies where the block's
Re K(jω) has a negative eigenvalue. It looks on a dense grid while the grid sees any,
then between the exact crossings of the Hamiltonian pencil, built from a realization in
the poles' own coordinates (no factorisation per pole). These tests check, on the ITI
barge (WAMIT, ROSCO), that this realization is K itself, that its crossings are those of
Gilbert's realization, that the exact phase finds bands the grid cannot see, and that
every block called passive is passive by a check the sweep does not use.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import cummins
from cummins.radiation.fit import fit_radiation, order_search, vector
from cummins.radiation.passivity import imaginary_axis_zeros


@pytest.fixture(scope="module")
def barge_blocks(corpus):
    """(fitted, enforced, passive) of every passivity enforcement of the ITI barge's fit,
    and the sweeps whose grid saw nothing, with what the exact sweep found there."""
    calls, blind = [], []
    enforce, sweep = order_search.enforce_passivity, vector.passivity_violations

    def recording_enforce(block, data, **options):
        out = enforce(block, data, **options)
        calls.append((block, out[0], out[1]))
        return out

    def recording_sweep(block, lo, hi, exact=True):
        found = sweep(block, lo, hi, exact=exact)
        if not exact:
            blind.append((block, lo, hi, bool(found[0])))
        return found

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(order_search, "enforce_passivity", recording_enforce)
        mp.setattr(vector, "passivity_violations", recording_sweep)
        ds = cummins.read(corpus / "ROSCO" / "wamit_ITI_barge_5MW_Baseline" / "Barge.1")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            fit_radiation(ds)
    assert calls, "the fit enforced passivity on no block"
    return calls, blind


def _scaled(block, omega):
    """Re K(jω) with the DOF scaling of the sweep (diagonal peaks 1)."""
    k = block.response(omega).real
    peak = np.abs(np.diagonal(k, axis1=1, axis2=2)).max(axis=0)
    s = 1.0 / np.sqrt(peak)
    return k * np.outer(s, s)[None], s


def test_the_coordinate_realization_is_the_block(barge_blocks):
    """C(sI − A)⁻¹B of the coordinate realization equals the pole–residue sum."""
    calls, _ = barge_blocks
    omega = np.geomspace(0.01, 50.0, 40)
    for fitted, _, _ in calls[::3]:
        a, b, c = fitted.coordinate_realization()
        eye = np.eye(a.shape[0])
        k = np.array([c @ np.linalg.solve(1j * w * eye - a, b) for w in omega])
        reference = fitted.response(omega)
        assert np.abs(k - reference).max() <= 1e-9 * np.abs(reference).max()


def test_its_crossings_are_where_the_smallest_eigenvalue_changes_sign(barge_blocks):
    """Every sign change of λ_min(S Re K S) on a fine grid lies within 0.5 % of a crossing
    of the coordinate realization, and within 0.5 % of one of Gilbert's realization."""
    calls, _ = barge_blocks
    omega = np.geomspace(0.05, 20.0, 6000)  # spacing 0.1 %
    checked = 0
    for fitted, _, _ in calls:
        scaled, s = _scaled(fitted, omega)
        low = np.linalg.eigvalsh(scaled)[:, 0]
        change = np.flatnonzero(np.sign(low[1:]) != np.sign(low[:-1]))
        # a sign change that the grid resolves: λ_min leaves zero on both sides
        clear = [i for i in change if min(abs(low[i]), abs(low[i + 1])) > 1e-9]
        for realization in (fitted.coordinate_realization(), fitted.realization(rank_tol=0.0)):
            a, b, c = realization
            crossings = imaginary_axis_zeros(a, b * s[None, :], s[:, None] * c)
            for i in clear:
                mid = np.sqrt(omega[i] * omega[i + 1])
                assert np.abs(crossings - mid).min() <= 5e-3 * mid, (fitted.dofs, mid)
                checked += 1
    assert checked >= 20


def test_the_exact_sweep_finds_bands_the_grid_cannot_see(barge_blocks):
    """Somewhere in the barge's fit the grid saw no violation and the exact sweep found
    one (a band narrower than the grid's 1.5 % spacing): the grid alone would have
    called a non-passive block passive."""
    _, blind = barge_blocks
    missed = [
        b for b, lo, hi, saw in blind if not saw and vector.passivity_violations(b, lo, hi)[0]
    ]
    assert missed


def test_every_block_called_passive_is_passive(barge_blocks):
    """Independent of the sweep: λ_min(S Re K S) ≥ −10⁻⁷ (ten times the sweep's own
    threshold; the issue's check asks −10⁻⁶) on 20 000 frequencies over 10⁻⁴–10³ rad/s
    and at the midpoints between Gilbert's crossings. Before the pencil's zeros near the
    axis were taken as crossing candidates, yaw's block was called passive with a dip of
    −1.1·10⁻⁷ at 0.649 rad/s, between the sweep's grid points."""
    calls, _ = barge_blocks
    passive = [enforced for _, enforced, ok in calls if ok]
    assert len(passive) >= len(calls) - 1
    for block in passive:
        omega = np.geomspace(1e-4, 1e3, 20000)
        _, s = _scaled(block, omega)
        a, b, c = block.realization(rank_tol=0.0)
        edges = np.r_[1e-4, imaginary_axis_zeros(a, b * s[None, :], s[:, None] * c), 1e3]
        points = np.r_[omega, np.sqrt(edges[1:] * edges[:-1])]
        scaled, _ = _scaled(block, points)
        assert np.linalg.eigvalsh(scaled)[:, 0].min() >= -1e-7, block.dofs
