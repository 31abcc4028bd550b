"""Figures a user wants to look at, as matplotlib figures (saved as PNG by the CLI).

All functions return a :class:`matplotlib.figure.Figure` and draw nothing on screen,
so they work the same in a notebook, a script and on a headless server.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from cummins.display import (
    kernel_window,
    mark_negligible,
    motion_units,
    negligible_series,
    note_kernel_window,
    phase_line,
    rotation_scale,
    wrapped_phase_deg,
)
from cummins.errors import check_writable
from cummins.files import replacing
from cummins.fit_figures import plot_coupling_fit as plot_coupling_fit  # its earlier place
from cummins.hydrodb import is_rotation


def _diagonal_dofs(ds: xr.Dataset, dofs: Sequence[str] | None) -> list[str]:
    labels = [str(d) for d in ds.influenced_dof.values]
    if dofs is None:
        return labels
    return [d for d in dofs if d in labels]


def _unit(dof: str, kind: str) -> str:
    rotation = is_rotation(dof)
    if kind == "added_mass":
        return "kg·m²" if rotation else "kg"
    if kind == "damping":
        return "kg·m²/s" if rotation else "kg/s"
    return "N·m/m" if rotation else "N/m"


def plot_added_mass_damping(ds: xr.Dataset, dofs: Sequence[str] | None = None) -> Figure:
    """Diagonal added mass A_ii(ω) and damping B_ii(ω), with A(0) and A(∞) marked.

    Parameters
    ----------
    ds
        A ``HydroDB`` (the first forward speed is shown if there are several).
    dofs
        DOF labels to show (default: all).
    """
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    dofs = _diagonal_dofs(ds, dofs)
    fig = Figure(figsize=(10, 2.2 * len(dofs) + 0.8), layout="constrained")
    axes = fig.subplots(len(dofs), 2, squeeze=False, sharex=True)
    w = ds.omega.values
    for row, dof in enumerate(dofs):
        a = ds.added_mass.sel(influenced_dof=dof, radiating_dof=dof).values
        b = ds.radiation_damping.sel(influenced_dof=dof, radiating_dof=dof).values
        ax_a, ax_b = axes[row]
        ax_a.plot(w, a, ".-", color="C0", label="A(ω)")
        if "added_mass_inf" in ds:
            ax_a.axhline(
                float(ds.added_mass_inf.sel(influenced_dof=dof, radiating_dof=dof)),
                color="C3",
                ls="--",
                label="A(∞)",
            )
        if "added_mass_zero" in ds:
            ax_a.plot(
                [0.0],
                [float(ds.added_mass_zero.sel(influenced_dof=dof, radiating_dof=dof))],
                "s",
                color="C2",
                label="A(0)",
            )
        ax_b.plot(w, b, ".-", color="C1", label="B(ω)")
        negative = b < 0
        if negative.any():
            ax_b.plot(w[negative], b[negative], "x", color="C3", ms=8, label="B < 0")
        ax_b.axhline(0.0, color="0.6", lw=0.8)
        ax_a.set_ylabel(f"A {dof} [{_unit(dof, 'added_mass')}]")
        ax_b.set_ylabel(f"B {dof} [{_unit(dof, 'damping')}]")
        for ax in (ax_a, ax_b):
            ax.grid(alpha=0.3)
            ax.legend(fontsize="small", loc="best")
    for ax in axes[-1]:
        ax.set_xlabel("ω [rad/s]")
    fig.suptitle(f"Added mass and damping — {_title(ds)}")
    return fig


def plot_excitation(
    ds: xr.Dataset, dofs: Sequence[str] | None = None, headings_deg: Sequence[float] | None = None
) -> Figure:
    """Magnitude and phase of the first-order excitation force per DOF and heading.

    Parameters
    ----------
    headings_deg
        Wave directions to show, degrees (default: up to five spread over the data).
    """
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    if "excitation_force" not in ds:
        raise ValueError("the dataset has no excitation_force")
    force = ds.excitation_force.rename(influenced_dof="dof").transpose(
        "omega", "wave_direction", "dof"
    )
    return _amplitude_phase_by_heading(
        force,
        _diagonal_dofs(ds, dofs),
        heading_picks(np.degrees(ds.wave_direction.values), headings_deg, 5),
        "X",
        lambda dof: _unit(dof, "force"),
        f"Wave excitation (per metre of wave amplitude) — {_title(ds)}",
    )


def plot_rao(
    rao: xr.DataArray,
    dofs: Sequence[str] | None = None,
    headings_deg: Sequence[float] | None = None,
) -> Figure:
    """|RAO| and its phase per DOF, one line per heading (at most eight shown by default);
    ``rao`` from :func:`cummins.seakeeping.frequency_domain.motion_rao`."""
    labels = [str(d) for d in rao.dof.values]
    source = str(rao.attrs.get("source_file", "")).rpartition("/")[2]
    return _amplitude_phase_by_heading(
        rao.transpose("omega", "wave_direction", "dof"),
        labels if dofs is None else [d for d in dofs if d in labels],
        heading_picks(np.degrees(rao.wave_direction.values), headings_deg, 8),
        "RAO",
        lambda dof: "rad/m" if is_rotation(dof) else "m/m",
        f"Motion RAOs (per metre of wave amplitude) {('— ' + source) if source else ''}",
        degrees=True,
    )


#: The amplitude plots leave a phase out where the amplitude is below this fraction of the
#: DOF's largest over the headings drawn: it is numerically meaningless there.
PHASE_SHOWN_ABOVE = 0.01


def _amplitude_phase_by_heading(
    values: xr.DataArray,
    dofs: Sequence[str],
    picks: Sequence[int],
    symbol: str,
    unit,
    title: str,
    *,
    degrees: bool = False,
) -> Figure:
    """|values| and phase (deg) against ω, a row per DOF, a line per picked heading;
    ``values`` complex with dims (omega, wave_direction, dof). The phase is drawn as
    seakeeping tools draw it: wrapped to ±180° (the line breaks where it wraps), and
    left out where the magnitude is below :data:`PHASE_SHOWN_ABOVE` of the DOF's largest
    over the headings (the phase of a negligible response says nothing). A DOF
    numerically zero at every heading drawn (sway in head seas) is drawn as "≈ 0"
    (:func:`cummins.display.negligible_series`); with
    ``degrees`` rotations are shown in degrees."""
    beta = np.degrees(values.wave_direction.values)
    fig = Figure(figsize=(10, 2.2 * len(dofs) + 0.8), layout="constrained")
    axes = fig.subplots(len(dofs), 2, squeeze=False, sharex=True)
    w = values.omega.values
    shown = values.isel(wave_direction=list(picks))
    peaks = [float(np.abs(shown.sel(dof=dof).values).max()) for dof in dofs]
    zero = negligible_series(peaks, [is_rotation(d) for d in dofs])
    for row, dof in enumerate(dofs):
        x = values.sel(dof=dof)
        scale, shown_unit = rotation_scale(unit(dof)) if degrees else (1.0, unit(dof))
        tiny = PHASE_SHOWN_ABOVE * float(np.abs(x.values).max())
        for k in picks:
            xk = x.isel(wave_direction=k).values
            label = f"β = {beta[k]:.0f}°"
            axes[row, 0].plot(w, scale * np.abs(xk), label=label)
            if not zero[row]:
                axes[row, 1].plot(
                    *phase_line(w, wrapped_phase_deg(xk, tiny)),
                    lw=1.0,
                    marker=".",
                    ms=3,
                    label=label,
                )
        axes[row, 0].set_ylabel(f"|{symbol}| {dof} [{shown_unit}]")
        axes[row, 1].set_ylabel(f"∠{symbol} {dof} [deg]")
        axes[row, 1].set_ylim(-190.0, 190.0)
        axes[row, 1].set_yticks([-180, -90, 0, 90, 180])
        if zero[row]:
            mark_negligible(axes[row, 0], scale * peaks[row], shown_unit)
        for ax in axes[row]:
            ax.grid(alpha=0.3)
    fig.legend(
        *axes[0, 0].get_legend_handles_labels(),
        loc="outside lower center",
        ncols=min(len(picks), 8),
        fontsize="small",
    )
    for ax in axes[-1]:
        ax.set_xlabel("ω [rad/s]")
    axes[0, 1].set_title(
        f"phase where |{symbol}| ≥ {PHASE_SHOWN_ABOVE:.0%} of the DOF's peak",
        fontsize="small",
        color="0.35",
    )
    fig.suptitle(title)
    return fig


def _title(ds: xr.Dataset) -> str:
    source = ds.attrs.get("source_file") or ds.attrs.get("source_format", "")
    return Path(str(source)).name or "dataset"


def heading_picks(beta_deg, headings_deg=None, most: int = 5) -> list[int]:
    """Indices of the headings to draw: those nearest ``headings_deg``, or ``most`` spread
    evenly over ``beta_deg``."""
    beta_deg = np.asarray(beta_deg, dtype=float)
    if headings_deg is None:
        spread = np.linspace(0, beta_deg.size - 1, min(most, beta_deg.size))
        return [int(k) for k in np.unique(spread.round().astype(int))]
    return [int(np.argmin(np.abs(beta_deg - h))) for h in headings_deg]


def save_figure(
    fig: Figure, path: str | os.PathLike[str], *, force: bool = False, dpi: int = 120
) -> Path:
    """Write ``fig`` as PNG; refuse to overwrite an existing file unless ``force``.

    A figure of constrained layout is laid out once before it is written: the tick labels
    chosen at the final axes' size can be wider than those the layout measured, and a
    y label ("A Roll [kg·m²]") would be cut at the edge (:func:`settle_layout`)."""
    p = Path(path)
    check_writable(p, force)
    p.parent.mkdir(parents=True, exist_ok=True)
    settle_layout(fig, dpi)
    with replacing(p) as tmp:
        fig.savefig(tmp, dpi=dpi, format=p.suffix.lstrip(".").lower() or "png")
    return p


def settle_layout(fig: Figure, dpi: float | None = None) -> None:
    """Run a figure's layout engine once at ``dpi`` so that the layout of the drawing
    that follows sees the tick labels of the final axes' size."""
    engine = fig.get_layout_engine()
    if engine is not None:
        if dpi is not None:
            fig.set_dpi(dpi)
        engine.execute(fig)


