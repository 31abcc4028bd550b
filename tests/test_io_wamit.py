"""WAMIT reader: numeric files against the .out log, MSS's processed struct, physics."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

import cummins
from cummins import HydroDataError
from cummins.seakeeping.frequency_domain import motion_rao


@pytest.fixture(scope="module")
def tanker_dir(shared_data):
    return shared_data / "mss" / "tanker"


@pytest.fixture(scope="module")
def tanker_out(tanker_dir):
    return cummins.read(tanker_dir / "tanker.out")


def test_numeric_files_agree_with_out_log(tanker_wamit, tanker_out):
    """.1/.3/.hst and the .out are independent printouts of one run (WAMIT 6.3)."""
    ds, out = tanker_wamit, tanker_out
    assert ds.attrs["source_format"] == "wamit"
    assert out.attrs["source_format"] == "wamit-out"
    np.testing.assert_array_equal(ds.omega, out.omega)
    # The .1 and the .out print A and B with the same 7 significant digits.
    for name in ("added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero"):
        np.testing.assert_allclose(ds[name], out[name], rtol=1e-6, atol=0, err_msg=name)
    # The .out prints C(i,j) with 5 significant digits ("10222.", "0.92149E+06").
    c, c_out = ds.hydrostatic_stiffness.values, out.hydrostatic_stiffness.values
    np.testing.assert_allclose(c_out, c, rtol=5e-5, atol=1e-9 * np.abs(c).max())
    # Excitation: moduli to 7 digits, phases in whole degrees in the .out.
    x, x_out = ds.excitation_force.values, out.excitation_force.values
    big = np.abs(x) > 1e-4 * np.abs(x).max(axis=(0, 1), keepdims=True)
    np.testing.assert_allclose(np.abs(x_out)[big], np.abs(x)[big], rtol=1e-6)
    phase_error = np.degrees(np.abs(np.angle(x_out[big] / x[big])))
    assert phase_error.max() <= 0.5 + 1e-6


def test_zero_and_infinite_frequency_rows(tanker_wamit, tanker_dir):
    """PER = -1 is ω = 0 and PER = 0 is ω = ∞: compare with the raw rows of the .1 file."""
    rows = np.loadtxt(tanker_dir / "tanker.1", usecols=(0, 1, 2, 3), max_rows=36)
    rho = 1025.0
    for period, name in ((-1.0, "added_mass_zero"), (0.0, "added_mass_inf")):
        for per, i, j, a in rows[rows[:, 0] == period]:
            value = float(
                tanker_wamit[name].isel(influenced_dof=int(i) - 1, radiating_dof=int(j) - 1)
            )
            length_power = 3 + (i > 3) + (j > 3)
            assert value == pytest.approx(a * rho * 1.0**length_power, rel=1e-12), (per, i, j)
    assert 0.0 not in tanker_wamit.omega.values
    assert np.all(np.isfinite(tanker_wamit.omega))


def test_tanker_agrees_with_mss_processed_struct(tanker_wamit, tanker_dir):
    """MSS's own wamit2vessel output for the same files (Fossen axes, ρ = 1025, g = 9.80665)."""
    mss = cummins.read(tanker_dir / "tanker.mat")
    ours = cummins.change_axes(tanker_wamit, "z-down")
    assert mss.attrs["axis_convention"] == "z-down"
    np.testing.assert_allclose(ours.reference_point, mss.reference_point, atol=1e-9)
    common = np.intersect1d(np.round(ours.omega.values, 10), np.round(mss.omega.values, 10))
    assert common.size == ours.omega.size
    for name in ("added_mass", "radiation_damping"):
        a = ours[name].values
        b = mss[name].sel(omega=ours.omega.values, method="nearest").values
        scale = np.abs(a).max(axis=0, keepdims=True)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-6 * scale.max(), err_msg=name)
    for name in ("added_mass_inf", "added_mass_zero"):
        np.testing.assert_allclose(ours[name], mss[name], rtol=1e-6, atol=1e-6, err_msg=name)
    c = ours.hydrostatic_stiffness.values
    np.testing.assert_allclose(
        mss.hydrostatic_stiffness.values, c, rtol=1e-5, atol=1e-6 * np.abs(c).max()
    )
    # Excitation magnitude on the headings WAMIT computed (MSS mirrors them to 360°).
    x = ours.excitation_force
    y = mss.excitation_force.sel(wave_direction=x.wave_direction, method="nearest")
    np.testing.assert_allclose(
        np.abs(y.sel(omega=x.omega, method="nearest")),
        np.abs(x),
        rtol=1e-6,
        atol=1e-6 * float(np.abs(x).max()),
    )


