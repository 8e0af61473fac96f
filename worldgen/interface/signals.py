"""The stop signals of a simulator process (ROS 1's or ROS 2's), which runs as a child of ``worldgen run`` or
``worldgen sim``: SIGTERM and SIGHUP become KeyboardInterrupt like Ctrl-C; they are held while the simulator starts
(a KeyboardInterrupt raised inside an import's clean-up callback is printed as "Exception ignored" and lost) and
delivered once its loop can handle them; and once it is writing its trace, a second signal must not cut that short.
Only a simulator process's own ``__main__`` calls :func:`simulator_main`, so no other process's handlers change."""

from __future__ import annotations

import signal
import sys
from typing import Callable

from ..sim.quiet import import_pybullet

STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


def _interrupt(signum, frame):
    raise KeyboardInterrupt(f"signal {signum}")


def deliver_interrupts() -> None:
    """Let the held stop signals in (raised as KeyboardInterrupt where the loop handles it)."""
    signal.pthread_sigmask(signal.SIG_UNBLOCK, set(STOP_SIGNALS))


def pending_interrupt() -> bool:
    """Whether a stop signal came while they are held (the simulator still starting)."""
    return bool(set(STOP_SIGNALS) & signal.sigpending())


def ignore_interrupts() -> None:
    """From now on the stop signals do nothing (the trace is being written)."""
    for sig in STOP_SIGNALS:
        try:
            signal.signal(sig, signal.SIG_IGN)
        except ValueError:   # not the main thread
            pass


def run_main(main: Callable[[list], int]) -> None:
    """Run a simulator's ``main(argv)`` as the process's whole life (see the module docstring) and exit with its
    code; interrupted before its loop started, it exits 0 with nothing to write."""
    signal.signal(signal.SIGTERM, _interrupt)
    signal.signal(signal.SIGHUP, _interrupt)
    signal.pthread_sigmask(signal.SIG_BLOCK, set(STOP_SIGNALS))
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:
        sys.exit(0)


def simulator_main(load: Callable[[], Callable[[list], int]]) -> None:
    """A simulator process's whole life (``python -m worldgen.ros1`` or ``ros2``): the stop signals held from the
    start (a Ctrl-C while it imports would print a KeyboardInterrupt traceback from deep in an import, and be lost),
    pybullet imported with its greeting silenced (``worldgen sim`` shares its terminal), then ``load()``'s main run
    by :func:`run_main`, which delivers the held signals where the node handles them."""
    signal.pthread_sigmask(signal.SIG_BLOCK, set(STOP_SIGNALS))
    import_pybullet()
    run_main(load())
