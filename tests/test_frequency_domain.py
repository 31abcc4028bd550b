"""Motion RAOs, response spectra and significant amplitudes."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

import cummins
from cummins.errors import HydroDataError
from cummins.plots import plot_rao
from cummins.seakeeping.excitation import excitation_transfer, wave_response
from cummins.seakeeping.frequency_domain import (
    impedance,
    load_rao,
    motion_rao,
    motion_transfer,
    response_spectrum,
    save_rao,
    significant_amplitude,
    spectral_moment,
)
from cummins.seakeeping.waves import irregular_waves, spreading_weights, wave_spectrum


@pytest.fixture(scope="module")
def tanker(shared_data):
    return cummins.read(shared_data / "mss" / "tanker" / "tanker.1")


@pytest.fixture(scope="module")
def tanker_rao(tanker):
    return motion_rao(tanker)


def relative_errors(x: np.ndarray, ref: np.ndarray) -> list[float]:
    """max |x − ref| / max |ref| per DOF (last axis)."""
    return [
        float(np.abs(x[..., d] - ref[..., d]).max() / np.abs(ref[..., d]).max())
        for d in range(ref.shape[-1])
    ]


def test_tanker_rao_matches_mss_motion_rao(shared_data, tanker_rao):
    """MSS's tanker.mat holds WAMIT's own RAOs (its .4 file, with the .frc external
    damping); our coupled solution from the .1/.3/.hst/.frc data agrees to < 1 % of each
    DOF's largest RAO (0.2 % heave, 0.8 % surge at the lowest frequency, where surge has
    no restoring)."""
    mss = cummins.change_axes(cummins.read(shared_data / "mss" / "tanker" / "tanker.mat"), "z-up")
    ref = mss.rao.sel(wave_direction=tanker_rao.wave_direction.values, method="nearest")
    errors = relative_errors(
        tanker_rao.values, ref.transpose("omega", "wave_direction", "radiating_dof").values
    )
    assert max(errors) < 0.01, errors
    assert errors[2] < 0.003  # heave
    # all 36 headings of MSS, the 190…350° ones from the mirrored excitation
    full = motion_rao(
        cummins.read(shared_data / "mss" / "tanker" / "tanker.1"), None, mss.wave_direction.values
    )
    errors = relative_errors(
        full.values, mss.rao.transpose("omega", "wave_direction", "radiating_dof").values
    )
    assert max(errors) < 0.01, errors


def test_tanker_rao_matches_wamit_out(shared_data, tanker_rao):
    """The WAMIT log prints its RAOs with phases in whole degrees (±0.9 % error)."""
    out = cummins.read(shared_data / "mss" / "tanker" / "tanker.out", format="wamit-out")
    errors = relative_errors(
        tanker_rao.values, out.rao.transpose("omega", "wave_direction", "radiating_dof").values
    )
    assert max(errors) < 0.02, errors


def test_supply_rao_matches_veres(shared_data):
    """VERES's own RAOs (input.re1); roll differs by its linearised roll damping."""
    ds = cummins.read(shared_data / "mss" / "supply" / "input.re7")
    rao = motion_rao(ds)
    errors = relative_errors(rao.values, ds.rao.transpose(..., "radiating_dof").values)
    assert errors[0] < 1e-3 and errors[2] < 1e-4 and errors[4] < 1e-4  # surge, heave, pitch
    assert errors[1] < 0.01 and errors[5] < 0.02 and errors[3] < 0.1  # sway, yaw, roll


