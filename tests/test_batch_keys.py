"""Study keys that say what the command-line options say: a heading in a gap of the
data's headings names the study's key (not ``--heading``), as the warnings of what the
files lack do (not ``--rho``), and ``water_depth`` and ``ulen`` are ``--water-depth`` and
``--ulen`` for the data whose files record neither."""

from __future__ import annotations

import warnings
from dataclasses import replace

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


def test_warnings_name_the_study_keys_not_the_options(corpus, tmp_path):
    """The RM1's files record neither rho, g, ULEN nor the depth: the warnings of a
    study on it said "give --rho (rho=)", options batch does not have; they name the
    keys of the study's file now, as the heading's error does, once each, and say what
    was assumed as before."""
    grid = {"heading": [45], "hs": [2], "tp": [8]}
    study = _rm1(corpus, grid=grid, source=tmp_path / "rm1.yaml")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        context, _ = prepare_study(study)
        _run_case(context, study.all_cases[0])
    texts = [str(w.message) for w in caught if issubclass(w.category, AssumptionWarning)]
    for key, assumed in (
        ("rho", "1025 kg/m^3 assumed"),
        ("g", "9.81 m/s^2 assumed"),
        ("ulen", "1 m assumed"),
        ("water_depth", "deep water assumed"),
    ):
        named = [t for t in texts if f"give the key {key} of rm1.yaml" in t]
        assert len(named) == 1 and assumed in named[0], key
    assert not [t for t in texts if "--" in t]


