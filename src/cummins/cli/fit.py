"""``cummins fit``: state-space models of the fluid memory of every significant coupling."""

from __future__ import annotations

import json
import sys
import time
from dataclasses import replace
from pathlib import Path

import click
from rich.markup import escape
from rich.table import Table

from cummins.cli.common import (
    Number,
    check_dof_selection,
    console,
    counted_progress,
    force_option,
    non_negative,
    positive,
    prepare_outputs,
    read_hydrodb,
    read_options,
    reports_errors,
    select_body,
    select_speed,
    speed_option,
    stage_progress,
)
from cummins.cli.option_rules import refuse_repeated
from cummins.cli.system_options import SystemCommand, system_from_options, system_options
from cummins.dofs import split_dof
from cummins.files import write_text


@click.command(name="fit", cls=SystemCommand)
@click.argument("path", type=click.Path(exists=True))
@read_options
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    required=True,
    help="NetCDF file for the model (A, B, C, D, A-infinity, per-coupling metrics).",
)
@click.option(
    "--method",
    type=click.Choice(["vf", "fd", "realization", "prony"]),
    default="vf",
    show_default=True,
    help="vf: the coupled DOFs share their poles (vector fitting of each block, passive as "
    "fitted); fd: one model per coupling (Levy, Sanathanan-Koerner, nonlinear); "
    "realization: Kung/ERA on K(t); prony: Prony on K(t).",
)
@click.option(
    "--r2",
    type=Number(0.0, 1.0, min_open=True, max_open=True),
    default=0.99,
    show_default=True,
    help="Target R-squared of A(w) and B(w) for the diagonal terms.",
)
@click.option(
    "--r2-coupling",
    type=Number(0.0, 1.0, min_open=True, max_open=True),
    default=0.97,
    show_default=True,
    help="Target for the off-diagonal couplings.",
)
@click.option(
    "--r2-kernel",
    type=Number(0.0, 1.0, min_open=True, max_open=True),
    default=0.9,
    show_default=True,
    help="Target R-squared of K(t) of the diagonal terms against the data's K(t), whose "
    "damping continues beyond the last frequency as its fitted tail: the model must "
    "decay there as the data's damping does.",
)
@click.option(
    "--max-order",
    type=click.IntRange(1, 50),
    default=None,
    help="Highest order tried: common poles of a block (vf, default 20), the order of a "
    "coupling otherwise (default 10).",
)
@click.option(
    "--order",
    "orders",
    type=(str, str, click.IntRange(1, 50)),
    multiple=True,
    metavar="DOF DOF N",
    help="Fix the order of a coupling, e.g. --order Heave Pitch 4 (repeatable); with vf "
    "the number of poles the block of these DOFs shares.",
)
@click.option(
    "--added-mass-inf",
    type=click.Choice(["auto", "data", "fit", "ogilvie"]),
    default="auto",
    show_default=True,
    help="A-infinity: the data row (auto when present; estimated for the DOFs whose "
    "added mass is far from causal with it when their motions miss the target), the data "
    "row everywhere (data), a joint estimate (fit), or Ogilvie's relation.",
)
@click.option(
    "--omega-min", type=non_negative("rad/s"), default=None, metavar="RAD/S", help="Fitting range."
)
@click.option(
    "--omega-max", type=positive("rad/s"), default=None, metavar="RAD/S", help="Fitting range."
)
@click.option(
    "--keep-suspect",
    is_flag=True,
    help="Fit the suspect frequencies too (irregular frequencies, spikes).",
)
@click.option(
    "--threshold",
    type=Number(0.0, 1.0, max_open=True),
    default=0.01,
    show_default=True,
    help="Couplings below this fraction of the diagonal terms are left out.",
)
@click.option(
    "--json",
    "json_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write a summary as JSON (couplings with order, R2, stable, passive).",
)
@click.option(
    "--plot",
    "plot_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Write one PNG per DOF, fit_<DOF>.png, a row per coupling of that DOF (A, B, |K|, "
    "K(t): data against the model).",
)
@click.option(
    "--openfast",
    type=click.Path(dir_okay=False),
    default=None,
    help="Also write the model as an OpenFAST HydroDyn .ss file.",
)
@click.option(
    "--mss",
    "mss_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Also write an MSS vesselABC .mat (Fossen axes).",
)
@speed_option()
@click.option(
    "--passive/--no-passive",
    default=True,
    show_default=True,
    help="Make the MIMO model passive (K + K^H >= 0 at every frequency) by the smallest "
    "data-weighted change of the residues. Diagonal models are positive real either way.",
)
@click.option(
    "--reciprocity",
    type=click.Choice(["auto", "average", "as-given"]),
    default="auto",
    show_default=True,
    help="Data with A_ij != A_ji or B_ij != B_ji (zero speed): auto fits a block's couplings "
    "as given (K_ij and K_ji each, passive as K + K^H >= 0) where the data's reciprocal "
    "part alone misses the motion target, else their average; average always; as-given "
    "every pair that is not reciprocal (vf).",
)
@click.option(
    "--refine-motions/--no-refine-motions",
    default=None,
    help="A block whose motion RAOs miss their aim after the order search has its "
    "residues refined on the motions themselves, passive at every step (vf). Default: "
    "when the fit's motions miss the target, a number of poles that cannot reach it "
    "given up early (WEC-Sim's RM3 3.7 % -> 0.4 % of the peak); --refine-motions: "
    "whenever they miss the aim, every number of poles enforced to the end (slower); "
    "--no-refine-motions: never.",
)
@click.option(
    "--body",
    metavar="N|NAME",
    default=None,
    help="Of several bodies, fit only this one (1-based number or name), e.g. for --mss.",
)
@click.option(
    "--dof",
    "dofs",
    multiple=True,
    metavar="DOF",
    help="Fit only the DOFs that move (repeatable), the others held at zero, e.g. --dof "
    "body1__Heave --dof body2__Heave; with joints, the motions the fit aims at.",
)
@system_options
@force_option()
@reports_errors
def fit_command(
    path,
    format_,
    rho,
    g,
    ulen,
    output,
    method,
    r2,
    r2_coupling,
    r2_kernel,
    max_order,
    orders,
    added_mass_inf,
    omega_min,
    omega_max,
    keep_suspect,
    threshold,
    json_path,
    plot_dir,
    openfast,
    mss_path,
    speed,
    passive,
    reciprocity,
    refine_motions,
    body,
    dofs,
    system_options,
    force,
):
    """Identify stable, passive state-space models of the fluid memory, every coupling.

    \b
    By default (vf) the DOFs that radiate into each other (surge-heave-pitch and
    sway-roll-yaw of a ship, all DOFs of interacting bodies) form a block whose
    couplings share their poles: vector fitting (Gustavsen & Semlyen 1999), at the
    smallest number of poles whose R-squared of A(w) and B(w) reaches the targets
    and whose motion RAOs (with inertia and restoring in the data) are within 1 %
    of the data's; each block is made passive as fitted. With fd each coupling
    K_ij(s) gets its own model. Data that are not reciprocal (A_ij != A_ji) beyond
    what the motions allow have those couplings fitted as given, K_ij and K_ji each
    (--reciprocity). Negligible couplings and suspect frequencies are
    left out and reported. The MIMO model (A, B, C, D = 0) and A-infinity go to
    OUTPUT; a fit that misses a target it should reach exits with status 3.

    \b
    Examples:
      cummins fit tanker.1 -o tanker_model.nc --json fit.json --plot fit-plots
      cummins fit input.re7 -o supply_model.nc --method realization --max-order 12
      cummins fit tanker.1 -o model.nc --order Heave Pitch 4 --openfast tanker.ss

    \b
    Bodies joined (--joint, --pto, --dof, --no-body-coupling, as simulate and rao take
    them): the model holds the DOFs that move and aims at the motions of the joined
    system; give simulate the model file with the same options, e.g.
      cummins fit oswec.out --rho 1000 --mass 127000 --mass 999 ... --joint fixed body2
        ground --joint revolute body1 body2 --axis 0 1 0 --point 0 0 -8.9
        --pto-damping 1.2e5 --no-body-coupling -o flap_model.nc
    """
    from cummins.radiation.fit import fit_radiation

    refuse_repeated(orders, "--order", key=lambda o: tuple(sorted(o[:2])), what="coupling")
    above = [o for o in orders if max_order is not None and o[2] > max_order]
    if above:
        a, b, n = above[0]
        raise click.UsageError(
            f"--order {a} {b} {n} is above --max-order {max_order}: one of the two would be "
            "ignored; raise --max-order or lower the order"
        )
    prepare_outputs(output, json_path, openfast, mss_path, force=force, folders=[plot_dir])
    ds = select_speed(read_hydrodb(path, format_, rho, g, ulen), speed)
    if body is not None:
        ds = select_body(ds, body)
    ds, joined = joined_data(ds, system_from_options(system_options, dofs), dofs)
    labels = [str(d) for d in ds.influenced_dof.values]
    check_model_outputs(labels, mss_path=mss_path, openfast=openfast)
    fixed = {}
    for a, b, n in orders:
        for label in (a, b):
            if label not in labels:
                raise click.BadParameter(
                    f"unknown DOF {label!r}; use {', '.join(labels)}", param_hint="--order"
                )
        fixed[(labels.index(a), labels.index(b))] = n
    start = time.perf_counter()
    from cummins.radiation.retardation import significant_couplings

    with counted_progress("couplings", len(significant_couplings(ds, threshold))) as progress:
        model = fit_radiation(
            ds,
            method=method,
            r2=r2,
            r2_coupling=r2_coupling,
            r2_kernel=r2_kernel,
            max_order=max_order,
            orders=fixed or None,
            threshold=threshold,
            added_mass_inf=added_mass_inf,
            omega_min=omega_min,
            omega_max=omega_max,
            exclude_suspect=not keep_suspect,
            passivity="mimo" if passive else "diagonal",
            reciprocity=reciprocity,
            refine_motions=refine_motions,
            progress=progress,
            joined=joined,
        )
    elapsed = time.perf_counter() - start
    console.print(fit_table(model))
    for line in fit_notes(model):
        console.print(escape(line), highlight=False)
    summary = fit_summary(model, elapsed)
    console.print(
        f"total order {summary['total_order']}, every model stable: {summary['mimo_stable']}, "
        f"MIMO passive: {summary['mimo_passive']}, {elapsed:.2f} s"
    )
    error = model.attrs.get("motion_error")
    if error is not None:  # the data hold the inertia and the restoring
        target = model.attrs.get("motion_target")
        console.print(
            f"motion-RAO error {float(error):.2%} of the peak"
            + (f" (target {float(target):.2%})" if target is not None else "")
            + (f", on {model.attrs['motions_of']}" if model.attrs.get("motions_of") else "")
        )
    coordinates = model.attrs.get("coordinate_r2")
    if coordinates:  # what the joined system holds of the memory: Tᵀ K T
        console.print(
            "joined coordinates: "
            + "; ".join(f"{q} R² of A {a:.4f}, of B {b:.4f}" for q, (a, b) in coordinates.items())
        )
    for note in model.attrs.get("data_notes", []):
        console.print(f"[yellow]data:[/yellow] {escape(note)}")
    negligible = [c for c in model.attrs.get("negligible_couplings", []) if "-" in c]
    if negligible:
        listed = ", ".join(negligible[:NEGLIGIBLE_LISTED])
        more = len(negligible) - NEGLIGIBLE_LISTED
        if more > 0:
            listed += f" and {more} more (the model file's attrs: negligible_couplings)"
        console.print(
            f"{len(negligible)} negligible couplings (< {threshold:g} of the diagonal terms): "
            + listed
        )
    # the file given, not the solver file its attrs name (a converted NetCDF with moorings
    # or inertia keeps the solver's source_file): what simulate/rao read for this model
    model = replace(model, attrs={**model.attrs, "data_file": str(Path(path).resolve())})
    model.save(output, force=force)
    console.print(f"wrote {output}")
    if json_path:
        write_text(json_path, json.dumps(summary, indent=2) + "\n")
        console.print(f"wrote {json_path}")
    if openfast:
        from cummins.io.openfast import write_openfast_ss

        write_openfast_ss(model, openfast, force=force)
        console.print(f"wrote {openfast}: {openfast_states_note(model, openfast)}")
    if mss_path:
        from cummins.cli.pipeline import write_model_mss_abc

        write_model_mss_abc(model, ds, Path(mss_path), force=force)
        console.print(f"wrote {mss_path} (Fossen axes, about the data's reference point)")
    if plot_dir:
        from cummins.cli.pipeline import write_fit_plots

        with stage_progress("drawing the fit of every DOF's couplings") as say:
            write_fit_plots(model, ds, Path(plot_dir), force=force, say=console.print)
            say("done")
    failures = model.attrs.get("failures", [])
    for failure in failures:
        console.print(f"[bold red]failure:[/bold red] {escape(failure)}", highlight=False)
    remedy = inconsistent_data_remedy(failures, model.attrs.get("data_notes", []), omega_max)
    if remedy:
        console.print(f"[yellow]note:[/yellow] {escape(remedy)}", highlight=False)
    speed_value = float(ds.coords["forward_speed"]) if "forward_speed" in ds.coords else 0.0
    if failures and speed_value:
        console.print(
            f"note: at {speed_value:g} m/s the data hold the speed terms (U·A∞ damping, the "
            "U²/ω² radiation restoring of pitch and yaw, the antisymmetric U K¹), which no "
            "causal memory follows; this plain fit of the data at speed fits them as memory "
            "and averages the antisymmetric part away. With zero speed in the same file, "
            "the memory is built with the speed terms kept apart: "
            "cummins simulate DATA --speed U (Python: "
            "cummins.radiation.speed.vessel_at_speed, fit_per_speed)",
            highlight=False,
        )
    missed = any(f.startswith("motion error") for f in failures)
    if missed and refine_motions is not True and not model.attrs.get("statically_unstable"):
        console.print(
            "hint: --refine-motions refines the blocks that miss on the motion RAOs "
            "themselves at every number of poles to the end, passive at every step "
            "(slower than the default's refinement, which gives up a number of poles "
            "whose steps stay above the target; --no-refine-motions skips it); it keeps "
            "a refined block only where the motions come nearer",
            highlight=False,
        )
    if failures:
        sys.exit(FIT_FAILED)


