"""Reading Python without running it: the values a plain reading of a ROS 2 launch file or an ament_python
``setup.py`` gives (:mod:`.evaluate`: the walk over a module's statements and expressions, :mod:`.values`: what it
reads into and the bounds of one read, :mod:`.stdlib`: the operators and standard library it knows), and what
a setup.py installs (:mod:`.setup_py`).

Why not astroid's inference (tried, astroid 4.3.4, on a launch.py of our writer): it reads ``model`` as
``[Uninferable, 'burger']``, and the world path, every ``get_package_share_directory``/``os.path.join`` value and
``os.environ.get(...)`` as Uninferable, since it has neither our substitutions nor a way to say *why* a value is
unknown (each ROS call would need an inference tip, i.e. the rules of this part again); ``list.append`` in a loop
is lost; and it has no bound on work or memory: ``'a' * 10**8`` is folded into a 100 MB string (+107 MB RSS,
0.3 s) where :mod:`.values` refuses past ``MAX_SIZE``. So this part stays ours.
"""
