"""SDF in and out: ``writer`` turns a built floorplan into a Gazebo world or model folder; ``reader`` reads any
world or model file (ours or saved by Gazebo) into a scene. Import the submodule you need: the reader pulls in
trimesh and numpy, the writer only lxml."""
