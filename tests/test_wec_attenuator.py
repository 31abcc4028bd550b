"""An attenuator (M4, Pelamis): three floating boxes in a row hinged about y, with a
rotational PTO on each hinge (``tests/data/make_attenuator.py``, Capytaine).

References no one here wrote: the frequency-domain solution with the constraint basis T
written by hand from the screw transform (u(p) = u(o) + θ × (p − o)), and ½ c ω² |Δ|², the
power of a mechanical resistance. Also the warnings for a user's slips: a hinge point
given in the wrong units, a DOF selection that holds what the joints move.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import cummins
from _batch_run import run_batch_study
from cummins.errors import AssumptionWarning
from cummins.mechanics import PTO, Joint, MechanicalSystem, assemble
from cummins.seakeeping.frequency_domain import motion_rao, pto_rao
from cummins.seakeeping.waves import regular_wave
from cummins.timedomain.harmonics import harmonic_amplitude
from cummins.timedomain.simulate import simulate_waves
from cummins.vessel import vessel_from_hydrodb

DATA = Path(__file__).parent / "data" / "attenuator_capytaine.nc"
#: The boxes' reference points (their centres of mass) and the hinges, m.
CENTRES = {"body1": (-11.0, 0.0, -1.0), "body2": (0.0, 0.0, -1.0), "body3": (11.0, 0.0, -1.0)}
HINGES = {"body1": (-5.5, 0.0, -1.0), "body3": (5.5, 0.0, -1.0)}
DAMPING = 1.0e6  # N m s/rad


@pytest.fixture(scope="module")
def attenuator():
    return cummins.read(DATA)


def hinged(dofs=None) -> MechanicalSystem:
    """The outer boxes hinged to the middle one about y, a rotational PTO on each hinge."""
    joints = tuple(
        Joint("revolute", body, "body2", axis=(0, 1, 0), point=HINGES[body], name=f"h{body[-1]}")
        for body in ("body1", "body3")
    )
    ptos = tuple(PTO(joint=j.name, damping=DAMPING) for j in joints)
    return MechanicalSystem(joints, ptos, dofs)


def skew(r) -> np.ndarray:
    """S(r) with S(r) θ = θ × r."""
    x, y, z = r
    return np.array([[0.0, z, -y], [-z, 0.0, x], [y, -x, 0.0]])


def basis_by_hand() -> np.ndarray:
    """T (18 × 8), q = (the middle box's six DOFs, the outer boxes' pitch): an outer box
    keeps the middle one's roll and yaw, pitches by its own angle about its hinge h, and
    its centre moves by u₂ + θ₂ × (h − o₂) + θ × (o − h)."""
    t = np.zeros((18, 8))
    t[6:12, :6] = np.eye(6)
    o2 = np.array(CENTRES["body2"])
    for row, body, column in ((0, "body1", 6), (12, "body3", 7)):
        h, o = np.array(HINGES[body]), np.array(CENTRES[body])
        t[row : row + 3, :3] = np.eye(3)
        t[row : row + 3, 3:6] = skew(h - o2)
        swing = skew(o - h)
        t[row : row + 3, 3] += swing[:, 0]
        t[row : row + 3, 5] += swing[:, 2]
        t[row : row + 3, column] += swing[:, 1]
        t[row + 3, 3], t[row + 4, column], t[row + 5, 5] = 1.0, 1.0, 1.0
    return t


def test_attenuator_rao_is_the_hand_built_constrained_solution(attenuator):
    """motion_rao and pto_rao with two hinges equal Tᵀ Z T q = Tᵀ F with T by hand, and
    the power is ½ c ω² |θ_outer − θ_middle|², at every frequency and heading of the
    data (body coupling on)."""
    ds = attenuator
    omega = ds.omega.values
    headings = ds.wave_direction.values
    rao = motion_rao(ds, omega, headings, system=hinged())
    pto = pto_rao(rao, ds, hinged())
    t = basis_by_hand()
    d1, d3 = t[4] - t[10], t[16] - t[10]
    m = ds.inertia_matrix.values
    c = ds.hydrostatic_stiffness.values
    x = rao.transpose("omega", "wave_direction", "dof").values
    power = pto.pto_power.transpose("omega", "wave_direction", "pto").values
    for i, w in enumerate(omega):
        a, b = ds.added_mass.values[i], ds.radiation_damping.values[i]
        z = -(w**2) * (m + a) + 1j * w * b + c
        zq = t.T @ z @ t + 1j * w * DAMPING * (np.outer(d1, d1) + np.outer(d3, d3))
        for j in range(headings.size):
            f = ds.excitation_force.values[i, j]
            q = np.linalg.solve(zq, t.T @ f)
            np.testing.assert_allclose(x[i, j], t @ q, rtol=1e-7, atol=1e-9 * np.abs(t @ q).max())
            expected = [0.5 * DAMPING * w**2 * abs(d @ q) ** 2 for d in (d1, d3)]
            np.testing.assert_allclose(power[i, j], expected, rtol=1e-7)


def test_attenuator_time_domain_against_frequency_domain(attenuator):
    """The hinged boxes in a regular wave (a = 0.5 m, T = 4.5 s, heading 45°: every DOF
    of the middle box moves): the steady motions and hinge angles within 0.5 % of the
    frequency domain and the mean PTO powers within 1 % (measured: 0.18 % and 0.17 %),
    each the power of its damper, ½ c ω² |Δ|², of the run's own hinge angle."""
    ds = attenuator
    system = hinged()
    period, amplitude, heading = 4.5, 0.5, np.deg2rad(45.0)
    omega = 2 * np.pi / period
    rao = motion_rao(ds, [omega], [heading], system=system)
    pto = pto_rao(rao, ds, system)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the fit's notes on the coarse mesh's data
        vessel = vessel_from_hydrodb(ds, system=system)
    run = simulate_waves(
        vessel, ds, regular_wave(amplitude, period, heading), duration=40 * period, dt=0.05
    )
    t = run.time.values
    x_fd = amplitude * rao.values[0, 0]
    x_td = harmonic_amplitude(t, run.motion.values, omega, 5)
    large = np.abs(x_fd) > 1e-2 * np.abs(x_fd).max()
    np.testing.assert_array_less(np.abs(np.abs(x_td[large]) / np.abs(x_fd[large]) - 1), 0.005)
    last = t > t[-1] - 5 * period + 1e-6
    for k in range(2):
        delta = harmonic_amplitude(t, run.pto_displacement.values[:, k], omega, 5)
        delta_fd = amplitude * pto.pto_displacement.values[0, 0, k]
        assert abs(abs(delta) / abs(delta_fd) - 1) < 0.005
        power = float(run.pto_power.values[last, k].mean())
        assert power == pytest.approx(amplitude**2 * pto.pto_power.values[0, 0, k], rel=0.01)
        assert power == pytest.approx(0.5 * DAMPING * omega**2 * abs(delta) ** 2, rel=1e-3)


