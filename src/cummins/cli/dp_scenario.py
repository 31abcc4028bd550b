"""The dynamic-positioning scenario of Smogeli et al. (2004) §7 with the S-175 data of MSS.

The S-175 container ship (ShipX/VERES strip theory, processed by MSS; zero speed) holds
position by DP in short-crested waves — JONSWAP H_s 4 m, ω_p 0.60 rad/s, γ 3.3, mean
direction 45° off the (starboard) bow — when, at t = 100 s, a crane load of 1000 kN is
hung at r = [0, 15, 0] m (15 m to starboard of the origin, in the waterline). The paper
shows the first-order wave and radiation forces (its Fig. 3) and the pose (Fig. 4): "the
main effect is a new mean roll angle". The model is :mod:`cummins.timedomain.unified` (eq. 56) with
the loads of :mod:`cummins.timedomain.loads` — first-order waves at the instantaneous relative
heading, Newman drift, ITTC surge resistance and cross-flow drag (with an optional
current), optional wind with gusts, the crane load (its weight along the NED down axis)
— and the controller of :mod:`cummins.timedomain.dp` (nonlinear PID with a wave filter,
pseudo-inverse allocation to two bow tunnels and two stern azimuths).

Checks (:func:`scenario_checks`): the change of the mean roll after the load against the
static heel of the linearised restoring (heave, roll and pitch solved together:
G ξ = τ_crane), and the watch circle (largest horizontal distance from the setpoint).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

#: The paper's sea state and load.
HS, OMEGA_P, GAMMA = 4.0, 0.60, 3.3
WAVES_FROM_DEG = 45.0  # off the bow, starboard side
CRANE_LOAD, CRANE_POINT, CRANE_TIME = 1.0e6, (0.0, 15.0, 0.0), 100.0
#: The heel check averages the roll from HEEL_SETTLE s after the crane load, over at
#: least 60 s: runs not longer than HEEL_CHECK_DURATION have none.
HEEL_SETTLE = 100.0
HEEL_CHECK_DURATION = CRANE_TIME + HEEL_SETTLE + 60.0
#: cos-2s spreading exponent of the short-crested sea (the paper does not give it).
SPREADING = 5.0
#: Linear viscous damping of surge, sway and yaw, N s/m and N m s/rad: the lowest
#: frequency values of MSS's frequency-dependent ``Bv`` of this ship (rounded).
LOW_FREQUENCY_DAMPING = {"Surge": 2.3e4, "Sway": 1.7e4, "Yaw": 1.65e8}


@dataclass(frozen=True)
class Scenario:
    """What :func:`run_scenario` built and ran: the model, the loads, the controller."""

    model: object
    loads: tuple
    controller: object
    sea: object
    run: xr.Dataset


def s175_data(path: str | Path | None = None) -> xr.Dataset:
    """The S-175 at zero speed from MSS's ``s175.mat``: the copy bundled with cummins
    (MIT licence, ``cummins/data/s175``), or ``path`` (the file, or a folder holding
    ``mss/s175/s175.mat`` such as ``../shared/data``)."""
    from importlib import resources

    import cummins

    if path is None:
        file = Path(str(resources.files("cummins") / "data" / "s175" / "s175.mat"))
    else:
        file = Path(path)
        if file.is_dir():
            file = file / "mss" / "s175" / "s175.mat"
    if not file.is_file():
        from cummins.errors import HydroDataError

        raise HydroDataError("no S-175 data (s175.mat of MSS) there", path=file)
    return cummins.read(file).sel(forward_speed=0.0)


def scenario_data(
    path: str | Path | None = None,
    second_order: str = "newman",
    *,
    water_depth: float | None = None,
    main_dimensions: tuple[float, float, float] | None = None,
) -> tuple[xr.Dataset, dict[str, float]]:
    """The vessel of the scenario at zero speed and the linear viscous damping of its
    horizontal plane (N s/m, N m s/rad).

    ``path`` None, or a folder holding ``mss/s175/s175.mat``: the S-175
    (:func:`s175_data`) with :data:`LOW_FREQUENCY_DAMPING`. Any other file cummins reads
    (MSS, WAMIT, VERES …): its zero-speed data, checked by :func:`check_dp_data`, and the
    damping of :func:`data_viscous_damping`; ``water_depth`` (m) for files that do not
    record it (:func:`cummins.read`); ``main_dimensions`` (Lpp, B, T in m) for data that do
    not give them (WAMIT), replacing the data's.
    """
    import cummins
    from cummins.errors import HydroDataError

    if path is None or (Path(path).is_dir() and (Path(path) / "mss" / "s175").is_dir()):
        return s175_data(path), dict(LOW_FREQUENCY_DAMPING)
    ds = cummins.read(path, water_depth=water_depth)
    if "forward_speed" in ds.dims:
        speeds = np.asarray(ds.forward_speed.values, dtype=float)
        if not np.any(np.abs(speeds) < 1e-3):
            listed = ", ".join(f"{u:g}" for u in speeds)
            raise HydroDataError(
                f"DP needs the data at zero forward speed; they hold {listed} m/s", path=path
            )
        ds = ds.isel(forward_speed=int(np.argmin(np.abs(speeds))))
    elif "forward_speed" in ds.coords and abs(float(ds.forward_speed)) > 1e-3:
        raise HydroDataError(
            f"DP needs the data at zero forward speed; they hold {float(ds.forward_speed):g} m/s",
            path=path,
        )
    from cummins.cli.common import with_main_dimensions

    ds = with_main_dimensions(ds, main_dimensions)
    check_dp_data(ds, second_order)
    return ds, data_viscous_damping(ds)


def check_dp_data(ds: xr.Dataset, second_order: str = "newman") -> None:
    """Raise one HydroDataError naming all that the scenario needs and ``ds`` lacks: six
    DOFs, added mass and damping, the rigid-body mass and restoring, first-order wave
    excitation over headings, the mean drift (for ``second_order`` newman or mean) and
    the main dimensions (length, breadth, draught) the resistance, drag and thruster
    layout are scaled with."""
    from cummins.errors import HydroDataError
    from cummins.hydrodb import DOF_NAMES

    missing = []
    if [str(d) for d in ds.influenced_dof.values] != list(DOF_NAMES):
        missing.append("the six DOFs of one body")
    for name, what in (
        ("added_mass", "added mass"),
        ("radiation_damping", "radiation damping"),
        ("inertia_matrix", "rigid-body mass (inertia_matrix)"),
        ("hydrostatic_stiffness", "restoring (hydrostatic_stiffness)"),
        ("excitation_force", "first-order wave excitation"),
    ):
        if name not in ds or (name == "inertia_matrix" and not np.any(ds[name].values)):
            missing.append(what)
    if "excitation_force" in ds and "wave_direction" not in ds["excitation_force"].dims:
        missing.append("wave headings of the excitation")
    if second_order in ("newman", "mean") and "drift_force" not in ds:
        missing.append("mean drift forces (or --second-order none)")
    dims = [k for k in ("ship_length", "ship_breadth", "ship_draught") if k not in ds.attrs]
    if dims:
        missing.append("main dimensions (" + ", ".join(dims) + ")")
    if missing:
        raise HydroDataError(
            "the DP scenario needs " + "; ".join(missing),
            path=ds.attrs.get("source_file"),
            hint="an MSS vessel struct (.mat) holds all of it"
            + (
                "; give the main dimensions with --main-dimensions LPP B T (m; in Python "
                "the attributes ship_length, ship_breadth, ship_draught): WAMIT files, and "
                "the structs cummins writes from them, have none"
                if dims
                else ""
            ),
        )


def data_viscous_damping(ds: xr.Dataset) -> dict[str, float]:
    """Linear viscous damping of surge, sway and yaw: the data's ``additional_damping``
    (MSS's ``Bv``) at their lowest frequency, the value :func:`cummins.timedomain.lfmodel`
    takes with ``viscous={dof: 'data'}`` at ω = 0; DOFs without any are left out, with a
    warning (the quadratic drag and the controller then damp them alone)."""
    import warnings

    from cummins.errors import AssumptionWarning

    out: dict[str, float] = {}
    if "additional_damping" in ds:
        var = ds["additional_damping"].transpose(..., "influenced_dof", "radiating_dof")
        if "omega" in var.dims:
            var = var.isel(omega=int(np.argmin(ds.omega.values)))
        for dof in LOW_FREQUENCY_DAMPING:
            if dof in ds.influenced_dof.values:
                value = float(var.sel(influenced_dof=dof, radiating_dof=dof))
                if value > 0:
                    out[dof] = value
    lacking = [dof for dof in LOW_FREQUENCY_DAMPING if dof not in out]
    if lacking:
        warnings.warn(
            f"no linear viscous damping of {', '.join(lacking)} in the data (MSS's Bv): "
            "only the quadratic drag and the DP controller damp them",
            AssumptionWarning,
            stacklevel=2,
        )
    return out


def build_scenario(
    ds: xr.Dataset,
    *,
    duration: float = 600.0,
    seed: int = 1,
    n_components: int = 40,
    n_directions: int = 5,
    current_speed: float = 0.0,
    current_from_deg: float = 0.0,
    wind_speed: float = 0.0,
    wind_from_deg: float = 30.0,
    crane: bool = True,
    bandwidth: float = 0.1,
    filter_cutoff: float = 0.3,
    second_order: str = "newman",
    viscous_damping: dict[str, float] | None = None,
    keep_suspect: bool = False,
    yaw_setpoint: float = 0.0,
):
    """The unified model, loads and controller of the scenario (module docstring);
    ``bandwidth`` (rad/s) of the position loop and ``filter_cutoff`` (rad/s) of the
    wave filter (keep it ≈ 4 × the bandwidth and well below the waves' 0.6 rad/s);
    ``second_order``: the wave drift, ``"newman"`` (the paper's, at the instantaneous
    relative heading), ``"mean"`` (the data's mean drift at the instantaneous relative
    heading), ``"full"`` (a QTF of the data at the instantaneous relative heading:
    :class:`cummins.timedomain.loads.SecondOrderWaveLoad`, the S-175 of MSS has none) or
    ``"none"``; ``yaw_setpoint`` (rad): the DP set-point in yaw (the ship starts heading
    North, 0, and turns to it; the wave loads follow its relative heading);
    ``viscous_damping``: linear damping of surge, sway and yaw (default
    :data:`LOW_FREQUENCY_DAMPING`, the S-175's; :func:`scenario_data` gives another
    vessel's). Dimensions not in the data are the S-175's; the block coefficient is
    ∇/(L B T) when the displaced volume is known.

    Returns (model, loads, controller, sea).
    """
    import warnings

    from cummins.seakeeping import waves as wv
    from cummins.timedomain import loads as ld
    from cummins.timedomain.dp import DPController, DPGains, Thrusters, WaveFilter
    from cummins.timedomain.unified import unified_vessel

    length = float(ds.attrs.get("ship_length", 175.0))
    breadth = float(ds.attrs.get("ship_breadth", 25.4))
    draught = float(ds.attrs.get("ship_draught", 9.5))
    block = float(ds.attrs.get("block_coefficient", 0.572))
    if "block_coefficient" not in ds.attrs and "displaced_volume" in ds.attrs:
        block = float(ds.attrs["displaced_volume"]) / (length * breadth * draught)
    damping = LOW_FREQUENCY_DAMPING if viscous_damping is None else viscous_damping
    current = None
    if current_speed > 0:
        # "from" as sailors give it: the current flows to the opposite direction
        current = ld.Current(current_speed, np.radians(current_from_deg) + np.pi)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # MSS's frequency-dependent Bv: replaced below
        model = unified_vessel(ds, viscous_damping=damping, current=current)
    direction = np.radians(WAVES_FROM_DEG) + np.pi  # waves travel to 225°
    omega_max = float(ds.omega.values.max())
    sea = wv.irregular_waves(
        wv.wave_spectrum("jonswap", HS, 2 * np.pi / OMEGA_P, gamma=GAMMA),
        duration=duration,
        n_components=n_components,
        direction=direction,
        spreading=SPREADING,
        n_directions=n_directions,
        seed=seed,
        omega_max=omega_max,
    )
    loads = [
        ld.FirstOrderWaveLoad.from_hydrodb(ds, sea),
        *_drift_load(ds, sea, second_order, keep_suspect),
        ld.SurgeResistance.from_main_particulars(length, breadth, draught, block, current=current),
        ld.CrossFlowDrag.from_main_particulars(length, breadth, draught, current=current),
    ]
    if wind_speed > 0:
        loads.append(
            ld.WindLoad(
                wind=ld.Wind(wind_speed, np.radians(wind_from_deg)),
                frontal_area=breadth * 10.0,
                lateral_area=length * 10.0,
                length_overall=length * 1.05,
                point=np.array([0.0, 0.0, -8.0]),
            )
        )
    if crane:
        loads.append(
            ld.PointLoad(
                force_vector=np.array([0.0, 0.0, CRANE_LOAD]),
                point=np.array(CRANE_POINT),
                frame="ned",
                start=CRANE_TIME,
                name="crane",
            )
        )
    gains = DPGains.from_vessel(model.mass, model.damping, bandwidth=bandwidth)
    thrusters = Thrusters.typical(length, max_thrust=1.0e6, beam=breadth)
    controller = DPController(
        gains,
        thrusters,
        wave_filter=WaveFilter(cutoff=filter_cutoff),
        setpoint=(0.0, 0.0, float(yaw_setpoint)),
    )
    return model, tuple(loads), controller, sea


def _drift_load(ds, sea, second_order: str, keep_suspect: bool = False) -> list:
    """The wave-drift load of ``--second-order`` (none: no load); the mean drift at the
    suspect frequencies of the data left out unless ``keep_suspect``."""
    from cummins.timedomain import loads as ld

    if second_order == "none":
        return []
    if second_order == "full":  # at the instantaneous relative heading, as the others
        return [
            ld.SecondOrderWaveLoad.from_hydrodb(
                ds, sea, model="full", name="wave drift", keep_suspect=keep_suspect
            )
        ]
    slowly = second_order == "newman"
    return [
        ld.WaveDriftLoad.from_hydrodb(
            ds, sea, extrapolate="zero", slowly_varying=slowly, keep_suspect=keep_suspect
        )
    ]


def run_scenario(
    ds: xr.Dataset | None = None,
    *,
    duration: float = 600.0,
    dt: float = 0.2,
    seed: int = 1,
    progress: Callable[[float], None] | None = None,
    **options,
) -> Scenario:
    """Build (:func:`build_scenario`) and simulate the scenario for ``duration`` s."""
    from cummins.validation import check_simulation_size

    check_simulation_size(duration, dt, 60, 54)  # before the model is built (~60 states)
    ds = s175_data() if ds is None else ds
    model, loads, controller, sea = build_scenario(ds, duration=duration, seed=seed, **options)
    run = simulate_scenario(model, loads, controller, duration=duration, dt=dt, progress=progress)
    run["wave_elevation"] = ("time", sea.elevation(run.time.values), {"units": "m"})
    run.attrs.update(
        {
            "scenario": "Smogeli et al. (2004) section 7: S-175 under DP, crane load 1000 kN "
            "at t = 100 s",
            "hs": HS,
            "omega_p": OMEGA_P,
            "gamma": GAMMA,
            "waves_from_deg_off_bow": WAVES_FROM_DEG,
            "yaw_setpoint_deg": float(np.degrees(options.get("yaw_setpoint", 0.0))),
            "seed": seed,
        }
    )
    run.attrs.update({f"check_{k}": v for k, v in scenario_checks(run, model).items()})
    return Scenario(model, loads, controller, sea, run)


def simulate_scenario(
    model, loads, controller, *, duration: float, dt: float, progress=None
) -> xr.Dataset:
    """Run the loads of :func:`build_scenario`: the first-order wave force at every
    Runge–Kutta stage, the slow loads (drift, drag, wind, crane) once a step."""
    from cummins.timedomain.unified import simulate_unified

    return simulate_unified(
        model,
        duration=duration,
        dt=dt,
        loads=loads[:1],
        slow_loads=loads[1:],
        controller=controller,
        progress=progress,
    )


def static_heel(model, force: np.ndarray) -> np.ndarray:
    """(heave, roll, pitch) of the linearised static equilibrium G ξ = τ (m, rad, rad)."""
    idx = [2, 3, 4]
    return np.linalg.solve(model.restoring[np.ix_(idx, idx)], np.asarray(force)[idx])


def scenario_checks(run: xr.Dataset, model, *, settle: float = HEEL_SETTLE) -> dict[str, float]:
    """Mean roll before the crane load and after it has settled (``settle`` s later),
    the static heel it should give, and the watch circle (m)."""
    t = run.time.values
    roll = run.eta.sel(dof="Roll").values
    out = {
        "watch_circle_m": float(np.hypot(run.eta.sel(dof="North"), run.eta.sel(dof="East")).max()),
        "max_yaw_deg": float(np.degrees(np.abs(run.eta.sel(dof="Yaw")).max())),
    }
    if "force_crane" in run and t[-1] > CRANE_TIME + settle + 60.0:
        before = (t > 30) & (t < CRANE_TIME)
        after = t > CRANE_TIME + settle
        crane = run.force_crane.values[after].mean(axis=0)
        heel = static_heel(model, crane)
        out.update(
            {
                "mean_roll_before_deg": float(np.degrees(roll[before].mean())),
                "mean_roll_after_deg": float(np.degrees(roll[after].mean())),
                "static_heel_deg": float(np.degrees(heel[1])),
            }
        )
        change = out["mean_roll_after_deg"] - out["mean_roll_before_deg"]
        out["heel_error"] = float(change / out["static_heel_deg"] - 1.0)
    return out


def write_scenario_plots(scenario: Scenario, folder: Path, *, force: bool = False) -> list[Path]:
    """pose.png (seed Fig. 4), wave_and_radiation_forces.png (Fig. 3), loads.png (the
    other loads and the thrust), watch_circle.png."""
    from cummins.plots import (
        plot_generalized_forces,
        plot_pose,
        plot_watch_circle,
        save_figure,
    )

    run = scenario.run
    forces = [name for name in run.data_vars if name.startswith("force_")]
    first = next((n for n in forces if "first-order" in n), forces[0])
    slow = [n for n in forces if n != first]  # the first-order force would hide them
    files = [
        save_figure(plot_pose(run, mark=CRANE_TIME), folder / "pose.png", force=force),
        save_figure(
            plot_generalized_forces(
                run,
                [first, "memory_force"],
                labels=["first-order wave force τ_W1", "fluid memory force μ"],
            ),
            folder / "wave_and_radiation_forces.png",
            force=force,
        ),
        save_figure(
            plot_generalized_forces(
                run, [*slow, "thrust"], labels=[n[6:] for n in slow] + ["thrust (DP)"]
            ),
            folder / "loads.png",
            force=force,
        ),
        save_figure(plot_watch_circle(run), folder / "watch_circle.png", force=force),
    ]
    return files
