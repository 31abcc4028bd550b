"""The mean drift at the suspect frequencies of the radiation data.

A panel method without irregular-frequency removal spoils the whole solution at its
irregular frequencies, the diffraction potential too: the mean drift, quadratic in the
potential, is worse than the A(ω), B(ω) that reveal them. The WAMIT tanker's ``.out``
prints a heave drift of −1.7·10⁸ N/m² in head seas at 4.49 rad/s, where the drift is
−1.3·10⁵ N/m² at 3.4 rad/s; the damping flags 3.65–5.98 rad/s.

:func:`drift_suspect_frequencies` takes the suspect frequencies the fit and ``cummins
kernel`` leave out (:func:`cummins.repair.suspects_by_dof`: each DOF's own curves; the
points of a sharp resonance of the data, physics, are not suspect), over all DOFs: one
irregular frequency spoils the drift of every DOF. :func:`drift_at_suspects` measures
the drift there against its values elsewhere (``cummins check``), and the second-order
loads (:mod:`cummins.timedomain.loads.second_order`, the DP model's
:class:`~cummins.timedomain.loads.WaveDriftLoad`) leave those frequencies out of the
mean drift by default (:func:`suspects_left_out`; interior ones bridged linearly between
their sound neighbours, beyond the last sound frequency the drift is zero, as outside the
data).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from cummins.errors import AssumptionWarning

if TYPE_CHECKING:
    from cummins.repair import Judged

#: The mean drift at the suspect frequencies beyond this multiple of its largest value
#: elsewhere (a DOF's) is spoilt: ``cummins check`` names it a warning and the
#: second-order loads leave those frequencies out (:func:`suspects_left_out`). The WAMIT
#: tanker: 9 497 (surge); the WAMIT drift sphere 0.85, the S-175 and supply vessel of MSS
#: 0 (their one suspect frequency, the lowest, holds no drift).
DRIFT_SUSPECT_RATIO = 1.5


def drift_suspect_frequencies(ds: xr.Dataset, judged: Judged = ()) -> NDArray[np.float64]:
    """The frequencies (rad/s, sorted) of ``ds`` at which its mean drift is not trusted:
    those suspect in any DOF's own A(ω), B(ω) (:func:`cummins.repair.suspects_by_dof`),
    sharp resonances of the data excepted.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed, with ``added_mass`` and ``radiation_damping``.
    judged
        Data :func:`~cummins.repair.suspects_by_dof` has judged already, with what it
        found (``cummins check``).
    """
    from cummins.repair import suspects_by_dof

    found: set[float] = set()
    for own in suspects_by_dof(ds, judged).values():
        found |= {s.omega for s in own.suspects if s.omega not in own.features}
    return np.array(sorted(found), dtype=float)


@dataclass(frozen=True)
class SuspectDrift:
    """The mean drift at the suspect frequencies (:func:`drift_at_suspects`).

    Attributes
    ----------
    omega
        The suspect frequencies, rad/s.
    dof
        The DOF whose drift there departs most.
    ratio
        Its largest |drift| at the suspect frequencies over its largest |drift| at the
        others (all directions).
    at
        The frequency (rad/s) and direction (deg) of that value.
    value
        That value, N/m² or N·m/m².
    """

    omega: tuple[float, ...]
    dof: str
    ratio: float
    at: tuple[float, float]
    value: float


def drift_at_suspects(
    ds: xr.Dataset, suspects: NDArray[np.float64] | None = None, name: str = "drift_force"
) -> SuspectDrift | None:
    """How far the mean drift ``name`` at the suspect frequencies departs from its values
    at the sound ones: per DOF, the largest |F̄| there over the largest elsewhere; the
    worst DOF. None when there are no suspect frequencies or no sound one.

    Parameters
    ----------
    ds
        A ``HydroDB`` at one forward speed with ``name``.
    suspects
        The suspect frequencies (default :func:`drift_suspect_frequencies`).
    """
    suspects = drift_suspect_frequencies(ds) if suspects is None else suspects
    w = ds.omega.values
    bad = np.isin(w, suspects)
    if not bad.any() or bad.all():
        return None
    signed = ds[name].transpose("omega", "wave_direction", "influenced_dof").values
    drift = np.abs(signed)
    inside = drift[bad].max(axis=(0, 1))
    outside = drift[~bad].max(axis=(0, 1))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(outside > 0, inside / outside, np.where(inside > 0, np.inf, 0.0))
    k = int(np.argmax(ratio))
    sub = drift[bad][:, :, k]
    i, j = np.unravel_index(int(np.argmax(sub)), sub.shape)
    value = signed[bad][i, j, k]
    return SuspectDrift(
        tuple(float(x) for x in w[bad]),
        str(ds.influenced_dof.values[k]),
        float(ratio[k]),
        (float(w[bad][i]), float(np.degrees(ds.wave_direction.values[j]))),
        float(value),
    )


def suspects_left_out(
    ds: xr.Dataset, keep: bool, notes: list[str], stacklevel: int = 4
) -> tuple[float, ...]:
    """The suspect frequencies (:func:`drift_suspect_frequencies`) to leave out of the
    mean drift of a second-order load, with an :class:`~cummins.errors.AssumptionWarning`
    and a line in ``notes`` saying so. None when ``keep`` (a line says they were kept),
    when the drift there is no larger than :data:`DRIFT_SUSPECT_RATIO` times its largest
    elsewhere (:func:`drift_at_suspects`: not spoilt, kept, a line says so), or when
    fewer than two frequencies would stay."""
    if "added_mass" not in ds or "radiation_damping" not in ds:
        return ()
    suspects = drift_suspect_frequencies(ds)
    listed = ", ".join(f"{x:.4g}" for x in suspects)
    if suspects.size == 0:
        return ()
    if keep:
        notes.append(
            f"mean drift kept at the {suspects.size} suspect frequencies ({listed} rad/s) "
            "as asked (irregular frequencies may spoil it: cummins check)"
        )
        return ()
    w = ds.omega.values
    sound = w[~np.isin(w, suspects)]
    if sound.size < 2:
        return ()
    found = drift_at_suspects(ds, suspects) if "drift_force" in ds else None
    if found is not None and found.ratio <= DRIFT_SUSPECT_RATIO:
        notes.append(
            f"mean drift kept at the {suspects.size} suspect frequencies ({listed} rad/s): "
            f"no larger there than elsewhere ({found.dof}: {found.ratio:.3g} times)"
        )
        return ()
    how = []
    if ((suspects > sound[0]) & (suspects < sound[-1])).any():
        how.append("bridged linearly between sound neighbours")
    if (suspects < sound[0]).any():
        how.append(f"no drift below {sound[0]:.4g} rad/s")
    if (suspects > sound[-1]).any():
        how.append(f"no drift above {sound[-1]:.4g} rad/s")
    spoilt = (
        ""
        if found is None
        else f"{found.dof} up to {found.ratio:.3g} times its largest elsewhere; "
    )
    line = (
        f"mean drift left out at the {suspects.size} suspect frequencies of the data "
        f"({listed} rad/s; {spoilt}irregular frequencies spoil it: {', '.join(how)}); "
        "keep_suspect=True (--keep-suspect) keeps them"
    )
    warnings.warn(line, AssumptionWarning, stacklevel=stacklevel)
    notes.append(line)
    return tuple(float(x) for x in suspects)
