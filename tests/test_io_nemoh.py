"""NEMOH reader: the WEC-Sim cylinder (NEMOH v3.0.2), its v2 layout, damaged files.

Reference values are the numbers NEMOH printed in the files (quoted from the file text),
or physics that NEMOH's other files state independently (ρ g A_wp against KH.dat,
excitation = Froude-Krylov + diffraction).
"""

from __future__ import annotations

import re
import shutil
import warnings

import numpy as np
import pytest
import xarray as xr

import cummins
from cummins import HydroDataError
from cummins.io import nemoh

NEMOH_FILES = (
    "Nemoh.cal",
    "Mesh.cal",
    "KH.dat",
    "Hydrostatics.dat",
    "RadiationCoefficients.tec",
    "ExcitationForce.tec",
    "DiffractionForce.tec",
    "FKForce.tec",
    "IRF.tec",
)


@pytest.fixture(scope="module")
def run_dir(shared_data):
    return shared_data / "wecsim" / "cylinder" / "cylinder_nemoh"


@pytest.fixture(scope="module")
def cylinder(run_dir):
    with pytest.warns(UserWarning, match="IRF.tec"):
        return nemoh.read_nemoh(run_dir)


@pytest.fixture
def nemoh_copy(run_dir, tmp_path):
    """The NEMOH files of the run (only those) in a scratch folder."""
    folder = tmp_path / "run"
    folder.mkdir()
    for name in NEMOH_FILES:
        shutil.copy(run_dir / name, folder / name)
    return folder


def _read_quiet(path, **kwargs):
    with pytest.warns(UserWarning, match="IRF.tec"):
        return nemoh.read_nemoh(path, **kwargs)


# --------------------------------------------------------------------------- detection


def test_sniff_recognises_nemoh_files_only(run_dir, shared_data):
    for name in (
        "RadiationCoefficients.tec",
        "ExcitationForce.tec",
        "DiffractionForce.tec",
        "FKForce.tec",
        "IRF.tec",
        "Nemoh.cal",
    ):
        assert nemoh.sniff(run_dir / name), name
    for other in (
        run_dir / "cyl.1",
        run_dir / "cyl.out",
        run_dir / "KH.dat",
        run_dir / "cylinder_hydrodynamics.nc",
        shared_data / "wecsim" / "cylinder_aqwa" / "cylinder.LIS",
    ):
        assert not nemoh.sniff(other), other.name


def test_sniff_dir_returns_the_one_run(run_dir, tmp_path):
    assert nemoh.sniff_dir(run_dir) == [run_dir / "RadiationCoefficients.tec"]
    assert nemoh.sniff_dir(tmp_path) == []


def test_folder_with_several_solvers_is_ambiguous_for_the_registry(run_dir):
    """The folder also holds WAMIT cyl.* output: the registry must not guess."""
    with pytest.raises(HydroDataError, match="several runs"):
        cummins.read(run_dir)
    with pytest.warns(UserWarning, match="IRF.tec"):
        ds = cummins.read(run_dir, format="nemoh")
    assert ds.attrs["source_format"] == "nemoh"


def test_every_entry_point_reads_the_same_run(cylinder, run_dir):
    for name in (
        "RadiationCoefficients.tec",
        "ExcitationForce.tec",
        "FKForce.tec",
        "DiffractionForce.tec",
        "IRF.tec",
        "Nemoh.cal",
    ):
        with pytest.warns(UserWarning, match="IRF.tec"):
            ds = cummins.read(run_dir / name)
        xr.testing.assert_identical(ds.drop_attrs(), cylinder.drop_attrs())


# --------------------------------------------------------------------------- values


