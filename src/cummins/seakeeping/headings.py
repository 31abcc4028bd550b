"""Wave headings for the excitation: coverage, port/starboard mirroring, interpolation weights.

Step 3 of the interpolation of :func:`cummins.seakeeping.excitation.excitation_transfer`
(the phase-corrected force G(ω, β) of that module's docstring), in heading:
periodic over 2π. When the data cover only one half-plane (0…π, as the
WAMIT tanker ``.3``, or π…2π plus 0, as the VERES supply vessel) and the body is
port/starboard symmetric, the other half is mirrored: F(ω, −β) = T F(ω, β) with
T = diag(1, −1, 1, −1, 1, −1) (surge, heave, pitch symmetric; sway, roll, yaw change
sign under y → −y, in z-up and z-down axes alike). Symmetry is judged from the data
(``mirror=None``, :func:`symmetry_evidence`): no coupling between the symmetric and
antisymmetric DOFs in A(ω), B(ω) (below 1e-3 of the geometric mean of the diagonal terms),
no sway, roll or yaw excitation in head and following seas (below 1e-3 of its largest
value), and a centre of buoyancy on y = 0. ``mirror=True``/``False`` forces the choice
(:func:`heading_coverage`). On the circle of available headings G is interpolated by a
periodic cubic spline (a not-a-knot spline along the arc when a gap wider than
``max_heading_gap``, 90° by default, breaks the circle; linear with two or three
headings). A direction inside such a gap is an error that names it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline

from cummins.errors import HydroDataError
from cummins.hydrodb import DOF_NAMES, bodies, single_speed, split_dof

#: Sign of each DOF under the reflection y → −y (surge … yaw).
MIRROR_SIGNS = np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])
#: Relative size below which a coupling or force counts as zero for the symmetry test.
SYMMETRY_TOLERANCE = 1e-3

#: How a user chooses the heading, in the hint of a direction in a gap (a batch study
#: says its own key instead: :func:`cummins.studies.wording.study_wording`).
HEADING_CHOICE = "on the command line --heading DEG, the default being 180°"

_TWO_PI = 2.0 * np.pi
_ANGLE_TOL = 1e-6  # rad: headings closer than this are the same heading


def _where(ds: xr.Dataset) -> str | None:
    return ds.attrs.get("source_file") or ds.attrs.get("source_format") or None


def _deg(angle: float) -> str:
    return f"{np.degrees(angle):.6g}°"


@dataclass(frozen=True)
class HeadingCoverage:
    """The wave directions available for interpolation, after mirroring if any.

    Attributes
    ----------
    directions
        Sorted directions in [0, 2π), rad.
    source
        For each direction, the index of the data heading it comes from.
    mirrored
        For each direction, whether it is the mirror image of a data heading.
    mirror_used
        Whether any heading was mirrored.
    reason
        Why mirroring was or was not used (one sentence).
    """

    directions: NDArray[np.float64]
    source: NDArray[np.int64]
    mirrored: NDArray[np.bool_]
    mirror_used: bool
    reason: str

    def gaps(self, max_gap: float) -> list[tuple[float, float]]:
        """Arcs (start, end) in rad, end possibly > 2π, wider than ``max_gap`` with no data."""
        b = self.directions
        ends = np.append(b[1:], b[0] + _TWO_PI)
        return [(s, e) for s, e in zip(b, ends, strict=True) if e - s > max_gap + 1e-12]


def symmetry_evidence(ds: xr.Dataset) -> tuple[bool, str]:
    """Is the body port/starboard symmetric, judged from the data? (ok, reason)."""
    labels = [str(d) for d in ds.influenced_dof.values]
    if len(bodies(ds)) != 1:
        return False, "several bodies: mirroring would exchange them"
    names = [split_dof(label)[1] for label in labels]
    if any(d not in DOF_NAMES for d in names):
        return False, "generalized modes: their port/starboard parity is not known"
    sym = [i for i, d in enumerate(names) if d in ("Surge", "Heave", "Pitch")]
    anti = [i for i, d in enumerate(names) if d in ("Sway", "Roll", "Yaw")]
    if not anti:
        return True, "the dataset has no sway, roll or yaw DOF"
    for name in ("added_mass", "radiation_damping"):
        m = np.abs(ds[name].transpose("omega", "influenced_dof", "radiating_dof").values)
        diag = np.sqrt(np.max(np.abs(np.diagonal(m, axis1=1, axis2=2)), axis=0))
        scale = np.outer(diag, diag)
        # A DOF with (numerically) no added mass or damping of its own (yaw of a sphere)
        # says nothing about symmetry: its couplings are round-off.
        rotation = np.array([DOF_NAMES.index(d) >= 3 for d in names])
        active = np.array(
            [
                diag[i] ** 2 > 1e-6 * (diag[rotation == rotation[i]] ** 2).max()
                for i in range(len(names))
            ]
        )
        for i in sym:
            for j in anti:
                if not (active[i] and active[j]):
                    continue
                for a, b in ((i, j), (j, i)):
                    if scale[a, b] > 0 and m[:, a, b].max() > SYMMETRY_TOLERANCE * scale[a, b]:
                        return False, (
                            f"{name}[{labels[a]}, {labels[b]}] couples symmetric and "
                            "antisymmetric motions"
                        )
    # without excitation (a drift table alone) the heading test has nothing to look at
    f = (
        np.abs(ds["excitation_force"].transpose("omega", "wave_direction", "influenced_dof").values)
        if "excitation_force" in ds
        else None
    )
    beta = np.mod(ds.wave_direction.values, _TWO_PI) if "wave_direction" in ds.dims else np.zeros(0)
    along = np.flatnonzero(
        (np.abs(beta) < _ANGLE_TOL)
        | (np.abs(beta - np.pi) < _ANGLE_TOL)
        | (np.abs(beta - _TWO_PI) < _ANGLE_TOL)
    )
    rotation = np.array([DOF_NAMES.index(d) >= 3 for d in names])
    for j in anti if f is not None else ():
        peak = f[:, :, rotation == rotation[j]].max()  # largest force (or moment) of any DOF
        if along.size and peak > 0 and f[:, along, j].max() > SYMMETRY_TOLERANCE * peak:
            return False, (
                f"{labels[j]} is excited by waves along the x axis "
                f"({f[:, along, j].max() / peak:.2g} of the largest excitation of its kind)"
            )
    for key in ("center_of_buoyancy", "center_of_gravity"):
        if key in ds.attrs:
            point = np.asarray(ds.attrs[key], dtype=float).reshape(-1)
            if point.size >= 2 and abs(point[1]) > 1e-3 * max(1.0, float(np.abs(point).max())):
                return False, f"{key} is off the centre plane (y = {point[1]:g} m)"
    return (
        True,
        "no coupling between symmetric and antisymmetric DOFs, none excited in head "
        "or following seas",
    )


def heading_coverage(
    ds: xr.Dataset, *, mirror: bool | None = None, directions: ArrayLike | None = None
) -> HeadingCoverage:
    """The directions available for interpolation, with mirrored ones (module docstring §3).

    Parameters
    ----------
    ds
        A ``HydroDB`` with ``excitation_force``.
    mirror
        None: mirror when the data cover one half-plane only and the body looks
        port/starboard symmetric; True: mirror (single body); False: never.
    directions
        The directions to cover (rad), when not the dataset's ``wave_direction`` (a
        QTF's own directions, :func:`cummins.qtf.headings.mirrored_qtf`); the symmetry
        is judged from ``ds`` all the same.
    """
    ds = single_speed(ds)
    if directions is None:
        if "wave_direction" not in ds.dims:
            raise HydroDataError("the dataset has no wave directions", path=_where(ds))
        directions = ds.wave_direction.values
    beta = np.mod(np.asarray(directions, dtype=float).reshape(-1), _TWO_PI)
    beta[np.abs(beta - _TWO_PI) < _ANGLE_TOL] = 0.0
    order = np.argsort(beta, kind="stable")
    beta, source = beta[order], order
    keep = np.concatenate([[True], np.diff(beta) > _ANGLE_TOL])
    beta, source = beta[keep], source[keep]
    mirrored = np.zeros(beta.size, dtype=bool)

    def half_plane(b: NDArray) -> bool:
        upper = np.all((b <= np.pi + _ANGLE_TOL) | (b >= _TWO_PI - _ANGLE_TOL))
        lower = np.all((b >= np.pi - _ANGLE_TOL) | (b <= _ANGLE_TOL))
        return bool(upper or lower)

    one_half = half_plane(beta)
    if mirror is False:
        return HeadingCoverage(beta, source, mirrored, False, "mirroring switched off")
    if mirror is None:
        if not one_half:
            return HeadingCoverage(
                beta, source, mirrored, False, "the data cover both sides of the x axis"
            )
        ok, why = symmetry_evidence(ds)
        if not ok:
            return HeadingCoverage(
                beta,
                source,
                mirrored,
                False,
                f"not mirrored: the body does not look port/starboard symmetric ({why})",
            )
        reason = f"mirrored about the x axis: {why}"
    else:
        if len(bodies(ds)) != 1:
            raise HydroDataError(
                "cannot mirror the headings of several bodies",
                path=_where(ds),
                hint="mirroring about y = 0 would exchange bodies; give the data for all headings",
            )
        reason = "mirrored about the x axis (asked for)"
    image = np.mod(-beta, _TWO_PI)
    image[np.abs(image - _TWO_PI) < _ANGLE_TOL] = 0.0
    new = np.array([np.min(np.abs(_wrap_pi(b - beta))) > _ANGLE_TOL for b in image])
    all_beta = np.concatenate([beta, image[new]])
    all_source = np.concatenate([source, source[new]])
    all_mirrored = np.concatenate([mirrored, np.ones(int(new.sum()), dtype=bool)])
    order = np.argsort(all_beta, kind="stable")
    if not new.any():
        reason = reason.replace("mirrored about the x axis", "symmetric, but no heading to add")
    return HeadingCoverage(
        all_beta[order], all_source[order], all_mirrored[order], bool(new.any()), reason
    )


def mirror_headings(
    ds: xr.Dataset, *, mirror: bool | None = None
) -> tuple[xr.Dataset, HeadingCoverage]:
    """The dataset on the headings of :func:`heading_coverage`: every variable with a
    ``wave_direction`` dimension (excitation, RAOs, drift) taken at its source heading,
    times T = diag(1, −1, 1, −1, 1, −1) where mirrored, F(ω, −β) = T F(ω, β) (module
    docstring); ``wave_direction`` in [0, 2π), sorted. The coverage says whether any
    heading was added and why (not). Several forward speeds: the symmetry is judged at
    the first and the mirror applied to all."""
    if "wave_direction" not in ds.dims:
        return ds, HeadingCoverage(np.zeros(0), np.zeros(0, int), np.zeros(0, bool), False, "")
    first = ds.isel(forward_speed=0) if "forward_speed" in ds.dims else ds
    coverage = heading_coverage(first, mirror=mirror)
    out = ds.isel(wave_direction=xr.DataArray(coverage.source, dims="wave_direction"))
    out = out.assign_coords(wave_direction=coverage.directions)
    mirrored = xr.DataArray(coverage.mirrored, dims="wave_direction")
    for name, var in out.data_vars.items():
        dof = next((d for d in ("influenced_dof", "radiating_dof") if d in var.dims), None)
        if "wave_direction" not in var.dims or dof is None:
            continue
        labels = [split_dof(str(d))[1] for d in var[dof].values]
        signs = xr.DataArray(
            [MIRROR_SIGNS[DOF_NAMES.index(d)] if d in DOF_NAMES else 1.0 for d in labels],
            dims=dof,
        )
        out[name] = xr.where(mirrored, var * signs, var).transpose(*var.dims)
        out[name].attrs = var.attrs
    return out, coverage


def _wrap_pi(a: ArrayLike) -> NDArray[np.float64]:
    return np.mod(np.asarray(a, dtype=float) + np.pi, _TWO_PI) - np.pi


def _heading_weights(
    coverage: HeadingCoverage,
    targets: NDArray[np.float64],
    max_gap: float,
    where: str | None,
    method: str = "cubic",
) -> NDArray[np.float64]:
    """(n_targets, n_headings) interpolation weights along the circle of headings."""
    b = coverage.directions
    nb = b.size
    t = np.mod(targets, _TWO_PI)
    weights = np.zeros((t.size, nb))
    exact = np.abs(_wrap_pi(t[:, None] - b[None, :])) <= _ANGLE_TOL
    hit = exact.any(axis=1)
    weights[hit, np.argmax(exact[hit], axis=1)] = 1.0
    todo = np.flatnonzero(~hit)
    if todo.size == 0:
        return weights
    listed = ", ".join(_deg(x) for x in b[:12]) + (" …" if nb > 12 else "")
    if nb == 1:
        raise HydroDataError(
            f"wave direction {_deg(t[todo[0]])} asked for, but the data hold one heading "
            f"({_deg(b[0])})",
            path=where,
            hint="use that direction, or compute the excitation for more headings",
        )
    gaps = coverage.gaps(max_gap)
    for s, e in gaps:
        inside = ((t[todo] > s) & (t[todo] < e)) | (
            (t[todo] + _TWO_PI > s) & (t[todo] + _TWO_PI < e)
        )
        if inside.any():
            note = "" if coverage.mirror_used else f" ({coverage.reason})"
            raise HydroDataError(
                f"wave direction {_deg(t[todo][inside][0])} lies in a gap of the data's "
                f"headings, from {_deg(s)} to {_deg(np.mod(e, _TWO_PI))}{note}",
                path=where,
                hint=f"available headings: {listed}; choose one ({HEADING_CHOICE}), pass "
                "mirror=True (Python) if the body is port/starboard symmetric, or compute the "
                "missing headings",
            )
    if gaps:  # an open arc: start after the widest gap, not-a-knot spline along it
        widths = [e - s for s, e in gaps]
        start = np.mod(gaps[int(np.argmax(widths))][1], _TWO_PI)
        k0 = int(np.argmin(np.abs(_wrap_pi(b - start))))
        order = np.roll(np.arange(nb), -k0)
        x = np.unwrap(b[order])
        x = x - _TWO_PI * np.floor(x[0] / _TWO_PI)
        tt = np.mod(t[todo] - x[0], _TWO_PI) + x[0]
        weights[todo] = _cardinal_weights(x, np.eye(nb)[order], tt, method, "not-a-knot")
        return weights
    x = np.append(b, b[0] + _TWO_PI)
    eye = np.vstack([np.eye(nb), np.eye(nb)[:1]])
    tt = np.mod(t[todo] - b[0], _TWO_PI) + b[0]
    weights[todo] = _cardinal_weights(x, eye, tt, method, "periodic")
    return weights


def _cardinal_weights(x, unit_values, tt, method: str, boundary: str) -> NDArray[np.float64]:
    """Weights of each heading's value at the angles ``tt``: the interpolants through
    the unit vectors ``unit_values`` (one row per knot ``x``) — cubic spline with the
    ``boundary`` condition when ``method == "cubic"`` and there are ≥ 4 headings, else
    linear."""
    nb = unit_values.shape[1]
    if nb >= 4 and method == "cubic":
        return CubicSpline(x, unit_values, bc_type=boundary)(tt)
    return np.stack([np.interp(tt, x, unit_values[:, j]) for j in range(nb)], axis=1)
