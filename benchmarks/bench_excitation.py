"""Benchmark: causal excitation models (issue 33), per 6 DOFs × one heading, against the
radiation fit of the same data in the same run.

For the OC3 spar (WEIS, WAMIT, 100 frequencies, the case whose SS_Excitation_Fitting
file the corpus holds), the MSS tanker (WAMIT, 58 frequencies) and the semisubmersible
computed with Capytaine for the tests (52 frequencies), in one run:

* ``fit_radiation`` (the default: common poles per block, passive);
* ``fit_excitation`` at every heading of the data (the tanker: 0, 45, 90, 135, 180 deg,
  the hard case of a long ship), timed per heading (6 DOFs each), with
  the states and the worst NRMSE over the wave band, and the ratio to the radiation fit;
* for the spar at 0 deg: its states and NRMSE against the data beside SS_Excitation_Fitting's
  57-state file (no t_c recorded: its best over 0–40 s), and the correlation of a 1-hour
  force from the written .ssexctn with the frequency-domain synthesis of the same sea.

Run: ``python benchmarks/bench_excitation.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import tempfile
import warnings
from pathlib import Path

import numpy as np

import cummins
from _timing import SHARED_DATA, timed
from cummins.excitation_model import fit_excitation
from cummins.excitation_model.fit import nrmse
from cummins.io.openfast import read_openfast_ssexctn
from cummins.io.openfast_excitation import excitation_model_from_ssexctn, write_openfast_ssexctn
from cummins.radiation.fit import fit_radiation
from cummins.seakeeping.excitation import excitation_force
from cummins.seakeeping.waves import harmonic_sum, irregular_waves, wave_spectrum

ROOT = Path(__file__).resolve().parents[1]
#: (data, headings in degrees or None for all of the data's)
CASES = {
    "OC3 spar (WAMIT)": (SHARED_DATA / "corpus" / "WEIS" / "ss_fitting_OC3_spar" / "spar.1", None),
    "MSS tanker (WAMIT)": (SHARED_DATA / "mss" / "tanker" / "tanker.1", [0, 45, 90, 135, 180]),
    "semisub (Capytaine)": (ROOT / "tests" / "data" / "semisub_capytaine.nc", None),
}


def read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path)


def band(f):
    return np.abs(f) > 0.01 * np.abs(f).max()


def case(label: str, path: Path, headings) -> None:
    ds = read(path)
    radiation_s, radiation = timed(lambda: fit_radiation(ds), repeat=1)
    directions = None if headings is None else np.radians(headings)
    n_headings = ds.sizes["wave_direction"] if headings is None else len(headings)
    excitation_s, model = timed(lambda: fit_excitation(ds, directions), repeat=1)
    per_heading = excitation_s / n_headings
    worst = max(m.metrics.get("nrmse", 0.0) for m in model.models)
    print(f"{label}: {ds.sizes['omega']} frequencies, {n_headings} headings")
    print(f"  radiation fit   {radiation_s:7.2f} s, {radiation.total_order} states")
    print(
        f"  excitation fit  {excitation_s:7.2f} s for {n_headings} headings: "
        f"{per_heading:.3f} s per 6 DOFs x heading (ratio to the radiation fit "
        f"{per_heading / radiation_s:.2f}); states per heading "
        f"{int(model.orders.sum(axis=1).min())}-{int(model.orders.sum(axis=1).max())}, "
        f"worst NRMSE {worst:.3f}, {len(model.attrs['failures'])} DOF x heading above target"
    )


def spar_against_ss_fitting() -> None:
    folder = SHARED_DATA / "corpus" / "WEIS" / "ss_fitting_OC3_spar"
    ds = read(folder / "spar.1")
    model = fit_excitation(ds, [0.0])
    with tempfile.TemporaryDirectory() as tmp:
        path = write_openfast_ssexctn(model, Path(tmp) / "spar.ssexctn")
        ours = read_openfast_ssexctn(path)
    theirs = read_openfast_ssexctn(folder / "spar.ssexctn")
    w = ds.omega.values
    data = ds.excitation_force.sel(wave_direction=0.0).transpose("omega", "influenced_dof").values
    print(
        f"OC3 spar, 0 deg: cummins {ours.n_states} states, SS_Excitation_Fitting {theirs.n_states}"
    )
    for d, name in ((0, "surge"), (2, "heave"), (4, "pitch")):
        mine = nrmse(ours.frequency_response(w)[:, d], data[:, d], band(data[:, d]))
        best = min(
            nrmse(theirs.frequency_response(w, time_offset=tc)[:, d], data[:, d], band(data[:, d]))
            for tc in np.arange(0.0, 40.01, 0.5)
        )
        print(
            f"  {name:6s} states {ours.states_per_dof[d]:2d} vs {theirs.states_per_dof[d]:2d}, "
            f"NRMSE {mine:.4f} vs {best:.4f} (theirs at its best t_c)"
        )
    replay = excitation_model_from_ssexctn(ours)
    waves = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0), duration=3600, n_components=300, direction=0.0,
        seed=3, omega_min=w[0], omega_max=w[-1],
    )  # fmt: skip
    t = np.arange(-600.0, 3600.0 + replay.delays[0] + 0.1, 0.1)
    seconds, (times, force) = timed(
        lambda: replay.force(t, harmonic_sum(t, waves.omega, waves.complex_amplitude), 0),
        repeat=1,
    )
    hour = times >= 0
    reference = excitation_force(ds, waves, times[hour])
    r = [np.corrcoef(force[hour, d], reference[:, d])[0, 1] for d in (0, 2, 4)]
    print(
        f"  1 hour (JONSWAP Hs 4 m, Tp 10 s) from the .ssexctn against excitation_force: "
        f"r = {r[0]:.5f}, {r[1]:.5f}, {r[2]:.5f} (surge, heave, pitch); the state-space run "
        f"took {seconds:.3f} s"
    )


def main() -> None:
    for label, (path, headings) in CASES.items():
        case(label, path, headings)
    spar_against_ss_fitting()


if __name__ == "__main__":
    main()
