"""An axisymmetric body's two horizontal blocks (surge–pitch and sway–roll), whose data
differ only by the panels' asymmetry, share their common poles: the second block fits its
own residues at the first one's poles (:func:`cummins.radiation.fit.blocks.mirror_block`,
:data:`~cummins.radiation.fit.blocks.SHARED_POLES`) instead of its own order search.

Measured on the corpus (``benchmarks/bench_identification.py``, CPU s of the fit): the ITI
barge 0.36 → 0.27, the monopile 0.38 → 0.23, the WAMIT drift sphere 0.47 → 0.37, the
AQWA PEND hull 0.27 → 0.22; no scoreboard measure worse on any of the 38 cases.
"""

from __future__ import annotations

import warnings
from importlib import resources

import numpy as np
import pytest

import cummins
from cummins.radiation.fit import blocks, fit_radiation

SPHERE = "WEC-Sim_Applications/wamit_mean_drift_sphere/outputFiles/sphere.1"
PEND = "WEC-Sim/aqwa_19.1_PEND_hull/19_1.AH1"


def _fits(ds, monkeypatch):
    """The model as fitted, and with no block sharing another's poles."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        shared = fit_radiation(ds)
        with monkeypatch.context() as m:
            m.setattr(blocks, "SHARED_POLES", 0.0)
            own = fit_radiation(ds)
    return shared, own


def _block(model, dofs):
    return next(b for b in model.blocks if b.dofs == dofs)


@pytest.mark.parametrize("case", [SPHERE, PEND])
def test_twin_blocks_share_their_poles(corpus, case, monkeypatch):
    """The sway–roll block takes the surge–pitch block's poles, says so, and is no further
    from the data than its own search's fit: every pair's R² of A and B at least that of
    its own search less 0.002 (measured: the sphere's 0.9931–0.9980 → 0.9933–0.9992, the
    PEND hull's equal), the model's motion error within 1 % of it (equal on both)."""
    ds = cummins.read(corpus / case)
    shared, own = _fits(ds, monkeypatch)
    surge_pitch, sway_roll = _block(shared, (0, 4)), _block(shared, (1, 3))
    assert "common poles of the Surge-Pitch block" in sway_roll.note
    assert "common poles of" not in _block(own, (1, 3)).note
    ours = np.linalg.eigvals(sway_roll.a)
    theirs = np.linalg.eigvals(surge_pitch.a)
    for pole in ours:  # a pole of the twin, each one (a residue of rank 0 costs no state)
        assert np.min(np.abs(theirs - pole)) <= 1e-8 * np.abs(pole)
    for pair, metrics in _block(own, (1, 3)).metrics.items():
        got = sway_roll.metrics[pair]
        assert got["r2_added_mass"] >= metrics["r2_added_mass"] - 0.002, pair
        assert got["r2_damping"] >= metrics["r2_damping"] - 0.002, pair
    assert shared.attrs["motion_error"] == pytest.approx(own.attrs["motion_error"], rel=0.01)
    assert len(shared.attrs["failures"]) == len(own.attrs["failures"])


def test_a_ship_has_no_twin_blocks():
    """A ship's sway–roll–yaw data are not its surge–heave–pitch data: every block has its
    own order search (the S-175)."""
    path = resources.files("cummins") / "data" / "s175" / "s175.mat"
    ds = cummins.read(str(path)).sel(forward_speed=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = fit_radiation(ds)
    assert len(model.blocks) > 1
    assert not any("common poles of" in b.note for b in model.blocks)


def test_twins_are_matched_dof_for_dof():
    """``mirror_block`` pairs DOFs by their diagonal data, in any order, within
    SHARED_POLES, and refuses blocks of another size or with one DOF too different."""
    w = np.linspace(0.1, 3.0, 40)
    a = np.zeros((w.size, 4, 4))
    b = np.zeros((w.size, 4, 4))
    for d, (scale, shift) in enumerate([(1.0, 0.0), (5.0, 1.0), (5.0, 1.0), (1.0, 0.0)]):
        a[:, d, d] = scale * (2 + np.cos(w + shift))
        b[:, d, d] = scale * w * np.exp(-w)
    b[:, 3, 3] *= 1.01  # 1 %: twins
    done = [("First", (0, 1), ((0, 0), (0, 1), (1, 1)), "poles", "score", 0.05)]
    found = blocks.mirror_block(done, (2, 3), ((2, 2), (2, 3), (3, 3)), a, b)
    assert found is not None and found[0] == "First"
    assert found[-1] == pytest.approx(0.01 / 1.01, rel=1e-6)  # relative to the larger
    assert blocks.mirror_block(done, (2,), ((2, 2),), a, b) is None
    b[:, 3, 3] *= 1.1  # 11 %: not twins
    assert blocks.mirror_block(done, (2, 3), ((2, 2), (2, 3), (3, 3)), a, b) is None
