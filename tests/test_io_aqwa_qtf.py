"""AQWA listings of the 2023 R1 layout and of two structures, and AQWA's ``.QTF`` files.

SYNTHETIC FILES: no AQWA file of these kinds is public under a licence that lets cummins
ship it (BEMRosetta's AQWA 2023 R1 box runs are GPL-3.0). The files here are built by
``tests/_aqwa_layouts.py``: the layouts of those AQWA 2023 R1 files around the real
numbers of the corpus's AQWA 19.1 PEND hull listing (WEC-Sim, Apache-2.0), and a ``.QTF``
whose diagonal is that listing's mean drift and whose off-diagonal values are invented.
What they check is the reading (layouts, structures, conventions applied, damage); the
conventions themselves were checked on the real GPL files (docs/second_order.md), and
one of those checks stays here: AQWA's printed QTF of the 2 m box, two numbers per
frequency pair quoted, against the long-wave physics of ``tests/_bound_waves.py``. A real
permissively licensed file is still needed to close the item.
"""

from __future__ import annotations

import shutil
import warnings

import numpy as np
import pytest

import cummins
from _aqwa_layouts import DY, build_runs, synthetic_qtf, write_aqtf
from _bound_waves import small_body_forces, wavenumber
from cummins import HydroDataError, HydroDataWarning
from cummins.io.aqwa.qtf import read_aqwa_qtf
from cummins.qtf import qtf_table


@pytest.fixture(scope="module")
def runs(shared_data, tmp_path_factory):
    return build_runs(shared_data, tmp_path_factory.mktemp("aqwa_layouts"))


@pytest.fixture(scope="module")
def original(shared_data):
    return cummins.read(shared_data / "corpus/WEC-Sim/aqwa_19.1_PEND_hull/19_1.LIS")


def _read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("error", HydroDataWarning)  # an undamaged file reads clean
        return cummins.read(path)


# --------------------------------------------------------------------------- listings


def test_2023_layout_reads_as_the_19_1_listing(runs, original):
    """Directions inside the frequency table, the drift's six DOFs in one block: the same
    numbers as the 19.1 layout of the same listing."""
    ds = _read(runs["2023"] / "19_1.LIS")
    assert set(ds.data_vars) - set(original.data_vars) == {"qtf_difference", "qtf_sum"}
    for name in original.data_vars:
        np.testing.assert_array_equal(ds[name].values, original[name].values, err_msg=name)
    np.testing.assert_array_equal(ds.omega.values, original.omega.values)
    np.testing.assert_array_equal(ds.wave_direction.values, original.wave_direction.values)


@pytest.mark.parametrize("name", ["2023x2", "19.1x2"])
def test_two_structures_read_each_about_its_own_centre_of_gravity(runs, original, name):
    """Structure 2 is structure 1 moved by DY along y: the same matrices, no coupling, and
    its wave forces referred to the origin from a point DY further: X₂ = X₁ e^{−ik DY sin β}."""
    ds = _read(runs[name] / "19_1.LIS")
    assert ds.sizes["influenced_dof"] == 12
    assert [str(d) for d in ds.influenced_dof.values[[0, 6]]] == ["body1__Surge", "body2__Surge"]
    for var in ("added_mass", "radiation_damping"):
        block = ds[var].values
        np.testing.assert_array_equal(block[:, :6, :6], original[var].values)
        np.testing.assert_array_equal(block[:, 6:, 6:], original[var].values)
        assert not block[:, :6, 6:].any() and not block[:, 6:, :6].any()
    cg = np.asarray(ds.attrs["center_of_gravity"]).reshape(2, 3)
    np.testing.assert_allclose(cg[1] - cg[0], [0, DY, 0])
    k = aqwa_k(ds)
    shift = np.exp(-1j * k[:, None] * DY * np.sin(ds.wave_direction.values)[None, :])
    x = ds.excitation_force.values
    np.testing.assert_allclose(x[..., :6], original.excitation_force.values, rtol=1e-12)
    np.testing.assert_allclose(x[..., 6:], x[..., :6] * shift[..., None], rtol=1e-12, atol=0)
    drift = ds.drift_force.values
    np.testing.assert_array_equal(drift[..., 6:], drift[..., :6])
    assert "no added mass or damping between the structures" in ds.attrs["history"]


def aqwa_k(ds):
    from cummins.io.aqwa import wavenumber as k_of

    return k_of(ds.omega.values, float(ds.attrs["water_depth"]), float(ds.attrs["g"]))


def _edit(path, old, new, count=1):
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, count))


