"""Modes per body of a WAMIT run: several bodies, and generalized modes (mode 7, 8 … of a
body, WAMIT User Manual v7 ch. 8), as the files say (``.out``, ``.pot``, ``.mmx``, the
``.cfg``'s NEWMDS) or ``modes=`` gives, never from n % 6; and the memory check of a run's
arrays (:data:`MEMORY_LIMIT`).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from cummins.errors import HydroDataError

#: Memory the arrays of one run may take before the reader refuses (bytes).
MEMORY_LIMIT = 4 * 2**30


def _mode_layout(
    n_seen: int,
    *,
    n_bodies: int | None,
    new_modes: dict[int, int],
    extra_modes: bool | None,
    modes: int | Sequence[int] | None,
    path: Path,
    history: list[str],
) -> list[int]:
    """Modes per body, from the files (never from n % 6).

    ``n_seen`` is the largest DOF index in the data; ``n_bodies`` the body count the
    ``.out``/``.pot``/``.mmx`` give; ``new_modes`` the ``.cfg`` NEWMDS per body;
    ``extra_modes`` whether the ``.out`` announces generalized modes (``None``: no
    ``.out``).
    """
    if modes is not None:
        layout = [int(modes)] if isinstance(modes, int | np.integer) else [int(m) for m in modes]
        if any(m < 1 for m in layout) or sum(layout) < n_seen:
            raise HydroDataError(
                f"modes={layout} does not hold the DOF indices 1…{n_seen} of the file",
                path=path,
            )
        history.append(f"modes per body: {layout} (given)")
        return layout
    if n_bodies is not None and n_bodies < 1:
        raise HydroDataError("the files announce no body", path=path)
    if new_modes and n_bodies is not None:
        layout = [6 + new_modes.get(k + 1, 0) for k in range(n_bodies)]
        if sum(layout) < n_seen:
            raise HydroDataError(
                f"DOF index {n_seen} in the data, but the .cfg announces {sum(layout)} modes "
                f"({layout} per body)",
                path=path,
                hint="the files come from different runs, or one is damaged",
            )
        history.append(f"modes per body: {layout} (bodies from the files, NEWMDS from the .cfg)")
        return layout
    if n_bodies == 1:
        if n_seen > 6 and extra_modes is False:
            raise HydroDataError(
                f"DOF index {n_seen} in the data, but the .out announces one body and no "
                "generalized modes",
                path=path,
                hint="the file is damaged, or pass modes= to say how many modes the body has",
            )
        layout = [max(n_seen, 6)]
        if n_seen > 6:
            history.append(f"one body with {n_seen - 6} generalized modes (Mode7 …)")
        return layout
    if n_bodies is not None:
        if n_seen > 6 * n_bodies:
            raise HydroDataError(
                f"DOF index {n_seen} in the data, more than the 6 modes of each of the "
                f"{n_bodies} bodies the files announce",
                path=path,
                hint="keep the run's .cfg (NEWMDS) beside it, or pass modes=[…] per body",
            )
        return [6] * n_bodies
    if n_seen <= 6:
        return [6]
    raise HydroDataError(
        f"DOF indices go up to {n_seen}, and no file of the run says how many bodies there are",
        path=path,
        hint=f"keep the run's .out (or .pot, .mmx, .cfg) beside it, or pass modes=: e.g. "
        f"modes=[6, 6] for two bodies, modes={n_seen} for one body with generalized modes",
    )


def _check_memory(n: int, n_omega: int, n_beta: int, path: Path) -> None:
    need = 8 * n * n * n_omega * 4 + 16 * n * n_beta * n_omega * 4
    if need > MEMORY_LIMIT:
        raise HydroDataError(
            f"{n} DOFs × {n_omega} frequencies would need {need / 2**30:.1f} GiB",
            path=path,
            hint="the DOF count comes from the file's indices: is the file damaged?",
        )
