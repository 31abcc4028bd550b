"""Slow drift in the frequency domain: the normalisation of the mean and of S_F(μ) against
a closed form, Newman against the full QTF, the grid advice.

With Q⁻ ≡ q on every pair the second-order force is q |A(t)|², A = Σ_i c_i e^{iω_i t} the
complex envelope of a Gaussian sea: |A|² is exponentially distributed with mean 2 m₀
(E|A|² = Σ a_i²), so the mean force is 2 q m₀ and the slowly varying part has variance
(2 q m₀)² — the closed form the factor 8 of S_F(μ) = 8 ∫ S(ω) S(ω+μ) |Q|² dω must give
(Pinkster (1980)).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate

import cummins
from cummins.qtf import QTFTable, qtf_table
from cummins.seakeeping import slow_drift as sd
from cummins.seakeeping.spectra import wave_spectrum

OC4 = "corpus/WEIS/ss_fitting_OC4_semi/marin_semi.1"


def _constant(q: float, lo=0.05, hi=4.0, n=80) -> QTFTable:
    w = np.linspace(lo, hi, n)
    values = np.full((n, n, 1, 1), q, dtype=complex)
    return QTFTable("difference", w, np.zeros(1), values, ("Surge",))


def test_mean_and_variance_of_a_constant_qtf_are_the_envelope_s():
    shape = wave_spectrum("jonswap", 4.0, 9.0)
    m0 = integrate.quad(shape, 0.05, 4.0, limit=200)[0]
    q = 1000.0
    table = _constant(q)
    mean = float(sd.mean_drift(table, shape, n_omega=8000)[0])
    assert mean == pytest.approx(2 * q * m0, rel=2e-3)
    mu = np.linspace(1e-4, 3.9, 3000)
    spectra = sd.slow_drift_spectrum(table, shape, mu, n_omega=4000)
    std = float(sd.standard_deviation(spectra)[0])
    assert std == pytest.approx(2 * q * m0, rel=5e-3)


def test_newman_equals_the_full_qtf_when_the_qtf_is_newman_s():
    w = np.linspace(0.2, 2.5, 40)
    t = 1e4 * (w / 2.5) ** 2  # a mean drift growing with frequency
    values = (0.5 * (t[:, None] + t[None, :]))[:, :, None, None].astype(complex)
    table = QTFTable("difference", w, np.zeros(1), values, ("Surge",))
    c = sd.newman_vs_full(table, wave_spectrum("jonswap", 5.0, 10.0))
    assert float(c.force_std_newman[0]) == pytest.approx(float(c.force_std_full[0]), rel=1e-9)


def test_oc4_newman_against_the_full_qtf(shared_data):
    """Measured (JONSWAP Hs 6 m, Tp 10 s, μ ≤ 0.5 rad/s): the slowly varying surge force of
    Newman's approximation is 26 % below the full QTF's (9.26e4 against 1.24e5 N), but
    the moored surge (natural period 100 s, 20 % of critical damping) within 2 % (0.745
    against 0.761 m): Newman is enough for the resonant slow drift, not for the force's
    higher difference frequencies; in pitch it misses 84 % of the force."""
    ds = cummins.read(shared_data / OC4)
    c = sd.newman_vs_full(qtf_table(ds), wave_spectrum("jonswap", 6.0, 10.0))
    ratio = (c.force_std_newman / c.force_std_full).sel(influenced_dof=["Surge", "Pitch"])
    assert 0.6 < float(ratio[0]) < 0.9 and float(ratio[1]) < 0.3
    assert float(c.mean_force.sel(influenced_dof="Surge")) == pytest.approx(8.90e4, rel=0.01)
