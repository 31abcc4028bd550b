"""The motions fitted themselves (``refine_motions``, :mod:`cummins.radiation.fit.
motion_refinement`): a block that misses its motion aim has its residues refined on the
motion RAOs by Gauss–Newton steps, passive at every step.

References: the derivative of the motions by finite differences; the demo ship with a
bump in its heave added mass that its damping does not have (not Kramers–Kronig
consistent: no causal model follows both; measured 2.46 % → 1.14 %, 2026-12-06); WEC-Sim's
RM3 from WAMIT (3.73 % → 0.40 % of the scoreboard, 20 common poles, by default since its
motions miss their target); the HAMS cylinder, whose non-reciprocal data keep it at 12.6 %
(the default's refinement gives up: the model as without it).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import cummins
from _synthetic import demo_block_motion_error, wecsim_rm3
from cummins.radiation.fit import fit_radiation
from cummins.radiation.fit.scorecard import motion_rao_error
from cummins.radiation.passivity import passivity_test


def _fit(ds, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fit_radiation(ds, **options)


@pytest.mark.parametrize("dofs", [(2,), (0, 2, 4)])
def test_the_linearised_motions_are_their_derivative(dofs):
    """BlockMotionError.linearised: its residuals are the motion error of __call__ (the
    largest, to rounding) and its derivative predicts a small change of K̂ as finite
    differences do (δX = −Z⁻¹ jω δK̂ X)."""
    _, k_data, w, errors = demo_block_motion_error()
    index = np.asarray(dofs)
    rng = np.random.default_rng(3)
    k_block = k_data[:, index[:, None], index[None, :]] * (
        1 + 0.1 * rng.uniform(-1, 1, (w.size, len(dofs), len(dofs)))
    )
    omega, r, s = errors.linearised(dofs, k_block)
    assert np.array_equal(omega, w)
    assert np.abs(r).max() == pytest.approx(errors(dofs, k_block), rel=1e-9)
    step = 1e-6 * k_block * rng.uniform(-1, 1, k_block.shape)
    moved = errors.linearised(dofs, k_block + step)[1]
    predicted = np.einsum("wrab,wab->wr", s, step)
    assert np.abs(moved - r - predicted).max() < 1e-3 * np.abs(predicted).max()


@pytest.fixture(scope="module")
def bumped():
    """The demo ship with 10 % of its heave added mass peak added as a bump at 0.8 rad/s
    that its damping does not have."""
    ds = cummins.demo_dataset().copy(deep=True)
    w = ds.omega.values
    heave = list(ds.influenced_dof.values).index("Heave")
    a = ds.added_mass.values
    a[:, heave, heave] += (
        0.1 * np.abs(a[:, heave, heave]).max() * np.exp(-(((w - 0.8) / 0.15) ** 2))
    )
    return ds


def test_the_refinement_brings_the_motions_nearer(bumped):
    """The default misses its motion aim (2.46 % measured); refined, the motions are
    nearer the data's (1.14 %), the model stable and passive, its note says so, and the
    refinement adds no failure."""
    plain = _fit(bumped)
    refined = _fit(bumped, refine_motions=True)
    before = motion_rao_error(bumped, plain).error
    after = motion_rao_error(bumped, refined).error
    assert before > 0.02
    assert after < 0.6 * before
    assert refined.attrs["motion_error"] < plain.attrs["motion_error"]
    assert np.all(np.linalg.eigvals(refined.A).real < 0)
    assert passivity_test(refined).passive
    assert any("refined on the motions" in n for n in refined.attrs["data_notes"])
    assert len(refined.attrs["failures"]) <= len(plain.attrs["failures"])


def test_a_fit_within_its_aim_is_not_refined():
    """The demo meets its aim: the option changes nothing."""
    ds = cummins.demo_dataset()
    plain, refined = _fit(ds), _fit(ds, refine_motions=True)
    assert np.array_equal(plain.A, refined.A) and np.array_equal(plain.C, refined.C)


@pytest.mark.parametrize("refine", [None, True])
def test_rm3_refined_meets_the_motion_target(shared_data, refine):
    """WEC-Sim's RM3 (issue 30): unrefined 3.7 % of the peak; refined on its motions —
    by default, its motions missing their target, and with the option — within the
    scoreboard's 1 % (0.40 % measured, 20 common poles), passive by the exact test and
    stable, without the motion failure; its notes those of the refined fit."""
    ds = wecsim_rm3(shared_data)
    model = _fit(ds, refine_motions=refine)
    assert motion_rao_error(ds, model).error <= 0.006  # the aim, 0.8 %, with room
    assert np.all(np.linalg.eigvals(model.A).real < 0)
    assert passivity_test(model).passive
    assert not [f for f in model.attrs["failures"] if f.startswith("motion error")]
    # the float's pitch, refined without BeyondBounds, peaked beyond the data (28 %)
    assert not [f for f in model.attrs["failures"] if "beyond the data" in f]
    notes = model.attrs["data_notes"]
    assert any(n.startswith("A∞ of") for n in notes)  # the refit's A∞, said once
    assert any("refined on the motions at 20 common poles" in n for n in notes)
    assert not any("the motions miss their aim" in n for n in notes)  # the search's, gone


def test_a_fit_the_refinement_cannot_help_is_left_as_it_was(shared_data):
    """The HAMS cylinder misses its motion target by its data (not reciprocal: 12.6 %);
    the default's refinement gives up every number of poles whose steps stay above the
    target: the model is the unrefined one, matrix for matrix."""
    path = shared_data / "corpus" / "HAMS" / "Cylinder" / "Output_Benchmark" / "Wamit_format"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = cummins.read(path / "Buoy.1")
    default, never = _fit(ds), _fit(ds, refine_motions=False)
    assert default.attrs["motion_error"] > default.attrs["motion_target"]  # the premise
    assert np.array_equal(default.A, never.A) and np.array_equal(default.C, never.C)
    assert not any("refined on the motions" in n for n in default.attrs["data_notes"])


def test_the_refinement_option_has_three_states():
    """None (the default), True and False; anything else is refused naming them."""
    from cummins.errors import FitError
    from cummins.radiation.fit import DEFAULT

    assert DEFAULT.refine_motions is None
    with pytest.raises(FitError, match="refine_motions"):
        DEFAULT.with_changes(refine_motions="yes").checked()


def test_the_grouped_normal_equations_are_those_of_the_jacobian():
    """motion_normal: Re JᴴJ and Re Jᴴy grouped by elements (the symmetries T_fe = T_efᵀ
    and those of φ̄_a φ_b) are those of the explicit (ω·R) × z Jacobian, d r / d z of an
    element (i, j) the sensitivity at (i, j) and (j, i) (an antisymmetric part (p, q):
    + at (p, q), − at (q, p)) times jω basis(jω) N_e, and jω for a free A∞."""
    from types import SimpleNamespace

    from cummins.radiation.fit.motion_refinement import (
        Coordinates,
        element_maps,
        element_sensitivities,
        motion_normal,
    )
    from cummins.radiation.fit.poles import Poles
    from cummins.radiation.fit.vector import PoleResidueBlock

    rng = np.random.default_rng(5)
    poles = Poles(np.array([-0.3, -2.0]), np.array([-0.1 + 0.8j, -0.4 + 1.7j]))
    dofs, elements = (0, 2, 4), ((0, 0), (0, 2), (2, 2), (2, 4), (4, 4), (4, 2))
    block = PoleResidueBlock(
        dofs, elements, poles, np.zeros((len(elements), poles.count)), np.zeros(len(elements))
    )
    free = np.array([True, False, True, True, False, False])
    coords = Coordinates.of(block, SimpleNamespace(free_inf=free))
    omega = np.linspace(0.2, 3.0, 17)
    sensitivity = rng.normal(size=(omega.size, 4, 3, 3)) + 1j * rng.normal(
        size=(omega.size, 4, 3, 3)
    )
    weighted = element_sensitivities(block, sensitivity)
    residual = rng.normal(size=(omega.size, 4)) + 1j * rng.normal(size=(omega.size, 4))
    normal, rhs = motion_normal(block, coords, omega, weighted, residual)
    # the explicit Jacobian, column by column
    s = 1j * omega
    phi = np.concatenate([s[:, None] * poles.basis(s), s[:, None]], axis=1)
    maps, _ = element_maps(coords, poles.count)
    jac = np.zeros((omega.size, 4, coords.size), dtype=complex)
    where = {d: k for k, d in enumerate(dofs)}
    for e, (i, j) in enumerate(elements):
        a, b = where[i], where[j]
        g = sensitivity[:, :, a, a] if i == j else sensitivity[:, :, a, b]
        if i < j:
            g = g + sensitivity[:, :, b, a]
        elif i > j:
            g = g - sensitivity[:, :, b, a]
        start, stop = coords.offsets[e], coords.offsets[e + 1]
        jac[:, :, start:stop] = g[:, :, None] * (phi @ maps[e])[:, None, : stop - start]
    jac = jac.reshape(-1, coords.size)
    expected = (np.conj(jac).T @ jac).real
    assert np.allclose(normal, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())
    assert np.allclose(rhs, (np.conj(jac).T @ residual.reshape(-1)).real, rtol=1e-12)
