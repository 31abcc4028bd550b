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
