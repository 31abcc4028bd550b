"""A ship at forward speed meets the waves at the encounter frequency.

Reference: the ShipX/VERES RAOs of the S-175 that MSS ships in ``s175.mat`` (5 speeds,
36 headings): a solver's own output no one here wrote.
"""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import SimulationError
from cummins.radiation.speed import SpeedError, vessel_at_speed
from cummins.seakeeping.excitation import encounter_excitation, encounter_frequencies, forward_speed
from cummins.seakeeping.frequency_domain import impedance, motion_rao
from cummins.seakeeping.waves import regular_wave
from cummins.timedomain.simulate import simulate_waves

S175 = str(resources.files("cummins") / "data" / "s175" / "s175.mat")
VERTICAL = ["Heave", "Pitch"]
#: The range of interest and tight targets (tests/test_speed.py fits the same data so).
FIT = {"omega_max": 2.0, "r2": 0.999, "max_order": 6}


@pytest.fixture(scope="module")
def s175() -> xr.Dataset:
    return cummins.read(S175)


@pytest.fixture(scope="module")
def vertical_at_20_knots(s175):
    return vessel_at_speed(s175, float(s175.forward_speed[4]), dofs=VERTICAL, **FIT)


def _veres(one: xr.Dataset, we: np.ndarray) -> np.ndarray:
    """VERES' RAO (omega, wave_direction, dof), referred to e^{iω_e t} (conjugated where
    ω_e < 0, as VERES refers it to e^{i|ω_e|t})."""
    ref = one.rao.transpose("omega", "wave_direction", "radiating_dof").values
    return np.where((we < 0)[..., None], np.conj(ref), ref)


def test_encounter_frequency_of_the_data():
    """ω_e = ω − k U cos β: zero speed gives ω back; head seas raise it, following seas
    lower it; finite depth uses the dispersion relation (k > ω²/g)."""
    ds = cummins.read(S175)
    zero, fast = ds.isel(forward_speed=0), ds.isel(forward_speed=4)
    w = np.array([0.3, 0.5, 1.0])
    np.testing.assert_array_equal(encounter_frequencies(zero, w, np.pi), w)
    u, g = forward_speed(fast), fast.attrs["g"]
    assert u == pytest.approx(10.28889)
    np.testing.assert_allclose(encounter_frequencies(fast, w, np.pi), w + w**2 * u / g)
    np.testing.assert_allclose(encounter_frequencies(fast, w, 0.0), w - w**2 * u / g)
    np.testing.assert_allclose(encounter_frequencies(fast, w, np.pi / 2), w, atol=1e-12)
    shallow = fast.assign_attrs(water_depth=20.0)
    assert encounter_frequencies(shallow, 0.3, np.pi) > encounter_frequencies(fast, 0.3, np.pi)
    # F is conjugated exactly where ω_e < 0
    f = np.array([[1 + 2j], [3 - 1j]])
    np.testing.assert_array_equal(encounter_excitation(f, [0.5, -0.5]), [[1 + 2j], [3 + 1j]])


@pytest.mark.parametrize("k", range(5))
def test_rao_at_speed_is_the_veres_rao(s175, k):
    """Every speed and heading: heave and pitch RAOs, complex, within 1.5 % and 3 % of
    their peaks where |ω_e| lies in the data (measured ≤ 0.85 %, ≤ 2.2 %). The same data
    solved at the wave frequency miss VERES by up to 68 % at 20 kn."""
    one = s175.isel(forward_speed=k)
    rao = motion_rao(one)
    w = one.omega.values
    ww, bb = np.meshgrid(w, one.wave_direction.values, indexing="ij")
    we = encounter_frequencies(one, ww, bb)
    ref = _veres(one, we)
    tol = 1e-9 * w[-1]
    inside = (np.abs(we) >= w[0] - tol) & (np.abs(we) <= w[-1] + tol)
    if k:
        np.testing.assert_allclose(rao.encounter_frequency.values, we)
        assert rao.attrs["encounter_outside_data"] == int((~inside).sum()) > 0
    for dof, tol in (("Heave", 0.015), ("Pitch", 0.03)):
        d = list(rao.dof.values).index(dof)
        error = np.abs(rao.values[..., d] - ref[..., d]) / np.abs(ref[..., d]).max()
        assert error[inside].max() < tol, (dof, error[inside].max())
        assert np.all(np.isfinite(rao.values[..., d]))
    if k == 4:  # solving at ω instead of ω_e: far off in head seas
        head = int(np.argmin(np.abs(one.wave_direction.values - np.pi)))
        f = one.excitation_force.isel(wave_direction=head).transpose("omega", ...).values
        x = np.linalg.solve(impedance(one, w), f[..., None])[..., 0]
        d = 2
        wrong = np.abs(np.abs(x[:, d]) - np.abs(ref[:, head, d])).max()
        assert wrong > 0.3 * np.abs(ref[:, head, d]).max()


