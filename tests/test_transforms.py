"""Exact transforms of piecewise-linear functions, against closed forms and quadrature."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from cummins.radiation.transforms import cosine_transform, hilbert_pv, sine_transform


def test_linear_function_closed_form():
    """∫₀¹ x cos(xy) dx = (cos y + y sin y − 1)/y² and ∫₀¹ x sin(xy) dx = (sin y − y cos y)/y²."""
    x = np.array([0.0, 0.3, 1.0])  # a straight line is represented exactly by any grid
    y = np.array([0.0, 1e-3, 0.5, 2.0, 40.0])
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.where(y > 0, (np.cos(y) + y * np.sin(y) - 1) / y**2, 0.5)
        s = np.where(y > 0, (np.sin(y) - y * np.cos(y)) / y**2, 0.0)
    np.testing.assert_allclose(cosine_transform(x, x, y), c, rtol=1e-7, atol=1e-12)
    np.testing.assert_allclose(sine_transform(x, x, y), s, rtol=1e-7, atol=1e-12)


@settings(max_examples=25, deadline=None)
@given(
    seed=st.integers(0, 10_000),
    y=st.floats(0.0, 60.0),
)
def test_against_quadrature_of_the_interpolant(seed, y):
    rng = np.random.default_rng(seed)
    x = np.sort(np.r_[0.0, rng.uniform(0.0, 5.0, 12), 5.0])
    x = np.unique(x)
    f = rng.normal(size=x.size)

    def interpolant(z):
        return np.interp(z, x, f)

    points = list(x)
    c = sum(
        quad(lambda z: interpolant(z) * np.cos(z * y), a, b)[0]
        for a, b in itertools.pairwise(points)
    )
    s = sum(
        quad(lambda z: interpolant(z) * np.sin(z * y), a, b)[0]
        for a, b in itertools.pairwise(points)
    )
    assert cosine_transform(x, f, [y])[0] == pytest.approx(c, abs=1e-9)
    assert sine_transform(x, f, [y])[0] == pytest.approx(s, abs=1e-9)


def test_trailing_dimensions():
    x = np.linspace(0, 2, 7)
    f = np.stack([np.sin(x), np.cos(x), x**2], axis=1).reshape(7, 3, 1)
    out = cosine_transform(x, f, [0.0, 1.0])
    assert out.shape == (2, 3, 1)
    np.testing.assert_allclose(out[:, 1, 0], cosine_transform(x, np.cos(x), [0.0, 1.0]))


@pytest.mark.parametrize("y", [0.37, 1.5, 2.0, 3.99])
def test_hilbert_principal_value(y):
    """PV ∫ f(x)/(x² − y²) dx against QUADPACK's Cauchy weight, also with y on a grid point."""
    x = np.array([0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.5, 6.0])
    f = np.exp(-((x - 1.5) ** 2)) * x

    def g(z):  # f/(z + y): the Cauchy weight supplies 1/(z − y)
        return np.interp(z, x, f) / (z + y)

    reference = quad(g, 0.0, 6.0, weight="cauchy", wvar=y, limit=500)[0]
    assert hilbert_pv(x, f, [y])[0] == pytest.approx(reference, rel=1e-6, abs=1e-9)


def test_hilbert_split_at_a_shared_end_point():
    """Two calls that share an end point give the integral over the union, even at that point."""
    x = np.linspace(0.0, 4.0, 41)
    f = x * np.exp(-x)
    whole = hilbert_pv(x, f, [2.0, 2.05])
    parts = hilbert_pv(x[:21], f[:21], [2.0, 2.05]) + hilbert_pv(x[20:], f[20:], [2.0, 2.05])
    np.testing.assert_allclose(parts, whole, rtol=1e-12)


def test_bad_grids():
    with pytest.raises(ValueError, match="increasing"):
        cosine_transform([0.0, 1.0, 1.0], [0.0, 1.0, 2.0], [1.0])
    with pytest.raises(ValueError, match="y > 0"):
        hilbert_pv([0.0, 1.0], [0.0, 1.0], [0.0])


