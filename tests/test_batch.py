"""Batch studies on Dask: identical results on 1 and 2 workers, resumption, statistics,
operability, study files and the ``cummins batch`` command (the bundled real tanker)."""

from __future__ import annotations

import json
import logging
import math
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.errors import ArgumentError, OutputExistsError
from cummins.studies.batch import (
    Limit,
    Study,
    StudyError,
    case_statistics,
    load_results,
    load_study,
    parts_folder,
    prepare_study,
    run_study,
)
from cummins.studies.operability import limiting_hs, operability

distributed = pytest.importorskip("distributed")

TANKER = cummins.demo_files() / "tanker.1"
FD_LIMITS = {"Roll": "4 deg", "Pitch": "1.5 deg", "Heave": {"max": "2.5 m"}}


def _cluster(n: int):
    return distributed.LocalCluster(
        n_workers=n,
        threads_per_worker=1,
        processes=True,
        dashboard_address=":0",  # any free port: never a clash with another cluster
        silence_logs=logging.ERROR,
    )


@pytest.fixture(scope="module")
def two_workers():
    """Address of a local cluster of two worker processes, shared by the module."""
    with _cluster(2) as cluster:
        yield cluster.scheduler_address


def _fd_study(**changes) -> Study:
    options = {
        "data": TANKER,
        "analysis": "rao",
        "grid": {"heading": [90, 135, 180], "hs": [1.0, 2.5, 4.0], "tp": [7.0, 10.0, 13.0]},
        "viscous_damping": {"Roll": "5e8"},
        "n_omega": 250,
        "limits": FD_LIMITS,
        "scatter": {
            "hs": [1.0, 2.5, 4.0],
            "tp": [7.0, 10.0, 13.0],
            "probability": [[0.2, 0.1, 0.05], [0.1, 0.2, 0.1], [0.05, 0.1, 0.1]],
        },
    }
    options.update(changes)
    return Study(**options)


@pytest.fixture(scope="module")
def fd_run(two_workers, tmp_path_factory):
    """An uninterrupted frequency-domain study (27 cases) on two workers."""
    out = tmp_path_factory.mktemp("fd") / "results.nc"
    return run_study(_fd_study(), out, scheduler=two_workers)


@pytest.fixture(scope="module")
def model_file(tmp_path_factory):
    """The tanker's default passive fit, saved as a model file."""
    path = tmp_path_factory.mktemp("model") / "tanker_model.nc"
    cummins.fit_radiation(cummins.demo_dataset()).save(path)
    return path


def test_one_and_two_workers_give_identical_results(two_workers, model_file, tmp_path):
    """Time-domain cases (random phases from per-case seeds) are bitwise the same on one
    worker and on two, and equal to the same simulation run here."""
    study = Study(
        data=TANKER,
        model=model_file,
        analysis="simulate",
        grid={"heading": [135, 180], "hs": [2.0, 3.0], "tp": 9.0, "seed": [1, 2]},
        duration=300.0,
        dt=0.2,
        components=60,
        viscous_damping={"Surge": 1e6, "Sway": 1e6, "Yaw": 1e10},
        limits={"Pitch": {"max": "1 deg"}},
    )
    with _cluster(1) as one:
        single = run_study(study, tmp_path / "one.nc", scheduler=one.scheduler_address)
    double = run_study(study, tmp_path / "two.nc", scheduler=two_workers)
    assert (single.workers, double.workers) == (1, 2)
    assert single.computed == double.computed == 8
    xr.testing.assert_identical(single.results, double.results)
    xr.testing.assert_identical(
        load_results(tmp_path / "one.nc"), load_results(tmp_path / "two.nc")
    )
    assert single.results.significant_amplitude.dims == ("heading", "hs", "tp", "seed", "dof")
    # the model it ran: a fit that met its targets records its order, no failures
    model = cummins.RadiationModel.load(model_file)
    attrs = single.results.attrs
    assert "model_failures" not in attrs and not model.attrs.get("failures")
    assert attrs["radiation_model_order"] == model.total_order
    assert attrs["radiation_model_motion_error"] == model.attrs["motion_error"]
    # one case again, in this process, from its documented ingredients
    from cummins.seakeeping.waves import irregular_waves, wave_spectrum
    from cummins.timedomain.simulate import simulate_waves
    from cummins.vessel import vessel_from_hydrodb

    ds = cummins.demo_dataset()
    vessel = vessel_from_hydrodb(
        ds, cummins.RadiationModel.load(model_file), viscous_damping=[1e6, 1e6, 0, 0, 0, 1e10]
    )
    sea = irregular_waves(
        wave_spectrum("jonswap", 3.0, 9.0),
        duration=300.0,
        n_components=60,
        direction=math.radians(135),
        seed=2,
    )
    run = simulate_waves(vessel, ds, sea, duration=300.0, dt=0.2)
    case = double.results.sel(heading=135, hs=3.0, tp=9.0, seed=2)
    np.testing.assert_allclose(
        case.significant_amplitude.values, 2 * run.motion.values.std(axis=0), rtol=1e-9
    )
    np.testing.assert_allclose(
        case.maximum.values, np.abs(run.motion.values).max(axis=0), rtol=1e-9
    )
    # a different seed is a different sea: the statistics must differ
    other = double.results.sel(heading=135, hs=3.0, tp=9.0, seed=1)
    assert not np.allclose(other.maximum.values, case.maximum.values)


