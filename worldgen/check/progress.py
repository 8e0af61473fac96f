"""How ``worldgen validate`` shows progress on stderr while a batch runs.

On a terminal, a progress bar (click's); in a log (CI, a pipe), one line per finished file, so that a long
class's grading shows it is alive and which file is slow: ``[3/40] FAIL submissions/ana/launch/room.launch``.
Nothing goes to stdout, where the report is.
"""

from __future__ import annotations

import sys
import threading
from contextlib import contextmanager
from typing import Iterator, Optional

from .report import _unicode


class LogLines:
    """One line per finished job on ``stream``: its number, its verdict(s) and its path."""

    def __init__(self, total: int, stream=None):
        self.total, self.done = total, 0
        self.stream = stream if stream is not None else sys.stderr
        self._lock = threading.Lock()

    def __call__(self, job, results) -> None:
        verdicts = " ".join(r.verdict for r in results) or "–"
        with self._lock:
            self.done += 1
            self.stream.write(_unicode(f"[{self.done}/{self.total}] {verdicts} {job.path}\n"))
            self.stream.flush()


@contextmanager
def progress_for(total: int, stream=None, tty: Optional[bool] = None) -> Iterator:
    """A ``progress(job, results)`` callback for :func:`worldgen.check.validate.run_jobs`: a bar on a terminal,
    lines otherwise (``tty`` overrides the guess)."""
    import click

    stream = stream if stream is not None else sys.stderr
    if tty is None:
        tty = stream.isatty()
    if not tty:
        yield LogLines(total, stream)
        return
    with click.progressbar(length=total, label="validating", file=stream) as bar:
        lock = threading.Lock()

        def step(_job, _results) -> None:
            with lock:
                bar.update(1)

        yield step
