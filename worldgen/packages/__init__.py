"""catkin and ament packages: scaffolding as catkin_create_pkg and ros2 pkg create write it (:mod:`.catkin`,
:mod:`.ament`), a built world put into a package (:mod:`.world_files`), the class's packages for ROS 1 and ROS 2
(:mod:`.course_ros1`, :mod:`.course_ros2`), and what would break in a package (:mod:`.check`,
:mod:`.check_ament`, :mod:`.build_files`)."""
