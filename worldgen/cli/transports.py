"""``--ros noetic|humble|jazzy`` → the transport that runs students' nodes (:mod:`worldgen.bridge.transport`)."""

from __future__ import annotations

from ..bridge.transport import Transport
from ..ros1.transport import ROS1


def transport_for(ros: str, cmd_vel: str | None = None) -> Transport:
    """ROS 1's rospy transport for noetic; the ROS 2 DDS one for humble and jazzy (``cmd_vel``: Jazzy's
    ``stamped`` or ``twist``, as ``launch --cmd-vel`` writes the bridge)."""
    if ros == "noetic":
        return ROS1
    from ..ros2.transport import Ros2   # the ROS 2 extra (cyclonedds) is imported only when asked for

    return Ros2(ros, cmd_vel)
