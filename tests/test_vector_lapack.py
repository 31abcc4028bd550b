"""The relocation's direct LAPACK calls (:mod:`cummins.radiation.fit.vector`): the
solutions numpy's ``lstsq`` and ``eigvals`` give, and their errors."""

from __future__ import annotations

import numpy as np
import pytest

from cummins.radiation.fit.vector import _eigenvalues, _least_squares


@pytest.mark.parametrize("shape", [(40, 13), (1700, 20), (6, 1), (13, 13), (5, 9)])
def test_least_squares_is_numpys(shape):
    """Tall, square and wide systems: numpy's minimum-norm least-squares solution."""
    rng = np.random.default_rng(7)
    matrix, rhs = rng.standard_normal(shape), rng.standard_normal(shape[0])
    expected = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
    np.testing.assert_allclose(_least_squares(matrix, rhs), expected, rtol=1e-9, atol=1e-12)


def test_least_squares_of_a_rank_deficient_system_is_the_minimum_norm_one():
    """Two equal columns share the weight equally, as the pseudo-inverse does."""
    rng = np.random.default_rng(8)
    matrix = rng.standard_normal((30, 4))
    matrix[:, 3] = matrix[:, 2]
    rhs = matrix @ np.array([1.0, -2.0, 0.5, 0.5])
    x = _least_squares(matrix, rhs)
    np.testing.assert_allclose(x, [1.0, -2.0, 0.5, 0.5], rtol=1e-9)


def test_eigenvalues_of_a_damped_pair_and_a_real_pole():
    """A 2 × 2 rotation–scaling block and a real pole: −0.1 ± 2j and −3."""
    matrix = np.array([[-0.1, 2.0, 0.0], [-2.0, -0.1, 0.0], [0.0, 0.0, -3.0]])
    found = np.sort_complex(_eigenvalues(matrix))
    np.testing.assert_allclose(found, [-3.0, -0.1 - 2j, -0.1 + 2j], atol=1e-12)


def test_eigenvalues_of_a_matrix_with_a_nan_raise():
    """What numpy raises (the order search skips that order)."""
    with pytest.raises(np.linalg.LinAlgError):
        _eigenvalues(np.array([[np.nan, 0.0], [0.0, 1.0]]))
