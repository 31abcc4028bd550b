"""
07 · Motion RAOs in the frequency domain
========================================

``motion_rao`` solves [−ω²(M + A(ω)) + iω(B(ω) + B_v) + C] X = F(ω, β) at every frequency
and heading (solved, not interpolated: between the data's frequencies A, B and F are
interpolated and the equation is solved there, so a sharp roll resonance is resolved).
"""

# %%
import numpy as np

import cummins
from cummins.plots import plot_rao
from cummins.seakeeping.frequency_domain import (
    motion_rao,
    response_spectrum,
    significant_amplitude,
)
from cummins.seakeeping.waves import wave_spectrum

ds = cummins.demo_dataset()
roll_damping = [0, 0, 0, 5e8, 0, 0]  # viscous roll damping, kg m²/s
rao = motion_rao(
    ds, np.linspace(0.1, 1.6, 300), np.radians([90, 135, 180]), viscous_damping=roll_damping
)
print(rao.dims, rao.sizes)

# %%
# Roll and pitch in degrees per metre of wave amplitude; the phases unwrapped. In head
# seas (180°) sway, roll and yaw are zero by symmetry.
fig = plot_rao(rao, ["Heave", "Roll", "Pitch"])

# %%
# Significant amplitudes 2√m₀ in a JONSWAP sea of Hs 4 m, Tp 10 s from 135°.
sea = wave_spectrum("jonswap", 4.0, 10.0)
spectra = response_spectrum(rao.sel(wave_direction=np.radians(135.0)), sea)
amplitude = significant_amplitude(spectra)
for dof in ("Heave", "Roll", "Pitch"):
    value = float(amplitude.sel(dof=dof))
    print(dof, f"{np.degrees(value):.2f} deg" if dof != "Heave" else f"{value:.2f} m")
