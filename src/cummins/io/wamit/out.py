"""The WAMIT ``.out`` log read on its own (:func:`read_wamit_out`): its 'Wave period'
blocks of added mass and damping (with the A(0) and A(∞) blocks), diffraction (else
Haskind) excitation, motion RAOs and mean drift forces (every method the log prints,
``drift_force`` the one the numeric files' reader prefers: control surface, else
pressure integration, else momentum conservation), nondimensional as in the numeric
files but to fewer digits (phases in whole degrees).
"""

from __future__ import annotations

import os
import re
from collections.abc import Collection, Sequence
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import HydroDataError
from cummins.hydrodb import dof_labels, make_hydrodb
from cummins.io._common import (
    DEPTH_ASSUMED,
    force_exponents,
    length_exponents,
    resolve_constant,
    resolve_rho_g,
    rotation_flags,
    warn_damage,
)
from cummins.io._text import (
    TextFile,
    check_line_ends,
    parse_numbers,
)
from cummins.io.wamit.detect import _sibling, is_out_file
from cummins.io.wamit.frc import _read_frc
from cummins.io.wamit.input_files import _Config, _Mmx, _read_cfg
from cummins.io.wamit.mass import _body_attrs, _mass_matrices, _restoring_weight
from cummins.io.wamit.modes import _check_memory, _mode_layout
from cummins.io.wamit.out_header import (
    _FLOAT,
    _hydrostatics_matrix,
    _out_header,
    _OutHeader,
)
from cummins.io.wamit.second_order import DRIFT_PREFERENCE, drift_variables
from cummins.io.wamit.settings import RunSettings
from cummins.io.wamit.text import MAX_ABS_VALUE, _read_text
from cummins.qtf.data import with_second_order

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
    "DRIFT FORCES (Control Surface)": "drift_control_surface",
}


#: The ``.out`` table of each mean-drift method.
_DRIFT_TABLES = {
    "control_surface": "drift_control_surface",
    "pressure": "drift_pressure",
    "momentum": "drift_momentum",
}
#: The ``sections`` of :func:`read_wamit_out` that hold the mean drift.
DRIFT_SECTIONS = tuple(_DRIFT_TABLES.values())


#: A line that ends with a section title (and blanks).
_SECTION_LINE = re.compile("(" + "|".join(map(re.escape, _SECTION_TITLES)) + r")\s*$")


def _section_kind(line: str) -> str | None:
    m = _SECTION_LINE.search(line)
    return _SECTION_TITLES[m.group(1)] if m else None


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
            rows.append(values)
            where.append(k)
        k += 1
    if rows:  # checked once per table (NaN compares False: not below the limit)
        sizes = np.abs(np.concatenate(rows))
        if not np.all(sizes < MAX_ABS_VALUE):
            for values, w in zip(rows, where, strict=True):
                if not np.all(np.isfinite(values)):
                    raise text.error("non-finite value (NaN or Inf) in the data", w)
                if np.any(np.abs(values) >= MAX_ABS_VALUE):
                    raise text.error("implausible value (a missing-value marker?)", w)
    return rows, where, k


def _skip_column_titles(text: TextFile, i: int, stop: int) -> int:
    """Number of lines from ``i`` up to and including the column-title line (I J …)."""
    for k in range(i, min(i + 6, stop)):
        fields = text.lines[k].split()  # "I  J …", with blanks or tabs between
        if fields and fields[0] == "I":
            return k - i + 1
    return 0


def _next_section(text: TextFile, k: int, stop: int) -> int:
    """The first line from ``k`` that starts a section (a numeric row never does)."""
    lines = text.lines
    while k < stop:
        head = lines[k].lstrip()[:1]
        if head.isalpha() and _section_kind(lines[k]) is not None:
            return k
        k += 1
    return stop


