"""A folder is never left: a symlinked folder inside a folder handed to validate or run that leads out of it is
not followed (the folder's note names it), and writers never write through a symlinked folder inside an output."""

from __future__ import annotations

import os
from pathlib import Path

from conftest import CliRunner

from worldgen.bridge.grade import submissions
from worldgen.check.discover import search_folder
from worldgen.cli import main

ROOM = Path(__file__).resolve().parent.parent / "examples" / "enclosed_room.yaml"
MANIFEST = ("<package format='2'><name>{}</name><version>0.0.1</version><description>d</description>"
            "<maintainer email='a@b.c'>a</maintainer><license>BSD</license></package>\n")


def package(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(MANIFEST.format(name))
    return folder


def class_folder(tmp_path: Path) -> Path:
    """Two submissions; one holds a link to a folder of 3 packages outside the class folder, and one back up."""
    elsewhere = tmp_path / "system"
    for name in ("sys_a", "sys_b", "sys_c"):
        package(elsewhere / name, name)
    subs = tmp_path / "submissions"
    package(subs / "ana" / "lab", "lab")
    package(subs / "bo" / "lab", "lab")
    os.symlink(elsewhere, subs / "ana" / "share")
    os.symlink("..", subs / "bo" / "up")   # inside the class folder: walked once, as before
    return subs


def test_validate_does_not_follow_a_link_out_of_the_folder(tmp_path):
    subs = class_folder(tmp_path)
    found = search_folder(subs)
    assert [p.relative_to(subs).as_posix() for p in found.packages] == ["ana/lab", "bo/lab"]
    assert found.links_out == (subs / "ana" / "share",)
    assert f"1 folder link leading out of it not followed: {subs / 'ana' / 'share'} -> {tmp_path / 'system'}" \
        in found.note
    done = CliRunner().invoke(main, ["validate", "--skip-sim", str(subs)])
    assert "folder link leading out of it not followed" in done.stderr
    assert "sys_a" not in done.output


def test_a_folder_of_worlds_names_its_links_out_too(tmp_path):
    worlds = tmp_path / "worlds"
    worlds.mkdir()
    (worlds / "room.yaml").write_text(ROOM.read_text())
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "far.yaml").write_text(ROOM.read_text())
    os.symlink(tmp_path / "other", worlds / "more")
    found = search_folder(worlds)
    assert [p.name for _, p in found.files] == ["room.yaml"]
    assert found.links_out == (worlds / "more",)


def test_run_grades_only_what_is_in_the_folder(tmp_path):
    subs = class_folder(tmp_path)
    assert [p.relative_to(subs).as_posix() for p in submissions(subs)] == ["ana/lab", "bo/lab"]


def test_build_does_not_write_through_a_link_inside_the_package(tmp_path):
    done = CliRunner().invoke(main, ["scaffold", "lab", "rospy", "-p", str(tmp_path)])
    assert done.exit_code == 0, done.output
    pkg = tmp_path / "lab"
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (pkg / "worlds").rename(tmp_path / "old_worlds")
    os.symlink(elsewhere, pkg / "worlds")
    done = CliRunner().invoke(main, ["build", str(ROOM), "--package", str(pkg)])
    assert done.exit_code == 2
    (line,) = done.stderr.splitlines()
    assert f"{pkg / 'worlds'} is a symbolic link" in line
    assert list(elsewhere.iterdir()) == [] and not (pkg / "launch" / "turtlebot3_in_enclosed_room.launch").exists()


def test_launch_does_not_write_through_a_link_inside_the_package(tmp_path):
    done = CliRunner().invoke(main, ["scaffold", "lab", "rospy", "-p", str(tmp_path), "--world", str(ROOM)])
    assert done.exit_code == 0, done.output
    pkg = tmp_path / "lab"
    elsewhere = tmp_path / "elsewhere"
    (pkg / "launch").rename(elsewhere)
    os.symlink(elsewhere, pkg / "launch")
    done = CliRunner().invoke(main, ["launch", str(pkg / "worlds" / "enclosed_room.world"), "--name", "two"])
    assert done.exit_code == 2 and "is a symbolic link" in done.stderr
    assert not (elsewhere / "two.launch").exists()
