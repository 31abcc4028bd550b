"""The benchmark scripts of BENCHMARKS.md run to the end on the shared data.

Their numbers are not asserted (timings belong in the benchmarks, not in tests): this
only keeps a script from breaking unnoticed when the library changes under it, as
``bench_passivity.py`` and ``bench_reduce.py`` did when common poles became the default.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"
#: scripts that take minutes (every corpus case fitted three ways, or by two source trees;
#: thousands of damaged files): run by hand, their results are in BENCHMARKS.md
BY_HAND = {"bench_identification.py", "bench_fit_reference.py", "fuzz_readers.py"}
#: What a run here needs of a script that repeats its timings (best of 5 or 7 by hand):
#: one repeat runs every line of it (the CI's budget: bench_check_suspects took 118 s),
#: and of the batch study one seed per sea state (60 cases, not 240: 127 s).
ONE_REPEAT = {
    "bench_check_suspects.py": ["1"],
    "bench_read_out_once.py": ["1"],
    "bench_batch.py": ["1"],
}
SCRIPTS = sorted(
    p.name for p in BENCHMARKS.glob("*.py") if not p.name.startswith("_") and p.name not in BY_HAND
)


def test_every_benchmark_is_run_here_or_by_hand():
    every = {p.name for p in BENCHMARKS.glob("*.py") if not p.name.startswith("_")}
    assert every == set(SCRIPTS) | BY_HAND
    assert len(SCRIPTS) >= 10


@pytest.mark.slow
@pytest.mark.parametrize("script", SCRIPTS)
def test_benchmark_script_runs(script, shared_data):
    env = {
        **os.environ,
        "CUMMINS_SHARED_DATA": str(shared_data),
        "MPLBACKEND": "Agg",
        "BENCH_REPEAT": "1",
    }
    run = subprocess.run(
        [sys.executable, str(BENCHMARKS / script), *ONE_REPEAT.get(script, [])],
        cwd=BENCHMARKS.parent,
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.stdout.strip(), "a benchmark prints what it measured"
