"""The LF model built from a ``HydroDB`` (Ross, Perez & Fossen (2006) §3.1).

:func:`lf_model_from_retardation` (from K(t) and A∞: eqs. 22–23, 25–26, 29–30) and
:func:`lf_model_from_frequency_data` (from A(ω), B(ω): eqs. 18–21, 24) compute the same
numbers by two routes; both take each DOF at its frequency (Definition 1), entry (i, j)
at min(ω_i, ω_j) or at ω_j, and add the viscous damping asked for.
"""

from __future__ import annotations

import re
import warnings
from collections.abc import Mapping
from typing import Literal

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsWarning, HydroDataError
from cummins.hydrodb import dof_matrix, single_speed
from cummins.radiation.fingerprint import data_fingerprint
from cummins.radiation.model import RadiationModel
from cummins.timedomain.lfmodel.coefficients import _Coefficients, _FromFrequencyData, _FromKernel
from cummins.timedomain.lfmodel.frequencies import _is_zero_frequency_dof, natural_frequency
from cummins.timedomain.lfmodel.model import LowFrequencyModel
from cummins.timedomain.lfmodel.viscous import ViscousSpec, _database_damping, _viscous_value
from cummins.vessel import vessel_from_hydrodb

Couplings = Literal["min", "radiating"]

#: How the advice on frequency-dependent ``additional_damping`` names the remedy; the
#: command line rewrites it to its option (``cummins lf-model --data-damping``).
DATA_DAMPING_ADVICE = "viscous={dof: 'data'}"


def _nonnegative_damping(
    ds: xr.Dataset, coefficients: _Coefficients, dof: str, i: int, omega: float, value: float
) -> tuple[float, str]:
    """B_ii(ω₀) of a passive body is ≥ 0; a negative value from a route (a few N·s/m where
    B_ii peaks at 10⁵: the truncation error of K(t), or a cubic spline undershooting where
    the data are nearly zero) is replaced by the data's own B_ii(ω₀), interpolated
    linearly, with a warning. Data negative at ω₀ themselves are refused."""
    w = ds.omega.values
    b = dof_matrix(ds, "radiation_damping")[:, i, i]
    peak = float(np.max(np.abs(b)))
    if not w[0] <= omega <= w[-1]:
        raise HydroDataError(
            f"{dof}: the potential damping at the natural frequency ω₀ = {omega:.4g} rad/s "
            f"comes out negative ({value:.4g}) from the {coefficients.route}, and ω₀ is "
            f"outside the data ({w[0]:.4g}–{w[-1]:.4g} rad/s) to check it against",
            path=ds.attrs.get("source_file"),
            quantity=f"radiation_damping[{dof}, {dof}]",
            hint="give data that cover the natural frequency, or the frequency with "
            f"frequencies={{{dof!r}: ω}} (--route frequency on the command line)",
        )
    from_data = float(np.interp(omega, w, b))
    if from_data < 0:
        raise HydroDataError(
            f"{dof}: the data's damping is negative at the natural frequency ω₀ = "
            f"{omega:.4g} rad/s ({from_data:.4g}, peak {peak:.4g}): a low-frequency model "
            "with it would be unstable",
            path=ds.attrs.get("source_file"),
            quantity=f"radiation_damping[{dof}, {dof}]",
            hint="remove the suspect frequencies first (cummins.repair."
            "remove_suspect_frequencies), or add viscous damping for this DOF",
        )
    how = (
        f"the {coefficients.route} gave B(ω₀) = {value:.4g} < 0 (its error, {abs(value):.2g}, "
        f"is {abs(value) / max(peak, 1e-300):.1e} of the peak {peak:.4g} but exceeds B(ω₀) "
        f"itself): B(ω₀) = {from_data:.4g} interpolated linearly in the data instead"
    )
    warnings.warn(f"{dof}: {how}", CumminsWarning, stacklevel=4)
    return from_data, how


