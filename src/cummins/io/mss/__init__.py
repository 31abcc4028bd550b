"""Marine Systems Simulator (MSS) ``vessel`` structs in MATLAB ``.mat`` files.

MSS (Fossen, cybergalactic/MSS on GitHub) stores a processed vessel as one struct named
``vessel``, written by ``wamit2vessel.m`` or ``veres2vessel.m`` and read by
``vessel2ss.m`` and the Simulink models. Its fields, as found in the MSS files
``tanker.mat`` (from WAMIT), ``supply.mat`` and ``s175.mat`` (from ShipX/VERES):

==================  ==================================================================
``main``            ``name``, ``rho`` (kg/m³), ``g`` (m/s²), ``m`` (kg), ``nabla`` (m³),
                    ``Lpp``, ``B``, ``T`` (m), ``CG``, ``CB`` (m, see below),
                    ``k44`` … (m, radii of gyration about CG),
                    ``GM_T``, ``GM_L`` (m)
``MRB``             6×6 rigid-body mass matrix about the reference point (kg, kg·m, kg·m²)
``A``, ``B``, ``C`` 6×6×Nfreq (×Nspeed) added mass, potential damping, restoring
``Bv``              6×6×Nfreq (×Nspeed) viscous damping estimated by MSS
``freqs``           1×Nfreq, rad/s
``headings``        1×Nhead, rad (0:10:350 deg)
``velocities``      1×Nspeed, m/s
``forceRAO``        ``w`` (rad/s), ``amp{1:6}``, ``phase{1:6}``: (Nω, Nhead, Nslot)
``motionRAO``       as ``forceRAO``; amplitudes m/m and rad/m
``driftfrc``        ``w``, ``amp{1:3}``: mean drift in surge, sway and yaw (N/m², N·m/m²)
``roll``            (VERES only) VERES roll damping, ``Bv44`` and the raw ``veres`` rows
==================  ==================================================================

Conventions, checked against the WAMIT and VERES files MSS processed (see the tests):

* Axes are Fossen's body axes (x forward, y to starboard, z down): this reader returns
  ``axis_convention="z-down"`` data as MSS has it, SI units.
* Complex values are ``amp * exp(1j * phase)`` with the phase in radians and time
  dependence Re{X e^{iωt}}; they equal WAMIT's and VERES's complex values after the axis
  change (``tanker.mat`` forceRAO agrees with the WAMIT ``.3`` file to round-off).
* ``headings`` is the direction in which the waves travel, from +x towards +y
  (starboard): the ``wave_direction`` of the z-down dataset.
* MSS (``wamit2vessel``) puts ω = 0 as the first frequency and A(∞) at a last stand-in
  frequency of 10 rad/s, with zero damping at both (``vessel2ss`` relies on this). The
  reader moves a first entry at ω = 0 into ``added_mass_zero``, and a last entry with
  exactly zero damping (the frequency before it having some) into ``added_mass_inf``.
* ``C`` is repeated for every frequency; it must not vary (else the first value is used
  and the history says so).
* ``forceRAO.amp`` etc. have a third index over up to 10 speed slots, of which the first
  ``numel(velocities)`` are used.
* MSS computes 0–180° and fills 190–350° itself. The first-order tables there are the
  port/starboard mirror images, the ``driftfrc`` of MSS's own files is not:
  ``wamit2vessel`` puts the drift of 10–170° at 190–350° in the same order, sway and yaw
  negated (``tanker.mat``), ``read_veres_WD`` mirrors the yaw drift with its sign kept
  (``supply.mat``, ``s175.mat``). The reader replaces such a drift at 190–350° by the
  mirror image of 0–180° (:func:`~cummins.io.mss.reader.mirrored_mss_drift`; the history
  says so, ``drift_as_stored=True`` keeps MSS's numbers, which ``cummins check``'s
  ``wave_parity`` then names with the headings and the pattern).

Reference point. MSS calls the origin CO of its b-frame the point on the waterline at
Lpp/2 on the centre line. ``main.CG`` is written in two ways: older files (all three
here) give ``[x_g, y_g, KG]`` with KG the height of G above the keel; newer MSS
versions (those that write ``hydrodynamic_reference``, ``'CO'`` or ``'CG'``: the point
the data are about) give the FSD vector from CO. Without that field the reader decides
which from ``MRB``, whose off-diagonal block holds m·r_g about the point the matrices
are taken about: the reference point is CG − r_g, and the interpretation that puts it
on the waterline (z = 0) wins. The dataset's ``reference_point`` is that point, in
z-down coordinates from CO. It is CO for ``tanker.mat`` and ``supply.mat``, and 0.05 m
above the waterline for ``s175.mat`` (VERES computed the S-175 about its CG height and
MSS moved the matrices only along x).

VERES-derived structs (with a ``roll.veres`` field and no ``hydrodynamic_reference``
field), written by the older MSS versions, have ``forceRAO`` and ``motionRAO`` left
about the VERES motion reference point, at the longitudinal position of G, while
``A``, ``B``, ``C`` and ``MRB`` were moved to CO. The reader moves the RAOs to the
reference point of the matrices (``rao_reference`` overrides the detected point), and
notes that the surge row of ``A`` and ``B`` is MSS's estimate (A11 = α A22,
B11 = α B22), not VERES output.

:func:`write_mss` writes any ``HydroDB`` as such a struct (MATLAB v5 file), about the
dataset's reference point, which it records in ``vessel.cummins.reference_point`` (read
back first by this reader) besides ``hydrodynamic_reference`` (``'CO'``/``'CG'``).

The package's modules: :mod:`~cummins.io.mss.matfile` (detection, struct access),
:mod:`~cummins.io.mss.grid` (frequency grid, wave tables), :mod:`~cummins.io.mss.points`
(reference point, CG, CB), :mod:`~cummins.io.mss.reader` (:func:`read_mss`),
:mod:`~cummins.io.mss.writer` (:func:`write_mss`) and :mod:`~cummins.io.mss.rao`
(:func:`read_force_rao`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from cummins._lazy import lazy_attributes
from cummins.io.mss.matfile import DRIFT_DOFS as DRIFT_DOFS
from cummins.io.mss.matfile import MSS_INFINITE_FREQUENCY as MSS_INFINITE_FREQUENCY
from cummins.io.mss.matfile import load_mat_struct as load_mat_struct
from cummins.io.mss.matfile import sniff, sniff_dir

#: Where the names of the package live; imported on first use (PEP 562), so that
#: recognising a file of another format (``cummins.io.detect_format`` asks every format)
#: imports the detection module only.
_LAZY = {"read_force_rao": "rao", "read_mss": "reader", "write_mss": "writer"}

if TYPE_CHECKING:  # pragma: no cover
    from cummins.io.mss.rao import read_force_rao as read_force_rao
    from cummins.io.mss.reader import read_mss
    from cummins.io.mss.writer import write_mss

__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, globals())


__all__ = ["read_mss", "sniff", "sniff_dir", "write_mss"]
