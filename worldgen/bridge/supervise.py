"""Child processes that never outlive us: each started in a process group of its own, its output captured to a
file, stopped with its whole group (SIGINT, as roslaunch does, then SIGTERM, then SIGKILL).

:class:`Supervisor` keeps every process it started and stops them all in :meth:`Supervisor.stop_all`, which the
``with`` block calls on any exit — a normal end, an exception, Ctrl-C. While a supervisor is active, SIGTERM and
SIGHUP to this process raise :class:`KeyboardInterrupt`, so a killed parent still stops its children.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

STOP_GRACE = 3.0   # s after SIGINT before SIGTERM, and after SIGTERM before SIGKILL
PR_SET_PDEATHSIG = 1


def _libc():
    try:
        import ctypes

        return ctypes.CDLL(None, use_errno=True)
    except (OSError, AttributeError):
        return None


_LIBC = _libc() if sys.platform.startswith("linux") else None


def _die_with_parent() -> None:
    """In the child, before exec: Linux sends it SIGTERM when the thread that started it dies, so that even a
    parent killed with SIGKILL leaves no orphan."""
    if _LIBC is not None:
        _LIBC.prctl(PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)


@dataclass
class Child:
    """One started process: what it is called in reports, its Popen, and the file holding its output."""

    name: str
    proc: subprocess.Popen
    log: Path | None
    stopped_by_us: bool = False
    last: bool = False   # stopped after every other child (a master outlives its nodes)

    @property
    def running(self) -> bool:
        return self.proc.poll() is None

    def output(self) -> str:
        if self.log is None:
            return ""
        try:
            return self.log.read_text(encoding="utf-8", errors="replace")
        except OSError:
            return ""

    def says(self, text: str) -> bool:
        """Whether its output so far holds ``text``."""
        return text in self.output()

    def last_error_line(self) -> str:
        """The last non-empty line of its output (a traceback's last line says what went wrong)."""
        lines = [ln.strip() for ln in self.output().splitlines() if ln.strip()]
        return lines[-1] if lines else ""


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
        return True
    except (ProcessLookupError, PermissionError):
        return False


def stop_group(proc: subprocess.Popen, grace: float = STOP_GRACE) -> None:
    """Stop ``proc`` and everything in its process group: SIGINT, then SIGTERM, then SIGKILL, each given
    ``grace`` seconds; the leader is reaped."""
    pgid = proc.pid
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL):
        if not _group_alive(pgid) and proc.poll() is not None:
            break
        try:
            os.killpg(pgid, sig)
        except (ProcessLookupError, PermissionError):
            pass
        deadline = time.monotonic() + (grace if sig != signal.SIGKILL else 10.0)
        while time.monotonic() < deadline:
            proc.poll()
            if proc.returncode is not None and not _group_alive(pgid):
                break
            time.sleep(0.02)
    try:
        proc.wait(timeout=5)
    except subprocess.TimeoutExpired:
        pass


_ACTIVE: set = set()
_ACTIVE_LOCK = threading.Lock()


def stop_everything() -> None:
    """Stop the children of every active supervisor (any thread's): what the main thread does when it is
    interrupted while worker threads run."""
    with _ACTIVE_LOCK:
        active = list(_ACTIVE)
    for supervisor in active:
        supervisor.stop_all(grace=1.0)


@dataclass(eq=False)
class Supervisor:
    """Starts processes in their own groups and stops every one of them on exit (see the module docstring)."""

    children: list[Child] = field(default_factory=list)
    _old: dict = field(default_factory=dict)

    def start(self, name: str, argv: list[str], env: dict[str, str], log: Path | None = None,
              cwd: str | Path | None = None, show_errors: bool = False, last: bool = False) -> Child:
        """Start ``argv`` in a new process group; its output goes to ``log`` (None: nowhere; with
        ``show_errors``, stderr stays ours)."""
        out = open(log, "wb") if log is not None else subprocess.DEVNULL
        try:
            proc = subprocess.Popen(argv, env=env, cwd=cwd, stdin=subprocess.DEVNULL, stdout=out,
                                    stderr=None if show_errors else subprocess.STDOUT, start_new_session=True,
                                    preexec_fn=_die_with_parent if _LIBC is not None else None)
        finally:
            if log is not None:
                out.close()
        child = Child(name, proc, log, last=last)
        self.children.append(child)
        return child

    def stop(self, child: Child, grace: float = STOP_GRACE) -> None:
        if child.running:
            child.stopped_by_us = True
        stop_group(child.proc, grace)

    def stop_all(self, grace: float = STOP_GRACE) -> None:
        """Stop every child: all at once, then those marked ``last`` (the master, so that nodes can still leave
        it cleanly)."""
        for wave in (False, True):
            children = [c for c in reversed(self.children) if c.last == wave]
            for child in children:
                if child.running:
                    child.stopped_by_us = True
                    try:
                        os.killpg(child.proc.pid, signal.SIGINT)
                    except (ProcessLookupError, PermissionError):
                        pass
            for child in children:
                stop_group(child.proc, grace)

    def __enter__(self) -> Supervisor:
        with _ACTIVE_LOCK:
            _ACTIVE.add(self)

        def interrupt(signum, frame):
            raise KeyboardInterrupt(f"signal {signum}")

        for sig in (signal.SIGTERM, signal.SIGHUP):
            try:
                self._old[sig] = signal.signal(sig, interrupt)
            except ValueError:   # not the main thread: the caller's own handlers stay
                pass
        return self

    def __exit__(self, *exc) -> None:
        try:
            self.stop_all()
        finally:
            with _ACTIVE_LOCK:
                _ACTIVE.discard(self)
            for sig, old in self._old.items():
                signal.signal(sig, old)
            self._old.clear()
