"""BEMIO .h5 (WEC-Sim): both corpus layouts, their WAMIT .out twins, the round trip."""

from __future__ import annotations

import h5py
import numpy as np
import pytest

import cummins
from cummins.io import detect_format
from cummins.io.bemio import read_bemio, read_bemio_state_space, sniff, sniff_dir, write_bemio

OSWEC = "WEC-Sim/wamit_OSWEC_2015_with_bemio_h5"
WAVESTAR = "WEC-Sim_Applications/wamit_wavestar_NMPC_with_h5"
#: (folder, h5, out, the h5's rho and g)
TWINS = [
    (OSWEC, "oswec.h5", "oswec.out", 1000.0, 9.81),
    (WAVESTAR, "wavestar.h5", "wavestar.out", 1000.0, 9.80665),
]


@pytest.mark.parametrize(("folder", "h5", "out", "rho", "g"), TWINS, ids=["oswec-2015", "wavestar"])
def test_h5_agrees_with_its_wamit_out_twin(corpus, folder, h5, out, rho, g):
    """BEMIO processed these .h5 from the .out beside them (readWamit.py, bemio.m).

    Read with the h5's own rho and g, every coefficient agrees with the .out to
    round-off: measured max |difference| / max |value| <= 1.4e-16 for A, B, A_inf,
    the excitation and (Wavestar) C. 1e-12 leaves room for rounding only: a wrong
    normalisation (rho, rho*w, rho*g), transposition or frequency order would be off by
    orders of magnitude. OSWEC's 2015 file is dimensional (rho = 1000 as in its
    simulation_parameters), Wavestar's MATLAB file normalised.
    """
    h = read_bemio(corpus / folder / h5)
    o = cummins.read(corpus / folder / out, rho=rho, g=g)
    assert list(h.influenced_dof.values) == list(o.influenced_dof.values)
    np.testing.assert_array_equal(h.omega.values, o.omega.values)
    compared = 0
    for name in (
        "added_mass",
        "radiation_damping",
        "added_mass_inf",
        "excitation_force",
        "hydrostatic_stiffness",
    ):
        if name in h and name in o:
            a, b = h[name].values, o[name].values
            if name == "hydrostatic_stiffness":
                # the .out prints C's upper triangle; BEMIO leaves the lower one zero where
                # cummins mirrors it (C54 = C45 = -rho g ∫xy dS): compare what was printed
                a, b = np.triu(a), np.triu(b)
            assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max(), name
            compared += 1
    assert compared >= 4
    # the coefficients are about each body's centre of gravity, which the .out's
    # body origin (XBODY) confirms
    np.testing.assert_allclose(h.attrs["reference_point"], o.attrs["reference_point"])


def test_layouts_are_told_apart_and_described(corpus):
    oswec = read_bemio(corpus / OSWEC / "oswec.h5")
    assert "Python bemio (2015) layout; coefficients dimensional" in oswec.attrs["history"]
    assert oswec.attrs["body_names"] == "flap\nbase"
    assert list(oswec.influenced_dof.values[:2]) == ["body1__Surge", "body1__Sway"]
    wave = read_bemio(corpus / WAVESTAR / "wavestar.h5")
    assert "MATLAB BEMIO layout; coefficients normalised" in wave.attrs["history"]
    # FK and scattering are NaN throughout in this file (the .out had none): left out, said
    assert "Froude_Krylov_force" not in wave
    assert "froude-krylov holds NaN only" in wave.attrs["history"]
    assert wave.attrs["rho"] == 1000.0 and wave.attrs["g"] == 9.80665


