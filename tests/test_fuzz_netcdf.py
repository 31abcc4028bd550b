"""Damaged Capytaine NetCDF, cummins NetCDF-4 and BEMIO .h5 files: refused, warned, or
read alike (the oracle of tests/_mutate.py).

What a reader cannot see: a NetCDF-3 (or checksum-free HDF5) file has no checksum, so a
flipped mantissa byte inside ``added_mass`` or ``radiation_damping`` of a Capytaine file
is a different, equally plausible number (measured on the sphere file: 20 of 40 flipped
copies read as different numbers before any check, those in A and B payload remain).
The rest of a Capytaine file is checked: structure, labels, coordinates against the
derived ``freq``/``period``, ``excitation_force`` against ``Froude_Krylov_force +
diffraction_force`` (Capytaine writes their exact sum), NaN patterns, magnitudes, and the
legacy exporter's KH files against the stiffness. The Capytaine cases below therefore
damage the whole file by truncation and every byte outside the A and B payload by
flips. BEMIO files repeat every coefficient (``components``/``comps``, mag/phase, T/w),
and files cummins writes carry Fletcher-32 checksums: there the whole file is fuzzed.
"""

from __future__ import annotations

import random
from pathlib import Path

import numpy as np
import pytest
import scipy.io

import cummins
from _mutate import Damager, FuzzCase, failures, mutate_bytes

COER = "corpus/WEC-Sim/capytaine_COER_comp"
COER_NC = "outputs/coer_comp_hydrodynamics.nc"

CASES = [
    FuzzCase(
        "bemio-matlab-wavestar",
        "corpus/WEC-Sim_Applications/wamit_wavestar_NMPC_with_h5",
        "wavestar.h5",
        ("wavestar.h5",),
        quantities=(
            "wavestar.h5:body1/hydro_coeffs/added_mass/all",
            "wavestar.h5:body1/hydro_coeffs/radiation_damping/all",
            "wavestar.h5:body1/hydro_coeffs/excitation/re+body1/hydro_coeffs/excitation/im:scale",
            "wavestar.h5:body1/hydro_coeffs/linear_restoring_stiffness:negate",
        ),
    ),
    FuzzCase(
        "bemio-python-oswec",
        "corpus/WEC-Sim/wamit_OSWEC_2015_with_bemio_h5",
        "oswec.h5",
        ("oswec.h5",),
        quantities=(
            "oswec.h5:body1/hydro_coeffs/added_mass/all",
            "oswec.h5:body1/hydro_coeffs/radiation_damping/all",
            "oswec.h5:body1/hydro_coeffs/excitation/re+body1/hydro_coeffs/excitation/im:scale",
            "oswec.h5:body1/hydro_coeffs/linear_restoring_stiffness:negate",
        ),
    ),
    FuzzCase("capytaine-legacy-text", COER, ".", ("outputs/KH.dat", "outputs/Hydrostatics.dat")),
]
#: Files cummins wrote (NetCDF-4 and BEMIO, with checksums), made in a temporary root.
WRITTEN = [
    FuzzCase(
        "cummins-netcdf4",
        "written",
        "tanker.nc",
        ("tanker.nc",),
        quantities=(
            "tanker.nc:omega",
            "tanker.nc:added_mass+added_mass_inf+added_mass_zero",
            "tanker.nc:radiation_damping",
            "tanker.nc:excitation_force:scale",
            "tanker.nc:inertia_matrix",
            "tanker.nc:hydrostatic_stiffness",
            "tanker.nc:additional_damping:negate",
        ),
    ),
    FuzzCase(
        "cummins-bemio",
        "written",
        "tanker.h5",
        ("tanker.h5",),
        quantities=(
            "tanker.h5:body1/hydro_coeffs/added_mass/all",
            "tanker.h5:body1/hydro_coeffs/radiation_damping/all",
            "tanker.h5:body1/hydro_coeffs/excitation/re+body1/hydro_coeffs/excitation/im:scale",
            "tanker.h5:body1/hydro_coeffs/linear_restoring_stiffness:negate",
        ),
    ),
]


@pytest.fixture(scope="module")
def written_root(tmp_path_factory, shared_data):
    root = tmp_path_factory.mktemp("fuzz")
    folder = root / "written"
    folder.mkdir()
    ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.1")
    cummins.write(ds, folder / "tanker.nc")
    cummins.write(ds, folder / "tanker.h5")
    return root


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


@pytest.mark.parametrize("case", WRITTEN, ids=lambda c: c.name)
def test_damaged_files_cummins_wrote_are_refused_or_read_alike(written_root, case):
    with Damager(written_root, case) as damager:
        assert not failures(damager.cases(40, seed=11))


@pytest.mark.parametrize("case", WRITTEN, ids=lambda c: c.name)
def test_scaled_quantities_of_files_cummins_wrote_are_not_read_silently(written_root, case):
    """Every declared quantity, every operation: the checksums are rewritten with the
    numbers (h5py), so only the physics can tell."""
    with Damager(written_root, case) as damager:
        assert not failures(damager.quantity_cases())


def _payload_ranges(path: Path) -> list[range]:
    """Byte ranges of the added_mass and radiation_damping arrays in a NetCDF-3 file."""
    data = path.read_bytes()
    ranges = []
    with scipy.io.netcdf_file(path, "r", mmap=False) as f:
        for name in ("added_mass", "radiation_damping"):
            raw = f.variables[name].data.tobytes()
            start = data.find(raw)
            assert start >= 0
            ranges.append(range(start, start + len(raw)))
    return ranges


def test_damaged_capytaine_netcdf3_outside_the_unprotected_payload(shared_data):
    source = shared_data / COER / COER_NC
    data = source.read_bytes()
    protected_out = _payload_ranges(source)
    rng = random.Random(5)
    case = FuzzCase("capytaine-nc3", COER, ".", (COER_NC,))
    outcomes = []
    with Damager(shared_data, case) as damager:
        while len(outcomes) < 50:
            damaged = mutate_bytes(data, rng)
            if len(damaged) == len(data):  # a flip: keep it outside the A and B payload
                flipped = np.flatnonzero(
                    np.frombuffer(damaged, np.uint8) != np.frombuffer(data, np.uint8)
                )
                if any(k in r for k in flipped for r in protected_out):
                    continue
            outcomes.append((COER_NC, "bytes", damager.judge(COER_NC, damaged)))
    assert not failures(outcomes)


def _float_datasets(f) -> list:
    import h5py

    found = []

    def visit(_, obj):
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f" and obj.ndim > 0:
            found.append(obj)

    f.visititems(visit)
    return found


def test_written_files_are_checksummed(written_root):
    import h5py

    for name in ("tanker.nc", "tanker.h5"):
        with h5py.File(written_root / "written" / name) as f:
            datasets = _float_datasets(f)
            assert datasets and all(d.fletcher32 for d in datasets), name
