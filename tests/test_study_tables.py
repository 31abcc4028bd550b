"""What `cummins batch` prints and `cummins report` tables for a study with an axis beyond
heading × H_s × T_p (here a PTO-damping sweep of the WaveBot heaving on a PTO to the
ground, ``tests/test_pto_sweep.py``): every case must be told apart by its axes, and the
limiting H_s is given per damping, as the operability is.
"""

from __future__ import annotations

import html
import re

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from cummins.cli import main
from cummins.cli.html_cases import cases_body
from cummins.studies.operability import limiting_hs
from test_pto_sweep import STUDY, WAVEBOT, _run, _study

DAMPINGS = [300.0, 1000.0, 3000.0, 10000.0, 30000.0]


@pytest.fixture(scope="module")
def folder(corpus, tmp_path_factory):
    path = tmp_path_factory.mktemp("study_tables")
    (path / "waveBotBuoy.out").symlink_to(corpus / WAVEBOT)
    return path


def _rows(table_html: str) -> list[list[str]]:
    rows = re.findall(r"<tr>(.*?)</tr>", table_html, flags=re.S)
    cells = [re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", r, flags=re.S) for r in rows]
    return [[html.unescape(c).strip() for c in row] for row in cells]


def test_cli_prints_the_limiting_hs_per_damping(folder):
    """With limits and a damping sweep, the limiting H_s table has one row per heading and
    damping, each cell the file's limiting_hs (it was left out without a word)."""
    sweep = f"pto_damping: [{', '.join(f'{c:g}' for c in DAMPINGS)}]"
    text = STUDY.format(sweep=sweep) + "limits:\n  Heave: 0.05 m\n"
    (folder / "limits.yaml").write_text(text, encoding="utf-8")
    out = folder / "limits.nc"
    args = ["batch", str(folder / "limits.yaml"), "-o", str(out), "--workers", "1", "--force"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert "Limiting Hs [m] per heading [deg], pto_damping [N s/m] (rows)" in result.output
    with xr.open_dataset(out, engine="h5netcdf") as results:
        lim = limiting_hs(results.load()).sel(heading=0).transpose("pto_damping", "tp")
    assert lim.dims == ("pto_damping", "tp")
    table = result.output.split("Limiting Hs [m] per")[1].split("beyond the grid")[0]
    cells = [
        [c.strip() for c in line.split("│")[1:-1]] for line in table.splitlines() if "│" in line
    ]
    assert [r[:2] for r in cells] == [["0", f"{c:g}"] for c in DAMPINGS]
    for row, c in zip(cells, DAMPINGS, strict=True):
        one = lim.sel(pto_damping=c)
        expected = [
            f"> {v:.3g}" if b else f"{v:.3g}"
            for v, b in zip(one.values, one.beyond_grid.values, strict=True)
        ]
        assert row[2:] == expected
    # more damping, less heave: the limiting H_s cannot fall as the damping grows
    finite = lim.where(~lim.beyond_grid).values
    assert np.all(np.diff(finite, axis=0)[np.isfinite(np.diff(finite, axis=0))] >= 0)


def test_report_case_table_names_every_axis_with_units(corpus):
    """Each row of "Statistics per case" is one case: with the damping's column, no two
    rows share their axes (without it the 5 dampings of a sea state looked like repeats),
    and each row's significant heave is the file's for that damping."""
    results = _run(_study(corpus / WAVEBOT, DAMPINGS))
    body = cases_body(results)
    rows = _rows(body)
    header, cells = rows[0], rows[1:]
    assert header[:4] == ["heading [deg]", "hs [m]", "tp [s]", "pto_damping [N s/m]"]
    assert len(cells) == results.operable.size == 20
    keys = [tuple(r[:4]) for r in cells]
    assert len(set(keys)) == len(keys)
    for row in cells:
        h, hs, tp, c = (float(v) for v in row[:4])
        case = results.significant_amplitude.sel(heading=h, hs=hs, tp=tp, pto_damping=c)
        assert float(row[4]) == pytest.approx(float(case.squeeze()), rel=1e-3)


def test_report_says_how_it_chose_the_cases_it_shows(corpus):
    """More cases than the table holds: with limits, the worst; without, the first ones,
    said so (it claimed "the largest response/limit ratio" of a study without limits)."""
    results = _run(_study(corpus / WAVEBOT, DAMPINGS))
    body = cases_body(results, most=8)
    assert "The first 8 cases of 20 (no limits to rank them by)." in body
    assert "response/limit ratio" not in body
    limited = _run(_study(corpus / WAVEBOT, DAMPINGS, limits={"Heave": "0.05 m"}))
    body = cases_body(limited, most=8)
    assert "The 8 cases with the largest response/limit ratio of 20." in body
    shown = [float(r[-2]) for r in _rows(body)[1:]]
    worst = np.sort(limited.limit_ratio.max("criterion").values.ravel())[::-1][:8]
    np.testing.assert_allclose(shown, worst, rtol=1e-3)
