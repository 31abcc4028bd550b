"""Batch studies: many sea states, headings and seeds, run on a Dask cluster.

A :class:`Study` is one vessel (a ``HydroDB`` file, optionally a fitted radiation model)
and a set of :class:`Case`\\ s — the outer product of a ``grid`` of headings, H_s, T_p
(and optionally γ, cos-2s spreading and seeds), or an explicit list. Each case is one
of two analyses:

``rao`` (frequency domain, cheap)
    The coupled motion RAOs (:func:`cummins.seakeeping.frequency_domain.motion_rao`, on
    ``n_omega`` frequencies over the data's range, once per heading and worker), the
    response spectrum S_j = Σ_β w_β |X_j|² S(ω) and its moments m₀, m₂. Statistics: the
    standard deviation σ = √m₀, the significant (single) amplitude 2√m₀
    (:func:`cummins.seakeeping.frequency_domain.significant_amplitude`: half the crest-to-trough
    4√m₀, as H_s/2 for the waves), the mean zero-up-crossing period T_z = 2π√(m₀/m₂) and
    the most probable maximum in ``duration`` (Rayleigh peaks: σ√(2 ln N), N = duration/T_z).
``simulate`` (time domain)
    :func:`cummins.timedomain.simulate.simulate_waves` of the vessel (the model file, or one passive
    fit made before the cases) in a realisation of the sea, ``duration`` s at ``dt``,
    started on the stationary solution. Statistics of the record: σ, 2σ, T_z from the
    mean up-crossings and the observed maximum max|ξ(t)|. Each case's random phases come
    from its ``seed``, or from a seed derived from the case itself (a hash of its
    parameters): results never depend on which worker ran a case, or in which order.

:func:`run_study` runs the cases with ``dask.distributed`` (``pip install
cummins[dask]``): a local cluster of single-threaded worker processes (BLAS limited to one
thread) or any scheduler address; the vessel data are sent to each worker once. Every
finished case is saved at once as ``<output>.parts/<case id>.json`` (exact floats); a
rerun after an interruption loads the saved cases and computes only the others. The case
id is a hash of everything the result depends on (analysis settings, the content of the
data and model, the case's parameters), so a changed study never mixes old results into
new ones: cases that changed are computed again, saved cases of other definitions are
ignored (and counted). At the end the results are gathered into one ``xarray.Dataset``
(dims of the grid — ``heading`` (deg), ``hs``, ``tp``, … — and ``dof``, or ``case`` for a
list), limits applied (:mod:`cummins.studies.operability`), written as NetCDF (or Zarr for a
``.zarr`` output) and the parts removed.

A study may describe a multi-body system (``system:``, :mod:`cummins.mechanics`): joints,
PTOs, the DOFs that move, the body coupling. Both analyses then solve the joined system
and report, besides the motions of the DOFs that can move, each PTO's mean absorbed power
``pto_mean_power``: Σ_β w_β ∫ c ω² |Δ̂(ω, β)|² S(ω) dω in the frequency domain, the mean of
(kΔ + cΔ̇)Δ̇ over the run in the time domain (W).

The study itself is defined in :mod:`cummins.studies.study`.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import math
import os
import shutil
import time
import uuid
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from cummins.errors import CumminsError, check_writable
from cummins.files import replacing
from cummins.radiation.model import MODEL_FAILURES, model_failures
from cummins.studies.pto_sweep import SWEEP_AXES, best_pto_damping, case_system, sweep_units
from cummins.studies.results import is_results, load_results, write_results
from cummins.studies.speed import select_study_speed, vessel_at_study_speed
from cummins.studies.study import (
    _BLAS_ENV,
    _RESULT_KIND,
    ANALYSES,
    GRID_AXES,
    Case,
    Limit,
    Study,
    StudyError,
    at_key,
    example_study_text,
    load_study,
    parse_limit_value,
)
from cummins.studies.wording import (
    WARNINGS_KEY,
    recorded_warnings,
    reissue_warnings,
    study_warnings,
    study_wording,
)
from cummins.validation import check_memory, simulation_memory, time_steps

__all__ = [
    "ANALYSES",
    "GRID_AXES",
    "BatchRun",
    "Case",
    "Limit",
    "Study",
    "StudyContext",
    "StudyError",
    "case_ids",
    "case_statistics",
    "example_study_text",
    "gather_results",
    "is_results",
    "load_results",
    "load_study",
    "parse_limit_value",
    "parts_folder",
    "prepare_study",
    "run_study",
    "write_results",
]


# --------------------------------------------------------------------------- one case


@dataclass(frozen=True, eq=False)
class StudyContext:
    """What every case needs, sent to each worker once."""

    study: Study
    ds: xr.Dataset
    vessel: Any = None
    omega: Any = None
    cache: dict = field(default_factory=dict, repr=False)
    dofs: tuple[str, ...] = ()
    ptos: tuple[str, ...] = ()
    vessels: dict = field(default_factory=dict, repr=False)  # per swept (c, k) of a PTO
    units: dict = field(default_factory=dict)  # of the sweep's axes

    def system(self, case: Case):
        """The study's system with the case's swept PTO values (:mod:`.pto_sweep`)."""
        s = self.study
        return case_system(s.system, s.swept_pto, case.pto_damping, case.pto_stiffness)

    def vessel_for(self, case: Case):
        """The vessel of a time-domain case: with the case's swept PTO values."""
        return self.vessels.get((case.pto_damping, case.pto_stiffness), self.vessel)

    @property
    def radiation_model(self) -> dict[str, Any]:
        """What the results record of the radiation model of a time-domain study (empty
        for ``rao``): the model file (or that it was fitted to the data), its order, its
        motion error and, when it missed its fit targets (``cummins fit`` exit status
        3), its ``failures`` as ``model_failures`` (one per line, as ``cummins
        simulate``'s run file records them)."""
        if self.vessel is None:
            return {}
        attrs = self.vessel.radiation.attrs
        study = self.study
        out: dict[str, Any] = {
            "radiation_model": str(study.model) if study.model else "fitted to the data",
            "radiation_model_order": int(self.vessel.radiation.total_order),
        }
        if attrs.get("motion_error") is not None:
            out["radiation_model_motion_error"] = float(attrs["motion_error"])
        for key in ("speed_memory", "speed_motion_error", "speed_terms", "soft_springs"):
            if key in self.vessel.attrs:  # a ship at speed (vessel_at_speed)
                out[key] = self.vessel.attrs[key]
        failures = model_failures(attrs)
        if failures:
            out[MODEL_FAILURES] = "\n".join(failures)
        if len(self.vessels) > 1:  # a PTO sweep: one model for every value
            fitted = "" if study.model else ", fitted at the smallest damping"
            out["radiation_model_sweep"] = f"one radiation model for every PTO value{fitted}"
        return out

    @property
    def labels(self) -> list[str]:
        """The DOFs of the results (those the system lets move)."""
        return list(self.dofs) or [str(d) for d in self.ds.influenced_dof.values]


