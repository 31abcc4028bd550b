"""The terms of the equation of motion that hydrodynamic files often leave out.

A BEM run describes the fluid; the rigid-body inertia, moorings and a power take-off
belong to the structure, and many file sets hold them only in part (a WAMIT ``.out``
prints the displaced volume and radii of gyration, a NEMOH run may have no
``Mechanics/Inertia.dat``, a Capytaine file its ``inertia_matrix`` only when the script
computed it). These functions complete a ``HydroDB`` so that :func:`cummins.motion_rao`
and :func:`cummins.vessel_from_hydrodb` have the equation of motion

    [−ω²(M_RB + A(ω)) + iω(B(ω) + B_ext) + C + C_ext] ξ = F(ω, β)

with M_RB built from the mass properties of each body (Smogeli et al. (2004) eq. 25: the
rigid-body inertia about a point other than the centre of gravity), the restoring C
holding the weight of that body (:mod:`cummins.restoring`), and external stiffness C_ext
and damping B_ext per DOF pair (``additional_stiffness``, ``additional_damping``). Every
value given or assumed is written to ``history``.

Examples
--------
>>> import numpy as np, cummins
>>> from cummins.mass_properties import with_inertia
>>> w = np.array([0.5, 1.0]); a = np.tile(np.eye(6), (2, 1, 1))
>>> ds = cummins.make_hydrodb(w, a, a, rho=1025.0, g=9.81, source_format="arrays")
>>> ds = with_inertia(ds, mass=2.0e6, center_of_gravity=[0, 0, -1.0],
...                   radii_of_gyration=[5.0, 20.0, 20.0])
>>> float(ds.inertia_matrix.sel(influenced_dof="Roll", radiating_dof="Roll"))
52000000.0
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import ArgumentError, AssumptionWarning, HydroDataError
from cummins.hydrodb import add_history, bodies, dof_matrix, split_dof
from cummins.kinematics import center_of_gravity_from_inertia, rigid_body_inertia
from cummins.restoring import with_weight
from cummins.validation import MAX_MASS, in_range

#: The heaviest floating structures are of order 10⁹ kg (ULCCs, the largest FPSOs):
#: a body a thousand times heavier is a unit error, not a vessel.
MAX_MASS_KG = MAX_MASS


def inertia_from_radii(
    mass: float,
    center_of_gravity: ArrayLike,
    radii_of_gyration: ArrayLike,
    reference_point: ArrayLike = (0.0, 0.0, 0.0),
) -> NDArray[np.float64]:
    """Rigid-body inertia matrix M_RB (6×6) about ``reference_point``.

    Parameters
    ----------
    mass
        kg.
    center_of_gravity
        m, in the body axes, from the same origin as ``reference_point``.
    radii_of_gyration
        m, about axes through the centre of gravity parallel to the body axes: r_xx,
        r_yy, r_zz (I = m r²; no products of inertia: give the whole matrix to
        :func:`with_inertia` when the body has them).
    reference_point
        The point about which moments and rotations are taken, m.

    Returns
    -------
    (6, 6) ndarray
        kg, kg·m, kg·m² (Smogeli et al. (2004) eq. 25, the parallel-axis theorem).

    Examples
    --------
    >>> m = inertia_from_radii(1000.0, [0, 0, 0], [1.0, 2.0, 2.0])
    >>> [float(m[i, i]) for i in (3, 4, 5)]
    [1000.0, 4000.0, 4000.0]
    """
    mass = in_range(
        mass,
        "mass",
        "kg",
        low=0.0,
        low_open=True,
        high=MAX_MASS_KG,
        hint="heavier than any floating body: check the unit (kg)",
    )
    cog = _vector(center_of_gravity, "center_of_gravity")
    ref = _vector(reference_point, "reference_point")
    radii = np.asarray(radii_of_gyration, dtype=float).reshape(-1)
    if radii.shape != (3,) or not np.all(np.isfinite(radii)) or np.any(radii <= 0):
        raise ArgumentError(
            f"radii_of_gyration must be 3 finite values > 0 (r_xx, r_yy, r_zz in m), "
            f"got {radii.tolist()}"
        )
    return rigid_body_inertia(mass, cog - ref, mass * radii**2)


def with_inertia(
    ds: xr.Dataset,
    *,
    mass: float | Sequence[float | None] | None = None,
    center_of_gravity: ArrayLike | None = None,
    radii_of_gyration: ArrayLike | None = None,
    matrix: ArrayLike | None = None,
    replace: bool = True,
    restoring: str | None = None,
) -> xr.Dataset:
    """The dataset with its ``inertia_matrix`` built from mass properties, or given, and
    its restoring holding the weight of that body.

    Parameters
    ----------
    ds
        A ``HydroDB``.
    mass
        kg, one value or one per body. ``None``: ρ∇ of a freely floating body, from the
        data's ``displaced_volume`` (said so in ``history``).
    center_of_gravity
        m, (3,) or (n_bodies, 3), in the dataset's axes; default: the data's
        ``center_of_gravity``.
    radii_of_gyration
        m, about the centre of gravity: (3,) or (n_bodies, 3) (see
        :func:`inertia_from_radii`).
    matrix
        Instead of the above: the n×n inertia matrix of all DOFs, or a 6×6 matrix per
        body ((n_bodies, 6, 6)), about the reference point, kg, kg·m, kg·m².
    replace
        Replace an ``inertia_matrix`` the data already hold (default); with ``False``
        that is an error.
    restoring
        What the data's ``hydrostatic_stiffness`` holds, when the files do not say or
        say it wrongly: ``"hydrostatic"`` (buoyancy only) or ``"total"`` (with the weight
        of the body the files describe); default: what the files record
        (:func:`cummins.restoring.describe_restoring`), else ``"hydrostatic"`` with a
        warning.

    Returns
    -------
    xarray.Dataset
        A copy with ``inertia_matrix`` (and ``center_of_gravity``) set, and the weight's
        part of the restoring made that of this mass and centre of gravity:
        C₄₄, C₅₅ += −g (m z_G − m_file z_G,file), C₄₆ += g (m x_G − m_file x_G,file),
        C₅₆ += g (m y_G − m_file y_G,file) about each body's reference point (WAMIT (2020)
        §3.1; :func:`cummins.restoring.with_weight`), where m_file, G_file are what the
        files' restoring holds: WAMIT's ``.hst`` the weight of ρ∇ at the ``.out``'s centre
        of gravity, NEMOH's ``KH`` and Capytaine's ``hydrostatic_stiffness`` that of
        their centre of mass, OpenFAST's WAMIT files none. Every change is written to
        ``history`` and ``restoring_source``. A matrix that is not that of a rigid body
        has no single centre of gravity: its restoring is left as it is (a warning says
        so).

    Raises
    ------
    ArgumentError
        Values that are not finite, out of range, or of the wrong shape; mass properties
        that cannot give the matrix (a body with generalized modes needs ``matrix``).
    """
    labels = [str(d) for d in ds.influenced_dof.values]
    n = len(labels)
    if "inertia_matrix" in ds and not replace:
        raise ArgumentError("the data already hold an inertia_matrix; pass replace=True")
    groups = bodies(ds)
    lines: list[str] = []
    cogs = None
    if matrix is not None:
        if any(v is not None for v in (mass, center_of_gravity, radii_of_gyration)):
            raise ArgumentError(
                "give either matrix= or the mass properties (mass, center_of_gravity, "
                "radii_of_gyration), not both"
            )
        m = _matrix_per_body(matrix, labels, groups)
        lines.append("inertia_matrix given as a matrix")
    else:
        if None in groups and len(groups) > 1:  # DOFs of the system beside named bodies
            shared = [d for d in labels if split_dof(d)[0] is None]
            raise ArgumentError(
                f"{', '.join(shared)} name no body (DOFs of the system, over several bodies): "
                "mass properties per body cannot give their inertia",
                hint="give the whole inertia matrix of all the DOFs (matrix=; "
                "--inertia-matrix FILE)",
            )
        m, lines, cogs = _matrix_from_properties(
            ds, labels, groups, mass, center_of_gravity, radii_of_gyration
        )
    if not np.all(np.isfinite(m)):
        raise ArgumentError("the inertia matrix holds values that are not finite")
    if np.any(np.diag(m) <= 0) or np.any(np.abs(np.diag(m)) > MAX_MASS_KG * 1e6):
        bad = [labels[i] for i in range(n) if not 0 < m[i, i] <= MAX_MASS_KG * 1e6]
        raise ArgumentError(
            f"the inertia matrix has a diagonal entry that is not a positive mass or inertia "
            f"for {', '.join(bad)}",
            hint="give kg for translations and kg m^2 for rotations",
        )
    if np.max(np.abs(m - m.T)) > 1e-9 * np.max(np.abs(m)):
        raise ArgumentError("the inertia matrix must be symmetric")
    out = ds.copy()
    previous = "inertia_matrix" in ds
    out["inertia_matrix"] = xr.DataArray(
        m,
        dims=("influenced_dof", "radiating_dof"),
        coords={"influenced_dof": labels, "radiating_dof": labels},
        attrs={"units": "kg | kg m | kg m^2", "long_name": "rigid-body inertia matrix M_RB"},
    )
    if cogs is not None:
        out.attrs["center_of_gravity"] = np.concatenate(cogs)
    for line in lines:
        add_history(out, line + (" (replaces the file's)" if previous else ""))
    return complete_restoring(
        out, restoring=restoring, why="given" if matrix is None else "from the matrix given"
    )


def complete_restoring(
    ds: xr.Dataset, *, restoring: str | None = None, why: str = "from the inertia matrix"
) -> xr.Dataset:
    """The dataset whose restoring holds the weight of the body its ``inertia_matrix``
    describes (mass and centre of gravity of each body's rigid block,
    :func:`cummins.kinematics.center_of_gravity_from_inertia`), replacing the weight the
    files' restoring holds (:func:`cummins.restoring.with_weight`; ``restoring`` as
    :func:`with_inertia` takes it). Without an inertia matrix or a restoring, ``ds``."""
    if "inertia_matrix" not in ds or "hydrostatic_stiffness" not in ds:
        return ds
    labels = [str(d) for d in ds.influenced_dof.values]
    groups = bodies(ds)
    m = dof_matrix(ds, "inertia_matrix")
    refs = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float).reshape(-1, 3)
    masses, centers = [], []
    for k, index in enumerate(_body_slices(labels, groups)):
        rigid = [i for i in index if split_dof(labels[i])[1] in _RIGID]
        name = groups[k] or "the body"
        if len(rigid) != 6:
            warnings.warn(
                AssumptionWarning(
                    f"{name} has no six rigid-body modes: the weight's terms of its "
                    "restoring are left as the files give them"
                ),
                stacklevel=3,
            )
            return ds
        mass, r_g, inconsistency = center_of_gravity_from_inertia(m[np.ix_(rigid, rigid)])
        if inconsistency > 1e-3:
            warnings.warn(
                AssumptionWarning(
                    f"the inertia matrix of {name} is not that of a rigid body (its coupling "
                    "block is not -m S(r_g)): it gives no single centre of gravity, and the "
                    "weight's terms of the restoring are left as the files give them"
                ),
                stacklevel=3,
            )
            return ds
        ref = refs[k] if len(refs) == len(groups) else refs[0]
        masses.append(mass)
        centers.append(ref + r_g)
    return with_weight(ds, masses, centers, includes=restoring, why=why)


def with_external_terms(
    ds: xr.Dataset,
    *,
    stiffness: Mapping[tuple[str, str], float] | ArrayLike | None = None,
    damping: Mapping[tuple[str, str], float] | ArrayLike | None = None,
    source: str = "given",
) -> xr.Dataset:
    """Add external linear stiffness and damping (moorings, a power take-off, a
    hinge spring) to the data's ``additional_stiffness`` and ``additional_damping``.

    Parameters
    ----------
    stiffness, damping
        ``{(influenced DOF, radiating DOF): value}`` or an n×n array, N/m, N·m/rad …
        and kg/s, kg·m²/s …, added to what the data hold. A mapping sets the entries it
        names only: give ``(j, i)`` too for a symmetric coupling.
    source
        Where the terms come from, for ``history`` (``"given"``; the joints' pre-load
        says what it added, :func:`cummins.mechanics.assemble`).

    Returns
    -------
    xarray.Dataset
        A copy; the additions are written to ``history``. Data without a
        ``hydrostatic_stiffness`` (a NEMOH run whose KH files describe another mesh)
        given a ``stiffness`` get a zero one: the stiffness given is then the whole
        restoring, which a warning and ``history`` say.
    """
    labels = [str(d) for d in ds.influenced_dof.values]
    out = ds.copy()
    if stiffness is not None and "hydrostatic_stiffness" not in out:
        n = len(labels)
        out["hydrostatic_stiffness"] = xr.DataArray(
            np.zeros((n, n)),
            dims=("influenced_dof", "radiating_dof"),
            coords={"influenced_dof": labels, "radiating_dof": labels},
            attrs={"units": "N/m | N/rad, N | N m/rad"},
        )
        said = (
            "the data hold no hydrostatic restoring: the external stiffness given is the "
            "whole restoring (hydrostatics, weight, moorings)"
        )
        add_history(out, f"hydrostatic_stiffness: zero; {said}")
        warnings.warn(said, AssumptionWarning, stacklevel=2)
    for name, value, unit in (
        ("additional_stiffness", stiffness, "N/m | N/rad, N | N m/rad"),
        ("additional_damping", damping, "kg/s | kg m/s | kg m^2/s"),
    ):
        if value is None:
            continue
        added = _pair_matrix(value, labels, name)
        if name in out and "omega" in out[name].dims:
            base = out[name].transpose("omega", "influenced_dof", "radiating_dof")
            out[name] = base + xr.DataArray(added, dims=("influenced_dof", "radiating_dof"))
            out[name] = out[name].transpose(*ds[name].dims)
        else:
            total = (dof_matrix(out, name) if name in out else 0.0) + added
            out[name] = xr.DataArray(
                total,
                dims=("influenced_dof", "radiating_dof"),
                coords={"influenced_dof": labels, "radiating_dof": labels},
                attrs={"units": unit},
            )
        entries = ", ".join(
            f"{labels[i]}-{labels[j]} {added[i, j]:.6g}"
            for i in range(len(labels))
            for j in range(len(labels))
            if added[i, j]
        )
        add_history(out, f"{name} added ({source}): {entries}")
    return out


# --------------------------------------------------------------------------- pieces


def check_inertia_terms(
    *,
    mass: Sequence[float] = (),
    center_of_gravity: Sequence[Sequence[float]] = (),
    radii_of_gyration: Sequence[Sequence[float]] = (),
    matrix_given: bool = False,
    name=str,
) -> None:
    """The inertia a user gives, checked as a whole (the command line's ``--mass`` & co.,
    a study's keys): the mass and centre of gravity build the inertia matrix together with
    the radii of gyration; an inertia matrix excludes the three. ``name(key)``: how the
    user wrote the input (``"--mass"``, ``"mass"``), for the messages.

    Raises
    ------
    ArgumentError
        A combination :func:`with_given_terms` cannot build.
    """
    if matrix_given and (mass or center_of_gravity or radii_of_gyration):
        raise ArgumentError(
            f"give either {name('inertia_matrix')} or {name('mass')}/"
            f"{name('center_of_gravity')}/{name('radii_of_gyration')}, not both"
        )
    if not matrix_given and not radii_of_gyration and (mass or center_of_gravity):
        raise ArgumentError(
            f"{name('mass')} and {name('center_of_gravity')} build the inertia matrix "
            f"together with {name('radii_of_gyration')}: give the radii too (rxx, ryy, rzz "
            "in m about the centre of gravity, one per body)"
        )


def with_given_terms(
    ds: xr.Dataset,
    *,
    mass: Sequence[float] = (),
    center_of_gravity: Sequence[Sequence[float]] = (),
    radii_of_gyration: Sequence[Sequence[float]] = (),
    matrix: ArrayLike | None = None,
    restoring: str | None = None,
    external_stiffness: Sequence[tuple[str, str, float]] = (),
    external_damping: Sequence[tuple[str, str, float]] = (),
    name=str,
) -> xr.Dataset:
    """``ds`` completed with the inertia and external terms a user gives — the command
    line's options (``--mass`` … ``--external-damping``) and a study's keys of the same
    meaning: the inertia from ``matrix`` or from the mass properties
    (:func:`with_inertia`, its restoring made to hold that inertia's weight per
    ``restoring``), else the restoring completed with the data's own inertia
    (:func:`complete_restoring`); then the external terms, ``[(DOF, DOF, value), …]``
    (:func:`with_external_terms`). ``name(key)`` names the input in the messages as the
    user wrote it (``"--radii-of-gyration"``, ``"radii_of_gyration"``).

    Raises
    ------
    ArgumentError
        Naming the input: a combination :func:`check_inertia_terms` refuses, properties
        :func:`with_inertia` refuses, ``restoring`` without an inertia, an external term
        on a DOF the data lack.
    """
    check_inertia_terms(
        mass=mass,
        center_of_gravity=center_of_gravity,
        radii_of_gyration=radii_of_gyration,
        matrix_given=matrix is not None,
        name=name,
    )
    key = "inertia_matrix"
    try:
        if matrix is not None:
            ds = with_inertia(ds, matrix=np.asarray(matrix, dtype=float), restoring=restoring)
        elif radii_of_gyration:
            key = "radii_of_gyration"
            ds = with_inertia(
                ds,
                mass=list(mass) or None,
                center_of_gravity=[list(c) for c in center_of_gravity] or None,
                radii_of_gyration=[list(r) for r in radii_of_gyration],
                restoring=restoring,
            )
        elif restoring is not None:
            key = "restoring_includes_weight"
            if "inertia_matrix" not in ds:
                raise ArgumentError(
                    "completes the restoring with the weight of the body's inertia, and the "
                    f"data hold none: give {name('mass')}, {name('center_of_gravity')} and "
                    f"{name('radii_of_gyration')} (or {name('inertia_matrix')})"
                )
            ds = complete_restoring(ds, restoring=restoring, why="the files' inertia")
    except ArgumentError as exc:
        raise ArgumentError(f"{name(key)}: {exc}") from None
    labels = [str(d) for d in ds.influenced_dof.values]
    terms = {}
    for kind, given in (("stiffness", external_stiffness), ("damping", external_damping)):
        for i, j, _ in given:
            for dof in (i, j):
                if dof not in labels:
                    raise ArgumentError(
                        f"{name(f'external_{kind}')}: unknown DOF {dof!r}; the data have "
                        f"{', '.join(labels)}"
                    )
        if given:
            terms[kind] = {(i, j): value for i, j, value in given}
    return with_external_terms(ds, **terms) if terms else ds


#: A body whose mass differs from its displaced mass ρ∇ by more than this fraction is
#: not in static equilibrium floating freely (:func:`equilibrium_notes`).
EQUILIBRIUM_TOLERANCE = 0.1


def equilibrium_notes(ds: xr.Dataset) -> list[str]:
    """One line per body whose mass (the inertia matrix's) differs from ρ∇ (the data's
    displaced volume) by more than :data:`EQUILIBRIUM_TOLERANCE`: floating freely it is
    not in static equilibrium, so a joint, a mooring or a DOF selection must hold it
    (WEC-Sim's OSWEC base, 999 kg on a hinge to the seabed). Empty without the inertia
    matrix or one displaced volume per body."""
    volume = ds.attrs.get("displaced_volume")
    if "inertia_matrix" not in ds or volume is None:
        return []
    labels = [str(d) for d in ds.influenced_dof.values]
    groups = bodies(ds)
    volumes = np.atleast_1d(np.asarray(volume, dtype=float))
    if len(volumes) != len(groups):
        return []
    inertia = dof_matrix(ds, "inertia_matrix")
    rho = float(ds.attrs["rho"])
    out = []
    for k, index in enumerate(_body_slices(labels, groups)):
        surge = [i for i in index if split_dof(labels[i])[1] == "Surge"]
        buoyancy = rho * volumes[k]
        if not surge or not buoyancy > 0:
            continue
        mass = float(inertia[surge[0], surge[0]])
        if abs(mass / buoyancy - 1.0) > EQUILIBRIUM_TOLERANCE:
            out.append(
                f"{groups[k] or 'the body'}: mass {mass:.4g} kg, {mass / buoyancy:.1%} of its "
                f"displaced mass ρ∇ = {buoyancy:.4g} kg: floating freely it is not in static "
                "equilibrium; a joint, a mooring or --dof must hold it (--joint KIND "
                f"{groups[k] or 'body1'} ground, or a joint to a body that is held)"
            )
    return out


def _vector(value: ArrayLike, name: str) -> NDArray[np.float64]:
    v = np.asarray(value, dtype=float).reshape(-1)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ArgumentError(f"{name} must be 3 finite coordinates (m), got {v.tolist()}")
    return v


def _per_body(value: Any, count: int, name: str, width: int | None) -> list[Any]:
    """One entry per body from a scalar / (3,) value or a sequence of them."""
    if value is None:
        return [None] * count
    arr = np.asarray(value, dtype=object if width is None else float)
    if width is None:  # masses
        items = list(np.atleast_1d(arr))
    elif arr.ndim == 1:
        items = [arr]
    else:
        items = list(arr)
    if len(items) == 1 and count > 1:
        raise ArgumentError(
            f"{name}: the data hold {count} bodies; give one value per body, in their order"
        )
    if len(items) != count:
        raise ArgumentError(f"{name}: {len(items)} values given for {count} bodies")
    return items


def _body_slices(labels: list[str], groups: list[str | None]) -> list[list[int]]:
    return [[i for i, d in enumerate(labels) if split_dof(d)[0] == b] for b in groups]


def _matrix_from_properties(ds, labels, groups, mass, cog, radii):
    """The inertia matrix of every body from its mass properties, the history lines and
    the centres of gravity used."""
    n = len(labels)
    count = len(groups)
    if radii is None:
        raise ArgumentError(
            "radii_of_gyration (m, about the centre of gravity) are needed to build the "
            "inertia matrix",
            hint="give them, or the whole matrix (matrix=; --inertia-matrix FILE)",
        )
    masses = _per_body(mass, count, "mass", None)
    cogs = _per_body(cog, count, "center_of_gravity", 3)
    radii_list = _per_body(radii, count, "radii_of_gyration", 3)
    refs = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float).reshape(-1, 3)
    file_cogs = ds.attrs.get("center_of_gravity")
    file_cogs = None if file_cogs is None else np.asarray(file_cogs, dtype=float).reshape(-1, 3)
    volume = ds.attrs.get("displaced_volume")
    rho = float(ds.attrs["rho"])
    m = np.zeros((n, n))
    lines: list[str] = []
    used: list[NDArray[np.float64]] = []
    for k, index in enumerate(_body_slices(labels, groups)):
        name = groups[k] or "the body"
        rigid = [i for i in index if split_dof(labels[i])[1] in _RIGID]
        if len(index) != 6 or [split_dof(labels[i])[1] for i in rigid] != list(_RIGID):
            raise ArgumentError(
                f"{name} has the modes {', '.join(labels[i] for i in index)}: mass properties "
                "give the six rigid-body modes only",
                hint="give the whole inertia matrix of all its modes (matrix=; "
                "--inertia-matrix FILE)",
            )
        body_mass = masses[k]
        if body_mass is None:
            volumes = np.atleast_1d(np.asarray(volume, dtype=float)) if volume is not None else []
            if len(volumes) != count:
                raise ArgumentError(
                    f"no mass given for {name} and the data hold no displaced volume per body",
                    hint="give the mass (mass=; --mass KG)",
                )
            body_mass = rho * float(volumes[k])
            lines.append(
                f"mass of {name} = rho * volume = {body_mass:.6g} kg (freely floating body: "
                "weight = buoyancy; give the mass if it is moored or ballasted otherwise)"
            )
        else:
            lines.append(f"mass of {name} = {float(body_mass):.6g} kg (given)")
        body_cog = cogs[k]
        if body_cog is None:
            if file_cogs is None or len(file_cogs) != count:
                raise ArgumentError(
                    f"no centre of gravity given for {name}, and the data hold none",
                    hint="give it (center_of_gravity=; --center-of-gravity X Y Z)",
                )
            body_cog = file_cogs[k]
            where = "from the file"
        else:
            where = "given"
        body_cog = _vector(body_cog, "center_of_gravity")
        ref = refs[k] if len(refs) == count else refs[0]
        block = inertia_from_radii(body_mass, body_cog, radii_list[k], ref)
        lines.append(
            f"inertia of {name} from the radii of gyration "
            f"{np.round(np.asarray(radii_list[k], dtype=float), 6).tolist()} m about the "
            f"centre of gravity {body_cog.tolist()} m ({where}), reference point {ref.tolist()} m"
        )
        m[np.ix_(index, index)] = block
        used.append(body_cog)
    return m, lines, used


_RIGID = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


def _matrix_per_body(matrix: ArrayLike, labels: list[str], groups) -> NDArray[np.float64]:
    arr = np.asarray(matrix, dtype=float)
    n = len(labels)
    if arr.shape == (n, n):
        return arr
    slices = _body_slices(labels, groups)
    six_each = all(len(s) == 6 for s in slices)
    if six_each and arr.shape == (len(groups), 6, 6):
        out = np.zeros((n, n))
        for block, index in zip(arr, slices, strict=True):
            out[np.ix_(index, index)] = block
        return out
    if six_each and arr.shape == (6 * len(groups), 6):
        return _matrix_per_body(arr.reshape(len(groups), 6, 6), labels, groups)
    raise ArgumentError(
        f"the inertia matrix has shape {arr.shape}; the data hold {n} DOFs "
        f"({len(groups)} bod{'y' if len(groups) == 1 else 'ies'})",
        hint=f"give an {n}×{n} matrix, or a 6×6 matrix per body stacked one below the other",
    )


def _pair_matrix(value: Any, labels: list[str], name: str) -> NDArray[np.float64]:
    n = len(labels)
    if isinstance(value, Mapping):
        out = np.zeros((n, n))
        for key, v in value.items():
            try:
                i_label, j_label = key
            except (TypeError, ValueError):
                raise ArgumentError(f"{name}: keys are (DOF, DOF) pairs, got {key!r}") from None
            for label in (i_label, j_label):
                if label not in labels:
                    raise ArgumentError(
                        f"{name}: unknown DOF {label!r}", hint=f"the data have {', '.join(labels)}"
                    )
            x = float(v)
            if not np.isfinite(x):
                raise ArgumentError(f"{name}[{i_label}, {j_label}] = {x!r} is not finite")
            out[labels.index(i_label), labels.index(j_label)] += x
        return out
    arr = np.asarray(value, dtype=float)
    if arr.shape != (n, n):
        raise ArgumentError(f"{name} must be {n}×{n} (the data's DOFs), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ArgumentError(f"{name} holds values that are not finite")
    return arr


def read_matrix_file(path: str) -> NDArray[np.float64]:
    """A matrix from a text file (whitespace or commas, ``#`` comments) or ``.npy``."""
    from pathlib import Path

    p = Path(path)
    try:
        if p.suffix.lower() == ".npy":
            return np.asarray(np.load(p, allow_pickle=False), dtype=float)
        rows = []
        for number, line in enumerate(p.read_text(encoding="utf-8-sig").splitlines(), 1):
            text = line.split("#", 1)[0].replace(",", " ").strip()
            if not text:
                continue
            try:
                rows.append([float(x) for x in text.split()])
            except ValueError:
                raise HydroDataError(
                    f"expected numbers, found {line.strip()[:60]!r}", path=p, line=number
                ) from None
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise HydroDataError(f"cannot read a matrix: {exc}", path=p) from None
    if not rows or len({len(r) for r in rows}) != 1:
        raise HydroDataError("expected a rectangular table of numbers", path=p)
    return np.asarray(rows, dtype=float)


__all__ = [
    "MAX_MASS_KG",
    "complete_restoring",
    "inertia_from_radii",
    "read_matrix_file",
    "with_external_terms",
    "with_inertia",
]
