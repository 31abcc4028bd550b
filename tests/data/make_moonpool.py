"""Generate ``moonpool_capytaine.nc``: a floating ring (a cylinder with a moonpool) computed
with Capytaine, whose heave data hold the moonpool's piston resonance.

A thin-walled annular cylinder: inner radius (the moonpool's) 3.5 m, outer radius 4.5 m,
1.5 m draft, flat bottom, freely floating, heave only. Mass = displaced mass
(ρ = 1025 kg/m³, g = 9.81 m/s²), centre of mass at half the draft. The water column in
the moonpool resonates as a piston near 1.7 rad/s (about 10 % of critical damping):
B₃₃ peaks there (its largest value) and A₃₃ goes negative above it; on the user's grid
of 0.12 rad/s the spike test flags its two points at 1.64 and 1.76 rad/s, as the HAMS
moonpool run of issue 30 was flagged. The heave motions depend on it (bridged over,
they move by 38 % of their peak), so ``cummins check`` names it ("a piston/gap
resonance at 1.64–1.76 rad/s in Heave … kept") and the fit keeps it. The first
axisymmetric sloshing mode of the moonpool (k·a = 3.83, about 3.3 rad/s) lies above the
frequencies computed.

Capytaine direct BIE method with the default Delhommeau tabulation (the ring lies near
the surface), 24 × 14 hull panels (rotation symmetry) and a lid on the annular
waterplane (irregular-frequency removal; the moonpool's free surface is water, not
lidded), 24 frequencies from 0.2 to 2.96 rad/s every 0.12 rad/s, the ω = 0 and ω = ∞
added mass, headings 0 and 45°, infinite depth.

The test suite uses ``tests/data/moonpool_capytaine.nc``, made with Capytaine 3.0.0
(a few seconds on one core) by::

    OMP_NUM_THREADS=1 python tests/data/make_moonpool.py tests/data/moonpool_capytaine.nc

``--inner 3 --outer 5 --draft 1 --step 0.1`` makes a sharper piston (5 % of critical,
four points flagged at 1.7–2.0 rad/s) than the identification's poles may follow
(:data:`cummins.radiation.fit.vector.MIN_DAMPING`).
"""

import argparse
import sys
import time
from pathlib import Path

import capytaine as cpt
import numpy as np
import xarray as xr

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_float_spar import RHO, G, cosine_spacing, make_body, polyline, revolve, without_round_off
from make_semisub import with_hydrostatics

NTHETA = 24
DOFS = ["Heave"]
HEADINGS_DEG = [0.0, 45.0]


def build(inner, outer, draft):
    """Hull (inner wall down, bottom outwards, outer wall up: the body on the left, the
    normals outwards) and the lid of its annular waterplane."""
    profile = polyline(
        [(inner, 0.0), (inner, -draft), (outer, -draft), (outer, 0.0)],
        [cosine_spacing(5, fine_at_end=False), 4, cosine_spacing(5)],
    )
    hull = revolve(profile, NTHETA, "ring")
    lid = revolve(polyline([(outer, 0.0), (inner, 0.0)], [3]), NTHETA, "ring_lid")
    return hull, lid


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="moonpool_capytaine.nc", help="output NetCDF")
    parser.add_argument("--inner", type=float, default=3.5, help="moonpool radius, m")
    parser.add_argument("--outer", type=float, default=4.5, help="outer radius, m")
    parser.add_argument("--draft", type=float, default=1.5, help="draft, m")
    parser.add_argument("--step", type=float, default=0.12, help="frequency step, rad/s")
    args = parser.parse_args()
    hull, lid = build(args.inner, args.outer, args.draft)
    z_g = -args.draft / 2
    body = make_body(hull, lid, "ring", z_g).with_only_dofs(DOFS)
    plain = make_body(hull.merged(), lid.merged(), "ring", z_g).with_only_dofs(DOFS)
    print(
        f"hull panels {body.mesh.nb_faces} lid panels {body.lid_mesh.nb_faces}"
        f" volume {body.volume:.2f} m3 mass {body.mass / 1e3:.2f} t"
    )
    solver = cpt.BEMSolver(method="direct")
    common = {"radiating_dof": DOFS, "water_depth": [np.inf], "rho": [RHO], "g": [G]}
    omega = np.round(np.arange(0.2, 3.0, args.step), 10)
    start = time.perf_counter()
    waves = xr.Dataset(
        coords={"omega": omega, "wave_direction": np.deg2rad(HEADINGS_DEG), **common}
    )
    limits = xr.Dataset(coords={"omega": [0.0, np.inf], **common})
    ds, ds_limits = (
        with_hydrostatics(
            solver.fill_dataset(problems, body, hydrostatics=False, progress_bar=False), plain
        )
        for problems in (waves, limits)
    )
    ds = xr.merge([ds, ds_limits], compat="no_conflicts", join="outer")
    ds.attrs["description"] = (
        f"floating ring with a moonpool (r {args.inner:g}-{args.outer:g} m, {args.draft:g} m "
        "draft), made by tests/data/make_moonpool.py of cummins"
    )
    cpt.io.xarray.save_dataset_as_netcdf(args.out, without_round_off(ds))
    print(f"wrote {args.out} in {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