def prepare_study(study: Study) -> tuple[StudyContext, str]:
    """Read the data (and model), complete them with the study's inertia and external
    terms (:mod:`cummins.studies.equation_of_motion`), check that they hold what the
    analysis needs, fit once if needed; (context, digest of the inputs). Everything a
    study can fail on in its definition or its data is found here, before any Dask
    work. Its warnings name the study's keys, not the options of the command line
    (:func:`~cummins.studies.wording.study_warnings`)."""
    with study_warnings(study.source):
        try:
            return _prepare_study(study)
        except CumminsError as exc:  # its hints in the study's keys, its type kept
            if exc.args and isinstance(exc.args[0], str):
                exc.args = (study_wording(exc.args[0], study.source), *exc.args[1:])
            raise


def _prepare_study(study: Study) -> tuple[StudyContext, str]:
    """:func:`prepare_study`'s work."""
    from cummins.hydrodb import single_speed
    from cummins.io import read
    from cummins.studies.equation_of_motion import check_study_data, complete_study_data

    full = complete_study_data(
        read(study.data, rho=study.rho, g=study.g, ulen=study.ulen, water_depth=study.water_depth),
        study,
    )
    ds = select_study_speed(full, study)
    check_study_data(ds, study)
    labels = [str(d) for d in ds.influenced_dof.values]
    system = {}
    if study.system is not None:
        from cummins.mechanics import assemble

        assembly = assemble(single_speed(ds), study.system)
        labels = list(assembly.dofs)
        system = {"dofs": assembly.dofs, "ptos": tuple(p.name for p in assembly.ptos)}
        system["units"] = sweep_units(assembly, study.swept_pto)
    for lim in study.limits:
        if lim.dof not in labels:
            raise StudyError(
                f"{at_key(study.source, f'limits.{lim.dof}')}: the data have no DOF {lim.dof!r}"
                + (" that can move" if study.system is not None else ""),
                hint=f"DOFs: {', '.join(labels)}",
            )
    for dof, _ in study.viscous_damping:
        if dof not in labels:
            raise StudyError(
                f"{at_key(study.source, f'viscous_damping.{dof}')}: the data have no DOF {dof!r}"
                + (" that can move" if study.system is not None else ""),
                hint=f"DOFs: {', '.join(labels)}",
            )
    check_study_size(study, len(labels))
    digest = hashlib.sha256(_dataset_digest(ds).encode())
    damping = dict(study.viscous_damping) or None
    if study.analysis == "rao":
        w = ds.omega.values
        lo = float(w[0]) if study.omega_min is None else study.omega_min
        hi = float(w[-1]) if study.omega_max is None else study.omega_max
        if not hi > lo:
            raise StudyError(f"{at_key(study.source, 'omega_max')}: must exceed omega_min")
        omega = np.linspace(lo, hi, study.n_omega)
        return StudyContext(study, ds, omega=omega, **system), digest.hexdigest()
    from cummins.radiation.model import RadiationModel
    from cummins.vessel import vessel_from_hydrodb

    model = None
    if study.model is not None:
        model = RadiationModel.load(study.model)
        digest.update(Path(study.model).read_bytes())
    at_speed = vessel_at_study_speed(full, ds, study, damping)
    if at_speed is not None:  # no PTO at speed (studies/speed.py): nothing swept
        vessel, ds = at_speed
        vessel.stability()
        return StudyContext(study, ds, vessel=vessel, **system), digest.hexdigest()
    swept = {(c.pto_damping, c.pto_stiffness) for c in study.all_cases}
    context = StudyContext(study, ds, **system)
    vessels = {}  # one fit, at the smallest damping swept (the most resonant system)
    for c, k in sorted(swept, key=lambda ck: (ck[0] or 0.0, str(ck[1]))):
        swept_system = case_system(study.system, study.swept_pto, c, k)
        vessels[c, k] = vessel_from_hydrodb(
            single_speed(ds), model, viscous_damping=damping, system=swept_system
        )
        model = vessels[c, k].radiation
        vessels[c, k].stability()
    vessel = next(iter(vessels.values()))
    return replace(context, vessel=vessel, vessels=vessels), digest.hexdigest()


