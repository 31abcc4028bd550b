"""Model-order reduction by balanced truncation (Unneland (2007) Ch. 5).

A stable continuous-time model G(s) = C (sI − A)⁻¹ B + D of order n is brought into
coordinates x̄ = T x in which two positive (semi)definite matrices M and N of the model,
transformed as T M Tᵀ and T⁻ᵀ N T⁻¹, are equal and diagonal, Σ = diag(σ₁ ≥ … ≥ σ_n)
(Unneland (2007) eq. 5.14); the reduced model keeps the r leading states,
A_r = Ā₁₁, B_r = B̄₁, C_r = C̄₁, D_r = D (eq. 5.13). The choice of (M, N) is the method:

``"lyapunov"`` (Moore (1981); Unneland (2007) §5.2.1)
    M = P and N = Q, the controllability and observability gramians
    A P + P Aᵀ + B Bᵀ = 0 (eq. 5.15), Aᵀ Q + Q A + Cᵀ C = 0 (eq. 5.16). Σ holds the Hankel
    singular values. Every truncation is stable when σ_r > σ_{r+1}, and
    ‖G − G_r‖∞ ≤ 2 Σ σ_k over the *distinct* discarded values (Glover 1984). The bound
    printed in Unneland (2007) eq. 5.22 lacks the factor 2: that is an erratum (MATLAB's
    ``imp2ss`` reports 2 Σ too), and :func:`glover_bound` has the 2.
``"riccati"`` (positive-real balancing: Desai & Pal 1984, Green 1988, Unneland (2007) §5.2.2)
    Positive-real (or phase-system) balancing. M = R_min and N = O_min, the minimal
    solutions of the positive-real (PR) Riccati equations
    A R + R Aᵀ + (R Cᵀ − B)(D + Dᵀ)⁻¹(C R − Bᵀ) = 0 (eq. 5.43) and
    Aᵀ O + O A + (O B − Cᵀ)(D + Dᵀ)⁻¹(Bᵀ O − C) = 0 (eq. 5.44).
    For a PR G, Σ ≤ I (eq. 5.47) and every truncation is PR (Def. 5.2).
``"mixed"`` (mixed-gramian balancing, Unneland (2007) §5.2.3, Theorem 5.1)
    M = P (eq. 5.83) and N = O_min (eq. 5.84): one Lyapunov and one Riccati equation.
    Every truncation of a PR G is PR: the (1, 1) block of eq. 5.84 in the balanced
    coordinates (eq. 5.97) is the dual PR Riccati equation of the truncation, solved by
    Σ₁ > 0.
``"mixed-rq"``
    The dual variant, M = R_min (eq. 5.85) and N = Q (eq. 5.86), equally PR. For SISO
    models both variants give the same transfer function; for MIMO models the (R, Q)
    reduction of G is the transpose of the (P, O) reduction of Gᵀ (eqs. 5.98–5.102), so
    a symmetric G = Gᵀ gives two reductions that are each other's transpose, and neither
    is symmetric in general (Unneland (2007) §6.3.3). Lyapunov and Riccati truncations of a
    symmetric G are symmetric.

The package, one concept a module, each importing only those above it:

* :mod:`~cummins.radiation.reduce.system`: the checks of a model and of the options, its
  frequency response and H∞ norm;
* :mod:`~cummins.radiation.reduce.gramians`: the Lyapunov and positive-real (Riccati)
  gramians, and the regularisation of a strictly proper model (D = 0);
* :mod:`~cummins.radiation.reduce.balancing`: the square-root balancing, low-frequency
  weighting, order selection and :func:`balanced_truncation`;
* :mod:`~cummins.radiation.reduce.candidates`: the truncations of one radiation coupling;
* :mod:`~cummins.radiation.reduce.modal`: a symmetric MIMO memory model in modal form with
  rank-limited residues (the parameters of the corrections of a block);
* :mod:`~cummins.radiation.reduce.blocks`: the truncations of one common-pole block, with
  K(0) = 0 and passivity restored in the truncated states;
* :mod:`~cummins.radiation.reduce.orders`: the order of every coupling (total order,
  mapping or tolerance);
* :mod:`~cummins.radiation.reduce.radiation_model`: :func:`reduce_radiation_model` and
  :func:`reduction_failures`;
* :mod:`~cummins.radiation.reduce.motions`: :func:`reduce_to_motion_tolerance`, the fewest
  states whose motion RAOs stay within a tolerance of the data's.

Radiation models
----------------
:func:`reduce_radiation_model` reduces a :class:`~cummins.radiation.model.RadiationModel`
coupling by coupling (each K_ij is a SISO model), so that the block structure, the
file formats and the symmetry K_ij = K_ji are kept: a symmetric pair is reduced once
and used twice; a model of common-pole blocks (the default fit) is reduced block by
block. See its docstring for the allocation of a total order over the couplings and for
what is recorded.
"""

# Every name of the module before the split stays importable from here.
from cummins.radiation.reduce.balancing import (  # noqa: F401
    DISTINCT_RTOL,
    RANK_RTOL,
    BalancedTruncation,
    balanced_truncation,
    glover_bound,
)
from cummins.radiation.reduce.candidates import (  # noqa: F401
    MEASURE_POINTS,
    MIN_COUPLING_ORDER,
    WEIGHT_CANDIDATES,
)
from cummins.radiation.reduce.gramians import (  # noqa: F401
    DEFAULT_REGULARIZATION,
    PSD_RTOL,
    RICCATI_RTOL,
    hankel_singular_values,
    lyapunov_gramians,
    positive_real_gramians,
)
from cummins.radiation.reduce.motions import (  # noqa: F401
    MOTION_SEARCH,
    reduce_to_motion_tolerance,
)
from cummins.radiation.reduce.radiation_model import (  # noqa: F401
    DATA_METRICS,
    FAILED_R2,
    reduce_radiation_model,
    reduction_failures,
)
from cummins.radiation.reduce.system import (  # noqa: F401
    MAX_EIGENVECTOR_CONDITION,
    METHODS,
    PR_METHODS,
    SWEEP_POINTS_PER_DECADE,
    frequency_response,
    hinf_norm,
)

__all__ = [
    "DEFAULT_REGULARIZATION",
    "METHODS",
    "BalancedTruncation",
    "balanced_truncation",
    "frequency_response",
    "glover_bound",
    "hankel_singular_values",
    "hinf_norm",
    "lyapunov_gramians",
    "positive_real_gramians",
    "reduce_radiation_model",
    "reduce_to_motion_tolerance",
]
