"""The fluid memory of the Cummins equation, stage by stage.

From the frequency-domain coefficients to a state-space model of the radiation force:

* :mod:`~cummins.radiation.transforms`: exact cosine, sine and Kramers–Kronig integrals of
  piecewise-linear functions;
* :mod:`~cummins.radiation.retardation`: retardation functions K(t), causality diagnostics;
* :mod:`~cummins.radiation.infinite_frequency`: A∞, the data's row or Ogilvie's (1964)
  estimate;
* :mod:`~cummins.radiation.damping_tail`: the high-frequency tails of B(ω) beyond the data;
* :mod:`~cummins.radiation.fit`: identification of stable, passive state-space models;
* :mod:`~cummins.radiation.passivity`: the passivity test and its enforcement;
* :mod:`~cummins.radiation.reduce`: balanced truncation;
* :mod:`~cummins.radiation.speed`: forward speed (Hjulstad, 2004);
* :mod:`~cummins.radiation.model`: the model itself (:class:`RadiationModel`), and
  :mod:`~cummins.radiation.model_file` its NetCDF file.

The model's classes are importable from here: ``from cummins.radiation import RadiationModel``.
"""

from cummins.radiation.model import (
    CouplingModel,
    MemoryBlock,
    RadiationModel,
    SisoStateSpace,
    change_model_axes,
    siso_frequency_response,
    symmetric_couplings,
)
from cummins.radiation.model_file import (  # also registers the format of save/load
    read_radiation_model,
    write_radiation_model,
)

__all__ = [
    "CouplingModel",
    "MemoryBlock",
    "RadiationModel",
    "SisoStateSpace",
    "change_model_axes",
    "read_radiation_model",
    "siso_frequency_response",
    "symmetric_couplings",
    "write_radiation_model",
]
