"""ANSYS AQWA-LINE output: the ``.LIS`` listing and the ``.AH1`` hydrodynamic database.

Both files are dimensional, in the unit system of the run (cummins requires the
"Metric: kg, m [N]" system that the listing header states). All matrices and forces
are printed "WITH RESPECT TO STRUCTURE COG": cummins records the centre of gravity as
``reference_point`` (AQWA's fixed reference axes: z up, x and y in the mean free
surface, as cummins).

The ``.LIS`` (:mod:`~cummins.io.aqwa.lis`, the AQWA 19.1 and 2023 R1 layouts, one or
more structures without hydrodynamic interaction) gives the constants, A and B per
frequency, the hydrostatic stiffness, the excitation, diffraction and Froude-Krylov
forces, the motion RAOs, the mass properties and the mean drift; the ``.AH1``
(:mod:`~cummins.io.aqwa.ah1`, any number of structures) the same 5-digit A and B and
excitation amplitudes, but no RAOs and no Froude-Krylov/diffraction split. With the
LHFR option the added mass at 100 rad/s becomes ``added_mass_inf``; the low-frequency
row is not used as A(0) (:mod:`~cummins.io.aqwa.conventions`). The run's ``.QTF`` (the
AQTF option's full difference- and sum-frequency QTFs, :mod:`~cummins.io.aqwa.qtf`) is
read beside either file.

Conventions. AQWA prints phase lags relative to the incident wave at the centre of
gravity: cummins takes X = |X| exp(−iφ) (its exp(+iωt) convention) and refers the
phases to the global origin by adding k (x_G cos β + y_G sin β) to φ
(:mod:`~cummins.io.aqwa.conventions`). Wave directions are directions of propagation,
anticlockwise from +x (0 = following seas), as cummins; AQWA often lists both −180°
and 180°, kept as two directions.

Modules: :mod:`~cummins.io.aqwa.detection` (recognising the files),
:mod:`~cummins.io.aqwa.conventions` (wave number, phase convention, LHFR limits),
:mod:`~cummins.io.aqwa.pages` (a listing's pages by structure, its wave grid),
:mod:`~cummins.io.aqwa.lis` (the listing), :mod:`~cummins.io.aqwa.drift` (its mean
drift), :mod:`~cummins.io.aqwa.ah1` (the database), :mod:`~cummins.io.aqwa.qtf` (the
``.QTF``); this module holds :func:`read_aqwa`.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from cummins.errors import HydroDataError
from cummins.io.aqwa.conventions import ASYMMETRY_LIMIT as ASYMMETRY_LIMIT
from cummins.io.aqwa.conventions import HIGH_FREQUENCY_LIMIT as HIGH_FREQUENCY_LIMIT
from cummins.io.aqwa.conventions import asymmetry as asymmetry
from cummins.io.aqwa.conventions import wavenumber as wavenumber
from cummins.io.aqwa.detection import _head, _is_ah1, _is_lis, _is_qtf, sniff, sniff_dir

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["read_aqwa", "sniff", "sniff_dir"]

# --------------------------------------------------------------------------- reader


def read_aqwa(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
) -> xr.Dataset:
    """Read an AQWA-LINE ``.LIS`` listing or ``.AH1`` database into a ``HydroDB``.

    Parameters
    ----------
    path
        The ``.LIS`` (one structure; gives also RAOs and the Froude-Krylov/diffraction
        split) or the ``.AH1`` file (any number of structures), or a folder holding one
        run (the ``.LIS`` is preferred when both are there).
    rho, g
        Water density (kg/m³) and gravity (m/s²). AQWA's output is dimensional: they
        may only confirm the file's values (a different value is an error).

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB`` about the centre of gravity (``reference_point``), SI,
        exp(+iωt), z-up axes, phases relative to the wave at the global origin.

    Raises
    ------
    HydroDataError
        Unreadable, truncated or inconsistent files, naming file and line.
    """
    path = Path(path)
    if not path.exists():
        raise HydroDataError("no such file or folder", path=path)
    if path.is_dir():
        runs = sniff_dir(path)
        if len(runs) != 1:
            raise HydroDataError(
                f"expected one AQWA run (.LIS or .AH1) in the folder, found {len(runs)}",
                path=path,
                hint="pass the file to read",
            )
        path = runs[0]
    text_head = _head(path, 65536)
    if _is_qtf(text_head):
        runs = [
            p
            for p in path.parent.iterdir()
            if p.stem.lower() == path.stem.lower() and p.suffix.lower() in (".lis", ".ah1")
        ]
        raise HydroDataError(
            "an AQWA .QTF holds only the run's second-order loads",
            path=path,
            hint=(
                f"read {sorted(runs)[-1].name}, which reads the .QTF beside it"
                if runs
                else "read the run's .LIS or .AH1 (same name), which reads the .QTF beside it"
            ),
        )
    # the readers imported here: recognising a file of another format need not load them
    if _is_lis(text_head[:8192]):
        from cummins.io.aqwa.lis import _read_lis

        return _read_lis(path, rho, g)
    if _is_ah1(text_head):
        from cummins.io.aqwa.ah1 import _read_ah1

        return _read_ah1(path, rho, g)
    raise HydroDataError("not an AQWA .LIS or .AH1 file (unrecognised content)", path=path)
