"""What a fit asks for twice on the same data, kept: the Kramers–Kronig integral of the
data's damping (Ogilvie's A∞ and the data's causality with the model's A∞, before and
after the refit with A∞ estimated) and a block's damping tails (the fit and its refit).
The answer kept is the one computed, read-only; other data are computed anew."""

from __future__ import annotations

import numpy as np
import pytest

import cummins
from cummins.radiation import infinite_frequency
from cummins.radiation.fit import tail
from cummins.radiation.retardation import kramers_kronig_added_mass


def test_the_kramers_kronig_integral_is_kept_for_the_same_data():
    ds = cummins.demo_dataset()
    infinite_frequency._last_integral.clear()
    first = infinite_frequency._kramers_kronig_integral(ds, "auto")
    again = infinite_frequency._kramers_kronig_integral(ds.copy(deep=True), "auto")
    assert again is first
    assert not first.flags.writeable
    with pytest.raises(ValueError):
        first[0, 0, 0] = 1.0
    # other data, or another tail: computed anew, as without the one kept
    changed = ds.copy(deep=True)
    changed["radiation_damping"] = 2.0 * changed["radiation_damping"]
    doubled = infinite_frequency._kramers_kronig_integral(changed, "auto")
    assert doubled is not first
    infinite_frequency._last_integral.clear()
    np.testing.assert_array_equal(
        doubled, infinite_frequency._kramers_kronig_integral(changed, "auto")
    )
    other = infinite_frequency._kramers_kronig_integral(ds, "none")
    infinite_frequency._last_integral.clear()
    np.testing.assert_array_equal(other, infinite_frequency._kramers_kronig_integral(ds, "none"))
    # the public answers with A∞ added are new arrays each time
    a_inf = np.zeros((ds.sizes["influenced_dof"],) * 2)
    predicted = kramers_kronig_added_mass(ds, added_mass_inf=a_inf)
    assert predicted.values.flags.writeable


def _block_arrays(seed: int):
    rng = np.random.default_rng(seed)
    w = np.linspace(0.1, 3.0, 40)
    peak = np.exp(-((w - 1.0) ** 2))
    damping = peak[:, None, None] * (np.eye(2) + 0.3 * rng.random((2, 2)))[None]
    damping = 0.5 * (damping + np.swapaxes(damping, 1, 2))
    added_mass = 1.0 + 0.2 * peak[:, None, None] * np.ones((1, 2, 2))
    used = np.ones((w.size, 3), dtype=bool)
    return w, added_mass, damping, used, [(0, 0), (0, 1), (1, 1)], tail.tail_frequencies(3.0)


def test_a_block_tails_are_kept_for_the_same_arguments():
    args = _block_arrays(1)
    tail._last_tails.clear()
    first = tail.block_tail_equations(*args)
    again = tail.block_tail_equations(
        *(np.copy(x) if isinstance(x, np.ndarray) else x for x in args)
    )
    assert all(x[0] is y[0] for x, y in zip(again, first, strict=True))  # the same arrays
    assert all(not x[0].flags.writeable for x in first)
    direct = tail._block_tail_equations(*args)
    for (b, weight, _), (b_direct, weight_direct, _) in zip(first, direct, strict=True):
        np.testing.assert_array_equal(b, b_direct)
        np.testing.assert_array_equal(weight, weight_direct)
    other = _block_arrays(2)
    changed = tail.block_tail_equations(*other)
    for (b, _, _), (b_direct, _, _) in zip(
        changed, tail._block_tail_equations(*other), strict=True
    ):
        np.testing.assert_array_equal(b, b_direct)


def test_the_diagonal_kernels_are_kept_for_the_same_arguments():
    from cummins.radiation import retardation

    ds = cummins.demo_dataset()
    t = np.linspace(0.0, 20.0, 201)
    retardation._last_diagonal.clear()
    first = retardation.diagonal_retardation_functions(ds, t, [0, 2])
    assert retardation.diagonal_retardation_functions(ds.copy(deep=True), t.copy(), [0, 2]) is first
    assert not first.flags.writeable
    full = retardation.retardation_function(ds, t).values
    top = np.abs(full).max()
    np.testing.assert_allclose(first, full[:, [0, 2], [0, 2]], rtol=1e-10, atol=1e-12 * top)
    # other DOFs or times: computed anew
    other = retardation.diagonal_retardation_functions(ds, t, [1])
    np.testing.assert_allclose(other[:, 0], full[:, 1, 1], rtol=1e-10, atol=1e-12 * top)
    later = retardation.diagonal_retardation_functions(ds, t[:50], [0, 2])
    np.testing.assert_allclose(later, first[:50], rtol=1e-10, atol=1e-12 * top)


def test_an_answer_kept_in_one_thread_is_not_another_threads():
    import threading

    from cummins.arrays import LastAnswer, digest

    last = LastAnswer()
    key = digest(np.arange(3.0), "auto")
    assert digest(np.arange(3.0), "auto") == key
    assert digest(np.arange(3), "auto") != key  # another dtype, another key
    assert last.keep(key, "mine") == "mine" and last.get(key) == "mine"
    seen = []
    thread = threading.Thread(target=lambda: seen.append(last.get(key)))
    thread.start()
    thread.join()
    assert seen == [None]
    assert last.get(digest(np.arange(4.0), "auto")) is None
    last.clear()
    assert last.get(key) is None


def test_forgetting_the_kept_answers_empties_every_one():
    from cummins.arrays import forget_kept_answers

    ds = cummins.demo_dataset()
    first = infinite_frequency._kramers_kronig_integral(ds, "auto")
    assert infinite_frequency._kramers_kronig_integral(ds, "auto") is first
    forget_kept_answers()
    again = infinite_frequency._kramers_kronig_integral(ds, "auto")
    assert again is not first  # computed anew: the same numbers
    np.testing.assert_array_equal(again, first)
