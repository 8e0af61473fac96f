"""Simulated time as a node sees it: at ``--rate max`` /clock goes out only as often as a node can tell (a 60 Hz
lattice and before each message, each clock taken in before the next), and a node's ``rospy.Rate`` loops (10 Hz
and 30 Hz) and ``rospy.sleep`` still wake exactly when they ask to: each deadline is a /clock value, never one
passed over, and the loop reads that time on waking; at a paced rate every other physics step (120 Hz) as
Gazebo's plugins see it.

Real rosmaster and rospy (Debian's); the node is tests/rosnodes/rate_loops.py.
"""

from __future__ import annotations

import bisect
import json

import pytest
from conftest import CliRunner

from bridgetools import NODES, ROOM, tag  # noqa: F401 (a fixture)
from worldgen.cli import main

DURATION = 3.0
NS = 1_000_000_000


def read_wakes(path) -> tuple[list[int], dict[str, list[tuple[int, int]]]]:
    """The /clock values published (sorted, once each) and, per loop, its (deadline, woke) pairs."""
    loops: dict = {}
    for line in path.read_text().splitlines():
        name, deadline, woke = line.split()
        loops.setdefault(name, []).append((int(deadline), int(woke)))
    clocks = sorted({int(v) for v in path.with_name(path.name + ".clock").read_text().split()})
    return clocks, loops


def first_clock_at_or_after(clocks: list[int], t: int) -> int | None:
    i = bisect.bisect_left(clocks, t)
    return clocks[i] if i < len(clocks) else None


@pytest.mark.parametrize("rate, per_second", [("max", 60), ("4", 120)])
def test_rate_and_sleep_loops_wake_at_their_deadlines(tag, tmp_path, rate, per_second):
    out = tmp_path / "wakes.txt"
    result = CliRunner().invoke(main, ["run", str(ROOM), str(NODES / "rate_loops.py"), f"out:={out}", "--rate", rate,
                                       "--duration", str(DURATION), "--format", "json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["metrics"]["cmd_vel_messages"] > 0
    clocks, loops = read_wakes(out)
    heard = clocks[-1]   # the recorder may lag behind when the run ends
    assert heard > DURATION * NS / 2
    ticks = [c for c in clocks if c > 0]
    assert len(ticks) == pytest.approx(heard / NS * per_second, abs=2), ticks[:10]   # 60 Hz at max, 120 Hz paced
    for name in ("rate10", "rate30", "sleep0.25"):
        pairs = loops[name]
        assert len(pairs) >= 5, name   # it ran (one that falls behind skips deadlines, as rospy.Rate does)
        assert all(woke >= deadline for deadline, woke in pairs), name   # never early
        for deadline, woke in pairs[1:]:   # the first sleeps from time 0 (rospy waits for a clock first)
            if deadline <= heard:
                # the node wakes on the first /clock at or past its deadline: the deadline itself (within the ns
                # that rospy's Duration(1/30) sheds each period), so a node that keeps up wakes when it asked to
                tick = first_clock_at_or_after(clocks, deadline)
                assert tick - deadline < 1000, (name, deadline, tick)
        if rate == "max":
            # and they do: after the first (from time 0 rospy waits for a clock, then sleeps the period), each
            # wake reads its deadline's time, each clock waiting for the node to take it in (at a paced rate the
            # clock keeps its pace whatever the node does; a loaded machine may leave a few wakes behind)
            exact = [woke - deadline < 1000 for deadline, woke in pairs[1:]]
            assert sum(exact) >= 0.9 * len(exact), (name, pairs)
    rate10 = [d for d, _ in loops["rate10"]]
    # made at time 0, the loop keeps its own lattice (each deadline one period after the last) unless it has fallen
    # more than two periods behind (a loaded machine leaving its thread unscheduled): then rospy.Rate starts anew
    # from the time it was called at, more than three periods after the last deadline; never anything between
    period = NS // 10
    assert rate10[0] == period
    assert all(b - a == period or b - a > 3 * period for a, b in zip(rate10, rate10[1:])), rate10[:20]
