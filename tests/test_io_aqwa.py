"""AQWA reader: the WEC-Sim cylinder's .LIS listing and .AH1 database (AQWA 2020 R1).

The two files are independent printouts of one run: they must agree to their printed
precision. Long-wave physics checks the RAO conventions (phase lag → exp(+iωt), degrees
→ radians) without any other solver.
"""

from __future__ import annotations

import shutil
import warnings

import numpy as np
import pytest

import cummins
from cummins import HydroDataError
from cummins.io import aqwa


@pytest.fixture(scope="module")
def aqwa_dir(shared_data):
    return shared_data / "wecsim" / "cylinder_aqwa"


@pytest.fixture(scope="module")
def lis(aqwa_dir):
    return aqwa.read_aqwa(aqwa_dir / "cylinder.LIS")


@pytest.fixture(scope="module")
def ah1(aqwa_dir):
    return aqwa.read_aqwa(aqwa_dir / "cylinder.AH1")


# --------------------------------------------------------------------------- detection


def test_sniff(aqwa_dir, shared_data):
    assert aqwa.sniff(aqwa_dir / "cylinder.LIS")
    assert aqwa.sniff(aqwa_dir / "cylinder.AH1")
    nemoh_dir = shared_data / "wecsim" / "cylinder" / "cylinder_nemoh"
    for other in (
        "RadiationCoefficients.tec",
        "cyl.1",
        "cyl.3",
        "cyl.out",
        "KH.dat",
        "cylinder_hydrodynamics.nc",
    ):
        assert not aqwa.sniff(nemoh_dir / other), other


def test_sniff_dir_prefers_the_listing(aqwa_dir, tmp_path):
    assert aqwa.sniff_dir(aqwa_dir) == [aqwa_dir / "cylinder.LIS"]
    shutil.copy(aqwa_dir / "cylinder.AH1", tmp_path / "other.AH1")
    assert aqwa.sniff_dir(tmp_path) == [tmp_path / "other.AH1"]
    ds = cummins.read(aqwa_dir)  # one run: the registry reads the listing
    assert ds.attrs["source_file"].endswith("cylinder.LIS")


# --------------------------------------------------------------------------- values


def test_listing_values_from_the_file(lis):
    assert lis.attrs["rho"] == 1025.0
    assert lis.attrs["g"] == 9.807
    assert lis.attrs["water_depth"] == 3.0
    assert lis.omega.size == 50
    assert float(lis.omega[0]) == 0.04
    assert float(lis.omega[-1]) == 10.49998
    np.testing.assert_allclose(np.degrees(lis.wave_direction), [-180.0, 0.0, 180.0])
    a = lis.added_mass.isel(omega=0)
    # "ADDED MASS" at WAVE FREQUENCY = 0.0400: row Z col Z 1.2389E+02; row RY col X -5.0223E+01
    assert float(a.sel(influenced_dof="Heave", radiating_dof="Heave")) == 123.89
    assert float(a.sel(influenced_dof="Pitch", radiating_dof="Surge")) == -50.223
    assert float(a.sel(influenced_dof="Surge", radiating_dof="Pitch")) == -50.248
    c = lis.hydrostatic_stiffness
    assert float(c.sel(influenced_dof="Heave", radiating_dof="Heave")) == 3856.9
    np.testing.assert_allclose(lis.attrs["reference_point"], [0.0, 0.0, 0.0])
    np.testing.assert_allclose(lis.attrs["center_of_buoyancy"], [0.0, 0.0, -0.315])
    assert lis.attrs["displaced_volume"] == 0.241731
    # mass = ρ V of the listing (2.4777E+02 kg vs 1025 × 0.241731)
    assert float(lis.inertia_matrix[0, 0]) == pytest.approx(1025 * 0.241731, rel=1e-4)


def test_listing_and_database_agree(lis, ah1):
    """.LIS and .AH1 of one run: A, B, C, A∞ to all digits; excitation to the listing's 3."""
    np.testing.assert_allclose(ah1.omega, lis.omega, rtol=2e-5)
    for name in ("added_mass", "radiation_damping", "added_mass_inf", "hydrostatic_stiffness"):
        np.testing.assert_array_equal(ah1[name].values, lis[name].values, err_msg=name)
    # the listing prints the inertia with 4 digits (2.478E+02), the AH1 with 5
    np.testing.assert_allclose(lis.inertia_matrix, ah1.inertia_matrix, rtol=2.5e-4, atol=1e-9)
    x, y = lis.excitation_force.values, ah1.excitation_force.values
    scale = np.abs(y).max(axis=(0, 1), keepdims=True)
    # 3 significant digits: |ΔX| ≤ 0.5e-2 |X|; phases to 0.01 deg in both
    assert np.all(np.abs(x - y) <= 5e-3 * np.abs(y) + 1e-6 * scale)
    assert ah1.attrs["rho"] == lis.attrs["rho"]
    assert ah1.attrs["water_depth"] == lis.attrs["water_depth"]