def _dataset_digest(ds: xr.Dataset) -> str:
    """SHA-256 of a dataset's variables and values (not of its file: any format)."""
    h = hashlib.sha256()
    for name in sorted(map(str, ds.variables)):
        values = np.asarray(ds[name].values)
        h.update(name.encode())
        h.update(str(values.shape).encode())
        if values.dtype.kind in "OUS":
            h.update(repr(values.tolist()).encode())
        else:
            h.update(np.ascontiguousarray(values).tobytes())
    return h.hexdigest()


def _derived_seed(case: Case) -> int:
    """A seed from the case's parameters: the same case gets the same sea anywhere, and
    every value of a PTO sweep the same sea (the dampings compared on one realisation)."""
    sea = {k: v for k, v in case.parameters().items() if k not in SWEEP_AXES}
    text = json.dumps(sea, sort_keys=True)
    return int(hashlib.sha256(text.encode()).hexdigest()[:8], 16)


def check_study_size(study: Study, n_dofs: int) -> None:
    """Refuse a study whose cases need more memory than :func:`cummins.validation.memory_limit`
    before anything is allocated (an :class:`~cummins.errors.ArgumentError` naming the
    study's key): the RAO frequency grid and the coupled solve per heading
    (``n_omega`` × n² complex matrices), or a run (``duration``/``dt`` samples of the
    states) and its wave components (``components`` × ``directions``)."""
    n = int(n_dofs)
    if study.analysis == "rao":
        check_memory(
            float(study.n_omega) * (n * n * 16 * 4 + n * 16 * 4 + 8 * 4),
            f"{at_key(study.source, 'n_omega')}: RAOs at {study.n_omega} frequencies "
            f"({n} DOFs) per case",
            hint="lower n_omega",
        )
        return
    steps = time_steps(study.duration, study.dt)
    check_memory(
        simulation_memory(steps, 2 * n, n),
        f"{at_key(study.source, 'duration')}: a run of {steps:.4g} time steps ({n} DOFs) per case",
        hint="shorten duration or lengthen dt",
    )
    components = float(study.components) * float(study.directions)
    check_memory(
        components * (8 * 6 + n * 16 * 2),
        f"{at_key(study.source, 'components')}: {study.components} wave components x "
        f"{study.directions} directions ({n} DOFs) per case",
        hint="lower components (or directions)",
    )


