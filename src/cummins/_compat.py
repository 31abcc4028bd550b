"""Module paths of earlier releases, kept importable.

The package was regrouped by stage (``cummins.radiation``, ``cummins.seakeeping``,
``cummins.timedomain``, ``cummins.studies``, ``cummins.cli``). Code written against the
earlier flat layout (``from cummins.retardation import retardation_function``,
``import cummins.loads``) keeps working: an import of an earlier path returns the module
at its new place, the very same module object, so attributes, ``isinstance`` checks and
monkeypatching behave as they did. Nothing is imported until an earlier path is used.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
from types import ModuleType

#: earlier module path (below ``cummins.``) → where that module lives now
MOVED: dict[str, str] = {
    "transforms": "radiation.transforms",
    "retardation": "radiation.retardation",
    "passivity": "radiation.passivity",
    "reduce": "radiation.reduce",
    "speed": "radiation.speed",
    "fit": "radiation.fit",
    "io.model_netcdf": "radiation.model_file",
    "waves": "seakeeping.waves",
    "excitation": "seakeeping.excitation",
    "frequency_domain": "seakeeping.frequency_domain",
    "simulate": "timedomain.simulate",
    "unified": "timedomain.unified",
    "loads": "timedomain.loads",
    "dp": "timedomain.dp",
    "lfmodel": "timedomain.lfmodel",
    "study": "studies.study",
    "batch": "studies.batch",
    "operability": "studies.operability",
    "demo": "cli.demo",
    "pipeline": "cli.pipeline",
    "dp_scenario": "cli.dp_scenario",
    "report": "cli.html_report",
    **{
        f"cli_{name}": f"cli.{name}"
        for name in (
            [
                "batch",
                "bem",
                "common",
                "dp",
                "fit",
                "kernel",
                "lfmodel",
                "rao",
                "reduce",
                "simulate",
                "sysid",
            ]
        )
    },
}


def new_location(fullname: str) -> str | None:
    """The current path of a module imported by an earlier path, or None.

    >>> new_location("cummins.retardation")
    'cummins.radiation.retardation'
    >>> new_location("cummins.fit.vector")
    'cummins.radiation.fit.vector'
    >>> new_location("cummins.hydrodb") is None
    True
    """
    if not fullname.startswith("cummins."):
        return None
    rest = fullname[len("cummins.") :]
    for old, new in MOVED.items():
        if rest == old or rest.startswith(old + "."):
            return "cummins." + new + rest[len(old) :]
    return None


class _MovedModuleFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds an earlier path and loads it as the module at its new place."""

    def __init__(self) -> None:
        self._specs: dict[str, object] = {}

    def find_spec(self, fullname, path=None, target=None):
        new = new_location(fullname)
        if new is None:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec) -> ModuleType:
        module = importlib.import_module(new_location(spec.name))
        self._specs[spec.name] = module.__spec__
        return module

    def exec_module(self, module: ModuleType) -> None:
        # the import system put the alias spec on the module: give it its own back
        module.__spec__ = self._specs.pop(module.__spec__.name)


def install() -> None:
    """Make the earlier module paths importable (called once by ``import cummins``)."""
    if not any(isinstance(f, _MovedModuleFinder) for f in sys.meta_path):
        # first: a submodule of a moved package (cummins.fit.vector) must not be found
        # again, as a second copy, in the package's folder
        sys.meta_path.insert(0, _MovedModuleFinder())
