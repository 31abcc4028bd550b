"""The ``plausibility`` check: relations every floating body keeps between its quantities,
so that one of them scaled (a factor 10³ in a file, a wrong unit) or of the wrong sign
stands out, though each looks like a number on its own.

* **One mass.** The surge, sway and heave masses of a rigid body are equal.
* **Mass and displacement.** A freely floating body weighs what it displaces: m = ρ∇
  (Archimedes; moorings and ballast change it by tens of per cent, not by ten times).
  Without ∇ the waterplane gives a scale: m / (ρ A_wp^{3/2}), A_wp = C33/(ρg), is a
  draft over a breadth, from 0.09 (the MSS tanker) to 72 (the HAMS Hywind spar) in the
  corpus.
* **Added mass and damping.** A(ω) − A∞ = (2/π) PV∫ B(ν)/(ν² − ω²) dν (Kramers–Kronig,
  Hjulstad (2004) eq. 5.23): the least-squares factor s between the variation of A over
  frequency and that implied by B is 0.55–1.16 in the corpus wherever it is judged (8
  frequencies over a range of 4 at least); A or B scaled by 10³ makes it 10^∓3, a
  flipped sign makes the shapes oppose.
* **Excitation and damping.** The energy a body radiates is what it takes from waves:
  B_ii = k/(8πρ g c_g) ∫|X_i(β)|² dβ (Newman (1977) ch. 6, the Haskind relation), with
  the wave number k and group velocity c_g of the water depth. Over the headings the data
  hold, the ratio of the two sides is 1.00 for every DOF of the MSS tanker (36 headings
  over the circle), up to 120 for one DOF of a body seen from one heading; the largest
  ratio of a body's DOFs scaled by 10⁶ or 10⁻⁶ is an excitation scaled by 10^±3.
* **Frequencies and size.** The data's wave numbers against the body's length L (∇^{1/3},
  else the cube root of the largest translational added mass over ρ): k L from 10⁻⁴ to
  6·10³ in the corpus; frequencies scaled by 10^±3 move it by 10^±6.
* **Signs.** C33 = ρ g A_wp is never negative; an external damping (``additional_damping``)
  gives energy away, its diagonal is never negative.
* **Natural periods.** ω_n² = C_ii / (M_ii + A_ii(ω_n)) of heave, roll and pitch lies
  within a factor 100 of the data's frequencies (warning only: a moored or fixed body may
  have none).

The bounds leave a factor of at least 10 to every case of ``../shared/data`` (see
``benchmarks/bench_plausibility.py``). The findings are errors (warnings for the natural
periods and for a body whose mass is 3–30 times from ρ∇); :func:`warn_implausible` gives
the errors as :class:`~cummins.errors.HydroDataWarning` when a file is read, so a damaged
file is not read silently by the commands that do not run ``cummins check``.
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from cummins.check.report import Finding
from cummins.dofs import bodies, is_rotation, split_dof
from cummins.errors import CumminsError, HydroDataWarning
from cummins.hydrodb import dof_matrix

#: m / ρ∇ of a body: a warning beyond a factor 3 either way, an error beyond 30.
MASS_RATIO_WARN = 3.0
MASS_RATIO_ERROR = 30.0
#: The translational masses of a rigid body are one mass: beyond this ratio, one is
#: damaged (the corpus: equal to the printed digits).
TRANSLATION_MASS_SPREAD = 1.01
#: m / (ρ A_wp^{3/2}): outside these bounds, the mass or the restoring is scaled.
WATERPLANE_MASS_RANGE = (5e-3, 2e3)
#: Least-squares factor between A(ω)'s variation and the one B(ω) implies, where the two
#: shapes correlate by at least KK_CORRELATION: outside this range, A or B is scaled.
KK_SCALE_RANGE = (0.05, 20.0)
KK_CORRELATION = 0.8
#: The factor is computed with at least this many trusted frequencies over a range of at
#: least this ratio ω_max/ω_min (the corpus holds runs of 2 and 3 frequencies).
KK_MIN_FREQUENCIES = 8
KK_MIN_SPAN = 4.0
#: A DOF's damping counts when its peak reaches this share of the largest of its kind
#: (translations or rotations): the yaw of an axisymmetric body does not.
SIGNIFICANT_DAMPING = 1e-3
#: The largest Haskind ratio of a body's DOFs (module docstring) must lie in this range.
HASKIND_RANGE = (1e-3, 1e4)
#: k L of the data: the highest within this range, the lowest below the last number.
KL_HIGHEST_RANGE = (0.05, 1e5)
KL_LOWEST_MAX = 300.0
#: C33 below −this × ρ g L² is a sign, not numerical noise around zero.
NEGATIVE_RESTORING = 1e-3
#: Natural frequencies of heave, roll and pitch within this factor of the data's range.
NATURAL_FREQUENCY_FACTOR = 100.0


def _finding(severity: str, message: str, where: str, advice: str, value=None) -> Finding:
    return Finding(
        "plausibility",
        severity,
        message,
        where=where,
        value=None if value is None else float(value),
        advice=advice,
    )


def _zero_speed(ds: xr.Dataset) -> xr.Dataset | None:
    """The data at zero forward speed (None when they hold only others)."""
    if "forward_speed" not in ds.dims:
        speed = float(ds.forward_speed) if "forward_speed" in ds.coords else 0.0
        return ds if abs(speed) <= 1e-3 else None
    at_zero = np.flatnonzero(np.abs(ds.forward_speed.values) <= 1e-3)
    return ds.isel(forward_speed=int(at_zero[0])) if at_zero.size else None


def _body_index(labels: list[str]) -> dict[str | None, dict[str, int]]:
    out: dict[str | None, dict[str, int]] = {}
    for k, label in enumerate(labels):
        body, name = split_dof(label)
        out.setdefault(body, {})[name] = k
    return out


def _per_body(ds: xr.Dataset, key: str, n_bodies: int) -> list[float] | None:
    if key not in ds.attrs:
        return None
    values = np.atleast_1d(np.asarray(ds.attrs[key], dtype=float)).reshape(-1)
    return [float(v) for v in values] if values.size == n_bodies else None


def _body_length(ds: xr.Dataset, dofs: dict[str, int], volume: float | None) -> float | None:
    """A length of the body: ∇^{1/3}, else (max translational |A| / ρ)^{1/3}."""
    if volume is not None and np.isfinite(volume) and volume > 0:
        return float(volume) ** (1.0 / 3.0)
    a = np.abs(dof_matrix(ds, "added_mass"))
    peaks = [a[:, k, k].max() for name, k in dofs.items() if name in ("Surge", "Sway", "Heave")]
    peak = max(peaks, default=0.0)
    rho = float(ds.attrs["rho"])
    return (peak / rho) ** (1.0 / 3.0) if peak > 0 else None


def plausibility_findings(ds: xr.Dataset) -> list[Finding]:
    """Every finding of the module docstring's relations (``ok`` when none is broken)."""
    zero = _zero_speed(ds)
    out: list[Finding] = []
    out += _mass_findings(ds)
    out += _sign_findings(ds)
    if zero is not None:
        out += _frequency_findings(zero)
        out += _kramers_kronig_findings(zero)
        out += _haskind_findings(zero)
        out += _natural_frequency_findings(zero)
    if not out:
        out.append(
            Finding(
                "plausibility",
                "ok",
                "mass and displacement, added mass and damping (Kramers–Kronig), excitation "
                "and damping (Haskind), frequencies and size agree as for any floating body",
            )
        )
    return out