def case_statistics(context: StudyContext, case: Case) -> dict[str, Any]:
    """Response statistics of one case (module docstring), per DOF, SI units.

    Returns a dict of lists: ``std``, ``significant_amplitude``, ``maximum``,
    ``zero_crossing_period`` and the ``seed`` used (simulate).
    """
    study = context.study
    heading = math.radians(case.heading)
    if study.analysis == "rao":
        return _rao_statistics(context, case, heading)
    from cummins.seakeeping.waves import energy_range, irregular_waves, wave_spectrum
    from cummins.timedomain.simulate import simulate_waves

    seed = _derived_seed(case) if case.seed is None else case.seed
    shape = wave_spectrum(study.spectrum, case.hs, case.tp, _gamma(study, case))
    lo, hi = energy_range(shape)
    data_w = context.ds.omega.values
    sea = irregular_waves(
        shape,
        omega_min=max(lo, float(data_w[0])),  # as `cummins simulate`: the force is known
        omega_max=min(hi, float(data_w[-1])),  # within the data's frequencies only
        duration=study.duration,
        n_components=study.components,
        direction=heading,
        spreading=case.spreading,
        n_directions=study.directions if case.spreading is not None else 1,
        seed=seed,
    )
    vessel = context.vessel_for(case)
    run = simulate_waves(vessel, context.ds, sea, duration=study.duration, dt=study.dt)
    xi = run.motion.values
    std = xi.std(axis=0)
    centred = xi - xi.mean(axis=0)
    up = ((centred[:-1] < 0) & (centred[1:] >= 0)).sum(axis=0)
    tz = np.where(up > 0, study.duration / np.maximum(up, 1), np.nan)
    out = {
        "std": std.tolist(),
        "significant_amplitude": (2.0 * std).tolist(),
        "maximum": np.abs(xi).max(axis=0).tolist(),
        "zero_crossing_period": tz.tolist(),
        "seed": int(seed),
    }
    if "pto_power" in run:
        out["pto_mean_power"] = run.pto_power.mean("time").values.tolist()
    return out


def _gamma(study: Study, case: Case) -> float | None:
    if str(study.spectrum).lower() == "jonswap":
        return case.gamma
    if case.gamma is not None:
        raise StudyError(f"{at_key(study.source, 'gamma')}: applies to the JONSWAP spectrum only")
    return None


