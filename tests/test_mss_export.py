"""What cummins writes for MSS, against MSS's own files: the ``vesselABC`` of ``fit --mss``
(supply and tanker against ``supplyABC.mat`` and ``tankerABC.mat``) and the ``vessel``
struct of ``convert`` from VERES files (against MSS's ``supply.mat`` and the VERES
hydrostatics printed in ``input.hyd``)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.io
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import HydroDataWarning


def _run(args, code=0):
    result = CliRunner().invoke(main, [str(a) for a in args])
    assert result.exit_code == code, result.output
    assert "Traceback" not in result.output
    return result


def _abc(path):
    return scipy.io.loadmat(path)["vesselABC"][0, 0]


@pytest.mark.parametrize(
    ("source", "reference"),
    [("supply/supply.mat", "supply/supplyABC.mat"), ("tanker/tanker.1", "tanker/tankerABC.mat")],
)
def test_fit_mss_matches_mss_own_vessel_abc(shared_data, tmp_path, source, reference):
    """r_g, MRB, G as MSS's vessel2ss wrote them (r_g was NaN before); Minv = inv(MRB + MA);
    MA is the fit's A∞ (a legitimate difference for VERES data: measured 2.3 % of the
    largest entry for the supply, 1e-5 for the WAMIT tanker, whose A∞ is the solver's)."""
    mss = shared_data / "mss"
    abc = tmp_path / "ABC.mat"
    result = _run(["fit", mss / source, "-o", tmp_path / "m.nc", "--mss", abc])
    assert "NaN" not in result.output
    ours, theirs = _abc(abc), _abc(mss / reference)
    np.testing.assert_allclose(ours["r_g"], theirs["r_g"], atol=1e-6)
    np.testing.assert_allclose(ours["MRB"], theirs["MRB"], rtol=1e-6, atol=1e-6)
    scale = np.abs(theirs["G"]).max()
    assert np.abs(ours["G"] - theirs["G"]).max() < 1e-4 * scale  # tanker: 6e-6
    np.testing.assert_allclose(ours["Minv"], np.linalg.inv(ours["MRB"] + ours["MA"]), rtol=1e-9)
    tolerance = 0.1 if "supply" in source else 1e-3
    assert np.abs(ours["MA"] - theirs["MA"]).max() < tolerance * np.abs(theirs["MA"]).max()


def test_vessel_abc_without_mass_properties_warns(tmp_path):
    """A model that knows no mass, restoring or G: NaN, and one warning naming them."""
    from cummins.io.mss_abc import write_mss_abc
    from cummins.radiation.model import RadiationModel

    model = RadiationModel(cummins.DOF_NAMES, (), np.eye(6), {"axis_convention": "z-down"})
    with pytest.warns(HydroDataWarning, match=r"vesselABC\.MRB, G, r_g unknown"):
        write_mss_abc(model, tmp_path / "x.mat")
    assert np.all(np.isnan(_abc(tmp_path / "x.mat")["r_g"]))
    # with MRB alone, r_g comes from its m·r_g block
    mrb = np.diag([1e6, 1e6, 1e6, 1e8, 1e9, 1e9])
    mrb[1, 5] = mrb[5, 1] = 1e6 * 4.0  # m x_g
    mrb[0, 4] = mrb[4, 0] = 1e6 * -2.0  # m z_g
    with pytest.warns(HydroDataWarning, match=r"vesselABC\.G unknown"):
        write_mss_abc(model, tmp_path / "y.mat", inertia_matrix=mrb)
    np.testing.assert_allclose(_abc(tmp_path / "y.mat")["r_g"].ravel(), [4.0, 0.0, -2.0])


@pytest.fixture(scope="module")
def veres_at_co(shared_data, tmp_path_factory):
    folder = tmp_path_factory.mktemp("veres")
    out = folder / "supply_veres.mat"
    src = shared_data / "mss" / "supply" / "input.re7"
    result = _run(["convert", src, out, "--reference-point", "0", "0", "0"])
    return out, result.output


