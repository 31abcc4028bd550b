"""Damaged copies of the ShipX/VERES and MSS .mat files must be refused, warned about or
read alike (the oracle of tests/_mutate.py); re-encodings (BOM, CRLF, CR, tabs) read
identically.

A VERES transfer-function file (.re8, .re1) lists, per heading and frequency, six rows
labelled 1…6 by DOF: the reader checks the labels and the frequency and heading lines
against each other, but the same DOF's rows of two frequency blocks swapped leave a file
that is well-formed in every respect (1 in 40 damaged copies of the supply's .re8): such
swaps are ``swap_blind``.
"""

from __future__ import annotations

import pytest

from _mutate import Damager, FuzzCase, failures

CASES = [
    FuzzCase(
        "veres-supply",
        "mss/supply",
        "input.re7",
        ("input.re7", "input.re8", "input.re1"),
        format="veres",
        swap_blind=("input.re8", "input.re1"),
    ),
    FuzzCase("mss-supply-mat", "mss/supply", "supply.mat", ("supply.mat",), format="mss"),
    FuzzCase("mss-s175-mat", "mss/s175", "s175.mat", ("s175.mat",), format="mss"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_damaged_copies_are_refused_or_read_alike(shared_data, case):
    with Damager(shared_data, case) as damager:
        assert not failures(damager.cases(40, seed=5))


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_reencoded_copies_read_identically(shared_data, case):
    with Damager(shared_data, case) as damager:
        assert not failures(damager.encodings())
