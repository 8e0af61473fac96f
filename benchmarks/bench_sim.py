"""Speed of the pybullet session: steps/s and simulated-to-real time ratio (target > 100×), LiDAR scan time, and
a complete spin + stop-at-wall run, in the class's enclosed room (from the shared corpus, else the same room
built by hand) and, when the corpus is there, in ROBOTIS's turtlebot3_world (cylinders and triangle meshes).

    .venv/bin/python benchmarks/bench_sim.py
"""

from __future__ import annotations

import math
import statistics
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from worldgen.core.scene import Scene, Shape  # noqa: E402

CORPUS = REPO.parent / "shared" / "corpus"
CLASS_ROOM = (CORPUS / "worlds" /
              "Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world")
TB3_WORLD = (CORPUS / "worlds" /
             "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_world.world")


def hand_room() -> Scene:
    """A 5 m room of 0.15 m walls around the origin, as the class's enclosed room is."""
    walls = [((2.5, 0), (0.15, 5)), ((-2.5, 0), (0.15, 5)), ((0, 2.5), (5, 0.15)), ((0, -2.5), (5, 0.15))]
    return Scene(source=None, shapes=[
        Shape("box", (x, y, 1.25), size=(sx, sy, 2.5), model="room", link=f"Wall_{i}", name="collision")
        for i, ((x, y), (sx, sy)) in enumerate(walls)])


def worlds():
    """(name, scene or world path, spawn) for each world benchmarked."""
    if CLASS_ROOM.is_file():
        yield "class enclosed room (corpus)", str(CLASS_ROOM), (-4.905, -1.415, 0.0)
    else:
        yield "5 m room (hand-built)", hand_room(), (0.0, 0.0, 0.0)
    if TB3_WORLD.is_file():
        yield "turtlebot3_world (corpus)", str(TB3_WORLD), (-2.0, -0.5, 0.0)


def scene_of(world) -> Scene:
    if isinstance(world, Scene):
        return world
    from worldgen.sdf.reader import read_world
    return read_world(world, model_paths=(str(CORPUS / "gazebo_models"),))


def bench_session(name: str, scene: Scene, spawn, repeats: int = 3) -> None:
    """Median and best of ``repeats`` sessions (other processes on a 2-core machine make single runs noisy)."""
    from worldgen.sim.session import DEFAULT_SOLVER_ITERATIONS, DEFAULT_TIME_STEP, Session

    setups, ratios, scans = [], [], []
    sim = 20.0
    for _ in range(repeats):
        t0 = time.perf_counter()
        with Session(scene, "burger", spawn) as session:
            setups.append(time.perf_counter() - t0)
            session.run(0.5)
            session.cmd_vel(0.05, 1.0)   # circle slowly in place: wheel contacts busy, walls far
            t0 = time.perf_counter()
            session.run(sim)
            ratios.append(sim / (time.perf_counter() - t0))
            for _ in range(100):
                t0 = time.perf_counter()
                session.scan()
                scans.append(time.perf_counter() - t0)
    ratio, best = statistics.median(ratios), max(ratios)
    print(f"{name}: {len(scene.shapes)} shapes; session setup median {statistics.median(setups) * 1000:.0f} ms")
    print(f"  step {DEFAULT_TIME_STEP:.5f} s, {DEFAULT_SOLVER_ITERATIONS} solver iterations: "
          f"{ratio / DEFAULT_TIME_STEP:,.0f} steps/s, {ratio:.0f}x real time (best {best:.0f}x; target > 100x)")
    print(f"  LiDAR scan (360 rays, noise, quantised): median {statistics.median(scans) * 1000:.2f} ms")


def bench_exercise(name: str, world, spawn) -> None:
    """A complete spin + stop-at-wall (kp 0.5), in-process and through run_isolated (process start included)."""
    from worldgen.check.sources import load_scene, run_on_scene
    from worldgen.core.stoplaw import StopLaw
    from worldgen.sim.behaviours import settle, spin, stop_at_wall
    from worldgen.sim.exercise import Exercise
    from worldgen.sim.session import Session

    scene = scene_of(world)
    t0 = time.perf_counter()
    with Session(scene, "burger", spawn) as session:
        settle(session, 0.5)
        turn = spin(session, seconds=2 * math.pi / 1.5, omega=1.5)
        stop = stop_at_wall(session, StopLaw(target=0.5, kp=0.5), duration=20.0)
        sim = session.t
    wall = time.perf_counter() - t0
    final = "-" if stop.final_distance is None else f"{stop.final_distance:.3f} m"
    print(f"  spin + stop-at-wall in-process: {wall:.2f} s wall for {sim:.1f} s simulated "
          f"(drift {turn.max_drift * 1000:.0f} mm; stopped at {final}, contacts {len(stop.contacts)})")
    if isinstance(world, str):
        t0 = time.perf_counter()
        read, _ = load_scene(world, model_paths=[str(CORPUS / "gazebo_models")])
        run_on_scene("worldgen.sim.exercise:drive_exercise", read,
                     {"world": world, "exercise": Exercise(spawn=tuple(spawn)).to_dict()}, 120.0)
        print(f"  worldgen drive's job (read world + stop-at-wall, isolated process): "
              f"{time.perf_counter() - t0:.2f} s wall")


def main() -> None:
    t0 = time.perf_counter()
    import pybullet  # noqa: F401
    print(f"import pybullet: {(time.perf_counter() - t0) * 1000:.0f} ms")
    for name, world, spawn in worlds():
        bench_session(name, scene_of(world), spawn)
        bench_exercise(name, world, spawn)


if __name__ == "__main__":
    main()
