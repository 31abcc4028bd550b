"""Reduction of the default (common-pole) models, block by block (issue 16: "``reduce``
meets its tolerance or says it cannot").

References: the unreduced block (an exact modal form, finite differences of a quadratic
form), the data's own motion RAOs (``motion_rao``, the scoreboard's comparison), and
independent checks of the results: the exact passivity test and a dense λ_min sweep,
K(0) and K − Kᵀ evaluated from the realization.
"""

from __future__ import annotations

import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import cummins
from cummins.errors import FitError
from cummins.radiation.fit import fit_radiation
from cummins.radiation.fit.scorecard import motion_rao_error, passivity_margin
from cummins.radiation.passivity import passivity_test
from cummins.radiation.reduce import frequency_response, reduce_radiation_model
from cummins.radiation.reduce.blocks import make_passive, prepared_block
from cummins.radiation.reduce.modal import modal_form

FLOAT_SPAR = Path(__file__).parent / "data" / "float_spar_capytaine.nc"


def _quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return function(*args, **kwargs)


@pytest.fixture(scope="module")
def tanker():
    ds = cummins.demo_dataset()
    return ds, _quiet(fit_radiation, ds)


@pytest.fixture(scope="module")
def float_spar():
    ds = cummins.read(FLOAT_SPAR)
    return ds, _quiet(fit_radiation, ds)


def _check_structure(model):
    """Every block: stable, K(0) = 0, K = Kᵀ, from its own matrices."""
    w = np.geomspace(1e-3, 50, 400)
    for block in model.blocks:
        a, b, c = block.a, block.b, block.c
        assert np.all(np.linalg.eigvals(a).real < 0)
        k = frequency_response(a, b, c, None, w)
        peak = np.abs(k).max()
        assert np.abs(c @ np.linalg.solve(a, b)).max() <= 1e-9 * peak
        assert np.abs(k - np.swapaxes(k, 1, 2)).max() <= 1e-9 * peak


def test_modal_form_is_exact_and_keeps_the_order(tanker):
    """The modal form of a fitted block (rank-limited symmetric residues) is the block:
    same K(jω) to rounding, same number of states; its realization too."""
    _, model = tanker
    w = np.geomspace(1e-2, 10, 300)
    for block in model.blocks:
        modal = modal_form(block.a, block.b, block.c)
        reference = frequency_response(block.a, block.b, block.c, None, w)
        peak = np.abs(reference).max()
        assert modal.order == block.order
        assert np.abs(modal.response(w) - reference).max() <= 1e-10 * peak
        assert np.abs(frequency_response(*modal.realization(), None, w) - reference).max() <= (
            1e-10 * peak
        )
        assert np.allclose(modal.dc(), 0.0, atol=1e-9 * peak)


def test_modal_derivative_against_central_differences(tanker):
    """K is quadratic in the vectors u: a central difference is exact up to rounding."""
    _, model = tanker
    block = model.blocks[0]
    modal = modal_form(block.a, block.b, block.c)
    x = modal.parameters()
    f = lambda p: 1.0 / (0.6j - p)  # noqa: E731
    jac = modal.derivative(f)
    rng = np.random.default_rng(3)
    for index in rng.choice(x.size, 6, replace=False):
        step = max(abs(x[index]), 1.0)  # exact for a quadratic: any step
        up, down = x.copy(), x.copy()
        up[index] += step
        down[index] -= step
        numeric = (modal.with_parameters(up).value(f) - modal.with_parameters(down).value(f)) / (
            2 * step
        )
        assert np.abs(numeric - jac[index]).max() <= 1e-6 * np.abs(jac[index]).max()


def test_tanker_by_tolerance(tanker):
    """tol 0.02: fewer states, passive by the exact test and by a dense sweep, K(0) = 0 and
    symmetry exact, the change within tol, no failure, motions within 3 % of the data's
    (1.4 % measured; the unreduced model 0.54 %)."""
    ds, model = tanker
    small = _quiet(reduce_radiation_model, model, tol=0.02, data=ds)
    assert small.total_order < 0.7 * model.total_order
    assert len(small.blocks) == len(model.blocks) and not small.couplings
    _check_structure(small)
    assert passivity_test(small).passive
    assert passivity_margin(small) >= -1e-6
    assert small.attrs["failures"] == model.attrs.get("failures", [])
    for block in small.blocks:
        for metrics in block.metrics.values():
            assert metrics["reduction_hinf_relative"] <= 0.02
            assert metrics["passive"] and metrics["stable"]
            assert metrics["r2_added_mass"] >= 0.95 and metrics["r2_damping"] >= 0.95
    assert motion_rao_error(ds, small).error <= 0.03
    assert "reduced by lyapunov balanced truncation of the block" in small.blocks[0].note


def test_tanker_by_total_order(tanker):
    """A total order is allocated over the blocks (minimax of the fit error); the result is
    passive at that order or, where no passive truncation exists, says which order it
    kept; R² of A and B against the data stay high."""
    ds, model = tanker
    small = _quiet(reduce_radiation_model, model, order=26, data=ds)
    notes = " ".join(b.note for b in small.blocks)
    assert small.total_order == 26 or "no passive truncation to" in notes
    assert small.total_order <= 30
    _check_structure(small)
    assert passivity_test(small).passive
    assert small.attrs["reduction_order_before"] == model.total_order
    assert motion_rao_error(ds, small).error <= 0.04


