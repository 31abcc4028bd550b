"""The ``reciprocity`` check: what the identification does with data that are not
reciprocal (A_ij ≠ A_ji, B_ij ≠ B_ji at zero speed).

The ``symmetry`` check says how far the matrices are from symmetric; this one says
whether it matters for the motions and what ``cummins fit`` does about it, with the
decision the fit itself takes (:func:`cummins.radiation.fit.reciprocity.reciprocity_of`):
where the data's reciprocal part alone is further from the data's own motions than the
fit's motion aim (without inertia: where it misses a coupling's R² target), the block's
couplings are fitted as given, K_ij and K_ji each, passive as K(jω) + K(jω)ᴴ ⪰ 0.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import xarray as xr

from cummins.check.common import PreparedFits, _speeds
from cummins.check.report import Finding

if TYPE_CHECKING:
    from cummins.repair import Judged


def _check_reciprocity(
    ds: xr.Dataset, judged: Judged = (), prepared: PreparedFits | None = None
) -> list[Finding]:
    """One finding at zero speed when some coupling is not reciprocal (none when every
    pair is, or the data cannot be fitted: other checks say why); ``judged``: data whose
    suspect frequencies were found already (:func:`cummins.repair.suspects_by_dof`);
    ``prepared``: the preparations of the data shared by the checks (made here when not
    given)."""
    zero = [sub for sub in _speeds(ds) if float(sub.coords.get("forward_speed", 0.0)) == 0.0]
    if not zero:
        return []
    inp = (prepared or PreparedFits(judged))(zero[0])
    if inp is None:
        return []
    found = inp.reciprocity
    if found.as_given:
        pairs = sorted(found.as_given)
        labels = inp.labels
        return [
            Finding(
                "reciprocity",
                "warning",
                " ".join(found.notes),
                where=", ".join(f"{labels[i]}-{labels[j]}" for i, j in pairs[:6])
                + (" …" if len(pairs) > 6 else ""),
                value=max((x for x in found.floors.values() if x is not None), default=None),
                advice="cummins fit fits these couplings as given (K_ij ≠ K_ji), passive as "
                "K(jω) + K(jω)ᴴ ⪰ 0 (--reciprocity average for the reciprocal part "
                "alone); at zero speed A and B should be symmetric: check the solver run "
                "(mesh, DOF order, signs)",
                details={
                    "couplings_as_given": [f"{labels[i]}-{labels[j]}" for i, j in pairs],
                    "motion_error_of_reciprocal_part": {
                        "-".join(labels[d] for d in dofs): floor
                        for dofs, floor in found.floors.items()
                    },
                },
            )
        ]
    floors = {dofs: x for dofs, x in found.floors.items() if x is not None}
    if floors:
        dofs, worst = max(floors.items(), key=lambda item: item[1])
        return [
            Finding(
                "reciprocity",
                "ok",
                f"A and B are not exactly reciprocal, but their reciprocal part is within "
                f"{100 * worst:.3g} % of the data's own motions "
                f"({'-'.join(inp.labels[d] for d in dofs)}): cummins fit uses it",
                value=worst,
            )
        ]
    return []
