"""Command-line behaviours checked by value, each against a reference computed here.

The options below were only ever run for their exit status (or not at all): starting
from rest, the wave spectra and spreading, quadratic damping, the energy balance, the
MSS export read back, the DP demo's current and wind, the LF model's kernel route and
viscous surge damping, identify-damping's bounded method and coupling terms, and the
findings of ``check`` with its exit status.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.integrate
import scipy.signal
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main

VISCOUS = ["--viscous-damping", "Surge", "1e6", "--viscous-damping", "Sway", "1e6",
           "--viscous-damping", "Yaw", "1e10"]  # fmt: skip


def _run(args, code=0):
    result = CliRunner().invoke(main, [str(a) for a in args])
    assert result.exit_code == code, result.output
    assert "Traceback" not in result.output
    return result


def _open(path) -> xr.Dataset:
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        return ds.load()


@pytest.fixture(scope="module")
def fitted(shared_data, tmp_path_factory):
    """The tanker's radiation model from `cummins fit`, with its MSS export."""
    folder = tmp_path_factory.mktemp("fit")
    model, abc = folder / "model.nc", folder / "tankerABC.mat"
    _run(["fit", shared_data / "mss" / "tanker" / "tanker.1", "-o", model, "--mss", abc])
    return model, abc


def test_every_command_declares_each_option_once():
    """click warns of a duplicate option only when the command runs: none may have one."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name in main.commands:
            _run([name, "--help"])


def test_mss_export_reads_back_as_the_same_model(fitted):
    """`fit --mss` writes MSS's vesselABC; read back, its fluid memory has the fitted
    model's K(jω) (in MSS's z-down axes: T K T with T = diag(1, −1, −1, 1, −1, −1))."""
    from cummins.io.mss_abc import read_mss_abc
    from cummins.radiation.model import RadiationModel

    model_path, abc = fitted
    model = RadiationModel.load(model_path)
    back = read_mss_abc(abc)
    w = np.linspace(0.1, 2.0, 40)
    k = model.frequency_response(w).values
    t = np.diag([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
    k_back = back.frequency_response(w).values
    expected = (
        np.einsum("ij,wjk,kl->wil", t, k, t)
        if back.attrs.get("axis_convention", "z-down") == "z-down"
        else k
    )
    assert np.abs(k_back - expected).max() < 1e-9 * np.abs(k).max()
    np.testing.assert_allclose(np.diag(back.added_mass_inf), np.diag(model.added_mass_inf))


def test_simulation_from_rest_joins_the_stationary_one(fitted, tmp_path):
    """--start rest: motion and velocity zero at t = 0; the stationary start is the
    frequency-domain solution at t = 0. Once the transient has decayed (heave and pitch
    are heavily damped, ζ ≈ 0.18) the two runs agree to 1 % of the heave amplitude."""
    model, _ = fitted
    common = [
        "simulate",
        model,
        "--regular",
        "--wave-period",
        "9",
        "--heading",
        "150",
        "--duration",
        "300",
        "--dt",
        "0.1",
        *VISCOUS,
        "--viscous-damping",
        "Roll",
        "5e9",
    ]
    rest, stationary = tmp_path / "rest.nc", tmp_path / "stationary.nc"
    _run([*common, "-o", rest, "--start", "rest"])
    _run([*common, "-o", stationary])
    a, b = _open(rest), _open(stationary)
    assert np.all(a.motion.values[0] == 0) and np.all(a.velocity.values[0] == 0)
    heave_a, heave_b = a.motion.sel(dof="Heave").values, b.motion.sel(dof="Heave").values
    amplitude = np.abs(heave_b).max()
    assert abs(heave_b[0]) > 0.1 * amplitude
    late = a.time.values > 200
    assert np.abs(heave_a[late] - heave_b[late]).max() < 0.01 * amplitude
    assert np.abs(heave_a[:20] - heave_b[:20]).max() > 0.1 * amplitude  # it did start apart


#: 6 steps per period of the shortest component (the Torsethaugen's reach 6 rad/s here)
ELEVATION_DT = 0.15


def _elevation(model, folder, name, *options):
    out = folder / f"{name}.nc"
    _run(
        [
            "simulate",
            model,
            "--hs",
            "4",
            "--tp",
            "10",
            *options,
            "--duration",
            "2000",
            "--dt",
            f"{ELEVATION_DT:g}",
            "--seed",
            "3",
            *VISCOUS,
            "-o",
            out,
        ]
    )
    return _open(out).wave_elevation.values


def _peak_share(eta: np.ndarray, tp: float = 10.0) -> float:
    """Share of the elevation's energy within ±10 % of the peak frequency (Welch)."""
    f, s = scipy.signal.welch(eta, fs=1.0 / ELEVATION_DT, nperseg=2048)
    w = 2 * np.pi * f
    near = (w > 0.9 * 2 * np.pi / tp) & (w < 1.1 * 2 * np.pi / tp)
    return float(s[near].sum() / s.sum())