def test_veres_struct_has_mss_headings_and_forces(veres_at_co, shared_data):
    """VERES gives 0–180°; the struct holds 0–350° as MSS's own supply.mat, the port side
    mirrored (sway, roll, yaw change sign): excitation and motion RAOs equal MSS's to
    1e-6 of each DOF's largest value (measured 3e-8: MSS's single precision, moved)."""
    path, _ = veres_at_co
    raw = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)["vessel"]
    np.testing.assert_allclose(np.degrees(raw.headings), np.arange(0.0, 360.0, 10.0), atol=1e-9)
    ours = cummins.read(path)
    mss = cummins.read(shared_data / "mss" / "supply" / "supply.mat")
    for name in ("excitation_force", "rao"):
        a, b = ours[name].values, mss[name].values
        assert a.shape == b.shape
        scale = np.abs(b).max(axis=(0, 1))
        assert np.all(np.abs(a - b).max(axis=(0, 1)) <= 1e-6 * scale), name
    # the mirrored halves: F(ω, −β) = T F(ω, β)
    f = ours.excitation_force.values
    signs = np.array([1, -1, 1, -1, 1, -1])
    np.testing.assert_allclose(f[:, 27, :], f[:, 9, :] * signs, rtol=1e-12, atol=0)


def test_veres_struct_main_against_veres_hydrostatics(veres_at_co):
    """particulars.GM_T and C_B against VERES's input.hyd (2.144 m, 0.651; measured 0.01 %,
    0.04 %), GM_L from the restoring as MSS builds G (97.9 m: the strip-theory C55 is not
    VERES's hydrostatic 103.6 m, 6 % apart), CG from CO; the missing CB is named."""
    path, output = veres_at_co
    particulars = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)["vessel"].main
    gm_t, gm_l, c_b = (float(getattr(particulars, k)) for k in ("GM_T", "GM_L", "C_B"))
    assert gm_t == pytest.approx(2.144, rel=1e-3)
    assert c_b == pytest.approx(0.651, rel=2e-3)
    assert gm_l == pytest.approx(103.628, rel=0.12)
    length, draught, waterline = (float(getattr(particulars, k)) for k in ("Lpp", "T", "Lwl"))
    assert length == pytest.approx(82.8) and draught == 6.0 and waterline == length
    np.testing.assert_allclose(particulars.CG, [-5.3859, 0.0, -1.3], atol=1e-3)
    assert "vessel.main lacks CB" in output
    raw = scipy.io.loadmat(path, squeeze_me=True)["vessel"]
    assert str(raw["hydrodynamic_reference"]) == "CO"


def test_veres_struct_radii_of_gyration_about_cg(veres_at_co, shared_data):
    """main.k44 … are about CG, as MSS's rbody takes them: H(r_g)ᵀ diag(m k²) H(r_g)
    rebuilds the struct's own MRB, and k55, k66 equal MSS's supply.mat (20.741, 20.700 m;
    measured 0.2 % and 0.0003 %; about CO they were 21.43, 21.39 m, 3.3 % off)."""
    path, _ = veres_at_co
    vessel = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)["vessel"]
    main = vessel.main
    m, r_g = float(main.m), np.asarray(main.CG, dtype=float)  # CG about CO = r_g here
    radii = np.array([float(main.k44), float(main.k55), float(main.k66)])
    inertia = m * np.diag(radii**2) + m * (r_g @ r_g * np.eye(3) - np.outer(r_g, r_g))
    np.testing.assert_allclose(np.diag(inertia), np.diag(vessel.MRB)[3:], rtol=1e-6)
    mss = scipy.io.loadmat(
        shared_data / "mss" / "supply" / "supply.mat", squeeze_me=True, struct_as_record=False
    )["vessel"].main
    assert float(main.k55) == pytest.approx(float(mss.k55), rel=5e-3)
    assert float(main.k66) == pytest.approx(float(mss.k66), rel=1e-3)


