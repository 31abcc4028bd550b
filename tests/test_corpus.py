"""Every real case users bring reads, and yields the equation of motion its files hold.

The 33 cases of ``../shared/data/corpus`` (see its README) are passed to
:func:`cummins.read` as a user would pass them: the case folder itself. Each reads, or
refuses with a ``CumminsError`` that names what is missing; never another exception.
Where the files hold the mass properties, the dataset has ``inertia_matrix``; where it
has inertia, restoring and excitation, ``cummins rao`` and ``cummins simulate`` run.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from conftest import SHARED_DATA
from cummins.cli import main

CORPUS = SHARED_DATA / "corpus"


def _case_names() -> list[str]:
    """Case folders (two levels down), listed from the corpus's manifest so that the
    parametrisation does not depend on the folder being present (the fixture decides
    whether a missing corpus fails or skips)."""
    manifest = CORPUS / "MANIFEST.sha256"
    if not manifest.exists():
        return []
    names = set()
    for line in manifest.read_text(encoding="utf-8").splitlines():
        parts = line.split(maxsplit=1)[-1].lstrip("*").lstrip("./").split("/")
        if len(parts) > 2:
            names.add("/".join(parts[:2]))
    return sorted(names)


CASES = _case_names()

#: Cases whose files hold the mass properties (the corpus README and the files say
#: which): each must read with an ``inertia_matrix``.
WITH_MASS_PROPERTIES: tuple[str, ...] = (
    "HAMS/Cylinder",  # Input/Hydrostatic.in
    "HAMS/DeepCwind",
    "HAMS/HywindSpar",
    "WEC-Sim/aqwa_19.1_PEND_hull",  # the .LIS mass and inertia table
    "WEC-Sim/capytaine_COER_comp",  # Capytaine's inertia_matrix
    "WEC-Sim/capytaine_OSWEC_flap",
    "WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar",  # Mechanics/Inertia.dat
    "WEC-Sim_Applications/aqwa_floating_OWC_AH1only",  # the .AH1 MASS section
    "WEC-Sim_Applications/wamit_generalized_modes_barge",  # .frc form 2, 10 x 10
    "WEC-Sim_Applications/wamit_mean_drift_sphere",  # .out volume and radii of gyration
)

#: Cases whose files give a mass (rho V) but radii of gyration of zero, WAMIT's
#: placeholder when nobody gave the rotational inertia: no inertia_matrix is made up,
#: and the history says what to give.
ZERO_RADII: tuple[str, ...] = (
    "WEC-Sim/wamit_COER_comp",
    "WEC-Sim_Applications/wamit_WaveBot",
    "WEC-Sim_Applications/wamit_wavestar_NMPC_with_h5",
    "bemio/wamit_WEC3_single_body",
    "bemio/wamit_plate_24headings",
)


def _read(path: Path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path)


def test_the_manifest_lists_33_cases():
    assert len(CASES) == 33, CASES


@pytest.mark.parametrize("name", CASES)
def test_case_reads_or_refuses_cleanly(corpus, name):
    """A dataset, or a CumminsError with a message naming the case's folder or file."""
    try:
        ds = _read(corpus / name)
    except cummins.CumminsError as exc:
        message = str(exc)
    else:
        _check_dataset(ds)
        return
    assert str(corpus / name) in message or Path(name).name in message, message


def _check_dataset(ds) -> None:
    cummins.validate(ds)
    assert ds.sizes["omega"] > 0
    labels = [str(d) for d in ds.influenced_dof.values]
    assert labels == [str(d) for d in ds.radiating_dof.values]
    assert len(set(labels)) == len(labels)


@pytest.mark.parametrize("name", WITH_MASS_PROPERTIES)
def test_case_with_mass_properties_has_its_inertia(corpus, name):
    ds = _read(corpus / name)
    assert "inertia_matrix" in ds, ds.attrs.get("history")
    m = ds.inertia_matrix.values
    assert np.allclose(m, m.T, rtol=0, atol=1e-9 * np.abs(m).max())
    assert np.all(np.linalg.eigvalsh(m) > 0)


@pytest.mark.parametrize("name", ZERO_RADII)
def test_case_with_placeholder_radii_says_what_to_give(corpus, name, tmp_path):
    """No inertia from zero radii; the history names the option, and with the radii
    given on the command line `cummins rao` runs (the mass defaults to ρ∇)."""
    ds = _read(corpus / name)
    assert "inertia_matrix" not in ds
    assert "--radii-of-gyration" in ds.attrs["history"]
    result = CliRunner().invoke(
        main, ["info", str(corpus / name), "--radii-of-gyration", "1", "1", "1"]
    )
    assert result.exit_code == 0, result.output
    assert "rho * volume" in result.output


