"""MSS vessel structs: against the WAMIT and VERES files MSS processed, round trips."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.io
import xarray as xr

import cummins
from cummins import HydroDataError
from cummins.io.mss import read_mss, sniff, sniff_dir, write_mss
from cummins.io.veres import read_veres_transfer_function
from cummins.io.wamit import read_wamit_out

#: T = diag(1, -1, -1, 1, -1, -1): z-up (x fwd, y port) to z-down (x fwd, y stbd).
Z_DOWN = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])


@pytest.fixture(scope="module")
def mss_dir(shared_data):
    return shared_data / "mss"


@pytest.fixture(scope="module")
def tanker_mat(mss_dir):
    return read_mss(mss_dir / "tanker" / "tanker.mat")


@pytest.fixture(scope="module")
def s175_mat(mss_dir):
    return read_mss(mss_dir / "s175" / "s175.mat")


def _raw_vessel(path):
    return scipy.io.loadmat(str(path))["vessel"][0, 0]


def _assert_same(a, b, names=None, rtol=1e-12):
    """Every variable of ``a`` equal in ``b``, to ``rtol`` of the variable's largest entry."""
    for name in names or list(a.data_vars):
        assert name in b, name
        x, y = a[name].values, b[name].transpose(*a[name].dims).values
        scale = max(float(np.abs(x).max()), 1e-300)
        assert np.abs(x - y).max() <= rtol * scale, name


# --------------------------------------------------------------------------- detection


def test_sniff(mss_dir):
    for name in ("tanker/tanker.mat", "supply/supply.mat", "s175/s175.mat"):
        assert sniff(mss_dir / name)
    # The fitted-model files hold a struct vesselABC, not vessel; text files are not .mat.
    for name in ("tanker/tankerABC.mat", "tanker/tanker.1", "supply/input.re7"):
        assert not sniff(mss_dir / name)
    assert sniff_dir(mss_dir / "supply") == [mss_dir / "supply" / "supply.mat"]
    assert cummins.detect_format(mss_dir / "tanker" / "tanker.mat")[0] == "mss"


# --------------------------------------------------------------------------- tanker (WAMIT)


def test_tanker_frequency_limits_detected(tanker_mat, mss_dir):
    """freqs = [0, 58 WAMIT frequencies, 10]: ω = 0 and the stand-in for ω = ∞ are split off."""
    raw = _raw_vessel(mss_dir / "tanker" / "tanker.mat")
    freqs = raw["freqs"].ravel()
    assert freqs[0] == 0 and freqs[-1] == 10
    np.testing.assert_array_equal(tanker_mat.omega.values, freqs[1:-1])
    np.testing.assert_array_equal(tanker_mat.added_mass_zero.values, raw["A"][:, :, 0])
    np.testing.assert_array_equal(tanker_mat.added_mass_inf.values, raw["A"][:, :, -1])
    history = tanker_mat.attrs["history"]
    assert "omega = 0" in history and "stand-in for omega = infinity" in history


def test_tanker_agrees_with_wamit(tanker_mat, tanker_wamit):
    """MSS's wamit2vessel output equals the WAMIT files read by cummins, in z-down axes.

    A, B, A(0), A(∞) and MRB come from the same printed numbers: they agree to round-off
    (1e-12 of each variable's largest entry). MSS took C from the .out header, printed to
    5-6 digits, cummins from the .hst (7 digits): 2e-5. MSS built the excitation from the
    modulus and phase columns of the .3, cummins from the real and imaginary columns, all
    printed to 7 digits (the phase in degrees: up to 180 x 5e-7 deg): 3e-6 of each value.
    """
    wamit = cummins.change_axes(tanker_wamit, "z-down")
    assert tanker_mat.attrs["axis_convention"] == "z-down"
    _assert_same(
        wamit,
        tanker_mat,
        ["added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero", "inertia_matrix"],
    )
    _assert_same(wamit, tanker_mat, ["hydrostatic_stiffness"], rtol=2e-5)
    # Wave directions computed by WAMIT (0…180 deg, i.e. 0 and 180…350 deg in z-down);
    # MSS's other 17 headings are its port-starboard mirror of them.
    beta = wamit.wave_direction.values
    x_mss = tanker_mat.excitation_force.sel(wave_direction=beta, method="nearest")
    np.testing.assert_allclose(x_mss.wave_direction, beta, atol=1e-12)
    x, y = wamit.excitation_force.values, x_mss.values
    # In head and following seas sway, roll and yaw are numerical noise (< 1e-7 of their
    # peak), whose sign MSS's port-starboard mirroring flips: 2e-7 of each DOF's peak.
    peak = np.abs(x).max(axis=(0, 1))
    assert np.all(np.abs(x - y) <= 3e-6 * np.abs(x) + 2e-7 * peak)


