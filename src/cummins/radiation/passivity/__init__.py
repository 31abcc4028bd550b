"""Passivity of radiation models: the exact test and its enforcement (Unneland (2007) §3.2).

The map from the body velocities ξ̇ to the memory force μ is passive:
K(jω) + K(jω)ᴴ = 2 B(ω) ⪰ 0 for all ω (Unneland (2007) Prop. 3.4, eq. 3.24; the MIMO criterion
λ_min[K(jω) + Kᵀ(−jω)] ≥ 0, eq. 3.13). A model that is not can feed energy into a
simulation. Positive-real diagonal terms do not make the MIMO model passive: the
couplings must not outweigh them anywhere.

**Test** (:func:`passivity_test`, in :mod:`cummins.radiation.passivity.check`): the
frequencies where an eigenvalue of Φ(jω) = K(jω) + Kᵀ(−jω) crosses zero, as the
imaginary-axis zeros of Φ(s) from its Rosenbrock pencil (no (D + Dᵀ)⁻¹ needed, D = 0),
the sign of λ_min between them, the limits ω → 0 and ω → ∞, and a dense sweep
(:func:`passivity_sweep`) as a safeguard.

**Enforcement** (:func:`enforce_passivity`, in :mod:`cummins.radiation.passivity.enforcement`):
the residues of the coupling models are perturbed, poles and K(0) = 0 kept, by the smallest
change in the data-weighted least-squares sense subject to the linearised constraints
(Lawson & Hanson's LDP through NNLS), repeated until the test passes;
:func:`augment_for_passivity` adds poles where residues alone cannot do it.

The public names of both modules are importable from here.
"""

from __future__ import annotations

from cummins.radiation.passivity.check import ANTISYMMETRY_TOLERANCE as ANTISYMMETRY_TOLERANCE
from cummins.radiation.passivity.check import AXIS_TOLERANCE as AXIS_TOLERANCE
from cummins.radiation.passivity.check import ORIGIN_TOLERANCE as ORIGIN_TOLERANCE
from cummins.radiation.passivity.check import PASSIVITY_TOLERANCE as PASSIVITY_TOLERANCE
from cummins.radiation.passivity.check import SAME_CROSSING as SAME_CROSSING
from cummins.radiation.passivity.check import PassivityReport as PassivityReport
from cummins.radiation.passivity.check import PassivitySweep as PassivitySweep
from cummins.radiation.passivity.check import ViolationBand as ViolationBand
from cummins.radiation.passivity.check import band_points as band_points
from cummins.radiation.passivity.check import default_sweep as default_sweep
from cummins.radiation.passivity.check import dof_scaling as dof_scaling
from cummins.radiation.passivity.check import imaginary_axis_zeros as imaginary_axis_zeros
from cummins.radiation.passivity.check import is_passive as is_passive
from cummins.radiation.passivity.check import midpoint as midpoint
from cummins.radiation.passivity.check import passivity_sweep as passivity_sweep
from cummins.radiation.passivity.check import passivity_test as passivity_test
from cummins.radiation.passivity.enforcement import ENFORCEMENT_MARGIN as ENFORCEMENT_MARGIN
from cummins.radiation.passivity.enforcement import KERNEL_WEIGHT as KERNEL_WEIGHT
from cummins.radiation.passivity.enforcement import POINTS_PER_BAND as POINTS_PER_BAND
from cummins.radiation.passivity.enforcement import PassivityEnforcement as PassivityEnforcement
from cummins.radiation.passivity.enforcement import augment_for_passivity as augment_for_passivity
from cummins.radiation.passivity.enforcement import (
    constrained_least_squares as constrained_least_squares,
)
from cummins.radiation.passivity.enforcement import enforce_passivity as enforce_passivity
from cummins.radiation.passivity.enforcement import fit_range_grid as fit_range_grid
from cummins.radiation.passivity.enforcement import (
    least_distance as least_distance,
)
from cummins.radiation.passivity.enforcement import (
    least_distance_multipliers as least_distance_multipliers,
)
