"""Fuzz every reader with many damaged copies of real files and count the outcomes.

Usage: python benchmarks/fuzz_readers.py [N per case] [seed] [name filter]

The cases are the ``CASES`` lists of ``tests/test_fuzz_*.py``; the rule each outcome is
judged by is in ``tests/_mutate.py``: a damaged file must raise ``HydroDataError``, warn
(``HydroDataWarning``) or read exactly the undamaged data; re-encodings (BOM, CRLF, CR,
tabs) must read identically. Prints one line per case and every failure; exit status 1
when there is any.
"""

from __future__ import annotations

import collections
import importlib.util
import os
import sys
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from _mutate import Damager, failures  # noqa: E402

SHARED = Path(os.environ.get("CUMMINS_SHARED_DATA", ROOT.parent / "shared" / "data"))


def _cases():
    for path in sorted((ROOT / "tests").glob("test_fuzz_*.py")):
        spec = importlib.util.spec_from_file_location(path.stem, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        yield from getattr(module, "CASES", [])


def main() -> int:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    only = sys.argv[3] if len(sys.argv) > 3 else ""
    warnings.simplefilter("ignore")
    bad = 0
    for case in _cases():
        if only not in case.name:
            continue
        t0 = time.perf_counter()
        with Damager(SHARED, case) as damager:
            outcomes = list(damager.cases(n, seed)) + list(damager.encodings())
        counts = collections.Counter(o.kind for _, _, o in outcomes)
        wrong = failures(outcomes)
        bad += len(wrong)
        summary = ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
        elapsed = time.perf_counter() - t0
        print(f"{case.name:40s} {len(outcomes):5d} cases {elapsed:6.1f} s  {summary}")
        for line in wrong:
            print("   ", line)
    print(f"failures: {bad}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
