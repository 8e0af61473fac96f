"""Launch files of both ROS generations: what they are (:mod:`.model`: the nodes, namespaces and what a read
finds), the readers (roslaunch XML: :mod:`.reader`, :mod:`.walk_xml`, :mod:`.params_xml`,
:mod:`.substitution_xml`; ROS 2 Python launch files, read without running them: :mod:`.reader_py`,
:mod:`.scope_py`, :mod:`.values_py`, :mod:`.gazebo_py`), the writers (:mod:`.writer_xml`, :mod:`.writer_py`,
:mod:`.gz_bridge_params`), the spawn pose a launch file gets (:mod:`.spawn`) and the ROS + Gazebo targets
(:mod:`.targets`). The readers never import the writers."""
