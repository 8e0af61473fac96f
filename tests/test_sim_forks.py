"""Isolated runs forked from a warm server (``worldgen validate``'s simulations): the same answers and errors as
a child process, a crash or a hang ends only its own run, nothing is left behind, and the server is made only
where forking is safe. Each case runs in a fresh Python (the test process itself runs threads)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent

TARGETS = '''
import ctypes, os, time

def double(x):
    print("python-level noise")
    os.write(1, b"C-level noise on fd 1\\n")
    os.write(2, b"a line on stderr\\n")
    return {"x": 2 * x, "far": float("inf"), "pid": os.getpid()}

def bad_input():
    from worldgen.core.errors import InputError
    raise InputError("unknown thing", path="a.world", line=3, hint="fix it")

def bug():
    return {}["missing"]

def crash():
    os.write(2, b"about to crash\\n")
    ctypes.string_at(0)

def hang():
    time.sleep(30)
'''


def run_script(tmp_path: Path, body: str) -> tuple[dict, str]:
    (tmp_path / "fork_targets.py").write_text(TARGETS)
    script = tmp_path / "script.py"
    script.write_text(textwrap.dedent(body))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join((str(REPO), str(tmp_path))))
    proc = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env, timeout=120)
    assert proc.returncode == 0, proc.stderr
    *_, last = proc.stdout.strip().splitlines()
    return json.loads(last), proc.stdout


def test_a_fork_answers_as_a_child_process_would(tmp_path):
    found, stdout = run_script(tmp_path, """
        import json, os
        from worldgen.core.errors import InputError
        from worldgen.sim.forkserver import forking
        from worldgen.sim.process import SimError, run_isolated

        out = {}
        with forking(["fork_targets"]) as server:
            out["server"] = server.pid
            out["first"] = run_isolated("fork_targets:double", {"x": 21})
            out["second"] = run_isolated("fork_targets:double", {"x": 2})
            try:
                run_isolated("fork_targets:bad_input")
            except InputError as err:
                out["input_error"] = [err.message, err.path, err.line, err.hint]
            try:
                run_isolated("fork_targets:bug")
            except SimError as err:
                out["bug"] = [str(err), "missing" in err.child_traceback]
        out["me"] = os.getpid()
        print(json.dumps(out))
    """)
    first, second = found["first"], found["second"]
    assert (first["x"], first["far"], second["x"]) == (42, float("inf"), 4)
    assert first["pid"] not in (found["me"], found["server"]) and first["pid"] != second["pid"]   # a fork each
    assert "noise" not in stdout and "stderr" not in stdout   # the worker's output never reaches the command's
    assert found["input_error"] == ["unknown thing", "a.world", 3, "fix it"]
    assert found["bug"] == ["KeyError: 'missing'", True]


def test_a_crash_or_a_hang_ends_its_run_alone_and_nothing_is_left(tmp_path):
    found, _ = run_script(tmp_path, """
        import json, os, time
        from worldgen.sim.forkserver import forking
        from worldgen.sim.process import SimCrashed, run_isolated

        def alive(pid):
            try:
                os.kill(pid, 0)
            except ProcessLookupError:
                return False
            return True

        out = {}
        with forking(["fork_targets"]) as server:
            try:
                run_isolated("fork_targets:crash")
            except SimCrashed as err:
                out["crash"] = [err.rc, str(err), err.stderr_tail]
            started = time.monotonic()
            try:
                run_isolated("fork_targets:hang", timeout=1.0)
            except SimCrashed as err:
                out["hang"] = [err.timed_out, str(err), round(time.monotonic() - started)]
            out["after"] = run_isolated("fork_targets:double", {"x": 1})["x"]
            worker = run_isolated("fork_targets:double", {"x": 1})["pid"]
        out["left"] = [pid for pid in (server.pid, worker) if alive(pid)]
        print(json.dumps(out))
    """)
    rc, message, tail = found["crash"]
    assert rc == -11 and message.startswith("the simulation process running fork_targets:crash was killed by "
                                            "signal 11") and tail == "about to crash"
    timed_out, message, seconds = found["hang"]
    assert timed_out and "did not finish within 1 s" in message and seconds < 5
    assert found["after"] == 2    # the server serves on after a crash and a hang
    assert found["left"] == []


def test_runs_from_threads_at_once(tmp_path):
    found, _ = run_script(tmp_path, """
        import json
        from concurrent.futures import ThreadPoolExecutor
        from worldgen.sim.forkserver import forking
        from worldgen.sim.process import run_isolated

        with forking(["fork_targets"]):
            with ThreadPoolExecutor(4) as pool:
                got = list(pool.map(lambda x: run_isolated("fork_targets:double", {"x": x})["x"], range(8)))
        print(json.dumps(got))
    """)
    assert found == [2 * x for x in range(8)]


def test_no_server_where_threads_run_and_runs_keep_their_child_process(tmp_path):
    found, _ = run_script(tmp_path, """
        import json, os, threading
        from worldgen.sim.forkserver import forking
        from worldgen.sim.process import run_isolated

        stop = threading.Event()
        thread = threading.Thread(target=stop.wait)
        thread.start()
        with forking(["fork_targets"]) as server:
            answer = run_isolated("fork_targets:double", {"x": 5})
        stop.set()
        print(json.dumps({"server": server is not None, "x": answer["x"]}))
    """)
    assert found == {"server": False, "x": 10}


def test_validate_starts_its_server_before_anything_runs_threads():
    """``worldgen validate`` forks its server first thing: by then the command has imported no numpy (whose BLAS
    starts threads), pybullet, shapely or lxml, and runs one thread."""
    code = ("import sys; from worldgen.cli import main; main.get_command(None, 'validate'); "
            "from worldgen.sim.forkserver import thread_count; "
            "heavy = sorted(m for m in ('numpy', 'pybullet', 'shapely', 'lxml', 'yaml', 'rospy') if m in sys.modules); "
            "print(heavy, thread_count())")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=REPO,
                          env=dict(os.environ, PYTHONPATH=str(REPO)))
    assert proc.stdout.strip() == "[] 1", proc.stderr


ROOM = ("<sdf version='1.6'><world name='w'><model name='room'><static>1</static>"
        + "".join(f"<link name='w{i}'><pose>{x} {y} 0.25 0 0 {yaw}</pose><collision name='c'><geometry><box>"
                  "<size>4 0.1 0.5</size></box></geometry></collision></link>"
                  for i, (x, y, yaw) in enumerate([(0, 2, 0), (0, -2, 0), (2, 0, 1.5708), (-2, 0, 1.5708)]))
        + "</model></world></sdf>")


def test_the_program_forks_validates_server_before_click_and_the_checks_load(tmp_path):
    """``worldgen validate`` (the program, not the library) forks its simulations' server first of all, before
    click, numpy or the checks are imported, and the command simulates through that one server: the same report
    as a validate that starts its own."""
    world = tmp_path / "room.world"
    world.write_text(ROOM)
    script = tmp_path / "program.py"
    script.write_text(textwrap.dedent("""
        import contextlib, json, sys
        import worldgen.sim.forkserver as forkserver

        real, seen = forkserver.forking, []

        @contextlib.contextmanager
        def forking(preload):
            seen.append({"loaded": sorted(m for m in ("click", "numpy", "lxml", "worldgen.check.checks")
                                          if m in sys.modules), "threads": forkserver.thread_count()})
            with real(preload) as server:
                yield server
            print(json.dumps(seen), file=sys.stderr)

        forkserver.forking = forking
        sys.argv = ["worldgen", "validate", sys.argv[1], "--format", "json"]
        from worldgen.__main__ import run
        run()
    """))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join((str(REPO), str(tmp_path))))
    proc = subprocess.run([sys.executable, str(script), str(world)], capture_output=True, text=True, env=env,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stderr.strip().splitlines()[-1]) == [{"loaded": [], "threads": 1}]
    library = subprocess.run([sys.executable, "-c", "from worldgen.cli import run; run()", "validate", str(world),
                              "--format", "json"], capture_output=True, text=True, env=env, timeout=120)
    assert library.returncode == 0 and json.loads(library.stdout) == json.loads(proc.stdout)


@pytest.mark.parametrize("args", [["validate", "--no-such-option"], ["validate", "missing.world"]],
                         ids=["usage-error", "missing-file"])
def test_the_programs_early_server_ends_with_the_command(tmp_path, args):
    """A server forked for a validate that then simulates nothing (a usage error, no file to read): the command's
    one line and exit status 2, and neither a process nor the server's folder left behind."""
    from bridgetools import no_leftovers

    marker = f"WORLDGEN_EARLY_TEST={tmp_path.name}"
    env = dict(os.environ, PYTHONPATH=str(REPO), TMPDIR=str(tmp_path), WORLDGEN_EARLY_TEST=tmp_path.name)
    proc = subprocess.run([sys.executable, "-m", "worldgen", *args], capture_output=True, text=True, env=env,
                          cwd=tmp_path, timeout=120)
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1, proc.stderr
    no_leftovers(marker)
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith("worldgen-forks-")) == []


