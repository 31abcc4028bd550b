"""Every command and Python block of the README and of the user guide runs, and CI runs
the README's test command.

The pages are read in order: the README, then the guide (``docs/guide/*.md`` in the
order of its contents) and the notes of ``docs/`` that hold ``$ cummins`` lines. Every
distinct ``$ cummins …`` line of their console blocks (a trailing backslash continues
it) runs once, in a temporary folder holding the files the pages name (the ``workdir``
fixture); a command that reads a file another command writes first runs the latest
command before it that writes it — in the README for the README's tour, in the guide and
the notes for theirs — and what each command wrote reads back as what it claims to be.
The Python blocks of a page run one after the other in one namespace, in that folder,
with every warning an error.
"""

from __future__ import annotations

import re
import shlex
import shutil
from pathlib import Path
from typing import NamedTuple

import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main

ROOT = Path(__file__).resolve().parents[1]
GUIDE = ROOT / "docs" / "guide"


def _blocks(path: Path, language: str) -> list[str]:
    text = path.read_text(encoding="utf-8")
    return re.findall(rf"```{language}\n(.*?)```", text, flags=re.S)


def _guide_pages() -> list[Path]:
    """The guide's pages in the order of its contents (``docs/guide/index.md``)."""
    index = (GUIDE / "index.md").read_text(encoding="utf-8")
    toctree = re.search(r"```\{toctree\}\n(.*?)```", index, flags=re.S).group(1)
    names = [line.strip() for line in toctree.splitlines() if line.strip()]
    return [GUIDE / f"{name}.md" for name in names if not name.startswith(":")]


def _notes() -> list[Path]:
    """The notes of ``docs/`` whose console blocks hold ``$ cummins`` lines."""
    notes = sorted((ROOT / "docs").glob("*.md"))
    return [p for p in notes if any("$ cummins" in b for b in _blocks(p, "console"))]


#: The documents in the order a reader takes them, in groups: a command reads what an
#: earlier command of its own group writes (the README's tour stands alone).
GROUPS = ((ROOT / "README.md",), (*_guide_pages(), *_notes()))


class Command(NamedTuple):
    page: str  # the document, relative to the repository
    group: int
    position: int  # order within the group
    args: tuple[str, ...]  # after ``cummins``


def _console_lines(block: str) -> list[str]:
    lines = block.replace("\\\n", " ").splitlines()
    return [line[2:].strip() for line in lines if line.startswith("$ cummins")]


def _commands() -> list[Command]:
    commands = []
    for group, documents in enumerate(GROUPS):
        position = 0
        for path in documents:
            for block in _blocks(path, "console"):
                for line in _console_lines(block):
                    args = tuple(shlex.split(line, comments=True)[1:])
                    page = str(path.relative_to(ROOT))
                    commands.append(Command(page, group, position, args))
                    position += 1
    return commands


COMMANDS = _commands()


def _key(args: tuple[str, ...]) -> tuple[str, ...]:
    """A command without ``--force`` (the guide re-runs the tour's commands with it)."""
    return tuple(a for a in args if a != "--force")


#: each command once, where it first appears (the README's tour repeats the guide's)
DISTINCT = list({_key(c.args): c for c in reversed(COMMANDS)}.values())[::-1]


def test_two_setup_commands_and_ci():
    setup = [
        line
        for block in _blocks(ROOT / "README.md", "bash")
        for line in block.splitlines()
        if line.strip()
    ]
    assert len(setup) == 2, setup
    assert setup[0].endswith("cummins demo")
    assert "pytest" in setup[1] and ".[test" in setup[1]
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert setup[1] in ci.splitlines(), "the CI script must run the README's test command"


def test_the_pages_are_read():
    """The scan is not vacuous: the README's tour, every stage of the guide and the
    OpenFAST note hold commands, and the README repeats the guide rather than adding."""
    pages = {c.page for c in COMMANDS}
    for page in ("README.md", "docs/guide/fit.md", "docs/guide/wec.md", "docs/openfast_wecsim.md"):
        assert page in pages, page
    assert len(DISTINCT) >= 40
    guide = {_key(c.args) for c in COMMANDS if c.group == 1}
    tour = [_key(c.args) for c in COMMANDS if c.group == 0]
    assert 10 <= len(tour) <= 16
    assert [a for a in tour if a not in guide] == [("demo", "-o", "cummins-demo")]


def _study_files() -> dict[str, str]:
    """The YAML blocks of the pages that open with their file's name (``# rm3_sweep.yaml``):
    a reader saves them under that name before the commands that read them."""
    out = {}
    for path in (p for group in GROUPS for p in group):
        for block in _blocks(path, "yaml"):
            first = block.splitlines()[0] if block.strip() else ""
            found = re.fullmatch(r"# (\S+\.ya?ml)", first.strip())
            if found:
                out[found.group(1)] = block
    return out


