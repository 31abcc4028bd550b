"""``cummins.check`` judging each DOF's suspect frequencies once per run (shared by the
``suspect_frequencies`` check and the mean drift's ``drift_suspect``) against the code of
an earlier commit, which judged them in each, in the same run.

Each version runs in a subprocess of its own (the earlier one from ``git archive`` of
``REF``, by default the commit before the change) and checks every case best of
``repeat`` times; the reports (JSON) must be the same.

Usage: ``python benchmarks/bench_check_suspects.py [repeat] [REF]``
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from _reference import ROOT, alternating, reference_source
from _timing import SHARED_DATA

#: The last commit whose check found the suspect frequencies twice.
REFERENCE = "d2fcefc"
CASES = {
    "WAMIT tanker (drift from its .out)": ROOT / "src/cummins/data/tanker/tanker.1",
    "WAMIT drift sphere (.7/.8/.9)": SHARED_DATA
    / "corpus/WEC-Sim_Applications/wamit_mean_drift_sphere/outputFiles/sphere.1",
    "MSS S-175 (5 speeds, drift)": ROOT / "src/cummins/data/s175/s175.mat",
    "WEC-Sim RM3 (2 bodies, no drift)": SHARED_DATA / "corpus/WEC-Sim/wamit_RM3_2body/rm3.1",
    "OC4 semi (full QTFs)": SHARED_DATA / "corpus/WEIS/ss_fitting_OC4_semi/marin_semi.1",
}

_CHILD = """
import pickle, sys, time, warnings
import cummins
repeat, paths = int(sys.argv[1]), sys.argv[2:]
out = []
warnings.simplefilter("ignore")
for path in paths:
    ds = cummins.read(path)
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        report = cummins.check(ds)
        best = min(best, time.perf_counter() - start)
    out.append((best, report.to_json()))
sys.stdout.buffer.write(pickle.dumps(out))
"""


def main(repeat: int = 5, ref: str = REFERENCE) -> None:
    paths = [str(p) for p in CASES.values()]
    with tempfile.TemporaryDirectory() as tmp:
        old_src = reference_source(ref, Path(tmp))
        old, new = alternating((old_src, ROOT / "src"), _CHILD, (str(repeat), *paths))
    print(f"cummins.check, best of {repeat} x 3 alternating runs, this tree against {ref}")
    print(f"{'data':<36} {'before':>9} {'after':>9} {'ratio':>6} same report")
    for name, (t0, r0), (t1, r1) in zip(CASES, old, new, strict=True):
        print(f"{name:<36} {t0 * 1e3:7.1f}ms {t1 * 1e3:7.1f}ms {t0 / t1:6.2f} {r0 == r1}")


if __name__ == "__main__":
    main(*(int(a) if i == 0 else a for i, a in enumerate(sys.argv[1:])))
