"""``cummins rao``: options, output file, plots, refusal to overwrite, error messages.

The command is invoked directly (``rao_command``), so the tests do not depend on its
registration in ``cummins.cli``.
"""

from __future__ import annotations

import shutil

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli.rao import expand_list_options, rao_command
from cummins.seakeeping.frequency_domain import load_rao, motion_rao


@pytest.fixture
def runner():
    return CliRunner()


@pytest.fixture
def tanker_copy(tmp_path):
    for f in cummins.demo_files().glob("tanker.*"):
        shutil.copy(f, tmp_path / f.name)
    return tmp_path / "tanker.1"


def test_rao_command_writes_the_raos(runner, tanker_copy, tmp_path):
    out = tmp_path / "rao.nc"
    plots = tmp_path / "plots"
    args = [str(tanker_copy), "-o", str(out), "--headings", "0", "45", "90", "--omega-min"]
    args += ["0.2", "--omega-max", "1.5", "--n-omega", "27", "--viscous-damping", "Roll", "5e8"]
    args += ["--plot", str(plots)]
    result = runner.invoke(rao_command, args)
    assert result.exit_code == 0, result.output
    assert "Roll" in result.output and "mirrored" in result.output
    rao = load_rao(out)
    assert rao.dims == ("omega", "wave_direction", "dof")
    np.testing.assert_allclose(rao.wave_direction.values, np.radians([0.0, 45.0, 90.0]))
    np.testing.assert_allclose(rao.omega.values, np.linspace(0.2, 1.5, 27))
    expected = motion_rao(
        cummins.read(tanker_copy),
        np.linspace(0.2, 1.5, 27),
        np.radians([0.0, 45.0, 90.0]),
        viscous_damping={"Roll": 5e8},
    )
    np.testing.assert_allclose(rao.values, expected.values)
    assert (plots / "rao.png").stat().st_size > 10_000
    # again: refused without --force, done with it
    again = runner.invoke(rao_command, args)
    assert again.exit_code == 2 and "refusing to overwrite" in again.output
    assert runner.invoke(rao_command, [*args, "--force"]).exit_code == 0


def test_defaults_are_the_data_grid(runner, tanker_copy, tmp_path):
    out = tmp_path / "rao.nc"
    result = runner.invoke(rao_command, [str(tanker_copy), "-o", str(out), "--no-additional"])
    assert result.exit_code == 0, result.output
    rao = load_rao(out)
    ds = cummins.read(tanker_copy)
    np.testing.assert_array_equal(rao.omega.values, ds.omega.values)
    np.testing.assert_array_equal(rao.wave_direction.values, ds.wave_direction.values)
    assert "additional_damping" not in rao.attrs["terms"]


def test_headings_syntax(runner, tanker_copy, tmp_path):
    assert expand_list_options(["--headings", "0", "45", "-90", "f.1", "--force"]) == [
        "--headings", "0", "--headings", "45", "--headings", "-90", "f.1", "--force",
    ]  # fmt: skip
    a, b = tmp_path / "a.nc", tmp_path / "b.nc"
    common = ["--omega-min", "0.3", "--omega-max", "0.6", "--n-omega", "4"]
    first = runner.invoke(
        rao_command, [str(tanker_copy), "-o", str(a), "--headings", "30,60", *common]
    )
    second = runner.invoke(
        rao_command,
        ["--headings", "30", "--headings", "60", str(tanker_copy), "-o", str(b), *common],
    )
    assert first.exit_code == 0 and second.exit_code == 0, first.output + second.output
    np.testing.assert_array_equal(load_rao(a).values, load_rao(b).values)


def test_errors_are_one_line(runner, tanker_copy, tmp_path):
    out = str(tmp_path / "x.nc")
    result = runner.invoke(rao_command, [str(tanker_copy), "-o", out, "--omega-max", "9"])
    assert result.exit_code == 2 and "outside the data's range" in result.output
    assert "Traceback" not in result.output
    result = runner.invoke(
        rao_command, [str(tanker_copy), "-o", out, "--viscous-damping", "Rol", "1"]
    )
    assert result.exit_code == 2 and "unknown DOF 'Rol'" in result.output
    result = runner.invoke(rao_command, [str(tanker_copy), "-o", out, "--headings", "north"])
    assert result.exit_code == 2
    help_text = runner.invoke(rao_command, ["--help"]).output
    assert "--headings" in help_text and "head" in help_text


def test_rao_names_the_dofs_apart_from_the_data_own_raos(runner, shared_data, tmp_path):
    """MSS's supply.mat holds VERES' motion RAOs; with MSS's Bv (roll 3e7 N m s) the
    computed roll RAO peaks at 0.158 rad/m where VERES' does at 0.054: the note names
    Roll (measured 192 % of its peak) and leaves heave and pitch (0.0 %, 0.3 %) out."""
    data = shared_data / "mss" / "supply" / "supply.mat"
    out = tmp_path / "rao.nc"
    result = runner.invoke(rao_command, [str(data), "-o", str(out), "--headings", "90", "180"])
    assert result.exit_code == 0, result.output
    note = " ".join(result.output.split()).split("note: the data's own motion RAOs")[1]
    listed = {
        part.split()[0]: float(part.split()[1])
        for part in note.split(": ", 1)[1].split(" (largest")[0].split(", ")
    }
    assert listed["Roll"] > 100.0
    assert "Heave" not in listed and "Pitch" not in listed
    # HAMS' own .4 RAOs of its test cylinder are those of its .1/.3/.hst: no note
    # (measured 0.0 % in every DOF), the comparison's units and conventions hold
    cylinder = shared_data / "corpus" / "HAMS" / "Cylinder" / "Output_Benchmark"
    args = [str(cylinder / "Wamit_format" / "Buoy.1"), "-o", str(tmp_path / "cyl.nc")]
    result = runner.invoke(rao_command, args)
    assert result.exit_code == 0, result.output
    assert "Motion RAOs" in result.output and "note: the data's own" not in result.output


def test_rao_says_when_a_resonance_moved(runner, shared_data, tmp_path):
    """MSS's S-175 at zero speed in beam seas: the struct's MRB and restoring put roll's
    resonance at 0.349 rad/s (√(C44/(I44 + A44)) = 0.346), VERES' own RAOs in the struct
    peak at 0.314; the note blamed terms such as viscous roll damping, which cannot move
    a resonance that far (0.2 % of critical in the struct's roll Bv44). A second note
    names the shift; heave and pitch, which agree, are not named."""
    data = shared_data / "mss" / "s175" / "s175.mat"
    args = [str(data), "--speed", "0", "-o", str(tmp_path / "r.nc"), "--headings", "90"]
    result = runner.invoke(rao_command, args)
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "note: Roll peaks at 0.349 rad/s, the solver's at 0.314 rad/s" in text
    assert "Heave peaks" not in text and "Pitch peaks" not in text
    # the HAMS cylinder's RAOs are its data's: no such note
    cylinder = shared_data / "corpus" / "HAMS" / "Cylinder" / "Output_Benchmark"
    args = [str(cylinder / "Wamit_format" / "Buoy.1"), "-o", str(tmp_path / "c.nc")]
    result = runner.invoke(rao_command, args)
    assert result.exit_code == 0 and "peaks at" not in result.output
