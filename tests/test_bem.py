"""BEM runs with Capytaine (optional extra ``[bem]``): physics of small parametric hulls.

Meshes are deliberately coarse (≈ 100 panels) to keep the suite fast; each tolerance
says which discretisation error it covers.
"""

from __future__ import annotations

import importlib.util
import math
import sys

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner
from scipy.integrate import simpson

import cummins
from cummins import CumminsError
from cummins.kinematics import center_of_gravity_from_inertia

HAVE_CAPYTAINE = importlib.util.find_spec("capytaine") is not None
needs_capytaine = pytest.mark.skipif(not HAVE_CAPYTAINE, reason="capytaine is not installed")
pytestmark = pytest.mark.bem

RHO, G = 1025.0, 9.81
L, B, T = 20.0, 8.0, 2.0
RESOLUTION = 10  # box: 10 × 4 panels on the bottom, 2 over the draft: 96 panels
OMEGA = [0.2, 0.6, 1.0, 1.4]
#: 0 … 90°: enough for the Haskind integral over all directions, by the box's symmetry
HEADINGS_DEG = [0.0, 22.5, 45.0, 67.5, 90.0]


@pytest.fixture(scope="module")
def bem():
    pytest.importorskip("capytaine")
    from cummins import bem

    return bem


@pytest.fixture(scope="module")
def box_mesh(bem):
    return bem.box_barge_mesh(L, B, T, resolution=RESOLUTION)


@pytest.fixture(scope="module")
def box(bem, box_mesh):
    return bem.compute_hydrodb(
        box_mesh, OMEGA, wave_direction=np.radians(HEADINGS_DEG), rho=RHO, g=G
    )


def _diag(ds, name, dof):
    return ds[name].sel(influenced_dof=dof, radiating_dof=dof).values


# --------------------------------------------------------------------------- box barge


def test_box_mass_and_hydrostatics(box):
    """Exact for a box: the panels tile the waterplane and the hull exactly."""
    mass, cog, inconsistency = center_of_gravity_from_inertia(box.inertia_matrix.values)
    assert mass == pytest.approx(RHO * L * B * T, rel=1e-9)
    np.testing.assert_allclose(cog, [0.0, 0.0, 0.0], atol=1e-9)  # default: waterline above CB
    assert inconsistency < 1e-9
    c = box.hydrostatic_stiffness.values
    assert c[2, 2] == pytest.approx(RHO * G * L * B, rel=1e-9)
    # C44 = ρg(I_wp + V z_B) − m g z_G with z_G = 0, z_B = −T/2. Capytaine integrates
    # y² over the waterplane with the midpoint rule: exact ∫y² × (1 − 1/n²) for n = 4
    # panels across the beam (10 along the length), hence the tolerance.
    water_plane_x, water_plane_y = L * B**3 / 12, B * L**3 / 12
    c44 = RHO * G * (water_plane_x - L * B * T**2 / 2)
    c55 = RHO * G * (water_plane_y - L * B * T**2 / 2)
    assert abs(c[3, 3] - c44) <= (1 / 4**2 + 1e-3) * RHO * G * water_plane_x
    assert abs(c[4, 4] - c55) <= (1 / 10**2 + 1e-3) * RHO * G * water_plane_y
    assert box.attrs["displaced_volume"] == pytest.approx(L * B * T, rel=1e-9)
    np.testing.assert_allclose(box.attrs["center_of_buoyancy"], [0.0, 0.0, -T / 2], atol=1e-9)
    np.testing.assert_array_equal(box.attrs["reference_point"], [0.0, 0.0, 0.0])


def test_box_is_a_valid_usable_hydrodb(box):
    cummins.validate(box)
    assert box.attrs["source_format"] == "capytaine"
    assert box.attrs["rho"] == RHO and box.attrs["water_depth"] == math.inf
    np.testing.assert_allclose(box.wave_direction, np.radians(HEADINGS_DEG))
    report = cummins.check(box)
    errors = [f for f in report.findings if f.severity == "error"]
    assert not errors, errors
    for dof in cummins.DOF_NAMES:
        assert np.all(_diag(box, "radiation_damping", dof) >= 0), dof


def test_box_added_mass_limits(box):
    """A(0) and A(∞) were solved (deep water) and fit the finite frequencies: at
    ω = 0.2 rad/s (kT = 0.008) A is within 5 % of A(0) (measured ≤ 3.9 %, heave); heave
    and pitch come closer to A(∞) as ω grows (surge and sway still rise to a peak at
    ω = 1 rad/s); A(0) > A(∞) > 0 for a surface-piercing hull."""
    assert {"added_mass_zero", "added_mass_inf"} <= set(box.data_vars)
    for dof in cummins.DOF_NAMES:
        a = _diag(box, "added_mass", dof)
        a0 = _diag(box, "added_mass_zero", dof)
        assert abs(a[0] - a0) < 0.05 * a0, dof
    for dof in ("Surge", "Sway", "Heave", "Pitch"):
        assert _diag(box, "added_mass_zero", dof) > _diag(box, "added_mass_inf", dof) > 0, dof
    for dof in ("Heave", "Pitch"):
        a = _diag(box, "added_mass", dof)
        a_inf = _diag(box, "added_mass_inf", dof)
        assert abs(a[-1] - a_inf) < abs(a[0] - a_inf), dof
    eig = np.linalg.eigvalsh(0.5 * (box.added_mass_inf + box.added_mass_inf.T))
    assert eig.min() > 0