def test_radiation_values_and_orientation(cylinder):
    """Zone j ("Motion … in DoF j") pair k is A[influenced k, radiating j] (file text)."""
    a = cylinder.added_mass.isel(omega=0)
    b = cylinder.radiation_damping.isel(omega=0)
    assert float(cylinder.omega[0]) == 0.04
    # zone "DoF 3", first row: 0.1231259E+03 0.4875782E+00 in pair 3
    assert float(a.sel(influenced_dof="Heave", radiating_dof="Heave")) == 123.1259
    assert float(b.sel(influenced_dof="Heave", radiating_dof="Heave")) == 0.4875782
    # zone "DoF 1" pair 5 is -0.4920152E+02; zone "DoF 5" pair 1 is -0.4920866E+02
    assert float(a.sel(influenced_dof="Pitch", radiating_dof="Surge")) == -49.20152
    assert float(a.sel(influenced_dof="Surge", radiating_dof="Pitch")) == -49.20866
    assert cylinder.omega.size == 525
    assert float(cylinder.omega[-1]) == 21.0


def test_constants_and_reference_point_from_nemoh_cal(cylinder):
    assert cylinder.attrs["rho"] == 1000.0
    assert cylinder.attrs["g"] == 9.81
    assert cylinder.attrs["water_depth"] == 3.0
    assert cylinder.attrs["nemoh_version"] == "v3"
    assert cylinder.attrs["body_name"] == "cylinder"
    np.testing.assert_array_equal(cylinder.attrs["reference_point"], [0.0, 0.0, 0.0])
    assert list(cylinder.influenced_dof.values) == list(cummins.DOF_NAMES)
    np.testing.assert_array_equal(cylinder.wave_direction, [0.0])


def test_hydrostatics_files(cylinder):
    """KH.dat against ρ g A_wp of Hydrostatics.dat; CB, CG, volume, mass = ρ V."""
    c = cylinder.hydrostatic_stiffness
    assert float(c.sel(influenced_dof="Heave", radiating_dof="Heave")) == 3764.562
    rho_g_awp = 1000 * 9.81 * cylinder.attrs["waterplane_area"]
    # both printed to 7 digits by NEMOH: agree to their rounding
    assert float(c.sel(influenced_dof="Heave", radiating_dof="Heave")) == pytest.approx(
        rho_g_awp, rel=1e-5
    )
    np.testing.assert_allclose(cylinder.attrs["center_of_buoyancy"], [0, 0, -0.315])
    np.testing.assert_allclose(cylinder.attrs["center_of_gravity"], [0, 0, 0])
    assert cylinder.attrs["displaced_volume"] == 0.2417605
    assert cylinder.attrs["mass"] == pytest.approx(1000 * cylinder.attrs["displaced_volume"])


def test_excitation_is_conjugated_and_sums_diffraction_and_froude_krylov(cylinder):
    x = cylinder.excitation_force.isel(omega=0, wave_direction=0)
    # ExcitationForce.tec, first row: |F1| = 0.3036780E+02, angle = -0.1570798E+01 rad
    surge = complex(x.sel(influenced_dof="Surge"))
    assert abs(surge) == pytest.approx(30.3678, rel=1e-12)
    assert np.angle(surge) == pytest.approx(+1.570798, abs=1e-12)
    # The three files are independent printouts: X = FK + diffraction, to print precision.
    total = cylinder.diffraction_force + cylinder.Froude_Krylov_force
    scale = np.abs(cylinder.excitation_force).max(dim="omega")
    assert float((np.abs(cylinder.excitation_force - total) / scale).max()) < 1e-5
    assert "conjugated" in cylinder.attrs["history"]


def test_rho_must_match_the_dimensional_files(run_dir):
    ds = _read_quiet(run_dir, rho=1000.0, g=9.81)
    assert ds.attrs["rho"] == 1000.0
    with pytest.raises(HydroDataError, match="rho = 1025"):
        nemoh.read_nemoh(run_dir, rho=1025.0)


# --------------------------------------------------------------------------- IRF.tec


