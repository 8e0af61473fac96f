"""A teaching assistant grades the course's own lab package, handed in unchanged by two students: its launch file
starts the world of another course package (``class_meeting_02_custom_gazebo_world``). That package is found
beside the submissions in the folder graded, or on ROS_PACKAGE_PATH; when it is nowhere, one finding per submission
says what to add (not the same cause three times: the package row, the launch row and the read of the file)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from conftest import CliRunner

from worldgen.bridge.grade import not_submissions, submissions
from worldgen.cli import main

WORLD_PACKAGE = "class_meeting_02_custom_gazebo_world"
LAB = "lab_a_stop_at_wall"
NO_PATHS = {"ROS_PACKAGE_PATH": None, "AMENT_PREFIX_PATH": None}


@pytest.fixture(scope="module", params=["noetic", "humble"])
def course(request, tmp_path_factory) -> Path:
    """The course's packages as ``worldgen course`` writes them for a stack: WORKSPACE/src/intro_robo."""
    workspace = tmp_path_factory.mktemp(f"course_{request.param}")
    done = CliRunner().invoke(main, ["course", "--ros", request.param, "-w", str(workspace)])
    assert done.exit_code == 0, done.output
    return workspace / "src" / "intro_robo"


def hand_in(course: Path, folder: Path, students=("alice", "bob")) -> Path:
    """Each student's copy of the lab package, unchanged, in ``folder/STUDENT/``."""
    for student in students:
        shutil.copytree(course / LAB, folder / student / LAB)
    return folder


def grade(folder: Path, env=None) -> tuple[int, dict]:
    done = CliRunner().invoke(main, ["validate", "--skip-sim", "--format", "json", str(folder)],
                              env={**NO_PATHS, **(env or {})})
    assert done.exit_code in (0, 1), done.output
    return done.exit_code, json.loads(done.stdout)


def naming(doc: dict, package: str) -> list:
    """(row, finding) for every finding that names ``package``."""
    return [(r["path"], f) for r in doc["results"] for f in r["findings"]
            if package in f["message"] or package in (f.get("fix") or "")]


def test_a_course_package_that_is_nowhere_is_one_finding_per_submission(course, tmp_path):
    folder = hand_in(course, tmp_path / "submissions")
    code, doc = grade(folder)
    said = naming(doc, WORLD_PACKAGE)
    assert code == 1
    for student in ("alice", "bob"):
        [(row, finding)] = [(row, f) for row, f in said if f"/{student}/" in row]
        assert row.startswith(str(folder / student / LAB / "launch"))   # the launch file's row, not the package's
        assert finding["severity"] == "error" and finding["check"] == "launch"
        assert "cannot be found" in finding["message"] and "the folder graded" in finding["message"]
        assert "beside the submissions" in finding["fix"] and "worldgen course -w DIR" in finding["fix"]
    assert len(said) == 2
    assert all(r["ok"] for r in doc["results"] if r["path"].endswith(LAB))   # the package rows say nothing of it


@pytest.mark.parametrize("given", ["absolute", "submissions/", "."])
def test_the_course_package_beside_the_submissions_serves_them_all(course, tmp_path, monkeypatch, given):
    """However the folder is named: absolute, relative, or the working folder itself ($(find) gives an absolute
    path, as rospack does; relative, the world would be looked up on Gazebo's resource path instead)."""
    folder = hand_in(course, tmp_path / "submissions")
    shutil.copytree(course / WORLD_PACKAGE, folder / WORLD_PACKAGE)
    monkeypatch.chdir(tmp_path if given == "submissions/" else folder)
    code, doc = grade(folder if given == "absolute" else Path(given))
    assert code == 0 and naming(doc, WORLD_PACKAGE) == []
    launches = [r for r in doc["results"] if f"/{LAB}/launch/" in r["path"]]
    assert len(launches) == 2 and all(r["checks"][:2] == ["launch", "parse"] for r in launches)
    assert {r["metrics"].get("enclosed") for r in launches} == {True}


def test_ros_package_path_finds_it(course, tmp_path):
    folder = hand_in(course, tmp_path / "submissions")
    code, doc = grade(folder, {"ROS_PACKAGE_PATH": str(course.parent)})
    assert code == 0 and naming(doc, WORLD_PACKAGE) == []


def test_a_package_several_students_hold_is_not_borrowed_from_another(course, tmp_path):
    """Alice hands in the world package beside her lab and finds it; Carol hands in one too; Bob, who did not, is
    not graded against a copy in another student's folder."""
    folder = hand_in(course, tmp_path / "submissions")
    for student in ("alice", "carol"):
        shutil.copytree(course / WORLD_PACKAGE, folder / student / WORLD_PACKAGE)
    code, doc = grade(folder)
    said = naming(doc, WORLD_PACKAGE)
    assert code == 1 and [row.split("/submissions/")[1].split("/")[0] for row, _ in said] == ["bob"]


def test_the_run_leaves_out_the_package_the_submissions_share(course, tmp_path):
    folder = hand_in(course, tmp_path / "submissions")
    shutil.copytree(course / WORLD_PACKAGE, folder / WORLD_PACKAGE)
    found = submissions(folder)
    assert folder / WORLD_PACKAGE in found
    assert list(not_submissions(found, "stop-at-wall")) == [folder / WORLD_PACKAGE]
    # a package another depends on that holds the task's node is a submission still
    launcher = folder / "zed" / "launcher"
    launcher.mkdir(parents=True)
    (launcher / "package.xml").write_text(f'<package format="2"><name>launcher</name><version>0.1.0</version>'
                                          f'<exec_depend>{LAB}</exec_depend></package>', encoding="utf-8")
    assert list(not_submissions(submissions(folder), "stop-at-wall")) == [folder / WORLD_PACKAGE]


