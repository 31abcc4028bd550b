"""Damaged copies of the ShipX/VERES and MSS .mat files must be refused, warned about or
read alike (the oracle of tests/_mutate.py); re-encodings (BOM, CRLF, CR, tabs) read
identically.

A VERES transfer-function file (.re8, .re1) lists, per heading and frequency, six rows
labelled 1…6 by DOF: the reader checks the labels and the frequency and heading lines
against each other, but the same DOF's rows of two frequency blocks swapped leave a file
that is well-formed in every respect (1 in 40 damaged copies of the supply's .re8): such
swaps are ``swap_blind``.

The MSS ``RAO`` struct of the naval vessel (force RAOs for 5 speeds) is read by
:func:`cummins.io.mss.read_force_rao`, not :func:`cummins.read` (the ``reader`` hook of
the oracle); like every MSS ``.mat`` here it is zlib-compressed, so a flipped byte fails
the stream's checksum.
"""

from __future__ import annotations

import collections
import shutil

import pytest

import cummins
from _mutate import Damager, FuzzCase, failures
from cummins.io.mss import read_force_rao

CASES = [
    FuzzCase(
        "veres-supply",
        "mss/supply",
        "input.re7",
        ("input.re7", "input.re8", "input.re1"),
        format="veres",
        swap_blind=("input.re8", "input.re1"),
    ),
    FuzzCase(
        "mss-supply-mat",
        "mss/supply",
        "supply.mat",
        ("supply.mat",),
        format="mss",
        quantities=(
            "supply.mat:vessel.freqs",
            "supply.mat:vessel.A",
            "supply.mat:vessel.B",
            "supply.mat:vessel.MRB",
            "supply.mat:vessel.C",
            "supply.mat:vessel.forceRAO.amp:scale",
        ),
    ),
    FuzzCase(
        "mss-s175-mat",
        "mss/s175",
        "s175.mat",
        ("s175.mat",),
        format="mss",
        quantities=(
            "s175.mat:vessel.freqs",
            "s175.mat:vessel.A",
            "s175.mat:vessel.B",
            "s175.mat:vessel.MRB",
            "s175.mat:vessel.C",
            "s175.mat:vessel.forceRAO.amp:scale",
        ),
    ),
    FuzzCase(
        "mss-naval-vessel-force-rao",
        "corpus/MSS/navalvessel_forceRAO",
        "forceRAO_navalvessel.mat",
        ("forceRAO_navalvessel.mat",),
        reader=read_force_rao,
    ),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_damaged_copies_are_refused_or_read_alike(shared_data, case):
    with Damager(shared_data, case) as damager:
        assert not failures(damager.cases(40, seed=5))


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


def test_a_zero_speed_row_unlike_the_other_headings_is_named(shared_data, tmp_path):
    """The supply's .re7 (zero speed) repeats the same matrices for each of its 19
    headings; one row edited in the second heading's copy (line 1392: -0.12841295E+09
    made -0.12851295E+09) is refused, naming the line."""
    run = tmp_path / "supply"
    shutil.copytree(shared_data / "mss/supply", run)
    re7 = run / "input.re7"
    re7.chmod(0o644)
    lines = re7.read_text().splitlines()
    zero = "0.00000000E+00"
    row = f"  {zero}  {zero}  0.19462218E+08  {zero} -0.12841295E+09  {zero}"
    assert collections.Counter(lines)[row] == 19 and lines[1391] == row
    lines[1391] = row.replace("-0.12841295E+09", "-0.12851295E+09")
    re7.write_text("\n".join(lines) + "\n")
    with pytest.raises(cummins.HydroDataError, match=r"input.re7, line 1392: at zero speed"):
        cummins.read(run / "input.re7", format="veres")
