"""The canonical dataset: construction, validation, DOF selection, transforms."""

from __future__ import annotations

import numpy as np
import pytest

import cummins
from cummins import HydroDataError
from cummins.hydrodb import describe, dof_index, make_hydrodb, split_dof
from cummins.kinematics import (
    center_of_gravity_from_inertia,
    rigid_body_inertia,
    screw_transform,
    skew,
)


def _arrays(n_omega=4):
    w = np.linspace(0.2, 2.0, n_omega)
    rng = np.random.default_rng(0)
    q = rng.normal(size=(n_omega, 6, 6))
    a = q @ np.swapaxes(q, 1, 2) + 6 * np.eye(6)
    return w, a, 0.1 * a


def test_make_hydrodb_sorts_and_records():
    w, a, b = _arrays()
    ds = make_hydrodb(w[::-1], a[::-1], b[::-1], rho=1025, g=9.81, source_format="arrays")
    np.testing.assert_array_equal(ds.omega, w)
    np.testing.assert_array_equal(ds.added_mass.values, a)
    assert "sorted" in ds.attrs["history"]
    assert ds.added_mass.attrs["units"].startswith("kg")


@pytest.mark.parametrize(
    ("change", "pattern"),
    [
        (lambda w, a, b: (w, a[:, :5], b), "added_mass has shape"),
        (lambda w, a, b: (np.r_[w[:-1], w[0]], a, b), "appears more than once"),
        (lambda w, a, b: (np.r_[0.0, w[1:]], a, b), "not positive"),
        (lambda w, a, b: (np.r_[w[:-1], np.inf], a, b), "non-finite"),
    ],
)
def test_make_hydrodb_rejects(change, pattern):
    w, a, b = change(*_arrays())
    with pytest.raises(HydroDataError, match=pattern):
        make_hydrodb(w, a, b, rho=1025, g=9.81, source_format="arrays", source_file="x.dat")


def test_nan_is_located():
    w, a, b = _arrays()
    b[2, 2, 4] = np.nan
    with pytest.raises(HydroDataError) as info:
        make_hydrodb(w, a, b, rho=1025, g=9.81, source_format="arrays", source_file="x.dat")
    message = str(info.value)
    assert "radiation_damping[omega=1.4 rad/s, Heave, Pitch]" in message
    assert message.startswith("x.dat")


def test_dof_labels():
    assert cummins.dof_labels(["a", "b"])[7] == "b__Sway"
    assert split_dof("float__Heave") == ("float", "Heave")
    assert dof_index("b__Yaw") == 5
    with pytest.raises(HydroDataError, match="unknown DOF"):
        dof_index("Wobble")


def test_select_dofs(tanker_wamit):
    sub = cummins.select_dofs(tanker_wamit, ["Heave", "Pitch"])
    assert list(sub.influenced_dof.values) == ["Heave", "Pitch"]
    np.testing.assert_array_equal(
        sub.added_mass.values, tanker_wamit.added_mass.values[:, 2::2, 2::2][:, :2, :2]
    )
    with pytest.raises(HydroDataError, match="not in the data"):
        cummins.select_dofs(tanker_wamit, ["Heave", "Spin"])


def test_screw_transform_moves_a_point_force():
    """A vertical force F at P = (10, 2, -3) gives the moment r × F about O (eq. 45)."""
    r = np.array([10.0, 2.0, -3.0])
    force_at_p = np.array([0.0, 0.0, 5.0, 0.0, 0.0, 0.0])
    tau = screw_transform(r).T @ force_at_p
    np.testing.assert_allclose(tau[:3], force_at_p[:3])
    np.testing.assert_allclose(tau[3:], np.cross(r, force_at_p[:3]))
    np.testing.assert_allclose(skew(r) @ [1.0, 0, 0], np.cross(r, [1.0, 0, 0]))


