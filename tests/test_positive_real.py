"""The positive-real test of a fitted coupling (`cummins.radiation.fit.frequency`): the
verdict of `is_positive_real` without polishing the local minima a bound proves harmless."""

from __future__ import annotations

import numpy as np
import pytest

from cummins.radiation.fit import frequency
from cummins.radiation.fit.frequency import (
    PR_TOLERANCE,
    _bracket_floor,
    is_positive_real,
    minimum_real_part,
)


def _random_model(rng: np.random.Generator, pairs: int, real: int):
    """Stable poles (conjugate pairs and real ones) and residues (conjugate for pairs)."""
    centre = np.exp(rng.uniform(-1.0, 2.0, pairs))
    damping = centre * np.exp(rng.uniform(np.log(0.02), np.log(0.8), pairs))
    upper = -damping + 1j * centre
    residue = (rng.uniform(0.1, 2.0, pairs) + 1j * rng.normal(0.0, 0.5, pairs)) * centre
    poles = np.concatenate([upper, upper.conj(), -np.exp(rng.uniform(-1.0, 2.0, real))])
    residues = np.concatenate([residue, residue.conj(), rng.uniform(0.1, 2.0, real)])
    return poles, residues


def _re_k(poles, residues, omega):
    return np.real((residues / (1j * np.asarray(omega)[:, None] - poles)).sum(axis=1))


def test_bracket_floor_is_a_lower_bound():
    rng = np.random.default_rng(3)
    checked = 0
    for _ in range(60):
        poles, residues = _random_model(rng, int(rng.integers(1, 5)), int(rng.integers(0, 3)))
        for _ in range(20):
            centre = float(np.exp(rng.uniform(-2.0, 3.0)))
            if rng.random() < 0.5:  # around a resonance, where the bound is weakest
                centre = float(abs(poles[int(rng.integers(poles.size))].imag)) or centre
            h = centre * float(np.exp(rng.uniform(np.log(1e-4), np.log(0.3))))
            split = float(rng.choice([1e-9, 1e-3, rng.uniform(0.05, 0.95)]))
            x = np.array([centre - h / 2, centre - h / 2 + split * h, centre + h / 2])
            if x[0] <= 0:
                continue
            floor = _bracket_floor(x, _re_k(poles, residues, x), poles, residues)
            dense = _re_k(poles, residues, np.linspace(x[0], x[2], 4001))
            assert floor <= dense.min()
            checked += np.isfinite(floor)
    assert checked > 500


def test_bracket_floor_has_no_bound_without_distance():
    poles = np.array([-0.0 + 1j, -0.0 - 1j])  # on the axis: no bound
    x = np.array([0.9, 1.0, 1.1])
    assert _bracket_floor(x, np.ones(3), poles, np.ones(2)) == -np.inf


def _verdict(poles, residues) -> bool:
    """The verdict from the whole search (every local minimum polished)."""
    if np.any(np.real(poles) >= 0):
        return False
    minimum, _, k_max = minimum_real_part(poles, residues)
    return bool(minimum >= -PR_TOLERANCE * max(k_max, np.finfo(float).tiny))


def test_the_verdict_is_that_of_the_whole_search():
    rng = np.random.default_rng(7)
    verdicts = []
    for _ in range(150):
        poles, residues = _random_model(rng, int(rng.integers(1, 5)), int(rng.integers(0, 3)))
        # a real part shifted so that its least value sits near zero, on either side
        minimum, _, k_max = minimum_real_part(poles, residues)
        offset = minimum + k_max * PR_TOLERANCE * float(rng.choice([-2.0, -1.001, 0.5, 3.0]))
        extra = -1e3 * abs(poles).max()  # a fast real pole: Re K shifted by ≈ −offset
        shifted = (np.append(poles, extra), np.append(residues, offset * extra))
        for model in ((poles, residues), shifted):
            expected = _verdict(*model)
            assert is_positive_real(*model) == expected
            verdicts.append(expected)
    assert 0.2 < np.mean(verdicts) < 0.9  # both verdicts seen


def test_a_passive_model_is_judged_without_polishing(monkeypatch):
    # two resonances and Re K > 0 between them: a local minimum the bound proves
    poles = np.array([-0.1 + 1j, -0.1 - 1j, -0.3 + 5j, -0.3 - 5j])
    residues = np.array([0.2, 0.2, 1.5, 1.5], dtype=complex)
    calls = []
    original = frequency.minimize_scalar

    def counted(*args, **kwargs):
        calls.append(1)
        return original(*args, **kwargs)

    monkeypatch.setattr(frequency, "minimize_scalar", counted)
    minimum_real_part(poles, residues)
    assert calls  # the whole search polishes
    calls.clear()
    assert is_positive_real(poles, residues)
    assert not calls


@pytest.mark.parametrize("scale", [1.0, -1.0])
def test_a_negative_grid_value_decides_at_once(scale):
    poles = np.array([-0.1 + 1j, -0.1 - 1j])
    residues = scale * np.array([0.2, 0.2], dtype=complex)
    assert is_positive_real(poles, residues) == (scale > 0)


def test_the_grid_response_by_blocks_is_the_whole_arrays():
    from cummins.radiation.fit.frequency import RESPONSE_ROWS, _partial_fractions

    rng = np.random.default_rng(11)
    poles, residues = _random_model(rng, 40, 5)
    grid = np.geomspace(1e-3, 1e3, 3 * RESPONSE_ROWS + 17)
    whole = (residues / (1j * grid[:, None] - poles)).sum(axis=1)
    np.testing.assert_allclose(_partial_fractions(residues, poles, grid), whole, rtol=1e-14)
