"""The equation of motion completed from mass properties and external terms.

References: Capytaine's own ``compute_rigid_body_inertia`` (stored in the corpus's
Capytaine files, written by WEC-Sim's scripts, not by us) and the parallel-axis
theorem; the impedance's dependence on an added spring or damper is exact.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import cummins
from cummins import ArgumentError
from cummins.cli import main
from cummins.kinematics import center_of_gravity_from_inertia, skew
from cummins.mass_properties import inertia_from_radii, read_matrix_file, with_inertia
from cummins.seakeeping.frequency_domain import impedance

COER = "WEC-Sim/capytaine_COER_comp/outputs/coer_comp_hydrodynamics.nc"
OSWEC = "WEC-Sim/capytaine_OSWEC_flap/outputs/oswec_hydrodynamics.nc"


def _mass_properties(m_rb: np.ndarray, reference: np.ndarray):
    """Mass, centre of gravity and radii of gyration about it, from a 6×6 M_RB about
    ``reference`` (the inverse of the parallel-axis theorem, written out here)."""
    mass, r_g, _ = center_of_gravity_from_inertia(m_rb)
    s = skew(r_g)
    inertia_cg = m_rb[3:, 3:] + mass * s @ s
    return mass, r_g + reference, np.sqrt(np.diag(inertia_cg) / mass), inertia_cg


@pytest.mark.parametrize("case", [COER, OSWEC])
def test_capytaine_inertia_is_rebuilt_from_its_mass_properties(corpus, case):
    """Capytaine's rigid-body inertia (axisymmetric float; flap and base) comes back from
    its mass, centre of gravity and radii of gyration. Radii cannot carry products of
    inertia: the float has none (< 1e-9 of the moments), the flap's mesh an I_xy of
    126 kg m² (9.3e-5 of I_xx); the rebuilt matrix differs from Capytaine's by exactly
    that product (checked to 1e-9 of the largest entry), and by nothing else."""
    ds = cummins.read(corpus / case)
    m_file = ds.inertia_matrix.values.copy()
    groups = cummins.hydrodb.bodies(ds)
    refs = np.asarray(ds.attrs.get("reference_point", (0, 0, 0)), dtype=float).reshape(-1, 3)
    masses, cogs, radii = [], [], []
    for k in range(len(groups)):
        block = m_file[6 * k : 6 * k + 6, 6 * k : 6 * k + 6]
        ref = refs[k] if len(refs) == len(groups) else refs[0]
        mass, cog, r, inertia_cg = _mass_properties(block, ref)
        off = inertia_cg - np.diag(np.diag(inertia_cg))
        assert np.max(np.abs(off)) < 5e-4 * np.max(np.diag(inertia_cg))
        m_file[6 * k + 3 : 6 * k + 6, 6 * k + 3 : 6 * k + 6] -= off  # what radii cannot hold
        masses.append(mass)
        cogs.append(cog)
        radii.append(r)
    rebuilt = with_inertia(ds, mass=masses, center_of_gravity=cogs, radii_of_gyration=radii)
    error = np.max(np.abs(rebuilt.inertia_matrix.values - m_file)) / np.max(np.abs(m_file))
    assert error < 1e-9
    assert "mass of" in rebuilt.attrs["history"]
    assert np.allclose(rebuilt.attrs["center_of_gravity"], np.concatenate(cogs))


def test_inertia_about_another_point_follows_the_parallel_axis_theorem():
    """Roll inertia about a point 10 m below G: I_g + m·10²; the surge–pitch coupling is
    m·z_g (Smogeli et al. (2004) eq. 25)."""
    m = inertia_from_radii(2.0e6, [0.0, 0.0, 0.0], [5.0, 20.0, 21.0], reference_point=[0, 0, -10])
    assert m[3, 3] == pytest.approx(2.0e6 * (25.0 + 100.0))
    assert m[4, 4] == pytest.approx(2.0e6 * (400.0 + 100.0))
    assert m[5, 5] == pytest.approx(2.0e6 * 441.0)
    assert m[0, 4] == pytest.approx(2.0e6 * 10.0)
    assert np.allclose(m, m.T)


def test_mass_defaults_to_the_displaced_water_of_a_floating_body(shared_data):
    """Without a mass, a freely floating body weighs its displaced water: ρ∇ from the
    data's displaced volume, said so in history."""
    ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.1")  # ∇ from the .out
    volume = float(ds.attrs["displaced_volume"])
    out = with_inertia(ds, radii_of_gyration=[14.0, 60.0, 60.0], center_of_gravity=[0, 0, -1])
    assert out.inertia_matrix.values[0, 0] == pytest.approx(ds.attrs["rho"] * volume)
    assert "freely floating" in out.attrs["history"]