def test_detection_by_content_and_folders(corpus, tmp_path, shared_data):
    h5 = corpus / WAVESTAR / "wavestar.h5"
    assert sniff(h5)
    # a NetCDF-4 file is HDF5 too, but not BEMIO; and a BEMIO file renamed .nc is still BEMIO
    nc = tmp_path / "sphere.nc"
    cummins.write(cummins.read(shared_data / "wecsim" / "sphere" / "sphere_hydrodynamics.nc"), nc)
    assert not sniff(nc) and detect_format(nc)[0] == "netcdf"
    renamed = tmp_path / "wavestar.nc"
    renamed.write_bytes(h5.read_bytes())
    assert detect_format(renamed)[0] == "bemio"
    # beside its .out the .h5 is a processed copy: the folder reads as the WAMIT run
    assert sniff_dir(corpus / WAVESTAR) == []
    assert (
        detect_format(corpus / WAVESTAR)[0] == "wamit-out"
        or detect_format(corpus / WAVESTAR)[0] == "wamit"
    )
    alone = tmp_path / "alone"
    alone.mkdir()
    (alone / "wavestar.h5").write_bytes(h5.read_bytes())
    assert detect_format(alone) == ("bemio", alone / "wavestar.h5")


@pytest.mark.parametrize(("folder", "h5"), [(OSWEC, "oswec.h5"), (WAVESTAR, "wavestar.h5")])
def test_read_write_read_is_identical(corpus, tmp_path, folder, h5):
    ds = read_bemio(corpus / folder / h5)
    out = cummins.write(ds, tmp_path / "copy.h5")
    back = cummins.read(out)
    assert back.identical(ds)
    assert "read_warnings" not in back.attrs


def test_written_layout_is_the_one_wec_sim_reads(corpus, tmp_path):
    """Every dataset readBEMIOH5.m reads exists, with the shape MATLAB's writeBEMIOH5
    gives it: compared with the corpus file MATLAB BEMIO wrote for the same run."""
    original = corpus / WAVESTAR / "wavestar.h5"
    out = write_bemio(read_bemio(original), tmp_path / "w.h5")
    read_by_wec_sim = [
        "simulation_parameters/scaled",
        "simulation_parameters/wave_dir",
        "simulation_parameters/water_depth",
        "simulation_parameters/w",
        "simulation_parameters/T",
        "body1/properties/name",
        "body1/properties/body_number",
        "body1/properties/cg",
        "body1/properties/cb",
        "body1/properties/disp_vol",
        "body1/hydro_coeffs/linear_restoring_stiffness",
        "body1/hydro_coeffs/excitation/re",
        "body1/hydro_coeffs/excitation/im",
        "body1/hydro_coeffs/added_mass/all",
        "body1/hydro_coeffs/added_mass/inf_freq",
        "body1/hydro_coeffs/radiation_damping/all",
        "body1/hydro_coeffs/radiation_damping/impulse_response_fun/K",
        "body1/hydro_coeffs/radiation_damping/impulse_response_fun/t",
    ]
    with h5py.File(original) as a, h5py.File(out) as b:
        for name in read_by_wec_sim:
            assert name in b, name
            if name.endswith("impulse_response_fun/K"):
                assert b[name].shape[:2] == a[name].shape[:2]
            elif not name.endswith(("/t", "/name")):
                assert b[name].shape == a[name].shape, name
            if b[name].dtype.kind == "f":
                assert b[name].fletcher32, name
        # normalised as MATLAB BEMIO normalises: the same numbers as the original
        for name in (
            "body1/hydro_coeffs/added_mass/all",
            "body1/hydro_coeffs/excitation/re",
            "body1/hydro_coeffs/linear_restoring_stiffness",
        ):
            np.testing.assert_allclose(b[name][()], a[name][()], rtol=1e-12, atol=0)


def test_state_space_of_bemio_reproduces_its_own_impulse_response(corpus):
    """WEC-Sim's state space (radiationIRFSS) against the IRF in the same file.

    BEMIO fitted each K_ij(t) to R2 >= 0.84 (its r2t); measured on the diagonal the
    model's impulse response matches the file's K(t) with R2 >= 0.9989; 0.99 allows
    for the fits' spread, a wrong C scaling (rho) or ordering would fail by far."""
    path = corpus / WAVESTAR / "wavestar.h5"
    model = read_bemio_state_space(path)
    with h5py.File(path) as f:
        irf = f["body1/hydro_coeffs/radiation_damping/impulse_response_fun"]
        kernel = irf["K"][()] * 1000.0
        t = irf["t"][()].ravel()
    response = model.impulse_response(t).transpose("time", "influenced_dof", "radiating_dof")
    for i in (0, 2, 4):
        k = kernel[i, i]
        r2 = 1 - np.sum((response.values[:, i, i] - k) ** 2) / np.sum((k - k.mean()) ** 2)
        assert r2 >= 0.99, (i, r2)


