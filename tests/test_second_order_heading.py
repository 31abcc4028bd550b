"""The second-order wave loads of the DP model at the vessel's instantaneous relative heading
(`cummins.timedomain.loads.relative_heading`), on real data: the WAMIT tanker's mean drift
(its `.out`, 19 headings 0–180°, mirrored for the symmetric hull), the OC4 semi's QTF (WAMIT
`.12d`/`.12s`, one heading) and a multi-heading QTF made of the tanker's drift."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner
from scipy.interpolate import CubicSpline

import cummins
from cummins.cli import main
from cummins.errors import AssumptionWarning, HydroDataError
from cummins.qtf import QTFTable, qtf_table, with_second_order
from cummins.seakeeping.headings import MIRROR_SIGNS
from cummins.seakeeping.waves import WaveComponents, irregular_waves, wave_spectrum
from cummins.timedomain.loads import SecondOrderWaveLoad, WaveDriftLoad

OC4 = "corpus/WEIS/ss_fitting_OC4_semi/marin_semi.1"
SOUND = 3.0  # rad/s: below the tanker's suspect frequencies (3.65 rad/s and above)


def _quiet_read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path)


@pytest.fixture(scope="module")
def tanker():
    return _quiet_read(cummins.demo_files() / "tanker.1")


@pytest.fixture(scope="module")
def tanker_qtf(tanker):
    """A QTF of several headings from real data: Newman's Q(ω₁, ω₂, β) = ½(T(ω₁, β) +
    T(ω₂, β)) of the tanker's drift (z-up, 0–180°, below its suspect frequencies)."""
    ds = tanker.isel(omega=tanker.omega.values < SOUND)
    t = ds.drift_force.transpose("omega", "wave_direction", "influenced_dof").values
    q = (0.5 * (t[:, None] + t[None, :])).astype(complex)
    dofs = tuple(str(d) for d in ds.influenced_dof.values)
    table = QTFTable("difference", ds.omega.values, ds.wave_direction.values, q, dofs)
    return ds, with_second_order(ds, [table])


def _pose(psi_deg, north=0.0, east=0.0):
    return np.array([north, east, 0.0, 0.0, 0.0, np.radians(psi_deg)])


def _data_drift(ds_z, omega, relative_deg):
    """The z-down data's drift at a data frequency and relative direction, the other
    half-plane by the mirror rule T F(−β)."""
    beta = np.mod(np.degrees(ds_z.wave_direction.values), 360.0)
    rel = np.mod(relative_deg, 360.0)
    f = ds_z.drift_force.sel(omega=omega).transpose("wave_direction", "influenced_dof").values
    hit = np.isclose(beta, rel, atol=1e-6) | np.isclose(np.abs(beta - rel), 360.0, atol=1e-6)
    if hit.any():
        return f[np.argmax(hit)]
    image = np.isclose(beta, np.mod(-rel, 360.0), atol=1e-6)
    assert image.any(), relative_deg
    return MIRROR_SIGNS * f[np.argmax(image)]


def test_mean_drift_follows_the_relative_heading_on_the_data(tanker):
    """A vessel held at heading ψ in a regular wave travelling to β sees the data's drift
    at β − ψ: at the data's headings (and their mirror images) to rounding, midway
    between two of them their mean, within the linear interpolation's error of a
    periodic cubic spline through the data."""
    ds_z = cummins.change_axes(tanker, "z-down")
    omega = float(tanker.omega.values[np.argmin(np.abs(tanker.omega.values - 0.6))])
    for beta in (180.0, 225.0):
        waves = WaveComponents([omega], [1.0], [0.0], [np.radians(beta)])
        load = SecondOrderWaveLoad.from_hydrodb(tanker, waves, model="mean")
        for relative in (180.0, 170.0, 150.0, 90.0, 240.0, 40.0, 0.0, 300.0):
            psi = beta - relative  # the data's headings and their mirror images
            expected = _data_drift(ds_z, omega, relative)
            scale = np.abs(ds_z.drift_force.sel(omega=omega).values).max(axis=0)
            got = load.force(0.0, _pose(psi, 3.0, -4.0), np.zeros(6))
            np.testing.assert_allclose(got, expected, rtol=0, atol=1e-10 * scale.max())
        # midway between 180° and 190° (relative), and between 10° and 20°
        for mid in (185.0, 15.0):
            psi = beta - mid
            got = load.force(0.0, _pose(psi), np.zeros(6))
            lo, hi = _data_drift(ds_z, omega, mid - 5), _data_drift(ds_z, omega, mid + 5)
            np.testing.assert_allclose(got, 0.5 * (lo + hi), rtol=1e-12, atol=1e-6)
            grid = np.arange(0.0, 360.0, 10.0)
            values = np.array([_data_drift(ds_z, omega, g) for g in grid])
            spline = CubicSpline(
                np.append(grid, 360.0), np.vstack([values, values[:1]]), bc_type="periodic"
            )
            # the error of linear interpolation midway, h² |f''| / 8, from the second
            # differences around it (allowed 4 times)
            i = int(np.searchsorted(grid, mid - 5))
            near = values[(i + np.array([-1, 0, 1, 2])) % grid.size]
            bound = 0.5 * np.abs(np.diff(near, 2, axis=0)).max(axis=0) + 1e-9 * scale
            assert np.all(np.abs(got - spline(mid)) <= bound)


