"""Figures of the second-order data: |Q(ω₁, ω₂)| over the frequency plane and the mean
drift (matplotlib ``Figure`` s, no pyplot state; imported only when drawn)."""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from cummins.dofs import is_rotation
from cummins.qtf.data import qtf_table, significant_dofs


def _significant(table) -> list[int]:
    """DOFs whose QTF is at least 1 % of the largest of its kind (forces, moments)."""
    peaks = np.abs(table.values).reshape(-1, len(table.dofs)).max(axis=0)
    return [int(k) for k in np.flatnonzero(significant_dofs(peaks, table.dofs))]


def plot_qtf(ds: xr.Dataset, kind: str = "difference", direction: int = 0) -> Figure:
    """|Q(ω₁, ω₂)| of every significant DOF over the frequency plane, at the QTF's
    ``direction``-th wave direction (both waves of a pair), with the mean drift (the
    diagonal, difference QTF) or the double-frequency force (sum QTF) drawn in."""
    table = qtf_table(ds, kind)
    w = table.omega
    dofs = _significant(table)
    n = max(len(dofs), 1)
    cols = min(n, 3)
    rows = int(np.ceil(n / cols))
    fig = Figure(figsize=(4.2 * cols, 3.6 * rows), layout="constrained")
    beta = np.degrees(table.directions[direction])
    for panel, k in enumerate(dofs):
        ax = fig.add_subplot(rows, cols, panel + 1)
        if table.bidirectional:
            q = table.values[:, :, direction, direction, k]
        else:
            q = table.values[:, :, direction, k]
        unit = "N·m/m²" if is_rotation(table.dofs[k]) else "N/m²"
        mesh = ax.pcolormesh(w, w, np.abs(q).T, shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=f"|Q| ({unit})")
        ax.plot(w, w, color="white", lw=0.6, ls="--")
        ax.set_xlabel("ω₁ (rad/s)")
        ax.set_ylabel("ω₂ (rad/s)")
        ax.set_title(table.dofs[k])
        ax.set_aspect("equal")
    fig.suptitle(f"{kind}-frequency QTF |Q(ω₁, ω₂)|, waves towards {beta:.4g}°")
    return fig