def test_a_far_hinge_point_is_warned(attenuator):
    """A hinge given in mm (−5500 for −5.5 m) turns the box about an axis 5.5 km away:
    legal, but a slip; the warning names the joint and the point. The hinges where they
    are, and a PTO between bodies at a point near them, give none."""
    far = Joint("revolute", "body1", "body2", axis=(0, 1, 0), point=(-5500.0, 0.0, -1.0))
    with pytest.warns(AssumptionWarning, match=r"joint revolute body1-body2: the point .*5489 m"):
        assemble(attenuator, MechanicalSystem(joints=(far,)))
    with warnings.catch_warnings():
        warnings.simplefilter("error", AssumptionWarning)
        assemble(attenuator, hinged())
        near = PTO(body="body1", base="body3", axis=(1, 0, 0), point=(0, 0, 0), damping=1e5)
        assemble(attenuator, MechanicalSystem(hinged().joints, (near,)))


def test_a_dof_selection_that_holds_what_the_joints_move_is_warned(attenuator):
    """--dof with joints holds every DOF not listed: the outer boxes' heave, which their
    hinges move with the middle box's heave and pitch and their own pitch, held at zero
    leaves the four listed DOFs two motions of their four — said, naming those DOFs. Listed
    too, nothing is said; holding the surge, sway, roll and yaw (that move none of the
    listed DOFs) is not a restriction of them."""
    listed = ("body2__Heave", "body2__Pitch", "body1__Pitch", "body3__Pitch")
    with pytest.warns(AssumptionWarning, match="holds body1__Heave, body3__Heave at zero") as w:
        assembly = assemble(attenuator, hinged(listed))
    assert "keep 2 of the 4 independent motions" in str(w[0].message)
    assert assembly.basis.shape[1] == 2
    with warnings.catch_warnings():
        warnings.simplefilter("error", AssumptionWarning)
        assembly = assemble(attenuator, hinged((*listed, "body1__Heave", "body3__Heave")))
    assert assembly.basis.shape[1] == 4


