"""A teaching assistant grades a folder of submissions in one ``worldgen validate FOLDER`` call: every catkin
package found (in workspaces, metapackage folders, nested), each checked with the spawn its own launch file gives,
one verdict per submission in JSON and JUnit; ``--shard K/N`` splits the class over CI runners; folders without
packages, missing paths and worlds without any spawn are reported plainly."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from lxml import etree

from conftest import CliRunner
from worldgen.cli import main


def cli(*args, check_code=None):
    result = CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)
    if check_code is not None:
        assert result.exit_code == check_code, result.output
    return result


def write_spec(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


# Ana: a workspace (with an install space that holds a copy of her manifest: not a second package), a room far
# from the origin, spawned off its centre. Ben: a room with a whole wall missing. Cara: a metapackage and a member
# whose launch file starts a world that is not there.
ANA = """name: ana_room
rooms:
  - name: lab
    rect: {center: [10, 5], size: [4, 4]}
robot: {model: burger, at: [9.2, 4.4], yaw: 0.5}
"""
BEN = """name: ben_room
segments:
  - {from: [-10, 1], to: [-6, 1]}
  - {from: [-6, 1], to: [-6, 5]}
  - {from: [-6, 5], to: [-10, 5]}
robot: {model: burger, at: [-7.5, 3.3], yaw: 0}
"""
CARA = """name: cara_room
rooms:
  - name: hall
    rect: {center: [0, -8], size: [4, 3]}
