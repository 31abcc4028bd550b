"""The time step of a run and its energy balance; the fit's motion error kept by reduce;
the limiting Hs within the grid; degrees in the printed statistics; repeated --dof.

References no one here wrote: the frequency-domain response of the same linear model
(``component_motions``), the first-order hold's gain sinc²(1/N) (Oppenheim & Schafer
(2010)), and the fit's own ``motion_error`` recorded in its model file.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import ArgumentError, CumminsWarning
from cummins.seakeeping.waves import irregular_waves, regular_wave, wave_spectrum
from cummins.timedomain.simulate import component_motions, simulate_waves
from cummins.timedomain.time_step import (
    ENERGY_TOLERANCE,
    STEPS_PER_SHORTEST_PERIOD,
    largest_time_step,
)

TANKER = cummins.demo_files() / "tanker.1"


@pytest.fixture(scope="module")
def tanker():
    ds = cummins.read(TANKER)
    model = cummins.fit_radiation(ds)
    vessel = cummins.vessel_from_hydrodb(ds, model, viscous_damping=[1e6, 1e6, 0, 5e8, 0, 1e10])
    return ds, model, vessel


def _run(args, code=0):
    result = CliRunner().invoke(main, [str(a) for a in args])
    assert result.exit_code == code, result.output
    assert "Traceback" not in result.output
    return result


def test_largest_step_is_six_per_shortest_period():
    limit, reason = largest_time_step([0.5, 2 * np.pi / 1.5, -1.0])
    assert limit == pytest.approx(1.5 / STEPS_PER_SHORTEST_PERIOD)
    assert "1.5 s" in reason


def test_a_step_too_long_for_the_sea_is_refused(tanker):
    """The audit's run: Hs 4 m, Tp 10 s at dt 5 s (its components reach 4 rad/s, Nyquist
    at 0.63): refused in the API naming dt and the step that would do."""
    ds, _, vessel = tanker
    sea = irregular_waves(wave_spectrum("jonswap", 4.0, 10.0), duration=600, seed=1, data=ds)
    limit = 2 * np.pi / sea.omega.max() / STEPS_PER_SHORTEST_PERIOD
    with pytest.raises(ArgumentError, match=r"dt = 5 s .*give dt <= 0\.2"):
        simulate_waves(vessel, ds, sea, duration=600, dt=5.0)
    run = simulate_waves(vessel, ds, sea, duration=600, dt=0.98 * limit)  # accepted
    assert run.attrs["energy_relative_residual"] < 0.5 * ENERGY_TOLERANCE  # 0.0021


def test_cli_refuses_the_step_before_the_run(tmp_path):
    result = _run(
        ["simulate", TANKER, "--hs", "4", "--tp", "10", "--heading", "150", "--duration",
         "600", "--dt", "5", "-o", tmp_path / "big.nc"],
        code=2,
    )  # fmt: skip
    assert "--dt = 5 s" in result.output and "give --dt <= 0.26" in result.output
    assert not (tmp_path / "big.nc").exists()


@pytest.mark.parametrize("steps", [6, 60])
def test_regular_amplitude_follows_the_first_order_hold(tanker, steps):
    """A regular 9 s wave: the steady heave amplitude against the frequency domain's
    falls short by 1 − sinc²(1/N) (8.8 % at N = 6, 0.09 % at 60; measured 9.4 % and
    0.16 %: within 1.5 % of the amplitude of it), and the energy balance sees it: a
    failure at 6 steps, none at 60."""
    ds, _, vessel = tanker
    period = 9.0
    wave = regular_wave(1.0, period, np.radians(150))
    reference = np.abs(component_motions(vessel, ds, wave)[0, 2])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = simulate_waves(vessel, ds, wave, duration=20 * period, dt=period / steps)
    t = run.time.values
    last = t >= t[-1] - 10 * period
    phasor = np.exp(1j * 2 * np.pi / period * t[last])
    amplitude = abs(2 * np.mean(run.motion.sel(dof="Heave").values[last] * phasor.conj()))
    expected = np.sinc(1 / steps) ** 2
    assert amplitude / reference == pytest.approx(expected, abs=0.015)
    failed = [w for w in caught if issubclass(w.category, CumminsWarning)]
    if steps == 6:
        assert run.attrs["energy_relative_residual"] > 5 * ENERGY_TOLERANCE
        assert "energy balance" in run.attrs["failure"] and failed
    else:
        assert run.attrs["energy_relative_residual"] < 0.2 * ENERGY_TOLERANCE
        assert "failure" not in run.attrs and not failed


def test_cli_failed_balance_exits_3_and_prints_degrees(tmp_path):
    """A regular 6 s wave at 0.8 s (7.5 steps per period) runs, is written, and fails its
    energy balance with exit status 3; the table gives roll and pitch in degrees, equal to
    the file's radians × 180/π."""
    out = tmp_path / "reg.nc"
    result = _run(
        ["simulate", TANKER, "--regular", "--wave-period", "6", "--heading", "150",
         "--duration", "60", "--dt", "0.8", "-o", out],
        code=3,
    )  # fmt: skip
    assert "failure: the energy balance misses" in result.output and out.exists()
    with xr.open_dataset(out, engine="h5netcdf") as run:
        run = run.load()
    assert run.motion.attrs["units"].split(" | ")[3] == "rad"
    roll = run.motion.sel(dof="Roll").values
    line = next(x for x in result.output.splitlines() if "Roll" in x)
    cells = [c.strip() for c in line.replace("│", "|").split("|") if c.strip()]
    assert cells[-1] == "deg"
    assert float(cells[2]) == pytest.approx(np.degrees(np.abs(roll).max()), rel=1e-3)