def test_box_haskind_relation(box):
    """Energy conservation (deep water): B_jj = ω³/(4πρg³) ∫₀^{2π} |X_j(β)|² dβ.

    Damping from the radiation problems, excitation from the diffraction problems:
    independent outputs. On this 96-panel mesh the ratio is 0.90–1.09 (it tends to 1
    with the mesh: 0.97–0.99 on 272 panels), hence 12 %. Roll, with 2 panels over the
    draft, is not resolved well enough for the check.
    """
    omega = box.omega.values
    beta = box.wave_direction.values
    for dof in ("Surge", "Sway", "Heave", "Pitch"):
        x2 = np.abs(box.excitation_force.sel(influenced_dof=dof).values) ** 2
        integral = 4 * simpson(x2, x=beta, axis=1)  # symmetric about both axes
        haskind = omega**3 / (4 * np.pi * RHO * G**3) * integral
        np.testing.assert_allclose(
            haskind, _diag(box, "radiation_damping", dof), rtol=0.12, err_msg=dof
        )


def test_box_long_wave_limit_fixes_the_time_convention(box):
    """At ω = 0.2 rad/s (λ = 1540 m ≫ L) the heave force is the hydrostatic one, in phase
    with the wave crest at the origin: X₃ ≈ +C33. In waves travelling along +x the surge
    force follows the fluid acceleration, a quarter period ahead of the elevation: arg X₁ =
    +90° for x(t) = Re{X e^{+iωt}} (it would be −90° in Capytaine's e^{-iωt})."""
    x = box.excitation_force.sel(wave_direction=0.0).isel(omega=0)
    c33 = float(box.hydrostatic_stiffness.sel(influenced_dof="Heave", radiating_dof="Heave"))
    x3 = complex(x.sel(influenced_dof="Heave"))
    assert abs(x3 - c33) < 0.05 * c33
    assert np.degrees(np.angle(complex(x.sel(influenced_dof="Surge")))) == pytest.approx(
        90.0, abs=5
    )


def test_box_netcdf_round_trip(box, tmp_path):
    path = cummins.write(box, tmp_path / "box.nc")
    xr.testing.assert_identical(cummins.read(path), box)


def test_capytaines_own_file_reads_like_our_run(bem, box_mesh, box, tmp_path):
    """Solve the same problems with Capytaine's own API, save them with Capytaine's
    NetCDF writer (Capytaine ≥ 2 layout: ω = 0 and ∞ rows, complex dimension, dims
    (omega, influenced_dof, radiating_dof) in Capytaine 3) and read that file."""
    cpt = bem.import_capytaine()
    body = cpt.FloatingBody(
        mesh=box_mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)), center_of_mass=(0, 0, 0)
    )
    test_matrix = xr.Dataset(
        coords={
            "omega": [0.0, *OMEGA, np.inf],
            "wave_direction": np.radians(HEADINGS_DEG[::2]),
            "radiating_dof": list(body.dofs),
            "water_depth": [np.inf],
            "rho": [RHO],
            "g": [G],
        }
    )
    with bem._quiet_capytaine(level=100):
        dataset = cpt.BEMSolver().fill_dataset(test_matrix, body, progress_bar=False)
    path = tmp_path / "capytaine.nc"
    cpt.io.xarray.export_dataset(path, dataset)
    ds = cummins.read(path)
    assert ds.attrs["source_format"] == "capytaine"
    for name in ("added_mass", "radiation_damping", "added_mass_zero", "added_mass_inf"):
        np.testing.assert_allclose(
            ds[name], box[name], rtol=1e-9, atol=1e-6 * abs(box[name]).max(), err_msg=name
        )
    np.testing.assert_allclose(
        ds.excitation_force,
        box.excitation_force.isel(wave_direction=[0, 2, 4]),
        rtol=1e-9,
        atol=1e-9 * abs(box.excitation_force).max(),
    )
    np.testing.assert_array_equal(ds.attrs["reference_point"], [0.0, 0.0, 0.0])


