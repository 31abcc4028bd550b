"""The vessel driven by a wave elevation record (``simulate --wave-elevation``) against the
same sea through the frequency-domain synthesis of the force."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import HydroDataError
from cummins.hydrodb import select_dofs
from cummins.seakeeping.waves import irregular_waves, wave_spectrum
from cummins.sysid.records import read_wave_elevation
from cummins.timedomain.simulate import simulate_waves
from cummins.vessel import vessel_from_hydrodb

SEMISUB = Path(__file__).parent / "data" / "semisub_capytaine.nc"
#: 5 % of critical viscous damping in heave and pitch (heave plates): without it the
#: semisub's heave rings for thousands of seconds after the start from rest
DAMPING = {"Heave": 1.03e6, "Pitch": 3.53e8}


@pytest.fixture(scope="module")
def semisub():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return select_dofs(cummins.read(SEMISUB), ["Heave", "Pitch"])


def test_a_synthesized_sea_as_csv_gives_the_motions_of_the_frequency_synthesis(semisub, tmp_path):
    """JONSWAP Hs 3 m, Tp 9 s at 0 deg, 20 min: the run from the CSV record (causal
    excitation model, from rest) and simulate_waves (excitation_force of the same wave
    components, steady start) agree after 300 s within 2 % of each motion's RMS and peak
    (measured: 0.9 % heave, 0.4 % pitch)."""
    w = semisub.omega.values
    waves = irregular_waves(
        wave_spectrum("jonswap", 3.0, 9.0), duration=1200, n_components=200, direction=0.0,
        seed=5, omega_min=w[0], omega_max=w[-1],
    )  # fmt: skip
    vessel = vessel_from_hydrodb(semisub, viscous_damping=[DAMPING["Heave"], DAMPING["Pitch"]])
    reference = simulate_waves(vessel, semisub, waves, duration=1200, dt=0.1)
    record = tmp_path / "eta.csv"
    rows = np.c_[reference.time.values, reference.wave_elevation.values * 100.0]
    np.savetxt(record, rows, fmt="%.12g", delimiter=",", header="time [s], wave elevation [cm]")
    record.write_text(record.read_text().removeprefix("# "))
    out = tmp_path / "rec.nc"
    args = [
        "simulate", SEMISUB, "--wave-elevation", record, "--heading", 0, "--dof", "Heave",
        "--dof", "Pitch", "-o", out,
    ]  # fmt: skip
    for dof, value in DAMPING.items():
        args += ["--viscous-damping", dof, value]
    result = CliRunner().invoke(main, [str(a) for a in args])
    assert result.exit_code == 0, result.output
    run = xr.load_dataset(out)
    assert run.attrs["initial"] == "rest" and run.attrs["excitation_states"] > 0
    t = run.time.values
    assert t[-1] == pytest.approx(1200.0 - run.attrs["excitation_delay"], abs=0.11)
    late = t >= 300
    expected = reference.motion.sel(time=t[late]).values
    got = run.motion.values[late]
    for d in range(2):
        assert np.std(got[:, d] - expected[:, d]) < 0.02 * np.std(expected[:, d])
        assert np.abs(got[:, d] - expected[:, d]).max() < 0.02 * np.abs(expected[:, d]).max()


def test_the_record_options_are_checked(tmp_path):
    record = tmp_path / "eta.csv"
    record.write_text("time [s], wave elevation [m]\n0, 0\n1, 0.1\n2, 0.2\n")
    base = ["simulate", str(SEMISUB), "--wave-elevation", str(record), "-o", str(tmp_path / "r.nc")]
    result = CliRunner().invoke(main, [*base, "--hs", "2", "--tp", "8"])
    assert result.exit_code == 2 and "--wave-elevation replaces" in result.output
    short = CliRunner().invoke(main, [*base, "--heading", "0", "--dof", "Heave"])
    assert short.exit_code == 2 and "less than the excitation model's time advance" in short.output


def test_read_wave_elevation(tmp_path):
    good = tmp_path / "eta.csv"
    good.write_text("# probe 1\ntime [s]; eta [mm]; Heave [m]\n0; 5; 0\n0.5; -5; 0\n1; 0; 0\n")
    eta = read_wave_elevation(good)
    assert eta.values.tolist() == [0.005, -0.005, 0.0] and eta.time.values[-1] == 1.0
    bad = tmp_path / "bad.csv"
    bad.write_text("time [s], Heave [m]\n0, 1\n1, 2\n2, 3\n")
    with pytest.raises(HydroDataError, match="no wave elevation column"):
        read_wave_elevation(bad)
    gap = tmp_path / "gap.csv"
    gap.write_text("time [s], wave elevation [m]\n0, 1\n1, 2\n3, 3\n")
    with pytest.raises(HydroDataError, match="time step changes"):
        read_wave_elevation(gap)


def test_a_record_with_second_order_is_refused_naming_both_options(tmp_path):
    """--second-order needs the sea's components; with a record it was silently ignored."""
    record = tmp_path / "eta.csv"
    record.write_text("time [s], wave elevation [m]\n0, 0\n1, 0.1\n2, 0.2\n")
    args = ["simulate", str(SEMISUB), "--wave-elevation", str(record), "--second-order"]
    result = CliRunner().invoke(main, [*args, "newman", "-o", str(tmp_path / "r.nc")])
    assert result.exit_code == 2
    assert "--second-order" in result.output and "--hs/--tp" in result.output
    assert not (tmp_path / "r.nc").exists()
