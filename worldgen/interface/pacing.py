"""How fast simulated time runs: at a fixed multiple of real time, or, at ``--rate max``, as fast as the nodes
under test keep up (:class:`Governor`), judged by the bytes of messages waiting unread in their sockets
(:class:`Backlog`) and, clock by clock, by whether they have taken the last one in (:class:`Followers`).

Those bytes are read from the kernel's socket tables (/proc/net/tcp), which costs the kernel a walk of every TCP
socket of the machine: about 5 ms per table on a busy machine, whether the nodes have two sockets or twenty.
Looking 20 times a second from the stepping loop took a fifth of its time (a third of what a camera run at max
could do); a thread of its own looks instead, and the loop takes the latest answer. IPv6 sockets are looked at only
when ROS uses IPv6 (``ROS_IPV6=on``, rospy's own rule), which halves the cost.
"""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path

BACKLOG = int(os.environ.get("WG_BACKLOG", "4096"))  # bytes unread by the nodes: they are falling behind
CHECK_EVERY = float(os.environ.get("WG_CHECK", "0.05"))  # s of real time between looks at the nodes' sockets


def unread_bytes(pids: list[int], udp: bool = False) -> int:
    """Bytes waiting unread in the TCP sockets of processes ``pids`` (Linux: their socket inodes in /proc/PID/fd,
    matched with the rx_queue column of /proc/net/tcp, and tcp6 when ROS uses IPv6), or in their UDP sockets with
    ``udp`` (DDS: /proc/net/udp and udp6); 0 where /proc cannot tell."""
    inodes = set()
    for pid in pids:
        try:
            for fd in os.listdir(f"/proc/{pid}/fd"):
                try:
                    target = os.readlink(f"/proc/{pid}/fd/{fd}")
                except OSError:
                    continue
                if target.startswith("socket:["):
                    inodes.add(target[8:-1])
        except OSError:
            continue
    if not inodes:
        return 0
    total = 0
    if udp:
        tables: tuple = ("/proc/net/udp", "/proc/net/udp6")
    else:
        tables = ("/proc/net/tcp", "/proc/net/tcp6") if os.environ.get("ROS_IPV6") == "on" else ("/proc/net/tcp",)
    for table in tables:
        try:
            lines = Path(table).read_text().splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            fields = line.split()
            if len(fields) > 9 and fields[9] in inodes:
                total += int(fields[4].split(":")[1], 16)
    return total


class Backlog:
    """What the watched processes leave unread, measured every :data:`CHECK_EVERY` s in a thread of its own:
    ``sample`` is (when, bytes), the smaller of two looks in a row (what persists, not a message in flight)."""

    def __init__(self, pids: list[int], udp: bool = False):
        self.pids, self.udp = list(pids), udp
        self.sample: tuple[float, int] | None = None
        self.stopped = threading.Event()
        self.thread = threading.Thread(target=self._watch, name="worldgen-backlog", daemon=True)
        self.thread.start()

    def _watch(self) -> None:
        previous = 0
        while not self.stopped.wait(CHECK_EVERY):
            now = unread_bytes(self.pids, self.udp)
            self.sample, previous = (time.monotonic(), min(now, previous)), now

    def stop(self) -> None:
        self.stopped.set()


class Governor:
    """Paces simulated time: at ``rate`` × real time, or, at rate 0 (max), as fast as the watched processes (the
    nodes under test) keep up: when more than :data:`BACKLOG` bytes of messages wait unread in their sockets, they
    are falling behind, and the pace drops below what was achieved; when nothing waits, it rises again, up to no
    limit. (A node that lags reacts late in simulated time, which Gazebo at real time never shows.)"""

    def __init__(self, rate: float, backlog: Backlog | None, sim_t: float = 0.0):
        self.rate, self.backlog = rate, backlog
        self.anchor_wall, self.anchor_sim = time.monotonic(), sim_t
        self.limit = rate if rate > 0 else None   # None: no limit
        self.last_check = self.anchor_wall

    def pace(self, sim_t: float) -> None:
        now = time.monotonic()
        sample = self.backlog.sample if self.rate <= 0 and self.backlog is not None else None
        if sample is not None and sample[0] > self.last_check:
            waiting = sample[1]
            achieved = (sim_t - self.anchor_sim) / max(now - self.anchor_wall, 1e-6)
            if waiting > BACKLOG:
                self.limit = max(1.0, min(achieved, self.limit or achieved) * 0.7)
            elif waiting == 0 and self.limit is not None:
                self.limit = self.limit * 1.5 if self.limit < 200 else None
            self.anchor_wall, self.anchor_sim, self.last_check = now, sim_t, now
        if self.limit is not None:
            ahead = self.anchor_wall + (sim_t - self.anchor_sim) / self.limit - now
            if ahead > 0.0005:
                time.sleep(ahead)


