"""The keeper: a small process between worldgen and everything a run starts, so that nothing a run starts outlives
it — not a node's daemon (double fork, setsid), not a node that ignores SIGTERM, not even when worldgen itself is
killed with SIGKILL.

Why a process of its own: a daemon leaves its parent's process group and session, and once its parent exits
Linux gives it to the nearest ancestor that is a *child subreaper* (``prctl(PR_SET_CHILD_SUBREAPER)``), else to
init. The keeper is that subreaper: it starts every child of a :class:`~worldgen.bridge.supervise.Supervisor`
(worldgen asks it over a pipe), so every process of the run, daemonised or not, stays below it, and "what is left
of the run" is exactly the keeper's descendants (read from ``/proc``). worldgen itself could be the subreaper, but
when it is killed with SIGKILL its orphans go to init, out of anyone's reach; the keeper survives worldgen (it is
in a session of its own, so Ctrl-C in the terminal does not reach it either), sees its request pipe close, and
ends the lot. cgroups would do it too, but a student's account can seldom create one.

Its children get ``PR_SET_PDEATHSIG`` = SIGKILL, for the one case left: the keeper itself killed.

Protocol (one JSON object a line): worldgen sends ``{"op": "start", "id": K, "argv", "env", "cwd", "log",
"show_errors"}`` (answered ``{"reply": K, "pid": P}`` or ``{"reply": K, "error": [errno, strerror, filename]}``)
and ``{"op": "sweep", "id": K, "grace": S}`` (every process still below the keeper is sent SIGTERM, and SIGKILL
after ``S`` seconds; answered ``{"reply": K, "ended": [{"pid", "cmd", "owner", "own"}]}``, ``owner`` the start
request's id it descends from or null, ``own`` whether it is that started process itself); the keeper sends
``{"exit": P, "code": C}`` when a started process ends (``C`` as Popen's returncode); ``{"op": "remove", "path": P}``
(not answered) names a folder of the run's to remove once all is ended. When the pipe closes (worldgen done, or
dead), or on SIGTERM/SIGHUP, it sweeps, removes those folders (a worldgen killed with SIGKILL leaves no temporary
folder either) and exits. Owners are found by ancestry while the parent lives,
else by :data:`MARK` in the environment (each started process gets ``MARK=<keeper pid>.<id>``, which its children
inherit), else by process group or session. While a child runs, the keeper frees the middle of its log on disk
(:func:`.logtail.trim`).
"""

from __future__ import annotations

import json
import os
import select
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

from .logtail import trim

PR_SET_PDEATHSIG = 1
PR_SET_CHILD_SUBREAPER = 36
MARK = "WORLDGEN_KEEPER_CHILD"
TRIM_EVERY = 0.05          # s between trims of the logs
TRIM_SOON = 0.01           # s to the next, while a log grows fast
SWEEP_GRACE = 1.0          # s between SIGTERM and SIGKILL when worldgen is gone
GIVE_UP = 10.0             # s after SIGKILL before a process that will not go (uninterruptible) is left


def _libc():
    try:
        import ctypes

        return ctypes.CDLL(None, use_errno=True)
    except (OSError, AttributeError):
        return None


_LIBC = _libc() if sys.platform.startswith("linux") else None


def _child_setup() -> None:
    """In a started child, before exec: Ctrl-C's default (whatever worldgen's own parent left), and SIGKILL when
    the keeper dies (which only happens when it is killed)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    if _LIBC is not None:
        _LIBC.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


def exit_code(status: int) -> int:
    """A wait status as Popen's returncode: the exit code, or minus the signal that ended it."""
    if os.WIFSIGNALED(status):
        return -os.WTERMSIG(status)
    return os.WEXITSTATUS(status) if os.WIFEXITED(status) else status


def process_table() -> dict[int, tuple[int, int, int, str]]:
    """Every process's (parent, process group, session, state) from ``/proc``."""
    table = {}
    try:
        entries = os.listdir("/proc")
    except OSError:   # no /proc (not Linux): nothing can be found, nothing is swept
        return table
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as handle:
                fields = handle.read().rsplit(b")", 1)[1].split()
        except (OSError, IndexError):
            continue
        table[int(entry)] = (int(fields[1]), int(fields[2]), int(fields[3]), fields[0].decode())
    return table


def descendants(root: int, table: dict) -> list[int]:
    """The living (not zombie) processes below ``root``, parents before children."""
    below: dict[int, list[int]] = {}
    for pid, (ppid, _, _, _) in table.items():
        below.setdefault(ppid, []).append(pid)
    found, todo = [], list(below.get(root, []))
    while todo:
        pid = todo.pop(0)
        if table[pid][3] != "Z":
            found.append(pid)
        todo += below.get(pid, [])
    return found


def command_line(pid: int) -> str:
    try:
        text = " ".join(Path(f"/proc/{pid}/cmdline").read_bytes().decode(errors="replace").replace("\0", " ").split())
    except OSError:
        return "?"
    return text if len(text) <= 200 else text[:197] + "..."


def marked(pid: int, token: str) -> str | None:
    """The start request's id in ``pid``'s environment (:data:`MARK`), when it is this keeper's."""
    try:
        environ = Path(f"/proc/{pid}/environ").read_bytes()
    except OSError:
        return None
    for item in environ.split(b"\0"):
        if item.startswith(MARK.encode() + b"="):
            mine, _, key = item.split(b"=", 1)[1].decode(errors="replace").partition(".")
            return key if mine == token else None
    return None


