"""A node graded across worlds it has never seen: the course's stop_at_wall.py in 6 generated apartments and 6
arenas passes (the pass rate is printed); a deliberately over-tuned node — it drives for a fixed time that fits
the class's 5 m room and never looks at its LiDAR — fails most of them, each failing world named with the one
command that runs it again. Real rosmaster, real rospy nodes, --rate max, two worlds at once."""

from __future__ import annotations

import json
import re
from pathlib import Path

from conftest import CliRunner

from bridgetools import NODES, tag  # noqa: F401  (fixture)
from worldgen.cli import main
from worldgen.packages.course_ros1 import write_course

OVER_TUNED = NODES / "stop_after_fixed_time.py"


def test_the_course_node_passes_across_worlds_and_an_over_tuned_one_fails_most(tmp_path, tag):  # noqa: F811
    node = write_course(tmp_path / "course") / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    runner = CliRunner()
    for source in ("rooms:6", "arena:6@100"):
        good = runner.invoke(main, ["run", "--worlds", source, str(node), "--task", "stop-at-wall", "--rate", "max",
                                    "-j", "2", "--min-pass", "0.8"])
        assert "Traceback" not in good.output, good.output
        rate = re.search(r"stop-at-wall passed in (\d+) of 6 worlds \((\d+)%\)", good.stdout)
        assert rate and int(rate.group(1)) >= 5 and good.exit_code == 0, good.output
        assert len([line for line in good.stdout.splitlines() if re.match(r"(rooms|arena)_\d+ ", line)]) == 6
    # the same 12 worlds, the over-tuned node: JSON and JUnit as run writes them
    junit = tmp_path / "over.xml"
    failed = []
    for source in ("rooms:6", "arena:6@100"):
        bad = runner.invoke(main, ["run", "--worlds", source, str(OVER_TUNED), "--task", "stop-at-wall", "--rate",
                                   "max", "-j", "2", "--format", "json", "--junit", str(junit), "--force"])
        assert bad.exit_code == 1 and "Traceback" not in bad.output, bad.output
        doc = json.loads(bad.stdout)
        assert doc["total"] == 6 and not doc["ok"]
        failed += [w for w in doc["worlds"] if not w["ok"]]
        assert junit.read_text().count('<testcase classname="') >= 6
    assert len(failed) >= 9, [w["world"] for w in failed]   # most of the 12
    one = failed[0]
    assert one["rerun"] == (f"worldgen run --worlds {one['source']} {OVER_TUNED} --task stop-at-wall --rate max")
    assert re.fullmatch(r"(rooms|arena):1@\d+", one["source"])
    # the rerun command, as printed, runs that one world alone, with the same verdict
    again = runner.invoke(main, one["rerun"].split()[1:] + ["--format", "json"])
    assert again.exit_code == 1 and json.loads(again.stdout)["total"] == 1


def test_every_submission_of_a_class_meets_the_same_worlds(tmp_path, monkeypatch, tag):  # noqa: F811
    """A folder of submissions with --worlds: each submission in each world, its own pass rate, the failing
    (submission, world) pairs named with the command that reruns that submission's node there alone."""
    import shutil

    node = write_course(tmp_path / "course") / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    runner = CliRunner()
    for name, script in (("ann", node), ("ben", OVER_TUNED)):
        made = runner.invoke(main, ["scaffold", f"{name}_lab", "rospy", "geometry_msgs", "sensor_msgs", "-p",
                                    str(tmp_path / "subs")])
        assert made.exit_code == 0, made.output
        shutil.copy(script, tmp_path / "subs" / f"{name}_lab" / "scripts" / "stop_at_wall.py")
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(main, ["run", "subs/", "--worlds", "arena:2@5", "--task", "stop-at-wall", "--rate", "max",
                                  "-j", "2", "--min-pass", "0.5", "--format", "json"])
    assert result.exit_code == 1 and "Traceback" not in result.output, result.output
    doc = json.loads(result.stdout)
    marks = {Path(s["path"]).name: (s["passed"], s["total"], s["ok"]) for s in doc["submissions"]}
    assert marks == {"ann_lab": (2, 2, True), "ben_lab": (0, 2, False)}
    reruns = sorted(w["rerun"] for w in doc["worlds"] if not w["ok"])
    assert reruns == [f"worldgen run --worlds arena:1@{s} subs/ben_lab/scripts/stop_at_wall.py --task stop-at-wall "
                      "--rate max" for s in (5, 6)]
    refused = runner.invoke(main, ["run", "subs/", "--worlds", "arena:2", "--spawn", "0,0", "--task", "spin"])
    assert refused.exit_code == 2 and "--spawn is for one world" in refused.output