def test_tanker_motion_rao_agrees_with_wamit_out(tanker_mat, mss_dir):
    """MSS's motionRAO (from WAMIT's .4) against the RAOs of the .out log: the .out prints
    phases in whole degrees (0.5 deg = 0.9 % of the modulus), so 1 % of each DOF's peak."""
    out = cummins.change_axes(read_wamit_out(mss_dir / "tanker" / "tanker.out"), "z-down")
    mss = tanker_mat.rao.sel(wave_direction=out.wave_direction.values, method="nearest")
    x, y = out.rao.values, mss.values
    peak = np.abs(x).max(axis=(0, 1))
    assert np.all(np.abs(x - y).max(axis=(0, 1)) <= 0.01 * peak)


def test_tanker_points(tanker_mat, tanker_wamit):
    """CO is WAMIT's origin; main.CG = [x, y, KG] is converted to the FSD vector from CO."""
    np.testing.assert_allclose(tanker_mat.attrs["reference_point"], [0, 0, 0], atol=1e-9)
    cg_wamit = np.asarray(tanker_wamit.attrs["center_of_gravity"]) * Z_DOWN[:3]
    np.testing.assert_allclose(tanker_mat.attrs["center_of_gravity"], cg_wamit, atol=1e-9)
    cb_wamit = np.asarray(tanker_wamit.attrs["center_of_buoyancy"]) * Z_DOWN[:3]
    np.testing.assert_allclose(tanker_mat.attrs["center_of_buoyancy"], cb_wamit, atol=1e-5)


def test_constants_and_conflicts(tanker_mat, mss_dir):
    assert tanker_mat.attrs["rho"] == 1025.0
    assert tanker_mat.attrs["g"] == 9.80665
    with pytest.raises(HydroDataError, match="rho"):
        read_mss(mss_dir / "tanker" / "tanker.mat", rho=1000.0)


# --------------------------------------------------------------------------- VERES-derived


def test_supply_raos_moved_from_the_veres_point(mss_dir):
    """supply.mat keeps forceRAO about the VERES motion point (x of G) while A, B, C, MRB
    are about CO. The reader moves the RAOs to CO; the heave force, which a shift along x
    does not change, is untouched, the pitch moment changes by x_G · F3."""
    path = mss_dir / "supply" / "supply.mat"
    moved = read_mss(path)
    x_g = float(moved.attrs["center_of_gravity"][0])
    as_stored = read_mss(path, rao_reference=moved.attrs["reference_point"])
    assert "VERES motion reference point" in moved.attrs["history"]
    f = as_stored.excitation_force
    g = moved.excitation_force
    np.testing.assert_allclose(g.sel(influenced_dof="Heave"), f.sel(influenced_dof="Heave"))
    # Moment about CO of the heave force at (x_g, 0, 0), z down: M5 = -x_g F3.
    expected = f.sel(influenced_dof="Pitch") - x_g * f.sel(influenced_dof="Heave")
    np.testing.assert_allclose(g.sel(influenced_dof="Pitch"), expected, rtol=1e-12)