def test_veres_struct_off_co_and_asymmetric_warn(shared_data, tmp_path):
    """About VERES's own point (not CO) the writer says MSS wants CO; a hull that is not
    known to be symmetric keeps its 0–180° and the warning names the arc without data."""
    from cummins.io.mss import write_mss

    ds = cummins.read(shared_data / "mss" / "supply" / "input.re7")
    with pytest.warns(HydroDataWarning, match="neither CO nor CG"):
        write_mss(ds, tmp_path / "a.mat")
    lopsided = ds.copy()
    lopsided.attrs["center_of_gravity"] = np.array([-5.39, 0.5, 1.3])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        write_mss(lopsided, tmp_path / "b.mat")
    texts = [str(w.message) for w in caught]
    assert any("no wave heading between 180° and 360°" in t for t in texts), texts
    assert cummins.read(tmp_path / "b.mat").sizes["wave_direction"] == 19


def test_simulate_names_the_option_for_mss_bv_left_out(shared_data, tmp_path):
    """MSS's Bv of surge, sway and yaw varies with frequency (supply: 6.2e3 to 1.3e5 N s/m
    in surge) and is left out of the time-domain model: the note names the option that
    gives the value, not only the Python argument (viscous_damping)."""
    data = shared_data / "mss" / "supply" / "supply.mat"
    args = ["simulate", data, "--dof", "Surge", "--dof", "Heave", "--dof", "Pitch"]
    args += ["--hs", "2", "--tp", "9", "--duration", "60", "-o", tmp_path / "run.nc"]
    output = " ".join(_run(args).output.split())
    assert "Surge-Surge (6.23e+03 to 1.3e+05)" in output
    assert "left out; pass the value you want as viscous_damping (--viscous-damping" in output


def test_multi_speed_struct_keeps_one_bv_as_mss(shared_data, tmp_path):
    """MSS's s175.mat (5 speeds) holds one Bv, 6×6×36, for every speed; convert wrote it
    6×6×36×5. Now the round trip gives MSS's layout and values, and k44 … (about CG) equal
    MSS's (k55 42.000 m; about the reference point 42.077)."""
    source = shared_data / "mss" / "s175" / "s175.mat"
    _run(["convert", source, tmp_path / "s175.mat"])

    def load(path):
        return scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)["vessel"]

    ours, mss = load(tmp_path / "s175.mat"), load(source)
    assert np.shape(ours.Bv) == np.shape(mss.Bv) == (6, 6, 36)
    np.testing.assert_allclose(ours.Bv, mss.Bv, rtol=1e-12)
    assert np.shape(ours.A) == (6, 6, 36, 5)
    for k in ("k44", "k55", "k66"):
        assert float(getattr(ours.main, k)) == pytest.approx(float(getattr(mss.main, k)), rel=1e-6)
    # and --viscous-damping says it adds to the data's constant Bv (roll: 3e7 N m s/rad)
    for command in ("simulate", "rao", "identify-damping"):
        text = " ".join(_run([command, "--help"]).output.split())
        assert "added to the data's own constant additional_damping (MSS's Bv" in text


def test_wamit_struct_has_motion_raos_as_mss_tanker(shared_data, tmp_path):
    """WAMIT's tanker (.1 .3 .hst .frc, no .4) written as an MSS struct had no
    ``motionRAO``, which MSS's own ``tanker.mat`` (wamit2vessel, from WAMIT's .4) holds.
    cummins' RAOs are written instead, said by a warning, and equal MSS's complex RAOs
    within 2 % of each DOF's peak over the 58 frequencies and 36 headings (measured 0.8 %,
    surge)."""
    from cummins.errors import AssumptionWarning
    from cummins.io.mss import write_mss

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.1")
    assert "rao" not in ds
    with pytest.warns(AssumptionWarning, match="motionRAO computed by cummins"):
        write_mss(ds, tmp_path / "t.mat")

    def load(path):
        return scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)["vessel"]

    ours, mss = load(tmp_path / "t.mat"), load(shared_data / "mss" / "tanker" / "tanker.mat")
    np.testing.assert_allclose(ours.motionRAO.w, mss.motionRAO.w, rtol=1e-6)
    np.testing.assert_allclose(ours.headings, mss.headings, atol=1e-9)
    for k in range(6):
        a = ours.motionRAO.amp[k] * np.exp(1j * ours.motionRAO.phase[k])
        b = mss.motionRAO.amp[k][:, :, 0] * np.exp(1j * mss.motionRAO.phase[k][:, :, 0])
        assert np.abs(a - b).max() <= 0.02 * np.abs(b).max(), k
    # read back, they are known as cummins', and `rao` says so instead of "the solver's"
    from cummins.io.mss.reader import RAO_BY_CUMMINS

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert cummins.read(tmp_path / "t.mat").rao.attrs["description"] == RAO_BY_CUMMINS
    args = ["rao", tmp_path / "t.mat", "-o", tmp_path / "r.nc", "--headings", "90"]
    assert "note:" not in _run(args).output  # the same equation, the same RAOs
    text = " ".join(_run([*args, "--viscous-damping", "Roll", "5e8", "--force"]).output.split())
    assert "the motion RAOs the file holds (cummins', computed when it was written)" in text
    assert "the solver's" not in text
    # without the inertia, none, and the warning says what to give
    bare = ds.drop_vars("inertia_matrix")
    with pytest.warns(HydroDataWarning, match="motionRAO not written.*--mass"):
        write_mss(bare, tmp_path / "b.mat")
    assert not hasattr(load(tmp_path / "b.mat"), "motionRAO")