def test_units_and_mass_consistency(tanker_wamit):
    """ρ∇ equals the mass in the .frc; C33 equals ρ g A_wp with A_wp = C̄33 L²."""
    ds = tanker_wamit
    assert ds.attrs["rho"] == 1025.0
    assert ds.attrs["g"] == pytest.approx(9.80665)
    mass = float(ds.inertia_matrix.sel(influenced_dof="Surge", radiating_dof="Surge"))
    assert mass == pytest.approx(ds.attrs["rho"] * ds.attrs["displaced_volume"], rel=2e-4)
    c33 = float(ds.hydrostatic_stiffness.sel(influenced_dof="Heave", radiating_dof="Heave"))
    assert c33 == pytest.approx(1025.0 * 9.80665 * 1.022150e4, rel=1e-6)
    # Long waves: the heave force tends to the hydrostatic force C33 per metre.
    x3 = np.abs(ds.excitation_force.sel(influenced_dof="Heave").isel(omega=0)).values
    np.testing.assert_allclose(x3, c33, rtol=0.01)


def test_constants_and_length_scale(tanker_dir):
    """Given ρ, g, ULEN rescale the nondimensional data as WAMIT defines it."""
    base = cummins.read(tanker_dir / "tanker.1")
    scaled = cummins.read(tanker_dir / "tanker.1", rho=1000.0, g=9.81, ulen=2.0)
    k = np.array([0, 0, 0, 1, 1, 1])
    a_ratio = (1000.0 / 1025.0) * 2.0 ** (3 + k[:, None] + k[None, :])
    np.testing.assert_allclose(scaled.added_mass_inf, base.added_mass_inf * a_ratio, rtol=1e-12)
    np.testing.assert_allclose(
        scaled.radiation_damping, base.radiation_damping * a_ratio, rtol=1e-12
    )
    f_ratio = (1000.0 * 9.81 / (1025.0 * 9.80665)) * 2.0 ** (2 + k)
    np.testing.assert_allclose(scaled.excitation_force, base.excitation_force * f_ratio, rtol=1e-12)
    assert "given" in scaled.attrs["history"]


def test_rho_default_is_recorded_when_unknown(shared_data, tmp_path):
    """WAMIT 7 does not print ρ: the default is used and said in the history."""
    ds = cummins.read(shared_data / "wecsim" / "sphere" / "sphere.1")
    assert ds.attrs["rho"] == 1025.0
    assert "default" in ds.attrs["history"]
    assert ds.attrs["g"] == 9.81  # printed in sphere.out
    assert ds.attrs["water_depth"] == 50.0
    # The body origin is ZBODY = -2 m below the free surface: the reference point.
    np.testing.assert_allclose(ds.attrs["reference_point"], [0.0, 0.0, -2.0])


def test_version7_header_lines(shared_data):
    """WAMIT 7 numeric files start with a title line; the cylinder reads."""
    ds = cummins.read(shared_data / "wecsim" / "cylinder" / "cylinder_nemoh" / "cyl.1", rho=1000.0)
    assert ds.sizes["omega"] > 100
    assert "added_mass_inf" in ds and "hydrostatic_stiffness" in ds
    assert ds.attrs["water_depth"] == 3.0


def test_siblings_option(tanker_dir):
    ds = cummins.read(tanker_dir / "tanker.1", siblings=False)
    assert "excitation_force" not in ds and "hydrostatic_stiffness" not in ds
    assert ds.attrs["rho"] == 1025.0 and ds.attrs["g"] == 9.81  # defaults: .out not read


def test_out_file_has_raos_and_drift(tanker_out):
    assert {"rao", "drift_force"} <= set(tanker_out.data_vars)
    # Heave RAO tends to 1 m/m in long waves; mean surge drift pushes the ship the way the
    # waves travel (below the irregular frequencies near 3.9 rad/s, where it is garbage).
    rao3 = np.abs(tanker_out.rao.sel(radiating_dof="Heave").isel(omega=0))
    np.testing.assert_allclose(rao3, 1.0, atol=0.02)
    surge = tanker_out.drift_force.sel(influenced_dof="Surge").sel(omega=slice(0.5, 2.0))
    assert np.all(surge.sel(wave_direction=0.0) > 0)
    assert np.all(surge.sel(wave_direction=np.pi, method="nearest") < 0)


