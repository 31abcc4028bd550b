"""The ``cummins`` command line: one module per command, the options they share in
:mod:`cummins.cli.common`, and the application pieces only the command line uses (the demo,
the pipeline stages it composes, the DP demo scenario, the HTML report).

The library (everything outside this package) never imports from here.
"""

from cummins.cli.app import main

__all__ = ["main"]
