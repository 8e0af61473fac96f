"""Isolated runs (results, errors, crashes, timeouts) and the ``worldgen drive`` command end to end."""

from __future__ import annotations

import json
import math
import textwrap

import pytest
from conftest import CliRunner

from worldgen.cli import main
from worldgen.cli.drive import gain_sets
from worldgen.sim.exercise import Gains
from worldgen.core.errors import InputError
from worldgen.sim.process import SimCrashed, SimError, run_isolated

TARGETS = '''
import ctypes, os, time

def double(x):
    print("python-level noise")
    os.write(1, b"C-level noise on fd 1\\n")
    return {"x": 2 * x, "far": float("inf")}

def bad_input():
    from worldgen.core.errors import InputError
    raise InputError("unknown thing", path="a.world", line=3, hint="fix it")

def bug():
    return {}["missing"]

def crash():
    ctypes.string_at(0)

def hang():
    time.sleep(30)
'''


@pytest.fixture()
def child_env(tmp_path, monkeypatch):
    (tmp_path / "sim_targets.py").write_text(TARGETS)
    monkeypatch.setenv("PYTHONPATH", str(tmp_path))


def test_run_isolated_returns_the_result_and_keeps_stdout_clean(child_env):
    assert run_isolated("sim_targets:double", {"x": 21}) == {"x": 42, "far": math.inf}


def test_run_isolated_raises_the_childs_errors(child_env):
    with pytest.raises(InputError) as err:
        run_isolated("sim_targets:bad_input")
    assert (err.value.path, err.value.line, err.value.hint) == ("a.world", 3, "fix it")
    with pytest.raises(SimError, match="KeyError") as err:
        run_isolated("sim_targets:bug")
    assert "missing" in err.value.child_traceback


def test_run_isolated_reports_crashes_and_timeouts(child_env):
    with pytest.raises(SimCrashed, match="killed by signal 11") as err:
        run_isolated("sim_targets:crash")
    assert err.value.rc == -11
    with pytest.raises(SimCrashed, match="within 1 s") as err:
        run_isolated("sim_targets:hang", timeout=1.0)
    assert err.value.timed_out


def test_gain_sets():
    assert gain_sets((), (), ()) == (Gains(kp=0.5, ki=0.0, kd=0.0),)
    assert gain_sets((0.3, 1.0), (0.1,), ()) == (Gains(kp=0.3, ki=0.1, kd=0.0), Gains(kp=1.0, ki=0.1, kd=0.0))
    with pytest.raises(InputError, match="--kd is given 2 times for 3 runs"):
        gain_sets((1, 2, 3), (), (0.1, 0.2))


ROOM = textwrap.dedent("""\
    <?xml version="1.0"?>
    <sdf version="1.6">
      <world name="default">
        <model name="room">
          <static>1</static>
          <link name="Wall_0"><pose>1.5 0 1 0 0 0</pose>
            <collision name="c"><geometry><box><size>0.15 3 2</size></box></geometry></collision></link>
          <link name="Wall_1"><pose>-1.5 0 1 0 0 0</pose>
            <collision name="c"><geometry><box><size>0.15 3 2</size></box></geometry></collision></link>
          <link name="Wall_2"><pose>0 1.5 1 0 0 0</pose>
            <collision name="c"><geometry><box><size>3 0.15 2</size></box></geometry></collision></link>
          <link name="Wall_3"><pose>0 -1.5 1 0 0 0</pose>
            <collision name="c"><geometry><box><size>3 0.15 2</size></box></geometry></collision></link>
        </model>
      </world>
    </sdf>
    """)


@pytest.fixture()
def world(tmp_path):
    path = tmp_path / "room.world"
    path.write_text(ROOM)
    return path


def test_drive_stop_at_wall_with_plot_and_csv(world, tmp_path):
    plot, csv = tmp_path / "steps.png", tmp_path / "steps.csv"
    result = CliRunner().invoke(main, ["drive", str(world), "--spawn", "-0.5,0", "--kp", "0.5", "--kp", "1",
                                       "--duration", "16", "--plot", str(plot), "--csv", str(csv),
                                       "--format", "json"])
    assert result.exit_code == 0, result.output
    report = json.loads(result.output)
    assert report["ok"] and report["spawn"] == [-0.5, 0.0, 0.0] and report["spawn_source"] == "--spawn"
    assert [run["kp"] for run in report["runs"]] == [0.5, 1.0]
    for run in report["runs"]:
        assert run["final_distance"] == pytest.approx(0.5, abs=0.05) and run["contacts"] == []
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = csv.read_text().splitlines()
    assert rows[0] == "run,kp,ki,kd,t,distance,measured,v_cmd,v" and len(rows) == 1 + 2 * 81
    assert rows[1].startswith("1,0.5,0,0,0.0000,1.9")
    again = CliRunner().invoke(main, ["drive", str(world), "--spawn", "-0.5,0", "--csv", str(csv)])
    assert again.exit_code == 2 and "exists" in again.output
    text = CliRunner().invoke(main, ["drive", str(world), "--spawn", "-0.5,0", "--csv", str(csv), "--force"])
    assert text.exit_code == 0 and text.stdout.splitlines()[-1] == f"wrote {csv}"   # the text report says so


