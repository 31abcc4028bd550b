"""The lightly damped modes a slow-drift force resonates (cummins.timedomain.modes), on
WEIS' OC4 semisubmersible (WAMIT .1 .hst .12d .12s): the eigenvalues of the vessel's state
matrix (fitted fluid memory) against the natural frequency and damping ratio of one DOF
computed from the data's own A(ω), B(ω)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.timedomain.modes import lightly_damped_modes
from cummins.vessel import vessel_from_hydrodb

SEMI = ("WEIS", "ss_fitting_OC4_semi", "marin_semi.1")
MASS = 1.3473e7  # OC4 DeepCwind platform with the turbine (as in the README)
K = 7.0e4  # surge mooring stiffness, N/m


@pytest.fixture(scope="module")
def surge(corpus):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(corpus.joinpath(*SEMI))
        ds = cummins.with_inertia(
            ds,
            mass=MASS,
            center_of_gravity=[0, 0, -13.46],
            radii_of_gyration=[23.9, 23.9, 32.2],
            restoring="hydrostatic",
        )
        ds = cummins.hydrodb.select_dofs(ds, ["Surge"])
    return ds


def _data_mode(ds, c):
    """ω_n = √(k / (m + A(ω_n))) by fixed point on the data's A(ω), and
    ζ = (c + B(ω_n)) / (2 ω_n (m + A(ω_n)))."""
    w = ds.omega.values
    a = ds.added_mass.values[:, 0, 0]
    b = ds.radiation_damping.values[:, 0, 0]
    omega = np.sqrt(K / MASS)
    for _ in range(50):
        omega = np.sqrt(K / (MASS + np.interp(omega, w, a)))
    total = MASS + np.interp(omega, w, a)
    return omega, (c + np.interp(omega, w, b)) / (2 * omega * total)


@pytest.mark.parametrize("zeta", [0.003, 0.006])
def test_surge_mode_against_the_data(surge, zeta):
    """A moored surge with damping c = 2ζω_n(m + A): the mode is listed, at the data's
    natural frequency within 1 % and damping ratio within 5 %."""
    omega0, _ = _data_mode(surge, 0.0)
    c = (
        2
        * zeta
        * omega0
        * (MASS + np.interp(omega0, surge.omega.values, surge.added_mass.values[:, 0, 0]))
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.with_external_terms(
            surge, stiffness={("Surge", "Surge"): K}, damping={("Surge", "Surge"): c}
        )
        vessel = vessel_from_hydrodb(ds)
    modes = lightly_damped_modes(vessel, below=0.6)
    assert len(modes) == 1 and modes[0].dof == "Surge"
    omega, expected = _data_mode(ds, c)
    assert modes[0].omega == pytest.approx(omega, rel=0.01)
    assert modes[0].zeta == pytest.approx(expected, rel=0.05)
    # more damped than the threshold, or above the frequency asked: not listed
    assert lightly_damped_modes(vessel, below=0.6, zeta_max=0.5 * zeta) == []
    assert lightly_damped_modes(vessel, below=0.5 * omega) == []


def test_simulate_names_the_undamped_slow_drift_modes(corpus, tmp_path):
    """The 6-DOF semi moored in surge, sway and yaw with no damping given, in its full
    QTF's slow drift: surge reached 83 m (max over an hour) with no word of why; the note
    names the modes (surge 112 s) and the options that damp them. The mean drift alone
    (a static force) gets no note."""
    base = [
        "simulate",
        str(corpus.joinpath(*SEMI)),
        "--mass",
        str(MASS),
        "--center-of-gravity",
        "0",
        "0",
        "-13.46",
        "--radii-of-gyration",
        "23.9",
        "23.9",
        "32.2",
        "--external-stiffness",
        "Surge",
        "Surge",
        str(K),
        "--external-stiffness",
        "Sway",
        "Sway",
        str(K),
        "--external-stiffness",
        "Yaw",
        "Yaw",
        "1e8",
        "--heading",
        "0",
        "--hs",
        "6",
        "--tp",
        "10",
        "--duration",
        "200",
        "--seed",
        "1",
    ]
    result = CliRunner().invoke(
        main, [*base, "--second-order", "full", "-o", str(tmp_path / "a.nc")]
    )
    text = " ".join(result.output.split())
    assert result.exit_code == 0, result.output
    assert "lightly damped modes below the sea peak: Surge 112 s" in text
    assert "--external-damping" in text
    # quadratic drag given on surge: not in the linear eigenvalues, so surge is not named
    quad = str(tmp_path / "q.nc")
    result = CliRunner().invoke(
        main,
        [*base, "--second-order", "full", "--quadratic-damping", "Surge", "1e6", "-o", quad],
    )
    text = " ".join(result.output.split())
    assert result.exit_code == 0 and "below the sea peak: Sway 112 s" in text, text
    assert "Surge 112 s" not in text
    result = CliRunner().invoke(
        main, [*base, "--second-order", "mean", "-o", str(tmp_path / "b.nc")]
    )
    assert result.exit_code == 0 and "lightly damped" not in result.output
