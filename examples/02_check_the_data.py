"""
02 · Check the data before using them
=====================================

``cummins.check`` tests what a physically usable database needs — symmetric A and B,
damping positive semi-definite at every frequency, A∞ consistent with A(ω) and B(ω),
inertia and restoring — and names the DOF and frequency at fault.
"""

# %%
import numpy as np
from matplotlib.figure import Figure

import cummins

ds = cummins.demo_dataset()
report = cummins.check(ds)
print("usable:", report.ok)
for finding in list(report)[:6]:
    print(f"{finding.severity}: {finding.message}")

# %%
# The suspect frequencies — spikes and negative damping, the irregular frequencies of a
# panel method — found on each DOF's own curves.
clean, suspects = cummins.repair.remove_suspect_frequencies(ds, above_first=True)
for s in suspects[:5]:
    print(f"{s.omega:.3f} rad/s: {s.quantity}, {s.reason}")

# %%
# The heave damping with the frequencies left out marked.
w = ds.omega.values
b = ds.radiation_damping.sel(influenced_dof="Heave", radiating_dof="Heave").values
left_out = np.isin(w, [s.omega for s in suspects])
fig = Figure(figsize=(8, 3.5), layout="constrained")
ax = fig.subplots()
ax.plot(w, b, ".-", color="C1", label="B heave (data)")
ax.plot(w[left_out], b[left_out], "x", color="C3", ms=9, label="suspect: left out")
ax.axhline(0.0, color="0.6", lw=0.8)
ax.set_xlabel("ω [rad/s]")
ax.set_ylabel("B [kg/s]")
ax.legend()
ax.grid(alpha=0.3)
