"""The stiffness of the static loads the joints carry (joint pre-load): against the
second derivative of the potential of the constant force under exact finite rotations
(SciPy's rotations, an independent route), the closed form about a hinge, and the OSWEC's
flap held down by its hinge (WEC-Sim's set-up: 297 t of buoyancy, 127 t of mass, the
hinge 5 m below the flap's reference point: F (z_o − z_h) = 8.3 MN·m/rad, which the
user had to add by hand)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from cummins.dofs import DOF_NAMES
from cummins.errors import AssumptionWarning
from cummins.mechanics import Joint, assemble
from cummins.mechanics.bodies import BodyFrame
from cummins.mechanics.constraints import null_space_basis
from cummins.mechanics.joints import joint_rows
from cummins.mechanics.preload import preload_stiffness
from test_wec import oswec_flap

F = 1.7e6  # N, upward: buoyancy above weight


def _one_body(point) -> BodyFrame:
    return BodyFrame(tuple(DOF_NAMES), (None,), ("body",), np.asarray([point], dtype=float))


def _hinge_stiffness(frame: BodyFrame, joint: Joint, forces) -> float:
    """K about the hinge per radian² from :func:`preload_stiffness` (T's column scaled to
    a unit rotation)."""
    g, _ = joint_rows(joint, frame)
    t, coordinates = null_space_basis(g, frame.labels)
    preload = preload_stiffness(frame, (joint,), g, t, coordinates, np.asarray(forces))
    assert not preload.unbalanced and not preload.left_out
    column = t[:, 0] / np.linalg.norm(t[3:, 0])  # a unit rotation about the axis
    return float(column @ preload.stiffness @ column)


def _finite_rotation_stiffness(o, h, axis, force, step=1e-4) -> float:
    """d²/dθ² of the potential −F·x_o(θ) of a constant force at o, x_o(θ) = h + R(θa)(o − h)."""

    def potential(theta: float) -> float:
        x = h + Rotation.from_rotvec(theta * np.asarray(axis)).apply(o - h)
        return -float(np.asarray(force) @ x)

    return (potential(step) - 2 * potential(0.0) + potential(-step)) / step**2


@pytest.mark.parametrize(
    ("o", "h", "axis"),
    [
        ((0.0, 0.0, -3.9), (0.0, 0.0, -8.9), (0.0, 1.0, 0.0)),  # the OSWEC: F (z_o − z_h)
        ((1.0, 2.0, 0.5), (1.0, 2.0, -4.0), (1.0, 0.0, 0.0)),  # a hinge about x
        # an inclined axis, the hinge in the plane of the axis and the vertical through o
        ((0.0, 0.0, 0.0), (0.0, -1.5, -3.0), (0.0, 0.6, 0.8)),
        ((0.0, 0.0, 0.0), (0.0, 0.0, 2.0), (0.0, 1.0, 0.0)),  # hinge above: destabilising
    ],
)
def test_hinge_preload_is_the_second_derivative_of_the_force_potential(o, h, axis):
    a = np.asarray(axis) / np.linalg.norm(axis)
    frame = _one_body(o)
    joint = Joint("revolute", "body", "ground", axis=tuple(a), point=h)
    stiffness = _hinge_stiffness(frame, joint, [F])
    force = np.array([0.0, 0.0, F])
    v = np.asarray(o) - np.asarray(h)
    closed = float(force @ v - (force @ a) * (a @ v))
    reference = _finite_rotation_stiffness(np.asarray(o), np.asarray(h), a, force)
    np.testing.assert_allclose(stiffness, closed, rtol=1e-12, atol=1e-6)
    np.testing.assert_allclose(stiffness, reference, rtol=1e-5)
    assert abs(stiffness) > 0.1 * F  # the cases are not trivial


def test_a_body_balanced_or_turning_about_its_own_point_gains_nothing():
    """ρ∇ = m (a freely floating body: the RM3's), or the hinge through o: no pre-load."""
    frame = _one_body((0.0, 0.0, -2.0))
    joint = Joint("revolute", "body", "ground", axis=(0, 1, 0), point=(0.0, 0.0, -6.0))
    assert _hinge_stiffness(frame, joint, [0.0]) == 0.0
    through = Joint("revolute", "body", "ground", axis=(0, 1, 0), point=(0.0, 0.0, -2.0))
    assert abs(_hinge_stiffness(frame, through, [F])) < 1e-9 * F


def test_a_load_the_joints_do_not_carry_is_named():
    """A float with buoyancy above its weight on a vertical slide, and a hinge beside the
    force's line of action: the mean position is no equilibrium, the coordinate named."""
    frame = _one_body((0.0, 0.0, 0.0))
    for joint, coordinate in (
        (Joint("translational", "body", "ground", axis=(0, 0, 1)), "Heave"),
        (Joint("revolute", "body", "ground", axis=(0, 1, 0), point=(2.0, 0.0, 0.0)), None),
    ):
        g, _ = joint_rows(joint, frame)
        t, coordinates = null_space_basis(g, frame.labels)
        preload = preload_stiffness(frame, (joint,), g, t, coordinates, np.array([F]))
        assert len(preload.unbalanced) == 1, joint
        name, value = preload.unbalanced[0]
        assert name == (coordinate or coordinates[0])
        # the force's work on the free motion: F times the heave of o per unit coordinate
        assert abs(value - F * t[2, 0]) < 1e-9 * F and abs(t[2, 0]) > 0.5


@pytest.fixture(scope="module")
def oswec(corpus):
    """(data, system) of WEC-Sim's OSWEC (tests/test_wec.py)."""
    return oswec_flap(corpus)


def test_oswec_flap_gains_its_hinge_preload(oswec):
    """The flap (ρ∇ = 297.01 t from WAMIT's .out, m = 127 t) on its hinge 5 m below o:
    F (z_o − z_h) added on its pitch, as the user gave it by hand before, and said in
    the history; the base's far larger net force goes to the ground through its fixed
    joint and adds nothing the flap feels."""
    data, system = oswec
    volume = float(np.ravel(data.attrs["displaced_volume"])[0])
    expected = (1000.0 * volume - 127000.0) * float(data.attrs["g"]) * (-3.9 + 8.9)
    with warnings.catch_warnings():
        warnings.simplefilter("error", AssumptionWarning)
        assembly = assemble(data, system)
    added = assembly.ds["additional_stiffness"].sel(
        influenced_dof="body1__Pitch", radiating_dof="body1__Pitch"
    )
    np.testing.assert_allclose(float(added), expected, rtol=1e-12)
    assert float(np.abs(assembly.ds["additional_stiffness"]).sum()) == pytest.approx(expected)
    assert "joint pre-load" in assembly.ds.attrs["history"]


def test_without_the_volume_the_preload_is_said_missing(oswec):
    data, system = oswec
    data = data.copy()
    del data.attrs["displaced_volume"]
    with pytest.warns(AssumptionWarning, match="pre-load is not included"):
        assembly = assemble(data, system)
    assert "additional_stiffness" not in assembly.ds


def test_a_flap_on_a_pitching_base_matches_the_exact_kinematics():
    """A chain: a flap (body1, +F at o_f) on a hinge about y at h on a base (body2, −F
    at o_b: the system floats as a whole) that surges, heaves and pitches. The Hessian of
    the forces' potential in the generalized coordinates (the base's x, z, φ and the
    flap's rotation relative to it), by finite differences of the exact positions, equals
    Jᵀ K J, J the Jacobian of the body DOFs in those coordinates."""
    labels = tuple(f"body{b}__{d}" for b in (1, 2) for d in DOF_NAMES)
    o_b, o_f, h = np.array([0.2, 0, 0.0]), np.array([0.2, 0, 3.0]), np.array([0.2, 0, 1.0])
    frame = BodyFrame(labels, ("body1", "body2"), ("flap", "base"), np.array([o_f, o_b]))
    joint = Joint("revolute", "body1", "body2", axis=(0, 1, 0), point=tuple(h))
    rows = [joint_rows(joint, frame)[0]]
    for i, label in enumerate(labels):  # the base in the x-z plane
        if label.split("__")[1] in ("Sway", "Roll", "Yaw") and label.startswith("body2"):
            rows.append(np.eye(len(labels))[i][None])
    g = np.vstack(rows)
    t, coordinates = null_space_basis(g, labels)
    preload = preload_stiffness(frame, (joint,), g, t, coordinates, np.array([F, -F]))
    assert not preload.unbalanced and not preload.left_out

    def rotation(angle: float) -> np.ndarray:
        return Rotation.from_rotvec([0.0, angle, 0.0]).as_matrix()

    def positions(q):  # q = (x_b, z_b, φ, θ relative)
        base = o_b + np.array([q[0], 0.0, q[1]])
        hinge = base + rotation(q[2]) @ (h - o_b)
        return hinge + rotation(q[2] + q[3]) @ (o_f - h), base

    def potential(q) -> float:
        flap, base = positions(q)
        return -(F * flap[2] - F * base[2])

    def dofs(q) -> np.ndarray:
        flap, base = positions(q)
        out = np.zeros(12)
        out[0:3], out[4], out[6:9], out[10] = flap - o_f, q[2] + q[3], base - o_b, q[2]
        return out

    step, eye = 1e-4, np.eye(4)
    hessian = np.array(
        [
            [
                (
                    potential(step * (eye[i] + eye[j]))
                    - potential(step * (eye[i] - eye[j]))
                    - potential(step * (eye[j] - eye[i]))
                    + potential(-step * (eye[i] + eye[j]))
                )
                / (4 * step**2)
                for j in range(4)
            ]
            for i in range(4)
        ]
    )
    jacobian = np.array([(dofs(1e-7 * e) - dofs(-1e-7 * e)) / 2e-7 for e in eye]).T
    assert np.abs(g @ jacobian).max() < 1e-6  # the coordinates move as the joints allow
    np.testing.assert_allclose(
        jacobian.T @ preload.stiffness @ jacobian, hessian, atol=1e-6 * np.abs(hessian).max()
    )
    assert np.abs(hessian).max() > F  # not trivial: 3 F·m on the base's pitch


def test_the_rounding_of_printed_masses_and_volumes_is_no_load(corpus):
    """AQWA's floating OWC (the masses and volumes of its listing, five digits): the
    water column's buoyancy and weight differ by 1.4e-5 of them (637 N of 45 MN), the
    rounding of the printout, not a load: its joints carry none, and no warning says
    the mean position is no equilibrium."""
    from cummins.io import read
    from cummins.mechanics import MechanicalSystem
    from cummins.mechanics.bodies import body_frame
    from cummins.mechanics.preload import BALANCED, net_static_forces

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = read(corpus / "WEC-Sim_Applications/aqwa_floating_OWC_AH1only/floatingOWC.AH1")
    volumes = np.ravel(ds.attrs["displaced_volume"]) * float(ds.attrs["rho"])
    masses = np.diag(ds.inertia_matrix.values)[[0, 6]]
    imbalance = np.abs(volumes - masses) / masses
    assert 1e-5 < imbalance.max() < 0.5 * BALANCED  # 1.4e-5: above the old threshold
    assert not np.any(net_static_forces(ds, body_frame(ds)))
    system = MechanicalSystem(
        joints=(
            Joint("translational", "body1", "ground", axis=(0, 0, 1)),
            Joint("translational", "body2", "body1", axis=(0, 0, 1)),
        )
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error", AssumptionWarning)
        assembly = assemble(ds, system)
    assert "joint pre-load" not in str(assembly.ds.attrs.get("history", ""))
