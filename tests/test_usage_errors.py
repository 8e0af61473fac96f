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
