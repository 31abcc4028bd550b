"""WAMIT output: numeric files ``.1`` ``.3`` ``.4`` ``.hst`` (with ``.frc``, ``.mmx``,
``.cfg``, ``.pot``) and the ``.out`` log; also the "Wamit_format" files HAMS writes
(read through :mod:`cummins.io.hams`).

WAMIT writes nondimensional numbers (WAMIT User Manual v7, §4.1). With L the length
scale ULEN, ρ the density and g gravity, and k = 0 for translations and generalized
modes, 1 for rotations:

* added mass       A = Ā ρ L^(3+k_i+k_j)          (``.1``)
* damping          B = B̄ ρ ω L^(3+k_i+k_j)        (``.1``)
* excitation       X = X̄ ρ g L^(2+k_i)            (``.3``, per metre of wave amplitude)
* hydrostatics     C = C̄ ρ g L^(2+k_i+k_j)        (``.hst``)
* motion RAO       ξ = ξ̄ / L^k_i                  (``.4`` and ``.out``)
* mean drift       F = F̄ ρ g L^(1+k_i)            (``.out``, per squared amplitude)

Generalized modes (mode 7, 8 … of a body, WAMIT User Manual v7 ch. 8) are normalized
like the translational modes (k = 0): their amplitude is a length. The corpus holds no
generalized-mode run with ULEN ≠ 1, so that exponent could not be checked on data.

Time dependence is Re{X e^{iωt}}, as in cummins. Wave heading β is the direction of
propagation from +x (0 = following seas), as in cummins. Axes are x forward, y to port,
z up; moments are about the body origin (XBODY, YBODY, ZBODY), which cummins records
as the ``reference_point`` in global coordinates (origin on the mean free surface).

Mass properties (→ ``inertia_matrix``) come from the ``.frc`` (form 2: IMASS as given;
form 1: VCG and radii of gyration) or the ``.out`` header, I_ij = m r_ij |r_ij| with
m = ρ∇ (WAMIT User Manual v7, §4.3 and §3.4): see :mod:`cummins.io.wamit.mass`.

WAMIT does not write the water density in its numeric files (version 7 not even in
the ``.out``): ρ comes from the ``.out`` (version 6), else from the ``.frc``, else
from ``rho=``, else 1025 kg/m³, and the dataset's ``history`` says which.

Modules: :mod:`~cummins.io.wamit.run` (a run assembled: :func:`read_wamit`,
:func:`read_wamit_run`), :mod:`~cummins.io.wamit.out` (the ``.out`` alone:
:func:`read_wamit_out`), :mod:`~cummins.io.wamit.out_header` (the ``.out`` header),
:mod:`~cummins.io.wamit.numeric` (``.1``, ``.3``/``.4``, ``.hst``),
:mod:`~cummins.io.wamit.frc` (``.frc`` forms 1 and 2), :mod:`~cummins.io.wamit.input_files`
(``.cfg``, ``.pot``, ``.mmx``), :mod:`~cummins.io.wamit.modes` (modes per body),
:mod:`~cummins.io.wamit.mass` (inertia and external matrices, body points),
:mod:`~cummins.io.wamit.settings` (:class:`RunSettings`), :mod:`~cummins.io.wamit.detect`
(detection by content, sibling files), :mod:`~cummins.io.wamit.text` (line-level reading).
"""

from __future__ import annotations

from cummins.io.wamit.detect import is_out_file as is_out_file
from cummins.io.wamit.detect import numeric_kind as numeric_kind
from cummins.io.wamit.detect import sniff, sniff_dir
from cummins.io.wamit.modes import MEMORY_LIMIT as MEMORY_LIMIT
from cummins.io.wamit.numeric import FIRST_COLUMNS as FIRST_COLUMNS
from cummins.io.wamit.numeric import _parse_dot1 as _parse_dot1
from cummins.io.wamit.numeric import _read_hst as _read_hst
from cummins.io.wamit.numeric import _read_wave_file as _read_wave_file
from cummins.io.wamit.out import read_wamit_out
from cummins.io.wamit.run import read_wamit
from cummins.io.wamit.run import read_wamit_run as read_wamit_run
from cummins.io.wamit.settings import RunSettings as RunSettings
from cummins.io.wamit.text import MAX_ABS_VALUE as MAX_ABS_VALUE
from cummins.io.wamit.text import _read_text as _read_text

__all__ = ["read_wamit", "read_wamit_out", "sniff", "sniff_dir"]
