"""setup.py read without running it, comprehensions included: the ROS 2 packages worldgen writes are read in full
(their install check runs, with nothing to say), a comprehension over what can be known is run, one over what
cannot stays unknown, and the work comprehensions may take is bounded."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import CliRunner

from worldgen.cli import main
from worldgen.pyread.setup_py import installed_files, read_setup
from worldgen.pyread.values import MAX_ITERATIONS

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.mark.parametrize("ros", ["humble", "jazzy"])
def test_the_setup_py_worldgen_writes_is_read_in_full(tmp_path, ros):
    done = CliRunner().invoke(main, ["scaffold", "lab", "rclpy", "--ros", ros, "-p", str(tmp_path), "--world",
                                     str(EXAMPLES / "enclosed_room.yaml")])
    assert done.exit_code == 0, done.output
    package = tmp_path / "lab"
    (package / "launch" / "later.launch.py").write_text("")   # added after the scaffold: installed too
    (package / "launch" / "sub").mkdir()                       # a folder: never installed
    info = read_setup(package / "setup.py")
    assert info.unreadable == []
    installed = installed_files(package, info)
    assert sorted(p.name for p in installed["share/lab/launch"]) == sorted(
        p.name for p in (package / "launch").iterdir() if p.is_file())
    assert "later.launch.py" in {p.name for p in installed["share/lab/launch"]}
    assert [p.suffix for p in installed["share/lab/worlds"]] == [".sdf" if ros == "jazzy" else ".world"]


def setup_py(tmp_path: Path, body: str) -> Path:
    path = tmp_path / "setup.py"
    path.write_text("import os\nfrom glob import glob\nfrom setuptools import setup\n" + body)
    return path


def test_a_comprehension_over_known_values_is_run(tmp_path):
    path = setup_py(tmp_path, "folders = ['launch', 'worlds', 'maps']\n"
                              "setup(name='p', data_files=[(os.path.join('share', 'p', d), glob(d + '/*'))\n"
                              "                            for d in folders if d != 'maps'],\n"
                              "      entry_points={'console_scripts': [f'{n} = p.{n}:main' for n in ('a', 'b')]})\n")
    info = read_setup(path)
    assert info.unreadable == []
    assert [dest for dest, _ in info.data_files] == ["share/p/launch", "share/p/worlds"]
    assert info.scripts == {"a", "b"}


def test_a_comprehension_over_what_cannot_be_known_stays_unknown(tmp_path):
    path = setup_py(tmp_path, "setup(name='p', data_files=[(d, [f]) for d, f in os.walk('.')])\n")
    info = read_setup(path)
    assert info.data_files == []
    assert any("comprehension" in reason for _, reason in info.unreadable)
    path = setup_py(tmp_path, "setup(name='p', data_files=[('share/p', [f]) for f in ['a', 'b'] "
                              "if os.path.exists(f)])\n")   # the condition looks at the disk: not told
    assert read_setup(path).data_files == []


def test_comprehensions_are_bounded(tmp_path):
    path = setup_py(tmp_path, "big = [[a for a in 'x' * 100000] for b in 'y' * 100000]\n"
                              "setup(name='p', data_files=[('share/p', ['package.xml'])])\n")
    info = read_setup(path)   # stops after MAX_ITERATIONS items, not 10^10: the line is left unknown
    assert info.data_files == [("share/p", ["package.xml"])]
    assert any(line == 4 and "comprehension" in reason for line, reason in info.unreadable)
    assert MAX_ITERATIONS <= 1_000_000
