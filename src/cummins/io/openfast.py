"""OpenFAST HydroDyn state-space radiation file (``.ss``), as SS_Fitting writes it.

HydroDyn (OpenFAST) models the fluid memory with a state-space system when
``RdtnMod = 2``: it reads ``<PotFile>.ss`` in ``SS_Rad_Init``
(``modules/hydrodyn/src/SS_Radiation.f90``) and adds the output y = C x to the
platform loads unchanged (``WAMIT_CalcOutput``: ``F_Rdtn = SS_Rdtn_y%y``). The file is
written by NREL's SS_Fitting tool (and by BEMRosetta). Layout, for NBody bodies and N
states (one record per line; numbers free-format, separated by blanks)::

    line 1            title (any text)
    line 2            6·NBody DOF flags (1 = DOF modelled), then an optional comment
    line 3            N, the total number of states, then an optional comment
    line 4            6·NBody numbers of states per DOF (they add up to N)
    next N lines      A, one row per line (N numbers)
    next N lines      B, one row per line (6·NBody numbers)
    next 6·NBody lines C, one row per line (N numbers)

and nothing after: HydroDyn counts every remaining line (blank ones too) and requires
(lines − 6·NBody)/2 = N. It also requires every flag to be 1 (it enables all DOFs and
reads B and C with 6·NBody columns and rows whatever the flags say).

Conventions of the file (from HydroDyn and SS_Fitting's writer):

* x' = A x + B q̇, F_rad = C x, with q̇ the body velocities (m/s, rad/s) and F_rad the
  radiation memory *force* on the body (N, N·m), SI units, not scaled by ρ. cummins'
  model gives the memory term μ with F_rad = −μ, so the file's C is −C of the model
  (SS_Fitting also writes ``CC = -C``).
* Axes are HydroDyn's platform axes, z up (x forward along the WAMIT x axis, y to
  port), about the WAMIT body reference point: cummins' ``"z-up"`` axes. A model in
  ``"z-down"`` (MSS) axes is converted on writing (c of coupling (i, j) times
  T_i T_j, T = diag(1, −1, −1, 1, −1, −1)).
* The states are grouped by radiating DOF: the first n₁ states (line 4) are those
  driven by the surge velocity, then the n₂ of sway, … HydroDyn relies on this to drop
  the states of a disabled DOF. :func:`write_openfast_ss` therefore orders the
  couplings by (radiating j, influenced i), which permutes the states of the
  :class:`~cummins.radiation.model.RadiationModel` (whose states follow its couplings).

Numbers are written with 17 significant digits, so a file read back gives the same
matrices bit for bit (HydroDyn itself stores them in single precision).
"""

from __future__ import annotations

import os
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from cummins._version import __version__
from cummins.errors import HydroDataError, HydroDataWarning, check_writable
from cummins.files import replacing
from cummins.hydrodb import DOF_NAMES
from cummins.io._model_common import resolve_axis_convention
from cummins.io._text import TextFile, check_cut_numbers, parse_numbers
from cummins.radiation.model import CouplingModel, RadiationModel, change_model_axes

__all__ = [
    "OpenFastExcitationSS",
    "OpenFastSS",
    "read_openfast_ss",
    "read_openfast_ssexctn",
    "write_openfast_ss",
]

_FMT = "{:.16e}"