def test_rao_solves_the_equation_of_motion(tanker, tanker_rao):
    """At the data frequencies the RAO satisfies the equation of motion written out here
    from the dataset's arrays (not through the module's impedance); between them it
    satisfies the module's interpolated impedance, by both solution paths."""
    from cummins.hydrodb import dof_matrix

    w = tanker_rao.omega.values
    assert np.array_equal(w, tanker.omega.values)
    m, c = dof_matrix(tanker, "inertia_matrix"), dof_matrix(tanker, "hydrostatic_stiffness")
    a, b = dof_matrix(tanker, "added_mass"), dof_matrix(tanker, "radiation_damping")
    b = b + dof_matrix(tanker, "additional_damping")  # the .frc's external damping
    for name in ("additional_stiffness", "additional_added_mass"):
        assert name not in tanker  # the WAMIT tanker has none: nothing left out below
    wc = w[:, None, None]
    z = -(wc**2) * (m + a) + 1j * wc * b + c
    f = tanker.excitation_force.transpose("omega", "wave_direction", "influenced_dof").values
    residual = np.einsum("wij,wbj->wbi", z, tanker_rao.values) - f
    assert np.abs(residual).max() < 1e-9 * np.abs(f).max()
    # between the data frequencies and headings too
    w = np.linspace(0.3, 1.2, 37)
    beta = np.radians([15.0, 125.0, 305.0])
    rao = motion_rao(tanker, w, beta, viscous_damping={"Roll": 3e9})
    z = impedance(tanker, w, viscous_damping={"Roll": 3e9})
    ww, bb = np.meshgrid(w, beta, indexing="ij")
    f = excitation_transfer(tanker, ww.ravel(), bb.ravel()).reshape(w.size, 3, 6)
    residual = np.einsum("wij,wbj->wbi", z, rao.values) - f
    assert np.abs(residual).max() < 1e-9 * np.abs(f).max()
    pairs = motion_transfer(tanker, ww.ravel(), bb.ravel(), viscous_damping={"Roll": 3e9})
    np.testing.assert_allclose(pairs.reshape(rao.shape), rao.values, rtol=1e-12, atol=1e-15)


def test_long_waves_heave_follows_the_surface(tanker, tanker_rao, shared_data):
    """ω → 0: a free-floating body rides the wave: heave RAO → 1, in phase."""
    heave = tanker_rao.sel(dof="Heave").isel(omega=0).values
    np.testing.assert_allclose(np.abs(heave), 1.0, atol=1e-3)
    np.testing.assert_allclose(np.angle(heave), 0.0, atol=np.radians(0.1))
    sphere = cummins.read(shared_data / "wecsim" / "sphere" / "sphere_hydrodynamics.nc")
    rao = motion_rao(sphere)
    assert abs(rao.sel(dof="Heave").values[0, 0]) == pytest.approx(1.0, abs=0.01)
    # Long waves along +x: surge is the orbital displacement, a quarter period behind
    # the elevation; along y (90°) the same holds for sway.
    bare = motion_rao(tanker, tanker.omega.values[:1], [0.0, np.pi / 2], additional=False)
    surge = bare.sel(dof="Surge").values[0, 0]  # (without the .frc surge damping)
    sway = bare.sel(dof="Sway").values[0, 1]
    assert np.degrees(np.angle(surge)) == pytest.approx(-90.0, abs=1.0)
    assert np.degrees(np.angle(sway)) == pytest.approx(-90.0, abs=1.0)
    # head and following seas excite no antisymmetric motion
    for dof in ("Sway", "Roll", "Yaw"):
        assert np.abs(tanker_rao.sel(dof=dof).isel(wave_direction=[0, -1])).max() < 1e-6


def one_dof_database(step: float) -> tuple[xr.Dataset, callable]:
    """A lightly damped heave oscillator (ζ ≈ 0.5 %, resonance at 0.7 rad/s) whose A, B
    and F are low-order polynomials in ω, on a grid of the given step."""
    w = np.arange(0.2, 1.6 + step / 2, step) + 0.021  # the resonance between two points
    mass, stiffness = 1e6, 0.49 * 1.27e6

    def a(x):
        return 2e5 + 1e5 * x

    def b(x):
        return 2e4 * x**2

    def f(x):
        return 1e6 * (1 - 0.2 * x) + 0j

    def exact(x):
        return f(x) / (-(x**2) * (mass + a(x)) + 1j * x * b(x) + stiffness)

    ds = cummins.make_hydrodb(
        w,
        a(w)[:, None, None],
        b(w)[:, None, None],
        rho=1025.0,
        g=9.81,
        source_format="synthetic",
        dofs=["Heave"],
        wave_direction=[np.pi],
        excitation_force=f(w)[:, None, None],
        inertia_matrix=[[mass]],
        hydrostatic_stiffness=[[stiffness]],
    )
    return ds, exact


