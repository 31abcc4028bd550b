"""The power take-offs in `cummins report`: the RAO file, the run and the batch study of
WEC-Sim's RM3 (float on a PTO sliding along the heave-only spar, 1.2 MN·s/m, no body
coupling; ``docs/guide/wec.md``).

What is checked: the page prints the numbers of the file (the mean power, the peak power
RAO, every cell of the power matrix) to its printed digits, and they obey what no one here
wrote: the run's mean power is the frequency domain's ½ c ω² |Δ̂|² a² (278.3 kW), the power
matrix scales as H_s² at each T_p.
"""

from __future__ import annotations

import html
import re
import shutil

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from _browser import CHROMIUM, not_blank, playwright_chromium
from cummins.cli import main
from cummins.mass_properties import with_inertia

RM3_OPTIONS = [
    "--rho", "1000", "--mass", "725833", "--mass", "886687",
    "--center-of-gravity", "0", "0", "-0.72", "--center-of-gravity", "0", "0", "-21.29",
    "--radii-of-gyration", "5.367", "5.418", "7.148",
    "--radii-of-gyration", "10.319", "10.319", "5.674",
    "--joint", "translational", "body2", "ground",
    "--joint", "translational", "body1", "body2", "--axis", "0", "0", "1",
    "--pto-damping", "1.2e6", "--no-body-coupling",
]  # fmt: skip
#: ½ c ω² |Δ̂|² a² of the frequency-domain solution, H 2.5 m, T 8 s (docs/wec.md).
FREQUENCY_DOMAIN_POWER = 278.33e3


def _run(args):
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return result


@pytest.fixture(scope="module")
def pages(corpus, tmp_path_factory):
    """The RM3's RAO file, regular-wave run and power-matrix study, and their reports."""
    from cummins.studies.batch import (
        Study,
        case_ids,
        case_statistics,
        gather_results,
        prepare_study,
        write_results,
    )

    folder = tmp_path_factory.mktemp("report_pto")
    for f in (corpus / "WEC-Sim" / "wamit_RM3_2body").glob("rm3.*"):
        shutil.copy(f, folder / f.name)
    data = str(folder / "rm3.out")
    files = {"rao": folder / "rm3_rao.nc", "run": folder / "rm3_run.nc"}
    _run(["rao", data, *RM3_OPTIONS, "-o", str(files["rao"])])
    sea = ["--regular", "--wave-period", "8", "--wave-amplitude", "1.25", "--duration", "160"]
    _run(["simulate", data, *RM3_OPTIONS, *sea, "-o", str(files["run"])])
    ds = with_inertia(
        cummins.read(folder / "rm3.out", rho=1000.0),
        mass=[725833, 886687],
        center_of_gravity=[[0, 0, -0.72], [0, 0, -21.29]],
        radii_of_gyration=[[5.367, 5.418, 7.148], [10.319, 10.319, 5.674]],
    )
    cummins.write(ds, folder / "rm3.nc")
    study = Study(
        data=folder / "rm3.nc",
        grid={"heading": 0, "hs": [1, 2.5], "tp": [6, 8, 10]},
        spectrum="pm",
        n_omega=200,
        system={
            "body_coupling": False,
            "joints": [
                {"kind": "translational", "body": "body2", "axis": [0, 0, 1]},
                {
                    "kind": "translational",
                    "body": "body1",
                    "base": "body2",
                    "pto": {"damping": 1.2e6},
                },
            ],
        },
    )
    context, digest = prepare_study(study)
    values = [case_statistics(context, c) for c in study.all_cases]
    results = gather_results(
        study, values, case_ids(study, digest), context.labels, ptos=context.ptos
    )
    files["batch"] = folder / "rm3_results.nc"
    write_results(results, files["batch"])
    out = {}
    for kind, path in files.items():
        page = folder / f"{kind}.html"
        _run(["report", str(path), "-o", str(page)])
        out[kind] = (path, page.read_text(encoding="utf-8"), page)
    return out


def _section(page: str, title: str) -> str:
    start = page.index(f"<h2>{title}</h2>")
    end = page.find("<section", start)
    return page[start : end if end > 0 else None]


