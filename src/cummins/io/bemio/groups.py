"""The groups of a BEMIO ``.h5`` file, one writer function per group.

Each function writes one group of one body (or the file's ``simulation_parameters``)
from a :class:`BemioData` (the data prepared once: dimensional, z-up, about each body's
centre of gravity) through an :class:`H5Out` (datasets with ``description`` and
``units`` attributes and HDF5's Fletcher-32 checksum). :data:`BODY_GROUPS` lists the
per-body writers in the order :func:`cummins.io.bemio.write_bemio` calls them; a new
group (mean drift, QTFs …) is one more function added there.

Layouts (h5py order, MATLAB's ``permute`` reversed; see :mod:`cummins.io.bemio`):
arrays ``all`` (m, N, nω), excitation (m, nβ, nω), normalised as BEMIO's ``hydro``
structure (A/ρ, B/(ρω), C and F/(ρg), K/ρ, K_ex/(ρg)); and the ``components``
subgroups of the older MATLAB writer that some scripts read: ``<i>_<j>`` arrays (nω, 2)
of (period, value), ``i`` the body's own row (1-based), ``j`` the column of all DOFs or
the heading; (t, value) for the impulse responses.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

__all__ = ["BODY_GROUPS", "BemioData", "BodyRows", "H5Out"]


class H5Out:
    """Writes datasets into an open :class:`h5py.File`."""

    def __init__(self, f) -> None:
        self.file = f

    def text(self, name: str, value: str) -> None:
        """A scalar string dataset."""
        data = (value or " ").encode("utf-8")
        self.file.create_dataset(name, data=np.bytes_(data))

    def number(self, name: str, values, description: str, units: str) -> None:
        """A float dataset with ``description`` and ``units`` (and a checksum)."""
        data = np.asarray(values, dtype=float)
        dset = self.file.create_dataset(name, data=data, fletcher32=data.size > 0)
        dset.attrs["description"] = np.bytes_(description or " ")
        dset.attrs["units"] = np.bytes_(units or " ")

    def components(self, base: str, first, values, description: str) -> None:
        """``base/components/<i>_<j>`` = (first, values[i, j]) as (n, 2) arrays."""
        m, count = values.shape[:2]
        for i in range(m):
            for j in range(count):
                self.number(
                    f"{base}/components/{i + 1}_{j + 1}",
                    np.c_[first, values[i, j]],
                    description,
                    "",
                )


@dataclass(frozen=True)
class BodyRows:
    """One body of the file: ``number`` (1-based), its rows ``start`` … ``start + modes``."""

    number: int
    start: int
    modes: int

    @property
    def rows(self) -> slice:
        return slice(self.start, self.start + self.modes)

    @property
    def group(self) -> str:
        return f"body{self.number}"


@dataclass(frozen=True)
class BemioData:
    """The data a BEMIO file holds, prepared once (SI units, z-up, about each body's
    centre of gravity; the writers normalise).

    ``forces`` maps the group (``excitation``, ``excitation/froude-krylov``,
    ``excitation/scattering``) to F (nω, nβ, n); ``radiation_irf`` is (t, K (nt, n, n));
    ``excitation_irf`` (t, K_ex (nt, nβ, n)) or None; ``state_space`` the per-coupling
    arrays of :func:`cummins.io.bemio.state_space._state_space` or None; ``volume`` per
    body, NaN where the data do not know it; ``ds`` the dataset they come from (z-up,
    about each body's centre of gravity), for a group writer that needs more of it.
    """

    rho: float
    g: float
    omega: np.ndarray
    directions: np.ndarray
    names: list[str]
    cg: list[np.ndarray]
    cb: list[np.ndarray]
    volume: np.ndarray
    added: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    added_inf: np.ndarray
    added_inf_note: str
    forces: dict[str, np.ndarray]
    radiation_irf: tuple[np.ndarray, np.ndarray]
    excitation_irf: tuple[np.ndarray, np.ndarray] | None = None
    state_space: dict | None = None
    notes: list[str] = field(default_factory=list)
    ds: xr.Dataset | None = field(default=None, repr=False)

    @property
    def periods(self) -> np.ndarray:
        return 2 * np.pi / self.omega


def write_simulation_parameters(out: H5Out, data: BemioData, depth: float, code: str) -> None:
    """``simulation_parameters``: ρ, g, ω, T, headings (deg), depth, ``scaled`` = 0."""
    from cummins._version import __version__

    out.text("bem_data/code", code)
    out.text("cummins_version", __version__)
    if np.isinf(depth):
        out.text("simulation_parameters/water_depth", "infinite")
    else:
        out.number("simulation_parameters/water_depth", [[depth]], "Water depth", "m")
    out.number("simulation_parameters/scaled", [[0.0]], "", "")
    out.number("simulation_parameters/g", [[data.g]], "Gravitational acceleration", "m/s^2")
    out.number("simulation_parameters/rho", [[data.rho]], "Water density", "kg/m^3")
    out.number("simulation_parameters/T", data.periods[:, None], "Wave periods", "s")
    out.number("simulation_parameters/w", data.omega[:, None], "Wave frequencies", "rad/s")
    out.number(
        "simulation_parameters/wave_dir",
        np.degrees(data.directions)[:, None],
        "Wave direction",
        "deg",
    )


def write_properties(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``properties``: name, number, cg, cb, disp_vol (left out where unknown), DOFs."""
    k = body.number - 1
    group = f"{body.group}/properties"
    out.text(f"{group}/name", data.names[k])
    out.number(
        f"{group}/body_number",
        [[float(body.number)]],
        "Number of rigid body from the BEM simulation",
        "",
    )
    out.number(f"{group}/cb", data.cb[k][:, None], "Center of buoyancy", "m")
    out.number(f"{group}/cg", data.cg[k][:, None], "Center of gravity", "m")
    if np.isfinite(data.volume[k]):
        out.number(f"{group}/disp_vol", [[data.volume[k]]], "Displaced volume", "m^3")
    out.number(f"{group}/dof", [[float(body.modes)]], "Degrees of freedom", "")
    out.number(f"{group}/dof_start", [[body.start + 1.0]], "Degrees of freedom", "")
    out.number(f"{group}/dof_end", [[float(body.start + body.modes)]], "Degrees of freedom", "")


def write_hydrostatics(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``hydro_coeffs/linear_restoring_stiffness``: the body's C/(ρg), m × m."""
    rows = body.rows
    out.number(
        f"{body.group}/hydro_coeffs/linear_restoring_stiffness",
        data.stiffness[rows, rows] / (data.rho * data.g),
        "Hydrostatic stiffness matrix (normalized by rho*g)",
        "N/m",
    )


def write_added_mass(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``hydro_coeffs/added_mass``: ``all`` A/ρ, ``inf_freq`` A∞/ρ, ``components``."""
    group = f"{body.group}/hydro_coeffs/added_mass"
    values = np.transpose(data.added[:, body.rows, :], (1, 2, 0)) / data.rho
    out.number(
        f"{group}/inf_freq", data.added_inf[body.rows, :] / data.rho, data.added_inf_note, "kg"
    )
    out.number(f"{group}/all", values, "Added mass (normalized by rho)", "kg")
    out.components(group, data.periods, values, "Added mass components as a function of frequency")


def write_radiation_damping(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``hydro_coeffs/radiation_damping``: ``all`` B/(ρω), ``components``."""
    group = f"{body.group}/hydro_coeffs/radiation_damping"
    per_omega = data.damping[:, body.rows, :] / data.omega[:, None, None]
    values = np.transpose(per_omega, (1, 2, 0)) / data.rho
    out.number(f"{group}/all", values, "Radiation damping (normalized by rho*w)", "N-s/m")
    out.components(
        group, data.periods, values, "Radiation damping components as a function of frequency"
    )


_FORCE_NAMES = {
    "excitation": "excitation",
    "excitation/froude-krylov": "Froude-Krylov",
    "excitation/scattering": "scattering",
}


def write_excitation(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``hydro_coeffs/excitation`` (and ``froude-krylov``, ``scattering`` where the data
    hold them): re, im, mag, phase of F/(ρg), (m, nβ, nω), and their ``components``."""
    for group, values in data.forces.items():
        part = np.transpose(values[:, :, body.rows], (2, 1, 0)) / (data.rho * data.g)
        what = _FORCE_NAMES[group]
        path = f"{body.group}/hydro_coeffs/{group}"
        for key, array, unit in (
            ("re", part.real, "N"),
            ("im", part.imag, "N"),
            ("mag", np.abs(part), "N"),
            ("phase", np.angle(part), "rad"),
        ):
            out.number(f"{path}/{key}", array, f"{key} of {what} force (normalized by rho*g)", unit)
            _force_components(out, path, key, data.periods, array, what)


def _force_components(out: H5Out, path: str, key: str, periods, array, what: str) -> None:
    """``<path>/components/<key>/<i>_<k>`` = (T, value) per DOF i and heading k."""
    m, nb = array.shape[:2]
    for i in range(m):
        for k in range(nb):
            out.number(
                f"{path}/components/{key}/{i + 1}_{k + 1}",
                np.c_[periods, array[i, k]],
                f"{key} of {what} force as a function of frequency",
                "",
            )


def write_excitation_irf(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``hydro_coeffs/excitation/impulse_response_fun``: ``f`` K_ex/(ρg) (m, nβ, nt),
    ``t`` (symmetric about 0), ``w``, and ``components/f``."""
    if data.excitation_irf is None:
        return
    t, k = data.excitation_irf
    _write_irf(
        out,
        f"{body.group}/hydro_coeffs/excitation/impulse_response_fun",
        "f",
        t,
        np.transpose(k[:, :, body.rows], (2, 1, 0)) / (data.rho * data.g),
        data.omega,
        ("Impulse response function (normalized by rho*g)", "Components of the IRF:f"),
    )


def write_radiation_irf(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``hydro_coeffs/radiation_damping/impulse_response_fun``: ``K`` K(t)/ρ (m, N, nt),
    ``t``, ``w``, and ``components/K``."""
    t, kernel = data.radiation_irf
    _write_irf(
        out,
        f"{body.group}/hydro_coeffs/radiation_damping/impulse_response_fun",
        "K",
        t,
        np.transpose(kernel[:, body.rows, :], (1, 2, 0)) / data.rho,
        data.omega,
        ("Impulse response function (normalized by rho)", "Components of the IRF"),
    )


def _write_irf(out: H5Out, group: str, name: str, t, values, omega, descriptions) -> None:
    """An impulse-response group of BEMIO's layout: ``name`` (m, n, nt), ``t``, ``w`` and
    ``components/name/i_j`` ([t, value] columns), with BEMIO's descriptions (its spelling
    of "resonse" included)."""
    whole, component = descriptions
    out.number(f"{group}/{name}", values, whole, "")
    out.number(f"{group}/t", t[:, None], "Time vector for the impulse resonse function", "s")
    out.number(
        f"{group}/w",
        omega[:, None],
        "Frequencies of the data the impulse response function integrates",
        "rad/s",
    )
    m, count = values.shape[:2]
    for i in range(m):
        for j in range(count):
            out.number(
                f"{group}/components/{name}/{i + 1}_{j + 1}", np.c_[t, values[i, j]], component, ""
            )


def write_state_space(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``hydro_coeffs/radiation_damping/state_space`` of a fitted model (A, B, C/ρ, D,
    K, it, r2t, conv), when one is given."""
    ss = data.state_space
    if ss is None:
        return
    rows = body.rows
    group = f"{body.group}/hydro_coeffs/radiation_damping/state_space"
    for key in ("A", "B", "C", "K"):
        out.number(f"{group}/{key}/all", ss[key][rows], f"State Space {key} Coefficient", "")
    out.number(f"{group}/D/all", ss["D"][rows], "State Space D Coefficient", "")
    out.number(f"{group}/it", ss["it"][rows], "Order of state space realization", "")
    out.number(f"{group}/r2t", ss["r2t"][rows], "State space curve fitting R**2 value", "")
    out.number(f"{group}/conv", ss["conv"][rows], "State space conversion status", "")


#: The per-body group writers, in the order :func:`cummins.io.bemio.write_bemio` calls
#: them: f(out, data, body).
def write_mean_drift_group(out: H5Out, data: BemioData, body: BodyRows) -> None:
    """``hydro_coeffs/mean_drift/<method>``: the data's mean-drift estimates, where
    WEC-Sim reads them (:func:`cummins.io.bemio.second_order.write_mean_drift`)."""
    from cummins.io.bemio.second_order import write_mean_drift

    write_mean_drift(out.number, f"{body.group}/hydro_coeffs", data.ds, body.rows, data.rho, data.g)


BODY_GROUPS: list[Callable[[H5Out, BemioData, BodyRows], None]] = [
    write_properties,
    write_hydrostatics,
    write_added_mass,
    write_radiation_damping,
    write_excitation,
    write_excitation_irf,
    write_mean_drift_group,
    write_radiation_irf,
    write_state_space,
]
