"""A node graded across worlds it has never seen: the course's stop_at_wall.py in 10 generated apartments and 10
arenas passes (the pass rate is printed); a deliberately over-tuned node — it drives for a fixed time that fits
the class's 5 m room and never looks at its LiDAR — fails most of them, each failing world named with the one
command that runs it again. Real rosmaster, real rospy nodes, --rate max, two worlds at once."""

from __future__ import annotations

import json
import re

from conftest import CliRunner

from bridgetools import NODES, tag  # noqa: F401  (fixture)
from worldgen.cli import main
from worldgen.packages.course_ros1 import write_course

OVER_TUNED = NODES / "stop_after_fixed_time.py"


def test_the_course_node_passes_across_worlds_and_an_over_tuned_one_fails_most(tmp_path, tag):  # noqa: F811
    node = write_course(tmp_path / "course") / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    runner = CliRunner()
    for source in ("rooms:10", "arena:10@100"):
        good = runner.invoke(main, ["run", "--worlds", source, str(node), "--task", "stop-at-wall", "--rate", "max",
                                    "-j", "2", "--min-pass", "0.9"])
        assert "Traceback" not in good.output, good.output
        rate = re.search(r"stop-at-wall passed in (\d+) of 10 worlds \((\d+)%\)", good.stdout)
        assert rate and int(rate.group(1)) >= 9 and good.exit_code == 0, good.output
        assert len([line for line in good.stdout.splitlines() if re.match(r"(rooms|arena)_\d+ ", line)]) == 10
    # the same 20 worlds, the over-tuned node: JSON and JUnit as run writes them
    junit = tmp_path / "over.xml"
    failed = []
    for source in ("rooms:10", "arena:10@100"):
        bad = runner.invoke(main, ["run", "--worlds", source, str(OVER_TUNED), "--task", "stop-at-wall", "--rate",
                                   "max", "-j", "2", "--format", "json", "--junit", str(junit), "--force"])
        assert bad.exit_code == 1 and "Traceback" not in bad.output, bad.output
        doc = json.loads(bad.stdout)
        assert doc["total"] == 10 and not doc["ok"]
        failed += [w for w in doc["worlds"] if not w["ok"]]
        assert junit.read_text().count('<testcase classname="') >= 10
    assert len(failed) >= 15, [w["world"] for w in failed]   # most of the 20
    one = failed[0]
    assert one["rerun"] == (f"worldgen run --worlds {one['source']} {OVER_TUNED} --task stop-at-wall --rate max")
    assert re.fullmatch(r"(rooms|arena):1@\d+", one["source"])
    # the rerun command, as printed, runs that one world alone, with the same verdict
    again = runner.invoke(main, one["rerun"].split()[1:] + ["--format", "json"])
    assert again.exit_code == 1 and json.loads(again.stdout)["total"] == 1
