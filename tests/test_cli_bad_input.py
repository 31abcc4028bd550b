"""Every command of ``cummins --help`` given wrong inputs: bad numbers (NaN, negative, zero,
huge), wrong kinds of file, paths under an existing file, existing outputs without
``--force``.

Each case must end with exit status 2 (a bad option or argument) or 1 (data that cannot
be used), one ``error:`` line (click's own "Error:" for usage), no Python traceback, no
exception escaping the command, and the user's files byte-identical afterwards. Almost
all of them fail before any work starts: the whole file runs in a few seconds.
"""

from __future__ import annotations

import hashlib
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main

TWO_BODIES = "bemio/nemoh_two_body"  # corpus case with two cubes, 12 DOFs


@pytest.fixture(scope="module")
def work(tmp_path_factory, shared_data):
    """A folder of the user's files: the tanker (WAMIT), the sphere without inertia, a
    binary file, an empty file, a plain file ``afile`` (outputs "under" it are refused),
    existing outputs (``old.*``), a truncated NetCDF and datasets no body can have."""
    root = tmp_path_factory.mktemp("user")
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, root / f.name)
    for f in (shared_data / "wecsim" / "sphere").glob("sphere.*"):
        shutil.copy(f, root / f.name)
    rng = np.random.default_rng(7)
    (root / "binary.dat").write_bytes(rng.integers(0, 256, 4000, dtype=np.uint8).tobytes())
    (root / "binary.yaml").write_bytes((root / "binary.dat").read_bytes())
    (root / "empty.1").write_bytes(b"")
    (root / "afile").write_text("not a folder\n", encoding="utf-8")
    for name in ("old.nc", "old.json", "old.html", "old.mat", "old.ss"):
        (root / name).write_text("the user's earlier result\n", encoding="utf-8")
    tanker = cummins.read(root / "tanker.1")
    cummins.write(tanker, root / "tanker.nc")
    (root / "truncated.nc").write_bytes((root / "tanker.nc").read_bytes()[:3000])
    negated = tanker.copy(deep=True)
    negated["radiation_damping"] = -negated.radiation_damping
    cummins.write(negated, root / "negated.nc")
    heavy = tanker.copy(deep=True)
    heavy["added_mass"] = heavy.added_mass.copy()
    heavy["added_mass"].values[5, 2, 2] = 1e20  # beyond any floating body, not any number
    cummins.write(heavy, root / "absurd.nc")
    heavy["added_mass"].values[5, 2, 2] = 1e300  # refused by the reader already
    cummins.write(heavy, root / "absurd300.nc")
    return root