def _build(
    ds: xr.Dataset,
    coefficients: _Coefficients,
    *,
    viscous: Mapping[str, ViscousSpec] | None,
    frequencies: Mapping[str, float] | None,
    couplings: Couplings,
    additional: bool,
    potential_b0: str,
    tol: float,
    max_iter: int,
) -> LowFrequencyModel:
    if potential_b0 not in ("zero", "computed"):
        raise HydroDataError(
            f"unknown potential_b0 {potential_b0!r}", hint="use 'zero' or 'computed'"
        )
    dofs = tuple(str(d) for d in ds.influenced_dof.values)
    n = len(dofs)
    # M_RB, C (with moorings) and the database's constant B_v exactly as the full vessel
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        no_memory = RadiationModel(
            dofs, (), np.zeros((n, n)), {"data_fingerprint": data_fingerprint(ds)}
        )
        base = vessel_from_hydrodb(ds, no_memory, additional=additional)
    for w in caught:  # the vessel's advice, restated for the LF model
        message = str(w.message)
        if issubclass(w.category, UserWarning) and "varies with frequency" in message:
            pairs = re.findall(r"(\w+)-(\w+) \(", message)
            if pairs and all(a == b and a in (viscous or {}) for a, b in pairs):
                continue  # every entry named is diagonal, its viscous damping asked for
            message = message.split(": a linear")[0] + (
                ": the low-frequency model leaves these entries out unless you ask for "
                f"{DATA_DAMPING_ADVICE}, which takes them at the DOF's frequency"
            )
        warnings.warn(message, w.category, stacklevel=3)
    m_rb, c = base.rigid_body_mass, base.stiffness
    if couplings not in ("min", "radiating"):
        raise HydroDataError(f"unknown couplings {couplings!r}", hint="use 'min' or 'radiating'")
    for name in list(viscous or {}) + list(frequencies or {}):
        if name not in dofs:
            raise HydroDataError(
                f"DOF {name!r} is not in the data", hint=f"DOFs: {', '.join(dofs)}"
            )
    chosen = np.zeros(n)
    notes: list[str] = []
    iterations: dict[str, int] = {}
    for i, dof in enumerate(dofs):
        if frequencies and dof in frequencies:
            chosen[i] = float(frequencies[dof])
            if not (np.isfinite(chosen[i]) and chosen[i] >= 0):
                raise HydroDataError(
                    f"{dof}: the frequency given, {chosen[i]}, must be finite and ≥ 0 rad/s"
                )
            notes.append(f"ω = {chosen[i]:.6g} rad/s given")
        elif _is_zero_frequency_dof(dof):
            chosen[i] = 0.0
            notes.append(f"zero-frequency model; {coefficients.zero_note}")
        else:
            chosen[i], iterations[dof] = natural_frequency(
                coefficients, m_rb[i, i], c[i, i], i, dof=dof, tol=tol, max_iter=max_iter
            )
            notes.append(
                f"natural-frequency model, ω₀ = {chosen[i]:.6g} rad/s from eq. 24 "
                f"({iterations[dof]} iterations); A(ω₀), B(ω₀) from the "
                f"{coefficients.route} (eqs. 29–30)"
            )
    cache: dict[float, tuple[NDArray, NDArray]] = {}
    m_a = np.zeros((n, n))
    b_p = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            w = float(chosen[j] if couplings == "radiating" else min(chosen[i], chosen[j]))
            if w not in cache:
                cache[w] = coefficients(w)
            m_a[i, j] = cache[w][0][i, j]
            b_p[i, j] = 0.0 if (w == 0.0 and potential_b0 == "zero") else cache[w][1][i, j]
    if couplings == "min":  # the data's own small asymmetry (K_ij ≠ K_ji) averaged out
        m_a = 0.5 * (m_a + m_a.T)
        b_p = 0.5 * (b_p + b_p.T)
    for i, dof in enumerate(dofs):
        if chosen[i] > 0 and b_p[i, i] < 0:
            b_p[i, i], how = _nonnegative_damping(
                ds, coefficients, dof, i, float(chosen[i]), b_p[i, i]
            )
            notes[i] += f"; {how}"
    b0 = coefficients(0.0)[1]
    if couplings == "symmetric":
        m_a = 0.5 * (m_a + m_a.T)
        b_p = 0.5 * (b_p + b_p.T)
    b_v = np.array(base.viscous_damping)
    for dof, spec in (viscous or {}).items():
        i = dofs.index(dof)
        if isinstance(spec, str):
            value, how = _database_damping(ds, spec, dof, i, float(chosen[i]))
            b_v[i, i] = value  # replaces the constant part taken above, if any
        else:
            value, how = _viscous_value(spec, dof, float(chosen[i]), m_rb[i, i], m_a[i, i])
            b_v[i, i] += value
        notes[i] += f"; {how} → {value:.4g}"
    provenance = tuple(f"{dof}: {note}" for dof, note in zip(dofs, notes, strict=True))
    model = LowFrequencyModel(
        dofs=dofs,
        rigid_body_mass=m_rb,
        added_mass=m_a,
        potential_damping=b_p,
        viscous_damping=b_v,
        stiffness=c,
        frequencies=chosen,
        provenance=provenance,
        zero_frequency_damping=b0,
        attrs={
            "route": coefficients.route,
            "couplings": couplings,
            "potential_b0": potential_b0,
            "source_file": str(ds.attrs.get("source_file", "")),
            "viscous_damping_source": str(base.attrs.get("viscous_damping_source", "")),
            "reference_point": np.asarray(ds.attrs.get("reference_point", (0.0, 0.0, 0.0))),
            "axis_convention": str(ds.attrs.get("axis_convention", "z-up")),
        },
    )
    return model


