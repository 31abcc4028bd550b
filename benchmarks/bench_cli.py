"""Benchmark: what the command line costs beyond the work it runs.

Each command is run as a user runs it, ``python -m cummins …`` in a fresh process, and
timed by its process CPU time (user + system, from ``getrusage`` of the children: the
machine is shared, and CPU time does not count the time other processes take) and by
its wall time; the median of ``--repeat`` runs. With ``--before SRC`` the same commands
run, interleaved, on another source tree (``/work/main/src``: the code before a change),
so that before and after are measured in the same run.

* start-up: ``cummins --help`` and ``cummins info tanker.1``, with the import time
  Python reports (``-X importtime``, the top-level modules' cumulative time);
* ``cummins fit tanker.1 -o m.nc --json fit.json`` against the fit it runs: the CPU time
  of ``fit_radiation`` alone, in a process where its modules are imported and the data
  read (the overhead is the difference: reading, writing the model and the JSON and
  every import included), and a script of three lines that reads and fits in a fresh
  process, as a user's script pays it (the overhead is what the command adds to it);
* the floor of each command: the scientific stack it needs imported alone (``STACKS``);
* with ``--plots``: ``fit --plot`` of the WEC-Sim RM3 (12 DOFs, two bodies) and of the
  tanker (6 DOFs), and ``report model.nc`` of a 6-DOF HAMS model (the cylinder).

Run: ``python benchmarks/bench_cli.py [--before /work/main/src] [--plots] [--repeat 5]``.
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _timing import SHARED_DATA

ROOT = Path(__file__).resolve().parents[1]
AFTER = ROOT / "src"
DATA = Path(os.environ.get("CUMMINS_SHARED_DATA", SHARED_DATA))
TANKER = ROOT / "src" / "cummins" / "data" / "tanker" / "tanker.1"
RM3 = DATA / "corpus" / "WEC-Sim" / "wamit_RM3_2body" / "rm3.out"
RM3_OPTIONS = [
    "--rho", "1000", "--mass", "725833", "--mass", "886687",
    "--center-of-gravity", "0", "0", "-0.72", "--center-of-gravity", "0", "0", "-21.29",
    "--radii-of-gyration", "5.367", "5.418", "7.148",
    "--radii-of-gyration", "10.319", "10.319", "5.674",
]  # fmt: skip
HAMS_CYLINDER = DATA / "corpus" / "HAMS" / "Cylinder"

#: A command run as in an environment without dask (the default install: dask is the
#: ``[dask]`` extra). With dask installed, xarray imports ``dask.array`` at its first
#: ``Variable``.
WITHOUT_DASK = """
import sys
sys.modules["dask"] = None
from cummins.cli import main
main(sys.argv[1:])
"""

#: In-process timing of the fit alone (its modules imported, the data read, before the
#: clock starts; what it imports as it runs is the fit's).
FIT_ALONE = """
import sys, time
import cummins
from cummins.radiation.fit import fit_radiation
ds = cummins.read(sys.argv[1])
start = time.process_time()
fit_radiation(ds)
print(time.process_time() - start)
"""
#: The same fit as a user's script pays it, from a fresh process (imports and reading in).
FIT_SCRIPT = """
import sys
import cummins
cummins.fit_radiation(cummins.read(sys.argv[1]))
"""


#: The floor of each command: the scientific stack it needs, imported in a fresh process
#: (``info``: NumPy, xarray and pandas; ``fit``: SciPy's linalg and optimize, which the
#: identification and passivity enforcement use, and h5netcdf, which writes the model).
STACKS = {
    "info": "import numpy, xarray",
    "fit": "import numpy, xarray, scipy.linalg, scipy.optimize, h5netcdf",
}


def _env(src: Path) -> dict[str, str]:
    """The environment of a user's run: bytecode cached (an installed package has its
    ``.pyc``; ``PYTHONDONTWRITEBYTECODE`` would compile every module at each start)."""
    dropped = ("COLUMNS", "LINES", "PYTHONDONTWRITEBYTECODE")
    env = {k: v for k, v in os.environ.items() if k not in dropped}
    return {**env, "PYTHONPATH": str(src), "OPENBLAS_NUM_THREADS": "1", "MPLBACKEND": "Agg"}


def run(src: Path, args: list[str], cwd: Path) -> tuple[float, float, str]:
    """(CPU s, wall s, standard output) of ``python ARGS`` on the source tree ``src``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(
        [sys.executable, *args], cwd=cwd, env=_env(src), capture_output=True, text=True
    )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 3):  # 3: a fit that misses a target, written all the same
        raise RuntimeError(f"{' '.join(args)} failed: {done.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall, done.stdout


def import_ms(src: Path, args: list[str], cwd: Path) -> float:
    """Python's own import time of a command (``-X importtime``): the sum of the
    cumulative times of the top-level imports, ms."""
    done = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "cummins", *args],
        cwd=cwd,
        env=_env(src),
        capture_output=True,
        text=True,
    )
    total = 0
    for line in done.stderr.splitlines():
        match = re.match(r"import time:\s+\d+ \|\s+(\d+) \| (\S.*)$", line)
        if match and not match.group(2).startswith(" "):
            total += int(match.group(1))
    return total / 1000


