"""The ``forbidden_couplings`` check: radiation couplings that the body's own symmetry
forbids, judged from the data.

A body symmetric about its x–z plane (port/starboard) radiates no coupling between the
DOFs that keep their sign under y → −y (surge, heave, pitch) and those that change it
(sway, roll, yaw): A and B of those pairs vanish. A body of revolution about z (or one
with N ≥ 3 planes of symmetry through z: its 6×6 matrices are the same) keeps only the
diagonal terms, A₁₁ = A₂₂, A₄₄ = A₅₅, and surge–pitch and sway–roll, A₁₅ = −A₂₄
(Newman (1977) ch. 4, the added mass of a body with planes of symmetry; the damping
alike). A solver that does not exploit the symmetry prints noise there; where the noise
is as large as the couplings ``cummins fit`` models (its ``--threshold``), the fit joins
DOFs the physics keeps apart in one block of common poles and fits the noise.

The symmetry is never assumed, it is read from the data, per body (:func:`body_symmetry`):

* rotational symmetry about z from the diagonals: A₁₁ = A₂₂, B₁₁ = B₂₂, A₄₄ = A₅₅,
  B₄₄ = B₅₅ at every frequency to :data:`ROTATION_TOL` of their largest value;
* the port/starboard mirror from the wave forces: F(ω, −β) = T F(ω, β) at the
  mirrored headings (head and following seas: no sway force) to
  :data:`~cummins.check.common.PARITY_TOL` of the largest force; or, for a body whose
  diagonals say rotational, the forces at several headings those of a body of
  revolution (the horizontal and the heave force of the same size at every heading),
  which has every vertical plane through its axis as a plane of symmetry. The forces,
  not the moments: the excitation moments come from the same solution as the radiation
  moments (Haskind's relations) and carry the same noise (the HAMS cylinders: the
  forces mirror to 1 %, the moments to 10 %, as the roll–pitch coupling), so the
  moments would let the noise judge itself; their mismatch is reported. A body
  without excitation is judged from its diagonals alone.

Each body's forbidden couplings are measured as ``cummins fit`` measures a coupling
(:func:`cummins.radiation.retardation.coupling_sizes`: max|B_ij| and the range of A_ij
over the geometric mean of the diagonal terms, X_ij and X_ji alike). One that the fit
would model (above its default threshold, :data:`FIT_THRESHOLD`) and that the body's
measured asymmetry ε does not explain (above :data:`EXPLAINED` ε: a body a little
off symmetric has forbidden couplings of the order of its asymmetry) is a warning.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from cummins.check.common import PARITY_TOL, PreparedFits, _speed_suffix, _speeds
from cummins.check.parity import mirror_pairs
from cummins.check.report import Finding
from cummins.hydrodb import DOF_NAMES, bodies, split_dof

if TYPE_CHECKING:
    from cummins.repair import Judged

#: Largest relative difference of surge/sway and roll/pitch diagonals (A and B, each
#: over the larger of the two) of a body taken as rotationally symmetric. The corpus:
#: the HAMS cylinders 0.6 %, the other bodies of revolution of WAMIT, NEMOH, AQWA,
#: Capytaine ≤ 0.44 % (the RM3 spar/plate), AQWA's pendulum hull 0.9 %; the WAMIT
#: drift sphere 3.4 % (its roll and pitch about the centre: noise of nothing), the two
#: NEMOH cubes side by side 5–8 %, ships, flaps and the long GBM barge ≥ 50 %.
ROTATION_TOL = 0.02

#: A forbidden coupling is noise beyond the body's own asymmetry ε (the relative
#: mismatch of the evidence that found the symmetry) when larger than EXPLAINED · ε.
EXPLAINED = 2.0

#: The coupling size above which ``cummins fit`` models a coupling (its default
#: ``--threshold``, :class:`cummins.radiation.fit.options.FitOptions`).
FIT_THRESHOLD = 0.01

#: Size below which a forbidden coupling is reported as nothing (the heading module's
#: symmetry tolerance, :data:`cummins.seakeeping.headings.SYMMETRY_TOLERANCE`).
NEGLIGIBLE = 1e-3

#: The DOFs that keep their sign under y → −y.
_SYMMETRIC = ("Surge", "Heave", "Pitch")
#: Couplings a body of revolution keeps (beyond the diagonal).
_AXISYMMETRIC_KEPT = {("Surge", "Pitch"), ("Sway", "Roll")}
#: Couplings an N-fold rotational symmetry without a mirror plane keeps (A₁₄ = A₂₅, A₃₆).
_ROTATION_KEPT = _AXISYMMETRIC_KEPT | {("Surge", "Roll"), ("Sway", "Pitch"), ("Heave", "Yaw")}


@dataclass(frozen=True)
class BodySymmetry:
    """The symmetry of one body, as its data show it.

    Attributes
    ----------
    body
        The body's name (None for the DOFs of a single unnamed body).
    mirror
        Symmetric about its x–z plane (port/starboard).
    rotational
        Rotationally symmetric about its z axis (its diagonals).
    mirror_asymmetry
        ε of the evidence for the mirror (relative), None when there is none.
    rotation_asymmetry
        The diagonals' largest relative mismatch (surge/sway, roll/pitch).
    evidence
        One clause: what found it.
    revolution
        The excitation at several headings is a body of revolution's.
    """

    body: str | None
    mirror: bool
    rotational: bool
    mirror_asymmetry: float | None
    rotation_asymmetry: float
    evidence: str
    revolution: bool = False

    @property
    def name(self) -> str:
        """What the symmetry is called in the findings."""
        if self.mirror and self.rotational:
            if self.revolution:
                return "axisymmetric"
            return "port/starboard symmetric and rotationally symmetric about z"
        if self.rotational:
            return "rotationally symmetric about z"
        return "port/starboard symmetric" if self.mirror else "not symmetric"

    def forbids(self, p: str, q: str) -> float | None:
        """ε of the symmetry that forbids the coupling of DOFs ``p``–``q`` (the smaller
        when both do), None when none does."""
        found = []
        if self.mirror and ((p in _SYMMETRIC) != (q in _SYMMETRIC)):
            found.append(self.mirror_asymmetry or 0.0)
        pair = tuple(sorted((p, q), key=DOF_NAMES.index))
        if self.rotational:
            kept = _AXISYMMETRIC_KEPT if self.mirror else _ROTATION_KEPT
            if pair not in kept:
                found.append(self.rotation_asymmetry)
        return min(found) if found else None


def _rigid_columns(labels: list[str], body: str | None) -> list[int] | None:
    """The six rigid-body DOFs of ``body``, in DOF order, or None when one is missing."""
    where = {split_dof(lab)[1]: i for i, lab in enumerate(labels) if split_dof(lab)[0] == body}
    if not all(d in where for d in DOF_NAMES):
        return None
    return [where[d] for d in DOF_NAMES]


def diagonal_mismatch(a: np.ndarray, b: np.ndarray, cols: list[int]) -> float:
    """max over ω of |X₁₁ − X₂₂| and |X₄₄ − X₅₅| (X = A, B), each over the larger of the
    two diagonals' largest magnitude: 0 for a body of revolution. ``a``, ``b`` are
    (omega, dof, dof)."""
    worst = 0.0
    for m in (a, b):
        for p, q in ((0, 1), (3, 4)):
            x, y = m[:, cols[p], cols[p]], m[:, cols[q], cols[q]]
            scale = max(np.abs(x).max(), np.abs(y).max())
            if scale > 0:
                worst = max(worst, float(np.abs(x - y).max() / scale))
    return worst


def mirror_mismatch(force: np.ndarray, beta: np.ndarray) -> tuple[float, float] | None:
    """max |F(ω, −β) − T F(ω, β)| over the mirrored headings and ω, of the forces (over
    the largest force) and of the moments (over the largest moment); None without
    mirrored headings. ``force`` is (omega, wave_direction, 6), surge … yaw."""
    from cummins.seakeeping.headings import MIRROR_SIGNS

    pairs = mirror_pairs(beta)
    if not pairs:
        return None
    scale = _kind_scale(force)
    worst = np.zeros(6)
    for k, m in pairs:
        d = np.abs(force[:, m] - MIRROR_SIGNS * force[:, k]).max(axis=0) / scale
        worst = np.maximum(worst, d)
    return float(worst[:3].max()), float(worst[3:].max())


def revolution_mismatch(force: np.ndarray, beta: np.ndarray) -> tuple[float, float] | None:
    """How far the excitation is from a body of revolution's: the spread over the
    headings, at each ω, of |F_horizontal| and |F₃| (over the largest force), and of
    |M_horizontal| and |M₆| itself (over the largest moment); None without two
    headings that are not 180° apart (a body with two planes of symmetry has the same
    sizes there)."""
    b = np.mod(np.asarray(beta, dtype=float), np.pi)
    if b.size < 2 or np.abs(np.angle(np.exp(2j * (b - b[0])))).max() < 1e-6:
        return None
    scale = _kind_scale(force)
    mag = np.abs(force)
    forces = max(
        float(np.ptp(np.hypot(mag[..., 0], mag[..., 1]), axis=1).max()),
        float(np.ptp(mag[..., 2], axis=1).max()),
    )
    moments = max(
        float(np.ptp(np.hypot(mag[..., 3], mag[..., 4]), axis=1).max()),
        float(mag[..., 5].max()),
    )
    return forces / scale[0], moments / scale[3]


def _kind_scale(force: np.ndarray) -> np.ndarray:
    """Per DOF, the largest force (translations) or moment (rotations) of the body."""
    mag = np.abs(force).max(axis=(0, 1))
    forces, moments = mag[:3].max(), mag[3:].max()
    scale = np.array([forces] * 3 + [moments] * 3)
    return np.where(scale > 0, scale, 1.0)


def body_symmetry(ds: xr.Dataset, body: str | None) -> BodySymmetry | None:
    """The symmetry of ``body`` judged from its diagonals and its excitation (module
    docstring); None when the body lacks one of the six rigid-body DOFs. ``ds`` is one
    forward speed."""
    from cummins.hydrodb import dof_matrix

    labels = [str(d) for d in ds.influenced_dof.values]
    cols = _rigid_columns(labels, body)
    if cols is None:
        return None
    a, b = dof_matrix(ds, "added_mass"), dof_matrix(ds, "radiation_damping")
    rot = diagonal_mismatch(a, b, cols)
    rotational = rot <= ROTATION_TOL
    mirror = revolution = None
    along = False
    if "excitation_force" in ds and "wave_direction" in ds.dims:
        along = all(k == m for k, m in mirror_pairs(ds.wave_direction.values))
        f = ds.excitation_force.transpose("omega", "wave_direction", "influenced_dof").values
        f, beta = f[:, :, cols], ds.wave_direction.values
        mirror = mirror_mismatch(f, beta)
        if rotational:
            revolution = revolution_mismatch(f, beta)
    diag = f"its surge/sway and roll/pitch diagonals agree to {_pct(rot)}"
    found = [
        (eps, revolved)
        for eps, revolved in ((mirror, False), (revolution, True))
        if eps is not None and eps[0] <= PARITY_TOL
    ]
    if found:
        (eps, moments), revolved = min(found, key=lambda item: item[0][0])
        text = (
            "its wave forces are those of a body of revolution at every heading"
            if revolved
            else "it has no sway force in waves along x"
            if along
            else "its wave forces mirror with the heading"
        ) + f" (to {_pct(eps)} of the largest force"
        if moments > PARITY_TOL:
            text += f"; the moments to {_pct(moments)} of the largest moment"
        text += ")"
        if rotational:
            text += f", {diag}"
        shown = revolution is not None and revolution[0] <= PARITY_TOL
        return BodySymmetry(body, True, rotational, eps, rot, text, shown)
    if rotational:
        why = (
            "no excitation to judge the port/starboard mirror by"
            if mirror is None and revolution is None
            else "its wave forces show no plane of symmetry"
        )
        return BodySymmetry(body, False, True, None, rot, f"{diag}; {why}")
    return BodySymmetry(body, False, False, None, rot, "")


@dataclass(frozen=True)
class ForbiddenCoupling:
    """A coupling the body's symmetry forbids: its DOF indices, names (``Roll–Pitch``),
    size as the fit measures it, the asymmetry ε of the symmetry that forbids it,
    whether ``cummins fit`` models it, and whether both DOFs have a damping of their own
    (else the fit leaves the coupling out: the yaw of a body of revolution)."""

    pair: tuple[int, int]
    names: str
    size: float
    explained: float
    fitted: bool
    active: bool

    @property
    def costly(self) -> bool:
        """``cummins fit`` models it, and the body's asymmetry does not explain it."""
        return self.fitted and self.size > EXPLAINED * self.explained


