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


def _one_dof(ds, label):
    return ds.sel(influenced_dof=[label], radiating_dof=[label])


def test_a_resonance_that_looks_like_spikes_is_a_sharp_feature(corpus):
    """The WAMIT MHK RM1 platform's surge damping peaks at 2.1 rad/s (0.58 of its
    maximum) with the matching swing of A(ω); the spike test flags five points of it.
    Kramers–Kronig keeps them (Ogilvie's estimate flat through them, far off with them
    bridged), and the estimate that keeps them lands within 2 % of WAMIT's own ω = ∞ row
    (measured 0.81 %; bridged, 3.7 %): a reference no one here computed."""
    from cummins.radiation.retardation import added_mass_inf
    from cummins.repair import sharp_features

    ds = cummins.read(corpus / "ROSCO" / "wamit_MHK_RM1_floating" / "MHK_RM1_Floating.1")
    surge = _one_dof(ds, "Surge")
    found = find_suspect_frequencies(surge)
    features = sharp_features(surge, found)
    assert len(features) >= 3 and all(1.9 < x < 2.3 for x in features), features
    w = ds.omega.values
    kept = np.ones((w.size, 6), dtype=bool)
    for s in found:
        if s.omega not in features:
            kept[np.isclose(w, s.omega), 0] = False
    bridged = kept.copy()
    for x in features:
        bridged[np.isclose(w, x), 0] = False
    row = float(ds.added_mass_inf.sel(influenced_dof="Surge", radiating_dof="Surge"))
    ds = ds.drop_vars("added_mass_inf")
    pick = {"influenced_dof": "Surge", "radiating_dof": "Surge"}
    with_feature = float(added_mass_inf(ds, "ogilvie", kept=kept).sel(pick))
    without = float(added_mass_inf(ds, "ogilvie", kept=bridged).sel(pick))
    assert abs(with_feature / row - 1) < 0.02
    assert abs(without / row - 1) > 2 * abs(with_feature / row - 1)


def test_irregular_frequency_spikes_are_not_a_sharp_feature(corpus):
    """The AQWA PEND hull's heave spikes at 10.7–11.3 and 13.9–14.3 rad/s (an irregular
    frequency: Ogilvie's estimate jumps with them, stays flat without) stay suspect."""
    from cummins.repair import sharp_features

    ds = cummins.read(corpus / "WEC-Sim" / "aqwa_19.1_PEND_hull" / "19_1.AH1")
    heave = _one_dof(ds, "Heave")
    found = find_suspect_frequencies(heave)
    assert sum(10.6 < s.omega < 11.3 for s in found) >= 3
    assert not [x for x in sharp_features(heave, found) if 10.6 < x < 14.3]


def test_added_mass_inf_ignores_the_damping_a_dof_leaves_out(tanker_wamit):
    """``kept``: the damping at the points a DOF leaves out does not enter the estimate
    of its pairs (bridged from its neighbours), and the median runs over the points both
    DOFs keep; with every point kept, the plain estimate."""
    from cummins.radiation.retardation import added_mass_inf

    ds = tanker_wamit.drop_vars("added_mass_inf")
    w = ds.omega.values
    kept = np.ones((w.size, 6), dtype=bool)
    np.testing.assert_array_equal(
        added_mass_inf(ds, "ogilvie", kept=kept).values, added_mass_inf(ds, "ogilvie").values
    )
    out = (w > 3.5) & (w < 4.6)
    surge = list(ds.influenced_dof.values).index("Surge")
    kept[out, surge] = False
    damping = ds.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof")
    spoiled = damping.values.copy()
    spoiled[out, surge, :] *= 50.0
    spoiled[out, :, surge] *= 50.0
    spoilt = ds.assign(radiation_damping=damping.copy(data=spoiled))
    clean = added_mass_inf(ds, "ogilvie", kept=kept).values
    again = added_mass_inf(spoilt, "ogilvie", kept=kept).values
    np.testing.assert_allclose(again[surge], clean[surge], rtol=1e-12)
    plain = added_mass_inf(spoilt, "ogilvie").values
    assert abs(plain[surge, surge] / clean[surge, surge] - 1) > 0.01
