"""The Python functions apply the guards the commands apply: a sea made for data of a
short frequency range stays within it (with a warning saying how much energy is left
out), and a note the user has answered is not repeated."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import cummins
from cummins.errors import ArgumentError, CumminsWarning, HydroDataError
from cummins.seakeeping.spectra import energy_range
from cummins.seakeeping.waves import irregular_waves, wave_spectrum


@pytest.fixture(scope="module")
def short_range():
    """The tanker between 0.3 and 1.2 rad/s: a JONSWAP of Tp 10 s reaches beyond it."""
    return cummins.demo_dataset().sel(omega=slice(0.3, 1.2))


def test_irregular_waves_for_data_stay_within_its_frequencies(short_range):
    sea = wave_spectrum("jonswap", 4.0, 10.0)
    _, hi = energy_range(sea)
    w = short_range.omega.values
    assert hi > w[-1]  # the spectrum's energy reaches beyond the data
    with pytest.warns(CumminsWarning, match="limited to the data's frequencies") as caught:
        waves = irregular_waves(sea, duration=600, n_components=80, data=short_range, seed=1)
    assert w[0] <= waves.omega.min() and waves.omega.max() <= w[-1]
    # the share of the energy said to be left out is the spectrum's beyond the data
    grid = np.linspace(w[-1], hi, 4000)
    beyond = np.trapezoid(sea(grid), grid) / (4.0 / 4) ** 2  # m0 = (Hs/4)^2
    said = float(str(caught[0].message).split("; ")[-1].split(" %")[0])
    assert said == pytest.approx(100 * beyond, rel=0.2)
    # without data= the same sea cannot drive the data: refused, naming the range
    wide = irregular_waves(sea, duration=600, n_components=80, seed=1)
    vessel = cummins.vessel_from_hydrodb(short_range, viscous_damping=[1e6, 1e6, 0, 5e8, 0, 1e10])
    with pytest.raises(HydroDataError, match="outside the data's range"):
        cummins.simulate_waves(vessel, short_range, wide, duration=60, dt=0.1)
    run = cummins.simulate_waves(vessel, short_range, waves, duration=60, dt=0.1)
    assert np.isfinite(run.motion.values).all()


def test_a_spectrum_outside_the_data_is_refused(short_range):
    with pytest.raises(ArgumentError, match="outside the data's frequencies"):
        irregular_waves(wave_spectrum("jonswap", 1.0, 3.0), duration=60, data=[0.1, 0.3])


def test_damping_the_user_gave_is_not_a_warning_again():
    """MSS's frequency-dependent surge, sway and yaw damping: left out of the vessel with a
    warning, unless the user's viscous damping replaces it (then only recorded)."""
    ds = cummins.read(cummins.demo_files().parent / "s175" / "s175.mat").isel(forward_speed=0)
    model = cummins.fit_radiation(ds, method="realization", max_order=6, passivity="diagonal")
    with pytest.warns(UserWarning, match="varies with frequency for Surge-Surge"):
        cummins.vessel_from_hydrodb(ds, model)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        vessel = cummins.vessel_from_hydrodb(ds, model, viscous_damping=[1e6, 1e6, 0, 0, 0, 1e10])
    source = vessel.attrs["viscous_damping_source"]
    assert "replaced by the given: Surge-Surge" in source and "Yaw-Yaw" in source


def test_the_rao_file_says_its_time_convention(tmp_path):
    """In memory x(t) = Re{X e^{iωt}}; the file holds Capytaine's e^{−iωt} and says so on
    the file itself, and reads back in cummins' convention."""
    import h5py

    from cummins.seakeeping.frequency_domain import load_rao, motion_rao, save_rao

    rao = motion_rao(cummins.demo_dataset(), [0.5, 0.8], [np.pi])
    save_rao(rao, tmp_path / "rao.nc")
    with h5py.File(tmp_path / "rao.nc", "r") as f:
        said = f.attrs["time_convention"]
        said = said.decode() if isinstance(said, bytes) else str(said)
        stored = f["rao"][...]
    assert "exp(-i omega t)" in said
    back = load_rao(tmp_path / "rao.nc")
    np.testing.assert_allclose(back.values, rao.values, rtol=1e-12)
    # the stored imaginary part is the conjugate's
    value = rao.transpose("omega", "wave_direction", "dof").values
    np.testing.assert_allclose(stored[..., 1] if stored.shape[-1] == 2 else stored[1], -value.imag)


def test_dir_offers_the_interface_not_the_package_own_imports():
    """Tab completion in a notebook (``dir(cummins)``): every public name, none of the
    modules the package imports for itself (``sys``, ``Path`` … were listed)."""
    names = dir(cummins)
    assert set(cummins.__all__) <= set(names) and "__version__" in names
    assert not {"sys", "importlib", "Path", "TYPE_CHECKING", "annotations"} & set(names)
