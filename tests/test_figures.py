"""The figures show what the numbers are: K(t) to where it has decayed, numerically-zero
DOFs as "≈ 0", rotations in degrees, RAO phases as unwrapped lines, legends outside the
panels, labels inside the image, one fit figure per DOF."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

import cummins
from cummins import plots
from cummins.display import DECAY_FRACTION, negligible_series


@pytest.fixture(scope="module")
def tanker():
    return cummins.demo_dataset()


@pytest.fixture(scope="module")
def model(tanker):
    return cummins.fit_radiation(tanker)


@pytest.fixture(scope="module")
def head_seas_run(tanker, model):
    from cummins.seakeeping.waves import irregular_waves, wave_spectrum

    vessel = cummins.vessel_from_hydrodb(tanker, model, viscous_damping=[1e6, 1e6, 0, 0, 0, 1e10])
    sea = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0), duration=120, n_components=60, direction=np.pi, seed=1
    )
    return cummins.simulate_waves(vessel, tanker, sea, duration=120, dt=0.1), sea, vessel


def _axis_by_ylabel(fig, start):
    return next(ax for ax in fig.axes if ax.get_ylabel().startswith(start))


def test_kernel_panels_end_where_k_has_decayed(tanker):
    k = cummins.retardation_function(tanker)
    t = k.time.values
    fig = plots.plot_retardation(k)
    for ax, dof in zip(fig.axes, cummins.DOF_NAMES, strict=True):
        end = ax.get_xlim()[1]
        values = np.abs(k.sel(influenced_dof=dof, radiating_dof=dof).values)
        # beyond the panel |K| stays below 1 % of its peak; the panel is not the record
        assert values[t > end].max(initial=0.0) < DECAY_FRACTION * values.max()
        assert end < 0.6 * t[-1], (dof, end, t[-1])
        assert any("record to" in text.get_text() for text in ax.texts)


def test_numerically_zero_dofs_and_degrees_in_time_series(head_seas_run):
    run, _, _ = head_seas_run
    fig = plots.plot_time_series(run)
    motion = run.motion
    # head seas: sway, roll and yaw are numerical noise against surge, heave and pitch
    assert float(np.abs(motion.sel(dof="Sway")).max()) < 1e-6
    for dof in ("Sway", "Roll", "Yaw"):
        ax = _axis_by_ylabel(fig, dof)
        assert list(ax.get_yticks()) == [0.0] and any("≈ 0" in t.get_text() for t in ax.texts)
    heave = _axis_by_ylabel(fig, "Heave")
    assert not heave.texts and heave.get_ylabel() == "Heave [m]"
    pitch = _axis_by_ylabel(fig, "Pitch")
    assert pitch.get_ylabel() == "Pitch [deg]"
    drawn = pitch.get_lines()[0].get_ydata()
    np.testing.assert_allclose(
        np.abs(drawn).max(), np.degrees(np.abs(motion.sel(dof="Pitch").values).max())
    )


def test_rao_phases_are_wrapped_masked_and_rotations_in_degrees(tanker):
    """The phase as seakeeping tools show it: within ±180°, its line broken where it wraps
    (no segment crosses the panel), and drawn only where |RAO| ≥ 1 % of the DOF's peak."""
    from cummins.seakeeping.frequency_domain import motion_rao

    rao = motion_rao(tanker, wave_direction=[np.radians(150.0)])
    fig = plots.plot_rao(rao)
    phase = _axis_by_ylabel(fig, "∠RAO Heave")
    (line,) = phase.get_lines()
    x = np.asarray(line.get_xdata(), dtype=float)
    y = np.asarray(line.get_ydata(), dtype=float)
    assert np.nanmax(np.abs(y)) <= 180.0
    both = np.isfinite(y[:-1]) & np.isfinite(y[1:])
    assert np.abs(np.diff(y))[both].max() < 180.0  # broken at the wraps
    heave = rao.sel(dof="Heave").isel(wave_direction=0)
    shown = np.isin(heave.omega.values, x[np.isfinite(y)])
    amplitude = np.abs(heave.values)
    assert amplitude[shown].min() >= 0.01 * amplitude.max()
    assert (~shown).any() and amplitude[~shown].max() < 0.01 * amplitude.max()
    np.testing.assert_allclose(
        y[np.isfinite(y)], np.degrees(np.angle(heave.values[shown])), atol=1e-9
    )
    roll = _axis_by_ylabel(fig, "|RAO| Roll")
    assert roll.get_ylabel() == "|RAO| Roll [deg/m]"
    np.testing.assert_allclose(
        np.max(roll.get_lines()[0].get_ydata()),
        np.degrees(np.abs(rao.sel(dof="Roll").values).max()),
    )
    assert fig.legends and not any(ax.get_legend() for ax in fig.axes)


