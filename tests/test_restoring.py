"""The restoring is complete and consistent with the mass and centre of gravity of the
equation of motion: hydrostatics plus the weight's terms, with what the files hold
detected (or stated) and never counted twice.

References: the moment of the weight differentiated numerically (the weight's terms);
WAMIT's box barge computed with the centre of gravity at the waterline, against the
analytic box C44 = ρg(LB³/12 + ∇z_B) − m g z_G; Capytaine's ``hydrostatic_stiffness``
computed here with and without a mass and centre of mass (the weight's part of two
Capytaine runs, and a Capytaine NetCDF file through the reader); WAMIT's tanker, whose
``.hst`` holds the weight for the ``.out``'s centre of gravity.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.spatial.transform import Rotation

import cummins
from cummins.cli import main
from cummins.errors import ArgumentError, AssumptionWarning
from cummins.restoring import describe_restoring, recorded_weight, weight_stiffness

RHO, G = 1025.0, 9.81


def _c(ds) -> np.ndarray:
    return ds.hydrostatic_stiffness.transpose("influenced_dof", "radiating_dof").values


def _read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path)


@pytest.mark.parametrize("axes", ["z-up", "z-down"])
def test_weight_terms_are_the_derivative_of_the_weights_moment(axes):
    """C = −∂M/∂θ of the weight's moment about O, the body turned by small rotations
    (central differences of exact rotations): C44 = C55 = −m g z, C46 = m g x,
    C56 = m g y in z-up axes, nothing in the forces or in C64, C65."""
    mass, r = 2.5e6, np.array([3.0, -1.5, 4.0])
    gravity = np.array([0.0, 0.0, -G if axes == "z-up" else G])

    def moment(theta):
        turned = Rotation.from_rotvec(theta).apply(r)
        return np.cross(turned, mass * gravity)

    h = 1e-6
    numeric = np.zeros((3, 3))
    for j in range(3):
        step = np.zeros(3)
        step[j] = h
        numeric[:, j] = -(moment(step) - moment(-step)) / (2 * h)
    w = weight_stiffness(mass * r, G, axes)
    np.testing.assert_allclose(w[3:, 3:], numeric, atol=1e-6 * mass * G * 4)
    assert not np.any(w[:3]) and not np.any(w[:, :3])


def test_analytic_box_from_wamits_barge(corpus):
    """WEC-Sim's generalized-mode barge is a box, L = 80 m, B = 10 m, draught 5 m, and
    WAMIT computed it with the centre of gravity at the waterline (its .out), so its .hst
    holds no weight terms: given a centre of gravity 3 m below the waterline, C44 and
    C55 become the box's ρg(LB³/12 + ∇z_B) − m g z_G and ρg(BL³/12 + ∇z_B) − m g z_G
    (WAMIT's panels: within 0.06 %), heave unchanged."""
    ds = _read(corpus / "WEC-Sim_Applications" / "wamit_generalized_modes_barge")
    rho, g = ds.attrs["rho"], ds.attrs["g"]
    length, beam, draught = 80.0, 10.0, 5.0
    volume, z_b, z_g = length * beam * draught, -draught / 2, -3.0
    [held] = recorded_weight(ds)
    assert held.center[2] == 0.0  # the .out's centre of gravity: the waterline
    out = cummins.with_inertia(
        ds.isel(influenced_dof=slice(0, 6), radiating_dof=slice(0, 6)),
        center_of_gravity=[0.0, 0.0, z_g],
        radii_of_gyration=[4.0, 23.0, 23.0],
    )
    mass = rho * volume
    c = _c(out)
    c44 = rho * g * (length * beam**3 / 12 + volume * z_b) - mass * g * z_g
    c55 = rho * g * (beam * length**3 / 12 + volume * z_b) - mass * g * z_g
    assert c[3, 3] == pytest.approx(c44, rel=2e-3)
    assert c[4, 4] == pytest.approx(c55, rel=2e-3)
    assert c[2, 2] == _c(ds)[2, 2] == pytest.approx(rho * g * length * beam, rel=2e-3)
    # exactly the weight's terms were added, nothing else
    delta = c - _c(ds)[:6, :6]
    expected = np.zeros((6, 6))
    expected[3, 3] = expected[4, 4] = -mass * g * z_g
    np.testing.assert_allclose(delta, expected, atol=1e-9 * mass * g)
    assert f"{mass:.6g} kg at [0.0, 0.0, -3.0] m" in describe_restoring(out)


def test_wamit_hst_holds_the_weight_and_is_not_counted_twice(shared_data):
    """The tanker's .hst is WAMIT's hydrostatic and gravitational restoring for ρ∇ at the
    .out's centre of gravity (3.93, 0, 2.5): the same mass and centre change nothing; G
    5 m lower adds m g 5 to C44 and C55 only; a heavier body at the same G adds the
    weight of the difference."""
    ds = _read(shared_data / "mss" / "tanker" / "tanker.1")
    [held] = recorded_weight(ds)
    volume = float(ds.attrs["displaced_volume"])
    assert held.mass == pytest.approx(ds.attrs["rho"] * volume)
    np.testing.assert_allclose(held.center, [3.93, 0.0, 2.5])
    radii = [17.0, 64.0, 66.0]
    same = cummins.with_inertia(ds, center_of_gravity=[3.93, 0, 2.5], radii_of_gyration=radii)
    np.testing.assert_array_equal(_c(same), _c(ds))
    lower = cummins.with_inertia(ds, center_of_gravity=[3.93, 0, -2.5], radii_of_gyration=radii)
    expected = np.zeros((6, 6))
    expected[3, 3] = expected[4, 4] = held.mass * ds.attrs["g"] * 5.0
    np.testing.assert_allclose(_c(lower) - _c(ds), expected, atol=1e-6 * held.mass)
    heavier = cummins.with_inertia(
        ds, mass=1.1 * held.mass, center_of_gravity=[3.93, 0, 2.5], radii_of_gyration=radii
    )
    dm = 0.1 * held.mass * ds.attrs["g"]
    change = _c(heavier) - _c(ds)
    assert change[3, 3] == pytest.approx(-dm * 2.5) and change[4, 4] == pytest.approx(-dm * 2.5)
    assert change[3, 5] == pytest.approx(dm * 3.93)
    assert "in place of the file's (recorded" in heavier.attrs["history"]


def _capytaine_box(mass=None, center_of_mass=(0.0, 0.0, 0.0)):
    cpt = pytest.importorskip("capytaine")
    mesh = cpt.mesh_parallelepiped(
        size=(20.0, 8.0, 6.0), center=(0, 0, -1.0), resolution=(10, 4, 3)
    )
    body = cpt.FloatingBody(
        mesh=mesh,
        dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)),
        center_of_mass=center_of_mass,
        mass=mass,
    ).immersed_part()
    return body, body.compute_hydrostatic_stiffness(rho=RHO, g=G).values