def _pairs(kernel, couplings) -> list[tuple[str, str]]:
    labels = [str(d) for d in kernel.influenced_dof.values]
    if couplings is None:
        return [(d, d) for d in labels]
    return [(labels[i], labels[j]) for i, j in couplings]


def _k_unit(a: str, b: str) -> str:
    rot = sum(is_rotation(x) for x in (a, b))
    return ("kg/s²", "kg·m/s²", "kg·m²/s²")[rot]


def plot_retardation(
    kernel: xr.DataArray,
    couplings: Sequence[tuple[int, int]] | None = None,
    *,
    reference: xr.DataArray | None = None,
    reference_label: str = "reference",
) -> Figure:
    """K_ij(t) per coupling (diagonal by default), optionally against a reference K(t);
    each panel ends a little after |K| stays below 1 % of its peak
    (:func:`cummins.display.kernel_window`), and says where the record ends."""
    pairs = _pairs(kernel, couplings)
    ncols = 2 if len(pairs) > 3 else 1
    nrows = int(np.ceil(len(pairs) / ncols))
    fig = Figure(figsize=(5.5 * ncols, 2.2 * nrows + 0.8), layout="constrained")
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False).ravel())
    t = kernel.time.values
    for ax, (a, b) in zip(axes, pairs, strict=False):
        k = kernel.sel(influenced_dof=a, radiating_dof=b).values
        shown = kernel_window(t, [k])
        ax.plot(t, k, color="C0", label="K(t)")
        if reference is not None:
            ref = reference.sel(influenced_dof=a, radiating_dof=b)
            ax.plot(ref.time.values, ref.values, "--", color="C3", label=reference_label)
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.set_xlim(0.0, shown)  # to where K has decayed, not the whole record
        note_kernel_window(ax, shown, float(t[-1]))
        ax.set_title(a if a == b else f"{a} ← {b}", fontsize="medium")
        ax.set_ylabel(f"K [{_k_unit(a, b)}]")
        ax.grid(alpha=0.3)
    for ax in axes[len(pairs) :]:
        ax.set_visible(False)
    for ax in axes[-ncols:]:
        ax.set_xlabel("t [s]")
    axes[0].legend(fontsize="small")
    fig.suptitle("Retardation functions K(t)")
    return fig


