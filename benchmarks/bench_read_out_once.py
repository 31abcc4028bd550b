"""Reading a WAMIT run whose ``.out`` is read once (its text and header passed along)
against the reader of an earlier commit, which opened the log up to five times (banner,
header, drift search, and once more per table read), in the same run.

Each version runs in a subprocess of its own (the earlier one from ``git archive`` of
``REF``, by default the commit before the change), reads every case best of ``repeat``
times and hands back its dataset, which must be ``identical`` (attrs included) to the
current one.

Usage: ``python benchmarks/bench_read_out_once.py [repeat] [REF]``
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import warnings
from pathlib import Path

from _reference import ROOT, alternating, reference_source
from _timing import SHARED_DATA

#: The last commit whose WAMIT reader opened the ``.out`` several times.
REFERENCE = "d2fcefc"
CASES = {
    "tanker .1/.3/.hst/.frc/.out (drift from the .out)": ROOT / "src/cummins/data/tanker/tanker.1",
    "COER comp .1/.hst/.frc/.out (excitation from the .out)": SHARED_DATA
    / "corpus/WEC-Sim/wamit_COER_comp/coer_comp.1",
    "RM3 .1/.3/.hst/.out (two bodies)": SHARED_DATA / "corpus/WEC-Sim/wamit_RM3_2body/rm3.1",
}
NO_DOT3 = "tanker .1/.hst/.frc/.out (excitation and drift from the .out)"

_CHILD = """
import pickle, sys, time, warnings
import cummins
repeat, paths = int(sys.argv[1]), sys.argv[2:]
out = []
for path in paths:
    best = float("inf")
    for _ in range(repeat):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            start = time.perf_counter()
            ds = cummins.read(path)
            best = min(best, time.perf_counter() - start)
    out.append((best, ds))
sys.stdout.buffer.write(pickle.dumps(out))
"""


def main(repeat: int = 7, ref: str = REFERENCE) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        tanker = ROOT / "src/cummins/data/tanker"
        for suffix in (".1", ".hst", ".frc", ".out"):  # no .3: the excitation from the .out
            shutil.copy(tanker / f"tanker{suffix}", Path(tmp) / f"tanker{suffix}")
        cases = {**CASES, NO_DOT3: Path(tmp) / "tanker.1"}
        paths = [str(p) for p in cases.values()]
        old_src = reference_source(ref, Path(tmp))
        old, new = alternating((old_src, ROOT / "src"), _CHILD, (str(repeat), *paths))
    print(f"cummins.read, best of {repeat} x 3 alternating runs, this tree against {ref}")
    print(f"{'run':<66} {'before':>9} {'after':>9} {'ratio':>6} identical")
    for name, (t0, ds0), (t1, ds1) in zip(cases, old, new, strict=True):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            same = ds1.identical(ds0)
        print(f"{name:<66} {t0 * 1e3:7.1f}ms {t1 * 1e3:7.1f}ms {t0 / t1:6.2f} {same}")


if __name__ == "__main__":
    main(*(int(a) if i == 0 else a for i, a in enumerate(sys.argv[1:])))
