"""The command-line options of a multi-body system: joints, PTOs, body coupling.

``rao``, ``simulate`` and ``fit`` take::

    --joint KIND BODY BODY     fixed | translational | revolute | planar, BODY a body of the
                               data (body1, its name in the file, its number) or ground
    --axis X Y Z               after a --joint or a --pto: its axis (unit vector)
    --point X Y Z              after a --joint or a --pto: a point on the axis (m)
    --pto A B                  a PTO between two DOFs (body1__Heave body2__Heave, or
                               DOF ground), or along --axis between two bodies
    --pto-damping C            after a --pto, or after a --joint (then a PTO on the
    --pto-stiffness K          joint's free motion)
    --no-body-coupling         leave out the radiation coupling between bodies

``--axis``, ``--point``, ``--pto-damping`` and ``--pto-stiffness`` belong to the
``--joint`` or ``--pto`` written before them: :func:`expand_system_args` numbers them
before click parses the line, and :func:`system_from_options` builds the
:class:`cummins.mechanics.MechanicalSystem`.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from typing import TYPE_CHECKING

import click

from cummins.cli.common import finite, non_negative
from cummins.cli.option_rules import Command
from cummins.dofs import DOF_NAMES, split_dof
from cummins.errors import ArgumentError
from cummins.mechanics.joints import JOINT_KINDS, Joint

if TYPE_CHECKING:
    from cummins.mechanics.pto import PTO
    from cummins.mechanics.system import MechanicalSystem

#: Options that belong to the --joint or --pto before them.
ATTACHED = ("--axis", "--point", "--pto-damping", "--pto-stiffness")
#: Options that start an element (a joint or a PTO).
ELEMENTS = ("--joint", "--pto")


def expand_system_args(args: Sequence[str]) -> list[str]:
    """Insert, after each of :data:`ATTACHED`, the number (1-based) of the ``--joint`` or
    ``--pto`` before it (0 when there is none), so that click can keep them apart:
    ``--joint revolute flap ground --axis 0 1 0`` → ``… --axis 1 0 1 0``."""
    out: list[str] = []
    element = 0
    for k, token in enumerate(args):
        if token == "--":
            out.extend(args[k:])
            break
        out.append(token)
        if token in ELEMENTS:
            element += 1
        elif token in ATTACHED:
            count = 1 if token.startswith("--pto-") else 3
            values = list(args[k + 1 : k + 1 + count])
            if len(values) < count or any(v.startswith("--") for v in values):
                what = "one number" if count == 1 else "three numbers X Y Z"
                raise click.UsageError(f"{token} takes {what}")
            out.append(str(element))
    return out


def prepare_system_args(ctx: click.Context, args: Sequence[str]) -> list[str]:
    """:func:`expand_system_args`, kept in the context (shared with the command) so that
    :func:`system_from_options` knows the order of the --joint and --pto options."""
    expanded = expand_system_args(list(args))
    ctx.meta[_ARGS_KEY] = expanded
    return expanded


class SystemCommand(Command):
    """A ``cummins`` command (:class:`cummins.cli.option_rules.Command`) whose system
    options attach to the --joint or --pto before them."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        return super().parse_args(ctx, prepare_system_args(ctx, args))


