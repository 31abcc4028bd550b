"""Every command in the README runs, and CI runs the README's test command."""

from __future__ import annotations

import re
import shlex
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", README, flags=re.S)


def test_two_setup_commands_and_ci():
    setup = [line for block in _blocks("bash") for line in block.splitlines() if line.strip()]
    assert len(setup) == 2, setup
    assert setup[0].endswith("cummins demo")
    assert "pytest" in setup[1] and ".[test" in setup[1]
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert setup[1] in ci.splitlines(), "the CI script must run the README's test command"


def _console_commands() -> list[str]:
    return [
        line[2:].strip()
        for block in _blocks("console")
        for line in block.splitlines()
        if line.startswith("$ cummins")
    ]


@pytest.fixture
def workdir(tmp_path, shared_data, monkeypatch):
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, tmp_path / f.name)
    shutil.copytree(shared_data / "mss" / "supply", tmp_path / "supply")
    shutil.copy(cummins.demo_files().parent / "s175" / "s175.mat", tmp_path / "s175.mat")
    for f in (shared_data / "corpus" / "WEC-Sim" / "wamit_RM3_2body").glob("rm3.*"):
        shutil.copy(f, tmp_path / f.name)  # the README's wave-energy converter
    semi = shared_data / "corpus" / "WEIS" / "ss_fitting_OC4_semi"
    for suffix in (".1", ".hst", ".12d", ".12s"):  # the OC4 semi's WAMIT run with its QTFs
        shutil.copy(semi / f"marin_semi{suffix}", tmp_path / f"marin_semi{suffix}")
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.mark.parametrize("command", _console_commands())
def test_readme_console_command(command, workdir):
    if " bem " in f" {command} ":
        pytest.importorskip("capytaine")
    args = shlex.split(command)[1:]
    # a command that reads a file another README command writes runs after that one
    for earlier in _console_commands():
        made = shlex.split(earlier)[1:]
        if made[0] != args[0] and any(f in args[1:2] for f in _outputs(made)):
            first = CliRunner().invoke(main, made, catch_exceptions=False)
            assert first.exit_code == 0, f"{earlier}\n{first.output}"
    result = CliRunner().invoke(main, args, catch_exceptions=False)
    assert result.exit_code == 0, f"{command}\n{result.output}"
    _read_back(args, workdir)


def _outputs(args: list[str]) -> list[str]:
    return [args[k + 1] for k, a in enumerate(args[:-1]) if a in ("-o", "--output")]


def _option(args: list[str], name: str) -> str | None:
    return args[args.index(name) + 1] if name in args[:-1] else None


def _read_back(args: list[str], workdir: Path) -> None:
    """What a README command wrote reads back as what it claims to be."""
    import json

    import numpy as np
    import xarray as xr

    from cummins.radiation.model import RadiationModel
    from cummins.seakeeping.frequency_domain import load_rao

    command = args[0]
    outputs = [workdir / f for f in _outputs(args)]
    for path in outputs:
        assert path.exists() and (path.is_dir() or path.stat().st_size > 0), path
    for flag in ("--json",):
        if _option(args, flag):
            json.loads((workdir / _option(args, flag)).read_text(encoding="utf-8"))
    for flag in ("--plot", "--report"):
        if _option(args, flag):
            folder = workdir / _option(args, flag)
            pngs = [folder] if folder.suffix == ".png" else list(folder.glob("*.png"))
            assert pngs and all(p.stat().st_size > 10_000 for p in pngs), folder
    if command == "convert":
        back = cummins.read(workdir / args[2])
        source = cummins.read(workdir / args[1])
        # the same body: heave added mass does not depend on the axes or the reference point
        heave = {"influenced_dof": "Heave", "radiating_dof": "Heave"}
        np.testing.assert_allclose(
            back.added_mass.sel(heave).values, source.added_mass.sel(heave).values, rtol=1e-6
        )
    elif command in ("fit", "reduce"):
        model = RadiationModel.load(outputs[0])
        assert model.is_stable()
        if command == "reduce" and _option(args, "--order"):
            assert model.total_order <= int(_option(args, "--order"))
        if _option(args, "--openfast"):
            from cummins.io.openfast import read_openfast_ss

            assert read_openfast_ss(workdir / _option(args, "--openfast")).n_states > 0
        if _option(args, "--mss"):
            from cummins.io.mss_abc import read_mss_abc

            assert read_mss_abc(workdir / _option(args, "--mss")).total_order > 0
    elif command == "rao":
        rao = load_rao(outputs[0])
        assert set(rao.dims) == {"omega", "wave_direction", "dof"}
        if _option(args, "--headings"):
            given = args[args.index("--headings") + 1 :]
            count = next((k for k, a in enumerate(given) if a.startswith("-")), len(given))
            assert rao.sizes["wave_direction"] == count
    elif command == "simulate":
        with xr.open_dataset(outputs[0], engine="h5netcdf") as run:
            duration = float(_option(args, "--duration"))
            assert run.time.values[-1] == np.float64(duration)
            assert np.all(np.isfinite(run.motion.values))
    elif command in ("kernel", "lf-model", "batch", "bem"):
        if outputs[0].suffix == ".nc":
            with xr.open_dataset(outputs[0], engine="h5netcdf") as ds:
                assert len(ds.data_vars) > 0
    elif command == "report":
        text = outputs[0].read_text(encoding="utf-8")
        assert text.lstrip().lower().startswith("<!doctype html") and "<img" in text
    elif command == "dp-demo":
        with xr.open_dataset(outputs[0] / "run.nc", engine="h5netcdf") as run:
            assert "eta" in run


def test_readme_python_block(workdir):
    """The README's Python blocks run with every warning an error: what they show a user
    raise none (a warning there would be the first thing a user sees)."""
    import warnings

    blocks = _blocks("python")
    assert blocks
    for code in blocks:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            exec(compile(code, "README.md", "exec"), {})
    assert (workdir / "tanker_at_cg.nc").is_file()
