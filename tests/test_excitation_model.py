"""Causal excitation models: K_ex(t), the time advance t_c, the fit, the file, the drive."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy.special import erfcinv

import cummins
from cummins.errors import FitError, HydroDataError, SimulationError
from cummins.excitation_model import (
    ExcitationModel,
    causal_delay,
    excitation_irf,
    fit_excitation,
)
from cummins.excitation_model.fit import fit_response, fitting_grid, nrmse
from cummins.excitation_model.impulse import zero_frequency_force
from cummins.hydrodb import make_hydrodb

SPAR = "WEIS/ss_fitting_OC3_spar"


def pulse_hydrodb(t0=-2.0, s=1.0, with_stiffness=True):
    """One heave DOF whose excitation impulse response is a Gaussian centred at t0 < 0:
    K_ex(t) = exp(-(t - t0)^2 / (2 s^2)), F(w) = s sqrt(2 pi) exp(-s^2 w^2 / 2 - i w t0)."""
    w = np.linspace(0.01, 8.0, 400)
    force = s * np.sqrt(2 * np.pi) * np.exp(-(s**2) * w**2 / 2 - 1j * w * t0)
    ones = np.ones((w.size, 1, 1))
    return make_hydrodb(
        w,
        1e3 * ones,
        1e2 * ones,
        rho=1025.0,
        g=9.81,
        source_format="synthetic",
        dofs=["Heave"],
        wave_direction=[np.pi],
        excitation_force=force[:, None, None],
        hydrostatic_stiffness=[[s * np.sqrt(2 * np.pi)]] if with_stiffness else None,
    )


@pytest.fixture(scope="module")
def spar(corpus):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(corpus / SPAR / "spar.1")


@pytest.fixture(scope="module")
def spar_model(spar):
    return fit_excitation(spar, [0.0])


def test_impulse_response_of_a_known_pulse():
    """K_ex of a Gaussian pulse centred 2 s before t = 0, against the analytic one."""
    t = np.linspace(-10, 10, 401)
    k = excitation_irf(pulse_hydrodb(), t).values[:, 0, 0]
    exact = np.exp(-((t + 2.0) ** 2) / 2)
    assert np.abs(k - exact).max() < 2e-3
    # without the long-wave limit the integral starts at 0.01 rad/s: F(0) w_min / pi lost
    bare = excitation_irf(pulse_hydrodb(with_stiffness=False), t).values[:, 0, 0]
    assert np.abs(bare - exact).max() > 3e-3


def test_time_advance_of_a_known_pulse():
    """The energy of K_ex^2 (a Gaussian of variance s^2/2) before -t_c is erfc((t_c + t0)/s)/2."""
    t = np.linspace(-30, 30, 6001)
    irf = excitation_irf(pulse_hydrodb(), t)
    for fraction in (1e-2, 1e-3):
        expected = 1.0 * erfcinv(2 * fraction) + 2.0
        assert causal_delay(irf, fraction)[0] == pytest.approx(expected, abs=0.02)


def test_long_wave_limit_is_the_hydrostatic_heave_column(spar):
    """F(0) = C[:, heave] (z-up): the spar's heave excitation tends to rho g A_wp."""
    f0 = zero_frequency_force(spar)
    c33 = float(spar.hydrostatic_stiffness.sel(influenced_dof="Heave", radiating_dof="Heave"))
    assert f0[2] == c33
    lowest = abs(complex(spar.excitation_force.isel(omega=0, wave_direction=18)[2]))
    assert lowest == pytest.approx(c33, rel=0.06)  # the first frequency, 0.05 rad/s
    down = cummins.change_axes(spar, "z-down")  # heave down: F3 and F(0) change sign
    low = complex(down.excitation_force.isel(omega=0, wave_direction=18)[2])
    assert zero_frequency_force(down)[2] == pytest.approx(-c33)
    assert low.real == pytest.approx(-c33, rel=0.06)


def test_spar_head_seas_meet_the_target_with_fewer_states_than_ss_fitting(spar_model, spar):
    """OC3 spar, 0 deg: every excited DOF within 3 % NRMSE over its band, stable, and
    fewer states than SS_Excitation_Fitting's 57 (whose error is measured elsewhere)."""
    m = spar_model
    assert m.is_stable() and not m.attrs["failures"]
    assert m.orders[0].tolist()[1::2] == [0, 0, 0]  # sway, roll, yaw: not excited
    assert 0 < m.total_order <= 57
    w = spar.omega.values
    data = spar.excitation_force.sel(wave_direction=0.0).transpose("omega", "influenced_dof").values
    fitted = m.frequency_response(w)[:, 0, :]
    for d in (0, 2, 4):
        band = np.abs(data[:, d]) > 0.01 * np.abs(data[:, d]).max()
        assert nrmse(fitted[:, d], data[:, d], band) < 0.03
    assert 5.0 < m.delays[0] < 20.0


