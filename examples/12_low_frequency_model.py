"""
12 · The low-frequency manoeuvring model
========================================

The constant-coefficient model (M_RB + M_A) ν̇ + D ν + G η = τ of Ross, Perez & Fossen
(2006): surge, sway and yaw at ω = 0, heave, roll and pitch at their natural frequency,
where ω₀²(M_RB + A(ω₀)) = C is solved iteratively.
"""

# %%
import cummins
from cummins.plots import plot_lf_model
from cummins.timedomain.lfmodel import lf_model_from_frequency_data

ds = cummins.demo_dataset()
lf = lf_model_from_frequency_data(ds)
for dof in ("Heave", "Roll", "Pitch"):
    print(dof, "ω0 =", round(float(lf.frequencies[lf.index(dof)]), 4), "rad/s")

# %%
# The chosen values marked on A(ω) and B(ω) (the paper's Figs. 1–2).
fig = plot_lf_model(ds, lf, ["Surge", "Heave", "Roll"])