class _Interrupt(Exception):
    pass


def test_interrupted_study_resumes_without_recomputing(two_workers, fd_run, tmp_path):
    """Stop after 7 saved cases; a changed study ignores those parts; the original study
    then computes only the 20 others, leaves the saved parts untouched, and equals the
    uninterrupted run."""
    out = tmp_path / "results.nc"
    study = _fd_study()
    saved: list[str] = []

    def stop_after_seven(case_id, case):
        saved.append(case_id)
        if len(saved) == 7:
            raise _Interrupt

    with pytest.raises(_Interrupt):
        run_study(study, out, scheduler=two_workers, on_case_saved=stop_after_seven)
    folder = parts_folder(out)
    parts = {p.stem: p.stat().st_mtime_ns for p in folder.glob("*.json")}
    assert set(parts) == set(saved) and len(parts) == 7
    assert not out.exists()

    # another definition (a finer RAO grid) with the same output: nothing of it is reused
    messages: list[str] = []
    changed_ids: list[str] = []

    def stop_at_once(case_id, case):
        changed_ids.append(case_id)
        raise _Interrupt

    with pytest.raises(_Interrupt):
        run_study(
            _fd_study(n_omega=300),
            out,
            scheduler=two_workers,
            on_case_saved=stop_at_once,
            say=messages.append,
        )
    assert any("7 saved cases" in m and "another study" in m for m in messages), messages
    assert not set(changed_ids) & set(saved)

    computed: list[str] = []

    def record(case_id, case):
        if not computed:  # the parts saved before are untouched
            assert {p: (folder / f"{p}.json").stat().st_mtime_ns for p in parts} == parts
        computed.append(case_id)

    resumed = run_study(study, out, scheduler=two_workers, on_case_saved=record)
    assert resumed.skipped == 7 and resumed.computed == 20 and resumed.ignored == 1
    assert not set(computed) & set(saved)
    assert len(set(computed) | set(saved)) == 27
    xr.testing.assert_identical(resumed.results, fd_run.results)
    assert not folder.exists()  # gathered into the output, parts removed
    xr.testing.assert_identical(load_results(out), load_results(fd_run.output))


