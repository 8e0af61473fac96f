"""Usage errors (an unknown option or command, a missing argument, a bad value for an option) are one line on
stderr and exit code 2, like every other error of worldgen: never click's usage block."""

from __future__ import annotations

import subprocess
import sys

import pytest
from conftest import CliRunner

from worldgen.cli import main

CASES = [
    (["validate", "--bogus", "x.world"], "--bogus", "worldgen validate --help"),
    (["build"], "SPEC", "worldgen build --help"),
    (["buidl", "x.yaml"], "buidl", "worldgen --help"),
    (["--bogus"], "--bogus", "worldgen --help"),
    (["validate", "--jobs", "many", "x.world"], "many", "worldgen validate --help"),
    (["launch", "x.world", "--model", "tank"], "tank", "worldgen launch --help"),
    (["preview"], "preview", "worldgen preview --help"),
    (["run", "--ros", "kinetic"], "kinetic", "worldgen run --help"),
]


@pytest.mark.parametrize("argv, named, helped", CASES)
def test_a_usage_error_is_one_line(argv, named, helped):
    result = CliRunner().invoke(main, argv)
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    assert result.stderr.count("\n") == 1, result.stderr
    line = result.stderr.strip()
    assert line.startswith("worldgen: error: ")
    assert named in line or named in helped
    assert f"(see '{helped}')" in line
    assert "Usage:" not in line


def test_a_misspelt_command_is_answered_with_the_nearest_one():
    result = CliRunner().invoke(main, ["valdate", "x.world"])
    assert result.exit_code == 2 and "No such command 'valdate'. Did you mean 'validate'?" in result.stderr
    far = CliRunner().invoke(main, ["zzz"])
    assert far.exit_code == 2 and "Did you mean" not in far.stderr and "Choose one of: build, course," in far.stderr
    kind = CliRunner().invoke(main, ["generate", "foo"])
    assert kind.exit_code == 2 and "Choose one of: arena, clutter, maze, rooms, track." in kind.stderr
    assert "Did you mean 'maze'?" in CliRunner().invoke(main, ["generate", "mazes"]).stderr


def test_usage_error_of_the_installed_command():
    """The real entry point (``python -m worldgen``), not click's runner: the same one line."""
    done = subprocess.run([sys.executable, "-m", "worldgen", "validate", "--skip-simm", "x.world"],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60)
    assert done.returncode == 2
    assert done.stdout == ""
    [line] = done.stderr.splitlines()   # click 8.1 (Python 3.8) words it "No such option: --skip-simm Did you …"
    assert line.startswith("worldgen: error: No such option") and line.endswith("(see 'worldgen validate --help')")
    assert "--skip-simm" in line and "Did you mean" in line and line.count("--skip-sim") == 2


def test_help_is_still_help():
    result = CliRunner().invoke(main, ["validate", "--help"])
    assert result.exit_code == 0
    assert "Usage:" in result.output and "--skip-sim" in result.output


@pytest.mark.parametrize("argv, lists", [([], "validate"), (["generate"], "maze")])
def test_a_command_without_its_subcommand_shows_the_help(argv, lists):
    """Asking what there is is no mistake: the help on stdout and exit 0, whichever click (8.2 calls it an error)."""
    result = CliRunner().invoke(main, argv)
    assert result.exit_code == 0 and result.stderr == ""
    assert result.stdout.startswith("Usage: ") and lists in result.stdout


@pytest.mark.parametrize("argv, said", [
    (["preview", "{d}/shot.png"], "shot.png: is a picture, not a world or spec"),
    (["preview", "{d}/node.py"], "node.py: is a Python file (a node, or setup.py), not a world or spec"),
    (["build", "{d}/node.py", "-o", "{d}/out"], "node.py: is a Python file (a node, or setup.py), not a spec"),
    (["launch", "{d}/room.yaml", "--package", "p", "-o", "{d}/out"], "room.yaml: is a floorplan spec, not a world"),
    (["launch", "{d}/node.py", "--package", "p", "-o", "{d}/out"], "is a Python file (a node, or setup.py), not a "
                                                                    "world"),
])
def test_a_file_of_the_wrong_kind_is_named_for_what_it_is(tmp_path, argv, said):
    """Not "not well-formed XML" for a picture, a node or a spec given where a world goes; nothing written (a
    picture given to preview is not taken for its own output, which exists)."""
    (tmp_path / "shot.png").write_bytes(b"\x89PNG\r\n\x1a\n")
    (tmp_path / "node.py").write_text("import rospy\n")
    (tmp_path / "room.yaml").write_text("name: room\nrooms:\n  - rect: {center: [0, 0], size: [4, 4]}\n")
    before = sorted(tmp_path.rglob("*"))
    result = CliRunner().invoke(main, [a.format(d=tmp_path) for a in argv])
    assert result.exit_code == 2 and result.stdout == "" and result.stderr.count("\n") == 1, result.output
    assert result.stderr.startswith("worldgen: error: ") and said in result.stderr
    assert sorted(tmp_path.rglob("*")) == before
