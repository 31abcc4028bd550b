"""The ``--second-order`` option of ``cummins simulate`` and ``cummins dp-demo``, and what
both say about it."""

from __future__ import annotations

import warnings

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


def keep_suspect_option(func):
    """``--keep-suspect`` (the mean drift at the suspect frequencies)."""
    return click.option(
        "--keep-suspect",
        "keep_suspect",
        is_flag=True,
        default=False,
        help="With --second-order mean|newman: keep the mean drift at the suspect "
        "frequencies of the data (irregular frequencies, which cummins check lists). "
        "By default they are left out of it: bridged linearly between sound "
        "neighbours, no drift above the last sound frequency.",
    )(func)


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


def build_second_order(
    ds, sea, model: str, *, sum_frequency: bool | None = None, keep_suspect: bool = False
):
    """The :func:`~cummins.timedomain.loads.second_order.second_order_force` of ``sea``,
    or None for ``model == "none"`` (with a note when the data hold second-order data);
    its warnings and notes are printed."""
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
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        force = second_order_force(
            ds, sea, model=model, sum_frequency=sum_frequency, keep_suspect=keep_suspect
        )
    for w in caught:  # printed once, as a warning, not again as a note
        warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    said = {str(w.message) for w in caught}
    for line in force.notes:
        if line not in said:
            console.print(f"note: {line}")
    return force
