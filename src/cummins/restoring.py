"""The restoring matrix C of the equation of motion: its buoyancy and weight parts, which
of them a file holds, and the static stability they give.

For small rotations θ = (θ₄, θ₅, θ₆) about the reference point O of a body of mass m
whose centre of gravity is at r = G − O, the weight −m g e_z (z up) keeps its direction
while its point of application turns with the body: its moment about O changes by
δM = (θ × r) × (−m g e_z), i.e. δM₄ = m g (z θ₄ − x θ₆), δM₅ = m g (z θ₅ − y θ₆). The
weight's part of C = −∂M/∂θ is therefore

    C₄₄ = C₅₅ = −m g z,    C₄₆ = m g x,    C₅₆ = m g y,

and nothing else: the weight does not change with the motion, so it adds nothing to the
heave force or to the C₃₄, C₃₅ waterplane terms (WAMIT (2020) §3.1, Newman (1977) ch. 6,
Faltinsen (1990) ch. 2). The buoyancy part, ρ g (∫y² dA + ∇ z_B) in C₄₄,
−ρ g ∇ x_B in C₄₆ …, depends on the hull alone. A solver's restoring holds the weight's
part for the mass and centre of gravity its input gave (WAMIT's ``.hst`` for XCG/VCG and
m = ρ∇, NEMOH's ``KH`` and Capytaine's ``hydrostatic_stiffness`` for their centre of
mass), or none (OpenFAST's WAMIT files, run with the centre of gravity at the origin).

What the data's ``hydrostatic_stiffness`` holds is recorded in the attributes

``restoring_weight_mass``
    kg per body: the mass whose weight the restoring includes (0: none; NaN: the body's
    own mass, not recorded — a freely floating body's ρ∇);
``restoring_weight_center``
    m, 3 per body, in the dataset's axes: where that weight acts;
``restoring_source``
    one line saying where C came from and what it holds;

and no ``restoring_weight_*`` at all when the files do not tell. :func:`with_weight`
(called by :func:`cummins.with_inertia`) replaces the weight's part by that of the mass
and centre of gravity of the equation of motion, ΔC = W(m, G) − W(m_file, G_file).
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.dofs import DOF_NAMES, bodies, is_rigid_body_dof, is_rotation
from cummins.errors import ArgumentError, AssumptionWarning, HydroDataError
from cummins.hydrodb import add_history, reference_points

#: The attributes of a dataset that say what its restoring holds (module docstring).
WEIGHT_MASS = "restoring_weight_mass"
WEIGHT_CENTER = "restoring_weight_center"
SOURCE = "restoring_source"

#: ``with_weight(includes=…)``: what the data's restoring holds, when the user says so.
INCLUDES = {"hydrostatic": False, "total": True}
#: How a user says the restoring holds the weight, in the warning of files that do not
#: say (a batch study says its own key instead: :func:`cummins.studies.wording.study_wording`).
INCLUDES_WEIGHT_CHOICE = "--restoring-includes-weight yes (includes='total')"


# --------------------------------------------------------------------------- the weight


def weight_stiffness(
    first_moment: ArrayLike, g: float, axis_convention: str = "z-up"
) -> NDArray[np.float64]:
    """The weight's part of the 6×6 restoring matrix about the reference point O.

    Parameters
    ----------
    first_moment
        m (G − O), kg·m, in the dataset's axes.
    g
        m/s².
    axis_convention
        ``"z-up"`` (gravity along −z) or ``"z-down"`` (Fossen's axes, gravity along +z).

    Returns
    -------
    (6, 6) ndarray
        C₄₄ = C₅₅ = −m g z, C₄₆ = m g x, C₅₆ = m g y in z-up axes (module docstring;
        WAMIT (2020) §3.1); in z-down axes the same matrix turned by T = diag(1, −1, −1,
        1, −1, −1): C₄₄ = C₅₅ = m g z, C₄₆ = −m g x, C₅₆ = m g y.

    Examples
    --------
    >>> w = weight_stiffness([0.0, 0.0, 1.0e6], 9.81)   # 1000 t, G 1 m above O
    >>> float(w[3, 3]), float(w[4, 4]), float(w[3, 5])
    (-9810000.0, -9810000.0, 0.0)
    """
    r = np.asarray(first_moment, dtype=float).reshape(3)
    if axis_convention == "z-down":
        r = r * np.array([1.0, -1.0, -1.0])
    w = np.zeros((6, 6))
    w[3, 3] = w[4, 4] = -g * r[2]
    w[3, 5] = g * r[0]
    w[4, 5] = g * r[1]
    if axis_convention == "z-down":
        t = np.diag([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
        w = t @ w @ t
    return w


@dataclass(frozen=True)
class BodyWeight:
    """The weight a restoring holds for one body: ``mass`` kg (NaN: the body's own,
    not recorded), ``center`` m in the dataset's axes."""

    mass: float
    center: NDArray[np.float64]


def weight_record(masses: ArrayLike, centers: ArrayLike, source: str) -> dict[str, Any]:
    """The attributes a reader gives ``make_hydrodb`` when the files say which weight
    their restoring holds (module docstring): one mass (kg, NaN when the files imply the
    body's own without recording it, 0 for none) and one centre (m) per body."""
    m = np.atleast_1d(np.asarray(masses, dtype=float)).reshape(-1)
    c = np.asarray(centers, dtype=float).reshape(-1)
    if c.size != 3 * m.size:
        raise ValueError(f"{m.size} masses but {c.size} coordinates of centres")
    return {
        WEIGHT_MASS: float(m[0]) if m.size == 1 else m,
        WEIGHT_CENTER: c,
        SOURCE: source,
    }


def recorded_weight(ds: xr.Dataset) -> list[BodyWeight] | None:
    """The weight the data's restoring holds, per body; None when the files do not say."""
    if WEIGHT_MASS not in ds.attrs or WEIGHT_CENTER not in ds.attrs:
        return None
    m = np.atleast_1d(np.asarray(ds.attrs[WEIGHT_MASS], dtype=float)).reshape(-1)
    c = np.asarray(ds.attrs[WEIGHT_CENTER], dtype=float).reshape(-1, 3)
    if len(c) != len(m):
        return None
    return [BodyWeight(float(mk), ck.copy()) for mk, ck in zip(m, c, strict=True)]


def describe_restoring(ds: xr.Dataset) -> str:
    """One line: where the data's restoring came from and whether it holds the weight."""
    if "hydrostatic_stiffness" not in ds:
        return "no restoring matrix"
    source = str(ds.attrs.get(SOURCE, "")).strip()
    weights = recorded_weight(ds)
    if weights is None:
        holds = "whether it holds the weight's terms is not recorded"
    elif all(w.mass == 0 for w in weights):
        holds = "hydrostatics only (no weight terms)"
    else:
        holds = "hydrostatics and the weight of " + "; ".join(_weight_text(w) for w in weights)
    return f"{source}: {holds}" if source else holds


def _weight_text(w: BodyWeight) -> str:
    if w.mass == 0:
        return "no weight"
    mass = "its own mass (rho V)" if np.isnan(w.mass) else f"{w.mass:.6g} kg"
    return f"{mass} at {np.round(w.center, 6).tolist()} m"


def with_weight(
    ds: xr.Dataset,
    masses: Sequence[float],
    centers: Sequence[ArrayLike],
    *,
    includes: str | None = None,
    why: str = "given",
) -> xr.Dataset:
    """The dataset whose restoring holds the weight of ``masses`` at ``centers``.

    ΔC = W(m, G) − W(m_file, G_file) on each body's rotations (:func:`weight_stiffness`,
    about the body's reference point), with m_file, G_file what the files' restoring
    holds (:func:`recorded_weight`).

    Parameters
    ----------
    ds
        A ``HydroDB``; without ``hydrostatic_stiffness`` it is returned as it is.
    masses, centers
        kg and m (dataset axes), one per body.
    includes
        What the data's restoring holds, when the user says so: ``"hydrostatic"`` (no
        weight terms) or ``"total"`` (the weight of the body the files describe: their
        ``center_of_gravity`` and mass, else the one given here). By default what the
        files record; when they record nothing, ``"hydrostatic"`` is assumed (OpenFAST's
        convention) with an :class:`~cummins.errors.AssumptionWarning`.
    why
        How the mass and centre were obtained, for ``history``.

    Raises
    ------
    ArgumentError
        ``includes="hydrostatic"`` for files that record a weight term, an unknown
        ``includes``, a count of masses or centres that is not one per body.
    """
    if "hydrostatic_stiffness" not in ds:
        return ds
    if includes is not None and includes not in INCLUDES:
        raise ArgumentError(f"includes must be one of {', '.join(INCLUDES)}, not {includes!r}")
    groups = bodies(ds)
    if len(masses) != len(groups) or len(centers) != len(groups):
        raise ArgumentError(
            f"{len(masses)} masses and {len(centers)} centres of gravity for {len(groups)} bodies"
        )
    labels = [str(d) for d in ds.influenced_dof.values]
    axes = str(ds.attrs.get("axis_convention", "z-up"))
    g = float(ds.attrs["g"])
    refs = np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0)), dtype=float).reshape(-1, 3)
    recorded = recorded_weight(ds)
    where = _file_name(ds)
    if recorded is not None and len(recorded) != len(groups):
        recorded = None
    if includes == "hydrostatic" and recorded is not None:
        held = [
            k
            for k, w in enumerate(recorded)
            if w.mass != 0 and np.any(np.abs(w.center - refs[min(k, len(refs) - 1)]) > 1e-9)
        ]
        if held:
            raise ArgumentError(
                f"{where} records the weight terms of its restoring "
                f"({_weight_text(recorded[held[0]])}): it is not hydrostatic only",
                hint="Leave the statement of what the restoring holds out "
                "(--restoring-includes-weight)",
            )
    if recorded is None:
        if includes is None:
            warnings.warn(
                AssumptionWarning(
                    f"{where}: the files do not say whether the restoring holds the weight's "
                    "terms; taken as hydrostatic only (OpenFAST's convention) and the weight "
                    "of the mass and centre of gravity given is added (C44, C55 -m g z_G). "
                    f"If the solver included it, say {INCLUDES_WEIGHT_CHOICE}"
                ),
                stacklevel=3,
            )
        old = _file_weights(ds, groups, masses, centers, includes == "total")
        stated = "assumed" if includes is None else "stated"
    else:
        old = recorded
        stated = "recorded"
    c = np.array(
        ds["hydrostatic_stiffness"].transpose("influenced_dof", "radiating_dof").values,
        dtype=float,
    )
    changes: list[str] = []
    new: list[BodyWeight] = []
    for k, body in enumerate(groups):
        ref = refs[k] if len(refs) == len(groups) else refs[0]
        mass = float(masses[k])
        center = np.asarray(centers[k], dtype=float).reshape(3)
        file_mass = mass if np.isnan(old[k].mass) else old[k].mass
        delta = weight_stiffness(mass * (center - ref), g, axes) - weight_stiffness(
            file_mass * (old[k].center - ref), g, axes
        )
        index = _rigid_index(labels, body)
        for a, i in index.items():
            for b, j in index.items():
                if delta[a, b] != 0.0 and j is not None and i is not None:
                    c[i, j] += delta[a, b]
                    if abs(delta[a, b]) > 1e-9 * max(abs(c[i, j]), 1.0):
                        changes.append(f"C[{labels[i]}, {labels[j]}] {delta[a, b]:+.6g}")
        new.append(BodyWeight(mass, center))
    out = ds.copy()
    out["hydrostatic_stiffness"] = ds["hydrostatic_stiffness"].copy(
        data=c if ds["hydrostatic_stiffness"].dims == ("influenced_dof", "radiating_dof") else c.T
    )
    before = str(ds.attrs.get(SOURCE, "")).split(" [")[0].strip() or "the data's restoring"
    weights = "; ".join(_weight_text(w) for w in new)
    out.attrs.update(
        weight_record(
            [w.mass for w in new],
            np.concatenate([w.center for w in new]),
            f"{before} [weight terms made those of the mass and centre of gravity {why}, in "
            f"place of the file's ({stated}: {'; '.join(_weight_text(w) for w in old)})]",
        )
    )
    add_history(
        out,
        f"restoring: weight terms for {weights} ({why}) in place of the file's "
        f"({stated}: {'; '.join(_weight_text(w) for w in old) or 'none'}): "
        + (", ".join(changes) if changes else "no change"),
    )
    return out


