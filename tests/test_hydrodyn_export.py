"""WAMIT files written for OpenFAST's HydroDyn (`cummins convert … x.1`): the ``.hst`` holds
buoyancy and waterplane alone (ElastoDyn adds the weight), the ``.1`` its ω = 0 and ω = ∞
rows, the reference point and the QTFs are said; OpenFAST's ``.ss``/``.ssexctn`` are
described by `cummins info`. References: WAMIT's own files of the same platforms (the WEIS
OC3 spar, the RAFT copy of it without limit rows, ROSCO's RM1) and analytic hydrostatics."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest
from click.testing import CliRunner

import cummins
from cummins.cli import main
from cummins.hydrodb import dof_matrix
from cummins.restoring import weight_stiffness


def _read(path, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path, **options)


def _convert(*args):
    result = CliRunner().invoke(main, ["convert", *map(str, args)])
    assert result.exit_code == 0, result.output
    return " ".join(result.output.split())


def _rows(path):
    out = {}
    for line in path.read_text().splitlines():
        fields = line.split()
        if fields:
            out[tuple(float(x) for x in fields[:3])] = np.array([float(x) for x in fields[3:]])
    return out


# --------------------------------------------------------------------------- restoring


def test_nemoh_spar_hst_is_buoyancy_alone_as_the_weis_wamit_file(corpus, tmp_path):
    """NEMOH's KH holds the weight of ρ∇ at G = (0, 0, −78): about the waterline the
    buoyancy alone is ρg(I_wp + ∇ z_B) < 0. The WEIS OC3 spar.hst (WAMIT, run for
    HydroDyn) is the same platform at half the radius of the NEMOH mesh (C33 and ∇ four
    times smaller), so C44/C33 ≈ z_B ∇/A_wp is the scale-free check: −15015 m² (WAMIT)
    against −15007 (measured, 0.05 %)."""
    out = tmp_path / "spar.1"
    text = _convert(
        corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar", out, "--reference-point", 0, 0, 0
    )
    assert "weight's terms" in text and "taken out" in text
    assert "PtfmRefzt = 0" in text and "--reference-point 0 0 0" not in text
    ours = dof_matrix(_read(out, rho=1025.0, g=9.81), "hydrostatic_stiffness")
    weis = dof_matrix(
        _read(corpus / "WEIS" / "ss_fitting_OC3_spar" / "spar.1", rho=1025.0, g=9.81),
        "hydrostatic_stiffness",
    )
    assert ours[3, 3] < 0 and ours[4, 4] < 0  # before: +5.13e5 rho g (the weight kept)
    assert ours[3, 3] / ours[2, 2] == pytest.approx(weis[3, 3] / weis[2, 2], rel=0.01)
    assert ours[2, 2] / weis[2, 2] == pytest.approx(4.0, rel=0.01)


def test_without_reference_point_the_moments_are_about_the_data_s(corpus, tmp_path):
    """About NEMOH's reference (0, 0, −78) = G the weight has no terms: the .hst is NEMOH's
    KH, and the output says PtfmRefzt = −78 and how to write about the waterline."""
    out = tmp_path / "spar.1"
    text = _convert(corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar", out)
    assert "PtfmRefzt = -78" in text and "--reference-point 0 0 0" in text
    assert "PtfmVol0 = 32082" in text
    kh = np.loadtxt(corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar" / "Mesh" / "KH.dat")
    ours = dof_matrix(_read(out, rho=1025.0, g=9.81), "hydrostatic_stiffness")
    np.testing.assert_allclose(np.diag(ours)[2:5], np.diag(kh)[2:5], rtol=1e-5)


def test_moved_hydrostatics_alone_match_the_analytic_waterplane():
    """Hydrostatics alone (WAMIT (2020) §3.1) of a rectangular waterplane off the origin
    and a centre of buoyancy off the axis, about O and about O': moving the reference
    point gives the formulas about O' (the screw transform alone misses ρ g ∇ Δz)."""
    ds = cummins.demo_dataset()
    rho, g, volume = float(ds.attrs["rho"]), float(ds.attrs["g"]), 5000.0
    x0, x1, y0, y1 = -12.0, 20.0, -7.0, 9.0
    b = np.array([3.0, 0.5, -6.0])

    def hydrostatics(o):
        xa, xb, ya, yb = x0 - o[0], x1 - o[0], y0 - o[1], y1 - o[1]
        area = (xb - xa) * (yb - ya)
        sx, sy = area * (xa + xb) / 2, area * (ya + yb) / 2
        ixx = (xb - xa) * (yb**3 - ya**3) / 3
        iyy = (yb - ya) * (xb**3 - xa**3) / 3
        ixy = (xb**2 - xa**2) * (yb**2 - ya**2) / 4
        r = b - o
        c = np.zeros((6, 6))
        c[2, 2] = area
        c[2, 3] = c[3, 2] = sy
        c[2, 4] = c[4, 2] = -sx
        c[3, 3] = ixx + volume * r[2]
        c[4, 4] = iyy + volume * r[2]
        c[3, 4] = c[4, 3] = -ixy
        c[3, 5] = -volume * r[0]
        c[4, 5] = -volume * r[1]
        return rho * g * c

    ds["hydrostatic_stiffness"] = ds.hydrostatic_stiffness.copy(data=hydrostatics(np.zeros(3)))
    ds.attrs.update(restoring_weight_mass=0.0, displaced_volume=volume)
    new = np.array([4.0, -2.0, -15.0])
    moved = cummins.move_reference_point(ds, new)
    got = dof_matrix(moved, "hydrostatic_stiffness")
    expected = hydrostatics(new)
    np.testing.assert_allclose(got, expected, atol=1e-9 * np.abs(expected).max())
    # with the weight of ρ∇ above B (equilibrium) the screw transform alone is exact
    center = np.array([b[0], b[1], 2.0])
    total = ds.copy()
    weight = weight_stiffness(rho * volume * center, g)
    total["hydrostatic_stiffness"] = ds.hydrostatic_stiffness + weight
    total.attrs.update(restoring_weight_mass=rho * volume, restoring_weight_center=center)
    both = dof_matrix(cummins.move_reference_point(total, new), "hydrostatic_stiffness")
    expected = hydrostatics(new) + weight_stiffness(rho * volume * (center - new), g)
    np.testing.assert_allclose(both, expected, atol=1e-9 * np.abs(expected).max())


