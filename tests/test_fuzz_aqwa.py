"""Damaged and re-encoded copies of real AQWA runs (the oracle of ``tests/_mutate.py``).

Cases: the WEC-Sim cylinder (``.LIS`` and ``.AH1`` file version 5, AQWA 2020 R1), the
PEND hull of AQWA 19.1 (``.LIS`` paged tables, ``.AH1`` file version 4), the floating
OWC of AQWA 2022 R1 (``.AH1`` version 5 alone, two structures). 50 damaged copies per
case here; ``benchmarks/fuzz_readers.py 500 1 aqwa`` runs more.

One damage is beyond any reader: the rows 2-6 of an ``.AH1`` record (a 6x6 block) carry
no label, so two of them swapped leave no structural trace; the reader refuses a row in
the wrong fixed format (a phase row among matrix rows, a cut number) and a matrix far
from symmetric, but AQWA's own coupling noise (asymmetry up to 0.69 of the scale
measured on these files) hides a swap of two noise rows. Such swaps (2 in 50 damaged
copies of the floating OWC) are left out of the rule for the ``.AH1`` files
(``swap_blind``); the ``.LIS`` labels every row, and has no such exception.
"""

from __future__ import annotations

import pytest

from _mutate import Damager, FuzzCase, failures

CASES = [
    FuzzCase("aqwa-lis-cylinder", "wecsim/cylinder_aqwa", "cylinder.LIS", ("cylinder.LIS",)),
    FuzzCase(
        "aqwa-ah1-v5-cylinder",
        "wecsim/cylinder_aqwa",
        "cylinder.AH1",
        ("cylinder.AH1",),
        swap_blind=("cylinder.AH1",),
    ),
    FuzzCase(
        "aqwa-lis-19.1-pend",
        "corpus/WEC-Sim/aqwa_19.1_PEND_hull",
        "19_1.LIS",
        ("19_1.LIS",),
    ),
    FuzzCase(
        "aqwa-ah1-v4-pend",
        "corpus/WEC-Sim/aqwa_19.1_PEND_hull",
        "19_1.AH1",
        ("19_1.AH1",),
        swap_blind=("19_1.AH1",),
    ),
    FuzzCase(
        "aqwa-ah1-v5-alone-two-bodies",
        "corpus/WEC-Sim_Applications/aqwa_floating_OWC_AH1only",
        ".",
        ("floatingOWC.AH1",),
        swap_blind=("floatingOWC.AH1",),
    ),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_damaged_copies_are_refused_or_read_alike(shared_data, case):
    with Damager(shared_data, case) as damager:
        assert not failures(damager.cases(50, seed=7))


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


#: Synthetic AQWA 2023 R1 listings (tests/_aqwa_layouts.py: the PEND hull's numbers in the
#: 2023 layout, one structure, and with a second structure, its copy moved 3 m): no
#: listing of that layout is public under a licence cummins can ship. The .QTF beside
#: is test_fuzz_second_order.py's. A matrix row (X … RZ) swapped with the same row of
#: another frequency's matrix is refused when it leaves the matrix far from symmetric,
#: and invisible when the two matrices are nearly equal: such swaps are counted blind
#: (``same-label``), here as in any listing.
_BLIND = ("19_1.LIS:same-label",)
LAYOUT_CASES = [
    FuzzCase("aqwa-lis-2023-layout", "2023", "19_1.LIS", ("19_1.LIS",), swap_blind=_BLIND),
    FuzzCase(
        "aqwa-lis-2023-two-structures", "2023x2", "19_1.LIS", ("19_1.LIS",), swap_blind=_BLIND
    ),
    FuzzCase(
        "aqwa-lis-19.1-two-structures", "19.1x2", "19_1.LIS", ("19_1.LIS",), swap_blind=_BLIND
    ),
]


@pytest.fixture(scope="module")
def layout_runs(shared_data, tmp_path_factory):
    from _aqwa_layouts import build_runs

    root = tmp_path_factory.mktemp("aqwa_layout_runs")
    build_runs(shared_data, root)
    return root


@pytest.mark.parametrize("case", LAYOUT_CASES, ids=lambda c: c.name)
def test_damaged_listings_of_other_layouts_are_refused_or_read_alike(layout_runs, case):
    with Damager(layout_runs, case) as damager:
        assert not failures(damager.cases(25, seed=13))
