"""The ROS side: launch files (writer and reader), catkin packages (scaffold, course, package check) and the
spawn pose a launch file gets."""