def test_openfast_files_round_trip_exactly(corpus, tmp_path):
    """ROSCO's RM1 files (limit rows, no record of the weight): written again, the same
    entries and numbers; the assumption about the restoring is said."""
    source = corpus / "ROSCO" / "wamit_MHK_RM1_floating" / "MHK_RM1_Floating.1"
    out = tmp_path / "rm1.1"
    result = CliRunner().invoke(main, ["convert", str(source), str(out)])
    assert result.exit_code == 0, result.output
    assert "do not say whether the restoring holds the weight" in result.output
    assert "estimated" not in result.output  # the data's own limit rows
    for suffix in (".1", ".hst"):
        mine, theirs = _rows(out.with_suffix(suffix)), _rows(source.with_suffix(suffix))
        assert mine.keys() == theirs.keys(), suffix
        for key, values in theirs.items():
            np.testing.assert_array_equal(mine[key], values, err_msg=f"{suffix} {key}")


# --------------------------------------------------------------------------- limit rows


def test_missing_limit_rows_are_estimated_and_said(corpus, tmp_path):
    """RAFT's copy of the WEIS OC3 spar without its ω = 0 and ω = ∞ rows: the written .1
    holds them again; A∞ is Ogilvie's estimate (within 1e-4 of WAMIT's own row on the
    diagonal, measured 9e-5), A(0) the lowest frequency's (WAMIT's within 0.3 %)."""
    source = corpus / "RAFT" / "wamit_OC3_spar_no_A0_Ainf_rows" / "spar.1"
    out = tmp_path / "spar.1"
    text = _convert(source, out)
    assert "PER = 0 row) estimated" in text and "PER = -1 row) taken as" in text
    back = _read(out, rho=1025.0, g=9.81, ulen=1.0)
    data = _read(source, rho=1025.0, g=9.81, ulen=1.0)
    estimate = cummins.added_mass_inf(data, method="ogilvie").values
    written = dof_matrix(back, "added_mass_inf")
    assert np.abs(written - estimate).max() <= 1.2e-6 * np.abs(estimate).max()
    np.testing.assert_allclose(
        dof_matrix(back, "added_mass_zero"), dof_matrix(data, "added_mass")[0], rtol=1.2e-6
    )
    wamit = _read(corpus / "WEIS" / "ss_fitting_OC3_spar" / "spar.1", rho=1025.0, g=9.81)
    for name, tolerance in (("added_mass_inf", 5e-4), ("added_mass_zero", 1e-2)):
        ours, theirs = np.diag(dof_matrix(back, name)), np.diag(dof_matrix(wamit, name))
        assert np.all(np.abs(ours - theirs) <= tolerance * np.abs(theirs)), name
    bare = tmp_path / "bare.1"
    text = _convert(source, bare, "--no-limit-rows")
    assert "estimated" not in text
    assert not any(key[0] <= 0 for key in _rows(bare))


# --------------------------------------------------------------------------- said


