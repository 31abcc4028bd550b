"""A model that missed its fit targets never flows on silently (issue 30, point 6):
``simulate``, ``reduce``, ``report`` and ``convert --model`` given such a model, and
``simulate`` fitting one on the fly, say so in one line, and the run file and the reduced
model record it.

The failed model is the identification of a moonpool's sharp piston mode
(``tests/data/moonpool_sharp_capytaine.nc``, 5 % of critical damping) held to at most
4 common poles (``--max-order 4``): motion error 5.5 % of the peak, above the 2 % that
makes a fit a failure (exit status 3; the default fit, 20 poles, is within 1.1 %). Data
whose default fit fails: the HAMS cylinder of the corpus, whose data are not reciprocal
(motion error 12.6 %, the data's limit, which the failure names).
"""

from pathlib import Path

import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.cli.failed_model import failed_model_line

DATA = Path(__file__).parent / "data"
SHARP = DATA / "moonpool_sharp_capytaine.nc"
#: a regular wave of the data's heading 0 at the piston mode, short
WAVE = ["--regular", "--wave-period", "3.5", "--heading", "0", "--duration", "60"]


def _run(*args):
    result = CliRunner().invoke(main, [str(a) for a in args])
    return result


@pytest.fixture(scope="module")
def failed(tmp_path_factory):
    """The fit of the sharp piston mode, saved as ``cummins fit`` writes it."""
    path = tmp_path_factory.mktemp("failed") / "model.nc"
    result = _run("fit", SHARP, "-o", path, "--max-order", 4)
    assert result.exit_code == 3, result.output  # a failure: the premise of these tests
    assert cummins.RadiationModel.load(path).attrs["failures"]
    # the motions fail: the option that fits them on the motions themselves is named
    assert "hint: --refine-motions refines the blocks that miss" in result.output
    return path


def _warnings(output: str) -> list[str]:
    return [line for line in output.splitlines() if "missed its" in line]


def test_simulate_a_failed_model_says_so_and_the_run_records_it(failed, tmp_path):
    run = tmp_path / "run.nc"
    result = _run("simulate", failed, *WAVE, "-o", run)
    assert result.exit_code == 0, result.output
    (line,) = _warnings(result.output)
    assert line.startswith("warning: model.nc: this model missed its fit targets: motion error")
    assert "(cummins fit exit 3); results inherit it" in line
    recorded = xr.open_dataset(run).attrs["model_failures"]
    assert recorded.splitlines() == cummins.RadiationModel.load(failed).attrs["failures"]


def test_simulate_data_whose_fit_fails_says_so(tmp_path, corpus):
    run = tmp_path / "run.nc"
    cylinder = corpus / "HAMS" / "Cylinder" / "Output_Benchmark" / "Wamit_format" / "Buoy.1"
    result = _run("simulate", cylinder, *WAVE, "-o", run)
    assert result.exit_code == 0, result.output
    (line,) = _warnings(result.output)
    assert "Buoy.1: the radiation model fitted to these data missed" in line
    assert "motion error" in line
    assert "motion error" in xr.open_dataset(run).attrs["model_failures"]


def test_reduce_a_failed_model_says_so_and_the_reduced_model_keeps_it(failed, tmp_path):
    reduced = tmp_path / "small.nc"
    result = _run("reduce", failed, "-o", reduced, "--tol", "0.05")
    (line,) = _warnings(result.output)
    assert line.startswith("warning: model.nc: this model missed its fit targets")
    kept = cummins.RadiationModel.load(reduced).attrs["failures"]
    assert set(cummins.RadiationModel.load(failed).attrs["failures"]) <= set(kept)
    # and the reduced model says so again wherever it goes
    again = _run("report", reduced, "-o", tmp_path / "small.html")
    assert again.exit_code == 0, again.output
    assert _warnings(again.output)[0].startswith("warning: small.nc: this model missed")


def test_convert_with_a_failed_model_says_so(tmp_path):
    """The BEMIO .h5 WEC-Sim reads gets a failed model's state space: said in the line
    (the semisubmersible held to 2 poles per block: motion error 12.6 %, exit 3)."""
    data, model = DATA / "semisub_capytaine.nc", tmp_path / "semi.nc"
    assert _run("fit", data, "-o", model, "--max-order", 2).exit_code == 3
    result = _run("convert", data, tmp_path / "semi.h5", "--model", model)
    assert result.exit_code == 0, result.output
    (line,) = _warnings(result.output)
    assert line.startswith("warning: semi.nc: this model missed its fit targets")


