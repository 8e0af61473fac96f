"""Isolated runs forked from a warm process instead of a fresh Python start each.

``worldgen validate`` runs every world's simulation apart from itself (pybullet can crash the process on bad
input; see :mod:`.process`). A fresh ``python -m`` per world costs a Python start and pybullet's and numpy's
imports; here one *fork server* pays them once, while the command itself is still reading its inputs, and each
run is a fork of it. :func:`forking` starts the server for a ``with`` block; meanwhile
:func:`worldgen.sim.process.run_isolated` runs its targets through it, with the same answers and the same errors.

Three processes per run, each with one job:

- the **server**, forked from the command before it has started any thread (checked: a fork copies only the
  calling thread, so a lock another thread held would stay locked), imports the preloaded modules with BLAS held
  to one thread (so it stays single-threaded), then forks a supervisor for each connection on its socket (a
  private folder's Unix socket) until the command closes the pipe it watches (the command ended, however); it
  waits for each supervisor, as each waits for its worker, so their CPU time counts as the command's;
- the **supervisor** forks the worker, tells the caller its pid, waits for it (killing it at the run's timeout)
  and sends back how it ended, the last lines it wrote to stderr and its answer;
- the **worker** runs the target with stdout on /dev/null and stderr and the answer in files of the supervisor's,
  and leaves with ``os._exit``, so a segfault, an abort or a hang ends the worker alone: the caller gets
  :class:`~.process.SimCrashed` as from a child process, and the next run forks afresh.

Every forked process leaves with ``os._exit``: none runs the command's ``atexit`` handlers or finalizers (its
temporary folders stay its own). Where ``fork`` is missing, or the command already runs threads, :func:`forking`
starts nothing and runs keep their child processes.
"""

from __future__ import annotations

import gc
import importlib
import json
import os
import select
import shutil
import signal
import socket
import struct
import sys
import tempfile
import threading
import time
from contextlib import contextmanager
from typing import Iterator, Sequence

from .answer import STDERR_TAIL, execute

_HEADER = struct.Struct("!Q")   # each message: its length, then JSON (or the worker's answer as it wrote it)
_GRACE = 10.0                   # s the caller waits past a run's timeout for the supervisor's word
_SERVER: ForkServer | None = None
_BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def one_blas_thread() -> None:
    """Hold BLAS (numpy's, scipy's) to the calling thread in this process and its children: imported after
    this, numpy starts no thread of its own, so the process may still fork a server."""
    for name in _BLAS_THREADS:
        os.environ[name] = "1"


def thread_count() -> int:
    """Threads of this process, native ones included (Linux: /proc/self/task), else Python's own."""
    try:
        return len(os.listdir("/proc/self/task"))
    except OSError:
        return threading.active_count()


def active() -> ForkServer | None:
    """The server runs go through in this process, if one is running (a fork of the command sees none)."""
    server = _SERVER
    return server if server is not None and server.owner == os.getpid() else None


@contextmanager
def forking(preload: Sequence[str] = ()) -> Iterator[ForkServer | None]:
    """A fork server for the block, ``preload`` imported in it (not here): module names, or ``module:function``
    for a function to call once imported (a warm-up each fork inherits); None, and runs keep their child
    processes, when this process cannot fork safely (no ``fork``, threads running) or one is running."""
    global _SERVER
    if active() is not None or not hasattr(os, "fork") or thread_count() != 1:
        yield None
        return
    server = ForkServer(preload)
    _SERVER = server
    try:
        yield server
    finally:
        _SERVER = None
        server.stop()