@pytest.mark.slow
def test_ctrl_c_then_rerun_computes_only_the_missing_cases(two_workers, model_file, tmp_path):
    """The command line interrupted as a terminal's Ctrl-C does (SIGINT to its process
    group, Dask's workers included) keeps the saved cases; the study run again (here on
    the shared cluster) resumes from them and computes only the others."""
    study = tmp_path / "study.yaml"
    study.write_text(
        textwrap.dedent(
            f"""\
            data: {TANKER}
            model: {model_file}
            analysis: simulate
            duration: 300
            dt: 0.1
            grid: {{heading: [120, 150, 180], hs: [2, 3, 4, 5], tp: [8, 10, 12, 14, 16]}}
            viscous_damping: {{Surge: 1e6, Sway: 1e6, Yaw: 1e10}}
            limits: {{Pitch: 2 deg}}
            """
        ),
        encoding="utf-8",
    )
    command = [sys.executable, "-m", "cummins.cli", "batch", str(study), "-o", "r.nc"]
    command += ["--workers", "1"]
    parts = tmp_path / "r.nc.parts"
    first = subprocess.Popen(
        command,
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        start_new_session=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    deadline = time.monotonic() + 120
    while len(list(parts.glob("*.json"))) < 5 and time.monotonic() < deadline:
        time.sleep(0.05)
    os.killpg(first.pid, signal.SIGINT)
    first.communicate(timeout=60)
    assert first.returncode != 0 and not (tmp_path / "r.nc").exists()
    saved = len(list(parts.glob("*.json")))
    assert 5 <= saved < 60
    before = {p.name: p.stat().st_mtime_ns for p in parts.glob("*.json")}
    computed: list[str] = []
    messages: list[str] = []
    again = run_study(
        load_study(study),
        tmp_path / "r.nc",
        scheduler=two_workers,
        say=messages.append,
        on_case_saved=lambda case_id, case: computed.append(f"{case_id}.json"),
    )
    assert f"resuming: {saved} of 60 cases already saved in {parts}" in messages
    assert (again.skipped, again.computed) == (saved, 60 - saved)
    assert not set(computed) & set(before) and len(computed) == 60 - saved
    results = load_results(tmp_path / "r.nc")
    assert results.case_id.size == 60 and np.isfinite(results.maximum.values).all()
    assert not parts.exists()


def test_frequency_domain_statistics_match_an_independent_computation(fd_run):
    """Significant amplitude, T_z and the most probable maximum of one case from
    cummins.seakeeping.frequency_domain and the Rayleigh formula written out here."""
    from cummins.seakeeping.frequency_domain import (
        motion_rao,
        response_spectrum,
        significant_amplitude,
    )
    from cummins.seakeeping.waves import jonswap

    ds = cummins.demo_dataset()
    w = np.linspace(ds.omega.values[0], ds.omega.values[-1], 250)
    rao = motion_rao(ds, w, [math.radians(135)], viscous_damping={"Roll": 5e8})
    s = jonswap(w, hs=2.5, tp=10.0, gamma=3.3)
    response = response_spectrum(rao, s)
    power = np.abs(rao.values[:, 0, :]) ** 2 * s[:, None]
    m0 = np.trapezoid(power, w, axis=0)
    m2 = np.trapezoid(power * w[:, None] ** 2, w, axis=0)
    tz = 2 * np.pi * np.sqrt(m0 / m2)
    mpm = np.sqrt(m0) * np.sqrt(2 * np.log(10800.0 / tz))
    case = fd_run.results.sel(heading=135, hs=2.5, tp=10.0)
    np.testing.assert_allclose(
        case.significant_amplitude.values, significant_amplitude(response).values, rtol=1e-12
    )
    np.testing.assert_allclose(case.significant_amplitude.values, 2 * np.sqrt(m0), rtol=1e-10)
    np.testing.assert_allclose(case.zero_crossing_period.values, tz, rtol=1e-10)
    np.testing.assert_allclose(case.maximum.values, mpm, rtol=1e-10)
    roll = case.limit_ratio.sel(criterion="Roll significant <= 4 deg")
    assert float(roll) == pytest.approx(2 * np.sqrt(m0[3]) / np.radians(4.0), rel=1e-10)


def test_operability_against_a_hand_count(fd_run):
    """Operability weighted by the scatter diagram, counted case by case; the limiting
    Hs is where the worst response meets its limit (a case computed at that Hs)."""
    results = fd_run.results
    p = {(1.0, 7.0): 0.2, (1.0, 10.0): 0.1, (1.0, 13.0): 0.05, (2.5, 7.0): 0.1}
    p |= {(2.5, 10.0): 0.2, (2.5, 13.0): 0.1, (4.0, 7.0): 0.05, (4.0, 10.0): 0.1}
    p |= {(4.0, 13.0): 0.1}
    roll_limit, pitch_limit = np.radians(4.0), np.radians(1.5)
    op = operability(results)
    assert 0 < float(op.min()) < 1, "the study should have some sea states beyond the limits"
    for heading in (90, 135, 180):
        good = total = 0.0
        for (hs, tp), prob in p.items():
            case = results.sel(heading=heading, hs=hs, tp=tp)
            sig = case.significant_amplitude.sel
            ok = (
                float(sig(dof="Roll")) <= roll_limit
                and float(sig(dof="Pitch")) <= pitch_limit
                and float(case.maximum.sel(dof="Heave")) <= 2.5
            )
            good += prob * ok
            total += prob
        assert float(op.sel(heading=heading)) == pytest.approx(good / total, rel=1e-12)
    lim = limiting_hs(results)
    assert lim.dims == ("heading", "tp")
    study = _fd_study()
    context, _ = prepare_study(study)
    from cummins.studies.batch import Case

    hs = float(lim.sel(heading=90, tp=10.0))
    stats = case_statistics(context, Case(heading=90, hs=hs, tp=10.0))
    ratios = [
        stats["significant_amplitude"][3] / roll_limit,
        stats["significant_amplitude"][4] / pitch_limit,
        stats["maximum"][2] / 2.5,
    ]
    assert max(ratios) == pytest.approx(1.0, rel=1e-9)


def test_list_study_with_probabilities(two_workers, tmp_path):
    """A list of cases gives a ``case`` dimension; operability uses their probabilities."""
    study_file = tmp_path / "list.yaml"
    study_file.write_text(
        textwrap.dedent(
            f"""\
            data: {TANKER}
            n_omega: 200
            cases:
              - {{heading: 90, hs: 4, tp: 12, probability: 0.25}}
              - {{heading: 90, hs: 1, tp: 8, probability: 0.75}}
              - {{heading: 180, hs: 4, tp: 12, gamma: 1.0, probability: 1}}
            limits:
              Roll: 3 deg
            """
        ),
        encoding="utf-8",
    )
    run = run_study(load_study(study_file), tmp_path / "list.nc", scheduler=two_workers)
    res = run.results
    assert res.significant_amplitude.dims == ("case", "dof")
    assert res.heading.values.tolist() == [90, 90, 180]
    assert np.isnan(res.gamma.values[0]) and res.gamma.values[2] == 1.0
    ok = res.operable.values
    assert ok.tolist() == [False, True, True]  # 4 m beam seas at 12 s roll the tanker > 3°
    op = operability(res)
    assert float(op.sel(heading=90)) == pytest.approx(0.75)
    assert float(op.sel(heading=180)) == 1.0


BAD_STUDIES = {
    "heading beyond a turn": ("data: {data}\ngrid: {{heading: 1e9, hs: 1, tp: 8}}", "grid"),
    "unknown key": ("data: {data}\nanalysys: rao\ngrid: {{heading: 1, hs: 1, tp: 8}}", "analysys"),
    "missing data": ("data: nowhere.1\ngrid: {{heading: 1, hs: 1, tp: 8}}", "nowhere.1"),
    "degrees on heave": (
        "data: {data}\ngrid: {{heading: 1, hs: 1, tp: 8}}\nlimits: {{Heave: 3 deg}}",
        "limits.Heave",
    ),
    "no unit": (
        "data: {data}\ngrid: {{heading: 1, hs: 1, tp: 8}}\nlimits: {{Roll: 3}}",
        "limits.Roll",
    ),
    "unknown dof": (
        "data: {data}\ngrid: {{heading: 1, hs: 1, tp: 8}}\nlimits: {{Rol: 3 deg}}",
        "limits.Rol",
    ),
    "unknown axis": ("data: {data}\ngrid: {{heading: 1, hs: 1, tp: 8, speed: 3}}", "grid.speed"),
    "seed in rao": ("data: {data}\ngrid: {{heading: 1, hs: 1, tp: 8, seed: [1, 2]}}", "seed"),
    "bad statistic": (
        "data: {data}\ngrid: {{heading: 1, hs: 1, tp: 8}}\nlimits: {{Roll: {{mean: 2 deg}}}}",
        "limits.Roll.mean",
    ),
    "yaml": ("data: {data}\ngrid: [heading: 1", "line"),
    # keys of the other analysis (the audit's rao_model.yaml and sim_nomega.yaml)
    "model in rao": ("data: {data}\nmodel: {data}\ngrid: {{heading: 1, hs: 1, tp: 8}}", "model"),
    "dt in rao": ("data: {data}\ndt: 0.5\ngrid: {{heading: 1, hs: 1, tp: 8}}", "dt"),
    "components in rao": (
        "data: {data}\ncomponents: 10\ngrid: {{heading: 1, hs: 1, tp: 8}}",
        "components",
    ),
    "n_omega in simulate": (
        "data: {data}\nanalysis: simulate\nn_omega: 5\ngrid: {{heading: 1, hs: 1, tp: 8}}",
        "n_omega",
    ),
    "omega_max in simulate": (
        "data: {data}\nanalysis: simulate\nomega_max: 0.3\ngrid: {{heading: 1, hs: 1, tp: 8}}",
        "omega_max",
    ),
    # the equation of motion's keys, checked as the CLI checks --mass & co.
    "mass without radii": ("data: {data}\nmass: 1e7\ngrid: {{heading: 1, hs: 1, tp: 8}}", "mass"),
    "matrix and mass": (
        "data: {data}\ninertia_matrix: [[1]]\nmass: 1e7\nradii_of_gyration: [1, 2, 3]\n"
        "grid: {{heading: 1, hs: 1, tp: 8}}",
        "inertia_matrix",
    ),
    "radii not three": (
        "data: {data}\nradii_of_gyration: [1, 2]\ngrid: {{heading: 1, hs: 1, tp: 8}}",
        "radii_of_gyration",
    ),
    "negative rho": ("data: {data}\nrho: -1025\ngrid: {{heading: 1, hs: 1, tp: 8}}", "rho"),
    "repeated stiffness": (
        "data: {data}\nexternal_stiffness: [[Surge, Surge, 1e5], [Surge, Surge, 2e5]]\n"
        "grid: {{heading: 1, hs: 1, tp: 8}}",
        "external_stiffness",
    ),
    "restoring yes or no": (
        "data: {data}\nrestoring_includes_weight: maybe\ngrid: {{heading: 1, hs: 1, tp: 8}}",
        "restoring_includes_weight",
    ),
}


@pytest.mark.parametrize("name", list(BAD_STUDIES))
def test_bad_study_files_name_the_file_and_key(name, tmp_path):
    text, key = BAD_STUDIES[name]
    path = tmp_path / "study.yaml"
    path.write_text(text.format(data=TANKER), encoding="utf-8")
    with pytest.raises(StudyError) as info:
        load_study(path)
    message = str(info.value)
    assert str(path) in message and key in message, message
    if name.endswith((" in rao", " in simulate")) and name != "seed in rao":  # other analysis
        assert f"not to this study's analysis: {'rao' if 'rao' in name else 'simulate'}" in message
    result = CliRunner().invoke(main, ["batch", str(path), "-o", str(tmp_path / "r.nc")])
    assert result.exit_code == 2
    assert key in result.output and len(result.output.strip().splitlines()) == 1, result.output


def test_limit_on_a_dof_the_data_lack(tmp_path):
    """Checked against the data when the study runs (before any cluster is started)."""
    ds = cummins.select_dofs(cummins.demo_dataset(), ["Heave", "Pitch"])
    cummins.write(ds, tmp_path / "two_dofs.nc")
    study = Study(
        data=tmp_path / "two_dofs.nc",
        grid={"heading": 180, "hs": 2, "tp": 8},
        limits={"Roll": "2 deg"},
        source=tmp_path / "s.yaml",
    )
    with pytest.raises(StudyError, match=r"limits\.Roll: the data have no DOF 'Roll'"):
        prepare_study(study)


@pytest.mark.parametrize(
    ("changes", "key"),
    [
        ({"analysis": "rao", "n_omega": 1e9}, "n_omega"),  # issue 31: grew to 16 GB
        ({"analysis": "simulate", "components": 1e9}, "components"),
        ({"analysis": "simulate", "duration": 1e12}, "duration"),
    ],
)
def test_a_study_too_large_for_memory_is_refused_before_anything_is_allocated(
    changes, key, tmp_path, monkeypatch
):
    """A CLI run of the same study says so in one line, exit status 2 (no Dask needed:
    the size is checked as the study is prepared, before any cluster starts)."""
    import tracemalloc

    monkeypatch.setenv("CUMMINS_MEMORY_LIMIT", "1")  # 1 GiB: far from any of these
    study = Study(
        data=TANKER, grid={"heading": 180, "hs": 2, "tp": 8}, source=tmp_path / "s.yaml", **changes
    )
    tracemalloc.start()
    try:
        with pytest.raises(ArgumentError, match=rf"s\.yaml: {key}.* more than the 1 GiB"):
            prepare_study(study)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 200e6, peak  # the data read, not the request


def test_zarr_results(fd_run, tmp_path):
    """The same results through a Zarr store (zarr is in the test extra: never skipped)."""
    from cummins.studies.batch import write_results

    write_results(fd_run.results, tmp_path / "results.zarr")
    back = load_results(tmp_path / "results.zarr")
    xr.testing.assert_identical(back, load_results(fd_run.output))


def test_existing_output_is_not_overwritten(fd_run):
    with pytest.raises(OutputExistsError):
        run_study(_fd_study(), fd_run.output)


def test_cli_example_study(two_workers, tmp_path, monkeypatch):
    """``--example`` writes a study that runs; the tables are printed; no overwriting."""
    monkeypatch.chdir(tmp_path)
    runner = CliRunner()
    result = runner.invoke(
        main,
        ["batch", "--example", "study.yaml", "-o", "results.nc", "--scheduler", two_workers],
    )
    assert result.exit_code == 0, result.output
    assert "60 cases computed" in result.output and "Operability" in result.output
    assert "Limiting Hs [m]" in result.output
    res = load_results("results.nc")
    assert dict(res.sizes) == {"heading": 3, "hs": 4, "tp": 5, "dof": 6, "criterion": 3}
    again = runner.invoke(main, ["batch", "study.yaml", "-o", "results.nc"])
    assert again.exit_code == 2 and "exists" in again.output
    study = json.loads(res.attrs["study"])
    assert study["limits"][0] == {"dof": "Roll", "statistic": "significant", "limit": "4 deg"}


def test_without_dask_import_works_and_batch_says_what_to_install(tmp_path):
    """cummins and its CLI import without Dask; ``cummins batch`` then fails in one line."""
    (tmp_path / "study.yaml").write_text(
        f"data: {TANKER}\ngrid: {{heading: 180, hs: 1, tp: 8}}\n", encoding="utf-8"
    )
    code = textwrap.dedent(
        """\
        import sys
        sys.modules["dask"] = sys.modules["distributed"] = None
        import cummins, cummins.studies.batch, cummins.cli.html_report, cummins.studies.operability
        from click.testing import CliRunner
        from cummins.cli import main
        assert CliRunner().invoke(main, ["--help"]).exit_code == 0
        r = CliRunner().invoke(main, ["batch", "study.yaml", "-o", "r.nc"])
        print(r.exit_code, r.output.strip())
        """
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, check=True
    )
    assert out.stdout.startswith("1 error:"), out.stdout + out.stderr  # not a usage error
    assert "pip install cummins[dask]" in out.stdout


def test_limit_parsing():
    study = Study(
        data=TANKER,
        grid={"heading": [0, 90], "hs": 2, "tp": [8, 10]},
        limits={"Roll": {"significant": "0.05 rad", "max": "6 deg"}, "Heave": "50 cm"},
    )
    assert study.limits == (
        Limit("Roll", "significant", 0.05, "0.05 rad"),
        Limit("Roll", "max", math.radians(6), "6 deg"),
        Limit("Heave", "significant", 0.5, "50 cm"),
    )
    assert study.dims == ("heading", "hs", "tp") and len(study.all_cases) == 4
    assert [c.tp for c in study.all_cases] == [8, 10, 8, 10]


# ------------------------------------------------- a failed radiation model (audit item 1)

RM3 = ("WEC-Sim", "wamit_RM3_2body", "rm3.out")
#: WEC-Sim's RM3 set-up (corpus README): rho 1000, the bodies' masses rho x volume,
#: centres of gravity and radii of gyration of their inertias about them
RM3_KEYS = textwrap.dedent(
    """\
    rho: 1000
    mass: [725833, 886687]
    center_of_gravity: [[0, 0, -0.72], [0, 0, -21.29]]
    radii_of_gyration: [[5.367, 5.418, 7.148], [10.319, 10.319, 5.674]]
    """
)


def _rm3_study(folder, data, model=None) -> str:
    path = folder / ("model.yaml" if model else "fitted.yaml")
    path.write_text(
        f"data: {data}\n"
        + (f"model: {model}\n" if model else "")
        + RM3_KEYS
        + "analysis: simulate\nduration: 20\ndt: 0.1\ncomponents: 30\n"
        + "grid: {heading: [0], hs: [2.5], tp: [8], seed: [3]}\n",
        encoding="utf-8",
    )
    return str(path)


def test_a_failed_model_is_said_in_one_line_and_recorded(two_workers, corpus, tmp_path):
    """The RM3's fit misses its targets (its data are not causal: the R² of K(t) of two
    DOFs below 0.9 once its residues are refined on its motions, 0.40 %; exit 3 of
    `cummins fit`): `batch` with that model file, or fitting one itself, says
    so in `simulate`'s one line, records the failures, order and motion error in the
    results, and ends as `simulate` does on such a model (exit 0, the cases run)."""
    from cummins.cli.failed_model import ATTRIBUTE, model_failures
    from cummins.mass_properties import with_inertia

    data = corpus.joinpath(*RM3)
    ds = with_inertia(
        cummins.read(data, rho=1000.0),
        mass=[725833, 886687],
        center_of_gravity=[[0, 0, -0.72], [0, 0, -21.29]],
        radii_of_gyration=[[5.367, 5.418, 7.148], [10.319, 10.319, 5.674]],
    )
    model = cummins.fit_radiation(ds)
    failures = list(model.attrs["failures"])
    assert failures  # the premise
    model.save(tmp_path / "rm3_model.nc")
    for study, kind in (
        (_rm3_study(tmp_path, data, "rm3_model.nc"), "this model missed its fit targets"),
        (_rm3_study(tmp_path, data), "the radiation model fitted to these data missed"),
    ):
        out = tmp_path / f"{kind[:4]}.nc"
        result = CliRunner().invoke(
            main, ["batch", study, "-o", str(out), "--scheduler", two_workers]
        )
        assert result.exit_code == 0, result.output
        lines = [line for line in result.output.splitlines() if "missed its" in line]
        assert len(lines) == 1, result.output
        source = "rm3_model.nc" if "this model" in kind else "rm3.out"
        assert lines[0].startswith(f"warning: {source}: {kind}"), lines[0]
        said = failures[0].split(" (")[0]  # the R² of K(t) of the float's pitch measured
        assert said in lines[0] and "results inherit it" in lines[0]
        attrs = load_results(out).attrs
        assert attrs[ATTRIBUTE].splitlines() == failures  # as `simulate`'s run file
        assert model_failures(attrs) == failures
        assert attrs["radiation_model_order"] == model.total_order
        assert attrs["radiation_model_motion_error"] == pytest.approx(
            model.attrs["motion_error"], rel=1e-12
        )
        assert not parts_folder(out).exists()


# ------------------------------------- the equation of motion in the study (audit item 2)

SPAR = ("WEIS", "ss_fitting_OC3_spar", "spar.1")
#: the OC3 spar with its turbine (ρ∇ 8.23e6 kg; the files hold no inertia), and moorings
SPAR_KEYS = {
    "rho": 1025.0,
    "g": 9.80665,
    "mass": 8066048.0,
    "center_of_gravity": [0.0, 0.0, -78.0],
    "radii_of_gyration": [23.8, 23.8, 4.69],
    "external_stiffness": [["Surge", "Surge", 41180.0], ["Sway", "Sway", 41180.0]],
    "external_damping": [["Heave", "Heave", 1e5]],
}


def test_a_study_without_inertia_is_refused_before_dask_naming_the_keys(corpus, tmp_path):
    """The audit's spar_raw.yaml: one line naming the study keys to add, exit status 1
    (the data lack it: not a bad option), no Dask traceback and no empty parts folder."""
    study = tmp_path / "spar_raw.yaml"
    study.write_text(
        f"data: {corpus.joinpath(*SPAR)}\ngrid: {{heading: [180], hs: [2], tp: [10]}}\n",
        encoding="utf-8",
    )
    out = tmp_path / "r.nc"
    result = CliRunner().invoke(main, ["batch", str(study), "-o", str(out), "--workers", "1"])
    assert result.exit_code == 1, result.output
    (line,) = [x for x in result.output.splitlines() if x.startswith("error:")]
    assert "spar.1" in line and "no 'inertia_matrix'" in line, line
    assert (
        "add to spar_raw.yaml the study keys mass, center_of_gravity and radii_of_gyration" in line
    )
    assert "Compute Failed" not in result.output and "command line" not in result.output
    assert not out.exists() and not parts_folder(out).exists()
    # a key naming a DOF the data lack: the key, before Dask too
    bad = Study(
        data=corpus.joinpath(*SPAR),
        grid={"heading": 180, "hs": 2, "tp": 10},
        **{**SPAR_KEYS, "external_damping": [["Heave", "Hevae", 1e5]]},
        source=study,
    )
    with pytest.raises(
        ArgumentError, match=r"spar_raw\.yaml: external_damping: unknown DOF 'Hevae'"
    ):
        prepare_study(bad)


def test_study_keys_give_the_inertia_and_external_terms_as_the_cli_options(corpus, tmp_path):
    """mass, centre of gravity, radii of gyration, moorings, a damper, rho and g: the
    data the cases use are those the functions behind `--mass` & co. give, and the
    rigid-body inertia is m (r² + z_G²) about the waterline's origin (the parallel
    axes); the moorings change the surge statistics."""
    from cummins.mass_properties import with_external_terms, with_inertia

    study = Study(
        data=corpus.joinpath(*SPAR),
        grid={"heading": 180, "hs": 2, "tp": 10},
        n_omega=100,
        **SPAR_KEYS,
    )
    context, digest = prepare_study(study)
    m, z, (rxx, ryy, rzz) = 8066048.0, -78.0, SPAR_KEYS["radii_of_gyration"]
    inertia = context.ds.inertia_matrix.values
    np.testing.assert_allclose(
        np.diag(inertia),
        [m, m, m, m * (rxx**2 + z**2), m * (ryy**2 + z**2), m * rzz**2],
        rtol=1e-12,
    )
    reference = with_external_terms(
        with_inertia(
            cummins.read(corpus.joinpath(*SPAR), rho=1025.0, g=9.80665),
            mass=m,
            center_of_gravity=[0, 0, z],
            radii_of_gyration=[rxx, ryy, rzz],
        ),
        stiffness={("Surge", "Surge"): 41180.0, ("Sway", "Sway"): 41180.0},
        damping={("Heave", "Heave"): 1e5},
    )
    for name in (
        "inertia_matrix",
        "hydrostatic_stiffness",
        "additional_stiffness",
        "additional_damping",
    ):
        xr.testing.assert_equal(context.ds[name], reference[name])
    assert context.ds.attrs["rho"] == 1025.0 and context.ds.attrs["g"] == 9.80665
    # the same study without the moorings is other data: other case ids, other results
    free = Study(**{**study.__dict__, "external_stiffness": ()})
    assert prepare_study(free)[1] != digest
    case = study.all_cases[0]
    moored = case_statistics(context, case)["significant_amplitude"]
    unmoored = case_statistics(prepare_study(free)[0], case)["significant_amplitude"]
    assert abs(moored[0] / unmoored[0] - 1) > 0.02  # 6 %: the surge resonance they add


def test_no_empty_parts_folder_after_an_unreachable_scheduler(corpus, tmp_path):
    import dask

    study = tmp_path / "s.yaml"
    study.write_text(
        f"data: {TANKER}\ngrid: {{heading: [180], hs: [2], tp: [10]}}\n", encoding="utf-8"
    )
    out = tmp_path / "r.nc"
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}):
        result = CliRunner().invoke(
            main, ["batch", str(study), "-o", str(out), "--scheduler", "tcp://127.0.0.1:9"]
        )
    assert result.exit_code != 0 and "127.0.0.1:9" in result.output, result.output
    assert not parts_folder(out).exists()
