"""Helpers shared by tests: a one-DOF dataset from given curves, a quiet reader."""

from __future__ import annotations

import warnings

import numpy as np

import cummins
from cummins.hydrodb import make_hydrodb


def one_dof_hydrodb(w, a, b, dof: str = "Heave"):
    """One DOF with the given A(ω), B(ω) (SI units, sea water)."""
    return make_hydrodb(
        w,
        np.asarray(a)[:, None, None],
        np.asarray(b)[:, None, None],
        rho=1025.0,
        g=9.81,
        source_format="synthetic",
        dofs=[dof],
    )


def read_quietly(path):
    """:func:`cummins.read` with its warnings silenced (the tests judge the data)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path)


def wecsim_rm3(shared_data):
    """WEC-Sim's RM3 (corpus ``WEC-Sim/wamit_RM3_2body/rm3.out``, ρ = 1000) with WEC-Sim's
    mass properties (the regression case's), read quietly."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(
            shared_data / "corpus" / "WEC-Sim" / "wamit_RM3_2body" / "rm3.out", rho=1000
        )
        return cummins.with_inertia(
            ds,
            mass=[725833.0, 886687.0],
            center_of_gravity=[[0.0, 0.0, -0.72], [0.0, 0.0, -21.29]],
            radii_of_gyration=[[5.367, 5.418, 7.148], [10.319, 10.319, 5.674]],
        )


def demo_block_motion_error():
    """(sensitivity, the data's K(jω) = B + jωA at the frequencies the motion error
    compares, their ω, the BlockMotionError of it) of the demo tanker."""
    from cummins.hydrodb import dof_matrix
    from cummins.radiation.fit.motion import BlockMotionError, motion_sensitivity

    ds = cummins.demo_dataset()
    sensitivity = motion_sensitivity(ds)
    rows = sensitivity.compared_frequencies()
    w = sensitivity.omega[rows]
    a = dof_matrix(ds, "added_mass")[rows]
    b = dof_matrix(ds, "radiation_damping")[rows]
    k_data = b + 1j * w[:, None, None] * a
    return sensitivity, k_data, w, BlockMotionError(sensitivity, k_data)
