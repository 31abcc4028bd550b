"""The BEMIO .h5 cummins writes: every group WEC-Sim reads, the displaced volume where the
data know it, the excitation impulse response, the ``components`` copies, and a round trip
on every corpus case that can be written."""

from __future__ import annotations

import shutil
import warnings

import h5py
import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from conftest import SHARED_DATA
from cummins.cli import main
from cummins.errors import CumminsError, CumminsWarning
from cummins.excitation_model import excitation_irf
from cummins.io.bemio import read_bemio, write_bemio
from cummins.io.bemio.files import COPY_GROUP

CORPUS = SHARED_DATA / "corpus"
WAVESTAR = "WEC-Sim_Applications/wamit_wavestar_NMPC_with_h5/wavestar.h5"
SPAR = "WEIS/ss_fitting_OC3_spar/spar.1"
#: What WEC-Sim's readBEMIOH5.m reads with h5read outside a try (it stops without them).
REQUIRED = (
    "simulation_parameters/scaled",
    "simulation_parameters/wave_dir",
    "simulation_parameters/water_depth",
    "simulation_parameters/w",
    "simulation_parameters/T",
    "body{k}/properties/name",
    "body{k}/properties/body_number",
    "body{k}/properties/cg",
    "body{k}/properties/cb",
    "body{k}/hydro_coeffs/linear_restoring_stiffness",
    "body{k}/hydro_coeffs/excitation/re",
    "body{k}/hydro_coeffs/excitation/im",
    "body{k}/hydro_coeffs/added_mass/all",
    "body{k}/hydro_coeffs/added_mass/inf_freq",
    "body{k}/hydro_coeffs/radiation_damping/all",
)
#: What it reads in a try, all of which cummins writes.
OPTIONAL = (
    "body{k}/properties/dof",
    "body{k}/properties/dof_start",
    "body{k}/properties/dof_end",
    "body{k}/hydro_coeffs/excitation/impulse_response_fun/f",
    "body{k}/hydro_coeffs/excitation/impulse_response_fun/t",
    "body{k}/hydro_coeffs/radiation_damping/impulse_response_fun/K",
    "body{k}/hydro_coeffs/radiation_damping/impulse_response_fun/t",
)


def _quiet_read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path)


def _cases():
    from test_corpus import CASES

    return CASES


def _without_copy(path, tmp_path):
    """The file as another tool sees it: the cummins group removed."""
    bare = tmp_path / "bare.h5"
    shutil.copy(path, bare)
    with h5py.File(bare, "a") as f:
        del f[COPY_GROUP]
    return bare


@pytest.mark.parametrize("name", _cases())
def test_every_corpus_case_reads_back_the_same_numbers(name, tmp_path):
    """Read, written as .h5, read again: the same dataset (cummins' copy), the BEMIO
    datasets in agreement with it (no damage warning), and read without the copy (as
    WEC-Sim sees the file) the same coefficients about the centre of gravity."""
    try:
        ds = _quiet_read(CORPUS / name)
    except CumminsError:
        return  # two cases are refused with a message (test_corpus checks which)
    if "excitation_force" not in ds or "hydrostatic_stiffness" not in ds:
        with pytest.raises(CumminsError, match="WEC-Sim needs"):
            write_bemio(ds, tmp_path / "x.h5")
        return
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        path = write_bemio(ds, tmp_path / "x.h5")
    volume_known = "displaced_volume" in ds.attrs
    said = [str(w.message) for w in caught if "disp_vol" in str(w.message)]
    assert bool(said) != volume_known
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        back = cummins.read(path)
    assert not [w for w in caught if "copy cummins wrote" in str(w.message)]
    for variable in ds.data_vars:
        np.testing.assert_array_equal(back[variable].values, ds[variable].values, variable)
    bare = read_bemio(_without_copy(path, tmp_path))
    reference = ds
    if "center_of_gravity" in ds.attrs and np.all(np.isfinite(ds.attrs["center_of_gravity"])):
        point = np.asarray(ds.attrs["center_of_gravity"], dtype=float)
        reference = cummins.move_reference_point(ds, point.reshape(-1, 3).squeeze())
    for variable in ("added_mass", "radiation_damping", "excitation_force"):
        a, b = bare[variable].values, reference[variable].values
        assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max(), variable
    n_bodies = len(cummins.hydrodb.bodies(ds))
    with h5py.File(path) as f:
        for k in range(1, n_bodies + 1):
            for item in REQUIRED + OPTIONAL:
                assert item.format(k=k) in f, item
            assert (f"body{k}/properties/disp_vol" in f) == volume_known


def test_disp_vol_unknown_is_left_out_and_the_file_reads(tmp_path):
    """Issue 33: `cummins convert spar.1 spar.h5` wrote disp_vol = NaN and `cummins info`
    refused cummins' own file. Now the dataset is left out, with a warning naming what to
    give, and --displaced-volume writes it."""
    runner = CliRunner()
    out = tmp_path / "spar.h5"
    result = runner.invoke(main, ["convert", str(CORPUS / SPAR), str(out)])
    assert result.exit_code == 0, result.output
    assert "disp_vol is left out" in result.output
    info = runner.invoke(main, ["info", str(out)])
    assert info.exit_code == 0, info.output
    given = tmp_path / "spar_v.h5"
    result = runner.invoke(
        main, ["convert", str(CORPUS / SPAR), str(given), "--displaced-volume", "8029"]
    )
    assert result.exit_code == 0 and "left out" not in result.output
    with h5py.File(given) as f:
        assert f["body1/properties/disp_vol"][()].item() == 8029.0
    assert read_bemio(_without_copy(given, tmp_path)).attrs["displaced_volume"] == 8029.0
    wrong = runner.invoke(
        main, ["convert", str(CORPUS / SPAR), str(tmp_path / "w.h5"), "--displaced-volume", "1",
               "--displaced-volume", "2"],
    )  # fmt: skip
    assert wrong.exit_code == 2 and "one volume per body" in wrong.output


