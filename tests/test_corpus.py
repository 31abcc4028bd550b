"""Every real case users bring reads, and yields the equation of motion its files hold.

The 32 cases of ``../shared/data/corpus`` (see its README) are passed to
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
WITH_MASS_PROPERTIES: tuple[str, ...] = ()


def _read(path: Path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path)


def test_the_manifest_lists_32_cases():
    assert len(CASES) == 32, CASES


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
    of the data: both succeed, and the run is finite."""
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
    assert run.exit_code == 0, run.output
    assert "Traceback" not in run.output