def test_a_vessel_turned_by_90_degrees_sees_the_beam_sea_drift(tanker):
    """JONSWAP Hs 4 m, Tp 10 s travelling south (head seas for a vessel heading north):
    the mean drift pushes the tanker astern, with no sway and no yaw (the mirror
    symmetry); turned to heading 90° (east) it sees the waves on its port beam: the
    data's beam-sea drift, Σ a² T(ω, 90°) summed by hand, pushing it to starboard."""
    sea = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0),
        duration=600,
        n_components=80,
        direction=np.pi,
        seed=1,
        omega_max=SOUND,
        data=tanker,
    )
    load = SecondOrderWaveLoad.from_hydrodb(tanker, sea, model="mean")
    head = load.force(0.0, _pose(0.0), np.zeros(6))
    beam = load.force(0.0, _pose(90.0), np.zeros(6))
    ds_z = cummins.change_axes(tanker, "z-down")
    by_hand = np.zeros(6)
    for dof in range(6):
        t90 = np.array([_data_drift(ds_z, w, 90.0)[dof] for w in ds_z.omega.values])
        by_hand[dof] = np.sum(sea.amplitude**2 * np.interp(sea.omega, ds_z.omega.values, t90))
    np.testing.assert_allclose(beam, by_hand, rtol=1e-10, atol=1e-9 * np.abs(by_hand).max())
    assert head[0] < 0 and abs(head[1]) < 1e-4 * abs(head[0])
    assert abs(head[5]) < 1e-4 * abs(beam[5]) + 1.0
    assert beam[1] > 0 and beam[1] > 3 * abs(head[0])


@pytest.mark.parametrize("model", ["mean", "newman"])
def test_dp_demos_drift_and_the_second_order_load_agree_at_any_heading(tanker, model):
    """`dp-demo --second-order mean|newman` (WaveDriftLoad, without or with its slowly
    varying part) and SecondOrderWaveLoad(model=...), two implementations, in a
    short-crested sea at headings all round and off the origin."""
    sea = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0),
        duration=600,
        n_components=30,
        direction=2.6,
        spreading=5,
        n_directions=5,
        seed=3,
        omega_max=SOUND,
        data=tanker,
    )
    ours = SecondOrderWaveLoad.from_hydrodb(tanker, sea, model=model)
    slowly = model == "newman"
    dp = WaveDriftLoad.from_hydrodb(tanker, sea, slowly_varying=slowly, extrapolate="zero")
    for psi in np.arange(-180.0, 180.0, 17.0):
        a = ours.force(41.0, _pose(psi, 5.0, -7.0), np.zeros(6))
        b = dp.force(41.0, _pose(psi, 5.0, -7.0), np.zeros(6))
        np.testing.assert_allclose(a, b, rtol=1e-10, atol=1e-10 * np.abs(b).max())


def test_full_qtf_at_the_start_heading_is_the_fixed_heading_force(shared_data):
    """No regression: the OC4 semi's QTFs (difference and sum, one heading, 0°) in a
    long-crested sea, the vessel at its start heading and off its origin: the force
    that follows the heading equals the fixed-heading one to rounding; yawed, a QTF of
    one direction is held at it (and the notes say so)."""
    ds = _quiet_read(shared_data / OC4)
    sea = irregular_waves(
        wave_spectrum("jonswap", 6.0, 10.0),
        duration=1800,
        n_components=100,
        direction=0.0,
        seed=1,
        omega_min=0.25,
        omega_max=3.0,
    )
    new = SecondOrderWaveLoad.from_hydrodb(ds, sea, model="full")
    old = SecondOrderWaveLoad.from_hydrodb(ds, sea, model="full", follow_heading=False)
    assert new.sum is not None and new.headings.sum is not None
    forces = []
    for t in np.linspace(0.0, 600.0, 13):
        a = new.force(t, _pose(0.0, 4.0, -3.0), np.zeros(6))
        b = old.force(t, _pose(0.0, 4.0, -3.0), np.zeros(6))
        forces.append((a, b))
    a, b = (np.array(x) for x in zip(*forces, strict=True))
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-10 * np.abs(b).max(axis=0).max())
    yawed = new.force(100.0, _pose(5.0, 4.0, -3.0), np.zeros(6))
    np.testing.assert_allclose(yawed, old.force(100.0, _pose(5.0, 4.0, -3.0), np.zeros(6)))
    assert any("one direction (0 deg): held" in n for n in new.notes)


