"""A WAMIT run assembled (:func:`read_wamit`, :func:`read_wamit_run`): the ``.1`` file
and its siblings with the same stem (``.3``, ``.4``, ``.hst``, ``.frc``, ``.mmx``,
``.cfg``, ``.pot``, ``.out``), made dimensional with ρ, g and ULEN (WAMIT User Manual v7,
§4.1); the excitation from the ``.out`` when there is no ``.3``. A ``.1`` in a HAMS
project is read by :func:`cummins.io.hams.read_hams`.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Sequence
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
from cummins.io.wamit.detect import _sibling, is_out_file, numeric_kind
from cummins.io.wamit.frc import _read_frc
from cummins.io.wamit.input_files import _Config, _Mmx, _read_cfg, _read_mmx, _read_pot_bodies
from cummins.io.wamit.mass import _body_attrs, _mass_matrices, _restoring_weight
from cummins.io.wamit.modes import _check_memory, _mode_layout
from cummins.io.wamit.numeric import (
    FIRST_COLUMNS,
    _dot1_arrays,
    _parse_dot1,
    _read_hst,
    _read_wave_file,
)
from cummins.io.wamit.out import DRIFT_SECTIONS, _read_out_text, read_wamit_out
from cummins.io.wamit.out_header import _hydrostatics_matrix, _out_header, _OutHeader
from cummins.io.wamit.second_order import attach_wamit_second_order, wamit_second_order
from cummins.io.wamit.settings import RunSettings
from cummins.io.wamit.text import _read_out_log
from cummins.qtf.data import DRIFT_ALTERNATIVES


def _hams_project(dot1: Path) -> Path | None:
    """The HAMS project folder of a file in ``<project>/Output*/Wamit_format/``."""
    folder = dot1.resolve().parent
    if folder.name == "Wamit_format":
        project = folder.parent.parent
        if (project / "Input" / "ControlFile.in").is_file():
            return project
    return None


def read_wamit(
    path: str | os.PathLike[str],
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    first_column: str | None = None,
    siblings: bool = True,
    modes: int | Sequence[int] | None = None,
    water_depth: float | None = None,
) -> xr.Dataset:
    """Read a WAMIT run into a canonical ``HydroDB``.

    Parameters
    ----------
    path
        A ``.1`` file (its ``.3``, ``.4``, ``.hst``, ``.frc``, ``.mmx``, ``.cfg``,
        ``.pot`` and ``.out`` siblings with the same stem are read too, unless
        ``siblings=False``), a ``.3`` or ``.hst`` file (then the ``.1`` sibling is
        required), or a ``.out`` file (read on its own, see :func:`read_wamit_out`). A
        ``.1`` in a HAMS project's ``Output/Wamit_format/`` is read with the HAMS
        project's settings (:func:`cummins.io.hams.read_hams`).
    rho, g, ulen
        Water density (kg/m³), gravity (m/s²) and WAMIT length scale ULEN (m) used to
        make the numbers dimensional. By default they come from the ``.out`` header
        (ρ also from the ``.frc``), else ρ = 1025, g = 9.81, ULEN = 1.
    first_column
        What the first column of the numeric files holds: ``"period"`` (s, WAMIT's
        default), ``"omega"`` (rad/s), ``"wavenumber"`` (finite depth),
        ``"wavenumber_deep"`` or ``"wavelength"``; by default from the ``.cfg``
        (IPEROUT/IPERIO), else period.
    siblings
        Read the sibling files of a ``.1`` file.
    modes
        Modes per body (an int for one body, or one per body), when the files do not
        say (a ``.1`` without its ``.out``/``.pot``/``.cfg`` and DOF indices beyond 6).
    water_depth
        m (``inf``: deep water), when the ``.out`` does not record it (it converts a
        wavenumber first column and is the depth of the wave kinematics); default deep
        water, said by an ``AssumptionWarning`` where a result depends on it. A value
        that contradicts the ``.out`` is an error.

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
        return read_wamit_out(path, rho=rho, g=g, ulen=ulen, modes=modes, water_depth=water_depth)
    kind = numeric_kind(path)
    if kind is None:
        raise HydroDataError(
            "not a WAMIT .1, .3, .hst, second-order or .out file (unrecognised content)",
            path=path,
        )
    dot1 = path if kind == ".1" else _sibling(path, ".1")
    if dot1 is None:
        raise HydroDataError(
            f"a WAMIT {kind} file alone has no added mass and damping",
            path=path,
            hint=f"put the .1 file of the same run next to it ({path.with_suffix('.1').name})",
        )
    project = _hams_project(dot1)
    if project is not None and first_column is None:
        from cummins.io.hams import read_hams

        return read_hams(project, rho=rho, g=g, output=dot1.parent.parent, siblings=siblings)
    return read_wamit_run(
        dot1,
        rho=rho,
        g=g,
        ulen=ulen,
        first_column=first_column,
        siblings=siblings or kind != ".1",
        modes=modes,
        entry=path,
        water_depth=water_depth,
    )


