"""Environmental and external loads of the nonlinear 6-DOF DP/manoeuvring model.

The loads of Smogeli et al. (2004) §4–5 (the DP model of the Marine Systems Simulator),
each a small frozen dataclass with a ``name`` and a method

    force(t, eta, nu) -> ndarray (6,)

giving the generalized force in the b-frame about the origin O, in N and N·m, at time
``t`` (s), pose η = (N, E, D, φ, θ, ψ) (m, rad) and body velocity ν = (u, v, w, p, q, r)
(m/s, rad/s). Anything with that signature is a :class:`Load` (a ``Protocol``), so users
can add their own (moorings, risers, a thruster model) or wrap a function in
:class:`FunctionLoad`. The simulator calls ``force`` at every Runge–Kutta stage:
everything that can be prepared (interpolation tables, wave numbers, strip weights) is
prepared once when the load is built, and a call costs O(number of wave components).

Conventions
-----------
* b-frame: x forward, y to starboard, z down, origin O: the reference point of the
  hydrodynamic data (``reference_point`` of the ``HydroDB``). n-frame: north-east-down.
* Angles in the n-frame are measured clockwise (seen from above) from North, towards
  East, in rad:

  - waves: β_j is the direction the component **travels to** (as
    :class:`cummins.seakeeping.waves.WaveComponents`). The data are looked up at the relative
    direction β_j − ψ, the ``wave_direction`` of a z-down ``HydroDB`` (from body +x
    towards starboard; π: head seas);
  - current: β_c is the direction the current **flows to** (Smogeli et al. (2004) eq. 40);
  - wind: β_w is the direction the wind **comes from** (meteorological convention): a
    ship heading North (ψ = 0) in a wind from β_w = 0 has a head wind, which pushes it
    aft. The relative wind angle γ_rw = β_w − ψ of Smogeli et al. (2004) §5.5 (for a vessel at rest)
    is then the angle, from the bow towards starboard, the wind comes from.

* Time convention of the wave data x(t) = Re{X e^{iωt}}; wave elevation at the n-frame
  point (N, E): ζ = Σ_j ζ_j cos(ω_j t − k_j (N cos β_j + E sin β_j) + φ_j).

Loads
-----
=============================  ==============================================  =========
class                          model                                           Smogeli et al. (2004)
=============================  ==============================================  =========
:class:`Current`               current velocity, relative velocity (no load)   eqs. 40, 49
:class:`FirstOrderWaveLoad`    first-order wave excitation                     eq. 46
:class:`WaveDriftLoad`         mean and slowly varying drift (Newman)          eqs. 47–48
:class:`SecondOrderWaveLoad`   mean and slow drift (Newman or QTF), sum freq.  eqs. 46–47
:class:`SurgeResistance`       ITTC 1957 friction line resistance              eqs. 50–51, 54
:class:`CrossFlowDrag`         cross-flow drag in sway and yaw (strips)        eqs. 52–54
:class:`WindLoad`              wind with gusts (Harris, NORSOK)                eq. 55, §4.2
:class:`PointLoad`             force/moment at a point (crane load)            eq. 45
:class:`ConstantLoad`          constant generalized force
:class:`FunctionLoad`          any user function f(t, η, ν)
=============================  ==============================================  =========

Modules
-------
* :mod:`~cummins.timedomain.loads.base`: the :class:`Load` protocol and shared helpers;
* :mod:`~cummins.timedomain.loads.current`: :class:`Current` and the relative velocity;
* :mod:`~cummins.timedomain.loads.waves`: first-order wave excitation and wave drift;
* :mod:`~cummins.timedomain.loads.second_order`: the second-order wave force from QTFs
  (:mod:`~cummins.timedomain.loads.quadratic_form`: its factorised double sum;
  :mod:`~cummins.timedomain.loads.relative_heading`: at the vessel's instantaneous
  relative heading);
* :mod:`~cummins.timedomain.loads.viscous`: surge resistance and cross-flow drag;
* :mod:`~cummins.timedomain.loads.wind`: gust spectra, wind, wind coefficients, wind load;
* :mod:`~cummins.timedomain.loads.external`: point, constant and function loads, and sums.

Every name is importable from :mod:`cummins.timedomain.loads` itself.
"""

from __future__ import annotations

from cummins.timedomain.loads.base import Load
from cummins.timedomain.loads.current import Current
from cummins.timedomain.loads.external import (
    ConstantLoad,
    FunctionLoad,
    PointLoad,
    load_forces,
    total_force,
)
from cummins.timedomain.loads.second_order import SecondOrderWaveLoad, second_order_force
from cummins.timedomain.loads.viscous import (
    HOERNER_DRAG,
    CrossFlowDrag,
    SurgeResistance,
    denny_mumford_wetted_surface,
    hoerner_drag_coefficient,
    ittc_friction,
)
from cummins.timedomain.loads.viscous import NU_WATER as NU_WATER
from cummins.timedomain.loads.viscous import RHO_WATER as RHO_WATER
from cummins.timedomain.loads.waves import FirstOrderWaveLoad, WaveDriftLoad
from cummins.timedomain.loads.wind import RHO_AIR as RHO_AIR
from cummins.timedomain.loads.wind import (
    WIND_SPECTRA,
    ParametricWindCoefficients,
    Wind,
    WindCoefficients,
    WindGust,
    WindLoad,
    harris,
    harris_variance,
    norsok,
    norsok_variance,
    wind_gust,
)

__all__ = [
    "HOERNER_DRAG",
    "WIND_SPECTRA",
    "ConstantLoad",
    "CrossFlowDrag",
    "Current",
    "FirstOrderWaveLoad",
    "FunctionLoad",
    "Load",
    "ParametricWindCoefficients",
    "PointLoad",
    "SecondOrderWaveLoad",
    "SurgeResistance",
    "WaveDriftLoad",
    "Wind",
    "WindCoefficients",
    "WindGust",
    "WindLoad",
    "denny_mumford_wetted_surface",
    "harris",
    "harris_variance",
    "hoerner_drag_coefficient",
    "ittc_friction",
    "load_forces",
    "norsok",
    "norsok_variance",
    "second_order_force",
    "total_force",
    "wind_gust",
]
