"""What OpenFAST's HydroDyn needs in the WAMIT files it reads (``PotFile``), made from any
``HydroDB`` before :func:`~cummins.io.wamit.numeric_writer.write_wamit` writes them.

* The ``.hst`` holds the restoring of buoyancy and waterplane alone, about the WAMIT
  reference point: ElastoDyn adds the platform's weight itself (OpenFAST HydroDyn user
  documentation, "Floating Platform"). A solver's restoring that holds the weight
  (NEMOH's ``KH``, Capytaine's, WAMIT's with a centre of gravity off the origin) has it
  taken out: :func:`cummins.restoring.hydrostatic_restoring`.
* The ``.1`` holds the zero- and infinite-frequency rows (HydroDyn's input file: "they
  must contain the zero- and infinite-frequency limits"). Data without them get
  PER = 0 (ω = ∞) from Ogilvie's estimate of A∞ (:func:`cummins.added_mass_inf`, the
  median over the frequencies of A(ω) − (2/π) PV∫ B(ν)/(ν² − ω²) dν; de Haan (2022)
  eq. 2.16) and PER = −1 (ω = 0) with A(0) the added mass at the lowest frequency.
  The Kramers–Kronig value A∞ + (2/π) ∫ B(ν)/ν² dν (Hjulstad (2004) eq. 5.23) is not
  used there: with B interpolated linearly from B(0) = 0 the integral diverges like
  log ω at ω → 0, and with B ∝ ω³ below the first frequency it was no closer to the
  solvers' own A(0) than A(ω_min) on seven WAMIT runs of the corpus (docs/formats.md).
  HydroDyn itself takes A∞ from the PER = 0 row and B(ω) from the others.

Each estimate or change is one line of :attr:`HydroDynData.notes` and of ``history``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from cummins.hydrodb import add_history, dof_matrix, single_speed

__all__ = ["HydroDynData", "hydrodyn_data"]


@dataclass(frozen=True)
class HydroDynData:
    """The dataset as HydroDyn reads it, and what was done to it.

    ``notes``: one line per change or estimate; ``assumptions``: what could not be known
    (the caller warns); ``settings``: the HydroDyn inputs the files imply
    (``PtfmRefxt`` …, ``PtfmVol0``, ``PtfmCOBxt`` …) as text lines."""

    ds: xr.Dataset
    notes: tuple[str, ...]
    assumptions: tuple[str, ...]
    settings: tuple[str, ...]


def hydrodyn_data(ds: xr.Dataset, *, limits: bool = True) -> HydroDynData:
    """The data ready to be written as the WAMIT files HydroDyn reads (module docstring).

    Parameters
    ----------
    ds
        A ``HydroDB`` at zero forward speed, in the axes and about the reference point to
        be written.
    limits
        Add the ω = 0 and ω = ∞ rows the data lack (estimated); False leaves the ``.1``
        with the rows the data hold.

    Returns
    -------
    HydroDynData
    """
    from cummins.restoring import hydrostatic_restoring

    ds = single_speed(ds)
    notes: list[str] = []
    assumptions: list[str] = []
    restoring = hydrostatic_restoring(ds)
    ds = restoring.ds
    if restoring.note:
        (notes if restoring.known else assumptions).append(restoring.note)
    if limits:
        ds, added = _with_limit_rows(ds)
        notes += added
    return HydroDynData(ds, tuple(notes), tuple(assumptions), tuple(_settings(ds)))


def _with_limit_rows(ds: xr.Dataset) -> tuple[xr.Dataset, list[str]]:
    """``added_mass_inf`` (Ogilvie) and ``added_mass_zero`` (A at the lowest frequency)
    when the data lack them, each said in one line."""
    from cummins.radiation.infinite_frequency import added_mass_inf

    notes = []
    out = ds
    coords = {"influenced_dof": ds.influenced_dof.values, "radiating_dof": ds.radiating_dof.values}
    units = ds.added_mass.attrs.get("units", "")
    if "added_mass_inf" not in ds:
        estimate = added_mass_inf(ds, method="ogilvie")
        values = np.asarray(estimate.transpose("influenced_dof", "radiating_dof").values)
        spread = np.asarray(estimate.spread.transpose("influenced_dof", "radiating_dof").values)
        diagonal = np.abs(np.diag(values))
        relative = np.diag(spread) / np.where(diagonal > 0, diagonal, 1.0)
        worst = int(np.argmax(relative))
        label = str(ds.influenced_dof.values[worst])
        out = out.assign(
            added_mass_inf=xr.DataArray(
                values,
                dims=("influenced_dof", "radiating_dof"),
                coords=coords,
                attrs={"units": units, "long_name": "A(inf) estimated (Ogilvie), not computed"},
            )
        )
        notes.append(
            "added mass at w = inf (PER = 0 row) estimated from A(w), B(w) (Ogilvie's "
            f"estimate): the data lack it; spread up to {100 * relative[worst]:.2g} % ({label})"
        )
    if "added_mass_zero" not in ds:
        w = np.asarray(ds.omega.values, dtype=float)
        lowest = int(np.argmin(w))
        out = out.assign(
            added_mass_zero=xr.DataArray(
                dof_matrix(ds, "added_mass")[lowest],
                dims=("influenced_dof", "radiating_dof"),
                coords=coords,
                attrs={"units": units, "long_name": f"A at the lowest frequency {w[lowest]:g}"},
            )
        )
        notes.append(
            f"added mass at w = 0 (PER = -1 row) taken as that at the lowest frequency, "
            f"{w[lowest]:.4g} rad/s (T = {2 * np.pi / w[lowest]:.4g} s): the data lack it"
        )
    if notes:
        out = out.copy()
        for line in notes:
            add_history(out, line)
    return out, notes


def _settings(ds: xr.Dataset) -> list[str]:
    """The HydroDyn inputs that must agree with the files: the reference point the moments
    are about, the displaced volume and the centre of buoyancy, when known."""
    from cummins.dofs import bodies

    count = len(bodies(ds))
    ref = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float)
    ref = ref.reshape(-1, 3)
    lines = []
    for name, column in (("PtfmRefxt", 0), ("PtfmRefyt", 1), ("PtfmRefzt", 2)):
        lines.append(f"{name} = {_values(ref[:, column])}")
    volume = np.atleast_1d(np.asarray(ds.attrs.get("displaced_volume", np.nan), dtype=float))
    if volume.size == count and np.all(np.isfinite(volume)):
        lines.append(f"PtfmVol0 = {_values(volume)}")
    cob = ds.attrs.get("center_of_buoyancy")
    if cob is not None:
        cob = np.asarray(cob, dtype=float).reshape(-1, 3)
        if len(cob) == count and np.all(np.isfinite(cob[:, :2])):
            lines.append(f"PtfmCOBxt = {_values(cob[:, 0])}")
            lines.append(f"PtfmCOByt = {_values(cob[:, 1])}")
    return lines


def _values(x) -> str:
    return ", ".join(f"{float(v) + 0.0:.6g}" for v in np.ravel(x))