def _file_weights(ds, groups, masses, centers, total: bool) -> list[BodyWeight]:
    """The weight an unrecorded restoring holds: none, or (``total``) that of the body the
    files describe (their centre of gravity and mass), else the one given."""
    if not total:
        return [BodyWeight(0.0, np.zeros(3)) for _ in groups]
    cogs = ds.attrs.get("center_of_gravity")
    cogs = None if cogs is None else np.asarray(cogs, dtype=float).reshape(-1, 3)
    out = []
    for k in range(len(groups)):
        center = cogs[k] if cogs is not None and len(cogs) == len(groups) else centers[k]
        out.append(BodyWeight(float("nan"), np.asarray(center, dtype=float).reshape(3)))
    del masses
    return out


def _rigid_index(labels: list[str], body: str | None) -> dict[int, int | None]:
    """Position in the dataset of each of the body's six rigid DOFs (None if absent)."""
    out: dict[int, int | None] = {}
    for a, name in enumerate(DOF_NAMES):
        label = f"{body}__{name}" if body else name
        out[a] = labels.index(label) if label in labels else None
    return out


def _file_name(ds: xr.Dataset) -> str:
    from pathlib import Path

    source = str(ds.attrs.get("source_file", "") or "")
    return Path(source).name if source else "the data"


