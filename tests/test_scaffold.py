"""worldgen scaffold: the same package.xml meaning as catkin_create_pkg for the same arguments, the class's
folders, and clean refusals; check_package on packages we made and broke."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from conftest import CliRunner

from rosstubs import need, ros_env
from worldgen.cli import main
from worldgen.core.errors import InputError
from worldgen.packages.check import check_package
from worldgen.packages.catkin import PackageArgs, package_request

# catkin_create_pkg argument sets: plain class package, everything at once, no dependencies, messages, C++
ARG_SETS = [
    ["lab_a", "rospy", "std_msgs", "geometry_msgs", "sensor_msgs"],
    ["full_pkg", "roscpp", "rospy", "std_msgs", "python-yaml", "-s", "eigen", "python-numpy", "-b", "thread",
     "system", "-V", "1.2.3", "-D", "Drives a robot", "-l", "MIT", "-l", "BSD", "-a", "Ann Author", "-a", "Bob",
     "-m", "Jane Doe", "-m", "Al Zed"],
    ["bare"],
    ["my_msgs", "message_generation", "message_runtime", "std_msgs"],
    ["cpp_only", "roscpp", "-b", "filesystem", "-V", "0.3.0"],
]


def parsed(pkg_dir: Path):
    from catkin_pkg.package import parse_package

    return parse_package(str(pkg_dir / "package.xml"))


def meaning(pkg) -> dict:
    """What a package.xml says, as catkin_pkg reads it."""
    names = lambda deps: sorted(d.name for d in deps)   # noqa: E731
    return {
        "name": pkg.name, "version": pkg.version, "description": pkg.description, "format": pkg.package_format,
        "licenses": list(pkg.licenses),
        "maintainers": [(p.name, p.email) for p in pkg.maintainers],
        "authors": [(p.name, p.email) for p in pkg.authors],
        "buildtool": names(pkg.buildtool_depends), "build": names(pkg.build_depends),
        "build_export": names(pkg.build_export_depends), "exec": names(pkg.exec_depends),
        "metapackage": pkg.is_metapackage(),
    }


def catkin_create_pkg(args: list[str], where: Path) -> Path:
    where.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run([need("catkin_create_pkg"), *args], cwd=where, capture_output=True, text=True,
                          env=ros_env(where, ROS_DISTRO="noetic"))
    assert proc.returncode == 0, proc.stderr
    return where / args[0]


def scaffold(args: list[str], where: Path) -> Path:
    result = CliRunner().invoke(main, ["scaffold", *args, "-p", str(where)])
    assert result.exit_code == 0, result.output
    return where / args[0]


@pytest.mark.parametrize("args", ARG_SETS, ids=[a[0] for a in ARG_SETS])
def test_same_meaning_as_catkin_create_pkg(args, tmp_path):
    pytest.importorskip("catkin_pkg")
    theirs = meaning(parsed(catkin_create_pkg(args, tmp_path / "catkin")))
    ours = meaning(parsed(scaffold(args, tmp_path / "ours")))
    assert ours == theirs


def test_catkin_defaults_are_ours(tmp_path):
    """No options: version 0.0.0, "The NAME package", license TODO, the user as maintainer with a @todo.todo
    address, catkin as buildtool, each dependency as build, build_export and exec dependency."""
    pytest.importorskip("catkin_pkg")
    pkg = meaning(parsed(scaffold(["lab_b", "rospy", "geometry_msgs"], tmp_path)))
    import getpass

    user = getpass.getuser()
    assert pkg == {"name": "lab_b", "version": "0.0.0", "description": "The lab_b package", "format": 2,
                   "licenses": ["TODO"], "maintainers": [(user, f"{user}@todo.todo")], "authors": [],
                   "buildtool": ["catkin"], "build": ["geometry_msgs", "rospy"],
                   "build_export": ["geometry_msgs", "rospy"], "exec": ["geometry_msgs", "rospy"],
                   "metapackage": False}


def test_folders_like_catkin_plus_the_class_ones(tmp_path):
    py = scaffold(["py_pkg", "rospy"], tmp_path)
    cpp = scaffold(["cpp_pkg", "roscpp"], tmp_path)
    plain = scaffold(["plain_pkg", "std_msgs"], tmp_path)
    files = lambda p: sorted(str(f.relative_to(p)) for f in p.rglob("*") if f.is_file())   # noqa: E731
    assert files(py) == ["CMakeLists.txt", "launch/.gitkeep", "package.xml", "scripts/.gitkeep", "src/.gitkeep",
                         "worlds/.gitkeep"]
    assert "include/cpp_pkg/.gitkeep" in files(cpp) and "src/.gitkeep" in files(cpp)
    assert not (plain / "src").exists()
    cmake = (py / "CMakeLists.txt").read_text()
    live = [ln for ln in cmake.splitlines() if ln.strip() and not ln.startswith("#")]
    assert live[:3] == ["cmake_minimum_required(VERSION 3.0.2)", "project(py_pkg)",
                        "find_package(catkin REQUIRED COMPONENTS"]
    assert "  CATKIN_DEPENDS rospy" in live and "install(DIRECTORY launch worlds" in live


def test_metapackage(tmp_path):
    pytest.importorskip("catkin_pkg")
    theirs = meaning(parsed(catkin_create_pkg(["my_meta", "--meta"], tmp_path / "catkin")))
    meta = scaffold(["my_meta", "--meta"], tmp_path / "ours")
    assert meaning(parsed(meta)) == theirs and theirs["metapackage"]
    assert sorted(p.name for p in meta.iterdir()) == ["CMakeLists.txt", "package.xml"]
    # catkin's exact metapackage boilerplate (catkin checks it), and members as exec_depend only (REP 127)
    assert (meta / "CMakeLists.txt").read_text() == ("cmake_minimum_required(VERSION 3.0.2)\nproject(my_meta)\n"
                                                     "find_package(catkin REQUIRED)\ncatkin_metapackage()\n")
    with_members = meaning(parsed(scaffold(["grouped", "lab_a", "lab_b", "--meta"], tmp_path / "ours")))
    assert with_members["exec"] == ["lab_a", "lab_b"] and with_members["build"] == [] and \
        with_members["build_export"] == []


def test_people_and_escaping(tmp_path):
    pytest.importorskip("catkin_pkg")
    from lxml import etree

    folder = scaffold(["people", "-m", "Jane Doe <jane@uni.edu>", "-m", "Max max@uni.edu",
                       "-a", "Ann <ann@uni.edu>", "-D", "Rooms & <walls>"], tmp_path)
    pkg = meaning(parsed(folder))
    assert pkg["maintainers"] == [("Jane Doe", "jane@uni.edu"), ("Max", "max@uni.edu")]
    assert pkg["authors"] == [("Ann", "ann@uni.edu")]
    # catkin_create_pkg would write the description unescaped, which is not XML
    assert etree.parse(str(folder / "package.xml")).getroot().findtext("description") == "Rooms & <walls>"


def test_greedy_options_like_catkin(tmp_path):
    """-s and -b take every word up to the next option, as catkin_create_pkg's argparse nargs='*' does."""
    pkg = scaffold(["greedy", "rospy", "-s", "eigen", "opencv", "-b", "thread", "system", "-V", "0.1.0"], tmp_path)
    text = (pkg / "CMakeLists.txt").read_text()
    assert "find_package(Boost REQUIRED COMPONENTS thread system)" in text
    assert "find_package(eigen REQUIRED)" in text and "find_package(opencv REQUIRED)" in text
    assert "<exec_depend>boost</exec_depend>" in (pkg / "package.xml").read_text()


