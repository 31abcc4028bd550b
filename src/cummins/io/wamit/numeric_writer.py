"""Writing WAMIT numeric files ``.1``, ``.3`` and ``.hst`` from any ``HydroDB``.

So that a Capytaine, NEMOH, AQWA or HAMS run can feed the tools that read WAMIT's
files — OpenFAST's HydroDyn above all (``PotFile``), and SS_Fitting. The files are
nondimensional as WAMIT writes them (WAMIT User Manual v7 §4.1; the scales of
:mod:`cummins.io.wamit`), with ρ, g and ULEN = L given:

* ``.1``   ``PER  I  J  Ā(I,J)  B̄(I,J)``, Ā = A/(ρ L^(3+k_i+k_j)), B̄ = B/(ρ ω L^(3+k_i+k_j)),
  and the limits without B̄: PER = −1 for ω = 0 (``added_mass_zero``), PER = 0 for ω = ∞
  (``added_mass_inf``), when the data hold them; the entries nonzero at some frequency
  (WAMIT leaves structural zeros out), the same in every block;
* ``.3``   ``PER  β  I  |X̄|  arg X̄  Re X̄  Im X̄``, X̄ = X/(ρ g L^(2+k_i)), β and the phase
  in degrees, every DOF of every heading;
* ``.hst`` ``I  J  C̄(I,J)``, C̄ = C/(ρ g L^(2+k_i+k_j)), every entry: by default the
  restoring of buoyancy and waterplane alone, as HydroDyn reads it (the weight's terms
  the data record taken out), and the ``.1`` with estimated limit rows when the data
  lack them (:mod:`cummins.io.wamit.hydrodyn`);
* ``.7``, ``.8``, ``.9`` the mean drift (``drift_force`` and the other estimates a run
  holds, ``drift_force_<method>``), each in the file of its method — ``.7`` the control
  surface, ``.8`` momentum conservation, ``.9`` pressure integration (WAMIT User Manual v7
  §4.10; what HydroDyn's ``MnDrift``/``NewmanApp`` = 7, 8 or 9 read): ``PER  β  β  I
  |F̄|  arg F̄  Re F̄  Im F̄``, F̄ = F/(ρ g L^(1+k_i)) per squared wave amplitude, a
  title line, then one row per period, heading (β₁ = β₂) and DOF the method computes
  (``dofs_computed``). A drift whose
  method the data do not record (MSS, VERES, AQWA) goes to the ``.9`` when it holds
  heave, roll or pitch (which only the near-field methods compute), else to the ``.8``,
  with an :class:`~cummins.errors.AssumptionWarning` naming the choice;

k = 1 for rotations, 0 for translations and generalized modes; PER the period 2π/ω, s.
Numbers are written as WAMIT prints them, with 7 significant digits (``E14.6``), so a
file read back gives the data to that precision. Axes are WAMIT's (z up; a ``z-down``
dataset is converted), moments about the data's ``reference_point`` (WAMIT's body
origin XBODY), time dependence Re{X e^{iωt}} and the heading the direction of travel,
as WAMIT's. Not written: the ``.4`` RAOs and the mass properties (``.frc``), which
HydroDyn does not read.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from cummins._version import __version__
from cummins.errors import AssumptionWarning, HydroDataError, check_writable
from cummins.hydrodb import change_axes, dof_matrix, single_speed
from cummins.io._common import force_exponents, length_exponents
from cummins.qtf.data import DRIFT_ALTERNATIVES

__all__ = ["write_wamit"]

_NUMBER = "{:14.6E}"


def _modes(ds: xr.Dataset) -> list[int]:
    from cummins.hydrodb import bodies, split_dof

    labels = [str(d) for d in ds.influenced_dof.values]
    return [sum(1 for lab in labels if split_dof(lab)[0] == body) for body in bodies(ds)]


def _periods(omega: np.ndarray) -> np.ndarray:
    return 2 * np.pi / omega


def format_dot1(ds: xr.Dataset, rho: float, length: float) -> str:
    """The text of the ``.1`` file (module docstring)."""
    n = ds.sizes["influenced_dof"]
    scale = rho * length ** length_exponents(n, 3, _modes(ds))
    w = np.asarray(ds.omega.values, dtype=float)
    a = dof_matrix(ds, "added_mass") / scale
    b = dof_matrix(ds, "radiation_damping") / (scale * w[:, None, None])
    limits = []
    for mark, name in ((-1.0, "added_mass_zero"), (0.0, "added_mass_inf")):
        if name in ds:
            limits.append((mark, dof_matrix(ds, name) / scale))
    used = np.any(a != 0, axis=0) | np.any(b != 0, axis=0)
    for _, matrix in limits:
        used |= matrix != 0
    pairs = np.argwhere(used)
    lines = []
    for mark, matrix in limits:
        lines += [
            f"{_NUMBER.format(mark)} {i + 1:5d} {j + 1:5d} {_NUMBER.format(matrix[i, j])}"
            for i, j in pairs
        ]
    order = np.argsort(_periods(w))
    for k in order:
        per = _NUMBER.format(_periods(w)[k])
        lines += [
            f"{per} {i + 1:5d} {j + 1:5d} {_NUMBER.format(a[k, i, j])} {_NUMBER.format(b[k, i, j])}"
            for i, j in pairs
        ]
    return "\n".join(lines) + "\n"


def format_dot3(ds: xr.Dataset, rho: float, g: float, length: float) -> str:
    """The text of the ``.3`` file (module docstring)."""
    n = ds.sizes["influenced_dof"]
    scale = rho * g * length ** force_exponents(n, 2, _modes(ds))
    w = np.asarray(ds.omega.values, dtype=float)
    x = ds.excitation_force.transpose("omega", "wave_direction", "influenced_dof").values / scale
    beta = np.degrees(np.asarray(ds.wave_direction.values, dtype=float))
    lines = []
    for k in np.argsort(_periods(w)):
        per = _NUMBER.format(_periods(w)[k])
        for h, heading in enumerate(beta):
            for i in range(n):
                z = x[k, h, i]
                values = (abs(z), np.degrees(np.angle(z)), z.real, z.imag)
                numbers = " ".join(_NUMBER.format(v) for v in values)
                lines.append(f"{per} {_NUMBER.format(heading)} {i + 1:5d} {numbers}")
    return "\n".join(lines) + "\n"


#: The mean-drift file of each method (WAMIT's suffixes).
DRIFT_SUFFIXES: dict[str, str] = {"control_surface": ".7", "momentum": ".8", "pressure": ".9"}
#: How the readers name the methods (the start of the ``method`` attribute).
_METHOD_NAMES = (
    ("control surface", "control_surface"),
    ("pressure", "pressure"),
    ("momentum", "momentum"),
    ("far field", "momentum"),
)


def drift_files(ds: xr.Dataset) -> tuple[dict[str, str], list[str]]:
    """{suffix: variable} of the mean-drift estimates of ``ds`` (module docstring), and
    the assumptions made: a method not recorded, an estimate whose file another takes."""
    files: dict[str, str] = {}
    assumed: list[str] = []
    for name in ("drift_force", *DRIFT_ALTERNATIVES):
        if name not in ds:
            continue
        if name != "drift_force":
            method = name.removeprefix("drift_force_")
        else:
            text = str(ds[name].attrs.get("method", "")).lower()
            method = next((m for start, m in _METHOD_NAMES if text.startswith(start)), None)
        if method is None:
            computed = _computed(ds, name)
            vertical = any(d.split("__")[-1] in ("Heave", "Roll", "Pitch") for d in computed)
            method = "pressure" if vertical else "momentum"
            assumed.append(
                f"the mean drift's method is not recorded: written to the "
                f"{DRIFT_SUFFIXES[method]} ("
                + (
                    "it holds heave, roll or pitch, which only the near field computes"
                    if vertical
                    else "surge, sway and yaw alone, as momentum conservation"
                )
                + f"; HydroDyn's MnDrift = {DRIFT_SUFFIXES[method][1:]})"
            )
        suffix = DRIFT_SUFFIXES[method]
        if suffix in files:
            assumed.append(f"{name} not written: {files[suffix]} takes the {suffix}")
            continue
        files[suffix] = name
    return files, assumed


def _computed(ds: xr.Dataset, name: str) -> list[str]:
    """The DOFs the estimate ``name`` computes (``dofs_computed``, else those not zero at
    every frequency and heading)."""
    labels = [str(d) for d in ds.influenced_dof.values]
    recorded = ds[name].attrs.get("dofs_computed")
    if recorded:
        return [d for d in labels if d in str(recorded).split()]
    nonzero = (ds[name] != 0).any([d for d in ds[name].dims if d != "influenced_dof"])
    return [d for d, used in zip(labels, nonzero.values, strict=True) if used]


def format_mean_drift(ds: xr.Dataset, name: str, rho: float, g: float, length: float) -> str:
    """The text of a ``.7``/``.8``/``.9`` file of the estimate ``name`` (module docstring)."""
    labels = [str(d) for d in ds.influenced_dof.values]
    n = len(labels)
    scale = rho * g * length ** force_exponents(n, 1, _modes(ds))
    w = np.asarray(ds.omega.values, dtype=float)
    f = ds[name].transpose("omega", "wave_direction", "influenced_dof").values / scale
    beta = np.degrees(np.asarray(ds.wave_direction.values, dtype=float))
    keep = [labels.index(d) for d in _computed(ds, name)]
    source = Path(str(ds[name].attrs.get("source") or ds.attrs.get("source_file", ""))).name
    lines = [  # a title line first, as WAMIT writes it (HydroDyn's WAMIT2 skips it)
        f" WAMIT Numeric Output -- mean drift ({name}) of {source or 'the data'} "
        f"written by cummins {__version__}"
    ]
    for k in np.argsort(w):  # the longest period first, as WAMIT lists a run's
        per = _NUMBER.format(_periods(w)[k])
        for h, heading in enumerate(beta):
            angle = _NUMBER.format(heading)
            for i in keep:
                z = complex(f[k, h, i])
                values = (abs(z), np.degrees(np.angle(z)), z.real, z.imag)
                numbers = " ".join(_NUMBER.format(v) for v in values)
                lines.append(f"{per} {angle} {angle} {i + 1:5d} {numbers}")
    return "\n".join(lines) + "\n"


def format_hst(ds: xr.Dataset, rho: float, g: float, length: float) -> str:
    """The text of the ``.hst`` file (module docstring)."""
    n = ds.sizes["influenced_dof"]
    c = dof_matrix(ds, "hydrostatic_stiffness") / (
        rho * g * length ** length_exponents(n, 2, _modes(ds))
    )
    return (
        "\n".join(
            f"{i + 1:6d} {j + 1:5d} {_NUMBER.format(c[i, j])}" for i in range(n) for j in range(n)
        )
        + "\n"
    )


def write_wamit(
    ds: xr.Dataset,
    path: str | os.PathLike[str],
    *,
    ulen: float = 1.0,
    force: bool = False,
    hydrodyn: bool = True,
    limits: bool = True,
) -> list[Path]:
    """Write ``ds`` as WAMIT numeric files: ``<stem>.1``, and ``<stem>.3``, ``<stem>.hst``
    and the mean drift's ``<stem>.7``/``.8``/``.9`` when the data hold the excitation, the
    hydrostatics and mean drift (module docstring).

    Parameters
    ----------
    ds
        A ``HydroDB`` at zero forward speed.
    path
        The ``.1`` file (the others take its stem).
    ulen
        WAMIT's length scale ULEN, m (HydroDyn's ``WAMITULEN``).
    force
        Overwrite existing files.
    hydrodyn
        Write what OpenFAST's HydroDyn reads (:func:`cummins.io.wamit.hydrodyn.hydrodyn_data`):
        the restoring of buoyancy and waterplane alone (the weight's terms the files
        record taken out; an :class:`~cummins.errors.AssumptionWarning` when they do not
        say) and, with ``limits``, the ω = 0 and ω = ∞ rows the data lack, estimated.
        False: the data's own restoring and rows.
    limits
        With ``hydrodyn``, add the missing limit rows.

    Returns
    -------
    list of Path
        The files written.

    Raises
    ------
    HydroDataError
        Forward speed (WAMIT's numeric files hold zero-speed data), a path that is not a
        ``.1``, a ULEN that is not positive.
    """
    path = Path(path)
    if path.suffix != ".1":
        raise HydroDataError("a WAMIT run is written as <stem>.1 (with .3 and .hst)", path=path)
    if not (np.isfinite(ulen) and ulen > 0):
        raise HydroDataError(f"ULEN must be a positive length, not {ulen!r}", path=path)
    ds = single_speed(ds)
    speed = float(ds.forward_speed) if "forward_speed" in ds.coords else 0.0
    if speed != 0.0:
        raise HydroDataError(
            f"the data are at forward speed {speed:g} m/s; WAMIT's numeric files hold "
            "zero-speed data",
            path=path,
        )
    if ds.attrs.get("axis_convention", "z-up") != "z-up":
        ds = change_axes(ds, "z-up")
    if hydrodyn:
        from cummins.io.wamit.hydrodyn import hydrodyn_data

        prepared = hydrodyn_data(ds, limits=limits)
        for line in prepared.assumptions:
            warnings.warn(AssumptionWarning(line), stacklevel=2)
        ds = prepared.ds
    rho, g = float(ds.attrs["rho"]), float(ds.attrs["g"])
    texts = {path: format_dot1(ds, rho, ulen)}
    if "excitation_force" in ds:
        texts[path.with_suffix(".3")] = format_dot3(ds, rho, g, ulen)
    if "hydrostatic_stiffness" in ds:
        texts[path.with_suffix(".hst")] = format_hst(ds, rho, g, ulen)
    drifts, assumed = drift_files(ds)
    for suffix, name in drifts.items():
        texts[path.with_suffix(suffix)] = format_mean_drift(ds, name, rho, g, ulen)
    for target in texts:
        check_writable(target, force)
    for target, text in texts.items():
        target.write_text(text, encoding="utf-8")
    for line in assumed:
        warnings.warn(AssumptionWarning(line), stacklevel=2)
    return list(texts)
