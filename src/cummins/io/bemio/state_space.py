"""The radiation state-space models of a BEMIO file (``radiation_damping/state_space``).

BEMIO's ``radiationIRFSS`` fits one SISO model per coupling (i, j) and stores the
matrices padded to the largest order, ``C`` normalised by ρ: read here as a
:class:`~cummins.radiation.model.RadiationModel`, and built from one for the writer.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError
from cummins.hydrodb import dof_matrix
from cummins.io.bemio.reader import read_bemio


def read_bemio_state_space(path: str | os.PathLike[str]):
    """The radiation state-space models BEMIO fitted (``radiationIRFSS``), as a
    :class:`~cummins.radiation.model.RadiationModel` (memory term μ = K * q̇, SI units).

    Per coupling (i, j) the first ``it(i, j)`` states of ``A/all``, ``B/all``,
    ``C/all`` (×ρ, as WEC-Sim's ``bodyClass`` does) form one SISO model; couplings with
    a zero ``C`` contribute nothing and are left out. ``D`` is not used (WEC-Sim does
    not use it either). A∞ is the file's ``inf_freq`` × ρ.

    Raises
    ------
    HydroDataError
        No state space in the file, or inconsistent shapes.
    """
    import h5py

    from cummins.radiation.model import CouplingModel, RadiationModel

    path = Path(path)
    ds = read_bemio(path)
    n = ds.sizes["influenced_dof"]
    rho = float(ds.attrs["rho"])
    couplings = []
    try:
        with h5py.File(path, "r") as f:
            start = 0
            k = 1
            while f"body{k}" in f:
                group = f"body{k}/hydro_coeffs/radiation_damping/state_space"
                if group not in f:
                    raise HydroDataError(f"no {group} in the file", path=path)
                ss = f[group]
                orders = np.asarray(ss["it"][()], dtype=float)
                m = orders.shape[0]
                a_all = np.asarray(ss["A/all"][()], dtype=float)
                b_all = np.asarray(ss["B/all"][()], dtype=float)
                c_all = np.asarray(ss["C/all"][()], dtype=float)
                for i in range(m):
                    for j in range(n):
                        o = round(float(orders[i, j]))
                        if o <= 0:
                            continue
                        c = c_all[i, j, 0, :o] * rho
                        if not np.any(c):
                            continue
                        couplings.append(
                            CouplingModel(
                                start + i,
                                j,
                                a_all[i, j, :o, :o].copy(),
                                b_all[i, j, :o, 0].copy(),
                                c,
                                method="bemio-ss",
                            )
                        )
                start += m
                k += 1
    except HydroDataError:
        raise
    except Exception as exc:
        raise HydroDataError(
            f"cannot read the state-space models ({type(exc).__name__}: {exc})", path=path
        ) from None
    inf = dof_matrix(ds, "added_mass_inf") if "added_mass_inf" in ds else np.full((n, n), np.nan)
    attrs = {"axis_convention": "z-up", "source_format": "bemio", "source_file": str(path)}
    return RadiationModel(
        tuple(str(d) for d in ds.influenced_dof.values), tuple(couplings), inf, attrs
    )


def _state_space(model, labels: Sequence[str], t: np.ndarray, rho: float, path: Path) -> dict:
    """BEMIO's per-coupling arrays (h5py order, all DOFs as rows) of a RadiationModel."""
    dofs = [str(d) for d in model.dofs]
    if dofs != list(labels):
        raise HydroDataError(
            f"the model's DOFs ({', '.join(dofs)}) are not the data's ({', '.join(labels)})",
            path=path,
        )
    n = len(labels)
    model = model.as_couplings()  # BEMIO stores one state-space model per coupling
    by_pair = {(k.influenced, k.radiating): k for k in model.couplings}
    order = max([k.order for k in model.couplings] + [1])
    a = np.zeros((n, n, order, order))
    b = np.zeros((n, n, order, 1))
    c = np.zeros((n, n, 1, order))
    it = np.ones((n, n))
    r2 = np.full((n, n), np.nan)
    conv = np.zeros((n, n))
    kernel = np.zeros((n, n, t.size))
    for i in range(n):
        for j in range(n):
            coupling = by_pair.get((i, j))
            if coupling is None or coupling.order == 0:
                a[i, j, 0, 0], b[i, j, 0, 0] = -1.0, 1.0
                continue
            o = coupling.order
            a[i, j, :o, :o] = coupling.a
            b[i, j, :o, 0] = coupling.b
            c[i, j, 0, :o] = coupling.c / rho
            it[i, j] = o
            conv[i, j] = 1.0
            kernel[i, j] = coupling.impulse_response(t) / rho
            metric = dict(coupling.metrics).get("r2_damping", dict(coupling.metrics).get("r2_B"))
            if metric is not None:
                r2[i, j] = float(metric)
    return {
        "A": a,
        "B": b,
        "C": c,
        "D": np.zeros((n, n)),
        "K": kernel,
        "it": it,
        "r2t": r2,
        "conv": conv,
    }