def test_directions_announced_but_not_listed_are_refused(runs, tmp_path):
    run = tmp_path / "run"
    shutil.copytree(runs["2023"], run)
    _edit(run / "19_1.LIS", "    0.00   90.00  180.00\n", "    0.00   90.00\n")
    with pytest.raises(HydroDataError, match="announces 5 directions and lists 4"):
        cummins.read(run / "19_1.LIS")


def test_a_lost_frequency_row_is_refused(runs, tmp_path):
    run = tmp_path / "run"
    shutil.copytree(runs["2023"], run)
    lines = (run / "19_1.LIS").read_text().splitlines()
    row = next(i for i, line in enumerate(lines) if line.split()[:2] == ["7", "1.23471"])
    del lines[row]
    (run / "19_1.LIS").write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match="frequency number 8 where 7 was expected"):
        cummins.read(run / "19_1.LIS")


def test_structures_with_other_grids_are_refused(runs, tmp_path):
    run = tmp_path / "run"
    shutil.copytree(runs["2023x2"], run)
    text = (run / "19_1.LIS").read_text()
    second = text.index("      2     1   0.10000")
    text = text[:second] + text[second:].replace("-90.00    0.00", "-45.00    0.00", 1)
    (run / "19_1.LIS").write_text(text)
    with pytest.raises(HydroDataError, match="structure 2 has other wave directions"):
        cummins.read(run / "19_1.LIS")


def test_interaction_matrices_are_refused(runs, tmp_path):
    run = tmp_path / "run"
    shutil.copytree(runs["2023x2"], run)
    _edit(run / "19_1.LIS", "ADDED  MASS", "ADDED MASS FOR FORCE ON STR#1 DUE TO MOTION OF STR#2")
    with pytest.raises(HydroDataError, match="hydrodynamic interaction"):
        cummins.read(run / "19_1.LIS")


def test_a_page_whose_structure_is_lost_is_refused(runs, tmp_path):
    """The title naming structure 2 of a hydrostatics page blanked: its centre of gravity
    could be either structure's."""
    run = tmp_path / "run"
    shutil.copytree(runs["2023x2"], run)
    lines = (run / "19_1.LIS").read_text().splitlines()
    hydrostatics = [i for i, line in enumerate(lines) if "H Y D R O S T A T I C   P R O" in line]
    marker = next(
        k
        for k in range(hydrostatics[1], hydrostatics[1] + 6)
        if "S T R U C T U R E   2" in lines[k]
    )
    lines[marker] = ""
    (run / "19_1.LIS").write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match="names no structure"):
        cummins.read(run / "19_1.LIS")


def test_a_matrix_row_moved_between_frequencies_is_refused(runs, tmp_path):
    """Rows of the listing's matrices are labelled X … RZ, not by frequency: the damping's
    RY row swapped with the RY row of another frequency leaves a matrix far from
    symmetric (a swap between two nearly equal matrices stays invisible)."""
    run = tmp_path / "run"
    shutil.copytree(runs["2023"], run)
    lines = (run / "19_1.LIS").read_text().splitlines()
    damping = [i for i, line in enumerate(lines) if line.strip() == "DAMPING"]

    def ry_row(label):
        return next(k for k in range(label, label + 30) if lines[k].split()[:1] == ["RY"])

    first, second = ry_row(damping[10]), ry_row(damping[60])
    lines[first], lines[second] = lines[second], lines[first]
    (run / "19_1.LIS").write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=r"damping at .* is not symmetric"):
        cummins.read(run / "19_1.LIS")


# --------------------------------------------------------------------------- .QTF


def test_qtf_diagonal_is_the_listing_mean_drift(runs):
    """The QTF beside the listing reads; check finds its diagonal on the listing's drift
    (the file's diagonal is that drift rounded to 5 digits) and its mirror symmetries."""
    ds = _read(runs["2023"] / "19_1.LIS")
    assert {"qtf_difference", "qtf_sum"} <= set(ds.data_vars)
    table = qtf_table(ds, "difference")
    assert table.values.shape == (6, 6, 5, 6)
    findings = {f.check: f for f in cummins.check(ds).findings if f.check.startswith("qtf_")}
    assert findings["qtf_mean_drift"].severity == "ok"
    assert findings["qtf_mean_drift"].value < 1e-3
    assert findings["qtf_symmetry"].severity == "ok"
    assert "AQTF-2.0" in ds.attrs["history"]