@pytest.mark.parametrize("args, words", [
    (["Lab_A"], "invalid package name 'Lab_A'"),
    (["1lab"], "invalid package name"),
    (["lab-a"], "invalid package name"),
    (["lab_a", "-V", "1.0"], "invalid package version"),
    (["lab_a", "-m", "O'Brien"], "invalid email"),
    (["lab_a", "lab_a"], "cannot depend on itself"),
    (["lab_a", "--rosdistro", "humble"], "ROS 2 distro"),
    (["lab_a", "--meta", "--world", "{spec}"], "metapackage holds no worlds"),
    (["lab_a", "--world", "{on_wall}"],
     "the spec's robot pose (2.0, 0.0) is no place for the robot: it is inside a wall"),
])
def test_bad_input_writes_nothing(tmp_path, args, words):
    spec = tmp_path / "room.yaml"
    spec.write_text("name: room\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [4, 4]}\n")
    on_wall = tmp_path / "on_wall.yaml"
    on_wall.write_text(spec.read_text() + "robot: {model: burger, at: [2.0, 0.0], yaw: 0}\n")
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["scaffold", *[a.format(spec=spec, on_wall=on_wall) for a in args],
                                       "-p", str(out)])
    assert result.exit_code == 2
    (line,) = [ln for ln in result.output.splitlines() if "rror" in ln]
    assert words in line
    assert not out.exists() or not any(out.iterdir())


def test_existing_folder_needs_force(tmp_path):
    pkg = scaffold(["keep_me", "rospy"], tmp_path)
    (pkg / "scripts" / "mine.py").write_text("# student work\n")
    again = CliRunner().invoke(main, ["scaffold", "keep_me", "rospy", "-p", str(tmp_path)])
    assert again.exit_code == 2 and "exists" in again.output
    assert (pkg / "scripts" / "mine.py").exists()
    forced = CliRunner().invoke(main, ["scaffold", "keep_me", "std_msgs", "-p", str(tmp_path), "--force"])
    assert forced.exit_code == 0 and not (pkg / "scripts" / "mine.py").exists()
    assert "<build_depend>std_msgs</build_depend>" in (pkg / "package.xml").read_text()