def _out_blocks(
    text: TextFile, starts: list[int], kinds: Collection[str] | None = None
) -> list[tuple[str, dict, int]]:
    """Per 'Wave period' block: its label, {section: rows} and its first line; with
    ``kinds``, the added mass and damping and those sections only (the others skipped
    unread)."""
    blocks = []
    bounds = [*starts, len(text)]
    for b in range(len(starts)):
        i0, i1 = bounds[b], bounds[b + 1]
        label = _PERIOD_LINE.search(text.lines[i0]).group(1)
        content: dict = {}
        k = i0 + 1
        while k < i1:
            kind = _section_kind(text.lines[k])
            if kind is None:
                k += 1
                continue
            if kinds is not None and kind != "radiation" and kind not in kinds:
                k = _next_section(text, k + 1, i1)
                continue
            if kind in content:
                raise text.error(
                    f"a second {kind} table in the block of period {label} (a 'Wave period' "
                    "line deleted?)",
                    k,
                )
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
                    if beta in per_heading:
                        raise text.error(f"heading {beta:g} deg appears twice in this block", k)
                    rows, where, k = _rows_after(
                        text, k + 1 + _skip_column_titles(text, k + 1, i1), i1
                    )
                    per_heading[beta] = (rows, where)
                    continue
                k += 1
            content[kind] = per_heading
        blocks.append((label, content, i0))
    return blocks


def _check_out_tables(text: TextFile, blocks) -> None:
    """Every row of the log's tables as WAMIT writes it: as many numbers as the other
    rows of its kind of table (limit blocks print A alone; the drift tables mix 3- and
    5-number rows), in WAMIT's fixed columns (:func:`check_line_ends`, per kind and
    number of fields). A garbled number that splits in two ("1.2.3" reads as 1.2 and
    0.3) or a cut row would otherwise pass."""
    groups: dict[tuple[str, int], list[int]] = {}
    sizes: dict[tuple[str, bool], dict[int, list[int]]] = {}
    for label, content, _ in blocks:
        limit = label in ("infinite", "zero")
        for kind, value in content.items():
            tables = [value] if kind == "radiation" else list(value.values())
            for rows, where in tables:
                for r, w in zip(rows, where, strict=True):
                    groups.setdefault((kind, r.size), []).append(w)
                    if not kind.startswith("drift"):
                        sizes.setdefault((kind, limit), {}).setdefault(r.size, []).append(w)
    for (kind, limit), by_size in sizes.items():
        usual = max(by_size, key=lambda size: len(by_size[size]))
        odd = [size for size in by_size if size != usual]
        if odd:
            line = min(by_size[odd[0]])
            raise text.error(
                f"expected {usual} numbers, as on the other rows of the {kind} tables"
                f"{' of the limit blocks' if limit else ''}, found {odd[0]}",
                line,
                hint="the file is damaged; take it again from the WAMIT run",
            )
    for lines in groups.values():
        check_line_ends(text, lines)


def read_wamit_out(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    modes: int | Sequence[int] | None = None,
    water_depth: float | None = None,
    sections: Collection[str] | None = None,
) -> xr.Dataset:
    """Read a WAMIT ``.out`` log on its own (``water_depth``, m, only for a log that does
    not print it: see :func:`cummins.io.wamit.read_wamit`; ``sections``: the tables to
    read besides the added mass and damping, e.g. ``("drift_pressure", …)``, default
    all).

    The log prints the same nondimensional quantities as the numeric files, to
    fewer digits (phases in whole degrees), plus motion RAOs and mean drift forces:
    added mass and damping, A(0) and A(∞), diffraction (else Haskind) excitation,
    hydrostatics and mass properties (header), RAOs and mean drift forces (``drift_force``
    the control surface's, else pressure integration's, else momentum conservation's, as
    the ``.7/.9/.8`` are read; the others as ``drift_force_<method>``), about the body
    origin. A ``.cfg``
    (NEWMDS) and ``.frc`` with the same stem are read too.

    Parameters
    ----------
    path
        The ``.out`` file.
    rho, g, ulen
        As in :func:`read_wamit`; from the header when printed there.
    modes
        Modes per body, when the files do not say (see :func:`read_wamit`).
    """
    path = Path(path)
    text = _read_text(path)
    if not is_out_file(path):
        raise text.error("not a WAMIT .out file (no WAMIT banner)")
    return _read_out_text(
        text,
        _out_header(text),
        rho=rho,
        g=g,
        ulen=ulen,
        modes=modes,
        water_depth=water_depth,
        sections=sections,
    )


