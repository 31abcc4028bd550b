"""Damaged and re-encoded copies of real second-order files (the oracle of ``tests/_mutate.py``).

A damaged QTF or mean-drift file must stop the run from reading (``HydroDataError``), or
leave the second-order data out with a ``HydroDataWarning`` that says so, or read
exactly the undamaged numbers; BOM, CRLF, CR-only line ends and tabs must read
identically. Cases: the OC4 semisubmersible's WAMIT ``.12d``/``.12s`` (a title line,
one triangle of 56 x 56 periods), the mean-drift sphere's ``.7``/``.8``/``.9`` (negative
mode indices, 200 periods), the OC3 spar's NEMOH ``OUT_QTFM_N_0.dat``/``OUT_QTFP_N_0.dat``
and the drift tables of the AQWA 19.1 PEND hull's listing (damaged inside those tables
only: the rest of the listing is ``test_fuzz_aqwa.py``'s).

Every row of these files is labelled (frequencies, headings and mode), so a swap of two
rows reads identically, except in the AQWA drift tables, whose rows carry only the
frequency: the row of one DOF's table swapped with the row of the same frequency in
another DOF's table leaves no trace (``_blind_aqwa_swap``), and is counted, not failed.
"""

from __future__ import annotations

import random

import pytest

from _mutate import TEXT_OPS, Damager, FuzzCase, Outcome, failures, mutate_text

