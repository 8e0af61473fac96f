"""Child processes that never outlive us: each started in a process group of its own below a keeper process, its
output captured to a file and read back bounded, stopped with its whole group (SIGINT, as roslaunch does, then
SIGTERM, then SIGKILL), and whatever it left behind ended with it.

How nothing outlives a run, even a node's daemon (double fork, setsid) or a node ignoring SIGTERM, even when
worldgen is killed with SIGKILL: a :class:`Supervisor` starts its children through a keeper (:mod:`.keeper`), a
small process that is a child subreaper, so every process the run starts, however it detaches, stays below the
keeper. :meth:`Supervisor.stop_all` stops each child's group as before, then has the keeper sweep whatever is still
below it (SIGTERM, then SIGKILL): those processes are the run's leftovers (:attr:`Supervisor.left`, each traced to
the child it came from, for the run's report). The keeper lives in a session of its own and outlives worldgen: if
worldgen dies (SIGKILL too), the keeper's request pipe closes and it ends the lot itself.

Process-wide state only around the work: while a supervisor is active (its ``with`` block, in the main thread),
SIGTERM and SIGHUP to this process raise :class:`KeyboardInterrupt`, so a killed parent still stops its children;
on leaving the block the handlers of SIGTERM, SIGHUP and SIGINT are put back as they were (a caller that ignored
Ctrl-C while stopping gets Ctrl-C back).

A child's output is kept bounded however much it prints (:mod:`.logtail`): :meth:`Child.output` holds its first
lines and its last megabyte, with one line saying how much was left out.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from ..core.errors import WorldgenError
from .keeper import descendants, process_table
from .logtail import Kept, read_kept

STOP_GRACE = 3.0   # s after SIGINT before SIGTERM, and after SIGTERM before SIGKILL
SWEEP_GRACE = 1.0  # s a leftover gets between SIGTERM and SIGKILL
ANSWER_TIMEOUT = 30.0
BOOT = "import sys; sys.path.insert(0, sys.argv[1]); from worldgen.bridge.keeper import main; main()"


class Process:
    """A process the keeper started, as far as the runs use a Popen: its ``pid``, ``returncode`` (None while it
    runs; minus the signal that ended it), :meth:`poll` and :meth:`wait`."""

    def __init__(self, pid: int, link: KeeperLink):
        self.pid = pid
        self.returncode: int | None = None
        self._link = link

    def poll(self) -> int | None:
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        with self._link.changed:
            if not self._link.changed.wait_for(lambda: self.returncode is not None, timeout):
                raise subprocess.TimeoutExpired(str(self.pid), timeout)
        return self.returncode


class KeeperLink:
    """worldgen's end of one keeper: the requests it sends, the answers and exits a reader thread receives."""

    def __init__(self):
        root = str(Path(__file__).resolve().parents[2])
        self.proc = subprocess.Popen([sys.executable, "-I", "-S", "-c", BOOT, root], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, start_new_session=True)
        self.changed = threading.Condition()
        self._answers: dict[str, dict] = {}
        self._processes: dict[int, Process] = {}
        self._count = 0
        self._writing = threading.Lock()
        self.gone = False
        self._reader = threading.Thread(target=self._read, name="worldgen-keeper", daemon=True)
        self._reader.start()

    def _read(self) -> None:
        for line in self.proc.stdout:
            try:
                message = json.loads(line)
            except ValueError:
                continue
            with self.changed:
                if "exit" in message:
                    process = self._processes.pop(message["exit"], None)
                    if process is not None:
                        process.returncode = message["code"]
                else:
                    if "pid" in message:   # registered before its exit can come (one pipe, in order)
                        message["process"] = self._processes[message["pid"]] = Process(message["pid"], self)
                    self._answers[message["reply"]] = message
                self.changed.notify_all()
        with self.changed:   # the keeper is gone, and its children with it (their parent-death signal)
            self.gone = True
            for process in self._processes.values():
                process.returncode = -signal.SIGKILL
            self.changed.notify_all()

    def _write(self, request: dict) -> bool:
        """Send ``request`` (one line); False when the keeper's pipe is closed (it has ended, or is ending)."""
        data = (json.dumps(request) + "\n").encode()
        try:
            with self._writing:
                self.proc.stdin.write(data)
                self.proc.stdin.flush()
        except (OSError, ValueError):
            return False
        return True

    def ask(self, request: dict) -> dict:
        """Send ``request`` and wait for its answer."""
        with self.changed:
            self._count += 1
            key = str(self._count)
        if not self._write(dict(request, id=key)):
            raise WorldgenError("worldgen's process keeper has ended", hint="please report this to the worldgen "
                                                                             "developers")
        with self.changed:
            self.changed.wait_for(lambda: key in self._answers or self.gone, ANSWER_TIMEOUT)
            if key not in self._answers:
                raise WorldgenError("worldgen's process keeper did not answer",
                                    hint="please report this to the worldgen developers")
            answer = self._answers.pop(key)
        return dict(answer, id=key)

    def start(self, argv: list[str], env: dict[str, str], log: Path | None, cwd, show_errors: bool
              ) -> tuple[str, Process]:
        """Start ``argv`` below the keeper: the request's id and the process; OSError as Popen raises it."""
        answer = self.ask({"op": "start", "argv": [str(a) for a in argv], "env": dict(env),
                           "cwd": str(cwd) if cwd is not None else None, "log": str(log) if log else None,
                           "show_errors": show_errors})
        if "error" in answer:
            number, text, name = answer["error"]
            if number is None:
                raise subprocess.SubprocessError(text)
            raise OSError(number, text, name) if name is not None else OSError(number, text)
        return answer["id"], answer["process"]

    def remove_at_end(self, folder: str) -> None:
        """Have the keeper remove ``folder`` once it has ended everything (it does so even when worldgen is killed);
        not answered, and nothing to do when the keeper has gone."""
        self._write({"op": "remove", "path": str(folder)})

    def sweep(self, grace: float) -> list[dict]:
        """End every process still below the keeper (see :mod:`.keeper`); what was ended (nothing, when the keeper
        has ended: it swept as it ended, or another thread closed it while the command was stopping)."""
        if self.gone or self.proc.stdin.closed:
            return []
        try:
            return self.ask({"op": "sweep", "grace": grace})["ended"]
        except WorldgenError:
            if self.gone or self.proc.stdin.closed or self.proc.poll() is not None:
                return []
            raise

    def close(self) -> None:
        """Let the keeper go (it sweeps once more, then exits) and wait for it."""
        try:
            with self._writing:   # not in the middle of another thread's request
                self.proc.stdin.close()
        except OSError:
            pass
        try:
            self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        self._reader.join(timeout=5)
        self.proc.stdout.close()


