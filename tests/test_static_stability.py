"""A statically unstable body (a negative eigenvalue of the restoring on the DOFs that
have restoring) is said the same way by the frequency and the time domain: ``rao``
warns and marks its file, ``simulate`` (``Vessel.stability``) refuses, both with
:func:`cummins.restoring.instability_message`."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import SimulationError, StaticInstabilityWarning
from cummins.radiation.model import RadiationModel
from cummins.restoring import instability_message, static_instability
from cummins.seakeeping.frequency_domain import motion_rao
from cummins.vessel import vessel_from_hydrodb

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


def test_negative_eigenvalues_named_and_unit_free():
    """Free surge, sway and yaw are not instabilities; a negative roll is; a heave-pitch
    coupling stronger than √(C33 C55) is, though both diagonals are positive; scaling the
    DOFs (other units) changes no verdict (Sylvester's law of inertia)."""
    c = np.diag([0.0, 0.0, 1e7, 5e8, 4e10, 0.0])
    assert static_instability(c, DOFS) == []
    rolled = c.copy()
    rolled[3, 3] = -2e8
    [found] = static_instability(rolled, DOFS)
    assert found.dof == "Roll" and found.stiffness == -2e8
    coupled = c.copy()
    coupled[2, 4] = coupled[4, 2] = 1.01 * np.sqrt(1e7 * 4e10)
    [found] = static_instability(coupled, DOFS)
    assert found.dof in ("Heave", "Pitch")
    scale = np.diag([1.0, 1.0, 1e-3, 1e3, 7.0, 1.0])
    assert len(static_instability(scale @ coupled @ scale, DOFS)) == 1
    coupled[2, 4] = coupled[4, 2] = 0.99 * np.sqrt(1e7 * 4e10)
    assert static_instability(coupled, DOFS) == []


@pytest.fixture(scope="module")
def gbm_barge(corpus):
    """The generalized-mode barge: WAMIT computed it with the centre of gravity at the
    waterline (.out), so its roll restoring is negative (C44 = -3.3e7 N m/rad)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(corpus / "WEC-Sim_Applications" / "wamit_generalized_modes_barge")


def test_rao_warns_and_simulation_refuses_with_one_sentence(gbm_barge):
    ds = gbm_barge
    labels = [str(d) for d in ds.influenced_dof.values]
    c = ds.hydrostatic_stiffness.transpose("influenced_dof", "radiating_dof").values
    unstable = static_instability(c, labels)
    assert [u.dof for u in unstable] == ["Roll"]
    sentence = instability_message(unstable)
    with pytest.warns(StaticInstabilityWarning) as caught:
        rao = motion_rao(ds, ds.omega.values[::50], [0.0])
    assert any(str(w.message).startswith(sentence) for w in caught)
    assert rao.attrs["static_stability"].startswith(sentence)
    model = RadiationModel(tuple(labels), (), ds.added_mass_inf.values)
    vessel = vessel_from_hydrodb(ds, model)
    with pytest.raises(SimulationError) as refused:
        vessel.stability()
    assert str(refused.value).startswith(sentence)
    # a stable body: no warning, no mark
    with warnings.catch_warnings():
        warnings.simplefilter("error", StaticInstabilityWarning)
        held = cummins.with_external_terms(ds, stiffness={("Roll", "Roll"): 2 * 3.3e7})
        rao = motion_rao(held, ds.omega.values[::50], [0.0])
    assert "static_stability" not in rao.attrs


def test_rao_command_says_it_and_marks_the_file(corpus, tmp_path):
    """HAMS's DeepCwind semi as its test run has it: the hydrostatics alone with the centre
    of gravity at the waterline, roll and pitch negative even with the mooring."""
    out = tmp_path / "rao.nc"
    result = CliRunner().invoke(
        main, ["rao", str(corpus / "HAMS" / "DeepCwind"), "-o", str(out), "--headings", "180"]
    )
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "statically unstable in Roll" in text and "Pitch" in text
    with xr.open_dataset(out) as saved:
        mark = saved.attrs.get("static_stability") or saved["rao"].attrs.get("static_stability")
    assert mark and "Roll" in mark and "Pitch" in mark