STUDY_FILES = _study_files()


def test_study_files_are_found():
    """The guide's PTO-damping sweep is a study file the tests write and run."""
    assert "rm3_sweep.yaml" in STUDY_FILES
    assert any(c.args[:2] == ("batch", "rm3_sweep.yaml") for c in COMMANDS)


#: the options that name a file or folder a command writes (refused when it exists)
WRITES = ("-o", "--output", "--plot", "--json", "--report", "--openfast", "--mss")


def test_the_tour_runs_in_one_folder():
    """A reader who follows the README and then the guide and the notes in one folder
    never meets "exists; refusing to overwrite": a command that writes what an earlier
    one wrote says --force (the guide re-runs the tour's commands on purpose)."""
    written: dict[str, Command] = {}
    clashes = []
    for command in COMMANDS:
        args = command.args
        names = [args[k + 1] for k, a in enumerate(args[:-1]) if a in WRITES]
        if args[0] == "convert":
            names.append(args[2])
        for name in names:
            if name in written and "--force" not in args:
                first = written[name]
                clashes.append(f"{command.page}: {name} written before by {first.page}")
            written.setdefault(name, command)
    assert not clashes, "\n".join(clashes)


@pytest.fixture
def workdir(tmp_path, shared_data, monkeypatch):
    import numpy as np

    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, tmp_path / f.name)
    shutil.copytree(shared_data / "mss" / "supply", tmp_path / "supply")
    shutil.copy(cummins.demo_files().parent / "s175" / "s175.mat", tmp_path / "s175.mat")
    for f in (shared_data / "corpus" / "WEC-Sim" / "wamit_RM3_2body").glob("rm3.*"):
        shutil.copy(f, tmp_path / f.name)  # the wave-energy converter
    oswec = shared_data / "corpus" / "WEC-Sim" / "wamit_OSWEC_2015_with_bemio_h5" / "oswec.out"
    shutil.copy(oswec, tmp_path / "oswec.out")  # the hinged flap
    weis = shared_data / "corpus" / "WEIS"
    for suffix in (".1", ".hst", ".12d", ".12s"):  # the OC4 semi's WAMIT run with its QTFs
        shutil.copy(weis / "ss_fitting_OC4_semi" / f"marin_semi{suffix}", tmp_path)
    for suffix in (".1", ".3", ".hst", ".ss"):  # the OC3 spar of the OpenFAST note
        shutil.copy(weis / "ss_fitting_OC3_spar" / f"spar{suffix}", tmp_path)
    shutil.copy(ROOT / "tests" / "data" / "semisub_capytaine.nc", tmp_path / "semisub.nc")
    t = np.arange(0.0, 600.0, 0.5)  # a wave probe's record, 10 minutes
    eta = 0.8 * np.cos(0.6 * t) + 0.5 * np.cos(0.9 * t + 1.0) + 0.3 * np.cos(0.45 * t + 2.0)
    rows = "".join(f"{a:g}, {b:.6f}\n" for a, b in zip(t, eta, strict=True))
    (tmp_path / "probe.csv").write_text("time [s], wave elevation [m]\n" + rows)
    for name, text in STUDY_FILES.items():  # the study files the pages show
        (tmp_path / name).write_text(text, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _outputs(args: tuple[str, ...]) -> list[str]:
    written = [args[k + 1] for k, a in enumerate(args[:-1]) if a in ("-o", "--output")]
    if args[0] == "convert":
        written.append(args[2])
    return written


def _prerequisites(command: Command, done: set[tuple[str, ...]]) -> list[Command]:
    """The commands to run before ``command``: for each file it reads that a command of
    its group writes, the latest such command before it (and what that one needs)."""
    chain = []
    for name in command.args[1:]:
        if name in _outputs(command.args):
            continue
        writers = [
            c
            for c in COMMANDS
            if c.group == command.group
            and c.position < command.position
            and name in _outputs(c.args)
        ]
        if writers and writers[-1].args not in done:
            done.add(writers[-1].args)
            chain += [*_prerequisites(writers[-1], done), writers[-1]]
    return chain


#: Numbers the pages quote from what a command prints: per command (as the pages write
#: it, without --force), (page, pattern of its output, the page's sentence built from the
#: pattern's groups). A page that drifts from its command fails here.
QUOTED = {
    "fit tanker.1 -o tanker_model.nc --json fit.json --plot fit-plots": [
        ("README.md", r"total order (\d+),", "two blocks of common poles, {0} states"),
    ],
    "reduce tanker_model.nc -o tanker_model_1pc.nc --motion-tol 0.01 --data tanker.1": [
        (
            "docs/guide/reduce.md",
            r"(\d+) → (\d+) states.*?motion-RAO error ([\d.]+)%",
            "the tanker {0} → {1} states at {2} %",
        ),
    ],
    "reduce tanker_model.nc -o tanker_model_small.nc --tol 0.02 --data tanker.1": [
        ("docs/guide/reduce.md", r"→ (\d+) states", "`--tol 0.02` gives {0} states"),
    ],
    "batch rm3_sweep.yaml -o rm3_sweep.nc --workers 1": [
        ("docs/guide/wec.md", r"3e\+06: ([\d.]+) kW", "3·10⁶ N·s/m ({0} kW)"),
        ("docs/guide/wec.md", r"│ 2\.5 │ 1e\+06 \(([\d.]+) kW\)", "({0} kW at H_s 2.5 m)"),
    ],
    "dp-demo -o dp --duration 300 --seed 1": [
        ("docs/guide/dp.md", r"static heel [-\d.]+° \((-?[\d.]+) %\)", "prints {0} %"),
    ],
}


def _check_quoted(command: Command, output: str) -> None:
    for page, pattern, sentence in QUOTED.get(" ".join(_key(command.args)), []):
        found = re.search(pattern, " ".join(output.split()), flags=re.S)
        assert found, f"{pattern!r} not in the output of {command.args}"
        text = " ".join((ROOT / page).read_text(encoding="utf-8").replace("−", "-").split())
        quoted = sentence.format(*found.groups())
        assert quoted in text, f"{page} should say {quoted!r} (what the command prints)"


def test_quoted_commands_are_on_their_pages():
    """The commands whose numbers the pages quote are commands of the pages."""
    assert set(QUOTED) <= {" ".join(_key(c.args)) for c in COMMANDS}


@pytest.mark.parametrize(
    "command", DISTINCT, ids=[f"{c.page}:{' '.join(c.args)[:60]}" for c in DISTINCT]
)
def test_console_command(command, workdir):
    if command.args[0] == "bem":
        pytest.importorskip("capytaine")
    for earlier in _prerequisites(command, {command.args}):
        first = CliRunner().invoke(main, list(earlier.args), catch_exceptions=False)
        assert first.exit_code == 0, f"{earlier.page}: {earlier.args}\n{first.output}"
    result = CliRunner().invoke(main, list(command.args), catch_exceptions=False)
    assert result.exit_code == 0, f"{command.page}: {command.args}\n{result.output}"
    _read_back(list(command.args), workdir)
    _check_quoted(command, result.output)


def _option(args: list[str], name: str) -> str | None:
    return args[args.index(name) + 1] if name in args[:-1] else None


def _read_back(args: list[str], workdir: Path) -> None:
    """What a command wrote reads back as what it claims to be."""
    import json

    import numpy as np
    import xarray as xr

    from cummins.radiation.model import RadiationModel
    from cummins.seakeeping.frequency_domain import load_rao

    command = args[0]
    outputs = [workdir / f for f in _outputs(tuple(args))]
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
    elif command == "fit-excitation":
        model = cummins.ExcitationModel.load(outputs[0])
        if _option(args, "--openfast"):
            from cummins.io.openfast import read_openfast_ssexctn

            ss = read_openfast_ssexctn(workdir / _option(args, "--openfast"))
            assert ss.heading == float(_option(args, "--heading")) and ss.n_states > 0
    elif command == "rao":
        rao = load_rao(outputs[0])
        assert set(rao.dims) == {"omega", "wave_direction", "dof"}
        if _option(args, "--headings"):
            given = args[args.index("--headings") + 1 :]
            count = next((k for k, a in enumerate(given) if a.startswith("-")), len(given))
            assert rao.sizes["wave_direction"] == count
    elif command == "simulate":
        with xr.open_dataset(outputs[0], engine="h5netcdf") as run:
            if _option(args, "--duration"):
                assert run.time.values[-1] == np.float64(_option(args, "--duration"))
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


PYTHON_PAGES = [p for group in GROUPS for p in group if _blocks(p, "python")]
#: files a page's Python blocks write, that the test finds
WRITES = {"docs/guide/read.md": "tanker_at_cg.nc", "docs/guide/fit.md": "tanker_model.nc"}


@pytest.mark.parametrize("page", PYTHON_PAGES, ids=[str(p.relative_to(ROOT)) for p in PYTHON_PAGES])
def test_python_blocks(page, workdir):
    """A page's Python blocks run with every warning an error: what they show a user
    raises none (a warning there would be the first thing a user sees)."""
    import warnings

    namespace: dict = {}
    for code in _blocks(page, "python"):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            exec(compile(code, str(page.relative_to(ROOT)), "exec"), namespace)
    written = WRITES.get(str(page.relative_to(ROOT)))
    assert written is None or (workdir / written).is_file()


def test_python_pages():
    """The README and the guide's stages hold Python, and the files checked are theirs."""
    names = {str(p.relative_to(ROOT)) for p in PYTHON_PAGES}
    assert {"README.md", "docs/guide/read.md", "docs/guide/wec.md"} <= names
    assert set(WRITES) <= names
