"""Run a function in a child Python process: pybullet writes to the C-level stdout and can crash the whole
process on bad input, so simulations run apart from the CLI.

``run_isolated("pkg.module:function", kwargs, timeout)`` starts ``python -m worldgen.sim.process``, sends
``{"target": …, "kwargs": …}`` as JSON on its stdin and returns the function's JSON-able result. The child moves
file descriptor 1 to /dev/null before importing anything (keeping a duplicate for its answer), so nothing a C
library prints can corrupt the result. A worldgen error raised in the child is raised again in the parent as
the same class; another exception becomes :class:`SimError` with the child's traceback; a crash (killed by a
signal, or no answer) or a timeout becomes :class:`SimCrashed` with the exit code and the last stderr lines.

The child imports only this module and the target's module, so a job costs a Python start plus what it uses.
Threads may call ``run_isolated`` concurrently (``validate -j N``): each call is its own process.
"""

from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys
import traceback
from pathlib import Path

STDERR_TAIL = 20   # lines of the child's stderr kept in error messages


class SimCrashed(RuntimeError):
    """The child process died (``rc`` < 0: killed by that signal), timed out, or gave no answer."""

    def __init__(self, message: str, *, rc: int | None, stderr_tail: str = "", timed_out: bool = False):
        super().__init__(message + (f"\n--- last stderr lines ---\n{stderr_tail}" if stderr_tail else ""))
        self.rc = rc
        self.stderr_tail = stderr_tail
        self.timed_out = timed_out


class SimError(RuntimeError):
    """The target raised an exception that is not a worldgen error; ``child_traceback`` is its traceback."""

    def __init__(self, message: str, child_traceback: str = ""):
        super().__init__(message)
        self.child_traceback = child_traceback


def run_isolated(target: str, kwargs: dict | None = None, timeout: float = 120.0, *,
                 env: dict[str, str] | None = None) -> dict:
    """Call ``target`` ("package.module:function") with ``kwargs`` in a fresh Python process and return its
    result (anything JSON can carry; floats keep inf and nan). See the module docstring for the errors."""
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
    tail = _tail(proc.stderr)
    try:
        answer = json.loads(proc.stdout.decode("utf-8"))
    except (UnicodeDecodeError, ValueError):
        answer = None
    if not isinstance(answer, dict) or "ok" not in answer:
        how = f"was killed by signal {-proc.returncode}" if proc.returncode < 0 else \
            f"exited with code {proc.returncode} without an answer"
        raise SimCrashed(f"the simulation process running {target} {how}", rc=proc.returncode,
                         stderr_tail=tail)
    if answer["ok"]:
        return answer["result"]
    raise _rebuild_error(answer["error"])


def _tail(data: bytes | None) -> str:
    lines = (data or b"").decode("utf-8", "replace").splitlines()
    return "\n".join(lines[-STDERR_TAIL:])


def _rebuild_error(error: dict) -> Exception:
    if error.get("worldgen"):
        from ..core import errors
        cls = getattr(errors, error["type"], errors.WorldgenError)
        return cls(error["message"], path=error.get("path"), line=error.get("line"), hint=error.get("hint"))
    return SimError(f"{error['type']}: {error['message']}", error.get("traceback", ""))


def _describe(exc: BaseException) -> dict:
    from ..core.errors import WorldgenError
    if isinstance(exc, WorldgenError):
        return {"worldgen": True, "type": type(exc).__name__, "message": exc.message, "path": exc.path,
                "line": exc.line, "hint": exc.hint}
    return {"worldgen": False, "type": type(exc).__name__, "message": str(exc),
            "traceback": "".join(traceback.format_exception(type(exc), exc, exc.__traceback__))}


def _child() -> int:
    answer_fd = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.close(devnull)
    sys.stdout = sys.stderr   # Python-level prints go with the logs, not into the answer
    try:
        request = json.loads(sys.stdin.read())
        module_name, _, func_name = request["target"].partition(":")
        func = getattr(importlib.import_module(module_name), func_name)
        answer = {"ok": True, "result": func(**request.get("kwargs", {}))}
    except Exception as exc:  # reported to the parent, which raises it again
        answer = {"ok": False, "error": _describe(exc)}
    try:
        data = json.dumps(answer).encode("utf-8")
    except (TypeError, ValueError) as exc:   # a result JSON cannot carry
        data = json.dumps({"ok": False, "error": _describe(exc)}).encode("utf-8")
    with os.fdopen(answer_fd, "wb") as out:
        out.write(data)
    return 0


if __name__ == "__main__":
    sys.exit(_child())
