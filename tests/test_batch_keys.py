"""Study keys that say what the command-line options say: a heading in a gap of the
data's headings names the study's key (not ``--heading``), and ``water_depth`` is
``--water-depth`` for the data whose files record no depth."""

from __future__ import annotations

import warnings

import pytest

from cummins.errors import AssumptionWarning, HydroDataError
from cummins.studies.batch import _run_case, prepare_study
from cummins.studies.study import Study, StudyError

RM1 = "ROSCO/wamit_MHK_RM1_floating/MHK_RM1_Floating.1"  # 4 headings 0-90 deg, no depth


def _rm1(corpus, **keys) -> Study:
    return Study(
        data=corpus / RM1,
        analysis="rao",
        n_omega=20,
        mass=1e6,
        center_of_gravity=[0, 0, -5],
        radii_of_gyration=[10, 10, 10],
        restoring_includes_weight="no",
        **keys,
    )


def test_a_heading_in_a_gap_names_the_study_key(corpus):
    """The MHK RM1's headings (0-90°, mirrored to 270-360°) leave 90-270° open: a case at
    180° fails in one line that names the study's heading, where the command-line hint
    said `--heading DEG`, an option batch does not have."""
    study = _rm1(corpus, grid={"heading": [180], "hs": [2], "tp": [8]}, water_depth=50)
    context, _ = prepare_study(study)
    with pytest.raises(StudyError) as caught:
        _run_case(context, study.all_cases[0])
    message = str(caught.value)
    assert "lies in a gap of the data's headings, from 90° to 270°" in message
    assert "grid.heading" in message and "--heading" not in message
    assert "\n" not in message


def test_water_depth_key_is_the_cli_option(corpus):
    """Without a depth the RM1's excitation between headings assumes deep water and says
    so; ``water_depth: 50`` takes the depth instead (no warning), enters the case ids,
    and a depth other than the one a file records is refused (the WaveBot's 6.1 m)."""
    grid = {"heading": [45], "hs": [2], "tp": [8]}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        context, _ = prepare_study(_rm1(corpus, grid=grid))
        _run_case(context, context.study.all_cases[0])
    deep = [w for w in caught if "water depth is not recorded" in str(w.message)]
    assert deep and issubclass(deep[0].category, AssumptionWarning)
    study = _rm1(corpus, grid=grid, water_depth=50)
    assert (
        study.settings()["water_depth"] == 50.0
        and "water_depth" not in _rm1(corpus, grid=grid).settings()
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        context, _ = prepare_study(study)
        _run_case(context, study.all_cases[0])
    assert context.ds.attrs["water_depth"] == 50.0
    assert not [w for w in caught if "water depth" in str(w.message)]
    assert _rm1(corpus, grid=grid, water_depth=".inf").water_depth == float("inf")
    with pytest.raises(StudyError, match="water_depth"):
        _rm1(corpus, grid=grid, water_depth=-3)
    wavebot = Study(
        data=corpus / "WEC-Sim_Applications/wamit_WaveBot/waveBotBuoy.out",
        rho=1000,
        mass=858.4,
        center_of_gravity=[0, 0, 0],
        radii_of_gyration=[0.3, 0.3, 0.3],
        grid=grid,
        water_depth=20,
    )
    with pytest.raises(HydroDataError, match="water_depth = 20 m was given but the files record"):
        prepare_study(wavebot)