#: What each sibling of a ``.1`` gives, for the warning when it is empty.
_SIBLING_GIVES = {
    ".3": "no wave excitation",
    ".4": "no motion RAOs of the solver",
    ".hst": "no hydrostatic restoring",
    ".frc": "no inertia or external matrices",
    ".out": "no constants, body parameters or mass properties from the log",
    ".mmx": "no mass or external matrices",
    ".cfg": "no settings (first column, modes)",
    ".pot": "no body names",
}


def _nonempty_sibling(dot1: Path, suffix: str, history: list[str], notes: list[str]) -> Path | None:
    """The sibling file with ``suffix``; an empty one (0 bytes) is skipped with a warning,
    as a damaged one is: the quantity it holds is lost (a solver that wrote nothing there
    writes no file)."""
    p = _sibling(dot1, suffix)
    if p is not None and p.stat().st_size == 0:
        history.append(f"{p.name} is empty (0 bytes): skipped")
        warn_damage(
            f"the file is empty (0 bytes): skipped, so {_SIBLING_GIVES.get(suffix, 'nothing')} "
            "from it",
            path=p,
            notes=notes,
        )
        return None
    return p


def read_wamit_run(
    dot1: Path,
    *,
    rho: float | None = None,
    g: float | None = None,
    ulen: float | None = None,
    first_column: str | None = None,
    siblings: bool = True,
    modes: int | Sequence[int] | None = None,
    settings: RunSettings | None = None,
    entry: Path | None = None,
    water_depth: float | None = None,
) -> xr.Dataset:
    """Read the WAMIT-format run of the ``.1`` file ``dot1`` (see :func:`read_wamit`);
    ``settings`` carry what another program's project fixes (HAMS)."""
    settings = settings or RunSettings()
    history: list[str] = [f"read {dot1.name}", *settings.history]
    notes: list[str] = list(settings.notes)

    def sibling(suffix: str) -> Path | None:
        if not siblings and not (entry is not None and entry.suffix.lower() == suffix):
            return None
        return _nonempty_sibling(dot1, suffix, history, notes)

    dot3, dot4, hst = sibling(".3"), sibling(".4"), sibling(".hst")
    out_path, frc_path = sibling(".out"), sibling(".frc")
    mmx_path, cfg_path, pot_path = sibling(".mmx"), sibling(".cfg"), sibling(".pot")

    header = _OutHeader()
    out_text = _read_out_log(out_path) if out_path is not None else None
    have_out = out_text is not None
    if have_out:
        header = _out_header(out_text)
        history.append(f"constants and body parameters from {out_path.name}")
        if not header.has_gravity_line or header.ulen is None:
            warn_damage(
                "the .out header has no 'Gravity: … Length scale: …' line (damaged?): "
                "g and ULEN not taken from it",
                path=out_path,
                notes=notes,
            )
        for body in header.bodies:
            history.extend(body.notes)
    cfg = _Config()
    if cfg_path is not None:
        try:
            cfg = _read_cfg(cfg_path)
        except HydroDataError as exc:
            warn_damage(f"not read: {exc}", path=cfg_path, notes=notes)
    column = first_column or settings.first_column or cfg.first_column or "period"
    if column not in FIRST_COLUMNS:
        raise HydroDataError(
            f"first_column must be one of {', '.join(FIRST_COLUMNS)}, got {column!r}"
        )
    if column != "period":
        history.append(f"first column of the numeric files: {column}")
    depth = settings.water_depth if settings.water_depth is not None else header.water_depth
    depth_assumed = depth is None and water_depth is None
    if depth is not None and water_depth is not None and not _same_depth(depth, water_depth):
        raise HydroDataError(
            f"water_depth = {water_depth:g} m was given but the run records {depth:g} m",
            path=out_path or dot1,
            hint="the coefficients were computed at the recorded depth: drop --water-depth",
        )
    if depth is None and water_depth is not None:
        history.append(f"water depth = {water_depth:g} m (given)")
    depth = (np.inf if water_depth is None else float(water_depth)) if depth is None else depth
    if depth_assumed:
        history.append(
            "water depth not recorded (no .out): deep water assumed; pass water_depth= "
            "(--water-depth) to change"
        )
    g_guess = g or settings.g or header.g or 9.81
    d = _parse_dot1(dot1, column, depth=depth, g=g_guess)
    history.extend(d.notes)

    pot_names = None
    if pot_path is not None and not header.bodies:
        try:
            pot_names = _read_pot_bodies(pot_path)
        except HydroDataError as exc:
            warn_damage(f"not read: {exc}", path=pot_path, notes=notes)
    mmx = _Mmx()
    if mmx_path is not None:
        try:
            mmx = _read_mmx(mmx_path)
        except HydroDataError as exc:
            warn_damage(f"not read: {exc}", path=mmx_path, notes=notes)
    n_bodies = (
        len(header.bodies) if header.bodies else (len(pot_names) if pot_names else mmx.n_bodies)
    )
    layout = _mode_layout(
        d.n_seen,
        n_bodies=n_bodies,
        new_modes=cfg.new_modes,
        extra_modes=header.extra_modes if have_out and header.bodies else None,
        modes=modes,
        path=dot1,
        history=history,
    )
    n = sum(layout)
    _check_memory(n, d.omega.size, 1, dot1)

    frc = None
    if frc_path is not None:
        try:
            frc = _read_frc(frc_path, n, len(layout), cfg.ialtfrc)
            history.append(f"{frc_path.name}: alternative form {frc.form}")
        except HydroDataError as exc:
            warn_damage(
                f"not read, so no inertia or external matrices from it: {exc}",
                path=frc_path,
                notes=notes,
            )
    rho_in_file = header.rho if header.rho is not None else (frc.rho if frc else None)
    rho_source = g_source = None
    if rho_in_file is None:
        rho_in_file, rho_source = settings.rho, settings.constants_source
    if header.g is None:
        g_source = settings.constants_source
    rho_v, g_v = resolve_rho_g(
        rho,
        g,
        rho_in_file,
        header.g if header.g is not None else settings.g,
        path=dot1,
        history=history,
        dimensional=False,
        sources=(rho_source, g_source),
    )
    L = resolve_constant(
        "ulen",
        ulen,
        header.ulen if header.ulen is not None else settings.ulen,
        1.0,
        unit="m",
        path=dot1,
        history=history,
        dimensional=False,
    )
    if column != "period" and column != "omega" and not np.isclose(g_v, g_guess):
        d = _parse_dot1(dot1, column, depth=depth, g=g_v)

    a_bar, b_bar, a_zero, a_inf = _dot1_arrays(d, n)
    omega = d.omega
    scale_a = rho_v * L ** length_exponents(n, 3, layout)
    extra: dict = {
        "added_mass": a_bar * scale_a,
        "radiation_damping": b_bar * scale_a * omega[:, None, None],
    }
    if a_inf is not None:
        extra["added_mass_inf"] = a_inf * scale_a
    if a_zero is not None:
        extra["added_mass_zero"] = a_zero * scale_a
    force_scale = rho_v * g_v * L ** force_exponents(n, 2, layout)
    parsed_out = None  # the .out read whole for the excitation, reused for the drift
    if dot3 is not None:
        x_bar, beta = _read_wave_file(dot3, d.first, n, what="excitation")
        extra["excitation_force"] = x_bar * force_scale
        extra["wave_direction"] = beta
        history.append(f"excitation from {dot3.name}")
    elif have_out:
        parsed_out = _excitation_from_out(
            out_text, header, omega, layout, (rho_v, g_v, L), extra, history
        )
    if dot4 is not None:
        try:
            rao_bar, beta4 = _read_wave_file(dot4, d.first, n, what="RAO")
            if "wave_direction" in extra and not (
                beta4.shape == extra["wave_direction"].shape
                and np.allclose(beta4, extra["wave_direction"])
            ):
                raise HydroDataError("its headings differ from the excitation headings", path=dot4)
            extra["rao"] = rao_bar / L ** rotation_flags(n, layout)
            if settings.rao_times_rho_g:
                extra["rao"] = extra["rao"] * (-1j * rho_v * g_v)
                history.append(f"{dot4.name}: RAOs written as i·ξ/(rho g) by HAMS, multiplied back")
            extra.setdefault("wave_direction", beta4)
            history.append(f"motion RAOs from {dot4.name} (the solver's own)")
        except HydroDataError as exc:
            warn_damage(f"RAOs not read: {exc}", path=dot4, notes=notes)
    restoring_from = None
    if hst is not None:
        try:
            extra["hydrostatic_stiffness"] = _read_hst(hst, n) * (
                rho_v * g_v * L ** length_exponents(n, 2, layout)
            )
            history.append(f"hydrostatics from {hst.name}")
            restoring_from = hst.name
        except HydroDataError as exc:
            warn_damage(f"hydrostatics not read: {exc}", path=hst, notes=notes)
    elif header.bodies and all(b.hydrostatics for b in header.bodies) and n == 6 * len(layout):
        extra["hydrostatic_stiffness"] = _hydrostatics_matrix(header, layout) * (
            rho_v * g_v * L ** length_exponents(n, 2, layout)
        )
        history.append(f"hydrostatics from {out_path.name} (no .hst file)")
        restoring_from = out_path.name
    if restoring_from is not None:
        extra.update(
            _restoring_weight(restoring_from, header, layout, frc, rho_v, settings, out_path)
        )

    _mass_matrices(
        extra,
        layout,
        rho_v,
        header,
        frc,
        frc_path,
        mmx,
        mmx_path,
        out_path,
        settings,
        history,
        notes,
        omega.size,
    )
    names = header.body_names if len(header.body_names) == len(layout) else (pot_names or [])
    labels = dof_labels(len(layout) if len(layout) > 1 else None, layout)
    second = None
    if siblings:
        second = wamit_second_order(
            dot1,
            omega=omega,
            directions=extra.get("wave_direction"),
            dofs=labels,
            layout=layout,
            rho=rho_v,
            g=g_v,
            ulen=L,
            first_column=column,
            depth=depth,
            notes=notes,
        )
    ds = make_hydrodb(
        omega,
        extra.pop("added_mass"),
        extra.pop("radiation_damping"),
        rho=rho_v,
        g=g_v,
        water_depth=depth,
        source_format=settings.source_format,
        source_file=str(dot1),
        dofs=labels,
        history=history,
        read_warnings=notes,
        ulen=L,
        body_names="\n".join(names) if len(names) == len(layout) else None,
        **{DEPTH_ASSUMED: 1 if depth_assumed else None},
        **extra,
        **_body_attrs(header, layout, settings),
    )
    if second is not None and have_out and not second["drift"]:
        _drift_from_out(
            (out_text, header, parsed_out),
            second,
            omega,
            extra.get("wave_direction"),
            (rho_v, g_v, L),
            layout,
            notes,
        )
    return ds if second is None else attach_wamit_second_order(ds, second)


