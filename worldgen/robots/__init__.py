"""Robot descriptions: our own TurtleBot3 xacro files (``worldgen_turtlebot3/``) and the code that turns a model
name or a user's file into URDF text (:mod:`.description`) and reads what a simulator needs from it
(:mod:`.profile`). Importing this package is cheap: xacro is imported only when a file is processed."""

from .description import MODELS, absolute_mesh_paths, find_package, robot_file, robot_urdf

__all__ = ["MODELS", "absolute_mesh_paths", "find_package", "robot_file", "robot_urdf"]
