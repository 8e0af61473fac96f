"""``python -m worldgen.ros2 CONFIG.json``: the simulator process (:mod:`.node`), started by
:func:`worldgen.interface.signals.simulator_main` (stop signals held, pybullet quiet) before the node's imports."""

from ..interface.signals import simulator_main


def _node_main():
    from .node import main   # after the signals are held and pybullet imported quietly: see simulator_main

    return main


simulator_main(_node_main)
