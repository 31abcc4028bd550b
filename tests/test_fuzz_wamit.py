"""Damaged copies of real WAMIT and HAMS runs are refused, warned about, or read alike
(the oracle of tests/_mutate.py); re-encodings read identically."""

from __future__ import annotations

import pytest

from _mutate import Damager, FuzzCase, failures

CASES = [
    FuzzCase("tanker", "mss/tanker", "tanker.1", ("tanker.1", "tanker.3", "tanker.hst")),
    FuzzCase("sphere", "wecsim/sphere", "sphere.1", ("sphere.1", "sphere.3", "sphere.hst")),
    FuzzCase(
        "barge_gbm",
        "corpus/WEC-Sim_Applications/wamit_generalized_modes_barge",
        "barge.1",
        ("barge.hst", "barge.frc", "barge.cfg"),
    ),
    FuzzCase(
        "hams_hywind",
        "corpus/HAMS/HywindSpar",
        ".",
        ("Output_Benchmark/Wamit_format/Buoy.1", "Output_Benchmark/Wamit_format/Buoy.3"),
    ),
    FuzzCase(
        "iti_barge_crlf",
        "corpus/ROSCO/wamit_ITI_barge_5MW_Baseline",
        "Barge.1",
        ("Barge.1",),  # Barge.hst is free-format: a cut number there is not noticed yet
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
