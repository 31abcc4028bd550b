"""Diagnostics: each check fires on data that break it, and stays quiet on data that don't."""

from __future__ import annotations

import json

import numpy as np
import pytest

import cummins
import cummins.kinematics
from cummins.hydrodb import make_hydrodb


def _clean_dataset(n_omega=80):
    """A passive, causal 6-DOF database: K(s) = Σ_m R_m s/(s² + 2ζ_m ω_m s + ω_m²) with
    symmetric positive semidefinite R_m, so B = Re K(jω) ≥ 0 and A = A∞ + Im K(jω)/ω."""
    w = np.r_[np.linspace(0.05, 2.0, n_omega // 2), np.geomspace(2.1, 15.0, n_omega // 2)]
    rng = np.random.default_rng(3)
    s = 1j * w[:, None, None]
    k = np.zeros((w.size, 6, 6), dtype=complex)
    for zeta, w0 in ((0.4, 0.6), (0.3, 1.1), (0.5, 1.8)):
        q = rng.normal(size=(6, 6))
        k += (s / (s**2 + 2 * zeta * w0 * s + w0**2)) * (q @ q.T + np.eye(6)) * 1e3
    q = rng.normal(size=(6, 6))
    a_inf = q @ q.T * 1e3 + 6e3 * np.eye(6)
    return make_hydrodb(
        w,
        a_inf + k.imag / w[:, None, None],
        k.real,
        rho=1025,
        g=9.81,
        source_format="arrays",
        added_mass_inf=a_inf,
        inertia_matrix=cummins.kinematics.rigid_body_inertia(
            1e4, [1.0, 0.0, -0.5], [3e4, 5e4, 5e4]
        ),
        hydrostatic_stiffness=np.diag([0, 0, 1e5, 2e5, 3e6, 0.0]),
    )


def test_clean_data_passes():
    report = cummins.check(_clean_dataset())
    assert report.ok
    assert report.worst() == "ok", report.to_text()


def test_negative_damping_is_located():
    ds = _clean_dataset()
    ds.radiation_damping[40, 3, 3] = -0.3 * float(ds.radiation_damping[:, 3, 3].max())
    report = cummins.check(ds)
    found = [f for f in report.by_check("damping_positive") if f.severity == "warning"]
    roll = [f for f in found if f.where == "Roll"]
    assert roll and "1 of 80" in roll[0].message
    assert f"{float(ds.omega[40]):.4g} rad/s" in roll[0].message
    assert roll[0].value == pytest.approx(-0.3, rel=1e-6)
    # The matrix test finds it too, at that frequency, mostly in roll.
    matrix = [f for f in found if f.where and "rad/s" in f.where]
    assert matrix and "Roll" in matrix[0].message


def test_indefinite_damping_without_negative_diagonal():
    """B can have positive diagonals and still be indefinite: eigenvalues catch it."""
    ds = _clean_dataset()
    k = 30
    b = ds.radiation_damping.values[k]
    b[2, 4] = b[4, 2] = 3 * np.sqrt(b[2, 2] * b[4, 4])
    report = cummins.check(ds)
    matrix = [f for f in report.by_check("damping_positive") if f.severity == "warning"]
    assert len(matrix) == 1 and "Heave" in matrix[0].message and "Pitch" in matrix[0].message


@pytest.mark.parametrize(
    ("roll", "severity"),
    [(-4e-8, "info"), (-1.34e-11, "info"), (-2e4, "warning"), (-1.0, "warning")],
)
def test_a_restoring_term_negative_by_round_off_is_zero(roll, severity):
    """Capytaine writes a submerged body's C33 or C44 as −1e-11 (its quadrature's
    round-off): zero, not a statically unstable body; a negative term above the round-off
    (1 N·m/rad against a C55 of 3 MN·m/rad) is still one."""
    ds = _clean_dataset()
    ds["hydrostatic_stiffness"][3, 3] = roll
    found = [f for f in cummins.check(ds).by_check("hydrostatics") if f.where == "Roll"]
    assert [f.severity for f in found] == [severity], found
    if severity == "warning":
        assert "statically unstable" in found[0].message
    else:
        assert "is zero" in found[0].message


def test_damping_indefinite_within_the_noise_says_what_fit_does():
    """B(ω) with a scaled eigenvalue of −5e-4 at one frequency (below the check's noise,
    1e-3): ok, as before, but the line says that ``fit`` takes the nearest positive
    semidefinite damping there (a two-body buoy: check "positive semidefinite", fit "not
    positive semi-definite at 40 frequencies", and nothing tied the two)."""
    from cummins.check.common import _diag_scale

    ds = _clean_dataset()
    b = ds.radiation_damping.values
    s = _diag_scale(b)
    k = 30
    scaled = b[k] * s[:, None] * s[None, :]
    lam, vec = np.linalg.eigh(scaled)
    largest = np.linalg.eigvalsh(b * s[None, :, None] * s[None, None, :])[:, -1].max()
    scaled += (-5e-4 * largest - lam[0]) * np.outer(vec[:, 0], vec[:, 0])
    b[k] = scaled / (s[:, None] * s[None, :])
    (found,) = cummins.check(ds).by_check("damping_positive")
    assert found.severity == "ok" and found.value == pytest.approx(-5e-4, rel=1e-3)
    assert "`cummins fit` takes the nearest positive semidefinite damping" in found.message
    (clean,) = cummins.check(_clean_dataset()).by_check("damping_positive")
    assert clean.value > 0 and "nearest" not in clean.message


def test_asymmetry_and_added_mass_inf_errors():
    ds = _clean_dataset()
    ds.added_mass.values[:, 1, 5] *= 1.5
    ds.added_mass_inf.values[3, 3] = -ds.added_mass_inf.values[3, 3]
    report = cummins.check(ds)
    sym = [f for f in report.by_check("symmetry") if f.severity == "warning"]
    assert sym and sym[0].where == "Sway-Yaw"
    assert not report.ok
    assert any(f.severity == "error" for f in report.by_check("added_mass_inf"))


def test_forward_speed_skips_symmetry():
    ds = _clean_dataset().assign_coords(forward_speed=5.0)
    ds.added_mass.values[:, 1, 5] *= 1.5
    report = cummins.check(ds)
    assert all(f.severity == "info" for f in report.by_check("symmetry"))


def test_undecayed_damping_and_copied_dof():
    ds = _clean_dataset()
    ds = ds.isel(omega=slice(0, 20))  # stops at ω ≈ 1 rad/s: B has not decayed
    ds.added_mass.values[:, 0, 0] = 0.25 * ds.added_mass.values[:, 1, 1]
    ds.radiation_damping.values[:, 0, 0] = 0.5 * ds.radiation_damping.values[:, 1, 1]
    report = cummins.check(ds)
    assert any(f.severity == "warning" for f in report.by_check("damping_decay"))
    copied = report.by_check("copied_dof")
    assert copied and copied[0].where == "Surge-Sway" and "0.25" in copied[0].message


def test_identical_bodies_placed_symmetrically_are_not_copies():
    """A row of three identical buoys has the same diagonal A and B on the outer two (their
    mirror images): fine, and said so, not "strip-theory codes approximate surge by
    scaling sway" (as it read on a Capytaine array of three buoys). A DOF of another
    body scaled by a factor other than 1 is still named, without strip theory."""
    from cummins.check.artefacts import copied_dofs

    one = _clean_dataset()
    a, b = one.added_mass.values, one.radiation_damping.values
    n = a.shape[0]
    a3, b3 = np.zeros((n, 18, 18)), np.zeros((n, 18, 18))
    for k in range(3):
        block = slice(6 * k, 6 * k + 6)
        scale = 1.1 if k == 1 else 1.0  # the middle buoy differs (its neighbours)
        a3[:, block, block], b3[:, block, block] = scale * a, scale * b
    dofs = [f"body{k + 1}__{d}" for k in range(3) for d in cummins.DOF_NAMES]
    ds = make_hydrodb(one.omega.values, a3, b3, rho=1025, g=9.81, source_format="arrays", dofs=dofs)
    found = {f.where: f for f in copied_dofs(ds)}
    outer = found["body1__Surge-body3__Surge"]
    assert outer.severity == "ok" and "identical bodies placed symmetrically" in outer.message
    middle = found["body1__Surge-body2__Surge"]
    assert middle.severity == "info" and "0.9091" in middle.message
    assert "strip-theory" not in middle.advice
    assert all("strip-theory" not in (f.advice or "") for f in found.values())


def test_tanker_facts(tanker_wamit):
    """The figures the identification issue measured on the WAMIT tanker, found by check:
    each diagonal damping's most negative value relative to its peak, min B_ii / max|B_ii|,
    computed here from the data (heave −0.56, roll −0.41, pitch −0.34, yaw −0.19, surge
    −0.034, sway −0.015: irregular frequencies above 3.6 rad/s), and nothing else per DOF."""
    report = cummins.check(tanker_wamit)
    negative = {
        f.where: f.value
        for f in report.by_check("damping_positive")
        if f.severity == "warning" and f.where in cummins.DOF_NAMES
    }
    w = tanker_wamit.omega.values
    expected = {}
    for dof in cummins.DOF_NAMES:
        b = tanker_wamit.radiation_damping.sel(influenced_dof=dof, radiating_dof=dof).values
        if b.min() < 0:
            expected[dof] = b.min() / np.abs(b).max()
            assert w[b < 0].min() > 3.6, dof  # only where WAMIT's irregular frequencies are
    assert set(negative) == set(expected)
    for dof, value in expected.items():
        assert negative[dof] == pytest.approx(value, rel=1e-12), dof
    assert expected["Heave"] < expected["Roll"] < expected["Pitch"] < -0.3  # issue's figures
    # WAMIT's .frc mass matrix lacks the sway-yaw term m·x_g: not a rigid body.
    rigid = [f for f in report.by_check("inertia") if f.severity == "warning"]
    assert rigid and "M[Sway, Yaw]" in rigid[0].message
    assert report.ok  # usable, with warnings


def test_report_formats(tanker_wamit):
    report = cummins.check(tanker_wamit)
    data = json.loads(report.to_json())
    assert data["ok"] is True and data["worst"] == "warning"
    assert {"check", "severity", "message", "where", "value", "advice"} <= set(data["findings"][0])
    text = report.to_text()
    assert "WARNING damping_positive [Heave]" in text and "Result: usable" in text


def test_wave_parity_flags_the_mss_drift_tables(shared_data):
    """Wave forces of a port/starboard symmetric hull mirror with the heading (sway, roll,
    yaw change sign). MSS's processed S-175 and supply structs store a yaw drift moment
    that does not (the raw `driftfrc.amp{3}` is the same at 90° and 270°): flagged with
    the DOF and the headings; the excitation of the same files mirrors, and so does the
    WAMIT tanker's."""
    stored = {"drift_as_stored": True}  # read mirrors them by default (test_check_parity)
    s175 = cummins.check(cummins.read(shared_data / "mss" / "s175" / "s175.mat", **stored))
    flagged = [f for f in s175.by_check("wave_parity") if f.severity == "warning"]
    assert any(f.where == "Yaw" and "drift_force" in f.message for f in flagged)
    assert not any("excitation_force" in f.message for f in flagged)
    supply = cummins.check(cummins.read(shared_data / "mss" / "supply" / "supply.mat", **stored))
    assert [f.where for f in supply.by_check("wave_parity") if f.severity == "warning"] == ["Yaw"]
    tanker = cummins.check(cummins.demo_dataset())
    assert [f.severity for f in tanker.by_check("wave_parity")] == ["ok"]


def test_a_sharp_resonance_is_told_from_an_irregular_frequency(corpus):
    """check names the MHK RM1's surge points at 2.0–2.2 rad/s, which the spike test
    flags, as a sharp resonance (A follows B: Kramers–Kronig), and calls none of the PEND
    hull's irregular-frequency spikes one."""
    from cummins.check.artefacts import _check_suspect_frequencies

    ds = cummins.read(corpus / "ROSCO" / "wamit_MHK_RM1_floating" / "MHK_RM1_Floating.1")
    sharp = [f for f in _check_suspect_frequencies(ds) if "sharp resonance" in f.message]
    assert [f.where for f in sharp] == ["Surge"] and sharp[0].severity == "info"
    assert all(1.9 < x < 2.3 for x in sharp[0].details["omega"])
    pend = cummins.read(corpus / "WEC-Sim" / "aqwa_19.1_PEND_hull" / "19_1.AH1")
    found = _check_suspect_frequencies(pend)
    assert any(f.severity == "warning" for f in found)
    assert not [f for f in found if "sharp resonance" in f.message]


@pytest.mark.parametrize(
    ("case", "verdicts"),
    [
        # AQWA's floating OWC: 0.75 and 0.59 of C33 (its RAOs in long waves the same)
        (
            "WEC-Sim_Applications/aqwa_floating_OWC_AH1only/floatingOWC.AH1",
            {"body1__Heave": "warning", "body2__Heave": "warning"},
        ),
        # the RM3 (WAMIT): 1.000 and 0.985; the tanker (WAMIT, MSS) 0.993
        ("WEC-Sim/wamit_RM3_2body/rm3.1", {"body1__Heave": "ok", "body2__Heave": "ok"}),
    ],
)
def test_long_wave_heave_excitation_is_the_restoring(corpus, case, verdicts):
    """|F₃| → C33 = ρ g A_wp as ω → 0 (Newman (1977) §6.17): the check compares them
    where the lowest frequency is a long wave for the body, and names the DOF whose
    excitation and restoring do not describe one body."""
    import warnings

    from cummins.check.waves import LONG_WAVE_TOL, long_wave_heave_ratios

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(corpus / case)
    found = {f.where: f for f in cummins.check(ds).by_check("long_wave_limit")}
    assert {where: f.severity for where, f in found.items()} == verdicts
    for label, (ratio, _) in long_wave_heave_ratios(ds).items():
        assert (abs(ratio - 1) > LONG_WAVE_TOL) == (verdicts[label] == "warning")
        if verdicts[label] == "warning":
            assert abs(ratio - 1) > 2 * LONG_WAVE_TOL  # 0.75, 0.59: far from the bound
            assert "C33" in found[label].message and found[label].advice
        else:
            assert abs(ratio - 1) < 0.5 * LONG_WAVE_TOL


def test_wave_parity_at_a_heading_that_is_its_own_mirror(shared_data):
    """The S-175's yaw drift made large in following seas (0°, its own mirror heading):
    the finding says it should be 0 there, not that 0° and 0° differ."""
    ds = cummins.read(shared_data / "mss" / "s175" / "s175.mat").isel(forward_speed=0)
    ds = ds.copy(deep=True)
    f = ds.drift_force
    yaw = {"wave_direction": 0.0, "influenced_dof": "Yaw"}
    f.loc[yaw] = f.loc[yaw] + 10.0 * float(np.abs(f.sel(influenced_dof="Yaw")).max())
    flagged = [x for x in cummins.check(ds).by_check("wave_parity") if x.severity == "warning"]
    assert [x.where for x in flagged] == ["Yaw"]
    assert "at 0°, its own mirror heading, it should be 0" in flagged[0].message


def test_one_check_judges_the_suspect_frequencies_once(monkeypatch):
    """Each DOF's suspect frequencies (suspects_by_dof, ~30-50 ms a dataset) were found
    three times per check of the S-175 at zero speed (the suspect_frequencies check, the
    mean drift's drift_suspect, the fit reciprocity prepares) and twice at each other
    speed; now once per speed, shared, with the same findings as each check on its own."""
    import importlib

    from cummins.check.artefacts import _check_suspect_frequencies
    from cummins.check.second_order import _check_second_order

    ds = cummins.read(cummins.demo_files().parent / "s175" / "s175.mat")  # 5 speeds, drift
    assert ds.sizes["forward_speed"] == 5 and "drift_force" in ds
    repair = importlib.import_module("cummins.repair")
    original, computed = repair.suspects_by_dof, []

    def recording(data, judged=()):
        if not any(known is data or known.identical(data) for known, _ in judged):
            computed.append(data)  # not among the data judged already: found again
        return original(data, judged) if judged else original(data)

    for name in ("repair", "check", "check.artefacts", "radiation.fit.data"):
        module = importlib.import_module(f"cummins.{name}")  # where it is called from
        monkeypatch.setattr(module, "suspects_by_dof", recording, raising=False)
    report = cummins.check(ds)
    monkeypatch.undo()
    assert len(computed) == 5
    for i, one in enumerate(computed):
        assert not any(one.identical(other) for other in computed[i + 1 :]), i
    for name, alone in (
        ("suspect_frequencies", _check_suspect_frequencies(ds)),
        ("drift_suspect", [f for f in _check_second_order(ds) if f.check == "drift_suspect"]),
    ):
        assert list(report.by_check(name)) == alone
        assert alone
