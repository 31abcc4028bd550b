"""Multi-body files as users have them (issue 30, point 7): a WAMIT ``.out``'s displaced
volume per body (the mass defaults to ρ∇), a Capytaine dataset whose DOFs name a body for
some and none for others (WecOptTool's ``float__Heave``, ``spar__Heave``, ``Surge``,
``Pitch``), and NEMOH's lines of additional information (meant for generalised modes,
which NEMOH does not compute)."""

import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import ArgumentError, HydroDataError
from cummins.seakeeping.frequency_domain import motion_rao
from cummins.seakeeping.waves import regular_wave
from cummins.timedomain.simulate import simulate_waves
from cummins.vessel import vessel_from_hydrodb

DATA = Path(__file__).parent / "data"
#: WEC-Sim's RM3 radii of gyration (float, spar), m
RADII = ([5.367, 5.418, 7.148], [10.319, 10.319, 5.674])


@pytest.fixture(scope="module")
def rm3_out(corpus):
    return corpus / "WEC-Sim" / "wamit_RM3_2body" / "rm3.out"


def test_the_wamit_out_gives_each_body_its_displaced_volume(rm3_out):
    ds = cummins.read(rm3_out, rho=1000.0)
    # the .out's "Volumes (VOLX,VOLY,VOLZ)" of each body: 725.833 and 886.687 m³
    np.testing.assert_allclose(ds.attrs["displaced_volume"], [725.833, 886.687], rtol=1e-5)
    with_mass = cummins.with_inertia(ds, radii_of_gyration=RADII)
    m = with_mass.inertia_matrix
    for body, volume in (("body1", 725.833), ("body2", 886.687)):
        mass = float(m.sel(influenced_dof=f"{body}__Surge", radiating_dof=f"{body}__Surge"))
        assert mass == pytest.approx(1000.0 * volume, rel=1e-5)  # ρ∇, WEC-Sim's "equilibrium"
    assert "rho * volume" in with_mass.attrs["history"]


