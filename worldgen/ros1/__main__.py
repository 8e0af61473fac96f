"""``python -m worldgen.ros1 CONFIG.json``: the simulator process (:mod:`.node`). The stop signals are held from
its first line (a Ctrl-C while it imports would print a KeyboardInterrupt traceback from deep in an import, and be
lost), pybullet is imported with its greeting silenced (:mod:`worldgen.sim.quiet`: ``worldgen sim`` shares its
terminal), then :func:`worldgen.interface.signals.run_main` delivers the held signals where the node handles them."""

import signal

signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM, signal.SIGHUP})

from ..sim.quiet import import_pybullet  # noqa: E402  (after the signals are held, on purpose)

import_pybullet()

from ..interface.signals import run_main  # noqa: E402
from .node import main  # noqa: E402

run_main(main)