def test_excitation_impulse_response_agrees_with_bemio(tmp_path):
    """The file's excitation/impulse_response_fun against MATLAB BEMIO's excitationIRF
    (the Wavestar .h5 of the corpus): K_ex(t)/(rho g) within 5e-4 of its peak on BEMIO's
    own times, when the force below the first frequency is left out as BEMIO does; with
    the long-wave limit the written one differs by the band [0, 0.2] rad/s (~3 %)."""
    original = read_bemio(CORPUS / WAVESTAR)
    with h5py.File(CORPUS / WAVESTAR) as f:
        bemio_f = f["body1/hydro_coeffs/excitation/impulse_response_fun/f"][()]
        t = f["body1/hydro_coeffs/excitation/impulse_response_fun/t"][()].ravel()
    scale = original.attrs["rho"] * original.attrs["g"]
    ours = excitation_irf(original, t, zero_frequency="none").values / scale
    for d in (0, 2, 4):  # surge, heave, pitch: measured 1.7e-4, 7.5e-5, 9.9e-5
        peak = np.abs(bemio_f[d, 0]).max()
        assert np.abs(ours[:, 0, d] - bemio_f[d, 0]).max() < 5e-4 * peak
    path = write_bemio(original, tmp_path / "w.h5")
    with h5py.File(path) as f:
        written = f["body1/hydro_coeffs/excitation/impulse_response_fun/f"][()]
        times = f["body1/hydro_coeffs/excitation/impulse_response_fun/t"][()].ravel()
        assert written.shape == (6, 1, times.size) and np.allclose(times, -times[::-1])
        # the components are (t, f) of each DOF and heading
        component = f["body1/hydro_coeffs/excitation/impulse_response_fun/components/f/3_1"][()]
        np.testing.assert_array_equal(component, np.c_[times, written[2, 0]])
    expected = excitation_irf(original, times).values / scale
    np.testing.assert_allclose(written[:, 0, :].T, expected[:, 0, :], rtol=0, atol=1e-9)


def test_components_are_the_all_arrays_by_pair(tmp_path):
    """``components/<i>_<j>`` (period, value), as the older MATLAB BEMIO wrote them and
    scripts read them (added mass, damping, the forces by DOF and heading)."""
    ds = _quiet_read(CORPUS / WAVESTAR)
    path = write_bemio(ds, tmp_path / "w.h5")
    with h5py.File(path) as f, h5py.File(CORPUS / WAVESTAR) as matlab:
        hc = f["body1/hydro_coeffs"]
        period = f["simulation_parameters/T"][()].ravel()
        for name in ("added_mass", "radiation_damping"):
            full = hc[f"{name}/all"][()]
            for i, j in ((1, 1), (3, 5), (5, 3)):
                pair = hc[f"{name}/components/{i}_{j}"][()]
                np.testing.assert_array_equal(pair, np.c_[period, full[i - 1, j - 1]])
                assert pair.shape == matlab[f"body1/hydro_coeffs/{name}/components/{i}_{j}"].shape
        for key in ("re", "im", "mag", "phase"):
            np.testing.assert_array_equal(
                hc[f"excitation/components/{key}/3_1"][()],
                np.c_[period, hc[f"excitation/{key}"][()][2, 0]],
            )
    nemoh = _quiet_read(CORPUS / "WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar")
    path = write_bemio(nemoh, tmp_path / "n.h5")
    bare = read_bemio(_without_copy(path, tmp_path))
    for variable in ("Froude_Krylov_force", "diffraction_force"):
        assert variable in nemoh
        b = nemoh[variable].values
        assert np.abs(bare[variable].values - b).max() <= 1e-12 * np.abs(b).max()
    with h5py.File(path) as f:
        for group in ("froude-krylov", "scattering"):
            assert f"body1/hydro_coeffs/excitation/{group}/components/phase/1_1" in f


def test_no_displaced_volume_warning_when_known(tmp_path):
    ds = _quiet_read(CORPUS / WAVESTAR)
    assert "displaced_volume" in ds.attrs
    with warnings.catch_warnings():
        warnings.simplefilter("error", CumminsWarning)
        write_bemio(ds, tmp_path / "w.h5")


def test_missing_excitation_names_the_file_to_read(corpus, tmp_path):
    """WEIS' OC4 semi (its .3 missing): the refusal named an option convert does not have
    (--stiffness) for a variable that was not missing; now it names the excitation file."""
    from cummins.cli import main

    source = corpus / "WEIS" / "ss_fitting_OC4_semi" / "marin_semi.1"
    result = CliRunner().invoke(main, ["convert", str(source), str(tmp_path / "s.h5")])
    text = " ".join(result.output.split())
    assert result.exit_code == 1 and "needs excitation_force" in text
    assert "WAMIT .3" in text and "--stiffness" not in text and "hydrostatic" not in text
    assert not (tmp_path / "s.h5").exists()
