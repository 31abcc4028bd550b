"""WAMIT numeric files written from any HydroDB (a Capytaine run to HydroDyn): read back
by cummins' WAMIT reader, the same numbers to WAMIT's printed precision (7 digits)."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import AssumptionWarning, HydroDataError
from cummins.io.wamit.numeric_writer import write_wamit

SEMISUB = Path(__file__).parent / "data" / "semisub_capytaine.nc"
VARIABLES = (
    "added_mass",
    "radiation_damping",
    "excitation_force",
    "hydrostatic_stiffness",
    "added_mass_inf",
    "added_mass_zero",
)
#: 7 significant digits: a relative rounding of at most 5e-7 per number
PRINTED = 1.2e-6


def _read(path, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path, **options)


def _same(back, ds):
    compared = 0
    for name in VARIABLES:
        if name in ds:
            a, b = back[name].values, ds[name].values
            assert a.shape == b.shape, name
            assert np.abs(a - b).max() <= PRINTED * np.abs(b).max(), name
            compared += 1
    np.testing.assert_allclose(back.omega.values, ds.omega.values, rtol=PRINTED)
    return compared


@pytest.mark.parametrize("ulen", [1.0, 3.5])
def test_capytaine_run_round_trip(tmp_path, ulen):
    ds = _read(SEMISUB)
    files = write_wamit(ds, tmp_path / "semi.1", ulen=ulen, hydrodyn=False)
    assert [f.suffix for f in files] == [".1", ".3", ".hst"]
    back = _read(files[0], rho=ds.attrs["rho"], g=ds.attrs["g"], ulen=ulen)
    assert _same(back, ds) == 6
    np.testing.assert_allclose(back.wave_direction.values, ds.wave_direction.values, atol=1e-6)


def test_wamit_run_is_written_as_wamit_wrote_it(shared_data, tmp_path):
    """The tanker's own files, read and written again: the same entries (WAMIT leaves the
    structural zeros of the .1 out) and the same numbers, digit for digit."""
    original = shared_data / "mss" / "tanker" / "tanker.1"
    ds = _read(original)
    files = write_wamit(ds, tmp_path / "tanker.1", ulen=float(ds.attrs["ulen"]), hydrodyn=False)

    def rows(path):
        return {
            tuple(float(x) for x in line.split()[:3]): [float(x) for x in line.split()[3:]]
            for line in path.read_text().splitlines()
        }

    for suffix in (".1", ".3", ".hst"):
        mine, theirs = rows(files[0].with_suffix(suffix)), rows(original.with_suffix(suffix))
        assert mine.keys() == theirs.keys(), suffix
        for key, values in theirs.items():
            if suffix == ".3" and values[0] == 0:  # the phase of a zero: WAMIT writes 90
                values, got = values[::2] + values[3:], mine[key][::2] + mine[key][3:]
            else:
                got = mine[key]
            np.testing.assert_allclose(got, values, rtol=1e-6, atol=1e-6, err_msg=suffix)


def test_two_bodies_and_fossen_axes(corpus, tmp_path):
    ds = _read(corpus / "WEC-Sim" / "wamit_RM3_2body" / "rm3.out")
    files = write_wamit(cummins.change_axes(ds, "z-down"), tmp_path / "rm3.1", hydrodyn=False)
    back = _read(files[0], rho=ds.attrs["rho"], g=ds.attrs["g"], ulen=1.0, modes=[6, 6])
    assert _same(back, ds) >= 4  # written in WAMIT's z-up axes


def test_convert_writes_the_three_files_and_refuses_to_overwrite(tmp_path):
    out = tmp_path / "semi.1"
    result = CliRunner().invoke(main, ["convert", str(SEMISUB), str(out)])
    assert result.exit_code == 0, result.output
    assert all(out.with_suffix(s).exists() for s in (".1", ".3", ".hst"))
    out.unlink()  # the .3 and .hst are still there
    again = CliRunner().invoke(main, ["convert", str(SEMISUB), str(out)])
    assert again.exit_code == 2 and "semi.3" in again.output and not out.exists()


def test_forward_speed_is_refused(tmp_path):
    s175 = cummins.read(cummins.demo_files().parent / "s175" / "s175.mat")
    with pytest.raises(HydroDataError, match="forward speed"):
        write_wamit(s175.isel(forward_speed=4), tmp_path / "s.1")


SPHERE = "corpus/WEC-Sim_Applications/wamit_mean_drift_sphere/outputFiles/sphere.1"
DRIFT_SPHERE = Path(__file__).parent / "data" / "sphere_drift_capytaine.nc"


def _rows(path):
    """The rows of a mean-drift file of positive mode index, in file order: (PER, β₁, β₂,
    I, |F|, Re F), F nondimensional."""
    rows = [[float(v) for v in line.split()] for line in path.read_text().splitlines()[1:]]
    return np.array([[*x[:5], x[6]] for x in rows if x[3] > 0])


def test_mean_drift_is_written_as_wamit_wrote_it(shared_data, tmp_path):
    """The drift sphere's .7, .8 and .9 (control surface, momentum, pressure), read and
    written again: each estimate to the file of its method, the same rows in the same
    order (the .8 surge, sway and yaw alone, as WAMIT's) and the same numbers as WAMIT's
    own files (its periods printed to 6 digits, its values to 7)."""
    original = shared_data / SPHERE
    ds = _read(original)
    files = write_wamit(ds, tmp_path / "sphere.1", hydrodyn=False)
    assert [f.suffix for f in files] == [".1", ".3", ".hst", ".7", ".9", ".8"]
    for suffix in (".7", ".8", ".9"):
        mine, theirs = _rows(tmp_path / f"sphere{suffix}"), _rows(original.with_suffix(suffix))
        assert mine.shape == theirs.shape, suffix
        np.testing.assert_allclose(mine[:, 0], theirs[:, 0], rtol=1e-5)  # 6 digits: 5e-6
        np.testing.assert_array_equal(mine[:, 1:4], theirs[:, 1:4])
        peak = np.abs(theirs[:, 4]).max()
        np.testing.assert_allclose(mine[:, 4:], theirs[:, 4:], rtol=1e-6, atol=1e-9 * peak)
    back = _read(files[0], rho=ds.attrs["rho"], g=ds.attrs["g"])
    for name in ("drift_force", "drift_force_pressure", "drift_force_momentum"):
        assert back[name].attrs["method"].split(",")[0] == ds[name].attrs["method"].split(",")[0]
        np.testing.assert_allclose(back[name].values, ds[name].values, rtol=PRINTED)


def test_capytaine_far_field_drift_goes_to_the_dot8(tmp_path):
    """Capytaine's far-field drift (momentum: surge, sway, yaw) is HydroDyn's MnDrift = 8
    file; read back with the .1, the same numbers to 7 digits."""
    ds = _read(DRIFT_SPHERE)
    files = write_wamit(ds, tmp_path / "s.1", hydrodyn=False)
    assert [f.suffix for f in files][-1] == ".8"
    assert set(_rows(tmp_path / "s.8")[:, 3]) == {1.0, 2.0, 6.0}
    back = _read(files[0], rho=ds.attrs["rho"], g=ds.attrs["g"])
    assert back.drift_force.attrs["method"].startswith("momentum")
    a, b = back.drift_force.values, ds.drift_force.values
    assert np.abs(a - b).max() <= PRINTED * np.abs(b).max()


def test_a_drift_of_unknown_method_is_written_with_the_choice_said(shared_data, tmp_path):
    """MSS's supply vessel records no method and holds surge, sway and yaw: written to the
    .8 with an AssumptionWarning naming it; z-down data in WAMIT's z-up axes, read back."""
    ds = _read(shared_data / "mss" / "supply" / "supply.mat")
    with pytest.warns(AssumptionWarning, match=r"not recorded: written to the \.8"):
        files = write_wamit(ds, tmp_path / "s.1", hydrodyn=False)
    assert files[-1].suffix == ".8"
    back = _read(files[0], rho=ds.attrs["rho"], g=ds.attrs["g"])
    z_up = cummins.change_axes(ds, "z-up").drift_force.values
    assert np.abs(back.drift_force.values - z_up).max() <= PRINTED * np.abs(z_up).max()
    assert np.abs(z_up[..., 1]).max() > 0.1 * np.abs(z_up).max()  # sway: a real check


def test_convert_says_which_drift_file_hydrodyn_reads(shared_data, tmp_path):
    result = CliRunner().invoke(main, ["convert", str(shared_data / SPHERE), str(tmp_path / "x.1")])
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "x.7 (control surface" in text and "MnDrift (or NewmanApp) = 7 or 9 or 8" in text
    assert all((tmp_path / f"x{s}").exists() for s in (".7", ".8", ".9"))