def test_info_with_radii_only_works_on_the_wamit_out(rm3_out):
    args = ["info", str(rm3_out), "--rho", "1000"]
    for radii in RADII:
        args += ["--radii-of-gyration", *(str(r) for r in radii)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert "725.833, 886.688 m³" in result.output  # the mean of VOLX, VOLY, VOLZ
    assert "mass of body2 = rho * volume = 886688 kg" in " ".join(result.output.split())


def test_a_capytaine_multibody_gives_each_body_its_displaced_volume():
    ds = cummins.read(DATA / "float_spar_capytaine.nc")
    volumes = np.asarray(ds.attrs["displaced_volume"])
    masses = [
        float(ds.inertia_matrix.sel(influenced_dof=d, radiating_dof=d))
        for d in ("body1__Surge", "body2__Surge")
    ]
    # the file's masses are its displaced masses (make_float_spar.py): ρ∇ per body
    np.testing.assert_allclose(volumes * ds.attrs["rho"], masses, rtol=1e-9)


@pytest.fixture(scope="module")
def shared():
    return cummins.read(DATA / "shared_dofs_capytaine.nc")


def test_dofs_that_name_no_body_are_kept_and_said(shared):
    assert [str(d) for d in shared.influenced_dof.values] == [
        "body1__Heave",
        "body2__Heave",
        "Surge",
        "Pitch",
    ]
    assert shared.attrs["body_names"].splitlines() == ["float", "spar"]
    history = " ".join(shared.attrs["history"].split())
    assert "DOFs Surge, Pitch name no body: DOFs of the system as the file defines them" in history
    # the system's surge carries both bodies: its mass is theirs together
    m = shared.inertia_matrix
    surge = float(m.sel(influenced_dof="Surge", radiating_dof="Surge"))
    heaves = [
        float(m.sel(influenced_dof=d, radiating_dof=d)) for d in ("body1__Heave", "body2__Heave")
    ]
    assert surge == pytest.approx(sum(heaves), rel=1e-12)
    # mass properties per body need six rigid-body modes: refused with the way out
    with pytest.raises(ArgumentError, match="Surge, Pitch name no body"):
        cummins.with_inertia(shared, radii_of_gyration=RADII)


def test_read_check_fit_rao_simulate_on_shared_dofs(shared):
    assert cummins.check(shared).ok
    model = cummins.fit_radiation(shared)
    assert not model.attrs.get("failures") and list(model.dofs) == list(
        shared.influenced_dof.values
    )
    omega, period = 1.0, 2 * np.pi
    rao = motion_rao(shared, [omega], [0.0]).isel(omega=0, wave_direction=0)
    peak = np.abs(motion_rao(shared, None, [0.0]).isel(wave_direction=0)).max("omega")
    vessel = vessel_from_hydrodb(shared, model)
    run = simulate_waves(
        vessel, shared, regular_wave(1.0, period, 0.0), duration=10 * period, dt=period / 200
    )
    last = run.time.values >= run.time.values[-1] - period
    for dof in shared.influenced_dof.values:
        steady = 0.5 * np.ptp(run.motion.sel(dof=dof).values[last])
        expected = abs(complex(rao.sel(dof=dof).values))
        # the time domain against the data's RAO: measured within 0.1 % of each peak
        assert abs(steady - expected) < 0.01 * float(peak.sel(dof=dof)), dof


def test_the_command_line_runs_on_shared_dofs(tmp_path):
    data = DATA / "shared_dofs_capytaine.nc"
    runner = CliRunner()
    for args in (
        ["check", data],
        ["fit", data, "-o", tmp_path / "model.nc"],
        ["rao", data, "-o", tmp_path / "rao.nc", "--headings", "0"],
        [
            "simulate",
            tmp_path / "model.nc",
            "--hs",
            "2",
            "--tp",
            "8",
            "--heading",
            "0",
            "--duration",
            "120",
            "--seed",
            "1",
            "-o",
            tmp_path / "run.nc",
        ],
    ):
        result = runner.invoke(main, [str(a) for a in args])
        assert result.exit_code == 0, (args[0], result.output)
    assert "body1__Heave" in result.output and "Pitch" in result.output


@pytest.fixture
def nemoh_run(corpus, tmp_path):
    run = tmp_path / "oswec"
    shutil.copytree(corpus / "WEC-Sim" / "nemoh_v2.3_OSWEC_flap", run)
    return run


def _edit_cal(run: Path, number: int, replace: str, insert: list[str]) -> None:
    """Nemoh.cal with its line ``number`` (1-based) replaced and lines inserted after it."""
    path = run / "Nemoh.cal"
    lines = path.read_text().split("\n")
    lines[number - 1 : number] = [replace, *insert]
    path.write_text("\n".join(lines))


def test_nemoh_lines_of_additional_information_are_skipped_as_nemoh_does(corpus, nemoh_run):
    """NEMOH v2 skips them (v3 reads the count line only, 'reserved'): the first body's
    count set to 2 with two lines below reads the same numbers, and history says so."""
    cal = (nemoh_run / "Nemoh.cal").read_text().split("\n")
    assert "additional information" in cal[24] and cal[24].split()[0] == "0"
    _edit_cal(
        nemoh_run,
        25,
        "2  ! Number of lines of additional information",
        ["1 0. 0. 1. 0. 0. 0.", "0.5"],
    )
    edited = cummins.read(nemoh_run)
    original = cummins.read(corpus / "WEC-Sim" / "nemoh_v2.3_OSWEC_flap")
    np.testing.assert_array_equal(edited.added_mass.values, original.added_mass.values)
    np.testing.assert_array_equal(edited.excitation_force.values, original.excitation_force.values)
    assert "lines of additional information skipped, as NEMOH does" in edited.attrs["history"]


def test_a_nemoh_dof_of_type_3_is_refused_with_the_reason(nemoh_run):
    """DOF type 3 (a generalised mode): NEMOH's preprocessor stops on it ('radiation case
    3 not implemented yet'), so no results hold it."""
    cal = (nemoh_run / "Nemoh.cal").read_text().split("\n")
    heave = next(
        k for k, line in enumerate(cal) if line.startswith("1 0. 0. 1.") and "Heave" in line
    )
    _edit_cal(nemoh_run, heave + 1, "3 0. 0. 1. 0. 0. 0.  ! a generalised mode", [])
    with pytest.raises(HydroDataError, match=r"generalised mode.*not implemented yet") as error:
        cummins.read(nemoh_run)
    assert f"line {heave + 1}" in str(error.value)