def gross_errors(ds: xr.Dataset) -> list[Finding]:
    """The errors of the checks that take no fit: ``physical``, and when it finds none,
    :func:`plausibility_findings`, ``damping_positive``, ``added_mass_inf`` and
    ``inertia`` (0.1 s on 12 DOFs × 260 frequencies). Data with one of them are not
    usable (``cummins check`` fails them too)."""
    from cummins.check.coefficients import _check_added_mass_inf, _check_damping
    from cummins.check.physical import _check_physical
    from cummins.check.rigid_body import _check_rigid_body

    findings = [f for f in _check_physical(ds) if f.severity == "error"]
    if findings:
        return findings
    for part in (plausibility_findings, _check_damping, _check_added_mass_inf, _check_rigid_body):
        findings += [f for f in part(ds) if f.severity == "error"]
    return findings


def warn_implausible(ds: xr.Dataset) -> list[str]:
    """Warn (:class:`~cummins.errors.HydroDataWarning`) about every error of
    :func:`gross_errors`; returns their texts. Called by :func:`cummins.read`: a file
    whose numbers no floating body has is not read silently by the commands that do not
    run ``cummins check``."""
    try:
        findings = gross_errors(ds)
    except (CumminsError, ValueError, FloatingPointError, np.linalg.LinAlgError):
        return []  # cummins check says what is wrong
    texts = []
    source = ds.attrs.get("source_file") or "the data"
    for f in findings:
        where = f"{f.where}: " if f.where else ""
        text = f"{source}: {where}{f.message} ({f.advice})"
        warnings.warn(HydroDataWarning(text), stacklevel=3)
        texts.append(text)
    return texts