def _nemoh_k(ds: xr.Dataset, time: np.ndarray) -> np.ndarray:
    """NEMOH's IRF: (2/π)∫B cos(ωt)dω, trapezoidal rule on the run's grid, (t, i, j)."""
    w = ds.omega.values
    b = ds.radiation_damping.values
    return (
        2 / np.pi * np.trapezoid(b[:, None] * np.cos(np.outer(w, time))[..., None, None], w, axis=0)
    )


def test_irf_tec_of_another_run_is_rejected(cylinder, run_dir):
    """IRF.tec in this folder is not this cylinder's: A∞ is left unset, with a note.

    Its AddedMass (heave 2.4e5 kg) is 2900 times WAMIT's A∞ of this cylinder (83.6 kg),
    and its K(t) is not the transform of RadiationCoefficients.tec's damping.
    """
    assert "added_mass_inf" not in cylinder
    assert "IRF.tec not used" in cylinder.attrs["history"]
    irf = nemoh._read_tecplot(run_dir / "IRF.tec")
    time = irf.zones[2].table[:, 0]
    k_file = irf.zones[2].table[:, 6]  # zone "DoF 3", column "IRF 3"
    k_run = _nemoh_k(cylinder, time)[:, 2, 2]
    assert np.abs(k_file - k_run).max() > 100 * np.abs(k_run).max()
    wamit = cummins.read(run_dir / "cyl.1", rho=1000)
    a33_irf = irf.zones[2].table[0, 5]
    a33_wamit = float(wamit.added_mass_inf.sel(influenced_dof="Heave", radiating_dof="Heave"))
    assert a33_irf / a33_wamit > 1000


def _write_irf(path, ds: xr.Dataset, added_mass_inf: np.ndarray) -> None:
    """An IRF.tec as NEMOH's post-processor writes it (format of postProcessor/IRF.f90)."""
    time = np.arange(1, 101) * 0.1
    k = _nemoh_k(ds, time)
    n = ds.sizes["influenced_dof"]
    lines = [' VARIABLES="Time (s)"']
    lines += [f'"AddedMass {j + 1:4d}" "IRF {j + 1:4d}"' for j in range(n)]
    for j in range(n):  # zone j: radiating DOF j; column pair i: influenced DOF i
        lines.append(f'Zone t="DoF {j + 1:4d}",I={time.size:6d},F=POINT')
        for t in range(time.size):
            values = [time[t]]
            for i in range(n):
                values += [added_mass_inf[i, j], k[t, i, j]]
            lines.append(" ".join(f"{v:14.7E}" for v in values))
    path.write_text("\n".join(lines) + "\n")


def test_irf_tec_of_the_run_gives_added_mass_inf(cylinder, run_dir, nemoh_copy):
    """A consistent IRF.tec is used, zone = radiating DOF, column = influenced DOF."""
    wamit = cummins.read(run_dir / "cyl.1", rho=1000)
    a_inf = wamit.added_mass_inf.values  # A15 = -34.99, A51 = -35.01: not symmetric
    _write_irf(nemoh_copy / "IRF.tec", cylinder, a_inf)
    ds = nemoh.read_nemoh(nemoh_copy)
    np.testing.assert_allclose(ds.added_mass_inf.values, a_inf, rtol=1e-6, atol=1e-12)
    assert "from NEMOH's IRF.tec" in ds.attrs["history"]


# --------------------------------------------------------------------------- v2 and variants


