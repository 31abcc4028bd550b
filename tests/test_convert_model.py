"""`cummins convert DATA x.h5 --model MODEL.nc`: the radiation state space of a fitted
model in the BEMIO file WEC-Sim reads (``hydro_coeffs/radiation_damping/state_space``).

References: the Python route (``cummins.write(ds, "x.h5", model=…)``), written
independently of the command line, and the model itself (its impulse response, read back
from the .h5 by cummins' BEMIO state-space reader, which scales C by ρ as WEC-Sim's
``bodyClass`` does).
"""

from __future__ import annotations

import shutil

import h5py
import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.io.bemio import read_bemio_state_space
from cummins.radiation.model import RadiationModel

SPAR = ("WEIS", "ss_fitting_OC3_spar")
STATE_SPACE = "body1/hydro_coeffs/radiation_damping/state_space"


@pytest.fixture(scope="module")
def spar(corpus, tmp_path_factory):
    """The OC3 spar's WAMIT files and the model `cummins fit` writes of them."""
    folder = tmp_path_factory.mktemp("convert_model")
    for suffix in (".1", ".3", ".hst"):
        shutil.copy(corpus.joinpath(*SPAR) / f"spar{suffix}", folder)
    model = folder / "spar_model.nc"
    result = CliRunner().invoke(main, ["fit", str(folder / "spar.1"), "-o", str(model)])
    assert result.exit_code == 0, result.output
    return folder, model


def _state_space(path) -> dict[str, np.ndarray]:
    with h5py.File(path, "r") as f:
        group = f[STATE_SPACE]
        return {k: group[f"{k}/all"][()] for k in ("A", "B", "C", "D")} | {
            "it": group["it"][()],
            "K": group["K/all"][()],
        }


def test_convert_writes_the_models_state_space(spar):
    """The .h5 of `convert --model` holds the state space the Python route writes (the
    same arrays, bit for bit), and read back it is the model: its K(t) within 1e-12."""
    folder, model_path = spar
    out = folder / "spar.h5"
    result = CliRunner().invoke(
        main,
        [
            "convert",
            str(folder / "spar.1"),
            str(out),
            "--displaced-volume",
            "8029",
            "--model",
            str(model_path),
        ],
    )
    assert result.exit_code == 0, result.output
    model = RadiationModel.load(model_path)
    orders = [k.order for k in model.as_couplings().couplings if k.order]
    assert f"with the state space of spar_model.nc: {len(orders)} couplings" in result.output
    assert "radiation_damping/state_space" in result.output

    ds = cummins.read(folder / "spar.1")
    ds.attrs["displaced_volume"] = 8029.0
    python = folder / "spar_python.h5"
    cummins.write(ds, python, model=model)
    cli, ref = _state_space(out), _state_space(python)
    assert set(cli) == set(ref)
    for key in cli:
        np.testing.assert_array_equal(cli[key], ref[key], err_msg=key)
    assert np.count_nonzero(cli["C"]) > 0 and int(cli["it"].max()) == max(orders)

    back = read_bemio_state_space(out)
    t = np.linspace(0.0, 60.0, 301)
    k_model = model.impulse_response(t).values
    k_back = back.impulse_response(t).values
    scale = np.abs(k_model).max()
    assert scale > 0
    np.testing.assert_allclose(k_back, k_model, rtol=0, atol=1e-12 * scale)


def test_a_model_of_other_data_is_refused(spar, corpus, tmp_path):
    """Other DOFs (the two-body RM3), or the same data moved to another reference point
    (their A(ω), B(ω) are no longer the fit's): exit 2, one line naming the model and
    what differs; nothing written."""
    folder, model_path = spar
    rm3 = corpus / "WEC-Sim" / "wamit_RM3_2body" / "rm3.out"
    cases = [
        ([str(rm3), str(tmp_path / "rm3.h5"), "--rho", "1000"], "DOFs"),
        (
            [
                str(folder / "spar.1"),
                str(tmp_path / "moved.h5"),
                "--reference-point",
                "0",
                "0",
                "-10",
            ],
            "the added mass of Pitch differs",
        ),
    ]
    for args, what in cases:
        result = CliRunner().invoke(main, ["convert", *args, "--model", str(model_path)])
        assert result.exit_code == 2, result.output
        message = " ".join(result.output.split())
        assert "--model spar_model.nc was fitted to other data" in message
        assert what in message
        assert not (tmp_path / args[1]).exists()


def test_model_refused_for_formats_that_do_not_store_it(spar, tmp_path):
    """A .nc (or .1, .mat) does not store a state space; a file that is not a radiation
    model is not one: exit 2 before anything is read or written."""
    folder, model_path = spar
    for destination, model, what in (
        (tmp_path / "spar.nc", model_path, "only a BEMIO .h5 stores a radiation state space"),
        (tmp_path / "spar.h5", folder / "spar.1", "is not a radiation model file"),
    ):
        result = CliRunner().invoke(
            main, ["convert", str(folder / "spar.1"), str(destination), "--model", str(model)]
        )
        assert result.exit_code == 2, result.output
        assert what in " ".join(result.output.split())
        assert not destination.exists()


def test_the_state_space_goes_to_the_centre_of_gravity_with_the_coefficients(spar, tmp_path):
    """The coefficients go into the .h5 about the centre of gravity (the OC3 spar's, 89.92 m
    below the waterline, Jonkman 2010), and the state space with them: read back, each
    coupling's K(t) is Hᵀ K(t) H of the model (H the screw transform, computed here
    from :func:`cummins.kinematics.screw_transform`), within 1e-9 of its peak; the
    pitch's K(t) about the centre of gravity is nothing like the model's about the
    waterline (its peak 100 times larger: surge's memory times the 89.92 m lever²)."""
    from cummins.kinematics import screw_transform

    folder, model_path = spar
    model = RadiationModel.load(model_path)
    ds = cummins.read(folder / "spar.1")
    ds.attrs["displaced_volume"] = 8029.0
    cg = np.array([0.0, 0.0, -89.92])
    ds.attrs["center_of_gravity"] = cg
    out = tmp_path / "spar_cg.h5"
    cummins.write(ds, out, model=model)
    written = read_bemio_state_space(out)
    t = np.linspace(0.0, 60.0, 241)
    h = screw_transform(np.asarray(ds.attrs["reference_point"], dtype=float) - cg)
    kernel = model.impulse_response(t).transpose("time", "influenced_dof", "radiating_dof")
    expected = np.einsum("ki,tkl,lj->tij", h, kernel.values, h)
    found = written.impulse_response(t).transpose("time", "influenced_dof", "radiating_dof")
    peak = np.abs(expected).max(axis=0)
    scale = np.sqrt(np.outer(np.diag(peak), np.diag(peak)))
    error = np.abs(found.values - expected).max(axis=0)
    assert np.all(error <= 1e-9 * scale + 1e-12 * peak.max())
    pitch = 4
    moved_by = np.abs(expected[:, pitch, pitch] - kernel.values[:, pitch, pitch]).max()
    assert moved_by > 0.5 * peak[pitch, pitch]  # the point matters: measured 0.99
