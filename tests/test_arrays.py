"""`cummins.frequencies.at_frequency`: np.isclose's answer for a frequency on a grid."""

from __future__ import annotations

import numpy as np
import pytest

from cummins.arrays import at_frequency, column_medians


@pytest.mark.parametrize("rtol", [1e-12, 1e-9, 0.0])
def test_at_frequency_is_isclose(rtol):
    rng = np.random.default_rng(5)
    w = np.sort(rng.uniform(0.01, 40.0, 500))
    targets = np.concatenate(
        [w[::7], w[::11] * (1 + rtol * rng.uniform(-2, 2, w[::11].size)), [0.0, -w[3]]]
    )
    for target in targets:
        expected = np.isclose(w, target, rtol=rtol, atol=0.0)
        assert np.array_equal(at_frequency(w, float(target), rtol), expected)


@pytest.mark.parametrize("target", [np.inf, -np.inf, np.nan])
def test_a_target_that_is_not_finite(target):
    w = np.array([1.0, np.inf, 2.0])
    assert np.array_equal(at_frequency(w, target), np.isclose(w, target, rtol=1e-12, atol=0.0))


def test_column_medians_are_numpys():
    rng = np.random.default_rng(6)
    for rows in (1, 2, 3, 8, 9, 798):
        x = rng.normal(size=(rows, 5))
        x[:, 1] = np.round(x[:, 1])  # ties
        assert np.array_equal(column_medians(x), np.median(x, axis=0))
    x = rng.normal(size=(7, 3))
    x[2, 1] = np.nan
    assert np.array_equal(column_medians(x), np.median(x, axis=0), equal_nan=True)
