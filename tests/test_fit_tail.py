"""Issue 31: the model beyond the data. One damping tail for the data's K(t) and for the
fit (``cummins.radiation.damping_tail``, ``cummins.radiation.fit.tail``); the default fit
decays beyond the data as the data's damping does — no resonance of its own there, its
K(t) close to the data's; the R² of K(t) is a target whose miss is a failure naming the
DOF; "targets not met" says which target and whether the motions show it.

Before (main of 2026-12-04, the lead's audit, the scorecard's measures): the monopile's
pitch damping peaked beyond the data at 2.7× the data's peak (23.6 rad/s; R² of K(t)
−25.8); the supply vessel's roll decayed beyond the data far slower than its tail
(K(0) 3.0·10⁸ against 7.7·10⁷, R² of K(t) −4.9); the HAMS cylinder's pitch 1.35× its
peak (R² of K(t) −14.6 against the data's K(t) then truncated at the last frequency).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.signal
from click.testing import CliRunner
from scipy.integrate import quad

import cummins
from cummins.errors import FitError
from cummins.radiation.damping_tail import RISE_KNEES, DampingTail, fit_damping_tail
from cummins.radiation.fit import fit_radiation
from cummins.radiation.fit.order_search import BlockScore, targets_not_met
from cummins.radiation.fit.scorecard import damping_beyond, kernel_r2, scorecard
from cummins.radiation.fit.tail import (
    PEAK_TOLERANCE,
    damping_beyond_data,
    rise_after_top,
)
from cummins.radiation.transforms import cosine_transform

# an analytic fluid memory: one damped mode, K(s) = c s / (s² + 2ζω₀s + ω₀²) — K(0) = 0,
# strictly proper, passive; its damping peaks at ω₀ = 3 rad/s
C, ZETA, W0 = 5.0, 0.3, 3.0


def _mode(omega):
    s = 1j * np.asarray(omega, dtype=float)
    k = C * s / (s**2 + 2 * ZETA * W0 * s + W0**2)
    return k.real, k.imag / np.asarray(omega, dtype=float)  # B(ω), A(ω) − A∞


@pytest.mark.parametrize("last", [2.0, 2.3, 2.6])
def test_a_rising_damping_is_continued_as_its_added_mass_says(last):
    """Data that end below the damping's peak (ω_N = 2, 2.3, 2.6 rad/s; peak at 3): the
    tail continued to the knee that makes A(ω) most consistent with B(ω) (Kramers–Kronig)
    gives a K(t) closer to the mode's exact K(t) than the ω⁻² law from the last point
    (measured R² 0.75 / 0.96 / 0.96 against 0.37 / 0.65 / 0.90)."""
    w = np.linspace(0.05, last, 50)
    b, a = _mode(w)
    t = np.linspace(0.0, 20.0, 2001)
    _, exact = scipy.signal.impulse(scipy.signal.lti([C, 0.0], [1.0, 2 * ZETA * W0, W0**2]), T=t)
    inner = (2 / np.pi) * cosine_transform(np.r_[0.0, w], np.r_[0.0, b][:, None], t)[:, 0]
    r2 = []
    for tail in (fit_damping_tail(w, b, added_mass=a), fit_damping_tail(w, b)):
        assert tail.kind[0] == "rising"
        k = inner + (2 / np.pi) * tail.cosine(t)[:, 0]
        r2.append(1 - np.sum((k - exact) ** 2) / np.sum((exact - exact.mean()) ** 2))
    assert r2[0] > r2[1] + 0.03, r2


def test_the_rising_tail_is_transformed_exactly():
    """A rising tail (linear to the knee, then ω⁻²): its cosine and sine transforms and its
    area equal quadrature of the tail itself."""
    tail = DampingTail(
        np.array(["rising"], dtype=object),
        2.0,
        np.array([3.0]),
        np.array([2.0]),
        np.array([""], dtype=object),
        np.array([2.6]),
        np.array([1.5]),
    )
    top = 3.0 + 1.5 * 0.6
    assert tail.at([2.0, 2.3, 2.6, 5.2])[:, 0] == pytest.approx([3.0, 3.45, top, top / 4])
    for t in (0.0, 0.7, 3.1):
        cos = quad(lambda x, t=t: tail.at([x])[0, 0] * np.cos(x * t), 2.0, 2.6)[0]
        sin = quad(lambda x, t=t: tail.at([x])[0, 0] * np.sin(x * t), 2.0, 2.6)[0]
        if t > 0:
            cos += quad(lambda x: top * (2.6 / x) ** 2, 2.6, np.inf, weight="cos", wvar=t)[0]
            sin += quad(lambda x: top * (2.6 / x) ** 2, 2.6, np.inf, weight="sin", wvar=t)[0]
        else:
            cos += top * 2.6  # ∫ (k/x)² dx from k
        assert tail.cosine([t])[0, 0] == pytest.approx(cos, rel=1e-6, abs=1e-9)
        assert tail.sine([t])[0, 0] == pytest.approx(sin, rel=1e-6, abs=1e-9)
    area = 0.5 * (3.0 + top) * 0.6 + top * 2.6
    assert tail.area()[0] == pytest.approx(area)


def test_the_knee_is_the_most_consistent_one():
    """The knee chosen (closed-form transforms) is the one whose Ogilvie estimates of A∞
    over the upper half of the frequencies spread least, recomputed here with the tail's
    own (sampled) Kramers–Kronig transform."""
    from cummins.radiation.transforms import hilbert_pv

    w = np.linspace(0.05, 2.3, 50)
    b, a = _mode(w)
    chosen = fit_damping_tail(w, b, added_mass=a)
    upper = w >= 0.5 * w[-1]
    upper[-1] = False
    inner = hilbert_pv(np.r_[0.0, w], np.r_[0.0, b][:, None], w)[:, 0]
    spreads = {}
    for factor in RISE_KNEES:
        tail = DampingTail(
            chosen.kind,
            chosen.omega_start,
            chosen.value,
            chosen.rate,
            chosen.note,
            np.array([factor * w[-1]]),
            chosen.slope,
        )
        estimate = a - (2 / np.pi) * (inner + tail.hilbert(w)[:, 0])
        spreads[factor] = np.std(estimate[upper])
    best = min(spreads, key=spreads.get)
    assert chosen.knee[0] == pytest.approx(best * w[-1])
    assert best > 1.0  # the peak lies beyond the data: the tail rises first


def test_a_small_rise_at_the_end_is_noise_not_a_tail():
    """A damping that has decayed to 0.3 % of its peak and creeps up at the last points
    (WAMIT's cylinder heave at 21 rad/s) gets no tail: continued, it added 4 % to K(0)
    against NEMOH's same body."""
    w = np.linspace(0.1, 20.0, 200)
    b = np.exp(-((w - 2.0) ** 2)) + 0.003 * (w / 20.0) ** 4
    tail = fit_damping_tail(w, b)
    assert tail.kind[0] == "none" and "small" in tail.note[0]


def _fit(path):
    ds = cummins.read(path)
    if "forward_speed" in ds.dims:
        ds = ds.sel(forward_speed=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return ds, fit_radiation(ds)


@pytest.fixture(scope="module")
def monopile(corpus):
    return _fit(corpus / "WEC-Sim_Applications" / "wamit_monopile" / "monopile.out")


@pytest.fixture(scope="module")
def supply(shared_data):
    return _fit(shared_data / "mss" / "supply" / "supply.mat")


def test_the_monopile_decays_beyond_its_data(monopile):
    """Every DOF's damping beyond the data (20 … 20 000 rad/s) below 5 % of the data's peak
    (measured ≤ 0.6 %; before, pitch 2.7× at 23.6 rad/s), no peak of its own, and R² of
    K(t) ≥ 0.9 (measured ≥ 0.995; before −25.8)."""
    ds, model = monopile
    beyond = damping_beyond(ds, model)
    assert set(beyond) == {"Surge", "Sway", "Roll", "Pitch"}
    for dof, found in beyond.items():
        assert found.ratio <= 0.05 and found.ok(0.5 * PEAK_TOLERANCE), (dof, found)
    assert min(kernel_r2(ds, model).values()) >= 0.9
    assert not [f for f in model.attrs["failures"] if "R² of K(t)" in f or "beyond" in f]


def test_the_supply_vessels_roll_decays_as_its_tail(supply):
    """The supply vessel's roll damping is still 58 % of its peak at the last frequency
    (3.14 rad/s): K(0), which holds the tail's area, within 5 % of the data's (measured
    0.4 %; before 3.0·10⁸ against 7.7·10⁷), the model's damping at 10 ω_N below 5 % of the
    data's last value (measured 0.9 %; before half of it), R² of K(t) ≥ 0.9 on every DOF
    (measured ≥ 0.96; before roll −4.9), and the motions never 2 % off (measured
    0.78 %)."""
    ds, model = supply
    i = model.dofs.index("Roll")
    data = cummins.retardation_function(ds, [0.0]).values[0, i, i]
    fitted = model.impulse_response([0.0]).values[0, i, i]
    assert fitted == pytest.approx(data, rel=0.05)
    w, b = ds.omega.values, ds.radiation_damping.values[:, i, i]
    assert model.response([10 * w[-1]])[0, i, i].real <= 0.05 * b[-1]
    assert min(kernel_r2(ds, model).values()) >= 0.9
    card = scorecard(ds, model)
    assert card.rao_error.error <= 0.02 and card.beyond_ok


def test_the_hams_cylinder_pitch_stays_under_its_tail(corpus):
    """The HAMS cylinder's pitch damping is at its peak at the last frequency (5.42 rad/s):
    the data's tail continues it to a knee (Kramers–Kronig with A(ω)), then ω⁻². The model
    stays under that tail (measured excess 0; before, 1.35× the data's peak beyond the
    data with a peak of its own), does not rise again after its largest value, and its
    K(t) has R² ≥ 0.9 against the data's (measured 0.988 fitted reciprocal, 0.939 with its
    surge–pitch and sway–roll fitted as given; −14.6 before, against the data's
    K(t) then truncated at the last frequency)."""
    ds, model = _fit(corpus / "HAMS" / "Cylinder" / "Output_Benchmark" / "Wamit_format" / "Buoy.1")
    pitch = damping_beyond(ds, model)["Pitch"]
    assert pitch.excess <= 0.5 * PEAK_TOLERANCE and pitch.rise <= 0.5 * PEAK_TOLERANCE, pitch
    assert kernel_r2(ds, model)["Pitch"] >= 0.9


def test_a_kernel_miss_is_a_failure_that_names_it(corpus):
    """The MHK RM1's yaw damping at its last frequency (62.8 rad/s) is 43 % of its peak, one
    point (WAMIT's T = 0.1 s) between values of 10⁻⁶ of it: the data's K(0) holds that
    triangle, which no model follows. R² of K(t) below 0.9 (measured 0.66 on the
    scoreboard), and a failure says so, naming yaw and K(0) (exit status 3 of
    `cummins fit`)."""
    ds, model = _fit(corpus / "ROSCO" / "wamit_MHK_RM1_floating" / "MHK_RM1_Floating.1")
    failures = model.attrs["failures"]
    for dof, value in kernel_r2(ds, model).items():
        if value < 0.9:
            assert any(f.startswith(f"{dof}: R² of K(t)") and "K(0)" in f for f in failures)
    assert kernel_r2(ds, model)["Yaw"] < 0.9


def test_the_kernel_target_is_an_option():
    """``r2_kernel``: a target out of reach is a failure per diagonal (the tanker at
    0.99999: measured ≤ 0.9995), ``None`` none; out of (0, 1) a FitError."""
    ds = cummins.demo_dataset()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        strict = fit_radiation(ds, r2_kernel=0.99999)
        off = fit_radiation(ds, r2_kernel=None)
    named = [f for f in strict.attrs["failures"] if "R² of K(t)" in f]
    assert named and all(f.split(":")[0] in strict.dofs for f in named)
    assert not [f for f in off.attrs["failures"] if "R² of K(t)" in f]
    with pytest.raises(FitError, match="r2_kernel"):
        fit_radiation(ds, r2_kernel=1.5)


def test_cummins_fit_exits_3_on_a_kernel_miss(tmp_path):
    """The command line: --r2-kernel out of reach, the failure printed, exit status 3."""
    from cummins.cli import main

    result = CliRunner().invoke(
        main,
        [
            "fit",
            str(cummins.demo_files() / "tanker.1"),
            "-o",
            str(tmp_path / "m.nc"),
            "--r2-kernel",
            "0.99999",
        ],
    )
    assert result.exit_code == 3, result.output
    assert "R² of K(t)" in result.output and "failure" in result.output


def test_targets_not_met_says_which_and_whether_it_matters():
    """The note of a block no count brings to its targets names the target (the R² of
    which coupling, with its value and target) and says whether the motions show it."""
    score = BlockScore(
        {(0, 0): (0.995, 0.97), (0, 1): (0.98, 0.99), (1, 1): (0.999, 0.999)},
        0.02,
        0.004,
        True,
    )
    labels = ("body2__Roll", "body2__Pitch")
    note = targets_not_met(16, score, r2=0.99, r2_coupling=0.97, motion_aim=0.008, labels=labels)
    assert "R² of B of body2__Roll 0.9700 < 0.99" in note
    assert "kept 16" in note and "the motions meet their aim" in note
    assert "body2__Pitch" not in note  # only what misses
    missed = BlockScore(score.r2, 0.02, 0.03, True)  # 2.75 aims over, R² of B 2 allowed
    note = targets_not_met(16, missed, r2=0.99, r2_coupling=0.97, motion_aim=0.008, labels=labels)
    assert note.index("motion error 3.00 %") < note.index("R² of B")  # the worst first
    assert "the RAOs show it" in note
    note = targets_not_met(16, score, r2=0.99, r2_coupling=0.97, labels=labels)
    assert "no motions to judge it by" in note


def test_a_real_note_names_its_target():
    """On real data: a block whose targets no count meets says which (the S-175's heave
    added mass at its last frequency is not causal with a decaying damping: R² of A of
    heave, and the motions meet their aim)."""
    _, model = _fit(cummins.demo_files().parent / "s175" / "s175.mat")
    notes = [n for n in model.attrs["data_notes"] if "targets not met" in n]
    assert notes and all("R² of" in n or "motion error" in n for n in notes)
    assert any("R² of A of Heave" in n and "costs nothing the RAOs show" in n for n in notes)


def test_the_rise_is_the_checks_and_names_its_lowest_point():
    """:func:`rise_after_top`, the check's peak of its own (and the motion refinement's
    bound on it): at each point after the largest value, b_k − min over top ≤ m ≤ k of
    b_m (brute force), 0 before; ``low_at`` names the first m of that minimum (damping
    rounded to whole numbers: ties); :func:`damping_beyond_data`'s ``rise`` is its
    largest value over the data's peak, at that point's frequency."""
    rng = np.random.default_rng(4)
    w = np.geomspace(1.0, 10.0, 60)
    for _ in range(30):
        b = np.round(np.cumsum(rng.normal(size=60)) + 2 * rng.normal(size=60))
        rise, low_at = rise_after_top(b)
        top = int(np.argmax(b))
        for k in range(60):
            if k < top:
                assert rise[k] == 0.0 and low_at[k] == k
            else:
                assert rise[k] == b[k] - b[top : k + 1].min()
                assert low_at[k] == top + int(np.argmin(b[top : k + 1]))
        found = damping_beyond_data(b, w, 2.0)
        assert found.rise == rise.max() / 2.0
        if rise.max() > 0:
            assert found.peak_omega == w[int(np.argmax(rise))]
