"""Multi-body mechanics: bodies joined by joints, power take-offs, body coupling.

=================== =====================================================================
module              concept
=================== =====================================================================
``bodies``          the bodies of a dataset, their reference points, the motion of a point
``joints``          :class:`Joint`: fixed, translational, revolute, planar, as rows of G ξ = 0
``pto``             :class:`PTO`: a linear spring-damper on a relative motion; its outputs
``constraints``     ξ = T q, the null space of G (coordinate partitioning); inertia check
``coupling``        :func:`without_body_coupling` (WEC-Sim's default)
``system``          :class:`MechanicalSystem` and :func:`assemble`
=================== =====================================================================

See ``docs/wec.md``.
"""

from cummins.mechanics.bodies import GROUND, BodyFrame, body_frame
from cummins.mechanics.constraints import null_space_basis
from cummins.mechanics.coupling import without_body_coupling
from cummins.mechanics.joints import JOINT_KINDS, Joint, joint_rows
from cummins.mechanics.pto import (
    PTO,
    PTOLine,
    pto_frequency_response,
    pto_matrices,
    pto_time_series,
)
from cummins.mechanics.system import Assembly, MechanicalSystem, assemble, system_from_mapping

__all__ = [
    "GROUND",
    "JOINT_KINDS",
    "PTO",
    "Assembly",
    "BodyFrame",
    "Joint",
    "MechanicalSystem",
    "PTOLine",
    "assemble",
    "body_frame",
    "joint_rows",
    "null_space_basis",
    "pto_frequency_response",
    "pto_matrices",
    "pto_time_series",
    "system_from_mapping",
    "without_body_coupling",
]
