"""The WAMIT force control file ``.frc``: alternative form 1 (VCG and radii of gyration
XPRDCT per body) or form 2 (RHO, XCG, then the IMASS, IDAMP, ISTIF matrices), WAMIT User
Manual v7 §4.3–4.4.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from cummins.io.wamit.text import MAX_ABS_VALUE, _leading_numbers, _read_text


@dataclass
class _ForceControl:
    """What cummins uses from a ``.frc`` file (alternative form 1 or 2)."""

    form: int | None = None
    rho: float | None = None
    vcg: list[float] = field(default_factory=list)  # form 1, per body
    radii_of_gyration: list[np.ndarray] = field(default_factory=list)  # form 1, per body
    center_of_gravity: np.ndarray | None = None  # form 2
    mass: np.ndarray | None = None
    damping: np.ndarray | None = None
    stiffness: np.ndarray | None = None


def _read_frc(path: Path, n: int, n_bodies: int, ialtfrc: int | None) -> _ForceControl:
    """Read a ``.frc`` file: alternative form 1 (VCG, radii of gyration XPRDCT per body)
    or form 2 (RHO, XCG, then the IMASS, IDAMP, ISTIF flags each followed by an n×n
    matrix when 1), WAMIT User Manual v7 §4.3–4.4. Damage raises HydroDataError.
    """
    text = _read_text(path)
    rows = [(i, _leading_numbers(line)) for i, line in enumerate(text.lines) if line.strip()]
    rows = rows[1:]  # the title
    if len(rows) < 5:
        raise text.error("too few lines for a .frc file (truncated?)", len(text) - 1)
    (i_opt, ioptn), body = rows[0], rows[1:]
    if len(ioptn) < 1:
        raise text.error("expected the IOPTN option flags", i_opt)
    form = ialtfrc
    if form is None:
        sizes = [len(v) for _, v in body[:3]]
        if sizes[:2] == [1, 3] and sizes[2] == 3:
            form = 1
        elif sizes[:3] == [1, 3, 1]:
            form = 2
        else:
            raise text.error(
                "neither alternative form 1 (VCG, XPRDCT) nor form 2 (RHO, XCG, IMASS …)",
                body[0][0],
            )
    out = _ForceControl(form=form)

    def need(k: int, count: int) -> list[float]:
        if k >= len(body):
            raise text.error("the file ends too early (truncated?)", len(text) - 1)
        i, values = body[k]
        if len(values) != count:
            raise text.error(f"expected {count} numbers, found {len(values)}", i)
        if not np.all(np.isfinite(values)) or np.any(np.abs(values) >= MAX_ABS_VALUE):
            raise text.error("non-finite or implausible value", i)
        return values

    if form == 1:
        k = 0
        for _ in range(n_bodies):
            out.vcg.append(need(k, 1)[0])
            out.radii_of_gyration.append(np.array([need(k + r, 3) for r in (1, 2, 3)]))
            k += 4
        return out
    if form != 2:
        raise text.error(f"alternative form {form} of the .frc is not read", i_opt)
    out.rho = need(0, 1)[0]
    if not out.rho > 0:
        raise text.error(f"RHO = {out.rho:g} is not a density", body[0][0])
    out.center_of_gravity = np.array(need(1, 3))
    k = 2
    matrices = []
    for name in ("IMASS", "IDAMP", "ISTIF"):
        flag = need(k, 1)[0]
        k += 1
        if flag == 1:
            matrix = np.array([need(k + r, n) for r in range(n)])
            if name != "ISTIF" and np.any(np.diag(matrix) < 0):
                # a mass or a damping of the wrong sign: no body has one (a damping that
                # gives energy to the body), a sign lost or flipped in the file
                r = int(np.argmax(np.diag(matrix) < 0))
                what = "mass" if name == "IMASS" else "external damping"
                raise text.error(
                    f"the {what} of mode {r + 1} is negative ({matrix[r, r]:g}): no body "
                    f"has one ({name} matrix damaged?)",
                    body[k + r][0],
                )
            matrices.append(matrix)
            k += n
        elif flag == 0:
            matrices.append(None)
        else:
            raise text.error(f"{name} = {flag:g}: only 0 and 1 are read", body[k - 1][0])
    out.mass, out.damping, out.stiffness = matrices
    return out