def fitted_pairs(
    ds: xr.Dataset, judged: Judged = (), prepared: PreparedFits | None = None
) -> list[tuple[int, int]]:
    """The couplings (i ≤ j) ``cummins fit`` models with its default options, as its own
    preparation of the data decides (:func:`cummins.radiation.fit.data.prepare_fit`: the
    size above :data:`FIT_THRESHOLD`, X_ij deciding, or the pairs fitted as given);
    without a fit (the data cannot be fitted: other checks say why), the pairs whose
    size exceeds the threshold. ``judged``: data whose suspect frequencies were found
    already (:func:`cummins.repair.suspects_by_dof`); ``prepared``: the preparations of
    the data shared by the checks (made here when not given)."""
    from cummins.radiation.retardation import significant_couplings

    inp = (prepared or PreparedFits(judged))(ds)
    if inp is None:
        return significant_couplings(ds, FIT_THRESHOLD)
    return list(inp.pairs)


def forbidden_couplings(
    ds: xr.Dataset, symmetry: BodySymmetry, fitted: list[tuple[int, int]]
) -> list[ForbiddenCoupling]:
    """The couplings of ``symmetry.body`` that its symmetry forbids, largest first, with
    their size as ``cummins fit`` measures it (X_ij and X_ji alike) and whether it models
    them (``fitted``, :func:`fitted_pairs`)."""
    from cummins.radiation.retardation import coupling_sizes

    labels = [str(d) for d in ds.influenced_dof.values]
    cols = _rigid_columns(labels, symmetry.body)
    if cols is None:
        return []
    sizes, modelled = coupling_sizes(ds, either=True)
    fitted_set = set(fitted)
    out = []
    for p in range(6):
        for q in range(p + 1, 6):
            eps = symmetry.forbids(DOF_NAMES[p], DOF_NAMES[q])
            if eps is None:
                continue
            i, j = cols[p], cols[q]
            out.append(
                ForbiddenCoupling(
                    (i, j),
                    f"{DOF_NAMES[p]}–{DOF_NAMES[q]}",
                    float(sizes[i, j]),
                    eps,
                    (min(i, j), max(i, j)) in fitted_set,
                    bool(modelled[i] and modelled[j]),
                )
            )
    return sorted(out, key=lambda c: -c.size)