def body_volumes(ds: xr.Dataset, count: int) -> NDArray[np.float64]:
    """The displaced volume of each of ``count`` bodies, m³ (NaN where not recorded)."""
    v = np.atleast_1d(np.asarray(ds.attrs.get("displaced_volume", np.nan), dtype=float))
    v = v.reshape(-1)
    return v if v.size == count else np.full(count, np.nan)


def moved_restoring(
    ds: xr.Dataset, old: NDArray[np.float64], new: NDArray[np.float64]
) -> tuple[xr.Dataset, str]:
    """The correction the screw transform of the restoring misses when the body is not in
    equilibrium in it — the restoring holds the hydrostatics alone, or the weight of a
    mass m other than ρ∇ (a buoyant flap on its hinge) — for a move of the reference
    point from ``old`` to ``new`` (m, one row per body), applied to ``ds`` (whose matrices
    are already transformed).

    The restoring of buoyancy and weight together, in equilibrium (weight ρ∇ above the
    centre of buoyancy), has no static load and transforms as the other matrices,
    Hᵀ C H (Smogeli et al. (2004) eq. 38). The buoyancy's own part about O,
    ρ g (∫y² dA + ∇ (z_B − z_O)) in C₄₄, −ρ g ∇ (x_B − x_O) in C₄₆ … (WAMIT (2020)
    §3.1), carries the static load ρ g ∇, and the weight's part W(m (G − O))
    (:func:`weight_stiffness`), which Hᵀ · H leaves unchanged, the load −m g: it becomes

        C(O_new) = Hᵀ C(O_old) H + W((ρ∇ − m) (O_new − O_old)),

    C₄₄ and C₅₅ −(ρ∇ − m) g Δz, with m = 0 for the hydrostatics alone. A restoring
    recorded to hold the body's own weight (ρ∇), a mass within
    :data:`~cummins.mechanics.preload.BALANCED` of it (the rounding, as the joints'
    pre-load takes it) or a given mass when the displaced volume is not known (taken as
    in equilibrium) is left to the screw transform.

    Returns
    -------
    (xarray.Dataset, str)
        The dataset, and a note for ``history`` (empty when nothing changed). A restoring
        not recorded to hold a weight is taken as the hydrostatics alone (OpenFAST's
        convention, as :func:`with_weight`); when its volume is not recorded, the dataset
        is returned as it is with an :class:`~cummins.errors.AssumptionWarning`.
    """
    if "hydrostatic_stiffness" not in ds:
        return ds, ""
    from cummins.mechanics.preload import net_buoyancy

    groups = bodies(ds)
    shift = np.asarray(new, dtype=float).reshape(-1, 3) - np.asarray(old, dtype=float).reshape(
        -1, 3
    )
    if not np.any(shift != 0):
        return ds, ""
    recorded = recorded_weight(ds)
    if recorded is not None and len(recorded) != len(groups):
        recorded = None
    rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
    volumes = body_volumes(ds, len(groups))
    axes = str(ds.attrs.get("axis_convention", "z-up"))
    labels = [str(d) for d in ds.influenced_dof.values]
    delta = np.zeros((len(labels), len(labels)))
    notes, unknown = [], []
    for k, body in enumerate(groups):
        step = shift[min(k, len(shift) - 1)]
        held = 0.0 if recorded is None else recorded[k].mass
        if not np.any(step != 0) or np.isnan(held):
            continue  # the body's own weight ρ∇ held, in equilibrium: the screw transform
        if not np.isfinite(volumes[k]):
            if held == 0:  # a given weight with no volume is taken as in equilibrium
                unknown.append(body or "the body")
            continue
        net = net_buoyancy(rho * volumes[k], held)  # kg: the static load (ρ∇ − m) g
        if net == 0:
            continue  # floating freely up to the rounding: no load, as the joints' pre-load
        load = weight_stiffness(net * step, g, axes)
        index = _rigid_index(labels, body)
        for a, i in index.items():
            for b, j in index.items():
                if i is not None and j is not None:
                    delta[i, j] += load[a, b]
        what = (
            "restoring of the hydrostatics alone"
            + (" (assumed: not recorded)" if recorded is None else "")
            + " moved with its static load rho g V"
            if held == 0
            else f"restoring holding the weight of {held:.6g} kg, not rho V = "
            f"{rho * volumes[k]:.6g} kg, moved with its static load (rho V - m) g"
        )
        notes.append(f"{body + ': ' if body else ''}{what} (C44, C55 {load[3, 3]:+.6g})")
    if unknown:
        warnings.warn(
            AssumptionWarning(
                f"{_file_name(ds)}: the restoring of {', '.join(unknown)} was moved to the new "
                "reference point as the other matrices, which is exact if it holds the "
                "weight of m = rho V; if it holds the hydrostatics alone (as OpenFAST's "
                "files) C44, C55 change by -rho g V dz: give the displaced volume "
                "(--displaced-volume)"
            ),
            stacklevel=3,
        )
    if not notes:
        return ds, ""
    da = ds["hydrostatic_stiffness"]
    coords = {"influenced_dof": ds.influenced_dof.values, "radiating_dof": ds.radiating_dof.values}
    moved = da + xr.DataArray(delta, dims=("influenced_dof", "radiating_dof"), coords=coords)
    out = ds.copy()
    out["hydrostatic_stiffness"] = moved.transpose(*da.dims).assign_attrs(da.attrs)
    return out, "; ".join(notes)