def test_excitation_is_froude_krylov_plus_diffraction(lis):
    total = lis.Froude_Krylov_force + lis.diffraction_force
    scale = np.abs(lis.excitation_force).max(dim="omega")
    # three tables, each to 3 significant digits
    assert float((np.abs(lis.excitation_force - total) / scale).max()) < 1e-2


def test_long_wave_raos_prove_the_conventions(lis):
    """At ω = 0.04 rad/s (kh = 0.022) the cylinder follows the water surface.

    For waves travelling along +x (β = 0), η = exp(i(ωt − kx)): the surface moves
    horizontally by −i/tanh(kh), heaves by 1 and tilts by +ik (pitch, rad/m). AQWA
    prints lags (surge +89.96°, pitch −90.74°) and pitch in deg/m (0.4228): cummins must
    give surge phase −90°, pitch +90° and pitch k = 0.00738 rad/m.
    """
    k = aqwa.wavenumber(np.array([0.04]), 3.0, 9.807)[0]
    rao = lis.rao.isel(omega=0).sel(wave_direction=0.0)
    surge = complex(rao.sel(radiating_dof="Surge"))
    heave = complex(rao.sel(radiating_dof="Heave"))
    pitch = complex(rao.sel(radiating_dof="Pitch"))
    assert surge == pytest.approx(-1j / np.tanh(k * 3.0), rel=2e-3)
    assert heave == pytest.approx(1.0, abs=2e-3)
    # long-wave limit plus AQWA's 4 printed digits: within 1 % and 1°
    assert abs(pitch) == pytest.approx(k, rel=1e-2)
    assert np.degrees(np.angle(pitch)) == pytest.approx(90.0, abs=1.0)
    head = lis.rao.isel(omega=0).sel(wave_direction=np.pi)
    assert complex(head.sel(radiating_dof="Surge")) == pytest.approx(np.conj(surge), rel=1e-3)


def test_high_frequency_row_is_added_mass_inf_low_frequency_row_is_not(lis, ah1):
    for ds in (lis, ah1):
        assert "added_mass_inf" in ds
        assert "added_mass_zero" not in ds
        assert "at 100 rad/s" in ds.attrs["history"]
        assert "not used as A(0)" in ds.attrs["history"]
    # ADDEDMASS_HF, row Z col Z: 8.5189E+01
    assert float(lis.added_mass_inf.sel(influenced_dof="Heave", radiating_dof="Heave")) == 85.189


def test_rho_must_match(aqwa_dir):
    ds = aqwa.read_aqwa(aqwa_dir / "cylinder.AH1", rho=1025.0, g=9.807)
    assert ds.attrs["g"] == 9.807
    with pytest.raises(HydroDataError, match="rho = 1000"):
        aqwa.read_aqwa(aqwa_dir / "cylinder.LIS", rho=1000.0)


def test_phase_is_referred_from_the_cg_to_the_origin(aqwa_dir, ah1, tmp_path):
    """With the CG moved to x = 2 m, phases shift by k x_G cos β (WEC-Sim's convention).

    The AH1 is edited so that only COG changes: then X(origin) = X(CG) exp(−i k x_G cos β).
    """
    text = (aqwa_dir / "cylinder.AH1").read_text().splitlines()
    i = text.index("COG")
    text[i + 1] = "  1               2.000       0.000       0.000"
    path = tmp_path / "moved.AH1"
    path.write_text("\n".join(text) + "\n")
    moved = aqwa.read_aqwa(path)
    k = aqwa.wavenumber(ah1.omega.values, 3.0, 9.807)[:, None, None]
    beta = ah1.wave_direction.values[None, :, None]
    expected = ah1.excitation_force.values * np.exp(-1j * k * 2.0 * np.cos(beta))
    np.testing.assert_allclose(moved.excitation_force.values, expected, rtol=1e-12)
    np.testing.assert_allclose(moved.attrs["reference_point"], [2.0, 0.0, 0.0])