def test_capytaine_with_and_without_the_weight():
    """Capytaine computes the box's restoring about the waterline origin without weight
    terms (centre of mass at the origin) and with a mass of 3e5 kg at (0.5, −0.3, 1.2)
    m (not ρ∇, off the centre of buoyancy's vertical): adding that weight to the first
    gives the second, C44, C55, C46 and C56 included, to round-off."""
    _, without = _capytaine_box()
    _, with_weight = _capytaine_box(3.0e5, (0.5, -0.3, 1.2))
    ds = cummins.make_hydrodb(
        [1.0],
        np.eye(6)[None],
        np.eye(6)[None],
        rho=RHO,
        g=G,
        source_format="arrays",
        hydrostatic_stiffness=without,
        **cummins.restoring.weight_record([0.0], [0.0, 0.0, 0.0], "Capytaine, no weight"),
    )
    out = cummins.restoring.with_weight(ds, [3.0e5], [np.array([0.5, -0.3, 1.2])])
    np.testing.assert_allclose(_c(out), with_weight, rtol=1e-12, atol=1e-9 * abs(without).max())
    assert with_weight[3, 5] != 0 and with_weight[4, 5] != 0


def test_capytaine_file_through_the_reader(tmp_path):
    """A Capytaine NetCDF file (Capytaine's own writer) computed with the displaced mass
    at (0, 0, −1): the reader records that weight, and the mass properties of another
    body (4e5 kg at (1, 0, 0.5)) give Capytaine's own restoring for that body."""
    cpt = pytest.importorskip("capytaine")
    mesh = cpt.mesh_parallelepiped(
        size=(20.0, 8.0, 6.0), center=(0, 0, -1.0), resolution=(10, 4, 3)
    )
    body = cpt.FloatingBody(
        mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)), center_of_mass=(0, 0, -1.0)
    ).immersed_part()
    body.inertia_matrix = body.compute_rigid_body_inertia(rho=RHO)
    body.hydrostatic_stiffness = body.compute_hydrostatic_stiffness(rho=RHO, g=G)
    import xarray as xr

    test_matrix = xr.Dataset(
        coords={
            "omega": [0.8, 1.2],
            "wave_direction": [0.0],
            "radiating_dof": list(body.dofs),
            "water_depth": [np.inf],
            "rho": [RHO],
            "g": [G],
        }
    )
    dataset = cpt.BEMSolver().fill_dataset(test_matrix, body, progress_bar=False, hydrostatics=True)
    path = tmp_path / "box.nc"
    cpt.io.xarray.export_dataset(path, dataset)
    ds = _read(path)
    [held] = recorded_weight(ds)
    np.testing.assert_allclose(held.center, [0, 0, -1.0])
    assert held.mass == pytest.approx(RHO * 640.0)
    out = cummins.with_inertia(
        ds, mass=4.0e5, center_of_gravity=[1.0, 0.0, 0.5], radii_of_gyration=[3.0, 6.0, 6.0]
    )
    _, reference = _capytaine_box(4.0e5, (1.0, 0.0, 0.5))
    np.testing.assert_allclose(_c(out), reference, rtol=1e-9, atol=1e-9 * abs(reference).max())


