"""``python -m worldgen`` runs the command line."""

from .cli import main

main()
