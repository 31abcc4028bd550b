"""Options that contradict each other, refused before a command runs (exit status 2,
naming both options) instead of running with one of them ignored: a single-valued option
given twice (:class:`Command`), an option that applies only with another
(:func:`option_rules`), two that exclude each other, a repeatable option naming one DOF
twice (:func:`refuse_repeated`); directions beyond one turn are refused by their type
(:func:`cummins.cli.common.heading_degrees`)."""

from __future__ import annotations

import functools

import click


class Command(click.Command):
    """A ``cummins`` command: a single-valued option given twice is a usage error (click
    would keep the last value and drop the first without a word)."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        _refuse_repeated_options(self, ctx, args)
        return super().parse_args(ctx, args)


def _refuse_repeated_options(command: click.Command, ctx: click.Context, args: list[str]):
    single = {
        opt: param
        for param in command.params
        if isinstance(param, click.Option) and not param.multiple and not param.count
        for opt in (*param.opts, *param.secondary_opts)
    }
    seen: dict[str, list[str]] = {}
    for k, token in enumerate(args):
        if token == "--":
            break
        name, equals, value = token.partition("=") if token.startswith("--") else (token, "", "")
        param = single.get(name)
        if param is None:
            continue
        if not equals and not param.is_flag and param.nargs == 1 and k + 1 < len(args):
            value = args[k + 1]
        given = seen.setdefault(param.name or name, [])
        given.append(f"{name} {value}".strip())
        if len(given) == 2:
            raise click.UsageError(
                f"{given[0]} and {given[1]}: {max(param.opts, key=len)} takes one value; "
                "give it once",
                ctx=ctx,
            )


def option_given(name: str) -> bool:
    """Whether the option (its Python name) was given on the command line or in the
    environment, not left at its default."""
    from click.core import ParameterSource

    context = click.get_current_context()
    source = context.get_parameter_source(name)
    return source in (ParameterSource.COMMANDLINE, ParameterSource.ENVIRONMENT)


def option_label(name: str) -> str:
    """The longest flag of the option with Python name ``name`` (``--wave-period``)."""
    context = click.get_current_context()
    for param in context.command.params:
        if param.name == name:
            return max(param.opts, key=len) if isinstance(param, click.Option) else name
    return name


def option_rules(
    *,
    needs: dict[str, str | tuple[str, object]] | None = None,
    excludes: tuple[tuple[str, str], ...] = (),
):
    """Refuse options that contradict each other before the command runs (a usage error,
    exit status 2, naming both options), instead of running with one of them ignored.

    Parameters
    ----------
    needs
        ``{option: condition}``: the option applies only when the condition holds — the
        name of another option that must be given (a flag set: ``"regular"``), or
        ``(name, value)``: that option must have that value (its default counts), or
        ``(name, predicate, text)``: ``predicate(value)`` must hold (``text`` says what).
    excludes
        Pairs of options that cannot be given together.
    """
    needs = dict(needs or {})

    def decorate(func):
        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            context = click.get_current_context()
            params = context.params
            for first, second in excludes:
                if option_given(first) and option_given(second) and params.get(first) is not False:
                    raise click.UsageError(
                        f"{option_label(first)} and {option_label(second)} exclude each "
                        "other: give one of them",
                        ctx=context,
                    )
            for name, condition in needs.items():
                if not option_given(name):
                    continue
                if isinstance(condition, str):
                    ok = option_given(condition) and params.get(condition) is not False
                    what = option_label(condition)
                elif len(condition) == 2:
                    other, value = condition
                    ok = params.get(other) == value
                    what = f"{option_label(other)} {value}"
                else:
                    other, predicate, text = condition
                    ok = bool(predicate(params.get(other)))
                    what = f"{option_label(other)} {text}"
                if not ok:
                    raise click.UsageError(
                        f"{option_label(name)} applies only with {what}: without it, it "
                        "would be ignored",
                        ctx=context,
                    )
            return func(*args, **kwargs)

        return wrapper

    return decorate


def refuse_repeated(values, option: str, key=lambda v: v, what: str = "DOF") -> None:
    """A usage error when a repeatable option names one thing twice (a DOF, a pair of
    DOFs): ``--viscous-damping Roll 5e8 --viscous-damping Roll 1e9`` would otherwise have
    to guess whether the values add up or the last one counts."""
    seen: set = set()
    for value in values:
        k = key(value)
        if k in seen:
            shown = " ".join(str(x) for x in (k if isinstance(k, tuple) else (k,)))
            raise click.BadParameter(
                f"{shown} is given twice: give one value per {what}", param_hint=option
            )
        seen.add(k)


def unique_values(ctx: click.Context, param: click.Parameter, values):
    """A click ``callback`` of a repeatable option naming DOFs (``--dof``): the same one
    twice is refused in one line (:func:`refuse_repeated`)."""
    refuse_repeated(values, param.opts[0] if param.opts else str(param.name))
    return values
