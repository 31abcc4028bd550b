"""Generate ``float_spar_capytaine.nc``: a two-body RM3-like WEC database computed with Capytaine.

Bodies (both axisymmetric, 6 rigid-body DOFs each, 12 DOFs in total):

* float: solid disc of radius 10 m, 3 m draft, vertical wall from z=0 to z=-2 m, conical bottom
  from r=10 m at z=-2 m to r=4 m at z=-3 m, flat bottom inside r=4 m; centre of mass z=-0.7 m;
* spar: fully submerged column of radius 3 m from z=-4 m (1 m below the float) to z=-29.5 m,
  with a heave plate of radius 15 m from z=-29.5 m to z=-30 m; centre of mass z=-24 m, so that
  it is stable in pitch without a waterplane.

Masses equal the displaced masses (rho = 1025 kg/m3, g = 9.81 m/s2). Capytaine direct BIE method
(the indirect method gave float/spar cross couplings asymmetric by 10-40 %), Delhommeau Green
function with a finer tabulation than the default (the default one gives a spurious negative spike
in the small spar-pitch damping near 0.86 rad/s), 52 frequencies from 0.1 to 3.5 rad/s plus the
omega = 0 and omega = inf added-mass limits, wave headings 0, 45 and 90 deg, infinite depth, lid on
the float waterplane for irregular-frequency removal.

The real RM3 geometry, an annular float around a surface-piercing spar, is not used: the annular
gap is a moonpool whose pumping (heave) and sloshing (surge/pitch) resonances are nearly undamped
in potential flow and make the BEM data unusable (negative damping, mesh-dependent spikes, cf.
WEC-Sim issue #1110). It is still available with ``--moonpool`` (annular float, inner radius 3.5 m,
around a surface-piercing spar, 0.5 m gap).

The test suite uses ``tests/data/float_spar_capytaine.nc``, made with Capytaine 3.0.0 by::

    python tests/data/make_float_spar.py tests/data/float_spar_capytaine.nc

Usage: ``python make_float_spar.py [out.nc] [--quick] [--moonpool]``
(default output: ``float_spar_capytaine.nc`` in the current directory).
"""

import argparse
import time

import capytaine as cpt
import numpy as np
import xarray as xr
from capytaine.meshes.meshes import Mesh
from capytaine.meshes.symmetric_meshes import RotationSymmetricMesh

NTHETA = 32
RHO, G = 1025.0, 9.81  # WEC-Sim default rho


def polyline(points, nsegs):
    """Points along the (r, z) vertices ``points``.

    ``nsegs``: per segment, a number of subdivisions or an array of fractions in [0, 1].
    """
    out = [np.asarray(points[0], float)]
    for p0, p1, n in zip(points[:-1], points[1:], nsegs, strict=True):
        p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
        if np.ndim(n) == 0:
            ts = np.linspace(0, 1, int(n) + 1)[1:]
        else:
            ts = np.asarray(n, float)[1:]
        out.extend(p0 + t * (p1 - p0) for t in ts)
    return np.array(out)


def revolve(profile_rz, n, name):
    """Surface of revolution of the (r, z) profile, as n wedges of angle 2 pi / n.

    The normal points outwards when the profile is walked with the body on the left in the
    (r, z) plane (i.e. e_theta x tangent = outward normal).
    """
    dth = 2 * np.pi / n
    p0 = np.column_stack([profile_rz[:, 0], np.zeros(len(profile_rz)), profile_rz[:, 1]])
    p1 = np.column_stack(
        [profile_rz[:, 0] * np.cos(dth), profile_rz[:, 0] * np.sin(dth), profile_rz[:, 1]]
    )
    m = len(profile_rz)
    vertices = np.concatenate([p0, p1])
    faces = np.array([(i, i + m, i + m + 1, i + 1) for i in range(m - 1)])
    wedge = Mesh(vertices=vertices, faces=faces, name=f"wedge_{name}")
    return RotationSymmetricMesh(wedge=wedge, n=n, name=name)


def cosine_spacing(n, fine_at_end=True):
    """Fractions 0..1, refined towards t=1 (the free surface) when fine_at_end."""
    t = np.sin(np.linspace(0, np.pi / 2, n + 1))
    return t if fine_at_end else 1 - t[::-1]