@dataclass(frozen=True)
class HydrostaticRestoring:
    """The restoring of buoyancy and waterplane alone about the reference point
    (:func:`hydrostatic_restoring`): the dataset, and one line saying what was done
    (``known``: False when the files do not say whether the weight was included)."""

    ds: xr.Dataset
    note: str
    known: bool


def hydrostatic_restoring(ds: xr.Dataset) -> HydrostaticRestoring:
    """The dataset whose restoring holds the buoyancy and the waterplane alone, about its
    reference point: the weight's terms the files record (:func:`recorded_weight`)
    removed, C − W(m (G − O)) (:func:`weight_stiffness`; WAMIT (2020) §3.1). This is what
    OpenFAST's HydroDyn reads from a WAMIT ``.hst``: ElastoDyn adds the platform's weight.

    A restoring whose weight is the body's own mass, not recorded (WAMIT's ``.frc``
    without the ``.out``), takes m = ρ∇ from ``displaced_volume``. When the files do not
    say whether the weight is included, the restoring is returned as it is (``known``
    False: the caller warns).

    Raises
    ------
    HydroDataError
        The weight's mass is the body's own, its centre is not the reference point and
        the displaced volume is not known.
    """
    if "hydrostatic_stiffness" not in ds:
        return HydrostaticRestoring(ds, "", True)
    groups = bodies(ds)
    recorded = recorded_weight(ds)
    if recorded is None or len(recorded) != len(groups):
        return HydrostaticRestoring(
            ds,
            f"{_file_name(ds)}: the files do not say whether the restoring holds the weight's "
            "terms: written as read, taken as the hydrostatics alone (OpenFAST's convention)",
            False,
        )
    refs = reference_points(ds)
    volumes = body_volumes(ds, len(groups))
    rho = float(ds.attrs["rho"])
    masses = []
    for k, w in enumerate(recorded):
        ref = refs[k] if len(refs) == len(groups) else refs[0]
        lever = np.any(np.abs(w.center - ref) > 1e-9)
        if np.isnan(w.mass) and lever and not np.isfinite(volumes[k]):
            raise HydroDataError(
                f"the restoring holds the weight of {groups[k] or 'the body'}'s own mass at "
                f"{np.round(w.center, 6).tolist()} m, which the files do not give: it cannot "
                "be taken out",
                path=ds.attrs.get("source_file"),
                hint="give the displaced volume (--displaced-volume M3): m = rho V",
            )
        masses.append(rho * volumes[k] if np.isnan(w.mass) else w.mass)
    if all(
        m == 0 or not np.any(np.abs(w.center - refs[min(k, len(refs) - 1)]) > 1e-9)
        for k, (m, w) in enumerate(zip(masses, recorded, strict=True))
    ):
        return HydrostaticRestoring(
            ds,
            "restoring: buoyancy and waterplane alone (no weight terms about the reference point)",
            True,
        )
    filled = ds.copy()
    filled.attrs[WEIGHT_MASS] = masses[0] if len(masses) == 1 else np.asarray(masses)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AssumptionWarning)
        out = with_weight(
            filled,
            [0.0] * len(groups),
            [refs[min(k, len(refs) - 1)] for k in range(len(groups))],
            why="removed: hydrostatics alone, as HydroDyn reads them",
        )
    c0 = restoring_matrix(ds, additional=False)
    c1 = restoring_matrix(out, additional=False)
    changed = [
        f"C{i + 1}{j + 1} {c1[i, j] - c0[i, j]:+.4g}"
        for i, j in zip(*np.nonzero(np.abs(c1 - c0) > 1e-9 * np.abs(c0).max()), strict=True)
    ]
    weights = "; ".join(
        _weight_text(BodyWeight(m, w.center)) for m, w in zip(masses, recorded, strict=True)
    )
    return HydrostaticRestoring(
        out,
        f"restoring: the weight's terms ({weights}) taken out, buoyancy and waterplane "
        f"alone as HydroDyn reads them ({', '.join(changed[:4])})",
        True,
    )


