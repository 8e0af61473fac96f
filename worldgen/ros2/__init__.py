"""The ROS 2 transport: the simulated robot over DDS (PyPI cyclonedds), as Gazebo's ROS 2 plugins and
ros_gz_bridge publish it."""