def plot_reconstruction(
    ds: xr.Dataset, reconstructed: xr.Dataset, dofs: Sequence[str] | None = None
) -> Figure:
    """Original A(ω), B(ω) against the ones rebuilt from K(t) (Ogilvie), per DOF."""
    dofs = _diagonal_dofs(ds, dofs)
    fig = Figure(figsize=(10, 2.2 * len(dofs) + 0.8), layout="constrained")
    axes = fig.subplots(len(dofs), 2, squeeze=False, sharex=True)
    for row, dof in enumerate(dofs):
        for col, (name, unit) in enumerate(
            (("added_mass", "added_mass"), ("radiation_damping", "damping"))
        ):
            ax = axes[row, col]
            sel = {"influenced_dof": dof, "radiating_dof": dof}
            ax.plot(ds.omega, ds[name].sel(sel), "o", ms=3, color="0.3", label="data")
            ax.plot(
                reconstructed.omega, reconstructed[name].sel(sel), color="C1", label="from K(t)"
            )
            ax.set_ylabel(f"{'A' if col == 0 else 'B'} {dof} [{_unit(dof, unit)}]")
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize="small")
    for ax in axes[-1]:
        ax.set_xlabel("ω [rad/s]")
    fig.suptitle(f"A(ω), B(ω) rebuilt from K(t) — {_title(ds)}")
    return fig


