"""HTML reports of a database, a model, RAOs, a run and batch results: self-contained,
and shown by a real headless browser (Debian's Chromium) with their figures."""

from __future__ import annotations

import itertools
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from _browser import CHROMIUM, not_blank, playwright_chromium
from cummins.cli import main
from cummins.cli.html_report import detect_kind, write_report
from cummins.studies.batch import (
    Study,
    case_ids,
    case_statistics,
    gather_results,
    prepare_study,
    write_results,
)

TANKER = cummins.demo_files() / "tanker.1"
BROWSER_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """One file of each kind a report is made of (the bundled tanker)."""
    from cummins.io.netcdf import save_netcdf
    from cummins.seakeeping.frequency_domain import motion_rao, save_rao
    from cummins.seakeeping.waves import irregular_waves, wave_spectrum
    from cummins.timedomain.simulate import simulate_waves
    from cummins.vessel import vessel_from_hydrodb

    folder = tmp_path_factory.mktemp("report")
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, folder / f.name)
    ds = cummins.read(folder / "tanker.1")
    # heave and pitch only for the data and model pages: fewer figures to draw
    cummins.write(cummins.select_dofs(ds, ["Heave", "Pitch"]), folder / "heave_pitch.nc")
    small = cummins.read(folder / "heave_pitch.nc")
    cummins.fit_radiation(small).save(folder / "model.nc")
    model = cummins.fit_radiation(ds)
    save_rao(motion_rao(ds, wave_direction=np.radians([90, 180])), folder / "rao.nc")
    vessel = vessel_from_hydrodb(ds, model, viscous_damping=[1e6, 1e6, 0, 0, 0, 1e10])
    sea = irregular_waves(wave_spectrum("jonswap", 3, 9), duration=600, direction=2.6, seed=1)
    run = simulate_waves(vessel, ds, sea, duration=600, dt=0.1)
    run.attrs["sea"] = "JONSWAP Hs 3 m, Tp 9 s"
    save_netcdf(run, folder / "run.nc")
    # batch results made without a cluster: the same case function and gathering
    study = Study(
        data=folder / "tanker.1",
        grid={"heading": [90, 180], "hs": [2, 4], "tp": [8, 11]},
        n_omega=200,
        limits={"Roll": "3 deg", "Heave": {"max": "2 m"}},
    )
    context, digest = prepare_study(study)
    values = [case_statistics(context, c) for c in study.all_cases]
    dofs = [str(d) for d in context.ds.influenced_dof.values]
    results = gather_results(study, values, case_ids(study, digest), dofs)
    write_results(results, folder / "results.nc")
    return {
        "data": folder / "heave_pitch.nc",
        "model": folder / "model.nc",
        "rao": folder / "rao.nc",
        "run": folder / "run.nc",
        "batch": folder / "results.nc",
    }


@pytest.fixture(scope="module")
def reports(files, tmp_path_factory):
    """The report of each file, written through the command line."""
    folder = tmp_path_factory.mktemp("pages")
    out = {}
    for kind, path in files.items():
        page = folder / f"{kind}.html"
        result = CliRunner().invoke(main, ["report", str(path), "-o", str(page)])
        assert result.exit_code == 0, result.output
        out[kind] = page
    return out


@pytest.mark.parametrize("kind", ["data", "model", "rao", "run", "batch"])
def test_kind_is_detected_from_the_content(files, kind):
    assert detect_kind(files[kind]) == kind


EXPECTED = {
    "data": ("Data checks", "Retardation functions K(t)", "Motion RAOs", 4),
    # K(t) and one figure per DOF: heave (heave, heave ← pitch) and pitch
    "model": ("Fitted couplings", "Fits against the data", "Heave–Pitch", 3),
    "rao": ("Motion RAOs", "max |RAO|", "Roll", 1),
    "run": ("Response statistics", "Time series", "Response spectra", 2),
    "batch": ("Operability", "Limiting Hs", "Statistics per case", 2),
}