#: Exit status of ``cummins fit`` when the model was written but misses a target
#: (``model.attrs["failures"]``: not passive, a coupling degraded, motion error, R² of
#: K(t), damping beyond the data).
FIT_FAILED = 3


def openfast_states_note(model, path) -> str:
    """What the ``.ss`` holds against the model: its states, and why they are more (one
    model per coupling, grouped by radiating DOF) and which DOFs have none (enabled, as
    HydroDyn requires of every DOF, with no memory)."""
    from cummins.io.openfast import read_openfast_ss

    content = read_openfast_ss(path)
    text = f"{content.n_states} states"
    if content.n_states > model.total_order:
        text += (
            f" (the model has {model.total_order}: HydroDyn's format stores one model per "
            "coupling, grouped by the radiating DOF, so the states a common-pole block shares "
            "are repeated for each of its couplings)"
        )
    empty = [model.dofs[k] for k, count in enumerate(content.states_per_dof) if count == 0]
    if empty:
        text += (
            f"; no states for {', '.join(empty)}: no fluid memory (flagged enabled, as "
            "HydroDyn requires of every DOF)"
        )
    return text + reference_point_clause(model.attrs)


def reference_point_clause(attrs) -> str:
    """For a HydroDyn file (z-up) of a model about a point other than the origin: the
    point, which PtfmRefxt/yt/zt must give and the .1/.hst share ("" at the origin)."""
    import numpy as np

    point = np.asarray(attrs.get("reference_point", np.zeros(3)), dtype=float).reshape(-1, 3)
    if attrs.get("axis_convention") == "z-down":  # the file is in z-up axes
        point = point * np.array([1.0, -1.0, -1.0])
    if not np.any(point != 0):
        return ""
    listed = "; ".join(str(np.round(p, 6).tolist()) for p in point + 0.0)
    return (
        f"; moments about {listed} m (z-up), the data's reference point: HydroDyn's "
        "PtfmRefxt/yt/zt must give it, and its .1/.hst be about the same point (cummins "
        "convert DATA x.1 prints them; for the origin, convert with --reference-point "
        "0 0 0 and fit that .1)"
    )


