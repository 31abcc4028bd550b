"""Damaged and re-encoded copies of OpenFAST SS_Fitting files (the oracle of
``tests/_mutate.py``): refused, warned about, or read alike.

Cases: the radiation ``.ss`` of the ITI barge (SS_Fitting v1.00.00aTD, 2013, CRLF) and
the OC3 spar (v1.00.01, 2021, tabs in the header); the excitation fits of the OC4
semisubmersible (``.ssexctn`` with a time offset, and the ``.ss`` that holds such a fit)
and of the OC3 spar (``.ssexctn``, "%Enabled DoFs" layout). The readers are
:func:`~cummins.io.openfast.read_openfast_ss` and
:func:`~cummins.io.openfast.read_openfast_ssexctn`; every number they return is judged.

What the readers check (``src/cummins/io/openfast.py``): HydroDyn's counts of lines
and states, integer headers, a header line that lost its ``%`` comment (a cut "10"
read as "1"), the fixed ``%e`` width of the matrix numbers, the state grouping of the
header (A block-diagonal by DOF, a radiation B driven by its DOF's velocity only, an
excitation C giving its DOF's force only), decaying blocks with an input and an
output; for a radiation model (warnings) K(0) = 0, Re K_jj >= 0 and K_ij = K_ji.
Measured over every pair of lines swapped (2221 pairs for the barge, 2201 for the spar
``.ss``): none reads silently as different numbers.

One damage is beyond any reader: an excitation fit has no such invariant, and its
matrix rows carry no label, so two rows of A, B or C of the same DOF's states swapped
leave a well-formed, stable model (of all pairs of lines swapped: 194 of 1275 in the
semisubmersible's ``.ssexctn``, 425 of 2463 in its ``.ss``, 1596 of 7747 in the spar's
``.ssexctn``; nearly all within B, a column of unlabelled numbers). Swaps within the
matrix rows of the excitation files are ``swap_blind`` (``file:first-last``); swaps
that touch the header are judged as usual.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from _mutate import Damager, FuzzCase, failures
from cummins import HydroDataError, HydroDataWarning
from cummins.io.openfast import read_openfast_ss, read_openfast_ssexctn


def radiation_ss(path: Path) -> xr.Dataset:
    """Every number :func:`read_openfast_ss` returns (the title is free text)."""
    ss = read_openfast_ss(path)
    return xr.Dataset(
        {
            "A": (("state", "state_"), ss.A),
            "B": (("state", "dof"), ss.B),
            "C": (("dof", "state_"), ss.C),
            "dof_flags": ("dof", ss.dof_flags),
            "states_per_dof": ("dof", ss.states_per_dof),
        }
    )


def excitation_ss(path: Path) -> xr.Dataset:
    """Every number :func:`read_openfast_ssexctn` returns (the title is free text)."""
    ss = read_openfast_ssexctn(path)
    flags = np.full(ss.C.shape[0], -1) if ss.dof_flags is None else ss.dof_flags
    return xr.Dataset(
        {
            "A": (("state", "state_"), ss.A),
            "B": ("state", ss.B),
            "C": (("dof", "state_"), ss.C),
            "dof_flags": ("dof", flags),
            "states_per_dof": ("dof", ss.states_per_dof),
            "heading": ss.heading,
            "time_offset": np.nan if ss.time_offset is None else ss.time_offset,
        }
    )


SEMI = "corpus/WEIS/ss_fitting_OC4_semi"
SPAR = "corpus/WEIS/ss_fitting_OC3_spar"
BARGE = "corpus/ROSCO/wamit_ITI_barge_5MW_Baseline"

CASES = [
    FuzzCase("openfast-ss-barge-2013", BARGE, "Barge.ss", ("Barge.ss",), reader=radiation_ss),
    FuzzCase("openfast-ss-spar-2021", SPAR, "spar.ss", ("spar.ss",), reader=radiation_ss),
    FuzzCase(
        "openfast-ssexctn-semi-time-offset",
        SEMI,
        "marin_semi.ssexctn",
        ("marin_semi.ssexctn",),
        reader=excitation_ss,
        swap_blind=("marin_semi.ssexctn:6-51",),  # 20 states: A 6-25, B 26-45, C 46-51
    ),
    FuzzCase(
        "openfast-ss-holding-an-excitation-fit",
        SEMI,
        "marin_semi.ss",
        ("marin_semi.ss",),
        reader=excitation_ss,
        swap_blind=("marin_semi.ss:6-71",),  # 30 states: A 6-35, B 36-65, C 66-71
    ),
    FuzzCase(
        "openfast-ssexctn-spar-enabled-dofs",
        SPAR,
        "spar.ssexctn",
        ("spar.ssexctn",),
        reader=excitation_ss,
        swap_blind=("spar.ssexctn:6-125",),  # 57 states: A 6-62, B 63-119, C 120-125
    ),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_damaged_copies_are_refused_or_read_alike(shared_data, case):
    with Damager(shared_data, case) as damager:
        outcomes = list(damager.cases(200, seed=7))
    assert not failures(outcomes)
    assert sum(o.kind == "error" for _, _, o in outcomes) >= 100  # the checks do run


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


def _swapped(path: Path, i: int, j: int, tmp_path: Path) -> Path:
    lines = path.read_text().splitlines()
    lines[i - 1], lines[j - 1] = lines[j - 1], lines[i - 1]
    out = tmp_path / path.name
    out.write_text("\n".join(lines) + "\n")
    return out


@pytest.mark.parametrize(
    ("lines", "message"),
    [
        ((35, 36), r"line 35: K\(1,1\) at ω = 0 is 0.77 of its peak"),  # B rows within a block
        (
            (65, 69),
            r"line 65: K\(1,5\) and K\(5,1\) differ by 1 of their peak",
        ),  # C of surge, pitch
        ((66, 68), r"line 66: the damping Re K\(2,2\)"),  # C rows of sway and roll
    ],
)
def test_swapped_rows_of_a_radiation_model_are_named(shared_data, tmp_path, lines, message):
    """The swaps no layout rule sees (ITI barge): K(0) = 0 and positive damping do.

    Measured: K11(0) = 0.77 of the peak |K11| (1e-16 in the file; limit 0.1), K15 and K51
    1.0 apart (0 in the file; limit 0.5), Re K22 down to -1.0 of its peak (-0.0073 in the
    file; limit -0.2)."""
    path = _swapped(shared_data / BARGE / "Barge.ss", *lines, tmp_path)
    with pytest.warns(HydroDataWarning, match=message):
        read_openfast_ss(path)


def test_a_cut_time_offset_is_refused(shared_data, tmp_path):
    """'10          %time offset (tc)' cut to '1' would read as t_c = 1 s."""
    source = shared_data / SEMI / "marin_semi.ssexctn"
    lines = source.read_text().splitlines()
    assert lines[2].startswith("10 ")
    lines[2] = "1"
    path = tmp_path / source.name
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=r"line 3: this header line has no '%' comment"):
        read_openfast_ssexctn(path)