CASES = [
    FuzzCase(
        "wamit-qtf-oc4-semi",
        "corpus/WEIS/ss_fitting_OC4_semi",
        "marin_semi.1",
        ("marin_semi.12d", "marin_semi.12s"),
    ),
    FuzzCase(
        "wamit-mean-drift-sphere",
        "corpus/WEC-Sim_Applications/wamit_mean_drift_sphere/outputFiles",
        "sphere.1",
        ("sphere.7", "sphere.8", "sphere.9"),
    ),
    FuzzCase(
        "nemoh-qtf-oc3-spar",
        "corpus/WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar",
        ".",
        ("results/QTF/OUT_QTFM_N_0.dat", "results/QTF/OUT_QTFP_N_0.dat"),
    ),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_damaged_copies_are_refused_or_read_alike(shared_data, case):
    with Damager(shared_data, case) as damager:
        outcomes = list(damager.cases(30, seed=11))
        assert not failures(outcomes)
        # the damage reached the second-order data: most copies are warned about
        assert sum(o.kind == "warned" for _, _, o in outcomes) >= 10


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_reencoded_copies_read_identically(shared_data, case):
    with Damager(shared_data, case) as damager:
        assert not failures(damager.encodings())


AQWA = FuzzCase("aqwa-lis-drift", "corpus/WEC-Sim/aqwa_19.1_PEND_hull", "19_1.LIS", ("19_1.LIS",))


def _drift_region(lines: list[str]) -> tuple[int, int]:
    """First and last line (0-based) of the listing's wave-drift tables."""
    marks = [i for i, line in enumerate(lines) if "W A V E - D R I F T" in line]
    last = marks[-1]
    while last < len(lines) and not lines[last].strip().startswith("YAW(RZ)"):
        last += 1
    end = last + 1
    while end < len(lines) and (lines[end].strip() == "" or lines[end].split()[0][0].isdigit()):
        end += 1
    return marks[0], end


def _blind_aqwa_swap(before: list[str], after: list[str]) -> bool:
    moved = [k for k, (x, y) in enumerate(zip(before, after, strict=False)) if x != y]
    if len(moved) != 2:
        return False
    a, b = (before[k].split() for k in moved)
    return bool(a) and bool(b) and len(a) == len(b) and a[0] == b[0]


def test_damaged_aqwa_drift_tables_are_refused_or_read_alike(shared_data):
    with Damager(shared_data, AQWA) as damager:
        assert "drift_force" in damager.original
        text = (damager.source / "19_1.LIS").read_text(encoding="utf-8", errors="replace")
        lines = text.splitlines()
        first, end = _drift_region(lines)
        rng = random.Random(5)
        outcomes = []
        for _ in range(40):
            op = rng.choice([op for op in TEXT_OPS if op != "truncate"])
            region = "\n".join(lines[first:end])
            damaged = mutate_text(region, op, rng).splitlines()
            new = lines[:first] + damaged + lines[end:]
            outcome = damager.judge("19_1.LIS", ("\n".join(new) + "\n").encode("utf-8"))
            if op == "swap" and outcome.kind == "different" and _blind_aqwa_swap(lines, new):
                outcome = Outcome("blind", outcome.detail)
            outcomes.append(("19_1.LIS", op, outcome))
        assert not failures(outcomes)
        assert sum(o.kind == "warned" for _, _, o in outcomes) >= 10


# --------------------------------------------------------------------------- AQWA .QTF

#: A synthetic AQWA 2023 R1 run (tests/_aqwa_layouts.py: the PEND hull's listing in the
#: 2023 layout, a .QTF of invented off-diagonal values): no AQWA .QTF is public under a
#: licence cummins can ship.
AQWA_QTF = FuzzCase("aqwa-qtf-synthetic", "2023", "19_1.LIS", ("19_1.QTF",))


@pytest.fixture(scope="module")
def aqwa_runs(shared_data, tmp_path_factory):
    from _aqwa_layouts import build_runs

    root = tmp_path_factory.mktemp("aqwa_qtf_runs")
    build_runs(shared_data, root)
    return root


def _record_row(lines: list[str], k: int) -> tuple[tuple[str, ...], int] | None:
    """(label 'structure direction i j', row 0-3) of line ``k`` of an AQWA .QTF."""
    for back in range(4):
        words = lines[k - back].split() if k - back >= 0 else []
        if len(words) >= 4 and all(w.isdigit() for w in words[:4]):
            return tuple(words[:4]), back
    return None


def _blind_qtf_swap(before: list[str], after: list[str]) -> bool:
    """Swaps no reader can see in an AQWA .QTF: the same row of a record and its mirror
    (Q(w_i, w_j) and Q(w_j, w_i): the mirror relations still hold, the Im Q- rows
    conjugate both records), or two lines of diagonal records Q(w, w) (they have no
    mirror: only their Im Q- row, zeros, is constrained, and a swap that moves a non-zero
    row into it is refused)."""
    moved = [k for k, (x, y) in enumerate(zip(before, after, strict=False)) if x != y]
    if len(moved) != 2:
        return False
    a, b = (_record_row(before, k) for k in moved)
    if a is None or b is None:
        return False
    (s1, h1, i1, j1), (s2, h2, i2, j2) = a[0], b[0]
    if i1 == j1 and i2 == j2:
        return True
    return a[1] == b[1] and (s1, h1, i1, j1) == (s2, h2, j2, i2) and i1 != j1


def test_damaged_aqwa_qtf_is_refused_or_read_alike(aqwa_runs):
    with Damager(aqwa_runs, AQWA_QTF) as damager:
        assert "qtf_difference" in damager.original
        text = (damager.source / "19_1.QTF").read_text()
        lines = text.splitlines()
        rng = random.Random(3)
        outcomes = []
        for _ in range(30):
            op = rng.choice(TEXT_OPS)
            damaged = mutate_text(text, op, rng)
            outcome = damager.judge("19_1.QTF", damaged.encode("utf-8"))
            if (
                op == "swap"
                and outcome.kind == "different"
                and _blind_qtf_swap(lines, damaged.splitlines())
            ):
                outcome = Outcome("blind", outcome.detail)
            outcomes.append(("19_1.QTF", op, outcome))
        assert not failures(outcomes)
        assert sum(o.kind == "warned" for _, _, o in outcomes) >= 10


def test_reencoded_aqwa_qtf_reads_identically(aqwa_runs):
    with Damager(aqwa_runs, AQWA_QTF) as damager:
        assert not failures(damager.encodings())
