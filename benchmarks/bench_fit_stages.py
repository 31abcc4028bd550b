"""Benchmark: where a default fit spends its time outside the order search, this tree
against a reference tree in the same run.

For every case of ``benchmarks/bench_identification.py`` of ``BENCH_DOFS`` DOFs (6 by
default), the CPU time (``time.process_time``, best of ``BENCH_REPEAT``, one BLAS thread)
of ``fit_radiation(ds)``, of its data stage (``prepare_fit``) and of its order searches
(``order_search.identify_block``, every call), each tree in a fresh process per case;
"outside" is the fit less its order searches (the data stage, K(t) for the R² of K(t),
the metrics, the passivity test). The reference tree is ``BENCH_REFERENCE_SRC`` (a folder
holding ``cummins``; default: none, this tree alone).

Run: ``BENCH_REFERENCE_SRC=/path/to/main/src python benchmarks/bench_fit_stages.py [filter]``.
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

HERE = Path(__file__).resolve().parent
REPEAT = int(os.environ.get("BENCH_REPEAT", "3"))
DOFS = int(os.environ.get("BENCH_DOFS", "6"))


def worker(name: str) -> None:
    """Time one case with the ``cummins`` on ``sys.path``; print the result as JSON."""
    sys.path.insert(0, str(HERE))
    from _timing import forget_kept_answers
    from bench_identification import all_cases, read_case
    from cummins.radiation import fit
    from cummins.radiation.fit import order_search

    ds = read_case(dict(all_cases())[name])
    if ds.sizes["influenced_dof"] != DOFS:
        print(json.dumps({"skipped": True}))
        return
    spent = {"prepare": 0.0, "search": 0.0}

    def timed(function, key):
        def wrapper(*args, **kwargs):
            start = time.process_time()
            try:
                return function(*args, **kwargs)
            finally:
                spent[key] += time.process_time() - start

        return wrapper

    fit.prepare_fit = timed(fit.prepare_fit, "prepare")
    order_search.identify_block = timed(order_search.identify_block, "search")
    best = None
    for _ in range(REPEAT):
        spent.update(prepare=0.0, search=0.0)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            forget_kept_answers()
            start = time.process_time()
            fit.fit_radiation(ds)
            total = time.process_time() - start
        if best is None or total < best["total"]:
            best = {"total": total, **spent}
    print(json.dumps(best))


def run(tree: Path, name: str) -> dict | None:
    env = {**os.environ, "PYTHONPATH": str(tree), "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run(
        [sys.executable, __file__, "--worker", name], env=env, capture_output=True, text=True
    )
    if done.returncode:
        return None
    result = json.loads(done.stdout.strip().splitlines()[-1])
    return None if result.get("skipped") else result


def main(selection: str | None = None) -> None:
    sys.path.insert(0, str(HERE))
    from bench_identification import all_cases

    trees = [HERE.parent / "src"]
    if os.environ.get("BENCH_REFERENCE_SRC"):
        trees.insert(0, Path(os.environ["BENCH_REFERENCE_SRC"]))
    print("trees: " + ", ".join(str(t) for t in trees) + " (reference first)")
    print(
        f"{'case':40s} "
        + " | ".join("total  prep search outside" for _ in trees)
        + " | outside ratio"
    )
    ratios = []
    for name, _ in all_cases():
        if selection and selection not in name:
            continue
        found = [run(tree, name) for tree in trees]
        if any(r is None for r in found):
            continue
        outside = [r["total"] - r["search"] for r in found]
        cells = [
            f"{r['total']:5.3f} {r['prepare']:5.3f} {r['search']:6.3f} {rest:7.3f}"
            for r, rest in zip(found, outside, strict=True)
        ]
        ratio = outside[-1] / outside[0] if len(found) > 1 else float("nan")
        ratios.append(ratio)
        print(f"{name[-40:]:40s} " + " | ".join(cells) + f" | {ratio:5.2f}", flush=True)
    if len(trees) > 1 and ratios:
        print(
            f"\noutside the order search, this tree / reference: median {np.median(ratios):.2f}, "
            f"range {min(ratios):.2f}–{max(ratios):.2f} over {len(ratios)} cases"
        )


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--worker":
        worker(sys.argv[2])
    else:
        main(sys.argv[1] if len(sys.argv) > 1 else None)