def check_model_outputs(labels, *, mss_path=None, openfast=None) -> None:
    """Before the fit: the model files asked for can hold a model of these DOFs (an MSS
    vesselABC one body of six, HydroDyn six per body)."""
    from cummins.hydrodb import DOF_NAMES

    n = len(labels)
    several = len({label.rpartition("__")[0] for label in labels}) > 1
    if mss_path and [label.rpartition("__")[2] for label in labels] != list(DOF_NAMES):
        raise click.BadParameter(
            f"an MSS vesselABC holds one body with six DOFs; the data have {n} DOFs"
            + (": fit one body with --body N" if several else ""),
            param_hint="--mss",
        )
    if openfast and (n == 0 or n % 6):
        raise click.BadParameter(
            f"HydroDyn needs all six DOFs of each body; the data have {n} DOFs",
            param_hint="--openfast",
        )


def joined_data(ds, system, dofs):
    """The data of the DOFs that move and the mechanics the fit aims at
    (:class:`~cummins.radiation.fit.motion.JoinedMotion`, None for free bodies): the
    ``--dof`` selection, or the system of ``--joint``/``--pto``/``--no-body-coupling``
    applied (:func:`cummins.mechanics.assemble`, printed)."""
    check_dof_selection(ds, dofs)
    if system is None:
        if not dofs:
            return ds, None
        from cummins.hydrodb import select_dofs

        return select_dofs(ds, list(dofs)), None
    if float(ds.coords.get("forward_speed", 0.0)):
        raise click.UsageError(
            "joints, PTOs and --no-body-coupling are for bodies at zero speed: leave --speed out"
        )
    from cummins.cli.system_options import print_system
    from cummins.mechanics import assemble

    assembly = assemble(ds, system)
    print_system(assembly)
    return assembly.ds, assembly.joined_motion()