def plot_added_mass_inf(
    per_frequency: xr.DataArray,
    estimate: xr.DataArray,
    ds: xr.Dataset,
    dofs: Sequence[str] | None = None,
) -> Figure:
    """The Ogilvie estimate of A∞ at each frequency, its median, and the data row if any."""
    dofs = _diagonal_dofs(ds, dofs)
    fig = Figure(figsize=(6, 1.9 * len(dofs) + 0.8), layout="constrained")
    axes = np.atleast_1d(fig.subplots(len(dofs), 1, squeeze=False, sharex=True).ravel())
    for ax, dof in zip(axes, dofs, strict=True):
        sel = {"influenced_dof": dof, "radiating_dof": dof}
        ax.plot(per_frequency.omega, per_frequency.sel(sel), ".", ms=3, label="A∞(ω) (Ogilvie)")
        ax.axhline(float(estimate.sel(sel)), color="C1", label="median")
        if "added_mass_inf" in ds:
            ax.axhline(float(ds.added_mass_inf.sel(sel)), color="C3", ls="--", label="solver ω = ∞")
        value = float(estimate.sel(sel))
        if value:
            ax.set_ylim(sorted((value * 0.8, value * 1.2)))
        ax.set_ylabel(f"A∞ {dof} [{_unit(dof, 'added_mass')}]")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize="small")
    axes[-1].set_xlabel("ω [rad/s]")
    fig.suptitle("Infinite-frequency added mass from A(ω), B(ω)")
    return fig


def plot_time_series(run: xr.Dataset, window: float | None = 600.0) -> Figure:
    """Wave elevation and the motions of a simulation (the last ``window`` seconds);
    rotations in degrees, a DOF that is numerically zero drawn as "≈ 0"."""
    t = run.time.values
    keep = t >= t[-1] - window if window else np.ones(t.size, dtype=bool)
    dofs = [str(d) for d in run.dof.values]
    units = motion_units(run.motion, dofs)
    motion = run.motion.values[keep]
    zero = negligible_series(np.abs(motion).max(axis=0), [is_rotation(d) for d in dofs])
    fig = Figure(figsize=(11, 1.6 * (len(dofs) + 1)), layout="constrained")
    axes = fig.subplots(len(dofs) + 1, 1, sharex=True)
    axes[0].plot(t[keep], run.wave_elevation.values[keep], color="C0", lw=0.8)
    axes[0].set_ylabel("ζ [m]")
    for k, dof in enumerate(dofs):
        scale, unit = rotation_scale(units[k])
        axes[k + 1].plot(t[keep], scale * motion[:, k], color=f"C{k + 1}", lw=0.8)
        axes[k + 1].set_ylabel(f"{dof} [{unit}]")
        if zero[k]:
            mark_negligible(axes[k + 1], scale * float(np.abs(motion[:, k]).max()), unit)
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(str(run.attrs.get("sea", "simulation")))
    return fig