# ----------------------------------------------------------------------------- bad input


def _copy_run(src_dir, dst_dir, stem="tanker"):
    dst_dir.mkdir(parents=True, exist_ok=True)
    for suffix in (".1", ".3", ".hst", ".frc", ".out"):
        shutil.copy(src_dir / f"{stem}{suffix}", dst_dir / f"{stem}{suffix}")
    return dst_dir / f"{stem}.1"


def test_truncated_file_names_the_file(tanker_dir, tmp_path):
    target = _copy_run(tanker_dir, tmp_path)
    lines = target.read_text().splitlines()
    target.write_text("\n".join(lines[:-5]) + "\n")
    with pytest.raises(HydroDataError, match=r"tanker\.1.*(truncated|missing)"):
        cummins.read(target)


def test_garbled_number_names_the_line(tanker_dir, tmp_path):
    target = _copy_run(tanker_dir, tmp_path)
    lines = target.read_text().splitlines()
    lines[99] = lines[99].replace("E", "X", 1)
    target.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=r"tanker\.1, line 100"):
        cummins.read(target)


def test_nan_names_the_line(tanker_dir, tmp_path):
    target = _copy_run(tanker_dir, tmp_path)
    dot3 = tmp_path / "tanker.3"
    lines = dot3.read_text().splitlines()
    fields = lines[41].split()
    fields[5] = "NaN"
    lines[41] = "  ".join(fields)
    dot3.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=r"tanker\.3, line 42: non-finite"):
        cummins.read(target)


def test_shuffled_period_column(tanker_dir, tmp_path):
    target = _copy_run(tanker_dir, tmp_path)
    rows = [line.split() for line in target.read_text().splitlines()]
    periods = np.random.default_rng(1).permutation([row[0] for row in rows])
    target.write_text(
        "\n".join("  ".join([p, *row[1:]]) for p, row in zip(periods, rows, strict=True)) + "\n"
    )
    with pytest.raises(HydroDataError, match=r"tanker\.1, line \d+"):
        cummins.read(target)


def test_empty_and_foreign_files(tmp_path, tanker_dir):
    empty = tmp_path / "ship.1"
    empty.write_text("")
    with pytest.raises(HydroDataError, match="empty"):
        cummins.read(empty)
    foreign = tmp_path / "notes.1"
    foreign.write_text("This is not a WAMIT file.\nJust words.\n")
    with pytest.raises(HydroDataError, match="unrecognised"):
        cummins.read(foreign)
    with pytest.raises(HydroDataError, match="not a WAMIT"):
        cummins.read(foreign, format="wamit")
    binary = tmp_path / "blob.1"
    binary.write_bytes(bytes(range(256)) * 10)
    with pytest.raises(HydroDataError):
        cummins.read(binary)


def test_dot3_without_dot1(tanker_dir, tmp_path):
    shutil.copy(tanker_dir / "tanker.3", tmp_path / "tanker.3")
    with pytest.raises(HydroDataError, match=r"\.1 file"):
        cummins.read(tmp_path / "tanker.3")


def test_dot3_from_another_run(tanker_dir, shared_data, tmp_path):
    target = _copy_run(tanker_dir, tmp_path)
    shutil.copy(shared_data / "wecsim" / "sphere" / "sphere.3", tmp_path / "tanker.3")
    with pytest.raises(HydroDataError, match=r"tanker\.3.*(not in the \.1|DOF|period)"):
        cummins.read(target)


def test_folder_reading(tmp_path, tanker_dir):
    _copy_run(tanker_dir, tmp_path)
    ds = cummins.read(tmp_path)
    assert ds.attrs["source_format"] == "wamit"
    assert "excitation_force" in ds


# --------------------------------------------------------------------------- corpus variants