def test_quadratic_damping_work_closes_the_energy_balance(tanker):
    """With b₂|φ̇|φ̇ on roll its work enters the balance: the residual is that of a
    linear run (it was the damping's work, 0.6 % of the input, before)."""
    ds, _, vessel = tanker
    from cummins.timedomain.simulate import quadratic_damping_force

    sea = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0), duration=300, seed=1, data=ds, direction=np.pi / 2
    )
    force = quadratic_damping_force(vessel.dofs, {"Roll": 2e10})
    run = simulate_waves(vessel, ds, sea, duration=300, dt=0.1, nonlinear_force=force)
    assert run.attrs["energy_nonlinear"] < -1e-3 * run.attrs["energy_input"]
    assert run.attrs["energy_relative_residual"] < 1e-3


def test_runge_kutta_step_bounded_by_the_fastest_pole(tanker):
    vessel = tanker[2]
    f = vessel.state_space()[0]
    limit, reason = largest_time_step([0.1], f)
    assert limit == pytest.approx(2.5 / np.abs(np.linalg.eigvals(f)).max())
    assert "Runge-Kutta" in reason


def test_repeated_dof_is_refused_in_one_line(tmp_path):
    for command in (["simulate", "--regular", "--wave-period", "9"], ["rao"]):
        result = _run(
            [command[0], TANKER, *command[1:], "-o", tmp_path / "x.nc", "--dof", "Heave",
             "--dof", "Heave"],
            code=2,
        )  # fmt: skip
        assert "Heave is given twice" in result.output


def test_reduce_judges_by_the_fits_motion_error(tmp_path, shared_data):
    """The AQWA PEND hull: the fit leaves spikes of B(ω) out and scores 0.40 %; reduce's
    unreduced model scores the same (it said 1.73 %, every frequency) and meets 1 %."""
    data = shared_data / "corpus" / "WEC-Sim" / "aqwa_19.1_PEND_hull" / "19_1.LIS"
    model = tmp_path / "model.nc"
    fit = _run(["fit", data, "-o", model])
    from cummins.radiation.model_file import read_radiation_model

    recorded = float(read_radiation_model(model).attrs["motion_error"])
    assert f"motion-RAO error {recorded:.2%}" in fit.output
    _run(["reduce", model, "-o", tmp_path / "red.nc", "--motion-tol", "0.01", "--data", data])
    reduced = read_radiation_model(tmp_path / "red.nc")
    assert reduced.attrs["motion_error_unreduced"] == pytest.approx(recorded, rel=1e-6)
    assert recorded < reduced.attrs["motion_error"] <= 0.01


def test_limiting_hs_is_not_extrapolated_beyond_the_grid():
    """Linear responses: a case at Hs 2 m with ratio 0.5 scales to 4 m (inside a 1–4 m
    grid: kept), one at ratio 0.01 to 400 m (beyond: the grid's 4 m and the flag)."""
    from cummins.studies.operability import exceedance, limiting_hs
    from cummins.studies.study import Limit

    hs = np.array([1.0, 2.0, 4.0])
    per_tp = np.array([0.25, 0.005])  # significant amplitude per metre of Hs
    sig = hs[:, None, None] * per_tp[None, :, None]
    stats = xr.Dataset(
        {
            "significant_amplitude": (("hs", "tp", "dof"), sig),
            "maximum": (("hs", "tp", "dof"), 2 * sig),
        },
        coords={"hs": hs, "tp": [8.0, 12.0], "dof": ["Heave"], "heading": 180.0},
    ).expand_dims("heading")
    lim = limiting_hs(exceedance(stats, [Limit("Heave", "significant", 1.0, "1 m")]))
    values = lim.sel(heading=180.0).values
    assert values[0] == pytest.approx(4.0) and values[1] == 4.0
    assert lim.beyond_grid.sel(heading=180.0).values.tolist() == [False, True]
