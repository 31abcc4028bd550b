"""ShipX/VERES reader: physics of the conventions, MSS's processing of the same files."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

import cummins
from cummins import HydroDataError
from cummins.io.mss import read_mss
from cummins.io.veres import (
    file_kind,
    read_veres,
    read_veres_transfer_function,
    sniff,
    sniff_dir,
)


@pytest.fixture(scope="module")
def supply_dir(shared_data):
    return shared_data / "mss" / "supply"


@pytest.fixture(scope="module")
def supply(supply_dir):
    return read_veres(supply_dir / "input.re7")


def _copy_run(supply_dir, tmp_path, names=("input.re7", "input.re8", "input.re1", "input.re2")):
    for name in names:
        shutil.copy(supply_dir / name, tmp_path / name)
    return tmp_path


# --------------------------------------------------------------------------- detection


def test_sniff(shared_data, supply_dir):
    kinds = {
        name: file_kind(supply_dir / name)
        for name in ("input.re7", "input.re8", "input.re1", "input.re2", "input.hyd", "supply.mat")
    }
    assert kinds == {
        "input.re7": ".re7",
        "input.re8": ".re8",
        "input.re1": ".re1",
        "input.re2": ".re2",
        "input.hyd": None,
        "supply.mat": None,
    }
    assert sniff(supply_dir / "input.re8") and not sniff(supply_dir / "input.hyd")
    assert not sniff(shared_data / "mss" / "tanker" / "tanker.1")
    assert sniff_dir(supply_dir) == [supply_dir / "input.re7"]
    # Without a .re7 the folder still shows the run, so that reading it explains the gap.
    assert [p.suffix for p in sniff_dir(shared_data / "mss" / "s175")] in ([".re1"], [".re8"])


def test_missing_re7_is_named(shared_data):
    """The S-175 folder has .re1/.re2/.re8 but no .re7: no added mass, no dataset."""
    with pytest.raises(HydroDataError, match=r"input\.re7") as err:
        read_veres(shared_data / "mss" / "s175" / "input.re8")
    assert "read_veres_transfer_function" in str(err.value)


# --------------------------------------------------------------------------- conventions


def test_dataset_layout(supply):
    assert supply.attrs["source_format"] == "veres"
    assert supply.attrs["axis_convention"] == "z-up"
    assert supply.attrs["rho"] == 1025.0
    assert float(supply.forward_speed) == 0.0
    assert supply.sizes["omega"] == 36 and supply.sizes["wave_direction"] == 19
    # Motion reference point: XMTN = 5.385920 m aft of Lpp/2, ZMTN = 6.0 m = draught.
    np.testing.assert_allclose(supply.attrs["reference_point"], [-5.38592, 0.0, 0.0])
    np.testing.assert_allclose(supply.attrs["center_of_gravity"], [-5.38592, 0.0, 1.3], atol=1e-6)
    # The rigid-body mass matrix about that point: m z_G at (Surge, Pitch), z_G = 1.3 m up.
    m = supply.inertia_matrix.values
    assert m[0, 4] == pytest.approx(m[0, 0] * 1.3, rel=1e-6)
    assert "additional added mass" in supply.attrs["history"]
    assert "additional_added_mass" in supply


def test_roll_rao_needs_the_additional_added_mass(supply):
    """Beam seas: VERES's own roll RAO (.re1) solves the coupled sway-roll-yaw equation
    only when the .re7 additional added mass (the roll tank) is included: measured 5.8 %
    of the peak with it (the rest is the sea-state-dependent linearised viscous roll
    damping, which is not read), 60 % without."""
    ds = cummins.select_dofs(
        supply.sel(wave_direction=1.5 * np.pi, method="nearest"), ["Sway", "Roll", "Yaw"]
    )
    w = ds.omega.values[:, None, None]
    m, c = ds.inertia_matrix.values, ds.hydrostatic_stiffness.values
    b = ds.radiation_damping.values + ds.additional_damping.values
    f = ds.excitation_force.values[..., None]
    roll = ds.rao.sel(radiating_dof="Roll").values
    errors = {}
    for with_tank in (True, False):
        a = ds.added_mass.values + (ds.additional_added_mass.values if with_tank else 0.0)
        xi = np.linalg.solve(-(w**2) * (m + a) + 1j * w * b + c, f)[..., 0]
        errors[with_tank] = np.abs(xi[:, 1] - roll).max() / np.abs(roll).max()
    assert errors[True] < 0.08, errors
    assert errors[False] > 0.4, errors


def test_long_wave_limits_fix_heading_and_axes(supply):
    """At ω = 0.105 rad/s (λ = 5.6 km ≫ 83 m) the excitation is Froude-Krylov-like.

    For waves travelling towards +x, with x(t) = Re{X e^{iωt}}, the surge force is
    i k g (ρ∇ + A11): imaginary and positive; cummins' β = π (VERES heading 0) must
    give the negative. The heave force is ρ g A_wp = C33, real. The pitch moment (about
    +y, to port) is −∫x f_z dx, whose imaginary part ρ g k ∫x² b dx is positive for
    waves towards +x, negative in head seas. Sway at β = 3π/2 (towards starboard): −i k g
    (ρ∇ + A22). Tolerances: 3 % (diffraction and the finite wave length).
    """
    w = float(supply.omega[0])
    k = w**2 / supply.attrs["g"]
    x = supply.excitation_force.isel(omega=0)
    mass = float(supply.inertia_matrix.sel(influenced_dof="Surge", radiating_dof="Surge"))
    head = x.sel(wave_direction=np.pi, method="nearest")
    following = x.sel(wave_direction=0.0, method="nearest")
    beam_stbd = x.sel(wave_direction=1.5 * np.pi, method="nearest")
    g = supply.attrs["g"]
    assert complex(head.sel(influenced_dof="Surge")) == pytest.approx(-1j * k * g * mass, rel=0.03)
    assert complex(following.sel(influenced_dof="Surge")) == pytest.approx(
        1j * k * g * mass, rel=0.03
    )
    a22 = float(supply.added_mass.isel(omega=0).sel(influenced_dof="Sway", radiating_dof="Sway"))
    assert complex(beam_stbd.sel(influenced_dof="Sway")) == pytest.approx(
        -1j * k * g * (mass + a22), rel=0.03
    )
    c33 = float(supply.hydrostatic_stiffness.sel(influenced_dof="Heave", radiating_dof="Heave"))
    for f in (head, following, beam_stbd):
        assert complex(f.sel(influenced_dof="Heave")) == pytest.approx(c33, rel=0.03)
    assert complex(head.sel(influenced_dof="Pitch")).imag < 0
    assert complex(following.sel(influenced_dof="Pitch")).imag > 0
    # A particle in a long wave travelling towards -x moves as +i (surge RAO).
    rao = supply.rao.isel(omega=0).sel(wave_direction=np.pi, method="nearest")
    surge = complex(rao.sel(radiating_dof="Surge"))
    assert surge == pytest.approx(1j, abs=0.02)


def test_time_convention_from_motion_equation(supply):
    """The .re1 heave and pitch RAOs solve [−ω²(M+A) + iωB + C] ξ = F with the .re7/.re8
    data (head seas, where heave-pitch do not couple with the roll tank's added mass):
    within 3 % of the peak with +iω (measured 1.7 %), off by 157 % with −iω."""
    ds = supply.sel(wave_direction=np.pi, method="nearest")
    dofs = ["Heave", "Pitch"]
    sub = cummins.select_dofs(ds, dofs)
    w = sub.omega.values[:, None, None]
    m, c = sub.inertia_matrix.values, sub.hydrostatic_stiffness.values
    a, b = sub.added_mass.values, sub.radiation_damping.values + sub.additional_damping.values
    f = sub.excitation_force.values[..., None]
    rao = sub.rao.values
    peak = np.abs(rao).max(axis=0)
    errors = {}
    for sign in (+1, -1):
        z = -(w**2) * (m + a) + sign * 1j * w * b + c
        xi = np.linalg.solve(z, f)[..., 0]
        errors[sign] = (np.abs(xi - rao) / peak).max()
    assert errors[+1] < 0.03
    assert errors[-1] > 0.2


# --------------------------------------------------------------------------- against MSS


def test_supply_agrees_with_mss_struct(supply, supply_dir):
    """Acceptance: the raw VERES files, in Fossen axes about CO, equal MSS's supply.mat.

    MSS parsed the same printed numbers (8 significant digits); the residual comes from
    the position of the VERES point (XMTN printed with 7 digits, LCG with 8), so 1e-6 of
    each quantity's largest entry covers it (measured: 5e-8). MSS replaced the surge row
    and column of A and B by its own estimate, so they are left out; its Bv is its own
    viscous estimate, not compared. MSS left forceRAO/motionRAO about the VERES point,
    which read_mss corrects (see test_io_mss).
    """
    veres = cummins.move_reference_point(cummins.change_axes(supply, "z-down"), [0, 0, 0])
    mss = read_mss(supply_dir / "supply.mat")
    np.testing.assert_array_equal(veres.omega, mss.omega)
    beta = veres.wave_direction.values
    np.testing.assert_allclose(np.degrees(beta), np.arange(0, 181, 10), atol=1e-9)
    mss = mss.sel(wave_direction=beta, method="nearest")
    keep = [1, 2, 3, 4, 5]
    for name in ("added_mass", "radiation_damping", "hydrostatic_stiffness", "inertia_matrix"):
        x = veres[name].isel(influenced_dof=keep, radiating_dof=keep).values
        y = mss[name].isel(influenced_dof=keep, radiating_dof=keep).values
        assert np.abs(x - y).max() <= 1e-6 * np.abs(y).max(), name
    for name in ("excitation_force", "rao", "drift_force"):
        x, y = veres[name].values, mss[name].values
        tol = 1e-6 * np.abs(y).max(axis=(0, 1))
        assert np.all(np.abs(np.abs(x) - np.abs(y)) <= tol), name  # magnitude
        assert np.all(np.abs(x - y) <= tol), name  # and phase


def test_s175_speeds_match_mss(shared_data):
    """The S-175 .re8/.re1 speeds are s175.mat's velocities (printed to 7 digits), and
    the excitation and motions per speed agree with MSS's struct, for the components an
    x-shift of the reference point leaves alone (forces; rotations and surge motion)."""
    folder = shared_data / "mss" / "s175"
    mss = read_mss(folder / "s175.mat")
    flip = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])  # z-up to z-down
    for name, var, dofs in (
        ("input.re8", "excitation_force", [0, 1, 2, 3]),
        ("input.re1", "rao", [0, 3, 4, 5]),
    ):
        tf = read_veres_transfer_function(folder / name)
        np.testing.assert_allclose(tf.forward_speed, mss.forward_speed, rtol=1e-6)
        beta = np.mod(-tf.wave_direction.values, 2 * np.pi)
        y = mss[var].sel(wave_direction=beta, method="nearest")
        np.testing.assert_allclose(y.wave_direction, beta, atol=1e-9)
        x = tf.values * flip
        y = y.transpose("forward_speed", "omega", "wave_direction", ...).values
        tol = 1e-6 * np.abs(y).max(axis=(1, 2))[:, None, None, :]
        assert np.all(np.abs(x - y)[..., dofs] <= tol[..., dofs]), name


# --------------------------------------------------------------------------- variants


def test_version_1_file(supply_dir, supply, tmp_path):
    """A version-1 .re7 (no '-1 2' line, no additional matrices), made from the real file
    by dropping those lines, gives the same A, B, C and mass matrix."""
    lines = (supply_dir / "input.re7").read_text().splitlines()
    header, rest = lines[:9], lines[10:]
    counts, body = rest[0], rest[1:]
    out = [*header, counts, *body[:7]]  # mass matrix and speed line
    k = 7
    while k < len(body):
        if (
            len(body[k].split()) == 1
            and len(body[k + 1].split()) == 1
            and (len(body[k + 2].split()) == 6)
        ):
            out += body[k : k + 2]  # heading and first frequency
            k += 2
        elif len(body[k].split()) == 1:
            out.append(body[k])  # next frequency
            k += 1
        else:  # A, A_add, B, B_add, C, C_add (36 lines) and roll line
            blocks = body[k : k + 36]
            out += blocks[0:6] + blocks[12:18] + blocks[24:30] + [body[k + 36]]
            k += 37
    run = tmp_path / "v1"
    run.mkdir()
    (run / "input.re7").write_text("\n".join(out) + "\n")
    ds = read_veres(run / "input.re7")
    assert "version 1" in ds.attrs["history"]
    for name in ("added_mass", "radiation_damping", "hydrostatic_stiffness", "inertia_matrix"):
        np.testing.assert_array_equal(ds[name].values, supply[name].values, err_msg=name)


def test_speed_selection(supply_dir):
    ds = read_veres(supply_dir / "input.re1", speed=0.0)
    assert float(ds.forward_speed) == 0.0
    with pytest.raises(HydroDataError, match="forward speed 5"):
        read_veres(supply_dir / "input.re7", speed=5.0)
    with pytest.raises(HydroDataError, match="rho"):
        read_veres(supply_dir / "input.re7", rho=1000.0)


# --------------------------------------------------------------------------- errors


def _edit(path, edit):
    lines = path.read_text().splitlines()
    edit(lines)
    path.write_text("\n".join(lines) + "\n")


def test_truncated_re7(supply_dir, tmp_path):
    run = _copy_run(supply_dir, tmp_path)
    _edit(run / "input.re7", lambda lines: lines.__delitem__(slice(5000, None)))
    with pytest.raises(HydroDataError, match=r"input\.re7, line 11: .*truncated"):
        read_veres(run / "input.re7")


def test_garbled_number_in_re8_names_the_line(supply_dir, tmp_path):
    run = _copy_run(supply_dir, tmp_path)

    def garble(lines):
        lines[99] = lines[99].replace("E+0", "X+0", 1)

    _edit(run / "input.re8", garble)
    with pytest.raises(HydroDataError, match=r"input\.re8, line 100: expected"):
        read_veres(run / "input.re7")


def test_shuffled_frequency_column(supply_dir, tmp_path):
    """Swapping two frequency lines of the first heading breaks the increasing grid."""
    run = _copy_run(supply_dir, tmp_path, ["input.re7"])
    lines = (run / "input.re7").read_text().splitlines()
    freq_lines = [i for i, line in enumerate(lines[:2000]) if len(line.split()) == 1][1:]
    a, b = freq_lines[2], freq_lines[3]

    def swap(lines):
        lines[a], lines[b] = lines[b], lines[a]

    _edit(run / "input.re7", swap)
    # The first place the grid goes wrong is the later of the two lines.
    with pytest.raises(HydroDataError, match=rf"line {b + 1}: frequency .* does not increase"):
        read_veres(run / "input.re7")


def test_sibling_from_another_run(supply_dir, shared_data, tmp_path):
    run = _copy_run(supply_dir, tmp_path, ["input.re7"])
    shutil.copy(shared_data / "mss" / "s175" / "input.re8", run / "input.re8")
    with pytest.raises(HydroDataError, match=r"input\.re8: its forward speeds"):
        read_veres(run / "input.re7")


def test_fuzzed_files_raise_only_hydrodataerror(supply_dir, tmp_path):
    """Lines deleted, duplicated, blanked or garbled anywhere: a dataset or HydroDataError."""
    rng = np.random.default_rng(3)
    originals = {
        n: (supply_dir / n).read_text().splitlines()
        for n in ("input.re7", "input.re8", "input.re1", "input.re2")
    }
    errors = []
    for trial in range(40):
        run = tmp_path / f"r{trial}"
        run.mkdir()
        for name, lines in originals.items():
            (run / name).write_text("\n".join(lines) + "\n")
        name = list(originals)[trial % 4]
        lines = list(originals[name])
        i = int(rng.integers(len(lines)))
        action = trial // 4 % 5
        if action == 0:
            del lines[i]
        elif action == 1:
            lines.insert(i, lines[i])
        elif action == 2:
            lines[i] = ""
        elif action == 3 and lines[i]:
            j = int(rng.integers(len(lines[i])))
            lines[i] = lines[i][:j] + "#" + lines[i][j + 1 :]
        else:
            del lines[i:]
        (run / name).write_text("\n".join(lines) + "\n")
        try:
            read_veres(run / "input.re7")
        except HydroDataError as exc:
            errors.append(exc)
    # Every error names the file at fault.
    assert errors and all(exc.path is not None for exc in errors)


def test_drift_force_scale_and_direction(supply):
    """The .re2 coefficients times ρ g B²/L: in short beam waves (λ = 6 m ≪ B) the hull
    reflects nearly all the wave energy, and the sway drift tends to ½ ρ g L per m² of
    amplitude, pushing the ship the way the waves travel; in head seas the added
    resistance pushes it aft."""
    rho, g = supply.attrs["rho"], supply.attrs["g"]
    wall = 0.5 * rho * g * supply.attrs["ship_length"]
    drift = supply.drift_force.isel(omega=-1)
    beam = float(drift.sel(wave_direction=1.5 * np.pi, method="nearest").sel(influenced_dof="Sway"))
    assert -1.0 * wall < beam < -0.8 * wall  # waves travel towards -y (starboard)
    head = drift.sel(wave_direction=np.pi, method="nearest").sel(influenced_dof="Surge")
    assert float(head) < 0


def test_several_speeds_are_stacked(supply_dir, tmp_path):
    """A .re7 with two speed blocks (the supply's block repeated at 2 m/s) gives a
    forward_speed dimension; speed= picks one block."""
    lines = (supply_dir / "input.re7").read_text().splitlines()
    counts = lines[10].split()
    lines[10] = f"     2    {counts[1]}    {counts[2]}     {counts[3]}"
    block = lines[17:]
    speed_line = block[0].split()
    block[0] = "  2.0000000E+00  " + "  ".join(speed_line[1:])
    (tmp_path / "input.re7").write_text("\n".join(lines + block) + "\n")
    ds = read_veres(tmp_path / "input.re7")
    np.testing.assert_array_equal(ds.forward_speed.values, [0.0, 2.0])
    assert ds.added_mass.dims[0] == "forward_speed"
    one = read_veres(tmp_path / "input.re7", speed=2.0)
    np.testing.assert_array_equal(one.added_mass.values, ds.added_mass.isel(forward_speed=1))
    assert float(one.forward_speed) == 2.0