def _rows(section: str) -> list[list[str]]:
    """The cells of every table row of a section (header rows left out)."""
    rows = re.findall(r"<tr>((?:<td[^>]*>.*?</td>)+)</tr>", section)
    return [[html.unescape(c) for c in re.findall(r"<td[^>]*>(.*?)</td>", r)] for r in rows]


def cummins_open(path):
    import xarray as xr

    return xr.open_dataset(path, engine="h5netcdf")


def _printed(value: float) -> str:
    return f"{value:.4g}"  # as html_page.table_html prints a number


def test_rao_report_prints_the_files_peak_power(pages):
    """The largest pto_power of the file (kW/m²), its frequency and period; one figure."""
    from cummins.seakeeping.frequency_domain import load_pto_rao

    path, page, _ = pages["rao"]
    section = _section(page, "Power take-offs")
    pto = load_pto_rao(path)
    power = pto.pto_power.isel(pto=0, wave_direction=0).values
    i = int(np.argmax(power))
    w = float(pto.omega.values[i])
    row = _rows(section)[0]
    assert row[:5] == [
        "pto1",
        "0",
        _printed(power[i] / 1e3),
        _printed(w),
        _printed(2 * np.pi / w),
    ]
    delta = abs(complex(pto.pto_displacement.isel(pto=0, wave_direction=0).values[i]))
    assert row[6] == f"{delta:.4g} m/m"
    assert "translation along (0, 0, 1) of body1 relative to body2" in section
    assert 150 < power[i] / 1e3 < 230  # the RM3's peak (docs/guide/wec.md: 187.8 kW/m²)
    assert len(re.findall(r"<img ", section)) == 1


def test_run_report_prints_the_mean_power_of_the_file(pages):
    """The mean of pto_power over the last 10 periods and ∫ P dt, as the file gives them,
    and beside the mean the frequency domain's that simulate printed and recorded
    (pto_mean_power_frequency_domain); the mean is the frequency domain's within 0.5 %
    (measured 0.2 %)."""
    from cummins.timedomain.harmonics import last_periods

    path, page, _ = pages["run"]
    section = _section(page, "Power take-offs")
    with cummins_open(path) as run:
        t = run.time.values
        power = run.pto_power.values[:, 0]
        window = last_periods(t, 2 * np.pi / 8.0, 10)
        mean = float(power[window].mean())
        energy = float(np.trapezoid(power, t))
        reference = float(run.pto_mean_power_frequency_domain.values[0])
    row = _rows(section)[0]
    assert row[0] == "pto1"
    assert row[1] == _printed(mean / 1e3)
    assert row[2] == _printed(reference / 1e3)
    assert row[3] == _printed(energy / 1e6)
    assert float(row[1]) * 1e3 == pytest.approx(FREQUENCY_DOMAIN_POWER, rel=5e-3)
    assert reference == pytest.approx(FREQUENCY_DOMAIN_POWER, rel=1e-3)
    assert "over the last 10 wave periods of 8 s (t 80.05 to 160 s)" in section
    assert len(re.findall(r"<img ", section)) == 1


def test_batch_report_power_matrix(pages):
    """Every cell of the H_s × T_p table is the file's pto_mean_power (kW), and at each
    T_p the power scales as H_s² (linear responses): 2.5² = 6.25 to the printed digits."""
    from cummins.studies.batch import load_results

    path, page, _ = pages["batch"]
    section = _section(page, "Power matrix")
    power = load_results(path).pto_mean_power.isel(heading=0, pto=0).transpose("hs", "tp") / 1e3
    rows = _rows(section)
    assert len(rows) == 2
    for row, hs in zip(rows, power.hs.values, strict=True):
        assert row[0] == f"{hs:g}"
        assert row[1:] == [_printed(v) for v in power.sel(hs=hs).values]
    low, high = (np.array([float(c) for c in r[1:]]) for r in rows)
    np.testing.assert_allclose(high / low, 6.25, rtol=2e-3)
    assert 90 < float(rows[1][2]) < 130  # Hs 2.5, Tp 8: 110.8 kW in docs/wec.md
    assert len(re.findall(r"<img ", section)) == 1


