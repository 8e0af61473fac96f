"""The simulator's step loop, the same for every transport: step the physics and say what is due when.

The IMU goes out every other 1/240 s step (120 Hz of simulated time), and so does ``/clock`` on ROS 1 and Jazzy:
Gazebo's gazebo_ros publishes it at 100 Hz, ``rospy.Rate`` and rclpy timer loops up to 30 Hz wake within 8 ms of
when they should, and publishing every step would double the clock traffic every node receives for nothing.
Humble's gazebo_ros publishes it at 10 Hz, and so does the simulator there (the wire's ``clock_every``). The drive plugins' messages
go out at their update rate (30 Hz), the scans at the LiDAR's (5 Hz), the pictures at the camera's (30 Hz).

``rate`` paces simulated time at that many times real time (:mod:`.pacing`); 0 runs as fast as it goes, and then,
after each scan that some node listens to, waits (at most 50 ms of real time) for the ``cmd_vel`` that answers it,
so that a node reacting to scans reacts within the same scan period, as it does in Gazebo at real time.

At rate 0 ``/clock`` goes out only as often as a node can tell (every message costs the simulator a write and
every node a wake-up, and at full speed 2 400 of them in 20 simulated seconds were most of the loop's time): on a
60 Hz lattice of simulated time (:data:`MAX_CLOCK_EVERY` steps), so that ``rospy.Rate`` loops and rclpy timers at
any rate dividing 60 Hz (1, 2, 3, 4, 5, 6, 10, 12, 15, 20, 30, 60 Hz) wake exactly when they would with a clock
every other step, and before every other message: at each drive update and scan (whose callbacks then read the
time of the message), and every other step while some node listens to the IMU. A node can only learn the time
from ``/clock``, when a message comes or when it wakes, and it wakes on the first ``/clock`` at or past its
deadline; between those it cannot tell whether the clock went out. And a /clock waits, a little, for the nodes
to take it in (:class:`.pacing.Followers`), so that a loop it wakes runs at that simulated time, not at a later one
the simulator has run on to meanwhile: every clock while the nodes may act on their own time, none once they have
shown they only answer scans.

The transport's simulator object (a :class:`Wire`) publishes; this module only decides when.
"""

from __future__ import annotations

import time

from .pacing import Backlog, Followers, Governor

CLOCK_EVERY = 2          # physics steps per /clock and /imu message
MAX_CLOCK_EVERY = 4      # physics steps per /clock at rate max, unless a message goes out between (see above)
ANSWER_WAIT = 0.05       # s of real time to wait for the cmd_vel answering a scan at rate max
PAUSED_CLOCK = 0.1       # s of real time between /clock messages while paused


class Wire:
    """What the loop asks of a transport's simulator (the ROS 1 and ROS 2 ones implement it): ``session`` (the
    :class:`~worldgen.sim.session.Session`), ``paused``, ``person`` (a :class:`.simulator.Person`, or None),
    ``robots`` (the transport's robots: each with ``io``, its :class:`~.robot.RobotIO`, ``cameras``, each with
    ``every`` and ``publish(session, t)``, and ``publish_scan(session)``, True when some node listens),
    ``graded_robot`` (the one of them whose answers are waited for; ``graded``, its RobotIO), and the methods
    below."""

    session = None
    clock_every = CLOCK_EVERY   # physics steps between two /clock messages
    paused = False
    person = None
    robots: list = []
    graded_robot = None
    graded = None

    def shut_down(self) -> bool:
        raise NotImplementedError

    def drain(self) -> None:
        """Do what service calls asked, between two physics steps."""

    def publish_clock(self) -> None:
        raise NotImplementedError

    def fast_heard(self) -> bool:
        """Whether some node listens to what :meth:`publish_fast` sends (then, at rate max, /clock goes with it)."""
        return True

    def publish_fast(self, dt: float) -> None:
        """Each robot's IMU (``dt`` apart), and any per-step state topics."""
        raise NotImplementedError

    def publish_drive(self) -> None:
        raise NotImplementedError

    def publish_cameras(self, step: int) -> None:
        """The pictures due at physics step ``step`` that some node looks at."""
        for robot in self.robots:
            for camera in robot.cameras:
                if step % camera.every == 0:
                    camera.publish(self.session, self.session.t)

    def publish_scans(self) -> bool:
        """Each robot's scan; True when some node listens to the graded robot's."""
        listened = False
        for robot in self.robots:
            robot.io.answered.clear()
            heard = robot.publish_scan(self.session)
            listened = listened or (heard and robot is self.graded_robot)
        return listened

    def commanded(self) -> bool:
        """Whether some node publishes the graded robot's velocity commands (worth waiting for an answer)."""
        raise NotImplementedError


