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


def _outputs(args: list[str]) -> list[str]:
    return [args[k + 1] for k, a in enumerate(args[:-1]) if a in ("-o", "--output")]


def test_readme_python_block(workdir):
    (code,) = _blocks("python")
    exec(compile(code, "README.md", "exec"), {})
    assert (workdir / "tanker_at_cg.nc").is_file()