@dataclass(frozen=True)
class OpenFastSS:
    """The content of an OpenFAST ``.ss`` file.

    Attributes
    ----------
    title
        Line 1.
    dof_flags
        Line 2: 6·NBody flags (1 = DOF modelled).
    states_per_dof
        Line 4: number of states driven by each DOF's velocity.
    A, B, C
        The matrices as in the file: F_rad = C x is the radiation memory force, the
        negative of cummins' memory term μ.
    path
        The file read, if any.
    """

    title: str
    dof_flags: NDArray[np.int_]
    states_per_dof: NDArray[np.int_]
    A: NDArray[np.float64]
    B: NDArray[np.float64]
    C: NDArray[np.float64]
    path: Path | None = None

    @property
    def n_states(self) -> int:
        """N, the number of states."""
        return int(self.A.shape[0])

    def frequency_response(self, omega: ArrayLike) -> NDArray[np.complex128]:
        """cummins' memory transfer matrix K(jω) = −C (jωI − A)⁻¹ B, shape (nω, n, n)."""
        w = np.asarray(omega, dtype=float).reshape(-1)
        eye = np.eye(self.n_states)
        out = np.empty((w.size, self.C.shape[0], self.B.shape[1]), dtype=complex)
        for k, wk in enumerate(w):
            out[k] = -self.C @ np.linalg.solve(1j * wk * eye - self.A, self.B)
        return out

    def to_radiation_model(
        self,
        dofs: tuple[str, ...] | None = None,
        added_mass_inf: ArrayLike | None = None,
    ) -> RadiationModel:
        """The file as a :class:`~cummins.radiation.model.RadiationModel` of SISO couplings.

        The states are split into the connected blocks of A; each block must be driven
        by one velocity j and seen by one force i (a SISO model, as SS_Fitting and
        cummins write them), and the blocks with the same (i, j) form one coupling.
        Blocks with no input or no output contribute nothing to K and are dropped.

        Parameters
        ----------
        dofs
            DOF labels; default ``Surge`` … ``Yaw`` (``body1__Surge`` … for several
            bodies).
        added_mass_inf
            A∞ (the ``.ss`` file does not hold it; HydroDyn takes it from the WAMIT
            ``.1`` file). Default: NaN, which makes :meth:`added_mass` NaN too.

        Raises
        ------
        HydroDataError
            A block of states couples several inputs or outputs.
        """
        n = self.B.shape[1]
        if dofs is None:
            dofs = default_dof_labels(n)
        if len(dofs) != n:
            raise HydroDataError(f"{len(dofs)} DOF labels given for {n} DOFs", path=self.path)
        added = np.full((n, n), np.nan) if added_mass_inf is None else np.asarray(added_mass_inf)
        memory_c = -self.C
        groups: dict[tuple[int, int], list[NDArray[np.int_]]] = {}
        for block in _connected_blocks(self.A):
            inputs = np.flatnonzero(np.any(self.B[block] != 0, axis=0))
            outputs = np.flatnonzero(np.any(memory_c[:, block] != 0, axis=1))
            if inputs.size == 0 or outputs.size == 0:
                continue
            if inputs.size > 1 or outputs.size > 1:
                raise HydroDataError(
                    f"states {block[0] + 1}…{block[-1] + 1} couple the velocities "
                    f"{(inputs + 1).tolist()} to the forces {(outputs + 1).tolist()}: not a "
                    "stack of single-input single-output models",
                    path=self.path,
                    hint="use the matrices A, B, C of read_openfast_ss directly",
                )
            groups.setdefault((int(outputs[0]), int(inputs[0])), []).append(block)
        couplings = []
        for (i, j), blocks in groups.items():
            states = np.concatenate(blocks)
            couplings.append(
                CouplingModel(
                    i,
                    j,
                    self.A[np.ix_(states, states)],
                    self.B[states, j],
                    memory_c[i, states],
                    method="openfast-ss",
                )
            )
        attrs = {
            "axis_convention": "z-up",
            "source_format": "openfast-ss",
            "openfast_title": self.title,
        }
        if self.path is not None:
            attrs["source_file"] = str(self.path)
        if added_mass_inf is None:
            attrs["history"] = "added_mass_inf unknown (not in the .ss file): NaN"
        return RadiationModel(tuple(dofs), tuple(couplings), added, attrs)


