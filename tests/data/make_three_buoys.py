"""Generate ``three_buoys_capytaine.nc``: a row of three identical buoys computed with Capytaine.

Three truncated vertical cylinders (radius 4 m, draft 6 m, flat bottom) with their axes at
x = −15, 0 and 15 m, as one multibody problem: 18 DOFs, 6 rigid-body DOFs per body. Each
buoy's mass is its displaced mass (ρ = 1025 kg/m³, g = 9.81 m/s²), its centre of mass at
z = −3 m (GM 0.65 m; at z = −2 m it would be unstable in roll and pitch), its inertia that
of a uniform solid filling the hull. The outer buoys are mirror images of each other, so
their diagonal added mass and damping are equal; the waves between the buoys (kd = π at
1.43 rad/s) put bumps in the surge and pitch damping.

Capytaine direct BIE method with the finer Delhommeau tabulation of
``make_float_spar.py``, 360 hull and 120 lid panels per buoy (a lid on each waterplane:
without it the first irregular frequency, 2.43 rad/s, falls in the range), 45 frequencies
from 0.1 to 3 rad/s, the ω = 0 and ω = ∞ added mass, headings 0, 45 and 90°, infinite
depth. The data end before the surge damping has decayed (A₁₁ at 3 rad/s is 62 % of its
ω = ∞ value), so A∞ from the finite frequencies is not a fair test here.

The test suite uses ``tests/data/three_buoys_capytaine.nc``, made with Capytaine 3.0.0
(about 45 s on one core) by::

    OMP_NUM_THREADS=1 python tests/data/make_three_buoys.py tests/data/three_buoys_capytaine.nc
"""

import argparse
import sys
import time
from pathlib import Path

import capytaine as cpt
import numpy as np
import xarray as xr

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_float_spar import (
    RHO,
    G,
    cosine_spacing,
    direct_solver,
    make_body,
    polyline,
    revolve,
    without_round_off,
)

RADIUS, DRAFT, Z_G = 4.0, 6.0, -3.0
POSITIONS = {"b1": -15.0, "b2": 0.0, "b3": 15.0}  # buoy axes, x in m
NTHETA = 24


def buoy(name, x0):
    """One buoy at (x0, 0): plain meshes (an off-axis buoy has no rotation symmetry)."""
    profile = polyline([(0.0, -DRAFT), (RADIUS, -DRAFT), (RADIUS, 0.0)], [5, cosine_spacing(10)])
    hull = revolve(profile, NTHETA, name).merged().translated((x0, 0.0, 0.0), name=name)
    lid = revolve(polyline([(RADIUS, 0.0), (0.0, 0.0)], [5]), NTHETA, f"{name}_lid")
    lid = lid.merged().translated((x0, 0.0, 0.0), name=f"{name}_lid")
    return make_body(hull, lid, name, Z_G, x=x0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="three_buoys_capytaine.nc", help="output NetCDF")
    args = parser.parse_args()
    buoys = [buoy(name, x0) for name, x0 in POSITIONS.items()]
    for b in buoys:
        gm = float(b.hydrostatic_stiffness.values[3, 3]) / (RHO * G * b.volume)
        print(
            f"{b.name}: {b.mesh.nb_faces} hull panels, {b.lid_mesh.nb_faces} lid panels, "
            f"GM {gm:.3f} m"
        )
    body = buoys[0] + buoys[1] + buoys[2]  # every buoy has a lid: the plain sum works
    solver = direct_solver()
    common = {"radiating_dof": list(body.dofs), "water_depth": [np.inf], "rho": [RHO], "g": [G]}
    start = time.perf_counter()
    waves = xr.Dataset(
        coords={
            "omega": np.linspace(0.1, 3.0, 45),
            "wave_direction": np.deg2rad([0.0, 45.0, 90.0]),
            **common,
        }
    )
    limits = xr.Dataset(coords={"omega": [0.0, np.inf], **common})
    ds = xr.merge(
        [solver.fill_dataset(problems, body, progress_bar=False) for problems in (waves, limits)],
        compat="no_conflicts",
        join="outer",
    )
    cpt.io.xarray.save_dataset_as_netcdf(args.out, without_round_off(ds))
    print(f"wrote {args.out} in {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
