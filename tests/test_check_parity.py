"""The ``wave_parity`` check on MSS's processed structs: which headings break the port/
starboard mirror of the mean drift, in which pattern, against the solvers' own drift.

MSS computes 0–180° and fills 190–350°. Its ``tanker.mat`` (``wamit2vessel.m``) holds at
190–350° the drift of 10–170° in the same order, sway and yaw negated, F(β + π) = T F(β),
instead of the mirror F(−β) = T F(β), while its first-order tables there are the mirror
images; its VERES structs (``read_veres_WD.m``) keep the yaw drift's sign at the mirrored
headings, about the VERES motion reference point.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import cummins
from cummins.check.parity import break_pattern, degree_ranges, mirror_pairs
from cummins.hydrodb import change_axes, move_reference_point
from cummins.io.mss.points import _rigid_body_cg
from cummins.seakeeping.headings import MIRROR_SIGNS, mirror_headings


def _read(path, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cummins.read(path, **options)


def _parity_warnings(ds):
    return [f for f in cummins.check(ds).by_check("wave_parity") if f.severity == "warning"]


def _half_plane(ds):
    """The advice's selection: the headings 0–180° (the solver's, for MSS)."""
    return ds.isel(wave_direction=np.flatnonzero(ds.wave_direction.values <= np.pi + 1e-9))


def _correlation(a, b):
    a, b = np.ravel(a), np.ravel(b)
    return float(a @ b / np.linalg.norm(a) / np.linalg.norm(b))


def test_the_mss_tanker_drift_is_shifted_by_180_degrees_not_mirrored(shared_data):
    """tanker.mat: surge, sway and yaw drift flagged, 190–350° named, the pattern
    F(β + π) = T F(β) recognised, the first-order tables there mirroring (1e-7, single
    precision). Against the WAMIT drift of the same hull (tanker.out, pressure integration
    of another WAMIT run than the one MSS processed: MSS's drift is its repository's
    tanker.9) over 0.4–1.5 rad/s at 190–350°: the file's surge and yaw correlate
    negatively (−0.89, −0.62: the surge pushes the hull forward in near-head seas), the
    kept half-plane mirrored positively (0.90, 0.65, as 10–170° do)."""
    ds = _read(shared_data / "mss" / "tanker" / "tanker.mat", drift_as_stored=True)
    flagged = _parity_warnings(ds)
    assert sorted(f.where for f in flagged) == ["Surge", "Sway", "Yaw"]
    for f in flagged:
        assert "drift_force" in f.message and f.details["pattern"] == "shifted"
        assert set(f.details["headings_deg"]) <= set(range(190, 360, 10))
        assert {200.0, 300.0} <= set(f.details["headings_deg"])
        assert f.details["first_order_mismatch"] < 1e-5  # 1.1e-7
        assert "in the same order (β + 180°)" in f.message and "190–" in f.message
        assert "wamit2vessel" in f.advice
    degrees = np.degrees(ds.wave_direction.values).round().astype(int)
    upper = np.flatnonzero(degrees > 180)
    drift = ds.drift_force.values
    shifted = drift[:, upper - 18] * MIRROR_SIGNS  # F(β + π) = T F(β), to the last digit
    assert np.abs(drift[:, upper] - shifted).max() <= 1e-12 * np.abs(drift).max()

    kept, coverage = mirror_headings(_half_plane(ds))
    assert coverage.mirror_used and kept.sizes["wave_direction"] == 36
    for name in ("excitation_force", "rao"):  # MSS mirrored these itself
        assert (
            np.abs(kept[name].values - ds[name].values).max()
            <= 1e-12 * np.abs(ds[name].values).max()
        )
    assert not _parity_warnings(_half_plane(ds))
    default = _read(shared_data / "mss" / "tanker" / "tanker.mat")  # mirrored on reading
    assert np.array_equal(default.drift_force.values, kept.drift_force.values)
    assert not _parity_warnings(default)

    wamit, _ = mirror_headings(
        change_axes(_read(shared_data / "mss" / "tanker" / "tanker.1"), "z-down")
    )
    np.testing.assert_allclose(wamit.wave_direction.values, ds.wave_direction.values)
    band = (ds.omega.values > 0.4) & (ds.omega.values < 1.5)
    for dof, file_max, kept_min in (("Surge", -0.4, 0.45), ("Yaw", -0.3, 0.3)):
        ref = wamit.drift_force.sel(influenced_dof=dof).values[band][:, upper]
        as_read = ds.drift_force.sel(influenced_dof=dof).values[band][:, upper]
        mirrored = kept.drift_force.sel(influenced_dof=dof).values[band][:, upper]
        assert _correlation(as_read, ref) < file_max
        assert _correlation(mirrored, ref) > kept_min


@pytest.mark.parametrize("case", ["supply/supply.mat", "s175/s175.mat"])
def test_the_mss_veres_yaw_drift_keeps_its_sign_about_the_veres_point(shared_data, case):
    """supply.mat, s175.mat: only the yaw drift flagged, as mirrored with its sign kept
    about a point the check finds by least squares — the VERES motion reference point at
    the x of G (−5.386 m, −2.547 m from CO; cummins moved the drift from there to CO)."""
    path = shared_data / "mss" / case
    ds = _read(path, drift_as_stored=True)
    from scipy.io import loadmat

    x_g = _rigid_body_cg(loadmat(path)["vessel"][0, 0]["MRB"])[0]
    yaw = [f for f in _parity_warnings(ds) if f.where == "Yaw"]
    assert yaw and all(f.details["pattern"] == "sign_kept_about" for f in yaw)
    for f in yaw:
        assert abs(f.details["point_x"] - x_g) < 1e-3
        assert "read_veres_WD" in f.advice
    assert {f.where for f in _parity_warnings(ds)} <= {"Yaw", "Sway"}  # S-175's own 0° sway


def test_the_supply_drift_against_veres_own(shared_data):
    """supply.mat's drift at 0–180° is VERES's input.re2 (read by cummins' VERES reader,
    Fossen's axes, moved to CO) to 4.5e-8 of each DOF's peak (single precision); at
    190–350° the yaw is off by 117 % of its peak; the kept half-plane mirrored is VERES's
    mirrored to 4.5e-8 again."""
    ds = _read(shared_data / "mss" / "supply" / "supply.mat", drift_as_stored=True)
    veres = change_axes(_read(shared_data / "mss" / "supply" / "input.re7"), "z-down")
    veres, _ = mirror_headings(move_reference_point(veres, ds.attrs["reference_point"]))
    ref = veres.drift_force.values
    peak = np.abs(ref).max(axis=(0, 1))[[0, 1, 5]]
    lower = np.degrees(ds.wave_direction.values) < 180.5

    def error(values, where):
        return np.abs(values[:, where] - ref[:, where])[..., [0, 1, 5]].max(axis=(0, 1)) / peak

    assert error(ds.drift_force.values, lower).max() < 1e-6
    assert error(ds.drift_force.values, ~lower)[2] > 0.5
    kept, _ = mirror_headings(_half_plane(ds))
    assert error(kept.drift_force.values, slice(None)).max() < 1e-6
    # read by default, the struct's 190–350° are that mirror: VERES's own, everywhere
    default = _read(shared_data / "mss" / "supply" / "supply.mat")
    assert error(default.drift_force.values, slice(None)).max() < 1e-6
    assert "mirror image of the solver's 0–180°" in default.attrs["history"]
    assert not _parity_warnings(default)


def test_break_patterns_on_constructed_tables():
    """The patterns on a table built to have each (and a symmetric one none)."""
    beta = np.radians(np.arange(0, 360, 10))
    rng = np.random.default_rng(1)
    half = rng.normal(size=(5, 19))
    half[:, [0, 18]] = 0.0  # a sway-like DOF vanishes on the x axis
    mirror = np.concatenate([half, -half[:, 17:0:-1]], axis=1)  # F(−β) = −F(β)
    pairs = [p for p in mirror_pairs(beta) if p[0] != p[1]]
    kept = np.concatenate([half, half[:, 17:0:-1]], axis=1)
    shifted = np.concatenate([half, -half[:, 1:18]], axis=1)
    assert break_pattern(kept, beta, pairs, -1.0) == ("sign_kept", None)
    assert break_pattern(shifted, beta, pairs, -1.0) == ("shifted", None)
    assert break_pattern(mirror + 0.5 * rng.normal(size=mirror.shape), beta, pairs, -1.0) == (
        None,
        None,
    )
    sway = np.concatenate([half, -half[:, 17:0:-1]], axis=1)
    moment = kept + 3.0 * sway  # sign kept about x_P = 4 m, moved to x_O = 1 m
    assert break_pattern(moment, beta, pairs, -1.0, sway=sway, x_reference=1.0) == (
        "sign_kept_about",
        pytest.approx(4.0),
    )
    assert degree_ranges([190, 200, 210, 250, 300, 310]) == "190–210°, 250°, 300–310°"


def test_the_drift_loads_warn_about_a_drift_that_does_not_mirror(shared_data):
    """The mean drift as used in the time domain (the DP scenario's waves travel to 225°,
    in the half MSS fills): WaveDriftLoad warns, naming the DOFs and the headings, and
    not once the solvers' half-plane is kept (mirrored then by the load itself). At 225°
    (JONSWAP Hs 4 m, Tp 10.5 s) the tanker.mat drift's mean surge force is +3.3e5 N
    (forward), its mirror −4.2e5 N."""
    from cummins.errors import HydroDataWarning
    from cummins.seakeeping.waves import irregular_waves, wave_spectrum
    from cummins.timedomain.loads import WaveDriftLoad

    ds = _read(shared_data / "mss" / "tanker" / "tanker.mat", drift_as_stored=True)
    spectrum = wave_spectrum("jonswap", 4.0, 2 * np.pi / 0.6, gamma=3.3)
    sea = irregular_waves(spectrum, duration=300, n_components=50, direction=3.93, seed=1)
    with pytest.warns(HydroDataWarning, match=r"drift_force of Surge, Sway, Yaw .* at 190–"):
        WaveDriftLoad.from_hydrodb(ds, sea, extrapolate="zero")
    for fine in (_half_plane(ds), _read(shared_data / "mss" / "tanker" / "tanker.mat")):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            WaveDriftLoad.from_hydrodb(fine, sea, extrapolate="zero")
        assert not [w for w in caught if "mirror image" in str(w.message)]
    kept, _ = mirror_headings(_half_plane(ds))
    w = ds.omega.values
    sound = w < 3.5  # below the irregular frequencies
    density = np.asarray(spectrum(w[sound]))
    for heading in (220, 230):
        j = int(np.argmin(np.abs(np.degrees(ds.wave_direction.values) - heading)))
        mean = [  # 2 ∫ S(ω) D(ω) dω, surge
            2 * np.trapezoid(density * d.drift_force.values[sound, j, 0], w[sound])
            for d in (ds, kept)
        ]
        assert mean[0] > 1.5e5 and mean[1] < -2e5  # +3.3e5 N and −4.2e5 N
