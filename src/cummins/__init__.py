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

from importlib import resources
from pathlib import Path

import xarray as xr

from cummins import _compat, repair
from cummins._version import __version__
from cummins.check import CheckReport, Finding, check
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

_compat.install()  # the module paths of earlier releases (cummins.retardation, …)


def demo_files() -> Path:
    """Folder of the bundled demo vessel (MSS tanker, WAMIT output, MIT licence)."""
    return Path(str(resources.files("cummins") / "data" / "tanker"))


def demo_dataset() -> xr.Dataset:
    """The bundled tanker as a ``HydroDB`` (WAMIT ``.1/.3/.hst/.frc/.out``)."""
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
