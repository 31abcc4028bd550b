"""Shared by the benchmark scripts that measure a change against the code of an earlier
commit in the same run: that commit's ``src`` (``git archive``) and a child process
that runs a snippet with either source tree and hands back what it returns (pickled),
in turn with each tree (:func:`alternating`)."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import tarfile
import tempfile
from collections.abc import Sequence
from io import BytesIO
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def reference_source(ref: str, into: Path) -> Path:
    """The ``src`` folder of commit ``ref`` of this repository, extracted into ``into``."""
    archive = subprocess.run(
        ["git", "-C", str(ROOT), "archive", ref, "src"], capture_output=True, check=True
    ).stdout
    with tarfile.open(fileobj=BytesIO(archive)) as tar:
        tar.extractall(into, filter="data")
    return into / "src"


def reference_tree(ref: str | None = None) -> Path:
    """The reference ``src`` folder: ``BENCH_REFERENCE_SRC``, or commit
    ``BENCH_REFERENCE`` (else ``ref``, else the merge base of ``main`` and ``HEAD``)
    extracted into a temporary folder of its own (left for the run's processes)."""
    given = os.environ.get("BENCH_REFERENCE_SRC")
    if given:
        return Path(given)
    ref = os.environ.get("BENCH_REFERENCE") or ref
    if not ref:
        ref = subprocess.run(
            ["git", "-C", str(ROOT), "merge-base", "main", "HEAD"],
            check=True,
            capture_output=True,
            text=True,
        ).stdout.strip()
    return reference_source(ref, Path(tempfile.mkdtemp(prefix="cummins-reference-")))


def run_with(src: Path, code: str, *args: str) -> Any:
    """Run ``code`` (which writes ``pickle.dumps(result)`` to stdout) in a fresh Python
    importing cummins from ``src``, one BLAS thread; its result."""
    env = {**os.environ, "PYTHONPATH": str(src), "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run(
        [sys.executable, "-c", code, *args], env=env, capture_output=True, check=True
    )
    return pickle.loads(done.stdout)


def alternating(sources: Sequence[Path], code: str, args: Sequence[str], rounds: int = 3):
    """Run ``code`` (whose result is a list of (best time, value) per case) with each of
    ``sources`` in turn, ``rounds`` times, alternating so that a load on the machine
    falls on every source alike; per source, the best time of each case over the rounds
    and the values of the last round."""
    out: list[list] = [[] for _ in sources]
    for _ in range(rounds):
        for k, src in enumerate(sources):
            result = run_with(src, code, *args)
            out[k] = (
                result
                if not out[k]
                else [(min(t, t0), v) for (t, v), (t0, _) in zip(result, out[k], strict=True)]
            )
    return out
