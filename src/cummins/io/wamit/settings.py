"""What another program's run fixes for the WAMIT-format reader (:class:`RunSettings`,
used for HAMS).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class RunSettings:
    """What another program's run fixes for the WAMIT-format reader (used for HAMS).

    Attributes
    ----------
    source_format
        Recorded as the dataset's ``source_format``.
    first_column
        Kind of the first column (see :data:`FIRST_COLUMNS`).
    rho, g, ulen, water_depth
        Constants of the run, as recorded in its files (``None``: unknown).
    constants_source
        Where ``rho`` and ``g`` come from when no file of the run records them (the
        program's fixed constants), for the history; ``None``: from the files.
    history
        Lines to add to the dataset's history.
    inertia_matrix, additional_damping, additional_stiffness
        Matrices the run's input holds (n×n, dimensional).
    reference_point
        Point about which the run's moments are taken, m.
    rao_times_rho_g
        The ``.4`` holds i·ξ/(ρg) instead of the RAO ξ (HAMS does so).
    notes
        Damage the project's own files showed (warned about already), for the
        dataset's ``read_warnings``.
    """

    source_format: str = "wamit"
    first_column: str | None = None
    rho: float | None = None
    g: float | None = None
    ulen: float | None = None
    water_depth: float | None = None
    constants_source: str | None = None
    history: list[str] = field(default_factory=list)
    inertia_matrix: np.ndarray | None = None
    additional_damping: np.ndarray | None = None
    additional_stiffness: np.ndarray | None = None
    reference_point: np.ndarray | None = None
    rao_times_rho_g: bool = False
    notes: list[str] = field(default_factory=list)
