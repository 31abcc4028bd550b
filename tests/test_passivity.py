"""Passivity of MIMO radiation models: the exact test and its enforcement (issue 5).

References: a scalar root finder on the closed-form λ_min of a 2×2 system (crossing
frequencies), dense frequency sweeps (the test must agree with them), the real vessels.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

import cummins
from cummins.errors import FitError
from cummins.radiation.fit import fit_radiation
from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.radiation.passivity import (
    PASSIVITY_TOLERANCE,
    augment_for_passivity,
    enforce_passivity,
    imaginary_axis_zeros,
    passivity_sweep,
    passivity_test,
)
from cummins.repair import find_suspect_frequencies


def _mode(i: int, j: int, residue: float, zeta: float, w0: float) -> CouplingModel:
    """K_ij(s) = r s / (s² + 2ζω₀ s + ω₀²) in controllable form: passive for r > 0."""
    a = np.array([[0.0, 1.0], [-(w0**2), -2 * zeta * w0]])
    return CouplingModel(i, j, a, np.array([0.0, 1.0]), np.array([0.0, residue]))


def _two_dof(coupling: float) -> RadiationModel:
    """Diagonals s/(s² + s + 1); coupling c·s/(s² + 0.4 s + 1.44), symmetric."""
    k11, k22 = _mode(0, 0, 1.0, 0.5, 1.0), _mode(1, 1, 1.0, 0.5, 1.0)
    k12 = _mode(0, 1, coupling, 1 / 6, 1.2)
    return RadiationModel(("Surge", "Sway"), (k11, k12, k12.transposed(), k22), np.eye(2))


def _lambda_min_2x2(model: RadiationModel, w: float) -> float:
    k = model.response(np.array([w]))[0].real
    return float(np.linalg.eigvalsh(k + k.T)[0])


def test_crossings_agree_with_a_root_finder_on_the_closed_form():
    """Re K11 = Re K22 = ω²/((1−ω²)² + ω²): λ_min = 2(Re K11 − |Re K12|) crosses zero where
    the coupling's real part outgrows the diagonal; the pencil must find every crossing."""
    model = _two_dof(0.5)
    grid = np.geomspace(1e-3, 1e3, 200_001)
    values = np.array([_lambda_min_2x2(model, w) for w in grid[::50]])
    signs = np.flatnonzero(np.diff(np.sign(values)))
    coarse = grid[::50]
    roots = [brentq(lambda w: _lambda_min_2x2(model, w), coarse[k], coarse[k + 1]) for k in signs]
    assert len(roots) >= 2  # the coupling's resonance makes a violation band
    found = imaginary_axis_zeros(model.A, model.B, model.C)
    np.testing.assert_allclose(found, roots, rtol=1e-7)
    report = passivity_test(model)
    assert not report.passive
    band = report.bands[0]
    assert band.omega_low == pytest.approx(roots[0], rel=1e-7)
    assert band.omega_high == pytest.approx(roots[1], rel=1e-7)
    assert roots[0] < band.worst_omega < roots[1]


def test_a_weak_coupling_is_passive():
    model = _two_dof(0.05)
    report = passivity_test(model)
    assert report.passive and not report.bands
    assert passivity_sweep(model).passive


@st.composite
def _random_models(draw):
    """Symmetric 3-DOF models: passive diagonals, couplings of random size."""
    n = 3
    couplings = []
    for i in range(n):
        couplings.append(
            _mode(
                i,
                i,
                draw(st.floats(0.5, 2.0)),
                draw(st.floats(0.2, 0.9)),
                draw(st.floats(0.3, 3.0)),
            )
        )
        for j in range(i + 1, n):
            if draw(st.booleans()):
                k = _mode(
                    i,
                    j,
                    draw(st.floats(-1.5, 1.5)),
                    draw(st.floats(0.1, 0.9)),
                    draw(st.floats(0.3, 3.0)),
                )
                couplings += [k, k.transposed()]
    couplings.sort(key=lambda k: (k.influenced, k.radiating))
    return RadiationModel(("Surge", "Heave", "Pitch"), tuple(couplings), np.eye(n))


@settings(max_examples=25, deadline=None, derandomize=True)
@given(_random_models())
def test_the_exact_test_agrees_with_a_very_dense_sweep(model):
    report = passivity_test(model)
    dense = passivity_sweep(model, np.geomspace(1e-4, 1e4, 40_001))
    assert report.passive == dense.passive or abs(dense.min_eigenvalue.min()) < 1e-4
    if not report.passive and report.bands:
        assert report.min_eigenvalue <= dense.min_eigenvalue.min() + 1e-9


