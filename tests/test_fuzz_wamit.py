"""Damaged copies of real WAMIT and HAMS runs are refused, warned about, or read alike
(the oracle of tests/_mutate.py); re-encodings read identically.

Runs given as numeric files (``.1``, ``.3``, ``.hst``, with ``.frc``, ``.cfg``) and runs
given only as the ``.out`` log (the WaveBot, WAMIT 7.201, 456 periods; the plate,
WAMIT 7.063, 24 headings), read by :func:`cummins.io.wamit.read_wamit_out`: its tables
are in fixed columns, so a row that ends before the others of its table is a cut line
(a phase in whole degrees, "-177" cut to "-17", would otherwise pass), and every row
holds as many numbers as the others of its kind of table (a garbled "1.2.3" reads as
two numbers, 1.2 and 0.3).

One damage is beyond any reader of a ``.out``: its blocks are told apart only by their
"Wave period" and "Wave Heading" lines, so a row swapped with the row of the same label
(DOF index I, or I J) in another block leaves a well-formed log (3 in 300 damaged copies
of the plate, whose log has no Haskind forces or RAOs to compare with). Such swaps are
``swap_blind`` (``file:same-label``); any other swap is judged as usual.
"""

from __future__ import annotations

import shutil
import warnings

import pytest

import cummins
from _mutate import Damager, FuzzCase, failures

CASES = [
    FuzzCase(
        "tanker",
        "mss/tanker",
        "tanker.1",
        ("tanker.1", "tanker.3", "tanker.hst"),
        quantities=(
            "tanker.1:1",  # the periods
            "tanker.1:4",  # A (and the limit rows)
            "tanker.1:5",  # B
            "tanker.3:4+6+7:scale",  # |X|, Re X, Im X
            "tanker.hst:3",  # C (the run has its inertia: .frc, .out)
        ),
    ),
    FuzzCase(
        "sphere",
        "wecsim/sphere",
        "sphere.1",
        ("sphere.1", "sphere.3", "sphere.hst"),
        quantities=(
            "sphere.1:1",
            "sphere.1:4",
            "sphere.1:5",
            "sphere.3:4+6+7:scale",
            "sphere.hst:3:negate",  # no inertia in the run: C's scale has nothing to meet
        ),
    ),
    FuzzCase(
        "barge_gbm",
        "corpus/WEC-Sim_Applications/wamit_generalized_modes_barge",
        "barge.1",
        ("barge.hst", "barge.frc", "barge.cfg"),
        quantities=("barge.hst:3",),
    ),
    FuzzCase(
        "hams_hywind",
        "corpus/HAMS/HywindSpar",
        ".",
        ("Output_Benchmark/Wamit_format/Buoy.1", "Output_Benchmark/Wamit_format/Buoy.3"),
        # two frequencies: no Kramers-Kronig or Haskind relation; the wave numbers
        # against the size remain
        quantities=("Output_Benchmark/Wamit_format/Buoy.1:1",),
    ),
    FuzzCase(
        "iti_barge_crlf",
        "corpus/ROSCO/wamit_ITI_barge_5MW_Baseline",
        "Barge.1",
        ("Barge.1", "Barge.hst"),
        quantities=("Barge.1:1", "Barge.1:4", "Barge.1:5", "Barge.hst:3:negate"),
    ),
    FuzzCase(
        "wavebot_out_only",
        "corpus/WEC-Sim_Applications/wamit_WaveBot",
        "waveBotBuoy.out",
        ("waveBotBuoy.out",),
        swap_blind=("waveBotBuoy.out:same-label",),
    ),
    FuzzCase(
        "plate_out_only_24_headings",
        "corpus/bemio/wamit_plate_24headings",
        "plate.out",
        ("plate.out",),
        swap_blind=("plate.out:same-label",),
    ),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_damaged_copies_are_refused_or_read_alike(shared_data, case):
    with Damager(shared_data, case) as damager:
        assert not failures(damager.cases(40, seed=7))


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_reencoded_copies_read_identically(shared_data, case):
    with Damager(shared_data, case) as damager:
        assert not failures(damager.encodings())


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_scaled_quantities_and_emptied_or_removed_files_are_not_read_silently(shared_data, case):
    """Four seeded quantities scaled by 10^±3 or negated (FuzzCase.quantities), every
    target emptied, every removable companion removed (issue 31)."""
    with Damager(shared_data, case) as damager:
        assert not failures(damager.quantity_cases(4, seed=5))


def test_a_cut_number_in_the_iti_barge_hst_is_named(shared_data, tmp_path):
    """C33 '1.600000E+03' of Barge.hst (line 15) cut to '1.6': the run reads, without
    the hydrostatics, and the warning names the line."""
    run = tmp_path / "barge"
    shutil.copytree(shared_data / "corpus/ROSCO/wamit_ITI_barge_5MW_Baseline", run)
    hst = run / "Barge.hst"
    hst.chmod(0o644)
    lines = hst.read_text().splitlines()
    assert lines[14].split() == ["3", "3", "1.600000E+03"]
    lines[14] = lines[14].replace("1.600000E+03", "1.6")
    hst.write_text("\n".join(lines) + "\n")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = cummins.read(run / "Barge.1")
    messages = [str(w.message) for w in caught if issubclass(w.category, cummins.HydroDataWarning)]
    assert any("Barge.hst, line 15" in m and "'1.6' is shorter" in m for m in messages), messages
    assert "hydrostatic_stiffness" not in ds


def test_a_cut_phase_in_an_out_log_is_named(shared_data, tmp_path):
    """The plate's diffraction phase '-177' (heading 0, DOF 2) cut to '-17'."""
    run = tmp_path / "plate"
    shutil.copytree(shared_data / "corpus/bemio/wamit_plate_24headings", run)
    out = run / "plate.out"
    out.chmod(0o644)
    lines = out.read_text().splitlines()
    assert lines[324].split() == ["2", "2.151526E-05", "-177"]
    lines[324] = lines[324][:-1]
    out.write_text("\n".join(lines) + "\n")
    with pytest.raises(cummins.HydroDataError, match=r"plate.out, line 325: this row ends at"):
        cummins.read(out)


def test_a_number_garbled_in_two_in_an_out_log_is_named(shared_data, tmp_path):
    """WaveBot's damping B(5,5) '5.533032E-03' garbled to '1.2.3' (line 20333), which
    reads as two numbers, 1.2 and 0.3: a row of 5 numbers among rows of 4."""
    run = tmp_path / "wavebot"
    shutil.copytree(shared_data / "corpus/WEC-Sim_Applications/wamit_WaveBot", run)
    out = run / "waveBotBuoy.out"
    out.chmod(0o644)
    lines = out.read_text().splitlines()
    assert lines[20332].split() == ["5", "5", "3.589608E-02", "5.533032E-03"]
    lines[20332] = "5  5  3.589608E-02  1.2.3"
    out.write_text("\n".join(lines) + "\n")
    with pytest.raises(cummins.HydroDataError, match=r"waveBotBuoy.out, line 20333: expected 4"):
        cummins.read(out)