class ForkServer:
    """The server process (see the module docstring); :meth:`call` runs one target in a fork of it."""

    def __init__(self, preload: Sequence[str] = ()):
        self.owner = os.getpid()
        self.folder = tempfile.mkdtemp(prefix="worldgen-forks-")   # only this user can enter it
        self.address = os.path.join(self.folder, "socket")
        listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        listener.bind(self.address)
        listener.listen(64)
        alive_r, self._alive_w = os.pipe()
        for stream in (sys.stdout, sys.stderr):   # nothing buffered here may be written twice
            try:
                stream.flush()
            except (AttributeError, OSError, ValueError):
                pass
        self.pid = os.fork()
        if self.pid == 0:   # the server
            code = 1
            try:
                os.close(self._alive_w)
                _serve(listener, alive_r, tuple(preload))
                code = 0
            finally:
                os._exit(code)
        listener.close()
        os.close(alive_r)

    def call(self, target: str, kwargs: dict, timeout: float) -> tuple[bytes | None, int | None, str, bool]:
        """Run ``target`` with ``kwargs`` in a fresh fork: (its answer as it wrote it, or None; its exit code,
        negative for a signal, None when unknown; the last lines of its stderr; whether it was stopped at
        ``timeout``). OSError when the server cannot start the run (it is gone, or cannot fork)."""
        return self.start(target, kwargs, timeout).wait()

    def start(self, target: str, kwargs: dict, timeout: float) -> Run:
        """:meth:`call` begun: the worker runs while the caller goes on; :meth:`Run.wait` for its end."""
        conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            conn.connect(self.address)
            conn.sendall(_frame(json.dumps({"target": target, "kwargs": kwargs, "timeout": timeout}).encode()))
            deadline = time.monotonic() + timeout + _GRACE
            started = json.loads(_receive(conn, deadline))
            if "error" in started:
                raise OSError(started["error"])
        except BaseException:
            conn.close()
            raise
        return Run(conn, started["pid"], deadline)

    def stop(self) -> None:
        """End the server (it sees its pipe close) and remove its folder; runs under way finish on their own."""
        try:
            os.close(self._alive_w)
        except OSError:
            pass
        try:
            os.waitpid(self.pid, 0)
        except ChildProcessError:
            pass
        shutil.rmtree(self.folder, ignore_errors=True)


class Run:
    """One run under way: its worker's ``pid`` and the connection its supervisor answers on."""

    def __init__(self, conn: socket.socket, pid: int, deadline: float):
        self.conn, self.pid, self.deadline, self.ended = conn, pid, deadline, False

    def wait(self) -> tuple[bytes | None, int | None, str, bool]:
        """What :meth:`ForkServer.call` returns, once the worker has ended."""
        try:
            ended = json.loads(_receive(self.conn, self.deadline))
            answer = _receive(self.conn, self.deadline)
        except OSError as err:   # the supervisor died or fell silent: the worker goes too
            self.cancel()
            return None, None, f"({err})", isinstance(err, TimeoutError)
        except BaseException:    # interrupted: no worker left behind
            self.cancel()
            raise
        self.ended = True
        self.conn.close()
        return answer or None, ended["rc"], ended["stderr"], ended["timed_out"]

    def cancel(self) -> None:
        """Stop the worker (its supervisor then ends too); nothing once it has ended."""
        if not self.ended:
            self.ended = True
            _kill(self.pid)
            self.conn.close()


# -- the server ------------------------------------------------------------------------------------------------

def _serve(listener: socket.socket, alive: int, preload: tuple[str, ...]) -> None:
    _detach()
    one_blas_thread()   # BLAS started here would run threads: a fork of this must copy all there is
    signal.signal(signal.SIGINT, signal.SIG_IGN)   # Ctrl-C ends the command, and the command ends this
    gc.disable()   # importing makes no garbage worth a cycle collection: 5 % of the imports' time
    for name in preload:
        module, _, function = name.partition(":")
        try:
            loaded = importlib.import_module(module)
            if function:
                getattr(loaded, function)()
        except Exception:   # noqa: BLE001  (the run that needs it reports the error)
            pass
    gc.enable()
    while True:
        ready, _, _ = select.select([listener, alive], [], [])
        _reap(block=alive in ready)   # waited for, so that the command's CPU time counts theirs
        if alive in ready:   # the command closed its end: it is done, or gone
            return
        try:
            conn, _ = listener.accept()
        except OSError:
            continue
        try:
            pid = os.fork()
        except OSError as err:
            _tell(conn, {"error": f"cannot fork a simulation process: {err.strerror}"})
            conn.close()
            continue
        if pid == 0:
            code = 1
            try:
                listener.close()
                os.close(alive)
                _supervise(conn)
                code = 0
            finally:
                os._exit(code)
        conn.close()


