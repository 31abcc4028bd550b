"""The ``--second-order`` option of ``cummins simulate`` and ``cummins dp-demo``, and what
both say about it."""

from __future__ import annotations

import click

from cummins.cli.common import console

#: The choices of ``--second-order``.
CHOICES = ("none", "mean", "newman", "full")

HELP = (
    "Second-order wave force of the same sea: mean (the mean drift), newman (mean and "
    "slowly varying drift by Newman's approximation, from the QTF's diagonal or the "
    "mean drift), full (the full difference-frequency QTF, and the sum-frequency QTF "
    "when the data have one), none. A body without mooring (--external-stiffness) "
    "drifts off under the mean force."
)


def second_order_option(default: str = "none", help: str = HELP):
    """The ``--second-order`` click option."""
    return click.option(
        "--second-order",
        "second_order",
        type=click.Choice(CHOICES),
        default=default,
        show_default=True,
        help=help,
    )


def sum_frequency_option(func):
    """``--sum-frequency/--no-sum-frequency`` (with ``--second-order full``)."""
    return click.option(
        "--sum-frequency/--no-sum-frequency",
        "sum_frequency",
        default=None,
        help="With --second-order full: include the sum-frequency force (default: when "
        "the data have a sum-frequency QTF).",
    )(func)


def what_the_data_hold(ds) -> str | None:
    """A note naming the second-order data of ``ds`` (None when it has none)."""
    from cummins.qtf import has_qtf

    if has_qtf(ds, "difference"):
        return "a difference-frequency QTF"
    if "drift_force" in ds:
        return "a mean drift"
    return None


def build_second_order(ds, sea, model: str, *, sum_frequency: bool | None = None):
    """The :func:`~cummins.timedomain.loads.second_order.second_order_force` of ``sea``,
    or None for ``model == "none"`` (with a note when the data hold second-order data);
    its notes are printed."""
    from cummins.timedomain.loads.second_order import second_order_force

    if model == "none":
        held = what_the_data_hold(ds)
        if held:
            console.print(
                f"note: the data hold {held}, not used (--second-order mean|newman|full "
                "adds the second-order wave force)"
            )
        return None
    if sum_frequency and model != "full":
        raise click.UsageError("--sum-frequency needs --second-order full")
    force = second_order_force(ds, sea, model=model, sum_frequency=sum_frequency)
    for line in force.notes:
        console.print(f"note: {line}")
    return force
