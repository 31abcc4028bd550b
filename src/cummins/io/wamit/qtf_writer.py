"""Writing a QTF as a WAMIT ``.12d`` (difference) or ``.12s`` (sum) file, the format
OpenFAST HydroDyn's WAMIT2 module reads (``DiffQTF``/``SumQTF`` = 12).

The file is WAMIT's (:mod:`cummins.io.wamit.second_order`): a title line, then one row
per pair of periods of one triangle (PER1 ≤ PER2, ω₁ ≥ ω₂, as WAMIT writes them), per
heading pair and per mode — ``PER1 PER2 BETA1 BETA2 I Mod Pha Re Im`` — nondimensional,
F̄ = F/(ρ g L^k) (k = 1 for forces, 2 for moments; L the ``ulen`` of the data, default
1 m), phases in degrees, the convention of :mod:`cummins.qtf.data` (WAMIT's and
HydroDyn's: nothing to convert). Periods carry 9 significant digits, values 8, so a file
read back gives the QTF to 10⁻⁷. Only the DOFs the data compute are written
(``dofs_computed``); I numbers the DOFs as the dataset orders them (``body2__Surge`` is
7).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from cummins._version import __version__
from cummins.dofs import is_rotation
from cummins.errors import HydroDataError, check_writable
from cummins.qtf.data import QTF_VARIABLES, qtf_table

SUFFIXES = {".12d": "difference", ".12s": "sum"}


def write_wamit_qtf(
    ds: xr.Dataset,
    path: str | os.PathLike[str],
    kind: str | None = None,
    *,
    force: bool = False,
) -> Path:
    """Write the dataset's QTF of ``kind`` (default: from the suffix, ``.12d`` the
    difference-frequency one, ``.12s`` the sum-frequency one) as a WAMIT file.

    Raises
    ------
    HydroDataError
        The dataset holds no such QTF; an unknown suffix without ``kind``.
    """
    p = Path(path)
    check_writable(p, force)
    kind = kind or SUFFIXES.get(p.suffix.lower())
    if kind not in QTF_VARIABLES:
        raise HydroDataError(
            f"cannot tell which QTF to write to {p.suffix or 'a file without extension'}",
            path=p,
            hint="name it .12d (difference frequencies) or .12s (sum frequencies)",
        )
    if QTF_VARIABLES[kind] not in ds and "drift_force" in ds:
        raise HydroDataError(
            f"the data have no {kind}-frequency QTF ({QTF_VARIABLES[kind]}) to write, only "
            "a mean drift",
            path=p,
            hint="HydroDyn's mean drift and Newman's approximation (MnDrift, NewmanApp = 7, "
            "8 or 9) read WAMIT's .7/.8/.9: cummins convert … x.1 writes them beside the "
            ".1; a BEMIO .h5 holds the drift for WEC-Sim (cummins convert … x.h5)",
        )
    table = qtf_table(ds, kind)
    name = QTF_VARIABLES[kind]
    computed = ds[name].attrs.get("dofs_computed")
    keep = [d for d in table.dofs if not computed or d in str(computed).split()]
    rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
    length = float(ds.attrs.get("ulen", 1.0))
    scale = np.array([rho * g * length ** (2 if is_rotation(d) else 1) for d in table.dofs])
    beta = np.degrees(table.directions)
    m = beta.size
    pairs = (
        [(a, b) for a in range(m) for b in range(m)]
        if table.bidirectional
        else [(a, a) for a in range(m)]
    )
    period = 2 * np.pi / table.omega
    lines = [
        f" WAMIT Numeric Output -- Filename  {p.name}  written by cummins {__version__} "
        f"({kind}-frequency QTF of {Path(str(ds.attrs.get('source_file', ''))).name})"
    ]
    n = table.omega.size
    for a, b in pairs:
        for j in range(n):  # ω₂ increasing: PER2 from the longest period
            for i in range(j, n):  # ω₁ ≥ ω₂: PER1 ≤ PER2
                for k, dof in enumerate(table.dofs):
                    if dof not in keep:
                        continue
                    if table.bidirectional:
                        value = table.values[i, j, a, b, k]
                    else:
                        value = table.values[i, j, a, k]
                    value = complex(value) / scale[k]
                    lines.append(
                        f"{period[i]:16.8E}{period[j]:16.8E}{beta[a]:12.4f}{beta[b]:12.4f}"
                        f"{k + 1:6d}{abs(value):16.7E}{np.degrees(np.angle(value)):16.7E}"
                        f"{value.real:16.7E}{value.imag:16.7E}"
                    )
    tmp = p.with_name(f".{p.name}.tmp")
    try:
        tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
        os.replace(tmp, p)
    except OSError as exc:
        raise HydroDataError(f"cannot write the file ({exc})", path=p) from None
    finally:
        if tmp.exists():
            tmp.unlink()
    return p
