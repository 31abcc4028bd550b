"""The partial-fraction basis of the common poles (:mod:`cummins.radiation.fit.poles`):
the basis kept for a grid serves that grid's leading frequencies with the numbers a
fresh evaluation gives."""

from __future__ import annotations

import numpy as np
import pytest

from cummins.radiation.fit.poles import Poles


def _poles() -> Poles:
    return Poles(np.array([-0.7]), np.array([-0.05 + 0.4j, -0.2 + 1.3j, -0.6 + 2.9j]))


@pytest.mark.parametrize("leading", [1, 17, 199])
def test_kept_basis_at_leading_frequencies_is_the_basis_there(leading):
    """After the basis at 200 frequencies is kept, the basis at its first ``leading``
    frequencies is bit for bit what a fresh evaluation gives, and read-only."""
    s = 1j * np.geomspace(0.05, 8.0, 200)
    poles = _poles()
    whole = poles.kept_basis(s)
    part = poles.kept_basis(s[:leading])
    np.testing.assert_array_equal(part, _poles().basis(s[:leading]))
    np.testing.assert_array_equal(part, whole[:leading])
    assert not part.flags.writeable


def test_kept_basis_of_other_frequencies_is_computed_afresh():
    """Frequencies that are not a leading run of a kept grid (here its last 50, and a
    grid that starts like it but goes on elsewhere) get their own basis."""
    s = 1j * np.geomspace(0.05, 8.0, 200)
    poles = _poles()
    poles.kept_basis(s)
    tail = s[150:]
    np.testing.assert_array_equal(poles.kept_basis(tail), _poles().basis(tail))
    other = np.r_[s[:100], 1j * np.linspace(9.0, 12.0, 120)]
    found = poles.kept_basis(other)
    assert found.shape == (220, 7)
    np.testing.assert_array_equal(found, _poles().basis(other))