def symmetry_plane_offset(
    ds: xr.Dataset, symmetry: BodySymmetry, fitted: list[tuple[int, int]]
) -> tuple[float, float] | None:
    """The y of the body's plane of symmetry when its couplings say it is not y = 0:
    about a point off the plane by e, a port/starboard symmetric body has the couplings
    of the moved moments, A₃₄ = −e A₃₃, A₁₆ = e A₁₁, A₄₅ = −e A₃₅ … (the screw transform,
    Smogeli et al. (2004) eq. 45). e is the least-squares ratio −A₃₄/A₃₃; returned
    (y of the plane, the largest forbidden coupling about the point moved there) when,
    about that point, no coupling the mirror forbids is costly any more; else None."""
    from cummins.errors import CumminsError
    from cummins.hydrodb import dof_matrix, move_reference_point, reference_points

    if not symmetry.mirror:
        return None
    labels = [str(d) for d in ds.influenced_dof.values]
    cols = _rigid_columns(labels, symmetry.body)
    a = dof_matrix(ds, "added_mass")
    heave, roll = a[:, cols[2], cols[2]], a[:, cols[2], cols[3]]
    if not np.any(heave):
        return None
    e = -float(heave @ roll / (heave @ heave))
    points = reference_points(ds).copy()
    radiation = ds[["added_mass", "radiation_damping"]]
    index = bodies(ds).index(symmetry.body) if len(points) > 1 else 0
    best = None
    for sign in (1.0, -1.0):
        moved_points = points.copy()
        moved_points[index, 1] += sign * e
        try:
            with warnings.catch_warnings():  # the radiation alone is moved: nothing to say
                warnings.simplefilter("ignore")
                moved = move_reference_point(
                    radiation, moved_points if len(points) > 1 else moved_points[0]
                )
        except (CumminsError, ValueError):  # a diagnosis, never a failure of the check
            return None
        plane = BodySymmetry(
            symmetry.body, True, False, symmetry.mirror_asymmetry, 1.0, symmetry.evidence
        )
        left = forbidden_couplings(moved, plane, fitted)
        worst = max((c.size for c in left if c.active), default=0.0)
        if best is None or worst < best[1]:
            best = (float(moved_points[index, 1]), worst, left)
    y, worst, left = best
    if any(c.size > max(FIT_THRESHOLD, EXPLAINED * c.explained) for c in left if c.active):
        return None
    return y, worst