def run_loop(wire: Wire, rate: float, duration: float | None, pids=(), *, udp: bool = False) -> dict:
    """Step the session, publishing as the module docstring says, until ``duration`` simulated seconds have
    passed (None: until shut down). ``pids``: the nodes whose unread messages pace a run at rate max (in their
    TCP sockets, or UDP ones with ``udp``). Returns the timing numbers."""
    s = wire.session
    end_step = None if duration is None else round(duration / s.time_step)
    wall0, interrupted = time.monotonic(), False
    wire.publish_clock()
    wire.publish_drive()
    backlog = Backlog(list(pids), udp=udp) if rate <= 0 and pids else None
    followers = None
    if backlog is not None and wire.graded is not None:
        followers = Followers(pids, skip=[backlog.thread.native_id])
    try:
        _step_loop(wire, rate, end_step, backlog, followers)
    except KeyboardInterrupt:
        interrupted = True
    finally:
        if backlog is not None:
            backlog.stop()
        if followers is not None:
            followers.close()
    wall = time.monotonic() - wall0
    return {"sim_time_s": s.t, "wall_time_s": wall, "real_time_factor": s.t / wall if wall > 0 else None,
            "interrupted": interrupted}


def _step_loop(wire: Wire, rate: float, end_step: int | None, backlog: Backlog | None,
               followers: Followers | None) -> None:
    s = wire.session
    dt = s.time_step
    drive_every = s._update_every
    scan_every = max(1, round(1.0 / (s.lidar.update_rate * dt))) if s.lidar is not None else 0
    person = wire.person
    governor = Governor(rate, backlog)
    clock_every, sparse = wire.clock_every, rate <= 0 and wire.clock_every < MAX_CLOCK_EVERY
    if sparse:
        clock_every = MAX_CLOCK_EVERY
    step = 0
    while not wire.shut_down() and (end_step is None or step < end_step):
        wire.drain()
        if wire.paused:
            wire.publish_clock()   # the clock stands still
            time.sleep(PAUSED_CLOCK)
            governor = Governor(rate, backlog, s.t)   # paced afresh from where it stopped
            continue
        if person is not None:
            s.move_body(person.body, *person.xy(s.t + dt))
        s.run(dt)
        step += 1
        if step % clock_every == 0 or sparse and _message_due(wire, step, drive_every, scan_every):
            wire.publish_clock()
            if followers is not None and followers.due(s.t, wire.graded.cmd_count):
                followers.wait()
        if step % CLOCK_EVERY == 0:
            wire.publish_fast(dt * CLOCK_EVERY)
            governor.pace(s.t)
        if step % drive_every == 0:
            wire.publish_drive()
        wire.publish_cameras(step)
        if scan_every and step % scan_every == 0:
            listened = wire.publish_scans()
            if rate <= 0 and listened and wire.commanded():
                wire.graded.answered.wait(ANSWER_WAIT)
                if followers is not None:
                    followers.answered(wire.graded.cmd_count)


def _message_due(wire: Wire, step: int, drive_every: int, scan_every: int) -> bool:
    """Whether a message goes out at physics step ``step`` (drive update, scan, or a listened IMU step), so that
    a sparse ``/clock`` must go out first."""
    return (step % drive_every == 0 or (scan_every and step % scan_every == 0) or
            (step % CLOCK_EVERY == 0 and wire.fast_heard()))