def _digest(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def _run(work: Path, args: list[str], monkeypatch):
    monkeypatch.chdir(work)
    before = _digest(work)
    result = CliRunner().invoke(main, args, catch_exceptions=True)
    after = _digest(work)
    changed = [name for name, digest in before.items() if after.get(name) != digest]
    return result, changed


T = "tanker.1"
BOX = ["bem", "--hull", "box", "--length", "20", "--beam", "8", "--draft", "2"]
OMEGAS = ["--omega-min", "0.2", "--omega-max", "2", "-o", "b.nc"]
#: (command line, exit status, a fragment the message must hold)
CASES: dict[str, tuple[list[str], int, str]] = {
    # info
    "info-missing-file": (["info", "nothere.1"], 2, "does not exist"),
    "info-binary": (["info", "binary.dat"], 1, "unrecognised file format"),
    "info-empty": (["info", "empty.1"], 1, "empty"),
    "info-rho-nan": (["info", T, "--rho", "nan"], 2, "--rho"),
    "info-rho-negative": (["info", T, "--rho", "-1025"], 2, "--rho"),
    "info-g-zero": (["info", T, "--g", "0"], 2, "--g"),
    "info-ulen-inf": (["info", T, "--ulen", "inf"], 2, "--ulen"),
    "info-format-unknown": (["info", T, "--format", "bogus"], 2, "unknown format"),
    # check
    "check-json-exists": (["check", T, "--json", "old.json"], 2, "refusing to overwrite"),
    "check-json-under-file": (["check", T, "--json", "afile/r.json"], 2, "is a file"),
    "check-json-folder": (["check", T, "--json", "."], 2, "--json"),
    "check-negated-damping": (["check", "negated.nc"], 1, "negative at"),
    "check-absurd-mass": (["check", "absurd.nc"], 1, "beyond any floating body"),
    "check-1e300": (["check", "absurd300.nc"], 1, "beyond any physical value"),
    # convert
    "convert-exists": (["convert", T, "old.nc"], 2, "refusing to overwrite"),
    "convert-under-file": (["convert", T, "afile/t.nc"], 2, "is a file"),
    "convert-extension": (["convert", T, "t.txt"], 2, ".nc"),
    "convert-reference-nan": (["convert", T, "t.nc", "--reference-point", "nan", "0", "0"], 2, ""),
    "convert-binary": (["convert", "binary.dat", "t.nc"], 1, "unrecognised"),
    "convert-one-body-given-body": (["convert", T, "t.nc", "--body", "2"], 2, "one body"),
    # demo
    "demo-output-is-file": (["demo", "-o", "afile"], 2, "is a file"),
    "demo-under-file": (["demo", "-o", "afile/demo"], 2, "is a file"),
    # bem (fails on the options, with or without Capytaine)
    "bem-omega-zero": (
        [*BOX, "--omega-min", "0", "--omega-max", "2", "-o", "b.nc"],
        2,
        "--omega-min",
    ),
    "bem-length-negative": (
        ["bem", "--hull", "box", "--length", "-20", "--beam", "8", "--draft", "2", *OMEGAS],
        2,
        "--length",
    ),
    "bem-n-omega-zero": (
        [*BOX, "--omega-min", "0.2", "--omega-max", "2", "--n-omega", "0", "-o", "b.nc"],
        2,
        "--n-omega",
    ),
    "bem-depth-nan": (
        [*BOX, "--omega-min", "0.2", "--omega-max", "2", "--depth", "nan", "-o", "b.nc"],
        2,
        "--depth",
    ),
    "bem-headings-nan": (
        [*BOX, "--omega-min", "0.2", "--omega-max", "2", "--headings", "nan", "-o", "b.nc"],
        2,
        "--headings",
    ),
    "bem-exists": (
        [*BOX, "--omega-min", "0.2", "--omega-max", "2", "-o", "old.nc"],
        2,
        "exists",
    ),
    # kernel
    "kernel-dt-zero": (["kernel", T, "-o", "k.nc", "--dt", "0"], 2, "--dt"),
    "kernel-t-max-negative": (["kernel", T, "-o", "k.nc", "--t-max", "-1"], 2, "--t-max"),
    "kernel-huge": (["kernel", T, "-o", "k.nc", "--t-max", "1e7", "--dt", "1e-3"], 2, "TiB"),
    "kernel-dt-above-t-max": (["kernel", T, "-o", "k.nc", "--t-max", "10", "--dt", "100"], 2, ""),
    "kernel-under-file": (["kernel", T, "-o", "afile/sub/k.nc"], 2, "is a file"),
    "kernel-plot-under-file": (["kernel", T, "-o", "k.nc", "--plot", "afile/p"], 2, "is a file"),
    "rao-omega-outside-data": (["rao", T, "-o", "r.nc", "--omega-max", "9"], 2, "outside"),
    "kernel-exists": (["kernel", T, "-o", "old.nc"], 2, "refusing to overwrite"),
    "kernel-omega-max-nan": (["kernel", T, "-o", "k.nc", "--omega-max", "nan"], 2, ""),
    "kernel-speed": (["kernel", T, "-o", "k.nc", "--speed", "3"], 2, "one forward speed"),
    # fit
    "fit-r2-nan": (["fit", T, "-o", "m.nc", "--r2", "nan"], 2, "--r2"),
    "fit-r2-above-one": (["fit", T, "-o", "m.nc", "--r2", "1.5"], 2, "--r2"),
    "fit-r2-one": (["fit", T, "-o", "m.nc", "--r2", "1"], 2, "--r2"),
    "fit-threshold-negative": (["fit", T, "-o", "m.nc", "--threshold", "-1"], 2, "--threshold"),
    "fit-max-order-zero": (["fit", T, "-o", "m.nc", "--max-order", "0"], 2, "--max-order"),
    "fit-order-zero": (["fit", T, "-o", "m.nc", "--order", "Heave", "Heave", "0"], 2, ""),
    "fit-omega-min-negative": (["fit", T, "-o", "m.nc", "--omega-min", "-1"], 2, "--omega"),
    "fit-under-file": (["fit", T, "-o", "afile/m.nc"], 2, "is a file"),
    "fit-plot-is-file": (["fit", T, "-o", "m.nc", "--plot", "afile"], 2, "afile"),
    "fit-exists": (["fit", T, "-o", "old.nc"], 2, "refusing to overwrite"),
    "fit-mss-exists": (["fit", T, "-o", "m.nc", "--mss", "old.mat"], 2, "refusing"),
    "fit-absurd-data": (["fit", "absurd.nc", "-o", "m.nc"], 1, "beyond any floating body"),
    "fit-speed": (["fit", T, "-o", "m.nc", "--speed", "5"], 2, "one forward speed"),
    # fit-excitation
    "fit-excitation-nrmse-nan": (
        ["fit-excitation", T, "-o", "e.nc", "--nrmse", "nan"],
        2,
        "--nrmse",
    ),
    "fit-excitation-causality-one": (
        ["fit-excitation", T, "-o", "e.nc", "--causality", "1"],
        2,
        "--causality",
    ),
    "fit-excitation-delay-negative": (
        ["fit-excitation", T, "-o", "e.nc", "--delay", "-3"],
        2,
        "--delay",
    ),
    "fit-excitation-exists": (["fit-excitation", T, "-o", "old.nc"], 2, "refusing to overwrite"),
    "fit-excitation-openfast-headings": (
        ["fit-excitation", T, "-o", "e.nc", "--openfast", "t.ssexctn"],
        2,
        "one heading",
    ),
    "fit-excitation-plot-is-file": (
        ["fit-excitation", T, "-o", "e.nc", "--plot", "afile"],
        2,
        "afile",
    ),
    "simulate-wave-record-missing": (
        ["simulate", T, "--wave-elevation", "nothere.csv", "-o", "r.nc"],
        2,
        "does not exist",
    ),
    # reduce
    "reduce-no-order": (["reduce", "tanker.nc", "-o", "r.nc"], 2, "exactly one"),
    "reduce-order-zero": (["reduce", "tanker.nc", "-o", "r.nc", "--order", "0"], 2, "--order"),
    "reduce-tol-nan": (["reduce", "tanker.nc", "-o", "r.nc", "--tol", "nan"], 2, "--tol"),
    "reduce-tol-zero": (["reduce", "tanker.nc", "-o", "r.nc", "--tol", "0"], 2, "--tol"),
    "reduce-not-a-model": (["reduce", T, "-o", "r.nc", "--order", "10"], 1, ""),
    "reduce-exists": (["reduce", "tanker.nc", "-o", "old.nc", "--order", "10"], 2, "refusing"),
    # rao
    "rao-omega-min-negative": (["rao", T, "-o", "r.nc", "--omega-min", "-1"], 2, "--omega-min"),
    "rao-n-omega-zero": (["rao", T, "-o", "r.nc", "--n-omega", "0"], 2, "--n-omega"),
    "rao-headings-nan": (["rao", T, "-o", "r.nc", "--headings", "nan"], 2, "--headings"),
    "rao-viscous-nan": (["rao", T, "-o", "r.nc", "--viscous-damping", "Roll", "nan"], 2, ""),
    "rao-viscous-negative": (["rao", T, "-o", "r.nc", "--viscous-damping", "Roll", "-5"], 2, ""),
    "rao-under-file": (["rao", T, "-o", "afile/r.nc"], 2, "is a file"),
    "rao-exists": (["rao", T, "-o", "old.nc"], 2, "refusing to overwrite"),
    "rao-speed": (["rao", T, "-o", "r.nc", "--speed", "3"], 2, "one forward speed"),
    "rao-no-inertia": (["rao", "sphere.out", "-o", "r.nc"], 1, "inertia"),
    # simulate: the cases of issue 17
    **{
        f"simulate{option}-{value}": (
            ["simulate", T, "-o", "s.nc", "--hs", "2", "--tp", "10", option, value],
            2,
            option,
        )
        for option, value in (
            ("--dt", "0"),
            ("--duration", "-5"),
            ("--hs", "-1"),
            ("--tp", "0"),
            ("--components", "0"),
            ("--heading", "nan"),
            ("--seed", "-1"),
            ("--gamma", "0.5"),
            ("--spreading", "-1"),
        )
    },
    "simulate-huge": (
        ["simulate", T, "-o", "s.nc", "--hs", "2", "--tp", "10", "--duration", "1e12"],
        2,
        "PiB",
    ),
    "simulate-regular-period": (
        ["simulate", T, "-o", "s.nc", "--regular", "--wave-period", "0"],
        2,
        "--wave-period",
    ),
    "simulate-dof": (
        ["simulate", T, "-o", "s.nc", "--hs", "2", "--tp", "9", "--dof", "Spin"],
        2,
        "",
    ),
    "simulate-speed": (
        ["simulate", T, "-o", "s.nc", "--hs", "2", "--tp", "9", "--speed", "3"],
        2,
        "one forward speed",
    ),
    "simulate-under-file": (
        ["simulate", T, "-o", "afile/s.nc", "--hs", "2", "--tp", "9"],
        2,
        "is a file",
    ),
    "simulate-exists": (["simulate", T, "-o", "old.nc", "--hs", "2", "--tp", "9"], 2, "refusing"),
    "simulate-no-inertia": (
        ["simulate", "sphere.out", "-o", "s.nc", "--hs", "1", "--tp", "8"],
        1,
        "with_inertia",
    ),
    "simulate-no-sea": (["simulate", T, "-o", "s.nc"], 2, "--hs and --tp"),
    # identify-damping
    "identify-binary-record": (
        ["identify-damping", "binary.dat", "--model", T, "--report", "rep"],
        1,
        "binary.dat",
    ),
    "identify-cutoff-zero": (
        ["identify-damping", "tanker.hst", "--model", T, "--cutoff", "0", "--report", "rep"],
        2,
        "--cutoff",
    ),
    "identify-inertia-nan": (
        ["identify-damping", "tanker.hst", "--decay", "--inertia", "nan", "--report", "rep"],
        2,
        "--inertia",
    ),
    "identify-report-is-file": (
        ["identify-damping", "tanker.hst", "--model", T, "--report", "afile"],
        2,
        "afile",
    ),
    # dp-demo
    "dp-duration-zero": (["dp-demo", "-o", "dp", "--duration", "0"], 2, "--duration"),
    "dp-dt-nan": (["dp-demo", "-o", "dp", "--dt", "nan"], 2, "--dt"),
    "dp-huge": (["dp-demo", "-o", "dp", "--duration", "1e12"], 2, "PiB"),
    "dp-current-negative": (["dp-demo", "-o", "dp", "--current", "-1"], 2, "--current"),
    "dp-wind-nan": (["dp-demo", "-o", "dp", "--wind", "nan"], 2, "--wind"),
    "dp-seed-negative": (["dp-demo", "-o", "dp", "--seed", "-3"], 2, "--seed"),
    "dp-output-is-file": (["dp-demo", "-o", "afile"], 2, "afile"),
    # lf-model
    "lf-roll-negative": (["lf-model", T, "-o", "lf.nc", "--roll-damping", "-0.1"], 2, "--roll"),
    "lf-roll-nan": (["lf-model", T, "-o", "lf.nc", "--roll-damping", "nan"], 2, "--roll"),
    "lf-surge-nan": (["lf-model", T, "-o", "lf.nc", "--surge-damping", "nan", "0"], 2, "--surge"),
    "lf-speed": (["lf-model", T, "-o", "lf.nc", "--speed", "2"], 2, "one forward speed"),
    "lf-under-file": (["lf-model", T, "-o", "afile/lf.nc"], 2, "is a file"),
    "lf-exists": (["lf-model", T, "-o", "old.nc"], 2, "refusing to overwrite"),
    "lf-no-inertia": (["lf-model", "sphere.out", "-o", "lf.nc"], 1, "inertia"),
    # batch
    "batch-binary-study": (["batch", "binary.yaml", "-o", "b.nc"], 2, "not a text file"),
    "batch-no-output": (["batch", "binary.yaml"], 2, "-o"),
    "batch-workers-zero": (["batch", "binary.yaml", "-o", "b.nc", "--workers", "0"], 2, ""),
    "batch-missing-study": (["batch", "nothere.yaml", "-o", "b.nc"], 2, "does not exist"),
    # report
    "report-kind-run-on-data": (["report", T, "-o", "r.html", "--kind", "run"], 2, "not a run"),
    "report-binary": (["report", "binary.dat", "-o", "r.html"], 1, "unrecognised"),
    "report-truncated": (["report", "truncated.nc", "-o", "r.html"], 1, "truncated"),
    "report-exists": (["report", T, "-o", "old.html"], 2, "exists"),
    "report-under-file": (["report", T, "-o", "afile/r.html"], 2, "is a file"),
    "report-g-negative": (["report", T, "-o", "r.html", "--g", "-9.81"], 2, "--g"),
    "report-rho-nan": (["report", T, "-o", "r.html", "--rho", "nan"], 2, "--rho"),
    "report-ulen-zero": (["report", T, "-o", "r.html", "--ulen", "0"], 2, "--ulen"),
    # an output over a file the command reads, or two outputs on one file: refused with
    # --force too (issue 31: --force replaces an earlier output, never the input)
    **{
        f"{args[0]}-over-{args[-2]}": (args, 2, "reads")
        for args in (
            ["fit", T, "-o", T, "--force"],
            ["fit", T, "-o", "tanker.hst", "--force"],
            ["fit", T, "-o", "m.nc", "--openfast", "tanker.frc", "--force"],
            ["kernel", T, "-o", "tanker.out", "--force"],
            ["report", T, "-o", "tanker.3", "--force"],
            ["report", T, "-o", T, "--force"],
            ["rao", T, "-o", "tanker.3", "--force"],
            ["simulate", "tanker.nc", "-o", "tanker.nc", "--hs", "2", "--tp", "9", "--force"],
            ["convert", "tanker.nc", "tanker.nc", "--force"],
            ["check", T, "--json", "tanker.hst", "--force"],
        )
    },
    # options that contradict each other: refused, naming both, instead of one ignored
    **{
        f"contradiction-{k}": (args, 2, fragment)
        for k, (args, fragment) in enumerate(
            (
                (
                    ["simulate", T, "-o", "s.nc", "--regular", "--wave-period", "9", "--hs", "3"],
                    "--regular and --hs",
                ),
                (
                    ["simulate", T, "-o", "s.nc", "--regular", "--wave-period", "9", "--tp", "9"],
                    "--regular and --tp",
                ),
                (
                    [
                        "simulate",
                        T,
                        "-o",
                        "s.nc",
                        "--regular",
                        "--wave-period",
                        "9",
                        "--spreading",
                        "4",
                    ],
                    "--regular and --spreading",
                ),
                (
                    ["simulate", T, "-o", "s.nc", "--hs", "3", "--tp", "9", "--wave-period", "9"],
                    "--wave-period applies only with --regular",
                ),
                (
                    ["simulate", T, "-o", "s.nc", "--hs", "3", "--tp", "9", "--directions", "5"],
                    "--directions applies only with --spreading",
                ),
                (
                    [
                        "simulate",
                        T,
                        "-o",
                        "s.nc",
                        "--hs",
                        "3",
                        "--tp",
                        "9",
                        "--spectrum",
                        "pm",
                        "--gamma",
                        "2",
                    ],
                    "--gamma applies only with --spectrum jonswap",
                ),
                (
                    [
                        "simulate",
                        T,
                        "-o",
                        "s.nc",
                        "--hs",
                        "3",
                        "--tp",
                        "9",
                        "--viscous-damping",
                        "Roll",
                        "5e8",
                        "--viscous-damping",
                        "Roll",
                        "1e9",
                    ],
                    "Roll is given twice",
                ),
                (
                    ["simulate", T, "-o", "s.nc", "--hs", "3", "--tp", "9", "--heading", "1e9"],
                    "--heading",
                ),
                (
                    ["simulate", T, "-o", "s.nc", "--hs", "3", "--tp", "9", "--hs", "4"],
                    "--hs 3 and --hs 4",
                ),
                (
                    ["simulate", T, "-o", "s.nc", "--hs=3", "--tp", "9", "--dt=0.1", "--dt", "0.2"],
                    "--dt 0.1 and --dt 0.2",
                ),
                (
                    ["fit", T, "-o", "m.nc", "--order", "Heave", "Heave", "30", "--max-order", "5"],
                    "above --max-order 5",
                ),
                (
                    [
                        "fit",
                        T,
                        "-o",
                        "m.nc",
                        "--order",
                        "Heave",
                        "Pitch",
                        "3",
                        "--order",
                        "Pitch",
                        "Heave",
                        "4",
                    ],
                    "Heave Pitch is given twice",
                ),
                (
                    ["kernel", T, "-o", "k.nc", "--keep-suspect", "--above-first"],
                    "--above-first applies only with --remove-suspect",
                ),
                (["rao", T, "-o", "r.nc", "--headings", "0", "360"], "one direction"),
                (["rao", T, "-o", "r.nc", "--headings", "400"], "beyond one turn"),
                (
                    [
                        "rao",
                        T,
                        "-o",
                        "r.nc",
                        "--external-stiffness",
                        "Surge",
                        "Surge",
                        "1",
                        "--external-stiffness",
                        "Surge",
                        "Surge",
                        "2",
                    ],
                    "Surge Surge is given twice",
                ),
                (
                    ["reduce", "tanker.nc", "-o", "r.nc", "--order", "9", "--speed", "2"],
                    "--speed applies only with --data",
                ),
                (
                    ["dp-demo", "-o", "dp", "--wind-from", "40"],
                    "--wind-from applies only with --wind above 0",
                ),
                (["dp-demo", "-o", "dp", "--current-from", "720"], "--current-from"),
                (
                    [
                        *BOX,
                        "--omega-min",
                        "0.2",
                        "--omega-max",
                        "2",
                        "--headings",
                        "1e9",
                        "-o",
                        "b.nc",
                    ],
                    "beyond one turn",
                ),
                (
                    [
                        "bem",
                        "mesh.gdf",
                        "--resolution",
                        "9",
                        "--omega-min",
                        "0.2",
                        "--omega-max",
                        "2",
                        "-o",
                        "b.nc",
                    ],
                    "--resolution applies only with --hull",
                ),
                (
                    [
                        "identify-damping",
                        "tanker.hst",
                        "--model",
                        T,
                        "--inertia",
                        "1e9",
                        "--report",
                        "rep",
                    ],
                    "--inertia applies only with --decay",
                ),
                (
                    [
                        "identify-damping",
                        "tanker.hst",
                        "--decay",
                        "--terms",
                        "linear",
                        "--report",
                        "rep",
                    ],
                    "--decay and --terms exclude each other",
                ),
                (
                    [
                        "identify-damping",
                        "tanker.hst",
                        "--model",
                        T,
                        "--max-lag",
                        "5",
                        "--report",
                        "rep",
                    ],
                    "--max-lag applies only with --align",
                ),
                (
                    ["batch", "--example", "s.yaml", "--workers", "2"],
                    "--workers applies only with --output",
                ),
            )
        )
    },
    "fit-json-on-output": (
        ["fit", T, "-o", "old.nc", "--json", "./old.nc", "--force"],
        2,
        "--output old.nc and --json old.nc name one file",
    ),
    "reduce-json-on-output": (
        ["reduce", "tanker.nc", "-o", "old.json", "--json", "old.json", "--order", "9", "--force"],
        2,
        "one file",
    ),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_wrong_input_is_one_line_with_the_right_status(work, name, monkeypatch):
    args, status, fragment = CASES[name]
    result, changed = _run(work, args, monkeypatch)
    output = result.output
    assert "Traceback" not in output, output
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(
        result.exception
    )
    assert result.exit_code == status, output
    assert fragment in output, output
    assert not changed, f"the user's files changed: {changed}"
    assert output.lower().count("error") >= 1, output


def test_every_command_has_wrong_inputs():
    """The list above covers every command of ``cummins --help``."""
    commands = set(main.commands)
    covered = {args[0] for args, _, _ in CASES.values()}
    assert commands <= covered, sorted(commands - covered)


def test_two_bodies_to_mss_name_the_option(work, corpus, monkeypatch):
    """Issue 17: "select one body's six DOFs first" had no option to do so. The message
    now names --body; with it the .mat holds that body (the NEMOH two-cube verification
    case, whose bodies are both 6-DOF cubes)."""
    source = str(corpus / TWO_BODIES)
    result, changed = _run(work, ["convert", source, "two.mat"], monkeypatch)
    assert result.exit_code == 2 and "--body 1 … 2" in result.output, result.output
    assert not (work / "two.mat").exists() and not changed
    result, _ = _run(work, ["convert", source, "two.mat", "--body", "2"], monkeypatch)
    assert result.exit_code == 0, result.output
    assert "MRB (the rigid-body inertia) is written as zeros" in result.output  # said, once
    assert "MRB" in result.output and "written as zeros; MSS" in result.output
    back = cummins.read(work / "two.mat")
    whole = cummins.read(source)
    labels = [str(d) for d in whole.influenced_dof.values]
    second = [label for label in labels if label.rpartition("__")[0] != labels[0].split("__")[0]]
    expected = whole.added_mass.sel(influenced_dof=second, radiating_dof=second).values
    # the .mat is in Fossen's axes, T A T with T = diag(1, -1, -1, 1, -1, -1): the diagonal
    # terms are those of the second body as read
    np.testing.assert_allclose(back.omega.values, whole.omega.values)
    for k in range(6):
        np.testing.assert_allclose(back.added_mass.values[:, k, k], expected[:, k, k], rtol=1e-9)
    result, _ = _run(work, ["fit", source, "-o", "m2.nc", "--mss", "m2.mat"], monkeypatch)
    assert result.exit_code == 2 and "--body N" in result.output, result.output
    assert not (work / "m2.nc").exists()


def test_warnings_are_one_line_notes_without_source_paths(work, monkeypatch):
    """Raw ``UserWarning`` lines with the source path reached the terminal: now one line
    each, once, without the path."""
    result, changed = _run(work, ["convert", "sphere.out", "sphere.mat"], monkeypatch)
    assert result.exit_code == 0, result.output
    assert "warning: the data have no inertia_matrix: MRB" in result.output
    assert "UserWarning" not in result.output and ".py:" not in result.output
    assert not changed


def test_check_text_names_multi_body_findings(corpus, monkeypatch, tmp_path):
    """The text report lost the DOF of multi-body findings (``[body1__Heave]`` was read as
    rich markup); every ``where`` of the JSON report now appears in the text."""
    import json

    monkeypatch.chdir(tmp_path)
    source = str(corpus / TWO_BODIES)
    runner = CliRunner()
    # notes of the reader go to stderr: the JSON on stdout stays parseable
    as_json = json.loads(runner.invoke(main, ["check", source, "--json", "-"]).stdout)
    text = runner.invoke(main, ["check", source]).output
    wheres = {f["where"] for f in as_json["findings"] if f["where"] and "__" in f["where"]}
    assert wheres, "the two-body case should have findings on named DOFs"
    for where in wheres:
        assert f"[{where}]" in text, where


def test_simulate_without_seed_records_a_seed_that_repeats_the_run(work, monkeypatch):
    """The most common call failed (a 128-bit seed HDF5 cannot store). Now the drawn seed
    fits an int64, is printed and recorded, and ``--seed`` with it gives the same run
    bit for bit."""
    import xarray as xr

    common = ["--hs", "2", "--tp", "10", "--duration", "120", "--dt", "0.2"]
    common += ["--components", "50", "--dof", "Heave", "--dof", "Pitch"]
    result, _ = _run(work, ["simulate", T, "-o", "drawn.nc", *common], monkeypatch)
    assert result.exit_code == 0, result.output
    with xr.open_dataset(work / "drawn.nc", engine="h5netcdf") as run:
        seed = int(run.attrs["seed"])
        motion = run.motion.values.copy()
    assert 0 <= seed < 2**63 and f"--seed {seed}" in result.output
    again, _ = _run(
        work, ["simulate", T, "-o", "again.nc", *common, "--seed", str(seed)], monkeypatch
    )
    assert again.exit_code == 0, again.output
    with xr.open_dataset(work / "again.nc", engine="h5netcdf") as run:
        np.testing.assert_array_equal(run.motion.values, motion)


def test_regular_wave_summary_gives_the_amplitude(work, monkeypatch):
    """A regular wave has no significant amplitude: the summary gives the amplitude of the
    steady oscillation (half its range over the last period). Measured on the tanker in
    heave, head seas, 10 s waves of 1 m: 0.2732 m, against 0.2713 m from the
    frequency-domain RAO of the same data (0.69 %: the fitted radiation model stands in
    for A(ω), B(ω) in the time domain); 1 % bounds it."""
    args = ["simulate", T, "-o", "reg.nc", "--regular", "--wave-period", "10", "--duration"]
    args += ["200", "--dt", "0.1", "--dof", "Heave", "--dof", "Pitch"]
    result, _ = _run(work, args, monkeypatch)
    assert result.exit_code == 0, result.output
    assert "amplitude" in result.output and "2σ" not in result.output
    import xarray as xr

    from cummins.seakeeping.frequency_domain import motion_rao

    ds = cummins.select_dofs(cummins.read(work / T), ["Heave", "Pitch"])
    rao = motion_rao(ds, [2 * np.pi / 10], [np.pi])
    expected = float(abs(rao.sel(dof="Heave").values).squeeze())
    with xr.open_dataset(work / "reg.nc", engine="h5netcdf") as run:
        heave = run.motion.sel(dof="Heave").values
        t = run.time.values
    measured = 0.5 * np.ptp(heave[t >= t[-1] - 10])
    assert measured == pytest.approx(expected, rel=0.01)
    shown = float(
        next(line for line in result.output.splitlines() if "│ Heave" in line).split("│")[2]
    )
    assert shown == pytest.approx(measured, rel=1e-3)


def test_report_reads_the_kernel_output(work, monkeypatch):
    """``report`` could not read what ``kernel`` writes ("unrecognised file format")."""
    result, _ = _run(work, ["kernel", T, "-o", "K.nc"], monkeypatch)
    assert result.exit_code == 0, result.output
    result, _ = _run(work, ["report", "K.nc", "-o", "K.html"], monkeypatch)
    assert result.exit_code == 0, result.output
    page = (work / "K.html").read_text(encoding="utf-8")
    assert "retardation functions" in page and "Heave" in page
    result, _ = _run(work, ["report", "K.nc", "-o", "K2.html", "--kind", "data"], monkeypatch)
    assert result.exit_code == 2 and "is a kernel file" in result.output


@pytest.mark.parametrize(
    ("extra", "fragment"),
    [
        (["--omega-min", "0.2", "--omega-max", "2", "--headings", "nan"], "not a finite number"),
        (["--omega-min", "3", "--omega-max", "2"], "--omega"),
    ],
)
def test_bem_checks_its_arguments_before_looking_for_capytaine(work, monkeypatch, extra, fragment):
    """Without the [bem] extra, a bad argument is still a bad argument (exit status 2),
    not "Capytaine is not installed" (exit status 1)."""
    import sys

    monkeypatch.setitem(sys.modules, "capytaine", None)  # import capytaine: ImportError
    result, _ = _run(work, [*BOX, *extra, "-o", "b.nc"], monkeypatch)
    assert result.exit_code == 2, result.output
    assert fragment in result.output and "Capytaine" not in result.output, result.output
    good = [*BOX, "--omega-min", "0.2", "--omega-max", "2", "-o", "b.nc"]
    result, _ = _run(work, good, monkeypatch)
    assert result.exit_code == 1 and "Capytaine is not installed" in result.output, result.output