def _to_v2(folder):
    """Rewrite a v3 run as NEMOH v2 lays it out (Mesh/, Results/, v2 Nemoh.cal and titles)."""
    (folder / "Mesh").mkdir()
    (folder / "Results").mkdir()
    for name in ("KH.dat", "Hydrostatics.dat"):
        (folder / name).rename(folder / "Mesh" / name)
    for name in (
        "RadiationCoefficients.tec",
        "ExcitationForce.tec",
        "DiffractionForce.tec",
        "FKForce.tec",
    ):
        (folder / name).rename(folder / "Results" / name)
    (folder / "IRF.tec").unlink()
    cal = (folder / "Nemoh.cal").read_text().splitlines()
    cal = [
        re.sub(
            r"^1\t525\t0.04\t21.0\t\t! Freq type 1,2,3=\[rad/s,Hz,s\], ",
            "525\t0.04\t21.0\t! ",
            line,
        )
        for line in cal
    ]
    cut = next(i for i, line in enumerate(cal) if "Response Amplitude Operator" in line)
    (folder / "Nemoh.cal").write_text("\n".join(cal[:cut]) + "\n---\n")
    hydro = folder / "Mesh" / "Hydrostatics.dat"
    hydro.write_text(
        "".join(line for line in hydro.read_text().splitlines(keepends=True) if "Mass" not in line)
    )
    exc = folder / "Results" / "ExcitationForce.tec"
    exc.write_text(exc.read_text().replace("Excitation force - beta", "Diffraction force - beta"))


def test_v2_layout_reads_the_same(cylinder, nemoh_copy):
    _to_v2(nemoh_copy)
    ds = nemoh.read_nemoh(nemoh_copy)
    assert ds.attrs["nemoh_version"] == "v2"
    for name in cylinder.data_vars:
        xr.testing.assert_equal(ds[name], cylinder[name])
    assert "mass" not in ds.attrs
    assert ds.attrs["displaced_volume"] == cylinder.attrs["displaced_volume"]
    assert nemoh.sniff_dir(nemoh_copy) == [nemoh_copy / "Results" / "RadiationCoefficients.tec"]


def _rewrite_first_column(path, function, header):
    lines = path.read_text().splitlines()
    out = []
    for line in lines:
        values = line.split()
        if values and re.fullmatch(r"[-+]?\d\.\d+E[-+]\d+", values[0]):
            values[0] = f"{function(float(values[0])):.12E}"
            line = "  " + "  ".join(values)
        elif line.startswith("VARIABLES"):
            line = f'VARIABLES="{header}"'
        out.append(line)
    path.write_text("\n".join(out) + "\n")


@pytest.mark.parametrize(
    ("function", "header"),
    [
        (lambda w: w / (2 * np.pi), "f (Hz)"),
        (lambda w: 2 * np.pi / w, "T (s)"),
    ],
)
def test_v3_output_frequency_units(cylinder, nemoh_copy, function, header):
    """v3 writes the first column in Hz or s when "output freq type" is 2 or 3."""
    (nemoh_copy / "IRF.tec").unlink()
    for name in ("RadiationCoefficients.tec", "ExcitationForce.tec", "DiffractionForce.tec"):
        _rewrite_first_column(nemoh_copy / name, function, header)
    ds = nemoh.read_nemoh(nemoh_copy)
    np.testing.assert_allclose(ds.omega, cylinder.omega, rtol=1e-10)
    np.testing.assert_allclose(ds.added_mass, cylinder.added_mass, rtol=1e-12)
    np.testing.assert_allclose(ds.excitation_force, cylinder.excitation_force, rtol=1e-12)
    assert f"in {header.split('(')[1][:-1]}, converted" in ds.attrs["history"]


def test_phases_in_degrees_are_recognised(cylinder, nemoh_copy):
    path = nemoh_copy / "ExcitationForce.tec"
    out = []
    for line in path.read_text().splitlines():
        values = parse = line.split()
        if values and re.fullmatch(r"[-+]?\d\.\d+E[-+]\d+", values[0]):
            parse = [float(v) for v in values]
            parse[2::2] = np.degrees(parse[2::2])
            line = "  ".join(f"{v:.9E}" for v in parse)
        out.append(line)
    path.write_text("\n".join(out) + "\n")
    ds = _read_quiet(nemoh_copy)
    np.testing.assert_allclose(ds.excitation_force, cylinder.excitation_force, rtol=1e-7)
    assert "ExcitationForce.tec (phases in degrees)" in ds.attrs["history"]


