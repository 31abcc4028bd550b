"""Capytaine's legacy exporter files beside a ``.nc``: ``KH*.dat`` and ``Hydrostatics*.dat``.

``capytaine.io.legacy.export_hydrostatics`` writes, per body, the 6×6 hydrostatic
stiffness (``KH.dat`` / ``KH_<i>.dat``) and the centres of buoyancy and gravity and the
displaced volume (``Hydrostatics.dat`` / ``Hydrostatics_<i>.dat``). They complete a
``.nc`` that lacks them and are compared with it otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cummins.io._common import warn_damage
from cummins.io.netcdf.checks import IMPLAUSIBLE
from cummins.io.netcdf.layout import DofLayout


@dataclass(frozen=True)
class LegacyExport:
    """What Capytaine's legacy exporter (``export_hydrostatics``) wrote beside a ``.nc``.

    Attributes
    ----------
    stiffness_files, hydrostatics_files
        ``KH.dat`` or ``KH_0.dat``, ``KH_1.dat`` … and ``Hydrostatics*.dat``, by body.
    stiffness
        The 6×6 matrices (N/m, N, N·m/rad) of the ``KH`` files, in the same order.
    centre_of_buoyancy, centre_of_gravity, volume
        ``XF``/``XG`` columns and ``Displacement`` of the ``Hydrostatics`` files.
    """

    stiffness_files: tuple[Path, ...]
    stiffness: tuple[np.ndarray, ...]
    hydrostatics_files: tuple[Path, ...]
    centre_of_buoyancy: tuple[np.ndarray, ...]
    centre_of_gravity: tuple[np.ndarray, ...]
    volume: tuple[float, ...]

    def attributes(self, layout: DofLayout, where, lines: list[str], notes: list[str]) -> dict:
        """Centres and volume as dataset attributes (one per body)."""
        n = len(layout.body_names)
        if not self.hydrostatics_files:
            return {}
        if len(self.hydrostatics_files) != n:
            warn_damage(
                f"{len(self.hydrostatics_files)} Hydrostatics*.dat files beside the NetCDF "
                f"file for {n} bodies: they are not used",
                path=where,
                notes=notes,
            )
            return {}
        lines.append(
            "centres of gravity and buoyancy and displaced volume from "
            + ", ".join(f.name for f in self.hydrostatics_files)
        )
        volume = np.asarray(self.volume, dtype=float)
        return {
            "center_of_gravity": np.concatenate(self.centre_of_gravity),
            "center_of_buoyancy": np.concatenate(self.centre_of_buoyancy),
            "displaced_volume": float(volume[0]) if n == 1 else volume,
        }

    def stiffness_matrix(self, layout, where, lines, notes, stored):
        """The hydrostatic stiffness in the canonical DOFs: the ``KH`` files' when the
        ``.nc`` has none (None otherwise, after comparing them with the stored one)."""
        n = len(layout.body_names)
        if not self.stiffness_files:
            return None
        names = ", ".join(f.name for f in self.stiffness_files)
        if len(self.stiffness_files) != n:
            warn_damage(
                f"{len(self.stiffness_files)} KH*.dat files ({names}) beside the NetCDF file "
                f"for {n} bodies: they are not used",
                path=where,
                notes=notes,
            )
            return None
        size = len(layout.labels)
        full = np.zeros((size, size))
        for body, matrix in enumerate(self.stiffness):
            block = layout.rigid_block(body)
            if block is None:
                return None
            full[np.ix_(block, block)] = matrix
        if stored is None:
            lines.append(f"hydrostatic_stiffness from {names} (not in the NetCDF file)")
            return full
        values = np.asarray(stored.values, dtype=float)
        # the KH files print 7 significant digits (%E): agreement to 1e-6 of the block scale
        for body, (path, matrix) in enumerate(
            zip(self.stiffness_files, self.stiffness, strict=True)
        ):
            block = layout.rigid_block(body)
            if block is None:
                continue
            part = values[np.ix_(block, block)]
            scale = max(float(np.nanmax(np.abs(matrix))), 1e-300)
            with np.errstate(invalid="ignore"):
                off = np.abs(part - matrix) > 1e-6 * scale + 1e-6 * np.abs(matrix)
            if off.any():
                i, j = (int(x) for x in np.argwhere(off)[0])
                warn_damage(
                    f"hydrostatic_stiffness[{layout.labels[block[i]]}, "
                    f"{layout.labels[block[j]]}] = {part[i, j]!r} but {path.name} gives "
                    f"{matrix[i, j]!r}: the NetCDF file's value is used",
                    path=where,
                    notes=notes,
                    hint="one of the two files is damaged",
                )
                return None
        lines.append(f"hydrostatic_stiffness agrees with {names}")
        return None


def _legacy_exporter_files(folder: Path) -> LegacyExport | None:
    """The ``KH*.dat`` and ``Hydrostatics*.dat`` files of Capytaine's legacy exporter."""
    if any((folder / name).is_file() for name in ("Nemoh.cal", "nemoh.cal")):
        return None  # NEMOH's own KH.dat / Hydrostatics.dat, not Capytaine's exporter
    stiffness_files = _numbered(folder, "KH")
    hydro_files = _numbered(folder, "Hydrostatics")
    if not stiffness_files and not hydro_files:
        return None
    stiffness = tuple(_read_kh(f) for f in stiffness_files)
    parsed = [_read_hydrostatics(f) for f in hydro_files]
    return LegacyExport(
        tuple(stiffness_files),
        stiffness,
        tuple(hydro_files),
        tuple(p[0] for p in parsed),
        tuple(p[1] for p in parsed),
        tuple(p[2] for p in parsed),
    )