#: Below this many frequencies a state-space model of the fluid memory cannot be fitted.
MIN_FREQUENCIES = 8


def _runnable() -> list[str]:
    """Cases with inertia, restoring and excitation (decided by reading them)."""
    out = []
    for name in CASES:
        try:
            ds = _read(CORPUS / name)
        except cummins.CumminsError:
            continue
        if {"inertia_matrix", "hydrostatic_stiffness", "excitation_force"} <= set(ds.data_vars):
            out.append(name)
    return out


@pytest.mark.parametrize("name", _runnable())
def test_rao_and_simulate_run_on_the_case(corpus, name, tmp_path):
    """`cummins rao` and a short regular-wave `cummins simulate` at a period and heading
    of the data: both succeed and the run is finite. A body the data make statically
    unstable (a negative roll or pitch restoring: the GBM barge's roll, the OSWEC flap's
    pitch, which a hinge holds in reality) is refused as unstable, naming the DOF, and
    runs once a spring of twice that stiffness is given with --external-stiffness, as a
    user would give the hinge or mooring."""
    ds = _read(corpus / name)
    if "forward_speed" in ds.dims:
        ds = ds.isel(forward_speed=0)
    w = ds.omega.values
    period = 2 * np.pi / w[len(w) // 3]
    heading = float(np.degrees(ds.wave_direction.values[0]))
    rao = CliRunner().invoke(main, ["rao", str(corpus / name), "-o", str(tmp_path / "r.nc")])
    assert rao.exit_code == 0, rao.output
    args = ["simulate", str(corpus / name), "--regular", "--wave-period", f"{period:.6g}",
            "--heading", f"{heading:g}", "--duration", f"{20 * period:.6g}",
            "--dt", f"{period / 40:.6g}", "-o", str(tmp_path / "run.nc")]  # fmt: skip
    run = CliRunner().invoke(main, args)
    assert "Traceback" not in run.output
    if ds.sizes["omega"] < MIN_FREQUENCIES:
        # HAMS's DeepCwind and HywindSpar test runs hold 3 and 2 frequencies: RAOs at
        # those, but no fluid-memory model can be identified from them
        assert run.exit_code != 0, run.output
        assert "frequencies" in run.output
        fit = CliRunner().invoke(main, ["fit", str(corpus / name), "-o", str(tmp_path / "m.nc")])
        assert fit.exit_code == 1 and "Traceback" not in fit.output
        n = ds.sizes["omega"]  # the message says how many there are
        assert f"the data hold {n} (" in fit.output or f"{n} frequencies are too few" in fit.output
        return
    labels = [str(d) for d in ds.influenced_dof.values]
    c = np.diag(ds.hydrostatic_stiffness.values).copy()
    if "additional_stiffness" in ds:
        c += np.diag(ds.additional_stiffness.values)
    negative = [k for k in range(len(labels)) if c[k] < 0]
    if negative:
        assert run.exit_code != 0, run.output
        assert "unstable" in run.output
        springs = [a for k in negative for a in ("--external-stiffness", labels[k], labels[k],
                                                  f"{-2 * c[k]:.6g}")]  # fmt: skip
        run = CliRunner().invoke(main, [*args, "--force", *springs])
    assert run.exit_code == 0, run.output


def test_oc3_spar_copies_of_weis_and_raft_agree(corpus):
    """The OC3 spar as WEIS ships it (CRLF, with the ω = 0/∞ rows and .hst) and as RAFT
    ships it (LF, limit rows removed, no .hst) read as the same body: the same labels,
    frequencies and numbers; A∞ only where its row is; the assumed constants said."""
    weis = _read(corpus / "WEIS" / "ss_fitting_OC3_spar")
    raft = _read(corpus / "RAFT" / "wamit_OC3_spar_no_A0_Ainf_rows")
    assert list(weis.influenced_dof.values) == list(raft.influenced_dof.values)
    np.testing.assert_array_equal(weis.omega.values, raft.omega.values)
    for name in ("added_mass", "radiation_damping", "excitation_force"):
        np.testing.assert_array_equal(weis[name].values, raft[name].values)
    assert "added_mass_inf" in weis and "added_mass_inf" not in raft
    for ds in (weis, raft):
        assert "rho = 1025 kg/m^3 (not recorded in the file: default" in ds.attrs["history"]
