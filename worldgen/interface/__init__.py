"""The simulated robot's interface, described once for every transport: which topics a TurtleBot3 in Gazebo has on
each stack (ROS 1 Noetic + Gazebo Classic, ROS 2 Humble + Gazebo Classic, ROS 2 Jazzy + Gazebo Sim) with their
types, rates, frames and QoS (:mod:`.topics`), and what each message holds, computed from the simulation as plain
values (:mod:`.robot`, :mod:`.camera`), and the loop that steps the simulation and says when each is due
(:mod:`.loop`).

A transport (:mod:`worldgen.ros1` over rospy, :mod:`worldgen.ros2` over DDS) only turns those values into its own
messages and puts them on its wire; it never computes a pose, a scan or a rate of its own. Message values are
nested dicts in the message's own shape (ROS 2 field names), times as float seconds of simulated time.
"""