def test_generalized_modes_barge(corpus):
    """6 + 4 beam modes (NEWMDS=4 in barge.cfg): labels Mode7…Mode10, the 10×10 IMASS and
    ISTIF of the .frc (form 2) as inertia and additional stiffness, and the .1 against the
    dimensional-free values the .out prints for the beam modes (same 7 digits)."""
    run = corpus / "WEC-Sim_Applications" / "wamit_generalized_modes_barge"
    ds = cummins.read(run)
    assert list(ds.influenced_dof.values[6:]) == ["Mode7", "Mode8", "Mode9", "Mode10"]
    assert ds.inertia_matrix.sel(influenced_dof="Mode7", radiating_dof="Mode7") == 1.079216e06
    assert (
        ds.additional_stiffness.sel(influenced_dof="Mode10", radiating_dof="Mode10") == 4.664370e08
    )
    out = cummins.read(run / "barge.out")
    np.testing.assert_allclose(out.added_mass_inf.values, ds.added_mass_inf.values, rtol=1e-6)
    np.testing.assert_allclose(out.added_mass.values, ds.added_mass.values, rtol=2e-6, atol=1e-3)


def test_barge_motion_rao_reproduces_the_dot4(corpus):
    """motion_rao of the barge (rigid + beam modes, IMASS and ISTIF of its .frc) against
    WAMIT's own .4: measured worst difference 3e-4 of the peak for the rigid modes, 0.9 %
    for the beam modes (the .4 prints 6 digits, phases to 1e-4 deg)."""
    ds = cummins.read(corpus / "WEC-Sim_Applications" / "wamit_generalized_modes_barge")
    ours = motion_rao(ds).transpose("omega", "wave_direction", "dof").values
    ref = ds.rao.transpose("omega", "wave_direction", "radiating_dof").values
    for j, label in enumerate(ds.radiating_dof.values):
        peak = np.abs(ref[:, :, j]).max()
        if peak == 0:
            continue
        err = np.abs(ours[:, :, j] - ref[:, :, j]).max() / peak
        assert err < (2e-3 if j < 6 else 3e-2), (label, err)


def test_owc_is_one_body_with_a_piston_mode(corpus):
    """test17a.out: one XBODY, an 'Extra Mode' file and indices 1…7: one body, Mode7;
    the ω = 0 block written twice (identical) is read once."""
    ds = cummins.read(corpus / "WEC-Sim_Applications" / "wamit_OWC_Triton_GBM")
    assert list(ds.influenced_dof.values) == [*cummins.hydrodb.DOF_NAMES, "Mode7"]
    assert "written twice (identical)" in ds.attrs["history"]
    moved = cummins.move_reference_point(ds, [0.0, 0.0, -1.0])
    a77 = {"influenced_dof": "Mode7", "radiating_dof": "Mode7"}
    np.testing.assert_array_equal(moved.added_mass.sel(**a77), ds.added_mass.sel(**a77))
    assert cummins.check(ds) is not None


def test_two_bodies_take_the_geometry_names(corpus):
    ds = cummins.read(corpus / "WEC-Sim" / "wamit_OSWEC_2015_with_bemio_h5" / "oswec.out")
    assert ds.influenced_dof.values[6] == "body2__Surge"
    assert ds.attrs["body_names"].splitlines() == ["flap", "base"]


def test_inertia_from_the_out_agrees_with_wamit_mmx(corpus):
    """Mean-drift sphere: radii of gyration 0.4 m in the .out; WAMIT's own normalized
    mass matrix in sphere.mmx is 2.072930 (translation) and 0.3316688 (rotation):
    m = ρ·mean(VOL), I = m r|r| reproduce them to the 7 digits printed."""
    ds = cummins.read(corpus / "WEC-Sim_Applications" / "wamit_mean_drift_sphere", rho=1000.0)
    m = ds.inertia_matrix.values / 1000.0
    np.testing.assert_allclose(np.diag(m), [2.07293] * 3 + [0.3316688] * 3, rtol=2e-6)


def test_zero_radii_give_no_inertia_but_the_mass_agrees_with_capytaine(corpus):
    """COER: WAMIT's radii of gyration are all zero (WEC-Sim's placeholder): no inertia
    matrix, said in the history. The displaced volume ρ∇ agrees with Capytaine's mass of
    the same body (26.8178 kg at ρ = 1000; measured 4e-6)."""
    ds = cummins.read(corpus / "WEC-Sim" / "wamit_COER_comp", rho=1000.0)
    assert "inertia_matrix" not in ds and "radii of gyration all zero" in ds.attrs["history"]
    capy = cummins.read(
        corpus / "WEC-Sim" / "capytaine_COER_comp" / "outputs" / "coer_comp_hydrodynamics.nc"
    )
    mass = float(capy.inertia_matrix.values[0, 0])
    np.testing.assert_allclose(1000.0 * ds.attrs["displaced_volume"], mass, rtol=1e-4)
    # no .3 file: the excitation comes from the .out
    assert "excitation_force" in ds and "no .3 file" in ds.attrs["history"]


