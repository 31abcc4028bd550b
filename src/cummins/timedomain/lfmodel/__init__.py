"""Low-frequency (manoeuvring) model with constant coefficients (Ross, Perez & Fossen, 2006).

The Cummins equation (Ross, Perez & Fossen (2006) eq. 11) has a frequency-independent
inertia A∞ and a fluid memory ∫K(t − τ) ξ̇(τ) dτ. A manoeuvring or dynamic-positioning
model (eqs. 16–17) replaces the memory by constant coefficients,

    (M_RB + M_A) ν̇ + D ν + G η = τ,

and §3.1 of the paper (Definition 1) says *at which frequency* to take them:

* **Zero-frequency model, surge/sway/yaw** (mass–damper DOFs, little oscillation while
  manoeuvring): the classical hydrodynamic derivatives, the ω → 0 limits of the
  Ogilvie relations (eqs. 8–9),

  M_A = A(0) = A∞ − ∫₀^∞ τ K(τ) dτ                                 (eq. 22, 25)
  D   = B(0) + B_v(0) = ∫₀^∞ K(τ) dτ + β                          (eq. 23, 26)

  At zero speed in deep water B(0) = ∫K dτ = 0: the potential part of the linear
  surge/sway/yaw derivative vanishes and D is the viscous β alone (eq. 26).
* **Natural-frequency model, heave/roll/pitch** (mass–spring–damper DOFs, which move
  at their natural frequency ω₀): ω₀ solves

  ω₀² (M_RB,ii + A_ii(ω₀)) − C_ii = 0                               (eq. 24)

  iteratively, and the coefficients are taken there (eqs. 29–30 for roll),

  M_A = A(ω₀) = A∞ − (1/ω₀) ∫₀^∞ K(τ) sin(ω₀τ) dτ,
  D   = B(ω₀) + B_v(ω₀) = ∫₀^∞ (K(τ) + K_v(τ)) cos(ω₀τ) dτ.

Two routes compute the same numbers and must agree: :func:`lf_model_from_retardation`
integrates K(t) (exactly, for the piecewise-linear K through its samples; the only
error is K's truncation at its last time), and :func:`lf_model_from_frequency_data`
interpolates A(ω), B(ω) (cubic spline) and takes A(0) from the solver's ω = 0 row or a
low-frequency extrapolation. The paper does not say at which frequency a coupling between
DOFs of different frequencies is taken: cummins takes entry (i, j) at min(ω_i, ω_j)
(symmetric, passive; the couplings of the zero-frequency DOFs are their derivatives), or
on request at ω_j, the frequency of the radiating DOF.

Viscous damping B_v(ω) (§3 of the paper, the matrix after eq. 21): :class:`ExponentialDamping`
β e^{−αω} (Ross & Fossen (2005); intended for surge, sway and yaw) and, for roll, where the
paper uses Ikeda et al. (1976), :class:`CriticalDampingFraction` — **a proxy, not Ikeda's
method**: B_v = 2ζ ω₀ (M_RB,ii + A_ii(ω₀)) = 2ζ √(C_ii (M_RB,ii + A_ii(ω₀))), a fraction ζ
of critical damping at the natural frequency (the component-wise Ikeda estimate needs the
hull form, bilge keels and roll amplitude, which a hydrodynamic database does not hold).
Any callable B_v(ω) (a user's Ikeda curve) is accepted too, and ``"data"`` takes the
database's own frequency-dependent ``additional_damping`` (e.g. VERES's viscous roll
damping) at the DOF's frequency.

:func:`compare_with_cummins` runs a free decay or a step force through the LF model and
the full Cummins vessel and reports the difference (the acceptance of issue 8).

Units: SI throughout; masses kg, kg·m, kg·m²; damping kg/s … kg·m²/s; stiffness N/m,
N, N·m/rad; frequencies rad/s.

The package's modules: :mod:`~cummins.timedomain.lfmodel.model`
(:class:`LowFrequencyModel`), :mod:`~cummins.timedomain.lfmodel.frequencies`
(Definition 1, eq. 24), :mod:`~cummins.timedomain.lfmodel.coefficients` (the two routes
to A(ω), B(ω)), :mod:`~cummins.timedomain.lfmodel.viscous` (B_v),
:mod:`~cummins.timedomain.lfmodel.builders` (the two builders) and
:mod:`~cummins.timedomain.lfmodel.compare` (:func:`compare_with_cummins`).
"""

from __future__ import annotations

from cummins.timedomain.lfmodel.builders import Couplings as Couplings
from cummins.timedomain.lfmodel.builders import (
    lf_model_from_frequency_data,
    lf_model_from_retardation,
)
from cummins.timedomain.lfmodel.coefficients import extrapolate_zero_frequency
from cummins.timedomain.lfmodel.compare import compare_with_cummins
from cummins.timedomain.lfmodel.frequencies import (
    NATURAL_FREQUENCY_DOFS,
    ZERO_FREQUENCY_DOFS,
    natural_frequency,
)
from cummins.timedomain.lfmodel.model import LowFrequencyModel
from cummins.timedomain.lfmodel.viscous import CriticalDampingFraction, ExponentialDamping
from cummins.timedomain.lfmodel.viscous import ViscousSpec as ViscousSpec

__all__ = [
    "NATURAL_FREQUENCY_DOFS",
    "ZERO_FREQUENCY_DOFS",
    "CriticalDampingFraction",
    "ExponentialDamping",
    "LowFrequencyModel",
    "compare_with_cummins",
    "extrapolate_zero_frequency",
    "lf_model_from_frequency_data",
    "lf_model_from_retardation",
    "natural_frequency",
]
