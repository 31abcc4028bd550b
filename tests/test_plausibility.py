"""The plausibility check (issue 31): the relations every floating body keeps hold on
every real run (no false alarm), and a quantity scaled by 10^±3 or of the wrong sign —
which reads as numbers like any other — breaks one of them: ``cummins check`` calls
the data unusable and ``cummins.read`` warns.

The relations are measured first on data no one here wrote: Newman's (Haskind) relation
between the excitation and the damping on the MSS tanker (WAMIT, 36 headings) and
Kramers–Kronig between A(ω) and B(ω) on the tanker and the WEC-Sim sphere.
"""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
import scipy.io

import cummins
from cummins.check.plausibility import (
    haskind_ratio,
    kramers_kronig_scale,
    plausibility_findings,
)

SHARED_SETS = (
    "mss/tanker/tanker.1",
    "mss/tanker/tanker.mat",
    "mss/supply/supply.mat",
    "mss/s175/s175.mat",
    "wecsim/sphere/sphere_hydrodynamics.nc",
    "wecsim/cylinder/cylinder_nemoh/cylinder_hydrodynamics.nc",
    "wecsim/cylinder_aqwa/cylinder.LIS",
)


def _read(path):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = cummins.read(path)
    return ds, [str(w.message) for w in caught if issubclass(w.category, cummins.HydroDataWarning)]


def test_newman_relation_holds_on_the_tanker_over_the_whole_circle(shared_data):
    """MSS's tanker.mat holds 36 headings over 360°: the radiated energy equals the
    excitation's, k/(8πρg c_g)∫|X|²dβ = B, within 5 % for every DOF where B is large."""
    ds = cummins.read(shared_data / "mss/tanker/tanker.mat")
    ratio = haskind_ratio(ds)
    b = np.diagonal(ds.radiation_damping.transpose("omega", ...).values, axis1=1, axis2=2)
    for k, dof in enumerate(ds.influenced_dof.values):
        strong = b[:, k] > 0.1 * b[:, k].max()
        median = float(np.median(ratio.values[strong, k]))
        assert abs(median - 1.0) < 0.05, (dof, median)


@pytest.mark.parametrize("case", ["mss/tanker/tanker.1", "wecsim/sphere/sphere.out"])
def test_kramers_kronig_scale_is_one_on_consistent_data(shared_data, case):
    ds = cummins.read(shared_data / case)
    kk = kramers_kronig_scale(ds)
    for dof in ("Surge", "Heave", "Pitch"):
        assert abs(float(kk.scale.sel(influenced_dof=dof)) - 1.0) < 0.05, dof
        assert float(kk.correlation.sel(influenced_dof=dof)) > 0.99, dof


def _cases(root: Path) -> list[Path]:
    corpus = sorted(p for p in (root / "corpus").glob("*/*") if p.is_dir())
    return corpus + [root / c for c in SHARED_SETS]


def test_no_false_alarm_on_any_real_run(shared_data):
    """Every corpus case and shared file set that reads: no plausibility error or warning,
    and no read warning from it (the bounds leave a factor >= 10 to every one of them:
    benchmarks/bench_plausibility.py)."""
    checked = 0
    for path in _cases(shared_data):
        try:
            ds, messages = _read(path)
        except cummins.CumminsError:
            continue  # the two cases refused with a message (corpus README)
        alarms = [f for f in plausibility_findings(ds) if f.severity != "ok"]
        assert not alarms, (path, [f.message for f in alarms])
        assert not [m for m in messages if "plausib" in m or "Kramers" in m], (path, messages)
        checked += 1
    assert checked >= 35


def _write_variant(ds, tmp_path, name, **scaled):
    out = ds.copy(deep=True)
    for var, factor in scaled.items():
        if var == "omega":
            out = out.assign_coords(omega=out.omega * factor)
        else:
            out[var] = out[var] * factor
    path = tmp_path / f"{name}.nc"
    cummins.write(out, path)
    return path


@pytest.mark.parametrize(
    ("scaled", "fragment"),
    [
        ({"inertia_matrix": 1e-3}, "disagree: m/(ρ A_wp^1.5)"),
        ({"added_mass": 1e-3}, "times as much as B(ω) implies"),
        ({"radiation_damping": 1e3}, "times as much as B(ω) implies"),
        ({"excitation_force": 1e3}, "excitation and the damping disagree"),
        ({"added_mass": -1.0}, "varies opposite to what B(ω) implies"),
        ({"hydrostatic_stiffness": -1.0}, "C33 = -"),
        ({"omega": 1e3}, "no solver computes such a range"),
    ],
)
def test_a_scaled_or_negated_quantity_is_an_error_and_warns_on_reading(
    shared_data, tmp_path, scaled, fragment
):
    """The WEC-Sim sphere (Capytaine NetCDF, with its inertia): each damage makes `check`
    refuse the data with a plausibility error, and reading the file warns."""
    ds = cummins.read(shared_data / "wecsim/sphere/sphere_hydrodynamics.nc")
    path = _write_variant(ds, tmp_path, "damaged", **scaled)
    damaged, messages = _read(path)
    assert any(fragment in m for m in messages), messages
    report = cummins.check(damaged)
    assert not report.ok
    errors = [f.message for f in report.findings if f.severity == "error"]
    assert any(fragment in m for m in errors), errors


