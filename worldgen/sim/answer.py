"""What an isolated run answers (:mod:`.process`, :mod:`.forkserver`): the child calls its target and sends the
result or the error as JSON (:func:`execute`); the caller reads it back (:func:`read_answer`): the result, the
child's worldgen error raised again as the same class, another exception as :class:`SimError` with the child's
traceback, or :class:`SimCrashed` when there is no answer (the child was killed by a signal, or gave none).
"""

from __future__ import annotations

import importlib
import json
import traceback

from ..core import errors

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


def read_answer(target: str, data: bytes | None, rc: int | None, tail: str) -> dict:
    """The result in the child's answer ``data``, or the error it reports, or :class:`SimCrashed` for none
    (``rc``: its exit code, negative for a signal, None unknown; ``tail``: its last stderr lines)."""
    try:
        answer = json.loads((data or b"").decode("utf-8"))
    except (UnicodeDecodeError, ValueError):
        answer = None
    if not isinstance(answer, dict) or "ok" not in answer:
        how = ("gave no answer" if rc is None else f"was killed by signal {-rc}" if rc < 0 else
               f"exited with code {rc} without an answer")
        raise SimCrashed(f"the simulation process running {target} {how}", rc=rc, stderr_tail=tail)
    if answer["ok"]:
        return answer["result"]
    raise _rebuild_error(answer["error"])


def _rebuild_error(error: dict) -> Exception:
    if error.get("worldgen"):
        cls = getattr(errors, error["type"], errors.WorldgenError)
        return cls(error["message"], path=error.get("path"), line=error.get("line"), hint=error.get("hint"))
    return SimError(f"{error['type']}: {error['message']}", error.get("traceback", ""))


def describe(exc: BaseException) -> dict:
    """An exception as the answer carries it (a worldgen error with its fields, else its type, text and
    traceback)."""
    if isinstance(exc, errors.WorldgenError):
        return {"worldgen": True, "type": type(exc).__name__, "message": exc.message, "path": exc.path,
                "line": exc.line, "hint": exc.hint}
    return {"worldgen": False, "type": type(exc).__name__, "message": str(exc),
            "traceback": "".join(traceback.format_exception(type(exc), exc, exc.__traceback__))}


def execute(target: str, kwargs: dict) -> bytes:
    """Call ``target`` ("package.module:function") with ``kwargs``: the answer a child sends (JSON bytes), its
    result or the error it raised."""
    try:
        module_name, _, func_name = target.partition(":")
        func = getattr(importlib.import_module(module_name), func_name)
        answer = {"ok": True, "result": func(**kwargs)}
    except Exception as exc:  # reported to the parent, which raises it again
        answer = {"ok": False, "error": describe(exc)}
    try:
        return json.dumps(answer).encode("utf-8")
    except (TypeError, ValueError) as exc:   # a result JSON cannot carry
        return json.dumps({"ok": False, "error": describe(exc)}).encode("utf-8")