def test_results_without_nemoh_cal(cylinder, nemoh_copy):
    (nemoh_copy / "Nemoh.cal").unlink()
    ds = _read_quiet(nemoh_copy)
    np.testing.assert_array_equal(ds.added_mass, cylinder.added_mass)
    assert ds.attrs["rho"] == 1025.0
    assert "no Nemoh.cal" in ds.attrs["history"]
    assert "default" in ds.attrs["history"]


# --------------------------------------------------------------------------- damaged files


def test_truncated_radiation_file_names_file_and_line(nemoh_copy):
    path = nemoh_copy / "RadiationCoefficients.tec"
    lines = path.read_text().splitlines()
    path.write_text("\n".join(lines[:-40]) + "\n")
    with pytest.raises(HydroDataError, match=r"RadiationCoefficients.tec, line \d+: .*truncated"):
        nemoh.read_nemoh(nemoh_copy)


def test_garbled_number_names_the_line(nemoh_copy):
    path = nemoh_copy / "ExcitationForce.tec"
    lines = path.read_text().splitlines()
    lines[20] = lines[20].replace("E+", "X+", 1)
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=r"ExcitationForce.tec, line 21"):
        nemoh.read_nemoh(nemoh_copy)


def test_nan_names_the_line(nemoh_copy):
    path = nemoh_copy / "RadiationCoefficients.tec"
    lines = path.read_text().splitlines()
    values = lines[1100].split()
    values[5] = "NaN"
    lines[1100] = "  ".join(values)
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=r"line 1101: non-finite"):
        nemoh.read_nemoh(nemoh_copy)


def test_shuffled_frequency_column(nemoh_copy):
    path = nemoh_copy / "RadiationCoefficients.tec"
    lines = path.read_text().splitlines()
    rows = lines[8:533]
    order = np.random.default_rng(3).permutation(len(rows))
    lines[8:533] = [rows[k] for k in order]
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=r"RadiationCoefficients\.tec, line"):
        nemoh.read_nemoh(nemoh_copy)


def test_frequency_count_of_nemoh_cal_edited_after_the_run(cylinder, nemoh_copy):
    """Nemoh.cal asking for other frequencies than the results hold (as the OC3 spar of
    the corpus, edited after its run): the results' 525 frequencies are what the solver
    computed, so they are read, and history says which count was used and why."""
    cal = nemoh_copy / "Nemoh.cal"
    cal.write_text(cal.read_text().replace("1\t525\t0.04\t21.0", "1\t100\t0.04\t21.0"))
    with pytest.warns(UserWarning, match="IRF.tec"):
        ds = nemoh.read_nemoh(nemoh_copy)
    assert ds.sizes["omega"] == cylinder.sizes["omega"] == 525
    xr.testing.assert_equal(ds.added_mass, cylinder.added_mass)
    assert re.search(
        r"Nemoh\.cal asks for 100 .* holds 525 .* results' frequencies are used",
        ds.attrs["history"],
    )


def test_missing_and_foreign_files(tmp_path, run_dir, nemoh_copy):
    with pytest.raises(HydroDataError, match="no NEMOH results"):
        nemoh.read_nemoh(tmp_path)
    lonely = tmp_path / "lonely"
    lonely.mkdir()
    shutil.copy(run_dir / "ExcitationForce.tec", lonely)
    with pytest.raises(HydroDataError, match=r"RadiationCoefficients\.tec not found"):
        nemoh.read_nemoh(lonely / "ExcitationForce.tec")
    (nemoh_copy / "RadiationCoefficients.tec").write_text("")
    with pytest.raises(HydroDataError, match="empty"):
        nemoh.read_nemoh(nemoh_copy / "FKForce.tec")


# --------------------------------------------------------------------------- fuzz


