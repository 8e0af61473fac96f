"""Outputs are written as one unit: SIGKILL at random moments leaves the old set or the new set, the next run
sweeps what the killed one left, two writers without --force never both win, a symbolic link at an output is
never followed without --force, and a full or read-only disk leaves nothing behind."""

from __future__ import annotations

import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import REPO, CliRunner

from worldgen.cli import main

LEFTOVER = re.compile(r"\.worldgen-(tmp|journal|staging|old)-\d+")
ROOM = """name: lab
walls: {{thickness: 0.15, height: {height}}}
rooms:
  - name: room
    rect: {{center: [0, 0], size: [{size}, 4]}}
robot: {{model: burger, at: [0, 0], yaw: 0}}
"""
SEED = int(os.environ.get("WORLDGEN_KILL_SEED", time.time_ns() % 100000))


def run(args, cwd, check=True):
    env = dict(os.environ, PYTHONPATH=str(REPO))
    proc = subprocess.run([sys.executable, "-m", "worldgen", *map(str, args)], cwd=cwd, env=env,
                          capture_output=True, text=True)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


def start(args, cwd):
    env = dict(os.environ, PYTHONPATH=str(REPO))
    return subprocess.Popen([sys.executable, "-m", "worldgen", *map(str, args)], cwd=cwd, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def kill_somewhen(proc, watch: Path, took: float, rng: random.Random) -> None:
    """SIGKILL ``proc``: half the time after a random delay, half the time a random 0-5 ms after its staging
    (a temporary file, journal or staging folder) shows up under ``watch`` — the moments that matter."""
    if rng.random() < 0.5:
        time.sleep(rng.uniform(0.0, 1.1) * took)
    else:
        deadline = time.monotonic() + 2 * took + 1
        while proc.poll() is None and time.monotonic() < deadline:
            if any(LEFTOVER.search(name) for _, dirs, files in os.walk(watch) for name in dirs + files):
                break
        time.sleep(rng.uniform(0.0, 0.005))
    proc.send_signal(signal.SIGKILL)
    proc.communicate()


def state(root: Path):
    """(files → bytes, leftovers) under ``root``; files inside a leftover folder count as leftovers."""
    files, left = {}, []
    for p in sorted(root.rglob("*")):
        rel = p.relative_to(root)
        if any(LEFTOVER.search(part) for part in rel.parts):
            left.append(str(rel))
        elif p.is_symlink():
            files[str(rel)] = ("link", os.readlink(p))
        elif p.is_file():
            files[str(rel)] = p.read_bytes()
    return files, left


def spec_pair(folder: Path):
    a, b = folder / "a" / "lab.yaml", folder / "b" / "lab.yaml"
    for path, size, height in ((a, 4, 2.5), (b, 6, 1.0)):
        path.parent.mkdir()
        path.write_text(ROOM.format(size=size, height=height))
    return a, b


def kill_loop(tmp_path, watch: Path, args_for, reset=None, kills=20):
    """Runs ``args_for(i)`` and SIGKILLs it after a random delay, ``kills`` times; each time what ``watch`` holds
    must be what the previous complete state was or what this run writes. Every 5th run goes to the end; then
    nothing a killed run left may remain."""
    rng = random.Random(SEED + kills)
    expected = {}

    def complete(i):
        if reset:
            reset()
        t0 = time.monotonic()
        run(args_for(i), tmp_path)
        files, left = state(watch)
        assert not left, f"leftovers after a complete run (seed {SEED}): {left}"
        expected[i % 2] = files
        return time.monotonic() - t0

    if reset:
        reset()
    base = state(watch)[0]
    took = max(complete(0), complete(1))
    outcomes = {"old": 0, "new": 0, "journal": 0}
    for k in range(kills):
        i = k % 2
        if reset:
            reset()
        before, _ = state(watch)
        assert before in ([base] if reset else [expected[0], expected[1]]), f"seed {SEED}"
        kill_somewhen(start(args_for(i), tmp_path), watch, took, rng)
        files, left = state(watch)
        if any("worldgen-journal" in p for p in left):
            # killed after its commit point (the journal), before or during the moves: the run counts as done, and
            # the next run writing there completes the moves (a run without --force then finds its files in place)
            outcomes["journal"] += 1
            run(args_for(i), tmp_path, check=False)
            assert state(watch)[0] == expected[i]
        elif files == before:
            outcomes["old"] += 1
        else:
            assert files == expected[i], f"a mix after a kill (seed {SEED}, run {k}): {left}"
            outcomes["new"] += 1
        if k % 5 == 4:
            complete(i)
    complete(0)
    print(f"kills: {outcomes} (seed {SEED})")
    return outcomes


def test_build_model_dir_force_killed(tmp_path):
    a, b = spec_pair(tmp_path)
    out = tmp_path / "out"
    seen = kill_loop(tmp_path, out, lambda i: ["build", (a, b)[i], "-o", out, "--model-dir", "--force"])
    assert seen["old"] + seen["new"] + seen["journal"] == 20


def test_build_package_killed(tmp_path):
    a, b = spec_pair(tmp_path)
    run(["scaffold", "pkg", "rospy", "-p", tmp_path], tmp_path)
    pkg = tmp_path / "pkg"
    manifest = (pkg / "package.xml").read_bytes()   # build gives it the launch file's exec_depends, in the same set

    def reset():
        for p in (pkg / "worlds" / "lab.world", pkg / "launch" / "turtlebot3_in_lab.launch"):
            if p.exists():
                p.unlink()
        (pkg / "package.xml").write_bytes(manifest)

    kill_loop(tmp_path, pkg, lambda i: ["build", (a, b)[i], "--package", pkg], reset=reset)


def test_course_force_killed(tmp_path):
    """course's output does not depend on its input: the old set is the fresh one with a file changed and one
    added."""
    src = tmp_path / "ws" / "src"
    run(["course", "-w", tmp_path / "ws"], tmp_path)
    fresh, _ = state(src)
    t0 = time.monotonic()
    run(["course", "-w", tmp_path / "ws", "--force"], tmp_path)
    took = time.monotonic() - t0
    rng = random.Random(SEED)
    seen = {"old": 0, "new": 0}
    for k in range(20):
        tree = src / "intro_robo"
        (tree / "OLD").write_text("the old set\n")
        (tree / "intro_robo" / "package.xml").write_text("old\n")
        old, _ = state(src)
        kill_somewhen(start(["course", "-w", tmp_path / "ws", "--force"], tmp_path), src, took, rng)
        files, left = state(src)
        assert files in (old, fresh), f"a mix after a kill (seed {SEED}, run {k}): {sorted(set(files) ^ set(old))}"
        seen["old" if files == old else "new"] += 1
        if k % 5 == 4:
            run(["course", "-w", tmp_path / "ws", "--force"], tmp_path)
            assert state(src) == (fresh, [])
    print(f"kills: {seen} (seed {SEED})")
    run(["course", "-w", tmp_path / "ws", "--force"], tmp_path)
    assert state(src) == (fresh, []) and sorted(os.listdir(src)) == ["intro_robo"]


def test_scaffold_force_killed(tmp_path):
    a, b = spec_pair(tmp_path)
    seen = kill_loop(tmp_path, tmp_path / "pkgs",
                     lambda i: ["scaffold", "lab_pkg", "rospy", "-D", f"version {i}", "--world", (a, b)[i],
                                "-p", tmp_path / "pkgs", "--force"])
    assert sum(seen.values()) == 20


def test_two_builds_without_force_one_wins(tmp_path):
    a, b = spec_pair(tmp_path)
    for k in range(10):
        out = tmp_path / f"out{k}"
        extra = ["--model-dir"] if k % 2 else []
        procs = [start(["build", spec, "-o", out, *extra], tmp_path) for spec in (a, b)]
        results = [(p.wait(), p.communicate()) for p in procs]
        codes = sorted(r[0] for r in results)
        assert codes == [0, 2], results
        loser = next(r for r in results if r[0] == 2)
        assert loser[1][1].count("\n") == 1 and loser[1][1].startswith("worldgen: error: ")
        files, left = state(out)
        assert not left and sorted(files) == (["lab.world", "lab/model.config", "lab/model.sdf"] if extra
                                              else ["lab.world"])
        winner = (a, b)[[r[0] for r in results].index(0)]
        wanted = run(["build", winner, "-o", tmp_path / f"check{k}", *extra], tmp_path)
        assert wanted.returncode == 0 and state(tmp_path / f"check{k}")[0] == files


def test_symlink_at_output_needs_force_and_is_replaced_itself(tmp_path):
    a, _ = spec_pair(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me\n")
    (out / "lab.world").symlink_to(tmp_path / "nowhere")      # dangling
    runner = CliRunner()
    refused = runner.invoke(main, ["build", str(a), "-o", str(out)])
    assert refused.exit_code == 2 and "lab.world is a symbolic link" in refused.stderr
    assert os.readlink(out / "lab.world") == str(tmp_path / "nowhere")
    (out / "lab.world").unlink()
    (out / "lab.world").symlink_to(victim)
    assert runner.invoke(main, ["build", str(a), "-o", str(out)]).exit_code == 2
    forced = runner.invoke(main, ["build", str(a), "-o", str(out), "--force"])
    assert forced.exit_code == 0, forced.output
    assert not (out / "lab.world").is_symlink() and victim.read_text() == "keep me\n"
    (tmp_path / "pkgs").mkdir()
    (tmp_path / "pkgs" / "lab_pkg").symlink_to(tmp_path / "elsewhere")
    assert runner.invoke(main, ["scaffold", "lab_pkg", "-p", str(tmp_path / "pkgs")]).exit_code == 2
    assert not (tmp_path / "elsewhere").exists()
    assert runner.invoke(main, ["scaffold", "lab_pkg", "-p", str(tmp_path / "pkgs"), "--force"]).exit_code == 0
    assert (tmp_path / "pkgs" / "lab_pkg").is_dir() and not (tmp_path / "pkgs" / "lab_pkg").is_symlink()


def test_leftovers_of_a_live_run_are_kept(tmp_path):
    a, _ = spec_pair(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    live = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        mine = out / f".lab.world.worldgen-tmp-{live.pid}-abcd1234"
        mine.write_text("a live run's temporary file")
        dead = out / ".lab.worldgen-staging-999999999"
        dead.mkdir()
        assert CliRunner().invoke(main, ["build", str(a), "-o", str(out)]).exit_code == 0
        assert mine.exists() and not dead.exists()
    finally:
        live.kill()
        live.wait()


@pytest.fixture
def small_disk(tmp_path):
    disk = tmp_path / "disk"
    disk.mkdir()
    if os.geteuid() != 0 or shutil.which("mount") is None:
        pytest.skip("mounting a small tmpfs needs root")
    made = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(disk)], capture_output=True)
    if made.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {made.stderr.decode().strip()}")
    yield disk
    subprocess.run(["umount", "-l", str(disk)], check=False)


def test_full_disk_and_read_only_disk_leave_nothing(tmp_path, small_disk):
    a, _ = spec_pair(tmp_path)
    runner = CliRunner()
    filler = small_disk / "filler"
    with open(filler, "wb") as fh:   # leave about 4 KB: less than the course or a world needs
        try:
            fh.write(b"\0" * (256 * 1024 - 4096))
        except OSError:
            pass
    before = sorted(os.listdir(small_disk))
    for args in (["build", str(a), "-o", str(small_disk / "new" / "out"), "--model-dir"],
                 ["course", "-w", str(small_disk / "ws")],
                 ["scaffold", "lab_pkg", "rospy", "--world", str(a), "-p", str(small_disk / "pkgs")]):
        result = runner.invoke(main, args)
        assert result.exit_code == 2, result.output
        assert result.stderr.count("\n") == 1 and "No space left on device" in result.stderr
        assert sorted(os.listdir(small_disk)) == before, args
    filler.unlink()
    assert runner.invoke(main, ["build", str(a), "-o", str(small_disk / "out")]).exit_code == 0
    subprocess.run(["mount", "-o", "remount,ro", str(small_disk)], check=True)
    old = (small_disk / "out" / "lab.world").read_bytes()
    for args in (["build", str(a), "-o", str(small_disk / "out"), "--force"],
                 ["build", str(a), "-o", str(small_disk / "new")],
                 ["course", "-w", str(small_disk / "ws")]):
        result = runner.invoke(main, args)
        assert result.exit_code == 2 and "Read-only file system" in result.stderr, result.output
    assert sorted(os.listdir(small_disk)) == ["out"] and os.listdir(small_disk / "out") == ["lab.world"]
    assert (small_disk / "out" / "lab.world").read_bytes() == old


def test_sweep_completes_a_committed_journal_and_restores_a_folder_moved_aside(tmp_path):
    """What a run killed after its commit point leaves (made by hand here, with a PID that cannot be alive): the
    next write into the folder completes the moves; a folder moved aside whose place is empty is put back."""
    import json

    from worldgen.core.fsio import sweep, write_file

    dead = 2**22 + 12345   # above Linux's pid_max
    out = tmp_path / "out"
    (out / "lab").mkdir(parents=True)
    (out / "lab.world").write_text("new world\n")                      # moved before the kill
    (out / "lab" / "model.sdf").write_text("old model\n")               # not yet
    waiting = out / "lab" / f".model.sdf.worldgen-tmp-{dead}-abcd1234"
    waiting.write_text("new model\n")
    journal = out / f".lab.world.worldgen-journal-{dead}"
    journal.write_text(json.dumps({"force": True, "moves": [
        [str(out / f".lab.world.worldgen-tmp-{dead}-gone0000"), str(out / "lab.world")],
        [str(waiting), str(out / "lab" / "model.sdf")]]}))
    uncommitted = out / f".lab.world.worldgen-tmp-{dead}-zzzz9999"
    uncommitted.write_text("half")
    aside = out / f".pkg.worldgen-old-{dead}"
    (aside / "src").mkdir(parents=True)
    sweep([out / "lab", out])
    assert (out / "lab" / "model.sdf").read_text() == "new model\n" and (out / "lab.world").read_text() == "new world\n"
    assert (out / "pkg" / "src").is_dir()
    assert state(out)[1] == []
    write_file(out / "other.txt", "x")   # an ordinary write sweeps too
    assert sorted(os.listdir(out)) == ["lab", "lab.world", "other.txt", "pkg"]


def test_without_renameat2_or_hard_links_the_same_guarantees_hold(tmp_path, monkeypatch):
    """The portable paths (no renameat2 outside Linux; no hard links on some file systems, e.g. FAT): a folder is
    moved aside then swapped; a file is claimed by rename after a check — still never over an existing output."""
    import errno as errno_

    from worldgen.core import fsio
    from worldgen.core.errors import OutputExistsError

    monkeypatch.setattr(fsio, "_renameat2", lambda src, dst, flags: False)

    def no_links(src, dst, **kwargs):
        raise OSError(errno_.EPERM, "Operation not permitted", str(dst))

    monkeypatch.setattr(fsio.os, "link", no_links)
    fsio.write_tree(tmp_path / "pkg", {"a.txt": "old"})
    with pytest.raises(OutputExistsError):
        fsio.write_tree(tmp_path / "pkg", {"b.txt": "new"})
    fsio.write_tree(tmp_path / "pkg", {"b.txt": "new"}, force=True)
    assert os.listdir(tmp_path / "pkg") == ["b.txt"]
    fsio.write_files({tmp_path / "x.txt": "1", tmp_path / "sub" / "y.txt": "2"})
    (tmp_path / "z.txt").symlink_to(tmp_path / "nowhere")
    with pytest.raises(OutputExistsError):
        fsio.write_files({tmp_path / "w.txt": "1", tmp_path / "z.txt": "2"})
    assert not (tmp_path / "w.txt").exists() and (tmp_path / "z.txt").is_symlink()
    assert sorted(os.listdir(tmp_path)) == ["pkg", "sub", "x.txt", "z.txt"]
    assert state(tmp_path)[1] == []


def test_two_scaffolds_without_force_one_wins(tmp_path):
    for k in range(4):
        procs = [start(["scaffold", "lab_pkg", "rospy", "-D", f"writer {w}", "-p", tmp_path / f"p{k}"], tmp_path)
                 for w in (0, 1)]
        results = [(p.wait(), p.communicate()) for p in procs]
        assert sorted(r[0] for r in results) == [0, 2], results
        winner = [r[0] for r in results].index(0)
        files, left = state(tmp_path / f"p{k}")
        assert not left and f"writer {winner}".encode() in files["lab_pkg/package.xml"]
