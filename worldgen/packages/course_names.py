"""The names of the class's packages, which the course writers give them and the checks recognise (a lab's launch
file starts the world of another course package): here, so that reading them loads none of the writers."""

from __future__ import annotations

REPOSITORY = "intro_robo"                              # the metapackage, and the folder under src/
WORLD_PACKAGE = "class_meeting_02_custom_gazebo_world"  # the enclosed room every lab A launch file starts
LINE_PACKAGE = "lab_b_line_follower"                    # lab B: its own world with the tape loop
SHARED_WORLD_PACKAGES = (WORLD_PACKAGE, LINE_PACKAGE)   # course packages whose worlds launch files start