def test_wavenumber_dispersion():
    w = np.array([0.04, 1.0, 5.0, 20.0])
    k = aqwa.wavenumber(w, 3.0, 9.807)
    np.testing.assert_allclose(9.807 * k * np.tanh(3.0 * k), w**2, rtol=1e-12)
    np.testing.assert_allclose(aqwa.wavenumber(w, np.inf, 9.81), w**2 / 9.81)
    # the listing's wave-number column (0.00738, 0.04688, …, 11.24232)
    assert k[0] == pytest.approx(0.00738, abs=5e-6)


# --------------------------------------------------------------------------- damaged files


@pytest.fixture
def aqwa_copy(aqwa_dir, tmp_path):
    for name in ("cylinder.LIS", "cylinder.AH1"):
        shutil.copy(aqwa_dir / name, tmp_path / name)
    return tmp_path


def test_truncated_listing(aqwa_copy):
    path = aqwa_copy / "cylinder.LIS"
    lines = path.read_text().splitlines()
    path.write_text("\n".join(lines[:6000]) + "\n")
    with pytest.raises(HydroDataError, match=r"cylinder.LIS, line \d+: .*(truncated|incomplete)"):
        aqwa.read_aqwa(path)


def test_truncated_database(aqwa_copy):
    path = aqwa_copy / "cylinder.AH1"
    lines = path.read_text().splitlines()
    path.write_text("\n".join(lines[:500]) + "\n")
    with pytest.raises(HydroDataError, match=r"cylinder.AH1, line \d+: .*truncated"):
        aqwa.read_aqwa(path)


def test_garbled_matrix_entry_names_the_line(aqwa_copy):
    path = aqwa_copy / "cylinder.LIS"
    lines = path.read_text().splitlines()
    i = next(k for k, line in enumerate(lines) if line.strip().startswith("Z ") and "E+0" in line)
    lines[i] = lines[i].replace("E+0", "Q+0", 1)
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=rf"line {i + 1}: expected 6 numbers"):
        aqwa.read_aqwa(path)


def test_nan_in_database(aqwa_copy):
    path = aqwa_copy / "cylinder.AH1"
    lines = path.read_text().splitlines()
    tokens = lines[45].split()  # a row of the first ADDEDMASS record
    tokens[2] = "NaN"
    lines[45] = "  ".join(tokens)
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match=r"line 46: non-finite"):
        aqwa.read_aqwa(path)


def test_foreign_and_empty_files(aqwa_copy, shared_data):
    (aqwa_copy / "empty.LIS").write_text("")
    with pytest.raises(HydroDataError):
        aqwa.read_aqwa(aqwa_copy / "empty.LIS")
    with pytest.raises(HydroDataError, match="not an AQWA"):
        aqwa.read_aqwa(shared_data / "wecsim" / "cylinder" / "cylinder_nemoh" / "KH.dat")


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
            tokens[k] = str(rng.choice(["1.2.3", "nan", "-", "*****", "1E+", "0", "-1", "X"]))
            lines[i] = " ".join(tokens)
    elif kind == 2:
        return text[: int(rng.integers(len(text)))]
    elif kind == 3:
        lines.insert(i, lines[int(rng.integers(len(lines)))])
    else:
        j = int(rng.integers(len(lines)))
        lines[i], lines[j] = lines[j], lines[i]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize(("name", "count"), [("cylinder.AH1", 40), ("cylinder.LIS", 12)])
def test_fuzz_only_hydro_data_errors(aqwa_copy, name, count):
    """Mutated real files give a valid dataset or a HydroDataError, nothing else."""
    path = aqwa_copy / name
    original = path.read_text()
    rng = np.random.default_rng(len(name) + count)
    for _ in range(count):
        path.write_text(_mutate(original, rng))
        error = None
        try:
            ds = aqwa.read_aqwa(path)
        except HydroDataError as exc:
            error = exc
        if error is None:
            cummins.validate(ds)
        else:
            assert error.path is not None, str(error)


# --------------------------------------------------------------------------- corpus variants


def _read_warned(path, **options):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = cummins.read(path, **options)
    return ds, [str(w.message) for w in caught if issubclass(w.category, cummins.HydroDataWarning)]