def test_external_spring_and_damper_enter_the_impedance_exactly(shared_data):
    """Z(ω) changes by exactly k + iωc at the pair given, nowhere else."""
    ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.1")
    k, c = 3.0e6, 4.0e5
    out = cummins.with_external_terms(
        ds, stiffness={("Surge", "Surge"): k}, damping={("Sway", "Yaw"): c}
    )
    w = ds.omega.values[5:9]
    dz = impedance(out, w) - impedance(ds, w)
    expected = np.zeros_like(dz)
    expected[:, 0, 0] = k
    expected[:, 1, 5] = 1j * w * c
    assert np.allclose(dz, expected, rtol=1e-9, atol=1e-6 * k)
    assert "additional_stiffness added (given): Surge-Surge 3e+06" in out.attrs["history"]


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"mass": -5.0, "radii_of_gyration": [1, 1, 1]}, "mass must be a finite number > 0"),
        ({"mass": 1e13, "radii_of_gyration": [1, 1, 1]}, "heavier than any floating body"),
        ({"mass": 1e6, "radii_of_gyration": [1, np.nan, 1]}, "radii_of_gyration"),
        (
            {"mass": 1e6, "radii_of_gyration": [1, 1, 1], "center_of_gravity": [0, np.inf, 0]},
            "center_of_gravity",
        ),
        ({"mass": 1e6}, "radii_of_gyration"),
        ({"matrix": np.eye(5)}, "shape"),
        ({"matrix": -np.eye(6)}, "positive mass"),
    ],
)
def test_impossible_mass_properties_are_refused(shared_data, kwargs, words):
    ds = cummins.read(shared_data / "mss" / "tanker" / "tanker.1")
    with pytest.raises(ArgumentError, match=words):
        with_inertia(ds, **kwargs)


def test_cli_completes_the_data_with_mass_properties_and_moorings(corpus, tmp_path):
    """The OC3 spar of WEIS has no inertia in its files: given the platform's published
    mass properties (Jonkman 2010, NREL/TP-500-47535 Table 2-1: 7 466 330 kg, CG 89.92 m
    below the waterline, roll inertia 4.229e9 kg m² about the CG, yaw 1.642e8) and its
    surge/sway mooring stiffness (41 180 N/m), `cummins rao` runs and the quasi-static
    heave RAO tends to 1 m/m at the lowest frequency (weight = buoyancy: any other
    value would mean the restoring or the excitation is wrong)."""
    spar = corpus / "WEIS" / "ss_fitting_OC3_spar" / "spar.1"
    rxx = float(np.sqrt(4.229e9 / 7466330))
    rzz = float(np.sqrt(1.642e8 / 7466330))
    out = tmp_path / "rao.nc"
    args = [
        "rao",
        str(spar),
        "-o",
        str(out),
        "--headings",
        "180",
        "--mass",
        "7466330",
        "--center-of-gravity",
        "0",
        "0",
        "-89.92",
        "--radii-of-gyration",
        str(rxx),
        str(rxx),
        str(rzz),
        "--external-stiffness",
        "Surge",
        "Surge",
        "41180",
        "--external-stiffness",
        "Sway",
        "Sway",
        "41180",
    ]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert "inertia_matrix" in result.output and "additional_stiffness" in result.output
    assert "body coupling" not in result.output  # one body: nothing to couple
    from cummins.seakeeping.frequency_domain import load_rao

    rao = load_rao(out)
    heave = np.abs(rao.sel(dof="Heave").isel(wave_direction=0).values)
    assert heave[0] == pytest.approx(1.0, abs=0.02)


