"""Capytaine NetCDF variants of the corpus: versions 1.1-2.3, NetCDF-3 and -4, folders."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import xarray as xr

import cummins
from cummins import HydroDataError, HydroDataWarning
from cummins.io import detect_format
from cummins.io.netcdf import read_netcdf

OSWEC = "WEC-Sim/capytaine_OSWEC_flap"
COER = "WEC-Sim/capytaine_COER_comp"
RAFT = "RAFT/capytaine_integration_float/floatData.nc"


def test_case_folders_with_outputs_subfolder_read_as_the_run(corpus):
    for folder, stem in ((OSWEC, "oswec"), (COER, "coer_comp")):
        name, target = detect_format(corpus / folder)
        assert (
            name == "netcdf" and target == corpus / folder / "outputs" / f"{stem}_hydrodynamics.nc"
        )


def test_two_bodies_are_positional_with_the_file_names_kept(corpus):
    ds = cummins.read(corpus / OSWEC)
    assert list(ds.influenced_dof.values[:7]) == [
        "body1__Surge",
        "body1__Sway",
        "body1__Heave",
        "body1__Roll",
        "body1__Pitch",
        "body1__Yaw",
        "body2__Surge",
    ]
    assert cummins.hydrodb.body_names(ds) == ["oswec_flap", "oswec_base_shift"]
    raw = xr.load_dataset(corpus / OSWEC / "outputs" / "oswec_hydrodynamics.nc", engine="scipy")
    a = raw.added_mass.sel(
        radiating_dof="oswec_base_shift__Heave", influenced_dof="oswec_flap__Pitch"
    ).values
    np.testing.assert_array_equal(
        ds.added_mass.sel(influenced_dof="body1__Pitch", radiating_dof="body2__Heave").values,
        a[~np.isnan(a)],
    )


def test_legacy_exporter_files_agree_and_give_the_rotation_centre(corpus):
    """KH_0/KH_1.dat (7 significant digits) equal the .nc's stiffness blocks; with the
    CG of Hydrostatics_*.dat and the rigid-body inertia (no mass-moment coupling) the
    rotation centre is the CG, as main.py set it: (0, 0, -3.9) and (0, 0, -10.9) m."""
    ds = cummins.read(corpus / OSWEC)
    history = ds.attrs["history"]
    assert "hydrostatic_stiffness agrees with KH_0.dat, KH_1.dat" in history
    np.testing.assert_allclose(ds.attrs["reference_point"], [0, 0, -3.9, 0, 0, -10.9])
    np.testing.assert_allclose(ds.attrs["displaced_volume"], [297.3767, 48.708], rtol=1e-6)
    coer = cummins.read(corpus / COER)
    np.testing.assert_allclose(coer.attrs["reference_point"], [0, 0, -0.2])


def test_stiffness_from_kh_when_the_nc_has_none(corpus, tmp_path):
    raw = xr.load_dataset(corpus / COER / "outputs" / "coer_comp_hydrodynamics.nc", engine="scipy")
    target = tmp_path / "outputs"
    target.mkdir()
    raw.drop_vars("hydrostatic_stiffness").to_netcdf(target / "c.nc", engine="scipy")
    for name in ("KH.dat", "Hydrostatics.dat"):
        (target / name).write_bytes((corpus / COER / "outputs" / name).read_bytes())
    ds = cummins.read(tmp_path)
    full = cummins.read(corpus / COER)
    assert "hydrostatic_stiffness from KH.dat" in ds.attrs["history"]
    np.testing.assert_allclose(
        ds.hydrostatic_stiffness.values,
        full.hydrostatic_stiffness.values,
        rtol=1e-6,
        atol=1e-6 * 7.7e5,
    )


def test_capytaine_1_1_alphabetical_order_and_no_excitation_variable(corpus):
    raw = xr.load_dataset(corpus / RAFT, engine="scipy")
    assert list(raw.influenced_dof.values) == ["Heave", "Pitch", "Roll", "Surge", "Sway", "Yaw"]
    ds = cummins.read(corpus / RAFT)
    assert list(ds.influenced_dof.values) == list(cummins.hydrodb.DOF_NAMES)
    # axisymmetric float: surge = sway and roll = pitch once reordered (they were not
    # adjacent in the file), A15 = -A24
    a = ds.added_mass.values[0]
    assert a[0, 0] == pytest.approx(a[1, 1], rel=1e-6) and a[3, 3] == pytest.approx(
        a[4, 4], rel=1e-6
    )
    assert a[0, 4] == pytest.approx(-a[1, 3], rel=1e-3)
    np.testing.assert_array_equal(
        ds.added_mass.sel(influenced_dof="Heave", radiating_dof="Heave").values,
        raw.added_mass.sel(influenced_dof="Heave", radiating_dof="Heave").values,
    )
    fk = raw.Froude_Krylov_force.sel(complex="re") + 1j * raw.Froude_Krylov_force.sel(complex="im")
    dif = raw.diffraction_force.sel(complex="re") + 1j * raw.diffraction_force.sel(complex="im")
    total = np.conj(
        (fk + dif)
        .transpose("omega", "wave_direction", "influenced_dof")
        .sel(influenced_dof=list(cummins.hydrodb.DOF_NAMES))
        .values
    )
    np.testing.assert_array_equal(ds.excitation_force.values, total)
    assert "no excitation_force in the file" in ds.attrs["history"]
    assert "incoming_waves_convention = Nemoh" in ds.attrs["history"]


def test_netcdf4_copy_reads_like_the_netcdf3_file(corpus, tmp_path):
    """Capytaine >= 2 can write NetCDF-4 (h5netcdf): strings become HDF5 strings instead
    of NetCDF-3 char arrays; the data must read identically."""
    source = corpus / OSWEC / "outputs" / "oswec_hydrodynamics.nc"
    raw = xr.load_dataset(source, engine="scipy")
    nc4 = tmp_path / "oswec4.nc"
    raw.to_netcdf(nc4, engine="h5netcdf")
    assert nc4.read_bytes()[:4] == b"\x89HDF"
    a = read_netcdf(source, siblings=False)
    b = read_netcdf(nc4, siblings=False)
    for name in a.data_vars:
        np.testing.assert_array_equal(a[name].values, b[name].values)
    assert list(a.influenced_dof.values) == list(b.influenced_dof.values)


def test_custom_dof_names_are_kept(corpus, tmp_path):
    raw = xr.load_dataset(corpus / COER / "outputs" / "coer_comp_hydrodynamics.nc", engine="scipy")
    names = ["Surge", "Sway", "Heave", "Roll", "Flap", "Yaw"]
    renamed = raw.assign_coords(influenced_dof=names, radiating_dof=names)
    path = tmp_path / "flap.nc"
    renamed.to_netcdf(path, engine="scipy")
    ds = read_netcdf(path)
    assert list(ds.influenced_dof.values) == ["Surge", "Sway", "Heave", "Roll", "Yaw", "Flap"]
    assert "keep the file's names: Flap" in ds.attrs["history"]


@pytest.mark.parametrize("coordinate", ["wave_direction", "omega"])
def test_nan_coordinate_is_an_error_naming_it(corpus, tmp_path, coordinate):
    raw = xr.load_dataset(corpus / COER / "outputs" / "coer_comp_hydrodynamics.nc", engine="scipy")
    values = raw[coordinate].values.copy()
    values[3] = np.nan
    path = tmp_path / "nan.nc"
    raw.assign_coords({coordinate: values}).to_netcdf(path, engine="scipy")
    with pytest.raises(HydroDataError, match=coordinate):
        read_netcdf(path)


def test_nan_in_inertia_is_warned_and_named(corpus, tmp_path):
    raw = xr.load_dataset(corpus / COER / "outputs" / "coer_comp_hydrodynamics.nc", engine="scipy")
    raw["inertia_matrix"][2, 2] = np.nan
    path = tmp_path / "nan.nc"
    raw.to_netcdf(path, engine="scipy")
    with pytest.warns(HydroDataWarning, match=r"inertia_matrix has NaN at \[Heave, Heave\]"):
        ds = read_netcdf(path)
    assert "inertia_matrix" not in ds and "inertia_matrix" in ds.attrs["read_warnings"]


def test_the_corpus_files_read_without_damage_warnings(corpus):
    with warnings.catch_warnings():
        warnings.simplefilter("error", HydroDataWarning)
        for target in (corpus / OSWEC, corpus / COER, corpus / RAFT):
            assert "read_warnings" not in cummins.read(target).attrs
