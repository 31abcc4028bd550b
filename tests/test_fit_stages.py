"""The identification as stages a user can call (cummins.radiation.fit): the options as one
frozen ``FitOptions`` with named presets, and ``prepare_fit`` → ``fit_blocks`` /
``fit_per_coupling`` composing to what ``fit_radiation`` returns, on the bundled tanker."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import cummins
from cummins.radiation.fit import (
    DEFAULT,
    MOTION_ACCURACY,
    PREVIOUS_DEFAULT,
    FitError,
    FitOptions,
    fit_blocks,
    fit_per_coupling,
    fit_radiation,
    prepare_fit,
)


@pytest.fixture(scope="module")
def tanker():
    return cummins.demo_dataset()


def test_options_are_frozen_and_presets_are_named_instances():
    assert FitOptions() == DEFAULT
    with pytest.raises(dataclasses.FrozenInstanceError):
        DEFAULT.r2 = 0.5
    # a preset as a mapping holds the fields it sets away from the defaults
    assert dict(MOTION_ACCURACY) == {"motion_tol": 0.002}
    assert dict(PREVIOUS_DEFAULT) == {
        "method": "fd",
        "weighting": "uniform",
        "exclude_suspect": "above_first",
    }
    assert dict(DEFAULT) == {}
    assert MOTION_ACCURACY.with_changes(r2=0.95).r2 == 0.95
    assert MOTION_ACCURACY.motion_tol == 0.002  # the preset itself is unchanged
    with pytest.raises(FitError, match="unknown fit option"):
        DEFAULT.with_changes(r_two=0.9)
    with pytest.raises(FitError, match="method"):
        FitOptions(method="magic").checked()
    assert FitOptions(method="fd").checked().max_order == 10
    assert FitOptions().checked().max_order == 20


def test_the_stages_compose_to_fit_radiation(tanker):
    whole = fit_radiation(tanker)
    options = DEFAULT.checked()
    prepared = prepare_fit(tanker, options)
    assert list(prepared.labels) == [str(d) for d in tanker.influenced_dof.values]
    assert prepared.weighting == "motion"  # the tanker holds its inertia and restoring
    assert all(i <= j for i, j in prepared.pairs)
    staged = fit_blocks(prepared, options)
    assert staged.total_order == whole.total_order
    assert staged.dofs == whole.dofs
    w = np.linspace(0.1, 2.0, 40)
    np.testing.assert_allclose(
        staged.frequency_response(w).values,
        whole.frequency_response(w).values,
        rtol=1e-9,
        atol=1e-9 * float(np.abs(whole.frequency_response(w).values).max()),
    )


def test_the_per_coupling_stage_is_the_fd_method(tanker):
    options = PREVIOUS_DEFAULT.checked()
    staged = fit_per_coupling(prepare_fit(tanker, options), options)
    whole = fit_radiation(tanker, PREVIOUS_DEFAULT)
    assert not staged.blocks and staged.is_stable()
    assert [(k.influenced, k.radiating, k.order) for k in staged.couplings] == [
        (k.influenced, k.radiating, k.order) for k in whole.couplings
    ]
    # keyword overrides on top of a preset, as with **preset
    assert fit_radiation(tanker, **PREVIOUS_DEFAULT).total_order == whole.total_order
