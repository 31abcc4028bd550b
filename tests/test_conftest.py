"""The CI guards of tests/conftest.py, run on a throw-away suite in a subprocess.

Under ``CI=true`` a skipped test or module fails the session and is named; xfail is not a
skip; without CI a skip is only reported. With ``OPENBLAS_CORETYPE`` set to a kernel
OpenBLAS does not run, the session refuses to start.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

CONFTEST = Path(__file__).with_name("conftest.py")

SUITE = {
    "test_some.py": (
        "import pytest\n\n\n"
        "def test_passes():\n    pass\n\n\n"
        "def test_skips():\n    pytest.skip('no widget here')\n\n\n"
        "@pytest.mark.xfail(reason='known')\n"
        "def test_expected_failure():\n    assert False\n"
    ),
    "test_optional.py": (
        "import pytest\n\n"
        "pytest.importorskip('no_such_module_for_the_guard')\n\n\n"
        "def test_never_runs():\n    pass\n"
    ),
}


@pytest.fixture
def suite(tmp_path) -> Path:
    shutil.copy(CONFTEST, tmp_path / "conftest.py")
    for name, text in SUITE.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    return tmp_path


def _pytest(folder: Path, *args: str, **env: str) -> subprocess.CompletedProcess:
    environment = {k: v for k, v in os.environ.items() if k not in ("CI", "PYTEST_ADDOPTS")}
    environment.update(env)
    return subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *args],
        cwd=folder,
        env=environment,
        capture_output=True,
        text=True,
        timeout=300,
    )


@pytest.mark.parametrize("workers", [[], ["-n", "2"]], ids=["serial", "xdist"])
def test_a_skip_fails_the_session_under_ci(suite, workers):
    run = _pytest(suite, *workers, CI="true")
    assert run.returncode == 1, run.stdout + run.stderr
    assert "test_some.py::test_skips: no widget here" in run.stdout
    assert "test_optional.py: could not import 'no_such_module_for_the_guard'" in run.stdout
    assert "test_expected_failure" not in run.stdout.split("skipped under CI=true")[1]


def test_without_ci_a_skip_is_only_reported(suite):
    run = _pytest(suite)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "2 skipped" in run.stdout and "skipped under CI=true" not in run.stdout


def test_no_skip_passes_under_ci(suite):
    run = _pytest(
        suite, "test_some.py::test_passes", "test_some.py::test_expected_failure", CI="true"
    )
    assert run.returncode == 0, run.stdout + run.stderr


def test_the_openblas_kernel_is_checked(suite):
    """A kernel name OpenBLAS does not know leaves it on the detected one: refused. The
    kernel this session runs is accepted."""
    import numpy  # noqa: F401
    import scipy.linalg  # noqa: F401
    import threadpoolctl

    kernels = {
        info["architecture"]
        for info in threadpoolctl.threadpool_info()
        if info.get("internal_api") == "openblas"
    }
    assert len(kernels) == 1, kernels
    wrong = _pytest(suite, "test_some.py::test_passes", OPENBLAS_CORETYPE="NoSuchKernel")
    assert wrong.returncode == pytest.ExitCode.USAGE_ERROR, wrong.stdout + wrong.stderr
    assert "OPENBLAS_CORETYPE=NoSuchKernel is set but OpenBLAS runs another kernel" in (
        wrong.stderr
    )
    right = _pytest(suite, "test_some.py::test_passes", OPENBLAS_CORETYPE=kernels.pop())
    assert right.returncode == 0, right.stdout + right.stderr
