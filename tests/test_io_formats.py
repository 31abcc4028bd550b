"""Every file set in ../shared/data is detected by content and reads into a valid HydroDB."""

from __future__ import annotations

import shutil
import warnings

import pytest

import cummins
from cummins import HydroDataError

#: path under shared data → (detected format, options)
FILE_SETS = {
    "mss/tanker/tanker.1": ("wamit", {}),
    "mss/tanker/tanker.3": ("wamit", {}),
    "mss/tanker/tanker.hst": ("wamit", {}),
    "mss/tanker/tanker.out": ("wamit-out", {}),
    "mss/tanker/tanker.mat": ("mss", {}),
    "mss/supply/input.re7": ("veres", {}),
    "mss/supply/supply.mat": ("mss", {}),
    "mss/s175/s175.mat": ("mss", {}),
    "wecsim/sphere/sphere.1": ("wamit", {"rho": 1000.0}),
    "wecsim/sphere/sphere.out": ("wamit-out", {"rho": 1000.0}),
    "wecsim/sphere/sphere_hydrodynamics.nc": ("netcdf", {}),
    "wecsim/cylinder/cylinder_nemoh/cyl.1": ("wamit", {"rho": 1000.0}),
    "wecsim/cylinder/cylinder_nemoh/RadiationCoefficients.tec": ("nemoh", {}),
    "wecsim/cylinder/cylinder_nemoh/Nemoh.cal": ("nemoh", {}),
    "wecsim/cylinder/cylinder_nemoh/cylinder_hydrodynamics.nc": ("netcdf", {}),
    "wecsim/cylinder_aqwa/cylinder.LIS": ("aqwa", {}),
    "wecsim/cylinder_aqwa/cylinder.AH1": ("aqwa", {}),
    "wecsim/cylinder_aqwa": ("aqwa", {}),
}


@pytest.mark.parametrize("relative", sorted(FILE_SETS))
def test_file_set_reads(shared_data, relative):
    expected, options = FILE_SETS[relative]
    name, _ = cummins.detect_format(shared_data / relative)
    assert name == expected
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # NEMOH's foreign IRF.tec is reported
        ds = cummins.read(shared_data / relative, **options)
    cummins.validate(ds)
    assert ds.sizes["omega"] >= 20
    source = {"netcdf": "capytaine", "wamit": ("wamit", "wamit-out")}.get(expected, expected)
    assert ds.attrs["source_format"] in source
    assert ds.attrs["history"]


def test_s175_multi_speed(shared_data):
    ds = cummins.read(shared_data / "mss" / "s175" / "s175.mat")
    assert ds.sizes["forward_speed"] == 5
    assert float(ds.forward_speed.max()) == pytest.approx(20 * 0.514444, rel=1e-4)  # 20 kn


def test_s175_raw_files_need_the_re7(shared_data):
    with pytest.raises(HydroDataError, match=r"\.re7"):
        cummins.read(shared_data / "mss" / "s175" / "input.re8")


@pytest.mark.parametrize(
    "folder", ["mss/tanker", "wecsim/sphere", "wecsim/cylinder/cylinder_nemoh"]
)
def test_folders_with_several_solvers_are_ambiguous(shared_data, folder):
    """These folders hold the same body from several solvers: the user must choose."""
    with pytest.raises(HydroDataError, match="several runs") as info:
        cummins.read(shared_data / folder)
    assert "format=" in str(info.value)


def test_folder_with_format_chosen(shared_data):
    ds = cummins.read(shared_data / "wecsim" / "sphere", format="netcdf")
    assert ds.attrs["source_format"] == "capytaine"


def test_unknown_format_name(shared_data):
    with pytest.raises(HydroDataError, match="unknown format"):
        cummins.read(shared_data / "mss" / "tanker" / "tanker.1", format="sesam")


def test_missing_path():
    with pytest.raises(HydroDataError, match="no such file"):
        cummins.read("/nonexistent/ship.1")


def test_file_of_another_kind(tmp_path, shared_data):
    png = tmp_path / "plot.nc"
    shutil.copy(shared_data / "mss" / "supply" / "input.hyd", png)
    with pytest.raises(HydroDataError):
        cummins.read(png, format="netcdf")