def test_cli_says_the_slips_in_one_line(tmp_path):
    """The command line prints both warnings as one line each, naming the option."""
    from click.testing import CliRunner

    from cummins.cli import main

    base = ["rao", str(DATA), "-o", str(tmp_path / "r.nc"), "--n-omega", "3", "--force"]
    base += ["--omega-min", "0.5", "--omega-max", "1.5"]
    hinge = ["--joint", "revolute", "body1", "body2", "--axis", "0", "1", "0", "--point"]
    result = CliRunner().invoke(main, [*base, *hinge, "-5500", "0", "-1", "--pto-damping", "1e6"])
    assert result.exit_code == 0, result.output
    line = next(x for x in result.output.splitlines() if "check its units" in x)
    assert line.startswith("warning: --joint revolute body1 body2: the point")
    dofs = ["--dof", "body2__Heave", "--dof", "body2__Pitch", "--dof", "body1__Pitch"]
    result = CliRunner().invoke(main, [*base, *hinge, "-5.5", "0", "-1", *dofs])
    assert result.exit_code == 0, result.output
    line = next(x for x in result.output.splitlines() if "holds body1__Heave" in x)
    assert line.startswith("warning: the DOF selection (--dof)")


def test_a_model_fitted_without_body_coupling_is_refused_with_it(attenuator, tmp_path):
    """``fit --no-body-coupling`` records it in the model (and ``info`` says it);
    ``simulate`` of that model without the option would keep the cross-body radiation
    in its equations but not in the model's memory (the hinged boxes' power 18 % off the
    frequency domain): refused in one line naming the option. With the option it runs;
    a model of one body's DOFs has no coupling to miss and is taken either way."""
    from click.testing import CliRunner

    from cummins.cli import main
    from cummins.radiation.model import RadiationModel

    model_path = tmp_path / "model.nc"
    dofs = [f"--dof={body}__{name}" for body in CENTRES for name in ("Heave", "Pitch")]
    hinges = [
        *("--joint", "revolute", "body1", "body2", "--axis", "0", "1", "0"),
        *("--point", "-5.5", "0", "-1", "--pto-damping", "1e6"),
        *("--joint", "revolute", "body3", "body2", "--axis", "0", "1", "0"),
        *("--point", "5.5", "0", "-1", "--pto-damping", "1e6"),
    ]
    runner = CliRunner()
    result = runner.invoke(
        main, ["fit", str(DATA), *dofs, *hinges, "--no-body-coupling", "-o", str(model_path)]
    )
    assert result.exit_code in (0, 3), result.output
    assert RadiationModel.load(model_path).attrs["body_coupling"] == "off"
    info = runner.invoke(main, ["info", str(model_path)])
    assert "body_coupling" in info.output and "off" in info.output
    sea = ["--regular", "--wave-period", "4.5", "--wave-amplitude", "0.5", "--heading", "0"]
    run = ["simulate", str(model_path), *dofs, *hinges, *sea, "--duration", "20"]
    result = runner.invoke(main, [*run, "-o", str(tmp_path / "a.nc")])
    assert result.exit_code == 2, result.output
    line = next(x for x in result.output.splitlines() if x.startswith("error:"))
    assert "fitted with the body coupling off (--no-body-coupling" in line
    result = runner.invoke(main, [*run, "--no-body-coupling", "-o", str(tmp_path / "b.nc")])
    assert result.exit_code == 0, result.output
    one_body = MechanicalSystem(dofs=("body1__Heave", "body1__Pitch"), body_coupling=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = vessel_from_hydrodb(attenuator, system=one_body).radiation
        assert model.attrs["body_coupling"] == "off"
        vessel_from_hydrodb(attenuator, model, system=MechanicalSystem(dofs=one_body.dofs))


def test_a_model_of_the_free_bodies_used_with_joints_says_to_fit_with_them(attenuator):
    """A model fitted without the system holds DOFs the joints hold at zero: refused, as
    before, but saying so and how to mend it (fit with the same options), not that it
    was "fitted to other data" — the data are the same."""
    from cummins.errors import HydroDataError

    free = MechanicalSystem(dofs=("body1__Heave", "body1__Pitch"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = vessel_from_hydrodb(attenuator, system=free).radiation
    with pytest.raises(HydroDataError) as error:
        vessel_from_hydrodb(attenuator, model, system=MechanicalSystem(dofs=("body1__Heave",)))
    text = str(error.value)
    assert "other data" not in text and "let only body1__Heave move" in text
    assert "same --dof, --joint, --pto and --no-body-coupling options" in text


def test_the_joint_pre_load_is_said_where_the_system_is(attenuator, tmp_path):
    """The fore box ballasted to half its displacement and hinged to the ground 2 m below
    its centre carries F = ½ρ∇g up through the hinge: the pre-load stiffness F (z_o − z_h)
    = 2F about it (docs/wec.md) is printed under the system by rao (and simulate, fit)
    and recorded in the RAO file (attribute joint_preload), not only in the history."""
    from click.testing import CliRunner

    from cummins.cli import main
    from cummins.mass_properties import with_inertia

    rho, g, volume = 1025.0, 9.81, 80.0
    ds = with_inertia(
        attenuator,
        mass=[0.5 * rho * volume, rho * volume, rho * volume],
        center_of_gravity=list(CENTRES.values()),
        radii_of_gyration=[[1.3, 2.9, 3.1]] * 3,
    )
    force = 0.5 * rho * volume * g
    hinge = Joint("revolute", "body1", "ground", axis=(0, 1, 0), point=(-11.0, 0.0, -3.0))
    assembly = assemble(ds, MechanicalSystem(joints=(hinge,)))
    assert f"{2 * force:+.4g} N·m/rad on body1__Pitch" in assembly.preload
    path = tmp_path / "ballasted.nc"
    cummins.write(ds, path)
    args = ["rao", str(path), "-o", str(tmp_path / "r.nc"), "--n-omega", "3", "--force"]
    args += ["--omega-min", "0.5", "--omega-max", "1.5", "--joint", "revolute", "body1"]
    args += ["ground", "--axis", "0", "1", "0", "--point", "-11", "0", "-3"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert f"  joint pre-load: {2 * force:+.4g} N·m/rad on body1__Pitch" in result.output
    with xr.open_dataset(tmp_path / "r.nc", engine="h5netcdf") as rao:
        assert f"{2 * force:+.4g}" in rao.rao.attrs["joint_preload"]


def test_a_study_shows_its_cases_warnings_once_each_in_one_line(attenuator, tmp_path):
    """A PTO study of the hinged boxes whose data lack the displaced volumes (so every
    case warns that the joints' pre-load is left out): the warning is one line of
    ``batch``, once — the Dask workers printed it raw (the code's path and line, the
    source line), once per case."""
    pytest.importorskip("distributed")
    ds = attenuator.copy()
    del ds.attrs["displaced_volume"]
    cummins.write(ds, tmp_path / "boxes.nc")
    result = run_batch_study(
        tmp_path,
        "data: boxes.nc\nanalysis: rao\n"
        "grid: {heading: [0], hs: [1], tp: [5, 6, 7]}\n"
        "system:\n  joints:\n"
        "    - {kind: revolute, body: body1, base: body2, axis: [0, 1, 0],"
        " point: [-5.5, 0, -1], pto: {damping: 1.0e+6}}\n",
    )
    output = result.stdout + result.stderr
    assert result.returncode == 0, output
    lines = [x for x in output.splitlines() if "pre-load is not included" in x]
    assert len(lines) == 1 and lines[0].startswith("warning: "), output
    assert "AssumptionWarning" not in output and ".py:" not in output, output


def test_the_rao_report_gives_no_peak_where_the_waves_do_not_move_the_pto(tmp_path):
    """The middle box on a hinge about y through its centre, to the ground: in beam seas
    the row of boxes is symmetric fore and aft, its pitch is not excited and the power RAO
    is rounding, ~1e-30 kW/m², whose "largest value" the report printed with an ω and a
    period; it says 0 with no frequency now. Head seas keep theirs."""
    import html
    import re

    from click.testing import CliRunner

    from cummins.cli import main

    rao = tmp_path / "rao.nc"
    hinges = [
        *("--joint", "revolute", "body2", "ground", "--axis", "0", "1", "0"),
        *("--point", "0", "0", "-1", "--pto-damping", "1e6"),
    ]
    runner = CliRunner()
    result = runner.invoke(main, ["rao", str(DATA), *hinges, "-o", str(rao)])
    assert result.exit_code == 0, result.output
    result = runner.invoke(main, ["report", str(rao), "-o", str(tmp_path / "r.html")])
    assert result.exit_code == 0, result.output
    page = (tmp_path / "r.html").read_text(encoding="utf-8")
    rows = {}
    for row in re.findall(r"<tr>(.*?)</tr>", page):
        cells = [html.unescape(c) for c in re.findall(r"<td[^>]*>(.*?)</td>", row)]
        if cells and cells[0] == "pto1":
            rows[float(cells[1])] = cells
    assert rows[90.0][2:] == ["0", "—", "—", "—", "—"]
    assert float(rows[0.0][2]) > 1 and rows[0.0][3] != "—"


def test_wecsims_rotational_constraint_is_the_revolute_joint(attenuator):
    """WEC-Sim calls a hinge a "Rotational" constraint: ``--joint rotational`` (any case)
    is the revolute joint, and an unknown kind's message gives WEC-Sim's names."""
    from cummins.errors import ArgumentError

    joint = Joint("Rotational", "body1", "body2", axis=(0, 1, 0), point=HINGES["body1"])
    assert joint.kind == "revolute"
    with pytest.raises(ArgumentError, match="WEC-Sim's Rotational is revolute"):
        Joint("floating", "body1", "ground")


def test_a_dof_named_with_the_files_body_name_says_its_label(tmp_path):
    """Capytaine names the DOFs with the bodies' names (fore__Pitch), cummins with their
    numbers (body1__Pitch), while --joint takes either body name: a --dof or a PTO's DOF
    written the file's way is refused, as before, saying which label it is."""
    from click.testing import CliRunner

    from cummins.cli import main

    base = ["rao", str(DATA), "-o", str(tmp_path / "r.nc"), "--n-omega", "3"]
    for extra, option in (
        (["--dof", "fore__Pitch"], "--dof"),
        (["--pto", "fore__Pitch", "mid__Pitch", "--pto-damping", "1e5"], "--pto fore__Pitch"),
    ):
        result = CliRunner().invoke(main, [*base, *extra])
        assert result.exit_code == 2, result.output
        assert option in result.output and "fore__Pitch is body1__Pitch here" in result.output