def test_scaffold_with_a_world(tmp_path):
    from lxml import etree

    from worldgen.launch.reader import read_launch

    spec = tmp_path / "box_room.yaml"
    spec.write_text("name: box_room\nrooms:\n  - name: a\n    rect: {center: [1, 2], size: [4, 3]}\n"
                    "robot: {model: burger, at: [1.5, 2.0], yaw: 0.5}\n")
    pkg = scaffold(["my_world", "rospy", "--world", str(spec)], tmp_path)
    assert (pkg / "worlds" / "box_room.world").read_text().startswith("<?xml")
    assert (pkg / "models" / ".gitkeep").exists()
    info = read_launch(pkg / "launch" / "turtlebot3_in_box_room.launch", environ={}, ros_package_path=[])
    assert info.world_path == pkg / "worlds" / "box_room.world" and info.spawn == (1.5, 2.0, 0.0, 0.5)
    xml = etree.parse(str(pkg / "package.xml")).getroot()
    assert {"gazebo_ros", "turtlebot3_description", "xacro"} <= {e.text for e in xml.findall("exec_depend")}
    assert xml.find("export/gazebo_ros").get("gazebo_model_path") == "${prefix}/models"
    assert "install(DIRECTORY launch models worlds" in (pkg / "CMakeLists.txt").read_text()
    assert [f for f in check_package(pkg, environ={}) if f.severity != "info"] == []
    # a spec without a robot: the launch file spawns at the middle of the room
    spec.write_text("name: box_room\nrooms:\n  - name: a\n    rect: {center: [1, 2], size: [4, 3]}\n")
    pkg2 = scaffold(["other_world", "--world", str(spec)], tmp_path)
    spawn = read_launch(pkg2 / "launch" / "turtlebot3_in_box_room.launch", environ={}).spawn
    assert spawn == (1.0, 2.0, 0.0, 0.0)


def test_request_validation_is_a_library_function():
    with pytest.raises(InputError):
        package_request(PackageArgs("Bad"))
    req = package_request(PackageArgs("ok_pkg", ("std_msgs", "catkin", "rospy", "std_msgs"),
                                      maintainers=("Z Last", "A First")))
    assert req.catkin_deps == ("rospy", "std_msgs")
    assert [m.email for m in req.maintainers] == ["First@todo.todo", "Last@todo.todo"]


# ------------------------------------------------------------------------------------------- check_package

def test_check_package_finds_what_breaks(tmp_path):
    from worldgen.packages.catkin import create_package

    spec = tmp_path / "room.yaml"
    spec.write_text("name: room\nrooms:\n  - name: a\n    rect: {center: [0, 0], size: [4, 4]}\n"
                    "robot: {at: [0, 0]}\n")
    pkg = create_package(tmp_path, package_request(PackageArgs("checked", ("rospy",))), world_spec=spec)
    (pkg / "scripts" / "go.py").write_text("#!/usr/bin/env python3\n")
    (pkg / "scripts" / "go.py").chmod(0o755)
    assert [f for f in check_package(pkg, environ={}) if f.severity in ("error", "warning")] == []

    (pkg / "scripts" / "go.py").chmod(0o644)
    (pkg / "worlds" / "room.world").unlink()
    launch = pkg / "launch" / "turtlebot3_in_room.launch"
    launch.write_text(launch.read_text().replace("$(optenv TURTLEBOT3_MODEL burger)", "burgr").replace(
        "</launch>", '  <node pkg="checked" type="missing.py" name="m"/>\n</launch>'))
    cmake = pkg / "CMakeLists.txt"
    cmake.write_text(cmake.read_text().replace("install(DIRECTORY launch models worlds", "install(DIRECTORY models"))
    found = {(f.check, f.severity) for f in check_package(pkg, environ={})}
    assert found == {("script-executable", "error"), ("launch-world", "error"), ("launch-model", "error"),
                     ("launch-node", "error"), ("cmake-install", "warning")}

    (pkg / "package.xml").write_text("<package format='2'><name>checked</name></package>")
    assert ("package-xml", "error") in {(f.check, f.severity) for f in check_package(pkg, environ={})}
    bad_launch = pkg / "launch" / "broken.launch"
    bad_launch.write_text("<launch>\n<arg name='x'\n")
    assert any(f.check == "launch-parse" and f.where.endswith(":3") for f in check_package(pkg, environ={}))


def test_a_broken_package_xml_is_named_with_its_line_without_catkin_pkg(tmp_path, monkeypatch):
    """A wheel install has no catkin_pkg (a test dependency): the manifest's XML error still names its line."""
    monkeypatch.setitem(sys.modules, "catkin_pkg.package", None)   # importing it raises ImportError
    pkg = tmp_path / "lab"
    pkg.mkdir()
    (pkg / "package.xml").write_text("<?xml version='1.0'?>\n<package format='2'>\n  <name>lab</name>\n")
    [finding] = [f for f in check_package(pkg, environ={}) if f.check == "package-xml"]
    assert finding.severity == "error" and finding.where == f"{pkg / 'package.xml'}:4"
    assert "not well-formed XML" in finding.message
    (pkg / "package.xml").write_text("<package format='2'><version>0.1.0</version></package>\n")
    [finding] = [f for f in check_package(pkg, environ={}) if f.check == "package-xml"]
    assert finding.message == "package.xml has no <name>" and "<name>" in finding.fix


def test_check_package_on_a_folder_that_is_no_package(tmp_path):
    (finding,) = check_package(tmp_path)
    assert (finding.check, finding.severity) == ("package-xml", "error")