def build(ntheta=NTHETA):
    """Solid float disc + fully submerged spar (default geometry); only the float has a lid."""
    fl_pts = [(0.0, -3.0), (4.0, -3.0), (10.0, -2.0), (10.0, 0.0)]
    float_mesh = revolve(polyline(fl_pts, [4, 5, 3]), ntheta, "float")
    float_lid = revolve(polyline([(10.0, 0.0), (0.0, 0.0)], [6]), ntheta, "float_lid")
    sp_pts = [(0.0, -30.0), (15.0, -30.0), (15.0, -29.5), (3.0, -29.5), (3.0, -4.0), (0.0, -4.0)]
    spar_mesh = revolve(polyline(sp_pts, [7, 1, 6, cosine_spacing(10), 3]), ntheta, "spar")
    return float_mesh, float_lid, spar_mesh, None


def build_moonpool(ntheta=NTHETA):
    """Annular float (r 3.5-10 m) around a surface-piercing spar (0.5 m moonpool gap)."""
    # float: inner-top -> down -> bottom outwards -> frustum -> outer wall up
    fl_pts = [(3.5, 0.0), (3.5, -3.0), (4.0, -3.0), (10.0, -2.0), (10.0, 0.0)]
    float_mesh = revolve(polyline(fl_pts, [3, 1, 5, 3]), ntheta, "float")
    float_lid = revolve(polyline([(10.0, 0.0), (3.5, 0.0)], [5]), ntheta, "float_lid")
    # spar: axis bottom -> plate bottom outward -> rim up -> plate top inward -> column up
    sp_pts = [(0.0, -30.0), (15.0, -30.0), (15.0, -29.5), (3.0, -29.5), (3.0, 0.0)]
    spar_mesh = revolve(polyline(sp_pts, [7, 1, 6, cosine_spacing(12)]), ntheta, "spar")
    spar_lid = revolve(polyline([(3.0, 0.0), (0.0, 0.0)], [2]), ntheta, "spar_lid")
    return float_mesh, float_lid, spar_mesh, spar_lid


def join_with_single_lid(flt, spar, lid):
    """float + spar when only the float has a lid.

    Capytaine 3.0.0's Multibody fails when exactly one body has a RotationSymmetricMesh lid
    (RotationSymmetricMesh.join_meshes() with no other mesh calls set.intersection() without
    argument), so the lid is attached after construction, as Multibody does.
    """
    from capytaine.bodies.multibodies import Multibody

    body = Multibody([flt, spar])
    body.lid_mesh = lid.with_normal_vector_going_down()
    body.mesh_including_lid, masks = body.mesh.join_meshes(body.lid_mesh, return_masks=True)
    body.hull_mask = masks[0]
    fb = body.as_FloatingBody
    body.as_FloatingBody = cpt.FloatingBody(
        mesh=body.mesh,
        dofs=body.dofs,
        lid_mesh=body.lid_mesh,
        mass=fb.mass,
        center_of_mass=fb.center_of_mass,
        name=body.name,
    )
    return body


def make_body(mesh, lid, name, zg, x=0.0):
    """A floating body in hydrostatic equilibrium, its centre of mass at (x, 0, zg)."""
    b = cpt.FloatingBody(mesh=mesh, lid_mesh=lid, name=name, center_of_mass=(x, 0, zg))
    b.mass = RHO * b.volume  # displaced mass: body in hydrostatic equilibrium
    b.add_all_rigid_body_dofs()  # rotation centre = centre of mass
    b.inertia_matrix = b.compute_rigid_body_inertia(rho=RHO)
    b.hydrostatic_stiffness = b.compute_hydrostatic_stiffness(rho=RHO, g=G)
    return b


def direct_solver():
    """Capytaine's direct BIE method (the default indirect method gives A_ij != A_ji by up
    to 25 % for float/spar couplings) with a finer Delhommeau tabulation."""
    return cpt.BEMSolver(
        green_function=cpt.Delhommeau(
            tabulation_nr=1500, tabulation_nz=1500, tabulation_zmin=-300.0, tabulation_rmax=200.0
        ),
        method="direct",
    )


