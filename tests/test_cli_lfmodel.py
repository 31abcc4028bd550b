"""`cummins lf-model`: the low-frequency model from the command line."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.timedomain.lfmodel import lf_model_from_frequency_data


def test_cli_writes_the_model_of_the_python_api(tmp_path):
    tanker = cummins.demo_files() / "tanker.1"
    out = tmp_path / "lf.nc"
    args = [
        "lf-model",
        str(tanker),
        "-o",
        str(out),
        "--plot",
        str(tmp_path / "lf.png"),
        "--roll-damping",
        "0.05",
        "--compare",
        str(tmp_path / "cmp"),
    ]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    written = xr.open_dataset(out, engine="h5netcdf")
    from cummins.timedomain.lfmodel import CriticalDampingFraction

    same = lf_model_from_frequency_data(
        cummins.read(tanker), viscous={"Roll": CriticalDampingFraction(0.05)}
    )
    np.testing.assert_allclose(written.added_mass.values, same.added_mass)
    np.testing.assert_allclose(written.damping.values, same.damping)
    np.testing.assert_allclose(written.frequency.values, same.frequencies)
    # surge, sway, yaw at ω = 0; heave, roll, pitch at their natural frequency (eq. 24)
    assert list(written.frequency.values[[0, 1, 5]]) == [0.0, 0.0, 0.0]
    # the roll natural frequency solves ω²(M44 + A44(ω)) = C44, here by bisection on the
    # data linearly interpolated (the model interpolates A with a spline: measured 0.013 %
    # apart; 1 % allows for any interpolation of A)
    import scipy.optimize

    data = cummins.read(tanker)
    m44 = float(data.inertia_matrix.sel(influenced_dof="Roll", radiating_dof="Roll"))
    c44 = float(data.hydrostatic_stiffness.sel(influenced_dof="Roll", radiating_dof="Roll"))
    a44 = data.added_mass.sel(influenced_dof="Roll", radiating_dof="Roll")

    def residual(w):
        return w**2 * (m44 + float(a44.interp(omega=w))) - c44

    w0 = scipy.optimize.brentq(residual, 0.1, 2.0)
    assert written.frequency.sel(dof="Roll") == pytest.approx(w0, rel=0.01)
    # the steps of the zero-frequency DOFs agree with the Cummins model to a few per cent
    for dof in ("Surge", "Sway", "Yaw"):
        line = next(s for s in result.output.splitlines() if s.startswith(f"step of {dof}"))
        assert float(line.split("difference ")[1].split(" %")[0]) < 3.0
    assert (tmp_path / "cmp" / "decay_Roll.png").stat().st_size > 10_000
    assert (tmp_path / "lf.png").stat().st_size > 10_000
    # what each DOF is taken as is printed whole, whatever the terminal's width
    printed = " ".join(result.output.split())
    for sentence in same.provenance:
        assert " ".join(sentence.split()) in printed, sentence
    assert "ζ = 0.05 → " in printed and "(eqs. 20–21)" in printed


def test_data_damping_takes_mss_bv(shared_data, tmp_path):
    """--data-damping (the CLI form of viscous={dof: 'data'}): surge, sway and yaw damped
    by the supply vessel's MSS Bv at its lowest frequency, where without it D = 0 and the
    note names the option, not the Python keyword."""
    supply = shared_data / "mss" / "supply" / "supply.mat"
    bare = CliRunner().invoke(main, ["lf-model", str(supply), "-o", str(tmp_path / "a.nc")])
    assert bare.exit_code == 0, bare.output
    assert "--data-damping" in bare.output and "viscous={" not in bare.output
    with xr.open_dataset(tmp_path / "a.nc", engine="h5netcdf") as ds:
        assert np.all(ds.damping.values[[0, 1, 5], [0, 1, 5]] == 0)
    out = tmp_path / "b.nc"
    args = ["lf-model", str(supply), "-o", str(out), "--data-damping", "all"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert "varies with frequency" not in result.output
    data = cummins.read(supply)
    bv = data.additional_damping.isel(omega=0).values
    same = lf_model_from_frequency_data(
        data, viscous=dict.fromkeys(data.influenced_dof.values.tolist(), "data")
    )
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        np.testing.assert_allclose(ds.damping.values, same.damping)
        for k in (0, 1, 5):
            assert ds.damping.values[k, k] == pytest.approx(bv[k, k], rel=1e-9)
    bad = CliRunner().invoke(main, ["lf-model", str(supply), "-o", str(out), "--force",
                                    "--data-damping", "Swag"])  # fmt: skip
    assert bad.exit_code == 2 and "--data-damping" in bad.output and "Swag" in bad.output