def lf_model_from_retardation(
    ds: xr.Dataset,
    kernel: xr.DataArray | None = None,
    *,
    added_mass_inf: ArrayLike | None = None,
    viscous: Mapping[str, ViscousSpec] | None = None,
    frequencies: Mapping[str, float] | None = None,
    couplings: Couplings = "min",
    additional: bool = True,
    potential_b0: Literal["zero", "computed"] = "zero",
    tol: float = 1e-10,
    max_iter: int = 100,
) -> LowFrequencyModel:
    """The LF model from the retardation function K(t) and A∞ (Ross, Perez & Fossen (2006) §3.1).

    Zero-frequency DOFs (surge, sway, yaw): M_A = A∞ − ∫τK dτ (eqs. 22, 25) and
    D = ∫K dτ + B_v(0) (eqs. 23, 26). Natural-frequency DOFs (heave, roll, pitch): ω₀
    from eq. 24 by fixed-point iteration, M_A = A∞ − (1/ω₀)∫K sin ω₀τ dτ (eq. 29) and
    D = ∫K cos ω₀τ dτ + B_v(ω₀) (eq. 30). The integrals are exact for the
    piecewise-linear K through its samples, truncated at its last time. The first
    moment ∫τK dτ weights the late, small part of K: on the bundled tanker A(0) from
    the default grid (88.7 s) is within 3 % of A(0) − A∞ of the solver's ω = 0 row, and
    moves by about as much with the grid's length.

    Parameters
    ----------
    ds
        ``HydroDB`` at one forward speed (zero speed is what Ross, Perez & Fossen (2006)
        assume), with ``inertia_matrix`` and ``hydrostatic_stiffness``.
    kernel
        K(t) (time from 0, influenced_dof, radiating_dof), kg/s² …; default
        :func:`cummins.radiation.retardation.default_retardation_function` of ``ds``.
    added_mass_inf
        A∞ (n, n); default :func:`cummins.radiation.infinite_frequency.added_mass_inf` of ``ds``.
    viscous
        ``{dof: spec}``: :class:`ExponentialDamping`, :class:`CriticalDampingFraction`,
        a callable B_v(ω) or a constant, evaluated at the DOF's frequency and added to
        the diagonal of D; or ``"data"``: the database's own ``additional_damping``
        (e.g. a VERES viscous roll damping curve, which a time-domain vessel cannot
        take because it varies with ω) interpolated linearly at that frequency (held
        at its first value below the lowest frequency), replacing the constant part.
    frequencies
        ``{dof: ω}`` (rad/s) to impose a DOF's frequency (e.g. measured in a decay test).
    couplings
        ``"min"`` (default): entry (i, j) at min(ω_i, ω_j), then symmetrised (the mean
        with its transpose removes the data's small asymmetry), so M_A and D are
        symmetric and a coupling with a zero-frequency DOF takes the zero-frequency values (no
        potential damping: D stays positive semi-definite); ``"radiating"``: entry
        (i, j) at ω_j, the frequency of the motion that causes the force — asymmetric,
        and D may then be indefinite (a free sway coupled to a damped roll).
    additional
        Take the database's ``additional_stiffness`` into G and its constant
        ``additional_damping`` into B_v, as :func:`cummins.vessel.vessel_from_hydrodb`.
    potential_b0
        ``"zero"`` (default): the potential part of D in the zero-frequency DOFs is
        B(0) = ∫K dτ = 0, its value at zero speed in deep water (then
        Ross, Perez & Fossen (2006) eq. 26 leaves the viscous β alone); ``"computed"``:
        the number the route gives, which is that zero plus truncation noise of either
        sign (a slightly negative value makes a free DOF unstable). The computed value is
        kept in :attr:`LowFrequencyModel.zero_frequency_damping` either way.
    tol, max_iter
        Convergence of eq. 24 (see :func:`natural_frequency`).

    Returns
    -------
    LowFrequencyModel

    Examples
    --------
    >>> import cummins
    >>> from cummins.timedomain.lfmodel import lf_model_from_retardation
    >>> lf = lf_model_from_retardation(cummins.demo_dataset())
    >>> [round(float(w), 3) for w in lf.frequencies]
    [0.0, 0.0, 0.651, 0.489, 0.689, 0.0]
    """
    from cummins.radiation import retardation

    ds = single_speed(ds)
    if kernel is None:
        kernel = retardation.default_retardation_function(ds)
    if added_mass_inf is None:
        added_mass_inf = retardation.added_mass_inf(ds).values
    labels = [str(d) for d in ds.influenced_dof.values]
    kernel = kernel.sel(influenced_dof=labels, radiating_dof=labels)
    a_inf = np.asarray(added_mass_inf, dtype=float)
    return _build(
        ds,
        _FromKernel(kernel, a_inf),
        viscous=viscous,
        frequencies=frequencies,
        couplings=couplings,
        additional=additional,
        potential_b0=potential_b0,
        tol=tol,
        max_iter=max_iter,
    )


