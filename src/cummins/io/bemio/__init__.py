"""BEMIO ``.h5``: WEC-Sim's hydrodynamic data file (read both layouts, write MATLAB's).

WEC-Sim (NREL/Sandia) runs on an HDF5 file that its pre-processor BEMIO writes from a
solver's output. Two layouts are in use:

* **MATLAB BEMIO** (``writeBEMIOH5.m``, read by WEC-Sim's ``readBEMIOH5.m``), the one in
  use today. MATLAB writes column-major arrays after ``permute(X, [3 2 1])``, so that
  h5py (row-major) sees, per body b with m DOFs starting at row n of the full matrices:

  ======================================================  ===========================
  dataset (under ``body<b>/``)                            h5py shape, element
  ======================================================  ===========================
  ``hydro_coeffs/added_mass/all``                         (m, N, nω): A(n+i, j, ω)/ρ
  ``hydro_coeffs/added_mass/inf_freq``                    (m, N): A∞(n+i, j)/ρ
  ``hydro_coeffs/radiation_damping/all``                  (m, N, nω): B(n+i, j, ω)/(ρω)
  ``hydro_coeffs/excitation/re``, ``im`` (``mag``,        (m, nβ, nω): F(n+i, β, ω)/(ρg)
  ``phase``; ``froude-krylov/…``, ``scattering/…``)
  ``hydro_coeffs/linear_restoring_stiffness``             (m, m): C/(ρg)
  ``hydro_coeffs/radiation_damping/impulse_response_fun`` ``K`` (m, N, nt): K(t)/ρ, ``t``
  ``hydro_coeffs/radiation_damping/state_space``          ``A/all`` (m, N, o, o), ``B/all``
                                                          (m, N, o, 1), ``C/all`` (m, N, 1,
                                                          o) /ρ, ``D/all``, ``K/all``,
                                                          ``it`` (orders), ``r2t``, ``conv``
  ``properties/name``, ``cg``, ``cb``, ``disp_vol``,      m, m, m³; ``dof`` modes per body
  ``dof``, ``dof_start``, ``dof_end``, ``body_number``
  ======================================================  ===========================

  and ``simulation_parameters/`` ``rho``, ``g``, ``w`` (rad/s), ``T`` (s), ``wave_dir``
  (degrees), ``water_depth`` (m, or the text ``infinite``), ``scaled`` (0: the
  coefficients are normalised as above; WEC-Sim multiplies them by ρ, ρω, ρg), and
  ``bem_data/code``. The normalisations are those of BEMIO's ``hydro`` structure (the
  datasets' ``description`` attributes say "normalized by rho", "rho*w", "rho*g") and of
  WEC-Sim's ``bodyClass`` which undoes them (``.*rho``, ``.*rho.*w``, ``.*rho.*g``; the
  state-space ``C`` too). Older MATLAB files also hold ``components/<i>_<j>`` copies
  (nω × 2: period, value) of every coefficient.
* **Python bemio (2015)** (``bemio.io.output.write_hdf5``): the same group names with
  ``comps/comp_<i>_<j>`` copies, wave directions in radians, no ``scaled`` flag, and
  *dimensional* coefficients (measured: the OSWEC file equals its WAMIT ``.out`` made
  dimensional with the file's ρ = 1000 kg/m³, g = 9.81 m/s² to 1e-12).

Conventions: WAMIT's (BEMIO converts NEMOH and Capytaine data to them): time dependence
e^{+iωt}, z up, β the direction the waves travel from +x towards +y, coefficients about
each body's centre of gravity (WEC-Sim requires it; the corpus files' WAMIT ``.out``
twins have XBODY = cg), which becomes ``reference_point`` here.

Writing (:func:`write_bemio`) produces the MATLAB layout above, every numeric dataset
with HDF5's Fletcher-32 checksum, and adds a group ``cummins`` holding the dataset in
cummins' NetCDF layout (:func:`cummins.io.netcdf.to_capytaine_layout`), which WEC-Sim
ignores and which makes read → write → read exact (the normalised copies are checked
against it on reading).

Modules
-------
:mod:`~cummins.io.bemio.files` (detection, checked access to the datasets),
:mod:`~cummins.io.bemio.reader` (both layouts), :mod:`~cummins.io.bemio.state_space`
(BEMIO's radiation state-space models) and :mod:`~cummins.io.bemio.writer`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cummins._lazy import lazy_attributes
from cummins.io.bemio.files import COPY_GROUP, sniff, sniff_dir  # noqa: F401

#: Where the names of the package live; imported on first use (PEP 562), so that
#: recognising a file of another format (``cummins.io.detect_format`` asks every format)
#: imports the detection module only.
_LAZY = {
    "read_bemio": "reader",
    "read_bemio_state_space": "state_space",
    "write_bemio": "writer",
}

if TYPE_CHECKING:  # pragma: no cover
    from cummins.io.bemio.reader import read_bemio
    from cummins.io.bemio.state_space import read_bemio_state_space
    from cummins.io.bemio.writer import write_bemio

__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, globals())


__all__ = ["read_bemio", "read_bemio_state_space", "sniff", "sniff_dir", "write_bemio"]
