"""Bad input behind the command line: the validation layer, the numerical guards of the
fit, passivity and reduction, ``check``'s physical errors and the low-frequency model's
damping at the natural frequency."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import cummins
from cummins import validation
from cummins.check import check
from cummins.errors import ArgumentError, CumminsWarning, FitError, HydroDataError
from cummins.seakeeping import waves

# --------------------------------------------------------------------------- validation


@pytest.mark.parametrize("value", [0.0, -5.0, float("nan"), float("inf"), "x", None])
def test_positive_refuses_with_name_unit_and_value(value):
    with pytest.raises(ArgumentError, match=r"^dt must be a .*> 0 s, not ") as info:
        validation.positive(value, "dt", "s")
    assert isinstance(info.value, ValueError)  # callers catching ValueError still do


def test_ranges_and_counts():
    assert validation.in_range(0.99, "r2", low=0, high=1, low_open=True, high_open=True) == 0.99
    with pytest.raises(ArgumentError, match=r"r2 must be a finite number > 0 and < 1, not 1\.5"):
        validation.in_range(1.5, "r2", low=0, high=1, low_open=True, high_open=True)
    assert validation.count(3.0, "n") == 3
    for bad in (0, 2.5, "two"):
        with pytest.raises(ArgumentError, match="n must be a whole number"):
            validation.count(bad, "n")


def test_the_memory_needed_is_said_before_allocating():
    """``--duration 1e12`` tried to allocate 146 TiB (the time vector alone); the refusal
    now comes first and says how much the whole run needs."""
    with pytest.raises(ArgumentError) as info:
        validation.check_simulation_size(1e12, 0.05, 12, 6, option="--duration")
    message = str(info.value)
    assert "2e+13 time steps" in message and "PiB" in message and "--dt" in message
    # 3 hours at 0.05 s with 100 states: 216 001 steps, about 0.8 GB, allowed
    assert validation.check_simulation_size(3 * 3600, 0.05, 100, 6) == 216_001


def test_memory_limit_from_the_environment(monkeypatch):
    monkeypatch.setenv("CUMMINS_MEMORY_LIMIT", "0.5")
    assert validation.memory_limit() == 2**29
    monkeypatch.setenv("CUMMINS_MEMORY_LIMIT", "nonsense")
    assert validation.memory_limit() == validation.MEMORY_LIMIT


def test_sea_states_raise_argument_error():
    """Every public function taking a sea state, a duration or a time step raises
    ArgumentError (a CumminsError), not a plain ValueError."""
    spectrum = waves.wave_spectrum("jonswap", 4.0, 10.0)
    calls = [
        lambda: waves.wave_spectrum("jonswap", -1.0, 10.0),
        lambda: waves.wave_spectrum("pm", 4.0, 0.0),
        lambda: waves.regular_wave(1.0, 0.0),
        lambda: waves.regular_wave(1.0, 10.0, direction=np.nan),
        lambda: waves.irregular_waves(spectrum, duration=-5.0),
        lambda: waves.irregular_waves(spectrum, duration=60.0, n_components=0),
        lambda: waves.irregular_waves(spectrum, duration=60.0, direction=np.nan),
        lambda: waves.irregular_waves(spectrum, duration=60.0, n_components=10**9),
    ]
    for call in calls:
        with pytest.raises(ArgumentError):
            call()


def test_a_drawn_seed_fits_an_int64_and_repeats_the_sea():
    """Issue 17: the drawn seed was the 128-bit entropy of a SeedSequence, which HDF5 cannot
    store; now it fits an int64 and makes the same components again."""
    spectrum = waves.wave_spectrum("jonswap", 4.0, 10.0)
    drawn = waves.irregular_waves(spectrum, duration=600.0, n_components=20)
    assert isinstance(drawn.seed, int) and 0 <= drawn.seed < 2**63
    again = waves.irregular_waves(spectrum, duration=600.0, n_components=20, seed=drawn.seed)
    np.testing.assert_array_equal(again.phase, drawn.phase)
    np.testing.assert_array_equal(again.omega, drawn.omega)


def test_simulate_waves_refuses_bad_duration_and_step():
    from cummins.radiation.model import RadiationModel
    from cummins.timedomain.simulate import simulate_waves
    from cummins.vessel import vessel_from_hydrodb

    ds = cummins.select_dofs(cummins.demo_dataset(), ["Heave"])
    vessel = vessel_from_hydrodb(ds, RadiationModel(("Heave",), (), np.zeros((1, 1))))
    sea = waves.regular_wave(1.0, 10.0, np.pi)
    for duration, dt in ((60.0, 0.0), (-1.0, 0.1), (np.nan, 0.1), (1e12, 0.05), (1.0, 5.0)):
        with pytest.raises(ArgumentError):
            simulate_waves(vessel, ds, sea, duration=duration, dt=dt)


# --------------------------------------------------------------------------- numerical guards


def _damaged(value, var="added_mass", index=(5, 2, 2)):
    ds = cummins.demo_dataset().copy(deep=True)
    ds[var] = ds[var].copy()
    ds[var].values[index] = value
    return ds


@pytest.mark.parametrize(
    ("var", "value"),
    [("added_mass", 1e300), ("radiation_damping", -9.99e99), ("added_mass", np.nan)],
)
def test_fit_refuses_absurd_data_naming_the_pair(var, value):
    """Values of 1e300 or -9.99e99 reached LAPACK (a raw LinAlgError); now a FitError names
    the DOF and the frequency before any fit starts."""
    from cummins.radiation.fit import fit_radiation

    ds = _damaged(value, var)
    w = float(ds.omega.values[5])
    with pytest.raises(FitError, match=rf"{var} \[Heave at omega = {w:.4g} rad/s\]"):
        fit_radiation(ds, max_order=4)


def test_fit_targets_are_checked():
    from cummins.radiation.fit import fit_radiation

    ds = cummins.demo_dataset()
    for options in ({"r2": 1.5}, {"r2": np.nan}, {"r2": 1.0}, {"threshold": -1.0}):
        with pytest.raises(ArgumentError):
            fit_radiation(ds, **options)


def test_passivity_and_reduction_refuse_a_model_with_nan():
    from cummins.radiation.model import CouplingModel, RadiationModel
    from cummins.radiation.passivity import enforce_passivity, passivity_test
    from cummins.radiation.reduce import reduce_radiation_model

    a = np.array([[-0.1, 1.0], [-1.0, -0.1]])
    good = CouplingModel(1, 1, a, np.array([0.0, 1.0]), np.array([1.0, 0.0]))
    bad = CouplingModel(0, 0, a, np.array([0.0, 1.0]), np.array([np.nan, 0.0]))
    model = RadiationModel(("Surge", "Heave"), (bad, good), np.eye(2))
    for call in (
        lambda: passivity_test(model),
        lambda: enforce_passivity(model),
        lambda: reduce_radiation_model(model, order=2),
    ):
        with pytest.raises(FitError, match="coupling Surge"):
            call()


# --------------------------------------------------------------------------- check


def _errors(ds):
    return [f for f in check(ds) if f.severity == "error"]


def test_check_flags_negated_damping():
    """Damping negated at every frequency passed ``check``; now each DOF is an error.
    On the tanker the sign-flipped B_ii is negative at 37 to 54 of the 58 frequencies
    (the rest are the irregular-frequency spikes, now positive), its peak included."""
    ds = cummins.demo_dataset().copy(deep=True)
    ds["radiation_damping"] = -ds.radiation_damping
    errors = [f for f in _errors(ds) if f.check == "damping_positive"]
    assert {f.where for f in errors} == set(cummins.DOF_NAMES)
    assert not check(ds).ok
    assert not _errors(cummins.demo_dataset())  # the data as solved: no error


def test_check_flags_nan_directions_and_positions():
    ds = cummins.demo_dataset()
    beta = ds.wave_direction.values.copy()
    beta[3] = np.nan
    errors = _errors(ds.assign_coords(wave_direction=beta))
    assert [f.where for f in errors] == ["wave_direction"]
    moved = ds.copy()
    moved.attrs = {**ds.attrs, "center_of_gravity": np.array([0.0, np.nan, 0.0])}
    assert [f.where for f in _errors(moved)] == ["center_of_gravity"]


@pytest.mark.parametrize(
    ("value", "fragment"), [(1e300, "beyond any floating body"), (-9.462e7, "negative")]
)
def test_check_flags_impossible_masses(value, fragment):
    """A 1e300 kg mass passed ``check``; a negative one too (beyond its inertia test)."""
    ds = cummins.demo_dataset().copy(deep=True)
    ds["inertia_matrix"] = ds.inertia_matrix.copy()
    for k in range(3):
        ds["inertia_matrix"].values[k, k] = value
    errors = _errors(ds)
    assert any(fragment in f.message and f.where == "Heave" for f in errors), errors


def test_published_data_with_a_noisy_base_are_no_error(corpus):
    """The near miss of the sign test among the 32 corpus cases: the OSWEC base (WAMIT 6,
    2015) has a roll damping of ±1.1e3 kg m²/s, negative at 47 of 50 frequencies, where
    the flap's rotations reach 2.8e7: solver noise (4e-5 of its kind), not a flipped sign."""
    ds = cummins.read(corpus / "WEC-Sim" / "wamit_OSWEC_2015_with_bemio_h5")
    assert not [f for f in _errors(ds) if f.check in ("damping_positive", "physical")]