def test_sharp_resonance_is_solved_not_interpolated():
    """de Haan (2022) §3.1.2: a peaked RAO sampled every 0.05 rad/s cannot be interpolated —
    neither in the complex plane nor as amplitude and phase. cummins solves the equation
    at the new frequencies with interpolated A, B and F (smooth), and gets it right."""
    ds, exact = one_dof_database(0.05)
    fine = np.linspace(0.25, 1.55, 5001)
    coarse = motion_rao(ds).values[:, 0, 0]
    np.testing.assert_allclose(coarse, exact(ds.omega.values), rtol=1e-12)
    solved = motion_rao(ds, fine).values[:, 0, 0]
    truth = exact(fine)
    assert np.abs(solved - truth).max() < 1e-9 * np.abs(truth).max()
    w = ds.omega.values
    complex_plane = np.interp(fine, w, coarse.real) + 1j * np.interp(fine, w, coarse.imag)
    amp_phase = np.interp(fine, w, np.abs(coarse)) * np.exp(
        1j * np.interp(fine, w, np.unwrap(np.angle(coarse)))
    )
    for interpolated in (complex_plane, amp_phase):
        assert np.abs(interpolated - truth).max() > 0.5 * np.abs(truth).max()
    # the resonance falls between two data points, where the phase turns by ~180°
    peak = fine[np.argmax(np.abs(truth))]
    k = np.searchsorted(w, peak)
    turn = np.degrees(np.angle(coarse[k] / coarse[k - 1]))
    assert abs(turn) > 120


def test_viscous_damping(tanker, tanker_rao):
    labels = list(tanker_rao.dof.values)
    matrix = np.zeros((6, 6))
    matrix[3, 3] = 5e9
    by_dict = motion_rao(tanker, viscous_damping={"Roll": 5e9})
    by_matrix = motion_rao(tanker, viscous_damping=matrix)
    by_array = motion_rao(
        tanker,
        viscous_damping=xr.DataArray(
            matrix,
            dims=("influenced_dof", "radiating_dof"),
            coords={"influenced_dof": labels, "radiating_dof": labels},
        ),
    )
    np.testing.assert_array_equal(by_dict.values, by_matrix.values)
    np.testing.assert_array_equal(by_dict.values, by_array.values)
    roll = np.abs(tanker_rao.sel(dof="Roll")).max()
    damped = np.abs(by_dict.sel(dof="Roll")).max()
    assert damped < 0.8 * roll
    assert "viscous_damping" in by_dict.attrs["terms"]
    without = motion_rao(tanker, additional=False)
    assert "additional_damping" not in without.attrs["terms"]
    assert np.abs(without.sel(dof="Roll")).max() > roll  # the .frc roll damping removed
    with pytest.raises(HydroDataError, match="'Rol'"):
        motion_rao(tanker, viscous_damping={"Rol": 1.0})
    with pytest.raises(HydroDataError, match="shape"):
        motion_rao(tanker, viscous_damping=np.eye(3))


def test_errors(shared_data, tanker):
    sphere = cummins.read(shared_data / "wecsim" / "sphere" / "sphere.1", rho=1000.0)
    with pytest.raises(HydroDataError, match="no 'inertia_matrix'"):
        motion_rao(sphere)
    with pytest.raises(HydroDataError, match=r"frequency 8 rad/s is outside"):
        motion_rao(tanker, [1.0, 8.0])
    with pytest.raises(HydroDataError, match="no 'hydrostatic_stiffness'"):
        motion_rao(tanker.drop_vars("hydrostatic_stiffness"))


# --------------------------------------------------------------------------- spectra


