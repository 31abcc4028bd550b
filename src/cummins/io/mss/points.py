"""Reference point, centre of gravity and centre of buoyancy of an MSS ``vessel`` struct.

``main.CG`` is written in two ways (older files: ``[x_g, y_g, KG]``; newer MSS and
cummins: the FSD vector from CO); :func:`_points` decides which from
``hydrodynamic_reference``, ``vessel.cummins.reference_point`` or the m·r_g block of
``MRB`` (:func:`_rigid_body_cg`), as the docstring of :mod:`cummins.io.mss` explains.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from cummins.errors import HydroDataError
from cummins.io.mss.matfile import _has, _numeric, _scalar, _substruct, _text


def _rigid_body_cg(mrb: NDArray) -> NDArray | None:
    """r_g (FSD, from the matrices' reference point) from MRB = [m I, −m S(r_g); …].

    Each coordinate appears twice in the upper-right block (e.g. m·x_g at (2, 6) and
    −m·x_g at (3, 5), 1-based); mass matrices typed by hand (the tanker's WAMIT ``.frc``)
    sometimes fill only one of them, so a zero entry defers to its partner.
    """
    m = mrb[0, 0]
    if not m > 0:
        return None
    pairs = ((mrb[1, 5], -mrb[2, 4]), (-mrb[0, 5], mrb[2, 3]), (mrb[0, 4], -mrb[1, 3]))
    r_g = [a if b == 0 else b if a == 0 else 0.5 * (a + b) for a, b in pairs]
    return np.asarray(r_g, dtype=float) / m


_FSD = "the FSD vector from CO"
_KEEL = "x_g, y_g, KG (KG: height of G above the keel)"


@dataclass(frozen=True)
class _Points:
    reference: NDArray
    center_of_gravity: NDArray | None
    center_of_buoyancy: NDArray | None


def _points(
    vessel: np.void, main: np.void | None, mrb: NDArray | None, path: Path, history: list[str]
) -> _Points:
    """Reference point, CG and CB in z-down coordinates from CO (see :mod:`cummins.io.mss`)."""

    def vec(name: str) -> NDArray | None:
        if not _has(main, name):
            return None
        v = _numeric(main[name], path, f"vessel.main.{name}").reshape(-1)
        return v if v.size == 3 and np.all(np.isfinite(v)) else None

    cg_raw, cb_raw = vec("CG"), vec("CB")
    cg_raw = None if cg_raw is None else cg_raw + 0.0  # no negative zeros
    cb_raw = None if cb_raw is None else cb_raw + 0.0
    draft = _scalar(main, "T", path, "vessel.main")
    r_g = _rigid_body_cg(mrb) if mrb is not None else None
    extras = _substruct(vessel, "cummins")
    if _has(extras, "reference_point"):
        # Written by write_mss: main.CG is the FSD vector from CO, the data are about
        # the point recorded here.
        ref = _numeric(extras["reference_point"], path, "vessel.cummins.reference_point")
        ref = ref.reshape(-1)
        if ref.size != 3 or not np.all(np.isfinite(ref)):
            raise HydroDataError(
                "expected 3 coordinates", path=path, quantity="vessel.cummins.reference_point"
            )
        history.append(
            f"data about {np.round(ref, 6).tolist()} m (z-down, from CO), as recorded by "
            "cummins in vessel.cummins.reference_point"
        )
        return _Points(ref + 0.0, cg_raw, cb_raw)
    declared = _text(vessel, "hydrodynamic_reference")
    if declared is not None:
        # Newer MSS: main.CG is the FSD vector from CO; matrices about CO or CG.
        cg, cb = cg_raw, cb_raw
        if declared.upper() == "CG" and cg is not None:
            ref = cg.copy()
        else:
            ref = np.zeros(3)
        history.append(
            f"vessel.hydrodynamic_reference = '{declared}': data about "
            f"{np.round(ref, 6).tolist()} m (z-down, from CO)"
        )
        return _Points(ref, cg, cb)
    if cg_raw is None:
        history.append("vessel.main.CG missing: reference point taken as CO")
        return _Points(np.zeros(3), None, None)
    keel = None if draft is None else np.array([cg_raw[0], cg_raw[1], draft - cg_raw[2]])
    options = [(_FSD, cg_raw)] + ([] if keel is None else [(_KEEL, keel)])
    if r_g is None:
        label, cg = options[-1]
        label = f"{label} = {np.round(cg_raw, 6).tolist()} m"
        history.append(
            f"vessel.main.CG read as {label}; MRB has no mass: reference point taken as CO"
        )
        return _Points(np.zeros(3), cg, None)
    label, cg = min(options, key=lambda option: abs(option[1][2] - r_g[2]))
    label = f"{label} = {np.round(cg_raw, 6).tolist()} m"
    # main.CG of VERES-derived files holds single-precision values (7.3000002):
    # round the point to 0.01 mm.
    ref = np.round(cg - r_g, 5) + 0.0
    cb = None
    if cb_raw is not None:
        cb = cb_raw if label == _FSD else np.array([cb_raw[0], cb_raw[1], draft - cb_raw[2]])
    history.append(
        f"vessel.main.CG read as {label}; with r_g = {np.round(r_g, 6).tolist()} m from "
        f"MRB the matrices are about {np.round(ref, 6).tolist()} m (z-down, from CO)"
    )
    return _Points(ref, cg, cb)
