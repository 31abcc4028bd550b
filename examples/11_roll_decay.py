"""
11 · Roll damping from a free decay
===================================

A roll decay of the tanker simulated with the fitted fluid memory and a known viscous
roll damping, then analysed as a model-basin record would be: the decrement of the
half cycles and a fit of φ̈ + p₁φ̇ + p₂|φ̇|φ̇ + ω₀²φ = 0 (de Haan (2022)).
"""

# %%
import numpy as np

import cummins
from cummins.plots import plot_roll_decay
from cummins.sysid import roll_decay
from cummins.timedomain.simulate import simulate

ds = cummins.demo_dataset()
model = cummins.fit_radiation(ds)
vessel = cummins.vessel_from_hydrodb(ds, model, viscous_damping=[1e6, 1e6, 0, 5e8, 0, 1e10])
t = np.arange(0.0, 240.0, 0.1)
state = np.zeros(vessel.n_states)
state[vessel.dofs.index("Roll")] = np.radians(10.0)  # released from 10° of heel
run = simulate(vessel, t, np.zeros((t.size, len(vessel.dofs))), initial_state=state)
phi = run.motion.sel(dof="Roll").values

# %%
decay = roll_decay(t, phi)
print(f"p1 = {decay['p1']:.4f} 1/s, p2 = {decay['p2']:.4f} 1/rad, ω0 = {decay['omega0']:.4f} rad/s")
print(decay["p2_note"])  # the damping here is linear: p2 is judged by its 95 % interval
fig = plot_roll_decay(t, phi, decay)