def _read_out_text(
    text: TextFile,
    header: _OutHeader,
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    modes: int | Sequence[int] | None = None,
    water_depth: float | None = None,
    sections: Collection[str] | None = None,
) -> xr.Dataset:
    """:func:`read_wamit_out` of a log already read (``text``) whose ``header`` was
    parsed (:func:`~cummins.io.wamit.out_header._out_header`): a ``.1`` that takes the
    excitation or the drift from its ``.out`` reads the file once."""
    path = text.path
    notes: list[str] = []
    history = [f"read {path.name}"]
    for body in header.bodies:
        history.extend(body.notes)
    if not header.has_gravity_line or header.ulen is None:
        warn_damage(
            "no 'Gravity: … Length scale: …' line in the header (damaged?)",
            path=path,
            notes=notes,
        )
    rho_v, g_v = resolve_rho_g(
        rho, g, header.rho, header.g, path=path, history=history, dimensional=False
    )
    L = resolve_constant(
        "ulen", ulen, header.ulen, 1.0, unit="m", path=path, history=history, dimensional=False
    )

    starts = [i for i, line in enumerate(text.lines) if _PERIOD_LINE.search(line)]
    if not starts:
        raise text.error(
            "no 'Wave period' blocks: the run did not reach the FORCE output (truncated log?)"
        )
    blocks = _out_blocks(text, starts, sections)
    _check_out_tables(text, blocks)
    if header.announced_blocks is not None and header.announced_blocks != len(blocks):
        warn_damage(
            f"the header lists {header.announced_blocks} periods, the log holds "
            f"{len(blocks)} 'Wave period' blocks (truncated or edited?): read the "
            f"{len(blocks)}",
            path=path,
            notes=notes,
        )

    n_seen = 0
    for _, content, _ in blocks:
        for r, w in zip(*content.get("radiation", ([], [])), strict=True):
            if r.size < 3 or r[0] != int(r[0]) or r[1] != int(r[1]) or min(r[0], r[1]) < 1:
                raise text.error("expected DOF indices I J at the start of the row", w)
            if max(r[0], r[1]) > 10000:
                raise text.error(f"DOF index {max(r[0], r[1]):g} is not plausible", w)
            n_seen = max(n_seen, int(r[0]), int(r[1]))
    if n_seen == 0:
        raise text.error("no added-mass coefficients found")
    cfg = _Config()
    cfg_path = _sibling(path, ".cfg")
    if cfg_path is not None and cfg_path.stat().st_size:
        try:
            cfg = _read_cfg(cfg_path)
        except HydroDataError as exc:
            warn_damage(f"not read: {exc}", path=cfg_path, notes=notes)
    layout = _mode_layout(
        n_seen,
        n_bodies=len(header.bodies) or None,
        new_modes=cfg.new_modes,
        extra_modes=header.extra_modes if header.bodies else None,
        modes=modes,
        path=path,
        history=history,
    )
    n = sum(layout)

    def matrix(rows, where, column):
        m = np.zeros((n, n))
        seen = set()
        for r, w in zip(rows, where, strict=True):
            if r.size <= column:
                raise text.error(f"expected at least {column + 1} numbers", w)
            key = (int(r[0]), int(r[1]))
            if key in seen:
                raise text.error(f"entry {key} appears twice in this table", w)
            seen.add(key)
            m[key[0] - 1, key[1] - 1] = r[column]
        return m

    finite = []
    limits: dict[str, np.ndarray] = {}
    for label, content, block_start in blocks:
        if "radiation" not in content:
            raise text.error(f"no added-mass coefficients for period {label}", block_start)
        rows, where = content["radiation"]
        if label in ("infinite", "zero"):
            value = matrix(rows, where, 2)
            if label in limits:
                if not np.allclose(value, limits[label], rtol=1e-6, atol=0):
                    raise text.error(
                        f"the block of period {label} is written twice, with different values",
                        block_start,
                    )
                history.append(f"the period-{label} block is written twice (identical): read once")
            limits[label] = value
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
    if np.any(periods <= 0):
        raise text.error(f"period {periods[periods <= 0][0]:g} s is not positive", starts[0])
    omega = 2 * np.pi / periods
    order = np.argsort(omega)
    headings0 = sorted(finite[0][1].get("diffraction", finite[0][1].get("haskind", {})))
    _check_memory(n, omega.size, max(len(headings0), 1), path)
    scale_a = rho_v * L ** length_exponents(n, 3, layout)
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
            return None, None, []
        first_dofs = None
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
                dofs = []
                for r, w in zip(rows, where, strict=True):
                    if r.size < 3 or not 1 <= abs(r[0]) <= n or r[0] != int(r[0]):
                        raise text.error("expected a DOF index, a modulus and a phase", w)
                    if int(abs(r[0])) in dofs:
                        raise text.error(f"DOF {int(abs(r[0]))} appears twice here", w)
                    dofs.append(int(abs(r[0])))
                    value = r[1] * np.exp(1j * np.radians(r[2]))
                    out[kk, h, int(abs(r[0])) - 1] = value.real if real else value
                if first_dofs is None:
                    first_dofs = sorted(dofs)
                elif sorted(dofs) != first_dofs:
                    raise text.error(
                        f"the {kind} output at period {finite[k][0]:g} s, heading {beta:g} deg "
                        f"holds DOFs {sorted(dofs)}, not {first_dofs} (a line deleted?)",
                        where[-1] if where else finite[k][4],
                    )
        return out * scale, np.radians(headings), first_dofs or []

    force_scale = rho_v * g_v * L ** force_exponents(n, 2, layout)
    x, beta, _ = by_heading("diffraction", force_scale)
    if x is None:
        x, beta, _ = by_heading("haskind", force_scale)
        if x is not None:
            history.append("excitation from the Haskind relations (no diffraction output)")
    if x is not None:
        extra["excitation_force"] = x
        extra["wave_direction"] = beta
    rao, beta_r, _ = by_heading("rao", 1.0 / L ** rotation_flags(n, layout))
    if rao is not None:
        if beta is not None and (beta.shape != beta_r.shape or not np.allclose(beta, beta_r)):
            raise text.error("the RAO headings differ from the excitation headings")
        extra["rao"], extra["wave_direction"] = rao, beta_r
    drift_scale = rho_v * g_v * L ** force_exponents(n, 1, layout)
    drift: dict = {"drift": {}, "attrs": {}, "history": []}
    found, beta_d = [], None
    for method in DRIFT_PREFERENCE:
        values, beta_m, present = by_heading(_DRIFT_TABLES[method], drift_scale, real=True)
        if values is None:
            continue
        reference = extra.get("wave_direction", beta_d)
        if reference is not None and (
            beta_m.shape != reference.shape or not np.allclose(beta_m, reference)
        ):
            raise text.error("the drift-force headings differ from the excitation headings")
        beta_d = beta_m
        on = np.isin(np.arange(1, n + 1), present)
        found.append((method, values, on, path.name))
    if header.bodies and all(bd.hydrostatics for bd in header.bodies):
        extra["hydrostatic_stiffness"] = _hydrostatics_matrix(header, layout) * (
            rho_v * g_v * L ** length_exponents(n, 2, layout)
        )
        if n != 6 * len(layout):
            history.append(
                "hydrostatics of the generalized modes are not printed in the .out: "
                "their rows are 0 (the run's .hst has them)"
            )
    frc_path = _sibling(path, ".frc")
    frc = None
    if frc_path is not None and frc_path.stat().st_size:
        try:
            frc = _read_frc(frc_path, n, len(layout), cfg.ialtfrc)
        except HydroDataError as exc:
            warn_damage(
                f"not read, so no inertia or external matrices from it: {exc}",
                path=frc_path,
                notes=notes,
            )
    _mass_matrices(
        extra,
        layout,
        rho_v,
        header,
        frc,
        frc_path,
        _Mmx(),
        None,
        path,
        RunSettings(),
        history,
        notes,
        omega.size,
    )
    if "hydrostatic_stiffness" in extra:
        extra.update(_restoring_weight(path.name, header, layout, frc, rho_v, RunSettings(), path))
    names = header.body_names
    ds = make_hydrodb(
        omega[order],
        a,
        b,
        rho=rho_v,
        g=g_v,
        water_depth=header.water_depth
        if header.water_depth is not None
        else (np.inf if water_depth is None else water_depth),
        **{DEPTH_ASSUMED: 1 if header.water_depth is None and water_depth is None else None},
        source_format="wamit-out",
        source_file=str(path),
        dofs=dof_labels(len(layout) if len(layout) > 1 else None, layout),
        history=history,
        read_warnings=notes,
        ulen=L,
        body_names="\n".join(names) if len(names) == len(layout) else None,
        **extra,
        **_body_attrs(header, layout, RunSettings()),
    )
    if not found:
        return ds
    drift_variables(found, list(ds.influenced_dof.values.astype(str)), drift)
    return with_second_order(
        ds,
        drift=drift["drift"],
        wave_direction=beta_d,
        history=drift["history"],
        attrs=drift["attrs"],
    )
