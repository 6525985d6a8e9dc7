"""`python -m bearingsim`: the command line, where the `bearingsim` script is not on PATH
(a virtual environment that is not activated, Windows' per-user scripts folder)."""

from .pipeline.cli.commands import main

main()
