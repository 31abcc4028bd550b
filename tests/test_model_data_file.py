"""A model file names the data it was fitted to: the file ``cummins fit`` was given, not
the solver file that data came from. A NetCDF written by ``convert`` with moorings keeps
its solver's ``source_file`` (tanker.1); a model fitted to it, then simulated, used the
raw tanker.1 without the moorings (surge σ 8 % off, exit 0)."""

from __future__ import annotations

import shutil

import numpy as np
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main

SIM = ["--hs", "4", "--tp", "10", "--heading", "135", "--duration", "200", "--seed", "1"]


def _run(args):
    result = CliRunner().invoke(main, [str(a) for a in args])
    assert result.exit_code in (0, 3), result.output
    return result


def test_a_model_simulates_with_the_data_it_was_fitted_to(tmp_path):
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, tmp_path / f.name)
    moored = tmp_path / "tanker_moored.nc"
    mooring = [
        *("--external-stiffness", "Surge", "Surge", "2e6"),
        *("--external-stiffness", "Sway", "Sway", "2e6"),
        *("--external-stiffness", "Yaw", "Yaw", "5e9"),
    ]
    _run(["convert", tmp_path / "tanker.1", moored, *mooring])
    model = tmp_path / "models" / "moored_model.nc"
    model.parent.mkdir()
    _run(["fit", moored, "-o", model])
    assert cummins.RadiationModel.load(model).attrs["data_file"] == str(moored.resolve())
    _run(["simulate", moored, *SIM, "-o", tmp_path / "a.nc"])
    _run(["simulate", model, *SIM, "-o", tmp_path / "b.nc"])
    with xr.open_dataset(tmp_path / "a.nc") as a, xr.open_dataset(tmp_path / "b.nc") as b:
        np.testing.assert_array_equal(a.motion.values, b.motion.values)
    # moved with its data into another folder: found beside the model
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    shutil.move(model, elsewhere / model.name)
    shutil.move(moored, elsewhere / moored.name)
    _run(["simulate", elsewhere / model.name, *SIM, "-o", tmp_path / "c.nc"])
    with xr.open_dataset(tmp_path / "a.nc") as a, xr.open_dataset(tmp_path / "c.nc") as c:
        np.testing.assert_array_equal(a.motion.values, c.motion.values)
