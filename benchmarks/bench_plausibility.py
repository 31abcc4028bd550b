"""False alarms and detections of the plausibility check (``cummins.check.plausibility``).

Usage: python benchmarks/bench_plausibility.py [--filter TEXT]

For every case of ``bench_corpus.py`` (the corpus and the shared file sets): the
plausibility findings of the data as they are (any warning or error is a false alarm:
these are real runs), then the same data with one quantity damaged in memory — the
added mass, the damping, the excitation, the inertia, the restoring or the frequencies
scaled by 10³ or 10⁻³, or the added mass, damping or restoring negated — and whether
the checks that take no fit then find an error (the plausibility relations, or the
physical, sign and definiteness checks that already existed: what ``cummins.read`` warns
about and ``cummins check`` fails). Prints one line per case and the totals; exit
status 1 when the undamaged data raise a plausibility error.

A quantity a case does not hold, or cannot be judged on (no inertia: its scale; two
frequencies: Kramers–Kronig and Haskind), is counted as such, not as a miss.
"""

from __future__ import annotations

import argparse
import collections
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cummins
from bench_corpus import SHARED, corpus_cases
from cummins.check.plausibility import gross_errors, plausibility_findings

#: (name, variables scaled together, factor)
DAMAGES = [
    (f"{name} x{factor:g}", variables, factor)
    for name, variables in (
        ("A", ("added_mass", "added_mass_inf", "added_mass_zero")),
        ("B", ("radiation_damping",)),
        ("F", ("excitation_force",)),
        ("M", ("inertia_matrix",)),
        ("C", ("hydrostatic_stiffness",)),
        ("omega", ("omega",)),
    )
    for factor in (1e3, 1e-3)
] + [
    ("A negated", ("added_mass", "added_mass_inf", "added_mass_zero"), -1.0),
    ("B negated", ("radiation_damping",), -1.0),
    ("C negated", ("hydrostatic_stiffness",), -1.0),
]


def damaged(ds, variables, factor):
    """``ds`` with ``variables`` multiplied by ``factor`` (None when it holds none)."""
    present = [v for v in variables if v in ds.variables]
    if not present:
        return None
    out = ds.copy(deep=True)
    for name in present:
        if name == "omega":
            out = out.assign_coords(omega=out.omega * factor)
        else:
            out[name] = out[name] * factor
    return out


def detected(ds) -> bool:
    """An error of the checks that take no fit (what ``cummins.read`` warns about and
    ``cummins check`` fails: the retardation diagnostics give warnings only)."""
    try:
        return bool(gross_errors(ds))
    except cummins.CumminsError:
        return True


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--filter", default="", help="only cases whose name contains TEXT")
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore")
    false_alarms = 0
    totals = collections.Counter()
    missed: list[str] = []
    for path in corpus_cases():
        name = str(path.relative_to(SHARED))
        if args.filter not in name:
            continue
        t0 = time.perf_counter()
        try:
            ds = cummins.read(path)
        except cummins.CumminsError:
            continue
        alarms = [f for f in plausibility_findings(ds) if f.severity != "ok"]
        false_alarms += sum(f.severity == "error" for f in alarms)
        counts = collections.Counter()
        for label, variables, factor in DAMAGES:
            bad = damaged(ds, variables, factor)
            if bad is None:
                counts["absent"] += 1
                continue
            if detected(bad):
                counts["detected"] += 1
            else:
                counts["missed"] += 1
                missed.append(f"{name}: {label}")
        totals.update(counts)
        alarm_text = "; ".join(f"{f.severity} {f.where}: {f.message[:60]}" for f in alarms)
        print(
            f"{name:58s} {time.perf_counter() - t0:5.1f} s  detected {counts['detected']:2d}, "
            f"missed {counts['missed']:2d}, absent {counts['absent']:2d}"
            + (f"  ALARM {alarm_text}" if alarms else ""),
            flush=True,
        )
    print(
        f"total: {totals['detected']} damaged copies detected, {totals['missed']} missed, "
        f"{totals['absent']} quantities absent; plausibility errors on the undamaged data: "
        f"{false_alarms}"
    )
    for line in missed:
        print("   missed", line)
    return 1 if false_alarms else 0


if __name__ == "__main__":
    np.seterr(all="ignore")
    sys.exit(main())
