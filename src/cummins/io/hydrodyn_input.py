"""OpenFAST HydroDyn input files (``*_HydroDyn.dat``): which WAMIT files they name.

A HydroDyn input file holds no hydrodynamic coefficients: with ``PotMod = 1`` HydroDyn
reads them from the WAMIT files whose root name is ``PotFile`` (``.1``, ``.3``, ``.hst``,
and the ``.ss``/``.ssexctn`` of ``RdtnMod``/``ExctnMod = 2``), made dimensional with
``WAMITULEN`` and the water density and gravity of the OpenFAST input (Jonkman et al.
(2014), HydroDyn User's Guide and Theory Manual: ``PotMod``, ``PotFile``, ``WAMITULEN``).
A relative ``PotFile`` is relative to the folder of the HydroDyn input file, as OpenFAST
resolves it. cummins is pointed at those files; :func:`hydrodyn_hint` says which.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = ["HydroDynInput", "hydrodyn_hint", "read_hydrodyn_input"]

#: lines read: the floating-platform section comes first in every HydroDyn version
_MAX_LINES = 400


@dataclass(frozen=True)
class HydroDynInput:
    """What a HydroDyn input file says of its potential-flow data.

    Attributes
    ----------
    path
        The HydroDyn input file.
    pot_mod
        ``PotMod`` (0: no potential flow, 1: WAMIT files, 2: FIT), None if absent.
    pot_files
        ``PotFile`` roots, one per body (``NBodyMod > 1``), resolved against the
        folder of ``path``.
    ulen
        ``WAMITULEN`` values, m (as many as given).
    """

    path: Path
    pot_mod: int | None
    pot_files: tuple[Path, ...]
    ulen: tuple[float, ...]


def _values(lines: list[str], key: str) -> list[str]:
    """The values before ``key`` on the first line that names it (HydroDyn's layout
    ``value(s)  KEY  - description``), quotes removed."""
    for line in lines:
        tokens = line.split()
        if key in tokens[1:]:
            return [t.strip("\"'") for t in tokens[: tokens.index(key)]]
    return []


def read_hydrodyn_input(path: str | Path) -> HydroDynInput | None:
    """The potential-flow inputs of a HydroDyn input file, or None if ``path`` is not one.

    A HydroDyn input file is recognised by its first line (``HydroDyn Input File``, as
    OpenFAST writes it) or by a ``PotFile`` entry within its first lines.
    """
    path = Path(path)
    try:
        with path.open("r", encoding="utf-8", errors="replace") as f:
            lines = [line for _, line in zip(range(_MAX_LINES), f, strict=False)]
    except (OSError, UnicodeError):
        return None
    if not lines:
        return None
    pot_files = _values(lines, "PotFile")
    if "hydrodyn" not in lines[0].lower() and not pot_files:
        return None
    pot_mod = _values(lines, "PotMod")
    try:
        mod = int(pot_mod[0]) if pot_mod else None
    except ValueError:
        mod = None
    ulen: list[float] = []
    for value in _values(lines, "WAMITULEN"):
        try:
            ulen.append(float(value))
        except ValueError:
            break
    files = tuple(
        (p if p.is_absolute() else path.parent / p) for p in (Path(v) for v in pot_files if v)
    )
    return HydroDynInput(path, mod, files, tuple(ulen))


def hydrodyn_hint(path: str | Path) -> str | None:
    """What to read instead of a HydroDyn input file (None if ``path`` is not one)."""
    found = read_hydrodyn_input(path)
    if found is None:
        return None
    if found.pot_mod == 0:
        return (
            "an OpenFAST HydroDyn input file with PotMod = 0: it uses no potential-flow "
            "(WAMIT) data, and holds no hydrodynamic coefficients to read"
        )
    if not found.pot_files:
        return (
            "an OpenFAST HydroDyn input file: it holds no hydrodynamic coefficients; read "
            "the WAMIT files its PotFile names (<PotFile>.1, beside its .3 and .hst)"
        )
    commands = []
    for k, root in enumerate(found.pot_files):
        ulen = found.ulen[min(k, len(found.ulen) - 1)] if found.ulen else None
        option = f" --ulen {ulen:g}" if ulen is not None else ""
        commands.append(f"cummins info {root}.1{option}")
    return (
        "an OpenFAST HydroDyn input file: it holds no hydrodynamic coefficients; read the "
        f"WAMIT files its PotFile names (WAMITULEN as --ulen; --rho and --g: WtrDens and "
        f"Gravity of the OpenFAST input), e.g. {'; '.join(commands)}"
    )
