"""Generate ``sphere_drift_capytaine.nc``: a floating hemisphere with Capytaine's far-field
mean drift, the body of the corpus's WAMIT mean-drift sphere.

The corpus case ``WEC-Sim_Applications/wamit_mean_drift_sphere`` (WAMIT 7.311) is a
sphere of radius 1 m floating with its centre in the free surface (a hemisphere below
it), deep water, mass ρ∇, centre of gravity at the origin and radii of gyration 0.4 m
(its ``sphere.frc``). The same body here, computed with Capytaine 3.0 — radiation and
diffraction with their Kochin functions on 0–2π, the motion RAOs of Capytaine
(``capytaine.post_pro.rao``) and the far-field mean drift
``capytaine.post_pro.far_field_mean_drift_force`` (surge, sway, yaw; momentum
conservation, as WAMIT's ``.8``) — 12 frequencies 1–5 rad/s (the hemisphere's first
irregular frequency is above them), one heading (0°), ρ = 1025 kg/m³ and g = 9.80665 m/s²
(the WAMIT run's), a mesh of 30 x 60 panels on the sphere. The drift variables are stored
as Capytaine computes them (dims omega, wave_direction_k, wave_direction_l; complex values split
along ``complex`` by Capytaine's own NetCDF export, ``capytaine.export_dataset``).

The test suite uses ``tests/data/sphere_drift_capytaine.nc``, made with Capytaine 3.0.0 by::

    python tests/data/make_drift_sphere.py tests/data/sphere_drift_capytaine.nc
"""

import sys

import capytaine as cpt
import numpy as np
import xarray as xr
from capytaine.post_pro import far_field_mean_drift_force, rao

RHO, G = 1025.0, 9.80665
RADIUS, GYRATION = 1.0, 0.4


def main(out: str = "sphere_drift_capytaine.nc") -> None:
    mesh = cpt.mesh_sphere(radius=RADIUS, center=(0, 0, 0), resolution=(30, 60)).immersed_part()
    body = cpt.FloatingBody(
        mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)), center_of_mass=(0, 0, 0)
    )
    volume = 2.0 / 3.0 * np.pi * RADIUS**3
    mass = RHO * volume
    inertia = np.diag([mass, mass, mass, *(3 * [mass * GYRATION**2])])
    body.inertia_matrix = body.add_dofs_labels_to_matrix(inertia)
    body.hydrostatic_stiffness = body.compute_hydrostatic_stiffness(rho=RHO, g=G)
    omega = np.linspace(1.0, 5.0, 12)
    theta = np.linspace(-0.5, 2 * np.pi + 0.5, 121)
    test = xr.Dataset(
        coords={
            "omega": omega,
            "wave_direction": [0.0],
            "radiating_dof": list(body.dofs),
            "water_depth": [np.inf],
            "rho": [RHO],
            "g": [G],
            "theta": theta,
        }
    )
    ds = cpt.BEMSolver().fill_dataset(test, body)
    motions = rao(ds)
    drift = far_field_mean_drift_force(motions, ds)
    ds = ds.drop_vars(["kochin_radiation", "kochin_diffraction"])
    ds = xr.merge([ds, drift.drop_vars([c for c in drift.coords if c not in drift.dims])])
    ds = ds.drop_vars("theta", errors="ignore")
    cpt.export_dataset(out, ds, format="netcdf")


if __name__ == "__main__":
    main(*sys.argv[1:2])