@pytest.fixture(scope="module")
def pend(corpus):
    folder = corpus / "WEC-Sim" / "aqwa_19.1_PEND_hull"
    return _read_warned(folder / "19_1.LIS"), _read_warned(folder / "19_1.AH1")


def test_pend_listing_of_aqwa_19_1_reads_and_agrees_with_its_database(pend):
    """AQWA 19.1 prints its frequency table over two pages; the listing and the .AH1
    (file version 4) are the same run: A and B to the 5 printed digits (rtol 1e-4),
    the mass matrix (24.259 kg, inertia 0.46, 0.46, 0.71 kg m² about the CG) and the
    stiffness exactly, the excitation to the listing's 3 digits (measured 0.40 % of the
    largest amplitude per DOF; 1 % allowed)."""
    (lis, lis_damage), (ah1, ah1_damage) = pend
    assert not lis_damage and not ah1_damage
    assert lis.sizes["omega"] == ah1.sizes["omega"] == 100
    for name in ("added_mass", "radiation_damping", "added_mass_inf"):
        a, b = lis[name].values, ah1[name].values
        scale = np.abs(b).max(axis=(-2, -1), keepdims=True)
        assert np.all(np.abs(a - b) <= 1e-4 * np.abs(b) + 1e-4 * scale), name
    np.testing.assert_array_equal(lis.inertia_matrix.values, ah1.inertia_matrix.values)
    np.testing.assert_allclose(
        np.diag(lis.inertia_matrix.values), [24.259] * 3 + [0.46, 0.46, 0.71]
    )
    np.testing.assert_allclose(
        lis.hydrostatic_stiffness.values, ah1.hydrostatic_stiffness.values, rtol=1e-4, atol=1e-9
    )
    f_lis, f_ah1 = lis.excitation_force.values, ah1.excitation_force.values
    scale = np.abs(f_ah1).max(axis=(0, 1))
    assert (np.abs(f_lis - f_ah1).max(axis=(0, 1)) / scale).max() < 0.01
    assert "inertia matrix from MASS AND INERTIA PROPERTIES" in lis.attrs["history"]
    assert "file version 4" in ah1.attrs["history"]


def test_database_alone_with_two_structures(corpus):
    """The floating OWC (AQWA 2022 R1, .AH1 file version 5 with one header block per
    structure, no .LIS): 12 positional DOFs, the MASS section per body (2.5378e6 and
    4.6058e6 kg) and history saying what only the listing would give."""
    ds, damage = _read_warned(corpus / "WEC-Sim_Applications" / "aqwa_floating_OWC_AH1only")
    assert not damage
    assert list(ds.influenced_dof.values) == cummins.hydrodb.dof_labels(2)
    assert ds.sizes["omega"] == 100 and ds.sizes["wave_direction"] == 3
    m = ds.inertia_matrix.values
    assert m[0, 0] == pytest.approx(2.5378e6) and m[6, 6] == pytest.approx(4.6058e6)
    assert m[0, 6] == 0.0
    np.testing.assert_allclose(ds.attrs["displaced_volume"], [2475.9, 4493.4])
    assert "no floatingOWC.LIS beside the database" in ds.attrs["history"]
    assert "excitation_force" in ds and "rao" not in ds


def test_truncated_listing_warns_and_names_what_is_lost(aqwa_copy):
    """A listing cut after its hydrodynamic blocks used to lose excitation, RAOs and
    A(inf) silently: now the missing FINISH line and the LHFR block that OPTIONS
    announces are named."""
    path = aqwa_copy / "cylinder.LIS"
    lines = path.read_text().splitlines()
    cut = next(i for i, line in enumerate(lines) if "VARIATION WITH WAVE PERIOD" in line)
    path.write_text("\n".join(lines[:cut]) + "\n")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = aqwa.read_aqwa(path)
    text = " ".join(str(w.message) for w in caught)
    assert "FINISH" in text and "the excitation force" in text and "the RAOs" in text
    assert "excitation_force" not in ds
    assert ds.attrs["read_warnings"]


def test_swapped_database_rows_are_refused(aqwa_copy):
    """Two rows of an ADDEDMASS record swapped make the matrix far from symmetric."""
    path = aqwa_copy / "cylinder.AH1"
    lines = path.read_text().splitlines()
    start = lines.index("ADDEDMASS") + 1
    lines[start + 1], lines[start + 4] = lines[start + 4], lines[start + 1]
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(HydroDataError, match="not symmetric"):
        aqwa.read_aqwa(path)
