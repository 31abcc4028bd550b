"""The second-order wave loads of a ``HydroDB``: mean drift and quadratic transfer functions.

The canonical form, whatever the solver (WAMIT ``.7/.8/.9`` and ``.10d–.12s``, NEMOH v3
``OUT_QTF[M|P]_N.dat``, AQWA's ``.LIS`` drift tables and ``.QTF``, Capytaine's far-field
drift, a cummins NetCDF), dimensional and in SI units, in the dataset's axes and about its
``reference_point``:

==========================  ===============================================  ==============
variable                    dims                                             unit
==========================  ===============================================  ==============
``drift_force``             omega, wave_direction, influenced_dof            N/m², N·m/m²
``drift_force_<method>``    as ``drift_force`` (the other estimates a run    N/m², N·m/m²
                            writes: ``pressure``, ``momentum``,
                            ``control_surface``)
``qtf_difference``          qtf_omega, qtf_omega2, qtf_wave_direction,       N/m², N·m/m²
                            [qtf_wave_direction2,] influenced_dof            (complex)
``qtf_sum``                 as ``qtf_difference``                            N/m², N·m/m²
==========================  ===============================================  ==============

The QTFs have their own frequency grid (``qtf_omega`` = ``qtf_omega2``, rad/s: solvers
compute them on a coarser grid than the first-order coefficients) and their own headings
(``qtf_wave_direction``, rad, the direction the waves travel, as ``wave_direction``);
``qtf_wave_direction2`` exists only for bi-directional data (pairs of waves of two
directions), otherwise both waves of a pair travel in the same direction. The full
square of frequency pairs is stored (both triangles), whichever triangle the file held.

**The force** (the convention of WAMIT's second-order output and of OpenFAST HydroDyn's
``WAMIT2`` module, which reads it). The sea is ζ(t) = Re Σ_i c_i e^{iω_i t}, c_i = a_i e^{iφ_i}
the complex amplitude of component i at the origin (as
:class:`cummins.seakeeping.waves.WaveComponents`); then

    F⁻(t) = Re Σ_i Σ_j c_i c_j* Q⁻(ω_i, ω_j, β_i, β_j) e^{i(ω_i − ω_j) t},
    F⁺(t) = Re Σ_i Σ_j c_i c_j  Q⁺(ω_i, ω_j, β_i, β_j) e^{i(ω_i + ω_j) t},

both double sums over every ordered pair (the full square, no factor ½). So a regular
wave of amplitude a gives the mean drift a² Q⁻(ω, ω) (``drift_force`` = Re Q⁻(ω, ω, β, β))
and the double-frequency force Re a² Q⁺(ω, ω) e^{2iωt}; two waves give the
difference-frequency force 2 Re[c₁ c₂* Q⁻(ω₁, ω₂) e^{i(ω₁−ω₂)t}]; and an irregular sea of
spectrum S(ω) the mean force Σ a_i² Q⁻(ω_i, ω_i) = 2 ∫ S(ω) Q⁻(ω, ω) dω (a_i² = 2 S Δω).
The symmetries Q⁻(ω_j, ω_i, β_j, β_i) = Q⁻(ω_i, ω_j, β_i, β_j)* and Q⁺(ω_j, ω_i, β_j, β_i) =
Q⁺(ω_i, ω_j, β_i, β_j) follow (the sums pair (i, j) with (j, i)); readers fill the
triangle a file leaves out by them. Time dependence e^{+iωt}, phases relative to the
incident wave at the origin, as the first-order ``excitation_force`` (NEMOH's e^{−iωt}
values are conjugated on reading). The moments are about ``reference_point``, a point
fixed in space (WAMIT's positive mode indices; its negative indices, the moments in the
moving body axes, are not read).

:class:`QTFTable` holds one QTF as arrays; :func:`qtf_table` takes it out of a dataset,
:func:`with_second_order` puts tables (and mean drift) into one, :func:`complete_square`
builds the full square from the rows of a file (readers), :func:`second_order_summary`
says what a dataset holds (``cummins info``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from cummins.errors import HydroDataError

#: The QTF variables of a ``HydroDB`` by kind.
QTF_VARIABLES: dict[str, str] = {"difference": "qtf_difference", "sum": "qtf_sum"}
OMEGA, OMEGA2 = "qtf_omega", "qtf_omega2"
DIRECTION, DIRECTION2 = "qtf_wave_direction", "qtf_wave_direction2"
#: The mean-drift estimates a run may hold besides ``drift_force`` (its preferred one).
DRIFT_METHODS: dict[str, str] = {
    "pressure": "pressure integration",
    "control_surface": "control surface",
    "momentum": "momentum conservation (far field)",
}
DRIFT_ALTERNATIVES: tuple[str, ...] = tuple(f"drift_force_{m}" for m in DRIFT_METHODS)

#: What to do when the data hold no QTF (every "no QTF" error says it).
NO_QTF_HINT = (
    "read the solver's QTF output with the run (WAMIT .12d/.12s, NEMOH "
    "results/QTF/OUT_QTFM_N.dat, AQWA .QTF beside the .LIS)"
)

_UNITS = "N/m^2 | N m/m^2 (per product of wave amplitudes)"
_LONG_NAMES = {
    "difference": "difference-frequency quadratic transfer function Q-(w1, w2, b1, b2)",
    "sum": "sum-frequency quadratic transfer function Q+(w1, w2, b1, b2)",
}
CONVENTION = (
    "F-(t) = Re sum_i sum_j c_i conj(c_j) Q-(w_i, w_j) exp(i (w_i - w_j) t), "
    "F+(t) = Re sum_i sum_j c_i c_j Q+(w_i, w_j) exp(i (w_i + w_j) t), "
    "zeta(t) = Re sum_i c_i exp(i w_i t) at the origin; full square, no 1/2"
)


@dataclass(frozen=True)
class QTFTable:
    """One quadratic transfer function as arrays.

    Attributes
    ----------
    kind
        ``"difference"`` or ``"sum"``.
    omega
        The frequency grid ω, rad/s, shape (n,), increasing (both frequencies of a pair
        are on it).
    directions
        Wave directions β (rad), shape (m,), increasing.
    values
        Q, complex, N/m² and N·m/m²: shape (n, n, m, d) for unidirectional data
        (Q[i, j, a, k] = Q_k(ω_i, ω_j, β_a, β_a)) and (n, n, m, m, d) for bi-directional
        data (Q[i, j, a, b, k] = Q_k(ω_i, ω_j, β_a, β_b)).
    dofs
        The DOF labels (``influenced_dof``), length d.
    bidirectional
        Whether the two waves of a pair may travel in different directions.
    """

    kind: str
    omega: NDArray[np.float64]
    directions: NDArray[np.float64]
    values: NDArray[np.complex128]
    dofs: tuple[str, ...]
    bidirectional: bool = False

    def __post_init__(self) -> None:
        if self.kind not in QTF_VARIABLES:
            raise HydroDataError(f"QTF kind must be 'difference' or 'sum', not {self.kind!r}")
        n, m, d = self.omega.size, self.directions.size, len(self.dofs)
        shape = (n, n, m, m, d) if self.bidirectional else (n, n, m, d)
        if self.values.shape != shape:
            raise HydroDataError(
                f"QTF values have shape {self.values.shape}, expected {shape} "
                "(frequency, frequency, direction(s), DOF)"
            )

    @property
    def name(self) -> str:
        """The variable name in a ``HydroDB``."""
        return QTF_VARIABLES[self.kind]

    def diagonal(self) -> NDArray[np.complex128]:
        """Q(ω_i, ω_i, β_a, β_a), shape (n, m, d): the mean drift (difference) or the
        double-frequency force (sum) of regular waves, per squared amplitude."""
        v = self.values
        if self.bidirectional:
            v = np.diagonal(v, axis1=2, axis2=3)  # (n, n, d, m)
            v = np.moveaxis(v, -1, 2)
        return np.diagonal(v, axis1=0, axis2=1).transpose(2, 0, 1)

    def to_dataarray(self, attrs: dict | None = None) -> xr.DataArray:
        """The table as the ``qtf_difference``/``qtf_sum`` variable of a ``HydroDB``."""
        dims = (OMEGA, OMEGA2, DIRECTION, DIRECTION2, "influenced_dof")
        if not self.bidirectional:
            dims = (OMEGA, OMEGA2, DIRECTION, "influenced_dof")
        coords = {
            OMEGA: (OMEGA, self.omega, {"units": "rad/s", "long_name": "first wave frequency"}),
            OMEGA2: (OMEGA2, self.omega, {"units": "rad/s", "long_name": "second wave frequency"}),
            DIRECTION: (
                DIRECTION,
                self.directions,
                {"units": "rad", "long_name": "direction of propagation of the first wave"},
            ),
            "influenced_dof": ("influenced_dof", list(self.dofs)),
        }
        if self.bidirectional:
            coords[DIRECTION2] = (
                DIRECTION2,
                self.directions,
                {"units": "rad", "long_name": "direction of propagation of the second wave"},
            )
        out = xr.DataArray(self.values, dims=dims, coords=coords, name=self.name)
        out.attrs.update(
            units=_UNITS, long_name=_LONG_NAMES[self.kind], convention=CONVENTION, **(attrs or {})
        )
        return out


def has_qtf(ds: xr.Dataset, kind: str | None = None) -> bool:
    """Whether the dataset holds a QTF (of ``kind``, or any)."""
    names = QTF_VARIABLES.values() if kind is None else [QTF_VARIABLES[kind]]
    return any(name in ds for name in names)


def qtf_table(ds: xr.Dataset, kind: str = "difference") -> QTFTable:
    """The dataset's ``qtf_difference`` (or ``qtf_sum``) as a :class:`QTFTable`.

    Raises
    ------
    HydroDataError
        The dataset holds no such QTF.
    """
    if kind not in QTF_VARIABLES:
        raise HydroDataError(f"QTF kind must be 'difference' or 'sum', not {kind!r}")
    name = QTF_VARIABLES[kind]
    if name not in ds:
        have = [k for k, v in QTF_VARIABLES.items() if v in ds]
        raise HydroDataError(
            f"the dataset has no {kind}-frequency QTF ({name})",
            path=ds.attrs.get("source_file"),
            hint=f"it holds a {have[0]}-frequency QTF" if have else NO_QTF_HINT,
        )
    var = ds[name]
    bidirectional = DIRECTION2 in var.dims
    order = (OMEGA, OMEGA2, DIRECTION, DIRECTION2, "influenced_dof")
    var = var.transpose(*[d for d in order if d in var.dims])
    return QTFTable(
        kind=kind,
        omega=np.asarray(var[OMEGA].values, dtype=float),
        directions=np.asarray(var[DIRECTION].values, dtype=float),
        values=np.asarray(var.values, dtype=complex),
        dofs=tuple(str(d) for d in var.influenced_dof.values),
        bidirectional=bidirectional,
    )


def with_second_order(
    ds: xr.Dataset,
    tables: Iterable[QTFTable] = (),
    *,
    drift: dict[str, tuple[NDArray, str]] | None = None,
    wave_direction: ArrayLike | None = None,
    history: Sequence[str] = (),
    attrs: dict[str, dict] | None = None,
) -> xr.Dataset:
    """A copy of ``ds`` with QTFs and mean-drift estimates added.

    Parameters
    ----------
    ds
        A ``HydroDB``.
    tables
        :class:`QTFTable` s on the dataset's DOFs (``qtf_difference``, ``qtf_sum``);
        the difference and sum QTFs of one dataset share their grid.
    drift
        Mean drift per squared amplitude, {variable: (values (nω, nβ, n), description)},
        on the dataset's ``omega`` and ``wave_direction``: ``drift_force`` and
        ``drift_force_<method>`` (:data:`DRIFT_ALTERNATIVES`).
    wave_direction
        The directions (rad) of the mean drift when the dataset has none (a run without
        first-order excitation).
    history
        Lines appended to ``history``.
    attrs
        Further attributes per variable.

    Raises
    ------
    HydroDataError
        Shapes that do not fit the dataset, non-finite values, grids that are not
        increasing and positive, two QTFs on different grids.
    """
    out = ds.copy()
    # the QTF grid of variables since dropped: replaced by the new tables'
    stale = [
        c
        for c in (OMEGA, OMEGA2, DIRECTION, DIRECTION2)
        if c in out.coords and not any(c in v.dims for v in out.data_vars.values())
    ]
    out = out.drop_vars(stale)
    where = ds.attrs.get("source_file") or None
    attrs = attrs or {}
    labels = [str(d) for d in ds.influenced_dof.values]
    grids: list[tuple[NDArray, NDArray]] = []
    for table in tables:
        if list(table.dofs) != labels:
            raise HydroDataError(
                f"the {table.kind}-frequency QTF has DOFs {list(table.dofs)}, the data {labels}",
                path=where,
            )
        _check_grid(table.omega, "QTF frequency", "rad/s", where)
        _check_grid(table.directions, "QTF wave direction", "rad", where, positive=False)
        if not np.all(np.isfinite(table.values)):
            k = np.argwhere(~np.isfinite(table.values))[0]
            raise HydroDataError(
                f"non-finite {table.kind}-frequency QTF at omega = {table.omega[k[0]]:.6g}, "
                f"{table.omega[k[1]]:.6g} rad/s, {labels[k[-1]]}",
                path=where,
            )
        for omega, directions in grids:
            if not (
                omega.shape == table.omega.shape
                and np.allclose(omega, table.omega)
                and directions.shape == table.directions.shape
                and np.allclose(directions, table.directions)
            ):
                raise HydroDataError(
                    "the difference- and sum-frequency QTFs are on different grids",
                    path=where,
                    hint="read them from the same run",
                )
        grids.append((table.omega, table.directions))
        var = table.to_dataarray(attrs.get(table.name))
        for key in (OMEGA, OMEGA2, DIRECTION, DIRECTION2):
            if key in out.coords and key in var.coords:
                var = var.assign_coords({key: out[key].values})
        out[table.name] = var
    if drift and "wave_direction" not in out.dims:
        if wave_direction is None:
            raise HydroDataError("mean drift needs the dataset's wave_direction", path=where)
        out = out.assign_coords(
            wave_direction=(
                "wave_direction",
                np.asarray(wave_direction, dtype=float).reshape(-1),
                {"units": "rad", "long_name": "direction of wave propagation (0 = along +x)"},
            )
        )
    for name, (values, description) in (drift or {}).items():
        if name != "drift_force" and name not in DRIFT_ALTERNATIVES:
            raise HydroDataError(f"unknown mean-drift variable {name!r}")
        values = np.asarray(values, dtype=float)
        shape = (out.sizes["omega"], out.sizes["wave_direction"], len(labels))
        if values.shape != shape:
            raise HydroDataError(f"{name} has shape {values.shape}, expected {shape}", path=where)
        if not np.all(np.isfinite(values)):
            raise HydroDataError(f"non-finite value in {name}", path=where)
        out[name] = (("omega", "wave_direction", "influenced_dof"), values)
        out[name].attrs.update(
            units="N/m^2 | N m/m^2 (mean drift per squared wave amplitude)",
            long_name=f"mean second-order wave drift force ({description})",
            method=description,
            **attrs.get(name, {}),
        )
    for line in history:
        old = out.attrs.get("history", "")
        out.attrs["history"] = f"{old}\n{line}" if old else line
    return out


def _check_grid(values: NDArray, what: str, unit: str, where, *, positive: bool = True) -> None:
    if values.size == 0 or not np.all(np.isfinite(values)):
        raise HydroDataError(f"the {what} grid is empty or not finite", path=where)
    if positive and np.any(values <= 0):
        raise HydroDataError(
            f"{what} {values[values <= 0][0]:g} {unit} is not positive", path=where
        )
    if np.any(np.diff(values) <= 0):
        raise HydroDataError(f"the {what}s are not strictly increasing", path=where)


def complete_square(
    kind: str,
    omega1: ArrayLike,
    omega2: ArrayLike,
    beta1: ArrayLike,
    beta2: ArrayLike,
    dof: ArrayLike,
    values: ArrayLike,
    *,
    n_dofs: int,
    error: Callable[[str, int], Exception],
    rtol: float = 1e-4,
) -> tuple[NDArray, NDArray, NDArray, bool, NDArray]:
    """The full square of a QTF from the rows of a file (one triangle, or both).

    Each row gives Q(ω₁, ω₂, β₁, β₂) of one DOF; the pair it mirrors, (ω₂, ω₁, β₂, β₁), is
    its complex conjugate (difference) or itself (sum) (module docstring). Every pair of
    the frequency grid must be given, directly or by its mirror, for every heading (pair)
    and every DOF the file holds: a missing one is an error (a truncated or edited file),
    never a zero. A pair given twice must agree with itself (within ``rtol`` of the
    largest |Q| of that DOF): a duplicated line with other numbers is damage.

    Parameters
    ----------
    kind
        ``"difference"`` or ``"sum"``.
    omega1, omega2, beta1, beta2
        Frequencies (rad/s) and directions (rad) of each row, shape (r,).
    dof
        0-based DOF index of each row, shape (r,).
    values
        Q of each row (complex, dimensional), shape (r,).
    n_dofs
        Number of DOFs of the dataset.
    error
        ``error(message, row)`` returns the exception naming the file and line of row.
    rtol
        Tolerance of the agreement of a pair given twice.

    Returns
    -------
    omega, directions, table, bidirectional, present
        The grids, the values (n, n, m[, m], n_dofs) and which DOFs the file holds.
    """
    w1, w2 = np.asarray(omega1, dtype=float), np.asarray(omega2, dtype=float)
    b1, b2 = np.asarray(beta1, dtype=float), np.asarray(beta2, dtype=float)
    k = np.asarray(dof, dtype=int)
    q = np.asarray(values, dtype=complex)
    omega, i = _merge_grid(np.concatenate([w1, w2]), rtol=1e-6)
    directions, a = _merge_grid(np.concatenate([b1, b2]), rtol=1e-9, atol=1e-9)
    r = w1.size
    i1, i2, a1, a2 = i[:r], i[r:], a[:r], a[r:]
    bidirectional = bool(np.any(a1 != a2))
    n, m = omega.size, directions.size
    present = np.zeros(n_dofs, dtype=bool)
    present[np.unique(k)] = True
    shape = (n, n, m, m, n_dofs)
    table = np.zeros(shape, dtype=complex)
    given = np.zeros(shape, dtype=bool)
    row_at = np.full(shape, -1, dtype=np.int64)
    flat = np.ravel_multi_index((i1, i2, a1, a2, k), shape)
    order = np.argsort(flat, kind="stable")
    dup = np.flatnonzero(np.diff(flat[order]) == 0)
    if dup.size:
        first, second = order[dup[0]], order[dup[0] + 1]
        raise error(
            f"the pair omega = {w1[second]:.6g}, {w2[second]:.6g} rad/s, DOF {k[second] + 1} "
            f"appears twice (also row {first + 1} of the table)",
            int(second),
        )
    table.flat[flat] = q
    given.flat[flat] = True
    row_at.flat[flat] = np.arange(r)
    mirror = np.swapaxes(np.swapaxes(table, 0, 1), 2, 3)
    mirror_given = np.swapaxes(np.swapaxes(given, 0, 1), 2, 3)
    if kind == "difference":
        mirror = np.conj(mirror)
    # a cell that is its own mirror (ω₁ = ω₂, β₁ = β₂) is not compared: its imaginary
    # part (difference) is the solver's round-off, which cummins check reports
    own = np.zeros((n, n, m, m), dtype=bool)
    i_own, a_own = np.arange(n)[:, None], np.arange(m)[None, :]
    own[i_own, i_own, a_own, a_own] = True
    both = given & mirror_given & ~own[..., None]
    if both.any():
        scale = np.abs(table).max(axis=(0, 1, 2, 3), keepdims=True)
        bad = both & (np.abs(table - mirror) > rtol * scale + 1e-300)
        if bad.any():
            cell = tuple(np.argwhere(bad)[0])
            row = int(row_at[cell])
            rule = "the complex conjugate of" if kind == "difference" else "equal to"
            raise error(
                f"Q(omega = {omega[cell[0]]:.6g}, {omega[cell[1]]:.6g} rad/s) of DOF "
                f"{cell[4] + 1} is not {rule} its mirror Q(omega = {omega[cell[1]]:.6g}, "
                f"{omega[cell[0]]:.6g}) given elsewhere in the file",
                row,
            )
    table = np.where(given, table, mirror)
    covered = given | mirror_given
    heading_pairs = np.ones((m, m), dtype=bool) if bidirectional else np.eye(m, dtype=bool)
    need = np.broadcast_to(
        heading_pairs[None, None, :, :, None] & present[None, None, None, None, :], shape
    )
    missing = need & ~covered
    if missing.any():
        c = tuple(np.argwhere(missing)[0])
        raise error(
            f"no value for omega = {omega[c[0]]:.6g}, {omega[c[1]]:.6g} rad/s, directions "
            f"{np.degrees(directions[c[2]]):.6g}, {np.degrees(directions[c[3]]):.6g} deg, DOF "
            f"{c[4] + 1}, nor for its mirror: every pair of the frequency grid must be given "
            "(a truncated or edited file?)",
            r - 1,
        )
    if not bidirectional:
        table = np.diagonal(table, axis1=2, axis2=3)  # (n, n, d, m)
        table = np.moveaxis(table, -1, 2)
    return omega, directions, table, bidirectional, present


def _merge_grid(values: NDArray, *, rtol: float, atol: float = 0.0) -> tuple[NDArray, NDArray]:
    """Distinct values (within ``rtol``/``atol``: printed digits) and the index of each."""
    order = np.argsort(values, kind="stable")
    v = values[order]
    new = np.ones(v.size, dtype=bool)
    new[1:] = np.diff(v) > rtol * np.abs(v[1:]) + atol
    group = np.cumsum(new) - 1
    grid = np.array([v[group == g].mean() for g in range(group[-1] + 1)]) if v.size else v
    index = np.empty(values.size, dtype=int)
    index[order] = group
    return grid, index


def significant_dofs(peaks: ArrayLike, labels: Sequence[str], share: float = 0.01) -> NDArray:
    """Which DOFs carry a value of their own: a peak of at least ``share`` of the largest
    force (or moment) peak; the others (sway, roll, yaw in head seas) are round-off."""
    from cummins.dofs import is_rotation

    peaks = np.asarray(peaks, dtype=float)
    rotation = np.array([is_rotation(str(d)) for d in labels])
    out = np.zeros(len(labels), dtype=bool)
    for group in (rotation, ~rotation):
        if group.any() and peaks[group].max() > 0:
            out |= group & (peaks >= share * peaks[group].max())
    return out


def second_order_summary(ds: xr.Dataset) -> dict:
    """What second-order data a ``HydroDB`` holds (``cummins info``): per QTF its grid,
    directions and DOFs, and the mean-drift estimates."""
    out: dict = {}
    for kind, name in QTF_VARIABLES.items():
        if name not in ds:
            continue
        table = qtf_table(ds, kind)
        w = table.omega
        spacing = np.diff(w)
        computed = ds[name].attrs.get("dofs_computed")
        out[name] = {
            "n_omega": int(w.size),
            "omega_range_rad_s": [float(w[0]), float(w[-1])],
            "omega_spacing_rad_s": [float(spacing.min()), float(spacing.max())]
            if spacing.size
            else [],
            "wave_directions_deg": [float(b) for b in np.degrees(table.directions)],
            "bidirectional": table.bidirectional,
            "dofs": str(computed).split() if computed else list(table.dofs),
            "source": ds[name].attrs.get("source", ""),
        }
    for name in ("drift_force", *DRIFT_ALTERNATIVES):
        if name in ds:
            out[name] = {"method": ds[name].attrs.get("method", "")}
    return out
