"""HAMS projects of the corpus: frequency types, constants, Hydrostatic.in, RAOs, Output/
against Output_Benchmark/."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

import cummins
from cummins.io.wamit import _parse_dot1, _read_text, _read_wave_file
from cummins.seakeeping.frequency_domain import motion_rao


def test_frequency_types_follow_the_control_file(corpus):
    """Output_frequency_type 4 (period), 2 (wavenumber, deep water), 3 (omega)."""
    cyl = cummins.read(corpus / "HAMS" / "Cylinder")
    np.testing.assert_allclose(cyl.omega.values[-1], 2 * np.pi / 1.16e0, rtol=0.01)
    deep = cummins.read(corpus / "HAMS" / "DeepCwind")
    # k = 0.5, 1.0, 1.5 1/m at infinite depth (Waterdepth -200): ω² = g k, with HAMS's g
    np.testing.assert_allclose(deep.omega.values, np.sqrt(9.80665 * np.array([0.5, 1.0, 1.5])))
    assert deep.attrs["water_depth"] == np.inf and deep.attrs["g"] == 9.80665
    raft = cummins.read(corpus / "RAFT" / "hams_cylinder_empty_dot4")
    np.testing.assert_allclose(raft.omega.values, 0.2 * np.arange(1, 31), rtol=1e-6)
    assert "Buoy.4 is empty (0 bytes): skipped" in raft.attrs["history"]
    assert "inertia_matrix" not in raft  # Hydrostatic.in holds a mass matrix of zeros


def test_constants_not_written_are_not_said_to_come_from_the_file(corpus):
    """RAFT's HAMS run has no Hydrostar_format headers: rho and g are HAMS's constants,
    and the history must not also say they came from the file (nor, with rho given, that
    the file records 1025); DeepCwind's .rao headers do print them."""
    raft = cummins.read(corpus / "RAFT" / "hams_cylinder_empty_dot4")
    history = raft.attrs["history"]
    assert raft.attrs["rho"] == 1025.0 and raft.attrs["g"] == 9.80665
    assert "rho = 1025 kg/m^3 (from the file)" not in history
    assert "g = 9.80665 m/s^2 (from the file)" not in history
    assert "rho = 1025 kg/m^3 (HAMS's constant, not written" in history
    given = cummins.read(corpus / "RAFT" / "hams_cylinder_empty_dot4", rho=1000.0)
    assert given.attrs["rho"] == 1000.0
    assert "the file records" not in given.attrs["history"]
    assert "rho = 1000 kg/m^3 (given; HAMS's constant" in given.attrs["history"]
    np.testing.assert_allclose(given.added_mass.values * 1.025, raft.added_mass.values)
    deep = cummins.read(corpus / "HAMS" / "DeepCwind")
    assert "rho = 1025 kg/m^3 (from the file)" in deep.attrs["history"]


def test_wavenumber_limits_are_zero_then_infinite(corpus):
    """With a wavenumber column HAMS writes k = 0 (ω = 0) and −1 (ω = ∞): the surge added
    mass at the highest k (1.5/m: 6067 nondim.) is near the −1 block (6397), far from the
    0 block (8561)."""
    ds = cummins.read(corpus / "HAMS" / "DeepCwind")
    a11 = ds.added_mass.sel(influenced_dof="Surge", radiating_dof="Surge").values
    inf = float(ds.added_mass_inf.sel(influenced_dof="Surge", radiating_dof="Surge"))
    zero = float(ds.added_mass_zero.sel(influenced_dof="Surge", radiating_dof="Surge"))
    assert abs(a11[-1] - inf) < abs(a11[-1] - zero) / 4


def test_hydrostatics_scale_matches_the_input_matrix(corpus):
    """The .hst is C/(ρg); Hydrostatic.in of the Cylinder holds the dimensional C33 that
    pyHAMS's test writes (0.31462E+05 N/m): with ρ = 1025 and g = 9.80665 they agree to
    the 5 digits printed (measured 1e-5)."""
    ds = cummins.read(corpus / "HAMS" / "Cylinder")
    c33 = float(ds.hydrostatic_stiffness.sel(influenced_dof="Heave", radiating_dof="Heave"))
    np.testing.assert_allclose(c33, 0.31462e05, rtol=1e-4)