def test_openfast_files_assume_hydrostatics_only_or_take_the_users_word(corpus):
    """WEIS's OC3 spar (OpenFAST's WAMIT files, no .out or .frc): nothing recorded; the
    published mass properties (7 466 330 kg, G 89.92 m below the waterline) add
    −m g z_G to roll and pitch with a warning that it was assumed; said "total", the
    restoring is kept; said "hydrostatic", the same as assumed, without the warning."""
    ds = _read(corpus / "WEIS" / "ss_fitting_OC3_spar")
    assert recorded_weight(ds) is None
    assert "not recorded" in describe_restoring(ds)
    props = {
        "mass": 7466330.0,
        "center_of_gravity": [0.0, 0.0, -89.92],
        "radii_of_gyration": [23.8, 23.8, 4.69],
    }
    with pytest.warns(AssumptionWarning, match="--restoring-includes-weight"):
        assumed = cummins.with_inertia(ds, **props)
    added = 7466330.0 * ds.attrs["g"] * 89.92
    assert _c(assumed)[3, 3] - _c(ds)[3, 3] == pytest.approx(added)
    assert _c(assumed)[4, 4] - _c(ds)[4, 4] == pytest.approx(added)
    assert _c(assumed)[3, 3] > 0 > _c(ds)[3, 3]  # the spar floats upright only with it
    with warnings.catch_warnings():
        warnings.simplefilter("error", AssumptionWarning)
        stated = cummins.with_inertia(ds, restoring="hydrostatic", **props)
        total = cummins.with_inertia(ds, restoring="total", **props)
    np.testing.assert_array_equal(_c(stated), _c(assumed))
    np.testing.assert_array_equal(_c(total), _c(ds))


def test_stating_hydrostatic_against_a_recorded_weight_is_refused(shared_data):
    ds = _read(shared_data / "mss" / "tanker" / "tanker.1")
    with pytest.raises(ArgumentError, match=r"tanker\.1 records the weight terms"):
        cummins.with_inertia(ds, radii_of_gyration=[17.0, 64.0, 66.0], restoring="hydrostatic")