def _same_depth(a: float, b: float) -> bool:
    """Two water depths (m, ``inf`` for deep water) that are the same."""
    return (np.isinf(a) and np.isinf(b)) or bool(np.isclose(a, b, rtol=1e-6))


def _drift_from_out(out, second: dict, omega, directions, constants, layout, notes) -> None:
    """The mean drift printed in the ``.out`` (``out``: its text, its header and the
    dataset :func:`_excitation_from_out` read from it, if any) into ``second`` (of
    :func:`~cummins.io.wamit.second_order.wamit_second_order`) when the run has no
    ``.7``/``.8``/``.9``: every method the log prints, ``drift_force`` the preferred one
    (:data:`~cummins.io.wamit.second_order.DRIFT_PREFERENCE`). ``second["attrs"]`` and
    ``["history"]`` say where it came from; a log of other frequencies or headings is
    left out with a line in ``history``, a damaged one with a warning."""
    text, header, parsed = out
    out_path = text.path
    if not any("DRIFT FORCES" in line for line in text.lines):
        return
    history = second["history"]
    try:
        with warnings.catch_warnings():  # the header's warnings were given with the .1
            warnings.simplefilter("ignore")
            rho, g, ulen = constants
            out = parsed or _read_out_text(
                text, header, rho=rho, g=g, ulen=ulen, modes=layout, sections=DRIFT_SECTIONS
            )
    except HydroDataError as exc:
        warn_damage(f"mean drift not read: {exc}", path=out_path, notes=notes)
        return
    names = [name for name in ("drift_force", *DRIFT_ALTERNATIVES) if name in out]
    if not names:
        return
    if out.sizes["omega"] != omega.size or not np.allclose(out.omega.values, omega, rtol=1e-5):
        history.append(f"no mean drift from {out_path.name}: it has other frequencies")
        return
    beta = out.wave_direction.values
    if directions is not None and (
        beta.shape != directions.shape or not np.allclose(beta, directions)
    ):
        history.append(f"no mean drift from {out_path.name}: it has other wave directions")
        return
    for name in names:
        var = out[name].transpose("omega", "wave_direction", "influenced_dof")
        second["drift"][name] = (var.values, var.attrs["method"])
        second["attrs"][name] = {k: var.attrs[k] for k in ("source", "dofs_computed")}
    if directions is None:
        second["directions"] = beta
    history.append(
        f"mean drift from {out_path.name} (no .7, .8 or .9 file; the log prints 6-7 "
        f"digits): drift_force by {out.drift_force.attrs['method']}"
    )


def _excitation_from_out(text, header, omega, layout, constants, extra, history) -> xr.Dataset:
    """Excitation printed in the ``.out`` (``text``, its ``header`` parsed) when the run
    has no ``.3`` file, into ``extra``; the log read as :func:`read_wamit_out` does (all
    its tables, for :func:`_drift_from_out` too)."""
    rho_v, g_v, L = constants
    out = _read_out_text(text, header, rho=rho_v, g=g_v, ulen=L, modes=layout)
    out_path = text.path
    if "excitation_force" not in out:
        history.append(f"no excitation: no .3 file, and {out_path.name} prints none")
        return out
    if out.sizes["omega"] != omega.size or not np.allclose(out.omega.values, omega, rtol=1e-5):
        history.append(f"no excitation: no .3 file, and {out_path.name} has other frequencies")
        return out
    extra["excitation_force"] = out.excitation_force.values
    extra["wave_direction"] = out.wave_direction.values
    history.append(
        f"excitation from {out_path.name} (no .3 file; the log prints 7 digits and phases "
        "in whole degrees)"
    )
    return out