def test_fitted_model_is_written_as_bemio_state_space(shared_data, tmp_path):
    ds = cummins.select_dofs(cummins.demo_dataset(), list(cummins.hydrodb.DOF_NAMES))
    from cummins.radiation.model import CouplingModel, RadiationModel

    heave = CouplingModel(
        2,
        2,
        np.array([[-1.0, -2.0], [1.0, 0.0]]),
        np.array([1.0, 0.0]),
        np.array([3e6, 1e6]),
        method="test",
    )
    radiation = RadiationModel(
        tuple(cummins.hydrodb.DOF_NAMES), (heave,), np.asarray(ds.added_mass_inf.values)
    )
    out = cummins.write(ds, tmp_path / "m.h5", model=radiation)
    back = read_bemio_state_space(out)
    # written about the centre of gravity (3.93 m forward of the reference point), as
    # the coefficients: a heave force there is the heave force, and it pitches with the
    # lever: K'_33 = K_33, K'_35 = K'_53 = x_G K_33, K'_55 = x_G² K_33
    x_g = float(ds.attrs["center_of_gravity"][0])
    found = {(k.influenced, k.radiating): k for k in back.couplings}
    assert set(found) == {(2, 2), (2, 4), (4, 2), (4, 4)}
    w = np.linspace(0.1, 3.0, 30)
    k33 = heave.frequency_response(w)
    for pair, factor in (((2, 2), 1.0), ((2, 4), x_g), ((4, 2), x_g), ((4, 4), x_g**2)):
        np.testing.assert_allclose(
            found[pair].frequency_response(w), factor * k33, rtol=1e-10, err_msg=str(pair)
        )
    with h5py.File(out) as f:
        ss = f["body1/hydro_coeffs/radiation_damping/state_space"]
        assert ss["it"][2, 2] == 2 and ss["conv"][2, 2] == 1 and ss["conv"][0, 0] == 0


def _store_single(path, group, change=None):
    """Rewrite ``group``'s re, im, mag and phase as float32, as a single-precision BEMIO
    writer stores them (mag and phase rounded apart from re and im); ``change`` edits mag."""
    with h5py.File(path, "r+") as f:
        for key in ("re", "im", "mag", "phase"):
            name = f"{group}/{key}"
            data = np.asarray(f[name][()], dtype=np.float32)
            if key == "mag" and change is not None:
                data = change(data)
            attrs = dict(f[name].attrs)
            del f[name]
            f.create_dataset(name, data=data)
            f[name].attrs.update(attrs)


def test_single_precision_magnitude_and_phase_are_not_damage(corpus, tmp_path):
    """WEC-Sim's wavestar with its excitation stored in float32: |F| e^{i arg F} differs
    from re + i im by ~4e-7 of the largest force, the rounding of single precision, not
    damage (the 1e-9 of double precision called every such file damaged); a magnitude
    changed by 1e-4 still is."""
    import shutil
    import warnings

    path = tmp_path / "wavestar.h5"
    shutil.copy(corpus / WAVESTAR / "wavestar.h5", path)
    group = "body1/hydro_coeffs/excitation"
    _store_single(path, group)
    with h5py.File(path, "r") as f:
        re, im = f[f"{group}/re"][()], f[f"{group}/im"][()]
        polar = f[f"{group}/mag"][()] * np.exp(1j * f[f"{group}/phase"][()].astype(float))
        gap = np.abs(polar - (re + 1j * im)).max() / np.abs(re + 1j * im).max()
    assert 1e-8 < gap < 1e-5  # the rounding the old tolerance took for damage
    with warnings.catch_warnings():
        warnings.simplefilter("error", cummins.HydroDataWarning)
        ds = cummins.read(path)
    assert "read_warnings" not in ds.attrs
    _store_single(path, group, change=lambda mag: mag * np.float32(1 + 1e-4))
    with pytest.warns(cummins.HydroDataWarning, match="mag and phase differ from re and im"):
        cummins.read(path)
