"""The package layout shows the architecture (docs/architecture.md): the command line in
``cummins.cli``, imported by no library module; modules of one concept, none over ~800
lines; no import cycle; the module paths of earlier releases still importable.

The import graph is read from the source (``ast``): an edge for every ``import`` and
``from … import`` at module level (imports inside functions are deferred by design and
not part of the graph; those under ``if TYPE_CHECKING:`` are never executed).
"""

from __future__ import annotations

import ast
import importlib
import subprocess
import sys
from pathlib import Path

import pytest

import cummins
from conftest import package_modules
from cummins import _compat

#: the most lines a module may have (the earlier layout had modules of 1.2k–1.9k lines)
MAX_LINES = 800
MODULES = package_modules()


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _imports(module: str, path: Path, *, deferred: bool) -> set[str]:
    """The cummins modules ``module`` imports (at module level, or anywhere if ``deferred``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: set[str] = set()

    def visit(node: ast.AST, top: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and _is_type_checking(child):
                continue
            nested = isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda)
            if isinstance(child, ast.Import) and (top or deferred):
                found.update(a.name for a in child.names if a.name.startswith("cummins"))
            elif isinstance(child, ast.ImportFrom) and (top or deferred):
                base = child.module or ""
                if child.level:
                    anchor = package.split(".")[: len(package.split(".")) - child.level + 1]
                    base = ".".join([*anchor, base] if base else anchor)
                if base.startswith("cummins"):
                    for alias in child.names:
                        sub = f"{base}.{alias.name}"
                        found.add(sub if sub in MODULES else base)
            visit(child, top and not nested)

    visit(tree, True)
    return {m for m in found if m in MODULES and m != module}


def test_no_module_is_longer_than_800_lines():
    lengths = {m: len(p.read_text(encoding="utf-8").splitlines()) for m, p in MODULES.items()}
    too_long = {m: n for m, n in lengths.items() if n > MAX_LINES}
    assert not too_long, f"split by concept: {too_long}"
    # the limit binds: the largest modules of the earlier layout were 1.2k–1.9k lines
    assert max(lengths.values()) > 500


def test_no_import_cycle_between_modules():
    graph = {m: _imports(m, p, deferred=False) for m, p in MODULES.items()}
    state: dict[str, int] = {}  # 1 on the current path, 2 done
    path: list[str] = []

    def walk(node: str) -> None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                cycle = [*path[path.index(nxt) :], nxt]
                pytest.fail("import cycle: " + " → ".join(cycle))
            if nxt not in state:
                walk(nxt)
        path.pop()
        state[node] = 2

    for module in sorted(graph):
        if module not in state:
            walk(module)
    # the graph is real: the fit imports the model, the model file imports the model
    assert "cummins.radiation.model" in graph["cummins.radiation.model_file"]
    assert "cummins.radiation.model_file" not in graph["cummins.radiation.model"]


def test_the_library_never_imports_the_command_line():
    # ``python -m cummins`` (cummins/__main__.py) is the command line's entry, not library
    library = {
        m: p
        for m, p in MODULES.items()
        if not m.startswith("cummins.cli") and m != "cummins.__main__"
    }
    offenders = {
        m: sorted(i for i in _imports(m, p, deferred=True) if i.startswith("cummins.cli"))
        for m, p in library.items()
    }
    assert not {m: i for m, i in offenders.items() if i}
    # and the command line does use the library (the check above is not vacuous)
    assert any(
        i.startswith("cummins.radiation")
        for i in _imports("cummins.cli.fit", MODULES["cummins.cli.fit"], deferred=True)
    )


def test_importing_the_library_loads_no_command_line_module():
    code = (
        "import sys, cummins, cummins.timedomain.unified, cummins.studies.batch, "
        "cummins.radiation.speed\n"
        "print(sorted(m for m in sys.modules if m.startswith('cummins.cli')))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == "[]"


@pytest.mark.parametrize("old", sorted(_compat.MOVED))
def test_earlier_module_paths_are_the_same_modules(old):
    new = _compat.new_location(f"cummins.{old}")
    assert new is not None and new in MODULES
    moved = importlib.import_module(f"cummins.{old}")
    assert moved is importlib.import_module(new)
    assert moved.__spec__.name == new  # the module keeps its own identity


def test_earlier_paths_of_submodules_and_names():
    from cummins.fit.vector import vector_fit  # noqa: F401 (an earlier path of a submodule)
    from cummins.io.model_netcdf import read_radiation_model
    from cummins.retardation import retardation_function

    assert retardation_function is cummins.retardation_function
    assert read_radiation_model is cummins.radiation.read_radiation_model
    assert sys.modules["cummins.fit.vector"] is sys.modules["cummins.radiation.fit.vector"]


def test_the_pipeline_stages_are_found_by_their_names():
    """read → check → retardation → fit → reduce → simulate, as docs/architecture.md draws it."""
    for stage in (
        "cummins.io",
        "cummins.check",
        "cummins.radiation.retardation",
        "cummins.radiation.fit",
        "cummins.radiation.passivity",
        "cummins.radiation.reduce",
        "cummins.seakeeping.frequency_domain",
        "cummins.timedomain.simulate",
        "cummins.studies.batch",
    ):
        assert stage in MODULES, stage


#: the imports of the README's Python blocks before the regrouping, verbatim
EARLIER_README_IMPORTS = """\
import cummins
from cummins import loads
from cummins.dp import DPController, DPGains, Thrusters
from cummins.frequency_domain import motion_rao, response_spectrum, significant_amplitude
from cummins.lfmodel import lf_model_from_frequency_data
from cummins.simulate import simulate_waves
from cummins.speed import encounter_frequency
from cummins.sysid import identify_damping, make_record, roll_decay
from cummins.unified import simulate_unified, unified_vessel
from cummins.vessel import vessel_from_hydrodb
from cummins.waves import irregular_waves, regular_wave, wave_spectrum
from cummins.fit import MOTION_ACCURACY, fit_radiation
from cummins.retardation import added_mass_inf, retardation_function
from cummins.reduce import reduce_radiation_model
from cummins.passivity import enforce_passivity, passivity_test
from cummins.io.model_netcdf import read_radiation_model, write_radiation_model
from cummins.cli import main
assert loads.WindLoad is cummins.timedomain.loads.WindLoad
assert fit_radiation is cummins.fit_radiation
"""


def test_the_earlier_readme_imports_still_work():
    """In a fresh interpreter, so that nothing imported earlier in the session helps."""
    run = subprocess.run(
        [sys.executable, "-c", EARLIER_README_IMPORTS], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr


@pytest.mark.parametrize("module", ["cummins", "cummins.cli"])
def test_python_dash_m_runs_the_command(module):
    run = subprocess.run(
        [sys.executable, "-m", module, "--version"], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == f"cummins, version {cummins.__version__}"
