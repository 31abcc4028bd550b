"""What a suspect point costs an identification: that point, not the rest of the data
(issue 16), and a model not fitted where the data are sound is reported, not passed.

* The spike test of :func:`cummins.repair.find_suspect_frequencies` judges a point only
  where the data are sampled finely enough around it: on the WAMIT OSWEC 2015 run (periods
  8, 7, …, 1 s at the top) it flagged every point above 0.78 rad/s, one after another, and
  the fitting range of all twelve DOFs ended at 0.153 rad/s.
* A fitting range cut where other DOFs' points are suspect, and a model that misses a DOF's
  curves above it, is a failure of the fit, and the same one the scoreboard measures (the
  NEMOH two-body case: R² of A −9.5 by the scoreboard, no failure reported before).
* The passivity programme of a block on non-passive data stays small (the OSWEC 2015 fit
  took 227–300 s, 9 000 constraints on 275 unknowns) and the model is passive by an
  independent sweep.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from _synthetic import one_dof_hydrodb, read_quietly
from cummins.radiation.fit import fit_radiation
from cummins.radiation.fit.scorecard import diagonal_r2, passivity_margin
from cummins.repair import find_suspect_frequencies


def test_a_coarsely_sampled_peak_is_not_a_spike():
    """A smooth resonant damping sampled at periods 30 … 12 s, then 11, 10, …, 1 s (Δω/ω
    up to 100 %): none of its points is a spike (the test without the sampling rule
    flagged 2.09, 3.14 and 6.28 rad/s). The same curve with one point spoiled on a fine
    grid still has that one, and only that one."""
    periods = np.r_[np.linspace(30.0, 12.0, 40), np.arange(11.0, 0.0, -1.0)]
    w = 2 * np.pi / periods
    b = w**4 / ((1.0 - w**2) ** 2 + (0.6 * w) ** 2)
    a = 1.0 + 0.5 / (1.0 + w**2)
    assert find_suspect_frequencies(one_dof_hydrodb(w, a, b)) == ()
    fine = np.linspace(0.2, 3.0, 120)
    b = fine**4 / ((1.0 - fine**2) ** 2 + (0.6 * fine) ** 2)
    b[60] *= 1.5  # a spike of 50 % of the local value: ~20 % of the curve's range
    a = 1.0 + 0.5 / (1.0 + fine**2)
    found = [round(s.omega, 6) for s in find_suspect_frequencies(one_dof_hydrodb(fine, a, b))]
    assert found == [round(fine[60], 6)]


def test_the_oswec_2015_periods_are_not_spikes_and_the_fit_covers_its_range(corpus):
    """WAMIT OSWEC 2015 (`.out`, 50 periods, the top eight 8, 7, …, 1 s): the flap's
    curves are not flagged above 0.78 rad/s; the base's roll damping, negative at 0.157–
    1.257 rad/s (down to −1 × its peak), still is. The fit covers the data's range, is
    passive by a dense sweep and stable, and reports what passivity cost: the base's roll,
    R² of A 0.9994 → −2.66, the worst miss its block's note names.

    The order search stops once passivity has lost a coupling at two orders in a row,
    since more poles cannot make non-passive data passive. Since the fit follows the
    data's damping tail (issue 31) the plain fits meet the 0.99 target only at 12 common
    poles, the most the roll's 14 kept frequencies allow (8–11: 0.979–0.990), so at the
    default targets the search ends there; at 0.98 (couplings 0.96) they meet it from 8
    poles and the rule stops the search at 10, saying the data are not passive."""
    ds = read_quietly(corpus / "WEC-Sim" / "wamit_OSWEC_2015_with_bemio_h5" / "oswec.out")
    w = ds.omega.values
    top = w[w > 0.78]
    for label in ("body1__Surge", "body1__Pitch", "body1__Yaw"):
        one = ds.sel(influenced_dof=[label], radiating_dof=[label])
        flagged = {round(s.omega, 4) for s in find_suspect_frequencies(one)}
        assert not flagged & {round(x, 4) for x in top}, (label, flagged)
    roll = ds.sel(influenced_dof=["body2__Roll"], radiating_dof=["body2__Roll"])
    negative = [s.omega for s in find_suspect_frequencies(roll) if "negative" in s.reason]
    assert len(negative) >= 30 and min(negative) < 0.16 and max(negative) > 1.2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = fit_radiation(ds)
    assert model.attrs["omega_fit_max"] == pytest.approx(w.max())
    assert model.is_stable()
    assert passivity_margin(model) >= -1e-6
    # the data are not passive (the base's roll): what enforcing passivity cost is a failure
    roll = [f for f in model.attrs["failures"] if f.startswith("body2__Roll: passivity took")]
    assert roll and float(roll[0].split(" to ")[1].split()[0]) < 0.0  # −2.66
    big = next(b for b in model.blocks if len(b.dofs) > 2)
    assert big.note.startswith("targets not met") and "R² of A of body2__Roll -" in big.note
    # where the plain fits meet the targets at two orders, the search stops there rather
    # than adding poles that cannot help
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        relaxed = fit_radiation(ds, r2=0.98, r2_coupling=0.96)
    big = next(b for b in relaxed.blocks if len(b.dofs) > 2)
    assert "the data are not passive" in big.note


def test_a_model_extrapolated_over_sound_data_is_a_failure(corpus, tanker_wamit):
    """NEMOH two cubes (bemio): the zigzag of the surge and pitch curves cuts the fitting
    range at 1.415 of 2 rad/s (1.123 before its slightly non-passive damping was fitted
    by its passive part: the negative-damping points are gone); the other DOFs' curves
    are sound above it and the model misses them. The fit names that as a failure, with the DOFs the
    scoreboard (:func:`diagonal_r2`, computed here) finds below target. The tanker's
    range is cut too (irregular frequencies above 3.4 rad/s), but the model still
    meets the target on every DOF there: no such failure."""
    ds = read_quietly(corpus / "bemio" / "nemoh_two_body")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = fit_radiation(ds)
    assert model.attrs["omega_fit_max"] < 0.75 * float(ds.omega.max())
    cut = [f for f in model.attrs["failures"] if "cut the range" in f]
    assert len(cut) == 1, model.attrs["failures"]
    r2 = diagonal_r2(ds, model)
    below = [dof for dof, (ra, rb) in r2.items() if min(ra, rb) < 0.99]
    assert below  # the scoreboard's verdict
    worst = min(r2, key=lambda d: min(r2[d]))
    assert f"{worst} " in cut[0]
    tanker = fit_radiation(tanker_wamit)
    assert tanker.attrs["omega_fit_max"] < float(tanker_wamit.omega.max())
    assert not [f for f in tanker.attrs["failures"] if "cut the range" in f]
    assert min(min(v) for v in diagonal_r2(tanker_wamit, tanker).values()) > 0.99


@pytest.mark.parametrize(
    ("case", "dofs", "labels"),
    [
        ("ROSCO/wamit_ITI_barge_5MW_Baseline/Barge.1", (0, 4), ("Surge", "Pitch")),
        ("RAFT/capytaine_integration_float/floatData.nc", (2,), ("Heave",)),
    ],
)
def test_short_of_its_targets_a_block_keeps_the_fewest_poles_that_fit_as_well(
    corpus, case, dofs, labels
):
    """Blocks that no number of common poles makes meet the targets once passive: the
    ITI barge's surge–pitch (an irregular frequency spoils the barge's data; passivity
    costs ~0.011 of R² at every count) and the RAFT Capytaine float's heave (passivity
    costs 0.01–0.08 at every count from 7 to 20). The search keeps fewer poles than the
    most it may use, and the most (fixed here) fit no better by more than 0.001 of R²:
    what the data allow is not bought with states. (Since issue 31, the damping beyond the
    data held to the data's tail, the barge's surge–pitch plain fits level off from 10
    common poles and the search stops at 12, keeping 11 — R² 0.9830 at 22 states against
    0.9861 at 40 for 20 poles, both short of 0.99: at most 0.007 lost (2.3× the 0.0031
    measured), at most 80 % of the states (55 % measured).)"""
    from cummins.radiation.fit.order_search import NEAR

    ds = read_quietly(corpus / case)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        default = fit_radiation(ds)
        most = fit_radiation(ds, orders={(dofs[0], dofs[0]): 20})
    blocks = {
        name: next(b for b in m.blocks if b.dofs == dofs)
        for name, m in (("default", default), ("most", most))
    }
    poles = {m["common_poles"] for m in blocks["default"].metrics.values()}.pop()
    r2 = {
        name: min(min(diagonal_r2(ds, m)[d]) for d in labels)
        for name, m in (("default", default), ("most", most))
    }
    assert poles < 20
    assert blocks["most"].a.shape[0] > blocks["default"].a.shape[0]
    if "Barge" in case:
        assert r2["default"] >= r2["most"] - 0.007, r2
        assert blocks["default"].a.shape[0] <= 0.8 * blocks["most"].a.shape[0]
    else:
        assert r2["default"] >= r2["most"] - NEAR * (1 - 0.99) - 1e-9, r2
    assert passivity_margin(default) >= -1e-6


def test_the_kept_count_meets_the_targets_or_is_the_fewest_nearly_as_close():
    """The rule of :func:`kept_count` on its own: a count that meets every target wins
    over any that does not (however few poles), a passive one over any that is not, and
    short of the targets the fewest within NEAR of the closest."""
    from cummins.radiation.fit.order_search import NEAR, kept_count

    assert kept_count({6: (False, 0.05), 10: (False, 0.0), 8: (False, 0.0)}) == 8
    assert kept_count({5: (True, 0.5), 9: (False, 2.0)}) == 9
    near, far = 1.10 + 0.9 * NEAR, 1.10 + 1.1 * NEAR
    assert kept_count({12: (False, far), 15: (False, near), 20: (False, 1.10)}) == 15
    assert kept_count({12: (False, far), 20: (False, 1.10)}) == 20


def test_a_coupling_no_order_follows_does_not_stop_the_diagonal_improving(corpus):
    """NEMOH v3's two cubes side by side: the yaw–yaw coupling between the bodies is noise
    at about 1 % of the diagonal, which no number of common poles follows (R² ≈ 0 at 4 …
    16). The order search measured a fit by its largest shortfall alone, so that coupling
    hid every other improvement: it stopped at 8 poles and kept 5, and the bodies' yaw
    had R² of A 0.14 and of B 0.06 (sway 0.71 / 0.37, roll 0.64 / −0.05). Now the largest
    shortfall on the diagonal counts too. And the fitting range, cut by one suspect
    point at the lowest frequency (0.03 rad/s, heave), is not blamed for what the model
    misses inside it."""
    ds = read_quietly(corpus / "WEC-Sim" / "nemoh_v3.0.2_Cubes_2body")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = fit_radiation(ds)
    r2 = diagonal_r2(ds, model)
    for body in ("body1", "body2"):
        for dof in ("Sway", "Roll", "Yaw"):
            added_mass, damping = r2[f"{body}__{dof}"]
            assert added_mass > 0.8 and damping > 0.6, (body, dof, r2[f"{body}__{dof}"])
    assert passivity_margin(model) >= -1e-6
    assert model.attrs["omega_fit_min"] > float(ds.omega.min())
    assert not [f for f in model.attrs["failures"] if "cut the range" in f]


def test_the_badness_of_a_fit_is_its_largest_shortfall_when_a_diagonal_term_has_it():
    """:func:`distance` on its own: the largest shortfall when it is a diagonal term's
    (the measure the order search always had), the mean of it and the largest diagonal
    shortfall when a coupling is furthest from its target."""
    from cummins.radiation.fit.order_search import BlockScore, distance

    def score(r2):
        short = max((0.99 if i == j else 0.97) - min(p) for (i, j), p in r2.items())
        return BlockScore(r2, max(short, 0.0), None, True)

    diagonal_worst = score({(0, 0): (0.95, 0.97), (0, 1): (0.96, 0.96), (1, 1): (0.99, 0.99)})
    assert distance(diagonal_worst, 0.99, None) == pytest.approx(0.04 / 0.01)
    coupling_worst = score({(0, 0): (0.98, 0.99), (0, 1): (0.0, 0.1), (1, 1): (0.99, 0.99)})
    assert distance(coupling_worst, 0.99, None) == pytest.approx(0.5 * (0.97 + 0.01) / 0.01)
    met = score({(0, 0): (0.995, 0.999), (0, 1): (0.98, 0.99), (1, 1): (0.99, 0.992)})
    assert distance(met, 0.99, None) == 0.0
