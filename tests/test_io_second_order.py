"""Second-order data read from real files: WAMIT .7/.8/.9 and .12d/.12s, NEMOH v3 QTFs,
AQWA .LIS drift tables, and the canonical form (NetCDF round trip, axes, reference point).

References are the files' own printed numbers (a row of the file, the .out's tables of
the same run), the symmetries every QTF must have, and a second method of the same run
(momentum conservation against the control surface).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import cummins
from cummins.io.wamit import read_wamit_out
from cummins.qtf import has_qtf, qtf_table

OC4 = "corpus/WEIS/ss_fitting_OC4_semi/marin_semi.1"
SPHERE = "corpus/WEC-Sim_Applications/wamit_mean_drift_sphere/outputFiles/sphere.1"
SPAR = "corpus/WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar"
PEND = "corpus/WEC-Sim/aqwa_19.1_PEND_hull/19_1.LIS"
RHO_G = 1025.0 * 9.81
DATA = Path(__file__).parent / "data"


@pytest.fixture(scope="module")
def oc4(shared_data):
    return cummins.read(shared_data / OC4)


@pytest.fixture(scope="module")
def spar(shared_data):
    return cummins.read(shared_data / SPAR)


def _at(ds, name, w1, w2, dof):
    q = ds[name].isel(qtf_wave_direction=0).sel(influenced_dof=dof)
    return complex(q.sel(qtf_omega=w1, qtf_omega2=w2, method="nearest").values)


def test_oc4_qtf_rows_read_as_the_file_prints_them(oc4):
    """marin_semi.12d, line 8: PER 20.944 s, 25.133 s (ω = 0.3, 0.25 rad/s), surge,
    Re −0.337323, Im −2.59062 (× ρ g, L = 1); .12s line 2: the sum QTF at 25.133 s."""
    assert has_qtf(oc4, "difference") and has_qtf(oc4, "sum")
    assert _at(oc4, "qtf_difference", 0.30, 0.25, "Surge") == pytest.approx(
        RHO_G * (-0.337323 - 2.59062j), rel=1e-6
    )
    # the other triangle, which WAMIT does not write: the complex conjugate
    assert _at(oc4, "qtf_difference", 0.25, 0.30, "Surge") == pytest.approx(
        RHO_G * (-0.337323 + 2.59062j), rel=1e-6
    )
    assert _at(oc4, "qtf_sum", 0.25, 0.25, "Surge") == pytest.approx(
        RHO_G * (-1.45161 - 1.27650j), rel=1e-6
    )
    table = qtf_table(oc4, "difference")
    assert table.omega.size == 56 and table.omega[0] == pytest.approx(0.25, rel=1e-4)
    assert table.omega[-1] == pytest.approx(3.0, rel=1e-4)


def test_oc4_qtfs_have_their_symmetries(oc4):
    d = qtf_table(oc4, "difference").values
    s = qtf_table(oc4, "sum").values
    off = ~np.eye(d.shape[0], dtype=bool)  # the diagonal is its own mirror: below
    assert np.array_equal(d[off], np.conj(np.swapaxes(d, 0, 1))[off])
    assert np.array_equal(s, np.swapaxes(s, 0, 1))
    # the diagonal of the difference QTF (the mean drift) is real to WAMIT's round-off in
    # the DOFs head seas drive (surge, heave, pitch; sway, roll and yaw are noise of
    # 1e-5 of them)
    diag = np.diagonal(d[:, :, 0, :], axis1=0, axis2=1)[[0, 2, 4]]
    assert np.all(np.abs(diag.imag).max(axis=1) < 1e-5 * np.abs(diag).max(axis=1))


def test_a_qtf_file_given_alone_reads_its_run(shared_data, oc4):
    ds = cummins.read(shared_data / OC4.replace(".1", ".12d"))
    assert np.array_equal(ds.qtf_difference.values, oc4.qtf_difference.values)


def test_sphere_mean_drift_of_three_methods(shared_data):
    ds = cummins.read(shared_data / SPHERE)
    rho_g = ds.attrs["rho"] * ds.attrs["g"]
    assert ds.drift_force.attrs["method"].startswith("control surface")
    # sphere.7, PER 2.0944 s (ω = 3 rad/s), surge: 0.2224456 ρ g
    surge = ds.drift_force.sel(influenced_dof="Surge").isel(wave_direction=0)
    assert float(surge.sel(omega=3.0, method="nearest")) == pytest.approx(0.2224456 * rho_g)
    # momentum conservation computes surge, sway and yaw only; heave is recorded as absent
    momentum = ds.drift_force_momentum
    assert momentum.attrs["dofs_computed"] == "Surge Sway Yaw"
    assert float(np.abs(momentum.sel(influenced_dof="Heave")).max()) == 0.0
    # the far field agrees with the control surface up to 5 rad/s (1.1 % of the peak
    # measured; beyond 6 rad/s the waves are short for the panels and they part by 10 %)
    low = ds.omega.values <= 5.0
    cs = ds.drift_force.sel(influenced_dof="Surge").values[low]
    mc = momentum.sel(influenced_dof="Surge").values[low]
    assert np.abs(cs - mc).max() < 0.05 * np.abs(cs).max()


def test_sphere_out_takes_the_drift_method_the_numeric_files_do(shared_data):
    """One WAMIT run, one mean drift: the .out prints the three methods' tables and is
    read as the .7/.9/.8 are — drift_force the control surface (was the pressure
    integration, 6.4 % lower at 2.95 rad/s, 'method not recorded'), the others as
    drift_force_pressure and drift_force_momentum, each equal to its numeric file within
    the .out's 6 significant digits (measured 2e-6 of the peak)."""
    ds = cummins.read(shared_data / SPHERE)
    out = read_wamit_out(shared_data / SPHERE.replace(".1", ".out"))
    assert np.allclose(out.omega.values, ds.omega.values)
    assert out.drift_force.attrs["method"] == "control surface, sphere.out"
    assert out.drift_force_momentum.attrs["dofs_computed"] == "Surge Sway Yaw"
    for name in ("drift_force", "drift_force_pressure", "drift_force_momentum"):
        a, b = ds[name].values, out[name].values
        assert np.abs(a - b).max() < 2e-5 * np.abs(a).max(), name
    # sphere.7 at PER 2.0944 s (3 rad/s), surge: 0.2224456 rho g; the .out prints it
    surge = out.drift_force.sel(influenced_dof="Surge").sel(omega=3.0, method="nearest")
    rho_g = out.attrs["rho"] * out.attrs["g"]
    assert float(surge.isel(wave_direction=0)) == pytest.approx(0.2224456 * rho_g, rel=1e-5)


