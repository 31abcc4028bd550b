"""Self-contained HTML reports of what cummins reads and writes.

:func:`write_report` looks at a file, decides what it is (:func:`detect_kind`) and writes
one HTML page of the pipeline's figures and tables for it:

``data`` (a hydrodynamic database: any solver file or folder cummins reads)
    the data checks (:func:`cummins.check`), added mass and damping, excitation, the
    retardation functions K(t) and the coupled motion RAOs;
``model`` (a radiation model from ``cummins fit``/``reduce``)
    the per-coupling table (order, R² of A, B, K(t), passivity) and, when the data it was
    fitted to are at hand, the data against the model for every coupling, and K(t);
``excitation-model`` (a wave excitation model from ``cummins fit-excitation``)
    states, t_c and NRMSE per heading and DOF, and F(ω) and K_ex(t) of the model against
    its data (:mod:`cummins.cli.html_excitation`);
``rao`` (a RAO file from ``cummins rao``)
    the RAOs and their largest values; with PTOs their power RAO, force and relative
    motion (:mod:`cummins.cli.html_pto`);
``run`` (a simulation from ``cummins simulate``)
    the response statistics (the amplitude in regular waves), time series and response
    spectra; with PTOs their mean power, energy and time series;
``kernel`` (the output of ``cummins kernel``)
    the diagnostics of every significant coupling and K(t);
``batch`` (results of ``cummins batch``)
    the study, the operability per heading, the limiting H_s per heading and T_p, and
    the statistics of the cases (all, or the worst when there are many); with PTOs the
    power matrix.

The figures are the library's (:mod:`cummins.plots`), drawn as PNG and embedded as
``data:`` URIs; the style sheet is inline. The page makes no request of its own: it can
be mailed, archived or opened offline.
The page itself (sections, figures, tables, style sheet) is assembled by
:mod:`cummins.cli.html_page`.

Examples
--------
>>> import cummins, tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "tanker.html"
>>> page = write_report(cummins.demo_files() / "tanker.1", out)   # doctest: +SKIP
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.cli.html_cases import cases_body
from cummins.cli.html_excitation import excitation_model_sections
from cummins.cli.html_page import Section as Section
from cummins.cli.html_page import _note, failures_html, figure_html, table_html
from cummins.cli.html_page import render_html as render_html
from cummins.cli.html_pto import pto_batch_sections, pto_rao_sections, pto_run_sections
from cummins.display import peak_index
from cummins.errors import CumminsError, check_writable
from cummins.files import files_read, fitted_data_file, refuse_overwriting_inputs, replacing
from cummins.hydrodb import is_rotation

__all__ = ["KINDS", "Section", "detect_kind", "render_html", "report_sections", "write_report"]

#: What a report can be made of.
KINDS: dict[str, str] = {
    "data": "hydrodynamic database",
    "model": "radiation model",
    "excitation-model": "wave excitation model",
    "rao": "motion RAOs",
    "run": "time-domain simulation",
    "dp": "nonlinear 6-DOF (DP) simulation",
    "lf": "low-frequency manoeuvring model",
    "kernel": "retardation functions (cummins kernel)",
    "batch": "batch study results",
}


class ReportError(CumminsError, ValueError):
    """A file a report cannot be made of."""


# --------------------------------------------------------------------------- detection


def detect_kind(path: str | os.PathLike[str]) -> str:
    """What ``path`` holds: one of :data:`KINDS` (by content, not by name).

    Raises
    ------
    ReportError
        ``path`` does not exist.
    """
    p = Path(path)
    if not p.exists():
        raise ReportError(f"{p} does not exist")
    if p.is_dir() and p.suffix.lower() != ".zarr":
        return "data"
    if p.suffix.lower() == ".zarr":
        return "batch"
    from cummins.files import is_hdf5

    if not is_hdf5(p):
        return "data"
    import h5py

    from cummins.excitation_model.model_file import FORMAT_NAME as EXCITATION
    from cummins.radiation.model_file import FORMAT_NAME as RADIATION

    try:
        with h5py.File(p, "r") as f:
            model_format = f.attrs.get("cummins_format")
            result_kind = f.attrs.get("cummins_kind")
            names = set(f.keys())
    except OSError as exc:  # an HDF5 signature on a damaged or truncated file
        raise ReportError(
            f"{p} starts like an HDF5/NetCDF file but cannot be opened ({exc})",
            hint="The file is damaged or truncated: write it again",
        ) from None
    model_format = model_format.decode() if isinstance(model_format, bytes) else model_format
    model = {RADIATION: "model", EXCITATION: "excitation-model"}.get(model_format)
    if model is not None:
        return model
    result_kind = result_kind.decode() if isinstance(result_kind, bytes) else result_kind
    from cummins.studies.study import _RESULT_KIND

    if result_kind == _RESULT_KIND:
        return "batch"
    if "rao" in names and "complex" in names:
        return "rao"
    if {"motion", "time", "wave_elevation"} <= names:
        return "run"
    if {"eta", "nu", "time"} <= names:
        return "dp"
    if {"added_mass", "damping", "stiffness", "frequency", "provenance"} <= names:
        return "lf"
    if {"retardation_function", "K0", "significant"} <= names:
        return "kernel"
    return "data"


def _check_kind(path: Path, kind: str) -> None:
    """ArgumentError when ``kind`` (``--kind``) is not what the file holds."""
    from cummins.errors import ArgumentError

    if kind not in KINDS:
        raise ArgumentError(f"unknown report kind {kind!r}; use one of {', '.join(KINDS)}")
    found = detect_kind(path)
    if found != kind:
        raise ArgumentError(
            f"{path} is a {found} file ({KINDS[found]}), not a {kind} file ({KINDS[kind]})",
            hint=f"Leave --kind out (it is detected from the content), or give a {kind} file",
        )


# --------------------------------------------------------------------------- sections


def _check_section(ds) -> Section:
    from cummins.check import check

    report = check(ds)
    rows, classes = [], []
    style = {"error": "bad", "warning": "warning", "ok": "good", "info": ""}
    for f in report:
        rows.append([f.severity, f.check, f.where or "", f.message])
        classes.append([style.get(f.severity, ""), "", "", ""])
    verdict = "usable" if report.ok else "NOT usable as it is"
    body = _note(f"Result: {verdict} (worst finding: {report.worst()}).") + table_html(
        ["severity", "check", "where", "finding"], rows, classes=classes
    )
    return Section("Data checks", body)


def data_sections(ds: xr.Dataset) -> list[Section]:
    """Checks, added mass and damping, excitation, K(t) and RAOs of a ``HydroDB``."""
    from cummins.hydrodb import describe
    from cummins.plots import plot_added_mass_damping, plot_excitation, plot_retardation
    from cummins.radiation.retardation import retardation_function

    info = describe(ds)
    rows = [
        ["file", f"{info['source_file']} ({info['source_format']})"],
        ["DOFs", ", ".join(info["dofs"])],
        [
            "frequencies",
            f"{info['n_omega']} from {info['omega_min_rad_s']:.4g} to "
            f"{info['omega_max_rad_s']:.4g} rad/s",
        ],
        ["wave directions", ", ".join(f"{b:g}" for b in info["wave_directions_deg"]) + " deg"],
        ["forward speeds", ", ".join(f"{u:g}" for u in info["forward_speeds_m_s"]) + " m/s"],
        ["rho, g", f"{info['rho_kg_m3']:g} kg/m³, {info['g_m_s2']:g} m/s²"],
    ]
    sections = [Section("Contents", table_html(["", ""], rows)), _check_section(ds)]
    one = ds.isel(forward_speed=0) if "forward_speed" in ds.dims else ds
    figures = [figure_html(plot_added_mass_damping(one), "Added mass A(ω) and damping B(ω)")]
    if "excitation_force" in one and "wave_direction" in one.dims:
        figures.append(figure_html(plot_excitation(one), "Wave excitation force per heading"))
    sections.append(Section("Added mass, damping and excitation", "".join(figures)))
    kernel = retardation_function(one)
    sections.append(
        Section(
            "Retardation functions K(t)",
            figure_html(plot_retardation(kernel), "K(t) = (2/π)∫B(ω)cos(ωt)dω, diagonal"),
        )
    )
    sections.append(_rao_data_section(one))
    second = _second_order_section(one)
    if second is not None:
        sections.append(second)
    return sections


def _second_order_section(ds: xr.Dataset) -> Section | None:
    """|Q(ω₁, ω₂)| of the QTFs and what the data hold (None without second-order data)."""
    from cummins.cli.info import second_order_lines
    from cummins.qtf import QTF_VARIABLES, second_order_summary
    from cummins.qtf.figures import plot_qtf

    summary = second_order_summary(ds)
    if not summary:
        return None
    body = table_html(["second-order data"], [[line] for line in second_order_lines(summary)])
    for kind, name in QTF_VARIABLES.items():
        if name in ds:
            body += figure_html(plot_qtf(ds, kind), f"{kind}-frequency QTF |Q(ω₁, ω₂)|")
    return Section("Second-order wave loads", body)


def _rao_data_section(ds: xr.Dataset) -> Section:
    from cummins.plots import plot_rao
    from cummins.seakeeping.frequency_domain import motion_rao

    try:
        headings = np.radians([90.0, 135.0, 180.0])
        w = ds.omega.values
        rao = motion_rao(ds, np.linspace(w[0], w[-1], 300), headings)
    except CumminsError as exc:
        return Section("Motion RAOs", _note(f"not computed: {exc}"))
    return Section(
        "Motion RAOs",
        figure_html(plot_rao(rao), "Coupled motion RAOs, beam to head seas (90°, 135°, 180°)")
        + rao_table_html(rao),
    )


def rao_table_html(rao: xr.DataArray) -> str:
    """Largest |RAO| of each DOF with its frequency and heading."""
    w = rao.omega.values
    rows = []
    for dof in rao.dof.values:
        amp = np.abs(rao.sel(dof=dof).transpose("omega", "wave_direction").values)
        i, j = peak_index(amp)
        rows.append(
            [
                str(dof),
                float(amp[i, j]),
                "rad/m" if is_rotation(str(dof)) else "m/m",
                float(w[i]),
                float(2 * np.pi / w[i]),
                float(np.degrees(rao.wave_direction.values[j])),
            ]
        )
    return table_html(
        ["DOF", "max |RAO|", "unit", "ω [rad/s]", "period [s]", "heading [deg]"], rows
    )


def model_sections(path: Path) -> list[Section]:
    """The fit table, K(t) of the model and, with its data, the fit of every coupling."""
    from cummins.cli.failed_model import model_failures
    from cummins.fit_figures import fit_figures
    from cummins.plots import plot_retardation
    from cummins.radiation.model import RadiationModel

    model = RadiationModel.load(path)
    failures = model_failures(model.attrs)
    box = failures_html(
        failures,
        f"This model missed its fit targets ({len(failures)}; cummins fit exits with status "
        "3): results made with it inherit it.",
    )
    rows = []
    for k in model.modelled:
        if k.influenced > k.radiating:
            continue
        m = k.metrics
        rows.append(
            [
                f"{model.dofs[k.influenced]}–{model.dofs[k.radiating]}",
                int(m.get("common_poles", k.order)),
                m.get("r2_added_mass", np.nan),
                m.get("r2_damping", np.nan),
                m.get("r2_kernel", np.nan),
                bool(k.is_stable()),
                m.get("passive", "") if k.influenced == k.radiating else "",
            ]
        )
    sections = [
        Section(
            "Fitted couplings",
            box
            + _note(
                f"{len(model.dofs)} DOFs, total order {model.total_order}, MIMO passive: "
                f"{model.attrs.get('mimo_passive', 'not recorded')}."
                + "".join(
                    f" {'-'.join(model.dofs[d] for d in b.dofs)}: one block of {b.order} "
                    "states (the order of its pairs is the number of common poles)."
                    for b in model.blocks
                )
            )
            + table_html(
                ["coupling", "order", "R² A", "R² B", "R² K(t)", "stable", "positive real"], rows
            ),
        )
    ]
    poles = [c.poles() for c in model.couplings if c.order]
    poles += [b.poles() for b in model.blocks if b.order]
    slowest = min(float(np.abs(p.real).min()) for p in poles) if poles else 1.0
    t = np.linspace(0.0, min(5.0 / max(slowest, 1e-3), 200.0), 600)
    sections.append(
        Section(
            "Retardation functions of the model",
            figure_html(plot_retardation(model.impulse_response(t)), "K(t) = C e^{At} B"),
        )
    )
    source, named = fitted_data_file(model.attrs, path)
    if source is None:
        sections.append(
            Section("Fits", _note(f"the data the model was fitted to ({named}) are not at hand"))
        )
        return sections
    from cummins.io import read

    ds = read(source)
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    figures = [
        figure_html(fig, f"{name[4:-4]}: its couplings, data against the model")
        for name, fig in fit_figures(model, ds)
    ]
    sections.append(Section(f"Fits against the data ({Path(str(source)).name})", "".join(figures)))
    return sections


def rao_sections(path: Path) -> list[Section]:
    """The RAOs of a ``cummins rao`` file."""
    from cummins.plots import plot_rao
    from cummins.seakeeping.frequency_domain import load_rao

    rao = load_rao(path)
    return [
        Section(
            "Motion RAOs",
            figure_html(plot_rao(rao), "Coupled motion RAOs per metre of wave amplitude")
            + rao_table_html(rao),
        ),
        *pto_rao_sections(path),
    ]


def run_sections(path: Path) -> list[Section]:
    """Statistics, time series and response spectra of a simulation file."""
    from cummins.plots import plot_response_spectra, plot_time_series

    with xr.open_dataset(path, engine="h5netcdf") as f:
        run = f.load()
    from cummins.timedomain.statistics import is_regular, motion_statistics

    regular = is_regular(run)
    rows = [[r.dof, r.amplitude, r.maximum, r.unit] for r in motion_statistics(run)]
    duration = float(run.time.values[-1] - run.time.values[0])
    notes = _note(
        f"{run.attrs.get('sea', 'simulation')}; {duration:g} s at dt "
        f"{float(run.attrs.get('dt', np.nan)):g} s; energy balance error "
        f"{float(run.attrs.get('energy_relative_residual', np.nan)):.2g}."
    )
    return [
        Section(
            "Response statistics",
            notes
            + table_html(
                [
                    "DOF",
                    "amplitude" if regular else "significant amplitude (2σ)",
                    "max |ξ|",
                    "unit",
                ],
                rows,
            ),
        ),
        Section(
            "Time series",
            figure_html(
                plot_time_series(run),
                "Wave elevation and motions (last "
                f"{min(600.0, float(run.time[-1] - run.time[0])):g} s)",
            ),
        ),
        Section(
            "Response spectra",
            figure_html(plot_response_spectra(run, {}), "Response spectra (Welch)"),
        ),
        *pto_run_sections(run),
    ]


def dp_sections(path: Path) -> list[Section]:
    """Checks, pose, forces and watch circle of a run of :mod:`cummins.timedomain.unified`
    (``cummins dp-demo``)."""
    from cummins.plots import plot_generalized_forces, plot_pose, plot_watch_circle

    with xr.open_dataset(path, engine="h5netcdf") as f:
        run = f.load()
    checks = [[k[6:].replace("_", " "), v] for k, v in run.attrs.items() if k.startswith("check_")]
    rows = []
    for k, dof in enumerate(run.dof.values):
        x = run.eta.values[:, k]
        scale, unit = (np.degrees(1.0), "deg") if k >= 3 else (1.0, "m")
        rows.append(
            [
                str(dof),
                float(scale * x.mean()),
                float(scale * 2 * x.std()),
                float(scale * np.abs(x).max()),
                unit,
            ]
        )
    forces = [v for v in run.data_vars if str(v).startswith("force_")]
    sections = [
        Section(
            "Pose statistics",
            _note(str(run.attrs.get("scenario", run.attrs.get("method", ""))))
            + table_html(["DOF", "mean", "2σ", "max |η|", "unit"], rows),
        ),
        Section("Pose", figure_html(plot_pose(run), "Pose η in the north-east-down frame")),
    ]
    if checks:
        sections.insert(1, Section("Checks", table_html(["check", "value"], checks)))
    if forces:
        extra = ["thrust"] if "thrust" in run else []
        sections.append(
            Section(
                "Loads",
                figure_html(
                    plot_generalized_forces(
                        run, [*forces, *extra], labels=[str(f)[6:] for f in forces] + extra
                    ),
                    "Generalized forces of every load (body frame, about the origin)",
                ),
            )
        )
    sections.append(Section("Watch circle", figure_html(plot_watch_circle(run), "Track")))
    return sections


def lf_sections(path: Path) -> list[Section]:
    """The coefficients of a low-frequency model file (``cummins lf-model``)."""
    with xr.open_dataset(path, engine="h5netcdf") as f:
        lf = f.load()
    rows = []
    for dof in lf.dof.values:
        pick = {"influenced_dof": dof, "radiating_dof": dof}
        rows.append(
            [
                str(dof),
                float(lf.frequency.sel(dof=dof)),
                float(lf.inertia_matrix.sel(pick) + lf.added_mass.sel(pick)),
                float(lf.damping.sel(pick)),
                float(lf.stiffness.sel(pick)),
                str(lf.provenance.sel(dof=dof).values),
            ]
        )
    sections = [
        Section(
            "Coefficients (diagonal)",
            table_html(["DOF", "taken at ω [rad/s]", "M_RB + M_A", "D", "G", "provenance"], rows),
        )
    ]
    if "speed_terms" in lf:  # lf-model --manoeuvring-speed: N(U), added to D
        from cummins.timedomain.lfmodel.speed import speed_term_entries

        n = lf.speed_terms.transpose("influenced_dof", "radiating_dof")
        entries = speed_term_entries(n.values, n.influenced_dof.values)
        speed = [[f"N[{row}, {column}]", value] for row, column, value in entries]
        title = f"Speed terms at {float(lf.attrs.get('forward_speed', np.nan)):g} m/s"
        text = _note(str(lf.attrs.get("speed_terms", ""))) + table_html(["", "N(U)"], speed)
        sections.append(Section(title, text))
    return sections


def batch_sections(results: xr.Dataset) -> list[Section]:
    """The study, operability, limiting H_s and the statistics of the cases."""
    import json

    from cummins.studies.operability import limiting_hs, operability

    study = json.loads(results.attrs.get("study", "{}"))
    crit = [str(c) for c in results.criterion.values] if "criterion" in results.dims else []
    rows = [
        ["analysis", f"{results.attrs['analysis']}: {results.attrs.get('analysis_description')}"],
        ["data", str(results.attrs.get("data_file", ""))],
        ["cases", str(results.attrs.get("n_cases"))],
        ["spectrum", str(results.attrs.get("spectrum"))],
        ["duration", f"{float(results.attrs.get('duration', np.nan)):g} s"],
        ["axes", ", ".join(f"{d} ({results.sizes[d]})" for d in results.operable.dims)],
        ["criteria", "; ".join(crit) or "none"],
    ]
    if study.get("model"):
        rows.insert(2, ["model", study["model"]])
    sections = [Section("Study", table_html(["", ""], rows))]
    if crit:
        op = operability(results)
        lim = limiting_hs(results)
        sections.append(Section("Operability", _operability_body(op) + _limiting_body(lim)))
    sections += pto_batch_sections(results)
    sections.append(Section("Statistics per case", cases_body(results)))
    return sections


def _operability_body(op: xr.DataArray) -> str:
    frame = op.to_dataframe().reset_index()
    keys = [c for c in frame.columns if c != "operability"]
    rows = [
        [*(float(r[k]) for k in keys), f"{100 * r['operability']:.1f} %"]
        for _, r in frame.iterrows()
    ]
    header = [f"{k} [deg]" if k == "heading" else k for k in keys] + ["operability"]
    fig = _plot_operability(op)
    return (
        _note(f"Share of the sea states meeting every criterion ({op.attrs['weights']} weights).")
        + table_html(header, rows)
        + figure_html(fig, "Operability per heading")
    )


def _limiting_body(lim: xr.DataArray) -> str:
    from cummins.studies.operability import beyond_grid_note, limiting_hs_text

    def cell(value, beyond):
        return limiting_hs_text(float(value), bool(beyond)) if beyond else float(value)

    if set(lim.dims) == {"heading", "tp"}:
        grid = lim.transpose("heading", "tp")
        header = ["heading [deg] \\ Tp [s]"] + [f"{t:g}" for t in grid.tp.values]
        rows = [
            [
                float(h),
                *map(cell, grid.sel(heading=h).values, grid.beyond_grid.sel(heading=h).values),
            ]
            for h in grid.heading.values
        ]
    else:
        frame = lim.to_dataframe().reset_index()
        header = [c for c in frame.columns if c != "beyond_grid"]
        rows = [
            [*(float(r[c]) for c in header[:-1]), cell(r[header[-1]], r["beyond_grid"])]
            for _, r in frame.iterrows()
        ]
    return (
        _note(
            "Limiting Hs [m]: the largest Hs meeting every criterion (responses scale with "
            "Hs), within the Hs computed: never a number scaled beyond the study."
        )
        + table_html(header, rows)
        + (_note(beyond_grid_note(lim) + ".") if bool(lim.beyond_grid.any()) else "")
        + figure_html(
            _plot_limiting_hs(lim),
            "Limiting Hs per peak period and heading (open triangles: beyond the grid, "
            "drawn at the largest Hs computed)",
        )
    )


def _plot_operability(op: xr.DataArray):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 3.2), layout="constrained")
    ax = fig.subplots()
    ax.plot(op.heading.values, 100 * op.values, "o-", color="C0")
    ax.set_xlabel("heading [deg] (180 = head seas)")
    ax.set_ylabel("operability [%]")
    ax.set_ylim(-5, 105)
    ax.grid(alpha=0.3)
    return fig


def _plot_limiting_hs(lim: xr.DataArray):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 3.6), layout="constrained")
    ax = fig.subplots()
    extra = [d for d in lim.dims if d not in ("heading", "tp")]  # the smallest over them
    reduced = lim.min(extra).assign_coords(beyond_grid=lim.beyond_grid.all(extra)) if extra else lim
    for k, h in enumerate(reduced.heading.values):
        values = reduced.sel(heading=h).values
        beyond = reduced.beyond_grid.sel(heading=h).values.astype(bool)
        color = f"C{k % 10}"
        ax.plot(
            reduced.tp.values,
            np.where(np.isfinite(values), values, np.nan),
            "-",
            color=color,
            label=f"{h:g}°",
        )
        ax.plot(reduced.tp.values[~beyond], values[~beyond], "o", color=color)
        ax.plot(reduced.tp.values[beyond], values[beyond], "^", color=color, mfc="none")
    finite = reduced.values[np.isfinite(reduced.values)]
    if finite.size:
        ax.set_ylim(0.0, float(finite.max()) * 1.1)
    ax.set_xlabel("Tp [s]")
    ax.set_ylabel("limiting Hs [m]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small", title="heading")
    return fig


# --------------------------------------------------------------------------- entry point


def report_sections(
    path: str | os.PathLike[str],
    kind: str | None = None,
    *,
    read_options: Mapping[str, object] | None = None,
) -> tuple[str, list[Section]]:
    """(kind, sections) of the report of ``path`` (kind detected when None; a kind given
    must be what the file holds). ``read_options`` (``format``, ``rho``, ``g``, ``ulen``)
    are passed to :func:`cummins.read` for a data file."""
    p = Path(path)
    if kind is None:
        kind = detect_kind(p)
    else:
        _check_kind(p, kind)
    builders: dict[str, Callable[[], list[Section]]] = {
        "data": lambda: data_sections(_read_data(p, read_options)),
        "kernel": lambda: kernel_sections(p),
        "model": lambda: model_sections(p),
        "excitation-model": lambda: excitation_model_sections(p, read_options),
        "rao": lambda: rao_sections(p),
        "run": lambda: run_sections(p),
        "dp": lambda: dp_sections(p),
        "lf": lambda: lf_sections(p),
        "batch": lambda: batch_sections(_load_batch(p)),
    }
    if kind not in builders:
        raise ReportError(f"unknown report kind {kind!r}; use one of {', '.join(KINDS)}")
    return kind, builders[kind]()


def _read_data(p: Path, options: Mapping[str, object] | None = None) -> xr.Dataset:
    from cummins.io import read

    return read(p, **{k: v for k, v in (options or {}).items() if v is not None})


def kernel_sections(path: Path) -> list[Section]:
    """The per-coupling diagnostics and K(t) of a ``cummins kernel`` output file."""
    from cummins.plots import plot_retardation

    with xr.open_dataset(path, engine="h5netcdf") as f:
        result = f.load()
    labels = [str(d) for d in result.influenced_dof.values]
    pairs = [
        (int(i), int(j))
        for i, j in zip(*np.nonzero(np.triu(result.significant.values)), strict=True)
    ]
    rows = []
    for i, j in pairs:
        row = result.isel(influenced_dof=i, radiating_dof=j)
        data = float(row.added_mass_inf_data)
        rows.append(
            [
                labels[i] if i == j else f"{labels[i]}-{labels[j]}",
                float(row.K0),
                float(row.k_end_ratio),
                float(row.tail_fraction),
                float(row.added_mass_inf_estimate),
                float(row.added_mass_inf_spread),
                data if np.isfinite(data) else "—",
                float(row.kramers_kronig_error),
            ]
        )
    notes = _note(
        f"K(t) to {float(result.attrs.get('t_max', result.time.values[-1])):.4g} s of "
        f"{result.attrs.get('source_file', 'the data')}; A∞ used: "
        f"{result.attrs.get('added_mass_inf_method', '?')}."
    )
    kernel = result.retardation_function
    diagonal = [(i, j) for i, j in pairs if i == j]
    couplings = [(i, j) for i, j in pairs if i != j]
    sections = [
        Section(
            "Diagnostics per significant coupling",
            notes
            + table_html(
                [
                    "coupling",
                    "K(0)",
                    "K(t_max)/max|K|",
                    "tail share",
                    "A∞ estimate",
                    "± spread",
                    "A∞ data",
                    "KK error",
                ],
                rows,
            ),
        )
    ]
    if diagonal:
        sections.append(
            Section(
                "K(t), diagonal",
                figure_html(plot_retardation(kernel, diagonal), "Retardation functions K_ii(t)"),
            )
        )
    if couplings:
        sections.append(
            Section(
                "K(t), couplings",
                figure_html(plot_retardation(kernel, couplings), "Retardation functions K_ij(t)"),
            )
        )
    return sections


def _load_batch(p: Path) -> xr.Dataset:
    from cummins.studies.batch import load_results

    return load_results(p)


def write_report(
    path: str | os.PathLike[str],
    output: str | os.PathLike[str],
    *,
    force: bool = False,
    kind: str | None = None,
    read_options: Mapping[str, object] | None = None,
) -> Path:
    """Write the HTML report of ``path`` (module docstring) to ``output``.

    Raises
    ------
    OutputExistsError
        ``output`` exists and ``force`` is false.
    ArgumentError
        ``output`` is a file the report reads (``path``, a run's companion files), with
        ``force`` or not.
    CumminsError
        ``path`` cannot be read as anything cummins knows.
    """
    output = Path(output)
    refuse_overwriting_inputs([output], [path])
    check_writable(output, force)
    with files_read() as used:
        kind, sections = report_sections(path, kind, read_options=read_options)
    refuse_overwriting_inputs([output], [path, *used])  # a run's companion files too
    title = f"{Path(path).name}: {KINDS[kind]}"
    page = render_html(title, f"cummins report of {Path(path).resolve()}", sections)
    output.parent.mkdir(parents=True, exist_ok=True)
    with replacing(output) as tmp:
        tmp.write_text(page, encoding="utf-8")
    return output