def plot_response_spectra(
    run: xr.Dataset, references: dict[str, tuple[np.ndarray, np.ndarray]]
) -> Figure:
    """Response spectra of a simulation (Welch) against frequency-domain ones, at most
    three panels a row (the figure grows with the DOFs), the legend above them;
    rotations in deg², a DOF numerically zero drawn as "≈ 0".

    ``references`` maps a label to (ω, S(ω) of shape (len(ω), n_dofs)), one-sided, per
    rad/s.
    """
    from scipy.signal import welch

    dt = float(run.attrs.get("dt", run.time.values[1] - run.time.values[0]))
    dofs = [str(d) for d in run.dof.values]
    f, p = welch(run.motion.values, fs=1 / dt, nperseg=min(4096, run.sizes["time"]), axis=0)
    w, s_td = 2 * np.pi * f, p / (2 * np.pi)
    ncols = min(3, len(dofs))
    nrows = (len(dofs) + ncols - 1) // ncols
    fig = Figure(figsize=(11, 2.6 * nrows + 1.2), layout="constrained")
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False).ravel())
    units = motion_units(run.motion, dofs)
    zero = negligible_series(np.abs(run.motion.values).max(axis=0), [is_rotation(d) for d in dofs])
    # up to where the responses hold 99.9 % of their variance, with a margin
    share = np.cumsum(s_td / np.maximum(s_td.sum(axis=0), 1e-300), axis=0)[:, ~zero].min(
        axis=1, initial=1.0
    )
    top = 1.3 * float(w[min(np.searchsorted(share, 0.999), w.size - 1)])
    for k, dof in enumerate(dofs):
        ax = axes[k]
        scale, unit = rotation_scale(f"{units[k]}²·s/rad")
        ax.plot(w, scale * s_td[:, k], color="0.2", lw=1.0, label="time domain (Welch)")
        for n, (label, (w_ref, s_ref)) in enumerate(references.items()):
            ax.plot(w_ref, scale * s_ref[:, k], "--", color=f"C{n}", lw=1.2, label=label)
        ax.set_xlim(0, top)
        ax.set_title(dof, fontsize="medium")
        ax.set_ylabel(f"S [{unit}]")
        if zero[k]:
            mark_negligible(ax, scale * float(s_td[:, k].max()), unit)
        ax.grid(alpha=0.3)
    for ax in axes[len(dofs) - ncols : len(dofs)]:
        ax.set_xlabel("ω_e [rad/s] (encounter)" if run.attrs.get("forward_speed") else "ω [rad/s]")
    fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=3)
    for ax in axes[len(dofs) :]:
        ax.set_visible(False)
    fig.suptitle(f"response spectra: {run.attrs.get('sea', '')}")
    return fig


# --------------------------------------------------------------------------- damping identification