def test_blank_fixed_width_cg_fields(corpus, tmp_path):
    """A .out whose CG line has only Zg filled reads: Xg, Yg from the CB above."""
    run = corpus / "WEC-Sim_Applications" / "wamit_mean_drift_sphere" / "outputFiles"
    target = tmp_path / "sphere.out"
    lines = (run / "sphere.out").read_text().splitlines()
    k = next(i for i, line in enumerate(lines) if "Center of Gravity" in line)
    head, _, tail = lines[k].partition("0.000000     0.000000")
    lines[k] = head + " " * len("0.000000     0.000000") + tail
    target.write_text("\n".join(lines) + "\n")
    ds = cummins.read(target)
    assert "inertia_matrix" in ds and "leaves Xg blank" in ds.attrs["history"]


def test_two_runs_in_a_folder_name_both_and_how_to_choose(corpus):
    folder = corpus / "bemio" / "wamit_COER_comp_f2"
    with pytest.raises(HydroDataError, match=r"coer_comp_f\.out.*coer_comp_f2\.out.*cummins info"):
        cummins.read(folder)


def test_damage_is_noticed(tanker_dir, tmp_path, corpus):
    """Issue 17's cases on copies of real files."""
    # a .out cut after 19 of its 58 frequencies
    lines = (tanker_dir / "tanker.out").read_text().splitlines()
    starts = [i for i, line in enumerate(lines) if "Wave period" in line]
    (tmp_path / "cut.out").write_text("\n".join(lines[: starts[21]]) + "\n")
    with pytest.warns(cummins.HydroDataWarning, match="truncated"):
        ds = cummins.read(tmp_path / "cut.out")
    assert "read_warnings" in ds.attrs
    # a .hst cut before C33: hydrostatics not read, with a warning, never zeros
    target = _copy_run(tanker_dir, tmp_path / "hst")
    hst = target.with_suffix(".hst")
    hst.write_text("\n".join(hst.read_text().splitlines()[:14]) + "\n")
    with pytest.warns(cummins.HydroDataWarning, match="C\\(3,3\\) missing"):
        ds = cummins.read(target)
    assert "hydrostatic_stiffness" not in ds
    # a .3 line deleted: an error naming the line, never 0j
    target = _copy_run(tanker_dir, tmp_path / "dot3")
    dot3 = target.with_suffix(".3")
    rows = dot3.read_text().splitlines()
    dot3.write_text("\n".join(rows[:100] + rows[101:]) + "\n")
    with pytest.raises(HydroDataError, match=r"tanker\.3, line \d+.*missing"):
        cummins.read(target)
    # a damaged .frc: a warning, not a silently missing inertia matrix
    target = _copy_run(tanker_dir, tmp_path / "frc")
    frc = target.with_suffix(".frc")
    frc.write_text(
        frc.read_text().replace("94620210.00 0.00 0.00 0.00 236550525.00", "94620210.00 0.00", 1)
    )
    with pytest.warns(cummins.HydroDataWarning, match="tanker.frc"):
        ds = cummins.read(target)
    assert "inertia_matrix" not in ds
    # a corrupted DOF index: an error, neither 12 DOFs nor a huge allocation
    text = (tanker_dir / "tanker.out").read_text()
    for bad in ("    7     1", " 9999     1"):
        (tmp_path / "dof.out").write_text(text.replace("     1     1", bad, 1))
        with pytest.raises(HydroDataError):
            cummins.read(tmp_path / "dof.out")
    # a missing-value marker
    target = _copy_run(tanker_dir, tmp_path / "big")
    dot1 = target
    rows = dot1.read_text().splitlines()
    fields = rows[40].split()
    fields[-1] = "-0.999000E+100"
    rows[40] = "  ".join(fields)
    dot1.write_text("\n".join(rows) + "\n")
    with pytest.raises(HydroDataError, match="implausible"):
        cummins.read(target)