def without_round_off(ds):
    """``ds`` with the restoring and inertia entries that are zero up to quadrature noise
    set to zero (e.g. K33 = -1e-10 of a submerged spar)."""
    for v in ("hydrostatic_stiffness", "inertia_matrix"):
        x = ds[v]
        ds[v] = x.where(abs(x) > 1e-9 * float(abs(x).max()), 0.0)
    return ds


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="float_spar_capytaine.nc", help="output NetCDF")
    parser.add_argument("--quick", action="store_true", help="two frequencies only (smoke test)")
    parser.add_argument(
        "--moonpool", action="store_true", help="annular float around a surface-piercing spar"
    )
    return parser.parse_args()


def main():
    args = parse_args()
    if args.moonpool:
        fm, fl, sm, sl = build_moonpool()
        flt = make_body(fm, fl, "float", -0.7)
        spar = make_body(sm, sl, "spar", -21.0)
    else:
        fm, fl, sm, _ = build()
        # the float lid is attached when joining (see join_with_single_lid)
        flt = make_body(fm, None, "float", -0.7)
        spar = make_body(sm, None, "spar", -24.0)
    for b in (flt, spar):
        nb_lid = b.lid_mesh.nb_faces if b.lid_mesh is not None else 0
        print(
            f"{b.name} hull panels {b.mesh.nb_faces} lid panels {nb_lid}"
            f" volume {b.volume:.1f} m3 mass {b.mass / 1e3:.1f} t"
            f" CoB {np.round(b.center_of_buoyancy, 3)} CoG {b.center_of_mass}"
            f" first irr. freq est {b.first_irregular_frequency_estimate(g=G):.2f} rad/s"
        )
        k33, k44, k55 = (float(b.hydrostatic_stiffness.values[i, i]) for i in (2, 3, 4))
        print(f"  K33 {k33:.4g}  K44 {k44:.4g}  K55 {k55:.4g}")
    body = flt + spar if args.moonpool else join_with_single_lid(flt, spar, fl)
    print("dofs", list(body.dofs))
    print(
        f"total hull panels {body.mesh.nb_faces} lid {body.lid_mesh.nb_faces}",
        type(body.mesh).__name__,
    )

    omegas = np.array([0.5, 2.0]) if args.quick else np.linspace(0.1, 3.5, 52)
    test_matrix = xr.Dataset(
        coords={
            "omega": omegas,
            "wave_direction": np.deg2rad([0.0, 45.0, 90.0]),
            "radiating_dof": list(body.dofs),
            "water_depth": [np.inf],
            "rho": [RHO],
            "g": [G],
        }
    )
    solver = direct_solver()
    t0 = time.perf_counter()
    ds = solver.fill_dataset(test_matrix, body, hydrostatics=True, progress_bar=False)
    t1 = time.perf_counter()
    print(f"finite-frequency solve: {t1 - t0:.1f} s")

    # omega = 0 and inf: radiation only (added-mass limits)
    try:
        tm2 = xr.Dataset(
            coords={
                "omega": [0.0, np.inf],
                "radiating_dof": list(body.dofs),
                "water_depth": [np.inf],
                "rho": [RHO],
                "g": [G],
            }
        )
        ds_lim = solver.fill_dataset(tm2, body, hydrostatics=True, progress_bar=False)
        print(f"limits solve: {time.perf_counter() - t1:.1f} s")
        ds = xr.merge([ds, ds_lim], compat="no_conflicts", join="outer")
    except Exception as e:
        print("omega 0/inf failed:", repr(e))
    ds = without_round_off(ds)
    ds.attrs["total_solve_time_s"] = time.perf_counter() - t0
    geometry = (
        "annular float (r 3.5-10 m) around a surface-piercing spar with heave plate"
        " (0.5 m moonpool gap)"
        if args.moonpool
        else "solid float disc + fully submerged spar with heave plate (no moonpool)"
    )
    ds.attrs["description"] = (
        f"RM3-like two-body WEC, made by tests/data/make_float_spar.py of cummins: {geometry}"
    )
    print(ds)
    # == separate_complex_values + str dofs + to_netcdf
    cpt.io.xarray.save_dataset_as_netcdf(args.out, ds)
    print("saved", args.out)


if __name__ == "__main__":
    main()
