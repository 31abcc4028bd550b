"""Suspect frequencies: detected where the data are wrong, nowhere else; removal is recorded."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import cummins
from cummins import HydroDataError
from cummins.repair import (
    find_suspect_frequencies,
    limit_frequency_range,
    remove_frequencies,
    remove_suspect_frequencies,
)


def test_tanker_irregular_frequencies(tanker_wamit):
    """The WAMIT tanker has no irregular-frequency removal: B33 falls to −0.56 of its peak at
    3.93 rad/s, B44 to −0.41, B55 to −0.34 (the identification issue's measurements)."""
    suspects = {round(s.omega, 3): s for s in find_suspect_frequencies(tanker_wamit)}
    assert 3.927 in suspects
    assert "negative damping, -0.562" in suspects[3.927].reason
    assert min(suspects) > 3.5  # nothing below the first irregular frequency
    cleaned, _ = remove_suspect_frequencies(tanker_wamit, above_first=True)
    assert cleaned.omega.values.max() < 3.5
    assert cummins.check(cleaned).by_check("suspect_frequencies")[0].severity == "ok"
    assert "removed" in cleaned.attrs["history"]


def test_supply_lowest_frequency(shared_data):
    """ShipX supply vessel: the 0.105 rad/s row is inconsistent with the rest (A_ii halves)."""
    supply = cummins.read(shared_data / "mss" / "supply" / "input.re7")
    suspects = find_suspect_frequencies(supply)
    assert [round(s.omega, 4) for s in suspects] == [0.1047]


@pytest.mark.parametrize(
    ("relative", "options"),
    [
        ("wecsim/cylinder/cylinder_nemoh/cyl.1", {"rho": 1000.0}),  # WAMIT with IRR = 1
        ("wecsim/sphere/sphere_hydrodynamics.nc", {}),
    ],
)
def test_clean_data_have_no_suspects(shared_data, relative, options):
    ds = cummins.read(shared_data / relative, **options)
    assert find_suspect_frequencies(ds) == ()


def test_nemoh_irregular_frequency(shared_data):
    """NEMOH has no irregular-frequency removal: the cylinder's first is near 10.4 rad/s."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        ds = cummins.read(
            shared_data / "wecsim" / "cylinder" / "cylinder_nemoh" / "RadiationCoefficients.tec"
        )
    first = find_suspect_frequencies(ds)[0].omega
    assert 10.3 < first < 10.5


def test_remove_and_limit(tanker_wamit):
    w = tanker_wamit.omega.values
    out = remove_frequencies(tanker_wamit, w[[3, 7]], reason="test")
    assert out.sizes["omega"] == w.size - 2
    assert "removed 2 frequencies" in out.attrs["history"] and "test" in out.attrs["history"]
    with pytest.raises(HydroDataError, match="not in the data"):
        remove_frequencies(tanker_wamit, [0.12345])
    with pytest.raises(HydroDataError, match="fewer than three"):
        remove_frequencies(tanker_wamit, w[2:])
    limited = limit_frequency_range(tanker_wamit, omega_max=2.0)
    assert limited.omega.values.max() <= 2.0
    assert "limited" in limited.attrs["history"]
    assert limit_frequency_range(tanker_wamit) is tanker_wamit
    np.testing.assert_array_equal(
        limited.added_mass.values, tanker_wamit.added_mass.values[w <= 2.0]
    )