def test_encodings_read_identically(tanker_dir, tmp_path):
    """UTF-8 BOM, CRLF and CR-only line ends are not damage."""
    base = cummins.read(tanker_dir / "tanker.1")
    for name, convert in (
        ("bom", lambda b: b"\xef\xbb\xbf" + b),
        ("crlf", lambda b: b.replace(b"\n", b"\r\n")),
        ("cr", lambda b: b.replace(b"\n", b"\r")),
    ):
        folder = tmp_path / name
        folder.mkdir()
        for f in tanker_dir.glob("tanker.*"):
            (folder / f.name).write_bytes(convert(f.read_bytes().replace(b"\r\n", b"\n")))
        ds = cummins.read(folder / "tanker.1")
        np.testing.assert_array_equal(ds.added_mass.values, base.added_mass.values)
        np.testing.assert_array_equal(ds.inertia_matrix.values, base.inertia_matrix.values)


def test_a_piston_mode_without_restoring_is_warned_of(corpus):
    """The Triton OWC's piston mode (Mode7) has zero hydrostatics in WAMIT's output (its
    DEFMOD gives none): its RAO grows as 1/ω² in long waves, which ``motion_rao`` and the
    time-domain vessel now say, naming the stiffness to give; given one (ρ g S), it is
    bounded and nothing is said. A rigid body's surge, sway and yaw (no restoring
    either) are not named."""
    import warnings

    from cummins.errors import HydroDataWarning
    from cummins.mass_properties import with_external_terms, with_inertia
    from cummins.mechanics import MechanicalSystem
    from cummins.vessel import vessel_from_hydrodb

    ds = cummins.read(corpus / "WEC-Sim_Applications" / "wamit_OWC_Triton_GBM")
    ds = with_inertia(ds, matrix=np.diag([588.8] * 3 + [147.2] * 3 + [1.0]))
    system = MechanicalSystem(dofs=("Heave", "Mode7"))
    w = np.array([0.71, 1.42])
    with pytest.warns(HydroDataWarning, match="Mode7: no restoring") as caught:
        free = motion_rao(ds, w, system=system)
    (said,) = [str(c.message) for c in caught if "no restoring" in str(c.message)]
    assert "--external-stiffness Mode7 Mode7" in said and "Surge" not in said
    piston = np.abs(free.sel(dof="Mode7").values).ravel()
    assert piston[0] > 2 * piston[1]  # growing in long waves
    held = with_external_terms(ds, stiffness={("Mode7", "Mode7"): 3000.0})
    with warnings.catch_warnings():
        warnings.simplefilter("error", HydroDataWarning)
        bounded = motion_rao(held, w, system=system)
    assert np.abs(bounded.sel(dof="Mode7").values).max() < piston[0]
    with pytest.warns(HydroDataWarning, match="Mode7: no restoring"):
        vessel = vessel_from_hydrodb(ds, system=system, max_order=10)
    assert "Mode7" in vessel.attrs["unrestrained_modes"]


def test_a_run_reads_its_out_once(tmp_path, monkeypatch):
    """A .1 takes constants, body parameters, the excitation (no .3) and the mean drift
    from its .out: the log is opened once (was up to five times: banner, header, drift
    search, one parse per table wanted), and what it gives equals the log read alone."""
    import builtins
    import io

    demo = cummins.demo_files()
    for name in ("tanker.1", "tanker.hst", "tanker.frc", "tanker.out"):
        shutil.copy(demo / name, tmp_path / name)
    alone = cummins.read(tmp_path / "tanker.out")
    opened: list[str] = []
    real_open = io.open

    def counting_open(file, *args, **kwargs):
        if str(file).endswith(".out"):
            opened.append(str(file))
        return real_open(file, *args, **kwargs)

    monkeypatch.setattr(io, "open", counting_open)
    monkeypatch.setattr(builtins, "open", counting_open)
    ds = cummins.read(tmp_path / "tanker.1")  # no .3: the excitation from the .out
    monkeypatch.undo()
    assert opened == [str(tmp_path / "tanker.out")]
    np.testing.assert_array_equal(ds.excitation_force.values, alone.excitation_force.values)
    np.testing.assert_array_equal(ds.drift_force.values, alone.drift_force.values)
    assert "mean drift from tanker.out" in ds.attrs["history"]
