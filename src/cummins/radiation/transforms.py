"""Exact integral transforms of piecewise-linear functions.

Hydrodynamic coefficients are known at a few dozen frequencies, often on a non-uniform
grid. Rather than sampling cos(ωt) on that coarse grid (the trapezoid rule, which
aliases as soon as t·Δω is not small), cummins integrates the piecewise-linear
interpolant of the data *exactly* against the oscillating kernel (a Filon-type rule):
the only approximation is the interpolation of the data, which is what the data allow.

For a segment [a, b] with midpoint m, half-width h and a linear function
f(x) = f̄ + s (x − m), with x = m + u:

* ∫ f(x) cos(xy) dx = 2h f̄ cos(my) sinc(hy) − 2 s h² sin(my) j₁(hy)
* ∫ f(x) sin(xy) dx = 2h f̄ sin(my) sinc(hy) + 2 s h² cos(my) j₁(hy)

with sinc(z) = sin(z)/z and j₁(z) = (sin z − z cos z)/z² the spherical Bessel function,
both evaluated stably near z = 0 (where the rule reduces to the trapezoid rule).

Integrated by parts twice, the cosine transform is a sum over the nodes x_k alone
(Filon's rule in its node form):

* ∫ f(x) cos(xy) dx = [f(x_N) sin(x_N y) − f(x₀) sin(x₀ y)]/y + Σ_k c_k cos(x_k y)/y²

with c_k = s_{k−1} − s_k the jump of the slope at x_k (s_{−1} = s_N = 0): one cosine per
node and one matrix product, where the segment form needs the sines and cosines of
midpoints and half-widths and a dozen arrays of the same size. It divides by y², so
:func:`cosine_transform` uses it only where its rounding stays small against the
integral's scale (:data:`NODE_ROUNDING`), the segment form below that.

The principal-value integral PV ∫ f(x)/(x² − y²) dx of the Kramers–Kronig relations
(Hjulstad (2004) eqs. 5.23–5.24, Unneland (2007) eq. 2.63) is also exact for piecewise-linear f:
with f = p + s x on a segment, 1/(x² − y²) = [1/(x − y) − 1/(x + y)]/(2y) gives
[(p + sy) ln|(b − y)/(a − y)| − (p − sy) ln|(b + y)/(a + y)|]/(2y). Where y falls on a
grid point the two logarithmic singularities of the adjacent segments cancel (f is
continuous); the convention ln 0 := 0 implements that cancellation, also across two
calls that share the end point (data and tail).
"""

from __future__ import annotations

import collections
import contextlib
import threading
from collections.abc import Iterator

import numpy as np
from numpy.typing import ArrayLike, NDArray


def _uniform_step(y: NDArray) -> float | None:
    """The step of ``y`` when it is a uniform grid of 64 points or more (a time grid),
    else None."""
    size = y.size
    step = (y[-1] - y[0]) / (size - 1) if size > 1 else 0.0
    uniform = size >= 64 and np.all(
        np.abs(y - (y[0] + step * np.arange(size))) <= 1e-14 * np.abs(y).max()
    )
    return float(step) if uniform else None


def _cos_sin(x: NDArray, y: NDArray) -> tuple[NDArray, NDArray]:
    """cos(y xᵀ) and sin(y xᵀ), shape (M, N), for x (N,) and y (M,): the blocks of
    :func:`_angle_blocks` put together."""
    x, y = x.reshape(-1), y.reshape(-1)
    cos, sin = np.empty((y.size, x.size)), np.empty((y.size, x.size))
    for rows, cos_rows, sin_rows in _angle_blocks(x, y):
        cos[rows], sin[rows] = cos_rows, sin_rows
    return cos, sin


def _even_odd(m: NDArray, h: NDArray, y: NDArray) -> tuple[NDArray, ...]:
    """The kernels of a segment (midpoint m, half-width h) at y, (M, N) each:
    cos(my), sin(my), 2h sinc(hy) and 2h j₁(hy) (sinc(z) = sin z / z, j₁(z) = (sin z −
    z cos z)/z², from one sine and cosine of hy; 1 and the series of j₁ to z⁵ near 0)."""
    cos_m, sin_m = _cos_sin(m, y)
    cos, sin = _cos_sin(h, y)
    sinc, j1 = _sinc_j1(y.reshape(-1, 1) * h[None, :], cos, sin)
    return cos_m, sin_m, 2 * h[None, :] * sinc, 2 * h[None, :] * j1