@settings(max_examples=15, deadline=None, derandomize=True)
@given(_random_models())
def test_enforcement_returns_passive_models_and_keeps_poles_zero_and_symmetry(model):
    result = enforce_passivity(model)
    fixed = result.model
    assert result.after.passive and passivity_test(fixed).passive
    dense = passivity_sweep(fixed, np.geomspace(1e-4, 1e4, 20_001))
    assert dense.min_eigenvalue.min() >= -PASSIVITY_TOLERANCE
    for old, new in zip(model.couplings, fixed.couplings, strict=True):
        np.testing.assert_array_equal(old.a, new.a)  # poles kept
        k0 = -new.c @ np.linalg.solve(new.a, new.b)  # K(0) = 0 kept
        assert abs(k0) <= 1e-9 * np.abs(new.c).sum()
    w = np.geomspace(0.05, 20, 50)
    k = fixed.response(w)
    np.testing.assert_allclose(k, np.swapaxes(k, 1, 2), atol=1e-12)
    if model is not fixed:
        assert result.iterations >= 1


def test_enforcement_is_no_larger_than_the_naive_fix():
    """The naive fix of a 2-DOF model whose coupling is slightly too strong scales the
    coupling down until the model is passive (bisection on the exact test). The minimal
    change found by enforcement spreads over the three terms: none of them changes by
    more than the naive fix changes the coupling."""
    model = _two_dof(0.4)
    assert not passivity_test(model).passive

    def scaled(kappa):
        k12 = _mode(0, 1, 0.4 * kappa, 1 / 6, 1.2)
        c = model.couplings
        return RadiationModel(model.dofs, (c[0], k12, k12.transposed(), c[3]), np.eye(2))

    lo, hi = 0.0, 1.0  # passive at lo, not at hi
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if passivity_test(scaled(mid)).passive else (lo, mid)
    naive = 1.0 - lo
    result = enforce_passivity(model)
    assert result.after.passive
    assert 0 < max(result.relative_change.values()) <= naive


def test_unstable_models_are_refused():
    bad = _mode(0, 0, 1.0, 0.5, 1.0)
    bad = CouplingModel(0, 0, -bad.a, bad.b, bad.c)
    model = RadiationModel(("Heave",), (bad,), np.eye(1))
    with pytest.raises(FitError, match="stable"):
        enforce_passivity(model)


def test_augmentation_adds_poles_without_changing_the_response():
    model = _two_dof(0.6)
    report = passivity_test(model)
    augmented = augment_for_passivity(model, report)
    assert augmented.total_order > model.total_order
    w = np.geomspace(0.01, 100, 300)
    np.testing.assert_allclose(augmented.response(w), model.response(w), atol=1e-13)


# ----------------------------------------------------------------------------- real data


@pytest.mark.parametrize("vessel", ["tanker", "supply"])
def test_real_vessels_are_passive_after_enforcement_with_diagonal_r2_kept(shared_data, vessel):
    """Issue 5: the tanker and supply vessel 6×6 models of the per-coupling
    identification (``method="fd"``) are made passive as MIMO systems by the residue
    enforcement, every diagonal R² still ≥ 0.99; a dense sweep confirms. (The default
    common-pole identification is passive as fitted: test_identification_targets.py.)"""
    ds = cummins.read(shared_data / "mss" / vessel / f"{vessel}.mat")
    identified = fit_radiation(ds, method="fd", passivity="diagonal")
    assert not passivity_test(identified).passive  # the identification alone is not
    model = fit_radiation(ds, method="fd")
    assert model.attrs["mimo_passive"] is True
    assert passivity_test(model).passive
    sweep = passivity_sweep(model, np.geomspace(1e-3, 1e3, 60_001))
    assert sweep.min_eigenvalue.min() >= -PASSIVITY_TOLERANCE
    assert model.is_stable()
    for c in model.couplings:
        if c.influenced == c.radiating:
            assert min(c.metrics["r2_added_mass"], c.metrics["r2_damping"]) >= 0.99, c.note
            assert c.metrics["passive"]
    changed = [c for c in model.couplings if "MIMO passivity" in c.note]
    assert changed and all("→" in c.note for c in changed)


