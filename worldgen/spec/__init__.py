"""Floorplan specs: the spec model (:mod:`.model`), its YAML reader (:mod:`.load`), ASCII grids (:mod:`.grid`) and
ROS map_server maps (:mod:`.maps`). Imports nothing heavy: no pybullet, trimesh or shapely."""
