"""WAMIT output: numeric files ``.1`` ``.3`` ``.hst`` (with ``.frc``) and the ``.out`` log.

WAMIT writes nondimensional numbers (WAMIT User Manual, ch. 4). With L the length
scale ULEN, ρ the density and g gravity, and k = 0 for translations, 1 for rotations:

* added mass       A = Ā ρ L^(3+k_i+k_j)          (``.1``, periods −1 → ω = 0, 0 → ω = ∞)
* damping          B = B̄ ρ ω L^(3+k_i+k_j)        (``.1``)
* excitation       X = X̄ ρ g L^(2+k_i)            (``.3``, per metre of wave amplitude)
* hydrostatics     C = C̄ ρ g L^(2+k_i+k_j)        (``.hst``)
* motion RAO       ξ = ξ̄ / L^k_i                  (``.out``)
* mean drift       F = F̄ ρ g L^(1+k_i)            (``.out``, per squared amplitude)

Time dependence is Re{X e^{iωt}}, as in cummins. Wave heading β is the direction of
propagation from +x (0 = following seas), as in cummins. Axes are x forward, y to port,
z up; moments are about the body origin (XBODY, YBODY, ZBODY), which cummins records
as the ``reference_point`` in global coordinates (origin on the mean free surface).

WAMIT does not write the water density in its numeric files (version 7 not even in
the ``.out``): ρ comes from the ``.out`` (version 6), else from the ``.frc``, else
from ``rho=``, else 1025 kg/m³, and the dataset's ``history`` says which.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import dof_labels, make_hydrodb
from cummins.io._common import (
    force_exponents,
    length_exponents,
    resolve_constant,
    resolve_rho_g,
)
from cummins.io._text import TextFile, numeric_table, parse_numbers

__all__ = ["read_wamit", "read_wamit_out", "sniff", "sniff_dir"]

_NUMERIC_KINDS = {".1": 4, ".3": 7, ".hst": 3}


# --------------------------------------------------------------------------- detection


def _first_data_line(path: Path, max_lines: int = 5) -> tuple[str, list[str]]:
    head: list[str] = []
    with open(path, "rb") as f:
        for _ in range(max_lines):
            raw = f.readline()
            if not raw:
                break
            head.append(raw.decode("utf-8", errors="replace"))
    return (head[0] if head else ""), head


def numeric_kind(path: str | os.PathLike[str]) -> str | None:
    """Which WAMIT numeric file ``path`` is by its content: ``".1"``, ``".3"``, ``".hst"``.

    ``.1`` rows are ``PER I J A [B]``, ``.3`` rows ``PER BETA I Mod Pha Re Im`` and
    ``.hst`` rows ``I J C``; the integer columns must hold DOF indices.
    """
    try:
        first, head = _first_data_line(Path(path))
    except OSError:
        return None
    lines = head[1:] if "WAMIT" in first else head
    rows = [parse_numbers(line) for line in lines if line.strip()]
    rows = [r for r in rows if r is not None]
    if not rows or any(r is None for r in rows):
        return None

    def is_dof(x: float) -> bool:
        return float(x).is_integer() and 1 <= x <= 600

    widths = {r.size for r in rows}
    if widths <= {4, 5} and all(is_dof(r[1]) and is_dof(r[2]) for r in rows):
        return ".1"
    if widths == {7} and all(is_dof(r[2]) for r in rows):
        return ".3"
    if widths == {3} and all(is_dof(r[0]) and is_dof(r[1]) for r in rows):
        return ".hst"
    return None


def is_out_file(path: str | os.PathLike[str]) -> bool:
    """True if ``path`` is a WAMIT ``.out`` log (by its banner)."""
    try:
        with open(path, "rb") as f:
            head = f.read(4096).decode("utf-8", errors="replace")
    except OSError:
        return False
    return "WAMIT" in head and ("Version" in head or "POTEN" in head or "Output from" in head)


def sniff(path: Path) -> bool:
    """Content-based test: is ``path`` a WAMIT numeric file (``.1``, ``.3``, ``.hst``)?"""
    return numeric_kind(path) is not None


def sniff_dir(path: Path) -> list[Path]:
    """The WAMIT runs in a directory: one ``.1`` file per run (else ``.out`` files)."""
    ones = sorted(p for p in path.glob("*.1") if numeric_kind(p) == ".1")
    if ones:
        return ones
    return sorted(p for p in path.glob("*.out") if is_out_file(p))


# --------------------------------------------------------------------------- constants


@dataclass
class _OutHeader:
    """Constants and body parameters printed in a ``.out`` header."""

    g: float | None = None
    ulen: float | None = None
    rho: float | None = None
    water_depth: float | None = None
    body_origin: list[np.ndarray] = field(default_factory=list)
    center_of_gravity: list[np.ndarray] = field(default_factory=list)
    center_of_buoyancy: list[np.ndarray] = field(default_factory=list)
    volume: list[float] = field(default_factory=list)
    hydrostatics: list[dict[tuple[int, int], float]] = field(default_factory=list)
    irregular_frequency_removal: bool | None = None


_FLOAT = r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?)"


def _out_header(text: TextFile) -> _OutHeader:
    h = _OutHeader()
    stop = text.find(r"Output from\s+WAMIT")
    stop = len(text) if stop < 0 else stop
    for i in range(stop):
        line = text.lines[i]
        if m := re.search(r"Gravity:\s*" + _FLOAT, line):
            h.g = float(m.group(1))
        if m := re.search(r"Length scale:\s*" + _FLOAT, line):
            h.ulen = float(m.group(1))
        if m := re.search(r"Water depth:\s*(infinite|" + _FLOAT[1:-1] + ")", line):
            h.water_depth = np.inf if m.group(1) == "infinite" else float(m.group(1))
        if m := re.search(r"Water density:\s*" + _FLOAT, line):
            h.rho = float(m.group(1))
        if m := re.search(r"IRR\s*=\s*(\d+)", line):
            h.irregular_frequency_removal = int(m.group(1)) > 0
        if "XBODY" in line:
            vals = re.findall(r"[XYZ]BODY\s*=\s*" + _FLOAT, line)
            if len(vals) == 3:
                h.body_origin.append(np.array([float(v) for v in vals]))
        if line.strip().startswith("Volumes"):
            nums = parse_numbers(line.split(":", 1)[1])
            if nums is not None and nums.size:
                h.volume.append(float(nums[-1]))
        if "Center of Buoyancy" in line:
            h.center_of_buoyancy.append(_three_after_colon(text, i))
        if "Center of Gravity" in line:
            h.center_of_gravity.append(_three_after_colon(text, i))
        if "Hydrostatic and gravitational restoring" in line:
            h.hydrostatics.append(_out_hydrostatics(text, i + 1))
    return h


def _three_after_colon(text: TextFile, i: int) -> np.ndarray:
    nums = parse_numbers(text.lines[i].split(":", 1)[1])
    if nums is None or nums.size != 3:
        raise text.error("expected three coordinates after the colon", i)
    return nums


def _out_hydrostatics(text: TextFile, i: int) -> dict[tuple[int, int], float]:
    """The three ``C(3,3),C(3,4),C(3,5): …`` lines of a ``.out`` header."""
    entries: dict[tuple[int, int], float] = {}
    for k in range(i, min(i + 3, len(text))):
        line = text.lines[k]
        if ":" not in line:
            break
        names, values = line.split(":", 1)
        pairs = re.findall(r"C\((\d),(\d)\)", names)
        nums = parse_numbers(values)
        if nums is None or len(pairs) != nums.size:
            raise text.error("unreadable hydrostatic coefficients", k)
        for (a, b), v in zip(pairs, nums, strict=True):
            entries[(int(a), int(b))] = float(v)
    return entries


def _hydrostatics_from_out(entries: dict[tuple[int, int], float]) -> np.ndarray:
    """6×6 nondimensional C from the upper-triangle entries printed in the ``.out``.

    C34, C35 and C45 are symmetric (pure hydrostatics); C46 and C56 are the
    gravitational moments WAMIT adds, which have no symmetric counterpart (as in the
    ``.hst`` file).
    """
    c = np.zeros((6, 6))
    for (i, j), v in entries.items():
        c[i - 1, j - 1] = v
        if (i, j) in {(3, 4), (3, 5), (4, 5)}:
            c[j - 1, i - 1] = v
    return c


# --------------------------------------------------------------------------- numeric files


def _period_blocks(
    text: TextFile, periods: np.ndarray, where: np.ndarray, key_columns: np.ndarray
) -> list[tuple[float, np.ndarray]]:
    """Group row indices by period; reject duplicate keys and interleaved blocks."""
    blocks: list[tuple[float, list[int]]] = []
    seen_at: dict[float, int] = {}
    keys_seen: dict[tuple, int] = {}
    for r, per in enumerate(periods):
        key = (per, *key_columns[r])
        if key in keys_seen:
            raise text.error(
                f"entry {tuple(float(k) for k in key)} appears twice (first on line "
                f"{where[keys_seen[key]] + 1})",
                where[r],
                hint="the file is damaged or two runs were joined",
            )
        keys_seen[key] = r
        if not blocks or blocks[-1][0] != per:
            if per in seen_at:
                raise text.error(
                    f"rows of period {per:g} s are not contiguous (also on line "
                    f"{where[seen_at[per]] + 1}): the period column is out of order",
                    where[r],
                    hint="WAMIT writes one block per period; the file seems edited or damaged",
                )
            seen_at[per] = r
            blocks.append((per, []))
        blocks[-1][1].append(r)
    return [(p, np.asarray(rows)) for p, rows in blocks]


def _dof_count(text: TextFile, indices: np.ndarray, where: np.ndarray) -> int:
    if indices.size == 0:
        raise text.error("no data rows")
    bad = (indices < 1) | (indices != np.round(indices))
    if bad.any():
        r = int(np.argmax(bad.any(axis=1) if bad.ndim > 1 else bad))
        raise text.error("DOF index must be a positive integer", where[r])
    n = int(indices.max())
    return 6 * int(np.ceil(n / 6))


def _omega_from_first_column(text: TextFile, values: np.ndarray, where, first_column: str):
    if first_column == "period":
        with np.errstate(divide="ignore"):
            return 2 * np.pi / values
    if first_column == "omega":
        return values
    raise HydroDataError(f"first_column must be 'period' or 'omega', got {first_column!r}")


def _read_dot1(path: Path, first_column: str):
    """Parse a ``.1`` file: per-period nondimensional A (and B) matrices."""
    text = TextFile.read(path)
    start = 1 if "WAMIT" in text.lines[0] else 0
    table, where = numeric_table(text, start, columns=(4, 5))
    per = table[:, 0]
    finite_period = per > 0
    missing_b = finite_period & np.isnan(table[:, 4])
    if missing_b.any():
        raise text.error(
            "a row at a finite period needs both added mass and damping (5 numbers)",
            where[np.argmax(missing_b)],
        )
    if (per < 0).any() and not np.all(per[per < 0] == -1):
        raise text.error(
            "negative period other than -1 (the zero-frequency marker)", where[np.argmax(per < -1)]
        )
    ij = table[:, 1:3]
    n = _dof_count(text, ij, where)
    blocks = _period_blocks(text, per, where, ij)
    pairs_of = {p: {tuple(ij[r]) for r in rows} for p, rows in blocks}
    finite = [(p, rows) for p, rows in blocks if p > 0]
    if not finite:
        raise text.error("no finite period in the file: nothing to build A(ω), B(ω) from")
    reference_pairs = pairs_of[finite[0][0]]
    for p, rows in finite[1:]:
        if pairs_of[p] != reference_pairs:
            missing = sorted(reference_pairs - pairs_of[p])
            detail = (
                f"entry (i, j) = {tuple(int(x) for x in missing[0])} missing"
                if missing
                else ("entries differ from the first period")
            )
            raise text.error(
                f"period {p:g} s does not have the same entries as period {finite[0][0]:g} s: "
                f"{detail} (truncated file?)",
                where[rows[-1]],
            )
    values = []
    for p, rows in finite:
        a = np.zeros((n, n))
        b = np.zeros((n, n))
        i = ij[rows, 0].astype(int) - 1
        j = ij[rows, 1].astype(int) - 1
        a[i, j] = table[rows, 3]
        b[i, j] = table[rows, 4]
        values.append((p, a, b))
    limits = {}
    for p, rows in blocks:
        if p <= 0:
            a = np.zeros((n, n))
            a[ij[rows, 0].astype(int) - 1, ij[rows, 1].astype(int) - 1] = table[rows, 3]
            limits[p] = a
    first = np.array([p for p, _, _ in values])
    omega = _omega_from_first_column(text, first, where, first_column)
    order = np.argsort(omega)
    return (
        text,
        first[order],
        omega[order],
        np.stack([values[k][1] for k in order]),
        np.stack([values[k][2] for k in order]),
        limits.get(-1.0),
        limits.get(0.0),
        n,
    )


def _read_dot3(path: Path, first_values: np.ndarray, n: int):
    """Parse a ``.3`` file: nondimensional complex excitation per period and heading."""
    text = TextFile.read(path)
    start = 1 if "WAMIT" in text.lines[0] else 0
    table, where = numeric_table(text, start, columns=7)
    per, beta, dof = table[:, 0], table[:, 1], table[:, 2]
    _period_blocks(text, per, where, table[:, 1:3])
    if dof.max() > n or dof.min() < 1 or np.any(dof != np.round(dof)):
        r = int(np.argmax((dof > n) | (dof < 1) | (dof != np.round(dof))))
        raise text.error(f"DOF index {dof[r]:g} does not exist in the .1 file", where[r])
    headings = np.unique(beta)
    periods_here = np.unique(per)
    wanted = set(first_values.tolist())
    extra = sorted(set(periods_here.tolist()) - wanted)
    missing = sorted(wanted - set(periods_here.tolist()))
    if extra:
        r = int(np.argmax(per == extra[0]))
        raise text.error(
            f"period {extra[0]:g} s is not in the .1 file",
            where[r],
            hint="the .1 and .3 files must come from the same run",
        )
    if missing:
        raise text.error(
            f"no excitation for period {missing[0]:g} s of the .1 file (truncated file?)",
            len(text) - 1,
        )
    x = np.zeros((first_values.size, headings.size, n), dtype=complex)
    by_value = np.argsort(first_values)  # every period of the .3 is in first_values (checked)
    k = by_value[np.searchsorted(first_values[by_value], per)]
    h = np.searchsorted(headings, beta)
    x[k, h, dof.astype(int) - 1] = table[:, 5] + 1j * table[:, 6]
    filled = np.zeros((first_values.size, headings.size), dtype=bool)
    filled[k, h] = True
    if not filled.all():
        kk, hh = np.argwhere(~filled)[0]
        raise text.error(
            f"no excitation at period {first_values[kk]:g} s, heading {headings[hh]:g} deg "
            "(truncated file?)",
            len(text) - 1,
        )
    return x, np.radians(headings)


def _read_hst(path: Path, n: int) -> np.ndarray:
    text = TextFile.read(path)
    start = 1 if "WAMIT" in text.lines[0] else 0
    table, where = numeric_table(text, start, columns=3)
    ij = table[:, :2]
    if np.any(ij < 1) or np.any(ij > n) or np.any(ij != np.round(ij)):
        r = int(np.argmax(((ij < 1) | (ij > n) | (ij != np.round(ij))).any(axis=1)))
        raise text.error(f"DOF index out of range 1…{n}", where[r])
    c = np.zeros((n, n))
    c[ij[:, 0].astype(int) - 1, ij[:, 1].astype(int) - 1] = table[:, 2]
    return c


@dataclass
class _ForceControl:
    """What cummins uses from a ``.frc`` file (alternative form 2)."""

    rho: float | None = None
    center_of_gravity: np.ndarray | None = None
    mass: np.ndarray | None = None
    damping: np.ndarray | None = None
    stiffness: np.ndarray | None = None
    note: str | None = None


def _read_frc(path: Path) -> _ForceControl:
    """Read the density, CG and external mass/damping/stiffness of a ``.frc`` file.

    Alternative form 2 (``RHO``, ``XCG YCG ZCG``, ``IMASS`` + 6×6 …) is read; for
    form 1 (radii of gyration) only the note that it was not used is returned.
    """
    text = TextFile.read(path)
    out = _ForceControl()
    try:
        rho = text.numbers(2, 1)
        cg = text.numbers(3, 3)
        imass = text.numbers(4)
    except HydroDataError:
        out.note = f"{path.name}: not read (not alternative form 2 of the .frc)"
        return out
    if imass.size != 1:
        out.note = f"{path.name}: alternative form 1 (radii of gyration) is not read"
        return out
    out.rho, out.center_of_gravity = float(rho[0]), cg
    line = 4
    matrices = []
    for _ in range(3):
        flag = text.numbers(line, 1)[0]
        line += 1
        if flag == 1:
            matrices.append(np.vstack([text.numbers(line + k, 6) for k in range(6)]))
            line += 6
        else:
            matrices.append(None)
    out.mass, out.damping, out.stiffness = matrices
    return out


def _sibling(path: Path, suffix: str) -> Path | None:
    for candidate in (path.with_suffix(suffix), path.with_suffix(suffix.upper())):
        if candidate.is_file():
            return candidate
    return None


def read_wamit(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    first_column: str = "period",
    siblings: bool = True,
) -> xr.Dataset:
    """Read a WAMIT run into a canonical ``HydroDB``.

    Parameters
    ----------
    path
        A ``.1`` file (its ``.3``, ``.hst``, ``.frc`` and ``.out`` siblings with the
        same stem are read too, unless ``siblings=False``), a ``.3`` or ``.hst`` file
        (then the ``.1`` sibling is required), or a ``.out`` file (read on its own, see
        :func:`read_wamit_out`).
    rho, g, ulen
        Water density (kg/m³), gravity (m/s²) and WAMIT length scale ULEN (m) used to
        make the numbers dimensional. By default they come from the ``.out`` header
        (ρ also from the ``.frc``), else ρ = 1025, g = 9.81, ULEN = 1.
    first_column
        What the first column of the numeric files holds: ``"period"`` (s, WAMIT's
        default, IPEROUT=1) or ``"omega"`` (rad/s, IPEROUT=2).
    siblings
        Read the sibling files of a ``.1`` file.

    Returns
    -------
    xarray.Dataset
        Canonical ``HydroDB``, z-up axes, about the body origin.

    Examples
    --------
    >>> import cummins
    >>> ds = cummins.read(cummins.demo_files() / "tanker.1")
    >>> float(ds.attrs["rho"])
    1025.0
    """
    path = Path(path)
    if not path.exists():
        raise HydroDataError("file not found", path=path)
    if is_out_file(path):
        return read_wamit_out(path, rho=rho, g=g, ulen=ulen)
    kind = numeric_kind(path)
    if kind is None:
        raise HydroDataError(
            "not a WAMIT .1, .3, .hst or .out file (unrecognised content)", path=path
        )
    dot1 = path if kind == ".1" else _sibling(path, ".1")
    if dot1 is None:
        raise HydroDataError(
            f"a WAMIT {kind} file alone has no added mass and damping",
            path=path,
            hint=f"put the .1 file of the same run next to it ({path.with_suffix('.1').name})",
        )
    read_siblings = siblings or kind != ".1"
    dot3 = (path if kind == ".3" else _sibling(dot1, ".3")) if read_siblings else None
    hst = (path if kind == ".hst" else _sibling(dot1, ".hst")) if read_siblings else None
    out_path = _sibling(dot1, ".out") if read_siblings else None
    frc_path = _sibling(dot1, ".frc") if read_siblings else None

    history: list[str] = [f"read {dot1.name}"]
    header = _OutHeader()
    if out_path is not None and is_out_file(out_path):
        header = _out_header(TextFile.read(out_path))
        history.append(f"constants and body parameters from {out_path.name}")
    frc = _read_frc(frc_path) if frc_path is not None else _ForceControl()
    if frc.note:
        history.append(frc.note)
    rho_in_file = header.rho if header.rho is not None else frc.rho
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        rho_in_file,
        header.g,
        path=dot1,
        history=history,
        dimensional=False,
    )
    L = resolve_constant(
        "ulen", ulen, header.ulen, 1.0, unit="m", path=dot1, history=history, dimensional=False
    )

    _, first_vals, omega, a_bar, b_bar, a_zero, a_inf, n = _read_dot1(dot1, first_column)
    scale_a = rho_v * L ** length_exponents(n, 3)
    added_mass = a_bar * scale_a
    damping = b_bar * scale_a * omega[:, None, None]

    extra: dict = {}
    if a_inf is not None:
        extra["added_mass_inf"] = a_inf * scale_a
    if a_zero is not None:
        extra["added_mass_zero"] = a_zero * scale_a
    if dot3 is not None:
        x_bar, beta = _read_dot3(dot3, first_vals, n)
        extra["excitation_force"] = x_bar * (rho_v * g_v * L ** force_exponents(n, 2))
        extra["wave_direction"] = beta
        history.append(f"excitation from {dot3.name}")
    if hst is not None:
        extra["hydrostatic_stiffness"] = _read_hst(hst, n) * (
            rho_v * g_v * L ** length_exponents(n, 2)
        )
        history.append(f"hydrostatics from {hst.name}")
    if frc.mass is not None and n == 6:
        extra["inertia_matrix"] = frc.mass
        history.append(f"inertia matrix from {frc_path.name} (IMASS)")
    if frc.damping is not None and n == 6 and np.any(frc.damping):
        extra["additional_damping"] = np.broadcast_to(frc.damping, (omega.size, 6, 6))
        history.append(f"external damping from {frc_path.name} (IDAMP) as additional_damping")
    if frc.stiffness is not None and n == 6 and np.any(frc.stiffness):
        extra["additional_stiffness"] = frc.stiffness
        history.append(f"external stiffness from {frc_path.name} (ISTIF)")

    return make_hydrodb(
        omega,
        added_mass,
        damping,
        rho=rho_v,
        g=g_v,
        water_depth=header.water_depth if header.water_depth is not None else np.inf,
        source_format="wamit",
        source_file=str(dot1),
        dofs=dof_labels([f"body{k + 1}" for k in range(n // 6)]),
        history=history,
        ulen=L,
        **extra,
        **_body_attrs(header, frc, n),
    )


def _body_attrs(header: _OutHeader, frc: _ForceControl, n: int) -> dict:
    """Reference point, CG, CB in global coordinates (origin on the free surface)."""
    nb = n // 6
    origin = np.zeros((nb, 3))
    for k, o in enumerate(header.body_origin[:nb]):
        origin[k] = o
    attrs: dict = {"reference_point": origin.reshape(-1) if nb > 1 else origin[0]}
    cg = header.center_of_gravity[:nb]
    if not cg and frc.center_of_gravity is not None and nb == 1:
        cg = [frc.center_of_gravity]
    if len(cg) == nb:
        attrs["center_of_gravity"] = (np.vstack(cg) + origin).reshape(-1)
    cb = header.center_of_buoyancy[:nb]
    if len(cb) == nb:
        attrs["center_of_buoyancy"] = (np.vstack(cb) + origin).reshape(-1)
    if len(header.volume) >= nb and nb == 1:
        attrs["displaced_volume"] = header.volume[0]
    return attrs


# --------------------------------------------------------------------------- .out file

_PERIOD_LINE = re.compile(r"Wave period\s*(?:\(sec\))?\s*=\s*(infinite|zero|" + _FLOAT[1:-1] + ")")
_HEADING_LINE = re.compile(r"Wave Heading \(deg\)\s*:\s*" + _FLOAT)
_SECTION_TITLES = {
    "ADDED-MASS AND DAMPING COEFFICIENTS": "radiation",
    "ADDED-MASS COEFFICIENTS": "radiation",
    "DIFFRACTION EXCITING FORCES AND MOMENTS": "diffraction",
    "HASKIND EXCITING FORCES AND MOMENTS": "haskind",
    "RESPONSE AMPLITUDE OPERATORS": "rao",
    "DRIFT FORCES (Pressure Integration)": "drift_pressure",
    "DRIFT FORCES (Momentum Conservation)": "drift_momentum",
}


def _section_kind(line: str) -> str | None:
    stripped = line.strip()
    for title, kind in _SECTION_TITLES.items():
        if stripped.endswith(title):
            return kind
    return None


def _rows_after(text: TextFile, i: int, stop: int) -> tuple[list[np.ndarray], list[int], int]:
    """Numeric rows after line ``i`` up to the first non-numeric non-blank line."""
    rows, where = [], []
    k = i
    while k < stop:
        line = text.lines[k]
        if line.strip():
            values = parse_numbers(line)
            if values is None:
                break
            if not np.all(np.isfinite(values)):
                raise text.error("non-finite value (NaN or Inf) in the data", k)
            rows.append(values)
            where.append(k)
        k += 1
    return rows, where, k


def read_wamit_out(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
) -> xr.Dataset:
    """Read a WAMIT ``.out`` log on its own.

    The log prints the same nondimensional quantities as the numeric files, to
    fewer digits (phases in whole degrees), plus motion RAOs and mean drift forces:
    added mass and damping, A(0) and A(∞), diffraction (else Haskind) excitation,
    hydrostatics (header), RAOs and mean drift forces (pressure integration, else
    momentum conservation), about the body origin.

    Parameters
    ----------
    path
        The ``.out`` file.
    rho, g, ulen
        As in :func:`read_wamit`; from the header when printed there.
    """
    path = Path(path)
    text = TextFile.read(path)
    if not is_out_file(path):
        raise text.error("not a WAMIT .out file (no WAMIT banner)")
    header = _out_header(text)
    history = [f"read {path.name}"]
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        header.rho,
        header.g,
        path=path,
        history=history,
        dimensional=False,
    )
    L = resolve_constant(
        "ulen", ulen, header.ulen, 1.0, unit="m", path=path, history=history, dimensional=False
    )

    starts = [i for i, line in enumerate(text.lines) if _PERIOD_LINE.search(line)]
    if not starts:
        raise text.error(
            "no 'Wave period' blocks: the run did not reach the FORCE output (truncated log?)"
        )
    starts.append(len(text))
    # per period: {"radiation": rows, "diffraction": {beta: rows}, ...}
    blocks: list[tuple[str, dict]] = []
    for b in range(len(starts) - 1):
        i0, i1 = starts[b], starts[b + 1]
        label = _PERIOD_LINE.search(text.lines[i0]).group(1)
        content: dict = {}
        k = i0 + 1
        while k < i1:
            kind = _section_kind(text.lines[k])
            if kind is None:
                k += 1
                continue
            if kind == "radiation":
                rows, where, k = _rows_after(text, k + 1 + _skip_column_titles(text, k + 1, i1), i1)
                content["radiation"] = (rows, where)
                continue
            per_heading: dict[float, tuple[list[np.ndarray], list[int]]] = {}
            k += 1
            while k < i1:
                if _section_kind(text.lines[k]) is not None:
                    break
                m = _HEADING_LINE.search(text.lines[k])
                if m:
                    beta = float(m.group(1))
                    rows, where, k = _rows_after(
                        text, k + 1 + _skip_column_titles(text, k + 1, i1), i1
                    )
                    per_heading[beta] = (rows, where)
                    continue
                k += 1
            content[kind] = per_heading
        blocks.append((label, content))

    n = 0
    for _, content in blocks:
        rows, _ = content.get("radiation", ([], []))
        for r in rows:
            n = max(n, int(r[0]), int(r[1]))
    if n == 0:
        raise text.error("no added-mass coefficients found")
    n = 6 * int(np.ceil(n / 6))

    def matrix(rows, where, column):
        m = np.zeros((n, n))
        for r, w in zip(rows, where, strict=True):
            if r.size <= column:
                raise text.error(f"expected at least {column + 1} numbers", w)
            if not (1 <= r[0] <= n and 1 <= r[1] <= n and r[0] == int(r[0]) and r[1] == int(r[1])):
                raise text.error("expected DOF indices I J at the start of the row", w)
            m[int(r[0]) - 1, int(r[1]) - 1] = r[column]
        return m

    finite = []
    limits: dict[str, np.ndarray] = {}
    for (label, content), block_start in zip(blocks, starts, strict=False):
        if "radiation" not in content:
            raise text.error(f"no added-mass coefficients for period {label}", starts[0])
        rows, where = content["radiation"]
        if label in ("infinite", "zero"):
            limits[label] = matrix(rows, where, 2)
        else:
            finite.append((float(label), content, rows, where, block_start))
    if not finite:
        raise text.error("no finite wave period in the log")
    first_pairs = {(int(r[0]), int(r[1])) for r in finite[0][2]}
    for period, _, rows, _, block_start in finite[1:]:
        if {(int(r[0]), int(r[1])) for r in rows} != first_pairs:
            raise text.error(
                f"the added-mass and damping table at period {period:g} s does not have the "
                "same entries as the first period (truncated or edited log?)",
                block_start,
            )
    periods = np.array([p for p, *_ in finite])
    omega = 2 * np.pi / periods
    order = np.argsort(omega)
    scale_a = rho_v * L ** length_exponents(n, 3)
    a = np.stack([matrix(finite[k][2], finite[k][3], 2) for k in order]) * scale_a
    b = (
        np.stack([matrix(finite[k][2], finite[k][3], 3) for k in order])
        * scale_a
        * omega[order, None, None]
    )

    extra: dict = {}
    if "infinite" in limits:  # infinite period: omega = 0
        extra["added_mass_zero"] = limits["infinite"] * scale_a
    if "zero" in limits:
        extra["added_mass_inf"] = limits["zero"] * scale_a

    def by_heading(kind: str, scale: np.ndarray, real: bool = False):
        """Stack one section over periods and headings; every period must be complete."""
        headings = sorted(finite[0][1].get(kind, {}))
        if not headings:
            return None, None
        out = np.zeros((len(order), len(headings), n), dtype=float if real else complex)
        for kk, k in enumerate(order):
            per_heading = finite[k][1].get(kind, {})
            if sorted(per_heading) != headings:
                raise text.error(
                    f"the {kind} output at period {finite[k][0]:g} s has headings "
                    f"{sorted(per_heading)}, not {headings} as the first period "
                    "(truncated or edited log?)",
                    finite[k][4],
                )
            for h, beta in enumerate(headings):
                rows, where = per_heading[beta]
                for r, w in zip(rows, where, strict=True):
                    if r.size < 3 or not 1 <= r[0] <= n or r[0] != int(r[0]):
                        raise text.error("expected a DOF index, a modulus and a phase", w)
                    value = r[1] * np.exp(1j * np.radians(r[2]))
                    out[kk, h, int(r[0]) - 1] = value.real if real else value
        return out * scale, np.radians(headings)

    force_scale = rho_v * g_v * L ** force_exponents(n, 2)
    x, beta = by_heading("diffraction", force_scale)
    if x is None:
        x, beta = by_heading("haskind", force_scale)
        if x is not None:
            history.append("excitation from the Haskind relations (no diffraction output)")
    if x is not None:
        extra["excitation_force"] = x
        extra["wave_direction"] = beta
    rao, beta_r = by_heading("rao", 1.0 / L ** (np.arange(n) % 6 >= 3).astype(int))
    if rao is not None:
        if beta is not None and (beta.shape != beta_r.shape or not np.allclose(beta, beta_r)):
            raise text.error("the RAO headings differ from the excitation headings")
        extra["rao"], extra["wave_direction"] = rao, beta_r
    drift_scale = rho_v * g_v * L ** force_exponents(n, 1)
    drift, beta_d = by_heading("drift_pressure", drift_scale, real=True)
    if drift is None:
        drift, beta_d = by_heading("drift_momentum", drift_scale, real=True)
    if drift is not None and "wave_direction" in extra:
        same = beta_d.shape == extra["wave_direction"].shape
        if not same or not np.allclose(beta_d, extra["wave_direction"]):
            raise text.error("the drift-force headings differ from the excitation headings")
        extra["drift_force"] = drift
    if header.hydrostatics and n == 6:
        extra["hydrostatic_stiffness"] = _hydrostatics_from_out(header.hydrostatics[0]) * (
            rho_v * g_v * L ** length_exponents(n, 2)
        )

    return make_hydrodb(
        omega[order],
        a,
        b,
        rho=rho_v,
        g=g_v,
        water_depth=header.water_depth if header.water_depth is not None else np.inf,
        source_format="wamit-out",
        source_file=str(path),
        dofs=dof_labels([f"body{k + 1}" for k in range(n // 6)]),
        history=history,
        ulen=L,
        **extra,
        **_body_attrs(header, _ForceControl(), n),
    )


def _skip_column_titles(text: TextFile, i: int, stop: int) -> int:
    """Number of lines from ``i`` up to and including the column-title line (I J …)."""
    for k in range(i, min(i + 6, stop)):
        stripped = text.lines[k].strip()
        if stripped.startswith("I ") or stripped == "I":
            return k - i + 1
    return 0