def test_convert_one_speed_of_a_multi_speed_struct(shared_data, tmp_path):
    """MSS's s175.mat holds 5 speeds: convert to WAMIT (or BEMIO) stopped with a Python
    hint (``ds.sel(forward_speed=0.0)``) the command line cannot follow. --speed writes one:
    the .1 reads back as the struct's zero-speed added mass (z-up, 7 digits), and a .mat
    at 10 kn holds that speed alone."""
    source = shared_data / "mss" / "s175" / "s175.mat"
    refused = CliRunner().invoke(main, ["convert", str(source), str(tmp_path / "a.1")])
    assert refused.exit_code == 2 and "choose one with --speed" in refused.output
    _run(["convert", source, tmp_path / "s.1", "--speed", "0"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        back = cummins.read(tmp_path / "s.1", rho=1025.0, g=9.81)
        data = cummins.change_axes(cummins.read(source).sel(forward_speed=0.0), "z-up")
    a, b = back.added_mass.values, data.added_mass.values
    assert np.abs(a - b).max() <= 1e-6 * np.abs(b).max()
    _run(["convert", source, tmp_path / "u.mat", "--speed", "5.14444"])
    vessel = scipy.io.loadmat(tmp_path / "u.mat", squeeze_me=True, struct_as_record=False)
    assert float(vessel["vessel"].velocities) == pytest.approx(5.14444)
    assert np.shape(vessel["vessel"].A) == (6, 6, 36)


def test_convert_main_dimensions_into_the_struct(shared_data, tmp_path):
    """WAMIT files give no main dimensions: the struct warned that vessel.main lacks Lpp,
    B, T, C_B, Lwl, S with no way to give them. --main-dimensions (MSS's tanker.mat:
    246, 46, 10 m) writes them, C_B = ∇/(Lpp B T) as MSS defines it, and the struct then
    runs the DP scenario, which refused it for the lack of them."""
    source = shared_data / "mss" / "tanker" / "tanker.1"
    warned = _run(["convert", source, tmp_path / "a.mat"]).output
    assert "--main-dimensions LPP B T" in " ".join(warned.split())
    out = tmp_path / "t.mat"
    text = _run(["convert", source, out, "--main-dimensions", "246", "46", "10"]).output
    assert "lacks Lpp" not in text
    ours = scipy.io.loadmat(out, squeeze_me=True, struct_as_record=False)["vessel"].main
    mss = scipy.io.loadmat(
        shared_data / "mss" / "tanker" / "tanker.mat", squeeze_me=True, struct_as_record=False
    )["vessel"].main
    for key in ("Lpp", "B", "T", "nabla"):
        assert float(getattr(ours, key)) == pytest.approx(float(getattr(mss, key)), rel=1e-9)
    assert float(ours.C_B) == pytest.approx(float(mss.nabla) / (246 * 46 * 10), rel=1e-9)
    _run(["dp-demo", "-o", tmp_path / "dp", "--duration", "30", "--data", out])
    # a WAMIT file has no field for them: refused, not dropped
    dims = ["--main-dimensions", "246", "46", "10"]
    _run(["convert", source, tmp_path / "w.1", *dims], code=2)
