"""
09 · Forward speed: the S-175 meets the waves at the encounter frequency
========================================================================

At a forward speed U the ship meets the waves at ω_e = ω − kU cos β. The RAOs of the
S-175 (ShipX/VERES at five speeds, bundled as an MSS struct) are solved with A and B at
ω_e and the excitation at the wave frequency ω (Hjulstad (2004)).
"""

# %%
import numpy as np
from matplotlib.figure import Figure

import cummins
from cummins.radiation.speed import encounter_frequency
from cummins.seakeeping.frequency_domain import motion_rao

data = cummins.read(cummins.demo_files().parent / "s175" / "s175.mat")
print("speeds", data.forward_speed.values, "m/s")
print("head seas at 5 m/s: ω = 0.6 rad/s is met at", round(encounter_frequency(0.6, 5.0, np.pi), 3))

# %%
# Heave and pitch RAOs in head seas at every speed.
fig = Figure(figsize=(10, 3.8), layout="constrained")
axes = fig.subplots(1, 2)
for k, speed in enumerate(data.forward_speed.values):
    ds = data.isel(forward_speed=k)
    rao = motion_rao(ds, wave_direction=[np.pi]).isel(wave_direction=0)
    for ax, dof in zip(axes, ("Heave", "Pitch"), strict=True):
        scale = 1.0 if dof == "Heave" else np.degrees(1.0)
        ax.plot(rao.omega, scale * np.abs(rao.sel(dof=dof)), label=f"U = {speed:.1f} m/s")
axes[0].set_ylabel("|RAO| heave [m/m]")
axes[1].set_ylabel("|RAO| pitch [deg/m]")
for ax in axes:
    ax.set_xlabel("wave frequency ω [rad/s]")
    ax.grid(alpha=0.3)
axes[1].legend(fontsize="small")
