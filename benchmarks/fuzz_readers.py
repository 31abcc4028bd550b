"""Fuzz every reader with many damaged copies of real files and count the outcomes.

Usage: python benchmarks/fuzz_readers.py [N per case] [seed] [name filter] [--markdown]

The cases are the ``CASES`` lists of ``tests/test_fuzz_*.py``: WAMIT numeric files and
``.out`` logs, HAMS projects (WAMIT-format output, ``ControlFile.in``,
``Hydrostatic.in``), NEMOH, AQWA, ShipX/VERES, MSS ``.mat`` (``vessel`` and ``RAO``
structs), Capytaine and BEMIO files, OpenFAST SS_Fitting ``.ss``/``.ssexctn``. Cases
read by another function than :func:`cummins.read` name it (``FuzzCase.reader``). The
rule each outcome is judged by is in ``tests/_mutate.py``: a damaged file must raise
``HydroDataError``, warn (``HydroDataWarning``) or read exactly the undamaged data;
re-encodings (BOM, CRLF, CR, tabs) must read identically. Besides N seeded damaged
copies per case, every declared quantity of the case (``FuzzCase.quantities``) is scaled
by 10^3 and 10^-3 and negated, every target emptied and every removable companion file
removed (``Damager.quantity_cases``). Prints one line per case and
every failure, then the totals (with ``--markdown``, a table for BENCHMARKS.md); exit
status 1 when there is any failure.
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
KINDS = ("error", "warned", "same", "blind", "different", "crash")


def _cases():
    for path in sorted((ROOT / "tests").glob("test_fuzz_*.py")):
        spec = importlib.util.spec_from_file_location(path.stem, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        for case in getattr(module, "CASES", []):
            yield path.stem.removeprefix("test_fuzz_"), case


def main() -> int:
    args = [a for a in sys.argv[1:] if a != "--markdown"]
    markdown = "--markdown" in sys.argv[1:]
    n = int(args[0]) if len(args) > 0 else 200
    seed = int(args[1]) if len(args) > 1 else 1
    only = args[2] if len(args) > 2 else ""
    warnings.simplefilter("ignore")
    bad = 0
    rows = []
    for group, case in _cases():
        if only not in case.name and only != group:
            continue
        t0 = time.perf_counter()
        with Damager(SHARED, case) as damager:
            damaged = list(damager.cases(n, seed))
            encoded = list(damager.encodings())
            quantities = list(damager.quantity_cases())
        outcomes = damaged + encoded + quantities
        counts = collections.Counter(o.kind for _, _, o in damaged)
        q_counts = collections.Counter(o.kind for _, _, o in quantities)
        wrong = failures(outcomes)
        bad += len(wrong)
        elapsed = time.perf_counter() - t0
        summary = ", ".join(f"{k} {counts[k]}" for k in KINDS if counts[k])
        q_summary = ", ".join(f"{k} {q_counts[k]}" for k in KINDS if q_counts[k])
        print(
            f"{case.name:40s} {len(damaged):5d} damaged + {len(encoded):2d} re-encoded "
            f"{elapsed:6.1f} s  {summary}; {len(quantities)} quantities: {q_summary}",
            flush=True,
        )
        for line in wrong:
            print("   ", line, flush=True)
        rows.append(
            (group, case.name, len(damaged), len(encoded), counts, len(wrong), elapsed, q_counts)
        )
    total = collections.Counter()
    q_total = collections.Counter()
    for *_, counts, _, _, q_counts in rows:
        total.update(counts)
        q_total.update(q_counts)
    print(
        f"total: {sum(r[2] for r in rows)} damaged copies of {len(rows)} cases, "
        + ", ".join(f"{k} {total[k]}" for k in KINDS)
        + f"; {sum(q_total.values())} damaged quantities and emptied or removed files, "
        + ", ".join(f"{k} {q_total[k]}" for k in KINDS)
        + f"; failures: {bad}"
    )
    if markdown:
        print()
        print(
            "| reader | case | damaged | error | warned | same | blind | quantities "
            "(error/warned/same) | failures | s |"
        )
        print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
        for group, name, count, _, counts, wrong, elapsed, q_counts in rows:
            values = " | ".join(str(counts[k]) for k in ("error", "warned", "same", "blind"))
            q_values = "/".join(str(q_counts[k]) for k in ("error", "warned", "same"))
            print(
                f"| {group} | {name} | {count} | {values} | {q_values} | {wrong} | {elapsed:.0f} |"
            )
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
