"""Issue 16's targets for the default identification, on real data of several solvers.

Every measure is recomputed here from the model and the data, never read from the fit's
own flags: R² of A and B from K̂(jω) (``diagonal_r2``), passivity by a dense sweep of
λ_min(K + Kᴴ) in the test itself, the motion-RAO error from ``motion_rao`` against
``Vessel.response``. Each case is fitted once (module-scoped fixture). Timings are in
``benchmarks/bench_identification.py``, not here.

Measured on this machine (2026-12-02, third session), default fit (common poles per
block), RAO error with 2 % of critical damping; identical orders and values to four
digits with 1 and 2 BLAS threads and under OpenBLAS's Sandybridge kernel (the
two-body float and spar from Capytaine: tests/test_fit_reciprocity.py):

==========================  =====  =======  =======  ========  ================
case                        order  R² A     R² B     RAO err.  common poles
==========================  =====  =======  =======  ========  ================
MSS tanker (WAMIT)          42     0.9948   0.9959   0.54 %    7, 7
MSS supply (ShipX)          44     0.9965   0.9937   0.30 %    5, 7, 9
MSS S-175 (U = 0)           41     0.9933   0.9914   0.61 %    4, 7, 8
WEC-Sim cylinder (NEMOH)    24     0.9919   0.9916   0.26 %    6, 4, 4
WEC-Sim sphere (Capytaine)  22     0.9958   0.9931   0.66 %    4, 4, 6
AQWA floating OWC (12 DOF)  30     0.9935   0.9942   0.33 %    4, 4, 7
NEMOH OC3 Hywind spar       23     0.9916   0.9908   0.14 %    5, 4, 5
WAMIT barge, 4 beam modes   90     0.9953   0.9942   0.55 %    9, 4, 14, 4
WAMIT sphere (mean drift)   46     0.9878   0.9928   0.77 %    8, 7, 5, 11
Capytaine COER (tank)       70     0.9952   0.9769   0.77 %    20, 10, 6, 4
AQWA PEND hull (tank)       51     0.9946   0.9900   1.72 %    12, 12, 3
Capytaine semisub ¹         64     0.9988   0.9949   0.37 %    6, 6, 4, 4
Capytaine 3 buoys (18 DOF)¹ 243    0.9942   0.9915   0.95 %    19, 12
==========================  =====  =======  =======  ========  ================

¹ Computed with Capytaine for what the corpus lacks (added 2026-12-03):
``tests/data/semisub_capytaine.nc`` (``tests/data/make_semisub.py``), an OC4-like
semisubmersible with its inertia, roll and pitch resonant at 0.29 rad/s and heave at
0.36 rad/s where the radiation damping is nearly zero (the corpus's semis carry no
inertia, so no motions); ``tests/data/three_buoys_capytaine.nc``
(``tests/data/make_three_buoys.py``), a row of three identical buoys, three bodies in
one model.

Two figures are set by the data, not the fit: the PEND hull's 1.72 % is at 11.07 rad/s,
one of its irregular frequencies (heave damping spikes at 10.7–11.3 rad/s, left out of
the fit, kept by the scorecard's comparison; on the fitted frequencies the motion error
is 0.38 %), and COER's pitch R² of B 0.9769 comes from irregular-frequency spikes at
23–31 rad/s (10–35 % of the peak damping) that the suspect filter does not flag and that
no broadband model follows.

The tolerances are the issue's limits: the RAO error never above 2 % (≥ 2.5× margin
on every case but the PEND hull, whose margin is set by its data as said), every
modelled diagonal R² ≥ 0.98 (COER pitch B excepted, as said: ≥ 0.97).

WEC-Sim's RM3 (WAMIT, two bodies, with WEC-Sim's mass properties; added 2026-12-04, issue
30) is not reciprocal beyond what the motions allow and is fitted as given: passive, not
within 1 %: its spar's surge and pitch added mass are 85 % and 97 % off the Kramers–Kronig
transform of their damping with the data's ω = ∞ row, which no causal model follows and
the failure names. With that row the motion error is 14.1 %; the A∞ of the DOFs that miss
their motions for that reason is estimated with the model instead, the row kept for the
others (:mod:`cummins.radiation.fit.causal_inf`): 3.7 %, and 0.40 % once its residues are
refined on its motions, which the default does since they miss their target (its tests
here fit it without: ``refine_motions=False``). Its tests are at the end.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import cummins
from _synthetic import wecsim_rm3
from cummins.errors import FitError
from cummins.hydrodb import dof_matrix
from cummins.radiation.fit import PREVIOUS_DEFAULT, fit_radiation
from cummins.radiation.fit.frequency import r_squared
from cummins.radiation.fit.scorecard import data_frequencies, diagonal_r2, motion_rao_error
from cummins.radiation.passivity import passivity_test
from cummins.radiation.reduce import reduce_radiation_model

SHARED = {
    "tanker": "mss/tanker/tanker.1",
    "supply": "mss/supply/supply.mat",
    "s175": "mss/s175/s175.mat",
    "cylinder": "wecsim/cylinder/cylinder_nemoh/cylinder_hydrodynamics.nc",
    "sphere": "wecsim/sphere/sphere_hydrodynamics.nc",
}
CORPUS = {
    "floating_owc": "WEC-Sim_Applications/aqwa_floating_OWC_AH1only/floatingOWC.AH1",
    "oc3_spar": "WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar",
    "gbm_barge": "WEC-Sim_Applications/wamit_generalized_modes_barge/barge.1",
    "drift_sphere": "WEC-Sim_Applications/wamit_mean_drift_sphere/outputFiles",
    "coer": "WEC-Sim/capytaine_COER_comp/outputs/coer_comp_hydrodynamics.nc",
    "pend_hull": "WEC-Sim/aqwa_19.1_PEND_hull/19_1.AH1",
}
#: Cases computed for the tests (tests/data), with their inertia.
GENERATED = {"semisub": "semisub_capytaine.nc", "three_buoys": "three_buoys_capytaine.nc"}
#: Diagonal R² floors other than 0.98, with the reason in the module docstring.
R2_FLOOR = {"coer": 0.97}
#: DOFs whose data are numerical noise, not radiation: the WAMIT sphere's yaw (a sphere
#: radiates no yaw; |B| ≤ 7.8·10⁻⁸ N·m·s against 3.3·10³ N·s in surge, and rising at the
#: last frequency). Modelled (its damping is not negligible against the other rotations',
#: themselves noise), it cannot be followed inside the data by a model that decays beyond
#: them (issue 31; before, a peak 1.55× the data's beyond them): not judged by the
#: targets, but its misses must be failures that name it, never silent.
NOISE = {"drift_sphere": ("Yaw",)}


def _read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(path)
    if "forward_speed" in ds.dims:
        ds = ds.sel(forward_speed=0.0)
    return ds


@pytest.fixture(scope="module", params=[*SHARED, *CORPUS, *GENERATED])
def fitted(request, shared_data):
    name = request.param
    if name in GENERATED:
        path = Path(__file__).parent / "data" / GENERATED[name]
    elif name in SHARED:
        path = shared_data / SHARED[name]
    else:
        path = shared_data / "corpus" / CORPUS[name]
    assert path.exists(), f"{path} is not there"  # the shared data are required
    ds = _read(path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = fit_radiation(ds)
    return name, ds, model


def _dense_passivity_margin(model) -> float:
    """min over 4000 log-spaced ω (10⁻⁴…10² rad/s) of λ_min(K + Kᴴ), relative to max ‖K‖."""
    w = np.geomspace(1e-4, 1e2, 4000)
    k = model.response(w)
    lam = np.linalg.eigvalsh(k + np.conj(np.swapaxes(k, 1, 2)))[:, 0]
    return float(lam.min() / np.linalg.norm(k, ord=2, axis=(1, 2)).max())


def test_the_default_model_is_stable_and_passive(fitted):
    """Target 2: every pole in the left half-plane, λ_min(K + Kᴴ) ≥ −10⁻⁶ max‖K‖ on a grid
    denser and wider than the scorecard's (measured ≥ −3·10⁻⁹ on every case), and the
    exact test (crossings of the imaginary axis, limits) passes."""
    name, _, model = fitted
    poles = np.linalg.eigvals(model.A)
    assert np.all(poles.real < 0), name
    assert _dense_passivity_margin(model) >= -1e-6, name
    # no passivity step took a coupling below its target, and the model says it is passive
    noise = NOISE.get(name, ())
    passivity = [
        f for f in model.attrs["failures"] if "passiv" in f and f.split(":")[0] not in noise
    ]
    assert not passivity, (name, passivity)
    assert passivity_test(model).passive, name


def test_the_default_model_reproduces_the_motion_raos(fitted):
    """Target 1: the motion-RAO error (2 % critical damping, 4 headings) never above 2 %
    (measured: module docstring)."""
    name, ds, model = fitted
    error = motion_rao_error(ds, model)
    assert error.error <= 0.02, (name, error.worst_dof, error.worst_omega, error.per_dof)


def test_the_default_model_fits_every_diagonal(fitted):
    """R² of A and of B of every modelled diagonal, recomputed against the data, ≥ 0.98
    (measured ≥ 0.9877; COER: module docstring)."""
    name, ds, model = fitted
    floor = R2_FLOOR.get(name, 0.98)
    for dof, (r2a, r2b) in diagonal_r2(ds, model).items():
        if dof in NOISE.get(name, ()):  # noise: a miss is a failure naming it
            if min(r2a, r2b) < floor:
                assert any(f.startswith(f"{dof}:") for f in model.attrs["failures"]), dof
            continue
        assert r2a >= floor and r2b >= floor, (name, dof, r2a, r2b)


#: Corpus cases with the solver's ω = ∞ row and finite frequencies that reach where the
#: damping has decayed: A∞ of the default fit without the row, against it (measured
#: 2026-12-03, eighth session: OWC 0.08 %, generalized-mode barge 0.11 %, OC3 spar
#: 0.008 %, OC4 semi 0.034 %, COER 0.52 %, WaveBot 0.44 %, Wavestar 0.17 %, WEC3 0.03 %,
#: plate 0.04 %, MHK RM1 0.81 %, ITI barge 0.83 %). Not here, for their margin to 2 %:
#: the WAMIT sphere (1.03 %), the COER `.frc` form 2 (1.31 %), the 2015 WAMIT OSWEC
#: (1.60 %); and the cases whose data end before the damping decays or contradict the row
#: (BENCHMARKS.md, identification).
ADDED_MASS_INF_CASES = {
    "floating_owc": "WEC-Sim_Applications/aqwa_floating_OWC_AH1only/floatingOWC.AH1",
    "gbm_barge": "WEC-Sim_Applications/wamit_generalized_modes_barge/barge.1",
    "oc3_spar": "WEIS/ss_fitting_OC3_spar",
    "oc4_semi": "WEIS/ss_fitting_OC4_semi",
    "coer": "WEC-Sim/wamit_COER_comp",
    "wavebot": "WEC-Sim_Applications/wamit_WaveBot",
    "wavestar": "WEC-Sim_Applications/wamit_wavestar_NMPC_with_h5",
    "wec3": "bemio/wamit_WEC3_single_body",
    "plate": "bemio/wamit_plate_24headings",
    # a surge resonance at 2 rad/s that the spike test flags and Kramers-Kronig keeps
    # (3.6 % when Ogilvie's prior left it out)
    "mhk_rm1": "ROSCO/wamit_MHK_RM1_floating/MHK_RM1_Floating.1",
    # irregular frequencies in every DOF above 2.8 rad/s (1.7 % when the prior took only
    # the frequencies where every DOF is sound)
    "iti_barge": "ROSCO/wamit_ITI_barge_5MW_Baseline/Barge.1",
}


@pytest.mark.parametrize("case", list(ADDED_MASS_INF_CASES))
def test_added_mass_inf_from_the_finite_frequencies(corpus, case):
    """Target 2's A∞: the default fit of the data without their ω = ∞ row, its A∞ within
    2 % of that row on every modelled diagonal (``added_mass_inf_error``; a DOF whose A∞ is
    below 10⁻³ of the largest of its kind, the yaw of an axisymmetric body, against that
    scale)."""
    from cummins.radiation.fit.scorecard import added_mass_inf_error

    ds = _read(corpus / ADDED_MASS_INF_CASES[case])
    assert "added_mass_inf" in ds
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = fit_radiation(ds.drop_vars("added_mass_inf"))
    error = added_mass_inf_error(ds, model)
    assert error is not None and error <= 0.02, (case, error)


@pytest.mark.parametrize("vessel", ["tanker", "supply", "s175"])
def test_better_motions_than_the_previous_default(shared_data, vessel):
    """The default's RAO error is at most half the previous default's (measured: tanker
    0.55 vs 6.01 %, supply 0.31 vs 3.15 %, S-175 0.33 vs 4.65 %)."""
    ds = _read(shared_data / SHARED[vessel])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        new = motion_rao_error(ds, fit_radiation(ds)).error
        old = motion_rao_error(ds, fit_radiation(ds, **PREVIOUS_DEFAULT)).error
    assert new <= 0.5 * old, (new, old)


@pytest.mark.parametrize("vessel", ["tanker", "supply"])
def test_a_tighter_motion_target_never_gives_worse_motions(shared_data, vessel):
    """``MOTION_ACCURACY`` (``--accurate``) weighs the motions more, and passivity can cost
    such fits more: on the supply vessel its heave-pitch block was 0.55 % at 10 common
    poles against the default's 0.29 % at 9. A block the tighter fit leaves further from
    its targets than the default's fit keeps the default's (measured by the scorecard,
    2 % damping: supply 0.29 % at 50 states against the default's 0.30 % at 44; tanker
    0.14 % against 0.54 %)."""
    from cummins.radiation.fit import MOTION_ACCURACY

    ds = _read(shared_data / SHARED[vessel])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        default = motion_rao_error(ds, fit_radiation(ds)).error
        accurate_model = fit_radiation(ds, MOTION_ACCURACY)
    accurate = motion_rao_error(ds, accurate_model).error
    assert accurate <= 1.1 * default, (accurate, default)
    if vessel == "tanker":  # where the data allow it, the tighter target buys motions
        assert accurate <= 0.5 * default, (accurate, default)
    assert not [f for f in accurate_model.attrs["failures"] if "motion" in f]


def test_an_inconsistent_infinite_frequency_row_is_not_used(corpus):
    """AQWA's "100 rad/s" added mass of the PEND hull (52.1 kg in surge where A(18.8 rad/s)
    is 2.2 kg and Ogilvie's estimate 3.4 kg) contradicts the finite frequencies: the fit
    says so and estimates A∞ instead; with the row forced in, no model of surge reaches
    R² 0 (measured −299), with it estimated R² of A ≥ 0.98 (measured 0.998, identification
    only)."""
    ds = _read(corpus / "WEC-Sim" / "aqwa_19.1_PEND_hull" / "19_1.AH1")
    from cummins.radiation.fit import inconsistent_added_mass_inf
    from cummins.radiation.retardation import added_mass_inf

    estimate = added_mass_inf(ds.drop_vars("added_mass_inf"), method="ogilvie")
    spread = np.maximum(estimate.spread.values, 0.005 * np.abs(estimate.values))
    found = inconsistent_added_mass_inf(ds, estimate.values, spread)
    assert any(item.startswith("Surge 52.1") for item in found), found


def test_asymmetric_pairs_are_named():
    """A_ij ≠ A_ji beyond 10 %: the warning names the pair and both values."""
    from cummins.errors import CumminsWarning

    ds = cummins.demo_dataset()
    a = ds.added_mass.copy()
    a.loc[{"influenced_dof": "Surge", "radiating_dof": "Pitch"}] *= -1.0
    with pytest.warns(CumminsWarning, match=r"A\[Surge, Pitch\] = .* but A\[Pitch, Surge\]"):
        model = fit_radiation(ds.assign(added_mass=a), passivity="diagonal")
    assert any("A[Surge, Pitch]" in note for note in model.attrs["data_notes"])
    # a flipped sign is what a mixed-up convention gives: the advice names it
    said = [note for note in model.attrs["data_notes"] if "A[Surge, Pitch]" in note]
    assert all("check the DOF order and signs" in note for note in said), said


def test_asymmetry_of_one_sign_is_not_blamed_on_a_sign_convention(shared_data):
    """HAMS's benchmark cylinder: B[Surge, Pitch] and B[Pitch, Surge] differ (−234 and
    −303 at 5.42 rad/s, as HAMS wrote them in Buoy.1) but share their sign: the solver's
    asymmetry, which cummins check calls so, not a DOF order or sign mixed up."""
    from cummins.radiation.fit.reciprocity import asymmetric_pairs

    ds = cummins.read(shared_data / "corpus" / "HAMS" / "Cylinder")
    said = asymmetric_pairs(ds)
    assert any(
        m.startswith("B[Surge, Pitch] = -233.61 but B[Pitch, Surge] = -303.28") for m in said
    )
    assert said and all("the solver's own asymmetry" in m for m in said), said
    assert not any("check the DOF order" in m for m in said)


@pytest.mark.parametrize(
    "case",
    [
        SHARED["supply"],
        # fitted to its passive part (repair.nearest_passive_damping): that path too
        "corpus/HAMS/Cylinder/Output_Benchmark/Wamit_format/Buoy.1",
        # three bodies, 18 DOFs: a 9-DOF block and its passivity programme
        "three_buoys",
    ],
)
def test_the_fit_does_not_depend_on_blas_threads(shared_data, case):
    """Target 5: the same blocks, numbers of common poles, orders and R² (to 10⁻⁶) with 1
    and 2 BLAS threads."""
    import threadpoolctl

    if case in GENERATED:
        ds = _read(Path(__file__).parent / "data" / GENERATED[case])
    else:
        ds = _read(shared_data / case)
    results = []
    for threads in (1, 2):
        with threadpoolctl.threadpool_limits(threads), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = fit_radiation(ds)
        results.append(
            (
                [(b.dofs, b.order) for b in model.blocks],
                [
                    (
                        k.influenced,
                        k.radiating,
                        k.metrics["common_poles"],
                        k.metrics["r2_added_mass"],
                        k.metrics["r2_damping"],
                    )
                    for k in model.modelled
                ],
            )
        )
    assert results[0][0] == results[1][0] and results[0][0]
    assert len(results[0][1]) == len(results[1][1]) > 0
    for one, two in zip(results[0][1], results[1][1], strict=True):
        assert one[:3] == two[:3]
        assert one[3] == pytest.approx(two[3], abs=1e-6) and one[4] == pytest.approx(
            two[4], abs=1e-6
        )


# ----------------------------------------------------------------------------- RM3
# WEC-Sim's two-body RM3 (WAMIT's own run, ``corpus/WEC-Sim/wamit_RM3_2body``), the data
# as they are: A(1,7) = 44.9 but A(7,1) = −14.7 in its ``.out`` (not reciprocal), and the
# spar's roll and pitch added mass 98 % off the Kramers–Kronig transform of their damping
# with its ω = ∞ row (not causal). Its couplings are fitted as given
# (:mod:`cummins.radiation.fit.reciprocity`): the motion error 4.8 % against 30.6 % for the
# reciprocal fit of before (measured 2026-12-04), the rest named as the data's.


@pytest.fixture(scope="module")
def rm3(shared_data):
    """WEC-Sim's RM3 (WAMIT ``.out``, ρ = 1000) with its mass properties, and its fit
    without the motion refinement (``refine_motions=False``: what the weighted fit of K
    gives and the limit it names; the default refines it on its motions, 0.40 %:
    ``tests/test_motion_refinement.py``)."""
    ds = wecsim_rm3(shared_data)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return ds, fit_radiation(ds, refine_motions=False)


#: The couplings of RM3 whose both directions matter (ranges of A_ij and A_ji ≥ 40 % of
#: √(range A_ii range A_jj)), and the smallest R² of A and of B, each direction,
#: measured: surge–pitch 0.967/0.978 (A), 0.877/0.818 (B); float–spar surge 0.961/0.905,
#: 0.974/0.970 (0.214/0.551 of A with the data's ω = ∞ row for the spar's non-causal
#: surge); float–spar heave 0.983/0.989, 0.990/0.989.
RM3_PAIRS = (("body1__Surge", "body1__Pitch"), ("body1__Surge", "body2__Surge"),
             ("body1__Heave", "body2__Heave"))  # fmt: skip


def test_rm3_couplings_are_fitted_each_as_given(rm3):
    """Each direction of RM3's main couplings is reproduced (R² ≥ 0.67: the measured
    ≥ 0.81 with over half its 1 − R² to spare), where their reciprocal part cannot be (its
    R² against the two directions of the float–spar surge added mass: below 0.5) — the
    float–spar surge added mass too (0.96 and 0.91), now that the spar's surge A∞, whose
    added mass is 85 % off the Kramers–Kronig transform of its damping with the data's
    row, is estimated with the model (with the row: 0.21 and 0.55)."""
    ds, model = rm3
    keep = np.flatnonzero(data_frequencies(ds))
    w = ds.omega.values[keep]
    a = dof_matrix(ds, "added_mass")[keep]
    b = dof_matrix(ds, "radiation_damping")[keep]
    k, inf, labels = model.response(w), model.added_mass_inf, model.dofs
    for one, two in RM3_PAIRS:
        assert f"{one}-{two}" in model.attrs["couplings_as_given"]
        i, j = labels.index(one), labels.index(two)
        for p, q in ((i, j), (j, i)):
            assert r_squared(a[:, p, q], inf[p, q] + k[:, p, q].imag / w) >= 0.67
            assert r_squared(b[:, p, q], k[:, p, q].real) >= 0.67
    (failure,) = [f for f in model.attrs["failures"] if f.startswith("motion error")]
    assert "body2__Surge" in failure and "Kramers–Kronig" in failure
    # a data limit that is not measured is not claimed as one
    assert "the data may limit it" in failure and "not measured" in failure
    i, j = labels.index("body1__Surge"), labels.index("body2__Surge")
    average = 0.5 * (a[:, i, j] + a[:, j, i])
    assert min(r_squared(a[:, i, j], average), r_squared(a[:, j, i], average)) < 0.5


def test_rm3_is_passive(rm3):
    """Target 2 on RM3: stable, passive by the exact test and by a dense sweep of
    λ_min(K + Kᴴ) (this module's, measured ≥ −10⁻¹⁷)."""
    _, model = rm3
    assert np.all(np.linalg.eigvals(model.A).real < 0)
    assert passivity_test(model).passive
    assert _dense_passivity_margin(model) >= -1e-6


def test_rm3_motions_and_the_limit_named(rm3):
    """The motion error against the data's own RAOs: 3.7 % measured, against 14.1 % with
    the data's ω = ∞ row for every DOF (``added_mass_inf="data"``, which keeps it) and
    30.6 % for the reciprocal fit before (its reciprocal part alone: 26.7 %); not 1 %: the
    spar's pitch added mass is still 82 % off the Kramers–Kronig transform of its damping
    with the A∞ estimated, which the failure names. The A∞ estimated is that of the DOFs
    that missed their motions for that reason (the spar's surge and pitch, the float's
    pitch); every other DOF keeps the solver's row exactly. (A fit that put damping beyond
    the data, before issue 31, reached 4.8 % with a K(t) of the float's surge nothing like
    the data's: R² −4.9.)"""
    ds, model = rm3
    error = motion_rao_error(ds, model).error
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with_row = fit_radiation(ds, added_mass_inf="data", refine_motions=False)
    assert "added_mass_inf_estimated" not in with_row.attrs
    assert error < 0.5 * motion_rao_error(ds, with_row).error  # 3.7 % against 14.1 %
    assert error < 0.5 * model.attrs["reciprocal_motion_error_floor"]
    estimated = model.attrs["added_mass_inf_estimated"]
    assert {"body2__Surge", "body2__Pitch"} <= set(estimated)
    row = dof_matrix(ds, "added_mass_inf")
    labels = list(model.dofs)
    for d, label in enumerate(labels):
        if label not in estimated and label.split("__")[1] in ("Surge", "Heave", "Pitch"):
            assert model.added_mass_inf[d, d] == pytest.approx(row[d, d], rel=1e-12)
    spar_pitch = labels.index("body2__Pitch")
    assert model.added_mass_inf[spar_pitch, spar_pitch] != pytest.approx(
        row[spar_pitch, spar_pitch], rel=1e-3
    )
    notes = [n for n in model.attrs["data_notes"] if n.startswith("A∞ of")]
    assert notes and "body2__Pitch" in notes[0] and "with the row" in notes[0]
    failure = [f for f in model.attrs["failures"] if f.startswith("motion error")]
    assert failure and "Kramers–Kronig" in failure[0] and "body2__Pitch" in failure[0]
    assert "estimated for" in failure[0]


def test_the_check_says_what_the_fit_does(rm3):
    """``cummins check`` on RM3: a ``reciprocity`` warning naming the couplings fitted as
    given and the motion error of the reciprocal part."""
    ds, _ = rm3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        found = cummins.check(ds).by_check("reciprocity")
    assert found and found[0].severity == "warning"
    assert "body1__Surge-body2__Surge" in found[0].details["couplings_as_given"]
    assert found[0].value > 0.2  # 26.7 % measured
    assert "as given" in found[0].advice


def test_rm3_reduce_is_refused_cleanly(rm3):
    """Its one block is fitted as given: a total order below its states is refused with
    the number it keeps."""
    _, model = rm3
    with pytest.raises(FitError, match=str(model.blocks[0].order)):
        reduce_radiation_model(model, order=model.total_order - 10)