def test_qtfs_are_said_to_go_to_their_own_files(corpus, tmp_path):
    text = _convert(corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar", tmp_path / "s.1")
    assert "QTFs are not in the .1" in text and "s.12d" in text and "s.12s" in text
    assert not (tmp_path / "s.12d").exists()


def test_data_without_excitation_or_hydrostatics_say_so(corpus, tmp_path):
    """WEIS' OC4 semi (.1 .hst .12d .12s, its .3 missing): convert wrote s.1 and s.hst and
    said nothing of the .3 HydroDyn reads with ExctnMod = 1; now it says so."""
    text = _convert(corpus / "WEIS" / "ss_fitting_OC4_semi" / "marin_semi.1", tmp_path / "s.1")
    assert "no s.3: the data hold no wave excitation" in text and "ExctnMod = 0" in text
    assert not (tmp_path / "s.3").exists()
    text = _convert(corpus / "WEIS" / "ss_fitting_OC3_spar" / "spar.1", tmp_path / "t.1")
    assert "no t.3" not in text and (tmp_path / "t.3").exists()
    assert "no t.hst" not in text and (tmp_path / "t.hst").exists()
    # RAFT's copy of the spar has no .hst: said as well
    raft = corpus / "RAFT" / "wamit_OC3_spar_no_A0_Ainf_rows" / "spar.1"
    text = _convert(raft, tmp_path / "r.1")
    assert "no r.hst: the data hold no hydrostatics" in text and "no r.3" not in text
    assert not (tmp_path / "r.hst").exists()


def test_main_help_lists_what_convert_writes():
    result = CliRunner().invoke(main, ["--help"])
    line = " ".join(result.output.split())
    assert all(s in line for s in (".nc", ".h5", ".1/.3/.hst", ".12d/.12s", ".mat"))


@pytest.mark.parametrize(
    ("case", "kind", "states"),
    [
        (("ROSCO", "wamit_ITI_barge_5MW_Baseline", "Barge.ss"), "radiation", 30),
        (("WEIS", "ss_fitting_OC3_spar", "spar.ssexctn"), "excitation", 57),
        (("WEIS", "ss_fitting_OC4_semi", "marin_semi.ss"), "excitation", 30),
    ],
)
def test_info_describes_openfast_state_space_files(corpus, case, kind, states):
    """The counts of line 4 of the file (HydroDyn's grouping of the states per DOF) and the
    states; an .ss that holds an excitation fit is told as one."""
    path = corpus.joinpath(*case)
    result = CliRunner().invoke(main, ["info", str(path), "--json"])
    assert result.exit_code == 0, result.output
    d = json.loads(result.output[result.output.index("{") :])
    assert kind in d["kind"] and d["states"] == states and d["stable"] is True
    listed = sum(int(part.split(":")[1]) for part in d["states_per_dof"].split(","))
    assert listed == states
    if kind == "radiation":  # line 4: the states of each DOF
        assert sum(int(x) for x in path.read_text().splitlines()[3].split()[:6]) == states


def test_a_hydrodyn_input_file_names_the_wamit_files_it_reads(corpus, tmp_path):
    """ROSCO's RM1 HydroDyn input (PotFile "MHK_RM1_Floating", WAMITULEN 1): cummins says
    which files to read instead of "unrecognised file format", and those files read."""
    dat = corpus / "ROSCO" / "wamit_MHK_RM1_floating" / "MHK_RM1_Floating_HydroDyn.dat"
    result = CliRunner().invoke(main, ["info", str(dat)])
    text = " ".join(result.output.split())
    assert result.exit_code == 1 and "unrecognised" not in text
    assert "HydroDyn input file" in text and "--ulen 1" in text
    named = text.split("cummins info ")[-1].split()[0]
    assert named == str(dat.parent / "MHK_RM1_Floating.1")
    assert _read(named, ulen=1.0).sizes["omega"] == 420
    # PotMod = 0: no potential-flow data to point at
    lines = dat.read_text().splitlines()
    lines = [
        ("0   PotMod   - no potential flow" if "PotMod" in line.split()[1:2] else line)
        for line in lines
    ]
    off = tmp_path / "off_HydroDyn.dat"
    off.write_text("\n".join(lines) + "\n")
    result = CliRunner().invoke(main, ["info", str(off)])
    assert result.exit_code == 1 and "PotMod = 0" in " ".join(result.output.split())


def test_openfast_models_say_their_reference_point(corpus, tmp_path):
    """NEMOH's OC3 run is about (0, 0, -78) m: `fit --openfast` and `fit-excitation
    --openfast` wrote .ss/.ssexctn about that point without a word, where HydroDyn takes
    PtfmRefzt and the .1/.hst (convert's, often moved to the origin) must agree. They say
    it now; about the origin (WEIS' WAMIT spar) nothing is added."""
    nemoh = str(corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar")
    excitation = ["fit-excitation", nemoh, "-o", str(tmp_path / "b.nc"), "--heading", "0"]
    runs = [
        ["fit", nemoh, "-o", str(tmp_path / "a.nc"), "--openfast", str(tmp_path / "a.ss")],
        [*excitation, "--openfast", str(tmp_path / "b.ssexctn")],
    ]
    for args in runs:
        result = CliRunner().invoke(main, args)
        assert result.exit_code == 0, result.output
        text = " ".join(result.output.split())
        assert "moments about [0.0, 0.0, -78.0] m (z-up), the data's reference point" in text
    spar = str(corpus / "WEIS" / "ss_fitting_OC3_spar" / "spar.1")
    result = CliRunner().invoke(
        main, ["fit", spar, "-o", str(tmp_path / "c.nc"), "--openfast", str(tmp_path / "c.ss")]
    )
    assert result.exit_code == 0 and "moments about" not in result.output