class Keeper:
    """The keeper's state: the processes it started (pid → request id, Popen), their logs, where replies go."""

    def __init__(self, out: int = 1):
        self.out = out
        self.token = str(os.getpid())
        self.running: dict[int, tuple[str, subprocess.Popen]] = {}
        self.started: dict[int, str] = {}        # every pid ever started → its request id
        self.logs: dict[str, list] = {}           # request id → [open log, trimmed up to]
        self.remove: list[str] = []               # folders to remove at the end

    def send(self, message: dict) -> None:
        try:
            os.write(self.out, (json.dumps(message) + "\n").encode())
        except OSError:   # worldgen is gone: nobody to tell
            pass

    def start(self, request: dict) -> dict:
        key = str(request["id"])
        log = open(request["log"], "wb") if request.get("log") else None
        env = dict(request["env"], **{MARK: f"{self.token}.{key}"})
        try:
            proc = subprocess.Popen(request["argv"], env=env, cwd=request.get("cwd"), stdin=subprocess.DEVNULL,
                                    stdout=log or subprocess.DEVNULL,
                                    stderr=None if request.get("show_errors") else subprocess.STDOUT,
                                    start_new_session=True, preexec_fn=_child_setup)
        except OSError as err:
            if log is not None:
                log.close()
            return {"reply": key, "error": [err.errno, err.strerror, err.filename]}
        except subprocess.SubprocessError as err:
            if log is not None:
                log.close()
            return {"reply": key, "error": [None, str(err), None]}
        self.running[proc.pid] = (key, proc)
        self.started[proc.pid] = key
        if log is not None:
            self.logs[key] = [log, 0]
        return {"reply": key, "pid": proc.pid}

    def reap(self) -> None:
        """Collect every child that ended (started ones are reported, orphans only reaped)."""
        while True:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return
            if pid in self.running:
                _, proc = self.running.pop(pid)
                proc.returncode = exit_code(status)
                self.send({"exit": pid, "code": proc.returncode})

    def owner(self, pid: int, table: dict) -> str | None:
        """The start request ``pid`` descends from (see the module docstring), or None."""
        seen, step = set(), pid
        while step in table and step not in seen and step != os.getpid():
            if step in self.running:
                return self.running[step][0]
            seen.add(step)
            step = table[step][0]
        key = marked(pid, self.token)
        if key is not None:
            return key
        _, group, session, _ = table[pid]
        return self.started.get(group) or self.started.get(session)

    def sweep(self, grace: float) -> list[dict]:
        """End every process below the keeper: SIGTERM, SIGKILL after ``grace`` s; what was found, as each was
        first seen."""
        ended: dict[int, dict] = {}
        termed: set = set()
        kill_at = time.monotonic() + grace
        while True:
            self.reap()
            table = process_table()
            alive = descendants(os.getpid(), table)
            for pid in alive:
                if pid not in ended:
                    ended[pid] = {"pid": pid, "cmd": command_line(pid), "owner": self.owner(pid, table),
                                  "own": pid in self.running}
            now = time.monotonic()
            if not alive or now > kill_at + GIVE_UP:
                return list(ended.values())
            for pid in alive:
                if now >= kill_at or pid not in termed:
                    _signal(pid, signal.SIGKILL if now >= kill_at else signal.SIGTERM)
                    termed.add(pid)
            time.sleep(0.02)

    def trim_logs(self) -> bool:
        """Free the middle of every log on disk; whether some log had grown enough to need it (then the next
        look comes sooner: a node can print a gigabyte a second)."""
        busy = False
        for entry in self.logs.values():
            if entry[1] >= 0 and not entry[0].closed:
                done = trim(entry[0].fileno(), entry[1])
                busy = busy or done > entry[1]
                entry[1] = done
        return busy

    def handle(self, line: bytes) -> None:
        try:
            request = json.loads(line)
        except ValueError:
            return
        if request.get("op") == "start":
            self.send(self.start(request))
        elif request.get("op") == "sweep":
            self.send({"reply": str(request["id"]), "ended": self.sweep(float(request.get("grace", SWEEP_GRACE)))})
        elif request.get("op") == "remove" and isinstance(request.get("path"), str):
            self.remove.append(request["path"])

    def serve(self, source: int = 0) -> None:
        """Answer requests until ``source`` closes or a stop signal comes, then sweep (see the module docstring)."""
        stop: list = []
        signal.signal(signal.SIGINT, lambda *_: None)   # not SIG_IGN: its children would inherit that
        for sig in (signal.SIGTERM, signal.SIGHUP):
            signal.signal(sig, lambda *_: stop.append(True))
        signal.signal(signal.SIGCHLD, lambda *_: None)
        wake, wake_in = os.pipe()
        os.set_blocking(wake, False)
        os.set_blocking(wake_in, False)
        signal.set_wakeup_fd(wake_in)   # a signal ends select at once
        pending, wait = b"", TRIM_EVERY
        while not stop:
            ready, _, _ = select.select([source, wake], [], [], wait)
            if wake in ready:
                _drain(wake)
            self.reap()
            if source in ready:
                data = os.read(source, 1 << 16)
                if not data:
                    break
                *lines, pending = (pending + data).split(b"\n")
                for line in lines:
                    self.handle(line)
            wait = TRIM_SOON if self.trim_logs() else TRIM_EVERY
        self.sweep(SWEEP_GRACE)
        for entry in self.logs.values():
            entry[0].close()
        for folder in self.remove:
            shutil.rmtree(folder, ignore_errors=True)


def _signal(pid: int, sig: int) -> None:
    try:
        os.kill(pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def _drain(fd: int) -> None:
    try:
        while os.read(fd, 4096):
            pass
    except BlockingIOError:
        pass


def main() -> None:
    """The keeper process (see the module docstring): a subreaper serving requests on stdin, replies on stdout."""
    if _LIBC is not None:
        _LIBC.prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
    out = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)   # nothing else may write into the reply pipe
    os.close(devnull)
    Keeper(out).serve(0)


if __name__ == "__main__":
    main()