def test_several_bodies_each_their_own_weight(corpus):
    """RM3 (WAMIT, two bodies, origins at WEC-Sim's centres of gravity): WEC-Sim's set-up
    changes nothing; the spar's centre of gravity 1 m lower changes the spar's roll and
    pitch by m g and nothing of the float."""
    ds = _read(corpus / "WEC-Sim" / "wamit_RM3_2body")
    masses = [725833.0, 886687.0]
    radii = [[5.4, 5.4, 7.1], [10.3, 10.3, 5.7]]
    same = cummins.with_inertia(
        ds,
        mass=masses,
        center_of_gravity=[[0, 0, -0.72], [0, 0, -21.29]],
        radii_of_gyration=radii,
    )
    np.testing.assert_allclose(_c(same), _c(ds), atol=1e-6 * np.abs(_c(ds)).max())
    lower = cummins.with_inertia(
        ds,
        mass=masses,
        center_of_gravity=[[0, 0, -0.72], [0, 0, -22.29]],
        radii_of_gyration=radii,
    )
    delta = _c(lower) - _c(ds)
    expected = np.zeros((12, 12))
    expected[9, 9] = expected[10, 10] = masses[1] * ds.attrs["g"]
    np.testing.assert_allclose(delta, expected, atol=1e-3 * masses[1])


def test_z_down_data_get_the_same_physical_change(shared_data):
    """MSS's tanker (Fossen's axes, z down) and WAMIT's (z up): the centre of gravity 2 m
    lower and 1 m forward changes C44 and C55 alike in both, and C46 as T = diag(1, −1,
    −1, 1, −1, −1) says (the sign of C46 flips)."""
    up = _read(shared_data / "mss" / "tanker" / "tanker.1")
    down = _read(shared_data / "mss" / "tanker" / "tanker.mat")
    radii = [17.0, 64.0, 66.0]
    mass = float(recorded_weight(up)[0].mass)
    moved_up = cummins.with_inertia(
        up, mass=mass, center_of_gravity=[4.93, 0, 0.5], radii_of_gyration=radii
    )
    moved_down = cummins.with_inertia(
        down, mass=mass, center_of_gravity=[4.93, 0, -0.5], radii_of_gyration=radii
    )
    d_up, d_down = _c(moved_up) - _c(up), _c(moved_down) - _c(down)
    for i, j, sign in ((3, 3, 1), (4, 4, 1), (3, 5, -1)):
        assert d_down[i, j] == pytest.approx(sign * d_up[i, j], rel=1e-9)
    assert d_up[3, 3] == pytest.approx(mass * up.attrs["g"] * 2.0)


def test_info_says_where_the_restoring_came_from_and_history_records_changes(shared_data, tmp_path):
    tanker = str(shared_data / "mss" / "tanker" / "tanker.1")
    result = CliRunner().invoke(main, ["info", tanker])
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "restoring" in text and "tanker.hst" in text and "[3.93, 0.0, 2.5] m" in text
    result = CliRunner().invoke(
        main,
        [
            "info",
            tanker,
            "--center-of-gravity",
            "3.93",
            "0",
            "0",
            "--radii-of-gyration",
            "17",
            "64",
            "66",
        ],
    )
    text = " ".join(result.output.split())
    assert result.exit_code == 0, result.output
    assert "[3.93, 0.0, 0.0] m" in text and "C[Roll, Roll] +" in text
    # a converted file keeps what its restoring holds
    ds = _read(tanker)
    cummins.write(ds, tmp_path / "t.nc")
    assert describe_restoring(_read(tmp_path / "t.nc")) == describe_restoring(ds)


def test_check_says_when_the_restoring_and_the_inertia_disagree(shared_data):
    """The tanker's .hst holds the weight for G at z = 2.5 m; an inertia matrix put in
    for G at z = −2.5 m without touching the restoring (a script that sets
    ``inertia_matrix`` by hand) is flagged with the C44 change it implies; the files as
    read are not."""
    from cummins.kinematics import rigid_body_inertia

    ds = _read(shared_data / "mss" / "tanker" / "tanker.1")
    assert not [f for f in cummins.check(ds).findings if "inertia matrix describes" in f.message]
    mass = float(recorded_weight(ds)[0].mass)
    hand = ds.copy()
    hand["inertia_matrix"] = ds.inertia_matrix.copy(
        data=rigid_body_inertia(
            mass, np.array([3.93, 0.0, -2.5]), mass * np.array([17, 64, 66]) ** 2
        )
    )
    [finding] = [f for f in cummins.check(hand).findings if "inertia matrix describes" in f.message]
    assert finding.severity == "warning"
    assert f"{mass * ds.attrs['g'] * 5.0:.4g}" in finding.message


