"""The canonical QTF: the full square from one triangle (unidirectional and bi-directional
files), the symmetries kept by the interpolation, damage refused."""

from __future__ import annotations

import numpy as np
import pytest

from cummins.errors import HydroDataError
from cummins.qtf import QTFTable, complete_square, interpolate, pair_matrix


def _bidirectional(rng, n=6, m=3, d=2):
    """A random QTF with Q(ω_j, ω_i, β_b, β_a) = Q(ω_i, ω_j, β_a, β_b)*."""
    q = rng.standard_normal((n, n, m, m, d)) + 1j * rng.standard_normal((n, n, m, m, d))
    return 0.5 * (q + np.conj(np.transpose(q, (1, 0, 3, 2, 4))))


def _error(message, row):
    return HydroDataError(f"{message} (row {row})")


def test_the_square_from_one_triangle_of_every_direction_pair():
    """As NEMOH writes a bi-directional QTF: ω₁ ≥ ω₂, every (β₁, β₂)."""
    rng = np.random.default_rng(0)
    w, beta = np.linspace(0.3, 1.8, 6), np.radians([0.0, 45.0, 90.0])
    q = _bidirectional(rng)
    rows = [
        (w[i], w[j], beta[a], beta[b], k, q[i, j, a, b, k])
        for k in range(2)
        for a in range(3)
        for b in range(3)
        for i in range(6)
        for j in range(i + 1)
    ]
    cols = list(zip(*rows, strict=True))
    omega, directions, values, bidirectional, present = complete_square(
        "difference", *cols[:5], cols[5], n_dofs=2, error=_error
    )
    assert bidirectional and present.all()
    assert np.allclose(omega, w) and np.allclose(directions, beta)
    assert np.allclose(values, q)
    # a row deleted is refused, not a zero
    with pytest.raises(HydroDataError, match="no value for omega"):
        complete_square("difference", *[c[1:] for c in cols[:6]], n_dofs=2, error=_error)


def test_bidirectional_interpolation_keeps_the_symmetry():
    rng = np.random.default_rng(1)
    table = QTFTable(
        "difference",
        np.linspace(0.3, 1.8, 6),
        np.radians([-90.0, 0.0, 90.0, 180.0]),
        _bidirectional(rng, m=4),
        ("Surge", "Heave"),
        bidirectional=True,
    )
    omega = rng.uniform(0.3, 1.8, 30)
    beta = rng.choice(np.radians([-20.0, 10.0, 60.0]), 30)
    m = pair_matrix(table, 1, omega, beta)
    assert np.allclose(m, np.conj(m.T))
    # pointwise interpolation agrees with the block construction
    i, j = 3, 17
    assert interpolate(table, omega[i], omega[j], beta[i], beta[j])[1] == pytest.approx(m[i, j])