def _reap(block: bool) -> None:
    """Wait for the supervisors that have ended (``block``: for all of them)."""
    while True:
        try:
            pid, _ = os.waitpid(-1, 0 if block else os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            return


def _supervise(conn: socket.socket) -> None:
    """One run: fork the worker, tell its pid, wait for it (the timeout kills it), send how it ended."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    request = json.loads(_receive(conn, None))
    answer = tempfile.TemporaryFile()
    stderr = tempfile.TemporaryFile()
    pid = os.fork()
    if pid == 0:
        code = 1
        try:
            conn.close()
            _work(request, answer.fileno(), stderr.fileno())
            code = 0
        finally:
            os._exit(code)
    _tell(conn, {"pid": pid})
    timed_out, reaped = [], []

    def stop(_signum, _stack) -> None:
        if not reaped:
            timed_out.append(True)
            _kill(pid)

    signal.signal(signal.SIGALRM, stop)
    signal.setitimer(signal.ITIMER_REAL, max(0.001, float(request["timeout"])))
    _, status = os.waitpid(pid, 0)
    reaped.append(True)
    signal.setitimer(signal.ITIMER_REAL, 0)
    rc = -os.WTERMSIG(status) if os.WIFSIGNALED(status) else os.WEXITSTATUS(status)
    _tell(conn, {"rc": rc, "stderr": _tail(stderr), "timed_out": bool(timed_out)})
    answer.seek(0)
    _send(conn, b"" if timed_out else answer.read())


def _work(request: dict, answer_fd: int, stderr_fd: int) -> None:
    """The worker: fd 1 to /dev/null, fd 2 to the supervisor's file, the answer to its other file."""
    signal.signal(signal.SIGALRM, signal.SIG_DFL)
    devnull = os.open(os.devnull, os.O_RDWR)
    for fd, to in ((0, devnull), (1, devnull), (2, stderr_fd)):
        os.dup2(to, fd)
    os.close(devnull)
    sys.stdout = sys.stderr   # Python-level prints go with the logs
    data = execute(request["target"], request.get("kwargs") or {})
    with os.fdopen(answer_fd, "wb") as out:
        out.write(data)
    sys.stderr.flush()


def _tail(handle) -> str:
    handle.seek(0, os.SEEK_END)
    size = handle.tell()
    handle.seek(max(0, size - 64 * 1024))
    lines = handle.read().decode("utf-8", "replace").splitlines()
    return "\n".join(lines[-STDERR_TAIL:])


def _detach() -> None:
    """The server holds none of the command's standard streams: stdin, stdout and stderr on /dev/null (a pipe the
    command's caller reads must close when the command ends, not when its last simulation does)."""
    devnull = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):
        os.dup2(devnull, fd)
    os.close(devnull)


def _kill(pid: int) -> None:
    try:
        os.kill(pid, signal.SIGKILL)
    except OSError:
        pass


# -- messages --------------------------------------------------------------------------------------------------

def _tell(conn: socket.socket, message: dict) -> None:
    _send(conn, json.dumps(message).encode("utf-8"))


def _frame(data: bytes) -> bytes:
    return _HEADER.pack(len(data)) + data


def _send(conn: socket.socket, data: bytes) -> None:
    try:
        conn.sendall(_frame(data))
    except OSError:   # the caller is gone (interrupted): nothing to tell
        pass


def _receive(conn: socket.socket, deadline: float | None) -> bytes:
    size = _HEADER.unpack(_read(conn, _HEADER.size, deadline))[0]
    return _read(conn, size, deadline)


def _read(conn: socket.socket, size: int, deadline: float | None) -> bytes:
    chunks, left = [], size
    while left:
        if deadline is not None:
            wait = deadline - time.monotonic()
            if wait <= 0 or not select.select([conn], [], [], wait)[0]:
                raise TimeoutError("no word from the simulation process")
        chunk = conn.recv(min(left, 1 << 20))
        if not chunk:
            raise ConnectionError("the simulation process closed its connection")
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)