# --------------------------------------------------------------------------- stability


@dataclass(frozen=True)
class StaticInstability:
    """A negative eigenvalue of the restoring on the DOFs that have restoring: the DOF
    that dominates its mode, and that DOF's own restoring coefficient."""

    dof: str
    stiffness: float

    def describe(self) -> str:
        """``"body1__Pitch (C = -1.934e+06)"``: the DOF and its own restoring."""
        return f"{self.dof} (C = {self.stiffness:.4g})"


def static_instability(
    stiffness: ArrayLike, dofs: Sequence[str], basis: ArrayLike | None = None
) -> list[StaticInstability]:
    """The statically unstable modes of a restoring matrix C (hydrostatics, weight,
    moorings): the negative eigenvalues of its symmetric part on the DOFs whose own
    restoring is not zero (surge, sway and yaw of a free body drift, they are not
    unstable). The count of negative eigenvalues does not depend on the units of the DOFs
    (Sylvester's law of inertia), so C is scaled by its diagonal first.

    Parameters
    ----------
    stiffness
        C (n, n) of the DOFs ``dofs``.
    dofs
        Their labels.
    basis
        For bodies joined by joints, the basis T (n, m) of the motions they allow
        (ξ = T q, :mod:`cummins.mechanics`): the test is then on Tᵀ C T, and a mode is
        named by the DOF with the largest share of T v.

    Returns
    -------
    list of StaticInstability
        One per negative eigenvalue, naming the DOF with the largest share of its mode;
        empty for a stable body.
    """
    c = np.asarray(stiffness, dtype=float)
    labels = [str(d) for d in dofs]
    if not np.all(np.isfinite(c)):
        return []
    t = np.eye(c.shape[0]) if basis is None else np.asarray(basis, dtype=float)
    cq = t.T @ c @ t
    diagonal = np.abs(np.diag(cq))
    if not diagonal.size or diagonal.max() == 0:
        return []
    # a diagonal of round-off (1e-12 in surge) is no restoring: judged against the largest
    # of its kind (translations N/m, rotations N m/rad, generalized modes), not of all;
    # a coordinate's kind is that of the DOF that carries most of it
    lead = np.argmax(np.abs(t), axis=0)
    kinds = np.array(
        [2 if not is_rigid_body_dof(labels[i]) else int(is_rotation(labels[i])) for i in lead]
    )
    largest = np.array([diagonal[kinds == k].max() for k in kinds])
    active = np.flatnonzero(diagonal > 1e-9 * largest)
    if not active.size:
        return []
    sub = 0.5 * (cq + cq.T)[np.ix_(active, active)]
    scale = 1.0 / np.sqrt(diagonal[active])
    lam, vec = np.linalg.eigh(sub * scale[:, None] * scale[None, :])
    found = set()
    for k in np.flatnonzero(lam < -1e-9):
        v = np.zeros(cq.shape[0])
        v[active] = scale * vec[:, k]
        found.add(int(np.argmax(np.abs(t @ v))))
    return [StaticInstability(labels[i], float(c[i, i])) for i in sorted(found)]


