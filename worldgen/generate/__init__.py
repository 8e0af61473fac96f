"""``worldgen generate``: seeded worlds of five kinds (maze, rooms, clutter, arena, track) written as floorplan
specs, each closed, with a clear spawn and every room reachable through openings the robot fits, by construction;
the same seed gives the same bytes on every machine and every Python from 3.8 on. The entry point is
:func:`worldgen.generate.worlds.generate`."""

from __future__ import annotations
