"""`cummins report` of a wave excitation model (`cummins fit-excitation`): the kind is
detected from the file's ``cummins_format``, the page holds the model's states, t_c and
NRMSE as the file records them (and measured again on the data it was fitted to, the
same numbers), the figure of the data against the model, and the model's failures in a
box, with one warning line on the terminal. The models are fitted to the bundled tanker
at two headings (head and beam seas) in well under a second each."""

from __future__ import annotations

import dataclasses
import html
import itertools
import re
import shutil

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.cli.html_report import detect_kind
from cummins.excitation_model import ExcitationModel, fit_excitation
from cummins.excitation_model.fit import model_nrmse
from test_report import _assert_self_contained

HEADINGS = np.radians([180.0, 90.0])
_PAGES = itertools.count()


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A model that meets its target (NRMSE 0.15: the tanker reaches 0.1 in head seas),
    one held to 6 states (it misses the 3 % target: a failure), one whose data are gone."""
    folder = tmp_path_factory.mktemp("excitation")
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, folder / f.name)
    ds = cummins.read(folder / "tanker.1")
    good = fit_excitation(ds, HEADINGS, nrmse_target=0.15)
    assert not good.attrs["failures"]  # the premise of the tests of a model without failures
    failed = fit_excitation(ds, HEADINGS, max_order=6)
    assert failed.attrs["failures"]
    lost = dataclasses.replace(
        good, attrs={**good.attrs, "source_file": str(folder / "gone" / "tanker_gone.1")}
    )
    out = {"data": folder / "tanker.1"}
    for name, model in (("good", good), ("failed", failed), ("lost", lost)):
        out[name] = model.save(folder / f"{name}.nc")
    return out


def _report(path, *options):
    page = path.with_name(f"{path.stem}-{next(_PAGES)}.html")
    result = CliRunner().invoke(main, ["report", str(path), "-o", str(page), *options])
    return result, page


def _rows(page: str) -> list[list[str]]:
    """The cells of every table row of the page, as text."""
    return [
        [html.unescape(c) for c in re.findall(r"<td[^>]*>(.*?)</td>", row)]
        for row in re.findall(r"<tr>(.*?)</tr>", page)
    ]


def _warnings(output: str) -> list[str]:
    return [line for line in output.splitlines() if "missed its" in line]


def test_kind_is_detected_and_checked(files):
    assert detect_kind(files["good"]) == "excitation-model"
    result, page = _report(files["good"], "--kind", "excitation-model")
    assert result.exit_code == 0, result.output
    assert "<title>good.nc: wave excitation model</title>" in page.read_text(encoding="utf-8")
    wrong, _ = _report(files["good"], "--kind", "model")
    assert wrong.exit_code == 2
    assert "wave excitation model" in wrong.output and "not a model file" in wrong.output
    data, _ = _report(files["data"], "--kind", "excitation-model")
    assert data.exit_code == 2 and "not a excitation-model file" in data.output


def test_page_holds_the_states_and_nrmse_the_file_records(files):
    """A row per (heading, DOF) with states: heading, t_c, DOF, states, the NRMSE the file
    records and the NRMSE measured again on the data (the same), target met; one figure,
    embedded; no failure box and no warning line."""
    result, page_file = _report(files["good"])
    assert result.exit_code == 0, result.output
    assert not _warnings(result.output)
    page = page_file.read_text(encoding="utf-8")
    _assert_self_contained(
        page, ("States and NRMSE per heading and DOF", "Fits against the data (tanker.1)"), 1
    )
    assert 'class="failures"' not in page
    model = ExcitationModel.load(files["good"])
    expected = [
        [
            f"{np.degrees(model.headings[m.heading]):.4g}",
            f"{model.delays[m.heading]:.4g}",
            model.dofs[m.dof],
            str(m.order),
            f"{m.metrics['nrmse']:.4g}",
            f"{m.metrics['nrmse']:.4g}",  # measured on the data now: the same
            "yes",
        ]
        for m in model.models
        if m.order
    ]
    rows = [r[:7] for r in _rows(page) if len(r) == 10]
    assert rows == expected
    assert len(rows) == 3 + 6  # head seas: surge, heave, pitch; beam seas: all six
    assert f"{model.total_order} over every heading and DOF" in page


def test_nrmse_measured_again_is_the_recorded_one(files):
    """model_nrmse on the data the model was fitted to gives the NRMSE the fit recorded;
    on the same data read with another water density (forces 1000/1025 of theirs) not."""
    model = ExcitationModel.load(files["good"])
    recorded = np.array([m.metrics["nrmse"] for m in model.models]).reshape(model.orders.shape)
    fitted = model.orders > 0
    measured = model_nrmse(cummins.read(files["data"]), model)
    np.testing.assert_allclose(measured[fitted], recorded[fitted], rtol=1e-9)
    assert np.all(np.isnan(measured[~fitted]))
    other = model_nrmse(cummins.read(files["data"], rho=1000.0), model)
    assert np.all(np.abs(other[fitted] - recorded[fitted]) > 1e-3 * recorded[fitted])


def test_data_read_otherwise_are_flagged(files):
    """``--rho 1000``: the data are not those the model was fitted to; the page says so."""
    result, page_file = _report(files["good"], "--rho", "1000")
    assert result.exit_code == 0, result.output
    page = page_file.read_text(encoding="utf-8")
    assert "the data are not those the model was fitted to" in page
    assert page.count('<td class="warning">') == int(
        (ExcitationModel.load(files["good"]).orders > 0).sum()
    )


def test_a_failed_model_says_so_in_a_box_and_one_line(files):
    result, page_file = _report(files["failed"])
    assert result.exit_code == 0, result.output
    (line,) = _warnings(result.output)
    assert line.startswith("warning: failed.nc: this model missed its fit targets: ")
    assert "(cummins fit-excitation exit 3)" in line
    page = page_file.read_text(encoding="utf-8")
    box = re.search(r'<div class="failures">(.*?)</div>', page, re.S)
    assert box is not None
    failures = ExcitationModel.load(files["failed"]).attrs["failures"]
    items = [html.unescape(i) for i in re.findall(r"<li>(.*?)</li>", box[1])]
    assert items == list(failures)
    misses = [r for r in _rows(page) if len(r) == 10 and r[6] == "no"]
    assert len(misses) == len(failures)


def test_data_not_found_the_page_shows_the_recorded_metrics(files):
    result, page_file = _report(files["lost"])
    assert result.exit_code == 0, result.output
    page = page_file.read_text(encoding="utf-8")
    _assert_self_contained(page, ("were not found", "response (data not found)"), 1)
    assert "NRMSE on the data now" not in page
    model = ExcitationModel.load(files["lost"])
    rows = [r for r in _rows(page) if len(r) == 9]
    assert [r[4] for r in rows] == [f"{m.metrics['nrmse']:.4g}" for m in model.models if m.order]


def test_data_recorded_relative_are_found_beside_the_model(files, tmp_path, monkeypatch):
    """`cummins fit-excitation tanker.1 …` records ``tanker.1`` as given; the report made
    from another folder finds it beside the model file."""
    folder = tmp_path / "work"
    folder.mkdir()
    for f in files["data"].parent.glob("tanker.*"):
        shutil.copy(f, folder / f.name)
    monkeypatch.chdir(folder)
    args = ["fit-excitation", "tanker.1", "-o", "exc.nc", "--heading", "180", "--nrmse", "0.15"]
    assert CliRunner().invoke(main, args).exit_code == 0
    assert ExcitationModel.load(folder / "exc.nc").attrs["source_file"] == "tanker.1"
    monkeypatch.chdir(tmp_path)
    result, page_file = _report(folder / "exc.nc")
    assert result.exit_code == 0, result.output
    assert "Fits against the data (tanker.1)" in page_file.read_text(encoding="utf-8")


def test_pages_open_in_chromium_with_their_figure(files, tmp_path):
    """The page of a model and of a failed one, in a real headless browser: no console
    or page error, the figure decoded, nothing fetched beyond the file, not blank, and the
    failed model's box rendered (visible, with one item per failure)."""
    from _browser import CHROMIUM, not_blank, playwright_chromium
    from test_report import BROWSER_ARGS, _open

    with playwright_chromium() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=BROWSER_ARGS)
        try:
            for name in ("good", "failed"):
                result, page_file = _report(files[name])
                assert result.exit_code == 0, result.output
                shot = tmp_path / f"{name}.png"
                errors, widths, requests = _open(browser, page_file, shot)
                assert not errors, f"{name}: {errors}"
                assert widths and min(widths) > 0, f"{name}: figure not shown {widths}"
                assert all(u.startswith(("file:", "data:")) for u in requests), requests
                for png in (shot, shot.with_suffix(".figure.png")):
                    spread, ink = not_blank(png)
                    assert spread > 0.05 and ink > 0.03, f"{name}: blank {png.name} {spread} {ink}"
            page = browser.new_page()
            page.goto(_report(files["failed"])[1].as_uri())
            box = page.locator("div.failures")
            assert box.is_visible()
            failures = ExcitationModel.load(files["failed"]).attrs["failures"]
            assert box.locator("li").count() == len(failures)
            page.close()
        finally:
            browser.close()
