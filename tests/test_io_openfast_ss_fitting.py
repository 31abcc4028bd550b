"""OpenFAST SS_Fitting reference models: every header generation in the corpus."""

from __future__ import annotations

import numpy as np
import pytest

import cummins
from cummins import HydroDataError
from cummins.io.openfast import read_openfast_ss, read_openfast_ssexctn

SPAR = "WEIS/ss_fitting_OC3_spar"
BARGE = "ROSCO/wamit_ITI_barge_5MW_Baseline"
SEMI = "WEIS/ss_fitting_OC4_semi"

#: per diagonal Surge … Yaw: max |K_ss(jw) - K_data(jw)| / max |K_data| measured over
#: w <= w_max (beyond it the data have irregular frequencies SS_Fitting did not fit);
#: tolerance 1.5 x measured. None: SS_Fitting gave that DOF no states.
AGREEMENT = {
    "spar": (SPAR, "spar", 2.0, [0.061, 0.061, 0.054, 0.121, 0.120, None]),
    "barge": (BARGE, "Barge", 1.5, [0.041, 0.041, 0.177, 0.140, 0.140, 0.051]),
}


@pytest.mark.parametrize("case", sorted(AGREEMENT))
def test_ss_fitting_radiation_model_against_the_data(corpus, case):
    """K(jw) of SS_Fitting's .ss against the data's B + jw(A - A_inf) it was fitted to.

    Header generations: v1.00.01 (2021, spar) and v1.00.00aTD (2013, barge)."""
    folder, stem, w_max, measured = AGREEMENT[case]
    ss = read_openfast_ss(corpus / folder / f"{stem}.ss")
    ds = cummins.read(corpus / folder / f"{stem}.1")
    sel = ds.omega.values <= w_max
    w = ds.omega.values[sel]
    model = ss.to_radiation_model(added_mass_inf=ds.added_mass_inf.values)
    k = model.response(w)
    a = ds.added_mass.values[sel]
    data = ds.radiation_damping.values[sel] + 1j * w[:, None, None] * (a - ds.added_mass_inf.values)
    for i, expected in enumerate(measured):
        error = np.abs(k[:, i, i] - data[:, i, i]).max() / np.abs(data[:, i, i]).max()
        if expected is None:
            assert ss.states_per_dof[i] == 0 and np.all(k[:, i, i] == 0)
        else:
            assert error <= 1.5 * expected, (i, error)


def test_header_generations_and_counts(corpus):
    spar = read_openfast_ss(corpus / SPAR / "spar.ss")
    assert spar.title.startswith("SS_Fitting v1.00.01") and spar.n_states == 30
    assert spar.states_per_dof.tolist() == [6, 6, 4, 7, 7, 0]
    barge = read_openfast_ss(corpus / BARGE / "Barge.ss")
    assert barge.title.startswith("SS_Fitting v1.00.00aTD") and barge.n_states == 30
    assert all(np.linalg.eigvals(m.A).real.max() < 0 for m in (spar, barge))


def test_an_excitation_fit_in_a_ss_file_is_named(corpus):
    with pytest.raises(HydroDataError, match="excitation"):
        read_openfast_ss(corpus / SEMI / "marin_semi.ss")
    fit = read_openfast_ssexctn(corpus / SEMI / "marin_semi.ss")
    assert fit.time_offset == 10.0 and fit.heading == 0.0 and fit.n_states == 30


def test_both_ssexctn_layouts(corpus):
    semi = read_openfast_ssexctn(corpus / SEMI / "marin_semi.ssexctn")  # "%time offset (tc)"
    assert semi.time_offset == 10.0 and semi.dof_flags is None
    assert semi.states_per_dof.tolist() == [4, 2, 4, 4, 4, 2]
    spar = read_openfast_ssexctn(corpus / SPAR / "spar.ssexctn")  # "%Enabled DoFs"
    assert spar.time_offset is None and spar.dof_flags.tolist() == [1] * 6
    assert spar.states_per_dof.tolist() == [19, 0, 19, 0, 19, 0] and spar.B.shape == (57,)
    with pytest.raises(HydroDataError, match="time offset"):
        spar.frequency_response([0.5])
    # the time offset enters as e^{jw tc}: a phase, not a magnitude
    w = np.linspace(0.1, 2.0, 20)
    h0, h5 = semi.frequency_response(w, time_offset=0.0), semi.frequency_response(w)
    np.testing.assert_allclose(np.abs(h0), np.abs(h5), rtol=1e-12)
    np.testing.assert_allclose(
        h5 / np.where(h0 == 0, 1, h0),
        np.exp(1j * w * 10.0)[:, None] * (h0 != 0) + (h0 == 0),
        rtol=1e-9,
    )


def test_damaged_ssexctn_is_refused(corpus, tmp_path):
    """Each damage is refused with the file and the line at fault."""
    lines = (corpus / SEMI / "marin_semi.ssexctn").read_text().splitlines()
    damages = [
        (50, lines[:-1]),  # the last row of C lost: 50 lines of the 51 the header implies
        (50, lines[:5] + lines[6:]),  # a row of A lost
        (2, [lines[0], "x", *lines[2:]]),  # the heading
    ]
    for k, (line, damaged) in enumerate(damages):
        path = tmp_path / f"d{k}.ssexctn"
        path.write_text("\n".join(damaged) + "\n")
        with pytest.raises(HydroDataError, match=r"line \d+") as info:
            read_openfast_ssexctn(path)
        assert str(path) in str(info.value)
        assert info.value.line == line
