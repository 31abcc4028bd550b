"""The power take-offs in ``cummins report`` (:mod:`cummins.cli.html_report`).

What the result files hold of each PTO (variables ``pto_*`` on a ``pto`` dimension), as a
WEC-Sim user reads it:

``rao`` (``cummins rao`` with ``--pto``)
    the mean absorbed power per unit wave amplitude squared ``pto_power`` = ½ c ω² |Δ̂|²
    (the time-average power of a mechanical resistance, Falnes (2002)) against the wave
    period, with the PTO force and relative-motion RAOs, and the largest power per heading;
``run`` (``cummins simulate`` with PTOs)
    the mean absorbed power (over the last whole wave periods of a regular-wave run, up
    to 10, as ``cummins simulate`` prints it; over the whole run otherwise), the energy
    absorbed, the force and relative motion, their time series and the running mean power;
``batch`` (a study with a ``system:``)
    the power matrix ``pto_mean_power`` over H_s × T_p as a table and a heat map, and the
    mean over the scatter diagram when the study has one; with a sweep of a PTO's damping
    (:mod:`cummins.studies.pto_sweep`) the best damping per sea state and its power, the
    mean power against the damping per T_p, and over the scatter diagram the power per
    damping and the best single damping for the site.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.cli.html_page import Section, _note, figure_html, table_html
from cummins.display import energy_unit, power_text, power_unit, rotation_scale
from cummins.hydrodb import is_rotation

#: Power matrices drawn at most (one per PTO and heading …); the tables show them all.
MOST_MATRICES = 6


def pto_descriptions(coordinate: xr.DataArray) -> dict[str, str]:
    """{PTO name: what it acts on} from the ``description`` of a ``pto`` coordinate
    (``name: text`` per line, as :func:`cummins.mechanics.pto_time_series` writes it)."""
    out = {}
    for line in str(coordinate.attrs.get("description", "")).splitlines():
        name, _, text = line.partition(": ")
        out[name.strip()] = text.strip()
    return out


def is_rotational(description: str) -> bool:
    """Whether a PTO of this description acts on a rotation (its Δ in rad, force N·m)."""
    first = description.split(" ", 1)[0] if description else ""
    return description.startswith("rotation about") or (bool(first) and is_rotation(first))


def pto_units(coordinate: xr.DataArray) -> dict[str, dict[str, str]]:
    """Units of Δ, Δ̇ and the force of each PTO."""
    text = pto_descriptions(coordinate)
    out = {}
    for name in (str(p) for p in coordinate.values):
        if is_rotational(text.get(name, "")):
            out[name] = {"displacement": "rad", "velocity": "rad/s", "force": "N m"}
        else:
            out[name] = {"displacement": "m", "velocity": "m/s", "force": "N"}
    return out


def _description_note(coordinate: xr.DataArray) -> str:
    text = pto_descriptions(coordinate)
    return "".join(_note(f"{name}: {what}") for name, what in text.items())


# --------------------------------------------------------------------------- RAO file

#: A PTO's power RAO at a heading below this fraction of the file's largest is the
#: rounding of a motion the waves do not excite (a hinge about y in beam seas): none.
NO_POWER = 1e-9


def pto_rao_sections(path: Path) -> list[Section]:
    """The PTOs of a ``cummins rao`` file (none without ``pto_*`` variables)."""
    from cummins.seakeeping.frequency_domain import load_pto_rao

    with xr.open_dataset(path, engine="h5netcdf") as f:
        if not any(str(n).startswith("pto_") for n in f.data_vars):
            return []
    pto = load_pto_rao(path)
    units = pto_units(pto.pto)
    w = pto.omega.values
    largest = float(np.nanmax(np.abs(pto.pto_power.values), initial=0))
    factor, unit = power_unit(largest)
    rows = []
    for name in (str(p) for p in pto.pto.values):
        one = pto.sel(pto=name)
        power = one.pto_power.transpose("omega", "wave_direction").values
        for j, beta in enumerate(pto.wave_direction.values):
            i = int(np.nanargmax(power[:, j]))
            if not power[i, j] > NO_POWER * largest:  # rounding: the waves do not move it
                rows.append([name, float(np.degrees(beta)), 0.0, "—", "—", "—", "—"])
                continue
            force = one.pto_force.transpose("omega", "wave_direction").values[i, j]
            delta = one.pto_displacement.transpose("omega", "wave_direction").values[i, j]
            u = units[name]
            rows.append(
                [
                    name,
                    float(np.degrees(beta)),
                    float(power[i, j] / factor),
                    float(w[i]),
                    float(2 * np.pi / w[i]),
                    f"{abs(force):.4g} {u['force']}/m",
                    f"{abs(delta):.4g} {u['displacement']}/m",
                ]
            )
    body = (
        _description_note(pto.pto)
        + _note(
            "Mean absorbed power in a regular wave of unit amplitude, ½ c ω² |Δ̂|² "
            "(pto_power; times a² in a wave of amplitude a), at its largest per heading, "
            "with the PTO force and relative motion there."
        )
        + table_html(
            [
                "PTO",
                "heading [deg]",
                f"max power [{unit}/m²]",
                "ω [rad/s]",
                "period [s]",
                "|force| RAO",
                "|Δ| RAO",
            ],
            rows,
        )
        + figure_html(
            plot_pto_rao(pto, units),
            "Power RAO (mean absorbed power per unit wave amplitude squared), PTO force and "
            "relative-motion RAOs against the wave period",
        )
    )
    return [Section("Power take-offs", body)]


def plot_pto_rao(pto: xr.Dataset, units: dict[str, dict[str, str]]):
    """Per PTO (a column): power, |force| and |Δ| per unit wave amplitude against the
    period, one line per heading (at most five)."""
    from matplotlib.figure import Figure

    from cummins.plots import heading_picks

    names = [str(p) for p in pto.pto.values]
    beta = np.degrees(pto.wave_direction.values)
    picks = heading_picks(beta)
    w = pto.omega.values
    keep = w > 0
    period = 2 * np.pi / w[keep]
    fig = Figure(figsize=(5.5 * len(names) + 1.5, 7), layout="constrained")
    axes = np.asarray(fig.subplots(3, len(names), sharex=True, squeeze=False))
    for c, name in enumerate(names):
        one = pto.sel(pto=name)
        u = units[name]
        scale, shown = rotation_scale(u["displacement"])
        factor, unit = power_unit(float(np.nanmax(np.abs(one.pto_power.values), initial=0)))
        series = [
            (one.pto_power / factor, f"power [{unit}/m²]", 1.0),
            (np.abs(one.pto_force), f"|force| [{u['force']}/m]", 1.0),
            (np.abs(one.pto_displacement), f"|Δ| [{shown}/m]", scale),
        ]
        for r, (values, label, factor) in enumerate(series):
            ax = axes[r, c]
            grid = values.transpose("omega", "wave_direction").values[keep]
            for k, j in enumerate(picks):
                ax.plot(period, factor * grid[:, j], color=f"C{k}", label=f"{beta[j]:g}°")
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
        axes[0, c].set_title(name)
        axes[-1, c].set_xlabel("wave period [s]")
        axes[-1, c].set_xlim(period.min(), _period_span(period, one.pto_power.values[keep]))
    if len(picks) > 1:
        axes[0, 0].legend(fontsize="small", title="heading")
    return fig


def _period_span(period: np.ndarray, power: np.ndarray) -> float:
    """The longest period drawn: 1.5 times the longest at which the power reaches 1 % of
    its peak (the long-period tail, where nothing is absorbed, left out)."""
    power = np.nan_to_num(np.asarray(power, dtype=float).reshape(period.size, -1)).max(axis=1)
    if not power.max() > 0:
        return float(period.max())
    return float(min(period.max(), 1.5 * period[power >= 0.01 * power.max()].max()))


# --------------------------------------------------------------------------- run file


def pto_run_sections(run: xr.Dataset) -> list[Section]:
    """The PTOs of a ``cummins simulate`` run (none without ``pto_power``)."""
    if "pto_power" not in run:
        return []
    from cummins.timedomain.harmonics import harmonic_amplitude, last_periods

    t = run.time.values
    regular = str(run.attrs.get("spectrum", "")) == "regular"
    period = float(run.attrs.get("tp", np.nan))
    omega = 2 * np.pi / period if regular and period > 0 else None
    window = last_periods(t, omega, 10) if omega else np.ones(t.size, bool)
    count = int(min(10, np.floor((t[-1] - t[0]) / period + 1e-9))) if omega else 0
    units = pto_units(run.pto)
    reference = run.get("pto_mean_power_frequency_domain")
    record = run.get("pto_mean_power_frequency_domain_record")  # irregular runs
    names = [str(p) for p in run.pto.values]
    powers = run.pto_power.values
    means = {name: float(powers[window, k].mean()) for k, name in enumerate(names)}
    energies = [float(np.trapezoid(powers[:, k], t)) for k in range(len(names))]
    shown = [*means.values(), *([] if reference is None else reference.values)]
    shown += [] if record is None else list(record.values)
    mean_factor, mean_unit = power_unit(float(np.nanmax(np.abs(shown), initial=0)))
    peak_factor, peak_unit = power_unit(float(np.nanmax(np.abs(powers), initial=0)))
    damper = run.attrs.get("energy_pto")
    energy_factor, energy_unit_text = energy_unit(
        float(np.nanmax(np.abs([*energies, float(damper or 0.0)]), initial=0))
    )
    rows = []
    for k, name in enumerate(names):
        force = run.pto_force.values[:, k]
        delta = run.pto_displacement.values[:, k]
        u = units[name]
        row = [name, means[name] / mean_factor]
        if reference is not None:
            row += [float(reference.values[k]) / mean_factor]
        if record is not None:
            row += [float(record.values[k]) / mean_factor]
        row += [energies[k] / energy_factor, float(powers[:, k].max() / peak_factor)]
        if omega:
            periods = max(count, 1)
            row += [
                f"{abs(harmonic_amplitude(t, delta, omega, periods)):.4g} {u['displacement']}",
                f"{abs(harmonic_amplitude(t, force, omega, periods)):.4g} {u['force']}",
            ]
        else:
            row += [
                f"{2 * delta.std():.4g} {u['displacement']}",
                f"{2 * force.std():.4g} {u['force']}",
            ]
        row += [f"{np.abs(force).max():.4g} {u['force']}"]
        rows.append(row)
    if omega and count:
        where = (
            f"over the last {count} wave periods of {period:g} s (t {t[window][0]:g} to "
            f"{t[-1]:g} s{': the whole run, the start-up included' if window[1] else ''}), "
            "as cummins simulate prints it; amplitudes fitted over them"
        )
    else:
        start = (
            "started on the stationary solution"
            if run.attrs.get("initial") == "steady"
            else "the start-up included"
        )
        where = f"over the whole run (t {t[0]:g} to {t[-1]:g} s, {start})"
    notes = _note(
        f"Mean absorbed power {where}. Energy: ∫ pto_power dt over the run"
        + (
            " (the PTO dampers' work in the energy balance: "
            f"{float(damper) / energy_factor:.4g} {energy_unit_text})."
            if damper is not None
            else "."
        )
    )
    header = ["PTO", f"mean power [{mean_unit}]"]
    if reference is not None:
        left_out = str(reference.attrs.get("left_out", "none"))
        linear = "" if left_out == "none" else "linear "
        header += [f"{linear}frequency domain [{mean_unit}]"]
        notes += _note(
            "Frequency domain: the mean power of the linear frequency-domain solution of the "
            "same equations for the run's wave components, Σ ½ c ω² |Δ̂|² a², as cummins "
            "simulate prints it" + ("." if left_out == "none" else f" (it leaves out {left_out}).")
        )
    if record is not None:
        header += [f"frequency domain, this record [{mean_unit}]"]
        notes += _note(
            "Frequency domain, this record: the mean power of the same solution over the "
            "run's own waves, Re Σ Δ̂ a e^{i(ωt + φ)}, which the run follows to its radiation "
            "model's error; components of different frequencies do not average out over a "
            "finite record, and the frequency domain's mean differs from it by that alone."
        )
    header += [f"energy [{energy_unit_text}]", f"max power [{peak_unit}]"]
    header += ["amplitude Δ", "force amplitude"] if omega else ["2σ of Δ", "2σ of the force"]
    header += ["max |force|"]
    body = _description_note(run.pto) + notes + table_html(header, rows)
    for name in means:
        body += figure_html(
            plot_pto_time_series(run, name, window, units[name]),
            f"{name}: force, relative velocity and absorbed power (last "
            f"{min(600.0, float(t[-1] - t[0])):g} s), and the running mean power over the run",
        )
    return [Section("Power take-offs", body)]


def plot_pto_time_series(
    run: xr.Dataset, name: str, window: np.ndarray, units: dict[str, str], span: float = 600.0
):
    """Force, relative velocity and power of one PTO over the last ``span`` seconds, and
    the running mean power (1/t ∫ P dt) over the run with the mean over ``window``."""
    from matplotlib.figure import Figure

    t = run.time.values
    keep = t >= t[-1] - span
    one = run.sel(pto=name)
    scale, velocity_unit = rotation_scale(units["velocity"])
    power = one.pto_power.values
    factor, unit = power_unit(float(np.nanmax(np.abs(power), initial=0)))
    fig = Figure(figsize=(11, 7), layout="constrained")
    axes = fig.subplots(4, 1)
    series = [
        (one.pto_force.values, f"force [{units['force']}]", 1.0),
        (one.pto_velocity.values, f"velocity [{velocity_unit}]", scale),
        (power / factor, f"power [{unit}]", 1.0),
    ]
    for k, (values, label, scaling) in enumerate(series):
        axes[k].plot(t[keep], scaling * values[keep], color=f"C{k}", lw=0.8)
        axes[k].set_ylabel(label)
        axes[k].sharex(axes[0])
    elapsed = t - t[0]
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))])
    running = np.divide(work, elapsed, out=np.full(t.size, np.nan), where=elapsed > 0)
    mean = float(power[window].mean())
    factor, unit = power_unit(float(np.nanmax(np.abs([*running, mean]), initial=0)))
    axes[3].plot(t, running / factor, color="C3", label="running mean (1/t)∫P dt")
    axes[3].axhline(mean / factor, color="k", ls="--", lw=0.8, label=f"mean {power_text(mean)}")
    axes[3].set_ylabel(f"mean power [{unit}]")
    axes[3].legend(fontsize="small", loc="lower right")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[2].set_xlabel("t [s]")
    axes[3].set_xlabel("t [s]")
    fig.suptitle(f"{name}: {run.attrs.get('sea', 'simulation')}")
    return fig


# --------------------------------------------------------------------------- batch results


def pto_batch_sections(results: xr.Dataset) -> list[Section]:
    """The power matrix of a batch study (none without ``pto_mean_power``)."""
    if "pto_mean_power" not in results:
        return []
    factor, unit = power_unit(float(np.nanmax(np.abs(results.pto_mean_power.values), initial=0)))
    power = (results.pto_mean_power / factor).assign_attrs(units=unit)
    how = (
        "∫ 2 P(ω) S(ω) dω of the power RAO P (frequency domain)"
        if results.attrs.get("analysis") == "rao"
        else "the mean of pto_power over each run (one realisation per case)"
    )
    body = _description_note(results.pto) + _note(f"Mean absorbed power [{unit}]: {how}.")
    if {"hs", "tp"} <= set(power.dims):
        body += _matrices(power, results.get("probability"))
    else:
        body += _case_table(power)
    return [Section("Power matrix", body), *pto_sweep_sections(results)]


def _others(power: xr.DataArray) -> list[dict[str, object]]:
    """Every combination of the coordinates besides H_s, T_p (and the PTO)."""
    dims = [d for d in power.dims if d not in ("hs", "tp", "pto")]
    if not dims:
        return [{}]
    combinations = itertools.product(*(power[d].values for d in dims))
    return [dict(zip(dims, values, strict=True)) for values in combinations]


def _label(pick: dict[str, object]) -> str:
    names = {"heading": ("heading", "°"), "gamma": ("γ", ""), "seed": ("seed", "")}
    parts = []
    for key, value in pick.items():
        name, unit = names.get(key, (key, ""))
        parts.append(f"{name} {float(value):g}{unit}")
    return ", ".join(parts)


def _matrices(power: xr.DataArray, probability: xr.DataArray | None) -> str:
    out = []
    drawn = 0
    scatter = probability is not None and set(probability.dims) == {"hs", "tp"}
    for name in (str(p) for p in power.pto.values):
        for pick in _others(power):
            grid = power.sel(pto=name, **pick).transpose("hs", "tp")
            title = f"{name}" + (f", {_label(pick)}" if pick else "")
            header = ["Hs [m] \\ Tp [s]"] + [f"{t:g}" for t in grid.tp.values]
            rows = [[float(h), *(float(v) for v in grid.sel(hs=h).values)] for h in grid.hs.values]
            text = f"<h3>{title}</h3>" if len(power.pto) > 1 or pick else ""
            if scatter:
                weights = probability.transpose("hs", "tp").values
                mean = float(np.nansum(weights * grid.values) / np.sum(weights))
                text += _note(f"Mean over the scatter diagram: {mean:.4g} {power.attrs['units']}.")
            text += table_html(header, rows)
            if drawn < MOST_MATRICES:
                figure = plot_power_matrix(grid, title, power.attrs["units"])
                text += figure_html(figure, f"Power matrix, {title}")
                drawn += 1
            out.append(text)
    total = len(power.pto) * len(_others(power))
    if total > MOST_MATRICES:
        out.append(_note(f"The first {MOST_MATRICES} of the {total} matrices drawn."))
    return "".join(out)


def _case_table(power: xr.DataArray) -> str:
    frame = power.to_dataframe(name="power").reset_index()
    keys = [c for c in frame.columns if c not in ("power", "pto", "case", "case_id")]
    rows = [
        [str(r["pto"]), *(float(r[k]) for k in keys), float(r["power"])]
        for _, r in frame.iterrows()
    ]
    return table_html(["PTO", *keys, f"mean power [{power.attrs['units']}]"], rows)


def plot_power_matrix(grid: xr.DataArray, title: str, unit: str = "kW"):
    """A heat map of the mean power [``unit``] over H_s (rows) and T_p (columns), each
    cell written in."""
    from matplotlib.figure import Figure

    values = grid.values
    hs, tp = grid.hs.values, grid.tp.values
    fig = Figure(figsize=(1.2 * tp.size + 3, 0.6 * hs.size + 2.2), layout="constrained")
    ax = fig.subplots()
    image = ax.imshow(values, origin="lower", aspect="auto", cmap="viridis")
    ax.set_xticks(range(tp.size), [f"{t:g}" for t in tp])
    ax.set_yticks(range(hs.size), [f"{h:g}" for h in hs])
    top = np.nanmax(values) if np.isfinite(values).any() else 1.0
    for i in range(hs.size):
        for j in range(tp.size):
            v = values[i, j]
            ax.text(
                j,
                i,
                "–" if not np.isfinite(v) else f"{v:.4g}",
                ha="center",
                va="center",
                fontsize="small",
                color="k" if np.isfinite(v) and v > 0.6 * top else "w",
            )
    ax.set_xlabel("Tp [s]")
    ax.set_ylabel("Hs [m]")
    ax.set_title(title)
    fig.colorbar(image, ax=ax, label=f"mean power [{unit}]")
    return fig


# --------------------------------------------------------------------------- PTO sweep


def pto_sweep_sections(results: xr.Dataset) -> list[Section]:
    """The best damping of a PTO sweep (``pto_damping_best`` …, none without a sweep):
    per heading a table of the best damping and its mean power per H_s and T_p, the mean
    power against the damping per T_p at the largest H_s, and with a scatter diagram the
    mean power over it per damping and the best single damping for the site."""
    if "pto_damping_best_note" in results.attrs:  # a list of cases: said, not computed
        return [Section("PTO damping sweep", _note(results.attrs["pto_damping_best_note"]))]
    if "pto_damping_best" not in results:
        return []
    units = results.pto_damping.attrs.get("units", "")
    body = _note(
        f"The damping [{units}] of the study's list with the largest mean power absorbed by "
        "the PTOs, per sea state; * where it is the smallest or largest of the list (the "
        "optimum may lie beyond it)."
    )
    best = results.pto_damping_best
    if not {"hs", "tp"} <= set(best.dims):
        frame = best.to_dataframe().reset_index()
        keys = [c for c in frame.columns if c != "pto_damping_best"]
        rows = [
            [*(float(r[k]) for k in keys), float(r["pto_damping_best"])]
            for _, r in frame.iterrows()
        ]
        return [Section("PTO damping sweep", body + table_html([*keys, f"best [{units}]"], rows))]
    total = results.pto_mean_power.sum("pto", min_count=1)
    for pick in _others(best):
        one = results[["pto_damping_best", "pto_mean_power_best", "pto_damping_best_at_edge"]]
        one = one.sel(**pick).transpose("hs", "tp")
        title = _label(pick)
        header = ["Hs [m] \\ Tp [s]"] + [f"{t:g}" for t in one.tp.values]
        rows = []
        for hs in one.hs.values:
            cell = one.sel(hs=hs)
            rows.append(
                [
                    float(hs),
                    *(
                        f"{c:.3g}{'*' if e else ''} ({power_text(float(p), digits=3)})"
                        for c, p, e in zip(
                            cell.pto_damping_best.values,
                            cell.pto_mean_power_best.values,
                            cell.pto_damping_best_at_edge.values,
                            strict=True,
                        )
                    ),
                ]
            )
        body += (f"<h3>{title}</h3>" if title else "") + table_html(header, rows)
        curves = total.sel(**{k: v for k, v in pick.items() if k in total.dims})
        if "seed" in curves.dims:
            curves = curves.mean("seed")
        curves = curves.sel(hs=curves.hs.max()).transpose("tp", "pto_damping")
        body += figure_html(
            plot_power_against_damping(curves, units, title),
            "Mean power against the PTO damping" + (f", {title}" if title else ""),
        )
    if "pto_damping_site_best" in results:
        site = results.pto_mean_power_site
        for pick in _others(results.pto_damping_site_best):
            chosen = float(results.pto_damping_site_best.sel(**pick))
            edge = bool(results.pto_damping_site_best_at_edge.sel(**pick))
            listed = "; ".join(
                f"{c:.3g}: {power_text(float(p))}"
                for c, p in zip(results.pto_damping.values, site.sel(**pick).values, strict=True)
            )
            power = power_text(float(results.pto_mean_power_site_best.sel(**pick)))
            label = f" ({_label(pick)})" if pick else ""
            body += _note(
                f"Over the scatter diagram{label}, mean power per damping [{units}]: {listed}. "
                f"Best single damping for the site: {chosen:.3g}{'*' if edge else ''} "
                f"{units}, {power}."
            )
    return [Section("PTO damping sweep", body)]


def plot_power_against_damping(curves: xr.DataArray, units: str, title: str):
    """The mean power absorbed against the PTO damping (log axis), one curve per T_p
    (``curves``: dims tp, pto_damping, W), the best of each curve marked."""
    from matplotlib.figure import Figure

    c = curves.pto_damping.values
    order = np.argsort(c)
    factor, unit = power_unit(float(np.nanmax(np.abs(curves.values))))
    fig = Figure(figsize=(6.4, 4.0), layout="constrained")
    ax = fig.subplots()
    for tp in curves.tp.values:
        p = curves.sel(tp=tp).values[order] / factor
        (line,) = ax.plot(c[order], p, marker="o", ms=3, label=f"Tp {tp:g} s")
        if np.isfinite(p).any():
            k = int(np.nanargmax(p))
            ax.plot(c[order][k], p[k], marker="*", ms=12, color=line.get_color())
    ax.set_xscale("log")
    ax.set_xlabel(f"PTO damping [{units}]")
    ax.set_ylabel(f"mean power [{unit}]")
    hs = float(curves.hs) if "hs" in curves.coords else None
    ax.set_title(", ".join(x for x in (title, "" if hs is None else f"Hs {hs:g} m") if x))
    ax.legend(fontsize="small")
    ax.grid(True, which="both", alpha=0.3)
    return fig
