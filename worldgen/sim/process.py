"""Run a function in a child Python process: pybullet writes to the C-level stdout and can crash the whole
process on bad input, so simulations run apart from the CLI.

``run_isolated("pkg.module:function", kwargs, timeout)`` starts ``python -m worldgen.sim.process``, sends
``{"target": …, "kwargs": …}`` as JSON on its stdin and returns the function's JSON-able result. The child moves
file descriptor 1 to /dev/null before importing anything (keeping a duplicate for its answer), so nothing a C
library prints can corrupt the result. A worldgen error raised in the child is raised again in the parent as
the same class; another exception becomes :class:`SimError` with the child's traceback; a crash (killed by a
signal, or no answer) or a timeout becomes :class:`SimCrashed` with the exit code and the last stderr lines.

The child imports only this module and the target's module, so a job costs a Python start plus what it uses.
Within :func:`worldgen.sim.forkserver.forking` (``worldgen validate``), the child is instead a fork of a process
that has imported them already, with the same isolation, answers and errors. Threads may call ``run_isolated``
concurrently (``validate -j N``): each call is its own process.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from .answer import STDERR_TAIL, SimCrashed, SimError, describe, execute, read_answer
from .forkserver import active

__all__ = ["Pending", "SimCrashed", "SimError", "run_isolated", "start_isolated"]


def run_isolated(target: str, kwargs: dict | None = None, timeout: float = 120.0, *,
                 env: dict[str, str] | None = None) -> dict:
    """Call ``target`` ("package.module:function") with ``kwargs`` in a fresh Python process and return its
    result (anything JSON can carry; floats keep inf and nan). See the module docstring for the errors."""
    return start_isolated(target, kwargs, timeout, env=env).result()


class Pending:
    """A run started by :func:`start_isolated`: :meth:`result` waits for it, :meth:`cancel` stops it."""

    def __init__(self, target: str, timeout: float, run=None, later=None):
        self.target, self.timeout, self._run, self._later = target, timeout, run, later

    def result(self) -> dict:
        if self._run is None:
            return self._later()
        data, rc, tail, timed_out = self._run.wait()
        if timed_out:
            raise SimCrashed(f"{self.target} did not finish within {self.timeout:g} s and was stopped", rc=None,
                             stderr_tail=tail, timed_out=True)
        return read_answer(self.target, data, rc, tail)

    def cancel(self) -> None:
        if self._run is not None:
            self._run.cancel()


def start_isolated(target: str, kwargs: dict | None = None, timeout: float = 120.0, *,
                   env: dict[str, str] | None = None) -> Pending:
    """:func:`run_isolated` begun: within a fork server (``env`` None) the run goes on while the caller does
    other work, and :meth:`Pending.result` waits for it; otherwise the child process starts when it is asked."""
    server = active() if env is None else None
    if server is not None:
        try:
            return Pending(target, timeout, run=server.start(target, kwargs or {}, timeout))
        except OSError:   # the server is gone: a child process as below
            pass
    return Pending(target, timeout, later=lambda: _run_child(target, kwargs, timeout, env))


def _run_child(target: str, kwargs: dict | None, timeout: float, env: dict[str, str] | None) -> dict:
    request = json.dumps({"target": target, "kwargs": kwargs or {}})
    child_env = dict(os.environ if env is None else env)
    root = str(Path(__file__).resolve().parents[2])   # the folder holding the worldgen package
    child_env["PYTHONPATH"] = os.pathsep.join(p for p in (root, child_env.get("PYTHONPATH")) if p)
    try:
        proc = subprocess.run([sys.executable, "-m", "worldgen.sim.process"], input=request.encode(),
                              capture_output=True, timeout=timeout, env=child_env)
    except subprocess.TimeoutExpired as err:
        raise SimCrashed(f"{target} did not finish within {timeout:g} s and was stopped", rc=None,
                         stderr_tail=_tail(err.stderr), timed_out=True) from None
    return read_answer(target, proc.stdout, proc.returncode, _tail(proc.stderr))


def _tail(data: bytes | None) -> str:
    lines = (data or b"").decode("utf-8", "replace").splitlines()
    return "\n".join(lines[-STDERR_TAIL:])


def _child() -> int:
    answer_fd = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.close(devnull)
    sys.stdout = sys.stderr   # Python-level prints go with the logs, not into the answer
    try:
        request = json.loads(sys.stdin.read())
        data = execute(request["target"], request.get("kwargs", {}))
    except Exception as exc:  # reported to the parent, which raises it again
        data = json.dumps({"ok": False, "error": describe(exc)}).encode("utf-8")
    with os.fdopen(answer_fd, "wb") as out:
        out.write(data)
    return 0


if __name__ == "__main__":
    sys.exit(_child())