def _mss_variant(shared_data, tmp_path, name, edit):
    content = scipy.io.loadmat(shared_data / "mss/tanker/tanker.mat")
    edit(content["vessel"][0, 0])
    path = tmp_path / f"{name}.mat"
    scipy.io.savemat(path, {"vessel": content["vessel"]})
    return path


def _excitation_times(factor):
    def edit(vessel):
        amplitudes = vessel["forceRAO"][0, 0]["amp"]
        for k in range(amplitudes.size):
            amplitudes.flat[k] = amplitudes.flat[k] * factor

    return edit


@pytest.mark.parametrize(
    ("name", "edit", "fragment"),
    [
        ("negated_A", lambda v: v.__setitem__("A", -v["A"]), "varies opposite"),
        ("excitation_1e295", _excitation_times(1e295), "beyond any floating body"),
        ("frequencies_1e300", lambda v: v.__setitem__("freqs", v["freqs"] * 1e300), "wave"),
    ],
)
def test_damaged_mss_structs_warn_and_check_refuses_them_without_a_traceback(
    shared_data, tmp_path, name, edit, fragment
):
    """Issue 31: an MSS struct with every added mass negated, excitation of 10^300, or
    frequencies x 10^300 read silently, and `check` crashed on the last."""
    path = _mss_variant(shared_data, tmp_path, name, edit)
    ds, messages = _read(path)
    assert any(fragment in m for m in messages), messages
    report = cummins.check(ds)
    assert not report.ok
    assert any(fragment in f.message for f in report.findings if f.severity == "error")


def test_a_negative_external_damping_is_an_error(shared_data):
    ds = cummins.read(shared_data / "mss/tanker/tanker.1")
    labels = [str(d) for d in ds.influenced_dof.values]
    extra = np.zeros((len(labels), len(labels)))
    extra[3, 3] = -2e9  # the .frc gives 1.56e9: the sum is negative
    ds = cummins.with_external_terms(ds, damping=extra)
    errors = [f for f in cummins.check(ds).findings if f.severity == "error"]
    assert [f.where for f in errors if "external damping" in f.message] == ["Roll"]


def _tanker_copy(shared_data, tmp_path) -> Path:
    run = tmp_path / "tanker"
    shutil.copytree(shared_data / "mss/tanker", run)
    for f in run.iterdir():
        f.chmod(0o644)
    return run


def test_a_hst_cut_in_its_first_line_is_damage_not_a_zero_restoring(shared_data, tmp_path):
    """Cut to '     1     1   0.000', the .hst reads as a 1x1 matrix of zeros: the rest
    of the run's restoring would have been silent zeros."""
    run = _tanker_copy(shared_data, tmp_path)
    hst = run / "tanker.hst"
    hst.write_text(hst.read_text()[:18])
    ds, messages = _read(run / "tanker.1")
    assert any("tanker.hst" in m and "1×1 matrix, the run has 6 modes" in m for m in messages)
    assert "hydrostatic_stiffness" not in ds


def test_a_negative_external_damping_in_a_frc_is_damage(shared_data, tmp_path):
    """tanker.frc's external damping B11 = 410000 negated: the .frc is not read (a
    warning names the line), instead of a damping that feeds the ship."""
    run = _tanker_copy(shared_data, tmp_path)
    frc = run / "tanker.frc"
    lines = frc.read_text().splitlines()
    k = lines.index("410000.00 0.00 0.00 0.00 0.00 0.00")
    lines[k] = lines[k].replace("410000.00", "-410000.00", 1)
    frc.write_text("\n".join(lines) + "\n")
    ds, messages = _read(run / "tanker.1")
    assert any(
        f"tanker.frc, line {k + 1}: the external damping of mode 1 is negative" in m
        for m in messages
    ), messages
    assert float(ds.additional_damping.values.min()) >= 0 if "additional_damping" in ds else True


@pytest.mark.parametrize(
    ("case", "change", "fragment"),
    [
        ("hams-buoy3-empty", "Output_Benchmark/Wamit_format/Buoy.3", "no wave excitation"),
        ("hams-hydrostatic-missing", "Input/Hydrostatic.in", "HAMS reads it for every run"),
        ("nemoh-kh-missing", "Mesh/KH.dat", "no hydrostatic restoring"),
    ],
)
def test_an_empty_or_missing_companion_file_warns(shared_data, tmp_path, case, change, fragment):
    """Issue 31: a whole quantity dropped without a word, where the truncated file warns."""
    source = {
        "hams": "corpus/HAMS/Cylinder",
        "nemoh": "corpus/WEC-Sim/nemoh_v3.0.2_COER_comp",
    }[case.split("-")[0]]
    run = tmp_path / "run"
    shutil.copytree(shared_data / source, run)
    target = run / change
    target.chmod(0o644)
    if "empty" in case:
        target.write_bytes(b"")
    else:
        target.unlink()
    _, messages = _read(run)
    assert any(fragment in m for m in messages), messages