def fit_summary(model, elapsed: float) -> dict:
    """The ``--json`` summary: couplings (1-based i, j), total order, stability, passivity."""
    from cummins.radiation.passivity import is_passive

    couplings = []
    for k in model.modelled:
        m = k.metrics
        couplings.append(
            {
                "i": k.influenced + 1,
                "j": k.radiating + 1,
                "order": int(m.get("common_poles", k.order)),
                "r2_added_mass": float(m["r2_added_mass"]),
                "r2_damping": float(m["r2_damping"]),
                "r2_kernel": None if m.get("r2_kernel") is None else float(m["r2_kernel"]),
                "stable": bool(m["stable"]),
                "passive": None if m.get("passive") is None else bool(m["passive"]),
            }
        )
    blocks = [
        {
            "dofs": [d + 1 for d in block.dofs],
            "order": block.order,
            "common_poles": int(next(iter(block.metrics.values()), {}).get("common_poles", 0)),
        }
        for block in model.blocks
    ]
    return {
        "couplings": couplings,
        "blocks": blocks,
        "total_order": model.total_order,
        "mimo_stable": model.is_stable(),
        "mimo_passive": is_passive(model),
        "motion_error": model.attrs.get("motion_error"),
        "failures": list(model.attrs.get("failures", [])),
        "elapsed_s": elapsed,
        # a fit for joined bodies: the R² of A and B of each free coordinate (Tᵀ K T)
        **(
            {"coordinate_r2": model.attrs["coordinate_r2"]}
            if model.attrs.get("coordinate_r2")
            else {}
        ),
    }