@pytest.mark.parametrize("case", ["HAMS/Cylinder", "HAMS/DeepCwind"])
def test_motion_rao_reproduces_the_hams_dot4(corpus, case):
    """Our motion_rao with the run's own mass, hydrostatics and external stiffness gives
    HAMS's .4 RAOs once the .4 is read as i·ξ/(ρg) (what HAMS writes): measured worst
    relative difference 3e-5 (Cylinder 7e-6), 0.03° in phase, over every DOF above
    1e-3 of the peak, all frequencies and headings."""
    ds = cummins.read(corpus / case)
    ours = motion_rao(ds).transpose("omega", "wave_direction", "dof").values
    ref = ds.rao.transpose("omega", "wave_direction", "radiating_dof").values
    big = np.abs(ref) > 1e-3 * np.abs(ref).max()
    ratio = ours[big] / ref[big]
    np.testing.assert_allclose(np.abs(ratio), 1.0, atol=3e-4)
    assert np.abs(np.degrees(np.angle(ratio))).max() < 0.3


def test_benchmark_set_agrees_with_the_run(corpus, tmp_path):
    """DeepCwind: Output/ holds only the ω = 0/∞ blocks, Output_Benchmark/ the whole run.
    The reader falls back to the benchmark set and says so; where both are complete (the
    limit blocks, the .3 excitation) they agree (measured 0 and 1e-6 relative)."""
    root = corpus / "HAMS" / "DeepCwind"
    ds = cummins.read(root)
    assert "read Output_Benchmark/ instead" in ds.attrs["history"]
    with pytest.raises(cummins.HydroDataError, match="no finite frequency"):
        _parse_dot1(root / "Output" / "Wamit_format" / "Buoy.1", "wavenumber", depth=np.inf, g=9.8)
    text = _read_text(root / "Output" / "Wamit_format" / "Buoy.1")
    bench = _read_text(root / "Output_Benchmark" / "Wamit_format" / "Buoy.1")
    limits = [
        line
        for line in bench.lines
        if line.split() and line.split()[0] in ("0.000000E+00", "-1.000000E+00")
    ]
    np.testing.assert_allclose(
        np.array([[float(x) for x in line.split()] for line in text.lines if line.strip()]),
        np.array([[float(x) for x in line.split()] for line in limits]),
        rtol=1e-5,
    )
    first = np.array([0.5, 1.0, 1.5])
    x_run, _ = _read_wave_file(
        root / "Output" / "Wamit_format" / "Buoy.3", first, 6, what="excitation"
    )
    x_bench, _ = _read_wave_file(
        root / "Output_Benchmark" / "Wamit_format" / "Buoy.3", first, 6, what="excitation"
    )
    np.testing.assert_allclose(x_run, x_bench, rtol=1e-4, atol=1e-4 * np.abs(x_bench).max())


def test_a_dot1_inside_a_project_reads_with_its_settings(corpus):
    """Reading Output_Benchmark/Wamit_format/Buoy.1 directly uses the project's settings."""
    path = corpus / "HAMS" / "HywindSpar" / "Output_Benchmark" / "Wamit_format" / "Buoy.1"
    ds = cummins.read(path)
    assert ds.attrs["source_format"] == "hams"
    np.testing.assert_allclose(ds.omega.values, np.sqrt(9.80665 * np.array([0.75, 1.5])))
    assert "inertia_matrix" in ds and "additional_stiffness" in ds


def test_damaged_control_file_is_an_error(corpus, tmp_path):
    shutil.copytree(corpus / "HAMS" / "HywindSpar", tmp_path / "run")
    control = tmp_path / "run" / "Input" / "ControlFile.in"
    control.write_text(
        control.read_text().replace(
            "Output_frequency_type       2", "Output_frequency_type       9"
        )
    )
    with pytest.raises(cummins.HydroDataError, match=r"ControlFile\.in, line"):
        cummins.read(tmp_path / "run")
