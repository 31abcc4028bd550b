"""What ``motion_rao`` says of data at forward speed (the S-175 of MSS, VERES strip theory
at five speeds): the notes gathered before the speed terms are kept, and RAOs where the
encounter frequency falls to zero in following seas are named as not meaningful for the
DOFs without restoring."""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest

import cummins
from cummins.errors import HydroDataWarning, StaticInstabilityWarning
from cummins.seakeeping.frequency_domain import motion_rao

S175 = str(resources.files("cummins") / "data" / "s175" / "s175.mat")


@pytest.fixture(scope="module")
def at_20_knots():
    return cummins.read(S175).isel(forward_speed=4)


def test_notes_before_the_speed_terms_are_kept(at_20_knots):
    """A negative roll restoring: the static-stability note is in the RAO's attrs at
    speed, beside the forward speed (it was replaced by the speed's attrs)."""
    ds = at_20_knots.copy()
    c = ds.hydrostatic_stiffness.copy()
    c.loc[{"influenced_dof": "Roll", "radiating_dof": "Roll"}] = -1.0e6
    ds["hydrostatic_stiffness"] = c
    with pytest.warns(StaticInstabilityWarning):
        rao = motion_rao(ds, wave_direction=[np.pi])
    assert "Roll" in rao.attrs["static_stability"]
    assert rao.attrs["forward_speed"] == pytest.approx(10.2889, abs=1e-3)


def test_following_seas_near_zero_encounter_frequency_are_named(at_20_knots):
    """10° at 20 kn: ω_e = ω − ω² U cos β / g crosses zero at ω ≈ 0.97 rad/s, where surge
    reaches hundreds of m/m; the warning names the DOFs without restoring."""
    with pytest.warns(HydroDataWarning, match="Surge, Sway, Yaw have no restoring"):
        rao = motion_rao(at_20_knots, wave_direction=[np.radians(10.0)])
    assert float(np.abs(rao.sel(dof="Surge")).max()) > 50.0
    # head seas: ω_e > ω, never below the data's lowest frequency: no such warning
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", HydroDataWarning)
        motion_rao(at_20_knots, wave_direction=[np.pi])
