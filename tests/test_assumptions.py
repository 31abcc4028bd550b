"""Every value a result depends on that the files do not record — ρ, g, ULEN, the water
depth, a missing companion file — is an ``AssumptionWarning`` naming the file and how to
give it, shown once per run; ``--water-depth`` gives the depth; a value the files
record is no assumption (the bundled demo data read and run without one).

References: the same runs read with their companion files (the WAMIT sphere's ``.out``:
depth 50 m; NEMOH's ``Nemoh.cal`` of the COER float: ρ = 1000 kg/m³, depth 2.2 m).
"""

from __future__ import annotations

import shutil
import warnings

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import AssumptionWarning, HydroDataError
from cummins.seakeeping.frequency_domain import motion_rao


def _messages(caught) -> list[str]:
    return [str(w.message) for w in caught if issubclass(w.category, AssumptionWarning)]


@pytest.fixture
def sphere_without_out(shared_data, tmp_path):
    """The WEC-Sim sphere's WAMIT run without its .out (which records ρ, g, ULEN and the
    50 m depth)."""
    for suffix in (".1", ".3", ".hst"):
        shutil.copy(shared_data / "wecsim" / "sphere" / f"sphere{suffix}", tmp_path)
    return tmp_path / "sphere.1"


def test_wamit_run_without_its_out(shared_data, sphere_without_out):
    with pytest.warns(AssumptionWarning) as caught:
        ds = cummins.read(sphere_without_out)
    said = " ".join(_messages(caught))
    for name in ("rho", "g ", "ulen"):
        assert f"{name.strip()} is not recorded" in said and "sphere.1" in said
    assert ds.attrs["water_depth"] == np.inf and ds.attrs["water_depth_assumed"]
    # the depth is said where a result depends on it: the wave force between headings
    with_inertia = cummins.with_inertia(
        ds,
        mass=2.6e5,
        center_of_gravity=[0, 0, -2.0],
        radii_of_gyration=[3.0, 3.0, 3.0],
        restoring="total",
    )
    with pytest.warns(AssumptionWarning, match="deep water assumed .* --water-depth"):
        motion_rao(with_inertia, ds.omega.values[::20], [0.0])
    # given the run's depth (and ρ, g the .out records), the numbers are the full run's
    full = cummins.read(shared_data / "wecsim" / "sphere" / "sphere.1")
    with warnings.catch_warnings():
        warnings.simplefilter("error", AssumptionWarning)
        given = cummins.read(
            sphere_without_out, rho=full.attrs["rho"], g=full.attrs["g"], ulen=1.0, water_depth=50.0
        )
    assert given.attrs["water_depth"] == full.attrs["water_depth"] == 50.0
    assert "water_depth_assumed" not in given.attrs
    np.testing.assert_array_equal(given.excitation_force.values, full.excitation_force.values)
    with pytest.raises(HydroDataError, match="records 50 m"):
        cummins.read(shared_data / "wecsim" / "sphere" / "sphere.1", water_depth=30.0)


def test_nemoh_run_without_nemoh_cal(corpus, tmp_path):
    """The COER float's NEMOH run (ρ = 1000 kg/m³, depth 2.2 m in Nemoh.cal) without its
    Nemoh.cal: the missing file, ρ and g are warnings (not only history lines); given
    them, the data are those of the complete run."""
    source = corpus / "WEC-Sim" / "nemoh_v3.0.2_COER_comp"
    run = tmp_path / "run"
    shutil.copytree(source, run)
    (run / "Nemoh.cal").unlink()
    with pytest.warns(AssumptionWarning) as caught:
        ds = cummins.read(run)
    said = " ".join(_messages(caught))
    assert "no Nemoh.cal" in said and "rho is not recorded" in said and "g is not recorded" in said
    assert ds.attrs["rho"] == 1025.0 and ds.attrs["water_depth_assumed"]
    full = cummins.read(source)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        given = cummins.read(run, rho=1000.0, g=full.attrs["g"], water_depth=2.2)
    assert not [m for m in _messages(caught) if "is not recorded" in m]
    assert given.attrs["water_depth"] == full.attrs["water_depth"] == 2.2
    np.testing.assert_allclose(given.added_mass.values, full.added_mass.values)


def test_cli_water_depth_option_and_one_warning_per_run(sphere_without_out, tmp_path):
    args = [
        "rao",
        str(sphere_without_out),
        "-o",
        str(tmp_path / "rao.nc"),
        "--headings",
        "0",
        "--mass",
        "2.6e5",
        "--center-of-gravity",
        "0",
        "0",
        "-2",
        "--radii-of-gyration",
        "3",
        "3",
        "3",
        "--restoring-includes-weight",
        "yes",
    ]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert text.count("deep water assumed") == 1  # said once, not per frequency or call
    assert "rho is not recorded" in text
    result = CliRunner().invoke(main, [*args, "--force", "--water-depth", "50"])
    assert result.exit_code == 0, result.output
    assert "deep water assumed" not in " ".join(result.output.split())
    result = CliRunner().invoke(main, [*args, "--force", "--water-depth", "nan"])
    assert result.exit_code == 2


def test_bundled_demo_data_assume_nothing():
    """The tanker (WAMIT with its .out) and the S-175 (MSS struct: deep water is MSS's
    own convention) read and give RAOs without any assumption warning."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", AssumptionWarning)
        tanker = cummins.read(cummins.demo_files() / "tanker.1")
        motion_rao(tanker, tanker.omega.values[::10], [np.pi])
        s175 = cummins.read(cummins.demo_files().parent / "s175" / "s175.mat")
        motion_rao(s175.sel(forward_speed=0.0), s175.omega.values[::10], [np.pi])