def system_options(func):
    """Add the options of the module docstring; the command receives ``system_options``
    (a dict for :func:`system_from_options`)."""
    decorators = [
        click.option(
            "--joint",
            "joints",
            type=(str, str, str),
            multiple=True,
            metavar="KIND BODY BODY",
            help="A joint: KIND is "
            + ", ".join(JOINT_KINDS)
            + " (WEC-Sim's rotational: revolute); the first BODY moves relative to the "
            "second (a body of the data: body1, "
            "its name in the file or its number; or ground), e.g. --joint translational "
            "body1 body2 --axis 0 0 1, --joint planar body2 ground (surge, heave, pitch "
            "free), --joint revolute body1 body2 --axis 0 1 0 --point 0 0 -8.9. "
            "Repeatable.",
        ),
        click.option(
            "--axis",
            "axes",
            type=(int, finite(), finite(), finite()),
            multiple=True,
            metavar="X Y Z",
            help="After a --joint: its sliding direction, hinge axis or the normal of its "
            "plane (default 0 0 1; 0 1 0 for planar and revolute). After a --pto between "
            "bodies: the direction it acts along.",
        ),
        click.option(
            "--point",
            "points",
            type=(int, finite("m"), finite("m"), finite("m")),
            multiple=True,
            metavar="X Y Z",
            help="After a --joint: a point of its axis, m, in the data's axes (required "
            "for revolute). After a --pto between bodies: where the relative translation "
            "is taken (default: the first body's reference point).",
        ),
        click.option(
            "--pto",
            "ptos",
            type=(str, str),
            multiple=True,
            metavar="A B",
            help="A power take-off on the relative motion of A and B: two DOFs "
            "(--pto body1__Heave body2__Heave; B may be ground) or two bodies with --axis "
            "(translation along it). Give --pto-damping (and --pto-stiffness) after it. "
            "A --pto-damping after a --joint makes a PTO on the joint's free motion.",
        ),
        click.option(
            "--pto-damping",
            "pto_damping",
            type=(int, non_negative()),
            multiple=True,
            metavar="C",
            help="Damping of the --pto or --joint before it: N s/m, N m s/rad (>= 0).",
        ),
        click.option(
            "--pto-stiffness",
            "pto_stiffness",
            type=(int, finite()),
            multiple=True,
            metavar="K",
            help="Stiffness of the --pto or --joint before it: N/m, N m/rad.",
        ),
        click.option(
            "--no-body-coupling",
            is_flag=True,
            help="Leave out the radiation coupling between bodies (cross-body A, B, A_inf, "
            "A(0) set to zero before the fit and the frequency-domain solve), as WEC-Sim does "
            "by default. Without it the physics is complete.",
        ),
    ]

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        names = ("joints", "axes", "points", "ptos", "pto_damping", "pto_stiffness")
        kwargs["system_options"] = {name: kwargs.pop(name) for name in names}
        kwargs["system_options"]["no_body_coupling"] = kwargs.pop("no_body_coupling")
        return func(*args, **kwargs)

    for decorator in reversed(decorators):
        wrapper = decorator(wrapper)
    return wrapper


def _is_dof(token: str) -> bool:
    name = split_dof(token)[1]
    return name in DOF_NAMES or (name.startswith("Mode") and name[4:].isdigit())


