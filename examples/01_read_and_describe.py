"""
01 · Read solver output and look at it
======================================

``cummins.read`` detects the format from the content (WAMIT here: ``tanker.1`` with its
``.3``, ``.hst``, ``.frc`` and ``.out`` beside it) and returns one canonical, dimensional
``xarray.Dataset`` with Capytaine's names, whatever the solver.
"""

# %%
import cummins
from cummins.hydrodb import describe
from cummins.plots import plot_added_mass_damping, plot_excitation

ds = cummins.read(cummins.demo_files() / "tanker.1")
info = describe(ds)
print(info["source_format"], info["n_omega"], "frequencies,", info["dofs"])
print("rho =", ds.attrs["rho"], "kg/m³; g =", ds.attrs["g"], "m/s²")
print(ds.added_mass.sel(influenced_dof="Heave", radiating_dof="Heave").values[:3])

# %%
# Where each value came from is kept in ``history``: the density and gravity of the
# nondimensional WAMIT files, the inertia from the ``.frc`` file.
print(ds.attrs["history"])

# %%
# The diagonal added mass A(ω) and damping B(ω), with A(0) and A(∞) where the solver
# computed them; damping below zero (crosses) marks irregular frequencies.
fig = plot_added_mass_damping(ds, ["Heave", "Roll", "Pitch"])

# %%
# The first-order wave excitation per metre of wave amplitude, at five headings
# (0° = following seas, 180° = head seas).
fig_excitation = plot_excitation(ds, ["Surge", "Heave", "Pitch"], headings_deg=[0, 90, 180])
