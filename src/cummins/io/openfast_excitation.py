"""OpenFAST HydroDyn state-space wave-excitation file (``.ssexctn``), written from a
causal excitation model.

HydroDyn integrates the wave excitation as a state-space model when ``ExctnMod = 2``:
``SS_Exc_Init`` (``modules/hydrodyn/src/SS_Excitation.f90``) reads
``<PotFile>.ssexctn`` and integrates x' = A x + B η(t + t_c), F = C x, with η the
incident wave elevation at the platform origin (``WaveElev0``; at the displaced
position with ``ExctnDisp`` > 0) and F added to the platform loads as it is (N, N·m).
NREL's SS_Excitation_Fitting, which made the files in use, was never released. Layout,
for NBody bodies and N states (one record per line; numbers free-format)::

    line 1              title (any text)
    line 2              wave heading, degrees, then an optional comment
    line 3              time offset t_c, s, then an optional comment
    line 4              N, the number of states, then an optional comment
    line 5              6·NBody numbers of states per DOF (they add up to N)
    next N lines        A, one row per line (N numbers)
    next N lines        B, one number per line
    next 6·NBody lines  C, one row per line (N numbers)

and nothing after: HydroDyn counts the lines and requires 2N + 6·NBody of them after
line 5 (a blank line at the end counts). Conventions, as HydroDyn uses them:

* The heading is the direction the waves travel, degrees, HydroDyn's ``WaveDir`` (0:
  along +x, the platform's surge axis): HydroDyn stops with an error unless it equals
  the sea state's ``WaveDir``. A file holds one heading.
* t_c: the model is driven by the elevation t_c ahead (``GetWaveElevation(t + Tc)``).
* B is one column: the states of each body are driven by that body's elevation (all
  the same at ``ExctnDisp = 0``).
* Axes are HydroDyn's platform axes, z up (cummins' ``"z-up"``), forces about the
  WAMIT body reference point, SI units (not scaled by ρ or g). A ``"z-down"`` model is
  converted on writing: rows of C times diag(1, −1, −1, 1, −1, −1), heading −β.
* The states are grouped by DOF (line 5): DOF d's force is read from its own states
  only; a DOF with 0 states has a zero row of C. (HydroDyn rotates the rows of C by
  ``PtfmRefztRot``; nothing else depends on the grouping.)

Numbers are written with 17 significant digits: the file reads back to the same
matrices (:func:`cummins.io.openfast.read_openfast_ssexctn`).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from cummins._version import __version__
from cummins.errors import HydroDataError, check_writable
from cummins.hydrodb import DOF_NAMES, split_dof
from cummins.io.openfast import OpenFastExcitationSS

__all__ = [
    "excitation_model_from_ssexctn",
    "format_openfast_ssexctn",
    "openfast_ssexctn_from_model",
    "write_openfast_ssexctn",
]

_FMT = "{:.16e}"
#: diag(T) of the change between z-down (Fossen) and z-up axes, per rigid-body DOF.
_Z_DOWN_SIGNS = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])


def _check_dofs(dofs, path) -> None:
    """Six rigid-body DOFs per body, Surge … Yaw, as HydroDyn's 6·NBody rows."""
    names = [split_dof(str(d))[1] for d in dofs]
    n = len(names)
    if n == 0 or n % 6 or names != list(DOF_NAMES) * (n // 6):
        raise HydroDataError(
            f"HydroDyn's .ssexctn holds the six rigid-body DOFs of each body (Surge … Yaw); "
            f"the model has {', '.join(str(d) for d in dofs)}",
            path=path,
            hint="fit the excitation of all six DOFs of each body (no generalized modes)",
        )


def _heading_index(model, heading: float | None, path) -> int:
    if heading is None:
        if np.size(model.headings) != 1:
            have = ", ".join(f"{np.degrees(b):g}" for b in model.headings)
            raise HydroDataError(
                f"the model holds {np.size(model.headings)} headings ({have} deg); HydroDyn "
                "reads one per .ssexctn (its WaveDir)",
                path=path,
                hint="give the heading to write (heading= in degrees, --heading DEG)",
            )
        return 0
    return model.heading_index(np.radians(float(heading)))


def openfast_ssexctn_from_model(
    model, heading: float | None = None, *, title: str | None = None
) -> OpenFastExcitationSS:
    """The ``.ssexctn`` content of one heading (degrees; default the model's only one) of
    an :class:`~cummins.excitation_model.model.ExcitationModel`, in HydroDyn's z-up axes.
    """
    _check_dofs(model.dofs, None)
    h = _heading_index(model, heading, None)
    a, b, c = model.state_space(h)
    beta = float(model.headings[h])
    if model.attrs.get("axis_convention", "z-up") == "z-down":
        c = c * np.tile(_Z_DOWN_SIGNS, len(model.dofs) // 6)[:, None]
        beta = -beta
    degrees = float(np.degrees(np.angle(np.exp(1j * beta))))
    degrees = 0.0 if abs(degrees) < 1e-12 else degrees
    if title is None:
        method = model.attrs.get("method", "vf")
        title = (
            f"cummins {__version__}: state-space wave excitation for HydroDyn SS_Excitation "
            f"(method {method}), x' = A x + B eta(t + tc), F = C x, states grouped by DOF"
        )
    return OpenFastExcitationSS(
        title=" ".join(str(title).split()),
        heading=degrees,
        time_offset=float(model.delays[h]),
        dof_flags=None,
        states_per_dof=model.orders[h].astype(int),
        A=a,
        B=b,
        C=c,
    )


def format_openfast_ssexctn(content: OpenFastExcitationSS) -> str:
    """The text of a ``.ssexctn`` file (HydroDyn's layout, module docstring)."""
    lines = [
        content.title,
        f"{content.heading:.12g}    %Wave heading angle (deg, direction of travel)",
        f"{content.time_offset:.17g}    %time offset (tc), s",
        f"{content.n_states}    %total # of states",
        " ".join(str(int(v)) for v in content.states_per_dof) + "    %# states per DOF",
    ]
    lines.extend(" ".join(_FMT.format(x) for x in row) for row in content.A)
    lines.extend(_FMT.format(x) for x in content.B)
    lines.extend(" ".join(_FMT.format(x) for x in row) for row in content.C)
    return "\n".join(lines) + "\n"


def write_openfast_ssexctn(
    model,
    path: str | os.PathLike[str],
    *,
    heading: float | None = None,
    title: str | None = None,
    force: bool = False,
) -> Path:
    """Write one heading of ``model`` as an OpenFAST HydroDyn ``.ssexctn`` file.

    Parameters
    ----------
    model
        An :class:`~cummins.excitation_model.model.ExcitationModel` of the six DOFs of
        each body, about the WAMIT body reference point.
    path
        Output file; HydroDyn reads ``<PotFile>.ssexctn``.
    heading
        The heading to write, degrees (direction of travel, as the model's); default the
        model's only heading.
    title
        Line 1; by default it names cummins and the method.
    force
        Overwrite an existing file.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    HydroDataError
        Not six rigid-body DOFs per body, no states at all, several headings and none
        chosen, a heading the model does not hold.
    """
    path = Path(path)
    check_writable(path, force)
    _check_dofs(model.dofs, path)
    try:
        content = openfast_ssexctn_from_model(model, heading, title=title)
    except HydroDataError as exc:
        raise HydroDataError(str(exc), path=path) from None
    if content.n_states == 0:
        raise HydroDataError(
            "the model has no states at this heading (no DOF is excited): nothing to write",
            path=path,
            hint="without wave excitation, run HydroDyn with ExctnMod = 0",
        )
    path.write_text(format_openfast_ssexctn(content), encoding="utf-8")
    return path


def excitation_model_from_ssexctn(
    content: OpenFastExcitationSS,
    *,
    time_offset: float | None = None,
    dofs: tuple[str, ...] | None = None,
    axis_convention: str = "z-up",
):
    """A ``.ssexctn`` (SS_Excitation_Fitting's, cummins') as an
    :class:`~cummins.excitation_model.model.ExcitationModel` of one heading (z-up axes),
    to simulate or to compare with data.

    Parameters
    ----------
    content
        From :func:`cummins.io.openfast.read_openfast_ssexctn`.
    time_offset
        t_c, s, for a file that does not record it (SS_Fitting's time-domain layout);
        overrides the file's otherwise.
    dofs
        DOF labels; default ``Surge`` … ``Yaw`` (``body1__Surge`` … for several bodies).
    axis_convention
        Written to the model's attributes (the file's axes are z-up).
    """
    from cummins.excitation_model.model import DofExcitation, ExcitationModel
    from cummins.io.openfast import default_dof_labels

    tc = content.time_offset if time_offset is None else float(time_offset)
    if tc is None:
        raise HydroDataError(
            "the file does not record the time offset t_c of the excitation model",
            path=content.path,
            hint="pass time_offset= (HydroDyn would read this layout's third line as t_c)",
        )
    n = content.C.shape[0]
    labels = default_dof_labels(n) if dofs is None else tuple(dofs)
    parts = []
    start = 0
    for d, count in enumerate(content.states_per_dof):
        rows = slice(start, start + int(count))
        parts.append(
            DofExcitation(
                d, 0, content.A[rows, rows].copy(), content.B[rows].copy(),
                content.C[d, rows].copy(), {}, "",
            )
        )  # fmt: skip
        start += int(count)
    attrs = {"axis_convention": axis_convention, "source_format": "openfast-ssexctn"}
    if content.path is not None:
        attrs["source_file"] = str(content.path)
    return ExcitationModel(
        tuple(labels), np.array([np.radians(content.heading)]), np.array([tc]), tuple(parts),
        attrs,
    )  # fmt: skip