def _sinc_j1(z: NDArray, cos: NDArray, sin: NDArray) -> tuple[NDArray, NDArray]:
    """sinc(z) = sin z / z and j₁(z) = (sin z − z cos z)/z² from cos z and sin z (1 and
    the series of j₁ to z⁵ near 0)."""
    small = np.abs(z) < 1e-2
    safe = np.where(small, 1.0, z)
    sinc = np.where(z == 0, 1.0, sin / np.where(z == 0, 1.0, z))
    j1 = (sin - z * cos) / safe**2
    if small.any():
        zs = z[small]
        j1[small] = zs / 3 - zs**3 / 30 + zs**5 / 840
    return sinc, j1


def _angle_blocks(x: NDArray, y: NDArray, sine: bool = True):
    """(rows, cos(y[rows] xᵀ), sin(y[rows] xᵀ)) by blocks of rows that stay in cache, for
    x (N,) and y (M,); with ``sine`` False the sines are not computed (None). On a uniform
    grid y_k = y₀ + kΔ (a time grid) by the angle addition cos(a + b) = cos a cos b −
    sin a sin b (and sin) from √M block starts and √M steps: 2√M instead of M sines and
    cosines of each x, to within the rounding of the products x·y themselves."""
    size, step = y.size, _uniform_step(y)
    if step is None:
        for start in range(0, size, 64):
            rows = slice(start, min(start + 64, size))
            angle = y[rows, None] * x[None, :]
            yield rows, np.cos(angle), np.sin(angle) if sine else None
        return
    block = int(np.sqrt(size))
    starts = np.outer(y[0] + step * np.arange(0, size, block), x)  # (Q, N)
    steps = np.outer(step * np.arange(block), x)  # (L, N)
    ca, sa, cb, sb = np.cos(starts), np.sin(starts), np.cos(steps), np.sin(steps)
    for q in range(starts.shape[0]):
        count = min(block, size - q * block)
        rows = slice(q * block, q * block + count)
        cos = (ca[q] * cb[:count]) - (sa[q] * sb[:count])
        sin = (sa[q] * cb[:count]) + (ca[q] * sb[:count]) if sine else None
        yield rows, cos, sin


def _cosine_segments(m: NDArray, h: NDArray, y: NDArray) -> tuple[NDArray, NDArray]:
    """cos(my) 2h sinc(hy) and sin(my) 2h j₁(hy), (M, K): the products of
    :func:`_even_odd` the cosine transform takes, the same numbers, computed by blocks of
    rows that stay in cache."""
    even, odd = np.empty((y.size, m.size)), np.empty((y.size, m.size))
    double = 2 * h[None, :]
    blocks = zip(_angle_blocks(m, y), _angle_blocks(h, y), strict=True)
    for (rows, cos_m, sin_m), (_, cos, sin) in blocks:
        sinc, j1 = _sinc_j1(y[rows].reshape(-1, 1) * h[None, :], cos, sin)
        np.multiply(cos_m, double * sinc, out=even[rows])
        np.multiply(sin_m, double * j1, out=odd[rows])
    return even, odd


def _segments(x: ArrayLike, f: ArrayLike):
    x = np.asarray(x, dtype=float)
    f = np.asarray(f, dtype=float)
    if x.ndim != 1 or f.shape[0] != x.size:
        raise ValueError(f"f must have {x.size} rows like x, got shape {f.shape}")
    if x.size < 2 or np.any(np.diff(x) <= 0):
        raise ValueError("x must be strictly increasing with at least two points")
    m = 0.5 * (x[1:] + x[:-1])
    h = 0.5 * (x[1:] - x[:-1])
    f_mean = 0.5 * (f[1:] + f[:-1]).reshape(m.size, -1)
    f_half_diff = 0.5 * (f[1:] - f[:-1]).reshape(m.size, -1)  # = s h
    return m, h, f_mean, f_half_diff, f.shape[1:]


