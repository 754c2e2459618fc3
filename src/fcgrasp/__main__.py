"""``python -m fcgrasp``: the command line."""

from .apps.cli import run

run()
