"""NEMOH v3's QTFs: ``results/QTF/OUT_QTFM_N.dat`` (difference) and ``OUT_QTFP_N.dat`` (sum).

NEMOH's QTF post-processor (``QTFpostProc``, Kurnia et al. (2022)) writes one header line
and then, for every generalised force (the ``DOF`` column, numbered over all bodies as
in ``Nemoh.cal``), every pair of wave directions (β₁, β₂) and every pair of frequencies
of one triangle (ω₁ ≥ ω₂), the row ``w1 w2 beta1 beta2 DOF |Q|/(ρg) phase(deg) Re/(ρg)
Im/(ρg)``: the QTF divided by ρ g (N/m² → m), directions in degrees, frequencies in the
unit the QTF section of ``Nemoh.cal`` asks for (the header says: ``w1[rad/s]``, or Hz or
s). Its complex amplitudes follow e^{−iωt} like the first-order ones, so the values are
conjugated to the canonical e^{+iωt} (BEMRosetta's NEMOH reader negates the phases to
"follow WAMIT" alike) and multiplied by ρ g; the other triangle follows from the
symmetries of :mod:`cummins.qtf.data`. The moments are about the rotation point of
``Nemoh.cal``, as the first-order data. Which contributions the total holds (DUOK, HASBO,
HASFS + ASYMP) is the run's choice (``Nemoh.cal``, "Contrib"): without the free-surface
integral (HASFS) the off-diagonal difference QTF lacks part of the second-order potential;
the diagonal (the mean drift) is complete with DUOK alone.

WEC-Sim's copy of the OC3 Hywind run names them ``OUT_QTFM_N_0.dat``: any
``OUT_QTFM_N*.dat`` is read when there is one (several: none, with a note).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError
from cummins.io._common import warn_damage
from cummins.io._text import check_cut_numbers, numeric_table
from cummins.io.wamit.text import _read_text
from cummins.qtf.data import QTFTable, complete_square

_UNITS = (("[rad/s]", "rad/s"), ("[hz]", "Hz"), ("[s]", "s"))


def qtf_files(folder: Path) -> tuple[dict[str, Path], list[str]]:
    """The QTF files of a ``results/QTF`` folder by kind, and notes."""
    notes: list[str] = []
    found: dict[str, Path] = {}
    for kind, letter in (("difference", "M"), ("sum", "P")):
        exact = [p for p in folder.iterdir() if p.name.upper() == f"OUT_QTF{letter}_N.DAT"]
        pattern = re.compile(rf"^OUT_QTF{letter}_N.*\.DAT$", re.IGNORECASE)
        candidates = exact or sorted(p for p in folder.iterdir() if pattern.match(p.name))
        if len(candidates) > 1:
            notes.append(
                f"{kind}-frequency QTF not read: several files in {folder.name} "
                f"({', '.join(p.name for p in candidates)})"
            )
        elif candidates and candidates[0].stat().st_size > 0:
            found[kind] = candidates[0]
    return found, notes


def _frequency_unit(header: str, path: Path) -> str:
    first = header.split()[0].lower() if header.split() else ""
    for token, unit in _UNITS:
        if token in first:
            return unit
    raise HydroDataError(
        f"the header {header.strip()[:40]!r} does not say the unit of the frequency column",
        path=path,
        line=1,
        hint="NEMOH writes 'w1[rad/s]' (or Hz, s) first",
    )


def read_nemoh_qtf(
    path: Path, kind: str, *, force_to_dof: dict[int, int], n_dofs: int, rho: float, g: float
) -> tuple[tuple, list[str], np.ndarray]:
    """One NEMOH QTF file as a :class:`~cummins.qtf.QTFTable` on the dataset's DOFs.

    Parameters
    ----------
    path
        ``OUT_QTFM_N.dat`` or ``OUT_QTFP_N.dat``.
    kind
        ``"difference"`` or ``"sum"``.
    force_to_dof
        Generalised-force number of the file (1-based) → DOF position in the dataset;
        forces without a DOF are not read.
    n_dofs
        Number of DOFs of the dataset.
    rho, g
        ρ and g of the run (the file is divided by ρ g).

    Returns
    -------
    (omega, directions, values, bidirectional), notes, present
        The QTF's grids and full square (dimensional, e^{+iωt}; see
        :func:`cummins.qtf.complete_square`), notes for ``history``, which DOFs it holds.
    """
    text = _read_text(path)
    if not text.lines:
        raise text.error("the file is empty")
    unit = _frequency_unit(text.lines[0], path)
    table, where = numeric_table(text, 1, columns=9)
    check_cut_numbers(text, where, (0, 1, 2, 3, 5, 6, 7, 8))
    w1, w2, b1, b2, force = (table[:, c] for c in range(5))
    modulus, phase, re, im = table[:, 5], table[:, 6], table[:, 7], table[:, 8]
    bad = (force < 1) | (force != np.round(force))
    if bad.any():
        r = int(np.argmax(bad))
        raise text.error(f"DOF {force[r]:g} is not a generalised-force number", where[r])
    value = re + 1j * im
    # the modulus, the phase (degrees, 7 significant digits) and Re, Im must agree
    off = np.abs(np.abs(value) - modulus) > 1e-5 * np.abs(modulus) + 1e-6 * (
        np.abs(modulus).max() + 1e-300
    )
    rebuilt = modulus * np.exp(1j * np.radians(phase))
    off |= np.abs(rebuilt - value) > 1e-4 * np.abs(modulus) + 1e-6 * (
        np.abs(modulus).max() + 1e-300
    )
    if off.any():
        r = int(np.argmax(off))
        raise text.error(
            f"modulus {modulus[r]:g} and phase {phase[r]:g} deg do not match Re, Im "
            f"({re[r]:g}, {im[r]:g}): an edited number?",
            where[r],
        )
    if np.any(np.abs(np.concatenate([b1, b2])) > 720):
        r = int(np.argmax((np.abs(b1) > 720) | (np.abs(b2) > 720)))
        raise text.error("a wave direction beyond ±720 deg is not an angle", where[r])
    if unit == "rad/s":
        o1, o2 = w1, w2
    elif unit == "Hz":
        o1, o2 = 2 * np.pi * w1, 2 * np.pi * w2
    else:
        with np.errstate(divide="ignore"):
            o1, o2 = 2 * np.pi / w1, 2 * np.pi / w2
    if np.any(~np.isfinite(o1) | ~np.isfinite(o2) | (o1 <= 0) | (o2 <= 0)):
        r = int(np.argmax(~np.isfinite(o1 * o2) | (o1 <= 0) | (o2 <= 0)))
        raise text.error(f"frequency {w1[r]:g}, {w2[r]:g} {unit} is not positive", where[r])
    number = force.astype(int)
    keep = np.array([k in force_to_dof for k in number])
    notes = []
    if not keep.all():
        dropped = sorted(set(number[~keep].tolist()))
        notes.append(f"{path.name}: forces {dropped} have no DOF in the data: not read")
    if not keep.any():
        raise text.error("no row of a generalised force the data have")
    dof = np.array([force_to_dof[k] for k in number[keep]])

    def error(message: str, r: int) -> HydroDataError:
        rows = where[keep]
        return text.error(message, int(rows[min(r, rows.size - 1)]))

    omega, directions, values, bidirectional, present = complete_square(
        kind,
        o1[keep],
        o2[keep],
        np.radians(b1[keep]),
        np.radians(b2[keep]),
        dof,
        np.conj(value[keep]) * rho * g,
        n_dofs=n_dofs,
        error=error,
    )
    if unit != "rad/s":
        notes.append(f"{path.name}: frequency columns in {unit}, converted to rad/s")
    return (omega, directions, values, bidirectional), notes, present


def nemoh_second_order(
    results: Path,
    qtf_folder: Path | None,
    *,
    dofs: list[str],
    pick: np.ndarray,
    rho: float,
    g: float,
    notes: list[str],
) -> dict:
    """The QTFs of a NEMOH run for :func:`cummins.qtf.with_second_order` (``tables``,
    ``history``, ``attrs``); a damaged file is left out with a warning in ``notes``."""
    out: dict = {"tables": [], "history": [], "attrs": {}}
    if qtf_folder is None:
        return out
    files, lines = qtf_files(qtf_folder)
    out["history"].extend(lines)
    force_to_dof = {int(f) + 1: position for position, f in enumerate(pick)}
    for kind, path in files.items():
        try:
            (omega, directions, values, bidirectional), lines, present = read_nemoh_qtf(
                path, kind, force_to_dof=force_to_dof, n_dofs=len(dofs), rho=rho, g=g
            )
        except HydroDataError as exc:
            warn_damage(f"{kind}-frequency QTF not read: {exc}", path=path, notes=notes)
            continue
        table = QTFTable(kind, omega, directions, values, tuple(dofs), bidirectional)
        out["tables"].append(table)
        computed = [d for d, p in zip(dofs, present, strict=True) if p]
        out["attrs"][table.name] = {"source": path.name, "dofs_computed": " ".join(computed)}
        out["history"].extend(lines)
        out["history"].append(
            f"{kind}-frequency QTF from {path.relative_to(results.parent)}: {omega.size} "
            f"frequencies {omega[0]:.4g}–{omega[-1]:.4g} rad/s, {directions.size} "
            f"direction(s){' (bi-directional)' if bidirectional else ''}; NEMOH's Q/(rho g) "
            "in exp(-iwt) multiplied by rho g and conjugated"
        )
    return out