def instability_message(unstable: Sequence[StaticInstability]) -> str:
    """The sentence :func:`cummins.motion_rao` warns with and the time domain refuses
    with."""
    listed = ", ".join(u.describe() for u in unstable)
    return (
        f"the body is statically unstable in {listed}: the restoring matrix (hydrostatics, "
        "weight, moorings, PTO springs) has a negative eigenvalue there, so the body has "
        "no equilibrium to oscillate about"
    )


def unrestrained_modes(stiffness: ArrayLike, dofs: Sequence[str]) -> list[str]:
    """The generalized modes (``Mode7`` …: an OWC's piston, a flexible mode) whose own
    restoring, moorings and PTO springs included, is zero. A rigid body's surge, sway
    and yaw drift without one, as they should; a generalized mode with none is a missing
    input (WAMIT writes zero hydrostatics for a generalized mode unless its DEFMOD gives
    them), and its motion grows as 1/ω² in long waves."""
    c = np.asarray(stiffness, dtype=float)
    return [
        str(d)
        for k, d in enumerate(dofs)
        if not is_rigid_body_dof(str(d)) and np.all(c[k, :] == 0) and np.all(c[:, k] == 0)
    ]


def unrestrained_message(modes: Sequence[str]) -> str:
    """The warning of :func:`unrestrained_modes` (``rao`` and ``simulate`` alike)."""
    first = modes[0]
    return (
        f"{', '.join(modes)}: no restoring (zero rows of the data's restoring, and no "
        "mooring or PTO spring): the motion grows without bound in long waves; give its "
        f"stiffness (--external-stiffness {first} {first} K; an oscillating water "
        "column's piston mode: ρ g times the area of its free surface)"
    )