# --------------------------------------------------------------------------- the relations


def _mass_findings(ds: xr.Dataset) -> list[Finding]:
    if "inertia_matrix" not in ds:
        return []
    labels = [str(d) for d in ds.influenced_dof.values]
    groups = bodies(ds)
    index = _body_index(labels)
    m = dof_matrix(ds, "inertia_matrix").reshape(-1, len(labels), len(labels))[0]
    c = dof_matrix(ds, "hydrostatic_stiffness") if "hydrostatic_stiffness" in ds else None
    c = None if c is None else c.reshape(-1, len(labels), len(labels))[0]
    volumes = _per_body(ds, "displaced_volume", len(groups))
    rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
    out = []
    for b, body in enumerate(groups):
        dofs = index[body]
        if "Heave" not in dofs:
            continue
        k = dofs["Heave"]
        mass = float(m[k, k])
        if not mass > 0:
            continue  # the physical check names a negative mass
        where = body or "the body"
        masses = [
            float(m[dofs[name], dofs[name]]) for name in ("Surge", "Sway", "Heave") if name in dofs
        ]
        if min(masses) > 0 and max(masses) > TRANSLATION_MASS_SPREAD * min(masses):
            out.append(
                _finding(
                    "error",
                    "the masses in surge, sway and heave differ ("
                    + ", ".join(f"{x:.4g}" for x in masses)
                    + " kg): a rigid body has one mass",
                    where,
                    "a diagonal entry of the inertia matrix is scaled or damaged: check it",
                    max(masses) / min(masses),
                )
            )
        c33 = float(c[k, k]) if c is not None else 0.0
        floating = c33 > 0
        volume = volumes[b] if volumes is not None else None
        if volume is not None and np.isfinite(volume) and volume > 0:
            ratio = mass / (rho * volume)
            factor = max(ratio, 1.0 / ratio)
            if factor > MASS_RATIO_ERROR or (factor > MASS_RATIO_WARN and floating):
                severe = factor > MASS_RATIO_ERROR and floating
                out.append(
                    _finding(
                        "error" if severe else "warning",
                        f"the mass {mass:.4g} kg is {ratio:.3g} times ρ∇ = {rho * volume:.4g} kg"
                        + (" of a floating body (C33 > 0)" if floating else ""),
                        where,
                        "a freely floating body weighs what it displaces; check the inertia "
                        "matrix and the displaced volume (a factor 10^3 is a unit or a damaged "
                        "file; moorings and ballast change it by tens of per cent)",
                        ratio,
                    )
                )
        if floating:
            waterplane = c33 / (rho * g)
            ratio = mass / (rho * waterplane**1.5)
            low, high = WATERPLANE_MASS_RANGE
            if not low <= ratio <= high:
                out.append(
                    _finding(
                        "error",
                        f"the mass {mass:.4g} kg and the heave restoring C33 = {c33:.4g} N/m "
                        f"disagree: m/(ρ A_wp^1.5) = {ratio:.3g} with A_wp = C33/(ρg) = "
                        f"{waterplane:.4g} m² (floating bodies: {low:g} to {high:g})",
                        where,
                        "one of the two is scaled (a unit, a factor 10^3, a damaged file): "
                        "check the inertia matrix and the hydrostatics",
                        ratio,
                    )
                )
    return out