#: The node form of the cosine transform is used at the points y where its rounding,
#: u (‖c‖₂/y² + (|f(x₀)| + |f(x_N)|)/|y|) (u the unit roundoff, c the slope jumps of each
#: column), is at most this many units of roundoff of ∫|f| dx, the integral's own
#: scale (for every column); the segment form elsewhere. The rounding of each phase x·y,
#: u·x·y relative, is common to both forms. Measured on the corpus's 27 six-DOF cases
#: (each coupling's damping and power-law tail on the fit's fine time grid, against the
#: segment form in 80-bit arithmetic): largest error 1.2·10⁻¹³ of max |K| (the segment
#: form's 9.7·10⁻¹⁴, both the phases' rounding on 800 frequencies), the node form at
#: 90–100 % of the times on the grids of 2000 (0 % on the NEMOH cylinder's 114 short
#: times), 5–18 times faster there.
NODE_ROUNDING = 10.0


def _slope_jumps(x: NDArray, f: NDArray) -> NDArray:
    """c_k = s_{k−1} − s_k at each node (s_{−1} = s_N = 0), shape (N + 1, P)."""
    s = np.diff(f, axis=0) / np.diff(x)[:, None]
    c = np.empty_like(f)
    c[0], c[-1] = -s[0], s[-1]
    c[1:-1] = s[:-1] - s[1:]
    return c


