"""Damaged and re-encoded copies of real NEMOH runs (the oracle of ``tests/_mutate.py``).

A damaged file must raise ``HydroDataError``, warn (``HydroDataWarning``, saying what
was lost) or read exactly the undamaged numbers; BOM, CRLF, CR-only line ends and tabs
must read identically. Cases: the WEC-Sim cylinder (v3, one body), the OC3 spar (v3,
QTF run, ``Mechanics/``, a ``Nemoh.cal`` edited after the run), the bemio two cubes
(v2, two bodies, ``IRF.tec``, hydrostatics files of another mesh). 60 damaged copies
per case here (~3 s each case); ``benchmarks/fuzz_readers.py 500 1 nemoh`` runs more.

One damage is beyond any reader: NEMOH wraps a Tecplot row of more than ten values over
several lines, and two continuation lines (no frequency on them) swapped leave no
structural trace; the solver's own asymmetry of the couplings (|A_ij - A_ji| up to 2x
the larger of the two in the OSWEC and COER runs) is too large for a symmetry test to
tell. Such swaps (about 1 in 300 damaged copies of the OC3 spar) are left out of the
rule for the files with wrapped rows (``swap_blind``).
"""

from __future__ import annotations

import pytest

from _mutate import Damager, FuzzCase, failures

CASES = [
    FuzzCase(
        "nemoh-v3-cylinder",
        "wecsim/cylinder/cylinder_nemoh",
        "Nemoh.cal",
        (
            "Nemoh.cal",
            "KH.dat",
            "Hydrostatics.dat",
            "RadiationCoefficients.tec",
            "ExcitationForce.tec",
            "FKForce.tec",
        ),
        format="nemoh",
        removable=("KH.dat", "Hydrostatics.dat"),
        quantities=(
            "RadiationCoefficients.tec:1",  # ω
            "RadiationCoefficients.tec:2::2",  # A
            "RadiationCoefficients.tec:3::2",  # B
            "ExcitationForce.tec:2::2:scale",  # |X|
            "KH.dat:3:negate",  # no inertia in the run: C's scale has nothing to meet
        ),
    ),
    FuzzCase(
        "nemoh-v3-qtf-oc3-spar",
        "corpus/WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar",
        ".",
        (
            "Nemoh.cal",
            "Mechanics/Inertia.dat",
            "Mechanics/Km.dat",
            "Mechanics/Kh.dat",
            "Mesh/KH.dat",
            "Mesh/Hydrostatics.dat",
            "results/RadiationCoefficients.tec",
            "results/ExcitationForce.tec",
            "results/index.dat",
        ),
        swap_blind=("results/RadiationCoefficients.tec",),
        removable=("Mesh/KH.dat", "Mesh/Hydrostatics.dat"),
        quantities=(
            "results/RadiationCoefficients.tec:2::2",
            "results/RadiationCoefficients.tec:3::2",
            "results/ExcitationForce.tec:2::2:scale",
            "Mechanics/Inertia.dat:1::1",  # the whole matrix
            "Mechanics/Kh.dat:3",
        ),
    ),
    FuzzCase(
        "nemoh-v2-two-bodies",
        "corpus/bemio/nemoh_two_body",
        ".",
        (
            "Nemoh.cal",
            "Mesh/KH_0.dat",
            "Mesh/Hydrostatics_1.dat",
            "Results/RadiationCoefficients.tec",
            "Results/FKForce.tec",
            "Results/DiffractionForce.tec",
            "Results/IRF.tec",
        ),
        swap_blind=("Results/RadiationCoefficients.tec", "Results/IRF.tec"),
        removable=("Mesh/KH_0.dat", "Mesh/Hydrostatics_1.dat"),
        quantities=(
            "Results/RadiationCoefficients.tec:2::2",
            "Results/RadiationCoefficients.tec:3::2",
        ),
    ),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_damaged_copies_are_refused_or_read_alike(shared_data, case):
    with Damager(shared_data, case) as damager:
        assert not failures(damager.cases(60, seed=7))


@pytest.mark.filterwarnings("ignore:.*IRF.tec.*:UserWarning")
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