def _sign_findings(ds: xr.Dataset) -> list[Finding]:
    labels = [str(d) for d in ds.influenced_dof.values]
    out = []
    if "hydrostatic_stiffness" in ds:
        c = dof_matrix(ds, "hydrostatic_stiffness").reshape(-1, len(labels), len(labels))[0]
        rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
        groups = bodies(ds)
        volumes = _per_body(ds, "displaced_volume", len(groups))
        for b, dofs in enumerate(_body_index(labels).values()):
            if "Heave" not in dofs:
                continue
            k = dofs["Heave"]
            length = _body_length(ds, dofs, volumes[b] if volumes else None)
            if length is None or not c[k, k] < -NEGATIVE_RESTORING * rho * g * length**2:
                continue
            out.append(
                _finding(
                    "error",
                    f"the heave restoring C33 = {c[k, k]:.4g} N/m is negative: it is ρ g A_wp, "
                    "never below zero",
                    labels[k],
                    "the sign is flipped or the file damaged: check the hydrostatics",
                    c[k, k],
                )
            )
    if "additional_damping" in ds:
        extra = dof_matrix(ds, "additional_damping").reshape(-1, len(labels), len(labels))
        diagonal = np.diagonal(extra, axis1=1, axis2=2).min(axis=0)
        for k in np.flatnonzero(diagonal < 0):
            out.append(
                _finding(
                    "error",
                    f"the external damping of {labels[k]} is negative ({diagonal[k]:.4g}): a "
                    "damper gives energy away, it never feeds the body",
                    labels[k],
                    "check the sign of the external (additional) damping in the file or the "
                    "--external-damping given",
                    diagonal[k],
                )
            )
    return out


def _frequency_findings(ds: xr.Dataset) -> list[Finding]:
    from cummins.seakeeping.waves import wavenumber

    labels = [str(d) for d in ds.influenced_dof.values]
    groups = bodies(ds)
    volumes = _per_body(ds, "displaced_volume", len(groups))
    lengths = [
        _body_length(ds, dofs, volumes[b] if volumes else None)
        for b, dofs in enumerate(_body_index(labels).values())
    ]
    lengths = [x for x in lengths if x]
    if not lengths:
        return []
    length = max(lengths)
    w = ds.omega.values
    depth = float(ds.attrs.get("water_depth", np.inf))
    with np.errstate(over="ignore", invalid="ignore"):
        k = wavenumber(w[[0, -1]], depth=depth, g=float(ds.attrs["g"]))
    low, high = k[0] * length, k[-1] * length
    if KL_HIGHEST_RANGE[0] <= high <= KL_HIGHEST_RANGE[1] and low <= KL_LOWEST_MAX:
        return []
    return [
        _finding(
            "error",
            f"the frequencies {w[0]:.4g} to {w[-1]:.4g} rad/s are waves of k L = {low:.3g} to "
            f"{high:.3g} on a body of length L ≈ {length:.3g} m: no solver computes such a "
            f"range (real runs: the highest k L between {KL_HIGHEST_RANGE[0]:g} and "
            f"{KL_HIGHEST_RANGE[1]:g}, the lowest below {KL_LOWEST_MAX:g})",
            "omega",
            "the frequencies are scaled (periods for frequencies, Hz for rad/s, a factor "
            "10^3, a damaged file), or the body's size is: check the first column",
            high,
        )
    ]


def _significant(b: np.ndarray, labels: list[str]) -> np.ndarray:
    """DOFs whose damping peak reaches :data:`SIGNIFICANT_DAMPING` of their kind's."""
    peak = np.abs(np.diagonal(b, axis1=1, axis2=2)).max(axis=0)
    rotation = np.array([is_rotation(lab) for lab in labels])
    out = np.zeros(len(labels), dtype=bool)
    for kind in (False, True):
        same = rotation == kind
        if same.any() and peak[same].max() > 0:
            out[same] = peak[same] >= SIGNIFICANT_DAMPING * peak[same].max()
    return out