def test_model_impulse_response_follows_the_data_after_minus_tc(spar_model, spar):
    m = spar_model
    irf = excitation_irf(spar, wave_direction=[0.0])
    t = irf.time.values
    after = t > -m.delays[0] + 1.0
    data = irf.values[after, 0, 2]
    model = m.impulse_response(t)[after, 0, 2]
    assert np.linalg.norm(model - data) < 0.1 * np.linalg.norm(data)
    assert np.all(m.impulse_response(t[t < -m.delays[0]]) == 0)


def test_given_delay_is_used_and_zero_delay_misses_the_target(spar):
    model = fit_excitation(spar, [0.0], delay=0.0, max_order=10)
    assert model.delays.tolist() == [0.0]
    assert model.attrs["delay_rule"] == "given"
    assert len(model.attrs["failures"]) == 3  # K_ex starts ~10 s before 0: not causal
    assert "NRMSE" in model.model(0, 0).note


def test_realization_method_meets_the_target(spar):
    model = fit_excitation(spar, [0.0], method="realization")
    assert model.is_stable() and not model.attrs["failures"]
    assert model.attrs["method"] == "realization"


def test_fitting_grid_resolves_the_delay():
    w = np.array([0.1, 0.2, 1.2, 1.3])
    grid = fitting_grid(w, 10.0)
    assert np.all(np.isin(w, grid))
    assert np.diff(grid).max() <= np.pi / 40 + 1e-12
    sparse = fitting_grid(w, 10.0, keep=[True, True, False, False])
    assert np.isin(1.3, sparse) and np.sum((sparse > 1.2) & (sparse < 1.3)) == 0


def test_fit_response_of_a_rational_delayed_system():
    """F = e^{-jw 3} 2/(1 + jw) (a causal system advanced by 3 s): two states suffice."""
    w = fitting_grid(np.linspace(0.05, 6.0, 120), 3.0)
    force = 2.0 / (1 + 1j * w) * np.exp(1j * w * 3.0)
    a, *_, metrics, _ = fit_response(w, force, 3.0, target=1e-6, max_order=4)
    assert a.shape[0] <= 2 and metrics["nrmse"] < 1e-6
    assert np.linalg.eigvals(a).real.max() < 0


def test_model_file_round_trip_is_exact(spar, tmp_path):
    model = fit_excitation(spar, [0.0, np.pi / 2], max_order=12)
    path = model.save(tmp_path / "exc.nc")
    back = ExcitationModel.load(path)
    w = np.linspace(0.05, 3.0, 40)
    np.testing.assert_array_equal(back.frequency_response(w), model.frequency_response(w))
    assert back.dofs == model.dofs and back.delays.tolist() == model.delays.tolist()
    assert [m.metrics for m in back.models] == [m.metrics for m in model.models]
    assert [m.note for m in back.models] == [m.note for m in model.models]
    assert back.attrs["failures"] == model.attrs["failures"]
    with pytest.raises(FileExistsError):
        model.save(path)
    other = tmp_path / "not_a_model.nc"
    cummins.write(spar, other)
    with pytest.raises(HydroDataError, match="not a cummins excitation-model file"):
        ExcitationModel.load(other)


def test_drive_gives_the_frequency_response_in_a_regular_wave(spar_model):
    """The exact first-order-hold integration of x' = A x + B eta(t + t_c): in steady
    state the force is |H| cos(wt + arg H) for eta = cos(wt)."""
    omega = 0.6
    t = np.arange(0.0, 1500.0, 0.05)
    times, force = spar_model.force(t, np.cos(omega * t), 0)
    assert times[-1] == pytest.approx(t[-1] - spar_model.delays[0], abs=0.05)
    h = spar_model.frequency_response([omega])[0, 0]
    late = times > 1000
    for d in (0, 2, 4):
        expected = np.abs(h[d]) * np.cos(omega * times[late] + np.angle(h[d]))
        assert np.abs(force[late, d] - expected).max() < 1e-3 * np.abs(h[d])
    with pytest.raises(SimulationError, match="shorter than"):
        spar_model.force(t[:20], np.zeros(20), 0)


def test_forward_speed_and_missing_excitation_are_refused(shared_data):
    s175 = cummins.read(shared_data / "mss" / "s175" / "s175.mat")
    with pytest.raises(HydroDataError, match="forward speed"):
        fit_excitation(s175.isel(forward_speed=4))
    bare = pulse_hydrodb().drop_vars("excitation_force")
    with pytest.raises(HydroDataError, match="no excitation_force"):
        fit_excitation(bare)
    with pytest.raises(FitError, match="unknown method"):
        fit_excitation(pulse_hydrodb(), method="prony")
