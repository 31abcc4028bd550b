"""Generate ``semisub_capytaine.nc``: a full-scale semisubmersible computed with Capytaine.

An OC4-DeepCwind-like floater as one rigid body (6 DOFs): three offset columns of radius
6 m and 14 m draft at 28.9 m from the centre, each on a base column of radius 12 m from
z = −14 m to z = −20 m, and a central column of radius 3.25 m and 20 m draft; no pontoons
or braces. Mass = displaced mass (ρ = 1025 kg/m³, g = 9.81 m/s²), centre of mass at
z = −10 m (GM 7.5 m in roll and pitch), the inertia of a uniform solid filling the hull.
Heave resonance at 0.36 rad/s, roll and pitch at 0.29 rad/s, where the radiation damping
is nearly zero: the case the motion-weighted identification is for (issue 16's
semisubmersible). No mooring: surge, sway and yaw have no restoring.

Capytaine direct BIE method with the finer Delhommeau tabulation of
``make_float_spar.py``, 3-fold rotation symmetry (1752 hull panels), a lid on each
waterplane (irregular-frequency removal), 59 frequencies (24 log-spaced from 0.05 to
0.5 rad/s, then linear to 3 rad/s), the ω = 0 and ω = ∞ added mass, headings 0, 45, 90,
135 and 180°, infinite depth. B₃₃ falls steeply between 1.30 and 1.40 rad/s (the columns'
interaction, the same with and without lid on a grid of 0.05 rad/s): ``cummins check``
calls 1.21–1.36 rad/s suspect; it is physics, coarsely sampled.

The test suite uses ``tests/data/semisub_capytaine.nc``, made with Capytaine 3.0.0
(about 1 minute on one core) by::

    OMP_NUM_THREADS=1 python tests/data/make_semisub.py tests/data/semisub_capytaine.nc
"""

import argparse
import sys
import time
from pathlib import Path

import capytaine as cpt
import numpy as np
import xarray as xr
from capytaine.io.xarray import VARIABLES_ATTRIBUTES
from capytaine.meshes.meshes import Mesh
from capytaine.meshes.symmetric_meshes import RotationSymmetricMesh

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_float_spar import (
    RHO,
    G,
    cosine_spacing,
    direct_solver,
    make_body,
    polyline,
    without_round_off,
)

Z_G = -10.0
OFFSET = 28.9  # m, centre to offset column axis
OMEGA = np.concatenate([np.geomspace(0.05, 0.5, 24), np.linspace(0.5, 3.0, 36)[1:]])
HEADINGS_DEG = [0.0, 45.0, 90.0, 135.0, 180.0]


def revolve_sector(profile_rz, th0, th1, n, axis_xy=(0.0, 0.0), name=None):
    """Surface of revolution of the (r, z) profile about the vertical axis through
    ``axis_xy`` for θ in [th0, th1], n strips; the normal points outwards when the profile
    is walked with the body on its left."""
    ths = np.linspace(th0, th1, n + 1)
    m = len(profile_rz)
    cx, cy = axis_xy
    r, z = profile_rz[:, 0], profile_rz[:, 1]
    vertices = np.concatenate(
        [np.column_stack([cx + r * np.cos(t), cy + r * np.sin(t), z]) for t in ths]
    )
    faces = np.array(
        [
            (i + j * m, i + (j + 1) * m, i + 1 + (j + 1) * m, i + 1 + j * m)
            for j in range(n)
            for i in range(m - 1)
        ]
    )
    return Mesh(vertices=vertices, faces=faces, name=name)


def build():
    """Hull and lid: one wedge (an offset column and a 120° sector of the central column)
    repeated three times about the vertical axis."""
    offset_profile = polyline(
        [(0.0, -20.0), (12.0, -20.0), (12.0, -14.0), (6.0, -14.0), (6.0, 0.0)],
        [5, 3, 3, cosine_spacing(7)],
    )
    column = revolve_sector(offset_profile, 0.0, 2 * np.pi, 28, axis_xy=(OFFSET, 0.0))
    centre_profile = polyline([(0.0, -20.0), (3.25, -20.0), (3.25, 0.0)], [2, cosine_spacing(8)])
    centre = revolve_sector(centre_profile, -np.pi / 3, np.pi / 3, 8)
    hull = RotationSymmetricMesh(wedge=Mesh.join_meshes(column, centre), n=3, name="semisub")
    column_lid = revolve_sector(
        polyline([(6.0, 0.0), (0.0, 0.0)], [3]), 0.0, 2 * np.pi, 28, axis_xy=(OFFSET, 0.0)
    )
    centre_lid = revolve_sector(polyline([(3.25, 0.0), (0.0, 0.0)], [2]), -np.pi / 3, np.pi / 3, 8)
    lid = RotationSymmetricMesh(
        wedge=Mesh.join_meshes(column_lid, centre_lid), n=3, name="semisub_lid"
    )
    return hull, lid


def with_hydrostatics(ds, plain_body):
    """What ``fill_dataset(hydrostatics=True)`` adds, computed on the body with plain
    meshes: Capytaine 3.0.0 fails on a RotationSymmetricMesh there (``Multibody([body])``
    joins no other mesh and calls ``set.intersection()`` without argument)."""
    dofs = ds.coords["radiating_dof"].values.astype(str)
    hydrostatics = cpt.compute_hydrostatics_dataset(
        plain_body, rho=ds.coords["rho"].values, g=ds.coords["g"].values, only_dofs=dofs
    )
    hydrostatics = hydrostatics.assign_coords(
        radiating_dof=ds.coords["radiating_dof"].to_index(),
        influenced_dof=ds.coords["influenced_dof"].to_index(),
    )
    out = xr.merge([ds, hydrostatics], compat="no_conflicts", join="outer")
    for var in set(out) | set(out.coords):
        if var in VARIABLES_ATTRIBUTES:
            out[var].attrs.update(VARIABLES_ATTRIBUTES[var])
    out.attrs.update(ds.attrs)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="semisub_capytaine.nc", help="output NetCDF")
    args = parser.parse_args()
    hull, lid = build()
    body = make_body(hull, lid, "semisub", Z_G)
    plain = make_body(hull.merged(), lid.merged(), "semisub", Z_G)
    k = body.hydrostatic_stiffness.values
    print(
        f"hull panels {body.mesh.nb_faces} lid panels {body.lid_mesh.nb_faces}"
        f" volume {body.volume:.1f} m3 mass {body.mass / 1e3:.1f} t"
        f" GM roll {k[3, 3] / (RHO * G * body.volume):.2f} m"
    )
    solver = direct_solver()
    common = {"radiating_dof": list(body.dofs), "water_depth": [np.inf], "rho": [RHO], "g": [G]}
    start = time.perf_counter()
    waves = xr.Dataset(
        coords={"omega": OMEGA, "wave_direction": np.deg2rad(HEADINGS_DEG), **common}
    )
    limits = xr.Dataset(coords={"omega": [0.0, np.inf], **common})
    ds, ds_limits = (
        with_hydrostatics(
            solver.fill_dataset(problems, body, hydrostatics=False, progress_bar=False), plain
        )
        for problems in (waves, limits)
    )
    ds = xr.merge([ds, ds_limits], compat="no_conflicts", join="outer")
    cpt.io.xarray.save_dataset_as_netcdf(args.out, without_round_off(ds))
    print(f"wrote {args.out} in {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