def test_vessel_at_speed_reproduces_veres(s175, vertical_at_20_knots):
    """The time-domain vessel at 20 kn (memory fitted at speed without the STF terms that
    are not memory, plus U K¹, U D¹, U G): its transfer function at ω_e against VERES'
    RAOs, every heading, |ω_e| ≤ 2 rad/s: heave within 2.5 %, pitch within 6 % of the peak
    (measured 1.4 %, 4.4 %)."""
    vessel = vertical_at_20_knots
    assert vessel.attrs["forward_speed"] == pytest.approx(10.28889)
    assert np.all(vessel.stability().real < 0)
    one = s175.isel(forward_speed=4)
    w = one.omega.values
    ww, bb = np.meshgrid(w, one.wave_direction.values, indexing="ij")
    we = encounter_frequencies(one, ww, bb)
    ref = _veres(one, we)[..., 2:5:2]
    use = (np.abs(we) >= w[0]) & (np.abs(we) <= 2.0)
    f = one.excitation_force.transpose("omega", "wave_direction", ...).values[..., 2:5:2]
    x = vessel.response(we[use], encounter_excitation(f[use], we[use]))
    for d, tol in ((0, 0.025), (1, 0.06)):
        error = np.abs(x[:, d] - ref[use][:, d]) / np.abs(ref[..., d]).max()
        assert error.max() < tol, (vessel.dofs[d], error.max())
    # the speed terms matter: the zero-speed vessel misses by far more in head seas
    from cummins.vessel import vessel_from_hydrodb

    still = vessel_from_hydrodb(
        s175.isel(forward_speed=0).sel(influenced_dof=VERTICAL, radiating_dof=VERTICAL),
        vessel_at_speed(s175, 0.0, dofs=VERTICAL, **FIT).radiation,
    )
    head = use & (np.abs(bb - np.pi) < 1e-6)
    y = still.response(we[head], f[head])
    assert np.abs(y[:, 1] - ref[head][:, 1]).max() > 0.1 * np.abs(ref[..., 1]).max()


def test_regular_head_waves_at_speed_in_the_time_domain(s175, vertical_at_20_knots):
    """simulate_waves at 20 kn in regular head waves: the motions oscillate at ω_e and
    their amplitudes equal VERES' RAO (steady start, within 5 % of the amplitude)."""
    one = s175.isel(forward_speed=4).sel(influenced_dof=VERTICAL, radiating_dof=VERTICAL)
    w = float(one.omega.values[np.argmin(np.abs(one.omega.values - 0.55))])
    sea = regular_wave(1.0, 2 * np.pi / w, np.pi)
    run = simulate_waves(vertical_at_20_knots, one, sea, duration=300.0, dt=0.1)
    we = float(encounter_frequencies(one, w, np.pi))
    assert run.attrs["forward_speed"] == pytest.approx(10.28889)
    t = run.time.values
    basis = np.c_[np.cos(we * t), np.sin(we * t)]
    head = int(np.argmin(np.abs(one.wave_direction.values - np.pi)))
    for dof in VERTICAL:
        x = run.motion.sel(dof=dof).values
        coef, *_ = np.linalg.lstsq(basis, x, rcond=None)
        assert np.std(x - basis @ coef) < 0.01 * np.std(x)  # one frequency: ω_e
        expected = abs(
            complex(one.rao.sel(radiating_dof=dof).isel(wave_direction=head).sel(omega=w).values)
        )
        assert np.hypot(*coef) == pytest.approx(expected, rel=0.05)
    eta = run.wave_elevation.values
    coef, *_ = np.linalg.lstsq(basis, eta, rcond=None)
    assert np.hypot(*coef) == pytest.approx(1.0, rel=1e-9)


