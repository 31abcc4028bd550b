"""The ``cummins`` command line.

Every command prints what it did; errors are reported in one line naming the file, line,
option or quantity at fault, without a traceback: exit status 2 for a bad option or
argument (a value out of range, an output that exists without --force, a path under a
file), 1 for data that cannot be used (and for `check`, data that fail it). Warnings are
shown once each as one-line notes.
"""

from __future__ import annotations

import click

from cummins._version import __version__
from cummins.cli.batch import batch_command
from cummins.cli.bem import bem_command
from cummins.cli.check import check_command
from cummins.cli.convert import convert_command
from cummins.cli.demo import demo_command
from cummins.cli.dp import dp_demo_command
from cummins.cli.fit import fit_command
from cummins.cli.fit_excitation import fit_excitation_command
from cummins.cli.info import info_command
from cummins.cli.kernel import kernel_command
from cummins.cli.lfmodel import lf_model_command
from cummins.cli.rao import rao_command
from cummins.cli.reduce import reduce_command
from cummins.cli.report import report_command
from cummins.cli.simulate import simulate_command
from cummins.cli.sysid import identify_damping_command


@click.group(
    context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100},
)
@click.version_option(__version__, "--version", "-V", prog_name="cummins")
def main() -> None:
    """cummins: from frequency-domain hydrodynamics to time-domain vessel models.

    \b
    The pipeline, one command per stage:
      cummins info FILE        what is in a solver output file (or folder)
      cummins check FILE       is the data physically usable? (symmetry, B >= 0, A-inf, decay)
      cummins convert IN OUT   write canonical NetCDF (.nc) or an MSS vessel struct (.mat)
      cummins bem MESH         compute a database with Capytaine (pip install cummins[bem])
      cummins kernel FILE      retardation functions K(t), A-infinity, causality diagnostics
      cummins fit FILE         stable, passive state-space models of the fluid memory
      cummins fit-excitation FILE
                               causal state-space models of the wave excitation (OpenFAST)
      cummins reduce MODEL     fewer states by balanced truncation, passive again
      cummins rao DATA         coupled motion RAOs, frequency domain (the reference)
      cummins simulate DATA    the vessel in regular or irregular waves, time domain
      cummins identify-damping RECORDS --model DATA
                               viscous (roll) damping from motion records or decays
      cummins dp-demo -o DIR   the nonlinear 6-DOF DP model (Smogeli et al., 2004) on the S-175
      cummins lf-model DATA    constant-coefficient manoeuvring model (Ross, Perez & Fossen, 2006)
      cummins batch STUDY      many cases (headings x sea states) on Dask; operability
      cummins report FILE      a self-contained HTML page of a data, model, run or results file
      cummins demo             run all of it on a bundled real vessel (WAMIT tanker)

    \b
    Formats read (detected from the content): WAMIT .1/.3/.hst/.out, NEMOH .tec,
    AQWA .LIS/.AH1, ShipX/VERES .re7/.re8/.re1, Capytaine NetCDF, MSS .mat.
    Nondimensional WAMIT files take --rho, --g and --ulen.

    Run `cummins COMMAND --help` for the options of a command.
    """


main.add_command(info_command)
main.add_command(check_command)
main.add_command(convert_command)
main.add_command(demo_command)
main.add_command(bem_command)  # works without Capytaine: it then says how to install it
main.add_command(kernel_command)
main.add_command(fit_command)
main.add_command(fit_excitation_command)
main.add_command(reduce_command)
main.add_command(rao_command)
main.add_command(simulate_command)
main.add_command(identify_damping_command)
main.add_command(dp_demo_command)
main.add_command(lf_model_command)
main.add_command(batch_command)  # works without Dask: it then says how to install it
main.add_command(report_command)


if __name__ == "__main__":  # pragma: no cover
    main()
