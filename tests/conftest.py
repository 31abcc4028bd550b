"""Shared fixtures: the real solver output in ../shared/data.

Tests that need the real data take the ``shared_data`` fixture. When the folder is
absent they are skipped with a reason, except under ``CI=true`` where a missing
folder is a failure: CI must always run them all.
"""

from __future__ import annotations

import os
from pathlib import Path

# Fits and simulations are small dense problems: BLAS threads only add overhead and
# make pytest-xdist workers fight for the two CI cores.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import pytest

ROOT = Path(__file__).resolve().parents[1]
SHARED_DATA = Path(os.environ.get("CUMMINS_SHARED_DATA", ROOT.parent / "shared" / "data"))


def _require_shared_data() -> Path:
    if SHARED_DATA.is_dir():
        return SHARED_DATA
    message = f"real solver data not found at {SHARED_DATA} (set CUMMINS_SHARED_DATA)"
    if os.environ.get("CI", "").lower() == "true":
        pytest.fail(message + "; under CI=true every real-data test must run")
    pytest.skip(message)


@pytest.fixture(scope="session")
def shared_data() -> Path:
    """Path of ``../shared/data`` (real WAMIT, NEMOH, AQWA, VERES, Capytaine, MSS files)."""
    return _require_shared_data()


@pytest.fixture(scope="session")
def corpus(shared_data) -> Path:
    """Path of ``../shared/data/corpus``: 32 cases of public solver output (see its README)."""
    path = shared_data / "corpus"
    if not path.is_dir():
        message = f"the public corpus is not at {path}"
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(message + "; under CI=true every real-data test must run")
        pytest.skip(message)
    return path


@pytest.fixture(scope="session")
def tanker_wamit(shared_data):
    """The MSS tanker read from its WAMIT numeric files (.1/.3/.hst + .frc, .out)."""
    import cummins

    return cummins.read(shared_data / "mss" / "tanker" / "tanker.1")
