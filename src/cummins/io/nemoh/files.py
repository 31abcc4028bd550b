"""The files of a NEMOH run: their names, detection by content and the run layout.

A NEMOH run folder holds ``Nemoh.cal`` (the input), a ``mesh/`` (or ``Mesh/``) folder
with ``KH.dat`` and ``Hydrostatics.dat`` and a ``results/`` (or ``Results/``) folder with
the Tecplot files; some projects keep everything in one folder, and file names may come
in any case of letters. :func:`sniff` recognises a result file or ``Nemoh.cal`` by its
content, :func:`sniff_dir` the run in a folder, and ``_locate`` finds, from any of them,
the results, ``Nemoh.cal`` and the folders that may hold the companion files.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from cummins.errors import HydroDataError

RADIATION_FILE = "RadiationCoefficients.tec"
_FORCE_FILES = {
    "excitation": "ExcitationForce.tec",
    "diffraction": "DiffractionForce.tec",
    "froude_krylov": "FKForce.tec",
}
_IRF_FILE = "IRF.tec"

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"


# --------------------------------------------------------------------------- detection


def _head(path: Path, size: int = 4096) -> str:
    with open(path, "rb") as f:
        return f.read(size).decode("utf-8-sig", errors="replace")


def _is_tecplot(head: str) -> bool:
    lines = [line.strip() for line in head.splitlines() if line.strip()]
    if not lines or not lines[0].upper().startswith("VARIABLES"):
        return False
    zone = next((line for line in lines if line.lower().startswith("zone")), None)
    if zone is None:
        return False
    zone = zone.lower()
    return any(key in zone for key in ("motion of body", "beta", "fkforce", "dof"))


def _is_nemoh_cal(head: str) -> bool:
    low = head.lower()
    return "--- environment" in low and "number of bodies" in low


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` a NEMOH ``.tec`` result file or a ``Nemoh.cal``?"""
    path = Path(path)
    if not path.is_file():
        return False
    head = _head(path)
    return _is_tecplot(head) or _is_nemoh_cal(head)


def _find(folder: Path, name: str) -> Path | None:
    """The file ``name`` in ``folder``, whatever the case of its letters."""
    exact = folder / name
    if exact.is_file():
        return exact
    if not folder.is_dir():
        return None
    lower = name.lower()
    for candidate in sorted(folder.iterdir()):
        if candidate.name.lower() == lower and candidate.is_file():
            return candidate
    return None


def _subfolder(folder: Path, name: str) -> Path | None:
    for candidate in (folder / name, folder / name.capitalize()):
        if candidate.is_dir():
            return candidate
    if folder.is_dir():
        for candidate in sorted(folder.iterdir()):
            if candidate.is_dir() and candidate.name.lower() == name:
                return candidate
    return None


def sniff_dir(path: Path) -> list[Path]:
    """The NEMOH run in a folder: ``[RadiationCoefficients.tec]`` or ``[]``.

    The folder may be the results folder itself or the run folder holding
    ``Nemoh.cal`` and a ``results/`` subfolder.
    """
    path = Path(path)
    for folder in (path, _subfolder(path, "results")):
        if folder is None:
            continue
        found = _find(folder, RADIATION_FILE)
        if found is not None and sniff(found):
            return [found]
    return []


# --------------------------------------------------------------------------- run layout


@dataclass
class _Run:
    folder: Path  # the run folder (where Nemoh.cal is), else the results folder
    results: Path
    radiation: Path
    cal: Path | None
    mesh_dirs: list[Path] = field(default_factory=list)


def _locate(path: Path) -> _Run:
    if not path.exists():
        raise HydroDataError("no such file or folder", path=path)
    if path.is_dir():
        found = sniff_dir(path)
        if not found:
            raise HydroDataError(
                f"no NEMOH results ({RADIATION_FILE}) in this folder or its results/ subfolder",
                path=path,
            )
        radiation = found[0]
    elif _is_nemoh_cal(_head(path)):
        found = sniff_dir(path.parent)
        if not found:
            raise HydroDataError(
                f"no {RADIATION_FILE} next to this Nemoh.cal or in results/", path=path
            )
        radiation = found[0]
    else:
        radiation = _find(path.parent, RADIATION_FILE)
        if radiation is None:
            raise HydroDataError(
                f"{RADIATION_FILE} not found next to this file",
                path=path,
                hint="cummins needs the added mass and damping of the run; keep the results "
                "folder together",
            )
    results = radiation.parent
    cal = _find(results, "Nemoh.cal") or _find(results.parent, "Nemoh.cal")
    run = cal.parent if cal is not None else results
    mesh_dirs = [d for d in (_subfolder(run, "mesh"), run, results) if d is not None]
    return _Run(run, results, radiation, cal, list(dict.fromkeys(mesh_dirs)))