def _numbered(folder: Path, stem: str) -> list[Path]:
    """``<stem>_0.dat``, ``<stem>_1.dat`` … in order, or ``[<stem>.dat]``."""
    numbered = []
    k = 0
    while (folder / f"{stem}_{k}.dat").is_file():
        numbered.append(folder / f"{stem}_{k}.dat")
        k += 1
    if numbered:
        return numbered
    single = folder / f"{stem}.dat"
    return [single] if single.is_file() else []


def _without_bom(text):
    """The text without a UTF-8 byte-order mark (an encoding, not damage)."""
    if text.lines and text.lines[0].startswith("\ufeff"):
        return type(text)(text.path, (text.lines[0][1:], *text.lines[1:]))
    return text


def _read_kh(path: Path) -> np.ndarray:
    from cummins.io._text import TextFile

    text = _without_bom(TextFile.read(path))
    rows = [k for k, line in enumerate(text.lines) if line.strip()]
    if len(rows) != 6:
        raise text.error(
            f"expected 6 rows of the 6x6 hydrostatic stiffness, found {len(rows)}",
            rows[-1] if rows else 0,
        )
    matrix = np.empty((6, 6))
    for r, k in enumerate(rows):
        values = text.numbers(k, 6)
        if not np.all(np.isfinite(values)) or np.any(np.abs(values) > IMPLAUSIBLE):
            raise text.error("not a finite stiffness value", k)
        matrix[r] = values
    return matrix


def _read_hydrostatics(path: Path) -> tuple[np.ndarray, np.ndarray, float]:
    """``XF = … - XG = …`` (three lines: x, y, z) and ``Displacement = …``."""
    import re

    from cummins.io._text import TextFile

    text = _without_bom(TextFile.read(path))
    pattern = re.compile(r"^\s*[XYZ]F\s*=\s*(\S+)\s*-\s*[XYZ]G\s*=\s*(\S+)\s*$", re.IGNORECASE)
    buoyancy, gravity, volume = [], [], None
    for k, line in enumerate(text.lines):
        if not line.strip():
            continue
        match = pattern.match(line)
        if match and len(buoyancy) < 3:
            try:
                buoyancy.append(float(match.group(1)))
                gravity.append(float(match.group(2)))
            except ValueError:
                raise text.error("expected 'XF = <number> - XG = <number>'", k) from None
            continue
        if line.strip().lower().startswith("displacement") and volume is None:
            try:
                volume = float(line.split("=", 1)[1].split()[0])
            except (IndexError, ValueError):
                raise text.error("expected 'Displacement = <volume>'", k) from None
            continue
        if "=" in line and volume is not None:
            continue  # further "name = value" lines (waterplane area, mass …) are not used
        raise text.error("expected three lines 'XF = … - XG = …' and 'Displacement = …'", k)
    centres = np.array(buoyancy + gravity, dtype=float)
    if len(buoyancy) != 3 or volume is None:
        raise text.error(
            "expected three lines 'XF = … - XG = …' (x, y, z) and 'Displacement = …'",
            len(text) - 1,
        )
    if not np.all(np.isfinite(centres)) or not (np.isfinite(volume) and volume > 0):
        raise text.error("non-finite centre or non-positive displacement", len(text) - 1)
    return np.array(buoyancy), np.array(gravity), float(volume)