def test_s175_forward_speeds(s175_mat, mss_dir):
    raw = _raw_vessel(mss_dir / "s175" / "s175.mat")
    np.testing.assert_array_equal(s175_mat.forward_speed.values, raw["velocities"].ravel())
    assert s175_mat.added_mass.dims[0] == "forward_speed"
    # A(ω) per speed is A[:, :, ω, speed] of the struct.
    np.testing.assert_array_equal(
        s175_mat.added_mass.isel(forward_speed=3)
        .transpose("influenced_dof", "radiating_dof", "omega")
        .values,
        raw["A"][:, :, :, 3],
    )
    one = read_mss(mss_dir / "s175" / "s175.mat", speed=float(raw["velocities"][0, 2]))
    _assert_same(one, s175_mat.isel(forward_speed=2), rtol=0)
    with pytest.raises(HydroDataError, match="forward speed 3"):
        read_mss(mss_dir / "s175" / "s175.mat", speed=3.0)


def test_s175_reference_height_from_the_veres_files(s175_mat, mss_dir):
    """VERES computed the S-175 about ZMTN = VCG (0.05 m above the waterline) and MSS moved
    the matrices along x only: the reader finds the reference point 0.05 m above CO."""
    tf = read_veres_transfer_function(mss_dir / "s175" / "input.re8")
    z_veres_up = float(tf.attrs["reference_point"][2])
    assert z_veres_up == pytest.approx(0.05, abs=1e-5)
    np.testing.assert_allclose(s175_mat.attrs["reference_point"], [0, 0, -z_veres_up], atol=1e-5)


# --------------------------------------------------------------------------- writing


def test_round_trip_wamit_tanker(tanker_wamit, tmp_path):
    """WAMIT (z-up) → MSS struct → reader: the z-down data, to round-off (1e-12), its
    0–180° headings completed to 0–350° by port/starboard symmetry, as MSS's tanker.mat."""
    from cummins.seakeeping.headings import mirror_headings

    path = write_mss(tanker_wamit, tmp_path / "tanker.mat")
    back = read_mss(path)
    expected, coverage = mirror_headings(cummins.change_axes(tanker_wamit, "z-down"))
    assert coverage.mirror_used and expected.sizes["wave_direction"] == 36
    # MSS's driftfrc holds surge, sway and yaw (the .out's heave, roll, pitch drift lost)
    vertical = {"influenced_dof": ["Heave", "Roll", "Pitch"]}
    assert float(np.abs(expected.drift_force.loc[vertical]).max()) > 0
    expected["drift_force"] = expected.drift_force.copy()
    expected.drift_force.loc[vertical] = 0.0
    _assert_same(expected, back)
    # plus motionRAO, which the WAMIT files lack (no .4): cummins' RAOs, as MSS's tanker.mat
    assert set(back.data_vars) == set(expected.data_vars) | {"rao"}
    np.testing.assert_array_equal(back.omega, expected.omega)
    np.testing.assert_allclose(back.wave_direction, expected.wave_direction, atol=1e-15)
    # MSS's layout: freqs = [0, ω…, 10] with zero damping at both ends (vessel2ss needs it).
    raw = _raw_vessel(path)
    freqs = raw["freqs"].ravel()
    assert freqs[0] == 0 and freqs[-1] == 10 and freqs.size == expected.omega.size + 2
    assert not np.any(raw["B"][:, :, [0, -1]])
    np.testing.assert_allclose(
        raw["main"]["CG"][0, 0].ravel(), expected.attrs["center_of_gravity"], atol=1e-9
    )


def test_round_trip_mss_files(tanker_mat, s175_mat, tmp_path):
    """tanker.mat and s175.mat (5 speeds, reference point 0.05 m above CO) → write → read
    reproduce the datasets, reference point included."""
    back = read_mss(write_mss(tanker_mat, tmp_path / "t.mat"))
    _assert_same(tanker_mat, back)
    back = read_mss(write_mss(s175_mat, tmp_path / "s.mat"))
    _assert_same(s175_mat, back)
    np.testing.assert_array_equal(back.forward_speed, s175_mat.forward_speed)
    np.testing.assert_allclose(back.attrs["reference_point"], s175_mat.attrs["reference_point"])
    assert "history before write_mss" in back.attrs["history"]