def test_full_qtf_of_several_headings_follows_the_relative_heading(tanker_qtf):
    """A multi-heading QTF made of the tanker's drift (Newman's form, 0–180°, mirrored as a
    symmetric hull's): the full load at any heading equals the DP model's Newman drift
    (WaveDriftLoad, which follows the heading by its own code) in a long-crested sea, to
    rounding; in a short-crested sea at the start heading it equals the fixed-heading
    load (pair matrices decomposed without truncation)."""
    ds, dq = tanker_qtf
    long = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0),
        duration=600,
        n_components=60,
        direction=np.pi,
        seed=1,
        omega_max=2.9,  # inside the QTF grid (to 2.936 rad/s): no pair left out
        data=ds,
    )
    full = SecondOrderWaveLoad.from_hydrodb(dq, long, model="full")
    assert any("QTF of the mirrored directions" in n for n in full.notes)
    # the QTF is used as it is: the drift too (its suspect frequencies kept)
    newman = WaveDriftLoad.from_hydrodb(ds, long, extrapolate="zero", keep_suspect=True)
    for psi in (0.0, 7.0, 33.0, 90.0, 150.0, 200.0, -100.0):
        a = full.force(12.3, _pose(psi, 3.0, -2.0), np.zeros(6))
        b = newman.force(12.3, _pose(psi, 3.0, -2.0), np.zeros(6))
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * np.abs(b).max())
    short = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0),
        duration=600,
        n_components=20,
        direction=np.pi,
        spreading=5,
        n_directions=5,
        seed=2,
        omega_max=2.9,  # inside the QTF grid (to 2.936 rad/s): no pair left out
        data=ds,
    )
    new = SecondOrderWaveLoad.from_hydrodb(dq, short, model="full", heading=0.3)
    old = SecondOrderWaveLoad.from_hydrodb(
        dq, short, model="full", heading=0.3, follow_heading=False, tol=1e-12
    )
    for t in (0.0, 40.0, 333.0):
        a = new.force(t, _pose(np.degrees(0.3), 1.0, 2.0), np.zeros(6))
        b = old.force(t, _pose(np.degrees(0.3), 1.0, 2.0), np.zeros(6))
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * np.abs(b).max())


def test_a_relative_heading_outside_the_data_is_held_and_said(tanker):
    """The tanker's drift cut to 0–90° (z-up), mirrored to −90…90°: a gap of 180° that no
    mirror closes. A sea outside it at the start heading is refused in one line naming the
    data's headings; a vessel that turns into it takes the nearest heading's drift, with
    one warning saying so."""
    ds = tanker.isel(wave_direction=tanker.wave_direction.values < np.radians(90.5))
    waves = WaveComponents([0.6], [1.0], [0.0], [0.0])
    head = WaveComponents([0.6], [1.0], [0.0], [np.pi])
    with pytest.raises(HydroDataError, match=r"no wave direction near 180 deg \(it has .*90"):
        SecondOrderWaveLoad.from_hydrodb(ds, head, model="mean")
    load = SecondOrderWaveLoad.from_hydrodb(ds, waves, model="mean")
    assert any("in gaps over 90 deg it takes the nearest" in n for n in load.notes)
    at_270 = load.force(0.0, _pose(90.0), np.zeros(6))  # relative −90° = 270°: data
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        inside_gap = load.force(5.0, _pose(150.0), np.zeros(6))  # relative 210°
        again = load.force(6.0, _pose(160.0), np.zeros(6))
    said = [w for w in caught if issubclass(w.category, AssumptionWarning)]
    assert len(said) == 1 and "outside the mean drift's directions" in str(said[0].message)
    assert "t = 5 s" in str(said[0].message) and "nearest direction" in str(said[0].message)
    np.testing.assert_array_equal(inside_gap, at_270)
    np.testing.assert_array_equal(again, at_270)


