"""Figures of a fitted radiation model against its data: one per DOF, a row per coupling.

``cummins fit --plot`` draws, for each DOF i, the couplings (i, j ≥ i) the model holds —
A_ij(ω), B_ij(ω), |K_ij(jω)| and K_ij(t), data against the model — so that a two-body
model of 12 DOFs takes a dozen figures, not one per coupling, and the curves every panel
needs (the model's frequency and impulse responses, K(t) of the data) are computed once
(:class:`FitCurves`). :func:`plot_coupling_fit` draws one coupling with the phase of K.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.ticker import NullLocator
from numpy.typing import NDArray

from cummins.display import kernel_window, note_kernel_window
from cummins.dofs import is_rotation


@dataclass(frozen=True)
class FitCurves:
    """What the figures of a model against its data draw, computed once for all pairs.

    Attributes
    ----------
    omega
        The data's frequencies (rad/s); ``left_out`` marks those the fit left out.
    added_mass, damping
        The symmetric part ½(X_ij + X_ji) of the data, what the fit used (ω, i, j).
    added_mass_read, damping_read
        The data as read (ω, i, j).
    omega_model, response
        A log grid around the fitted range and the model's K(jω) there (ω, i, j).
    time, kernel_data, kernel_model
        K(t) of the data kept (trapezoid-exact, :func:`~cummins.radiation.retardation.
        retardation_function`) and of the model, on the data's default time grid.
    """

    omega: NDArray[np.float64]
    left_out: NDArray[np.bool_]
    added_mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    added_mass_read: NDArray[np.float64]
    damping_read: NDArray[np.float64]
    omega_model: NDArray[np.float64]
    response: NDArray[np.complex128]
    time: NDArray[np.float64]
    kernel_data: NDArray[np.float64]
    kernel_model: NDArray[np.float64]


def fit_curves(ds: xr.Dataset, model, left_out: Sequence[float] = ()) -> FitCurves:
    """The curves of :class:`FitCurves` for ``model`` fitted to ``ds`` (one forward
    speed, the model's DOFs), ``left_out`` the frequencies (rad/s) the fit left out."""
    from cummins.radiation.retardation import default_time_grid, retardation_function

    dofs = list(model.dofs)
    ds = ds.sel(influenced_dof=dofs, radiating_dof=dofs)
    w = ds.omega.values
    out = np.isin(w, np.asarray(left_out, dtype=float))
    a_read = ds.added_mass.transpose("omega", "influenced_dof", "radiating_dof").values
    b_read = ds.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").values
    w_model = np.geomspace(w[~out][0] * 0.5, w[~out][-1] * 2.0, 400)
    kept = ds.isel(omega=np.flatnonzero(~out))
    t = default_time_grid(kept)
    k_data = retardation_function(kept, t).transpose("time", "influenced_dof", "radiating_dof")
    return FitCurves(
        omega=w,
        left_out=out,
        added_mass=0.5 * (a_read + a_read.transpose(0, 2, 1)),
        damping=0.5 * (b_read + b_read.transpose(0, 2, 1)),
        added_mass_read=a_read,
        damping_read=b_read,
        omega_model=w_model,
        response=model.frequency_response(w_model).values,
        time=t,
        kernel_data=k_data.values,
        kernel_model=model.impulse_response(t).values,
    )


def fitted_rows(model) -> dict[int, list[int]]:
    """For each DOF i, the DOFs j ≥ i of the couplings the model holds (the figures)."""
    rows: dict[int, list[int]] = {}
    for k in model.modelled:
        if k.influenced <= k.radiating:
            rows.setdefault(k.influenced, []).append(k.radiating)
    return {i: sorted(js) for i, js in sorted(rows.items())}


def plot_dof_fits(curves: FitCurves, model, i: int, columns: Sequence[int]) -> Figure:
    """Data against the model for the couplings (i, j), j in ``columns``: a row each of
    A(ω), B(ω), |K(jω)| (log-log) and K(t) (to where it has decayed).

    Parameters
    ----------
    curves
        From :func:`fit_curves`.
    model
        The :class:`cummins.radiation.model.RadiationModel`.
    i
        0-based DOF index (force).
    columns
        0-based DOF indices (velocity) of the couplings to draw.
    """
    n = len(columns)
    fig = Figure(figsize=(15, 2.6 * n + 0.7))
    fig.subplots_adjust(
        left=0.07, right=0.99, bottom=0.5 / (2.6 * n + 0.7), top=1 - 0.75 / (2.6 * n + 0.7)
    )
    grid = {"hspace": 0.55, "wspace": 0.32}
    axes = np.atleast_2d(fig.subplots(n, 4, squeeze=False, gridspec_kw=grid))
    for row, j in enumerate(columns):
        _coupling_row(axes[row], curves, model, i, j)
    for ax in axes[-1]:
        ax.set_xlabel(ax.get_xlabel() or "ω [rad/s]")
    axes[0, 0].legend(fontsize="x-small", loc="best")
    axes[0, 3].legend(fontsize="x-small", loc="lower right")
    fig.suptitle(f"{model.dofs[i]}: the fitted model against the data")
    return fig


def _coupling_row(axes, curves: FitCurves, model, i: int, j: int) -> None:
    """One row of :func:`plot_dof_fits`."""
    ax_a, ax_b, ax_m, ax_k = axes
    w, out, wm = curves.omega, curves.left_out, curves.omega_model
    rot = sum(is_rotation(d) for d in (model.dofs[i], model.dofs[j]))
    unit = ("kg", "kg·m", "kg·m²")[rot]
    a, b = curves.added_mass[:, i, j], curves.damping[:, i, j]
    a_inf = float(model.added_mass_inf[i, j])
    k_model = curves.response[:, i, j]
    k_data = b + 1j * w * (a - a_inf)

    def points(ax, values, plot="plot") -> None:
        getattr(ax, plot)(w[~out], values[~out], "o", ms=2.5, color="0.3", label="data")
        if out.any():
            getattr(ax, plot)(
                w[out], values[out], "o", ms=3.5, mfc="none", color="0.55", label="left out"
            )

    for ax, read, used in (
        (ax_a, curves.added_mass_read[:, i, j], a),
        (ax_b, curves.damping_read[:, i, j], b),
    ):
        if not np.allclose(read, used, rtol=1e-6, atol=0.0):
            ax.plot(w, read, "x", ms=3, color="0.65", label="as read (A_ij ≠ A_ji)")
    points(ax_a, a)
    ax_a.plot(wm, a_inf + k_model.imag / wm, color="C0", label="model")
    ax_a.axhline(a_inf, color="C3", ls="--", lw=0.8, label="A∞")
    ax_a.set_ylabel(f"A [{unit}]")
    points(ax_b, b)
    ax_b.plot(wm, k_model.real, color="C1", label="model")
    ax_b.axhline(0.0, color="0.6", lw=0.6)
    ax_b.set_ylabel(f"B [{unit}/s]")
    points(ax_m, np.abs(k_data), "loglog")
    ax_m.loglog(wm, np.abs(k_model), color="C2", label="model")
    ax_m.set_ylabel(f"|K(jω)| [{unit}/s]")
    t = curves.time
    kd, km = curves.kernel_data[:, i, j], curves.kernel_model[:, i, j]
    shown = kernel_window(t, [kd, km])
    keep = t <= shown
    ax_k.plot(t[keep], kd[keep], color="0.3", label="from the data")
    ax_k.plot(t[keep], km[keep], "--", color="C0", label="model")
    ax_k.axhline(0.0, color="0.6", lw=0.6)
    ax_k.set_xlim(0.0, shown)
    ax_k.set_xlabel("t [s]")
    ax_k.set_ylabel(f"K(t) [{unit}/s²]")
    note_kernel_window(ax_k, shown, float(t[-1]))
    # major ticks only: the minor ticks of a log axis cost most of a figure's drawing
    ax_m.xaxis.set_minor_locator(NullLocator())
    ax_m.yaxis.set_minor_locator(NullLocator())
    for ax in axes:
        ax.grid(alpha=0.3)
        if ax is not ax_m:
            ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4))
    ax_a.set_title(_row_title(model, i, j), loc="left", fontsize="medium")