def _joined_block(
    ds: xr.Dataset, costly: list[ForbiddenCoupling], pairs: list[tuple[int, int]]
) -> tuple[str, str]:
    """The fit's block that holds the costly couplings, and the blocks it falls into
    without them (DOF names)."""
    from cummins.radiation.fit.order_search import block_groups

    labels = [str(d) for d in ds.influenced_dof.values]
    dof = min(costly[0].pair)
    block = next(dofs for dofs, _ in block_groups(len(labels), pairs) if dof in dofs)
    drop = {(min(c.pair), max(c.pair)) for c in costly}
    rest = [pair for pair in pairs if pair not in drop]
    apart = [dofs for dofs, _ in block_groups(len(labels), rest) if set(dofs) <= set(block)]

    def names(dofs) -> str:
        return ", ".join(labels[i] for i in dofs)

    return names(block), "; ".join(names(d) for d in apart)


def _check_forbidden_couplings(
    ds: xr.Dataset, judged: Judged = (), prepared: PreparedFits | None = None
) -> list[Finding]:
    """Per body and forward speed: the radiation couplings its symmetry forbids (a
    warning where ``cummins fit`` would model them, an info where it would model them
    but the body's asymmetry explains them, ok otherwise); ``judged`` and ``prepared``
    as :func:`fitted_pairs`."""
    out: list[Finding] = []
    for sub in _speeds(ds):
        found = [s for s in (body_symmetry(sub, body) for body in bodies(sub)) if s is not None]
        if not found:
            continue
        # the fit's own choice of couplings (a preparation of the data) only where a
        # forbidden coupling is large enough for it to matter
        large = any(
            c.active and c.size > FIT_THRESHOLD
            for symmetry in found
            for c in forbidden_couplings(sub, symmetry, [])
        )
        fitted = fitted_pairs(sub, judged, prepared) if large else []
        out.extend(_body_finding(sub, symmetry, fitted) for symmetry in found)
    return out