def test_inertia_obeys_the_parallel_axis_theorem(bem, box_mesh, box):
    """Rotations about a point 1 m below the waterline: the inertia is that of the same
    rigid body (I' = I + m d², coupling m d), not Capytaine's open-hull integral."""
    ds = bem.compute_hydrodb(
        box_mesh,
        [0.8],
        wave_direction=[0.0],
        rho=RHO,
        g=G,
        reference_point=(0.0, 0.0, -1.0),
        limits=False,
    )
    mass = RHO * L * B * T
    m0, m1 = box.inertia_matrix.values, ds.inertia_matrix.values
    for k in (3, 4):  # roll, pitch: d = 1 m
        assert m1[k, k] == pytest.approx(m0[k, k] + mass * 1.0**2, rel=1e-9)
    assert m1[5, 5] == pytest.approx(m0[5, 5], rel=1e-9)  # yaw axis is the same line
    assert m1[0, 4] == pytest.approx(mass * 1.0, rel=1e-9)  # surge-pitch coupling m (z_G − z_P)
    np.testing.assert_array_equal(ds.attrs["reference_point"], [0.0, 0.0, -1.0])


# --------------------------------------------------------------------------- Wigley hull


def test_wigley_geometry_and_run(bem):
    """y = ±(B/2)(1 − (2x/L)²)(1 − (z/T)²): V = 4/9 LBT, A_wp = 2/3 LB, z_B = −3T/8.
    Flat panels on the parabolic sections (4 over the draft) lose ≈ 1/(4n²) = 1.6 % of the
    volume, hence 2.5 %."""
    length, beam, draft = 20.0, 2.0, 1.25
    mesh = bem.wigley_mesh(length, beam, draft, resolution=12)
    ds = bem.compute_hydrodb(mesh, [0.8, 1.6], wave_direction=[np.pi], rho=RHO, g=G, limits=False)
    assert ds.attrs["displaced_volume"] == pytest.approx(4 / 9 * length * beam * draft, rel=0.025)
    c33 = float(ds.hydrostatic_stiffness.sel(influenced_dof="Heave", radiating_dof="Heave"))
    assert c33 == pytest.approx(RHO * G * 2 / 3 * length * beam, rel=0.01)
    assert ds.attrs["center_of_buoyancy"][2] == pytest.approx(-3 * draft / 8, rel=0.03)
    # port/starboard and fore/aft symmetry of the mesh: no roll-yaw or heave-pitch inertia
    inertia = ds.inertia_matrix.values
    assert abs(inertia[3, 5]) < 1e-9 * inertia[3, 3]
    cummins.validate(ds)
    scale = float(abs(ds.radiation_damping).max())
    for dof in cummins.DOF_NAMES:
        assert np.all(_diag(ds, "radiation_damping", dof) >= -1e-6 * scale), dof


# --------------------------------------------------------------------------- options


def test_mesh_file_gives_the_same_result(bem, box_mesh, box, tmp_path):
    """A WAMIT .gdf file of the same panels (written here) is read by Capytaine."""
    panels = np.asarray(box_mesh.vertices)[np.asarray(box_mesh.faces)]
    lines = ["box barge written by the test", f"1.0 {G}", "0 0", str(len(panels))]
    lines += [f"{x:.12g} {y:.12g} {z:.12g}" for panel in panels for x, y, z in panel]
    gdf = tmp_path / "barge.gdf"
    gdf.write_text("\n".join(lines) + "\n")
    ds = bem.compute_hydrodb(gdf, OMEGA[:2], wave_direction=[0.0], rho=RHO, g=G, limits=False)
    np.testing.assert_allclose(ds.added_mass, box.added_mass.isel(omega=[0, 1]), rtol=1e-8)
    assert ds.attrs["source_file"] == str(gdf)
    assert ds.attrs["body_name"] == "barge"


def test_finite_depth_omits_zero_frequency(bem, box_mesh):
    """Capytaine has no ω = 0 in finite depth: A(∞) only, and the history says so."""
    ds = bem.compute_hydrodb(box_mesh, [0.8], wave_direction=[0.0], water_depth=10.0)
    assert "added_mass_inf" in ds and "added_mass_zero" not in ds
    assert "added_mass_zero not computed" in ds.attrs["history"]
    assert ds.attrs["water_depth"] == 10.0


def test_progress_callback_and_bad_input(bem, box_mesh):
    calls = []
    bem.compute_hydrodb(
        box_mesh,
        [1.0],
        wave_direction=[0.0],
        limits=False,
        progress=lambda done, total: calls.append((done, total)),
    )
    assert calls == [(k, 7) for k in range(1, 8)]  # 6 radiation + 1 diffraction problems
    with pytest.raises(CumminsError, match="omega must hold"):
        bem.compute_hydrodb(box_mesh, [0.0, 1.0])
    with pytest.raises(CumminsError, match="draft"):
        bem.box_barge_mesh(10.0, 4.0, -1.0)
    with pytest.raises(cummins.HydroDataError, match="mesh file not found"):
        bem.compute_hydrodb("no_such_mesh.gdf", [1.0])


