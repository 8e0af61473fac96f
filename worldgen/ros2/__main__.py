"""``python -m worldgen.ros2 CONFIG.json``: the simulator process (:mod:`.node`), pybullet imported first with its
greeting silenced (:mod:`worldgen.sim.quiet`), since ``worldgen sim`` shares its terminal with it."""

from ..sim.quiet import import_pybullet

import_pybullet()

from ..interface.signals import run_main  # noqa: E402  (after pybullet, on purpose)
from .node import main  # noqa: E402

run_main(main)