def test_response_spectra_of_12_dofs_are_not_cramped(head_seas_run):
    import xarray as xr

    run, _, _ = head_seas_run
    labels = [f"body{1 + k // 6}__{d}" for k, d in enumerate(2 * list(cummins.DOF_NAMES))]
    motion = np.concatenate([run.motion.values, 0.5 * run.motion.values], axis=1)
    twelve = xr.Dataset(
        {"motion": (("time", "dof"), motion)},
        coords={"time": run.time.values, "dof": labels},
        attrs={"dt": run.attrs["dt"], "sea": "two bodies"},
    )
    w = np.linspace(0.2, 2.0, 50)
    fig = plots.plot_response_spectra(twelve, {"reference": (w, np.ones((50, 12)))})
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert len(visible) == 12
    columns = {round(ax.get_position().x0, 3) for ax in visible}
    assert len(columns) == 3  # at most three panels a row
    assert fig.legends and not any(ax.get_legend() for ax in fig.axes)
    assert fig.get_size_inches()[1] >= 4 * 2.6


def test_labels_are_inside_the_saved_image(tanker, tmp_path):
    """The tanker's added-mass figure cut "A Roll [kg·m²]" at the left edge."""
    fig = plots.plot_added_mass_damping(tanker)
    canvas = FigureCanvasAgg(fig)
    plots.save_figure(fig, tmp_path / "a.png")
    renderer = canvas.get_renderer()
    for ax in fig.axes:
        box = ax.yaxis.label.get_window_extent(renderer)
        assert box.x0 >= 0, ax.get_ylabel()


def test_one_fit_figure_per_dof_with_a_row_per_coupling(tanker, model):
    from cummins.fit_figures import fit_figures, fitted_rows

    figures = dict(fit_figures(model, tanker))
    rows = fitted_rows(model)
    assert sorted(figures) == sorted(f"fit_{model.dofs[i]}.png" for i in rows)
    # the tanker: surge with heave and pitch, sway with roll and yaw, ...
    assert [model.dofs[j] for j in rows[0]] == ["Surge", "Heave", "Pitch"]
    for i, columns in rows.items():
        assert len(figures[f"fit_{model.dofs[i]}.png"].axes) == 4 * len(columns)
    # each K(t) panel ends where the model and the data have decayed
    surge = figures["fit_Surge.png"].axes[3]
    assert surge.get_xlim()[1] < 40.0


def test_negligible_series_by_kind():
    peaks = [1.0, 1e-7, 0.02, 1e-9, 0.5]
    rotations = [False, False, True, True, True]
    assert negligible_series(peaks, rotations).tolist() == [False, True, False, True, False]


def test_the_peak_of_equal_headings_is_the_first():
    """An axisymmetric buoy's PTO power is the same at 0, 30, 60 and 90° up to the
    solver's rounding: the table named 60°, where the rounding put the largest; now the
    first of the tied headings, and a real peak where it is."""
    from cummins.display import peak_index

    omega = np.linspace(0.5, 2.0, 7)
    power = np.tile(np.exp(-((omega - 1.2) ** 2))[:, None], (1, 4))
    power[:, 2] *= 1 + 3e-15  # the rounding
    assert peak_index(power) == (3, 0)
    power[:, 3] *= 1.01  # a heading that is larger
    assert peak_index(power) == (3, 3)
