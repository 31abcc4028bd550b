"""The pole relocation's stop on a settled fit (:data:`cummins.radiation.fit.vector.SETTLED`):
what a relocation would still change, ‖P⊥ f (σ − d)‖ / (|d| ‖P⊥ f‖), falls as the relaxed
vector fitting converges (Gustavsen (2006)), and the fit stopped on it is the fit the
relocation converges to, within a few percent of its misfit."""

from __future__ import annotations

import numpy as np
import pytest

from cummins.radiation.fit import vector

OMEGA = np.linspace(0.05, 5.0, 250)


def _block(noise: float) -> vector.BlockData:
    """One element, A(ω) − A∞ − jB(ω)/ω of three damped pairs and a real pole, with
    complex noise of ``noise`` × its largest magnitude; weighted as the fit weighs."""
    s = 1j * OMEGA
    terms = [(-0.1 + 1j, 0.3 + 0.1j), (-0.6 + 1.5j, 1.0 - 0.5j), (-1.5 + 3.0j, 0.8 + 0.2j)]
    values = 0.5 / (s + 2.0)
    for p, r in terms:
        values = values + r / (s - p) + np.conj(r) / (s - np.conj(p))
    rng = np.random.default_rng(3)
    scale = noise * np.abs(values).max()
    values = values + scale * (rng.standard_normal(s.size) + 1j * rng.standard_normal(s.size))
    n = OMEGA.size
    weight_real = np.ones((1, n)) / np.std(values.real) / np.sqrt(n)
    weight_imag = OMEGA[None] / np.std(OMEGA * values.imag) / np.sqrt(n)
    return vector.BlockData(
        (0,), ((0, 0),), OMEGA, values[None], weight_real, weight_imag, np.zeros(1), n
    )


def _counted(monkeypatch) -> list[int]:
    calls = [0]
    relocation = vector.relocation

    def counting(data, poles):
        calls[0] += 1
        return relocation(data, poles)

    monkeypatch.setattr(vector, "relocation", counting)
    return calls


def _misfit(data: vector.BlockData, fit: vector.PoleResidueBlock) -> float:
    r = fit.element_response(OMEGA)[:, 0] / (1j * OMEGA) - data.values[0]
    return float(
        np.hypot(
            np.linalg.norm(data.weight_real[0] * r.real),
            np.linalg.norm(data.weight_imag[0] * r.imag),
        )
    )


def test_the_change_vanishes_as_the_relocation_converges():
    """From the starting poles the relocation changes the fit by about its misfit; at the
    converged poles (moves below CONVERGED) by a vanishing part of it."""
    data = _block(1e-3)
    poles = vector.starting_poles(OMEGA, 6)
    moved, first = vector.relocation(data, poles)
    assert first > 10 * vector.SETTLED
    for _ in range(40):
        poles, (moved, change) = moved, vector.relocation(data, moved)
        if vector._same_poles(moved, poles):
            break
    else:
        pytest.fail("the relocation did not converge")
    assert change < 1e-3 * vector.SETTLED


def test_a_settled_fit_is_the_converged_fit(monkeypatch):
    """Noisier data, a slowly converging relocation: stopped on SETTLED, in fewer
    relocations than the poles take to converge (8 against 18), with the converged fit's
    misfit to a few percent (0.9 %)."""
    data = _block(1e-2)
    calls = _counted(monkeypatch)
    settled = vector.vector_fit(data, 6)
    used = calls[0]
    monkeypatch.setattr(vector, "SETTLED", 0.0)
    monkeypatch.setattr(vector, "ITERATIONS", 100)
    calls[0] = 0
    converged = vector.vector_fit(data, 6)
    assert used < calls[0] < 100
    assert abs(_misfit(data, settled) - _misfit(data, converged)) <= 3e-2 * _misfit(data, converged)
