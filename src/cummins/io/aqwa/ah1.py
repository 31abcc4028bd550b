"""The AQWA ``.AH1`` hydrodynamic database (any number of structures; file versions 4, 5).

A ``*`` header, then ``nbodies ndirections nfrequencies`` with the directions and
frequencies (version 5, AQWA 2022 R1: one such block per structure), and keyword
sections GENERAL (depth, ρ, g), COG, COB, DISPLACEMENT, MASS, HYDSTIFFNESS, ADDEDMASS
and DAMPING (records ``body body frequency`` + 6×6), FORCERAO (records ``body direction
frequency``: 6 amplitudes then 6 phases in degrees) and, with LHFR, ADDEDMASS_LF,
DAMPING_LF and ADDEDMASS_HF. It has the same 5-digit A and B as the listing, 5-digit
excitation amplitudes, but no RAOs and no Froude-Krylov/diffraction split. Records
must be in AQWA's fixed formats and its matrices near symmetric
(:data:`ASYMMETRY_LIMIT`). The run's ``.QTF`` beside it (same name) is read as its QTFs
(:mod:`cummins.io.aqwa.qtf`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.hydrodb import dof_labels, make_hydrodb
from cummins.io._common import resolve_rho_g, warn_damage
from cummins.io._text import TextFile, parse_numbers
from cummins.io.aqwa.conventions import (
    _NUMBER,
    ASYMMETRY_LIMIT,
    HIGH_FREQUENCY_LIMIT,
    _complex,
    _depth,
    _limits_history,
    asymmetry,
)
from cummins.io.aqwa.qtf import aqwa_second_order
from cummins.qtf.data import with_second_order
from cummins.restoring import weight_record


@dataclass
class _Section:
    name: str
    rows: list[np.ndarray]
    lines: list[int]


def _ah1_sections(text: TextFile) -> tuple[list[float], list[int], dict[str, _Section], str]:
    """Header numbers, their lines, the keyword sections and the ``*`` header text."""
    header = []
    numbers: list[float] = []
    number_lines: list[int] = []
    sections: dict[str, _Section] = {}
    current: _Section | None = None
    for i, line in enumerate(text.lines):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith("*") and not sections and not numbers:
            header.append(stripped)
            continue
        if re.fullmatch(r"[A-Z][A-Z_0-9]*", stripped):
            if stripped in sections:
                raise text.error(f"section {stripped} appears twice", i)
            current = sections[stripped] = _Section(stripped, [], [])
            continue
        values = parse_numbers(line)
        if values is None:
            raise text.error(f"expected a row of numbers, found {stripped[:60]!r}", i)
        if not np.all(np.isfinite(values)):
            raise text.error("non-finite value (NaN or Inf) in the data", i)
        if current is None:
            numbers.extend(values.tolist())
            number_lines.extend([i] * values.size)
        else:
            current.rows.append(values)
            current.lines.append(i)
    return numbers, number_lines, sections, "\n".join(header)


def _records(text: TextFile, section: _Section, n_index: int, n_rows: int):
    """Records of ``n_rows`` lines: ``n_index`` indices + 6 values, then rows of 6.

    Values are in AQWA's E format (1.2345E+06), except the second row of a FORCERAO
    record (phases, -178.71)."""
    out = []
    r = 0
    rows, lines = section.rows, section.lines
    while r < len(rows):
        first = rows[r]
        if first.size != n_index + 6:
            raise text.error(
                f"{section.name}: expected {n_index} indices and 6 values, "
                f"found {first.size} numbers",
                lines[r],
            )
        index = first[:n_index]
        if np.any(index != np.round(index)) or np.any(index < 1):
            raise text.error(f"{section.name}: indices must be positive whole numbers", lines[r])
        _check_fields(text, section.name, lines[r], n_index, _AH1_FIELDS[0])
        block = [first[n_index:]]
        for extra in range(1, n_rows):
            if r + extra >= len(rows):
                raise text.error(f"{section.name}: record incomplete (truncated?)", lines[-1])
            if rows[r + extra].size != 6:
                raise text.error(
                    f"{section.name}: expected 6 numbers, found {rows[r + extra].size}",
                    lines[r + extra],
                )
            phases = section.name == "FORCERAO" and extra == 1
            _check_fields(text, section.name, lines[r + extra], 0, _AH1_FIELDS[1 if phases else 0])
            block.append(rows[r + extra])
        out.append((index.astype(int), np.vstack(block), lines[r]))
        r += n_rows
    return out


#: The fixed formats AQWA writes the values of an AH1 record in: 1.2345E+06 (matrices,
#: amplitudes) or -178.71 (phases), one format per row.
_AH1_FIELDS = (re.compile(r"-?\d\.\d{4}E[-+]\d\d"), re.compile(r"-?\d+\.\d\d"))


def _check_fields(text: TextFile, section: str, line: int, n_index: int, form) -> None:
    """A record row must be written in AQWA's fixed format ``form`` (a cut number, or a
    row of phases among matrix rows, is not)."""
    fields = text.lines[line].split()[n_index:]
    bad = next((f for f in fields if not form.fullmatch(f)), None)
    if bad is not None:
        raise text.error(
            f"{section}: {bad!r} is not written in AQWA's format for this row (cut, moved or "
            "edited?)",
            line,
        )


def _check_symmetric(text: TextFile, section: _Section, matrices: np.ndarray, omega=None):
    """HydroDataError when a matrix of ``section`` is far from symmetric (rows swapped)."""
    values = asymmetry(matrices)
    worst = int(np.argmax(values))
    if values[worst] > ASYMMETRY_LIMIT:
        where = f" at {omega[worst]:g} rad/s" if omega is not None else ""
        raise text.error(
            f"{section.name}: the matrix{where} is not symmetric (asymmetry "
            f"{values[worst]:.3g}, AQWA's are below {ASYMMETRY_LIMIT:g}): rows swapped or edited?",
            section.lines[0],
        )


def _ah1_require(text: TextFile, sections: dict[str, _Section], name: str) -> _Section:
    if name not in sections or not sections[name].rows:
        raise text.error(f"no {name} section (truncated?)", len(text.lines) - 1)
    return sections[name]


def _ah1_matrices(text, sections, name, nb, nf, with_frequency: bool) -> np.ndarray:
    """ADDEDMASS/DAMPING (nf, 6nb, 6nb) or *_LF/_HF (6nb, 6nb) from their records."""
    section = _ah1_require(text, sections, name)
    n_index = 3 if with_frequency else 2
    shape = (nf, 6 * nb, 6 * nb) if with_frequency else (6 * nb, 6 * nb)
    out = np.full(shape, np.nan)
    for index, block, line in _records(text, section, n_index, 6):
        i, j = index[0] - 1, index[1] - 1
        if i >= nb or j >= nb or (with_frequency and index[2] > nf):
            raise text.error(f"{name}: index {index.tolist()} out of range", line)
        target = out[index[2] - 1] if with_frequency else out
        view = target[6 * i : 6 * i + 6, 6 * j : 6 * j + 6]
        if not np.isnan(view).all():
            raise text.error(f"{name}: record {index.tolist()} appears twice", line)
        view[...] = block
    if np.isnan(out).any():
        where = np.argwhere(np.isnan(out))[0]
        raise text.error(
            f"{name}: missing record for {(where // 6 + 1).tolist()} (truncated?)",
            section.lines[-1],
        )
    _check_symmetric(text, section, out)
    return out


def _ah1_per_body(text, sections, name, nb) -> np.ndarray:
    """MASS / HYDSTIFFNESS: one 6×6 per body (first row prefixed by the body index)."""
    section = _ah1_require(text, sections, name)
    out = np.zeros((6 * nb, 6 * nb))
    records = _records(text, section, 1, 6)
    if len(records) != nb:
        raise text.error(f"{name}: {len(records)} matrices for {nb} bodies", section.lines[-1])
    for index, block, line in records:
        k = index[0] - 1
        if k >= nb:
            raise text.error(f"{name}: body {index[0]} out of range", line)
        out[6 * k : 6 * k + 6, 6 * k : 6 * k + 6] = block
    _check_symmetric(text, section, out)
    return out


def _ah1_points(text, sections, name, nb) -> np.ndarray | None:
    if name not in sections:
        return None
    section = sections[name]
    points = np.full((nb, 3), np.nan)
    for row, line in zip(section.rows, section.lines, strict=True):
        if row.size != 4 or row[0] != round(row[0]) or not 1 <= row[0] <= nb:
            raise text.error(f"{name}: expected 'body x y z'", line)
        points[int(row[0]) - 1] = row[1:]
    if np.isnan(points).any():
        raise text.error(f"{name}: a body is missing", section.lines[-1] if section.lines else None)
    return points


def _ah1_lhfr(header: str) -> tuple[float, float]:
    """Low and high LHFR frequencies (rad/s) stated in the AH1 header (0.001 and 100)."""
    flat = re.sub(r"\s*\n\s*\*\s*", " ", header.upper())
    found = []
    for which, default in (("LOW", 0.001), ("HIGH", 100.0)):
        m = re.search(which + r"-\s*FREQUENCY\s*\((" + _NUMBER + r")\s*RAD/S\)", flat)
        found.append(float(m.group(1)) if m else default)
    return found[0], found[1]


def _ah1_header(text: TextFile, numbers: list[float], lines: list[int]):
    """Bodies, directions (deg) and frequencies (rad/s) of the numeric AH1 header.

    File version 5 (AQWA 2022 R1) writes one block ``body nh nf directions frequencies``
    per structure (``1 3 100 …`` then ``2 3 100 …``); one block whose first number is
    above 1 is read as the older ``nbodies nh nf …`` (one set for all structures).
    """
    blocks = []
    pos = 0
    while pos < len(numbers):
        if len(numbers) - pos < 3:
            raise text.error("expected 'body directions frequencies' in the header", lines[pos])
        first, nh, nf = numbers[pos : pos + 3]
        if min(first, nh, nf) < 1 or any(v != round(v) for v in (first, nh, nf)) or first > 100:
            raise text.error("invalid numbers of bodies, directions or frequencies", lines[pos])
        nh, nf = int(nh), int(nf)
        end = pos + 3 + nh + nf
        if end > len(numbers):
            raise text.error(
                f"expected {nh} directions and {nf} frequencies, found {len(numbers) - pos - 3} "
                "numbers",
                lines[-1],
            )
        blocks.append(
            (
                int(first),
                np.asarray(numbers[pos + 3 : pos + 3 + nh]),
                np.asarray(numbers[pos + 3 + nh : end]),
                lines[pos],
            )
        )
        pos = end
    if len(blocks) == 1:
        return blocks[0][0], blocks[0][1], blocks[0][2]
    for k, (index, directions, omega, line) in enumerate(blocks):
        if index != k + 1:
            raise text.error(f"header block of body {index} where body {k + 1} was expected", line)
        if directions.shape != blocks[0][1].shape or not np.allclose(directions, blocks[0][1]):
            raise text.error("the bodies have different wave directions", line)
        if omega.shape != blocks[0][2].shape or not np.allclose(omega, blocks[0][2]):
            raise text.error("the bodies have different wave frequencies", line)
    return len(blocks), blocks[0][1], blocks[0][2]


def _read_ah1(path: Path, rho, g) -> xr.Dataset:
    text = TextFile.read(path)
    numbers, number_lines, sections, header = _ah1_sections(text)
    if len(numbers) < 3:
        raise text.error("expected 'bodies directions frequencies' after the header")
    nb, directions, omega = _ah1_header(text, numbers, number_lines)
    nh, nf = directions.size, omega.size
    notes: list[str] = []
    version = re.search(r"FILE VERSION NO\s*(\d+)", header)
    history = [
        f"read AQWA hydrodynamic database {path.name} (file version "
        f"{version.group(1) if version else '?'}; {nb} structure{'s' if nb > 1 else ''})"
    ]
    if not any(
        p.suffix.lower() == ".lis" and p.stem.lower() == path.stem.lower()
        for p in path.parent.iterdir()
    ):
        history.append(
            f"no {path.stem}.LIS beside the database: read without what only the listing "
            "holds (motion RAOs, the Froude-Krylov/diffraction split, the structures' names); "
            "rho, g and depth from GENERAL, mass and inertia from MASS, excitation from "
            "FORCERAO"
        )
    general = _ah1_require(text, sections, "GENERAL").rows[0]
    if general.size >= 4:
        depth, rho_f, g_f = general[1:4]
    elif general.size == 3:
        depth, rho_f, g_f = general
    else:
        raise text.error(
            "GENERAL: expected depth, density and gravity", sections["GENERAL"].lines[0]
        )
    if rho_f <= 0 or g_f <= 0 or depth < 0:
        raise text.error(
            "GENERAL: density and gravity must be positive", sections["GENERAL"].lines[0]
        )
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        float(rho_f),
        float(g_f),
        path=path,
        history=history,
        dimensional=True,
    )
    depth = _depth(float(depth))
    cog = _ah1_points(text, sections, "COG", nb)
    if cog is None:
        raise text.error("no COG section: AQWA refers all results to the centre of gravity")
    history.append("matrices and forces about the centre(s) of gravity (COG section)")
    a = _ah1_matrices(text, sections, "ADDEDMASS", nb, nf, True)
    b = _ah1_matrices(text, sections, "DAMPING", nb, nf, True)
    extra: dict = {}
    extra["hydrostatic_stiffness"] = _ah1_per_body(text, sections, "HYDSTIFFNESS", nb)
    if "MASS" in sections:
        extra["inertia_matrix"] = _ah1_per_body(text, sections, "MASS", nb)
        masses = np.diag(extra["inertia_matrix"])[0::6]
        history.append(
            "inertia matrix from the MASS section (about each centre of gravity; mass "
            + ", ".join(f"{m:.6g}" for m in masses)
            + " kg)"
        )
    else:
        history.append("no MASS section: no inertia_matrix")
    low, high = _ah1_lhfr(header)
    if "ADDEDMASS_HF" in sections and high >= HIGH_FREQUENCY_LIMIT:
        extra["added_mass_inf"] = _ah1_matrices(text, sections, "ADDEDMASS_HF", nb, nf, False)
    _limits_history(
        history,
        extra.get("added_mass_inf"),
        high if "ADDEDMASS_HF" in sections else None,
        low if "ADDEDMASS_LF" in sections else None,
        g_v,
    )
    if "FORCERAO" not in sections:
        warn_damage(
            "no FORCERAO section, which AQWA writes after DAMPING: the file seems truncated; "
            "read without the excitation force",
            path=path,
            line=len(text.lines),
            notes=notes,
        )
    else:
        amplitude = np.full((nf, nh, 6 * nb), np.nan)
        phase = np.full_like(amplitude, np.nan)
        for index, block, line in _records(text, sections["FORCERAO"], 3, 2):
            k, h, n = index - 1
            if k >= nb or h >= nh or n >= nf:
                raise text.error(f"FORCERAO: index {index.tolist()} out of range", line)
            if not np.isnan(amplitude[n, h, 6 * k]):
                raise text.error(f"FORCERAO: record {index.tolist()} appears twice", line)
            amplitude[n, h, 6 * k : 6 * k + 6] = block[0]
            phase[n, h, 6 * k : 6 * k + 6] = block[1]
        if np.isnan(amplitude).any():
            n, h, d = np.argwhere(np.isnan(amplitude))[0]
            raise text.error(
                f"FORCERAO: no record for body {d // 6 + 1}, direction {h + 1}, "
                f"frequency {n + 1} (truncated?)",
                sections["FORCERAO"].lines[-1],
            )
        x = np.empty_like(amplitude, dtype=complex)
        for k in range(nb):
            s = slice(6 * k, 6 * k + 6)
            x[..., s] = _complex(
                amplitude[..., s], phase[..., s], omega, directions, cog[k], depth, g_v
            )
        extra["excitation_force"] = x
        extra["wave_direction"] = np.radians(directions)
        history.append(
            "AQWA phase lags converted: X = |X| exp(-i(phase + k(xG cos b + yG sin b))), "
            "phases referred from the centre of gravity to the origin"
        )
    cob = _ah1_points(text, sections, "COB", nb)
    volume = _ah1_volumes(text, sections, nb)
    names = [f"body{k + 1}" for k in range(nb)]

    def flat(points: np.ndarray | None) -> np.ndarray | None:
        return None if points is None else (points.reshape(-1) if nb > 1 else points[0])

    if cog is not None:  # about each G, where the weight's terms vanish: AQWA's matrices
        masses = (
            [float(extra["inertia_matrix"][6 * k, 6 * k]) for k in range(nb)]
            if "inertia_matrix" in extra
            else [np.nan] * nb
        )
        extra.update(weight_record(masses, cog, "AQWA's HYDSTIFFNESS (about each G)"))
    labels = list(dof_labels(names))
    second = aqwa_second_order(path, cgs=cog, depth=depth, g=g_v, dofs=labels, notes=notes)
    ds = make_hydrodb(
        omega,
        a,
        b,
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format="aqwa",
        source_file=str(path),
        dofs=labels,
        reference_point=flat(cog),
        history=history,
        center_of_gravity=flat(cog),
        center_of_buoyancy=flat(cob),
        displaced_volume=volume,
        read_warnings=notes,
        **extra,
    )
    if not (second["tables"] or second["history"]):
        return ds
    return with_second_order(ds, second["tables"], history=second["history"], attrs=second["attrs"])


def _ah1_volumes(text: TextFile, sections: dict[str, _Section], nb: int):
    """Displaced volumes (m³) of the DISPLACEMENT section: a float, one per body, or None."""
    if "DISPLACEMENT" not in sections:
        return None
    section = sections["DISPLACEMENT"]
    volumes = np.full(nb, np.nan)
    for row, line in zip(section.rows, section.lines, strict=True):
        if row.size != 2 or row[0] != round(row[0]) or not 1 <= row[0] <= nb:
            raise text.error("DISPLACEMENT: expected 'body volume'", line)
        volumes[int(row[0]) - 1] = row[1]
    if np.isnan(volumes).any():
        raise text.error("DISPLACEMENT: a body is missing", section.lines[-1])
    return float(volumes[0]) if nb == 1 else volumes
