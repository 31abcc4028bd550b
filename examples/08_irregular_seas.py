"""
08 · The Cummins equation in an irregular sea
=============================================

(M_RB + A∞) ξ̈ + B_v ξ̇ + μ + C ξ = τ with the fluid memory μ from the state-space model,
exactly discretised: half an hour of 6-DOF motions in about a second, checked against
the frequency domain of the same model (Cummins (1962)).
"""

# %%
import numpy as np

import cummins
from cummins.plots import plot_response_spectra, plot_time_series
from cummins.seakeeping.waves import irregular_waves, wave_spectrum
from cummins.timedomain.simulate import component_motions

ds = cummins.demo_dataset()
model = cummins.fit_radiation(ds)
vessel = cummins.vessel_from_hydrodb(ds, model, viscous_damping=[1e6, 1e6, 0, 5e8, 0, 1e10])
sea = irregular_waves(
    wave_spectrum("jonswap", 4.0, 10.0),
    duration=1800,
    n_components=200,
    direction=np.radians(150.0),
    seed=1,
    data=ds,
)
run = cummins.simulate_waves(vessel, ds, sea, duration=1800, dt=0.1)
run.attrs["sea"] = "JONSWAP Hs 4 m, Tp 10 s, waves from 150°"
print(
    "heave std",
    float(run.motion.sel(dof="Heave").std()),
    "m; energy balance error",
    run.attrs["energy_relative_residual"],
)

# %%
# The last ten minutes: roll and pitch in degrees.
fig = plot_time_series(run)

# %%
# The response spectra of the run (Welch) against the frequency domain of the same model:
# each wave component's steady response.
x = component_motions(vessel, ds, sea)
order = np.argsort(sea.omega)
density = 0.5 * np.abs(x[order]) ** 2 / sea.bin_width
fig_spectra = plot_response_spectra(run, {"frequency domain": (sea.omega[order], density)})
