"""``cummins check`` on second-order data: QTF symmetries, the QTF's diagonal against the
run's mean drift, the mean-drift methods against each other, the QTF's grid."""

from __future__ import annotations

import numpy as np
import pytest

import cummins
from cummins.qtf import QTFTable, qtf_table, with_second_order
from cummins.seakeeping.slow_drift import qtf_grid_advice
from cummins.seakeeping.spectra import wave_spectrum

OC4 = "corpus/WEIS/ss_fitting_OC4_semi/marin_semi.1"
SPHERE = "corpus/WEC-Sim_Applications/wamit_mean_drift_sphere/outputFiles/sphere.1"


@pytest.fixture(scope="module")
def oc4(shared_data):
    return cummins.read(shared_data / OC4)


def _findings(ds, name):
    return [f for f in cummins.check(ds) if f.check == name]


def test_oc4_qtfs_keep_their_symmetries_and_an_edit_is_named(oc4):
    assert all(f.severity == "ok" for f in _findings(oc4, "qtf_symmetry"))
    table = qtf_table(oc4, "difference")
    edited = table.values.copy()
    edited[10, 3, 0, 0] *= 1.5  # surge, one pair, its mirror left alone
    bad = with_second_order(
        oc4.drop_vars("qtf_difference"),
        [QTFTable("difference", table.omega, table.directions, edited, table.dofs)],
    )
    found = [f for f in _findings(bad, "qtf_symmetry") if f.severity == "warning"]
    assert len(found) == 1 and found[0].where == "Surge"


def test_qtf_diagonal_against_the_mean_drift(oc4):
    """The OC4 run has no separate mean drift: give it its own QTF diagonal (on the
    first-order frequencies), then the same with the heave drift 30 % too large."""
    table = qtf_table(oc4, "difference")
    diag = table.diagonal().real[:, 0, :]  # (n, d)
    w = oc4.omega.values
    inside = (w >= table.omega[0]) & (w <= table.omega[-1])
    drift = np.zeros((w.size, 1, 6))
    for k in range(6):
        drift[inside, 0, k] = np.interp(w[inside], table.omega, diag[:, k])
    same = with_second_order(
        oc4, drift={"drift_force": (drift, "test")}, wave_direction=table.directions
    )
    (finding,) = _findings(same, "qtf_mean_drift")
    assert finding.severity == "ok" and finding.value < 0.02
    drift[:, 0, 2] *= 1.3
    wrong = with_second_order(
        oc4, drift={"drift_force": (drift, "test")}, wave_direction=table.directions
    )
    (finding,) = _findings(wrong, "qtf_mean_drift")
    assert finding.severity == "warning" and finding.where.startswith("Heave")
    assert finding.value == pytest.approx(0.3 / 1.3, rel=0.1)  # of the (scaled) drift's peak


def test_sphere_pressure_integration_parts_from_the_control_surface(shared_data):
    ds = cummins.read(shared_data / SPHERE)
    found = {f.message.split(" parts")[0]: f for f in _findings(ds, "drift_methods")}
    pressure = next(f for k, f in found.items() if "pressure integration" in k)
    assert pressure.severity == "warning" and pressure.where.startswith("Surge")
    assert pressure.value > 0.5  # up to 120 % of the peak above 5 rad/s
    assert "from 3.4 rad/s" in pressure.message
    momentum = next(f for k, f in found.items() if "momentum" in k)
    # momentum conservation stays with the control surface below 8 rad/s
    part = float(momentum.message.split(" from ")[-1].split(" rad/s")[0])
    assert part > 8.0


def test_oc4_grid_and_its_resonances(oc4):
    info = [f for f in _findings(oc4, "qtf_grid") if f.severity == "info"]
    assert info[0].details["spacing_rad_s"] == pytest.approx(0.05, rel=0.01)
    assert info[0].details["longest_resolved_period_s"] == pytest.approx(np.pi / 0.05, rel=0.01)
    warned = {f.where for f in _findings(oc4, "qtf_grid") if f.severity == "warning"}
    # heave (natural period ~17 s) and pitch (~26 s) resonances between two QTF frequencies;
    # sway, roll, yaw are noise in head seas and not judged
    assert warned == {"Heave", "Pitch"}
    advice = qtf_grid_advice(
        qtf_table(oc4), spectrum=wave_spectrum("jonswap", 6.0, 10.0), natural_periods={"Surge": 110}
    )
    assert any("needs dw <= 0.0286" in n for n in advice.notes)
    assert advice.energy_outside < 0.01


def test_the_drift_at_the_suspect_frequencies_is_named():
    """The demo tanker's .out (WAMIT, no irregular-frequency removal): the damping flags
    9 frequencies from 3.65 rad/s, and the drift there is WAMIT's garbage — heave
    −1.74e8 N/m² in head seas at 4.49 rad/s, up to 3000 times its largest below over the
    headings (measured; surge 9500 times). `check` names the drift there, a warning."""
    ds = cummins.read(cummins.demo_files() / "tanker.out")
    found = _findings(ds, "drift_suspect")
    assert len(found) == 1 and found[0].severity == "warning"
    omega = np.array(found[0].details["omega"])
    assert omega.size == 9 and omega.min() == pytest.approx(3.653, abs=1e-3)
    assert found[0].value > 100  # the WAMIT values are 1e3–1e4 times the sound ones
    # its drift below the suspect frequencies is of the size the audit measured (~1e5)
    heave = ds.drift_force.sel(influenced_dof="Heave").values
    sound = ds.omega.values < omega.min()
    assert np.abs(heave[sound]).max() < 1e-2 * np.abs(heave[~sound]).max()