def median_of(src, args, cwd, repeat) -> tuple[float, float]:
    run(src, args, cwd)  # writes the bytecode
    cpu, wall = zip(*(run(src, args, cwd)[:2] for _ in range(repeat)), strict=True)
    return statistics.median(cpu), statistics.median(wall)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", type=Path, default=None, help="source tree before")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--plots", action="store_true", help="fit --plot and report too")
    options = parser.parse_args()
    trees = {"after": AFTER} if options.before is None else {
        "before": options.before, "after": AFTER
    }  # fmt: skip
    work = Path(tempfile.mkdtemp(prefix="bench_cli_"))
    print(f"process CPU time (user + system) and wall time, median of {options.repeat}; "
          "one BLAS thread; the machine is shared: compare CPU times")  # fmt: skip

    print("\nstart-up")
    for label, args in (("cummins --help", ["--help"]), ("cummins info", ["info", str(TANKER)])):
        for name, src in trees.items():
            cpu, wall = median_of(src, ["-m", "cummins", *args], work, options.repeat)
            imports = import_ms(src, args, work)
            print(f"  {label:<14} {name:<6} CPU {cpu:6.2f} s  wall {wall:6.2f} s  "
                  f"imports {imports:6.0f} ms")  # fmt: skip
        if "info" in args:
            cpu, wall = median_of(AFTER, ["-c", WITHOUT_DASK, *args], work, options.repeat)
            print(f"  {label:<14} after, without dask: CPU {cpu:6.2f} s  wall {wall:6.2f} s")
            cpu, wall = median_of(AFTER, ["-c", STACKS["info"]], work, options.repeat)
            print(f"  {STACKS['info']!r} alone: CPU {cpu:6.2f} s  wall {wall:6.2f} s")

    print("\ncummins fit tanker.1 -o m.nc --json fit.json, against the fit it runs")
    fit = ["-m", "cummins", "fit", str(TANKER), "-o", "m.nc", "--json", "fit.json", "--force"]
    for name, src in trees.items():
        cpu, wall = median_of(src, fit, work, options.repeat)
        alone = statistics.median(
            float(run(src, ["-c", FIT_ALONE, str(TANKER)], work)[2].split()[-1])
            for _ in range(options.repeat)
        )
        script, _ = median_of(src, ["-c", FIT_SCRIPT, str(TANKER)], work, options.repeat)
        print(f"  {name:<6} command CPU {cpu:5.2f} s (wall {wall:5.2f} s); fit alone "
              f"{alone:5.2f} s: overhead {cpu - alone:5.2f} s; the same fit as a script "
              f"{script:5.2f} s: overhead {cpu - script:5.2f} s")  # fmt: skip

    cpu, wall = median_of(AFTER, ["-c", STACKS["fit"]], work, options.repeat)
    print(f"  {STACKS['fit']!r} alone: CPU {cpu:5.2f} s (wall {wall:5.2f} s)")

    if not options.plots:
        return
    print("\nfit --plot and report (once each)")
    cases = [("tanker, 6 DOFs", [str(TANKER)])]
    if RM3.is_file():
        cases.insert(0, ("WEC-Sim RM3, 12 DOFs", [str(RM3), *RM3_OPTIONS]))
    for label, data in cases:
        for name, src in trees.items():
            folder = work / f"plots-{name}-{len(data)}"
            args = ["-m", "cummins", "fit", *data, "-o", "p.nc", "--force", "--plot", str(folder)]
            cpu, wall, _ = run(src, args, work)
            figures = len(list(folder.glob("*.png")))
            print(f"  fit --plot {label:<22} {name:<6} CPU {cpu:6.1f} s  wall {wall:6.1f} s  "
                  f"{figures} figures")  # fmt: skip
    if HAMS_CYLINDER.is_dir():
        model = work / "hams.nc"
        run(AFTER, ["-m", "cummins", "fit", str(HAMS_CYLINDER), "-o", str(model)], work)
        for name, src in trees.items():
            page = work / f"report-{name}.html"
            args = ["-m", "cummins", "report", str(model), "-o", str(page), "--force"]
            cpu, wall, _ = run(src, args, work)
            print(f"  report model.nc (HAMS cylinder, 6 DOFs) {name:<6} CPU {cpu:6.1f} s  "
                  f"wall {wall:6.1f} s")  # fmt: skip


if __name__ == "__main__":
    main()
