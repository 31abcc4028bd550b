"""
10 · Dynamic positioning with a crane load
==========================================

The nonlinear 6-DOF model of the Marine Systems Simulator (Smogeli et al. (2004) eq. 56)
on the S-175 at zero speed: first-order wave forces at the instantaneous heading, the
fluid memory as the fitted state-space model, a DP controller on wave-filtered positions
and a crane load of 1000 kN 15 m to starboard from t = 30 s.
"""

# %%
import numpy as np

import cummins
from cummins.plots import plot_pose, plot_watch_circle
from cummins.seakeeping.waves import irregular_waves, wave_spectrum
from cummins.timedomain import loads
from cummins.timedomain.dp import DPController, DPGains, Thrusters
from cummins.timedomain.unified import simulate_unified, unified_vessel

data = cummins.read(cummins.demo_files().parent / "s175" / "s175.mat")
ds = data.isel(forward_speed=0)
ship = unified_vessel(ds, viscous_damping=[1e6, 1e6, 0, 0, 0, 1e10])
seaway = irregular_waves(
    wave_spectrum("jonswap", 4.0, 10.0),
    duration=120,
    n_components=50,
    direction=np.radians(135.0),
    seed=1,
    data=ds,
)
crane = loads.PointLoad(force_vector=[0, 0, 1e6], point=[0, 15, 0], frame="ned", start=30)
dp = DPController(DPGains.from_vessel(ship.mass, ship.damping), Thrusters.typical(175, 2e6))
run = simulate_unified(
    ship,
    duration=120,
    dt=0.2,
    controller=dp,
    slow_loads=[crane],
    loads=[loads.FirstOrderWaveLoad.from_hydrodb(ds, seaway)],
)
print("roll at the end", np.degrees(float(run.eta.sel(dof="Roll")[-1])), "deg")

# %%
# The pose in the north-east-down frame; the dashed line marks the crane load.
fig = plot_pose(run, mark=30.0)

# %%
# The track of the origin and the watch circle.
fig_circle = plot_watch_circle(run)
