"""Benchmark: the cosine transform of the fit's K(t) in Filon's node form against the
segment form, in the same run.

For every six-DOF case of ``benchmarks/bench_identification.py``, the K(t) the fit
judges its R² of K(t) by (:func:`cummins.radiation.retardation.diagonal_retardation_functions`:
the diagonal damping of the prepared data and its power-law tails, on the fine time grid
of :func:`cummins.radiation.fit.tail.fine_time_grid`), transformed by
:func:`cummins.radiation.transforms.cosine_transform` with ``node_form`` (the default)
and without it (the segment form at every time). Printed per case: grid sizes, the share
of times the node form serves (:data:`~cummins.radiation.transforms.NODE_ROUNDING`), the
CPU time of both (best of ``REPEAT``, one BLAS thread) and their ratio, and the largest
error of each against the segment form evaluated in 80-bit arithmetic, relative to
max |K| of each coupling.

Run: ``python benchmarks/bench_transforms.py [filter]``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys
import time
import warnings

import numpy as np

from bench_identification import all_cases, read_case
from cummins.hydrodb import dof_matrix
from cummins.radiation import transforms
from cummins.radiation.fit import FitOptions
from cummins.radiation.fit.data import prepare_fit
from cummins.radiation.fit.tail import fine_time_grid
from cummins.radiation.retardation import _damping_grid, fit_damping_tail

REPEAT = 3


def cpu_time(function) -> float:
    best = np.inf
    for _ in range(REPEAT):
        start = time.process_time()
        function()
        best = min(best, time.process_time() - start)
    return best


def extended_reference(x, f, y) -> np.ndarray:
    """The segment form in 80-bit arithmetic (np.longdouble), summed in that precision."""
    x, f, y = (np.asarray(a, dtype=np.longdouble) for a in (x, f, y))
    m, h = (x[1:] + x[:-1]) / 2, (x[1:] - x[:-1]) / 2
    mean, half = (f[1:] + f[:-1]) / 2, (f[1:] - f[:-1]) / 2
    z = y[:, None] * h[None]
    safe = np.where(z == 0, 1, z)
    sinc = np.where(z == 0, 1, np.sin(z) / safe)
    j1 = np.where(np.abs(z) < 1e-3, z / 3 - z**3 / 30, (np.sin(z) - z * np.cos(z)) / safe**2)
    even = np.cos(y[:, None] * m[None]) * 2 * h * sinc
    odd = np.sin(y[:, None] * m[None]) * 2 * h * j1
    return (np.einsum("mk,kp->mp", even, mean) - np.einsum("mk,kp->mp", odd, half)).astype(float)


def main(selection: str | None = None) -> None:
    warnings.simplefilter("ignore")
    print(
        f"{'case':36s} {'grid':>13s} {'node':>5s} {'segment s':>9s} {'node s':>7s} "
        f"{'ratio':>5s} {'err segment':>11s} {'err node':>9s}"
    )
    ratios, worst = [], [0.0, 0.0]
    for name, path in all_cases():
        if selection and selection not in name:
            continue
        try:
            ds = read_case(path)
            if ds.sizes["influenced_dof"] != 6:
                continue
            inp = prepare_fit(ds, FitOptions().checked())
        except Exception:  # a case the fit refuses: not this benchmark's
            continue
        w, b = _damping_grid(inp.data, "linear", True)
        t = fine_time_grid(inp.measured.time, float(w.max()))
        data_w = inp.data.omega.values
        flat = b.shape[1]
        tail = fit_damping_tail(
            data_w,
            b[1:],
            "auto",
            added_mass=dof_matrix(inp.data, "added_mass").reshape(data_w.size, flat),
        )
        diagonal = np.arange(6) * 7
        grids = [(w, b[:, diagonal])]
        power = np.flatnonzero(tail.kind[diagonal] == "power")
        if power.size:
            tail_w, tail_b = tail.sampled()
            grids.append((tail_w, tail_b[:, diagonal[power]]))
        for k, (x, f) in enumerate(grids):
            segment = cpu_time(
                lambda x=x, f=f, t=t: transforms.cosine_transform(x, f, t, node_form=False)
            )
            node = cpu_time(lambda x=x, f=f, t=t: transforms.cosine_transform(x, f, t))
            reference = extended_reference(x, f, t)
            scale = np.abs(reference).max(axis=0)
            scale[scale == 0] = 1.0
            errors = [
                float(
                    (
                        np.abs(transforms.cosine_transform(x, f, t, node_form=flag) - reference)
                        / scale
                    ).max()
                )
                for flag in (False, True)
            ]
            share = transforms._node_rows(x, f, transforms._slope_jumps(x, f), t).mean()
            worst = [max(worst[0], errors[0]), max(worst[1], errors[1])]
            ratios.append(node / segment)
            label = name[-36:] if k == 0 else "  power tails"
            print(
                f"{label:36s} {x.size:5d}×{t.size:<5d}x{f.shape[1]} {share:5.0%} {segment:9.4f} "
                f"{node:7.4f} {node / segment:5.2f} {errors[0]:11.1e} {errors[1]:9.1e}",
                flush=True,
            )
    if ratios:
        print(
            f"\ntime node / segment form: median {np.median(ratios):.2f}, range "
            f"{min(ratios):.2f}–{max(ratios):.2f} over {len(ratios)} transforms; largest "
            f"error against the 80-bit reference: segment {worst[0]:.1e}, node {worst[1]:.1e} "
            "of max |K|"
        )


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
