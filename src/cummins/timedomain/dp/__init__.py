"""Dynamic positioning (DP): wave filter, nonlinear PID and thrust allocation.

A small, self-contained station-keeping controller for the nonlinear DP simulation
(Smogeli et al., 2004): enough to hold a vessel on position and
heading against slowly varying environmental loads while ignoring its wave-frequency (WF)
motion. It is a *sampled* controller: the simulator calls :meth:`DPController.update` once
per time step and holds the returned generalized force until the next call.

The three parts, after Fossen (2021), *Handbook of Marine Craft Hydrodynamics and Motion
Control*, 2nd ed. (the chapters on PID control for dynamic positioning,
on wave filtering and observers, and on control allocation); chapter numbers are left out
on purpose, as they differ between editions:

1. **Wave filter** (:class:`WaveFilter`): a Butterworth low-pass on the measured north,
   east and (unwrapped) heading, discretised exactly (zero-order hold) at the controller's
   step. Its states are the low-frequency (LF) pose *and its time derivatives*, so it
   also gives the LF velocity without numerical differentiation.
2. **Nonlinear PID** (:class:`DPGains`): with the n-frame error e = η̂_LF − η_d (heading
   error wrapped to (−π, π]) rotated into the b-frame,

   τ = −K_p Rᵀ(ψ̂) e − K_d ν̂ − K_i Rᵀ(ψ̂) ∫ e dt,

   with anti-windup by clamping the integral force and by conditional integration while
   the thrusters saturate. :meth:`DPGains.from_vessel` places the linearised closed-loop
   poles.
3. **Thrust allocation** (:class:`Thrusters`): the weighted pseudo-inverse
   f = W⁻¹Bᵀ(BW⁻¹Bᵀ)⁻¹τ of the extended thrust formulation (an azimuth thruster is two
   forces, fx and fy), then saturation of each thruster, and the generalized force the
   saturated thrusters *deliver* (with the roll and pitch moments of thrusters below O).

Conventions: n-frame north-east-down; b-frame x forward, y to starboard, z down, origin O.
Pose η = (N, E, D, φ, θ, ψ) in m and rad, body velocity ν = (u, v, w, p, q, r);
generalized forces are 6-vectors in the b-frame about O, N and N·m. The 3-DOF quantities
of this module are (surge, sway, yaw) = 6-vector indices (0, 1, 5).

Examples
--------
Hold position with a typical thruster layout (gains for a 175 m ship):

>>> import numpy as np
>>> gains = DPGains.from_vessel(np.diag([2.7e7, 4.0e7, 6.0e10]), np.diag([2.7e5, 4.0e5, 6.0e8]))
>>> ctrl = DPController(gains, Thrusters.typical(175.0, 8e5), setpoint=(0.0, 0.0, 0.0))
>>> tau = ctrl.update(0.0, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0])  # 1 m north of the setpoint
>>> bool(tau[0] < 0.0)  # push back south (astern)
True

Modules: :mod:`~cummins.timedomain.dp.base` (3-DOF conventions, :class:`DPConfigError`),
:mod:`~cummins.timedomain.dp.wave_filter`, :mod:`~cummins.timedomain.dp.thrusters` and
:mod:`~cummins.timedomain.dp.controller` (gains and controller); every name is importable
from :mod:`cummins.timedomain.dp` itself.
"""

from __future__ import annotations

from cummins.timedomain.dp.base import DOF3, DPConfigError, rotation_3dof, wrap_angle
from cummins.timedomain.dp.controller import DPController, DPGains
from cummins.timedomain.dp.thrusters import Allocation, Thrusters
from cummins.timedomain.dp.thrusters import ThrusterKind as ThrusterKind
from cummins.timedomain.dp.wave_filter import WaveFilter

__all__ = [
    "DOF3",
    "Allocation",
    "DPConfigError",
    "DPController",
    "DPGains",
    "Thrusters",
    "WaveFilter",
    "rotation_3dof",
    "wrap_angle",
]
