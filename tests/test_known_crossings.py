"""The model's passivity test given the crossings of its block's last exact test.

The enforcement and the motion refinement end on an exact test of the block they
return (:func:`~cummins.radiation.fit.block_passivity.passivity_violations`, on the
poles' coordinate realization); the model made of that one block tests the same K(s)
on Gilbert's realization, and takes those crossings instead of a second QZ of the
Hamiltonian pencil (:func:`~cummins.radiation.fit.block_passivity.exact_crossings`,
``passivity_test(model, known=...)``). These tests check that the crossings are kept
for that block only, that they are those of the model, and that the test given them
reaches the same verdict.
"""

from __future__ import annotations

import numpy as np
import pytest

from cummins.radiation.fit import block_passivity
from cummins.radiation.fit.vector import PoleResidueBlock, Poles
from cummins.radiation.model import MemoryBlock, RadiationModel
from cummins.radiation.passivity import passivity_test


def _block(seed: int) -> PoleResidueBlock:
    """A symmetric 2-DOF block over one real pole and three pairs, random residues on a
    passive diagonal: a coupling that makes it not passive in some bands."""
    poles = Poles(np.array([-0.5]), np.array([-0.2 + 1.0j, -0.4 + 2.5j, -0.3 + 4.0j]))
    elements = ((0, 0), (0, 1), (1, 1))
    rng = np.random.default_rng(seed)
    coefficients = rng.standard_normal((len(elements), poles.count))
    return PoleResidueBlock((0, 1), elements, poles, coefficients, np.zeros(len(elements)))


def _model(block: PoleResidueBlock) -> RadiationModel:
    a, b, c = block.realization()
    return RadiationModel(("Surge", "Heave"), (), np.eye(2), {}, (MemoryBlock((0, 1), a, b, c),))


def test_the_crossings_are_kept_for_the_block_last_tested_only():
    first, second = _block(1), _block(2)
    block_passivity.passivity_violations(first, 0.1, 10.0, exact=True)
    kept = block_passivity.exact_crossings(first)
    assert kept is not None
    # an equal block that is another object, and the block after another's test: None
    same = PoleResidueBlock(
        first.dofs, first.elements, first.poles, first.coefficients.copy(), first.added_mass_inf
    )
    assert block_passivity.exact_crossings(same) is None
    block_passivity.passivity_violations(second, 0.1, 10.0, exact=True)
    assert block_passivity.exact_crossings(first) is None
    assert block_passivity.exact_crossings(second) is not None


@pytest.mark.parametrize("seed", [1, 2, 5, 8])
def test_the_model_given_its_block_crossings_reaches_the_same_verdict(seed):
    block = _block(seed)
    block_passivity.passivity_violations(block, 0.1, 10.0, exact=True)
    known = block_passivity.exact_crossings(block)
    model = _model(block)
    own = passivity_test(model)
    given = passivity_test(model, known=(block.dofs, known))
    assert given.passive == own.passive
    np.testing.assert_array_equal(given.crossings, known)
    # the crossings of K whichever realization and DOF scaling (off the origin's cluster)
    real = own.crossings[own.crossings > 1e-3]
    np.testing.assert_allclose(real, known[known > 1e-3], rtol=1e-6)
    assert len(given.bands) == len(own.bands)
    for x, y in zip(given.bands, own.bands, strict=True):
        assert x.min_eigenvalue == pytest.approx(y.min_eigenvalue, rel=1e-6, abs=1e-12)
    assert given.min_eigenvalue == pytest.approx(own.min_eigenvalue, rel=1e-6, abs=1e-12)


def test_crossings_of_other_dofs_are_not_used():
    block = _block(1)
    model = _model(block)
    own = passivity_test(model)
    given = passivity_test(model, known=((0,), np.array([1.234])))
    np.testing.assert_array_equal(given.crossings, own.crossings)
    assert given.passive == own.passive
