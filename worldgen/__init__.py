"""worldgen: floorplan specs to Gazebo worlds, launch files and catkin packages; worlds checked in pybullet.

The library is importable without the heavy simulation stack: pybullet, trimesh and matplotlib are imported
only by the modules that need them (``worldgen.sim``, ``worldgen.sdf.reader``, ``worldgen.view``).
"""

__version__ = "0.1.0"