#: The negligible couplings ``cummins fit`` names (a multi-body model has hundreds).
NEGLIGIBLE_LISTED = 12


def fit_table(model) -> Table:
    """Per-coupling summary printed by ``cummins fit``: narrow enough for an 80-column
    terminal (the DOFs of several bodies named short: :func:`table_label`); each
    coupling's note is numbered in the last column and printed below the table
    (:func:`fit_notes`). The poles of a pair of a common-pole block are those its DOFs
    share (the block's states are in the notes), of a per-coupling model its order."""
    from rich import box

    table = Table(
        title=f"fluid-memory model ({model.attrs.get('method')}; A∞: "
        f"{model.attrs.get('added_mass_inf_method')})",
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        collapse_padding=True,
    )
    for column in ("coupling", "poles", "R² A", "R² B", "R² K(t)", "stable", "passive", "note"):
        left = column == "coupling"
        table.add_column(column, justify="left" if left else "right", no_wrap=left)
    numbers: dict[str, int] = {}
    for k in model.modelled:
        if k.influenced > k.radiating and not k.metrics.get("as_given"):
            continue  # the same model as (j, i); a pair fitted as given has two
        m = k.metrics
        a, b = table_label(model.dofs[k.influenced]), table_label(model.dofs[k.radiating])
        passive = m.get("passive")
        note = short_note(k.note)
        if note and note not in numbers:
            numbers[note] = len(numbers) + 1
        table.add_row(
            a if a == b else f"{a}-{b}",
            str(m.get("common_poles", k.order)),
            f"{m['r2_added_mass']:.4f}",
            f"{m['r2_damping']:.4f}",
            "—" if m.get("r2_kernel") is None else f"{m['r2_kernel']:.4f}",
            "yes" if m["stable"] else "NO",
            "—" if passive is None else ("yes" if passive else "NO"),
            f"[{numbers[note]}]" if note else "",
        )
    return table