def test_write_about_co_for_mss(s175_mat, tmp_path):
    """Moved to CO first (as MSS wants), the struct says so and MRB holds r_g from CO."""
    at_co = cummins.move_reference_point(s175_mat, [0.0, 0.0, 0.0])
    path = write_mss(at_co, tmp_path / "co.mat")
    raw = _raw_vessel(path)
    assert str(raw["hydrodynamic_reference"][0]) == "CO"
    mrb = raw["MRB"]
    # main.CG holds VERES's single-precision VCG (9.5500002): 1e-5 m.
    z_g = s175_mat.attrs["center_of_gravity"][2]
    assert mrb[0, 4] / mrb[0, 0] == pytest.approx(z_g, abs=1e-5)
    back = read_mss(path)
    # Moving the drift forces 0.05 m up creates roll and pitch drift moments, which
    # driftfrc (surge, sway, yaw) cannot hold.
    _assert_same(at_co, back, [n for n in at_co.data_vars if n != "drift_force"])
    _assert_same(
        at_co.isel(influenced_dof=[0, 1, 5]),
        back.isel(influenced_dof=[0, 1, 5]),
        ["drift_force"],
    )


def test_write_keeps_limits_when_frequencies_exceed_10(tanker_wamit, tmp_path):
    """Above 10 rad/s MSS's stand-in cannot be used: A(0), A(∞) go to vessel.cummins."""
    ds = tanker_wamit.assign_coords(omega=tanker_wamit.omega * 2)
    back = read_mss(write_mss(ds, tmp_path / "fast.mat"))
    expected = cummins.change_axes(ds, "z-down")
    _assert_same(expected, back, ["added_mass_inf", "added_mass_zero", "added_mass"])
    np.testing.assert_array_equal(back.omega, expected.omega)


# --------------------------------------------------------------------------- errors


