"""The causal state-space excitation model: F(t) from the wave elevation η(t + t_c).

For each wave heading β the model is the single-input system (Yu & Falnes (1995); the
form HydroDyn's ``SS_Excitation`` integrates)

    ẋ = A x + B η(t + t_c),    F = C x,

with η the incident wave elevation at the origin (m), F the first-order wave forces and
moments (N, N·m) of every DOF, and t_c the time advance of that heading (s). Its
frequency response is

    F(ω)/η(ω) = C (jωI − A)⁻¹ B · e^{jω t_c}

in cummins' e^{+iωt} convention: the data's ``excitation_force`` at β. Each DOF has its
own states (a SISO model per DOF, as HydroDyn's ``.ssexctn`` stores them: the states of
a DOF are contiguous, C gives each DOF's force from its own states only); a DOF the
waves of that heading do not excite has none. D = 0: the causal impulse response
K_ex(t − t_c) has no impulse at t = 0, and the ``.ssexctn`` format has no D.

The model is frozen; :meth:`ExcitationModel.save` writes it as NetCDF
(:mod:`cummins.excitation_model.model_file`), :func:`~cummins.excitation_model.model_file.
read_excitation_model` reads it back exactly.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import scipy.linalg
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import CumminsError, HydroDataError
from cummins.radiation.model import SisoStateSpace

__all__ = ["DofExcitation", "ExcitationModel"]


@dataclass(frozen=True, eq=False)
class DofExcitation(SisoStateSpace):
    """The causal model of one DOF at one heading: H(s) = c (sI − a)⁻¹ b ≈ F(ω) e^{−jωt_c}.

    Attributes
    ----------
    dof, heading
        0-based indices into :attr:`ExcitationModel.dofs` and ``headings``.
    a, b, c
        (n, n), (n,), (n,); n may be 0 (a DOF not excited at that heading).
    metrics
        Fit measures: ``nrmse`` (complex response over the wave band, see
        :mod:`cummins.excitation_model.fit`), ``band_min``, ``band_max`` (rad/s),
        ``peak`` (max |F|), ``target_met`` …
    note
        What the user should know about this fit.
    """

    dof: int
    heading: int
    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    metrics: Mapping[str, Any] = field(default_factory=dict)
    note: str = ""


@dataclass(frozen=True, eq=False)
class ExcitationModel:
    """Causal state-space models of the wave excitation of every DOF, per heading.

    Attributes
    ----------
    dofs
        DOF labels (``Surge`` … ``Yaw``; ``body1__Surge`` … for several bodies).
    headings
        Directions of wave travel β, rad (0 following seas, π head seas), as the data.
    delays
        Time advance t_c of each heading, s (the model is driven by η(t + t_c)).
    models
        One :class:`DofExcitation` per (heading, DOF), heading-major: ``models[h * n + d]``.
    attrs
        Provenance and the fit's options: ``source_file``, ``rho``, ``g``,
        ``axis_convention``, ``reference_point``, ``nrmse_target``, ``causality``,
        ``failures`` …

    Examples
    --------
    >>> import numpy as np
    >>> one = DofExcitation(0, 0, np.array([[-1.0]]), np.array([1.0]), np.array([2.0]))
    >>> model = ExcitationModel(("Heave",), np.array([np.pi]), np.array([0.0]), (one,))
    >>> model.total_order, complex(model.frequency_response([0.0])[0, 0, 0])
    (1, (2+0j))
    """

    dofs: tuple[str, ...]
    headings: NDArray[np.float64]
    delays: NDArray[np.float64]
    models: tuple[DofExcitation, ...]
    attrs: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        n, nb = len(self.dofs), np.size(self.headings)
        if np.shape(self.delays) != (nb,):
            raise CumminsError(f"delays must have one value per heading ({nb})")
        if len(self.models) != n * nb:
            raise CumminsError(f"{len(self.models)} models for {nb} headings × {n} DOFs")
        for k, m in enumerate(self.models):
            if (m.heading, m.dof) != divmod(k, n):
                raise CumminsError(f"model {k} is not (heading {k // n}, DOF {k % n})")
            r = m.a.shape[0] if m.a.ndim == 2 else -1
            if m.a.shape != (r, r) or m.b.shape != (r,) or m.c.shape != (r,):
                raise CumminsError(f"model {k}: a must be n×n, b and c of length n")
        if not np.all(np.isfinite(self.delays)) or np.any(np.asarray(self.delays) < 0):
            raise CumminsError("the time advances t_c must be finite and >= 0")

    # ------------------------------------------------------------------ access

    def model(self, heading: int, dof: int) -> DofExcitation:
        """The model of DOF ``dof`` (index) at heading ``heading`` (index)."""
        return self.models[heading * len(self.dofs) + dof]

    def heading_index(self, direction: float, *, tol: float = 1e-6) -> int:
        """Index of the heading ``direction`` (rad); HydroDataError naming the headings
        modelled when it is not one of them."""
        beta = np.asarray(self.headings, dtype=float)
        gap = np.abs(np.angle(np.exp(1j * (beta - float(direction)))))
        k = int(np.argmin(gap))
        if gap[k] > tol:
            have = ", ".join(f"{np.degrees(b):g}" for b in beta)
            raise HydroDataError(
                f"no model for the wave direction {np.degrees(direction):g} deg",
                hint=f"the model holds {have} deg; fit that heading (cummins fit-excitation "
                "--heading DEG)",
            )
        return k

    @property
    def orders(self) -> NDArray[np.int_]:
        """States per (heading, DOF), shape (nβ, n)."""
        return np.array([m.order for m in self.models], dtype=int).reshape(
            np.size(self.headings), len(self.dofs)
        )

    @property
    def total_order(self) -> int:
        """States of all headings together."""
        return int(self.orders.sum())

    def is_stable(self) -> bool:
        """Every model's poles in the open left half-plane."""
        return all(m.is_stable() for m in self.models if m.order)

    # ------------------------------------------------------------------ state space

    def state_space(self, heading: int) -> tuple[NDArray, NDArray, NDArray]:
        """(A, B, C) of one heading (index): A block-diagonal by DOF, B (N,), C (n, N).

        The states of DOF d are contiguous, in DOF order (the layout of HydroDyn's
        ``.ssexctn``)."""
        parts = [self.model(heading, d) for d in range(len(self.dofs))]
        sizes = [p.order for p in parts]
        total = sum(sizes)
        a = scipy.linalg.block_diag(*[p.a for p in parts if p.order]) if total else np.zeros((0, 0))
        b = np.concatenate([p.b for p in parts]) if total else np.zeros(0)
        c = np.zeros((len(self.dofs), total))
        start = 0
        for d, p in enumerate(parts):
            c[d, start : start + p.order] = p.c
            start += p.order
        return a, b, c

    # ------------------------------------------------------------------ responses

    def frequency_response(
        self, omega: ArrayLike, *, causal: bool = False
    ) -> NDArray[np.complex128]:
        """F(ω)/η = c (jωI − a)⁻¹ b · e^{jωt_c}, shape (nω, nβ, n), N/m and N·m/m.

        ``causal=True`` leaves out the time advance: the response to η(t + t_c)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        n = len(self.dofs)
        out = np.zeros((w.size, np.size(self.headings), n), dtype=complex)
        for m in self.models:
            if m.order:
                out[:, m.heading, m.dof] = m.frequency_response(w)
        if not causal:
            out *= np.exp(1j * np.outer(w, self.delays))[:, :, None]
        return out

    def impulse_response(self, t: ArrayLike) -> NDArray[np.float64]:
        """The model's K_ex(t) = c e^{a(t + t_c)} b for t ≥ −t_c, 0 before; (nt, nβ, n)."""
        times = np.asarray(t, dtype=float).reshape(-1)
        out = np.zeros((times.size, np.size(self.headings), len(self.dofs)))
        for m in self.models:
            if not m.order:
                continue
            shifted = times + self.delays[m.heading]
            inside = shifted >= 0
            out[inside, m.heading, m.dof] = m.impulse_response(shifted[inside])
        return out

    def response_dataarray(self, omega: ArrayLike) -> xr.DataArray:
        """:meth:`frequency_response` as a DataArray (omega, wave_direction, influenced_dof),
        like the data's ``excitation_force``."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        return xr.DataArray(
            self.frequency_response(w),
            dims=("omega", "wave_direction", "influenced_dof"),
            coords={
                "omega": w,
                "wave_direction": np.asarray(self.headings, dtype=float),
                "influenced_dof": list(self.dofs),
            },
            name="excitation_force",
        )

    def force(
        self, t: ArrayLike, elevation: ArrayLike, heading: int = 0
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The wave forces driven by a record of the wave elevation at the origin.

        Integrates ẋ = A x + B η(t + t_c), F = C x exactly for an elevation that is
        linear between the samples (first-order hold; Van Loan (1978)), from x = 0 at
        the first sample. F(t) needs η up to t + t_c: it is returned for the times t of
        the record up to its end less t_c.

        Parameters
        ----------
        t
            Uniformly spaced times of the record, s.
        elevation
            η(t) at the origin, m.
        heading
            Index of the heading whose model to use.

        Returns
        -------
        (times, force)
            times (m,) and forces (m, n) in N, N·m, DOFs in the order of :attr:`dofs`.
        """
        from cummins.excitation_model.drive import drive_model

        return drive_model(self, t, elevation, heading)

    # ------------------------------------------------------------------ files

    def save(self, path: str | os.PathLike[str], *, force: bool = False) -> Path:
        """Write the model as NetCDF (:mod:`cummins.excitation_model.model_file`);
        ``force`` overwrites an existing file."""
        from cummins.errors import check_writable
        from cummins.excitation_model.model_file import write_excitation_model

        check_writable(Path(path), force)
        return write_excitation_model(self, path)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> ExcitationModel:
        """Read a model written by :meth:`save`."""
        from cummins.excitation_model.model_file import read_excitation_model

        return read_excitation_model(path)