def test_pto_pages_open_in_chromium(pages, tmp_path):
    """The three pages load without errors and their PTO figures are decoded and drawn."""
    from test_report import BROWSER_ARGS, _open

    with playwright_chromium() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=BROWSER_ARGS)
        try:
            for kind, (_, _, page_file) in pages.items():
                shot = tmp_path / f"{kind}.png"
                errors, widths, requests = _open(browser, page_file, shot)
                assert not errors, f"{kind}: {errors}"
                assert widths and min(widths) > 0, f"{kind}: figures not shown {widths}"
                assert all(u.startswith(("file:", "data:")) for u in requests), requests
                spread, ink = not_blank(shot)
                assert spread > 0.05 and ink > 0.03, f"{kind}: blank page {spread} {ink}"
        finally:
            browser.close()


def test_files_without_ptos_get_no_pto_section(tmp_path):
    """A RAO file, a run or results without PTOs: no PTO section (nothing made up)."""
    import xarray as xr

    from cummins.cli.html_pto import pto_batch_sections, pto_rao_sections, pto_run_sections
    from cummins.seakeeping.frequency_domain import motion_rao, save_rao

    ds = cummins.read(cummins.demo_files() / "tanker.1")
    save_rao(motion_rao(ds, [0.5, 1.0], [np.pi]), tmp_path / "rao.nc")
    assert pto_rao_sections(tmp_path / "rao.nc") == []
    empty = xr.Dataset({"motion": (("time", "dof"), np.zeros((3, 1)))})
    assert pto_run_sections(empty) == [] and pto_batch_sections(empty) == []


def test_tank_scale_pto_tables_are_in_watts(corpus, tmp_path):
    """The WaveBot (858 kg) in a regular wave of 1 cm and its RAOs on a PTO of 1 N·s/m:
    the run page's and RAO page's PTO tables write the powers in W (0.29 W, not
    0.00029 kW; the energy in J), as ``simulate`` and ``rao`` print them, each number the
    file's (kept in W) to its printed digits; before, these tables were in kW alone."""
    from cummins.cli.html_pto import pto_rao_sections, pto_run_sections
    from cummins.seakeeping.frequency_domain import load_pto_rao
    from cummins.timedomain.harmonics import last_periods

    data = str(corpus / "WEC-Sim_Applications/wamit_WaveBot/waveBotBuoy.out")
    common = [data, "--rho", "1000", "--mass", "858.415", "--dof", "Heave"]
    common += ["--pto", "Heave", "ground"]
    run_file, rao_file = tmp_path / "run.nc", tmp_path / "rao.nc"
    sea = ["--regular", "--wave-period", "2.5", "--wave-amplitude", "0.01", "--duration", "30"]
    _run(["simulate", *common, "--pto-damping", "1000", *sea, "-o", str(run_file)])
    _run(["rao", *common, "--pto-damping", "1", "--n-omega", "40", "-o", str(rao_file)])

    with cummins_open(run_file) as f:
        run = f.load()
    (section,) = pto_run_sections(run)
    power = run.pto_power.values[:, 0]
    mean = float(power[last_periods(run.time.values, 2 * np.pi / 2.5, 10)].mean())
    reference = float(run.pto_mean_power_frequency_domain.values[0])
    energy = float(np.trapezoid(power, run.time.values))
    assert 0.05 < mean < 1.0  # W (measured 0.29 W): the scale the W column is for
    for header in ("mean power [W]", "frequency domain [W]", "energy [J]", "max power [W]"):
        assert f"<th>{header}</th>" in section.body
    row = _rows(section.body)[0]
    assert row[1:5] == [_printed(v) for v in (mean, reference, energy, power.max())]
    text = re.sub(r"<img[^>]*>", "", section.body)  # a figure's base64 may spell kW
    assert "kW" not in text and "MJ" not in text

    (section,) = pto_rao_sections(rao_file)
    pto = load_pto_rao(rao_file).pto_power.isel(pto=0, wave_direction=0).values
    assert 0.1 < pto.max() < 1e3  # W/m² at 1 N·s/m
    assert "<th>max power [W/m²]</th>" in section.body
    assert _rows(section.body)[0][2] == _printed(pto.max())
    assert "kW" not in re.sub(r"<img[^>]*>", "", section.body)