def test_missing_capytaine_is_a_clear_error(monkeypatch):
    from cummins import bem

    monkeypatch.setitem(sys.modules, "capytaine", None)  # makes `import capytaine` fail
    with pytest.raises(CumminsError, match=r"pip install cummins\[bem\]"):
        bem.box_barge_mesh(10.0, 4.0, 1.0)


# --------------------------------------------------------------------------- command line


@needs_capytaine
def test_cli_box_run_and_overwrite_protection(tmp_path):
    from cummins.cli.bem import bem_command

    out = tmp_path / "barge.nc"
    args = [
        "--hull",
        "box",
        "--length",
        "20",
        "--beam",
        "8",
        "--draft",
        "2",
        "--resolution",
        "8",
        "--omega-min",
        "0.5",
        "--omega-max",
        "1.0",
        "--n-omega",
        "2",
        "--headings",
        "0,90",
        "--headings",
        "180",
        "-o",
        str(out),
    ]
    runner = CliRunner()
    result = runner.invoke(bem_command, args)
    assert result.exit_code == 0, result.output
    assert "saved" in result.output
    ds = cummins.read(out)
    np.testing.assert_allclose(ds.omega, [0.5, 1.0])
    np.testing.assert_allclose(np.degrees(ds.wave_direction), [0.0, 90.0, 180.0])
    assert "added_mass_inf" in ds and "added_mass_zero" in ds
    before = out.read_bytes()
    again = runner.invoke(bem_command, args)
    assert again.exit_code != 0 and "exists" in again.output
    assert out.read_bytes() == before
    forced = runner.invoke(bem_command, [*args, "--force", "--rho", "1000"])
    assert forced.exit_code == 0, forced.output
    assert cummins.read(out).attrs["rho"] == 1000.0


@needs_capytaine
def test_cli_usage_errors(tmp_path):
    from cummins.cli.bem import bem_command

    runner = CliRunner()
    common = ["--omega-min", "0.5", "--omega-max", "1", "-o", str(tmp_path / "x.nc")]
    result = runner.invoke(bem_command, ["--hull", "box", "--length", "20", *common])
    assert result.exit_code == 2 and "--beam" in result.output
    result = runner.invoke(bem_command, common)
    assert result.exit_code == 2 and "MESH" in result.output
    result = runner.invoke(
        bem_command,
        [
            "--hull",
            "box",
            "--length",
            "20",
            "--beam",
            "8",
            "--draft",
            "2",
            "--headings",
            "north",
            *common,
        ],
    )
    assert result.exit_code == 2 and "north" in result.output
    assert not (tmp_path / "x.nc").exists()


@needs_capytaine
def test_cli_warns_when_its_own_data_are_not_symmetric_or_too_few(tmp_path):
    """The audit's barge (8 frequencies: its fit missed its targets, motion error 4.2 %)
    in miniature: after the run, `bem` says what `cummins check` finds that the run's
    settings mend — B[Sway, Roll] not symmetric on coarse panels (the check's own
    finding, with --resolution to raise) and too few frequencies (--n-omega)."""
    from cummins.cli.bem import bem_command

    out = tmp_path / "barge.nc"
    box = ["--hull", "box", "--length", "20", "--beam", "8", "--draft", "2"]
    args = [*box, "--resolution", "8", "--omega-min", "1", "--omega-max", "2", "--n-omega", "2"]
    result = CliRunner().invoke(bem_command, [*args, "-o", str(out)])
    assert result.exit_code == 0, result.output
    warned = [line for line in result.output.splitlines() if line.startswith("warning:")]
    symmetry = [line for line in warned if "not symmetric" in line]
    findings = [
        f for f in cummins.check(cummins.read(out)).by_check("symmetry") if f.severity == "warning"
    ]
    assert findings and len(symmetry) == len(findings)  # one line per finding of the check
    for line, finding in zip(symmetry, findings, strict=True):
        assert line.startswith(f"warning: {finding.where}: {finding.message}")
        assert "raise --resolution (now 8 panels along the length)" in line
    assert any("only 2 frequencies" in line and "--n-omega" in line for line in warned)
    # one frequency: --omega-min = --omega-max; two different ones are refused
    one = [*box, "--resolution", "6", "--n-omega", "1", "--no-limits", "-o", str(out), "--force"]
    result = CliRunner().invoke(bem_command, [*one, "--omega-min", "0.8", "--omega-max", "0.8"])
    assert result.exit_code == 0, result.output
    np.testing.assert_array_equal(cummins.read(out).omega.values, [0.8])
    result = CliRunner().invoke(bem_command, [*one, "--omega-min", "0.8", "--omega-max", "0.9"])
    assert result.exit_code == 2 and "--omega-min = --omega-max" in result.output
