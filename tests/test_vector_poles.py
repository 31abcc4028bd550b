"""The relocated poles made stable, damped and bounded (:func:`cummins.radiation.fit.
vector._poles_from`, Gustavsen & Semlyen (1999): unstable poles reflected into the left
half-plane)."""

from __future__ import annotations

import numpy as np

from cummins.radiation.fit.vector import MIN_DAMPING, _poles_from


def _conjugate_closed(pairs, real=()):
    pairs = np.asarray(pairs, dtype=complex)
    return np.r_[np.asarray(real, dtype=complex), pairs, np.conj(pairs)]


def test_unstable_and_light_poles_come_back_stable_damped_and_sorted():
    """An unstable pair is reflected, a pair damped below the floor is held at it, an
    unstable real pole is reflected, a pole at zero becomes a tiny negative one; the real
    poles sorted slowest first, the pairs by frequency."""
    values = _conjugate_closed([0.3 + 2.0j, -1e-4 + 0.5j, -0.8 + 1.0j], real=[2.0, -5.0, 0.0])
    poles = _poles_from(values, min_damping=MIN_DAMPING)
    assert np.all(poles.real < 0)
    np.testing.assert_array_equal(poles.real, np.sort(poles.real)[::-1])
    assert poles.real[0] == -np.finfo(float).eps
    np.testing.assert_allclose(poles.real[1:], [-2.0, -5.0])
    np.testing.assert_allclose(poles.pairs.imag, [0.5, 1.0, 2.0])
    # held at MIN_DAMPING of the relocated pole's magnitude: at least that of its frequency
    assert np.all(-poles.pairs.real >= MIN_DAMPING * poles.pairs.imag)
    np.testing.assert_allclose(poles.pairs[0].real, -MIN_DAMPING * abs(-1e-4 + 0.5j))
    np.testing.assert_allclose(poles.pairs[1:], [-0.8 + 1.0j, -0.3 + 2.0j])
    assert poles.count == values.size


def test_poles_beyond_the_limit_are_brought_to_it_along_their_ray():
    """A pole beyond ``limit`` keeps its direction at the limit's magnitude; the others do
    not move."""
    values = _conjugate_closed([-3.0 + 40.0j, -0.2 + 1.0j], real=[-100.0])
    poles = _poles_from(values, limit=20.0, min_damping=0.0)
    np.testing.assert_allclose(poles.real, [-20.0])
    np.testing.assert_allclose(np.abs(poles.pairs[1]), 20.0)
    np.testing.assert_allclose(np.angle(poles.pairs[1]), np.angle(-3.0 + 40.0j))
    assert poles.pairs[0] == -0.2 + 1.0j


def test_random_conjugate_sets_keep_their_count_and_the_floor():
    """Random sets closed under conjugation: as many real parameters come back, every
    pole stable, every pair damped by at least ``min_damping`` × its frequency, no real
    pole and no frequency beyond the limit."""
    rng = np.random.default_rng(3)
    for _ in range(50):
        pairs = rng.normal(size=6) + 1j * rng.uniform(0.1, 30.0, size=6)
        values = _conjugate_closed(pairs, real=rng.normal(size=3) * 10)
        poles = _poles_from(values, limit=25.0, min_damping=0.05)
        assert poles.count == values.size
        assert np.all(poles.real < 0) and np.all(poles.pairs.real < 0)
        # brought within the limit before the floor damps them: frequencies within it
        assert np.all(poles.real >= -25.0 * (1 + 1e-12))
        assert np.all(poles.pairs.imag <= 25.0 * (1 + 1e-12))
        assert np.all(-poles.pairs.real >= 0.05 * poles.pairs.imag)