# --------------------------------------------------------------------------- lf-model


def test_lf_model_heave_damping_of_a_spar_is_not_negative(corpus):
    """Issue 17: lf-model returned a negative heave damping on a spar. The route: K(t)
    (``--route kernel``) gives B_33(ω₀) = -62.6 kg/s at ω₀ = 0.208 rad/s on the OC3 spar
    (WEIS SS_Fitting case), where B_33 of the data is 29.9 at 0.20 and 2.45 at 0.25 rad/s:
    the truncation error of K(t) is larger than the damping itself. B(ω₀) is now taken
    from the data, linearly interpolated (25.7), with a warning."""
    from cummins.kinematics import rigid_body_inertia
    from cummins.timedomain.lfmodel import lf_model_from_frequency_data, lf_model_from_retardation

    ds = cummins.read(corpus / "WEIS" / "ss_fitting_OC3_spar")
    # OC3 Hywind platform mass (Jonkman 2010, 7.466e6 kg); rotations do not matter in heave
    m = rigid_body_inertia(7.466e6, [0.0, 0.0, 0.0], [1e9, 1e9, 1e9])
    ds["inertia_matrix"] = (("influenced_dof", "radiating_dof"), m)
    heave = cummins.select_dofs(ds, ["Heave"])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        kernel = lf_model_from_retardation(heave)
    w0 = kernel.frequencies[0]
    b = heave.radiation_damping.values[:, 0, 0]
    expected = np.interp(w0, heave.omega.values, b)
    assert kernel.damping[0, 0] == pytest.approx(expected, rel=1e-12)
    assert kernel.damping[0, 0] > 0 and "instead" in kernel.provenance[0]
    assert any(issubclass(w.category, CumminsWarning) for w in caught)
    # the frequency route's spline gives 21.6, positive: kept as it is
    spline = lf_model_from_frequency_data(heave)
    assert 0 < spline.damping[0, 0] < 30 and "instead" not in spline.provenance[0]


def test_lf_model_refuses_data_negative_at_the_natural_frequency():
    ds = cummins.select_dofs(cummins.demo_dataset(), ["Heave"]).copy(deep=True)
    ds["radiation_damping"] = -ds.radiation_damping
    from cummins.timedomain.lfmodel import lf_model_from_frequency_data

    with pytest.raises(HydroDataError, match="negative at the natural frequency"):
        lf_model_from_frequency_data(ds)


# --------------------------------------------------------------------------- messages


def test_missing_inertia_names_what_and_how():
    """The message suggested ".hst/.frc" when the .hst was there: it now names the missing
    variable, what the data have, and how to give it."""
    from cummins.vessel import vessel_from_hydrodb

    ds = cummins.demo_dataset().drop_vars("inertia_matrix")
    with pytest.raises(HydroDataError) as info:
        vessel_from_hydrodb(ds)
    message = str(info.value)
    assert "no 'inertia_matrix' (they have hydrostatic_stiffness)" in message
    assert "cummins.with_inertia(" in message and "--mass" in message
    assert "--radii-of-gyration" in message
