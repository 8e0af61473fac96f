"""Reader speed: the class world (a few ms) and a 400-room Building-Editor building, 1600 walls (well under 0.5 s).

Run: ``python benchmarks/bench_reader.py [CORPUS_DIR]``. Prints median wall-clock times; the building is written
the way Gazebo saves a world (visual, material, surface and meta blocks per wall), about 4 MB of SDF.
"""

from __future__ import annotations

import math
import statistics
import sys
import tempfile
import time
from pathlib import Path

from worldgen.sdf.reader import read_world

CORPUS = Path(__file__).resolve().parent.parent.parent / "shared" / "corpus"
CLASS_WORLD = "worlds/Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world"

WALL = """      <link name='Wall_{i}'>
        <collision name='Wall_{i}_Collision'>
          <geometry><box><size>5 0.15 2.5</size></box></geometry>
          <pose>0 0 1.25 0 -0 0</pose>
          <surface><contact><ode/></contact><bounce/><friction><torsional><ode/></torsional><ode/></friction></surface>
          <max_contacts>10</max_contacts>
        </collision>
        <visual name='Wall_{i}_Visual'>
          <pose>0 0 1.25 0 -0 0</pose>
          <geometry><box><size>5 0.15 2.5</size></box></geometry>
          <material>
            <script><uri>file://media/materials/scripts/gazebo.material</uri><name>Gazebo/Grey</name></script>
            <ambient>1 1 1 1</ambient>
          </material>
          <meta><layer>0</layer></meta>
        </visual>
        <pose>{x:.4f} {y:.4f} 0 0 -0 {yaw:.5f}</pose>
        <self_collide>0</self_collide>
        <enable_wind>0</enable_wind>
        <kinematic>0</kinematic>
      </link>
"""


def building(rooms: int = 400) -> str:
    """``rooms`` 5 × 5 m rooms on a 20-wide grid, 4 walls each (so 4 × rooms boxes)."""
    links = []
    for r in range(rooms):
        cx, cy = (r % 20) * 5.0, (r // 20) * 5.0
        for k, (dx, dy, yaw) in enumerate(((0, -2.5, 0), (2.5, 0, math.pi / 2), (0, 2.5, math.pi),
                                           (-2.5, 0, -math.pi / 2))):
            links.append(WALL.format(i=4 * r + k, x=cx + dx, y=cy + dy, yaw=yaw))
    return ("<sdf version='1.7'>\n  <world name='default'>\n    <model name='building'>\n"
            "      <pose>0 0 0 0 -0 0</pose>\n" + "".join(links) + "      <static>1</static>\n    </model>\n"
            "  </world>\n</sdf>\n")


def median_ms(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append((time.perf_counter() - start) * 1000)
    return statistics.median(times)


def main() -> None:
    corpus = Path(sys.argv[1]) if len(sys.argv) > 1 else CORPUS
    if (corpus / CLASS_WORLD).is_file():
        ms = median_ms(lambda: read_world(corpus / CLASS_WORLD), 50)
        print(f"class world (4 walls, <state>):        {ms:7.2f} ms median of 50")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "building.world"
        path.write_text(building())
        scene = read_world(path)
        ms = median_ms(lambda: read_world(path), 7)
        size = path.stat().st_size / 1e6
        print(f"400-room building ({len(scene.shapes)} boxes, {size:.1f} MB): {ms:7.2f} ms median of 7")


if __name__ == "__main__":
    main()