def _mutate(text: str, rng: np.random.Generator) -> str:
    lines = text.splitlines()
    kind = rng.integers(5)
    i = int(rng.integers(len(lines)))
    if kind == 0:
        del lines[i]
    elif kind == 1:
        tokens = lines[i].split()
        if tokens:
            k = int(rng.integers(len(tokens)))
            tokens[k] = str(rng.choice(["1.2.3", "nan", "-", "*****", "1E+", "0", "-1"]))
            lines[i] = " ".join(tokens)
    elif kind == 2:
        return text[: int(rng.integers(len(text)))]
    elif kind == 3:
        lines.insert(i, lines[int(rng.integers(len(lines)))])
    else:
        j = int(rng.integers(len(lines)))
        lines[i], lines[j] = lines[j], lines[i]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize(
    "name",
    [
        "Nemoh.cal",
        "RadiationCoefficients.tec",
        "ExcitationForce.tec",
        "KH.dat",
        "Hydrostatics.dat",
        "IRF.tec",
        "FKForce.tec",
    ],
)
def test_fuzz_only_hydro_data_errors(nemoh_copy, name):
    """Mutated real files give a valid dataset or a HydroDataError, nothing else."""
    path = nemoh_copy / name
    original = path.read_text()
    rng = np.random.default_rng(sum(map(ord, name)))
    for _ in range(8):
        path.write_text(_mutate(original, rng))
        error = None
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)  # the foreign IRF.tec
                ds = nemoh.read_nemoh(nemoh_copy)
        except HydroDataError as exc:
            error = exc
        if error is None:
            cummins.validate(ds)
        else:
            assert error.path is not None or error.quantity is not None, str(error)
    path.write_text(original)


# --------------------------------------------------------------------------- corpus variants


def _read_warned(path, **options):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = cummins.read(path, **options)
    return ds, [str(w.message) for w in caught if issubclass(w.category, cummins.HydroDataWarning)]


def _nemoh_dat(path):
    """CA.dat / CM.dat of NEMOH v3: ``Nb de frequency : n``, then per frequency the
    frequency and an n×n block whose row j is the radiating DOF j."""
    lines = [line.split() for line in path.read_text().splitlines()[1:] if line.strip()]
    blocks, omega, k = [], [], 0
    while k < len(lines):
        omega.append(float(lines[k][0]))
        n = len(lines[k + 1])
        blocks.append(np.array(lines[k + 1 : k + 1 + n], dtype=float))
        k += 1 + n
    return np.array(omega), np.array(blocks)