def _assert_self_contained(page: str, texts, n_figures: int) -> None:
    """The texts are there, ``n_figures`` embedded PNGs, inline style, no scripts, no
    address outside the page."""
    for text in texts:
        assert text in page
    images = re.findall(r'<img src="([^"]+)"', page)
    assert len(images) == n_figures
    assert all(src.startswith("data:image/png;base64,") for src in images)
    assert "<script" not in page.lower()
    assert not re.search(r'(src|href)="(?!data:|#)', page), "a link out of the page"
    assert "<style>" in page and "<link" not in page


@pytest.mark.parametrize("kind", list(EXPECTED))
def test_report_is_self_contained(reports, kind):
    """Embedded PNG figures, inline style, no scripts, no address outside the page."""
    *texts, n_figures = EXPECTED[kind]
    _assert_self_contained(reports[kind].read_text(encoding="utf-8"), texts, n_figures)


def test_batch_report_tables(reports, files):
    """The operability table in the page is the one of cummins.studies.operability."""
    from cummins.studies.batch import load_results
    from cummins.studies.operability import operability

    page = reports["batch"].read_text(encoding="utf-8")
    op = operability(load_results(files["batch"]))
    for heading, value in zip(op.heading.values, op.values, strict=True):
        assert f'<td>{heading:g}</td><td class="text">{100 * value:.1f} %</td>' in page


def test_report_refuses_to_overwrite_and_names_bad_input(reports, tmp_path):
    runner = CliRunner()
    again = runner.invoke(main, ["report", str(TANKER), "-o", str(reports["data"])])
    assert again.exit_code == 2 and "exists" in again.output
    junk = tmp_path / "junk.txt"
    junk.write_text("not a solver file\n", encoding="utf-8")
    bad = runner.invoke(main, ["report", str(junk), "-o", str(tmp_path / "x.html")])
    assert bad.exit_code == 1 and "junk.txt" in bad.output
    with pytest.raises(cummins.CumminsError):
        write_report(junk, tmp_path / "y.html")


def _report_text(page: Path) -> list[str]:
    """The visible text of a report, one item per line (no figures, no style)."""
    import html

    text = re.sub(r"<img[^>]*>|<style.*?</style>", "", page.read_text(), flags=re.S)
    text = re.sub(r"<[^>]+>", "\n", text)
    return [html.unescape(line).strip() for line in text.splitlines() if line.strip()]


def test_report_of_nondimensional_files_with_rho_g_ulen(tmp_path):
    """``--rho 1000 --g 9.80665 --ulen 2`` on the tanker's .1/.3/.hst without its .out
    (so neither constant is in the files): the page states them, and its dimensional
    values are those of reading the files with the same constants through the API
    (heave A-infinity, the 'data row' of the K(t) table: rho L^3 times the .1's value),
    not those of the defaults (1025 kg/m^3, L = 1 m)."""
    for suffix in (".1", ".3", ".hst"):
        shutil.copy(TANKER.with_suffix(suffix), tmp_path / f"tanker{suffix}")
    data = tmp_path / "tanker.1"
    page = tmp_path / "tanker.html"
    options = ["--rho", "1000", "--g", "9.80665", "--ulen", "2"]
    result = CliRunner().invoke(main, ["report", str(data), "-o", str(page), *options])
    assert result.exit_code == 0, result.output
    lines = _report_text(page)
    assert lines[lines.index("rho, g") + 1] == "1000 kg/m³, 9.80665 m/s²"
    heave = [b for a, b in itertools.pairwise(lines) if a == "Heave" and "K(0)" in b]
    assert len(heave) == 1, heave
    printed = float(re.search(r"data row (\S+);", heave[0])[1])
    given = cummins.read(data, rho=1000, g=9.80665, ulen=2)
    default = cummins.read(data)
    pick = {"influenced_dof": "Heave", "radiating_dof": "Heave"}
    expected = float(given.added_mass_inf.sel(pick))
    assert printed == float(f"{expected:.4g}")
    # the constants did reach the numbers: rho 1000/1025 and L^3 = 8 apart
    ratio = expected / float(default.added_mass_inf.sel(pick))
    assert ratio == pytest.approx(8 * 1000 / 1025, rel=1e-12)


