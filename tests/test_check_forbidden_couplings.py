"""The ``forbidden_couplings`` check on real data: the radiation couplings a body's own
symmetry forbids, judged from the data, where ``cummins fit`` would model them.

HAMS's truncated cylinder (its benchmark output and pyHAMS's test truth) has the
diagonals and wave forces of a body of revolution, yet roll–pitch, heave–roll,
sway–pitch and surge–roll couplings of 4–14 % of the diagonals; the other solvers'
bodies of revolution, the ships and the barge keep theirs below the fit's threshold.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import cummins
from cummins.check.forbidden_couplings import (
    FIT_THRESHOLD,
    _check_forbidden_couplings,
    body_symmetry,
)
from cummins.radiation.fit.options import DEFAULT

HAMS = (
    "corpus/HAMS/Cylinder/Output_Benchmark/Wamit_format/Buoy.1",
    "corpus/pyHAMS/Cylinder_headings/truth/Buoy.1",
)

#: Sound bodies of the corpus and the symmetry the data show: (mirror, rotational).
SOUND = {
    # its roll and pitch (about the centre: nothing but noise) 3.4 % apart
    "corpus/WEC-Sim_Applications/wamit_mean_drift_sphere": (True, None),
    "wecsim/sphere/sphere.out": (True, True),
    "wecsim/cylinder/cylinder_nemoh/cyl.1": (True, True),
    "corpus/WEIS/ss_fitting_OC3_spar": (True, True),
    "corpus/WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar": (True, True),
    "corpus/WEC-Sim_Applications/wamit_WaveBot": (True, True),
    "corpus/WEC-Sim_Applications/wamit_monopile": (True, True),
    "corpus/ROSCO/wamit_ITI_barge_5MW_Baseline": (True, True),
    "mss/tanker/tanker.1": (True, False),
    "mss/supply/input.re7": (True, False),
    "mss/s175/s175.mat": (True, False),
}


def _read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path)


def _by_body(ds):
    return {f.where: f for f in _check_forbidden_couplings(ds)}


def test_the_threshold_is_the_fits():
    assert DEFAULT.threshold == FIT_THRESHOLD


@pytest.mark.parametrize("name", HAMS)
def test_the_hams_cylinders_couplings_that_axisymmetry_forbids_are_named(shared_data, name):
    """Diagonals of a body of revolution (surge/sway, roll/pitch within 0.6 %), wave forces
    of one at every heading (0.5 %), but roll–pitch 14 % (A's range, as the fit measures
    it), heave–roll and sway–pitch 4.5–4.8 %, surge–roll 3.9 %: a warning naming those
    four, the block of five DOFs the fit makes of them and a --threshold that leaves them
    out; the couplings the symmetry keeps (surge–pitch, sway–roll) are not named."""
    ds = _read(shared_data / name)
    [finding] = _check_forbidden_couplings(ds)
    assert finding.severity == "warning"
    details = finding.details
    assert details["symmetry"] == "axisymmetric"
    assert details["rotation_asymmetry"] < 0.015  # 0.006
    assert details["mirror_asymmetry"] < 0.015  # the forces: 0.005, 0.0035
    assert set(details["costly"]) == {"Roll–Pitch", "Heave–Roll", "Sway–Pitch", "Surge–Roll"}
    assert 0.1 < details["costly"]["Roll–Pitch"] < 0.2  # 0.14
    assert all(0.02 < details["costly"][p] < 0.08 for p in ("Heave–Roll", "Surge–Roll"))
    assert details["fit_block"] == "Surge, Sway, Heave, Roll, Pitch"
    assert details["threshold_leaving_them_out"] > details["costly"]["Roll–Pitch"]
    assert "Roll–Pitch 14 %" in finding.message and "--threshold 0.15" in finding.advice
    # the threshold it advises leaves them out of the fit's couplings
    from cummins.radiation.retardation import significant_couplings

    labels = [str(d) for d in ds.influenced_dof.values]
    kept = significant_couplings(ds, details["threshold_leaving_them_out"], either=True)
    assert {(labels[i], labels[j]) for i, j in kept if i != j} == {
        ("Surge", "Pitch"),
        ("Sway", "Roll"),
    }


def test_the_hams_cylinder_without_its_noise_passes(shared_data):
    """The same data with the forbidden couplings set to zero: the symmetry is still
    found, nothing is flagged (the check judges the couplings, not the file)."""
    ds = _read(shared_data / HAMS[0])
    keep = np.zeros((6, 6), bool)
    keep[np.diag_indices(6)] = True
    keep[0, 4] = keep[4, 0] = keep[1, 3] = keep[3, 1] = True
    for name in ("added_mass", "radiation_damping"):
        ds[name] = ds[name].where(_mask(ds[name], keep), 0.0)
    [finding] = _check_forbidden_couplings(ds)
    assert finding.severity == "ok" and finding.details["symmetry"] == "axisymmetric"
    assert finding.value < 1e-12


def _mask(da, keep):
    """``keep`` over the (influenced_dof, radiating_dof) dims of ``da``."""
    import xarray as xr

    return xr.DataArray(
        keep,
        dims=("influenced_dof", "radiating_dof"),
        coords={"influenced_dof": da.influenced_dof, "radiating_dof": da.radiating_dof},
    )


@pytest.mark.parametrize("name", sorted(SOUND))
def test_sound_symmetric_bodies_are_not_flagged(shared_data, name):
    """WAMIT's, NEMOH's bodies of revolution, the OC3 spars, WaveBot, the monopile, the
    ITI barge (square: the same zeros), the MSS ships: the symmetry found as the data
    show it, and no forbidden coupling the fit would model."""
    ds = _read(shared_data / name)
    findings = _check_forbidden_couplings(ds)
    assert findings and all(f.severity == "ok" for f in findings)
    sub = ds.isel(forward_speed=0) if "forward_speed" in ds.dims else ds
    symmetry = body_symmetry(sub, None)
    mirror, rotational = SOUND[name]
    assert symmetry.mirror == mirror
    assert rotational is None or symmetry.rotational == rotational
    assert findings[0].value < FIT_THRESHOLD


def _inject(ds, p, q, size):
    """A coupling p–q of ``size`` times the geometric mean of the diagonals, in A (its
    range) and B (its peak), reciprocal."""
    ds = ds.copy(deep=True)
    labels = [str(d) for d in ds.influenced_dof.values]
    i, j = labels.index(p), labels.index(q)
    for name, measure in (("added_mass", np.ptp), ("radiation_damping", lambda x: np.abs(x).max())):
        x = ds[name].transpose("omega", "influenced_dof", "radiating_dof").values.copy()
        scale = np.sqrt(measure(x[:, i, i]) * measure(x[:, j, j]))
        shape = x[:, i, i] / measure(x[:, i, i]) * size * scale
        x[:, i, j] = x[:, j, i] = shape
        ds[name] = (("omega", "influenced_dof", "radiating_dof"), x)
    return ds


@pytest.mark.parametrize(
    ("name", "pair"),
    [
        ("wecsim/cylinder/cylinder_nemoh/cyl.1", ("Roll", "Pitch")),  # rotation forbids it
        ("wecsim/cylinder/cylinder_nemoh/cyl.1", ("Surge", "Heave")),
        ("mss/tanker/tanker.1", ("Heave", "Roll")),  # the mirror forbids it
    ],
)
def test_an_injected_forbidden_coupling_is_a_warning_only_above_the_fits_threshold(
    shared_data, name, pair
):
    """A coupling the symmetry forbids put into clean data: 5 % of the diagonals is
    named (the fit would model it), 0.3 % is not (it would not)."""
    ds = _read(shared_data / name)
    big = _check_forbidden_couplings(_inject(ds, *pair, 0.05))
    assert [f.severity for f in big] == ["warning"]
    assert list(big[0].details["costly"]) == ["–".join(pair)]
    assert big[0].details["costly"]["–".join(pair)] == pytest.approx(0.05, rel=1e-6)
    small = _check_forbidden_couplings(_inject(ds, *pair, 0.003))
    assert [f.severity for f in small] == ["ok"]


def test_a_coupling_the_symmetry_keeps_is_not_named(shared_data):
    """Surge–pitch and sway–roll belong to a body of revolution (A₁₅ = −A₂₄): however
    large, they are not forbidden; surge–roll is."""
    ds = _read(shared_data / "wecsim/cylinder/cylinder_nemoh/cyl.1")
    symmetry = body_symmetry(ds, None)
    assert symmetry.forbids("Surge", "Pitch") is None
    assert symmetry.forbids("Sway", "Roll") is None
    assert symmetry.forbids("Surge", "Roll") is not None
    assert symmetry.forbids("Heave", "Yaw") is not None


def test_a_body_that_is_not_symmetric_has_nothing_to_rule_out(shared_data):
    """The WEC3 (three flaps meshed as one body): diagonals 99 % apart and wave forces
    that do not mirror: no symmetry, one ok finding."""
    ds = _read(shared_data / "corpus/bemio/wamit_WEC3_single_body")
    [finding] = _check_forbidden_couplings(ds)
    assert (
        finding.severity == "ok" and "no port/starboard or rotational symmetry" in finding.message
    )


def test_without_excitation_the_diagonals_alone_judge(shared_data):
    """The OC4 semisubmersible's .1 (its .3 missing): rotationally symmetric from its
    diagonals (3 columns: the 6×6 matrices of a body of revolution), the mirror not
    judged, so surge–roll and heave–yaw are not ruled out; nothing the fit models."""
    ds = _read(shared_data / "corpus/WEIS/ss_fitting_OC4_semi")
    symmetry = body_symmetry(ds, None)
    assert symmetry.rotational and not symmetry.mirror
    assert symmetry.forbids("Surge", "Roll") is None
    assert symmetry.forbids("Roll", "Pitch") is not None
    [finding] = _check_forbidden_couplings(ds)
    assert finding.severity == "ok"


def test_multibody_cases_are_judged_per_body(shared_data):
    """The NEMOH cubes side by side: each port/starboard symmetric (their diagonals 5–8 %
    apart: not rotational), nothing flagged; the RM3 float: its coaxial system's
    symmetry found, nothing the fit models. The RM3 spar/plate's heave–roll (A's range
    8 % of its diagonals, a heave added mass that hardly varies) is one the fit models."""
    cubes = _by_body(_read(shared_data / "corpus/WEC-Sim/nemoh_v3.0.2_Cubes_2body"))
    assert set(cubes) == {"body1", "body2"}
    assert all(
        f.severity == "ok" and f.details["symmetry"] == "port/starboard symmetric"
        for f in cubes.values()
    )
    rm3 = _by_body(_read(shared_data / "corpus/WEC-Sim/wamit_RM3_2body"))
    assert set(rm3) == {"body1", "body2"}
    assert rm3["body1"].severity == "ok"
    assert rm3["body2"].severity == "warning"
    assert list(rm3["body2"].details["costly"]) == ["Heave–Roll"]


def test_wavestars_couplings_are_a_plane_of_symmetry_off_y_0(shared_data):
    """WECCCOMP's Wavestar float (WAMIT): heave–roll 6 %, roll–pitch 5.7 %, surge–yaw
    2.4 % of the diagonals, and A₃₄/A₃₃ = −A₁₆/A₁₁ = A₄₅/A₃₅ = −0.00117 at every
    frequency: the moved moments of a port/starboard symmetric body whose plane is at
    y = −1.17 mm. The finding says so; the data moved onto that plane (the screw
    transform of cummins.move_reference_point, not the check's own arithmetic) pass."""
    from cummins.hydrodb import move_reference_point

    ds = _read(shared_data / "corpus/WEC-Sim_Applications/wamit_wavestar_NMPC_with_h5")
    [finding] = _check_forbidden_couplings(ds)
    assert finding.severity == "warning"
    assert set(finding.details["costly"]) >= {"Heave–Roll", "Roll–Pitch", "Surge–Yaw"}
    y = finding.details["symmetry_plane_y"]
    assert y == pytest.approx(-0.00117, abs=2e-5)
    assert "plane of symmetry is y = -0.001174" in finding.message
    point = np.asarray(ds.attrs["reference_point"], float).copy()
    point[1] = y
    [moved] = _check_forbidden_couplings(move_reference_point(ds, point))
    assert moved.severity == "ok" and moved.value < 0.002  # 0.038 %


def test_a_coupling_the_bodys_own_asymmetry_explains_is_an_info(shared_data):
    """NEMOH's cylinder with its surge diagonal made 1.5 % larger than sway's (still
    rotational, ε = 1.5 %): a surge–heave coupling of 2 % is modelled by the fit but
    within 2ε (an info); one of 5 % is beyond it (a warning)."""
    ds = _read(shared_data / "wecsim/cylinder/cylinder_nemoh/cyl.1")
    for name in ("added_mass", "radiation_damping"):
        scale = _ones(ds[name])
        scale.loc[{"influenced_dof": "Surge", "radiating_dof": "Surge"}] = 1.015
        ds[name] = ds[name] * scale
    symmetry = body_symmetry(ds, None)
    assert symmetry.rotational and 0.01 < symmetry.rotation_asymmetry < 0.02
    explained = _check_forbidden_couplings(_inject(ds, "Surge", "Heave", 0.02))
    assert [f.severity for f in explained] == ["info"]
    assert "Surge–Heave 2 %" in explained[0].message
    beyond = _check_forbidden_couplings(_inject(ds, "Surge", "Heave", 0.05))
    assert [f.severity for f in beyond] == ["warning"]


def _ones(da):
    """Ones over the (influenced_dof, radiating_dof) dims of ``da``."""
    return _mask(da, np.ones((da.sizes["influenced_dof"], da.sizes["radiating_dof"]))).astype(float)


def test_check_prepares_the_fit_once_for_its_checks(shared_data, monkeypatch):
    """``cummins.check`` prepares the data as the fit would once per speed, for the
    reciprocity and the forbidden-couplings checks alike (0.15 s each on a 12-DOF run):
    on the HAMS cylinder, whose forbidden couplings are large enough for both to ask,
    one preparation, and those checks' findings are the ones each gives alone."""
    import cummins.radiation.fit.data as fit_data
    from cummins.check.reciprocity import _check_reciprocity

    ds = _read(shared_data / HAMS[0])
    alone = _check_reciprocity(ds) + _check_forbidden_couplings(ds)
    calls = []
    prepare = fit_data.prepare_fit

    def counted(*args, **kwargs):
        calls.append(args[0])
        return prepare(*args, **kwargs)

    monkeypatch.setattr(fit_data, "prepare_fit", counted)
    report = cummins.check(ds)
    assert len(calls) == 1
    shared = [f for f in report.findings if f.check in ("reciprocity", "forbidden_couplings")]
    assert [(f.check, f.severity, f.message) for f in shared] == [
        (f.check, f.severity, f.message) for f in alone
    ]