@pytest.mark.parametrize("uniform", [True, False])
def test_node_form_against_segment_form(uniform):
    """The node form of the cosine transform (slope jumps at the nodes, used where it is
    well conditioned) gives the segment form's numbers: a damping-like curve on 400
    uneven frequencies with noise, 300 times (a uniform grid: the angle-addition blocks;
    uneven: direct cosines). Measured difference 2·10⁻¹⁵ of max |K|."""
    from cummins.radiation.transforms import _node_rows, _slope_jumps

    rng = np.random.default_rng(3)
    x = np.r_[0.0, np.sort(rng.uniform(0.05, 8.0, 399))]
    f = np.stack(
        [x**2 * np.exp(-x), np.exp(-((x - 2) ** 2)) * (1 + 1e-3 * rng.normal(size=x.size))]
    )
    f = f.T
    t = np.linspace(0.0, 60.0, 300) if uniform else np.sort(rng.uniform(0.0, 60.0, 300))
    rows = _node_rows(x, f, _slope_jumps(x, f), t)
    assert rows.mean() > 0.8 and not rows[0]  # the node form serves most times, not t = 0
    new, old = cosine_transform(x, f, t), cosine_transform(x, f, t, node_form=False)
    np.testing.assert_allclose(new, old, rtol=0.0, atol=1e-12 * np.abs(old).max())


def test_node_form_closed_form():
    """∫₀¹ x cos(xy) dx = (cos y + y sin y − 1)/y² on 200 uniform y up to 500 (node form
    beyond the smallest y), and ∫₀^π sin x cos(xy) dx = (1 + cos πy)/(1 − y²) for the
    piecewise-linear sine on a fine grid, to its interpolation error (measured 3·10⁻¹⁷
    and 1.0·10⁻⁷)."""
    y = np.linspace(0.0, 500.0, 200)
    with np.errstate(divide="ignore", invalid="ignore"):
        exact = np.where(y > 0, (np.cos(y) + y * np.sin(y) - 1) / y**2, 0.5)
    np.testing.assert_allclose(
        cosine_transform(np.array([0.0, 0.25, 1.0]), np.array([0.0, 0.25, 1.0]), y),
        exact,
        rtol=0.0,
        atol=1e-14,
    )
    x = np.linspace(0.0, np.pi, 4001)
    y = np.linspace(0.0, 7.7, 100)  # avoids y = 1
    exact = (1 + np.cos(np.pi * y)) / (1 - y**2)
    # the interpolation error of the chord rule is (Δx²/8) max|f''| × π ≈ 2.4·10⁻⁷
    np.testing.assert_allclose(cosine_transform(x, np.sin(x), y), exact, rtol=0.0, atol=1e-6)


def test_shared_kernels_keep_the_numbers_and_no_memory():
    """Inside ``shared_kernels`` hilbert_pv computes each grid's logarithms once and gives
    the numbers it gives outside, bit for bit; they are dropped when the context ends."""
    from cummins.radiation import transforms

    x = np.r_[0.0, np.linspace(0.1, 8.0, 300)]
    f = np.stack([x * np.exp(-x), np.sin(x) ** 2], axis=1)
    y = x[1:]  # on the grid points: the principal values' cancellation too
    outside = hilbert_pv(x, f, y)
    with transforms.shared_kernels():
        first = hilbert_pv(x, f, y)
        again = hilbert_pv(x, 2 * f, y)
        assert len(transforms._PV_CACHE) == 1  # one grid, computed once
    assert not transforms._PV_CACHE
    np.testing.assert_array_equal(first, outside)
    np.testing.assert_array_equal(again, hilbert_pv(x, 2 * f, y))


def test_pv_kernels_are_the_segments_logarithms():
    from cummins.radiation.transforms import _pv_kernels

    rng = np.random.default_rng(4)
    x = np.r_[0.0, np.sort(rng.uniform(0.1, 20.0, 60))]
    for y in (x[1:], np.sort(rng.uniform(0.05, 25.0, 45))):  # on the grid and off it
        difference, total = _pv_kernels(x, y)
        a, b, yy = x[:-1], x[1:], y[:, None]
        with np.errstate(divide="ignore"):
            left = np.log(np.abs(b - yy)) - np.log(np.abs(a - yy))
        left[~np.isfinite(left)] = 0.0  # ln 0 := 0 where y is a grid point
        right = np.log((b + yy) / (a + yy))
        at = np.isin(y, x)[:, None] & (np.isin(a, y)[None, :] | np.isin(b, y)[None, :])
        keep = ~at  # where y is an end of the segment the reference's cancellation differs
        np.testing.assert_allclose(difference[keep], (left - right)[keep], rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(total[keep], (yy * (left + right))[keep], rtol=1e-12, atol=1e-11)
        assert difference.flags.c_contiguous and total.flags.c_contiguous