def test_drive_reports_a_collision_with_exit_1(world):
    result = CliRunner().invoke(main, ["drive", str(world), "--spawn", "-0.5,0", "--kp", "2", "--max-speed", "1", "--target", "0.15",
                                       "--duration", "12"])
    assert result.exit_code == 1
    assert "FAILED: touched room/Wall_" in result.output


def test_drive_out_of_an_open_room_says_so_not_to_tune_the_gains(tmp_path):
    """Facing a missing wall, the law drives out of the room and ends with nothing ahead: the reason is the
    world (validate names the gap), not the gains; no advice to try a larger --kp."""
    spec = tmp_path / "three_walls.yaml"
    spec.write_text("name: three_walls\nsegments:\n"
                    "  - {from: [-2, -2], to: [-2, 2]}\n  - {from: [-2, -2], to: [2, -2]}\n"
                    "  - {from: [-2, 2], to: [2, 2]}\n")
    result = CliRunner().invoke(main, ["drive", str(spec), "--spawn", "0,0", "--duration", "20"])
    assert result.exit_code == 1, result.output
    assert "no wall ahead at the end: the robot saw nothing to stop at" in result.output
    assert "worldgen validate WORLD names the gaps" in result.output and "--kp" not in result.output


def test_drive_spin(world):
    result = CliRunner().invoke(main, ["drive", str(world), "--behavior", "spin", "--robot", "waffle",
                                       "--omega", "1.82", "--format", "json"])
    assert result.exit_code == 0, result.output
    run = json.loads(result.output)["runs"][0]
    assert run["max_drift"] < 0.03 and run["turned"] == pytest.approx(2 * math.pi, rel=0.05)


@pytest.mark.parametrize("args, words", [
    (["--robot", "tank"], "unknown robot"),
    (["--spawn", "1,x"], "bad --spawn"),
    (["--kp", "1", "--kp", "2", "--ki", "1", "--ki", "2", "--ki", "3"], "--kp is given 2 times for 3 runs"),
    (["--kp", "nan"], "nan is not a finite number"),
    (["--target", "nan"], "nan is not a finite number"),
    (["--duration", "nan"], "nan is not a finite number"),
    (["--target", "-0.5"], "not in the range x>0.0"),
    (["--spawn", "5,5"], "--spawn (5.0, 5.0) is no place for the robot: it is outside the room"),
    (["--spawn", "1.45,0"], "it is inside a wall"),
    (["--spawn", "1.3,0,3.14"], "the robot reaches 0.148 m from its centre"),
])
def test_drive_bad_input_exits_2(world, args, words):
    result = CliRunner().invoke(main, ["drive", str(world), *args])
    assert result.exit_code == 2 and words in result.output and "Traceback" not in result.output


def test_drive_turns_a_simulator_crash_into_one_line(world, monkeypatch):
    import worldgen.check.sources as sources   # where drive's simulator child is started

    def crashed(*args, **kwargs):
        raise SimCrashed("the simulation process running x was killed by signal 11", rc=-11,
                         stderr_tail="Traceback (most recent call last):\n  pybullet said something")

    monkeypatch.setattr(sources, "run_isolated", crashed)
    result = CliRunner().invoke(main, ["drive", str(world)])
    assert result.exit_code == 2 and "Traceback" not in result.output
    (line,) = result.output.splitlines()
    assert line.startswith(f"worldgen: error: {world}: the simulation failed: ") and "signal 11" in line


def test_drive_missing_world_exits_2(tmp_path):
    result = CliRunner().invoke(main, ["drive", str(tmp_path / "nope.world")])
    assert result.exit_code == 2 and "no such file" in result.output


def test_drive_from_a_spec(tmp_path):
    pytest.importorskip("worldgen.sdf.writer")
    spec = tmp_path / "box.yaml"
    spec.write_text("name: box\nrooms:\n  - name: main\n    rect: {center: [0, 0], size: [3, 3]}\n"
                    "robot: {model: burger, at: [-0.5, 0], yaw: 0}\n")
    result = CliRunner().invoke(main, ["drive", str(spec), "--duration", "16", "--format", "json"])
    assert result.exit_code == 0, result.output
    report = json.loads(result.output)
    assert report["spawn"] == [-0.5, 0.0, 0.0] and report["spawn_source"] == "the spec's robot entry"
    assert report["runs"][0]["final_distance"] == pytest.approx(0.5, abs=0.05)