def _row_title(model, i: int, j: int) -> str:
    dof_i, dof_j = model.dofs[i], model.dofs[j]
    name = dof_i if i == j else f"{dof_i} ← {dof_j}"
    coupling = model.coupling(i, j)
    metrics = coupling.metrics if coupling is not None else {}
    r2 = ", ".join(
        f"{label} {metrics[key]:.4f}"
        for key, label in (("r2_added_mass", "A"), ("r2_damping", "B"), ("r2_kernel", "K(t)"))
        if metrics.get(key) is not None
    )
    poles = metrics.get("common_poles")
    size = f"{poles} common poles" if poles else f"order {coupling.order if coupling else 0}"
    return f"{name}: {size}; R² {r2}"


def fit_figures(model, ds: xr.Dataset) -> Iterator[tuple[str, Figure]]:
    """``(file name, figure)`` for each DOF with a fitted coupling, one at a time:
    ``fit_<DOF>.png`` holding the couplings (i, j ≥ i) of :func:`fitted_rows`; ``ds`` the
    data (one forward speed). The curves are computed once (:func:`fit_curves`)."""
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    curves = fit_curves(ds, model, model.attrs.get("excluded_frequencies", []))
    for i, columns in fitted_rows(model).items():
        yield f"fit_{model.dofs[i]}.png", plot_dof_fits(curves, model, i, columns)


