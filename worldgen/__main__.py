"""``python -m worldgen`` runs the command line."""

from .cli import run

run()