def test_report_of_a_failed_model_and_of_its_run_say_so(failed, tmp_path):
    import html
    import re

    result = _run("report", failed, "-o", tmp_path / "model.html")
    assert result.exit_code == 0, result.output
    assert len(_warnings(result.output)) == 1
    # and the page, in a box above the fit table: every failure the model records
    page = (tmp_path / "model.html").read_text(encoding="utf-8")
    box = re.search(r'<div class="failures">(.*?)</div>', page, re.S)
    assert box is not None and page.index(box[0]) < page.index("<table")
    items = [html.unescape(i) for i in re.findall(r"<li>(.*?)</li>", box[1])]
    assert items == list(cummins.RadiationModel.load(failed).attrs["failures"])
    run = tmp_path / "run.nc"
    assert _run("simulate", failed, *WAVE, "-o", run).exit_code == 0
    result = _run("report", run, "-o", tmp_path / "run.html")
    assert result.exit_code == 0, result.output
    (line,) = _warnings(result.output)
    assert "run.nc: the radiation model this file was made with missed its fit targets" in line


def test_a_model_that_met_its_targets_says_nothing(tmp_path):
    model = tmp_path / "good.nc"
    assert _run("fit", DATA / "moonpool_capytaine.nc", "-o", model).exit_code == 0
    run = tmp_path / "run.nc"
    result = _run("simulate", model, *WAVE, "-o", run)
    assert result.exit_code == 0, result.output
    assert not _warnings(result.output)
    assert "model_failures" not in xr.open_dataset(run).attrs
    assert not _warnings(_run("report", run, "-o", tmp_path / "run.html").output)


def test_the_line_puts_the_motion_error_first_and_counts_the_rest():
    failures = [
        "Surge: passivity took the R² of A from 0.99 to 0.97 (target 0.99)",
        "Heave: passivity took the R² of B from 0.99 to 0.95 (target 0.99)",
        "Pitch: passivity took the R² of B from 0.99 to 0.90 (target 0.99)",
        "motion error 30.56 % of the peak motion (target 1 %, never above 2 %)",
    ]
    line = failed_model_line(failures, "rm3.nc")
    assert line == (
        "rm3.nc: this model missed its fit targets: motion error 30.56 % of the peak motion; "
        "Surge: passivity took the R² of A from 0.99 to 0.97 and 2 more (cummins fit exit 3); "
        "results inherit it"
    )


def test_a_failed_model_of_any_name_says_so(failed, tmp_path):
    """Told by its content, not its name: the same model saved as ``fit.model`` gives
    the same one line in `report` (and `simulate`), and the page is a model's."""
    import shutil

    renamed = tmp_path / "fit.model"
    shutil.copy(failed, renamed)
    result = _run("report", renamed, "-o", tmp_path / "page.html")
    assert result.exit_code == 0, result.output
    (line,) = _warnings(result.output)
    assert line.startswith("warning: fit.model: this model missed its fit targets")
    assert "Fitted couplings" in (tmp_path / "page.html").read_text(encoding="utf-8")
    result = _run("simulate", renamed, *WAVE, "-o", tmp_path / "run.nc")
    assert result.exit_code == 0, result.output
    assert _warnings(result.output)[0].startswith("warning: fit.model: this model missed")


def test_the_refinement_can_be_turned_off(tmp_path):
    """``--no-refine-motions``: the fit without the default's refinement, still a failure
    (exit 3), and the hint names the option that refines to the end."""
    result = _run("fit", SHARP, "-o", tmp_path / "m.nc", "--max-order", 4, "--no-refine-motions")
    assert result.exit_code == 3, result.output
    assert "hint: --refine-motions refines the blocks that miss" in result.output


def test_a_statically_unstable_system_is_what_the_motion_failure_names(corpus, tmp_path):
    """Capytaine's OSWEC (corpus) fitted floating freely, with the file's own inertia and
    hydrostatics: the flap's pitch restoring is negative (the hinge holds it in WEC-Sim),
    so its motion RAOs are no steady state. The motion failure names that instability,
    not the data's causality it blamed before, and ``fit`` hints no refinement of such
    motions; a stable body's fit names none."""
    from cummins.hydrodb import dof_matrix

    data = corpus / "WEC-Sim/capytaine_OSWEC_flap/outputs/oswec_hydrodynamics.nc"
    ds = cummins.read(data)
    pitch = list(ds.influenced_dof.values).index("body1__Pitch")
    assert dof_matrix(ds, "hydrostatic_stiffness")[pitch, pitch] < 0  # Capytaine's: the premise
    result = _run("fit", data, "-o", tmp_path / "oswec.nc")
    assert result.exit_code == 3, result.output
    assert "statically unstable in body1__Pitch" in result.output
    assert "hint: --refine-motions" not in result.output
    model = cummins.RadiationModel.load(tmp_path / "oswec.nc")
    (unstable,) = model.attrs["statically_unstable"]
    assert unstable.startswith("body1__Pitch (C = -")
    (failure,) = [f for f in model.attrs["failures"] if f.startswith("motion error")]
    assert "statically unstable in body1__Pitch" in failure
    assert "the data limit it" not in failure
    stable = cummins.fit_radiation(cummins.read(SHARP))
    assert stable.attrs["statically_unstable"] == []