def lf_model_from_frequency_data(
    ds: xr.Dataset,
    *,
    zero_frequency: Literal["auto", "data", "extrapolate"] = "auto",
    points: int = 4,
    viscous: Mapping[str, ViscousSpec] | None = None,
    frequencies: Mapping[str, float] | None = None,
    couplings: Couplings = "min",
    additional: bool = True,
    potential_b0: Literal["zero", "computed"] = "zero",
    tol: float = 1e-10,
    max_iter: int = 100,
) -> LowFrequencyModel:
    """The LF model directly from A(ω), B(ω).

    Ross, Perez & Fossen (2006) eqs. 20–21, 24, and 18–19 at ω₀.

    The same model as :func:`lf_model_from_retardation` computed without K(t): A and B
    are interpolated by cubic splines at ω₀ (eq. 24 solved on the spline); A(0) is the
    solver's ω = 0 row (``"data"``) or an even extrapolation c₀ + c₂ω² of the lowest
    ``points`` frequencies (``"extrapolate"``; ``"auto"``: the row when present); B(0)
    is always extrapolated (≈ 0 at zero speed). ω₀ must lie within the data.

    Parameters are those of :func:`lf_model_from_retardation` plus ``zero_frequency``
    and ``points`` (see :func:`extrapolate_zero_frequency`).

    Examples
    --------
    >>> import cummins
    >>> from cummins.timedomain.lfmodel import lf_model_from_frequency_data
    >>> lf = lf_model_from_frequency_data(cummins.demo_dataset())
    >>> abs(lf.eq24_residual("Roll")) < 1e-6 * float(lf.stiffness[3, 3])
    True
    """
    ds = single_speed(ds)
    return _build(
        ds,
        _FromFrequencyData(ds, zero_frequency, points),
        viscous=viscous,
        frequencies=frequencies,
        couplings=couplings,
        additional=additional,
        potential_b0=potential_b0,
        tol=tol,
        max_iter=max_iter,
    )
