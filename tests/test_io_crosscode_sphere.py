"""Cross-code acceptance: the WEC-Sim floating sphere from WAMIT and from Capytaine.

Two independent panel codes computed the same body (a sphere of radius 5 m, centre on
the free surface, 50 m water depth) on different meshes. After reading, both datasets
must agree to within what the meshes explain. Measured (WAMIT 7.2 vs Capytaine 2.3.1):
diagonal A and B within 2.9 % of their peak (median 0.9 %), largest at the
highest frequencies where the waves are shortest relative to the panels, and where WAMIT
removed the irregular frequencies (IRR=1) but Capytaine did not; excitation moduli
within 1.2 % of the peak, phases within 1° where the modulus is above 20 % of its peak;
hydrostatics within 1e-5. The tolerances below are about 1.5 × those numbers.

Conventions this proves:

* time: Capytaine's e^{-iωt} values are conjugated on read; without it the surge and
  pitch excitation phases differ from WAMIT's by about 160°;
* density: WAMIT's numbers are nondimensional and its .out does not record ρ, so the
  WAMIT run is scaled with the density of the Capytaine file (1000 kg/m³);
* reference point: WAMIT's moments are about the body origin (XBODY, YBODY, ZBODY) =
  (0, 0, −2), which the reader records as ``reference_point``. Capytaine 2 does not
  store its rotation centre; the data give it: a sphere rotating about its own centre
  radiates no waves, so pitch about (0, 0, z_c) radiates like surge with lever arm −z_c,
  A15 / A11 = −z_c = 2.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

import cummins
from cummins.io.netcdf import read_netcdf

#: Relative to the peak of the curve over the frequencies.
A_B_MAX_TOL = 0.04
A_B_MEDIAN_TOL = 0.015
EXCITATION_MODULUS_TOL = 0.02
EXCITATION_PHASE_TOL_DEG = 2.0
HYDROSTATICS_TOL = 1e-5
#: DOFs with hydrodynamic content for a sphere (yaw of a sphere is zero up to noise).
DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch")
SPHERE_RADIUS = 5.0


@pytest.fixture(scope="module")
def capytaine_raw(shared_data):
    return read_netcdf(shared_data / "wecsim" / "sphere" / "sphere_hydrodynamics.nc")


@pytest.fixture(scope="module")
def capytaine(shared_data):
    return read_netcdf(
        shared_data / "wecsim" / "sphere" / "sphere_hydrodynamics.nc",
        reference_point=(0.0, 0.0, -2.0),
    )


@pytest.fixture(scope="module")
def wamit(shared_data, capytaine):
    ds = cummins.read(shared_data / "wecsim" / "sphere" / "sphere.1", rho=capytaine.attrs["rho"])
    # WAMIT prints periods to 4 decimals: match the frequencies to 1e-4 relative.
    index = [int(np.argmin(np.abs(ds.omega.values - w))) for w in capytaine.omega.values]
    matched = ds.isel(omega=index)
    np.testing.assert_allclose(matched.omega.values, capytaine.omega.values, rtol=1e-4)
    return matched.assign_coords(omega=capytaine.omega.values)


def _diag(ds: xr.Dataset, name: str, dof: str) -> np.ndarray:
    return ds[name].sel(influenced_dof=dof, radiating_dof=dof).values


def _compare_radiation(a: xr.Dataset, b: xr.Dataset, dofs) -> None:
    for dof in dofs:
        for name in ("added_mass", "radiation_damping"):
            x, ref = _diag(a, name, dof), _diag(b, name, dof)
            error = np.abs(x - ref) / np.abs(ref).max()
            assert error.max() < A_B_MAX_TOL, (name, dof, error.max())
            assert np.median(error) < A_B_MEDIAN_TOL, (name, dof, np.median(error))


def _compare_excitation(a: xr.Dataset, b: xr.Dataset, dofs) -> None:
    for dof in dofs:
        x = a.excitation_force.sel(influenced_dof=dof).isel(wave_direction=0).values
        ref = b.excitation_force.sel(influenced_dof=dof).isel(wave_direction=0).values
        peak = np.abs(ref).max()
        assert np.abs(np.abs(x) - np.abs(ref)).max() < EXCITATION_MODULUS_TOL * peak, dof
        big = np.abs(ref) > 0.2 * peak
        phase = np.degrees(np.abs(np.angle(x[big] / ref[big])))
        assert phase.max() < EXCITATION_PHASE_TOL_DEG, (dof, phase.max())


def test_setup_is_the_same_body_and_sea(capytaine, wamit):
    assert capytaine.attrs["rho"] == wamit.attrs["rho"] == 1000.0
    assert capytaine.attrs["g"] == wamit.attrs["g"] == 9.81
    assert capytaine.attrs["water_depth"] == wamit.attrs["water_depth"] == 50.0
    np.testing.assert_array_equal(wamit.attrs["reference_point"], [0.0, 0.0, -2.0])
    np.testing.assert_array_equal(capytaine.wave_direction, wamit.wave_direction)
    assert capytaine.sizes["omega"] == 417  # 420 in the file, 3 unsolved by Capytaine


def test_capytaines_rotation_centre_from_the_data(capytaine_raw, wamit):
    """A15 / A11 = −z_c for a sphere centred on the free surface: z_c = −2 m in both codes."""
    for ds in (capytaine_raw, wamit):
        a11 = ds.added_mass.sel(influenced_dof="Surge", radiating_dof="Surge")
        a15 = ds.added_mass.sel(influenced_dof="Surge", radiating_dof="Pitch")
        b11 = ds.radiation_damping.sel(influenced_dof="Surge", radiating_dof="Surge")
        b15 = ds.radiation_damping.sel(influenced_dof="Surge", radiating_dof="Pitch")
        np.testing.assert_allclose(-(a15 / a11), -2.0, rtol=1e-3)
        large = b11 > 0.01 * b11.max()
        np.testing.assert_allclose(-(b15 / b11)[large], -2.0, rtol=1e-3)
    # A file without a rotation centre is read about the origin, and says so.
    assert "assumed at the origin" in capytaine_raw.attrs["history"]


def test_radiation_agrees_about_the_common_body_origin(capytaine, wamit):
    _compare_radiation(capytaine, wamit, DOFS)


def test_radiation_agrees_about_another_point(capytaine, wamit):
    """Move both to a point off the axis: now yaw has added mass too (A11 y² + A22 x²)."""
    point = (1.0, 0.5, -5.0)
    c = cummins.move_reference_point(capytaine, point)
    w = cummins.move_reference_point(wamit, point)
    _compare_radiation(c, w, (*DOFS, "Yaw"))
    _compare_excitation(c, w, ("Surge", "Heave", "Roll", "Pitch", "Yaw"))


def test_excitation_modulus_and_phase_agree(capytaine, wamit):
    _compare_excitation(capytaine, wamit, ("Surge", "Heave", "Pitch"))


def test_without_conjugation_the_phases_disagree(capytaine, wamit):
    """The check above is not vacuous: Capytaine's raw e^{-iωt} numbers are far off."""
    for dof in ("Surge", "Pitch"):
        x = np.conj(
            capytaine.excitation_force.sel(influenced_dof=dof).isel(wave_direction=0).values
        )
        ref = wamit.excitation_force.sel(influenced_dof=dof).isel(wave_direction=0).values
        big = np.abs(ref) > 0.2 * np.abs(ref).max()
        assert np.median(np.degrees(np.abs(np.angle(x[big] / ref[big])))) > 90.0


def test_hydrostatics_agree(capytaine, wamit):
    c, w = capytaine.hydrostatic_stiffness.values, wamit.hydrostatic_stiffness.values
    for k in (2, 3, 4):  # heave, roll, pitch
        assert c[k, k] == pytest.approx(w[k, k], rel=HYDROSTATICS_TOL)
    # and both match the waterplane of a sphere of radius 5 m: C33 = ρ g π R²
    rho_g = capytaine.attrs["rho"] * capytaine.attrs["g"]
    assert c[2, 2] == pytest.approx(rho_g * np.pi * SPHERE_RADIUS**2, rel=2e-3)
