"""The low-frequency model of a ship moving ahead: the linearised Coriolis and centripetal
forces of the rigid body and the added mass (:mod:`cummins.timedomain.lfmodel.speed`),
``cummins lf-model --manoeuvring-speed U``."""

from __future__ import annotations

import warnings
from importlib import resources

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import HydroDataError
from cummins.timedomain.lfmodel import LowFrequencyModel, lf_model_from_frequency_data
from cummins.timedomain.lfmodel.speed import at_forward_speed, speed_matrix
from cummins.timedomain.unified import coriolis_rigid_body

S175 = str(resources.files("cummins") / "data" / "s175" / "s175.mat")
U = 10.28889  # 20 kn


@pytest.fixture(scope="module")
def s175_zero() -> xr.Dataset:
    return cummins.read(S175).sel(forward_speed=0.0)


@pytest.fixture(scope="module")
def lf_s175(s175_zero) -> LowFrequencyModel:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return lf_model_from_frequency_data(s175_zero)


def test_speed_matrix_is_the_jacobian_of_the_coriolis_force(lf_s175):
    """N(U) against a central-difference Jacobian of Kirchhoff's C(ν)ν as the unified
    model computes it (timedomain.unified.coriolis_rigid_body, written for the rigid body
    and valid for any symmetric inertia), at ν₀ = (U, 0, …): for the S-175's M_RB (its
    centre of gravity off the origin) and its M_A, to 1e-7 of the largest entry."""
    for mass in (lf_s175.rigid_body_mass, 0.5 * (lf_s175.added_mass + lf_s175.added_mass.T)):
        nu0 = np.array([U, 0, 0, 0, 0, 0.0])
        jacobian = np.zeros((6, 6))
        for k in range(6):
            step = np.zeros(6)
            step[k] = 1e-3
            jacobian[:, k] = (
                coriolis_rigid_body(mass, nu0 + step) - coriolis_rigid_body(mass, nu0 - step)
            ) / 2e-3
        got = speed_matrix(mass, U)
        np.testing.assert_allclose(got, jacobian, atol=1e-7 * np.abs(jacobian).max())


def test_manoeuvring_terms_are_fossens(lf_s175):
    """The S-175's model at 20 kn carries the linear manoeuvring model's speed terms
    (Fossen (2011) §7.1) with M = M_RB + M_A of its own model: sway (m + A11) U r, the yaw
    Munk moment (A22 − A11) U v, yaw (m x_g + A26) U r, heave −(m + A11) U q and the pitch
    Munk moment (A11 − A33) U w; the rest of the model unchanged, and its vessel's damping
    D + N(U)."""
    moving = at_forward_speed(lf_s175, U)
    m = lf_s175.mass
    n = moving.speed_terms
    k = {d: lf_s175.index(d) for d in lf_s175.dofs}
    s, w, y, h, p = k["Surge"], k["Sway"], k["Yaw"], k["Heave"], k["Pitch"]
    assert n[w, y] == pytest.approx(m[s, s] * U, rel=1e-12)
    assert n[y, w] == pytest.approx((m[w, w] - m[s, s]) * U, rel=1e-12)
    assert n[y, y] == pytest.approx(0.5 * (m[w, y] + m[y, w]) * U, rel=1e-9)
    assert n[h, p] == pytest.approx(-m[s, s] * U, rel=1e-12)
    assert n[p, h] == pytest.approx((m[s, s] - m[h, h]) * U, rel=1e-12)
    assert n[y, w] > 0  # A22 > A11: the destabilising Munk moment −(A22 − A11) U v
    np.testing.assert_array_equal(moving.damping, lf_s175.damping)
    np.testing.assert_array_equal(lf_s175.speed_terms, np.zeros((6, 6)))
    vessel = moving.to_vessel()
    np.testing.assert_allclose(vessel.viscous_damping, lf_s175.damping + n)
    assert moving.attrs["forward_speed"] == U
    assert "speed_terms" in moving.to_dataset()


def test_speed_terms_of_one_hull_only(lf_s175):
    """A model of several bodies is refused, naming its DOFs; a speed that is not finite
    too."""
    two = LowFrequencyModel(
        ("body1__Surge", "body2__Surge"),
        *[np.eye(2)] * 5,
        np.zeros(2),
        ("a", "b"),
        np.zeros((2, 2)),
    )
    with pytest.raises(HydroDataError, match=r"one rigid hull.*body1__Surge"):
        at_forward_speed(two, U)
    with pytest.raises(HydroDataError, match="finite"):
        at_forward_speed(lf_s175, float("nan"))


def test_cli_manoeuvring_speed(tmp_path, lf_s175):
    """``cummins lf-model s175.mat --speed 0 --manoeuvring-speed 10.28889``: the zero-speed
    model with the speed terms, printed and written; with the data at speed, or with
    --compare: a usage error; the data at speed alone: the warning names the option."""
    out = tmp_path / "lf.nc"
    base = ["lf-model", S175, "-o", str(out)]
    runner = CliRunner()
    result = runner.invoke(main, [*base, "--speed", "0", "--manoeuvring-speed", str(U)])
    assert result.exit_code == 0, result.output
    assert "speed terms at 10.2889 m/s" in result.output
    with xr.open_dataset(out) as written:
        expected = at_forward_speed(lf_s175, U).speed_terms
        np.testing.assert_allclose(written.speed_terms.values, expected, rtol=1e-12, atol=1e-6)
        np.testing.assert_allclose(written.added_mass.values, lf_s175.added_mass)
    result = runner.invoke(main, [*base, "--speed", str(U), "--manoeuvring-speed", "5", "--force"])
    assert result.exit_code == 2 and "--speed 0" in result.output
    compare = ["--compare", str(tmp_path / "cmp"), "--force"]
    result = runner.invoke(main, [*base, "--speed", "0", "--manoeuvring-speed", "5", *compare])
    assert result.exit_code == 2 and "--compare" in result.output
    result = runner.invoke(main, [*base, "--speed", str(U), "--force"])
    assert result.exit_code == 0, result.output
    assert "--speed 0 --manoeuvring-speed 10.2889" in " ".join(result.output.split())
