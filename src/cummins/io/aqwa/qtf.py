"""AQWA's full QTF file, ``<run>.QTF`` (options AQTF with CQTF), into the canonical form.

The layout of ``AQTF-2.0``, which AQWA 2023 R1 writes, as the Ansys Aqwa Reference
Manual's CQTF data record describes the file and BEMRosetta's ``examples/aqwa/line/Box1``
and ``Box2`` hold it:

* line 1: ``AQTF-<version> :`` and an optional title (versions 1.0 and 2.0 exist; the
  layout of 2.0 is read, 1.0 is refused);
* per structure, a header ``structure n_directions n_frequencies`` followed by the
  directions (degrees) and the frequencies (rad/s), wrapped over lines as they come;
* then, for that structure, every direction and every ordered pair of frequencies (both
  triangles), a record of four rows of six values (X … RZ), in AQWA's E format
  (``-1.2367E-05``): the first row labelled ``structure direction i j``, then
  Re Q⁻, Im Q⁻, Re Q⁺, Im Q⁺ of Q(ω_i, ω_j) — the difference- and the sum-frequency QTF,
  dimensional (N/m², N·m/m² per product of wave amplitudes), about the structure's
  centre of gravity, phases relative to the incident wave at the centre of gravity.

Conventions, as checked on the AQWA 2023 R1 box of BEMRosetta (docs/second_order.md):
the diagonal Re Q⁻(ω, ω) is the listing's "WAVE-DRIFT LOADS FOR UNIT WAVE AMPLITUDE**2"
(the same numbers to the listing's three digits: AQWA's QTF is per product of
amplitudes, the force convention of :mod:`cummins.qtf.data` without a factor ½); Re + i Im
is already cummins' e^{+iωt} value of Q(ω_i, ω_j) (the sign of the long-wave surge force
of the bound set-down flow, which a conjugated reading would reverse); the mirror
records are exact (Q⁻(ω_j, ω_i) = Q⁻(ω_i, ω_j)*, Q⁺ symmetric) and the imaginary row of
the mean drift Q⁻(ω, ω) is zeros: both are checked, a record that breaks them being
damage. The phases are referred from each centre of gravity to the origin as the
first-order forces are (:mod:`~cummins.io.aqwa.conventions`): Q⁻ × exp(−i(k_i − k_j) d),
Q⁺ × exp(−i(k_i + k_j) d), d = x_G cos β + y_G sin β.

The ``.MQT`` file of the MQTF option is a binary database of the QTFs between waves of
different directions (the Aqwa Reference Manual: copied into Aqwa-Drift by the FILE
record of deck 9); its layout is not public: it is not read, and ``history`` says so.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError
from cummins.io._common import warn_damage
from cummins.io._text import TextFile
from cummins.io.aqwa.conventions import wavenumber
from cummins.qtf.data import QTFTable, complete_square

_VERSION = re.compile(r"AQTF-(\d+(?:\.\d+)?)")
#: AQWA's fixed format of a QTF value (``-1.2367E-05``): a shorter token is a cut number.
_VALUE = re.compile(r"-?\d\.\d{4}E[-+]\d{2,3}")
#: A value and its mirror (Q(ω_j, ω_i) of Q(ω_i, ω_j)) are the same printed number:
#: relative difference allowed (one unit of the fifth digit).
_MIRROR_RTOL = 1.5e-4
_KINDS = ("difference", "sum")


@dataclass
class _Block:
    structure: int
    directions: np.ndarray
    omega: np.ndarray
    line: int
    records: dict[tuple[int, int, int], tuple[np.ndarray, int]] = field(default_factory=dict)


def qtf_beside(path: Path) -> tuple[Path | None, Path | None]:
    """The ``.QTF`` and ``.MQT`` files of the run of ``path`` (same stem, any case)."""
    found: dict[str, Path] = {}
    for p in path.parent.iterdir():
        suffix = p.suffix.lower()
        if p.is_file() and p.stem.lower() == path.stem.lower() and suffix in (".qtf", ".mqt"):
            found[suffix] = p
    return found.get(".qtf"), found.get(".mqt")


def _blocks(text: TextFile) -> list[_Block]:
    """The structure blocks of the file, records parsed and format-checked."""
    blocks: list[_Block] = []
    pending: list[float] = []
    header: tuple[int, int, int, int] | None = None  # structure, nh, nf, line
    k = 1
    n = len(text.lines)
    while k < n:
        words = text.lines[k].split()
        if not words:
            k += 1
            continue
        if header is not None:  # the header's directions and frequencies
            pending.extend(_header_numbers(text, k, words))
            if len(pending) > header[1] + header[2]:
                raise text.error(
                    f"the header announces {header[1]} directions and {header[2]} "
                    f"frequencies, found more numbers",
                    k,
                )
            if len(pending) == header[1] + header[2]:
                structure, nh, nf, line = header
                blocks.append(
                    _Block(structure, np.array(pending[:nh]), np.array(pending[nh:]), line)
                )
                header, pending = None, []
            k += 1
            continue
        labels = _leading_ints(words)
        if labels >= 4 and blocks:
            k = _record(text, k, words, blocks[-1])
            continue
        if labels == 3:
            structure, nh, nf = (int(w) for w in words[:3])
            if min(structure, nh, nf) < 1:
                raise text.error("expected 'structure directions frequencies' (positive)", k)
            if any(b.structure == structure for b in blocks):
                raise text.error(f"a second block for structure {structure}", k)
            header = (structure, nh, nf, k)
            pending = _header_numbers(text, k, words[3:]) if len(words) > 3 else []
            if len(pending) > nh + nf:
                raise text.error("more header numbers than directions and frequencies", k)
            if len(pending) == nh + nf:
                blocks.append(_Block(structure, np.array(pending[:nh]), np.array(pending[nh:]), k))
                header, pending = None, []
            k += 1
            continue
        raise text.error(
            "expected a record 'structure direction i j' and six values, or a block header "
            f"'structure directions frequencies', found {' '.join(words)[:60]!r}",
            k,
        )
    if header is not None:
        raise text.error("the file ends inside a block header (truncated?)", n - 1)
    if not blocks:
        raise text.error("no structure block in the QTF file")
    return blocks


def _leading_ints(words: list[str]) -> int:
    count = 0
    while count < len(words) and words[count].isdigit():
        count += 1
    return count


def _header_numbers(text: TextFile, k: int, words: list[str]) -> list[float]:
    out = []
    for w in words:
        try:
            value = float(w)
        except ValueError:
            value = np.nan
        if "." not in w or not np.isfinite(value):
            raise text.error(f"{w!r} is not a direction or a frequency of the header", k)
        out.append(value)
    return out


def _record(text: TextFile, k: int, words: list[str], block: _Block) -> int:
    """Parse the record at line ``k`` into ``block``; the index of the next line."""
    s, h, i, j = (int(w) for w in words[:4])
    if s != block.structure:
        raise text.error(
            f"a record of structure {s} in the block of structure {block.structure}", k
        )
    nh, nf = block.directions.size, block.omega.size
    if not (1 <= h <= nh and 1 <= i <= nf and 1 <= j <= nf):
        raise text.error(
            f"record {s} {h} {i} {j}: index beyond {nh} directions, {nf} frequencies", k
        )
    if (h, i, j) in block.records:
        raise text.error(f"record {s} {h} {i} {j} appears twice", k)
    rows = [words[4:]]
    for extra in range(1, 4):
        if k + extra >= len(text.lines):
            raise text.error("the file ends inside a record (truncated?)", len(text.lines) - 1)
        rows.append(text.lines[k + extra].split())
    values = np.empty((4, 6))
    for r, row in enumerate(rows):
        if len(row) != 6:
            raise text.error(f"expected six values (X … RZ), found {len(row)}", k + r)
        bad = next((w for w in row if not _VALUE.fullmatch(w)), None)
        if bad is not None:
            raise text.error(
                f"{bad!r} is not written in AQWA's format for a QTF value (cut or edited?)", k + r
            )
        values[r] = [float(w) for w in row]
    block.records[(h, i, j)] = (values, k)
    return k + 4


def _check_mirrors(text: TextFile, block: _Block) -> None:
    """Each record agrees with its mirror: Re Q⁻, Q⁺ equal, Im Q⁻ opposite (exact copies in
    AQWA's files); the mean drift Q⁻(ω, ω) is real (AQWA writes its Im row as zeros)."""
    sign = np.array([1.0, -1.0, 1.0, 1.0])[:, None]
    for (h, i, j), (values, line) in block.records.items():
        if i == j and np.any(values[1] != 0):
            raise text.error(
                f"record {block.structure} {h} {i} {j}: the mean drift Q-(w, w) has an "
                "imaginary part, which AQWA writes as zeros (a moved or edited line)",
                line + 1,
            )
        mirror = block.records.get((h, j, i))
        if mirror is None or i >= j:
            continue
        other = sign * mirror[0]
        off = np.abs(values - other) > _MIRROR_RTOL * np.maximum(np.abs(values), np.abs(other))
        if off.any():
            r, d = np.argwhere(off)[0]
            raise text.error(
                f"record {block.structure} {h} {i} {j} and its mirror "
                f"{block.structure} {h} {j} {i} disagree in row {r + 1}, DOF {d + 1} "
                f"({values[r, d]:g} against {other[r, d]:g}): a moved or edited line",
                line + r,
            )


def read_aqwa_qtf(
    path: Path, *, cgs: np.ndarray, depth: float, g: float
) -> tuple[dict[str, tuple], list[str], np.ndarray]:
    """The difference- and sum-frequency QTFs of an AQWA ``.QTF`` file.

    Parameters
    ----------
    path
        The ``.QTF`` file.
    cgs
        Centre of gravity of each structure of the run (m), shape (n, 3): the file's
        phases are relative to the wave there.
    depth, g
        Water depth (m, ``inf`` for deep water) and gravity (m/s²) of the run, for the
        wave numbers of the phase referral.

    Returns
    -------
    tables, notes, present
        {kind: (omega, directions, values)} on the run's 6n DOFs (full square,
        :func:`cummins.qtf.complete_square`), lines for ``history``, which DOFs the file
        holds.

    Raises
    ------
    HydroDataError
        Not an AQWA QTF file, another version, damaged records (naming the line).
    """
    text = TextFile.read(path)
    m = _VERSION.match(text.lines[0].strip())
    if not m:
        raise text.error("not an AQWA QTF file: the first line must be 'AQTF-<version>'", 0)
    if m.group(1) not in ("2", "2.0"):
        raise text.error(
            f"AQTF version {m.group(1)}: cummins reads the layout of version 2.0, which "
            "AQWA 2023 R1 writes",
            0,
            hint="send the file to the cummins developers to add its layout",
        )
    blocks = _blocks(text)
    n_structures = cgs.shape[0]
    first = blocks[0]
    for block in blocks:
        if block.structure > n_structures:
            raise text.error(
                f"structure {block.structure}, but the run has {n_structures}", block.line
            )
        if block.directions.size != first.directions.size or not np.allclose(
            block.directions, first.directions
        ):
            raise text.error("the structures' QTFs have different directions", block.line)
        if block.omega.size != first.omega.size or not np.allclose(block.omega, first.omega):
            raise text.error("the structures' QTFs have different frequencies", block.line)
        if np.any(block.omega <= 0):
            raise text.error("a QTF frequency is not positive", block.line)
        _check_mirrors(text, block)
    out: dict[str, tuple] = {}
    present = np.zeros(6 * n_structures, dtype=bool)
    for kind in _KINDS:
        rows = _rows(blocks, kind, cgs, depth, g)
        lines = rows.pop("line")

        def error(message: str, r: int, lines=lines) -> HydroDataError:
            return text.error(message, int(lines[min(r, lines.size - 1)]))

        omega, directions, values, _, held = complete_square(
            kind, **rows, n_dofs=6 * n_structures, error=error
        )
        out[kind] = (omega, directions, values)
        present |= held
    notes = [
        f"{path.name}: AQTF-{m.group(1)}, {len(blocks)} structure(s), {first.omega.size} "
        f"frequencies {first.omega.min():.4g}–{first.omega.max():.4g} rad/s, "
        f"{first.directions.size} direction(s); Q = Re + i Im of each record (e^(+iwt), per "
        "product of amplitudes), moments about each centre of gravity, phases referred "
        "from the centre of gravity to the origin"
    ]
    return out, notes, present


def _rows(blocks: list[_Block], kind: str, cgs: np.ndarray, depth: float, g: float) -> dict:
    """The records of every block as the rows :func:`complete_square` takes."""
    parts: dict[str, list] = {k: [] for k in ("w1", "w2", "b", "dof", "q", "line")}
    re_row, im_row, sign = (0, 1, -1.0) if kind == "difference" else (2, 3, 1.0)
    for block in blocks:
        k = wavenumber(block.omega, depth, g)
        beta = np.radians(block.directions)
        cg = cgs[block.structure - 1]
        for (h, i, j), (values, line) in block.records.items():
            d = cg[0] * np.cos(beta[h - 1]) + cg[1] * np.sin(beta[h - 1])
            shift = np.exp(-1j * (k[i - 1] + sign * k[j - 1]) * d)
            q = (values[re_row] + 1j * values[im_row]) * shift
            parts["w1"].append(np.full(6, block.omega[i - 1]))
            parts["w2"].append(np.full(6, block.omega[j - 1]))
            parts["b"].append(np.full(6, beta[h - 1]))
            parts["dof"].append(6 * (block.structure - 1) + np.arange(6))
            parts["q"].append(q)
            parts["line"].append(np.full(6, line))
    cat = {key: np.concatenate(value) for key, value in parts.items()}
    return {
        "omega1": cat["w1"],
        "omega2": cat["w2"],
        "beta1": cat["b"],
        "beta2": cat["b"],
        "dof": cat["dof"],
        "values": cat["q"],
        "line": cat["line"],
    }


def aqwa_second_order(
    path: Path, *, cgs: np.ndarray, depth: float, g: float, dofs: list[str], notes: list[str]
) -> dict:
    """The QTFs of the run of ``path`` (a ``.LIS`` or ``.AH1``) for
    :func:`cummins.qtf.with_second_order` (``tables``, ``history``, ``attrs``); a damaged
    ``.QTF`` is left out with a warning in ``notes``, as for the other solvers."""
    out: dict = {"tables": [], "history": [], "attrs": {}}
    qtf, mqt = qtf_beside(path)
    if mqt is not None:
        out["history"].append(
            f"{mqt.name} not read: AQWA's binary database of the QTFs between waves of "
            "different directions (MQTF option), whose layout is not public"
        )
    if qtf is None:
        return out
    try:
        tables, lines, present = read_aqwa_qtf(qtf, cgs=np.atleast_2d(cgs), depth=depth, g=g)
    except HydroDataError as exc:
        warn_damage(f"QTFs not read: {exc}", path=qtf, notes=notes)
        return out
    computed = " ".join(d for d, p in zip(dofs, present, strict=True) if p)
    for kind, (omega, directions, values) in tables.items():
        table = QTFTable(kind, omega, directions, values, tuple(dofs))
        out["tables"].append(table)
        out["attrs"][table.name] = {"source": qtf.name, "dofs_computed": computed}
    out["history"].extend(lines)
    if not present.all():
        missing = [d for d, p in zip(dofs, present, strict=True) if not p]
        out["history"].append(f"{qtf.name} holds no QTF for {', '.join(missing)}: zero there")
    return out
