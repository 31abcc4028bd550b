"""Fuzzing the readers with mutated real files.

Each reader is fed real solver output with random damage (lines deleted, duplicated or
swapped, numbers garbled, the file truncated, bytes flipped in binary files). It must
either return a valid dataset or raise ``HydroDataError``: never another exception.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import cummins
from cummins import HydroDataError

#: format → (folder under shared data, files to copy, file to mutate candidates, file to read)
CASES = {
    "wamit": (
        "mss/tanker",
        ["tanker.1", "tanker.3", "tanker.hst", "tanker.frc", "tanker.out"],
        ["tanker.1", "tanker.3", "tanker.hst", "tanker.frc", "tanker.out"],
        "tanker.1",
    ),
    "wamit-out": ("mss/tanker", ["tanker.out"], ["tanker.out"], "tanker.out"),
    "nemoh": (
        "wecsim/cylinder/cylinder_nemoh",
        [
            "RadiationCoefficients.tec",
            "ExcitationForce.tec",
            "DiffractionForce.tec",
            "FKForce.tec",
            "KH.dat",
            "Hydrostatics.dat",
            "Nemoh.cal",
            "IRF.tec",
        ],
        ["RadiationCoefficients.tec", "ExcitationForce.tec", "KH.dat", "Nemoh.cal"],
        "RadiationCoefficients.tec",
    ),
    "aqwa": ("wecsim/cylinder_aqwa", ["cylinder.LIS"], ["cylinder.LIS"], "cylinder.LIS"),
    "aqwa-ah1": ("wecsim/cylinder_aqwa", ["cylinder.AH1"], ["cylinder.AH1"], "cylinder.AH1"),
    "veres": (
        "mss/supply",
        ["input.re7", "input.re8", "input.re1", "input.hyd"],
        ["input.re7", "input.re8", "input.re1"],
        "input.re7",
    ),
    "netcdf": (
        "wecsim/sphere",
        ["sphere_hydrodynamics.nc"],
        ["sphere_hydrodynamics.nc"],
        "sphere_hydrodynamics.nc",
    ),
    "mss": ("mss/supply", ["supply.mat"], ["supply.mat"], "supply.mat"),
}
BINARY = {".nc", ".mat"}


def _mutate_text(text: str, op: str, a: int, b: int, junk: str) -> str:
    lines = text.splitlines()
    n = len(lines)
    i, j = a % n, b % n
    if op == "delete":
        del lines[i]
    elif op == "duplicate":
        lines.insert(i, lines[i])
    elif op == "swap":
        lines[i], lines[j] = lines[j], lines[i]
    elif op == "truncate":
        return text[: a % len(text)]
    elif op == "garble":
        fields = lines[i].split()
        if fields:
            fields[b % len(fields)] = junk
            lines[i] = "  ".join(fields)
    elif op == "insert":
        lines.insert(i, junk)
    elif op == "blank":
        lines[i] = ""
    return "\n".join(lines) + "\n"


def _mutate_bytes(data: bytes, op: str, a: int, b: int) -> bytes:
    n = len(data)
    if op == "truncate":
        return data[: a % n]
    i = a % n
    buf = bytearray(data)
    for k in range(1 + b % 16):
        buf[(i + 37 * k) % n] ^= 0xFF
    return bytes(buf)


TEXT_OPS = ["delete", "duplicate", "swap", "truncate", "garble", "insert", "blank"]
JUNK = st.sampled_from(["1.2.3", "abc", "NaN", "-inf", "", "1e999", "***", "7", "0.0 0.0 0.0"])


@pytest.mark.parametrize("case", sorted(CASES))
@settings(
    max_examples=12,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(
    which=st.integers(0, 10),
    op=st.sampled_from(TEXT_OPS),
    a=st.integers(0, 10**7),
    b=st.integers(0, 10**7),
    junk=JUNK,
)
def test_mutated_files_raise_only_hydro_data_error(shared_data, case, which, op, a, b, junk):
    folder, files, targets, entry = CASES[case]
    fmt = "aqwa" if case == "aqwa-ah1" else case
    with tempfile.TemporaryDirectory() as tmp:
        tmp_path = Path(tmp)
        for name in files:
            shutil.copy(shared_data / folder / name, tmp_path / name)
        target = tmp_path / targets[which % len(targets)]
        if target.suffix in BINARY:
            target.write_bytes(
                _mutate_bytes(target.read_bytes(), "truncate" if op == "truncate" else "flip", a, b)
            )
        else:
            text = target.read_text(encoding="utf-8", errors="replace")
            target.write_text(_mutate_text(text, op, a, b, junk), encoding="utf-8")
        try:
            ds = cummins.read(tmp_path / entry, format=fmt)
        except HydroDataError as exc:
            message = str(exc)
        else:
            cummins.validate(ds)
            return
    assert message, "an error message must say what is wrong"