def default_dof_labels(n: int) -> tuple[str, ...]:
    """``Surge`` … ``Yaw`` for 6 DOFs, ``body1__Surge`` … for 6·NBody."""
    if n == 6:
        return DOF_NAMES
    return tuple(f"body{b + 1}__{d}" for b in range(n // 6) for d in DOF_NAMES)


def _connected_blocks(a: NDArray) -> list[NDArray[np.int_]]:
    """Index sets of the connected components of the graph of A's nonzero entries."""
    from scipy.sparse.csgraph import connected_components

    if a.shape[0] == 0:
        return []
    count, labels = connected_components(a != 0, directed=True, connection="weak")
    blocks = [np.flatnonzero(labels == k) for k in range(count)]
    return sorted(blocks, key=lambda b: int(b[0]))


# --------------------------------------------------------------------------- writing


def ordered_for_openfast(model: RadiationModel) -> tuple[CouplingModel, ...]:
    """The couplings in the state order of the ``.ss`` file: by radiating DOF, then i."""
    return tuple(sorted(model.couplings, key=lambda k: (k.radiating, k.influenced)))


def write_openfast_ss(
    model: RadiationModel,
    path: str | os.PathLike[str],
    *,
    axis_convention: str | None = None,
    title: str | None = None,
    force: bool = False,
) -> Path:
    """Write ``model`` as an OpenFAST HydroDyn ``.ss`` file (see the module docstring).

    Parameters
    ----------
    model
        The memory model, six DOFs per body, about the WAMIT body reference point.
    path
        Output file; HydroDyn reads ``<PotFile>.ss``.
    axis_convention
        Axes of the model when it does not record them (attribute ``axis_convention``).
        A ``"z-down"`` model is converted to HydroDyn's z-up axes.
    title
        Line 1; by default it names cummins and the identification methods.
    force
        Overwrite an existing file.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    check_writable(path, force)
    n = len(model.dofs)
    if n == 0 or n % 6:
        raise HydroDataError(
            f"the model has {n} DOFs; HydroDyn needs all six DOFs of each body", path=path
        )
    if model.total_order == 0:
        raise HydroDataError(
            "the model has no states: nothing to write",
            path=path,
            hint="without fluid memory, run HydroDyn with RdtnMod = 0",
        )
    current = resolve_axis_convention(model, axis_convention, path=path)
    z_up = change_model_axes(model, "z-up", current=current)
    content = openfast_ss_from_model(z_up, title=title)
    with replacing(path) as tmp:
        tmp.write_text(format_openfast_ss(content), encoding="utf-8")
    return path


def openfast_ss_from_model(model: RadiationModel, *, title: str | None = None) -> OpenFastSS:
    """The ``.ss`` content of a z-up ``model``: states grouped by radiating DOF, C = −C
    (a common-pole block is written pair by pair, :meth:`RadiationModel.as_couplings`)."""
    model = model.as_couplings()
    n = len(model.dofs)
    ordered = RadiationModel(model.dofs, ordered_for_openfast(model), model.added_mass_inf)
    per_dof = np.zeros(n, dtype=int)
    for k in ordered.couplings:
        per_dof[k.radiating] += k.order
    if title is None:
        methods = sorted({k.method for k in model.couplings if k.method})
        title = (
            f"cummins {__version__}: state-space radiation (fluid memory) matrices for "
            f"HydroDyn SS_Radiation, methods: {', '.join(methods) or 'unknown'}; "
            "states grouped by radiating DOF, F_rad = C x"
        )
    return OpenFastSS(
        title=" ".join(str(title).split()),
        dof_flags=np.ones(n, dtype=int),
        states_per_dof=per_dof,
        A=ordered.A,
        B=ordered.B,
        C=-ordered.C,
    )


def format_openfast_ss(content: OpenFastSS) -> str:
    """The text of a ``.ss`` file, lines ending with ``\\n``, nothing after C."""
    lines = [
        content.title,
        " ".join(str(int(f)) for f in content.dof_flags) + "    %Enabled DoFs",
        f"{content.n_states}    %Radiation states",
        " ".join(str(int(v)) for v in content.states_per_dof) + "    %Radiation states per DOFs",
    ]
    for matrix in (content.A, content.B, content.C):
        lines.extend(" ".join(_FMT.format(x) for x in row) for row in matrix)
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- reading


def read_openfast_ss(path: str | os.PathLike[str]) -> OpenFastSS:
    """Read an OpenFAST ``.ss`` file (written by SS_Fitting, BEMRosetta or cummins).

    The file is checked as HydroDyn checks it (counts of lines and states), so a file
    that reads here is one HydroDyn accepts. Use :meth:`OpenFastSS.to_radiation_model`
    for a :class:`~cummins.radiation.model.RadiationModel`.

    Raises
    ------
    HydroDataError
        Naming the file and line: missing or malformed header, wrong counts, a header
        line that lost its ``%`` comment, a matrix row with the wrong number of values
        or a number shorter than the others (a cut line), lines after the C matrix;
        states that break the grouping of line 4 (A block-diagonal by DOF, B driving
        them by their DOF's velocity only), a block of A that does not decay or has no
        input or output, a DOF's states with no force on that DOF.

    Warns
    -----
    HydroDataWarning
        K(jω) is not a radiation memory function: K(0) ≠ 0, negative damping on the
        diagonal, K_ij ≠ K_ji (:data:`RESPONSE_LIMITS`; two rows of B or C swapped).
    """
    text = TextFile.read(path)
    if len(text) < 4:
        raise text.error("the file ends before the 4 header lines", len(text) - 1)
    if is_excitation_file(text):
        raise text.error(
            "this file holds a state-space *excitation* fit (SS_Excitation_Fitting: wave "
            "heading and time offset in its header), not a radiation model",
            1,
            hint="read it with cummins.io.openfast.read_openfast_ssexctn (HydroDyn reads "
            "such a model from <PotFile>.ssexctn)",
        )
    flags = _leading_integers(text, 1, "DOF flags")
    if flags.size == 0 or flags.size % 6:
        raise text.error(
            f"expected 6 DOF flags per body, found {flags.size}",
            1,
            hint="line 2 lists 6·NBody flags (1 = DOF modelled)",
        )
    if np.any((flags != 0) & (flags != 1)):
        raise text.error("the DOF flags must be 0 or 1", 1)
    count = _leading_integers(text, 2, "number of states")
    if count.size < 1 or count[0] < 0:
        raise text.error("expected the number of states", 2)
    n_states, n_dofs = int(count[0]), flags.size
    per_dof = _leading_integers(text, 3, "states per DOF")
    if per_dof.size < n_dofs:
        raise text.error(f"expected {n_dofs} numbers of states per DOF, found {per_dof.size}", 3)
    per_dof = per_dof[:n_dofs]
    if int(per_dof.sum()) != n_states:
        raise text.error(
            f"the states per DOF add up to {int(per_dof.sum())}, not to {n_states} (line 3)", 3
        )
    _check_header_comments(text, range(1, 4))
    expected = 4 + 2 * n_states + n_dofs
    if len(text) != expected:
        where = min(len(text), expected) - 1
        raise text.error(
            f"expected {expected} lines (4 header lines, {n_states} rows of A, {n_states} of "
            f"B, {n_dofs} of C), found {len(text)}",
            where,
            hint="HydroDyn counts every line, blank ones too: remove lines after C",
        )
    a = _rows(text, 4, n_states, n_states)
    b = _rows(text, 4 + n_states, n_states, n_dofs)
    c = _rows(text, 4 + 2 * n_states, n_dofs, n_states)
    check_cut_numbers(text, range(4, expected), range(max(n_states, n_dofs)))
    _check_structure(text, 4, a, b, c, per_dof.astype(int), excitation=False)
    _check_radiation_response(text, 4, a, b, c, per_dof.astype(int))
    return OpenFastSS(
        title=text.lines[0].strip(),
        dof_flags=flags.astype(int),
        states_per_dof=per_dof.astype(int),
        A=a,
        B=b,
        C=c,
        path=text.path,
    )


def _leading_integers(text: TextFile, index: int, what: str) -> NDArray[np.int_]:
    """The integers at the start of a header line, up to a comment or other text."""
    values = []
    for field in text.lines[index].split():
        try:
            values.append(int(field))
        except ValueError:
            try:
                number = float(field.replace("D", "E").replace("d", "e"))
            except ValueError:
                break
            if not np.isfinite(number) or number != int(number):
                raise text.error(f"expected integers ({what}), found {field!r}", index) from None
            values.append(int(number))
    return np.asarray(values, dtype=int)


def _check_header_comments(text: TextFile, indices: range) -> None:
    """Every header line keeps its ``%`` comment when the others have one.

    SS_Fitting, SS_Excitation_Fitting and cummins end each header line with a comment
    after the numbers; a line cut short loses it first, and a cut number ("10" read as
    "1") would otherwise pass as a plausible value.
    """
    present = [i for i in indices if i < len(text) and "%" in text.lines[i]]
    if not present or len(present) == len(indices):
        return
    missing = next(i for i in indices if i not in present)
    raise text.error(
        f"this header line has no '%' comment, unlike lines "
        f"{', '.join(str(i + 1) for i in present)}: a line cut short?",
        missing,
        hint="the file is damaged; write it again (SS_Fitting, cummins fit --openfast)",
    )


def _check_structure(
    text: TextFile, start: int, a: NDArray, b: NDArray, c: NDArray, per_dof, *, excitation: bool
) -> None:
    """The state grouping of the header, and decaying blocks that have an input and an output.

    The states are grouped by DOF (line of states per DOF): those of DOF j form one
    diagonal block of A; in a radiation file B drives them by velocity j only, in an
    excitation file C gives force j only from them. Each connected block of A must
    decay (a memory or an excitation impulse response dies out) and have an input and
    an output. SS_Fitting and cummins write files so; a row moved, swapped or edited
    breaks one of these.
    """
    n = a.shape[0]
    group = np.repeat(np.arange(per_dof.size), per_dof)
    rows_b, rows_c = start + n, start + 2 * n
    hint = "the file is damaged or edited; write it again (SS_Fitting, cummins fit --openfast)"
    cross = (a != 0) & (group[:, None] != group[None, :])
    if cross.any():
        k, m = np.argwhere(cross)[0]
        raise text.error(
            f"A couples state {k + 1} (of DOF {group[k] + 1}) with state {m + 1} (of DOF "
            f"{group[m] + 1}): the states of each DOF form one block of A (line "
            f"{start}): a row moved?",
            start + k,
            hint=hint,
        )
    if b.ndim == 2:
        wrong = (b != 0) & (np.arange(b.shape[1])[None, :] != group[:, None])
        if wrong.any():
            k, j = np.argwhere(wrong)[0]
            raise text.error(
                f"state {k + 1} belongs to DOF {group[k] + 1} (line {start}) but B drives it "
                f"by the velocity of DOF {j + 1}: a row moved?",
                rows_b + k,
                hint=hint,
            )
    if excitation:
        wrong = (c != 0) & (np.arange(c.shape[0])[:, None] != group[None, :])
        if wrong.any():
            i, k = np.argwhere(wrong)[0]
            raise text.error(
                f"C gives the force of DOF {i + 1} from state {k + 1}, which belongs to DOF "
                f"{group[k] + 1} (line {start}): a row moved?",
                rows_c + i,
                hint=hint,
            )
    b2 = b.reshape(n, -1)
    for block in _connected_blocks(a):
        span = (
            f"states {block[0] + 1}…{block[-1] + 1}" if block.size > 1 else f"state {block[0] + 1}"
        )
        growth = float(np.linalg.eigvals(a[np.ix_(block, block)]).real.max())
        if growth >= 0:
            raise text.error(
                f"the block of {span} does not decay (an eigenvalue of A with real part "
                f"{growth:.4g} >= 0): "
                "not a fitted impulse response; a row of A moved or edited?",
                start + block[0],
                hint=hint,
            )
        if not np.any(b2[block]):
            raise text.error(
                f"the block of {span} receives no input (its rows of B are zero): a row of B "
                "moved?",
                rows_b + block[0],
                hint=hint,
            )
        if not np.any(c[:, block]):
            raise text.error(
                f"the block of {span} acts on no force (its columns of C are zero): a row of "
                "C moved?",
                rows_c,
                hint=hint,
            )
    if not excitation:
        for j in np.flatnonzero(per_dof):
            if not np.any(c[j, group == j]):
                raise text.error(
                    f"the {per_dof[j]} states driven by the velocity of DOF {j + 1} (line "
                    f"{start}) give no force on DOF {j + 1}: a radiation model always has "
                    "the diagonal term; a row of C moved?",
                    rows_c + j,
                    hint=hint,
                )


#: Limits of :func:`_check_radiation_response`, as fractions of each entry's peak |K(jω)|.
#: Measured on SS_Fitting's files (ITI barge, OC3 spar): |K(0)| <= 1.2e-16, the lowest
#: Re K_jj >= -0.0073, |K_ij - K_ji| <= 3.9e-4; two rows of B or C swapped give 0.45-0.81,
#: -0.80 to -1.0 and 0.996-1.05.
RESPONSE_LIMITS = {"zero_frequency": 0.1, "negative_damping": 0.2, "reciprocity": 0.5}


def _check_radiation_response(
    text: TextFile, start: int, a: NDArray, b: NDArray, c: NDArray, per_dof: NDArray
) -> None:
    """Warn when K(jω) = −C (jωI − A)⁻¹ B is not a radiation memory function.

    Three properties every fit of B(ω) + jω(A(ω) − A∞) keeps, whatever its method:
    K(0) = 0 (B(0) = 0, SS_Fitting and cummins build the zero in), Re K_jj ≥ 0 (the
    radiation damping of a DOF is positive) and K_ij = K_ji (reciprocity, where both are
    modelled). Two rows of B or C swapped within a block of states break one of them
    but no rule of the layout; a poor fit may break them mildly, hence warnings with
    generous limits (:data:`RESPONSE_LIMITS`).
    """
    n = a.shape[0]
    if n == 0:
        return
    magnitudes = np.abs(np.linalg.eigvals(a))
    omega = np.logspace(np.log10(magnitudes.min() / 10), np.log10(magnitudes.max() * 10), 300)
    eye = np.eye(n)
    k = np.stack([-c @ np.linalg.solve(1j * w * eye - a, b) for w in omega])
    k0 = -c @ np.linalg.solve(-a, b)
    peak = np.abs(k).max(axis=0)
    group = np.repeat(np.arange(per_dof.size), per_dof)
    first_b = {j: start + n + int(np.argmax(group == j)) for j in np.flatnonzero(per_dof)}
    rows_c = start + 2 * n
    found: list[tuple[str, int]] = []
    modelled = peak > 0
    ratio = np.abs(k0) / np.where(modelled, peak, 1.0)
    if np.any(ratio > RESPONSE_LIMITS["zero_frequency"]):
        i, j = np.argwhere(ratio > RESPONSE_LIMITS["zero_frequency"])[0]
        found.append(
            (
                f"K({i + 1},{j + 1}) at ω = 0 is {ratio[i, j]:.2g} of its peak, not 0: a radiation "
                "memory function vanishes at ω = 0 (a row of B moved?)",
                first_b.get(j, start + n),
            )
        )
    for j in np.flatnonzero(np.diag(modelled)):
        lowest = float(k[:, j, j].real.min()) / peak[j, j]
        if lowest < -RESPONSE_LIMITS["negative_damping"]:
            found.append(
                (
                    f"the damping Re K({j + 1},{j + 1}) falls to {lowest:.2g} of its peak: "
                    "the radiation damping of a DOF is positive (a row of C moved?)",
                    rows_c + j,
                )
            )
            break
    for i in range(c.shape[0]):
        for j in range(i + 1, c.shape[0]):
            if modelled[i, j] and modelled[j, i]:
                gap = np.abs(k[:, i, j] - k[:, j, i]).max() / max(peak[i, j], peak[j, i])
                if gap > RESPONSE_LIMITS["reciprocity"]:
                    found.append(
                        (
                            f"K({i + 1},{j + 1}) and K({j + 1},{i + 1}) differ by {gap:.2g} of "
                            "their peak: radiation couplings are reciprocal (a row of C moved?)",
                            rows_c + i,
                        )
                    )
                    break
    for message, line in found[:1]:
        warnings.warn(
            HydroDataWarning(
                str(
                    text.error(
                        message,
                        line,
                        hint="check the file against the data it was fitted to",
                    )
                )
            ),
            stacklevel=3,
        )


def _rows(text: TextFile, start: int, count: int, width: int) -> NDArray[np.float64]:
    out = np.empty((count, width))
    for r in range(count):
        values = parse_numbers(text.lines[start + r])
        if values is None or values.size != width:
            found = "text" if values is None else f"{values.size} numbers"
            raise text.error(f"expected a matrix row of {width} numbers, found {found}", start + r)
        if not np.all(np.isfinite(values)):
            raise text.error("NaN or Inf in a matrix", start + r)
        out[r] = values
    return out


# --------------------------------------------------------------------------- excitation


@dataclass(frozen=True)
class OpenFastExcitationSS:
    """A state-space model of the wave excitation (SS_Fitting's ``.ssexctn``).

    HydroDyn's ``SS_Excitation`` module integrates x' = A x + B η(t + t_c), F = C x, with
    η the incident wave elevation at the platform origin and t_c the time offset that
    makes the non-causal excitation impulse response causal (Yu & Falnes 1995; the
    model fits K_e(t − t_c)). Its frequency response is therefore

        F(ω)/η(ω) = C (jωI − A)⁻¹ B · e^{jω t_c}

    in cummins' e^{+iωt} convention (WAMIT's), to compare with the data's
    ``excitation_force`` at the file's wave heading.

    Attributes
    ----------
    title
        Line 1.
    heading
        Wave heading of the fit, degrees (line 2).
    time_offset
        t_c, s; ``None`` when the file does not record it (the "%Enabled DoFs" layout
        of SS_Fitting v1.00.01's time-domain method, which HydroDyn cannot read: its
        third line is read by HydroDyn as the time offset).
    dof_flags
        6·NBody flags of the "%Enabled DoFs" layout, else ``None``.
    states_per_dof
        States per DOF.
    A, B, C
        (N, N), (N,), (6·NBody, N).
    path
        The file read.
    """

    title: str
    heading: float
    time_offset: float | None
    dof_flags: NDArray[np.int_] | None
    states_per_dof: NDArray[np.int_]
    A: NDArray[np.float64]
    B: NDArray[np.float64]
    C: NDArray[np.float64]
    path: Path | None = None

    @property
    def n_states(self) -> int:
        return int(self.A.shape[0])

    def frequency_response(
        self, omega: ArrayLike, time_offset: float | None = None
    ) -> NDArray[np.complex128]:
        """F(ω)/η, shape (nω, 6·NBody), N/m and N·m/m (e^{+iωt}).

        ``time_offset`` (s) replaces the file's t_c (needed when the file has none).
        """
        tc = self.time_offset if time_offset is None else float(time_offset)
        if tc is None:
            raise HydroDataError(
                "the file does not record the time offset t_c of the excitation model",
                path=self.path,
                hint="pass time_offset= (HydroDyn would read this layout's third line as t_c)",
            )
        w = np.asarray(omega, dtype=float).reshape(-1)
        eye = np.eye(self.n_states)
        out = np.empty((w.size, self.C.shape[0]), dtype=complex)
        for k, wk in enumerate(w):
            out[k] = self.C @ np.linalg.solve(1j * wk * eye - self.A, self.B)
            out[k] *= np.exp(1j * wk * tc)
        return out


def is_excitation_file(text: TextFile) -> bool:
    """SS_Excitation_Fitting's header: title naming it, or "%Wave heading" on line 2."""
    title = text.lines[0].lower()
    second = text.lines[1].lower() if len(text) > 1 else ""
    return "excitation" in title or "wave heading" in second


def read_openfast_ssexctn(path: str | os.PathLike[str]) -> OpenFastExcitationSS:
    """Read a state-space excitation model (``.ssexctn``, or an ``.ss`` holding one).

    Two layouts are in use (OpenFAST r-tests, WEIS): HydroDyn's ("title / heading /
    time offset t_c / N / states per DOF", written by SS_Excitation_Fitting) and
    SS_Fitting v1.00.01's time-domain method ("title / heading / DOF flags / N / states
    per DOF", no t_c). Then A (N rows of N), B (N rows of 1), C (6·NBody rows of N), and
    nothing after: as HydroDyn counts them ((lines − 5 − 6·NBody)/2 = N).

    Raises
    ------
    HydroDataError
        Naming the file and line: the counts, headers and matrix rows as for
        :func:`read_openfast_ss`, and the grouping of the states per DOF (A
        block-diagonal, C giving each DOF's force from its own states only), blocks
        of A that decay and have an input and an output.
    """
    text = TextFile.read(path)
    if len(text) < 5:
        raise text.error("the file ends before the 5 header lines", len(text) - 1)
    heading = parse_numbers(text.lines[1].split("%")[0])
    if heading is None or heading.size != 1 or not np.isfinite(heading[0]):
        raise text.error("expected the wave heading (degrees) on line 2", 1)
    third = text.lines[2].split("%")[0]
    comment = text.lines[2].lower()
    values = parse_numbers(third)
    if values is None or values.size == 0:
        raise text.error("expected the time offset or the DOF flags on line 3", 2)
    flags = None
    time_offset = None
    if "enabled" in comment or values.size > 1:
        flags = values
        if flags.size % 6 or np.any((flags != 0) & (flags != 1)):
            raise text.error(f"expected 6·NBody DOF flags (0 or 1), found {flags.size}", 2)
        flags = flags.astype(int)
    else:
        time_offset = float(values[0])
        if not np.isfinite(time_offset) or abs(time_offset) > 1e4:
            raise text.error(f"time offset {time_offset!r} s is not usable", 2)
    count = _leading_integers(text, 3, "number of states")
    if count.size < 1 or count[0] <= 0:
        raise text.error("expected the number of states", 3)
    n_states = int(count[0])
    per_dof = _leading_integers(text, 4, "states per DOF")
    if per_dof.size == 0 or per_dof.size % 6:
        raise text.error(f"expected 6·NBody numbers of states per DOF, found {per_dof.size}", 4)
    if flags is not None and flags.size != per_dof.size:
        raise text.error(f"{flags.size} DOF flags but {per_dof.size} numbers of states per DOF", 4)
    if int(per_dof.sum()) != n_states:
        raise text.error(f"the states per DOF add up to {int(per_dof.sum())}, not to {n_states}", 4)
    _check_header_comments(text, range(1, 5))
    n_dofs = per_dof.size
    expected = 5 + 2 * n_states + n_dofs
    if len(text) != expected:
        raise text.error(
            f"expected {expected} lines (5 header lines, {n_states} rows of A, {n_states} of "
            f"B, {n_dofs} of C), found {len(text)}",
            min(len(text), expected) - 1,
            hint="HydroDyn counts every line, blank ones too",
        )
    a = _rows(text, 5, n_states, n_states)
    b = _rows(text, 5 + n_states, n_states, 1)[:, 0]
    c = _rows(text, 5 + 2 * n_states, n_dofs, n_states)
    check_cut_numbers(text, range(5, expected), range(n_states))
    _check_structure(text, 5, a, b, c, per_dof.astype(int), excitation=True)
    return OpenFastExcitationSS(
        title=text.lines[0].strip(),
        heading=float(heading[0]),
        time_offset=time_offset,
        dof_flags=flags,
        states_per_dof=per_dof.astype(int),
        A=a,
        B=b,
        C=c,
        path=text.path,
    )
