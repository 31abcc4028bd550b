"""What the commands print reads right anywhere: in a pipe, a log or CI (no terminal)
the tables show every number in full, the help lists every format read, and the symbols
and column names say what the result is."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

import cummins


def _run(*args: str, cwd) -> str:
    """``python -m cummins ARGS`` with its output in a pipe (not a terminal), as a log or CI
    gets it: no COLUMNS, no terminal size to take."""
    env = {k: v for k, v in os.environ.items() if k not in ("COLUMNS", "LINES")}
    run = subprocess.run(
        [sys.executable, "-m", "cummins", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
        stdin=subprocess.DEVNULL,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    return run.stdout


@pytest.fixture
def tanker_deep(tmp_path):
    """The bundled tanker in a folder whose path is wider than 80 columns."""
    folder = tmp_path / ("a_folder_with_a_long_name_" * 3) / "tanker"
    folder.mkdir(parents=True)
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, folder / f.name)
    return folder / "tanker.1"


def test_info_in_a_pipe_names_the_whole_file(tanker_deep, tmp_path):
    out = _run("info", str(tanker_deep), cwd=tmp_path)
    assert "…" not in out
    row = next(line for line in out.splitlines() if line.startswith("file"))
    assert str(tanker_deep) in row and "(wamit)" in row


def test_info_of_a_converted_file_names_the_file_read(tmp_path):
    """`info x.h5` (or .nc) of a file convert wrote named only the solver's file its
    data came from ("file tanker.1 (wamit)"), not the file read, nor its format."""
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, tmp_path / f.name)

    def row(name):
        out = _run("info", name, cwd=tmp_path)
        return " ".join(next(line for line in out.splitlines() if line.startswith("file")).split())

    for name, kind in (("t.nc", "netcdf"), ("t.h5", "bemio"), ("tanker.nc", "netcdf")):
        _run("convert", "tanker.1", name, cwd=tmp_path)
        assert row(name) == f"file {name} ({kind}): the data of tanker.1 (wamit)"
    # a file of the run itself names the run's file, as before
    assert row("tanker.3") == "file tanker.1 (wamit)"


def test_kernel_in_a_pipe_prints_every_number_in_full(tanker_deep, tmp_path):
    out = _run("kernel", str(tanker_deep), "-o", "K.nc", cwd=tmp_path)
    assert "…" not in out and "\x1b[" not in out  # full numbers, no spinner
    with xr.open_dataset(tmp_path / "K.nc", engine="h5netcdf") as f:
        k0 = f.retardation_function.isel(time=0).load()
    rows = {line.split("│")[1].strip(): line for line in out.splitlines() if "│" in line}
    for name in ("Surge", "Heave-Pitch", "Roll-Yaw", "Yaw"):
        a, _, b = name.partition("-")
        value = float(k0.sel(influenced_dof=a, radiating_dof=b or a))
        assert f"{value:.4g}" in rows[name], (name, rows[name])
    # the header too: the column that says how far K has decayed
    assert "K(t_max)/max|K|" in out


def test_fit_in_a_pipe_prints_the_r2_of_the_json_summary(tanker_deep, tmp_path):
    out = _run("fit", str(tanker_deep), "-o", "m.nc", "--json", "fit.json", cwd=tmp_path)
    assert "…" not in out
    summary = json.loads((tmp_path / "fit.json").read_text())
    labels = list(cummins.DOF_NAMES)
    rows = [line.split() for line in out.splitlines()]
    printed = {
        r[0]: r for r in rows if len(r) >= 7 and r[0].split("-")[0] in labels and r[1].isdigit()
    }
    assert len(printed) == sum(c["i"] <= c["j"] for c in summary["couplings"])
    for c in summary["couplings"]:
        if c["i"] > c["j"]:
            continue
        a, b = labels[c["i"] - 1], labels[c["j"] - 1]
        row = printed[a if a == b else f"{a}-{b}"]
        assert row[1] == str(c["order"])  # the poles column
        assert row[2] == f"{c['r2_added_mass']:.4f}" and row[3] == f"{c['r2_damping']:.4f}"
    # one meaning per column name: the fit counts poles, the reduction states
    assert re.search(r"coupling\s+poles\s+R² A", out)
    assert "\x1b[" not in out and "\r" not in out  # no progress bar in a pipe
    reduced = _run(
        "reduce", "m.nc", "-o", "s.nc", "--tol", "0.02", "--data", str(tanker_deep), cwd=tmp_path
    )
    assert "\x1b[" not in reduced and "\r" not in reduced  # no spinner in a pipe
    assert "None" not in reduced and "(lyapunov; R² against the data)" in reduced
    assert re.search(r"coupling\s*┃\s*states\s*┃", reduced), reduced
    # a pair of a block shows its block's states (as the model files hold them)
    states = re.search(r"│\s+Heave\s+│\s+(\d+) → (\d+)\s+│", reduced)
    heave = cummins.DOF_NAMES.index("Heave")
    (before,) = [
        b.order for b in cummins.RadiationModel.load(tmp_path / "m.nc").blocks if heave in b.dofs
    ]
    (after,) = [
        b.order for b in cummins.RadiationModel.load(tmp_path / "s.nc").blocks if heave in b.dofs
    ]
    assert states and (int(states[1]), int(states[2])) == (before, after)


def test_help_lists_every_format_read():
    from click.testing import CliRunner

    from cummins.cli import main

    runner = CliRunner()
    top = " ".join(runner.invoke(main, ["--help"]).output.split())
    option = " ".join(runner.invoke(main, ["convert", "--help"]).output.split())
    for name, fmt in cummins.FORMATS.items():
        assert " ".join(fmt.description.split()) in top, name
        assert f"{name} (" in option, name
    for words in ("HAMS", "BEMIO .h5"):
        assert words in top and words in option


def test_help_starts_without_the_library():
    """``cummins --help`` imports no SciPy, xarray or matplotlib (they take seconds)."""
    code = (
        "import sys\n"
        "from cummins.cli import main\n"
        "try:\n"
        "    main(['--help'])\n"
        "except SystemExit:\n"
        "    pass\n"
        "print(sorted(m for m in ('scipy', 'xarray', 'matplotlib', 'pandas') "
        "if m in sys.modules))"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip().splitlines()[-1] == "[]"
    assert np  # numpy is fine: the commands' options use it


def test_info_imports_no_scipy_it_does_not_use():
    """``cummins info`` reads and describes a run without SciPy's integrate, interpolate,
    optimize or signal (0.3 s of imports: the wave spectra, K(t)'s interpolation and the
    damping tail import them when they are used)."""
    code = (
        "import sys\n"
        "from cummins.cli import main\n"
        "try:\n"
        f"    main(['info', {str(cummins.demo_files() / 'tanker.1')!r}])\n"
        "except SystemExit:\n"
        "    pass\n"
        "heavy = ('scipy.integrate', 'scipy.interpolate', 'scipy.optimize', 'scipy.signal')\n"
        "print(sorted(m for m in heavy if m in sys.modules))"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip().splitlines()[-1] == "[]"


#: What ``cummins info`` of a WAMIT run has no use for: Dask (xarray would import
#: ``dask.array`` at its first Variable), the other formats' readers (detection asks every
#: format, by its detection module), h5py (a text file is no model file), SciPy's optimize.
NOT_FOR_INFO = (
    "dask",
    "cummins.io.nemoh.reader",
    "cummins.io.aqwa.lis",
    "cummins.io.aqwa.ah1",
    "cummins.io.mss.reader",
    "cummins.io.bemio.reader",
    "cummins.io.netcdf.reader",
    "h5py",
    "scipy.optimize",
)


def test_info_leaves_dask_and_the_other_readers_unimported():
    """``cummins info tanker.1`` with Dask installed imports none of :data:`NOT_FOR_INFO`,
    and leaves the process as it found it: Dask importable again (``batch`` in the same
    process runs on it), the garbage collector's thresholds restored (its objects frozen
    only at exit), and the run read the same as ``cummins.read`` (the same DOFs and
    frequencies printed)."""
    pytest.importorskip("dask")
    code = (
        "import atexit, gc, json, sys\n"
        "from cummins.cli import main\n"
        "before = gc.get_threshold()\n"
        "atexit.register(lambda: print('frozen at exit', gc.get_freeze_count() > 0))\n"
        f"main(['info', {str(cummins.demo_files() / 'tanker.1')!r}, '--json'], "
        "standalone_mode=False)\n"
        f"print(json.dumps(sorted(m for m in {NOT_FOR_INFO!r} if m in sys.modules)))\n"
        "print(gc.get_threshold() == before)\n"
        "from cummins.studies.batch import _dask\n"
        "print(_dask().Client is not None and 'dask' in sys.modules)\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    *output, imported, restored, distributed, frozen = run.stdout.strip().splitlines()
    assert json.loads(imported) == []
    assert restored == "True" and distributed == "True"
    assert frozen == "frozen at exit True"  # no collection over the whole heap at exit
    described = json.loads("\n".join(output))
    data = cummins.demo_dataset()
    assert described["dofs"] == [str(d) for d in data.influenced_dof.values]
    assert described["n_omega"] == data.sizes["omega"]


def test_fit_imports_no_dask(tmp_path):
    """``cummins fit`` (no Dask in its work) runs without xarray importing ``dask.array``
    (0.3 s), and writes the same model as ``fit_radiation`` in a process with Dask."""
    pytest.importorskip("dask")
    path = tmp_path / "m.nc"
    code = (
        "import sys\n"
        "from cummins.cli import main\n"
        f"main(['fit', {str(cummins.demo_files() / 'tanker.1')!r}, '-o', {str(path)!r}], "
        "standalone_mode=False)\n"
        "print(sorted(m for m in ('dask', 'dask.array', 'matplotlib') if m in sys.modules))"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip().splitlines()[-1] == "[]"
    model = cummins.RadiationModel.load(path)
    import dask  # noqa: F401  (xarray sees Dask here, as a user's script does)

    again = cummins.fit_radiation(cummins.demo_dataset())
    assert model.total_order == again.total_order
    np.testing.assert_array_equal(model.added_mass_inf, again.added_mass_inf)
    poles, expected = (np.sort_complex(np.linalg.eigvals(m.A)) for m in (model, again))
    np.testing.assert_allclose(poles, expected, rtol=1e-8)


def test_writing_a_file_asks_dask_nothing(tmp_path):
    """Writing a NetCDF file of in-memory data does not import ``dask.distributed``
    (xarray's default write lock asks dask which scheduler runs: a quarter of a second
    of every command that writes a file, when the ``[dask]`` extra is installed), and
    the file reads back the same."""
    pytest.importorskip("dask")
    path = tmp_path / "tanker.nc"
    code = (
        "import sys\n"
        "import cummins\n"
        f"cummins.write(cummins.demo_dataset(), {str(path)!r})\n"
        "print('distributed' in sys.modules)"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip().splitlines()[-1] == "False"
    written = cummins.read(path)
    data = cummins.demo_dataset()
    np.testing.assert_array_equal(written.radiation_damping.values, data.radiation_damping.values)


def test_info_describes_the_model_files_of_fit_and_fit_excitation(tmp_path):
    """``cummins info`` on a model file says what it is — its DOFs, states, stability, the
    data it was fitted to and its failures — rather than "unrecognised file format"."""
    from click.testing import CliRunner

    from cummins.cli import main
    from cummins.excitation_model import fit_excitation

    ds = cummins.demo_dataset()
    radiation = cummins.fit_radiation(ds)
    radiation.save(tmp_path / "model.nc")
    run = CliRunner().invoke(main, ["info", str(tmp_path / "model.nc"), "--json"])
    assert run.exit_code == 0, run.output
    told = json.loads(run.output)
    assert told["kind"].startswith("radiation model")
    assert told["states"] == radiation.total_order and told["passive"] is True
    assert told["dofs"].split(", ") == list(radiation.dofs)
    assert told["fitted_to"].endswith("tanker.1") and told["failures"] == []
    run = CliRunner().invoke(main, ["info", str(tmp_path / "model.nc"), "--rho", "1000"])
    assert run.exit_code == 2 and "is a model file, not solver data: --rho" in run.output
    excitation = fit_excitation(ds, [np.pi])
    excitation.save(tmp_path / "exc.nc")
    run = CliRunner().invoke(main, ["info", str(tmp_path / "exc.nc")])
    assert run.exit_code == 0, run.output
    assert "wave excitation model" in run.output
    assert f"states  {excitation.total_order}" in run.output
    for failure in excitation.attrs.get("failures", []):
        assert f"failure: {failure}" in run.output


def test_the_demo_marks_a_missed_target_not_with_a_check_mark(monkeypatch, tmp_path):
    from click.testing import CliRunner

    import cummins.cli.demo as demo
    from cummins.cli import main

    steps = [
        demo.DemoStep("fit", "42 states, passive"),
        demo.DemoStep("reduce", "smallest diagonal R² 0.7862, below the target", ok=False),
    ]
    monkeypatch.setattr(demo, "run_demo", lambda *args, **kwargs: steps)
    run = CliRunner().invoke(main, ["demo", "-o", str(tmp_path / "d")])
    assert run.exit_code == demo.DEMO_MISSED == 3
    out = run.output
    lines = out.splitlines()
    assert any(line.startswith("✓ fit") for line in lines)
    assert any(line.startswith("! reduce") for line in lines)
    assert not any(line.startswith("✓ reduce") for line in lines)
    assert "1 step(s) did not reach their targets: reduce" in out


def test_the_demo_reduction_keeps_the_motions_within_its_tolerance(tmp_path):
    """The demo's reduction of the fit to 1 % of the data's motion RAOs: fewer states,
    passive, and the motion error it reports recomputed from the saved model."""
    import cummins.cli.demo as demo
    from cummins.radiation.fit.scorecard import motion_rao_error
    from cummins.radiation.model import RadiationModel

    ds = cummins.demo_dataset()
    model = cummins.fit_radiation(ds)
    step = demo._reduce_step(ds, model, tmp_path, False)
    reduced = RadiationModel.load(tmp_path / "tanker_reduced.nc")
    assert step.ok and reduced.total_order < model.total_order
    told = float(re.search(r"motion RAOs within ([\d.]+)%", step.detail)[1]) / 100
    assert told <= 0.01
    assert motion_rao_error(ds, reduced).error == pytest.approx(told, abs=1e-4)