def test_response_spectrum_area_and_significant_amplitude():
    w = np.linspace(0.05, 8.0, 40_001)
    spectrum = wave_spectrum("jonswap", 6.0, 12.0)
    unit = xr.DataArray(
        np.ones((w.size, 1, 2), dtype=complex) * np.array([1.0, 0.5j]),
        dims=("omega", "wave_direction", "dof"),
        coords={"omega": w, "wave_direction": [0.0], "dof": ["Heave", "Roll"]},
    )
    s = response_spectrum(unit, spectrum)
    assert s.dims == ("omega", "dof")
    np.testing.assert_allclose(s.sel(dof="Roll"), 0.25 * spectrum(w))
    amp = significant_amplitude(s)
    assert float(amp.sel(dof="Heave")) == pytest.approx(3.0, rel=1e-4)  # H_s / 2
    assert float(amp.sel(dof="Roll")) == pytest.approx(1.5, rel=1e-4)
    m2 = spectral_moment(s.sel(dof="Heave"), 2)
    assert float(m2) == pytest.approx(np.trapezoid(w**2 * spectrum(w), w))
    np.testing.assert_allclose(response_spectrum(unit, spectrum(w)), s)


def test_response_spectrum_over_directions(tanker_rao):
    spectrum = wave_spectrum("jonswap", 4.0, 10.0)
    with pytest.raises(ValueError, match="19 wave directions"):
        response_spectrum(tanker_rao, spectrum)
    beta = tanker_rao.wave_direction.values
    weights = spreading_weights(beta, np.radians(150), 10.0)
    spread = response_spectrum(tanker_rao, spectrum, direction_weights=weights)
    s = spectrum(tanker_rao.omega.values)[:, None]
    manual = sum(
        wt * np.abs(tanker_rao.isel(wave_direction=j).values) ** 2 * s
        for j, wt in enumerate(weights)
    )
    np.testing.assert_allclose(spread.values, manual)
    one = response_spectrum(tanker_rao.sel(wave_direction=[np.pi]), spectrum)
    assert float(significant_amplitude(one).sel(dof="Roll")) < 1e-6  # head seas
    assert float(significant_amplitude(spread).sel(dof="Roll")) > 1e-3  # short-crested
    with pytest.raises(ValueError, match="sum"):
        response_spectrum(tanker_rao, spectrum, direction_weights=np.ones(beta.size))


def test_significant_amplitude_matches_a_simulated_record(tanker):
    """2√m₀ from |RAO|² S equals twice the standard deviation of the same sea's linear
    response in time (superposition of the components; de Haan (2022) §1.9)."""
    spectrum = wave_spectrum("jonswap", 4.0, 10.0)
    waves = irregular_waves(spectrum, duration=20_000, n_components=400, omega_max=2.5, seed=4)
    beta = np.radians(140.0)
    w = np.linspace(waves.attrs["omega_min"], waves.attrs["omega_max"], 4001)
    rao = motion_rao(tanker, w, [beta])
    expected = significant_amplitude(response_spectrum(rao, spectrum))
    t = np.arange(0.0, 20_000.0, 0.5)
    x = wave_response(waves, motion_transfer(tanker, waves.omega, beta), t)
    measured = 2 * x.std(axis=0)
    for d, dof in enumerate(rao.dof.values):
        assert measured[d] == pytest.approx(float(expected.sel(dof=dof)), rel=0.04), dof


# --------------------------------------------------------------------------- files, figure


def test_save_and_load(tmp_path, tanker_rao):
    path = save_rao(tanker_rao, tmp_path / "rao.nc")
    back = load_rao(path)
    np.testing.assert_array_equal(back.values, tanker_rao.values)
    assert back.dims == ("omega", "wave_direction", "dof")
    assert back.attrs["terms"] == tanker_rao.attrs["terms"]
    raw = xr.open_dataset(path, engine="h5netcdf")
    assert raw.rao.dims[0] == "complex" and list(raw.complex.values) == ["re", "im"]
    np.testing.assert_array_equal(raw.rao.sel(complex="im").values, -tanker_rao.values.imag)
    assert "exp(-i omega t)" in raw.rao.attrs["time_convention"]
    raw.close()
    with pytest.raises(cummins.OutputExistsError):
        save_rao(tanker_rao, path)


def test_plot(tanker_rao):
    fig = plot_rao(tanker_rao, dofs=["Heave", "Roll"], headings_deg=[90, 180])
    assert len(fig.axes) == 4
