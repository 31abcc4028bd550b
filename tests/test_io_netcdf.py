"""Capytaine NetCDF reader and cummins' NetCDF writer (same layout, round trips)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

import cummins
from cummins import HydroDataError, OutputExistsError
from cummins.hydrodb import dof_labels, make_hydrodb, stack_forward_speeds
from cummins.io import detect_format
from cummins.io.netcdf import (
    JSON_ATTRS,
    VERSION_ATTR,
    read_netcdf,
    sniff,
    sniff_dir,
    write_netcdf,
)

SPHERE_CENTRE_OF_ROTATION = (0.0, 0.0, -2.0)


@pytest.fixture(scope="module")
def sphere_nc(shared_data):
    return shared_data / "wecsim" / "sphere" / "sphere_hydrodynamics.nc"


@pytest.fixture(scope="module")
def cylinder_nc(shared_data):
    return shared_data / "wecsim" / "cylinder" / "cylinder_nemoh" / "cylinder_hydrodynamics.nc"


@pytest.fixture(scope="module")
def sphere_raw(sphere_nc):
    """The file as plain xarray sees it (Capytaine 2.3.1 layout, NetCDF-3)."""
    return xr.load_dataset(sphere_nc, engine="scipy")


@pytest.fixture(scope="module")
def sphere(sphere_nc):
    return read_netcdf(sphere_nc, reference_point=SPHERE_CENTRE_OF_ROTATION)


def _complex(raw: xr.Dataset, name: str) -> xr.DataArray:
    return raw[name].sel(complex="re") + 1j * raw[name].sel(complex="im")


# --------------------------------------------------------------------------- detection


def test_sniff_recognises_capytaine_files(sphere_nc, cylinder_nc, shared_data, tmp_path):
    assert sniff(sphere_nc)
    assert sniff(cylinder_nc)
    assert not sniff(shared_data / "wecsim" / "sphere" / "sphere.1")
    # An HDF5/NetCDF-4 file that is not a hydrodynamic database is not ours.
    other = tmp_path / "other.nc"
    xr.Dataset({"temperature": ("x", [1.0, 2.0])}).to_netcdf(other, engine="h5netcdf")
    assert not sniff(other)
    assert detect_format(sphere_nc) == ("netcdf", sphere_nc)
    assert sniff_dir(sphere_nc.parent) == [sphere_nc]
    assert sniff_dir(tmp_path) == []


def test_read_dispatches_through_the_registry(sphere_nc, sphere):
    ds = cummins.read(sphere_nc, reference_point=SPHERE_CENTRE_OF_ROTATION)
    xr.testing.assert_identical(ds, sphere)


# --------------------------------------------------------------------------- values


def test_values_are_the_files_conjugated_and_transposed(sphere, sphere_raw):
    """A, B as stored (dims matched by name); complex values conjugated (e^{-iωt} → e^{+iωt})."""
    raw = sphere_raw.sel(omega=sphere.omega.values)
    a = raw.added_mass.transpose("omega", "influenced_dof", "radiating_dof").values
    np.testing.assert_array_equal(sphere.added_mass.values, a)
    b = raw.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").values
    np.testing.assert_array_equal(sphere.radiation_damping.values, b)
    for name in ("excitation_force", "Froude_Krylov_force", "diffraction_force"):
        x = _complex(raw, name).transpose("omega", "wave_direction", "influenced_dof").values
        np.testing.assert_array_equal(sphere[name].values, np.conj(x), err_msg=name)
    np.testing.assert_array_equal(
        sphere.hydrostatic_stiffness.values, sphere_raw.hydrostatic_stiffness.values
    )
    np.testing.assert_array_equal(sphere.inertia_matrix.values, sphere_raw.inertia_matrix.values)
    # Excitation = Froude-Krylov + diffraction, as Capytaine defines it.
    np.testing.assert_allclose(
        sphere.excitation_force,
        sphere.Froude_Krylov_force + sphere.diffraction_force,
        rtol=1e-12,
        atol=1e-9,
    )


def test_constants_and_metadata(sphere, sphere_raw):
    assert sphere.attrs["rho"] == float(sphere_raw.rho) == 1000.0
    assert sphere.attrs["g"] == 9.81
    assert sphere.attrs["water_depth"] == 50.0
    assert float(sphere.forward_speed) == 0.0
    assert sphere.attrs["source_format"] == "capytaine"
    assert sphere.attrs["capytaine_version"] == "2.3.1"
    assert sphere.attrs["body_name"] == "floating_sphere"
    assert sphere.attrs["time_convention"] == "x(t) = Re{X exp(i omega t)}"
    np.testing.assert_array_equal(sphere.attrs["reference_point"], SPHERE_CENTRE_OF_ROTATION)
    assert "conjugated" in sphere.attrs["history"]
    assert list(sphere.influenced_dof.values) == list(cummins.DOF_NAMES)


def test_unsolved_frequencies_are_dropped_and_recorded(sphere, sphere_raw, cylinder_nc):
    """Capytaine 2.3 could not solve ω ≤ 0.06 rad/s at 50 m depth (kh < 0.1): NaN in the file."""
    unsolved = np.isnan(sphere_raw.added_mass).all(("radiating_dof", "influenced_dof"))
    np.testing.assert_allclose(sphere_raw.omega.values[unsolved.values], [0.02, 0.04, 0.06])
    expected = sphere_raw.omega.values[~unsolved.values]
    np.testing.assert_array_equal(sphere.omega.values, expected)
    assert "3 frequencies dropped" in sphere.attrs["history"]
    assert "0.02, 0.04, 0.06 rad/s" in sphere.attrs["history"]
    cylinder = read_netcdf(cylinder_nc)
    assert cylinder.sizes["omega"] == 524
    assert "1 frequency dropped" in cylinder.attrs["history"]
    assert "rotation centre: assumed at the origin" in cylinder.attrs["history"]
    np.testing.assert_array_equal(cylinder.attrs["reference_point"], [0.0, 0.0, 0.0])


def test_rho_may_only_confirm_the_file(sphere_nc):
    assert read_netcdf(sphere_nc, rho=1000.0).attrs["rho"] == 1000.0
    with pytest.raises(HydroDataError, match=r"rho = 1025 .* records 1000"):
        read_netcdf(sphere_nc, rho=1025.0)
    with pytest.raises(HydroDataError, match="forward_speed = 3 m/s was given"):
        read_netcdf(sphere_nc, forward_speed=3.0)


def test_layouts_of_capytaine_2_and_3_give_the_same_dataset(sphere_raw, sphere, tmp_path):
    """Capytaine 3 orders A as (omega, influenced, radiating), uses NetCDF-4 and records the
    rotation centre; the result must not depend on any of that."""
    raw3 = sphere_raw.transpose("complex", "omega", "influenced_dof", "radiating_dof", ...)
    raw3 = raw3.assign_coords(
        rotation_center=("space_coordinate", list(SPHERE_CENTRE_OF_ROTATION)),
        space_coordinate=("space_coordinate", ["x", "y", "z"]),
    )
    path = tmp_path / "capytaine3.nc"
    raw3.to_netcdf(path, engine="h5netcdf")
    ds = read_netcdf(path)
    for name in sphere.data_vars:
        np.testing.assert_array_equal(ds[name].values, sphere[name].values, err_msg=name)
    np.testing.assert_array_equal(ds.attrs["reference_point"], SPHERE_CENTRE_OF_ROTATION)
    assert "rotation_center" in ds.attrs["history"]
    with pytest.raises(HydroDataError, match="records the rotation centre"):
        read_netcdf(path, reference_point=(0.0, 0.0, 0.0))


def test_zero_and_infinite_frequency_rows(sphere_raw, tmp_path):
    """Capytaine ≥ 2 stores ω = 0 and ω = ∞ as rows of the frequency grid (damping 0,
    diffraction NaN): they must become added_mass_zero / added_mass_inf."""
    finite = sphere_raw.isel(omega=slice(3, None))  # drop the unsolved rows
    low, high = finite.isel(omega=[0]), finite.isel(omega=[-1])
    a0 = low.added_mass.values[0] * 1.5  # recognisable values for the limit rows
    a_inf = high.added_mass.values[0] * 0.5
    limits = xr.concat(
        [low, high], dim="omega", data_vars="minimal", coords="minimal", compat="override"
    ).assign_coords(omega=[0.0, np.inf])
    limits["added_mass"].values[:] = np.stack([a0, a_inf])
    limits["radiation_damping"].values[:] = 0.0
    for name in ("excitation_force", "Froude_Krylov_force", "diffraction_force"):
        limits[name].values[:] = np.nan
    path = tmp_path / "limits.nc"
    xr.concat(
        [limits.isel(omega=[0]), finite, limits.isel(omega=[1])],
        dim="omega",
        data_vars="minimal",
        coords="minimal",
        compat="override",
    ).to_netcdf(path, engine="h5netcdf")
    ds = read_netcdf(path)
    # a0 is stored (omega, radiating, influenced): transpose to (influenced, radiating)
    np.testing.assert_array_equal(ds.added_mass_zero.values, a0.T)
    np.testing.assert_array_equal(ds.added_mass_inf.values, a_inf.T)
    np.testing.assert_array_equal(ds.omega.values, finite.omega.values)
    assert "added_mass_zero" in ds.attrs["history"]


# --------------------------------------------------------------------------- writer


def test_tanker_round_trip_is_exact(tmp_path):
    ds = cummins.demo_dataset()
    path = write_netcdf(ds, tmp_path / "tanker.nc")
    back = read_netcdf(path)
    xr.testing.assert_identical(back, ds)
    assert back.attrs["history"] == ds.attrs["history"]  # multi-line string survives
    assert "\n" in back.attrs["history"]


def test_sphere_round_trip_is_exact(sphere, tmp_path):
    back = read_netcdf(write_netcdf(sphere, tmp_path / "sphere.nc"))
    xr.testing.assert_identical(back, sphere)


def test_written_file_has_capytaines_layout_and_conventions(tmp_path):
    ds = cummins.demo_dataset()
    path = write_netcdf(ds, tmp_path / "tanker.nc")
    raw = xr.load_dataset(path, engine="h5netcdf")
    assert list(raw["complex"].values) == ["re", "im"]
    assert raw.excitation_force.dims == ("complex", "omega", "wave_direction", "influenced_dof")
    # Stored in Capytaine's e^{-iωt}: the conjugate of cummins' values.
    np.testing.assert_array_equal(raw.excitation_force.sel(complex="re"), ds.excitation_force.real)
    np.testing.assert_array_equal(raw.excitation_force.sel(complex="im"), -ds.excitation_force.imag)
    for name in ("rho", "g", "water_depth"):
        assert raw[name].dims == () and name in raw.coords
        assert name not in raw.attrs
    assert float(raw.rho) == 1025.0 and float(raw.water_depth) == np.inf
    np.testing.assert_array_equal(raw.rotation_center, ds.attrs["reference_point"])
    assert raw.attrs[VERSION_ATTR] == cummins.__version__
    assert "exp(-i omega t)" in raw.attrs["time_convention"]
    for name in ("added_mass_inf", "added_mass_zero", "additional_damping"):
        np.testing.assert_array_equal(raw[name].values, ds[name].values)


def test_capytaine_merges_our_complex_values(tmp_path):
    cpt_xarray = pytest.importorskip("capytaine.io.xarray")
    ds = cummins.demo_dataset()
    path = write_netcdf(ds, tmp_path / "tanker.nc")
    merged = cpt_xarray.merge_complex_values(xr.open_dataset(path, engine="h5netcdf"))
    np.testing.assert_array_equal(
        merged.excitation_force.values, np.conj(ds.excitation_force.values)
    )


def test_multi_speed_round_trip(tmp_path):
    base = cummins.demo_dataset()
    speeds = []
    for k, u in enumerate((0.0, 2.5, 5.0)):
        one = base.copy(deep=True)
        one["added_mass"] = one.added_mass * (1 + 0.1 * k)
        one["excitation_force"] = one.excitation_force * np.exp(0.2j * k)
        speeds.append(one.assign_coords(forward_speed=u))
    ds = stack_forward_speeds(speeds)
    assert ds.sizes["forward_speed"] == 3
    path = write_netcdf(ds, tmp_path / "speeds.nc")
    xr.testing.assert_identical(read_netcdf(path), ds)
    one = read_netcdf(path, forward_speed=2.5)
    np.testing.assert_array_equal(one.added_mass.values, speeds[1].added_mass.values)
    np.testing.assert_array_equal(one.excitation_force.values, speeds[1].excitation_force.values)
    with pytest.raises(HydroDataError, match="no forward speed 1 m/s"):
        read_netcdf(path, forward_speed=1.0)


def test_two_bodies_and_awkward_attributes_round_trip(tmp_path):
    tanker = cummins.demo_dataset()
    n = tanker.sizes["omega"]

    def two(a):
        out = np.zeros((*a.shape[:-2], 12, 12), dtype=a.dtype)
        out[..., :6, :6] = a
        out[..., 6:, 6:] = 2 * a
        return out

    x = tanker.excitation_force.values
    ds = make_hydrodb(
        tanker.omega.values,
        two(tanker.added_mass.values),
        two(tanker.radiation_damping.values),
        rho=1025.0,
        g=9.81,
        source_format="test",
        dofs=dof_labels(["buoy", "float"]),
        wave_direction=tanker.wave_direction.values,
        excitation_force=np.concatenate([x, -x], axis=-1),
        rao=np.concatenate([x, x], axis=-1) * 1e-8,
        drift_force=np.abs(np.concatenate([x, x], axis=-1)) * 1e-3,
        added_mass_inf=two(tanker.added_mass_inf.values),
        history=["line one", "line two: ü, ω"],
        flag=True,
        nothing_else=[1, 2.5, "three"],
        settings={"panels": 400, "method": "indirect", "tol": 1e-6},
        one_element=np.array([4.0]),
        matrix=np.arange(6.0).reshape(2, 3),
        gain=1 + 2j,
    )
    ds.attrs["optional"] = None
    # one reference point per body, as move_reference_point stores them
    ds.attrs["reference_point"] = np.array([0.0, 0.0, -1.0, 10.0, 0.0, -2.0])
    assert ds.sizes["influenced_dof"] == 12 and ds.sizes["omega"] == n
    path = write_netcdf(ds, tmp_path / "two.nc")
    raw = xr.load_dataset(path, engine="h5netcdf")
    assert JSON_ATTRS in raw.attrs  # None, bool, dict, list, 2-D array need the JSON side channel
    assert raw.rotation_center.dims == ("body", "space_coordinate")
    back = read_netcdf(path)
    xr.testing.assert_identical(back, ds)
    assert back.attrs["flag"] is True and back.attrs["optional"] is None
    assert back.attrs["settings"] == {"panels": 400, "method": "indirect", "tol": 1e-6}
    assert back.attrs["matrix"].shape == (2, 3) and back.attrs["one_element"].shape == (1,)
    assert back.attrs["gain"] == 1 + 2j


def test_variables_unknown_to_the_reader_survive_a_round_trip(tmp_path):
    ds = cummins.demo_dataset()
    ds["viscous_roll_damping"] = ds.radiation_damping.isel(influenced_dof=3, radiating_dof=3) * 0.1
    ds["wave_drift_damping"] = ds.excitation_force * 1e-3j
    ds["viscous_roll_damping"].attrs["units"] = "kg m^2/s"
    back = read_netcdf(write_netcdf(ds, tmp_path / "extra.nc"))
    xr.testing.assert_identical(back, ds)


def test_write_refuses_to_overwrite(tmp_path):
    ds = cummins.demo_dataset()
    path = tmp_path / "tanker.nc"
    cummins.write(ds, path)
    with pytest.raises(OutputExistsError):
        cummins.write(ds, path)
    cummins.write(ds, path, force=True)
    assert not list(tmp_path.glob(".*.tmp"))


def test_unstorable_attribute_is_refused(tmp_path):
    ds = cummins.demo_dataset()
    ds.attrs["callback"] = object()
    with pytest.raises(HydroDataError, match="attribute 'callback'"):
        write_netcdf(ds, tmp_path / "x.nc")
    assert not (tmp_path / "x.nc").exists()


# --------------------------------------------------------------------------- bad input


def test_damaged_and_foreign_files(sphere_nc, tmp_path):
    data = sphere_nc.read_bytes()
    cases = {
        "empty.nc": b"",
        "text.nc": b"this is not NetCDF\n",
        "truncated.nc": data[: len(data) // 3],
        "header_only.nc": data[:200],
        "cdf5.nc": b"CDF\x05" + data[4:],
    }
    for name, content in cases.items():
        path = tmp_path / name
        path.write_bytes(content)
        with pytest.raises(HydroDataError) as info:
            read_netcdf(path)
        assert name in str(info.value), name
    with pytest.raises(HydroDataError, match="file not found"):
        read_netcdf(tmp_path / "missing.nc")


def test_not_a_hydrodynamic_database(tmp_path, sphere_raw):
    path = tmp_path / "hydrostatics_only.nc"
    sphere_raw[["hydrostatic_stiffness", "inertia_matrix"]].to_netcdf(path, engine="h5netcdf")
    with pytest.raises(HydroDataError, match="no 'added_mass' variable"):
        read_netcdf(path)


def test_several_densities_are_refused(tmp_path, sphere_raw):
    two = xr.concat(
        [sphere_raw, sphere_raw], dim="rho", data_vars="all", coords="minimal", compat="override"
    ).assign_coords(rho=[1000.0, 1025.0])
    path = tmp_path / "two_rho.nc"
    two.to_netcdf(path, engine="h5netcdf")
    with pytest.raises(HydroDataError, match="dimension 'rho' with 2 values"):
        read_netcdf(path)


def test_bad_complex_labels(tmp_path, sphere_raw):
    path = tmp_path / "complex.nc"
    sphere_raw.assign_coords(complex=["a", "b"]).to_netcdf(path, engine="h5netcdf")
    with pytest.raises(HydroDataError, match="'re' and 'im'"):
        read_netcdf(path)


def test_fuzzed_files_give_a_dataset_or_hydrodataerror(sphere_nc, cylinder_nc, tmp_path):
    """Random truncations, deleted byte ranges and garbled bytes of the real files."""
    rng = np.random.default_rng(20240611)
    ours = write_netcdf(cummins.demo_dataset(), tmp_path / "tanker.nc")  # NetCDF-4 / HDF5
    for source in (sphere_nc, cylinder_nc, ours):
        data = source.read_bytes()
        for k in range(25):
            kind = 0 if source == ours else k % 3
            a = int(rng.integers(0, len(data)))
            b = min(len(data), a + int(rng.integers(1, 2000)))
            if kind == 0:
                mutated = data[:a]
            elif kind == 1:
                mutated = data[:a] + data[b:]
            else:
                noise = rng.integers(0, 256, size=b - a, dtype=np.uint8).tobytes()
                mutated = data[:a] + noise + data[b:]
            path = tmp_path / f"fuzz{k}.nc"
            path.write_bytes(mutated)
            try:
                ds = read_netcdf(path)
            except HydroDataError:
                continue
            cummins.validate(ds)
