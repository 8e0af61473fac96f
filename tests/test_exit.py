"""The program's way out (``worldgen.cli.run``): past the command, no interpreter teardown, but nothing lost —
the exit status, every byte of output (through a pipe, past its buffer), the exit handlers, and a thread the
command left running."""

from __future__ import annotations

import subprocess
import sys

from conftest import REPO

PROGRAM = """
import atexit, sys, threading, time
from worldgen.cli import run
{setup}
sys.argv = ["worldgen", *{args!r}]
run()
"""


def program(args, setup: str = "") -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", PROGRAM.format(setup=setup, args=list(args))], cwd=REPO,
                          capture_output=True, text=True, timeout=120)


def test_the_exit_status_and_the_one_line_come_through(tmp_path):
    empty = tmp_path / "empty.world"
    empty.write_text("<sdf version='1.6'><world name='w'></world></sdf>\n")
    done = program(["validate", str(empty), "--skip-sim"])
    assert done.returncode == 1 and "no walls around the spawn" in done.stdout
    done = program(["validate", "examples/enclosed_room.yaml", "--skip-sim"])
    assert done.returncode == 0 and "1 passed, 0 failed" in done.stdout
    done = program(["build", "--no-such-flag"])
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "no-such-flag" in done.stderr


def test_output_larger_than_a_pipe_arrives_whole(tmp_path):
    """A batch's specs listed on stdout: far more than the 64 KiB a pipe holds, every line there."""
    done = program(["generate", "maze", "--seed", "0", "--count", "2000", "-o", str(tmp_path)])
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert len(lines) == 2000 and lines[-1].endswith("maze_1999.yaml")
    assert sum(len(line) + 1 for line in lines) > 65536


def test_exit_handlers_run_and_a_running_thread_is_waited_for():
    setup = ("atexit.register(lambda: print('handler ran', flush=True))\n"
             "threading.Thread(target=lambda: (time.sleep(0.5), print('thread done', flush=True))).start()")
    done = program(["--version"], setup)
    assert done.returncode == 0
    assert done.stdout.splitlines()[1:] == ["thread done", "handler ran"], done.stdout
