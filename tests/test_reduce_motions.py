"""Reduction to a motion tolerance (`reduce --motion-tol`, issue 16).

``tol`` bounds the change of the DOF-scaled K(jω); what users check is the motions, and
near a lightly damped resonance a small change of K is a large one of the RAO (the tanker
at ``tol`` 0.02: 1.43 % of the peak motion, the OC3 Hywind spar 2.99 %).
:func:`~cummins.radiation.reduce.reduce_to_motion_tolerance` keeps the fewest states whose
motions stay within the tolerance, measured as the fit measured the full model
(:func:`cummins.radiation.fit.motion.fit_motion_error`), and the scoreboard's independent
:func:`cummins.radiation.fit.scorecard.motion_rao_error` agrees.
"""

from __future__ import annotations

import warnings

import pytest
from click.testing import CliRunner

from _synthetic import read_quietly
from cummins.cli import main
from cummins.errors import FitError, HydroDataError
from cummins.radiation.fit import fit_radiation
from cummins.radiation.fit.motion import fit_motion_error
from cummins.radiation.fit.scorecard import scorecard
from cummins.radiation.reduce import (
    MOTION_SEARCH,
    reduce_radiation_model,
    reduce_to_motion_tolerance,
)


def _fit(ds, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fit_radiation(ds, **options)


@pytest.fixture(scope="module")
def tanker(shared_data):
    ds = read_quietly(shared_data / "mss" / "tanker" / "tanker.1")
    return ds, _fit(ds)


@pytest.mark.parametrize(
    "case",
    [
        "mss/tanker/tanker.1",
        "mss/supply/supply.mat",
        "corpus/WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar",
    ],
)
def test_the_reduced_motions_stay_within_the_tolerance(shared_data, case):
    """Fewer states, the motions within 1 % by an independent recomputation of the error,
    passive and stable by the scorecard; and the next larger tolerance of the search
    would have missed 1 % (the search kept the fewest states it could)."""
    ds = read_quietly(shared_data / case)
    model = _fit(ds)
    small = reduce_to_motion_tolerance(model, ds, 0.01)
    assert small.total_order < model.total_order
    card = scorecard(ds, small)
    assert card.passive and card.stable
    assert card.rao_error.error <= 0.01
    # reduce judges by the fit's own measure (its kept frequencies): the unreduced model
    # scores the fit's motion_error (within 5e-8: the fit's data were its passive part)
    assert small.attrs["motion_error"] == pytest.approx(fit_motion_error(ds, small)[0], rel=1e-9)
    assert small.attrs["motion_error_unreduced"] == pytest.approx(
        model.attrs["motion_error"], rel=1e-6
    )
    used = MOTION_SEARCH.index(small.attrs["reduction_tol"])
    if used > 0:
        larger = reduce_radiation_model(model, tol=MOTION_SEARCH[used - 1], data=ds)
        assert fit_motion_error(ds, larger)[0] > 0.01


def test_a_model_already_further_than_the_tolerance_is_kept_and_says_why(tanker):
    """The tanker's fit is 0.54 % from the data's motions: no reduction meets 0.1 %."""
    ds, model = tanker
    kept = reduce_to_motion_tolerance(model, ds, 0.001)
    assert kept.total_order == model.total_order
    assert any("no reduction can meet it" in f for f in kept.attrs["failures"])


def test_a_per_coupling_model_or_data_without_inertia_is_refused(tanker, corpus):
    ds, _ = tanker
    with pytest.raises(FitError, match="common-pole"):
        reduce_to_motion_tolerance(_fit(ds, method="fd"), ds, 0.01)
    barge = read_quietly(corpus / "ROSCO" / "wamit_ITI_barge_5MW_Baseline" / "Barge.1")
    with pytest.raises(HydroDataError, match="inertia_matrix"):
        reduce_to_motion_tolerance(_fit(barge), barge, 0.01)


def test_the_command_line(tanker, tmp_path, shared_data):
    """--motion-tol needs --data (usage error, 2); it prints the motion error and the
    tolerance used; a target the unreduced model misses is a failure (exit status 3)."""
    _, model = tanker
    path = tmp_path / "model.nc"
    model.save(path)
    data = str(shared_data / "mss" / "tanker" / "tanker.1")
    runner = CliRunner()
    out = str(tmp_path / "small.nc")
    result = runner.invoke(main, ["reduce", str(path), "-o", out, "--motion-tol", "0.01"])
    assert result.exit_code == 2 and "--data" in result.output
    result = runner.invoke(
        main, ["reduce", str(path), "-o", out, "--motion-tol", "0.01", "--data", data]
    )
    assert result.exit_code == 0, result.output
    assert "motion-RAO error" in result.output and "reduced at --tol" in result.output
    result = runner.invoke(
        main,
        ["reduce", str(path), "-o", out, "--motion-tol", "0.001", "--data", data, "--force"],
    )
    assert result.exit_code == 3 and "no reduction can meet it" in result.output


def test_a_joined_model_is_reduced_on_the_joined_systems_motions(tmp_path):
    """A model fitted for joined bodies (the float and spar of ``float_spar_capytaine.nc``
    on a heave slider with a 1 MN·s/m PTO) is reduced against --data given the same
    options: its unreduced motion error is the one its fit measured (the joined system's,
    0.43 %; the free bodies' is 0.94 %). The options without --data are a usage error, and
    --data without them says that the motions compared are the free bodies'."""
    from pathlib import Path

    from cummins.radiation.model import RadiationModel

    data = str(Path(__file__).parent / "data" / "float_spar_capytaine.nc")
    joint = ["--joint", "translational", "body1", "body2", "--axis", "0", "0", "1"]
    joint += ["--pto-damping", "1e6"]
    model, small = str(tmp_path / "model.nc"), str(tmp_path / "small.nc")
    runner = CliRunner()
    result = runner.invoke(main, ["fit", data, *joint, "-o", model])
    assert result.exit_code == 0, result.output
    fitted = RadiationModel.load(model).attrs["motion_error"]
    reduce = ["reduce", model, "-o", small, "--motion-tol", "0.02", "--force"]
    result = runner.invoke(main, [*reduce, "--data", data, *joint])
    assert result.exit_code == 0, result.output
    reduced = RadiationModel.load(small)
    # the fit measured it on its repaired (nearest passive) data: the same to 0.2 %
    assert reduced.attrs["motion_error_unreduced"] == pytest.approx(fitted, rel=0.02)
    assert reduced.attrs["motion_error"] <= 0.02
    assert reduced.total_order < RadiationModel.load(model).total_order
    assert "fitted for the joined system" not in result.output
    result = runner.invoke(main, [*reduce, *joint])
    assert result.exit_code == 2 and "give --data" in result.output
    result = runner.invoke(main, [*reduce, "--data", data])
    assert result.exit_code == 0, result.output
    assert "fitted for the joined system's motions" in result.output
    free = RadiationModel.load(small).attrs["motion_error_unreduced"]
    assert free > 1.5 * fitted  # the free bodies' motions are another measure


def test_the_command_line_names_the_inertia_options(corpus, tmp_path):
    """WEIS' OC3 spar (no inertia in its WAMIT files), fitted, then reduced with
    --motion-tol: the error ended in "give the data the model was fitted to (with the
    mass properties)", naming no option; with the mass options given, the model fitted
    without them missed the target (2.2 %) with no word of why. Now: a usage error naming
    --mass …; and a note to fit again with them, which, followed, reduces (0.25 %)."""
    data = str(corpus / "WEIS" / "ss_fitting_OC3_spar" / "spar.1")
    mass = ["--mass", "7.466e6", "--center-of-gravity", "0", "0", "-89.92"]
    mass += ["--radii-of-gyration", "66.2", "66.2", "10"]
    mass += ["--external-stiffness", "Surge", "Surge", "4.1e4"]
    mass += ["--external-stiffness", "Sway", "Sway", "4.1e4"]
    mass += ["--external-stiffness", "Yaw", "Yaw", "9.8e7"]
    runner = CliRunner()
    bare, aimed = str(tmp_path / "bare.nc"), str(tmp_path / "aimed.nc")
    assert runner.invoke(main, ["fit", data, "-o", bare]).exit_code == 0
    reduce = ["reduce", bare, "-o", str(tmp_path / "r.nc"), "--motion-tol", "0.01"]
    result = runner.invoke(main, [*reduce, "--data", data])
    assert result.exit_code == 2 and "--mass" in result.output, result.output
    result = runner.invoke(main, [*reduce, "--data", data, *mass])
    text = " ".join(result.output.split())
    assert result.exit_code == 3 and "was fitted without the motions to aim at" in text
    assert runner.invoke(main, ["fit", data, "-o", aimed, *mass]).exit_code == 0
    reduce[1] = aimed
    result = runner.invoke(main, [*reduce, "--data", data, *mass, "--force"])
    assert result.exit_code == 0, result.output
    assert "was fitted without" not in result.output