def _node_rows(x: NDArray, f: NDArray, c: NDArray, y: NDArray) -> NDArray[np.bool_]:
    """Where the node form's rounding is within :data:`NODE_ROUNDING` units of roundoff of
    ∫|f| dx (bounded by Σ h (|f_k| + |f_{k+1}|)) for every column."""
    scale = np.sum(0.5 * np.diff(x)[:, None] * (np.abs(f[1:]) + np.abs(f[:-1])), axis=0)
    some = scale > 0
    if not some.any():
        return y != 0
    jumps = np.sqrt(np.sum(c[:, some] ** 2, axis=0))
    ends = np.abs(f[0, some]) + np.abs(f[-1, some])
    a = np.abs(y)[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        rounding = jumps / a**2 + ends / a
    return (a[:, 0] > 0) & np.all(rounding <= NODE_ROUNDING * scale[some], axis=1)


def _node_cosine(x: NDArray, f: NDArray, c: NDArray, y: NDArray) -> NDArray:
    """The node form of the cosine transform at y ≠ 0 (module docstring), (M, P)."""
    out = np.empty((y.size, f.shape[1]))
    for rows, cos, _ in _angle_blocks(x, y, sine=False):
        out[rows] = cos @ c
    yy = y[:, None]
    out /= yy**2
    out += (np.sin(x[-1] * yy) * f[-1] - np.sin(x[0] * yy) * f[0]) / yy
    return out


def cosine_transform(
    x: ArrayLike, f: ArrayLike, y: ArrayLike, *, node_form: bool = True
) -> NDArray[np.float64]:
    """∫_{x₀}^{x_N} f(x) cos(x y) dx for the piecewise-linear f through (x, f).

    Parameters
    ----------
    x
        Sample points, strictly increasing, shape (N,).
    f
        Values, shape (N, ...): any trailing dimensions are transformed together.
    y
        Points at which to evaluate the transform, shape (M,).
    node_form
        Filon's node form where it is well conditioned (:data:`NODE_ROUNDING`, module
        docstring), the segment form elsewhere; False: the segment form at every y (the
        same numbers to rounding, several times slower on long grids).

    Returns
    -------
    ndarray, shape (M, ...)

    Examples
    --------
    >>> x = np.linspace(0.0, 1.0, 3)
    >>> round(float(cosine_transform(x, x, [2.0])[0]), 6)  # ∫₀¹ x cos 2x dx = 0.100612
    0.100612
    """
    m, h, f_mean, f_half, shape = _segments(x, f)
    x = np.asarray(x, dtype=float)
    f = np.asarray(f, dtype=float).reshape(x.size, -1)
    y = np.asarray(y, dtype=float).reshape(-1)
    c = _slope_jumps(x, f)
    node = _node_rows(x, f, c, y) if node_form else np.zeros(y.size, dtype=bool)
    out = np.empty((y.size, f.shape[1]))
    if not node.all():  # the segment form where the node form would lose digits
        even, odd = _cosine_segments(m, h, y[~node])
        out[~node] = even @ f_mean - odd @ f_half
    if node.any():
        out[node] = _node_cosine(x, f, c, y[node])
    return out.reshape((y.size, *shape))


def sine_transform(x: ArrayLike, f: ArrayLike, y: ArrayLike) -> NDArray[np.float64]:
    """∫_{x₀}^{x_N} f(x) sin(x y) dx for the piecewise-linear f through (x, f).

    Same arguments and shapes as :func:`cosine_transform`.
    """
    m, h, f_mean, f_half, shape = _segments(x, f)
    y = np.asarray(y, dtype=float).reshape(-1, 1)
    cos, sin, sinc, j1 = _even_odd(m, h, y)
    even, odd = sin * sinc, cos * j1
    out = even @ f_mean + odd @ f_half
    return out.reshape((y.size, *shape))


def fourier_transform(x: ArrayLike, f: ArrayLike, y: ArrayLike) -> NDArray[np.complex128]:
    """∫_{x₀}^{x_N} f(x) e^{i x y} dx for the piecewise-linear (complex) f through (x, f).

    :func:`cosine_transform` + i :func:`sine_transform` of the real and imaginary parts,
    with the kernels computed once. Same arguments and shapes; complex result.

    Examples
    --------
    >>> x = np.linspace(0.0, 1.0, 3)
    >>> z = fourier_transform(x, x + 0j, [2.0])[0]  # ∫₀¹ x e^{2ix} dx
    >>> round(float(z.real), 6), round(float(z.imag), 6)
    (0.100612, 0.435398)
    """
    x = np.asarray(x, dtype=float)
    f = np.asarray(f, dtype=complex)
    m, h, f_mean, f_half, shape = _segments_complex(x, f)
    y = np.asarray(y, dtype=float).reshape(-1, 1)
    cos, sin, sinc, j1 = _even_odd(m, h, y)
    phase = cos + 1j * sin
    even, odd = phase * sinc, 1j * phase * j1
    out = even @ f_mean + odd @ f_half
    return out.reshape((y.size, *shape))


def _segments_complex(x: NDArray, f: NDArray):
    if x.ndim != 1 or f.shape[0] != x.size:
        raise ValueError(f"f must have {x.size} rows like x, got shape {f.shape}")
    if x.size < 2 or np.any(np.diff(x) <= 0):
        raise ValueError("x must be strictly increasing with at least two points")
    m = 0.5 * (x[1:] + x[:-1])
    h = 0.5 * (x[1:] - x[:-1])
    f_mean = 0.5 * (f[1:] + f[:-1]).reshape(m.size, -1)
    f_half = 0.5 * (f[1:] - f[:-1]).reshape(m.size, -1)
    return m, h, f_mean, f_half, f.shape[1:]


def hilbert_pv(x: ArrayLike, f: ArrayLike, y: ArrayLike) -> NDArray[np.float64]:
    """Principal value PV ∫_{x₀}^{x_N} f(x) / (x² − y²) dx for piecewise-linear f.

    Parameters
    ----------
    x
        Sample points, strictly increasing, ≥ 0, shape (N,).
    f
        Values, shape (N, ...).
    y
        Points (> 0) at which to evaluate, shape (M,). At an end point x₀ or x_N the
        integral is logarithmically singular unless f vanishes there or the integral is
        continued beyond it by another call sharing that point.

    Returns
    -------
    ndarray, shape (M, ...)
    """
    x = np.asarray(x, dtype=float)
    f = np.asarray(f, dtype=float)
    m, h, f_mean, f_half, shape = _segments(x, f)
    a = x[:-1]
    slope = f_half / h[:, None]  # (K, P)
    p = f_mean - slope * m[:, None]  # f = p + s x on each segment
    y = np.asarray(y, dtype=float).reshape(-1)
    if np.any(y <= 0):
        raise ValueError("hilbert_pv needs y > 0")
    yy = y[:, None]
    if _PV_USERS[0] and PV_CACHED_SIZE[0] <= y.size * a.size <= PV_CACHED_SIZE[1]:
        difference, total = _pv_kernels_cached(x, y)
    else:
        difference, total = _pv_kernels(x, y)
    # (p + s y) ln|(b − y)/(a − y)| − (p − s y) ln|(b + y)/(a + y)|, per segment
    out = difference @ p + total @ slope
    out = out / (2 * yy)
    return out.reshape((y.size, *shape))


def _pv_kernels(x: NDArray, y: NDArray) -> tuple[NDArray, NDArray]:
    """The logarithms of :func:`hilbert_pv` for the grid ``x`` and the points ``y``, (M, K)
    each: ln|(b − y)/(a − y)| − ln|(b + y)/(a + y)| and y × their sum, per segment [a, b]."""
    a, b = x[:-1], x[1:]  # the grid points themselves: y == x_k must give exactly 0
    yy = y[:, None]
    size = (y.size, a.size)
    # ln|x_k − y| once for both ends of each segment, ln 0 := 0 (the principal-value
    # cancellation, module docstring), in place: three arrays of 5 MB at 800 points, the
    # two returned and one for the temporaries, each written contiguously
    logs = np.subtract(x[None, :], yy)
    np.abs(logs, out=logs)
    np.copyto(logs, 1.0, where=~(logs > 0))
    np.log(logs, out=logs)
    log_minus = np.subtract(logs[:, 1:], logs[:, :-1])  # (M, K)
    log_plus = logs.reshape(-1)[: y.size * a.size].reshape(size)  # logs' memory, reused
    np.add(b[None, :], yy, out=log_plus)  # ln((b + y)/(a + y))
    difference = np.add(a[None, :], yy)  # a + y, then the difference itself
    np.divide(log_plus, difference, out=log_plus)
    np.log(log_plus, out=log_plus)
    np.subtract(log_minus, log_plus, out=difference)
    np.add(log_minus, log_plus, out=log_minus)
    return difference, np.multiply(log_minus, yy, out=log_minus)


#: Within :func:`shared_kernels`, :func:`hilbert_pv` keeps the logarithms of the grids
#: it is called with, of this many points × segments (the smallest are cheaper to
#: compute again), up to :data:`PV_CACHED_BYTES` in all (two arrays of 5 MB for 800
#: frequencies): the fit's data stage takes the Kramers–Kronig integral on the same
#: frequencies and tail grids some ten to thirty times (Ogilvie's A∞ per frequency, the
#: sharp-resonance and irregular-frequency tests).
PV_CACHED_SIZE = (10_000, 700_000)
PV_CACHED_BYTES = 32_000_000
_PV_CACHE: collections.OrderedDict[tuple[bytes, bytes], tuple[NDArray, NDArray]] = (
    collections.OrderedDict()
)
_PV_LOCK = threading.Lock()
_PV_USERS = [0]  # the shared_kernels contexts open


@contextlib.contextmanager
def shared_kernels() -> Iterator[None]:
    """A context in which :func:`hilbert_pv` computes the logarithms of each grid once
    (:data:`PV_CACHED_SIZE`): the same numbers, kept until the last such context ends."""
    with _PV_LOCK:
        _PV_USERS[0] += 1
    try:
        yield
    finally:
        with _PV_LOCK:
            _PV_USERS[0] -= 1
            if not _PV_USERS[0]:
                _PV_CACHE.clear()


def _pv_kernels_cached(x: NDArray, y: NDArray) -> tuple[NDArray, NDArray]:
    """:func:`_pv_kernels`, kept (read-only) for the next call on the same grids inside
    :func:`shared_kernels`; the least recently used dropped beyond
    :data:`PV_CACHED_BYTES`."""
    key = (x.tobytes(), y.tobytes())
    with _PV_LOCK:
        found = _PV_CACHE.get(key)
        if found is not None:
            _PV_CACHE.move_to_end(key)
            return found
    found = _pv_kernels(x, y)
    for array in found:
        array.flags.writeable = False
    with _PV_LOCK:
        if _PV_USERS[0]:
            _PV_CACHE[key] = found
        while sum(a.nbytes + b.nbytes for a, b in _PV_CACHE.values()) > PV_CACHED_BYTES:
            _PV_CACHE.popitem(last=False)
    return found