def plot_residual_force(res: xr.Dataset, estimate, *, max_points: int = 4000) -> Figure:
    """The residual force of a DOF against each regressor, with their correlation in
    the titles (the screening plot of de Haan (2022) Fig. 3.24), and against the DOF's
    velocity with the identified damping curve and its confidence band of the linear
    term.

    ``res`` is a :func:`cummins.sysid.residual_force` result restricted to the samples
    used; ``estimate`` the :class:`cummins.sysid.DampingEstimate` of that DOF.
    """
    from cummins.sysid.identify import regressor_matrix

    dof = estimate.dof
    y = res.residual_force.sel(dof=dof).values
    x = regressor_matrix(res, estimate.regressors)
    pick = np.linspace(0, y.size - 1, min(max_points, y.size)).astype(int)
    n = len(estimate.regressors) + 1
    cols = min(n, 3)
    fig = Figure(figsize=(4 * cols, 3.4 * ((n + cols - 1) // cols)), layout="constrained")
    axes = np.atleast_1d(fig.subplots((n + cols - 1) // cols, cols)).ravel()
    force_unit = "N·m" if is_rotation(dof) else "N"
    for k, r in enumerate(estimate.regressors):
        ax = axes[k]
        ax.plot(x[pick, k], y[pick], ".", ms=1.5, color="0.4")
        corr = np.corrcoef(x[:, k], y)[0, 1] if np.std(x[:, k]) > 0 else float("nan")
        ax.set_title(f"{r.name}: r = {corr:.2f}", fontsize="medium")
        ax.set_xlabel(r.name)
        ax.set_ylabel(f"residual [{force_unit}]")
        ax.grid(alpha=0.3)
    ax = axes[n - 1]
    v = res.velocity.sel(dof=dof).values
    ax.plot(v[pick], y[pick], ".", ms=1.5, color="0.6", label="residual force")
    grid = np.linspace(v.min(), v.max(), 200)
    ax.plot(grid, estimate.damping_force(grid), color="C3", lw=2, label="identified damping")
    ax.set_xlabel(f"{dof} velocity [{'rad' if is_rotation(dof) else 'm'}/s]")
    ax.set_ylabel(f"force [{force_unit}]")
    ax.legend(fontsize="small")
    ax.grid(alpha=0.3)
    for extra in axes[n:]:
        extra.set_visible(False)
    fig.suptitle(
        f"{dof}: residual force of the potential-flow model (R² of the fit {estimate.r2:.3f}, "
        f"condition number {estimate.condition_number:.3g})"
    )
    return fig


def plot_reprediction(
    runs: dict[str, xr.Dataset], window: float | None = 300.0, dofs: Sequence[str] | None = None
) -> Figure:
    """Measured motions against re-predictions (:func:`cummins.sysid.repredict`), the
    correlation of each in the legend; the last ``window`` seconds."""
    first = next(iter(runs.values()))
    dofs = [str(d) for d in first.dof.values] if dofs is None else list(dofs)
    t = first.time.values
    keep = t >= t[-1] - window if window else np.ones(t.size, dtype=bool)
    fig = Figure(figsize=(11, 2.2 * len(dofs) + 0.6), layout="constrained")
    axes = np.atleast_1d(fig.subplots(len(dofs), 1, sharex=True))
    for ax, dof in zip(axes, dofs, strict=True):
        scale = np.degrees(1.0) if is_rotation(dof) else 1.0
        unit = "deg" if is_rotation(dof) else "m"
        ax.plot(
            t[keep],
            scale * first.measured.sel(dof=dof).values[keep],
            color="0.1",
            lw=1.2,
            label="measured",
        )
        for k, (label, run) in enumerate(runs.items()):
            corr = float(run.correlation.sel(dof=dof))
            ax.plot(
                t[keep],
                scale * run.motion.sel(dof=dof).values[keep],
                "--",
                color=f"C{k}",
                lw=1.0,
                label=f"{label} (r = {corr:.3f})",
            )
        ax.set_ylabel(f"{dof} [{unit}]")
        ax.legend(fontsize="small", loc="upper right")
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle("re-prediction of the recorded motions from the excitation force")
    return fig


def plot_segment_validation(validation: xr.Dataset) -> Figure:
    """Coefficients per segment with their confidence intervals, and the correlations
    of the re-predictions in sample, with the previous segment's coefficients and
    without identified damping (de Haan (2022) Figs. 3.25–3.27)."""
    dofs = [str(d) for d in validation.dof.values]
    terms = [str(t) for t in validation.term.values]
    seg = validation.segment.values
    fig = Figure(figsize=(4 * (len(terms) + 1), 3.2 * len(dofs)), layout="constrained")
    axes = np.atleast_2d(fig.subplots(len(dofs), len(terms) + 1))
    for i, dof in enumerate(dofs):
        for j, term in enumerate(terms):
            ax = axes[i, j]
            c = validation.coefficient.values[:, i, j]
            lo, hi = validation.lower.values[:, i, j], validation.upper.values[:, i, j]
            ax.errorbar(seg, c, yerr=[c - lo, hi - c], fmt="o", capsize=3)
            ax.axhline(0, color="0.5", lw=0.8)
            bad = validation.negative.values[:, i] | validation.ill_conditioned.values[:, i]
            ax.plot(seg[bad], c[bad], "x", color="C3", ms=10, label="flagged")
            ax.set_title(f"{dof}: {term}", fontsize="medium")
            ax.set_xlabel("segment")
            ax.grid(alpha=0.3)
        ax = axes[i, -1]
        for k, name in enumerate(("in_sample", "previous", "baseline")):
            ax.plot(seg, validation[name].values[:, i], "o-", color=f"C{k}", label=name)
        ax.set_title(f"{dof}: correlation of re-predictions", fontsize="medium")
        ax.set_xlabel("segment")
        ax.legend(fontsize="small")
        ax.grid(alpha=0.3)
    return fig


def plot_roll_decay(t, phi, decay) -> Figure:
    """A free-decay record with the fitted decay, and the decrement Δφ against the mean
    amplitude φ_m with the line of eq. (2) of :mod:`cummins.sysid.decay`."""
    t = np.asarray(t, dtype=float)
    phi = np.asarray(phi, dtype=float)
    fig = Figure(figsize=(11, 4), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2, width_ratios=(2, 1))
    ax1.plot(t, np.degrees(phi), color="0.2", lw=1.0, label="record")
    ax1.plot(t, np.degrees(decay.simulate(t)), "--", color="C3", lw=1.0, label="fitted decay")
    ax1.plot(
        decay.extremes_time,
        np.degrees(decay.extremes + decay.offset),
        "o",
        ms=3,
        color="C0",
        label="extremes",
    )
    ax1.set_xlabel("t [s]")
    ax1.set_ylabel("roll [deg]")
    ax1.legend(fontsize="small")
    ax1.grid(alpha=0.3)
    amp = np.degrees(decay.amplitudes)
    ax2.plot(amp, np.degrees(decay.decrements), "o", color="C0", label="half cycles")
    grid = np.linspace(0, amp.max() * 1.05, 50)
    g = np.radians(grid)
    line = np.pi * decay["p1"] / (2 * decay["omega0"]) * g + 4 / 3 * decay["p2"] * g**2
    ax2.plot(grid, np.degrees(line), color="C3", label="p1, p2 of the fit")
    ax2.set_xlabel("mean amplitude φ_m [deg]")
    ax2.set_ylabel("decrement Δφ [deg]")
    ax2.legend(fontsize="small")
    ax2.grid(alpha=0.3)
    fig.suptitle(
        f"roll decay: p1 = {decay['p1']:.4g} 1/s, p2 = {decay['p2']:.4g} 1/rad, "
        f"ω0 = {decay['omega0']:.4g} rad/s"
    )
    return fig


# --------------------------------------------------------------------------- unified (DP) model


def _dof_axes(fig: Figure, n: int = 6):
    return np.atleast_1d(fig.subplots(n, 1, sharex=True))


def plot_pose(run: xr.Dataset, *, mark: float | None = None) -> Figure:
    """The pose η (N, E, D in m; roll, pitch, yaw in degrees) of a unified-model run
    (Smogeli et al. (2004) Fig. 4); ``mark`` draws a vertical line (e.g. when a load is
    applied)."""
    t = run.time.values
    fig = Figure(figsize=(11, 11), layout="constrained")
    axes = _dof_axes(fig)
    for k, (ax, dof) in enumerate(zip(axes, run.dof.values, strict=True)):
        values = run.eta.values[:, k]
        rotation = k >= 3
        ax.plot(t, np.degrees(values) if rotation else values, color=f"C{k}", lw=0.8)
        ax.set_ylabel(f"{dof} [{'deg' if rotation else 'm'}]")
        if mark is not None:
            ax.axvline(mark, color="0.5", ls="--", lw=0.8)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle("pose η in the north-east-down frame")
    return fig


def plot_generalized_forces(
    run: xr.Dataset, variables: Sequence[str], *, labels: Sequence[str] | None = None
) -> Figure:
    """Generalized forces of a unified-model run, one panel per DOF (N, kN·m scaled to
    kN and MN·m), e.g. the first-order wave force and the fluid memory force
    (Smogeli et al. (2004) Fig. 3) or every load with the thrust."""
    t = run.time.values
    labels = list(variables) if labels is None else list(labels)
    fig = Figure(figsize=(11, 11), layout="constrained")
    axes = _dof_axes(fig)
    for k, (ax, dof) in enumerate(zip(axes, run.velocity.values, strict=True)):
        scale, unit = (1e-6, "MN·m") if k >= 3 else (1e-3, "kN")
        for n, (name, label) in enumerate(zip(variables, labels, strict=True)):
            ax.plot(t, scale * run[name].values[:, k], lw=0.8, color=f"C{n}", label=label)
        ax.set_ylabel(f"{dof} [{unit}]")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize="small", loc="upper right", ncols=min(len(variables), 4))
    axes[-1].set_xlabel("t [s]")
    fig.suptitle("generalized forces, body frame, about the origin")
    return fig


def plot_watch_circle(run: xr.Dataset, setpoint: Sequence[float] = (0.0, 0.0)) -> Figure:
    """The track of the vessel's origin (east, north) and the watch circle: the largest
    horizontal distance from the setpoint."""
    n = run.eta.sel(dof="North").values - setpoint[0]
    e = run.eta.sel(dof="East").values - setpoint[1]
    radius = float(np.hypot(n, e).max())
    fig = Figure(figsize=(6, 6), layout="constrained")
    ax = fig.subplots()
    ax.plot(e, n, lw=0.6, color="C0", label="track")
    a = np.linspace(0, 2 * np.pi, 200)
    ax.plot(
        radius * np.sin(a),
        radius * np.cos(a),
        "--",
        color="C3",
        label=f"watch circle {radius:.2f} m",
    )
    ax.plot(0, 0, "k+", ms=12)
    ax.set_aspect("equal")
    ax.set_xlabel("East [m]")
    ax.set_ylabel("North [m]")
    ax.legend(fontsize="small")
    ax.grid(alpha=0.3)
    return fig


def plot_lf_model(ds: xr.Dataset, model, dofs: Sequence[str] | None = None) -> Figure:
    """A_ii(ω) and B_ii(ω) per DOF with the values of a low-frequency model marked.

    Like Ross, Perez & Fossen (2006) Figs. 1–2: the cross marks (ω_i, M_A,ii) and
    (ω_i, B_p,ii) of a :class:`cummins.timedomain.lfmodel.LowFrequencyModel` — at ω = 0 for
    surge, sway and yaw, at the natural frequency ω₀ (eq. 24) for heave, roll
    and pitch; a diamond marks the total damping D_ii = B_p,ii + B_v,ii when viscous
    damping is present, on the curves of :func:`plot_added_mass_damping` (with A(∞) and
    A(0) when the data hold them).

    Parameters
    ----------
    ds
        The ``HydroDB`` the model was made from (one forward speed).
    model
        The :class:`cummins.timedomain.lfmodel.LowFrequencyModel`.
    dofs
        DOF labels to show (default: those of the model).
    """
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    labels = list(model.dofs) if dofs is None else [d for d in dofs if d in model.dofs]
    fig = plot_added_mass_damping(ds, labels)
    axes = np.asarray(fig.get_axes()).reshape(len(labels), 2)
    for (ax_a, ax_b), dof in zip(axes, labels, strict=True):
        i = model.dofs.index(dof)
        w0 = float(model.frequencies[i])
        ax_a.plot([w0], [model.added_mass[i, i]], "x", color="C3", ms=10, mew=2, label="M_A")
        ax_b.plot([w0], [model.potential_damping[i, i]], "x", color="C3", ms=10, mew=2, label="B_p")
        if model.viscous_damping[i, i] != 0:
            ax_b.plot([w0], [model.damping[i, i]], "D", color="C2", ms=6, label="D = B_p + B_v")
        where = "ω = 0" if w0 == 0 else f"ω₀ = {w0:.3f} rad/s"
        ax_a.set_title(f"{dof}: {where}", fontsize="medium", loc="left")
        for ax in (ax_a, ax_b):
            ax.legend(fontsize="small", loc="best")
    fig.suptitle(f"Low-frequency model coefficients (Ross, Perez & Fossen, 2006) — {_title(ds)}")
    return fig


def plot_lf_comparison(result: xr.Dataset, dof: str, kind: str) -> Figure:
    """A decay or step response of the low-frequency model against the Cummins model
    (:func:`cummins.timedomain.lfmodel.compare_with_cummins`)."""
    fig = Figure(figsize=(9, 3.5), layout="constrained")
    ax = fig.subplots()
    scale, unit = rotation_scale("rad" if is_rotation(dof) else "m")
    for n, (name, label) in enumerate(
        (("cummins", "Cummins model (fluid memory)"), ("lf", "low-frequency model"))
    ):
        values = scale * result[name].sel(dof=dof).values
        ax.plot(result.time.values, values, lw=1.0, color=f"C{n}", label=label)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(f"{dof} [{unit}]")
    ax.set_title(f"{kind} of {dof}: low-frequency model against the Cummins model")
    ax.legend(fontsize="small")
    ax.grid(alpha=0.3)
    return fig
