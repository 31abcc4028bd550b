"""Figures of a causal excitation model against its data (PNG through the CLI).

One figure per heading: for each DOF the waves excite, the Bode plot of the data's
F(ω) and of the model (|F| and the phase of F e^{−jωt_c}, the causal response the
model fits, which turns slowly), and the excitation impulse response K_ex(t) of the data
against the model's (zero before −t_c).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from cummins.hydrodb import is_rotation

__all__ = ["plot_excitation_fit"]


def plot_excitation_fit(ds: xr.Dataset, model, heading: int) -> Figure:
    """Data against the model at heading ``heading`` (index into ``model.headings``).

    Parameters
    ----------
    ds
        The data the model was fitted to (one forward speed, zero).
    model
        An :class:`~cummins.excitation_model.model.ExcitationModel`.
    heading
        Index of the heading.
    """
    from cummins.excitation_model.impulse import excitation_irf, force_on_grid

    beta = float(model.headings[heading])
    tc = float(model.delays[heading])
    w = np.asarray(ds.omega.values, dtype=float)
    dofs = [d for d in range(len(model.dofs)) if model.model(heading, d).order]
    data = force_on_grid(ds, np.array([beta]), w)[:, 0, :]
    w_model = np.linspace(w[0], w[-1], 800)
    fitted = model.frequency_response(w_model)[:, heading, :]
    irf = excitation_irf(ds, wave_direction=[beta])
    t = irf.time.values
    k_model = model.impulse_response(t)[:, heading, :]
    rows = max(len(dofs), 1)
    fig = Figure(figsize=(13, 2.6 * rows + 0.6), layout="constrained")
    axes = fig.subplots(rows, 3, squeeze=False)
    for row, d in enumerate(dofs):
        label = model.dofs[d]
        unit = "N·m/m" if is_rotation(label) else "N/m"
        part = model.model(heading, d)
        ax_m, ax_p, ax_k = axes[row]
        ax_m.semilogy(w, np.abs(data[:, d]), "o", ms=3, color="0.3", label="data")
        ax_m.semilogy(w_model, np.abs(fitted[:, d]), color="C0", label="model")
        ax_m.set_ylabel(f"{label} |F| [{unit}]")
        causal = np.unwrap(np.angle(data[:, d] * np.exp(-1j * w * tc)))
        model_phase = np.unwrap(np.angle(fitted[:, d] * np.exp(-1j * w_model * tc)))
        ax_p.plot(w, np.degrees(causal), "o", ms=3, color="0.3")
        ax_p.plot(w_model, np.degrees(model_phase), color="C1")
        ax_p.set_ylabel("∠F e^{-jωt_c} [deg]")
        ax_k.plot(t, irf.values[:, 0, d], color="0.3", label="K_ex(t) of the data")
        ax_k.plot(t, k_model[:, d], "--", color="C2", label="model")
        ax_k.axvline(-tc, color="C3", lw=0.8, ls=":", label="-t_c")
        ax_k.set_ylabel(f"K_ex [{unit}/s]")
        metrics = part.metrics
        ax_m.set_title(
            f"{part.order} states, NRMSE {metrics.get('nrmse', np.nan):.3g}", fontsize="small"
        )
        for ax in (ax_m, ax_p):
            ax.set_xlabel("ω [rad/s]")
            ax.grid(alpha=0.3, which="both")
        ax_k.set_xlabel("t [s]")
        ax_k.grid(alpha=0.3)
        if row == 0:
            ax_m.legend(fontsize="small")
            ax_k.legend(fontsize="small")
    if not dofs:
        axes[0, 0].text(0.5, 0.5, "no DOF excited at this heading", ha="center")
    fig.suptitle(f"wave excitation, heading {np.degrees(beta):g} deg, t_c = {tc:.3g} s")
    return fig
