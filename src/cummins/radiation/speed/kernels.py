"""Speed kernels (:func:`speed_dependent_model`, Hjulstad (2004) eqs. 3.28–3.36).

The memory kernel K_U = K⁰ + U K¹ + U² K² (eq. 3.28), with K⁰ the fitted zero-speed model and
K¹, K² derived *exactly* from it instead of by separate transforms: since
Z₀(s) = K⁰(s) + s A∞, the STF terms are K⁰(s)/s and K⁰(s)/s² plus constants. For a
coupling model K(s) = c (sI − a)⁻¹ b **[derived, not in thesis]**::

    K(s)/s  = c a⁻¹ (sI − a)⁻¹ b − (c a⁻¹ b)/s
    K(s)/s² = c a⁻² (sI − a)⁻¹ b − (c a⁻² b)/s − (c a⁻¹ b)/s²

so K¹ and K² have the *same poles* as K⁰ (stable when K⁰ is) and new output vectors.
The terms that are not memory are kept separately, as in the thesis: the U·α∞
infinite-frequency damping (eqs. 3.35 and §6: B₃₅(∞) = +U A∞₃₃, B₅₃(∞) = −U A∞₃₃,
B₂₆(∞) = −U A∞₂₂, B₆₂(∞) = +U A∞₂₂ …) and the 1/s terms, which act on the
displacement: a *radiation restoring* stiffness (Hjulstad (2004) §10.2: "the
subtracted constant corresponds to a pure integrator … a radiation restoring
coefficient"). In pitch it is C₅₅ = −U² A₃₃(0) (a destabilising, Munk-like moment;
A₃₃(0) of the model). c a⁻¹ b = K⁰(0) vanishes for fitted models (zero DC), so the 1/s² term is
zero to rounding; its size is recorded in ``attrs`` and it is not modelled.

The STF terms are those of :mod:`~cummins.radiation.speed.stf`. The model
(:class:`SpeedDependentModel`) also gives the radiation force for a speed that varies in
time (:meth:`SpeedDependentModel.radiation_force`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.linalg
import scipy.signal
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import FitError
from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.radiation.speed.blending import _blend
from cummins.radiation.speed.stf import _zero_speed, speed_coupling_matrix

#: Fit options the speed-dependent fits start from: the motion weighting that
#: :func:`cummins.radiation.fit.fit_radiation` uses by default weights the error by the zero-speed
#: equation of motion, which is not the one at speed; the memory parts are fitted by R²
#: over the frequencies below the first suspect one, as before motion weighting. Fit a K⁰
#: for :func:`speed_dependent_model` with the same options. The speed terms K¹, K² are
#: derived coupling by coupling (``method="fd"``: one SISO model per coupling), not from
#: the common-pole blocks of the zero-speed default.
SPEED_FIT_DEFAULTS: dict[str, Any] = {
    "method": "fd",
    "weighting": "uniform",
    "exclude_suspect": "above_first",
}


@dataclass(frozen=True)
class SpeedDependentModel:
    """Radiation model K_U = K⁰ + U K¹ + U² K² plus the non-memory speed terms.

    Force on the body (N, N·m) for body velocity ν (m/s, rad/s) and displacement η::

        τ = −A∞ ν̇ − (K⁰ + U K¹ + U² K²) * ν − U D¹ ν − (U G¹ + U² G²) η

    (``*`` convolution; Hjulstad (2004) eq. 3.28, with b = U·α∞ of §6/App. C.3).

    For a speed U(t) varying in a simulation, the states of K⁰, K¹, K² are driven by ν
    alone and U, U² scale their *outputs*, so the memory stays stable for any U(t).
    Hjulstad scales the inputs instead (§10.5, "rather arbitrary"); the two agree at
    constant speed only (a speed that varies in time, or a turn, breaks the steady-speed
    assumption of eq. 3.28, so neither choice is exact then).

    Attributes
    ----------
    k0
        The zero-speed model (the one given or fitted, unchanged).
    k1, k2
        Models of the linear and quadratic speed kernels (units of K⁰ per m/s, per m²/s²),
        same poles as the K⁰ couplings they come from.
    damping_inf
        D¹ (n, n): infinite-frequency damping per unit speed, B_U(∞) = U D¹ (kg/m, …):
        the U·α∞ terms, e.g. D¹₃₅ = +A∞₃₃, D¹₅₃ = −A∞₃₃.
    restoring
        G¹, G² (2, n, n): radiation restoring stiffness per U and per U² (the 1/s parts,
        module docstring), e.g. G²₅₅ = −A₃₃(0) of the model.
    attrs
        Provenance, and ``dropped_double_integrator``: max |c a⁻¹ b| of the K⁰ couplings
        used (should be ~0).
    """

    k0: RadiationModel
    k1: RadiationModel
    k2: RadiationModel
    damping_inf: NDArray[np.float64]
    restoring: NDArray[np.float64]
    attrs: Mapping[str, Any] = field(default_factory=dict)

    @property
    def dofs(self) -> tuple[str, ...]:
        """DOF labels."""
        return self.k0.dofs

    def response(self, omega: ArrayLike, speed: float) -> NDArray[np.complex128]:
        """Memory kernel K_U(jω) = K⁰ + U K¹ + U² K² (len(omega), n, n); at U = 0 this is
        ``k0.response(omega)`` exactly (the same array operations)."""
        r0 = self.k0.response(omega)
        if speed == 0:
            return r0
        return r0 + speed * self.k1.response(omega) + speed**2 * self.k2.response(omega)

    def impedance(self, omega: ArrayLike, speed: float) -> NDArray[np.complex128]:
        """Total radiation impedance Z_U(ω) = B_U + jω A_U = jω A∞ + K_U(jω) + U D¹
        + (U G¹ + U² G²)/(jω) (len(omega), n, n), kg/s …; compare with the data's
        B + jω A (:func:`stf_speed_terms`)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        s = 1j * w[:, None, None]
        z = s * self.k0.added_mass_inf[None] + self.response(w, speed)
        if speed == 0:
            return z
        stiff = speed * self.restoring[0] + speed**2 * self.restoring[1]
        return z + speed * self.damping_inf[None] + stiff[None] / s

    def added_mass_damping(
        self, omega: ArrayLike, speed: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """A_U(ω), B_U(ω) of the model (the STF-corrected coefficients it represents)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        z = self.impedance(w, speed)
        return z.imag / w[:, None, None], z.real

    def memory_model(self, speed: float) -> RadiationModel:
        """K_U at a fixed speed as one :class:`RadiationModel` (K⁰ itself at U = 0)."""
        if speed == 0:
            return self.k0
        return _blend([(1.0, self.k0), (float(speed), self.k1), (float(speed) ** 2, self.k2)])

    def radiation_force(
        self, t: ArrayLike, velocity: ArrayLike, speed: ArrayLike, motion: ArrayLike | None = None
    ) -> NDArray[np.float64]:
        """The speed-dependent radiation force without the A∞ν̇ term, for a speed that
        varies in time: μ(t) = (K⁰ * ν) + U(t) (K¹ * ν) + U(t)² (K² * ν) + U(t) D¹ ν(t)
        + (U(t) G¹ + U(t)² G²) η(t), N and N·m, shape (len(t), n).

        Each of K⁰, K¹, K² runs as its own state-space model on the velocity (from rest,
        :func:`scipy.signal.lsim`); U(t) scales their outputs, so the memory is stable for
        any speed history (class notes). ``speed`` is a scalar or one value per time (m/s);
        ``motion`` η is needed for the restoring terms (default zero)."""
        t = np.asarray(t, dtype=float).reshape(-1)
        v = np.asarray(velocity, dtype=float).reshape(t.size, -1)
        u = np.broadcast_to(np.asarray(speed, dtype=float), t.shape)
        eta = np.zeros_like(v) if motion is None else np.asarray(motion, float).reshape(v.shape)
        out = np.zeros_like(v)
        for power, model in enumerate((self.k0, self.k1, self.k2)):
            if model.total_order == 0:
                continue
            _, y, _ = scipy.signal.lsim(model.to_scipy(), v, t - t[0])
            out += (u**power)[:, None] * np.asarray(y).reshape(v.shape)
        out += u[:, None] * (v @ self.damping_inf.T)
        out += (u[:, None] * (eta @ self.restoring[0].T)) + (u**2)[:, None] * (
            eta @ self.restoring[1].T
        )
        return out

    def is_stable(self) -> bool:
        """True when K⁰, K¹ and K² are stable (then K_U is, for any U(t))."""
        return self.k0.is_stable() and self.k1.is_stable() and self.k2.is_stable()


def _distinct_sources(model: RadiationModel, e: NDArray, power: int):
    """{(i, j): {source coupling: σ}} for the U^power term of Z_U
    (:mod:`~cummins.radiation.speed.stf`)."""
    n = len(model.dofs)
    if power == 1:  # Z₀E − EᵀZ₀: (i, j) ← Σ_l Z_il E_lj − Σ_k E_ki Z_kj
        terms = [(i, l, i, j, e[l, j]) for i in range(n) for l in range(n) for j in range(n)]
        terms += [(k, j, i, j, -e[k, i]) for i in range(n) for k in range(n) for j in range(n)]
    else:  # −EᵀZ₀E: (i, j) ← −Σ E_ki Z_kl E_lj
        terms = [
            (k, l, i, j, -e[k, i] * e[l, j])
            for i in range(n)
            for j in range(n)
            for k in range(n)
            for l in range(n)
        ]
    out: dict[tuple[int, int], dict[int, tuple[CouplingModel, float]]] = {}
    for k, l, i, j, sigma in terms:
        if sigma == 0:
            continue
        source = model.coupling(k, l)
        if source is None:
            continue
        slot = out.setdefault((i, j), {})
        # symmetric pairs share their matrices: count them as one source
        key = next(
            (
                key
                for key, (m, _) in slot.items()
                if m.a is source.a
                or (np.array_equal(m.a, source.a) and np.array_equal(m.c, source.c))
            ),
            id(source),
        )
        m, total = slot.get(key, (source, 0.0))
        slot[key] = (m, total + sigma)
    return out


def speed_dependent_model(
    ds: xr.Dataset, model: RadiationModel | None = None, **fit_options: Any
) -> SpeedDependentModel:
    """K⁰, K¹, K² models of the forward-speed formulation of Hjulstad (2004) eqs. 3.28–3.36.

    Parameters
    ----------
    ds
        Zero-speed ``HydroDB`` (3-D panel data or the zero-speed strip-theory data).
    model
        The zero-speed model K⁰; fitted with :func:`cummins.radiation.fit.fit_radiation`
        (``**fit_options``) when not given.

    Returns
    -------
    SpeedDependentModel
        K¹, K² built exactly from the K⁰ couplings (module docstring): K¹₃₅ = K⁰₃₃/s
        (eq. 3.35: the cosine transform of α₃₃ − α∞₃₃ is the integral of K₃₃),
        K¹₅₃ = −K¹₃₅ (App. C.2), K²₅₅ from −K⁰₃₃/s² (eq. 3.32), D¹₃₅ = A∞₃₃ (eq. 3.35,
        the subtracted U α∞), K¹₅₅ = 0 (eq. 3.31), K²₃₅ = 0 (eq. 3.36), and the
        sway–yaw mirror terms.

    Raises
    ------
    FitError
        When a K⁰ coupling that a speed term needs has a singular state matrix.
    """
    ds = _zero_speed(ds)
    if model is None:
        from cummins.radiation.fit import fit_radiation

        model = fit_radiation(ds, **{**SPEED_FIT_DEFAULTS, **fit_options})
    if model.blocks:
        raise FitError(
            "the speed terms are built coupling by coupling, and this K⁰ holds common-pole blocks",
            hint="fit K⁰ with fit_radiation(ds, **SPEED_FIT_DEFAULTS) (method='fd'), or "
            "leave model out",
        )
    labels = list(model.dofs)
    n = len(labels)
    e = speed_coupling_matrix(labels)
    a_inf = model.added_mass_inf
    a_inf = 0.5 * (a_inf + a_inf.T)  # an antisymmetric A∞ part is not a speed term
    damping_inf = a_inf @ e - e.T @ a_inf
    restoring = np.zeros((2, n, n))
    restoring[1] = -(e.T @ a_inf @ e)
    dropped = 0.0
    built: list[RadiationModel] = []
    for power in (1, 2):
        couplings = []
        for (i, j), sources in sorted(_distinct_sources(model, e, power).items()):
            blocks = []
            for source, sigma in sources.values():
                if sigma == 0:
                    continue
                try:
                    inv = np.linalg.inv(source.a)
                except np.linalg.LinAlgError:
                    raise FitError(
                        f"coupling {labels[source.influenced]}-{labels[source.radiating]}: "
                        "singular state matrix, K/s has no state-space form"
                    ) from None
                c1 = source.c @ inv
                dc = float(c1 @ source.b)  # K(0) = −c a⁻¹ b
                if power == 1:
                    blocks.append((source.a, source.b, sigma * c1))
                    restoring[0, i, j] += -sigma * dc
                else:
                    c2 = c1 @ inv
                    blocks.append((source.a, source.b, sigma * c2))
                    restoring[1, i, j] += -sigma * float(c2 @ source.b)
                    dropped = max(dropped, abs(dc))
            if blocks:
                couplings.append(
                    CouplingModel(
                        i,
                        j,
                        scipy.linalg.block_diag(*[a for a, _, _ in blocks]),
                        np.concatenate([b for _, b, _ in blocks]),
                        np.concatenate([c for _, _, c in blocks]),
                        f"speed-K{power}",
                        note=f"K{power} from K0/s^{power} (Hjulstad (2004) eq. 3.28)",
                    )
                )
        built.append(RadiationModel(model.dofs, tuple(couplings), np.zeros((n, n))))
    return SpeedDependentModel(
        model,
        built[0],
        built[1],
        damping_inf,
        restoring,
        {"dropped_double_integrator": dropped, "source_file": model.attrs.get("source_file", "")},
    )