def test_a_qtf_of_another_drift_is_named_by_check(runs, tmp_path):
    run = tmp_path / "run"
    shutil.copytree(runs["2023"], run)
    ds = _read(run / "19_1.LIS")
    table = qtf_table(ds, "difference")
    qd = table.values.copy()
    qd[..., 2] *= 1.3  # heave 30 % larger (CG at the origin in x, y: no phase referral)
    qs = qtf_table(ds, "sum").values
    write_aqtf(run / "19_1.QTF", [(1, np.degrees(table.directions), table.omega, qd, qs)])
    findings = cummins.check(_read(run / "19_1.LIS")).findings
    finding = next(f for f in findings if f.check == "qtf_mean_drift")
    assert finding.severity == "warning"
    assert finding.where.startswith("Heave")


def test_qtf_of_two_structures_referred_from_each_centre_of_gravity(runs):
    """The two blocks hold the same CG-relative QTF; structure 2's CG is DY further along y:
    Q⁻₂ = Q⁻₁ e^{−i(k_i − k_j) DY sin β}, Q⁺₂ = Q⁺₁ e^{−i(k_i + k_j) DY sin β}."""
    ds = _read(runs["2023x2"] / "19_1.LIS")
    for kind, sign in (("difference", -1), ("sum", 1)):
        table = qtf_table(ds, kind)
        k = aqwa_k_of(table.omega, ds)
        phase = (k[:, None] + sign * k[None, :])[..., None] * DY * np.sin(table.directions)
        expected = table.values[..., :6] * np.exp(-1j * phase)[..., None]
        np.testing.assert_allclose(table.values[..., 6:], expected, rtol=1e-9, atol=1e-12)
    diag = qtf_table(ds, "difference").diagonal()
    np.testing.assert_array_equal(diag[..., 6:], diag[..., :6])  # the mean drift: no phase


def aqwa_k_of(omega, ds):
    from cummins.io.aqwa import wavenumber as k_of

    return k_of(omega, float(ds.attrs["water_depth"]), float(ds.attrs["g"]))


def test_a_damaged_qtf_is_left_out_with_a_warning(runs, tmp_path):
    run = tmp_path / "run"
    shutil.copytree(runs["2023"], run)
    lines = (run / "19_1.QTF").read_text().splitlines()
    del lines[40]
    (run / "19_1.QTF").write_text("\n".join(lines) + "\n")
    with pytest.warns(HydroDataWarning, match="QTFs not read"):
        ds = cummins.read(run / "19_1.LIS")
    assert "qtf_difference" not in ds and "added_mass" in ds


def test_an_edited_record_that_breaks_its_mirror_is_refused(runs, tmp_path):
    path = tmp_path / "x.QTF"
    shutil.copy(runs["2023"] / "19_1.QTF", path)
    lines = path.read_text().splitlines()
    record = next(i for i, line in enumerate(lines) if line.split()[:4] == ["1", "1", "1", "2"])
    words = lines[record + 2].split()
    words[2] = f"{float(words[2]) * 1.01:.4E}"
    lines[record + 2] = " " * 15 + "".join(f" {float(w): .4E}" for w in words)
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match="disagree in row 3, DOF 3"):
        read_aqwa_qtf(path, cgs=np.zeros((1, 3)), depth=np.inf, g=9.81)


def test_a_mean_drift_with_an_imaginary_part_is_refused(runs, tmp_path):
    """AQWA writes the Im row of Q⁻(ω, ω) as zeros: a row moved there is damage (the
    diagonal has no mirror to betray it)."""
    path = tmp_path / "x.QTF"
    shutil.copy(runs["2023"] / "19_1.QTF", path)
    lines = path.read_text().splitlines()
    record = next(i for i, line in enumerate(lines) if line.split()[:4] == ["1", "2", "3", "3"])
    lines[record + 1], lines[record + 3] = lines[record + 3], lines[record + 1]
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match="mean drift Q-\\(w, w\\) has an imaginary part"):
        read_aqwa_qtf(path, cgs=np.zeros((1, 3)), depth=np.inf, g=9.81)


def test_qtf_beside_a_database_of_two_structures(corpus, tmp_path):
    """The .AH1 alone (the floating OWC, two structures) reads the .QTF beside it too,
    each block's phases referred from its structure's centre of gravity (COG section)."""
    run = tmp_path / "owc"
    shutil.copytree(corpus / "WEC-Sim_Applications/aqwa_floating_OWC_AH1only", run)
    ds = cummins.read(run / "floatingOWC.AH1")
    omega = ds.omega.values[[10, 20, 30]]
    directions = np.degrees(ds.wave_direction.values)
    rng = np.random.default_rng(1)
    qd, qs = synthetic_qtf(omega, rng.uniform(1e3, 1e4, (3, directions.size, 6)))
    write_aqtf(
        run / "floatingOWC.QTF", [(1, directions, omega, qd, qs), (2, directions, omega, qd, qs)]
    )
    out = _read(run / "floatingOWC.AH1")
    table = qtf_table(out, "difference")
    assert table.values.shape == (3, 3, directions.size, 12)
    cg = np.asarray(out.attrs["center_of_gravity"]).reshape(2, 3)
    k = aqwa_k_of(table.omega, out)
    for body in range(2):
        d = cg[body, 0] * np.cos(table.directions) + cg[body, 1] * np.sin(table.directions)
        shift = np.exp(-1j * (k[:, None] - k[None, :])[..., None] * d)
        np.testing.assert_allclose(
            table.values[..., 6 * body : 6 * body + 6], qd * shift[..., None], rtol=1e-12
        )


