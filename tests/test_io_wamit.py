"""WAMIT reader: numeric files against the .out log, MSS's processed struct, physics."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

import cummins
from cummins import HydroDataError


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