def test_errors(mss_dir, tmp_path):
    with pytest.raises(HydroDataError, match="vesselABC"):
        read_mss(mss_dir / "tanker" / "tankerABC.mat")
    with pytest.raises(HydroDataError, match="not a readable MATLAB"):
        read_mss(mss_dir / "tanker" / "tanker.1")
    data = (mss_dir / "supply" / "supply.mat").read_bytes()
    truncated = tmp_path / "truncated.mat"
    truncated.write_bytes(data[: len(data) // 2])
    with pytest.raises(HydroDataError, match=r"truncated\.mat"):
        read_mss(truncated)
    # A struct whose A has the wrong shape names the field.
    vessel = {"freqs": np.array([[0.5, 1.0]]), "A": np.zeros((6, 6, 3)), "B": np.zeros((6, 6, 2))}
    scipy.io.savemat(tmp_path / "bad.mat", {"vessel": vessel})
    with pytest.raises(HydroDataError, match=r"vessel\.A"):
        read_mss(tmp_path / "bad.mat")
    with pytest.raises(HydroDataError, match="six DOFs"):
        write_mss(
            cummins.select_dofs(read_mss(mss_dir / "tanker" / "tanker.mat"), ["Heave", "Pitch"]),
            tmp_path / "x.mat",
        )


def _outcome(path) -> xr.Dataset | HydroDataError:
    """What ``read_mss`` makes of ``path``: a dataset, or the HydroDataError (any other
    exception propagates and fails the test)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            return read_mss(path)
    except HydroDataError as exc:
        return exc


def _check_success(ds: xr.Dataset) -> None:
    """A dataset from damaged input is a valid one: the structural validation passes and
    every number in it, coordinates included, is finite (checked here, not by validate)."""
    assert cummins.validate(ds) is ds
    for name in [*ds.data_vars, *ds.coords]:
        values = np.asarray(ds[name].values)
        if values.dtype.kind in "fc":
            assert np.all(np.isfinite(values)), name


def test_damaged_bytes_raise_only_hydrodataerror(mss_dir, tmp_path):
    """Random byte damage: either a valid dataset or HydroDataError naming the file,
    nothing else. Measured 2026-12-02: the 25 damaged files all raise (the zlib-compressed
    MAT 5 stream does not survive a changed byte: "not a readable MATLAB .mat file")."""
    data = bytearray((mss_dir / "supply" / "supply.mat").read_bytes())
    rng = np.random.default_rng(7)
    outcomes = {"error": 0, "dataset": 0}
    for trial in range(25):
        damaged = bytearray(data)
        for k in rng.integers(128, len(data), size=rng.integers(1, 10)):
            damaged[k] = int(rng.integers(256))
        path = tmp_path / f"f{trial}.mat"
        path.write_bytes(bytes(damaged))
        result = _outcome(path)
        if isinstance(result, HydroDataError):
            outcomes["error"] += 1
            assert path.name in str(result)
        else:
            outcomes["dataset"] += 1
            _check_success(result)
    assert outcomes["error"] >= 1, outcomes
    assert sum(outcomes.values()) == 25


#: Struct fields damaged by the fuzz below, and what is done to one of them.
FUZZED_FIELDS = ("MRB", "A", "B", "C", "freqs", "Bv", "velocities")
FUZZ_OPERATIONS = ("nan", "inf", "scale one entry", "drop the last column", "negate", "remove")


def _damaged_struct(vessel, rng) -> tuple[dict, str, str]:
    """The MSS vessel struct with one field damaged (FUZZ_OPERATIONS)."""
    fields = {name: vessel[name] for name in vessel.dtype.names}
    name = FUZZED_FIELDS[rng.integers(len(FUZZED_FIELDS))]
    op = FUZZ_OPERATIONS[rng.integers(len(FUZZ_OPERATIONS))]
    x = np.array(fields[name], dtype=float)
    if op == "remove":
        del fields[name]
        return fields, name, op
    if op == "nan":
        x.flat[rng.integers(x.size)] = np.nan
    elif op == "inf":
        x.flat[rng.integers(x.size)] = np.inf
    elif op == "scale one entry":
        x.flat[rng.integers(x.size)] *= 1 + rng.normal()
    elif op == "drop the last column":
        x = x[..., :-1]
    else:
        x = -x
    fields[name] = x
    return fields, name, op


def test_fuzzed_struct_raises_only_hydrodataerror(mss_dir, tmp_path):
    """A readable MAT file whose vessel struct is damaged (one field made NaN or Inf,
    scaled, truncated, negated or removed, 40 draws): either HydroDataError, or a dataset
    that validates with every number finite, and which, when A, B and freqs were left
    alone, holds the original A and B. Both outcomes occur (a wrong sign of the restoring
    or a missing Bv is for cummins.check, not for the reader).

    Measured 2026-12-02: 23 errors, 17 datasets. Before, a NaN or Inf in vessel.velocities
    (forward speed NaN m/s) and in vessel.C at a frequency other than the first passed
    unseen: now HydroDataError naming the field."""
    source = mss_dir / "supply" / "supply.mat"
    vessel = _raw_vessel(source)
    reference = _outcome(source)
    rng = np.random.default_rng(7)
    outcomes = {"error": 0, "dataset": 0}
    for trial in range(40):
        fields, name, op = _damaged_struct(vessel, rng)
        path = tmp_path / f"s{trial}.mat"
        scipy.io.savemat(path, {"vessel": fields})
        result = _outcome(path)
        if isinstance(result, HydroDataError):
            outcomes["error"] += 1
            assert path.name in str(result), (name, op)
            continue
        outcomes["dataset"] += 1
        assert op not in ("nan", "inf"), (name, op)  # a NaN or Inf is damage wherever it is
        _check_success(result)
        if name not in ("A", "B", "freqs"):
            np.testing.assert_array_equal(result.added_mass, reference.added_mass)
            np.testing.assert_array_equal(result.radiation_damping, reference.radiation_damping)
    assert outcomes["error"] >= 1 and outcomes["dataset"] >= 1, outcomes


# --------------------------------------------------------------------------- RAO struct


def _m_tables(path) -> dict[tuple[str, int, int], np.ndarray]:
    """The tables of MSS's ``.m`` text twin: ``RAO.Amp{k}(:,:,s) =... [rows]``, 40 × 12."""
    import re

    text = path.read_text()
    pattern = r"RAO\.(Amp|Phase)\{(\d)\}\(:,:,(\d)\)\s*=\s*\.\.\.\s*\[([^\]]*)\]"
    return {
        (m[1], int(m[2]), int(m[3])): np.array(m[4].split(), dtype=float).reshape(40, 12)
        for m in re.finditer(pattern, text)
    }


def _m_vector(path, name: str) -> np.ndarray:
    import re

    found = re.search(rf"RAO\.{name}\s*=\s*\[([^\]]*)\]", path.read_text())
    return np.array(found[1].split(), dtype=float)


def test_naval_vessel_force_rao_against_its_text_twin(corpus):
    """MSS's force RAOs of the naval vessel: the .mat struct against the .m MSS printed
    beside it (5 significant digits, phases in radians to 4 decimals).

    Measured over all 5 × 40 × 12 × 6 entries: |amplitude| within 4.98e-5 relative (the
    5-digit rounding), the complex value amp·exp(i·phase) within 5.02e-4 relative (the
    rounding of phases up to 40 rad); limits 6.3e-5 and 6.3e-4. Coordinates within the
    .m's 3 decimals (speeds: 1 decimal, 5.144 m/s printed 5.1)."""
    from cummins.io.mss import read_force_rao

    folder = corpus / "MSS" / "navalvessel_forceRAO"
    twin = folder / "forceRAO_navalvessel.m"
    rao = read_force_rao(folder / "forceRAO_navalvessel.mat")
    assert rao.dims == ("forward_speed", "omega", "wave_direction", "influenced_dof")
    assert rao.shape == (5, 40, 12, 6)
    assert np.all(np.isfinite(rao.values)) and np.abs(rao.values).max() > 1e5
    np.testing.assert_allclose(rao.omega, _m_vector(twin, "Freq"), atol=5e-4)
    np.testing.assert_allclose(rao.wave_direction, _m_vector(twin, "Dir"), atol=5e-4)
    np.testing.assert_allclose(rao.forward_speed, _m_vector(twin, "Vel"), atol=0.05)
    tables = _m_tables(twin)
    assert len(tables) == 60  # Amp and Phase, 6 DOFs, 5 speeds
    # the first number of the .m: surge amplitude, 0.25 rad/s, following seas, zero speed
    assert abs(abs(rao.values[0, 0, 0, 0]) / 2.2256e4 - 1) <= 6.3e-5
    worst_amp = worst = 0.0
    for k in range(1, 7):
        for s in range(1, 6):
            amp, phase = tables[("Amp", k, s)], tables[("Phase", k, s)]
            got = rao.values[s - 1, :, :, k - 1]
            worst_amp = max(worst_amp, float(np.max(np.abs(np.abs(got) - amp) / amp)))
            expected = amp * np.exp(1j * phase)
            worst = max(worst, float(np.max(np.abs(got - expected) / np.abs(expected))))
    assert worst_amp <= 6.3e-5
    assert worst <= 6.3e-4


@pytest.mark.parametrize("name", ["supply/supply.mat", "s175/s175.mat", "tanker/tanker.mat"])
def test_history_has_no_empty_placeholder(mss_dir, name):
    """No history line of an MSS struct read says "read as ()" or leaves a value empty
    (an empty tuple, list or array, a 'None', or nothing after '=' or ':')."""
    import re

    ds = cummins.read(mss_dir / name)
    lines = ds.attrs["history"].splitlines()
    assert len(lines) >= 5
    empty = re.compile(r"read as \(\)|\(\)|\[\]|\bNone\b|array\(\[\]|[=:]\s*$|read as\s*$")
    assert not [line for line in lines if empty.search(line)]
    # the line that once read "read as ()": the three numbers of vessel.main.CG
    cg = r"vessel\.main\.CG read as x_g, y_g, KG .* = \[-?[0-9.]+, -?[0-9.]+, -?[0-9.]+\] m"
    assert sum(bool(re.search(cg, line)) for line in lines) == 1
