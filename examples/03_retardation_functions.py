"""
03 · Retardation functions K(t) and the infinite-frequency added mass
=====================================================================

K(t) = (2/π) ∫ B(ω) cos(ωt) dω (Cummins (1962)) is integrated exactly for the
piecewise-linear damping, with B(0) = 0 and a fitted tail beyond the last frequency.
A∞ is the solver's row, or Ogilvie's relation (Ogilvie (1964)) evaluated at every
frequency and combined by the median.
"""

# %%
import cummins
from cummins.plots import plot_added_mass_inf, plot_retardation
from cummins.radiation.retardation import added_mass_inf_per_frequency

ds = cummins.demo_dataset()
clean, _ = cummins.repair.remove_suspect_frequencies(ds, above_first=True)
k = cummins.retardation_function(clean)
print(k.dims, k.sizes["time"], "times to", float(k.time[-1]), "s")

# %%
# Each panel ends a little after K stays within 1 % of its peak: the memory of a ship
# lasts seconds to tens of seconds.
fig = plot_retardation(k)

# %%
# Ogilvie's A∞ at every frequency against WAMIT's ω = ∞ row: the spread says how far the
# data are consistent (Kramers–Kronig) with themselves.
estimate = cummins.added_mass_inf(clean.drop_vars("added_mass_inf"))
per_frequency = added_mass_inf_per_frequency(clean)
fig_inf = plot_added_mass_inf(per_frequency, estimate, clean, ["Heave", "Pitch"])
print(estimate.sel(influenced_dof="Heave", radiating_dof="Heave").values, estimate.attrs["method"])
