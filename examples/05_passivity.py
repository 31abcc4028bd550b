"""
05 · Passivity: the model never creates energy
==============================================

A radiation model must be passive: K(jω) + K(jω)ᴴ ⪰ 0 at every frequency. cummins tests it
exactly, from the imaginary-axis zeros of K(s) + Kᵀ(−s), not on a grid, and the limits
ω → 0 and ω → ∞ included. Here the default (passive) fit of the tanker against a
per-coupling realization that is not made passive as a MIMO model.
"""

# %%
import numpy as np
from matplotlib.figure import Figure

import cummins
from cummins.radiation.passivity import passivity_sweep, passivity_test

ds = cummins.demo_dataset()
passive = cummins.fit_radiation(ds)
era = cummins.fit_radiation(ds, method="realization", max_order=12, passivity="diagonal")
for name, model in (("vector fitting", passive), ("ERA, per coupling", era)):
    report = passivity_test(model)
    print(f"{name}: passive {report.passive}, crossings at {np.round(report.crossings, 3)}")

# %%
# The smallest eigenvalue of the DOF-scaled K + Kᴴ over frequency, relative to the
# largest: below zero the model would feed energy into the motions.
fig = Figure(figsize=(8, 3.8), layout="constrained")
ax = fig.subplots()
for name, model in (("vector fitting (passive)", passive), ("ERA, per coupling", era)):
    sweep = passivity_sweep(model)
    ax.semilogx(sweep.omega, sweep.min_eigenvalue, label=name)
ax.axhline(0.0, color="C3", lw=0.8)
ax.set_ylim(-0.05, 0.2)
ax.set_xlabel("ω [rad/s]")
ax.set_ylabel("λ_min(K + Kᴴ) / λ_max")
ax.legend()
ax.grid(alpha=0.3)