def test_cli_refuses_a_mass_without_radii(corpus):
    spar = corpus / "WEIS" / "ss_fitting_OC3_spar" / "spar.1"
    result = CliRunner().invoke(main, ["info", str(spar), "--mass", "7466330"])
    assert result.exit_code == 2
    assert "--radii-of-gyration" in result.output
    assert "Traceback" not in result.output


def test_matrix_file_reads_text_and_names_the_bad_line(tmp_path):
    good = tmp_path / "m.txt"
    good.write_text("# M_RB\n1, 0\n0 2\n", encoding="utf-8")
    assert np.array_equal(read_matrix_file(str(good)), np.diag([1.0, 2.0]))
    bad = tmp_path / "bad.txt"
    bad.write_text("1 0\n0 x\n", encoding="utf-8")
    with pytest.raises(cummins.HydroDataError, match="line 2"):
        read_matrix_file(str(bad))


def test_external_stiffness_is_the_restoring_of_data_without_one(corpus, tmp_path):
    """The NEMOH cubes' KH files describe another mesh, so the reader leaves the
    restoring out and tells the user to give it (--external-stiffness): given as the
    cubes' ρ g A_wp (9.806e5 N/m, the reader's own Froude–Krylov estimate), it is the
    whole restoring — said so — and the heave RAO of each cube tends to 1 m/m in long
    waves (the excitation's quasi-static limit over that stiffness)."""
    cubes = corpus / "WEC-Sim" / "nemoh_v3.0.2_Cubes_2body"
    out = tmp_path / "rao.nc"
    args = ["rao", str(cubes), "-o", str(out), "--headings", "0"]
    for body, x in (("body1", "0"), ("body2", "100")):
        args += ["--mass", "1e6", "--center-of-gravity", x, "0", "-2.5"]
        args += ["--radii-of-gyration", "3", "3", "4", "--dof", f"{body}__Heave"]
        args += ["--external-stiffness", f"{body}__Heave", f"{body}__Heave", "9.806e5"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "the external stiffness given is the whole restoring" in text
    with xr.open_dataset(out, engine="h5netcdf") as rao:
        parts = rao.rao.isel(omega=0, wave_direction=0).transpose("complex", "dof").values
    lowest = np.hypot(*parts)  # the file keeps the real and imaginary parts
    assert lowest.shape == (2,)
    np.testing.assert_allclose(lowest, 1.0, atol=0.02)


def test_a_heave_only_run_needs_no_radii_of_gyration(corpus, tmp_path):
    """WEC-Sim's WaveBot in heave alone: `--mass` without radii is enough (no rotation
    moves), said so; the RAOs are those of any radii given (here 2 m), to the last bit."""
    wavebot = corpus / "WEC-Sim_Applications" / "wamit_WaveBot" / "waveBotBuoy.out"
    common = ["--dof", "Heave", "--mass", "858.4", "--headings", "0", "--rho", "1000"]
    outs = [tmp_path / "a.nc", tmp_path / "b.nc"]
    result = CliRunner().invoke(main, ["rao", str(wavebot), "-o", str(outs[0]), *common])
    assert result.exit_code == 0, result.output
    assert "radii of gyration not needed" in " ".join(result.output.split())
    given = ["--radii-of-gyration", "2", "2", "2"]
    result = CliRunner().invoke(main, ["rao", str(wavebot), "-o", str(outs[1]), *common, *given])
    assert result.exit_code == 0, result.output
    a, b = (xr.open_dataset(out, engine="h5netcdf") for out in outs)
    with a, b:
        np.testing.assert_array_equal(a.rao.values, b.rao.values)
    result = CliRunner().invoke(
        main, ["rao", str(wavebot), "-o", str(tmp_path / "c.nc"), "--mass", "858.4"]
    )
    assert result.exit_code == 2 and "give the radii too" in result.output  # rotations move
