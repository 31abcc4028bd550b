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

from cummins.errors import check_writable


def _diagonal_dofs(ds: xr.Dataset, dofs: Sequence[str] | None) -> list[str]:
    labels = [str(d) for d in ds.influenced_dof.values]
    if dofs is None:
        return labels
    return [d for d in dofs if d in labels]


def _unit(dof: str, kind: str) -> str:
    rotation = dof.rpartition("__")[2] in ("Roll", "Pitch", "Yaw")
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
    dofs = _diagonal_dofs(ds, dofs)
    beta = np.degrees(ds.wave_direction.values)
    if headings_deg is None:
        picks = np.unique(np.linspace(0, beta.size - 1, min(5, beta.size)).round().astype(int))
    else:
        picks = [int(np.argmin(np.abs(beta - h))) for h in headings_deg]
    fig = Figure(figsize=(10, 2.2 * len(dofs) + 0.8), layout="constrained")
    axes = fig.subplots(len(dofs), 2, squeeze=False, sharex=True)
    w = ds.omega.values
    for row, dof in enumerate(dofs):
        x = ds.excitation_force.sel(influenced_dof=dof)
        for k in picks:
            xk = x.isel(wave_direction=k).values
            label = f"β = {beta[k]:.0f}°"
            axes[row, 0].plot(w, np.abs(xk), label=label)
            axes[row, 1].plot(w, np.degrees(np.angle(xk)), ".", ms=3, label=label)
        axes[row, 0].set_ylabel(f"|X| {dof} [{_unit(dof, 'force')}]")
        axes[row, 1].set_ylabel(f"∠X {dof} [deg]")
        axes[row, 1].set_ylim(-185, 185)
        for ax in axes[row]:
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize="small")
    for ax in axes[-1]:
        ax.set_xlabel("ω [rad/s]")
    fig.suptitle(f"Wave excitation (per metre of wave amplitude) — {_title(ds)}")
    return fig


def _title(ds: xr.Dataset) -> str:
    source = ds.attrs.get("source_file") or ds.attrs.get("source_format", "")
    return Path(str(source)).name or "dataset"


def save_figure(
    fig: Figure, path: str | os.PathLike[str], *, force: bool = False, dpi: int = 120
) -> Path:
    """Write ``fig`` as PNG; refuse to overwrite an existing file unless ``force``."""
    p = Path(path)
    check_writable(p, force)
    p.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(p, dpi=dpi)
    return p