def test_dp_turn_reverses_the_drift_yaw_moment(tanker, shared_data):
    """The DP scenario on the WAMIT tanker (its mean drift; main dimensions and Bv of MSS's
    tanker.mat, the same ship) in the paper's short-crested sea from 45° off the bow, the
    yaw set-point at 70°: as the ship turns through head seas (ψ = 45°) the mean drift's
    yaw moment, which turned the bow away from the waves, changes sign (measured at
    ψ = 47.3°: the five directions' random frequencies are not exactly symmetric), and
    every step's moment is the data's drift at the relative heading of that step."""
    from cummins.cli.dp_scenario import data_viscous_damping, run_scenario

    mss = _quiet_read(shared_data / "mss" / "tanker" / "tanker.mat")
    ds = tanker.copy()
    ds.attrs.update({k: mss.attrs[k] for k in ("ship_length", "ship_breadth", "ship_draught")})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scenario = run_scenario(
            ds,
            duration=150.0,
            dt=0.2,
            seed=1,
            second_order="mean",
            crane=False,
            yaw_setpoint=np.radians(70.0),
            viscous_damping=data_viscous_damping(mss),
        )
    run = scenario.run
    yaw = np.degrees(run.eta.sel(dof="Yaw").values)
    moment = run["force_wave drift"].sel(velocity="Yaw").values
    assert yaw[-1] == pytest.approx(70.0, abs=4.0)
    assert moment[0] < -1e6 and moment[-1] > 1e6
    change = np.flatnonzero(np.diff(np.sign(moment)) != 0)
    assert change.size == 1 and 40.0 < yaw[change[0]] < 55.0
    load = SecondOrderWaveLoad.from_hydrodb(ds, scenario.sea, model="mean")
    expected = np.array(
        [
            load.force(t, e, np.zeros(6))[5]
            for t, e in zip(run.time.values, run.eta.values, strict=True)
        ]
    )
    np.testing.assert_allclose(moment, expected, rtol=0, atol=1e-9 * np.abs(moment).max())


def test_cli_dp_demo_yaw_setpoint(tmp_path):
    """`dp-demo --yaw-setpoint 30`: the S-175 turns towards 30° and the run says so."""
    out = tmp_path / "dp"
    args = [
        "dp-demo",
        "-o",
        str(out),
        "--duration",
        "60",
        "--yaw-setpoint",
        "30",
        "--second-order",
        "mean",
    ]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    run = xr.open_dataset(out / "run.nc", engine="h5netcdf")
    assert run.attrs["yaw_setpoint_deg"] == pytest.approx(30.0)
    assert np.degrees(run.eta.sel(dof="Yaw").values[-1]) > 15.0


def test_a_half_plane_qtf_of_a_symmetric_hull_is_mirrored(tanker_qtf):
    """The tanker's QTF (0–180°, z-up) on 36 directions: the new ones the old ones' images,
    sway, roll and yaw negated (the mirror rule of the first order); a QTF whose sway
    does not vanish in head seas says the hull is not symmetric and is left as it is."""
    from cummins.qtf.headings import mirrored_qtf

    _, dq = tanker_qtf
    table, coverage = mirrored_qtf(dq)
    assert coverage.mirror_used and table.directions.size == 36
    data = dq.qtf_difference.transpose("qtf_omega", "qtf_omega2", "qtf_wave_direction", ...).values
    for k, beta in enumerate(np.degrees(table.directions)):
        source = int(np.argmin(np.abs(np.degrees(dq.qtf_wave_direction.values) - beta)))
        if beta <= 180.0 + 1e-9:
            np.testing.assert_array_equal(table.values[:, :, k], data[:, :, source])
        else:
            image = int(np.argmin(np.abs(np.degrees(dq.qtf_wave_direction.values) - (360 - beta))))
            np.testing.assert_array_equal(table.values[:, :, k], data[:, :, image] * MIRROR_SIGNS)
    skewed = dq.copy(deep=True)
    head = int(np.argmin(np.abs(dq.qtf_wave_direction.values - np.pi)))
    sway = skewed.qtf_difference.values[:, :, head, 1]
    skewed.qtf_difference.values[:, :, head, 1] = sway + 0.01 * np.abs(data[..., 0]).max()
    table, coverage = mirrored_qtf(skewed)
    assert not coverage.mirror_used and table.directions.size == 19
    assert "not mirrored: the QTF's Sway in waves along the x axis" in coverage.reason


