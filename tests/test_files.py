"""The files a call reads and writes (``cummins.files``): the companion files a read uses
are recorded, an output never replaces an input (hard links included), and outputs are
written through unique temporary files, so two writers of one path do not collide
(issue 31: two ``cummins fit`` runs writing one model both failed, "unable to lock
file", on a shared temporary name).
"""

from __future__ import annotations

import multiprocessing
import os
import shutil

import pytest

import cummins
from cummins.errors import ArgumentError
from cummins.files import (
    files_read,
    is_hdf5,
    refuse_overwriting_inputs,
    replacing,
    same_file,
)


def test_a_wamit_read_records_every_companion_file_it_takes_numbers_from(tmp_path):
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, tmp_path / f.name)
    (tmp_path / "tanker.txt").write_text("a note beside the run\n")
    with files_read() as used:
        ds = cummins.read(tmp_path / "tanker.1")
    names = {p.name for p in used}
    assert names == {"tanker.1", "tanker.3", "tanker.hst", "tanker.frc", "tanker.out"}
    assert "hydrostatic_stiffness" in ds and "inertia_matrix" in ds


def test_an_output_on_an_input_is_refused_through_a_hard_link(tmp_path):
    source = tmp_path / "run.hst"
    source.write_text("1 1 1.0\n")
    link = tmp_path / "elsewhere.nc"
    os.link(source, link)
    assert same_file(link, source)
    with pytest.raises(ArgumentError, match=r"-o .*elsewhere.nc is a file this command reads"):
        refuse_overwriting_inputs([link], [source], labels=["-o"])
    refuse_overwriting_inputs([tmp_path / "new.nc"], [source])  # a new file is no input


def test_two_outputs_on_one_file_are_refused(tmp_path):
    with pytest.raises(ArgumentError, match=r"--output m\.nc and --json m\.nc name one file"):
        refuse_overwriting_inputs(["m.nc", "./m.nc"], [], labels=["--output", "--json"])


def test_a_failed_write_leaves_the_earlier_file_and_no_temporary(tmp_path):
    target = tmp_path / "model.nc"
    target.write_text("earlier result")

    def fail() -> None:
        with replacing(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("the fit failed")

    with pytest.raises(RuntimeError):
        fail()
    assert target.read_text() == "earlier result"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model.nc"]


def _write_many(path: str, count: int) -> None:
    ds = cummins.demo_dataset()
    for _ in range(count):
        cummins.write(ds, path, force=True)


def test_two_processes_writing_one_netcdf_file_both_succeed(tmp_path):
    target = tmp_path / "tanker.nc"
    context = multiprocessing.get_context("spawn")
    workers = [context.Process(target=_write_many, args=(str(target), 3)) for _ in range(2)]
    for w in workers:
        w.start()
    for w in workers:
        w.join(timeout=120)
    assert [w.exitcode for w in workers] == [0, 0]
    back = cummins.read(target)
    assert back.sizes["omega"] == cummins.demo_dataset().sizes["omega"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tanker.nc"]


def test_hdf5_is_told_by_content_at_the_offsets_the_specification_allows(tmp_path):
    """A NetCDF-4 file cummins writes, under any name; the signature after a user block
    of 512 or 2048 bytes (h5py writes one with ``userblock_size``, and opens the file);
    not at an offset the HDF5 specification does not allow (100), not a NetCDF-3 file,
    a text file, an empty file, a folder or a missing file."""
    import h5py
    import numpy as np
    import xarray as xr

    model = tmp_path / "model.whatever"
    cummins.write(cummins.read(cummins.demo_files() / "tanker.1"), tmp_path / "data.nc")
    shutil.copy(tmp_path / "data.nc", model)
    assert is_hdf5(model)
    for size in (512, 2048):
        path = tmp_path / f"block{size}.h5"
        with h5py.File(path, "w", userblock_size=size) as f:
            f["x"] = np.arange(3)
        assert is_hdf5(path)
    signature = b"\x89HDF\r\n\x1a\n"
    (tmp_path / "at100").write_bytes(b"\0" * 100 + signature + b"\0" * 1000)
    xr.Dataset({"x": ("t", np.arange(3.0))}).to_netcdf(tmp_path / "v3.nc", engine="scipy")
    (tmp_path / "text.1").write_text("WAMIT numbers\n")
    (tmp_path / "empty").write_bytes(b"")
    for path in ("at100", "v3.nc", "text.1", "empty", ".", "missing.nc"):
        assert not is_hdf5(tmp_path / path), path
