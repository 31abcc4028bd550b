"""NEMOH v2 / v3 results: ``RadiationCoefficients.tec`` and its companion files.

A NEMOH run folder holds ``Nemoh.cal`` (the input), a ``mesh/`` (or ``Mesh/``) folder
with ``KH.dat`` and ``Hydrostatics.dat`` (``KH_0.dat``, ``Hydrostatics_0.dat`` … for
several bodies) and a ``results/`` (or ``Results/``) folder with the Tecplot files.
Some projects keep everything in one folder; both layouts are read.

Files and what cummins takes from them (all dimensional, SI):

* ``Nemoh.cal``: ρ, g, water depth (``0`` means deep water), the bodies (named after
  their mesh files), the degrees of freedom and generalised forces (type 1 = translation
  along a direction, type 2 = rotation about an axis through a point), the wave
  directions and, in v3, the unit of the frequency column of the output files.
  v2 writes the frequency line as ``N wmin wmax`` (rad/s); v3 as ``type N min max``
  and adds the RAO / output-frequency-unit lines and a QTF section.
* ``RadiationCoefficients.tec``: one zone per radiating DOF ("Motion of body b in DoF
  j"); each row is ω followed by (A, B) for every generalised force: zone j, pair k is
  ``added_mass[influenced=k, radiating=j]`` (kg, kg·m, kg·m²) and the damping.
* ``ExcitationForce.tec``, ``DiffractionForce.tec``, ``FKForce.tec``: one zone per wave
  direction ("… - beta = β deg"), rows ω, then (|F|, phase) per force, N/m or N·m/m per
  metre of wave amplitude. v2 titles the zones of ``ExcitationForce.tec`` "Diffraction
  force" although they hold the total excitation. Phases are in radians (v2, v3.0);
  a file whose phases exceed π in magnitude is read as degrees (documented for later
  v3 releases), and the dataset's ``history`` says which.
* ``KH.dat``: the 6×6 hydrostatic stiffness per body (N/m, N, N·m/rad), as NEMOH wrote
  it; ``Hydrostatics.dat``: centre of buoyancy ``XF YF ZF``, centre of gravity
  ``XG YG ZG``, displaced volume (m³) and, in v3, the mass.
* ``Mechanics/Inertia.dat`` (v3) → ``inertia_matrix`` about the rotation point (NEMOH
  requires the matrices there; when the user gives none NEMOH writes its own estimate,
  ρ∇ and a uniform hull shell, which ``history`` then says), ``Km.dat`` →
  ``additional_stiffness``, ``Badd.dat`` → ``additional_damping`` (when not zero),
  ``Kh.dat`` checked against the mesh folder's ``KH.dat``. Without ``Inertia.dat`` there
  is no ``inertia_matrix``: ρ∇ is the mass only of a freely floating body, and the
  inertia tensor cannot come from the volume (``history`` says so).
* Several bodies: ``KH_0.dat`` … per body in the order of ``Nemoh.cal`` (a ``KH.dat``
  beside them is the mesher's file of the last mesh it processed), labels
  ``body1__Surge`` …, the mesh names in ``body_names``. C33 of each body is checked
  against ρ g A_wp, the ω → 0 limit of the run's own Froude-Krylov heave force: files
  of another mesh (the corpus Cubes and bemio two-body runs) are not read, with a
  warning.
* ``Nemoh.cal`` edited after the run (other frequency or direction counts than the
  results): the results are read, ``history`` says so.
* ``results/QTF/OUT_QTFM_N.dat``, ``OUT_QTFP_N.dat`` (v3): the difference- and
  sum-frequency QTFs (:mod:`cummins.io.nemoh.qtf`), as ``qtf_difference``, ``qtf_sum``.
* ``IRF.tec`` (if the post-processor was run with IRF on): NEMOH's own A(∞), column
  "AddedMass k" of zone "DoF j" being ``added_mass_inf[influenced=k, radiating=j]``.
  It is only used after checking that the file belongs to the run: its K(t) must be the
  cosine transform (2/π)∫B(ω)cos(ωt)dω of the run's damping, computed as NEMOH does
  (trapezoidal rule on the run's grid). Otherwise it is ignored, with a warning and a
  ``history`` line. NEMOH's K(t) itself is never put in the dataset.
* The frequency column is ω in rad/s unless the ``VARIABLES`` header says ``f (Hz)`` or
  ``T (s)`` (v3 "output freq type" 2 or 3), or ``Nemoh.cal`` asks for it.

Conventions. NEMOH's complex amplitudes follow exp(−iωt) (its RAO equation is
−(M+A)ω² − iωB + K, and WEC-Sim's reader negates the phases): cummins conjugates them
to its exp(+iωt) convention, i.e. F = |F|·exp(−i·phase). The cross-code test of the
WEC-Sim cylinder confirms it (NEMOH's surge phase −90° becomes WAMIT's +90°). Axes are
z up, x and y in the mean free surface (as cummins); wave direction β is the direction
of propagation from +x towards +y (as cummins). Moments and rotations are about the
point given on the rotation lines of ``Nemoh.cal``, recorded as ``reference_point``.

Modules: :mod:`~cummins.io.nemoh.files` (file names, detection, run layout),
:mod:`~cummins.io.nemoh.tecplot` (the result files, ``IRF.tec``),
:mod:`~cummins.io.nemoh.cal` (``Nemoh.cal``), :mod:`~cummins.io.nemoh.companions` (the
matrix files and ``Hydrostatics.dat``), :mod:`~cummins.io.nemoh.hydrostatics` (mass and
restoring, checked against the run), :mod:`~cummins.io.nemoh.reader` (the dataset:
:func:`read_nemoh`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cummins._lazy import lazy_attributes
from cummins.io.nemoh.files import sniff, sniff_dir

#: Where the names of the package live; imported on first use (PEP 562), so that
#: recognising a file of another format (``cummins.io.detect_format`` asks every format)
#: imports the detection module only.
_LAZY = {
    "IMPLAUSIBLE": "companions",
    "SYMMETRY_TOLERANCE": "companions",
    "HYDROSTATIC_TOLERANCE": "hydrostatics",
    "read_nemoh": "reader",
    "IRF_TOLERANCE": "tecplot",
    "_read_tecplot": "tecplot",
}

if TYPE_CHECKING:  # pragma: no cover
    from cummins.io.nemoh.companions import IMPLAUSIBLE as IMPLAUSIBLE
    from cummins.io.nemoh.companions import SYMMETRY_TOLERANCE as SYMMETRY_TOLERANCE
    from cummins.io.nemoh.hydrostatics import HYDROSTATIC_TOLERANCE as HYDROSTATIC_TOLERANCE
    from cummins.io.nemoh.reader import read_nemoh
    from cummins.io.nemoh.tecplot import IRF_TOLERANCE as IRF_TOLERANCE
    from cummins.io.nemoh.tecplot import _read_tecplot as _read_tecplot

__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, globals())


__all__ = ["read_nemoh", "sniff", "sniff_dir"]