def test_move_reference_point_round_trip(tanker_wamit):
    moved = cummins.move_reference_point(tanker_wamit, [-120.0, 3.0, 8.0])
    back = cummins.move_reference_point(moved, tanker_wamit.attrs["reference_point"])
    for name in (
        "added_mass",
        "radiation_damping",
        "added_mass_inf",
        "inertia_matrix",
        "hydrostatic_stiffness",
        "excitation_force",
    ):
        scale = float(np.abs(tanker_wamit[name]).max())
        np.testing.assert_allclose(back[name], tanker_wamit[name], rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(moved.attrs["reference_point"], [-120.0, 3.0, 8.0])
    assert "reference point moved" in moved.attrs["history"]


def test_move_reference_point_physics(tanker_wamit):
    """Known rigid-body results: parallel-axis theorem and heave stiffness at an offset."""
    ds = tanker_wamit.copy()
    cg = np.array([3.93, 0.0, 2.5])
    mass = 9.462021e7
    radii = np.array([17.02, 63.96, 66.42])  # MSS tanker.mat main.k44, k55, k66
    ds["inertia_matrix"] = ds.inertia_matrix.copy(
        data=rigid_body_inertia(mass, cg, mass * radii**2)
    )
    at_cg = cummins.move_reference_point(ds, cg)
    m = at_cg.inertia_matrix.values
    # About the CG the mass-moment coupling terms vanish and I_G is diagonal.
    np.testing.assert_allclose(m[:3, 3:], 0.0, atol=1e-6 * mass)
    np.testing.assert_allclose(m[3:, 3:], np.diag(mass * radii**2), rtol=1e-12, atol=1e-3)
    # Parallel-axis theorem back to the origin: I_O = I_G + m (|r|² I − r rᵀ).
    i_origin = m[3:, 3:] + mass * (cg @ cg * np.eye(3) - np.outer(cg, cg))
    np.testing.assert_allclose(i_origin, ds.inertia_matrix.values[3:, 3:], rtol=1e-9)
    # Heave stiffness seen from a point a metres aft: a bow-down pitch θ about the new
    # point lowers the old one by aθ (z up, y to port), so C35 gains −a C33 and C55 a² C33.
    a = 50.0
    moved = cummins.move_reference_point(ds, [-a, 0.0, 0.0])
    c, c0 = moved.hydrostatic_stiffness.values, ds.hydrostatic_stiffness.values
    assert c[2, 2] == pytest.approx(c0[2, 2])
    assert c[2, 4] == pytest.approx(c0[2, 4] - a * c0[2, 2])
    assert c[4, 4] == pytest.approx(c0[4, 4] - 2 * a * c0[2, 4] + a**2 * c0[2, 2])


def test_center_of_gravity_from_inertia():
    m = rigid_body_inertia(5.0, [1.0, -2.0, 3.0], [4.0, 5.0, 6.0])
    mass, r_g, inconsistency = center_of_gravity_from_inertia(m)
    assert mass == 5.0 and inconsistency < 1e-15
    np.testing.assert_allclose(r_g, [1.0, -2.0, 3.0])


def test_change_axes_is_an_involution(tanker_wamit):
    down = cummins.change_axes(tanker_wamit, "z-down")
    assert down.attrs["axis_convention"] == "z-down"
    np.testing.assert_allclose(down.attrs["center_of_gravity"], [3.93, 0.0, -2.5])
    # Heave-pitch coupling keeps its sign (both flip), surge-pitch changes sign.
    a, a0 = down.added_mass_inf.values, tanker_wamit.added_mass_inf.values
    assert a[2, 4] == a0[2, 4] and a[0, 4] == -a0[0, 4]
    # Waves travelling towards port (+y up) travel towards -y (starboard is +y) down.
    assert set(np.round(np.degrees(down.wave_direction.values))) == {0, *range(180, 360, 10)}
    up = cummins.change_axes(down, "z-up")
    for name in ("added_mass", "excitation_force", "inertia_matrix"):
        np.testing.assert_allclose(up[name], tanker_wamit[name], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(up.wave_direction, tanker_wamit.wave_direction, atol=1e-12)
    assert cummins.change_axes(tanker_wamit, "z-up") is tanker_wamit
    with pytest.raises(HydroDataError, match="unknown axis convention"):
        cummins.change_axes(tanker_wamit, "y-up")


def test_transforms_need_six_dofs(tanker_wamit):
    sub = cummins.select_dofs(tanker_wamit, ["Heave", "Pitch"])
    with pytest.raises(HydroDataError, match="all six DOFs"):
        cummins.move_reference_point(sub, [1.0, 0.0, 0.0])


def test_axis_change_of_models_matches_the_data_with_generalized_modes(corpus):
    """The generalized-mode barge (6 rigid + 4 beam modes): the radiation model's axis
    signs are those hydrodb.change_axes applies to the data (rigid modes T, beam modes 1),
    and check's rigid-body consistency runs on the six rigid modes only."""
    import cummins
    from cummins.radiation.model import _axis_signs

    ds = cummins.read(corpus / "WEC-Sim_Applications" / "wamit_generalized_modes_barge")
    labels = [str(d) for d in ds.influenced_dof.values]
    flipped = cummins.change_axes(ds, "z-down")
    t = _axis_signs(labels)
    a, b = ds.added_mass.values, flipped.added_mass.values
    np.testing.assert_allclose(b, t[None, :, None] * a * t[None, None, :], rtol=0, atol=0)
    assert list(t[6:]) == [1.0] * 4
    findings = [f for f in cummins.check(ds).findings if f.check == "inertia"]
    assert any("rigid body" in f.message for f in findings)


def test_describe_gives_no_mass_for_rotations_alone():
    """A flap whose one DOF is its hinge angle records a moment of inertia (kg·m²), not
    a mass: ``cummins info`` says no mass; with translations, each body's first."""
    w = np.linspace(0.2, 2.0, 4)
    a = np.full((4, 1, 1), 1.2e7)
    hinge = make_hydrodb(
        w,
        a,
        0.1 * a,
        rho=1025,
        g=9.81,
        source_format="arrays",
        dofs=["Pitch"],
        inertia_matrix=np.array([[2.47e6]]),
    )
    assert "mass_kg" not in describe(hinge)
    heaves = make_hydrodb(
        w,
        np.tile(np.diag([3e5, 7e5, 4e6]), (4, 1, 1)),
        np.zeros((4, 3, 3)),
        rho=1025,
        g=9.81,
        source_format="arrays",
        dofs=["b1__Heave", "b2__Heave", "b2__Pitch"],
        inertia_matrix=np.diag([2.6e5, 3.4e5, 9e6]),
    )
    assert describe(heaves)["mass_kg"] == [2.6e5, 3.4e5]
