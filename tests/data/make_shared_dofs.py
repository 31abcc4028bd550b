"""Generate ``shared_dofs_capytaine.nc``: a two-body WEC whose DOFs are those of a
WecOptTool model, computed with Capytaine: ``float__Heave``, ``spar__Heave``, ``Surge``,
``Pitch``.

The float and spar of ``make_float_spar.py`` (solid float disc of radius 10 m, 3 m
draft; fully submerged spar with a heave plate), coarser (16 sectors, no rotation
symmetry), as one Capytaine body whose four DOFs are motion fields on its panels: the
heave of the float alone, the heave of the spar alone, and the surge and the pitch about
the origin of both together (the two bodies move as one in surge and pitch, as when they
are joined by a heave slider). The labels name a body for two DOFs and none for the
others, as WecOptTool writes them. The inertia and restoring of the four DOFs are
Tᵀ M T and Tᵀ C T of the two bodies' 6 × 6 rigid-body matrices (each about its centre of
gravity, masses = displaced masses, ρ = 1025 kg/m³, g = 9.81 m/s²), with T the
kinematics above: a body's surge is q_surge + z_G θ, its heave q_heave, its pitch θ.

Capytaine direct BIE method, a lid on the float's waterplane, 20 frequencies from 0.2 to
2.1 rad/s, the ω = 0 and ω = ∞ added mass, headings 0 and 30°, infinite depth.

The test suite uses ``tests/data/shared_dofs_capytaine.nc``, made with Capytaine 3.0.0
(under a minute on one core) by::

    OMP_NUM_THREADS=1 python tests/data/make_shared_dofs.py tests/data/shared_dofs_capytaine.nc
"""

import argparse
import sys
import time
from pathlib import Path

import capytaine as cpt
import numpy as np
import xarray as xr

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_float_spar import RHO, G, build, make_body, without_round_off

NTHETA = 16
DOFS = ["float__Heave", "spar__Heave", "Surge", "Pitch"]
Z_G = {"float": -0.7, "spar": -24.0}
OMEGA = np.round(np.linspace(0.2, 2.1, 20), 10)
HEADINGS_DEG = [0.0, 30.0]


def kinematics():
    """T (12 × 4): each body's rigid-body motion (Surge … Yaw about its centre of gravity,
    float then spar) from the four DOFs."""
    t = np.zeros((12, 4))
    for k, body in enumerate(("float", "spar")):
        t[6 * k + 2, k] = 1.0  # its own heave
        t[6 * k + 0, 2] = 1.0  # surge of both
        t[6 * k + 4, 3] = 1.0  # pitch of both, about the origin:
        t[6 * k + 0, 3] = Z_G[body]  # its centre of gravity moves by z_G θ in x
    return t


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="shared_dofs_capytaine.nc")
    args = parser.parse_args()
    float_mesh, float_lid, spar_mesh, _ = build(NTHETA)
    float_mesh, float_lid, spar_mesh = (m.merged() for m in (float_mesh, float_lid, spar_mesh))
    bodies = [make_body(float_mesh, None, "float", Z_G["float"])]
    bodies.append(make_body(spar_mesh, None, "spar", Z_G["spar"]))
    mesh = cpt.Mesh.join_meshes(float_mesh, spar_mesh, name="float_spar")
    n_float = float_mesh.nb_faces
    centers = mesh.faces_centers
    on_float = np.arange(mesh.nb_faces) < n_float
    dofs = {
        "float__Heave": np.where(on_float[:, None], [0.0, 0.0, 1.0], 0.0),
        "spar__Heave": np.where(on_float[:, None], 0.0, [0.0, 0.0, 1.0]),
        "Surge": np.tile([1.0, 0.0, 0.0], (mesh.nb_faces, 1)),
        "Pitch": np.column_stack(
            [centers[:, 2], np.zeros(mesh.nb_faces), -centers[:, 0]]
        ),  # θ e_y × r
    }
    body = cpt.FloatingBody(mesh=mesh, lid_mesh=float_lid, dofs=dofs, name="float_spar")
    t = kinematics()
    m12 = np.zeros((12, 12))
    c12 = np.zeros((12, 12))
    for k, part in enumerate(bodies):
        m12[6 * k : 6 * k + 6, 6 * k : 6 * k + 6] = part.inertia_matrix.values
        c12[6 * k : 6 * k + 6, 6 * k : 6 * k + 6] = part.hydrostatic_stiffness.values
    print(f"panels {mesh.nb_faces} (float {n_float}), lid {float_lid.nb_faces}")
    solver = cpt.BEMSolver(method="direct")
    common = {"radiating_dof": DOFS, "water_depth": [np.inf], "rho": [RHO], "g": [G]}
    start = time.perf_counter()
    waves = xr.Dataset(
        coords={"omega": OMEGA, "wave_direction": np.deg2rad(HEADINGS_DEG), **common}
    )
    limits = xr.Dataset(coords={"omega": [0.0, np.inf], **common})
    ds = xr.merge(
        [
            solver.fill_dataset(problems, body, hydrostatics=False, progress_bar=False)
            for problems in (waves, limits)
        ],
        compat="no_conflicts",
        join="outer",
    )
    matrix = {"influenced_dof": DOFS, "radiating_dof": DOFS}
    ds["inertia_matrix"] = xr.DataArray(t.T @ m12 @ t, coords=matrix, dims=list(matrix))
    ds["hydrostatic_stiffness"] = xr.DataArray(t.T @ c12 @ t, coords=matrix, dims=list(matrix))
    ds.attrs["description"] = (
        "float and spar with the DOFs float__Heave, spar__Heave, Surge, Pitch (about the "
        "origin), made by tests/data/make_shared_dofs.py of cummins"
    )
    cpt.io.xarray.save_dataset_as_netcdf(args.out, without_round_off(ds))
    print(f"wrote {args.out} in {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
