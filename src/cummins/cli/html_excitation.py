"""The ``cummins report`` page of a wave excitation model (``cummins fit-excitation``).

The model (:class:`~cummins.excitation_model.ExcitationModel`): what it holds and how it
was fitted, its failures in a box, and per heading and DOF the states, the time advance
t_c and the NRMSE of the complex response over the wave band against its target
(:mod:`cummins.excitation_model.fit`). When the data it was fitted to (its
``source_file``) are at hand, the NRMSE is measured again on them
(:func:`~cummins.excitation_model.fit.model_nrmse`: equal to the recorded one unless the
data are not those), and the figure draws the data against the model; otherwise the page
says the data were not found and draws the model alone. The figure
(:func:`~cummins.excitation_model.figures.plot_excitation_model`) has a row per excited
DOF: |F(ω)|, the causal phase ∠F e^{−jωt_c}, and the excitation impulse response
K_ex(t) (Falnes (2002) ch. 5), a line for each of at most :data:`MOST` headings.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.cli.html_page import Section, _note, failures_html, figure_html, table_html
from cummins.errors import CumminsError
from cummins.files import fitted_data_file

__all__ = ["MOST", "drawn_headings", "excitation_model_sections", "fitted_data"]

#: At most this many headings are drawn on the figure (the table lists them all).
MOST = 5
#: A NRMSE measured again on the data that differs from the recorded one by more than
#: this (relative) says the data are not those the model was fitted to.
SAME = 1e-6


def excitation_model_sections(
    path: Path, read_options: Mapping[str, object] | None = None
) -> list[Section]:
    """The sections of the page of the excitation model file ``path``; ``read_options``
    (``format``, ``rho``, ``g``, ``ulen``; None: the model's recorded ``rho`` and ``g``)
    to read the data it was fitted to."""
    from cummins.excitation_model import ExcitationModel
    from cummins.excitation_model.figures import plot_excitation_model
    from cummins.excitation_model.fit import model_nrmse

    model = ExcitationModel.load(path)
    ds, missing = fitted_data(model, Path(path), read_options)
    measured = model_nrmse(ds, model) if ds is not None else None
    sections = [
        Section("Excitation model", _summary(model, missing)),
        Section("States and NRMSE per heading and DOF", _table(model, measured)),
    ]
    picks = drawn_headings(model)
    shown = ", ".join(f"{np.degrees(model.headings[h]):g}°" for h in picks)
    which = (
        f"the {len(picks)} headings drawn of {len(model.headings)} ({shown}: spread over "
        "them and the worst fit)"
        if len(picks) < len(model.headings)
        else f"heading{'s' if len(picks) > 1 else ''} {shown}"
    )
    figure = plot_excitation_model(model, ds, picks)
    if ds is None:
        title = "The model's response (data not found)"
        caption = f"|F|, causal phase and K_ex(t) of the model, {which}"
        body = figure_html(figure, caption)
    else:
        name = Path(str(model.attrs["source_file"])).name
        title = f"Fits against the data ({name})"
        caption = (
            f"|F| and causal phase ∠F e^(-jωt_c): data (markers) against the model; K_ex(t) "
            f"of the data and of the model (dashed), {which}"
        )
        body = figure_html(figure, caption)
    sections.append(Section(title, body))
    return sections


def fitted_data(
    model, path: Path, read_options: Mapping[str, object] | None = None
) -> tuple[xr.Dataset | None, str]:
    """(the data ``model`` was fitted to at zero speed, "") or (None, why they are not
    at hand). The recorded ``source_file``, or the file of that name beside the model
    file ``path`` when it was recorded as a relative path that does not resolve; read
    with the model's ``rho`` and ``g`` unless ``read_options`` give others."""
    from cummins.io import read

    found, source = fitted_data_file(model.attrs, path)
    if source is None:
        return None, "The model does not record the data it was fitted to."
    if found is None:
        return None, (
            f"The data the model was fitted to ({source}) were not found: the NRMSE shown "
            "are those the model file records, and the figure draws the model alone."
        )
    options = {key: model.attrs.get(key) for key in ("rho", "g")}
    options.update({k: v for k, v in (read_options or {}).items() if v is not None})
    try:
        ds = read(found, **{k: v for k, v in options.items() if v is not None})
    except CumminsError as exc:
        return None, f"The data the model was fitted to ({source}) could not be read: {exc}"
    if "forward_speed" in ds.dims:
        zero = np.flatnonzero(np.abs(ds.forward_speed.values) < 1e-9)
        if zero.size == 0:
            return None, f"The data {source} hold no results at zero forward speed."
        ds = ds.isel(forward_speed=int(zero[0]))
    return ds, ""


def drawn_headings(model, most: int = MOST) -> list[int]:
    """Indices of the headings the figure draws: at most ``most`` spread over the model's
    (:func:`cummins.plots.heading_picks`), the one of the worst fit (largest NRMSE)
    among them."""
    from cummins.plots import heading_picks

    picks = heading_picks(np.degrees(model.headings), None, most)
    errors = np.array([[m.metrics.get("nrmse", 0.0) for m in model.models]]).reshape(
        model.orders.shape
    )
    worst = int(np.argmax(errors.max(axis=1))) if errors.size else 0
    if worst not in picks:
        nearest = int(np.argmin(np.abs(np.array(picks) - worst)))
        picks[nearest] = worst
    return sorted(picks)


def _summary(model, missing: str) -> str:
    """What the model holds and how it was fitted, its failures in a box."""
    from cummins.cli.failed_model import model_failures

    attrs = model.attrs
    headings = ", ".join(f"{np.degrees(b):g}" for b in model.headings)
    rows = [
        ["fitted to", str(attrs.get("source_file") or "not recorded")],
        ["DOFs", ", ".join(model.dofs)],
        ["headings", f"{len(model.headings)}: {headings} deg (direction of wave travel)"],
        ["states", f"{model.total_order} over every heading and DOF"],
        ["every model stable", model.is_stable()],
        [
            "NRMSE target",
            f"{float(attrs.get('nrmse_target', np.nan)):g} over the wave band (|F| above "
            f"{float(attrs.get('band', np.nan)):g} of its peak)",
        ],
        ["method", str(attrs.get("method", "not recorded"))],
        ["t_c", str(attrs.get("delay_rule", "not recorded"))],
    ]
    rows += [["data", str(note)] for note in attrs.get("data_notes", [])]
    failures = model_failures(attrs)
    box = failures_html(
        failures,
        f"This model missed its fit targets ({len(failures)}; cummins fit-excitation exits "
        "with status 3): the forces of these DOFs are less accurate than asked for.",
    )
    intro = _note(
        "The wave force as the output of a causal state space driven by the wave elevation "
        "at the origin, advanced by t_c: x' = A x + B η(t + t_c), F = C x."
    )
    return box + intro + table_html(["", ""], rows) + (_note(missing) if missing else "")


def _table(model, measured: np.ndarray | None) -> str:
    """A row per (heading, DOF) with states: t_c, states, the NRMSE recorded (and
    measured again on the data), met, the band, stable, the fit's note."""
    target = float(model.attrs.get("nrmse_target", np.nan))
    header = ["heading [deg]", "t_c [s]", "DOF", "states", "NRMSE"]
    header += [] if measured is None else ["NRMSE on the data now"]
    header += ["target met", "band [rad/s]", "stable", "note"]
    rows, classes, idle, differ = [], [], [], []
    for h, beta in enumerate(model.headings):
        for d, label in enumerate(model.dofs):
            part = model.model(h, d)
            if not part.order:
                idle.append(f"{label} at {np.degrees(beta):g}°")
                continue
            m = part.metrics
            recorded = float(m.get("nrmse", np.nan))
            met = bool(m.get("target_met", recorded <= target))
            row = [float(np.degrees(beta)), float(model.delays[h]), label, part.order, recorded]
            cls = ["", "", "", "", "good" if met else "bad"]
            if measured is not None:
                now = float(measured[h, d])
                same = abs(now - recorded) <= SAME * max(recorded, 1e-12)
                if not same:
                    differ.append(f"{label} at {np.degrees(beta):g}°")
                row.append(now)
                cls.append("" if same else "warning")
            band = f"{m.get('band_min', np.nan):.3g}–{m.get('band_max', np.nan):.3g}"
            row += [met, band, bool(part.is_stable()), part.note]
            cls += ["good" if met else "bad", "", "", ""]
            rows.append(row)
            classes.append(cls)
    notes = f"NRMSE of the complex response over the wave band; target {target:g}."
    if idle:
        notes += " Not excited (no states): " + ", ".join(idle) + "."
    if differ:
        notes += (
            " The NRMSE measured on the data now differs from the recorded one for "
            + ", ".join(differ)
            + ": the data are not those the model was fitted to (changed since, or read "
            "with other constants: --rho, --g, --ulen)."
        )
    return _note(notes) + table_html(header, rows, classes=classes)
