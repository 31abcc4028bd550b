"""The least-distance programmes of an enforcement continued from the last one's NNLS
multipliers (:func:`cummins.radiation.passivity.enforcement.warm_nnls`): against scipy's
NNLS and the Karush–Kuhn–Tucker conditions on random programmes, and the Cholesky factor
of the passive set updated column by column."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import nnls

from cummins.radiation.passivity.enforcement import (
    _PassiveCholesky,
    factored_misfit,
    least_distance,
    least_distance_multipliers,
    warm_nnls,
)


def _programme(rng, rows: int = 80, size: int = 20):
    misfit = factored_misfit(
        [(rng.standard_normal((30, size // 2)), rng.standard_normal(30)) for _ in range(2)]
    )
    g = rng.standard_normal((rows, size))
    h = g @ (3.0 * rng.standard_normal(size)) - np.abs(rng.standard_normal(rows))  # feasible
    return misfit, g, h


@pytest.mark.parametrize("seed", range(8))
def test_a_programme_continued_from_the_last_is_solved_as_from_nothing(seed):
    """A programme with rows added to the last, continued from the last's multipliers,
    has the solution of scipy's NNLS on all its rows (to rounding), its constraints
    met, and multipliers that meet the KKT conditions: non-negative, zero where the
    constraint does not bind."""
    rng = np.random.default_rng(seed)
    misfit, g, h = _programme(rng)
    first = 40
    _, u = least_distance_multipliers(misfit, g[:first], h[:first], start=np.ones(first, bool))
    assert u.size == first and (u > 0).any()
    warm, u_warm = least_distance_multipliers(misfit, g, h, start=np.ones(80, bool), warm=u)
    whole, _ = least_distance(misfit, g, h)
    scale = np.abs(whole).max()
    np.testing.assert_allclose(warm, whole, rtol=1e-8, atol=1e-10 * scale)
    slack = g @ warm - h
    assert np.all(slack >= -1e-8 * np.abs(h).max())
    assert np.all(u_warm >= 0)
    binding = u_warm > 0
    assert np.all(np.abs(slack[binding]) <= 1e-8 * np.abs(h).max())


@pytest.mark.parametrize("seed", range(8))
def test_warm_nnls_meets_the_kkt_conditions_of_nnls(seed):
    """u ≥ 0 with Eᵀ(f − E u) ≤ 0 everywhere and = 0 where u > 0 (Lawson & Hanson Thm
    23.4), and the residual of scipy's NNLS, from the optimum of the first columns."""
    rng = np.random.default_rng(100 + seed)
    matrix = rng.standard_normal((50, 70))
    target = rng.standard_normal(50)
    head, _ = nnls(matrix[:, :30], target)
    u = warm_nnls(matrix, target, head)
    assert u is not None
    gradient = matrix.T @ (target - matrix @ u)
    scale = np.linalg.norm(matrix, axis=0) * np.linalg.norm(target)
    assert np.all(u >= 0)
    assert np.all(gradient <= 1e-10 * scale)
    assert np.all(np.abs(gradient[u > 0]) <= 1e-8 * scale[u > 0])
    reference, _ = nnls(matrix, target, maxiter=5000)
    np.testing.assert_allclose(matrix @ u, matrix @ reference, atol=1e-8 * np.abs(target).max())


def test_a_programme_whose_warm_start_gives_up_is_solved_still(monkeypatch):
    """When warm_nnls gives up (here at once: no change of its passive set allowed) the
    programme is solved from its working set by scipy's NNLS, as without a warm start."""
    from cummins.radiation.passivity import enforcement

    rng = np.random.default_rng(7)
    misfit, g, h = _programme(rng, rows=60)
    _, u = least_distance_multipliers(misfit, g[:30], h[:30], start=np.ones(30, bool))
    monkeypatch.setattr(enforcement, "WARM_CHANGES", 0)
    assert enforcement.warm_nnls(np.eye(3), np.ones(3), np.zeros(1)) is None
    z, _ = least_distance_multipliers(misfit, g, h, start=np.ones(60, bool), warm=u)
    whole, _ = least_distance(misfit, g, h)
    np.testing.assert_allclose(z, whole, rtol=1e-8, atol=1e-10 * np.abs(whole).max())


def test_the_passive_cholesky_factor_follows_its_columns():
    """Columns added and removed in any order: RᵀR is the cross-products of the columns
    in the factor's order (to rounding), R upper triangular."""
    rng = np.random.default_rng(3)
    matrix = rng.standard_normal((40, 25))
    factor = _PassiveCholesky(matrix, np.array([0, 3, 5]))
    assert factor.ok
    for column in (7, 9, 1, 12):
        assert factor.add(column)
    for column in (3, 12, 0):
        factor.remove(column)
    assert factor.add(20)
    sub = matrix[:, factor.order]
    np.testing.assert_allclose(factor.r.T @ factor.r, sub.T @ sub, atol=1e-12 * 40)
    assert np.allclose(factor.r, np.triu(factor.r))
    rhs = rng.standard_normal(len(factor.order))
    np.testing.assert_allclose(sub.T @ sub @ factor.solve(rhs), rhs, atol=1e-10)
    assert not factor.add(factor.order[0])  # a column already in: dependent


@pytest.mark.parametrize("fortran", [False, True])
def test_the_triangular_solves_are_scipys(fortran):
    """The passive set's solves call LAPACK's trtrs as scipy's solve_triangular does, for
    a factor in either memory order (a fresh Cholesky factor is Fortran-ordered, an
    updated one C-ordered): R⁻ᵀ y and R⁻¹ y, and a singular R raises."""
    import scipy.linalg

    from cummins.radiation.passivity.enforcement import _triangular

    rng = np.random.default_rng(3)
    x = rng.standard_normal((40, 25))
    r = scipy.linalg.cholesky(x.T @ x, lower=False)
    r = np.asfortranarray(r) if fortran else np.ascontiguousarray(r)
    y = rng.standard_normal(25)
    for transposed in (False, True):
        expected = scipy.linalg.solve_triangular(r, y, trans="T" if transposed else "N")
        np.testing.assert_allclose(_triangular(r, y, transposed), expected, rtol=1e-12)
    singular = r.copy()
    singular[5, 5] = 0.0
    with pytest.raises(np.linalg.LinAlgError):
        _triangular(singular, y, False)
