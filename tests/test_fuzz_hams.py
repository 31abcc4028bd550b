"""Damaged and re-encoded copies of a HAMS project's inputs, ``Input/ControlFile.in``
and ``Input/Hydrostatic.in``, read through :func:`cummins.read` of the project folder
(the oracle of ``tests/_mutate.py``). The project's WAMIT-format output is fuzzed in
``tests/test_fuzz_wamit.py``.

What the reader checks: ControlFile.in values finite, three coordinates for the centre,
an integer output frequency type, and the water depth, reference length and centre
against those the run's own Hydrostar_format headers print; Hydrostatic.in blocks
present once each in HAMS's reading order, its fixed ``E12.5`` numbers not cut, and
matrices a user could have given (a rigid body's mass matrix, dissipative damping,
near-symmetric restoring, the hydrostatic restoring equal to the run's ``.hst``, which
HAMS writes from it); implausible matrices are a warning and none of the file's
matrices is read.

One damage is beyond any reader: the rows of the six 6×6 blocks carry no label (HAMS
reads them in order), so a row of a diagonal matrix swapped with the row at the same
place in another block (HywindSpar's external linear damping row 1, [1e5 0 0 0 0 0],
with the zero row 1 of its quadratic damping) leaves two plausible matrices. Of all
611 pairs of lines of HywindSpar's file swapped, 8 read so (231 refused, 372 warned);
of HAMS/Cylinder's 456, none. Swaps among the matrix rows (lines 4-37) are therefore
``swap_blind`` for HywindSpar.
"""

from __future__ import annotations

import shutil

import pytest

import cummins
from _mutate import Damager, FuzzCase, failures
from cummins import HydroDataError

INPUTS = ("Input/Hydrostatic.in", "Input/ControlFile.in")

CASES = [
    FuzzCase(
        "hams-inputs-cylinder",
        "corpus/HAMS/Cylinder",
        ".",
        INPUTS,
        removable=("Input/Hydrostatic.in",),
        quantities=("Input/Hydrostatic.in:3", "Input/Hydrostatic.in:1::1"),
    ),
    FuzzCase(
        "hams-inputs-hywind-spar",
        "corpus/HAMS/HywindSpar",
        ".",
        INPUTS,
        swap_blind=("Input/Hydrostatic.in:4-37",),
        removable=("Input/Hydrostatic.in",),
        quantities=("Input/Hydrostatic.in:3", "Input/Hydrostatic.in:1::1"),
    ),
]


#: Damaged copies per case (HAMS/Cylinder reads in 0.05 s, HywindSpar in 0.006 s).
COUNT = {"hams-inputs-cylinder": 150, "hams-inputs-hywind-spar": 200}


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_damaged_copies_are_refused_or_read_alike(shared_data, case):
    with Damager(shared_data, case) as damager:
        outcomes = list(damager.cases(COUNT[case.name], seed=7))
    assert not failures(outcomes)
    assert sum(o.kind == "error" for _, _, o in outcomes) >= 50  # the checks do run


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


def _edited(shared_data, tmp_path, name, edit):
    project = tmp_path / "Cylinder"
    shutil.copytree(shared_data / "corpus/HAMS/Cylinder", project)
    path = project / "Input" / name
    path.chmod(0o644)
    lines = path.read_text().splitlines()
    edit(lines)
    path.write_text("\n".join(lines) + "\n")
    return project


def test_a_depth_the_run_did_not_use_is_refused(shared_data, tmp_path):
    """'Waterdepth  10.D0' cut to 'Waterdepth  1': the run's headers print 10 m."""

    def cut(lines):
        assert lines[2].split()[:2] == ["Waterdepth", "10.D0"]
        lines[2] = "   Waterdepth  1"

    project = _edited(shared_data, tmp_path, "ControlFile.in", cut)
    with pytest.raises(HydroDataError, match=r"ControlFile.in, line 3: Waterdepth is 1 m here"):
        cummins.read(project)


def test_a_cut_matrix_number_is_refused(shared_data, tmp_path):
    """The yaw inertia '0.11931E+04' cut to '0.1193' (the last line of the mass matrix)."""

    def cut(lines):
        assert lines[8].endswith("0.11931E+04")
        lines[8] = lines[8][: -len("0.11931E+04")] + "0.1193"

    project = _edited(shared_data, tmp_path, "Hydrostatic.in", cut)
    with pytest.raises(HydroDataError, match=r"Hydrostatic.in, line 9: the number '0.1193'"):
        cummins.read(project)
