"""Benchmark: reading each solver format, against a bare parse of the same files.

For every real file set in ../shared/data the script times ``cummins.read`` (format
detection, parsing, unit conversion, validation) and, in the same run, a reference that
only parses the numbers (``numpy.loadtxt`` / ``str.split`` for text, ``xarray`` for
NetCDF, ``scipy.io.loadmat`` for MATLAB files). It prints both times and their ratio:
reading must never be the slow stage of a pipeline.

Run: ``python benchmarks/bench_read.py [--repeat N] [--json out.json]``.
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

import numpy as np
import scipy.io
import xarray as xr

import cummins
from _timing import timed

ROOT = Path(__file__).resolve().parents[1]
DATA = Path(os.environ.get("CUMMINS_SHARED_DATA", ROOT.parent / "shared" / "data"))


def _split_numbers(*paths: Path) -> int:
    """Reference for text formats: split every line and convert what is numeric."""
    count = 0
    for path in paths:
        for line in path.read_text(errors="replace").splitlines():
            for field in line.split():
                try:
                    float(field)
                    count += 1
                except ValueError:
                    pass
    return count


CASES = [
    # name, path read by cummins, options, reference callable
    (
        "WAMIT tanker .1/.3/.hst/.frc/.out",
        "mss/tanker/tanker.1",
        {},
        lambda d: [
            np.loadtxt(d / "mss/tanker/tanker.3"),
            _split_numbers(d / "mss/tanker/tanker.1"),
        ],
    ),
    (
        "WAMIT tanker .out log",
        "mss/tanker/tanker.out",
        {},
        lambda d: _split_numbers(d / "mss/tanker/tanker.out"),
    ),
    (
        "WAMIT sphere .1/.3/.hst/.out",
        "wecsim/sphere/sphere.1",
        {"rho": 1000.0},
        lambda d: [
            np.loadtxt(d / "wecsim/sphere/sphere.3", skiprows=1),
            _split_numbers(d / "wecsim/sphere/sphere.1"),
        ],
    ),
    (
        "NEMOH cylinder (folder)",
        "wecsim/cylinder/cylinder_nemoh/RadiationCoefficients.tec",
        {},
        lambda d: _split_numbers(*(d / "wecsim/cylinder/cylinder_nemoh").glob("*.tec")),
    ),
    (
        "AQWA cylinder .LIS",
        "wecsim/cylinder_aqwa/cylinder.LIS",
        {},
        lambda d: _split_numbers(d / "wecsim/cylinder_aqwa/cylinder.LIS"),
    ),
    (
        "AQWA cylinder .AH1",
        "wecsim/cylinder_aqwa/cylinder.AH1",
        {},
        lambda d: _split_numbers(d / "wecsim/cylinder_aqwa/cylinder.AH1"),
    ),
    (
        "VERES supply .re7/.re8/.re1",
        "mss/supply/input.re7",
        {},
        lambda d: _split_numbers(*(d / f"mss/supply/input.re{k}" for k in (7, 8, 1))),
    ),
    (
        "Capytaine sphere NetCDF",
        "wecsim/sphere/sphere_hydrodynamics.nc",
        {},
        lambda d: xr.load_dataset(d / "wecsim/sphere/sphere_hydrodynamics.nc", engine="scipy"),
    ),
    (
        "MSS S-175 .mat (5 speeds)",
        "mss/s175/s175.mat",
        {},
        lambda d: scipy.io.loadmat(d / "mss/s175/s175.mat"),
    ),
]


def best_time(function, repeat: int) -> float:
    """Best of ``repeat`` wall-clock times, seconds."""
    return timed(function, repeat)[0]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json", type=Path, default=None, help="write the results as JSON")
    args = parser.parse_args()
    results = []
    print(f"{'file set':38s} {'cummins.read':>13s} {'bare parse':>11s} {'ratio':>7s}")
    for name, rel, options, reference in CASES:
        path = DATA / rel
        t_read = best_time(lambda p=path, o=options: cummins.read(p, **o), args.repeat)
        t_ref = best_time(lambda r=reference: r(DATA), args.repeat)
        results.append(
            {"case": name, "read_s": t_read, "reference_s": t_ref, "ratio": t_read / t_ref}
        )
        print(f"{name:38s} {t_read * 1e3:10.1f} ms {t_ref * 1e3:8.1f} ms {t_read / t_ref:7.2f}")
    if args.json:
        args.json.write_text(json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    main()
