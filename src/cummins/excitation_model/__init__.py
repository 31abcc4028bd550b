"""Causal state-space models of the first-order wave excitation.

The wave force on a body as the output of a causal linear system driven by the wave
elevation at the origin, η(t + t_c) (Yu & Falnes (1995); what OpenFAST's HydroDyn
integrates with ``ExctnMod = 2``, and what model-predictive control of wave-energy
converters and floating wind turbines needs):

* :mod:`~cummins.excitation_model.impulse`: the non-causal excitation impulse response
  K_ex(t) = (1/2π) ∫ F(ω) e^{iωt} dω (Falnes (2002)) and the time advance t_c;
* :mod:`~cummins.excitation_model.fit`: vector fitting of F(ω) e^{−iωt_c} per DOF and
  heading, the order against an NRMSE target over the wave band;
* :mod:`~cummins.excitation_model.model`: :class:`ExcitationModel` (frozen), its
  responses and state-space matrices;
* :mod:`~cummins.excitation_model.drive`: the forces driven by an elevation record;
* :mod:`~cummins.excitation_model.model_file`: its NetCDF file.

HydroDyn's ``.ssexctn`` file: :mod:`cummins.io.openfast_excitation`.
"""

from __future__ import annotations

from cummins.excitation_model.fit import fit_excitation
from cummins.excitation_model.impulse import causal_delay, excitation_irf
from cummins.excitation_model.model import DofExcitation, ExcitationModel

__all__ = [
    "DofExcitation",
    "ExcitationModel",
    "causal_delay",
    "excitation_irf",
    "fit_excitation",
]