def test_a_bidirectional_qtf_follows_the_relative_heading(tanker):
    """A bi-directional QTF of the tanker's drift, Q(ω₁, ω₂, β₁, β₂) = ½(T(ω₁, β₁) +
    T(ω₂, β₂)) (Newman's pairing of two directions; every second heading, 0.3–1.6 rad/s),
    in a short-crested sea on the beam: the full load follows the heading as the DP
    model's Newman drift does, to rounding, while the relative directions stay on the
    data's half-plane (a bi-directional QTF is not mirrored)."""
    w = tanker.omega.values
    ds = tanker.isel(omega=(w > 0.3) & (w < 1.6), wave_direction=slice(None, None, 2))
    t = ds.drift_force.transpose("omega", "wave_direction", "influenced_dof").values
    q = (0.5 * (t[:, None, :, None] + t[None, :, None, :])).astype(complex)
    dofs = tuple(str(d) for d in ds.influenced_dof.values)
    table = QTFTable(
        "difference", ds.omega.values, ds.wave_direction.values, q, dofs, bidirectional=True
    )
    dq = with_second_order(ds, [table])
    sea = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0),
        duration=600,
        n_components=20,
        direction=np.radians(270.0),
        spreading=5,
        n_directions=5,
        seed=2,
        omega_min=0.4,
        omega_max=1.5,
    )  # directions 184.8–355.2°: within the data's 180–360° (z-down) for |ψ| < 4.8°
    full = SecondOrderWaveLoad.from_hydrodb(dq, sea, model="full")
    assert full.headings.difference.bidirectional
    newman = WaveDriftLoad.from_hydrodb(
        ds, sea, extrapolate="zero", keep_suspect=True, mirror=False, max_heading_gap=np.pi
    )
    for psi in (0.0, 3.3, -4.0, 4.5):
        a = full.force(33.0, _pose(psi, 2.0, 1.0), np.zeros(6))
        b = newman.force(33.0, _pose(psi, 2.0, 1.0), np.zeros(6))
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * np.abs(b).max())


def test_a_load_that_follows_the_heading_builds_its_fixed_forms_on_first_use(
    tanker_qtf, monkeypatch
):
    """The DP load following the heading does not use the forms held at ψ₀ (the pair
    matrices of a short-crested sea decomposed: the costliest set-up); it builds them on
    the first ``time_series`` or ``stationary_state`` (once), and these, and ``mean``,
    equal the held load's to rounding. The multi-heading QTF of the tanker's drift, with
    the same values as a sum-frequency QTF (for the sum's form: the corpus's sum QTFs
    have one heading, which no short-crested sea fits), a sea of 30 × 3 components."""
    from cummins.timedomain.loads import second_order

    built = []
    full = second_order._full

    def counted(table, *args):
        built.append(table.kind)
        return full(table, *args)

    monkeypatch.setattr(second_order, "_full", counted)
    ds, dq = tanker_qtf
    table = qtf_table(dq, "difference")
    both = with_second_order(
        ds,
        [table, QTFTable("sum", table.omega, table.directions, table.values, table.dofs)],
    )
    sea = irregular_waves(
        wave_spectrum("jonswap", 4.0, 10.0),
        duration=600,
        n_components=30,
        direction=np.pi,
        spreading=5,
        n_directions=3,
        seed=3,
        omega_max=2.9,  # inside the QTF grid
        data=ds,
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        follow = SecondOrderWaveLoad.from_hydrodb(both, sea, model="full", heading=0.2)
        assert built == []  # nothing of the fixed heading built for the DP run
        held = SecondOrderWaveLoad.from_hydrodb(
            both, sea, model="full", heading=0.2, follow_heading=False
        )
        assert built == ["difference", "sum"]
        follow.force(10.0, _pose(12.0), np.zeros(6))
        assert built == ["difference", "sum"]  # the run's force: the heading table's
        t = np.arange(0.0, 600.0, 0.1)
        expected = held.time_series(t)
        np.testing.assert_allclose(
            follow.time_series(t), expected, rtol=0, atol=1e-12 * np.abs(expected).max()
        )
        assert built == ["difference", "sum"] * 2
        vessel = cummins.vessel_from_hydrodb(ds)
        x, notes = follow.stationary_state(vessel)
        y, held_notes = held.stationary_state(vessel)
    np.testing.assert_allclose(x, y, rtol=0, atol=1e-12 * np.abs(y).max())
    assert notes == held_notes and built == ["difference", "sum"] * 2  # built once
    np.testing.assert_array_equal(follow.mean, held.mean)
    assert follow.difference is not None and follow.sum is not None
    assert any("sum-frequency QTF: exact at the instantaneous" in n for n in follow.notes)
