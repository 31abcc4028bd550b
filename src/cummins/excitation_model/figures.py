"""Figures of a causal excitation model, against its data when they are at hand (PNG
through the CLI, embedded in ``cummins report``).

A row per DOF the waves excite, a line per heading: the Bode plot of the model and of
the data's F(ω) (|F| and the phase of F e^{−jωt_c}, the causal response the model
fits, which turns slowly), and the excitation impulse response K_ex(t) of the model
(zero before −t_c) and of the data (Falnes (2002) ch. 5).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from cummins.display import unwrapped_phase_deg
from cummins.hydrodb import is_rotation

__all__ = ["kernel_times", "plot_excitation_fit", "plot_excitation_model"]

#: The model's K_ex(t) is drawn to at most this many time constants of its slowest pole.
DECAYS = 5.0
#: ... and at most this long after t = 0, s.
LONGEST = 300.0


def plot_excitation_fit(ds: xr.Dataset, model, heading: int) -> Figure:
    """Data against the model at heading ``heading`` (index into ``model.headings``):
    :func:`plot_excitation_model` of that heading alone.

    Parameters
    ----------
    ds
        The data the model was fitted to (one forward speed, zero).
    model
        An :class:`~cummins.excitation_model.model.ExcitationModel`.
    heading
        Index of the heading.
    """
    return plot_excitation_model(model, ds, [heading])


def kernel_times(model, headings: Sequence[int], points: int = 800) -> np.ndarray:
    """Times to draw the model's K_ex(t) at, s: from 1.2 of the longest t_c before 0 to
    :data:`DECAYS` time constants of the slowest pole (at most :data:`LONGEST` s, at
    least twice the longest t_c)."""
    tc = max(float(model.delays[h]) for h in headings)
    rates = [
        float(np.abs(m.poles().real).min())
        for m in model.models
        if m.order and m.heading in headings
    ]
    end = min(DECAYS / max(min(rates), 1e-3), LONGEST) if rates else LONGEST
    return np.linspace(-1.2 * tc, max(end, 2.0 * tc, 1.0), points)


def plot_excitation_model(
    model, ds: xr.Dataset | None = None, headings: Sequence[int] | None = None
) -> Figure:
    """|F|, the causal phase and K_ex(t) of the model per DOF, one line per heading;
    with ``ds`` (the data it was fitted to, zero speed) the data too.

    Parameters
    ----------
    model
        An :class:`~cummins.excitation_model.model.ExcitationModel`.
    ds
        The data (markers: F at the data frequencies, a thin line: K_ex of the data), or
        None for the model alone.
    headings
        Indices into ``model.headings``; default every heading (give at most a few: a
        line each).
    """
    from cummins.excitation_model.impulse import excitation_irf, force_on_grid

    picks = list(range(len(model.headings))) if headings is None else [int(h) for h in headings]
    betas = np.asarray(model.headings, dtype=float)[picks]
    tcs = np.asarray(model.delays, dtype=float)[picks]
    orders = model.orders[picks]
    dofs = [d for d in range(len(model.dofs)) if orders[:, d].any()]
    if ds is not None:
        w = np.asarray(ds.omega.values, dtype=float)
        data = force_on_grid(ds, betas, w)
        irf = excitation_irf(ds, wave_direction=betas)
        t, k_data = irf.time.values, irf.values
    else:
        w = np.linspace(model.attrs.get("omega_min", 0.01), model.attrs.get("omega_max", 3.0), 2)
        t, k_data = kernel_times(model, picks), None
    w_model = np.linspace(w[0], w[-1], 800)
    fitted = model.frequency_response(w_model)[:, picks, :]
    at_data = model.frequency_response(w)[:, picks, :]
    k_model = model.impulse_response(t)[:, picks, :]
    single = len(picks) == 1
    rows = max(len(dofs), 1)
    fig = Figure(figsize=(13, 2.6 * rows + 0.8), layout="constrained")
    axes = fig.subplots(rows, 3, squeeze=False)
    for row, d in enumerate(dofs):
        label = model.dofs[d]
        unit = "N·m/m" if is_rotation(label) else "N/m"
        ax_m, ax_p, ax_k = axes[row]
        for k, (beta, tc) in enumerate(zip(betas, tcs, strict=True)):
            if not orders[k, d]:
                continue
            colour = "C0" if single else f"C{k % 10}"
            name = f"β = {np.degrees(beta):g}°, t_c = {tc:.3g} s"
            shifted = fitted[:, k, d] * np.exp(-1j * w_model * tc)
            phase = unwrapped_phase_deg(shifted)
            if ds is not None:
                marker = "0.3" if single else colour
                ax_m.semilogy(w, np.abs(data[:, k, d]), "o", ms=3, color=marker, alpha=0.7)
                near = _phase_near(data[:, k, d], at_data[:, k, d], np.interp(w, w_model, phase))
                ax_p.plot(w, near, "o", ms=3, color=marker, alpha=0.7)
                ax_k.plot(t, k_data[:, k, d], color=marker, lw=0.8, alpha=0.7)
            ax_m.semilogy(w_model, np.abs(fitted[:, k, d]), color=colour, label=name)
            ax_p.plot(w_model, phase, color="C1" if single else colour)
            ax_k.plot(t, k_model[:, k, d], "--", color="C2" if single else colour)
            ax_k.axvline(-tc, color="C3" if single else colour, lw=0.8, ls=":")
        ax_m.set_ylabel(f"{label} |F| [{unit}]")
        ax_p.set_ylabel("∠F e^{-jωt_c} [deg]")
        ax_k.set_ylabel(f"K_ex [{unit}/s]")
        if single:
            part = model.model(picks[0], d)
            ax_m.set_title(
                f"{part.order} states, NRMSE {part.metrics.get('nrmse', np.nan):.3g}",
                fontsize="small",
            )
        for ax in (ax_m, ax_p):
            ax.set_xlabel("ω [rad/s]")
            ax.grid(alpha=0.3, which="both")
        ax_k.set_xlabel("t [s]")
        ax_k.grid(alpha=0.3)
    if not dofs:
        axes[0, 0].text(0.5, 0.5, "no DOF excited at this heading", ha="center")
    _legend(fig, axes, single, ds is not None)
    if single:
        fig.suptitle(f"wave excitation, heading {np.degrees(betas[0]):g} deg, t_c = {tcs[0]:.3g} s")
    else:
        fig.suptitle("wave excitation model" + (" against the data" if ds is not None else ""))
    return fig


def _phase_near(data, fitted, phase_deg):
    """The causal phase of the data (deg) drawn on the model's unwrapped curve
    ``phase_deg``: the model's phase plus the angle between data and model (within
    ±180°). The data unwrapped on their own would miss or add turns of 360° between
    data frequencies far apart (the phase of e^{−jωt_c} turns by π every π/t_c)."""
    return phase_deg + np.degrees(np.angle(data * np.conj(fitted)))


def _legend(fig: Figure, axes, single: bool, with_data: bool) -> None:
    """What the markers and line styles are, and (several headings) which colour is
    which heading."""
    from matplotlib.lines import Line2D

    grey = "0.3"
    styles = [Line2D([], [], color="C0" if single else grey, label="model: |F|, phase")]
    styles.append(Line2D([], [], ls="--", color="C2" if single else grey, label="model K_ex(t)"))
    styles.append(Line2D([], [], ls=":", color="C3" if single else grey, label="-t_c"))
    if with_data:
        styles.insert(0, Line2D([], [], ls="", marker="o", ms=3, color=grey, label="data"))
        styles.append(Line2D([], [], lw=0.8, color=grey, label="K_ex(t) of the data"))
    axes[0, 2].legend(handles=styles, fontsize="small")
    if not single:
        named = {}
        for ax in axes[:, 0]:
            for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
                named.setdefault(label, handle)
        fig.legend(
            list(named.values()),
            list(named),
            loc="outside lower center",
            ncols=min(len(named), 5),
            fontsize="small",
        )