def system_from_options(options: dict, dofs: Sequence[str] = ()) -> MechanicalSystem | None:
    """The :class:`MechanicalSystem` of the command's options (None when none is given and
    no ``--dof`` selection either asks for one — the plain path).

    Raises
    ------
    click.BadParameter
        An option attached to no --joint or --pto, or to the wrong one (exit status 2);
        the system's own checks raise ArgumentError naming the option (exit status 2).
    """
    joints_given = list(options["joints"])
    ptos_given = list(options["ptos"])
    coupling = not options["no_body_coupling"]
    if not joints_given and not ptos_given and coupling:
        for option in ("axes", "points", "pto_damping", "pto_stiffness"):
            if options[option]:
                flag = "--" + option.replace("_", "-").replace("axes", "axis").replace(
                    "points", "point"
                )
                raise click.BadParameter(
                    "must follow a --joint or a --pto it belongs to", param_hint=flag
                )
        return None
    # the elements in the order written: their numbers are shared (expand_system_args)
    order = _element_order(joints_given, ptos_given)
    attached: dict[int, dict[str, object]] = {k: {} for k in range(1, len(order) + 1)}
    for option, values in (
        ("--axis", options["axes"]),
        ("--point", options["points"]),
        ("--pto-damping", options["pto_damping"]),
        ("--pto-stiffness", options["pto_stiffness"]),
    ):
        for value in values:
            k, rest = value[0], value[1:]
            if k not in attached:
                raise click.BadParameter(
                    "must follow the --joint or --pto it belongs to", param_hint=option
                )
            if option in attached[k]:
                raise click.BadParameter(f"given twice for {order[k - 1][1]}", param_hint=option)
            attached[k][option] = rest if len(rest) > 1 else rest[0]
    from cummins.mechanics.pto import PTO
    from cummins.mechanics.system import MechanicalSystem

    joints: list[Joint] = []
    ptos: list[PTO] = []
    for k, (kind, text, values) in enumerate(order, start=1):
        extra = attached[k]
        axis, point = extra.get("--axis"), extra.get("--point")
        damping = extra.get("--pto-damping")
        stiffness = extra.get("--pto-stiffness")
        if kind == "joint":
            joint = Joint(values[0], values[1], values[2], axis=axis, point=point, origin=text)
            joints.append(joint)
            if damping is not None or stiffness is not None:
                ptos.append(
                    PTO(
                        joint=str(len(joints)),
                        damping=damping or 0.0,
                        stiffness=stiffness or 0.0,
                        origin=f"{text} (its PTO)",
                    )
                )
            continue
        first, second = values
        if damping is None and stiffness is None:
            raise click.BadParameter(
                f"{text} needs --pto-damping C (and/or --pto-stiffness K) after it",
                param_hint="--pto",
            )
        terms = {"damping": damping or 0.0, "stiffness": stiffness or 0.0, "origin": text}
        if _is_dof(first):
            if axis is not None or point is not None:
                raise click.BadParameter(
                    f"{text} acts between two DOFs: --axis and --point apply to a PTO "
                    "between bodies",
                    param_hint="--axis",
                )
            ptos.append(PTO(dofs=(first, second), **terms))
        else:
            ptos.append(PTO(body=first, base=second, axis=axis, point=point, **terms))
    try:
        return MechanicalSystem(tuple(joints), tuple(ptos), tuple(dofs) if dofs else None, coupling)
    except ArgumentError as exc:
        raise click.BadParameter(str(exc)) from None


def _element_order(joints, ptos) -> list[tuple[str, str, tuple]]:
    """(kind, option text, values) of every --joint and --pto, in the order written (the
    order of click's parse, kept in the context's original arguments)."""
    ctx = click.get_current_context(silent=True)
    tokens = [] if ctx is None else _original_args(ctx)
    joint_iter, pto_iter = iter(joints), iter(ptos)
    out: list[tuple[str, str, tuple]] = []
    for token in tokens:
        if token == "--joint":
            values = next(joint_iter, None)
            if values is not None:
                out.append(("joint", "--joint " + " ".join(values), values))
        elif token == "--pto":
            values = next(pto_iter, None)
            if values is not None:
                out.append(("pto", "--pto " + " ".join(values), values))
    if len(out) != len(joints) + len(ptos):  # no context (called from Python): joints first
        out = [("joint", "--joint " + " ".join(v), v) for v in joints]
        out += [("pto", "--pto " + " ".join(v), v) for v in ptos]
    return out


_ARGS_KEY = "cummins.system_args"


def _original_args(ctx: click.Context) -> list[str]:
    return list(ctx.meta.get(_ARGS_KEY, ()))