robot: {model: burger, at: [0.6, -8.2], yaw: 0}
"""


@pytest.fixture(scope="module")
def submissions(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("grading")
    subs = root / "submissions"
    ana_src = subs / "ana" / "catkin_ws" / "src"
    ana_src.mkdir(parents=True)
    cli("scaffold", "ana_world", "rospy", "--world", write_spec(root / "ana.yaml", ANA), "-p", ana_src, check_code=0)
    install = subs / "ana" / "catkin_ws" / "install" / "share" / "ana_world"
    install.mkdir(parents=True)
    (install / "package.xml").write_text((ana_src / "ana_world" / "package.xml").read_text())
    (subs / "ana" / "catkin_ws" / "devel").mkdir()
    (subs / "ben").mkdir()
    cli("scaffold", "ben_world", "rospy", "-p", subs / "ben", check_code=0)
    cli("build", write_spec(root / "ben.yaml", BEN), "--package", subs / "ben" / "ben_world", check_code=0)
    (subs / "cara").mkdir()
    cli("scaffold", "cara", "--meta", "-p", subs / "cara", check_code=0)
    cli("scaffold", "cara_world", "rospy", "--world", write_spec(root / "cara.yaml", CARA), "-p", subs / "cara",
        check_code=0)
    for world in (subs / "cara" / "cara_world" / "worlds").glob("*.world"):
        world.unlink()   # the launch file's world is missing
    return subs


@pytest.fixture(scope="module")
def graded(submissions):
    report = submissions.parent / "out.xml"
    proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", str(submissions), "-j", "2",
                           "--junit", str(report), "--format", "json"], capture_output=True, text=True, timeout=300)
    assert "Traceback" not in proc.stderr, proc.stderr
    return proc, json.loads(proc.stdout), etree.parse(str(report)).getroot()


def rows(doc, who: str) -> list[dict]:
    return [r for r in doc["results"] if f"/{who}/" in r["path"] + "/"]


def test_the_folder_is_graded_per_package_with_each_launch_files_spawn(submissions, graded):
    proc, doc, _ = graded
    assert proc.returncode == 1
    ana_pkg = submissions / "ana" / "catkin_ws" / "src" / "ana_world"
    launch = ana_pkg / "launch" / "turtlebot3_in_ana_room.launch"
    # sorted by path: ana, ben, cara's metapackage, cara's world package; install/ is not searched
    assert [r["path"] for r in doc["results"]] == [
        str(ana_pkg), str(launch),
        str(submissions / "ben" / "ben_world"), str(submissions / "ben" / "ben_world" / "launch" /
                                                    "turtlebot3_in_ben_room.launch"),
        str(submissions / "cara" / "cara"),
        str(submissions / "cara" / "cara_world"), str(submissions / "cara" / "cara_world" / "launch" /
                                                      "turtlebot3_in_cara_room.launch")]
    assert "submissions: 4 catkin packages found" in proc.stderr
    # Ana: her room is 10 m from the origin; her launch file's spawn (9.2, 4.4, yaw 0.5) is used and passes
    ana = rows(doc, "ana")
    assert all(r["ok"] for r in ana), [f for r in ana for f in r["findings"]]
    assert ana[1]["spawn"] == [9.2, 4.4, 0.5] and ana[1]["spawn_source"] == f"from launch file {launch}"
    assert ana[1]["checks"][-4:] == ["settle", "lidar", "spin", "stop-at-wall"]
    assert ana[1]["metrics"]["enclosed"] is True and ana[1]["metrics"]["stop_touched"] == []
    # Ben: the room's left side is missing: a 4 m way out, located
    ben_launch = rows(doc, "ben")[1]
    assert ben_launch["ok"] is False and ben_launch["spawn"] == [-7.5, 3.3, 0.0]
    [gap] = ben_launch["metrics"]["gaps"]
    assert gap["width"] == pytest.approx(4.0, abs=0.2) and math.dist(gap["centre"], (-10, 3)) < 0.2
    # Cara: the metapackage needs no launch file; the launch row fails on the missing world, said there once
    meta, world_pkg, world_launch = rows(doc, "cara")
    assert meta["ok"] is True and meta["checks"] == ["package"]
    assert world_pkg["ok"] is True and world_pkg["findings"] == []
    [said] = [f for f in world_launch["findings"] if "cara_room.world" in f["message"]]
    assert said["severity"] == "error" and said["message"].endswith("cara_room.world does not exist")
    assert world_launch["ok"] is False and world_launch["skipped"]["enclosed"] == "no world to read"
    # progress: one line per finished file on stderr, never on stdout
    assert sum(line.startswith("[") for line in proc.stderr.splitlines()) == 7


def test_the_junit_report_gives_each_submission_its_verdict(graded):
    _, doc, junit = graded
    failing = {c.get("classname") for c in junit.iter("testcase") if c.find("failure") is not None}
    assert failing == {r["path"] for r in doc["results"] if not r["ok"]}
    assert len(failing) == 2 and all("/ben/ben_world/launch/" in p or "/cara/cara_world/launch/" in p
                                     for p in failing)
    classes = {c.get("classname") for c in junit.iter("testcase")}
    assert classes == {r["path"] for r in doc["results"]}


def test_shards_are_disjoint_cover_everything_and_do_not_depend_on_argument_order(submissions, tmp_path):
    folders = [submissions / "ana", submissions / "ben", submissions / "cara"]
    shards = []
    for k in (1, 2, 3):
        report = tmp_path / f"shard{k}.xml"
        forward = cli("validate", *folders, "--skip-sim", "--format", "json", "--shard", f"{k}/3", "--junit",
                      report)
        backward = cli("validate", *reversed(folders), "--skip-sim", "--format", "json", "--shard", f"{k}/3")
        paths = [r["path"] for r in json.loads(forward.stdout)["results"]]
        assert sorted(paths) == sorted(r["path"] for r in json.loads(backward.stdout)["results"])
        assert {c.get("classname") for c in etree.parse(str(report)).getroot().iter("testcase")} == set(paths)
        shards.append(paths)
    every = [r["path"] for r in json.loads(cli("validate", *folders, "--skip-sim", "--format", "json").stdout)[
        "results"]]
    assert sorted(p for s in shards for p in s) == sorted(every) and len(every) == 7
    assert all(len(s) in (2, 3) for s in shards)


@pytest.mark.parametrize("bad", ["0/3", "4/3", "1/0", "x/2", "1-2"])
def test_a_bad_shard_is_bad_usage(submissions, bad):
    proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", str(submissions), "--shard", bad],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stdout == ""
    assert len(proc.stderr.strip().splitlines()) == 1 and "--shard" in proc.stderr


def test_a_missing_path_is_a_failed_row_and_the_rest_still_run(submissions, tmp_path):
    report = tmp_path / "junit.xml"
    missing = submissions / "dan"
    out = cli("validate", missing, submissions / "ana", "--skip-sim", "--format", "json", "--junit", report)
    assert out.exit_code == 1
    doc = json.loads(out.stdout)
    first, *rest = doc["results"]
    assert first["path"] == str(missing) and first["ok"] is False
    assert [(f["check"], f["message"]) for f in first["findings"]] == [("input", "no such file or folder")]
    assert len(rest) == 2 and all(r["ok"] for r in rest)
    [case] = etree.parse(str(report)).getroot().xpath(f"//testcase[@classname='{missing}']")
    assert case.get("name") == "input" and case.find("failure") is not None
    # every argument bad: bad usage, one line
    assert cli("validate", missing, submissions / "eve").exit_code == 2


def test_a_folder_without_packages_is_searched_for_worlds_and_specs(tmp_path):
    folder = tmp_path / "worlds"
    (folder / "deep").mkdir(parents=True)
    write_spec(folder / "ana_room.yaml", ANA)
    cli("build", folder / "ana_room.yaml", "-o", folder, check_code=0)   # ana_room.world beside it: the spec
    assert (folder / "ana_room.world").is_file()                          # stands for both
    write_spec(folder / "deep" / "cara.yaml", CARA)
    cli("build", folder / "deep" / "cara.yaml", "-o", tmp_path / "built", check_code=0)
    (tmp_path / "built" / "cara_room.world").rename(folder / "deep" / "other.world")
    out = cli("validate", folder, "--skip-sim", "--format", "json")
    assert out.exit_code == 0, out.output
    doc = json.loads(out.stdout)
    assert [r["path"] for r in doc["results"]] == [str(folder / "ana_room.yaml"), str(folder / "deep" / "cara.yaml"),
                                                   str(folder / "deep" / "other.world")]
    assert f"{folder}: no catkin package; 1 world file, 2 specs found" in out.stderr
    empty = tmp_path / "empty"
    empty.mkdir()
    out = cli("validate", empty)
    assert out.exit_code == 2 and "holds no catkin package, world file or spec" in out.output


TWO_ROOMS = """name: apart
rooms:
  - name: big
    rect: {center: [4, 4], size: [4, 3]}
  - name: small
    rect: {center: [-3, 0], size: [2, 2]}