def test_report_with_a_bad_rho_is_one_error_line(tmp_path):
    """``--rho nan``: exit status 2 (a bad option), one error line naming --rho, no
    traceback, no page."""
    page = tmp_path / "r.html"
    result = CliRunner().invoke(main, ["report", str(TANKER), "-o", str(page), "--rho", "nan"])
    assert result.exit_code == 2
    assert "Traceback" not in result.output and not page.exists()
    errors = [line for line in result.output.splitlines() if "error" in line.lower()]
    assert len(errors) == 1 and "--rho" in errors[0] and "nan" in errors[0], result.output


def _open(browser, page_file: Path, shot: Path) -> tuple[list[str], list[int], list[str]]:
    """Load a page: (console and page errors, widths of its decoded images, URLs asked)."""
    page = browser.new_page(viewport={"width": 1200, "height": 1000})
    errors: list[str] = []
    requests: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("request", lambda r: requests.append(r.url))
    page.goto(page_file.as_uri())
    page.wait_for_load_state("load")
    widths = page.evaluate("Array.from(document.images).map(i => i.complete ? i.naturalWidth : 0)")
    page.screenshot(path=str(shot), full_page=False)
    page.locator("img").first.screenshot(path=str(shot.with_suffix(".figure.png")))
    page.close()
    return errors, widths, requests


def test_reports_open_in_chromium_with_their_figures(reports, tmp_path):
    """Every page loads without console or page errors, every figure is decoded
    (naturalWidth > 0) and the screenshot shows something (not a blank page)."""
    with playwright_chromium() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=BROWSER_ARGS)
        try:
            for kind, page_file in reports.items():
                shot = tmp_path / f"{kind}.png"
                errors, widths, requests = _open(browser, page_file, shot)
                assert not errors, f"{kind}: {errors}"
                assert widths and min(widths) > 0, f"{kind}: figures not shown {widths}"
                assert all(u.startswith(("file:", "data:")) for u in requests), requests
                for png in (shot, shot.with_suffix(".figure.png")):  # the page, its first figure
                    spread, ink = not_blank(png)
                    assert spread > 0.05 and ink > 0.03, f"{kind}: blank {png.name} {spread} {ink}"
        finally:
            browser.close()


def test_reports_of_dp_runs_and_lf_models(tmp_path):
    """`cummins report` on the outputs of `cummins dp-demo` and `cummins lf-model`: the
    kinds are detected from the content, and the pages hold their checks, tables and
    figures, self-contained."""
    from cummins.cli.html_report import detect_kind

    runner = CliRunner()
    dp = tmp_path / "dp"
    assert runner.invoke(main, ["dp-demo", "-o", str(dp), "--duration", "30"]).exit_code == 0
    lf = tmp_path / "lf.nc"
    assert runner.invoke(main, ["lf-model", str(TANKER), "-o", str(lf)]).exit_code == 0
    assert detect_kind(dp / "run.nc") == "dp"
    assert detect_kind(lf) == "lf"
    for source, texts, n_figures in (
        (dp / "run.nc", ("Pose statistics", "Checks", "watch circle m", "Loads"), 3),
        (lf, ("Coefficients (diagonal)", "natural-frequency model"), 0),
    ):
        out = tmp_path / f"{source.stem}.html"
        result = runner.invoke(main, ["report", str(source), "-o", str(out)])
        assert result.exit_code == 0, result.output
        _assert_self_contained(out.read_text(encoding="utf-8"), texts, n_figures)
    # at a manoeuvring speed the page gives the speed and its terms N(U) (it showed only D,
    # as if at rest: N[Yaw, Yaw] = (m x_g + A26) U is on the diagonal)
    moving = tmp_path / "lf_moving.nc"
    args = ["lf-model", str(TANKER), "--manoeuvring-speed", "5", "-o", str(moving)]
    assert runner.invoke(main, args).exit_code == 0
    out = tmp_path / "lf_moving.html"
    assert runner.invoke(main, ["report", str(moving), "-o", str(out)]).exit_code == 0
    speed_terms = xr.open_dataset(moving, engine="h5netcdf").speed_terms
    yaw = float(speed_terms.sel(influenced_dof="Yaw", radiating_dof="Yaw"))
    _assert_self_contained(
        out.read_text(encoding="utf-8"), ("Speed terms at 5 m/s", "N[Yaw, Yaw]"), 0
    )
    assert yaw != 0 and f"{yaw:.4g}" in out.read_text(encoding="utf-8")