@dataclass
class Child:
    """One started process: what it is called in reports, its process, and the file holding its output."""

    name: str
    proc: Process
    log: Path | None
    stopped_by_us: bool = False
    last: bool = False   # stopped after every other child (a master outlives its nodes)

    @property
    def running(self) -> bool:
        return self.proc.poll() is None

    def kept(self) -> Kept:
        """Its output so far, bounded (see :mod:`.logtail`), with how much it wrote and how much was left out."""
        return read_kept(self.log) if self.log is not None else Kept("", 0, 0)

    def output(self) -> str:
        return self.kept().text

    def says(self, text: str) -> bool:
        """Whether its output so far holds ``text`` (in the kept part)."""
        return text in self.output()

    def last_error_line(self) -> str:
        """The last non-empty line of its output (a traceback's last line says what went wrong)."""
        lines = [ln.strip() for ln in self.output().splitlines() if ln.strip()]
        return lines[-1] if lines else ""


@dataclass(frozen=True)
class Leftover:
    """A process still running when its run ended, which the run ended: the child it came from (None when it
    cannot be told), its pid and command line."""

    owner: str | None
    pid: int
    cmd: str


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
        return True
    except (ProcessLookupError, PermissionError):
        return False


def stop_group(proc, grace: float = STOP_GRACE) -> None:
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
_STOPPING = threading.Event()   # set by stop_everything until in_parallel's runs have given up


def stop_everything() -> None:
    """Stop the children of every active supervisor (any thread's): what the main thread does when it is
    interrupted while worker threads run. Until :func:`in_parallel` clears it, no supervisor starts another
    process, and the runs' waits give up (:func:`check_stopping`)."""
    _STOPPING.set()
    with _ACTIVE_LOCK:
        active = list(_ACTIVE)
    for supervisor in active:
        supervisor.stop_all(grace=1.0)


def check_stopping() -> None:
    """Raise KeyboardInterrupt when the command is being stopped (:func:`stop_everything`): a run's waits call
    this, so that a worker thread gives its run up at once instead of waiting out a timeout on processes that have
    been ended (a folder's Ctrl-C took 15 s)."""
    if _STOPPING.is_set():
        raise KeyboardInterrupt("the command is stopping")


def _stopped() -> None:
    """Clear the stopping state once the main thread's runs have given up (a nested in_parallel, in a worker
    thread, leaves it to the main thread's)."""
    if threading.current_thread() is threading.main_thread():
        _STOPPING.clear()