def test_the_courses_metapackage_is_no_submission(course):
    """Grading the course's own src/intro_robo (the labs as handed out): the metapackage that groups them (ROS 1;
    ROS 2 has none) is left out with its reason, as the world package is, and every lab is graded."""
    left = not_submissions(submissions(course), "stop-at-wall")
    metapackages = [p for p, why in left.items() if why.startswith("a metapackage")]
    assert metapackages == ([course / "intro_robo"] if (course / "intro_robo" / "package.xml").is_file() else [])
    assert left[course / WORLD_PACKAGE].startswith("packages in the folder depend on it")
    assert course / LAB in submissions(course) and course / LAB not in left


def test_a_submission_without_its_package_xml_is_a_failed_row(course, tmp_path):
    """Not passed over: a student's folder holding the lab's files but no package.xml gets one error row naming
    it; a folder of other things (notes) beside the submissions gets none."""
    folder = hand_in(course, tmp_path / "submissions", students=("alice", "bob", "eve"))
    shutil.copytree(course / WORLD_PACKAGE, folder / WORLD_PACKAGE)
    (folder / "eve" / LAB / "package.xml").unlink()
    (folder / "notes").mkdir()
    (folder / "notes" / "grading.txt").write_text("late: bob\n")
    (folder / "fay").mkdir()   # handed in nothing
    (folder / "gus").mkdir()   # handed in a zip nobody unpacked
    (folder / "gus" / "lab.zip").write_bytes(b"PK\x05\x06" + bytes(18))
    (folder / "gus" / ".DS_Store").write_bytes(b"\0")
    code, doc = grade(folder)
    assert code == 1
    rows = {Path(r["path"]).name: r for r in doc["results"] if Path(r["path"]).name in ("eve", "fay", "gus")}
    assert sorted(rows) == ["eve", "fay", "gus"]
    said = {}
    for name, row in rows.items():
        assert row["path"] == str(folder / name) and not row["ok"]
        [finding] = row["findings"]
        assert finding["check"] == "package" and finding["severity"] == "error"
        said[name] = finding["message"]
    assert "no package.xml" in said["eve"]
    assert said["fay"] == "holds nothing: no package was handed in"
    assert said["gus"] == "holds no package, only an archive (lab.zip)"
    assert not [r for r in doc["results"] if "notes" in r["path"]]
    assert all(r["ok"] for r in doc["results"] if Path(r["path"]).name not in rows)


def test_an_empty_folder_in_a_workspace_is_no_missing_submission(course, tmp_path):
    """A workspace's src/ may hold an empty folder (a git submodule never cloned): not a student's empty hand-in."""
    from worldgen.check.discover import search_folder

    src = tmp_path / "ws" / "src"
    shutil.copytree(course / LAB, src / LAB)
    (src / "turtlebot3_msgs").mkdir()
    (src / "downloads").mkdir()
    (src / "downloads" / "labs.zip").write_bytes(b"PK\x05\x06" + bytes(18))
    assert search_folder(src).unpackaged == ()
    assert search_folder(src.parent).unpackaged == ()


def test_a_lab_whose_setup_py_does_not_parse_is_not_run(course, tmp_path):
    """colcon cannot build an ament_python package whose setup.py is not Python: run grades it as a node that
    cannot run, naming the file and line, not by running its script as if it had been built."""
    from worldgen.bridge.grade import _check_buildable
    from worldgen.core.errors import InputError

    lab = shutil.copytree(course / LAB, tmp_path / LAB)
    if not (lab / "setup.py").is_file():
        pytest.skip("a catkin lab has no setup.py to build with")
    _check_buildable(lab)   # as written by course: builds
    (lab / "setup.py").write_text((lab / "setup.py").read_text() + "\nsetup(\n")
    with pytest.raises(InputError, match="colcon cannot build the package") as raised:
        _check_buildable(lab)
    assert str(raised.value).startswith(f"{lab / 'setup.py'}:")


def test_a_misspelt_world_package_is_named_with_the_one_meant(course, tmp_path):
    """$(find class_meeting_02_custom_gazebo_wrold): the world cannot be found, and the error names the package
    beside it that was meant, not 'put …_wrold in the workspace'."""
    folder = hand_in(course, tmp_path / "submissions", students=("alice",))
    shutil.copytree(course / WORLD_PACKAGE, folder / WORLD_PACKAGE)
    typo = WORLD_PACKAGE.replace("world", "wrold")
    [launch] = [p for p in (folder / "alice" / LAB / "launch").iterdir() if WORLD_PACKAGE in p.read_text()]
    launch.write_text(launch.read_text().replace(WORLD_PACKAGE, typo))
    code, doc = grade(folder)
    [finding] = [f for r in doc["results"] for f in r["findings"] if typo in f["message"]]
    assert code == 1 and finding["severity"] == "error" and f"did you mean {WORLD_PACKAGE!r}?" in finding["message"]
    assert WORLD_PACKAGE in finding["fix"] and typo not in finding["fix"]
