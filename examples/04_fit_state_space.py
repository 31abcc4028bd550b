"""
04 · Stable, passive state-space models of the fluid memory
===========================================================

``cummins.fit_radiation`` models every significant coupling. The DOFs that radiate into
each other (surge–heave–pitch and sway–roll–yaw of a ship) form a block whose couplings
share their poles, fitted by vector fitting of A(ω) − jB(ω)/ω (Gustavsen & Semlyen
(1999)) until the R² of A and B and the motion RAOs reach their targets, then made
passive (Unneland (2007)).
"""

# %%
import tempfile
from pathlib import Path

import cummins
from cummins.fit_figures import fit_figures

ds = cummins.demo_dataset()
model = cummins.fit_radiation(ds)
print("states:", model.total_order, "stable:", model.is_stable())
for block in model.blocks:
    print("-".join(model.dofs[d] for d in block.dofs), block.order, "states")
heave = model.coupling("Heave", "Heave")
print(
    "heave: R² of A",
    round(heave.metrics["r2_added_mass"], 4),
    "of B",
    round(heave.metrics["r2_damping"], 4),
)

# %%
# The fit of heave and its coupling with pitch against the data: A(ω), B(ω), the magnitude of K(jω)
# and K(t). Open circles are the irregular frequencies the fit left out.
fig = next(figure for name, figure in fit_figures(model, ds) if name == "fit_Heave.png")

# %%
# The model is a public NetCDF file (A, B, C, D, A∞, the blocks and their metrics).
folder = Path(tempfile.mkdtemp())
model.save(folder / "tanker_model.nc")
same = cummins.RadiationModel.load(folder / "tanker_model.nc")
print(same.total_order, same.A.shape)