def _rao_statistics(context: StudyContext, case: Case, heading: float) -> dict[str, Any]:
    from cummins.seakeeping.frequency_domain import (
        motion_rao,
        response_spectrum,
        significant_amplitude,
        spectral_moment,
    )
    from cummins.seakeeping.waves import spreading_directions, wave_spectrum

    study = context.study
    if case.spreading is None:
        directions, weights = np.array([heading]), None
    else:
        directions, weights = spreading_directions(heading, case.spreading, study.directions)
    key = (*directions.tolist(), case.pto_damping, case.pto_stiffness)
    rao = context.cache.get(key)
    if rao is None:
        system = context.system(case)
        rao = motion_rao(
            context.ds,
            context.omega,
            directions,
            viscous_damping=dict(study.viscous_damping) or None,
            system=system,
        )
        if system is not None and system.ptos:
            from cummins.seakeeping.frequency_domain import pto_rao

            rao = (rao, pto_rao(rao, context.ds, system).pto_power)
        context.cache[key] = rao
    power = None
    if isinstance(rao, tuple):
        rao, power = rao
    sea = wave_spectrum(study.spectrum, case.hs, case.tp, _gamma(study, case))
    response = response_spectrum(rao, sea, direction_weights=weights)
    m0 = spectral_moment(response, 0).values
    m2 = spectral_moment(response, 2).values
    sigma = np.sqrt(m0)
    with np.errstate(divide="ignore", invalid="ignore"):
        tz = np.where(m2 > 0, 2.0 * np.pi * np.sqrt(m0 / m2), np.nan)
        n_peaks = np.where(tz > 0, study.duration / tz, 1.0)
    mpm = sigma * np.sqrt(2.0 * np.log(np.maximum(n_peaks, math.e)))
    out = {
        "std": sigma.tolist(),
        "significant_amplitude": significant_amplitude(response).values.tolist(),
        "maximum": mpm.tolist(),
        "zero_crossing_period": tz.tolist(),
        "seed": None,
    }
    if power is not None:
        # a component of amplitude a = sqrt(2 S dω) absorbs pto_power a²: P = ∫ 2 pto_power S dω
        w = np.ones(directions.size) / directions.size if weights is None else np.asarray(weights)
        density = 2.0 * (power * xr.DataArray(w, dims="wave_direction")).sum("wave_direction")
        mean = (density * xr.DataArray(sea(power.omega.values), dims="omega")).integrate("omega")
        out["pto_mean_power"] = mean.values.tolist()
    return out


def _run_case(context: StudyContext, case: Case) -> dict[str, Any]:
    """The task a worker runs: statistics of one case (errors name the case; errors and
    warnings name the study's keys: :mod:`cummins.studies.wording`)."""
    source = context.study.source
    try:
        with study_warnings(source):
            return case_statistics(context, case)
    except CumminsError as exc:
        raise StudyError(f"case {case.label}: {study_wording(str(exc), source)}") from None


def _worker_case(context: StudyContext, case: Case) -> dict[str, Any]:
    """:func:`_run_case` in a worker process: its warnings return with its results
    (:func:`~cummins.studies.wording.recorded_warnings`), shown once where the study runs."""
    with recorded_warnings() as caught:
        values = _run_case(context, case)
    return {**values, WARNINGS_KEY: caught}


# --------------------------------------------------------------------------- running


@dataclass(frozen=True)
class BatchRun:
    """What :func:`run_study` did: the gathered results and how they were obtained."""

    results: xr.Dataset
    output: Path
    computed: int
    skipped: int
    ignored: int
    workers: int
    elapsed: float


def case_ids(study: Study, digest: str) -> list[str]:
    """The id of each case: a hash of the settings, the inputs' digest and the case."""
    settings = json.dumps(study.settings(), sort_keys=True)
    out = []
    for case in study.all_cases:
        text = json.dumps([settings, digest, case.parameters()], sort_keys=True)
        out.append(hashlib.sha256(text.encode()).hexdigest()[:24])
    return out


def parts_folder(output: str | os.PathLike[str]) -> Path:
    """Where the finished cases of a run into ``output`` are saved: ``<output>.parts``."""
    output = Path(output)
    return output.with_name(output.name + ".parts")


