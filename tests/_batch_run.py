"""``cummins batch`` on a study written into a folder, in a process of its own (the Dask
workers' output reaches the terminal as a user sees it), shared by the multi-body tests."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path


def run_batch_study(folder: Path, study: str) -> subprocess.CompletedProcess:
    """Write ``study`` (YAML) to ``folder/study.yaml`` and run ``cummins batch study.yaml
    -o r.nc --workers 1`` there with one BLAS thread; the completed process, its output
    as text."""
    (folder / "study.yaml").write_text(study, encoding="utf-8")
    return subprocess.run(
        [sys.executable, "-m", "cummins", "batch", "study.yaml", "-o", "r.nc", "--workers", "1"],
        cwd=folder,
        env={**os.environ, "OPENBLAS_NUM_THREADS": "1"},
        capture_output=True,
        text=True,
        timeout=300,
    )
