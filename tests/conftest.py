"""Shared fixtures: the real solver output in ../shared/data; CI guards.

Tests that need the real data take the ``shared_data`` fixture. When the folder is
absent they are skipped with a reason, except under ``CI=true`` where a missing
folder is a failure: CI must always run them all.

Under ``CI=true`` a skipped test of any kind (a missing optional package, browser or
tool) fails the session, naming the tests: the CI installs everything the suite uses
(capytaine, dask/distributed, control, ruff, playwright, zarr, Debian's chromium), so a
skip there hides a test. When ``OPENBLAS_CORETYPE`` is set, the session starts only if
every OpenBLAS loaded by numpy and scipy runs that kernel (threadpoolctl), so that the
CI run meant for another kernel really runs on it.
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


def package_modules() -> dict[str, Path]:
    """Every module of the installed ``cummins`` package: dotted name → source file
    (a package by its ``__init__.py``)."""
    import cummins

    package = Path(cummins.__file__).parent
    modules = {}
    for path in sorted(package.rglob("*.py")):
        parts = ("cummins", *path.relative_to(package).with_suffix("").parts)
        modules[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return modules


def _under_ci() -> bool:
    return os.environ.get("CI", "").lower() == "true"


def _openblas_core_types() -> list[tuple[str, str]]:
    """(library path, core type) of every OpenBLAS that numpy and scipy load."""
    import numpy  # noqa: F401  (loads numpy's OpenBLAS)
    import scipy.linalg  # noqa: F401  (loads scipy's)
    import threadpoolctl

    return [
        (str(info.get("filepath")), str(info.get("architecture")))
        for info in threadpoolctl.threadpool_info()
        if info.get("internal_api") == "openblas"
    ]


def pytest_configure(config: pytest.Config) -> None:
    """With OPENBLAS_CORETYPE set, refuse to start unless OpenBLAS runs that kernel."""
    wanted = os.environ.get("OPENBLAS_CORETYPE")
    if not wanted:
        return
    try:
        libraries = _openblas_core_types()
    except ImportError as exc:
        raise pytest.UsageError(
            f"OPENBLAS_CORETYPE={wanted} is set but the kernel in use cannot be checked "
            f"({exc}): pip install -e .[test]"
        ) from None
    if not libraries:
        raise pytest.UsageError(f"OPENBLAS_CORETYPE={wanted} is set but no OpenBLAS is loaded")
    wrong = [(path, core) for path, core in libraries if core.lower() != wanted.lower()]
    if wrong:
        listing = "; ".join(f"{path}: {core}" for path, core in wrong)
        raise pytest.UsageError(
            f"OPENBLAS_CORETYPE={wanted} is set but OpenBLAS runs another kernel ({listing})"
        )


#: Tests (and modules) skipped in this session: (node id, reason).
_SKIPPED: list[tuple[str, str]] = []


def _skip_reason(report: pytest.CollectReport | pytest.TestReport) -> str:
    longrepr = report.longrepr
    reason = (
        str(longrepr[2]) if isinstance(longrepr, tuple) and len(longrepr) == 3 else str(longrepr)
    )
    return reason.removeprefix("Skipped: ")


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    if report.skipped and not hasattr(report, "wasxfail"):
        _SKIPPED.append((report.nodeid, _skip_reason(report)))


def pytest_collectreport(report: pytest.CollectReport) -> None:
    if report.skipped:
        _SKIPPED.append((report.nodeid, _skip_reason(report)))


def _is_controller(config: pytest.Config) -> bool:
    return not hasattr(config, "workerinput")  # pytest-xdist workers report to it


def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    """Under CI=true any skip fails the session (see the module docstring)."""
    if (
        _under_ci()
        and _SKIPPED
        and _is_controller(session.config)
        and exitstatus == pytest.ExitCode.OK
    ):
        session.exitstatus = pytest.ExitCode.TESTS_FAILED


def pytest_terminal_summary(terminalreporter, exitstatus: int, config: pytest.Config) -> None:
    if _under_ci() and _SKIPPED and _is_controller(config):
        terminalreporter.section("tests skipped under CI=true (the session fails)", red=True)
        for nodeid, reason in _SKIPPED:
            terminalreporter.line(f"SKIPPED {nodeid}: {reason}", red=True)


def _require_shared_data() -> Path:
    if SHARED_DATA.is_dir():
        return SHARED_DATA
    message = f"real solver data not found at {SHARED_DATA} (set CUMMINS_SHARED_DATA)"
    if _under_ci():
        pytest.fail(message + "; under CI=true every real-data test must run")
    pytest.skip(message)


@pytest.fixture(scope="session")
def shared_data() -> Path:
    """Path of ``../shared/data`` (real WAMIT, NEMOH, AQWA, VERES, Capytaine, MSS files)."""
    return _require_shared_data()


@pytest.fixture(scope="session")
def corpus(shared_data) -> Path:
    """Path of ``../shared/data/corpus``: 33 cases of public solver output (see its README)."""
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