FOLLOW_WAIT = 0.002      # s of real time a /clock waits at most for the nodes to take it in
PROBATION = 3.0          # s of simulated time every /clock waits, whatever the nodes do
STRIKES = 5              # a thread still running after that many such waits in a row is not waited for
LOOK_THREADS = 0.25      # s of real time between looks for new threads


class Followers:
    """At ``--rate max``, each /clock waits for the nodes to take it in: until no thread of theirs (``pids``), nor
    any of the simulator's own but the stepping one and ``skip`` (their native ids), is running or about to
    (state R in ``/proc/PID/task/TID/stat``): the clock's reader is done, a loop it woke (``rospy.Rate``,
    ``rospy.sleep``, a timer) has run and published, and the simulator has taken what it published.

    Without it a node's loop wakes when its thread gets the processor, by which time the simulator may have run
    several clocks on (rospy keeps only the latest of the clocks waiting): it then acts at a later simulated time
    than in Gazebo, more often the busier the machine. A wait lasts at most :data:`FOLLOW_WAIT`; a thread that is
    still running after :data:`STRIKES` waits in a row (a busy loop) is not waited for until it is seen resting.
    Each look reads a few hundred bytes per thread from files kept open (about 4 µs a thread).

    Waiting costs the simulator the nodes' share of the processor at every clock, which only nodes that act on
    their own time need: :meth:`due` says when to. Every clock waits in the first :data:`PROBATION` simulated
    seconds; after them only while the robot's commands have not all been answers to scans (:meth:`answered`): a
    node that drives on a timer or a ``rospy.Rate`` loop, or none yet, is followed to the end; one that only
    answers scans (and so is waited for after each, see :mod:`.loop`) no longer, until a command comes
    unasked."""

    def __init__(self, pids, skip=()):
        self.pids = [int(p) for p in pids]
        self.own = os.getpid()
        self.skip = {threading.get_native_id(), *skip}
        self.files: dict[tuple[int, int], int] = {}
        self.strikes: dict[tuple[int, int], int] = {}
        self.looked = 0.0
        self.counted, self.answers, self.unasked = 0, False, False

    def due(self, sim_t: float, commands: int) -> bool:
        """Whether the clock at simulated time ``sim_t`` waits for the nodes, the robot having had ``commands``
        commands so far (see the class docstring)."""
        if commands != self.counted:   # commands that answered no scan
            self.unasked, self.counted = True, commands
        return sim_t < PROBATION or self.unasked or not self.answers

    def answered(self, commands: int) -> None:
        """After a scan's wait for its answer: the commands that came meanwhile (``commands`` in all) answered it."""
        if commands != self.counted:
            self.answers, self.counted = True, commands

    def _look_for_threads(self) -> None:
        now = time.monotonic()
        if now - self.looked < LOOK_THREADS:
            return
        self.looked = now
        seen = set()
        for pid in self.pids + [self.own]:
            try:
                tids = [int(t) for t in os.listdir(f"/proc/{pid}/task")]
            except OSError:
                continue
            for tid in tids:
                if pid == self.own and tid in self.skip:
                    continue
                seen.add((pid, tid))
                if (pid, tid) not in self.files:
                    try:
                        self.files[(pid, tid)] = os.open(f"/proc/{pid}/task/{tid}/stat", os.O_RDONLY)
                    except OSError:
                        pass
        for key in set(self.files) - seen:
            os.close(self.files.pop(key))
            self.strikes.pop(key, None)

    def _running(self) -> list[tuple[int, int]]:
        """The threads running or runnable now, but those struck out (whose strikes reset when seen resting)."""
        found = []
        for key, fd in self.files.items():
            try:
                data = os.pread(fd, 512, 0)
            except OSError:
                continue
            end = data.rfind(b")")
            if end > 0 and data[end + 2:end + 3] == b"R":
                if self.strikes.get(key, 0) < STRIKES:
                    found.append(key)
            else:
                self.strikes.pop(key, None)
        return found

    def wait(self) -> None:
        """Until the nodes have taken the clock just published in (see the class docstring)."""
        self._look_for_threads()
        deadline = time.monotonic() + FOLLOW_WAIT
        running = self._running()
        while running:
            if time.monotonic() > deadline:
                for key in running:
                    self.strikes[key] = self.strikes.get(key, 0) + 1
                return
            time.sleep(0.00005)
            running = self._running()

    def close(self) -> None:
        for fd in self.files.values():
            os.close(fd)
        self.files.clear()
