"""A radiation model is used only with the data it was fitted to: the fit records their
fingerprint (DOFs, ρ, g, frequencies, A(ω) and B(ω) at 12 of them, the source file's
name and SHA-256) and every place a model meets data refuses other data, naming what
differs, unless the user says so (``--allow-other-data``); model files written before
the fingerprint are checked by their DOFs and A∞ with a warning.
"""

from __future__ import annotations

import shutil
import warnings
from dataclasses import replace

import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import CumminsWarning, HydroDataError
from cummins.radiation.fingerprint import check_model_data
from cummins.vessel import vessel_from_hydrodb


@pytest.fixture(scope="module")
def tanker(tmp_path_factory):
    """The bundled tanker in a folder of the user's, its default model saved there."""
    root = tmp_path_factory.mktemp("tanker")
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, root / f.name)
    ds = cummins.read(root / "tanker.1")
    model = cummins.fit_radiation(ds)
    model.save(root / "model.nc")
    return root, ds, model


def _read(path, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path, **options)


def test_the_fingerprint_is_recorded_and_survives_the_file(tanker):
    root, ds, model = tanker
    saved = cummins.RadiationModel.load(root / "model.nc")
    fp = saved.attrs["data_fingerprint"]
    assert fp == model.attrs["data_fingerprint"]
    assert fp["dofs"] == [str(d) for d in ds.influenced_dof.values]
    assert fp["source_name"] == "tanker.1" and len(fp["source_sha256"]) == 64
    assert len(fp["omega"]) == 12
    check_model_data(saved, ds)  # its own data: nothing to say
    # a converted copy of the same data is the same data
    cummins.write(ds, root / "copy.nc", force=True)
    check_model_data(saved, _read(root / "copy.nc"))


def test_another_vessels_data_are_refused_naming_what_differs(tanker, shared_data):
    _, _, model = tanker
    supply = _read(shared_data / "mss" / "supply" / "supply.mat")
    with pytest.raises(HydroDataError) as refused:
        vessel_from_hydrodb(supply, model)
    text = str(refused.value)
    assert "fitted to other data" in text and "fitted to tanker.1, used with supply.mat" in text
    assert "--allow-other-data" in text
    with pytest.warns(CumminsWarning, match="used anyway"):
        check_model_data(model, supply, allow_other_data=True)


def test_other_density_refused_on_the_command_line(tanker, tmp_path):
    """`cummins simulate model.nc` reads the model's own file; with another --rho the
    data are not those of the fit: exit 1 naming ρ, unless --allow-other-data."""
    root, _, _ = tanker
    args = ["simulate", str(root / "model.nc"), "--regular", "--wave-period", "9",
            "--heading", "150", "--duration", "20", "--viscous-damping", "Surge", "1e6",
            "--viscous-damping", "Sway", "1e6", "--viscous-damping", "Yaw", "1e10",
            "-o", str(tmp_path / "run.nc")]  # fmt: skip
    result = CliRunner().invoke(main, [*args, "--rho", "1000"])
    assert result.exit_code == 1, result.output
    text = " ".join(result.output.split())
    assert "rho 1025 kg/m^3 at the fit, 1000 kg/m^3 here" in text
    result = CliRunner().invoke(main, [*args, "--rho", "1000", "--allow-other-data"])
    assert result.exit_code == 0, result.output
    assert "used anyway" in " ".join(result.output.split())
    result = CliRunner().invoke(main, [*args, "--force"])
    assert result.exit_code == 0, result.output


def test_reduce_with_another_vessels_data_is_refused(tanker, shared_data, tmp_path):
    root, _, _ = tanker
    supply = shared_data / "mss" / "supply" / "supply.mat"
    args = ["reduce", str(root / "model.nc"), "-o", str(tmp_path / "small.nc"), "--tol", "0.05",
            "--data", str(supply), "--speed", "0"]  # fmt: skip
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 1, result.output
    assert "model.nc was fitted to other data" in " ".join(result.output.split())


def test_model_files_without_fingerprint_warn_and_compare_a_inf(tanker, shared_data):
    """A model written before the fingerprint: a warning with its own data, and another
    vessel's data refused by A∞ (the tanker's roll A∞, 9.6e9 kg m², against the supply
    vessel's 6.9e7)."""
    _, ds, model = tanker
    old = replace(model, attrs={k: v for k, v in model.attrs.items() if k != "data_fingerprint"})
    with pytest.warns(CumminsWarning, match="records no fingerprint"):
        vessel_from_hydrodb(ds, old)
    supply = _read(shared_data / "mss" / "supply" / "supply.mat")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CumminsWarning)
        with pytest.raises(HydroDataError, match=r"A-infinity of Roll is 9\.58"):
            check_model_data(old, supply)
