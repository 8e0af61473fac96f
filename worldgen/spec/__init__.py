"""Floorplan specs: the spec model (:mod:`.model`) and its reader: the entry points (:mod:`.load`), YAML composed into
line-numbered nodes (:mod:`.nodes`), one value read and checked (:mod:`.values`), a spec's parts (:mod:`.walls`,
:mod:`.objects`, :mod:`.markings`, :mod:`.grid_spec`), the wording of messages (:mod:`.messages`); ASCII grids
(:mod:`.grid`) and ROS map_server maps (:mod:`.maps`). Imports nothing heavy: no pybullet, trimesh or shapely."""
