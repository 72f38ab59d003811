"""``python -m crankdyn``: the command line."""

from crankdyn.cli import run

run()