def _body_finding(
    sub: xr.Dataset, symmetry: BodySymmetry, fitted: list[tuple[int, int]]
) -> Finding:
    """The finding of one body (module docstring)."""
    where = (symmetry.body or "") + _speed_suffix(sub) or None
    if not (symmetry.mirror or symmetry.rotational):
        return Finding(
            "forbidden_couplings",
            "ok",
            "no port/starboard or rotational symmetry in the data (surge/sway and "
            f"roll/pitch diagonals {_pct(symmetry.rotation_asymmetry)} apart, "
            + (
                "the wave forces do not mirror with the heading"
                if "excitation_force" in sub
                else "no excitation"
            )
            + "): no coupling to rule out",
            where=where,
        )
    found = forbidden_couplings(sub, symmetry, fitted)
    costly = [c for c in found if c.costly]
    details = {
        "symmetry": symmetry.name,
        "evidence": symmetry.evidence,
        "mirror_asymmetry": symmetry.mirror_asymmetry,
        "rotation_asymmetry": symmetry.rotation_asymmetry,
        "couplings": {c.names: float(c.size) for c in found if c.active and c.size > NEGLIGIBLE},
        "fit_threshold": FIT_THRESHOLD,
    }
    head = f"the body is {symmetry.name}: {symmetry.evidence}"
    if not costly:
        modelled = [c for c in found if c.fitted]
        if modelled:
            listed = ", ".join(f"{c.names} {_pct(c.size)}" for c in modelled)
            return Finding(
                "forbidden_couplings",
                "info",
                f"{head}; couplings its symmetry forbids reach {listed} of their "
                f"diagonals, which cummins fit models, within {EXPLAINED:g}× the body's "
                "own asymmetry",
                where=where,
                value=modelled[0].size,
                details=details,
            )
        size = max((c.size for c in found if c.active), default=0.0)
        return Finding(
            "forbidden_couplings",
            "ok",
            f"{head}; the couplings its symmetry forbids "
            + (
                f"reach at most {_pct(size)} of their diagonals, none of them modelled by "
                "cummins fit"
                if size > NEGLIGIBLE
                else f"stay below {_pct(NEGLIGIBLE)} of their diagonals"
            ),
            where=where,
            value=size,
            details=details,
        )
    listed = ", ".join(f"{c.names} {_pct(c.size)}" for c in costly)
    block, apart = _joined_block(sub, costly, fitted)
    eps = min(c.explained for c in costly)
    level = float(f"{costly[0].size * 1.05:.2g}")
    details.update(
        costly={c.names: float(c.size) for c in costly},
        fit_block=block,
        threshold_leaving_them_out=level,
    )
    plane = symmetry_plane_offset(sub, symmetry, fitted)
    cause = (
        "the solver's numerical noise, or a mesh or reference point off the symmetry the "
        "rest of the data keep"
    )
    first = ""
    if plane is not None:
        details.update(symmetry_plane_y=plane[0], couplings_about_plane=plane[1])
        cause = (
            f"they are those of a body whose plane of symmetry is y = {plane[0]:.4g}, not "
            f"the reference point's y: about a point on it they fall to {_pct(plane[1])}"
        )
        first = (
            f"check the mesh's position, or take the data about a point on y = "
            f"{plane[0]:.4g} (cummins.move_reference_point); otherwise "
        )
    return Finding(
        "forbidden_couplings",
        "warning",
        f"{head}; yet couplings its symmetry forbids reach {listed} of their diagonals "
        f"(the size cummins fit gives a coupling, which it models above {FIT_THRESHOLD:g}; "
        f"the body's asymmetry would explain {_pct(EXPLAINED * eps)}): {cause}. "
        f"cummins fit takes them for physics and joins {block} in one block of "
        "common poles" + (f", where the symmetry keeps {apart} apart" if apart else ""),
        where=where,
        value=costly[0].size,
        advice=first
        + (
            "solve again with a finer mesh, or with the body's planes of symmetry declared "
            "to the solver (WAMIT's ISX/ISY, the x/y symmetry flags of HAMS's "
            "HullMesh.pnl), which makes these couplings exactly zero; or fit with "
            f"--threshold {level:g}, which leaves out every coupling smaller than that: "
            f"{_also_left_out(found, fitted, sub, level)}fewer states and a faster fit "
            "that keeps the symmetry, but the data's own RAOs hold these couplings, so the "
            "model's motions then differ more from them (the HAMS benchmark cylinder at "
            "--threshold 0.2: fit 1.05 → 0.18 s, failed targets 13 → 2, motion error "
            "against the data's RAOs 12.6 → 25.5 %). Which to trust is the user's choice"
        ),
        details=details,
    )


def _pct(x: float) -> str:
    """A relative size as a percentage, two significant digits (``0.6 %``)."""
    return f"{100 * float(x):.2g} %" if x >= 1e-4 else "< 0.01 %"


def _also_left_out(
    found: list[ForbiddenCoupling], fitted: list[tuple[int, int]], sub: xr.Dataset, level: float
) -> str:
    """The couplings the symmetry allows that ``--threshold level`` leaves out too, as a
    clause (empty when none)."""
    from cummins.radiation.retardation import coupling_sizes

    sizes, _ = coupling_sizes(sub)
    labels = [str(d) for d in sub.influenced_dof.values]
    forbidden = {(min(c.pair), max(c.pair)) for c in found}
    allowed = [
        f"{labels[i]}–{labels[j]}"
        for i, j in fitted
        if i != j and (i, j) not in forbidden and sizes[i, j] <= level
    ]
    if not allowed:
        return ""
    return f"also {', '.join(allowed[:6])}{' …' if len(allowed) > 6 else ''}; "