def test_nemoh_spar_qtf_is_conjugated_and_dimensional(spar):
    """OUT_QTFM_N_0.dat: ω = 0.30, 0.25 rad/s, DOF 5 (pitch about (0, 0, −78) m),
    Re/ρg 1.759121, Im/ρg −6.183337; NEMOH's exp(−iωt) conjugated."""
    assert list(spar.attrs["reference_point"]) == [0.0, 0.0, -78.0]
    assert _at(spar, "qtf_difference", 0.30, 0.25, "Pitch") == pytest.approx(
        RHO_G * (1.759121 + 6.183337j), rel=1e-6
    )
    assert _at(spar, "qtf_difference", 0.25, 0.30, "Pitch") == pytest.approx(
        RHO_G * (1.759121 - 6.183337j), rel=1e-6
    )
    # the sum QTF: the first row of OUT_QTFP_N_0.dat (ω = 0.25, 0.25, surge), conjugated
    assert _at(spar, "qtf_sum", 0.25, 0.25, "Surge") == pytest.approx(
        RHO_G * (-0.4703354e-3 + 1.467730j), rel=1e-6
    )
    s = qtf_table(spar, "sum").values
    assert np.array_equal(s, np.swapaxes(s, 0, 1))


def test_aqwa_listing_mean_drift(shared_data):
    ds = cummins.read(shared_data / PEND)
    assert list(np.degrees(ds.wave_direction.values)) == [-180.0, -90.0, 0.0, 90.0, 180.0]
    surge = ds.drift_force.sel(influenced_dof="Surge")
    # first row of the SURGE(X) table: 0.100 rad/s, 7.42E-04 ... 6.82E-04 N/m²
    assert surge.isel(omega=0).values == pytest.approx(
        [7.42e-4, 2.95e-4, 7.10e-4, 3.21e-4, 6.82e-4]
    )
    yaw = ds.drift_force.sel(influenced_dof="Yaw")
    assert np.abs(yaw).max() > 0  # all six tables read