def _save_part(folder: Path, case_id: str, case: Case, values: dict[str, Any]) -> None:
    from cummins._version import __version__

    record = {
        "case_id": case_id,
        "case": case.parameters(),
        "values": values,
        "cummins_version": __version__,
    }
    folder.mkdir(parents=True, exist_ok=True)  # with the first part: never an empty one
    with replacing(folder / f"{case_id}.json") as tmp:
        tmp.write_text(json.dumps(record), encoding="utf-8")


def _load_parts(folder: Path, wanted: dict[str, Case]) -> tuple[dict[str, dict], int]:
    """Saved results of the wanted cases, and the number of other (ignored) parts."""
    done: dict[str, dict] = {}
    ignored = 0
    if not folder.is_dir():
        return done, ignored
    for file in folder.glob("*.json"):
        try:
            record = json.loads(file.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue  # a part cut short by a crash: computed again
        case_id = record.get("case_id")
        if case_id in wanted and record.get("case") == wanted[case_id].parameters():
            done[case_id] = record["values"]
        else:
            ignored += 1
    return done, ignored


def _dask():
    try:
        import distributed
    except ImportError:
        raise CumminsError(
            "batch studies run on Dask, which is not installed: pip install cummins[dask]"
        ) from None
    return distributed


def run_study(
    study: Study,
    output: str | os.PathLike[str],
    *,
    scheduler: str | None = None,
    workers: int | None = None,
    force: bool = False,
    progress: Callable[[int, int], object] | None = None,
    on_case_saved: Callable[[str, Case], object] | None = None,
    say: Callable[[str], object] = lambda message: None,
    on_prepared: Callable[[StudyContext], object] | None = None,
) -> BatchRun:
    """Run every case of ``study`` on Dask and write the gathered results to ``output``.

    Parameters
    ----------
    study
        The study (:func:`load_study`, or a :class:`Study`).
    output
        The results file: NetCDF (``.nc``) or Zarr (``.zarr``, needs the ``zarr``
        package). Finished cases are saved in ``<output>.parts`` as they come (a rerun
        resumes from them) and the folder is removed once the results are written.
    scheduler
        Address of a running Dask scheduler (``tcp://host:8786``); None: a local cluster
        of ``workers`` single-threaded processes (default: one per core).
    workers
        Worker processes of the local cluster.
    force
        Overwrite ``output`` if it exists (saved parts of the same cases are still used).
    progress
        Called with (cases done, total) as cases finish (resumed ones count as done).
    on_case_saved
        Called with (case id, case) after each newly computed case is saved.
    say
        Called with short messages (cases resumed, parts ignored).
    on_prepared
        Called with the :class:`StudyContext` once the data are read, checked and the
        radiation model fitted or loaded, before any Dask work (``cummins batch`` says
        there, in one line, that the model missed its fit targets).

    Returns
    -------
    BatchRun
        The results (:func:`load_results` layout) and counts of computed and resumed cases.
        A time-domain study's results record its radiation model
        (:attr:`StudyContext.radiation_model`: ``radiation_model_order``,
        ``radiation_model_motion_error``, and ``model_failures`` when it missed its fit
        targets).

    Raises
    ------
    StudyError
        A bad study, or a case that failed (named); the cases saved before it are kept.
    """
    _dask()  # Dask installed, before anything is read
    output = Path(output)
    check_writable(output, force)
    output.parent.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    context, digest = prepare_study(study)
    if on_prepared is not None:
        on_prepared(context)
    cases = study.all_cases
    ids = case_ids(study, digest)
    folder = parts_folder(output)
    done, ignored = _load_parts(folder, dict(zip(ids, cases, strict=True)))
    skipped = len(done)
    if skipped:
        say(f"resuming: {skipped} of {len(cases)} cases already saved in {folder}")
    if ignored:
        say(f"{ignored} saved cases in {folder} belong to another study definition: ignored")
    todo = [(i, c) for i, c in zip(ids, cases, strict=True) if i not in done]
    report = progress or (lambda done, total: None)
    report(len(done), len(cases))
    try:
        n_workers = _compute(
            context,
            todo,
            folder,
            done,
            len(cases),
            scheduler=scheduler,
            workers=workers,
            report=report,
            on_case_saved=on_case_saved,
        )
    finally:
        _remove_if_empty(folder)  # a study refused or failed before its first case
    values = [done[i] for i in ids]
    results = gather_results(
        study, values, ids, context.labels, ptos=context.ptos, units=context.units
    )
    results.attrs.update(context.radiation_model)
    write_results(results, output, force=force)
    shutil.rmtree(folder, ignore_errors=True)
    return BatchRun(
        results,
        output,
        computed=len(todo),
        skipped=skipped,
        ignored=ignored,
        workers=n_workers,
        elapsed=time.perf_counter() - start,
    )


def _remove_if_empty(folder: Path) -> None:
    with contextlib.suppress(OSError):
        folder.rmdir()  # only when empty


def _compute(
    context: StudyContext,
    todo: list[tuple[str, Case]],
    folder: Path,
    done: dict[str, dict],
    total: int,
    *,
    scheduler: str | None,
    workers: int | None,
    report: Callable[[int, int], object],
    on_case_saved: Callable[[str, Case], object] | None,
) -> int:
    """Run the ``todo`` cases on Dask, each saved in ``folder`` and put in ``done`` as it
    comes; the number of workers used."""
    distributed = _dask()
    n_workers = 0
    if todo:
        cluster = None
        if scheduler is None:
            import logging

            cluster = distributed.LocalCluster(
                n_workers=workers or os.cpu_count() or 1,
                threads_per_worker=1,
                processes=True,
                dashboard_address=":0",  # any free port: never a clash with another cluster
                silence_logs=logging.CRITICAL,  # a case's error is raised as one line
                env=_BLAS_ENV,
            )
        try:
            with distributed.Client(cluster or scheduler) as client:
                n_workers = len(client.scheduler_info().get("workers", {}))
                shared = client.scatter(context, broadcast=True)
                token = uuid.uuid4().hex[:8]  # keys of this run only: a rerun is never confused
                futures = {
                    client.submit(_worker_case, shared, case, key=f"cummins-{i}-{token}"): (i, case)
                    for i, case in todo
                }
                try:
                    for future in distributed.as_completed(futures):
                        case_id, case = futures[future]
                        values = future.result()
                        reissue_warnings(values.pop(WARNINGS_KEY, []))
                        _save_part(folder, case_id, case, values)
                        done[case_id] = values
                        report(len(done), total)
                        if on_case_saved is not None:
                            on_case_saved(case_id, case)
                finally:
                    client.cancel(list(futures))
        finally:
            if cluster is not None:
                cluster.close()
    return n_workers


# --------------------------------------------------------------------------- results


_VARIABLES = {
    "std": "standard deviation of the response",
    "significant_amplitude": "significant single amplitude 2 sqrt(m0) (half of 4 sqrt(m0))",
    "maximum": "maximum amplitude",
    "zero_crossing_period": "mean zero-up-crossing period",
}


def gather_results(
    study: Study,
    values: Sequence[dict],
    ids: Sequence[str],
    dofs: Sequence[str],
    *,
    ptos: Sequence[str] = (),
    units: dict | None = None,
) -> xr.Dataset:
    """One Dataset of the cases' statistics, limits applied (:func:`cummins.studies.operability.
    exceedance`): ``values`` from :func:`case_statistics` and ``ids`` from :func:`case_ids`
    in ``study.all_cases`` order; ``dofs`` the DOF labels of the results; ``ptos`` the PTOs'
    names (their ``pto_mean_power``, W); ``units`` those of the grid's axes where they
    depend on the data (a PTO sweep's, :func:`.pto_sweep.sweep_units`). A PTO sweep's
    best damping is added (:func:`.pto_sweep.best_pto_damping`)."""
    from cummins._version import __version__
    from cummins.studies.operability import exceedance

    cases = study.all_cases
    n_dof = len(dofs)
    axis_units = {**GRID_AXES, **(units or {})}
    if study.grid is not None:
        shape = tuple(len(v) for _, v in study.grid)
        coords: dict[str, Any] = {
            name: (name, np.asarray(v), {"units": axis_units[name]}) for name, v in study.grid
        }
    else:  # a list: each case's values (a PTO's too) as coordinates along "case"
        shape = (len(cases),)
        coords = {"case": ("case", np.arange(len(cases)))}
        for name in GRID_AXES:
            column = [getattr(c, name) for c in cases]
            if any(v is not None for v in column):
                column = [np.nan if v is None else float(v) for v in column]
                coords[name] = ("case", np.asarray(column), {"units": axis_units[name]})
    coords["dof"] = ("dof", dofs)
    dims = study.dims
    data: dict[str, Any] = {}
    max_label = (
        "most probable maximum sigma sqrt(2 ln(duration/Tz)) (Rayleigh)"
        if study.analysis == "rao"
        else "observed maximum |x(t)|"
    )
    for name, long_name in _VARIABLES.items():
        array = np.array([v[name] for v in values], dtype=float).reshape(*shape, n_dof)
        units = "s" if name == "zero_crossing_period" else "m | rad (translation | rotation)"
        data[name] = (
            (*dims, "dof"),
            array,
            {"units": units, "long_name": max_label if name == "maximum" else long_name},
        )
    if ptos:
        coords["pto"] = ("pto", list(ptos))
        power = np.array([v["pto_mean_power"] for v in values], dtype=float)
        data["pto_mean_power"] = (
            (*dims, "pto"),
            power.reshape(*shape, len(ptos)),
            {"units": "W", "long_name": "mean power absorbed by the PTO"},
        )
    data["case_id"] = (dims, np.array(list(ids), dtype=object).reshape(shape))
    if study.analysis == "simulate":
        seeds = np.array([v["seed"] for v in values], dtype=np.int64).reshape(shape)
        data["seed_used"] = (dims, seeds, {"long_name": "seed of the random phases"})
    if study.grid is not None and study.scatter:
        axes = dict(study.grid)
        table = np.zeros((len(axes["hs"]), len(axes["tp"])))
        for hs, tp, p in study.scatter:
            table[axes["hs"].index(hs), axes["tp"].index(tp)] = p
        data["probability"] = (("hs", "tp"), table / table.sum(), {"long_name": "scatter"})
    elif study.grid is None and any(c.probability is not None for c in cases):
        weights = np.array([0.0 if c.probability is None else c.probability for c in cases])
        data["probability"] = (("case",), weights / weights.sum())
    ds = xr.Dataset(data, coords=coords)
    ds.attrs = {
        "cummins_kind": _RESULT_KIND,
        "title": study.name or f"cummins batch study ({study.analysis})",
        "analysis": study.analysis,
        "analysis_description": ANALYSES[study.analysis],
        "data_file": str(study.data),
        "model_file": "" if study.model is None else str(study.model),
        "study_file": "" if study.source is None else str(study.source),
        "study": json.dumps(study.describe()),
        "n_cases": len(cases),
        "duration": study.duration,
        "spectrum": str(study.spectrum).lower(),
        "cummins_version": __version__,
    }
    out = exceedance(ds, study.limits)
    if study.limits and {"heading", "tp"} <= set(out.dims):
        from cummins.studies.operability import limiting_hs

        lim = limiting_hs(out).reindex(heading=out.heading, tp=out.tp)
        out["limiting_hs"] = lim.drop_vars("beyond_grid")
        out["limiting_hs_beyond_grid"] = lim.beyond_grid.fillna(False).astype(bool)
        out.limiting_hs_beyond_grid.attrs = dict(lim.beyond_grid.attrs)
    out = out.assign_coords({d: ds[d] for d in dims if d in ds.coords})  # with their units
    return best_pto_damping(out)