def test_a_crash_in_the_forked_simulation_is_a_finding(tmp_path):
    """The whole command: the simulation, forked from validate's server, aborts; the world still gets its
    geometric checks and one error naming the stage, never a traceback."""
    (tmp_path / "crashing_job.py").write_text(
        "import os\n\ndef simulate(stage_file=None, **kwargs):\n"
        "    open(stage_file, 'w').write('spinning in place')\n    os.abort()\n")
    world = tmp_path / "room.world"
    world.write_text(ROOM)
    script = tmp_path / "crash_validate.py"
    script.write_text(textwrap.dedent("""
        import contextlib, sys
        import worldgen.sim.forkserver as forkserver

        real = forkserver.forking

        @contextlib.contextmanager
        def forking(preload):   # the job swapped for the crashing one once the real server runs
            with real(preload) as server:
                assert server is not None, "no fork server"
                import worldgen.check.validate
                worldgen.check.validate.SIM_JOB = "crashing_job:simulate"
                yield server

        forkserver.forking = forking
        from worldgen.cli import main
        sys.argv = ["worldgen", "validate", sys.argv[1], "--format", "json"]
        main()
    """))
    proc = subprocess.run([sys.executable, str(script), str(world)], capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=os.pathsep.join((str(REPO), str(tmp_path)))), timeout=120)
    assert proc.returncode == 1 and "Traceback" not in proc.stderr, proc.stderr
    [result] = json.loads(proc.stdout)["results"]
    [crash] = [f for f in result["findings"] if f["severity"] == "error"]
    assert crash["message"] == "pybullet crashed (killed by SIGABRT) while spinning in place"
    assert result["metrics"]["enclosed"] is True


