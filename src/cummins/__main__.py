"""``python -m cummins``: the ``cummins`` command (where the script is not on the PATH)."""

from cummins.cli.app import main

main()
