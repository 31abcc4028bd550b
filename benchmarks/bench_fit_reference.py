"""Benchmark: the default identification of every case against a reference source tree,
in the same run.

The scoreboard of :mod:`cummins.radiation.fit.scorecard` and the fit's CPU time
(``time.process_time``, best of ``BENCH_REPEAT``, one BLAS thread) of the default fit
(``fit_radiation(ds)``) of each case of ``benchmarks/bench_identification.py`` (its
set-ups included: RM3 with WEC-Sim's mass properties), computed by this tree and by a
reference tree — by default the commit this branch left ``main`` at (``git merge-base
main HEAD``) as ``git archive`` extracts it into a temporary folder
(``BENCH_REFERENCE=<git ref>``, or ``BENCH_REFERENCE_SRC=<folder holding cummins>``).
Each case runs in a fresh process per tree, the two trees one after the other, so that
a machine shared with other work loads both alike; the CPU time of one process is what
the load changes least. Printed per case: order, smallest diagonal R² of A and B, passive
(independent sweep), motion-RAO error, failures of the fit and CPU seconds for both trees,
and the time ratio (this tree / reference); a summary of the ratios and of what changed.

With ``BENCH_DOFS=6`` only the cases of that many DOFs are fitted, and the summary counts
the cases within the time target of issue 30 for that size (6 DOFs: 0.3 s, 12: 3 s,
18: 8 s) in each tree — the single-body check of issue 30 is
``BENCH_DOFS=6 BENCH_REPEAT=3 python benchmarks/bench_fit_reference.py``.

Run: ``python benchmarks/bench_fit_reference.py [filter]`` (a substring of the case name
selects cases; ``BENCH_REPEAT`` defaults to 2).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import json
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from _reference import reference_tree
from _timing import forget_kept_answers

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
REPEAT = int(os.environ.get("BENCH_REPEAT", "2"))
#: Only the cases of this many DOFs (all when unset).
DOFS = int(os.environ.get("BENCH_DOFS", "0"))
#: CPU time targets of issue 30 by the number of DOFs, s.
TARGETS = {6: 0.3, 12: 3.0, 18: 8.0}


def worker(name: str) -> None:
    """Fit one case with the ``cummins`` on ``sys.path``; print the result as JSON."""
    sys.path.insert(0, str(HERE))
    from bench_identification import all_cases, read_case
    from cummins.radiation.fit import fit_radiation
    from cummins.radiation.fit.scorecard import scorecard

    path = dict(all_cases())[name]
    ds = read_case(path)
    if DOFS and ds.sizes["influenced_dof"] != DOFS:
        print(json.dumps({"skipped": True}))
        return
    best, model = np.inf, None
    for _ in range(REPEAT):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            forget_kept_answers()
            start = time.process_time()
            model = fit_radiation(ds)
            best = min(best, time.process_time() - start)
    card = scorecard(ds, model)
    print(
        json.dumps(
            {
                "dofs": int(ds.sizes["influenced_dof"]),
                "order": card.total_order,
                "r2_A": card.r2_added_mass,
                "r2_B": card.r2_damping,
                "passive": bool(card.passive and card.stable),
                "rao": None if card.rao_error is None else card.rao_error.error,
                "failures": len(model.attrs.get("failures", [])),
                "cpu_s": best,
            }
        )
    )


def run(tree: Path, name: str) -> dict | None:
    env = {**os.environ, "PYTHONPATH": str(tree), "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run(
        [sys.executable, __file__, "--worker", name], env=env, capture_output=True, text=True
    )
    if done.returncode:
        tail = (done.stderr.strip().splitlines()[-1:] or ["?"])[0]
        print(f"  {name}: failed under {tree}: {tail[:120]}")
        return None
    result = json.loads(done.stdout.strip().splitlines()[-1])
    return None if result.get("skipped") else result


def cells(r: dict | None) -> str:
    if r is None:
        return f"{'—':>40s}"
    rao = "—" if r["rao"] is None else f"{100 * r['rao']:.2f}"
    return (
        f"{r['order']:4d} {r['r2_A']:8.4f} {r['r2_B']:8.4f} {'y' if r['passive'] else 'N':>2s} "
        f"{rao:>7s} {r['failures']:3d} {r['cpu_s']:6.2f}"
    )


def main(selection: str | None = None) -> None:
    sys.path.insert(0, str(HERE))
    from bench_identification import all_cases

    reference = reference_tree()
    mine = ROOT / "src"
    head = (
        f"{'order':>4s} {'R² A':>8s} {'R² B':>8s} {'ps':>2s} {'RAO %':>7s} {'F':>3s} {'cpu s':>6s}"
    )
    print(f"reference: {reference}")
    print(f"{'case':40s} {'dof':>3s} | {head} | {head} | ratio")
    ratios, changed = [], []
    met, sized = [0, 0], 0
    for name, _ in all_cases():
        if selection and selection not in name:
            continue
        new = run(mine, name)
        if DOFS and new is None:
            continue  # another size (or a case that does not fit: the reference says)
        ref = run(reference, name)
        ratio = new["cpu_s"] / ref["cpu_s"] if ref and new else float("nan")
        dofs = (new or ref or {"dofs": 0})["dofs"]
        print(
            f"{name[-40:]:40s} {dofs:3d} | {cells(ref)} | {cells(new)} | {ratio:5.2f}", flush=True
        )
        if ref and new:
            ratios.append(ratio)
            same = all(
                ref[k] == new[k] if not isinstance(ref[k], float) else abs(ref[k] - new[k]) < 1e-4
                for k in ("order", "r2_A", "r2_B", "passive", "rao", "failures")
                if ref[k] is not None and new[k] is not None
            )
            if not same:
                changed.append(name)
            target = TARGETS.get(new["dofs"])
            if target is not None:
                met[0] += ref["cpu_s"] <= target
                met[1] += new["cpu_s"] <= target
                sized += 1
    if ratios:
        print(
            f"\ntime ratio this tree / reference: median {np.median(ratios):.2f}, "
            f"range {min(ratios):.2f}–{max(ratios):.2f} over {len(ratios)} cases"
        )
    if sized:
        print(
            f"within the time target of their size (issue 30): reference {met[0]}, "
            f"this tree {met[1]} of {sized} cases"
        )
    print(f"scoreboard changed on {len(changed)} cases: {', '.join(changed) or 'none'}")


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--worker":
        worker(sys.argv[2])
    else:
        main(sys.argv[1] if len(sys.argv) > 1 else None)