@pytest.mark.parametrize("module", ["worldgen.sim.forkserver"])
def test_the_server_module_imports_nothing_heavy(module):
    code = (f"import sys, {module}; "
            "print(sorted(m for m in ('numpy', 'pybullet', 'shapely', 'lxml') if m in sys.modules))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=str(REPO)))
    assert proc.stdout.strip() == "[]", proc.stderr


def test_an_early_run_that_read_another_world_is_simulated_again_on_the_checked_scene(tmp_path):
    """An early child reads the world itself; when what it read is not the scene checked here (the file changed
    between the two reads), its numbers are dropped and the checked scene is simulated."""
    from worldgen.check import sim_run
    from worldgen.check.report import Result
    from worldgen.check.sources import WorldSource
    from worldgen.check.validate import SIM_JOB, Options
    from worldgen.sim.process import start_isolated

    def room(path: Path, half: float) -> Path:
        walls = "".join(
            f"<link name='w{i}'><pose>{x} {y} 0.25 0 0 {yaw}</pose><collision name='c'><geometry><box>"
            f"<size>{2 * half + 0.1} 0.1 0.5</size></box></geometry></collision></link>"
            for i, (x, y, yaw) in enumerate([(0, half, 0), (0, -half, 0), (half, 0, 1.5708), (-half, 0, 1.5708)]))
        path.write_text(f"<sdf version='1.6'><world name='w'><model name='room'><static>1</static>{walls}"
                        "</model></world></sdf>")
        return path

    big, small = room(tmp_path / "big.world", 2.0), room(tmp_path / "small.world", 1.2)
    options = Options(spawn=(0.0, 0.0, 0.0))
    result = Result(path=str(small), spawn=(0.0, 0.0, 0.0), robot="burger")
    (tmp_path / "job").mkdir()
    early = sim_run.EarlyRun(start_isolated(SIM_JOB, {
        **sim_run._kwargs(result, options, tmp_path / "job"), "world": {"path": str(big), "text": None}}))
    scene = WorldSource(small).read()
    early.read(scene)
    sim_run.judge(result, early, scene, options, (0.0, None), tmp_path / "job", SIM_JOB)
    assert result.metrics["lidar_nearest_m"] < 1.2   # the small room's walls (the big one's are 1.9 m away)


def test_rooms_simulated_ahead_give_what_each_room_gives_from_its_own_spawn(tmp_path):
    """A world of several closed rooms and no spawn: under the fork server the rooms' simulations start ahead of
    the checks that wait for them (check.sim_run.Ahead), each still driving from its own room's spawn, with the
    numbers that room gives when validated alone from that spawn."""
    spec = tmp_path / "three.yaml"
    spec.write_text("name: three\nrooms:\n"
                    "  - {name: wide, rect: {center: [4, 4], size: [5, 3]}}\n"
                    "  - {name: small, rect: {center: [-3, 0], size: [2, 2]}}\n"
                    "  - {name: long, rect: {center: [0, -6], size: [7, 2.5]}}\n")

    def results(*extra) -> list[dict]:
        proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", str(spec), "--format", "json", *extra],
                              capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=str(REPO)), timeout=120)
        assert proc.returncode in (0, 1) and "Traceback" not in proc.stderr, proc.stderr
        return json.loads(proc.stdout)["results"]

    sim_numbers = ("stop_distance_m", "stop_time_s", "spin_drift_m", "settle_height_m", "sim_seconds")
    rooms = results()
    assert len(rooms) == 3 and len({r["metrics"]["stop_distance_m"] for r in rooms}) > 1
    for room in rooms:
        [alone] = results("--spawn", ",".join(f"{v:g}" for v in room["spawn"]))
        assert [room["metrics"].get(k) for k in sim_numbers] == [alone["metrics"].get(k) for k in sim_numbers]
        assert room["checks"] == alone["checks"]


def test_ctrl_c_in_the_middle_of_a_validate_leaves_nothing(tmp_path):
    """Ctrl-C while the program validates a folder of worlds, a simulation forked from its early server under way:
    click's "Aborted!" and exit 1, and neither a process nor the server's folder left behind."""
    import signal
    import time

    from bridgetools import no_leftovers

    worlds = tmp_path / "worlds"
    worlds.mkdir()
    for i in range(30):
        (worlds / f"room_{i:02d}.world").write_text(ROOM)
    marker = f"WORLDGEN_EARLY_TEST={tmp_path.name}"
    env = dict(os.environ, PYTHONPATH=str(REPO), TMPDIR=str(tmp_path), WORLDGEN_EARLY_TEST=tmp_path.name)
    proc = subprocess.Popen([sys.executable, "-m", "worldgen", "validate", str(worlds)], env=env, cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    said = ""
    while not said.startswith("[1/30]") and proc.poll() is None:   # the first world checked, the next simulating
        said = proc.stderr.readline()
    assert said.startswith("[1/30]"), said + proc.stderr.read()
    time.sleep(0.1)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 1 and err.strip().endswith("Aborted!") and "Traceback" not in err, err
    no_leftovers(marker)
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith("worldgen-forks-")) == []