def _diagonal_r2(ds, model) -> dict[str, tuple[float, float]]:
    """R² (1 − Σ(y − ŷ)²/Σ(y − ȳ)², Unneland (2007) eq. 6.19) of A_ii and B_ii of each
    modelled diagonal, from the model's own K(jω) and A∞ (A = A∞ + Im K/ω, B = Re K) against
    the data, at the data's frequencies less those the suspect-frequency detector of
    cummins.repair flags (not the fit's own metrics nor its own list of exclusions)."""
    w = ds.omega.values.astype(float)
    suspect = [s.omega for s in find_suspect_frequencies(ds)]
    keep = ~np.isclose(w[:, None], np.reshape(suspect, (1, -1)), rtol=1e-12, atol=0.0).any(axis=1)
    w = w[keep]
    k = model.response(w)
    a = ds.added_mass.transpose("omega", "influenced_dof", "radiating_dof").values[keep]
    b = ds.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").values[keep]

    def r2(y, y_model):
        return 1.0 - np.sum((y - y_model) ** 2) / np.sum((y - y.mean()) ** 2)

    out = {}
    for c in model.modelled:
        i = c.influenced
        if i != c.radiating:
            continue
        a_model = model.added_mass_inf[i, i] + k[:, i, i].imag / w
        out[model.dofs[i]] = (
            float(r2(a[:, i, i], a_model)),
            float(r2(b[:, i, i], k[:, i, i].real)),
        )
    return out


def _scaled_lambda_min(model, w) -> float:
    """min_ω λ_min(S(K + Kᴴ)S) / max_ω λ_max(S(K + Kᴴ)S), S = diag(1/√max_ω|K_ii|): a dense
    sweep of the model's K(jω) written here. S is a congruence (passivity is unchanged),
    which keeps the translations from vanishing next to the rotations."""
    k = model.response(w)
    herm = k + np.conj(np.swapaxes(k, 1, 2))
    peak = np.abs(np.diagonal(k, axis1=1, axis2=2)).max(axis=0)
    s = np.where(peak > 0, 1.0 / np.sqrt(np.where(peak > 0, peak, 1.0)), 1.0)
    eig = np.linalg.eigvalsh(herm * s[None, :, None] * s[None, None, :])
    return float(eig[:, 0].min() / eig[:, -1].max())


@pytest.mark.parametrize(
    ("relative", "options"),
    [
        ("mss/s175/s175.mat", {}),
        ("wecsim/sphere/sphere.1", {"rho": 1000.0}),
        ("wecsim/cylinder/cylinder_nemoh/cyl.1", {"rho": 1000.0}),
        ("mss/supply/input.re7", {}),
    ],
)
def test_other_bodies_are_passive_after_enforcement(shared_data, relative, options):
    """Every body of the shared data ends passive and stable with the default (common-pole)
    identification, every DOF whose damping is not rounding noise modelled on the diagonal
    (``model.modelled``: the default fit has blocks, no ``couplings``), each diagonal R² of
    A and B ≥ 0.985 recomputed here from the model's response.

    Measured 2026-12-02 (the same under OPENBLAS_CORETYPE=Sandybridge, one thread):
    smallest diagonal R² S-175 0.9933 (heave A), sphere 0.9981 (heave A), cylinder 0.9904
    (pitch B: axisymmetric, surge–pitch and sway–roll damping are nearly singular at every
    frequency), supply (VERES) 0.9955 (pitch B); the bound 1 − 0.985 = 0.015 is 1.56× the
    worst 1 − R² (0.0096). Scaled λ_min of K + Kᴴ over 10⁻³–10³ rad/s (20 001 points),
    relative to the largest: S-175 7e-13, sphere −1.6e-9, cylinder 0, supply −4.5e-9,
    against the definition of passive, ≥ −PASSIVITY_TOLERANCE (10⁻⁶).

    The S-175's heave since issue 31: R² of A 0.981, its added mass at the last frequency
    not causal with a damping that decays beyond the data (``tests/test_fit.py``,
    ``test_real_vessels``): floor 0.97 there."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        ds = cummins.read(shared_data / relative, **options)
    if "forward_speed" in ds.dims:
        ds = ds.sel(forward_speed=0.0)
    model = fit_radiation(ds)
    assert model.is_stable()
    assert np.all(np.linalg.eigvals(model.A).real < 0)
    assert _scaled_lambda_min(model, np.geomspace(1e-3, 1e3, 20_001)) >= -PASSIVITY_TOLERANCE
    r2 = _diagonal_r2(ds, model)
    # nothing vanishes silently: a DOF without a diagonal model is reported as negligible
    # and its damping is rounding noise (yaw of the axisymmetric sphere and cylinder:
    # 2e-11 of the largest diagonal peak; VERES gives no surge damping: 0)
    peak = np.abs(np.diagonal(ds.radiation_damping.values, axis1=1, axis2=2)).max(axis=0)
    for dof, p in zip(ds.influenced_dof.values, peak, strict=True):
        if str(dof) not in r2:
            assert str(dof) in model.attrs["negligible_couplings"], dof
            assert p <= 1e-9 * peak.max(), (dof, p / peak.max())
    for dof, (r2_a, r2_b) in r2.items():
        floor = 0.97 if (relative, dof) == ("mss/s175/s175.mat", "Heave") else 0.985
        assert min(r2_a, r2_b) >= floor, (dof, r2_a, r2_b)
