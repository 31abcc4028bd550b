"""
06 · Fewer states: balanced truncation judged by the motions
============================================================

``reduce_to_motion_tolerance`` asks for the fewest states whose motion RAOs stay within a
fraction of each DOF's peak of the data's: each common-pole block is truncated in its
balanced coordinates (Unneland (2007) ch. 5), with K(0) = 0 and passivity restored in its
own states.
"""

# %%
import numpy as np
from matplotlib.figure import Figure

import cummins
from cummins.radiation.reduce import reduce_radiation_model, reduce_to_motion_tolerance

ds = cummins.demo_dataset()
model = cummins.fit_radiation(ds)
small = reduce_to_motion_tolerance(model, ds, 0.01)
print(
    f"{model.total_order} → {small.total_order} states, motion-RAO error "
    f"{small.attrs['motion_error']:.2%} of the peak (unreduced "
    f"{small.attrs['motion_error_unreduced']:.2%})"
)
tight = reduce_radiation_model(model, tol=0.02, data=ds)
print("tol 0.02:", tight.total_order, "states")

# %%
# Heave's K(jω): the data, the fitted model and the reduced ones.
w = np.geomspace(0.05, 4.0, 300)
fig = Figure(figsize=(8, 3.8), layout="constrained")
ax = fig.subplots()
data = ds.radiation_damping.sel(influenced_dof="Heave", radiating_dof="Heave")
ax.plot(data.omega, data, "o", ms=3, color="0.3", label="data B(ω)")
for name, m in (
    (f"fit, {model.total_order} states", model),
    (f"motion tol 1 %, {small.total_order}", small),
    (f"tol 0.02, {tight.total_order}", tight),
):
    ax.plot(
        w,
        m.frequency_response(w).sel(influenced_dof="Heave", radiating_dof="Heave").real,
        label=name,
    )
ax.set_xlim(0, 4)
ax.set_xlabel("ω [rad/s]")
ax.set_ylabel("B heave [kg/s]")
ax.legend()
ax.grid(alpha=0.3)
