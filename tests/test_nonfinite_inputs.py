"""Non-finite numbers where a file holds a physical quantity end in one clear line, never
a traceback: an MSS struct whose ``forceRAO`` frequencies are NaN (``cummins check``),
a model file whose A∞ holds a NaN (``cummins simulate``, ``RadiationModel.load``).
"""

from __future__ import annotations

import shutil

import h5py
import numpy as np
import pytest
import scipy.io
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import HydroDataError


def _no_traceback(result) -> None:
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception


def test_check_mss_struct_with_nan_force_rao_frequencies(tmp_path, shared_data):
    data = scipy.io.loadmat(shared_data / "mss" / "tanker" / "tanker.mat", squeeze_me=False)
    vessel = data["vessel"]
    vessel["forceRAO"][0, 0]["w"][0, 0][0, 3] = np.nan
    path = tmp_path / "nan_force_rao.mat"
    scipy.io.savemat(path, {"vessel": vessel})
    result = CliRunner().invoke(main, ["check", str(path)])
    _no_traceback(result)
    assert result.exit_code in (0, 1), result.output


@pytest.fixture(scope="module")
def tanker_model(tmp_path_factory):
    root = tmp_path_factory.mktemp("model")
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, root / f.name)
    model = cummins.fit_radiation(cummins.read(root / "tanker.1"))
    model.save(root / "model.nc")
    return root


def test_model_with_nan_added_mass_inf_is_refused_at_load(tanker_model, tmp_path):
    path = tmp_path / "model_nan.nc"
    shutil.copy(tanker_model / "model.nc", path)
    with h5py.File(path, "r+") as f:
        a = f["added_mass_inf"][...]
        a[2, 2] = np.nan
        f["added_mass_inf"][...] = a
    with pytest.raises(HydroDataError, match=r"model_nan\.nc.*A-infinity \[Heave\]"):
        cummins.RadiationModel.load(path)
    # the command names the file and the quantity on one line (exit 1: bad data)
    local = tanker_model / "model_nan.nc"
    shutil.copy(path, local)
    result = CliRunner().invoke(
        main,
        [
            "simulate",
            str(local),
            "--regular",
            "--wave-period",
            "9",
            "--heading",
            "90",
            "--duration",
            "30",
            "-o",
            str(tmp_path / "run.nc"),
        ],
    )
    _no_traceback(result)
    assert result.exit_code == 1, result.output
    assert "A-infinity" in result.output and "model_nan.nc" in result.output