def print_system(assembly) -> None:
    """What the system leaves free, what it holds, its PTOs and the body coupling."""
    from rich.markup import escape

    from cummins.cli.common import console
    from cummins.dofs import bodies

    system = assembly.system
    several = len(bodies(assembly.ds)) > 1  # the body coupling means nothing for one
    for joint in system.joints:
        if joint.point is not None and joint.kind != "revolute":
            console.print(
                escape(
                    f"note: {joint.where}: --point changes nothing: a {joint.kind} joint's "
                    "constraints are the same through every point (only a revolute joint's "
                    "hinge is placed by it)"
                )
            )
    if not several and not system.body_coupling:
        held_bodies = {split_dof(d)[0] for d in assembly.held} - set(bodies(assembly.ds))
        why = (
            f"only one body moves ({', '.join(sorted(map(str, held_bodies)))} held at zero)"
            if held_bodies - {None}
            else "the data hold one body"
        )
        console.print(
            f"note: --no-body-coupling changes nothing: {why}, no coupling between moving "
            "bodies to leave out"
        )
        if not system.joints and not system.ptos and not assembly.held:
            return
    if system.is_plain and not assembly.held:
        if several:
            console.print(system.coupling_note())
        return
    held = ""
    if assembly.held:
        listed = ", ".join(assembly.held[:6]) + (" …" if len(assembly.held) > 6 else "")
        held = f"; {len(assembly.held)} DOFs held at zero ({listed})"
    console.print(
        escape(
            f"system: {len(system.joints)} joints, {len(assembly.ptos)} PTOs; "
            f"{len(assembly.coordinates)} coordinates ({', '.join(assembly.coordinates)}){held}"
        )
    )
    for pto in assembly.ptos:
        console.print(
            escape(
                f"  {pto.name}: {pto.description}, damping {pto.damping:g}, "
                f"stiffness {pto.stiffness:g}"
            )
        )
    if assembly.preload:
        console.print(escape(f"  {assembly.preload}"))
    if several:
        console.print(system.coupling_note())


def print_pto_run(
    run, vessel, sea, ds, system, viscous_damping=None, *, regular=False, left_out=()
):
    """The PTOs of a run: the mean absorbed power (over the last whole wave periods of a
    regular-wave run, up to 10; over the run otherwise) beside that of the frequency-domain
    solution of the same equations with the data's A(ω), B(ω), F(ω) for the same wave
    components (``sea``; none for a wave record) and, in irregular waves, that of the same
    solution over the run's own record (:func:`_frequency_domain_power`); in regular waves
    also the steady amplitudes of the relative displacement and of the force (fitted over
    those periods). ``left_out``: the options of the run that the linear frequency domain
    leaves out (``--quadratic-damping``, ``--second-order``), said in the column and a
    note. Returns the frequency domain's mean power of each PTO, W, and its mean over the
    run's record (each None when there is none)."""
    import numpy as np
    from rich.table import Table

    from cummins.cli.common import console
    from cummins.display import power_text
    from cummins.timedomain.harmonics import harmonic_amplitude, last_periods

    t = run.time.values
    window = np.ones(t.size, bool)
    reference = record = None
    if sea is not None:
        times = None if regular else t
        reference, record = _frequency_domain_power(sea, ds, system, viscous_damping, times)
    if regular:
        omega = float(sea.omega[0])
        count = int(min(10, np.floor((t[-1] - t[0]) * omega / (2 * np.pi) + 1e-9)))
        window = last_periods(t, omega, 10)
    table = Table(title="PTOs" + (" (steady state)" if regular else ""))
    columns = ["PTO", "mean power"]
    if reference is not None:
        columns += ["linear frequency domain" if left_out else "frequency domain"]
    if record is not None:
        columns += ["frequency domain, this record"]
    if regular:
        columns += ["amplitude", "force amplitude"]
    for column in columns:
        table.add_column(column, justify="right")
    for k, pto in enumerate(vessel.ptos):
        power = float(run.pto_power.values[window, k].mean())
        row = [pto.name, power_text(power, digits=5)]
        if reference is not None:
            row += [power_text(reference[k], digits=5)]
        if record is not None:
            row += [power_text(record[k], digits=5)]
        if regular:
            periods = max(count, 1)
            delta = harmonic_amplitude(t, run.pto_displacement.values[:, k], omega, periods)
            force = harmonic_amplitude(t, run.pto_force.values[:, k], omega, periods)
            row += [
                f"{abs(delta):.5g} {pto.units['displacement']}",
                f"{abs(force):.5g} {pto.units['force']}",
            ]
        table.add_row(*row)
    console.print(table)
    if reference is not None and left_out:
        console.print(
            f"note: the frequency domain leaves out {' and '.join(left_out)}: the run's "
            f"power differs from it by {'their' if len(left_out) > 1 else 'its'} effect, "
            "not by an error"
        )
    if record is not None:
        _say_record(record, reference, vessel.ptos, float(t[-1] - t[0]))
    return reference, record