@pytest.mark.parametrize("spectrum", ["jonswap", "pm", "torsethaugen"])
def test_wave_spectra_of_the_command_line(fitted, tmp_path, spectrum):
    """The recorded wave elevation has the significant height asked for: 4σ within 5 %
    (the components' amplitudes are deterministic; the sample variance of 2000 s of 200
    components varies by ~2 %)."""
    eta = _elevation(fitted[0], tmp_path, spectrum, "--spectrum", spectrum)
    assert 4 * eta.std() == pytest.approx(4.0, rel=0.05)


def test_jonswap_peakedness_of_the_command_line(fitted, tmp_path):
    """--gamma 7 puts more of the energy near the peak than --gamma 1 (Pierson–Moskowitz
    shape): the JONSWAP peak enhancement factor at ω_p is γ itself."""
    sharp = _peak_share(_elevation(fitted[0], tmp_path, "g7", "--gamma", "7"))
    flat = _peak_share(_elevation(fitted[0], tmp_path, "g1", "--gamma", "1"))
    assert sharp > 1.4 * flat


def test_short_crested_seas_excite_sway_in_head_seas(fitted, tmp_path):
    """Long-crested head seas give no sway on a symmetric hull; cos-2s spreading (s = 2)
    does: sway RMS at least 20 times larger (measured ratio ≫ 100)."""
    model, _ = fitted
    common = [
        "simulate",
        model,
        "--hs",
        "4",
        "--tp",
        "10",
        "--heading",
        "180",
        "--duration",
        "600",
        "--dt",
        "0.25",
        "--seed",
        "1",
        *VISCOUS,
    ]
    long_crested, short_crested = tmp_path / "long.nc", tmp_path / "short.nc"
    _run([*common, "-o", long_crested])
    _run([*common, "--spreading", "2", "--directions", "9", "-o", short_crested])
    sway_long = _open(long_crested).motion.sel(dof="Sway").values.std()
    sway_short = _open(short_crested).motion.sel(dof="Sway").values.std()
    assert sway_short > 20 * sway_long


def test_quadratic_roll_damping_equals_its_equivalent_linearisation(fitted, tmp_path, shared_data):
    """Regular beam waves near the roll resonance with quadratic damping b₂|φ̇|φ̇: the
    roll amplitude φ_a equals that of the linear damping b_eq = 8/(3π) b₂ ω φ_a (the
    describing function, exact for the fundamental harmonic) within 3 %; and the
    energy the run records as viscous work is ∫ξ̇ᵀB_vξ̇ recomputed here from its record."""
    model, _ = fitted
    period, b2 = 13.0, 2.0e10
    common = [
        "simulate",
        model,
        "--regular",
        "--wave-period",
        period,
        "--heading",
        "90",
        "--wave-amplitude",
        "1",
        "--duration",
        "1200",
        "--dt",
        "0.1",
        *VISCOUS,
    ]
    quad = tmp_path / "quad.nc"
    _run([*common, "--quadratic-damping", "Roll", b2, "-o", quad, "--start", "rest"])
    run = _open(quad)
    late = run.time.values > 900
    roll = run.motion.sel(dof="Roll").values[late]
    amplitude = 0.5 * (roll.max() - roll.min())
    b_eq = 8.0 / (3.0 * np.pi) * b2 * (2 * np.pi / period) * amplitude
    lin = tmp_path / "lin.nc"
    _run([*common, "--viscous-damping", "Roll", b_eq, "-o", lin])
    roll_lin = _open(lin).motion.sel(dof="Roll").values[late]
    assert 0.5 * (roll_lin.max() - roll_lin.min()) == pytest.approx(amplitude, rel=0.03)
    # viscous work of the linear run, recomputed from its record (Simpson, not trapezoid)
    lin_run = _open(lin)
    from cummins.radiation.model import RadiationModel

    given = {"Surge": 1e6, "Sway": 1e6, "Roll": b_eq, "Yaw": 1e10}
    ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.1")
    vessel = cummins.vessel_from_hydrodb(ds, RadiationModel.load(model), viscous_damping=given)
    b_v = vessel.viscous_damping  # the given values and the .frc's external damping
    v = lin_run.velocity.values
    power = np.einsum("ti,ij,tj->t", v, b_v, v)
    work = scipy.integrate.simpson(power, x=lin_run.time.values)
    assert lin_run.attrs["energy_viscous"] == pytest.approx(work, rel=1e-3)
    power_in = np.einsum("ti,ti->t", v, lin_run.external_force.values)
    work_in = scipy.integrate.simpson(power_in, x=lin_run.time.values)
    assert lin_run.attrs["energy_input"] == pytest.approx(work_in, rel=1e-3)
    assert lin_run.attrs["energy_relative_residual"] < 1e-2