def kramers_kronig_scale(ds: xr.Dataset) -> xr.Dataset:
    """Per DOF, the least-squares factor s and the correlation r between the variation
    of A_ii(ω) over the trusted frequencies and the one B_ii(ω) implies, (2/π) PV∫
    B(ν)/(ν² − ω²) dν (Kramers–Kronig, Hjulstad (2004) eq. 5.23; the means removed, so
    A∞ does not enter): s = r = 1 for consistent data.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed.

    Returns
    -------
    xarray.Dataset
        ``scale`` and ``correlation`` (influenced_dof); NaN where A or the implied
        variation is constant.

    Examples
    --------
    >>> import cummins
    >>> kk = kramers_kronig_scale(cummins.demo_dataset())
    >>> round(float(kk.scale.sel(influenced_dof="Heave")), 2)
    1.0
    """
    from cummins.radiation.infinite_frequency import trusted_frequencies
    from cummins.radiation.retardation import kramers_kronig_added_mass

    keep = trusted_frequencies(ds)
    n = ds.sizes["influenced_dof"]
    a = np.diagonal(dof_matrix(ds, "added_mass"), axis1=1, axis2=2)[keep]
    implied = kramers_kronig_added_mass(ds, added_mass_inf=np.zeros((n, n))).values
    implied = np.diagonal(implied, axis1=1, axis2=2)[keep]
    da, di = a - a.mean(axis=0), implied - implied.mean(axis=0)
    cross = np.sum(da * di, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        scale = cross / np.sum(di * di, axis=0)
        correlation = cross / np.sqrt(np.sum(da * da, axis=0) * np.sum(di * di, axis=0))
    coords = {"influenced_dof": ds.influenced_dof.values}
    return xr.Dataset(
        {
            "scale": ("influenced_dof", scale),
            "correlation": ("influenced_dof", correlation),
        },
        coords=coords,
    )


def _kramers_kronig_findings(ds: xr.Dataset) -> list[Finding]:
    from cummins.radiation.infinite_frequency import trusted_frequencies

    w = ds.omega.values
    keep = trusted_frequencies(ds)
    if keep.sum() < KK_MIN_FREQUENCIES or w[keep][-1] < KK_MIN_SPAN * w[keep][0]:
        return []
    labels = [str(d) for d in ds.influenced_dof.values]
    kk = kramers_kronig_scale(ds)
    out = []
    for i in np.flatnonzero(_significant(dof_matrix(ds, "radiation_damping"), labels)):
        scale = float(kk.scale.values[i])
        correlation = float(kk.correlation.values[i])
        if not (np.isfinite(scale) and np.isfinite(correlation)):
            continue
        low, high = KK_SCALE_RANGE
        if correlation <= -KK_CORRELATION:
            message = (
                f"A(ω) varies opposite to what B(ω) implies (Kramers–Kronig: correlation "
                f"{correlation:.2f}): the sign of the added mass or of the damping is flipped"
            )
        elif correlation >= KK_CORRELATION and not low <= scale <= high:
            message = (
                f"A(ω) varies {scale:.3g} times as much as B(ω) implies (Kramers–Kronig; "
                f"the two shapes agree, correlation {correlation:.2f}): the added mass or the "
                "damping is scaled"
            )
        else:
            continue
        out.append(
            _finding(
                "error",
                message,
                labels[i],
                "a unit, a factor 10^3 or a sign in the file (a damaged file, or the wrong "
                "--rho/--ulen for one of them): check A and B of this DOF",
                scale,
            )
        )
    return out


def haskind_ratio(ds: xr.Dataset) -> xr.DataArray:
    """k/(8πρ g c_g) · 2π ⟨|X_i(β)|²⟩_β / B_ii(ω) per frequency and DOF: 1 when the data's
    headings sample the whole circle evenly and the excitation and damping are
    consistent (the energy a body radiates, Newman (1977) ch. 6; k and c_g of the water
    depth); the mean over fewer headings tilts it by the directivity of X_i.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed with ``excitation_force``.

    Returns
    -------
    xarray.DataArray
        (omega, influenced_dof); NaN where B_ii = 0.

    Examples
    --------
    >>> import cummins, numpy as np
    >>> r = haskind_ratio(cummins.demo_dataset())  # 19 headings over half the circle
    >>> round(float(np.nanmedian(r.sel(influenced_dof="Heave"))), 1)
    1.0
    """
    from cummins.seakeeping.waves import wavenumber

    rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
    depth = float(ds.attrs.get("water_depth", np.inf))
    w = ds.omega.values
    k = wavenumber(w, depth=depth, g=g)
    kh = k * depth if np.isfinite(depth) else np.full_like(k, np.inf)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        stretch = np.where(kh < 300, 1.0 + 2.0 * kh / np.sinh(np.minimum(2.0 * kh, 700)), 1.0)
        group = 0.5 * w / k * stretch
        factor = k / (8.0 * np.pi * rho * g * group)
        force = ds.excitation_force.transpose("omega", "wave_direction", "influenced_dof").values
        energy = 2.0 * np.pi * np.mean(np.abs(force) ** 2, axis=1)  # (omega, dof)
        diagonal = np.diagonal(dof_matrix(ds, "radiation_damping"), axis1=1, axis2=2)
        ratio = np.where(diagonal != 0, factor[:, None] * energy / diagonal, np.nan)
    return xr.DataArray(
        ratio,
        dims=("omega", "influenced_dof"),
        coords={"omega": ds.omega, "influenced_dof": ds.influenced_dof.values},
        name="haskind_ratio",
    )


def _haskind_findings(ds: xr.Dataset) -> list[Finding]:
    if "excitation_force" not in ds or "wave_direction" not in ds.dims:
        return []
    labels = [str(d) for d in ds.influenced_dof.values]
    ratio = haskind_ratio(ds).values
    b = dof_matrix(ds, "radiation_damping")
    diagonal = np.diagonal(b, axis1=1, axis2=2)
    significant = _significant(b, labels)
    out = []
    for body, dofs in _body_index(labels).items():
        best, where = None, None
        for i in dofs.values():
            if not significant[i]:
                continue
            strong = diagonal[:, i] >= 0.1 * diagonal[:, i].max()
            values = ratio[strong, i]
            values = values[np.isfinite(values) & (values > 0)]
            if values.size < 3:
                continue
            r = float(np.median(values))
            if best is None or r > best:
                best, where = r, labels[i]
        if best is None:
            continue
        low, high = HASKIND_RANGE
        if low <= best <= high:
            continue
        out.append(
            _finding(
                "error",
                f"the wave excitation and the damping disagree: k/(8πρg c_g) ∫|X|² dβ / B is "
                f"{best:.3g} at most over {body or 'the body'}'s DOFs ({where}), where the "
                f"energy a body radiates makes it about 1 (Haskind; {low:g} to {high:g} with "
                "the headings of real runs)",
                where or "",
                "the excitation or the damping is scaled (a unit, a factor 10^3, a damaged "
                "file): check both",
                best,
            )
        )
    return out


def _natural_frequency_findings(ds: xr.Dataset) -> list[Finding]:
    if "inertia_matrix" not in ds or "hydrostatic_stiffness" not in ds:
        return []
    labels = [str(d) for d in ds.influenced_dof.values]
    n = len(labels)
    m = dof_matrix(ds, "inertia_matrix").reshape(-1, n, n)[0]
    c = dof_matrix(ds, "hydrostatic_stiffness").reshape(-1, n, n)[0]
    a = dof_matrix(ds, "added_mass")
    w = ds.omega.values
    out = []
    for i, label in enumerate(labels):
        if split_dof(label)[1] not in ("Heave", "Roll", "Pitch") or not c[i, i] > 0:
            continue
        total = m[i, i] + np.median(a[:, i, i])
        if not total > 0:
            continue
        natural = float(np.sqrt(c[i, i] / total))
        if w[0] / NATURAL_FREQUENCY_FACTOR <= natural <= w[-1] * NATURAL_FREQUENCY_FACTOR:
            continue
        out.append(
            _finding(
                "warning",
                f"the natural frequency √(C/(M + A)) = {natural:.3g} rad/s lies far outside "
                f"the data's {w[0]:.4g} to {w[-1]:.4g} rad/s",
                label,
                "check the inertia, the restoring and the frequencies (one of them scaled?)",
                natural,
            )
        )
    return out
