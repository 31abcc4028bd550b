"""AQWA files in the layouts of AQWA 2023 R1, built from a real AQWA 19.1 listing.

SYNTHETIC FILES. No AQWA listing of the 2023 layout nor AQWA ``.QTF`` file under a
permissive licence is public: the only ones found (BEMRosetta's
``examples/aqwa/line/Box1`` and ``Box2``, AQWA 2023 R1, GPL-3.0) may not be copied into
cummins. Their layouts are reproduced here around real numbers — the WEC-Sim PEND hull's
listing (AQWA 19.1, Apache-2.0, the corpus's ``WEC-Sim/aqwa_19.1_PEND_hull``):

* :func:`relayout` moves the listing's wave frequency and direction table into the 2023
  layout (the directions as a sub-table inside the frequency table), merges its six
  one-DOF drift pages into one block (2023), and may add a second structure: a copy of
  every page of structure 1, its centre of gravity moved by ``dy`` (the listing's phases
  are relative to each centre of gravity, so the copy's data are structure 1's, referred
  from another point);
* :func:`write_aqtf` writes a ``.QTF`` (``AQTF-2.0``) in AQWA's record layout and format;
* :func:`synthetic_qtf` makes QTFs whose diagonal is a given mean drift (the listing's)
  and whose off-diagonal values are invented (Hermitian, smooth): what they test is the
  reading, not AQWA's hydrodynamics.

A real file is still needed to close the item (docs/second_order.md).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

_FREQ_TITLE = "WAVEFREQUENCIES/PERIODSANDDIRECTIONS"
_DRIFT_TITLE = "WAVE-DRIFTLOADS"
_RULE = " " + "-" * 102
_INNER_RULE = " " * 10 + "-" * 93


def _squash(line: str) -> str:
    return re.sub(r"\s+", "", line)


def _pages(lines: list[str]) -> list[tuple[int, int]]:
    starts = [i for i, line in enumerate(lines) if line.strip() == "1"]
    return list(zip(starts, [*starts[1:], len(lines)], strict=True))


def _structure_of(page: list[str]) -> int | None:
    for line in page[1:9]:
        m = re.search(r"(?:FOR|OF)STRUCTURE(\d+)", _squash(line))
        if m:
            return int(m.group(1))
    return None


def _as_structure(page: list[str], structure: int, dy: float) -> list[str]:
    """A page of structure 1 relabelled for ``structure``, its centre of gravity moved by
    ``dy`` in y."""
    out = []
    for line in page:
        line = re.sub(r"(S T R U C T U R E\s+)1(?=\s|$)", rf"\g<1>{structure}", line)
        line = re.sub(r"(STRUCTURE NUMBER\s+)1(?=\s|$)", rf"\g<1>{structure}", line)
        m = re.search(r"GY=\s*([-\d.]+)", line)
        if m:
            value = f"{float(m.group(1)) + dy:.4f}".rjust(len(m.group(1)))
            line = line[: m.start(1)] + value + line[m.end(1) :]
        m = re.match(r"(\s*CENTRE OF GRAVITY\s+)(\S+)(\s+)(\S+)(.*)$", line)
        if m:
            value = f"{float(m.group(4)) + dy:.3f}".rjust(len(m.group(4)))
            line = m.group(1) + m.group(2) + m.group(3) + value + m.group(5)
        out.append(line)
    return out


def _frequency_table(lines: list[str], pages) -> tuple[list[str], list[str], list[str]]:
    """(title lines, rows without the structure number, directions) of the listing."""
    rows, directions, title = [], [], []
    for a, b in pages:
        page = lines[a:b]
        if _FREQ_TITLE not in _squash(" ".join(page[1:3])):
            continue
        title = title or page[:3]
        for line in page[3:]:
            words = line.split()
            if len(words) >= 10 and words[0].isdigit() and words[1].isdigit():
                rows.append(" " * 7 + line[7:])  # drop the structure number
            elif len(words) >= 9 and words[0].isdigit() and "." in words[1]:
                rows.append(line)
            elif words and words[0].isdigit() and all("." in w for w in words[1:]) and words[1:]:
                directions = words[1:]
    return title, rows, directions


def _table_page(title, rows, directions, layout: str, n: int) -> list[str]:
    header = [
        _RULE,
        " STRUCTURE    FREQUENCY FREQUENCY  PERIOD      WAVE      WAVE    MAX ELEM    "
        "DEPTH RATIOS    PARAMETERS",
        "              (RAD/SEC)  (HERTZ)  (SECONDS)   NUMBER    LENGTH     SIZE      D/L      K*D",
        _RULE,
    ]
    values = "".join(f"{d:>8}" for d in directions)
    indices = "".join(f"{k + 1:<8}" for k in range(len(directions)))
    out = ["1", *title[1:], *header]
    for s in range(1, n + 1):
        out.append(f"{s:7d}" + rows[0][7:])
        out.extend(rows[1:])
        if layout == "2023":
            out += [_INNER_RULE, "            DIRECTIONS   " + indices.rstrip(), _INNER_RULE]
            out += [" " * 13 + values, _RULE]
    if layout != "2023":
        out.append(_RULE)
        out += ["1", *title[1:], _RULE, " STRUCTURE  DIRECTIONS   " + indices.rstrip(), _RULE]
        out += [f"{s:7d}" + " " * 6 + values for s in range(1, n + 1)]
        out.append(_RULE)
    return out


def _merged_drift(lines: list[str], pages) -> list[str]:
    """The one-DOF drift pages of structure 1 as one block (AQWA 2023)."""
    out: list[str] = []
    for a, b in pages:
        page = lines[a:b]
        if _DRIFT_TITLE not in _squash(" ".join(page[1:3])):
            continue
        label = next(k for k, line in enumerate(page) if re.fullmatch(r"\s*\w+\(\w+\)\s*", line))
        end = label + 1
        while end < len(page) and page[end].split() and page[end].split()[0][0].isdigit():
            end += 1
        out.extend(page[:end] if not out else page[label:end])
    return out


def relayout(text: str, *, layout: str = "2023", structures: int = 1, dy: float = 0.0) -> str:
    """The listing ``text`` (AQWA 19.1, one structure) in ``layout`` ("2023" or "19.1")
    with ``structures`` structures (2: structure 1 copied, its CG moved by ``dy`` m)."""
    lines = text.splitlines()
    pages = _pages(lines)
    title, rows, directions = _frequency_table(lines, pages)
    drift = _merged_drift(lines, pages) if layout == "2023" else []
    out = lines[: pages[0][0]]
    table_done = drift_done = False
    for a, b in pages:
        page = lines[a:b]
        heading = _squash(" ".join(page[1:3]))
        if _FREQ_TITLE in heading:
            if not table_done:
                out += _table_page(title, rows, directions, layout, structures)
                table_done = True
            continue
        if _DRIFT_TITLE in heading and layout == "2023":
            if not drift_done:
                for s in range(1, structures + 1):
                    out += drift if s == 1 else _as_structure(drift, s, dy)
                drift_done = True
            continue
        out += page
        if structures > 1 and _structure_of(page) == 1:
            for s in range(2, structures + 1):
                out += _as_structure(page, s, dy)
    return "\n".join(out) + "\n"


# --------------------------------------------------------------------------- .QTF


def _e(value: float) -> str:
    return f" {value: .4E}"


def write_aqtf(path: Path, blocks, *, title: str = "") -> None:
    """An AQWA ``.QTF`` (AQTF-2.0): ``blocks`` of (structure, directions in degrees, omega
    in rad/s, Q⁻ and Q⁺ of shape (n, n, m, 6), complex, relative to the wave at the
    structure's centre of gravity); both triangles, every direction, AQWA's format."""
    out = [f"AQTF-2.0 :{title:<60}"]
    for structure, directions, omega, qd, qs in blocks:
        out.append(
            f" {structure:2d} {len(directions):2d} {len(omega):3d}    "
            + "".join(f"   {d: 9.5f}" for d in directions)
        )
        out.append(" " * 15 + "".join(f"   {w:9.7f}" for w in omega))
        for h in range(len(directions)):
            for i in range(len(omega)):
                for j in range(len(omega)):
                    rows = (qd[i, j, h].real, qd[i, j, h].imag, qs[i, j, h].real, qs[i, j, h].imag)
                    out.append(
                        f" {structure:2d} {h + 1:2d} {i + 1:3d} {j + 1:3d} "
                        + "".join(_e(v) for v in rows[0])
                    )
                    out += [" " * 15 + "".join(_e(v) for v in row) for row in rows[1:]]
    Path(path).write_text("\n".join(out) + "\n")


def synthetic_qtf(omega: np.ndarray, drift: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Q⁻ and Q⁺ (n, n, m, 6) whose mean drift Q⁻(ω, ω) is ``drift`` (n, m, 6), rounded to
    AQWA's five digits: Q⁻(ω_i, ω_j) = ½(T_i + T_j) + 0.1 i (ω_i − ω_j)/Δ (|T_i| + |T_j|)
    (Hermitian), Q⁺ = (0.3 + 0.2 i) ½(T_i + T_j) (symmetric). Invented values."""
    t_i, t_j = drift[:, None], drift[None, :]
    span = np.ptp(omega) or 1.0
    ratio = ((omega[:, None] - omega[None, :]) / span)[..., None, None]
    qd = 0.5 * (t_i + t_j) + 0.1j * ratio * (np.abs(t_i) + np.abs(t_j))
    qs = (0.3 + 0.2j) * 0.5 * (t_i + t_j)

    def five_digits(z):
        return np.array([float(f"{v:.4E}") for v in z.ravel()]).reshape(z.shape)

    return five_digits(qd.real) + 1j * five_digits(qd.imag), five_digits(
        qs.real
    ) + 1j * five_digits(qs.imag)


# --------------------------------------------------------------------------- runs

PEND = "corpus/WEC-Sim/aqwa_19.1_PEND_hull"
#: The PEND hull's frequencies (indices of its 100) on which the synthetic QTF is given:
#: 5.8–9.6 rad/s, where its mean drift peaks.
QTF_FREQUENCIES = (30, 35, 40, 43, 46, 50)
#: How far structure 2 of the two-structure runs is moved (m, along y).
DY = 3.0


def build_runs(shared_data: Path, root: Path) -> dict[str, Path]:
    """Synthetic AQWA runs (module docstring) in ``root``: ``2023`` (one structure, a
    ``.QTF``), ``2023x2`` (two structures, a ``.QTF`` of both), ``19.1x2`` (two
    structures, the 19.1 layout); {name: folder}. ``root/source.nc`` is the PEND
    listing as read, for comparisons."""
    import cummins

    source = shared_data / PEND / "19_1.LIS"
    text = source.read_text(encoding="utf-8", errors="replace")
    original = cummins.read(source)
    pick = list(QTF_FREQUENCIES)
    omega = original.omega.values[pick]
    drift = original.drift_force.transpose("omega", "wave_direction", "influenced_dof").values
    qd, qs = synthetic_qtf(omega, drift[pick])
    directions = np.degrees(original.wave_direction.values)
    out = {}
    for name, layout, n in (("2023", "2023", 1), ("2023x2", "2023", 2), ("19.1x2", "19.1", 2)):
        folder = root / name
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "19_1.LIS").write_text(relayout(text, layout=layout, structures=n, dy=DY))
        if layout == "2023":
            blocks = [(s, directions, omega, qd, qs) for s in range(1, n + 1)]
            write_aqtf(folder / "19_1.QTF", blocks, title=" synthetic (cummins tests)")
        out[name] = folder
    return out