#: The relative gap between the frequency domain's mean power over the run's record and
#: over all records of its components above which :func:`_say_record` says why.
RECORD_GAP = 0.02


def _say_record(record, reference, ptos, duration: float) -> None:
    """One note when the frequency domain's power over the run's record is more than
    :data:`RECORD_GAP` off its mean over all records: that gap is the record's, not the
    model's."""
    import numpy as np
    from rich.markup import escape

    from cummins.cli.common import console
    from cummins.display import power_text

    gap = np.abs(np.asarray(record) / np.where(reference != 0, reference, 1.0) - 1.0)
    k = int(np.argmax(gap))
    if reference[k] == 0 or gap[k] <= RECORD_GAP:
        return
    side = "below" if record[k] < reference[k] else "above"
    console.print(
        escape(
            f"note: over this {duration:g} s record the frequency-domain solution itself "
            f"absorbs {power_text(record[k], digits=4)} ({ptos[k].name}), "
            f"{100 * gap[k]:.1f} % {side} its mean over all records of these wave "
            f"components ({power_text(reference[k], digits=4)}): components of different "
            "frequencies do not average out over a finite record; the run's mean power is "
            "to be compared with the record's (a longer --duration narrows the gap)"
        ),
        highlight=False,
    )


def _frequency_domain_power(sea, ds, system, viscous_damping=None, times=None):
    """Mean absorbed power of each PTO in the frequency domain, W: Σ_k ½ c ω_k² |Δ̂_k|² a_k²
    over the wave components (ω_k, β_k, a_k) of ``sea`` (one for a regular wave), Δ̂ the
    data's frequency-domain solution per unit amplitude — the mean of the products of
    components of different frequencies vanishes over a long record (Falnes (2002)). With
    ``times`` (s), also the mean over them of the power (kΔ + cΔ̇)Δ̇ of the same solution
    on the run's own record, Δ(t) = Re Σ_k Δ̂_k a_k e^{i(ω_k t + φ_k)} (the waves of
    ``sea``, :meth:`~cummins.seakeeping.waves.WaveComponents.elevation`): over a finite
    record those products do not vanish (components of random frequencies: 8 % in
    1200 s of a JONSWAP sea), and a linear time-domain run of the same components
    follows this one to its radiation model's error. Returns (mean, record); (None, None)
    when it cannot be computed (a component outside the data), record None without
    ``times``."""
    import numpy as np

    from cummins.errors import CumminsError
    from cummins.seakeeping.frequency_domain import motion_rao, pto_rao
    from cummins.seakeeping.waves import harmonic_sum

    omegas, at_omega = np.unique(np.asarray(sea.omega, float), return_inverse=True)
    directions, at_direction = np.unique(np.asarray(sea.direction, float), return_inverse=True)
    try:
        rao = motion_rao(ds, omegas, directions, viscous_damping=viscous_damping, system=system)
        ptos = pto_rao(rao, ds, system)
    except CumminsError:
        return None, None
    at = (at_omega.ravel(), at_direction.ravel())
    power = ptos.pto_power.transpose("omega", "wave_direction", "pto").values[at]
    amplitude = np.asarray(sea.amplitude, float)
    mean = (power * amplitude[:, None] ** 2).sum(axis=0)  # (pto,)
    if times is None:
        return mean, None
    c = (amplitude * np.exp(1j * np.asarray(sea.phase, float)))[:, None]
    omega = np.asarray(sea.omega, float)
    delta = ptos.pto_displacement.transpose("omega", "wave_direction", "pto").values[at] * c
    force = ptos.pto_force.transpose("omega", "wave_direction", "pto").values[at] * c
    t = np.asarray(times, float)
    rate = harmonic_sum(t, omega, 1j * omega[:, None] * delta).reshape(t.size, -1)
    on_pto = harmonic_sum(t, omega, force).reshape(t.size, -1)  # on the PTO's first body
    return mean, (-on_pto * rate).mean(axis=0)