def test_second_order_data_survive_netcdf(oc4, shared_data, tmp_path):
    cummins.write(oc4, tmp_path / "oc4.nc")
    back = cummins.read(tmp_path / "oc4.nc")
    for name in ("qtf_difference", "qtf_sum"):
        assert np.array_equal(back[name].values, oc4[name].values)
        assert back[name].attrs["source"] == oc4[name].attrs["source"]
    sphere = cummins.read(shared_data / SPHERE)
    cummins.write(sphere, tmp_path / "sphere.nc")
    again = cummins.read(tmp_path / "sphere.nc")
    for name in ("drift_force", "drift_force_pressure", "drift_force_momentum"):
        assert np.array_equal(again[name].values, sphere[name].values)


def test_axes_and_reference_point_transform_the_qtf(oc4):
    back = cummins.change_axes(cummins.change_axes(oc4, "z-down"), "z-up")
    assert np.array_equal(back.qtf_difference.values, oc4.qtf_difference.values)
    down = cummins.change_axes(oc4, "z-down")
    # sway, heave, pitch... change sign with the axes: T = diag(1, -1, -1, 1, -1, -1)
    assert np.array_equal(
        down.qtf_sum.sel(influenced_dof="Heave").values,
        -oc4.qtf_sum.sel(influenced_dof="Heave").values,
    )
    # the moment about a point 2 m to port: M_z' = M_z + 2 F_x, M_x' = M_x - 2 F_z
    moved = cummins.move_reference_point(oc4, [0.0, 2.0, 0.0])
    q, m = oc4.qtf_difference, moved.qtf_difference
    assert np.allclose(
        m.sel(influenced_dof="Yaw"), q.sel(influenced_dof="Yaw") + 2 * q.sel(influenced_dof="Surge")
    )
    assert np.allclose(
        m.sel(influenced_dof="Roll"),
        q.sel(influenced_dof="Roll") - 2 * q.sel(influenced_dof="Heave"),
    )


def test_info_says_what_second_order_data_a_run_holds(shared_data):
    from click.testing import CliRunner

    from cummins.cli import main

    result = CliRunner().invoke(main, ["info", str(shared_data / OC4)])
    assert result.exit_code == 0, result.output
    assert "qtf_difference: 56x56 frequencies 0.25–3 rad/s" in result.output
    result = CliRunner().invoke(main, ["info", str(shared_data / SPHERE), "--json"])
    assert '"drift_force_momentum"' in result.output


def test_capytaine_far_field_drift_against_wamit(shared_data):
    """tests/data/sphere_drift_capytaine.nc: Capytaine 3.0's far-field drift of the body
    of the corpus's WAMIT mean-drift sphere (tests/data/make_drift_sphere.py). Read as
    ``drift_force`` (surge, sway, yaw; the rest recorded as not computed), it agrees with
    WAMIT's momentum conservation (.8) of the same body: at the peak (3.55 rad/s) within
    0.8 % measured, on 3.4–4.7 rad/s within 6.6 %."""
    import xarray as xr

    path = DATA / "sphere_drift_capytaine.nc"
    ds = cummins.read(path)
    assert ds.drift_force.attrs["dofs_computed"] == "Surge Sway Yaw"
    raw = xr.open_dataset(path)
    surge_raw = raw.drift_force_surge.sel(complex="re").isel(wave_direction_k=0, wave_direction_l=0)
    surge = ds.drift_force.sel(influenced_dof="Surge").isel(wave_direction=0)
    assert np.array_equal(surge.values, surge_raw.values)
    wamit = cummins.read(shared_data / SPHERE).drift_force_momentum
    reference = wamit.sel(influenced_dof="Surge").isel(wave_direction=0).interp(omega=ds.omega)
    peak = int(np.argmax(surge.values))
    assert float(surge[peak]) == pytest.approx(float(reference[peak]), rel=0.05)
    band = (ds.omega.values > 3.4) & (ds.omega.values < 4.7)
    assert np.all(np.abs(surge.values[band] / reference.values[band] - 1) < 0.15)


