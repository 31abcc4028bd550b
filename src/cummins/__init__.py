"""cummins: from frequency-domain hydrodynamics to time-domain vessel models.

Read the output of WAMIT, NEMOH, AQWA, ShipX/VERES, Capytaine or MSS into one
canonical dataset, check it, compute retardation functions and identify stable
state-space models of the fluid memory, and simulate the vessel in waves against the
frequency domain.

>>> import cummins
>>> ds = cummins.read(cummins.demo_files() / "tanker.1")
>>> report = cummins.check(ds)
>>> model = cummins.fit_radiation(ds)
>>> model.is_stable()
True
"""

from __future__ import annotations

import importlib
import sys
from importlib import resources
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING

from cummins import _compat
from cummins._version import __version__
from cummins.errors import (
    ArgumentError,
    CumminsError,
    CumminsWarning,
    FitError,
    HydroDataError,
    HydroDataWarning,
    OutputExistsError,
    SimulationError,
)

if TYPE_CHECKING:  # what the names below are; imported on first use (``__getattr__``)
    import xarray as xr

    from cummins import repair
    from cummins.check import CheckReport, Finding, check
    from cummins.excitation_model import ExcitationModel, excitation_irf, fit_excitation
    from cummins.hydrodb import (
        DOF_NAMES,
        change_axes,
        dof_labels,
        make_hydrodb,
        move_reference_point,
        select_dofs,
        validate,
    )
    from cummins.io import FORMATS, detect_format, read, write
    from cummins.mass_properties import with_external_terms, with_inertia
    from cummins.radiation import passivity, reduce
    from cummins.radiation.fit import fit_radiation
    from cummins.radiation.model import CouplingModel, RadiationModel
    from cummins.radiation.retardation import (
        added_mass_inf,
        kramers_kronig_error,
        retardation_function,
    )
    from cummins.seakeeping import frequency_domain, waves
    from cummins.seakeeping.frequency_domain import motion_rao
    from cummins.timedomain.simulate import simulate_waves
    from cummins.vessel import Vessel, vessel_from_hydrodb

#: The public names and the module each comes from. They are imported when first used,
#: so that ``import cummins`` (and ``cummins --help``) does not load SciPy, xarray or
#: matplotlib before a command needs them; ``from cummins import read`` works as before.
_LAZY: dict[str, str] = {
    **dict.fromkeys(
        ("ExcitationModel", "excitation_irf", "fit_excitation"), "cummins.excitation_model"
    ),
    **dict.fromkeys(("CheckReport", "Finding", "check"), "cummins.check"),
    **dict.fromkeys(
        (
            "DOF_NAMES",
            "change_axes",
            "dof_labels",
            "make_hydrodb",
            "move_reference_point",
            "select_dofs",
            "validate",
        ),
        "cummins.hydrodb",
    ),
    **dict.fromkeys(("FORMATS", "detect_format", "read", "write"), "cummins.io"),
    **dict.fromkeys(("with_external_terms", "with_inertia"), "cummins.mass_properties"),
    "fit_radiation": "cummins.radiation.fit",
    **dict.fromkeys(("CouplingModel", "RadiationModel"), "cummins.radiation.model"),
    **dict.fromkeys(
        ("added_mass_inf", "kramers_kronig_error", "retardation_function"),
        "cummins.radiation.retardation",
    ),
    "motion_rao": "cummins.seakeeping.frequency_domain",
    "simulate_waves": "cummins.timedomain.simulate",
    **dict.fromkeys(("Vessel", "vessel_from_hydrodb"), "cummins.vessel"),
}
#: Public modules, by their short name.
_MODULES: dict[str, str] = {
    "repair": "cummins.repair",
    "passivity": "cummins.radiation.passivity",
    "reduce": "cummins.radiation.reduce",
    "frequency_domain": "cummins.seakeeping.frequency_domain",
    "waves": "cummins.seakeeping.waves",
}


def __getattr__(name: str):
    """The public names of :data:`_LAZY` and :data:`_MODULES`, imported on first use."""
    if name in _MODULES:
        value = importlib.import_module(_MODULES[name])
    elif name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
    else:
        raise AttributeError(f"module 'cummins' has no attribute {name!r}")
    globals()[name] = value
    return value


#: What the package imports for itself, not part of its interface (hidden from ``dir``).
_OWN_IMPORTS = frozenset(
    {"annotations", "importlib", "sys", "resources", "Path", "ModuleType", "TYPE_CHECKING"}
)


def __dir__() -> list[str]:
    """The public names (``__all__``), the subpackages imported so far and the module's
    dunders: what tab completion in a notebook should offer."""
    shown = {n for n in globals() if not n.startswith("_") and n not in _OWN_IMPORTS}
    return sorted({*shown, *__all__, "__version__"})


class _Package(ModuleType):
    """The ``cummins`` module: the function ``cummins.check`` keeps its name when the
    package ``cummins.check`` is imported (the import system sets the parent's attribute
    to the subpackage, which an eager ``from cummins.check import check`` used to undo)."""

    def __setattr__(self, name: str, value) -> None:
        if name in _LAZY and isinstance(value, ModuleType) and hasattr(value, name):
            value = getattr(value, name)
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
_compat.install()  # the module paths of earlier releases (cummins.retardation, …)


def demo_files() -> Path:
    """Folder of the bundled demo vessel (MSS tanker, WAMIT output, MIT licence)."""
    return Path(str(resources.files("cummins") / "data" / "tanker"))


def demo_dataset() -> xr.Dataset:
    """The bundled tanker as a ``HydroDB`` (WAMIT ``.1/.3/.hst/.frc/.out``)."""
    from cummins.io import read

    return read(demo_files() / "tanker.1")


__all__ = [
    "DOF_NAMES",
    "FORMATS",
    "ArgumentError",
    "CheckReport",
    "CouplingModel",
    "CumminsError",
    "CumminsWarning",
    "ExcitationModel",
    "Finding",
    "FitError",
    "HydroDataError",
    "HydroDataWarning",
    "OutputExistsError",
    "RadiationModel",
    "SimulationError",
    "Vessel",
    "__version__",
    "added_mass_inf",
    "change_axes",
    "check",
    "demo_dataset",
    "demo_files",
    "detect_format",
    "dof_labels",
    "excitation_irf",
    "fit_excitation",
    "fit_radiation",
    "frequency_domain",
    "kramers_kronig_error",
    "make_hydrodb",
    "motion_rao",
    "move_reference_point",
    "passivity",
    "read",
    "reduce",
    "repair",
    "retardation_function",
    "select_dofs",
    "simulate_waves",
    "validate",
    "vessel_from_hydrodb",
    "waves",
    "with_external_terms",
    "with_inertia",
    "write",
]
