"""WAMIT's second-order output: mean drift ``.7/.8/.9`` and QTFs ``.10d–.12d``, ``.10s–.12s``.

Mean drift files (one row per period, heading pair and mode; WAMIT User Manual v7 §3.8,
§4.10): ``PER BETA1 BETA2 I Mod(F̄) Pha(F̄) Re(F̄) Im(F̄)``, F̄ = F/(ρ g A² L^k), k = 1 for
forces, 2 for moments: ``.7`` the control-surface estimate, ``.8`` momentum conservation
(the far field: surge, sway and yaw only), ``.9`` pressure integration. A negative mode
index gives the moment in the moving body axes (HydroDyn's WAMIT2 module skips those
rows, and so does this reader: the canonical moments are about a point fixed in space).
Rows with BETA1 ≠ BETA2 (the mean force of two waves of one frequency and different
directions) are not represented in ``drift_force`` and are skipped with a note.
``drift_force`` takes the control-surface estimate (``.7``) when the run has it, else
pressure integration (``.9``), else momentum conservation (``.8``); the others are kept
as ``drift_force_<method>`` for ``cummins check`` to compare. Pressure integration
converges slowest with the panels: on the corpus's mean-drift sphere (WAMIT 7.311, low
order) it leaves the other two above ω ≈ 5 rad/s, where those agree within ~5 %.

QTF files (one row per frequency pair, heading pair and mode): ``PER1 PER2 BETA1 BETA2 I
Mod Pha Re Im``, normalised alike, F̄ = F/(ρ g A₁ A₂ L^k) — HydroDyn's WAMIT2 module
dimensionalises them by ρ g L^k and reads the Re and Im columns, as here. WAMIT writes
one triangle of the frequency square (PER1 ≤ PER2 in the corpus's OC4 semi, a title line
first); the other follows from Q⁻(ω₂, ω₁) = Q⁻(ω₁, ω₂)* and Q⁺(ω₂, ω₁) = Q⁺(ω₁, ω₂)
(:func:`cummins.qtf.complete_square`). ``d`` files hold the difference-frequency QTF,
``s`` files the sum-frequency QTF; ``.10``, ``.11`` and ``.12`` are the estimates of
WAMIT's different methods (HydroDyn accepts any of them): the reader takes ``.12``,
else ``.11``, else ``.10``, and says which in ``history``. The force convention is
:mod:`cummins.qtf.data`'s (WAMIT's time dependence e^{+iωt}, phases relative to the
incident wave at the origin, as the first-order files).

The first column follows the run's ``first_column`` (period by default, as the ``.1``).
Every frequency, heading and mode the file covers must be complete: a missing row is
damage (an error naming the file and line), never a zero.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError
from cummins.io._common import force_exponents, warn_damage
from cummins.io.wamit.detect import _sibling
from cummins.io.wamit.numeric import _limit_markers, _omega_from_first_column
from cummins.io.wamit.text import _numeric_rows, _read_text, _title_lines
from cummins.qtf.data import DRIFT_METHODS, QTFTable, complete_square

#: The mean-drift methods in order of preference for ``drift_force`` (the numeric files
#: and the ``.out``'s tables alike): the control surface converges fastest with the
#: panels; pressure integration, slowest, still computes heave, roll and pitch, which
#: momentum conservation (the far field) does not.
DRIFT_PREFERENCE: tuple[str, ...] = ("control_surface", "pressure", "momentum")
#: Mean-drift files by method, in order of preference for ``drift_force``.
DRIFT_FILES: dict[str, str] = {".7": "control_surface", ".9": "pressure", ".8": "momentum"}
#: QTF files of each kind, in order of preference.
QTF_FILES: dict[str, tuple[str, ...]] = {
    "difference": (".12d", ".11d", ".10d"),
    "sum": (".12s", ".11s", ".10s"),
}


@dataclass(frozen=True)
class _Rows:
    """The usable rows of a second-order file: first column(s), headings (rad), mode
    index (0-based), complex value (nondimensional), and the line of each row."""

    first: np.ndarray
    beta1: np.ndarray
    beta2: np.ndarray
    mode: np.ndarray
    value: np.ndarray
    line: np.ndarray
    notes: tuple[str, ...]


def _read_rows(path: Path, n_first: int, n_modes: int, first_column: str) -> tuple[_Rows, object]:
    """Parse the rows of a mean-drift (``n_first`` = 1) or QTF (2) file, with the damage
    checks: numbers cut short, a modulus that disagrees with Re and Im, mode indices."""
    text = _read_text(path)
    width = n_first + 7
    value_cols = (*range(n_first + 2), n_first + 3, n_first + 4, n_first + 5, n_first + 6)
    table, where = _numeric_rows(text, _title_lines(text), width, value_columns=value_cols)
    first = table[:, :n_first]
    beta1, beta2, mode = table[:, n_first], table[:, n_first + 1], table[:, n_first + 2]
    modulus, re, im = table[:, n_first + 3], table[:, n_first + 5], table[:, n_first + 6]
    notes: list[str] = []
    bad = (mode == 0) | (mode != np.round(mode)) | (np.abs(mode) > n_modes)
    if bad.any():
        r = int(np.argmax(bad))
        raise text.error(
            f"mode index {mode[r]:g} is not one of the run's modes 1…{n_modes}", where[r]
        )
    if np.any(np.abs(np.concatenate([beta1, beta2])) > 720):
        r = int(np.argmax((np.abs(beta1) > 720) | (np.abs(beta2) > 720)))
        raise text.error("a wave heading beyond ±720 deg is not an angle", where[r])
    value = re + 1j * im
    off = np.abs(np.abs(value) - modulus) > 1e-3 * np.abs(modulus) + 1e-6 * (
        np.abs(modulus).max() + 1e-300
    )
    if off.any():
        r = int(np.argmax(off))
        raise text.error(
            f"the modulus {modulus[r]:g} does not match the real and imaginary parts "
            f"({abs(value[r]):g}): an edited number?",
            where[r],
        )
    keep = mode > 0
    if not keep.all():
        notes.append(
            f"{path.name}: {int((~keep).sum())} rows of negative mode index (moments in the "
            "moving body axes) not read"
        )
    zero_mark, inf_mark = _limit_markers(first_column)
    limit = np.any((first == zero_mark) | (first == inf_mark) | (first < 0), axis=1)
    if first_column == "period" and np.any((first < 0) & (first != -1)):
        r = int(np.argmax(np.any((first < 0) & (first != -1), axis=1)))
        raise text.error("negative period other than -1 (the ω = 0 marker)", where[r])
    if (limit & keep).any():
        notes.append(
            f"{path.name}: {int((limit & keep).sum())} rows at the ω = 0 or ω = ∞ limit not read"
        )
    keep &= ~limit
    if not keep.any():
        raise text.error("no row at a finite frequency with a positive mode index")
    rows = _Rows(
        first[keep],
        np.radians(beta1[keep]),
        np.radians(beta2[keep]),
        mode[keep].astype(int) - 1,
        value[keep],
        where[keep],
        tuple(notes),
    )
    return rows, text


def _omega(values: np.ndarray, first_column: str, depth: float, g: float, text, where):
    with np.errstate(divide="ignore", invalid="ignore"):
        omega = _omega_from_first_column(values, first_column, depth=depth, g=g)
    bad = ~np.isfinite(omega) | (omega <= 0)
    if bad.any():
        r = int(np.argmax(bad.reshape(len(where), -1).any(axis=1)))
        raise text.error(f"first-column value is not a {first_column}", where[r])
    return omega


def read_mean_drift(
    path: Path,
    omega: np.ndarray,
    n_modes: int,
    *,
    first_column: str = "period",
    depth: float = np.inf,
    g: float = 9.81,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[str]]:
    """Read a WAMIT ``.7``, ``.8`` or ``.9`` file on the run's frequencies ``omega``.

    Returns
    -------
    values, directions, present, notes
        F̄ (nondimensional, real part; shape (nω, nβ, n_modes)), the headings (rad),
        which modes the file holds, and notes for ``history``.

    Raises
    ------
    HydroDataError
        Damage, a frequency the ``.1`` does not have, a missing row.
    """
    rows, text = _read_rows(path, 1, n_modes, first_column)
    notes = list(rows.notes)
    uni = np.isclose(rows.beta1, rows.beta2, atol=1e-9)
    if not uni.all():
        notes.append(
            f"{path.name}: {int((~uni).sum())} rows of two different wave headings "
            "(bi-directional mean drift) not read"
        )
    first, beta, mode = rows.first[uni, 0], rows.beta1[uni], rows.mode[uni]
    value, where = rows.value[uni], rows.line[uni]
    if first.size == 0:
        raise text.error("no rows of one wave heading (BETA1 = BETA2)")
    w = _omega(first, first_column, depth, g, text, where)
    k = np.searchsorted(omega, w)
    k = np.clip(k, 0, omega.size - 1)
    left = np.clip(k - 1, 0, omega.size - 1)
    k = np.where(np.abs(omega[left] - w) < np.abs(omega[k] - w), left, k)
    matched = np.abs(omega[k] - w) <= 1e-5 * w
    if not matched.all():
        r = int(np.argmax(~matched))
        raise text.error(
            f"frequency {w[r]:.6g} rad/s is not one of the .1 file's",
            where[r],
            hint="the .1 and the mean-drift files must come from the same run",
        )
    headings, h = np.unique(np.round(beta, 9), return_inverse=True)
    key = (k * headings.size + h) * n_modes + mode
    order = np.argsort(key, kind="stable")
    dup = np.flatnonzero(np.diff(key[order]) == 0)
    if dup.size:
        r = int(order[dup[0] + 1])
        raise text.error(
            f"the row of mode {mode[r] + 1} at {first[r]:g}, heading "
            f"{np.degrees(beta[r]):g} deg appears twice",
            where[r],
            hint="the file is damaged or two runs were joined",
        )
    given = np.zeros((omega.size, headings.size, n_modes), dtype=bool)
    given[k, h, mode] = True
    present = given.any(axis=(0, 1))
    need = np.broadcast_to(present, given.shape)
    missing = need & ~given
    if missing.any():
        kk, hh, mm = np.argwhere(missing)[0]
        raise HydroDataError(
            f"no mean drift of mode {mm + 1} at {omega[kk]:.6g} rad/s, heading "
            f"{np.degrees(headings[hh]):.6g} deg (a line deleted or the file cut?)",
            path=path,
            line=int(where.max()) + 1,
        )
    values = np.zeros(given.shape)
    values[k, h, mode] = value.real
    return values, headings, present, notes


def read_qtf(
    path: Path,
    kind: str,
    n_modes: int,
    *,
    first_column: str = "period",
    depth: float = np.inf,
    g: float = 9.81,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool, np.ndarray, list[str]]:
    """Read a WAMIT QTF file (``.10d`` … ``.12s``): the full square, nondimensional.

    Returns
    -------
    omega, directions, values, bidirectional, present, notes
        See :func:`cummins.qtf.complete_square`; ``values`` are F̄ (not yet scaled).
    """
    rows, text = _read_rows(path, 2, n_modes, first_column)
    w = _omega(rows.first, first_column, depth, g, text, rows.line)

    def error(message: str, r: int) -> HydroDataError:
        return text.error(message, int(rows.line[min(r, rows.line.size - 1)]))

    omega, directions, values, bidirectional, present = complete_square(
        kind,
        w[:, 0],
        w[:, 1],
        rows.beta1,
        rows.beta2,
        rows.mode,
        rows.value,
        n_dofs=n_modes,
        error=error,
    )
    return omega, directions, values, bidirectional, present, list(rows.notes)


def drift_variables(found, dofs: list[str], out: dict) -> None:
    """Put mean-drift estimates into ``out`` (``drift``, ``attrs``, ``history`` of
    :func:`wamit_second_order`): ``drift_force`` the first of ``found`` in the order of
    :data:`DRIFT_PREFERENCE`, ``drift_force_<method>`` the others, each with the method,
    its source and the DOFs it computes.

    Parameters
    ----------
    found
        (method, values (nω, nβ, n), DOFs present (n,), source name) per estimate.
    dofs
        The DOF labels.
    """
    rank = {m: k for k, m in enumerate(DRIFT_PREFERENCE)}
    found = sorted(found, key=lambda item: rank[item[0]])
    for k, (method, values, present, source) in enumerate(found):
        name = "drift_force" if k == 0 else f"drift_force_{method}"
        out["drift"][name] = (values, f"{DRIFT_METHODS[method]}, {source}")
        computed = [d for d, p in zip(dofs, present, strict=True) if p]
        out["attrs"][name] = {"source": source, "dofs_computed": " ".join(computed)}
        missing = [d for d, p in zip(dofs, present, strict=True) if not p]
        out["history"].append(
            f"{name}: mean drift by {DRIFT_METHODS[method]} from {source}"
            + (f" ({', '.join(missing)} not computed by it: 0)" if missing else "")
        )


def second_order_files(dot1: Path) -> dict[str, Path]:
    """The second-order files of the run of ``dot1`` (same stem), by suffix."""
    found = {}
    for suffix in (*DRIFT_FILES, *QTF_FILES["difference"], *QTF_FILES["sum"]):
        p = _sibling(dot1, suffix)
        if p is not None and p.stat().st_size > 0:
            found[suffix] = p
    return found


def wamit_second_order(
    dot1: Path,
    *,
    omega: np.ndarray,
    directions: np.ndarray | None,
    dofs: list[str],
    layout,
    rho: float,
    g: float,
    ulen: float,
    first_column: str,
    depth: float,
    notes: list[str],
) -> dict:
    """The second-order data of a WAMIT run, dimensional, for :func:`with_second_order`.

    Returns a dict with ``tables`` (:class:`~cummins.qtf.QTFTable` s), ``drift`` (the
    ``drift`` argument), ``directions`` (the headings the mean drift defines when the
    run has no first-order ones) and ``history``. A damaged second-order file does not
    stop the run from reading: it is left out with a warning (``notes``) saying so.
    """
    files = second_order_files(dot1)
    n = len(dofs)
    scale = rho * g * ulen ** force_exponents(n, 1, layout)
    history: list[str] = []
    out: dict = {"tables": [], "drift": {}, "directions": None, "history": history, "attrs": {}}
    read_drift: list[tuple[str, np.ndarray, np.ndarray, np.ndarray, Path]] = []
    for suffix, method in DRIFT_FILES.items():
        path = files.get(suffix)
        if path is None:
            continue
        try:
            values, beta, present, lines = read_mean_drift(
                path, omega, n, first_column=first_column, depth=depth, g=g
            )
        except HydroDataError as exc:
            warn_damage(f"mean drift not read: {exc}", path=path, notes=notes)
            continue
        history.extend(lines)
        read_drift.append((method, values * scale, beta, present, path))
    if read_drift:
        reference = directions if directions is not None else read_drift[0][2]
        kept = []
        for method, values, beta, present, path in read_drift:
            if beta.shape != reference.shape or not np.allclose(
                np.mod(beta, 2 * np.pi), np.mod(reference, 2 * np.pi), atol=1e-6
            ):
                warn_damage(
                    "mean drift not read: its headings "
                    f"({', '.join(f'{b:g}' for b in np.degrees(beta))} deg) differ from the "
                    "run's first-order ones",
                    path=path,
                    notes=notes,
                )
                continue
            kept.append((method, values, present, path.name))
        if directions is None and kept:
            out["directions"] = reference
        drift_variables(kept, dofs, out)
    for kind, suffixes in QTF_FILES.items():
        available = [s for s in suffixes if s in files]
        for suffix in available:
            path = files[suffix]
            try:
                w, beta, values, bidirectional, present, lines = read_qtf(
                    path, kind, n, first_column=first_column, depth=depth, g=g
                )
            except HydroDataError as exc:
                warn_damage(f"{kind}-frequency QTF not read: {exc}", path=path, notes=notes)
                continue
            values = values * scale
            out["tables"].append(QTFTable(kind, w, beta, values, tuple(dofs), bidirectional))
            computed = [d for d, p in zip(dofs, present, strict=True) if p]
            missing = [d for d, p in zip(dofs, present, strict=True) if not p]
            out["attrs"][QTFTable(kind, w, beta, values, tuple(dofs), bidirectional).name] = {
                "source": path.name,
                "dofs_computed": " ".join(computed),
            }
            history.extend(lines)
            others = [files[s].name for s in available if s != suffix]
            history.append(
                f"{kind}-frequency QTF from {path.name}: {w.size} frequencies "
                f"{w[0]:.4g}–{w[-1]:.4g} rad/s, {beta.size} heading(s)"
                + (" (bi-directional)" if bidirectional else "")
                + (f", {', '.join(missing)} not in the file: 0" if missing else "")
                + (f"; {', '.join(others)} not read (one QTF per kind)" if others else "")
            )
            break
    return out


def attach_wamit_second_order(ds, second: dict):
    """``ds`` with what :func:`wamit_second_order` read (itself when it read nothing)."""
    from cummins.qtf.data import with_second_order

    if not (second["tables"] or second["drift"]):
        return ds
    return with_second_order(
        ds,
        second["tables"],
        drift=second["drift"],
        wave_direction=second["directions"],
        history=second["history"],
        attrs=second["attrs"],
    )
