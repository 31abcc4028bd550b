"""What the pairs of a block share (:class:`cummins.radiation.model.ModalForm`: V⁻¹ b and
e^{λ t} kept) and the passivity sweep's batched response: the same numbers as each
computed alone, the einsum's sums to rounding."""

from __future__ import annotations

import numpy as np

from cummins.radiation.model import (
    MemoryBlock,
    ModalForm,
    RadiationModel,
    modal_form,
    siso_frequency_response,
    siso_impulse_response,
)


def _block(seed: int, m: int = 3, count: int = 4):
    """A stable block of ``count`` modes per DOF pair: (a, b, c)."""
    rng = np.random.default_rng(seed)
    n = 2 * count
    a = np.zeros((n, n))
    for k in range(count):
        w0, zeta = rng.uniform(0.3, 3.0), rng.uniform(0.05, 0.5)
        a[2 * k : 2 * k + 2, 2 * k : 2 * k + 2] = [[0.0, 1.0], [-(w0**2), -2 * zeta * w0]]
    return a, rng.standard_normal((n, m)), rng.standard_normal((m, n))


def test_the_shared_modal_form_gives_each_pairs_own_numbers():
    a, b, c = _block(0)
    t, fine = np.linspace(0.0, 30.0, 301), np.linspace(0.0, 30.0, 1201)
    w = np.geomspace(0.05, 20.0, 90)
    shared = modal_form(a)
    assert isinstance(shared, ModalForm)
    for i in range(c.shape[0]):
        for j in range(b.shape[1]):
            for grid in (t, fine, t):  # the grids alternate, as a block's pairs ask them
                alone = siso_impulse_response(a, b[:, j], c[i], grid, tuple(modal_form(a)))
                np.testing.assert_allclose(
                    siso_impulse_response(a, b[:, j], c[i], grid, shared), alone, rtol=1e-13
                )
            np.testing.assert_allclose(
                siso_frequency_response(a, b[:, j], c[i], w, shared),
                siso_frequency_response(a, b[:, j], c[i], w, tuple(modal_form(a))),
                rtol=1e-13,
            )
    # one e^{λ t} per grid and one V⁻¹ b per input column, not one per pair
    assert shared.exponentials(t) is shared.exponentials(t)
    assert shared.exponentials(fine) is not shared.exponentials(t)
    assert len(shared._solved) == b.shape[1]


def test_the_batched_response_is_the_einsums_to_rounding():
    a, b, c = _block(1, m=3, count=5)
    block = MemoryBlock((0, 1, 2), a, b, c, "vf", {}, "")
    model = RadiationModel(("Surge", "Heave", "Pitch"), (), np.eye(3), {}, (block,))
    w = np.geomspace(1e-3, 1e3, 700)
    exact, batched = model.response(w), model.response(w, batched=True)
    assert batched.shape == exact.shape
    np.testing.assert_allclose(batched, exact, rtol=1e-11, atol=1e-13 * np.abs(exact).max())