#: What to do about a statically unstable body.
INSTABILITY_HINT = (
    "Check the centre of gravity and whether the restoring holds the weight's terms "
    "(cummins info says where C came from; --center-of-gravity, "
    "--restoring-includes-weight), or give the hinge or mooring that holds the body "
    "(--external-stiffness); a negative PTO stiffness (--pto-stiffness, reactive control) "
    "must stay smaller than the restoring it acts against"
)


def restoring_matrix(ds: xr.Dataset, additional: bool = True) -> NDArray[np.float64]:
    """C of the equation of motion: ``hydrostatic_stiffness`` plus, with ``additional``,
    the data's ``additional_stiffness`` (moorings, external springs)."""
    c = np.array(
        ds["hydrostatic_stiffness"].transpose("influenced_dof", "radiating_dof").values,
        dtype=float,
    )
    if additional and "additional_stiffness" in ds:
        c = c + ds["additional_stiffness"].transpose("influenced_dof", "radiating_dof").values
    return c


__all__ = [
    "INCLUDES",
    "INSTABILITY_HINT",
    "BodyWeight",
    "HydrostaticRestoring",
    "StaticInstability",
    "body_volumes",
    "describe_restoring",
    "hydrostatic_restoring",
    "instability_message",
    "moved_restoring",
    "recorded_weight",
    "restoring_matrix",
    "static_instability",
    "unrestrained_message",
    "unrestrained_modes",
    "weight_record",
    "weight_stiffness",
    "with_weight",
]
