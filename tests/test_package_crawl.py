"""The package crawl (worldgen.core.packages.crawl) against catkin_pkg's finder where catkin_pkg can be used (no
symlinked folders), and on the symlink loops catkin_pkg cannot walk."""

from __future__ import annotations

import os

import pytest

from worldgen.core.packages import IGNORE_MARKERS, MANIFEST, crawl

catkin_packages = pytest.importorskip("catkin_pkg.packages")


def package(folder, name: str):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / MANIFEST).write_text(f"<package format='2'><name>{name}</name><version>0.1.0</version>"
                                   "<description>d</description><maintainer email='ta@example.com'>ta</maintainer>"
                                   "<license>MIT</license></package>\n")
    (folder / "launch").mkdir()
    return folder


def class_folder(root):
    """Students' trees: packages at several depths, one inside another, folders with each ignore marker, a
    hidden folder, and folder names whose sorted order differs from their paths' string order."""
    package(root / "ana" / "src" / "lab_a", "lab_a")
    package(root / "ana" / "src" / "lab_a" / "nested", "nested")          # inside a package: not a package
    package(root / "ana-old" / "lab_a", "lab_a_old")
    package(root / "ben" / "catkin_ws" / "src" / "b" / "lab_b", "lab_b")
    package(root / "ben" / "catkin_ws" / "src" / "a_first", "a_first")
    for marker in IGNORE_MARKERS:
        ignored = package(root / "cara" / marker.lower() / "pkg", f"ignored_{marker.lower()}")
        (ignored.parent / marker).write_text("")
    package(root / ".git" / "pkg", "hidden")
    return root


def test_the_crawl_finds_what_catkin_pkg_finds_in_sorted_order(tmp_path):
    root = class_folder(tmp_path / "class")
    found = [os.path.relpath(p, root) for p in crawl(root)]
    assert sorted(found) == sorted(catkin_packages.find_package_paths(str(root)))
    assert found == ["ana/src/lab_a", "ana-old/lab_a", "ben/catkin_ws/src/a_first", "ben/catkin_ws/src/b/lab_b"]
    assert set(IGNORE_MARKERS) == set(catkin_packages.DEFAULT_IGNORE_MARKERS)


def test_a_package_root_is_that_package(tmp_path):
    lab = package(tmp_path / "lab_a", "lab_a")
    package(lab / "inner", "inner")
    assert crawl(lab) == [lab]
    assert catkin_packages.find_package_paths(str(lab)) == ["."]


def test_symlink_loops_are_walked_once_each(tmp_path):
    """Links back up the tree, in two students' folders: catkin_pkg's walk would follow them until ELOOP, each
    inside the other (it does not finish); the crawl walks each real folder once and finds each package once."""
    root = class_folder(tmp_path / "class")
    (root / "ana" / "src" / "up").symlink_to(root)
    (root / "ben" / "catkin_ws" / "src" / "b" / "back").symlink_to(root / "ben")
    (root / "ana-old" / "side").symlink_to(root / "ben" / "catkin_ws")
    found = crawl(root)
    assert len({os.path.realpath(p) for p in found}) == len(found) == 4
