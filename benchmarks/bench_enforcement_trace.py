"""Benchmark (diagnostic): why a block passivity enforcement needs the iterations it does.

The default fit of one case (the HAMS cylinder unless a substring of another case's name
is given) is run with the enforcement's sweep and programme observed
(:func:`cummins.radiation.fit.block_passivity.enforcement_steps`; nothing in the fit is
changed). For each enforcement: its iterations, where the violations of each sweep lie
(below, inside or above the data's frequency range, the limits ω → 0, ∞, the bounds of
the damping beyond the data), and, at the frequencies constrained in one iteration,
whether the next sweep finds λ_min negative there again, with the change of the
DOF-scaled matrix ‖ΔH‖₂ and the gap λ₂ − λ₁ before the step, both relative to the
largest |λ| there. The row of each constraint, wᴴ H w for the eigenvector w it was made
of, is linear in the residues, so the programme's step meets it exactly; λ_min is
negative again when the step turns the eigenvector (a change above the gap: Gustavsen &
Semlyen (2001)'s first-order eigenvalue perturbation no longer holds).

Run: ``python benchmarks/bench_enforcement_trace.py [case filter]`` (BENCHMARKS.md,
2026-12-06, thirteenth session).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys
import warnings
from collections import defaultdict
from itertools import pairwise

import numpy as np

import cummins.radiation.fit.block_passivity as passivity
import cummins.radiation.fit.order_search as order_search
import cummins.radiation.passivity.enforcement as programme
from bench_identification import all_cases, read_case
from cummins.radiation.fit import fit_radiation
from cummins.radiation.fit.tail import TailBounds

CASE = "HAMS/Cylinder/Output_Benchmark"


class Trace:
    """The sweeps and programmes of every enforcement of one fit, in order."""

    def __init__(self):
        self.current: int | None = None
        self.runs: list[dict] = []

    def install(self) -> None:
        steps, sweep, solve, tail = (
            passivity.enforcement_steps,
            passivity.passivity_violations,
            programme.least_distance,
            TailBounds.__call__,
        )

        def traced_steps(block, data, *, bounds=None):
            run = {"range": None, "sweeps": [], "steps": []}
            self.runs.append(run)
            index = len(self.runs) - 1
            inner = steps(block, data, bounds=bounds)
            while True:
                self.current = index
                try:
                    value = next(inner)
                except StopIteration as end:
                    self.current = None
                    return end.value
                self.current = None
                yield value

        def traced_sweep(block, lo, hi, exact=True, sweep=None):
            found, scale = sweep_(block, lo, hi, exact=exact, sweep=sweep)
            if self.current is not None and found:
                run = self.runs[self.current]
                run["range"] = (lo, hi)
                run["sweeps"].append(
                    {"block": block, "scale": scale, "found": located(block, found, sweep)}
                )
            return found, scale

        sweep_ = sweep

        def traced_solve(misfit, g, h, transformed=None, start=None):
            z, active = solve(misfit, g, h, transformed, start)
            if self.current is not None:
                self.runs[self.current]["steps"].append((z.copy(), misfit.r_all))
            return z, active

        def traced_tail(bounds, block):
            out = tail(bounds, block)
            if self.current is not None and self.runs[self.current]["sweeps"]:
                self.runs[self.current]["sweeps"][-1]["tail"] = len(out)
            return out

        order_search.enforcement_steps = traced_steps
        passivity.enforcement_steps = traced_steps
        passivity.passivity_violations = traced_sweep
        programme.least_distance = traced_solve
        TailBounds.__call__ = traced_tail


def located(block, found, sweep) -> list[tuple[float, float, float, np.ndarray]]:
    """(ω, λ, largest |λ|, w) of each violation: ω of the sweep's point whose linear form
    is the violation's (0 and ∞ for the limits)."""
    high, low = passivity.limit_forms(block.poles)
    points = sweep.grid
    if sweep.band_extra is not None:
        points = np.union1d(points, sweep.band_extra)
    forms = 1j * points[:, None] * block.poles.basis(1j * points)
    if block.symmetric:
        forms = forms.real
    out = []
    for g, lam, w, local in found:
        if g is high or g is low:
            omega = np.inf if g is high else 0.0
        else:
            omega = float(points[np.argmin(np.abs(forms - g).sum(axis=1))])
        out.append((omega, lam, local, w))
    return out


def region(omega: float, lo: float, hi: float) -> str:
    if omega == 0.0:
        return "limit 0"
    if not np.isfinite(omega):
        return "limit inf"
    return "below" if omega < lo else "above" if omega > hi else "inside"


def scaled_matrix(block, scale, omega: float) -> np.ndarray:
    return block.hermitian_part(np.array([omega]))[0] * np.outer(scale, scale)


def report(run: dict, number: int) -> dict:
    """Print one enforcement's summary; the counts by region (for the total)."""
    lo, hi = run["range"] or (np.nan, np.nan)
    sweeps, steps = run["sweeps"], run["steps"]
    counts: dict = defaultdict(int)
    again: dict = defaultdict(lambda: [0, 0, [], []])  # region: again, all, ΔH, gap
    for before, after in pairwise(sweeps):
        for omega, _, local, _ in before["found"]:
            if not (0.0 < omega < np.inf):
                continue
            old = scaled_matrix(before["block"], before["scale"], omega)
            new = scaled_matrix(after["block"], before["scale"], omega)
            values = np.linalg.eigvalsh(old)
            entry = again[region(omega, lo, hi)]
            entry[0] += bool(np.linalg.eigvalsh(new)[0] < 0)
            entry[1] += 1
            entry[2].append(np.linalg.norm(new - old, 2) / local)
            entry[3].append((values[1] - values[0]) / local if values.size > 1 else np.nan)
    for sweep in sweeps:
        for omega, _, _, _ in sweep["found"]:
            counts[region(omega, lo, hi)] += 1
        counts["tail bounds"] += sweep.get("tail", 0)
    shares = ""
    if steps:
        final, r = steps[-1]
        norm = np.linalg.norm(r @ final) or 1.0
        made = [np.zeros_like(final)] + [z for z, _ in steps]
        shares = " ".join(f"{np.linalg.norm(r @ (z - z0)) / norm:.2f}" for z0, z in pairwise(made))
    print(f"enforcement {number}: {len(steps)} programmes, range {lo:.3g}-{hi:.3g} rad/s")
    print("  violations: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
    for name, (bad, total, change, gap) in again.items():
        gap = [g for g in gap if np.isfinite(g)] or [np.nan]  # 1 × 1 blocks: no gap
        print(
            f"  {name}: negative again at {bad} of {total} constrained frequencies; "
            f"median ‖ΔH‖ {np.median(change):.3g}, gap {np.median(gap):.3g} (of max |λ|)"
        )
    if shares:
        print(f"  ‖R Δδ‖ / ‖R δ‖ by iteration: {shares}")
    return counts


def main() -> None:
    wanted = sys.argv[1] if len(sys.argv) > 1 else CASE
    cases = all_cases()  # the HAMS cylinder is in the corpus: without it, the first case
    name, path = next(((n, p) for n, p in cases if wanted in n), cases[0])
    trace = Trace()
    trace.install()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit_radiation(read_case(path))
    print(name)
    total: dict = defaultdict(int)
    for number, run in enumerate(trace.runs):
        for key, value in report(run, number).items():
            total[key] += value
    programmes = sum(len(run["steps"]) for run in trace.runs)
    print(f"{len(trace.runs)} enforcements, {programmes} programmes; violations: {dict(total)}")


if __name__ == "__main__":
    main()