"""


def test_no_spawn_checks_every_closed_room_from_its_deepest_point(tmp_path):
    spec = write_spec(tmp_path / "apart.yaml", TWO_ROOMS)
    out = cli("validate", spec, "--skip-sim", "--format", "json")
    assert out.exit_code == 0, out.output
    big, small = json.loads(out.stdout)["results"]
    assert (big["room"], small["room"]) == (1, 2)
    assert big["spawn"] == [4.0, 4.0, 0.0] and small["spawn"] == [-3.0, 0.0, 0.0]
    assert big["spawn_source"].startswith("no spawn given: checked from the deepest free point of room 1 at "
                                          "(4.00, 4.00)")
    assert small["spawn_source"] == "no spawn given: checked from the deepest free point of room 2 at (-3.00, 0.00)"
    assert all(r["metrics"]["enclosed"] for r in (big, small))
    text = cli("validate", spec, "--skip-sim").stdout
    assert "apart.yaml [room 2]" in text   # (long paths are shortened from the left in the table)
    # a world with no closed room at all says so, and the enclosed check locates the way out
    no_robot = BEN.replace("robot: {model: burger, at: [-7.5, 3.3], yaw: 0}\n", "")
    open_spec = write_spec(tmp_path / "ben_spec.yaml", no_robot)
    world = tmp_path / "open.world"
    cli("build", open_spec, "-o", tmp_path, check_code=0)
    (tmp_path / "ben_room.world").rename(world)
    out = cli("validate", world, "--skip-sim", "--format", "json")
    [r] = json.loads(out.stdout)["results"]
    assert out.exit_code == 1 and r["spawn_source"].startswith("no spawn given and this world has no closed room")
    assert r["metrics"]["gaps"][0]["width"] == pytest.approx(4.0, abs=0.2)


def test_drive_in_a_folder_drives_each_launch_files_world_from_its_spawn(submissions):
    out = cli("drive", submissions, "--format", "json")
    doc = json.loads(out.stdout)
    assert out.exit_code == 1 and doc["ok"] is False
    ana, ben, cara = doc["worlds"]
    assert ana["world"].endswith("ana_world/launch/turtlebot3_in_ana_room.launch")
    assert ana["spawn"] == [9.2, 4.4, 0.5] and ana["spawn_source"].startswith("from launch file")
    assert ana["runs"][0]["final_distance"] == pytest.approx(0.5, abs=0.05) and ana["runs"][0]["contacts"] == []
    assert ben["spawn"] == [-7.5, 3.3, 0.0]
    assert cara["ok"] is False and "cannot be found" in cara["error"]
    refused = cli("drive", submissions, "--plot", submissions.parent / "steps.png")
    assert refused.exit_code == 2 and "--plot, --csv and --html take a single world" in refused.output


# ------------------------------------------------------------------------------------------ the README says so

def readme() -> str:
    from conftest import REPO

    return (REPO / "README.md").read_text(encoding="utf-8")


def run_readme_command(line: str, cwd: Path) -> subprocess.CompletedProcess:
    import shlex

    words = shlex.split(line)
    assert words[0] == "worldgen"
    return subprocess.run([sys.executable, "-m", "worldgen", *words[1:]], cwd=cwd, capture_output=True, text=True,
                          timeout=300)


def test_the_readme_grading_command_runs_as_written(submissions):
    import re

    [command] = re.findall(r"```sh\n(worldgen validate submissions/[^\n]*)\n```", readme())
    proc = run_readme_command(command, submissions.parent)
    assert proc.returncode == 1 and "Traceback" not in proc.stderr   # Ben's and Cara's submissions fail
    cases = etree.parse(str(submissions.parent / "report.xml")).getroot().iter("testcase")
    assert {c.get("classname") for c in cases if c.find("failure") is not None} == {
        "submissions/ben/ben_world/launch/turtlebot3_in_ben_room.launch",
        "submissions/cara/cara_world/launch/turtlebot3_in_cara_room.launch"}


def test_the_readme_text_report_is_what_validate_prints(tmp_path):
    import re

    from conftest import REPO

    block = re.search(r"```\n\$ (worldgen validate examples/[^\n]*)\n(.*?)```", readme(), flags=re.S)
    (tmp_path / "examples").symlink_to(REPO / "examples")
    proc = run_readme_command(block.group(1), tmp_path)
    assert proc.stdout == block.group(2)
    assert proc.returncode == 1 and (tmp_path / "report.xml").is_file()


def test_a_launch_file_that_only_runs_nodes_is_not_failed_for_having_no_world(tmp_path):
    cli("scaffold", "lab_b", "rospy", "-p", tmp_path, check_code=0)
    (tmp_path / "lab_b" / "launch" / "talk.launch").write_text(
        '<launch>\n  <node pkg="rospy_tutorials" type="talker" name="talker"/>\n</launch>\n')
    out = cli("validate", tmp_path, "--format", "json")
    package, launch = json.loads(out.stdout)["results"]
    assert out.exit_code == 0 and launch["ok"] is True and launch["checks"] == ["launch"]
    assert [f["message"] for f in launch["findings"] if f["check"] == "launch"] == [
        "starts no Gazebo world and spawns no robot (nodes only): nothing to simulate"]


@pytest.mark.parametrize("missing", ["s1", "s2"])
def test_students_packages_of_the_same_name_each_start_their_own_world(tmp_path, missing):
    spec = write_spec(tmp_path / "ana.yaml", ANA)
    for student in ("s1", "s2"):
        cli("scaffold", "my_world", "rospy", "--world", spec, "-p", tmp_path / "class" / student, check_code=0)
    for world in (tmp_path / "class" / missing / "my_world" / "worlds").glob("*.world"):
        world.unlink()
    out = cli("validate", tmp_path / "class", "--skip-sim", "--format", "json")
    verdicts = {r["path"]: r["ok"] for r in json.loads(out.stdout)["results"]}
    launch = "my_world/launch/turtlebot3_in_ana_room.launch"
    assert {Path(p).relative_to(tmp_path / "class").parts[0]: ok for p, ok in verdicts.items() if p.endswith(launch)} \
        == {"s1": missing != "s1", "s2": missing != "s2"}


def test_a_symlink_loop_in_a_class_folder_is_walked_once(tmp_path):
    """A link back up the tree (a student's `ln -s .. up`) neither hangs the search nor counts a package twice; a
    workspace's install space, holding copies of the manifests, is not searched."""
    from worldgen.check.discover import find_packages
    from worldgen.bridge.grade import submissions

    cli("scaffold", "lab_a", "rospy", "-p", tmp_path / "class" / "ana" / "src", check_code=0)
    (tmp_path / "class" / "ana" / ".catkin_workspace").write_text("")
    install = tmp_path / "class" / "ana" / "install" / "share" / "lab_a"
    install.mkdir(parents=True)
    (install / "package.xml").write_text((tmp_path / "class" / "ana" / "src" / "lab_a" / "package.xml").read_text())
    (tmp_path / "class" / "ana" / "src" / "up").symlink_to(tmp_path / "class")
    expected = [tmp_path / "class" / "ana" / "src" / "lab_a"]
    assert find_packages(tmp_path / "class") == expected
    assert submissions(tmp_path / "class") == expected