def table_label(dof: str) -> str:
    """A DOF as the fit table names it: ``body2__Pitch`` as ``b2.Pitch``, so that both
    DOFs of a coupling between bodies fit an 80-column terminal (the notes below the
    table and the model file keep the full names); a single body's DOFs as they are."""
    body, name = split_dof(dof)
    if body is None:
        return name
    if body.startswith("body") and body[4:].isdigit():
        body = "b" + body[4:]
    return f"{body}.{name}"


def inconsistent_data_remedy(failures, data_notes, omega_max=None) -> str | None:
    """For failed DOFs whose data are not causal above some frequency (an irregular
    frequency: the data notes' "A(ω) departs from what B(ω) implies from X rad/s", a
    Kramers–Kronig test, Ogilvie (1964)), the --omega-max that leaves that part out."""
    import re

    starts = {}
    for note in data_notes:
        found = re.match(r"(\S+): A\(ω\) departs .*; fitted below ([0-9.eE+-]+) rad/s", note)
        if found:
            starts[found.group(1)] = float(found.group(2))
    failed = {f.split(":", 1)[0] for f in failures}
    named = {dof: w for dof, w in starts.items() if dof in failed}
    if not named or (omega_max is not None and omega_max <= min(named.values())):
        return None
    w = min(named.values())
    dofs = ", ".join(sorted(named, key=named.get))
    return (
        f"{dofs}: the data are not causal from {w:.4g} rad/s (an irregular frequency: "
        f"cummins check): no causal model follows them there, and the R² counts them; "
        f"--omega-max {w:.4g} fits the consistent part only"
    )


def fit_notes(model) -> list[str]:
    """The numbered notes of :func:`fit_table`, in the same order (a note shared by the
    pairs of a block once), then one line per common-pole block."""
    out: list[str] = []
    seen: set[str] = set()
    owner = {d: "-".join(model.dofs[x] for x in b.dofs) for b in model.blocks for d in b.dofs}
    for k in model.modelled:
        if k.influenced > k.radiating and not k.metrics.get("as_given"):
            continue
        note = short_note(k.note)
        if note and note not in seen:
            seen.add(note)
            a, b = model.dofs[k.influenced], model.dofs[k.radiating]
            name = owner.get(k.influenced) or (a if a == b else f"{a}-{b}")
            out.append(f"[{len(out) + 1}] {name}: {note}")
    for block in model.blocks:
        poles = next(iter(block.metrics.values()), {}).get("common_poles")
        names = "-".join(model.dofs[d] for d in block.dofs)
        shared = f", {poles} common poles" if poles else ""
        out.append(f"{names}: one block of {block.order} states{shared}")
    return out


#: Steps every fit may take; the table leaves them out (the model file keeps the note).
ROUTINE_STEPS = (
    "refined by nonlinear least squares",
    "Steiglitz–McBride refinement",
    "zero at s = 0 imposed",
    "started from the pruned poles",
)


def short_note(note: str) -> str:
    """The parts of a coupling's note worth a line in the table."""
    parts = [p.strip() for p in note.split(";") if p.strip()]
    kept = [
        p.replace("residues adjusted for MIMO passivity: ", "MIMO passivity: ")
        for p in parts
        if not p.startswith(ROUTINE_STEPS)
    ]
    siso = [p for p in kept if "passivity" in p and "MIMO" not in p]
    if siso and not any(p.startswith("not passive") for p in kept):
        kept = [p for p in kept if p not in siso] + ["passivity enforced"]
    return "; ".join(kept)
