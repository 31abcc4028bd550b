"""``python -m cummins.cli``: the ``cummins`` command."""

from cummins.cli.app import main

main()
