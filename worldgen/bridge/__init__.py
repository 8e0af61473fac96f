"""The ROS 1 side of the simulator: to a rospy node, worldgen looks like Gazebo with the TurtleBot3 plugins.

:mod:`.node` is the simulator node (a :class:`~worldgen.sim.session.Session` behind ``/scan``, ``/odom``, ``/tf``,
``/cmd_vel`` …); :mod:`.master` starts and stops a ROS master; :mod:`.rosenv` finds the system's ROS 1 Python;
:mod:`.nodes` and :mod:`.supervise` resolve and run the students' nodes; :mod:`.run` runs one exercise (or a folder
of submissions) and :mod:`.metrics`, :mod:`.rubrics` and :mod:`.record` say what the robot did. The simulation
never imports any of this.
"""
