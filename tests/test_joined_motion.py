"""The fit of a joined system aims at the motions that system has (issue 30): the motion
sensitivity with joints and PTOs, H = T (Tᵀ Z T)⁻¹ Tᵀ (cummins.radiation.fit.motion)."""

import numpy as np
import pytest

import cummins
from cummins.radiation.fit.motion import JoinedMotion, motion_sensitivity, transfer


def test_transfer_of_a_basis_picking_dofs_is_the_inverse_of_their_block():
    """T made of unit columns (DOFs 0 and 2 free, 1 held): H is (Z restricted to those
    DOFs)⁻¹ embedded, zero on the held DOF — an analytic reference."""
    rng = np.random.default_rng(3)
    z = rng.normal(size=(4, 3, 3)) + 1j * rng.normal(size=(4, 3, 3)) + 5 * np.eye(3)
    t = np.eye(3)[:, [0, 2]]
    h = transfer(z, t)
    keep = np.ix_(range(4), [0, 2], [0, 2])
    np.testing.assert_allclose(h[keep], np.linalg.inv(z[keep]), rtol=1e-12)
    assert np.all(h[:, 1, :] == 0) and np.all(h[:, :, 1] == 0)
    np.testing.assert_allclose(transfer(z, None), np.linalg.inv(z), rtol=1e-12)


def test_free_bodies_without_ptos_change_nothing():
    """A JoinedMotion with no constraint and no PTO gives the free bodies' weights."""
    ds = cummins.demo_dataset()
    n = ds.sizes["influenced_dof"]
    free = motion_sensitivity(ds)
    joined = motion_sensitivity(ds, joined=JoinedMotion(None, np.zeros((n, n)), np.zeros((n, n))))
    np.testing.assert_array_equal(free.weight, joined.weight)


@pytest.fixture(scope="module")
def rm3(corpus):
    ds = cummins.read(corpus / "WEC-Sim" / "wamit_RM3_2body" / "rm3.out", rho=1000.0)
    return cummins.with_inertia(
        ds,
        mass=[725833.0, 886687.0],
        center_of_gravity=[[0.0, 0.0, -0.72], [0.0, 0.0, -21.29]],
        radii_of_gyration=[[5.367, 5.418, 7.148], [10.319, 10.319, 5.674]],
    )


def test_a_pto_and_a_constraint_reach_the_fit(rm3):
    """RM3 on heave joints with its PTO: the model says whose motions it was fitted to,
    and its motion error is that of the joined system (the RAOs of the two heaves with
    the PTO, not of two free floating bodies)."""
    from cummins.mechanics import PTO, Joint, MechanicalSystem
    from cummins.vessel import vessel_from_hydrodb

    system = MechanicalSystem(
        joints=(
            Joint("translational", "body2", "ground", axis=(0, 0, 1)),
            Joint("translational", "body1", "body2", axis=(0, 0, 1), name="pto"),
        ),
        ptos=(PTO(joint="pto", damping=1.2e6),),
    )
    vessel = vessel_from_hydrodb(rm3, system=system)
    said = vessel.radiation.attrs["motions_of"]
    assert "joined system" in said and "power take-offs" in said
    assert vessel.radiation.attrs["motion_error"] <= 0.01