def test_mapping_names_a_block(tanker):
    """An order for a pair of a block's DOFs reduces that block; the others stay; two
    orders for one block are refused, naming it."""
    _, model = tanker
    first = model.blocks[0]
    i, j = first.dofs[0], first.dofs[-1]
    small = _quiet(reduce_radiation_model, model, order={(i, j): 12})
    assert small.blocks[0].order >= 12 and small.blocks[0].order < first.order
    assert small.blocks[1].order == model.blocks[1].order
    np.testing.assert_array_equal(small.blocks[1].a, model.blocks[1].a)
    with pytest.raises(FitError, match="one block"):
        reduce_radiation_model(model, order={(i, i): 10, (j, j): 12})


def test_an_unstable_block_is_refused(tanker):
    """A block with a pole in the right half-plane: a FitError naming its DOFs and the pole."""
    _, model = tanker
    bad = replace(model.blocks[0], a=-model.blocks[0].a)
    with pytest.raises(FitError, match=r"DOFs \(0, 2, 4\) .*not stable: a pole at"):
        reduce_radiation_model(replace(model, blocks=(bad, *model.blocks[1:])), tol=0.02)


def test_two_bodies_with_antisymmetric_added_mass(float_spar):
    """The float and spar (12 DOF, three blocks, the spar's antisymmetric A∞ kept): tol 0.01
    halves the states, passive and stable, motions within 2 % of the data's (1.0 %
    measured, the unreduced model 0.5 %), no failure; the antisymmetric A∞ is kept."""
    ds, model = float_spar
    small = _quiet(reduce_radiation_model, model, tol=0.01, data=ds)
    assert small.total_order <= 0.6 * model.total_order
    _check_structure(small)
    assert passivity_test(small).passive
    assert passivity_margin(small) >= -1e-6
    assert small.attrs["failures"] == []
    np.testing.assert_array_equal(small.added_mass_inf, model.added_mass_inf)
    assert motion_rao_error(ds, small).error <= 0.02


def test_a_correction_that_ruins_a_truncation_is_not_used(shared_data):
    """The sphere's surge–pitch block at 4 of its 8 states can only be made passive by
    ruining it (max(1 − R²) 0.3 → 900): a total order of 13 keeps more states there and
    says so, rather than returning a passive model that misses the data."""
    ds = cummins.read(shared_data / "wecsim" / "sphere" / "sphere_hydrodynamics.nc")
    model = _quiet(fit_radiation, ds)
    small = _quiet(reduce_radiation_model, model, order=13, data=ds)
    assert small.attrs["failures"] == []
    notes = " ".join(b.note for b in small.blocks)
    assert small.total_order == 13 or "no passive truncation to" in notes
    assert passivity_test(small).passive
    assert motion_rao_error(ds, small).error <= 0.02


def test_passivity_in_the_truncated_states(tanker):
    """A truncation with Re K < 0 somewhere is made passive without a new state, K(0) = 0
    kept, its fit to the unreduced block no worse than twice (independent sweep of the
    result, far beyond the fitted range)."""
    _, model = tanker
    block = model.blocks[1]
    grid = np.geomspace(model.attrs["omega_fit_min"], model.attrs["omega_fit_max"], 200)
    unit = prepared_block(block, 1, "lyapunov", 1e-6, grid)
    violating = None
    for r in range(6, block.order):
        x = unit.best(r)
        lam = np.linalg.eigvalsh(x.modal.response(unit.sweep).real)[:, 0]
        if lam.min() < -1e-4 * np.abs(lam).max():
            violating = x
            break
    assert violating is not None
    modal, passive, _, _ = make_passive(
        violating.modal, unit.reference, float(grid.min()), float(grid.max()), unit.peak
    )
    assert passive and modal.order == violating.order
    corrected = unit.passive(violating)
    assert corrected.passive and corrected.error <= 2 * violating.error + 1e-3
    w = np.geomspace(1e-4, 1e3, 4000)
    values = np.linalg.eigvalsh(modal.response(w).real)
    assert values[:, 0].min() >= -1e-8 * np.abs(values).max()
    assert np.abs(modal.dc()).max() <= 1e-11 * unit.peak


def test_response_jacobian_is_the_derivative(tanker):
    """d K_ij(jω)/du of the pairs i ≤ j against :meth:`ModalBlock.derivative`."""
    _, model = tanker
    modal = modal_form(model.blocks[0].a, model.blocks[0].b, model.blocks[0].c)
    omega = np.array([0.2, 0.7, 1.9])
    jac = modal.response_jacobian(omega)
    upper = np.triu_indices(modal.size)
    for g, w in enumerate(omega):
        full = modal.derivative(lambda p, w=w: 1.0 / (1j * w - p))[:, upper[0], upper[1]]
        np.testing.assert_allclose(jac[g], full.T, rtol=1e-10, atol=1e-12 * np.abs(full).max())


def test_form_gradients_are_the_contracted_derivative(tanker):
    """wᵀ Re K w and its gradient (the passivity constraints) against the full derivative,
    at a frequency and in both limits."""
    _, model = tanker
    block = model.blocks[1]
    modal = modal_form(block.a, block.b, block.c)
    w = np.random.default_rng(5).normal(size=(3, modal.size))
    functions = (lambda p: 1.0 / (0.4j - p), lambda p: -p, lambda p: 1.0 / p**3)
    fp = np.array([f(modal.poles) for f in functions])
    fq = np.array([f(np.conj(modal.poles)) for f in functions])
    values, rows = modal.form_gradients(w, fp, fq)
    for k, f in enumerate(functions):
        assert values[k] == pytest.approx(float(w[k] @ modal.value(f).real @ w[k]), rel=1e-10)
        full = np.einsum("i,kij,j->k", w[k], modal.derivative(f).real, w[k])
        np.testing.assert_allclose(rows[k], full, rtol=1e-9, atol=1e-12 * np.abs(full).max())