def test_dp_demo_holds_against_current_and_wind(tmp_path):
    """With a 0.5 m/s current and 15 m/s wind from the north-east the DP still holds the
    ship (watch circle below 15 m), and its mean thrust opposes the mean environmental
    force pushing towards the south-west: mean thrust North and East both > 0."""
    out = tmp_path / "dp"
    _run(
        [
            "dp-demo",
            "-o",
            out,
            "--duration",
            "300",
            "--seed",
            "1",
            "--current",
            "0.5",
            "--current-from",
            "45",
            "--wind",
            "15",
            "--wind-from",
            "45",
        ]
    )
    run = _open(out / "run.nc")
    radius = np.hypot(run.eta.sel(dof="North").values, run.eta.sel(dof="East").values)
    assert radius.max() < 15.0
    late = run.time.values > 150
    heading = run.eta.sel(dof="Yaw").values[late].mean()
    thrust_body = run.thrust.values[late].mean(axis=0)
    c, s = np.cos(heading), np.sin(heading)
    north = c * thrust_body[0] - s * thrust_body[1]
    east = s * thrust_body[0] + c * thrust_body[1]
    assert north > 0 and east > 0


def test_lf_model_kernel_route_and_viscous_surge_damping(shared_data, tmp_path):
    """--route kernel gives the zero-frequency surge added mass from K(t) within 5 % of
    the frequency route (the solver's ω = 0 row; measured 2.8 %, the truncation of
    ∫τK); --surge-damping β α puts β e^{−αω} at the surge model's frequency (ω = 0) into
    the viscous damping (besides the data's own): β exactly; the total damping is the
    potential plus the viscous one."""
    data = shared_data / "mss" / "tanker" / "tanker.1"
    freq, kern = tmp_path / "f.nc", tmp_path / "k.nc"
    _run(["lf-model", data, "-o", freq])
    _run(["lf-model", data, "-o", kern, "--route", "kernel", "--surge-damping", "3e5", "0.5"])
    a, b = _open(freq), _open(kern)
    surge = {"influenced_dof": "Surge", "radiating_dof": "Surge"}
    assert float(a.frequency.sel(dof="Surge")) == 0.0
    a0 = float(cummins.read(data).added_mass_zero.sel(surge))
    assert float(a.added_mass.sel(surge)) == pytest.approx(a0, rel=1e-6)
    assert float(b.added_mass.sel(surge)) == pytest.approx(a0, rel=0.05)
    added = float(b.viscous_damping.sel(surge)) - float(a.viscous_damping.sel(surge))
    assert added == pytest.approx(3e5, rel=1e-9)  # besides the .frc's external damping
    np.testing.assert_allclose(
        b.damping.values, b.potential_damping.values + b.viscous_damping.values, rtol=1e-12
    )


def test_check_findings_and_exit_status(shared_data, tmp_path):
    """`check` names a negative roll restoring, the Kramers–Kronig inconsistency of a heave
    added mass scaled by 1.5 (B unchanged) and a grid too coarse for K(t) (every 8th
    frequency), exits 0 on such usable-but-suspect data and 1 on data it cannot use (a
    negative surge mass: the inertia is not positive definite)."""
    import json

    ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.1")
    bad = ds.copy(deep=True)
    roll = {"influenced_dof": "Roll", "radiating_dof": "Roll"}
    heave = {"influenced_dof": "Heave", "radiating_dof": "Heave"}
    bad["hydrostatic_stiffness"].loc[roll] *= -1
    bad["added_mass"].loc[heave] = bad["added_mass"].loc[heave] * 1.5
    path = tmp_path / "bad.nc"
    cummins.write(bad, path)
    result = _run(["check", path, "--json", tmp_path / "report.json"], code=0)
    findings = json.loads((tmp_path / "report.json").read_text())["findings"]
    flagged = {(f["check"], f.get("where")) for f in findings if f["severity"] == "warning"}
    assert ("hydrostatics", "Roll") in flagged
    kk = [f for f in findings if f["check"] == "retardation" and f.get("where") == "Heave"]
    assert kk[0]["severity"] == "warning" and "Kramers" in kk[0]["message"]
    good_kk = [f for f in cummins.check(ds).findings if f.check == "retardation"]
    assert next(f for f in good_kk if f.where == "Heave").severity == "ok"
    assert "C_Roll" in result.output
    coarse = cummins.check(ds.isel(omega=slice(None, None, 8)))
    assert any(f.check == "frequency_grid" and f.severity == "warning" for f in coarse.findings)
    impossible = ds.copy(deep=True)
    impossible["inertia_matrix"].loc[{"influenced_dof": "Surge", "radiating_dof": "Surge"}] *= -1
    path = tmp_path / "impossible.nc"
    cummins.write(impossible, path)
    result = _run(["check", path], code=1)
    assert "NOT usable" in result.output and "inertia" in result.output