def test_vessel_at_speed_refuses_what_it_cannot_build(s175):
    """A free 6-DOF ship at 20 kn is directionally unstable (yaw Munk moment): refused,
    naming the remedy; soft springs make it stable. No zero speed, or a speed not in the
    data: SpeedError."""
    u = float(s175.forward_speed[4])
    with pytest.raises(SimulationError, match="soft_springs"):
        vessel_at_speed(s175, u)
    held = vessel_at_speed(s175, u, soft_springs=200.0)
    assert np.all(held.stability().real < 0)
    assert "Sway" in held.attrs["soft_springs"] and "Yaw" in held.attrs["soft_springs"]
    with pytest.raises(SpeedError, match="no zero speed"):
        vessel_at_speed(s175.isel(forward_speed=[2, 4]), u)
    with pytest.raises(SpeedError, match="no data at 3"):
        vessel_at_speed(s175, 3.0)
    with pytest.raises(SpeedError, match="soft_springs"):
        vessel_at_speed(s175, u, soft_springs=-1.0)


def test_cli_simulate_at_speed(tmp_path):
    """``cummins simulate s175.mat --speed 10.28889 --dof Heave --dof Pitch``: the run
    oscillates at ω_e and records which memory at speed the vessel holds and its RAO error
    against the data's frequency domain (default options: the memory derived from K⁰,
    measured heave 2.5 %, pitch 4.9 %); 6 DOFs without --soft-springs: a clear error;
    --soft-springs at zero speed: a usage error."""
    runner = CliRunner()
    out = tmp_path / "run.nc"
    common = ["--regular", "--wave-period", "12", "--duration", "200", "--heading", "180"]
    result = runner.invoke(
        main,
        [
            "simulate",
            S175,
            "--speed",
            "10.28889",
            "--dof",
            "Heave",
            "--dof",
            "Pitch",
            *common,
            "-o",
            str(out),
        ],
    )
    assert result.exit_code == 0, result.output
    with xr.open_dataset(out) as run:
        assert list(run.dof.values) == VERTICAL
        t, x = run.time.values, run.motion.sel(dof="Heave").values
        assert run.attrs["forward_speed"] == pytest.approx(10.28889)
        assert run.attrs["speed_memory"].startswith("K0 + U K1 + U^2 K2")
        assert run.attrs["speed_motion_error"] < 0.08  # the fit at speed alone: 0.69
    w = 2 * np.pi / 12
    we = w + w**2 * 10.28889 / 9.81
    spectrum = np.abs(np.fft.rfft(x - x.mean(), 8 * x.size))
    peak = 2 * np.pi * np.fft.rfftfreq(8 * x.size, t[1] - t[0])[np.argmax(spectrum)]
    assert peak == pytest.approx(we, rel=0.01)
    assert abs(peak - w) > 0.2
    result = runner.invoke(
        main, ["simulate", S175, "--speed", "10.28889", *common, "-o", str(tmp_path / "b.nc")]
    )
    assert result.exit_code != 0 and "--soft-springs" in result.output
    result = runner.invoke(
        main,
        [
            "simulate",
            S175,
            "--speed",
            "0",
            "--soft-springs",
            "200",
            *common,
            "-o",
            str(tmp_path / "c.nc"),
        ],
    )
    assert result.exit_code == 2 and "--soft-springs applies" in result.output
