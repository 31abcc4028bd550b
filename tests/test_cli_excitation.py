"""``cummins fit-excitation``: table, files, exit status; the .ssexctn it writes."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from cummins.cli import main
from cummins.excitation_model import ExcitationModel

SPAR = "WEIS/ss_fitting_OC3_spar"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_fit_excitation_writes_the_model_table_json_and_plots(corpus, tmp_path):
    out, summary, plots = tmp_path / "exc.nc", tmp_path / "exc.json", tmp_path / "plots"
    result = run(
        "fit-excitation", corpus / SPAR / "spar.1", "-o", out, "--heading", 0,
        "--json", summary, "--plot", plots,
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    assert "Surge" in result.output and "Sway" not in result.output  # not excited at 0 deg
    model = ExcitationModel.load(out)
    info = json.loads(summary.read_text())
    assert info["total_states"] == model.total_order and info["stable"]
    assert info["delays_s"] == [float(model.delays[0])]
    assert (plots / "excitation_0deg.png").stat().st_size > 10_000
    again = run("fit-excitation", corpus / SPAR / "spar.1", "-o", out, "--heading", 0)
    assert again.exit_code == 2 and "--force" in again.output


def test_a_missed_target_exits_with_status_3(corpus, tmp_path):
    out = tmp_path / "exc.nc"
    result = run(
        "fit-excitation", corpus / SPAR / "spar.1", "-o", out, "--heading", 0, "--max-order", 4
    )
    assert result.exit_code == 3, result.output
    assert "failure" in result.output and out.exists()


def test_given_delay_and_order(corpus, tmp_path):
    out = tmp_path / "exc.nc"
    result = run(
        "fit-excitation", corpus / SPAR / "spar.1", "-o", out, "--heading", 0,
        "--delay", 12.5, "--order", 20,
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    model = ExcitationModel.load(out)
    assert model.delays.tolist() == [12.5]
    assert model.orders[0].tolist() == [20, 0, 20, 0, 20, 0]
    assert np.isclose(model.headings[0], 0.0)


@pytest.mark.parametrize(
    ("args", "text"),
    [
        (["--nrmse", "0"], "--nrmse"),
        (["--causality", "0.7"], "--causality"),
        (["--delay", "-1"], "--delay"),
    ],
)
def test_bad_options_are_refused(corpus, tmp_path, args, text):
    result = run("fit-excitation", corpus / SPAR / "spar.1", "-o", tmp_path / "x.nc", *args)
    assert result.exit_code == 2 and text in result.output


def test_openfast_ssexctn_needs_one_heading(corpus, tmp_path):
    from cummins.io.openfast import read_openfast_ssexctn

    out, ss = tmp_path / "exc.nc", tmp_path / "spar.ssexctn"
    result = run("fit-excitation", corpus / SPAR / "spar.1", "-o", out, "--openfast", ss)
    assert result.exit_code == 2 and "one heading" in result.output and not out.exists()
    result = run(
        "fit-excitation", corpus / SPAR / "spar.1", "-o", out, "--heading", 0, "--openfast", ss
    )
    assert result.exit_code == 0, result.output
    content = read_openfast_ssexctn(ss)
    assert content.n_states == ExcitationModel.load(out).total_order
    assert f"{content.n_states} states" in result.output


def test_openfast_ssexctn_says_the_wavedir_it_wrote(shared_data, tmp_path):
    """MSS's S-175 (Fossen's z-down axes), head-quartering seas 150°: the file holds
    HydroDyn's z-up heading, -150°, which SS_Excitation compares with WaveDir and stops
    on a mismatch; the command printed "WaveDir 150 deg". It prints the file's value."""
    out = tmp_path / "s.ssexctn"
    args = ["fit-excitation", str(shared_data / "mss" / "s175" / "s175.mat"), "--speed", "0"]
    args += ["-o", str(tmp_path / "e.nc"), "--heading", "150", "--nrmse", "0.12"]
    result = CliRunner().invoke(main, [*args, "--openfast", str(out)])
    assert result.exit_code == 0, result.output
    written = float(out.read_text().splitlines()[1].split()[0])
    assert written == -150.0
    text = " ".join(result.output.split())
    assert "WaveDir -150 deg, the data's 150 deg in their z-down axes" in text
