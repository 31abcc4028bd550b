"""The corpus scoreboard: read every real case users bring and say what it yields.

Usage (from the project root)::

    python benchmarks/bench_corpus.py [--markdown] [--filter TEXT]

For every case folder of ``../shared/data/corpus`` (each passed to ``cummins.read`` as
it is, as a user would) and for the file sets of ``../shared/data``: status (``ok``, or
the first line of the ``CumminsError``; ``CRASH`` for any other exception, a defect),
DOFs, frequencies, which of ``inertia_matrix`` (I), ``hydrostatic_stiffness`` (C),
``excitation_force`` (F) and ``added_mass_inf`` (A∞) are present, the number of read
warnings, and the read time. ``--markdown`` prints the table for BENCHMARKS.md.
Exit status 1 when a case crashed.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import cummins

ROOT = Path(__file__).resolve().parents[1]
SHARED = Path(os.environ.get("CUMMINS_SHARED_DATA", ROOT.parent / "shared" / "data"))

#: The shared file sets (a folder there holds several formats of one body, so each
#: run is named by the file a user would pass).
SHARED_CASES = (
    "mss/tanker/tanker.1",
    "mss/tanker/tanker.out",
    "mss/tanker/tanker.mat",
    "mss/supply/input.re7",
    "mss/supply/supply.mat",
    "mss/s175/s175.mat",
    "wecsim/sphere/sphere.out",
    "wecsim/sphere/sphere_hydrodynamics.nc",
    "wecsim/cylinder/cylinder_nemoh/RadiationCoefficients.tec",
    "wecsim/cylinder/cylinder_nemoh/cyl.1",
    "wecsim/cylinder/cylinder_nemoh/cylinder_hydrodynamics.nc",
    "wecsim/cylinder_aqwa/cylinder.LIS",
    "wecsim/cylinder_aqwa/cylinder.AH1",
)

#: The variables whose presence decides what a user can do with a case.
KEYS = (
    ("I", "inertia_matrix"),
    ("C", "hydrostatic_stiffness"),
    ("F", "excitation_force"),
    ("A∞", "added_mass_inf"),
)


@dataclass(frozen=True)
class Row:
    case: str
    status: str
    dofs: int | None = None
    frequencies: int | None = None
    present: tuple[str, ...] = ()
    n_warnings: int = 0
    seconds: float = 0.0

    @property
    def equation_of_motion(self) -> bool:
        """Inertia, restoring and excitation: ``cummins rao`` and ``simulate`` run."""
        return {"I", "C", "F"} <= set(self.present)


def corpus_cases(shared: Path = SHARED) -> list[Path]:
    """Every case of the corpus (folders two levels down) and the shared file sets."""
    corpus = sorted(p for p in (shared / "corpus").glob("*/*") if p.is_dir())
    return corpus + [shared / c for c in SHARED_CASES if (shared / c).exists()]


def read_case(path: Path, shared: Path = SHARED) -> Row:
    name = str(path.relative_to(shared))
    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            ds = cummins.read(path)
        except cummins.CumminsError as exc:
            return Row(name, "error: " + str(exc).splitlines()[0], seconds=_since(t0))
        except Exception as exc:  # a defect: every failure must be a CumminsError
            return Row(name, f"CRASH {type(exc).__name__}: {exc}", seconds=_since(t0))
    damage = sum(issubclass(w.category, cummins.HydroDataWarning) for w in caught)
    return Row(
        name,
        "ok",
        dofs=ds.sizes.get("radiating_dof"),
        frequencies=ds.sizes.get("omega"),
        present=tuple(key for key, var in KEYS if var in ds),
        n_warnings=damage,
        seconds=_since(t0),
    )


def _since(t0: float) -> float:
    return time.perf_counter() - t0


def _text(rows: list[Row]) -> str:
    lines = []
    for r in rows:
        if r.status == "ok":
            what = f"ok {r.dofs:3d} DOF {r.frequencies:5d} ω  {' '.join(r.present):12s}"
            if r.n_warnings:
                what += f" {r.n_warnings} warning(s)"
        else:
            what = r.status[:110]
        lines.append(f"{r.case:58s} {r.seconds:5.2f} s  {what}")
    return "\n".join(lines)


def _markdown(rows: list[Row]) -> str:
    head = (
        "| case | status | DOF | ω | I | C | F | A∞ | read [s] |\n"
        "|---|---|---|---|---|---|---|---|---|"
    )
    body = []
    for r in rows:
        marks = ["✓" if key in r.present else "" for key, _ in KEYS]
        status = "ok" if r.status == "ok" else r.status.replace("|", "/")[:90]
        body.append(
            f"| {r.case} | {status} | {r.dofs or ''} | {r.frequencies or ''} | "
            + " | ".join(marks)
            + f" | {r.seconds:.2f} |"
        )
    return "\n".join([head, *body])


def summary(rows: list[Row]) -> str:
    ok = [r for r in rows if r.status == "ok"]
    crashes = [r for r in rows if r.status.startswith("CRASH")]
    return (
        f"{len(ok)}/{len(rows)} cases read, "
        f"{sum('I' in r.present for r in ok)} with inertia_matrix, "
        f"{sum(r.equation_of_motion for r in ok)} with inertia, restoring and excitation, "
        f"{len(rows) - len(ok) - len(crashes)} clean errors, {len(crashes)} crashes; "
        f"read in {sum(r.seconds for r in rows):.1f} s"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--markdown", action="store_true", help="print a Markdown table")
    parser.add_argument("--filter", default="", help="only cases whose name contains TEXT")
    args = parser.parse_args(argv)
    rows = [read_case(p) for p in corpus_cases() if args.filter in str(p)]
    print(_markdown(rows) if args.markdown else _text(rows))
    print(summary(rows))
    return 1 if any(r.status.startswith("CRASH") for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
