"""Reading Python without running it: the values a plain reading of a ROS 2 launch file or an ament_python
``setup.py`` gives (:mod:`.evaluate`: the walk over a module's statements and expressions, :mod:`.values`: what it
reads into and the bounds of one read, :mod:`.stdlib`: the operators and standard library it knows), and what
a setup.py installs (:mod:`.setup_py`)."""