def test_identify_damping_bounded_with_a_coupling_term(fitted, shared_data, tmp_path):
    """A 20-minute simulated record with known roll damping b₁ = 3e8, b₂ = 2e10 and no
    cubic term, identified with linear, quadratic and cubic terms by --method bounded and
    a 'Sway acceleration' coupling term: b₁ and b₂ within 2 % (measured 0.2 %, 0.1 %),
    b₃ ≥ 0 with 0 inside its interval, every damping value ≥ 0, and the coupling term —
    absent from the simulation — below 0.1 % of the model's own sway–roll inertia
    coupling (measured 0.06 %)."""
    import json

    from cummins.radiation.model import RadiationModel

    model, _ = fitted
    record = tmp_path / "roll.nc"
    _run(
        [
            "simulate",
            model,
            "--hs",
            "6",
            "--tp",
            "12",
            "--heading",
            "100",
            "--duration",
            "1200",
            "--seed",
            "2",
            *VISCOUS,
            "--viscous-damping",
            "Roll",
            "3e8",
            "--quadratic-damping",
            "Roll",
            "2e10",
            "-o",
            record,
        ]
    )
    report = tmp_path / "report"
    _run(
        [
            "identify-damping",
            record,
            "--model",
            model,
            "--dof",
            "Roll",
            "--terms",
            "linear,quadratic,cubic",
            "--method",
            "bounded",
            *VISCOUS,
            "--coupling",
            "Sway acceleration",
            "--report",
            report,
        ]
    )
    terms = {
        t["kind"]: t
        for t in json.loads((report / "damping.json").read_text())["estimates"][0]["terms"]
    }
    assert terms["linear"]["value"] == pytest.approx(3e8, rel=0.02)
    assert terms["quadratic"]["value"] == pytest.approx(2e10, rel=0.02)
    lo, hi = terms["cubic"]["interval"]
    assert terms["cubic"]["value"] >= 0 and lo <= 0.0 <= hi
    assert all(terms[k]["value"] >= 0 for k in ("linear", "quadratic", "cubic"))
    ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.1")
    m = ds.inertia_matrix.values + RadiationModel.load(model).added_mass_inf
    assert abs(terms["acceleration"]["value"]) < 1e-3 * abs(m[3, 1])


def test_the_fit_table_of_three_bodies_fits_80_columns(tmp_path):
    """A row of three buoys (18 DOFs): every coupling of the table named in full, short
    (``b1.Surge-b2.Pitch``), within 80 columns; the hundred-odd negligible couplings
    counted, a dozen named (all in the model file), not printed on one line of 2 700
    characters."""
    from pathlib import Path

    from cummins.cli.fit import NEGLIGIBLE_LISTED

    data = Path(__file__).parent / "data" / "three_buoys_capytaine.nc"
    model = tmp_path / "model.nc"
    output = _run(["fit", data, "-o", model]).output.splitlines()
    start = next(i for i, line in enumerate(output) if line.lstrip().startswith("coupling"))
    end = next(i for i in range(start + 2, len(output)) if not output[i].strip())
    table = output[start:end]
    assert all(len(line) <= 80 and "…" not in line for line in table), table
    rows = [line.split()[0] for line in table[2:]]
    assert "b1.Surge" in rows and "b1.Surge-b2.Surge" in rows and "b1.Pitch-b3.Pitch" in rows
    negligible = next(line for line in output if "negligible couplings" in line)
    saved = cummins.radiation.RadiationModel.load(model).attrs["negligible_couplings"]
    pairs = [c for c in saved if "-" in c]
    assert negligible.startswith(f"{len(pairs)} negligible couplings")
    assert f"and {len(pairs) - NEGLIGIBLE_LISTED} more" in negligible
    assert len(negligible) < 600