def plot_coupling_fit(
    ds: xr.Dataset, model, i: int, j: int, left_out: Sequence[float] = ()
) -> Figure:
    """Data against the fitted model for coupling (i, j): A, B, |K|, ∠K and K(t).

    The data drawn are what the fit used, the symmetric part ½(X_ij + X_ji); where the
    entry as read differs (A_ij ≠ A_ji) it is drawn as crosses too.

    Parameters
    ----------
    ds
        The data (one forward speed).
    model
        A :class:`cummins.radiation.model.RadiationModel`.
    i, j
        0-based DOF indices (force, velocity).
    left_out
        Frequencies (rad/s) of ``ds`` the fit left out: drawn as open circles, and not
        used for K(t) from the data.
    """
    from cummins.radiation.retardation import default_time_grid, retardation_function

    dof_i, dof_j = model.dofs[i], model.dofs[j]
    title = dof_i if i == j else f"{dof_i} ← {dof_j}"
    out = np.isin(ds.omega.values, np.asarray(left_out, dtype=float))
    w = ds.omega.values
    w_model = np.geomspace(w[~out][0] * 0.5, w[~out][-1] * 2.0, 400)
    sel = {"influenced_dof": dof_i, "radiating_dof": dof_j}
    swapped = {"influenced_dof": dof_j, "radiating_dof": dof_i}
    # what the fit used: the symmetric part ½(X_ij + X_ji) (the R² in the title are
    # against it); the entries as read are drawn too where they differ
    a_read = ds.added_mass.sel(sel).values
    b_read = ds.radiation_damping.sel(sel).values
    a_data = 0.5 * (a_read + ds.added_mass.sel(swapped).values)
    b_data = 0.5 * (b_read + ds.radiation_damping.sel(swapped).values)
    a_inf = float(model.added_mass_inf[i, j])
    k_data = b_data + 1j * w * (a_data - a_inf)
    k_model = model.frequency_response(w_model).values[:, i, j]
    fig = Figure(figsize=(11, 7.5), layout="constrained")
    grid = fig.add_gridspec(3, 2)
    ax_a, ax_b = fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1])
    ax_m, ax_p = fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[1, 1])
    ax_k = fig.add_subplot(grid[2, :])
    rot = sum(is_rotation(d) for d in (dof_i, dof_j))
    mass_unit = ("kg", "kg·m", "kg·m²")[rot]

    def points(ax, values, plot="plot"):
        getattr(ax, plot)(w[~out], values[~out], "o", ms=3, color="0.3", label="data")
        if out.any():
            getattr(ax, plot)(
                w[out], values[out], "o", ms=4, mfc="none", color="0.5", label="left out"
            )

    for ax, read, fitted in ((ax_a, a_read, a_data), (ax_b, b_read, b_data)):
        if not np.allclose(read, fitted, rtol=1e-6, atol=0.0):
            ax.plot(w, read, "x", ms=3, color="0.6", label=f"{dof_i}, {dof_j} as read")
    points(ax_a, a_data)
    ax_a.plot(w_model, a_inf + k_model.imag / w_model, color="C0", label="model")
    ax_a.axhline(a_inf, color="C3", ls="--", lw=0.8, label="A∞")
    ax_a.set_ylabel(f"A [{mass_unit}]")
    points(ax_b, b_data)
    ax_b.plot(w_model, k_model.real, color="C1")
    ax_b.set_ylabel(f"B [{mass_unit}/s]")
    points(ax_m, np.abs(k_data), "loglog")
    ax_m.loglog(w_model, np.abs(k_model), color="C2")
    ax_m.set_ylabel(f"|K(jω)| [{mass_unit}/s]")
    points(ax_p, np.degrees(np.angle(k_data)), "semilogx")
    ax_p.semilogx(w_model, np.degrees(np.angle(k_model)), color="C4")
    ax_p.set_ylabel("∠K(jω) [deg]")
    for ax in (ax_a, ax_b, ax_m, ax_p):
        ax.set_xlabel("ω [rad/s]")
        ax.grid(alpha=0.3, which="both")
    ax_a.legend(fontsize="small")
    kept = ds.isel(omega=np.flatnonzero(~out))
    t = default_time_grid(kept)
    k_t = retardation_function(kept, t).sel(sel).values
    k_model_t = model.impulse_response(t).values[:, i, j]
    ax_k.plot(t, k_t, color="0.3", label="from the data" + (" kept" if out.any() else ""))
    ax_k.plot(t, k_model_t, "--", color="C0", label="model")
    shown = kernel_window(t, [k_t, k_model_t])
    ax_k.set_xlim(0.0, shown)
    note_kernel_window(ax_k, shown, float(t[-1]))
    ax_k.set_xlabel("t [s]")
    ax_k.set_ylabel(f"K(t) [{mass_unit}/s²]")
    ax_k.grid(alpha=0.3)
    ax_k.legend(fontsize="small")
    coupling = model.coupling(i, j)
    metrics = coupling.metrics if coupling is not None else {}
    r2 = ", ".join(
        f"{label} {metrics[k]:.4f}"
        for k, label in (("r2_added_mass", "A"), ("r2_damping", "B"), ("r2_kernel", "K(t)"))
        if metrics.get(k) is not None
    )
    order = coupling.order if coupling is not None else 0
    poles = metrics.get("common_poles")
    size = f"{poles} common poles" if poles else f"order {order}"
    fig.suptitle(f"{title}: {size}; R² {r2}")
    return fig