def test_the_qtf_alone_says_which_file_to_read(runs):
    with pytest.raises(HydroDataError, match=r"read 19_1\.LIS, which reads the \.QTF beside it"):
        cummins.read(runs["2023"] / "19_1.QTF")


def test_version_1_and_binary_mqt(runs, tmp_path):
    run = tmp_path / "run"
    shutil.copytree(runs["2023"], run)
    (run / "19_1.MQT").write_bytes(b"\x00\x01binary")
    ds = _read(run / "19_1.LIS")
    assert "19_1.MQT not read" in ds.attrs["history"]
    _edit(run / "19_1.QTF", "AQTF-2.0", "AQTF-1.0")
    with pytest.warns(HydroDataWarning, match="AQTF version 1.0"):
        cummins.read(run / "19_1.LIS")


# --------------------------------------------------------------------------- the sign

#: AQWA 2023 R1's QTF of BEMRosetta's Box1 (a 2 m cube floating in 70 m of water, CG
#: (0, 2, -1) m, 8200 kg), waves along +x (0 deg): Q⁻(ω₁, ω₂) surge and heave as printed
#: (Re, Im), and the listing's A11, A33, C33 at 0.1 rad/s. Quoted from
#: examples/aqwa/line/Box1/ANALYSIS.QTF and ANALYSIS.LIS of BEMRosetta (GPL-3.0).
BOX1 = {
    (0.0999969, 0.4000002): ((-2.3038e-03, 9.5201e01), (-9.5458e02, 7.0908e-01), (156.86, 370.03)),
    (0.0999969, 0.7000003): ((-2.1114e-01, 4.0762e02), (-3.5629e02, 9.8938e00), (156.86, 912.63)),
}
BOX1_BODY = {"mass": 8200.0, "a11": 7795.2, "a33": 3742.6, "c33": 40221.0, "z": -1.0}


@pytest.mark.parametrize("pair", sorted(BOX1))
def test_aqwa_printed_qtf_has_the_sign_of_the_long_wave_physics(tmp_path, pair):
    """The surge force of the bound set-down flow on the small box is +i|F| for ω₁ < ω₂ in
    waves travelling along +x (tests/_bound_waves.py); AQWA's printed record, read as
    Re + i Im without conjugation, has it (a conjugated reading would give −i|F|)."""
    (sx, sz, (t1, t2)) = BOX1[pair]
    omega = np.array(pair)
    qd = np.zeros((2, 2, 1, 6), dtype=complex)
    qd[0, 0, 0, 2], qd[1, 1, 0, 2] = t1, t2
    qd[0, 1, 0, 0], qd[0, 1, 0, 2] = complex(*sx), complex(*sz)
    qd[1, 0] = np.conj(qd[0, 1])
    path = tmp_path / "box.QTF"
    write_aqtf(path, [(1, np.array([0.0]), omega, qd, np.zeros_like(qd))])
    tables, _, _ = read_aqwa_qtf(path, cgs=np.array([[0.0, 2.0, -1.0]]), depth=70.0, g=9.81)
    q = tables["difference"][2][0, 1, 0]  # Q⁻(ω₁, ω₂), β = 0, at the origin
    surge, heave = small_body_forces(*pair, 70.0, **BOX1_BODY)
    assert q[0].imag > 0 and surge.imag > 0
    assert abs(q[0] - surge) < 0.25 * abs(surge)
    assert q[2].real < 0 and heave.real < 0
    if pair[1] < 0.5:
        assert abs(q[2] - heave) < 0.1 * abs(heave)


def test_wavenumbers_of_the_two_references_agree():
    """The test's wave number and the reader's solve the same dispersion relation."""
    from cummins.io.aqwa import wavenumber as k_of

    omega = np.array([0.1, 0.4, 0.7, 1.0])
    np.testing.assert_allclose(k_of(omega, 70.0, 9.81), [wavenumber(w, 70.0) for w in omega])
