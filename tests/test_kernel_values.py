"""K(t) of the fit's data stage on arrays (`retardation.default_kernel_values`) and the
bridged couplings (`infinite_frequency.bridged_couplings`)."""

from __future__ import annotations

import numpy as np

import cummins
from cummins.hydrodb import dof_matrix
from cummins.radiation.fit.data import fit_data
from cummins.radiation.infinite_frequency import bridged_couplings
from cummins.radiation.retardation import default_kernel_values, default_retardation_function


def test_the_arrays_give_the_datasets_kernel():
    ds = cummins.demo_dataset()
    for max_points, node_form in ((500, False), (20_000, True)):
        expected = default_retardation_function(ds, max_points=max_points, node_form=node_form)
        time, kernel = default_kernel_values(
            ds.omega.values,
            dof_matrix(ds, "radiation_damping"),
            dof_matrix(ds, "added_mass"),
            max_points=max_points,
            node_form=node_form,
        )
        np.testing.assert_allclose(time, expected.time.values, rtol=1e-15, atol=0)
        values = expected.transpose("time", "influenced_dof", "radiating_dof").values
        np.testing.assert_allclose(kernel, values, rtol=1e-13, atol=1e-13 * abs(values).max())


def test_fit_data_kernel_is_that_of_the_reciprocal_damping():
    ds = cummins.demo_dataset()
    b = ds.radiation_damping
    skewed = ds.assign(
        radiation_damping=b + 0.1 * b.transpose(..., "radiating_dof", "influenced_dof").values
    )
    measured = fit_data(skewed)
    swapped = skewed.radiation_damping.transpose(..., "radiating_dof", "influenced_dof").values
    symmetric = skewed.assign(radiation_damping=0.5 * (skewed.radiation_damping + swapped))
    expected = default_retardation_function(symmetric, max_points=500, node_form=False)
    values = expected.transpose("time", "influenced_dof", "radiating_dof").values
    np.testing.assert_allclose(measured.time, expected.time.values, rtol=1e-15, atol=0)
    np.testing.assert_allclose(measured.kernel, values, rtol=1e-13, atol=1e-13 * abs(values).max())


def test_a_zero_kernel_keeps_every_time():
    w = np.linspace(0.1, 3.0, 30)
    time, kernel = default_kernel_values(w, np.zeros((30, 2, 2)), np.ones((30, 2, 2)))
    assert time.size == kernel.shape[0] > 20 and not kernel.any()


def test_bridged_couplings_interpolate_the_left_out_points():
    w = np.linspace(1.0, 5.0, 9)
    values = np.stack([np.outer([1.0, 2.0], [1.0, 3.0]) * x**2 for x in w])
    kept = np.ones((9, 2), dtype=bool)
    kept[4, 1] = False
    out = bridged_couplings(values, w, kept)
    assert np.array_equal(out[:, 0, 0], values[:, 0, 0])
    line = 0.5 * (values[3] + values[5])
    np.testing.assert_allclose(out[4, 0, 1], line[0, 1])
    np.testing.assert_allclose(out[4, 1, 1], line[1, 1])
    kept[:3, 0] = False  # below the first kept point: the line from 0 at ω = 0
    low = bridged_couplings(values, w, kept, from_zero=True)
    np.testing.assert_allclose(low[:3, 0, 0], values[3, 0, 0] * w[:3] / w[3])
