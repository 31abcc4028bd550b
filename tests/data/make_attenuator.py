"""Generate ``attenuator_capytaine.nc``: three floating boxes in a row (an attenuator such
as M4 or Pelamis) computed with Capytaine.

Three boxes 10 m long (x), 4 m wide, 2 m draft, their centres at x = −11, 0 and 11 m
(gaps of 1 m), as one multibody problem: 18 DOFs, 6 rigid-body DOFs per body, each about
its centre of mass at z = −1 m. Each box's mass is its displaced mass (ρ = 1025 kg/m³,
g = 9.81 m/s²), its inertia that of a uniform solid filling the wetted box (GM in roll
0.67 m). The tests hinge the outer boxes to the middle one about y at (±5.5, 0, −1) with
rotational PTOs (``tests/test_wec_attenuator.py``).

Capytaine direct BIE method (the default Delhommeau tabulation), 162 hull panels per box
(no lid: the boxes' first irregular frequency, about 3 rad/s, is at the end of the range),
30 frequencies from 0.1 to 3 rad/s, the ω = 0 and ω = ∞ added mass, headings 0, 45 and
90°, infinite depth. The 1 m gaps put a piston resonance in the middle box's surge at
2.4–3 rad/s (the fit leaves it out and says so).

The test suite uses ``tests/data/attenuator_capytaine.nc``, made with Capytaine 3.0.0
(about 10 s on one core) by::

    OMP_NUM_THREADS=1 python tests/data/make_attenuator.py tests/data/attenuator_capytaine.nc
"""

import argparse
import sys
import time
from pathlib import Path

import capytaine as cpt
import numpy as np
import xarray as xr

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_float_spar import RHO, G, without_round_off

LENGTH, WIDTH, DRAFT = 10.0, 4.0, 2.0
POSITIONS = {"fore": -11.0, "mid": 0.0, "aft": 11.0}  # box centres, x in m


def box(name, x0):
    """A floating box at (x0, 0), open at the waterline, rotating about its centre of mass
    (the centre of the wetted box), with the inertia of a uniform solid filling it."""
    mesh = cpt.mesh_parallelepiped(
        size=(LENGTH, WIDTH, DRAFT),
        center=(x0, 0.0, -DRAFT / 2),
        resolution=(12, 5, 3),
        missing_sides={"top"},
        name=name,
    )
    body = cpt.FloatingBody(mesh=mesh, name=name, center_of_mass=(x0, 0.0, -DRAFT / 2))
    body.add_all_rigid_body_dofs()
    mass = RHO * body.volume
    a, b, c = LENGTH, WIDTH, DRAFT
    inertia = np.zeros((6, 6))
    inertia[:3, :3] = mass * np.eye(3)
    inertia[3:, 3:] = np.diag(mass / 12 * np.array([b**2 + c**2, a**2 + c**2, a**2 + b**2]))
    body.mass = mass
    body.inertia_matrix = body.add_dofs_labels_to_matrix(inertia)
    body.hydrostatic_stiffness = body.compute_hydrostatic_stiffness(rho=RHO, g=G)
    return body


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="attenuator_capytaine.nc", help="output NetCDF")
    args = parser.parse_args()
    boxes = [box(name, x0) for name, x0 in POSITIONS.items()]
    body = boxes[0] + boxes[1] + boxes[2]
    solver = cpt.BEMSolver(method="direct")
    common = {"radiating_dof": list(body.dofs), "water_depth": [np.inf], "rho": [RHO], "g": [G]}
    start = time.perf_counter()
    waves = xr.Dataset(
        coords={
            "omega": np.linspace(0.1, 3.0, 30),
            "wave_direction": np.deg2rad([0.0, 45.0, 90.0]),
            **common,
        }
    )
    limits = xr.Dataset(coords={"omega": [0.0, np.inf], **common})
    ds = xr.merge(
        [
            solver.fill_dataset(problems, body, hydrostatics=True, progress_bar=False)
            for problems in (waves, limits)
        ],
        compat="no_conflicts",
        join="outer",
    )
    cpt.io.xarray.save_dataset_as_netcdf(args.out, without_round_off(ds))
    print(f"wrote {args.out} in {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
