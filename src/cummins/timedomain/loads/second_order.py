"""Second-order wave loads in the time domain: the mean drift, the slowly varying force
(Newman's approximation or the full difference-frequency QTF) and the sum-frequency force.

:class:`SecondOrderWaveLoad` realises the force of :mod:`cummins.qtf.data` for a sea of
:class:`~cummins.seakeeping.waves.WaveComponents`,

    F(t) = Re Σ_i Σ_j c_i c_j* Q⁻(ω_i, ω_j, β_i, β_j) e^{i(ω_i − ω_j)t}
         + Re Σ_i Σ_j c_i c_j Q⁺(ω_i, ω_j, β_i, β_j) e^{i(ω_i + ω_j)t},

(the same components, phases and directions as the first-order force, so the slow drift
follows the wave groups of the simulated sea), with

* ``model="full"``: Q⁻ the dataset's ``qtf_difference`` interpolated over the
  components' pairs (bilinear in (ω₁, ω₂), linear in direction:
  :mod:`cummins.qtf.interpolation`), and Q⁺ its ``qtf_sum`` when it has one
  (``sum_frequency``);
* ``model="newman"``: Q⁻(ω_i, ω_j) ≈ ½(T_i + T_j), T_i the mean drift of component i
  (Newman (1974)): the QTF's diagonal when the dataset has a QTF, else ``drift_force``
  (linear in ω, linear in direction); no sum-frequency force;
* ``model="mean"``: only the mean Σ_i a_i² T_i.

Pairs of components with a frequency outside the QTF's (or the drift's) grid have no
second-order force; the load's ``notes`` say which share of the sea's variance that is.
A unidirectional QTF gives a pair of components of different directions its value at
their mean direction (short-crested seas; a note says so).

The double sums are factorised once (:mod:`cummins.timedomain.loads.quadratic_form`):
:meth:`time_series` gives F on a simulation's time grid (a 3-hour record of 200
components at 0.05 s in about a second), :meth:`force` the load of the nonlinear model
(``force(t, η, ν)``, with the phase of the vessel's horizontal position, as
:class:`~cummins.timedomain.loads.WaveDriftLoad`), :meth:`stationary_state` the state a
linear simulation starts from to be stationary at once.

Axes: :meth:`from_hydrodb` builds the load of the nonlinear DP model — z-down body axes,
the data taken at the vessel's instantaneous relative heading β_i − ψ(t) at every call
(:mod:`cummins.timedomain.loads.relative_heading`: the data's directions, mirrored for a
symmetric hull, interpolated linearly; ``follow_heading=False`` holds the start heading
ψ₀) — and :func:`second_order_force` the force of a linear simulation in the dataset's own
axes, without position phase. A load that follows the heading builds the factorised
forms held at ψ₀ (``difference``, ``sum``: the pair matrices of a short-crested sea
decomposed, the run's costliest set-up) only on first use, by :meth:`time_series` or
:meth:`stationary_state`: its :meth:`force` does not use them.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import ArgumentError, HydroDataError
from cummins.hydrodb import bodies, change_axes, dof_index, single_speed
from cummins.qtf.data import NO_QTF_HINT, has_qtf
from cummins.qtf.headings import mirrored_qtf
from cummins.qtf.interpolation import (
    at_directions,
    coverage,
    direction_weights,
    frequency_weights,
    interpolate,
    pair_matrix,
    weight_matrix,
)
from cummins.qtf.suspect_drift import suspects_left_out
from cummins.seakeeping.waves import WaveComponents, wavenumber
from cummins.timedomain.loads.quadratic_form import (
    QuadraticForm,
    full_form,
    grid_form,
    newman_form,
    time_series,
)
from cummins.timedomain.loads.relative_heading import HeadingTable, heading_table
from cummins.timedomain.loads.waves import _wave_vectors, warn_drift_mirror

#: The second-order models.
MODELS = ("full", "newman", "mean")
#: Default truncation of the factorised QTF (relative, of the force's standard deviation).
TOLERANCE = 1e-3
#: Most components whose pairs the stationary start sums one by one (N² per mode);
#: above, the run starts from the static offset of the mean force.
STATIONARY_LIMIT = 600


@dataclass(frozen=True, eq=False)
class SecondOrderWaveLoad:
    """The second-order wave force of a sea (module docstring).

    Attributes
    ----------
    waves
        The sea.
    dofs
        DOF labels of the force's columns.
    model
        ``"full"``, ``"newman"`` or ``"mean"``.
    difference
        The factorised difference-frequency force (mean included); None for the mean
        drift alone. Given as a function that builds it, it is built on first use (the
        ``difference`` property; a load that follows the heading).
    sum
        The factorised sum-frequency force, or None (or a function that builds it).
    mean
        The mean force Σ_i a_i² Re Q⁻(ω_i, ω_i), shape (n_dofs,), N and N·m.
    index
        Position of each DOF in the 6-vector of the nonlinear model (``from_hydrodb``).
    wavenumbers
        k_i, rad/m (for the position phase).
    position_phase
        Include the phase of the vessel's horizontal position in :meth:`force`.
    notes
        What the load assumes or leaves out (one line each).
    name
        Name of the load.
    drift_left_out
        The frequencies (rad/s) left out of the mean drift (``drift_force``) as suspect
        (irregular frequencies: :mod:`cummins.qtf.suspect_drift`).
    headings
        The data at each of their directions, for a :meth:`force` at the vessel's
        instantaneous relative heading
        (:class:`~cummins.timedomain.loads.relative_heading.HeadingTable`); None: the
        force at the directions of ``waves`` as given (the heading ψ₀ of
        :meth:`from_hydrodb` with ``follow_heading=False``, or the data's axes).
    """

    waves: WaveComponents
    dofs: tuple[str, ...]
    model: str
    _difference: QuadraticForm | Callable[[], QuadraticForm] | None
    _sum: QuadraticForm | Callable[[], QuadraticForm] | None
    mean: NDArray[np.float64]
    index: NDArray[np.intp] | None = None
    wavenumbers: NDArray[np.float64] | None = None
    position_phase: bool = False
    notes: tuple[str, ...] = ()
    name: str = "second-order wave force"
    drift_left_out: tuple[float, ...] = ()
    headings: HeadingTable | None = None
    _k: NDArray | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        if self.wavenumbers is not None:
            k = np.asarray(self.wavenumbers, dtype=float)
            object.__setattr__(self, "_k", _wave_vectors(k, self.waves.direction))

    @property
    def difference(self) -> QuadraticForm | None:
        """The factorised difference-frequency force (built now if it was deferred)."""
        return self._built("_difference")

    @property
    def sum(self) -> QuadraticForm | None:
        """The factorised sum-frequency force, or None (built now if it was deferred)."""
        return self._built("_sum")

    def _built(self, name: str) -> QuadraticForm | None:
        value = getattr(self, name)
        if callable(value):  # deferred: built once, kept
            value = value()
            object.__setattr__(self, name, value)
        return value

    @classmethod
    def from_hydrodb(
        cls,
        ds: xr.Dataset,
        waves: WaveComponents,
        *,
        model: str = "full",
        sum_frequency: bool | None = None,
        heading: float = 0.0,
        position_phase: bool = True,
        tol: float = TOLERANCE,
        max_gap: float = np.pi / 2,
        name: str = "second-order wave force",
        keep_suspect: bool = False,
        follow_heading: bool = True,
    ) -> SecondOrderWaveLoad:
        """The load of the nonlinear DP model (z-down axes, b-frame about O), at the
        vessel's instantaneous relative heading (module docstring).

        Parameters
        ----------
        ds
            A ``HydroDB`` of one body, with ``qtf_difference`` (``model="full"``) or a
            QTF or ``drift_force`` (``"newman"``, ``"mean"``).
        waves
            The sea (directions in the n-frame).
        model
            ``"full"``, ``"newman"`` or ``"mean"`` (module docstring).
        sum_frequency
            Include the sum-frequency force (``"full"`` only; default: when the data
            have ``qtf_sum``).
        heading
            ψ₀, rad: the vessel's heading at the start. The data must cover the sea's
            relative directions β_i − ψ₀ there; :meth:`time_series`,
            :meth:`stationary_state` and ``mean`` are the force held at ψ₀.
        position_phase
            Include the phase of the vessel's horizontal position.
        tol
            Truncation of the factorised QTF (:mod:`~cummins.timedomain.loads.quadratic_form`).
        max_gap
            Widest gap between data directions to interpolate across, rad.
        name
            Name of the load.
        keep_suspect
            Keep the mean drift (``drift_force``) at the suspect frequencies of the
            radiation data (default: left out, :mod:`cummins.qtf.suspect_drift`).
        follow_heading
            :meth:`force` at the instantaneous relative heading β_i − ψ(t), ψ(t) = η₆
            (default; :mod:`~cummins.timedomain.loads.relative_heading`); False: at
            β_i − ψ₀ whatever the vessel's yaw.
        """
        ds = single_speed(ds)
        if len(bodies(ds)) != 1:
            raise HydroDataError(
                f"the dataset holds {len(bodies(ds))} bodies; a vessel load needs one",
                path=ds.attrs.get("source_file"),
            )
        if ds.attrs.get("axis_convention", "z-up") != "z-down":
            ds = change_axes(ds, "z-down")
        relative = WaveComponents(
            waves.omega, waves.amplitude, waves.phase, waves.direction - float(heading)
        )
        parts = _build(
            ds, relative, model, sum_frequency, tol, max_gap, keep_suspect, defer=follow_heading
        )
        index = np.array([dof_index(str(d)) for d in ds.influenced_dof.values], dtype=np.intp)
        k = wavenumber(
            waves.omega, float(ds.attrs.get("water_depth", np.inf)), float(ds.attrs.get("g", 9.81))
        )
        table = None
        if follow_heading:
            table = heading_table(
                model,
                waves.omega,
                waves.phase,
                waves.amplitude,
                waves.direction,
                parts["directions"],
                parts["per_direction"],
                difference=parts["table"],
                sum_table=parts["sum_table"],
                max_gap=max_gap,
                what=parts["what"],
            )
        notes = parts["notes"] + [_heading_note(parts, heading, follow_heading, max_gap)]
        return cls(
            waves,
            parts["dofs"],
            model,
            parts["difference"],
            parts["sum"],
            parts["mean"],
            index,
            k,
            position_phase,
            tuple(notes),
            name,
            parts["left_out"],
            table,
        )

    def time_series(self, t) -> NDArray[np.float64]:
        """F(t) at uniform times ``t`` (s), shape (nt, n_dofs), N and N·m."""
        t = np.asarray(t, dtype=float).reshape(-1)
        forms = [f for f in (self.difference, self.sum) if f is not None]
        out = time_series(forms, t) if forms else np.zeros((t.size, self.mean.size))
        if self._difference is None:
            out += self.mean
        return out

    def stationary_state(self, vessel) -> tuple[NDArray[np.float64], list[str]]:
        """The state of a :class:`~cummins.vessel.Vessel` that makes its response to this
        force stationary from t = 0 (QuadraticForm.stationary_state), and notes."""
        f, g = vessel.state_space()
        if self._difference is None:
            x, notes = _static_state(f, g, self.mean)
        elif len(self.waves) > STATIONARY_LIMIT:
            x, notes = _static_state(f, g, self.mean)
            notes = [
                *notes,
                f"{len(self.waves)} components: the run starts from the static offset of the "
                f"mean force (the stationary slow drift is summed over the pairs of at most "
                f"{STATIONARY_LIMIT}); discard the first few natural periods",
            ]
            return x, notes
        else:
            x, notes = self.difference.stationary_state(f, g)
        if self.sum is not None:
            xs, more = self.sum.stationary_state(f, g)
            x, notes = x + xs, notes + more
        return x, notes

    def force(self, t: float, eta: NDArray[np.float64], nu: NDArray[np.float64]) -> NDArray:
        """The 6-vector of the nonlinear model, b-frame about O, N and N·m."""
        shift = None
        if self.position_phase and self._k is not None:
            shift = np.asarray(eta, dtype=float)[:2] @ self._k
        if self.headings is not None:
            value = self.headings.force(t, float(eta[5]), shift)
        else:
            value = self.mean if self.difference is None else self.difference.at(t, shift)
            if self.sum is not None:
                value = value + self.sum.at(t, shift)
        out = np.zeros(6)
        index = self.index if self.index is not None else np.arange(min(6, value.size))
        out[index] = value[: index.size]
        return out


def _heading_note(parts: dict, heading: float, follow: bool, max_gap: float) -> str:
    """What the DP load does with the vessel's heading, and the data's directions."""
    what, directions = parts["what"], np.sort(np.mod(parts["directions"], 2 * np.pi))
    have = ", ".join(f"{x:.4g}" for x in np.degrees(directions[:12]))
    have += (" …" if directions.size > 12 else "") + " deg"
    start = f"{np.degrees(heading):.4g} deg"
    if not follow:
        return f"{what} at the relative directions of the heading {start}, whatever the yaw"
    if directions.size == 1:
        return (
            f"the {what} has one direction ({have}): held at every relative heading "
            f"(the drift does not follow the yaw; start heading {start})"
        )
    ends = np.append(directions[1:], directions[0] + 2 * np.pi)
    if np.any(ends - directions > max_gap + 1e-12):
        return (
            f"{what} at the instantaneous relative heading, linear between its directions "
            f"({have}); in gaps over {np.degrees(max_gap):.4g} deg it takes the nearest "
            f"direction's values (a warning says when); start heading {start}"
        )
    return (
        f"{what} at the instantaneous relative heading, linear between its directions "
        f"({have}); start heading {start}"
    )


def _static_state(f: NDArray, g: NDArray, force: NDArray) -> tuple[NDArray, list[str]]:
    """x with F x + G τ̄ = 0 in the modes that have restoring (the others left at rest)."""
    lam, vec = np.linalg.eig(f)
    q = np.linalg.solve(vec, g @ force)
    scale = max(float(np.abs(lam).max()), 1e-12)
    free = np.abs(lam) <= 1e-9 * scale
    q = np.where(free, 0.0, q / np.where(free, 1.0, -lam))
    notes = ["a DOF without restoring starts at rest and drifts"] if (free & (q != 0)).any() else []
    return (vec @ q).real, notes


def second_order_force(
    ds: xr.Dataset,
    waves: WaveComponents,
    *,
    model: str = "full",
    sum_frequency: bool | None = None,
    tol: float = TOLERANCE,
    max_gap: float = np.pi / 2,
    keep_suspect: bool = False,
) -> SecondOrderWaveLoad:
    """The second-order force of a linear simulation (:func:`cummins.simulate_waves`), in
    the dataset's axes and DOFs, without position phase (module docstring; ``keep_suspect``
    as in :meth:`SecondOrderWaveLoad.from_hydrodb`)."""
    ds = single_speed(ds)
    parts = _build(ds, waves, model, sum_frequency, tol, max_gap, keep_suspect)
    return SecondOrderWaveLoad(
        waves,
        parts["dofs"],
        model,
        parts["difference"],
        parts["sum"],
        parts["mean"],
        notes=tuple(parts["notes"]),
        drift_left_out=parts["left_out"],
    )


def _build(
    ds, waves: WaveComponents, model, sum_frequency, tol, max_gap, keep_suspect, defer=False
) -> dict:
    """The parts of a load (a dict): the factorised forms as functions that build them
    when ``defer`` (a load that follows the heading: :class:`SecondOrderWaveLoad`)."""
    if model not in MODELS:
        raise ArgumentError(f"second-order model must be one of {', '.join(MODELS)}, not {model!r}")
    if not 0 < tol < 1:
        raise ArgumentError(f"tol must be between 0 and 1, got {tol!r}")
    dofs = tuple(str(d) for d in ds.influenced_dof.values)
    notes: list[str] = []
    a = waves.amplitude
    left_out: tuple[float, ...] = ()
    have_qtf = has_qtf(ds, "difference")
    if model == "full" and not have_qtf:
        raise HydroDataError(
            "the data have no difference-frequency QTF (qtf_difference) for the full "
            "second-order force",
            path=ds.attrs.get("source_file"),
            hint=f"{NO_QTF_HINT}, or use Newman's approximation (model='newman', "
            "--second-order newman), which needs only the mean drift",
        )
    table = None
    if have_qtf:
        table = _mirrored(ds, "difference", notes)
        cover = coverage(table, waves.omega, a)
        inside = cover.inside
        if cover.note():
            notes.append(cover.note())
        directions = table.directions
        per_direction = np.stack(
            [interpolate(table, waves.omega, waves.omega, g, g).real for g in directions]
        )
        source = f"the QTF's diagonal ({table.omega.size} frequencies)"
        what = "QTF"
        if np.unique(np.round(waves.direction, 9)).size > 1 and not table.bidirectional:
            notes.append(
                "unidirectional QTF in a short-crested sea: a pair of components of two "
                "directions takes the QTF at their mean direction"
            )
    else:
        directions, per_direction, inside, source, left_out = _drift_table(
            ds, waves, notes, keep_suspect
        )
        what = "mean drift"
    per_direction = np.where(inside[None, :, None], per_direction, 0.0)
    a0, a1, ta = direction_weights(directions, waves.direction, max_gap=max_gap, what=what)
    rows = np.arange(len(waves))
    diag = (1 - ta)[:, None] * per_direction[a0, rows] + ta[:, None] * per_direction[a1, rows]
    mean = (a**2) @ diag
    exact = "exact at the instantaneous relative heading"  # HeadingTable: no truncation
    if model == "full":
        difference = partial(_full, table, waves, tol, max_gap)
        if not defer:
            difference = difference()
        notes.append(
            f"full difference-frequency QTF ({table.omega.size} x {table.omega.size} "
            f"frequencies) over the pairs of {len(waves)} components: "
            + (exact if defer else _describe(difference, tol))
        )
    elif model == "newman":
        difference = partial(newman_form, waves.omega, waves.phase, a, diag)
        if not defer:
            difference = difference()
        notes.append(f"Newman's approximation from {source}")
    else:
        difference = None
        notes.append(f"mean drift only, from {source}")
    total_sum = sum_table = None
    want_sum = has_qtf(ds, "sum") if sum_frequency is None else bool(sum_frequency)
    if want_sum and model == "full":
        if not has_qtf(ds, "sum"):
            raise HydroDataError(
                "the data have no sum-frequency QTF", path=ds.attrs.get("source_file")
            )
        sum_table = _mirrored(ds, "sum", [])
        total_sum = partial(_full, sum_table, waves, tol, max_gap)
        if not defer:
            total_sum = total_sum()
        notes.append("sum-frequency QTF: " + (exact if defer else _describe(total_sum, tol)))
    return {
        "dofs": dofs,
        "difference": difference,
        "sum": total_sum,
        "mean": mean,
        "notes": notes,
        "left_out": left_out,
        "directions": directions,
        "per_direction": per_direction,
        "table": table if model == "full" else None,
        "sum_table": sum_table,
        "what": what,
    }


def _mirrored(ds, kind: str, notes: list[str]):
    """The dataset's QTF on its directions mirrored for a symmetric hull
    (:func:`cummins.qtf.headings.mirrored_qtf`); a note when mirrored."""
    table, cover = mirrored_qtf(ds, kind)
    if cover.mirror_used:
        notes.append(f"{kind}-frequency QTF of the mirrored directions: {cover.reason}")
    return table


def _full(table, waves: WaveComponents, tol: float, max_gap: float) -> QuadraticForm:
    """The factorised double sum of one QTF over the components' pairs: exact on the QTF's
    grid when the sea has one direction, truncated eigen (or singular value) terms of the
    pair matrices otherwise (:mod:`~cummins.timedomain.loads.quadratic_form`)."""
    a = waves.amplitude
    difference = table.kind == "difference"
    directions = np.unique(np.round(np.mod(waves.direction, 2 * np.pi), 12))
    if directions.size == 1:
        beta = float(waves.direction[0])
        values = [at_directions(table, d, beta, beta, max_gap) for d in range(len(table.dofs))]
        weights = weight_matrix(table.omega, waves.omega)
        return grid_form(waves.omega, waves.phase, a, weights, values, difference=difference)
    matrices = [
        a[:, None]
        * pair_matrix(table, d, waves.omega, waves.direction, max_gap=max_gap)
        * a[None, :]
        for d in range(len(table.dofs))
    ]
    return full_form(waves.omega, waves.phase, matrices, difference=difference, tol=tol)


def _describe(form: QuadraticForm, tol: float) -> str:
    sizes = [cols.size for cols, _ in form.blocks]
    if len(set(sizes)) == 1 and form.columns.shape[1] == sizes[0]:
        return f"exact on the {sizes[0]} QTF frequencies the sea uses"
    return f"{sum(sizes)} terms over the DOFs (truncated at {tol:g} of each DOF's weight)"


def _drift_table(
    ds, waves: WaveComponents, notes, keep_suspect=False
) -> tuple[NDArray, NDArray, NDArray, str, tuple[float, ...]]:
    """T_i of every component at each direction of ``drift_force`` (mirrored for a
    symmetric hull), shape (m, N, d): linear in ω (zero outside the data's frequencies);
    without the suspect frequencies
    (:func:`~cummins.qtf.suspect_drift.drift_suspect_frequencies`) unless
    ``keep_suspect``, which are returned. Returns (directions, table, inside, source,
    left out)."""
    if "drift_force" not in ds:
        raise HydroDataError(
            "the data have neither a QTF nor a mean drift (drift_force)",
            path=ds.attrs.get("source_file"),
            hint="read a run that holds one (WAMIT .7/.8/.9, .out drift tables or .12d, "
            "NEMOH QTF, AQWA .LIS or .QTF, MSS .mat with driftfrc)",
        )
    from cummins.seakeeping.headings import mirror_headings

    warn_drift_mirror(ds, stacklevel=5)
    # a port/starboard symmetric hull's drift on the other half-plane, as the first order
    parts = [v for v in ("added_mass", "radiation_damping", "excitation_force") if v in ds]
    mirrored, coverage = mirror_headings(ds[[*parts, "drift_force"]])
    if coverage.mirror_used:
        notes.append(f"mean drift of the mirrored headings: {coverage.reason}")
    drift = mirrored.drift_force.transpose("omega", "wave_direction", "influenced_dof").values
    w = ds.omega.values
    left_out = suspects_left_out(ds, keep_suspect, notes)
    if left_out:
        sound = ~np.isin(w, left_out)
        w, drift = w[sound], drift[sound]
    i, t, inside = frequency_weights(w, waves.omega)
    hi = np.minimum(i + 1, w.size - 1)
    value = (1 - t)[:, None, None] * drift[i] + t[:, None, None] * drift[hi]  # (N, m, d)
    if not inside.all():
        a2 = waves.amplitude**2
        share = a2[~inside].sum() / a2.sum()
        notes.append(
            f"{int((~inside).sum())} wave components ({100 * share:.2g} % of the variance) "
            f"outside the mean drift's frequencies {w[0]:.4g}–{w[-1]:.4g} rad/s: no drift "
            "from them"
        )
    method = ds.drift_force.attrs.get("method", "mean drift")
    directions = mirrored.wave_direction.values.astype(float)
    return directions, np.moveaxis(value, 1, 0), inside, f"drift_force ({method})", left_out