@pytest.fixture(scope="module")
def oc3(corpus):
    return _read_warned(corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar")


def test_oc3_spar_qtf_run_with_edited_nemoh_cal(oc3, corpus):
    """The OC3 spar's Nemoh.cal asks for 26 frequencies (0.025–1.5 rad/s) but its results
    (and index.dat) hold 128 (0.025–6 rad/s): the results are read, history says why,
    and CM.dat/CA.dat, NEMOH's own second print of the same coefficients (6 digits, row
    = radiating DOF), are the added mass and damping read (to 1e-5 of each matrix)."""
    ds, damage = oc3
    assert not damage
    assert ds.sizes["omega"] == 128 and list(ds.influenced_dof.values) == list(cummins.DOF_NAMES)
    assert "asks for 26 frequencies" in ds.attrs["history"]
    assert "QTF" in ds.attrs["history"]
    results = corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar" / "results"
    for name, variable in (("CM.dat", "added_mass"), ("CA.dat", "radiation_damping")):
        omega, blocks = _nemoh_dat(results / name)
        np.testing.assert_allclose(omega, ds.omega.values, atol=5e-5)
        values = ds[variable].values
        for k in range(omega.size):
            scale = np.abs(blocks[k]).max()
            np.testing.assert_allclose(values[k], blocks[k].T, rtol=1e-5, atol=1e-5 * scale)


def test_oc3_spar_mechanics_give_the_inertia(oc3, corpus):
    """Mechanics/Inertia.dat is the inertia matrix (about the rotation point (0, 0, −78)
    of Nemoh.cal); its mass is NEMOH's rho V of Hydrostatics.dat (1025 × 32081.97 =
    3.2884e7 kg), which history says; zero Km.dat/Badd.dat add nothing."""
    ds, _ = oc3
    folder = corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar"
    expected = np.loadtxt(folder / "Mechanics" / "Inertia.dat")
    np.testing.assert_array_equal(ds.inertia_matrix.values, expected)
    np.testing.assert_allclose(ds.inertia_matrix.values[2, 2], 1025.0 * 32081.97, rtol=1e-5)
    np.testing.assert_allclose(ds.attrs["reference_point"], [0, 0, -78.0])
    assert "NEMOH's own estimate" in ds.attrs["history"]
    assert "additional_stiffness" not in ds and "additional_damping" not in ds
    np.testing.assert_array_equal(
        ds.hydrostatic_stiffness.values, np.loadtxt(folder / "Mesh" / "KH.dat")
    )


def test_mechanics_km_and_badd_become_external_terms(corpus, tmp_path):
    folder = tmp_path / "oc3"
    shutil.copytree(corpus / "WEC-Sim" / "nemoh_v3.0.2_OC3_Hywind_spar", folder)
    km = np.zeros((6, 6))
    km[0, 0] = km[1, 1] = 4.1e4  # a mooring's surge/sway stiffness
    badd = np.zeros((6, 6))
    badd[2, 2] = 1.0e5
    for name, matrix in (("Km.dat", km), ("Badd.dat", badd)):
        (folder / "Mechanics" / name).chmod(0o644)
        np.savetxt(folder / "Mechanics" / name, matrix, fmt="%15.7E")
    ds, _ = _read_warned(folder)
    np.testing.assert_array_equal(ds.additional_stiffness.values, km)
    assert ds.additional_damping.shape == (128, 6, 6)
    np.testing.assert_array_equal(ds.additional_damping.values[57], badd)


def test_two_bodies_are_positional_with_mesh_names(corpus):
    ds, _ = _read_warned(corpus / "WEC-Sim" / "nemoh_v2.3_OSWEC_flap")
    assert list(ds.influenced_dof.values) == cummins.hydrodb.dof_labels(2)
    assert cummins.hydrodb.body_names(ds) == ["flap", "base"]
    renamed = cummins.hydrodb.rename_bodies(ds)
    assert str(renamed.influenced_dof.values[6]) == "base__Surge"
    # KH_0.dat / KH_1.dat on the diagonal blocks, as NEMOH wrote them
    c = ds.hydrostatic_stiffness.values
    assert c[2, 2] == pytest.approx(0.3178439e6) and c[10, 10] == pytest.approx(0.3582881e6)
    assert c[2, 8] == 0.0


@pytest.mark.parametrize(
    ("case", "ratio"),
    [("WEC-Sim/nemoh_v3.0.2_Cubes_2body", "2"), ("bemio/nemoh_two_body", "0.803")],
)
def test_hydrostatics_of_another_mesh_are_refused_with_a_warning(corpus, case, ratio):
    """The Cubes' KH_0/KH_1.dat (and KH.dat, all three equal) hold C33 = 1.962e6 N/m:
    rho g A_wp of both cubes together (200 m²), while each cube's own Froude-Krylov heave
    force tends to 9.806e5 N/m as w -> 0; bemio's KH_0.dat gives 7.84e5 against 9.76e5.
    The files are not of these meshes: no hydrostatic_stiffness, a warning naming it."""
    ds, damage = _read_warned(corpus / case)
    assert "hydrostatic_stiffness" not in ds and "center_of_buoyancy" not in ds.attrs
    assert len(damage) == 1 and f"(ratio {ratio})" in damage[0]
    assert damage[0] in ds.attrs["read_warnings"]


def test_cubes_history_says_the_single_mesh_files_are_not_used(corpus):
    """The Cubes' Mesh/Inertia_hull.dat and the 'Mass = 0.1000006E+07' line of its
    Hydrostatics_0/1.dat (rho x 1000 m^3, both cubes) are the NEMOH mesher's output for
    the two cubes meshed as one (GC_hull.dat: centre at x = 50 m, between the cubes'
    reference points x = 0 and 100 m of Nemoh.cal): one history line says they are not
    used, and nothing is taken from them."""
    folder = corpus / "WEC-Sim/nemoh_v3.0.2_Cubes_2body"
    assert "Mass = 0.1000006E+07" in (folder / "Mesh/Hydrostatics_0.dat").read_text()
    ds, _ = _read_warned(folder)
    lines = [
        line
        for line in ds.attrs["history"].splitlines()
        if "Inertia_hull.dat" in line or "Mass line" in line
    ]
    assert len(lines) == 1
    assert re.fullmatch(
        r"Mesh/Inertia_hull\.dat and the Mass line of Hydrostatics_0\.dat, "
        r"Hydrostatics_1\.dat not used: NEMOH's mesher writes them for one mesh, not per "
        r"body \(here the 2 bodies meshed together: Mesh/GC_hull\.dat puts its centre at "
        r"x = 50\.00 m, y = 0\.00 m, between the bodies' reference points\)",
        lines[0],
    )
    assert "inertia_matrix" not in ds and "mass" not in ds
    # a one-body run uses its Mass line: no such history line there
    spar, _ = _read_warned(corpus / "WEC-Sim/nemoh_v3.0.2_OC3_Hywind_spar")
    assert "Mass line" not in spar.attrs["history"]


def test_froude_krylov_limit_confirms_matching_hydrostatics(cylinder):
    """The cylinder's KH.dat C33 and its own Froude-Krylov heave force at 0.04 rad/s
    agree (3764.56 vs 3764.21 N/m, 0.01 %), so the stiffness is kept and history says it was
    checked."""
    assert "agrees with the run's own Froude-Krylov heave force" in cylinder.attrs["history"]
    c33 = float(cylinder.hydrostatic_stiffness.sel(influenced_dof="Heave", radiating_dof="Heave"))
    f3 = abs(
        complex(
            cylinder.Froude_Krylov_force.isel(omega=0, wave_direction=0).sel(influenced_dof="Heave")
        )
    )
    assert abs(c33 / f3 - 1) < nemoh.HYDROSTATIC_TOLERANCE


def test_run_without_mass_properties_says_what_is_missing(corpus):
    ds, _ = _read_warned(corpus / "WEC-Sim" / "nemoh_v3.0.2_COER_comp")
    assert "inertia_matrix" not in ds
    assert re.search(
        r"no inertia_matrix: .* rho\*V = 26\.8178 kg\); rho\*V is the mass only",
        ds.attrs["history"],
    )


def test_damaged_sibling_matrix_warns_and_names_what_is_lost(cylinder, nemoh_copy):
    kh = nemoh_copy / "KH.dat"
    lines = kh.read_text().splitlines()
    lines[2], lines[3] = lines[3], lines[2]  # rows swapped: no longer symmetric
    kh.write_text("\n".join(lines) + "\n")
    with pytest.warns(cummins.HydroDataWarning, match=r"not symmetric.*hydrostatic_stiffness"):
        ds = nemoh.read_nemoh(nemoh_copy)
    assert "hydrostatic_stiffness" not in ds
    xr.testing.assert_equal(ds.added_mass, cylinder.added_mass)


def test_sentinel_values_in_a_sibling_are_refused(nemoh_copy):
    kh = nemoh_copy / "KH.dat"
    kh.write_text(kh.read_text().replace("0.0000000E+00", "-9.99E+99", 1))
    with pytest.warns(cummins.HydroDataWarning, match="implausible value"):
        ds = nemoh.read_nemoh(nemoh_copy)
    assert "hydrostatic_stiffness" not in ds
