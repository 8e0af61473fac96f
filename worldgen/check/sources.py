"""The parent's side of every simulation: read an input into a scene (a world file, or the world a spec builds,
exactly as ``worldgen build`` writes it), then hand that scene to a job in the simulator child.

The child gets the scene pickled into a private temporary folder, so a world is read once and the simulator
drives in exactly the scene the parent's checks looked at; the simulation itself never reads or writes SDF.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..core.scene import Scene
from ..sim.process import run_isolated


@dataclass(frozen=True)
class WorldSource:
    """Where a world comes from: a file, or SDF text built from a spec (``path`` then names the spec's would-be
    world file, for messages). ``validate`` reads its jobs' worlds through it, the view its LiDAR child's."""

    path: Path
    text: str | None = None

    def read(self, model_paths=()) -> Scene:
        """The scene: the file read, or the text read as if it were that file."""
        from ..sdf.reader import read_world, read_world_text

        if self.text is not None:
            return read_world_text(self.text, source=self.path, model_paths=tuple(model_paths))
        return read_world(self.path, model_paths=tuple(model_paths))


def load_scene(path: str | Path, kind: str = "world", model_paths=()) -> tuple[Scene, dict | None]:
    """The scene of a world file, or of the world a spec builds (``kind`` "spec"), and the spec's robot entry
    ({"model", "spawn": [x, y, yaw]}) when it has one."""
    from ..sdf.reader import read_world, read_world_text

    if kind != "spec":
        return read_world(path, model_paths=tuple(model_paths)), None
    from ..sdf.writer import spec_world_sdf
    from ..spec.load import load_spec

    spec = load_spec(path)
    scene = read_world_text(spec_world_sdf(spec), source=spec.source or path, model_paths=tuple(model_paths))
    robot = None
    if spec.robot is not None:
        robot = {"model": spec.robot.model, "spawn": [spec.robot.at[0], spec.robot.at[1], spec.robot.yaw]}
    return scene, robot


def run_on_scene(target: str, scene: Scene, kwargs: dict, timeout: float, folder: str | Path | None = None) -> dict:
    """``run_isolated(target, {"scene_file": …, **kwargs})`` with ``scene`` pickled into ``folder`` (a private
    temporary folder of its own when None)."""
    if folder is None:
        with tempfile.TemporaryDirectory(prefix="worldgen-") as tmp:
            return run_on_scene(target, scene, kwargs, timeout, tmp)
    scene_file = Path(folder) / "scene.pickle"
    scene.save(scene_file)
    return run_isolated(target, {"scene_file": str(scene_file), **kwargs}, timeout)
