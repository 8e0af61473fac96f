"""pybullet simulation of a TurtleBot3 in a world: session, LiDAR, camera (drawn with OpenGL on the CPU), diff
drive, behaviours, isolated runs.

Importing this package imports nothing heavy; :mod:`.process` runs sessions in a child process."""