def in_parallel(work, items: list, jobs: int) -> list:
    """``work(item)`` for every item, ``jobs`` at once on worker threads; the results in the items' order. Ctrl-C
    (or SIGTERM) in the main thread stops every run's processes, the runs under way give up at their next wait,
    and the interrupt is raised once they have."""
    from concurrent.futures import ThreadPoolExecutor

    pool = ThreadPoolExecutor(max_workers=max(1, jobs))
    futures = [pool.submit(work, item) for item in items]
    try:
        return [f.result() for f in futures]
    except BaseException as err:   # an interrupt, or a run's own error: no further run starts
        for future in futures:
            future.cancel()
        if isinstance(err, KeyboardInterrupt):
            stop_everything()
        raise
    finally:
        try:
            pool.shutdown(wait=True)
        except KeyboardInterrupt:   # Ctrl-C while the runs under way finish: stop them too
            stop_everything()
            pool.shutdown(wait=True)
            raise
        finally:
            _stopped()


def _interrupt(signum, frame):
    raise KeyboardInterrupt(f"signal {signum}")


@dataclass(eq=False)
class Supervisor:
    """Starts processes in their own groups below a keeper and stops every one of them, and all they started, on
    exit (see the module docstring). :attr:`left`: the processes found still running at the end, and ended."""

    children: list[Child] = field(default_factory=list)
    left: list[Leftover] = field(default_factory=list)
    _old: dict = field(default_factory=dict)
    _link: KeeperLink | None = None
    _names: dict = field(default_factory=dict)   # keeper request id → child name
    _lock: threading.Lock = field(default_factory=threading.Lock)

    def _keeper(self) -> KeeperLink:
        with self._lock:
            if self._link is None:
                self._link = KeeperLink()
            return self._link

    def start(self, name: str, argv: list[str], env: dict[str, str], log: Path | None = None,
              cwd: str | Path | None = None, show_errors: bool = False, last: bool = False) -> Child:
        """Start ``argv`` in a new process group; its output goes to ``log`` (None: nowhere; with
        ``show_errors``, stderr stays ours). Nothing starts once the command is being stopped."""
        check_stopping()
        key, proc = self._keeper().start(argv, env, log, cwd, show_errors)
        child = Child(name, proc, log, last=last)
        self._names[key] = name
        self.children.append(child)
        return child

    def remove_at_end(self, folder: str | Path) -> None:
        """``folder`` (the run's temporary one) removed once every process of the supervisor has ended, by the
        keeper: also when worldgen itself is killed (SIGKILL) and no ``finally`` of its own runs."""
        self._keeper().remove_at_end(str(folder))

    def stop(self, child: Child, grace: float = STOP_GRACE) -> None:
        if child.running:
            child.stopped_by_us = True
        stop_group(child.proc, grace)

    def stop_all(self, grace: float = STOP_GRACE) -> None:
        """Stop every child: all at once, then those marked ``last`` (the master, so that nodes can still leave
        it cleanly); then end whatever they left running (recorded in :attr:`left`)."""
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
        self._sweep(min(grace, SWEEP_GRACE))

    def end_all(self) -> None:
        """End every child at once, with SIGKILL to each one's group, when every process of the run is in one of
        those groups (nothing is lost: no child gets to run its shutdown, and none is waited for); when some
        process left its group (a node's daemon), :meth:`stop_all` instead, so that the node may still end it
        as it shuts down, as it always could. For a run whose result is already written."""
        if self._link is None or not self._contained():
            self.stop_all()
            return
        for child in self.children:
            if child.running:
                child.stopped_by_us = True
            try:
                os.killpg(child.proc.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        deadline = time.monotonic() + 10.0
        for child in self.children:
            while (child.proc.poll() is None or _group_alive(child.proc.pid)) and time.monotonic() < deadline:
                time.sleep(0.005)
        self._sweep(SWEEP_GRACE)

    def _contained(self) -> bool:
        """Whether every living process below the keeper is in the process group of a child."""
        groups = {c.proc.pid for c in self.children}
        table = process_table()
        return all(table[pid][1] in groups for pid in descendants(self._link.proc.pid, table) if pid in table)

    def _sweep(self, grace: float) -> None:
        """Have the keeper end whatever is still below it, recorded in :attr:`left`."""
        if self._link is not None:
            ended = self._link.sweep(grace)
            with self._lock:
                known = {p.pid for p in self.left}
                self.left += [Leftover(self._names.get(e["owner"]), e["pid"], e["cmd"])
                              for e in ended if not e["own"] and e["pid"] not in known]

    def __enter__(self) -> Supervisor:
        with _ACTIVE_LOCK:
            _ACTIVE.add(self)
        if threading.current_thread() is threading.main_thread():   # elsewhere the caller's own handlers stay
            self._old[signal.SIGINT] = signal.getsignal(signal.SIGINT)
            for sig in (signal.SIGTERM, signal.SIGHUP):
                self._old[sig] = signal.signal(sig, _interrupt)
        return self

    def __exit__(self, *exc) -> None:
        try:
            self.stop_all()
        finally:
            with _ACTIVE_LOCK:
                _ACTIVE.discard(self)
            if self._link is not None:
                self._link.close()
            for sig, old in self._old.items():
                signal.signal(sig, old if old is not None else signal.SIG_DFL)
            self._old.clear()
