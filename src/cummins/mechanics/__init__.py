"""Multi-body mechanics: bodies joined by joints, power take-offs, body coupling.

=================== =====================================================================
module              concept
=================== =====================================================================
``bodies``          the bodies of a dataset, their reference points, the motion of a point
``joints``          :class:`Joint`: fixed, translational, revolute, planar, as rows of G ξ = 0
``pto``             :class:`PTO`: a linear spring-damper on a relative motion; its outputs
``constraints``     ξ = T q, the null space of G (coordinate partitioning); inertia check
``preload``         the stiffness of the static loads the joints carry (ρ∇ ≠ m)
``coupling``        :func:`without_body_coupling` (WEC-Sim's default)
``system``          :class:`MechanicalSystem` and :func:`assemble`
=================== =====================================================================

See ``docs/wec.md``.
"""

from typing import TYPE_CHECKING

from cummins._lazy import lazy_attributes

#: Where each public name lives; imported on first use (PEP 562), so that a command's
#: options (``cli/system_options``) can name the joint kinds without importing xarray.
_LAZY = {
    "GROUND": "bodies",
    "BodyFrame": "bodies",
    "body_frame": "bodies",
    "null_space_basis": "constraints",
    "without_body_coupling": "coupling",
    "JOINT_KINDS": "joints",
    "Joint": "joints",
    "joint_rows": "joints",
    "Preload": "preload",
    "preload_stiffness": "preload",
    "PTO": "pto",
    "PTOLine": "pto",
    "pto_frequency_response": "pto",
    "pto_matrices": "pto",
    "pto_time_series": "pto",
    "Assembly": "system",
    "MechanicalSystem": "system",
    "assemble": "system",
    "system_from_mapping": "system",
}

if TYPE_CHECKING:  # pragma: no cover
    from cummins.mechanics.bodies import GROUND, BodyFrame, body_frame
    from cummins.mechanics.constraints import null_space_basis
    from cummins.mechanics.coupling import without_body_coupling
    from cummins.mechanics.joints import JOINT_KINDS, Joint, joint_rows
    from cummins.mechanics.preload import Preload, preload_stiffness
    from cummins.mechanics.pto import (
        PTO,
        PTOLine,
        pto_frequency_response,
        pto_matrices,
        pto_time_series,
    )
    from cummins.mechanics.system import (
        Assembly,
        MechanicalSystem,
        assemble,
        system_from_mapping,
    )

__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, globals())


__all__ = [
    "GROUND",
    "JOINT_KINDS",
    "PTO",
    "Assembly",
    "BodyFrame",
    "Joint",
    "MechanicalSystem",
    "PTOLine",
    "Preload",
    "assemble",
    "body_frame",
    "joint_rows",
    "null_space_basis",
    "preload_stiffness",
    "pto_frequency_response",
    "pto_matrices",
    "pto_time_series",
    "system_from_mapping",
    "without_body_coupling",
]
