"""Pipeline stages composed from the library functions, shared by the CLI and the demo.

Each stage takes a ``HydroDB`` and options, applies the documented steps in order and
returns plain results; printing and file names are left to the caller.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np
import xarray as xr

from cummins.errors import check_writable
from cummins.hydrodb import dof_matrix


def kernel_stage(
    ds: xr.Dataset,
    *,
    t_max: float | None = None,
    dt: float | None = None,
    tail: str = "auto",
    interpolation: str = "linear",
    omega_max: float | None = None,
    remove_suspect: bool = True,
    above_first: bool = False,
    truncate: str | None = None,
    say: Callable[[str], object] = lambda message: None,
) -> tuple[xr.Dataset, xr.Dataset]:
    """Repair options, K(t) and diagnostics: what ``cummins kernel`` and the demo run.

    Steps: :func:`~cummins.repair.limit_frequency_range` (``omega_max``), the suspect
    frequencies left out as the fit leaves them out (``remove_suspect``, the default:
    :func:`leave_out_suspects`; with ``above_first``
    :func:`~cummins.repair.remove_suspect_frequencies` and everything above the first;
    without ``remove_suspect`` they stay and a note says so), each reported through
    ``say``, a time grid of step ``dt`` to ``t_max`` (defaults from
    :func:`~cummins.radiation.retardation.default_time_grid`),
    :func:`~cummins.radiation.retardation.retardation_dataset` and, with ``truncate``,
    :func:`~cummins.radiation.retardation.truncate_retardation` at t_max.

    Returns
    -------
    (result, ds)
        The :func:`cummins.radiation.retardation.retardation_dataset` and the (repaired) data.
    """
    from cummins.radiation.retardation import (
        default_time_grid,
        retardation_dataset,
        truncate_retardation,
    )
    from cummins.repair import limit_frequency_range, remove_suspect_frequencies
    from cummins.validation import check_memory, positive, time_steps

    if omega_max is not None:
        ds = limit_frequency_range(ds, omega_max=omega_max)
    if remove_suspect and above_first:
        ds, suspects = remove_suspect_frequencies(ds, above_first=True)
        for s in suspects:
            say(f"  suspect {s.omega:.4g} rad/s: {s.quantity}, {s.reason}")
    else:
        ds = leave_out_suspects(ds, say=say, remove=remove_suspect)
    if t_max is not None:
        positive(t_max, "t_max", "s")
    if dt is not None:
        positive(dt, "dt", "s")
    end = t_max if t_max is not None else float(default_time_grid(ds)[-1])
    step = dt if dt is not None else end / 1000
    n_t = time_steps(end, step)
    n = ds.sizes["influenced_dof"]
    check_memory(
        n_t * (ds.sizes["omega"] * 16 + n * n * 32),
        f"K(t) at {n_t:.4g} times for {n} x {n} couplings",
        hint="Shorten --t-max or lengthen --dt",
    )
    t = np.arange(0.0, end + 0.5 * step, step)
    result = retardation_dataset(ds, t, tail=tail, interpolation=interpolation)
    if truncate:
        k = truncate_retardation(result.retardation_function, float(t[-1]), method=truncate)
        result["retardation_function"] = k
        result.attrs["truncation"] = k.attrs["truncation"]
    return result, ds


def leave_out_suspects(
    ds: xr.Dataset, *, say: Callable[[str], object] = lambda message: None, remove: bool = True
) -> xr.Dataset:
    """The data without the suspect frequencies the fit leaves out of its couplings.

    Each DOF's own curves are judged (:func:`cummins.repair.suspects_by_dof`); a
    frequency suspect in one of them (irregular frequency, spike, negative damping) is
    removed from the whole grid (B and A are then linear between its neighbours), except
    the points of a sharp resonance the motions depend on (a piston or gap resonance is
    physics, not an error: kept, and said). When fewer than
    :data:`~cummins.radiation.fit.data.MIN_KEPT_FREQUENCIES` would be left, all stay.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed.
    say
        Receives one line per suspect frequency and a summary.
    remove
        False: keep them all and only say which they are and the option that removes them.
    """
    from cummins.radiation.fit.data import MIN_KEPT_FREQUENCIES
    from cummins.repair import remove_frequencies, suspects_by_dof

    own = suspects_by_dof(ds)
    worst: dict[float, object] = {}
    dofs: dict[float, list[str]] = {}
    for label, found in own.items():
        for s in found.suspects:
            if s.omega in found.kept:
                continue
            dofs.setdefault(s.omega, []).append(label)
            if s.omega not in worst or s.score > worst[s.omega].score:
                worst[s.omega] = s
        for resonance in found.resonances:
            if resonance.kept:
                say(f"  kept: {resonance.description(label)}")
    if not worst:
        return ds
    omega = sorted(worst)
    where = f"{omega[0]:.4g}–{omega[-1]:.4g} rad/s"
    touched = ", ".join(
        str(d)
        for d in ds.influenced_dof.values
        if any(str(d) in labels for labels in dofs.values())
    )
    if not remove:
        say(
            f"note: K(t) keeps {len(omega)} suspect frequencies ({where}; {touched}: "
            "irregular frequencies, spikes or negative damping) that the fit leaves out; "
            "they ring in K(t) and lengthen it (--remove-suspect, the default, leaves "
            "them out; cummins check lists them)"
        )
        return ds
    if ds.sizes["omega"] - len(omega) < MIN_KEPT_FREQUENCIES:
        say(
            f"note: {len(omega)} of {ds.sizes['omega']} frequencies look suspect; all kept, "
            "too few would be left (check the data: cummins check)"
        )
        return ds
    for w in omega:
        s = worst[w]
        say(f"  suspect {w:.4g} rad/s: {s.quantity}, {s.reason} ({', '.join(dofs[w])})")
    say(
        f"left out {len(omega)} suspect frequencies ({where}) of {touched}, as the fit "
        "does (--keep-suspect keeps them)"
    )
    return remove_frequencies(
        ds, omega, reason="suspect in a DOF's own curves (irregular frequencies, spikes)"
    )


def write_kernel_plots(
    result: xr.Dataset, ds: xr.Dataset, folder: Path, *, force: bool = False
) -> list[Path]:
    """K(t) (diagonal, couplings), A and B rebuilt from K, and A∞(ω), as PNG files."""
    from cummins.plots import (
        plot_added_mass_inf,
        plot_reconstruction,
        plot_retardation,
        save_figure,
    )
    from cummins.radiation.retardation import reconstruct_added_mass_damping, significant_couplings

    omega = np.linspace(ds.omega.values[0], ds.omega.values[-1], 400)
    rebuilt = reconstruct_added_mass_damping(
        result.retardation_function, result.added_mass_inf.values, omega
    )
    off_diagonal = [c for c in significant_couplings(ds) if c[0] != c[1]]
    figures = [
        ("retardation.png", plot_retardation(result.retardation_function)),
        ("reconstruction.png", plot_reconstruction(ds, rebuilt)),
        (
            "added_mass_inf.png",
            plot_added_mass_inf(
                result.added_mass_inf_per_frequency, result.added_mass_inf_estimate, ds
            ),
        ),
    ]
    if off_diagonal:
        figures.append(
            (
                "retardation_couplings.png",
                plot_retardation(result.retardation_function, off_diagonal),
            )
        )
    return [save_figure(fig, folder / name, force=force) for name, fig in figures]


def write_fit_plots(
    model,
    ds: xr.Dataset,
    folder: Path,
    *,
    force: bool = False,
    say: Callable[[str], object] = lambda message: None,
) -> list[Path]:
    """One PNG per DOF with a fitted coupling, a row per coupling (i, j ≥ i): data against
    the model (``fit_<DOF>.png``, :func:`cummins.fit_figures.fit_figures`); ``say`` is
    told each file as it is written.

    ``ds`` is the data as read (one forward speed); the frequencies the fit left out are
    drawn as open circles.
    """
    from cummins.fit_figures import fit_figures, fitted_rows
    from cummins.plots import save_figure

    names = [f"fit_{model.dofs[i]}.png" for i in fitted_rows(model)]
    for name in names:  # before any work: no file is overwritten without --force
        check_writable(folder / name, force)
    written = []
    for name, fig in fit_figures(model, ds):
        written.append(save_figure(fig, folder / name, force=force))
        say(f"wrote {written[-1]}")
    return written


def write_model_mss_abc(model, ds: xr.Dataset, path: Path, *, force: bool = False) -> Path:
    """The model as an MSS ``vesselABC`` .mat, in Fossen's axes, with the data's rigid-body
    inertia and restoring matrices (about the data's reference point) and ``r_g`` from the
    data's centre of gravity (else from the inertia matrix; NaN and a warning if neither)."""
    from cummins.hydrodb import change_axes
    from cummins.io.mss_abc import write_mss_abc
    from cummins.radiation.model import change_model_axes

    fossen = change_axes(ds, "z-down")

    def matrix(name):
        if name not in fossen:
            return None
        return dof_matrix(fossen, name)

    z_down = change_model_axes(model, "z-down")
    cg = fossen.attrs.get("center_of_gravity")
    if cg is not None:  # r_g = G − the data's reference point, in the model's origin
        data_point = np.asarray(fossen.attrs.get("reference_point", np.zeros(3)), dtype=float)
        model_point = np.asarray(z_down.attrs.get("reference_point", np.zeros(3)), dtype=float)
        if data_point.size == 3 and model_point.size == 3 and np.size(cg) == 3:
            cg = np.asarray(cg, dtype=float).reshape(3) - data_point.reshape(3) + model_point
        else:
            cg = None
    return write_mss_abc(
        z_down,
        path,
        inertia_matrix=matrix("inertia_matrix"),
        hydrostatic_stiffness=matrix("hydrostatic_stiffness"),
        center_of_gravity=cg,
        force=force,
    )


def model_as_data(model, points: int = 200):
    """The model's own A(ω) − A∞ + A∞, B(ω) and K(t) as :class:`cummins.radiation.fit.FitData`: the
    reference a reduced or corrected model is measured against when the data are not at
    hand (log grid over the fitted range, K(t) to five times the slowest time constant)."""
    from cummins.radiation.fit import FitData
    from cummins.radiation.passivity import fit_range_grid

    w = fit_range_grid(model, points)
    k = model.response(w)
    poles = np.concatenate(
        [c.poles() for c in model.couplings if c.order]
        + [b.poles() for b in model.blocks if b.order]
    )
    t_end = 5.0 / max(float(np.abs(poles.real).min()), 1e-6)
    t = np.linspace(0.0, min(t_end, 100 * 2 * np.pi / w[0]), 500)
    inf = 0.5 * (model.added_mass_inf + model.added_mass_inf.T)  # as fit_data's symmetric A
    a = inf[None, :, :] + k.imag / w[:, None, None]
    return FitData(w, a, k.real, t, model.impulse_response(t).values)


def reduce_stage(
    model,
    *,
    order=None,
    tol: float | None = None,
    method: str = "lyapunov",
    data: xr.Dataset | None = None,
    passive: bool = True,
    motion_tol: float | None = None,
    progress: Callable[[str], object] | None = None,
    joined=None,
):
    """Reduce a radiation model and, by default, make the result passive as a MIMO model.

    A model of common-pole blocks (the default fit) comes out of the reduction passive,
    block by block, or with a failure (:func:`cummins.radiation.reduce.reduce_radiation_model`);
    ``passive`` applies to per-coupling models. The reduced model is measured against the
    data of the fit when ``data`` is given,
    else against the unreduced model (:func:`model_as_data`); the passivity correction
    minimises the change against the same reference (:func:`cummins.radiation.passivity.
    enforce_passivity`) and each coupling it changed gets its R² before and after in its
    note. With ``motion_tol`` (and ``data``), the fewest states whose motion RAOs stay
    within it (:func:`cummins.radiation.reduce.reduce_to_motion_tolerance`; with
    ``joined``, the joined system's motions a joined fit aimed at). Returns the
    reduced model, whether a passivity correction was made (None when ``passive`` is
    false) and the reference (:class:`cummins.radiation.fit.FitData`).
    """
    from cummins.radiation.fit import make_passive, model_fit_data
    from cummins.radiation.fit.metrics import coupling_metrics
    from cummins.radiation.passivity import is_passive
    from cummins.radiation.reduce import reduce_radiation_model, reduce_to_motion_tolerance

    if motion_tol is not None:
        reduced = reduce_to_motion_tolerance(
            model, data, motion_tol, method=method, progress=progress, joined=joined
        )
    else:
        reduced = reduce_radiation_model(
            model, order=order, tol=tol, method=method, data=data, progress=progress
        )
    reference = model_fit_data(model, data) if data is not None else model_as_data(model)
    if reduced.blocks:  # common-pole blocks are made passive by their reduction
        attrs = {**reduced.attrs, "mimo_passive": is_passive(reduced)}
        return replace(reduced, attrs=attrs), None, reference
    if not passive:
        return reduced, None, reference
    if progress is not None:
        progress("measuring the couplings; passivity of the MIMO model")
    # measures of fit against the reference, for the weighting of the correction
    couplings = []
    for k in reduced.couplings:
        i, j = k.influenced, k.radiating
        metrics = coupling_metrics(
            k,
            reference.omega,
            reference.added_mass[:, i, j],
            reference.damping[:, i, j],
            float(reduced.added_mass_inf[i, j]),
            time=reference.time,
            kernel=reference.kernel[:, i, j],
        )
        couplings.append(replace(k, metrics={**k.metrics, **metrics}))
    reduced = replace(reduced, couplings=tuple(couplings))
    if is_passive(reduced):
        return replace(reduced, attrs={**reduced.attrs, "mimo_passive": True}), None, reference
    r2 = float(model.attrs.get("r2_target", 0.99))
    r2_coupling = float(model.attrs.get("r2_coupling_target", 0.97))
    corrected = make_passive(reduced, reference, r2=r2, r2_coupling=r2_coupling, augment=False)
    return corrected, True, reference


def write_simulation_plots(run, vessel, ds, sea, folder: Path, *, force: bool = False):
    """``time_series.png``, and for irregular seas ``response_spectra.png``: the
    simulation (Welch) against the frequency-domain spectrum of the same linear model."""
    from cummins.plots import plot_response_spectra, plot_time_series, save_figure
    from cummins.timedomain.simulate import component_motions

    folder.mkdir(parents=True, exist_ok=True)
    written = [save_figure(plot_time_series(run), folder / "time_series.png", force=force)]
    if len(sea) > 1:
        from cummins.seakeeping.excitation import encounter_frequencies

        width = float(getattr(sea, "bin_width", None) or np.median(np.diff(np.sort(sea.omega))))
        # at a forward speed the run is on the encounter-frequency axis: the density of
        # each component's variance there is divided by |dω_e/dω| (1 at zero speed)
        we = encounter_frequencies(ds, sea.omega, sea.direction)
        step = 1e-6 * sea.omega
        slope = (
            encounter_frequencies(ds, sea.omega + step, sea.direction)
            - encounter_frequencies(ds, sea.omega - step, sea.direction)
        ) / (2 * step)
        order = np.argsort(np.abs(we))
        w = np.abs(we)[order]
        x = component_motions(vessel, ds, sea)[order]
        jacobian = np.maximum(np.abs(slope[order]), 1e-3)[:, None]
        density = 0.5 * np.abs(x) ** 2 / (width * jacobian)
        references = {"frequency domain (same model)": (w, density)}
        written.append(
            save_figure(
                plot_response_spectra(run, references),
                folder / "response_spectra.png",
                force=force,
            )
        )
    return written
