"""Work started ahead in a thread of its own: a space the disc search will probably need next, computed while the
search computes the one it needs now (GEOS lets go of the GIL, so on a machine with a spare core the two take the
time of the longer one).

Plain threads and futures: nothing here knows about geometry.
"""

from __future__ import annotations

import threading
from concurrent.futures import Future


def in_thread(work) -> Future:
    """``work()`` run in a daemon thread (a guess that turned out unneeded never holds up the exit), its result or
    exception in the future returned."""
    future: Future = Future()

    def run() -> None:
        try:
            future.set_result(work())
        except BaseException as err:   # kept for the one who asks; computed again there, raising as it would
            future.set_exception(err)

    threading.Thread(target=run, name="worldgen-ahead", daemon=True).start()
    return future


def outcome(future: Future):
    """The future's result once done, or None when its work failed."""
    return None if future.exception() is not None else future.result()