@pytest.mark.parametrize("case", [OC4, SPAR], ids=["oc4-wamit", "oc3-spar-nemoh"])
def test_qtf_round_trip_through_a_wamit_12d_file(shared_data, tmp_path, case):
    """The QTF written as WAMIT writes it (for OpenFAST HydroDyn) reads back through the
    WAMIT reader beside the OC4 .1 to 1e-7 of its largest value (9 significant digits of
    the periods, 8 of the values); the NEMOH spar's too."""
    import shutil

    ds = cummins.read(shared_data / case)
    run = tmp_path / "run"
    run.mkdir()
    for suffix in (".1", ".hst"):
        shutil.copy(shared_data / OC4.replace(".1", suffix), run / f"qtf{suffix}")
    cummins.write(ds, run / "qtf.12d")
    cummins.write(ds, run / "qtf.12s")
    back = cummins.read(run / "qtf.1", rho=ds.attrs["rho"], g=ds.attrs["g"])
    for name in ("qtf_difference", "qtf_sum"):
        a, b = ds[name].values, back[name].values
        assert np.abs(a - b).max() < 1e-7 * np.abs(a).max()
        assert np.allclose(back[name].qtf_omega, ds[name].qtf_omega, rtol=1e-8)
    with pytest.raises(cummins.HydroDataError, match="no sum-frequency QTF"):
        cummins.write(cummins.read(shared_data / SPHERE), tmp_path / "sphere.12s")


def test_mean_drift_in_the_bemio_h5(shared_data, tmp_path):
    """Where WEC-Sim reads it: body1/hydro_coeffs/mean_drift/control_surface/val (and
    momentum_conservation), normalised by rho g, shaped like the excitation."""
    import h5py

    ds = cummins.read(shared_data / SPHERE)
    cummins.write(ds, tmp_path / "sphere.h5")
    with h5py.File(tmp_path / "sphere.h5") as f:
        group = f["body1/hydro_coeffs/mean_drift"]
        assert set(group) == {"control_surface", "momentum_conservation", "pressure_integration"}
        cs = group["control_surface/val"][()]
        assert cs.shape == f["body1/hydro_coeffs/excitation/re"].shape
        rho_g = ds.attrs["rho"] * ds.attrs["g"]
        expected = ds.drift_force.transpose("influenced_dof", "wave_direction", "omega").values
        assert np.allclose(cs * rho_g, expected)
    back = cummins.read(tmp_path / "sphere.h5")
    assert np.array_equal(back.drift_force_momentum.values, ds.drift_force_momentum.values)


def test_the_report_draws_the_qtf(shared_data):
    from cummins.cli.html_report import _second_order_section

    section = _second_order_section(cummins.read(shared_data / OC4))
    assert section is not None and section.body.count("<img") == 2
    assert "qtf_sum: 56x56 frequencies" in section.body


def test_a_dot1_takes_the_drift_of_its_out_when_the_run_wrote_no_dot7():
    """The demo tanker has no .7/.8/.9 but its .out prints pressure-integration drift
    tables: tanker.1 reads them (was: no drift_force, '--second-order newman' refused)."""
    ds = cummins.read(cummins.demo_files() / "tanker.1")
    out = cummins.read(cummins.demo_files() / "tanker.out")
    assert np.array_equal(ds.drift_force.values, out.drift_force.values)
    assert "mean drift from tanker.out" in ds.attrs["history"]


def test_convert_says_where_the_mean_drift_goes(shared_data, tmp_path):
    """convert sphere.1 x.1 named the QTFs only; x.12d pointed to Newman's approximation,
    which convert does not do."""
    from click.testing import CliRunner

    from cummins.cli import main

    source = str(shared_data / SPHERE)
    result = CliRunner().invoke(main, ["convert", source, str(tmp_path / "x.1")])
    assert result.exit_code == 0, result.output
    assert "the mean drift: x.7" in " ".join(result.output.split())
    result = CliRunner().invoke(main, ["convert", source, str(tmp_path / "x.12d")])
    assert result.exit_code == 1
    assert ".7/.8/.9" in result.output and "use the mean drift" not in result.output
