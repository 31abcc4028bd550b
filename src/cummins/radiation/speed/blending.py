"""Radiation models fitted at several forward speeds, blended linearly in U.

Per-speed fits (Hjulstad (2004)): one :class:`~cummins.radiation.model.RadiationModel`
per speed of a multi-speed database (``forward_speed`` dimension, e.g. the MSS S-175
at 5 speeds), blended linearly in U between the two neighbouring fitted speeds
(:meth:`SpeedModels.at`).
The fits themselves are :func:`~cummins.radiation.speed.per_speed.fit_per_speed`.
"""

from __future__ import annotations

import bisect
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.linalg
import scipy.signal
from numpy.typing import ArrayLike, NDArray

from cummins.radiation.model import CouplingModel, RadiationModel
from cummins.radiation.speed.errors import SpeedError


def _blend(models: Sequence[tuple[float, RadiationModel]]) -> RadiationModel:
    """Σ w_k K_k as one state-space model: the couplings' blocks stacked, outputs scaled."""
    first = models[0][1]
    n = len(first.dofs)
    parts: dict[tuple[int, int], list[tuple[float, CouplingModel]]] = {}
    for weight, model in models:
        if model.dofs != first.dofs:
            raise SpeedError("models at different speeds have different DOFs")
        for k in model.couplings:
            parts.setdefault((k.influenced, k.radiating), []).append((weight, k))
    couplings = []
    for (i, j), items in sorted(parts.items()):
        a = scipy.linalg.block_diag(*[k.a for _, k in items])
        b = np.concatenate([k.b for _, k in items])
        c = np.concatenate([w * k.c for w, k in items])
        couplings.append(CouplingModel(i, j, a, b, c, "speed-blend"))
    a_inf = sum(w * m.added_mass_inf for w, m in models)
    return RadiationModel(first.dofs, tuple(couplings), np.asarray(a_inf).reshape(n, n))


@dataclass(frozen=True)
class SpeedModels:
    """Radiation models fitted at several forward speeds, blended between them.

    Attributes
    ----------
    speeds
        Fitted forward speeds, m/s, increasing.
    models
        One :class:`~cummins.radiation.model.RadiationModel` per speed.

    Notes
    -----
    :meth:`at` between two fitted speeds U_a < U < U_b returns the linear blend
    K_U(s) = (1 − λ) K_a(s) + λ K_b(s), λ = (U − U_a)/(U_b − U_a), and A∞ likewise,
    realised as one state-space model (both models' states, outputs scaled by 1 − λ and
    λ). So the frequency responses *and* the time-domain memory forces are interpolated
    linearly in U; the poles are those of the two fitted models, hence stable. A
    simulation with a varying speed can run every fitted model on the same velocity and
    blend their outputs with the weights of the current speed (at most two non-zero);
    this stays stable for any U(t), since the weights act on outputs only. Outside the
    fitted range: :class:`SpeedError`.

    When the speed terms that are not memory were taken out before fitting
    (``damping_inf`` D¹ and ``restoring`` G¹, G², :func:`fit_per_speed`), the radiation
    force at speed U is the models' memory plus U D¹ ν + (U G¹ + U² G²) η
    (:meth:`impedance`), as in :class:`SpeedDependentModel`.
    """

    speeds: tuple[float, ...]
    models: tuple[RadiationModel, ...]
    attrs: Mapping[str, Any] = field(default_factory=dict)
    damping_inf: NDArray[np.float64] | None = None
    restoring: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        if len(self.speeds) != len(self.models) or not self.speeds:
            raise SpeedError("SpeedModels needs one model per speed, at least one")
        if any(b <= a for a, b in zip(self.speeds, self.speeds[1:], strict=False)):
            raise SpeedError(f"speeds must increase: {self.speeds}")

    def _weights(self, speed: float) -> list[tuple[float, int]]:
        u = float(speed)
        lo, hi = self.speeds[0], self.speeds[-1]
        if not lo - 1e-9 <= u <= hi + 1e-9:
            raise SpeedError(
                f"speed {u:g} m/s is outside the fitted speeds {lo:g} … {hi:g} m/s",
                hint="extrapolation in speed is not supported; fit data at that speed",
            )
        for k, s in enumerate(self.speeds):
            if abs(u - s) <= 1e-9 * max(1.0, abs(s)):
                return [(1.0, k)]
        k = bisect.bisect_right(self.speeds, u)
        ua, ub = self.speeds[k - 1], self.speeds[k]
        lam = (u - ua) / (ub - ua)
        return [(1.0 - lam, k - 1), (lam, k)]

    def at(self, speed: float) -> RadiationModel:
        """The model at ``speed`` (m/s): the fitted model itself at a fitted speed
        (the same object), else the linear blend of its two neighbours (class notes)."""
        weights = self._weights(speed)
        if len(weights) == 1:
            return self.models[weights[0][1]]
        return _blend([(w, self.models[k]) for w, k in weights])

    def response(self, omega: ArrayLike, speed: float) -> NDArray[np.complex128]:
        """K_U(jω) (len(omega), n, n) at ``speed``, linear in U between fitted speeds."""
        weights = self._weights(speed)
        return sum(w * self.models[k].response(omega) for w, k in weights)

    def impedance(self, omega: ArrayLike, speed: float) -> NDArray[np.complex128]:
        """Z_U(jω) = jω A∞ + K_U(jω) + U D¹ + (U G¹ + U² G²)/(jω): the radiation force
        per unit body velocity, to compare with B_U(ω) + jω A_U(ω) of the data."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        weights = self._weights(speed)
        a_inf = sum(wk * np.asarray(self.models[k].added_mass_inf) for wk, k in weights)
        z = 1j * w[:, None, None] * a_inf + self.response(w, speed)
        if self.damping_inf is not None:
            u = float(speed)
            z = z + u * self.damping_inf
            z = z + (u * self.restoring[0] + u**2 * self.restoring[1]) / (1j * w[:, None, None])
        return z

    def is_stable(self) -> bool:
        """True when every fitted model is stable (then so is every blend)."""
        return all(m.is_stable() for m in self.models)
