"""The motion error of one block's fit by Woodbury (cummins.radiation.fit.motion.
BlockMotionError) is the error MotionSensitivity.error_of gives with the whole K(jω)."""

import numpy as np
import pytest

from _synthetic import demo_block_motion_error


@pytest.mark.parametrize("dofs", [(2,), (0, 4), (1, 3, 5)])
def test_block_error_is_the_whole_error(dofs):
    """K of the block's DOFs changed by up to 20 % (a poor fit) and by 0.1 % (a good one):
    the same relative motion error as the n × n solve, to rounding."""
    sensitivity, k_data, w, errors = demo_block_motion_error()
    index = np.asarray(dofs)
    rng = np.random.default_rng(len(dofs))
    for size in (0.2, 1e-3):
        k_block = k_data[:, index[:, None], index[None, :]] * (
            1 + size * rng.uniform(-1, 1, (w.size, len(dofs), len(dofs)))
        )
        k = k_data.copy()
        k[:, index[:, None], index[None, :]] = k_block
        whole = sensitivity.error_of(k, np.zeros(k.shape[1:]))[0]
        assert whole > 0
        assert errors(dofs, k_block) == pytest.approx(whole, rel=1e-9)