def _hinged_boxes():
    """The attenuator's three boxes (``tests/data/attenuator_capytaine.nc``, each 82 t
    of displacement) at 60 % of it, as buoyant flaps: the middle box fixed, the outer
    ones hinged to it about y at (±5.5, 0, −1) with 1 MN·m·s/rad PTOs. The hinges carry
    the net buoyancy (ρ∇ − m) g = 322 kN of each."""
    from pathlib import Path

    from cummins.mechanics import PTO, Joint, MechanicalSystem

    ds = _read(Path(__file__).parent / "data" / "attenuator_capytaine.nc")
    mass = 0.6 * RHO * np.asarray(ds.attrs["displaced_volume"], dtype=float)
    ds = cummins.with_inertia(
        ds,
        mass=list(mass),
        center_of_gravity=[[-11, 0, -1], [0, 0, -1], [11, 0, -1]],
        radii_of_gyration=[[1.3, 3.0, 3.1]] * 3,
    )
    system = MechanicalSystem(
        joints=(
            Joint("fixed", "body2", "ground"),
            Joint("revolute", "body1", "body2", axis=(0, 1, 0), point=(-5.5, 0, -1), name="h1"),
            Joint("revolute", "body3", "body2", axis=(0, 1, 0), point=(5.5, 0, -1), name="h3"),
        ),
        ptos=(PTO(joint="h1", damping=1e6), PTO(joint="h3", damping=1e6)),
    )
    return ds, system


def _pto_power(ds, system) -> np.ndarray:
    from cummins.seakeeping.frequency_domain import motion_rao, pto_rao

    omega = np.linspace(0.3, 2.5, 12)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the boxes are not in equilibrium: the premise
        rao = motion_rao(ds, omega, [0.0, np.pi / 4], system=system)
        return pto_rao(rao, ds, system).pto_power.values


def test_a_body_out_of_equilibrium_moves_its_restoring_with_its_static_load(tmp_path):
    """Buoyant flaps on hinges: their power take-offs absorb the same about any reference
    point. Moved 2 m down, the restoring (holding the weight of m = 0.6 ρ∇) gains
    −(ρ∇ − m) g Δz in C44, C55, as the joints' pre-load F·(o − h) changes by as much; the
    screw transform alone, as for a body in equilibrium, took the power 15 % off. The
    BEMIO .h5, about each centre of gravity, read as WEC-Sim reads it (without cummins'
    copy, the masses given again), gives the same power too."""
    import shutil

    import h5py

    from cummins.io.bemio.files import COPY_GROUP

    ds, system = _hinged_boxes()
    reference = _pto_power(ds, system)
    assert reference.max() > 0
    moved = cummins.move_reference_point(ds, [[-11, 0, -3], [0, 0, -3], [11, 0, -3]])
    step = moved.attrs["history"].splitlines()[-1]
    assert "moved with its static load (rho V - m) g" in step
    np.testing.assert_allclose(_pto_power(moved, system), reference, rtol=1e-9)
    # the .h5 WEC-Sim reads: about the centres of gravity (here the boxes' centres)
    shifted = cummins.with_inertia(
        moved,
        mass=list(0.6 * RHO * np.asarray(ds.attrs["displaced_volume"], dtype=float)),
        center_of_gravity=[[-11, 0, -2], [0, 0, -2], [11, 0, -2]],
        radii_of_gyration=[[1.3, 3.0, 3.1]] * 3,
    )
    path, bare = tmp_path / "boxes.h5", tmp_path / "bare.h5"
    cummins.write(shifted, path)
    shutil.copy(path, bare)
    with h5py.File(bare, "a") as f:
        del f[COPY_GROUP]
    wecsim = cummins.with_inertia(
        _read(bare),
        mass=list(0.6 * RHO * np.asarray(ds.attrs["displaced_volume"], dtype=float)),
        center_of_gravity=[[-11, 0, -2], [0, 0, -2], [11, 0, -2]],
        radii_of_gyration=[[1.3, 3.0, 3.1]] * 3,
    )
    assert np.allclose(wecsim.attrs["reference_point"], [-11, 0, -2, 0, 0, -2, 11, 0, -2])
    expected = _pto_power(shifted, system)
    np.testing.assert_allclose(_pto_power(wecsim, system), expected, rtol=1e-6)