def test_ulen_key_is_the_cli_option(corpus, tmp_path):
    """The RM1's files record no ULEN: ``ulen: 2`` reads them as ``rao --ulen 2`` does
    (every coefficient scaled by its power of the length), the study's RAOs are the
    command's, differ from those at ULEN 1, ulen enters the case ids and ``--example``
    lists it."""
    import numpy as np
    import xarray as xr
    from click.testing import CliRunner

    from cummins.cli import main
    from cummins.studies.batch import case_ids
    from cummins.studies.study import example_study_text

    grid = {"heading": [45], "hs": [2], "tp": [8]}
    raos = {}
    for ulen in (None, 2):
        study = _rm1(corpus, grid=grid, water_depth=50, ulen=ulen)
        context, digest = prepare_study(study)
        _run_case(context, study.all_cases[0])
        (raos[ulen],) = context.cache.values()
        raos[ulen] = np.abs(raos[ulen].transpose("omega", "wave_direction", ...).values)
        assert ("ulen" in study.settings()) == (ulen is not None)
        ids = case_ids(study, digest)
    assert study.settings()["ulen"] == 2.0 and ids != case_ids(_rm1(corpus, grid=grid), digest)
    omega = context.omega
    result = CliRunner().invoke(
        main,
        [
            "rao", str(corpus / RM1), "--ulen", "2", "--mass", "1e6",
            "--center-of-gravity", "0", "0", "-5", "--radii-of-gyration", "10", "10", "10",
            "--restoring-includes-weight", "no", "--water-depth", "50", "--headings", "45",
            "--omega-min", repr(float(omega[0])), "--omega-max", repr(float(omega[-1])),
            "--n-omega", str(omega.size), "-o", str(tmp_path / "rao.nc"),
        ],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    with xr.open_dataset(tmp_path / "rao.nc") as out:
        np.testing.assert_allclose(out.omega.values, omega, rtol=1e-12)
        rao = out.rao.sel(complex="re") + 1j * out.rao.sel(complex="im")
        command = np.abs(rao.transpose("omega", "wave_direction", "dof").values)
    scale = command.max(axis=(0, 1))
    np.testing.assert_allclose(raos[2], command, rtol=1e-9, atol=1e-12 * scale.max())
    assert np.abs(raos[None] - command).max(axis=(0, 1)).max() > 0.05 * scale.max()
    assert "# ulen: " in example_study_text()  # `cummins batch --example` lists it


def test_the_restoring_weight_warning_names_the_study_key(corpus, tmp_path):
    """The RM1's files do not say whether the restoring holds the weight: the warning of a
    study that does not say either told the user to give --restoring-includes-weight, an
    option batch does not have; it names the key of the study's file now."""
    grid = {"heading": [45], "hs": [2], "tp": [8]}
    study = _rm1(corpus, grid=grid, water_depth=50, source=tmp_path / "rm1.yaml")
    study = replace(study, restoring_includes_weight=None)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        prepare_study(study)
    texts = [str(w.message) for w in caught if "restoring holds the weight" in str(w.message)]
    assert len(texts) == 1, [str(w.message) for w in caught]
    assert "say the key restoring_includes_weight of rm1.yaml: yes" in texts[0]
    assert "--restoring-includes-weight" not in texts[0]


def test_a_statically_unstable_study_names_the_study_keys(corpus, tmp_path):
    """A spring that overturns the RM1 in heave: the simulate study is refused before any
    case, as `simulate` is (same error type), its hint naming the keys of the study's
    file, not the options --center-of-gravity, --external-stiffness of the command line."""
    from cummins.errors import CumminsError

    grid = {"heading": [45], "hs": [2], "tp": [8]}
    study = _rm1(corpus, grid=grid, water_depth=50, source=tmp_path / "rm1.yaml")
    study = replace(study, analysis="simulate", n_omega=None, duration=600.0)
    unstable = replace(study, external_stiffness=[["Heave", "Heave", -1.0e9]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(CumminsError) as caught:
            prepare_study(unstable)
    message = str(caught.value)
    assert "statically unstable in Heave" in message
    assert "the keys center_of_gravity and restoring_includes_weight of rm1.yaml" in message
    assert "(external_stiffness)" in message and "--" not in message
    assert type(caught.value).__name__ == "SimulationError"


@pytest.mark.parametrize(
    ("sea", "message"),
    [
        (
            "grid: {heading: [0], hs: [1, 2], tp: [6, -10]}",
            "bad.yaml: grid.tp: -10 s is not positive",
        ),
        ("grid: {heading: [0], hs: [0, 2], tp: [6]}", "bad.yaml: grid.hs: 0 m is not positive"),
        (
            "cases: [{heading: 0, hs: 1, tp: 6}, {heading: 0, hs: -1, tp: 6}]",
            "bad.yaml: cases[1].hs: -1 m is not positive",
        ),
    ],
)
def test_a_sea_state_not_positive_names_the_file_the_axis_and_the_value(tmp_path, sea, message):
    """A grid's H_s or T_p of 0 or less was refused as "grid: hs and tp must be positive",
    without the file, the axis or the value at fault."""
    from cummins.studies.study import load_study

    (tmp_path / "x.1").write_text("", encoding="utf-8")  # checked first: it exists
    (tmp_path / "bad.yaml").write_text(f"data: x.1\n{sea}\n", encoding="utf-8")
    with pytest.raises(StudyError) as caught:
        load_study(tmp_path / "bad.yaml").all_cases
    assert str(caught.value).endswith(message)


@pytest.mark.parametrize(
    ("key", "near"),
    [("n_omgea", "n_omega"), ("radii_of_gyrations", "radii_of_gyration"), ("density", None)],
)
def test_an_unknown_key_suggests_the_nearest_study_key(tmp_path, key, near):
    """A misspelt key is refused naming it and, when one is close, the key meant; the
    list of the keys follows as before."""
    from cummins.studies.study import STUDY_KEYS, load_study

    (tmp_path / "x.1").write_text("", encoding="utf-8")
    (tmp_path / "typo.yaml").write_text(f"data: x.1\n{key}: 1\n", encoding="utf-8")
    with pytest.raises(StudyError) as caught:
        load_study(tmp_path / "typo.yaml")
    message = str(caught.value)
    assert f"unknown key {key!r}" in message
    assert ("did you mean" in message) == (near is not None)
    if near is not None:
        assert f"did you mean {near!r}?" in message
    assert message.endswith(f"the keys are {', '.join(STUDY_KEYS)}")
